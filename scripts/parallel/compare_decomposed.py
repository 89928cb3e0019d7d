#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare a -parallel morph with the serial one, point by point.

compare_decomposed.py CASE TIME N SERIAL_POINTS
  - every processor<r>/<TIME>/polyMesh/points entry equals SERIAL_POINTS at its
    pointProcAddressing label to 1e-12 of the mesh extent;
  - the copies of a point shared by processors are bit-identical (to the digits written).
Exit 0 when both hold; prints the largest differences either way. ASCII files only.
"""
import re
import sys


def body(path):
    text = open(path).read()
    header_end = text.index("}", text.index("FoamFile"))
    match = re.compile(r"\n(\d+)\s*\n\(").search(text, header_end)
    return int(match.group(1)), text[match.end():]


def points(path):
    n, rest = body(path)
    values = re.findall(r"\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)", rest)[:n]
    if len(values) != n:
        sys.exit(f"{path}: expected {n} points (ASCII), found {len(values)}")
    return [tuple(float(v) for v in p) for p in values], [tuple(p) for p in values]


def labels(path):
    n, rest = body(path)
    return [int(v) for v in re.findall(r"-?\d+", rest[: rest.index(")")])][:n]


case, time, n_procs, serial_file = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
serial, _ = points(serial_file)
extent = max(max(p[k] for p in serial) - min(p[k] for p in serial) for k in range(3))
worst, mismatched, shared = 0.0, 0, 0
seen = {}
for r in range(n_procs):
    values, texts = points(f"{case}/processor{r}/{time}/polyMesh/points")
    addressing = labels(f"{case}/processor{r}/constant/polyMesh/pointProcAddressing")
    for p, text, g in zip(values, texts, addressing):
        worst = max(worst, max(abs(p[k] - serial[g][k]) for k in range(3)))
        if g in seen:
            shared += 1
            mismatched += seen[g] != text
        else:
            seen[g] = text
print(f"largest difference to the serial morph: {worst:.3e} ({worst / extent:.3e} of the extent)")
print(f"shared point copies: {shared}, not bit-identical: {mismatched}")
sys.exit(0 if worst <= 1e-12 * extent and mismatched == 0 else 1)
