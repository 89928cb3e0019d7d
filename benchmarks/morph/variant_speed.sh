#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The cost of one design variant on the full motorBike against moveMesh, in one run (issue
# 44's design of experiments: bike lift, pitch about the rear axle, and one lattice control
# point moving in x and z within 5 mm):
#   1. the peer: motorbike_vs_movemesh.sh -lifts 0.05 (moveMesh's whole process on the 5%
#      lift, and a one-off morphMesh of it);
#   2. morphMesh -variables on the four variables;
#   3. morphMesh -variants on a 20-row table: per row the stage times from its JSON (combine,
#      check with any repair, write), the rows that needed a repair with what it cost;
#   4. the same rows from Python (meshmorph.DesignStudy): evaluate + write, is_valid and
#      transpose_product, each the best of 3 per row (variant_speed.py).
# The goal (issue 44): a row that needs no repair at most 1/50 of moveMesh, check and write
# included; is_valid cheaper still. Prints and writes OUT/variant_speed.md.
#
#   variant_speed.sh [-cache DIR] [-build DIR] [-out DIR] [-results FILE | -no-results]
#
# -cache: the full motorBike (scripts/openfoam/motorbike.sh DIR full); -build: the build
# tree whose morphMesh and Python module are timed (default build/release). -results FILE:
# also write the table with the run's context to FILE (benchmarks/results.sh); -no-results:
# none. Default: benchmarks/results/variant_speed.md; none when MESHMORPH_NO_RESULTS=1.
set -euo pipefail
script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$script_dir/../.." && pwd)
source "$script_dir/natural_morph.sh"
source "$script_dir/timed.sh" # timed <log> <cmd...>: $wall, $rss
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh" # results_init, results_write, ...
results_init "$@"

cache=$root/build/cases/motorBike-full
build=$root/build/release
out=$root/build/bench/variant_speed
while [[ $# -gt 0 ]]; do
    case $1 in
        -cache) cache=$2; shift 2 ;;
        -build) build=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        *) echo "usage: variant_speed.sh [-cache DIR] [-build DIR] [-out DIR] [-results FILE | -no-results]" >&2; exit 2 ;;
    esac
done
build=$(realpath "$build")
morph_mesh=$build/applications/morphMesh/morphMesh
[ -x "$morph_mesh" ] || { echo "variant_speed.sh: no morphMesh in $build (build it first)" >&2; exit 2; }
[ -d "$cache/constant/polyMesh" ] || { echo "variant_speed.sh: no motorBike in $cache (scripts/openfoam/motorbike.sh $cache full)" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
rm -rf "$out" && mkdir -p "$out"
say() { echo "variant_speed.sh: $*"; }

say "1. the peer: moveMesh on the 5% lift"
natural_morph_peer "$cache" "$morph_mesh" "$out/peer" || exit 1
say "   moveMesh $movemesh_wall s, one-off morphMesh $oneoff_wall s"

say "2. the set-up: lift, pitch and one lattice control point in x and z"
case=$out/case
natural_motorbike_case "$cache" "$case"
cat >"$case/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary { default { type fixed; } }
designVariables
{
    // The bike rises by up to 5% of its height and raises its nose by up to 0.6 degrees
    // about the rear axle; the middle control point of a 5^3 lattice around it (two outer
    // layers fixed on each side) moves in x and z.
    lift  { patches ("motorBike_.*"); type translate; vector (0 0 0.0675781); bounds (0 1); }
    pitch { patches ("motorBike_.*"); type rotate; origin (1.433 0 0.3075); axis (0 1 0);
            angle 1; bounds (0 0.6); }
    point { type ffd; patches ("motorBike_.*"); lattice (5 5 5);
            box ((-0.35 -0.4 0.05) (1.8 0.4 1.4)); directions (x z); confine (2 2 2); }
}
DICT
timed "$out/log.variables" "$morph_mesh" -case "$case" -variables -json "$out/variables.json"
setup_wall=$wall
say "   $setup_wall s"

say "3. -variants: 20 rows in one process"
/usr/bin/python3 - "$out/doe.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("lift pitch point.2.2.2.x point.2.2.2.z\n")
    for r in range(20):  # the control point within 5 mm: |(x, z)| <= 4.95e-3
        row = (0.5 + 0.5 * math.sin(r), 0.3 + 0.3 * math.cos(1.3 * r),
               0.0035 * math.cos(0.4 * r), 0.0035 * math.sin(r))
        f.write(" ".join("%.6g" % v for v in row) + "\n")
PY
timed "$out/log.variants" "$morph_mesh" -case "$case" -variants "$out/doe.csv" -json "$out/doe.json"
variants_wall=$wall
say "   $variants_wall s"

say "4. the same rows from Python"
PYTHONPATH=$build/python /usr/bin/python3 "$script_dir/variant_speed.py" "$case" "$out/doe.csv" \
    "$out/python.json" >"$out/log.python" 2>&1 || { tail -20 "$out/log.python"; exit 1; }
rm -rf "$case/1" # the variant Python wrote

/usr/bin/python3 - "$out" "$movemesh_wall" "$oneoff_wall" "$setup_wall" "$variants_wall" <<'PY' | tee "$out/variant_speed.md"
import json, statistics, sys
out, movemesh, oneoff, setup, variants = sys.argv[1], *map(float, sys.argv[2:])
rows = json.load(open(f"{out}/doe.json"))["rows"]
py = json.load(open(f"{out}/python.json"))
stage = lambda r: sum(r["timings"][k] for k in ("combine", "check", "write"))
plain = [r for r in rows if "invalidBefore" not in r.get("untangle", {})]
repaired = [r for r in rows if "invalidBefore" in r.get("untangle", {})]
written = sum(1 for r in rows if r["valid"] and r["written"])
ratio = lambda s: f"1/{movemesh / s:.0f}" if s > 0 else ""
print("# The cost of a design variant on the full motorBike\n")
print(f"Four design variables (lift, pitch, one lattice point in x and z), 20 rows: "
      f"{written} of {len(rows)} valid and written, {len(repaired)} repaired.\n")
print("| measure | seconds | against moveMesh |")
print("| --- | --- | --- |")
print(f"| moveMesh, 5% lift (whole process) | {movemesh:.2f} | 1 |")
print(f"| morphMesh one-off, 5% lift (whole process) | {oneoff:.2f} | {ratio(oneoff)} |")
print(f"| -variables, 4 variables (whole process) | {setup:.2f} | {ratio(setup)} |")
print(f"| -variants, 20 rows (whole process) | {variants:.2f} | |")
# The first row also pages the set-up file in: apart. (The topology and the set-up mesh
# are checked once when the study opens, in the process's time, not a row's.)
later = [r for r in plain if r is not rows[0]]
if rows[0] in plain:
    s = stage(rows[0])
    print(f"| -variants first row (pages the set-up file in) | {s:.3f} | {ratio(s)} |")
for name, pick in (("median", statistics.median), ("largest", max)):
    if later:
        s = pick([stage(r) for r in later])
        print(f"| -variants later rows without repair, {name} (combine + check + write) | {s:.3f} | {ratio(s)} |")
if later:
    for k in ("combine", "check", "write"):
        s = statistics.median(r["timings"][k] for r in later)
        print(f"| &nbsp;&nbsp;of which {k} (median) | {s:.3f} | |")
for key, label in (("evaluateWrite", "Python evaluate + write"), ("isValid", "Python is_valid"),
                   ("transposeProduct", "Python transpose_product (dJ/da)")):
    s = statistics.median(py[key])
    print(f"| {label}, median over rows (best of 3 each) | {s:.3f} | {ratio(s)} |")
if repaired:
    print("\nRows that needed a repair (untangling of the linear combination):\n")
    print("| row | amplitudes | invalid before | after | points moved | untangle [s] | row [s] |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for k, r in enumerate(rows):
        u = r.get("untangle", {})
        if "invalidBefore" in u:
            a = " ".join("%.4g" % v for v in r["amplitudes"].values())
            print(f"| {k} | ({a}) | {u['invalidBefore']} | {u['invalidAfter']} | "
                  f"{u['pointsMoved']} | {u['seconds']:.3f} | {stage(r):.3f} |")
refused = [r for r in rows if not r["valid"]]
for r in refused:
    print(f"\nRefused: {r.get('refusal', '')}")
PY
results_body "$out/variant_speed.md" |
    results_write -openfoam variant_speed "The cost of a design variant on the full motorBike"
