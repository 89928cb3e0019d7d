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
