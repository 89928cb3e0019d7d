#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# `cmake --install` under a fresh prefix gives applications that run from any case, with no
# PATH or LD_LIBRARY_PATH into the build tree: morphMesh (with -vtk: the VTK module must be
# loaded from <prefix>/lib/meshmorph, not from the build tree; the loader's LD_DEBUG trace
# says which) and checkMeshQuality on its result.
# Usage: cmake_install.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 source=$2 work=$3
fail() { echo "cmake_install.sh: FAILED: $*" >&2; exit 1; }

rm -rf "$work"
mkdir -p "$work/case/system" "$work/case/constant"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for app in morphMesh checkMeshQuality; do
    [[ -x $work/prefix/bin/$app ]] || fail "$app not installed in $work/prefix/bin"
done

cp -r "$source/tutorials/pipe/constant/polyMesh" "$work/case/constant/"
cp "$source/tutorials/pipe/system/controlDict" "$work/case/system/"
cat > "$work/case/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
boundary
{
    wall { type translate; vector (0 0.001 0); }
    "(inlet|outlet)" { type fixed; }
}
DICT
cd "$work/case"
env -u LD_LIBRARY_PATH PATH=/usr/bin:/bin LD_DEBUG=files LD_DEBUG_OUTPUT=../ld-debug \
    "$work/prefix/bin/morphMesh" -vtk > ../morphMesh.log 2>&1 ||
    fail "installed morphMesh exited $? (log: $work/morphMesh.log)"
loaded=$(grep -ho 'file=[^ ]*libmeshmorph_vtk[^ ]*' ../ld-debug.* | sort -u)
[[ $loaded == "file=$work/prefix/lib/meshmorph/libmeshmorph_vtk.so" ]] ||
    fail "the VTK module was loaded from '${loaded#file=}', not from the prefix"
[[ -s 1/polyMesh/points ]] || fail "no 1/polyMesh/points"
compgen -G "VTK/morphMesh_*.vtu" > /dev/null || fail "no VTK/morphMesh_*.vtu"
env -u LD_LIBRARY_PATH PATH=/usr/bin:/bin "$work/prefix/bin/checkMeshQuality" -latestTime \
    > ../checkMeshQuality.log 2>&1 || fail "installed checkMeshQuality exited $?"
grep -q "Mesh OK" ../checkMeshQuality.log || fail "checkMeshQuality: no 'Mesh OK'"
echo "cmake_install.sh: the installed morphMesh and checkMeshQuality ran from $work/case"
