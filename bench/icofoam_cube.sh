#!/usr/bin/env bash
# grainflow's fluid against OpenFOAM's icoFoam (Debian package openfoam, v1912) on the lid-driven
# cube: 1 x 1 x 1 m, N^3 cells, lid y = 1 moving at 1 m/s in +x, no-slip elsewhere, nu = 0.01 m2/s
# (Re 100), both from rest with the same fixed step dt = 1/128 s for STEPS steps, one process / one
# thread each. The grainflow case is the 3D variant of cases/fluid_cavity.yaml (central convection);
# icoFoam runs its cavity tutorial's set-up in 3D (PISO, 2 correctors, Gauss linear) with GAMG for
# the pressure. Both solve to the tutorial's tolerances: pressure 1e-6, velocity 1e-5.
#
#   bash bench/icofoam_cube.sh [ROUNDS] [STEPS] [CELLS]      (defaults 3, 200, 64)
#
# Figure: wall time per cell and step. grainflow: its timing table without I/O (set-up not counted);
# icoFoam: the wall time between its first and its last-but-one step (set-up and the final field
# write not counted), from the time each "ExecutionTime" line appears in its log (its own
# ExecutionTime is CPU time, which on a busy machine is less than the wall time grainflow reports).
# The two codes alternate, ROUNDS times; the fastest round of each is compared.
# Same-problem check: the centreline profiles u(y) at x = z = 0.5 and v(x) at y = z = 0.5 after the
# last step (the mean of the four cells around each line; both codes store cell-centred velocities at
# the same points), largest difference relative to the lid speed, tolerance 0.02: the Ghia validation
# (validation/fluid_cavity_ghia) holds each code's discretisation error on a 64-cell grid to 0.01 of
# the lid speed, so two second-order discretisations (grainflow's staggered MAC grid with an
# incremental projection, icoFoam's collocated grid with PISO) may differ by twice that.
# Prints a summary and "result ..." lines (read by bench/compare_peers.sh).
# Installs openfoam from Debian if icoFoam is missing (needs root and apt).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=${1:-3}
steps=${2:-200}
cells=${3:-64}
work=${BENCH_DIR:-/tmp/grainflow_bench_icofoam_cube}
grainflow_exe=${GRAINFLOW:-$here/build/grainflow}
if [ ! -x "$grainflow_exe" ]; then
  echo "no $grainflow_exe: build grainflow first (bash scripts/build.sh)" >&2
  exit 1
fi
if [ "$steps" -lt 3 ] || [ $((cells % 2)) -ne 0 ]; then
  echo "STEPS must be at least 3 and CELLS even (got $steps, $cells)" >&2
  exit 1
fi
if ! command -v icoFoam >/dev/null || ! command -v blockMesh >/dev/null; then
  echo "installing openfoam (Debian) ..."
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq openfoam >/dev/null
fi
export WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc
dt=0.0078125  # s: CFL 0.5 on the lid speed at 64 cells (as cases/fluid_cavity.yaml at 128)
end=$(python3 -c "print($steps * $dt)")
rm -rf "$work" && mkdir -p "$work/ico/0" "$work/ico/constant" "$work/ico/system"
cd "$work"

# --- grainflow: cases/fluid_cavity.yaml made 3D
python3 - "$here/cases/fluid_cavity.yaml" cube.yaml "$cells" "$dt" "$end" <<'PY'
import sys, yaml
source, target, n, dt, end = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
case = yaml.safe_load(open(source))
case["case"] = {"name": "fluid_cube", "description": f"lid-driven cube, Re 100, {n}^3 (bench/icofoam_cube.sh)"}
case["domain"]["max"] = [1.0, 1.0, 1.0]
case["time"].update({"end": end, "dem_step": dt, "coupling_interval": 1})
case["output"] = {"interval": end, "particles": False}  # fluid fields at t = 0 and at the end
case.pop("monitors", None)
fluid = case["fluid"]
fluid["cells"] = [n, n, n]
fluid["pressure"] = {"tolerance": 1.0e-6}  # icoFoam's cavity tutorial: p 1e-6, U 1e-5
fluid["momentum_tolerance"] = 1.0e-5
lid = fluid["boundaries"]["y_max"]
if lid.get("velocity") != [1.0, 0.0, 0.0]:
    sys.exit(f"{source}: the lid (fluid.boundaries.y_max) is expected to move at [1, 0, 0] m/s")
yaml.safe_dump(case, open(target, "w"), sort_keys=False)
PY

# --- icoFoam: the cavity tutorial in 3D, GAMG for p
header() { printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n    object %s;\n}\n' "$1" "$2"; }
{ header dictionary blockMeshDict; cat <<EOF
scale 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) ($cells $cells $cells) simpleGrading (1 1 1));
edges ();
boundary
(
    lid { type wall; faces ((3 7 6 2)); }
    walls { type wall; faces ((0 4 7 3) (2 6 5 1) (1 5 4 0) (0 3 2 1) (4 5 6 7)); }
);
mergePatchPairs ();
EOF
} > ico/system/blockMeshDict
{ header dictionary controlDict; cat <<EOF
application icoFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime $end;
deltaT $dt;
writeControl timeStep;
writeInterval $steps;
purgeWrite 0;
writeFormat ascii;
writePrecision 10;
writeCompression off;
timeFormat general;
timePrecision 10;
runTimeModifiable false;
EOF
} > ico/system/controlDict
{ header dictionary fvSchemes; cat <<'EOF'
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear orthogonal; }
interpolationSchemes { default linear; }
snGradSchemes { default orthogonal; }
EOF
} > ico/system/fvSchemes
{ header dictionary fvSolution; cat <<'EOF'
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-06; relTol 0.05; }
    pFinal { $p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-05; relTol 0; }
}
PISO { nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }
EOF
} > ico/system/fvSolution
{ header dictionary transportProperties; echo "nu 0.01;"; } > ico/constant/transportProperties
{ header volVectorField U; cat <<'EOF'
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    lid { type fixedValue; value uniform (1 0 0); }
    walls { type noSlip; }
}
EOF
} > ico/0/U
{ header volScalarField p; cat <<'EOF'
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    lid { type zeroGradient; }
    walls { type zeroGradient; }
}
EOF
} > ico/0/p
(cd ico && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed (see $work/ico/log.blockMesh)" >&2; exit 1; }

run_grainflow() {  # appends grainflow's ns per cell-step to grainflow_ns
  OMP_NUM_THREADS=1 "$grainflow_exe" run cube.yaml --threads 1 --output gf_out --overwrite > grainflow.log 2>&1 ||
    { echo "grainflow failed (see $work/grainflow.log)" >&2; exit 1; }
  python3 - grainflow.log "$steps" "$cells" >> grainflow_ns <<'PY'
import re, sys
log, steps, n = open(sys.argv[1]).read(), int(sys.argv[2]), int(sys.argv[3])
total = re.search(r"^total\s+(\S+)", log, re.M)
io = re.search(r"^I/O\s+(\S+)", log, re.M)
if not total or not io: sys.exit("grainflow log: no timing table (see grainflow.log)")
print((float(total.group(1)) - float(io.group(1))) / (steps * n ** 3) * 1e9)
PY
}
run_icofoam() {  # appends icoFoam's ns per cell-step to icofoam_ns
  rm -rf ico/[1-9]* ico/0.[0-9]*
  # each log line with the wall time at which it appeared
  (cd ico && icoFoam 2>&1 | python3 -u -c 'import sys, time
for line in sys.stdin: sys.stdout.write(f"{time.monotonic():.6f} {line}")' > log.icoFoam) ||
    { echo "icoFoam failed (see $work/ico/log.icoFoam)" >&2; exit 1; }
  python3 - ico/log.icoFoam "$cells" >> icofoam_ns <<'PY'
import re, sys
stamps = [float(m.group(1)) for m in re.finditer(r"^(\S+) ExecutionTime = ", open(sys.argv[1]).read(), re.M)]
if len(stamps) < 3: sys.exit("icoFoam log: fewer than 3 time steps (see ico/log.icoFoam)")
# steps 2 .. N-1: no set-up, no field write (the last step writes)
print((stamps[-2] - stamps[0]) / ((len(stamps) - 2) * int(sys.argv[2]) ** 3) * 1e9)
PY
}

echo "lid-driven cube ${cells}^3, Re 100, $steps steps of $dt s: grainflow (1 thread) and icoFoam (1 process), $rounds round(s)"
: > grainflow_ns
: > icofoam_ns
for round in $(seq "$rounds"); do
  run_grainflow
  run_icofoam
  echo "round $round: grainflow $(tail -1 grainflow_ns | cut -c1-6) ns, icoFoam $(tail -1 icofoam_ns | cut -c1-6) ns per cell-step"
done

last=$(printf '%s\n' ico/[0-9]* | sort -t/ -k2 -g | tail -1)  # the time directory of the end
python3 - gf_out "$last/U" "$cells" "$end" "$steps" <<'PY'
import base64, glob, re, statistics, struct, sys

def vti_arrays(path):  # grainflow's VTI: inline base64 Float64 arrays with a UInt64 byte count
    text = open(path, encoding="ascii").read()
    arrays = {}
    for m in re.finditer(r'<DataArray type="Float64" Name="(\w+)" NumberOfComponents="1" format="binary">\s*([^<]*)<', text):
        raw = base64.b64decode(m.group(2).strip())
        (size,) = struct.unpack_from("<Q", raw, 0)
        arrays[m.group(1)] = struct.unpack_from(f"<{size // 8}d", raw, 8)
    return arrays

def foam_vectors(path):  # OpenFOAM ASCII volVectorField: internalField nonuniform List<vector> N ( (x y z) ... )
    text = open(path, encoding="ascii").read()
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    if not m: sys.exit(f"{path}: no nonuniform internalField")
    count = int(m.group(1))
    rows = re.findall(r"\(([^()]+)\)", text[m.end():m.end() + 80 * count])[:count]
    if len(rows) != count: sys.exit(f"{path}: {len(rows)} of {count} cell values read")
    xyz = [tuple(map(float, r.split())) for r in rows]
    return [v[0] for v in xyz], [v[1] for v in xyz]

out_dir, foam_u, n, end = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
vtis = sorted(glob.glob(f"{out_dir}/fluid_*.vti"))
if len(vtis) < 2: sys.exit(f"{out_dir}: no fluid field at the end time")
g = vti_arrays(vtis[-1])
gu, gv = g["velocity_x"], g["velocity_y"]
fu, fv = foam_vectors(foam_u)
if len(gu) != n ** 3 or len(fu) != n ** 3: sys.exit("cell counts differ from CELLS^3")
cell = lambda i, j, k: i + n * (j + n * k)  # x fastest in both (VTK ImageData, blockMesh hex)
h = n // 2
def u_of_y(f): return [sum(f[cell(i, j, k)] for i in (h - 1, h) for k in (h - 1, h)) / 4 for j in range(n)]
def v_of_x(f): return [sum(f[cell(i, j, k)] for j in (h - 1, h) for k in (h - 1, h)) / 4 for i in range(n)]
worst = 0.0
for name, a, b in (("u(y) at x = z = 0.5", u_of_y(gu), u_of_y(fu)), ("v(x) at y = z = 0.5", v_of_x(gv), v_of_x(fv))):
    d = [abs(p - q) for p, q in zip(a, b)]
    k = max(range(n), key=lambda c: d[c])
    worst = max(worst, d[k])
    print(f"  {name}: largest difference {d[k]:.4f} m/s at cell {k} (grainflow {a[k]:+.4f}, icoFoam {b[k]:+.4f}); "
          f"range grainflow [{min(a):+.4f}, {max(a):+.4f}], icoFoam [{min(b):+.4f}, {max(b):+.4f}]")
tolerance = 0.02  # of the lid speed (1 m/s); see the header of bench/icofoam_cube.sh
ours = [float(x) for x in open("grainflow_ns")]
theirs = [float(x) for x in open("icofoam_ns")]
cells = n ** 3
print(f"grainflow: fastest {min(ours):.1f}, median {statistics.median(ours):.1f} ns per cell-step "
      f"({min(ours) * cells * 1e-9:.4f} s per step, {len(ours)} rounds)")
print(f"icoFoam:   fastest {min(theirs):.1f}, median {statistics.median(theirs):.1f} ns per cell-step "
      f"({min(theirs) * cells * 1e-9:.4f} s per step)")
print(f"grainflow is {min(theirs) / min(ours):.2f} x faster than icoFoam (fastest rounds; "
      f"medians: {statistics.median(theirs) / statistics.median(ours):.2f} x)")
print(f"result cube procs=1 peer={min(theirs):.6g} grainflow={min(ours):.6g} "
      f"peer_median={statistics.median(theirs):.6g} grainflow_median={statistics.median(ours):.6g} "
      f"peer_s_per_step={min(theirs) * cells * 1e-9:.6g} grainflow_s_per_step={min(ours) * cells * 1e-9:.6g}")
print(f"check cube_profiles value={worst:.6g} tolerance={tolerance} pass={int(worst <= tolerance)} "
      f"steps={sys.argv[5]} time={end:g}")
PY
