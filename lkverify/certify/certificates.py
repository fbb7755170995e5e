"""Polynomial inequalities proved by explicit certificates (a Positivstellensatz-style identity).

A claim ``P ≥ 0`` under hypotheses ``hⱼ ≥ 0`` and equalities ``e = 0`` is proved by a certificate

    P ≡ Σ cₖ·Π(hypotheses)·qₖ² + Σ mₗ·eₗ        (cₖ constants decided ≥ 0, qₖ, mₗ polynomials),

checked by expanding the difference to 0 (SymPy, exact; the constants may hold radicals such as
√3).  A step whose certificate does not match is refuted when a rational point satisfying the
hypotheses with ``P < 0`` is found (screened in floats, confirmed exactly), else left ``undecided``.

Examples
--------
>>> x = sympy.Symbol("x", real=True)
>>> inequality_step("x ≥ 0 ⇒ x³ ≥ 0", x**3, [(1, [x], x)], hyps=[x], text="x³ = x·x²").status.value
'exact'
"""

from __future__ import annotations

import itertools

import numpy as np
import sympy

from ..report.results import Result
from ..status import Status

__all__ = ["inequality_step"]


def _nonneg_const(c) -> bool:
    c = sympy.nsimplify(sympy.sympify(c))
    return bool(c.is_number and c.is_real and (c.is_nonnegative or c == 0))


def _witness(claim, hyps, eqs, syms):
    """A rational point with every hypothesis ≥ 0, every equality 0 and ``claim`` < 0 (exact), or None."""
    syms = sorted(syms, key=str)
    if not syms:
        return ({}, claim) if sympy.nsimplify(claim).is_negative else None
    grid = [0, sympy.Rational(1, 2), 1, 2, -1, sympy.Rational(1, 10), sympy.Rational(1, 16)]
    f = sympy.lambdify(syms, [claim, *hyps, *eqs], modules="math")
    pts = itertools.product(grid, repeat=len(syms)) if len(syms) <= 5 else (
        tuple(grid[i] for i in row) for row in np.random.default_rng(0).integers(0, len(grid), (6000, len(syms))))
    for pt in itertools.islice(pts, 20000):
        vals = f(*(float(x) for x in pt))
        if vals[0] < -1e-12 and all(h >= -1e-12 for h in vals[1:1 + len(hyps)]) and all(
                abs(e) < 1e-12 for e in vals[1 + len(hyps):]):
            sub = dict(zip(syms, pt))
            if (sympy.nsimplify(claim.xreplace(sub)).is_negative and all(sympy.nsimplify(h.xreplace(sub)) >= 0 for h in hyps)
                    and all(sympy.simplify(e.xreplace(sub)) == 0 for e in eqs)):
                return sub, sympy.nsimplify(claim.xreplace(sub))
    return None


def inequality_step(name, claim, cert, *, text, hyps=(), eqs=(), cert_eq=()) -> Result:
    """``claim ≥ 0`` from ``hyps`` (each ≥ 0) and ``eqs`` (each = 0), by an exact certificate.

    ``cert`` is a list of ``(c, factors, q)``: the term c·Πfactors·q², c a constant ≥ 0, each factor an
    element of ``hyps``; ``cert_eq`` a list of ``(m, e)``, m any polynomial, e in ``eqs``.

    Examples
    --------
    >>> x, y = sympy.symbols("x y", real=True)
    >>> inequality_step("AM-GM", x**2 + y**2 - 2*x*y, [(1, [], x - y)], text="x² + y² ≥ 2xy").status
    <Status.EXACT: 'exact'>
    >>> r = inequality_step("wrong", x**2 + y**2 - 3*x*y, [(1, [], x - y)], text="x² + y² ≥ 3xy")
    >>> r.status, r.value["witness"]
    (<Status.FAILED: 'failed'>, {'x': '1/2', 'y': '1/2'})
    """
    claim, hyps, eqs = sympy.sympify(claim), [sympy.sympify(h) for h in hyps], [sympy.sympify(e) for e in eqs]
    bad = [c for c, fs, _ in cert if not _nonneg_const(c) or any(not any(sympy.expand(f - h) == 0 for h in hyps)
                                                               for f in fs)]
    total = sum((c * sympy.Mul(*fs) * sympy.sympify(q) ** 2 for c, fs, q in cert), sympy.S.Zero)
    total += sum((m * e for m, e in cert_eq), sympy.S.Zero)
    rest = sympy.expand(claim - total)
    if not bad and rest == 0:
        return Result("bound", name, Status.EXACT, {"claim": sympy.sstr(claim)},
                      f"{text}: the certificate expands to the claim (exact)")
    syms = claim.free_symbols.union(*(h.free_symbols for h in hyps), *(e.free_symbols for e in eqs))
    w = _witness(claim, hyps, eqs, syms)
    why = f"the certificate leaves {sympy.sstr(rest)}" if rest != 0 else f"negative constants {bad}"
    if w is None:
        return Result("bound", name, Status.UNDECIDED, {"claim": sympy.sstr(claim), "rest": sympy.sstr(rest)},
                      f"{text}: not proved ({why}) and no counterexample found")
    return Result("bound", name, Status.FAILED, {"claim": sympy.sstr(claim),
                                                 "witness": {str(k): sympy.sstr(x) for k, x in w[0].items()}},
                  f"{text}: refuted, at {', '.join(f'{k} = {x}' for k, x in w[0].items())} the hypotheses hold and "
                  f"the claim is {sympy.sstr(w[1])} < 0 (exact)")
