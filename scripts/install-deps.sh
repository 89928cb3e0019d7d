#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs meshMorph's build and test dependencies from Debian 12 packages.
#
# Usage: scripts/install-deps.sh [--no-openfoam] [--no-plots] [--check]
#   --no-openfoam  skip OpenFOAM and gmsh (the oracle tests that need them then skip)
#   --no-plots     skip the optional python3-matplotlib (plot scripts)
#   --check        only report what is missing; never install (exit 1 if anything is)
#
# Idempotent: packages already present are detected with dpkg-query, so a second run
# installs nothing and takes well under a second. As root it runs `apt-get update` once
# (only if something is missing) and installs non-interactively; as another user it
# prints the apt-get command to run and exits non-zero.
set -euo pipefail

with_openfoam=1
with_plots=1
check_only=0
for arg in "$@"; do
    case "$arg" in
        --no-openfoam) with_openfoam=0 ;;
        --no-plots) with_plots=0 ;;
        --check) check_only=1 ;;
        -h|--help) sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "install-deps.sh: unknown option '$arg' (try --help)" >&2; exit 2 ;;
    esac
done

# Build: compiler, CMake, Eigen, VTK, BLAS/LAPACK, JSON, zlib, OpenMPI (-parallel); tests
# and benchmarks; clang-format for the format check of scripts/run-tests.sh; clang for the
# asan preset and the fuzz targets: libclang-rt-14-dev holds the ASan/UBSan runtimes and
# libFuzzer (only recommended by clang, so named here), llvm its llvm-symbolizer (readable
# sanitizer stack traces).
required=(build-essential cmake g++ git libeigen3-dev libvtk9-dev libopenblas-dev liblapack-dev
          nlohmann-json3-dev zlib1g-dev libgtest-dev libgmock-dev libbenchmark-dev clang-format
          libopenmpi-dev openmpi-bin clang libclang-rt-14-dev llvm)
# The Python module (pybind11, Debian's python3 and numpy), its tests (pytest) and the
# tutorials/python example (SciPy's optimisers).
required+=(python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-scipy)
# pip's route for the module (pyproject.toml: setuptools and wheel, no build isolation, venv).
required+=(python3-pip python3-venv python3-setuptools python3-wheel)
# Oracle tests compare with OpenFOAM v1912 (Debian) and use its tutorials and gmsh.
if [[ $with_openfoam == 1 ]]; then
    required+=(openfoam openfoam-examples gmsh)
fi
optional=()
if [[ $with_plots == 1 ]]; then
    optional+=(python3-matplotlib)
fi

# missing_of <package...>: prints those of the packages that are not installed, one a line
# (one dpkg-query call; unknown packages are reported on stderr by dpkg-query, hence 2>/dev/null).
missing_of() {
    local installed
    installed=$(dpkg-query -W -f='${binary:Package} ${db:Status-Status}\n' "$@" 2>/dev/null |
                awk '$2 == "installed" { sub(/:.*/, "", $1); print $1 }' || true)
    local pkg
    for pkg in "$@"; do
        grep -qxF "$pkg" <<<"$installed" || echo "$pkg"
    done
}

mapfile -t missing < <(missing_of "${required[@]}" "${optional[@]}")

# Debian's openfoam-examples puts the tutorials under /usr/share/doc, which slim container
# images exclude from installation (dpkg path-exclude): the package is then "installed"
# but empty, and the snappyHexMesh test cases cannot be made.
check_tutorials() {
    if [[ $with_openfoam == 1 ]] &&
       [[ ! -d /usr/share/doc/openfoam-examples/examples/mesh/snappyHexMesh ]]; then
        echo "install-deps: warning: openfoam-examples has no tutorials in" \
             "/usr/share/doc/openfoam-examples/examples (a dpkg path-exclude of" \
             "/usr/share/doc in /etc/dpkg/dpkg.cfg.d?); remove it, then" \
             "apt-get install --reinstall openfoam-examples" >&2
    fi
}

if [[ ${#missing[@]} -eq 0 ]]; then
    echo "install-deps: all ${#required[@]} required and ${#optional[@]} optional packages are installed"
    check_tutorials
    exit 0
fi

echo "install-deps: missing packages: ${missing[*]}"
if [[ $check_only == 1 ]]; then
    exit 1
fi
if [[ $(id -u) -ne 0 ]]; then
    echo "install-deps: not root; install them with:" >&2
    echo "    sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
    echo "install-deps: apt-get not found; meshMorph's set-up script supports Debian 12 only." >&2
    echo "    Install the equivalents of: ${missing[*]}" >&2
    exit 1
fi

export DEBIAN_FRONTEND=noninteractive
apt_opts=(-y -q -o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold)
echo "install-deps: apt-get update"
apt-get update -q </dev/null
echo "install-deps: apt-get install ${missing[*]}"
apt-get install "${apt_opts[@]}" "${missing[@]}" </dev/null

mapfile -t still_missing < <(missing_of "${missing[@]}")
if [[ ${#still_missing[@]} -ne 0 ]]; then
    echo "install-deps: still missing after apt-get install: ${still_missing[*]}" >&2
    exit 1
fi
check_tutorials
echo "install-deps: done"
