#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Python module meshmorph with pip (pyproject.toml, setup.py) into a venv made
# from Debian's python3 with --system-site-packages (so apt's numpy and SciPy are seen):
# .venv in the source tree unless --venv. Then `.venv/bin/python` imports meshmorph from
# anywhere; nothing goes into a site directory that other interpreters share.
# Usage: scripts/install-python.sh [--venv DIR] [--build-dir BUILD_DIR]
#   --venv DIR        the venv to make or reuse (default .venv)
#   --build-dir DIR   build the module in this configured CMake build tree (for instance
#                     build/release: only the module is compiled) instead of build/pip/...
# Another environment (a conda or pyenv python, the user site): docs/python.md.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
venv=.venv build_dir=''
while [[ $# -gt 0 ]]; do
    case "$1" in
        --venv) venv=${2:?--venv needs a directory}; shift ;;
        --build-dir) build_dir=$(cd "${2:?--build-dir needs a directory}" && pwd); shift ;;
        -h|--help) sed -n '3,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "install-python.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
    esac
    shift
done

# Earlier versions put a meshmorph.pth naming build/release/python into the user site of
# python3.11, where every python 3.11 (pyenv, conda) finds it, numpy or not.
user_site=$(/usr/bin/python3 -c 'import site; print(site.getusersitepackages())')
if [[ -f $user_site/meshmorph.pth ]]; then
    rm "$user_site/meshmorph.pth"
    echo "install-python.sh: removed $user_site/meshmorph.pth (an earlier install, seen by every python of that version)"
fi

venv=$(realpath -m "$venv")
[[ -x $venv/bin/python ]] || /usr/bin/python3 -m venv --system-site-packages "$venv"
# setup.py builds in build/pip/<interpreter> unless MESHMORPH_CMAKE_BUILD_DIR names a tree.
MESHMORPH_CMAKE_BUILD_DIR=$build_dir "$venv/bin/python" -m pip install --no-build-isolation \
    --no-index --no-warn-script-location --quiet "$PWD"
# Checked from another directory, so that the source tree cannot stand in for the install.
where=$(cd / && "$venv/bin/python" -c 'import meshmorph, os; print(os.path.dirname(meshmorph.__file__))')
echo "install-python.sh: $venv/bin/python imports meshmorph from $where"
