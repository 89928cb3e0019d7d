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
        # The same numbers, not merely close (the case path is written as given).
        for key in set(cli) - {"case"}:
            assert mine[key] == cli[key], key
        assert mine["minScaledJacobian"] is not None
    assert case.check(scaled_jacobian=False)["minScaledJacobian"] is None


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

    case = meshmorph.Case(pipe, scaled_jacobian=True)  # morphMesh -json computes it
    report = case.morph()
    assert not report["refused"]
    for key in ("method", "constraints", "centres", "maxConstraintError", "maxDisplacement"):
        assert report[key] == cli[key], key
    for key in set(cli["after"]) - {"case"}:
        assert report["after"][key] == cli["after"][key], key
        assert report["before"][key] == cli["before"][key], key
    # The points themselves: the file the command line wrote, read back (17 significant
    # digits: the doubles round-trip), equals the array in memory.
    assert np.array_equal(meshmorph.Case(other, time="1").initial_points, case.points)
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
    # A default open would morph the morphed points again: refused, naming the way to ask.
    with pytest.raises(meshmorph.InputError, match="-time constant"):
        meshmorph.Case(pipe)
    reread = meshmorph.Case(pipe, time="constant")
    assert np.allclose(reread.initial_points, case.points, rtol=0, atol=1e-12)


def test_a_second_case_of_the_same_directory_reads_what_the_first_read(pipe):
    """The re-run rule in Python: a Case opened after a write reads the mesh the case
    starts from (constant), not the written result, and writes the same time."""
    write_dict(pipe / "system" / "morphDict", SQUEEZE)
    first = meshmorph.Case(pipe)
    first.morph()
    path = first.write()
    again = meshmorph.Case(pipe)
    assert again.instance == "constant"
    again.morph()
    assert again.write() == path
    assert np.array_equal(again.points, first.points)
    assert b"morphed by morphMesh" in path.read_bytes()[:2000]


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


def test_bad_prescriptions_raise_and_change_nothing(pipe):
    case = meshmorph.Case(pipe)  # no morphDict: each call fails on its own check
    n = case.n_points
    wall = case.patch_points("wall")
    bad_calls = [
        (lambda: case.morph(patches={"nope": "fixed"}), meshmorph.InputError, "no patch 'nope'"),
        (lambda: case.morph(patches={"wall": np.zeros((3, 3))}), meshmorph.InputError,
         f"3 rows given, {len(wall)} expected"),
        (lambda: case.morph(patches={"wall": np.zeros((len(wall), 2))}), ValueError,
         "expected shape (n, 3)"),
        (lambda: case.morph(patches={"wall": [1, 2]}), ValueError, "vector of 3 numbers"),
        (lambda: case.morph(patches={"wall": "wobble"}), ValueError, "not a motion"),
        (lambda: case.morph(patches={"wall": np.array(["a", "b", "c"])}), TypeError,
         "real numbers"),
        (lambda: case.morph(patches={"wall": np.full((len(wall), 3), np.nan)}),
         meshmorph.InputError, "not finite"),
        (lambda: case.morph(patches={"wall": [np.inf, 0, 0]}), meshmorph.InputError, "not finite"),
        (lambda: case.morph(points={"s": ([1.5], np.zeros((1, 3)))}), TypeError, "integers"),
        (lambda: case.morph(points={"s": ([0, 0], np.zeros((2, 3)))}), meshmorph.InputError,
         "listed twice"),
        (lambda: case.morph(points={"s": ([n], np.zeros((1, 3)))}), meshmorph.InputError,
         "out of range"),
        (lambda: case.morph(points={"s": ([-1], np.zeros((1, 3)))}), meshmorph.InputError,
         "out of range"),
        (lambda: case.morph(points={"s": (np.array([2**63 + 5], dtype=np.uint64),
                                          np.zeros((1, 3)))}), ValueError,
         f"label {2**63 + 5} out of range"),
        (lambda: case.morph(points={"s": 5}), TypeError, "(labels, displacements)"),
        (lambda: case.morph(patches="wall"), TypeError, "expected a dict"),
        (lambda: case.morph(patches={1: "fixed"}), TypeError, "names must be strings"),
        (lambda: case.set_points(np.full((n, 3), np.nan)), meshmorph.InputError, "not finite"),
        (lambda: case.set_points(np.zeros((n, 2))), ValueError, f"expected shape ({n}, 3)"),
        (lambda: case.set_points(np.full((n, 3), None)), TypeError, "real numbers"),
        (lambda: case.morph("system/morphDict", patches={"wall": "fixed"}), ValueError,
         "not both"),
        (lambda: case.morph(patches={}), meshmorph.InputError, "no prescriptions"),
        (lambda: case.morph(), meshmorph.IoError, "morphDict"),
    ]
    for call, kind, message in bad_calls:
        with pytest.raises(kind) as error:
            call()
        assert message in str(error.value)
        assert case.is_valid()  # nothing half-done
    assert np.array_equal(case.points, case.initial_points)
    assert not any(p.name[0].isdigit() for p in pipe.iterdir())  # nothing written


def test_a_failed_or_other_dictionary_does_not_change_later_morphs(pipe):
    write_dict(pipe / "system" / "morphDict",
               'method rbf; boundary { "(inlet|outlet)" { type slip; } }')
    write_dict(pipe / "system" / "morphDict.idw",
               'method idw; boundary { wall { type translate; vector (0.01 0 0); } }')
    prescriptions = {"wall": [0.0, 0.01, 0.0]}
    fresh = meshmorph.Case(pipe)
    expected = fresh.morph(patches=prescriptions)
    case = meshmorph.Case(pipe)
    with pytest.raises(meshmorph.IoError):
        case.morph("system/missing")
    assert case.morph("system/morphDict.idw")["method"] == "idw"
    report = case.morph(patches=prescriptions)
    assert report["method"] == expected["method"] == "rbf"
    assert np.array_equal(case.points, fresh.points)


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

    def reset_and_read():  # views taken while other threads morph: whole and read-only
        try:
            for _ in range(20):
                case.set_points(expected)
                p = case.points
                assert p.shape == expected.shape and not p.flags.writeable
        except Exception as e:
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(3)]
    threads.append(threading.Thread(target=reset_and_read))
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


def test_region_and_time_select_what_morphmesh_selects(pipe, tmp_path):
    """-region and -time/-latestTime: a region's mesh, dictionary and output directories,
    and the newest time's points."""
    region = pipe / "constant" / "fluid"
    shutil.move(str(pipe / "constant" / "polyMesh"), str(region / "polyMesh"))
    write_dict(pipe / "system" / "fluid" / "morphDict", SQUEEZE)
    other = tmp_path / "cli"
    shutil.copytree(pipe, other)
    run("morphMesh", "-region", "fluid", cwd=other)

    case = meshmorph.Case(pipe, region="fluid")
    assert case.region == "fluid" and case.n_cells == 2240
    case.morph()
    path = case.write()
    assert path == pipe / "1" / "fluid" / "polyMesh" / "points"
    assert path.read_bytes() == (other / "1/fluid/polyMesh/points").read_bytes()

    newest = meshmorph.Case(pipe, region="fluid", latest_time=True)
    assert newest.time == "1" and np.array_equal(newest.initial_points, case.points)
    first = meshmorph.Case(pipe, region="fluid", time="constant")
    assert np.array_equal(first.initial_points, case.initial_points)
    with pytest.raises(ValueError, match="not both"):
        meshmorph.Case(pipe, region="fluid", time="1", latest_time=True)
