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

Other exponents.  Everything above is written for an odd μ = σ ≥ 3 and built by :func:`chain_steps` (μ, σ),
:func:`conclusion` (σ) and :func:`find_choices` (``mu=``, ``sigma=``); the module-level :data:`steps`,
:data:`CONCLUSION`, :data:`DEFINITIONS` are μ = σ = 3 (the objects above, unchanged).  For general μ = σ the
(4, 4/3) and (3/2, 3) splits of the ḣ-term become (σ+1, (σ+1)/σ) and (σ/a, σ/(σ−a)) (:func:`hdot_young`),
the h^ν w²e-splits become ((σ+1)/2, (σ+1)/(σ−1)) and ((σ−1)/a, (σ−1)/(σ−1−a)) (:func:`mixed_young`), the
extra ‖η‖^{σ−3} of the ηᵀM-term goes through the tree, w^μ ≤ δ_ω^{μ−2}w² in the grad W-term, and
(ωᵀDω)^j enters a rule's factor only as an even power (|q|^{2i} = q^{2i} exactly; the odd rest is a
Rayleigh or Cauchy–Schwarz form, :func:`_damping`, :func:`_grad_term`).  For σ > μ the ḣ-term is split with
(μ+1, (μ+1)/μ) and its e-powers lowered on the region (:func:`hdot_young`, :func:`_hdot_term`), and half of
the damping is raised to w^{σ+1} on the region (:func:`_damping`).  Items: :mod:`.theorem2_exponents`.
"""

from __future__ import annotations

import sympy

import functools

from lkverify import Status, quad, t
from lkverify.certify.steps.chain import TermBound, lyapunov_steps
from lkverify.certify.steps.measures import Region, norm_measure
from lkverify.certify.matrices import matrix_positive_definite
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, RaiseOnRegion, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Condition, Equal, ProductCS, Rayleigh, crossed, mapped, measured,
                                          resolve_norm)
from lkverify.certify.steps.timevarying import TimeVaryingRate, UpperBound, sup_in_t

from .conditions_h import decide_h_conditions
from .equations import D, J, a1, a2, eps, eta, gamma, h, nu, omega
from .theorem1_chain import (E1, E2, HW, MEASURES as _MEASURES1, W_, _d_norm, _eig, _eta_norm, _h_of, _j_norm,
                             _Jw, _M_norm, _rational, _scalar, condition11, lemma6)
from .theorem2_functional import M as _M, instance, sigma

__all__ = ["CONCLUSION", "LAMBDA", "MEASURES", "REGION", "chain_steps", "conclusion", "eta_on_region", "find_choices",
           "hdot_young", "mixed_young", "steps"]

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
def _condition15(h_value, nu_value, mu_value=3):
    """(status, L, detail) of (15) at h, ν, μ: L the exact sup of |ḣ|/h^{1+(1−ν)/(μ+1)} (:mod:`.conditions_h`)."""
    res = decide_h_conditions(h_value, nu=nu_value, mu=sympy.Integer(mu_value), budget=10.0)
    r = next(r for r in res if r.name.startswith("(15)"))
    return r.status, r.value, r.detail


def _L15(v, mu_value=3):
    status, L, _ = _condition15(_h_of(v), sympy.sympify(v["nu"]), int(mu_value))
    return L if status is Status.EXACT and L is not None else sympy.Symbol("L_undecided", positive=True)


def _definitions(mu_value):
    """The named constants of the steps: the extreme eigenvalues of J and D, and L of (15) with this μ."""
    L = _L15 if mu_value == 3 else functools.partial(_L15, mu_value=mu_value)
    return {j_min: _eig("J", "min"), j_max: _eig("J", "max"), d_min: _eig("D", "min"), d_max: _eig("D", "max"),
            L15: L}


DEFINITIONS = _definitions(3)

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


def _condition15_rule(mu_value):
    """The decided condition (15) |ḣ| ≤ L h^{1+(1−ν)/(μ+1)} at the run's h, ν and this μ (a rewrite's lemma)."""
    def condition15(ctx) -> Condition:
        status, L, detail = _condition15(_h_of(ctx.values), sympy.sympify(ctx.values["nu"]), mu_value)
        if L is None:
            return Condition("(15) |ḣ| ≤ L h^(1+(1−ν)/(μ+1)) for t ≥ 0, some L",
                             Status.UNDECIDED if status is Status.EXACT else status, detail)
        return Condition(f"(15) |ḣ| ≤ L h^(1+(1−ν)/(μ+1)) for t ≥ 0 with L = {L}", status, detail)

    condition15.__doc__ = (f"(15) |ḣ| ≤ L h^{{1+(1−ν)/(μ+1)}} for t ≥ 0 at the run's h, ν, μ = {mu_value}, decided "
                           f"exactly (L the exact sup).")
    return condition15


condition15 = _condition15_rule(3)


def q_lower(ctx) -> Condition:
    """ωᵀDω ≥ λ_min(D)‖ω‖² ≥ 0: D − λ_min(D)I ⪰ 0 and λ_min(D) ≥ 0, decided exactly (so |ωᵀDω| = ωᵀDω)."""
    Dm = sympy.Matrix(ctx.at(D))
    dmin = _eig("D", "min")(ctx.values)
    res = matrix_positive_definite(Dm - dmin * sympy.eye(Dm.shape[0]), name="D − λ_min I", semidefinite=True)
    ok = res.status.is_proof and sympy.sympify(dmin) >= 0
    return Condition(f"ωᵀDω ≥ {dmin}‖ω‖² (D − λ_min(D)I ⪰ 0, λ_min(D) ≥ 0)",
                     res.status if ok else Status.FAILED, "" if ok else res.detail)


def q_upper(ctx) -> Condition:
    """|ωᵀDω| ≤ λ_max(D)‖ω‖²: λ_max(D)I − D ⪰ 0 and D ⪰ 0 (so |ωᵀDω| = ωᵀDω), decided exactly."""
    Dm = sympy.Matrix(ctx.at(D))
    dmax = _eig("D", "max")(ctx.values)
    top = matrix_positive_definite(dmax * sympy.eye(Dm.shape[0]) - Dm, name="λ_max I − D", semidefinite=True)
    low = matrix_positive_definite(Dm, name="D", semidefinite=True)
    bad = [r for r in (top, low) if not r.status.is_proof]
    return Condition(f"|ωᵀDω| ≤ {dmax}‖ω‖² (λ_max(D)I − D ⪰ 0, D ⪰ 0)",
                     Status.FAILED if bad else Status.EXACT if all(r.status is Status.EXACT for r in (top, low))
                     else Status.CERTIFIED, "; ".join(r.detail for r in bad))


# ---- the Young splits, derived by hand for σ ≥ μ (the rules check each) ----------------------------
def _larger_first(one, two):
    """Two (x, p) factors of a Young pair, the one with the larger power of its e_i first (ties: e1 first)."""
    return (one, two) if one[2] >= two[2] else (two, one)


def hdot_young(sg, mu_value=None) -> tuple:
    """The two Young steps of the ḣ-term: c·h^{(μν+1)/(μ+1)} w e1^a e2^{σ−a} into h w^{μ+1} and h^ν e_i^{σ(μ+1)/μ}.

    First, for each a = σ … 0, x = h^{1/(μ+1)}w, y = h^{μν/(μ+1)}e1^a e2^{σ−a} with (p, q) = (μ+1, (μ+1)/μ)
    and weight η_h: xy ≤ η_h h w^{μ+1}/(μ+1) + μ/(μ+1)·η_h^{−1/μ} h^ν e1^{a(μ+1)/μ} e2^{(σ−a)(μ+1)/μ}; then
    each mixed product (0 < a < σ) by (p, q) = (σ/a, σ/(σ−a)) with weight 1 into (a/σ)h^ν e1^{σ(μ+1)/μ} +
    ((σ−a)/σ)h^ν e2^{σ(μ+1)/μ}.  The h-powers add up for every ν: (15) gives h^{ν−1}|ḣ| ≤ L h^{ν+(1−ν)/(μ+1)}
    and ν + (1−ν)/(μ+1) = 1/(μ+1) + μν/(μ+1).  For σ = μ (``mu_value`` None or σ) the powers are w^{σ+1} and
    e_i^{σ+1}; for σ > μ the chain then lowers e_i^{σ(μ+1)/μ} ≤ δ1^{(σ−μ)/μ}e_i^{σ+1} on the region
    (:class:`~lkverify.certify.steps.rewrites.OnRegion`) and the damping meets h w^{μ+1} itself (:func:`_damping`).

    Examples
    --------
    >>> first, second = hdot_young(5)
    >>> len(first.pairs), len(second.pairs), first.pairs[1][2:4]
    (6, 4, (6, 6/5))
    >>> hdot_young(5, 3)[0].pairs[1][2:4]
    (4, 4/3)
    """
    s = sympy.Integer(sg)
    r = s if mu_value is None else sympy.Integer(mu_value)
    first = YoungEach(tuple((hh ** (1 / (r + 1)) * w, hh ** (r * nu / (r + 1)) * e1**a * e2 ** (s - a), r + 1,
                             (r + 1) / r, eta_h) for a in range(sg, -1, -1)))
    second = []
    for a in range(sg - 1, 0, -1):
        (x, p, _), (y, qq, _) = _larger_first((hh ** (a * nu / s) * e1 ** (a * (r + 1) / r), s / a, a),
                                              (hh ** ((s - a) * nu / s) * e2 ** ((s - a) * (r + 1) / r), s / (s - a),
                                               s - a))
        second.append((x, y, p, qq, 1))
    return first, YoungEach(tuple(second))


def mixed_young(sg, shift=0) -> tuple:
    """The two Young steps of c·h^{ν+s}w²(a1e1 + a2e2)^{σ−1} into h^{ν+s}w^{σ+1} and h^{ν+s}e_i^{σ+1} (s = ``shift``).

    First, for each monomial e1^a e2^{σ−1−a} (the pure ones first), x = h^{2(ν+s)/(σ+1)}w²,
    y = h^{(σ−1)(ν+s)/(σ+1)}e1^a e2^{σ−1−a} with (p, q) = ((σ+1)/2, (σ+1)/(σ−1)) and weight η_w:
    xy ≤ 2η_w x^p/(σ+1) + (σ−1)/(σ+1)·η_w^{−2/(σ−1)} y^q; then each mixed e1^{a(σ+1)/(σ−1)}e2^{…} by
    (p, q) = ((σ−1)/a, (σ−1)/(σ−1−a)) with weight 1.  Summed over the binomial expansion (Σ_a a·C(n,a)a1^a a2^{n−a}
    = n a1(a1+a2)^{n−1}) this is :func:`_mixed`.

    Examples
    --------
    >>> first, second = mixed_young(5)
    >>> [p[2:4] for p in first.pairs[:1]], len(second.pairs)
    ([(3, 3/2)], 3)
    """
    s, n = sympy.Integer(sg), nu + shift
    order = [sg - 1, 0, *range(sg - 2, 0, -1)]
    first = YoungEach(tuple((hh ** (2 * n / (s + 1)) * w**2, hh ** ((s - 1) * n / (s + 1)) * e1**a * e2 ** (sg - 1 - a),
                             (s + 1) / 2, (s + 1) / (s - 1), eta_w) for a in order))
    second = []
    for a in range(sg - 2, 0, -1):
        b = s - 1 - a
        (x, p, _), (y, qq, _) = _larger_first((hh ** (a * n / (s - 1)) * e1 ** (a * (s + 1) / (s - 1)), (s - 1) / a, a),
                                              (hh ** (b * n / (s - 1)) * e2 ** (b * (s + 1) / (s - 1)), (s - 1) / b, b))
        second.append((x, y, p, qq, 1))
    return first, YoungEach(tuple(second))


def _mixed(c, sg, shift=0):
    """c·h^{ν+s}w²(a1e1 + a2e2)^{σ−1} after :func:`mixed_young`, in closed form."""
    s, A = sympy.Integer(sg), a1 + a2
    core = (A ** (s - 1) * eta_w * w ** (s + 1)
            + (s - 1) / 2 * eta_w ** (-2 / (s - 1)) * A ** (s - 2) * (a1 * e1 ** (s + 1) + a2 * e2 ** (s + 1)))
    out = c * hh**nu * core * 2 / (s + 1)
    return out * hh if shift else out


def _cross_term(sign, sg=3):
    """γh^ν‖η‖^{σ−1}ωᵀJη ≷ ±γ‖J‖((a1 + a2)δ1)^{σ−1} h^ν Σ a_i(w² + e_i²)/2 (Cauchy–Schwarz, l on the region, Young)."""
    young = YoungEach(tuple((hh ** (nu / 2) * w, hh ** (nu / 2) * x, 2, 2, 1) for x in (e1, e2)))
    on_region = UpperBound("l", (a1 + a2) * delta1, eta_on_region, "‖η‖ ≤ (a1 + a2)δ1 on the region")
    c = gamma * hh**nu * j_max * (a1 + a2) ** (sg - 1) * delta1 ** (sg - 1)
    return TermBound("γh^ν‖η‖^{σ−1}ωᵀJη", sign * c * (a1 * (w**2 + e1**2) + a2 * (w**2 + e2**2)) / 2,
                     CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J,
                                   factor=gamma * hh**nu * l ** (sg - 1), operator_norm=_j_norm),
                     then=(on_region, young))


def _bounds(which, sg=3):
    """The term bounds of V ≥ L (``"min"``) or V ≤ U (``"max"``) of (16)."""
    jj = j_min if which == "min" else j_max
    return [
        TermBound("½ωᵀJω", jj / 2 * w**2,
                  Rayleigh(omega(t), J, factor=sympy.Rational(1, 2), eigenvalue=_eig("J", which), norm_squared=w**2)),
        TermBound("(a1/2)‖s1−r1‖²", a1 / 2 * e1**2, Equal(a1 / 2 * e1**2)),
        TermBound("(a2/2)‖s2−r2‖²", a2 / 2 * e2**2, Equal(a2 / 2 * e2**2)),
        _cross_term(-1 if which == "min" else 1, sg),
    ]


def _damping(m, sg=None):
    """−(μ+1)hW = −(μ+1)h(ωᵀDω)^k ≤ −(μ+1)λ_min(D)^k h w^{μ+1}, k = (μ+1)/2: a Rayleigh quotient, then q ≥ λ_min w².

    Only even powers of q = |ωᵀDω| go into a rule's factor (q^{2i} = (ωᵀDω)^{2i} exactly): for k even the
    quotient is [q]ᵀ[q]·q^{k−2}, for k odd it is ωᵀDω·q^{k−1}.  For σ > μ the power is then raised on the
    region w ≤ δ_ω on half of the term (:class:`~lkverify.certify.steps.rewrites.RaiseOnRegion`, the factor
    ≤ 0): −w^{μ+1} ≤ −½w^{μ+1} − ½δ_ω^{μ−σ}w^{σ+1}, so the damping meets both the ḣ-term's h w^{μ+1} and the
    h^ν w^{σ+1} of the other Young splits (the paper's step "if σ ≥ μ").
    """
    k = (m + 1) / 2
    sg = m if sg is None else sg
    if k % 2 == 0:
        rule = Rayleigh(sympy.Matrix([quad(omega(t), D)]), sympy.eye(1), factor=-(m + 1) * hh * q ** (k - 2),
                        eigenvalue=1, norm_squared=q**2)
    else:
        rule = Rayleigh(omega(t), D, factor=-(m + 1) * hh * q ** (k - 1), eigenvalue=d_min, norm_squared=w**2)
    then = (LowerBound("q", d_min * w**2, q_lower, "ωᵀDω ≥ λ_min(D)‖ω‖²"),)
    if sg > m:  # half kept (it meets the ḣ-term's h w^{μ+1}), half raised to w^{σ+1}
        half = sympy.Rational(1, 2)
        raised = -(m + 1) * d_min**k * hh * half * (w ** (m + 1) + delta_w ** (m - sg) * w ** (sg + 1))
        return TermBound("−(μ+1)hW", raised, rule, then=(*then, RaiseOnRegion("w", sg + 1, share=half)))
    return TermBound("−(μ+1)hW", -(m + 1) * d_min**k * hh * w ** (m + 1), rule, then=then)


def _hdot_term(m, sg, tree):
    """γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη: Cauchy–Schwarz, (15) with μ, the tree l ≤ a1e1 + a2e2, :func:`hdot_young`
    (for σ > μ then e_i^{σ(μ+1)/μ} ≤ δ1^{(σ−μ)/μ}e_i^{σ+1} on the region)."""
    s, A = sympy.Integer(sg), a1 + a2
    r = sympy.Integer(m) if sg > m else s  # σ < μ: the σ-split all the same (the conclusion breaks)
    fifteen = UpperBound("hw", L15 * hh ** (1 + (1 - nu) / (m + 1)) * w, _condition15_rule(int(m)),
                         "(15): |ḣ|‖ω‖ ≤ L h^(1+(1−ν)/(μ+1))‖ω‖")
    lower = (OnRegion("e1", s + 1), OnRegion("e2", s + 1)) if r < s else ()
    bound = gamma * nu * j_max * L15 * (eta_h * A**s * hh * w ** (r + 1) / (r + 1)
                                        + r / (r + 1) * eta_h ** (-1 / r) * delta1 ** ((s - r) / r) * A ** (s - 1)
                                        * hh**nu * (a1 * e1 ** (s + 1) + a2 * e2 ** (s + 1)))
    return TermBound("γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη", bound,
                     CauchySchwarz(h(t).diff(t) * omega(t), eta, (measured(HW), _eta_norm), matrix=J,
                                   factor=gamma * nu * hh ** (nu - 1) * l ** (sg - 1), operator_norm=_j_norm),
                     then=(fifteen, tree, *hdot_young(sg, r), *lower))


def _grad_term(m, sg, tree, region):
    """−γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη, grad W = (μ+1)q^j Dω with j = (μ−1)/2 (q^{2i} in the factor, as in :func:`_damping`).

    j odd: Cauchy–Schwarz on ωᵀDω and on (Dω)ᵀη (a product); j even: on (Dω)ᵀη; then q ≤ λ_max(D)w² (j > 1),
    ‖η‖^{σ−1} ≤ (a1+a2)δ1·(a1e1 + a2e2)^{σ−2}, w^μ ≤ δ_ω^{μ−2}w² on the region and :func:`mixed_young` (h^{ν+1}).
    """
    j = (m - 1) / 2
    dw = CauchySchwarz(D * omega(t), eta, (mapped(D, measured(W_), _d_norm), _eta_norm))
    base = -(m + 1) * gamma * hh ** (nu + 1) * l ** (sg - 2) * l2
    if j % 2 == 1:
        rule = ProductCS(CauchySchwarz(omega(t), omega(t), (measured(W_), measured(W_)), matrix=D, operator_norm=_d_norm),
                         dw, factor=base * q ** (j - 1))
    else:
        rule = CauchySchwarz(D * omega(t), eta, (mapped(D, measured(W_), _d_norm), _eta_norm), factor=base * q**j)
    upper_q = (UpperBound("q", d_max * w**2, q_upper, "|ωᵀDω| ≤ λ_max(D)‖ω‖²"),) if j > 1 else ()
    c = (m + 1) * gamma * d_max ** ((m + 1) / 2) * (a1 + a2) * delta1 * delta_w ** (m - 2)
    return TermBound("−γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη", _mixed(c, sg, shift=1), rule,
                     then=(*upper_q, region, tree, OnRegion("w", 2), *mixed_young(sg, 1)))


def _vdot_bounds(m=3, sg=3):
    """V̇ ≤ W term by term on the structured V̇ of :mod:`.theorem2_functional` (its seven terms), μ = m, σ = sg."""
    tree = UpperBound("l", a1 * e1 + a2 * e2, eta_tree, "‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖")
    young = mixed_young(sg)
    k = (sympy.Integer(sg) + 1) / 2
    six = LowerBound("l", sympy.sqrt(eps * (a1**2 * e1**2 + a2**2 * e2**2)), lemma6,
                     "(6): ‖η‖² ≥ ε(a1²‖s1−r1‖² + a2²‖s2−r2‖²)")
    region = UpperBound("l2", (a1 + a2) * delta1, eta_on_region, "‖η‖ ≤ (a1 + a2)δ1 on the region")
    more = (tree,) if sg > 3 else ()  # ‖η‖^{σ−3} in the ηᵀM-term
    return [
        _damping(m, sg),
        _hdot_term(m, sg, tree),
        TermBound("−γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)", _mixed((sg - 1) * gamma * j_max * (a1 + a2), sg),
                  ProductCS(CauchySchwarz(eta, _M, (_eta_norm, _M_norm)),
                            CauchySchwarz(omega(t), eta, (measured(W_), _eta_norm), matrix=J, operator_norm=_j_norm),
                            factor=-(sg - 1) * gamma * hh**nu * l ** (sg - 3)),
                  then=(*more, *young)),
        TermBound("−γh^ν‖η‖^{σ−1}(ω×Jω)ᵀη", _mixed(gamma * j_max * (a1 + a2) * delta1, sg),
                  CauchySchwarz(omega(t).cross(J * omega(t)), eta, (crossed(measured(W_), _Jw), _eta_norm),
                                factor=-gamma * hh**nu * l ** (sg - 2) * l2),
                  then=(region, tree, *young)),
        _grad_term(m, sg, tree, region),
        TermBound("−γh^ν‖η‖^{σ+1}", -gamma * eps**k * hh**nu * (a1**2 * e1**2 + a2**2 * e2**2) ** k,
                  Rayleigh(eta, sympy.eye(3), factor=-gamma * hh**nu * l ** (sg - 1), eigenvalue=1, norm_squared=l**2),
                  then=(six,)),
        TermBound("−γh^ν‖η‖^{σ−1}ωᵀJM", _mixed(gamma * j_max * (a1 + a2), sg),
                  CauchySchwarz(omega(t), _M, (measured(W_), _M_norm), matrix=J, factor=-gamma * hh**nu * l ** (sg - 1),
                                operator_norm=_j_norm),
                  then=(tree, *young)),
    ]


def chain_steps(mu_value=3, sigma_value=None):
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 2 on :data:`REGION` for W of order μ + 1 and ‖η‖^{σ−1} in V.

    μ, σ odd integers ≥ 3 (σ = μ unless given).  The splits are derived for σ ≥ μ (for σ > μ the damping is
    raised on the region, :func:`_damping`); with σ < μ the steps are built all the same (V's terms with σ, the
    damping with μ) and the checks say where the chain breaks (at the conclusion).

    Examples
    --------
    >>> [s.role for s in chain_steps(5)]
    ['lower', 'upper', 'vdot']
    """
    inst = instance(mu_value, sigma_value)
    m, sg = inst.mu, inst.sigma
    return lyapunov_steps(inst.functional, inst.system, _bounds("min", sg), _bounds("max", sg), _vdot_bounds(m, sg),
                          MEASURES, region=REGION, definitions=_definitions(int(m)), derivation=inst.derivation,
                          witness_time=1)


steps = chain_steps()


def conclusion(sigma_value=3) -> TimeVaryingRate:
    """V̇ ≤ −α8 h^ν V^λ, λ = (σ+1)/2, on the region for 0 < h ≤ sup h, the algebraic envelope; (11) decided.

    Examples
    --------
    >>> conclusion(5).lam
    3
    """
    return TimeVaryingRate(("w", "e1", "e2"), "hh", nu, alpha8, conditions=condition11,
                           lam=(sympy.Integer(sigma_value) + 1) / 2)


#: V̇ ≤ −α8 h^ν V^λ on the region for 0 < h ≤ sup h, the algebraic envelope; (11) makes it tend to 0
CONCLUSION = TimeVaryingRate(("w", "e1", "e2"), "hh", nu, alpha8, conditions=condition11, lam=LAMBDA)


def find_choices(values, box=None, *, mu=3, sigma=None) -> dict:
    """γ, ε, δ1, δ_ω, η_w, η_h, α8 at the run's values (exact strings), in closed form (no optimisation).

    For W of order μ + 1 and ‖η‖^{σ−1} in V (σ = μ unless given; k_μ = (μ+1)/2, λ = (σ+1)/2):
    ε = δ1 = δ_ω = 1/2 unless given; H = sup_{t≥0} h exactly, L of (15) exact.  The e_i^{σ+1}-terms of W:
    −γε^λ a_i^{σ+1}h^ν from Lemma 1 against γ·(νjL·σ/(σ+1)·η_h^{−1/σ}A^{σ−1}a_i + K(σ−1)/(σ+1)·η_w^{−2/(σ−1)}
    A^{σ−2}a_i)h^ν, A = a1 + a2, K = jA(σ + δ1) + (μ+1)d_max^{k_μ}Aδ1δ_ω^{μ−2}H (the ηᵀM-, ω×Jω-, M- and
    grad W-terms): η_h and η_w give each a quarter of ε^λ a_min^{σ+1} (γ cancels).  The w^{σ+1}-terms:
    γ(νjLη_hA^σ/(σ+1) + 2Kη_wA^{σ−1}H^{ν−1}/(σ+1)) ≤ (μ+1)d_min^{k_μ}/2 (half of the damping), and γ at
    most the (16) choice.  Then W ≤ −((μ+1)/2)d_min^{k_μ}h w^{μ+1} − (γε^λa_min^{σ+1}/2)h^ν e_i^{σ+1} and α8
    is 9/10 of min(((μ+1)/2)d_min^{k_μ}H^{1−ν}/ū_w^λ, γε^λa_min^{σ+1}/(2ū_e^λ))/3^{λ−1} (U^λ ≤ 3^{λ−1}Σū_k^λx_k^{2λ},
    ū the sups of U's coefficients), rounded down.  Floating point only picks the numbers: every step is
    proved at them.  (μ = σ = 3: the catalogued item.)

    σ > μ: the ḣ-term is split with (μ+1, (μ+1)/μ) (:func:`hdot_young`): its e-part carries δ1^{(σ−μ)/μ} and
    μ/(μ+1)·η_h^{−1/μ} (η_h takes its quarter with these), its w-part γνjLη_hA^σ/(μ+1)·h w^{μ+1} is at most
    a quarter of the damping (μ+1)d_min^{k_μ}, which keeps half of itself at h w^{μ+1} and raises half to
    ½(μ+1)d_min^{k_μ}δ_ω^{μ−σ}h w^{σ+1}; the mixed terms take at most half of that, and the other half,
    ¼(μ+1)d_min^{k_μ}δ_ω^{μ−σ}, is the w-margin of α8 in place of ((μ+1)/2)d_min^{k_μ}.

    With ``box`` (name → (lo, hi), from a run over a box) the boxed a1, a2 enter at their worst ends for
    each use, as the chain's coefficients enclosed over the box see them: a_min the smallest lower end
    (the −γε^λ margins), a_max and a1 + a2 the largest upper ends (every positive coefficient); ε, δ1,
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

    m, s = int(mu), int(mu if sigma is None else sigma)
    km, lam = (m + 1) / 2, (s + 1) / 2
    eps_, d1, dw = r("eps", "1/2"), r("delta1", "1/2", 1), r("delta_w", "1/2", 1)
    H, _ = sup_in_t(_h_of(values))
    H = float(H) if H is not None and H.is_number and H.is_finite else 1.0
    nu_ = float(values["nu"])
    L = float(_L15(values, m)) if _L15(values, m).is_number else 1.0  # (15) fails or undecided: the step says so
    jmin, jmax, dmin, dmax = (float(_eig(M_, k)(values)) for M_ in ("J", "D") for k in ("min", "max"))
    ends = [box.get(k, (values[k], values[k])) for k in ("a1", "a2")]
    a_lo, a_hi = min(float(lo) for lo, _ in ends), max(float(hi) for _, hi in ends)
    a, e_k = sum(float(hi) for _, hi in ends), float(eps_) ** lam
    margin = e_k * a_lo ** (s + 1)  # ε^λ a_min^{σ+1}
    K = jmax * a * (s + float(d1)) + (m + 1) * dmax**km * a * float(d1) * float(dw) ** (m - 2) * H
    rr = m if s > m else s  # the ḣ-term's Young pair (μ+1, (μ+1)/μ) for σ > μ (:func:`hdot_young`)
    low = float(d1) ** ((s - rr) / rr)  # δ1^{(σ−μ)/μ} of e_i^{σ(μ+1)/μ} lowered to e_i^{σ+1}
    et_h = _rational((4 * rr * nu_ * jmax * L * low * a ** (s - 1) * a_hi / ((rr + 1) * margin)) ** rr, up=True)
    et_w = _rational((4 * (s - 1) * K * a ** (s - 2) * a_hi / ((s + 1) * margin)) ** ((s - 1) / 2), up=True)
    hdot_w = nu_ * jmax * L * float(et_h) * a**s / (rr + 1)  # per γ: at h w^{μ+1} (σ > μ) or h w^{σ+1}
    mixed_w = 2 * K * a ** (s - 1) * float(et_w) * H ** (nu_ - 1) / (s + 1)  # per γ: at h w^{σ+1}
    c16 = jmax * a ** (s - 1) * float(d1) ** (s - 1) * H**nu_
    C = (m + 1) * dmin**km
    if s > m:  # half of the damping kept at w^{μ+1}, half raised to δ_ω^{μ−σ}w^{σ+1} (:func:`_damping`)
        damping = C / 4 * float(dw) ** (m - s)  # what is left at w^{σ+1}
        g_w = min(C / 4 / hdot_w, damping / mixed_w)
    else:
        damping = C / 2
        g_w = damping / (hdot_w + mixed_w)
    g = _rational(min(g_w, 0.5 * min(jmin / (c16 * a), 1 / c16)))
    u_w, u_e = jmax / 2 + float(g) * c16 * a / 2, a_hi / 2 * (1 + float(g) * c16)
    alpha = _rational(0.9 * min(damping * H ** (1 - nu_) / u_w**lam, float(g) * margin / (2 * u_e**lam))
                      / 3 ** (lam - 1))
    return {"gamma": str(g), "eps": str(eps_), "delta1": str(d1), "delta_w": str(dw), "eta_w": str(et_w),
            "eta_h2": str(et_h), "alpha8": str(alpha)}
