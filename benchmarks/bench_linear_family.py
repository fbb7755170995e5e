"""Benchmark: lkverify.linear.family — the linear margin of a whole gain grid, linearised once.

Run:  python benchmarks/bench_linear_family.py [--every 1]

Paper 002 (aleksandrov2023.fig1: a = 2, τ = 0.9, μ = 1) swept over b ∈ [−3, 3] (61 values) and
the damping h of F = h·I, h ∈ [0.1, 2] (40 values) — the acceptance grid of ``lkverify sweep``:

* the cost of one symbolic linearisation (``linear_family``) against one exact
  ``linearise`` (what a per-point loop would pay 2440 times), and the per-point cost of
  ``LinearFamily.evaluate`` (wall and CPU);
* the accuracy behind the defaults (NODES, REFINE, TOL): on every ``--every``-th point
  the abscissa at the default degree against degree 2·NODES and 40, the unrefined
  discretised abscissa against the refined one, at τ = 0.9, 3 and 6;
* structural zeros: paper 002 at μ = 2 in orthonormal coordinates of an irrational r
  (floating-point matrices not exactly singular) and a defective double zero, with the
  structural flag off — how far from 0 the computed abscissa lands.

Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import time

import numpy as np
import sympy


def _timed(f):
    w, c = time.perf_counter(), time.process_time()
    out = f()
    return out, time.perf_counter() - w, time.process_time() - c


def _grid():
    return np.array([[b, h] for b in np.linspace(-3, 3, 61) for h in np.linspace(0.1, 2, 40)])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--every", type=int, default=10, help="accuracy study on every k-th grid point")
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, load {os.getloadavg()[0]:.1f}")
    from lkverify.catalogue.loader import find_items
    from lkverify.linear import linearise
    from lkverify.linear.family import NODES, REFINE, TOL, linear_family

    example = find_items("aleksandrov2023.fig1")[0]
    run = example.runs[0]
    h = sympy.Symbol("h")
    values = {k: v for k, v in run.values.items() if k not in ("b", "F")}
    values["F"] = sympy.ImmutableMatrix(sympy.diag(h, h, h))
    _, w, c = _timed(lambda: linearise(run.system, example.equilibrium, run.values))
    print(f"\none exact linearise (Fig. 1's gains): {w:.2f} s wall, {c:.2f} s CPU  (× 2440 points: {2440 * w:.0f} s)")
    fam, w, c = _timed(lambda: linear_family(run.system, example.equilibrium, values, grid=("b", "h")))
    print(f"linear_family, grid (b, h): {w:.2f} s wall, {c:.2f} s CPU; n = {fam.n}, delay {fam.delay}, "
          f"structural zero {fam.structural_zero}")
    pts = _grid()
    fam.evaluate(pts[:5])                                  # the generated function, once per process
    batch, w, c = _timed(lambda: fam.evaluate(pts))
    print(f"evaluate {len(pts)} points (N = {NODES}, {REFINE} refined): {w:.2f} s wall, {c:.2f} s CPU = "
          f"{1000 * w / len(pts):.2f} ms wall, {1000 * c / len(pts):.2f} ms CPU per point; verdicts {batch.counts()}; "
          f"retried at 2N: {int(np.sum(batch.nodes > NODES))}; unconverged: {int(np.sum(~batch.converged))}; "
          f"max residual {np.nanmax(batch.residual):.1e}")
    _accuracy(run, example, values, pts[::args.every], TOL)
    _structural(run, example)


def _accuracy(run, example, values, pts, tol) -> None:
    from lkverify.linear.family import NODES, linear_family

    print(f"\naccuracy on {len(pts)} points (b, h), differences of the abscissa against degree 40:")
    values = {k: v for k, v in values.items() if k != "tau"}
    fam = linear_family(run.system, example.equilibrium, values, grid=("b", "h", "tau"))
    for tau in (0.9, 3.0, 6.0):
        p = np.column_stack([pts, np.full(len(pts), tau)])
        ref = dataclasses.replace(fam, nodes=40).evaluate(p)
        row = [f"τ = {tau}: |α| ≥ {np.nanmin(np.abs(ref.abscissa)):.1e}"]
        for nodes in (6, 8, NODES, 2 * NODES):
            got = dataclasses.replace(fam, nodes=nodes).evaluate(p)
            raw = dataclasses.replace(fam, nodes=nodes, refine=0).evaluate(p)
            row.append(f"N = {nodes}: refined {np.nanmax(np.abs(got.abscissa - ref.abscissa)):.1e}, "
                       f"unrefined {np.nanmax(np.abs(raw.abscissa - ref.abscissa)):.1e}, "
                       f"{1000 * got.seconds / len(p):.1f} ms/pt")
        flips = int(np.sum(np.array(ref.verdict) != np.array(fam.evaluate(p).verdict)))
        print("  " + "; ".join(row) + f"; verdicts differing from N = 40: {flips}")


def _structural(run, example) -> None:
    from lkverify import Equation, Parameters, System, Term, Vector, t
    from lkverify.linear.family import linear_family

    print("\nstructural zeros, structural flag off (the abscissa should be 0):")
    r = sympy.Matrix([1, sympy.sqrt(2), 0]) / sympy.sqrt(3)
    h = sympy.Symbol("h")
    fam = linear_family(run.system, {"omega": [0, 0, 0], "s": r},
                        {"mu": 2, "r": r, "F": sympy.ImmutableMatrix(sympy.diag(h, h, h))}, grid=("b", "h"),
                        coordinates="orthonormal")
    pts = np.array([[b, hh] for b in (-3, -1, 1, 3) for hh in (0.1, 0.7, 2.0)])
    got = dataclasses.replace(fam, structural_zero=False).evaluate(pts)
    print(f"  paper 002, μ = 2, r = (1, √2, 0)/√3, orthonormal tangent basis: max |α| = "
          f"{np.max(np.abs(got.abscissa)):.1e} (structural flag at construction: {fam.structural_zero})")
    P = Parameters()
    c = P.scalar("c", default=1)
    x = Vector("x", 2)
    th = sympy.Rational(3, 7)
    S = sympy.Matrix([[sympy.cos(th), -sympy.sin(th)], [sympy.sin(th), sympy.cos(th)]])
    J = sympy.Matrix([[0, c], [0, 0]])
    M = S * J * S.T                                         # a rotated Jordan block: λ = 0 twice, defective
    sys = System([Equation(x, [Term(M * sympy.Matrix([x(t)[0], x(t)[1]]))])], parameters=P, name="jordan")
    fam = linear_family(sys, {"x": [0, 0]}, grid=("c",))
    got = dataclasses.replace(fam, structural_zero=False).evaluate([[0.5], [1.0], [3.0]])
    print(f"  defective double zero (rotated Jordan block, c ∈ {{0.5, 1, 3}}): |α| = "
          f"{', '.join(f'{a:.1e}' for a in np.abs(got.abscissa))}; verdicts {got.verdict}")


if __name__ == "__main__":
    main()
