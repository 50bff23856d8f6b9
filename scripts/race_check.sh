#!/usr/bin/env bash
# Data races in the threaded code: the test suite under ThreadSanitizer with LLVM's Archer, the
# OMPT tool of LLVM's OpenMP runtime that tells ThreadSanitizer what OpenMP's barriers, reductions
# and region ends order (the runtime is not instrumented: without Archer, ThreadSanitizer does not
# see the order its barriers give, and may report races that cannot happen). Debian's clang++-14
# and libomp-14 (GCC's libgomp has no such tool), -O1 -g, in build-race/ (GRAINFLOW_RACE_DIR); the
# vector clones are off under Clang (core/cpu_features.hpp), so the SSE2 paths are the ones
# checked. The tests run on OMP_NUM_THREADS (default 2) threads, or the team sizes they set
# themselves (2-4); the bubbling bed (cases/cfddem_bubbling_fluidised_bed.yaml) runs 50 coupling
# steps on 2 threads. A race fails the test or run that reached it (halt_on_error). Not part of CI
# (~10 min on 2 cores: build ~5, tests ~5). Extra arguments go to ctest, e.g. `-R DemSystem`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh clang-14 libomp-14-dev
DIR=${GRAINFLOW_RACE_DIR:-build-race}
ARCHER=/usr/lib/llvm-14/lib/libarcher.so
[ -f "$ARCHER" ] || { echo "race_check: $ARCHER missing (package libomp-14-dev)" >&2; exit 1; }
TSAN="-fsanitize=thread"  # compiler and linker need it both
cmake -S . -B "$DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGRAINFLOW_BUILD_BENCH=OFF \
  -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="$TSAN -fno-omit-frame-pointer" -DCMAKE_EXE_LINKER_FLAGS="$TSAN"
cmake --build "$DIR" -j "$(nproc)"
export OMP_TOOL_LIBRARIES=$ARCHER OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
# ignore_noninstrumented_modules: libomp itself is not instrumented (Archer's advice)
TSAN_DEFAULTS="ignore_noninstrumented_modules=1 halt_on_error=1 history_size=4"
export TSAN_OPTIONS=${TSAN_OPTIONS:-$TSAN_DEFAULTS}
# Archer must be loaded (libomp loads it at its first parallel region; OMP_TOOL_LIBRARIES names
# it); the probe checks that it was.
probe=$(ARCHER_OPTIONS=verbose=1 "$DIR/tests/test_core" --gtest_filter='Parallel.*' 2>&1 || true)
grep -q "Archer detected OpenMP application with TSan" <<< "$probe" ||
  { echo "race_check: libomp did not load Archer ($ARCHER)" >&2; exit 1; }
# The issue-6 bed at full size on 2 threads (its fluid, pressure and coupling teams are sized by
# the grid and the particle count, larger than the tests' own): 50 coupling steps from insertion.
"$DIR/grainflow" run cases/cfddem_bubbling_fluidised_bed.yaml --end-time 0.001 --threads 2 \
  --output "$DIR/race_bubbling_bed" --overwrite --quiet
# The quick validation suite runs on one thread (`validate --threads 1`): nothing to race, and
# ~15 min under ThreadSanitizer; left out unless ctest arguments are given.
[ $# -gt 0 ] || set -- -E QuickSuiteOfTheRepositoryPasses
ctest --test-dir "$DIR" --output-on-failure -j "$(nproc)" --timeout 3600 "$@"
echo "race_check: no data race reported"
