"""The V̇ bound with c5 … c10 of the proof of Theorem 1 of paper 000, as a bound step.

After functional (9) the paper prints V̇ along (2), (7) and bounds it:

    V̇ ≤ (c5 − γc6)‖ω‖² − c7 f^ν‖L‖² + γc8‖ω‖(‖s1(t−τ) − r1‖^{2ν+1} + ‖s2(t−τ) − r2‖^{2ν+1})
        + c9‖ω‖²(‖s1 − r1‖ + ‖s2 − r2‖) + c10‖ω‖∫(‖s1(ξ) − r1‖^{2ν+1} + ‖s2(ξ) − r2‖^{2ν+1})dξ
        − λ∫W + (λτ + μ)W − μW(t − τ),        c5, …, c10 > 0.

The printed V̇ itself has the sign of γf^ν(t−τ)ωᵀL(t−τ) wrong (:mod:`.theorem1`); the
bound bounds that term by its absolute value, so it holds for the exact V̇.  Here the
exact V̇ is the structured form ``Vdot_structured`` (the printed terms with the sign
corrected and the term (α1(ω×s1)×r1 + α2(ω×s2)×r2)ᵀD⁻¹(∫f^νL − Θω) split in two),
proved equal to the derivative; the printed bound is then proved as printed, term by
term, with

    c6 = λ_min(D), c7 = λ_min(D⁻¹), c5 = ‖D⁻¹‖‖Θ‖(α1 + α2), c9 = ‖D⁻¹‖‖Θ‖max(α1, α2),
    c8 = sup f^ν(α1x1 + α2x2)/(x1^{2ν+1} + x2^{2ν+1}) (certified, homogeneity),
    c10 = ‖D⁻¹‖(α1 + α2)·κ with κ the same supremum inside the integral (certified).
"""

import sympy

from lkverify import Check, DerivativeClaim, Result, Status, Term, cross, dot, quad, t, window_integral, xi
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import norm_measure, window_integral_measure
from lkverify.certify.steps.rules import (CauchySchwarz, Equal, Homogeneous, Rayleigh, crossed, integral_of, mapped,
                                          measured, scaled, summed, unit)
from lkverify.declare.rigidbody import restoring_torque_rate

from .equations import (PAPER, P, D, D_inv, L, Theta, W, alpha1, alpha2, f, gamma, lam, mu, nu, omega, r1, r2, s1, s2,
                        system, tau)
from .functional9 import functional, int_fL

__all__ = ["structured_Vdot", "derivation", "printed_bound", "theorem1_bound",
           # the norm trees and constants the proof's chain (theorem1_chain) reuses
           "L_norm_tree", "M_norm_tree", "Theta_w_tree", "dinv", "eig_of", "f_of", "memory_pointwise"]

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (alpha1, alpha2))  # α1(ω×s1)×r1 + α2(ω×s2)×r2 = −L̇

# V̇ along (2), (7): the printed terms, the sign of the delayed term corrected, the M-term split
structured_Vdot = [
    Term(-gamma * quad(omega(t), D), text="−γωᵀDω"),
    Term(-f(t) ** nu * quad(L(t), D_inv), text="−f^ν LᵀD⁻¹L"),
    Term(-quad(L(t), D_inv, cross(omega(t), Theta * omega(t))), text="−LᵀD⁻¹(ω×(Θω))"),
    Term(-gamma * f(t - tau) ** nu * dot(omega(t), L(t - tau)), text="−γf^ν(t−τ)ωᵀL(t−τ)"),
    Term(quad(M, D_inv, int_fL), text="MᵀD⁻¹∫f^νL dξ"),
    Term(-quad(M, D_inv * Theta, omega(t)), text="−MᵀD⁻¹Θω"),
    Term(-lam * window_integral(W(xi), tau), text="−λ∫W dξ"),
    Term((lam * tau + mu) * W(t), text="(λτ+μ)W"),
    Term(-mu * W(t - tau), text="−μW(t−τ)"),
]
derivation = DerivativeClaim("Vdot_structured", functional, system, structured_Vdot,
                             description="V̇ along (2),(7): the printed V̇ with the sign of γf^ν(t−τ)ωᵀL(t−τ) corrected")

K = 2 * nu + 1
w_, e1_, e2_ = norm_measure("w", omega(t), text="‖ω(t)‖"), norm_measure("e1", s1(t) - r1), norm_measure("e2", s2(t) - r2)
d1_, d2_ = norm_measure("d1", s1(t - tau) - r1), norm_measure("d2", s2(t - tau) - r2)
l_ = norm_measure("l", L(t), text="‖L(t)‖")
K1, K2 = (window_integral_measure(n, v, p=K, window=tau) for n, v in (("K1", s1(xi) - r1), ("K2", s2(xi) - r2)))
I1, I2 = (window_integral_measure(n, v, p=K + 1, window=tau) for n, v in (("I1", s1(xi) - r1), ("I2", s2(xi) - r2)))
MEASURES = (w_, e1_, e2_, d1_, d2_, l_, K1, K2, I1, I2)
w, e1, e2, d1, d2, l, k1, k2, i1, i2 = (m.symbol for m in MEASURES)

c5, c6, c7, c8, c9, c10p, Dinv_norm, Th_norm = sympy.symbols("c5 c6 c7 c8 c9 c10p Dinv_norm Theta_norm", positive=True)


def eig_of(name, which, inverse=False):
    def value(v):
        ev = sympy.Matrix(v[name]).eigenvals(multiple=True)
        x = min(ev) if which == "min" else max(ev)
        return 1 / x if inverse else x
    return value


def _c5(v):
    return eig_of("D", "min", True)(v) * eig_of("Theta", "max")(v) * (v["alpha1"] + v["alpha2"])


def _c9(v):
    return eig_of("D", "min", True)(v) * eig_of("Theta", "max")(v) * sympy.Max(v["alpha1"], v["alpha2"])


DEFINITIONS = {c6: eig_of("D", "min"), c7: eig_of("D", "max", True), Dinv_norm: eig_of("D", "min", True),
               Th_norm: eig_of("Theta", "max"), c5: _c5, c9: _c9}


def f_of(x1, x2):
    return ((alpha1 * x1**2 + alpha2 * x2**2) / 2) ** nu


def L_norm_tree(m1, m2):
    return summed(scaled(alpha1, crossed(measured(m1), unit(r1))), scaled(alpha2, crossed(measured(m2), unit(r2))))


M_norm_tree = summed(scaled(alpha1, crossed(crossed(measured(w_), unit(s1(t))), unit(r1))),
                 scaled(alpha2, crossed(crossed(measured(w_), unit(s2(t))), unit(r2))))
Theta_w_tree = mapped(Theta, measured(w_), lambda ctx: max(sympy.Matrix(ctx.at(Theta)).eigenvals(multiple=True)))
_P1, _P2 = K1.pointwise_symbol, K2.pointwise_symbol  # ‖s_i(ξ) − r_i‖ inside the integral
memory_pointwise = scaled(f_of(_P1, _P2), summed(scaled(alpha1, crossed(measured(K1, at=xi), unit(r1))),
                                         scaled(alpha2, crossed(measured(K2, at=xi), unit(r2)))))
dinv = lambda ctx: 1 / min(sympy.Matrix(ctx.at(D)).eigenvals(multiple=True))  # noqa: E731  ‖D⁻¹‖

BOUNDS = [
    TermBound("−γωᵀDω", -gamma * c6 * w**2, Rayleigh(omega(t), D, factor=-gamma, eigenvalue=eig_of("D", "min"),
                                                    norm_squared=w**2)),
    TermBound("−f^ν LᵀD⁻¹L", -c7 * f_of(e1, e2) * l**2,
              Rayleigh(L(t), D_inv, factor=-f_of(e1, e2), eigenvalue=eig_of("D", "max", True), norm_squared=l**2)),
    TermBound("−LᵀD⁻¹(ω×(Θω))", c9 * w**2 * (e1 + e2),
              CauchySchwarz(L(t), cross(omega(t), Theta * omega(t)), (L_norm_tree(e1_, e2_), crossed(measured(w_), Theta_w_tree)),
                            matrix=D_inv, factor=-1, operator_norm=dinv)),
    TermBound("−γf^ν(t−τ)ωᵀL(t−τ)", gamma * c8 * w * (d1**K + d2**K),
              CauchySchwarz(omega(t), L(t - tau), (measured(w_), L_norm_tree(d1_, d2_)), factor=-gamma * f_of(d1, d2)),
              then=(Homogeneous(("d1", "d2"), d1**K + d2**K, "c8", factor=gamma * w),)),
    TermBound("MᵀD⁻¹∫f^νL dξ", Dinv_norm * (alpha1 + alpha2) * c10p * w * (k1 + k2),
              CauchySchwarz(M, int_fL, (M_norm_tree, integral_of(memory_pointwise, measures=(K1, K2), power=K, constant="c10p")),
                            matrix=D_inv, operator_norm=dinv)),
    TermBound("−MᵀD⁻¹Θω", c5 * w**2,
              CauchySchwarz(M, Theta * omega(t), (M_norm_tree, Theta_w_tree), matrix=D_inv, factor=-1, operator_norm=dinv)),
    TermBound("−λ∫W dξ", -lam * (i1 + i2), Equal(-lam * (i1 + i2))),
    TermBound("(λτ+μ)W", (lam * tau + mu) * (e1 ** (K + 1) + e2 ** (K + 1)),
              Equal((lam * tau + mu) * (e1 ** (K + 1) + e2 ** (K + 1)))),
    TermBound("−μW(t−τ)", -mu * (d1 ** (K + 1) + d2 ** (K + 1)), Equal(-mu * (d1 ** (K + 1) + d2 ** (K + 1)))),
]

#: the printed right-hand side, with c10 = ‖D⁻¹‖(α1 + α2)κ
PRINTED_RHS = ((c5 - gamma * c6) * w**2 - c7 * f_of(e1, e2) * l**2 + gamma * c8 * w * (d1**K + d2**K)
               + c9 * w**2 * (e1 + e2) + Dinv_norm * (alpha1 + alpha2) * c10p * w * (k1 + k2) - lam * (i1 + i2)
               + (lam * tau + mu) * (e1 ** (K + 1) + e2 ** (K + 1)) - mu * (d1 ** (K + 1) + d2 ** (K + 1)))

printed_bound = TermwiseBound("printed V̇ bound with c5…c10", functional, system, "Vdot", BOUNDS, PRINTED_RHS, MEASURES,
                              derivation=derivation, definitions=DEFINITIONS)


def _steps(values):
    sub = P.substitution(values)
    res = derivation.check(sub, values=values, budget=120)
    rows = [Result("identity", derivation.name, res.status, res.to_json(), f"{derivation.description}: {res.detail}")]
    if res.status.is_proof:
        rows += printed_bound.check(values).results()
    else:
        rows.append(Result("bound", printed_bound.name, Status.UNDECIDED, None,
                           "not checked: its left-hand side, the structured V̇, is not proved"))
    return rows


theorem1_bound = Check("theorem1_bound", parameters=P, checks=[_steps], paper=PAPER,
                       relevant=("Theta", "D", "alpha1", "alpha2", "nu", "tau", "r1", "r2"),
                       title="Theorem 1: the printed V̇ bound with c5…c10, term by term on the exact V̇")
