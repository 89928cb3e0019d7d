#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A multi-region tutorial split as its Allrun.pre splits it, e.g.
#   heatTransfer/chtMultiRegionFoam/multiRegionHeater (3000 blockMesh cells; topoSet makes
#     5 cellZones; splitMeshRegions -cellZones writes constant/<zone>/polyMesh for each,
#     every region keeping all 5 cellZones, the 4 of the other regions empty)
# Usage: split-regions.sh DIR TUTORIAL (the path under the tutorials directory)
#
# Steps: blockMesh, topoSet, splitMeshRegions -cellZones -overwrite. controlDict's
# writePrecision is raised to 15 so that checkMesh prints 15 digits. The fields
# (0.orig) are not restored: the regions' meshes do not need them.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 2 ]] || { echo "usage: $foam_script_name DIR TUTORIAL" >&2; exit 2; }
case_dir=$1
need_tool blockMesh topoSet splitMeshRegions
copy_tutorial "$2" "$case_dir"
rm -f "$case_dir"/Allrun* "$case_dir/Allclean"
set_control "$case_dir" writePrecision 15

run_step "$case_dir" blockMesh
run_step "$case_dir" topoSet
run_step "$case_dir" splitMeshRegions -cellZones -overwrite
regions=$(cd "$case_dir/constant" && for d in */polyMesh; do echo "${d%/polyMesh}"; done)
[[ -n "$regions" ]] || die "splitMeshRegions wrote no constant/<region>/polyMesh"
echo "$foam_script_name: wrote the regions" $regions "under $case_dir/constant"
