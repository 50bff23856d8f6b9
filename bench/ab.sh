#!/usr/bin/env bash
# Compare two builds of grainflow on this machine. The runs of A and B alternate in the order
# A B B A in every round, so a drift of the machine's speed (other jobs, clock changes) falls on
# both builds alike; medians over the rounds then keep single slow runs out of the result.
#
#   bash bench/ab.sh BENCH_A BENCH_B [ROUNDS] [FILTER]
#     BENCH_X  a build's bench/grainflow_bench (or that build's grainflow executable)
#     ROUNDS   rounds of A B B A (default 3)
#     FILTER   Google Benchmark filter, a regular expression (default BM_DemSettledBed/)
#     Prints, per benchmark and per-unit counter (ns_per_particle_step, ns_per_cell_step,
#     bytes_per_particle, ... and real_time), the median of A, the median of B and B / A.
#
#   bash bench/ab.sh --case CASE.yaml GRAINFLOW_A GRAINFLOW_B [ROUNDS] [END_TIME]
#     Runs the case with both grainflow executables up to END_TIME (default: the case's end
#     time), from the checkpoint RESTART=FILE if set (a short window of a long case), and prints
#     the median wall time of each phase of the run's timing table for A and B, and B / A. With
#     REFERENCE=PHASE (e.g. fluid) each phase is first divided by that phase's time in the same
#     run: a phase that neither build changes then absorbs the machine's drift. The last line says
#     whether A and B wrote identical checkpoints (expected for a change that keeps the results).
#
# THREADS=N (default 1) sets the OpenMP threads; set OMP_PROC_BIND / OMP_PLACES to pin them.
# B / A below 1: B is faster. A difference smaller than the rounds' spread is not a result.
set -euo pipefail
usage() { sed -n '2,21p' "$0" >&2; exit 2; }
threads=${THREADS:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

executable() {  # a build's executable of the wanted kind, or a usage error
  local given=$1 kind=$2
  [ -x "$given" ] && [ -f "$given" ] || { echo "ab: $given is not an executable" >&2; exit 2; }
  if [ "$kind" = bench ] && [ "$(basename "$given")" = grainflow ]; then
    given=$(dirname "$given")/bench/grainflow_bench
    [ -x "$given" ] || { echo "ab: no $given (build with -DGRAINFLOW_BUILD_BENCH=ON)" >&2; exit 2; }
  fi
  realpath "$given"
}

# Medians over the runs of A and B and their ratio; input lines "SIDE KEY VALUE".
summarise() {
  python3 -c '
import statistics, sys
values = {}
for line in sys.stdin:
    side, key, value = line.split()
    values.setdefault(key, {"A": [], "B": []})[side].append(float(value))
print("%-60s %12s %12s %8s  (median of %s runs each)" % (sys.argv[1], "A", "B", "B / A", sys.argv[2]))
for key, v in values.items():
    if not v["A"] or not v["B"]:
        continue
    a, b = statistics.median(v["A"]), statistics.median(v["B"])
    ratio = f"{b / a:8.3f}" if a > 0 else "       -"
    print(f"{key:<60} {a:12.5g} {b:12.5g} {ratio}")
' "$1" "$2"
}

if [ "${1:-}" = --case ]; then
  [ $# -ge 4 ] || usage
  case_file=$2
  a=$(executable "$3" grainflow) b=$(executable "$4" grainflow)
  rounds=${5:-3} end=${6:-}
  [ -f "$case_file" ] || { echo "ab: no case file $case_file" >&2; exit 2; }
  args=(run "$case_file" --threads "$threads" --overwrite)
  [ -n "$end" ] && args+=(--end-time "$end")
  [ -n "${RESTART:-}" ] && args+=(--restart "$RESTART")
  run_one() {  # SIDE EXE: one run; its timing table as "SIDE phase seconds" lines
    "$2" "${args[@]}" --output "$work/out_$1" >"$work/log" 2>&1 ||
      { cat "$work/log" >&2; echo "ab: the run of $2 failed" >&2; exit 1; }
    awk -v side="$1" -v reference="${REFERENCE:-}" '
      /^phase/ { table = 1; next }
      table && NF == 0 { table = 0 }
      table && $1 == "total" { t["total"] = $2; order[++n] = "total"; table = 0 }
      table && NF >= 3 { name = $1; for (i = 2; i < NF - 1; ++i) name = name "_" $i; t[name] = $(NF - 1); order[++n] = name }
      END {
        if (!("total" in t)) { print "ab: no timing table in the run output" > "/dev/stderr"; exit 1 }
        if (reference != "" && !(t[reference] > 0)) { print "ab: no time for phase " reference > "/dev/stderr"; exit 1 }
        for (k = 1; k <= n; ++k) { p = order[k]; print side, p, (reference == "" ? t[p] : t[p] / t[reference]) }
      }' "$work/log" >>"$work/results"
    cp "$work/out_$1/checkpoint.bin" "$work/checkpoint_$1"
  }
  for ((r = 1; r <= rounds; ++r)); do
    run_one A "$a"; run_one B "$b"; run_one B "$b"; run_one A "$a"
    echo "round $r of $rounds done" >&2
  done
  label="phase wall time [s]"
  [ -n "${REFERENCE:-}" ] && label="phase time / $REFERENCE time"
  summarise "$label, $threads thread(s)" $((2 * rounds)) <"$work/results"
  if cmp -s "$work/checkpoint_A" "$work/checkpoint_B"; then
    echo "checkpoints: identical (A and B computed the same results)"
  else
    echo "checkpoints: differ (A and B computed different results)"
  fi
  exit 0
fi

[ $# -ge 2 ] || usage
a=$(executable "$1" bench) b=$(executable "$2" bench)
rounds=${3:-3} filter=${4:-BM_DemSettledBed/}
run_one() {  # SIDE EXE: one run of the filter; "SIDE benchmark:counter value" lines
  OMP_NUM_THREADS=$threads "$2" --benchmark_filter="$filter" --benchmark_out="$work/json" \
    --benchmark_out_format=json >"$work/log" 2>&1 ||
    { cat "$work/log" >&2; echo "ab: $2 failed" >&2; exit 1; }
  python3 -c '
import json, sys
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    if b.get("run_type") == "aggregate":
        continue
    name = b["name"].replace(" ", "_")
    unit = b.get("time_unit", "ns")
    print(sys.argv[2], f"{name}:real_time[{unit}]", b["real_time"])
    for key, value in b.items():
        if "per_" in key and key != "per_family_instance_index" and isinstance(value, (int, float)):
            print(sys.argv[2], f"{name}:{key}", value)
' "$work/json" "$1" >>"$work/results"
}
for ((r = 1; r <= rounds; ++r)); do
  run_one A "$a"; run_one B "$b"; run_one B "$b"; run_one A "$a"
  echo "round $r of $rounds done" >&2
done
[ -s "$work/results" ] || { echo "ab: no benchmark matches $filter" >&2; exit 1; }
summarise "benchmark:counter, $threads thread(s)" $((2 * rounds)) <"$work/results"
