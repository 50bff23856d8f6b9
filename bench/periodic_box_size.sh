#!/usr/bin/env bash
# Cost of the periodic sedimentation box (seed 003 sec. 4) as the box grows, and the largest box
# that finishes the validation window in under LIMIT seconds (default 30 minutes).
#   bash bench/periodic_box_size.sh [THREADS] [FLUID_STEPS] [SCALES] [CASE] [LIMIT]
#   (defaults 2, 4, "1 2 3 4", validation/cfddem_periodic_box/case.yaml, 1800)
# Each scale s runs CASE with the box side, the insertion region and the cell count times s (the same
# grid spacing, the same <phi_p>: s^3 times the particles and the cells) for FLUID_STEPS fluid steps
# (FLUID_STEPS x time.coupling_interval DEM steps; no output files), and prints particles, cells,
# the wall time per simulated second and the ns per particle-step of the run's timing table (set-up
# and I/O excluded), and the wall time the validation window (CASE's time.end) would take.
# The largest box within LIMIT: the largest measured one, and the one interpolated as a power law of
# the particle count N between the two measured sizes around the limit: particles, side, cells.
# Then the bubbling bed (bench/cfddem_fluidised_bed.sh, THREADS threads, BUBBLING_WINDOW simulated
# seconds after its cached spin-up, default 0.05) for its ns per particle-step; BUBBLING=0 skips it.
# A short window measures the steady cost per step only: the periodic box's cost does not change
# with time (homogeneous start, rare contacts at phi = 1e-3), so it extrapolates to the window.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
threads=${1:-2}
fluid_steps=${2:-4}
scales=${3:-"1 2 3 4"}
case_file=${4:-$here/validation/cfddem_periodic_box/case.yaml}
limit=${5:-1800}
exe=${GRAINFLOW:-$here/build/grainflow}
work=${BENCH_DIR:-/tmp/grainflow_bench_periodic_box}
if [ ! -x "$exe" ]; then
  echo "no $exe: build grainflow first (bash scripts/build.sh)" >&2
  exit 1
fi
mkdir -p "$work"
# the case scaled by s: box, insertion region, cells, particle count (or volume_fraction kept)
scaled_case() {  # scaled_case SCALE TARGET
  python3 - "$case_file" "$@" <<'PY'
import sys, yaml
source, s, target = sys.argv[1], float(sys.argv[2]), sys.argv[3]
case = yaml.safe_load(open(source))
lo, hi = case["domain"]["min"], case["domain"]["max"]
case["domain"]["max"] = [a + s * (b - a) for a, b in zip(lo, hi)]
for ins in case["insertion"]:
    ins["max"] = [a + s * (b - a) for a, b in zip(ins["min"], ins["max"])]
    if "count" in ins: ins["count"] = int(round(ins["count"] * s ** 3))
case["fluid"]["cells"] = [int(round(n * s)) for n in case["fluid"]["cells"]]
case["output"] = {"interval": 1.0e9, "fluid": False}
case["monitors"] = []
case["case"]["name"] = f"{case['case']['name']}_x{s:g}"
yaml.safe_dump(case, open(target, "w"), sort_keys=False)
PY
}
window=$(python3 -c "import yaml,sys; print(yaml.safe_load(open(sys.argv[1]))['time']['end'])" "$case_file")
fluid_step=$(python3 -c "import yaml,sys; t=yaml.safe_load(open(sys.argv[1]))['time']; print(t['dem_step']*t.get('coupling_interval',1))" "$case_file")
end=$(python3 -c "print(f\"{$fluid_steps * $fluid_step:.6g}\")")
echo "periodic box: $case_file, window $window s, $fluid_steps fluid steps ($end s) per size, $threads thread(s)"
printf '%-6s %10s %10s %14s %12s %14s\n' scale particles cells "s wall/s sim" "ns/p-step" "window [min]"
results=$work/results.txt
: > "$results"
for s in $scales; do
  scaled_case "$s" "$work/box_$s.yaml"
  log=$work/box_$s.log
  OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} "$exe" run "$work/box_$s.yaml" --threads "$threads" --end-time "$end" \
    --output "$work/out_$s" --overwrite > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
  python3 - "$log" "$work/box_$s.yaml" "$s" "$end" "$window" >> "$results" <<'PY'
import re, sys, yaml
log_path, case_path, s, end, window = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
log = open(log_path).read()
total = re.search(r"^total\s+(\S+)", log, re.M)
io = re.search(r"^I/O\s+(\S+)", log, re.M)
particles = re.search(r"case '[^']*', (\d+) particles", log)
if not (total and io and particles): sys.exit(f"{log_path}: no timing table or particle count")
case = yaml.safe_load(open(case_path))
cells = 1
for n in case["fluid"]["cells"]: cells *= n
n = int(particles.group(1))
seconds = float(total.group(1)) - float(io.group(1))
per_sim = seconds / end
ns = seconds / (n * end / case["time"]["dem_step"]) * 1e9
print(s, n, cells, per_sim, ns, per_sim * window / 60.0, case["domain"]["max"][0] - case["domain"]["min"][0])
PY
  tail -1 "$results" | awk '{printf "%-6s %10d %10d %14.4g %12.1f %14.1f\n", $1, $2, $3, $4, $5, $6}'
done
python3 - "$results" "$window" "$limit" <<'PY'
import math, sys
rows = sorted((list(map(float, line.split())) for line in open(sys.argv[1]) if line.strip()), key=lambda r: r[1])
window, limit = float(sys.argv[2]), float(sys.argv[3])
fits = [r for r in rows if r[5] * 60.0 <= limit]
if fits:
    r = max(fits, key=lambda r: r[1])
    print(f"largest measured box within {limit / 60:g} min: scale {r[0]:g}, side {r[6]:.4g} m, {r[1]:.0f} particles, "
          f"{r[2]:.0f} cells, {r[3]:.4g} s wall per simulated second, {r[4]:.1f} ns per particle-step, window {r[5]:.1f} min")
else:
    print(f"no measured box finishes the window within {limit / 60:g} min")
# the window's wall time as a power law of N between the two measured sizes around the limit (or
# beyond the last two): the largest N within it, and the box side and cells that hold it
if len(rows) >= 2:
    k = next((i for i in range(1, len(rows)) if rows[i][5] * 60.0 > limit), len(rows) - 1)
    a, b = rows[k - 1], rows[k]
    p = math.log(b[5] / a[5]) / math.log(b[1] / a[1])
    if p > 0:
        n = a[1] * (limit / 60.0 / a[5]) ** (1.0 / p)
        s = a[0] * (n / a[1]) ** (1.0 / 3.0)
        print(f"between scales {a[0]:g} and {b[0]:g} the window's wall time grows as N^{p:.2f}: the largest box within "
              f"{limit / 60:g} min holds about {n:.0f} particles (scale {s:.2f}, side {a[6] / a[0] * s:.4g} m, "
              f"{a[2] * (s / a[0]) ** 3:.0f} cells)")
PY
if [ "${BUBBLING:-1}" != 0 ]; then
  out=$(bash "$here/bench/cfddem_fluidised_bed.sh" "$threads" "${BUBBLING_WINDOW:-0.05}" | tee "$work/bubbling.log" | grep '^result') || true
  if [ -z "$out" ]; then
    echo "bubbling bed: no result line (see $work/bubbling.log)" >&2
    exit 1
  fi
  python3 - "$out" "$here/cases/cfddem_bubbling_fluidised_bed.yaml" <<'PY'
import re, sys, yaml
line, case_path = sys.argv[1], sys.argv[2]
fields = dict(kv.split("=", 1) for kv in line.split()[2:])
dem_step = yaml.safe_load(open(case_path))["time"]["dem_step"]
per_sim, n = float(fields["s_per_s"]), int(fields["particles"])
print(f"bubbling bed (cases/cfddem_bubbling_fluidised_bed.yaml): {n} particles, {per_sim:.4g} s wall per simulated second, "
      f"{per_sim / (n / dem_step) * 1e9:.1f} ns per particle-step")
PY
fi
