"""Floating-point values of SymPy expressions evaluated once, by walking the tree (no code generation).

``sympy.lambdify`` prints an expression as Python source, optionally after common-subexpression
elimination, and compiles it: worth it for a function called many times (an integrand under
quadrature, an objective under an optimiser), but for one evaluation the printing costs a hundred
times the arithmetic.  :func:`float_values` visits every distinct node once (shared subtrees are
evaluated once) with the same floating-point operations as lambdify's ``math`` module, and raises
:class:`NotEvaluable` for a node it does not know, so the caller can fall back to lambdify.

>>> import sympy
>>> x, y = sympy.symbols("x y")
>>> float_values([x ** 2 + sympy.sin(y) / 2, sympy.sqrt(x)], {x: 4.0, y: 0.0})
[16.0, 2.0]
>>> float_values([sympy.Piecewise((x, x > 0), (0, True))], {x: 1.0})
Traceback (most recent call last):
...
lkverify.symbolic.floateval.NotEvaluable: Piecewise
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import sympy

__all__ = ["NotEvaluable", "float_values"]


class NotEvaluable(Exception):
    """A node :func:`float_values` does not evaluate (the caller falls back to ``sympy.lambdify``)."""


def _sign(x):
    return math.copysign(1.0, x) if x != 0 else 0.0


#: SymPy function → its ``math`` counterpart (lambdify's ``math`` module prints these)
_FUNCTIONS = {
    sympy.sin: math.sin, sympy.cos: math.cos, sympy.tan: math.tan, sympy.exp: math.exp,
    sympy.asin: math.asin, sympy.acos: math.acos, sympy.atan: math.atan, sympy.atan2: math.atan2,
    sympy.sinh: math.sinh, sympy.cosh: math.cosh, sympy.tanh: math.tanh, sympy.Abs: abs,
    sympy.floor: math.floor, sympy.ceiling: math.ceil, sympy.sign: _sign,
    sympy.Max: max, sympy.Min: min, sympy.log: math.log,   # SymPy writes log(x, b) as log(x)/log(b)
}


def _power(base, exp):
    if isinstance(base, float) and base < 0 and not float(exp).is_integer():
        raise ValueError("math domain error")   # as math.pow and math.sqrt (lambdify's printing) raise
    return base ** exp


def float_values(exprs: Sequence, env: Mapping) -> list:
    """The values of ``exprs`` with the symbols of ``env`` (symbol → float) substituted.

    Raises
    ------
    NotEvaluable
        A node that is not a number, a symbol of ``env``, a sum, product or power, or a function of
        :data:`_FUNCTIONS`.
    ValueError
        A real power of a negative number, a logarithm of a nonpositive one (as ``math`` raises).
    """
    memo: dict = dict(env)

    def value(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if e.is_Number or isinstance(e, sympy.NumberSymbol):
            out = float(e)
        elif e.is_Symbol:
            raise NotEvaluable(f"the symbol {e} has no value")
        elif e.is_Add:
            out = math.fsum(value(a) for a in e.args)
        elif e.is_Mul:
            out = 1.0
            for a in e.args:
                out = out * value(a)
        elif e.is_Pow:
            b, x = e.args
            if x == sympy.S.Half:
                out = math.sqrt(value(b))
            else:
                out = _power(value(b), int(x) if x.is_Integer else value(x))
        elif e.func in _FUNCTIONS:
            out = _FUNCTIONS[e.func](*[value(a) for a in e.args])
        else:
            raise NotEvaluable(type(e).__name__)
        memo[e] = out
        return out

    return [value(sympy.sympify(e)) for e in exprs]
