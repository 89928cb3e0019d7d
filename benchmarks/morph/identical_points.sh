#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checksums of the points morphMesh writes on the reference cases, to show that a change of
# structure changes no result: run it with the binaries before and after and compare the
# two files (`diff`). Cases:
#   pipe       tutorials/pipe as shipped (its morphDict: the wall onto the venturi STL)
#   handles    the pipe mesh with tutorials/handles' morphDict (handles, fixed walls)
#   flange     the snappyHexMesh flange (scripts/openfoam/flange.sh), flange_patch1 and
#              flange_patch2 translated (0.3 and 0.2 mm), the rest fixed (needs OpenFOAM; skipped without)
#   motorBike  the full motorBike (build/cases/motorBike-full, when present), natural
#              morphDict: every motorBike_.* patch lifted by 5% of the bike's height
#   parallel   the pipe driven by a decomposed pointDisplacement, mpirun -np 2 -parallel
#              (scripts/parallel/parallel_vs_serial.sh -field; needs OpenFOAM and mpirun)
#
# Usage: identical_points.sh -bin DIR -out FILE [-work DIR] [-motorBike CASE]
#   -bin   the directory holding morphMesh (and checkMeshQuality)
#   -out   where to write "case file sha256" lines
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
# shellcheck source=natural_morph.sh
source "$root/benchmarks/morph/natural_morph.sh"
bin="" out="" work=$root/build/identical_points motorbike=$root/build/cases/motorBike-full
while [[ $# -gt 0 ]]; do
    case "$1" in
        -bin) bin=$(cd "$2" && pwd); shift 2 ;;
        -out) out=$2; shift 2 ;;
        -work) work=$2; shift 2 ;;
        -motorBike) motorbike=$2; shift 2 ;;
        -help|-h) sed -n '3,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "identical_points.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
[[ -n $bin && -n $out ]] || { echo "identical_points.sh: -bin and -out are required" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
rm -rf "$work" && mkdir -p "$work"
: > "$out"
record() { # <case> <dir>: the checksums of every points file written under <dir>
    (cd "$2" && find . -path '*/[1-9]*/polyMesh/points*' -type f | sort | xargs -r sha256sum) |
        sed "s|^|$1 |" >> "$out"
}
morph() { # <case dir>
    "$bin/morphMesh" -case "$1" > "$1/log.morphMesh" 2>&1 ||
        { echo "identical_points.sh: morphMesh failed on $1 (see $1/log.morphMesh)" >&2; return 1; }
}

# The tutorial as shipped, by its Allrun (which writes the venturi STL, then morphs).
mkdir -p "$work/pipe" && cp -r "$root/tutorials/pipe/." "$work/pipe/"
(cd "$work/pipe" && MESHMORPH_BIN_DIR=$bin ./Allrun > log.Allrun 2>&1) ||
    { echo "identical_points.sh: tutorials/pipe/Allrun failed (see $work/pipe/log.Allrun)" >&2; exit 1; }
record pipe "$work/pipe"

mkdir -p "$work/handles/constant" && cp -r "$root/tutorials/pipe/constant/polyMesh" "$work/handles/constant/" &&
    cp -r "$root/tutorials/handles/system" "$work/handles/"
morph "$work/handles" && record handles "$work/handles"

if command -v snappyHexMesh > /dev/null; then
    bash "$root/scripts/openfoam/flange.sh" "$work/flange" > "$work/log.flange" 2>&1
    cat > "$work/flange/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    flange_patch1 { type translate; vector (0.0003 0 0); }
    flange_patch2 { type translate; vector (0 0.0002 0); }
    default       { type fixed; }
}
conflicts last;
DICT
    morph "$work/flange" && record flange "$work/flange"
    bash "$root/scripts/parallel/parallel_vs_serial.sh" -bin "$bin" -np 2 -method simple -field \
        -out "$work/parallel" > "$work/log.parallel" 2>&1 ||
        { echo "identical_points.sh: parallel_vs_serial.sh failed (see $work/log.parallel)" >&2; exit 1; }
    record parallel "$work/parallel/parallel"
else
    echo "identical_points.sh: no OpenFOAM: flange and parallel skipped" | tee -a "$out"
fi

if [[ -f $motorbike/constant/polyMesh/faces ]]; then
    natural_motorbike_case "$motorbike" "$work/motorBike"
    morph "$work/motorBike" && record motorBike "$work/motorBike"
else
    echo "identical_points.sh: no motorBike mesh at $motorbike: skipped" | tee -a "$out"
fi
cat "$out"
