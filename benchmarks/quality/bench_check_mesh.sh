#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Times checkMeshQuality (mesh reading included) against OpenFOAM's checkMesh on the same
# case, plain and with -allGeometry -allTopology, and prints the two time ratios.
#
# Usage: bench_check_mesh.sh CASE [REPEATS] [CHECKMESHQUALITY]
#   CASE              an OpenFOAM case; it is COPIED to a temporary directory first,
#                     because checkMesh writes sets into the case.
#   REPEATS           runs per tool and mode; the best wall time is kept (default 3)
#   CHECKMESHQUALITY  our executable (default: build/release, build/quality, build/dev ...)
# Goals on the motorBike tutorial mesh (353k cells, benchmarks/io/make_motorbike.sh):
#   plain <= 0.5 x checkMesh, -allGeometry -allTopology <= 0.25 x checkMesh.
# Both tools run with the machine's default thread count (checkMesh is serial). On a loaded
# machine, OpenMP's spinning barriers cost more than the second thread gains: compare with
# OMP_WAIT_POLICY=passive or OMP_NUM_THREADS=1 (environment, read at program start).
# Each pair of reports is also compared (same lines apart from set-writing lines).
set -euo pipefail
src=${1:?usage: bench_check_mesh.sh CASE [REPEATS] [CHECKMESHQUALITY]}
repeats=${2:-3}
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
ours=${3:-}
if [[ -z "$ours" ]]; then
    for b in release quality dev ci; do
        if [[ -x "$root/build/$b/applications/checkMeshQuality/checkMeshQuality" ]]; then
            ours="$root/build/$b/applications/checkMeshQuality/checkMeshQuality"
            break
        fi
    done
fi
[[ -x "$ours" ]] || { echo "bench_check_mesh.sh: checkMeshQuality not found (pass it as 3rd argument)" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v checkMesh >/dev/null || { echo "bench_check_mesh.sh: OpenFOAM's checkMesh not on PATH" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/bench_check_mesh.XXXXXX")
trap 'rm -rf "$work"' EXIT
cp -r "$src/system" "$src/constant" "$work/"
chmod -R u+w "$work"
# Time directories with a polyMesh (moved points) are copied too.
for t in "$src"/[0-9]*; do [[ -d "$t/polyMesh" ]] && cp -r "$t" "$work/"; done

best_time() { # best_time LOG COMMAND...: best wall seconds of $repeats runs, last log kept
    local log=$1; shift
    local best=""
    for ((i = 0; i < repeats; ++i)); do
        local t0 t1
        t0=$(date +%s.%N)
        (cd "$work" && "$@") > "$log" 2>&1 || true
        t1=$(date +%s.%N)
        best=$(awk -v a="$t0" -v b="$t1" -v best="$best" 'BEGIN { t = b - a; if (best == "" || t < best) best = t; printf "%.3f", best }')
        rm -rf "$work/constant/polyMesh/sets"
    done
    echo "$best"
}
report() { sed -n '/^Mesh stats/,/^\(Mesh OK\.\|Failed .*\)$/p' "$1" | grep -v '<<Writing'; }

cells=$(grep -m1 -oE '^ *cells: *[0-9]+' < <(cd "$work" && "$ours" -quiet) | grep -oE '[0-9]+' || echo "?")
echo "case: $src ($cells cells), $repeats runs each, best wall time"
echo "checkMeshQuality: $ours (OMP_NUM_THREADS=${OMP_NUM_THREADS:-default})"
printf '%-34s %12s %18s %8s\n' "mode" "checkMesh [s]" "checkMeshQuality [s]" "ratio"
for mode in "" "-allGeometry -allTopology"; do
    # shellcheck disable=SC2086
    t_of=$(best_time "$work/of.log" checkMesh $mode)
    # shellcheck disable=SC2086
    t_mm=$(best_time "$work/mm.log" "$ours" $mode)
    ratio=$(awk -v a="$t_mm" -v b="$t_of" 'BEGIN { printf "%.3f", a / b }')
    printf '%-34s %12s %18s %8s\n' "${mode:-plain}" "$t_of" "$t_mm" "$ratio"
    if ! diff -q <(report "$work/of.log") <(report "$work/mm.log") >/dev/null; then
        echo "  note: reports differ in mode '${mode:-plain}':"
        diff <(report "$work/of.log") <(report "$work/mm.log") | head -10 | sed 's/^/    /'
    fi
done
