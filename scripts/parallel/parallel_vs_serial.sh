#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The -parallel morph against the serial one on the pipe tutorial mesh: morphMesh serially,
# decomposePar (method simple or scotch), mpirun -np N morphMesh -parallel, and a comparison
# of every processor's points with the serial points (compare_decomposed.py: 1e-12 of the
# extent, shared points bit-identical); then (the default motion only) a morph both refuse,
# whose JSON must name the same patches (invalidCellsByPatch). Needs OpenFOAM (decomposePar)
# and OpenMPI.
#
#   parallel_vs_serial.sh -bin DIR -out DIR [-np N] [-method simple|scotch]
#                         [-field | -design | -sensitivity | -jump]
#
# -field: the wall and inlet take their motion from 0/pointDisplacement
# (write_point_displacement.py), and the case is written in binary, so that decomposePar
# writes `value nonuniform 0;` for a processor that holds none of the inlet's points (with
# -method simple along the pipe, every processor but the first).
# -design: the design commands instead of a morph, on tutorials/designVariables (11
# variables): -variables, -variant, -variant -direction (the largest valid step, the same
# serially and in parallel) and -sensitivity (a dJ/dx over every point, which
# decomposePar splits) serially and under mpirun; the variant's points compared as above,
# and dJ/da to 1e-12 relative.
# -sensitivity: -sensitivity without design variables (dJ/dXs of the morph: the wall
# scaled, the outlet slipping, the inlet fixed) serially and under mpirun; every
# processor's dJdXs against the serial one at its pointProcAddressing labels, to 1e-9 of
# the largest value (the master sums the gathered points in its own order: round-off).
# -jump: a box (blockMesh, 24 x 24 x 12 cells) whose lid is lifted against its fixed sides,
# so that the prescription jumps along the rim and the jump smoothing (jumpSmoothing auto)
# keeps the band's Laplacian; the band crosses the processor boundary (-method hierarchical
# splits along x). Both logs must say the smoothing was kept, for the same number of
# points. The repair of faces above maxNonOrtho is off there: a rank leaves the points of
# its cells on processor faces, so next to the cut it repairs otherwise than the serial run.
# -bin: the directory holding morphMesh. Exit 0 when the results agree, 77 when OpenFOAM or
# mpirun is missing (a skip), 1 otherwise.
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
bin="" out="" np=2 method=simple field=0 design=0 sensitivity=0 jump=0
while [ $# -gt 0 ]; do
    case "$1" in
        -bin) bin=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -np) np=$2; shift 2 ;;
        -method) method=$2; shift 2 ;;
        -field) field=1; shift ;;
        -design) design=1; shift ;;
        -sensitivity) sensitivity=1; shift ;;
        -jump) jump=1; shift ;;
        -help|-h) sed -n '3,30p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "parallel_vs_serial.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
[ -n "$bin" ] && [ -n "$out" ] || { echo "parallel_vs_serial.sh: -bin and -out are required" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v decomposePar >/dev/null || { echo "skipped: OpenFOAM's decomposePar is not installed"; exit 77; }
command -v mpirun >/dev/null || { echo "skipped: mpirun (openmpi-bin) is not installed"; exit 77; }
# OpenMPI refuses root without consent (CI runs as root); the cores may be fewer than ranks.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

rm -rf "$out" && mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)
motion_dict() {
    if [ "$sensitivity" = 1 ]; then
        cat <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    wall { type scale; origin (0 0 1); factor (1.02 1.03 1); }
    outlet { type slip; }
}
DICT
    elif [ "$jump" = 1 ]; then
        cat <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
maxNonOrtho none;   // its repair is per rank (cells on processor faces stay): not compared here
boundary { lid { type translate; vector (0 0 0.2); } }
DICT
    elif [ "$design" = 1 ]; then
        cat "$source_dir/tutorials/designVariables/system/morphDict"
    elif [ "$field" = 1 ]; then
        cat <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    "(wall|inlet)" { type pointDisplacement; }
    outlet { type slip; }
}
DICT
    else
        cat <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
boundary
{
    wall { type rotate; origin (0 0 1); axis (1 0 0); angle 4; }
    inlet { type translate; vector (0.02 0 0); }
    outlet { type slip; }
}
conflicts last;
DICT
    fi
}
# The lidded box of -jump.
box_case() {
    cat > "$1/system/blockMeshDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) (24 24 12) simpleGrading (1 1 1));
boundary
(
    lid { type wall; faces ((4 5 6 7)); }
    sides { type wall; faces ((0 3 2 1) (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)); }
);
DICT
    cp "$source_dir/tutorials/pipe/system/controlDict" "$1/system/" &&
        (cd "$1" && blockMesh > log.blockMesh 2>&1) ||
        { echo "blockMesh failed (see $1/log.blockMesh)"; return 1; }
}
make_case() {
    mkdir -p "$1/system" "$1/0" || return 1
    if [ "$jump" = 1 ]; then
        box_case "$1" || return 1
    else
        cp -r "$source_dir/tutorials/pipe/constant" "$1/" &&
            cp "$source_dir/tutorials/pipe/system/controlDict" "$1/system/" || return 1
    fi
    motion_dict > "$1/system/morphDict" || return 1
    if [ "$design" = 1 ] || [ "$sensitivity" = 1 ]; then
        /usr/bin/python3 "$source_dir/benchmarks/morph/write_point_field.py" "$1" 0/dJdx || return 1
    fi
    if [ "$field" = 1 ]; then
        /usr/bin/python3 "$here/write_point_displacement.py" "$1" &&
            sed -i 's/^writeFormat .*/writeFormat     binary;/' "$1/system/controlDict"
    fi
}
# run <log> <command...>: the command, its output in $out/log.<log>; stop if it fails.
run() {
    local log=$1
    shift
    "$@" > "$out/log.$log" 2>&1 || { echo "$* failed (see $out/log.$log)"; tail -5 "$out/log.$log"; exit 1; }
}
# morph <serial|parallel> <command prefix...>: the morph, or the three design commands.
amplitudes="(0.8 0.3 1 0.05 -0.05 0.05 -0.05 0.02 0.02 0.02 0.02)"
morph() {
    local name=$1
    shift
    if [ "$sensitivity" = 1 ]; then
        run "$name.sensitivity" "$@" -sensitivity 0/dJdx -json "$out/$name.json"
    elif [ "$design" = 1 ]; then
        run "$name.variables" "$@" -variables
        run "$name.variant" "$@" -variant "$amplitudes"
        run "$name.sensitivity" "$@" -sensitivity 0/dJdx -json "$out/$name.json"
        run "$name.step" "$@" -variant "(0.16 0.06 0.2 0 0 0 0 0 0 0 0)" \
            -direction "(0 0 0 1 -1 1 -1 0 0 0 0)" -json "$out/$name.step.json"
    else
        run "$name" "$@"
    fi
}
make_case "$out/serial" && make_case "$out/parallel" || exit 1
morph serial "$bin/morphMesh" -case "$out/serial"
cat > "$out/parallel/system/decomposeParDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains $np;
method $method;
simpleCoeffs { n (1 1 $np); delta 0.001; }
hierarchicalCoeffs { n ($np 1 1); delta 0.001; order xyz; }
DICT
(cd "$out/parallel" && decomposePar > log.decomposePar 2>&1) ||
    { echo "decomposePar failed (see $out/parallel/log.decomposePar)"; exit 1; }
morph parallel mpirun -np "$np" --oversubscribe "$bin/morphMesh" -case "$out/parallel" -parallel
if [ "$field" = 1 ]; then
    # The case this test is for: a processor holding none of the inlet's points.
    grep -aq "nonuniform 0;" "$out"/parallel/processor*/0/pointDisplacement ||
        { echo "no processor got an empty inlet list from decomposePar: the test misses its case"; exit 1; }
fi
if [ "$sensitivity" = 1 ]; then
    /usr/bin/python3 - "$out" "$np" <<'PY'
import re, sys
out, n = sys.argv[1], int(sys.argv[2])
def internal(path):
    text = open(path).read()
    m = re.search(r"internalField\s+nonuniform List<vector>\s+(\d+)\s*\(", text)
    rows = re.findall(r"\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)", text[m.end():])
    return [tuple(map(float, r)) for r in rows[: int(m.group(1))]]
def labels(path):
    text = open(path, "rb").read()
    m = re.compile(rb"\n(\d+)\s*\n\(").search(text, text.index(b"}", text.index(b"FoamFile")))
    return [int(v) for v in re.findall(rb"-?\d+", text[m.end(): text.index(b")", m.end())])]
serial = internal(f"{out}/serial/0/dJdXs")
largest = max(max(abs(v) for v in p) for p in serial)
worst = 0.0
for r in range(n):
    values = internal(f"{out}/parallel/processor{r}/0/dJdXs")
    addressing = labels(f"{out}/parallel/processor{r}/constant/polyMesh/pointProcAddressing")
    if len(values) != len(addressing):
        sys.exit(f"processor{r}: {len(values)} values for {len(addressing)} points")
    for v, g in zip(values, addressing):
        worst = max(worst, max(abs(v[k] - serial[g][k]) for k in range(3)))
print(f"dJ/dXs, -parallel against serial: largest difference {worst:.3g} of {largest:.3g}")
sys.exit(0 if largest > 0 and worst <= 1e-9 * largest else 1)
PY
    exit $?
fi
/usr/bin/python3 "$here/compare_decomposed.py" "$out/parallel" 1 "$np" "$out/serial/1/polyMesh/points" ||
    exit 1
if [ "$jump" = 1 ]; then
    kept() { grep -ao "jump smoothing: [0-9]* points" "$1" | head -1; }
    serial_band=$(grep -aq "jump smoothing kept" "$out/log.serial" && kept "$out/log.serial")
    parallel_band=$(grep -aq "jump smoothing kept" "$out/log.parallel" && kept "$out/log.parallel")
    echo "serial: ${serial_band:-not kept}; -parallel: ${parallel_band:-not kept}"
    [ -n "$serial_band" ] && [ "$serial_band" = "$parallel_band" ] || exit 1
    exit 0
fi
if [ "$design" != 1 ] && [ "$field" != 1 ]; then
    # A morph both refuse (the wall squeezed to 5% against fixed ends): the same refusal,
    # naming the same patches (their counts are a collective sum over the ranks).
    for c in serial parallel; do
        cat > "$out/$c/system/morphDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
steps 1;
untangle no;
boundary { wall { type scale; origin (0 0 1); factor (0.05 0.05 1); } }
DICT
    done
    "$bin/morphMesh" -case "$out/serial" -json "$out/refused.serial.json" > "$out/log.refused.serial" 2>&1
    serial_status=$?
    mpirun -np "$np" --oversubscribe "$bin/morphMesh" -case "$out/parallel" -parallel \
        -json "$out/refused.parallel.json" > "$out/log.refused.parallel" 2>&1
    parallel_status=$?
    [ "$serial_status" = 3 ] && [ "$parallel_status" = 3 ] ||
        { echo "expected both morphs refused (exit 3): serial $serial_status, -parallel $parallel_status"; exit 1; }
    /usr/bin/python3 - "$out/refused.serial.json" "$out/refused.parallel.json" <<'PY' || exit 1
import json, sys
s, p = (json.load(open(f))["invalidCellsByPatch"] for f in sys.argv[1:3])
print(f"refused: invalid cells by patch, serial {s}, -parallel {p}")
sys.exit(0 if s and s == p else 1)
PY
fi
[ "$design" = 1 ] || exit 0
/usr/bin/python3 - "$out/serial.json" "$out/parallel.json" <<'PY'
import json, sys
s, p = (json.load(open(f))["dJda"] for f in sys.argv[1:3])
worst = max(abs(s[k] - p[k]) / max(1.0, abs(s[k])) for k in s)
print(f"dJ/da of {len(s)} variables, -parallel against serial: largest relative difference {worst:.3g}")
sys.exit(0 if worst < 1e-12 and s.keys() == p.keys() else 1)
PY
/usr/bin/python3 - "$out/serial.step.json" "$out/parallel.step.json" <<'PY'
import json, sys
s, p = (json.load(open(f)) for f in sys.argv[1:3])
print(f"largest valid step: serial {s['step']!r} ({s['limitedBy']}), -parallel {p['step']!r} "
      f"({p['limitedBy']})")
same = all(s[k] == p[k] for k in ("step", "invalidAbove", "estimate", "limitedBy"))
sys.exit(0 if same and s["limitedBy"] == "inversion" else 1)
PY
