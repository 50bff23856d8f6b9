#!/usr/bin/env bash
# Coupled CFD-DEM cases on several MPI ranks through `grainflow run`: the particles and the grid are
# split along the same cuts; void-fraction and exchange deposits that fall into ghost cells are
# summed into the neighbour's cells, the samples read the neighbour's cells, and the sums are over
# all ranks. With hypre and tight solver tolerances on every rank count (the order of the sums is
# all that differs), the monitors of 2 and 4 ranks agree with 1 rank to 1e-10 relative; the
# particle volume equals the deposited volume and the momentum exchanged balances to round-off on
# any rank count; a run checkpointed on 4 ranks continues on 1 and on 3; a periodic axis split
# between ranks works; the output binds one piece per rank; rebalancing moves the cuts and the
# state without changing the results; the polydisperse drag laws agree too.
#   usage: coupled_ranks_test.sh GRAINFLOW MPIEXEC SOURCE_DIR
set -euo pipefail
grainflow=$1 mpiexec=$2 src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/rank_runs.sh"
# case_for SOURCE DESTINATION END LAYOUT: the case with hypre (or the pressure solver named by
# $SOLVER) and momentum tolerances of 1e-12,
# the given end time, monitors 5 times over the run, and domain.decomposition LAYOUT ("" = auto).
# (close, rank_runs.sh: the momentum-balance errors, round-off themselves, are left to `balanced`)
case_for() {
  python3 - "$@" <<'PY'
import os, sys, yaml
src, dst, end, layout = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
c = yaml.safe_load(open(src))
c["time"]["end"] = end
f = c["fluid"]
f["pressure"] = dict(f.get("pressure") or {}, solver=os.environ.get("SOLVER", "hypre"), tolerance=1e-12)
f["momentum_tolerance"] = 1e-12
if layout:
    c["domain"]["decomposition"] = [int(v) for v in layout.split(",")]
for m in c.get("monitors") or []:
    m["interval"] = end / 5
c.setdefault("output", {})["interval"] = end / 2
yaml.safe_dump(c, open(dst, "w"), sort_keys=False)
PY
}
# balanced DIR WHAT: coupling_balance.csv: relative momentum error below 1e-12 and the deposited
# volume equal to the particle volume to 1e-12 relative at every sample (no volume lost or counted
# twice at the cuts)
balanced() {
  python3 - "$1/coupling_balance.csv" "$2" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
what = sys.argv[2]
momentum = max(float(r["relative_momentum_error [-]"]) for r in rows)
volume = max(abs(float(r["deposited_volume [m^3]"]) - float(r["particle_volume [m^3]"])) /
             float(r["particle_volume [m^3]"]) for r in rows)
if momentum > 1e-12 or volume > 1e-12:
    sys.exit(f"FAIL: {what}: momentum error {momentum:.2e}, deposited vs particle volume {volume:.2e} (limit 1e-12)")
print(f"ok: {what}: momentum error {momentum:.2e}, deposited vs particle volume {volume:.2e}")
PY
}

# 1. Bubbling bed, 50 coupling steps (0.001 s): 2 ranks (auto layout: cut across the height) and
#    4 ranks (2 x 2 across the width and the height, so that cuts meet at edges) against 1 rank.
bed=$src/cases/cfddem_bubbling_fluidised_bed.yaml
case_for "$bed" "$work/bed.yaml" 0.001 ""
case_for "$bed" "$work/bed4.yaml" 0.001 "1,2,2"
case_for "$bed" "$work/bed3.yaml" 0.001 "1,3,1"
run 1 "$work/bed.yaml" "$work/bed1"
run 2 "$work/bed.yaml" "$work/bed2"
run 4 "$work/bed4.yaml" "$work/bed4"
close "$work/bed1" "$work/bed2" 1e-10 "bubbling bed: 2 ranks against 1 rank" momentum_error
close "$work/bed1" "$work/bed4" 1e-10 "bubbling bed: 4 ranks (1 x 2 x 2) against 1 rank" momentum_error
for n in 1 2 4; do balanced "$work/bed$n" "bubbling bed on $n rank(s): exchange balance"; done

# 2. Output: one particle piece and one fluid piece per rank.
last=$(ls "$work/bed4"/particles_*.pvtu | tail -n1)
[[ $(grep -c '<Piece Source=' "$last") == 4 ]] || { echo "FAIL: $last does not list 4 pieces"; exit 1; }
last=$(ls "$work/bed4"/fluid_*.pvti | tail -n1)
[[ $(grep -c '<Piece Extent=' "$last") == 4 ]] || { echo "FAIL: $last does not list 4 pieces"; exit 1; }
echo "ok: coupled output on 4 ranks: 4 particle and 4 fluid pieces per output"

# 3. Restart across rank counts: 4 ranks to half time, then 1 rank and 3 ranks (1 x 3 x 1), against
#    1 rank throughout.
run 4 "$work/bed4.yaml" "$work/half" --end-time 0.0005
run 1 "$work/bed.yaml" "$work/on1" --restart "$work/half/checkpoint.bin"
run 3 "$work/bed3.yaml" "$work/on3" --restart "$work/half/checkpoint.bin"
close "$work/bed1" "$work/on1" 1e-10 "bubbling bed: 4 ranks to t/2, then 1 rank, against 1 rank throughout" momentum_error
close "$work/bed1" "$work/on3" 1e-10 "bubbling bed: 4 ranks to t/2, then 3 ranks, against 1 rank throughout" momentum_error

# 4. A periodic axis split between two ranks: the batch sedimentation column (periodic in x and y)
#    on a 6 x 6 x 16 grid cut across x, so that deposits and samples wrap through the neighbour.
python3 - "$src/cases/cfddem_batch_sedimentation.yaml" "$work/column_src.yaml" <<'PY'
import sys, yaml
c = yaml.safe_load(open(sys.argv[1]))
c["fluid"]["cells"] = [6, 6, 16]
yaml.safe_dump(c, open(sys.argv[2], "w"), sort_keys=False)
PY
case_for "$work/column_src.yaml" "$work/column.yaml" 0.002 ""
case_for "$work/column_src.yaml" "$work/column2.yaml" 0.002 "2,1,1"
run 1 "$work/column.yaml" "$work/column1"
run 2 "$work/column2.yaml" "$work/column2"
close "$work/column1" "$work/column2" 1e-10 "sedimentation column: periodic x split between 2 ranks against 1 rank" momentum_error

# 5. Load balancing: a suspension in the lower quarter of a column split across its height on 2
#    ranks puts the particles' work on one rank; rebalancing (threshold 1.1, checked every 40 DEM
#    steps, a cell worth 2 particles) moves the cut down, taking at least 20 % of the cells to the other rank, and the
#    monitors stay within 1e-10 of 1 rank's.
python3 - "$src/cases/cfddem_batch_sedimentation.yaml" "$work/lopsided_src.yaml" <<'PY'
import sys, yaml
c = yaml.safe_load(open(sys.argv[1]))
c["time"].update(dem_step=1.0e-5, coupling_interval=1)
c["fluid"]["cells"] = [3, 3, 24]
c["insertion"][0].update(max=[0.012, 0.012, 0.012], count=6000, size={"distribution": "constant", "diameter": 0.0005})
c["coupling"]["smoothing_length"] = 0.0015
c["parallel"] = {"rebalance_threshold": 1.1, "rebalance_interval": 40, "rebalance_cell_cost": 2.0}
yaml.safe_dump(c, open(sys.argv[2], "w"), sort_keys=False)
PY
case_for "$work/lopsided_src.yaml" "$work/lopsided.yaml" 0.0016 ""
case_for "$work/lopsided_src.yaml" "$work/lopsided2.yaml" 0.0016 "1,1,2"
run 1 "$work/lopsided.yaml" "$work/lopsided1"
"$mpiexec" --oversubscribe -n 2 "$grainflow" run "$work/lopsided2.yaml" --threads 1 --output "$work/lopsided2" \
  >"$work/lopsided2.log" 2>&1 || { cat "$work/lopsided2.log"; exit 1; }
# (a cell weighs 2 particles, parallel.rebalance_cell_cost, so that the cuts do not depend on the
# machine's speeds: 9 cells and 1,000 particles per plane in the suspension, 9 cells above it put the
# cut 3 cells up; the test reads where the last re-cut left it, 12 cells up at the start)
cut=$(sed -n 's/.*cell cuts z: 0 \([0-9]*\) 24).*/\1/p' "$work/lopsided2.log" | tail -n1)
[[ -n $cut ]] || { echo "FAIL: no rebalancing on 2 ranks"; cat "$work/lopsided2.log"; exit 1; }
moved=$(( (12 - cut) * 100 / 24 ))
(( moved >= 20 )) ||
  { echo "FAIL: rebalancing moved the cut to $cut ($moved % of the cells; at least 20 expected)"; grep parallel "$work/lopsided2.log"; exit 1; }
echo "ok: rebalancing on 2 ranks moved the cut from 12 to $cut cells up ($moved % of the cells)"
close "$work/lopsided1" "$work/lopsided2" 1e-10 "lopsided column: 2 ranks with rebalancing against 1 rank" momentum_error

# 6. Polydisperse drag laws: their per-cell size statistics (class volume fractions, Sauter mean,
#    mixture velocity) are completed across the cuts: a three-size suspension with
#    beetstra_polydisperse, and with yin_sundaresan plus the fluid-mediated friction between the
#    classes, on 4 ranks (2 x 1 x 2, across the periodic x and the height) against 1 rank.
for law in beetstra_polydisperse yin_sundaresan; do
  python3 - "$work/column_src.yaml" "$work/${law}_src.yaml" "$law" <<'PY'
import sys, yaml
c = yaml.safe_load(open(sys.argv[1]))  # (the column of section 4)
c["insertion"][0].update(count=1500, size={"distribution": "discrete", "diameters": [0.0008, 0.001, 0.0012],
                                           "mass_fractions": [0.3, 0.4, 0.3]})
c["coupling"]["drag_law"] = sys.argv[3]
if sys.argv[3] == "yin_sundaresan":
    c["coupling"]["fluid_mediated_friction"] = True
yaml.safe_dump(c, open(sys.argv[2], "w"), sort_keys=False)
PY
  case_for "$work/${law}_src.yaml" "$work/$law.yaml" 0.002 ""
  case_for "$work/${law}_src.yaml" "$work/${law}4.yaml" 0.002 "2,1,2"
  run 1 "$work/$law.yaml" "$work/${law}1"
  run 4 "$work/${law}4.yaml" "$work/${law}4"
  close "$work/${law}1" "$work/${law}4" 1e-10 "$law, three sizes: 4 ranks against 1 rank" momentum_error
done

# 7. The multigrid on several ranks (fluid.pressure.solver: multigrid, a grid under
#    fluid.pressure.gather_cells): rank 0 solves the whole grid's pressure system, gathered from the
#    boxes. The bubbling bed on 2 and 4 ranks and the periodic column split across x agree with 1
#    rank's multigrid to the tolerance of item 7 of the parallel design (the system is the one rank's,
#    cut faces and the periodic wrap included).
SOLVER=multigrid case_for "$bed" "$work/mg.yaml" 0.001 ""
SOLVER=multigrid case_for "$bed" "$work/mg4.yaml" 0.001 "1,2,2"
SOLVER=multigrid case_for "$work/column_src.yaml" "$work/mgcolumn.yaml" 0.002 ""
SOLVER=multigrid case_for "$work/column_src.yaml" "$work/mgcolumn2.yaml" 0.002 "2,1,1"
run 1 "$work/mg.yaml" "$work/mg1"
# (run.progress_interval longer than the run: few progress lines in the log)
sed 's/^run:/run:\n  progress_interval: 1.0e+6/' "$work/mg.yaml" > "$work/mgq.yaml"
grep -q "progress_interval: 1.0e+6" "$work/mgq.yaml" || { echo "FAIL: could not set run.progress_interval"; exit 1; }
"$mpiexec" --oversubscribe -n 2 "$grainflow" run "$work/mgq.yaml" --threads 1 --output "$work/mg2" >"$work/mg2.log" 2>&1 ||
  { cat "$work/mg2.log"; exit 1; }
run 4 "$work/mg4.yaml" "$work/mg4"
run 1 "$work/mgcolumn.yaml" "$work/mgcolumn1"
run 2 "$work/mgcolumn2.yaml" "$work/mgcolumn2"
close "$work/mg1" "$work/mg2" 1e-10 "bubbling bed, gathered multigrid: 2 ranks against 1 rank" momentum_error
close "$work/mg1" "$work/mg4" 1e-10 "bubbling bed, gathered multigrid: 4 ranks (1 x 2 x 2) against 1 rank" momentum_error
close "$work/mgcolumn1" "$work/mgcolumn2" 1e-10 "sedimentation column, gathered multigrid: periodic x split between 2 ranks against 1 rank" momentum_error
balanced "$work/mg4" "bubbling bed, gathered multigrid on 4 ranks: exchange balance"
if grep -q hypre "$work/mg2.log"; then echo "FAIL: a 5,400-cell grid on 2 ranks went through hypre"; cat "$work/mg2.log"; exit 1; fi
# Above gather_cells the pressure goes through hypre, with a notice.
sed 's/^  pressure:/  pressure:\n    gather_cells: 100/' "$work/mg.yaml" > "$work/mgbig.yaml"
grep -q "gather_cells: 100" "$work/mgbig.yaml" || { echo "FAIL: could not set gather_cells"; exit 1; }
"$mpiexec" --oversubscribe -n 2 "$grainflow" run "$work/mgbig.yaml" --threads 1 --end-time 0.0001 --output "$work/mgbig" \
  >"$work/mgbig.log" 2>&1 || { cat "$work/mgbig.log"; exit 1; }
grep -q "goes through hypre" "$work/mgbig.log" || { echo "FAIL: no hypre notice above gather_cells"; cat "$work/mgbig.log"; exit 1; }
echo "ok: above fluid.pressure.gather_cells the pressure goes through hypre"
