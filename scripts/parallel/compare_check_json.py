#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare the JSON of checkMeshQuality -parallel with the serial one.

compare_check_json.py SERIAL_JSON PARALLEL_JSON
Every number must agree: integers exactly, reals to 1e-11 relative (the averages are sums
over the ranks taken in another order; the average non-orthogonality is the arc cosine of
an average, which amplifies round-off). Exceptions, as checkMesh -parallel:
  - boundaryOpenness: processor faces add to the sum of magnitudes (a round-off number
    unless the boundary is open);
  - faces on processor patches count once per side (as coupled faces do in checkMesh), so
    counts of faces may only exceed the serial ones;
  - openness (maxCellOpenness) is a round-off number unless a cell is open (its threshold is
    1e-6): the cells on processor patches sum their faces in another order; 1e-12 absolute.
Exit 0 when they agree, 1 otherwise (the differences are printed).
"""
import json
import sys

SKIPPED = {"boundaryOpenness", "case", "parallel"}
FACE_COUNTS = {"concaveFaces", "lowWeightFaces", "lowVolumeRatioFaces", "warpedFaces",
               "highlySkewedFaces", "severelyNonOrthogonalFaces", "nonOrthogonalityErrors",
               "meshQualityFaces", "faceTetErrors", "incorrectlyOrientedFacePyramids"}


def compare(serial, parallel, path, problems):
    key = path.split("/")[-1].split("[")[0]
    if key in SKIPPED:
        return 0
    if isinstance(serial, dict):
        return sum(compare(v, parallel.get(k), f"{path}/{k}", problems) for k, v in serial.items())
    if isinstance(serial, list):
        if not isinstance(parallel, list) or len(parallel) != len(serial):
            problems.append(f"{path}: {serial} != {parallel}")
            return 1
        return sum(compare(a, b, f"{path}[{i}]", problems)
                   for i, (a, b) in enumerate(zip(serial, parallel)))
    if isinstance(serial, bool) or not isinstance(serial, (int, float)):
        if serial != parallel:
            problems.append(f"{path}: {serial!r} != {parallel!r}")
        return 1
    if isinstance(serial, int) and isinstance(parallel, int):
        face_count = key in FACE_COUNTS or "/meshQualityFailures/" in path
        if serial != parallel and not (face_count and parallel > serial):
            problems.append(f"{path}: {serial} != {parallel}")
        return 1
    scale = max(abs(serial), abs(parallel), 1e-300)
    if key == "maxCellOpenness":
        scale = 0.1  # 1e-12 absolute
    if abs(serial - parallel) > 1e-11 * scale:
        problems.append(f"{path}: {serial!r} != {parallel!r} (relative {abs(serial - parallel) / scale:.1e})")
    return 1


def main():
    serial, parallel = (json.load(open(p)) for p in sys.argv[1:3])
    problems = []
    n = compare(serial, parallel, "", problems)
    for p in problems:
        print(p)
    print(f"JSON: {n} values compared, {len(problems)} differ")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
