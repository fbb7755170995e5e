"""Rewrites of a bound already derived: the small steps between a paper's estimates.

A :class:`~lkverify.certify.steps.chain.TermBound` applies its rule, then each rewrite
of ``then=`` in turn to the bound so far.  Every rewrite here is an inequality with its
side conditions checked exactly (structurally, on nonnegative measures):

* :class:`YoungEach` — Young's inequality on every additive term c·x·y that matches one of
  the given pairs (x, y), the sign of c checked against the direction;
* :class:`OnRegion` — x^a ≤ h^{a−k} x^k for a measure x ≤ h on the region (a ≥ k);
* :class:`RaiseOnRegion` — x^a ≥ h^{a−k} x^k for a measure x ≤ h on the region (0 < a < k, h > 0):
  a power raised in a term of the sign that lets the larger power replace the smaller;
* :class:`WindowHolder` — ∫‖v‖^k ≤ h^{1−k/P}(∫‖v‖^P)^{k/P} (Hölder on the window);
* :class:`PowerSplit` — (ΣA_i)^ν ≥ A_k^ν for A_i ≥ 0, ν > 0, in each term of the bound;
* :class:`LowerBound` — a measure replaced by a lower bound that a certified lemma gives on
  the region (e.g. (10) of paper 000: ‖L‖² ≥ ε(α1²‖s1−r1‖² + α2²‖s2−r2‖²)).

Substituting a bound for a measure is sound only where the expression is monotone in it;
that is checked by the sign of the partial derivative (structurally nonnegative for all
nonnegative measures and positive parameters).

Over a box of parameters (boxed parameters are symbols carrying their interval's sign) a
side condition is proved only when it holds for every value; one that is neither shown nor
refuted for every value (a sign that holds on part of the box) is ``undecided``, not ``failed``.

Examples
--------
>>> import sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, t
>>> from lkverify.certify.steps.measures import Region, norm_measure, sup_norm
>>> from lkverify.certify.steps.rules import Context
>>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
>>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
>>> a, b = norm_measure("a", x(t)), norm_measure("b", y(t))
>>> ctx = Context(sys_, P.resolve({}), {"a": a, "b": b}, Region({a: sympy.Rational(1, 10)}))
>>> A, B = a.symbol, b.symbol
>>> YoungEach(((A, B),)).rewrite(6 * A * B - B**2, ctx).bound          # 6ab ≤ 3a² + 3b²
3*a**2 + 2*b**2
>>> OnRegion("a", 2).rewrite(5 * A**3 * B, ctx).bound                  # a³ ≤ (1/10)a² on a ≤ 1/10
a**2*b/2
>>> RaiseOnRegion("a", 4).rewrite(-A**2 * B, ctx).bound              # −a² ≤ −100a⁴ on a ≤ 1/10
-100*a**4*b
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import sympy

from ...status import Status
from ..monomials import split_terms as _split
from .rules import Application, Condition, Rule, _cond, conjugate_exponents, nonnegative

__all__ = ["LowerBound", "OnRegion", "PowerSplit", "RaiseOnRegion", "WindowHolder", "YoungEach"]


def _measure_symbols(ctx) -> set:
    return {m.symbol for m in ctx.measures.values()}


def _signed(c, direction) -> bool | None:
    """Is the constant c of the sign that lets a bound x·y ≤ B be used in this direction (upper: c ≥ 0)?"""
    target = c if direction == "upper" else -c
    if nonnegative(target):
        return True
    if nonnegative(-target) and target != 0:
        return False
    return None


def _nonnegative_or_negative(e) -> bool | None:
    """True when e ≥ 0 (structurally), False when e < 0 for every value of its symbols (a negative number,
    or by the symbols' assumptions), None otherwise: a sign that holds on part of a parameter box only
    (a boxed symbol whose interval contains 0) is undecided, not refuted.

    >>> import sympy
    >>> c = sympy.Symbol("c", real=True)         # c ∈ [−1/10, 1]: the sign of a box symbol across 0
    >>> _nonnegative_or_negative(sympy.Rational(-1, 2)), _nonnegative_or_negative(c), _nonnegative_or_negative(c**2)
    (False, None, True)
    """
    e = sympy.sympify(e)
    if nonnegative(e):
        return True
    return False if e.is_negative else None


def _other_sign(ok) -> str:
    """The detail of a sign condition that is not proved: refuted, or not shown on every value."""
    return "it has the other sign" if ok is False else "its sign is not shown for every value of the parameters"


def _all_of(*oks) -> bool | None:
    """All of the tri-state decisions: False if one is False, True if all are True, else None."""
    if any(ok is False for ok in oks):
        return False
    return True if all(ok is True for ok in oks) else None


def _monotone(expr, symbol, increasing: bool) -> bool:
    """Is expr structurally nondecreasing (``increasing``) or nonincreasing in ``symbol`` ≥ 0?"""
    d = sympy.diff(expr, symbol)
    d = d if increasing else -d
    return d == 0 or nonnegative(sympy.factor_terms(d)) or nonnegative(sympy.expand(d))


def _substitute(previous, symbol, replacement, side: str, direction: str, what: str):
    """(bound, conditions): ``symbol`` replaced by ``replacement`` (symbol ≤ it for side "upper", ≥ for "lower")."""
    increasing = (side == "upper") == (direction == "upper")
    ok = _monotone(previous, symbol, increasing)
    cond = _cond(f"the bound is {'nondecreasing' if increasing else 'nonincreasing'} in {symbol}, so {what} may "
                 f"replace it", ok or None, f"∂/∂{symbol} of {previous} is not shown to have that sign")
    return sympy.expand(previous.xreplace({symbol: replacement})), [cond]


@dataclasses.dataclass(frozen=True)
class YoungEach(Rule):
    """c·x·y ≤ c(ε x^p/p + ε^{−q/p} y^q/q) on every additive term c·x·y matching one of ``pairs``.

    ``pairs``: tuples (x, y) or (x, y, p, q, ε) in measures (p = q = 2, ε = 1 by default;
    ε may be an expression in the parameters).  For an upper bound c ≥ 0 is required, for a
    lower bound c ≤ 0 (then c·x·y ≥ c(…)).  Terms that match no pair are kept.


    ==============================  ==========================================================
    licenses                        c·x·y ≤ c(ε x^p/p + ε^{−q/p} y^q/q) on each matching term
    direction                       ≤ steps with c ≥ 0; ≥ steps with c ≤ 0 (per term)
    side conditions                 p, q conjugate with p > 1; ε > 0; x, y ≥ 0; the sign of
                                    each matched coefficient; some term matches
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> a, b = norm_measure("a", x(t)), norm_measure("b", y(t)); A, B = a.symbol, b.symbol
    >>> ctx = Context(sys_, P.resolve({}), {"a": a, "b": b})
    >>> YoungEach(((A, B, 2, 2, sympy.Rational(1, 2)),)).rewrite(-4 * A * B, ctx, "lower").bound
    -a**2 - 4*b**2
    >>> YoungEach(((A, B),)).rewrite(-4 * A * B, ctx, "upper").status.value    # −4ab ≤ … needs c ≥ 0
    'failed'
    """

    pairs: tuple
    name = "Young's inequality with a parameter, term by term"
    directional = True

    def _pairs(self, ctx):
        out = []
        for pair in self.pairs:
            x, y, p, q, eps = (tuple(pair) + (2, 2, 1)[len(pair) - 2:])[:5]
            out.append(tuple(ctx.at(v) for v in (x, y, p, q, eps)))
        return out

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        syms = _measure_symbols(ctx)
        pairs = self._pairs(ctx)
        conds, total, used = [], sympy.S.Zero, 0
        for x, y, p, q, eps in pairs:
            conds.append(conjugate_exponents(p, q))
            conds.append(_cond(f"ε = {eps} > 0", bool(eps.is_positive) or None))
            conds.append(_cond(f"{x}, {y} ≥ 0", nonnegative(x) and nonnegative(y)))
        for c, m in _split(ctx.at(previous), syms):
            for x, y, p, q, eps in pairs:
                ratio = sympy.powsimp(sympy.expand_power_base(m / (x * y), force=True), force=True)
                if ratio.free_symbols & syms:
                    continue
                c = c * ratio
                ok = _signed(c, direction)
                conds.append(_cond(f"the coefficient {c} of ({x})·({y}) is {'≥' if direction == 'upper' else '≤'} 0",
                                   ok, _other_sign(ok)))
                total += c * (eps * x**p / p + eps ** (-q / p) * y**q / q)
                used += 1
                break
            else:
                total += c * m
        conds.append(_cond("some term is a product x·y of a pair", used > 0, f"no term of {previous} matches"))
        return Application(self.name, sympy.expand(total), tuple(conds))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


def _region_bound(rule, ctx, *, strict: bool):
    """(measure, its symbol x, k, h, conditions, h's sign) of a rule on the region's bound x ≤ h (h None: none).

    The conditions: the region bounds the measure, and h ≥ 0 (``strict``: h > 0) for every value.
    """
    m = ctx.measure(rule.measure)
    x, k = m.symbol, ctx.at(rule.keep)
    h = None if ctx.region is None else ctx.region.bound_of(m, ctx.sub)
    conds = [_cond(f"the region bounds {m.text}", h is not None, "no bound on it follows from the region")]
    if h is None:
        return m, x, k, None, conds, None
    h = ctx.at(h)
    if strict:
        h_ok = _positive_or_not(h)
        conds.append(_cond(f"{m.text} ≤ {h}, h > 0", h_ok,
                           "h ≤ 0" if h_ok is False else "h > 0 is not shown for every value of the parameters"))
    else:
        h_ok = _nonnegative_or_negative(h)
        conds.append(_cond(f"{m.text} ≤ {h}, h ≥ 0", h_ok,
                           "h < 0" if h_ok is False else "the sign of h is not shown for every value of the parameters"))
    return m, x, k, h, conds, h_ok


@dataclasses.dataclass(frozen=True)
class OnRegion(Rule):
    """x^a ≤ h^{a−k}·x^k on the region x ≤ h, for every term with x^a, a > k (``keep`` = k).

    The term's other factor must have the sign that lets the smaller power replace the larger
    (≥ 0 in an upper bound, ≤ 0 in a lower bound); h is the region's bound on the measure
    (:meth:`~lkverify.certify.steps.measures.Region.bound_of`: a norm at t or t − c, a window
    integral or norm, from the sup over the window).


    ==============================  ==========================================================
    licenses                        x^a ≤ h^{a−k}x^k for 0 ≤ x ≤ h, a > k
    direction                       ≤ steps: the term's other factor ≥ 0; ≥ steps: ≤ 0
    side conditions                 the region bounds the measure by h; h ≥ 0; the factor's
                                    sign; some term has a power above k
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import Region, norm_measure
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); a = norm_measure("a", x(t)); A = a.symbol
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"a": a},
    ...               Region({a: sympy.Rational(1, 4)}))
    >>> OnRegion("a", 2).rewrite(-A**3, ctx, "lower").bound              # −a³ ≥ −a²/4
    -a**2/4
    >>> OnRegion("a", 2).rewrite(-A**3, ctx, "upper").status.value       # −a³ ≤ −a²/4 is false
    'failed'
    """

    measure: str
    keep: object = 0
    name = "a power lowered on the region (x ≤ h ⇒ x^a ≤ h^{a−k}x^k)"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        m, x, k, h, conds, _ = _region_bound(self, ctx, strict=False)
        if h is None:
            return Application(self.name, None, tuple(conds))
        syms = _measure_symbols(ctx)
        total, used = sympy.S.Zero, 0
        for c, mono in _split(ctx.at(previous), syms):
            powers = sympy.powsimp(mono, force=True).as_powers_dict()
            a = powers.get(x, sympy.S.Zero)
            if not (sympy.sympify(a - k).is_positive):
                total += c * mono
                continue
            rest = c * mono / x**a
            ok = _signed(rest, direction)
            conds.append(_cond(f"the factor {rest} of {x}^{a} is {'≥' if direction == 'upper' else '≤'} 0", ok,
                               _other_sign(ok)))
            total += rest * h ** (a - k) * x**k
            used += 1
        conds.append(_cond(f"some term has a power of {x} above {k}", used > 0, f"none in {previous}"))
        return Application(self.name, sympy.expand(total), tuple(conds))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


def _positive_or_not(e) -> bool | None:
    """True when e > 0 for every value of its symbols, False when e ≤ 0 (0 included) for every value, else None.

    >>> import sympy
    >>> c = sympy.Symbol("c", real=True)
    >>> _positive_or_not(sympy.Rational(1, 4)), _positive_or_not(0), _positive_or_not(c), _positive_or_not(c**2)
    (True, False, None, None)
    """
    e = sympy.sympify(e)
    if e.is_positive:
        return True
    return False if e.is_nonpositive else None


@dataclasses.dataclass(frozen=True)
class RaiseOnRegion(Rule):
    """x^a ≥ h^{a−k}·x^k on the region 0 ≤ x ≤ h (h > 0), for every term with x^a, 0 < a < k (``keep`` = k).

    The sibling of :class:`OnRegion` that raises a power: x^a = x^k·x^{a−k} and x^{a−k} ≥ h^{a−k}
    for 0 < x ≤ h since a − k < 0 (x = 0: both sides 0).  A term c·x^a may be replaced by
    c·h^{a−k}x^k only when c ≤ 0 in an upper bound (then c·x^a ≤ c·h^{a−k}x^k) and c ≥ 0 in a lower
    bound.  This is how a damping −h‖ω‖^{μ+1} absorbs the ‖ω‖^{σ+1} of other terms near 0 when
    σ > μ: −w^{μ+1} ≤ −δ^{μ−σ}w^{σ+1} on w ≤ δ.  Terms whose power of x is not in (0, k)
    (x absent included) are kept as they are; h = 0 is refused (h^{a−k} is not finite).

    ``share`` = θ raises only the part θ of each such term and keeps the rest:
    c·x^a = θc·x^a + (1−θ)c·x^a ≤ θc·h^{a−k}x^k + (1−θ)c·x^a (for c ≤ 0), so a damping can meet both
    its own power and the raised one (θ = 1, the default: the whole term).


    ==============================  ==========================================================
    licenses                        x^a ≥ h^{a−k}x^k for 0 ≤ x ≤ h, h > 0, 0 < a < k (on the
                                    share θ of each term, 0 < θ ≤ 1)
    direction                       ≤ steps: each raised term's factor ≤ 0; ≥ steps: ≥ 0
    side conditions                 the region bounds the measure by h; h > 0 for every value
                                    of the parameters; 0 < θ ≤ 1; each raised factor's sign;
                                    some term has a power of x below k
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import Region, norm_measure
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); a = norm_measure("a", x(t)); A = a.symbol
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"a": a},
    ...               Region({a: sympy.Rational(1, 2)}))
    >>> RaiseOnRegion("a", 6).rewrite(-4 * A**4, ctx, "upper").bound      # −4a⁴ ≤ −16a⁶ on a ≤ 1/2
    -16*a**6
    >>> RaiseOnRegion("a", 6).rewrite(4 * A**4, ctx, "upper").status.value  # 4a⁴ ≤ 16a⁶ is false
    'failed'
    >>> RaiseOnRegion("a", 6, share=sympy.Rational(1, 2)).rewrite(-4 * A**4, ctx, "upper").bound
    -8*a**6 - 2*a**4
    """

    measure: str
    keep: object
    share: object = 1
    name = "a power raised on the region (0 ≤ x ≤ h, h > 0 ⇒ x^a ≥ h^{a−k}x^k)"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        m, x, k, h, conds, h_ok = _region_bound(self, ctx, strict=True)
        if h is None:
            return Application(self.name, None, tuple(conds))
        theta = ctx.at(self.share)
        theta_ok = _all_of(_positive_or_not(theta), _nonnegative_or_negative(1 - theta))
        conds.append(_cond(f"the share θ = {theta} raised: 0 < θ ≤ 1", theta_ok,
                           "it is not" if theta_ok is False else "not shown for every value of the parameters"))
        if h_ok is False:
            return Application(self.name, None, tuple(conds))
        total, used = sympy.S.Zero, 0
        for c, mono in _split(ctx.at(previous), _measure_symbols(ctx)):
            a = sympy.powsimp(mono, force=True).as_powers_dict().get(x, sympy.S.Zero)
            if not (sympy.sympify(a).is_positive and sympy.sympify(k - a).is_positive):
                total += c * mono
                continue
            rest = c * mono / x**a
            ok = _signed(-rest, direction)
            conds.append(_cond(f"the factor {rest} of {x}^{a} is {'≤' if direction == 'upper' else '≥'} 0", ok,
                               _other_sign(ok)))
            total += theta * rest * h ** (a - k) * x**k + (1 - theta) * c * mono
            used += 1
        conds.append(_cond(f"some term has a power of {x} in (0, {k})", used > 0, f"none in {previous}"))
        return Application(self.name, sympy.expand(total), tuple(conds))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


@dataclasses.dataclass(frozen=True)
class WindowHolder(Rule):
    """∫_{t−h}^t‖v‖^k ≤ h^{1−k/P}(∫_{t−h}^t‖v‖^P)^{k/P} (Hölder, P ≥ k): measure ``source`` by ``target``.

    ``source`` is a window integral of order k, ``target`` a window integral of order P of the
    same vector over the same window; the bound must be monotone in the source (checked).


    ==============================  ==========================================================
    licenses                        ∫‖v‖^k ≤ h^{1−k/P}(∫‖v‖^P)^{k/P} over one window, 0 < k ≤ P
    direction                       the bound nondecreasing in the source (≤ steps) or
                                    nonincreasing (≥ steps), checked by ∂/∂(source)
    side conditions                 both window integrals of one vector over one window;
                                    0 < k ≤ P; h ≥ 0; the monotonicity
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t, xi
    >>> from lkverify.certify.steps.measures import norm_measure, window_integral_measure
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> K, I = (window_integral_measure(n, x(xi), p=p, window=4) for n, p in (("K", 1), ("I", 2)))
    >>> w = norm_measure("w", y(t)); ctx = Context(sys_, P.resolve({}), {"K": K, "I": I, "w": w})
    >>> WindowHolder("K", "I").rewrite(3 * w.symbol * K.symbol, ctx).bound     # ∫‖x‖ ≤ 2(∫‖x‖²)^{1/2}
    6*sqrt(I)*w
    """

    source: str
    target: str
    name = "Hölder on the window (∫‖v‖^k ≤ h^{1−k/P}(∫‖v‖^P)^{k/P})"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        src, tgt = ctx.measure(self.source), ctx.measure(self.target)
        k, P = ctx.at(src.power), ctx.at(tgt.power)
        h = ctx.at(src.window)
        same = (src.kind == "window_integral" and tgt.kind == "window_integral" and src.vector == tgt.vector
                and sympy.simplify(h - ctx.at(tgt.window)) == 0)
        conds = [_cond(f"{src.name}, {tgt.name}: window integrals of one vector over one window", same,
                       f"{src.kind} of {src.vector.T}, {tgt.kind} of {tgt.vector.T}"),
                 _cond(f"orders k = {k} ≤ P = {P}", _all_of(_nonnegative_or_negative(P - k),
                                                           sympy.sympify(k).is_positive),
                       "not shown for every value of the parameters"),
                 _cond(f"window length {h} ≥ 0", _nonnegative_or_negative(h),
                       "not shown for every value of the parameters")]
        bound, more = _substitute(ctx.at(previous), src.symbol, h ** (1 - k / P) * tgt.symbol ** (k / P), "upper",
                                  direction, f"h^(1−k/P)·{tgt.name}^(k/P) ≥ {src.name}")
        return Application(self.name, bound, tuple(conds + more))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


@dataclasses.dataclass(frozen=True)
class PowerSplit(Rule):
    """(A_1 + … + A_n)^ν ≥ A_k^ν (A_i ≥ 0, ν > 0) in every additive term c·(ΣA_i)^ν·R of the bound.

    A_k is the summand whose measures R contains (the first summand otherwise); c·R must be
    ≤ 0 in an upper bound (≥ 0 in a lower one), so that the smaller power may replace the
    larger.  Applied to −c7 f^ν(α1²e1² + α2²e2²) it gives −c7((α1/2)^ν α1² e1^{2ν+2} + …).


    ==============================  ==========================================================
    licenses                        (ΣA_i)^ν ≥ A_k^ν for A_i ≥ 0, ν > 0
    direction                       ≤ steps: the factor c·R ≤ 0; ≥ steps: c·R ≥ 0
    side conditions                 every A_i ≥ 0; ν > 0; the factor's sign; some term has a
                                    power of a sum of measures
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> a, b = norm_measure("a", x(t)), norm_measure("b", y(t)); A, B = a.symbol, b.symbol
    >>> ctx = Context(sys_, P.resolve({}), {"a": a, "b": b})
    >>> PowerSplit().rewrite(-(A**2 + B**2) ** sympy.Rational(1, 2) * (A**2 + 2 * B**2), ctx).bound
    -a**3 - 2*b**3
    >>> PowerSplit().rewrite((A**2 + B**2) ** sympy.Rational(1, 2) * A, ctx).status.value   # c·R ≥ 0: wrong way
    'failed'
    """

    name = "(ΣA_i)^ν ≥ A_k^ν for A_i ≥ 0, ν > 0 (a power of a sum split)"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        syms = _measure_symbols(ctx)
        conds, total, used = [], sympy.S.Zero, 0
        for term in sympy.Add.make_args(sympy.expand(ctx.at(previous))):
            factors = sympy.Mul.make_args(term)
            pw = [f for f in factors if isinstance(f, sympy.Pow) and isinstance(f.base, sympy.Add)
                  and f.base.free_symbols & syms and not f.exp.free_symbols & syms]
            if len(pw) != 1:
                total += term
                continue
            power = pw[0]
            rest = sympy.Mul(*[f for f in factors if f is not power])
            A = list(sympy.Add.make_args(power.base))
            own = rest.free_symbols & syms
            pick = next((x for x in A if x.free_symbols & syms and x.free_symbols & syms <= own), A[0])
            conds.append(_cond(f"the summands of {power.base} are ≥ 0 and ν = {power.exp} > 0",
                               all(nonnegative(x) for x in A) and bool(sympy.sympify(power.exp).is_positive)))
            ok = _signed(-rest, direction)
            conds.append(_cond(f"the factor {rest} is {'≤' if direction == 'upper' else '≥'} 0", ok,
                               _other_sign(ok)))
            total += rest * sympy.powsimp(sympy.expand_power_base(pick ** power.exp, force=True), force=True)
            used += 1
        conds.append(_cond("some term has a power of a sum of measures", used > 0, f"none in {previous}"))
        return Application(self.name, sympy.expand(total), tuple(conds))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


@dataclasses.dataclass(frozen=True)
class LowerBound(Rule):
    """A measure m replaced by a lower bound ℓ ≤ m that a certified lemma gives on the region.

    ``certify(ctx)`` decides the lemma at the checked values and region and returns a
    :class:`~lkverify.certify.steps.rules.Condition` (certified, failed or undecided);
    ``bound`` is ℓ in the other measures.  The bound so far must be nonincreasing in m for an
    upper bound (nondecreasing for a lower one), checked structurally.


    ==============================  ==========================================================
    licenses                        m ≥ ℓ (LowerBound) or m ≤ u (UpperBound) from a lemma
    direction                       the bound nonincreasing in m (≤ steps with ℓ, ≥ steps with
                                    u) or nondecreasing (the other two), checked by ∂/∂m
    side conditions                 the lemma, decided at the values on the region (its own
                                    status); the monotonicity
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import Condition, Context
    >>> from lkverify.status import Status
    >>> P = Parameters(); x = Vector("x", 2); a, n = norm_measure("a", x(t)), norm_measure("n", 2 * x(t))
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"a": a, "n": n})
    >>> lemma = lambda ctx: Condition("‖2x‖ ≥ ‖x‖", Status.EXACT)
    >>> LowerBound("n", a.symbol, lemma, "‖2x‖ ≥ ‖x‖").rewrite(-3 * n.symbol**2, ctx).bound
    -3*a**2
    >>> LowerBound("n", a.symbol, lemma, "‖2x‖ ≥ ‖x‖").rewrite(3 * n.symbol**2, ctx).status.value
    'undecided'
    """

    measure: str
    bound: object
    certify: Callable
    text: str = "a lemma"
    name = "a lower bound from a certified lemma"
    directional = True
    side = "lower"  # the bound replaces m from below (LowerBound) or from above (UpperBound)

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        m = ctx.measure(self.measure)
        decided = self.certify(ctx)
        if not isinstance(decided, Condition):
            decided = Condition(self.text, Status.UNDECIDED, f"the check returned {type(decided).__name__}")
        bound, more = _substitute(ctx.at(previous), m.symbol, ctx.at(self.bound), self.side, direction,
                                  f"{self.text} (an {self.side} bound)" if self.side == "upper"
                                  else f"{self.text} (a {self.side} bound)")
        return Application(self.name, bound, (decided, *more))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)

