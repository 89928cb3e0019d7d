#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# morphMesh against OpenFOAM's moveMesh where a moving patch meets fixed ones, on the meshes
# of Debian's OpenFOAM tutorials: on every mesh the morph sweep's motion (the smallest wall
# patch scaled by 1% about its centre, every other patch fixed, in 2D within the planes),
# through morphMesh (its defaults, and each -variant) and through moveMesh at the same
# boundary motion (junction_one_mesh.py), then checkMesh -allGeometry on each result. The
# table (junction_summary.py): per mesh max non-orthogonality, faces above 70 degrees, max
# skewness and min determinant of each tool, and per morphMesh variant how often it is no
# worse than moveMesh on each figure.
#
# Usage: junction_vs_movemesh.sh [-cases REGEX] [-all] [-sweep DIR] [-out DIR] [-jobs N]
#                                [-morphMesh PATH] [-variant NAME=KEYS]...
#                                [-results FILE | -no-results] [-help]
#   -cases REGEX     only these tutorials (checkmesh_sweep.sh -cases, e.g. 'pitzDaily$')
#   -all             also the slow meshes (checkmesh_sweep.sh -all: snappyHexMesh,
#                    splitMeshRegions, ...), e.g. the chtMultiRegion windshields
#   -sweep DIR       meshes of an earlier `checkmesh_sweep.sh -morph -out DIR` instead of
#                    meshing again
#   -out DIR         output (default build/bench/junctions): sweep/ (the meshes), meshes/
#                    (logs and result.json per mesh), summary.md
#   -jobs N          meshes at a time (default 2)
#   -morphMesh PATH  default build/release/applications/morphMesh/morphMesh; the Python
#                    module beside it reads the meshes
#   -variant NAME=KEYS  one more morphMesh run per mesh with these morphDict entries, e.g.
#                    -variant "smoothed=jumpSmoothing yes;" (default: that one)
#   -results FILE    write the table there; -no-results: nowhere. Default
#                    benchmarks/results/junction_vs_movemesh.md (junction_vs_movemesh_all.md
#                    with -all), written only without -cases and -sweep
#
# Needs Debian's OpenFOAM v1912 and its tutorials (openfoam-examples).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
foam_script_name=junction_vs_movemesh.sh
# shellcheck source=scripts/openfoam/lib.sh
source "$root/scripts/openfoam/lib.sh"   # die, need_tool
# shellcheck source=benchmarks/results.sh
source "$root/benchmarks/results.sh"
results_init "$@"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

usage() { sed -n '3,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }

out="$root/build/bench/junctions"
morph="$root/build/release/applications/morphMesh/morphMesh"
cases='' all=0 sweep='' jobs=2
variants=()
while [[ $# -gt 0 ]]; do
    case $1 in
        -cases) cases=${2:?-cases needs a regex}; shift 2 ;;
        -all) all=1; shift ;;
        -sweep) sweep=${2:?-sweep needs a directory}; shift 2 ;;
        -out) out=${2:?-out needs a directory}; shift 2 ;;
        -jobs) jobs=${2:?-jobs needs a number}; shift 2 ;;
        -morphMesh) morph=${2:?-morphMesh needs a path}; shift 2 ;;
        -variant) variants+=("${2:?-variant needs NAME=KEYS}"); shift 2 ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -h | -help | --help) usage; exit 0 ;;
        *) echo "$foam_script_name: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
done
[[ ${#variants[@]} -gt 0 ]] || variants=("smoothed=jumpSmoothing yes;")
[[ $morph == /* ]] || morph="$PWD/$morph"
[[ -x $morph ]] || die "no morphMesh at $morph (cmake --build build/release)"
python_dir=$(cd "$(dirname "$morph")/../.." && pwd)/python
[[ -d $python_dir ]] || die "no Python module beside $morph ($python_dir)"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-jobs needs a positive number, not '$jobs'"
[[ -z $cases ]] || results_partial "-cases \"$cases\""
[[ -z $sweep ]] || results_partial "-sweep $sweep"
need_tool moveMesh
need_tool checkMesh

mkdir -p "$out"
out="$(cd "$out" && pwd)"
if [[ -z $sweep ]]; then
    sweep=$out/sweep
    echo "$foam_script_name: meshing the tutorials (checkmesh_sweep.sh -morph; output in $sweep)"
    args=(-morph -morph-mesh "$morph" -out "$sweep" -jobs "$jobs" -no-results)
    [[ -z $cases ]] || args+=(-cases "$cases")
    [[ $all == 0 ]] || args+=(-all)
    "$root/scripts/openfoam/checkmesh_sweep.sh" "${args[@]}" >"$out/log.sweep" 2>&1 ||
        die "checkmesh_sweep.sh failed (see $out/log.sweep)"
fi
sweep=$(cd "$sweep" && pwd)

# One line per mesh the sweep morphed (not skipped): its result.json. Tutorials that make
# the same mesh (pitzDaily's, six times) count once; duplicates.txt names the others.
list=$out/meshes.txt
/usr/bin/python3 - "$sweep" "$cases" "$out/duplicates.txt" >"$list" <<'PY'
import glob, hashlib, json, os, re, sys
sweep, cases, duplicates = sys.argv[1:4]
seen, dup = {}, []
for path in sorted(glob.glob(os.path.join(sweep, "cases", "*", "meshes", "*", "result.json"))):
    r = json.load(open(path))
    tutorial = path.split(os.sep)[-4].split("@")[0].replace("+", "/")  # as -cases matches it
    if r.get("verdict") == "skipped" or "instance" not in r or (cases and not re.search(cases, tutorial)):
        continue
    # Each file where OpenFOAM reads it: the instance's polyMesh, else constant's (points may
    # be in a time, the rest in constant), plain or gzipped.
    dirs = [os.path.join(r["case"], t, r.get("region", ""), "polyMesh") for t in (r["instance"], "constant")]
    digest = hashlib.sha256()
    for name in ("points", "faces", "owner", "boundary"):
        found = [p for d in dirs for p in (os.path.join(d, name), os.path.join(d, name + ".gz")) if os.path.exists(p)]
        if not found:
            sys.exit(f"{path}: no polyMesh/{name} in {' or '.join(dirs)}")
        with open(found[0], "rb") as f:
            digest.update(f.read())
    key = digest.hexdigest()
    if key in seen:
        dup.append(f"{path}\tsame mesh as\t{seen[key]}")
        continue
    seen[key] = path
    print(path)
with open(duplicates, "w") as f:
    f.write("".join(line + "\n" for line in dup))
PY
n=$(wc -l <"$list")
[[ $n -gt 0 ]] || die "no morphed mesh in $sweep${cases:+ matching '$cases'}"
echo "$foam_script_name: $n meshes ($(wc -l <"$out/duplicates.txt") duplicates left out), $jobs at a time"
rm -rf "$out/meshes"
mkdir -p "$out/meshes"

# one_mesh RESULT_JSON: junction_one_mesh.py on the mesh the sweep morphed.
one_mesh() {
    local result=$1 case_dir region instance name
    IFS='|' read -r case_dir region instance < <(/usr/bin/python3 -c \
        'import json,sys; r=json.load(open(sys.argv[1])); print(r["case"], r.get("region", ""), r["instance"], sep="|")' "$result")
    name=$(basename "$(dirname "$(dirname "$(dirname "$result")")")")+$(basename "$(dirname "$result")")
    local args=("$case_dir" "$out/meshes/$name" --morph-mesh "$morph" --time "$instance")
    [[ -z $region ]] || args+=(--region "$region")
    local v
    for v in "${variants[@]}"; do args+=(--variant "$v"); done
    mkdir -p "$out/meshes/$name"
    if PYTHONPATH=$python_dir /usr/bin/python3 "$root/benchmarks/morph/junction_one_mesh.py" "${args[@]}" \
        >"$out/meshes/$name/log" 2>&1; then
        echo "$foam_script_name: $name done"
    else
        echo "$foam_script_name: $name: junction_one_mesh.py failed (see $out/meshes/$name/log)"
    fi
}

running=0
while read -r result; do
    one_mesh "$result" &
    running=$((running + 1))
    if [[ $running -ge $jobs ]]; then
        wait -n || true
        running=$((running - 1))
    fi
done <"$list"
wait

/usr/bin/python3 "$root/benchmarks/morph/junction_summary.py" "$out" >/dev/null ||
    die "junction_summary.py failed"
cat "$out/summary.md"
name=junction_vs_movemesh
[[ $all == 0 ]] || name+=_all
results_write_report -openfoam "$name" "$out/summary.md"
