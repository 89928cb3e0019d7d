#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Build the snappyHexMesh motorBike tutorial mesh (about 353k cells) with the installed
# OpenFOAM, serially, in the three formats benchReadMesh compares:
#   <dir>/base    the tutorial case meshed by snappyHexMesh -overwrite (binary, as shipped)
#   <dir>/ascii   foamFormatConvert: writeFormat ascii (writePrecision 15)
#   <dir>/binary  foamFormatConvert: writeFormat binary
#   <dir>/gz      foamFormatConvert: writeFormat ascii, writeCompression on
# Usage: make_motorbike.sh <dir>     e.g. make_motorbike.sh build/cases/motorBike
# Several minutes (snappyHexMesh in serial): run it in the background. An existing
# <dir>/base mesh is reused; the variants must not exist yet.
# Steps are those of scripts/openfoam/motorbike.sh and convert-format.sh.
set -euo pipefail
dest=${1:?usage: make_motorbike.sh <dir>}
scripts="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts/openfoam" && pwd)"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

base="$dest/base"
if [[ ! -e "$base/constant/polyMesh/faces" && ! -e "$base/constant/polyMesh/faces.gz" ]]; then
    "$scripts/motorbike.sh" "$base" full
fi
# ASCII points at 15 significant digits (the tutorial's writePrecision is 6).
source "$scripts/lib.sh"
set_control "$base" writePrecision 15

"$scripts/convert-format.sh" "$base" "$dest/ascii" ascii
"$scripts/convert-format.sh" "$base" "$dest/binary" binary
"$scripts/convert-format.sh" "$base" "$dest/gz" ascii compressed
du -sh "$dest"/ascii/constant/polyMesh "$dest"/binary/constant/polyMesh "$dest"/gz/constant/polyMesh
