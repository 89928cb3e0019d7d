#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Two morphMesh binaries (say the last commit's and a change's) on the same -variants table,
# alternating, so that both see the same machine load: per run the first row, the median of
# the later rows (combine + check + write) and the median of their check, from the JSON
# timings. Uses the case and table variant_speed.sh leaves in its -out directory.
#
#   variant_rows_ab.sh OLD_MORPHMESH NEW_MORPHMESH [-dir DIR] [-runs N]
#
# DIR: variant_speed.sh's output (default build/bench/variant_speed: run it first); N: pairs
# of runs (default 3). Prints one line per run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
usage() { echo "usage: variant_rows_ab.sh OLD_MORPHMESH NEW_MORPHMESH [-dir DIR] [-runs N]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
old=$(realpath "$1") new=$(realpath "$2")
shift 2
dir=$root/build/bench/variant_speed
runs=3
while [[ $# -gt 0 ]]; do
    case $1 in
        -dir) dir=$2; shift 2 ;;
        -runs) runs=$2; shift 2 ;;
        *) usage ;;
    esac
done
if [ ! -x "$old" ] || [ ! -x "$new" ]; then
    echo "variant_rows_ab.sh: both binaries must be executable" >&2
    exit 2
fi
if [ ! -f "$dir/doe.csv" ] || [ ! -d "$dir/case" ]; then
    echo "variant_rows_ab.sh: no case and doe.csv in $dir (run benchmarks/morph/variant_speed.sh)" >&2
    exit 2
fi
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
json=$(mktemp)
trap 'rm -f "$json"' EXIT
for ((i = 1; i <= runs; ++i)); do
    for which in old new; do
        binary=$old
        [ "$which" = new ] && binary=$new
        "$binary" -case "$dir/case" -variants "$dir/doe.csv" -json "$json" >/dev/null 2>&1 ||
            { echo "variant_rows_ab.sh: $binary -variants failed" >&2; exit 1; }
        /usr/bin/python3 - "$json" "$which" <<'PY'
import json, statistics, sys
rows = json.load(open(sys.argv[1]))["rows"]
row = lambda r: sum(r["timings"][k] for k in ("combine", "check", "write"))
later = rows[1:]
print(f"{sys.argv[2]}: first row {row(rows[0]):.3f} s, later rows median "
      f"{statistics.median(map(row, later)):.3f} s, their check median "
      f"{statistics.median(r['timings']['check'] for r in later):.3f} s")
PY
    done
done
