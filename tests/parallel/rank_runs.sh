# Helpers of the tests that run cases through `grainflow run` on several MPI ranks (sourced by
# fluid_ranks_test.sh and coupled_ranks_test.sh after they set grainflow, mpiexec and work).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMPI_MCA_mpi_yield_when_idle=1

run() {  # run RANKS CASE OUTPUT [options]
  local ranks=$1 case=$2 out=$3
  shift 3
  "$mpiexec" --oversubscribe -n "$ranks" "$grainflow" run "$case" --quiet --threads 1 --output "$out" "$@"
}

# close A B TOLERANCE WHAT [SKIP]: every number of every monitor CSV agrees between the runs in
# directories A and B (rows of the same times: a run restarted into a new directory has the rows
# from its restart on), relative to the largest magnitude among the columns of the same unit in
# that file (a vector's components share a scale; a component that is round-off around zero is
# compared with the vector's size). SKIP: a Python regular expression; files or columns whose name
# matches it are not compared.
close() {
  python3 - "$1" "$2" "$3" "$4" "${5:-^$}" <<'PY'
import csv, glob, os, re, sys
a, b, tol, what, skip = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], re.compile(sys.argv[5])
worst, where = 0.0, ""
for fa in sorted(glob.glob(os.path.join(a, "*.csv"))):
    if skip.search(os.path.basename(fa)):
        continue
    fb = os.path.join(b, os.path.basename(fa))
    ra, rb = list(csv.reader(open(fa))), list(csv.reader(open(fb)))
    times_b = {row[0]: row for row in rb[1:]}
    pairs = [(row, times_b[row[0]]) for row in ra[1:] if row[0] in times_b]
    if not pairs or len(pairs) < len(rb) - 1:
        sys.exit(f"FAIL: {what}: {os.path.basename(fa)}: {len(pairs)} rows of the same times")
    unit = lambda c: re.sub(r"^.*\[", "[", ra[0][c])
    scale = {}
    for c in range(1, len(ra[0])):
        m = max(abs(float(r[c])) for r in ra[1:])
        scale[unit(c)] = max(scale.get(unit(c), 0.0), m)
    for row_a, row_b in pairs:
        for c in range(1, len(ra[0])):
            if skip.search(ra[0][c]):
                continue
            d = abs(float(row_a[c]) - float(row_b[c])) / max(scale[unit(c)], 1e-300)
            if d > worst:
                worst, where = d, f"{os.path.basename(fa)} column {ra[0][c]} at t = {row_a[0]}"
if worst > tol:
    sys.exit(f"FAIL: {what}: largest relative difference {worst:.2e} ({where}) > {tol}")
print(f"ok: {what}: largest relative difference {worst:.2e} ({where or 'none'})")
PY
}
