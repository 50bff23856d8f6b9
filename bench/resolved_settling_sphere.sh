#!/usr/bin/env bash
# Cost of the resolved CFD-DEM step (src/resolved, docs/resolved.md) on the settling sphere of
# cases/resolved_settling_sphere.yaml (d = 2 mm in a box of 8 d x 8 d x 16 d) at N cells per diameter,
# grid 8N x 8N x 16N (the default N = 16: 128 x 128 x 256 cells), against the fluid step alone on the
# same grid.
#   bash bench/resolved_settling_sphere.sh [N] [STEPS] [THREADS...]   (defaults 16, 20, "1 2")
# For each thread count: the resolved run (the sphere released from rest, STEPS fluid steps, after an
# untimed run of 2 steps) and the fluid alone (no particle, no resolved section, no gravity) twice:
# at rest (fluid_rest: its projections have nothing to do, the cheapest fluid step: the ratio against
# it is an upper bound) and started with a Taylor-Green vortex of 0.05 m/s, about the sphere's
# settling velocity (fluid_moving: more pressure work than the sphere's first steps make). The fluid
# step is the case's 0.25 ms at N = 8, scaled as 8 / N (the same Courant number). Prints per run the
# wall time of the steps (grainflow's phases less I/O: set-up and the final checkpoint excluded) with
# its fluid predictor, pressure solve and other (the resolved sums) parts, the wall time per simulated
# second, ns per cell-step, and the ratios of the resolved step to the fluid step alone (target <= 1.3).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
n=${1:-16}
steps=${2:-20}
shift $(( $# > 2 ? 2 : $# )) || true
threads_list=${*:-"1 2"}
exe=${GRAINFLOW:-$here/build/grainflow}
work=${BENCH_DIR:-/tmp/grainflow_bench_resolved}
[ -x "$exe" ] || { echo "no $exe: build grainflow first" >&2; exit 1; }
mkdir -p "$work"
# derived_case MODE TARGET: MODE resolved, fluid_rest or fluid_moving
derived_case() {
  python3 - "$here/cases/resolved_settling_sphere.yaml" "$n" "$1" "$2" <<'PY'
import sys, yaml
source, n, mode, target = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
case = yaml.safe_load(open(source))
case["fluid"]["cells"] = [8 * n, 8 * n, 16 * n]
case["time"]["dem_step"] = 2.5e-5 * 8.0 / n        # fluid step 0.25 ms x 8 / N (10 DEM steps)
case["output"] = {"interval": 0.0}
case["monitors"] = []
if mode != "resolved":
    del case["insertion"], case["resolved"]
    case["gravity"] = [0.0, 0.0, 0.0]
if mode == "fluid_moving":
    case["fluid"]["initial"] = {"type": "taylor_green", "amplitude": 0.05, "wavelength": 0.016}
yaml.safe_dump(case, open(target, "w"), sort_keys=False)
PY
}
cells=$(( 8 * n * 8 * n * 16 * n ))
dt=$(python3 -c "print(2.5e-4 * 8.0 / $n)")
end=$(python3 -c "print($steps * $dt)")
echo "settling sphere, $n cells per diameter: $((8 * n)) x $((8 * n)) x $((16 * n)) = $cells cells, fluid step $dt s, $steps steps"
declare -A wall
for mode in resolved fluid_rest fluid_moving; do
  derived_case "$mode" "$work/$mode.yaml"
  for t in $threads_list; do
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} "$exe" run "$work/$mode.yaml" --threads "$t" --end-time "$(python3 -c "print(2 * $dt)")" \
      --output "$work/warm_$mode" --overwrite --quiet >/dev/null
    log=$work/${mode}_$t.log
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} "$exe" run "$work/$mode.yaml" --threads "$t" --end-time "$end" \
      --output "$work/${mode}_$t" --overwrite > "$log" 2>&1
    # the steps' wall time: grainflow's phases less I/O (the checkpoint written at the end)
    read -r total fluid pressure other < <(awk '$1 == "total" {t = $2} $1 == "I/O" {io = $2}
      $1 == "fluid" {f = $2} $1 == "pressure" {p = $3} $1 == "other" {o = $2}
      END {print t - io, f, p, o}' "$log")
    wall[$mode,$t]=$total
    python3 -c "
t = $total; steps = $steps; cells = $cells; end = $end
print(f'$mode, $t thread(s): {t:.2f} s wall (fluid predictor $fluid, pressure solve $pressure, other $other), '
      f'{t / end:.1f} s wall per simulated second, {t / (steps * cells) * 1e9:.0f} ns per cell-step')"
  done
done
for t in $threads_list; do
  python3 -c "print(f'ratio resolved / fluid alone, $t thread(s): {${wall[resolved,$t]} / ${wall[fluid_rest,$t]}:.2f} against the fluid at rest, {${wall[resolved,$t]} / ${wall[fluid_moving,$t]}:.2f} against the moving fluid (target <= 1.3)')"
done
