#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The morph sweep's step for one mesh: a motion a user would ask for, morphMesh, then
OpenFOAM's checkMesh on the result, and a verdict.

Usage: morph_one_mesh.py CASE OUT_DIR --morph-mesh PATH [--region NAME] [--latest-time]
                         [--timeout S]

The motion: the smallest wall patch (by faces; the smallest `patch` if the mesh has no
wall) scaled by 1% about the centre of its points, every other patch fixed (morphMesh's
default); in a 2D case (empty patches) within the planes (factor 1 along their normal), in
an axisymmetric case (two wedge patches) about the point of the axis nearest that centre.
The dictionary is written to OUT_DIR/morphDict and passed with -dict, so the case's own
system/ is not touched; the result goes to the case's next time.

Verdicts (OUT_DIR/result.json, one line on stdout):
  valid     morphMesh exit 0 and checkMesh fails no check the mesh passed before
  warned    morphMesh exit 0, checkMesh fails a new check, and morphMesh said so (a
            Warning naming it, the JSON's newFailedChecks)
  silent    morphMesh exit 0, checkMesh fails a new check (or cannot read the result), and
            morphMesh did not say so: the defect this sweep is for
  refused   morphMesh exit 2, 3 or 4 with an error message (the reason is recorded)
  crashed   morphMesh exit 5, a signal, or a time-out
  skipped   no patch to move (the reason is recorded)
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

import meshmorph


def check_mesh_failures(log):
    """The categories of checkMesh's failures ('***' lines): their text before ':' or a
    number, so that counts and values do not make two runs differ."""
    failures = set()
    for line in log.splitlines():
        s = line.strip()
        if s.startswith("***"):
            s = s.lstrip("*").strip()
            s = re.split(r"[:=]|\s[-+]?\d", s)[0].strip()
            failures.add(s)
    return failures


def run(args, timeout, log_path):
    start = time.monotonic()
    try:
        p = subprocess.run(args, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                           timeout=timeout)
        out, err, rc = p.stdout, p.stderr, p.returncode
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        err = "timeout"
        rc = "timeout"
    with open(log_path, "w") as f:
        f.write(out + "\n--- stderr ---\n" + err)
    return rc, out, err, time.monotonic() - start


def choose_patch(case):
    """(name, faces) of the smallest wall patch, else of the smallest `patch`, else None."""
    patches = case.patches
    for kind in ("wall", "patch"):
        candidates = [(p["nFaces"], name) for name, p in patches.items()
                      if p["type"] == kind and p["nFaces"] > 0]
        if candidates:
            faces, name = min(candidates)
            return name, faces
    return None


def patch_coordinates(case, name):
    return case.initial_points[case.patch_points(name)]


def empty_normal_axis(check_mesh_log):
    """The coordinate axis a 2D case's empty planes are normal to, as checkMesh finds it
    ("Mesh has 2 solution (non-empty) directions (1 0 1)": y), or None (3D, or 1D)."""
    m = re.search(r"Mesh has 2 solution \(non-empty\) directions \((-?\d+) (-?\d+) (-?\d+)\)",
                  check_mesh_log)
    if not m:
        return None
    empty = [k for k in range(3) if int(m.group(k + 1)) != 1]
    return empty[0] if len(empty) == 1 else None


def plane_of(points):
    """(centroid, unit normal) of the best-fit plane of points."""
    centroid = points.mean(axis=0)
    return centroid, np.linalg.svd(points - centroid, full_matrices=False)[2][-1]


def wedge_axis_point(case, centre):
    """In an axisymmetric case (two wedge patches) the point of the common axis nearest to
    `centre`: a scale about it keeps every point in its wedge plane, as a user scaling a
    wedge case's wall would choose; None otherwise."""
    wedges = [name for name, p in case.patches.items() if p["type"] == "wedge" and p["nFaces"] > 0]
    if len(wedges) != 2:
        return None
    (c1, n1), (c2, n2) = (plane_of(patch_coordinates(case, w)) for w in wedges)
    direction = np.cross(n1, n2)
    direction /= np.linalg.norm(direction)
    on_axis = np.linalg.solve(np.array([n1, n2, direction]),
                              np.array([n1 @ c1, n2 @ c2, direction @ centre]))
    return on_axis


def morph_dict(patch, centre, axis, keys=""):
    factor = [1.01, 1.01, 1.01]
    if axis is not None:
        factor[axis] = 1.0
    vec = lambda v: "(" + " ".join(repr(float(x)) for x in v) + ")"  # noqa: E731
    return ("FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
            + (keys + "\n" if keys else "") +
            "boundary\n{\n"
            f"    \"{patch}\" {{ type scale; origin {vec(centre)}; factor {vec(factor)}; }}\n"
            "}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("--morph-mesh", required=True)
    ap.add_argument("--region", default="")
    ap.add_argument("--latest-time", action="store_true")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--keys", default="", help="more top-level morphDict entries")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    result = {"case": a.case, "region": a.region}

    def finish(verdict, **more):
        result.update(verdict=verdict, **more)
        with open(os.path.join(a.out, "result.json"), "w") as f:
            json.dump(result, f, indent=2)
        print(f"{verdict}: {more.get('reason', '')}".rstrip(": "))
        return 0

    try:
        case = meshmorph.Case(a.case, region=a.region, latest_time=a.latest_time)
    except meshmorph.Error as e:
        return finish("skipped", reason=f"the mesh cannot be read: {e}")
    chosen = choose_patch(case)
    if chosen is None:
        return finish("skipped", reason="no wall or patch-type patch to move")
    patch, faces = chosen
    centre = patch_coordinates(case, patch).mean(axis=0)
    on_axis = wedge_axis_point(case, centre)
    if on_axis is not None:
        centre = on_axis
    instance = case.time
    region = ["-region", a.region] if a.region else []
    check = ["checkMesh", "-case", a.case] + region
    before_rc, before_log, _, _ = run(check + ["-time", instance], a.timeout,
                                      os.path.join(a.out, "checkMesh.before.log"))
    axis = empty_normal_axis(before_log)
    result.update(patch=patch, patch_faces=faces, points=case.n_points, cells=case.n_cells,
                  instance=instance, two_d=axis is not None)
    dict_path = os.path.abspath(os.path.join(a.out, "morphDict"))
    with open(dict_path, "w") as f:
        f.write(morph_dict(patch, centre, axis, a.keys))
    json_path = os.path.join(a.out, "morph.json")
    morph = [a.morph_mesh, "-case", a.case, "-dict", dict_path, "-json", json_path] + region
    if a.latest_time:
        morph.append("-latestTime")
    rc, out, err, seconds = run(morph, a.timeout, os.path.join(a.out, "morphMesh.log"))
    result.update(morph_exit=rc, morph_seconds=round(seconds, 2))
    if rc == "timeout" or rc == 5 or (isinstance(rc, int) and rc < 0):
        return finish("crashed", reason=f"morphMesh exit {rc}: {err.strip()[-300:]}")
    if rc in (2, 3, 4):
        errors = [line for line in err.splitlines() if line.startswith("Error")]
        return finish("refused", reason=(errors[0] if errors else err.strip())[:400])
    if rc != 0:
        return finish("crashed", reason=f"morphMesh exit {rc}")
    report = json.load(open(json_path))
    after_rc, after_log, _, _ = run(check + ["-time", report["outputInstance"]], a.timeout,
                                    os.path.join(a.out, "checkMesh.after.log"))
    new = sorted(check_mesh_failures(after_log) - check_mesh_failures(before_log))
    if after_rc != 0 and "End" not in after_log:
        new.append(f"checkMesh could not check the result (exit {after_rc})")
    result.update(new_checkmesh_failures=new, said=report.get("newFailedChecks", []))
    if not new:
        return finish("valid")
    warned = bool(report.get("newFailedChecks")) and "Warning" in err
    return finish("warned" if warned else "silent", reason="; ".join(new))


if __name__ == "__main__":
    sys.exit(main())
