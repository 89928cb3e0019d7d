# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the morph benchmarks: the natural morph of the full motorBike, as a CFD
# engineer writes it (every motorBike_.* patch lifted by 5% of the bike's height, 1.35156 m
# in motorBike.obj; every other patch fixed; defaults otherwise).

#! natural_motorbike_case <full motorBike case> <dir>: a copy of its constant/ and system/
#! with that system/morphDict.
natural_motorbike_case() {
    mkdir -p "$2" && cp -r "$1/constant" "$1/system" "$2/" || return 1
    cat > "$2/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    "motorBike_.*" { type translate; vector (0 0 0.0675781); }
    default        { type fixed; }
}
DICT
}

#! natural_morph_peer <full motorBike case> <morphMesh> <dir>: moveMesh and a one-off
#! morphMesh of the natural lift in one run (motorbike_vs_movemesh.sh -lifts 0.05, into
#! <dir>); sets movemesh_wall, movemesh_rss, oneoff_wall, oneoff_rss (seconds, MB).
natural_morph_peer() {
    local here
    here=$(dirname "${BASH_SOURCE[0]}")
    bash "$here/motorbike_vs_movemesh.sh" -cache "$1" -morphMesh "$2" -lifts 0.05 -out "$3" \
        -no-results >"$3.log" 2>&1 || { tail -20 "$3.log"; return 1; }
    local row='$7 == tool { print $9, $11 }'
    read -r movemesh_wall movemesh_rss <<<"$(awk -F, -v tool=moveMesh "$row" "$3/results.csv")"
    read -r oneoff_wall oneoff_rss <<<"$(awk -F, -v tool=morphMesh "$row" "$3/results.csv")"
}
