# SPDX-License-Identifier: GPL-3.0-or-later
"""The optimiser of tutorials/adjointLoop (optimise.py): its BFGS steps and the retreat the
loop takes when a design makes J rise. The loop itself needs OpenFOAM's adjoint solver and
minutes per cycle; these check the state it keeps between cycles, on a quadratic."""
import json
import subprocess
import sys

from conftest import SOURCE

OPTIMISE = SOURCE / "tutorials" / "adjointLoop" / "optimise.py"


def optimise(*args):
    done = subprocess.run([sys.executable, str(OPTIMISE), *map(str, args)], capture_output=True,
                          text=True, check=True)
    return done.stdout.split("\n")


def gradient_file(path, g):
    names = [f"v{k}" for k in range(len(g))]
    path.write_text(json.dumps({"names": names, "dJda": dict(zip(names, g))}))
    return path


def test_a_retreat_halves_the_last_step_from_where_it_began(tmp_path):
    state = tmp_path / "state.json"
    kind, direction, _ = optimise("direction", state, gradient_file(tmp_path / "g0.json", [2.0, -1.0]))
    assert kind == "steepest descent"
    d = [float(x) for x in direction.split()]
    assert d == [-2.0, 1.0]
    a1 = [float(x) for x in optimise("step", state, 0.5, *d)[0].split()]
    assert a1 == [-1.0, 0.5]
    a_half = [float(x) for x in optimise("retreat", state)[0].split()]
    assert a_half == [-0.5, 0.25]
    a_quarter = [float(x) for x in optimise("retreat", state)[0].split()]
    assert a_quarter == [-0.25, 0.125]
    saved = json.loads(state.read_text())
    assert saved["a_prev"] == [0.0, 0.0] and saved["a"] == a_quarter


def test_the_bfgs_pair_after_a_retreat_spans_the_shorter_step(tmp_path):
    # J = (a0 - 1)^2 + 2 (a1 - 1)^2, gradient (2 (a0 - 1), 4 (a1 - 1)). A steepest-descent
    # step from 0 that overshoots, its retreat, then BFGS: the pair must be the step taken
    # (s = a - 0, y = g(a) - g(0)), so the updated inverse Hessian maps y to s (secant).
    def grad(a):
        return [2 * (a[0] - 1), 4 * (a[1] - 1)]

    state = tmp_path / "state.json"
    _, direction, _ = optimise("direction", state, gradient_file(tmp_path / "g0.json", grad([0, 0])))
    optimise("step", state, 1.0, *direction.split())
    a = [float(x) for x in optimise("retreat", state)[0].split()]
    assert a == [1.0, 2.0]
    kind, _, _ = optimise("direction", state, gradient_file(tmp_path / "g1.json", grad(a)))
    assert kind == "BFGS"
    s = a
    y = [p - q for p, q in zip(grad(a), grad([0, 0]))]
    h = json.loads(state.read_text())["H"]
    hy = [sum(hij * yj for hij, yj in zip(row, y)) for row in h]
    assert all(abs(p - q) < 1e-12 for p, q in zip(hy, s)), (hy, s)
