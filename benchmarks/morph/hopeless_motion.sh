#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# How long does morphMesh take to refuse a motion that cannot be made valid, against one
# morph of the same case? OpenFOAM's channel395DFSEM tutorial (blockMesh, 1.9M cells): its
# bottom wall turned in its own plane about the y axis through its centre, every other
# patch (the cyclic sides, inlet, outlet, top wall) fixed. Turned 0.02 degrees the morph is
# valid (one morph: the reference time); turned 1 degree every step down to 1/64 of the
# motion folds cells where the turning wall meets the fixed sides, and the morph is refused.
#
# Usage: hopeless_motion.sh [-out DIR] [-morphMesh PATH] [-unlimited] [-results FILE |
#                           -no-results] [-help]
#   -out DIR         scratch case and logs (default build/bench/hopeless)
#   -morphMesh PATH  default build/release/applications/morphMesh/morphMesh
#   -unlimited       also run the refused motion with maxUntangleCells 1000000000 (every
#                    step's repair tried, as before the limit existed): about 14 minutes
#   -results FILE    write the table there; -no-results: nowhere. Default:
#                    benchmarks/results/hopeless_motion.md, written only with -unlimited
#
# Needs Debian's OpenFOAM v1912 (blockMesh) and its tutorials (openfoam-examples).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
foam_script_name=hopeless_motion.sh
# shellcheck source=scripts/openfoam/lib.sh
source "$root/scripts/openfoam/lib.sh"   # die, need_tool
# shellcheck source=benchmarks/results.sh
source "$root/benchmarks/results.sh"
results_init "$@"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

usage() { sed -n '3,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }

out="$root/build/bench/hopeless"
morph="$root/build/release/applications/morphMesh/morphMesh"
unlimited=0
while [[ $# -gt 0 ]]; do
    case $1 in
        -out) out=${2:?-out needs a directory}; shift 2 ;;
        -morphMesh) morph=${2:?-morphMesh needs a path}; shift 2 ;;
        -unlimited) unlimited=1; shift ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -h | -help | --help) usage; exit 0 ;;
        *) echo "$foam_script_name: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
done
[[ $morph == /* ]] || morph="$PWD/$morph"
[[ -x $morph ]] || die "no morphMesh at $morph (cmake --build build/release)"
[[ $unlimited == 1 ]] || results_partial "without -unlimited"
need_tool blockMesh
tutorial=/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/LES/channel395DFSEM
[[ -d $tutorial ]] || die "no $tutorial (apt-get install openfoam-examples)"

mkdir -p "$out"
out="$(cd "$out" && pwd)"
case_dir="$out/channel395DFSEM"
if [[ ! -f $case_dir/constant/polyMesh/owner ]]; then
    rm -rf "$case_dir"
    cp -r "$tutorial" "$case_dir"
    echo "$foam_script_name: blockMesh (1.9M cells, about 20 s)"
    (cd "$case_dir" && blockMesh >log.blockMesh 2>&1) || die "blockMesh failed: $case_dir/log.blockMesh"
fi

# morph_dict ANGLE [EXTRA]: the bottom wall turned ANGLE degrees (L = 2 pi, W = pi).
morph_dict() {
    cat >"$case_dir/system/morphDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
$2
boundary
{
    bottomWall { type rotate; origin (3.14159 0 1.5708); axis (0 1 0); angle $1; }
}
DICT
}

table="$out/table.md"
{
    echo "| run | exit | wall [s] | ratio to one morph | steps | untangle [s] | verdict |"
    echo "| --- | --- | --- | --- | --- | --- | --- |"
} >"$table"
reference=""
# run NAME ANGLE EXTRA: one morphMesh run (nothing kept: -noWrite is not an option, so a
# written result is removed again), a table row.
run() {
    local name=$1 angle=$2 extra=$3 start end code wall
    morph_dict "$angle" "$extra"
    echo "$foam_script_name: $name"
    start=$(date +%s.%N)
    code=0
    (cd "$case_dir" && "$morph" -json "$out/$name.json" >"$out/$name.log" 2>&1) || code=$?
    end=$(date +%s.%N)
    find "$case_dir" -maxdepth 1 -regex '.*/[0-9.e+-]+' ! -name 0 -exec rm -rf {} +
    wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
    [[ -n $reference ]] || reference=$wall
    local verdict steps untangle
    verdict=$(grep -m1 '^Error:' "$out/$name.log" | sed 's/^Error: //; s/ Nothing written.*//' || true)
    [[ -n $verdict ]] || verdict="written, $(grep -m1 -E '^(Mesh OK|Failed)' "$out/$name.log" || echo '?')"
    steps=$(/usr/bin/python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["steps"]))' "$out/$name.json")
    untangle=$(/usr/bin/python3 -c 'import json,sys; print(round(json.load(open(sys.argv[1]))["timings"]["untangle"], 1))' "$out/$name.json")
    printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$code" "$wall" \
        "$(awk -v w="$wall" -v r="$reference" 'BEGIN { printf "%.1f", w / r }')" \
        "$steps" "$untangle" "$verdict" >>"$table"
}
run "turned 0.02 degrees (one morph)" 0.02 ""
run "turned 1 degree" 1 ""
[[ $unlimited == 0 ]] || run "turned 1 degree, maxUntangleCells 1000000000" 1 "maxUntangleCells 1000000000;"
morph_dict 1 ""
cat "$table"
{
    echo "OpenFOAM's channel395DFSEM (blockMesh, $(grep -m1 -o '[0-9]* cells' "$out/turned 1 degree.log" || echo '1886000 cells')), its bottom wall turned about the y axis through its centre, every other patch fixed; morphMesh's defaults. Wall time of the whole run (read, check, morph, write or refusal)."
    echo
    cat "$table"
} | results_write -openfoam hopeless_motion "A motion that cannot be made valid: time to the refusal"
