"""The proof of Theorem 1 of paper 001 from its V to the envelope, as checked bound steps.

The paper's proof has four steps: α1(‖ω‖² + Σ‖s_i−r_i‖²) ≤ V ≤ α2(…) "if γ is small enough";
the V̇ bound with α3 … α6 and δ1 "using Lemma 1"; (12) V̇ ≤ −α7 h^ν(t) V "for γ, δ2 small
enough, if (10) holds"; and, integrating (12), the envelope

    α1(‖ω(t)‖² + Σ‖s_i(t)−r_i‖²) ≤ V(t) ≤ V(t0) exp(−α7 ∫_{t0}^t h^ν(τ)dτ),

which tends to 0 by (11).  Here each step is a rule with checked side conditions, in the
measures w = ‖ω‖, e_i = ‖s_i − r_i‖, l = ‖η‖ and the two time-varying ones
hh = h(t), hw = ‖ḣ(t)ω(t)‖ = |ḣ|‖ω‖, on the region e1 ≤ δ1, e2 ≤ δ1 (which contains the
paper's ‖s1−r1‖² + ‖s2−r2‖² < δ1²):

* V ≥ L and V ≤ U: ½ωᵀJω by the eigenvalues of J, (a_i/2)e_i² exactly, and
  |γh^ν ωᵀJη| ≤ γh^ν‖J‖w(a1e1 + a2e2) (Cauchy–Schwarz, ‖s×r‖ ≤ ‖s−r‖), then Young;
* V̇ ≤ W along the printed V̇ (exact for every h), its third term split (:data:`split`, exact):
  −2hωᵀDω ≤ −2λ_min(D)hw²;  γνh^{ν−1}ḣωᵀJη ≤ γνh^{ν−1}‖J‖(|ḣ|w)(a1e1 + a2e2), then (10)
  |ḣ| ≤ Lh^{(3−ν)/2} (L the exact sup, decided by :mod:`.conditions_h`) and Young with
  h^{(ν+1)/2}we ≤ η_h hw²/2 + h^ν e²/(2η_h);  −γh^ν ηᵀ(ω×Jω) ≤ γh^ν‖J‖w²(a1e1 + a2e2) and
  e_i ≤ δ1;  −2γh^{ν+1}ηᵀDω ≤ 2γh^{ν+1}‖D‖(a1e1 + a2e2)w, then Young (η_D);
  −γh^ν‖η‖² ≤ −γεh^ν(a1²e1² + a2²e2²) by Lemma 1 (:mod:`.lemma1`, certified on the region);
  −γh^ν ωᵀJM ≤ γh^ν‖J‖(a1 + a2)w².

The conclusion (12) and the envelope are :class:`~lkverify.certify.steps.timevarying.TimeVaryingRate`:
W ≤ −α7 h^ν U coefficient-wise for 0 < h ≤ sup_{t≥0} h (computed exactly), (11) decided.
The choices γ, ε, δ1, η_h, η_D, α7 are found at the run's gains by :func:`find_choices`
(floating point only picks them; every step is then proved at those exact values).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy

from lkverify import Budget, IdentityClaim, Status, Term, dot, quad, t
from lkverify.certify.bounds import certify_positive
from lkverify.certify.steps.chain import TermBound, collect_monomials, lyapunov_steps
from lkverify.certify.steps.measures import Region, norm_measure
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Condition, Equal, Rayleigh, crossed, mapped, measured,
                                          scaled, summed, unit)
from lkverify.certify.steps.timevarying import TimeVaryingRate, UpperBound
from lkverify.declare.rigidbody import restoring_torque_rate

from .conditions_h import decide_h_conditions
from .equations import P, D, J, a1, a2, eps, eta, gamma, h, nu, omega, r1, r2, s1, s2, system
from .theorem1_functional import functional, printed_Vdot

__all__ = ["CONCLUSION", "EnvelopeAgainstRun", "REGION", "chain_steps", "condition10", "condition11", "split",
           "find_choices", "lemma6", "steps"]


def _scalar(name, **kw):
    """The registry's parameter ``name``, declared here (positive) unless another module already has."""
    return P[name].obj if name in P else P.scalar(name, positive=True, **kw)


delta1 = _scalar("delta1", latex=r"\delta_1", description="region ‖s_i − r_i‖ ≤ δ1 of Theorem 1's V̇ bound")
alpha7 = _scalar("alpha7", latex=r"\alpha_7", description="rate of (12) V̇ ≤ −α7 h^ν V (Theorem 1)")
eta_h = _scalar("eta_h", latex=r"\eta_h", description="Young's weight for the ḣ-term of Theorem 1's V̇")
eta_D = _scalar("eta_D", latex=r"\eta_D", description="Young's weight for the 2hDω-term of Theorem 1's V̇")

# ---- the measures --------------------------------------------------------------------------------
W_ = norm_measure("w", omega(t), text="‖ω(t)‖")
E1 = norm_measure("e1", s1(t) - r1, text="‖s1(t) − r1‖")
E2 = norm_measure("e2", s2(t) - r2, text="‖s2(t) − r2‖")
ETA = norm_measure("l", eta, text="‖η(t)‖")
HH = norm_measure("hh", sympy.Matrix([h(t)]), text="h(t)")
HW = norm_measure("hw", h(t).diff(t) * omega(t), text="|ḣ(t)|‖ω(t)‖")
MEASURES = (W_, E1, E2, ETA, HH, HW)
w, e1, e2, l, hh, hw = (m.symbol for m in MEASURES)
REGION = Region({E1: delta1, E2: delta1})

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (a1, a2))  # a1(ω×s1)×r1 + a2(ω×s2)×r2 = −η̇ by (2)

# ---- V̇ along (2), (9): the printed V̇ (proved exact in :mod:`.theorem1`), its third term split ------------
_T1, _T2, _T3, _T4 = printed_Vdot  # −2hωᵀDω, γνh^{ν−1}ḣωᵀJη, γh^ν ηᵀ(−ω×Jω − 2hDω − η), −γh^ν ωᵀJM
_split = (Term(-gamma * h(t) ** nu * dot(eta, omega(t).cross(J * omega(t))), text="−γh^ν ηᵀ(ω×Jω)"),
          Term(-2 * gamma * h(t) ** (nu + 1) * quad(eta, D, omega(t)), text="−2γh^{ν+1}ηᵀDω"),
          Term(-gamma * h(t) ** nu * dot(eta, eta), text="−γh^ν‖η‖²"))
#: the printed third term is the sum of the three the bounds treat separately (an identity, no derivative)
split = IdentityClaim("V̇ third term split", (_T3,), _split, system,
                      description="γh^ν ηᵀ(−ω×Jω − 2hDω − η) = −γh^ν ηᵀ(ω×Jω) − 2γh^{ν+1}ηᵀDω − γh^ν‖η‖²")
#: the lhs of V̇ ≤ W: the printed V̇ (= the derivative, exact) with its third term split (= by :data:`split`)
VDOT_TERMS = (_T1, _T2, *_split, _T4)

# ---- named constants ------------------------------------------------------------------------------
j_min, j_max, d_min, d_max, L10 = sympy.symbols("j_min j_max d_min d_max L10", positive=True)


def _eig(name, which):
    def value(v):
        ev = sympy.Matrix(v[name]).eigenvals(multiple=True)
        return min(ev) if which == "min" else max(ev)
    return value


@functools.lru_cache(maxsize=32)
def _condition10(h_value, nu_value):
    """(holds?, L, detail) of (10) at h, ν: L the exact sup of |ḣ|/h^{(3−ν)/2} (:mod:`.conditions_h`)."""
    res = decide_h_conditions(h_value, nu=nu_value, budget=10.0)
    r10 = next(r for r in res if r.name.startswith("(10)"))
    return r10.status, r10.value, r10.detail


def _h_of(v):
    value = v["h"]
    return value(t) if isinstance(value, sympy.Lambda) else sympy.sympify(value)


def _L10(v):
    status, L, _ = _condition10(_h_of(v), sympy.sympify(v["nu"]))
    return L if status is Status.EXACT and L is not None else sympy.Symbol("L_undecided", positive=True)


DEFINITIONS = {j_min: _eig("J", "min"), j_max: _eig("J", "max"), d_min: _eig("D", "min"), d_max: _eig("D", "max"),
               L10: _L10}


def condition10(ctx) -> Condition:
    """(10) |ḣ| ≤ L h^{(3−ν)/2} for t ≥ 0 at the run's h and ν, decided exactly (so |ḣ|‖ω‖ ≤ Lh^{(3−ν)/2}‖ω‖)."""
    status, L, detail = _condition10(_h_of(ctx.values), sympy.sympify(ctx.values["nu"]))
    if status is Status.EXACT and L is None:
        return Condition("(10) with an exact L", Status.UNDECIDED, detail)
    if L is None:
        return Condition("(10) |ḣ| ≤ L h^((3−ν)/2) for t ≥ 0, some L", status, detail)
    return Condition(f"(10) |ḣ| ≤ L h^((3−ν)/2) for t ≥ 0 with L = {L}", status, detail)


# ---- Lemma 1 on the region ------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _lemma_certificate(eps_, a1_, a2_, r1_, r2_, sigma_max, seconds, boxed=()):
    """F ≥ 0 (:func:`.lemma1.lemma1_F`) on σ ∈ [0, σ̄] × every axis u × the boxed parameters (``boxed``:
    ((symbol, (lo, hi)), …) for the symbols of ε, a1, a2 that are boxed): one certificate for every point."""
    from .lemma1 import _U, _sig, lemma1_F

    F = lemma1_F(eps_, a1_, a2_, sympy.Matrix(r1_), sympy.Matrix(r2_))
    return certify_positive(F, {_sig: (0, sigma_max), **_U.region, **dict(boxed)}, name=f"F ≥ 0 for σ ≤ {sigma_max}",
                            budget=Budget(seconds=seconds))


def _upper_over_box(expr, ctx):
    """A rational upper bound of ``expr`` at every point of the parameter box (the value itself without boxed
    symbols), or None when it cannot be enclosed."""
    from lkverify.certify.boxes import enclose_over, exact_interval, upper_rational

    expr = sympy.sympify(expr)
    boxed = {s_: ctx.parameter_box[s_] for s_ in expr.free_symbols if s_ in (ctx.parameter_box or {})}
    if expr.free_symbols - set(boxed):
        return None
    if not boxed:
        return expr
    exact = exact_interval(expr, boxed)
    return exact[1] if exact is not None else upper_rational(enclose_over(expr, boxed))


def _boxed_interval(expr, ctx):
    """(lo, hi) of a parameter that is a boxed symbol (its interval), (value, value) for a number, else None."""
    expr = sympy.sympify(expr)
    if expr in (ctx.parameter_box or {}):
        lo, hi = ctx.parameter_box[expr]
        return sympy.Rational(lo), sympy.Rational(hi)
    return (expr, expr) if expr.is_Rational else None


def lemma6(ctx) -> Condition:
    """(6) ‖η‖² ≥ ε(a1²e1² + a2²e2²) on the region, certified by Lemma 1 (:mod:`.lemma1`).

    With s_i = R r_i and σ = sin(φ/2), e1² + e2² ≥ 4σ² for orthonormal r1, r2, so on the region
    e_i ≤ b_i, σ ≤ √(b1² + b2²)/2; F(σ, u) ≥ 0 there for every axis u is (6) divided by σ².

    Over a parameter box (``ctx.parameter_box``) the boxed ε, a1, a2 in F are variables of the
    certificate's box (F ≥ 0 on σ × u × their intervals: for every point), ε's interval must lie in
    (0, 1), and σ̄ is taken from rational upper bounds of the region's b_i over the box.
    """
    eps_ = ctx.at(eps)
    eps_range = _boxed_interval(eps_, ctx)
    if eps_range is None or not (0 < eps_range[0] and eps_range[1] < 1):
        return Condition("(6) on the region", Status.FAILED if eps_range is not None or eps_.is_number else
                         Status.UNDECIDED, f"Lemma 1 needs 0 < ε < 1, got ε = {eps_}"
                         + (f" ∈ [{eps_range[0]}, {eps_range[1]}]" if eps_range and eps_range[0] != eps_range[1]
                            else ""))
    bounds = [ctx.region.bound_of(m, ctx.sub) if ctx.region is not None else None for m in (E1, E2)]
    if any(b is None for b in bounds):
        return Condition("(6) on the region", Status.UNDECIDED, "the region does not bound both ‖s_i − r_i‖")
    b1, b2 = (_upper_over_box(ctx.at(b), ctx) for b in bounds)
    if b1 is None or b2 is None:
        return Condition("(6) on the region", Status.UNDECIDED,
                         "the region's bounds on ‖s_i − r_i‖ have no rational upper bound over the box")
    sigma_max = sympy.sqrt(sympy.sympify(b1) ** 2 + sympy.sympify(b2) ** 2) / 2
    sigma_max = sympy.Rational(sympy.ceiling(sympy.N(sigma_max, 30) * 10**12), 10**12)  # a rational upper bound
    if sigma_max >= 1:
        return Condition("(6) on the region", Status.FAILED, f"the region allows σ = sin(φ/2) up to {sigma_max} ≥ 1")
    a1_, a2_ = ctx.at(a1), ctx.at(a2)
    boxed = tuple(sorted(((s_, (sympy.Rational(ctx.parameter_box[s_][0]), sympy.Rational(ctx.parameter_box[s_][1])))
                          for e in (eps_, a1_, a2_) for s_ in sympy.sympify(e).free_symbols
                          if s_ in (ctx.parameter_box or {})), key=lambda p: str(p[0])))
    if any(sympy.sympify(e).free_symbols - {s_ for s_, _ in boxed} for e in (eps_, a1_, a2_)):
        return Condition("(6) on the region", Status.UNDECIDED, f"ε = {eps_}, a1 = {a1_}, a2 = {a2_}: symbols "
                                                                "without an interval")
    if boxed:
        ctx.box_used = True  # the certificate depends on the box's ends
    chk = _lemma_certificate(eps_, a1_, a2_, tuple(ctx.values["r1"]), tuple(ctx.values["r2"]),
                             sigma_max, ctx.seconds_left(20.0), boxed)
    over = "" if not boxed else ", every " + ", ".join(f"{s_} ∈ [{lo}, {hi}]" for s_, (lo, hi) in boxed)
    text = f"(6) with ε = {eps_} on the region (Lemma 1: F ≥ 0 for σ ≤ {float(sigma_max):.4g}, every axis u{over})"
    status = Status.CERTIFIED if chk.status is Status.CERTIFIED else \
        Status.FAILED if chk.status is Status.FAILED and not boxed else Status.UNDECIDED
    return Condition(text, status, f"{chk.boxes} boxes" if status is Status.CERTIFIED else chk.detail)


# ---- norm trees -----------------------------------------------------------------------------------
_eta_norm = summed(scaled(a1, crossed(measured(E1), unit(r1))), scaled(a2, crossed(measured(E2), unit(r2))))
_M_norm = summed(scaled(a1, crossed(crossed(measured(W_), unit(s1(t))), unit(r1))),
                 scaled(a2, crossed(crossed(measured(W_), unit(s2(t))), unit(r2))))
_j_norm = lambda ctx: max(sympy.Matrix(ctx.at(J)).eigenvals(multiple=True))  # noqa: E731  ‖J‖
_d_norm = lambda ctx: max(sympy.Matrix(ctx.at(D)).eigenvals(multiple=True))  # noqa: E731  ‖D‖
_Jw = mapped(J, measured(W_), _j_norm)
_cross = a1 * e1 + a2 * e2


def _lower_bounds():
    young = YoungEach(tuple((hh ** (nu / 2) * w, hh ** (nu / 2) * x, 2, 2, 1) for x in (e1, e2)))
    return [
        TermBound("½ωᵀJω", j_min / 2 * w**2,
                  Rayleigh(omega(t), J, factor=sympy.Rational(1, 2), eigenvalue=_eig("J", "min"), norm_squared=w**2)),
        TermBound("(a1/2)‖s1−r1‖²", a1 / 2 * e1**2, Equal(a1 / 2 * e1**2)),
        TermBound("(a2/2)‖s2−r2‖²", a2 / 2 * e2**2, Equal(a2 / 2 * e2**2)),
        TermBound("γh^ν(t)ωᵀJη", -gamma * hh**nu * j_max * (a1 * (w**2 + e1**2) + a2 * (w**2 + e2**2)) / 2,
                  CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, factor=gamma * hh**nu,
                                operator_norm=_j_norm), then=(young,)),
    ]


def _upper_bounds():
    young = YoungEach(tuple((hh ** (nu / 2) * w, hh ** (nu / 2) * x, 2, 2, 1) for x in (e1, e2)))
    return [
        TermBound("½ωᵀJω", j_max / 2 * w**2,
                  Rayleigh(omega(t), J, factor=sympy.Rational(1, 2), eigenvalue=_eig("J", "max"), norm_squared=w**2)),
        TermBound("(a1/2)‖s1−r1‖²", a1 / 2 * e1**2, Equal(a1 / 2 * e1**2)),
        TermBound("(a2/2)‖s2−r2‖²", a2 / 2 * e2**2, Equal(a2 / 2 * e2**2)),
        TermBound("γh^ν(t)ωᵀJη", gamma * hh**nu * j_max * (a1 * (w**2 + e1**2) + a2 * (w**2 + e2**2)) / 2,
                  CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, factor=gamma * hh**nu,
                                operator_norm=_j_norm), then=(young,)),
    ]


def _vdot_bounds():
    e = (e1, e2)
    young_h = YoungEach(tuple((sympy.sqrt(hh) * w, hh ** (nu / 2) * x, 2, 2, eta_h) for x in e))
    young_D = YoungEach(tuple((hh ** (nu / 2) * x, hh ** (nu / 2 + 1) * w, 2, 2, eta_D) for x in e))
    six = LowerBound("l", sympy.sqrt(eps * (a1**2 * e1**2 + a2**2 * e2**2)), lemma6,
                     "(6): ‖η‖² ≥ ε(a1²‖s1−r1‖² + a2²‖s2−r2‖²)")
    ten = UpperBound("hw", L10 * hh ** ((3 - nu) / 2) * w, condition10, "(10): |ḣ|‖ω‖ ≤ L h^((3−ν)/2)‖ω‖")
    return [
        TermBound("−2h(t)ωᵀDω", -2 * d_min * hh * w**2,
                  Rayleigh(omega(t), D, factor=-2 * hh, eigenvalue=_eig("D", "min"), norm_squared=w**2)),
        TermBound("γνh^{ν−1}ḣ ωᵀJη",
                  gamma * nu * j_max * L10 * sum(a * (eta_h * hh * w**2 + hh**nu * x**2 / eta_h) / 2
                                                 for a, x in zip((a1, a2), e)),
                  CauchySchwarz(h(t).diff(t) * omega(t), eta, (measured(HW), _eta_norm), matrix=J,
                                factor=gamma * nu * hh ** (nu - 1), operator_norm=_j_norm),
                  then=(ten, young_h)),
        TermBound("−γh^ν ηᵀ(ω×Jω)", gamma * hh**nu * j_max * (a1 + a2) * delta1 * w**2,
                  CauchySchwarz(eta, omega(t).cross(J * omega(t)), (_eta_norm, crossed(measured(W_), _Jw)),
                                factor=-gamma * hh**nu),
                  then=(OnRegion("e1", 0), OnRegion("e2", 0))),
        TermBound("−2γh^{ν+1}ηᵀDω",
                  gamma * d_max * sum(a * (eta_D * hh**nu * x**2 + hh ** (nu + 2) * w**2 / eta_D)
                                      for a, x in zip((a1, a2), e)),
                  CauchySchwarz(eta, omega(t), (_eta_norm, measured(W_)), matrix=D, factor=-2 * gamma * hh ** (nu + 1),
                                operator_norm=_d_norm),
                  then=(young_D,)),
        TermBound("−γh^ν‖η‖²", -gamma * eps * hh**nu * (a1**2 * e1**2 + a2**2 * e2**2),
                  Rayleigh(eta, sympy.eye(3), factor=-gamma * hh**nu, eigenvalue=1, norm_squared=l**2),
                  then=(six,)),
        TermBound(_T4.text, gamma * hh**nu * j_max * (a1 + a2) * w**2,
                  CauchySchwarz(omega(t), M, (measured(W_), _M_norm), matrix=J, factor=-gamma * hh**nu,
                                operator_norm=_j_norm)),
    ]


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 1 on :data:`REGION`."""
    lower, upper, vdot = _lower_bounds(), _upper_bounds(), _vdot_bounds()
    return lyapunov_steps(functional, system, lower, upper, vdot, MEASURES,
                          region=REGION, definitions=DEFINITIONS, witness_time=1, vdot_terms=VDOT_TERMS)


steps = chain_steps()


# ---- the conclusion: (12) and the envelope, with (11) ---------------------------------------------
def condition11(values) -> list:
    """(11) ∫_0^∞ h^ν = ∞ at the run's h and ν (:mod:`.conditions_h`): the envelope then tends to 0."""
    res = decide_h_conditions(_h_of(values), nu=sympy.sympify(values["nu"]), budget=10.0)
    r11 = next(r for r in res if r.name.startswith("(11)"))
    return [Condition(f"(11) ∫_0^∞ h^ν dt = ∞ for h = {_h_of(values)}, ν = {values['nu']}", r11.status, r11.detail)]


#: (12) V̇ ≤ −α7 h^ν V on the region for 0 < h ≤ sup h, and the envelope; (11) makes it tend to 0
CONCLUSION = TimeVaryingRate(("w", "e1", "e2"), "hh", nu, alpha7, conditions=condition11)


# ---- the free choices -----------------------------------------------------------------------------
CHOICES = ("gamma", "eta_h", "eta_D")  # optimised; ε and δ1 fixed (or given), α7 follows
_SYMS = tuple(sympy.Symbol(n, positive=True) for n in CHOICES)


def _model(values, eps_, delta1_):
    """{role: {monomial: [(f(γ, η_h, η_D), p)]}}: the coefficients of L, U, W as floats times powers h^p."""
    from lkverify.declare.parameters import apply_substitution

    fixed = {k: v for k, v in values.items() if k not in (*CHOICES, "alpha7", "eps", "delta1")}
    sub = dict(system.parameters.substitution(fixed))
    consts = steps[2].named_constants(values)
    consts[L10] = consts[L10] if consts[L10].is_number else sympy.S.One  # (10) not holding: the step says so
    state = {w, e1, e2, l, hw}
    out = {}
    for step in steps:
        rhs = apply_substitution(step.rhs, sub).xreplace(consts).xreplace({eps: eps_, delta1: delta1_})
        out[step.role] = {}
        for mono, coeff in collect_monomials(rhs, state).items():
            terms = {}
            for term in sympy.Add.make_args(sympy.expand(coeff)):
                c, p = term.as_coeff_exponent(hh)
                terms[p] = terms.get(p, 0) + c
            out[step.role][mono] = [(sympy.lambdify(_SYMS, c, "math"), float(p)) for p, c in terms.items()]
    return out


def _sup_float(terms, x, shift, H):
    """sup over 0 < h ≤ H of Σ c h^{p−shift}, term by term (as :func:`~lkverify.certify.steps.timevarying.sup_on`)."""
    total = 0.0
    for f, p in terms:
        c, e = f(*x), p - shift
        if c > 0 and e < -1e-12:
            return math.inf
        if abs(e) <= 1e-12 or c > 0 or e < 0:
            total += c * H**e
    return total


def _best_alpha(model, x, nu_, H):
    """The largest α7 the conclusion's test allows at the choices x (0 when L or W has a wrong sign)."""
    for mono, terms in model["lower"].items():
        low = -_sup_float([(lambda *a, f=f: -f(*a), p) for f, p in terms], x, 0, H)
        if low <= 0 and mono in (w**2, e1**2, e2**2):
            return 0.0
    best = math.inf
    for mono in set(model["upper"]) | set(model["vdot"]):
        W_m, U_m = model["vdot"].get(mono, []), [(f, p + nu_) for f, p in model["upper"].get(mono, [])]
        q = min(p for _, p in W_m + U_m)
        sw, su = _sup_float(W_m, x, q, H), _sup_float(U_m, x, q, H)
        if sw >= 0:
            return 0.0
        if su > 0:
            best = min(best, -sw / su)
    return best


def _rational(x, digits=3, up=False):
    e = int(np.floor(np.log10(x))) - digits + 1
    m = math.ceil(x / 10.0**e) if up else math.floor(x / 10.0**e)
    return sympy.Rational(m) * sympy.Rational(10) ** e


def find_choices(values) -> dict:
    """γ, η_h, η_D maximising the rate α7 at the given gains (Nelder–Mead in log scale), ε, δ1, α7 (exact strings).

    ε = 1/2 and δ1 = 1/2 unless given (Lemma 1 then needs F ≥ 0 only for σ ≤ √2/4, far inside
    its certified δ(1/2)); H = sup_{t≥0} h exactly; α7 is 9/10 of the largest rate the
    conclusion's term-wise test allows at the rounded choices, rounded down.  Floating point
    only picks the numbers: every step is then proved at them.

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2017.equations import P
    >>> ch = find_choices(P.resolve({}, use_defaults=True))
    >>> sorted(ch), ch["eps"], ch["delta1"]
    (['alpha7', 'delta1', 'eps', 'eta_D', 'eta_h', 'gamma'], '1/2', '1/2')
    """
    from scipy.optimize import minimize

    from lkverify.certify.steps.timevarying import sup_in_t

    eps_ = sympy.Rational(values["eps"]) if values.get("eps") is not None else sympy.Rational(1, 2)
    delta1_ = sympy.Rational(values["delta1"]) if values.get("delta1") is not None else sympy.Rational(1, 2)
    H, _ = sup_in_t(_h_of(values))
    H = float(H) if H is not None and H.is_number and H.is_finite else 1.0
    nu_ = float(values["nu"])
    model = _model(values, eps_, delta1_)
    # a feasible start (the proof's "γ small enough"): the e_i²-parts of the ḣ- and 2hDω-terms a quarter of
    # εa_i² each, then γ such that the h‖ω‖²-terms take half of −2λ_min(D)
    dmin, dmax, jmax = (float(f(values)) for f in (_eig("D", "min"), _eig("D", "max"), _eig("J", "max")))
    L = float(_L10(values)) if _L10(values).is_number else 1.0  # (10) fails or is undecided: the step will say so
    a_lo, a_hi, a_sum = min(float(values["a1"]), float(values["a2"])), max(float(values["a1"]), float(values["a2"])), \
        float(values["a1"] + values["a2"])
    et_h = 2 * nu_ * jmax * L * a_hi / (float(eps_) * a_lo**2)
    et_D = float(eps_) * a_lo**2 / (4 * dmax * a_hi)
    per_gamma = (nu_ * jmax * L * a_sum * et_h / 2 + jmax * a_sum * (float(delta1_) + 1) * H ** (nu_ - 1)
                 + dmax * a_sum * H ** (nu_ + 1) / et_D)
    z0 = [math.log(dmin / per_gamma), math.log(et_h), math.log(et_D)]

    def objective(z):
        a = _best_alpha(model, [math.exp(v) for v in z], nu_, H)
        return -math.log(a) if 0 < a < math.inf else 50.0

    res = minimize(objective, z0, method="Nelder-Mead", options={"maxiter": 600, "xatol": 1e-3, "fatol": 1e-4})
    xs = [_rational(math.exp(v)) for v in res.x]
    best = _best_alpha(model, [float(v) for v in xs], nu_, H)
    alpha = _rational(0.9 * best) if 0 < best < math.inf else sympy.Rational(1, 1000)
    out = {n: str(v) for n, v in zip(CHOICES, xs)}
    out.update(eps=str(eps_), delta1=str(delta1_), alpha7=str(alpha))
    return out


# ---- the envelope against the section 6 run (lkverify constants aleksandrov2017.theorem1) ---------
def _integral_of_rate(h_expr, nu_value, times):
    """∫_0^t h^ν for each t of ``times``: in closed form when SymPy finds it, else the trapezoid rule on them."""
    T = sympy.Symbol("T", positive=True)
    try:
        F = sympy.integrate(h_expr**nu_value, (t, 0, T))
        if not F.has(sympy.Integral, sympy.Piecewise):
            return np.asarray(sympy.lambdify(T, F, "numpy")(times), dtype=float) * np.ones_like(times)
    except (NotImplementedError, ValueError, TypeError):
        pass
    f = sympy.lambdify(t, h_expr**nu_value, "numpy")(times) * np.ones_like(times)
    return np.concatenate([[0.0], np.cumsum((f[1:] + f[:-1]) / 2 * np.diff(times))])


class EnvelopeAgainstRun:
    """The constants job of Theorem 1: the certified chain's envelope against the section 6 run.

    ``lkverify constants aleksandrov2017.theorem1`` checks the chain at the run's values (choices
    found as in ``check``), takes the section 6 initial attitude and ω scaled down until
    ‖x(t0)‖ < δ2 (so the solution stays in the region), simulates (2), (9) and compares along it

        α1(‖ω‖² + Σ‖s_i − r_i‖²) ≤ V(t) ≤ V(t0) exp(−α7 ∫_0^t h^ν)

    (status ``simulated``; the largest ratio V / envelope is reported, ≤ 1 when it holds).
    """

    goals = ["default"]
    T_END = 400.0

    def run(self, item_name, values, shown, *, budget=120.0, progress=None, goal=None):
        """(Report, data for :meth:`plot`)."""
        from lkverify import Report, Result
        from lkverify.catalogue import find_items
        from lkverify.simulate import simulate

        from .example import INITIAL, initial_history

        (theorem1,) = find_items(item_name)  # the theorem this job belongs to (the catalogue passes its name)

        progress = progress or (lambda msg: None)
        progress(f"{item_name}: the chain at the run's values")
        report = theorem1.run(values, budget=budget)
        res = {r.name: r for r in report.results}
        rate = res.get("(12) V̇ ≤ −α7 h^ν V")
        if rate is None or rate.value is None or rate.value.get("delta2") is None:
            row = Result("simulation", "envelope against the section 6 run", Status.UNDECIDED, None,
                         f"the chain gives no envelope at these values: {report.verdict}")
            return Report(item_name, dict(shown), tuple(report.results) + (row,), report.verdict), {}
        v = {**values, **{k: sympy.Rational(x) for k, x in theorem1.chosen(values).items()}}
        alpha1_, alpha7_, delta2_ = rate.value["alpha1"], float(sympy.Rational(rate.value["alpha"])), \
            rate.value["delta2"]
        scale, hist = 1.0, None
        for _ in range(12):  # the section 6 history, scaled until ‖x(t0)‖ < δ2
            angles = tuple(scale * a for a in INITIAL.angles)
            omega0 = tuple(scale * x for x in INITIAL.omega)
            hist = initial_history(angles, omega0)
            x0 = np.sqrt(sum(np.sum((np.array(hist[f"s{i}"]) - np.array([float(c) for c in v[f"r{i}"]])) ** 2)
                             for i in (1, 2)) + np.sum(np.array(omega0) ** 2))
            if x0 < 0.9 * delta2_:
                break
            scale /= 2
        progress(f"{item_name}: simulating (2), (9) to t = {self.T_END:g} from ‖x(t0)‖ = {x0:.4g} < δ2 = {delta2_:.4g}")
        times = np.linspace(0.0, self.T_END, 4001)
        tr = simulate(system, history=hist, t_end=self.T_END, values={k: v[k] for k in ("J", "D", "a1", "a2", "h",
                                                                                         "r1", "r2", "r3")},
                      t_eval=times)
        sub = P.substitution(v)
        from lkverify.declare.parameters import apply_substitution

        args = [c for state in system.states for c in state(t)]
        V = sympy.lambdify([t, *args], apply_substitution(functional.expr, sub), "numpy")
        cols = [tr.states[state.name][:, i] for state in system.states for i in range(state.dim)]
        Vt = np.asarray(V(tr.t, *cols), dtype=float) * np.ones_like(tr.t)
        r = {i: np.array([float(c) for c in v[f"r{i}"]]) for i in (1, 2)}
        x2 = np.sum(tr.states["omega"] ** 2, axis=1) + sum(np.sum((tr.states[f"s{i}"] - r[i]) ** 2, axis=1)
                                                          for i in (1, 2))
        env = Vt[0] * np.exp(-alpha7_ * _integral_of_rate(_h_of(v), sympy.sympify(v["nu"]), tr.t))
        ratio, low = float(np.max(Vt / env)), float(np.max(alpha1_ * x2 / Vt))
        later = float(np.max((Vt / env)[tr.t >= 1.0]))  # equality at t0: the ratio after t = 1 says how loose
        ok = ratio <= 1 + 1e-9 and low <= 1 + 1e-9
        detail = (f"from the section 6 attitude and ω scaled by {scale:g} (‖x(t0)‖ = {x0:.4g} < δ2 = {delta2_:.4g}), "
                  f"h = {_h_of(v)}, t ∈ [0, {self.T_END:g}], {tr.outcome.value}: max V(t)/(V(t0)exp(−α7∫h^ν)) = "
                  f"{ratio:.4g} ({'≤ 1: the envelope holds' if ratio <= 1 + 1e-9 else '> 1: VIOLATED'}; = 1 at t0, "
                  f"{later:.3g} over t ≥ 1), "
                  f"max α1‖x(t)‖²/V(t) = {low:.4g} ({'≤ 1' if low <= 1 + 1e-9 else '> 1: VIOLATED'}); V(t_end)/V(t0) = "
                  f"{Vt[-1] / Vt[0]:.3g} against the envelope's {env[-1] / env[0]:.3g} (α7 = {alpha7_:.4g}: valid, loose)")
        row = Result("simulation", "envelope V(t) ≤ V(t0)exp(−α7∫h^ν) along the section 6 run",
                     Status.SIMULATED if ok else Status.FAILED,
                     {"largest_ratio": ratio, "largest_ratio_after_1": later, "largest_lower_ratio": low, "scale": scale, "x0": float(x0),
                      "delta2": delta2_, "alpha7": alpha7_, "alpha1": alpha1_, "t_end": self.T_END}, detail)
        verdict = f"{report.verdict.split(';')[0]}; envelope along the run: {row.status.value} (largest ratio {ratio:.4g})"
        data = {"t": tr.t, "V": Vt, "envelope": env, "lower": alpha1_ * x2, "ratio": ratio}
        return Report(item_name, dict(shown), tuple(report.results) + (row,), verdict), data

    def plot(self, extra, path, *, values=None):
        """V(t), its envelope and the lower bound α1‖x(t)‖² on a log scale."""
        from matplotlib.figure import Figure

        fig = Figure(figsize=(7.5, 4.5))
        ax = fig.subplots()
        if extra:
            ax.semilogy(extra["t"], extra["envelope"], "k--", lw=1.2, label=r"$V(t_0)e^{-\alpha_7\int h^\nu}$")
            ax.semilogy(extra["t"], extra["V"], lw=1.4, label=r"$V(t)$ (simulated)")
            ax.semilogy(extra["t"], extra["lower"], lw=1.0, label=r"$\alpha_1\|x(t)\|^2$")
            ax.set_title(f"Theorem 1 of paper 001: the envelope along the run (largest ratio {extra['ratio']:.3g})",
                         fontsize=10)
        ax.set_xlabel("$t$")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.0, 0.5))
        fig.tight_layout()
        from lkverify.report.files import save_figure

        save_figure(fig, path, dpi=120)
