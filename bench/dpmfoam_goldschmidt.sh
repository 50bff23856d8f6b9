#!/usr/bin/env bash
# The reference of issue 6's speed target: OpenFOAM's DPMFoam (Debian package openfoam, v1912) on
# its own Goldschmidt tutorial, the pseudo-2D bubbling bed that cases/cfddem_bubbling_fluidised_bed.yaml
# reproduces (24,750 spheres d = 2.5 mm, rho = 2526 kg/m3, 2 x 30 x 90 cells, inlet 1.875 m/s, fluid
# step 2e-5 s, E = 1e8 Pa, nu = 0.35, e = 0.97, mu = 0.10 / 0.09, Ergun + Wen-Yu drag).
# Times WINDOW simulated seconds and prints DPMFoam's wall time per simulated second, from its own
# ExecutionTime after the first step (the set-up, mesh and injection are not counted).
#   bash bench/dpmfoam_goldschmidt.sh [WINDOW] [PARTICLES_VTU] [PROCESSES]   (defaults 0.01, tutorial
#   lattice, 1; PROCESSES > 1: decomposePar into y slabs and mpirun, as the tutorial's decomposition)
# PARTICLES_VTU: start from the positions of a grainflow particles_*.vtu (e.g. a bubbling state of
# cases/cfddem_bubbling_fluidised_bed.yaml; the particles start at rest there), instead of the
# tutorial's lattice (particles at rest, falling into a packed bed during the first 0.1 s).
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
export WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc
rm -rf "$work" && mkdir -p "$work" && cp -r "$tutorial" "$work/case"
cd "$work/case"
[ -f constant/kinematicCloudPositions.gz ] && gunzip -f constant/kinematicCloudPositions.gz
if [ -n "$positions" ]; then
  python3 "$here/bench/vtu_positions_to_openfoam.py" "$positions" constant/kinematicCloudPositions
fi
# the window only, no field output (writeInterval beyond the end)
sed -i "s/^endTime .*/endTime         $window;/; s/^writeInterval .*/writeInterval   1000;/" system/controlDict
blockMesh > log.blockMesh 2>&1
echo "DPMFoam: t = 0 ... $window s on $processes process(es) ($(nproc) cores here)"
if [ "$processes" -gt 1 ]; then
  sed -i "s/^numberOfSubdomains .*/numberOfSubdomains $processes;/; s/^\( *n  *\)(.*);/\1(1 $processes 1);/" system/decomposeParDict
  decomposePar > log.decomposePar 2>&1
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -np "$processes" DPMFoam -parallel > log.DPMFoam 2>&1
else
  DPMFoam > log.DPMFoam 2>&1
fi
python3 - log.DPMFoam <<'PY'
import re, sys
log = open(sys.argv[1]).read()
times = [float(t) for t in re.findall(r"^Time = (\S+)$", log, re.M)]
wall = [float(w) for w in re.findall(r"^ExecutionTime = (\S+) s", log, re.M)]
cycles = [int(c) for c in re.findall(r"^\s*(\d+) move-collide subCycles", log, re.M)]
parcels = re.findall(r"Current number of parcels\s*=\s*(\d+)", log)
if len(times) < 3 or len(wall) < 3 or not cycles:
    sys.exit("DPMFoam log: fewer than 3 time steps or no sub-cycle lines (see log.DPMFoam)")
n = min(len(times), len(wall))
simulated = times[n - 1] - times[0]
seconds = wall[n - 1] - wall[0]
print(f"steps              {n} (fluid step {times[1] - times[0]:.3g} s), {parcels[-1] if parcels else '?'} parcels")
print(f"DEM sub-cycles     {sum(cycles) / len(cycles):.2f} per fluid step (min {min(cycles)}, max {max(cycles)})")
print(f"wall               {seconds:.1f} s for {simulated:.4g} simulated s after the first step")
print(f"throughput         {seconds / simulated:.0f} s wall per simulated second")
PY
