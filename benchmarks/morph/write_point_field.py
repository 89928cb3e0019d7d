#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Write a synthetic dJ/dx (a pointVectorField over every point) for timing -sensitivity.

write_point_field.py CASE NAME     (NAME relative to the case, e.g. 0/dJdx)
The values are smooth functions of the point's position; the patches get `calculated`
with uniform zero (the internalField carries the field). Reads constant/polyMesh/points.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../scripts/parallel"))
from compare_decomposed import points  # noqa: E402


def main():
    case, name = sys.argv[1], sys.argv[2]
    x, _ = points(os.path.join(case, "constant/polyMesh/points"))
    path = os.path.join(case, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class pointVectorField; object "
                f"{os.path.basename(name)}; }}\ndimensions [0 0 0 0 0 0 0];\n"
                f"internalField nonuniform List<vector> {len(x)}\n(\n")
        for p in x:
            f.write(f"({math.sin(p[0]):.9g} {math.cos(p[2]):.9g} {p[1]:.9g})\n")
        f.write(");\nboundaryField { \".*\" { type calculated; value uniform (0 0 0); } }\n")


if __name__ == "__main__":
    main()
