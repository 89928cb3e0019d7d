# SPDX-License-Identifier: GPL-3.0-or-later
"""The rows of a design table through meshmorph.DesignStudy (variant_speed.sh, step 4):
per row the best of 3 of evaluate + write, is_valid and transpose_product, in seconds.

    variant_speed.py CASE TABLE OUT.json
"""
import json
import sys
import time

import numpy as np

import meshmorph


def best_of_3(f):
    times = []
    for _ in range(3):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def main(case, table, out):
    rows = np.loadtxt(table, skiprows=1, ndmin=2)
    study = meshmorph.DesignStudy(case)
    dJdx = np.random.default_rng(1).normal(size=(study.points(rows[0]).shape[0], 3))
    result = {"evaluateWrite": [], "isValid": [], "transposeProduct": []}

    for a in rows:
        def evaluate_and_write():
            report = study.evaluate(a)
            if not report.get("refusal"):
                study.write(overwrite=False, time="1")

        result["evaluateWrite"].append(best_of_3(evaluate_and_write))
        result["isValid"].append(best_of_3(lambda: study.is_valid(a)))
        result["transposeProduct"].append(best_of_3(lambda: study.transpose_product(dJdx)))
    with open(out, "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main(*sys.argv[1:])
