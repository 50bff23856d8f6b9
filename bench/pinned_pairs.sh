#!/usr/bin/env bash
# One-thread A/B of two grainflow builds on a host whose speed drifts: runs a benchmark of build A
# pinned to CPU 0 and the same benchmark of build B pinned to CPU 1 at the same time, then the
# other way round, and prints B / A per round as sqrt((B@0 * B@1) / (A@0 * A@1)): both builds
# see the same minutes and each CPU once, so the drift of the host and the difference between
# the CPUs cancel. Session 38 found with it a 3-4 % one-thread slowdown of the settled bed that
# sessions of alternated runs had not resolved (concurrent pairs 0.953-0.986, every round below 1).
#   bash bench/pinned_pairs.sh GRAINFLOW_A GRAINFLOW_B [ROUNDS] [BENCHMARK]
#   (defaults 4, BM_DemSettledBed/; GRAINFLOW_X is a build's grainflow executable, whose
#   bench/grainflow_bench it runs)
# Last line: the geometric mean of B / A over the rounds (below 1: B is faster).
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '2,11p' "$0" >&2
  exit 2
fi
a=$1 b=$2
rounds=${3:-4}
benchmark=${4:-BM_DemSettledBed/}
if [ "$(nproc)" -lt 2 ]; then
  echo "pinned_pairs: needs two CPUs, this machine has $(nproc)" >&2
  exit 1
fi
for exe in "$a" "$b"; do
  [ -x "$exe" ] || { echo "pinned_pairs: $exe is not an executable" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# ns per particle-step of one run of build $1 pinned to CPU $2, written to file $3
ns_per_step() {
  taskset -c "$2" "$1" bench "$benchmark" --threads 1 2>/dev/null | awk -v name="$benchmark" '
    /^Benchmark/ { for (i = 1; i <= NF; ++i) if ($i == "ns_per_particle_step") column = i + 2 }
    index($0, name) == 1 && column { value = $column; gsub(/[^0-9.]/, "", value); print value }' >"$3"
}
for ((r = 1; r <= rounds; ++r)); do
  ns_per_step "$a" 0 "$work/a0" &
  ns_per_step "$b" 1 "$work/b1"
  wait
  ns_per_step "$b" 0 "$work/b0" &
  ns_per_step "$a" 1 "$work/a1"
  wait
  echo "$(cat "$work/a0") $(cat "$work/b1") $(cat "$work/b0") $(cat "$work/a1")"
done | awk '
  NF != 4 { print "pinned_pairs: a run gave no figure" > "/dev/stderr"; failed = 1; next }
  { ratio = sqrt(($2 * $3) / ($1 * $4)); logs += log(ratio); ++n
    printf "round %d: A %s ns on CPU 0, %s on CPU 1; B %s on CPU 0, %s on CPU 1; B / A %.3f\n", n, $1, $4, $3, $2, ratio }
  END { if (n) printf "B / A %.3f (geometric mean of %d rounds)\n", exp(logs / n), n; exit failed }'
