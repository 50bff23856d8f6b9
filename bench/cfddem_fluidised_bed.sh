#!/usr/bin/env bash
# Coupled benchmark of issue 6: the pseudo-2D bubbling fluidised bed (cases/cfddem_bubbling_fluidised_bed.yaml,
# 24,750 spheres, 2 x 30 x 90 cells, fluid step 2e-5 s, 3 DEM steps per fluid step), timed over
# DURATION simulated seconds of bubbling after a spin-up to SPINUP s (the inlet ramp ends at 0.3 s;
# the spin-up on 2 threads, not timed, see bench/spinup.sh).
# Prints grainflow's timing table of the timed part: phases, s wall per simulated second.
#   bash bench/cfddem_fluidised_bed.sh [THREADS] [DURATION] [SPINUP]     (defaults 1, 1.0, 0.35)
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
source "$here/bench/spinup.sh"
ensure_spinup "$exe" "$spin_dir" "$spinup" refresh
end=$(python3 -c "print($spinup + $duration)")
echo "timed: t = $spinup ... $end s on $threads thread(s)"
"$exe" run "$case_file" --threads "$threads" --end-time "$end" --restart "$spin_dir/checkpoint.bin" \
  --output "$work/timed_${threads}" --overwrite | sed -n '/^phase/,$p' | grep -v -e '^output written' -e '^view it' -e '^monitors (CSV)'
