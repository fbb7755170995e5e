"""The proof of Theorem 1 of paper 000 from functional (9) to its conclusion, as checked bound steps.

The paper proves Theorem 1 in four printed steps: two-sided bounds on V with c1 … c4, the
V̇ bound with c5 … c10 (:mod:`.theorem1_bound`), inequality (10) ‖L‖² ≥ ε(α1²‖s1−r1‖² +
α2²‖s2−r2‖²) near the target, and "using (10) and Jensen's inequality, for λ, μ, δ small
enough and γ large enough" the estimates (11), (12) on ‖s_{1t}−r1‖_τ + ‖s_{2t}−r2‖_τ < δ.
Here every one of those steps is a rule with checked side conditions, on the region

    ‖s_i(ξ) − r_i‖ ≤ δ for ξ ∈ [t − τ, t], i = 1, 2,

in the measures w = ‖ω(t)‖, e_i = ‖s_i(t) − r_i‖, d_i = ‖s_i(t−τ) − r_i‖, l = ‖L(t)‖,
K_i = ∫‖s_i(ξ)−r_i‖^{2ν+1}dξ, I_i = ∫‖s_i(ξ)−r_i‖^{2ν+2}dξ (k = 2ν+1, P = 2ν+2):

* V ≥ L: f exactly; (γ/2)ωᵀΘω ≥ (γ/2)θ_min w²; LᵀD⁻¹Θω ≥ −‖D⁻¹‖θ_max(α1e1 + α2e2)w, then
  Young (η_ω); the weighted integral ≥ μ(I1 + I2); −LᵀD⁻¹∫f^νL ≥ −‖D⁻¹‖c10′(α1e1 + α2e2)(K1 + K2)
  (c10′ the certified homogeneous supremum of :mod:`.theorem1_bound`), then Hölder on the
  window K_i ≤ τ^{1/P} I_i^{k/P} (the paper's "Jensen"), Young (η_K, exponents P and P/k)
  and e_i^P ≤ δ^{P−2}e_i² on the region.
* V ≤ U: the same terms bounded above (U has no constant term and nonnegative coefficients).
* V̇ ≤ W: the exact structured V̇ of :mod:`.theorem1_bound` term by term: the printed c5 … c10
  bounds, then (10) for l² (:func:`lemma10`, certified on the region), (ΣA_i)^ν ≥ A_i^ν,
  e_i ≤ δ in c9‖ω‖²(e1 + e2), Young (η) and d_i^{2k} ≤ δ^{2ν}d_i^P for the delayed term,
  Hölder, Young (η) and I_i^{2k/P} ≤ (τδ^P)^{2k/P−1} I_i for the memory term.

The conclusion (Krasovskii's theorem, [8, pp. 53, 54]) is then a sign condition on the
coefficients of L, U and W (:class:`~lkverify.certify.steps.chain.Krasovskii`).  The
choices γ, λ, μ, ε, δ and Young's η's are found at the run's gains by :func:`find_choices`
(floating point only picks them; every step is then proved at those exact values).

Over an interval of τ (``theorem1.run(box={"tau": (lo, hi)})``) the steps are proved with τ a
positive symbol; the choices at the interval's centre close the chain when they keep their
margin at its ends.  Every τ-dependent coefficient of L and W (through λτ + μ, τ^{1/P} and
(τδ^P)^{2k/P−1}) is worst at the upper end, so :func:`box_choices`, picked for both ends at
once, closes it on a whole interval: ``theorem1.run(box_choices(B), box=B)`` with
B = {"tau": ("1/10", "10")} is established in one piece.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy

from lkverify import Budget, Status, t, xi
from lkverify.certify.bounds import certify_positive
from lkverify.certify.steps.chain import Krasovskii, TermBound, collect_monomials, lyapunov_steps
from lkverify.certify.steps.measures import Region, sup_norm
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, PowerSplit, WindowHolder, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Condition, Equal, Homogeneous, Rayleigh, WindowWeight,
                                          crossed, integral_of, measured, scaled, summed, unit)

from .equations import (D, D_inv, L, Theta, alpha1, alpha2, delta, epsilon, eta, eta_K, eta_w, gamma, lam, mu, nu,
                        omega, r1, r2, s1, s2, system, tau)
from .functional9 import functional, int_fL
from .theorem1_bound import (MEASURES, M, L_norm_tree as _L_norm, M_norm_tree as _M_norm, Theta_w_tree as _Theta_w,
                             d1, d2, derivation, dinv as _dinv, e1, e2, eig_of as _eig, f_of as _f, i1, i2, k1, k2, l,
                             memory_pointwise as _pointwise, w)

__all__ = ["CONCLUSION", "REGION", "box_choices", "chain_steps", "find_choices", "lemma10", "optimal_choices",
           "steps"]

K = 2 * nu + 1  # k
Pw = 2 * nu + 2  # P
_by = {m.name: m for m in MEASURES}
SUP1, SUP2 = (sup_norm(f"m{k}", s(xi) - r, window=tau, text=f"max_{{[t−τ,t]}} ‖s{k}(ξ) − r{k}‖")
              for k, s, r in ((1, s1, r1), (2, s2, r2)))
REGION = Region({SUP1: delta, SUP2: delta})

theta_min, theta_max, c6, c7, Dinv_norm = sympy.symbols("theta_min theta_max c6 c7 Dinv_norm", positive=True)
c8, c10p = sympy.symbols("c8 c10p", positive=True)


DEFINITIONS = {theta_min: _eig("Theta", "min"), theta_max: _eig("Theta", "max"), c6: _eig("D", "min"),
               c7: _eig("D", "max", True), Dinv_norm: _eig("D", "min", True)}


# ---- (10): ‖L‖² ≥ ε(α1²‖s1−r1‖² + α2²‖s2−r2‖²) on the region --------------------------------
@functools.lru_cache(maxsize=64)
def _lemma10_certificate(eps, a1, a2, r1_, r2_, sigma_max, seconds):
    from ..aleksandrov2017.lemma1 import _U, _sig, lemma1_F

    F = lemma1_F(eps, a1, a2, sympy.Matrix(r1_), sympy.Matrix(r2_))
    return certify_positive(F, {_sig: (0, sigma_max), **_U.region}, name=f"F ≥ 0 for σ ≤ {sigma_max}",
                            budget=Budget(seconds=seconds))


def lemma10(ctx) -> Condition:
    """(10) on the region, certified: Lemma 1 of paper 001 (:mod:`lkverify.proofs.aleksandrov2017.lemma1`).

    With s_i = R r_i and σ = sin(φ/2) for the rotation angle φ, e1² + e2² ≥ 4σ² when r1 ⊥ r2,
    so on the region (e1² + e2² ≤ 2δ²) σ ≤ δ/√2; F(σ, u) ≥ 0 there for every axis u is (10)
    divided by σ².  Needs 0 < ε < 1 and orthonormal r1, r2 (declared).
    """
    eps = ctx.at(epsilon)
    if not (eps.is_Rational and 0 < eps < 1):
        return Condition("(10) on the region", Status.FAILED, f"(10) needs 0 < ε < 1, got ε = {eps}")
    b = ctx.at(ctx.region.bound_of(_by["e1"], ctx.sub)) if ctx.region is not None else None
    if b is None:
        return Condition("(10) on the region", Status.UNDECIDED, "the region does not bound ‖s_i − r_i‖")
    sigma_max = sympy.sympify(b) / sympy.sqrt(2)  # the region's exact bound (a Rational, or a float's binary value)
    sigma_max = sympy.Rational(sympy.ceiling(sympy.N(sigma_max, 30) * 10**12), 10**12)  # an upper rational bound
    chk = _lemma10_certificate(eps, ctx.at(alpha1), ctx.at(alpha2), tuple(ctx.values["r1"]), tuple(ctx.values["r2"]),
                               sigma_max, ctx.seconds_left(20.0))
    text = f"(10) with ε = {eps} on the region (Lemma 1: F ≥ 0 for σ ≤ {float(sigma_max):.4g}, every axis u)"
    status = Status.CERTIFIED if chk.status is Status.CERTIFIED else \
        Status.FAILED if chk.status is Status.FAILED else Status.UNDECIDED
    return Condition(text, status, f"{chk.boxes} boxes" if status is Status.CERTIFIED else chk.detail)


# ---- norm trees: those of theorem1_bound ---------------------------------------------------------
_memory = integral_of(_pointwise, measures=(_by["K1"], _by["K2"]), power=K, constant="c10p")
_tau_P = tau ** (1 / Pw)  # Hölder: ∫‖v‖^k ≤ τ^{1−k/P}(∫‖v‖^P)^{k/P}, 1 − k/P = 1/P
_Ik = [i ** (K / Pw) for i in (i1, i2)]


def _lower_bounds():
    q = Pw / K
    young_K = YoungEach(tuple((e, y, Pw, q, eta_K) for e in (e1, e2) for y in _Ik))
    cross = sum(a * e for a, e in ((alpha1, e1), (alpha2, e2)))
    return [
        TermBound("f", (alpha1 * e1**2 + alpha2 * e2**2) / 2, Equal((alpha1 * e1**2 + alpha2 * e2**2) / 2)),
        TermBound("(γ/2)ωᵀΘω", gamma / 2 * theta_min * w**2,
                  Rayleigh(omega(t), Theta, factor=gamma / 2, eigenvalue=_eig("Theta", "min"), norm_squared=w**2)),
        TermBound("LᵀD⁻¹Θω",
                  -Dinv_norm * theta_max * sum(a * (eta_w * e**2 / 2 + w**2 / (2 * eta_w))
                                               for a, e in ((alpha1, e1), (alpha2, e2))),
                  CauchySchwarz(L(t), Theta * omega(t), (_L_norm(_by["e1"], _by["e2"]), _Theta_w), matrix=D_inv,
                                operator_norm=_dinv),
                  then=(YoungEach(((e1, w, 2, 2, eta_w), (e2, w, 2, 2, eta_w))),)),
        TermBound("∫(λ(ξ+τ−t)+μ)‖s1−r1‖^{2ν+2}dξ", mu * i1, WindowWeight("I1", Pw, weight=lam * (xi + tau - t) + mu)),
        TermBound("∫(λ(ξ+τ−t)+μ)‖s2−r2‖^{2ν+2}dξ", mu * i2, WindowWeight("I2", Pw, weight=lam * (xi + tau - t) + mu)),
        TermBound("−LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ",
                  -Dinv_norm * c10p * _tau_P * sum(
                      a * (eta_K * delta ** (Pw - 2) * e**2 / Pw + eta_K ** (-q / Pw) * i / q)
                      for a, e in ((alpha1, e1), (alpha2, e2)) for i in (i1, i2)),
                  CauchySchwarz(L(t), int_fL, (_L_norm(_by["e1"], _by["e2"]), _memory), matrix=D_inv, factor=-1,
                                operator_norm=_dinv),
                  then=(WindowHolder("K1", "I1"), WindowHolder("K2", "I2"), young_K, OnRegion("e1", 2),
                        OnRegion("e2", 2))),
    ], cross


def _upper_bounds():
    cross = sum(a * e for a, e in ((alpha1, e1), (alpha2, e2)))
    return [
        TermBound("f", (alpha1 * e1**2 + alpha2 * e2**2) / 2, Equal((alpha1 * e1**2 + alpha2 * e2**2) / 2)),
        TermBound("(γ/2)ωᵀΘω", gamma / 2 * theta_max * w**2,
                  Rayleigh(omega(t), Theta, factor=gamma / 2, eigenvalue=_eig("Theta", "max"), norm_squared=w**2)),
        TermBound("LᵀD⁻¹Θω", Dinv_norm * theta_max * cross * w,
                  CauchySchwarz(L(t), Theta * omega(t), (_L_norm(_by["e1"], _by["e2"]), _Theta_w), matrix=D_inv,
                                operator_norm=_dinv)),
        TermBound("∫(λ(ξ+τ−t)+μ)‖s1−r1‖^{2ν+2}dξ", (lam * tau + mu) * i1,
                  WindowWeight("I1", Pw, weight=lam * (xi + tau - t) + mu)),
        TermBound("∫(λ(ξ+τ−t)+μ)‖s2−r2‖^{2ν+2}dξ", (lam * tau + mu) * i2,
                  WindowWeight("I2", Pw, weight=lam * (xi + tau - t) + mu)),
        TermBound("−LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ", Dinv_norm * c10p * cross * (k1 + k2),
                  CauchySchwarz(L(t), int_fL, (_L_norm(_by["e1"], _by["e2"]), _memory), matrix=D_inv, factor=-1,
                                operator_norm=_dinv)),
    ]


def _vdot_bounds():
    a = (alpha1, alpha2)
    delayed_L = summed(scaled(alpha1, crossed(measured(_by["d1"]), unit(r1))),
                       scaled(alpha2, crossed(measured(_by["d2"]), unit(r2))))
    ten = LowerBound("l", sympy.sqrt(epsilon * (alpha1**2 * e1**2 + alpha2**2 * e2**2)), lemma10,
                     "(10): ‖L‖² ≥ ε(α1²‖s1−r1‖² + α2²‖s2−r2‖²)")
    B = tau * delta**Pw  # the region's bound on I_i
    return [
        TermBound("−γωᵀDω", -gamma * c6 * w**2, Rayleigh(omega(t), D, factor=-gamma, eigenvalue=_eig("D", "min"),
                                                       norm_squared=w**2)),
        TermBound("−f^ν LᵀD⁻¹L",
                  -c7 * epsilon * sum((ai / 2) ** nu * ai**2 * e ** Pw for ai, e in zip(a, (e1, e2))),
                  Rayleigh(L(t), D_inv, factor=-_f(e1, e2), eigenvalue=_eig("D", "max", True), norm_squared=l**2),
                  then=(ten, PowerSplit())),
        TermBound("−LᵀD⁻¹(ω×(Θω))", Dinv_norm * theta_max * (alpha1 + alpha2) * delta * w**2,
                  CauchySchwarz(L(t), omega(t).cross(Theta * omega(t)),
                                (_L_norm(_by["e1"], _by["e2"]), crossed(measured(_by["w"]), _Theta_w)),
                                matrix=D_inv, factor=-1, operator_norm=_dinv),
                  then=(OnRegion("e1", 0), OnRegion("e2", 0))),
        TermBound("−γf^ν(t−τ)ωᵀL(t−τ)",
                  gamma * c8 * (eta * w**2 + delta ** (2 * nu) * (d1**Pw + d2**Pw) / (2 * eta)),
                  CauchySchwarz(omega(t), L(t - tau), (measured(_by["w"]), delayed_L), factor=-gamma * _f(d1, d2)),
                  then=(Homogeneous(("d1", "d2"), d1**K + d2**K, "c8", factor=gamma * w),
                        YoungEach(((w, d1**K, 2, 2, eta), (w, d2**K, 2, 2, eta))),
                        OnRegion("d1", Pw), OnRegion("d2", Pw))),
        TermBound("MᵀD⁻¹∫f^νL dξ",
                  Dinv_norm * (alpha1 + alpha2) * c10p * _tau_P * (
                      eta * w**2 + B ** (2 * K / Pw - 1) * (i1 + i2) / (2 * eta)),
                  CauchySchwarz(M, int_fL, (_M_norm, _memory), matrix=D_inv, operator_norm=_dinv),
                  then=(WindowHolder("K1", "I1"), WindowHolder("K2", "I2"),
                        YoungEach(tuple((w, y, 2, 2, eta) for y in _Ik)), OnRegion("I1", 1), OnRegion("I2", 1))),
        TermBound("−MᵀD⁻¹Θω", Dinv_norm * theta_max * (alpha1 + alpha2) * w**2,
                  CauchySchwarz(M, Theta * omega(t), (_M_norm, _Theta_w), matrix=D_inv, factor=-1,
                                operator_norm=_dinv)),
        TermBound("−λ∫W dξ", -lam * (i1 + i2), Equal(-lam * (i1 + i2))),
        TermBound("(λτ+μ)W", (lam * tau + mu) * (e1**Pw + e2**Pw), Equal((lam * tau + mu) * (e1**Pw + e2**Pw))),
        TermBound("−μW(t−τ)", -mu * (d1**Pw + d2**Pw), Equal(-mu * (d1**Pw + d2**Pw))),
    ]


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 1 on :data:`REGION`."""
    lower, _ = _lower_bounds()
    upper, vdot = _upper_bounds(), _vdot_bounds()
    return lyapunov_steps(functional, system, lower, upper, vdot, MEASURES,
                          region=REGION, definitions=DEFINITIONS, derivation=derivation)


steps = chain_steps()

#: the conclusion: V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖), V̇ ≤ −ψ(‖x(t)‖) with x(t) = (ω, s1 − r1, s2 − r2)
CONCLUSION = Krasovskii(("w", "e1", "e2"))


# ---- the free choices ---------------------------------------------------------------------------
def _homogeneous_estimate(k, nu_, a1, a2, n=2001):
    """sup_{x ≥ 0} f^ν(a1x1 + a2x2)/(x1^k + x2^k) on the arc x1² + x2² = 1 (sampled; degree 0)."""
    th = np.linspace(0, np.pi / 2, n)
    x1, x2 = np.cos(th), np.sin(th)
    f = ((a1 * x1**2 + a2 * x2**2) / 2) ** nu_
    return float(np.max(f * (a1 * x1 + a2 * x2) / (x1**k + x2**k)))


def _rational_below(x, digits=3):
    """A rational ≤ x with ``digits`` significant digits."""
    x = float(x)
    e = int(np.floor(np.log10(x))) - digits + 1
    return sympy.Rational(int(np.floor(x / 10.0**e)), 1) * sympy.Rational(10) ** e


def _rational_above(x, digits=3):
    x = float(x)
    e = int(np.floor(np.log10(x))) - digits + 1
    return sympy.Rational(int(np.ceil(x / 10.0**e)), 1) * sympy.Rational(10) ** e


def find_choices(values) -> dict:
    """γ, λ, μ, ε, δ, η_ω, η_K, η for which every coefficient of L, U, W has its sign (as exact strings).

    The recipe follows the proof ("λ, μ, δ small enough, γ large enough"): ε = 1/2; η_ω makes
    the e_i² coefficient of L α_i/4; λτ + μ is half the coefficient c7ε(α_i/2)^ν α_i² of (12);
    η_K makes the I_i coefficient of L μ/2; η = c6/(4c8); γ is twice what the ω-terms need;
    then δ is the largest value (to three digits, times 0.9) that keeps the δ-terms below
    half their budget.  Floating point only picks the numbers; the steps prove them.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.proofs.aleksandrov2026.equations import P
    >>> ch = find_choices(P.resolve({}, use_defaults=True))
    >>> sorted(ch), float(sympy.Rational(ch["delta"])) < 1e-3
    (['delta', 'epsilon', 'eta', 'eta_K', 'eta_w', 'gamma', 'lam', 'mu'], True)
    """
    v = values
    f = lambda x: float(sympy.N(x, 30))  # noqa: E731
    Th, Dm = sympy.Matrix(v["Theta"]), sympy.Matrix(v["D"])
    et, ed = [f(x) for x in Th.eigenvals(multiple=True)], [f(x) for x in Dm.eigenvals(multiple=True)]
    th_min, th_max, c6_, c7_, dn = min(et), max(et), min(ed), 1 / max(ed), 1 / min(ed)
    a1, a2, nu_, tau_ = f(v["alpha1"]), f(v["alpha2"]), f(v["nu"]), f(v["tau"])
    k, P_ = 2 * nu_ + 1, 2 * nu_ + 2
    c8_ = 1.05 * _homogeneous_estimate(k, nu_, a1, a2)
    c10_ = 1.05 * _homogeneous_estimate(k, nu_, a1, a2)
    eps = sympy.Rational(1, 2) if v.get("epsilon") is None else sympy.Rational(v["epsilon"])
    tp = tau_ ** (1 / P_)
    eta_w_ = _rational_below(1 / (2 * dn * th_max))
    E = min(c7_ * float(eps) * (a / 2) ** nu_ * a**2 for a in (a1, a2))
    mu_ = _rational_below(E / 4)
    lam_ = _rational_below(E / (4 * tau_))
    q = P_ / k
    eta_K_ = _rational_above((2 * dn * c10_ * tp * (a1 + a2) / (q * float(mu_))) ** k)
    eta_ = _rational_below(c6_ / (4 * c8_))
    c5 = dn * th_max * (a1 + a2)
    gamma_L = 2 * dn * th_max * (a1 + a2) / (2 * float(eta_w_)) * 2 / th_min
    rest = c5 + dn * th_max * (a1 + a2) + dn * (a1 + a2) * c10_ * tp * float(eta_)
    gamma_W = rest / (c6_ - c8_ * float(eta_)) * 2
    gamma_ = _rational_above(max(gamma_L, gamma_W))
    cands = [1.0 / 2,
             (float(mu_) * float(eta_) / (float(gamma_) * c8_)) ** (1 / (2 * nu_)),  # d: γc8δ^{2ν}/(2η) ≤ μ/2
             # I: ‖D⁻¹‖(α1+α2)c10′τ^{1/P}(τδ^P)^{2k/P−1}/(2η) ≤ λ/2
             ((float(lam_) * float(eta_) / (dn * (a1 + a2) * c10_ * tp)) ** (1 / (2 * k / P_ - 1)) / tau_) ** (1 / P_),
             # L: 2‖D⁻¹‖c10′τ^{1/P}η_K δ^{P−2}/P ≤ 1/8 (of the α_i/4 left)
             (P_ / (16 * dn * c10_ * tp * float(eta_K_))) ** (1 / (P_ - 2))]
    delta_ = _rational_below(0.9 * min(cands))
    return {"gamma": str(gamma_), "lam": str(lam_), "mu": str(mu_), "epsilon": str(eps), "delta": str(delta_),
            "eta_w": str(eta_w_), "eta_K": str(eta_K_), "eta": str(eta_)}


# ---- the largest region this chain certifies (Remark 1) ---------------------------------------
_CHOICE_NAMES = ("gamma", "lam", "mu", "eta_w", "eta_K", "eta")
_SIGNS = {"lower": 1, "upper": 1, "vdot": -1}


def _coefficient_expressions(values, eps):
    """[(sign wanted, coefficient, monomial)] of L and W in the choices γ, λ, μ, η_ω, η_K, η, δ (c8, c10′ estimated)."""
    f = lambda x: float(sympy.N(x, 30))  # noqa: E731
    a1, a2, nu_ = f(values["alpha1"]), f(values["alpha2"]), f(values["nu"])
    c = sympy.Rational(1.01 * _homogeneous_estimate(2 * nu_ + 1, nu_, a1, a2)).limit_denominator(10**6)
    values = {k: v for k, v in values.items() if k not in (*_CHOICE_NAMES, "delta", "epsilon")}
    sub = dict(steps[0].system.parameters.substitution(values))
    sub.update({k: v for k, v in steps[0].named_constants(values).items()})
    sub.update({c8: c, c10p: c})
    meas = {m.symbol for m in MEASURES}
    out = []
    for step in steps:
        if step.role == "upper":
            continue  # U's coefficients are positive for every positive choice
        rhs = sympy.sympify(step.rhs).xreplace(sub)
        if eps is not None:
            rhs = rhs.xreplace({epsilon: sympy.Rational(eps)})
        for mono, coeff in collect_monomials(rhs, meas).items():
            out.append((_SIGNS[step.role], sympy.expand(coeff), str(mono)))
    return out


EPSILON_MAX = sympy.Rational(99, 100)  # ε of (10) is chosen in (0, 99/100]: (10) then holds for e1² + e2² < 4(1 − ε)


def _gp_choices(exprs, *, margin=0.99, delta_max=0.5):
    """The choices maximising δ as a geometric programme (cvxpy, ``gp=True``); None when it is not one.

    Each coefficient must have exactly one term of the wanted sign g and others b_j:
    want·coeff > 0 ⇔ Σ|b_j|/|g| < 1, a posynomial constraint (here ≤ ``margin``).
    """
    import cvxpy as cp

    names = (*_CHOICE_NAMES, "epsilon", "delta")
    syms = [sympy.Symbol(n, positive=True) for n in names]
    var = {s_: cp.Variable(pos=True, name=str(s_)) for s_ in syms}

    def monomial(term):
        coeff, powers = sympy.S.One, {}
        for fac in sympy.Mul.make_args(term):
            base, exp = fac.as_base_exp()
            if base in var:
                powers[base] = powers.get(base, 0) + exp
            else:
                coeff *= fac
        if not coeff.is_number or any(not sympy.sympify(e).is_number for e in powers.values()):
            return None
        m = abs(float(coeff))
        for b, e in powers.items():
            m = m * var[b] ** float(e)
        return float(coeff), m

    constraints = [var[syms[-1]] <= delta_max, var[syms[-2]] <= float(EPSILON_MAX)]
    for want, coeff, _ in exprs:
        terms = [monomial(t_) for t_ in sympy.Add.make_args(coeff)]
        if any(t_ is None for t_ in terms):
            return None
        good = [m for c_, m in terms if c_ * want > 0]
        bad = [m for c_, m in terms if c_ * want < 0]
        if len(good) != 1:
            return None
        if bad:
            constraints.append(sum(bad) / good[0] <= margin)
    prob = cp.Problem(cp.Minimize(1 / var[syms[-1]]), constraints)
    try:
        prob.solve(gp=True, solver="CLARABEL")
    except (cp.error.SolverError, cp.error.DGPError):
        return None
    if prob.status not in ("optimal",):
        return None
    return [float(var[s_].value) for s_ in syms]


def _coefficient_functions(values, eps):
    """[(sign wanted, f(γ, λ, μ, η_ω, η_K, η, δ), monomial)] for every coefficient of L and W (floats)."""
    syms = [sympy.Symbol(n, positive=True) for n in (*_CHOICE_NAMES, "delta")]
    return [(want, sympy.lambdify(syms, coeff, "math"), mono) for want, coeff, mono in
            _coefficient_expressions(values, eps)]


def _largest_delta_at(fns, x, hi=0.5):
    """The largest δ ≤ hi with every coefficient of its sign at the choices x (bisection in log δ); 0 if none."""
    import math

    def ok(d):
        try:
            return all(want * g(*x, d) > 0 for want, g, _ in fns)
        except (ValueError, OverflowError, ZeroDivisionError):
            return False

    lo_, hi_ = -80.0, math.log(hi)
    if ok(hi):
        return hi
    if not ok(math.exp(lo_)):
        return 0.0
    for _ in range(60):
        mid = (lo_ + hi_) / 2
        lo_, hi_ = (mid, hi_) if ok(math.exp(mid)) else (lo_, mid)
    return math.exp(lo_)


def optimal_choices(values, *, start=None, maxiter=1000, rounds=8, box=None) -> dict:
    """The choices that maximise the region δ this chain certifies at the given gains.

    Every coefficient of L and W has one term of the sign it needs, so "every coefficient has
    its sign" is a geometric programme in γ, λ, μ, η_ω, η_K, η, ε, δ (each constraint
    posynomial/monomial ≤ 0.99; ε ≤ 99/100; the c8, c10′ suprema estimated 1 % high): its
    global optimum is found with cvxpy (``gp=True``, Clarabel).  Should the programme not be
    one (other gains changing the structure), Nelder–Mead from :func:`find_choices`'s recipe
    is restarted (at most ``rounds`` times) until δ improves by less than 1 %.  Returns exact
    strings, rounded to four digits, δ the largest the rounded choices allow, times 0.9 and
    rounded down; the chain then proves them (floating point only picks them).

    With ``box`` (name → (lo, hi) of scalar parameters, e.g. ``{"tau": ("1/2", "1")}``; ``values``
    at any point of it, the boxed entries are replaced) the choices are picked for every corner
    of the box at once: each constraint of the programme is imposed at each corner, and δ is
    the smallest the rounded choices allow over the corners.  In τ every constraint is a
    posynomial, log-convex in log τ, so its largest value over an interval is at an end: the
    picked choices then have their margin on the whole interval (the chain over the box, with
    the coefficients enclosed over it, is what proves that; this only picks the numbers).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.proofs.aleksandrov2026.equations import P
    >>> ch = optimal_choices(P.resolve({}, use_defaults=True))
    >>> ch["epsilon"], 1e-4 < float(sympy.Rational(ch["delta"])) < 1e-2
    ('99/100', True)
    """
    import math

    from scipy.optimize import minimize

    points = _corner_values(values, box)
    centre = points[0] if box is None else _at(values, {k: (sympy.Rational(lo) + sympy.Rational(hi)) / 2
                                                       for k, (lo, hi) in box.items()})
    start = dict(start or find_choices(centre))
    x0 = [math.log(float(sympy.Rational(start[n]))) for n in _CHOICE_NAMES]
    given_eps = values.get("epsilon")

    def largest_delta(fns_all, x):  # the δ every point allows
        return min(_largest_delta_at(fns, x) for fns in fns_all)

    gp = _gp_choices([e for v in points for e in _coefficient_expressions(v, given_eps)])
    if gp is not None:  # the global optimum of the geometric programme, rounded into the interior
        eps_ = sympy.Rational(given_eps) if given_eps is not None else min(_rational_below(gp[-2], 2), EPSILON_MAX)
        fns_e = [_coefficient_functions(v, eps_) for v in points]
        for s_ in (0.0, 0.02, 0.05, 0.1, 0.2, 0.4, 1.0):
            xs = [_rational_below(math.exp((1 - s_) * math.log(g) + s_ * a), 4) for g, a in zip(gp[:-2], x0)]
            d = largest_delta(fns_e, [float(x) for x in xs])
            if d > 0:
                out = {n: str(x) for n, x in zip(_CHOICE_NAMES, xs)}
                out.update(epsilon=str(eps_), delta=str(_rational_below(0.9 * d)))
                return out

    fns_all = [_coefficient_functions(v, start["epsilon"]) for v in points]

    def objective(z):
        d = largest_delta(fns_all, [math.exp(v) for v in z])
        return -math.log(d) if d > 0 else 200.0

    best, value = list(x0), objective(x0)
    for _ in range(rounds):  # Nelder–Mead restarted from its last point until δ gains < 1 %
        res = minimize(objective, best, method="Nelder-Mead",
                       options={"maxiter": maxiter, "xatol": 1e-4, "fatol": 1e-5})
        if res.fun >= value - 0.01:
            if res.fun < value:
                best, value = list(res.x), res.fun
            break
        best, value = list(res.x), res.fun
    # the optimum sits on several constraints at once: step back towards the recipe's interior
    # point until the choices, rounded to four digits, still leave a region
    for s_ in (0.02, 0.05, 0.1, 0.2, 0.4, 1.0):
        xs = [_rational_below(math.exp((1 - s_) * b + s_ * a), 4) for b, a in zip(best, x0)]
        d = largest_delta(fns_all, [float(x) for x in xs])
        if d > 0:
            break
    out = {n: str(x) for n, x in zip(_CHOICE_NAMES, xs)}
    out.update(epsilon=start["epsilon"], delta=str(_rational_below(0.9 * d)))
    return out


def _at(values, point):
    """``values`` with the entries of ``point`` (name → exact value) replaced (the same resolved type)."""
    out = type(values)({**values, **point})
    if hasattr(values, "from_float"):
        out.from_float = values.from_float
    return out


def _corner_values(values, box):
    """[values] without a box; else ``values`` at every corner of ``box`` (name → (lo, hi), exact)."""
    import itertools

    if not box:
        return [values]
    names = list(box)
    axes = [sorted({sympy.Rational(lo), sympy.Rational(hi)}) for lo, hi in (box[n] for n in names)]
    return [_at(values, dict(zip(names, corner))) for corner in itertools.product(*axes)]


def box_choices(box, values=None) -> dict:
    """The proof's choices for every point of ``box`` (name → (lo, hi)): :func:`optimal_choices` over its corners.

    ``values`` are the other parameters (the paper's defaults otherwise).  Give the result as
    the run's values with the same box, ``theorem1.run(box_choices(B), box=B)``: the chain is
    then checked at these exact choices for every point of the box (the choices are free: any
    that close the chain prove the theorem there; these are picked to close it on all of B).

    Examples
    --------
    >>> ch = box_choices({"tau": ("9", "10")})
    >>> sorted(ch) == sorted(_CHOICE_NAMES + ("epsilon", "delta"))
    True
    """
    from .equations import P

    given = dict(values or {})
    centre = {k: (sympy.Rational(lo) + sympy.Rational(hi)) / 2 for k, (lo, hi) in box.items()}
    resolved = P.resolve({**given, **{k: str(v) for k, v in centre.items()}}, use_defaults=True)
    return optimal_choices(resolved, box=dict(box))
