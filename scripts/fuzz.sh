#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer targets (fuzz/, preset asan: clang, ASan + UBSan) and runs each in turn
# over its seeds, for a time or a number of runs, then prints executions, time and result.
#
# Usage: scripts/fuzz.sh [--time S | --runs N] [--build-dir DIR] [--no-build] [TARGET...]
#   --time S        run each target S seconds (default 60)
#   --runs N        run each target N inputs instead (e.g. 1000000)
#   --build-dir DIR build tree configured with MESHMORPH_BUILD_FUZZERS=ON (default build/fuzz,
#                   the `fuzz` preset: asan optimised, only the fuzz targets; configured when
#                   missing). CI runs the asan build's: --build-dir build/asan --no-build
#   --no-build      use the executables as they are
#   TARGET...       some of the targets (default: all; names as in fuzz/corpus/)
# Seeds: fuzz/corpus/<target>/ (committed, small) and build/fuzz-seeds/<target>/ when present
# (larger ones from scripts/fuzz-seeds.sh). New inputs go to build/fuzz-runs/<target>/corpus,
# findings to build/fuzz-runs/<target>/ (crash-*, leak-*, timeout-*, oom-*), logs to
# build/fuzz-runs/<target>/log. Reproduce a finding with `build/fuzz/fuzz/<target> FILE`.
# Exits non-zero if any target reports a finding.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

limit=(-max_total_time=60)
build_dir=build/fuzz
build=1
targets=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --time) limit=(-max_total_time="$2"); shift 2 ;;
        --runs) limit=(-runs="$2"); shift 2 ;;
        --build-dir) build_dir=$2; shift 2 ;;
        --no-build) build=0; shift ;;
        -h|--help) sed -n '3,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "fuzz.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
        *) targets+=("$1"); shift ;;
    esac
done
if [[ ${#targets[@]} -eq 0 ]]; then
    mapfile -t targets < <(ls fuzz/corpus)
fi

if [[ $build == 1 ]]; then
    if [[ ! -f $build_dir/CMakeCache.txt ]]; then
        cmake --preset fuzz
    fi
    cmake --build "$build_dir" -j2 --target "${targets[@]}"
fi

# The libFuzzer dictionary of a target's input syntax.
dictionary_of() {
    case "$1" in
        fuzz_stl) echo fuzz/dictionaries/stl.dict ;;
        fuzz_obj) echo fuzz/dictionaries/obj.dict ;;
        *) echo fuzz/dictionaries/foam.dict ;;
    esac
}

status=0
summary=()
for target in "${targets[@]}"; do
    exe=$build_dir/fuzz/$target
    if [[ ! -x $exe ]]; then
        echo "fuzz.sh: $exe not built (configure with MESHMORPH_BUILD_FUZZERS=ON)" >&2
        exit 2
    fi
    work=build/fuzz-runs/$target
    mkdir -p "$work/corpus"
    seeds=(fuzz/corpus/"$target")
    [[ -d build/fuzz-seeds/$target ]] && seeds+=(build/fuzz-seeds/"$target")
    echo "==> $target: ${limit[*]} ($(date -u +%H:%M:%S) UTC)"
    result=ok
    # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is an OOM finding.
    "$exe" "${limit[@]}" -dict="$(dictionary_of "$target")" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$work/" "$work/corpus" "${seeds[@]}" \
        >"$work/log" 2>&1 || { result="FINDING (see $work/log)"; status=1; }
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
    secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$work/log" | tail -1)
    [[ $result == ok ]] || grep -E '^(==[0-9]+==ERROR|SUMMARY|artifact_prefix|Test unit written)' \
        "$work/log" | head -5 || true
    summary+=("$(printf '%-22s %10s runs %6s s  %s' "$target" "${runs:-?}" "${secs:-?}" "$result")")
done

echo
echo "==> fuzz summary (${limit[*]})"
printf '%s\n' "${summary[@]}"
exit "$status"
