#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The optimiser of tutorials/adjointLoop: BFGS on the design variables' amplitudes, as
OpenFOAM's own BFGS update (one steepest-descent step first, then BFGS with the inverse
Hessian scaled at its first update and etaHessian 0.8). Pure python (no numpy).

optimise.py direction STATE DJDA      reads dJ/da (morphMesh -sensitivity's JSON), updates
                                      the inverse Hessian in STATE (JSON), prints the search
                                      direction d (one number per variable) and its kind
optimise.py step STATE ETA D...       a <- a + ETA d; prints the new amplitudes
optimise.py undo STATE                a <- the amplitudes before the last step
optimise.py retreat STATE             the last step at half its length from where it
                                      started (J rose): prints the new amplitudes
"""
import json
import os
import sys

ETA_HESSIAN = 0.8


def load(path):
    return json.load(open(path)) if os.path.exists(path) else {}


def save(path, state):
    with open(path, "w") as f:
        json.dump(state, f)


def matvec(h, v):
    return [sum(hij * vj for hij, vj in zip(row, v)) for row in h]


def bfgs_update(h, s, y, first):
    """The inverse-Hessian update H+ = (I - r s y^T) H (I - r y s^T) + r s s^T."""
    sy = sum(a * b for a, b in zip(s, y))
    if sy <= 0:  # curvature condition fails: keep H (OpenFOAM does the same)
        return h
    n = len(s)
    if first:  # scaleFirstHessian: H0 = (s.y / y.y) I
        yy = sum(b * b for b in y)
        h = [[(sy / yy if i == j else 0.0) for j in range(n)] for i in range(n)]
    r = 1.0 / sy
    hy = matvec(h, y)
    yhy = sum(a * b for a, b in zip(y, hy))
    return [[h[i][j] - r * (s[i] * hy[j] + hy[i] * s[j]) + (r * r * yhy + r) * s[i] * s[j]
             for j in range(n)] for i in range(n)]


def direction(state_path, djda_path):
    state = load(state_path)
    sens = json.load(open(djda_path))
    g = [sens["dJda"][name] for name in sens["names"]]
    n = len(g)
    a = state.get("a", [0.0] * n)
    if "g" not in state:  # the first cycle: steepest descent
        d, kind = [-x for x in g], "steepest descent"
        state["H"] = None
    else:
        s = [x - y for x, y in zip(a, state["a_prev"])]
        y = [x - y for x, y in zip(g, state["g"])]
        h = state["H"] if state["H"] is not None else [[float(i == j) for j in range(n)] for i in range(n)]
        h = bfgs_update(h, s, y, state["H"] is None)
        state["H"] = h
        d, kind = [-x for x in matvec(h, g)], "BFGS"
    state.update({"a": a, "g": g, "names": sens["names"]})
    save(state_path, state)
    print(kind)
    print(" ".join(repr(x) for x in d))


def step(state_path, eta, d):
    state = load(state_path)
    a = state["a"]
    state["a_prev"] = list(a)
    state["a"] = [x + eta * y for x, y in zip(a, d)]
    state["eta"], state["d"] = eta, d
    save(state_path, state)
    print(" ".join(repr(x) for x in state["a"]))


def retreat(state_path):
    """The design the last step reached made J rise: half the step from where it began
    (the BFGS pair of the next direction then spans the shorter step)."""
    state = load(state_path)
    state["a"] = state["a_prev"]
    save(state_path, state)
    step(state_path, 0.5 * state["eta"], state["d"])


def undo(state_path):
    state = load(state_path)
    state["a"] = state["a_prev"]
    save(state_path, state)


if __name__ == "__main__":
    if sys.argv[1] == "direction":
        direction(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "undo":
        undo(sys.argv[2])
    elif sys.argv[1] == "retreat":
        retreat(sys.argv[2])
    elif sys.argv[1] == "step":
        step(sys.argv[2], float(sys.argv[3]), [float(x) for x in sys.argv[4:]])
    else:
        sys.exit("usage: optimise.py direction STATE DJDA | step STATE ETA D... | undo STATE | retreat STATE")
