#!/usr/bin/env bash
# The tree describes the code, not how it was developed: README.md, docs/, cases/, src/, bench/,
# tests/, validation/ and scripts/ must not mention numbered development sessions or rounds
# ("session 12", "sessions 28-47", "round 2"), tracker issues as history ("issue 6"), md5 sums of
# past runs, or the removed performance history (git log keeps the history). Lists every such line as file:line and fails if there is
# one. This script is the one file allowed to name the patterns.
#   usage: tests/tree_hygiene.sh [source root]   (default: the checkout holding this script)
set -euo pipefail
root=${1:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"}
cd "$root"
[[ -f README.md && -d src ]] || { echo "tree_hygiene: no README.md and src/ under '$root'" >&2; exit 2; }

paths=(README.md)
for dir in docs cases src bench tests validation scripts; do
  [[ -e $dir ]] && paths+=("$dir")
done
self=tests/tree_hygiene.sh
# \b before "session"/"round": "sessions 3" and "round 2" count, "around 2 mm" does not.
pattern='\b(sessions?[ -]+[0-9]+|(development )?rounds? [0-9]+\b|issues? #?[0-9]+)|md5|performance-history'

hits=$(grep -rInE -i "$pattern" "${paths[@]}" | grep -v "^$self:" || true)
if [[ -n $hits ]]; then
  echo "$hits"
  echo "tree_hygiene: $(wc -l <<<"$hits") line(s) above mention a development session or round, a tracker issue, an md5 sum" \
    "or the performance history; say what the code does and why instead (git log keeps the history)." >&2
  exit 1
fi
echo "tree_hygiene: clean (${paths[*]})"
