"""Certification over a box of parameters: symbols that stand for every point, enclosures, uniform bounds.

A theorem over a :class:`~lkverify.declare.boxes.ParameterBox` is checked with each boxed
parameter replaced by a fresh symbol carrying the sign its interval has (``b ∈ [−11/10,
−9/10]`` becomes a symbol ``b`` with ``negative=True``).  What a rule then proves with
that symbol holds for every value of that sign, so for every point of the box; what
needs the ends (a hypothesis' margin, a coefficient of the decay model, a template
supremum) is enclosed over the intervals with outward-rounded ball arithmetic
(:func:`lkverify.certify.intervals.enclose`), so it is at most ``certified``.

Functions here state what they license:

* :func:`margin_over_box` — ``margin > 0`` (``≥ 0``) at every point of the box, from an
  enclosure of the margin over it; a point of the box where it fails, from exact
  evaluation at the corners and the centre;
* :func:`uniform_bound` — for an upper bound (≤) ``Σ c_k(p) m^k ≤ Σ (sup_B c_k) m^k`` and
  for a lower bound (≥) ``Σ c_k(p) m^k ≥ Σ (inf_B c_k) m^k``, valid when every monomial
  ``m^k`` is ≥ 0, i.e. every variable ``m`` is a nonnegative measure (checked; otherwise
  :class:`~lkverify.errors.UnsupportedInput`).

Examples
--------
>>> import sympy
>>> from lkverify.declare.boxes import ParameterBox
>>> b = box_symbol("b", (sympy.Rational(-11, 10), sympy.Rational(-9, 10)))
>>> b.is_negative
True
>>> w = sympy.Symbol("w", nonnegative=True)
>>> uniform_bound(-b * w**2 - 3 * w, {b: (sympy.Rational(-11, 10), sympy.Rational(-9, 10))}, {w}, "upper")
11*w**2/10 - 3*w
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from ..errors import UnsupportedInput
from ..status import Status

__all__ = ["box_symbol", "enclose_over", "exact_interval", "margin_over_box", "uniform_bound", "upper_rational", "lower_rational"]


def box_symbol(name: str, interval: tuple, *, positive: bool = False, nonnegative: bool = False) -> sympy.Symbol:
    """A symbol standing for every value of ``interval``: the sign the interval (or the parameter's kind) has.

    >>> box_symbol("tau", (0, 1), positive=True).is_positive, box_symbol("a", (0, 1)).is_nonnegative
    (True, True)
    >>> box_symbol("c", (-1, 1)).is_nonnegative is None
    True
    """
    lo, hi = interval
    if positive or lo > 0:
        return sympy.Symbol(name, positive=True)
    if hi < 0:
        return sympy.Symbol(name, negative=True)
    if nonnegative or lo >= 0:
        return sympy.Symbol(name, nonnegative=True)
    if hi <= 0:
        return sympy.Symbol(name, nonpositive=True)
    return sympy.Symbol(name, real=True)


def enclose_over(expr, intervals: Mapping):
    """An arb ball containing ``expr`` at every point of the intervals (symbol → (lo, hi))."""
    from .intervals import enclose

    expr = sympy.sympify(expr)
    used = {s: intervals[s] for s in expr.free_symbols if s in intervals}
    missing = expr.free_symbols - set(used)
    if missing:
        raise UnsupportedInput(f"{expr}: the symbols {', '.join(sorted(map(str, missing)))} have no interval")
    for prec in (128, 512):
        ball = enclose(expr, {s: (sympy.Rational(lo), sympy.Rational(hi)) if lo != hi else sympy.Rational(lo)
                              for s, (lo, hi) in used.items()}, prec=prec)
        if ball.is_finite():
            return ball
    return ball


def exact_interval(expr, intervals: Mapping):
    """(lo, hi) exact rationals containing ``expr`` over the intervals, by rational interval arithmetic, or None.

    Covers sums, products, integer powers and ``Abs`` of rationals and boxed symbols (what
    polynomial margins and coefficients are made of); anything else (roots, functions) is None
    and goes to ball arithmetic.

    >>> import sympy
    >>> b, tau = sympy.symbols("b tau")
    >>> exact_interval(-b * tau + b**2, {b: (-2, -1), tau: (1, 2)})
    (2, 8)
    >>> exact_interval(sympy.sqrt(tau), {tau: (1, 2)}) is None
    True
    """
    e = sympy.sympify(expr)
    if e.is_Rational:
        return (e, e)
    if e in intervals:
        lo, hi = intervals[e]
        return (sympy.Rational(lo), sympy.Rational(hi))
    if isinstance(e, (sympy.Add, sympy.Mul)):
        parts = [exact_interval(a, intervals) for a in e.args]
        if any(p is None for p in parts):
            return None
        lo, hi = parts[0]
        for a, b in parts[1:]:
            if isinstance(e, sympy.Add):
                lo, hi = lo + a, hi + b
            else:
                ends = (lo * a, lo * b, hi * a, hi * b)
                lo, hi = min(ends), max(ends)
        return (lo, hi)
    if isinstance(e, sympy.Pow) and e.exp.is_Integer and e.exp > 0:
        base = exact_interval(e.base, intervals)
        if base is None:
            return None
        n, (lo, hi) = int(e.exp), base
        ends = (lo ** n, hi ** n)
        if n % 2 == 0 and lo <= 0 <= hi:
            return (sympy.S.Zero, max(ends))
        return (min(ends), max(ends))
    if isinstance(e, sympy.Abs):
        inner = exact_interval(e.args[0], intervals)
        if inner is None:
            return None
        lo, hi = inner
        if lo >= 0:
            return (lo, hi)
        if hi <= 0:
            return (-hi, -lo)
        return (sympy.S.Zero, max(-lo, hi))
    return None


def upper_rational(ball) -> sympy.Rational | None:
    """The exact rational upper end of a ball (None if not finite)."""
    from .intervals.rounding import upper_fraction

    q = upper_fraction(ball)
    return None if q is None else sympy.Rational(q.numerator, q.denominator)


def lower_rational(ball) -> sympy.Rational | None:
    """The exact rational lower end of a ball (None if not finite)."""
    from .intervals.rounding import lower_fraction

    q = lower_fraction(ball)
    return None if q is None else sympy.Rational(q.numerator, q.denominator)


def _end_of(c, intervals: Mapping, direction: str):
    """sup (upper) or inf (lower) of the coefficient ``c`` over the intervals, as an exact number."""
    c = sympy.sympify(c)
    if not (c.free_symbols & set(intervals)):
        if c.free_symbols:
            raise UnsupportedInput(f"the coefficient {c} has symbols without an interval")
        return c
    exact = exact_interval(c, intervals)
    if exact is not None:
        return exact[1] if direction == "upper" else exact[0]
    ball = enclose_over(c, intervals)
    end = upper_rational(ball) if direction == "upper" else lower_rational(ball)
    if end is None:
        raise UnsupportedInput(f"the coefficient {c} has no finite enclosure over the box")
    return end


def uniform_bound(expr, intervals: Mapping, variables, direction: str):
    """``expr`` (a sum of monomials in the nonnegative ``variables``) with each coefficient replaced by its
    supremum (``direction="upper"``) or infimum (``"lower"``) over the intervals, outward rounded.

    Licenses ``expr(p) ≤ uniform_bound(…, "upper")`` and ``expr(p) ≥ uniform_bound(…, "lower")`` for every
    point p of the intervals and every value of the variables ≥ 0.

    Raises
    ------
    UnsupportedInput
        A variable not known to be ≥ 0 (then a monomial may be negative), or a coefficient without
        a finite enclosure.

    >>> import sympy
    >>> p = sympy.Symbol("p", positive=True); x = sympy.Symbol("x", nonnegative=True)
    >>> uniform_bound(p * x - p**2 * x**3, {p: (1, 2)}, {x}, "lower")
    -4*x**3 + x
    >>> uniform_bound(p * sympy.Symbol("y"), {p: (1, 2)}, {sympy.Symbol("y")}, "upper")
    Traceback (most recent call last):
    ...
    lkverify.errors.UnsupportedInput: a uniform bound over the box needs nonnegative variables (every monomial ≥ 0); y is not known to be ≥ 0
    """
    from .monomials import collect_monomials

    if direction not in ("upper", "lower"):
        raise ValueError(f"direction: expected 'upper' or 'lower', got {direction!r}")
    variables = set(variables)
    bad = sorted(str(v) for v in variables if not v.is_nonnegative)
    if bad:
        raise UnsupportedInput(f"a uniform bound over the box needs nonnegative variables (every monomial ≥ 0); "
                               f"{', '.join(bad)} is not known to be ≥ 0")
    expr = sympy.expand(sympy.powsimp(sympy.expand(expr), force=True))
    if not (expr.free_symbols & set(intervals)):
        return expr
    out = sympy.S.Zero
    for mono, c in collect_monomials(expr, variables).items():
        if mono.free_symbols & set(intervals):
            raise UnsupportedInput(f"the monomial {mono} has a boxed parameter in an exponent")
        out += _end_of(c, intervals, direction) * mono
    return out


def _num(q) -> str:
    """A rational shown exactly when short, else to 6 digits."""
    return str(q) if len(str(q)) <= 12 else f"{float(q):.6g}"


def _point_margin(margin, point: Mapping):
    return sympy.sympify(margin).xreplace({s: sympy.Rational(v) for s, v in point.items()})


def margin_over_box(margin, intervals: Mapping, *, strict: bool = True):
    """(status, holds, detail, failing point or None) of ``margin > 0`` (``≥ 0``) over the box.

    ``holds`` is True when an enclosure over the whole box is > 0 (≥ 0) — or the margin is
    free of the boxed symbols and its sign is decided — False when the margin fails at a
    corner or the centre of the box (exactly, or by an enclosure of that point), None when
    neither is shown (the box must be split).  The failing point is a mapping symbol → value.

    >>> import sympy
    >>> b = sympy.Symbol("b", negative=True); tau = sympy.Symbol("tau", positive=True)
    >>> margin_over_box(-b * tau, {b: (-2, -1), tau: (1, 2)})[:3]
    (<Status.EXACT: 'exact'>, True, 'margin > 0 over the whole box (enclosure [1, 4] by rational interval arithmetic)')
    >>> st, holds, detail, point = margin_over_box(1 + b * tau, {b: (-2, -1), tau: (1/2, 1)})
    >>> holds, {str(k): v for k, v in point.items()}        # 1 + bτ = 0 there: not > 0
    (False, {'b': -2, 'tau': 1/2})
    """
    from .intervals import sign_of

    margin = sympy.sympify(margin)
    rel = ">" if strict else "≥"
    boxed = margin.free_symbols & set(intervals)
    if not boxed:
        return None, None, "free of the box", None
    exact = exact_interval(margin, intervals)
    if exact is not None:
        (lo, hi), how = exact, Status.EXACT
    else:
        ball = enclose_over(margin, intervals)
        (lo, hi), how = (lower_rational(ball), upper_rational(ball)), Status.CERTIFIED
    text = f"[{_num(lo)}, {_num(hi)}]" if lo is not None and hi is not None else "not finite"
    if lo is not None and (lo > 0 or (not strict and lo >= 0)):
        kind = "rational interval arithmetic" if how is Status.EXACT else "ball arithmetic"
        return how, True, f"margin {rel} 0 over the whole box (enclosure {text} by {kind})", None
    syms = sorted(boxed, key=lambda s: s.name)
    import itertools

    axes = [sorted({sympy.Rational(intervals[s][0]), sympy.Rational(intervals[s][1])}) for s in syms]
    points = [dict(zip(syms, c)) for c in itertools.product(*axes)]
    points.append({s: (sympy.Rational(intervals[s][0]) + sympy.Rational(intervals[s][1])) / 2 for s in syms})
    for point in points:
        m = _point_margin(margin, point)
        if m.is_Rational:
            fails, status = (m <= 0 if strict else m < 0), Status.EXACT
        else:
            sr = sign_of(m)
            if sr.sign is None:
                continue
            fails, status = (sr.sign <= 0 if strict else sr.sign < 0), Status.CERTIFIED
        if fails:
            where = ", ".join(f"{s} = {v}" for s, v in point.items())
            return status, False, f"fails at the point {where} of the box: margin {m}, need {rel} 0", point
    return Status.UNDECIDED, None, f"the enclosure {text} of the margin over the box contains 0; split the box", None
