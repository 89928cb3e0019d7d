#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# How far can a pipe's wall move before OpenFOAM's moveMesh (displacementLaplacian) breaks
# the mesh, and what does meshMorph's morphMesh make of 1.5 times that motion?
#
# Usage: pipe_amplitudes.sh [-out DIR] [-morphMesh PATH] [-search coarse|full]
#                           [-factor F] [-meshes "hex tet"] [-motions "squeeze shift"]
#                           [-casesOnly] [-results FILE | -no-results] [-help]
#   -out DIR          results and scratch cases (default build/bench/pipe); the script
#                     replaces its own cases/ and runs/ there and writes results.md,
#                     trials.tsv and verify.txt
#   -morphMesh PATH   meshMorph's morphMesh (default build/release/applications/morphMesh/
#                     morphMesh); when it is missing the morphMesh columns say so
#   -search MODE      coarse (default): every 0.05 up to the first broken amplitude, then
#                     every 0.01 below it; full: every 0.01 from 0.01 to 0.95 (also reports
#                     any valid amplitude above the first broken one)
#   -factor F         morphMesh amplitude = F x the larger of the two moveMesh breaking
#                     amplitudes (default 1.5; 0.95 is used when moveMesh never broke)
#   -meshes, -motions restrict the runs (default all)
#   -casesOnly        only make the meshes (OUT/cases/<mesh>, checked by checkMesh) and stop
#                     (benchmarks/paper/deformationBenchmarks -quick uses them)
#   -results FILE     also write results.md's table with the run's context (date, machine,
#                     OS, commit, OpenFOAM, this command line) to FILE (benchmarks/results.sh)
#   -no-results       write no such file. Default: benchmarks/results/pipe_amplitudes.md
#                     (pipe_amplitudes_full_search.md with -search full), written only by a
#                     full run: both meshes, both motions, -factor 1.5, morphMesh found; never
#                     with -casesOnly or when MESHMORPH_NO_RESULTS=1 (tests, quick runs)
#
# Meshes (both a pipe of radius R = 0.5 and length 2 along z, patches inlet, outlet, wall):
#   hex  tutorials/pipe's blockMesh O-grid (system/blockMeshDict, run by OpenFOAM's blockMesh)
#   tet  gmsh (OpenCASCADE cylinder, Delaunay, max element size 0.12) + gmshToFoam, wall
#        set to type wall (as scripts/openfoam/tet-gmsh.sh does)
# Motions of the wall (inlet and outlet fixed), s = z / 2, bump(s) = sin(pi s)^2:
#   squeeze  radially inward by A R bump(s) (a venturi of depth A)
#   shift    along +x by A R bump(s)
# written per point to 0/pointDisplacement by benchmarks/morph/pipe_motion.py (wall values in
# the order of the patch's meshPoints, checked after every moveMesh run: verify.txt).
#
# A trial at amplitude A: moveMesh (dynamicMotionSolverFvMesh, displacementLaplacian,
# diffusivity uniform or inverseDistance (wall); laplacian Gauss linear corrected;
# cellDisplacement PCG/DIC, tolerance 1e-8, relTol 0) writes 1/polyMesh/points; OpenFOAM's
# checkMesh -latestTime judges it. The mesh is broken when checkMesh reports more
# negative-volume cells or more incorrectly oriented face pyramids than for the
# undeformed mesh (zero for both meshes). The "break A" is the smallest such A on the
# 0.01 grid (range 0.01 .. 0.95; "none" if none). Resolution 0.01.
#
# morphMesh (its defaults; system/morphDict: method rbf; wall pointDisplacement, inlet and
# outlet fixed) then morphs the same motion at F x break A; exit 0 = written, 3 = refused
# (inverted cells). A refused morph is repeated with -force (same morph, written anyway) so
# that checkMesh can judge it; the table says so.
#
# Needs Debian's OpenFOAM v1912 (blockMesh, moveMesh, checkMesh, gmshToFoam), gmsh and
# /usr/bin/python3 with numpy (set PYTHON to use another). A few minutes (coarse search).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
here="$root/benchmarks/morph"
foam_script_name=pipe_amplitudes.sh
# shellcheck source=scripts/openfoam/lib.sh
source "$root/scripts/openfoam/lib.sh"   # die, need_tool, set_patch_type
# shellcheck source=benchmarks/results.sh
source "$root/benchmarks/results.sh"     # results_init, results_write, ...
results_init "$@"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

usage() { sed -n '3,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }

out="$root/build/bench/pipe"
morph="$root/build/release/applications/morphMesh/morphMesh"
search=coarse
factor=1.5
meshes="hex tet"
motions="squeeze shift"
cases_only=0
while [[ $# -gt 0 ]]; do
    case $1 in
        -out) out=${2:?-out needs a directory}; shift 2 ;;
        -morphMesh) morph=${2:?-morphMesh needs a path}; shift 2 ;;
        -search) search=${2:?-search needs coarse or full}; shift 2 ;;
        -factor) factor=${2:?-factor needs a number}; shift 2 ;;
        -meshes) meshes=${2:?-meshes needs a list}; shift 2 ;;
        -motions) motions=${2:?-motions needs a list}; shift 2 ;;
        -casesOnly) cases_only=1; shift ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -h | -help | --help) usage; exit 0 ;;
        *) echo "$foam_script_name: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
done
[[ $search == coarse || $search == full ]] || die "-search must be coarse or full"
for m in $meshes; do [[ $m == hex || $m == tet ]] || die "unknown mesh '$m' (hex, tet)"; done
for m in $motions; do [[ $m == squeeze || $m == shift ]] || die "unknown motion '$m'"; done
awk -v f="$factor" 'BEGIN { exit !(f + 0 > 0) }' || die "-factor must be a positive number"
[[ $morph == /* ]] || morph="$PWD/$morph"   # morphMesh runs inside the case directories
[[ " $meshes " == *" hex "* && " $meshes " == *" tet "* ]] || results_partial "-meshes \"$meshes\""
[[ " $motions " == *" squeeze "* && " $motions " == *" shift "* ]] || results_partial "-motions \"$motions\""
awk -v f="$factor" 'BEGIN { exit !(f + 0 == 1.5) }' || results_partial "-factor $factor"
[[ -x $morph ]] || results_partial "no morphMesh at $morph"

python=${PYTHON:-/usr/bin/python3}
"$python" -c 'import numpy' 2>/dev/null || die "$python cannot import numpy (apt-get install python3-numpy)"
need_tool blockMesh moveMesh checkMesh gmsh gmshToFoam
motion_py="$here/pipe_motion.py"

mkdir -p "$out"
out="$(cd "$out" && pwd)"
rm -rf "$out/cases" "$out/runs"
mkdir -p "$out/cases" "$out/runs"
trials="$out/trials.tsv"
verify_log="$out/verify.txt"
printf 'mesh\tmotion\tsolver\tA\tnegVolCells\twrongOrientedFaces\tmaxNonOrtho\tverdict\tbroken\n' >"$trials"
: >"$verify_log"

log() { echo "$foam_script_name: $*"; }


# run_in <dir> <log> <command...>: runs the command in <dir>, output to <dir>/<log>;
# dies naming the step (and showing the log's end) when it fails.
run_in() {
    local dir=$1 logf=$2
    shift 2
    if ! (cd "$dir" && "$@" </dev/null >"$logf" 2>&1); then
        echo "$foam_script_name: error: '$*' failed in $dir; end of $dir/$logf:" >&2
        tail -n 20 "$dir/$logf" >&2 || true
        exit 1
    fi
}

# checkmesh_summary <log>: "negVolCells wrongOrientedFaces maxNonOrtho verdict" from a
# checkMesh log (verdict OK, failed-N or error when checkMesh did not finish).
checkmesh_summary() {
    awk '
        /Number of negative volume cells:/ { n = $NF }
        /Error in face pyramids:/ { for (i = 1; i <= NF; i++) if ($i == "pyramids:") w = $(i + 1) }
        /Mesh non-orthogonality Max:/ { for (i = 1; i <= NF; i++) if ($i == "Max:") o = $(i + 1) }
        /^Mesh OK\./ { v = "OK" }
        /^Failed [0-9]+ mesh checks?\./ { v = "failed-" $2 }
        END { printf "%s %s %s %s\n", n + 0, w + 0, (o == "" ? "?" : o), (v == "" ? "error" : v) }
    ' "$1"
}

# latest_time <case>: the newest numeric time directory name (0 if none).
latest_time() {
    local d
    for d in "$1"/[0-9]*; do
        if [[ -d $d && $(basename "$d") =~ ^[0-9.eE+-]+$ ]]; then basename "$d"; fi
    done | sort -g | tail -n 1
}

clean_times() { # clean_times <case>: removes every time directory and polyMesh/sets
    local d
    for d in "$1"/[0-9]*; do
        if [[ -d $d && $(basename "$d") =~ ^[0-9.eE+-]+$ ]]; then rm -rf "$d"; fi
    done
    rm -rf "$1/constant/polyMesh/sets"
}

# ---------------------------------------------------------------------------------------
# Base cases: system/ from tutorials/pipe (controlDict: writePrecision 15, endTime 1,
# deltaT 1; fvSchemes: laplacian Gauss linear corrected) with fvSolution for moveMesh.
write_fv_solution() {
    {
        foam_header dictionary system fvSolution
        cat <<'DICT'
solvers
{
    "cellDisplacement.*"
    {
        solver          PCG;
        preconditioner  DIC;
        tolerance       1e-8;
        relTol          0;
    }
}
DICT
    } >"$1/system/fvSolution"
}

make_hex() {
    local c="$out/cases/hex"
    mkdir -p "$c"
    cp -r "$root/tutorials/pipe/system" "$c/"
    chmod -R u+w "$c"
    log "hex: blockMesh (tutorials/pipe/system/blockMeshDict) in $c"
    run_in "$c" log.blockMesh blockMesh
}

make_tet() {
    local c="$out/cases/tet"
    mkdir -p "$c"
    cp -r "$root/tutorials/pipe/system" "$c/"
    chmod -R u+w "$c"
    rm -f "$c/system/blockMeshDict"
    cat >"$c/pipe.geo" <<'GEO'
// The pipe of tutorials/pipe as tetrahedra: radius 0.5, 0 < z < 2.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 2, 0.5};
e = 1e-6;
in() = Surface In BoundingBox {-1, -1, -e, 1, 1, e};
out() = Surface In BoundingBox {-1, -1, 2 - e, 1, 1, 2 + e};
wall() = Surface In BoundingBox {-1, -1, -e, 1, 1, 2 + e};
wall() -= {in(), out()};
Physical Surface("inlet") = {in()};
Physical Surface("outlet") = {out()};
Physical Surface("wall") = {wall()};
Physical Volume("fluid") = {1};
Mesh.CharacteristicLengthMax = 0.12;
Mesh.Algorithm3D = 1;
GEO
    log "tet: gmsh + gmshToFoam in $c"
    # gmshToFoam (v1912) reads the MSH 2 format only.
    run_in "$c" log.gmsh gmsh -3 -format msh2 -o pipe.msh pipe.geo
    run_in "$c" log.gmshToFoam gmshToFoam pipe.msh
    set_patch_type "$c" wall wall
}

declare -A base_neg base_wrong mesh_size
for mesh in $meshes; do
    "make_$mesh"
    c="$out/cases/$mesh"
    write_fv_solution "$c"
    for patch in inlet outlet wall; do
        grep -qE "^ *$patch *\$" "$c/constant/polyMesh/boundary" || die "$mesh: no patch '$patch'"
    done
    run_in "$c" log.checkMesh checkMesh
    read -r n w o v < <(checkmesh_summary "$c/log.checkMesh")
    [[ $v == OK ]] || die "$mesh: checkMesh fails the undeformed mesh (see $c/log.checkMesh)"
    base_neg[$mesh]=$n
    base_wrong[$mesh]=$w
    info=$("$python" "$motion_py" info "$c")
    mesh_size[$mesh]=$(awk '/^cells/ { print $2 " cells, " $4 " points" }' <<<"$info")
    log "$mesh: ${mesh_size[$mesh]}, checkMesh: Mesh OK (max non-orthogonality $o)"
    awk '/^patch/ { printf "    patch %-7s type %-6s %5d faces %5d points\n", $2, $3, $4, $5 }' <<<"$info"
done
if ((cases_only)); then
    log "meshes in $out/cases (-casesOnly: no moveMesh or morphMesh runs)"
    exit 0
fi

# ---------------------------------------------------------------------------------------
# moveMesh trials.
# setup_movemesh <dir> <mesh> <diffusivity>
setup_movemesh() {
    local d=$1 mesh=$2 diff=$3
    mkdir -p "$d/logs"
    cp -r "$out/cases/$mesh/system" "$out/cases/$mesh/constant" "$d/"
    rm -rf "$d/constant/polyMesh/sets"
    local spec
    case $diff in
        uniform) spec="uniform" ;;
        inverseDistance) spec="inverseDistance (wall)" ;;
    esac
    {
        foam_header dictionary constant dynamicMeshDict
        cat <<DICT
dynamicFvMesh       dynamicMotionSolverFvMesh;
motionSolverLibs    (fvMotionSolvers);
motionSolver        displacementLaplacian;
displacementLaplacianCoeffs
{
    diffusivity     $spec;
}
DICT
    } >"$d/constant/dynamicMeshDict"
}

# trial <dir> <mesh> <motion> <diffusivity> <k>: moveMesh + checkMesh at A = k/100;
# returns 0 when the mesh is valid, 1 when broken.
trial() {
    local d=$1 mesh=$2 motion=$3 diff=$4 k=$5 a tag n w o v broken
    a=$(awk -v k="$k" 'BEGIN { printf "%.2f", k / 100 }')
    tag="A$a"
    clean_times "$d"
    run_in "$d" "logs/pointDisplacement.$tag" "$python" "$motion_py" displacement . \
        --motion "$motion" --amplitude "$a"
    run_in "$d" "logs/moveMesh.$tag" moveMesh
    grep -q "Selecting motion diffusion: $diff" "$d/logs/moveMesh.$tag" ||
        die "moveMesh did not select diffusivity $diff (see $d/logs/moveMesh.$tag)"
    # The wall points must end at x + d (values in meshPoints order), inlet/outlet fixed.
    if ! "$python" "$motion_py" verify "$d" --time 1 --motion "$motion" --amplitude "$a" \
            >>"$verify_log"; then
        tail -n 1 "$verify_log" >&2
        die "moveMesh's wall points differ from x + d ($d, A = $a): patch point order?"
    fi
    (cd "$d" && checkMesh -latestTime </dev/null >"logs/checkMesh.$tag" 2>&1) || true
    read -r n w o v < <(checkmesh_summary "$d/logs/checkMesh.$tag")
    broken=0
    if ((n > base_neg[$mesh] || w > base_wrong[$mesh])) || [[ $v == error ]]; then broken=1; fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$mesh" "$motion" "moveMesh-$diff" "$a" \
        "$n" "$w" "$o" "$v" "$broken" >>"$trials"
    printf '    A = %s  neg. volumes %5s  wrong faces %5s  max non-ortho %-8s %s\n' \
        "$a" "$n" "$w" "$o" "$([[ $broken == 1 ]] && echo broken || echo valid)"
    return "$broken"
}

# search <mesh> <motion> <diffusivity>: sets brk (e.g. 0.53, or none) and nonmono.
search_break() {
    local mesh=$1 motion=$2 diff=$3 d k first=""
    d="$out/runs/$mesh-$motion-$diff"
    setup_movemesh "$d" "$mesh" "$diff"
    log "$mesh $motion moveMesh/$diff ($search search) in $d"
    nonmono=""
    if [[ $search == full ]]; then
        for ((k = 1; k <= 95; k++)); do
            if ! trial "$d" "$mesh" "$motion" "$diff" "$k"; then
                if [[ -z $first ]]; then first=$k; fi
            elif [[ -n $first ]]; then
                nonmono+="${nonmono:+ }$(awk -v k="$k" 'BEGIN { printf "%.2f", k / 100 }')"
            fi
        done
    else
        local kc=""
        for ((k = 5; k <= 95; k += 5)); do
            if ! trial "$d" "$mesh" "$motion" "$diff" "$k"; then kc=$k; break; fi
        done
        if [[ -n $kc ]]; then
            first=$kc
            for ((k = kc - 4; k < kc; k++)); do
                if ! trial "$d" "$mesh" "$motion" "$diff" "$k"; then first=$k; break; fi
            done
        fi
    fi
    if [[ -n $first ]]; then
        brk=$(awk -v k="$first" 'BEGIN { printf "%.2f", k / 100 }')
    else
        brk=none
    fi
    clean_times "$d"
    log "$mesh $motion moveMesh/$diff: break A = $brk${nonmono:+ (valid again at $nonmono)}"
}

# ---------------------------------------------------------------------------------------
# morphMesh at factor x break A.
run_morphmesh() { # run_morphmesh <mesh> <motion> <A>: sets m_exit m_verdict m_neg m_wrong m_nonortho m_note
    local mesh=$1 motion=$2 a=$3 d rc t n w o v
    d="$out/runs/$mesh-$motion-morphMesh"
    m_exit="-" m_verdict="-" m_neg="-" m_wrong="-" m_nonortho="-" m_note=""
    if [[ ! -x $morph ]]; then
        m_exit="not run"
        m_note="no morphMesh binary at $morph"
        return 0
    fi
    mkdir -p "$d"
    cp -r "$out/cases/$mesh/system" "$out/cases/$mesh/constant" "$d/"
    rm -rf "$d/constant/polyMesh/sets"
    {
        foam_header dictionary system morphDict
        cat <<'DICT'
method      rbf;

boundary
{
    wall    { type pointDisplacement; }
    inlet   { type fixed; }
    outlet  { type fixed; }
}
DICT
    } >"$d/system/morphDict"
    run_in "$d" log.pointDisplacement "$python" "$motion_py" displacement . \
        --motion "$motion" --amplitude "$a"
    log "$mesh $motion morphMesh at A = $a in $d"
    rc=0
    (cd "$d" && "$morph" -case . </dev/null >log.morphMesh 2>&1) || rc=$?
    m_exit=$rc
    local judged=$d forced=0
    if [[ $rc == 3 ]]; then
        # Refused: the same morph once more, written anyway, for checkMesh.
        local f="$d-force"
        rm -rf "$f"
        mkdir -p "$f"
        cp -r "$d/system" "$d/constant" "$d/0" "$f/"
        local frc=0
        (cd "$f" && "$morph" -case . -force </dev/null >log.morphMesh 2>&1) || frc=$?
        if [[ $frc == 0 ]]; then
            judged=$f forced=1
            m_note="refused; checkMesh of the same morph written with -force"
        else
            m_note="refused; -force run exited $frc (see $f/log.morphMesh)"
            judged=""
        fi
    elif [[ $rc != 0 ]]; then
        m_note="exit $rc; see $d/log.morphMesh: $(grep -m1 -iE 'error' "$d/log.morphMesh" | cut -c1-160 || true)"
        judged=""
    fi
    if [[ -n $judged ]]; then
        t=$(latest_time "$judged")
        if [[ -z $t || $t == 0 || ! -f $judged/$t/polyMesh/points ]]; then
            m_note+="${m_note:+; }no <time>/polyMesh/points written"
        else
            (cd "$judged" && checkMesh -latestTime </dev/null >log.checkMesh 2>&1) || true
            read -r n w o v < <(checkmesh_summary "$judged/log.checkMesh")
            m_verdict=$v m_neg=$n m_wrong=$w m_nonortho=$o
            if [[ $forced == 1 ]]; then m_verdict+=" (-force)"; fi
            local vline
            vline=$("$python" "$motion_py" verify "$judged" --time "$t" --motion "$motion" \
                --amplitude "$a" --tolerance 1e-6 || true)
            echo "morphMesh: $vline" >>"$verify_log"
            m_note+="${m_note:+; }wall: $(sed -E 's/.*max \|x_moved - \(x \+ d\)\| = ([^ ]+) with meshPoints.*/max |x - (x0 + d)| = \1/' <<<"$vline")"
        fi
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$mesh" "$motion" "morphMesh(exit $m_exit)" \
        "$a" "$m_neg" "$m_wrong" "$m_nonortho" "$m_verdict" "-" >>"$trials"
    log "  exit $m_exit, checkMesh $m_verdict, neg. volumes $m_neg, wrong faces $m_wrong, max non-ortho $m_nonortho${m_note:+ ($m_note)}"
}

# ---------------------------------------------------------------------------------------
declare -a rows notes
for mesh in $meshes; do
    for motion in $motions; do
        search_break "$mesh" "$motion" uniform
        b_uni=$brk nm_uni=$nonmono
        search_break "$mesh" "$motion" inverseDistance
        b_inv=$brk nm_inv=$nonmono
        a_morph=$(awk -v u="$b_uni" -v i="$b_inv" -v f="$factor" 'BEGIN {
            if (u == "none") u = 0.95; if (i == "none") i = 0.95
            m = (u + 0 > i + 0) ? u : i; printf "%.4g", f * m }')
        run_morphmesh "$mesh" "$motion" "$a_morph"
        if [[ -n $nm_uni ]]; then b_uni+=" (valid again at $nm_uni)"; fi
        if [[ -n $nm_inv ]]; then b_inv+=" (valid again at $nm_inv)"; fi
        rows+=("| $mesh | $motion | $b_uni | $b_inv | $a_morph | $m_exit | $m_verdict | $m_neg | $m_wrong | $m_nonortho |")
        if [[ -n $m_note ]]; then notes+=("- $mesh $motion (morphMesh): $m_note"); fi
    done
done

# ---------------------------------------------------------------------------------------
md="$out/results.md"
{
    echo "# Pipe wall amplitudes: moveMesh's breaking point and morphMesh at ${factor}x"
    echo
    echo "Generated $(date -u '+%Y-%m-%d %H:%M UTC') by benchmarks/morph/pipe_amplitudes.sh" \
         "(-search $search; meshMorph $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'))."
    if [[ -x $morph ]]; then
        echo "morphMesh: $morph (modified $(date -u -r "$morph" '+%Y-%m-%d %H:%M UTC'), sha256 $(sha256sum "$morph" | cut -c1-12))."
    else
        echo "morphMesh: $morph (missing; not run)."
    fi
    echo
    echo "| mesh | motion | moveMesh uniform break A | moveMesh inverseDistance break A | morphMesh A | morphMesh exit | checkMesh verdict | neg. volumes | wrong faces | max non-ortho |"
    echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${rows[@]}"
    echo
    echo "Meshes (radius R = 0.5, length 2 along z; checkMesh: Mesh OK undeformed):"
    for mesh in $meshes; do echo "- $mesh: ${mesh_size[$mesh]}"; done
    echo
    echo "- break A: smallest amplitude on the 0.01 grid (0.01 .. 0.95) at which checkMesh"
    echo "  reports negative-volume cells or incorrectly oriented face pyramids after moveMesh"
    echo "  (displacementLaplacian, laplacian Gauss linear corrected, cellDisplacement PCG/DIC"
    echo "  tolerance 1e-8); none = valid up to 0.95."
    echo "- morphMesh A = ${factor} x the larger of the two break amplitudes (0.95 when none);"
    echo "  morphMesh run with its defaults, \`method rbf\`, wall \`pointDisplacement\`, inlet and"
    echo "  outlet \`fixed\`. exit 0 written, 3 refused (inverted cells). For squeeze, A > 1"
    echo "  pushes the wall through the axis, so no valid mesh exists there."
    echo "- Wall point order: after every moveMesh run the wall points equal x + d for the"
    echo "  values written in meshPoints order (verify.txt)."
    if ((${#notes[@]})); then
        echo
        echo "Notes:"
        printf '%s\n' "${notes[@]}"
    fi
    echo
    echo "Reproduce one trial (case directories under $out/runs):"
    echo
    echo '```sh'
    echo "export WM_PROJECT_DIR=/usr/share/openfoam"
    echo "cd $out/runs/<mesh>-<motion>-<uniform|inverseDistance>"
    echo "$python $motion_py displacement . --motion <motion> --amplitude <A>"
    echo "moveMesh && checkMesh -latestTime && rm -rf 1"
    echo '```'
    echo
    echo "Every trial: $trials; logs: runs/*/logs/."
} >"$md"

echo
cat "$md"
echo
log "wrote $md"
# results.md without its title and the reproduction recipe (this machine's paths).
results_body "$md" | sed '/^Reproduce one trial/,$d' |
    results_write -openfoam -meta "gmsh: $(gmsh --version 2>&1 | head -n 1)" \
        "pipe_amplitudes$([[ $search == full ]] && echo _full_search)" \
        "Pipe wall amplitudes: moveMesh's breaking point and morphMesh at ${factor}x"
