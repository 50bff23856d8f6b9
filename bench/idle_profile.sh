#!/usr/bin/env bash
# Where a 2-thread run of the bubbling bed (issue 6) loses time to waiting: records a short window
# from the spin-up checkpoint of bench/cfddem_fluidised_bed.sh with perf (call graphs from DWARF),
# then prints, for each of the two threads, the share of its samples spent waiting (OpenMP runtime,
# team barriers) and what the other thread ran meanwhile (bench/idle_profile.py). Time one thread
# waits while the other computes is what the team loses on that part: a serial section, an uneven
# split, or a slower core. Needs perf (Debian: linux-perf) and python3.
#   bash bench/idle_profile.sh [END_TIME] [FREQUENCY]     (defaults 0.37, 400 samples/s per thread)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
end=${1:-0.37}
frequency=${2:-400}
exe=${GRAINFLOW:-$here/build/grainflow}
spinup=${SPINUP_DIR:-/tmp/grainflow_bench_fluidised_bed/spinup_0.35}
case_file=$here/cases/cfddem_bubbling_fluidised_bed.yaml
command -v perf >/dev/null || { echo "idle_profile: needs perf (apt-get install linux-perf)" >&2; exit 2; }
source "$here/bench/spinup.sh"
ensure_spinup "$exe" "$spinup" 0.35
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
OMP_PROC_BIND=true OMP_PLACES="{0},{1}" perf record -q -F "$frequency" --call-graph dwarf,8192 -o "$work/perf.data" \
  "$exe" run "$case_file" --threads 2 --end-time "$end" --restart "$spinup/checkpoint.bin" --output "$work/out" \
  --overwrite --quiet
perf script -i "$work/perf.data" -F tid,time,ip,sym 2>/dev/null >"$work/script.txt"
python3 "$here/bench/idle_profile.py" "$work/script.txt"
