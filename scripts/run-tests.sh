#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Set-up and full test run, as CI does it: installs the dependencies (scripts/install-deps.sh),
# checks that every C++ file is clang-format clean (.clang-format; fix with
# `git ls-files '*.cpp' '*.h' | xargs clang-format -i`), configures with the `ci` preset
# (Release, -Werror) into build/ci, builds with 2 jobs and runs every CTest test (unit, OpenFOAM oracle and tutorial tests) with 2 jobs
# and OMP_NUM_THREADS=2, then the deform, morph and app tests once more with another
# OpenBLAS kernel (OPENBLAS_CORETYPE=SandyBridge, or Haswell where SandyBridge was the first).
# Then the Python module installed with pip into a fresh venv (build/pip-venv; its CMake build
# in build/pip/) and tests/python run against that copy from outside the source tree.
# Then the `asan` preset (clang, ASan + UBSan, Debug) into build/asan: the same tests except
# those labelled openfoam or tutorial, with OMP_NUM_THREADS=1, and each fuzz target 5 s over its
# seeds (scripts/fuzz.sh).
# Usage: scripts/run-tests.sh [--no-openfoam] [--no-asan]
#   --no-openfoam  tests that need OpenFOAM skip
#   --no-asan      skip the sanitizer build, its tests and the fuzz run
# Exits non-zero if any step or any test fails. ctest's output: build/ci/ctest.log and
# build/asan/ctest.log, JUnit XML: build/ci/ctest-junit.xml, build/asan/ctest-junit.xml.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

deps_args=()
with_asan=1
for arg in "$@"; do
    case "$arg" in
        --no-openfoam) deps_args+=(--no-openfoam) ;;
        --no-asan) with_asan=0 ;;
        -h|--help) sed -n '3,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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

# Results must not depend on the thread count: the ci stage runs with 2 OpenMP threads per
# test, the asan stage with 1 (and tests/app/same_result_test.cpp compares 1, 2 and 4).
step "Testing (preset ci, 2 jobs, OMP_NUM_THREADS=2)"
status=0
OMP_NUM_THREADS=2 ctest --preset ci --output-junit ctest-junit.xml 2>&1 | tee build/ci/ctest.log || status=$?

# Results must not depend on which OpenBLAS kernel runs either (a verdict that hangs on
# round-off flips between them): the numerical tests once more with another kernel than the
# first pass had (OPENBLAS_CORETYPE as this machine sets it, or OpenBLAS's own choice).
other_kernel=SandyBridge
[[ ${OPENBLAS_CORETYPE:-} == [Ss]andy[Bb]ridge ]] && other_kernel=Haswell
step "Testing again with OPENBLAS_CORETYPE=$other_kernel (deform, morph, app; first pass: ${OPENBLAS_CORETYPE:-chosen by OpenBLAS})"
kernel_status=0
OPENBLAS_CORETYPE=$other_kernel OMP_NUM_THREADS=2 ctest --preset ci -L 'deform|morph|app' \
    -LE 'openfoam|tutorial' --output-junit ctest-junit-kernel.xml 2>&1 |
    tee build/ci/ctest-kernel.log || kernel_status=$?
[[ $status -eq 0 ]] && status=$kernel_status

# The Python module as users get it: pip into a fresh venv (the whole CMake build of
# setup.py, in build/pip/), then its tests against that copy, run from / so that neither the
# source tree nor build/ci can stand in for it (the applications they compare with: build/ci).
step "Installing the Python module with pip into a fresh venv (build/pip-venv) and testing that copy"
venv=$PWD/build/pip-venv
rm -rf "$venv"
/usr/bin/python3 -m venv --system-site-packages "$venv"
pip_status=0
"$venv/bin/python" -m pip install --no-build-isolation --no-index "$PWD" 2>&1 |
    tee build/pip-install.log || pip_status=$?
if [[ $pip_status -eq 0 ]]; then
    (cd / && MESHMORPH_EXPECT_INSTALLED=1 MESHMORPH_BUILD_DIR=$OLDPWD/build/ci OMP_NUM_THREADS=2 \
        PYTHONDONTWRITEBYTECODE=1 "$venv/bin/python" -m pytest -q -p no:cacheprovider \
        --basetemp="$venv/pytest" "$OLDPWD/tests/python") 2>&1 | tee build/pip-pytest.log ||
        pip_status=$?
fi
[[ $status -eq 0 ]] && status=$pip_status

asan_status=0
if [[ $with_asan == 1 ]]; then
    asan_start=$SECONDS
    step "Configuring (preset asan: clang, ASan + UBSan, fuzz targets)"
    cmake --preset asan

    step "Building (preset asan, 2 jobs)"
    cmake --build --preset asan

    step "Testing under ASan + UBSan (preset asan, 2 jobs, OMP_NUM_THREADS=1; OpenFOAM oracle and tutorial tests excluded)"
    # Any sanitizer report aborts its test (-fno-sanitize-recover, LeakSanitizer's exit code).
    OMP_NUM_THREADS=1 ctest --preset asan -j2 --timeout 900 -LE 'openfoam|tutorial|foam_cases' --output-junit ctest-junit.xml \
        2>&1 | tee build/asan/ctest.log || asan_status=$?

    step "Fuzzing (each target 5 s over its seeds, build/asan)"
    bash scripts/fuzz.sh --build-dir build/asan --no-build --time 5 || asan_status=1
    echo "run-tests.sh: the asan stage took $((SECONDS - asan_start)) s"
fi

step "Summary"
# The ctest summary: pass rate, failed/skipped (not run) tests, time.
sed -n '/tests passed/,$p' build/ci/ctest.log
echo "again with OPENBLAS_CORETYPE=$other_kernel:"
sed -n '/tests passed/,$p' build/ci/ctest-kernel.log
echo "the pip-installed module (build/pip-pytest.log):"
tail -n 1 build/pip-pytest.log 2>/dev/null || echo "not tested: pip install failed (build/pip-install.log)"
if [[ $with_asan == 1 ]]; then
    echo "asan (ASan + UBSan):"
    sed -n '/tests passed/,$p' build/asan/ctest.log
fi
echo "run-tests.sh: $((SECONDS - start)) s in total; ctest exit status $status, asan stage $asan_status"
[[ $status -ne 0 ]] && exit "$status"
exit "$asan_status"
