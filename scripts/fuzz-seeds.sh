#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Seed inputs for the fuzz targets (fuzz/), one directory per target, from real files: the
# committed fixtures in tests/data, the tutorials' dictionaries, and, when OpenFOAM is
# installed, what it writes (blockMesh on the cavity and curved-block cases, ascii, binary via
# foamFormatConvert, gzip) and small surfaces of its tutorials (STL ascii/binary, OBJ).
#
# Usage: scripts/fuzz-seeds.sh [--out DIR] [--max-bytes N]
#   --out DIR       where to write DIR/<target>/ (default build/fuzz-seeds)
#   --max-bytes N   skip seeds larger than N bytes (default 65536; the committed corpus in
#                   fuzz/corpus was made with --out fuzz/corpus --max-bytes 4096)
# Existing seed-* files in DIR/<target>/ are replaced; other files (regression inputs) stay.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$PWD

out=build/fuzz-seeds
max_bytes=65536
while [[ $# -gt 0 ]]; do
    case "$1" in
        --out) out=$2; shift 2 ;;
        --max-bytes) max_bytes=$2; shift 2 ;;
        -h|--help) sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "fuzz-seeds.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
    esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)

targets=(fuzz_dictionary fuzz_mesh_file fuzz_point_field fuzz_stl fuzz_obj)
for t in "${targets[@]}"; do
    mkdir -p "$out/$t"
    rm -f "$out/$t"/seed-*
done

# seed <target> <file>: copies file (decompressed if .gz, and as is) under a name from its path.
seed() {
    local target=$1 file=$2 name
    [[ -f $file ]] || return 0
    name=$(realpath "$file")
    name=${name#"$root"/}
    name=${name#/usr/share/doc/openfoam-examples/examples/}
    name=${name#"${work:-/nonexistent}"/}
    name=seed-$(tr '/' '_' <<<"$name" | sed 's/^_*//')
    if [[ $(stat -c %s "$file") -le $max_bytes ]]; then
        cp "$file" "$out/$target/$name"
    fi
    if [[ $file == *.gz ]]; then
        local plain="$out/$target/${name%.gz}"
        gzip -dc "$file" >"$plain"
        [[ $(stat -c %s "$plain") -le $max_bytes ]] || rm -f "$plain"
    fi
}

# mesh_seeds <polyMesh dir>: every polyMesh file, plain and gzip.
mesh_seeds() {
    local dir=$1 f
    for f in points faces owner neighbour boundary faceZones cellZones pointZones; do
        seed fuzz_mesh_file "$dir/$f"
        seed fuzz_mesh_file "$dir/$f.gz"
    done
}

# Committed fixtures (OpenFOAM-written, and the malformed ones of the unit tests).
for variant in ascii binary gz binary_gz; do
    mesh_seeds "tests/data/io/curved_block/$variant/constant/polyMesh"
done
for dir in tests/data/io/malformed/*/; do
    for f in "$dir"*; do
        case "$(basename "$f")" in
            points|faces|owner|neighbour|boundary) seed fuzz_mesh_file "$f" ;;
        esac
    done
done
for f in tests/data/dict/zones_*/*Zones tests/data/dict/owner_binary; do
    seed fuzz_mesh_file "$f"
done
for f in tests/data/io/point_field/*/[01]/pointDisplacement; do
    seed fuzz_point_field "$f"
done
while IFS= read -r f; do
    seed fuzz_dictionary "$f"
done < <(find tests/data/dict tests/data/io/curved_block/ascii/system tutorials/*/system \
             tests/data/io/point_field/ascii/0 tests/data/io/point_field/binary/1 -type f | sort)

# What OpenFOAM writes: blockMesh, foamFormatConvert (binary), compressed variants.
if command -v blockMesh >/dev/null 2>&1 && command -v foamFormatConvert >/dev/null 2>&1; then
    export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
    examples=/usr/share/doc/openfoam-examples/examples
    work=$(mktemp -d)
    work=$(realpath "$work")
    trap 'rm -rf "$work"' EXIT
    cavity=$examples/incompressible/icoFoam/cavity/cavity
    if [[ -d $cavity ]]; then
        cp -r "$cavity" "$work/cavity"
        (cd "$work/cavity" && blockMesh >log.blockMesh 2>&1)
        mesh_seeds "$work/cavity/constant/polyMesh"
        seed fuzz_dictionary "$work/cavity/constant/polyMesh/boundary"
        for variant in binary binary_gz; do
            cp -r "$work/cavity" "$work/cavity_$variant"
            sed -i "s/^writeFormat .*/writeFormat binary;/" "$work/cavity_$variant/system/controlDict"
            if [[ $variant == binary_gz ]]; then
                sed -i "s/^writeCompression .*/writeCompression on;/" \
                    "$work/cavity_$variant/system/controlDict"
            fi
            (cd "$work/cavity_$variant" && foamFormatConvert -constant >log.convert 2>&1)
            mesh_seeds "$work/cavity_$variant/constant/polyMesh"
        done
        while IFS= read -r f; do seed fuzz_dictionary "$f"; done < <(find "$cavity" -type f)
    fi
    # Surfaces: the smallest STL/OBJ of the tutorials, and a binary STL written by OpenFOAM.
    while IFS= read -r f; do
        case "$f" in
            *.stl|*.stl.gz) seed fuzz_stl "$f" ;;
            *.obj|*.obj.gz) seed fuzz_obj "$f" ;;
        esac
    done < <(find "$examples" \( -iname '*.stl' -o -iname '*.stl.gz' -o -iname '*.obj' \
                 -o -iname '*.obj.gz' \) -size -"$((max_bytes / 1024 + 1))"k | sort | head -40)
    stl=$(find "$examples" -name 'baffle3D.stl' | head -1)
    if [[ -n $stl ]] && command -v surfaceConvert >/dev/null 2>&1; then
        (cd "$work" && surfaceConvert "$stl" baffle3D.stlb >log.surfaceConvert 2>&1 &&
             mv baffle3D.stlb baffle3D_binary.stl) || true
        seed fuzz_stl "$work/baffle3D_binary.stl"
    fi
fi

for t in "${targets[@]}"; do
    printf '%-22s %4d seeds %8d bytes\n' "$t" "$(find "$out/$t" -type f | wc -l)" \
        "$(cat "$out/$t"/* 2>/dev/null | wc -c)"
done
