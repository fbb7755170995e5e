"""Benchmark: the three template constants of aleksandrov2023.theorem3 (κ1, c_A, c_B) per enclosure strategy.

Run:  python3 benchmarks/bench_templates.py [--enclosure mean-value taylor] [--rel-gap 5e-3]
                                            [--boxes 40000] [--seconds 60] [--full-sphere]

Each constant is a supremum over a chart (:func:`lkverify.certify.bounds.sup_bound`): s on the cap
ρ ≤ 1/2 around r (:func:`~lkverify.certify.bounds.unit_vector_near`, ψ ∈ [0, 2π]) and a unit ω
(:func:`~lkverify.certify.bounds.unit_vector_angles`), at the section-6 values Θ = diag(5, 6, 4),
F = I, r = (1, 1, 1)/√3 (the defaults of ``proofs/aleksandrov2023/equations.py``):

    κ1  = sup (q/e)ᵀF⁻¹Θω,          ω on the sphere (= sup of |·|: ω → −ω flips the sign)
    c_A = sup −((ω×s)×r)ᵀF⁻¹Θω,     ω on the upper hemisphere θ ≤ π/2 (the form is even in ω)
    c_B = sup (q/e)ᵀF⁻¹(ω×Θω),      ω on the upper hemisphere (= sup of |·|: ψ → ψ + π flips q)

with q/e = cos(ρ/2) n×r = (s×r)/‖s − r‖ without the removable singularity, n the cap's direction.

The expressions are built here, independently of the proof module.  ``--full-sphere`` adds c_A
and c_B with ω on the whole sphere θ ∈ [0, π] (twice the work: both maximisers ±ω), as a
template rule that does not use the evenness in ω bounds them.  The defaults are those of the
``constants`` job (:class:`lkverify.certify.constants.ConstantsTuning`: accuracy, box budget); the
strategies compared default to ``mean-value`` (the strategy the templates used before the Taylor
forms) and ``taylor``.  For each constant and strategy it prints the estimate, the certified upper bound, the
relative gap (certified − proved lower)/lower, the status, the boxes and the wall-clock seconds
(estimate, compilation and branch and bound).  Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import sympy

from lkverify.certify.bounds import sup_bound, unit_vector_angles, unit_vector_near
from lkverify.certify.constants import ConstantsTuning
from lkverify.options import Accuracy, Budget

RHO_CAP = sympy.Rational(1, 2)


def templates(full_sphere: bool = False) -> list:
    """(name, expression, box) of κ1, c_A and c_B at the section-6 parameters (and c_A, c_B on S²)."""
    rho, psi, theta, phi = sympy.symbols("rho psi theta phi", real=True)
    Theta = sympy.diag(5, 6, 4)
    F = sympy.eye(3)
    r = sympy.Matrix([1, 1, 1]) / sympy.sqrt(3)
    cap = unit_vector_near(r, rho_max=RHO_CAP, rho=rho, psi=psi)
    sphere = unit_vector_angles(theta, phi)
    s, w = cap.value, sphere.value
    n = sympy.cos(psi) * cap.extras["e1"] + sympy.sin(psi) * cap.extras["e2"]
    q_over_e = sympy.cos(rho / 2) * n.cross(r)          # (s × r)/‖s − r‖ without the removable singularity
    Finv = F.inv()
    box = {**cap.region, **sphere.region}
    box_even = {**box, theta: (0, sympy.pi / 2)}
    kappa1 = (q_over_e.T * Finv * Theta * w)[0]
    c_A = -(w.cross(s).cross(r).T * Finv * Theta * w)[0]
    c_B = (q_over_e.T * Finv * w.cross(Theta * w))[0]
    out = [("kappa1", kappa1, box), ("c_A", c_A, box_even), ("c_B", c_B, box_even)]
    if full_sphere:
        out += [("c_A·S²", c_A, box), ("c_B·S²", c_B, box)]
    return out


def main(argv=None) -> None:
    tune = ConstantsTuning()
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--enclosure", nargs="+", default=["mean-value", "taylor"],
                    help="strategies to compare (names of lkverify.certify.engine.ENCLOSURES)")
    ap.add_argument("--rel-gap", type=float, default=tune.template_accuracy.rel_gap)
    ap.add_argument("--boxes", type=int, default=tune.template_boxes)
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--full-sphere", action="store_true", help="also c_A and c_B with ω on the whole sphere")
    args = ap.parse_args(argv)
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}; "
          f"rel_gap {args.rel_gap:g}, {args.boxes} boxes, {args.seconds:g} s per constant "
          f"(ConstantsTuning.template_enclosure = {tune.template_enclosure!r})")
    print(f"{'constant':8s} {'enclosure':11s} {'estimate':>10s} {'certified':>10s} {'rel.gap':>8s} "
          f"{'status':10s} {'boxes':>7s} {'seconds':>8s}")
    for name, expr, box in templates(args.full_sphere):
        for enc in args.enclosure:
            t0 = time.perf_counter()
            res = sup_bound(expr, box, accuracy=Accuracy(rel_gap=args.rel_gap),
                            budget=Budget(seconds=args.seconds, boxes=args.boxes), enclosure=enc)
            seconds = time.perf_counter() - t0
            print(f"{name:8s} {enc:11s} {res.estimate:10.6g} {res.certified:10.6g} {res.gap:8.2%} "
                  f"{res.status.value:10s} {res.boxes:7d} {seconds:8.2f}")


if __name__ == "__main__":
    main()
