#!/usr/bin/env bash
# OpenFOAM's DPMFoam (Debian package openfoam, v1912) on its own Goldschmidt tutorial, the pseudo-2D
# bubbling bed that cases/cfddem_bubbling_fluidised_bed.yaml reproduces (24,750 spheres d = 2.5 mm,
# rho = 2526 kg/m3, 2 x 30 x 90 cells, inlet 1.875 m/s, fluid step 2e-5 s, E = 1e8 Pa, nu = 0.35,
# e = 0.97, mu = 0.10 / 0.09, Ergun + Wen-Yu drag), the tutorial's settings unchanged but for the
# end time, the output and one function object (the mean pressure on the inlet patch).
#   bash bench/dpmfoam_goldschmidt.sh [WINDOW] [PARTICLES_VTU] [PROCESSES]   (defaults 0.01, tutorial
#   lattice, 1; PROCESSES > 1: decomposePar into y slabs and mpirun, as the tutorial's decomposition)
# PARTICLES_VTU: start from the positions of a grainflow particles_*.vtu (e.g. the bubbling state
# that bench/cfddem_fluidised_bed.sh keeps after its spin-up; the particles start at rest here)
# instead of the tutorial's lattice (particles at rest, falling into a packed bed during the first 0.1 s).
# Runs t = 0 ... WINDOW and prints DPMFoam's wall time per simulated second over its steps 2 to N-1
# (the set-up, mesh, injection and first step not counted), from the time each "ExecutionTime" line
# appears in its log (its own ExecutionTime is CPU time, which on a busy machine is less than the wall
# time), and the pressure drop over the bed (the inlet patch's mean pressure x rho.air, the outlet
# being at p = 0; every step into pressure_drop.csv: time, Pa); then one "result" line (read by
# bench/compare_peers.sh) with that figure, the number of parcels, the mean DEM sub-cycles per fluid
# step and the pressure-drop file.
# Installs openfoam and openfoam-examples from Debian if DPMFoam is missing (needs root and apt).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
window=${1:-0.01}
positions=${2:-}
processes=${3:-1}
work=${BENCH_DIR:-/tmp/grainflow_bench_dpmfoam}
tutorial=/usr/share/doc/openfoam-examples/examples/lagrangian/DPMFoam/Goldschmidt
if ! command -v DPMFoam >/dev/null || [ ! -d "$tutorial" ]; then
  echo "installing openfoam and openfoam-examples (Debian) ..."
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq openfoam openfoam-examples >/dev/null
fi
if [ -n "$positions" ] && [ ! -f "$positions" ]; then
  echo "no particle file $positions" >&2
  exit 1
fi
export WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc
rm -rf "$work" && mkdir -p "$work" && cp -r "$tutorial" "$work/case"
cd "$work/case"
[ -f constant/kinematicCloudPositions.gz ] && gunzip -f constant/kinematicCloudPositions.gz
if [ -n "$positions" ]; then
  python3 "$here/bench/vtu_positions_to_openfoam.py" "$positions" constant/kinematicCloudPositions
fi
# the window only, no field output (writeInterval beyond the end); the mean pressure on the inlet
# patch at every step (postProcessing/inletPressure/0/surfaceFieldValue.dat)
sed -i "s/^endTime .*/endTime         $window;/; s/^writeInterval .*/writeInterval   1000;/" system/controlDict
grep -q '^functions' system/controlDict && { echo "the tutorial's controlDict has functions already" >&2; exit 1; }
cat >> system/controlDict <<'EOF'

functions
{
    inletPressure
    {
        type            surfaceFieldValue;
        libs            ("libfieldFunctionObjects.so");
        writeControl    timeStep;
        writeInterval   1;
        log             false;
        writeFields     false;
        regionType      patch;
        name            bottom;
        operation       areaAverage;
        fields          (p);
    }
}
EOF
blockMesh > log.blockMesh 2>&1 || { echo "blockMesh failed (see $work/case/log.blockMesh)" >&2; exit 1; }
echo "DPMFoam: t = 0 ... $window s on $processes process(es) ($(nproc) cores here)"
stamp() { python3 -u -c 'import sys, time
for line in sys.stdin: sys.stdout.write(f"{time.monotonic():.6f} {line}")'; }
if [ "$processes" -gt 1 ]; then
  sed -i "s/^numberOfSubdomains .*/numberOfSubdomains $processes;/; s/^\( *n  *\)(.*);/\1(1 $processes 1);/" system/decomposeParDict
  decomposePar > log.decomposePar 2>&1 || { echo "decomposePar failed (see $work/case/log.decomposePar)" >&2; exit 1; }
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
    mpirun --oversubscribe -np "$processes" DPMFoam -parallel 2>&1 | stamp > log.DPMFoam ||
    { echo "DPMFoam failed (see $work/case/log.DPMFoam)" >&2; exit 1; }
else
  DPMFoam 2>&1 | stamp > log.DPMFoam || { echo "DPMFoam failed (see $work/case/log.DPMFoam)" >&2; exit 1; }
fi
python3 - log.DPMFoam postProcessing/inletPressure/0/surfaceFieldValue.dat constant/transportProperties "$processes" \
  "$work/case/pressure_drop.csv" <<'PY'
import re, statistics, sys
log = open(sys.argv[1]).read()
times = [float(t) for t in re.findall(r"^\S+ Time = (\S+)$", log, re.M)]
stamps = [float(s) for s in re.findall(r"^(\S+) ExecutionTime = ", log, re.M)]
cycles = [int(c) for c in re.findall(r"^\S+\s+(\d+) move-collide subCycles", log, re.M)]
parcels = re.findall(r"Current number of parcels\s*=\s*(\d+)", log)
if len(times) < 4 or len(stamps) < 4 or not cycles or not parcels:
    sys.exit("DPMFoam log: fewer than 4 time steps, or no sub-cycle or parcel lines (see log.DPMFoam)")
dt = times[1] - times[0]
seconds = stamps[-2] - stamps[0]  # steps 2 .. N-1
simulated = (len(stamps) - 2) * dt
rho = float(re.search(r"^rho\.\w+\s+(\S+);", open(sys.argv[3]).read(), re.M).group(1))
pressure = [(float(r.split()[0]), float(r.split()[1])) for r in open(sys.argv[2]) if r.strip() and not r.startswith("#")]
with open(sys.argv[5], "w") as out:
    out.write("time [s],pressure_drop [Pa]\n")
    for t, p in pressure:
        out.write(f"{t:.9g},{p * rho:.9g}\n")
window = [p * rho for t, p in pressure if t > 0.1 * times[-1]]
print(f"steps              {len(stamps)} (fluid step {dt:.3g} s), {parcels[-1]} parcels")
print(f"DEM sub-cycles     {statistics.mean(cycles):.2f} per fluid step (min {min(cycles)}, max {max(cycles)})")
print(f"wall               {seconds:.1f} s for {simulated:.4g} simulated s (steps 2 to {len(stamps) - 1})")
print(f"throughput         {seconds / simulated:.0f} s wall per simulated second")
print(f"pressure drop      {statistics.mean(window):.1f} Pa (mean of {len(window)} fluid steps after the first tenth)")
print(f"result bubbling_dpmfoam procs={sys.argv[4]} s_per_s={seconds / simulated:.6g} "
      f"particles={parcels[-1]} substeps={statistics.mean(cycles):.4g} pressure_csv={sys.argv[5]}")
PY
