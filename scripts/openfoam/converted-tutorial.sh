#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A tutorial mesh made by a converter, with the steps of its Allrun run by hand (Debian's
# tutorials lack the RunFunctions their Allrun needs):
#   biconic: compressible/rhoCentralFoam/biconic25-55Run35 (32385 cells; blockMesh,
#     datToFoam grid256.dat, collapseEdges -overwrite, the wedgeScr sed: a 0.1 degree
#     wedge about x with its axis collapsed)
#   naca: compressible/sonicFoam/RAS/nacaAirfoil (star4ToFoam of the shipped STAR-CD
#     mesh, its symmetry patches made empty: a 2D case)
# Usage: converted-tutorial.sh DIR biconic|naca
#
# Steps as above, then checkMesh (must say "Mesh OK"). writePrecision is raised to 15.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 2 ]] || { echo "usage: $foam_script_name DIR biconic|naca" >&2; exit 2; }
case_dir=$1
case "$2" in
biconic)
    need_tool blockMesh datToFoam collapseEdges checkMesh
    copy_tutorial compressible/rhoCentralFoam/biconic25-55Run35 "$case_dir"
    rm -f "$case_dir/Allrun" "$case_dir/Allclean"
    gunzip -f "$case_dir"/*.gz
    run_step "$case_dir" blockMesh
    run_step "$case_dir" datToFoam grid256.dat
    cat "$case_dir/constant/pointsHeader" "$case_dir/constant/points.tmp" \
        >"$case_dir/constant/polyMesh/points"
    run_step "$case_dir" collapseEdges -overwrite
    sed -f "$case_dir/constant/wedgeScr" "$case_dir/constant/polyMesh/boundary" \
        >"$case_dir/constant/polyMesh/boundary.wedge"
    mv "$case_dir/constant/polyMesh/boundary.wedge" "$case_dir/constant/polyMesh/boundary"
    ;;
naca)
    need_tool star4ToFoam checkMesh
    copy_tutorial compressible/sonicFoam/RAS/nacaAirfoil "$case_dir"
    rm -f "$case_dir/Allrun" "$case_dir/Allclean"
    resources="$(foam_tutorials)/resources/geometry/nacaAirfoil"
    mkdir -p "$case_dir/star"
    for f in "$resources"/nacaAirfoil.*; do
        if [[ $f == *.gz ]]; then
            gunzip -c "$f" >"$case_dir/star/$(basename "${f%.gz}")"
        else
            cp "$f" "$case_dir/star/"
        fi
    done
    run_step "$case_dir" star4ToFoam -scale 1 star/nacaAirfoil
    sed -i -e 's/symmetry\([)]*;\)/empty\1/' "$case_dir/constant/polyMesh/boundary"
    rm -rf "$case_dir/star" "$case_dir/constant/cellTable" \
        "$case_dir"/constant/polyMesh/{cellTableId,interfaces,origCellId}
    ;;
*) die "unknown tutorial '$2' (biconic or naca)" ;;
esac
set_control "$case_dir" writePrecision 15
run_step "$case_dir" checkMesh
grep -q "Mesh OK" "$case_dir/log.checkMesh" || die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
