"""The saturation SC(x, a_m) of (11): components bounded by a_m, direction kept, inactive set.

Text: "for vectors x, y and a parameter a_m > 0 introduce y = SC(x, a_m) with the algorithmic
definition q = max|x_i|; if q > a_m then y_i = a_m x_i/q.  This function bounds all components of
x in modulus by a_m but keeps the proportionality between them."  (The extracted text has no
``else`` branch; y = x when q ≤ a_m is the only reading under which SC is the identity on small
x, as (11) = (10) there requires.)  In closed form SC(x, a_m) = c x, c = a_m/max(a_m, q).

Checked for a saturation function ``sc(x, a_m)`` (the catalogued :func:`~.equations.SC`, or any
other, e.g. a mutation), at the run's a_m:

1. a search for exact rational witnesses (sc evaluated exactly) against each property: the
   bound max_i|y_i| ≤ a_m, the direction (y × x = 0, y·x > 0 for x ≠ 0), the inactive set
   (y = x when q ≤ a_m) and the active one (max_i|y_i| = a_m when q > a_m); a witness refutes;
2. a proof by cases over all of ℝ³ (exact): x = 0; otherwise pick j with |x_j| = q and signs
   s_i, write |x_j| = m, |x_i| = m/(1 + e_i) (e_i ≥ 0), and m = a_m + d (d > 0, active) or
   m = a_m/(1 + d) (d ≥ 0, inactive) — 3·8·2 cases that cover ℝ³ \\ {0}.  In each case every
   Max, Min and Abs of sc is resolved by an exact sign decision (the dominant argument's
   differences are nonnegative rational functions of the positive case variables), then each
   property is an exact sign or zero decision.  A max the signs do not decide is ``undecided``.
"""

from __future__ import annotations

import functools
import itertools

import sympy

from lkverify import Check, Result, Status

from .equations import PAPER, P, SC, saturation_factor

__all__ = ["saturation", "saturation_results", "resolve_extrema", "WITNESSES"]

_R = sympy.Rational
#: rational test points (times a_m): inside, on and outside the cube q ≤ a_m, ties, zeros, all signs
WITNESSES = [(0, 0, 0), (_R(1, 2), _R(-1, 3), _R(1, 4)), (1, -1, 1), (2, 1, 0), (3, -1, 2), (-5, _R(1, 2), _R(-7, 3)),
             (_R(3, 2), _R(3, 2), -1), (0, 0, -4), (_R(9, 10), 2, _R(-1, 10)), (-1, _R(1, 3), _R(6, 5))]


class _Undecided(Exception):
    pass


@functools.lru_cache(maxsize=4096)
def _nonneg(e) -> bool:
    """e ≥ 0 decided from the assumptions on the case variables (raises ``_Undecided``); cached: the 8
    sign patterns of a case repeat the same comparisons."""
    e = sympy.sympify(e)
    if e.is_nonnegative:
        return True
    e = sympy.factor(sympy.together(e))
    if e == 0 or e.is_nonnegative:
        return True
    if e.is_negative:
        return False
    raise _Undecided(sympy.sstr(e))


def resolve_extrema(expr):
    """Replace each Max, Min, Abs of ``expr`` by the argument the signs of its case variables select.

    Raises ``_Undecided`` when a comparison is not decided by the assumptions (positive symbols).

    Examples
    --------
    >>> m, e = sympy.symbols("m e", positive=True)
    >>> resolve_extrema(sympy.Max(m, m / (1 + e)) + sympy.Abs(-m))
    2*m
    """
    def pick(args, larger):
        for cand in args:
            try:
                if all(_nonneg(cand - o) if larger else _nonneg(o - cand) for o in args if o is not cand):
                    return cand
            except _Undecided:
                continue
        raise _Undecided(f"{'max' if larger else 'min'} of {sympy.sstr(args)}")

    def rec(e):
        if not e.args:
            return e
        args = [rec(a) for a in e.args]
        if isinstance(e, saturation_factor):  # a_m/max(a_m, |x1|, |x2|, |x3|), without building a Max
            am, *x = args
            return am / pick([am, *[xi if _nonneg(xi) else -xi for xi in x]], True)
        if isinstance(e, sympy.Max):
            return pick(args, True)
        if isinstance(e, sympy.Min):
            return pick(args, False)
        if isinstance(e, sympy.Abs):
            return args[0] if _nonneg(args[0]) else -args[0]
        return e.func(*args)

    return rec(sympy.sympify(expr))


def _evaluate(sc, x, am):
    return sympy.Matrix(sc(sympy.Matrix(x), am))


def _witness_rows(sc, am) -> list:
    bad = {"bound": None, "direction": None, "inactive": None, "active": None}
    for w in WITNESSES:
        x = sympy.Matrix(w) * am
        y = _evaluate(sc, x, am).applyfunc(sympy.simplify)
        q = max(abs(v) for v in x)
        top = max(abs(v) for v in y)
        if top > am and bad["bound"] is None:
            bad["bound"] = (x, y, f"max|y_i| = {top} > a_m = {am}")
        cr = x.cross(y)
        if x != sympy.zeros(3, 1) and (cr != sympy.zeros(3, 1) or x.dot(y) <= 0) and bad["direction"] is None:
            bad["direction"] = (x, y, f"x × y = {list(cr)}, x·y = {x.dot(y)}")
        if q <= am and y != x and bad["inactive"] is None:
            bad["inactive"] = (x, y, f"q = {q} ≤ a_m but y ≠ x")
        if q > am and top != am and bad["active"] is None:
            bad["active"] = (x, y, f"q = {q} > a_m but max|y_i| = {top} ≠ a_m")
    return bad


def _case_points(am):
    """The 48 cases: (x, is_active) with positive/nonnegative case variables, covering ℝ³ \\ {0}."""
    d = sympy.Symbol("d", positive=True)
    e = sympy.symbols("e1:3", nonnegative=True)
    for j, signs, active in itertools.product(range(3), itertools.product((1, -1), repeat=3), (True, False)):
        m = am + d if active else am / (1 + d)
        others = iter(e)
        x = [signs[i] * (m if i == j else m / (1 + next(others))) for i in range(3)]
        yield sympy.Matrix(x), active, j


def _proof_rows(sc, am) -> list:
    """The case analysis of the module docstring: one result per property."""
    fails = {"bound": None, "direction": None, "inactive set": None}
    try:
        zero = _evaluate(sc, sympy.zeros(3, 1), am).applyfunc(resolve_extrema)
        if zero != sympy.zeros(3, 1):
            fails["inactive set"] = "SC(0) ≠ 0"
        for x, active, j in _case_points(am):
            y = _evaluate(sc, x, am).applyfunc(resolve_extrema)
            if not all(_nonneg(am - (v if _nonneg(v) else -v)) for v in y):
                fails["bound"] = fails["bound"] or f"case x = {list(x)}"
            if not (all(sympy.cancel(c) == 0 for c in x.cross(y)) and not _nonneg(-x.dot(y))):
                fails["direction"] = fails["direction"] or f"case x = {list(x)}"
            if not active and not all(sympy.cancel(c) == 0 for c in (y - x)):
                fails["inactive set"] = fails["inactive set"] or f"case x = {list(x)}"
            if active and sympy.cancel(y[j] * sympy.sign(x[j]) - am) != 0:
                fails["inactive set"] = fails["inactive set"] or f"active case x = {list(x)}: |y_j| ≠ a_m"
    except _Undecided as exc:
        return [Result("bound", f"SC: {k} (proof by cases)", Status.UNDECIDED, None,
                       f"a comparison is not decided by the signs of the case variables: {exc}") for k in fails]
    text = {"bound": "max_i|SC_i(x)| ≤ a_m for every x ∈ ℝ³",
            "direction": "SC(x) = c x with c > 0 (x × SC(x) = 0, x·SC(x) > 0) for every x ≠ 0",
            "inactive set": "SC(x) = x exactly on the cube max_i|x_i| ≤ a_m (and max|SC_i| = a_m outside it)"}
    return [Result("bound", f"SC: {k} (proof by cases)", Status.FAILED if why else Status.EXACT, None,
                   f"{text[k]}: " + (f"fails in the {why}" if why else
                                     "exact in all 48 cases (argmax j, signs, active/inactive) and at x = 0"))
            for k, why in fails.items()]


def saturation_results(sc=SC, am=None) -> list:
    """Witness search, then the proof by cases, for a saturation function ``sc(x, a_m)``."""
    am = sympy.Symbol("a_m", positive=True) if am is None else sympy.sympify(am)
    found = _witness_rows(sc, am)
    rows = []
    for k, hit in found.items():
        if hit is not None:
            x, y, why = hit
            rows.append(Result("bound", f"SC: {k} (witness)", Status.FAILED, {"x": list(x), "y": list(y)},
                               f"refuted at x = {list(x)}: SC(x, a_m) = {list(y)}, {why} (exact)"))
    if rows:
        return rows
    return _proof_rows(sc, sympy.Symbol("a_m", positive=True)) + [
        Result("bound", "SC: witnesses", Status.EXACT, {"points": len(WITNESSES)},
               f"no violation at {len(WITNESSES)} rational points at a_m = {am} (each evaluated exactly)")]


def _check(v) -> list:
    return saturation_results(SC, v["a_m"])


saturation = Check("saturation", parameters=P, checks=[_check], paper=PAPER, relevant=("a_m",),
                   title="(11): SC(x, a_m) bounds every component by a_m, keeps the direction, is inactive on q ≤ a_m")
