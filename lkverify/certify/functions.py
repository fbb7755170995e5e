"""SymPy expressions in real variables compiled to functions on arb balls (:func:`compile_arb`).

Examples
--------
>>> import sympy
>>> x = sympy.Symbol("x")
>>> compile_arb(x**2 - 1, [x])((0, 1)).contains(-1)
True
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Sequence

import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from .affine import AFFINE_HELPERS
from .intervals import compile_program, to_ball
from .intervals.balls import _JUMPS
from .intervals.convert import _real_dummies, _sympify

__all__ = ["ArbFunction", "check_symbols", "compile_arb", "lambdify_real", "sympify_expr"]


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
    value_program, gradient_program, affine_program : callable
        The compiled programs on balls (the value; the value and the partial
        derivatives; the value on :class:`~lkverify.certify.affine.AffineForm`
        arguments), each returning a list; what the branch and bound calls.

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
    value_program: Callable = dataclasses.field(repr=False, compare=False)
    gradient_program: Callable | None = dataclasses.field(repr=False, compare=False)
    affine_program: Callable | None = dataclasses.field(repr=False, compare=False, default=None)

    def __call__(self, *args) -> arb:
        return self.value_program(*self._balls(args))[0]

    def balls(self, *args: arb) -> arb:
        """The value's enclosure for arguments that are already arb balls (no conversion, no checks)."""
        return self.value_program(*args)[0]

    def value_and_gradient(self, *args) -> tuple:
        """The value's enclosure and the tuple of the partial derivatives' enclosures.

        On a ball where the expression has a kink (``Abs``, ``Min``, ``Max``) the
        partial derivatives enclose Clarke's generalised gradient.
        """
        if self.gradient_program is None:
            raise InputError(f"no gradient for {self.expr}: it has jumps (sign, Heaviside) or "
                             f"a part whose derivative cannot be enclosed")
        out = self.gradient_program(*self._balls(args))
        return out[0], tuple(out[1:])

    def _balls(self, args) -> list:
        if len(args) != len(self.variables):
            raise InputError(f"expected {len(self.variables)} arguments "
                             f"({', '.join(map(str, self.variables))}), got {len(args)}")
        return [to_ball(a) for a in args]


def check_symbols(variables) -> tuple:
    """The variables as a tuple of distinct SymPy Symbols (InputError listing every problem otherwise).

    Examples
    --------
    >>> import sympy
    >>> check_symbols(sympy.symbols("x y"))
    (x, y)
    """
    variables = tuple(variables)
    problems = [f"{v!r} is not a SymPy Symbol" for v in variables if not isinstance(v, sympy.Symbol)]
    if len(set(variables)) != len(variables):
        problems.append("a variable is listed twice")
    if problems:
        raise InputError("variables: " + "; ".join(problems) + "; pass distinct sympy.Symbol objects")
    return variables


def sympify_expr(expr, what: str = "expression") -> sympy.Expr:
    """A user's scalar SymPy expression, strictly (strings are never evaluated; matrices refused).

    Examples
    --------
    >>> sympify_expr(3)
    3
    """
    if isinstance(expr, sympy.MatrixBase):
        raise InputError(f"{what}: expected a scalar expression, got a {expr.shape} matrix")
    return _sympify(expr, what)  # the interval layer's one conversion (floats at their binary value)


def compile_arb(expr, variables: Sequence, *, gradient: bool = True,
                signs: Sequence[tuple[bool, bool]] | None = None) -> ArbFunction:
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
    signs : sequence of (nonnegative, positive), optional
        Known signs of the variables (from a region's lower bounds), for the
        compiler's sign reasoning.

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
    variables = check_symbols(variables)
    expr = sympify_expr(expr)
    missing = expr.free_symbols - set(variables)
    if missing:
        raise InputError(f"free symbols {sorted(map(str, missing))} of {expr} have no interval; "
                         f"list them as variables or substitute their values")
    dummies = _real_dummies(variables, signs)
    dexpr = expr.xreplace(dummies)
    dvars = [dummies[v] for v in variables]
    flags = [bool(d.is_nonnegative) for d in dvars]
    back = {d: v for v, d in dummies.items()}
    prog = compile_program([dexpr], dvars, nonnegative=flags, originals=back)
    value_fn = prog.function()
    affine_fn = prog.function(AFFINE_HELPERS)

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
                       has_gradient=grad_fn is not None, value_program=value_fn, gradient_program=grad_fn,
                       affine_program=affine_fn)


def lambdify_real(dvars, dexpr) -> Callable:
    """``sympy.lambdify`` on NumPy arrays, quiet and broadcasting: float values for estimates only.

    Examples
    --------
    >>> import numpy as np, sympy
    >>> x, y = sympy.symbols("x y")
    >>> lambdify_real([x, y], x + 0 * y)(np.array([1.0, 2.0]), 0.0)
    array([1., 2.])
    """
    fn = sympy.lambdify(dvars, dexpr, modules="numpy")

    def f(*xs):
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = fn(*xs)
        shape = np.broadcast_shapes(*(np.shape(x) for x in xs)) if xs else ()
        return np.broadcast_to(np.asarray(out, dtype=float), shape)

    return f
