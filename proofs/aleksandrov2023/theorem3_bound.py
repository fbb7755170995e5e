"""Audit of the proof of Theorem 3 of paper 002: the printed bound on V̇, as a bound step.

The paper prints, among the estimates after the functional,

    V̇ ≤ … + b(λ + c7τ)‖ω(t)‖ ∫_{t−τ}^t ‖s(ξ) − r‖^μ dξ + …,     c_k > 0.

The exact V̇ (:mod:`.theorem3`, claim ``Vdot_structured``) has exactly two terms with ω
and the history: λbωᵀJ and −b((ω×s)×r)ᵀF⁻¹K.  The printed step bounds them by
b(λ + c7τ)‖ω‖∫‖s − r‖^μ — for b < 0 (Remark 3, the section 6 data) a quantity ≤ 0, so
it claims the two terms are ≤ 0 whatever the history.  Stated as printed (``c7`` only
claimed to exist, λ any positive value), the step is refuted by the generic witness
search; with |b| in place of b it is proved beside it by Cauchy–Schwarz, ‖a × b‖ ≤
‖a‖‖b‖ and a bound on the weight ξ + τ − t ≤ τ, with c7 = ‖F⁻¹‖.
"""

import sympy

from lkverify import Check, t, xi
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure
from lkverify.certify.steps.rules import CauchySchwarz, Printed, crossed, integral_of, measured, scaled, unit

from .equations import PAPER, P, F, F_inv, J, K, b, lam, mu, n, omega, r, s, system, tau
from .theorem3 import derivation, functional

__all__ = ["printed", "corrected", "theorem3_bound"]

W_ = norm_measure("w", omega(t), text="‖ω(t)‖")
I_ = window_integral_measure("I", s(xi) - r, p=mu, window=tau, text="∫‖s(ξ) − r‖^μ dξ")
SUP_ = sup_norm("m", s(xi) - r, window=tau, text="max_{[t−τ,t]} ‖s(ξ) − r‖")
w, I = W_.symbol, I_.symbol
c7 = sympy.Symbol("c7", positive=True)
#: the printed estimates hold "for ‖s_t − r‖_τ + ‖ω(t)‖ < δ": any small region will do for the refutation
REGION = Region({SUP_: sympy.Rational(1, 10), W_: sympy.Rational(1, 10)})

OMEGA_HISTORY = ("λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ", "−b((ω×s)×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ")

printed = TermwiseBound(
    "printed V̇ bound: the ω–history terms ≤ b(λ + c7τ)‖ω‖∫‖s−r‖^μ", functional, system, "Vdot",
    [TermBound(OMEGA_HISTORY, b * (lam + c7 * tau) * w * I, Printed("the V̇ estimate after the functional"))],
    b * (lam + c7 * tau) * w * I, (W_, I_), region=REGION, derivation=derivation, part=OMEGA_HISTORY,
    exists=(c7,), witness_seconds=20.0)

_pointwise = scaled(n(xi), crossed(measured(I_, at=xi), unit(r)))  # ‖n(ξ) s(ξ)×r‖ ≤ ‖s(ξ) − r‖^μ


def _finv_norm(ctx):
    return 1 / min(sympy.Matrix(ctx.at(F)).eigenvals(multiple=True))


Finv_norm = sympy.Symbol("Finv_norm", positive=True)

corrected = TermwiseBound(
    "corrected: the ω–history terms ≤ |b|(λ + ‖F⁻¹‖τ)‖ω‖∫‖s−r‖^μ", functional, system, "Vdot",
    [TermBound(OMEGA_HISTORY[0], lam * abs(b) * w * I,
               CauchySchwarz(omega(t), J, (measured(W_), integral_of(_pointwise, measure=I_, power=mu)),
                             factor=lam * b)),
     TermBound(OMEGA_HISTORY[1], abs(b) * Finv_norm * tau * w * I,
               CauchySchwarz(omega(t).cross(s(t)).cross(r), K,
                             (crossed(crossed(measured(W_), unit(s(t))), unit(r)),
                              integral_of(_pointwise, measure=I_, power=mu, weight=xi + tau - t)),
                             matrix=F_inv, factor=-b, operator_norm=_finv_norm))],
    abs(b) * (lam + Finv_norm * tau) * w * I, (W_, I_), region=REGION, derivation=derivation, part=OMEGA_HISTORY,
    definitions={Finv_norm: lambda v: 1 / min(sympy.Matrix(v["F"]).eigenvals(multiple=True))})


def _steps(values):
    out = []
    for step in (printed, corrected):
        out += step.check(values).results()
    return out


theorem3_bound = Check("theorem3_bound", parameters=P, checks=[_steps], paper=PAPER,
                       relevant=("Theta", "F", "a", "b", "tau", "mu", "r"),
                       title="The printed V̇ bound of Theorem 3's proof: b(λ+c7τ)‖ω‖∫‖s−r‖^μ, as printed and corrected")
