#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Set-up and full test run, as CI does it: installs the dependencies (scripts/install-deps.sh),
# checks that every C++ file is clang-format clean (.clang-format; fix with
# `git ls-files '*.cpp' '*.h' | xargs clang-format -i`), configures with the `ci` preset
# (Release, -Werror) into build/ci, builds with 2 jobs and runs every CTest test (unit, OpenFOAM oracle and tutorial tests) with 2 jobs.
# Usage: scripts/run-tests.sh [--no-openfoam]   (tests that need OpenFOAM then skip)
# Exits non-zero if any step or any test fails. ctest's output: build/ci/ctest.log,
# JUnit XML: build/ci/ctest-junit.xml.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

deps_args=()
for arg in "$@"; do
    case "$arg" in
        --no-openfoam) deps_args+=(--no-openfoam) ;;
        -h|--help) sed -n '3,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "run-tests.sh: unknown option '$arg' (try --help)" >&2; exit 2 ;;
    esac
done

step() { echo; echo "==> $* ($(date -u +%H:%M:%S) UTC)"; }
start=$SECONDS

step "Installing dependencies"
bash scripts/install-deps.sh "${deps_args[@]}"

step "Checking the format (clang-format, .clang-format)"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -z '*.cpp' '*.h' | xargs -0 clang-format --dry-run --Werror
else
    echo "run-tests.sh: not a git work tree; format check skipped"
fi

step "Configuring (preset ci)"
cmake --preset ci

step "Building (preset ci, 2 jobs)"
cmake --build --preset ci

step "Testing (preset ci, 2 jobs)"
status=0
ctest --preset ci --output-junit ctest-junit.xml 2>&1 | tee build/ci/ctest.log || status=$?

step "Summary"
# The ctest summary: pass rate, failed/skipped (not run) tests, time.
sed -n '/tests passed/,$p' build/ci/ctest.log
echo "run-tests.sh: $((SECONDS - start)) s in total; ctest exit status $status"
exit "$status"
