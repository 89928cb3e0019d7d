#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The largest difference between the points two cases wrote in time 1, relative to SCALE.

compare_points.py CASE_A CASE_B SCALE    (plain files, ascii or binary)
Prints "max |a - b| = X (X/SCALE of SCALE), at N points" and the count of points that
differ by more than 1e-9 SCALE.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../scripts/parallel"))
from compare_decomposed import points  # noqa: E402


def main():
    a_case, b_case, scale = sys.argv[1], sys.argv[2], float(sys.argv[3])
    a, _ = points(os.path.join(a_case, "1/polyMesh/points"))
    b, _ = points(os.path.join(b_case, "1/polyMesh/points"))
    if len(a) != len(b):
        sys.exit(f"different point counts: {len(a)} and {len(b)}")
    diffs = [max(abs(p[k] - q[k]) for k in range(3)) for p, q in zip(a, b)]
    worst = max(diffs)
    beyond = sum(1 for d in diffs if d > 1e-9 * scale)
    print(f"max |a - b| = {worst:.3g} ({worst / scale:.3g} of the lift); "
          f"{beyond} of {len(a)} points differ by more than 1e-9 of it")


if __name__ == "__main__":
    main()
