#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compare two checkMesh reports line by line (the block from "Mesh stats" to the verdict).

compare_reports.py EXPECTED ACTUAL
Both files are logs; the report block is cut out of each. Lines must have the same words;
numbers must agree to 1e-9 relative, or 1e-12 absolute for round-off noise near zero (the
boundary openness is a sum of face area vectors that cancels to ~1e-17: its digits depend
on the order of the sums, over the ranks too, and on whether the compiler contracts to
FMA). Exit 0 when they agree; otherwise prints the first differing lines and exits 1.
"""
import re
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def report(path):
    lines = open(path, errors="replace").read().splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("Mesh stats")), None)
    if start is None:
        sys.exit(f"{path}: no report (no 'Mesh stats' line)")
    end = next(i for i in range(start, len(lines))
               if lines[i] == "Mesh OK." or re.fullmatch(r"Failed \d+ mesh checks\.", lines[i]))
    return lines[start:end + 1]


def same(a, b):
    if NUMBER.sub("#", a) != NUMBER.sub("#", b):
        return False
    for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)):
        u, v = float(x), float(y)
        if abs(u - v) > 1e-9 * max(abs(u), abs(v)) + 1e-12:
            return False
    return True


def main():
    expected, actual = report(sys.argv[1]), report(sys.argv[2])
    differing = [(i, e, a) for i, (e, a) in enumerate(zip(expected, actual)) if not same(e, a)]
    if len(expected) != len(actual):
        differing.append((min(len(expected), len(actual)), f"{len(expected)} lines",
                          f"{len(actual)} lines"))
    for i, e, a in differing[:10]:
        print(f"line {i + 1}:\n< {e}\n> {a}")
    print(f"report: {len(expected)} lines, {len(differing)} differ")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
