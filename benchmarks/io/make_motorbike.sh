#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Build the snappyHexMesh motorBike tutorial mesh (about 353k cells) with the installed
# OpenFOAM, serially, for benchReadMesh. Produces three variants next to each other:
#   <dir>/ascii   (foamFormatConvert: writeFormat ascii, uncompressed)
#   <dir>/binary  (writeFormat binary)
#   <dir>/gz      (writeFormat ascii, writeCompression on)
# Usage: make_motorbike.sh <dir>        e.g. make_motorbike.sh build/cases/motorBike
# Takes several minutes (snappyHexMesh in serial); run it in the background.
set -eu
dest=${1:?usage: make_motorbike.sh <dir>}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

tutorial=""
for root in "${FOAM_TUTORIALS:-}" /usr/share/openfoam/tutorials /usr/share/doc/openfoam-examples/examples; do
    if [ -n "$root" ] && [ -d "$root/incompressible/simpleFoam/motorBike" ]; then
        tutorial=$root
        break
    fi
done
[ -n "$tutorial" ] || { echo "motorBike tutorial not found (install openfoam-examples)" >&2; exit 1; }

mkdir -p "$dest"
base="$dest/base"
rm -rf "$base"
cp -r "$tutorial/incompressible/simpleFoam/motorBike" "$base"
chmod -R u+w "$base"
mkdir -p "$base/constant/triSurface"
cp "$tutorial/resources/geometry/motorBike.obj.gz" "$base/constant/triSurface/"

run() { # run <log> <cmd...>
    log=$1; shift
    echo "Running $* (log: $base/log.$log)"
    (cd "$base" && "$@" > "log.$log" 2>&1) || { echo "$* failed, see $base/log.$log" >&2; exit 1; }
}
run surfaceFeatureExtract surfaceFeatureExtract
run blockMesh blockMesh
run snappyHexMesh snappyHexMesh -overwrite

# Keep only the mesh (fields are not needed) and make the format variants.
variant() { # variant <name> <format> <compression>
    out="$dest/$1"
    rm -rf "$out"
    mkdir -p "$out/constant" "$out/system"
    cp -r "$base/constant/polyMesh" "$out/constant/"
    rm -rf "$out/constant/polyMesh/sets"
    cp "$base/system/controlDict" "$base/system/fvSchemes" "$base/system/fvSolution" "$out/system/"
    sed -i -e "s/^writeFormat .*/writeFormat $2;/" \
           -e "s/^writeCompression .*/writeCompression $3;/" "$out/system/controlDict"
    grep -q '^writeFormat' "$out/system/controlDict" || echo "writeFormat $2;" >> "$out/system/controlDict"
    grep -q '^writeCompression' "$out/system/controlDict" || echo "writeCompression $3;" >> "$out/system/controlDict"
    echo "Running foamFormatConvert for $1"
    (cd "$out" && foamFormatConvert -constant > log.foamFormatConvert 2>&1)
}
variant ascii ascii off
variant binary binary off
variant gz ascii on
du -sh "$dest"/ascii/constant/polyMesh "$dest"/binary/constant/polyMesh "$dest"/gz/constant/polyMesh
