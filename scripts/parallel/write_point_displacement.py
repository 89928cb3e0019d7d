#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write 0/pointDisplacement for the pipe tutorial mesh: the wall and the inlet turned 4
degrees about the x axis through (0 0 1) (one rigid rotation, so the points they share get
one value), the outlet zero (morphDict makes it slip).

write_point_displacement.py CASE

The wall and inlet values are written `nonuniform List<vector>` in each patch's point
order (the order of first appearance in the patch's faces, as OpenFOAM's PrimitivePatch
numbers them), so that decomposePar splits them per processor and writes an empty list
for a processor that holds none of a patch's points. Reads the ASCII polyMesh of CASE.
(benchmarks/morph/pipe_motion.py writes such fields too, but needs numpy, an optional
dependency; this test must run without it.)
"""
import math
import re
import sys


def foam_list(path):
    text = open(path).read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    body = text[text.index("}", text.index("FoamFile")) + 1:]
    match = re.search(r"(\d+)\s*\(", body)
    return body[match.end():]


def read_points(case):
    rest = foam_list(f"{case}/constant/polyMesh/points")
    return [tuple(map(float, p)) for p in re.findall(r"\(([^()\s]+) ([^()\s]+) ([^()\s]+)\)", rest)]


def read_faces(case):
    rest = foam_list(f"{case}/constant/polyMesh/faces")
    return [list(map(int, f.split())) for f in re.findall(r"\d+\(([\d\s]+)\)", rest)]


def read_patches(case):
    text = open(f"{case}/constant/polyMesh/boundary").read()
    patches = {}
    for name, block in re.findall(r"(\w+)\s*\{([^}]*)\}", text[text.index("}") + 1:]):
        n = int(re.search(r"nFaces\s+(\d+)", block).group(1))
        start = int(re.search(r"startFace\s+(\d+)", block).group(1))
        patches[name] = (start, n)
    return patches


def patch_points(faces, start, n):
    seen, order = set(), []
    for face in faces[start:start + n]:
        for p in face:
            if p not in seen:
                seen.add(p)
                order.append(p)
    return order


def rotated(x, degrees=4.0, origin=(0.0, 0.0, 1.0)):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    y, z = x[1] - origin[1], x[2] - origin[2]
    return (0.0, c * y - s * z - y, s * y + c * z - z)


def vector_list(values):
    lines = "\n".join(f"({v[0]!r} {v[1]!r} {v[2]!r})" for v in values)
    return f"nonuniform List<vector>\n{len(values)}\n(\n{lines}\n)"


def main(case):
    points, faces, patches = read_points(case), read_faces(case), read_patches(case)
    wall = [rotated(points[p]) for p in patch_points(faces, *patches["wall"])]
    inlet = [rotated(points[p]) for p in patch_points(faces, *patches["inlet"])]
    with open(f"{case}/0/pointDisplacement", "w") as out:
        out.write(
            "FoamFile { version 2.0; format ascii; class pointVectorField; "
            "object pointDisplacement; }\n"
            "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
            f"    wall {{ type fixedValue; value {vector_list(wall)}; }}\n"
            f"    inlet {{ type fixedValue; value {vector_list(inlet)}; }}\n"
            "    outlet { type fixedValue; value uniform (0 0 0); }\n}\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
