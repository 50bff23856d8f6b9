#!/usr/bin/env bash
# grainflow on the pseudo-2D bubbling fluidised bed (cases/cfddem_bubbling_fluidised_bed.yaml: 24,750
# spheres, 2 x 30 x 90 cells, fluid step 2e-5 s, 3 DEM steps per fluid step), timed over DURATION
# simulated seconds after a spin-up to SPINUP s (the inlet ramp ends at 0.3 s).
#   bash bench/cfddem_fluidised_bed.sh [THREADS] [DURATION] [SPINUP] [START] [RANKS]
#   (defaults 1, 1.0, 0.35, continue, 1)
# RANKS > 1: the timed part on that many MPI ranks (mpirun, THREADS threads each; the pressure
#   through hypre), its result line named bubbling_grainflow_mpi with ranks=RANKS.
# START = continue: the spun-up bed goes on bubbling from t = SPINUP.
# START = rest: the spun-up positions at rest, the fluid at rest and the full inlet velocity from
#   t = 0 (no ramp): the start of bench/dpmfoam_goldschmidt.sh with the same positions, so that
#   both codes solve the same problem (bench/compare_peers.sh).
# The spin-up is not timed; it runs once on 2 threads and is kept in the work directory
# (spinup_SPINUP/: checkpoint.bin and particles_000001.vtu, the positions at t = SPINUP) until the
# grainflow executable or the case file is newer. The timed part writes no VTK output.
# Prints grainflow's timing table, the pressure drop over the bed (the case's pressure_drop monitor,
# first to last cell layer, sampled every fluid step into pressure_drop.csv), and one "result" line
# (read by bench/compare_peers.sh): wall seconds per simulated second without I/O (the set-up is not
# counted either), particles, DEM steps per fluid step, the pressure-drop file.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
threads=${1:-1}
duration=${2:-1.0}
spinup=${3:-0.35}
start=${4:-continue}
ranks=${5:-1}
exe=${GRAINFLOW:-$here/build/grainflow}
work=${BENCH_DIR:-/tmp/grainflow_bench_fluidised_bed}
case_file=$here/cases/cfddem_bubbling_fluidised_bed.yaml
if [ ! -x "$exe" ]; then
  echo "no $exe: build grainflow first (bash scripts/build.sh)" >&2
  exit 1
fi
case $start in continue|rest) ;; *) echo "START must be continue or rest, not '$start'" >&2; exit 1 ;; esac
mkdir -p "$work"
# The case file with other output and monitor settings (a checkpoint restarts under changed output
# and monitors keys): OUTPUT_INTERVAL = the spin-up's end (positions at t = SPINUP) or 0 (no VTK
# output); pressure drop every fluid step. With POSITIONS (a csv_file of x,y,z,r): these particles
# at rest instead of the random packing, and the inlet velocity without its ramp.
derived_case() {  # derived_case OUTPUT_INTERVAL TARGET [POSITIONS]
  python3 - "$case_file" "$@" <<'PY'
import sys, yaml
source, interval, target = sys.argv[1], float(sys.argv[2]), sys.argv[3]
case = yaml.safe_load(open(source))
case["output"] = {"interval": interval, "fluid": False}
drops = [m for m in case.get("monitors", []) if m.get("type") == "pressure_drop"]
if not drops: sys.exit(f"{source}: no pressure_drop monitor")
for m in drops: m["interval"] = 0.0  # every coupling (fluid) step
if len(sys.argv) > 4:
    material = case["insertion"][0]["material"]
    case["insertion"] = [{"type": "csv_file", "file": sys.argv[4], "material": material}]
    for face in case["fluid"]["boundaries"].values():
        face.pop("ramp_time", None)
yaml.safe_dump(case, open(target, "w"), sort_keys=False)
PY
}
spin_dir=$work/spinup_${spinup}
if [ ! -f "$spin_dir/checkpoint.bin" ] || [ "$spin_dir/checkpoint.bin" -ot "$exe" ] ||
   [ "$spin_dir/checkpoint.bin" -ot "$case_file" ] || [ ! -f "$spin_dir/particles_000001.vtu" ]; then
  echo "spin-up to t = $spinup s on 2 threads (not timed; kept in $spin_dir) ..."
  derived_case "$spinup" "$work/spinup.yaml"
  # passive OpenMP waits: on a machine busy with other work, spinning threads slow the run many-fold
  OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} "$exe" run "$work/spinup.yaml" --threads 2 --end-time "$spinup" \
    --output "$spin_dir" --overwrite --quiet
fi
out=$work/${start}_${threads}_${ranks}
if [ "$start" = continue ]; then
  derived_case 0 "$work/timed.yaml"
  begin=$spinup
  restart=(--restart "$spin_dir/checkpoint.bin")
else
  python3 "$here/bench/vtu_positions_to_openfoam.py" "$spin_dir/particles_000001.vtu" "$work/positions.csv" >/dev/null
  derived_case 0 "$work/timed.yaml" "$work/positions.csv"
  begin=0
  restart=()
fi
end=$(python3 -c "print($begin + $duration)")
echo "grainflow: t = $begin ... $end s on $ranks rank(s) x $threads thread(s), start: $start"
launcher=()
if [ "$ranks" -gt 1 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  launcher=(mpirun --oversubscribe -n "$ranks")
fi
# OpenMP wait policy: the default (threads spin briefly between parallel regions) on an idle machine;
# set OMP_WAIT_POLICY=passive yourself on a machine busy with other work.
"${launcher[@]}" "$exe" run "$work/timed.yaml" --threads "$threads" --end-time "$end" "${restart[@]}" \
  --output "$out" --overwrite > "$out.log" 2>&1 || { cat "$out.log" >&2; exit 1; }
sed -n '/^phase/,/^throughput/p' "$out.log"
python3 - "$out.log" "$out/pressure_drop.csv" "$out/run.yaml" "$threads" "$begin" "$end" "$ranks" <<'PY'
import csv, re, statistics, sys
log_path, drop_path, resolved_path, threads = sys.argv[1:5]
begin, end, ranks = float(sys.argv[5]), float(sys.argv[6]), int(sys.argv[7])
log = open(log_path).read()
total = re.search(r"^total\s+(\S+)", log, re.M)
io = re.search(r"^I/O\s+(\S+)", log, re.M)
particles = re.search(r"case '[^']*', (\d+) particles", log)
if not (total and io and particles): sys.exit(f"{log_path}: no timing table or particle count")
substeps = re.search(r"^time\.coupling_interval: (\d+)", open(resolved_path).read(), re.M)
rows = [(float(r[0]), float(r[1])) for r in list(csv.reader(open(drop_path)))[1:]]
later = [p for t, p in rows if t > begin + 0.1 * (end - begin)]
if not later: sys.exit(f"{drop_path}: no pressure-drop rows in the timed window")
seconds = float(total.group(1)) - float(io.group(1))
print(f"without I/O        {seconds / (end - begin):.4g} s wall per simulated second")
print(f"pressure drop      {statistics.mean(later):.1f} Pa (mean of {len(later)} fluid steps after the first tenth)")
name = "bubbling_grainflow" if ranks == 1 else f"bubbling_grainflow_mpi ranks={ranks}"
print(f"result {name} threads={threads if ranks == 1 else ranks} s_per_s={seconds / (end - begin):.6g} "
      f"particles={particles.group(1)} substeps={substeps.group(1) if substeps else 'nan'} pressure_csv={drop_path}")
PY
