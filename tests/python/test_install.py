# SPDX-License-Identifier: GPL-3.0-or-later
"""The module as installed: which copy is imported, its version, and what an interpreter
that cannot run it is told (instead of a traceback from inside the package)."""
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import meshmorph
import pytest

from conftest import SOURCE

PACKAGE = Path(meshmorph.__file__).resolve().parent


def import_in_subprocess(code, pythonpath):
    env = dict(os.environ, PYTHONPATH=str(pythonpath), PYTHONDONTWRITEBYTECODE="1")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd="/", stdin=subprocess.DEVNULL)


def test_the_version_is_the_projects():
    cmake = (SOURCE / "CMakeLists.txt").read_text()
    assert meshmorph.__version__ == re.search(r"project\(meshmorph VERSION ([0-9.]+)",
                                              cmake).group(1)


def test_an_installed_copy_is_imported_from_the_environments_site_packages():
    if not os.environ.get("MESHMORPH_EXPECT_INSTALLED"):
        pytest.skip("the build tree's copy under test (MESHMORPH_EXPECT_INSTALLED is set by "
                    "scripts/run-tests.sh's pip stage)")
    site = Path(sysconfig.get_paths()["platlib"]).resolve()
    assert site in PACKAGE.parents, f"meshmorph imported from {PACKAGE}, not from {site}"


def test_without_numpy_the_error_names_the_interpreters_and_the_remedy():
    done = import_in_subprocess("import sys; sys.modules['numpy'] = None; import meshmorph",
                                PACKAGE.parent)
    assert done.returncode != 0
    assert "ImportError: meshmorph needs numpy" in done.stderr
    assert f"this interpreter: {sys.executable}" in done.stderr
    assert "was built for: " in done.stderr
    assert "-m pip install --no-build-isolation --no-index" in done.stderr
    # One frame of the package (its __init__), none from its insides.
    frames = re.findall(r'File "([^"]+)"', done.stderr)
    assert [Path(f).name for f in frames if "meshmorph" in f] == ["__init__.py"], done.stderr


def test_an_extension_built_for_another_python_is_explained(tmp_path):
    copy = tmp_path / "meshmorph"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    for module in copy.glob("_core*.so"):
        module.rename(copy / "_core.cpython-399-x86_64-linux-gnu.so")
    done = import_in_subprocess("import meshmorph", tmp_path)
    assert done.returncode != 0
    assert "ImportError: meshmorph's C++ extension does not load in this interpreter" \
        in done.stderr
    assert f"this interpreter: {sys.executable}" in done.stderr
    assert "was built for: " in done.stderr
