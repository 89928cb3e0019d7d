#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the system python3 (/usr/bin/python3) import the meshmorph module of a build:
# writes meshmorph.pth, naming <build>/python, into the user's site-packages (no copy:
# a rebuild updates the module). Undo: rm "$(python3 -m site --user-site)/meshmorph.pth".
# Usage: scripts/install-python.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build/release}
package="$PWD/$build/python"
python=/usr/bin/python3
if ! compgen -G "$package/meshmorph/_core*.so" > /dev/null; then
    echo "install-python.sh: $package/meshmorph/_core*.so not built (build the target meshmorph_python)" >&2
    exit 1
fi
site=$("$python" -c 'import site; print(site.getusersitepackages())')
mkdir -p "$site"
echo "$package" > "$site/meshmorph.pth.tmp"
mv "$site/meshmorph.pth.tmp" "$site/meshmorph.pth"
# Check from another directory, so that the source tree cannot stand in for the install.
version=$(cd / && "$python" -c 'import meshmorph, os; print(os.path.dirname(meshmorph.__file__))')
echo "install-python.sh: $python imports meshmorph from $version ($site/meshmorph.pth)"
