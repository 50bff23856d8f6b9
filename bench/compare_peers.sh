#!/usr/bin/env bash
# grainflow against the codes a user would otherwise run, on the same machine in one run:
#   - DEM settled bed (15,000 spheres): LIGGGHTS 3.8 on 1 process and 2 MPI ranks, against
#     grainflow's BM_DemSettledBed on 1 and 2 threads (bench/liggghts_settled_bed.sh);
#   - coupled bubbling bed (24,750 spheres): DPMFoam on its Goldschmidt tutorial, 1 process and 2
#     ranks, against cases/cfddem_bubbling_fluidised_bed.yaml on 1 and 2 threads and on 2 MPI ranks,
#     all from the same particle positions at rest (bench/dpmfoam_goldschmidt.sh,
#     bench/cfddem_fluidised_bed.sh);
#   - lid-driven cube 64^3 at Re 100: icoFoam (PISO, GAMG) against grainflow's fluid, one process /
#     one thread each (bench/icofoam_cube.sh).
# In each pair the two codes alternate. It prints one table (markdown): per problem and process
# count the peer's figure, grainflow's, their ratio (peer / grainflow: how many times faster
# grainflow is) and whether its speed target is met; then the checks that both codes solved
# the same problem, each with its tolerance and pass / fail. Progress goes to stderr, the table to
# stdout; the work directory keeps every log.
#
#   bash bench/compare_peers.sh [--quick] [--only settled_bed,bubbling_bed,cube]
#
# --quick: fewer rounds and shorter windows; under 15 minutes on an idle 2-core machine, the
# installation of the peers and the bubbling bed's spin-up included. The full mode takes about
# 30 minutes there. --only: a comma-separated subset of the three problems.
#
# Same-problem checks (tolerances and why):
#   - settled bed: the kinetic energy of both codes every 500 steps from the same positions, within
#     10 % (bench/liggghts_settled_bed.sh: the walls' stiffness is the one difference left);
#   - bubbling bed: both codes start from the same positions (grainflow's bed after a spin-up to
#     0.35 s, the particles and the fluid at rest, the full inlet velocity at once) and their mean
#     pressure drop over the bed from a tenth of DPMFoam's window to its end must agree within 15 %:
#     the codes differ in the void fraction (grainflow divides each sphere among the cells it
#     overlaps, DPMFoam puts it in the cell of its centre) and in the gas viscosity (the tutorial's
#     nu = 1e-5 m2/s, 1.2e-5 Pa s, against the case file's 1.8e-5 Pa s of air; the viscous Ergun
#     term is about a seventh of the drag of a packed bed here, so this alone moves the drop by
#     about 5 %). The bed's weight per area is printed beside it: at rest under the full inlet
#     velocity the drop exceeds it (the bed is about to lift), so it is a scale, not the reference.
#     The particle counts must be equal. The DEM steps per fluid step are shown, not checked: grainflow's are fixed by the
#     case (3), DPMFoam picks its own from its collision time (3 to 4), which makes it do more work.
#   - cube: the centreline profiles after the same number of steps from rest, within 0.02 of the lid
#     speed (bench/icofoam_cube.sh: twice the Ghia validation's tolerance for one code).
# Installs the peers from Debian if they are missing (liggghts, openfoam, openfoam-examples; needs
# root and apt). Needs a built grainflow (bash scripts/build.sh); GRAINFLOW and GRAINFLOW_BENCH
# name other executables. Work directory: $COMPARE_PEERS_DIR (default /tmp/grainflow_compare_peers);
# the bubbling bed's spin-up is kept there until the grainflow executable is newer.
# Timings are only as steady as the machine: run it on an otherwise idle one.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
quick=0
only=settled_bed,bubbling_bed,cube
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --only) [ $# -ge 2 ] || { echo "--only needs a list, e.g. --only cube" >&2; exit 2; }; only=$2; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "unknown argument '$1' (bash bench/compare_peers.sh [--quick] [--only settled_bed,bubbling_bed,cube])" >&2; exit 2 ;;
  esac
  shift
done
for name in ${only//,/ }; do
  case $name in settled_bed|bubbling_bed|cube) ;; *) echo "--only: unknown problem '$name' (settled_bed, bubbling_bed, cube)" >&2; exit 2 ;; esac
done
wanted() { [[ ,$only, == *,$1,* ]]; }

if [ "$quick" = 1 ]; then
  settled_rounds=2; settled_steps=1000                   # LIGGGHTS: 500 warm-up + 1000 timed steps
  bubbling_rounds=1; peer_window=0.002; grainflow_window=0.01  # s simulated (DPMFoam: 100 fluid steps)
  cube_rounds=1; cube_steps=50
else
  settled_rounds=5; settled_steps=2000
  bubbling_rounds=2; peer_window=0.01; grainflow_window=0.05
  cube_rounds=3; cube_steps=200
fi
spinup=0.35  # s: the bubbling bed's positions are taken after the inlet ramp (0.3 s)

export GRAINFLOW=${GRAINFLOW:-$here/build/grainflow}
export GRAINFLOW_BENCH=${GRAINFLOW_BENCH:-$here/build/bench/grainflow_bench}
for exe in "$GRAINFLOW" "$GRAINFLOW_BENCH"; do
  if [ ! -x "$exe" ]; then
    echo "no $exe: build grainflow first (bash scripts/build.sh)" >&2
    exit 1
  fi
done

# --- the peers, from Debian
tutorial=/usr/share/doc/openfoam-examples/examples/lagrangian/DPMFoam/Goldschmidt
missing=()
command -v liggghts >/dev/null || missing+=(liggghts)
{ command -v DPMFoam >/dev/null && command -v icoFoam >/dev/null; } || missing+=(openfoam)
[ -d "$tutorial" ] || missing+=(openfoam-examples)
command -v mpirun >/dev/null || missing+=(openmpi-bin)
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "missing ${missing[*]}: install them (sudo apt-get install ${missing[*]}) or run this as root" >&2
    exit 1
  fi
  echo "installing ${missing[*]} (Debian) ..." >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq "${missing[@]}" > /tmp/grainflow_compare_peers_apt.log 2>&1 ||
    { apt-get update -qq > /dev/null 2>&1 && apt-get install -y -qq "${missing[@]}" > /tmp/grainflow_compare_peers_apt.log 2>&1; } ||
    { echo "apt-get install ${missing[*]} failed (see /tmp/grainflow_compare_peers_apt.log)" >&2; exit 1; }
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work=${COMPARE_PEERS_DIR:-/tmp/grainflow_compare_peers}
mkdir -p "$work/bin"
# one copy of the executables for the whole run (a rebuild meanwhile changes nothing here); -p keeps
# their time, against which the kept spin-up is judged
cp -p "$GRAINFLOW" "$work/bin/grainflow"
cp -p "$GRAINFLOW_BENCH" "$work/bin/grainflow_bench"
export GRAINFLOW=$work/bin/grainflow GRAINFLOW_BENCH=$work/bin/grainflow_bench
results=$work/results.txt
: > "$results"
started=$(date +%s)
note() { echo "[$(date +%H:%M:%S), $(( $(date +%s) - started )) s] $*" >&2; }
# run_logged LOG COMMAND...: runs a bench script, its output into LOG, its result and check lines
# into the results file
run_logged() {
  local log=$1
  shift
  if ! "$@" > "$log" 2>&1; then
    tail -20 "$log" >&2
    echo "failed: $* (log: $log)" >&2
    exit 1
  fi
  grep -E '^(result|check) ' "$log" >> "$results" || true
}

if wanted settled_bed; then
  note "DEM settled bed: LIGGGHTS and grainflow, 1 and 2 processes, $settled_rounds round(s) ..."
  BENCH_DIR=$work/settled_bed run_logged "$work/settled_bed.log" \
    bash "$here/bench/liggghts_settled_bed.sh" "$settled_rounds" "$settled_steps" 1 2
fi

if wanted bubbling_bed; then
  positions=$work/bubbling_bed/spinup_$spinup/particles_000001.vtu
  for round in $(seq "$bubbling_rounds"); do
    for p in 1 2; do
      spin=""
      [ -f "$positions" ] || spin=" (first the untimed spin-up to $spinup s, 2 to 5 minutes)"
      note "bubbling bed, round $round: grainflow on $p thread(s), $grainflow_window s from rest$spin ..."
      BENCH_DIR=$work/bubbling_bed run_logged "$work/bubbling_grainflow_$p.log" \
        bash "$here/bench/cfddem_fluidised_bed.sh" "$p" "$grainflow_window" "$spinup" rest
      if [ "$p" -gt 1 ]; then
        note "bubbling bed, round $round: grainflow on $p MPI ranks, $grainflow_window s from rest ..."
        BENCH_DIR=$work/bubbling_bed run_logged "$work/bubbling_grainflow_mpi_$p.log" \
          bash "$here/bench/cfddem_fluidised_bed.sh" 1 "$grainflow_window" "$spinup" rest "$p"
      fi
      note "bubbling bed, round $round: DPMFoam on $p process(es), $peer_window s from the same positions ..."
      BENCH_DIR=$work/dpmfoam_$p run_logged "$work/bubbling_dpmfoam_$p.log" \
        bash "$here/bench/dpmfoam_goldschmidt.sh" "$peer_window" "$positions" "$p"
    done
  done
fi

if wanted cube; then
  note "lid-driven cube 64^3: icoFoam and grainflow, $cube_steps steps, $cube_rounds round(s) ..."
  BENCH_DIR=$work/cube run_logged "$work/cube.log" bash "$here/bench/icofoam_cube.sh" "$cube_rounds" "$cube_steps" 64
fi
note "done"

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
version=$(git -C "$here" describe --always --dirty 2>/dev/null || echo unknown)
mode=$([ "$quick" = 1 ] && echo "--quick" || echo "full")
python3 - "$results" "$here/cases/cfddem_bubbling_fluidised_bed.yaml" "$peer_window" \
  "$(date +%Y-%m-%d)" "$cpu" "$(nproc)" "$version" "$mode" <<'PY'
import csv, math, statistics, sys
from collections import defaultdict
import yaml

results_path, case_path, peer_window = sys.argv[1], sys.argv[2], float(sys.argv[3])
date, cpu, cores, version, mode = sys.argv[4:9]

def parse(line):
    kind, name, *pairs = line.split()
    return kind, name, dict(p.split("=", 1) for p in pairs)

results = defaultdict(list)  # (name, procs) -> [fields]
checks = []
for line in open(results_path):
    kind, name, fields = parse(line)
    if kind == "result":
        procs = fields.get("procs") or fields.get("threads")
        results[(name, procs)].append(fields)
    else:
        checks.append((name, fields))

print(f"grainflow {version} against its peers, {date}, {cpu} ({cores} cores), bench/compare_peers.sh {mode}")
print()
print("| problem | processes | peer | peer's figure | grainflow's figure | ratio | target | met |")
print("|---|---|---|---|---|---|---|---|")
rows_out = []
for procs, target in (("1", 3.0), ("2", 2.5)):
    for r in results.get(("settled_bed", procs), []):
        ratio = float(r["peer"]) / float(r["grainflow"])
        print(f"| DEM settled bed, 15,000 spheres (ns per particle-step) | {procs} | LIGGGHTS 3.8 | "
              f"{float(r['peer']):.1f} | {float(r['grainflow']):.1f} | {ratio:.2f} | >= {target:g} | "
              f"{'yes' if ratio >= target else 'no'} |")
for r in results.get(("settled_bed_mpi", "2"), []):
    ratio = float(r["peer"]) / float(r["grainflow"])
    print(f"| DEM settled bed, 15,000 spheres, grainflow on MPI ranks (ns per particle-step) | 2 | LIGGGHTS 3.8 | "
          f"{float(r['peer']):.1f} | {float(r['grainflow']):.1f} | {ratio:.2f} | >= 2.5 | "
          f"{'yes' if ratio >= 2.5 else 'no'} |")
# Bubbling bed: each code's fastest round
bubbling = {}
for procs in ("1", "2"):
    peer = results.get(("bubbling_dpmfoam", procs), [])
    ours = results.get(("bubbling_grainflow", procs), [])
    if not peer or not ours:
        continue
    best_peer = min(peer, key=lambda r: float(r["s_per_s"]))
    best_ours = min(ours, key=lambda r: float(r["s_per_s"]))
    bubbling[procs] = (peer[-1], ours[-1])
    ratio = float(best_peer["s_per_s"]) / float(best_ours["s_per_s"])
    print(f"| coupled bubbling bed, 24,750 spheres (s wall per simulated s) | {procs} | DPMFoam (OpenFOAM v1912) | "
          f"{float(best_peer['s_per_s']):.0f} | {float(best_ours['s_per_s']):.0f} | {ratio:.1f} | >= 50 | "
          f"{'yes' if ratio >= 50 else 'no'} |")
mpi_peer, mpi_ours = results.get(("bubbling_dpmfoam", "2"), []), results.get(("bubbling_grainflow_mpi", "2"), [])
if mpi_peer and mpi_ours:
    best_peer = min(float(r["s_per_s"]) for r in mpi_peer)
    best_ours = min(float(r["s_per_s"]) for r in mpi_ours)
    ratio = best_peer / best_ours
    print(f"| coupled bubbling bed, 24,750 spheres, grainflow on MPI ranks (s wall per simulated s) | 2 | "
          f"DPMFoam (OpenFOAM v1912) | {best_peer:.0f} | {best_ours:.0f} | {ratio:.1f} | >= 50 | "
          f"{'yes' if ratio >= 50 else 'no'} |")
for r in results.get(("cube", "1"), []):
    ratio = float(r["peer"]) / float(r["grainflow"])
    print(f"| lid-driven cube 64^3, Re 100 (ns per cell-step; s per step) | 1 | icoFoam (OpenFOAM v1912) | "
          f"{float(r['peer']):.0f}; {float(r['peer_s_per_step']):.3f} | "
          f"{float(r['grainflow']):.0f}; {float(r['grainflow_s_per_step']):.4f} | {ratio:.1f} | >= 20 | "
          f"{'yes' if ratio >= 20 else 'no'} |")
print()
print("Figures: the fastest of the alternating rounds of each code, set-up and output not counted. "
      "Processes: MPI ranks of the peer, OpenMP threads of grainflow (the row 'grainflow on MPI ranks': "
      "MPI ranks x 1 thread, the run's wall time per particle-step with its warm-up steps).")

# --- same-problem checks
print()
print("| same-problem check | value | tolerance | result |")
print("|---|---|---|---|")
def row(what, value, tolerance, passed):
    print(f"| {what} | {value} | {tolerance} | {'pass' if passed else 'FAIL'} |")
for name, f in checks:
    if name == "settled_bed_kinetic_energy":
        row(f"settled bed: kinetic energy, grainflow vs LIGGGHTS on {f['procs']} rank(s), every 500 of "
            f"{f['steps']} steps (largest relative difference)",
            f"{100 * float(f['value']):.1f} %", f"{100 * float(f['tolerance']):.0f} %", f["pass"] == "1")
if bubbling:
    case = yaml.safe_load(open(case_path))
    insertion = case["insertion"][0]
    glass = next(m for m in case["materials"] if m["name"] == insertion["material"])
    d = insertion["size"]["diameter"]
    lo, hi = case["domain"]["min"], case["domain"]["max"]
    area = (hi[0] - lo[0]) * (hi[1] - lo[1])
    g = -case["gravity"][2]
    # buoyant weight of the bed per cross-section: N pi/6 d^3 (rho_p - rho_f) g / A
    weight = insertion["count"] * math.pi / 6 * d ** 3 * (glass["density"] - case["fluid"]["density"]) * g / area
    def mean_drop(path):  # mean pressure drop over the peer's window after its first tenth
        rows = [(float(r[0]), float(r[1])) for r in list(csv.reader(open(path)))[1:]]
        values = [p for t, p in rows if 0.1 * peer_window < t <= peer_window * (1 + 1e-9)]
        if not values:
            sys.exit(f"{path}: no pressure drop in ({0.1 * peer_window:g}, {peer_window:g}] s")
        return statistics.mean(values)
    for procs, (peer, ours) in sorted(bubbling.items()):
        a, b = mean_drop(ours["pressure_csv"]), mean_drop(peer["pressure_csv"])
        difference = abs(a / b - 1)
        row(f"bubbling bed: pressure drop from the same positions at rest, t = {0.1 * peer_window:g} ... "
            f"{peer_window:g} s, grainflow {a:.0f} Pa vs DPMFoam {b:.0f} Pa on {procs} process(es) "
            f"(bed weight / area {weight:.0f} Pa)", f"{100 * difference:.1f} %", "15 %", difference <= 0.15)
    for procs, (peer, ours) in sorted(bubbling.items()):
        row(f"bubbling bed: particles, grainflow vs DPMFoam on {procs} process(es)",
            f"{ours['particles']} / {peer['particles']}", "equal", ours["particles"] == peer["particles"])
    peer, ours = bubbling[min(bubbling)]
    print(f"| bubbling bed (note, not a check): DEM steps per fluid step, grainflow {ours['substeps']} (fixed), "
          f"DPMFoam {float(peer['substeps']):.2f} (from its collision time) | | | |")
for name, f in checks:
    if name == "cube_profiles":
        row(f"cube: centreline profiles u(y) and v(x) after {f['steps']} steps (t = {f['time']} s), "
            f"largest difference / lid speed", f"{float(f['value']):.4f}", f["tolerance"], f["pass"] == "1")
PY
