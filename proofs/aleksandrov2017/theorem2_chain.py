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
* The conclusion :data:`CONCLUSION` is :class:`~lkverify.certify.steps.timevarying.TimeVaryingRate`
  with ``lam`` = λ = (σ+1)/2 = 2: W + α8 h^ν n^{λ−1}Σ ū_k^λ x_k^{2λ} ≤ 0 coefficient-wise (U^λ bounded
  by the power mean of its squares) and the algebraic envelope.  It is attempted only when V̇ ≤ W
  is a proved step; that step is not encoded yet (see :data:`LEFT`).

The choices γ, δ1, δ_ω are found at the run's values by :func:`find_choices` (exact rationals; the
steps are then proved at them).
"""

from __future__ import annotations

import sympy

from lkverify import Status, t
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import Region
from lkverify.certify.steps.rules import CauchySchwarz, Condition, Equal, Rayleigh, _resolve_norm, measured
from lkverify.certify.steps.rewrites import YoungEach
from lkverify.certify.steps.timevarying import TimeVaryingRate, UpperBound, sup_in_t

from .equations import J, a1, a2, eta, gamma, nu, omega
from .theorem1_chain import (E1, E2, MEASURES, W_, _eig, _eta_norm, _h_of, _j_norm, _rational, _scalar,
                             condition11)
from .theorem2_functional import functional2, sigma, system4

__all__ = ["CONCLUSION", "LAMBDA", "LEFT", "MEASURES", "REGION", "chain_steps", "eta_on_region", "find_choices",
           "steps"]

delta1 = _scalar("delta1", latex=r"\delta_1", description="region ‖s_i − r_i‖ ≤ δ1 of the V̇ bounds")
delta_w = _scalar("delta_w", latex=r"\delta_\omega", description="region ‖ω‖ ≤ δ_ω of Theorem 2's V̇ bound")
alpha8 = _scalar("alpha8", latex=r"\alpha_8", description="rate of V̇ ≤ −α8 h^ν V^λ (Theorem 2)")

#: λ = (σ + 1)/2 of V̇ ≤ −α8 h^ν V^λ
LAMBDA = (sigma + 1) / 2

# ---- the measures and the region ------------------------------------------------------------------
w, e1, e2, l, hh, hw = (m.symbol for m in MEASURES)  # the measures of Theorem 1's chain (the same vectors)
REGION = Region({E1: delta1, E2: delta1, W_: delta_w})

j_min, j_max = sympy.symbols("j_min j_max", positive=True)
DEFINITIONS = {j_min: _eig("J", "min"), j_max: _eig("J", "max")}

#: what the chain does not encode yet (the theorem's ``unchecked``)
LEFT = ["V̇ ≤ W term by term (α3…α6, δ1: the seven terms of the structured V̇ of theorem2.py with (15) through "
        "UpperBound and Lemma 1), so the conclusion V̇ ≤ −α8 h^ν V^λ (TimeVaryingRate with lam = λ, ready) is not "
        "attempted; α8 is only estimated by sampling (aleksandrov2017.theorem2_example)"]


def eta_on_region(ctx) -> Condition:
    """‖η‖ ≤ a1‖s1−r1‖ + a2‖s2−r2‖ ≤ (a1 + a2)δ1 on the region: the norm tree of η (exact) and e_i ≤ δ1."""
    bound, conds = _resolve_norm(_eta_norm, eta, ctx)
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


def chain_steps():
    """(V ≥ L, V ≤ U) of (16) on :data:`REGION` (V̇ ≤ W: :data:`LEFT`)."""
    common = dict(region=REGION, definitions=DEFINITIONS, witness_time=1)
    total = lambda bounds: sum((tb.bound for tb in bounds), sympy.S.Zero)  # noqa: E731
    lower, upper = _bounds("min"), _bounds("max")
    return (TermwiseBound("V ≥ L", functional2, system4, "V", tuple(lower), total(lower), MEASURES, relation=">=",
                          role="lower", **common),
            TermwiseBound("V ≤ U", functional2, system4, "V", tuple(upper), total(upper), MEASURES, relation="<=",
                          role="upper", **common))


steps = chain_steps()

#: V̇ ≤ −α8 h^ν V^λ on the region for 0 < h ≤ sup h, the algebraic envelope; (11) makes it tend to 0
CONCLUSION = TimeVaryingRate(("w", "e1", "e2"), "hh", nu, alpha8, conditions=condition11, lam=LAMBDA)


def find_choices(values) -> dict:
    """γ, δ1, δ_ω at the run's values (exact strings): δ1 = δ_ω = 1/2 unless given, γ half the largest (16) allows.

    With H = sup_{t≥0} h (exact) and c = ‖J‖(a1 + a2)²δ1² H^ν, L's squares are j_min/2 − γc(a1 + a2)/2 (w²)
    and a_i(1 − γc)/2 (e_i²); γ is the rational ≈ ½ min(j_min/(c(a1+a2)), 1/c), rounded down.

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2017.equations import P
    >>> sorted(find_choices(P.resolve({}, use_defaults=True)))
    ['delta1', 'delta_w', 'gamma']
    """
    d1 = sympy.Rational(values["delta1"]) if values.get("delta1") is not None else sympy.Rational(1, 2)
    dw = sympy.Rational(values["delta_w"]) if values.get("delta_w") is not None else sympy.Rational(1, 2)
    H, _ = sup_in_t(_h_of(values))
    H = float(H) if H is not None and H.is_number and H.is_finite else 1.0
    jmin, jmax = (float(_eig("J", k)(values)) for k in ("min", "max"))
    a = float(values["a1"] + values["a2"])
    c = jmax * a**2 * float(d1) ** 2 * H ** float(values["nu"])
    g = _rational(0.5 * min(jmin / (c * a), 1 / c))
    return {"gamma": str(g), "delta1": str(d1), "delta_w": str(dw)}
