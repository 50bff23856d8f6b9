#!/usr/bin/env bash
# The test suite under AddressSanitizer and UndefinedBehaviorSanitizer (GCC, -O2 -g), with the
# standard library's own checks (_GLIBCXX_ASSERTIONS: vector/array indices against size()), in
# build-sanitize/ (GRAINFLOW_SANITIZE_DIR). Any out-of-bounds access, leak or undefined behaviour
# the tests reach fails the test that reached it (-fno-sanitize-recover: no error is only logged).
# Not part of CI: on 2 cores the build takes ~16-19 min and the suite ~10 min (the quick validation
# suite alone ~7 min). Extra arguments go to ctest, e.g. `-R Restart` or `-E QuickSuite`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
DIR=${GRAINFLOW_SANITIZE_DIR:-build-sanitize}
SANITIZE="-fsanitize=address,undefined"  # compiler and linker need the same list
FLAGS="$SANITIZE -fno-omit-frame-pointer -fno-sanitize-recover=undefined -D_GLIBCXX_ASSERTIONS"
cmake -S . -B "$DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGRAINFLOW_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="$SANITIZE"
cmake --build "$DIR" -j "$(nproc)"
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
  ctest --test-dir "$DIR" --output-on-failure -j "$(nproc)" --timeout 1800 "$@"
