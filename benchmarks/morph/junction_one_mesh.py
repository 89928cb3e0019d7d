#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""morphMesh against OpenFOAM's moveMesh on one tutorial mesh, at the same boundary motion:
the morph sweep's motion (the smallest wall patch scaled by 1% about its centre, every other
patch fixed, in 2D within the planes), where the moving patch meets fixed ones.

Usage: junction_one_mesh.py CASE OUT_DIR --morph-mesh PATH [--region NAME] [--time T]
                            [--timeout S] [--variant NAME=KEYS]... [--keep]

In OUT_DIR, from CASE's mesh at time T (default: the instance the case starts from):
  morph.<variant>/  morphMesh with the sweep's morphDict plus KEYS (default variant
                    'default': no keys; e.g. --variant "smoothed=jumpSmoothing yes;")
  moveMesh/         moveMesh (displacementLaplacian, inverseDistance diffusivity from the
                    moving patch, Gauss linear uncorrected, GAMG to 1e-8 with 25 iterations
                    at least), with the boundary motion morphMesh prescribes: every boundary
                    point's displacement as a fixedValue (constraint patches keep their own
                    type), taken from an IDW morph of the same dictionary in one step without
                    repair (the boundary points of any morph are its prescription)
and OpenFOAM's checkMesh -allGeometry on each result. OUT_DIR/result.json: per tool the exit
status, wall time and checkMesh figures (max non-orthogonality, faces above 70 degrees, max
skewness, min determinant, wrongly oriented face pyramids, negative-volume cells, failed
checks), and the largest difference between the tools' boundary points (the motions are
equal when it is round-off).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../scripts/openfoam"))
from morph_one_mesh import (choose_patch, empty_normal_axis, morph_dict,  # noqa: E402
                            patch_coordinates, wedge_axis_point)

import meshmorph  # noqa: E402

os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # Debian's OpenFOAM

CONSTRAINT_TYPES = {"empty", "wedge", "symmetry", "symmetryPlane", "cyclic", "cyclicAMI",
                    "cyclicACMI", "cyclicSlip", "processor", "processorCyclic", "nonConformalCyclic"}

HEADER = "FoamFile {{ version 2.0; format ascii; class {cls}; location \"{loc}\"; object {obj}; }}\n"

CONTROL_DICT = """application moveMesh;
startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;
writeControl timeStep; writeInterval 1; purgeWrite 0; writeFormat binary; writePrecision 17;
writeCompression off; timeFormat general; timePrecision 6; runTimeModifiable false;
"""

FV_SCHEMES = """ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear uncorrected; }
interpolationSchemes { default linear; }
snGradSchemes { default uncorrected; }
"""

FV_SOLUTION = """solvers
{
    cellDisplacement
    {
        solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0; minIter 25;
    }
}
"""


def run(args, timeout, log_path):
    """(exit status or 'timeout', wall seconds); stdout and stderr to log_path."""
    start = time.monotonic()
    with open(log_path, "w") as log:
        try:
            rc = subprocess.run(args, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
    return rc, round(time.monotonic() - start, 2)


def mesh_dir(case, region, instance):
    return os.path.join(case, instance, region, "polyMesh") if region else \
        os.path.join(case, instance, "polyMesh")


def make_case(src_mesh, dst):
    """A single-region case holding src_mesh as constant/polyMesh (no sets) and a one-step
    controlDict, fvSchemes and fvSolution for moveMesh."""
    shutil.rmtree(dst, ignore_errors=True)
    os.makedirs(os.path.join(dst, "system"))
    shutil.copytree(src_mesh, os.path.join(dst, "constant", "polyMesh"),
                    ignore=shutil.ignore_patterns("sets", "*.orig"))
    for name, body in (("controlDict", CONTROL_DICT), ("fvSchemes", FV_SCHEMES),
                       ("fvSolution", FV_SOLUTION)):
        with open(os.path.join(dst, "system", name), "w") as f:
            f.write(HEADER.format(cls="dictionary", loc="system", obj=name) + body)


def vector_list(values):
    rows = "\n".join(f"({x[0]!r} {x[1]!r} {x[2]!r})" for x in values)
    return f"nonuniform List<vector> {len(values)}\n(\n{rows}\n)"


def write_point_displacement(case, path, moving_patch, displaced):
    """0/pointDisplacement: every non-constraint patch fixedValue at the displacement the
    IDW morph gave its points (patch-local order); constraint patches their own type."""
    lines = ["dimensions [0 1 0 0 0 0 0];", "internalField uniform (0 0 0);", "boundaryField", "{"]
    for name, patch in case.patches.items():
        if patch["type"] in CONSTRAINT_TYPES:
            lines.append(f"    {name} {{ type {patch['type']}; }}")
            continue
        labels = case.patch_points(name)
        d = displaced[labels] - case.initial_points[labels]
        if not np.any(d):
            lines.append(f"    {name} {{ type fixedValue; value uniform (0 0 0); }}")
        else:
            lines.append(f"    {name}\n    {{\n        type fixedValue;\n        value {vector_list(d)};\n    }}")
    lines.append("}")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls="pointVectorField", loc="0", obj="pointDisplacement") + "\n".join(lines) + "\n")


def write_dynamic_mesh_dict(path, moving_patch):
    with open(path, "w") as f:
        f.write(HEADER.format(cls="dictionary", loc="constant", obj="dynamicMeshDict") +
                "dynamicFvMesh dynamicMotionSolverFvMesh;\n"
                "motionSolverLibs (\"libfvMotionSolvers.so\");\n"
                "motionSolver displacementLaplacian;\n"
                f"displacementLaplacianCoeffs {{ diffusivity inverseDistance ({moving_patch}); }}\n")


NUMBER = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan|inf)"


def check_mesh_figures(log):
    """checkMesh's figures from its log (-allGeometry); None for a figure not printed."""
    def find(pattern, default=None, kind=float):
        m = re.search(pattern, log)
        return kind(m.group(1)) if m else default
    return {
        "maxNonOrthogonality": find(r"Mesh non-orthogonality Max: " + NUMBER),
        "facesAbove70": find(r"Number of severely non-orthogonal \(> 70 degrees\) faces: (\d+)", 0, int),
        "maxSkewness": find(r"Max skewness = " + NUMBER),
        "minDeterminant": find(r"Cell determinant \([^)]*\) : minimum: " + NUMBER),
        "wrongPyramids": find(r"Error in face pyramids: (\d+) faces", 0, int),
        "negativeVolumeCells": find(r"Number of negative volume cells: (\d+)", 0, int),
        "failedChecks": find(r"Failed (\d+) mesh checks", 0, int),
        "read": "End" in log,
    }


def check(case_dir, out_dir, name, timeout):
    """checkMesh -allGeometry on the case's latest time."""
    log_path = os.path.join(out_dir, f"checkMesh.{name}.log")
    rc, _ = run(["checkMesh", "-case", case_dir, "-latestTime", "-allGeometry"], timeout, log_path)
    return check_mesh_figures(open(log_path, errors="replace").read())


def latest_points(case_dir):
    times = [d for d in os.listdir(case_dir) if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0"
             and os.path.exists(os.path.join(case_dir, d, "polyMesh", "points"))]
    if not times:
        return None
    latest = max(times, key=float)
    return meshmorph.Case(case_dir, time=latest).points.copy()


def boundary_mismatch(case, a, b):
    """The largest distance between two results' points on the non-constraint patches (the
    points both tools were given; a 2D case's empty planes hold every point), None when a
    result is missing."""
    if a is None or b is None:
        return None
    labels = np.unique(np.concatenate([case.patch_points(n) for n, p in case.patches.items()
                                       if p["type"] not in CONSTRAINT_TYPES] + [[]]).astype(int))
    if labels.size == 0:
        return 0.0
    return float(np.max(np.linalg.norm(a[labels] - b[labels], axis=1)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("--morph-mesh", required=True)
    ap.add_argument("--region", default="")
    ap.add_argument("--time", default=None)
    ap.add_argument("--timeout", type=float, default=900)
    ap.add_argument("--keep", action="store_true", help="keep the meshes (default: logs only)")
    ap.add_argument("--variant", action="append", default=[],
                    help="NAME=KEYS: a morphMesh run with these top-level morphDict entries")
    a = ap.parse_args()
    variants = [("default", "")] + [tuple(v.split("=", 1)) for v in a.variant]
    os.makedirs(a.out, exist_ok=True)
    out = os.path.abspath(a.out)
    result = {"case": a.case, "region": a.region}

    def finish(**more):
        result.update(more)
        with open(os.path.join(out, "result.json"), "w") as f:
            json.dump(result, f, indent=2)
        print(json.dumps({k: result.get(k) for k in ("patch", "skipped")}))
        return 0

    source = meshmorph.Case(a.case, region=a.region, time=a.time)
    base = os.path.join(out, "base")
    make_case(mesh_dir(a.case, a.region, source.instance), base)
    case = meshmorph.Case(base, time="constant")
    chosen = choose_patch(case)
    if chosen is None:
        return finish(skipped="no wall or patch-type patch to move")
    patch, faces = chosen
    centre = patch_coordinates(case, patch).mean(axis=0)
    on_axis = wedge_axis_point(case, centre)
    if on_axis is not None:
        centre = on_axis
    run(["checkMesh", "-case", base, "-allGeometry"], a.timeout, os.path.join(out, "checkMesh.before.log"))
    before_log = open(os.path.join(out, "checkMesh.before.log"), errors="replace").read()
    if "End" not in before_log:
        sys.exit(f"checkMesh cannot read {base} (see {out}/checkMesh.before.log)")
    axis = empty_normal_axis(before_log)
    result.update(patch=patch, patch_faces=faces, points=case.n_points, cells=case.n_cells,
                  two_d=axis is not None, before=check_mesh_figures(before_log), tools={})

    results_points = {}
    for name, keys in variants:
        dst = os.path.join(out, f"morph.{name}")
        shutil.rmtree(dst, ignore_errors=True)
        shutil.copytree(base, dst)
        dict_path = os.path.join(dst, "system", "morphDict")
        with open(dict_path, "w") as f:
            f.write(morph_dict(patch, centre, axis, keys))
        json_path = os.path.join(dst, "morph.json")
        rc, seconds = run([a.morph_mesh, "-case", dst, "-json", json_path], a.timeout,
                          os.path.join(out, f"morphMesh.{name}.log"))
        entry = {"exit": rc, "seconds": seconds, "keys": keys}
        if rc == 0:
            entry.update(check(dst, out, f"morph.{name}", a.timeout))
            results_points[name] = latest_points(dst)
        result["tools"][f"morphMesh {name}".strip()] = entry

    # The boundary motion every morph of this dictionary prescribes: an IDW morph in one step,
    # without repair (its boundary points are exact whatever its interior).
    motion_dict = os.path.join(out, "morphDict.motion")
    with open(motion_dict, "w") as f:
        f.write(morph_dict(patch, centre, axis, "method idw;\nsteps 1;\nuntangle no;"))
    motion = meshmorph.Case(base, time="constant", dict=motion_dict, force=True)
    motion.morph()
    displaced = motion.points.copy()

    dst = os.path.join(out, "moveMesh")
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(base, dst)
    write_point_displacement(case, os.path.join(dst, "0", "pointDisplacement"), patch, displaced)
    write_dynamic_mesh_dict(os.path.join(dst, "constant", "dynamicMeshDict"), patch)
    rc, seconds = run(["moveMesh", "-case", dst], a.timeout, os.path.join(out, "moveMesh.log"))
    entry = {"exit": rc, "seconds": seconds}
    moved = latest_points(dst) if rc == 0 else None
    if moved is not None:
        entry.update(check(dst, out, "moveMesh", a.timeout))
    result["tools"]["moveMesh"] = entry
    result["boundaryMismatch"] = {name: boundary_mismatch(case, p, moved) for name, p in results_points.items()}
    result["largestPrescribed"] = float(np.max(np.linalg.norm(displaced - case.initial_points, axis=1)))
    for path in () if a.keep else (base, *(os.path.join(out, f"morph.{n}") for n, _ in variants), dst):
        for sub in os.listdir(path):  # keep the logs and figures, not the meshes
            if sub not in ("system",):
                shutil.rmtree(os.path.join(path, sub), ignore_errors=True)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
