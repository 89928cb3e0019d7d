#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare a -parallel morph with the serial one, point by point.

compare_decomposed.py CASE TIME N SERIAL_POINTS
  - every processor<r>/<TIME>/polyMesh/points entry equals SERIAL_POINTS at its
    pointProcAddressing label to 1e-12 of the mesh extent;
  - the copies of a point shared by processors are bit-identical (to the digits written).
Exit 0 when both hold; prints the largest differences either way. ASCII or binary files
(not compressed).
"""
import re
import struct
import sys


def body(path):
    """The header's format, the list's length and the bytes after its '('."""
    data = open(path, "rb").read()
    header_end = data.index(b"}", data.index(b"FoamFile"))
    binary = re.search(rb"format\s+binary", data[:header_end]) is not None
    match = re.compile(rb"\n(\d+)\s*\n\(").search(data, header_end)
    return binary, int(match.group(1)), data[match.end():]


def points(path):
    """The points and, per point, its exact form (text, or the bytes of a binary file)."""
    binary, n, rest = body(path)
    if binary:
        values = [struct.unpack_from("<3d", rest, 24 * i) for i in range(n)]
        return values, [rest[24 * i: 24 * i + 24] for i in range(n)]
    values = re.findall(rb"\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)", rest)[:n]
    if len(values) != n:
        sys.exit(f"{path}: expected {n} points, found {len(values)}")
    return [tuple(float(v) for v in p) for p in values], [tuple(p) for p in values]


def labels(path):
    binary, n, rest = body(path)
    if binary:  # OpenFOAM's 32-bit labels
        return list(struct.unpack_from(f"<{n}i", rest))
    return [int(v) for v in re.findall(rb"-?\d+", rest[: rest.index(b")")])][:n]


def main():
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
    return 0 if worst <= 1e-12 * extent and mismatched == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
