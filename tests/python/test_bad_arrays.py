# SPDX-License-Identifier: GPL-3.0-or-later
"""No call takes the interpreter down: every array argument of the module, given values of
every wrong kind, raises a Python exception and leaves the object usable."""
import numpy as np
import pytest

import meshmorph

BAD_VALUES = {
    "None": None,
    "string": "nonsense",
    "dict": {"a": 1},
    "0-d": np.float64(1.0),
    "empty": np.zeros((0,)),
    "empty rows": np.zeros((0, 3)),
    "bool": np.ones((4, 3), dtype=bool),
    "complex": np.ones((4, 3), dtype=complex),
    "objects": np.array([[object()] * 3] * 4),
    "3-d": np.zeros((2, 2, 3)),
    "nan": np.full((4, 3), np.nan),
    "inf": np.full((4, 3), np.inf),
    "ragged": [[1, 2, 3], [1, 2]],
    "transposed": np.zeros((3, 4)).T[:, :3].T,
    "huge labels": np.array([2**40], dtype=np.int64),
    "uint64 max": np.array([np.iinfo(np.uint64).max], dtype=np.uint64),
}


def calls(case, study, surface):
    return {
        "set_points": lambda v: case.set_points(v),
        "patch values": lambda v: case.morph(patches={"wall": v}),
        "point-set labels": lambda v: case.morph(points={"s": (v, np.zeros((1, 3)))}),
        "point-set values": lambda v: case.morph(points={"s": ([0], v)}),
        "patch table": lambda v: case.morph(patches=v),
        "point-set table": lambda v: case.morph(points=v),
        "study.points": lambda v: study.points(v),
        "study.evaluate": lambda v: study.evaluate(v),
        "study.is_valid": lambda v: study.is_valid(v),
        "transpose_product": lambda v: study.transpose_product(v),
        "setSurfaceCoordinates": lambda v: surface.setSurfaceCoordinates(v),
        "warpDeriv": lambda v: surface.warpDeriv(v),
        "patch_points": lambda v: case.patch_points(v),
    }


def test_every_wrong_value_raises(design_pipe):
    meshmorph.setup_design(design_pipe)
    case = meshmorph.Case(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    surface = meshmorph.USMesh({"gridFile": str(design_pipe)})
    for call_name, call in calls(case, study, surface).items():
        for value_name, value in BAD_VALUES.items():
            if value is None and call_name.endswith("table"):
                continue  # patches=None, points=None: the morphDict's morph, not an error
            try:
                call(value)
            except (meshmorph.Error, ValueError, TypeError, OverflowError):
                continue
            pytest.fail(f"{call_name}({value_name}) did not raise")
    # Still usable, and unchanged.
    assert np.array_equal(case.points, case.initial_points)
    assert case.is_valid()
    assert study.evaluate(np.zeros(len(study.names)))["valid"]


def test_usmesh_refuses_wrong_kinds_of_the_right_size(pipe):
    """USMesh's arrays of the surface's own size but of the wrong kind are refused, not
    converted: numpy's float conversion would make True 1.0 and drop imaginary parts."""
    surface = meshmorph.USMesh({"gridFile": str(pipe)})
    xs = surface.getSurfaceCoordinates()
    n = meshmorph.Case(pipe).n_points
    for value in (xs > 0, xs + 1j, xs.astype(str), np.where(xs > 0, np.nan, xs)):
        with pytest.raises((TypeError, meshmorph.InputError)):
            surface.setSurfaceCoordinates(value)
    with pytest.raises(meshmorph.InputError, match="setSurfaceCoordinates first"):
        surface.warpMesh()  # nothing was set
    surface.setSurfaceCoordinates(xs.tolist())  # a list of numbers is fine
    surface.warpMesh()
    for value in (np.ones((n, 3), dtype=bool), np.ones((n, 3), dtype=complex)):
        with pytest.raises(TypeError):
            surface.warpDeriv(value)
