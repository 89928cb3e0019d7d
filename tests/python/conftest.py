# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the Python module's tests: the build's applications and small cases.

CTest (tests/python/CMakeLists.txt) sets PYTHONPATH to <build>/python and
MESHMORPH_BUILD_DIR to the build; run by hand:
    PYTHONPATH=build/ci/python MESHMORPH_BUILD_DIR=build/ci python3 -m pytest tests/python
"""
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("MESHMORPH_BUILD_DIR", SOURCE / "build" / "ci"))
PIPE_MESH = SOURCE / "tutorials" / "pipe" / "constant" / "polyMesh"
DESIGN_DICT = SOURCE / "tutorials" / "designVariables" / "system" / "morphDict"


def application(name):
    path = BUILD / "applications" / name / name
    if not path.is_file():
        pytest.fail(f"{path} not built (MESHMORPH_BUILD_DIR={BUILD})")
    return str(path)


def run(name, *args, cwd=None, expect=0):
    """Run an application; returns its completed process (stdout, stderr as text)."""
    # Without LD_PRELOAD: a sanitizer runtime preloaded into python for a sanitized module
    # (docs/python.md) must not be preloaded into the applications as well.
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    done = subprocess.run([application(name), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, stdin=subprocess.DEVNULL, env=env)
    assert done.returncode == expect, f"{name} {args}: exit {done.returncode}\n{done.stderr}"
    return done


def run_json(name, *args, cwd):
    run(name, *args, "-json", "report.json", cwd=cwd)
    return json.loads((Path(cwd) / "report.json").read_text())


def write_dict(path, body):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("FoamFile { version 2.0; format ascii; class dictionary; object "
                    f"{path.name}; }}\n{body}\n")


@pytest.fixture
def pipe(tmp_path):
    """The pipe tutorial's mesh (2651 points, 2240 cells; patches inlet, outlet, wall) in a
    case of its own, with the tutorial's controlDict and no morphDict."""
    case = tmp_path / "pipe"
    shutil.copytree(PIPE_MESH, case / "constant" / "polyMesh")
    (case / "system").mkdir()
    shutil.copy(SOURCE / "tutorials" / "pipe" / "system" / "controlDict", case / "system")
    return case


@pytest.fixture
def design_pipe(pipe):
    """The pipe with the designVariables tutorial's morphDict (11 variables)."""
    shutil.copy(DESIGN_DICT, pipe / "system" / "morphDict")
    return pipe
