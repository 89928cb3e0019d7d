#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks a deformationBenchmarks report (the CTest test PaperBenchmarksQuickReport): every
section present, Table 3 complete, every plot there, and the invariants that must hold
whatever the machine (never timings):

  - the RBF meets its constraints to 1e-9 (relative) wherever it is solved directly;
  - DM-FFD's least-squares residual does not grow on nested lattices;
  - the handle basis reproduces the fitted deformation, refit reproduces the basis, and the
    basis file reads back identical;
  - no defective surface makes a method fail; clamping lowers the DM-FFD rank;
  - the adaptive refinements lower the error; break amplitudes lie in (0, 1].

Usage: check_report.py DIR
"""
import json
import os
import re
import sys

errors = []


def check(cond, what):
    if not cond:
        errors.append(what)


def load(data, name):
    path = os.path.join(data, name + ".json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def main(out):
    report = os.path.join(out, "report.md")
    if not os.path.exists(report):
        print(f"check_report: no {report}")
        return 1
    with open(report) as f:
        md = f.read()
    data = os.path.join(out, "data")
    run = load(data, "run")

    # Structure.
    for heading in ("## 1. Performance", "## 2. Robustness", "## 3. Quality of deformation",
                    "## 4. Adaptivity", "## 5. Precision", "## 6. Volume mesh morphing",
                    "### 6.1 Pipe", "## Table 3 rebuilt from the measurements",
                    "## Where the results differ from the paper, and why",
                    "## What was not run", "## Steps"):
        check(heading in md, f"report.md has no '{heading}'")
    sections = re.split(r"^## ", md, flags=re.M)
    for s in sections[1:7]:
        check(not s.split("\n\n", 1)[1].startswith("Not run"),
              f"section '{s.splitlines()[0]}' was not run")
    t3 = md.split("## Table 3 rebuilt from the measurements", 1)[-1]
    for method in ("FFD", "DM-FFD", "RBF"):
        row = re.search(rf"^\| {re.escape(method)} \|(.*)\|$", t3, flags=re.M)
        check(row is not None, f"Table 3 has no row {method}")
        if row:
            cells = [c.strip() for c in row.group(1).split("|")]
            check(len(cells) == 6, f"Table 3 row {method}: {len(cells)} columns, expected 6")
            for c in cells:
                check(re.match(r"^(\+|o|-|n/a)( \(paper [+o-]\))?$", c) is not None,
                      f"Table 3 row {method}: bad mark '{c}'")
    check("How each mark was measured" in t3, "Table 3 has no rules")
    images = re.findall(r"!\[[^]]*\]\(([^)]+)\)", md)
    try:
        import matplotlib  # noqa: F401
        check(len(images) >= 10, f"only {len(images)} plots in the report")
    except ImportError:
        pass
    for img in images:
        path = os.path.join(out, img)
        ok = os.path.exists(path)
        if ok:
            with open(path, "rb") as f:
                ok = f.read(8) == b"\x89PNG\r\n\x1a\n"
        check(ok, f"plot {img} missing or not a PNG")
    if run:
        for s in run["steps"]:
            if s.get("exit") not in (0, None) and not s.get("optional"):
                errors.append(f"step {s['step']} exited {s['exit']}")

    # Invariants.
    exact = 1e-9
    for name in ("performance-serial", "performance-parallel"):
        p = load(data, name)
        check(p is not None, f"no data/{name}.json")
        if not p:
            continue
        for r in p["fig6"]:
            check(r["basisVsEvaluateRel"] <= exact,
                  f"{name} {r['method']}: B H differs from the fitted deformation by "
                  f"{r['basisVsEvaluateRel']}")
            check(r["refitVsApplyRel"] <= exact,
                  f"{name} {r['method']}: refit differs from B H by {r['refitVsApplyRel']}")
            check(r["loadedIdentical"], f"{name} {r['method']}: basis file reads back different")
        for r in p.get("scale", []):
            if r["method"] in ("rbf", "greedy+idw", "idw") and not r.get("skipped"):
                check(r["residual"]["maxRel"] <= exact,
                      f"{name} scale {r['method']} m={r['constraints']}: residual "
                      f"{r['residual']['maxRel']}")
    rb = load(data, "robustness")
    check(rb is not None, "no data/robustness.json")
    if rb:
        for r in rb["surfaces"]["runs"]:
            check(r["ok"], f"robustness: {r['method']} failed on {r['defect']} ({r['region']}): "
                           f"{r.get('error', 'non-finite')}")
        cl = rb["sphere"]["clamping"]
        ranks = [r["rank"] for r in cl]
        check(all(a >= b for a, b in zip(ranks, ranks[1:])),
              f"robustness: DM-FFD rank does not fall with the clamping: {ranks}")
        check(rb["sphere"]["rbfResidual"]["maxRel"] <= exact, "robustness: RBF residual")
    q = load(data, "quality")
    check(q is not None, "no data/quality.json")
    if q:
        for r in q["runs"]:
            if r["method"] == "rbf":
                check(r["residual"]["maxRel"] <= exact, f"quality: RBF residual "
                                                        f"{r['residual']['maxRel']}")
            check(r["curvature"]["vertices"] > 0, f"quality: no curvature for {r['method']}")
    p = load(data, "precision")
    check(p is not None, "no data/precision.json")
    if p:
        for sc in ("plane", "smooth"):
            dm = [r["residual"]["maxRel"] for r in p["runs"]
                  if r["scenario"] == sc and r["method"] == "dmffd"]
            check(len(dm) >= 3, f"precision {sc}: {len(dm)} DM-FFD lattices")
            check(all(b <= a * (1 + 1e-6) + 1e-12 for a, b in zip(dm, dm[1:])),
                  f"precision {sc}: DM-FFD residual grows on nested lattices: {dm}")
            rbf = [r for r in p["runs"] if r["scenario"] == sc and r["method"] == "rbf"]
            check(rbf and rbf[0]["residual"]["maxRel"] <= exact, f"precision {sc}: RBF residual")
    a = load(data, "adaptivity")
    check(a is not None, "no data/adaptivity.json")
    if a:
        for method in ("greedy-rbf", "dmffd-planes"):
            rs = [r for r in a["rows"] if r["method"] == method]
            check(len(rs) >= 3, f"adaptivity: {len(rs)} rows of {method}")
            if rs:
                check(rs[-1]["maxError"] < rs[0]["maxError"] and
                      rs[-1]["rmsError"] < rs[0]["rmsError"],
                      f"adaptivity: {method} does not improve")
        check(all(r["count"] <= a["constraints"] for r in a["rows"]
                  if r["method"] == "greedy-rbf"), "adaptivity: more centres than constraints")
    pipes = [x for x in (load(data, "pipe-hex"), load(data, "pipe-tet")) if x]
    check(pipes, "no data/pipe-*.json")
    for pp in pipes:
        for r in pp["runs"]:
            if r["method"] == "rbf":
                check(r["residual"]["maxRel"] <= exact, f"pipe {pp['name']}: RBF residual")
            check(abs(r["minScaledJacobian"][0] - pp["baseMinScaledJacobian"]) < 1e-12,
                  f"pipe {pp['name']} {r['method']}: A = 0 is not the undeformed mesh")
            b = r["breakAmplitude"]
            check(b is None or 0 < b <= 1.0, f"pipe {pp['name']} {r['method']}: break A {b}")
    if run and not run["environment"]["quick"] and "pipe" not in run["skipped"]:
        check(load(data, "pipe-movemesh") is not None or "pipe-movemesh" in run["skipped"],
              "pipe: neither moveMesh's break amplitudes nor a reason why not")
    mb = load(data, "motorbike")
    if mb:
        for r in mb["runs"]:
            if r["method"] == "rbf":
                check(r["residual"]["maxRel"] <= exact, "motorbike: RBF residual")
        checks = load(data, "motorbike-checks") or {}
        check("checkMeshQuality" in checks.get("original", {}).get("0", {}),
              "motorbike: no checkMeshQuality numbers for the original mesh")
        for r in mb["runs"]:
            for lift in mb["lifts"]:
                check("checkMeshQuality" in checks.get(r["method"], {}).get(lift, {}),
                      f"motorbike: no checkMeshQuality numbers for {r['method']} at {lift}")
    elif run:
        check("motorbike" in run["skipped"], "motorbike: neither data nor a reason")

    for e in errors:
        print("check_report: " + e)
    print(f"check_report: {out}: {'OK' if not errors else str(len(errors)) + ' problem(s)'}")
    return 1 if errors else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
