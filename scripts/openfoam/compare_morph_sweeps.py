#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Two morph sweeps (checkmesh_sweep.sh -morph) of the same meshes, mesh by mesh: how the
verdicts moved, and, on the meshes whose second sweep smoothed a jump band
(morph.json steps[].jumpSmoothedPoints > 0), how max non-orthogonality moved.

Usage: compare_morph_sweeps.py BEFORE_DIR AFTER_DIR
Reads each DIR/summary.csv and DIR/cases/<case>/meshes/<mesh>/morph.json; prints the
verdict transitions with their counts, every mesh whose verdict changed, then one line per
smoothed mesh and the counts of meshes whose max non-orthogonality rose, fell or stayed
within 0.01 degrees.
"""
import collections
import csv
import glob
import json
import os
import sys


def verdicts(sweep):
    with open(os.path.join(sweep, "summary.csv")) as f:
        return {(r["case"], r["mesh"]): r for r in csv.DictReader(f)}


def print_verdict_changes(before, after):
    moves = collections.Counter()
    for key in sorted(set(before) & set(after)):
        moves[(before[key]["verdict"], after[key]["verdict"])] += 1
    for (a, b), n in sorted(moves.items()):
        print(f"{a:>10} -> {b:<10} {n}")
    for key in sorted(set(before) & set(after)):
        if before[key]["verdict"] != after[key]["verdict"]:
            print(f"  {key[0]} {key[1]}: {before[key]['verdict']} -> {after[key]['verdict']}: "
                  f"{after[key]['reason'][:160]}")


def quality(path):
    with open(path) as f:
        j = json.load(f)
    a = j.get("after", {})
    smoothed = max((s.get("jumpSmoothedPoints", 0) for s in j.get("steps", [])), default=0)
    return smoothed, a.get("maxNonOrthogonality"), a.get("severelyNonOrthogonalFaces")


def print_quality_changes(before_dir, after_dir):
    counts = collections.Counter()
    pattern = os.path.join(after_dir, "cases", "*", "meshes", "*", "morph.json")
    for after_path in sorted(glob.glob(pattern)):
        rel = os.path.relpath(after_path, after_dir)
        before_path = os.path.join(before_dir, rel)
        if not os.path.exists(before_path):
            continue
        try:
            smoothed, after_max, after_severe = quality(after_path)
            _, before_max, before_severe = quality(before_path)
        except (OSError, ValueError):
            continue
        if smoothed == 0 or after_max is None or before_max is None:
            continue
        change = after_max - before_max
        counts["within 0.01" if abs(change) < 0.01 else "higher" if change > 0 else "lower"] += 1
        parts = rel.split(os.sep)
        print(f"  {parts[1]} {parts[3]}: {smoothed} points smoothed; max non-orthogonality "
              f"{before_max:.2f} -> {after_max:.2f}, faces above 70 {before_severe} -> "
              f"{after_severe}")
    print(f"meshes with a smoothed band: {sum(counts.values())}; max non-orthogonality higher "
          f"on {counts['higher']}, lower on {counts['lower']}, within 0.01 on "
          f"{counts['within 0.01']}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before_dir, after_dir = sys.argv[1], sys.argv[2]
    print_verdict_changes(verdicts(before_dir), verdicts(after_dir))
    print_quality_changes(before_dir, after_dir)


if __name__ == "__main__":
    main()
