"""States: vector-valued functions of time, and the constraints they carry.

A state ``x`` of dimension n is n undefined SymPy functions; ``x(t)``,
``x(t - tau)`` and ``x(xi)`` are its values now, delayed and inside an
integral.  Unit vectors (‖s‖ = 1) and orthonormal right-handed frames carry
their constraints, which identity proofs may use.

>>> from lkverify.declare.symbols import t
>>> s = UnitVector("s")
>>> s(t).T
Matrix([[s_x(t), s_y(t), s_z(t)]])
>>> s.constraint_polynomials(t)
[s_x(t)**2 + s_y(t)**2 + s_z(t)**2 - 1]
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import sympy
from .vectors import cross, dot
from ..errors import InputError

__all__ = ["Vector", "UnitVector", "Frame"]

_AXES = ("x", "y", "z")


def _component_names(name: str, dim: int) -> list[str]:
    if dim == 3:
        return [f"{name}_{a}" for a in _AXES]
    return [f"{name}_{i + 1}" for i in range(dim)]


class Vector:
    """A vector-valued function of time, x : R → Rⁿ.

    Parameters
    ----------
    name : str
        A Python identifier; component functions are ``name_x, name_y, name_z``
        for n = 3 and ``name_1 … name_n`` otherwise.
    dim : int, default 3
    latex : str, optional
        How the state is typeset (``r"\\omega"``); defaults to ``name``.
    text : str, optional
        How the state is printed in plain text (``"ω"``); defaults to ``name``.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.declare.symbols import t
    >>> tau = sympy.Symbol("tau", positive=True)
    >>> Vector("omega", text="ω")(t - tau).T
    Matrix([[omega_x(t - tau), omega_y(t - tau), omega_z(t - tau)]])
    >>> Vector("x", 2).constraint_polynomials(t)        # a plain vector is unconstrained
    []
    >>> Vector("2x")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: state name must be an identifier, got '2x'
    """

    unit = False
    frame = None

    def __init__(self, name: str, dim: int = 3, *, latex: str | None = None, text: str | None = None):
        if not isinstance(name, str) or not name.isidentifier():
            raise InputError(f"state name must be an identifier, got {name!r}")
        if not isinstance(dim, int) or dim < 1:
            raise InputError(f"state {name}: dimension must be a positive integer, got {dim!r}")
        self.name = name
        self.dim = dim
        self.latex = latex or name
        self.text = text or name
        self.functions = tuple(sympy.Function(c, real=True) for c in _component_names(name, dim))

    def __call__(self, time) -> sympy.Matrix:
        """The column of component values at ``time`` (``t``, ``t - tau``, ``xi`` …)."""
        time = sympy.sympify(time)
        return sympy.Matrix([f(time) for f in self.functions])

    at = __call__

    def constraint_polynomials(self, time) -> list[sympy.Expr]:
        """Polynomials in the components at ``time`` that vanish on the manifold."""
        return []

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}, dim={self.dim})"


class UnitVector(Vector):
    """A unit vector function of time, ‖s(t)‖ = 1 for every t (e.g. Poisson's equation).

    Examples
    --------
    >>> from lkverify.declare.symbols import t, xi
    >>> s = UnitVector("s")
    >>> s.unit, s.constraint_polynomials(xi)
    (True, [s_x(xi)**2 + s_y(xi)**2 + s_z(xi)**2 - 1])
    """

    unit = True

    def constraint_polynomials(self, time) -> list[sympy.Expr]:
        v = self(time)
        return [dot(v, v) - 1]


class Frame:
    """An orthonormal right-handed triad of unit-vector states (s1, s2, s3).

    The constraints are sᵢ·sⱼ = δᵢⱼ and s3 = s1 × s2.

    Examples
    --------
    >>> from lkverify.declare.symbols import t
    >>> F = Frame()
    >>> [v.name for v in F], F[2].frame is F
    (['s1', 's2', 's3'], True)
    >>> polys = F.constraint_polynomials(t)
    >>> len(polys), polys[1]                # 6 products sᵢ·sⱼ − δᵢⱼ, then the 3 components of s3 − s1 × s2
    (9, s1_x(t)*s2_x(t) + s1_y(t)*s2_y(t) + s1_z(t)*s2_z(t))
    >>> Frame(["a", "b"])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: a frame has three vectors, got names ['a', 'b']
    """

    def __init__(self, names: Sequence[str] = ("s1", "s2", "s3"), *, latex: Sequence[str] | None = None):
        if len(names) != 3:
            raise InputError(f"a frame has three vectors, got names {list(names)!r}")
        latex = latex or names
        self.vectors = tuple(UnitVector(n, 3, latex=l) for n, l in zip(names, latex))
        for v in self.vectors:
            v.frame = self

    def __iter__(self):
        return iter(self.vectors)

    def __getitem__(self, i):
        return self.vectors[i]

    def constraint_polynomials(self, time) -> list[sympy.Expr]:
        vs = [v(time) for v in self.vectors]
        polys = [dot(a, b) - (1 if i == j else 0)
                 for (i, a), (j, b) in itertools.combinations_with_replacement(enumerate(vs), 2)]
        polys += list(vs[2] - cross(vs[0], vs[1]))
        return polys

