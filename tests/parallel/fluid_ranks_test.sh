#!/usr/bin/env bash
# Fluid-only cases on several MPI ranks through `grainflow run`: the decomposed solver (hypre
# pressure, ghost exchange across the cuts) against one rank (the multigrid pressure), monitors
# within the pressure solvers' tolerance; the output binds one .vti piece per rank in a .pvti; a run
# checkpointed on 2 ranks continues on 1 to the same monitors as an uninterrupted run; a layout
# too fine for the grid is refused with a clear message.
#   usage: fluid_ranks_test.sh GRAINFLOW MPIEXEC SOURCE_DIR
set -euo pipefail
grainflow=$1 mpiexec=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/rank_runs.sh"
# (close: the divergence monitors hold the pressure solvers' residue, not the solution, and
# closed and periodic domains fix the pressure only up to a constant)
skip='divergence|^p |^pressure'

# 1. Lid-driven cavity (2D, 128 x 128) and the periodic channel at a prescribed flow rate, with the
#    hypre pressure and momentum tolerances of 1e-12 on every rank count, within 1e-10 between rank
#    counts (the reductions' order is all that differs), and against the
#    multigrid pressure of one rank within the pressure solvers' tolerance (1e-8 of the residual).
for name in fluid_cavity fluid_channel; do
  sed -e 's/pressure: {tolerance: [0-9.e-]*/pressure: {solver: hypre, tolerance: 1.0e-12/' \
    -e 's/^fluid:$/fluid:\n  momentum_tolerance: 1.0e-12/' "$src/cases/$name.yaml" >"$work/$name.yaml"
  if ! grep -q "solver: hypre" "$work/$name.yaml"; then  # (no pressure section: one under fluid)
    sed -i -e 's/^fluid:$/fluid:\n  pressure: {solver: hypre, tolerance: 1.0e-12}/' "$work/$name.yaml"
  fi
  run 1 "$src/cases/$name.yaml" "$work/${name}_multigrid" --end-time 1.0
  for n in 1 2 4; do run $n "$work/$name.yaml" "$work/${name}$n" --end-time 1.0; done
  for n in 2 4; do close "$work/${name}1" "$work/${name}$n" 1e-10 "$name: $n ranks against 1 rank (hypre)" "$skip"; done
  close "$work/${name}_multigrid" "$work/${name}2" 1e-5 "$name: 2 ranks (hypre) against 1 rank (multigrid)" "$skip"
done

# 2. Output: one piece per rank in the .pvti of each output, listed by fluid.pvd.
last=$(ls "$work/fluid_cavity4"/fluid_*.pvti | tail -n1)
[[ $(grep -c '<Piece Extent=' "$last") == 4 ]] || { echo "FAIL: $last does not list 4 pieces"; exit 1; }
grep -q "$(basename "$last")" "$work/fluid_cavity4/fluid.pvd" || { echo "FAIL: fluid.pvd does not list $last"; exit 1; }
echo "ok: fluid output on 4 ranks: $(basename "$last") binds 4 pieces"

# 3. Restart across rank counts: 2 ranks to half time, then 1 rank, against 1 rank throughout
#    (hypre on both).
run 2 "$work/fluid_cavity.yaml" "$work/half" --end-time 0.5
run 1 "$work/fluid_cavity.yaml" "$work/continued" --end-time 1.0 --restart "$work/half/checkpoint.bin"
close "$work/fluid_cavity1" "$work/continued" 1e-10 "cavity: 2 ranks to t/2, then 1 rank, against 1 rank throughout" "$skip"

# 4. A layout that leaves a rank fewer cells along a split axis than the ghost layers need is
#    refused before the run (exit 1, invalid case), naming the key and the most ranks that fit.
set +e
sed 's/^  max: \[0.012, 0.012, 0.048\]$/  max: [0.012, 0.012, 0.048]\n  decomposition: [2, 1, 1]/' \
  "$src/cases/cfddem_batch_sedimentation.yaml" >"$work/too_fine.yaml"
message=$(run 2 "$work/too_fine.yaml" "$work/refused" 2>&1)
code=$?
set -e
[[ $code -eq 1 && $message == *"domain.decomposition"* && $message == *"at least 3 cells per rank"* ]] ||
  { echo "FAIL: 2 ranks along 4 cells: exit $code: $message"; exit 1; }
echo "ok: a layout too fine for the grid refused: $(head -n1 <<<"$message")"
