"""The norm inequalities of paper 003's comparison system (:mod:`.comparison`) as checked steps.

Each step is a polynomial claim ``P ≥ 0`` under hypotheses ``hⱼ ≥ 0`` (earlier steps, or the
symbols that are norms, hence ≥ 0) and equalities ``e = 0``, with an explicit certificate
P ≡ Σ cₖ·Π(hypotheses)·qₖ² + Σ mₗ·eₗ, checked by the library's
:func:`lkverify.certify.certificates.inequality_step` (re-exported here).  Two rules link
the steps and are not polynomial: for x, y ≥ 0, x² ≤ y² ⇒ x ≤ y (a norm is the root of its square),
and X ≤ Y ⇒ max(0, X) ≤ max(0, Y).

The chain (names as in the rows; scalars: s = |σ|, d = |σ̇|, w = ‖ω‖, r = ‖V‖, n = ‖u_lin‖₂,
m = ‖u_lin‖_∞, all ≥ 0):

1. |x̃₂ⁱpᵢ| ≤ Vᵢ|pᵢ| (Vᵢ² = x̃₁² + x̃₂²): with the identity d(½Vᵢ²)/dt = −αVᵢ² + x̃₂ⁱpᵢ/β,
   V̇ᵢ ≤ −αVᵢ + |pᵢ|/β;
2. |σᵢ| ≤ Vᵢ, |σ̇ᵢ| ≤ √k0·Vᵢ, |vᵢ| ≤ k0Vᵢ (Cauchy–Schwarz on the rows of T, (k0, k1)T), summed over
   the channels: s ≤ r, d ≤ √k0·r, ‖v‖ ≤ k0r;
3. Cauchy–Schwarz and |x × y| ≤ |x||y| in ℝ³ (Lagrange's identity), the triangle inequality from
   them; ‖Ḃω‖ ≤ 2dw(1 + 3s) from the four terms of Ḃω;
4. ‖a‖ ≤ 2d²(1 + 3s) (with w(1 + s²) = 4d) ≤ 2k0r²(1 + 3r);
5. saturation, case ‖u_lin‖_∞ > a_m (c = a_m/m; else c = 1 and (1 − c)n = 0): m ≤ n ≤ √3m and
   (1 − c)n ≤ √3(n − a_m);
6. ‖p‖ = (1 − c)(1 + s²)n/4 ≤ √3·max(0, ‖v‖ + ‖a‖ − a_m/4) ≤ √3·max(0, g(r));
7. V̇ᵢ ≤ −αVᵢ + f̃, f̃ = (√3/β)max(0, g(r)); ΣVᵢ ≤ √3 r, so D⁺r ≤ −αr + (3/β)max(0, g(r)).
"""

from __future__ import annotations


import sympy

from lkverify import Status
from lkverify.certify.certificates import inequality_step

from .equations import P as _P, alpha, beta, k0, k1

__all__ = ["inequality_step", "norm_steps", "chain_status"]

_R3 = sympy.sqrt(3)


def _val(x, v):
    return sympy.sympify(x).subs({alpha: v["alpha"], beta: v["beta"], _P["a_m"].obj: v["a_m"]})


def _nn(names):
    return sympy.symbols(names, nonnegative=True)


def _rows_channel(v, T, K=None) -> list:
    """Steps 1–2: |x̃₂p| ≤ V|p|; |σᵢ|, |σ̇ᵢ|, |vᵢ| by the rows of T; summed over the channels."""
    x1, x2, p = sympy.symbols("xt1 xt2 p", real=True)
    rows = [inequality_step("|xt2 p| <= V_i |p|", (x1 ** 2 + x2 ** 2) * p ** 2 - x2 ** 2 * p ** 2, [(1, [], x1 * p)],
                            text="(Vᵢ|pᵢ|)² − (x̃₂pᵢ)² = (x̃₁pᵢ)² with Vᵢ² = x̃₁² + x̃₂²: V̇ᵢ ≤ −αVᵢ + |pᵢ|/β")]
    K0, K1 = _val(k0, v), _val(k1, v)
    K = K or {"sigma": 1, "sigmadot": sympy.sqrt(K0), "v": K0}
    label = {"sigma": "", "sigmadot": "sqrt(k0) ", "v": "k0 "}
    for nm, row in (("sigma", T[0, :]), ("sigmadot", T[1, :]), ("v", sympy.Matrix([[K0, K1]]) * T)):
        r1, r2 = row
        gap = K[nm] ** 2 - (r1 ** 2 + r2 ** 2)
        rows.append(inequality_step(f"|{nm}_i| <= {label[nm]}V_i",
                                    K[nm] ** 2 * (x1 ** 2 + x2 ** 2) - (r1 * x1 + r2 * x2) ** 2,
                                    [(gap, [], x1), (gap, [], x2), (1, [], r1 * x2 - r2 * x1)],
                                    text=f"Cauchy–Schwarz with the row {sympy.sstr(row)}: K²‖x̃‖² − (row·x̃)² = "
                                         f"(K² − |row|²)‖x̃‖² + (r₁x̃₂ − r₂x̃₁)², K = {sympy.sstr(K[nm])}"))
        Vs, cs = _nn("V1:4"), _nn("c1:4")
        hyps = [K[nm] ** 2 * Vi ** 2 - ci ** 2 for Vi, ci in zip(Vs, cs)]
        rows.append(inequality_step(f"|{nm}| <= {label[nm]}||V||",
                                    K[nm] ** 2 * sum(Vi ** 2 for Vi in Vs) - sum(ci ** 2 for ci in cs),
                                    [(1, [h], 1) for h in hyps], hyps=hyps,
                                    text=f"summed over the channels: |{nm}|² ≤ {sympy.sstr(K[nm] ** 2)}‖V‖²"))
    return rows


def _rows_vectors() -> list:
    """Step 3: Cauchy–Schwarz, |x × y| ≤ |x||y|, the triangle inequality; ‖Ḃω‖ ≤ 2dw(1 + 3s)."""
    x, y = sympy.Matrix(sympy.symbols("x1:4", real=True)), sympy.Matrix(sympy.symbols("y1:4", real=True))
    xx, yy, xy, cr = (x.T * x)[0], (y.T * y)[0], (x.T * y)[0], x.cross(y)
    nx, ny = _nn("nx ny")
    rows = [inequality_step("Cauchy-Schwarz in R^3", xx * yy - xy ** 2, [(1, [], c) for c in cr],
                            text="|x|²|y|² − (x·y)² = |x × y|² (Lagrange)"),
            inequality_step("|x cross y| <= |x||y|", xx * yy - (cr.T * cr)[0], [(1, [], xy)],
                            text="|x|²|y|² − |x × y|² = (x·y)²"),
            inequality_step("triangle inequality", (nx + ny) ** 2 - (nx ** 2 + 2 * xy + ny ** 2),
                            [(2, [nx * ny - xy], 1)], hyps=[nx * ny - xy],
                            text="|x + y|² = |x|² + 2x·y + |y|² ≤ (|x| + |y|)² by Cauchy–Schwarz")]
    s, d, w = _nn("s d w")
    t = _nn("t1:5")
    hyps = [2 * s * d * w - t[0], 2 * d * w - t[1], 2 * d * s * w - t[2], 2 * s * d * w - t[3]]
    rows.append(inequality_step("|B_rate omega| <= 2 d w (1 + 3 s)", 2 * d * w * (1 + 3 * s) - sum(t),
                                [(1, [h], 1) for h in hyps], hyps=hyps,
                                text="Ḃω = −2(σ·σ̇)ω + 2σ̇×ω + 2σ̇(σ·ω) + 2σ(σ̇·ω): the triangle inequality and the "
                                     "term norms tₖ ≤ 2sdw, 2dw, 2dsw, 2sdw (Cauchy–Schwarz, |σ̇×ω| ≤ dw)"))
    return rows


def _rows_a(v, cube=3) -> list:
    """Step 4: ‖a‖ ≤ 2d²(1 + 3s) ≤ 2k0r²(1 + 3r)."""
    s, d, w, na, r = _nn("s d w na r")
    K0 = _val(k0, v)
    h = d * w * (1 + 3 * s) / 2 - na
    eq = w * (1 + s ** 2) - 4 * d
    rows = [inequality_step("|a| <= 2 d^2 (1 + 3 s)", 2 * d ** 2 * (1 + 3 * s) - na,
                            [(1, [h], 1), (sympy.Rational(1, 2), [d, w], s), (sympy.Rational(3, 2), [s, d, w], s)],
                            hyps=[h, s, d, w], eqs=[eq], cert_eq=[(-d * (1 + 3 * s) / 2, eq)],
                            text="‖a‖ = ¼‖Ḃω‖ ≤ ½dw(1 + 3s) and w(1 + s²) = 4d (‖ω‖ = ‖D(σ)σ̇‖)")]
    h1, h2 = K0 * r ** 2 - d ** 2, r - s
    rows.append(inequality_step("2 d^2 (1 + 3 s) <= 2 k0 r^2 (1 + 3 r)",
                                2 * K0 * r ** 2 * (1 + 3 * r ** (cube - 2)) - 2 * d ** 2 * (1 + 3 * s),
                                [(2, [h1], 1), (6, [s, h1], 1), (6 * K0, [h2], r)], hyps=[h1, h2, s, r],
                                text="d² ≤ k0r², s ≤ r"))
    return rows


def _rows_saturation(v, root3=_R3, quarter=sympy.Rational(1, 4)) -> list:
    """Steps 5–7: the saturation factor, ‖p‖, the majorant f̃ and D⁺‖V‖."""
    u = sympy.symbols("u1:4", real=True)
    m, n, am = *_nn("m n"), sympy.sympify(v["a_m"])
    hyp_u = [m ** 2 - ui ** 2 for ui in u]
    rows = [inequality_step("|u|_inf <= |u|_2", sum(ui ** 2 for ui in u) - u[0] ** 2, [(1, [], u[1]), (1, [], u[2])],
                            text="a component is at most the norm (‖u‖_∞ ≤ ‖u‖₂, and |pᵢ| ≤ ‖p‖ in the step V̇ᵢ ≤ −αVᵢ + f̃): "
                                 "m = |u₁| (renumbered), ‖u‖₂² − m² = u₂² + u₃²"),
            inequality_step("|u|_2 <= sqrt(3) |u|_inf", root3 ** 2 * m ** 2 - sum(ui ** 2 for ui in u),
                            [(1, [h], 1) for h in hyp_u], hyps=hyp_u,
                            text=f"m² ≥ uᵢ² (i = 1, 2, 3): ‖u‖₂² ≤ {sympy.sstr(root3 ** 2)}m²")]
    hs = [root3 * m - n, m - am, n - m, m]
    rows.append(inequality_step("(1 - c)|u|_2 <= sqrt(3) max(0, |u|_2 - a_m)",
                                root3 * m * (n - am) - (m - am) * n, [(1, [hs[0], hs[1]], 1), (root3, [hs[3], hs[2]], 1)],
                                hyps=hs, text="case m > a_m, c = a_m/m (times m > 0): √3m(n − a_m) − (m − a_m)n = "
                                              "(√3m − n)(m − a_m) + √3m(n − m); case m ≤ a_m: c = 1, (1 − c)n = 0"))
    s, nv, na, nva, r, K0 = *_nn("s nv na nva r"), _val(k0, v)
    h = nv + na - nva
    rows.append(inequality_step("|v - a| - a_m(1+s^2)/4 <= |v| + |a| - a_m/4",
                                (nv + na - quarter * am) - (nva - am * (1 + s ** 2) / 4),
                                [(1, [h], 1), (am / 4, [], s)], hyps=[h],
                                text="‖p‖ = (1 − c)(1 + s²)n/4 ≤ √3·max(0, ‖v − a‖ − a_m(1 + s²)/4) (n = 4‖v − a‖/(1 + s²)), "
                                     "and the triangle inequality ‖v − a‖ ≤ ‖v‖ + ‖a‖"))
    d = _nn("d")
    g = K0 * r + 2 * K0 * r ** 2 + 6 * K0 * r ** 3 - am / 4
    hg = [K0 * r - nv, 2 * d ** 2 * (1 + 3 * s) - na, 2 * K0 * r ** 2 * (1 + 3 * r) - 2 * d ** 2 * (1 + 3 * s)]
    rows.append(inequality_step("|v| + |a| - a_m/4 <= g(||V||)", g - (nv + na - am / 4), [(1, [x], 1) for x in hg],
                                hyps=hg, text=f"‖v‖ ≤ k0r, ‖a‖ ≤ 2d²(1 + 3s) ≤ 2k0r²(1 + 3r): g(r) = {sympy.sstr(g)}"))
    al, be = sympy.sympify(v["alpha"]), sympy.sympify(v["beta"])
    Vi, G, P = _nn("V_i G P")
    hp = root3 * G - P
    rows.append(inequality_step("V_i' <= -alpha V_i + f(V)", (-al * Vi + _R3 * G / be) - (-al * Vi + P / be),
                                [(1 / be, [hp], 1)], hyps=[hp],
                                text="|pᵢ| ≤ ‖p‖ ≤ √3·max(0, g) = √3G: V̇ᵢ ≤ −αVᵢ + |pᵢ|/β ≤ −αVᵢ + f̃, f̃ = (√3/β)G"))
    Vs = _nn("V1:4")
    rows.append(inequality_step("sum V_i <= sqrt(3) ||V||", root3 ** 2 * sum(x ** 2 for x in Vs) - sum(Vs) ** 2,
                                [(1, [], Vs[0] - Vs[1]), (1, [], Vs[0] - Vs[2]), (1, [], Vs[1] - Vs[2])],
                                text=f"{sympy.sstr(root3 ** 2)}ΣVᵢ² − (ΣVᵢ)² = Σ_(i<j)(Vᵢ − Vⱼ)²"))
    F, S = _nn("F S")
    hd = [_R3 * r - S, F]
    rows.append(inequality_step("D+||V|| <= phi(||V||)", (-al * r ** 2 + F * _R3 * r) - (-al * r ** 2 + F * S),
                                [(1, hd, 1)], hyps=hd,
                                text="‖V‖·D⁺‖V‖ = ΣVᵢV̇ᵢ ≤ −α‖V‖² + f̃ΣVᵢ ≤ −α‖V‖² + √3f̃‖V‖, √3f̃ = (3/β)max(0, g)"))
    return rows


def norm_steps(v, T) -> list:
    """Every step of the chain at the run's values, T the real Jordan transform of a channel (:mod:`.comparison`)."""
    return _rows_channel(v, T) + _rows_vectors() + _rows_a(v) + _rows_saturation(v)


def chain_status(steps) -> tuple:
    """(status, names of the steps not proved): ``exact`` only if every step is exact."""
    missing = [r.name for r in steps if r.status is not Status.EXACT]
    if not missing:
        return Status.EXACT, []
    return (Status.FAILED if any(r.status is Status.FAILED for r in steps) else Status.UNDECIDED), missing
