#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Wall motions of a straight pipe for benchmarks/morph/pipe_amplitudes.sh.

The pipe's axis is z; s = (z - zmin) / (zmax - zmin) in [0, 1] over the mesh's bounding box,
bump(s) = sin(pi s)^2 (zero at the inlet and outlet), R = the largest distance of a wall
point from the axis (x = y = 0). Motions of the wall points, amplitude A (a fraction of R):

  squeeze  radially inward by A R bump(s)       (a venturi of depth A)
  shift    along +x by A R bump(s)               (a sideways bend)

Usage:
  pipe_motion.py displacement CASE --motion M --amplitude A [--time 0] [--patch wall]
      writes CASE/<time>/pointDisplacement: the patch's boundaryField
      `type fixedValue; value nonuniform List<vector> N (...)` in the order of the
      patch's meshPoints (the order in which the points first appear walking the patch's
      faces from startFace, as OpenFOAM's PrimitivePatch::calcMeshData numbers them);
      every other patch `fixedValue; value uniform (0 0 0)`.
  pipe_motion.py verify CASE --time T --motion M --amplitude A [--patch wall]
      compares CASE/<T>/polyMesh/points with constant/polyMesh/points + d on the patch's
      points; prints the largest error with the meshPoints order and, for contrast, the
      error had the values been given in increasing point-label order; exit 1 when the
      meshPoints error exceeds --tolerance (default 1e-9 relative to the pipe length).
  pipe_motion.py info CASE
      prints `cells N points N faces N` and the patches (name type nFaces nPoints).

Reads ascii OpenFOAM meshes only (constant/polyMesh/{points,faces,owner,neighbour,boundary}).
"""
import argparse
import math
import os
import re
import sys

import numpy as np

_COMMENTS = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def _body(path):
    """Text of an OpenFOAM file after its FoamFile header, comments removed."""
    if not os.path.exists(path):
        if os.path.exists(path + ".gz"):
            sys.exit(f"pipe_motion.py: {path}.gz: compressed meshes are not supported")
        sys.exit(f"pipe_motion.py: {path}: no such file")
    with open(path, "rb") as f:
        raw = f.read()
    text = raw.decode("latin-1")
    text = _COMMENTS.sub(" ", text)
    m = re.search(r"FoamFile\s*\{(.*?)\}", text, re.S)
    if m:
        if re.search(r"format\s+binary\s*;", m.group(1)):
            sys.exit(f"pipe_motion.py: {path}: binary format is not supported (use ascii)")
        text = text[m.end():]
    return text


def _list_start(text, path):
    """Index just after the '(' that opens the top-level list 'N ('."""
    m = re.search(r"(\d+)\s*\(", text)
    if not m:
        sys.exit(f"pipe_motion.py: {path}: no list found")
    return int(m.group(1)), m.end()


def read_points(path):
    text = _body(path)
    n, start = _list_start(text, path)
    nums = re.findall(r"\(\s*([^\s()]+)\s+([^\s()]+)\s+([^\s()]+)\s*\)", text[start:])
    pts = np.array(nums[:n], dtype=float)
    if pts.shape != (n, 3):
        sys.exit(f"pipe_motion.py: {path}: expected {n} points, read {len(nums)}")
    return pts


def read_faces(path):
    text = _body(path)
    m = re.search(r"class\s+(\w+)", open(path, encoding="latin-1").read(2000))
    if m and m.group(1) != "faceList":
        sys.exit(f"pipe_motion.py: {path}: class {m.group(1)} is not supported (faceList only)")
    n, start = _list_start(text, path)
    faces = [[int(v) for v in body.split()]
             for _, body in re.findall(r"(\d+)\s*\(([^()]*)\)", text[start:])]
    if len(faces) != n:
        sys.exit(f"pipe_motion.py: {path}: expected {n} faces, read {len(faces)}")
    return faces


def read_labels(path):
    text = _body(path)
    n, start = _list_start(text, path)
    vals = np.array(text[start:].split(")")[0].split(), dtype=np.int64)
    if vals.size != n:
        sys.exit(f"pipe_motion.py: {path}: expected {n} labels, read {vals.size}")
    return vals


def read_boundary(path):
    text = _body(path)
    _, start = _list_start(text, path)
    patches = []
    for name, body in re.findall(r"([\w.:\-\"]+)\s*\{([^{}]*)\}", text[start:]):
        entry = dict(re.findall(r"(\w+)\s+([^;]*);", body))
        patches.append({"name": name.strip('"'), "type": entry.get("type", "?"),
                        "nFaces": int(entry["nFaces"]), "startFace": int(entry["startFace"])})
    return patches


def mesh_points(faces, patch):
    """The patch's meshPoints: labels in order of first appearance walking its faces."""
    seen = {}
    for face in faces[patch["startFace"]:patch["startFace"] + patch["nFaces"]]:
        for p in face:
            if p not in seen:
                seen[p] = len(seen)
    return np.fromiter(seen.keys(), dtype=np.int64, count=len(seen))


def displacement(x, motion, amplitude, zmin, zmax, radius):
    """Displacement of the points x (n x 3)."""
    s = (x[:, 2] - zmin) / (zmax - zmin)
    # bump(s) = sin(pi s)^2, exactly 0 on the inlet and outlet planes (sin(pi) is not 0 in
    # floating point), so the wall's values there equal the fixed patches' (0 0 0).
    ends = (s <= 1e-12) | (s >= 1 - 1e-12)
    mag = np.where(ends, 0.0, amplitude * radius * np.sin(math.pi * s) ** 2)
    d = np.zeros_like(x)
    if motion == "squeeze":
        r = np.hypot(x[:, 0], x[:, 1])
        if np.any(r < 1e-12 * radius):
            sys.exit("pipe_motion.py: a wall point lies on the axis; no radial direction")
        d[:, 0] = -mag * x[:, 0] / r
        d[:, 1] = -mag * x[:, 1] / r
    elif motion == "shift":
        d[:, 0] = mag
    else:
        sys.exit(f"pipe_motion.py: unknown motion '{motion}' (squeeze or shift)")
    return d + 0.0  # no negative zeros


class Pipe:
    def __init__(self, case, patch_name):
        poly = os.path.join(case, "constant", "polyMesh")
        self.case = case
        self.points = read_points(os.path.join(poly, "points"))
        self.faces = read_faces(os.path.join(poly, "faces"))
        self.patches = read_boundary(os.path.join(poly, "boundary"))
        byname = {p["name"]: p for p in self.patches}
        if patch_name not in byname:
            sys.exit(f"pipe_motion.py: no patch '{patch_name}' in {poly}/boundary "
                     f"(patches: {' '.join(byname)})")
        self.patch = byname[patch_name]
        self.mp = mesh_points(self.faces, self.patch)
        self.zmin = float(self.points[:, 2].min())
        self.zmax = float(self.points[:, 2].max())
        w = self.points[self.mp]
        self.radius = float(np.hypot(w[:, 0], w[:, 1]).max())

    def wall_displacement(self, motion, amplitude, labels=None):
        labels = self.mp if labels is None else labels
        return displacement(self.points[labels], motion, amplitude, self.zmin, self.zmax,
                            self.radius)


def foam_header(cls, location, obj):
    return ("/*--------------------------------*- C++ -*----------------------------------*\\\n"
            "  Generated by meshMorph benchmarks/morph/pipe_motion.py\n"
            "\\*---------------------------------------------------------------------------*/\n"
            "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n    location    \"{location}\";\n"
            f"    object      {obj};\n}}\n"
            "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n")


def cmd_displacement(args):
    pipe = Pipe(args.case, args.patch)
    d = pipe.wall_displacement(args.motion, args.amplitude)
    out = [foam_header("pointVectorField", args.time, "pointDisplacement")]
    out.append(f"// motion {args.motion}, amplitude A = {args.amplitude:.17g} (fraction of "
               f"R = {pipe.radius:.17g}), axis z in [{pipe.zmin:.17g}, {pipe.zmax:.17g}];\n"
               f"// patch '{args.patch}': values in meshPoints order "
               f"(first appearance walking its faces from startFace).\n\n")
    out.append("dimensions      [0 1 0 0 0 0 0];\n\ninternalField   uniform (0 0 0);\n\n")
    out.append("boundaryField\n{\n")
    for p in pipe.patches:
        out.append(f"    {p['name']}\n    {{\n        type            fixedValue;\n")
        if p is pipe.patch:
            out.append(f"        value           nonuniform List<vector>\n{len(d)}\n(\n")
            out.extend(f"({v[0]:.17g} {v[1]:.17g} {v[2]:.17g})\n" for v in d)
            out.append(")\n;\n    }\n")
        else:
            out.append("        value           uniform (0 0 0);\n    }\n")
    out.append("}\n\n// ************************************************************************* //\n")
    tdir = os.path.join(args.case, args.time)
    os.makedirs(tdir, exist_ok=True)
    path = os.path.join(tdir, "pointDisplacement")
    with open(path + ".tmp", "w") as f:
        f.write("".join(out))
    os.replace(path + ".tmp", path)
    print(f"wrote {path}: {len(d)} '{args.patch}' point values, max |d| = "
          f"{np.linalg.norm(d, axis=1).max():.6g}")


def cmd_verify(args):
    pipe = Pipe(args.case, args.patch)
    moved = read_points(os.path.join(args.case, args.time, "polyMesh", "points"))
    if moved.shape != pipe.points.shape:
        sys.exit("pipe_motion.py: moved and original meshes differ in size")
    # The values as written (meshPoints order) applied to the meshPoints.
    d = pipe.wall_displacement(args.motion, args.amplitude)
    err = np.abs(moved[pipe.mp] - (pipe.points[pipe.mp] + d)).max()
    # The same list of values had OpenFOAM numbered the patch points in increasing label order.
    srt = np.sort(pipe.mp)
    err_sorted = np.abs(moved[srt] - (pipe.points[srt] + d)).max()
    same_order = bool(np.array_equal(srt, pipe.mp))
    # Other patches' points (inlet, outlet: fixed), except those shared with the wall.
    on_patch = np.zeros(len(pipe.points), bool)
    on_patch[pipe.mp] = True
    fixed_err = 0.0
    for p in pipe.patches:
        if p is pipe.patch:
            continue
        lab = mesh_points(pipe.faces, p)
        lab = lab[~on_patch[lab]]
        if lab.size:
            fixed_err = max(fixed_err, float(np.abs(moved[lab] - pipe.points[lab]).max()))
    tol = args.tolerance * (pipe.zmax - pipe.zmin)
    ok = err <= tol and fixed_err <= tol
    print(f"verify {args.case} time {args.time}: {len(pipe.mp)} '{args.patch}' points; "
          f"max |x_moved - (x + d)| = {err:.3g} with meshPoints (face-walk) order, "
          f"{err_sorted:.3g} with increasing-label order"
          f"{' (the two orders coincide here)' if same_order else ''}; other patches' "
          f"points moved by at most {fixed_err:.3g}; tolerance {tol:.3g}: "
          f"{'OK' if ok else 'MISMATCH'}")
    return 0 if ok else 1


def cmd_info(args):
    poly = os.path.join(args.case, "constant", "polyMesh")
    points = read_points(os.path.join(poly, "points"))
    faces = read_faces(os.path.join(poly, "faces"))
    owner = read_labels(os.path.join(poly, "owner"))
    neigh = read_labels(os.path.join(poly, "neighbour"))
    cells = int(max(owner.max(), neigh.max() if neigh.size else -1)) + 1
    print(f"cells {cells} points {len(points)} faces {len(faces)}")
    for p in read_boundary(os.path.join(poly, "boundary")):
        print(f"patch {p['name']} {p['type']} {p['nFaces']} {len(mesh_points(faces, p))}")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    for name in ("displacement", "verify"):
        sp = sub.add_parser(name)
        sp.add_argument("case")
        sp.add_argument("--motion", required=True, choices=("squeeze", "shift"))
        sp.add_argument("--amplitude", required=True, type=float)
        sp.add_argument("--time", default="0" if name == "displacement" else None,
                        required=(name == "verify"))
        sp.add_argument("--patch", default="wall")
        if name == "verify":
            sp.add_argument("--tolerance", type=float, default=1e-9)
    sp = sub.add_parser("info")
    sp.add_argument("case")
    args = ap.parse_args()
    return {"displacement": cmd_displacement, "verify": cmd_verify,
            "info": cmd_info}[args.cmd](args) or 0


if __name__ == "__main__":
    sys.exit(main())
