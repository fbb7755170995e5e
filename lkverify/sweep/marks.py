"""The paper's gains in the swept plane: which catalogued runs lie on the map, and where.

A sweep varies a few names (``--grid b=… --grid h=…``) of one example's values; every other
parameter keeps the example's value (or the ``--set`` one).  A catalogued example of the same
paper lies *in that plane* when it has a run on the same System, with the same initial history,
whose values equal the swept example's on every name that is not swept.  Its place on the map is
solved exactly:

* a grid name that is a parameter (``b``) takes the run's value;
* a grid name inside a ``--set`` template (``F=diag(h,h,h)``) is solved from
  template = the run's value, entry by entry (:func:`sympy.solve`); the solution must be unique
  and real, else the run is not on the map.

At ``lkverify sweep aleksandrov2023.fig1 --set "F=diag(h,h,h)" --grid b=… --grid h=…`` this finds
Fig. 1 (b = 2, h = 7/10) and Fig. 2 (b = −2, h = 7/10); Figs. 3–6 differ in a, μ or τ, and Fig. 7
in the initial history.

Examples
--------
x' = −a x(t − τ): a sweep of ``slow`` over a, with τ fixed, finds ``fast`` (same τ) but not
``late`` (another τ):

>>> from lkverify import Equation, Example, Parameters, Run, System, Term, Vector, t
>>> from lkverify.simulate import Converges
>>> P = Parameters(); a = P.scalar("a", default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
>>> def fig(name, values):
...     return Example(name, runs=[Run(name, sys, values, {"x": [1]})], t_end=10, series=[],
...                    distance=lambda s: abs(s["x"][:, 0]), claims=[Converges(name)])
>>> slow, fast, late = fig("fig1", {"a": "1/10"}), fig("fig2", {"a": "1/2"}), fig("fig3", {"tau": "2"})
>>> marks = paper_marks(slow, ("a",), {}, candidates=[slow, fast, late])
>>> [(m.label, m.coords, m.expected) for m in marks]
[('Fig. 1', {'a': 1/10}, 'converges'), ('Fig. 2', {'a': 1/2}, 'converges')]
>>> marks[1].to_meta()
{'label': 'Fig. 2', 'item': 'fig2', 'coords': {'a': 0.5}, 'expected': 'converges'}
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Mapping, Sequence

import numpy as np
import sympy

from ..errors import InputError

__all__ = ["Mark", "paper_marks", "expectation", "mark_label"]

#: what a mark's ``expected`` says, from the example's claims on the run
CONVERGES, DOES_NOT_CONVERGE = "converges", "does not converge"


@dataclasses.dataclass(frozen=True)
class Mark:
    """A catalogued run placed on the swept map.

    Attributes
    ----------
    label : str
        As the paper names it, e.g. ``"Fig. 1"``.
    item : str
        The example's qualified name, e.g. ``"aleksandrov2023.fig1"``.
    coords : dict
        Grid name → exact value (SymPy), the run's place on the map.
    expected : str
        ``"converges"``, ``"does not converge"`` (the example's claims on the run) or ``""``.
    run : Run
        The catalogued run (system, exact values, history): simulate it for the observed class.

    Examples
    --------
    >>> import sympy
    >>> m = Mark("Fig. 1", "aleksandrov2023.fig1", {"b": sympy.Integer(2), "h": sympy.Rational(7, 10)}, "converges")
    >>> m.floats(), m.to_meta()["expected"]
    ({'b': 2.0, 'h': 0.7}, 'converges')
    """

    label: str
    item: str
    coords: dict
    expected: str
    run: object = dataclasses.field(repr=False, compare=False, default=None)

    def floats(self) -> dict:
        """The coordinates as floats (name → float)."""
        return {k: float(v) for k, v in self.coords.items()}

    def to_meta(self) -> dict:
        """The mark as the figure's ``meta["marks"]`` entry wants it (without ``observed``)."""
        return {"label": self.label, "item": self.item, "coords": self.floats(), "expected": self.expected}


def paper_marks(example, grid_names: Sequence[str], templates: Mapping, *, fixed: Mapping | None = None,
                history: Mapping | None = None, candidates: Sequence | None = None) -> tuple:
    """The catalogued runs that lie in the swept plane, with their exact coordinates.

    Parameters
    ----------
    example : Example
        The swept example (one run).
    grid_names : sequence of str
        The swept names, e.g. ``("b", "h")``.
    templates : mapping
        Parameter name → SymPy value in the grid symbols (``--set F=diag(h,h,h)``).
    fixed : mapping, optional, keyword-only
        The ``--set`` values without grid names (parameter name → value): they override the
        swept run's values, and a catalogued run must have them too.
    history : mapping, optional, keyword-only
        The sweep's initial history, when it is not the swept run's (state name → vector).
    candidates : sequence of Example, optional, keyword-only
        Where to look; by default every catalogued item of the example's paper (a paper that
        is not in the catalogue, such as a user's file: the example alone).

    Returns
    -------
    tuple of Mark
        In the candidates' order, one per run in the plane.

    Raises
    ------
    InputError
        ``grid_names`` empty, a template key that is not a parameter, or fixed values that
        are not admissible.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.sweep import load_example
    >>> h = sympy.Symbol("h")
    >>> marks = paper_marks(load_example("aleksandrov2023.fig1"), ("b", "h"), {"F": sympy.diag(h, h, h)})
    >>> [(m.label, m.coords, m.expected) for m in marks]
    [('Fig. 1', {'b': 2, 'h': 7/10}, 'converges'), ('Fig. 2', {'b': -2, 'h': 7/10}, 'does not converge')]
    """
    names = tuple(grid_names)
    if not names:
        raise InputError("paper_marks: expected at least one grid name, got none; e.g. ('b', 'h')")
    run = example.runs[0]
    system, P = run.system, run.system.parameters
    unknown = sorted(set(templates) - set(P.names))
    if unknown:
        raise InputError(f"paper_marks: template(s) {', '.join(unknown)} are not parameters of "
                         f"{example.qualified_name}'s system; expected some of {', '.join(P.names)}")
    free = set(names) | set(templates)
    base = P.resolve({**dict(run.values), **dict(fixed or {})}, use_defaults=True)
    base = {k: v for k, v in base.items() if k not in free}
    hist = dict(run.history) if history is None else {**dict(run.history), **dict(history)}
    symbols = _grid_symbols(names, templates)
    pool = _candidates(example) if candidates is None else tuple(candidates)
    marks = []
    for cand in pool:
        for r in getattr(cand, "runs", ()):
            if r.system is not system or not _same_history(r.history, hist):
                continue
            coords = _place(r, P, base, free, names, symbols, templates)
            if coords is not None:
                marks.append(Mark(mark_label(cand, r), cand.qualified_name, coords, expectation(cand, r), r))
    return tuple(marks)


def mark_label(example, run) -> str:
    """The paper's name of a run: ``fig3`` → ``"Fig. 3"``; else the item name (and the run's label).

    >>> from types import SimpleNamespace as N
    >>> mark_label(N(name="fig12", runs=[1]), None), mark_label(N(name="example", runs=[1]), None)
    ('Fig. 12', 'example')
    >>> mark_label(N(name="counter", runs=[1, 2]), N(label="τ = 1/4"))
    'counter: τ = 1/4'
    """
    m = re.fullmatch(r"fig(\d+)", example.name)
    base = f"Fig. {m.group(1)}" if m else example.name
    return f"{base}: {run.label}" if len(example.runs) > 1 else base


def expectation(example, run) -> str:
    """What the example's claims say about ``run``: ``"converges"``, ``"does not converge"`` or ``""``.

    Only :class:`~lkverify.simulate.Converges` and :class:`~lkverify.simulate.DoesNotConverge`
    claims on that run count; both, or neither, give ``""``.

    >>> from types import SimpleNamespace as N
    >>> from lkverify.simulate import Converges, DoesNotConverge
    >>> r = N(label="r")
    >>> expectation(N(claims=[Converges("r")]), r), expectation(N(claims=[DoesNotConverge("r")]), r)
    ('converges', 'does not converge')
    >>> expectation(N(claims=[Converges("other")]), r)
    ''
    """
    from ..simulate import Converges, DoesNotConverge

    said = set()
    for claim in getattr(example, "claims", ()):
        if getattr(claim, "run", None) != run.label:
            continue
        if isinstance(claim, Converges):
            said.add(CONVERGES)
        elif isinstance(claim, DoesNotConverge):
            said.add(DOES_NOT_CONVERGE)
    return said.pop() if len(said) == 1 else ""


# -- helpers -----------------------------------------------------------------------------------------


def _candidates(example) -> tuple:
    """Every catalogued item of the example's paper (only that paper is loaded), else the example."""
    from ..catalogue.loader import find_items

    paper = example.qualified_name.split(".")[0] if "." in example.qualified_name else ""
    if not paper:
        return (example,)
    try:
        found = tuple(find_items(paper))
    except InputError:
        return (example,)
    return found if any(x is example for x in found) else (example, *found)


def _grid_symbols(names, templates) -> dict:
    """Grid name → the SymPy symbol the templates use for it (a plain Symbol if none does)."""
    seen = {}
    for v in templates.values():
        for s in getattr(v, "free_symbols", ()):
            seen.setdefault(str(s), s)
    return {n: seen.get(n, sympy.Symbol(n)) for n in names}


def _place(run, P, base, free, names, symbols, templates) -> dict | None:
    """The run's grid coordinates if it lies in the plane (exact, unique, real), else None."""
    try:
        values = P.resolve(dict(run.values), use_defaults=True)
    except InputError:
        return None
    if set(values) - free != set(base):
        return None
    if any(not _equal(values[k], base[k]) for k in base):
        return None
    equations = []
    for n in names:
        if n in P.names and n not in templates:
            if not isinstance(values.get(n), sympy.Expr):
                return None
            equations.append(symbols[n] - values[n])
    for k, template in templates.items():
        eqs = _entries(template, values.get(k))
        if eqs is None:
            return None
        equations += eqs
    return _solve(equations, [symbols[n] for n in names], names)


def _entries(template, value) -> list | None:
    """template − value, entry by entry (None when the shapes differ)."""
    if value is None:
        return None
    if isinstance(template, sympy.MatrixBase) or isinstance(value, sympy.MatrixBase):
        if not (isinstance(template, sympy.MatrixBase) and isinstance(value, sympy.MatrixBase)):
            return None
        if template.shape != value.shape:
            return None
        return list(sympy.Matrix(template) - sympy.Matrix(value))
    try:
        return [sympy.sympify(template) - sympy.sympify(value)]
    except (sympy.SympifyError, TypeError):
        return None


def _solve(equations, symbols, names) -> dict | None:
    """The unique real solution of the equations for every symbol, else None."""
    eqs = [sympy.expand(e) for e in equations]
    eqs = [e for e in eqs if e != 0]
    wanted = set(symbols)
    if any(not (e.free_symbols & wanted) for e in eqs):
        return None  # a constant nonzero difference: another value outside the swept names
    if not eqs:
        return None  # nothing fixes the grid names
    solutions = sympy.solve(eqs, symbols, dict=True)
    if len(solutions) != 1:
        return None
    sol = solutions[0]
    if set(sol) != wanted:
        return None
    coords = {}
    for n, s in zip(names, symbols):
        v = sol[s]
        if v.free_symbols or v.is_real is not True:
            return None
        coords[n] = v
    return coords


def _equal(a, b) -> bool:
    """Exact equality of two parameter values (numbers, matrices, expressions)."""
    if a is b:
        return True
    try:
        if a == b:
            return True
        if isinstance(a, sympy.MatrixBase) or isinstance(b, sympy.MatrixBase):
            if not (isinstance(a, sympy.MatrixBase) and isinstance(b, sympy.MatrixBase)) or a.shape != b.shape:
                return False
            return all(sympy.simplify(x - y) == 0 for x, y in zip(a, b))
        return sympy.simplify(sympy.sympify(a) - sympy.sympify(b)) == 0
    except (sympy.SympifyError, TypeError, ValueError):
        return False


def _same_history(a: Mapping, b: Mapping) -> bool:
    """Same states and the same initial values (compared as float arrays when they are numbers)."""
    if set(a) != set(b):
        return False
    for k in a:
        if a[k] is b[k]:
            continue
        try:
            x = np.asarray(a[k], dtype=float).ravel()
            y = np.asarray(b[k], dtype=float).ravel()
        except (TypeError, ValueError):
            if a[k] != b[k]:
                return False
            continue
        if x.shape != y.shape or not np.array_equal(x, y):
            return False
    return True
