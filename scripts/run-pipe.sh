#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Set-up and the pipe tutorial in one command: installs the dependencies
# (scripts/install-deps.sh), configures the `release` preset into build/release, builds
# meshMorph's applications and its Python module with 2 jobs, installs the module with pip
# into the venv .venv (scripts/install-python.sh; `.venv/bin/python` imports it) and runs
# tutorials/pipe/Allrun (logs in tutorials/pipe/log.*; tutorials/pipe/Allclean removes them).
# Usage: scripts/run-pipe.sh [--no-openfoam]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

deps_args=()
for arg in "$@"; do
    case "$arg" in
        --no-openfoam) deps_args+=(--no-openfoam) ;;
        -h|--help) sed -n '3,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "run-pipe.sh: unknown option '$arg' (try --help)" >&2; exit 2 ;;
    esac
done

step() { echo; echo "==> $*"; }

step "Installing dependencies"
bash scripts/install-deps.sh "${deps_args[@]}"

targets=(checkMeshQuality morphMesh meshmorph_python)

step "Configuring (preset release)"
cmake --preset release

step "Building ${targets[*]} (preset release, 2 jobs)"
cmake --build --preset release --target "${targets[@]}"

step "Installing the Python module with pip into .venv (from /usr/bin/python3, system site packages)"
bash scripts/install-python.sh --build-dir build/release

step "Running tutorials/pipe/Allrun"
bash tutorials/pipe/Allclean
MESHMORPH_BUILD_DIR="$PWD/build/release" bash tutorials/pipe/Allrun
echo "run-pipe.sh: done; logs in tutorials/pipe/log.*"
