"""What a sweep computes, built once on the client: the item, its values, the checks per point.

:func:`build_plan` turns ``ITEM --set … --grid …`` into a :class:`Plan`:

* the swept example (a catalogued figure with one run) and its System;
* the values: the run's, overridden by ``--set``; a ``--set`` value may be a template in the
  swept names (``F=diag(h,h,h)`` sweeps the matrix F through the scalar h);
* the exact checks, done on the client (cheap, cached by the values they depend on): the
  parameters' own hypotheses (F ≻ 0, a ≥ 0, τ > 0: a point outside them is ``invalid``) and
  the hypotheses of every catalogued theorem on the same System, with their margins;
* what the workers run (:class:`~lkverify.sweep.evaluate.Simulation`): the system compiled
  once with the swept names as runtime arguments, the linearisation at the declared
  equilibrium compiled once, the initial history, the distance to the equilibrium.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np
import sympy

from ..declare.parse import parse_assignment, parse_value
from ..declare.symbols import t as _t
from ..errors import InputError, UnsupportedInput
from ..status import Status
from .evaluate import Simulation
from .grid import Grid

__all__ = ["Plan", "TheoremChecks", "build_plan", "load_example"]


@dataclasses.dataclass(frozen=True)
class TheoremChecks:
    """The hypotheses of one catalogued theorem on the swept System."""

    name: str          # qualified name, e.g. aleksandrov2023.theorem3
    short: str         # theorem3
    hypotheses: tuple  # Hypothesis-like objects with .name and .evaluate(substitution)


@dataclasses.dataclass(frozen=True)
class Plan:
    """Everything a sweep needs, resolved and compiled once (see the module docstring).

    Examples
    --------
    >>> plan = build_plan("aleksandrov2023.fig1", grid=Grid.parse(["b=-2:2:2"]))
    >>> plan.swept_parameters, plan.values_at({"b": 2})["tau"], plan.fixed["F"][0, 0]
    (('b',), 9/10, 7/10)
    """

    item: str
    example: object
    grid: Grid
    sets: dict                 # name → text, as typed
    fixed: dict                # name → value (no swept name in it)
    templates: dict            # name → SymPy value containing swept symbols
    swept_parameters: tuple    # grid names that are parameters of the system
    theorems: tuple            # TheoremChecks
    simulation: Simulation
    linear_note: str           # why there is no linear margin ("" when there is one)
    simulation_note: str       # "" for the compiled path, else why each point is compiled on its own
    floated: frozenset = frozenset()   # names of the symbols whose values were given as floats (at most certified)

    def values_at(self, point: Mapping) -> dict:
        """The exact parameter values at a grid point (name → exact value)."""
        sub = {sympy.Symbol(k): v for k, v in point.items()}
        out = dict(self.fixed)
        out.update({k: v.xreplace(sub) for k, v in self.templates.items()})
        out.update({k: point[k] for k in self.swept_parameters})
        return out

    @property
    def parameters(self):
        return self.example.runs[0].system.parameters


def load_example(item: str):
    """The catalogued example ``item`` (one run), or InputError saying what came instead.

    Examples
    --------
    >>> load_example("aleksandrov2023.fig1").runs[0].values["b"]
    '2'
    >>> load_example("aleksandrov2023.theorem3")
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: sweep: expected one example (a numerical figure whose run is simulated), got aleksandrov2023.theorem3 (theorem); e.g. lkverify sweep aleksandrov2023.fig1 --grid b=-3:3:61
    """
    from ..catalogue.examples import Example
    from ..catalogue.loader import find_items

    found = find_items(item)
    examples = [x for x in found if isinstance(x, Example)]
    if len(found) != 1 or not examples:
        kinds = ", ".join(f"{x.qualified_name} ({type(x).__name__.lower()})" for x in found[:4])
        raise InputError(f"sweep: expected one example (a numerical figure whose run is simulated), got "
                         f"{kinds or 'nothing'}; e.g. lkverify sweep aleksandrov2023.fig1 --grid b=-3:3:61")
    ex = examples[0]
    if len(ex.runs) != 1:
        raise InputError(f"sweep: {ex.qualified_name} has {len(ex.runs)} runs "
                         f"({', '.join(r.label for r in ex.runs)}); expected an example with one run")
    return ex


def build_plan(item, *, grid: Grid, sets: Sequence[str] = (), t_end: float | None = None, samples: int = 1001,
               rtol: float = 1e-8, atol: float = 1e-10, level: float = 1e-2, max_steps: int = 10**6,
               divergence_bound: float = 1e6) -> Plan:
    """Resolve and compile a sweep (see the module docstring).

    Raises
    ------
    InputError
        An unknown item or name, a swept name neither a parameter nor used by a ``--set``
        template, a fixed value outside the parameter's hypotheses, a bad ``--t-end``.

    Examples
    --------
    A matrix swept through a scalar (paper 002's F = h·I):

    >>> plan = build_plan("aleksandrov2023.fig1", grid=Grid.parse(["h=0.5:1:2"]), sets=["F=diag(h,h,h)"])
    >>> plan.templates["F"][0, 0], plan.values_at({"h": 1})["F"][2, 2], [th.short for th in plan.theorems]
    (h, 1, ['theorem3'])
    """
    example = load_example(item) if isinstance(item, str) else item
    run = example.runs[0]
    P = run.system.parameters
    names = grid.names
    symbols = {n: sympy.Symbol(n) for n in names}
    given, texts = _parse_sets(sets, symbols, P)
    templates = {k: v for k, v in given.items() if _free(v) & set(symbols.values())}
    swept = tuple(n for n in names if n in P.names)
    _check_names(names, swept, templates, given, P, example)
    fixed = {**dict(run.values), **{k: v for k, v in given.items() if k not in templates}}
    for k in swept:
        fixed.pop(k, None)
    for k in templates:
        fixed.pop(k, None)
    resolved = P.resolve(fixed, use_defaults=False)      # exact, within their parameters' hypotheses
    floated = frozenset(str(s) for s in P.float_symbols(resolved))   # floats at their binary value: never exact
    fixed = dict(resolved)
    t_end = _t_end(example.t_end if t_end is None else t_end)
    symbolic = {**fixed, **templates, **{k: symbols[k] for k in swept}}
    simulation, sim_note = _simulation(example, symbolic, names, t_end, samples, rtol, atol, level, max_steps,
                                       divergence_bound)
    linear, lin_note = _linear(example, symbolic, names)
    simulation = dataclasses.replace(simulation, linear=linear)
    return Plan(example.qualified_name, example, grid, texts, fixed, templates,
                swept, _theorems(example), simulation, lin_note, sim_note, floated)


def _parse_sets(sets, symbols, P) -> tuple:
    """(name → parsed value, name → the text as typed)."""
    out, texts = {}, {}
    for text in sets:
        name, value = parse_assignment(text)
        if name not in P.names:
            raise InputError(f"--set {name}: no such parameter of the swept system; known: {', '.join(P.names)}")
        if name in out:
            raise InputError(f"--set {name}: given twice; expected each parameter once")
        out[name] = parse_value(value, name=name, variables=symbols, option="--set")
        texts[name] = value
    return out, texts


def _free(v) -> set:
    return set(getattr(v, "free_symbols", set()))


def _check_names(names, swept, templates, given, P, example) -> None:
    used = set().union(*[{str(s) for s in _free(v)} for v in templates.values()]) if templates else set()
    defaults = P.resolve({}, use_defaults=True)
    for n in names:
        if n == str(_t):
            raise InputError(f"--grid {n}: t is the time; expected a parameter name")
        if n in given and n in swept:
            raise InputError(f"--grid {n}: {n} is both swept and set with --set; expected one of the two")
        if n not in swept and n not in used:
            raise InputError(f"--grid {n}: no parameter {n} in {example.qualified_name}'s system and no --set "
                             f"template uses it; expected one of {', '.join(P.names)}, or a name in a template "
                             f"such as --set \"F=diag({n},{n},{n})\"")
        if n in swept and not isinstance(defaults.get(n, sympy.S.Zero), sympy.Expr):
            raise InputError(f"--grid {n}: {n} is a matrix or vector parameter; sweep it through a scalar with a "
                             f"template, e.g. --set \"{n}=diag(h,h,h)\" --grid h=0.1:2:20")


def _t_end(value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"--t-end: expected a positive number, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise InputError(f"--t-end: expected a positive finite number, got {value!r}")
    return v


def _simulation(example, symbolic, names, t_end, samples, rtol, atol, level, max_steps, bound):
    from ..simulate.family import compile_family

    run = example.runs[0]
    family, note = None, ""
    try:
        family = compile_family(run.system, symbolic, grid=names)
    except UnsupportedInput as exc:
        note = f"each point compiled on its own (slow path): {exc}"
    sim = Simulation(family=family, system=run.system, values=symbolic, names=tuple(names),
                     history=dict(run.history), t_end=t_end, t_eval=np.linspace(0.0, t_end, int(samples)),
                     rtol=rtol, atol=atol, divergence_bound=bound, max_steps=max_steps,
                     distance=example.distance, level=level, linear=None)
    return sim, note


def _linear(example, symbolic, names):
    equilibrium = getattr(example, "equilibrium", None)
    if not equilibrium:
        return None, f"{example.qualified_name} declares no equilibrium to linearise at"
    from ..linear.family import linear_family

    try:
        return linear_family(example.runs[0].system, equilibrium, symbolic, grid=names), ""
    except (InputError, UnsupportedInput) as exc:
        return None, f"no linear margin: {exc}"


def _theorems(example) -> tuple:
    """Catalogued theorems of the example's paper whose system is the example's System."""
    from ..catalogue.items import Theorem
    from ..catalogue.loader import find_items

    system = example.runs[0].system
    paper = getattr(example, "paper", "")
    if not paper:
        return ()
    try:
        items = find_items(paper)
    except InputError:            # not a catalogued paper (a user's example)
        return ()
    out = []
    for x in items:
        if isinstance(x, Theorem) and x.system is system and x.hypotheses:
            out.append(TheoremChecks(x.qualified_name, x.name, tuple(x.hypotheses)))
    return tuple(out)


# -- the exact checks per point (client side) ------------------------------------------------------


class PointChecks:
    """Parameter validity and theorem hypotheses, exact, each on the sub-grid of the names it depends on.

    A swept parameter depends on some of the grid's names (F = diag(h,h,h) on h alone); a
    hypothesis on the names of the parameters it contains.  Each is decided once per point
    of its own sub-grid and broadcast to the whole grid, so the exact work grows with the
    number of distinct values, not with the number of points.
    """

    def __init__(self, plan: Plan):
        self.plan = plan
        self.P = plan.parameters
        depends = {k: {str(s) for s in _free(v)} for k, v in plan.templates.items()}
        depends.update({k: {k} for k in plan.swept_parameters})
        self.depends = depends          # parameter → swept names it depends on
        self.base = dict(self.P.resolve(plan.fixed, use_defaults=True))

    def value(self, name: str, point: Mapping):
        """The exact value of a swept parameter at a (sub-)grid point."""
        if name in self.plan.templates:
            return self.plan.templates[name].xreplace({sympy.Symbol(k): v for k, v in point.items()})
        return point[name]

    def reason(self, name: str, point: Mapping) -> str:
        """'' when the parameter's own hypotheses hold at the point, else why not (one line)."""
        try:
            self.P.resolve({name: self.value(name, point)}, use_defaults=False)
            return ""
        except InputError as exc:
            return str(exc)

    def hypothesis_names(self, h) -> set:
        """The grid names a hypothesis depends on (through the parameters in it)."""
        params = _hypothesis_names(h)
        params = set(self.depends) if "*" in params else params & set(self.depends)
        return set().union(*[self.depends[p] for p in params]) if params else set()

    def hypothesis(self, h, point: Mapping) -> tuple:
        """(status, margin float, how decided) of a hypothesis at a sub-grid point.

        ``how`` is ``exact`` (a rational margin, held or failed), ``certified`` (decided by an
        enclosure, or on a value given as a float: :mod:`lkverify.status`, rule 3), ``undecided``,
        or None where a parameter value is invalid (not evaluated).
        """
        values = {p: self.value(p, point) for p, deps in self.depends.items() if deps <= set(point)}
        if any(self.reason(p, point) for p in values):
            return Status.UNDECIDED, float("nan"), None
        try:
            res = h.evaluate(self.P.substitution({**self.base, **values}))
        except InputError:
            return Status.UNDECIDED, float("nan"), Status.UNDECIDED
        how = res.status
        if how is Status.FAILED:
            how = Status.EXACT if isinstance(res.value, sympy.Basic) and res.value.is_Rational else Status.CERTIFIED
        names = _hypothesis_names(h)
        if self.plan.floated and ("*" in names or names & self.plan.floated):   # a float input: never exact
            how = Status.CERTIFIED if how is Status.EXACT else how
            status = Status.CERTIFIED if res.status is Status.EXACT else res.status
            return status, _float(res.value), how
        return res.status, _float(res.value), how


#: how a region was decided, weakest last: the region's status is its weakest point's
_STRENGTH = (Status.EXACT, Status.CERTIFIED, Status.UNDECIDED)


def weakest(statuses) -> Status:
    """The weakest of the ways a region's points were decided (EXACT when there are none).

    >>> weakest([Status.EXACT, Status.CERTIFIED]).value, weakest([]).value
    ('certified', 'exact')
    """
    ranks = [_STRENGTH.index(s) if s in _STRENGTH else len(_STRENGTH) - 1 for s in statuses]
    return _STRENGTH[max(ranks, default=0)]


def sub_grids(grid: Grid, names: set):
    """(index tuple into the full grid shape, point) for every point of the sub-grid of ``names``.

    The index has a slice for every axis not in ``names`` (broadcast over it).

    >>> g = Grid.parse(["b=0:1:2", "h=1:2:2"])
    >>> [(idx, pt) for idx, pt in sub_grids(g, {"h"})]
    [((slice(None, None, None), 0), {'h': 1}), ((slice(None, None, None), 1), {'h': 2})]
    """
    axes = [i for i, a in enumerate(grid.axes) if a.name in names]
    for sub in np.ndindex(*[grid.shape[i] for i in axes]):
        idx = [slice(None)] * len(grid.axes)
        point = {}
        for i, j in zip(axes, sub):
            idx[i] = j
            point[grid.axes[i].name] = grid.axes[i].values[j]
        yield tuple(idx), point


def _hypothesis_names(h) -> set:
    names = set()
    for f in dataclasses.fields(h) if dataclasses.is_dataclass(h) else ():
        v = getattr(h, f.name)
        if isinstance(v, sympy.Basic):
            names |= {str(s) for s in v.free_symbols}
    return names if names or dataclasses.is_dataclass(h) else {"*"}


def _float(v) -> float:
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def holds(status: Status) -> bool:
    return status in (Status.EXACT, Status.CERTIFIED)
