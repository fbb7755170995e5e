"""The proved layer of a sweep: each grid cell a box, the theorem's chain run for every point of it.

``lkverify sweep ITEM --grid … --prove`` adds, per catalogued theorem on the swept System, the
column ``proved:THEOREM`` (``established`` / ``failed`` / ``undecided``): the cell of a grid point
is the box of the points nearer to it than to its neighbours (half a step each side, clipped to
the grid's range), and :func:`lkverify.catalogue.boxrun.run_over_box` decides the chain for every
point of it (a few pieces at most, :data:`PROVE_MAX_BOXES`).  The proof's choices found for the
cell are kept (``proved_choices:THEOREM``, JSON).

A proved cell is cross-examined by a simulation (:func:`in_region_run`): at the cell's centre,
from a constant history inside the certified region (‖χ‖ = δ̃/2, a rotation of the
equilibrium's unit vectors and a shift of its other states in fixed directions), the decay
outputs (‖s − r‖, ‖ω‖, …) must stay under the certified envelope d‖χ‖(1 + κ‖χ‖t)^(−1/…).  One
that does not is a bug of lkverify: :class:`~lkverify.errors.InternalError` (exit 3), never a map.
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np
import sympy

from ..errors import InputError, InternalError

__all__ = ["PROVE_MAX_BOXES", "cell_box", "in_region_run", "prove_cell", "prove_cells", "prove_grid",
           "theorem_values"]

#: pieces of one cell's subdivision (the work limit of a cell)
PROVE_MAX_BOXES = 3

#: the horizon of a proved cell's in-region run
CHECK_T_END = 60.0


def cell_box(grid, k: int) -> dict:
    """The cell of grid point ``k`` as the map draws it: name → (lo, hi), half a step each side.

    The edge cells reach half a step beyond the grid's range (as the map's cells do); a cell that
    reaches inadmissible values there is ``undecided`` with the reason.

    >>> from lkverify.sweep.grid import Grid
    >>> g = Grid.parse(["b=-1:1:3", "h=1:1:1"])
    >>> cell_box(g, 0), cell_box(g, 1)
    ({'b': (-3/2, -1/2), 'h': (1, 1)}, {'b': (-1/2, 1/2), 'h': (1, 1)})
    """
    out = {}
    for axis, i in zip(grid.axes, grid.index(k)):
        v = axis.values[i]
        half = abs(axis.stop - axis.start) / (axis.n - 1) / 2 if axis.n > 1 else 0
        out[axis.name] = (v - half, v + half)
    return out


def theorem_values(plan) -> dict:
    """The values a theorem of the plan is run at: the example's run values and ``--set``, the templates
    written in the swept names (``F = diag(h,h,h)``), the swept parameters left to the box."""
    run = plan.example.runs[0]
    values = {k: v for k, v in run.values.items() if k not in plan.swept_parameters}
    values.update({k: v for k, v in plan.fixed.items() if k in plan.sets})
    values.update(plan.templates)
    return {k: v for k, v in values.items() if k not in plan.swept_parameters}


def prove_cells(theorem_name: str, values: Mapping, cells, **kw) -> list:
    """Neighbouring cells one after the other, each trying first the choices that closed the one before
    (a search of the choices costs more than a chain): [(k, result of :func:`prove_cell`)]."""
    out, hint = [], None
    for k, bounds in cells:
        res = prove_cell(theorem_name, values, bounds, hint=hint, **kw)
        found = json.loads(res["choices"]) if res["choices"] else []
        hint = found[0] if found else hint
        out.append((k, res))
    return out


def prove_cell(theorem_name: str, values: Mapping, bounds: Mapping, *, max_boxes: int = PROVE_MAX_BOXES,
               equilibrium: Mapping | None = None, check: bool = True, hint: Mapping | None = None) -> dict:
    """The chain of a theorem over one cell: {status, choices, detail, fraction, envelope}.

    A cell that reaches inadmissible values (a matrix not positive definite at its edge) is
    ``undecided`` with the reason; a proved cell gets its in-region run (``check``).
    """
    from ..catalogue.boxrun import BoxStatus, run_over_box
    from ..catalogue.loader import find_items

    (theorem,) = find_items(theorem_name)
    try:
        rep = run_over_box(theorem, dict(values), dict(bounds), max_boxes=max_boxes, hint=hint)
    except InputError as exc:
        return {"status": "undecided", "choices": "", "detail": f"not checked: {exc}", "fraction": "0",
                "envelope": np.nan}
    out = {"status": rep.status.value, "detail": rep.verdict[:400], "fraction": str(rep.proved_fraction),
           "choices": json.dumps([p.choices for p in rep.proved]), "envelope": np.nan}
    if rep.status is BoxStatus.ESTABLISHED and check and equilibrium is not None:
        out["envelope"] = max(in_region_run(theorem, values, piece, equilibrium) for piece in rep.proved)
    return out


def _constants(report) -> dict:
    return {r.name: float(r.value["value"]) for r in report.results
            if isinstance(r.value, dict) and isinstance(r.value.get("value"), (int, float))}


def in_region_run(theorem, values: Mapping, piece, equilibrium: Mapping, *, t_end: float = CHECK_T_END) -> float:
    """The largest ratio output / certified envelope along a run from inside the certified region.

    Raises
    ------
    InternalError
        The run leaves the envelope (a proved cell whose simulation contradicts its certificate).
    """
    from ..simulate import simulate
    from ..simulate.envelope import cross_check

    from ..certify.decay_model import Envelope

    decay = theorem.decay
    consts = _constants(piece.report)
    delta = consts.get("delta_tilde")
    envelopes = [Envelope(r.name.split(" ", 1)[1], d=r.value["d"], kappa=r.value["rate"], p=r.value["p"])
                 for r in piece.report.results if r.name.startswith("envelope ") and isinstance(r.value, dict)]
    if delta is None or not envelopes:
        return np.nan
    centre = piece.box.center()
    names = set(theorem.parameters.names)
    rep = {sympy.Symbol(n): v for n, v in centre.items() if n not in names}
    at = {k: (v.xreplace(rep) if isinstance(v, (sympy.Basic, sympy.MatrixBase)) else v) for k, v in values.items()}
    at.update({n: v for n, v in centre.items() if n in names})
    at.update({k: v for k, v in piece.choices.items()})
    resolved = theorem.parameters.resolve(at, use_defaults=True)
    history, chi = _history(theorem.system, resolved, equilibrium, delta / 2)
    traj = simulate(theorem.system, history=history, t_end=t_end, values=at)
    measures = {m.name: m for step in theorem.steps for m in step.measures}
    worst = 0.0
    tt = traj.t - traj.t[0]
    for env in envelopes:
        mname = decay.outputs[env.name]
        series = _measure_series(measures[mname], theorem.system, resolved, traj)
        chk = cross_check(tt, series, env(tt, chi), name=f"{env.name} of {theorem.qualified_name}", rtol=1e-6)
        if chk.first_violation is not None:
            raise InternalError(f"{theorem.qualified_name} is established on {piece.box}, but the run at its centre "
                                f"from ‖χ‖ = {chi:.3g} < δ̃ = {delta:.3g} leaves the certified envelope "
                                f"{env.text()} of {mname} at t = {chk.first_violation:.4g} (ratio "
                                f"{chk.max_ratio:.4g}); a bug of lkverify")
        worst = max(worst, chk.max_ratio)
    return worst


def _history(system, values, equilibrium, chi: float):
    """A constant history at distance ‖χ‖ = chi from the equilibrium (R^n Euclidean over every state)."""
    sub = system.parameters.substitution(values)
    rng = np.random.default_rng(0)
    base, dirs = {}, {}
    for state in system.states:
        eq = equilibrium.get(state.name, [0] * state.dim)
        if isinstance(eq, str):
            eq = values[eq]
        v = np.array([float(sympy.sympify(x).xreplace(sub)) for x in sympy.Matrix(eq)], dtype=float)
        d = rng.normal(size=state.dim)
        if state.unit:
            d -= d.dot(v) * v
        base[state.name], dirs[state.name] = v, d / np.linalg.norm(d)
    scale = chi / np.sqrt(len(system.states))  # each state at chi/√k: Σ ‖x_i − x_eq‖² = chi²
    history, total = {}, 0.0
    for state in system.states:
        v, d = base[state.name], dirs[state.name]
        if state.unit:  # a rotation by the angle whose chord is `scale`
            angle = 2 * np.arcsin(scale / 2)
            x = np.cos(angle) * v + np.sin(angle) * d
        else:
            x = v + scale * d
        total += float(np.sum((x - v) ** 2))
        history[state.name] = x.tolist()
    return history, float(np.sqrt(total))


def _measure_series(measure, system, values, traj) -> np.ndarray:
    """A norm measure ‖v(t)‖ along a trajectory (v in the states at t, parameters substituted)."""
    from sympy.core.function import AppliedUndef

    if measure.kind != "norm":
        raise InputError(f"the decay output {measure.name} is not a norm at t")
    sub = system.parameters.substitution(values)
    vec = sympy.Matrix(measure.vector).xreplace(sub)
    funcs = sorted(vec.atoms(AppliedUndef), key=str)
    where = system.state_functions()
    args = []
    for f in funcs:
        state, i = where[f.func]
        args.append(traj.states[state.name][:, i])
    dummies = [sympy.Dummy() for _ in funcs]
    fn = sympy.lambdify(dummies, vec.xreplace(dict(zip(funcs, dummies))), "numpy")
    vals = np.asarray(fn(*args), dtype=float).reshape(vec.shape[0], -1)
    return np.sqrt(np.sum(vals ** 2, axis=0))


def prove_grid(plan, grid, checks: Mapping, options, deadline=None, progress=None) -> dict:
    """The proved columns of a sweep: per theorem, every cell where its hypotheses hold at the grid point
    is run (on the sweep's Dask cluster, or in this process with ``scheduler="synchronous"``); a cell
    whose grid point fails a hypothesis is ``failed`` (that point is in the cell), an invalid one
    ``undecided``.  A worker's InternalError (a proved cell whose run leaves its envelope) is raised."""
    import time

    values = theorem_values(plan)
    equilibrium = getattr(plan.example, "equilibrium", None)
    n = grid.size
    out = {}
    jobs = []
    for th in plan.theorems:
        status = np.full(n, "undecided", dtype=object)
        applies = np.asarray(checks[f"applies:{th.short}"], dtype=bool)
        valid = np.asarray(checks["valid"], dtype=bool)
        status[valid & ~applies] = "failed"
        out[f"proved:{th.short}"] = status
        out[f"proved_choices:{th.short}"] = np.full(n, "", dtype=object)
        out[f"proved_envelope:{th.short}"] = np.full(n, np.nan)
        jobs += [(th.short, th.name, k) for k in np.flatnonzero(applies & valid)]

    start, count = time.monotonic(), [0]

    def record(short, k, res):
        out[f"proved:{short}"][k] = res["status"]
        out[f"proved_choices:{short}"][k] = res["choices"]
        out[f"proved_envelope:{short}"][k] = res["envelope"]
        count[0] += 1
        if progress is not None:
            progress(count[0], len(jobs), time.monotonic() - start)

    kw = dict(max_boxes=options.prove_max_boxes, equilibrium=equilibrium)
    tasks = _segments(jobs, grid, options)
    if options.scheduler == "synchronous":   # in order, each cell hinting the next one's choices
        for short, name, ks in tasks:
            for k in ks:
                if deadline is not None and time.monotonic() > deadline:
                    return out
                hint = _last_choices(out, short, ks, k)
                record(short, k, prove_cell(name, values, cell_box(grid, k), hint=hint, **kw))
        return out
    from ..parallel import run_tasks

    submitted = {i: (name, values, [(k, cell_box(grid, k)) for k in ks], kw) for i, (_, name, ks) in enumerate(tasks)}
    for i, cells, exc in run_tasks(_prove_cells_kw, submitted, options, deadline=deadline):
        short, _, ks = tasks[i]
        if exc is not None:
            for k in ks:
                record(short, k, {"status": "undecided", "choices": "", "envelope": np.nan,
                                  "detail": f"failed on a worker: {type(exc).__name__}: {exc}"})
            continue
        for k, res in cells:
            record(short, k, res)
    return out


def _prove_cells_kw(name, values, cells, kw):
    """:func:`prove_cells` with its keyword options as one argument (a task of :func:`lkverify.parallel.run_tasks`)."""
    return prove_cells(name, values, cells, **kw)


#: cells per task of a proved sweep at most (run in order along the first axis, each hinting the next)
SEGMENT = 4


#: the fewest tasks a proved sweep is cut into (when it has that many cells), whatever the number of workers
MIN_TASKS = 8


def _segments(jobs, grid, options) -> list:
    """The jobs as runs of neighbouring cells along the first axis: [(short, name, [k, …])].

    Runs of at most :data:`SEGMENT` cells, shorter when there would be fewer than :data:`MIN_TASKS`
    tasks (the hints save searches, the balance between workers saves more on a small grid).  The
    runs depend on the grid alone, never on the number of workers: a cell's hint (the choices of the
    cell before it in its run) decides which choices are tried first, so a map is the same map on
    any number of workers, and in process.

    >>> from types import SimpleNamespace
    >>> from lkverify.sweep.grid import Grid
    >>> g = Grid.parse(["b=0:1:4", "h=0:1:6"])
    >>> jobs = [("t", "x.t", k) for k in range(g.size)]
    >>> [ks for _, _, ks in _segments(jobs, g, SimpleNamespace(workers=1, scheduler=None))][:2]
    [[0, 6, 12], [18]]
    >>> one, four = SimpleNamespace(workers=1, scheduler=None), SimpleNamespace(workers=4, scheduler=None)
    >>> _segments(jobs, g, one) == _segments(jobs, g, four)
    True
    """
    size = max(1, min(SEGMENT, len(jobs) // MIN_TASKS))
    rows: dict = {}
    for short, name, k in jobs:
        idx = grid.index(k)
        rows.setdefault((short, name, idx[1:]), []).append(k)
    out = []
    for (short, name, _), ks in rows.items():
        ks = sorted(ks, key=lambda k: grid.index(k)[0])
        out += [(short, name, ks[i:i + size]) for i in range(0, len(ks), size)]
    return out


def _last_choices(out, short, ks, k):
    """The choices of the cell before ``k`` in its segment (None for the first or when it found none)."""
    i = ks.index(k)
    if i == 0:
        return None
    text = out[f"proved_choices:{short}"][ks[i - 1]]
    found = json.loads(text) if text else []
    return found[0] if found else None
