#!/usr/bin/env bash
# Load balancing of a coupled case: the spouted bed (cases/cfddem_spouted_bed.yaml, 175,800 spheres)
# on RANKS MPI ranks (default 2, one thread each) from rest to END seconds (default 0.01), once
# with the boxes kept (parallel.rebalance_interval: 0) and once rebalanced (threshold 1.1, checked
# every 400 DEM steps). Prints for each: the wall time, the particles per rank at the end (from the
# output pieces) with their max/mean, and the rebalancing events.
#   usage: bash bench/mpi_spouted_rebalance.sh [GRAINFLOW] [RANKS] [END]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
grainflow=${1:-$here/build/grainflow}
ranks=${2:-2}
end=${3:-0.01}
work=$(mktemp -d /tmp/grainflow_spouted_rebalance.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMPI_MCA_mpi_yield_when_idle=1
for mode in kept rebalanced; do
  python3 - "$here/cases/cfddem_spouted_bed.yaml" "$work/$mode.yaml" "$mode" "$end" <<'PY'
import sys, yaml
c = yaml.safe_load(open(sys.argv[1]))
c["parallel"] = {"rebalance_interval": 0} if sys.argv[3] == "kept" else {"rebalance_interval": 400,
                                                                       "rebalance_threshold": 1.1}
c["output"] = {"interval": float(sys.argv[4]), "fluid": False}
c["monitors"] = []
yaml.safe_dump(c, open(sys.argv[2], "w"), sort_keys=False)
PY
  start=$(date +%s.%N)
  mpirun --oversubscribe -n "$ranks" "$grainflow" run "$work/$mode.yaml" --threads 1 --end-time "$end" \
    --output "$work/$mode" >"$work/$mode.log" 2>&1 || { cat "$work/$mode.log"; exit 1; }
  stop=$(date +%s.%N)
  python3 - "$work/$mode" "$mode" "$(python3 -c "print($stop - $start)")" "$work/$mode.log" <<'PY'
import glob, os, re, sys
out, mode, wall, log = sys.argv[1], sys.argv[2], float(sys.argv[3]), open(sys.argv[4]).read()
last = sorted(glob.glob(os.path.join(out, "particles_*.pvtu")))[-1]
stem = os.path.basename(last)[:-5]
counts = [int(re.search(r'NumberOfPoints="(\d+)"', open(p).read()).group(1))
          for p in sorted(glob.glob(os.path.join(out, "pieces", stem + "_*.vtu")))]
mean = sum(counts) / len(counts)
print(f"{mode}: wall {wall:.0f} s; particles per rank at the end {counts}, max/mean {max(counts) / mean:.3f}")
for line in re.findall(r"parallel: imbalance.*", log):
    print("  " + line)
PY
done
