"""Norm trees checked against the vectors they bound: :class:`Norm` and :func:`resolve_norm`, with the
side conditions a tree carries — the operator norm ‖Mv‖ ≤ κ‖v‖ (:func:`operator_norm_conditions`), a
window weight or Hölder on a window integral (:func:`conjugate_exponents`), the pointwise constant of a
sum of window integrals (:func:`pointwise_constant`).

The constructors a proof writes (``measured``, ``unit``, ``crossed``, ``scaled``, ``summed``, ``mapped``,
``integral_of``) stay in :mod:`lkverify.certify.steps.rules`, which re-exports these names.
"""

from __future__ import annotations

import dataclasses

import sympy
from sympy.core.function import AppliedUndef

from ...declare.symbols import t, xi
from ...status import Status
from ..matrices import matrix_positive_definite
from .context import Condition, Context, _cond, _sign
from .measures import Measure

__all__ = ["FieldNorm", "Norm", "conjugate_exponents", "operator_norm_conditions", "pointwise_constant", "resolve_norm"]


# -- norm trees -------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Norm:
    """An upper bound ``‖vector‖ ≤ bound``, with how it follows (see the constructors in :mod:`.rules`).

    ``vector`` is in the model's vocabulary, ``bound`` in measures (at t) or in pointwise
    norms at ξ (inside a window integral).
    """

    how: str
    vector: object
    bound: object
    parts: tuple = ()
    conditions: tuple = ()
    data: tuple = ()

    def all_conditions(self) -> list:
        out = list(self.conditions)
        for p in self.parts:
            if isinstance(p, Norm):
                out += p.all_conditions()
        return out


#: the branch-and-bound work of one field constant κ ≥ max‖F(u)‖ (boxes only: deterministic)
FIELD_BOXES = 50_000


@dataclasses.dataclass(frozen=True)
class FieldNorm(Norm):
    """‖F(v)/κ‖ ≤ ‖v‖^k for a polynomial field F homogeneous of degree k (see ``rules.homogeneous_field``).

    ``data`` is (F in the plain variables, the variables, the measure, k, κ, pointwise?).  The
    side conditions, each decided: the vector is F(v)/κ for the measure's vector v (exactly);
    F has numeric coefficients after the values and every component is a form of degree k
    (exact, so ‖F(ρu)‖ = ρ^k‖F(u)‖); κ > 0; κ²‖x‖^{2k} − ‖F(x)‖² ≥ 0 for every x — identically
    0 (exact), or positive on the unit sphere (certified with arb by
    :func:`lkverify.certify.forms.homogeneous_positive_on_sphere`), or refuted at a rational point.
    """

    def resolve(self, vec, ctx, vector):
        field, xs, measure, k, kappa, pointwise = self.data
        k, kappa = ctx.at(k), ctx.at(kappa)
        F = sympy.Matrix(ctx.at(sympy.Matrix(field)))
        v = sympy.Matrix(measure.vector)
        if pointwise and measure.kind == "norm":
            v = v.subs(t, xi)
        symbol = measure.pointwise_symbol if pointwise else measure.symbol
        target = F.xreplace(dict(zip(xs, list(v)))) / kappa
        if target.shape != vec.shape or not all(ctx.zero(x) for x in vec - target):
            return None, [_cond("the vector is F(v)/κ (the field at the measure's vector)", False,
                                f"{list(vec)} is not {list(target)}")]
        conds = [_cond(f"the vector is F(v)/κ, F = {list(F)}, v the vector of {measure.name}", True)]
        k_ok = bool(k.is_Integer and k > 0)
        conds.append(_cond(f"the degree k = {k} is a positive integer", k_ok or (None if k.free_symbols else False)))
        others = set().union(*(sympy.sympify(c).free_symbols for c in F)) - set(xs)
        conds.append(_cond("F has numeric coefficients", not others or None,
                           f"free symbols {sorted(map(str, others))}" if others else ""))
        if not all(c.status.is_proof for c in conds):
            return None, conds
        bad = []
        for i, comp in enumerate(F):
            comp = sympy.expand(comp)
            if comp == 0:
                continue
            try:
                degs = {sum(m) for m in sympy.Poly(comp, *xs).monoms()}
            except sympy.PolynomialError:
                return None, conds + [_cond("F is a polynomial field", None, f"component {i + 1}: {comp}")]
            if degs != {k}:
                bad.append(f"component {i + 1} = {comp} has degree(s) {sorted(degs)}")
        conds.append(_cond(f"every component of F is a form of degree {k} (F(ρu) = ρ^k F(u))", not bad,
                           "; ".join(bad)))
        sk = _sign(kappa)
        conds.append(_cond(f"κ = {kappa} > 0", True if sk == 1 else (False if kappa.is_nonpositive else None),
                           "" if sk == 1 else "κ ≤ 0" if kappa.is_nonpositive else "the sign of κ is not known"))
        if not all(c.status.is_proof for c in conds):
            return None, conds
        conds.append(_field_constant(F, xs, k, kappa, ctx))
        return symbol**k, conds


def _field_constant(F, xs, k, kappa, ctx) -> Condition:
    """κ ≥ max_{‖u‖=1} ‖F(u)‖: κ²‖x‖^{2k} − ‖F(x)‖² ≥ 0, a form of degree 2k decided on the unit sphere."""
    from ...options import Budget
    from ..forms import homogeneous_positive_on_sphere

    g = sympy.expand(kappa**2 * sum((x**2 for x in xs), sympy.S.Zero) ** k - sum((c**2 for c in F), sympy.S.Zero))
    text = f"κ = {kappa} ≥ max_(‖u‖=1) ‖F(u)‖ (κ²‖x‖^(2k) − ‖F(x)‖² ≥ 0)"
    if g == 0:
        return _cond(text, True, "‖F(x)‖ = κ‖x‖^k identically")
    res = homogeneous_positive_on_sphere(g, xs, name="κ²‖x‖^(2k) − ‖F(x)‖²",
                                         budget=Budget(seconds=ctx.seconds_left(None), boxes=FIELD_BOXES))
    if res.status.is_proof:
        return Condition(text, Status.CERTIFIED, res.detail)
    if res.status is Status.FAILED and res.witness is not None:
        # the sphere test is strict (> 0); ≥ 0 fails only where the form is < 0 (exact, at a rational point)
        point = [sympy.Rational(p_.numerator, p_.denominator) if hasattr(p_, "numerator") else sympy.sympify(p_)
                 for p_ in res.witness]
        value = sympy.expand(g.xreplace(dict(zip(xs, point))))
        if not value.is_negative and len(xs) == 2:
            found = _negative_point(g, xs)
            point, value = (list(found[0]), found[1]) if found else (point, value)
        if value.is_negative:
            norm_f = sympy.sqrt(sum((c.xreplace(dict(zip(xs, point))) ** 2 for c in F), sympy.S.Zero))
            return Condition(text, Status.FAILED, f"at x = ({', '.join(map(str, point))}) ‖F(x)‖ = {norm_f} > "
                             f"κ‖x‖^k (κ²‖x‖^(2k) − ‖F(x)‖² = {value}, exact)")
        return Condition(text, Status.UNDECIDED, f"κ²‖x‖^(2k) − ‖F(x)‖² = {value} at x = "
                         f"({', '.join(map(str, point))}): ≥ 0 there, but a zero on the sphere is not decided "
                         f"(take κ larger)")
    return Condition(text, Status.UNDECIDED, res.detail)


def _negative_point(g, xs, grid: int = 96):
    """A rational point of the unit circle's parametrisation where the binary form g < 0 (exact), or None.

    x = (1 − s², 2s)/(1 + s²) scaled by 1 + s² (g homogeneous: the sign is that on the circle), s = k/grid·4
    for |k| ≤ grid, and x = (0, 1): the strict sphere test may stop at a zero of g, which refutes no "≥ 0".
    """
    pts = [(1 - s * s, 2 * s) for s in (sympy.Rational(4 * k, grid) for k in range(-grid, grid + 1))] + [(0, 1)]
    for p in pts:
        value = sympy.expand(g.xreplace(dict(zip(xs, p))))
        if value.is_negative:
            return p, value
    return None


def _window_factor(g, lo, hi, measure: Measure, k, holder, ctx: Context, *, lower=False):
    """(factor, conditions): ∫_{lo}^{hi} g·P^k ≤ factor·(measure-power), P the pointwise norm."""
    conds = []
    g = sympy.expand(ctx.at(g))
    order = ctx.at(measure.power)
    width = sympy.simplify(hi - lo)
    mw = sympy.simplify(ctx.at(measure.window))
    conds.append(_cond(f"the window [{lo}, {hi}] is the measure's window of length {mw}",
                       bool(sympy.simplify(width - mw) == 0) and bool(sympy.simplify(hi - t) == 0),
                       f"window of length {width}"))
    # g on the window: a polynomial in ξ, bounded at the ends and critical points
    try:
        poly = sympy.Poly(g, xi)
    except sympy.PolynomialError:
        return None, conds + [_cond("the weight is a polynomial in ξ", False, f"got {g}")]
    crit = [lo, hi]
    d = poly.diff(xi)
    if d.degree() > 0:
        for root in sympy.roots(d.as_expr(), xi, multiple=True):
            crit.append(root)
    vals = [sympy.simplify(g.subs(xi, c)) for c in crit]
    # only interior critical points matter; with parameters in g we use the ends for linear weights
    if poly.degree() > 1:
        return None, conds + [_cond("the weight is affine in ξ", False, f"degree {poly.degree()}")]
    vals = [sympy.simplify(g.subs(xi, lo)), sympy.simplify(g.subs(xi, hi))]
    if holder is None:
        if measure.kind == "window_integral":
            ok = bool(sympy.simplify(order - k) == 0)
            conds.append(_cond(f"the integrand's power {k} is the measure's order {order}", ok))
            mpow = 1
        elif measure.kind == "window_norm":
            ok = bool(sympy.simplify(order - k) == 0)
            conds.append(_cond(f"the integrand's power {k} is the measure's order {order}", ok))
            mpow = order
        else:
            return None, conds + [_cond("a window measure", False, f"{measure.name} is a {measure.kind}")]
        if lower:
            lo_vals = [v for v in vals]
            gmin = sympy.Min(*lo_vals) if len(set(lo_vals)) > 1 else lo_vals[0]
            s_ = _sign(gmin)
            conds.append(_cond(f"the weight is ≥ {gmin} ≥ 0 on the window (affine: its ends)", s_ == 1 or None))
            return (gmin, mpow), conds
        signs = [_sign(v) for v in vals]
        conds.append(_cond("the weight is ≥ 0 on the window (affine: its ends)", all(s_ == 1 for s_ in signs) or None,
                           f"ends {vals}"))
        gmax = vals[0] if len(set(vals)) == 1 else _max_of(vals)
        return (gmax, mpow), conds
    p, q = (ctx.at(x) for x in holder)
    conds.append(conjugate_exponents(p, q))
    if measure.kind != "window_norm":
        return None, conds + [_cond("Hölder needs a window norm (∫‖v‖^p)^{1/p}", False, f"{measure.name} is a "
                                    f"{measure.kind}")]
    conds.append(_cond(f"k·p = {k}·{p} is the measure's order {order}", bool(sympy.simplify(k * p - order) == 0),
                       f"k·p = {k * p}"))
    signs = [_sign(v) for v in vals]
    conds.append(_cond("the weight is ≥ 0 on the window (affine: its ends)", all(s_ == 1 for s_ in signs) or None))
    gq = sympy.integrate(g ** q, (xi, lo, hi))
    return (sympy.simplify(gq) ** (1 / q), k), conds


def _max_of(vals):
    d = sympy.simplify(vals[0] - vals[1])
    if d.is_nonnegative:
        return vals[0]
    if d.is_nonpositive:
        return vals[1]
    return sympy.Max(*vals)


def resolve_norm(nb: Norm, vector, ctx: Context) -> tuple:
    """(bound, conditions) proving ‖vector‖ ≤ bound by the norm tree ``nb`` (vector matched exactly).

    What a rule with a norm tree does inside; public for proof modules whose own conditions need a
    norm bound (a ``LowerBound``/``UpperBound`` check).  ``bound`` is None when the tree does not
    match; each condition carries its status.
    """
    conds = []
    vec = sympy.Matrix(ctx.at(sympy.Matrix(vector)))
    if callable(getattr(nb, "resolve", None)):  # a norm bound that resolves itself (steps.memory)
        return nb.resolve(vec, ctx, vector)
    if isinstance(nb.vector, tuple) and nb.vector[0] == "integrals":
        _, pointwise, measures, k, weight, constant = nb.vector
        return _resolve_integrals(vec, pointwise, measures, ctx.at(k), weight, constant, ctx, vector)
    if isinstance(nb.vector, tuple) and nb.vector[0] == "integral":
        _, pointwise, measure, k, weight, _window, holder = nb.vector
        k = ctx.at(k)
        parsed = _integrand(vec, pointwise, weight, ctx, vector)
        if parsed[0] is None:
            return None, parsed[1]
        (g, lo, hi, pb), pconds = parsed
        conds += pconds
        if pb is None:
            return None, conds
        P = measure.pointwise()
        conds.append(_cond(f"‖v(ξ)‖ ≤ ‖{measure.name}(ξ)‖^{k}", ctx.zero(ctx.pointwise(pb) - P ** k),
                           f"the pointwise bound is {pb}"))
        fac, wconds = _window_factor(g, lo, hi, measure, k, holder, ctx)
        conds += wconds
        if fac is None:
            return None, conds
        factor, mpow = fac
        return factor * measure.symbol ** mpow, conds
    if nb.how.startswith("‖Mv‖"):
        (inner,), (Mraw, kappa_raw) = nb.parts, nb.data
        M = sympy.Matrix(ctx.at(sympy.Matrix(Mraw)))
        kappa = ctx.at(kappa_raw)
        target = M * sympy.Matrix(ctx.at(sympy.Matrix(inner.vector)))
        if target.shape != vec.shape or not all(ctx.zero(x) for x in vec - target):
            return None, [_cond("the vector is M·v (‖Mv‖ ≤ κ‖v‖)", False, f"{list(vec)} is not {list(target)}")]
        conds += operator_norm_conditions(M, kappa)
        bi, ci = _resolve_norm(inner, inner.vector, ctx)
        conds += ci
        return (None if bi is None else kappa * bi), conds
    target = sympy.Matrix(ctx.at(sympy.Matrix(nb.vector)))
    if target.shape != vec.shape or not all(ctx.zero(x) for x in vec - target):
        return None, [_cond(f"the vector matches the norm bound's ({nb.how})", False,
                            f"{list(vec)} is not {list(target)}")]
    conds.append(_cond(f"the vector matches ({nb.how})", True))
    if nb.how == "unit vector":
        conds.append(_cond("it is a unit vector", _is_unit(vec, ctx), "not a unit state or unit parameter"))
        return sympy.S.One, conds
    if nb.how.startswith("‖a+b‖"):
        total = sympy.S.Zero
        for part in nb.parts:
            bp, cp = _resolve_norm(part, part.vector, ctx)
            conds += cp
            if bp is None:
                return None, conds
            total += bp
        return total, conds
    if nb.how.startswith("‖a×b‖"):
        a, b = nb.parts
        ba, ca = _resolve_norm(a, a.vector, ctx)
        bb, cb = _resolve_norm(b, b.vector, ctx)
        conds += ca + cb
        if ba is None or bb is None:
            return None, conds
        return ba * bb, conds
    if nb.how.startswith("|c|"):
        (inner,) = nb.parts
        bi, ci = _resolve_norm(inner, inner.vector, ctx)
        conds += ci + list(nb.conditions)
        if bi is None:
            return None, conds
        return ctx.at(nb.data[0]) * bi, conds
    return nb.bound, conds


_resolve_norm = resolve_norm


def _integrand(vec, pointwise, weight, ctx: Context, vector):
    """((g, lo, hi, pointwise bound), conditions) of a window integral ∫_{lo}^{hi} g(ξ)v(ξ)dξ, or (None, conditions)."""
    ints = list(vec)
    if not all(isinstance(c, sympy.Integral) and len(c.limits) == 1 for c in ints):
        return None, [_cond("the vector is a window integral ∫ g(ξ)v(ξ)dξ", False, f"got {vector}")]
    var, lo, hi = ints[0].limits[0]
    if any(c.limits[0] != (var, lo, hi) for c in ints):
        return None, [_cond("the components integrate over one window", False)]
    inner = sympy.Matrix([c.function for c in ints]).subs(var, xi)
    g = ctx.at(weight)
    pv = sympy.Matrix(ctx.at(sympy.Matrix(pointwise.vector)))
    conds = [_cond(f"the integrand is g(ξ)·v(ξ) with g = {g}", all(ctx.zero(x) for x in inner - g * pv), "it is not")]
    pb, pconds = _resolve_norm(pointwise, pv, ctx)
    return (g, lo, hi, pb), conds + pconds


def pointwise_constant(pb, measures, ps, k, constant, ctx: Context, same) -> tuple:
    """(κ, conditions) with B ≤ κ Σ‖v_i(ξ)‖^k for the pointwise bound ``pb`` of an integrand (κ None: not proved).

    ``pb`` is written in the measures' pointwise norms, renamed to ``ps``; B = Σ p_i^k gives κ = 1 when
    ``same(B − Σ p_i^k)`` holds, otherwise the homogeneous supremum is certified as ``constant`` (recorded
    in ``ctx.certified``).  Shared by window integrals (:func:`integral_of`) and memory integrals
    (``steps.memory``).
    """
    B = sympy.sympify(ctx.at(pb)).xreplace({m.pointwise_symbol: p for m, p in zip(measures, ps)})
    if B.atoms(AppliedUndef):
        return None, [_cond("the pointwise bound is written in the measures' pointwise norms", False, f"got {pb}")]
    T = sum((p**k for p in ps), sympy.S.Zero)
    if same(B - T):
        return sympy.S.One, []
    if constant is None:
        return None, [_cond(f"the pointwise bound is Σ‖v_i(ξ)‖^{k}", False, f"got {B}; name a constant= to "
                            f"certify a homogeneous bound")]
    from .templates import _homogeneous_sup  # at call time: steps.templates imports steps.rules, which imports this
    kappa, hconds, info = _homogeneous_sup(B, T, ps, ctx.seconds_left(), ctx.parameter_box)
    ctx.box_used = ctx.box_used or bool(ctx.parameter_box)
    if kappa is not None:
        ctx.certified[constant] = (info["certified"], info)
    return kappa, list(hconds)


def _resolve_integrals(vec, pointwise, measures, k, weight, constant, ctx: Context, vector):
    """‖∫ g v‖ ≤ max g · κ · Σ M_i for window-integral measures M_i of order k (see :func:`integral_of`)."""
    parsed = _integrand(vec, pointwise, weight, ctx, vector)
    if parsed[0] is None:
        return None, parsed[1]
    (g, lo, hi, pb), conds = parsed
    if pb is None:
        return None, conds
    ps = [sympy.Symbol(f"p_{m.name}", nonnegative=True) for m in measures]
    for m in measures:
        conds.append(_cond(f"{m.name} is a window integral of order {k}", m.kind == "window_integral"
                           and sympy.simplify(ctx.at(m.power) - k) == 0, f"{m.kind} of order {m.power}"))
    kappa, kconds = pointwise_constant(pb, measures, ps, k, constant, ctx, ctx.zero)
    conds += kconds
    if kappa is None:
        return None, conds
    fac, wconds = _window_factor(g, lo, hi, measures[0], k, None, ctx)
    conds += [c for c in wconds if "the integrand's power" not in c.text]
    if fac is None:
        return None, conds
    gmax, _ = fac
    return gmax * kappa * sum((m.symbol for m in measures), sympy.S.Zero), conds


def operator_norm_conditions(M, kappa) -> list:
    """The side conditions of ‖M v‖ ≤ κ‖v‖: κ ≥ 0 and κ²I − MᵀM ⪰ 0 (decided exactly, or in arb).

    Both are needed: κ²I − MᵀM ⪰ 0 alone also holds for κ = −‖M‖.

    Examples
    --------
    >>> import sympy
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), 1)]
    ['exact', 'exact']
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), sympy.Rational(1, 2))]
    ['exact', 'failed']
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), -1)]
    ['failed', 'exact']
    """
    M = sympy.Matrix(M)
    kappa = sympy.sympify(kappa)
    sk = _sign(kappa)
    conds = [_cond(f"κ = {kappa} ≥ 0", True if sk == 1 else (False if kappa.is_negative else None),
                   "κ is negative" if kappa.is_negative else "the sign of κ is not known")]
    res = matrix_positive_definite(kappa**2 * sympy.eye(M.shape[1]) - M.T * M, name="κ²I − MᵀM", semidefinite=True)
    conds.append(Condition(f"κ = {kappa} ≥ ‖M‖ (κ²I − MᵀM ⪰ 0)", res.status if res.status.is_proof else
                           (Status.FAILED if res.status is Status.FAILED else Status.UNDECIDED),
                           "" if res.status.is_proof else f"the operator norm is larger: {res.detail}"))
    return conds


def _is_unit(vec, ctx: Context) -> bool:
    return ctx.zero(sum(x**2 for x in vec) - 1)


def conjugate_exponents(p, q) -> Condition:
    """The side condition "p, q conjugate": 1/p + 1/q = 1 exactly and p > 1 (then q > 1 too).

    Decided exactly; symbolic exponents whose sign cannot be decided give ``undecided``.

    Examples
    --------
    >>> conjugate_exponents(3, sympy.Rational(3, 2)).status.value, conjugate_exponents(3, 2).status.value
    ('exact', 'failed')
    >>> conjugate_exponents(sympy.Rational(1, 2), -1).status.value     # 2 − 1 = 1 but p < 1
    'failed'
    """
    p, q = sympy.sympify(p), sympy.sympify(q)
    text = f"p = {p}, q = {q} conjugate (1/p + 1/q = 1, p > 1)"
    d = sympy.simplify(1 / p + 1 / q - 1)
    gt = sympy.simplify(p - 1)
    if d.is_zero is False or gt.is_positive is False:
        return _cond(text, False, f"1/p + 1/q = {sympy.simplify(1 / p + 1 / q)}, p − 1 = {gt}")
    if d == 0 and gt.is_positive:
        return _cond(text, True)
    return _cond(text, None, f"1/p + 1/q − 1 = {d}, p − 1 = {gt} not decided")
