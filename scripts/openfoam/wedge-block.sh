#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A small hand-written wedge (axisymmetric) blockMesh case: one block of 10 x 5 x 1 cells,
# 2 x 2.5 degrees about the z axis, symmetric about the x-z plane, the axis collapsed
# (an empty patch without faces, prisms along it), radially graded.
# Usage: wedge-block.sh DIR [twisted]
#
# Patches: inlet (z = 0), outlet (z = 1), outer (r = 0.2), back and front (wedges at
# -2.5 and +2.5 degrees), axis (empty). With "twisted", the outer front vertices are moved
# 0.005 along the axis: the wedges stay planar, but the edges across the wedge then lean in
# z, which checkMesh's wedge check reports (the script then requires that failure).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 1 || ( $# -eq 2 && $2 == twisted ) ]] ||
    { echo "usage: $foam_script_name DIR [twisted]" >&2; exit 2; }
case_dir=$1
twisted=${2:-}
z_in=0 z_out=1 # the front vertices' z
if [[ -n $twisted ]]; then z_in=0.005 z_out=1.005; fi
need_tool blockMesh checkMesh
new_case_dir "$case_dir"
write_system_files "$case_dir"

# r cos(2.5 deg), r sin(2.5 deg) for r = 0.2
x=0.199809644316372
y=0.00872387747306719
{
    foam_header dictionary system blockMeshDict
    cat <<DICT
scale 1;

vertices
(
    (0 0 0)                   // 0 axis, inlet
    (0 0 1)                   // 1 axis, outlet
    ($x -$y 0)                // 2 back, inlet
    ($x -$y 1)                // 3 back, outlet
    ($x $y $z_in)             // 4 front, inlet
    ($x $y $z_out)            // 5 front, outlet
);

blocks
(
    hex (0 1 3 2 0 1 5 4) (10 5 1) simpleGrading (1 0.5 1)
);

edges
(
);

boundary
(
    inlet  { type patch; faces ((0 2 4 0)); }
    outlet { type patch; faces ((1 3 5 1)); }
    outer  { type wall;  faces ((2 3 5 4)); }
    back   { type wedge; faces ((0 1 3 2)); }
    front  { type wedge; faces ((0 4 5 1)); }
    axis   { type empty; faces ((0 1 1 0)); }
);

mergePatchPairs ();
DICT
} >"$case_dir/system/blockMeshDict"

run_step "$case_dir" blockMesh
run_step "$case_dir" checkMesh
if [[ -z $twisted ]]; then
    grep -q "Mesh OK" "$case_dir/log.checkMesh" ||
        die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
else
    grep -q "Number of edges not aligned" "$case_dir/log.checkMesh" ||
        die "checkMesh did not report non-aligned edges (see $case_dir/log.checkMesh)"
fi
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
