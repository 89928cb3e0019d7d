#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Design variables on the full snappyHexMesh motorBike (issue 21's acceptance figures), in one
# run beside the peer:
#   1. motorbike_vs_movemesh.sh -lifts 0.05: moveMesh and a one-off morphMesh of the natural
#      lift (every motorBike_.* patch by 5% of the bike's height), time and peak memory;
#   2. morphMesh -variables with six variables (bike lift, bike pitch about the rear axle,
#      a front-wheel handle, a rider handle in x and z, a fairing scale): set-up time and
#      memory;
#   3. morphMesh -variant, three times each for two designs (the lift alone, amplitude 1,
#      which the one-off morph also made; and all six), time and memory per variant
#      including the check and writing the points; the lift variant against the one-off
#      morph's points (largest difference / lift);
#   3c. the largest valid step along three directions (-variant A -direction P);
#   3d. three variants past the rider's first inversion, untangled (or refused);
#   4. optionally (-lattice) a lattice of 100 variables around the bike: set-up, variant and
#      gradient times, peak memory, size of the set-up file.
# Prints and writes DIR/design.md.
#
#   design_motorbike.sh [-cache DIR] [-morphMesh PATH] [-out DIR] [-lattice]
#                       [-results FILE | -no-results]
#
# -results FILE: also write design.md's table with the run's context (date, machine, OS,
# commit, OpenFOAM, this command line) to FILE (benchmarks/results.sh); -no-results: write no
# such file. Default: benchmarks/results/design_motorbike.md, written only by a full run,
# i.e. with -lattice (the run the docs quote); none when MESHMORPH_NO_RESULTS=1.
set -euo pipefail
script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$script_dir/../.." && pwd)
source "$script_dir/natural_morph.sh"
source "$script_dir/timed.sh" # timed <log> <cmd...>: $wall, $rss
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh"   # results_init, results_write, ...
results_init "$@"

cache=$root/build/cases/motorBike-full
morph_mesh=$root/build/release/applications/morphMesh/morphMesh
out=$root/build/bench/design
lattice=false
while [[ $# -gt 0 ]]; do
    case $1 in
        -cache) cache=$2; shift 2 ;;
        -morphMesh) morph_mesh=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -lattice) lattice=true; shift ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        *) echo "usage: design_motorbike.sh [-cache DIR] [-morphMesh PATH] [-out DIR] [-lattice] [-results FILE | -no-results]" >&2; exit 2 ;;
    esac
done
morph_mesh=$(realpath "$morph_mesh")
$lattice || results_partial "no -lattice"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
rm -rf "$out" && mkdir -p "$out"
say() { echo "design_motorbike.sh: $*"; }

say "1. the peer: moveMesh and a one-off morphMesh of the 5% lift"
natural_morph_peer "$cache" "$morph_mesh" "$out/peer" || exit 1
say "   moveMesh $movemesh_wall s $movemesh_rss MB, morphMesh $oneoff_wall s $oneoff_rss MB"

say "2. the set-up of six design variables"
case=$out/design
natural_motorbike_case "$cache" "$case"
cat >"$case/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
// Six design variables of the motorBike, each at amplitude 1:
method rbf;
boundary { default { type fixed; } }
handles
{
    // The points around the front wheel's hub (interior points included). The box cuts
    // through the tyre and the forks, whose points outside it stay: a small motion.
    frontWheel { box (-0.15 -0.1 0.15) (0.18 0.1 0.45); displacement (0 0 0); }
}
designVariables
{
    // The tyres stand on the floor: the bike may rise (lift) and raise its nose (pitch,
    // degrees about the rear axle), not sink into the floor.
    lift    { patches ("motorBike_.*"); type translate; vector (0 0 0.0675781); bounds (0 1); }
    pitch   { patches ("motorBike_.*"); type rotate; origin (1.433 0 0.3075); axis (0 1 0);
              angle 1; bounds (0 2); }
    wheel   { handle frontWheel; vector (-0.002 0 0); }
    // The rider as a smooth handle: the one free control point of a 7^3 lattice around
    // him (confine 3: the motion vanishes with two derivatives at the box), in x and z.
    rider   { type ffd; patches ("motorBike_.*"); lattice (7 7 7);
              box ((0.3 -0.45 0.55) (1.35 0.45 1.45)); directions (x z); confine (3 3 3); }
    // The fairing and windshield scaled about the fairing's middle; they tear from the
    // parts around them (fixed in this variable), so only small factors stay valid.
    fairing { patches ("motorBike_frt-fairing.*" "motorBike_windshield.*"); type scale;
              origin (0.5 0 0.6); factor 1.002; }
}
DICT
timed "$out/log.variables" "$morph_mesh" -case "$case" -variables -json "$out/variables.json"
setup_wall=$wall setup_rss=$rss
say "   $setup_wall s, $setup_rss MB"

say "3. variants"
best() { printf '%s\n' "$@" | sort -g | head -1; }
run_variants() { # <name> <amplitudes>: best of three, into variant_wall/variant_rss
    local walls=() rsss=()
    for k in 1 2 3; do
        timed "$out/log.variant.$1.$k" "$morph_mesh" -case "$case" -variant "$2" -json "$out/variant.$1.json"
        walls+=("$wall") rsss+=("$rss")
    done
    variant_wall=$(best "${walls[@]}") variant_rss=$(best "${rsss[@]}")
}
run_variants lift "(1 0 0 0 0 0)"
lift_wall=$variant_wall lift_rss=$variant_rss
cp "$case/1/polyMesh/points" "$out/lift.points" 2>/dev/null || cp "$case/1/polyMesh/points.gz" "$out/lift.points.gz"
run_variants all "(1 2 1 0.05 -0.05 1)"
all_wall=$variant_wall all_rss=$variant_rss
say "   lift alone $lift_wall s $lift_rss MB; all six $all_wall s $all_rss MB"

oneoff=$(ls -d "$out"/peer/runs/*/morphMesh | head -1)
mkdir -p "$out/lift_variant/1/polyMesh"
if [ -f "$out/lift.points" ]; then cp "$out/lift.points" "$out/lift_variant/1/polyMesh/points"; else gunzip -c "$out/lift.points.gz" > "$out/lift_variant/1/polyMesh/points"; fi
[ -f "$oneoff/1/polyMesh/points" ] || gunzip -k "$oneoff/1/polyMesh/points.gz"
/usr/bin/python3 "$script_dir/compare_points.py" "$oneoff" "$out/lift_variant" 0.0675781 >"$out/agreement.txt" || true
say "   lift variant against the one-off morph: $(cat "$out/agreement.txt")"

say "3b. a design of experiments: 20 rows in one run"
/usr/bin/python3 - "$out/doe.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("lift pitch wheel rider.3.3.3.x rider.3.3.3.z fairing\n")
    for r in range(20):
        row = (0.5 + 0.5 * math.sin(r), 1 + math.cos(1.3 * r), 0.25 + 0.75 * math.sin(0.7 * r),
               0.05 * math.cos(0.4 * r), 0.05 * math.sin(r), math.sin(1.9 * r))
        f.write(" ".join("%.4g" % v for v in row) + "\n")
PY
timed "$out/log.variants" "$morph_mesh" -case "$case" -variants "$out/doe.csv" -json "$out/doe.json"
doe_wall=$wall doe_rss=$rss
doe_valid=$(/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['rows']; print(sum(1 for x in r if x['valid'] and x['written']), 'of', len(r))" "$out/doe.json")
say "   $doe_valid written and valid in $doe_wall s ($doe_rss MB)"

say "3c. the largest valid step along a direction (a line search's question)"
step_rows=()
run_step_search() { # <name> <start> <direction>: one search, its row in step_rows
    timed "$out/log.step.$1" "$morph_mesh" -case "$case" -variant "$2" -direction "$3" -json "$out/step.$1.json"
    local row
    row=$(/usr/bin/python3 - "$out/step.$1.json" "$2" "$3" "$wall" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
f = lambda v: "inf" if v is None else "%.6g" % v
print(f"| from {sys.argv[2]} along {sys.argv[3]} | {f(j['step'])} | {j['limitedBy']} "
      f"{j['boundVariable']} | {f(j['invalidAbove'])} | {f(j['estimate'])} | {j['checks']} | "
      f"{j['seconds']:.2f} | {sys.argv[4]} |")
PY
)
    step_rows+=("$row")
    say "   $row"
}
run_step_search rider "(0 0 0 0 0 0)" "(0 0 0 0 -1 0)"
run_step_search all "(0 0 0 0 0 0)" "(1 2 1 0.05 -0.05 1)"
run_step_search fairing "(0.5 1 0 0 0 0)" "(0 0 0 0 0 1)"

say "3d. variants past the first inversion (the rider's control point at -1, past 0.959): untangled"
untangle_rows=()
run_untangled() { # <name> <amplitudes>: one variant, its row in untangle_rows
    timed "$out/log.untangle.$1" "$morph_mesh" -case "$case" -variant "$2" -json "$out/untangle.$1.json"
    local row
    row=$(/usr/bin/python3 - "$out/untangle.$1.json" "$2" "$wall" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
u = j.get("untangle", {})
print(f"| {sys.argv[2]} | {'valid, written' if j['valid'] else 'refused: ' + j['refusal']} | "
      f"{u.get('invalidBefore', 0)} | {u.get('invalidAfter', 0)} | {u.get('pointsMoved', 0)} | "
      f"{u.get('maxMove', 0):.3g} | {u.get('seconds', 0):.2f} | {sys.argv[3]} |")
PY
)
    untangle_rows+=("$row")
    say "   $row"
    local written # the time directory it wrote, removed (the next variants reuse the name)
    written=$(/usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(j['outputInstance'] if j['written'] and j['outputInstance'] else '')" "$out/untangle.$1.json")
    [ -z "$written" ] || rm -rf "${case:?}/$written"
}
run_untangled rider1 "(0 0 0 0 -1 0)"
run_untangled rider105 "(0 0 0 0 -1.05 0)"
run_untangled rider12 "(0 0 0 0 -1.2 0)"

if $lattice; then
    say "4. a lattice of 100 variables"
    lcase=$out/lattice
    natural_motorbike_case "$cache" "$lcase"
    cat >"$lcase/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary { default { type fixed; } }
designVariables
{
    // 6 x 4 x 6 control points around the bike, the outer layer fixed: 4 x 2 x 4 = 32
    // control points moving in x, y and z, plus 4 more in z = 100 variables.
    body { type ffd; patches ("motorBike_.*"); lattice (6 4 6);
           box ((-0.35 -0.4 0.05) (1.8 0.4 1.4)); confine (1 1 1); }
    top  { type ffd; patches ("motorBike_.*"); lattice (4 4 4);
           box ((-0.35 -0.4 0.05) (1.8 0.4 1.4)); confine (1 1 1); directions (z); }
}
DICT
    timed "$out/log.lattice.variables" "$morph_mesh" -case "$lcase" -variables -json "$out/lattice.json"
    lattice_setup_wall=$wall lattice_setup_rss=$rss
    n=$(/usr/bin/python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['variables']))" "$out/lattice.json")
    amps="($(/usr/bin/python3 -c "import math; print(' '.join('%.4g' % (0.005*math.sin(k)) for k in range($n)))"))"
    timed "$out/log.lattice.variant" "$morph_mesh" -case "$lcase" -variant "$amps"
    lattice_variant_wall=$wall lattice_variant_rss=$rss
    /usr/bin/python3 "$script_dir/write_point_field.py" "$lcase" 0/dJdx
    timed "$out/log.lattice.sensitivity" "$morph_mesh" -case "$lcase" -sensitivity 0/dJdx
    lattice_sens_wall=$wall lattice_sens_rss=$rss
    lattice_bytes=$(stat -c %s "$lcase/constant/designBasis")
fi

{
    echo "# Design variables on the full motorBike ($(date -u +%F), $(nproc) cores)"
    echo
    echo "| run | wall [s] | peak RSS [MB] | ratio to one-off morphMesh | ratio to moveMesh |"
    echo "| --- | --- | --- | --- | --- |"
    r() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }
    echo "| moveMesh, 5% lift | $movemesh_wall | $movemesh_rss | | |"
    echo "| morphMesh one-off, 5% lift | $oneoff_wall | $oneoff_rss | 1 | $(r "$oneoff_wall" "$movemesh_wall") |"
    echo "| -variables (6 variables) | $setup_wall | $setup_rss | $(r "$setup_wall" "$oneoff_wall") | $(r "$setup_wall" "$movemesh_wall") |"
    echo "| -variant (1 0 0 0 0 0) (best of 3) | $lift_wall | $lift_rss | $(r "$lift_wall" "$oneoff_wall") | $(r "$lift_wall" "$movemesh_wall") |"
    echo "| -variant (1 2 1 0.05 -0.05 1) (best of 3) | $all_wall | $all_rss | $(r "$all_wall" "$oneoff_wall") | $(r "$all_wall" "$movemesh_wall") |"
    echo "| -variants, 20 rows ($doe_valid valid and written) | $doe_wall | $doe_rss | $(r "$doe_wall" "$oneoff_wall") | $(r "$doe_wall" "$movemesh_wall") |"
    if $lattice; then
        echo "| lattice -variables ($n variables, $((lattice_bytes / 1048576)) MB file) | $lattice_setup_wall | $lattice_setup_rss | | |"
        echo "| lattice -variant | $lattice_variant_wall | $lattice_variant_rss | | |"
        echo "| lattice -sensitivity | $lattice_sens_wall | $lattice_sens_rss | | |"
    fi
    echo
    echo "Largest valid step (-variant A -direction P; the step confirmed by the variant check,"
    echo "the estimate the cubic volumes' first root; search and run wall time in seconds):"
    echo
    echo "| search | step | limited by | invalid above | estimate | checks | search [s] | run [s] |"
    echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${step_rows[@]}"
    echo
    echo "Variants past the first inversion, untangled (invalid before/after: new invalid cells"
    echo "of the linear combination and after the repair; max move in metres):"
    echo
    echo "| amplitudes | verdict | invalid before | invalid after | points moved | max move | untangle [s] | run [s] |"
    echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${untangle_rows[@]}"
    echo
    echo "Lift variant against the one-off morph of the same lift: $(cat "$out/agreement.txt")"
    echo
    grep -E "^Timings|Mesh OK|Failed" "$out/log.variant.all.1" || true
} | tee "$out/design.md"
results_body "$out/design.md" |
    results_write -openfoam design_motorbike "Design variables on the full motorBike"
