"""Hypotheses on the parameters, decided with their margins.

A :class:`Hypothesis` is ``margin > 0`` (or ``≥ 0``); a :class:`MatrixHypothesis` is
``M ≻ 0``.  They follow the exactness policy of :mod:`lkverify.status`: rational margins
and LDLᵀ in fractions are ``exact``; irrational margins, and anything that went through
floating point, are decided by outward-rounded enclosures (:mod:`lkverify.certify.intervals`)
and are at most ``certified``.
"""

from __future__ import annotations

import dataclasses

import sympy
from sympy.core.function import AppliedUndef

from ..declare.parameters import apply_substitution
from ..declare.symbols import t as _t
from ..options import BudgetExceeded, Deadline
from ..report.results import Result
from ..status import Status
from .matrices import matrix_positive_definite
from .intervals import UnsupportedExpression, sign_of

__all__ = ["Hypothesis", "MatrixHypothesis"]


@dataclasses.dataclass(frozen=True)
class Hypothesis:
    """A hypothesis ``margin > 0`` (or ``≥ 0``) on the parameters.

    Parameters
    ----------
    name : str
        As printed, e.g. ``"b*tau < a"``; the margin of ``x < y`` is ``y − x``.
    margin : sympy expression in the parameters
    strict : bool
    reference : str
        The paper's label, e.g. ``"(14)"``.

    Examples
    --------
    >>> import sympy
    >>> mu = sympy.Symbol("mu", positive=True)
    >>> h = Hypothesis("mu > 1", mu - 1)
    >>> h.evaluate({mu: 2}).status.value, h.evaluate({mu: 2}).value
    ('exact', 1)
    >>> h.evaluate({mu: sympy.Rational(1, 2)}).status.value
    'failed'
    """

    name: str
    margin: object
    strict: bool = True
    reference: str = ""

    def evaluate(self, substitution, *, budget: float | None = None) -> Result:
        """Decide ``margin > 0`` (``≥ 0``) at the substituted values.

        ``exact`` when the margin is an exact rational; ``certified`` when its sign is
        decided by an outward-rounded enclosure (irrational margins, and every margin
        that contains a floating-point number, taken at its exact binary value);
        ``failed`` with the margin when it is ≤ 0 (< 0), not real or infinite;
        ``undecided`` when no enclosure separates it from 0 or an integral has no
        closed form.
        """
        ref = f" {self.reference}" if self.reference else ""
        prepared = _prepare(sympy.sympify(self.margin), substitution, budget, f"hypothesis{ref}")
        if isinstance(prepared, str):
            return Result("hypothesis", self.name, Status.UNDECIDED, None, prepared)
        m, floats = prepared
        if m.has(sympy.oo, -sympy.oo, sympy.zoo, sympy.nan):
            return Result("hypothesis", self.name, Status.FAILED, None,
                          f"fails{ref}: the margin {m} is not finite (a divergent integral?)")
        rel = ">" if self.strict else "≥"
        note = _float_note(floats)
        if m.is_Rational:
            status = Status.CERTIFIED if floats else Status.EXACT
            holds = m > 0 or (not self.strict and m == 0)
            how = "" if not floats else note
        else:
            im = sympy.im(m) if m.has(sympy.I) else sympy.S.Zero
            if im != 0:
                s_im = _sign(im)
                if s_im is None or s_im.sign is None:
                    return Result("hypothesis", self.name, Status.UNDECIDED, None,
                                  f"hypothesis{ref}: the margin {m} may not be real; no enclosure decided it")
                return Result("hypothesis", self.name, Status.FAILED, None,
                              f"fails{ref}: the margin {m} is not a real number (its imaginary part is "
                              f"{'positive' if s_im.sign > 0 else 'negative'}); need a real margin {rel} 0")
            sr, symbolic = _sign(m), False
            if sr is None:
                return Result("hypothesis", self.name, Status.UNDECIDED, None,
                              f"hypothesis{ref}: the margin {m} is outside what interval arithmetic encloses")
            if sr.sign is None and not sr.is_zero:
                simpler = _simplified(m, budget)
                if simpler is not None and simpler.is_Rational:
                    m, sr = simpler, _sign(simpler)
                    symbolic = not floats
            if sr.sign is None:
                if sr.is_zero:
                    holds = not self.strict
                else:
                    return Result("hypothesis", self.name, Status.UNDECIDED, m,
                                  f"hypothesis{ref}: margin too close to 0 to decide (enclosure "
                                  f"[{_f(sr.lower)}, {_f(sr.upper)}] at {sr.prec} bits)")
            else:
                holds = sr.sign > 0
            status = Status.EXACT if symbolic else Status.CERTIFIED
            how = " (simplified exactly)" if symbolic else \
                f" (enclosure [{_f(sr.lower)}, {_f(sr.upper)}] at {sr.prec} bits{note})"
        if holds:
            return Result("hypothesis", self.name, status, m, f"holds{ref}: margin {_show(m)} {rel} 0{how}")
        return Result("hypothesis", self.name, Status.FAILED, m, f"fails{ref}: margin {_show(m)}, need {rel} 0{how}")


@dataclasses.dataclass(frozen=True)
class MatrixHypothesis:
    """A hypothesis ``M ≻ 0`` on a matrix built from the parameters (e.g. ΞD + DΞᵀ of paper 000).

    Decided exactly (rational LDLᵀ) when the entries are rational, with arb balls
    otherwise; the margin is a lower bound of λ_min (:func:`lkverify.certify.matrices.matrix_positive_definite`).
    Entries are never rounded or snapped: floating-point entries are taken at their
    exact binary values, and a result that rests on them is at most ``certified``.

    Examples
    --------
    >>> import sympy
    >>> b = sympy.Symbol("b", real=True)
    >>> h = MatrixHypothesis("M", sympy.Matrix([[2, b], [b, 2]]))     # M ≻ 0 iff |b| < 2
    >>> r = h.evaluate({b: sympy.Integer(1)})
    >>> r.status.value, r.value
    ('exact', 1.0)
    >>> h.evaluate({b: sympy.Integer(3)}).status.value
    'failed'
    >>> h.evaluate({b: sympy.sqrt(2)}).status.value          # irrational entries: arb balls
    'certified'
    """

    name: str
    matrix: object
    reference: str = ""

    def evaluate(self, substitution, *, budget: float | None = None) -> Result:
        """Decide ``M ≻ 0`` at the substituted values."""
        ref = f" {self.reference}" if self.reference else ""
        M = sympy.Matrix(self.matrix)
        entries, floats = [], frozenset()
        for x in M:
            prepared = _prepare(sympy.sympify(x), substitution, budget, f"hypothesis{ref}")
            if isinstance(prepared, str):
                return Result("hypothesis", self.name, Status.UNDECIDED, None, prepared)
            entries.append(prepared[0])
            floats |= prepared[1]
        M = sympy.Matrix(M.rows, M.cols, entries)
        if any(x.has(sympy.oo, -sympy.oo, sympy.zoo, sympy.nan) for x in M):
            return Result("hypothesis", self.name, Status.FAILED, None,
                          f"fails{ref}: the matrix has entries that are not finite (a divergent integral?)")
        res = matrix_positive_definite(M, name=self.name, symmetrize=True)
        r = res.to_result("hypothesis")
        status = Status.CERTIFIED if floats and r.status is Status.EXACT else r.status
        return Result("hypothesis", self.name, status, r.value,
                      f"{ref.strip()} {r.detail}{_float_note(floats)}".strip())


def _show(m) -> str:
    return str(m) if m.is_Rational else f"{m} ≈ {float(m):.6g}"


def _simplified(m, budget):
    """``sympy.simplify(m)`` within at most 10 s of the budget, or None."""
    try:
        with Deadline(min(budget, 10.0) if budget else 10.0).enforced():
            return sympy.simplify(m)
    except BudgetExceeded:
        return None


def _float_note(floats) -> str:
    if not floats:
        return ""
    shown = ", ".join(str(f) for f in sorted(floats, key=float)[:3])
    return (f"; the floating-point number(s) {shown} are taken at their exact binary values, so the result is "
            f"certified, never exact")


def _f(q) -> str:
    return "−∞/∞" if q is None else f"{float(q):.6g}"


def _sign(m):
    try:
        return sign_of(m)
    except UnsupportedExpression:
        return None


def _exact_floats(expr):
    """Every SymPy Float replaced by the Rational of its exact binary value (no rounding, no snapping)."""
    floats = expr.atoms(sympy.Float)
    if not floats:
        return expr, frozenset()
    return expr.xreplace({f: sympy.Rational(f) for f in floats}), frozenset(floats)


def _prepare(expr, substitution, budget, what: str):
    """Substitute the values into a hypothesis expression and evaluate its integrals.

    Returns ``(value, floats)`` or a string: the reason it cannot be decided.
    """
    expr, floats = _exact_floats(expr)
    exact_sub = {}
    for key, value in substitution.items():
        if isinstance(value, sympy.Basic) and value.atoms(sympy.Float):
            value, more = _exact_floats(value)
            floats = floats | more
        exact_sub[key] = value
    m = sympy.sympify(apply_substitution(expr, exact_sub))
    states = sorted({str(a) for a in m.atoms(AppliedUndef)})
    free = m.free_symbols
    if states or _t in free:
        on = ", ".join(states) if states else "t"
        return (f"{what} depends on {on}: a hypothesis is a condition on constant parameters; "
                f"state it without states and time (a condition on a state is a bound step)")
    if free:
        return (f"{what} depends on symbols without a value: {', '.join(sorted(map(str, free)))}; give them "
                f"default values in the proof file or values at the command line")
    if m.has(sympy.Integral):
        try:
            with Deadline(budget).enforced():
                m = m.replace(lambda e: isinstance(e, sympy.Integral), lambda e: e.doit())
        except BudgetExceeded:
            return f"{what}: the integrals in the margin were not evaluated within the budget"
        if m.has(sympy.Integral):
            left = next(iter(m.atoms(sympy.Integral)))
            return f"{what}: SymPy finds no closed form for {left}, so the margin is not decided"
    m, more = _exact_floats(m)
    return m, floats | more
