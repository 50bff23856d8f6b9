#!/usr/bin/env bash
# The bubbling fluidised bed (cases/cfddem_bubbling_fluidised_bed.yaml) on 1 rank and on N MPI
# ranks (default 4, oversubscribed where the machine has fewer cores), each with its default
# pressure solver (the multigrid; on several ranks it solves the gathered system on rank 0, for
# this 5,400-cell grid), to END seconds (default 0.2): the time-mean
# bed pressure drop over the run of each, their relative difference (target: within 1 %), and the
# wall time of each. One thread per rank.
#   usage: bash bench/mpi_coupled_bed.sh [GRAINFLOW] [RANKS] [END]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
grainflow=${1:-$here/build/grainflow}
ranks=${2:-4}
end=${3:-0.2}
work=$(mktemp -d /tmp/grainflow_coupled_bed.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMPI_MCA_mpi_yield_when_idle=1
case=$here/cases/cfddem_bubbling_fluidised_bed.yaml
start=$(date +%s.%N)
"$grainflow" run "$case" --quiet --threads 1 --end-time "$end" --output "$work/one" >/dev/null
middle=$(date +%s.%N)
mpirun --oversubscribe -n "$ranks" "$grainflow" run "$case" --quiet --threads 1 --end-time "$end" \
  --output "$work/many" >/dev/null 2>&1
stop=$(date +%s.%N)
python3 - "$work/one/pressure_drop.csv" "$work/many/pressure_drop.csv" "$ranks" "$end" \
  "$(python3 -c "print($middle - $start)")" "$(python3 -c "print($stop - $middle)")" <<'PY'
import csv, sys
def mean(path):
    rows = list(csv.DictReader(open(path)))
    values = [float(r["pressure_drop [Pa]"]) for r in rows[1:]]
    return sum(values) / len(values), len(values)
one, n1 = mean(sys.argv[1])
many, n2 = mean(sys.argv[2])
ranks, end, t1, t2 = sys.argv[3], float(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
print(f"bubbling bed to {end:g} s, time-mean pressure drop over {n1} samples:")
print(f"  1 rank: {one:.2f} Pa, wall {t1:.0f} s")
print(f"  {ranks} ranks: {many:.2f} Pa, wall {t2:.0f} s")
print(f"  relative difference {abs(many - one) / abs(one) * 100:.3f} % (target: within 1 %)")
PY
