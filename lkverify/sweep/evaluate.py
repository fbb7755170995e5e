"""The work of one chunk of points, on a worker: simulate, classify, linear margin.

A :class:`Simulation` is shipped once to every worker (it pickles: SymPy data and generated
source, never compiled code); :func:`run_chunk` evaluates a chunk of points and returns its
columns.  Every point is computed on its own (its own adaptive steps), so its result does
not depend on which chunk or worker it ran in: a sweep gives the same table for any number
of workers.

Each point is classified from the distance to the equilibrium along the run
(``example.distance``) sampled at ``t_eval``:

* ``converged``: the run reached ``t_end`` and the distance stays below ``level`` (1e-2)
  from some time on (``t_to_level``);
* ``bounded``: the run reached ``t_end`` and did not converge in that sense;
* ``diverged``: ‖y‖ exceeded the divergence bound or became non-finite;
* ``undecided``: the run's step budget was spent or its steps collapsed (stiff);
* ``invalid``: the point lies outside a parameter's hypotheses (not simulated).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable

import numpy as np

from ..simulate.solver import Outcome

__all__ = ["CLASSES", "Simulation", "classify", "run_chunk"]

#: the simulated classes, in the map's legend order
CLASSES = ("converged", "bounded", "diverged", "undecided", "invalid")

_OUTCOMES = list(Outcome)


@dataclasses.dataclass(frozen=True)
class Simulation:
    """What every worker needs to simulate points of one sweep.

    Examples
    --------
    >>> from lkverify.sweep import Grid, build_plan
    >>> sim = build_plan("aleksandrov2023.fig1", grid=Grid.parse(["b=-2:2:2"])).simulation
    >>> sim.names, sim.t_end, sim.family is not None, sim.linear is not None
    (('b',), 100.0, True, True)
    """

    family: object               # CompiledFamily, or None for the slow path
    system: object               # the System (slow path)
    values: dict                 # parameter → value, swept names as symbols
    names: tuple                 # swept names, in grid order
    history: dict
    t_end: float
    t_eval: np.ndarray
    rtol: float
    atol: float
    divergence_bound: float
    max_steps: int
    distance: Callable
    level: float
    linear: object = None        # LinearFamily or None


def classify(outcome: Outcome, t, d, level: float) -> tuple:
    """(class, time after which d stays below level or NaN) of one run.

    >>> t = np.linspace(0, 10, 11)
    >>> classify(Outcome.SUCCESS, t, np.exp(-t), 1e-2)
    ('converged', 5.0)
    >>> classify(Outcome.SUCCESS, t, np.ones(11), 1e-2)[0], classify(Outcome.DIVERGED, t, t, 1e-2)[0]
    ('bounded', 'diverged')
    """
    if outcome is Outcome.DIVERGED:
        return "diverged", float("nan")
    if outcome is not Outcome.SUCCESS:
        return "undecided", float("nan")
    d = np.asarray(d, dtype=float)
    above = np.nonzero(~(d < level))[0]
    if above.size == 0:
        return "converged", float(t[0])
    k = int(above[-1])
    if k == len(d) - 1:
        return "bounded", float("nan")
    return "converged", float(t[k + 1])


def _empty(n: int) -> dict:
    nan = np.full(n, np.nan)
    return {"outcome": np.array([""] * n, dtype=object), "simulated": np.array(["invalid"] * n, dtype=object),
            "t_to_level": nan.copy(), "final_distance": nan.copy(), "max_distance": nan.copy(),
            "t_fail": nan.copy(), "n_steps": np.zeros(n, dtype=np.int64),
            "linear_abscissa": nan.copy(), "linear_verdict": np.array([""] * n, dtype=object)}


def run_chunk(sim: Simulation, points: np.ndarray, valid: np.ndarray) -> dict:
    """Columns of a chunk: simulate the valid points, classify them, their linear margin.

    ``points`` is an (m, len(names)) float array, ``valid`` a boolean mask (invalid points
    are not simulated and stay ``invalid``).

    Examples
    --------
    Figs. 2 and 1 of paper 002 (b = −2, 2):

    >>> from lkverify.sweep import Grid, build_plan
    >>> sim = build_plan("aleksandrov2023.fig1", grid=Grid.parse(["b=-2:2:2"])).simulation
    >>> cols = run_chunk(sim, np.array([[-2.0], [2.0]]), np.array([True, True]))
    >>> cols["simulated"].tolist(), cols["linear_verdict"].tolist()
    (['bounded', 'converged'], ['unstable', 'stable'])
    """
    start = time.monotonic()
    points = np.asarray(points, dtype=float).reshape(len(valid), len(sim.names))
    cols = _empty(len(valid))
    idx = np.nonzero(np.asarray(valid, dtype=bool))[0]
    if idx.size:
        if sim.family is not None:
            _fast(sim, points[idx], idx, cols)
        else:
            _slow(sim, points[idx], idx, cols)
        if sim.linear is not None:
            lin = sim.linear.evaluate(points[idx])
            cols["linear_abscissa"][idx] = np.asarray(lin.abscissa, dtype=float)
            cols["linear_verdict"][idx] = np.asarray(lin.verdict, dtype=object)
    cols["seconds"] = time.monotonic() - start
    return cols


def _record(sim, cols, j, outcome, t_fail, n_steps, states) -> None:
    cols["outcome"][j] = outcome.value
    cols["t_fail"][j] = np.nan if t_fail is None else float(t_fail)
    cols["n_steps"][j] = int(n_steps)
    d = None
    if states is not None:
        d = np.asarray(sim.distance(states), dtype=float)
        finite = np.isfinite(d)
        if finite.any():
            cols["final_distance"][j] = float(d[finite][-1])
            cols["max_distance"][j] = float(np.max(d[finite]))
    t = sim.t_eval
    cls, t_level = classify(outcome, t if d is None else t[:len(d)], d if d is not None else [np.inf], sim.level)
    cols["simulated"][j] = cls
    cols["t_to_level"][j] = t_level


def _fast(sim, pts, idx, cols) -> None:
    res = sim.family.integrate(pts, sim.history, t_end=sim.t_end, t_eval=sim.t_eval, rtol=sim.rtol, atol=sim.atol,
                               divergence_bound=sim.divergence_bound, max_steps=sim.max_steps)
    for k, j in enumerate(idx):
        outcome = res.outcomes[k]
        states = res.states(k) if outcome is Outcome.SUCCESS else None
        _record(sim, cols, j, outcome, res.t_fail[k], res.n_steps[k], states)


def _slow(sim, pts, idx, cols) -> None:
    """The reference path: :func:`lkverify.simulate.simulate` per point (its own compilation)."""
    import sympy

    from ..errors import InputError
    from ..simulate.control import StepControl
    from ..simulate.runs import simulate

    for k, j in enumerate(idx):
        sub = {sympy.Symbol(n): sympy.Float(x) for n, x in zip(sim.names, pts[k])}
        values = {n: (v.xreplace(sub) if isinstance(v, sympy.Basic) else v) for n, v in sim.values.items()}
        try:
            tr = simulate(sim.system, history=sim.history, t_end=sim.t_end, values=values, t_eval=sim.t_eval,
                          step=StepControl(rtol=sim.rtol, atol=sim.atol), divergence_bound=sim.divergence_bound)
        except InputError:
            cols["outcome"][j], cols["simulated"][j] = "", "invalid"
            cols["t_fail"][j] = np.nan
            continue
        states = tr.states if tr.outcome is Outcome.SUCCESS else None
        _record(sim, cols, j, tr.outcome, tr.t_fail, tr.n_steps, states)
