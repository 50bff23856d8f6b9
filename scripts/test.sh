#!/usr/bin/env bash
# One command from a fresh clone to a passing test suite: setup, build, run every test through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# warnings are errors here (and so in CI): the tree builds without one with GCC 12
GRAINFLOW_WERROR=${GRAINFLOW_WERROR:-ON} bash scripts/build.sh
BUILD_DIR=${GRAINFLOW_BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 1200
