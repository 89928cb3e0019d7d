#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sweep: checkMeshQuality against OpenFOAM v1912's checkMesh on every tutorial of Debian's
# openfoam-examples that can be meshed here, plain and with -allGeometry -allTopology; or,
# with -morph, a morph of every such mesh judged by OpenFOAM's checkMesh.
# Usage: checkmesh_sweep.sh [-cases REGEX] [-out DIR] [-all] [-jobs N] [-keep] [-list]
#                           [-mesh-timeout S] [-check-timeout S] [-checker PATH]
#                           [-morph [-morph-mesh PATH] [-morph-keys ENTRIES] [-fail-on-silent]]
#                           [-results FILE | -no-results] [-help]
#
#   -morph        the morph sweep instead of the checker comparison: on every mesh the
#                 smallest wall patch is scaled by 1% about its centre, everything else
#                 fixed (in 2D within the planes), by morphMesh; then checkMesh on the
#                 result (morph_one_mesh.py). Each mesh ends valid, warned (a new checkMesh
#                 failure that morphMesh named), silent (one it did not: the defect this
#                 sweep hunts), refused (with the reason), crashed or skipped. Output in
#                 build/bench/morph-sweep unless -out; summary.md has the counts and table.
#   -morph-mesh PATH  morphMesh to test (default build/release/applications/...); the
#                 Python module beside it (build/<preset>/python) reads the meshes
#   -fail-on-silent  with -morph: exit 1 when any mesh ends silent or crashed (CI's subset)
#   -morph-keys ENTRIES  with -morph: more top-level morphDict entries, e.g. "jumpSmoothing yes;"
#
#   -cases REGEX  only the tutorials whose path (relative to the tutorials directory,
#                 e.g. incompressible/icoFoam/cavity/cavity) matches REGEX (extended, as [[ =~ ]])
#   -out DIR      output directory (default build/bench/checkmesh-sweep); its cases/ and
#                 summary files are replaced, nothing else in it is touched
#   -all          also the slow meshes: tutorials whose Allrun/Allrun.pre/Allmesh runs
#                 snappyHexMesh, extrudeMesh, extrudeToRegionMesh, extrude2DMesh or
#                 splitMeshRegions (their own script, run through sweep_run_functions.sh)
#   -jobs N       cases at a time (default 1; OpenFOAM's tools run serially)
#   -keep         keep every meshed case copy (default: only those with a mismatch)
#   -list         print the cases that would be run (and the skipped ones), run nothing
#   -mesh-timeout S, -check-timeout S
#                 per-case limits in seconds: meshing (default 600, 1800 with -all) and
#                 each checker run (default 600)
#   -checker PATH checkMeshQuality to test (default build/release/applications/...)
#   -results FILE also write summary.md with the run's context (date, machine, OS, commit,
#                 OpenFOAM, this command line) to FILE (benchmarks/results.sh)
#   -no-results   write no such file. Default: benchmarks/results/checkmesh_sweep.md, or
#                 morph_sweep.md with -morph (checkmesh_sweep_all.md, morph_sweep_all.md
#                 with -all), written only when the sweep ran over every case: no -cases
#                 filter and no -morph-keys; none when MESHMORPH_NO_RESULTS=1 (tests)
#
# Cheap meshes (always): system/blockMeshDict or constant/polyMesh/blockMeshDict (blockMesh),
# system/<region>/blockMeshDict with constant/<region>/ (blockMesh -region),
# system/blockMeshDict.m4 (m4, then blockMesh), a shipped constant[/<region>]/polyMesh, and
# the tutorials whose Allrun converts a shipped mesh (fluentMeshToFoam, star4ToFoam,
# kivaToFoam, ansysToFoam, datToFoam, ...) or runs PDRblockMesh (their Allrun, through
# sweep_run_functions.sh, which stops at the solver). Only the tutorial's blockMeshDict
# itself is meshed: the later steps of its Allrun (topoSet, createBaffles, createPatch, ...)
# are not run in the cheap mode, and the variants (blockMeshDict.coarse, ...) are not used.
# Every other tutorial case is listed in the summary with the reason it was skipped.
#
# For each case: a copy in OUT/cases/<id>/case (symbolic links followed, *.gz unpacked but
# in polyMesh/, a missing controlDict made from controlDict.template/.orig), the mesh step(s)
# (logs in OUT/cases/<id>/), then for every polyMesh found in the copy (regions and
# sub-cases included) checkMesh and checkMeshQuality -writeSets (so that both print the
# "<<Writing N ... to set" lines), plain and with -allGeometry -allTopology, with -region
# for a region and -latestTime when a time directory has a mesh; logs in
# OUT/cases/<id>/meshes/<mesh>/. compare_checkmesh.py compares each pair of reports: the
# lines from "Time = " on (the start-up before it, banner, header, Create time/mesh, is not
# compared), without the lines that differ by nature (timings, End, ...), word by word, every
# number to 1e-6 relative (see its header), and the verdicts ("Mesh OK." /
# "Failed N mesh checks.").
# OUT/summary.md, summary.csv (one row per mesh and mode), summary.json; the Markdown is also
# printed. Exit status: 0 when the sweep ran (mismatches included), 1 on a script error,
# 2 on a usage error.
#
# OpenFOAM's tools need WM_PROJECT_DIR (Debian: /usr/share/openfoam, set by lib.sh).
set -euo pipefail
# shellcheck source=scripts/openfoam/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(cd "$script_dir/../.." && pwd)
python=/usr/bin/python3
# shellcheck source=benchmarks/results.sh
source "$repo_dir/benchmarks/results.sh"   # results_init, results_write, ...
results_init "$@"

usage() {
    sed -n '3,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
}
usage_error() {
    echo "$foam_script_name: error: $*" >&2
    echo "usage: $foam_script_name [-cases REGEX] [-out DIR] [-all] [-jobs N] [-keep] [-list]" \
         "[-mesh-timeout S] [-check-timeout S] [-checker PATH] [-results FILE | -no-results] [-help]" >&2
    exit 2
}

cases_regex='' out_dir='' all=0 jobs=1 keep=0 list=0 morph=0 fail_on_silent=0 morph_keys=
morph_mesh=$repo_dir/build/release/applications/morphMesh/morphMesh
mesh_timeout='' check_timeout=600 checker=$repo_dir/build/release/applications/checkMeshQuality/checkMeshQuality
while [[ $# -gt 0 ]]; do
    case "$1" in
    -h | -help | --help) usage; exit 0 ;;
    -cases) [[ $# -ge 2 ]] || usage_error "-cases needs a REGEX"; cases_regex=$2; shift ;;
    -out) [[ $# -ge 2 ]] || usage_error "-out needs a DIR"; out_dir=$2; shift ;;
    -all) all=1 ;;
    -jobs) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage_error "-jobs needs a positive integer"
           jobs=$2; shift ;;
    -keep) keep=1 ;;
    -list) list=1 ;;
    -mesh-timeout) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage_error "-mesh-timeout needs seconds"
                   mesh_timeout=$2; shift ;;
    -check-timeout) [[ $# -ge 2 && $2 =~ ^[1-9][0-9]*$ ]] || usage_error "-check-timeout needs seconds"
                    check_timeout=$2; shift ;;
    -checker) [[ $# -ge 2 ]] || usage_error "-checker needs a PATH"; checker=$2; shift ;;
    -morph) morph=1 ;;
    -fail-on-silent) fail_on_silent=1 ;;
    -morph-keys) [[ $# -ge 2 ]] || usage_error "-morph-keys needs ENTRIES"; morph_keys=$2; shift ;;
    -morph-mesh) [[ $# -ge 2 ]] || usage_error "-morph-mesh needs a PATH"; morph_mesh=$2; shift ;;
    -results) [[ $# -ge 2 ]] || usage_error "-results needs a FILE"; results_file "$2"; shift ;;
    -no-results) results_off ;;
    *) usage_error "unknown option '$1'" ;;
    esac
    shift
done
[[ -n $mesh_timeout ]] || mesh_timeout=$((all ? 1800 : 600))
[[ -z $cases_regex ]] || results_partial "-cases \"$cases_regex\""
[[ -z $morph_keys ]] || results_partial "-morph-keys \"$morph_keys\""
if [[ -z $out_dir ]]; then
    out_dir=$repo_dir/build/bench/checkmesh-sweep
    [[ $morph == 0 ]] || out_dir=$repo_dir/build/bench/morph-sweep
fi
if [[ -n $cases_regex ]]; then
    # a bad regex is a usage error, not "no case matched"
    rc=0
    [[ "" =~ $cases_regex ]] || rc=$?
    [[ $rc -le 1 ]] || usage_error "-cases: invalid regular expression '$cases_regex'"
fi

tutorials=$(foam_tutorials)
need_tool blockMesh checkMesh m4 timeout foamDictionary
[[ -x $python ]] || die "$python not found"
if [[ $list == 0 && $morph == 1 ]]; then
    [[ -x $morph_mesh ]] || die "morphMesh not found at '$morph_mesh' (build it: cmake --preset release && cmake --build build/release -j2)"
    morph_mesh=$(cd "$(dirname "$morph_mesh")" && pwd)/$(basename "$morph_mesh")
    morph_python_path=$(cd "$(dirname "$morph_mesh")/../.." && pwd)/python
    compgen -G "$morph_python_path/meshmorph/_core*.so" > /dev/null ||
        die "no Python module in $morph_python_path (build its target meshmorph_python: cmake --build $(dirname "$morph_python_path") --target meshmorph_python)"
elif [[ $list == 0 ]]; then
    [[ -x $checker ]] || die "checkMeshQuality not found at '$checker' (build it: cmake --preset release && cmake --build build/release -j2 --target checkMeshQuality)"
    checker=$(cd "$(dirname "$checker")" && pwd)/$(basename "$checker")
fi

# ---------------------------------------------------------------------------------------
# Discovery: "<id>\t<relative path>\t<method>\t<detail>" for the cases to run,
# "<relative path>\t<reason>" for the skipped ones.

mesh_tools_re='snappyHexMesh|extrudeMesh|extrudeToRegionMesh|extrude2DMesh|splitMeshRegions'
foamy_re='foamyHexMesh|foamyQuadMesh'
convert_re='fluentMeshToFoam|fluent3DMeshToFoam|star4ToFoam|kivaToFoam|ansysToFoam|datToFoam|gambitToFoam|ideasUnvToFoam|gmshToFoam|plot3dToFoam|PDRblockMesh'

#! mesh_scripts <dir>: the tutorial's own scripts that may make its mesh.
mesh_scripts() {
    local f
    for f in "$1"/Allrun "$1"/Allrun-serial "$1"/Allrun.pre "$1"/Allrun-pre "$1"/Allrun.mesh \
             "$1"/Allmesh "$1"/makeMesh "$1"/Allrun-parallel; do
        [[ -f $f ]] && echo "$f"
    done
    return 0
}

#! mesh_script_uses <dir> <regex>: prints the first tool of <regex> run by its scripts
#! (commented-out lines ignored).
mesh_script_uses() {
    local scripts
    mapfile -t scripts < <(mesh_scripts "$1")
    [[ ${#scripts[@]} -gt 0 ]] || return 1
    grep -hv '^[[:space:]]*#' "${scripts[@]}" | grep -oE "\\b($2)\\b" | head -n 1
}

#! m4_source <dir>: the m4 input its Allrun turns into system/blockMeshDict, if any.
m4_source() {
    local scripts
    mapfile -t scripts < <(mesh_scripts "$1")
    [[ ${#scripts[@]} -gt 0 ]] || return 1
    grep -hv '^[[:space:]]*#' "${scripts[@]}" |
        sed -nE 's#^[[:space:]]*m4[[:space:]]+(<[[:space:]]*)?(\./)?(system/[^[:space:]]+\.m4)[[:space:]]*>[[:space:]]*(\./)?system/blockMeshDict[[:space:]]*$#\3#p' |
        head -n 1
}

#! missing_include <system dir>: the first file its blockMeshDict #includes that is not
#! shipped (written by the Allrun), if any.
missing_include() {
    local f=$1/blockMeshDict
    [[ -f $f ]] || f=$f.gz
    # (not the C++ #include lines of #codeStream code, between #{ and #})
    zcat -f "$f" | awk '/#\{/ { code = 1 } !code { print } /#\}/ { code = 0 }' |
        sed -nE 's/^[[:space:]]*#include[[:space:]]+"([^"$]+)".*/\1/p' |
    while IFS= read -r inc; do
        [[ $inc == /* ]] || inc=$1/$inc
        if [[ ! -e $inc && ! -e $inc.gz ]]; then
            echo "${inc##*/}"
            break
        fi
    done
}

#! mesh_parent <relative path>: "<ancestor>\t<tool>" when an ancestor directory's own
#! scripts run a slow mesh tool (the mesh of this sub-case is made there).
mesh_parent() {
    local up=$1 tool
    while [[ $up == */* ]]; do
        up=${up%/*}
        if tool=$(mesh_script_uses "$tutorials/$up" "$mesh_tools_re") && [[ -n $tool ]]; then
            printf '%s\t%s\n' "$up" "$tool"
            return 0
        fi
    done
    return 1
}

#! driver_script <dir>: the script to run for an Allrun-made mesh.
driver_script() {
    local f
    for f in Allrun-serial Allrun Allrun.mesh Allmesh Allrun.pre Allrun-pre; do
        [[ -f $1/$f ]] && { echo "$f"; return 0; }
    done
    return 1
}

case_id() {
    local id=${1//\//+}
    echo "$id@$2"
}

discover() {
    local rel dir reason tool regions r found m4_input parent missing
    local -a scripts
    local -a allrun_units=()
    # directories with a system/ (not through symbolic links: they repeat other tutorials)
    while IFS= read -r rel; do
        [[ -z $cases_regex ]] || [[ $rel =~ $cases_regex ]] || continue
        dir=$tutorials/$rel
        found=0
        if [[ -f $dir/system/blockMeshDict || -f $dir/system/blockMeshDict.gz ]] &&
           missing=$(missing_include "$dir/system") && [[ -n $missing ]] &&
           tool=$(mesh_script_uses "$dir" blockMesh) && [[ -n $tool ]]; then
            # its Allrun writes the #include'd file first
            printf 'run\t%s\t%s\tallrun\t%s (%s)\n' "$(case_id "$rel" allrun)" "$rel" \
                "$(driver_script "$dir")" "blockMesh, #include $missing"
            found=1
        elif [[ -f $dir/system/blockMeshDict || -f $dir/system/blockMeshDict.gz ||
              -f $dir/constant/polyMesh/blockMeshDict || -f $dir/constant/polyMesh/blockMeshDict.gz ]]; then
            printf 'run\t%s\t%s\tblockMesh\t\n' "$(case_id "$rel" blockMesh)" "$rel"
            found=1
        fi
        regions=
        for r in "$dir"/system/*/blockMeshDict "$dir"/system/*/blockMeshDict.gz; do
            [[ -f $r ]] || continue
            r=${r%/blockMeshDict*}
            r=${r##*/}
            [[ -d $dir/constant/$r ]] && regions+="${regions:+ }$r"
        done
        if [[ -n $regions ]]; then
            printf 'run\t%s\t%s\tblockMesh-region\t%s\n' "$(case_id "$rel" blockMesh-region)" "$rel" "$regions"
            found=1
        fi
        if [[ -f $dir/system/blockMeshDict.m4 || -f $dir/system/blockMeshDict.m4.gz ]]; then
            printf 'run\t%s\t%s\tm4\tsystem/blockMeshDict.m4\n' "$(case_id "$rel" m4)" "$rel"
            found=1
        elif [[ $found == 0 ]] && m4_input=$(m4_source "$dir") && [[ -n $m4_input ]]; then
            printf 'run\t%s\t%s\tm4\t%s\n' "$(case_id "$rel" m4)" "$rel" "$m4_input"
            found=1
        fi
        if compgen -G "$dir/constant/polyMesh/points*" >/dev/null ||
           compgen -G "$dir/constant/*/polyMesh/points*" >/dev/null; then
            printf 'run\t%s\t%s\tshipped\t\n' "$(case_id "$rel" shipped)" "$rel"
            found=1
        fi
        if [[ $found == 0 ]] && compgen -G "$dir/system/blockMeshDict.*" >/dev/null &&
           tool=$(mesh_script_uses "$dir" blockMesh) && [[ -n $tool ]] &&
           ! mesh_script_uses "$dir" "$mesh_tools_re" >/dev/null; then
            # only blockMeshDict variants, chosen by its Allrun (blockMesh -dict ...)
            printf 'run\t%s\t%s\tallrun\t%s (%s)\n' "$(case_id "$rel" allrun)" "$rel" \
                "$(driver_script "$dir")" "blockMesh -dict"
            found=1
        elif tool=$(mesh_script_uses "$dir" "$convert_re") && [[ -n $tool ]]; then
            printf 'run\t%s\t%s\tallrun\t%s (%s)\n' "$(case_id "$rel" allrun)" "$rel" \
                "$(driver_script "$dir")" "$tool"
            found=1
        fi
        [[ $found == 1 ]] && continue
        # skipped: say why
        if tool=$(mesh_script_uses "$dir" "$foamy_re") && [[ -n $tool ]] && ! command -v "$tool" >/dev/null; then
            reason="$tool in its Allrun, not installed (Debian's openfoam does not package it)"
        elif tool=$(mesh_script_uses "$dir" "$mesh_tools_re") && [[ -n $tool ]]; then
            if [[ $all == 1 ]]; then continue; fi  # an -all unit below
            reason="$tool in its Allrun (slow: only with -all)"
        elif parent=$(mesh_parent "$rel") && [[ -n $parent ]]; then
            if [[ $all == 1 ]]; then continue; fi  # in the -all unit of the parent
            reason="mesh made by the Allrun of ${parent%%$'\t'*} (${parent#*$'\t'}: only with -all)"
        elif grep -qsE '^[[:space:]]*application[[:space:]]+chemFoam;' "$dir/system/controlDict"; then
            reason="chemFoam: a single-cell chemistry case, no mesh"
        elif tool=$(mesh_script_uses "$dir" "$foamy_re") && [[ -n $tool ]]; then
            reason="$tool in its Allrun (not swept: slow)"
        elif [[ -f $dir/system/blockMeshDict.template ]]; then
            reason="blockMeshDict.template only (its Allrun writes the blockMeshDict)"
        elif compgen -G "$dir/system/blockMeshDict.*" >/dev/null; then
            reason="only blockMeshDict variants ($(cd "$dir/system" && echo blockMeshDict.*)), chosen by its Allrun"
        elif mapfile -t scripts < <(mesh_scripts "$dir") && [[ ${#scripts[@]} -gt 0 ]] &&
             grep -qhE 'polyMesh|cloneCase|mapFields|\.\./' "${scripts[@]}" 2>/dev/null; then
            reason="mesh copied or mapped from another case by its Allrun"
        else
            reason="no blockMeshDict, shipped mesh or mesh step found"
        fi
        printf 'skip\t%s\t%s\n' "$rel" "$reason"
    done < <(cd "$tutorials" && find . -type d -name system ! -path '*/processor*' \
                 ! -path '*/system/*' -printf '%h\n' | sed 's|^\./||' | LC_ALL=C sort -u)

    [[ $all == 1 ]] || return 0
    # -all units: the topmost directories whose own scripts run a slow mesh tool
    local unit covered foamy
    while IFS= read -r rel; do
        tool=$(mesh_script_uses "$tutorials/$rel" "$mesh_tools_re" || true)
        # a sub-case made by its parent's script ((cd cylinderMesh && ./Allrun.pre)): the parent
        # (not a collection's Allrun that only runs its tutorials: it has no RunFunctions)
        while [[ $rel == */* ]] && mapfile -t scripts < <(mesh_scripts "$tutorials/${rel%/*}") &&
              [[ ${#scripts[@]} -gt 0 ]] &&
              grep -qwF -- "${rel##*/}" "${scripts[@]}" &&
              grep -qF RunFunctions "${scripts[@]}"; do
            rel=${rel%/*}
        done
        covered=0
        for unit in "${allrun_units[@]}"; do
            [[ $rel == "$unit" || $rel == "$unit"/* ]] && covered=1
        done
        [[ $covered == 0 ]] || continue
        allrun_units+=("$rel")
        [[ -z $cases_regex ]] || [[ $rel =~ $cases_regex ]] || continue
        dir=$tutorials/$rel
        if foamy=$(mesh_script_uses "$dir" "$foamy_re") && [[ -n $foamy ]] &&
           ! command -v "$foamy" >/dev/null; then
            continue  # listed as skipped above
        fi
        printf 'run\t%s\t%s\tallrun\t%s (%s)\n' "$(case_id "$rel" allrun)" "$rel" \
            "$(driver_script "$dir")" "$tool"
    done < <(cd "$tutorials" && grep -lE "\\b($mesh_tools_re)\\b" --include='Allrun*' \
                 --include=Allmesh --include=makeMesh -r . | xargs -r -n1 dirname |
             sed 's|^\./||' | LC_ALL=C sort -u |
             while IFS= read -r d; do
                 # only scripts that really run the tool (not in a comment)
                 if mesh_script_uses "$tutorials/$d" "$mesh_tools_re" >/dev/null; then echo "$d"; fi
             done)
}

# ---------------------------------------------------------------------------------------
# One case: copy, mesh, check, compare.

#! prepare_copy <src dir> <dst dir>: a writable copy with system/*.gz unpacked and a
#! controlDict (from controlDict.template/.orig when the tutorial writes it in its Allrun).
prepare_copy() {
    mkdir -p "$2"
    cp -rL "$1"/. "$2"/ 2>/dev/null || cp -r "$1"/. "$2"/
    chmod -R u+w "$2"
    # OpenFOAM reads X.gz for X, m4 and the mesh converters do not: unpack all but the meshes
    local f sys
    # (a script Debian compressed, e.g. patchifyObstacles.gz, must be executable again)
    while IFS= read -r f; do
        gunzip -f "$f"
        [[ $(head -c 2 "${f%.gz}") != '#!' ]] || chmod u+x "${f%.gz}"
    done < <(find "$2" -name '*.gz' -type f ! -path '*/polyMesh/*')
    while IFS= read -r sys; do
        [[ -f $sys/controlDict ]] && continue
        for f in "$sys"/controlDict.template "$sys"/controlDict.orig "$sys"/controlDict.org; do
            if [[ -f $f ]]; then
                sed 's/END_TIME/1/g' "$f" >"$sys/controlDict"
                break
            fi
        done
    done < <(find "$2" -type d -name system ! -path '*/system/*')
    for f in "$2"/system/*.template; do
        [[ -f $f && ! -e ${f%.template} ]] && cp "$f" "${f%.template}"
    done
    return 0
}

#! mesh_case <work> <copy> <method> <detail>: runs the mesh step(s); 0 when done.
mesh_case() {
    local work=$1 copy=$2 method=$3 detail=$4 r rc=0
    case "$method" in
    blockMesh)
        (cd "$copy" && timeout -k 10 "$mesh_timeout" blockMesh </dev/null) >"$work/log.blockMesh" 2>&1 || rc=$?
        ;;
    blockMesh-region)
        for r in $detail; do
            (cd "$copy" && timeout -k 10 "$mesh_timeout" blockMesh -region "$r" </dev/null) \
                >"$work/log.blockMesh.$r" 2>&1 || rc=$?
            [[ $rc == 0 ]] || break
        done
        ;;
    m4)
        (cd "$copy" && m4 "$detail" >system/blockMeshDict.m4out && mv system/blockMeshDict.m4out system/blockMeshDict) \
            >"$work/log.m4" 2>&1 || rc=$?
        if [[ $rc == 0 ]]; then
            (cd "$copy" && timeout -k 10 "$mesh_timeout" blockMesh </dev/null) >"$work/log.blockMesh" 2>&1 || rc=$?
        fi
        ;;
    shipped) ;;
    allrun)
        local script=${detail%% *}
        (cd "$copy" && WM_PROJECT_DIR=$shim_dir FOAM_TUTORIALS=$tutorials \
            SWEEP_STEPS_LOG=$work/steps.log timeout -k 10 "$mesh_timeout" sh "./$script" </dev/null) \
            >"$work/log.$script" 2>&1 || rc=$?
        ;;
    *) die "internal: unknown method '$method'" ;;
    esac
    return "$rc"
}

#! find_meshes <copy>: "<case dir relative to copy>\t<region>" for every mesh in the copy
#! (constant/polyMesh, constant/<region>/polyMesh, or only in time directories).
find_meshes() {
    (cd "$1" && find . \( -name 'processor*' -o -name sets -o -name triSurface \) -prune -o \
        -type f \( -name points -o -name points.gz \) -path '*/polyMesh/points*' -print) |
    while IFS= read -r p; do
        p=${p#./}
        p=${p%/polyMesh/*}
        local case_rel region=
        if [[ $p == constant || $p == */constant ]]; then
            case_rel=${p%constant}
        elif [[ $p == */constant/* || $p == constant/* ]]; then
            region=${p##*/}
            case_rel=${p%constant/*}
        else
            # a time directory: <case>/<time>[/<region>]
            local last=${p##*/} rest=${p%/*}
            if [[ $last =~ ^[-+0-9.eE]+$ ]]; then
                case_rel=${p%"$last"}
            elif [[ ${rest##*/} =~ ^[-+0-9.eE]+$ ]]; then
                region=$last
                case_rel=${rest%/*}/
                [[ $rest == */* ]] || case_rel=
            else
                continue
            fi
        fi
        case_rel=${case_rel%/}
        [[ -d $1/${case_rel:-.}/system ]] || continue
        printf '%s\t%s\n' "${case_rel:-.}" "$region"
    done | sort -u
}

#! has_time_mesh <case dir> <region>: a time directory holds a polyMesh for the region.
has_time_mesh() {
    local t
    for t in "$1"/*/; do
        t=${t%/}
        [[ ${t##*/} =~ ^[-+0-9.eE]+$ ]] || continue
        [[ -n $(compgen -G "$t/${2:+$2/}polyMesh/points*") ]] && return 0
    done
    return 1
}

run_case() {
    local id=$1 rel=$2 method=$3 detail=$4
    local work=$out_dir/cases/$id copy
    copy=$work/case
    rm -rf "$work"
    mkdir -p "$work"
    printf '%s\t%s\t%s\t%s\n' "$id" "$rel" "$method" "$detail" >"$work/case.tsv"
    prepare_copy "$tutorials/$rel" "$copy"
    local rc=0
    mesh_case "$work" "$copy" "$method" "$detail" || rc=$?
    if [[ $rc == 124 || $rc == 137 ]]; then
        echo "mesh timeout after ${mesh_timeout} s" >"$work/mesh_error"
    elif [[ $method == allrun ]]; then
        # a tutorial script's own exit status says little (a missing gnuplot at its end, ...):
        # a failed mesh step is one that sweep_run_functions.sh logged as FAILED
        if grep -q '^FAILED' "$work/steps.log" 2>/dev/null; then
            echo "mesh step failed" >"$work/mesh_error"
        fi
    elif [[ $rc != 0 ]]; then
        echo "mesh step failed (exit $rc)" >"$work/mesh_error"
    fi
    local meshes case_rel region mesh_name mesh_dir
    local -a args
    meshes=$(find_meshes "$copy")
    if [[ -z $meshes && ! -f $work/mesh_error ]]; then
        echo "no mesh made" >"$work/mesh_error"
    fi
    while IFS=$'\t' read -r case_rel region; do
        [[ -n $case_rel ]] || continue
        mesh_name=$case_rel
        [[ $mesh_name != . ]] || mesh_name=_
        mesh_name=${mesh_name//\//+}${region:+:$region}
        mesh_dir=$work/meshes/$mesh_name
        mkdir -p "$mesh_dir"
        printf '%s\t%s\n' "$case_rel" "$region" >"$mesh_dir/mesh.tsv"
        args=(-case "$copy/$case_rel")
        [[ -z $region ]] || args+=(-region "$region")
        if has_time_mesh "$copy/$case_rel" "$region"; then args+=(-latestTime); fi
        if [[ $morph == 1 ]]; then
            local margs=("$copy/$case_rel" "$mesh_dir" --morph-mesh "$morph_mesh" --timeout "$check_timeout"
                         --keys "$morph_keys")
            [[ -z $region ]] || margs+=(--region "$region")
            if has_time_mesh "$copy/$case_rel" "$region"; then margs+=(--latest-time); fi
            local verdict
            verdict=$(PYTHONPATH=$morph_python_path "$python" "$script_dir/morph_one_mesh.py" "${margs[@]}" 2>"$mesh_dir/morph_one_mesh.err") ||
                verdict="crashed: morph_one_mesh.py failed ($(tail -n 1 "$mesh_dir/morph_one_mesh.err"))"
            echo "$foam_script_name: $rel [$method] $mesh_name: $verdict"
            continue
        fi
        local mode opts crc
        for mode in plain all; do
            opts=()
            [[ $mode == plain ]] || opts=(-allGeometry -allTopology)
            crc=0
            timeout -k 10 "$check_timeout" checkMesh "${args[@]}" "${opts[@]}" </dev/null \
                >"$mesh_dir/checkMesh.$mode.log" 2>&1 || crc=$?
            echo "$crc" >"$mesh_dir/checkMesh.$mode.rc"
            crc=0
            timeout -k 10 "$check_timeout" "$checker" "${args[@]}" "${opts[@]}" -writeSets </dev/null \
                >"$mesh_dir/checkMeshQuality.$mode.log" 2>&1 || crc=$?
            echo "$crc" >"$mesh_dir/checkMeshQuality.$mode.rc"
        done
        "$python" "$script_dir/compare_checkmesh.py" mesh "$mesh_dir" ||
            die "compare_checkmesh.py failed on $mesh_dir"
    done <<<"$meshes"
    [[ $morph == 0 ]] || return 0
    local line
    line=$("$python" "$script_dir/compare_checkmesh.py" case "$work") ||
        die "compare_checkmesh.py failed on $work"
    echo "$foam_script_name: $rel [$method]: $line"
    if [[ $keep == 0 && $line == *"all agree"* ]]; then
        rm -rf "$copy"
    fi
}

# ---------------------------------------------------------------------------------------

work_list=$(discover)
n_run=$(grep -c '^run' <<<"$work_list" || true)
n_skip=$(grep -c '^skip' <<<"$work_list" || true)
if [[ $list == 1 ]]; then
    grep '^run' <<<"$work_list" | cut -f3- | tr '\t' ' ' || true
    grep '^skip' <<<"$work_list" | cut -f2- | sed 's/\t/: skipped: /' || true
    echo "$foam_script_name: $n_run cases to mesh, $n_skip skipped"
    exit 0
fi
[[ $n_run -gt 0 ]] || die "no case to run${cases_regex:+ (-cases \"$cases_regex\")}"

mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
rm -rf "$out_dir/cases" "$out_dir/summary.md" "$out_dir/summary.csv" "$out_dir/summary.json" \
       "$out_dir/foam"
mkdir -p "$out_dir/cases"
grep '^skip' <<<"$work_list" | cut -f2- >"$out_dir/skipped.tsv" || true
{
    echo "tutorials	$tutorials"
    if [[ $morph == 1 ]]; then echo "morphMesh	$morph_mesh"; else echo "checker	$checker"; fi
    [[ -z $morph_keys ]] || echo "morphKeys	$morph_keys"
    echo "options	${cases_regex:+-cases $cases_regex }$([[ $all == 1 ]] && echo -all)"
    echo "started	$(date -u +%Y-%m-%dT%H:%M:%SZ)"
} >"$out_dir/sweep.tsv"

# the stand-in OpenFOAM project directory for the tutorials' own scripts (-all, converters)
shim_dir=$out_dir/foam
mkdir -p "$shim_dir/bin/tools"
ln -s "$WM_PROJECT_DIR/etc" "$shim_dir/etc"
cp "$script_dir/sweep_run_functions.sh" "$shim_dir/bin/tools/RunFunctions"
echo ". \"\${WM_PROJECT_DIR:?}/bin/tools/RunFunctions\"" >"$shim_dir/bin/tools/CleanFunctions"

echo "$foam_script_name: $n_run cases to mesh, $n_skip skipped; output in $out_dir"
running=0
while IFS=$'\t' read -r _ id rel method detail; do
    if [[ $jobs == 1 ]]; then
        run_case "$id" "$rel" "$method" "$detail"
    else
        run_case "$id" "$rel" "$method" "$detail" &
        running=$((running + 1))
        if [[ $running -ge $jobs ]]; then
            wait -n || die "a case job failed"
            running=$((running - 1))
        fi
    fi
done < <(grep '^run' <<<"$work_list")
while [[ $running -gt 0 ]]; do
    wait -n || die "a case job failed"
    running=$((running - 1))
done
echo "finished	$(date -u +%Y-%m-%dT%H:%M:%SZ)" >>"$out_dir/sweep.tsv"

# write_results: summary.md, with the run's context, to benchmarks/results/ (results.sh).
write_results() {
    [[ -f $out_dir/summary.md ]] || return 0
    local name=checkmesh_sweep
    [[ $morph == 0 ]] || name=morph_sweep
    [[ $all == 0 ]] || name+=_all
    results_write_report -openfoam "$name" "$out_dir/summary.md"
}

if [[ $morph == 1 ]]; then
    summary_args=("$out_dir")
    [[ $fail_on_silent == 0 ]] || summary_args+=(--fail-on-silent)
    summary_rc=0
    "$python" "$script_dir/morph_sweep_summary.py" "${summary_args[@]}" || summary_rc=$?
    write_results   # silent or crashed meshes are results too
    [[ $summary_rc == 0 ]] ||
        die "silent or crashed meshes (or morph_sweep_summary.py failed): see $out_dir/summary.md"
    exit 0
fi
"$python" "$script_dir/compare_checkmesh.py" summary "$out_dir" ||
    die "compare_checkmesh.py summary failed"
write_results
