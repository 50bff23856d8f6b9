#!/usr/bin/env bash
# A/B of two grainflow binaries on the bubbling bed (issue 6) on a host whose speed drifts:
# alternates short windows of the bed (restart from the spin-up checkpoint of
# bench/cfddem_fluidised_bed.sh) between binary A and binary B, in the order A B B A per round, and
# prints each run's phase times divided by the time of a reference phase that neither binary
# changes (default: fluid). On the shared 2-vCPU VM the host's speed moved by x1.3 between runs
# minutes apart; the ratio of two phases of one run moves far less (session 32: coupling / fluid
# 1.565-1.587 over 6 runs of one binary, while the fluid time itself took 3.44-4.46 s).
#   bash bench/phase_ab.sh BINARY_A BINARY_B [THREADS] [ROUNDS] [END_TIME] [REFERENCE_PHASE]
#   (defaults 1, 3, 0.41, fluid; a window from 0.35 s to END_TIME)
# Last lines: the mean ratio per phase for A and for B and B / A. Both binaries must give the same
# results for the comparison to mean anything (compare the checkpoints' md5, printed per run).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 2 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
a=$1 b=$2
threads=${3:-1}
rounds=${4:-3}
end=${5:-0.41}
reference=${6:-fluid}
spinup=${SPINUP_DIR:-/tmp/grainflow_bench_fluidised_bed/spinup_0.35}
case_file=$here/cases/cfddem_bubbling_fluidised_bed.yaml
for exe in "$a" "$b"; do
  [ -x "$exe" ] || { echo "phase_ab: $exe is not an executable" >&2; exit 2; }
done
source "$here/bench/spinup.sh"
ensure_spinup "$a" "$spinup" 0.35
places="{0}"
[ "$threads" -ge 2 ] && places="{0},{1}"
work=$(mktemp -d)
trap '[ -n "${KEEP_AB:-}" ] && echo "kept $work" || rm -rf "$work"' EXIT
results=$work/results
# one run: label, then "phase seconds" pairs of the timing table and the checkpoint's md5
run_one() {
  local label=$1 exe=$2
  OMP_PROC_BIND=true OMP_PLACES="$places" "$exe" run "$case_file" --threads "$threads" --end-time "$end" \
    --restart "$spinup/checkpoint.bin" --output "$work/out" --overwrite 2>&1 |
    awk -v label="$label" '
      /^phase/ { table = 1; next }
      table && /^total/ { printf "%s total %s", label, $2; table = 0; next }
      table && NF >= 3 { name = $1; for (i = 2; i < NF - 1; ++i) name = name "_" $i; printf "%s %s %s\n", label, name, $(NF - 1) }' \
      >>"$results"
  echo " md5 $(md5sum "$work/out/checkpoint.bin" | cut -c1-8)" >>"$results"
  tail -n 1 "$results" | sed "s/^/$label: /" | sed 's/  */ /g'
}
for ((r = 1; r <= rounds; ++r)); do
  run_one A "$a"
  run_one B "$b"
  run_one B "$b"
  run_one A "$a"
done
awk -v reference="$reference" '
  $2 == "total" { ++runs[$1]; next }
  { t[$1, runs[$1] + 0, $2] = $3; phases[$2] = 1 }
  END {
    printf "%-18s %10s %10s %8s   (phase time / %s time, mean over runs)\n", "phase", "A", "B", "B / A", reference
    for (p in phases) {
      if (p == reference) continue
      for (side = 0; side < 2; ++side) {
        s = side ? "B" : "A"; sum = 0; n = 0
        for (k = 0; k < runs[s]; ++k)
          if (t[s, k, reference] > 0) { sum += t[s, k, p] / t[s, k, reference]; ++n }
        mean[s] = n ? sum / n : 0
      }
      ratio = mean["A"] > 0 ? mean["B"] / mean["A"] : 0
      printf "%-18s %10.4f %10.4f %8.3f\n", p, mean["A"], mean["B"], ratio
    }
  }' "$results"
