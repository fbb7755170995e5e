"""The proof of Theorem 2 of paper 001 as checked bound steps: the estimates (16), and the conclusion's form.

The proof (section 5, instance W = (ωᵀDω)², μ = σ = 3 of :mod:`.theorem2`) has four steps: the
estimates (16) α1(‖ω‖² + Σ‖s_i−r_i‖²) ≤ V ≤ α2(…) "for γ small enough"; the V̇ bound with
α3 … α6 and δ1 "using Lemma 1"; V̇ ≤ −α7(h‖ω‖^{μ+1} + h^ν Σ‖s_i−r_i‖^{σ+1}) ≤ −α8 h^ν V^λ,
λ = (σ+1)/2, "if σ ≥ μ and (15) holds"; and the algebraic envelope

    V(t) ≤ V(t0)(1 + α8(λ−1)V(t0)^{λ−1}∫_{t0}^t h^ν)^{−1/(λ−1)}.

Here, in the measures w = ‖ω‖, e_i = ‖s_i − r_i‖, l = ‖η‖, hh = h(t) and hw = |ḣ|‖ω‖, on the
region e1 ≤ δ1, e2 ≤ δ1, w ≤ δ_ω (the proof's δ2-neighbourhood bounds ω too):

* V ≥ L and V ≤ U (16), proved term by term: ½ωᵀJω by the eigenvalues of J, (a_i/2)e_i² exactly,
  and |γh^ν‖η‖²ωᵀJη| ≤ γh^ν‖J‖ l² w(a1e1 + a2e2) (Cauchy–Schwarz, ‖s×r‖ ≤ ‖s−r‖), then
  l ≤ (a1 + a2)δ1 on the region (:func:`eta_on_region`: the same norm tree, and the region), then
  Young h^ν w e_i ≤ h^ν(w² + e_i²)/2;  H = sup h exact, as in Theorem 1.
* V̇ ≤ W over the exact structured V̇ of :mod:`.theorem2_functional`, its seven terms:
  −4h(ωᵀDω)² ≤ −4λ_min(D)²h w⁴ (a measure q = ωᵀDω, q ≥ λ_min(D)w² decided);
  γνh^{ν−1}ḣ‖η‖²ωᵀJη ≤ γνh^{ν−1}‖J‖ l² hw(a1e1 + a2e2), then (15) |ḣ| ≤ Lh^{1+(1−ν)/4} (L exact),
  l ≤ a1e1 + a2e2 (:func:`eta_tree`), Young (4, 4/3) h^{(3ν+1)/4}w e³ ≤ η_h h w⁴/4 + ¾η_h^{−1/3}h^ν e⁴ and
  (3/2, 3) for the mixed e1^{8/3}e2^{4/3};  −2γh^ν(ηᵀM)(ωᵀJη) and −4γh^{ν+1}‖η‖²(ωᵀDω)(Dω)ᵀη by
  Cauchy–Schwarz on both factors (:class:`ProductCS`), the latter with ‖η‖² = l·l2 (one factor by the
  tree, one by the region) and w³ ≤ δ_ω w² (the region's bound on ω: the proof's δ2 bounds ω too);
  −γh^ν‖η‖²(ω×Jω)ᵀη likewise with l·l2;  −γh^ν‖η‖⁴ ≤ −γε²h^ν(a1²e1² + a2²e2²)² by Lemma 1
  (:func:`~.theorem1_chain.lemma6`, certified on the region);  −γh^ν‖η‖²ωᵀJM ≤ γh^ν‖J‖(a1+a2)l²w²;
  every h^ν w²e² and w²e1e2 then by Young (η_w) into h^ν w⁴ and h^ν e⁴.
* The conclusion :data:`CONCLUSION` is :class:`~lkverify.certify.steps.timevarying.TimeVaryingRate`
  with ``lam`` = λ = (σ+1)/2 = 2: W + α8 h^ν n^{λ−1}Σ ū_k^λ x_k^{2λ} ≤ 0 coefficient-wise for 0 < h ≤ H
  (U^λ bounded by the power mean of its n = 3 squares) and the algebraic envelope; (11) decided.

The choices γ, ε, δ1, δ_ω, η_w, η_h, α8 are computed at the run's values by :func:`find_choices` (exact
rationals, closed forms; the steps are then proved at them).  They are tiny (γ ≈ 2·10⁻⁷, α8 ≈ 3·10⁻⁸ at the
section 6 gains): the term-wise Young splits are crude, as the proof's "γ small enough" allows.
"""

from __future__ import annotations

import sympy

import functools

from lkverify import Status, quad, t
from lkverify.certify.steps.chain import TermBound, lyapunov_steps
from lkverify.certify.steps.measures import Region, norm_measure
from lkverify.certify.matrices import matrix_positive_definite
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Condition, Equal, ProductCS, Rayleigh, crossed, mapped, measured,
                                          resolve_norm)
from lkverify.certify.steps.timevarying import TimeVaryingRate, UpperBound, sup_in_t

from .conditions_h import decide_h_conditions
from .equations import D, J, a1, a2, eps, eta, gamma, h, nu, omega
from .theorem1_chain import (E1, E2, HW, MEASURES as _MEASURES1, W_, _d_norm, _eig, _eta_norm, _h_of, _j_norm,
                             _Jw, _M_norm, _rational, _scalar, condition11, lemma6)
from .theorem2_functional import M as _M, derivation2, functional2, mu, sigma, structured, system4

__all__ = ["CONCLUSION", "LAMBDA", "MEASURES", "REGION", "chain_steps", "eta_on_region", "find_choices",
           "steps"]

delta1 = _scalar("delta1", latex=r"\delta_1", description="region ‖s_i − r_i‖ ≤ δ1 of the V̇ bounds")
delta_w = _scalar("delta_w", latex=r"\delta_\omega", description="region ‖ω‖ ≤ δ_ω of Theorem 2's V̇ bound")
alpha8 = _scalar("alpha8", latex=r"\alpha_8", description="rate of V̇ ≤ −α8 h^ν V^λ (Theorem 2)")

#: λ = (σ + 1)/2 of V̇ ≤ −α8 h^ν V^λ
LAMBDA = (sigma + 1) / 2

# ---- the measures and the region ------------------------------------------------------------------
#: a second measure of η (the same vector): ‖η‖² = l·l2 lets one factor be bounded by the tree, one by the region
ETA2 = norm_measure("l2", eta, text="‖η(t)‖ (second factor)")
Q = norm_measure("q", sympy.Matrix([quad(omega(t), D)]), text="ωᵀDω")
MEASURES = (*_MEASURES1, ETA2, Q)
w, e1, e2, l, hh, hw, l2, q = (m.symbol for m in MEASURES)  # w … hw: the measures of Theorem 1's chain
REGION = Region({E1: delta1, E2: delta1, W_: delta_w})

j_min, j_max, d_min, d_max, L15 = sympy.symbols("j_min j_max d_min d_max L15", positive=True)
eta_w, eta_h = (_scalar(n, latex=x, description=d) for n, x, d in (
    ("eta_w", r"\eta_w", "Young's weight for the h^ν‖ω‖²‖s−r‖²-terms of Theorem 2's V̇"),
    ("eta_h2", r"\eta_{h}", "Young's weight for the ḣ-term of Theorem 2's V̇")))


@functools.lru_cache(maxsize=32)
def _condition15(h_value, nu_value):
    """(status, L, detail) of (15) at h, ν, μ: L the exact sup of |ḣ|/h^{1+(1−ν)/(μ+1)} (:mod:`.conditions_h`)."""
    res = decide_h_conditions(h_value, nu=nu_value, mu=mu, budget=10.0)
    r = next(r for r in res if r.name.startswith("(15)"))
    return r.status, r.value, r.detail


def _L15(v):
    status, L, _ = _condition15(_h_of(v), sympy.sympify(v["nu"]))
    return L if status is Status.EXACT and L is not None else sympy.Symbol("L_undecided", positive=True)


DEFINITIONS = {j_min: _eig("J", "min"), j_max: _eig("J", "max"), d_min: _eig("D", "min"), d_max: _eig("D", "max"),
               L15: _L15}

def eta_on_region(ctx) -> Condition:
    """‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖ ≤ (a1 + a2)δ1 on the region: the norm tree of η (exact) and e_i ≤ δ1."""
    bound, conds = resolve_norm(_eta_norm, eta, ctx)
    text = "‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖ ≤ (a1 + a2)δ1 on the region"
    bad = [c for c in conds if not c.status.is_proof]
    if bound is None or bad:
        return Condition(text, Status.FAILED if any(c.status is Status.FAILED for c in bad) else Status.UNDECIDED,
                         "; ".join(f"{c.text}: {c.detail}" for c in bad) or "the norm tree gives no bound")
    b = [ctx.region.bound_of(m, ctx.sub) if ctx.region is not None else None for m in (E1, E2)]
    if any(x is None for x in b):
        return Condition(text, Status.UNDECIDED, "the region does not bound both ‖s_i − r_i‖")
    if sympy.expand(ctx.at(bound) - ctx.at(a1 * e1 + a2 * e2)) != 0:
        return Condition(text, Status.FAILED, f"the tree gives ‖η‖ ≤ {bound}")
    return Condition(f"‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖ ≤ {ctx.at((a1 + a2) * b[0]) if b[0] == b[1] else 'a1δ + a2δ'}",
                     Status.EXACT if all(c.status is Status.EXACT for c in conds) else Status.CERTIFIED)


def eta_tree(ctx) -> Condition:
    """‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖: the norm tree of η (‖s×r‖ = ‖(s−r)×r‖ ≤ ‖s−r‖, triangle), exact."""
    bound, conds = resolve_norm(_eta_norm, eta, ctx)
    text = "‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖ (the norm tree)"
    bad = [c for c in conds if not c.status.is_proof]
    if bound is None or bad or sympy.expand(ctx.at(bound) - ctx.at(a1 * e1 + a2 * e2)) != 0:
        return Condition(text, Status.FAILED if any(c.status is Status.FAILED for c in bad) else Status.UNDECIDED,
                         "; ".join(f"{c.text}: {c.detail}" for c in bad) or f"the tree gives {bound}")
    return Condition(text, Status.EXACT if all(c.status is Status.EXACT for c in conds) else Status.CERTIFIED)


def condition15(ctx) -> Condition:
    """(15) |ḣ| ≤ L h^{1+(1−ν)/(μ+1)} for t ≥ 0 at the run's h, ν, μ = 3, decided exactly (L the exact sup)."""
    status, L, detail = _condition15(_h_of(ctx.values), sympy.sympify(ctx.values["nu"]))
    if L is None:
        return Condition("(15) |ḣ| ≤ L h^(1+(1−ν)/(μ+1)) for t ≥ 0, some L",
                         Status.UNDECIDED if status is Status.EXACT else status, detail)
    return Condition(f"(15) |ḣ| ≤ L h^(1+(1−ν)/(μ+1)) for t ≥ 0 with L = {L}", status, detail)


def q_lower(ctx) -> Condition:
    """ωᵀDω ≥ λ_min(D)‖ω‖² ≥ 0: D − λ_min(D)I ⪰ 0 and λ_min(D) ≥ 0, decided exactly (so |ωᵀDω| = ωᵀDω)."""
    Dm = sympy.Matrix(ctx.at(D))
    dmin = _eig("D", "min")(ctx.values)
    res = matrix_positive_definite(Dm - dmin * sympy.eye(Dm.shape[0]), name="D − λ_min I", semidefinite=True)
    ok = res.status.is_proof and sympy.sympify(dmin) >= 0
    return Condition(f"ωᵀDω ≥ {dmin}‖ω‖² (D − λ_min(D)I ⪰ 0, λ_min(D) ≥ 0)",
                     res.status if ok else Status.FAILED, "" if ok else res.detail)


def _cross_term(sign):
    """γh^ν‖η‖²ωᵀJη ≷ ±γ‖J‖(a1 + a2)²δ1² h^ν Σ a_i(w² + e_i²)/2 (Cauchy–Schwarz, l on the region, Young)."""
    young = YoungEach(tuple((hh ** (nu / 2) * w, hh ** (nu / 2) * x, 2, 2, 1) for x in (e1, e2)))
    on_region = UpperBound("l", (a1 + a2) * delta1, eta_on_region, "‖η‖ ≤ (a1 + a2)δ1 on the region")
    c = gamma * hh**nu * j_max * (a1 + a2) ** 2 * delta1**2
    return TermBound("γh^ν‖η‖^{σ−1}ωᵀJη", sign * c * (a1 * (w**2 + e1**2) + a2 * (w**2 + e2**2)) / 2,
                     CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, factor=gamma * hh**nu * l**2,
                                   operator_norm=_j_norm), then=(on_region, young))


def _bounds(which):
    """The term bounds of V ≥ L (``"min"``) or V ≤ U (``"max"``) of (16)."""
    jj = j_min if which == "min" else j_max
    return [
        TermBound("½ωᵀJω", jj / 2 * w**2,
                  Rayleigh(omega(t), J, factor=sympy.Rational(1, 2), eigenvalue=_eig("J", which), norm_squared=w**2)),
        TermBound("(a1/2)‖s1−r1‖²", a1 / 2 * e1**2, Equal(a1 / 2 * e1**2)),
        TermBound("(a2/2)‖s2−r2‖²", a2 / 2 * e2**2, Equal(a2 / 2 * e2**2)),
        _cross_term(-1 if which == "min" else 1),
    ]


def _vdot_bounds():
    """V̇ ≤ W term by term on the structured V̇ of :mod:`.theorem2_functional` (five of its seven terms)."""
    E = a1 * e1 + a2 * e2
    tree = UpperBound("l", E, eta_tree, "‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖")
    young_we = YoungEach(tuple((hh ** (nu / 2) * w**2, hh ** (nu / 2) * m, 2, 2, eta_w)
                               for m in (e1**2, e2**2, e1 * e2)))
    young_ee = YoungEach(((hh ** (nu / 2) * e1**2, hh ** (nu / 2) * e2**2, 2, 2, 1),))

    def quartic(c):  # c·h^ν w²(a1e1 + a2e2)² after both Young steps
        return c * hh**nu * ((a1 + a2) ** 2 * eta_w * w**4 + (a1 + a2) * (a1 * e1**4 + a2 * e2**4) / eta_w) / 2

    young_we1 = YoungEach(tuple((hh ** ((nu + 1) / 2) * w**2, hh ** ((nu + 1) / 2) * m, 2, 2, eta_w)
                                for m in (e1**2, e2**2, e1 * e2)))
    young_ee1 = YoungEach(((hh ** ((nu + 1) / 2) * e1**2, hh ** ((nu + 1) / 2) * e2**2, 2, 2, 1),))
    quartic1 = lambda c: quartic(c) * hh  # noqa: E731  the same with h^{ν+1}
    cubes = (e1**3, e1**2 * e2, e1 * e2**2, e2**3)
    young_h = YoungEach(tuple((hh ** sympy.Rational(1, 4) * w, hh ** (3 * nu / 4) * m, 4, sympy.Rational(4, 3), eta_h)
                              for m in cubes))
    young_h2 = YoungEach(((hh ** (2 * nu / 3) * e1 ** sympy.Rational(8, 3), hh ** (nu / 3) * e2 ** sympy.Rational(4, 3),
                           sympy.Rational(3, 2), 3, 1),
                          (hh ** (2 * nu / 3) * e2 ** sympy.Rational(8, 3), hh ** (nu / 3) * e1 ** sympy.Rational(4, 3),
                           sympy.Rational(3, 2), 3, 1)))
    six = LowerBound("l", sympy.sqrt(eps * (a1**2 * e1**2 + a2**2 * e2**2)), lemma6,
                     "(6): ‖η‖² ≥ ε(a1²‖s1−r1‖² + a2²‖s2−r2‖²)")
    fifteen = UpperBound("hw", L15 * hh ** (1 + (1 - nu) / (mu + 1)) * w, condition15,
                         "(15): |ḣ|‖ω‖ ≤ L h^(1+(1−ν)/(μ+1))‖ω‖")
    region = UpperBound("l2", (a1 + a2) * delta1, eta_on_region, "‖η‖ ≤ (a1 + a2)δ1 on the region")
    S = {term.text: term for term in structured}
    return [
        TermBound(S["−(μ+1)hW"].text, -4 * d_min**2 * hh * w**4,
                  Rayleigh(sympy.Matrix([quad(omega(t), D)]), sympy.eye(1), factor=-(mu + 1) * hh, eigenvalue=1,
                           norm_squared=q**2),
                  then=(LowerBound("q", d_min * w**2, q_lower, "ωᵀDω ≥ λ_min(D)‖ω‖²"),)),
        TermBound("γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη",
                  gamma * nu * j_max * L15 * (eta_h * (a1 + a2) ** 3 * hh * w**4 / 4
                                              + 3 * eta_h ** sympy.Rational(-1, 3) * (a1 + a2) ** 2 * hh**nu
                                              * (a1 * e1**4 + a2 * e2**4) / 4),
                  CauchySchwarz(h(t).diff(t) * omega(t), eta, (measured(HW), _eta_norm), matrix=J,
                                factor=gamma * nu * hh ** (nu - 1) * l**2, operator_norm=_j_norm),
                  then=(fifteen, tree, young_h, young_h2)),
        TermBound("−γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)", quartic(2 * gamma * j_max * (a1 + a2)),
                  ProductCS(CauchySchwarz(eta, _M, (_eta_norm, _M_norm)),
                            CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, operator_norm=_j_norm),
                            factor=-(sigma - 1) * gamma * hh**nu),
                  then=(young_we, young_ee)),
        TermBound("−γh^ν‖η‖^{σ−1}(ω×Jω)ᵀη", quartic(gamma * j_max * (a1 + a2) * delta1),
                  CauchySchwarz(omega(t).cross(J * omega(t)), eta, (crossed(measured(W_), _Jw), _eta_norm),
                                factor=-gamma * hh**nu * l * l2),
                  then=(region, tree, young_we, young_ee)),
        TermBound("−γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη", quartic1(4 * gamma * d_max**2 * (a1 + a2) * delta1 * delta_w),
                  ProductCS(CauchySchwarz(omega(t), omega(t), (measured(W_), measured(W_)), matrix=D,
                                          operator_norm=_d_norm),
                            CauchySchwarz(D * omega(t), eta, (mapped(D, measured(W_), _d_norm), _eta_norm)),
                            factor=-(mu + 1) * gamma * hh ** (nu + 1) * l * l2),
                  then=(region, tree, OnRegion("w", 2), young_we1, young_ee1)),
        TermBound("−γh^ν‖η‖^{σ+1}", -gamma * eps**2 * hh**nu * (a1**2 * e1**2 + a2**2 * e2**2) ** 2,
                  Rayleigh(eta, sympy.eye(3), factor=-gamma * hh**nu * l**2, eigenvalue=1, norm_squared=l**2),
                  then=(six,)),
        TermBound("−γh^ν‖η‖^{σ−1}ωᵀJM", quartic(gamma * j_max * (a1 + a2)),
                  CauchySchwarz(omega(t), _M, (measured(W_), _M_norm), matrix=J, factor=-gamma * hh**nu * l**2,
                                operator_norm=_j_norm),
                  then=(tree, young_we, young_ee)),
    ]


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 2 on :data:`REGION`."""
    return lyapunov_steps(functional2, system4, _bounds("min"), _bounds("max"), _vdot_bounds(), MEASURES,
                          region=REGION, definitions=DEFINITIONS, derivation=derivation2, witness_time=1)


steps = chain_steps()

#: V̇ ≤ −α8 h^ν V^λ on the region for 0 < h ≤ sup h, the algebraic envelope; (11) makes it tend to 0
CONCLUSION = TimeVaryingRate(("w", "e1", "e2"), "hh", nu, alpha8, conditions=condition11, lam=LAMBDA)


def find_choices(values, box=None) -> dict:
    """γ, ε, δ1, δ_ω, η_w, η_h, α8 at the run's values (exact strings), in closed form (no optimisation).

    ε = δ1 = δ_ω = 1/2 unless given; H = sup_{t≥0} h exactly, L of (15) exact.  The e_i⁴-terms of W:
    −γε²a_i⁴h^ν from Lemma 1 against γ·(¾νjLη_h^{−1/3}(a1+a2)²a_i + K(a1+a2)a_i/(2η_w))h^ν with
    K = j(a1+a2)(3 + δ1) + 4d_max²(a1+a2)δ1δ_ω H (the ηᵀM-, ω×Jω-, M- and grad W-terms): η_h and η_w give
    each a quarter of ε²a_min⁴ (γ cancels).  The w⁴-terms: γ(νjLη_h(a1+a2)³/4 + K(a1+a2)²η_w H^{ν−1}/2) ≤
    2d_min² (half of −4d_min²h), and γ at most the (16) choice.  Then W ≤ −2d_min²h w⁴ − (γε²a_min⁴/2)h^ν e_i⁴
    and α8 is 9/10 of min(2d_min²H^{1−ν}, γε²a_min⁴/2)/(3ū²) (U² ≤ 3Σū_k²x_k⁴, ū the sups of U's
    coefficients), rounded down.  Floating point only picks the numbers: every step is proved at them.

    With ``box`` (name → (lo, hi), from a run over a box) the boxed a1, a2 enter at their worst ends for
    each use, as the chain's coefficients enclosed over the box see them: a_min the smallest lower end
    (the −γε²a_i⁴ margins), a_max and a1 + a2 the largest upper ends (every positive coefficient); ε, δ1,
    δ_ω boxed are taken at their lower, upper, upper ends.  Other boxed names do not change the recipe.

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2017.equations import P
    >>> sorted(find_choices(P.resolve({}, use_defaults=True)))
    ['alpha8', 'delta1', 'delta_w', 'eps', 'eta_h2', 'eta_w', 'gamma']
    """
    box = {k: (sympy.Rational(lo), sympy.Rational(hi)) for k, (lo, hi) in (box or {}).items()}

    def r(k, d, end=0):
        if k in box:
            return box[k][end]
        return sympy.Rational(values[k]) if values.get(k) is not None else sympy.Rational(d)

    eps_, d1, dw = r("eps", "1/2"), r("delta1", "1/2", 1), r("delta_w", "1/2", 1)
    H, _ = sup_in_t(_h_of(values))
    H = float(H) if H is not None and H.is_number and H.is_finite else 1.0
    nu_ = float(values["nu"])
    L = float(_L15(values)) if _L15(values).is_number else 1.0  # (15) fails or undecided: the step says so
    jmin, jmax, dmin, dmax = (float(_eig(m, k)(values)) for m in ("J", "D") for k in ("min", "max"))
    ends = [box.get(k, (values[k], values[k])) for k in ("a1", "a2")]
    a_lo, a_hi = min(float(lo) for lo, _ in ends), max(float(hi) for _, hi in ends)
    a, e2_ = sum(float(hi) for _, hi in ends), float(eps_) ** 2
    K = jmax * a * (3 + float(d1)) + 4 * dmax**2 * a * float(d1) * float(dw) * H
    et_h = _rational((3 * nu_ * jmax * L * a**2 * a_hi / (e2_ * a_lo**4)) ** 3, up=True)
    et_w = _rational(2 * K * a * a_hi / (e2_ * a_lo**4), up=True)
    per_gamma = nu_ * jmax * L * float(et_h) * a**3 / 4 + K * a**2 * float(et_w) * H ** (nu_ - 1) / 2
    c16 = jmax * a**2 * float(d1) ** 2 * H**nu_
    g = _rational(min(2 * dmin**2 / per_gamma, 0.5 * min(jmin / (c16 * a), 1 / c16)))
    u_w, u_e = jmax / 2 + float(g) * c16 * a / 2, a_hi / 2 * (1 + float(g) * c16)
    alpha = _rational(0.9 * min(2 * dmin**2 * H ** (1 - nu_) / (3 * u_w**2), float(g) * e2_ * a_lo**4 / (6 * u_e**2)))
    return {"gamma": str(g), "eps": str(eps_), "delta1": str(d1), "delta_w": str(dw), "eta_w": str(et_w),
            "eta_h2": str(et_h), "alpha8": str(alpha)}
