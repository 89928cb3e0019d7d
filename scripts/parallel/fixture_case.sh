#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The -parallel applications on the committed decomposed fixture tests/data/parallel/duct
# (no OpenFOAM needed, only mpirun): on a copy of it,
#   - mpirun -np 2 checkMeshQuality -parallel -allGeometry -allTopology prints the report
#     checkMesh -parallel printed (checkMesh.parallel.report), line by line
#     (compare_reports.py);
#   - mpirun -np 2 morphMesh -parallel equals the serial morph of the undecomposed mesh
#     (compare_decomposed.py: 1e-12 of the extent, shared points bit-identical), and run
#     again writes the same points to the same time; with `jumpSmoothing yes;` too.
#
#   fixture_case.sh -morphMesh FILE -checkMeshQuality FILE -out DIR
#
# Exit 0 when both hold, 77 when mpirun is missing (a skip), 1 otherwise.
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
fixture=$(cd "$here/../../tests/data/parallel/duct" && pwd)
morph="" check="" out=""
while [ $# -gt 0 ]; do
    case "$1" in
        -morphMesh) morph=$2; shift 2 ;;
        -checkMeshQuality) check=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -help|-h) sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "fixture_case.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
[ -n "$morph" ] && [ -n "$check" ] && [ -n "$out" ] ||
    { echo "fixture_case.sh: -morphMesh, -checkMeshQuality and -out are required" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "skipped: mpirun (openmpi-bin) is not installed"; exit 77; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

rm -rf "$out" && mkdir -p "$out" && cp -r "$fixture" "$out/serial" && cp -r "$fixture" "$out/parallel" || exit 1
out=$(cd "$out" && pwd)
mpirun -np 2 --oversubscribe "$check" -case "$out/parallel" -parallel -allGeometry -allTopology \
    > "$out/log.checkMeshQuality" 2>&1 ||
    { echo "checkMeshQuality -parallel failed (see $out/log.checkMeshQuality)"; exit 1; }
/usr/bin/python3 "$here/compare_reports.py" "$fixture/checkMesh.parallel.report" \
    "$out/log.checkMeshQuality" || exit 1
"$morph" -case "$out/serial" > "$out/log.serial" 2>&1 ||
    { echo "serial morphMesh failed (see $out/log.serial)"; exit 1; }
mpirun -np 2 --oversubscribe "$morph" -case "$out/parallel" -parallel > "$out/log.parallel" 2>&1 ||
    { echo "morphMesh -parallel failed (see $out/log.parallel)"; exit 1; }
/usr/bin/python3 "$here/compare_decomposed.py" "$out/parallel" 1 2 "$out/serial/1/polyMesh/points" || exit 1
# The same command again reads what the first read (processor*/constant), not the first
# run's result in processor*/1: the same points to the same time, no processor*/2.
for p in "$out"/parallel/processor*; do cp "$p/1/polyMesh/points" "$p/points.first" || exit 1; done
mpirun -np 2 --oversubscribe "$morph" -case "$out/parallel" -parallel > "$out/log.parallel.again" 2>&1 ||
    { echo "morphMesh -parallel run again failed (see $out/log.parallel.again)"; exit 1; }
for p in "$out"/parallel/processor*; do
    cmp -s "$p/1/polyMesh/points" "$p/points.first" ||
        { echo "the re-run wrote other points to $p/1 (it morphed the first run's result)"; exit 1; }
    [ ! -e "$p/2" ] || { echo "the re-run wrote $p/2: it read the first run's result"; exit 1; }
done
echo "re-run: the same points in processor*/1, no processor*/2"
# `jumpSmoothing yes;` is honoured with -parallel (the band solved on the master): the same
# points as the serial morph with the same dictionary.
sed 's/^boundary/jumpSmoothing yes;\nboundary/' "$out/parallel/system/morphDict" > "$out/morphDict.jumps"
grep -q '^jumpSmoothing yes;' "$out/morphDict.jumps" || { echo "could not add jumpSmoothing to the morphDict"; exit 1; }
rm -rf "$out"/parallel/processor*/1 "$out/serial/1"
"$morph" -case "$out/serial" -dict "$out/morphDict.jumps" > "$out/log.serial.jumps" 2>&1 ||
    { echo "jumpSmoothing yes, serial: failed (see $out/log.serial.jumps)"; exit 1; }
mpirun -np 2 --oversubscribe "$morph" -case "$out/parallel" -parallel -dict "$out/morphDict.jumps" \
    > "$out/log.parallel.jumps" 2>&1 ||
    { echo "jumpSmoothing yes with -parallel: failed (see $out/log.parallel.jumps)"; exit 1; }
/usr/bin/python3 "$here/compare_decomposed.py" "$out/parallel" 1 2 "$out/serial/1/polyMesh/points" ||
    { echo "jumpSmoothing yes with -parallel: not the serial points"; exit 1; }
echo "jumpSmoothing yes with -parallel: the serial points"
