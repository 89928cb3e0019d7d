# shellcheck shell=sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A stand-in for OpenFOAM's bin/tools/RunFunctions (not packaged by Debian), used by
# checkmesh_sweep.sh -all to run a tutorial's own Allrun/Allrun.pre/Allmesh up to its mesh:
# checkmesh_sweep.sh points WM_PROJECT_DIR at a directory whose etc/ is Debian's
# /usr/share/openfoam/etc and whose bin/tools/RunFunctions is this file, so the tutorial
# scripts source it unchanged. POSIX sh: the tutorial scripts are #!/bin/sh.
#
# runApplication/runParallel run only the steps that make or edit the mesh (blockMesh,
# snappyHexMesh, extrudeMesh, splitMeshRegions, topoSet, createBaffles, converters, the
# case's own ./scripts, ...), serially (runParallel drops -parallel; decomposePar and
# reconstructParMesh are skipped, so a parallel mesh step runs on the whole case); they skip
# the steps known not to touch the mesh (setFields, decomposePar, potentialFoam, ...); any
# other application is taken for the solver and ends the script there ("exit 0"; in a
# subshell only that subshell ends). Each decision is one line in $SWEEP_STEPS_LOG.

sweep_step_log() {
    echo "$*" >>"${SWEEP_STEPS_LOG:-/dev/null}"
}

#! sweep_step_kind <app>: run (a mesh step), skip (does not touch the mesh) or stop (solver).
sweep_step_kind() {
    case "$1" in
    ./* | */*) echo run ;;
    blockMesh | PDRblockMesh | snappyHexMesh | surfaceFeatureExtract | surfaceFeatures | \
    extrudeMesh | extrudeToRegionMesh | extrude2DMesh | splitMeshRegions | topoSet | setSet | \
    setsToZones | createBaffles | createPatch | mergeOrSplitBaffles | subsetMesh | mergeMeshes | \
    transformPoints | surfaceTransformPoints | surfaceMeshConvert | surfaceConvert | \
    surfaceMeshExtract | surfaceCheck | refineMesh | refineHexMesh | refineWallLayer | \
    renumberMesh | stitchMesh | changeDictionary | polyDualMesh | collapseEdges | \
    foamDictionary | foamyQuadMesh | m4 | fluentMeshToFoam | fluent3DMeshToFoam | \
    star4ToFoam | kivaToFoam | ansysToFoam | datToFoam | gambitToFoam | ideasUnvToFoam | \
    gmshToFoam | plot3dToFoam | netgenNeutralToFoam | cfx4ToFoam | mshToFoam | \
    tetgenToFoam | vtkUnstructuredToFoam | ccmToFoam) echo run ;;
    decomposePar | reconstructPar | reconstructParMesh | redistributePar | setFields | \
    setAlphaField | setExprFields | setExprBoundaryFields | PDRsetFields | potentialFoam | mapFields | \
    mapFieldsPar | createZeroDirectory | foamToVTK | foamToEnsight | postProcess | \
    foamFormatConvert | checkMesh | makeFaMesh | paraFoam | foamListTimes | \
    surfaceRedistributePar | cumulativeDisplacement | writeActiveDesignVariables | \
    createExternalCoupledPatchGeometry | applyBoundaryLayer | foamyHexMesh | \
    moveMesh | moveDynamicMesh | chemkinToFoam | foamMeshToFluent | wmake | wclean) echo skip ;;
    *) echo stop ;;
    esac
}

#! sweep_run <parallel:0|1> [runApplication options] <app> [args...]
sweep_run() {
    _sweep_parallel=$1
    shift
    _sweep_suffix='' _sweep_mode='' _sweep_app=
    while [ "$#" -gt 0 ] && [ -z "$_sweep_app" ]; do
        case "$1" in
        '') ;;
        -a | -append) _sweep_mode=append ;;
        -o | -overwrite) _sweep_mode=overwrite ;;
        -s | -suffix) _sweep_suffix=".$2"; shift ;;
        -n | -np) shift ;;
        -decompose-dict=*) ;;
        -decomposeParDict) shift ;;
        *) _sweep_app=$1 ;;
        esac
        shift
    done
    _sweep_name=${_sweep_app##*/}
    _sweep_log="log.$_sweep_name$_sweep_suffix"
    case "$(sweep_step_kind "$_sweep_app")" in
    skip)
        sweep_step_log "skip: $_sweep_app $* (in $PWD)"
        return 0
        ;;
    stop)
        sweep_step_log "stop: $_sweep_app $* (in $PWD): not a mesh step, the script ends here"
        exit 0
        ;;
    esac
    if [ -f "$_sweep_log" ] && [ -z "$_sweep_mode" ]; then
        sweep_step_log "already run: $_sweep_app (in $PWD)"
        return 0
    fi
    if [ "$_sweep_parallel" = 1 ]; then
        # serially: drop -parallel and -decomposeParDict <dict>
        _sweep_n=$#
        while [ "$_sweep_n" -gt 0 ]; do
            _sweep_arg=$1
            shift
            _sweep_n=$((_sweep_n - 1))
            case "$_sweep_arg" in
            -parallel) ;;
            -decomposeParDict) shift; _sweep_n=$((_sweep_n - 1)) ;;
            *) set -- "$@" "$_sweep_arg" ;;
            esac
        done
        sweep_step_log "run (serial, was runParallel): $_sweep_app $* (in $PWD)"
    else
        sweep_step_log "run: $_sweep_app $* (in $PWD)"
    fi
    if [ "$_sweep_mode" = append ]; then
        "$_sweep_app" "$@" </dev/null >>"$_sweep_log" 2>&1
    else
        "$_sweep_app" "$@" </dev/null >"$_sweep_log" 2>&1
    fi
    _sweep_status=$?
    if [ "$_sweep_status" -ne 0 ]; then
        case "$_sweep_status" in
        126) _sweep_why=", not executable" ;;
        127) _sweep_why=", not found" ;;
        *) _sweep_why= ;;
        esac
        sweep_step_log "FAILED (exit $_sweep_status$_sweep_why): $_sweep_app $* (in $PWD, log $_sweep_log)"
    fi
    return "$_sweep_status"
}

runApplication() { sweep_run 0 "$@"; }
runParallel() { sweep_run 1 "$@"; }

isParallel() {
    for i; do [ "$i" = "-parallel" ] && return 0; done
    return 1
}
isTest() {
    for i; do [ "$i" = "-test" ] && return 0; done
    return 1
}
notTest() {
    for i; do [ "$i" = "-test" ] && return 1; done
    return 0
}
canCompile() { return 1; }
compileApplication() {
    sweep_step_log "skip: compile $1 (in $PWD)"
    return 1
}

getApplication() {
    # shellcheck disable=SC2046 # the words of the value, as RunFunctions does
    set -- $(foamDictionary -entry application -value system/controlDict 2>/dev/null)
    if [ "$#" -eq 1 ]; then echo "$1"; else echo false; return 1; fi
}

getNumberOfProcessors() {
    _sweep_dict=${1:-system/decomposeParDict}
    [ -f "$_sweep_dict" ] || _sweep_dict="system/$_sweep_dict"
    # shellcheck disable=SC2046
    set -- $(foamDictionary -entry numberOfSubdomains -value "$_sweep_dict" 2>/dev/null)
    if [ "$#" -eq 1 ]; then echo "$1"; else echo 1; return 1; fi
}

getNumberOfPatchFaces() {
    _sweep_file="constant/${2:-}${2:+/}polyMesh/boundary"
    sed -ne '/^ *'"$1"' *$/,/}/{s/^ *nFaces  *\([0-9][0-9]*\) *;.*$/\1/p}' "$_sweep_file"
}

isTrue() {
    _sweep_value=$1
    if [ "$_sweep_value" = "-dict" ]; then
        shift
        _sweep_value=$(foamDictionary -value "$@" 2>/dev/null) || return 2
    fi
    case "$_sweep_value" in
    t | y | true | yes | on) return 0 ;;
    f | n | false | no | off) return 1 ;;
    esac
    return 2
}

#! restore0Dir [-processor|-all]: 0.orig/ -> 0/ (the processor copies are not needed here).
restore0Dir() {
    [ -d 0.orig ] || return 0
    rm -rf 0
    cp -r 0.orig 0 2>/dev/null
    return 0
}

#! cloneCase <src> <dst>: constant, system and 0[.orig] of <src> into a new <dst>.
cloneCase() {
    [ -e "$2" ] && return 1
    [ -d "$1" ] || return 1
    mkdir "$2"
    for f in constant system; do cp -r "$1/$f" "$2"; done
    for f in 0 0.orig; do cp -r "$1/$f" "$2" 2>/dev/null; done
    return 0
}

cloneParallelCase() {
    sweep_step_log "stop: cloneParallelCase $* (in $PWD): parallel data are not made here"
    exit 0
}

# CleanFunctions, for scripts that source both: nothing to clean in a fresh copy.
cleanTimeDirectories() {
    for d in [1-9]*; do
        case "$d" in *[!0-9.e+-]*) ;; *) [ -d "$d" ] && rm -rf "$d" ;; esac
    done
    return 0
}
cleanCase() { return 0; }
cleanCase0() { return 0; }
cleanApplication() { return 0; }
cleanPolyMesh() { rm -rf constant/polyMesh/sets; return 0; }
cleanFaMesh() { return 0; }
cleanSnappyFiles() { return 0; }
cleanPostProcessing() { return 0; }
cleanExplicitFeatures() { return 0; }
cleanOptimisation() { return 0; }
removeCase() { return 0; }
