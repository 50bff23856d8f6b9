#!/usr/bin/env bash
# Installs the dependencies (Debian packages) and builds grainflow in Release into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
BUILD_DIR=${GRAINFLOW_BUILD_DIR:-build}
# GRAINFLOW_WERROR=ON (scripts/test.sh): compiler warnings are errors (GCC 12). Unset, the build
# directory keeps its setting, so the demo and the tests share one build without recompiling.
werror=()
if [ -n "${GRAINFLOW_WERROR:-}" ]; then werror=(-DGRAINFLOW_WERROR="$GRAINFLOW_WERROR"); fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "${werror[@]}"
cmake --build "$BUILD_DIR" -j "$(nproc)"
