#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Give moveMesh the boundary motion a morphMesh result made, point by point.

same_boundary_motion.py write CASE MORPHED FILE
    FILE (a 0/pointDisplacement): every non-constraint patch of CASE's constant/polyMesh
    fixedValue at the displacement of its points in MORPHED's latest time (patch-local
    order), constraint patches their own type. moveMesh run on it makes the same boundary
    motion as the morph, including which prescription won where two patches meet.
same_boundary_motion.py mismatch CASE A B
    Prints the largest distance between the latest-time points of cases A and B on CASE's
    non-constraint patches: round-off when the two tools made the same boundary motion.

Needs the meshmorph Python module on PYTHONPATH (build/<preset>/python).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from junction_one_mesh import boundary_mismatch, latest_points, write_point_displacement  # noqa: E402

import meshmorph  # noqa: E402


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("write", "mismatch"):
        sys.exit(__doc__)
    mode, case_dir, a, b = sys.argv[1:]
    case = meshmorph.Case(case_dir, time="constant")
    if mode == "write":
        moved = latest_points(a)
        if moved is None:
            sys.exit(f"same_boundary_motion.py: no morphed points in {a}")
        write_point_displacement(case, b, None, moved)
    else:
        pa, pb = latest_points(a), latest_points(b)
        mismatch = boundary_mismatch(case, pa, pb)
        print("NA" if mismatch is None else f"{mismatch:.3g}")
        scale = np.max(np.linalg.norm(pa - case.initial_points, axis=1)) if pa is not None else 0.0
        print("NA" if mismatch is None or scale == 0 else f"{mismatch / scale:.3g}")


if __name__ == "__main__":
    main()
