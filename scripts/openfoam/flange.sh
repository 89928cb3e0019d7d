#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The snappyHexMesh flange tutorial (mesh/snappyHexMesh/flange): about 19k cells, mostly
# hexahedra with split-hex/polyhedral cells at the surface, four wall patches, and
# cellLevel/pointLevel files in constant/polyMesh. Takes about 6 s on one core.
# Usage: flange.sh DIR
#
# Steps (the tutorial's Allrun, by hand): blockMesh, surfaceFeatureExtract,
# snappyHexMesh -overwrite, checkMesh (must say "Mesh OK"). controlDict's writePrecision
# is raised to 15 so that the written points are the ones OpenFOAM computed with.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 1 ]] || { echo "usage: $foam_script_name DIR" >&2; exit 2; }
case_dir=$1
need_tool blockMesh surfaceFeatureExtract snappyHexMesh checkMesh
tutorials=$(foam_tutorials)
copy_tutorial mesh/snappyHexMesh/flange "$case_dir"
rm -f "$case_dir/Allrun" "$case_dir/Allclean"
mkdir -p "$case_dir/constant/triSurface"
cp "$tutorials/resources/geometry/flange.stl.gz" "$case_dir/constant/triSurface/"
set_control "$case_dir" writePrecision 15

run_step "$case_dir" blockMesh
run_step "$case_dir" surfaceFeatureExtract
run_step "$case_dir" snappyHexMesh -overwrite
run_step "$case_dir" checkMesh
grep -q "Mesh OK" "$case_dir/log.checkMesh" || die "checkMesh did not report 'Mesh OK' (see $case_dir/log.checkMesh)"
echo "$foam_script_name: wrote $case_dir/constant/polyMesh"
