"""The proof of Theorem 2 of paper 002 from the functional to its conclusion, as checked bound steps.

"Имеем  c5‖x‖^{ν1} + c6‖y‖^{ν2} − c7τ‖y‖^{ν2−1}∫‖y‖^μ + α1∫‖x‖^{ν1} + α2∫‖y‖^{ν2+μ−1} ≤ V ≤ …,
 V̇ ≤ −m14‖x‖^{ν1} − m24‖y‖^{ν2+μ−1} + c1… + c2… + c3… + τc10… + ε2c4… + h2c4… − β1∫… − β2∫… + …",
then "using Young's inequality … for ‖x_t‖_τ + ‖y_t‖_τ < δ" the two-sided bound and
V̇ ≤ −½(m14‖x‖^{ν1} + m24‖y‖^{ν2+μ−1} + β1∫‖x‖^{ν1} + β2∫‖y‖^{ν2+μ−1}).

Here, for the catalogued instance (ν1 = ν2 = 2, μ = 3, V1 = xᵀS1x, V2 = yᵀS2y, :mod:`.theorem2`), every
term of V and of the exact structured V̇ along (П.4) gets a checked rule, on the region

    max_{[t−τ, t]} ‖x(ξ)‖ ≤ δ,   max_{[t−τ, t]} ‖y(ξ)‖ ≤ δ,

in the measures wx = ‖x(t)‖, ey = ‖y(t)‖, Ix = ∫‖x(ξ)‖²dξ, Iy = ∫‖y(ξ)‖⁴dξ, J3 = ∫‖y(ξ)‖³dξ:

* V ≥ L, V ≤ U: Rayleigh for V1, V2 (exact); the printed c7τ‖y‖∫‖y‖^μ for the cross term
  −(∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ (Cauchy–Schwarz, ‖B⁻¹‖, ‖S2‖ exact, ‖D(y)‖ ≤ κ‖y‖³ certified); in L it
  is then bounded by Hölder J3 ≤ τ^{1/4}Iy^{3/4}, Young (η_L) and Iy^{3/2} ≤ (τδ⁴)^{1/2}Iy on the region;
  the weighted integrals between α_i∫ and (α_i + β_iτ)∫ (exact).
* V̇ ≤ W: −2xᵀS1A⁻¹Bx ≤ −m14‖x‖² (Rayleigh on the symmetric part, exact); the polynomial terms in x(t), y(t)
  (Q(y − B⁻¹Ax), Q(y) − Q(y − B⁻¹Ax), the m24 term) split into their parts of bidegree (a, b) in (x, y), each
  ≤ κ_ab‖x‖^a‖y‖^b with κ_ab certified over the torus (:class:`BidegreeParts`); the window integrals of
  cubic maps by :class:`WindowCubicNorm`; then Young (η) and the region, where the order condition
  1 < (ν2+μ−1)/ν1 < μ is what makes every cross term small.

Against the paper: the printed two-sided estimate before Young (c5 = λ_min(S1), c6 = λ_min(S2), c8 = λ_max(S1),
c9 = λ_max(S2), c7 = 2‖B⁻¹‖‖S2‖κ_D with ‖D(y)‖ ≤ κ_D‖y‖³) is proved in the printed form, and at the choices the
proof's final estimates ½(c6‖y‖² + α2∫‖y‖⁴) + c5‖x‖² + α1∫‖x‖² ≤ L and W ≤ −½(m14‖x‖² + m24‖y‖⁴ + β1∫‖x‖² +
β2∫‖y‖⁴) hold coefficient by coefficient (:data:`PRINTED_L`, :data:`PRINTED_W`); no printed step is refuted.
The ε1/h1, ε2/h2 splitting is not needed here: every part of bidegree (a, b) of the cubic terms is of higher
order than −m14‖x‖² − m24‖y‖⁴ by itself (the (1, 3) parts after Young), which is the order condition.

The conclusion is Krasovskii's theorem on the coefficients of L, U, W.  The choices α1, β1, α2, β2,
η, η_L, δ are found at the run's values by :func:`find_choices` (floating point only picks them;
every step is proved at those exact values).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy

from lkverify import t, xi
from lkverify.certify.steps.chain import Krasovskii, TermBound, lyapunov_steps
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure
from lkverify.certify.steps.rewrites import OnRegion, WindowHolder, YoungEach
from lkverify.certify.steps.rules import (Application, CauchySchwarz, Equal, Nonpositive, Norm, Rayleigh,
                                          Rule, WindowWeight, decided, mapped, measured, sign_of, summed)

from .decomposition import A, B, D, P2, Q, q_of_xy, system_P4, tau, x, y
from .theorem1_bound import extreme_eigenvalue
from .theorem2_functional import S1, S2, alpha1, alpha2, beta1, beta2, derivation, functional

__all__ = ["CONCLUSION", "MEASURES", "REGION", "BidegreeParts", "CubicNorm", "WindowCubicNorm", "chain_steps",
           "find_choices", "steps", "delta", "eta", "eta_L"]

delta = P2.scalar("delta", positive=True, latex=r"\delta", description="region: max over the window of ‖x‖, ‖y‖")
eta = P2.scalar("eta", positive=True, latex=r"\eta", description="Young's parameter in V̇ ≤ W")
eta_L = P2.scalar("eta_L", positive=True, latex=r"\eta_L", description="Young's parameter in V ≥ L")

WX = norm_measure("wx", x(t), text="‖x(t)‖")
EY = norm_measure("ey", y(t), text="‖y(t)‖")
IX = window_integral_measure("Ix", x(xi), p=2, window=tau, text="∫‖x(ξ)‖²dξ")
IY = window_integral_measure("Iy", y(xi), p=4, window=tau, text="∫‖y(ξ)‖⁴dξ")
J3 = window_integral_measure("J3", y(xi), p=3, window=tau, text="∫‖y(ξ)‖³dξ")
MEASURES = (WX, EY, IX, IY, J3)
wx, ey, Ix, Iy, j3 = (m.symbol for m in MEASURES)
REGION = Region({sup_norm("mx", x(xi), window=tau, text="max ‖x(ξ)‖"): delta,
                 sup_norm("my", y(xi), window=tau, text="max ‖y(ξ)‖"): delta})

_Binv, _Ainv = B.inv(), A.inv()
_xt, _yt = sympy.Matrix(x(t)), sympy.Matrix(y(t))
_xs, _ys = sympy.Matrix(x(xi)), sympy.Matrix(y(xi))
_w = xi + tau - t


# ---- certified suprema of bihomogeneous parts -----------------------------------------------------
def _torus(expr, xv, yv):
    """{(a, b): c_ab(θ1, θ2)}: expr(x, y) = Σ ‖x‖^a‖y‖^b c_ab with x = ‖x‖(cos θ1, sin θ1), y likewise (exact)."""
    E1, E2 = sympy.symbols("E1 E2", nonnegative=True)
    th = sympy.symbols("theta1 theta2", real=True)
    rep = {xv[0]: E1 * sympy.cos(th[0]), xv[1]: E1 * sympy.sin(th[0]),
           yv[0]: E2 * sympy.cos(th[1]), yv[1]: E2 * sympy.sin(th[1])}
    out = {}
    for k, e in enumerate(expr):
        poly = sympy.Poly(sympy.expand(sympy.sympify(e).xreplace(rep)), E1, E2)
        for (a, b), c in poly.terms():
            out.setdefault((a, b), [0] * len(expr))[k] = c
    return out, th


_SUPS: dict = {}  # q → a certified (κ, text): one proof per expression and process


def _certified_sup(q, th, ctx, what):
    """(κ, condition): κ a rational ≥ sup of q over [0, 2π]², certified with arb (mean-value enclosure)."""
    from lkverify.certify.suprema import sup_bound
    from lkverify.options import Accuracy, Budget

    q = sympy.sympify(q)
    if q.free_symbols.isdisjoint(th):
        return (q, decided(f"{what} = {q} (constant)", True)) if q.is_Rational else \
            (None, decided(f"{what} is a rational constant", None, f"got {q}"))
    if q not in _SUPS:
        box = {s: (0, 2 * sympy.pi) for s in th}
        res = sup_bound(q, box, accuracy=Accuracy(rel_gap=2e-2), enclosure="mean-value",
                        budget=Budget(seconds=ctx.seconds_left(), boxes=20_000))
        if res.certified is None or not res.certified < float("inf"):
            return None, decided(f"{what} certified", None, "no finite certified bound in the budget", certified=True)
        _SUPS[q] = (sympy.Rational(res.certified), f"certified, estimate {res.estimate:.6g}")
    kappa, text = _SUPS[q]
    return kappa, decided(f"{what} ≤ {float(kappa):.6g} ({text})", True, certified=True)


def _norm_bound(F, xv, yv, ctx, what):
    """({(a, b): κ_ab}, conditions): ‖F(x, y)‖ ≤ Σ κ_ab‖x‖^a‖y‖^b (triangle inequality over the parts)."""
    parts, th = _torus(list(F), xv, yv)
    kappas, conds = {}, []
    for (a, b), comps in sorted(parts.items()):
        sq = sympy.expand(sum(c**2 for c in comps))
        k2, cond = _certified_sup(sq, th, ctx, f"‖{what}_({a},{b})‖²")
        conds.append(cond)
        if k2 is None:
            return None, conds
        kappas[(a, b)] = _sqrt_above(k2)
    return kappas, conds


def _sqrt_above(v):
    """A rational κ ≥ √v (exact comparison)."""
    v = sympy.Rational(v)
    if v <= 0:
        return sympy.S.Zero
    k = sympy.Rational(int(np.ceil(float(sympy.sqrt(v)) * 10**9)) + 1, 10**9)
    while k**2 < v:
        k += sympy.Rational(1, 10**9)
    return k


def _window_sup(ctx, vector):
    """The region's bound on max_{[t−τ, t]}‖vector(ξ)‖ (a sup measure over a window ≥ τ), or None."""
    for m, b in (ctx.region.bounds.items() if ctx.region is not None else ()):
        if m.kind == "sup" and m.vector == sympy.ImmutableMatrix(vector) and \
                sympy.simplify(ctx.at(m.window) - ctx.at(tau)).is_nonnegative:
            return ctx.at(b)
    return None


def _region(ctx, measure):
    h = None if ctx.region is None else ctx.region.bound_of(measure, ctx.sub)
    return None if h is None else ctx.at(h)


@dataclasses.dataclass(frozen=True)
class BidegreeParts(Rule):
    """term(x(t), y(t)) ≤ Σ κ_ab‖x‖^a‖y‖^b (or ≥ −Σ …), a polynomial split exactly by its bidegree.

    Each part c_ab(θ1, θ2)‖x‖^a‖y‖^b (x = ‖x‖(cos θ1, sin θ1), y likewise) is bounded by κ_ab = sup c_ab over
    the torus, certified with arb (for a lower bound: −sup(−c_ab)).  ``keep`` maps a bidegree (a, b) to
    (a', b') ≤ (a, b): that part is lowered on the region, ‖x‖^a‖y‖^b ≤ δx^{a−a'}δy^{b−b'}‖x‖^{a'}‖y‖^{b'}
    (valid when its κ has the right sign; a part of the other sign is bounded by 0).
    """

    constant: str
    xmeasure: str
    ymeasure: str
    parts: tuple
    keep: tuple = ()
    name = "bidegree parts, each a certified supremum over the torus"

    def apply(self, term, direction, ctx):
        mx, my = ctx.measure(self.xmeasure), ctx.measure(self.ymeasure)
        xv, yv = list(ctx.at(mx.vector)), list(ctx.at(my.vector))
        e = sympy.expand(ctx.at(term))
        others = {a for a in e.atoms(sympy.core.function.AppliedUndef)} - set(xv) - set(yv)
        conds = [decided("the term is a polynomial in the two measured vectors", not others and not e.has(sympy.Integral),
                       f"it involves {sorted(map(str, others))[:3]}")]
        if not conds[0].status.is_proof:
            return Application(self.name, None, tuple(conds))
        found, th = _torus([e], xv, yv)
        conds.append(decided(f"its bidegrees are among {list(self.parts)}", set(found) <= set(self.parts),
                           f"it has the parts {sorted(found)}"))
        keep = dict(self.keep)
        hx, hy = _region(ctx, mx), _region(ctx, my)
        sgn = 1 if direction == "upper" else -1
        bound, consts = sympy.S.Zero, []
        for a, b in self.parts:
            (c,) = found.get((a, b), [0])
            k, cond = _certified_sup(sgn * c, th, ctx, f"{'' if sgn > 0 else '−'}part_({a},{b})/(‖x‖^{a}‖y‖^{b})")
            conds.append(cond)
            if k is None:
                return Application(self.name, None, tuple(conds))
            a2, b2 = keep.get((a, b), (a, b))
            if (a2, b2) != (a, b):
                conds.append(decided(f"lowered on the region: ‖x‖^{a}‖y‖^{b} ≤ {hx}^{a - a2}·{hy}^{b - b2}·"
                                   f"‖x‖^{a2}‖y‖^{b2} (a part ≤ 0 is bounded by 0)",
                                   hx is not None and hy is not None and 0 <= a2 <= a and 0 <= b2 <= b))
                if hx is None or hy is None:
                    return Application(self.name, None, tuple(conds))
                k = max(k, sympy.S.Zero)
                bound += sgn * k * hx ** (a - a2) * hy ** (b - b2) * mx.symbol**a2 * my.symbol**b2
            else:
                bound += sgn * k * mx.symbol**a2 * my.symbol**b2
            consts.append((f"{self.constant}_{a}{b}", sgn * k, {"certified": float(k)}))
        return Application(self.name, sympy.expand(bound), tuple(conds), tuple(consts))


class CubicNorm(Norm):
    """‖F(x(t), y(t))‖ ≤ Σ κ_ab‖x‖^a‖y‖^b (parts certified over the torus, :func:`_norm_bound`).

    ``keep`` lowers parts on the region as in :class:`BidegreeParts`.  Build with :func:`cubic_norm`.
    """

    def resolve(self, vec, ctx, vector):
        xname, yname, keep, what, prefix, expected = self.data
        conds = [decided(f"the vector is {what}", all(ctx.zero(a - b) for a, b in zip(vec, ctx.at(self.vector))),
                       f"{list(vec)} is not it")]
        if not conds[0].status.is_proof:
            return None, conds
        mx, my = ctx.measure(xname), ctx.measure(yname)
        kappas, more = _norm_bound(vec, list(ctx.at(mx.vector)), list(ctx.at(my.vector)), ctx, what)
        conds += more
        if kappas is None:
            return None, conds
        if not _register(ctx, prefix, kappas, expected, conds):
            return None, conds
        hx, hy, keep = _region(ctx, mx), _region(ctx, my), dict(keep)
        total = sympy.S.Zero
        for (a, b), k in kappas.items():
            a2, b2 = keep.get((a, b), (a, b))
            if (a2, b2) != (a, b):
                conds.append(decided(f"the region bounds {mx.text}, {my.text}", hx is not None and hy is not None))
                if hx is None or hy is None:
                    return None, conds
                k = k * hx ** (a - a2) * hy ** (b - b2)
            total += k * mx.symbol**a2 * my.symbol**b2
        return sympy.expand(total), conds


def cubic_norm(F, what, prefix, *, keep=()) -> CubicNorm:
    """The norm bound of the vector F(x(t), y(t)) (see :class:`CubicNorm`); κ_ab are named ``prefix_ab``."""
    return CubicNorm(f"‖{what}‖ ≤ Σκ_ab‖x‖^a‖y‖^b", sympy.ImmutableMatrix(F), None,
                     data=("wx", "ey", tuple(keep), what, prefix, _CUBIC))


_CUBIC = ((0, 3), (1, 2), (2, 1), (3, 0))


def _register(ctx, prefix, kappas, expected, conds) -> bool:
    """Name the certified κ_ab ``prefix_ab`` (0 for an absent part); False if a part is not expected."""
    ok = set(kappas) <= set(expected)
    conds.append(decided(f"the parts are among {list(expected)}", ok, f"got {sorted(kappas)}"))
    for ab in expected:
        kappas.setdefault(ab, sympy.S.Zero)
        ctx.certified[f"{prefix}_{ab[0]}{ab[1]}"] = (kappas[ab], {"certified": float(kappas[ab])})
    return ok


def _window_parts(vec):
    """(integrand vector, (ξ, lo, hi)) of a vector of sums of window integrals over one window, or (None, why)."""
    rows, limits = [], None
    for entry in vec:
        total = sympy.S.Zero
        for arg in sympy.Add.make_args(sympy.expand(entry)):
            factors = sympy.Mul.make_args(arg)
            ints = [f for f in factors if isinstance(f, sympy.Integral)]
            c = sympy.Mul(*[f for f in factors if not isinstance(f, sympy.Integral)])
            if len(ints) != 1 or c.has(xi) or c.atoms(sympy.core.function.AppliedUndef):
                return None, f"{arg} is not a constant times one window integral"
            (I,) = ints
            if len(I.limits) != 1 or (limits is not None and I.limits[0] != limits):
                return None, "the integrals do not run over one window"
            limits = I.limits[0]
            total += c * I.function
        rows.append(total.subs(limits[0], xi))
    return (sympy.Matrix(rows), (xi, limits[1], limits[2])), ""


class WindowCubicNorm(Norm):
    """‖∫_{t−τ}^t g(ξ)F(x(ξ), y(ξ))dξ‖ ≤ max g·(κ03·J3 + κ12(Ix + Iy)/2 + (κ21δy + κ30δx)·Ix).

    F is split by bidegree (exact); ‖F_ab(x, y)‖ ≤ κ_ab‖x‖^a‖y‖^b with κ_ab certified over the torus, then
    pointwise: ‖x‖‖y‖² ≤ (‖x‖² + ‖y‖⁴)/2 (AM–GM), ‖x‖²‖y‖ ≤ δy‖x‖², ‖x‖³ ≤ δx‖x‖² on the region
    (‖x(ξ)‖ ≤ δx, ‖y(ξ)‖ ≤ δy on the window); the weight g ≥ 0 is affine in ξ, so max g is at an end of the window.  Only parts
    of total degree 3 are accepted.  Build with :func:`window_cubic_norm`.
    """

    def resolve(self, vec, ctx, vector):
        weight, F, what, prefix = self.data
        parsed, why = _window_parts(vec)
        if parsed is None:
            return None, [decided("the vector is a window integral ∫g(ξ)F(x(ξ), y(ξ))dξ", False, why)]
        G, (_, lo, hi) = parsed
        g = sympy.expand(ctx.at(weight))
        Fx = sympy.Matrix(ctx.at(sympy.Matrix(F)))
        conds = [decided("the window is [t − τ, t]", ctx.zero(hi - t) and ctx.zero(lo - (t - ctx.at(tau)))),
                 decided(f"the integrand is g(ξ)·{what} with g = {g}", all(ctx.zero(a - g * b) for a, b in zip(G, Fx)),
                       "it is not")]
        ends = [sympy.simplify(g.subs(xi, lo)), sympy.simplify(g.subs(xi, hi))]
        affine = sympy.Poly(g, xi).degree() <= 1
        conds.append(decided(f"g is affine in ξ and ≥ 0 at the ends {ends}", affine and all(sign_of(v) == 1 for v in ends)
                           or None, "not shown"))
        if not all(c.status.is_proof for c in conds):
            return None, conds
        first = sympy.simplify(ends[0] - ends[1]).is_nonnegative
        gmax = ends[0] if first else ends[1] if first is False else ends[0] + ends[1]  # both ≥ 0: the sum bounds
        kappas, more = _norm_bound(Fx, list(_xs), list(_ys), ctx, what)
        conds += more
        if kappas is None:
            return None, conds
        if not _register(ctx, prefix, kappas, _CUBIC, conds):
            return None, conds
        hx, hy = _window_sup(ctx, _xs), _window_sup(ctx, _ys)
        conds.append(decided("the region bounds ‖x(ξ)‖, ‖y(ξ)‖ on the window [t − τ, t]", hx is not None and hy is not None))
        if not all(c.status.is_proof for c in conds):
            return None, conds
        k = kappas  # ‖x‖²‖y‖ ≤ δy‖x‖², ‖x‖³ ≤ δx‖x‖², ‖x‖‖y‖² ≤ (‖x‖² + ‖y‖⁴)/2
        total = k[(0, 3)] * j3 + k[(1, 2)] * (Ix + Iy) / 2 + (k[(2, 1)] * hy + k[(3, 0)] * hx) * Ix
        return sympy.expand(gmax * total), conds


def window_cubic_norm(F, what, prefix, *, weight=1) -> WindowCubicNorm:
    """The norm bound of ∫_{t−τ}^t g(ξ)F(x(ξ), y(ξ))dξ, F a cubic map (see :class:`WindowCubicNorm`).

    The certified κ_ab are named ``prefix_ab`` (0 for an absent part), so that stated bounds can use them.
    """
    vector = sympy.ImmutableMatrix([sympy.Integral(weight * f, (xi, t - tau, t)) for f in F])
    return WindowCubicNorm(f"‖∫g·{what}‖ ≤ max g·(κ03J3 + κ12(Ix+Iy)/2 + (κ21+κ30)δIx)", vector, None,
                           data=(weight, sympy.ImmutableMatrix(F), what, prefix))


# ---- named constants (exact at the run's values) -------------------------------------------------------
def _at(values, expr):
    from lkverify.declare.parameters import apply_substitution

    sub = system_P4.parameters.substitution(values)
    return sympy.Matrix(apply_substitution(sympy.Matrix(expr), sub)) if isinstance(expr, sympy.MatrixBase) \
        else apply_substitution(sympy.sympify(expr), sub)


def operator_norm_above(M) -> sympy.Rational:
    """A rational κ ≥ ‖M‖ (κ²I − MᵀM ⪰ 0 is then decided exactly where κ is used); ∞ if M is not finite.

    (B⁻¹ at a singular B: the hypotheses fail, and the steps must still run without an error.)
    """
    if not all(sympy.sympify(e).is_finite for e in sympy.Matrix(M)):
        return sympy.oo
    return _sqrt_above(extreme_eigenvalue(sympy.Matrix(M).T * sympy.Matrix(M), "max"))


def _sym(M):
    M = sympy.Matrix(M)
    return (M + M.T) / 2


_S1AB = S1 * _Ainv * B
_MATRICES = {"S1A": S1 * _Ainv, "S2B": S2 * _Binv, "BSB": _Binv.T * S2 * _Binv, "Binv": _Binv}
s1m, s1M, s2m, s2M, bn, nS1A, nS2B, nBSB, m14 = sympy.symbols("s1m s1M s2m s2M bn nS1A nS2B nBSB m14", positive=True)


def _opn(name):
    return lambda ctx: operator_norm_above(ctx.at(_MATRICES[name]))


def _eig(M, which):
    return lambda ctx: extreme_eigenvalue(ctx.at(M), which)


DEFINITIONS = {
    s1m: lambda v: extreme_eigenvalue(_at(v, S1), "min"), s1M: lambda v: extreme_eigenvalue(_at(v, S1), "max"),
    s2m: lambda v: extreme_eigenvalue(_at(v, S2), "min"), s2M: lambda v: extreme_eigenvalue(_at(v, S2), "max"),
    bn: lambda v: operator_norm_above(_at(v, _Binv)), nS1A: lambda v: operator_norm_above(_at(v, _MATRICES["S1A"])),
    nS2B: lambda v: operator_norm_above(_at(v, _MATRICES["S2B"])),
    nBSB: lambda v: operator_norm_above(_at(v, _MATRICES["BSB"])),
    m14: lambda v: 2 * extreme_eigenvalue(_sym(_at(v, _S1AB)), "min"),
}

# ---- the constants certified inside the rules (named, so the stated bounds can use them) -----------------
_q = q_of_xy(t)
_Dq, _Dy = D(q_of_xy(xi)), D(_ys)
_C = {n: sympy.Symbol(n, real=True) for n in
      [f"{p}_{a}{b}" for p in ("kD", "kJ", "kE", "kQ") for a, b in ((0, 3), (1, 2), (2, 1), (3, 0))]
      + [f"c1_{a}{b}" for a, b in ((1, 3), (2, 2), (3, 1), (4, 0))] + [f"c3_{a}{b}" for a, b in ((1, 3), (2, 2), (3, 1))]
      + ["m24_04"]}
K = window_cubic_norm(_Dy, "D(y(ξ))", "kD", weight=_w)                     # ∫(ξ+τ−t)D(y(ξ))dξ
J = window_cubic_norm(_Dq, "D(y(ξ)−B⁻¹Ax(ξ))", "kJ")                     # ∫D(y(ξ) − B⁻¹Ax(ξ))dξ
E = window_cubic_norm(_Dy - _Dq, "D(y(ξ))−D(y(ξ)−B⁻¹Ax(ξ))", "kE")       # ∫(D(y) − D(y − B⁻¹Ax))dξ
Qq = cubic_norm(Q(_q), "Q(y−B⁻¹Ax)", "kQ", keep=(((1, 2), (1, 0)), ((2, 1), (1, 0)), ((3, 0), (1, 0))))

_Y = Iy ** sympy.Rational(3, 4)
_s = tau ** sympy.Rational(1, 4)               # Hölder: J3 ≤ τ^{1/4} Iy^{3/4}
_r = sympy.sqrt(tau * delta**4)                # Iy^{3/2} ≤ (τδ⁴)^{1/2} Iy on the region
c7 = 2 * bn * s2M * tau * _C["kD_03"]          # the printed c7τ: |−2(S2y)ᵀB⁻¹∫(ξ+τ−t)D(y)| ≤ c7·ey·J3


def _lower():
    return [
        TermBound("V1 = xᵀS1x", s1m * wx**2, Rayleigh(x(t), S1, eigenvalue=_eig(S1, "min"), norm_squared=wx**2)),
        TermBound("V2 = yᵀS2y", s2m * ey**2, Rayleigh(y(t), S2, eigenvalue=_eig(S2, "min"), norm_squared=ey**2)),
        TermBound("−(∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ", -c7 * _s * (eta_L * ey**2 / 2 + _r * Iy / (2 * eta_L)),
                  CauchySchwarz(S2 * _yt, K.vector, (mapped(S2, measured(EY), _eig(S2, "max")), K), matrix=_Binv,
                                factor=-2, operator_norm=_opn("Binv")),
                  then=(WindowHolder("J3", "Iy"), YoungEach(((ey, _Y, 2, 2, eta_L),)), OnRegion("Iy", 1))),
        TermBound("∫(α1+β1(ξ+τ−t))‖x(ξ)‖²dξ", alpha1 * Ix, WindowWeight("Ix", 2, weight=alpha1 + beta1 * _w)),
        TermBound("∫(α2+β2(ξ+τ−t))‖y(ξ)‖⁴dξ", alpha2 * Iy, WindowWeight("Iy", 4, weight=alpha2 + beta2 * _w)),
    ]


def _upper():
    return [
        TermBound("V1 = xᵀS1x", s1M * wx**2, Rayleigh(x(t), S1, eigenvalue=_eig(S1, "max"), norm_squared=wx**2)),
        TermBound("V2 = yᵀS2y", s2M * ey**2, Rayleigh(y(t), S2, eigenvalue=_eig(S2, "max"), norm_squared=ey**2)),
        TermBound("−(∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ", c7 * ey * j3,
                  CauchySchwarz(S2 * _yt, K.vector, (mapped(S2, measured(EY), _eig(S2, "max")), K), matrix=_Binv,
                                factor=-2, operator_norm=_opn("Binv"))),
        TermBound("∫(α1+β1(ξ+τ−t))‖x(ξ)‖²dξ", (alpha1 + beta1 * tau) * Ix,
                  WindowWeight("Ix", 2, weight=alpha1 + beta1 * _w)),
        TermBound("∫(α2+β2(ξ+τ−t))‖y(ξ)‖⁴dξ", (alpha2 + beta2 * tau) * Iy,
                  WindowWeight("Iy", 4, weight=alpha2 + beta2 * _w)),
    ]


def _young_x_y3(c13, rest):
    """c13·wx·ey³ by Young (η) and ey⁶ ≤ δ²ey⁴; the lowered parts rest·δ²wx²."""
    return c13 * (eta * wx**2 / 2 + delta**2 * ey**4 / (2 * eta)) + rest * delta**2 * wx**2


def _t3():
    """−2xᵀS1A⁻¹∫D(y − B⁻¹Ax): Cauchy–Schwarz, Hölder, Young (η) with wx, then the region on Ix², Iy^{3/2}, Iy²."""
    c = 2 * nS1A
    a03, ax, ay = c * _C["kJ_03"] * _s, c * (_C["kJ_12"] / 2 + (_C["kJ_21"] + _C["kJ_30"]) * delta), c * _C["kJ_12"] / 2
    bound = ((a03 + ax + ay) * eta * wx**2 / 2 + a03 * _r * Iy / (2 * eta) + ax * tau * delta**2 * Ix / (2 * eta)
             + ay * tau * delta**4 * Iy / (2 * eta))
    rule = CauchySchwarz(_xt, J.vector, (measured(WX), J), matrix=_MATRICES["S1A"], factor=-2, operator_norm=_opn("S1A"))
    then = (WindowHolder("J3", "Iy"), YoungEach(((wx, _Y, 2, 2, eta), (wx, Ix, 2, 2, eta), (wx, Iy, 2, 2, eta))),
            OnRegion("Ix", 1), OnRegion("Iy", 1))
    return TermBound("−2xᵀS1A⁻¹∫D(y(ξ)−B⁻¹Ax(ξ))dξ", bound, rule, then=then)


def _t6():
    """2yᵀS2B⁻¹∫(D(y) − D(y − B⁻¹Ax)): Cauchy–Schwarz, then ‖y(t)‖ ≤ δ (every part is of higher order)."""
    c = 2 * nS2B * delta
    bound = c * (_C["kE_03"] * j3 + _C["kE_12"] * (Ix + Iy) / 2 + (_C["kE_21"] + _C["kE_30"]) * delta * Ix)
    rule = CauchySchwarz(_yt, E.vector, (measured(EY), E), matrix=_MATRICES["S2B"], factor=2, operator_norm=_opn("S2B"))
    return TermBound("2yᵀS2B⁻¹∫(D(y(ξ))−D(y(ξ)−B⁻¹Ax(ξ)))dξ", bound, rule, then=(OnRegion("ey", 0),))


def _t7():
    """2(S2B⁻¹(Q(q) + J))ᵀB⁻¹K: Cauchy–Schwarz, Hölder, Young (η) against Iy^{3/4}, then the region."""
    c = 2 * nBSB * tau * _C["kD_03"] * _s
    kQd = (_C["kQ_12"] + _C["kQ_21"] + _C["kQ_30"]) * delta**2
    a, b = _C["kJ_12"] / 2 + (_C["kJ_21"] + _C["kJ_30"]) * delta, _C["kJ_12"] / 2
    bound = c * (_C["kQ_03"] * (eta * delta**2 * ey**4 / 2 + _r * Iy / (2 * eta)) + kQd * (eta * wx**2 / 2 + _r * Iy / (2 * eta))
                 + a * (eta * tau * delta**2 * Ix / 2 + _r * Iy / (2 * eta)) + _s * _C["kJ_03"] * _r * Iy
                 + b * (tau * delta**4) ** sympy.Rational(3, 4) * Iy)
    u = Q(_q) + J.vector
    rule = CauchySchwarz(u, K.vector, (summed(Qq, J), K), matrix=_MATRICES["BSB"], factor=2, operator_norm=_opn("BSB"))
    then = (WindowHolder("J3", "Iy"), YoungEach(((ey**3, _Y, 2, 2, eta), (wx, _Y, 2, 2, eta), (Ix, _Y, 2, 2, eta))),
            OnRegion("ey", 4), OnRegion("Ix", 1), OnRegion("Iy", 1))
    return TermBound("−(∂²V2/∂y² ẏ)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ", bound, rule, then=then)


def _vdot():
    low = (((2, 2), (2, 0)), ((3, 1), (2, 0)), ((4, 0), (2, 0)))
    c1, c3 = _C, _C
    return [
        TermBound("−(∂V1/∂x)ᵀA⁻¹Bx = −2xᵀS1A⁻¹Bx", -m14 * wx**2,
                  Rayleigh(x(t), _sym(_S1AB), factor=-2,
                           eigenvalue=lambda ctx: extreme_eigenvalue(_sym(ctx.at(_S1AB)), "min"), norm_squared=wx**2)),
        TermBound("−2xᵀS1A⁻¹Q(y−B⁻¹Ax)", _young_x_y3(c1["c1_13"], c1["c1_22"] + c1["c1_31"] + c1["c1_40"]),
                  BidegreeParts("c1", "wx", "ey", ((1, 3), (2, 2), (3, 1), (4, 0)), keep=low),
                  then=(YoungEach(((wx, ey**3, 2, 2, eta),)), OnRegion("ey", 4))),
        _t3(),
        TermBound("−(∂V2/∂y)ᵀB⁻¹(Q(y)+τD(y))", _C["m24_04"] * ey**4, BidegreeParts("m24", "wx", "ey", ((0, 4),))),
        TermBound("2yᵀS2B⁻¹(Q(y)−Q(y−B⁻¹Ax))", _young_x_y3(c3["c3_13"], c3["c3_22"] + c3["c3_31"]),
                  BidegreeParts("c3", "wx", "ey", ((1, 3), (2, 2), (3, 1)), keep=low[:2]),
                  then=(YoungEach(((wx, ey**3, 2, 2, eta),)), OnRegion("ey", 4))),
        _t6(),
        _t7(),
        TermBound("(α1+β1τ)‖x‖²", (alpha1 + beta1 * tau) * wx**2, Equal((alpha1 + beta1 * tau) * wx**2)),
        TermBound("−α1‖x(t−τ)‖²", 0, Nonpositive()),
        TermBound("−β1∫‖x(ξ)‖²dξ", -beta1 * Ix, Equal(-beta1 * Ix)),
        TermBound("(α2+β2τ)‖y‖⁴", (alpha2 + beta2 * tau) * ey**4, Equal((alpha2 + beta2 * tau) * ey**4)),
        TermBound("−α2‖y(t−τ)‖⁴", 0, Nonpositive()),
        TermBound("−β2∫‖y(ξ)‖⁴dξ", -beta2 * Iy, Equal(-beta2 * Iy)),
    ]


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 2 on :data:`REGION`."""
    lower, upper, vdot = _lower(), _upper(), _vdot()
    return lyapunov_steps(functional, system_P4, lower, upper, vdot, MEASURES,
                          region=REGION, definitions=DEFINITIONS, derivation=derivation)


steps = chain_steps()

#: the conclusion: V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖), V̇ ≤ −ψ(‖x(t)‖) with the state (x, y)
CONCLUSION = Krasovskii(("wx", "ey"))


# ---- the free choices -----------------------------------------------------------------------------------
def _sampled_sup(exprs, xv, yv, *, norm, n=181):
    """{(a, b): sampled sup} of the parts of exprs (a vector's norm if ``norm``, else the scalar) on the torus."""
    parts, th = _torus(list(exprs), xv, yv)
    grid = np.linspace(0.0, 2 * np.pi, n)
    T1, T2 = np.meshgrid(grid, grid)
    out = {}
    for ab, comps in parts.items():
        f = sympy.lambdify(th, sympy.sqrt(sum(c**2 for c in comps)) if norm else comps[0], "numpy")
        out[ab] = float(np.max(np.broadcast_to(f(T1, T2), T1.shape)))
    return out


def _estimates(values) -> dict:
    """Float estimates (5 % above the sampled suprema) of every constant certified inside the steps."""
    at = lambda e: _at(values, e)  # noqa: E731
    xt, yt, xs_, ys_ = list(_xt), list(_yt), list(_xs), list(_ys)
    est = {}
    for prefix, F, xv, yv in (("kD", at(_Dy), xs_, ys_), ("kJ", at(_Dq), xs_, ys_), ("kE", at(_Dy - _Dq), xs_, ys_),
                              ("kQ", at(Q(_q)), xt, yt)):
        sup = _sampled_sup(F, xv, yv, norm=True)
        est.update({f"{prefix}_{a}{b}": 1.05 * sup.get((a, b), 0.0) for a, b in _CUBIC})
    terms = {tm.text: tm.expr for tm in derivation.terms}
    for prefix, label, parts in (("c1", "−2xᵀS1A⁻¹Q(y−B⁻¹Ax)", ((1, 3), (2, 2), (3, 1), (4, 0))),
                                 ("c3", "2yᵀS2B⁻¹(Q(y)−Q(y−B⁻¹Ax))", ((1, 3), (2, 2), (3, 1))),
                                 ("m24", "−(∂V2/∂y)ᵀB⁻¹(Q(y)+τD(y))", ((0, 4),))):
        sup = _sampled_sup([at(terms[label])], xt, yt, norm=False)
        for a, b in parts:
            v = sup.get((a, b), 0.0)
            est[f"{prefix}_{a}{b}"] = v * 0.95 if v < 0 else (max(v, 0.0) * 1.05 if prefix != "m24" else v * 1.05)
    return est


def _rhs(step, values, est, choices):
    """The step's rhs at the values, the estimated constants and the choices (a float expression)."""
    sub = {**{_C[k]: v for k, v in est.items()}, **{k: float(v) for k, v in step.named_constants(values).items()}}
    return sympy.expand(_at({**values, **choices}, step.rhs).xreplace(sub))


def _coefficients(rhs):
    """{monomial: float coefficient} of an rhs in the measures."""
    poly = sympy.Poly(rhs, *[m.symbol for m in MEASURES])
    return {sympy.Mul(*[g**e for g, e in zip(poly.gens, mono)]): float(c) for mono, c in poly.terms()}


#: the proof's final estimates: ½(c6‖y‖² + α2∫‖y‖⁴) + c5‖x‖² + α1∫‖x‖² ≤ V (c5 = λ_min(S1), c6 = λ_min(S2)) and
#: V̇ ≤ −½(m14‖x‖² + m24‖y‖⁴ + β1∫‖x‖² + β2∫‖y‖⁴) (m24 = −m24_04, the best constant of the key term)
PRINTED_L = s1m * wx**2 + s2m * ey**2 / 2 + alpha1 * Ix + alpha2 * Iy / 2
PRINTED_W = -(m14 * wx**2 - _C["m24_04"] * ey**4 + beta1 * Ix + beta2 * Iy) / 2


def printed_final(role, values, constants, choices=None):
    """The printed final L or W (``role`` "lower" / "vdot") at the values, with the steps' constants."""
    sub = {**{k: v for k, v in steps[0].named_constants(values).items()},
           **{_C[k]: sympy.Rational(v) if not isinstance(v, float) else v for k, v in constants.items() if k in _C}}
    expr = PRINTED_L if role == "lower" else PRINTED_W
    return sympy.expand(_at({**values, **(choices or {})}, expr).xreplace(sub))


def _signs_hold(L, U, W, PL, PW) -> bool:
    """Krasovskii's sign conditions and the printed final estimates, coefficient by coefficient."""
    L, U, W, dL, dW = (_coefficients(e) for e in (L, U, W, L - PL, W - PW))
    return (all(c >= 0 for c in L.values()) and L.get(wx**2, 0) > 0 and L.get(ey**2, 0) > 0
            and all(c >= 0 for c in U.values())
            and all(c < 0 for c in W.values()) and W.get(wx**2, 0) < 0 and W.get(ey**4, 0) < 0
            and all(c >= 0 for c in dL.values()) and all(c <= 0 for c in dW.values()))


#: the choices when A or B is singular (nothing to choose: the hypotheses fail and the chain with them)
FALLBACK = {"alpha1": "1/100", "beta1": "1/100", "alpha2": "1/100", "beta2": "1/100", "eta": "1/100", "eta_L": "1/100",
            "delta": "1/1000"}


def find_choices(values) -> dict:
    """α1, β1, α2, β2, η, η_L, δ for which every coefficient of L, U, W has its sign (exact strings).

    The recipe follows the proof: α_i + β_iτ is a quarter of m14 (m24) so that it does not eat the
    negative terms; η makes the Young remainders on ‖x‖² a quarter of m14, η_L leaves half of λ_min(S2)
    in L; then δ is halved from 1/10 until every coefficient has its sign and the printed final estimates
    (:data:`PRINTED_L`, :data:`PRINTED_W`) hold coefficient by coefficient, at the estimated constants (5 %
    above sampled suprema).  When (8)'s m24 is not positive the recipe runs with m24 = 0.01 and the chain
    fails where it must.  Floating point only picks the numbers; the steps prove them.
    """
    from .theorem1_chain import _below

    if _at(values, A).det() == 0 or _at(values, B).det() == 0:  # (П.4) undefined: the hypotheses fail first
        return dict(FALLBACK)
    est = _estimates(values)
    v = {k: float(c) for k, c in steps[2].named_constants(values).items()}
    tau_ = float(_at(values, tau))
    m14_, m24_ = max(v[m14], 1e-2), max(-est["m24_04"], 1e-2)
    ch = {"alpha1": _below(m14_ / 8), "beta1": _below(m14_ / (8 * tau_)),
          "alpha2": _below(m24_ / 8), "beta2": _below(m24_ / (8 * tau_)), "delta": sympy.S.Zero,
          "eta": sympy.S.One, "eta_L": sympy.S.One}
    W = _rhs(steps[2], values, est, {**ch, "delta": 0, "eta": 1}).coeff(wx, 2)
    W2 = _rhs(steps[2], values, est, {**ch, "delta": 0, "eta": 2}).coeff(wx, 2)
    C = float(W2 - W)  # the coefficient of η in the wx² coefficient of W (δ = 0)
    ch["eta"] = _below(m14_ / (4 * max(C, 1e-9)))
    l1 = _rhs(steps[0], values, est, {**ch, "eta_L": 1}).coeff(ey, 2)
    l2 = _rhs(steps[0], values, est, {**ch, "eta_L": 2}).coeff(ey, 2)
    ch["eta_L"] = _below(float(v[s2m]) / (2 * max(float(l1 - l2), 1e-9)))
    d_ = sympy.Symbol("d_", positive=True)
    rhs = [_rhs(s_, values, est, {**ch, "delta": d_}) for s_ in steps]
    printed = [printed_final(r, values, est, ch) for r in ("lower", "vdot")]
    d = sympy.Rational(1, 10)
    for _ in range(30):
        if _signs_hold(*(r.subs(d_, d) for r in rhs), *printed):
            break
        d /= 2
    ch["delta"] = _below(float(d))
    return {k: str(val) for k, val in ch.items()}
