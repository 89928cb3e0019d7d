#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Summary of a morph sweep (checkmesh_sweep.sh -morph): the count of each verdict, and a
table of every mesh that did not end valid, with its reason.

Usage: morph_sweep_summary.py OUT_DIR [--fail-on-silent]
Reads OUT_DIR/cases/<case>/meshes/<mesh>/result.json (written by morph_one_mesh.py) and
OUT_DIR/cases/<case>/mesh_error (a tutorial that could not be meshed); writes
OUT_DIR/summary.md (also printed), summary.csv and summary.json. With --fail-on-silent
the exit status is 1 when any mesh ended silent or crashed.
"""
import csv
import glob
import json
import os
import sys

ORDER = ["valid", "warned", "refused", "skipped", "silent", "crashed", "not meshed"]


def collect(out_dir):
    rows = []
    for case_dir in sorted(glob.glob(os.path.join(out_dir, "cases", "*"))):
        case = os.path.basename(case_dir)
        results = sorted(glob.glob(os.path.join(case_dir, "meshes", "*", "result.json")))
        error = os.path.join(case_dir, "mesh_error")
        if not results and os.path.exists(error):
            rows.append({"case": case, "mesh": "", "verdict": "not meshed",
                         "reason": open(error).read().strip()})
        for path in results:
            r = json.load(open(path))
            rows.append({"case": case, "mesh": os.path.basename(os.path.dirname(path)),
                         "verdict": r["verdict"], "reason": r.get("reason", ""),
                         "patch": r.get("patch", ""), "cells": r.get("cells", ""),
                         "seconds": r.get("morph_seconds", "")})
        if not results and not os.path.exists(error):
            rows.append({"case": case, "mesh": "", "verdict": "crashed",
                         "reason": "no result written for its meshes"})
    return rows


def main():
    out_dir = sys.argv[1]
    fail_on_silent = "--fail-on-silent" in sys.argv[2:]
    rows = collect(out_dir)
    counts = {v: sum(r["verdict"] == v for r in rows) for v in ORDER}
    lines = ["# Morph sweep", "",
             "The smallest wall patch of every mesh scaled by 1% about its centre, every "
             "other patch fixed; OpenFOAM's checkMesh on the result.", "",
             "| verdict | meshes |", "|---|---|"]
    lines += [f"| {v} | {counts[v]} |" for v in ORDER]
    lines += [f"| **total** | {len(rows)} |", ""]
    others = [r for r in rows if r["verdict"] != "valid"]
    if others:
        lines += ["| case | mesh | verdict | reason |", "|---|---|---|---|"]
        for r in sorted(others, key=lambda r: (ORDER.index(r["verdict"]), r["case"])):
            reason = r["reason"].replace("|", "/").replace("\n", " ")[:300]
            lines.append(f"| {r['case']} | {r['mesh']} | {r['verdict']} | {reason} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "summary.md"), "w") as f:
        f.write(text)
    with open(os.path.join(out_dir, "summary.json"), "w") as f:
        json.dump({"counts": counts, "meshes": rows}, f, indent=2)
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["case", "mesh", "verdict", "reason", "patch", "cells",
                                          "seconds"])
        w.writeheader()
        for r in rows:
            w.writerow(r)
    print(text)
    if fail_on_silent and (counts["silent"] or counts["crashed"]):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
