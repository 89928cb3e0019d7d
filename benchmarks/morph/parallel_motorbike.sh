#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# morphMesh on the snappyHexMesh motorBike (bike lifted, tutorials/motorBike/system/morphDict)
# serially and with -parallel, ranks x threads: wall time and peak memory per rank.
#
#   parallel_motorbike.sh -bin DIR -out DIR [-case DIR] [-runs "1x1 1x2 2x1"]
#
# -case: the meshed motorBike (default build/cases/motorBike-full, made by
# benchmarks/io/make_motorbike.sh). Each entry of -runs is RANKSxTHREADS; 1xT is the serial
# morphMesh with T OpenMP threads, Rx T runs mpirun -np R morphMesh -parallel on the case
# decomposed by decomposePar (method simple). Writes DIR/summary.md.
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
bin="" out="" case_dir="$source_dir/build/cases/motorBike-full" runs="1x1 1x2 2x1"
while [ $# -gt 0 ]; do
    case "$1" in
        -bin) bin=$(cd "$2" && pwd); shift 2 ;;
        -out) out=$2; shift 2 ;;
        -case) case_dir=$2; shift 2 ;;
        -runs) runs=$2; shift 2 ;;
        -help|-h) sed -n '3,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "parallel_motorbike.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
done
[ -n "$bin" ] && [ -n "$out" ] || { echo "parallel_motorbike.sh: -bin and -out are required" >&2; exit 2; }
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

echo "| ranks x threads | wall [s] | peak memory per rank [MB] | fit [s] | evaluate [s] |" > "$out/summary.md"
echo "| --- | --- | --- | --- | --- |" >> "$out/summary.md"
decomposed=0
for run in $runs; do
    ranks=${run%x*} threads=${run#*x}
    log=$out/log.$run
    rm -rf "$work"/processor*/[1-9]* "$work"/[1-9]*
    if [ "$ranks" = 1 ]; then
        OMP_NUM_THREADS=$threads /usr/bin/time -v -o "$out/time.$run.0" "$bin/morphMesh" -case "$work" > "$log" 2>&1 || { echo "$run failed (see $log)"; continue; }
    else
        if [ $decomposed != "$ranks" ]; then
            rm -rf "$work"/processor*
            printf 'FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\nnumberOfSubdomains %s;\nmethod simple;\nsimpleCoeffs { n (%s 1 1); delta 0.001; }\n' "$ranks" "$ranks" > "$work/system/decomposeParDict"
            (cd "$work" && decomposePar > "$out/log.decomposePar.$ranks" 2>&1) || { echo "decomposePar failed"; exit 1; }
            decomposed=$ranks
        fi
        mpirun -np "$ranks" --oversubscribe -x OMP_NUM_THREADS="$threads" sh -c \
            "/usr/bin/time -v -o '$out/time.$run.'\$OMPI_COMM_WORLD_RANK '$bin/morphMesh' -case '$work' -parallel" > "$log" 2>&1 ||
            { echo "$run failed (see $log)"; continue; }
    fi
    mem=""
    for r in $(seq 0 $((ranks - 1))); do mem="$mem${mem:+ / }$(peak_mb "$out/time.$run.$r")"; done
    fit=$(sed -n 's/^Timings \[s\]: .*fit \([0-9.e+-]*\),.*/\1/p' "$log")
    eval=$(sed -n 's/^Timings \[s\]: .*evaluate \([0-9.e+-]*\),.*/\1/p' "$log")
    echo "| $run | $(wall_s "$out/time.$run.0") | $mem | $fit | $eval |" >> "$out/summary.md"
done
cat "$out/summary.md"
