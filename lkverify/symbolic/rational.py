"""Exact identities between rational functions (vectors and matrices of them), decided in ℚ(symbols).

Each entry of the difference is decided by the field arithmetic of ``sympy.field`` (an exact decision
for rational functions with rational coefficients; with radicals or I the numerator of ``together`` is
expanded): ``exact`` when every entry is 0, ``failed`` otherwise, with the first nonzero entry and its
value at a rational witness (evaluated exactly).  The identity engine for rational (not polynomial)
claims, next to :mod:`lkverify.symbolic.polynomial`; used by paper 003's kinematics (rational in σ).

Examples
--------
>>> s = sympy.Symbol("s", real=True)
>>> matrix_identity("a", sympy.Matrix([1 / (1 + s**2)]), sympy.Matrix([1 / (s**2 + 1)]), text="same").status.value
'exact'
>>> matrix_identity("b", sympy.Matrix([1 / (1 + s**2)]), sympy.Matrix([1 / (1 + s**2) + sympy.Rational(1, 10**30)]),
...                 text="a tiny difference").status.value
'failed'
"""

from __future__ import annotations

import sympy

from ..report.results import Result
from ..status import Status

__all__ = ["matrix_identity", "nonzero_witness", "rational_is_zero"]

_WITNESS = (sympy.Rational(1, 2), sympy.Rational(-1, 3), sympy.Rational(1, 5), sympy.Rational(2, 7),
            sympy.Rational(-3, 4), sympy.Rational(1, 6), sympy.Rational(3, 5), sympy.Rational(-2, 9))


def nonzero_witness(expr: sympy.Expr):
    """A rational point (a fixed sequence of rationals, in symbol order) where ``expr`` ≠ 0, or ``None``."""
    syms = sorted(expr.free_symbols, key=str)
    for shift in range(8):
        point = {s: _WITNESS[(k + shift) % len(_WITNESS)] * (1 + shift) for k, s in enumerate(syms)}
        val = sympy.cancel(expr.xreplace(point))
        if val != 0:
            return point, val
    return None


def rational_is_zero(e) -> bool:
    """Exactly: ``e`` is 0 in the field of rational functions ℚ(symbols) (else: the numerator of
    ``together(e)`` expands to 0, e.g. with I or radicals); the denominators here never vanish."""
    e = sympy.sympify(e)
    syms = sorted(e.free_symbols, key=str)
    if syms:
        try:
            field = sympy.field(syms, sympy.QQ)[0]
            return field.from_expr(e) == 0
        except (sympy.polys.polyerrors.PolynomialError, ValueError, TypeError, sympy.CoercionFailed):
            pass
    return sympy.expand(sympy.fraction(sympy.together(e))[0]) == 0


def matrix_identity(name: str, lhs, rhs, *, text: str, kind: str = "identity") -> Result:
    """``lhs == rhs`` (matrices or scalars) decided exactly; a failed result names the entries that differ.

    Examples
    --------
    >>> s1 = sympy.Symbol("σ1", real=True)
    >>> matrix_identity("x", sympy.Matrix([s1 ** 2]), sympy.Matrix([s1 * s1]), text="σ1² = σ1σ1").status
    <Status.EXACT: 'exact'>
    >>> r = matrix_identity("x", sympy.Matrix([2 * s1]), sympy.Matrix([s1]), text="2σ1 = σ1")
    >>> r.status, r.value["differences"]
    (<Status.FAILED: 'failed'>, {'(1, 1)': 'σ1'})
    """
    L = lhs if hasattr(lhs, "shape") else sympy.Matrix([lhs])
    R = rhs if hasattr(rhs, "shape") else sympy.Matrix([rhs])
    diff = L - R
    keys = [(i, j) for i in range(diff.rows) for j in range(diff.cols) if not rational_is_zero(diff[i, j])]
    bad = {f"({i + 1}, {j + 1})": diff[i, j] for i, j in keys}
    if not bad:
        return Result(kind, name, Status.EXACT, None, f"{text}: every entry of the difference cancels to 0 (exact)")
    first_key = next(iter(bad))
    first = bad[first_key] = sympy.factor(sympy.cancel(bad[first_key]))
    w = nonzero_witness(first)
    where = (f"; at {', '.join(f'{k} = {v}' for k, v in w[0].items())} entry {first_key} of the difference is "
             f"{w[1]} (exact)") if w else ""
    shown = {k: sympy.sstr(v) for k, v in bad.items() if k == first_key}
    return Result(kind, name, Status.FAILED, {"differences": shown},
                  f"{text}: refuted, lhs − rhs ≠ 0 in {len(bad)} entr{'y' if len(bad) == 1 else 'ies'}: "
                  f"{first_key}: {sympy.sstr(first)}{where}")
