"""Monomials of a polynomial-like expression in chosen symbols, coefficients free of them.

The lowest layer of the certify stage beside :mod:`~lkverify.certify.intervals`: the bound steps
(:mod:`~lkverify.certify.steps`), the conclusions and the parameter boxes
(:mod:`~lkverify.certify.boxes`) all read a right-hand side as {monomial: coefficient}.
"""

from __future__ import annotations

import sympy

__all__ = ["collect_monomials", "split_terms"]


def split_terms(expr, symbols) -> list:
    """[(c, monomial)] for the additive terms of the expanded ``expr``: c free of ``symbols``.

    >>> x, a = sympy.symbols("x a")
    >>> sorted(split_terms(a * x**2 + 3 * x + a, {x}), key=str)
    [(3, x), (a, 1), (a, x**2)]
    """
    out = []
    for term in sympy.Add.make_args(sympy.expand(expr)):
        c, m = sympy.S.One, sympy.S.One
        for f in sympy.Mul.make_args(term):
            if f.free_symbols & symbols:
                m *= f
            else:
                c *= f
        out.append((c, m))
    return out


def collect_monomials(expr, symbols) -> dict:
    """{monomial in ``symbols``: its coefficient} of an expanded expression (coefficients summed).

    >>> x, y, a = sympy.symbols("x y a", nonnegative=True)
    >>> sorted(collect_monomials(3 * x**2 + a * x**2 - y * x + 2, {x, y}).items(), key=str)
    [(1, 2), (x**2, a + 3), (x*y, -1)]
    """
    out: dict = {}
    for c, m in split_terms(expr, set(symbols)):
        m = sympy.powsimp(m, force=True)
        out[m] = out.get(m, sympy.S.Zero) + c
    return {m: c for m, c in out.items() if c != 0}
