#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""meshMorph tutorial "python": a few steps of a gradient-based optimisation with SciPy.

The pipe's wall is to become a venturi, the radius narrowed to 70 % at mid-length:
    J(a) = 1/2 sum over the wall points of |x_i(a) - t_i|^2,
with t_i the wall point moved radially onto the venturi. The design variables are the
morphDict's 32 lattice bumps (system/morphDict); each design x(a) = x0 + sum_j a_j F_j and
each gradient dJ/da = F^T dJ/dx comes from meshmorph's design set-up, in memory: no mesh
is written until the end. SciPy's L-BFGS-B takes the steps within the variables' bounds;
every design it asks for is checked for validity (the cheap test), and the best one is
checked in full (checkMesh's metrics) and written to 1/polyMesh/points.

    ./optimise.py [-iterations N]     (run by ./Allrun; needs the meshmorph module)
"""
import argparse
import sys

import numpy as np
from scipy.optimize import minimize

import meshmorph


def venturi_target(x0, wall):
    """The wall points moved radially onto r(z) = 0.5 (1 - 0.3 exp(-((z - 1) / 0.3)^2))."""
    p = x0[wall]
    r = np.hypot(p[:, 0], p[:, 1])
    r_target = 0.5 * (1.0 - 0.3 * np.exp(-((p[:, 2] - 1.0) / 0.3) ** 2))
    t = p.copy()
    t[:, :2] *= (r_target / r)[:, None]
    return t


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-iterations", type=int, default=8)
    args = parser.parse_args()

    print("Setting up the design variables (morphMesh -variables)", flush=True)
    setup = meshmorph.setup_design(".")
    print(f"  {len(setup['variables'])} variables, {setup['seconds']:.2f} s", flush=True)
    study = meshmorph.DesignStudy(".")
    wall = meshmorph.Case(".").patch_points("wall")
    target = venturi_target(study.initial_points, wall)
    evaluations = []

    def objective(a):
        x = study.points(a)
        misfit = x[wall] - target
        dJdx = np.zeros_like(x)
        dJdx[wall] = misfit
        J = 0.5 * float(np.sum(misfit ** 2))
        valid = study.is_valid(a)
        evaluations.append((J, valid))
        return J, study.transpose_product(dJdx)

    a0 = np.zeros(len(study.names))
    J0, g0 = objective(a0)
    # The gradient against a central difference along it (J is quadratic: exact).
    h = 1e-3 / np.linalg.norm(g0)
    fd = (objective(a0 + h * g0)[0] - objective(a0 - h * g0)[0]) / (2 * h)
    print(f"  J(0) = {J0:.6g}; gradient check along dJ/da: {fd:.10g} (finite difference) "
          f"vs {g0 @ g0:.10g} (transpose product)", flush=True)

    def report(a):
        J, valid = evaluations[-1]
        print(f"  iteration {len(history) + 1}: J = {J:.6g} ({J / J0:.1%} of J(0)), "
              f"{'valid' if valid else 'INVALID'}", flush=True)
        history.append(J)

    history = []
    bounds = [b if b is not None else (None, None) for b in study.bounds]
    result = minimize(objective, a0, jac=True, method="L-BFGS-B", bounds=bounds,
                      callback=report, options={"maxiter": args.iterations})
    print(f"L-BFGS-B: {result.message} after {result.nit} iterations, "
          f"{len(evaluations)} designs evaluated", flush=True)

    best = study.evaluate(result.x)
    after = best["after"]
    print(f"Best design: J = {result.fun:.6g} ({result.fun / J0:.1%} of J(0)); "
          f"max non-orthogonality {after['maxNonOrthogonality']:.4g}, "
          f"max skewness {after['maxSkewness']:.4g}, "
          f"{'Mesh OK' if after['meshOK'] else 'mesh checks failed'}", flush=True)
    if not best["valid"]:
        print("optimise.py: the best design is not a valid mesh", file=sys.stderr)
        return 1
    print(f"Wrote {study.write()}", flush=True)
    return 0 if result.fun < 0.5 * J0 else 1


if __name__ == "__main__":
    sys.exit(main())
