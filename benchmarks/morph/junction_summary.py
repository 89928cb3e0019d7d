#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The table of junction_vs_movemesh.sh: morphMesh against moveMesh per mesh, and how often
each morphMesh variant is no worse than moveMesh, per checkMesh figure.

Usage: junction_summary.py OUT_DIR
Reads OUT_DIR/meshes/*/result.json (junction_one_mesh.py); writes OUT_DIR/summary.md (also
printed) and OUT_DIR/summary.json.

A tool's result is valid when it wrote a mesh and checkMesh finds no negative-volume cell
and no wrongly oriented face pyramid; a refused morph (exit 3) is not valid. "No worse"
compares the figure of two valid results (larger non-orthogonality, more faces above 70
degrees, larger skewness, smaller determinant are worse; non-orthogonality and skewness to
1e-6 relative, the digits checkMesh prints and the solver's round-off leave). The boundary
mismatch is the largest distance between the two tools' points on the non-constraint
patches: the motions were the same where it is round-off.
"""
import glob
import json
import os
import sys

FIGURES = [  # (key, label, larger is worse)
    ("maxNonOrthogonality", "max non-orth.", True),
    ("facesAbove70", "faces > 70", True),
    ("maxSkewness", "max skewness", True),
    ("minDeterminant", "min determinant", False),
]


def valid(entry):
    return (entry.get("exit") == 0 and entry.get("read") and entry.get("negativeVolumeCells") == 0
            and entry.get("wrongPyramids") == 0)


def no_worse(ours, theirs, key, larger_is_worse):
    a, b = ours.get(key), theirs.get(key)
    if a is None or b is None:
        return None
    slack = 1e-6 * max(abs(a), abs(b)) if isinstance(a, float) else 0
    return a <= b + slack if larger_is_worse else a >= b - slack


def cell(entry):
    if entry.get("exit") not in (0, None):
        return "refused" if entry.get("exit") == 3 else f"exit {entry.get('exit')}"
    if not valid(entry):
        return (f"invalid ({entry.get('negativeVolumeCells')} neg., "
                f"{entry.get('wrongPyramids')} pyr.)")
    det = entry.get("minDeterminant")
    return (f"{entry['maxNonOrthogonality']:.2f} / {entry['facesAbove70']} / "
            f"{entry['maxSkewness']:.3g} / {det:.3g}" if det is not None else
            f"{entry['maxNonOrthogonality']:.2f} / {entry['facesAbove70']} / {entry['maxSkewness']:.3g} / -")


def main():
    out_dir = sys.argv[1]
    rows = []
    for path in sorted(glob.glob(os.path.join(out_dir, "meshes", "*", "result.json"))):
        r = json.load(open(path))
        if "tools" in r and "moveMesh" in r["tools"]:
            r["name"] = os.path.basename(os.path.dirname(path))
            rows.append(r)
    tools = []
    for r in rows:
        for t in r["tools"]:
            if t != "moveMesh" and t not in tools:
                tools.append(t)

    counts = {}
    for t in tools:
        c = counts[t] = {"meshes": 0, "bothValid": 0, "onlyMoveMeshValid": 0, "onlyOursValid": 0,
                         "neitherValid": 0}
        for key, _, _ in FIGURES:
            c[key] = 0
        c["allFigures"] = 0
        for r in rows:
            ours, theirs = r["tools"].get(t), r["tools"]["moveMesh"]
            if ours is None:
                continue
            c["meshes"] += 1
            vo, vt = valid(ours), valid(theirs)
            if vo and vt:
                c["bothValid"] += 1
                verdicts = [no_worse(ours, theirs, k, w) for k, _, w in FIGURES]
                for (key, _, _), v in zip(FIGURES, verdicts):
                    c[key] += bool(v)
                c["allFigures"] += all(v is not False for v in verdicts)
            elif vt:
                c["onlyMoveMeshValid"] += 1
            elif vo:
                c["onlyOursValid"] += 1
            else:
                c["neitherValid"] += 1

    md = ["# Junctions: morphMesh against moveMesh", "",
          "On each mesh the smallest wall patch scaled by 1% about its centre, every other patch "
          "fixed (in 2D within the planes): the same boundary motion through morphMesh and "
          "through moveMesh (displacementLaplacian, inverseDistance from the moving patch); "
          "OpenFOAM's checkMesh -allGeometry on both results.", ""]
    md += ["| morphMesh variant | meshes | both valid | only moveMesh valid | only morphMesh valid "
           "| neither | " + " | ".join(f"{label} no worse" for _, label, _ in FIGURES)
           + " | every figure no worse |",
           "|---" * (7 + len(FIGURES)) + "|"]
    for t, c in counts.items():
        md.append(f"| {t} | {c['meshes']} | {c['bothValid']} | {c['onlyMoveMeshValid']} | "
                  f"{c['onlyOursValid']} | {c['neitherValid']} | "
                  + " | ".join(f"{c[k]} of {c['bothValid']}" for k, _, _ in FIGURES)
                  + f" | {c['allFigures']} of {c['bothValid']} |")
    md += ["", "Per mesh: max non-orthogonality / faces above 70 degrees / max skewness / min "
           "determinant (checkMesh), and the wall time of each tool's process.", "",
           "| mesh | cells | moving patch | unmoved | " + " | ".join(tools) + " | moveMesh | "
           "time [s] " + " / ".join(tools + ["moveMesh"]) + " | boundary mismatch / largest motion |",
           "|---" * (7 + len(tools)) + "|"]
    for r in rows:
        mismatch = max((v for v in r.get("boundaryMismatch", {}).values() if v is not None), default=None)
        ratio = "-" if mismatch is None else f"{mismatch / r['largestPrescribed']:.1e}" \
            if r.get("largestPrescribed") else "0"
        times = " / ".join(str(r["tools"][t]["seconds"]) if t in r["tools"] else "-"
                           for t in tools + ["moveMesh"])
        md.append(f"| {r['name']} | {r['cells']} | {r['patch']} | {cell(dict(r['before'], exit=0))} | "
                  + " | ".join(cell(r["tools"][t]) if t in r["tools"] else "-" for t in tools)
                  + f" | {cell(r['tools']['moveMesh'])} | {times} | {ratio} |")
    text = "\n".join(md) + "\n"
    with open(os.path.join(out_dir, "summary.md"), "w") as f:
        f.write(text)
    with open(os.path.join(out_dir, "summary.json"), "w") as f:
        json.dump({"counts": counts, "meshes": rows}, f, indent=1)
    print(text)


if __name__ == "__main__":
    main()
