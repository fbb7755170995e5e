"""Audit of the proof of Theorem 2 of paper 000: the printed γβc7 term of the V̇ bound.

For functional (14) along (2), (13) the paper prints the estimate

    V̇ ≤ … + γβc7‖ω(t)‖(‖s1(t) − r1‖^{2ν+1} + ‖s2(t) − r2‖^{2ν+1}) + …,     c7 > 0.

The only term of V̇ with γβ is the one the proportional torque −βf^νL of (13) puts into
d/dt (γ/2)ωᵀΘω: −γβ f^ν ωᵀL (derived below with
:func:`~lkverify.symbolic.derivative.derivative_along`, not retyped).  Remark 3 allows
β ≤ 0 — the point of Theorem 2 — and then the printed bound is ≤ 0 while −γβf^νωᵀL
takes both signs: the step is refuted by a witness inside the hypotheses (β = −1 with the
kernel G = 3e^{−2ζ}I, so β + ∫G = 1/2 > 0, Assumption 2).  For β ≥ 0 the printed step is
proved as printed by the same rules.  With |β| it holds for every β:
Cauchy–Schwarz, the triangle inequality and ‖s×r‖ ≤ ‖s − r‖ give
γ|β|f^ν‖ω‖(α1‖s1 − r1‖ + α2‖s2 − r2‖), and homogeneity of degree 2ν + 1 in the two
distances with a certified supremum on the quarter circle gives c7.
"""

import sympy

from lkverify import Check, Functional, Result, Status, Term, quad, t, xi
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import attitude_measures
from lkverify.certify.steps.rules import CauchySchwarz, Homogeneous, crossed, measured, scaled, summed, unit
from lkverify.symbolic.derivative import derivative_along

from .equations import PAPER, P, L, Theta, alpha1, alpha2, beta, f, gamma, nu, omega, r1, r2, s1, s2, system_pid
from .theorem2 import theorem2

__all__ = ["REMARK3", "beta_term", "corrected", "printed", "theorem2_bound"]

#: a point of Remark 3 (β ≤ 0) inside Assumption 2: β = −1, G = 3e^{−2ζ}I, β + ∫G = 1/2 > 0
REMARK3 = {"beta": "-1", "g": "3*exp(-2*zeta)"}

(W_, E1, E2), REGION = attitude_measures(omega, (s1, s2), (r1, r2), bound=sympy.Rational(1, 5))
w, e1, e2 = W_.symbol, E1.symbol, E2.symbol
c7 = sympy.Symbol("c7", positive=True)


def _beta_term():
    """−γβf^νωᵀL: the γβ-part of d/dt (γ/2)ωᵀΘω along (2), (13), from the derivation."""
    d = sympy.expand(derivative_along(Functional([Term(gamma / 2 * quad(omega(t), Theta))]), system_pid).expr)
    part = sympy.expand(gamma * beta * d.coeff(gamma).coeff(beta))
    return Term(part, text="−γβf^ν ωᵀL (from (γ/2)ωᵀΘω)")


beta_term = _beta_term()
LABEL = beta_term.text
POWER = 2 * nu + 1
TEMPLATE = e1**POWER + e2**POWER
_f_in_measures = ((alpha1 * e1**2 + alpha2 * e2**2) / 2) ** nu  # f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²)
_L_norm = summed(scaled(alpha1, crossed(measured(E1), unit(r1))), scaled(alpha2, crossed(measured(E2), unit(r2))))

#: the rules that bound the term: Cauchy–Schwarz, the triangle inequality, ‖s×r‖ ≤ ‖s − r‖, then homogeneity
_RULE = CauchySchwarz(omega(t), L(t), (measured(W_), _L_norm), factor=-gamma * beta * _f_in_measures)
_THEN = (Homogeneous(("e1", "e2"), TEMPLATE, "c7", factor=gamma * abs(beta) * w),)

# As printed: proved by the rules when β ≥ 0 (then β = |β|); for β < 0 the stated bound is not the rules',
# and the witness search refutes it for every c7 ≥ 0 (c7 only claimed to exist).
printed = TermwiseBound(
    "printed V̇ bound of Theorem 2: −γβf^νωᵀL ≤ γβc7‖ω‖(‖s1−r1‖^{2ν+1} + ‖s2−r2‖^{2ν+1})", None, system_pid, "terms",
    [TermBound(LABEL, gamma * beta * c7 * w * TEMPLATE, _RULE, then=_THEN)],
    gamma * beta * c7 * w * TEMPLATE, (W_, E1, E2), region=REGION, terms=(beta_term,), exists=(c7,),
    witness_seconds=20.0)

corrected = TermwiseBound(
    "corrected: −γβf^νωᵀL ≤ γ|β|c7‖ω‖(‖s1−r1‖^{2ν+1} + ‖s2−r2‖^{2ν+1})", None, system_pid, "terms",
    [TermBound(LABEL, gamma * abs(beta) * c7 * w * TEMPLATE, _RULE, then=_THEN)],
    gamma * abs(beta) * c7 * w * TEMPLATE, (W_, E1, E2), region=REGION, terms=(beta_term,))


def _at(values, label):
    rows = []
    for step in (printed, corrected):
        for r in step.check(values).results():
            rows.append(Result(r.kind, f"{r.name} [{label}]", r.status, r.value, r.detail))
    return rows


def _steps(values):
    """The printed and corrected steps at the given values, and at Remark 3's β = −1 when β ≥ 0 there."""
    rows = _at(values, f"β = {values['beta']}")
    if not values["beta"] < 0:
        at = P.resolve(REMARK3, use_defaults=True)
        hyp = theorem2.run(REMARK3)
        ok = all(r.status.is_proof for r in hyp.results if r.kind == "hypothesis")
        rows.append(Result("hypothesis", "Remark 3 point inside Assumption 2 (β = −1, G = 3e^{−2ζ}I)",
                           Status.EXACT if ok else Status.FAILED, None,
                           "; ".join(f"{r.name}: {r.status}" for r in hyp.results if r.kind == "hypothesis")))
        rows += _at(at, "Remark 3: β = −1, G = 3e^{−2ζ}I")
    return rows


theorem2_bound = Check("theorem2_bound", parameters=P, checks=[_steps], paper=PAPER,
                       relevant=("Theta", "D", "alpha1", "alpha2", "nu", "beta", "g", "r1", "r2"),
                       title="The printed γβc7 term of Theorem 2's V̇ bound (β ≤ 0 allowed), as printed and corrected")
