#!/usr/bin/env bash
# Layering of the subsystems (docs/architecture.md): the DEM and the fluid meet only in src/coupling
# and src/app, and the shared base (src/core, src/io) knows no solver part. Lists every #include
# that crosses a forbidden boundary as file:line and fails if there is one.
#   usage: tests/layering_check.sh [source root]   (default: the checkout holding this script)
set -euo pipefail
root=${1:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"}
cd "$root"
[[ -d src ]] || { echo "layering_check: no src/ under '$root'" >&2; exit 2; }

# directory under src/ -> the subsystems it may not include (by the first part of the include path)
declare -A forbidden=(
  [core]="dem fluid coupling app"
  [io]="dem fluid coupling app"
  [dem]="fluid coupling app"
  [fluid]="dem coupling app"
  [coupling]="app"
  [parallel]="dem fluid coupling app"
  [resolved]="coupling app"
  [vof]="dem coupling app"
)

violations=0
for dir in "${!forbidden[@]}"; do
  [[ -d src/$dir ]] || continue
  pattern=$(tr ' ' '|' <<<"${forbidden[$dir]}")
  # '#include "dem/..."' or '#include <dem/...>', with any spacing after '#'
  while IFS= read -r hit; do
    [[ -n $hit ]] || continue
    file=${hit%%:*}
    rest=${hit#*:}
    line=${rest%%:*}
    target=$(sed -E 's/.*#[[:space:]]*include[[:space:]]*["<]([^">]*)[">].*/\1/' <<<"${rest#*:}")
    echo "$file:$line: includes $target (src/$dir may not include ${forbidden[$dir]// /\/, }/)"
    violations=$((violations + 1))
  done < <(grep -rnE --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.in' \
             "^[[:space:]]*#[[:space:]]*include[[:space:]]*[\"<]($pattern)/" "src/$dir" | sort || true)
done

if ((violations > 0)); then
  echo "layering_check: $violations include(s) cross a subsystem boundary; move the shared code to src/core or" \
       "src/io, or let src/coupling or src/app bring the parts together" >&2
  exit 1
fi
echo "layering_check: src/core, src/io, src/dem, src/fluid, src/coupling and src/vof include only what their layer may"
