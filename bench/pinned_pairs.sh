#!/usr/bin/env bash
# One-thread A/B of two grainflow builds on a host whose speed drifts: runs a benchmark of build A
# pinned to CPU 0 and the same benchmark of build B pinned to CPU 1 at the same time, then the
# other way round, and prints B / A per round as sqrt((B@0 * B@1) / (A@0 * A@1)): both builds
# see the same minutes and each CPU once, so the drift of the host and the difference between
# the CPUs cancel. Session 38 measured with it the ~2.5 % one-thread gain of the team-of-one
# contact sweep, which alternated runs had not resolved (12 rounds 0.953-1.039, 11 below 1).
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
source "$(dirname "$0")/ns_per_step.sh"
for ((r = 1; r <= rounds; ++r)); do
  ns_per_step "$a" "$benchmark" 0 >"$work/a0" &
  ns_per_step "$b" "$benchmark" 1 >"$work/b1"
  wait
  ns_per_step "$b" "$benchmark" 0 >"$work/b0" &
  ns_per_step "$a" "$benchmark" 1 >"$work/a1"
  wait
  echo "$(cat "$work/a0") $(cat "$work/b1") $(cat "$work/b0") $(cat "$work/a1")"
done | awk '
  NF != 4 { print "pinned_pairs: a run gave no figure" > "/dev/stderr"; failed = 1; next }
  { ratio = sqrt(($2 * $3) / ($1 * $4)); logs += log(ratio); ++n
    printf "round %d: A %s ns on CPU 0, %s on CPU 1; B %s on CPU 0, %s on CPU 1; B / A %.3f\n", n, $1, $4, $3, $2, ratio }
  END { if (n) printf "B / A %.3f (geometric mean of %d rounds)\n", exp(logs / n), n; exit failed }'
