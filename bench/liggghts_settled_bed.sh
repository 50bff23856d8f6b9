#!/usr/bin/env bash
# The reference of issue 4's speed target ("3x faster than the usual granular codes"): LIGGGHTS
# (Debian package liggghts, 3.8.0) on the same settled bed as BM_DemSettledBed, the same positions.
#   15,000 spheres d = 2 mm, rho = 2500 kg/m3, box 0.06 x 0.06 x 0.2 m (six walls), Hertz with
#   tangential history, E = 1e7 Pa, nu = 0.45, e = 0.3, mu = 0.5, dt = 2e-6 s, skin 0.2 mm.
#
#   bash bench/liggghts_settled_bed.sh [ROUNDS] [STEPS] [PROCESSES]
#   (defaults 5, 2000, 1; PROCESSES > 1: LIGGGHTS on that many MPI ranks split along x, against
#   grainflow on as many OpenMP threads). Installs liggghts from Debian if it is missing (root, apt).
#
# 1. grainflow_bench builds and settles the bed; GRAINFLOW_SETTLED_BED_CSV writes its positions.
# 2. ROUNDS rounds, each one grainflow_bench BM_DemSettledBed (500 warm-up steps, then >= 3 s
#    timed) and, right after it, LIGGGHTS on the same positions (the same 500 warm-up steps, in
#    which the friction history builds up, then STEPS timed steps: "Loop time" / (steps x
#    particles)). A shared host's speed can drift by tens of per cent within minutes,
#    so the two codes alternate, and the figures compared are each code's fastest round (the
#    least disturbed one) with the medians beside them.
# 3. The same physics: grainflow runs the same positions as a case (csv_file insertion) for
#    500 + STEPS steps, and its translational kinetic energy is set beside LIGGGHTS' KinEng every
#    500 steps. The top of the bed is still compacting, so the energy grows several-fold over the
#    run, and agreement is a real check. One difference is left: grainflow's box walls are rigid
#    (the benchmark's default wall material); LIGGGHTS' primitive walls have the particles' E and
#    nu (it has no rigid wall).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=${1:-5}
steps=${2:-2000}
processes=${3:-1}
work=${BENCH_DIR:-/tmp/grainflow_bench_liggghts}
bench_exe=${GRAINFLOW_BENCH:-$here/build/bench/grainflow_bench}
grainflow_exe=${GRAINFLOW:-$here/build/grainflow}
if ! command -v liggghts >/dev/null; then
  echo "installing liggghts (Debian) ..."
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts >/dev/null
fi
if [ ! -x "$bench_exe" ] || [ ! -x "$grainflow_exe" ]; then
  echo "no $bench_exe or $grainflow_exe: build first (bash scripts/build.sh)" >&2
  exit 1
fi
rm -rf "$work" && mkdir -p "$work"
cd "$work"

run_grainflow() {  # one BM_DemSettledBed run; appends its ns per particle-step to grainflow_ns
  env ${1:+GRAINFLOW_SETTLED_BED_CSV=$1} OMP_NUM_THREADS="$processes" \
    "$bench_exe" --benchmark_filter='BM_DemSettledBed/' > grainflow.log 2>&1
  python3 - grainflow.log >> grainflow_ns <<'PY'
import re, sys
m = re.search(r"ns_per_particle_step=([0-9.]+)", open(sys.argv[1]).read())
if not m: sys.exit("grainflow_bench: no ns_per_particle_step (see grainflow.log)")
print(m.group(1))
PY
}
run_liggghts() {  # one LIGGGHTS run of in.bed; appends its ns per particle-step to liggghts_ns
  if [ "$processes" -gt 1 ]; then
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -np "$processes" liggghts -in in.bed > log.liggghts 2>&1
  else
    liggghts -in in.bed > log.liggghts 2>&1
  fi
  python3 - log.liggghts >> liggghts_ns <<'PY'
import re, sys
loops = re.findall(r"Loop time of (\S+) on (\d+) procs(?: \(\d+ MPI x \d+ OpenMP\))? for (\d+) steps with (\d+) atoms",
                   open(sys.argv[1]).read())
if len(loops) < 2: sys.exit("LIGGGHTS log: no timed run (see log.liggghts)")
seconds, procs, steps, atoms = loops[-1]
print(float(seconds) / (int(steps) * int(atoms)) * 1e9)
PY
}

echo "settling the bed (grainflow_bench) ..."
run_grainflow "$work/bed.csv"
# LIGGGHTS data file (atom_style granular: id type diameter density x y z)
python3 - bed.csv <<'PY'
import sys
rows = [list(map(float, line.split(","))) for line in open(sys.argv[1]) if line.strip()]
with open("bed.data", "w") as out:
    out.write(f"grainflow settled bed\n\n{len(rows)} atoms\n1 atom types\n\n")
    out.write("0 0.06 xlo xhi\n0 0.06 ylo yhi\n0 0.2 zlo zhi\n\nAtoms\n\n")
    for k, (x, y, z, r) in enumerate(rows, 1):
        out.write(f"{k} 1 {2 * r:.17g} 2500 {x:.17g} {y:.17g} {z:.17g}\n")
PY
if [ "$processes" -gt 1 ]; then grid="processors $processes 1 1"; else grid=""; fi
cat > in.bed <<EOF
# settled bed of grainflow's BM_DemSettledBed (bench/liggghts_settled_bed.sh)
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
$grid
read_data bed.data
neighbor 0.0002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-6
fix gravity all gravity 9.81 vector 0.0 0.0 -1.0
fix wx0 all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix wx1 all wall/gran model hertz tangential history primitive type 1 xplane 0.06
fix wy0 all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix wy1 all wall/gran model hertz tangential history primitive type 1 yplane 0.06
fix wz0 all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix wz1 all wall/gran model hertz tangential history primitive type 1 zplane 0.2
fix integrate all nve/sphere
thermo 500
run 500
run $steps
EOF

: > grainflow_ns
: > liggghts_ns
for round in $(seq "$rounds"); do
  run_grainflow ""
  run_liggghts
  echo "round $round: grainflow $(tail -1 grainflow_ns | cut -c1-6) ns, LIGGGHTS $(tail -1 liggghts_ns | cut -c1-6) ns per particle-step"
done

echo "grainflow, the same positions as a case (kinetic energy check) ..."
end=$(python3 -c "print((500 + $steps) * 2e-6)")
cat > gf.yaml <<EOF
case: {name: liggghts_settled_bed_check}
domain: {min: [0, 0, 0], max: [0.06, 0.06, 0.2]}
gravity: [0, 0, -9.81]
time: {end: $end, dem_step: 2.0e-6}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1e7, poisson_ratio: 0.45}
contact: {law: hertz_mindlin, restitution: 0.3, friction: 0.5}
walls:
  - {type: box, min: [0, 0, 0], max: [0.06, 0.06, 0.2]}
insertion:
  - {type: csv_file, file: bed.csv}
neighbour_search: {skin: 0.0002}
monitors:
  - {type: kinetic_energy, interval: 0.001}
EOF
"$grainflow_exe" run gf.yaml --threads "$processes" --output gf_out --overwrite --quiet
python3 - log.liggghts gf_out/kinetic_energy.csv <<'PY'
import csv, re, statistics, sys
log = open(sys.argv[1]).read()
# LIGGGHTS thermo rows "Step Atoms KinEng CPU": KinEng by step
liggghts = {int(m.group(1)): float(m.group(2))
            for m in re.finditer(r"^\s+(\d+)\s+\d+\s+(\S+)\s+\S+\s*$", log, re.M)}
rows = list(csv.reader(open(sys.argv[2])))[1:]
grainflow = {round(float(r[0]) / 2e-6): float(r[1]) for r in rows}
common = sorted(k for k in liggghts if k in grainflow and k > 0)
if not common: sys.exit("no common kinetic-energy samples (see log.liggghts, gf_out/)")
worst = 0.0
print("  step   grainflow KE [J]   LIGGGHTS KE [J]   difference")
for k in common:
    d = grainflow[k] / liggghts[k] - 1.0
    worst = max(worst, abs(d))
    print(f"  {k:5d}   {grainflow[k]:.4e}         {liggghts[k]:.4e}        {100 * d:+.1f} %")
print(f"  largest difference {100 * worst:.1f} %")
ours = [float(x) for x in open("grainflow_ns")]
theirs = [float(x) for x in open("liggghts_ns")]
print(f"grainflow: fastest {min(ours):.1f}, median {statistics.median(ours):.1f} ns per particle-step ({len(ours)} rounds)")
print(f"LIGGGHTS:  fastest {min(theirs):.1f}, median {statistics.median(theirs):.1f} ns per particle-step")
print(f"grainflow is {min(theirs) / min(ours):.2f} x faster than LIGGGHTS (fastest rounds; "
      f"medians: {statistics.median(theirs) / statistics.median(ours):.2f} x)")
PY
