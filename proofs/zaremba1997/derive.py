"""Exact derivations for paper 004: V̇ along a closed loop, and printed formulas compared term by term.

The closed loops of paper 004 have no delay and no constraint is needed by its identities
(they hold for every value of the states, not only on ‖sᵢ‖ = 1), so an identity is decided
here by polynomial arithmetic on the state values: every ``x(t)`` and every ``ω_d(t)``,
``ω̇_d(t)`` becomes a plain symbol, V̇ = Σ ∂V/∂xᵢ·ẋᵢ + Σ ∂V/∂ω_d·ω̇_d is formed and the
difference with the printed formula is expanded.  Zero means ``exact`` (for every state,
every reference motion ω_d(t) and the parameter values of the run, which may themselves be
symbols).  A non-zero difference is shown term by term — which printed terms the derivation
confirms, which it does not, and the residue — and refuted at an exact rational witness
(unit vectors and the triad from a rational Cayley rotation, so the witness lies on the
state manifold).  Values that went through floating point are never ``exact``: such a
check is ``undecided``.

These are the same System objects the simulator integrates (:mod:`.example`).
"""

from __future__ import annotations

import random

import sympy
from sympy.core.function import AppliedUndef

from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

from lkverify import Result, Status

__all__ = ["plain", "derivative", "compare", "cayley", "witness_point", "poly_ring", "to_ring"]


def _replacement(expr) -> dict:
    rep = {}
    for d in expr.atoms(sympy.Derivative):
        f = d.expr
        if isinstance(f, AppliedUndef):
            rep[d] = sympy.Symbol(f"{f.func.__name__}_dot", real=True)
    for f in expr.atoms(AppliedUndef):
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
    """
    expr = sympy.sympify(expr)
    rep = _replacement(expr)
    derivs = {k: v for k, v in rep.items() if isinstance(k, sympy.Derivative)}
    return expr.xreplace(derivs).xreplace({k: v for k, v in rep.items() if k not in derivs})


def derivative(V, system, substitution=None):
    """V̇ of the scalar ``V`` (an expression in the states at t) along ``system``, in plain symbols.

    Chain rule: Σ ∂V/∂xᵢ ẋᵢ over the state components, plus ∂V/∂(coefficient)·(its derivative)
    for every time-varying coefficient (ω_d(t)); ``substitution`` (parameter values) is applied
    to V and to the right-hand sides first.
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
    every other symbol a small random rational."""
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
    """The polynomial ring QQ[symbols of ``exprs``] (sparse, fast arithmetic), and the ring's generators by symbol."""
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
    """``x`` (an expression or an element of another ring over the same symbols) as an element of R."""
    if isinstance(x, PolyElement):
        return x if x.ring == R else R.from_expr(x.as_expr())
    return R.from_expr(sympy.sympify(x))


def compare(name, printed, derived, *, kind="identity", reference="", R=None):
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
    """
    everything = [x for _, x in list(printed) + list(derived)]
    if any(not isinstance(x, PolyElement) and _has_float(x) for x in everything):
        return Result(kind, name, Status.UNDECIDED, None,
                      "floating-point parameter values: an identity is decided only for exact values (pass them as "
                      "text, e.g. --set a=0.1, which is read as 1/10)")
    R = R or poly_ring(everything)
    printed = [(lab, to_ring(R, x)) for lab, x in printed]
    derived = [(lab, to_ring(R, x)) for lab, x in derived]
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
