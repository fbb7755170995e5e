"""Persistent excitation (3.5) of paper 004 along the programmed motion, certified.

    (3.5)  β1 I ≤ ∫_t^{t+δ} φᵀ(τ)φ(τ) dτ ≤ β2 I   for every t ≥ 0,     φ̇ = −λ_cφ + Y_cᵀ (3.2).

On the programmed motion (ω = ω_d, sᵢ = cᵢ: e = 0, v = 0, ω_r = ω_d, ω̇_c = ω̇_d) the filter is driven by
Y_c = Y(ω_d, ω_d, ω̇_d) — obtained here from the symbolic Y_c of (3.3) by that substitution, never
retyped.  For the catalogued ω_d(t) (sines and cosines of rational multiples of t) Y_c is a
trigonometric polynomial, so φ from φ(0) = 0 and the Gram matrix of every window are exact
exponential polynomials, and β1, β2 are certified for every t ≥ 0 by
:func:`lkverify.certify.excitation.excitation_bounds` (arb balls, subdivision, Weyl's inequality; no
integrator).  The same for φφᵀ, the p × p matrix the parameter error sees.  A constant ω_d along
one axis (``--set wd1=1/2 --set wd2=0 --set wd3=0``) gives Y_c with a zero column: no excitation,
refuted at an exact window (failed).  A claimed β1 above the true one is refuted at an exact window
and vector by :func:`claimed_results`.
"""

from __future__ import annotations

import sympy

from lkverify import Check, Result, Status, t
from lkverify.certify.excitation import excitation_bounds as certified_bounds, filter_gram, refute_claim

from .equations import PAPER, P, Y_c, c1, c2, c3, omega, s1, s2, s3, wd

__all__ = ["excitation", "excitation_bounds", "reference_regressor", "claimed_results"]

_GRAMS = (("φᵀφ", False), ("φφᵀ", True))


def reference_regressor(values) -> sympy.Matrix:
    """Y_c(t) on the programmed motion at the run's values (exact, a function of t)."""
    sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
    on_motion = {f(t): wd[i] for i, f in enumerate(omega.functions)}
    for s, c in ((s1, c1), (s2, c2), (s3, c3)):
        on_motion.update({f(t): c[i] for i, f in enumerate(s.functions)})
    Yr = Y_c.xreplace(on_motion).xreplace(sub)
    coeffs = {sympy.Function(f"wd{i}", real=True): sympy.Lambda(t, sympy.sympify(values[f"wd{i}"])) for i in (1, 2, 3)}
    return Yr.subs(coeffs).doit()


def excitation_bounds(values) -> dict:
    """{"φᵀφ": ExcitationBounds, "φφᵀ": ExcitationBounds}: (3.5) certified along the programmed motion."""
    from lkverify.certify.excitation import ExcitationBounds
    from lkverify.errors import UnsupportedInput

    Yr = reference_regressor(values)
    out = {}
    for name, tr in _GRAMS:
        try:
            out[name] = certified_bounds(Yr, t, lam=values["lam_c"], delta=values["delta"], transpose=tr)
        except UnsupportedInput as exc:  # a valid ω_d the certification does not treat: not decided
            out[name] = ExcitationBounds(Status.UNDECIDED, None, None, float("nan"), float("nan"),
                                         f"not certified: {exc}")
    return out


def claimed_results(values, beta1=None, beta2=None, *, t0=None) -> list:
    """A claimed β1 (β2) of (3.5) for ∫φᵀφ refuted at an exact window t0 (default: the window of the sampled
    extreme), or not refuted there (``undecided``: one window proves nothing for all t)."""
    import numpy as np

    from lkverify.certify.excitation import _Gram

    Yr = reference_regressor(values)
    gram = _Gram(filter_gram(Yr, t, values["lam_c"]), values["delta"])
    out = []
    for beta, lower, label in ((beta1, True, "β1"), (beta2, False, "β2")):
        if beta is None:
            continue
        ts = np.linspace(0.0, 200.0, 8001)
        ev = np.linalg.eigvalsh(gram.floats(ts))
        k = int(np.argmin(ev[:, 0]) if lower else np.argmax(ev[:, -1]))
        at = sympy.Rational(t0) if t0 is not None else sympy.Rational(ts[k]).limit_denominator(1000)
        why = refute_claim(gram, at, sympy.Rational(beta), lower=lower)
        out.append(Result("constant", f"(3.5) claimed {label} = {beta}", Status.FAILED if why else Status.UNDECIDED,
                          {"claimed": str(beta), "t0": str(at)},
                          f"refuted: {why}" if why else f"not refuted at the window t0 = {at}"))
    return out


def _check(values):
    out = []
    for name, pe in excitation_bounds(values).items():
        out.append(Result("constant", f"(3.5) β1, β2 for ∫{name} over δ = {values['delta']}", pe.status,
                          {"beta1": pe.beta1, "beta2": pe.beta2, "beta1_sampled": pe.beta1_estimate,
                           "beta2_sampled": pe.beta2_estimate, "intervals": pe.intervals},
                          f"along ω = ω_d(t), sᵢ = cᵢ from φ(0) = 0: {pe.detail}"))
    return out


excitation = Check("excitation", parameters=P, checks=[_check], paper=PAPER,
                   relevant=("M", "Lam", "lam_c", "delta", "wd1", "wd2", "wd3"),
                   title="Persistent excitation (3.5): β1, β2 of the filter φ̇ = −λ_cφ + Y_cᵀ along the programmed "
                         "motion ω_d(t), certified for every t ≥ 0")
