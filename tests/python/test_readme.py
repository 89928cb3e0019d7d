# SPDX-License-Identifier: GPL-3.0-or-later
"""The README's first design loop runs as written, where the README says to run it."""
import json
import re
import shutil
import subprocess

import numpy as np

from conftest import PIPE_MESH, SOURCE


def readme_code(heading, language):
    """The first ```language block after `heading` in README.md."""
    text = (SOURCE / "README.md").read_text()
    assert heading in text, f"README.md has no heading {heading!r}"
    block = re.search(r"```" + language + r"\n(.*?)```", text.split(heading, 1)[1], re.S)
    assert block, f"README.md: no {language} block under {heading!r}"
    return block.group(1)


def test_the_readme_design_loop_narrows_the_wall_and_writes_a_checked_design(
        tmp_path, monkeypatch, capsys):
    # As the README says: tutorials/python, after `cp -r ../pipe/constant .`
    case = tmp_path / "python"
    shutil.copytree(SOURCE / "tutorials" / "python" / "system", case / "system")
    shutil.copytree(PIPE_MESH, case / "constant" / "polyMesh")
    monkeypatch.chdir(case)

    scope = {}
    exec(compile(readme_code("## A first design loop in Python", "python"), "README.md",
                 "exec"), scope)

    study, a, objective = scope["study"], scope["a"], scope["J"]
    assert len(a) == len(study.names) == 32
    start, end = objective(np.zeros_like(a))[0], objective(a)[0]
    assert end < 0.5 * start, f"J went from {start} to {end} only"
    printed = capsys.readouterr().out.split()
    assert 0.0 <= float(printed[-1]) < 90.0   # the design's max non-orthogonality
    assert (case / "1" / "polyMesh" / "points").is_file()


def test_the_readme_first_morph_runs_as_written_and_leaves_a_checked_mesh(tmp_path):
    # From a repository root: tutorials/ and the build's applications where the README has them.
    from conftest import BUILD, application
    (tmp_path / "tutorials").symlink_to(SOURCE / "tutorials")
    (tmp_path / "build").mkdir()
    (tmp_path / "build" / "release").symlink_to(BUILD.resolve())
    for app in ("morphMesh", "checkMeshQuality"):
        application(app)   # built, or the test fails naming it

    script = readme_code("## A first morph", "sh")
    done = subprocess.run(["bash", "-e", "-c", script], cwd=tmp_path, capture_output=True,
                          text=True, stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr
    assert "Mesh OK." in done.stdout
    assert "Warning" not in done.stderr, done.stderr
    report = json.loads((tmp_path / "myPipe" / "morph.json").read_text())
    assert report["written"] and report["exitStatus"] == 0
    assert report["maxConstraintError"] < 1e-9 * report["maxPrescribedDisplacement"] + 1e-15
    assert (tmp_path / "myPipe" / "1" / "polyMesh" / "points").is_file()
