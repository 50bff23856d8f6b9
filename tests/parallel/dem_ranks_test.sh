#!/usr/bin/env bash
# DEM-only runs on several MPI ranks give the same bits as on one (ParticleSet::orderKey and the
# ghosts of src/dem/system_parallel.cpp): the rank-independent checkpoint files of runs on 1, 2 and 4
# ranks are byte-identical, a run checkpointed on 4 ranks continues on 1 and on 3 ranks to the same
# bits as an uninterrupted run, and layouts that do not fit are refused before the run.
#   usage: dem_ranks_test.sh GRAINFLOW MPIEXEC SOURCE_DIR
set -euo pipefail
grainflow=$1 mpiexec=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# More ranks than cores: waiting ranks yield instead of spinning.
export OMPI_MCA_mpi_yield_when_idle=1

run() {  # run RANKS CASE OUTPUT [options]
  local ranks=$1 case=$2 out=$3
  shift 3
  "$mpiexec" --oversubscribe -n "$ranks" "$grainflow" run "$case" --quiet --threads 1 --output "$out" "$@"
}
same() {  # same A B WHAT
  if cmp -s "$1" "$2"; then echo "ok: $3"; else echo "FAIL: $3 ($1 and $2 differ)"; exit 1; fi
}

# 1. A settling bed in a box (polydisperse, Hertz-Mindlin, walls), split along z.
bed=$work/bed.yaml
sed -e 's/count: 2000/count: 600/' "$src/cases/dem_packed_bed_settling.yaml" >"$bed"
for n in 1 2 4; do run $n "$bed" "$work/bed$n" --end-time 0.04; done
same "$work/bed1/checkpoint.bin" "$work/bed2/checkpoint.bin" "settling bed: 2 ranks = 1 rank"
same "$work/bed1/checkpoint.bin" "$work/bed4/checkpoint.bin" "settling bed: 4 ranks = 1 rank"
same "$work/bed1/kinetic_energy.csv" "$work/bed4/kinetic_energy.csv" "settling bed: kinetic energy monitor on 4 ranks"
# Output on 4 ranks: one piece per rank, bound by a .pvtu that the .pvd lists; the pieces hold
# every particle once.
last=$(ls "$work/bed1"/particles_*.vtu | tail -n1)
last=$(basename "$last" .vtu)
points() { sed -n 's/.*<Piece NumberOfPoints="\([0-9]*\)".*/\1/p' "$@" | awk '{s += $1} END {print s}'; }
[[ $(grep -c '<Piece Source=' "$work/bed4/$last.pvtu") == 4 ]] || { echo "FAIL: $last.pvtu does not list 4 pieces"; exit 1; }
grep -q "file=\"$last.pvtu\"" "$work/bed4/particles.pvd" || { echo "FAIL: particles.pvd does not list $last.pvtu"; exit 1; }
[[ $(points "$work/bed4/pieces/${last}"_*.vtu) == $(points "$work/bed1/$last.vtu") ]] ||
  { echo "FAIL: the pieces of $last do not hold every particle once"; exit 1; }
echo "ok: output on 4 ranks: $last.pvtu binds 4 pieces with all $(points "$work/bed1/$last.vtu") particles"

# 2. Restart across rank counts: 4 ranks to half time, then 1 and 3 ranks to the end.
run 4 "$bed" "$work/half4" --end-time 0.02
run 1 "$bed" "$work/rest1" --end-time 0.04 --restart "$work/half4/checkpoint.bin"
run 3 "$bed" "$work/rest3" --end-time 0.04 --restart "$work/half4/checkpoint.bin"
same "$work/bed1/checkpoint.bin" "$work/rest1/checkpoint.bin" "restart: 4 ranks then 1 = uninterrupted"
same "$work/bed1/checkpoint.bin" "$work/rest3/checkpoint.bin" "restart: 4 ranks then 3 = uninterrupted"

# 3. A hopper: outlet, a plug that disappears, cylinder and disk walls, particles crossing ranks.
hopper=$work/hopper.yaml
sed -e 's/count: [0-9]*/count: 800/' "$src/cases/dem_hopper_discharge.yaml" >"$hopper"
for n in 1 4; do run $n "$hopper" "$work/hopper$n" --end-time 0.02; done
same "$work/hopper1/checkpoint.bin" "$work/hopper4/checkpoint.bin" "hopper: 4 ranks = 1 rank"

# 4. A periodic box (x and y periodic, split 2 x 2): ghosts and migration across periodic faces.
cat >"$work/periodic.yaml" <<'CASE'
case: {name: periodic_box}
domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.03], periodic: [1, 1, 0], decomposition: [2, 2, 1]}
time: {end: 0.03, dem_step: 1.0e-5}
materials:
  - {name: glass, density: 2500.0, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
contact: {law: hertz_mindlin, restitution: 0.5, friction: 0.4, rolling: epsd, rolling_friction: 0.1}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
insertion:
  - type: random_packing
    material: glass
    min: [0, 0, 0.002]
    max: [0.02, 0.02, 0.028]
    count: 500
    velocity: [0.3, 0.2, 0]
    size: {distribution: log_normal, median_diameter: 0.0015, sigma: 0.15}
CASE
for n in 1 4; do
  sed -e "s/decomposition: \[2, 2, 1\]/decomposition: $([[ $n == 1 ]] && echo auto || echo '[2, 2, 1]')/" \
    "$work/periodic.yaml" >"$work/periodic$n.yaml"
  run $n "$work/periodic$n.yaml" "$work/periodic$n"
done
same "$work/periodic1/checkpoint.bin" "$work/periodic4/checkpoint.bin" "periodic box 2 x 2: 4 ranks = 1 rank"

# 5. Layouts that do not fit are refused before the run (exit code 1: invalid case file).
expect_refused() {  # expect_refused RANKS LAYOUT TEXT [sed expression]
  sed -e "s/decomposition: \[2, 2, 1\]/decomposition: $2/" -e "${4:-s/^//}" "$work/periodic.yaml" >"$work/bad.yaml"
  set +e
  message=$(run "$1" "$work/bad.yaml" "$work/bad" 2>&1)
  code=$?
  set -e
  if [[ $code -ne 1 || $message != *"$3"* || -e $work/bad/checkpoint.bin ]]; then
    echo "FAIL: layout $2 on $1 ranks: exit $code, message: $message"
    exit 1
  fi
  echo "ok: layout $2 on $1 ranks refused: $(head -n1 <<<"$message")"
}
expect_refused 2 "[3, 1, 1]" "decomposition"
# 5 mm boxes for spheres of up to about 7 mm
expect_refused 4 "[4, 1, 1]" "narrower than the contact reach" "s/count: 500/count: 10/; s/median_diameter: 0.0015/median_diameter: 0.0045/"

# 6. A divergence seen by one rank stops every rank with one message naming that rank (exit code 3),
#    and the last good checkpoint stays.
sed -e '/name: floor/d' -e 's/^walls:$/walls: []/' -e 's/time: {end: 0.03, dem_step: 1.0e-5}/time: {end: 0.1, dem_step: 1.0e-5}\ncheckpoint: {interval_steps: 500}/' \
  "$work/periodic.yaml" >"$work/falls.yaml"
set +e
message=$(run 4 "$work/falls.yaml" "$work/falls" 2>&1)
code=$?
set -e
count=$(grep -c "particle left the domain" <<<"$message" || true)
if [[ $code -ne 3 || $count -ne 1 || $message != *"on rank "* || ! -s $work/falls/checkpoint.bin ]]; then
  echo "FAIL: divergence on 4 ranks: exit $code, $count messages: $message"
  exit 1
fi
echo "ok: divergence on 4 ranks: $(grep "particle left the domain" <<<"$message")"

# 7. Load balancing (parallel.rebalance_interval, parallel.rebalance_threshold): a bed in the lowest
#    third of a column cut in four slabs along z. Recursive coordinate bisection re-cuts the boxes at
#    the first list build (more than 20 % of the particles change rank) and at later checks when
#    the imbalance exceeds 1.1; the checkpoint equals the run on one rank. Then the periodic box,
#    re-cut at every check that finds any imbalance of particles and their pairs, against its run
#    on one rank.
low=$work/low.yaml
sed -e 's/count: 2000/count: 600/' -e 's/max: \[0.03, 0.03, 0.115\]/max: [0.03, 0.03, 0.04]/' \
  -e 's/^domain:$/domain:\n  decomposition: [1, 1, 4]/' "$src/cases/dem_packed_bed_settling.yaml" >"$low"
echo "parallel: {rebalance_interval: 500, rebalance_threshold: 1.1}" >>"$low"
for n in 1 4; do run $n "$low" "$work/low$n" --end-time 0.04 >"$work/low$n.log" 2>&1 || { cat "$work/low$n.log"; exit 1; }; done
same "$work/low1/checkpoint.bin" "$work/low4/checkpoint.bin" "rebalanced settling bed: 4 ranks = 1 rank"
events=$(grep -c "rebalanced at step" "$work/low4.log" || true)
moved=$(grep -o "([0-9.]* %) move" "$work/low4.log" | tr -d '(%' | awk '$1 > m {m = $1} END {print m + 0}')
if [[ $events -lt 1 ]] || ! awk -v m="$moved" 'BEGIN {exit !(m >= 20)}'; then
  echo "FAIL: rebalancing: $events events, at most $moved % of the particles moved"
  cat "$work/low4.log"
  exit 1
fi
echo "ok: rebalancing: $events events, up to $moved % of the particles moved: $(grep -m1 "rebalanced at step" "$work/low4.log")"
if grep -q "rebalanced" "$work/low1.log"; then echo "FAIL: one rank rebalanced"; exit 1; fi
# (the checkpoint holds the case's fingerprint: both runs read the same file)
sed -e '$a parallel: {rebalance_interval: 200, rebalance_threshold: 1.0, rebalance_weight: pairs}' \
  "$work/periodic4.yaml" >"$work/recut.yaml"
for n in 1 4; do run $n "$work/recut.yaml" "$work/recut$n" >"$work/recut$n.log" 2>&1 || { cat "$work/recut$n.log"; exit 1; }; done
same "$work/recut1/checkpoint.bin" "$work/recut4/checkpoint.bin" \
  "periodic box re-cut $(grep -c "rebalanced at step" "$work/recut4.log") times: 4 ranks = 1 rank"

# 8. A rank that owns no particle but holds ghosts: every particle below the cut of two slabs.
sed -e 's/decomposition: \[2, 2, 1\]/decomposition: [1, 1, 2]/' -e 's/max: \[0.01, 0.02, 0.028\]/max: [0.02, 0.02, 0.014]/' \
  -e 's/max: \[0.02, 0.02, 0.028\]/max: [0.02, 0.02, 0.014]/' -e 's/count: 500/count: 150/' \
  -e 's/time: {end: 0.03,/time: {end: 0.01,/' "$work/periodic.yaml" >"$work/empty.yaml"
echo "parallel: {rebalance_interval: 0}" >>"$work/empty.yaml"
for n in 1 2; do run $n "$work/empty.yaml" "$work/empty$n"; done
same "$work/empty1/checkpoint.bin" "$work/empty2/checkpoint.bin" "a rank with ghosts only: 2 ranks = 1 rank"
