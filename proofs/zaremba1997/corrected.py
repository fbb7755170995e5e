"""The corrected step (3.10′) of Theorem 2 (paper 004) and the additional hypothesis it needs.

(3.10) is false along the loop: T4 = d/dt ½‖η‖² keeps −ηᵀ(v × Mω) (:mod:`.theorem2`), a cubic term
no choice of α dominates globally.  Keeping it, along the loop (exact, in the ring of the abstract
loop):

    V̇ = R′ − A − B − C,
    R′ = −λ_cvᵀMv − (λ_c/4)‖η‖² − (λ_c/4)λ‖θ_e‖²_Γ⁻¹ − K_pΛeᵀe                       (3.10′)
    A  = (α − c)‖v‖² − λ_cvᵀMz + (λ_c/4)‖z‖² + (λ_c/2)‖Mv − ε‖²,   z = φᵀθ_e,  c = σ_M²W²/λ_c,
    B  = (λ_c/4)‖η + (2/λ_c)(v × Mω)‖²,
    C  = c‖v‖² − ‖v × Mω‖²/λ_c.

A ⪰ 0 iff α − c ≥ λ_cσ_M² (the Schur complement of the printed step); B is a square; C ≥ 0 wherever
‖ω‖ ≤ W, by Lagrange's identity ‖v × Mω‖² = ‖v‖²‖Mω‖² − (vᵀMω)² and σ_M²I − M² ⪰ 0.  So
**V̇ ≤ R′ wherever ‖ω‖ ≤ W**, for W ≤ W* = (λ_c(α − λ_cσ_M²))^{1/2}/σ_M — (λ_c/2)‖η‖² of the print
becomes (λ_c/4)‖η‖².

Where is ‖ω‖ ≤ W?  ω = v + ω_d − Λe, ‖ω_d(t)‖ ≤ w̄ (:func:`~lkverify.certify.steps.signals.sup_bound`),
‖v‖² ≤ 2V/σ_m, and ‖e‖ ≤ Σkᵢ‖(sᵢ − cᵢ) × cᵢ‖ ≤ Σkᵢ‖sᵢ − cᵢ‖ ≤ (Σkᵢ·V_δ)^{1/2} ≤ (2ΣkᵢV/K_p)^{1/2}
(Cauchy–Schwarz; V ≥ ½vᵀMv and V ≥ ½K_pV_δ because Γ⁻¹ ≻ 0, property (a) of (3.4)).  Hence on
{V ≤ V0}: ‖ω‖ ≤ w̄ + κ_V·V0^{1/2} with κ_V = (2/σ_m)^{1/2} + Λ(2Σkᵢ/K_p)^{1/2}, which is ≤ W for
V0 ≤ ((W − w̄)/κ_V)².  **The additional hypothesis** (derived; the paper has only α > λ_cσ_M²):
W* > w̄, i.e. α > λ_cσ_M² + σ_M²w̄²/λ_c; the statement is then semi-global: initial data with
V(0) < V0.  Every irrational number (W*, w̄, κ_V) is rounded to a rational on the safe side.
"""

from __future__ import annotations

import math

import sympy

from lkverify import Result, Status, cross, dot
from lkverify.certify.matrices import matrix_positive_definite
from lkverify.certify.steps.signals import sup_bound
from lkverify.symbolic.polynomial import compare_polynomials as compare

from .equations import lam

__all__ = ["level_constants", "additional_hypotheses", "corrected_results", "sqrt_up", "sqrt_down", "young_form_psd"]

_DIGITS = 10 ** 6


def _sqrt_rational(q, up: bool) -> sympy.Rational:
    """√q itself when it is rational, else the 6-decimal rational just above (``up``) or below it."""
    q = sympy.Rational(q)
    if q < 0:
        raise ValueError(f"sqrt_{'up' if up else 'down'}: expected q ≥ 0, got {q}")
    n, d = q.p, q.q
    root = sympy.Rational(math.isqrt(n * d), d)
    if root ** 2 == q:
        return root
    r = sympy.Rational(math.isqrt(n * _DIGITS ** 2 // d) + (1 if up else 0), _DIGITS)
    assert (r ** 2 >= q) if up else (r ** 2 <= q)
    return r


def sqrt_up(q) -> sympy.Rational:
    """A rational r ≥ √q (q ≥ 0 rational), within 10⁻⁶.

    >>> sqrt_up(2), sqrt_up(2) ** 2 >= 2, sqrt_up(sympy.Rational(9, 4))
    (707107/500000, True, 3/2)
    """
    return _sqrt_rational(q, up=True)


def sqrt_down(q) -> sympy.Rational:
    """A rational 0 ≤ r ≤ √q (q ≥ 0 rational), within 10⁻⁶.

    >>> sqrt_down(2), sqrt_down(2) ** 2 <= 2
    (1414213/1000000, True)
    """
    return _sqrt_rational(q, up=False)


def level_constants(values) -> dict:
    """σ_m, σ_M, w̄ ≥ sup‖ω_d‖, W ≤ W*, c = σ_M²W²/λ_c, κ_V, V0 and the additional hypothesis' margin (exact).

    ``w_bar`` is None (and ``status`` undecided) when no bound of ω_d can be read off.
    """
    M = sympy.Matrix(values["M"])
    eig = M.eigenvals(multiple=True)
    s_m, s_M = min(eig), max(eig)
    lc, al, kp, L = (sympy.sympify(values[k]) for k in ("lam_c", "alpha", "Kp", "Lam"))
    ks = [sympy.sympify(values[k]) for k in ("k1", "k2", "k3")]
    sups = [sup_bound(sympy.sympify(values[f"wd{i}"])) for i in (1, 2, 3)]
    out = {"sigma_m": s_m, "sigma_M": s_M, "w_bar": None, "status": Status.UNDECIDED, "margin": None}
    gap = lc * (al - lc * s_M ** 2)
    if any(b is None or not b.is_Rational for b in sups) or not all(x.is_Rational for x in (s_m, s_M, gap)):
        out["why"] = ("no rational bound of sup‖ω_d‖ (or of σ_m, σ_M) read off: ω_d = "
                      + ", ".join(str(values[f"wd{i}"]) for i in (1, 2, 3)))
        return out
    w_bar = sqrt_up(sum(b ** 2 for b in sups))
    W = sqrt_down(gap) / s_M if gap > 0 else sympy.Integer(0)
    kappa_V = sqrt_up(2 / s_m) + L * sqrt_up(2 * sum(ks) / kp)
    margin = W - w_bar
    V0 = (margin / kappa_V) ** 2 if margin > 0 else sympy.Integer(0)
    V0 = sympy.Rational(math.floor(V0 * 10 ** 8), 10 ** 8) if V0 > 10 ** -8 else V0
    out.update(w_bar=w_bar, W=W, c=s_M ** 2 * W ** 2 / lc, kappa_V=kappa_V, V0=V0, margin=margin,
               status=Status.EXACT if margin > 0 else Status.FAILED,
               threshold=lc * s_M ** 2 + s_M ** 2 * w_bar ** 2 / lc)
    return out


def additional_hypotheses(values) -> list:
    """The hypothesis (3.10′) adds: α > λ_cσ_M² + σ_M²w̄²/λ_c (W* > w̄), with the level V0 it gives."""
    k = level_constants(values)
    name = "additional (derived for (3.10′)): α > λ_cσ_M² + σ_M²w̄²/λ_c, w̄ ≥ sup‖ω_d‖"
    if k["w_bar"] is None:
        return [Result("hypothesis", name, Status.UNDECIDED, None, k["why"])]
    detail = (f"α = {values['alpha']}, λ_cσ_M² + σ_M²w̄²/λ_c = {k['threshold']} (≈ {float(k['threshold']):.4g}; "
              f"w̄ = {k['w_bar']} ≥ sup‖ω_d‖ term by term); W = {k['W']} ≤ (λ_c(α − λ_cσ_M²))^{{1/2}}/σ_M")
    if k["status"] is Status.EXACT:
        detail += (f" > w̄: (3.10′) holds on {{V ≤ V0}}, V0 = {k['V0']} (≈ {float(k['V0']):.3g}; "
                   f"‖ω‖ ≤ w̄ + κ_V·V0^{{1/2}} ≤ W, κ_V = {k['kappa_V']})")
    else:
        detail += " ≤ w̄: no level set of V keeps ‖ω‖ ≤ W"
    return [Result("hypothesis", name, k["status"], {"V0": str(k.get("V0")), "W": str(k.get("W"))}, detail)]


def young_form_psd(a, alpha, name):
    """``alpha``‖v‖² − λ_cvᵀMz + (λ_c/4)‖z‖² + (λ_c/2)‖w‖² ⪰ 0 in (v, w = Mv − ε, z = φᵀθ_e), decided exactly
    (its 9 × 9 matrix; by the Schur complement ⇔ alpha ≥ λ_cσ_M²): the quadratic slack of (3.10) and of (3.10′)."""
    lc = a.q["lam_c"]
    vs, ws, zs = (sympy.Matrix(sympy.symbols(f"{n}1:4", real=True)) for n in ("qv", "qw", "qz"))
    form = alpha * dot(vs, vs) - lc * dot(vs, a.M * zs) + lc / 4 * dot(zs, zs) + lc / 2 * dot(ws, ws)
    H = sympy.hessian(form, list(vs) + list(ws) + list(zs)) / 2
    return matrix_positive_definite(H, name=name, semidefinite=True)


def corrected_results(a, derived, values, *, W=None) -> dict:
    """The exact pieces of (3.10′) at these values: ``identity`` (V̇ = R′ − A − B − C), ``A`` (A ⪰ 0),
    ``lagrange`` (Lagrange's identity and σ_M²I − M² ⪰ 0), ``level`` (the split of V and sᵢ × cᵢ).

    ``W``: the bound of ‖ω‖ (default: the largest this α allows, :func:`level_constants`); the identity
    holds for every W (c cancels), A ⪰ 0 only for W ≤ W*."""
    k = level_constants(values)
    lc, al, kp, L = a.q["lam_c"], a.q["alpha"], a.q["Kp"], a.q["Lam"]
    c = k.get("c", sympy.Integer(0)) if W is None else k["sigma_M"] ** 2 * sympy.Rational(W) ** 2 / lc
    z, mv_e, g = a.ph.T * a.th_e, a.M * a.v - a.ep, cross(a.v, a.M * a.w)
    R1 = [("−λ_cvᵀMv", -lc * dot(a.v, a.M * a.v)), ("−(λ_c/4)‖η‖²", -lc / 4 * dot(a.eta, a.eta)),
          ("−(λ_c/4)λ‖θ_e‖²_Γ⁻¹", -lc / 4 * lam * (a.th_e.T * a.Gm * a.th_e)[0, 0]),
          ("−K_pΛeᵀe", -kp * L * dot(a.e, a.e))]
    A = (al - c) * dot(a.v, a.v) - lc * dot(a.v, a.M * z) + lc / 4 * dot(z, z) + lc / 2 * dot(mv_e, mv_e)
    h = a.eta + 2 * g / lc
    B = lc / 4 * dot(h, h)
    C = c * dot(a.v, a.v) - dot(g, g) / lc
    out = {"identity": compare("(3.10′): V̇ = R′ − A − B − C along the loop", R1 + [("−A", -A), ("−B", -B), ("−C", -C)],
                               [("V̇ derived (T1 + T2 + T3 + T4)", derived["T1"] + derived["T23"] + derived["T4"])],
                               reference="(3.10′) with the remainders A, B, C", R=a.R)}
    res = young_form_psd(a, al - c, "A")
    out["A"] = Result("bound", "A ⪰ 0 (α − c ≥ λ_cσ_M²)", res.status, str(c), f"c = σ_M²W²/λ_c = {c}: {res.detail}")
    x, y = (sympy.Matrix(sympy.symbols(f"{n}1:4", real=True)) for n in ("lx", "ly"))
    lag = compare("Lagrange: ‖x × y‖² + (xᵀy)² = ‖x‖²‖y‖²", [("‖x × y‖²", dot(cross(x, y), cross(x, y))),
                                                            ("(xᵀy)²", dot(x, y) ** 2)],
                  [("‖x‖²‖y‖²", dot(x, x) * dot(y, y))], reference="Lagrange's identity")
    sM = matrix_positive_definite(k["sigma_M"] ** 2 * sympy.eye(3) - a.M ** 2, name="σ_M²I − M²", semidefinite=True)
    out["lagrange"] = Result("bound", "C ≥ 0 where ‖ω‖ ≤ W", Status.weakest([lag.status, sM.status]), None,
                             f"‖v × Mω‖² ≤ ‖v‖²‖Mω‖² ({lag.detail}) ≤ σ_M²W²‖v‖² (σ_M²I − M² ⪰ 0: {sM.detail})")
    cs = [sympy.Matrix(sympy.sympify(values[f"c{i}"])) for i in (1, 2, 3)]
    ss = [sympy.Matrix(sympy.symbols(f"s{i}_1:4", real=True)) for i in (1, 2, 3)]
    unit = all(sympy.simplify(dot(ci, ci) - 1) == 0 for ci in cs)
    shift = [compare(f"(s{i} × c{i})_{j + 1} = ((s{i} − c{i}) × c{i})_{j + 1}", [("s × c", cross(s, ci)[j])],
                     [("(s − c) × c", cross(s - ci, ci)[j])], reference="c × c = 0")
             for i, (s, ci) in enumerate(zip(ss, cs), 1) for j in range(3)]
    st = Status.weakest([r.status for r in shift] + [Status.EXACT if unit else Status.FAILED])
    out["level"] = Result("bound", "‖e‖ ≤ (Σkᵢ·V_δ)^{1/2}", st, None,
                          "sᵢ × cᵢ = (sᵢ − cᵢ) × cᵢ (exact), ‖cᵢ‖ = 1" + ("" if unit else " FAILS")
                          + ", Cauchy–Schwarz: Σkᵢ‖sᵢ − cᵢ‖ ≤ (Σkᵢ)^{1/2}(Σkᵢ‖sᵢ − cᵢ‖²)^{1/2}")
    out["constants"] = k
    return out
