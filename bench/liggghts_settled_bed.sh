#!/usr/bin/env bash
# grainflow's DEM against LIGGGHTS (Debian package liggghts, 3.8.0) on the same settled bed as
# BM_DemSettledBed, the same positions:
#   15,000 spheres d = 2 mm, rho = 2500 kg/m3, box 0.06 x 0.06 x 0.2 m (six walls), Hertz with
#   tangential history, E = 1e7 Pa, nu = 0.45, e = 0.3, mu = 0.5, dt = 2e-6 s, skin 0.2 mm.
#
#   bash bench/liggghts_settled_bed.sh [ROUNDS] [STEPS] [PROCESSES...]
#   (defaults 5, 2000, 1; each PROCESSES value P: LIGGGHTS on P MPI ranks split along x, against
#   grainflow on P OpenMP threads and, for P > 1, grainflow on P MPI ranks split along x). Installs liggghts from Debian if it is missing (root, apt).
#
# 1. grainflow_bench builds and settles the bed; GRAINFLOW_SETTLED_BED_CSV writes its positions.
# 2. ROUNDS rounds, each one, for every P, grainflow_bench BM_DemSettledBed (500 warm-up steps, then
#    >= 3 s timed) and, right after it, LIGGGHTS on the same positions (the same 500 warm-up steps,
#    in which the friction history builds up, then STEPS timed steps: "Loop time" / (steps x
#    particles), a wall time). The host's speed drifts by tens of per cent within minutes on a
#    shared machine, so the two codes alternate, and the figures compared are each code's fastest
#    round (the least disturbed one) with the medians beside them.
# 3. The same physics: grainflow runs the same positions as a case (csv_file insertion) for
#    500 + STEPS steps, and its translational kinetic energy is set beside LIGGGHTS' KinEng every
#    500 steps (for every P; grainflow's DEM gives the same bits on any thread count). The top of the
#    bed is still compacting, so the energy grows several-fold over the run, and agreement is a real
#    check. Tolerance: 10 % at every sample. The codes differ in one respect: grainflow's box walls
#    are rigid (the benchmark's default wall material), LIGGGHTS' primitive walls have the
#    particles' E and nu (it has no rigid wall), which softens the contacts of the wall layer.
# Prints a summary per P and "result" / "check" lines (read by bench/compare_peers.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
rounds=${1:-5}
steps=${2:-2000}
shift $(($# < 2 ? $# : 2))
process_counts=("${@:-1}")
for p in "${process_counts[@]}"; do
  [[ $p =~ ^[1-9][0-9]*$ ]] || { echo "PROCESSES must be positive integers, not '$p'" >&2; exit 1; }
done
work=${BENCH_DIR:-/tmp/grainflow_bench_liggghts}
bench_exe=${GRAINFLOW_BENCH:-$here/build/bench/grainflow_bench}
grainflow_exe=${GRAINFLOW:-$here/build/grainflow}
if [ ! -x "$bench_exe" ] || [ ! -x "$grainflow_exe" ]; then
  echo "no $bench_exe or $grainflow_exe: build grainflow first (bash scripts/build.sh)" >&2
  exit 1
fi
if ! command -v liggghts >/dev/null; then
  echo "installing liggghts (Debian) ..."
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts >/dev/null
fi
rm -rf "$work" && mkdir -p "$work"
cd "$work"

run_grainflow() {  # run_grainflow P [CSV]: one BM_DemSettledBed run; appends its ns per particle-step to grainflow_ns.P
  env ${2:+GRAINFLOW_SETTLED_BED_CSV=$2} OMP_NUM_THREADS="$1" \
    "$bench_exe" --benchmark_filter='BM_DemSettledBed/' > grainflow.log 2>&1 ||
    { echo "grainflow_bench failed (see $work/grainflow.log)" >&2; exit 1; }
  python3 - grainflow.log >> "grainflow_ns.$1" <<'PY'
import re, sys
m = re.search(r"ns_per_particle_step=([0-9.]+)", open(sys.argv[1]).read())
if not m: sys.exit("grainflow_bench: no ns_per_particle_step (see grainflow.log)")
print(m.group(1))
PY
}
run_grainflow_mpi() {  # run_grainflow_mpi P: the bed as a case on P MPI ranks x 1 thread; appends ns per particle-step to grainflow_mpi_ns.P
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1 \
    mpirun --oversubscribe -np "$1" "$grainflow_exe" run "gf_mpi.$1.yaml" --threads 1 --output "gf_mpi_out.$1" \
    --overwrite > "grainflow_mpi.$1.log" 2>&1 || { echo "grainflow on $1 ranks failed (see $work/grainflow_mpi.$1.log)" >&2; exit 1; }
  python3 - "grainflow_mpi.$1.log" >> "grainflow_mpi_ns.$1" <<'PY'
import re, sys
m = re.search(r"([0-9.e+]+) ns per particle-step", open(sys.argv[1]).read())
if not m: sys.exit(f"grainflow on MPI ranks: no ns per particle-step (see {sys.argv[1]})")
print(m.group(1))
PY
}
run_liggghts() {  # run_liggghts P: one LIGGGHTS run of in.bed.P; appends its ns per particle-step to liggghts_ns.P
  if [ "$1" -gt 1 ]; then
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
      mpirun --oversubscribe -np "$1" liggghts -in "in.bed.$1" > "log.liggghts.$1" 2>&1 ||
      { echo "LIGGGHTS failed (see $work/log.liggghts.$1)" >&2; exit 1; }
  else
    liggghts -in in.bed.1 > log.liggghts.1 2>&1 || { echo "LIGGGHTS failed (see $work/log.liggghts.1)" >&2; exit 1; }
  fi
  python3 - "log.liggghts.$1" >> "liggghts_ns.$1" <<'PY'
import re, sys
loops = re.findall(r"Loop time of (\S+) on (\d+) procs(?: \(\d+ MPI x \d+ OpenMP\))? for (\d+) steps with (\d+) atoms",
                   open(sys.argv[1]).read())
if len(loops) < 2: sys.exit(f"LIGGGHTS log: no timed run (see {sys.argv[1]})")
seconds, procs, steps, atoms = loops[-1]
print(float(seconds) / (int(steps) * int(atoms)) * 1e9)
PY
}

echo "settling the bed (grainflow_bench) ..."
run_grainflow 1 "$work/bed.csv"
rm -f grainflow_ns.1
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
for p in "${process_counts[@]}"; do
  if [ "$p" -gt 1 ]; then grid="processors $p 1 1"; else grid=""; fi
  cat > "in.bed.$p" <<EOF
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
  : > "grainflow_ns.$p"
  : > "liggghts_ns.$p"
done

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
# grainflow on P MPI ranks (P > 1): the same bed as a case, split along x as LIGGGHTS splits it,
# the same 500 + STEPS steps; its figure is the run's wall time per particle-step (all phases, the
# warm-up steps included).
for p in "${process_counts[@]}"; do
  if [ "$p" -gt 1 ]; then
    sed -e "s/domain: {min: \[0, 0, 0\], max: \[0.06, 0.06, 0.2\]}/domain: {min: [0, 0, 0], max: [0.06, 0.06, 0.2], decomposition: [$p, 1, 1]}\nparallel: {rebalance_interval: 0}/" \
      -e '/^monitors:/,$d' gf.yaml > "gf_mpi.$p.yaml"
  fi
done

for round in $(seq "$rounds"); do
  for p in "${process_counts[@]}"; do
    run_grainflow "$p"
    run_liggghts "$p"
    [ "$p" -gt 1 ] && run_grainflow_mpi "$p"
    echo "round $round, $p thread(s) / rank(s): grainflow $(tail -1 "grainflow_ns.$p" | cut -c1-6) ns," \
      "LIGGGHTS $(tail -1 "liggghts_ns.$p" | cut -c1-6) ns per particle-step" \
      "$([ "$p" -gt 1 ] && echo "(grainflow on $p MPI ranks: $(tail -1 "grainflow_mpi_ns.$p" | cut -c1-6) ns)")"
  done
done

echo "grainflow, the same positions as a case (kinetic energy check) ..."
"$grainflow_exe" run gf.yaml --threads "$(nproc)" --output gf_out --overwrite --quiet
python3 - gf_out/kinetic_energy.csv "${process_counts[@]}" <<'PY'
import csv, re, statistics, sys
tolerance = 0.10  # at every sample; see the header of bench/liggghts_settled_bed.sh
rows = list(csv.reader(open(sys.argv[1])))[1:]
grainflow = {round(float(r[0]) / 2e-6): float(r[1]) for r in rows}
for p in sys.argv[2:]:
    log = open(f"log.liggghts.{p}").read()
    # LIGGGHTS thermo rows "Step Atoms KinEng CPU": KinEng by step
    liggghts = {int(m.group(1)): float(m.group(2))
                for m in re.finditer(r"^\s+(\d+)\s+\d+\s+(\S+)\s+\S+\s*$", log, re.M)}
    common = sorted(k for k in liggghts if k in grainflow and k > 0)
    if not common: sys.exit(f"no common kinetic-energy samples (see log.liggghts.{p}, gf_out/)")
    worst = 0.0
    print(f"kinetic energy, LIGGGHTS on {p} rank(s):\n  step   grainflow KE [J]   LIGGGHTS KE [J]   difference")
    for k in common:
        d = grainflow[k] / liggghts[k] - 1.0
        worst = max(worst, abs(d))
        print(f"  {k:5d}   {grainflow[k]:.4e}         {liggghts[k]:.4e}        {100 * d:+.1f} %")
    print(f"  largest difference {100 * worst:.1f} % (tolerance {100 * tolerance:.0f} %)")
    ours = [float(x) for x in open(f"grainflow_ns.{p}")]
    theirs = [float(x) for x in open(f"liggghts_ns.{p}")]
    print(f"grainflow ({p} thread(s)): fastest {min(ours):.1f}, median {statistics.median(ours):.1f} ns per particle-step ({len(ours)} rounds)")
    print(f"LIGGGHTS ({p} rank(s)):   fastest {min(theirs):.1f}, median {statistics.median(theirs):.1f} ns per particle-step")
    print(f"grainflow is {min(theirs) / min(ours):.2f} x faster than LIGGGHTS (fastest rounds; "
          f"medians: {statistics.median(theirs) / statistics.median(ours):.2f} x)")
    print(f"result settled_bed procs={p} peer={min(theirs):.6g} grainflow={min(ours):.6g} "
          f"peer_median={statistics.median(theirs):.6g} grainflow_median={statistics.median(ours):.6g}")
    try:
        ranks = [float(x) for x in open(f"grainflow_mpi_ns.{p}")]
        print(f"grainflow ({p} MPI ranks x 1 thread): fastest {min(ranks):.1f}, median {statistics.median(ranks):.1f} ns per particle-step")
        print(f"result settled_bed_mpi procs={p} peer={min(theirs):.6g} grainflow={min(ranks):.6g} "
              f"peer_median={statistics.median(theirs):.6g} grainflow_median={statistics.median(ranks):.6g}")
    except FileNotFoundError:
        pass
    print(f"check settled_bed_kinetic_energy procs={p} value={worst:.6g} tolerance={tolerance} "
          f"pass={int(worst <= tolerance)} steps={max(common)}")
PY
