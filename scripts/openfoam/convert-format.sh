#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Copies an OpenFOAM case and rewrites its mesh with foamFormatConvert.
# Usage: convert-format.sh SRC DST binary|ascii [compressed]
#
# DST gets SRC's system/ and constant/ (time directories and logs are not copied);
# controlDict's writeFormat is set to binary or ascii and writeCompression to on with
# `compressed` (files end in .gz), off otherwise; then `foamFormatConvert -constant`
# rewrites constant/polyMesh (and any other constant/ fields) in that format.
# OpenFOAM v1912 refuses to compress binary output ("Disabled binary format compression"),
# yet reads gzipped binary files; for `binary compressed` the converted polyMesh files are
# therefore gzipped here and checkMesh is run to prove OpenFOAM still reads them.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

usage() { echo "usage: $foam_script_name SRC DST binary|ascii [compressed]" >&2; exit 2; }
[[ $# -eq 3 || $# -eq 4 ]] || usage
src=$1 dst=$2 format=$3 compression=off
[[ $format == binary || $format == ascii ]] || usage
if [[ $# -eq 4 ]]; then
    [[ $4 == compressed ]] || usage
    compression=on
fi
[[ -d "$src/constant/polyMesh" ]] || die "'$src' has no constant/polyMesh"
[[ -f "$src/system/controlDict" ]] || die "'$src' has no system/controlDict"
need_tool foamFormatConvert
new_case_dir "$dst"

cp -r "$src/system" "$src/constant" "$dst/"
chmod -R u+w "$dst"
set_control "$dst" writeFormat "$format"
set_control "$dst" writeCompression "$compression"

run_step "$dst" foamFormatConvert -constant

# foamFormatConvert leaves the old file beside the new one when the name changes
# (points -> points.gz); keep only the converted one.
for f in "$dst"/constant/polyMesh/*; do
    base=${f%.gz}
    if [[ $compression == on && $f != *.gz && -e "$f.gz" ]]; then
        rm -f "$f"
    elif [[ $compression == off && $f == *.gz && -e "$base" ]]; then
        rm -f "$f"
    fi
done
if [[ $format == binary && $compression == on ]]; then
    for f in "$dst"/constant/polyMesh/*; do
        if [[ -f "$f" && $f != *.gz ]]; then gzip -n "$f"; fi
    done
    run_step "$dst" checkMesh
fi
owner="$dst/constant/polyMesh/owner"
[[ -f "$owner" ]] || owner="$owner.gz"
[[ -f "$owner" ]] || die "no constant/polyMesh/owner after foamFormatConvert"
# The header is in the first lines; `|| true` as zcat is cut short by head (pipefail).
header=$( { zcat -f "$owner" 2>/dev/null || true; } | head -n 20)
grep -qE "^ *format +$format;" <<<"$header" ||
    die "$owner is not in $format format after foamFormatConvert"
echo "$foam_script_name: wrote $dst/constant/polyMesh ($format, compression $compression)"
