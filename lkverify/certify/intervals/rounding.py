"""Outward rounding: the one routine that turns balls and rationals into floats and fractions.

An end point is read exactly (mantissa and exponent) and rounded in the stated direction,
so a float produced here is a proved bound at any arb precision.

Examples
--------
>>> from fractions import Fraction
>>> float_down(Fraction(1, 3)) < float_up(Fraction(1, 3))
True
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction

import sympy
from flint import arb, fmpq

from ...errors import InputError
__all__ = ["float_down", "float_up", "lower_fraction", "upper_fraction"]

# ---------------------------------------------------------------------------
# outward rounding: the one routine
# ---------------------------------------------------------------------------

_MAX = sys.float_info.max
_TINY = math.ulp(0.0)                # the smallest positive subnormal


def _point_fraction(p: arb) -> Fraction:
    """The exact value of an exact, finite arb point (mantissa · 2**exponent)."""
    m, e = p.man_exp()
    m, e = int(m), int(e)
    return Fraction(m << e) if e >= 0 else Fraction(m, 1 << -e)


def _round(q: Fraction, up: bool) -> float:
    """The float nearest to the rational ``q`` in the direction ``up`` (≥ q) or down (≤ q)."""
    try:
        f = q.numerator / q.denominator           # correctly rounded (nearest)
    except OverflowError:
        f = math.inf if q > 0 else -math.inf
    if math.isinf(f):
        if up:
            return f if f > 0 else -_MAX
        return f if f < 0 else _MAX
    exact = Fraction(f)
    if up and exact < q:
        return math.nextafter(f, math.inf)
    if not up and exact > q:
        return math.nextafter(f, -math.inf)
    return f


def _round_point(p: arb, up: bool) -> float:
    """An exact arb point rounded to a float in the direction ``up``."""
    m, e = p.man_exp()
    m, e = int(m), int(e)
    if m == 0:
        return 0.0
    top = m.bit_length() if m > 0 else (-m).bit_length()
    if top <= 53 and -1021 <= e + top <= 1024:
        return math.ldexp(float(m), e)            # exactly representable (normal range)
    if e + top > 1100:                            # |p| > 2**1099: beyond every float
        if up:
            return math.inf if m > 0 else -_MAX
        return _MAX if m > 0 else -math.inf
    if e + top < -1100:                           # 0 < |p| < 2**-1100: below every subnormal
        if up:
            return _TINY if m > 0 else -0.0
        return 0.0 if m > 0 else -_TINY
    return _round(_point_fraction(p), up)


def _as_fraction(x) -> Fraction:
    if isinstance(x, Fraction):
        return x
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return Fraction(x)
    if isinstance(x, sympy.Rational):
        return Fraction(int(x.p), int(x.q))
    if isinstance(x, fmpq):
        return Fraction(int(x.p), int(x.q))
    raise InputError(f"expected an arb ball or an exact rational (Fraction, int, sympy.Rational), got "
                     f"{type(x).__name__} {x!r}; enclose other numbers first with enclose(...)")


def float_down(x) -> float:
    """A float ≤ every point of ``x``, at any arb precision.

    Parameters
    ----------
    x : flint.arb or Fraction or int or float or sympy.Rational
        A ball (its lower end is rounded down) or an exact rational.

    Returns
    -------
    float
        ``-inf`` for a ball that is not finite.

    Examples
    --------
    >>> import flint
    >>> from fractions import Fraction
    >>> with flint.ctx.workprec(128):
    ...     third = flint.arb(1) / 3
    >>> Fraction(float_down(third)) <= lower_fraction(third)
    True
    >>> float_down(Fraction(1, 3)) == 1 / 3 < float_up(Fraction(1, 3))    # the float 1/3 is below 1/3
    True
    """
    if isinstance(x, arb):
        if not x.is_finite():
            return -math.inf
        return _round_point(x.lower(), up=False)
    return _round(_as_fraction(x), up=False)


def float_up(x) -> float:
    """A float ≥ every point of ``x``, at any arb precision (``inf`` for a ball that is not finite).

    See :func:`float_down`.

    Examples
    --------
    >>> import flint
    >>> with flint.ctx.workprec(300):
    ...     tenth = flint.arb(1) / 10
    >>> float_down(tenth) < 0.1 == float_up(tenth)     # the float 0.1 is above 1/10
    True
    """
    if isinstance(x, arb):
        if not x.is_finite():
            return math.inf
        return _round_point(x.upper(), up=True)
    return _round(_as_fraction(x), up=True)


def lower_fraction(x: arb) -> Fraction | None:
    """The exact rational lower end of the ball ``x`` (None if ``x`` is not finite).

    Examples
    --------
    >>> import flint
    >>> lower_fraction(flint.arb(3) / 4)
    Fraction(3, 4)
    >>> lower_fraction(flint.arb(1, 0.5)) <= 0.5
    True
    >>> lower_fraction(flint.arb("nan")) is None
    True
    """
    if not x.is_finite():
        return None
    return _point_fraction(x.mid()) - _point_fraction(x.rad())


def upper_fraction(x: arb) -> Fraction | None:
    """The exact rational upper end of the ball ``x`` (None if ``x`` is not finite).

    Examples
    --------
    >>> import flint
    >>> upper_fraction(flint.arb(1, 0.5)) >= 1.5
    True
    """
    if not x.is_finite():
        return None
    return _point_fraction(x.mid()) + _point_fraction(x.rad())
