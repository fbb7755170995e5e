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
* V̇ ≤ W along the structured V̇ (:data:`derivation`, exact for every h):
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

from lkverify import Budget, DerivativeClaim, Status, Term, dot, quad, t
from lkverify.certify.bounds import certify_positive
from lkverify.certify.steps.chain import TermBound, TermwiseBound, collect_monomials
from lkverify.certify.steps.measures import Region, norm_measure
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Condition, Equal, Rayleigh, crossed, mapped, measured,
                                          scaled, summed, unit)
from lkverify.certify.steps.timevarying import TimeVaryingRate, UpperBound
from lkverify.declare.rigidbody import restoring_torque_rate

from .conditions_h import decide_h_conditions
from .equations import P, D, J, a1, a2, eps, eta, gamma, h, nu, omega, r1, r2, s1, s2, system
from .theorem1 import functional

__all__ = ["CONCLUSION", "REGION", "chain_steps", "derivation", "find_choices", "lemma6", "steps"]


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

# ---- V̇ along (2), (9), structured: the printed third term split into its three parts --------------
derivation = DerivativeClaim("Vdot_structured", functional, system, [
    Term(-2 * h(t) * quad(omega(t), D), text="−2hωᵀDω"),
    Term(gamma * nu * h(t) ** (nu - 1) * h(t).diff(t) * quad(omega(t), J, eta), text="γνh^{ν−1}ḣωᵀJη"),
    Term(-gamma * h(t) ** nu * dot(eta, omega(t).cross(J * omega(t))), text="−γh^ν ηᵀ(ω×Jω)"),
    Term(-2 * gamma * h(t) ** (nu + 1) * quad(eta, D, omega(t)), text="−2γh^{ν+1}ηᵀDω"),
    Term(-gamma * h(t) ** nu * dot(eta, eta), text="−γh^ν‖η‖²"),
    Term(-gamma * h(t) ** nu * quad(omega(t), J, M), text="−γh^ν ωᵀJM"),
], description="V̇ along (2),(9) in the structured form the V̇ bound uses (the printed third term split)")

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
    return Condition(f"(10) |ḣ| ≤ L h^((3−ν)/2) for t ≥ 0 with L = {L}", status, detail)


# ---- Lemma 1 on the region ------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _lemma_certificate(eps_, a1_, a2_, r1_, r2_, sigma_max, seconds):
    from .lemma1 import _U, _sig, lemma1_F

    F = lemma1_F(eps_, a1_, a2_, sympy.Matrix(r1_), sympy.Matrix(r2_))
    return certify_positive(F, {_sig: (0, sigma_max), **_U.region}, name=f"F ≥ 0 for σ ≤ {sigma_max}",
                            budget=Budget(seconds=seconds))


def lemma6(ctx) -> Condition:
    """(6) ‖η‖² ≥ ε(a1²e1² + a2²e2²) on the region, certified by Lemma 1 (:mod:`.lemma1`).

    With s_i = R r_i and σ = sin(φ/2), e1² + e2² ≥ 4σ² for orthonormal r1, r2, so on the region
    e_i ≤ b_i, σ ≤ √(b1² + b2²)/2; F(σ, u) ≥ 0 there for every axis u is (6) divided by σ².
    """
    eps_ = ctx.at(eps)
    if not (eps_.is_Rational and 0 < eps_ < 1):
        return Condition("(6) on the region", Status.FAILED, f"Lemma 1 needs 0 < ε < 1, got ε = {eps_}")
    bounds = [ctx.region.bound_of(m, ctx.sub) if ctx.region is not None else None for m in (E1, E2)]
    if any(b is None for b in bounds):
        return Condition("(6) on the region", Status.UNDECIDED, "the region does not bound both ‖s_i − r_i‖")
    b1, b2 = (sympy.sympify(ctx.at(b)) for b in bounds)
    sigma_max = sympy.sqrt(b1**2 + b2**2) / 2
    sigma_max = sympy.Rational(sympy.ceiling(sympy.N(sigma_max, 30) * 10**12), 10**12)  # a rational upper bound
    if sigma_max >= 1:
        return Condition("(6) on the region", Status.FAILED, f"the region allows σ = sin(φ/2) up to {sigma_max} ≥ 1")
    chk = _lemma_certificate(eps_, ctx.at(a1), ctx.at(a2), tuple(ctx.values["r1"]), tuple(ctx.values["r2"]),
                             sigma_max, ctx.seconds_left(20.0))
    text = f"(6) with ε = {eps_} on the region (Lemma 1: F ≥ 0 for σ ≤ {float(sigma_max):.4g}, every axis u)"
    status = Status.CERTIFIED if chk.status is Status.CERTIFIED else \
        Status.FAILED if chk.status is Status.FAILED else Status.UNDECIDED
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
        TermBound("−2hωᵀDω", -2 * d_min * hh * w**2,
                  Rayleigh(omega(t), D, factor=-2 * hh, eigenvalue=_eig("D", "min"), norm_squared=w**2)),
        TermBound("γνh^{ν−1}ḣωᵀJη",
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
        TermBound("−γh^ν ωᵀJM", gamma * hh**nu * j_max * (a1 + a2) * w**2,
                  CauchySchwarz(omega(t), M, (measured(W_), _M_norm), matrix=J, factor=-gamma * hh**nu,
                                operator_norm=_j_norm)),
    ]


def _sum(bounds):
    return sum((tb.bound for tb in bounds), sympy.S.Zero)


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 1 on :data:`REGION`."""
    lower, upper, vdot = _lower_bounds(), _upper_bounds(), _vdot_bounds()
    common = dict(region=REGION, definitions=DEFINITIONS, witness_time=1)
    return (TermwiseBound("V ≥ L", functional, system, "V", lower, _sum(lower), MEASURES, relation=">=",
                          role="lower", **common),
            TermwiseBound("V ≤ U", functional, system, "V", upper, _sum(upper), MEASURES, relation="<=",
                          role="upper", **common),
            TermwiseBound("V̇ ≤ W", functional, system, "Vdot", vdot, _sum(vdot), MEASURES, relation="<=",
                          derivation=derivation, role="vdot", **common))


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
    dmin, dmax, jmax, L = (float(f(values)) for f in (_eig("D", "min"), _eig("D", "max"), _eig("J", "max"), _L10))
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
