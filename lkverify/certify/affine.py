"""Affine arithmetic: first-order models that keep the linear dependence on a box.

A quantity is carried as ``c + Σ gᵢ εᵢ ± e`` over εᵢ ∈ [-1, 1] with arb
coefficients (:class:`AffineForm`); :data:`AFFINE_HELPERS` replaces the ball
primitives of :mod:`lkverify.certify.intervals.balls` in generated code, so
one compiled program evaluates either on balls or on affine forms.

Examples
--------
>>> from flint import arb
>>> x = AffineForm(arb(0), (arb(1),), arb(0))          # x ∈ [-1, 1]
>>> (x - x).ball().contains(0), (x - x).radius() == 0   # x − x is exactly 0
(True, True)
"""

from __future__ import annotations

import operator

from flint import arb

from .intervals.balls import (_NAN, _ONE, _UNIT, _ZERO, _abs, _acos, _cos, _cosh, _heaviside, _increasing, _ipow,
                              _log, _max, _min, _powgen, _rpow_neg, _rpow_pos, _sgn, _sin, _sq, _sqrt, _sqrt_nn)

__all__ = ["AFFINE_HELPERS", "AffineForm"]

_add, _sub, _neg = operator.add, operator.sub, operator.neg


class AffineForm:
    """The set ``c + Σ gᵢ εᵢ + [-e, e]`` over εᵢ ∈ [-1, 1]; ``c``, ``gᵢ``, ``e`` are arb balls.

    On a box with centre m and half-widths r, the variable xᵢ is ``mᵢ + rᵢ εᵢ``.
    Every operation returns a form containing the exact result for every ε (the
    balls absorb rounding); nonlinear functions are linearised at the centre
    with the remainder bounded by the derivative's enclosure on the range
    (mean value theorem), or fall back to an interval (``g = 0``).  Unlike the
    natural ball extension, ``x − x`` is 0 and ``sin x · cos x`` keeps its
    linear part, so the enclosure's excess is second order in the box width.
    """

    __slots__ = ("c", "g", "e", "_r")

    def __init__(self, c: arb, g: tuple, e: arb):
        self.c = c
        self.g = g
        self.e = e
        self._r = None

    def radius(self) -> arb:
        """An upper bound of Σ|gᵢ| + e (a point ball)."""
        r = self._r
        if r is None:
            r = self.e.abs_upper()
            for gi in self.g:
                r = r + gi.abs_upper()
            r = self._r = r.abs_upper()
        return r

    def ball(self) -> arb:
        """A ball containing the form's range."""
        return self.c + _UNIT * self.radius()

    # arithmetic ---------------------------------------------------------
    def __add__(self, o):
        if o.__class__ is AffineForm:
            return AffineForm(self.c + o.c, tuple(map(_add, self.g, o.g)), self.e + o.e)
        if o.__class__ is not arb:
            o = arb(o)
        return AffineForm(self.c + o, self.g, self.e)

    __radd__ = __add__

    def __neg__(self):
        return AffineForm(-self.c, tuple(map(_neg, self.g)), self.e)

    def __sub__(self, o):
        if o.__class__ is AffineForm:
            return AffineForm(self.c - o.c, tuple(map(_sub, self.g, o.g)), self.e + o.e)
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if o.__class__ is not AffineForm:
            if o.__class__ is not arb:
                o = arb(o)
            return AffineForm(self.c * o, tuple([a * o for a in self.g]), self.e * o.abs_upper())
        c1, c2 = self.c, o.c
        e = c1.abs_upper() * o.e + c2.abs_upper() * self.e + self.radius() * o.radius()
        return AffineForm(c1 * c2, tuple([c1 * b + c2 * a for a, b in zip(self.g, o.g)]), e.abs_upper())

    __rmul__ = __mul__

    def __truediv__(self, o):
        if o.__class__ is not AffineForm:
            return self * (_ONE / o)
        return self * _aff_recip(o)

    def __rtruediv__(self, o):
        return _aff_recip(self) * o


def _aff_of(x, n: int) -> AffineForm:
    if x.__class__ is AffineForm:
        return x
    return AffineForm(x, (_ZERO,) * n, _ZERO)


def _aff_ball(b: arb, n: int) -> AffineForm:
    """An interval as an affine form without linear part."""
    return AffineForm(b, (_ZERO,) * n, _ZERO)


def _aff_linearise(a: AffineForm, f, df, fallback) -> AffineForm:
    """f(a) by the mean value theorem at the centre; ``fallback(ball)`` where f' is unbounded."""
    U = a.ball()
    m = a.c.mid()
    dU = df(U)
    fm = f(m)
    if not (dU.is_finite() and fm.is_finite()):
        return _aff_ball(fallback(U), len(a.g))
    dm = df(m)
    err = (dU - dm).abs_upper() * (U - m).abs_upper()
    return AffineForm(fm + dm * (a.c - m), tuple(dm * gi for gi in a.g),
                (dm.abs_upper() * a.e + err).abs_upper())


def _aff_recip(a: AffineForm) -> AffineForm:
    return _aff_linearise(a, lambda u: _ONE / u, lambda u: -_ONE / _sq(u), lambda u: _ONE / u)


def _aff_sq(a: AffineForm) -> AffineForm:
    """a² = c² + 2c·G + (2cE + (G + E)²) with (G + E)² ∈ [0, R²]."""
    if a.__class__ is not AffineForm:
        return _sq(a)
    R = a.radius()
    half = R * R / 2
    c = a.c
    return AffineForm(c * c + half, tuple(2 * c * gi for gi in a.g),
                (2 * c.abs_upper() * a.e + half).abs_upper())


def _aff_ipow(a, n: int):
    if a.__class__ is not AffineForm:
        return _ipow(a, n)
    if n % 2 == 0:
        return _aff_ipow(_aff_sq(a), n // 2) if n > 2 else _aff_sq(a)
    return _aff_linearise(a, lambda u: _ipow(u, n), lambda u: n * _ipow(u, n - 1),
                          lambda u: _ipow(u, n))


def _aff_unary(ball_f, ball_df):
    def f(a, *rest):
        if a.__class__ is not AffineForm:
            return ball_f(a, *rest)
        return _aff_linearise(a, lambda u: ball_f(u, *rest), lambda u: ball_df(u, *rest),
                              lambda u: ball_f(u, *rest))
    return f


def _aff_interval(ball_f):
    """Functions without a useful linearisation (kinks, jumps): evaluate on the range."""
    def f(*args):
        n = next((len(a.g) for a in args if a.__class__ is AffineForm), None)
        if n is None:
            return ball_f(*args)
        return _aff_ball(ball_f(*[a.ball() if a.__class__ is AffineForm else a for a in args]), n)
    return f


def _aff_abs(a):
    if a.__class__ is not AffineForm:
        return _abs(a)
    U = a.ball()
    if U > 0:
        return a
    if U < 0:
        return -a
    return _aff_ball(_abs(U), len(a.g))


def _d_sqrt(u):
    return _ONE / (2 * _sqrt_nn(u)) if u > 0 else _NAN


def _d_rpow(u, p, nonneg=True):
    return p * _rpow_pos(u, p - 1, nonneg) if p > 1 else (p * _rpow_neg(u, p - 1) if u > 0 else _NAN)


def _d_log(u):
    return _ONE / u if u > 0 else _NAN


def _d_asin(u):
    return _ONE / _sqrt(1 - _sq(u))


def _d_pow_neg(u, p):
    return p * _rpow_neg(u, p - 1)


def _aff_powgen(a, e):
    if a.__class__ is not AffineForm and e.__class__ is not AffineForm:
        return _powgen(a, e)
    n = len(a.g) if a.__class__ is AffineForm else len(e.g)
    la = _aff_unary(_log, _d_log)(_aff_of(a, n))
    return _aff_unary(_increasing("exp"), _increasing("exp"))(la * e)


AFFINE_HELPERS = {
    "_sq": _aff_sq, "_ipow": _aff_ipow,
    "_sqrt_nn": _aff_unary(_sqrt_nn, _d_sqrt), "_sqrt": _aff_unary(_sqrt, _d_sqrt),
    "_rpow_pos": _aff_unary(_rpow_pos, _d_rpow), "_rpow_neg": _aff_unary(_rpow_neg, _d_pow_neg),
    "_powgen": _aff_powgen, "_log": _aff_unary(_log, _d_log), "_abs": _aff_abs,
    "_sgn": _aff_interval(_sgn), "_heaviside": _aff_interval(_heaviside),
    "_max": _aff_interval(_max), "_min": _aff_interval(_min),
    "_tan": _aff_unary(lambda x: x.tan(), lambda x: 1 + _sq(x.tan())),
    "_sinc": _aff_interval(lambda x: x.sinc()),
    "_sin": _aff_unary(_sin, _cos), "_cos": _aff_unary(_cos, lambda x: -_sin(x)),
    "_exp": _aff_unary(_increasing("exp"), _increasing("exp")),
    "_atan": _aff_unary(_increasing("atan"), lambda x: _ONE / (1 + _sq(x))),
    "_sinh": _aff_unary(_increasing("sinh"), _cosh),
    "_tanh": _aff_unary(_increasing("tanh"), lambda x: 1 - _sq(_increasing("tanh")(x))),
    "_asin": _aff_unary(_increasing("asin"), _d_asin), "_acos": _aff_unary(_acos, lambda x: -_d_asin(x)),
    "_cosh": _aff_unary(_cosh, _increasing("sinh")),
}
