"""Vector algebra on SymPy column matrices: the notation of the papers.

>>> import sympy
>>> from lkverify.declare.vectors import cross, dot, norm_squared
>>> e1, e2 = sympy.Matrix([1, 0, 0]), sympy.Matrix([0, 1, 0])
>>> cross(e1, e2).T
Matrix([[0, 0, 1]])
>>> dot(e1, e2), norm_squared(e1 + e2)
(0, 2)
"""

from __future__ import annotations

import sympy
from ..errors import InputError

__all__ = ["as_column", "cross", "dot", "norm", "norm_squared", "norm_power", "quad"]


def as_column(v) -> sympy.Matrix:
    """Return ``v`` as a mutable SymPy column matrix (accepts lists and matrices)."""
    m = sympy.Matrix(v)
    if m.shape[1] != 1:
        if m.shape[0] == 1:
            return m.T
        raise InputError(f"expected a vector (n x 1 column), got a {m.shape[0]}x{m.shape[1]} matrix")
    return m


def cross(u, v) -> sympy.Matrix:
    """The cross product u × v of two 3-vectors.

    Examples
    --------
    >>> cross([1, 0, 0], [0, 1, 0]).T
    Matrix([[0, 0, 1]])
    >>> cross([1, 0], [0, 1])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: cross product needs two 3-vectors, got shapes (2, 1) and (2, 1)
    """
    u, v = as_column(u), as_column(v)
    if u.shape != (3, 1) or v.shape != (3, 1):
        raise InputError(f"cross product needs two 3-vectors, got shapes {u.shape} and {v.shape}")
    return u.cross(v)


def dot(u, v) -> sympy.Expr:
    """The scalar product uᵀv.

    Examples
    --------
    >>> dot([1, 2, 3], [4, 5, 6])
    32
    >>> dot([1, 2], [1, 2, 3])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: dot product of vectors of shapes (2, 1) and (3, 1)
    """
    u, v = as_column(u), as_column(v)
    if u.shape != v.shape:
        raise InputError(f"dot product of vectors of shapes {u.shape} and {v.shape}")
    return sum((a * b for a, b in zip(u, v)), sympy.S.Zero)


def quad(u, M, v=None) -> sympy.Expr:
    """The bilinear form uᵀ M v (v defaults to u).

    Examples
    --------
    >>> import sympy
    >>> quad([1, 2], sympy.diag(3, 5))                  # 1·3·1 + 2·5·2
    23
    >>> quad([1, 0], [[1, 2], [3, 4]], [0, 1])          # the (1, 2) entry
    2
    """
    u = as_column(u)
    v = u if v is None else as_column(v)
    return (u.T * sympy.Matrix(M) * v)[0, 0]


def norm_squared(u) -> sympy.Expr:
    """‖u‖², a polynomial in the components.

    Examples
    --------
    >>> from lkverify.declare.states import Vector
    >>> from lkverify.declare.symbols import t
    >>> norm_squared(Vector("w")(t))
    w_x(t)**2 + w_y(t)**2 + w_z(t)**2
    """
    return dot(u, u)


def norm(u) -> sympy.Expr:
    """The Euclidean norm ‖u‖ = (‖u‖²)^(1/2).

    Examples
    --------
    >>> norm([3, 4]), norm([1, 1])
    (5, sqrt(2))
    """
    return sympy.sqrt(norm_squared(u))


def norm_power(u, p) -> sympy.Expr:
    """‖u‖^p written as (‖u‖²)^(p/2), the one form lkverify uses for norm powers.

    Writing every norm power through this function keeps printed and derived
    expressions structurally comparable.

    Examples
    --------
    >>> import sympy
    >>> norm_power([3, 4], 3)
    125
    >>> a, b = sympy.symbols("a b", real=True)
    >>> norm_power([a, b], sympy.Symbol("mu") - 1)
    (a**2 + b**2)**(mu/2 - 1/2)
    """
    return sympy.Pow(norm_squared(u), sympy.sympify(p) / 2)
