"""Audit of the proof of Theorem 1 of paper 001: the printed h^{ν−1}ḣ term of the V̇ bound.

The paper bounds the exact V̇ (the printed V̇ of :mod:`.theorem1`, checked against the
derivation) by

    V̇ ≤ … + γα6(‖s1 − r1‖ + ‖s2 − r2‖)(h^{ν−1}(t)ḣ(t)‖ω‖ + h^ν‖ω‖² + h^{ν+1}‖ω‖),   α6 > 0.

Its first piece bounds the term γνh^{ν−1}ḣ ωᵀJη of V̇.  Conditions (5), (10), (11) let h
decrease (the section 6 example h = (1+t)^{−7/8} does), so ḣ < 0 and the printed piece
is ≤ 0 while the term takes both signs: refuted by a witness at t = 1.  With |ḣ| it
holds: Cauchy–Schwarz with ‖J‖ (the largest moment of inertia), the triangle inequality
and ‖s×r‖ ≤ ‖s − r‖, for every t.
"""

import sympy

from lkverify import Check, Result, t, xi
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import attitude_measures
from lkverify.certify.steps.rules import CauchySchwarz, crossed, measured, scaled, summed, unit

from .equations import PAPER, P, J, a1, a2, eta, gamma, h, nu, omega, r1, r2, s1, s2, system
from .theorem1 import theorem1

__all__ = ["corrected", "printed", "theorem1_bound", "WITNESS_TIME"]

#: the printed bound is claimed for every t ≥ 0; the witness is sought at this time
WITNESS_TIME = 1
LABEL = "γνh^{ν−1}ḣ ωᵀJη"
_derivation = next(c for c in theorem1.claims if c.name == "Vdot_printed")

(W_, E1, E2), REGION = attitude_measures(omega, (s1, s2), (r1, r2), bound=sympy.Rational(1, 5))
w, e1, e2 = W_.symbol, E1.symbol, E2.symbol
alpha6 = sympy.Symbol("alpha6", positive=True)
h_dot = h(t).diff(t)
J_norm = sympy.Symbol("J_norm", positive=True)

_eta_norm = summed(scaled(a1, crossed(measured(E1), unit(r1))), scaled(a2, crossed(measured(E2), unit(r2))))


def _j_norm(ctx):
    return max(sympy.Matrix(ctx.at(J)).eigenvals(multiple=True))


#: Cauchy–Schwarz with ‖J‖, the triangle inequality and ‖s×r‖ ≤ ‖s − r‖
_RULE = CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, factor=gamma * nu * h(t) ** (nu - 1) * h_dot,
                      operator_norm=_j_norm)
_alpha6 = {alpha6: lambda v: v["nu"] * max(sympy.Matrix(v["J"]).eigenvals(multiple=True)) * sympy.Max(v["a1"], v["a2"])}

# As printed, with α6 = ν‖J‖max(a1, a2): the rule's bound has |ḣ|, so the step is proved where ḣ ≥ 0 and
# refuted (for every α6 ≥ 0) at a time where h decreases.
printed = TermwiseBound(
    "printed V̇ bound of Theorem 1: γνh^{ν−1}ḣωᵀJη ≤ γα6(‖s1−r1‖ + ‖s2−r2‖)h^{ν−1}ḣ‖ω‖", None, system, "Vdot",
    [TermBound(LABEL, gamma * alpha6 * (e1 + e2) * h(t) ** (nu - 1) * h_dot * w, _RULE)],
    gamma * alpha6 * (e1 + e2) * h(t) ** (nu - 1) * h_dot * w, (W_, E1, E2), region=REGION, derivation=_derivation,
    part=(LABEL,), exists=(alpha6,), definitions=_alpha6, witness_time=WITNESS_TIME, witness_seconds=20.0)

corrected = TermwiseBound(
    "corrected: γνh^{ν−1}ḣωᵀJη ≤ γνh^{ν−1}|ḣ|‖J‖‖ω‖(a1‖s1−r1‖ + a2‖s2−r2‖)", None, system, "Vdot",
    [TermBound(LABEL, gamma * nu * h(t) ** (nu - 1) * sympy.Abs(h_dot) * J_norm * w * (a1 * e1 + a2 * e2), _RULE)],
    gamma * nu * h(t) ** (nu - 1) * sympy.Abs(h_dot) * J_norm * w * (a1 * e1 + a2 * e2), (W_, E1, E2), region=REGION,
    derivation=_derivation, part=(LABEL,),
    definitions={J_norm: lambda v: max(sympy.Matrix(v["J"]).eigenvals(multiple=True))})


def _steps(values):
    out = []
    for step in (printed, corrected):
        out += step.check(values).results()
    return out


theorem1_bound = Check("theorem1_bound", parameters=P, checks=[_steps], paper=PAPER,
                       relevant=("J", "D", "a1", "a2", "h", "nu", "r1", "r2"),
                       title="The printed h^{ν−1}ḣ term of Theorem 1's V̇ bound (h decreasing), as printed and corrected")
