#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The reverse pass (dJ/dXs) on the full motorBike, against the morph it reverses and against
central differences, in one run.

The bike's surface (every motorBike_.* patch) is moved as a CFD engineer's CAD change might:
a lift of LIFT (a fraction of the bike's height, 1.35156 m; default 0.02, below the 5% at
which the morph repairs a sliver face by the tyre) with a smooth 10% variation along the
bike, so that one surface point moves furthest (the limit's radius then follows it
smoothly); every other patch is fixed. Measured with the limit (the default) and without
it (its radius, the largest prescription, is a maximum with near-ties over a fine
surface: its derivative is one point's, the differences see neighbours take over), each
best of 3 where it is a time:
  - Case.morph (fit + evaluate + check) and Case.sensitivity (refit + reverse pass);
  - dJ/dXs for J = g . x (g random) against differences of J along a smooth perturbation
    delta of the surface motion (1e-4 of it, varying along the bike): morphs at d + t delta
    for t = -2 .. 2 and J's four successive differences. The case is run in a copy whose
    morphDict says `untangle no; steps 1;` (the repair of the sliver face by the tyre, at
    any lift, is not differentiated: the differences would see its iterations; the morph
    is then refused for those 2 cells, its field is still there), and each morph's
    greedy centre count is listed: the reverse pass holds the fit's choices (centres, jump
    flags, the limit's largest prescription), so a difference matches it to the IDW's
    single-precision round-off while the perturbed fits choose alike, and not across a
    change of choice.

    sensitivity_motorbike.py CASE [LIFT [OUT.md]]   (CASE: the full motorBike, e.g.
                                                     build/cases/motorBike-full)
Prints the table (and writes it to OUT.md if given).
"""
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import meshmorph


def best_of(n, call):
    times = []
    for _ in range(n):
        start = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - start)
    return min(times), result


def copy_without_repair(source, target, limit):
    """constant/ and system/ of the case, with a morphDict for one step without repair."""
    for part in ("constant", "system"):
        shutil.copytree(Path(source) / part, target / part)
    (target / "system" / "morphDict").write_text(
        "FoamFile { version 2.0; format ascii; class dictionary; object morphDict; }\n"
        f"untangle no;\nsteps 1;\nrbf {{ limit {'yes' if limit else 'no'}; }}\n")


def measure(source, lift, limit):
    """The table's rows for one run: the morph with or without the limit."""
    work = Path(tempfile.mkdtemp(prefix="sensitivity_motorbike."))
    copy_without_repair(source, work / "case", limit)
    case = meshmorph.Case(str(work / "case"))
    bike = np.unique(np.concatenate([case.patch_points(name) for name in case.patches
                                     if name.startswith("motorBike_")]))
    x = case.initial_points[bike]
    span = x[:, 0].max() - x[:, 0].min()
    d = np.zeros_like(x)
    along = (x[:, 0] - x[:, 0].min()) / span
    d[:, 2] = lift * 1.35156 * (1.0 + 0.1 * along)
    prescription = {"bike": (bike, d)}
    morph_time, report = best_of(3, lambda: case.morph(points=prescription))
    steps = len(report["steps"])
    rng = np.random.default_rng(5)
    g = rng.normal(size=(case.n_points, 3))
    reverse_time, sensitivity = best_of(3, lambda: case.sensitivity(g))
    dXs = sensitivity[bike]
    shape = np.column_stack([np.sin(5.0 * along), np.cos(2.0 * along), np.sin(3.0 * along)])
    delta = 1e-4 * lift * 1.35156 * shape
    objective, centres = [], []
    for t in (-2.0, -1.0, 0.0, 1.0, 2.0):
        r = case.morph(points={"bike": (bike, d + t * delta)})
        centres.append(r["steps"][0]["centres"])
        objective.append(float(np.sum(g * case.points)))
    adjoint = float(np.sum(dXs * delta))
    differences = np.diff(objective)
    shutil.rmtree(work)
    rows = [
        ("rbf { limit }", "yes (the default)" if limit else "no"),
        ("points, surface points", f"{case.n_points}, {len(bike)}"),
        ("lift (of the bike's height)", f"{lift}"),
        ("morph: steps, refused, cells repaired",
         f"{steps}, {report['refused']}, {report['steps'][0]['untangle']['invalidCells']}"),
        ("Case.morph [s] (best of 3)", f"{morph_time:.3f}"),
        ("Case.sensitivity [s] (best of 3)", f"{reverse_time:.3f}"),
        ("reverse pass / morph", f"{reverse_time / morph_time:.2f}"),
        ("greedy centres of the morph", f"{report['steps'][0]['centres']}"),
    ]
    rows.append(("dJ/dXs . delta (the reverse pass)", f"{adjoint:.8g}"))
    rows.append(("J(t + 1) - J(t), t = -2 .. 1 (morphs at d + t delta)",
                 ", ".join(f"{v:.8g}" for v in differences)))
    rows.append(("their relative differences from the reverse pass",
                 ", ".join(f"{abs(v - adjoint) / abs(adjoint):.1e}" for v in differences)))
    rows.append(("greedy centres of those morphs", ", ".join(map(str, centres))))
    return rows


def main():
    lift = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    text = ""
    for limit in (True, False):
        rows = measure(sys.argv[1], lift, limit)
        lines = ["| quantity | value |", "| --- | --- |"] + [f"| {a} | {b} |" for a, b in rows]
        text += "\n".join(lines) + "\n\n"
    print(text)
    if len(sys.argv) > 3:
        with open(sys.argv[3], "w") as out:
            out.write(text)


if __name__ == "__main__":
    main()
