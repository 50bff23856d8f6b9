#!/usr/bin/env bash
# One command from a fresh clone to a finished demo run: setup, build, run the main demo case.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${GRAINFLOW_BUILD_DIR:-build}
CASE=${1:-cases/falling_spheres.yaml}
"$BUILD_DIR/grainflow" run "$CASE" --overwrite
