#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The reverse pass (dJ/dXs, Case.sensitivity) on the full motorBike: its time against the
# morph it reverses, and against differences of J through morphs (sensitivity_motorbike.py
# says what and why).
#
# Usage: sensitivity_motorbike.sh [-cache DIR] [-build DIR] [-lift F] [-results FILE |
#                                 -no-results] [-help]
#   -cache DIR   the full motorBike case (scripts/openfoam/motorbike.sh DIR full; default
#                build/cases/motorBike-full)
#   -build DIR   the build whose python/ module is used (default build/release)
#   -lift F      the lift, a fraction of the bike's height (default 0.02)
#   -results FILE  write the table there; -no-results: nowhere. Default:
#                benchmarks/results/sensitivity_motorbike.md
# About a minute on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
# shellcheck source=benchmarks/results.sh
source "$root/benchmarks/results.sh"
results_init "$@"
usage() { sed -n '3,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; }

cache="$root/build/cases/motorBike-full"
build="$root/build/release"
lift=0.02
while [[ $# -gt 0 ]]; do
    case $1 in
        -cache) cache=${2:?-cache needs a directory}; shift 2 ;;
        -build) build=${2:?-build needs a directory}; shift 2 ;;
        -lift) lift=${2:?-lift needs a fraction}; shift 2 ;;
        -results) results_file "${2:?-results needs a file}"; shift 2 ;;
        -no-results) results_off; shift ;;
        -h | -help | --help) usage; exit 0 ;;
        *) echo "sensitivity_motorbike.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
done
[[ -f $cache/constant/polyMesh/owner ]] ||
    { echo "sensitivity_motorbike.sh: no motorBike mesh in $cache (scripts/openfoam/motorbike.sh $cache full)" >&2; exit 1; }
[[ $lift == 0.02 ]] || results_partial "-lift $lift"
table=$(mktemp)
trap 'rm -f "$table"' EXIT
PYTHONPATH=$build/python /usr/bin/python3 "$root/benchmarks/morph/sensitivity_motorbike.py" \
    "$cache" "$lift" "$table" >/dev/null
cat "$table"
results_write sensitivity_motorbike "The reverse pass (dJ/dXs) on the full motorBike" <"$table"
