#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# morphMesh against OpenFOAM's moveMesh on the snappyHexMesh motorBike tutorial mesh: the
# bike (patches motorBike_*) is lifted by a fraction of its height (1.3516 m in
# motorBike.obj: z from -4.232e-05 to 1.35152), every other patch (lowerWall included)
# stays fixed. Per lift and tool: exit status, wall time and peak memory (/usr/bin/time -v),
# and OpenFOAM's checkMesh on the result (failed checks against the unmoved mesh, wrongly
# oriented face pyramids, negative volumes, max non-orthogonality, max skewness, min volume).
#
# Usage: motorbike_vs_movemesh.sh [-cache DIR] [-morphMesh PATH] [-lifts "0.05 0.09 0.135"]
#                                 [-scaling [-factors "1 1.26 1.59 2"]] [-rbf "KEYS"] [-out DIR]
#                                 [-results FILE | -no-results]
# See usage() below. The two tools, per lift f (lift = f x 1.3516 m), each in a copy of the
# mesh (constant/polyMesh, system, 0) under OUT/runs/<run>/<tool>, log in log.<tool>:
#   moveMesh   constant/dynamicMeshDict: displacementLaplacian, inverseDistance diffusivity
#              from the bike; 0/pointDisplacement: bike fixedValue (0 0 lift), all other
#              patches fixedValue (0 0 0); laplacian "Gauss linear uncorrected";
#              cellDisplacement solved by GAMG to 1e-8 (minIter 25). One time step
#              (deltaT 1, endTime 1): writes 1/polyMesh/points.
#   morphMesh  system/morphDict: method rbf, "motorBike_.*" translate (0 0 lift), default
#              fixed; `morphMesh -case C` writes 1/polyMesh/points, or refuses (exit 3)
#              when the morph would invert cells (recorded, not fatal). Its time is the
#              one compared with moveMesh's. Then the same morph again with `-json
#              C/morph.json` (log.morphMeshJson), for the stage times below; its wall time
#              is reported too (-json adds the scaled Jacobian to both checks).
# Then `checkMesh -latestTime` on each result, and the largest point displacement (how far
# the motion spreads; the lift is the largest prescribed one), and morphMesh's stage times
# from its -json document: read, fit, evaluate, check, untangle, write, the roofline (read +
# write: the I/O no morph can avoid) and its ratio to moveMesh's time, the global RBF's
# centres and residual. Tables (Markdown, CSV, JSON) go to OUT.
# The two set-ups differ on the points the tyres share with lowerWall (57 on the full mesh):
# moveMesh's point patch values let the later patch (the bike) win, so they rise with the
# bike and pull the floor up; morphMesh's default conflict rule `fixed` holds them. So the
# lift study has a third row, morphMeshBikeWins: morphMesh with `conflicts first;` (the bike's
# entry wins there), the boundary motion moveMesh makes (time and checkMesh only).
# A fourth row, moveMeshSameMotion, gives moveMesh morphMesh's own boundary motion: the default
# row's boundary points, point by point, as fixedValue (the floor held under the tyres), so
# the default is also compared at equal motion; its note gives the largest difference of
# the two results' boundary points (round-off when the motions are equal). It needs the
# meshmorph Python module beside morphMesh (build/<preset>/python).
# The cached mesh is never modified (checkMesh writes sets, so it only runs on copies).
# Both tools run one at a time; morphMesh uses OpenMP (OMP_NUM_THREADS is honoured),
# moveMesh is serial.
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$script_dir/../.." && pwd)
foam_script_name=motorbike_vs_movemesh.sh
# shellcheck source=SCRIPTDIR/../../scripts/openfoam/lib.sh
source "$root/scripts/openfoam/lib.sh"   # die, need_tool, run_step, copy_tutorial, set_control
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh"     # results_init, results_write, ...
results_init "$@"

# Height of the bike in motorBike.obj (z from -4.232e-05 to 1.35152).
bike_height=1.35156232
python=/usr/bin/python3
marker=.motorbike_vs_movemesh   # marks the run directories this script may delete

usage() {
    cat <<EOF
usage: $foam_script_name [-cache DIR] [-morphMesh PATH] [-lifts "F ..."] [-scaling]
                          [-factors "K ..."] [-rbf "KEYS"] [-keys "ENTRIES"] [-out DIR]
                          [-results FILE | -no-results]

  -cache DIR        the full motorBike case (scripts/openfoam/motorbike.sh DIR full); built
                    there when missing (minutes), reused when present, never modified
                    (default $root/build/cases/motorBike-full)
  -morphMesh PATH   morphMesh executable (default build/release/applications/morphMesh/morphMesh;
                    when missing, only moveMesh runs)
  -lifts "F ..."    lift fractions of the bike's height ($bike_height m)
                    (default "0.05 0.09 0.135")
  -scaling          instead of the lift study: the 5% lift on meshes with finer blockMesh
                    backgrounds (the (20 8 8) block counts times each factor), time and
                    memory of both tools against the number of points, table and log-log
                    plot (scaling.png). Each mesh is cached next to the cache as DIR-x<K>;
                    meshing the finer ones takes long (snappyHexMesh is serial: ~3 min for
                    the full mesh on a 2-core machine, several times that for factor 2,
                    ~1.6M points)
  -factors "K ..."  block count factors for -scaling (default "1 1.26 1.59 2"; 1 = the cache)
  -rbf "KEYS"       morphDict's rbf sub-dictionary, e.g. "greedy { spread 1; jumpSlope 1; }"
                    (default: none, morphMesh's defaults)
  -keys "ENTRIES"   more top-level morphDict entries for both morphMesh rows, e.g.
                    "jumpSmoothing yes;" (default: none)
  -out DIR          results: results.{md,csv,json} (lifts) or scaling.{md,csv,json,png},
                    and the runs in DIR/runs (default $root/build/bench/motorbike)
  -results FILE     also write the Markdown table with the run's context (date, machine,
                    OS, commit, OpenFOAM, this command line) to FILE (benchmarks/results.sh)
  -no-results       write no such file. Default: benchmarks/results/motorbike_vs_movemesh.md
                    (the lift study) or motorbike_vs_movemesh_scaling.md (-scaling), written
                    only by a full run: the default -lifts (or -factors), no -rbf or -keys,
                    morphMesh found; none when MESHMORPH_NO_RESULTS=1 (tests, quick runs)
  -help             this text
EOF
    exit "${1:-2}"
}

# ---------------------------------------------------------------------------------------
# Options

cache=$root/build/cases/motorBike-full
morph_mesh=$root/build/release/applications/morphMesh/morphMesh
lifts="0.05 0.09 0.135"
factors="1 1.26 1.59 2"
scaling=false
rbf_keys=""
extra_keys=""
out=$root/build/bench/motorbike
while [[ $# -gt 0 ]]; do
    case $1 in
        -cache)     [[ $# -ge 2 ]] || usage; cache=$2; shift 2 ;;
        -morphMesh) [[ $# -ge 2 ]] || usage; morph_mesh=$2; shift 2 ;;
        -lifts)     [[ $# -ge 2 ]] || usage; lifts=$2; shift 2 ;;
        -factors)   [[ $# -ge 2 ]] || usage; factors=$2; shift 2 ;;
        -scaling)   scaling=true; shift ;;
        -rbf)       [[ $# -ge 2 ]] || usage; rbf_keys=$2; shift 2 ;;
        -keys)      [[ $# -ge 2 ]] || usage; extra_keys=$2; shift 2 ;;
        -out)       [[ $# -ge 2 ]] || usage; out=$2; shift 2 ;;
        -results)   [[ $# -ge 2 ]] || usage; results_file "$2"; shift 2 ;;
        -no-results) results_off; shift ;;
        -help|--help|-h) usage 0 ;;
        *) echo "$foam_script_name: unknown option '$1'" >&2; usage ;;
    esac
done
is_number() { [[ $1 =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]]; }
for f in $lifts $factors; do
    is_number "$f" || die "not a positive number: '$f' (in -lifts or -factors)"
done
[[ -n "${lifts// /}" ]] || die "-lifts is empty"
# shellcheck disable=SC2086,SC2116 # word lists, compared word by word
if $scaling; then
    [[ $(echo $factors) == "1 1.26 1.59 2" ]] || results_partial "-factors \"$factors\""
else
    [[ $(echo $lifts) == "0.05 0.09 0.135" ]] || results_partial "-lifts \"$lifts\""
fi
[[ -z $rbf_keys ]] || results_partial "-rbf \"$rbf_keys\""
[[ -z $extra_keys ]] || results_partial "-keys \"$extra_keys\""
cache=$(realpath -m "$cache")
if [[ $morph_mesh == */* ]]; then
    morph_mesh=$(realpath -m "$morph_mesh")
else
    morph_mesh=$(command -v "$morph_mesh" || echo "$morph_mesh")
fi
out=$(realpath -m "$out")
python_dir=$(realpath -m "$(dirname "$morph_mesh")/../../python")   # the meshmorph module beside it

# ---------------------------------------------------------------------------------------
# Small helpers

say() { echo "$foam_script_name: $*"; }

#! step_failed <step> <message...>: dies naming the step.
step_failed() {
    local step=$1
    shift
    die "step '$step' failed: $*"
}

#! lift_of <fraction>: the lift in metres (7 significant digits).
lift_of() { awk -v f="$1" -v h="$bike_height" 'BEGIN { printf "%.7g\n", f * h }'; }

#! scale_count <count> <factor>: round(count x factor), at least 1.
scale_count() { awk -v n="$1" -v k="$2" 'BEGIN { m = int(n * k + 0.5); print (m < 1 ? 1 : m) }'; }

#! checkmesh_verdict <log>: "Mesh OK." or "Failed N mesh checks." (empty if none).
checkmesh_verdict() { grep -E "^(Mesh OK\.|Failed [0-9]+ mesh checks\.)" "$1" 2>/dev/null || true; }

#! has_mesh <case>: the case has constant/polyMesh/faces and a checkMesh verdict in log.checkMesh.
has_mesh() {
    [[ -e "$1/constant/polyMesh/faces" || -e "$1/constant/polyMesh/faces.gz" ]] &&
        [[ -n "$(checkmesh_verdict "$1/log.checkMesh")" ]]
}

#! fresh_run_dir <dir>: (re)creates an empty run directory; only directories this script
#! made (with its marker file) are deleted.
fresh_run_dir() {
    if [[ -e "$1" ]]; then
        [[ -e "$1/$marker" ]] || die "'$1' exists and was not made by this script; remove it or choose another -out"
        rm -rf -- "$1"
    fi
    mkdir -p "$1"
    : >"$1/$marker"
}


# ---------------------------------------------------------------------------------------
# Meshes

#! build_full_case <dir>: the tutorial mesh via scripts/openfoam/motorbike.sh, unless present.
#! As v1912 makes it, checkMesh fails the skewness check (14 faces) and motorbike.sh exits
#! non-zero: accepted when the mesh and checkMesh's verdict are there.
build_full_case() {
    local dir=$1
    if has_mesh "$dir"; then
        say "reusing the motorBike mesh in $dir ($(checkmesh_verdict "$dir/log.checkMesh"))"
        return 0
    fi
    [[ ! -e "$dir" || -z "$(ls -A "$dir" 2>/dev/null)" ]] ||
        die "'$dir' exists but holds no complete motorBike mesh (no constant/polyMesh/faces or no verdict in log.checkMesh); remove it or pass another -cache"
    say "meshing the full motorBike tutorial into $dir (snappyHexMesh, several minutes)"
    if ! bash "$root/scripts/openfoam/motorbike.sh" "$dir" full; then
        has_mesh "$dir" || step_failed "mesh the motorBike (scripts/openfoam/motorbike.sh)" \
            "no mesh in $dir; see its log.* files"
        say "the snappyHexMesh mesh fails checkMesh as expected: $(checkmesh_verdict "$dir/log.checkMesh")"
    fi
}

#! build_scaled_case <dir> <factor>: the full tutorial with the (20 8 8) background blocks
#! scaled by <factor> (steps as scripts/openfoam/motorbike.sh), unless present. Meshes in
#! <dir>.partial and renames it when done, so an interrupted run is never reused.
build_scaled_case() {
    local dir=$1 factor=$2 nx ny nz
    if has_mesh "$dir"; then
        say "reusing the x$factor mesh in $dir ($(checkmesh_verdict "$dir/log.checkMesh"))"
        return 0
    fi
    [[ ! -e "$dir" ]] || die "'$dir' exists but holds no complete mesh; remove it"
    nx=$(scale_count 20 "$factor") ny=$(scale_count 8 "$factor") nz=$(scale_count 8 "$factor")
    say "WARNING: meshing the motorBike with a ($nx $ny $nz) background into $dir:" \
        "snappyHexMesh on one core takes long (the full mesh ~3 min, factor 2 several times that)"
    local tmp=$dir.partial
    if [[ -e "$tmp" ]]; then
        say "removing the unfinished $tmp"
        rm -rf -- "$tmp"
    fi
    copy_tutorial incompressible/simpleFoam/motorBike "$tmp"
    rm -f "$tmp/Allrun" "$tmp/Allclean"
    mkdir -p "$tmp/constant/triSurface"
    cp "$(foam_tutorials)/resources/geometry/motorBike.obj.gz" "$tmp/constant/triSurface/"
    set_control "$tmp" writePrecision 15
    sed -i -E "s/\(20 8 8\)/($nx $ny $nz)/" "$tmp/system/blockMeshDict"
    grep -qF "($nx $ny $nz)" "$tmp/system/blockMeshDict" ||
        step_failed "scale the blockMesh background" "no (20 8 8) block in $tmp/system/blockMeshDict"
    run_step "$tmp" surfaceFeatureExtract
    run_step "$tmp" blockMesh
    run_step "$tmp" snappyHexMesh -overwrite
    # checkMesh exits non-zero when checks fail; only a missing verdict is an error.
    (cd "$tmp" && checkMesh </dev/null >log.checkMesh 2>&1) || true
    [[ -n "$(checkmesh_verdict "$tmp/log.checkMesh")" ]] ||
        step_failed "checkMesh of the x$factor mesh" "no verdict in $tmp/log.checkMesh"
    mv -- "$tmp" "$dir"
    say "wrote $dir ($(checkmesh_verdict "$dir/log.checkMesh"))"
}

#! patch_names <case>: the patch names in constant/polyMesh/boundary, one a line.
patch_names() {
    awk '
        depth == 1 && NF == 1 && $1 !~ /[{}();]/ { name = $1 }
        /\{/ { depth++; if (depth == 2 && name != "") print name; name = "" }
        /\}/ { depth-- }
        /^\($/ && depth == 0 { depth = 1 }
    ' "$1/constant/polyMesh/boundary"
}

#! bike_group <case>: prints "motorBikeGroup" when every motorBike_* patch is in that
#! group (inGroups in constant/polyMesh/boundary), nothing otherwise.
bike_group() {
    awk '
        depth == 1 && NF == 1 && $1 !~ /[{}();]/ { name = $1 }
        /\{/ { depth++ }
        depth == 2 && name ~ /^motorBike_/ && /inGroups/ && /motorBikeGroup/ { grouped[name] = 1 }
        /\}/ { depth--; if (depth == 1) { if (name ~ /^motorBike_/) { n++; if (!(name in grouped)) missing++ } name = "" } }
        /^\($/ && depth == 0 { depth = 1 }
        END { if (n > 0 && missing == 0) print "motorBikeGroup" }
    ' "$1/constant/polyMesh/boundary"
}

# ---------------------------------------------------------------------------------------
# Run cases

#! copy_case <src> <dst>: the mesh (constant/polyMesh without sets), fvSchemes, fvSolution
#! and a one-step controlDict (no function objects; the source's writeFormat).
copy_case() {
    local src=$1 dst=$2 format
    mkdir -p "$dst/constant" "$dst/system"
    cp -r "$src/constant/polyMesh" "$dst/constant/"
    rm -rf "$dst/constant/polyMesh/sets"
    cp "$src/system/fvSchemes" "$src/system/fvSolution" "$dst/system/"
    chmod -R u+w "$dst"
    format=$(awk '$1 == "writeFormat" { sub(/;.*/, "", $2); print $2 }' "$src/system/controlDict")
    {
        foam_header dictionary system controlDict
        cat <<DICT
application     moveMesh;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         1;
deltaT          1;
writeControl    timeStep;
writeInterval   1;
purgeWrite      0;
writeFormat     ${format:-binary};
writePrecision  15;
writeCompression off;
timeFormat      general;
timePrecision   6;
runTimeModifiable false;
DICT
    } >"$dst/system/controlDict"
}

#! make_movemesh_case <src> <dst> <lift>: copy_case plus constant/dynamicMeshDict,
#! 0/pointDisplacement, uncorrected laplacian and a cellDisplacement solver.
make_movemesh_case() {
    local src=$1 dst=$2 lift=$3 group bike_key diffusivity_patches patch
    copy_case "$src" "$dst"
    group=$(bike_group "$dst")
    if [[ -n "$group" ]]; then
        bike_key=$group diffusivity_patches=$group
    else
        bike_key='"motorBike_.*"'
        diffusivity_patches=$(patch_names "$dst" | grep '^motorBike_' | tr '\n' ' ')
        diffusivity_patches=${diffusivity_patches% }
        [[ -n "$diffusivity_patches" ]] || step_failed "make the moveMesh case" "no motorBike_* patches in $dst"
    fi
    {
        foam_header dictionary constant dynamicMeshDict
        cat <<DICT
dynamicFvMesh       dynamicMotionSolverFvMesh;
motionSolverLibs    ("libfvMotionSolvers.so");
motionSolver        displacementLaplacian;
displacementLaplacianCoeffs
{
    diffusivity     inverseDistance ($diffusivity_patches);
}
DICT
    } >"$dst/constant/dynamicMeshDict"

    mkdir -p "$dst/0"
    {
        foam_header pointVectorField 0 pointDisplacement
        cat <<DICT
dimensions      [0 1 0 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    $bike_key
    {
        type    fixedValue;
        value   uniform (0 0 $lift);
    }
DICT
        while read -r patch; do
            [[ $patch == motorBike_* ]] && continue
            printf '    %s\n    {\n        type    fixedValue;\n        value   uniform (0 0 0);\n    }\n' "$patch"
        done < <(patch_names "$dst")
        echo "}"
    } >"$dst/0/pointDisplacement"

    local schemes=$dst/system/fvSchemes solution=$dst/system/fvSolution
    sed -i -E '/^laplacianSchemes/,/^\}/ s/^( *default ).*;/\1Gauss linear uncorrected;/' "$schemes"
    grep -qE '^ *default +Gauss linear uncorrected;' "$schemes" ||
        step_failed "make the moveMesh case" "could not set laplacianSchemes in $schemes"
    awk '
        /^solvers/ { in_solvers = 1 }
        { print }
        in_solvers && /^\{/ {
            print "    cellDisplacement"
            print "    {"
            print "        solver          GAMG;"
            print "        smoother        GaussSeidel;"
            print "        tolerance       1e-8;"
            print "        relTol          0;"
            print "        minIter         25;"
            print "    }"
            in_solvers = 0
        }' "$solution" >"$solution.tmp"
    mv "$solution.tmp" "$solution"
    grep -q '^    cellDisplacement$' "$solution" ||
        step_failed "make the moveMesh case" "no 'solvers' dictionary in $solution"
}

#! make_morphmesh_case <src> <dst> <lift> [<conflict rule>]: copy_case plus system/morphDict.
make_morphmesh_case() {
    local src=$1 dst=$2 lift=$3 rbf_line="" conflicts_line=""
    [[ -z "$rbf_keys" ]] || rbf_line="rbf { $rbf_keys }"
    [[ -z "${4:-}" ]] || conflicts_line="conflicts $4;"
    copy_case "$src" "$dst"
    cat >"$dst/system/morphDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }
method rbf;
$conflicts_line
$extra_keys
$rbf_line
boundary
{
    "motorBike_.*" { type translate; vector (0 0 $lift); }
    default        { type fixed; }
}
DICT
}

#! run_timed <dir> <tool> <command...>: runs the command in <dir> under /usr/bin/time -v,
#! output to <dir>/log.<tool>, time's report to <dir>/time.<tool>. Never fails; sets
#! run_status, run_wall (s), run_cpu (user + system s) and run_rss_mb.
run_timed() {
    local dir=$1 tool=$2
    shift 2
    say "running $tool in $dir (log: $dir/log.$tool)"
    run_status=0
    # The case was copied just before: its pages go to the disk first, so that neither
    # tool's time includes the kernel writing back the copy (on this 2-core machine that
    # took a core for part of a one-second morph).
    sync
    (cd "$dir" && /usr/bin/time -v -o "time.$tool" "$@" </dev/null >"log.$tool" 2>&1) || run_status=$?
    [[ -s "$dir/time.$tool" ]] || step_failed "time $tool" "/usr/bin/time wrote no report ($dir/time.$tool)"
    read -r run_wall run_cpu run_rss_mb < <(awk '
        /Elapsed \(wall clock\) time/ {
            n = split($NF, t, ":"); wall = 0
            for (i = 1; i <= n; i++) wall = wall * 60 + t[i]
        }
        /User time \(seconds\)/   { cpu += $NF }
        /System time \(seconds\)/ { cpu += $NF }
        /Maximum resident set size \(kbytes\)/ { rss = $NF / 1024 }
        END { printf "%.2f %.2f %.1f\n", wall, cpu, rss }' "$dir/time.$tool")
    say "  $tool: exit $run_status, wall ${run_wall} s, cpu ${run_cpu} s, peak RSS ${run_rss_mb} MB"
}

#! checkmesh_numbers <log>: the numbers of one checkMesh report, tab-separated:
#! failed checks, failed check names (comma-separated), wrongly oriented faces, negative
#! volume cells, max non-orthogonality, severely non-orthogonal faces (> 70 degrees), max
#! skewness, highly skewed faces, min volume, points, cells. "NA" for what the log does
#! not hold.
checkmesh_numbers() {
    awk '
        function num(s) { sub(/[.,;]+$/, "", s); return s }
        BEGIN { failed = pyr = neg = nonortho = nsevere = skew = nskew = minvol = points = cells = "NA"; names = "" }
        /^ *points: /  { points = $2 }
        /^ *cells: /   { cells = $2 }
        /^Mesh OK\./   { failed = 0 }
        /^Failed [0-9]+ mesh checks/ { failed = $2 }
        /Face pyramids OK/ { pyr = 0 }
        /\*\*\*Error in face pyramids:/ { for (i = 1; i < NF; i++) if ($i == "pyramids:") pyr = $(i + 1) }
        /Min volume = / { for (i = 1; i < NF; i++) if ($i == "volume" && $(i + 1) == "=") { minvol = num($(i + 2)); break }; neg = 0 }
        /Number of negative volume cells:/ {
            neg = $NF
            for (i = 1; i < NF; i++) if ($i == "volume:") minvol = num($(i + 1))
        }
        /Mesh non-orthogonality Max:/ { nonortho = $4; nsevere = 0 }
        /Number of severely non-orthogonal/ { nsevere = num($NF) }
        /Max skewness = / {
            for (i = 1; i < NF; i++) if ($i == "=") skew = num($(i + 1))
            nskew = /highly skew faces/ ? num($5) : 0
        }
        /\*\*\*/ {
            line = $0; sub(/^.*\*\*\*/, "", line)
            if (line ~ /^Error in face pyramids/)                 name = "pyramids"
            else if (line ~ /^Zero or negative cell volume/)      name = "volumes"
            else if (line ~ /^Max skewness/)                      name = "skewness"
            else if (line ~ /^Number of non-orthogonality errors/) name = "nonOrthogonality"
            else if (line ~ /^Zero or negative face area/)        name = "faceArea"
            else if (line ~ /^High aspect ratio/)                 name = "aspectRatio"
            else if (line ~ /^Open cells/)                        name = "openCells"
            else if (line ~ /openness/)                           name = "openness"
            else { name = line; sub(/[:=,.(].*$/, "", name); gsub(/[^A-Za-z0-9]+/, "_", name) }
            if (index("," names ",", "," name ",") == 0) names = names (names == "" ? "" : ",") name
        }
        END { printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", failed, (names == "" ? "-" : names),
                     pyr, neg, nonortho, nsevere, skew, nskew, minvol, points, cells }' "$1"
}

#! check_result <dir>: checkMesh -latestTime on the moved mesh (time 1) into
#! <dir>/log.checkMesh; prints checkmesh_numbers, or NA fields when nothing was written.
check_result() {
    local dir=$1
    if [[ ! -e "$dir/1/polyMesh/points" && ! -e "$dir/1/polyMesh/points.gz" ]]; then
        printf 'NA\t-\tNA\tNA\tNA\tNA\tNA\tNA\tNA\tNA\tNA\n'
        return 0
    fi
    (cd "$dir" && checkMesh -latestTime </dev/null >log.checkMesh 2>&1) || true
    [[ -n "$(checkmesh_verdict "$dir/log.checkMesh")" ]] ||
        step_failed "checkMesh -latestTime" "no verdict in $dir/log.checkMesh"
    grep -q '^Time = 1$' "$dir/log.checkMesh" ||
        step_failed "checkMesh -latestTime" "it did not check time 1 (see $dir/log.checkMesh)"
    checkmesh_numbers "$dir/log.checkMesh"
}

#! max_displacement <dir>: the largest point displacement |x(1) - x(constant)| of the
#! moved mesh (ascii or binary points, optionally .gz), or NA when nothing was written.
#! Shows how far the motion spreads: the prescribed lift is the largest boundary motion.
max_displacement() {
    "$python" - "$1" <<'PY'
import gzip, os, re, sys
import numpy as np
def points(d):
    for name in ("points", "points.gz"):
        p = os.path.join(d, "polyMesh", name)
        if os.path.exists(p):
            data = (gzip.open if name.endswith(".gz") else open)(p, "rb").read()
            break
    else:
        return None
    end = data.index(b"}", data.index(b"FoamFile"))
    binary = re.search(rb"format\s+binary", data[:end]) is not None
    m = re.compile(rb"\n\s*(\d+)\s*\(").search(data, end)
    n, off = int(m.group(1)), m.end()
    if binary:
        return np.frombuffer(data, "<f8", 3 * n, off).reshape(n, 3)
    text = data[off:].replace(b"(", b" ").replace(b")", b" ")
    return np.array(text.split()[:3 * n], dtype=float).reshape(n, 3)
case = sys.argv[1]
x0, x1 = points(os.path.join(case, "constant")), points(os.path.join(case, "1"))
print("NA" if x0 is None or x1 is None else f"{np.linalg.norm(x1 - x0, axis=1).max():.6g}")
PY
}

csv_header="study,mesh,points,cells,lift_fraction,lift_m,tool,exit_status,wall_s,cpu_s,peak_rss_mb,failed_checks,failed_check_names,baseline_failed_checks,baseline_failed_check_names,wrongly_oriented_faces,negative_volume_cells,max_non_orthogonality,severely_non_orthogonal_faces,max_skewness,highly_skewed_faces,min_volume,max_displacement_m,read_s,fit_s,evaluate_s,check_s,untangle_s,write_s,roofline_s,centres,global_residual,jump_constraints,json_wall_s,note"

#! run_tool <study> <mesh label> <source case> <run dir> <fraction> <tool> <baseline numbers>:
#! makes the case, runs the tool timed, checks its result and appends a CSV row.
run_tool() {
    local study=$1 label=$2 src=$3 run=$4 fraction=$5 tool=$6 baseline=$7 lift note="" json_wall=NA
    local dir=$run/$tool
    lift=$(lift_of "$fraction")
    mkdir -p "$dir"
    case $tool in
        moveMesh)
            make_movemesh_case "$src" "$dir" "$lift"
            run_timed "$dir" moveMesh moveMesh
            [[ $run_status -eq 0 ]] || note="moveMesh failed (exit $run_status), see $dir/log.moveMesh"
            if grep -q "Cannot find any patch or group" "$dir/log.moveMesh"; then
                step_failed "moveMesh" "inverseDistance patches not found (see $dir/log.moveMesh)"
            fi
            ;;
        morphMesh)
            make_morphmesh_case "$src" "$dir" "$lift"
            # The natural morph as a user runs it (the time the ratio uses), then the same
            # morph again with -json for its stage times: -json adds the scaled Jacobian to
            # both checks (~0.15 s on the motorBike), and this second run follows the first
            # back to back, so only its stages are reported.
            run_timed "$dir" morphMesh "$morph_mesh" -case "$dir"
            local plain_status=$run_status plain_wall=$run_wall plain_cpu=$run_cpu
            local plain_rss=$run_rss_mb
            rm -rf "$dir/1"
            run_timed "$dir" morphMeshJson "$morph_mesh" -case "$dir" -json "$dir/morph.json"
            json_wall=$run_wall
            [[ $run_status -eq $plain_status ]] ||
                note="-json run exit $run_status against $plain_status without; "
            run_status=$plain_status run_wall=$plain_wall run_cpu=$plain_cpu run_rss_mb=$plain_rss
            case $run_status in
                0) ;;
                3) note+="refused: $(morph_refusal "$dir")" ;;
                *) note+="morphMesh failed (exit $run_status), see $dir/log.morphMesh" ;;
            esac
            ;;
        moveMeshSameMotion)
            # moveMesh given morphMesh's own boundary motion (the default row's result, point
            # by point, floor held where the tyres touch it): the two tools at equal motion.
            local morphed=$run/morphMesh
            if [[ ! -d $morphed/1/polyMesh ]]; then
                note="no morphMesh result to take the motion from"
                run_status=NA run_wall=NA run_cpu=NA run_rss_mb=NA
            else
                make_movemesh_case "$src" "$dir" "$lift"
                PYTHONPATH=$python_dir "$python" "$script_dir/same_boundary_motion.py" write \
                    "$dir" "$morphed" "$dir/0/pointDisplacement" ||
                    step_failed "moveMeshSameMotion" "could not write $dir/0/pointDisplacement"
                run_timed "$dir" moveMesh moveMesh
                [[ $run_status -eq 0 ]] || note="moveMesh failed (exit $run_status), see $dir/log.moveMesh"
                local mismatch
                mismatch=$(PYTHONPATH=$python_dir "$python" "$script_dir/same_boundary_motion.py" \
                    mismatch "$dir" "$dir" "$morphed" | tr '\n' ' ')
                note+="boundary points differ from morphMesh's by at most ${mismatch%% *} m (${mismatch#* }x the largest displacement)"
            fi
            ;;
        morphMeshBikeWins)
            # The boundary motion moveMesh makes: the bike's prescription wins at the points
            # the tyres share with lowerWall (the first morphDict entry: conflicts first).
            make_morphmesh_case "$src" "$dir" "$lift" first
            run_timed "$dir" morphMesh "$morph_mesh" -case "$dir"
            case $run_status in
                0) ;;
                3) note+="refused: $(morph_refusal "$dir")" ;;
                *) note+="morphMesh failed (exit $run_status), see $dir/log.morphMesh" ;;
            esac
            ;;
    esac
    [[ -z "$note" ]] || say "  $tool: $note"
    local numbers
    numbers=$(check_result "$dir")
    local failed names pyr neg nonortho nsevere skew nskew minvol
    IFS=$'\t' read -r failed names pyr neg nonortho nsevere skew nskew minvol _ _ <<<"$numbers"
    local b_failed b_names b_points b_cells max_disp stages
    max_disp=$(max_displacement "$dir")
    stages=$(morph_stages "$dir" "$tool")
    IFS=$'\t' read -r b_failed b_names _ _ _ _ _ _ _ b_points b_cells <<<"$baseline"
    note=${note//\"/\'}
    printf '%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,"%s",%s,"%s",%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,"%s"\n' \
        "$study" "$label" "$b_points" "$b_cells" "$fraction" "$lift" "$tool" "$run_status" \
        "$run_wall" "$run_cpu" "$run_rss_mb" "$failed" "$names" "$b_failed" "$b_names" \
        "$pyr" "$neg" "$nonortho" "$nsevere" "$skew" "$nskew" "$minvol" "$max_disp" "$stages" \
        "$json_wall" "$note" >>"$csv"
}

#! morph_stages <dir> <tool>: morphMesh's stage times from its -json document (read, fit,
#! evaluate, check, untangle, write), the roofline (read + write: the I/O no morph avoids),
#! the global part's centres, its residual relative to the largest prescribed displacement
#! on the constraints it fits and the number of jump constraints it leaves to the local
#! correction (last accepted step), comma-separated; NA for moveMesh or a missing document.
morph_stages() {
    if [[ $2 != morphMesh || ! -s "$1/morph.json" ]]; then
        echo "NA,NA,NA,NA,NA,NA,NA,NA,NA,NA"
        return 0
    fi
    "$python" - "$1/morph.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
t = j.get("timings", {})
stage = [t.get(k) for k in ("read", "fit", "evaluate", "check", "untangle", "write")]
roof = t["read"] + t["write"] if "read" in t and "write" in t else None
steps = [s for s in j.get("steps", []) if s.get("accepted")]
residual = steps[-1].get("globalResidual") if steps else None
jumps = steps[-1].get("jumpConstraints") if steps else None
fields = stage + [roof, j.get("centres"), residual, jumps]
print(",".join("NA" if v is None else (f"{v:.4g}" if isinstance(v, float) else str(v)) for v in fields))
PY
}

#! morph_refusal <dir>: morphMesh's reason for refusing (from morph.json, else its log).
morph_refusal() {
    local reason=""
    if [[ -s "$1/morph.json" ]]; then
        reason=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1])).get("refusal",""))' \
                 "$1/morph.json" 2>/dev/null || true)
    fi
    [[ -n "$reason" ]] || reason=$(grep -iE "refus|negative|inverted" "$1/log.morphMesh" | head -n 1 || true)
    echo "${reason:-see log.morphMesh}" | tr '\n' ' ' | sed 's/ *$//'
}

#! baseline_numbers <case> <run dir>: checkMesh numbers of the unmoved mesh, from the
#! meshing's log.checkMesh (copied to <run dir>/baseline.log.checkMesh).
baseline_numbers() {
    cp "$1/log.checkMesh" "$2/baseline.log.checkMesh"
    checkmesh_numbers "$2/baseline.log.checkMesh"
}

# ---------------------------------------------------------------------------------------
# Report

#! report <csv> <prefix> <title> [plot]: prints the table per run (with the time and memory
#! ratios morphMesh/moveMesh) and writes <prefix>.md and <prefix>.json; with "plot" also
#! <prefix>.png (time against points, both tools, log-log).
report() {
    "$python" - "$@" <<'PY'
import csv, json, math, sys
path, prefix, title = sys.argv[1:4]
plot = len(sys.argv) > 4 and sys.argv[4] == "plot"
rows = list(csv.DictReader(open(path)))
meta = json.load(open(prefix + ".meta.json"))

def val(s):
    if s in ("NA", ""):
        return None
    try:
        return int(s)
    except ValueError:
        try:
            return float(s)
        except ValueError:
            return s

def show(s, digits=None):
    if s in ("NA", ""):
        return "n/a"
    return f"{float(s):.{digits}g}" if digits else s

def failed_vs_baseline(r):
    if r["failed_checks"] == "NA":
        return "n/a (nothing written)"
    base = set(r["baseline_failed_check_names"].split(",")) - {"-"}
    new = [n for n in r["failed_check_names"].split(",") if n not in base and n != "-"]
    s = f'{r["failed_checks"]} (baseline {r["baseline_failed_checks"]})'
    return s + (" new: " + ", ".join(new) if new else "")

cols = ["tool", "exit", "wall s", "peak RSS MB", "failed checks vs baseline",
        "wrongly oriented faces", "negative volumes", "max non-ortho", "faces > 70 deg",
        "max skewness", "skewed faces", "min volume", "max displacement m"]
groups = {}
for r in rows:
    groups.setdefault((r["mesh"], r["lift_fraction"]), []).append(r)

md = [f"# {title}", "",
      f'OpenFOAM {meta["openfoam"]}, {meta["nproc"]} cores (OMP_NUM_THREADS={meta["omp_num_threads"]}), '
      f'meshMorph {meta["commit"]}, {meta["date"]}. Lift = fraction x bike height '
      f'({meta["bike_height_m"]} m). checkMesh on each result; baseline = the unmoved mesh.', ""]
for (mesh, frac), rs in groups.items():
    r0 = rs[0]
    md.append(f'## {mesh}: {r0["points"]} points, {r0["cells"]} cells; lift {float(frac) * 100:g}% = {r0["lift_m"]} m')
    md.append("")
    md.append("| " + " | ".join(cols) + " |")
    md.append("|" + "|".join("---" for _ in cols) + "|")
    for r in rs:
        cells = [r["tool"], r["exit_status"], r["wall_s"], r["peak_rss_mb"], failed_vs_baseline(r),
                 show(r["wrongly_oriented_faces"]), show(r["negative_volume_cells"]),
                 show(r["max_non_orthogonality"], 4), show(r["severely_non_orthogonal_faces"]),
                 show(r["max_skewness"], 4),
                 show(r["highly_skewed_faces"]), show(r["min_volume"], 4),
                 show(r["max_displacement_m"], 4)]
        md.append("| " + " | ".join(cells) + " |")
    by_tool = {r["tool"]: r for r in rs}
    if "moveMesh" in by_tool and "morphMesh" in by_tool:
        a, b = by_tool["morphMesh"], by_tool["moveMesh"]
        t = float(a["wall_s"]) / float(b["wall_s"]) if float(b["wall_s"]) > 0 else math.nan
        m = float(a["peak_rss_mb"]) / float(b["peak_rss_mb"]) if float(b["peak_rss_mb"]) > 0 else math.nan
        md.append("")
        md.append(f"morphMesh / moveMesh: time {t:.2f}x, memory {m:.2f}x"
                  + ("" if a["exit_status"] == "0" else f' (morphMesh exit {a["exit_status"]}: no mesh written)'))
        if a.get("json_wall_s") not in (None, "", "NA") and float(b["wall_s"]) > 0:
            md.append("")
            md.append(f'morphMesh -json (the scaled Jacobian added to both checks; run right after the '
                      f'first): {a["json_wall_s"]} s, {float(a["json_wall_s"]) / float(b["wall_s"]):.2f}x moveMesh')
    if "morphMesh" in by_tool and by_tool["morphMesh"]["read_s"] not in ("NA", ""):
        a = by_tool["morphMesh"]
        md.append("")
        md.append("morphMesh stages [s]: " + ", ".join(f'{k} {a[k + "_s"]}' for k in
                  ("read", "fit", "evaluate", "check", "untangle", "write"))
                  + f'; roofline (read + write alone) {a["roofline_s"]} s'
                  + (f' = {float(a["roofline_s"]) / float(by_tool["moveMesh"]["wall_s"]):.3f}x moveMesh'
                     if "moveMesh" in by_tool and float(by_tool["moveMesh"]["wall_s"]) > 0 else "")
                  + f'; global RBF: {a["centres"]} centres, residual {a["global_residual"]} of the largest prescribed '
                  + f'displacement on the constraints it fits, {a["jump_constraints"]} jump constraints left to the correction')
    notes = [f'{r["tool"]}: {r["note"]}' for r in rs if r["note"]]
    if notes:
        md.append("")
        md += [f"- {n}" for n in notes]
    md.append("")
if plot:
    md += ["## Summary: time and memory against mesh size", "",
           "| mesh | points | cells | moveMesh wall s | moveMesh RSS MB | morphMesh exit | morphMesh wall s | morphMesh RSS MB | time ratio | memory ratio |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for (mesh, frac), rs in groups.items():
        t = {r["tool"]: r for r in rs}
        mv, mm = t.get("moveMesh"), t.get("morphMesh")
        def get(r, k):
            return r[k] if r else "n/a"
        ratio = lambda k: (f'{float(mm[k]) / float(mv[k]):.2f}' if mv and mm and float(mv[k]) > 0 else "n/a")
        md.append(f'| {mesh} | {rs[0]["points"]} | {rs[0]["cells"]} | {get(mv, "wall_s")} | {get(mv, "peak_rss_mb")} | '
                  f'{get(mm, "exit_status")} | {get(mm, "wall_s")} | {get(mm, "peak_rss_mb")} | {ratio("wall_s")} | {ratio("peak_rss_mb")} |')
    md.append("")
text = "\n".join(md)
print(text)
open(prefix + ".md", "w").write(text)
json.dump({"meta": meta, "runs": [{k: val(v) if k not in ("note", "failed_check_names",
           "baseline_failed_check_names", "mesh", "study", "tool") else v for k, v in r.items()}
           for r in rows]}, open(prefix + ".json", "w"), indent=2)
print(f"wrote {prefix}.md, {prefix}.json, {path}")

if plot:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for tool, marker in (("moveMesh", "o"), ("morphMesh", "s")):
        pts = sorted((int(r["points"]), float(r["wall_s"]), r["exit_status"]) for r in rows if r["tool"] == tool)
        if not pts:
            continue
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=tool)
        for x, y, status in pts:
            if status != "0":
                ax.annotate(f"exit {status}", (x, y), textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.set_xlabel("mesh points")
    ax.set_ylabel("wall time [s]")
    ax.set_title("motorBike, bike lifted 5%: wall time against mesh size")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=120)
    print(f"wrote {prefix}.png")
PY
}

#! write_meta <file>: the run's context as JSON.
write_meta() {
    local commit
    commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
    if [[ -n "$(git -C "$root" status --porcelain --untracked-files=no 2>/dev/null)" ]]; then commit+="+dirty"; fi
    local foam_version morph_built=unknown
    if [[ -x "$morph_mesh" ]]; then morph_built=$(date -r "$morph_mesh" +%FT%T); fi
    # shellcheck disable=SC2016 # ${Version} is dpkg-query's field, not a shell variable
    foam_version=$(dpkg-query -W -f='${Version}' openfoam 2>/dev/null || echo unknown)
    "$python" - "$1" "$commit" "$(nproc)" "${OMP_NUM_THREADS:-unset}" "$bike_height" \
        "$cache" "$morph_mesh" "$foam_version" "$morph_built" <<'PY'
import json, sys, datetime
f, commit, nproc, omp, h, cache, morph, foam, built = sys.argv[1:10]
json.dump({"commit": commit, "nproc": int(nproc), "omp_num_threads": omp,
           "bike_height_m": float(h), "cache": cache, "morphMesh": morph,
           "morphMesh_built": built,
           "openfoam": "v1912 (Debian " + foam + ")" if foam != "unknown" else "unknown",
           "date": datetime.datetime.now().isoformat(timespec="seconds")},
          open(f, "w"), indent=2)
PY
}

# ---------------------------------------------------------------------------------------
# Main

need_tool moveMesh checkMesh
[[ -x /usr/bin/time ]] || die "/usr/bin/time not found (apt-get install time)"
[[ -x $python ]] || die "$python not found"
tools=(moveMesh morphMesh)
if [[ ! -x "$morph_mesh" ]]; then
    say "WARNING: morphMesh not found at $morph_mesh (build it or pass -morphMesh): only moveMesh runs"
    tools=(moveMesh)
    results_partial "no morphMesh at $morph_mesh"
fi
mkdir -p "$out/runs"
build_full_case "$cache"

if ! $scaling; then
    csv=$out/results.csv
    echo "$csv_header" >"$csv"
    write_meta "$out/results.meta.json"
    if [[ ${#tools[@]} -gt 1 ]]; then
        if [[ -d $python_dir/meshmorph ]]; then
            tools+=(moveMeshSameMotion)
        else
            say "WARNING: no meshmorph Python module at $python_dir: the moveMeshSameMotion row is left out"
            results_partial "no meshmorph Python module at $python_dir"
        fi
        tools+=(morphMeshBikeWins)
    fi
    for fraction in $lifts; do
        run=$out/runs/lift$fraction
        fresh_run_dir "$run"
        baseline=$(baseline_numbers "$cache" "$run")
        say "lift $fraction x $bike_height m = $(lift_of "$fraction") m (run: $run)"
        for tool in "${tools[@]}"; do
            run_tool lifts "$(basename "$cache")" "$cache" "$run" "$fraction" "$tool" "$baseline"
        done
    done
    report "$csv" "$out/results" "morphMesh vs moveMesh: motorBike bike lifted"
    results_write_report -openfoam motorbike_vs_movemesh "$out/results.md"
else
    need_tool surfaceFeatureExtract blockMesh snappyHexMesh
    "$python" -c 'import matplotlib' 2>/dev/null ||
        die "matplotlib missing for $python (apt-get install python3-matplotlib)"
    csv=$out/scaling.csv
    echo "$csv_header" >"$csv"
    write_meta "$out/scaling.meta.json"
    for factor in $factors; do
        if [[ $factor == 1 || $factor == 1.0 ]]; then
            mesh=$cache
        else
            mesh=$cache-x$factor
            build_scaled_case "$mesh" "$factor"
        fi
        run=$out/runs/scaling-x$factor
        fresh_run_dir "$run"
        baseline=$(baseline_numbers "$mesh" "$run")
        for tool in "${tools[@]}"; do
            run_tool scaling "motorBike x$factor" "$mesh" "$run" 0.05 "$tool" "$baseline"
        done
    done
    report "$csv" "$out/scaling" "morphMesh vs moveMesh: mesh size scaling (bike lifted 5%)" plot
    results_write_report -openfoam motorbike_vs_movemesh_scaling "$out/scaling.md"
fi
