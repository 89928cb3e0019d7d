# SPDX-License-Identifier: GPL-3.0-or-later
"""meshmorph.DesignStudy against morphMesh -variables/-variant/-sensitivity, and the
transpose product against finite differences."""
import json
import shutil

import numpy as np
import pytest

import meshmorph
from conftest import run, run_json, write_dict

A = np.array([0.8, 0.3, 1, 0.05, -0.05, 0.05, -0.05, 0.02, 0.02, 0.02, 0.02])


def test_setup_and_variant_equal_the_command_line(design_pipe, tmp_path):
    cli_case = tmp_path / "cli"
    shutil.copytree(design_pipe, cli_case)
    cli_setup = run_json("morphMesh", "-variables", cwd=cli_case)
    cli_variant = run_json("morphMesh", "-variant", "(" + " ".join(map(repr, A)) + ")",
                           cwd=cli_case)

    setup = meshmorph.setup_design(design_pipe)
    assert [v["name"] for v in setup["variables"]] == [v["name"] for v in cli_setup["variables"]]
    assert setup["method"] == cli_setup["method"]
    study = meshmorph.DesignStudy(design_pipe)
    assert study.names == [v["name"] for v in setup["variables"]]
    assert study.bounds[0] == (-2.0, 2.0) and study.bounds[2] is None

    report = study.evaluate(A)
    assert report["valid"] and not report["written"]
    for key in ("maxConstraintError", "maxDisplacement", "maxPrescribedDisplacement"):
        assert report[key] == cli_variant[key], key
    assert report["after"]["maxNonOrthogonality"] == cli_variant["after"]["maxNonOrthogonality"]
    path = study.write()
    assert path.name == "points" and path.parent.parent.name == "1"
    assert path.read_bytes() == (cli_case / "1/polyMesh/points").read_bytes()
    # The points in memory are those the command line wrote (17 digits: doubles round-trip).
    assert np.array_equal(study.points(A), meshmorph.Case(cli_case, time="1").initial_points)
    assert np.array_equal(meshmorph.Case(design_pipe, time="1").initial_points,
                          meshmorph.Case(cli_case, time="1").initial_points)


def without_timings(report):
    return {k: v for k, v in report.items() if k != "timings"}


def test_a_later_variant_reports_as_in_a_fresh_study(design_pipe):
    # A study checks its later variants with the topology part and the scaled Jacobian's
    # corners of its first check (a variant moves points only): the report must be the one
    # a fresh study gives.
    meshmorph.setup_design(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    study.evaluate(0.5 * A)
    later = study.evaluate(A)
    fresh = meshmorph.DesignStudy(design_pipe).evaluate(A)
    assert later["after"]["cellTypes"] == fresh["after"]["cellTypes"]
    assert later["after"]["minScaledJacobian"] == fresh["after"]["minScaledJacobian"]
    assert without_timings(later) == without_timings(fresh)


def test_write_into_the_mesh_s_instance_keeps_the_original(design_pipe):
    meshmorph.setup_design(design_pipe)
    original = (design_pipe / "constant/polyMesh/points").read_bytes()
    study = meshmorph.DesignStudy(design_pipe)
    study.evaluate(A)
    path = study.write(overwrite=True)
    assert path == design_pipe / "constant/polyMesh/points"
    assert (design_pipe / "constant/polyMesh/points.orig").read_bytes() == original
    # The variant is the morphed mesh now: opening it is asked for by name.
    assert np.array_equal(meshmorph.Case(design_pipe, time="constant").initial_points,
                          study.points(A))
    path = study.write(time="7")
    assert path == design_pipe / "7/polyMesh/points"


def test_transpose_product_equals_sensitivity_and_finite_differences(design_pipe):
    meshmorph.setup_design(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    x0 = study.initial_points
    rng = np.random.default_rng(7)
    g = rng.normal(size=x0.shape)
    dJda = study.transpose_product(g)
    assert np.array_equal(dJda, study.transpose_product(g.reshape(-1)))  # flat dXv too

    # J(a) = sum g . x(a) is linear in a: central differences are exact up to round-off.
    h = 0.1
    for j in range(len(A)):
        e = np.zeros(len(A))
        e[j] = h
        fd = (np.sum(g * study.points(A + e)) - np.sum(g * study.points(A - e))) / (2 * h)
        assert fd == pytest.approx(dJda[j], rel=1e-9, abs=1e-9 * np.abs(dJda).max())

    # A nonlinear J (the squared distance of the wall from a target): the chain rule
    # dJ/da = F^T dJ/dx against central differences.
    target = x0 * 1.01
    wall = meshmorph.Case(design_pipe).patch_points("wall")

    def J(a):
        x = study.points(a)
        return 0.5 * np.sum((x[wall] - target[wall]) ** 2)

    x = study.points(A)
    dJdx = np.zeros_like(x)
    dJdx[wall] = x[wall] - target[wall]
    grad = study.transpose_product(dJdx)
    h = 1e-4
    for j in range(len(A)):
        e = np.zeros(len(A))
        e[j] = h
        fd = (J(A + e) - J(A - e)) / (2 * h)
        assert fd == pytest.approx(grad[j], rel=1e-6, abs=1e-8 * np.abs(grad).max())


def test_transpose_product_equals_morphmesh_sensitivity(design_pipe):
    run("morphMesh", "-variables", cwd=design_pipe)
    (design_pipe / "dJdx").write_text(
        "FoamFile { version 2.0; format ascii; class pointVectorField; object dJdx; }\n"
        "dimensions [0 0 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
        "    wall { type fixedValue; value uniform (1 1 0); }\n"
        "    \"(inlet|outlet)\" { type fixedValue; value uniform (0 0 0); }\n}\n")
    cli = run_json("morphMesh", "-sensitivity", "dJdx", cwd=design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    case = meshmorph.Case(design_pipe)
    g = np.zeros((case.n_points, 3))
    g[case.patch_points("wall")] = [1.0, 1.0, 0.0]
    dJda = study.transpose_product(g)
    # The same sums in the same order: equal, not close (the JSON's doubles round-trip).
    assert [cli["dJda"][name] for name in study.names] == list(dJda)


def test_is_valid_agrees_with_the_full_check(design_pipe):
    meshmorph.setup_design(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    assert study.is_valid(A) and study.evaluate(A)["valid"]
    # The lattice bumps have no bounds: five times one control point's unit move folds the
    # wall's cells.
    wild = np.zeros(len(A))
    wild[3] = 5.0
    assert not study.is_valid(wild)
    report = study.evaluate(wild, back_off=True)
    assert not report["valid"] and report["backOff"].startswith("bump.1.1.1.x ")
    with pytest.raises(meshmorph.InputError, match="refused"):
        study.write()


def test_design_errors(design_pipe):
    # No set-up yet: the advice is Python's step, not the command line's alone.
    with pytest.raises(meshmorph.IoError, match=r"meshmorph\.setup_design\(case\)"):
        meshmorph.DesignStudy(design_pipe)
    meshmorph.setup_design(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    with pytest.raises(meshmorph.InputError, match="11 design variables"):
        study.points([1.0, 2.0])
    with pytest.raises(meshmorph.InputError, match="not finite"):
        study.points(A * np.nan)
    with pytest.raises(meshmorph.InputError, match="outside its bounds"):
        study.points(A * 100)
    with pytest.raises(ValueError, match="dJ/dx"):
        study.transpose_product(np.zeros((3, 3)))
    with pytest.raises(meshmorph.InputError, match="evaluate"):
        study.write()
    # A changed dictionary makes the set-up stale: the CLI's message.
    dict_path = design_pipe / "system" / "morphDict"
    dict_path.write_text(dict_path.read_text().replace("angle 2;", "angle 3;"))
    with pytest.raises(meshmorph.InputError, match=r"setup_design\(case\) \(morphMesh -variables\) again"):
        meshmorph.DesignStudy(design_pipe)


def test_idwarp_aliases(design_pipe):
    meshmorph.setup_design(design_pipe)
    mesh = meshmorph.USMesh({"gridFile": str(design_pipe)})
    xs = mesh.getSurfaceCoordinates()
    assert xs.shape == (len(meshmorph.Case(design_pipe).patch_points("wall")), 3)
    target = xs.copy()
    target[:, 0] += 0.002 * np.cos(np.pi * target[:, 2])
    mesh.setSurfaceCoordinates(target)
    report = mesh.warpMesh()
    assert not report["refused"] and report["maxConstraintError"] < 1e-12
    assert np.allclose(mesh.getSurfaceCoordinates(), target, rtol=0, atol=1e-14)
    grid = mesh.getSolverGrid()
    assert grid.shape == (3 * meshmorph.Case(design_pipe).n_points,)
    dXv = np.random.default_rng(1).normal(size=grid.shape)
    study = meshmorph.DesignStudy(design_pipe)
    assert np.array_equal(mesh.designDeriv(dXv), study.transpose_product(dXv.reshape(-1, 3)))
    with pytest.raises(meshmorph.InputError):
        mesh.setSurfaceCoordinates(target[:-1])


def test_warp_deriv_is_dJ_dXs_equal_to_central_differences(pipe):
    """USMesh.warpDeriv returns dJ/dXs as IDWarp's does: for J = dXv . x, the derivative with
    respect to the surface coordinates through warpMesh, equal to central differences of J
    along a perturbation of each surface point by up to ~15% of its warp. A bump on the wall
    with one largest displacement: the limit's radius (the largest prescription) then moves
    smoothly (at a tie it has a kink, and differences across it see one side). The warp is
    linear in the surface with the fit's choices held and the limit smooth here, so the two
    agree to round-off; rel 1e-8 leaves room for the solve's conditioning."""
    mesh = meshmorph.USMesh({"gridFile": str(pipe)})
    with pytest.raises(meshmorph.InputError, match="warpMesh first"):
        mesh.warpDeriv(np.zeros(3 * meshmorph.Case(pipe).n_points))
    xs = mesh.getSurfaceCoordinates()
    rng = np.random.default_rng(2)
    top = len(xs) // 3
    bump = np.exp(-np.sum((xs - xs[top]) ** 2, axis=1) / 0.2**2)
    target = xs + 0.002 * bump[:, None] * np.array([1.0, 0.3, 0.2])
    mesh.setSurfaceCoordinates(target)
    mesh.warpMesh()
    dXv = rng.normal(size=mesh.getSolverGrid().shape)
    dXs = mesh.warpDeriv(dXv)
    assert dXs.shape == xs.shape and np.array_equal(mesh.getdXs(), dXs)
    delta = 0.05 * (target - xs) * rng.normal(size=xs.shape)

    def objective(t):
        mesh.setSurfaceCoordinates(target + t * delta)
        mesh.warpMesh()
        return dXv @ mesh.getSolverGrid()

    central = (objective(1.0) - objective(-1.0)) / 2.0
    assert central == pytest.approx(np.sum(dXs * delta), rel=1e-8)


def test_the_sensitivity_of_a_morph_it_cannot_differentiate_says_why(pipe):
    """Case.sensitivity before a morph, and after one that took more than one step, is an
    InputError that says what to change."""
    case = meshmorph.Case(pipe)
    g = np.ones((case.n_points, 3))
    with pytest.raises(meshmorph.InputError, match="morph first"):
        case.sensitivity(g)
    write_dict(pipe / "system" / "morphDict", "steps 2; boundary { wall { type translate; "
               "vector (0.001 0 0); } }")
    case.morph()
    with pytest.raises(meshmorph.InputError, match="took 2 steps"):
        case.sensitivity(g)


def write_point_field(path, values):
    """values (n, 3) as an ASCII pointVectorField whose patches take the internal values."""
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = "\n".join(f"({a!r} {b!r} {c!r})" for a, b, c in values)
    path.write_text("FoamFile { version 2.0; format ascii; class pointVectorField; object "
                    f"{path.name}; }}\ndimensions [0 0 0 0 0 0 0];\n"
                    f"internalField nonuniform List<vector> {len(values)}\n(\n{rows}\n);\n"
                    'boundaryField { ".*" { type calculated; } }\n')


def read_internal_field(path):
    """The internalField of an ASCII pointVectorField written by meshmorph, as (n, 3)."""
    text = path.read_text()
    body = text[text.index("internalField"):text.index("boundaryField")]
    rows = body[body.index("(\n") + 2:body.rindex(")")].split("\n")
    return np.array([[float(v) for v in r.strip("()").split()] for r in rows if r.strip("()")])


def test_morph_mesh_sensitivity_writes_what_case_sensitivity_gives(pipe):
    """morphMesh -sensitivity on a case without designVariables: the morphDict's morph,
    dJ/dx read from a pointVectorField, dJ/dXs written beside it as the pointVectorField
    dJdXs (nonzero at the morph's constrained points only): the values Case.sensitivity
    gives for the same morph (17 digits: the same doubles)."""
    write_dict(pipe / "system" / "morphDict",
               "boundary { wall { type scale; factor (1.02 1.03 1); origin (0 0 1); } }")
    case = meshmorph.Case(pipe)
    g = np.random.default_rng(3).normal(size=(case.n_points, 3))
    write_point_field(pipe / "0" / "dJdx", g)
    report = run_json("morphMesh", "-sensitivity", "0/dJdx", cwd=pipe)
    assert report["exitStatus"] == 0 and report["output"] == str(pipe / "0" / "dJdXs")
    written = read_internal_field(pipe / "0" / "dJdXs")
    case.morph()
    expected = case.sensitivity(g)
    assert np.array_equal(written, expected)
    constrained = np.count_nonzero(np.linalg.norm(expected, axis=1))
    assert constrained == report["constrainedPoints"] > 0
    assert not (pipe / "1").exists(), "a sensitivity run writes no mesh"


def test_morph_mesh_sensitivity_reads_a_bad_dJdx_before_it_morphs(pipe):
    """A dJ/dx file with too few values is an input error naming the file, given before the
    morph runs (no fit in the log) and with nothing written."""
    write_dict(pipe / "system" / "morphDict",
               "boundary { wall { type scale; factor (1.02 1.03 1); origin (0 0 1); } }")
    write_point_field(pipe / "0" / "dJdx", np.ones((7, 3)))
    done = run("morphMesh", "-sensitivity", "0/dJdx", cwd=pipe, expect=2)
    assert "0/dJdx" in done.stderr and "7" in done.stderr, done.stderr
    assert "Constraints:" not in done.stdout and "centres" not in done.stdout, done.stdout
    assert not (pipe / "0" / "dJdXs").exists() and not (pipe / "1").exists()


@pytest.fixture
def bump_search(design_pipe):
    """A study of the set-up pipe, a start design and a direction along which cells invert:
    the lattice's control points pushed in alternate directions (unbounded variables)."""
    meshmorph.setup_design(design_pipe)
    direction = np.zeros_like(A)
    direction[3:7] = [1.0, -1.0, 1.0, -1.0]
    return meshmorph.DesignStudy(design_pipe), 0.2 * A, direction


def test_max_valid_step_is_confirmed_by_the_check_and_stops_at_the_first_inversion(bump_search):
    study, start, direction = bump_search
    r = study.max_valid_step(start, direction)
    assert r["limitedBy"] == "inversion" and not r["written"], r
    t, above = r["step"], r["invalidAbove"]
    assert 0 < t < above and (above - t) / above <= 1.0001e-4, r
    assert study.is_valid(start + t * direction)
    assert not study.is_valid(start + above * direction)
    # The cubics' estimate is where the check found the inversion, within 2%.
    assert abs(r["estimate"] / t - 1) < 0.02, r
    # A limit below the inversion is the answer, checked once more.
    limited = study.max_valid_step(start, direction, limit=0.5 * t)
    assert limited["limitedBy"] == "limit" and limited["step"] == 0.5 * t, limited


def test_max_valid_step_keeps_a_non_orthogonality_limit(bump_search):
    study, start, direction = bump_search
    valid = study.max_valid_step(start, direction)
    assert valid["maxNonOrthogonality"] is None, valid
    non_ortho = lambda t: study.evaluate(start + t * direction)["after"]["maxNonOrthogonality"]
    # (At the valid step a cell is about to invert: its faces are near 180 degrees.)
    theta = 0.5 * (non_ortho(0) + min(non_ortho(valid["step"]), 90.0))
    r = study.max_valid_step(start, direction, max_non_orthogonality=theta)
    assert r["limitedBy"] == "nonOrthogonality", r
    assert 0 < r["step"] < r["invalidAbove"] < valid["step"], r
    assert (r["invalidAbove"] - r["step"]) / r["invalidAbove"] <= 1.0001e-4, r
    assert r["maxNonOrthogonality"] == non_ortho(r["step"]) <= theta < non_ortho(r["invalidAbove"])
    with pytest.raises(meshmorph.InputError, match="already above the limit"):
        study.max_valid_step(start, direction, max_non_orthogonality=0.5 * non_ortho(0))


def test_max_valid_step_stops_at_a_bound_and_refuses_a_bad_search(design_pipe):
    meshmorph.setup_design(design_pipe)
    study = meshmorph.DesignStudy(design_pipe)
    lift = np.zeros_like(A)
    lift[0] = 1.0
    r = study.max_valid_step(np.zeros_like(A), lift)  # lift is bounded by (-2, 2)
    assert r["limitedBy"] == "bounds" and r["boundVariable"] == "lift", r
    assert r["step"] == 2.0 and r["invalidAbove"] == float("inf"), r
    twist = np.zeros_like(A)
    twist[2] = 1.0
    with pytest.raises(meshmorph.InputError, match="direction is zero"):
        study.max_valid_step(A, np.zeros_like(A))
    with pytest.raises(meshmorph.InputError, match="components"):
        study.max_valid_step(A, twist[:3])
    with pytest.raises(meshmorph.InputError, match="limit must be positive"):
        study.max_valid_step(A, twist, limit=0)


def test_a_variant_that_folds_a_few_cells_is_untangled_exactly_unless_the_dict_says_no(
        design_pipe, bump_search):
    study, start, direction = bump_search
    # Just past the first inversion along the direction: the linear combination folds cells.
    step = study.max_valid_step(start, direction)
    folded = start + 1.02 * step["invalidAbove"] * direction
    assert not study.is_valid(folded)
    report = study.evaluate(folded)
    repair = report["untangle"]
    assert repair["invalidBefore"] > 0 and repair["invalidAfter"] == 0, repair
    assert 0 < repair["pointsMoved"] and repair["maxMove"] > 0, repair
    assert report["valid"] and report["after"]["negativeVolumeCells"] == 0, report
    assert report["after"]["incorrectlyOrientedFacePyramids"] == 0, report
    assert report["relativeConstraintError"] < 1e-9, report  # prescribed points stay exact
    written = meshmorph.Case(design_pipe, time=study.write().parent.parent.name).initial_points
    linear = study.points(folded)
    moved = np.linalg.norm(written - linear, axis=1)
    assert np.count_nonzero(moved) == repair["pointsMoved"], repair
    assert moved.max() == pytest.approx(repair["maxMove"], rel=1e-12)
    # A valid variant needs no repair and reports none.
    assert "untangle" not in study.evaluate(start)

    dict_path = design_pipe / "system" / "morphDict"
    dict_path.write_text(dict_path.read_text() + "\nuntangle no;\n")
    strict = meshmorph.DesignStudy(design_pipe).evaluate(folded)
    assert not strict["valid"] and "untangle" not in strict, strict


def test_a_variant_failing_a_check_the_mesh_passed_is_warned_about(pipe, caplog):
    # The wall squeezed to 0.5% of its radius: every cell valid, the aspect ratio 200 times
    # the pipe's 8.2, past checkMesh's limit of 1000.
    (pipe / "system" / "morphDict").write_text(
        "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
        "boundary { default { type fixed; } \"(inlet|outlet)\" { type slip; } }\n"
        "designVariables { squeeze { patches (wall); type scale; origin (0 0 1);"
        " factor (0.9 0.9 1); } }\n")
    meshmorph.setup_design(pipe)
    study = meshmorph.DesignStudy(pipe)
    assert study.evaluate([0.5])["newFailedChecks"] == []
    caplog.clear()
    report = study.evaluate([9.95])
    assert report["valid"] and study.is_valid([9.95]), report
    assert [f["check"] for f in report["newFailedChecks"]] == ["aspectRatio"], report
    warnings = [r.getMessage() for r in caplog.records if r.levelname == "WARNING"]
    assert any(w.startswith("the variant fails the check aspectRatio") for w in warnings), warnings


SHARED_DICT = """
method rbf;
rbf { greedy { tolerance 1e-3; } }
designBasis shared;
boundary { default { type fixed; } "(inlet|outlet)" { type slip; } }
designVariables
{
    squeeze { patches (wall); type scale; origin (0 0 1); factor (0.9 0.9 1); }
    bump { type ffd; patches (wall); lattice (4 4 4); box ((-0.6 -0.6 0.4) (0.6 0.6 1.6));
           directions (x y); confine (1 1 1); }
}
"""


def test_a_shared_set_up_is_linear_and_its_gradient_equals_finite_differences(pipe):
    # One held fit for the 17 variables: points(a) is linear in a to round-off (the fit's
    # solve, the correction's single-precision far terms), and transpose_product is its
    # transpose.
    write_dict(pipe / "system" / "morphDict", SHARED_DICT)
    report = meshmorph.setup_design(pipe)
    assert report["storage"] == "shared"
    assert report["storageReason"] == "designBasis shared"
    study = meshmorph.DesignStudy(pipe)
    n = len(study.names)
    assert n == 17
    x0 = study.initial_points
    a = 0.05 * np.sin(np.arange(1, n + 1))
    b = 0.03 * np.cos(np.arange(1, n + 1))
    moved = study.points(a + b) - x0
    assert np.abs(moved).max() > 1e-3
    linear_error = np.abs(study.points(a) - x0 + study.points(b) - x0 - moved).max()
    assert linear_error < 1e-8 * np.abs(moved).max()

    g = np.random.default_rng(3).normal(size=x0.shape)
    dJda = study.transpose_product(g)
    h = 0.1
    for j in (0, 1, 9, 16):
        e = np.zeros(n)
        e[j] = h
        fd = (np.sum(g * study.points(a + e)) - np.sum(g * study.points(a - e))) / (2 * h)
        assert fd == pytest.approx(dJda[j], rel=1e-6, abs=1e-6 * np.abs(dJda).max())
    r = study.evaluate(a)
    assert r["valid"] and r["relativeConstraintError"] < 1e-10

