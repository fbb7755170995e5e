"""Ball primitives: the enclosures the generated code calls (each returns a ball containing the image).

Names start with an underscore because generated source refers to them by name
(:data:`lkverify.certify.intervals.convert` keeps the table); :data:`SUPPORTED` lists the
whitelist in words.

Examples
--------
>>> from flint import arb
>>> _sq(arb(0, 1)).contains(-0.5)       # x**2 of [-1, 1] from the endpoints: [0, 1]
False
"""

from __future__ import annotations

import sympy
from flint import arb

__all__ = ["SUPPORTED"]

# ---------------------------------------------------------------------------
# ball primitives used by generated code (each returns an enclosure)
# ---------------------------------------------------------------------------

_NAN = arb("nan")
_ZERO = arb(0)
_ONE = arb(1)
_HALF_BALL = arb(0.5, 0.5)          # contains [0, 1]
_PI = arb.pi()
_TWO_PI = 2 * _PI
_HALF_PI = _PI / 2
_UNIT = arb(0, 1)                    # contains [-1, 1]
#: balls wider than this are enclosed from their endpoints (arb's own wide-ball bounds are loose)
_WIDE = 2.0 ** -24


def _hull(a: arb, b: arb) -> arb:
    """A ball containing the interval between the balls ``a`` and ``b``."""
    return a.union(b)


def _hull0(u: arb) -> arb:
    """A ball containing [0, u] for a ball ``u`` whose points are ≥ 0."""
    return _ZERO.union(u.upper())


def _interval(lo: float, hi: float) -> arb:
    """A ball containing the float interval [lo, hi] (a point ball if lo == hi)."""
    if lo == hi:
        return arb(lo)
    return arb(lo).union(arb(hi))


# ---------------------------------------------------------------------------
# arb primitives used by generated code (each returns an enclosure)
# ---------------------------------------------------------------------------

def _pw(p: arb, n: int) -> arb:
    """p**n for a (near-)point ball by repeated squaring."""
    result = _ONE
    base = p
    while n:
        if n & 1:
            result = result * base
        n >>= 1
        if n:
            base = base * base
    return result


def _ipow(x: arb, n: int) -> arb:
    """x**n for an integer n ≥ 2, from the endpoints (tight on wide balls)."""
    if not x.is_finite():
        return _NAN
    lo, hi = x.lower(), x.upper()
    if n % 2:
        return _hull(_pw(lo, n), _pw(hi, n))
    if lo >= 0:
        return _hull(_pw(lo, n), _pw(hi, n))
    if hi <= 0:
        return _hull(_pw(hi, n), _pw(lo, n))
    m = hi if hi > -lo else -lo
    return _hull0(_pw(m, n))


def _sq(x: arb) -> arb:
    """x**2 from the endpoints (a point ball: x*x)."""
    if not x.rad() > 0:
        return x * x
    if not x.is_finite():
        return _NAN
    lo, hi = x.lower(), x.upper()
    if lo >= 0:
        return (lo * lo).union(hi * hi)
    if hi <= 0:
        return (hi * hi).union(lo * lo)
    m = hi if hi > -lo else -lo
    return _ZERO.union((m * m).upper())


def _sqrt_nn(x: arb) -> arb:
    """sqrt(x) where x ≥ 0 is known (the ball may poke below 0 by rounding)."""
    if x > 0:
        if x.rad() > _WIDE:
            return x.lower().sqrt().union(x.upper().sqrt())
        return x.sqrt()
    if not x.is_finite():
        return _NAN
    u = x.upper()
    if u < 0:
        return _NAN
    return _hull0(u.sqrt())


def _sqrt(x: arb) -> arb:
    """sqrt(x); not finite unless the ball is certainly ≥ 0."""
    if x >= 0:
        return _sqrt_nn(x)
    return _NAN


def _rpow_pos(x: arb, p: arb, nonneg: bool) -> arb:
    """x**p for a constant p > 0 (x ≥ 0 required); [0, hi**p] if x touches 0."""
    if not x.is_finite():
        return _NAN
    if x > 0:
        lo, hi = x.lower(), x.upper()
        return _hull(lo ** p, hi ** p)
    if not (nonneg or x >= 0):
        return _NAN
    u = x.upper()
    if u < 0:
        return _NAN
    if u.is_zero():
        return _ZERO
    return _hull0(u ** p)


def _rpow_neg(x: arb, p: arb) -> arb:
    """x**p for a constant p < 0 (x > 0 required)."""
    if x > 0:
        lo, hi = x.lower(), x.upper()
        return _hull(hi ** p, lo ** p)
    return _NAN


def _powgen(x: arb, e: arb) -> arb:
    """x**e with a non-constant exponent: exp(e·log x), x > 0 required."""
    if x > 0:
        return (e * x.log()).exp()
    return _NAN


def _log(x: arb) -> arb:
    if x > 0:
        if x.rad() > _WIDE:
            return x.lower().log().union(x.upper().log())
        return x.log()
    return _NAN


def _abs(x: arb) -> arb:
    if x >= 0:
        return x
    if x <= 0:
        return -x
    if not x.is_finite():
        return _NAN
    return _hull0(x.abs_upper())


def _sgn(x: arb) -> arb:
    if x > 0:
        return _ONE
    if x < 0:
        return -_ONE
    if x.is_zero():
        return _ZERO
    if not x.is_finite() and x.is_nan():
        return _NAN
    return arb(0, 1)


def _heaviside(x: arb) -> arb:
    if x > 0:
        return _ONE
    if x < 0:
        return _ZERO
    if x.is_nan():
        return _NAN
    return _HALF_BALL


def _sin(x: arb) -> arb:
    """sin on a ball, tight for wide balls: the endpoint values, widened to ±1 at extrema inside."""
    if not x.rad() > _WIDE:
        return x.sin()
    if not x.is_finite():
        return _NAN
    lo, hi = x.lower(), x.upper()
    if hi - lo >= _TWO_PI:
        return _UNIT
    a, b = lo.sin(), hi.sin()
    top = _ONE if ((x - _HALF_PI) / _TWO_PI).contains_integer() else _maxpt([a.upper(), b.upper()])
    bot = -_ONE if ((x + _HALF_PI) / _TWO_PI).contains_integer() else -_maxpt([-a.lower(), -b.lower()])
    return bot.union(top)


def _cos(x: arb) -> arb:
    """cos on a ball, tight for wide balls (see :func:`_sin`)."""
    if not x.rad() > _WIDE:
        return x.cos()
    if not x.is_finite():
        return _NAN
    lo, hi = x.lower(), x.upper()
    if hi - lo >= _TWO_PI:
        return _UNIT
    a, b = lo.cos(), hi.cos()
    top = _ONE if (x / _TWO_PI).contains_integer() else _maxpt([a.upper(), b.upper()])
    bot = -_ONE if ((x - _PI) / _TWO_PI).contains_integer() else -_maxpt([-a.lower(), -b.lower()])
    return bot.union(top)


def _increasing(method: str):
    """A monotone increasing arb function, enclosed from the endpoints on wide balls."""
    def f(x: arb) -> arb:
        if not x.rad() > _WIDE:
            return getattr(x, method)()
        if not x.is_finite():
            return _NAN
        return getattr(x.lower(), method)().union(getattr(x.upper(), method)())
    f.__name__ = f"_{method}"
    return f


def _acos(x: arb) -> arb:
    if not x.rad() > _WIDE:
        return x.acos()
    if not x.is_finite():
        return _NAN
    return x.upper().acos().union(x.lower().acos())


def _cosh(x: arb) -> arb:
    if not x.rad() > _WIDE:
        return x.cosh()
    if not x.is_finite():
        return _NAN
    a, b = x.lower().cosh(), x.upper().cosh()
    top = _maxpt([a.upper(), b.upper()])
    if x > 0 or x < 0:
        return (-_maxpt([-a.lower(), -b.lower()])).union(top)   # [min of the end values, max]
    return _ONE.union(top)


def _max(*xs: arb) -> arb:
    if not all(x.is_finite() for x in xs):
        return _NAN
    lo = _maxpt([x.lower() for x in xs])
    hi = _maxpt([x.upper() for x in xs])
    return _hull(lo, hi)


def _min(*xs: arb) -> arb:
    if not all(x.is_finite() for x in xs):
        return _NAN
    lo = -_maxpt([-x.lower() for x in xs])
    hi = -_maxpt([-x.upper() for x in xs])
    return _hull(lo, hi)


def _maxpt(points: list) -> arb:
    """The largest of point balls (exact comparisons)."""
    best = points[0]
    for p in points[1:]:
        if p > best:
            best = p
    return best


_NATIVE = {  # SymPy function → helper (asin, acos: not finite on balls leaving [-1, 1])
    sympy.exp: "_exp", sympy.sin: "_sin", sympy.cos: "_cos", sympy.atan: "_atan",
    sympy.sinh: "_sinh", sympy.cosh: "_cosh", sympy.tanh: "_tanh", sympy.sinc: "_sinc",
    sympy.asin: "_asin", sympy.acos: "_acos",
}
_NONNEG_FUNCS = (sympy.exp, sympy.cosh, sympy.Abs, sympy.Heaviside, sympy.acos)
_JUMPS = (sympy.sign, sympy.Heaviside)
_HELPERS = {
    "_ipow": _ipow, "_sq": _sq, "_sqrt_nn": _sqrt_nn, "_sqrt": _sqrt, "_rpow_pos": _rpow_pos,
    "_rpow_neg": _rpow_neg, "_powgen": _powgen, "_log": _log, "_abs": _abs, "_sgn": _sgn,
    "_heaviside": _heaviside, "_max": _max, "_min": _min, "_tan": lambda x: x.tan(),
    "_sinc": lambda x: x.sinc(), "_sin": _sin, "_cos": _cos, "_exp": _increasing("exp"),
    "_atan": _increasing("atan"), "_sinh": _increasing("sinh"), "_tanh": _increasing("tanh"),
    "_asin": _increasing("asin"), "_acos": _acos, "_cosh": _cosh, "_NAN": _NAN,
}
SUPPORTED = ("+", "-", "*", "/", "integer and real powers", "sqrt", "exp", "log", "sin", "cos",
             "tan", "atan", "asin", "acos", "sinh", "cosh", "tanh", "sinc", "Abs", "sign", "Heaviside", "Min",
             "Max", "pi", "E", "rational and float constants")
