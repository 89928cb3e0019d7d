#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Hundreds of design variables on the full snappyHexMesh motorBike (issue 44, item 1): a
# lattice of 432 variables (8 x 6 x 8 control points around the bike, the outer layer fixed:
# 6 x 4 x 6 moving in x, y and z) set up with one shared fit (morphDict `designBasis
# shared`) and with a field per variable (`designBasis fields`), beside moveMesh and a
# one-off morph of the natural 5% lift in the same run:
#   1. the peer: moveMesh and a one-off morphMesh of the lift (natural_morph_peer);
#   2. each storage: -variables (time, peak memory, file size), -variant (best of 3) with
#      amplitudes of a few millimetres, -sensitivity (dJ/da from a dJ/dx over every point),
#      -variants with 5 rows (per row: combine, check, write), and from Python the study's
#      opening, evaluate, is_valid and transpose_product;
#   3. the two storages' variants at the same amplitudes against each other (both exact at
#      the constrained points; the interior differs within the fits' tolerance).
# Prints and writes DIR/shared_lattice.md.
#
#   shared_lattice.sh [-cache DIR] [-morphMesh PATH] [-out DIR] [-no-fields]
#                     [-results FILE | -no-results]
#
# -no-fields: the shared storage only (the fields set-up of 432 variables takes minutes and
# several GB). Default results file: benchmarks/results/shared_lattice.md, written only by a
# full run (with the fields); none when MESHMORPH_NO_RESULTS=1.
set -euo pipefail
script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$script_dir/../.." && pwd)
source "$script_dir/natural_morph.sh"
source "$script_dir/timed.sh" # timed <log> <cmd...>: $wall, $rss
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh"
results_init "$@"

cache=$root/build/cases/motorBike-full
morph_mesh=$root/build/release/applications/morphMesh/morphMesh
out=$root/build/bench/shared-lattice
fields=true
while [[ $# -gt 0 ]]; do
    case $1 in
        -cache) cache=$2; shift 2 ;;
        -morphMesh) morph_mesh=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -no-fields) fields=false; shift ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        *) echo "usage: shared_lattice.sh [-cache DIR] [-morphMesh PATH] [-out DIR] [-no-fields] [-results FILE | -no-results]" >&2; exit 2 ;;
    esac
done
morph_mesh=$(realpath "$morph_mesh")
$fields || results_partial "no fields storage (-no-fields)"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
rm -rf "$out" && mkdir -p "$out"
say() { echo "shared_lattice.sh: $*"; }
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

say "1. the peer: moveMesh and a one-off morphMesh of the 5% lift"
natural_morph_peer "$cache" "$morph_mesh" "$out/peer" || exit 1
say "   moveMesh $movemesh_wall s $movemesh_rss MB, morphMesh $oneoff_wall s $oneoff_rss MB"

#! lattice_case <dir> <storage>: the motorBike with the 432-variable lattice.
lattice_case() {
    natural_motorbike_case "$cache" "$1"
    cat >"$1/system/morphDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
designBasis $2;
boundary { default { type fixed; } }
designVariables
{
    body { type ffd; patches ("motorBike_.*"); lattice (8 6 8);
           box ((-0.35 -0.4 0.05) (1.8 0.4 1.4)); confine (1 1 1); }
}
DICT
    /usr/bin/python3 "$script_dir/write_point_field.py" "$1" 0/dJdx
}

rows=()
#! run_storage <storage>: set-up, variant, gradient and a 5-row table; appends a table row.
run_storage() {
    local storage=$1 dir=$out/$1
    say "2. designBasis $storage"
    lattice_case "$dir" "$storage"
    timed "$out/log.$storage.variables" "$morph_mesh" -case "$dir" -variables -json "$out/$storage.setup.json"
    local setup_wall=$wall setup_rss=$rss
    n=$(json "$out/$storage.setup.json" "len(j['variables'])")
    local bytes reason
    bytes=$(stat -c %s "$dir/constant/designBasis")
    reason=$(json "$out/$storage.setup.json" "j['storage'] + ': ' + j['storageReason']")
    amps="($(/usr/bin/python3 -c "import math; print(' '.join('%.4g' % (0.003*math.sin(1.7*k)) for k in range($n)))"))"
    local best=""
    for k in 1 2 3; do
        timed "$out/log.$storage.variant.$k" "$morph_mesh" -case "$dir" -variant "$amps" -json "$out/$storage.variant.json"
        [ -z "$best" ] || awk -v a="$wall" -v b="$best" 'BEGIN { exit !(a < b) }' && best=$wall
        [ "$k" = 3 ] || rm -rf "${dir:?}"/[1-9]*
    done
    local valid quality
    valid=$(json "$out/$storage.variant.json" "j['valid']")
    quality=$(json "$out/$storage.variant.json" "'%.2f / %.2f / %.3g / %.1f' % (j['after']['maxNonOrthogonality'], j['after']['maxSkewness'], j['after']['minVolume'], j['maxDisplacement'] / j['maxPrescribedDisplacement'])")
    cp -r "$dir/1" "$out/$storage.variant.points"
    rm -rf "${dir:?}"/[1-9]*
    timed "$out/log.$storage.sensitivity" "$morph_mesh" -case "$dir" -sensitivity 0/dJdx -json "$out/$storage.sens.json"
    local sens_wall=$wall sens_rss=$rss
    /usr/bin/python3 -c "
import math
n = $n
with open('$out/table.txt', 'w') as f:
    f.write('# five designs of a few millimetres\n')
    for r in range(5):
        f.write(' '.join('%.4g' % (0.003 * math.sin(1.7 * k + r)) for k in range(n)) + '\n')"
    timed "$out/log.$storage.variants" "$morph_mesh" -case "$dir" -variants "$out/table.txt" -json "$out/$storage.variants.json"
    # From Python: the study's opening (the shared fit chosen again), then per call.
    local python
    python=$(PYTHONPATH=$(dirname "$(dirname "$(dirname "$morph_mesh")")")/python /usr/bin/python3 - "$dir" "$n" <<'PY'
import math, sys, time
import numpy as np
import meshmorph
case, n = sys.argv[1], int(sys.argv[2])
t = time.perf_counter(); study = meshmorph.DesignStudy(case); opened = time.perf_counter() - t
a = np.array([0.003 * math.sin(1.7 * k + 0.5) for k in range(n)])
def best(f):
    times = []
    for _ in range(3):
        t = time.perf_counter(); f(); times.append(time.perf_counter() - t)
    return min(times)
g = np.ones((len(study.initial_points), 3))
print("%.2f / %.2f / %.2f / %.2f" % (opened, best(lambda: study.evaluate(a)),
                                     best(lambda: study.is_valid(a)),
                                     best(lambda: study.transpose_product(g))))
PY
)
    local per_row
    per_row=$(json "$out/$storage.variants.json" "'%.3g / %.3g / %.3g' % tuple(sorted(r['timings'][k] for r in j['rows'])[2] for k in ('combine', 'check', 'write'))")
    rm -rf "${dir:?}"/[1-9]*
    r() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }
    rows+=("| $storage | $reason | $n | $setup_wall ($(r "$setup_wall" "$oneoff_wall") one-off morphs) | $setup_rss | $(awk -v b="$bytes" 'BEGIN { printf "%.1f", b / 1048576 }') | $best ($(r "$best" "$movemesh_wall") moveMesh), $valid | $quality | $sens_wall | $per_row | $python |")
}

run_storage shared
$fields && run_storage fields

agreement="(not compared: -no-fields)"
if $fields; then
    agreement=$(/usr/bin/python3 - "$out" "$root" <<'PY'
import os, sys
out, root = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(root, "scripts/parallel"))
from compare_decomposed import points
x0, _ = points(os.path.join(out, "shared/constant/polyMesh/points"))
a, _ = points(os.path.join(out, "shared.variant.points/polyMesh/points"))
b, _ = points(os.path.join(out, "fields.variant.points/polyMesh/points"))
moved = max(max(abs(p - q) for p, q in zip(u, v)) for u, v in zip(a, x0))
diff = max(max(abs(p - q) for p, q in zip(u, v)) for u, v in zip(a, b))
print("largest coordinate difference %.3g m, %.3g of the largest displacement (%.3g m)"
      % (diff, diff / moved, moved))
PY
)
fi

{
    echo "# Hundreds of design variables on the full motorBike ($(date -u +%F), $(nproc) cores)"
    echo
    echo "moveMesh on the 5% lift: $movemesh_wall s, $movemesh_rss MB; one-off morphMesh: $oneoff_wall s, $oneoff_rss MB."
    echo
    echo "| storage | chosen | variables | -variables [s] | peak RSS [MB] | file [MB] | -variant [s] (best of 3), valid | its max non-ortho / max skewness / min volume / max displacement over max prescribed | -sensitivity [s] | -variants row: combine / check / write [s] (median of 5) | Python: DesignStudy() / evaluate / is_valid / transpose_product [s] (best of 3) |"
    echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${rows[@]}"
    echo
    echo "The same variant from both storages: $agreement. The unmoved mesh: $(json "$out/shared.setup.json" "'max non-ortho %.2f, max skewness %.2f, min volume %.3g' % (j['before']['maxNonOrthogonality'], j['before']['maxSkewness'], j['before']['minVolume'])")."
} | tee "$out/shared_lattice.md"
results_body "$out/shared_lattice.md" |
    results_write -openfoam shared_lattice "Hundreds of design variables on the full motorBike"
