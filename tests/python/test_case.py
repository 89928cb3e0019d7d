# SPDX-License-Identifier: GPL-3.0-or-later
"""meshmorph.Case against the applications: the same numbers and files, bit for bit."""
import json
import shutil

import numpy as np
import pytest

import meshmorph
from conftest import run, run_json, write_dict

# A natural morphDict: the wall squeezed to 90 % about the pipe's axis, the ends sliding.
SQUEEZE = """
method rbf;
boundary
{
    wall { type scale; origin (0 0 1); factor (0.9 0.9 1); }
    "(inlet|outlet)" { type slip; }
}
"""


def test_reads_the_mesh_checkmeshquality_reads(pipe):
    case = meshmorph.Case(pipe)
    cli = run_json("checkMeshQuality", cwd=pipe)
    assert (case.n_points, case.n_faces, case.n_cells) == (cli["points"], cli["faces"], cli["cells"])
    assert list(case.patches) == ["inlet", "outlet", "wall"]
    assert case.patches["wall"]["type"] == "wall"
    assert case.time == "constant" and case.instance == "constant"
    wall = case.patch_points("wall")
    assert wall.dtype == np.int64 and len(np.unique(wall)) == len(wall)


def test_check_equals_checkmeshquality_json(pipe):
    case = meshmorph.Case(pipe)
    for flags, kwargs in (((), {}), (("-allGeometry", "-allTopology"),
                                     {"all_geometry": True, "all_topology": True})):
        cli = run_json("checkMeshQuality", *flags, cwd=pipe)
        mine = case.check(**kwargs)
        # The scaled Jacobian is computed for the JSON only (checkMeshQuality -json): the
        # rest must be the same numbers, not merely close.
        for key in set(cli) - {"case", "minScaledJacobian"}:
            assert mine[key] == cli[key], key


def test_points_are_read_only_views_that_outlive_morphs(pipe):
    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    case = meshmorph.Case(pipe)
    x0 = case.initial_points
    before = case.points
    assert not before.flags.writeable and not x0.flags.writeable
    with pytest.raises(ValueError):
        before[0, 0] = 1.0
    copy_before = before.copy()
    case.morph()
    assert np.array_equal(before, copy_before)  # the old view: unchanged, still valid
    assert not np.array_equal(case.points, copy_before)
    assert np.shares_memory(case.points, case.points)  # no copy per access after a change
    case.reset()
    assert np.array_equal(case.points, x0)


def test_morph_with_the_morphdict_writes_morphmesh_s_file(pipe, tmp_path):
    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    other = tmp_path / "cli"
    shutil.copytree(pipe, other)
    cli = run_json("morphMesh", cwd=other)

    case = meshmorph.Case(pipe)
    report = case.morph()
    assert not report["refused"]
    for key in ("method", "constraints", "centres", "maxConstraintError", "maxDisplacement"):
        assert report[key] == cli[key], key
    assert report["after"]["maxNonOrthogonality"] == cli["after"]["maxNonOrthogonality"]
    written = case.write()
    assert str(written).endswith("1/polyMesh/points")
    assert (pipe / "1/polyMesh/points").read_bytes() == (other / "1/polyMesh/points").read_bytes()
    assert not list((pipe / "1/polyMesh").glob("*.tmp*"))  # atomic: no temporary left


def test_prescribed_values_equal_the_dictionary_s_motion(pipe):
    """A translation given as a vector, as per-point values and as a morphDict entry: one
    morph, the same points to the bit."""
    write_dict(pipe / "system" / "morphDict",
               'method rbf; boundary { wall { type translate; vector (0.01 0.02 0); } '
               '"(inlet|outlet)" { type slip; } }')
    case = meshmorph.Case(pipe)
    case.morph()
    from_dict = case.points.copy()
    case.morph(patches={"wall": [0.01, 0.02, 0.0]})
    assert np.array_equal(case.points, from_dict)
    n = len(case.patch_points("wall"))
    values = np.tile([0.01, 0.02, 0.0], (n, 1))
    case.morph(patches={"wall": values})
    assert np.array_equal(case.points, from_dict)
    # Strided (non-contiguous) and integer-typed input is converted, not misread.
    strided = np.tile([0.01, 0.02, 0.0, 7.0], (n, 1))[:, :3]
    assert not strided.flags.c_contiguous
    case.morph(patches={"wall": strided})
    assert np.array_equal(case.points, from_dict)


def test_point_sets_are_exact_and_override_patches(pipe):
    case = meshmorph.Case(pipe)  # no morphDict: unnamed patches are fixed
    wall = case.patch_points("wall")
    labels = wall[::7]
    d = np.zeros((len(labels), 3))
    d[:, 1] = 0.02 * np.sin(case.initial_points[labels, 2])
    report = case.morph(patches={"inlet": "slip", "outlet": "slip"}, points={"dent": (labels, d)})
    assert report["maxConstraintError"] < 1e-12
    assert np.allclose(case.points[labels] - case.initial_points[labels], d, atol=1e-14, rtol=0)
    others = np.setdiff1d(wall, labels)
    assert np.array_equal(case.points[others], case.initial_points[others])  # still fixed


def test_is_valid_and_refusal(pipe):
    case = meshmorph.Case(pipe)
    assert case.is_valid()
    # Pull the upper half of the wall down through the axis, the lower half fixed: cells
    # fold (a point reflection of the whole section would be a rotation, and valid).
    wall = case.patch_points("wall")
    x = case.initial_points[wall]
    d = np.zeros_like(x)
    top = x[:, 1] > 0
    d[top, 1] = -1.5 * x[top, 1]
    report = case.morph(patches={"wall": d, "inlet": "free", "outlet": "free"})
    assert report["refused"] and not case.is_valid()
    with pytest.raises(meshmorph.InputError, match="refused"):
        case.write()
    assert not (pipe / "1").exists()
    case.reset()
    assert case.is_valid()
    inverted = case.initial_points.copy()
    inverted[:, 0] *= -1.0  # a mirror image: every cell turned inside out
    case.set_points(inverted)
    assert not case.is_valid()


def test_overwrite_keeps_the_original(pipe):
    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    original = (pipe / "constant/polyMesh/points").read_bytes()
    case = meshmorph.Case(pipe)
    case.morph()
    case.write(overwrite=True)
    assert (pipe / "constant/polyMesh/points.orig").read_bytes() == original
    assert (pipe / "constant/polyMesh/points").read_bytes() != original
    reread = meshmorph.Case(pipe)
    assert np.allclose(reread.initial_points, case.points, rtol=0, atol=1e-12)


def test_bad_input_raises_with_the_applications_messages(pipe):
    broken = pipe / "system" / "morphDict"
    write_dict(broken, "method rbf;\nboundary\n{\n    wall { type wobble; }\n}")
    cli = run("morphMesh", cwd=pipe, expect=2)
    case = meshmorph.Case(pipe)
    with pytest.raises(meshmorph.ParseError) as error:
        case.morph()
    assert isinstance(error.value, ValueError) and isinstance(error.value, meshmorph.Error)
    assert str(error.value) in cli.stderr
    assert "morphDict:5" in str(error.value)  # the header is line 1

    with pytest.raises(meshmorph.IoError) as missing:
        meshmorph.Case(pipe / "nowhere")
    assert isinstance(missing.value, OSError)

    n = case.n_points
    wall = case.patch_points("wall")
    bad_calls = {
        "unknown patch": lambda: case.morph(patches={"nope": "fixed"}),
        "rows": lambda: case.morph(patches={"wall": np.zeros((3, 3))}),
        "shape": lambda: case.morph(patches={"wall": np.zeros((len(wall), 2))}),
        "vector": lambda: case.morph(patches={"wall": [1, 2]}),
        "motion": lambda: case.morph(patches={"wall": "wobble"}),
        "strings": lambda: case.morph(patches={"wall": np.array(["a", "b", "c"])}),
        "nan": lambda: case.morph(patches={"wall": np.full((len(wall), 3), np.nan)}),
        "inf vector": lambda: case.morph(patches={"wall": [np.inf, 0, 0]}),
        "float labels": lambda: case.morph(points={"s": ([1.5], np.zeros((1, 3)))}),
        "repeated label": lambda: case.morph(points={"s": ([0, 0], np.zeros((2, 3)))}),
        "label range": lambda: case.morph(points={"s": ([n], np.zeros((1, 3)))}),
        "negative label": lambda: case.morph(points={"s": ([-1], np.zeros((1, 3)))}),
        "not a pair": lambda: case.morph(points={"s": 5}),
        "points nan": lambda: case.set_points(np.full((n, 3), np.nan)),
        "points shape": lambda: case.set_points(np.zeros((n, 2))),
        "points objects": lambda: case.set_points(np.full((n, 3), None)),
        "dict and values": lambda: case.morph("system/morphDict", patches={"wall": "fixed"}),
        "nothing": lambda: case.morph(patches={}),
    }
    for name, call in bad_calls.items():
        with pytest.raises((meshmorph.Error, ValueError, TypeError)):
            call()
        assert case.is_valid(), name  # nothing half-done
    assert np.array_equal(case.points, case.initial_points)


def test_threads_take_turns_on_one_case(pipe):
    """The GIL is released during a morph: calls on one case from several threads must
    neither crash nor mix their results."""
    import threading

    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    case = meshmorph.Case(pipe)
    case.morph()
    expected = case.points.copy()
    errors = []

    def work():
        try:
            for _ in range(3):
                case.morph()
                assert case.is_valid()
                assert np.array_equal(case.points, expected)
        except Exception as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors


def test_log_goes_to_python_logging(pipe, caplog):
    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    case = meshmorph.Case(pipe)
    with caplog.at_level("INFO", logger="meshmorph"):
        case.morph()
    assert any(r.name == "meshmorph" and r.message.startswith("Method: rbf")
               for r in caplog.records)
