#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# checkMeshQuality -parallel against OpenFOAM's checkMesh -parallel and against the serial
# check, on the pipe tutorial mesh twisted by a morph (so that the checks have something to
# find across processor faces): morphMesh -overwrite, decomposePar (simple or hierarchical),
# then
#   - the report of mpirun -np N checkMeshQuality -parallel equals checkMesh -parallel's,
#     line by line from "Mesh stats" to the verdict (compare_reports.py: numbers to 1e-9,
#     round-off noise near zero to 1e-12);
#   - its JSON equals the serial checkMeshQuality's JSON (compare_check_json.py).
#
#   check_mesh_parallel.sh -morphMesh FILE -checkMeshQuality FILE -out DIR [-np N]
#                          [-method simple|hierarchical]
#
# Exit 0 when all agree, 77 when OpenFOAM or mpirun is missing (a skip), 1 otherwise.
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
morph="" check="" out="" np=2 method=simple
while [ $# -gt 0 ]; do
    case "$1" in
        -morphMesh) morph=$2; shift 2 ;;
        -checkMeshQuality) check=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -np) np=$2; shift 2 ;;
        -method) method=$2; shift 2 ;;
        -help|-h) sed -n '3,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "check_mesh_parallel.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
[ -n "$morph" ] && [ -n "$check" ] && [ -n "$out" ] ||
    { echo "check_mesh_parallel.sh: -morphMesh, -checkMeshQuality and -out are required" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v decomposePar >/dev/null || { echo "skipped: OpenFOAM's decomposePar is not installed"; exit 77; }
command -v mpirun >/dev/null || { echo "skipped: mpirun (openmpi-bin) is not installed"; exit 77; }
# OpenMPI refuses root without consent (CI runs as root); the cores may be fewer than ranks.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

rm -rf "$out" && mkdir -p "$out/case/system" || exit 1
out=$(cd "$out" && pwd)
case_dir=$out/case
cp -r "$source_dir/tutorials/pipe/constant" "$case_dir/" &&
    cp "$source_dir"/tutorials/pipe/system/{controlDict,fvSchemes,fvSolution} "$case_dir/system/" || exit 1
cat > "$case_dir/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    wall { type rotate; origin (0 0 1); axis (1 0 0); angle 12; }
    inlet { type translate; vector (0.15 0.05 0); }
    outlet { type fixed; }
}
conflicts last;
DICT
cat > "$case_dir/system/meshQualityDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object meshQualityDict; }
#includeEtc "caseDicts/meshQualityDict"
// Tight limits: every criterion that measures across faces flags some here.
maxNonOrtho 12;
maxInternalSkewness 0.25;
minTwist 0.9995;
minFaceWeight 0.47;
minVolRatio 0.9;
minTetQuality 0.2;
DICT
cat > "$case_dir/system/decomposeParDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains $np;
method $method;
simpleCoeffs { n (1 1 $np); delta 0.001; }
hierarchicalCoeffs { n (1 $np 1); delta 0.001; order xyz; }
DICT
run() { # log name, then the command
    local log=$out/log.$1; shift
    "$@" > "$log" 2>&1
}
run morphMesh "$morph" -case "$case_dir" -overwrite ||
    { echo "morphMesh failed (see $out/log.morphMesh)"; exit 1; }
(cd "$case_dir" && run decomposePar decomposePar) ||
    { echo "decomposePar failed (see $out/log.decomposePar)"; exit 1; }
checks="-allGeometry -allTopology -meshQuality"
# checkMesh's status says nothing about the checks; its report is compared below.
(cd "$case_dir" && run checkMesh.parallel mpirun -np "$np" --oversubscribe checkMesh -parallel $checks)
grep -q "^End" "$out/log.checkMesh.parallel" ||
    { echo "checkMesh -parallel failed (see $out/log.checkMesh.parallel)"; exit 1; }
# checkMeshQuality exits 1 when a check fails (the twisted mesh fails some): not an error.
# checkMesh always writes its sets (and says so); checkMeshQuality with -writeSets.
run checkMeshQuality.parallel mpirun -np "$np" --oversubscribe "$check" \
    -case "$case_dir" -parallel $checks -writeSets -json "$out/parallel.json"
[ $? -le 1 ] || { echo "checkMeshQuality -parallel failed (see $out/log.checkMeshQuality.parallel)"; exit 1; }
run checkMeshQuality.serial "$check" -case "$case_dir" $checks -json "$out/serial.json"
[ $? -le 1 ] || { echo "checkMeshQuality failed (see $out/log.checkMeshQuality.serial)"; exit 1; }

/usr/bin/python3 "$here/compare_reports.py" "$out/log.checkMesh.parallel" \
    "$out/log.checkMeshQuality.parallel" || exit 1
/usr/bin/python3 "$here/compare_check_json.py" "$out/serial.json" "$out/parallel.json"
