"""Certified constants: suprema, best constants and sign proofs on boxes.

Papers say "there exist positive constants c_k"; this module computes them and
proves them.  Every job has two halves:

* an **estimate** -- multistart local maximisation in floating point
  (SciPy); for a supremum it is a *lower* bound, status ``estimated``;
* a **certificate** -- branch and bound with outward-rounded ball arithmetic
  (python-flint's ``arb``); it is a *proved upper* bound, status
  ``certified``.

The building blocks:

:func:`compile_arb`
    a SymPy expression in named real variables → a function on ``arb`` balls
    returning a ball that contains every value the expression takes on the
    argument balls (an *enclosure*), optionally with the enclosure of the
    gradient; :func:`compile_numpy` is the float twin (``sympy.lambdify``).
:func:`sup_bound`
    the supremum of an expression over a box.
:func:`best_constant` / :func:`check_constant`
    the best ``c`` in "lhs ≤ c·template on the region", and a claimed ``c``
    proved or refuted.
:func:`certify_nonpositive` / :func:`certify_positive`
    prove ``expr ≤ 0`` (``expr > 0``) on a box, or find a proved
    counterexample.
:func:`unit_vector_angles`, :func:`unit_vector_near`,
:func:`rotation_axis_angle`, :func:`rotation_vector`,
:func:`rotation_quaternion`, :func:`rotation_euler`, :func:`ball_point`
    charts that turn the papers' manifold regions (a unit sphere, a cap
    ‖s − r‖ ≤ d, rotations near a reference frame, a ball in R³) into boxes.

What "certified" means here
---------------------------
A ``certified`` upper bound ``U`` of ``sup f`` over a box is proved like
this.  The box is covered by finitely many sub-boxes (the leaves of the
branch and bound).  On every leaf the compiled function returns a ball that
contains ``f`` of every point of the leaf, computed by arb with outward
rounding; ``U`` is the largest upper end of these balls (converted to a float
rounded *up*).  Up to three enclosures are intersected on each leaf: the
natural one (the expression evaluated on the leaf's balls), the mean-value
form ``f(c) + Σ ∂ᵢf(leaf)·(xᵢ − cᵢ)`` with the arb-enclosed gradient, and an
affine form (each quantity carried as ``c + Σ gᵢεᵢ ± e`` with arb
coefficients, nonlinear functions linearised at the centre with a
mean-value remainder; see ``enclosure=``).  When an enclosed partial
derivative has a constant sign on a leaf, the leaf is replaced by the face
where ``f`` is largest (monotonicity).  Derivatives of
``Abs``/``Min``/``Max`` enclose Clarke's generalised gradient (``sign`` and
``Heaviside`` of a ball that contains 0 are ``[-1, 1]`` and ``[0, 1]``), so
the mean-value and monotonicity arguments hold for these Lipschitz kinks too.
Expressions with jumps (``sign``, ``Heaviside``) get no gradient.

Lower bounds of a supremum, and counterexamples, are point values evaluated in
arb at exact binary (dyadic rational) points inside the region; a point value
whose ball lies above a threshold proves that the threshold is exceeded.

Nothing is certified with floats: floats only store ball endpoints that arb
produced, rounded outward (an upper end up, a lower end down).

Domains.  A function is *undefined* where SymPy's real function is
(``log`` of a nonpositive number, a non-integer power or ``sqrt`` of a
negative number, division by zero).  A ball on which the expression may be
undefined gets the enclosure "not finite" and can never be certified, so a
problem that is not defined on its whole region ends ``undecided``.  A
nonnegative base that touches 0 (``‖s − r‖**(2ν + 2)`` at ``s = r``) is
recognised structurally (sums of squares, ``Abs``, ``sqrt``, even powers,
``exp``, products of those) or by SymPy's assumptions (declare
``Symbol("x", nonnegative=True)`` or give a box with ``lo ≥ 0``).

Examples
--------
>>> import sympy
>>> x = sympy.Symbol("x")
>>> res = sup_bound(x * sympy.exp(-x), {x: (0, 5)})
>>> res.status
<Status.CERTIFIED: 'certified'>
>>> res.lower <= float(sympy.exp(-1)) <= res.certified <= 1.01 * res.lower
True
"""

from __future__ import annotations

import dataclasses
import fractions
import heapq
import math
import operator
import time
import warnings
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from .intervals import (  # the one SymPy → arb converter, its ball primitives and outward rounding
    _JUMPS, _NAN, _ONE, _UNIT, _ZERO, _abs, _acos, _cos, _cosh, _heaviside, _increasing, _ipow, _log, _max,
    _min, _powgen, _real_dummies, _rpow_neg, _rpow_pos, _sgn, _sin, _sq, _sqrt, _sqrt_nn, _sympy_number_ball,
    compile_program, float_down, float_up, to_ball)
from ..status import Status

__all__ = [
    "ArbFunction", "BranchProgress", "Chart", "CheckResult", "ConstantResult", "SupResult",
    "ball_point", "best_constant", "certify_nonpositive", "certify_positive", "check_constant",
    "compile_arb", "compile_numpy", "rotation_axis_angle", "rotation_euler", "rotation_quaternion",
    "rotation_vector", "sup_bound", "unit_vector_angles", "unit_vector_near",
]

_INF = math.inf
_add, _sub, _neg = operator.add, operator.sub, operator.neg
#: default budgets: a constant should certify in seconds; these are the ceilings
DEFAULT_BUDGET_BOXES = 200_000
DEFAULT_BUDGET_SECONDS = 30.0


# ---------------------------------------------------------------------------
# affine forms: first-order models that keep the linear dependence on the box
# ---------------------------------------------------------------------------

class _Aff:
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
        return self.c + _UNIT * self.radius()

    # arithmetic ---------------------------------------------------------
    def __add__(self, o):
        if o.__class__ is _Aff:
            return _Aff(self.c + o.c, tuple(map(_add, self.g, o.g)), self.e + o.e)
        if o.__class__ is not arb:
            o = arb(o)
        return _Aff(self.c + o, self.g, self.e)

    __radd__ = __add__

    def __neg__(self):
        return _Aff(-self.c, tuple(map(_neg, self.g)), self.e)

    def __sub__(self, o):
        if o.__class__ is _Aff:
            return _Aff(self.c - o.c, tuple(map(_sub, self.g, o.g)), self.e + o.e)
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if o.__class__ is not _Aff:
            if o.__class__ is not arb:
                o = arb(o)
            return _Aff(self.c * o, tuple([a * o for a in self.g]), self.e * o.abs_upper())
        c1, c2 = self.c, o.c
        e = c1.abs_upper() * o.e + c2.abs_upper() * self.e + self.radius() * o.radius()
        return _Aff(c1 * c2, tuple([c1 * b + c2 * a for a, b in zip(self.g, o.g)]), e.abs_upper())

    __rmul__ = __mul__

    def __truediv__(self, o):
        if o.__class__ is not _Aff:
            return self * (_ONE / o)
        return self * _aff_recip(o)

    def __rtruediv__(self, o):
        return _aff_recip(self) * o


def _aff_of(x, n: int) -> _Aff:
    if x.__class__ is _Aff:
        return x
    return _Aff(x, (_ZERO,) * n, _ZERO)


def _aff_ball(b: arb, n: int) -> _Aff:
    """An interval as an affine form without linear part."""
    return _Aff(b, (_ZERO,) * n, _ZERO)


def _aff_linearise(a: _Aff, f, df, fallback) -> _Aff:
    """f(a) by the mean value theorem at the centre; ``fallback(ball)`` where f' is unbounded."""
    U = a.ball()
    m = a.c.mid()
    dU = df(U)
    fm = f(m)
    if not (dU.is_finite() and fm.is_finite()):
        return _aff_ball(fallback(U), len(a.g))
    dm = df(m)
    err = (dU - dm).abs_upper() * (U - m).abs_upper()
    return _Aff(fm + dm * (a.c - m), tuple(dm * gi for gi in a.g),
                (dm.abs_upper() * a.e + err).abs_upper())


def _aff_recip(a: _Aff) -> _Aff:
    return _aff_linearise(a, lambda u: _ONE / u, lambda u: -_ONE / _sq(u), lambda u: _ONE / u)


def _aff_sq(a: _Aff) -> _Aff:
    """a² = c² + 2c·G + (2cE + (G + E)²) with (G + E)² ∈ [0, R²]."""
    if a.__class__ is not _Aff:
        return _sq(a)
    R = a.radius()
    half = R * R / 2
    c = a.c
    return _Aff(c * c + half, tuple(2 * c * gi for gi in a.g),
                (2 * c.abs_upper() * a.e + half).abs_upper())


def _aff_ipow(a, n: int):
    if a.__class__ is not _Aff:
        return _ipow(a, n)
    if n % 2 == 0:
        return _aff_ipow(_aff_sq(a), n // 2) if n > 2 else _aff_sq(a)
    return _aff_linearise(a, lambda u: _ipow(u, n), lambda u: n * _ipow(u, n - 1),
                          lambda u: _ipow(u, n))


def _aff_unary(ball_f, ball_df):
    def f(a, *rest):
        if a.__class__ is not _Aff:
            return ball_f(a, *rest)
        return _aff_linearise(a, lambda u: ball_f(u, *rest), lambda u: ball_df(u, *rest),
                              lambda u: ball_f(u, *rest))
    return f


def _aff_interval(ball_f):
    """Functions without a useful linearisation (kinks, jumps): evaluate on the range."""
    def f(*args):
        n = next((len(a.g) for a in args if a.__class__ is _Aff), None)
        if n is None:
            return ball_f(*args)
        return _aff_ball(ball_f(*[a.ball() if a.__class__ is _Aff else a for a in args]), n)
    return f


def _aff_abs(a):
    if a.__class__ is not _Aff:
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
    if a.__class__ is not _Aff and e.__class__ is not _Aff:
        return _powgen(a, e)
    n = len(a.g) if a.__class__ is _Aff else len(e.g)
    la = _aff_unary(_log, _d_log)(_aff_of(a, n))
    return _aff_unary(_increasing("exp"), _increasing("exp"))(la * e)


_AFF_OVERRIDES = {
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


@dataclasses.dataclass(frozen=True)
class ArbFunction:
    """A SymPy expression compiled to ball arithmetic.

    Calling it with one ball per variable returns a ball that contains the
    expression's value at every point of the product of the balls (a
    non-finite ball where the expression may be undefined).

    Attributes
    ----------
    expr : sympy.Expr
        The expression, in the caller's symbols.
    variables : tuple of sympy.Symbol
        The argument order.
    nonnegative : bool
        True if the compiler proved structurally that the value is ≥ 0
        wherever it is defined (sums of squares, ``Abs``, ``sqrt``, ...).
    has_gradient : bool
        True if :meth:`value_and_gradient` is available.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> f = compile_arb(x**2 - 2*x*y, [x, y])
    >>> f(1, 3)
    -5.00000000000000
    >>> box = f((0, 1), (0, 1))          # intervals as (lo, hi) pairs
    >>> box.contains(-2) and box.contains(1)
    True
    >>> v, g = f.value_and_gradient(1, 3)
    >>> g
    (-4.00000000000000, -2.00000000000000)
    """

    expr: sympy.Expr
    variables: tuple
    nonnegative: bool
    has_gradient: bool
    _value: Callable = dataclasses.field(repr=False, compare=False)
    _value_grad: Callable | None = dataclasses.field(repr=False, compare=False)
    _value_affine: Callable | None = dataclasses.field(repr=False, compare=False, default=None)
    _source_lines: int = dataclasses.field(repr=False, compare=False, default=0)

    def __call__(self, *args) -> arb:
        return self._value(*self._balls(args))[0]

    def value_and_gradient(self, *args) -> tuple:
        """The value's enclosure and the tuple of the partial derivatives' enclosures.

        On a ball where the expression has a kink (``Abs``, ``Min``, ``Max``) the
        partial derivatives enclose Clarke's generalised gradient.
        """
        if self._value_grad is None:
            raise InputError(f"no gradient for {self.expr}: it has jumps (sign, Heaviside) or "
                             f"a part whose derivative cannot be enclosed")
        out = self._value_grad(*self._balls(args))
        return out[0], tuple(out[1:])

    def _balls(self, args) -> list:
        if len(args) != len(self.variables):
            raise InputError(f"expected {len(self.variables)} arguments "
                             f"({', '.join(map(str, self.variables))}), got {len(args)}")
        return [to_ball(a) for a in args]


def _check_symbols(variables) -> tuple:
    variables = tuple(variables)
    problems = [f"{v!r} is not a SymPy Symbol" for v in variables if not isinstance(v, sympy.Symbol)]
    if len(set(variables)) != len(variables):
        problems.append("a variable is listed twice")
    if problems:
        raise InputError("variables: " + "; ".join(problems) + "; pass distinct sympy.Symbol objects")
    return variables


def _sympify_expr(expr, what: str = "expression") -> sympy.Expr:
    if isinstance(expr, str):
        raise InputError(f"{what}: expected a SymPy expression, got the string {expr!r}; "
                         f"build it with sympy (strings are never evaluated)")
    if isinstance(expr, sympy.MatrixBase):
        raise InputError(f"{what}: expected a scalar expression, got a {expr.shape} matrix")
    try:
        out = sympy.sympify(expr, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{what}: expected a SymPy expression, got {expr!r}") from exc
    if not isinstance(out, sympy.Expr):
        raise InputError(f"{what}: expected a SymPy expression, got {type(out).__name__} {out}")
    return out


def compile_arb(expr, variables: Sequence, *, gradient: bool = True,
                _signs: Sequence[tuple[bool, bool]] | None = None) -> ArbFunction:
    """Compile a SymPy expression in real variables to a function on arb balls.

    Parameters
    ----------
    expr : sympy.Expr
        Built from ``+ − × ÷``, integer and real powers, ``sqrt``, ``exp``,
        ``log``, ``sin``, ``cos``, ``tan``, ``atan``, ``asin``, ``acos``, ``sinh``, ``cosh``,
        ``tanh``, ``sinc``, ``Abs``, ``sign``, ``Heaviside``, ``Min``, ``Max``
        and the constants ``pi``, ``E``, integers, rationals and floats.
        Rationals are enclosed exactly (arb of an ``fmpq``); a SymPy ``Float``
        stands for its exact binary value, so write ``Rational(3, 10)`` for
        the decimal 0.3.
    variables : sequence of sympy.Symbol
        The argument order; every free symbol of ``expr`` must be listed.
        The variables are real; a symbol declared ``nonnegative=True`` or
        ``positive=True`` tells the compiler the sign (and is then only
        valid for arguments of that sign).
    gradient : bool, default True
        Also compile the partial derivatives (SymPy ``diff``) for
        :meth:`ArbFunction.value_and_gradient`.

    Returns
    -------
    ArbFunction

    Notes
    -----
    ``x**p`` for a non-integer constant ``p`` needs ``x ≥ 0``: a ball that
    touches 0 gives ``[0, hi**p]`` (``p > 0``) when the base is known to be
    nonnegative (structurally, by SymPy's assumptions, or because the ball
    itself is certainly ≥ 0), and a non-finite ball otherwise.  Integer
    powers use the interval endpoints, so ``x**2`` of ``[-1, 2]`` is
    ``[0, 4]``, not ``[-2, 4]``.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x", nonnegative=True)
    >>> f = compile_arb(x ** sympy.Rational(13, 10), [x], gradient=False)
    >>> y = f((0, 1))                    # contains [0, 1], and not much more
    >>> y.contains(0) and y.contains(1) and y.upper() < 1.000001 and y.lower() > -1e-6
    True
    >>> compile_arb(sympy.log(x), [x])(0).is_finite()   # undefined: not finite
    False
    """
    variables = _check_symbols(variables)
    expr = _sympify_expr(expr)
    missing = expr.free_symbols - set(variables)
    if missing:
        raise InputError(f"free symbols {sorted(map(str, missing))} of {expr} have no interval; "
                         f"list them as variables or substitute their values")
    dummies = _real_dummies(variables, _signs)
    dexpr = expr.xreplace(dummies)
    dvars = [dummies[v] for v in variables]
    flags = [bool(d.is_nonnegative) for d in dvars]
    back = {d: v for v, d in dummies.items()}
    prog = compile_program([dexpr], dvars, nonnegative=flags, originals=back)
    value_fn = prog.function()
    affine_fn = prog.function(_AFF_OVERRIDES)

    grad_fn = None
    if gradient and not dexpr.has(*_JUMPS):
        try:
            grads = [sympy.diff(dexpr, d) for d in dvars]
            bad = [g for g in grads if g.has(sympy.Derivative, sympy.Subs, sympy.DiracDelta)]
            if not bad:
                grad_fn = compile_program([dexpr, *grads], dvars, nonnegative=flags, originals=back).function()
        except InputError:
            grad_fn = None
    return ArbFunction(expr=expr, variables=variables, nonnegative=prog.nonnegative[0],
                       has_gradient=grad_fn is not None, _value=value_fn, _value_grad=grad_fn,
                       _value_affine=affine_fn, _source_lines=prog.lines)


def compile_numpy(expr, variables: Sequence) -> Callable:
    """The float twin of :func:`compile_arb`: ``sympy.lambdify`` on NumPy arrays.

    The returned function broadcasts: given arrays it returns an array of the
    broadcast shape, even for an expression that does not depend on every
    variable.  Values are *not* enclosures; use them only for estimates.

    Examples
    --------
    >>> import numpy as np, sympy
    >>> x, y = sympy.symbols("x y")
    >>> f = compile_numpy(x * sympy.exp(-x) + 0 * y, [x, y])
    >>> np.round(f(np.array([1.0, 2.0]), np.array([0.0, 0.0])), 4)
    array([0.3679, 0.2707])
    """
    variables = _check_symbols(variables)
    expr = _sympify_expr(expr)
    missing = expr.free_symbols - set(variables)
    if missing:
        raise InputError(f"free symbols {sorted(map(str, missing))} of {expr} have no value; "
                         f"list them as variables or substitute their values")
    dummies = _real_dummies(variables)
    return _lambdify([dummies[v] for v in variables], expr.xreplace(dummies))


def _lambdify(dvars, dexpr):
    fn = sympy.lambdify(dvars, dexpr, modules="numpy")

    def f(*xs):
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = fn(*xs)
        shape = np.broadcast_shapes(*(np.shape(x) for x in xs)) if xs else ()
        return np.broadcast_to(np.asarray(out, dtype=float), shape)

    return f


# ---------------------------------------------------------------------------
# regions (boxes)
# ---------------------------------------------------------------------------

def _exact_number(value, what: str):
    """A user number as a SymPy number; a float is taken at its exact binary value (see :mod:`lkverify.status`)."""
    if isinstance(value, bool):
        raise InputError(f"{what}: expected a number, got {value!r}")
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InputError(f"{what}: expected a finite number, got {value!r}")
        return sympy.Rational(value)
    if isinstance(value, (int, fractions.Fraction)):
        return sympy.Rational(value)
    if isinstance(value, sympy.Float):
        return sympy.Rational(value)
    if isinstance(value, str):
        raise InputError(f"{what}: expected a number, got the string {value!r}; "
                         f"pass a number or a SymPy expression such as sympy.pi")
    try:
        out = sympy.sympify(value, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{what}: expected a number, got {value!r}") from exc
    if not (isinstance(out, sympy.Expr) and out.is_number) or out.free_symbols:
        raise InputError(f"{what}: expected a number, got {out}")
    if out.is_real is False or not out.is_finite:
        raise InputError(f"{what}: expected a finite real number, got {out}")
    return out


@dataclasses.dataclass(frozen=True)
class _Region:
    variables: tuple
    bounds: tuple            # SymPy numbers (lo, hi) per variable
    lo_out: tuple            # floats ≤ lo  (the boxes of the branch and bound cover the region)
    hi_out: tuple            # floats ≥ hi
    lo_in: tuple             # floats ≥ lo  (sample and test points stay inside the region)
    hi_in: tuple             # floats ≤ hi

    @property
    def names(self) -> tuple:
        return tuple(str(v) for v in self.variables)

    @property
    def signs(self) -> list:
        return [(lo >= 0, lo > 0) for lo in self.lo_out]

    def text(self) -> str:
        return "{" + ", ".join(f"{v} ∈ [{lo}, {hi}]" for v, (lo, hi) in zip(self.variables, self.bounds)) + "}"

    def contains(self, point: Sequence[float]) -> bool:
        return all(lo <= x <= hi for x, lo, hi in zip(point, self.lo_in, self.hi_in))

    def point_dict(self, point) -> dict:
        return {name: float(x) for name, x in zip(self.names, point)}


def _parse_region(box, exprs: Sequence[sympy.Expr], what: str = "box") -> _Region:
    if not isinstance(box, Mapping):
        raise InputError(f"{what}: expected a mapping {{symbol: (lo, hi)}}, got {type(box).__name__}")
    problems = []
    variables, bounds, lo_out, hi_out, lo_in, hi_in = [], [], [], [], [], []
    for var, pair in box.items():
        if not isinstance(var, sympy.Symbol):
            problems.append(f"key {var!r} is not a sympy.Symbol")
            continue
        if not (isinstance(pair, Sequence) and not isinstance(pair, str) and len(pair) == 2):
            problems.append(f"{var}: expected a pair (lo, hi), got {pair!r}")
            continue
        try:
            lo, hi = (_exact_number(v, f"{what} bound of {var}") for v in pair)
        except InputError as exc:
            problems.append(str(exc))
            continue
        lo_b, hi_b = _sympy_number_ball(lo), _sympy_number_ball(hi)
        if not (lo_b.is_finite() and hi_b.is_finite()):
            problems.append(f"{var}: bounds {lo}, {hi} are not finite")
            continue
        if lo_b > hi_b:
            problems.append(f"{var}: lower bound {lo} exceeds upper bound {hi}")
            continue
        lo_o, hi_o, lo_i, hi_i = float_down(lo_b), float_up(hi_b), float_up(lo_b), float_down(hi_b)
        if lo_i > hi_i:
            if lo == hi:
                problems.append(f"{var}: the zero-width range [{lo}, {hi}] has no float inside; "
                                f"substitute {var} = {lo} into the expression instead")
            else:
                problems.append(f"{var}: the range [{lo}, {hi}] is too narrow for float points")
            continue
        if var.is_nonnegative and lo_o < 0:
            problems.append(f"{var} is declared nonnegative but its range starts at {lo}")
        if var.is_positive and lo_o <= 0:
            problems.append(f"{var} is declared positive but its range starts at {lo}")
        variables.append(var)
        bounds.append((lo, hi))
        lo_out.append(lo_o), hi_out.append(hi_o), lo_in.append(lo_i), hi_in.append(hi_i)
    free = set().union(*(e.free_symbols for e in exprs)) if exprs else set()
    missing = free - set(variables)
    if missing:
        problems.append(f"symbols {sorted(map(str, missing))} have no range; add them to the {what} "
                        f"or substitute their values")
    if problems:
        raise InputError(f"{what}: " + "; ".join(problems))
    return _Region(tuple(variables), tuple(bounds), tuple(lo_out), tuple(hi_out), tuple(lo_in),
                   tuple(hi_in))


# ---------------------------------------------------------------------------
# the objective: one expression compiled three ways
# ---------------------------------------------------------------------------

class _Objective:
    """f compiled to arb (value; value+gradient) and to NumPy (value; gradient)."""

    def __init__(self, expr: sympy.Expr, region: _Region, *, gradient: bool = True):
        # the float twin takes the caller's symbols (lambdify renames invalid identifiers)
        self.expr = expr
        self.region = region
        self.n = len(region.variables)
        self.arb = compile_arb(expr, region.variables, gradient=gradient, _signs=region.signs)
        self.fv = self.arb._value
        self.fvg = self.arb._value_grad
        self.np_f = _lambdify(list(region.variables), expr)

    def point_ball(self, point: Sequence[float]) -> arb:
        """The enclosure of f at an exact binary point."""
        return self.fv(*[arb(float(x)) for x in point])[0]

    def f_float(self, x: np.ndarray) -> float:
        v = float(self.np_f(*x))
        return v if math.isfinite(v) else -_INF


# ---------------------------------------------------------------------------
# the estimate: multistart local maximisation
# ---------------------------------------------------------------------------

def _estimate(obj: _Objective, *, starts: int, seed: int, deadline: float) -> list:
    """Candidate maximisers, best first: list of (value, point) with finite values."""
    from scipy.optimize import minimize
    from scipy.stats import qmc

    reg = obj.region
    n = obj.n
    if n == 0:
        v = obj.f_float(np.zeros(0))
        return [(v, ())] if math.isfinite(v) else []
    lo, hi = np.array(reg.lo_in), np.array(reg.hi_in)
    m = 1 << max(7, int(math.ceil(math.log2(128 * n))))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        u = qmc.Sobol(d=n, scramble=True, seed=seed).random(m)
    pts = [lo + u * (hi - lo), ((lo + hi) / 2)[None, :]]
    if n <= 8:
        corners = np.array(np.meshgrid(*[[a, b] for a, b in zip(lo, hi)], indexing="ij")).reshape(n, -1).T
        pts.append(corners)
    pts = np.vstack(pts)
    vals = np.asarray(obj.np_f(*pts.T), dtype=float)
    vals = np.where(np.isfinite(vals), vals, -np.inf)
    order = np.argsort(-vals, kind="stable")
    cands = [(float(vals[i]), tuple(pts[i])) for i in order[: max(1, starts)] if np.isfinite(vals[i])]

    bounds = list(zip(lo, hi))

    def negf(x):
        v = obj.f_float(x)
        return -v if math.isfinite(v) else 1e300

    def negf_grad(x):
        v = obj.f_float(x)
        if not math.isfinite(v):
            return 1e300, np.zeros(n)
        g = np.zeros(n)   # central differences, one-sided at the box's faces
        for i in range(n):
            h = 1e-6 * max(1.0, abs(x[i]))
            a, b = max(x[i] - h, lo[i]), min(x[i] + h, hi[i])
            if b <= a:
                continue
            xa, xb = x.copy(), x.copy()
            xa[i], xb[i] = a, b
            va, vb = obj.f_float(xa), obj.f_float(xb)
            if math.isfinite(va) and math.isfinite(vb):
                g[i] = (vb - va) / (b - a)
        return -v, -g

    found = list(cands)
    for _, x0 in cands:
        if time.monotonic() > deadline:
            break
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            # SLSQP, not L-BFGS-B: the latter spends milliseconds per iteration in threaded
            # OpenBLAS calls on tiny problems
            res = minimize(negf_grad, np.array(x0), jac=True, method="SLSQP", bounds=bounds,
                           options={"maxiter": 200})
        x = np.clip(res.x, lo, hi)
        v = obj.f_float(x)
        if math.isfinite(v):
            found.append((v, tuple(float(t) for t in x)))
            # snap coordinates that sit on the region's edge exactly onto it
            snapped = tuple(float(a if abs(t - a) <= 1e-7 * (b - a) else b if abs(t - b) <= 1e-7 * (b - a) else t)
                            for t, a, b in zip(x, lo, hi))
            if snapped != tuple(x):
                vs = obj.f_float(np.array(snapped))
                if math.isfinite(vs):
                    found.append((vs, snapped))
    found.sort(key=lambda p: -p[0])
    return found


# ---------------------------------------------------------------------------
# branch and bound
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class BranchProgress:
    """What a ``progress`` callback receives about twice a second.

    Attributes
    ----------
    boxes : int
        Boxes evaluated so far.
    lower, upper : float
        The proved lower bound and the current upper bound of the supremum
        (in a yes/no check: ``upper`` is the largest unresolved bound).
    seconds : float
    """

    boxes: int
    lower: float
    upper: float
    seconds: float


@dataclasses.dataclass
class _Outcome:
    kind: str                      # "done" | "failed" | "budget" | "stuck"
    upper: float                   # max over leaves of their upper bounds (valid in every case)
    lower: float = -_INF           # proved lower bound of sup (from points)
    lower_point: tuple | None = None
    boxes: int = 0
    counterexample: tuple | None = None
    margin: float | None = None
    reason: str = ""


class _BranchAndBound:
    """Branch and bound for sup f over a box, on floats that store arb endpoints."""

    def __init__(self, obj: _Objective, *, collapse: bool = True, strategy: str = "both"):
        strategy = {"mean-value": "mvf"}.get(strategy, strategy)
        self.obj = obj
        self.n = obj.n
        self.reg = obj.region
        self.fv = obj.fv
        self.fvg = obj.fvg if strategy in ("both", "mvf") else None
        self.faff = obj.arb._value_affine if strategy in ("both", "affine") else None
        self.collapse = collapse
        self.w0 = [max(h - l, 1e-300) for l, h in zip(self.reg.lo_out, self.reg.hi_out)]

    def evaluate(self, lo: list, hi: list, enough: float = -_INF):
        """(upper, lo, hi, split_dim, centre, f(centre) ball, centre in region).

        The affine form (the costliest enclosure) is skipped when the cheaper
        ones already give ``upper ≤ enough``.
        """
        n = self.n
        reg = self.reg
        while True:
            X = [arb(lo[i]) if lo[i] == hi[i] else arb(lo[i]).union(arb(hi[i])) for i in range(n)]
            G = None
            if self.fvg is not None:
                out = self.fvg(*X)
                v = out[0]
                G = out[1:]
                for g in G:
                    if not g.is_finite():
                        G = None
                        break
            else:
                v = self.fv(*X)[0]
            if G is not None and self.collapse:
                changed = False
                for i in range(n):
                    if lo[i] < hi[i]:
                        g = G[i]
                        if g >= 0:
                            lo = list(lo)
                            lo[i] = hi[i]
                            changed = True
                        elif g <= 0:
                            hi = list(hi)
                            hi[i] = lo[i]
                            changed = True
                if changed:
                    continue
            break
        upper = float_up(v)
        c = []
        inside = True
        for i in range(n):
            a, b = lo[i], hi[i]
            m = a + (b - a) * 0.5
            if not a <= m <= b:
                m = a
            p, q = max(a, reg.lo_in[i]), min(b, reg.hi_in[i])
            if p <= q:
                m = min(max(m, p), q)
            else:
                inside = False
            c.append(m)
        C = [arb(x) for x in c]
        fc = self.fv(*C)[0]
        dim = -1
        if G is not None:
            cen = fc
            best = -1.0
            for i in range(n):
                if lo[i] < hi[i]:
                    g = G[i]
                    cen = cen + g * (X[i] - C[i])
                    score = float(g.abs_upper()) * (hi[i] - lo[i])
                    if score > best:
                        best, dim = score, i
            cu = float_up(cen)
            if cu < upper:
                upper = cu
            if best <= 0.0:
                dim = -1
        if self.faff is not None and not upper <= enough:
            zero = (_ZERO,) * n
            xs = []
            for i in range(n):
                m = C[i]
                if lo[i] == hi[i]:
                    xs.append(_Aff(m, zero, _ZERO))
                    continue
                r = (arb(hi[i]) - m).union(m - arb(lo[i])).abs_upper()
                xs.append(_Aff(m, zero[:i] + (r,) + zero[i + 1:], _ZERO))
            A = self.faff(*xs)[0]
            au = float_up(A.ball()) if A.__class__ is _Aff else float_up(A)
            if au < upper:
                upper = au
        if dim < 0:
            best = -1.0
            for i in range(n):
                w = (hi[i] - lo[i]) / self.w0[i]
                if w > best and lo[i] < hi[i]:
                    best, dim = w, i
        return upper, lo, hi, dim, c, fc, inside

    def _split(self, lo, hi, dim):
        """Two halves along dim (or another splittable dimension); None if the box is a float point."""
        order = [dim] + sorted((i for i in range(self.n) if i != dim),
                               key=lambda i: -(hi[i] - lo[i]) / self.w0[i]) if dim >= 0 else \
            sorted(range(self.n), key=lambda i: -(hi[i] - lo[i]) / self.w0[i])
        for d in order:
            a, b = lo[d], hi[d]
            m = a + (b - a) * 0.5
            if a < m < b:
                hi1 = list(hi)
                hi1[d] = m
                lo2 = list(lo)
                lo2[d] = m
                return (list(lo), hi1), (lo2, list(hi))
        return None

    def run(self, *, mode: str, threshold: float = 0.0, strict: bool = False, rel_gap: float = 1e-2,
            abs_gap: float = 0.0, budget_boxes: int, deadline: float, start: float,
            lower: float = -_INF, lower_point=None, refute=None, progress=None) -> _Outcome:
        """``mode="sup"``: bound sup f to the gap.  ``mode="decide"``: prove sup f ≤ threshold
        (< if strict) or find a point where ``refute`` proves the opposite."""
        reg = self.reg
        boxes = 0
        counter = 0
        heap = []
        resolved_max = -_INF          # leaves set aside: pruned (sup) or proved (decide)
        stuck_max = -_INF
        last_report = time.monotonic()

        def ok(u):
            return u < threshold if strict else u <= threshold

        def visit(box_eval):
            """Returns a counterexample outcome or None; updates the lower bound."""
            nonlocal lower, lower_point
            upper, lo, hi, dim, c, fc, inside = box_eval
            if inside:
                pl = float_down(fc)
                if pl > lower:
                    lower, lower_point = pl, tuple(c)
                if mode == "decide" and refute is not None and fc.is_finite():
                    m = float(fc.mid())
                    if m > threshold or (strict and m >= threshold):
                        return refute(c)
            return None

        root = self.evaluate(list(reg.lo_out), list(reg.hi_out))
        boxes += 1
        hit = visit(root)
        if hit is not None:
            return _Outcome("failed", _INF, lower, lower_point, boxes, hit[1], hit[0])
        heapq.heappush(heap, (-root[0], counter, root[1], root[2], root[3]))

        def tol():
            return max(rel_gap * abs(lower), abs_gap) if math.isfinite(lower) else -_INF

        while heap:
            top = -heap[0][0]
            now = time.monotonic()
            if progress is not None and now - last_report >= 0.5:
                last_report = now
                progress(BranchProgress(boxes, lower, max(top, resolved_max, stuck_max), now - start))
            if mode == "sup":
                U = max(top, resolved_max, stuck_max)
                if U - lower <= tol():
                    return _Outcome("done", U, lower, lower_point, boxes)
                if top <= stuck_max and stuck_max - lower > tol():
                    return _Outcome("stuck", U, lower, lower_point, boxes,
                                    reason="boxes shrank to float resolution without closing the gap")
            if boxes >= budget_boxes or now > deadline:
                U = max(top, resolved_max, stuck_max)
                why = (f"box budget of {budget_boxes} spent" if boxes >= budget_boxes
                       else "time budget spent")
                return _Outcome("budget", U, lower, lower_point, boxes, reason=why)
            negu, _, lo, hi, dim = heapq.heappop(heap)
            u = -negu
            if mode == "sup" and u <= lower:
                resolved_max = max(resolved_max, u)
                continue
            if mode == "decide" and ok(u):
                resolved_max = max(resolved_max, u)
                continue
            halves = self._split(lo, hi, dim)
            if halves is None:
                stuck_max = max(stuck_max, u)
                if mode == "decide":
                    return _Outcome("stuck", max(u, -heap[0][0] if heap else -_INF, resolved_max), lower,
                                    lower_point, boxes,
                                    reason="a box shrank to float resolution without a decision")
                continue
            enough = lower if mode == "sup" else (math.nextafter(threshold, -_INF) if strict else threshold)
            for clo, chi in halves:
                ev = self.evaluate(clo, chi, enough)
                boxes += 1
                hit = visit(ev)
                if hit is not None:
                    return _Outcome("failed", _INF, lower, lower_point, boxes, hit[1], hit[0])
                cu = ev[0]
                if mode == "sup" and cu <= lower:
                    resolved_max = max(resolved_max, cu)
                elif mode == "decide" and ok(cu):
                    resolved_max = max(resolved_max, cu)
                else:
                    counter += 1
                    heapq.heappush(heap, (-cu, counter, ev[1], ev[2], ev[3]))
        U = max(resolved_max, stuck_max)
        if mode == "sup":
            if U - lower <= tol():
                return _Outcome("done", U, lower, lower_point, boxes)
            return _Outcome("stuck", U, lower, lower_point, boxes,
                            reason="boxes shrank to float resolution without closing the gap")
        return _Outcome("done", U, lower, lower_point, boxes)


#: enclosures the branch and bound intersects on every box (see the module docstring)
ENCLOSURES = ("both", "mean-value", "affine")


def _check_options(*, budget_boxes, budget_seconds, rel_gap, abs_gap=0.0, starts, seed, progress,
                   enclosure="both"):
    problems = []
    if enclosure not in ENCLOSURES:
        problems.append(f"enclosure must be one of {ENCLOSURES}, got {enclosure!r}")
    if isinstance(budget_boxes, bool) or not isinstance(budget_boxes, int) or budget_boxes < 1:
        problems.append(f"budget_boxes must be a positive integer, got {budget_boxes!r}")
    if not isinstance(budget_seconds, (int, float)) or isinstance(budget_seconds, bool) or not budget_seconds > 0:
        problems.append(f"budget_seconds must be a positive number, got {budget_seconds!r}")
    if not isinstance(rel_gap, (int, float)) or isinstance(rel_gap, bool) or not rel_gap >= 0:
        problems.append(f"rel_gap must be a number ≥ 0, got {rel_gap!r}")
    if not isinstance(abs_gap, (int, float)) or isinstance(abs_gap, bool) or not abs_gap >= 0:
        problems.append(f"abs_gap must be a number ≥ 0, got {abs_gap!r}")
    if isinstance(starts, bool) or not isinstance(starts, int) or starts < 1:
        problems.append(f"starts must be a positive integer, got {starts!r}")
    if isinstance(seed, bool) or not isinstance(seed, int):
        problems.append(f"seed must be an integer, got {seed!r}")
    if progress is not None and not callable(progress):
        problems.append(f"progress must be callable or None, got {progress!r}")
    if problems:
        raise InputError("; ".join(problems))


def _fmt(x) -> str:
    if x is None:
        return "none"
    return f"{x:.6g}" if math.isfinite(x) else str(x)


def _json_float(x):
    if x is None:
        return None
    return x if math.isfinite(x) else str(x)


# ---------------------------------------------------------------------------
# suprema
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class SupResult:
    """The supremum of an expression over a box.

    Attributes
    ----------
    expr_text : str
    variables : tuple of str
    estimate : float
        The best value found by sampling and local maximisation -- status
        ``estimated`` (a lower bound of the supremum up to float rounding,
        never a proof).
    maximiser : dict of str to float
        Where the estimate was found (inside the box).
    lower : float
        A proved lower bound of the supremum: the arb value at a point of the
        box, rounded down (``-inf`` if no point value was finite).
    certified : float or None
        A proved upper bound of the supremum (rounded up).  It is valid
        whatever ``status`` says -- also when a budget ran out -- unless it
        is ``None`` (not attempted) or ``inf`` (nothing proved).
    gap : float
        ``(certified − lower) / |lower|``.
    status : Status
        ``certified`` if the gap target was met, ``undecided`` if a budget ran
        out first, ``estimated`` if certification was not asked for.
    boxes : int
        Boxes evaluated by the branch and bound.
    seconds : float
    detail : str
    """

    expr_text: str
    variables: tuple
    estimate: float
    maximiser: dict
    lower: float
    certified: float | None
    gap: float
    status: Status
    boxes: int
    seconds: float
    detail: str

    @property
    def estimate_status(self) -> Status:
        """The status of :attr:`estimate` alone: always ``estimated``."""
        return Status.ESTIMATED

    def to_json(self) -> dict:
        return {"expr": self.expr_text, "variables": list(self.variables),
                "estimate": {"value": _json_float(self.estimate), "status": Status.ESTIMATED.value},
                "maximiser": dict(self.maximiser), "lower": _json_float(self.lower),
                "certified": _json_float(self.certified), "gap": _json_float(self.gap),
                "status": self.status.value, "boxes": self.boxes, "seconds": self.seconds,
                "detail": self.detail}


def _gap(upper, lower) -> float:
    if upper is None or not math.isfinite(upper) or not math.isfinite(lower):
        return _INF
    if upper <= lower:
        return 0.0
    return (upper - lower) / abs(lower) if lower != 0 else _INF


def _sup(obj: _Objective, *, budget_boxes, budget_seconds, rel_gap, abs_gap, starts, seed, certify,
         progress, start, enclosure="both"):
    """(estimate, maximiser point, outcome or None)."""
    deadline = start + budget_seconds
    cands = _estimate(obj, starts=starts, seed=seed, deadline=start + 0.5 * budget_seconds)
    estimate, est_point = (cands[0] if cands else (-_INF, None))
    lower, lower_point = -_INF, None
    for _, p in cands[:3]:
        if obj.region.contains(p):
            pl = float_down(obj.point_ball(p))
            if pl > lower:
                lower, lower_point = pl, p
    if not certify:
        return estimate, est_point, _Outcome("skipped", _INF, lower, lower_point)
    bb = _BranchAndBound(obj, strategy=enclosure)
    out = bb.run(mode="sup", rel_gap=rel_gap, abs_gap=abs_gap, budget_boxes=budget_boxes,
                 deadline=deadline, start=start, lower=lower, lower_point=lower_point, progress=progress)
    if out.lower_point is not None and math.isfinite(out.lower):
        v = obj.f_float(np.array(out.lower_point))
        if v > estimate:
            estimate, est_point = v, out.lower_point
    return estimate, est_point, out


def _sup_detail(out: _Outcome, rel_gap: float, singular_note: str | None = None) -> str:
    if out.kind == "skipped":
        return ("estimate only (certify=False): sampled and locally maximised in floating point; "
                "a lower bound of the supremum, not a proof")
    proved = (f"sup ≤ {_fmt(out.upper)} is proved by arb enclosures on {out.boxes} boxes covering the "
              f"box; sup ≥ {_fmt(out.lower)} by an arb point value")
    if out.kind == "done":
        return proved + f"; relative gap {_fmt(_gap(out.upper, out.lower))} ≤ {rel_gap:g}"
    head = f"undecided: {out.reason or 'budget spent'} before the relative gap reached {rel_gap:g}; "
    if math.isfinite(out.upper):
        return head + (f"the upper bound {_fmt(out.upper)} is nevertheless proved (valid, just not "
                       f"tight); sup ≥ {_fmt(out.lower)} by an arb point value")
    return head + "no finite upper bound was proved: " + (
        singular_note or "some box's enclosure is not finite (the expression may be undefined or "
                         "singular there; reparametrise or cancel the singular factor)")


def sup_bound(expr, box: Mapping, *, budget_boxes: int = DEFAULT_BUDGET_BOXES,
              budget_seconds: float = DEFAULT_BUDGET_SECONDS, rel_gap: float = 1e-2,
              abs_gap: float = 0.0, starts: int = 8, seed: int = 0, certify: bool = True,
              enclosure: str = "both",
              progress: Callable[[BranchProgress], None] | None = None) -> SupResult:
    """The supremum of an expression over a box: an estimate and a proved upper bound.

    Parameters
    ----------
    expr : sympy.Expr
        See :func:`compile_arb` for what may appear.
    box : mapping of sympy.Symbol to (lo, hi)
        Finite bounds: numbers or SymPy constants (``sympy.pi``); a float is
        taken at its exact binary value (pass ``sympy.Rational(1, 10)`` for 1/10).
    budget_boxes, budget_seconds
        Ceilings for the whole job (estimate included).
    rel_gap : float, default 1e-2
        Stop when ``certified − lower ≤ rel_gap·|lower|``.
    abs_gap : float, default 0
        Or when ``certified − lower ≤ abs_gap`` (needed when the supremum is 0).
    starts : int, default 8
        Local maximisations (SLSQP with bounds) started from the best Sobol sample points.
    seed : int, default 0
    certify : bool, default True
        False: only the estimate (status ``estimated``).
    enclosure : {"both", "mean-value", "affine"}, default "both"
        Which enclosures bound a box: the mean-value form with the enclosed
        gradient (cheap; also gives the monotonicity test and the split
        direction), affine forms (first-order models, tighter on wide boxes of
        trigonometric expressions, about 2× costlier), or both intersected.
        Any choice is sound; it only changes speed.
    progress : callable, optional
        Called with a :class:`BranchProgress` about twice a second.

    Returns
    -------
    SupResult

    Notes
    -----
    The branch and bound splits the box with the largest upper bound, along
    the dimension whose enclosed partial derivative times width is largest
    (the widest one without a gradient), and drops boxes whose upper bound is
    ≤ the best proved lower bound.  Lower bounds come from arb point values
    at box centres and at the estimate.  See the module docstring for what
    the certificate consists of.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> res = sup_bound(sympy.sin(x) * sympy.cos(y), {x: (0, 3), y: (-1, 1)})
    >>> res.status, res.certified >= 1.0, res.gap <= 1e-2
    (<Status.CERTIFIED: 'certified'>, True, True)
    >>> sup_bound(x * (1 - x), {x: (0, 1)}, certify=False).status
    <Status.ESTIMATED: 'estimated'>
    """
    start = time.monotonic()
    _check_options(budget_boxes=budget_boxes, budget_seconds=budget_seconds, rel_gap=rel_gap,
                   abs_gap=abs_gap, starts=starts, seed=seed, progress=progress, enclosure=enclosure)
    expr = _sympify_expr(expr)
    region = _parse_region(box, [expr])
    obj = _Objective(expr, region)
    estimate, point, out = _sup(obj, budget_boxes=budget_boxes, budget_seconds=budget_seconds,
                                rel_gap=rel_gap, abs_gap=abs_gap, starts=starts, seed=seed,
                                certify=certify, progress=progress, start=start, enclosure=enclosure)
    if not certify:
        status, certified = Status.ESTIMATED, None
    else:
        status = Status.CERTIFIED if out.kind == "done" else Status.UNDECIDED
        certified = out.upper
    return SupResult(expr_text=str(expr), variables=region.names, estimate=estimate,
                     maximiser=region.point_dict(point) if point is not None else {},
                     lower=out.lower, certified=certified, gap=_gap(certified, out.lower),
                     status=status, boxes=out.boxes, seconds=time.monotonic() - start,
                     detail=_sup_detail(out, rel_gap))


# ---------------------------------------------------------------------------
# yes/no checks: expr ≤ 0, expr > 0, lhs ≤ c·template
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class CheckResult:
    """A claim about a box, proved, refuted or left open.

    Attributes
    ----------
    name : str
    claim : str
        The claim in words, e.g. ``"x**2 - 1 <= 0 on {x ∈ [-1, 1]}"``.
    status : Status
        ``certified`` (proved on the whole box), ``failed`` (refuted at
        :attr:`point`), ``undecided`` (budget spent, or a prerequisite such as
        the template's sign could not be proved).
    point : dict of str to float or None
        For ``failed``: a point of the box (exact binary floats) where the
        claim is false, proved with arb.
    margin : float or None
        For ``failed``: a proved lower bound of the violation at
        :attr:`point` (``lhs − c·template``, ``expr``, or ``−expr`` for a
        positivity claim).  For ``certified``: the proved slack
        (``c − certified sup of lhs/template``, ``−sup expr``, ``inf expr``).
    bound : float or None
        The proved bound behind the verdict: the certified supremum
        (of ``expr``, or of ``lhs/template``), or for a positivity claim the
        certified infimum of ``expr``.  Valid also for ``undecided``.
    boxes : int
    seconds : float
    detail : str
    """

    name: str
    claim: str
    status: Status
    point: dict | None
    margin: float | None
    bound: float | None
    boxes: int
    seconds: float
    detail: str

    def to_result(self, kind: str = "hypothesis"):
        """This check as a :class:`lkverify.report.results.Result` (``kind`` as the report needs it)."""
        from ..report.results import Result
        value = self.margin if self.status is not Status.UNDECIDED else self.bound
        return Result(kind, self.name, self.status, value, self.detail)

    def to_json(self) -> dict:
        return {"name": self.name, "claim": self.claim, "status": self.status.value,
                "point": self.point, "margin": _json_float(self.margin),
                "bound": _json_float(self.bound), "boxes": self.boxes, "seconds": self.seconds,
                "detail": self.detail}


def _decide(obj: _Objective, *, threshold: float, strict: bool, refute, budget_boxes, budget_seconds,
            starts, seed, progress, start, enclosure="both"):
    """Estimate (to find counterexamples fast), then branch and bound. Returns _Outcome."""
    deadline = start + budget_seconds
    cands = _estimate(obj, starts=starts, seed=seed, deadline=start + 0.25 * budget_seconds)
    for value, p in cands[:max(3, starts)]:
        if value > threshold or (strict and value >= threshold):
            if obj.region.contains(p):
                hit = refute(p)
                if hit is not None:
                    return _Outcome("failed", _INF, counterexample=hit[1], margin=hit[0])
    bb = _BranchAndBound(obj, strategy=enclosure)
    return bb.run(mode="decide", threshold=threshold, strict=strict, budget_boxes=budget_boxes,
                  deadline=deadline, start=start, refute=refute, progress=progress)


def _sign_check(expr, box, *, positive: bool, name, budget_boxes, budget_seconds, starts, seed,
                progress, enclosure) -> CheckResult:
    start = time.monotonic()
    _check_options(budget_boxes=budget_boxes, budget_seconds=budget_seconds, rel_gap=0.0,
                   starts=starts, seed=seed, progress=progress, enclosure=enclosure)
    expr = _sympify_expr(expr)
    region = _parse_region(box, [expr])
    claim = f"{expr} {'> 0' if positive else '<= 0'} on {region.text()}"
    obj = _Objective(-expr if positive else expr, region)

    def refute(p):
        val = obj.point_ball(p)
        if positive:      # −expr ≥ 0 proves expr ≤ 0
            return (float_down(val), tuple(p)) if val >= 0 else None
        return (float_down(val), tuple(p)) if val > 0 else None

    out = _decide(obj, threshold=0.0, strict=positive, refute=refute, budget_boxes=budget_boxes,
                  budget_seconds=budget_seconds, starts=starts, seed=seed, progress=progress,
                  start=start, enclosure=enclosure)
    seconds = time.monotonic() - start
    if out.kind == "failed":
        point = region.point_dict(out.counterexample)
        what = (f"{expr} ≤ 0 at {point} (arb: −expr ≥ {_fmt(out.margin)})" if positive
                else f"{expr} ≥ {_fmt(out.margin)} > 0 at {point} (arb point value)")
        return CheckResult(name or claim, claim, Status.FAILED, point, out.margin, None, out.boxes, seconds,
                           f"refuted: {what}")
    bound = -out.upper if positive else out.upper
    if out.kind == "done":
        what = (f"{expr} ≥ {_fmt(bound)} > 0" if positive else f"{expr} ≤ {_fmt(bound)} ≤ 0")
        return CheckResult(name or claim, claim, Status.CERTIFIED, None, -out.upper, bound, out.boxes,
                           seconds, f"proved by arb enclosures on {out.boxes} boxes: {what} on the box")
    return CheckResult(name or claim, claim, Status.UNDECIDED, None, None, bound, out.boxes, seconds,
                       f"undecided: {out.reason}; no counterexample found; the proved "
                       f"{'lower' if positive else 'upper'} bound of {expr} is {_fmt(bound)}")


def certify_nonpositive(expr, box: Mapping, *, name: str | None = None,
                        budget_boxes: int = DEFAULT_BUDGET_BOXES,
                        budget_seconds: float = DEFAULT_BUDGET_SECONDS, starts: int = 8, seed: int = 0,
                        enclosure: str = "both",
                        progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove ``expr ≤ 0`` on a box, or refute it at a point.

    Parameters
    ----------
    expr : sympy.Expr
    box : mapping of sympy.Symbol to (lo, hi)
    name : str, optional
        Defaults to the claim's text.
    budget_boxes, budget_seconds, starts, seed, enclosure, progress
        As for :func:`sup_bound`.

    Returns
    -------
    CheckResult
        ``certified``: every box's enclosure has upper end ≤ 0.  ``failed``:
        ``point`` is a point of the box with an arb value > 0 (``margin`` is
        its proved lower bound).  ``undecided``: the budget ran out -- which is
        what happens when ``expr`` touches 0 at a point where no enclosure is
        exact (a maximum of exactly 0 cannot be separated from 0 by boxes;
        prove ``expr ≤ -m`` on a region that excludes the touching point, or
        divide the touching factor out).

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> certify_nonpositive(x**2 + y**2 - 3, {x: (-1, 1), y: (-1, 1)}).status
    <Status.CERTIFIED: 'certified'>
    >>> res = certify_nonpositive(x**2 + y**2 - 1.5, {x: (-1, 1), y: (-1, 1)})
    >>> res.status, res.margin > 0
    (<Status.FAILED: 'failed'>, True)
    """
    return _sign_check(expr, box, positive=False, name=name, budget_boxes=budget_boxes,
                       budget_seconds=budget_seconds, starts=starts, seed=seed, progress=progress,
                       enclosure=enclosure)


def certify_positive(expr, box: Mapping, *, name: str | None = None,
                     budget_boxes: int = DEFAULT_BUDGET_BOXES,
                     budget_seconds: float = DEFAULT_BUDGET_SECONDS, starts: int = 8, seed: int = 0,
                     enclosure: str = "both",
                     progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove ``expr > 0`` on a box, or refute it at a point (where ``expr ≤ 0`` is proved).

    ``bound`` is then a proved lower bound of ``expr`` on the box (> 0).  See
    :func:`certify_nonpositive` for the options and for what ``undecided`` means.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> res = certify_positive(sympy.cos(x), {x: (-1, 1)})
    >>> res.status, res.bound > 0.5
    (<Status.CERTIFIED: 'certified'>, True)
    >>> certify_positive(sympy.cos(x), {x: (0, 2)}).status
    <Status.FAILED: 'failed'>
    """
    return _sign_check(expr, box, positive=True, name=name, budget_boxes=budget_boxes,
                       budget_seconds=budget_seconds, starts=starts, seed=seed, progress=progress,
                       enclosure=enclosure)


# ---------------------------------------------------------------------------
# best constants: lhs ≤ c·template
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class ConstantResult:
    """The best constant ``c`` in "lhs ≤ c·template on the region".

    Attributes
    ----------
    name : str
    template_text : str
    estimate : float
        ``sup lhs/template`` found by sampling and local maximisation --
        status ``estimated`` (a lower bound of the best constant).
    maximiser : dict of str to float
    certified : float or None
        A proved ``c``: ``lhs ≤ certified·template`` holds on the whole
        region when :attr:`status` is ``certified``.  When ``undecided`` the
        number is still a proved upper bound of ``sup lhs/template`` but a
        prerequisite (the template's sign, a ratio identity) or the gap target
        is missing -- see :attr:`detail`.
    gap : float
        ``(certified − lower) / |lower|`` with ``lower`` the proved lower
        bound of the best constant.
    status : Status
    boxes : int
    detail : str
    lower : float
        A proved lower bound of the best constant (an arb point value).
    seconds : float
    lhs_text : str
    """

    name: str
    template_text: str
    estimate: float
    maximiser: dict
    certified: float | None
    gap: float
    status: Status
    boxes: int
    detail: str
    lower: float = -_INF
    seconds: float = 0.0
    lhs_text: str = ""

    @property
    def estimate_status(self) -> Status:
        """The status of :attr:`estimate` alone: always ``estimated``."""
        return Status.ESTIMATED

    def to_json(self) -> dict:
        return {"name": self.name, "lhs": self.lhs_text, "template": self.template_text,
                "estimate": {"value": _json_float(self.estimate), "status": Status.ESTIMATED.value},
                "maximiser": dict(self.maximiser), "lower": _json_float(self.lower),
                "certified": _json_float(self.certified), "gap": _json_float(self.gap),
                "status": self.status.value, "boxes": self.boxes, "seconds": self.seconds,
                "detail": self.detail}

    def to_result(self):
        """This constant as a :class:`lkverify.report.results.Result` of kind ``constant``."""
        from ..report.results import Result
        value = self.certified if self.status is Status.CERTIFIED else self.estimate
        return Result("constant", self.name, self.status, value, self.detail)


def _prove_zero(expr: sympy.Expr) -> bool:
    """True if SymPy reduces expr to 0 (a proof); False means 'not proved', not 'nonzero'."""
    for attempt in (lambda e: sympy.expand(e), sympy.cancel, sympy.simplify,
                    lambda e: sympy.simplify(sympy.expand_trig(e)),
                    lambda e: sympy.simplify(sympy.expand(sympy.expand_trig(e), trig=True))):
        try:
            if attempt(expr) == 0:
                return True
        except Exception:  # noqa: BLE001 -- a failed simplification proves nothing
            continue
    return False


@dataclasses.dataclass
class _Prepared:
    region: _Region
    lhs: sympy.Expr
    template: sympy.Expr
    ratio: sympy.Expr
    ratio_note: str
    ratio_proved: bool


def _prepare_constant(lhs, template, region, ratio, seed) -> _Prepared:
    lhs = _sympify_expr(lhs, "lhs")
    template = _sympify_expr(template, "template")
    exprs = [lhs, template]
    if ratio is not None:
        ratio = _sympify_expr(ratio, "ratio")
        exprs.append(ratio)
    reg = _parse_region(region, exprs, "region")
    if template.is_zero:
        raise InputError("template is identically 0; a best constant needs a template > 0")
    if ratio is None:
        num, den = sympy.fraction(sympy.together(lhs / template))
        try:
            g = sympy.gcd(num, den)
        except Exception:  # noqa: BLE001
            g = sympy.S.One
        if g.free_symbols:
            ratio = sympy.cancel(lhs / template)
            return _Prepared(reg, lhs, template, ratio,
                             f"the common factor {g} of lhs and template was cancelled exactly "
                             f"(polynomial gcd)", True)
        return _Prepared(reg, lhs, template, lhs / template, "", True)
    # a caller's ratio: refute numerically first, then prove the identity symbolically
    dummies = _real_dummies(reg.variables, reg.signs)
    diff = (ratio * template - lhs).xreplace(dummies)
    f = _lambdify([dummies[v] for v in reg.variables], diff)
    scale = _lambdify([dummies[v] for v in reg.variables], (abs(lhs) + abs(ratio * template)).xreplace(dummies))
    rng = np.random.default_rng(seed)
    pts = [rng.uniform(a, b, 16) for a, b in zip(reg.lo_in, reg.hi_in)]
    d = np.abs(f(*pts))
    sc = np.abs(scale(*pts))
    bad = np.isfinite(d) & (d > 1e-8 * np.maximum(sc, 1.0))
    if bad.any():
        i = int(np.argmax(bad))
        where = {n: float(p[i]) for n, p in zip(reg.names, pts)}
        raise InputError(f"ratio {ratio} is not lhs/template: ratio*template - lhs = {float(d[i]):.3g} "
                         f"at {where}; pass the simplified lhs/template or omit ratio")
    proved = _prove_zero(diff)
    note = ("the ratio's identity ratio·template = lhs was proved symbolically (SymPy)" if proved else
            "the ratio's identity ratio·template = lhs was NOT proved symbolically (only checked at "
            "16 random points), so the result cannot be certified")
    return _Prepared(reg, lhs, template, ratio, note, proved)


def _template_sign(prep: _Prepared, *, budget_boxes, budget_seconds, seed, start):
    """(status, text): is template ≥ 0 on the region proved?"""
    reg = prep.region
    tf = compile_arb(prep.template, reg.variables, gradient=False, _signs=reg.signs)
    dummies = _real_dummies(reg.variables, reg.signs)
    if tf.nonnegative or prep.template.xreplace(dummies).is_nonnegative:
        return Status.EXACT, "template ≥ 0 structurally (exact)"
    res = certify_nonpositive(-prep.template, dict(zip(reg.variables, reg.bounds)),
                              budget_boxes=budget_boxes, budget_seconds=budget_seconds, seed=seed)
    if res.status is Status.FAILED:
        raise InputError(f"template {prep.template} is negative at {res.point} (proved: "
                         f"≤ {-res.margin:.3g}); a best constant needs template ≥ 0 on the region")
    if res.status is Status.CERTIFIED:
        return Status.CERTIFIED, f"template ≥ 0 proved by arb on {res.boxes} boxes"
    return Status.UNDECIDED, "template ≥ 0 could not be proved within budget"


_SINGULAR_NOTE = ("where the template's enclosure contains 0 the ratio's enclosure is not finite and no "
                  "bound is certified there; cancel the vanishing factor (ratio=...) or reparametrise "
                  "so that it cancels")


def best_constant(lhs, template, region: Mapping, *, name: str = "c", ratio=None,
                  budget_boxes: int = DEFAULT_BUDGET_BOXES, budget_seconds: float = DEFAULT_BUDGET_SECONDS,
                  rel_gap: float = 1e-2, starts: int = 8, seed: int = 0, enclosure: str = "both",
                  progress: Callable[[BranchProgress], None] | None = None) -> ConstantResult:
    """The best ``c`` in "lhs ≤ c·template on the region", i.e. ``sup lhs/template``.

    Parameters
    ----------
    lhs, template : sympy.Expr
        ``template`` must be ≥ 0 on the region and > 0 except on a set with
        empty interior (where it vanishes, ``lhs`` must vanish too).
    region : mapping of sympy.Symbol to (lo, hi)
        A box; parametrise manifolds and balls with the charts of this module
        (:func:`unit_vector_near`, :func:`rotation_axis_angle`, ...).
    name : str, default "c"
    ratio : sympy.Expr, optional
        ``lhs/template`` with the vanishing factor cancelled (e.g.
        ``cos(rho/2)`` for ``sin(rho) / (2 sin(rho/2))``).  It is checked at
        random points (a mismatch raises :class:`InputError`) and the identity
        ``ratio·template = lhs`` is proved with SymPy; if SymPy cannot prove
        it the result is at most ``undecided``.  Without ``ratio`` a common
        polynomial factor of lhs and template is cancelled exactly
        (``sympy.cancel``) when there is one.
    budget_boxes, budget_seconds, rel_gap, starts, seed, enclosure, progress
        As for :func:`sup_bound`; the template's sign proof uses part of the budget.

    Returns
    -------
    ConstantResult
        ``certified`` when (1) template ≥ 0 is proved (structurally or by
        branch and bound), (2) the ratio identity, if any, is proved, and
        (3) the supremum of the ratio is bounded to ``rel_gap``.

    Notes
    -----
    Removable singularities.  At a point where the template vanishes (the
    origin, ``s = r``) the quotient ``lhs/template`` is 0/0 and its enclosure
    on every box around that point is not finite: such boxes get an
    infinite upper bound, are split again and again, and the result is
    ``undecided`` with ``certified = inf`` -- never a bogus certificate.  The
    cure is to hand over the quotient with the vanishing factor cancelled:
    either pass ``ratio=``, or reparametrise so the factor is explicit (the
    charts expose ``‖s − r‖ = 2 sin(ρ/2)`` and ``‖s × r‖ = sin ρ``) and cancel
    it in the expressions you pass.

    Why the certificate is sound: on every leaf box the ratio's enclosure is
    finite, so its denominator does not vanish there and ``lhs = ratio ·
    template`` holds pointwise; with ``template ≥ 0`` and ``ratio ≤ c`` this
    gives ``lhs ≤ c·template`` on the leaf, also where ``template = 0``.

    Examples
    --------
    For unit vectors s, r with angle ρ: ‖s × r‖ = sin ρ, ‖s − r‖ = 2 sin(ρ/2),
    so ‖s × r‖ ≤ c‖s − r‖ with best c = 1 (at s → r):

    >>> import sympy
    >>> rho = sympy.Symbol("rho")
    >>> res = best_constant(sympy.sin(rho), 2 * sympy.sin(rho / 2), {rho: (0, sympy.pi / 3)},
    ...                     ratio=sympy.cos(rho / 2))
    >>> res.status, 1.0 <= res.certified <= 1.01
    (<Status.CERTIFIED: 'certified'>, True)
    >>> best_constant(sympy.sin(rho), 2 * sympy.sin(rho / 2), {rho: (0, 1)},
    ...               budget_boxes=300).status          # 0/0 at rho = 0: never certified
    <Status.UNDECIDED: 'undecided'>
    """
    start = time.monotonic()
    _check_options(budget_boxes=budget_boxes, budget_seconds=budget_seconds, rel_gap=rel_gap,
                   starts=starts, seed=seed, progress=progress, enclosure=enclosure)
    if not isinstance(name, str):
        raise InputError(f"name must be a string, got {name!r}")
    prep = _prepare_constant(lhs, template, region, ratio, seed)
    reg = prep.region
    sign_status, sign_text = _template_sign(prep, budget_boxes=max(1, budget_boxes // 4),
                                            budget_seconds=budget_seconds / 4, seed=seed, start=start)
    obj = _Objective(prep.ratio, reg)
    remaining = max(budget_seconds - (time.monotonic() - start), 1e-3)
    estimate, point, out = _sup(obj, budget_boxes=budget_boxes, budget_seconds=remaining, rel_gap=rel_gap,
                                abs_gap=0.0, starts=starts, seed=seed, certify=True, progress=progress,
                                start=time.monotonic(), enclosure=enclosure)
    notes = [sign_text] + ([prep.ratio_note] if prep.ratio_note else [])
    ok = out.kind == "done" and sign_status.is_proof and prep.ratio_proved
    status = Status.CERTIFIED if ok else Status.UNDECIDED
    if ok:
        head = (f"lhs ≤ {_fmt(out.upper)}·template proved on the region "
                f"({out.boxes} boxes; best constant ≥ {_fmt(out.lower)}, relative gap "
                f"{_fmt(_gap(out.upper, out.lower))})")
    else:
        head = _sup_detail(out, rel_gap, _SINGULAR_NOTE) if out.kind != "done" else (
            f"sup lhs/template ≤ {_fmt(out.upper)} is proved, but not every prerequisite is")
    return ConstantResult(name=name, template_text=str(prep.template), estimate=estimate,
                          maximiser=reg.point_dict(point) if point is not None else {},
                          certified=out.upper, gap=_gap(out.upper, out.lower), status=status,
                          boxes=out.boxes, detail="; ".join([head] + notes), lower=out.lower,
                          seconds=time.monotonic() - start, lhs_text=str(prep.lhs))


def check_constant(lhs, template, region: Mapping, claimed_c, *, name: str = "c", ratio=None,
                   budget_boxes: int = DEFAULT_BUDGET_BOXES, budget_seconds: float = DEFAULT_BUDGET_SECONDS,
                   starts: int = 8, seed: int = 0, enclosure: str = "both",
                   progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove or refute a claimed constant: "lhs ≤ claimed_c·template on the region".

    Parameters
    ----------
    lhs, template, region, name, ratio
        As for :func:`best_constant`.
    claimed_c : number or SymPy number
        A float is taken at its exact binary value (pass ``sympy.Rational(921, 100)`` for 9.21).
    budget_boxes, budget_seconds, starts, seed, enclosure, progress
        As for :func:`sup_bound`.

    Returns
    -------
    CheckResult
        ``failed``: at :attr:`~CheckResult.point` (exact binary floats inside the
        region) the arb value of ``lhs − claimed_c·template`` has a lower
        bound ``margin > 0`` -- a proof that the constant is too small, which
        needs neither the template's sign nor the ratio.  ``certified``: the
        template is proved ≥ 0, the ratio identity (if any) is proved, and
        the certified supremum of lhs/template (``bound``) is ≤ claimed_c.
        ``undecided`` otherwise.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> check_constant(x * (2 - x), x, {x: (0, 2)}, 2.01).status     # lhs/template = 2 - x ≤ 2
    <Status.CERTIFIED: 'certified'>
    >>> res = check_constant(x * (2 - x), x, {x: (0, 2)}, 1.9)
    >>> res.status, res.point["x"] < 0.1, res.margin > 0
    (<Status.FAILED: 'failed'>, True, True)
    """
    start = time.monotonic()
    _check_options(budget_boxes=budget_boxes, budget_seconds=budget_seconds, rel_gap=0.0,
                   starts=starts, seed=seed, progress=progress, enclosure=enclosure)
    c_exact = _exact_number(claimed_c, "claimed_c")
    c_ball = _sympy_number_ball(c_exact)
    prep = _prepare_constant(lhs, template, region, ratio, seed)
    reg = prep.region
    claim = f"{prep.lhs} <= {c_exact}*({prep.template}) on {reg.text()}"
    violation = compile_arb(prep.lhs - sympy.Symbol("_c_lkverify") * prep.template,
                            list(reg.variables) + [sympy.Symbol("_c_lkverify")], gradient=False,
                            _signs=list(reg.signs) + [(False, False)])

    centre = [a + (b - a) / 2 for a, b in zip(reg.lo_in, reg.hi_in)]

    def refute(p):
        # where the template vanishes the violation is 0 even if the ratio exceeds c there:
        # then try points slightly inside, towards the centre of the region
        best = None
        for t in (0.0, 2.0 ** -30, 2.0 ** -20, 2.0 ** -10, 2.0 ** -6, 2.0 ** -3):
            q = tuple(float(a + t * (m - a)) for a, m in zip(p, centre))
            if not reg.contains(q):
                continue
            val = violation._value(*[arb(x) for x in q], c_ball)[0]
            if val > 0 and (best is None or float_down(val) > best[0]):
                best = (float_down(val), q)
        return best

    obj = _Objective(prep.ratio, reg)
    out = _decide(obj, threshold=float_down(c_ball), strict=False, refute=refute,
                  budget_boxes=budget_boxes, budget_seconds=budget_seconds * 0.75, starts=starts,
                  seed=seed, progress=progress, start=start, enclosure=enclosure)
    if out.kind == "failed":
        point = reg.point_dict(out.counterexample)
        return CheckResult(name, claim, Status.FAILED, point, out.margin, None, out.boxes,
                           time.monotonic() - start,
                           f"refuted: lhs − {c_exact}·template ≥ {_fmt(out.margin)} > 0 at {point} "
                           f"(arb point value at exact binary coordinates)")
    sign_status, sign_text = _template_sign(prep, budget_boxes=max(1, budget_boxes // 4),
                                            budget_seconds=max(budget_seconds * 0.25, 1e-3), seed=seed,
                                            start=start)
    notes = [sign_text] + ([prep.ratio_note] if prep.ratio_note else [])
    seconds = time.monotonic() - start
    if out.kind == "done" and sign_status.is_proof and prep.ratio_proved:
        return CheckResult(name, claim, Status.CERTIFIED, None, float_down(c_ball - arb(out.upper)), out.upper,
                           out.boxes, seconds,
                           "; ".join([f"proved: sup lhs/template ≤ {_fmt(out.upper)} ≤ {c_exact} by arb "
                                      f"enclosures on {out.boxes} boxes"] + notes))
    why = (out.reason if out.kind != "done" else "a prerequisite is not proved")
    bound_note = "" if math.isfinite(out.upper) else "; " + _SINGULAR_NOTE
    return CheckResult(name, claim, Status.UNDECIDED, None, None, out.upper, out.boxes, seconds,
                       "; ".join([f"undecided: {why}; no counterexample found{bound_note}"] + notes))


# ---------------------------------------------------------------------------
# charts: manifolds and balls as boxes
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Chart:
    """A parametrisation ``value(parameters)`` with the parameters in a box.

    Attributes
    ----------
    value : sympy.Matrix
        A 3-vector or a 3×3 rotation matrix in the parameters; substitute it
        for the state (``expr.subs(dict(zip(s, chart.value)))``).
    region : mapping of sympy.Symbol to (lo, hi)
        The parameter box; pass it (or a sub-box) to :func:`sup_bound`,
        :func:`best_constant`, ...
    extras : mapping of str to sympy.Expr
        Closed forms the chart knows (``"distance"``: ‖s − r‖, ``"angle"``, ...),
        for cancelling vanishing factors by hand.
    description : str
    """

    value: sympy.Matrix
    region: Mapping
    extras: Mapping
    description: str

    @property
    def parameters(self) -> tuple:
        return tuple(self.region)


def _mapping(d: dict):
    import types
    return types.MappingProxyType(dict(d))


def _symbols(given, names: str) -> tuple:
    if given is None:
        return sympy.symbols(names, real=True)
    given = tuple(given) if isinstance(given, (list, tuple)) else (given,)
    if not all(isinstance(s, sympy.Symbol) for s in given):
        raise InputError(f"chart parameters must be sympy Symbols, got {given!r}")
    return given


def _positive_bound(value, what: str, upper=None):
    v = _exact_number(value, what)
    if not v.is_positive:
        raise InputError(f"{what} must be > 0, got {v}")
    if upper is not None and (v - upper).is_positive:
        raise InputError(f"{what} must be ≤ {upper}, got {v}")
    return v


def _sphere(theta, phi) -> sympy.Matrix:
    return sympy.Matrix([sympy.sin(theta) * sympy.cos(phi), sympy.sin(theta) * sympy.sin(phi),
                         sympy.cos(theta)])


def _skew(v) -> sympy.Matrix:
    return sympy.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def _reference(reference) -> sympy.Matrix | None:
    if reference is None:
        return None
    R0 = sympy.Matrix(reference)
    if R0.shape != (3, 3) or R0.free_symbols:
        raise InputError(f"reference must be a numeric 3×3 rotation matrix, got shape {R0.shape}")
    if not all(_prove_zero(e) for e in (R0.T * R0 - sympy.eye(3))) or not _prove_zero(R0.det() - 1):
        raise InputError("reference must be a rotation matrix (R0ᵀR0 = I, det R0 = 1), checked exactly")
    return R0


def unit_vector_angles(theta=None, phi=None) -> Chart:
    """A unit vector on S² by spherical angles, θ ∈ [0, π], φ ∈ [0, 2π].

    ``s = (sin θ cos φ, sin θ sin φ, cos θ)``.

    Examples
    --------
    >>> ch = unit_vector_angles()
    >>> sympy.simplify(ch.value.dot(ch.value))
    1
    >>> [str(p) for p in ch.parameters]
    ['theta', 'phi']
    """
    theta, phi = _symbols(None if theta is None else (theta, phi), "theta phi")
    return Chart(_sphere(theta, phi), _mapping({theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({}), "unit vector s(θ, φ) on the sphere")


def unit_vector_near(r, *, rho_max=None, distance_max=None, rho=None, psi=None) -> Chart:
    """Unit vectors near a unit vector ``r``: angle ρ from r and azimuth ψ.

    ``s = cos ρ · r + sin ρ (cos ψ · e1 + sin ψ · e2)`` with (e1, e2, r) a
    right-handed orthonormal frame, so ``‖s − r‖ = 2 sin(ρ/2)`` and
    ``‖s × r‖ = sin ρ`` exactly (extras ``"distance"``, ``"cross_norm"``).

    Parameters
    ----------
    r : 3-vector of SymPy numbers with ‖r‖ = 1 (checked exactly)
    rho_max : number, optional
        ρ ∈ [0, rho_max], rho_max ≤ π.
    distance_max : number, optional
        Instead of rho_max: the cap ‖s − r‖ ≤ d (d ≤ 2), i.e. ρ ≤ 2 asin(d/2).
    rho, psi : sympy.Symbol, optional

    Examples
    --------
    >>> r = sympy.Matrix([1, 1, 1]) / sympy.sqrt(3)
    >>> ch = unit_vector_near(r, distance_max=1)
    >>> rho, psi = ch.parameters
    >>> s = ch.value
    >>> sympy.simplify((s - r).dot(s - r) - ch.extras["distance"] ** 2)
    0
    >>> ch.region[rho]
    (0, pi/3)
    """
    r = sympy.Matrix(r)
    if r.shape not in ((3, 1), (1, 3)) or r.free_symbols:
        raise InputError(f"r must be a numeric 3-vector, got {r}")
    r = r.reshape(3, 1)
    if not _prove_zero(r.dot(r) - 1):
        raise InputError(f"r must be a unit vector (checked exactly), got ‖r‖² = {sympy.nsimplify(r.dot(r))}")
    if (rho_max is None) == (distance_max is None):
        raise InputError("give exactly one of rho_max (angle from r) and distance_max (‖s − r‖ ≤ d)")
    if distance_max is not None:
        d = _positive_bound(distance_max, "distance_max", 2)
        top = 2 * sympy.asin(d / 2)
    else:
        top = _positive_bound(rho_max, "rho_max", sympy.pi)
    rho, psi = _symbols(None if rho is None else (rho, psi), "rho psi")
    k = min(range(3), key=lambda i: abs(float(r[i])))
    a = sympy.Matrix([1 if i == k else 0 for i in range(3)])
    w = a - a.dot(r) * r
    e1 = (w / sympy.sqrt(w.dot(w))).applyfunc(sympy.radsimp)
    e2 = r.cross(e1).applyfunc(sympy.radsimp)
    s = sympy.cos(rho) * r + sympy.sin(rho) * (sympy.cos(psi) * e1 + sympy.sin(psi) * e2)
    return Chart(s, _mapping({rho: (0, top), psi: (0, 2 * sympy.pi)}),
                 _mapping({"distance": 2 * sympy.sin(rho / 2), "cross_norm": sympy.sin(rho),
                           "angle": rho, "e1": e1, "e2": e2}),
                 f"unit vector s(ρ, ψ) at angle ρ ≤ {top} from r = {list(r)}")


def rotation_axis_angle(*, rho_max, rho=None, theta=None, phi=None, reference=None) -> Chart:
    """Rotations near a reference frame by angle ρ ∈ [0, rho_max] about an axis n(θ, φ).

    ``R = R0 (I + sin ρ N + (1 − cos ρ) N²)``, ``N = [n]×`` (Rodrigues), with
    ``n`` the unit vector of :func:`unit_vector_angles`; no singularity at
    ρ = 0 (the rotation vector is ρ·n).  ``‖R − R0‖_F = 2√2 sin(ρ/2)``
    (extra ``"frobenius_distance"``).

    Examples
    --------
    >>> ch = rotation_axis_angle(rho_max=sympy.pi / 6)
    >>> rho, theta, phi = ch.parameters
    >>> R = np.array(ch.value.subs({rho: 0.5, theta: 1.0, phi: 2.0}).evalf(), dtype=float)
    >>> bool(np.allclose(R.T @ R, np.eye(3)))
    True
    """
    top = _positive_bound(rho_max, "rho_max", sympy.pi)
    rho, theta, phi = _symbols(None if rho is None else (rho, theta, phi), "rho theta phi")
    n = _sphere(theta, phi)
    N = _skew(n)
    R = sympy.eye(3) + sympy.sin(rho) * N + (1 - sympy.cos(rho)) * N * N
    R0 = _reference(reference)
    if R0 is not None:
        R = R0 * R
    return Chart(R, _mapping({rho: (0, top), theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({"angle": rho, "axis": n,
                           "frobenius_distance": 2 * sympy.sqrt(2) * sympy.sin(rho / 2)}),
                 f"rotation by angle ρ ≤ {top} about n(θ, φ)" + (" after R0" if R0 is not None else ""))


def rotation_vector(v=None, *, radius, reference=None) -> Chart:
    """Rotations near a reference frame by a rotation vector v ∈ [−radius, radius]³.

    ``R = R0 (I + sinc θ · K + ½ sinc²(θ/2) · K²)``, ``K = [v]×``,
    ``θ = ‖v‖`` (written with ``sinc``, which arb encloses across θ = 0; the
    gradient of ``sinc(√(v·v))`` is not enclosed on boxes containing v = 0, so
    the branch and bound uses natural enclosures there).  Prefer
    :func:`rotation_axis_angle` when the angle must appear explicitly.

    Examples
    --------
    >>> ch = rotation_vector(radius=sympy.Rational(1, 2))
    >>> v = ch.parameters
    >>> R = ch.value.subs({v[0]: 0, v[1]: 0, v[2]: sympy.pi / 2})   # a quarter turn about z
    >>> np.round(np.array(R.evalf(), dtype=float), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    top = _positive_bound(radius, "radius", sympy.pi)
    v = _symbols(v, "v1 v2 v3")
    if len(v) != 3:
        raise InputError(f"a rotation vector has 3 components, got {len(v)}")
    K = _skew(v)
    th = sympy.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)
    R = sympy.eye(3) + sympy.sinc(th) * K + sympy.sinc(th / 2) ** 2 / 2 * K * K
    R0 = _reference(reference)
    if R0 is not None:
        R = R0 * R
    return Chart(R, _mapping({vi: (-top, top) for vi in v}), _mapping({"angle": th}),
                 f"rotation by the rotation vector v ∈ [−{top}, {top}]³")


def rotation_quaternion(q=None, *, radius, reference=None) -> Chart:
    """Rotations near a reference frame by the vector part q ∈ [−radius, radius]³ of a unit quaternion.

    ``q0 = √(1 − ‖q‖²)`` (requires 3·radius² ≤ 1); ``R = R0 ((q0² − ‖q‖²) I
    + 2 q qᵀ + 2 q0 [q]×)``; the rotation angle is ``2 asin ‖q‖``.

    Examples
    --------
    >>> ch = rotation_quaternion(radius=sympy.Rational(1, 2))
    >>> q = ch.parameters
    >>> R = ch.value.subs({q[0]: 0, q[1]: 0, q[2]: 0})
    >>> R == sympy.eye(3)
    True
    """
    top = _positive_bound(radius, "radius")
    if (3 * top ** 2 - 1).is_positive:
        raise InputError(f"radius must satisfy 3·radius² ≤ 1 so that ‖q‖ ≤ 1 on the box, got {top}")
    q = _symbols(q, "q1 q2 q3")
    if len(q) != 3:
        raise InputError(f"the quaternion's vector part has 3 components, got {len(q)}")
    qv = sympy.Matrix(q)
    nq = qv.dot(qv)
    q0 = sympy.sqrt(1 - nq)
    R = (q0 ** 2 - nq) * sympy.eye(3) + 2 * qv * qv.T + 2 * q0 * _skew(qv)
    R = R.applyfunc(sympy.expand)
    R0 = _reference(reference)
    if R0 is not None:
        R = R0 * R
    return Chart(R, _mapping({qi: (-top, top) for qi in q}),
                 _mapping({"angle": 2 * sympy.asin(sympy.sqrt(nq)), "q0": q0}),
                 f"rotation by the quaternion vector part q ∈ [−{top}, {top}]³")


_EULER = {
    "yzx": (("y", 2), ("z", 1), ("x", 0)),
    "zyx": (("z", 2), ("y", 1), ("x", 0)),
    "xyz": (("x", 0), ("y", 1), ("z", 2)),
}


def _elementary(axis: str, a) -> sympy.Matrix:
    c, s = sympy.cos(a), sympy.sin(a)
    if axis == "x":
        return sympy.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return sympy.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sympy.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rotation_euler(angles=None, *, bound, convention: str = "yzx", reference=None) -> Chart:
    """Rotations by aircraft angles roll φ, pitch θ, yaw ψ, each in [−bound, bound].

    Conventions as in :mod:`lkverify.simulate.rigidbody` (body-to-base matrices):
    ``"yzx"`` (default, GOST 20058-80) ``R = R_y(ψ) R_z(θ) R_x(φ)``;
    ``"zyx"`` ``R = R_z(ψ) R_y(θ) R_x(φ)``; ``"xyz"`` ``R = R_x(φ) R_y(θ) R_z(ψ)``.

    Examples
    --------
    >>> ch = rotation_euler(bound=sympy.pi / 4)
    >>> [str(p) for p in ch.parameters]
    ['roll', 'pitch', 'yaw']
    >>> ch.value.subs({p: 0 for p in ch.parameters}) == sympy.eye(3)
    True
    """
    if convention not in _EULER:
        raise InputError(f"convention must be one of {sorted(_EULER)}, got {convention!r}")
    top = _positive_bound(bound, "bound", sympy.pi)
    angles = _symbols(angles, "roll pitch yaw")
    if len(angles) != 3:
        raise InputError(f"give three angles (roll, pitch, yaw), got {len(angles)}")
    R = sympy.eye(3)
    for axis, which in _EULER[convention]:
        R = R * _elementary(axis, angles[which])
    R0 = _reference(reference)
    if R0 is not None:
        R = R0 * R
    return Chart(R, _mapping({a: (-top, top) for a in angles}), _mapping({}),
                 f"rotation by roll, pitch, yaw ∈ [−{top}, {top}] ({convention})")


def ball_point(*, r_max, radius=None, theta=None, phi=None) -> Chart:
    """A point of the closed ball ‖x‖ ≤ r_max in R³: radius × direction.

    ``x = ρ (sin θ cos φ, sin θ sin φ, cos θ)``, ρ ∈ [0, r_max]; ``‖x‖ = ρ``
    (extra ``"norm"``).  For homogeneous bounds divide by the right power of
    ρ before bounding (the ratio then depends on the direction only).

    Examples
    --------
    >>> ch = ball_point(r_max=2)
    >>> rho, theta, phi = ch.parameters
    >>> sympy.simplify(ch.value.dot(ch.value))
    rho**2
    """
    top = _positive_bound(r_max, "r_max")
    radius, theta, phi = _symbols(None if radius is None else (radius, theta, phi), "rho theta phi")
    return Chart(radius * _sphere(theta, phi),
                 _mapping({radius: (0, top), theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({"norm": radius}), f"point of the ball of radius {top} in R³")
