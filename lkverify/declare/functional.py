"""Lyapunov–Krasovskii functionals and the integral terms they are built from.

A functional is a sum of labelled scalar :class:`~lkverify.declare.terms.Term` objects:
point terms (``f(t)``, ``γ/2 ωᵀΘω``) and integral terms whose weights may
depend on t and ξ (``∫_{t-τ}^t (λ(ξ+τ-t)+μ) w(x(ξ)) dξ``), products of the two
(``Lᵀ D⁻¹ ∫ f^ν L dξ``) and double integrals with kernel tails
(``∫_0^t ∫_{t-ξ}^∞ ‖G(ζ)‖ dζ w(x(ξ)) dξ``).

>>> import sympy
>>> from lkverify import Parameters, Vector, t, xi
>>> P = Parameters(); tau = P.delay("tau")
>>> x = Vector("x", 1)
>>> window_integral(x(xi)[0] ** 2, tau)
Integral(x_1(xi)**2, (xi, t - tau, t))
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy

from .symbols import t, xi, zeta
from .terms import Term
from ..errors import InputError

__all__ = ["Functional", "window_integral", "memory_integral", "tail_integral", "outer_integrals", "split_outer"]


def outer_integrals(expr) -> list:
    """The integrals of ``expr`` that are not inside another integral, without repeats, in order.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.declare.symbols import t, xi, zeta
    >>> f = sympy.Function("f")
    >>> inner = sympy.Integral(f(zeta), (zeta, 0, xi))
    >>> outer_integrals(f(t) * sympy.Integral(inner, (xi, 0, t)) + sympy.Integral(f(xi), (xi, 0, 1)) ** 2)
    [Integral(f(xi), (xi, 0, 1)), Integral(f(zeta), (zeta, 0, xi), (xi, 0, t))]
    """
    found = []

    def walk(x):
        if isinstance(x, sympy.Integral):
            found.append(x)
            return
        for a in x.args:
            walk(a)

    walk(expr)
    return list(dict.fromkeys(found))


def split_outer(integral: sympy.Integral):
    """``(var, lower, upper, integrand)`` of the outermost integration of ``integral``.

    SymPy merges ``Integral(Integral(f, (ζ, ξ, t)), (ξ, t − τ, t))`` into one integral
    with two limits; the outermost is the last one, and its integrand is the integral
    over the others.

    >>> import sympy
    >>> from lkverify.declare.symbols import t, xi, zeta
    >>> f = sympy.Function("f")
    >>> I = sympy.Integral(sympy.Integral(f(zeta), (zeta, xi, t)), (xi, t - 1, t))
    >>> split_outer(I)
    (xi, t - 1, t, Integral(f(zeta), (zeta, xi, t)))

    Raises
    ------
    InputError
        For an indefinite integral (a limit without both ends).
    """

    limits = integral.limits
    if any(len(limit) != 3 for limit in limits):
        raise InputError(f"expected definite integrals (both limits given), got {integral}")
    var, lo, hi = limits[-1]
    inner = integral.function if len(limits) == 1 else sympy.Integral(integral.function, *limits[:-1])
    return var, lo, hi, inner


def _integrate(integrand, var, lower, upper):
    if isinstance(integrand, sympy.MatrixBase):
        return sympy.ImmutableMatrix(integrand.shape[0], integrand.shape[1],
                                     lambda i, j: sympy.Integral(integrand[i, j], (var, lower, upper)))
    return sympy.Integral(integrand, (var, lower, upper))


def window_integral(integrand, tau, *, weight=1):
    """``∫_{t-τ}^{t} weight · integrand dξ`` (componentwise for a vector integrand).

    ``integrand`` and ``weight`` are written in ``xi`` (and possibly ``t``).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.declare.states import Vector
    >>> tau, x = sympy.Symbol("tau", positive=True), Vector("x", 1)
    >>> window_integral(x(xi)[0] ** 2, tau, weight=xi - t + tau)
    Integral((-t + tau + xi)*x_1(xi)**2, (xi, t - tau, t))
    >>> window_integral(Vector("w", 2)(xi), tau).T      # componentwise
    Matrix([[Integral(w_1(xi), (xi, t - tau, t)), Integral(w_2(xi), (xi, t - tau, t))]])
    """
    if isinstance(integrand, sympy.MatrixBase):
        integrand = integrand * weight
    else:
        integrand = weight * integrand
    return _integrate(integrand, xi, t - tau, t)


def memory_integral(integrand, *, lower=0):
    """``∫_{lower}^{t} integrand dξ``: infinite memory from the initial time (0 by default).

    Examples
    --------
    >>> import sympy
    >>> g, x = sympy.Function("g"), sympy.Function("x")
    >>> memory_integral(g(t - xi) * x(xi))
    Integral(g(t - xi)*x(xi), (xi, 0, t))
    >>> memory_integral(x(xi), lower=-1)
    Integral(x(xi), (xi, -1, t))
    """
    return _integrate(integrand, xi, lower, t)


def tail_integral(kernel_of_zeta, lower):
    """``∫_{lower}^{∞} kernel(ζ) dζ``, e.g. the tail ``∫_{t-ξ}^∞ ‖G(ζ)‖ dζ`` of paper 000's (14).

    Examples
    --------
    >>> import sympy
    >>> g = sympy.Function("g")
    >>> tail_integral(g(zeta), t - xi)
    Integral(g(zeta), (zeta, t - xi, oo))
    >>> tail_integral(sympy.exp(-zeta), 0).doit()
    1
    """
    return _integrate(kernel_of_zeta, zeta, lower, sympy.oo)


class Functional:
    """A Lyapunov–Krasovskii functional V = Σ terms.

    Parameters
    ----------
    terms : sequence of Term
        Scalar terms, each labelled as the paper prints it.
    name : str
        The paper's label, e.g. "(9)".

    Examples
    --------
    >>> import sympy
    >>> from lkverify.declare.states import Vector
    >>> tau, x = sympy.Symbol("tau", positive=True), Vector("x", 1)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2"),
    ...                 Term(window_integral(x(xi)[0] ** 2, tau), text="∫x²")], name="(9)")
    >>> V, [term.text for term in V.terms]
    (Functional('(9)', 2 terms), ['x²/2', '∫x²'])
    >>> V.expr
    x_1(t)**2/2 + Integral(x_1(xi)**2, (xi, t - tau, t))
    """

    def __init__(self, terms: Sequence[Term], *, name: str = ""):
        terms = tuple(Term(t_.expr[0, 0], text=t_.text, latex=t_.latex)
                      if isinstance(t_, Term) and t_.is_vector and t_.shape == (1, 1) else t_ for t_ in terms)
        if not terms:
            raise InputError(f"Functional {name}: expected at least one term")
        for term in terms:
            if not isinstance(term, Term):
                raise InputError(f"Functional {name}: expected Term objects, got {type(term).__name__}")
            if term.is_vector:
                raise InputError(f"Functional {name}: term {term.text!r} is a {term.shape} matrix, expected a scalar")
        self.terms = terms
        self.name = name

    @property
    def expr(self) -> sympy.Expr:
        return sympy.Add(*[term.expr for term in self.terms])

    def __repr__(self) -> str:
        return f"Functional({self.name!r}, {len(self.terms)} terms)"
