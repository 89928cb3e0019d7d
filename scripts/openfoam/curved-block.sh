#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A small blockMesh hex case with curved edges (arc and spline), 336 cells in two blocks.
# Usage: curved-block.sh DIR
#
# Geometry: a 2 x 1 x 0.5 channel (x: 0..2, y: 0..1, z: 0..0.5) split at x = 1 into two
# 7 x 6 x 4 blocks (the second graded in x). The top edges (y = 1) bulge to y = 1.2 (arc),
# the bottom edges follow a spline through y = -0.05 / +0.03, all in planes z = const,
# so front and back stay planar. Patches: inlet, outlet (patch), walls (wall),
# front (z = 0, symmetryPlane), back (z = 0.5, symmetry). controlDict: ascii,
# writePrecision 15. Runs checkMesh and requires "Mesh OK".
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 1 ]] || { echo "usage: $foam_script_name DIR" >&2; exit 2; }
case_dir=$1
need_tool blockMesh
new_case_dir "$case_dir"
write_system_files "$case_dir"

{
    foam_header dictionary system blockMeshDict
    cat <<'DICT'
scale 1;

vertices
(
    (0 0 0)   (1 0 0)   (2 0 0)       // 0 1 2   bottom, z = 0
    (0 1 0)   (1 1 0)   (2 1 0)       // 3 4 5   top,    z = 0
    (0 0 0.5) (1 0 0.5) (2 0 0.5)     // 6 7 8   bottom, z = 0.5
    (0 1 0.5) (1 1 0.5) (2 1 0.5)     // 9 10 11 top,    z = 0.5
);

blocks
(
    hex (0 1 4 3 6 7 10 9) (7 6 4) simpleGrading (1 1 1)
    hex (1 2 5 4 7 8 11 10) (7 6 4) simpleGrading (2 1 1)
);

edges
(
    arc 3 4 (0.5 1.2 0)
    arc 9 10 (0.5 1.2 0.5)
    arc 4 5 (1.5 1.1 0)
    arc 10 11 (1.5 1.1 0.5)
    spline 0 1 ((0.25 -0.03 0) (0.5 -0.05 0) (0.75 -0.03 0))
    spline 6 7 ((0.25 -0.03 0.5) (0.5 -0.05 0.5) (0.75 -0.03 0.5))
    spline 1 2 ((1.3 0.02 0) (1.7 0.03 0))
    spline 7 8 ((1.3 0.02 0.5) (1.7 0.03 0.5))
);

boundary
(
    inlet
    {
        type patch;
        faces ((0 6 9 3));
    }
    outlet
    {
        type patch;
        faces ((2 5 11 8));
    }
    walls
    {
        type wall;
        faces
        (
            (3 9 10 4) (4 10 11 5)
            (0 1 7 6) (1 2 8 7)
        );
    }
    front
    {
        type symmetryPlane;
        faces ((0 3 4 1) (1 4 5 2));
    }
    back
    {
        type symmetry;
        faces ((6 7 10 9) (7 8 11 10));
    }
);

mergePatchPairs ();
DICT
} >"$case_dir/system/blockMeshDict"

run_step "$case_dir" blockMesh
run_step "$case_dir" checkMesh
grep -q "Mesh OK" "$case_dir/log.checkMesh" || die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
