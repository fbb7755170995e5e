"""What the catalogue's runners share about one statement: its symbols, the caller's cap, floats.

* :func:`_symbols_of` — the symbols and applied functions a hypothesis, claim or step is written in
  (which values it depends on: the box run's cache key, the float demotion below);
* :func:`_capped`, :func:`_cut_text` — a statement checked under the user's cap, and why it is
  undecided when the cap cut it;
* :func:`_not_exact_if_floats` — an ``exact`` result resting on a float input is ``certified``.

Used by :mod:`~lkverify.catalogue.items` (one point) and :mod:`~lkverify.catalogue.boxrun` (a box).
"""

from __future__ import annotations

import dataclasses

from ..certify.hypotheses import Hypothesis, MatrixHypothesis
from ..certify.steps import BoundClaim
from ..certify.steps.chain import TermwiseBound
from ..memo import Memo
from ..report.results import Result
from ..status import Status

__all__: list = []


def _capped(cap, fn):
    """``(fn(), None)`` under the caller's cap; ``(None, "before" | "during")`` when the cap cut it.

    The cap is checked before ``fn`` and enforced inside it (``SIGALRM`` in the main thread).

    >>> from lkverify.options import Deadline
    >>> _capped(Deadline(None, cap=True), lambda: 1)
    (1, None)
    """
    from ..options import BudgetExceeded

    if cap.seconds is None:
        return fn(), None
    if cap.expired:
        return None, "before"
    try:
        with cap.enforced():
            return fn(), None
    except BudgetExceeded:
        return None, "during"


def _cut_text(cap, how: str, what: str = "step") -> str:
    """Why a statement is undecided: the caller's budget was spent before or during it."""
    if how == "before":
        return f"the budget was spent before this {what} (time budget of {cap.seconds:g} s)"
    return f"the budget was spent during this {what} (time budget of {cap.seconds:g} s); raise --budget to finish"


def _checked_rows(fns, values, cap, what: str = "check", say=None) -> list:
    """The rows of every ``fn(values)`` under the cap; a call the cap cuts is one ``undecided`` row
    ("{what} k of n"), never missing."""
    out = []
    for k, fn in enumerate(fns):
        if say is not None:
            say(f"{what} {k + 1}/{len(fns)}")
        got, how = _capped(cap, lambda: fn(values))
        out += got if not how else [Result("bound", f"{what} {k + 1} of {len(fns)}", Status.UNDECIDED, None,
                                           _cut_text(cap, how, "check"))]
    return out


#: statement → its symbols (:meth:`Memo.owned`): a statement's expressions do not change, and every run asks for
#: its symbols once per result and once for the parameters shown
_SYMBOLS = Memo(512)


def _symbols_of(statement) -> set:
    """The symbols and applied functions a hypothesis or claim is written in."""
    hit = _SYMBOLS.owned(statement)
    if hit is not None:
        return set(hit)
    out = _symbols_uncached(statement)
    _SYMBOLS.keep(statement, (), frozenset(out))
    return out


def _symbols_uncached(statement) -> set:
    import sympy
    from sympy.core.function import AppliedUndef

    exprs = []
    if callable(getattr(statement, "symbols", None)):  # a statement that names its own symbols
        return set(statement.symbols())
    if isinstance(statement, Hypothesis):
        exprs.append(sympy.sympify(statement.margin))
    elif isinstance(statement, MatrixHypothesis):
        exprs += list(sympy.Matrix(statement.matrix))
    elif isinstance(statement, TermwiseBound):
        exprs += [statement.rhs, statement.functional.expr] + [tb.bound for tb in statement.bounds]
        exprs += [e for eq in statement.system.equations for term in eq.terms for e in [term.expr]]
        if statement.region is not None:
            exprs += list(statement.region.bounds.values())
    elif isinstance(statement, BoundClaim):
        exprs += [statement.rhs, statement.functional.expr]
        exprs += [e for eq in statement.system.equations for term in eq.terms for e in [term.expr]]
        if not isinstance(statement.lhs, str):
            exprs.append(statement.lhs)
    else:
        terms = list(getattr(statement, "terms", ())) + list(getattr(statement, "lhs", ())) \
            + list(getattr(statement, "rhs", ()))
        functional = getattr(statement, "functional", None)
        if functional is not None:
            terms += list(functional.terms)
        for eq in statement.system.equations:
            terms += list(eq.terms)
            if eq.mass is not None:
                exprs += list(eq.mass)
        exprs += [term.expr for term in terms]
    out: set = set()
    for e in exprs:
        e = sympy.sympify(e)
        out |= e.free_symbols
        out |= {a.func for a in e.atoms(AppliedUndef)}
    return out


def _not_exact_if_floats(result: Result, symbols: set, floated: frozenset) -> Result:
    """An ``exact`` result that rests on a parameter given as a float is only ``certified``."""
    if result.status is not Status.EXACT or not (symbols & floated):
        return result
    names = ", ".join(sorted(str(s) for s in symbols & floated))
    return dataclasses.replace(result, status=Status.CERTIFIED,
                               detail=f"{result.detail}; {names} came from floating-point input (taken at the "
                                      f"exact binary value), so the result is certified, never exact")
