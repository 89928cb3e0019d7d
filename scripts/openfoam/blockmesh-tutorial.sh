#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A tutorial mesh made by blockMesh alone, as shipped, e.g.
#   incompressible/pimpleFoam/laminar/movingCone (1900 cells; wedges normal to z, axis x)
#   combustion/reactingFoam/RAS/DLR_A_LTS (3466 cells; wedges normal to y, axis z; both
#     wedge cases have an empty axis patch that blockMesh collapses to no faces)
#   DNS/dnsFoam/boxTurb16 (4096 cells, translational cyclics in all three directions)
#   incompressible/boundaryFoam/boundaryWallFunctions (80 cells in a column, cyclic front
#     and back, empty sides: its cells' determinants need the cyclic faces)
#   incompressible/pimpleFoam/laminar/planarPoiseuille (1D: 40 graded cells, cyclic left
#     and right, a wall and a symmetryPlane; controlDict from controlDict.template)
#   incompressible/pimpleFoam/laminar/mixerVesselAMI2D (3072 cells from blockMeshDict.m4:
#     a rotor and a stator region joined by a cyclicAMI pair only)
# Usage: blockmesh-tutorial.sh DIR TUTORIAL (the path under the tutorials directory)
#
# Steps: [m4 system/blockMeshDict.m4 > system/blockMeshDict], blockMesh, checkMesh (must
# say "Mesh OK"). A controlDict the tutorial's Allrun makes from controlDict.template is
# copied from it. controlDict's writePrecision is raised to 15 so that checkMesh prints 15
# digits.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 2 ]] || { echo "usage: $foam_script_name DIR TUTORIAL" >&2; exit 2; }
case_dir=$1
need_tool blockMesh checkMesh
copy_tutorial "$2" "$case_dir"
rm -f "$case_dir/Allrun" "$case_dir/Allclean"
if [[ ! -f "$case_dir/system/controlDict" && -f "$case_dir/system/controlDict.template" ]]; then
    cp "$case_dir/system/controlDict.template" "$case_dir/system/controlDict"
    # The Allrun replaces placeholders such as planarPoiseuille's "endTime END_TIME;".
    set_control "$case_dir" endTime 1
fi
set_control "$case_dir" writePrecision 15

if [[ -f "$case_dir/system/blockMeshDict.m4" ]]; then
    need_tool m4
    echo "$foam_script_name: running m4 system/blockMeshDict.m4 > system/blockMeshDict"
    (cd "$case_dir" && m4 system/blockMeshDict.m4 >system/blockMeshDict) ||
        die "m4 failed on $case_dir/system/blockMeshDict.m4"
fi
run_step "$case_dir" blockMesh
run_step "$case_dir" checkMesh
grep -q "Mesh OK" "$case_dir/log.checkMesh" || die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
