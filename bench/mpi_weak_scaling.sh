#!/usr/bin/env bash
# Weak scaling of the DEM over MPI ranks: measured on this machine at 1 and 2 ranks, modelled to
# 1,024 ranks (docs/parallel.md explains the model).
#
# The problem: a dense bed (jittered lattice at solid fraction 0.5, spheres d = 2 mm, Hertz-Mindlin
# with history), periodic in x and y with a floor, N particles per rank: one rank owns an
# L x L x H box; two ranks own two such boxes side by side ([2, 1, 1], each with two faces shared
# across the periodic x direction). Each run is one thread per rank; the two rank counts alternate.
# From the runs it takes
#   c   - the cost of one particle-step on one rank (ns; force loop and integration, the phases
#         that grow with the ghosts; list builds, with the migration and ghost exchange, are
#         amortised over many steps in a settled bed),
#   g   - ghosts per owned particle for one shared face, and the cost factor k of a ghost in the
#         force loop relative to an owned particle,
#   the communication time per step for two bed sizes, from which the latency per message (alpha)
#         and the time per byte of the ghost updates (1 / bandwidth) follow,
#   the time of one allreduce (the rebuild vote) on 2 ranks.
# It prints them and the modelled efficiency E(P) = T(1) / T(P) for P = 2 ... 1,024 ranks at
# 1e5 particles per rank, with the term that limits it.
#
#   usage: bash bench/mpi_weak_scaling.sh [GRAINFLOW] [PARTICLES_PER_RANK] [STEPS] [ROUNDS]
#   (defaults: build/grainflow, 20000, 1000, 2)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
grainflow=${1:-$here/build/grainflow}
n=${2:-20000}
steps=${3:-1000}
rounds=${4:-2}
work=$(mktemp -d /tmp/grainflow_weak_scaling.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
command -v mpirun >/dev/null || { echo "mpirun not found (apt-get install openmpi-bin)" >&2; exit 2; }

# A box of `count` spheres per rank (d = 2 mm on a 2.2 mm lattice, 0.5 solid fraction after the
# jitter); side L from the count, height ~ L.
write_case() {  # write_case FILE COUNT RANKS
  python3 - "$1" "$2" "$3" "$steps" <<'PY'
import math, sys
path, count, ranks, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
d, fraction = 0.002, 0.45
side = (count * math.pi / 6 * d**3 / fraction) ** (1 / 3)
lx, ly, h = side * ranks, side, side
open(path, "w").write(f"""case: {{name: weak_scaling}}
domain: {{min: [0, 0, 0], max: [{lx:.6g}, {ly:.6g}, {h * 1.1:.6g}], periodic: [1, 1, 0], decomposition: [{ranks}, 1, 1]}}
gravity: [0, 0, -9.81]
time: {{end: {steps * 1e-5:.6g}, dem_step: 1.0e-5}}
materials:
  - {{name: glass, density: 2500.0, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}
contact: {{law: hertz_mindlin, restitution: 0.5, friction: 0.5}}
walls:
  - {{type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: glass}}
insertion:
  - {{type: random_packing, material: glass, min: [0, 0, 0], max: [{lx:.6g}, {ly:.6g}, {h:.6g}],
     count: {count * ranks}, seed: 3, size: {{diameter: {d}}}}}
""")
PY
}

# Runs a case on RANKS ranks; prints "wall comm ghosts owned" (rank 0's phases).
measure() {  # measure CASE RANKS
  local out
  out=$(mpirun --oversubscribe -n "$2" "$grainflow" run "$1" --threads 1 --overwrite --output "$work/out" 2>&1)
  python3 - "$out" <<'PY'
import re, sys
text = sys.argv[1]
def phase(name):
    m = re.search(rf"^{name}\s+([0-9.]+)", text, re.M)
    return float(m.group(1)) if m else 0.0
m = re.search(r"owns (\d+) particles and holds (\d+) ghosts", text)
owned, ghosts = (int(m.group(1)), int(m.group(2))) if m else (0, 0)
setup = 0.0
print(phase("total"), phase("communication"), ghosts, owned, phase("contacts") + phase("integration"))
PY
}

small=$((n / 8))
for size in "$n" "$small"; do
  for ranks in 1 2; do write_case "$work/case_${size}_$ranks.yaml" "$size" "$ranks"; done
done
echo "DEM weak scaling: $n particles per rank ($small for the second bed size), $steps steps, $rounds round(s), 1 thread per rank"
results=$work/results.txt
: >"$results"
for ((r = 1; r <= rounds; ++r)); do
  for size in "$n" "$small"; do
    for ranks in 1 2; do
      echo "$size $ranks $(measure "$work/case_${size}_$ranks.yaml" "$ranks")" >>"$results"
    done
  done
done

python3 - "$results" "$steps" "$n" <<'PY'
import math, statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
steps, n = int(sys.argv[2]), int(sys.argv[3])
def median(size, ranks, column):
    return statistics.median(float(r[column]) for r in rows if int(r[0]) == size and int(r[1]) == ranks)
sizes = sorted({int(r[0]) for r in rows}, reverse=True)
big, small = sizes[0], sizes[-1]
# columns: size ranks wall comm ghosts owned compute
c1 = median(big, 1, 6) / (big * steps) * 1e9               # ns per particle-step, force loop and integration, 1 rank
wall1 = median(big, 1, 2) / (big * steps) * 1e9
ghosts2, owned2 = median(big, 2, 4), median(big, 2, 5)
g = ghosts2 / owned2 / 2.0                                  # ghosts per owned particle and shared face
compute2 = median(big, 2, 6) / (owned2 * steps) * 1e9
k_measured = (compute2 / c1 - 1.0) / (2.0 * g) if g > 0 else 0.0   # cost of a ghost relative to an owned particle
# (a ghost's row is swept like an owned particle's: below 1 the measurement is within the noise of
# the two runs, and the model takes 1)
k = max(k_measured, 1.0)
comm_big = median(big, 2, 3) / steps                        # s per step
comm_small = median(small, 2, 3) / steps
bytes_big, bytes_small = 72.0 * median(big, 2, 4), 72.0 * median(small, 2, 4)
per_byte = max(0.0, (comm_big - comm_small) / max(bytes_big - bytes_small, 1.0))
fixed = max(0.0, comm_small - per_byte * bytes_small)       # latency part per step: 1 update message + 1 allreduce
alpha_measured = fixed / 2.0
alpha = max(alpha_measured, 1e-6)  # (1 us, a shared-memory MPI latency, when the fit's intercept is lost in the noise)
print()
print("measured (rank 0 of each run; medians)")
print(f"  c    cost of a particle-step on one rank        {c1:8.1f} ns (all phases: {wall1:.1f} ns)")
print(f"  g    ghosts per owned particle and shared face  {g:8.4f}  (N = {big} per rank)")
print(f"  k    cost of a ghost / an owned particle        {k_measured:8.2f}  (model: {k:.2f})")
print(f"       communication per step on 2 ranks          {comm_big * 1e6:8.1f} us (N = {big}), {comm_small * 1e6:.1f} us (N = {small})")
print(f"  a    latency per message or allreduce step      {alpha_measured * 1e6:8.2f} us  (model: {alpha * 1e6:.2f} us)")
print(f"  b    ghost update time per byte                 {per_byte * 1e9:8.3f} ns/B ({1e-9 / per_byte if per_byte > 0 else float('inf'):.2f} GB/s;")
print("       the communication phase includes waiting for the slower rank)")
print()
print("model (docs/parallel.md): T(P) = N c (1 + k g F(P)) + 26-neighbour updates + allreduces,")
print("  F(P): shared faces of a cubic box in a 3-D layout (6 once every axis is split, plus edges),")
print("  updates: F(P) messages of g N 72 bytes, allreduces: 3 per step of a log2(P) steps each")
target = 100000
g_target = g * (n / target) ** (1.0 / 3.0)                  # a face's share falls as N^(-1/3)
print(f"  at N = {target} per rank: g = {g_target:.4f} per face")
print(f"  {'P':>5} {'faces':>5} {'compute ms':>10} {'ghosts ms':>9} {'update ms':>9} {'allreduce ms':>12} {'E(P)':>6}")
base = target * c1 * 1e-9
worst = None
for p in [2, 8, 64, 512, 1024]:
    layout = [1, 1, 1]
    for i in range(int(round(math.log2(p)))): layout[i % 3] *= 2
    faces = sum(2 for a in layout if a > 1)
    edges = sum(1 for a in range(3) for b in range(a + 1, 3) if layout[a] > 1 and layout[b] > 1) * 4
    ghost_fraction = g_target * faces + edges * g_target ** 2
    t_ghost = base * k * ghost_fraction
    t_update = (faces + edges) * alpha + per_byte * 72.0 * ghost_fraction * target
    t_reduce = 3 * alpha * math.log2(p)
    e = base / (base + t_ghost + t_update + t_reduce)
    terms = {"ghost computation": t_ghost, "ghost updates": t_update, "allreduces": t_reduce}
    limit = max(terms, key=terms.get)
    print(f"  {p:>5} {faces:>5} {base * 1e3:10.3f} {t_ghost * 1e3:9.3f} {t_update * 1e3:9.3f} {t_reduce * 1e3:12.4f} {e:6.2f}  (largest: {limit})")
PY
