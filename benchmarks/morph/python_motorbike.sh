#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A design variant from Python against the same variant from the command line, on the full
# motorBike with the six design variables of design_motorbike.sh (run that first: it makes
# the case and its set-up; -setup makes the set-up again, e.g. after an upgrade made it
# stale), in one run:
#   - morphMesh -variant "(1 2 1 0.05 -0.05 1)": wall time (best of 3), and the start-up of
#     the process alone (morphMesh -help, best of 3);
#   - Python (meshmorph module): DesignStudy() (reads the mesh and the set-up's header: the
#     command line's reading), then evaluate(a) (combine + checkMesh's check), write(),
#     points(a) alone, is_valid(a) and transpose_product(dJ/dx), each best of 3;
#   - the natural one-off morph (natural_morph.sh) by morphMesh and by Case.morph() +
#     write(): wall times and whether the points files are identical.
# The acceptance: evaluate + write <= the command line's wall - start-up - reading.
# Prints and writes OUT/python.md.
#
#   python_motorbike.sh [-case DIR] [-build DIR] [-out DIR] [-cache DIR] [-setup]
#                       [-results FILE | -no-results]
#
# -results FILE: also write python.md with the run's context (date, machine, OS, commit, this
# command line) to FILE (benchmarks/results.sh); -no-results: write no such file. Default:
# benchmarks/results/python_motorbike.md (every run measures the whole set; the options only
# say where things are); none when MESHMORPH_NO_RESULTS=1 (tests, quick runs).
set -euo pipefail
script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$script_dir/../.." && pwd)
source "$script_dir/natural_morph.sh"
# shellcheck source=SCRIPTDIR/../results.sh
source "$root/benchmarks/results.sh"   # results_init, results_write, ...
results_init "$@"
cache=$root/build/cases/motorBike-full
case_dir=$root/build/bench/design/design
build=$root/build/release
out=$root/build/bench/python
setup=false
while [[ $# -gt 0 ]]; do
    case $1 in
        -case) case_dir=$2; shift 2 ;;
        -build) build=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -cache) cache=$2; shift 2 ;;
        -setup) setup=true; shift ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        *) echo "usage: python_motorbike.sh [-case DIR] [-build DIR] [-out DIR] [-cache DIR] [-setup] [-results FILE | -no-results]" >&2; exit 2 ;;
    esac
done
[ -f "$case_dir/constant/designBasis" ] ||
    { echo "python_motorbike.sh: no set-up in $case_dir: run design_motorbike.sh first" >&2; exit 1; }
morph_mesh=$build/applications/morphMesh/morphMesh
rm -rf "$out" && mkdir -p "$out"
if $setup; then
    # Earlier variants in time directories would be read as the mesh (morphMesh reads the
    # earliest time): the set-up is made on constant/.
    find "$case_dir" -mindepth 1 -maxdepth 1 -type d -regex '.*/[0-9][0-9.e+-]*' -exec rm -rf {} +
    "$morph_mesh" -case "$case_dir" -variables >"$out/log.variables" 2>&1 ||
        { tail -5 "$out/log.variables" >&2; exit 1; }
fi
amplitudes="(1 2 1 0.05 -0.05 1)"

best_wall() { # best_wall <log> <cmd...>: the best wall time of three runs
    local walls=()
    for k in 1 2 3; do
        /usr/bin/time -f "%e" -o "$1.time" "${@:2}" >"$1" 2>&1 ||
            { tail -5 "$1" >&2; echo "python_motorbike.sh: ${*:2} failed" >&2; exit 1; }
        walls+=("$(tail -1 "$1.time")")
    done
    printf '%s\n' "${walls[@]}" | sort -g | head -1
}
cli_wall=$(best_wall "$out/log.variant" "$morph_mesh" -case "$case_dir" -variant "$amplitudes" -json "$out/variant.json")
startup_wall=$(best_wall "$out/log.help" "$morph_mesh" -help)
instance=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['outputInstance'])" "$out/variant.json")
cp "$case_dir/$instance/polyMesh/points" "$out/cli.points"

natural_motorbike_case "$cache" "$out/natural_cli"
natural_motorbike_case "$cache" "$out/natural_python"
natural_wall=$(best_wall "$out/log.natural" "$morph_mesh" -case "$out/natural_cli")

PYTHONPATH=$build/python /usr/bin/python3 - "$case_dir" "$out" "$cli_wall" "$startup_wall" "$natural_wall" <<'PY' | tee "$out/python.md"
import filecmp, json, sys, time
import numpy as np
import meshmorph

case, out, cli_wall, startup = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
natural_wall = float(sys.argv[5])
a = np.array([1, 2, 1, 0.05, -0.05, 1.0])

def best(f, k=3):
    times = []
    for _ in range(k):
        t = time.perf_counter(); r = f(); times.append(time.perf_counter() - t)
    return min(times), r

open_s, study = best(lambda: meshmorph.DesignStudy(case), 1)
eval_s, report = best(lambda: study.evaluate(a))
write_s, path = best(lambda: study.write())
same = filecmp.cmp(path, f"{out}/cli.points", shallow=False)
points_s, x = best(lambda: study.points(a))
valid_s, valid = best(lambda: study.is_valid(a))
g = np.random.default_rng(0).normal(size=x.shape)
grad_s, _ = best(lambda: study.transpose_product(g))
cli = json.load(open(f"{out}/variant.json"))
budget = cli_wall - startup - open_s
print(f"# A variant from Python and from the command line, full motorBike ({x.shape[0]} points)\n")
print("| step | seconds |\n| --- | --- |")
print(f"| morphMesh -variant, whole process (best of 3) | {cli_wall:.3f} |")
print(f"| its start-up alone (morphMesh -help) | {startup:.3f} |")
print(f"| Python: DesignStudy() (mesh and set-up header read) | {open_s:.3f} |")
print(f"| command line minus start-up and reading | {budget:.3f} |")
print(f"| Python: evaluate(a) (combine {report['timings']['combine']:.3f}, check {report['timings']['check']:.3f}) | {eval_s:.3f} |")
print(f"| Python: write() | {write_s:.3f} |")
print(f"| Python: evaluate + write | {eval_s + write_s:.3f} ({(eval_s + write_s) / budget:.2f} of the budget) |")
print(f"| Python: points(a) alone | {points_s:.3f} |")
print(f"| Python: is_valid(a) | {valid_s:.3f} |")
print(f"| Python: transpose_product(dJ/dx) | {grad_s:.3f} |")
print(f"\nCommand line's own stage times: combine {cli['timings']['combine']:.3f}, check {cli['timings']['check']:.3f}, write {cli['timings']['write']:.3f} s")
print(f"Points file written by Python identical to the command line's: {same}")
print(f"Variant valid: {report['valid']} (is_valid: {valid})")

t = time.perf_counter()
natural = meshmorph.Case(f"{out}/natural_python")
natural_open = time.perf_counter() - t
morph_s, morph_report = best(natural.morph)
natural_write_s, natural_path = best(lambda: natural.write(), 1)
natural_same = filecmp.cmp(natural_path, f"{out}/natural_cli/1/polyMesh/points", shallow=False)
print(f"\nThe natural morph (every motorBike_.* patch lifted by 5 %):\n")
print("| step | seconds |\n| --- | --- |")
print(f"| morphMesh, whole process (best of 3) | {natural_wall:.3f} |")
print(f"| Python: Case() | {natural_open:.3f} |")
print(f"| Python: morph() (best of 3) | {morph_s:.3f} |")
print(f"| Python: write() | {natural_write_s:.3f} |")
print(f"\nPoints file written by Python identical to morphMesh's: {natural_same}; "
      f"refused: {morph_report['refused']}, max constraint error {morph_report['maxConstraintError']:.3g}")
PY
results_write_report python_motorbike "$out/python.md"
