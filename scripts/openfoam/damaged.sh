#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Copies a structured hex case and damages its mesh: inverted cells and twisted faces.
# Usage: damaged.sh SRC DST
#
# Made for blockMesh hex meshes (curved-block.sh, tutorials/pipe). SRC needs an ascii,
# uncompressed constant/polyMesh/points (blockMesh's default; else convert-format.sh SRC
# TMP ascii first) with at least 27 points. Two points move (topology is unchanged):
#   inverted: the point nearest the bounding-box centre, by +5 h along x (h: its distance
#             to the nearest other point). The volume of a hex is affine in one vertex and
#             drops by about a quarter of the cell per cell width moved, so the cells on its
#             +x side turn inside out. On curved-block: checkMesh reports 4 negative-volume
#             cells, 12 wrongly oriented faces (face pyramids), 4 warped faces
#             (-allGeometry), non-orthogonality errors.
#   twisted:  the point nearest lo + 0.25 (hi - lo), by +0.6 h' along z (h' its own
#             nearest-neighbour distance): the four faces around it that were planar
#             become mildly non-planar (flatness < 1 but above checkMesh's 0.8 warning);
#             no cell is inverted by it.
# DST/damage.txt lists, one a line, "<role> <point index> <dx> <dy> <dz>" (index as in the
# points file). checkMesh runs on DST (log.checkMesh) and must report failed checks.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

[[ $# -eq 2 ]] || { echo "usage: $foam_script_name SRC DST" >&2; exit 2; }
src=$1 dst=$2
points="$src/constant/polyMesh/points"
[[ -f "$points" ]] || die "'$points' not found (ascii, uncompressed points are needed; see convert-format.sh)"
grep -qE '^ *format +ascii;' "$points" || die "'$points' is not ascii (convert it with convert-format.sh SRC TMP ascii)"
new_case_dir "$dst"
cp -r "$src/system" "$src/constant" "$dst/"
chmod -R u+w "$dst"

# Pass 1 reads the points; the END block picks the two points and their displacements.
# Point lines are "(x y z)" between the count line and ")"; anything else is copied as is.
# Pass 2 (same program, second file) rewrites the moved points with 15 significant digits.
awk -v damage="$dst/damage.txt" '
    function parse(line, xyz) { gsub(/[()]/, "", line); return split(line, xyz, " ") == 3 }
    function nearest(tx, ty, tz,   i, d, best, bestd) {
        bestd = -1
        for (i = 0; i < n; ++i) {
            d = (x[i]-tx)^2 + (y[i]-ty)^2 + (z[i]-tz)^2
            if (bestd < 0 || d < bestd) { bestd = d; best = i }
        }
        return best
    }
    function spacing(p,   i, d, bestd) {
        bestd = -1
        for (i = 0; i < n; ++i) {
            if (i == p) continue
            d = (x[i]-x[p])^2 + (y[i]-y[p])^2 + (z[i]-z[p])^2
            if (bestd < 0 || d < bestd) bestd = d
        }
        return sqrt(bestd)
    }
    FNR == 1 { file++; state = 0; idx = 0 }
    file == 1 {
        if (state == 0 && $0 ~ /^[0-9]+ *$/) { count = $1 + 0; state = 1; next }
        if (state == 1 && $0 ~ /^\( *$/) { state = 2; next }
        if (state == 2 && $0 ~ /^\)/) { state = 3; next }
        if (state == 2) {
            if (!parse($0, xyz)) { printf "bad point line %d: %s\n", FNR, $0 > "/dev/stderr"; exit 3 }
            x[n] = xyz[1] + 0; y[n] = xyz[2] + 0; z[n] = xyz[3] + 0; n++
        }
        next
    }
    file == 2 && FNR == 1 {
        if (n != count || n < 27) { printf "expected %d points (>= 27), read %d\n", count, n > "/dev/stderr"; exit 3 }
        lox = hix = x[0]; loy = hiy = y[0]; loz = hiz = z[0]
        for (i = 1; i < n; ++i) {
            if (x[i] < lox) lox = x[i]; if (x[i] > hix) hix = x[i]
            if (y[i] < loy) loy = y[i]; if (y[i] > hiy) hiy = y[i]
            if (z[i] < loz) loz = z[i]; if (z[i] > hiz) hiz = z[i]
        }
        a = nearest((lox+hix)/2, (loy+hiy)/2, (loz+hiz)/2)
        b = nearest(lox + 0.25*(hix-lox), loy + 0.25*(hiy-loy), loz + 0.25*(hiz-loz))
        if (a == b) { print "inverted and twisted points coincide" > "/dev/stderr"; exit 3 }
        dx[a] = 5 * spacing(a); dy[a] = 0; dz[a] = 0
        dx[b] = 0; dy[b] = 0; dz[b] = 0.6 * spacing(b)
        printf "inverted %d %.15g %.15g %.15g\n", a, dx[a], dy[a], dz[a] > damage
        printf "twisted %d %.15g %.15g %.15g\n", b, dx[b], dy[b], dz[b] > damage
    }
    file == 2 {
        if (state == 0 && $0 ~ /^[0-9]+ *$/) { state = 1 }
        else if (state == 1 && $0 ~ /^\( *$/) { state = 2 }
        else if (state == 2 && $0 ~ /^\)/) { state = 3 }
        else if (state == 2) {
            if (idx in dx)
                $0 = sprintf("(%.15g %.15g %.15g)", x[idx] + dx[idx], y[idx] + dy[idx], z[idx] + dz[idx])
            idx++
        }
        print
    }' "$points" "$points" >"$dst/constant/polyMesh/points" ||
    die "could not parse '$points' (expected one \"(x y z)\" a line)"

run_step "$dst" checkMesh
grep -q "Failed [0-9]* mesh checks" "$dst/log.checkMesh" ||
    die "checkMesh did not flag the damaged mesh (see $dst/log.checkMesh)"
echo "$foam_script_name: wrote $dst/constant/polyMesh; moved points in $dst/damage.txt"
