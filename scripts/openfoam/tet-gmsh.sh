#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A small tetrahedral mesh made by gmsh and converted with gmshToFoam (about 900 cells).
# Usage: tet-gmsh.sh DIR
#
# Geometry: the box [0,1] x [0,0.5] x [0,0.4] (gmsh OpenCASCADE kernel, Delaunay, maximum
# element size 0.12). Patches: inlet (x = 0) and outlet (x = 1) of type patch, walls (the
# other four sides) set to type wall after gmshToFoam (which writes every patch as patch).
# gmshToFoam also writes the cellZone `fluid` (constant/polyMesh/cellZones) and a cellSet.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 1 ]] || { echo "usage: $foam_script_name DIR" >&2; exit 2; }
case_dir=$1
need_tool gmsh gmshToFoam
new_case_dir "$case_dir"
write_system_files "$case_dir"

cat >"$case_dir/box.geo" <<'GEO'
// OpenCASCADE box: surfaces 1..6 are x = 0, x = 1, y = 0, y = 0.5, z = 0, z = 0.4.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.4};
Physical Surface("inlet") = {1};
Physical Surface("outlet") = {2};
Physical Surface("walls") = {3, 4, 5, 6};
Physical Volume("fluid") = {1};
Mesh.CharacteristicLengthMax = 0.12;
Mesh.Algorithm3D = 1;
GEO

# gmshToFoam (v1912) reads the MSH 2 format only.
run_step "$case_dir" gmsh -3 -format msh2 -o box.msh box.geo
run_step "$case_dir" gmshToFoam box.msh
set_patch_type "$case_dir" walls wall
run_step "$case_dir" checkMesh
grep -q "Mesh OK" "$case_dir/log.checkMesh" || die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
