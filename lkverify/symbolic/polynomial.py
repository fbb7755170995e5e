"""Polynomial identities decided in ℚ[x]: the fast path of lkverify's one identity engine.

An identity whose two sides are polynomials in plain symbols (state values, reference signals,
parameters) is decided by sparse polynomial arithmetic over the rationals (``sympy.polys.rings``):
the difference is expanded once; zero means ``exact`` for every value of every symbol (so also on
any constraint manifold), a non-zero difference is shown term by term and refuted at an exact
rational witness (unit vectors and a triad from a rational Cayley rotation, so the witness lies
on the state manifold).  Values that went through floating point are never ``exact``.

:func:`~lkverify.symbolic.identity.check_identity` (every ``IdentityClaim`` and
``DerivativeClaim``) tries :func:`zero_difference` first, on the canonical atoms of its terms
and without the constraints: a zero there proves the identity before any Gröbner reduction.  The
closed loops of paper 004 (no delay; identities that hold for every state value, not only on
‖sᵢ‖ = 1) call :func:`compare_polynomials` directly, with V̇ formed by :func:`time_derivative`.

Examples
--------
>>> x, y = sympy.symbols("x y", real=True)
>>> str(compare_polynomials("square", [("(x+y)²", (x + y) ** 2)], [("x²+2xy+y²", x**2 + 2*x*y + y**2)]).status)
'exact'
>>> r = compare_polynomials("square", [("(x+y)²", (x + y) ** 2)], [("x²+y²", x**2 + y**2)])
>>> str(r.status), r.value["residue"]
('failed', '2*x*y')
"""

from __future__ import annotations

import random

import sympy
from sympy.core.function import AppliedUndef

from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

from ..declare.symbols import t
from ..errors import UnsupportedInput
from ..report.results import Result
from ..status import Status

__all__ = ["cayley", "compare_polynomials", "plain", "poly_ring", "time_derivative", "to_ring", "witness_point",
           "zero_difference"]


def _replacement(expr) -> dict:
    """x(t) → x, d/dt x(t) → x_dot; a value at another argument (x(t − τ), x(0)) is refused.

    Plain symbols name a function's value at t only: x(t) and x(t − τ) would become one symbol
    and a false identity between them would be proved.
    """
    rep = {}
    for d in expr.atoms(sympy.Derivative):
        f = d.expr
        if isinstance(f, AppliedUndef):
            if f.args != (t,) or d.variables != (t,):
                raise UnsupportedInput(f"polynomial identities: expected d/dt of a function of t, got {d}; an identity "
                                       f"with delayed or other arguments goes through check_identity")
            rep[d] = sympy.Symbol(f"{f.func.__name__}_dot", real=True)
    for f in expr.atoms(AppliedUndef):
        if f.args != (t,):
            raise UnsupportedInput(f"polynomial identities: expected functions of t only, got {f}; an identity "
                                   f"with delayed or other arguments goes through check_identity")
        rep.setdefault(f, sympy.Symbol(f.func.__name__, real=True))
    return rep


def plain(expr):
    """``expr`` with every x(t) → x and ẋ(t) of a coefficient → x_dot (symbols).

    Examples
    --------
    >>> from lkverify import t
    >>> f = sympy.Function("f", real=True)
    >>> plain(f(t) ** 2 + f(t).diff(t))
    f**2 + f_dot
    >>> plain(f(t) - f(t - 1))
    Traceback (most recent call last):
        ...
    lkverify.errors.UnsupportedInput: polynomial identities: expected functions of t only, got f(t - 1); an identity with delayed or other arguments goes through check_identity
    """
    expr = sympy.sympify(expr)
    rep = _replacement(expr)
    derivs = {k: v for k, v in rep.items() if isinstance(k, sympy.Derivative)}
    return expr.xreplace(derivs).xreplace({k: v for k, v in rep.items() if k not in derivs})


def time_derivative(V, system, substitution=None):
    """V̇ of the scalar ``V`` (an expression in the states at t) along ``system``, in plain symbols.

    Chain rule: Σ ∂V/∂xᵢ ẋᵢ over the state components, plus ∂V/∂(coefficient)·(its derivative)
    for every time-varying coefficient (ω_d(t)); ``substitution`` (parameter values) is applied
    to V and to the right-hand sides first.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    >>> time_derivative(x(t)[0] ** 2, sys)
    -2*x_1**2
    """
    sub = dict(substitution or {})
    Vs = sympy.sympify(V).xreplace(sub) if sub else sympy.sympify(V)
    Vp = plain(Vs)
    total = sympy.Integer(0)
    for state in system.states:
        rhs = system.rhs(state)
        for i, f in enumerate(state.functions):
            x = sympy.Symbol(f.__name__, real=True)
            dV = Vp.diff(x)
            if dV != 0:
                r = rhs[i].xreplace(sub) if sub else rhs[i]
                total += dV * plain(r)
    for d in Vs.atoms(sympy.Derivative):
        if isinstance(d.expr, AppliedUndef) and not any(d.expr.func.__name__ == g.__name__ for s in system.states
                                                        for g in s.functions):
            raise UnsupportedInput(f"time_derivative: V contains {d}, the rate of a coefficient, whose own rate is "
                                   f"not known here; write V without it or differentiate by hand")
    for f in Vs.atoms(AppliedUndef):
        name = f.func.__name__
        if any(name == g.__name__ for s in system.states for g in s.functions):
            continue
        x = sympy.Symbol(name, real=True)
        total += Vp.diff(x) * sympy.Symbol(f"{name}_dot", real=True)
    return total


def _has_float(expr) -> bool:
    return bool(sympy.sympify(expr).atoms(sympy.Float))


def cayley(k):
    """The rational rotation (I − K)⁻¹(I + K) of the rational vector k (K its skew matrix).

    Examples
    --------
    >>> R = cayley([1, 2, 3]); (R.T * R == sympy.eye(3), R.det())
    (True, 1)
    """
    a, b, c = (sympy.Rational(x) for x in k)
    K = sympy.Matrix([[0, -c, b], [c, 0, -a], [-b, a, 0]])
    return (sympy.eye(3) - K).inv() * (sympy.eye(3) + K)


def witness_point(expr, *, seed=0, frame=("s1", "s2", "s3")):
    """An exact rational point for the symbols of ``expr``: the triad s1, s2, s3 from a Cayley rotation,
    every other symbol a small random rational.

    Examples
    --------
    >>> s = sympy.symbols("s1_x s1_y s1_z", real=True); k = sympy.Symbol("k")
    >>> p = witness_point(sum(s) + k)
    >>> sum(p[c] ** 2 for c in s), p[k].is_Rational
    (1, True)
    """
    rng = random.Random(seed)
    R = cayley([sympy.Rational(rng.randint(-4, 4), 5) for _ in range(3)])
    point = {}
    for sym in sorted(sympy.sympify(expr).free_symbols, key=str):
        name = str(sym)
        base, _, axis = name.rpartition("_")
        if base in frame and axis in "xyz" and axis:
            point[sym] = R[("x", "y", "z").index(axis), frame.index(base)]
        else:
            point[sym] = sympy.Rational(rng.randint(-9, 9), rng.randint(1, 4))
    return point


def _show(p, n=160):
    """A ring element as text: factored when short, else its first terms."""
    if len(p.terms()) <= 12:
        s = str(sympy.factor(p.as_expr()))
    else:
        head = p.ring.from_dict(dict(p.terms()[:12]))
        s = str(head.as_expr()) + f" + … ({len(p.terms())} terms)"
    return s if len(s) <= n else s[: n - 1] + "…"


def poly_ring(exprs, extra=()):
    """The polynomial ring QQ[symbols of ``exprs``] (sparse, fast arithmetic).

    Examples
    --------
    >>> x, y = sympy.symbols("x y")
    >>> R = poly_ring([x * y + 1]); R.symbols, to_ring(R, (x + 1) * y) == to_ring(R, x * y + y)
    ((x, y), True)
    """
    syms = set(extra)
    for x in exprs:
        if isinstance(x, PolyElement):
            syms |= set(x.ring.symbols)
        else:
            syms |= sympy.sympify(x).free_symbols
    syms = sorted(syms, key=str)
    R, *gens = ring(syms, QQ) if syms else ring([sympy.Symbol("_unused")], QQ)
    return R


def to_ring(R, x):
    """``x`` (an expression or an element of another ring over the same symbols) as an element of R (see :func:`poly_ring`)."""
    if isinstance(x, PolyElement):
        return x if x.ring == R else R.from_expr(x.as_expr())
    return R.from_expr(sympy.sympify(x))


def compare_polynomials(name, printed, derived, *, kind="identity", reference="", R=None):
    """``Σ printed == Σ derived``, exact or refuted, with the term-by-term report.

    Parameters
    ----------
    name : str
    printed, derived : sequence of (label, expression or polynomial)
        Expressions in plain symbols (:func:`plain`, :func:`derivative`) or elements of ``R``.
    reference : str
        What the printed side is ("(2.10) as printed").
    R : polynomial ring, optional
        The ring to compute in (default: the rationals over every symbol that occurs).

    Returns
    -------
    Result
        ``exact`` when the difference is the zero polynomial, ``failed`` with the differing
        terms and an exact witness otherwise, ``undecided`` when floating-point values make a
        non-zero residue inconclusive.

    Examples
    --------
    >>> x, y = sympy.symbols("x y", real=True)
    >>> r = compare_polynomials("(2.9)", [("−x²", -x**2), ("−2xy", -2*x*y)], [("−(x+y)²", -(x + y)**2)])
    >>> str(r.status), r.value["residue"]      # the printed form dropped −y²
    ('failed', 'y**2')
    >>> str(compare_polynomials("root", [("√(1+x²)", sympy.sqrt(1 + x**2))], [("1", 1)]).status)   # not decided here
    'undecided'
    """
    everything = [x for _, x in list(printed) + list(derived)]
    if any(not isinstance(x, PolyElement) and _has_float(x) for x in everything):
        return Result(kind, name, Status.UNDECIDED, None,
                      "floating-point parameter values: an identity is decided only for exact values (pass them as "
                      "text, e.g. --set a=0.1, which is read as 1/10)")
    try:
        R = R or poly_ring(everything)
        printed = [(lab, to_ring(R, x)) for lab, x in printed]
        derived = [(lab, to_ring(R, x)) for lab, x in derived]
    except (ValueError, sympy.CoercionFailed, sympy.PolynomialError) as exc:
        return Result(kind, name, Status.UNDECIDED, None,
                      f"not a polynomial identity (a side is not a polynomial with rational coefficients: {exc}); "
                      f"an identity of other functions goes through check_identity")
    residue = sum((x for _, x in printed), R.zero) - sum((x for _, x in derived), R.zero)
    if residue == 0:
        return Result(kind, name, Status.EXACT, None,
                      f"{reference or 'the printed form'} equals the derivation exactly "
                      f"({' + '.join(lab for lab, _ in printed)})")
    matched, left, unmatched = [], list(derived), []
    for lab, x in printed:
        hit = next((d for d in left if x == d[1]), None)
        if hit is not None:
            matched.append(lab)
            left.remove(hit)
        else:
            unmatched.append((lab, x))
    used = sympy.Matrix(list(R.symbols))  # every generator gets a value (those absent from the residue are ignored)
    for seed in range(5):  # a non-zero polynomial vanishes at few rational points
        point = witness_point(used, seed=seed)
        value = residue.evaluate([(g, point[sym]) for g, sym in zip(R.gens, R.symbols)])
        if value != 0:
            break
    point = {sym: point[sym] for g, sym in zip(R.gens, R.symbols) if residue.degree(g) > 0}  # report what it uses
    terms = [{"printed": lab, "value": _show(x)} for lab, x in unmatched]
    terms += [{"derived": lab, "value": _show(x)} for lab, x in left]
    detail = (f"{reference or 'the printed form'} differs from the derivation: confirmed {', '.join(matched) or 'none'}; "
              f"not in the derivation: {', '.join(lab for lab, _ in unmatched) or 'none'}; derived but not printed: "
              f"{', '.join(lab for lab, _ in left) or 'none'}; printed − derived = {_show(residue)}"
              f" (= {value} ≠ 0 at an exact rational witness)")
    status = Status.FAILED if value != 0 else Status.UNDECIDED
    return Result(kind, name, status, {"terms": terms, "residue": _show(residue, 400), "witness_value": str(value),
                                       "witness": {str(k): str(v) for k, v in point.items()}}, detail)


def zero_difference(claimed, reference) -> bool:
    """True when Σ claimed − Σ reference is the zero polynomial over ℚ in the symbols that occur.

    The expressions must be polynomial in their free symbols with rational coefficients (e.g. the
    canonical atoms of :class:`~lkverify.symbolic.canonical.Canonicalizer`); anything else (a float,
    a non-polynomial term) gives False, never a wrong True.

    Examples
    --------
    >>> x, y = sympy.symbols("x y")
    >>> zero_difference([(x - y) * (x + y)], [x**2, -y**2]), zero_difference([x * y], [y * x + sympy.Rational(1, 10**30)])
    (True, False)
    >>> zero_difference([sympy.sqrt(x)], [sympy.sqrt(x)]), zero_difference([x * 1.0], [x])   # not polynomials: no claim
    (False, False)
    """
    exprs = [sympy.sympify(e) for e in (*claimed, *reference)]
    if any(_has_float(e) for e in exprs):
        return False
    try:
        R = poly_ring(exprs)
        total = sum((to_ring(R, e) for e in exprs[: len(claimed)]), R.zero) - \
            sum((to_ring(R, e) for e in exprs[len(claimed):]), R.zero)
    except (sympy.polys.polyerrors.PolynomialError, ValueError, TypeError, sympy.CoercionFailed):
        return False
    return total == 0
