#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The same morph on every machine, thread count and build: morphMesh of the release
# (-march=native) and ci (generic x86-64) builds, each with OMP_NUM_THREADS 1, 2 and 4, on
#   venturi       the pipe squeezed onto a venturi of depth 0.8 in one step (equidistant
#                 projections on its plane of symmetry)
#   bent          the venturi bent 2 radii sideways, auto steps and untangling (the motion
#                 of tests/app/morph_steps_test.cpp)
#   greedy        the venturi of depth 0.3 with the greedy RBF and its IDW correction
#   motorBike     the full snappyHexMesh motorBike, natural morphDict (every motorBike_.*
#                 patch lifted by 5% of the bike's height, the rest fixed), when its cached
#                 mesh exists (scripts/openfoam/motorbike.sh DIR full)
# For each case: the verdict of every run, and the largest coordinate difference of the
# written points from the release build's 1-thread run, relative to the largest prescribed
# displacement (docs/same-result.md states the tolerance these are held to).
#
# Usage: same_result.sh [-release DIR] [-ci DIR] [-motorBike CASE] [-out DIR]
#                       [-results FILE | -no-results]
#   -release, -ci  build directories (default build/release, build/ci); each needs morphMesh
#   -motorBike     the full motorBike case (default build/cases/motorBike-full; skipped if absent)
#   -out           work directory (default build/same_result; the table also in table.md)
#   -results FILE  also write the table with the run's context (date, machine, OS, commit,
#                  this command line) to FILE (benchmarks/results.sh)
#   -no-results    write no such file. Default: benchmarks/results/same_result.md, written
#                  only by a full run (the motorBike case included); none when
#                  MESHMORPH_NO_RESULTS=1 (tests, quick runs)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh"   # results_init, results_write, ...
results_init "$@"
# shellcheck source=natural_morph.sh
source "$root/benchmarks/morph/natural_morph.sh"
release=$root/build/release ci=$root/build/ci motorbike=$root/build/cases/motorBike-full
out=$root/build/same_result
while [[ $# -gt 0 ]]; do
    case "$1" in
        -release) release=$2; shift 2 ;;
        -ci) ci=$2; shift 2 ;;
        -motorBike) motorbike=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -help|-h) sed -n '3,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "same_result.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
for build in "$release" "$ci"; do
    [[ -x $build/applications/morphMesh/morphMesh ]] ||
        { echo "same_result.sh: no morphMesh in $build (cmake --build --preset ... --target morphMesh)" >&2; exit 2; }
done
rm -rf "$out" && mkdir -p "$out"
out=$(cd "$out" && pwd)

# The venturi cases, written as tests/app/venturi_case.h writes them.
venturi_case() { # <dir> <depth> <offset> <extra morphDict lines>
    local dir=$1
    mkdir -p "$dir/system" "$dir/constant/triSurface"
    cp -r "$root/tutorials/pipe/constant/polyMesh" "$dir/constant/"
    cp "$root/tutorials/pipe/system/controlDict" "$dir/system/"
    /usr/bin/python3 - "$2" "$3" > "$dir/constant/triSurface/venturi.stl" <<'PY'
import math, sys
depth, offset = float(sys.argv[1]), float(sys.argv[2])
def bump(z):
    return 0.0 if z <= 0.5 or z >= 1.5 else math.sin(math.pi * (z - 0.5)) ** 2
def vertex(r, t, z):
    return "vertex %.12g %.12g %.12g" % (offset * bump(z) + r * math.cos(t), r * math.sin(t), z)
lines = ["solid venturi"]
nt, nz = 128, 110
for k in range(nz):
    za, zb = -0.1 + 2.2 * k / nz, -0.1 + 2.2 * (k + 1) / nz
    ra, rb = 0.5 * (1 - depth * bump(za)), 0.5 * (1 - depth * bump(zb))
    for i in range(nt):
        ta, tb = 2 * math.pi * i / nt, 2 * math.pi * (i + 1) / nt
        for tri in ((vertex(ra, ta, za), vertex(ra, tb, za), vertex(rb, tb, zb)),
                    (vertex(ra, ta, za), vertex(rb, tb, zb), vertex(rb, ta, zb))):
            lines += ["facet normal 0 0 0", "outer loop", *tri, "endloop", "endfacet"]
lines.append("endsolid venturi")
print("\n".join(lines))
PY
    printf '%s\n' "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }" \
        "method rbf;" "$4" "boundary" "{" \
        "    wall { type surface; file \"constant/triSurface/venturi.stl\"; }" \
        "    \"(inlet|outlet)\" { type slip; }" "}" > "$dir/system/morphDict"
}
venturi_case "$out/src/venturi" 0.8 0 "steps 1;"
venturi_case "$out/src/bent" 0.8 1.0 ""
venturi_case "$out/src/greedy" 0.3 0 "rbf { greedy { tolerance 1e-2; } }"
cases="venturi bent greedy"
if [[ -f $motorbike/constant/polyMesh/faces ]]; then
    natural_motorbike_case "$motorbike" "$out/src/motorBike"
    cases="$cases motorBike"
else
    echo "same_result.sh: no motorBike mesh at $motorbike (skipped; scripts/openfoam/motorbike.sh $motorbike full)"
    results_partial "no motorBike mesh"
fi

for c in $cases; do
    for build in release ci; do
        exe=$([[ $build == release ]] && echo "$release" || echo "$ci")/applications/morphMesh/morphMesh
        for threads in 1 2 4; do
            run=$out/runs/$c/$build-$threads
            mkdir -p "$run" && cp -r "$out/src/$c/." "$run/"
            status=0
            OMP_NUM_THREADS=$threads "$exe" -case "$run" -json "$run/morph.json" > "$run/log" 2>&1 || status=$?
            echo "$c $build $threads $status" >> "$out/runs.txt"
        done
    done
done

/usr/bin/python3 - "$out" "$root/scripts/parallel" <<'PY' | tee "$out/table.md"
import json, sys
out = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from compare_decomposed import points as read_points  # noqa: E402 (ascii or binary points)
def points(path):
    return read_points(path)[0]
runs = [line.split() for line in open(f"{out}/runs.txt")]
print("| case | build | threads | exit | verdict | max difference / max prescribed displacement |")
print("| --- | --- | --- | --- | --- | --- |")
worst = {}
for case, build, threads, status in runs:
    d = f"{out}/runs/{case}"
    j = json.load(open(f"{d}/{build}-{threads}/morph.json"))
    verdict = "written" if j.get("written") else "refused"
    diff = "-"
    if status == "0":
        ref = points(f"{d}/release-1/1/polyMesh/points")
        got = points(f"{d}/{build}-{threads}/1/polyMesh/points")
        scale = j["maxPrescribedDisplacement"]
        rel = max(abs(a - b) for p, q in zip(ref, got) for a, b in zip(p, q)) / scale
        worst[case] = max(worst.get(case, 0.0), rel)
        diff = f"{rel:.2e}"
    print(f"| {case} | {build} | {threads} | {status} | {verdict} | {diff} |")
print()
for case, rel in worst.items():
    print(f"{case}: largest difference {rel:.2e} of the largest prescribed displacement")
PY
results_write same_result "The same morph on every build and thread count" "$out/table.md"
