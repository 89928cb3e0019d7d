#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# morphMesh on the snappyHexMesh motorBike (bike lifted, tutorials/motorBike/system/morphDict)
# serially and with -parallel, ranks x threads: wall time and peak memory per rank, and
# each -parallel result against the serial one (scripts/parallel/compare_decomposed.py).
# Then, on the case decomposed for the largest rank count, the check side by side with its
# peer: checkMeshQuality -parallel against checkMesh -parallel (-allGeometry -allTopology
# -meshQuality, same run, same ranks), reports compared line by line.
#
#   parallel_motorbike.sh -bin DIR -out DIR [-case DIR] [-runs "1x1 1x2 2x1"]
#                         [-results FILE | -no-results]
#
# -bin: the build's applications directory (holding morphMesh/ and checkMeshQuality/).
# -case: the meshed motorBike (default build/cases/motorBike-full, made by
# benchmarks/io/make_motorbike.sh). Each entry of -runs is RANKSxTHREADS; 1xT is the serial
# morphMesh with T OpenMP threads, Rx T runs mpirun -np R morphMesh -parallel on the case
# decomposed by decomposePar (method simple); the first entry must be serial. Writes
# DIR/summary.md.
# -results FILE: also write summary.md with the run's context (date, machine, OS, commit,
# OpenFOAM, this command line) to FILE (benchmarks/results.sh); -no-results: write no such
# file. Default: benchmarks/results/parallel_motorbike.md, written only by a full run: the
# default -runs, every run succeeded; none when MESHMORPH_NO_RESULTS=1 (tests, quick runs).
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
# shellcheck source=SCRIPTDIR/../results.sh
source "$source_dir/benchmarks/results.sh"   # results_init, results_write, ...
results_init "$@"
bin="" out="" case_dir="$source_dir/build/cases/motorBike-full" runs="1x1 1x2 2x1"
while [ $# -gt 0 ]; do
    case "$1" in
        -bin) bin=$(cd "$2" && pwd); shift 2 ;;
        -out) out=$2; shift 2 ;;
        -case) case_dir=$2; shift 2 ;;
        -runs) runs=$2; shift 2 ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -help|-h) sed -n '3,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
            *) echo "parallel_motorbike.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
done
[ -n "$bin" ] && [ -n "$out" ] || { echo "parallel_motorbike.sh: -bin and -out are required" >&2; exit 2; }
# shellcheck disable=SC2086,SC2116 # a word list, compared word by word
[ "$(echo $runs)" = "1x1 1x2 2x1" ] || results_partial "-runs \"$runs\""
[ -f "$case_dir/constant/polyMesh/owner" ] || [ -f "$case_dir/constant/polyMesh/owner.gz" ] ||
    { echo "no mesh in $case_dir (run benchmarks/io/make_motorbike.sh)" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out" && out=$(cd "$out" && pwd)
work=$out/case
rm -rf "$work" && mkdir -p "$work" && cp -r "$case_dir/constant" "$case_dir/system" "$work/" &&
    cp "$source_dir/tutorials/motorBike/system/morphDict" "$work/system/" || exit 1

peak_mb() { awk '/Maximum resident set size/ {printf "%.0f", $NF / 1024}' "$1"; }
wall_s() { awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + t[i]; printf "%.2f", s}' "$1"; }

morph=$bin/morphMesh/morphMesh check=$bin/checkMeshQuality/checkMeshQuality
echo "| ranks x threads | wall [s] | peak memory per rank [MB] | fit [s] | evaluate [s] | largest difference to serial (of the extent) |" > "$out/summary.md"
echo "| --- | --- | --- | --- | --- | --- |" >> "$out/summary.md"
decomposed=0
for run in $runs; do
    ranks=${run%x*} threads=${run#*x}
    log=$out/log.$run
    rm -rf "$work"/processor*/[1-9]* "$work"/[1-9]*
    if [ "$ranks" = 1 ]; then
        OMP_NUM_THREADS=$threads /usr/bin/time -v -o "$out/time.$run.0" "$morph" -case "$work" > "$log" 2>&1 || { echo "$run failed (see $log)"; results_partial "$run failed"; continue; }
        cp "$work/1/polyMesh/points" "$out/serial_points"
    else
        if [ $decomposed != "$ranks" ]; then
            rm -rf "$work"/processor*
            printf 'FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\nnumberOfSubdomains %s;\nmethod simple;\nsimpleCoeffs { n (%s 1 1); delta 0.001; }\n' "$ranks" "$ranks" > "$work/system/decomposeParDict"
            (cd "$work" && decomposePar > "$out/log.decomposePar.$ranks" 2>&1) || { echo "decomposePar failed"; exit 1; }
            decomposed=$ranks
        fi
        mpirun -np "$ranks" --oversubscribe -x OMP_NUM_THREADS="$threads" sh -c \
            "/usr/bin/time -v -o '$out/time.$run.'\$OMPI_COMM_WORLD_RANK '$morph' -case '$work' -parallel" > "$log" 2>&1 ||
            { echo "$run failed (see $log)"; results_partial "$run failed"; continue; }
    fi
    mem=""
    for r in $(seq 0 $((ranks - 1))); do mem="$mem${mem:+ / }$(peak_mb "$out/time.$run.$r")"; done
    fit=$(sed -n 's/^Timings \[s\]: .*fit \([0-9.e+-]*\),.*/\1/p' "$log")
    eval=$(sed -n 's/^Timings \[s\]: .*evaluate \([0-9.e+-]*\),.*/\1/p' "$log")
    diff="(serial)"
    if [ "$ranks" != 1 ]; then
        /usr/bin/python3 "$source_dir/scripts/parallel/compare_decomposed.py" "$work" 1 "$ranks" \
            "$out/serial_points" > "$out/compare.$run" 2>&1
        diff=$(sed -n 's/.*(\(.*\) of the extent).*/\1/p' "$out/compare.$run")
        grep -q "not bit-identical: 0" "$out/compare.$run" || diff="$diff; shared points differ"
    fi
    echo "| $run | $(wall_s "$out/time.$run.0") | $mem | $fit | $eval | $diff |" >> "$out/summary.md"
done

# The check, side by side with checkMesh, on the decomposed (undeformed) mesh.
if [ "$decomposed" != 0 ]; then
    rm -rf "$work"/processor*/[1-9]*
    checks="-allGeometry -allTopology -meshQuality"
    run_check() { # name, then the command
        local name=$1; shift
        /usr/bin/time -v -o "$out/time.$name" "$@" > "$out/log.$name" 2>&1
    }
    (cd "$work" && run_check checkMesh.parallel mpirun -np "$decomposed" --oversubscribe -x OMP_NUM_THREADS=1 checkMesh -parallel $checks)
    run_check checkMeshQuality.parallel mpirun -np "$decomposed" --oversubscribe -x OMP_NUM_THREADS=1 "$check" -case "$work" -parallel $checks -writeSets
    (cd "$work" && run_check checkMesh.serial checkMesh $checks)
    OMP_NUM_THREADS=1 run_check checkMeshQuality.serial "$check" -case "$work" $checks -writeSets
    same() { /usr/bin/python3 "$source_dir/scripts/parallel/compare_reports.py" "$out/log.$1" "$out/log.$2" | tail -1; }
    {
        echo
        echo "| check ($checks, 1 thread per rank) | wall [s] | peak memory [MB] (master) | report |"
        echo "| --- | --- | --- | --- |"
        echo "| checkMesh, serial | $(wall_s "$out/time.checkMesh.serial") | $(peak_mb "$out/time.checkMesh.serial") | |"
        echo "| checkMeshQuality, serial | $(wall_s "$out/time.checkMeshQuality.serial") | $(peak_mb "$out/time.checkMeshQuality.serial") | $(same checkMesh.serial checkMeshQuality.serial) |"
        echo "| checkMesh -parallel, $decomposed ranks | $(wall_s "$out/time.checkMesh.parallel") | | |"
        echo "| checkMeshQuality -parallel, $decomposed ranks | $(wall_s "$out/time.checkMeshQuality.parallel") | | $(same checkMesh.parallel checkMeshQuality.parallel) |"
    } >> "$out/summary.md"
fi
# A paper estimate for larger cases on 64 ranks, from the measured per-rank costs.
/usr/bin/python3 - "$out" "$work" <<'PY' >> "$out/summary.md"
import glob, re, sys
out, work = sys.argv[1], sys.argv[2]
def rss(path):
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(path).read())
    return int(m.group(1)) / 1024
def timing(log, key):
    m = re.search(r"^Timings \[s\]: .*" + key + r" ([0-9.e+-]+)", open(log).read(), re.M)
    return float(m.group(1)) if m else None
serial = glob.glob(f"{out}/time.1x1.0")
parallel = sorted(glob.glob(f"{out}/time.2x1.*"))
if not serial or len(parallel) < 2:
    sys.exit(0)
log = open(f"{out}/log.1x1").read()
cells = int(re.search(r"points, (\d+) cells", log).group(1))
constraints = int(re.search(r"Constraints: (\d+) prescribed", log).group(1))
m1, m2 = rss(serial[0]), max(rss(p) for p in parallel)
per_cell = (m1 - m2) / (cells / 2)           # MB per cell a rank holds
fixed = m1 - per_cell * cells                # libraries, buffers: per rank
fit, evaluate = timing(f"{out}/log.1x1", "fit"), timing(f"{out}/log.1x1", "evaluate")
print()
print("Paper estimate, 64 ranks (per-rank memory = fixed + per-cell x cells per rank; the")
print("constraints grow like the surface, cells^(2/3); the master's fit like the constraints,")
print("each rank's evaluation like its cells; the IDW part a rank receives is its locally")
print(f"essential tree). Measured: {cells} cells, {constraints} constraints, {per_cell * 1e3:.2f} kB")
print(f"per cell, {fixed:.0f} MB fixed, fit {fit} s, evaluate {evaluate} s (serial, 1 thread).")
print()
print("| cells | cells per rank | constraints | memory per rank [MB] | fit on the master [s] | evaluate per rank [s] |")
print("| --- | --- | --- | --- | --- | --- |")
for n in (10e6, 50e6):
    scale = (n / cells) ** (2 / 3)
    print(f"| {n / 1e6:.0f}M | {n / 64 / 1e3:.0f}k | {constraints * scale / 1e3:.0f}k | "
          f"{fixed + per_cell * n / 64:.0f} | {fit * scale:.1f} | {evaluate * (n / 64) / cells:.2f} |")
PY
cat "$out/summary.md"
results_write -openfoam parallel_motorbike "morphMesh on the full motorBike, serial and -parallel" \
    "$out/summary.md"
