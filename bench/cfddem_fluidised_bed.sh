#!/usr/bin/env bash
# The coupled benchmark: the pseudo-2D bubbling fluidised bed (cases/cfddem_bubbling_fluidised_bed.yaml,
# 24,750 spheres, 2 x 30 x 90 cells, fluid step 2e-5 s, 3 DEM steps per fluid step), timed over
# DURATION simulated seconds of bubbling after a spin-up to SPINUP s (the inlet ramp ends at 0.3 s).
# The spin-up is not timed; it runs once (again when the grainflow executable is newer than its
# checkpoint) and always on 2 threads: a run's bits depend on its thread count, so a fixed count
# gives the timed runs the same starting state whatever THREADS they use.
# Prints grainflow's timing table of the timed part: phases, s wall per simulated second.
#   bash bench/cfddem_fluidised_bed.sh [THREADS] [DURATION] [SPINUP]     (defaults 1, 1.0, 0.35)
# GRAINFLOW=EXE times another build; BENCH_DIR (default /tmp/grainflow_bench_fluidised_bed) holds
# the spin-up checkpoint and the timed output.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
threads=${1:-1}
duration=${2:-1.0}
spinup=${3:-0.35}
exe=${GRAINFLOW:-$here/build/grainflow}
work=${BENCH_DIR:-/tmp/grainflow_bench_fluidised_bed}
# OpenMP wait policy: the default (threads spin briefly between parallel regions) on an idle machine;
# set OMP_WAIT_POLICY=passive yourself on a machine busy with other work.
case_file=$here/cases/cfddem_bubbling_fluidised_bed.yaml
spin_dir=$work/spinup_${spinup}
if ! [ -f "$spin_dir/checkpoint.bin" ] || [ "$spin_dir/checkpoint.bin" -ot "$exe" ]; then
  echo "spin-up to t = $spinup s on 2 threads (not timed) ..."
  "$exe" run "$case_file" --threads 2 --end-time "$spinup" --output "$spin_dir" --overwrite --quiet
fi
end=$(python3 -c "print($spinup + $duration)")
echo "timed: t = $spinup ... $end s on $threads thread(s)"
"$exe" run "$case_file" --threads "$threads" --end-time "$end" --restart "$spin_dir/checkpoint.bin" \
  --output "$work/timed_${threads}" --overwrite | sed -n '/^phase/,$p' | grep -v -e '^output written' -e '^view it' -e '^monitors (CSV)'
