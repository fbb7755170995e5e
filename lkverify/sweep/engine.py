"""Run a sweep on Dask: chunks of points as tasks, each chunk kept on disk as it finishes.

:func:`sweep` is the entry point of ``lkverify sweep``.  The plan (:mod:`.plan`) is built
once on the client; the exact checks per point (parameter hypotheses, theorem hypotheses)
run there too, cached by the values they depend on; the simulations and linear margins run
on the Dask workers, one task per chunk of ``chunk_size`` points.

* Scheduler: by default a ``distributed.LocalCluster`` with one single-threaded worker
  process per core; ``scheduler="tcp://host:8786"`` uses an existing cluster;
  ``scheduler="synchronous"`` runs the chunks in this process, one after the other (no Dask
  cluster: the serial reference the parallel runs are tested against).
* Resumable: chunk ``k`` is written to ``OUT.parts/chunk-00000k.parquet`` as soon as it
  finishes, tagged with the sweep's fingerprint (item, values, grid, horizon, tolerances,
  chunk size, lkverify version); a rerun of the same sweep reuses the finished chunks and
  computes only the others.  Chunks are fixed by ``chunk_size``, not by the number of
  workers, and every point is computed on its own, so the table is the same for any
  number of workers.
* Budget: when ``budget`` seconds have passed, unfinished chunks are cancelled; their
  points are ``undecided`` in the table and the result says the sweep is incomplete (a
  rerun resumes it).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..report.files import check_writable_file
from .evaluate import CLASSES, run_chunk
from ..parallel import prepare, run_tasks
from .grid import Grid
from .plan import Plan, PointChecks, build_plan, holds, sub_grids, weakest

__all__ = ["SweepOptions", "SweepResult", "sweep", "DEFAULT_CHUNK_SIZE"]

#: points per task: large enough that Dask's per-task overhead (a few ms) stays below 1 % of a chunk
DEFAULT_CHUNK_SIZE = 64


#: a sweep with fewer points to simulate runs in this process (a Dask cluster's start, about 10 s, would
#: cost more than the second worker saves), unless a scheduler or a number of workers is given
IN_PROCESS_POINTS = 300


@dataclasses.dataclass(frozen=True)
class SweepOptions:
    """Options of :func:`sweep`.

    Attributes
    ----------
    t_end : float, optional
        Horizon of every run (default: the example's).
    samples : int
        Output samples per run (the distance is classified on them).
    rtol, atol : float
        Step control of every run.
    level : float
        A point has converged when its distance stays below ``level`` from some time on.
    max_steps : int
        Step budget of one run; a run needing more is ``undecided``.
    chunk_size : int
        Points per task.
    scheduler : str, optional
        None: in this process for fewer than :data:`IN_PROCESS_POINTS` points to simulate (unless
        ``workers`` is given), else a LocalCluster; "local": a LocalCluster whatever the size;
        "synchronous": in this process; else a scheduler address.
    workers : int, optional
        Worker processes of the LocalCluster (default: the number of cores).
    budget : float, optional
        Seconds for the whole sweep; unfinished chunks are then undecided.
    fresh : bool
        Discard finished chunks of an earlier run of this sweep instead of reusing them.
    prove : bool
        Also run each catalogued theorem's chain over every cell (:mod:`lkverify.sweep.prove`):
        the columns ``proved:T``, ``proved_choices:T``, ``proved_envelope:T``.
    prove_max_boxes : int
        Pieces of one cell's subdivision.

    Examples
    --------
    >>> SweepOptions(workers=2).chunk_size, SweepOptions(scheduler="synchronous").scheduler
    (64, 'synchronous')
    >>> SweepOptions(chunk_size=0)
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: --chunk-size: expected a whole number ≥ 1, got 0
    """

    t_end: float | None = None
    samples: int = 1001
    rtol: float = 1e-8
    atol: float = 1e-10
    level: float = 1e-2
    max_steps: int = 10**6
    chunk_size: int = DEFAULT_CHUNK_SIZE
    scheduler: str | None = None
    workers: int | None = None
    budget: float | None = None
    fresh: bool = False
    prove: bool = False
    prove_max_boxes: int = 3

    def __post_init__(self):
        if not (isinstance(self.prove_max_boxes, int) and self.prove_max_boxes >= 1):
            raise InputError(f"--prove-max-boxes: expected a whole number ≥ 1, got {self.prove_max_boxes!r}")
        if not (isinstance(self.chunk_size, int) and self.chunk_size >= 1):
            raise InputError(f"--chunk-size: expected a whole number ≥ 1, got {self.chunk_size!r}")
        if self.workers is not None and not (isinstance(self.workers, int) and self.workers >= 1):
            raise InputError(f"--workers: expected a whole number ≥ 1, got {self.workers!r}")
        if not (isinstance(self.samples, int) and self.samples >= 11):
            raise InputError(f"samples: expected a whole number ≥ 11, got {self.samples!r}")
        if not (0 < self.level < math.inf):
            raise InputError(f"level: expected a positive number, got {self.level!r}")


@dataclasses.dataclass(frozen=True)
class SweepResult:
    """The outcome of :func:`sweep`.

    Attributes
    ----------
    item : str
    path : Path
        The Parquet table (one row per point).
    table : pyarrow.Table
    meta : dict
        The sweep's description (also in the table's metadata, key ``lkverify.sweep``).
    counts : dict
        Points per simulated class.
    complete : bool
        False when the budget ran out (some points undecided; a rerun resumes).
    reused : int
        Chunks taken from an earlier run.
    seconds : float
    errors : tuple of str
        Chunks that failed on a worker (their points are undecided; a rerun retries them).
    plan : Plan
        What was swept (the example, its values, the compiled simulation).
    timings : dict
        Seconds spent building the plan (SymPy, once), on the exact checks, and running the chunks
        (``simulation``: cluster start, compilation on the workers and the simulations; ``cluster
        start`` alone).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> res = sweep("aleksandrov2023.fig1", grid=["b=-2:2:2"], out=pathlib.Path(tempfile.mkdtemp()) / "s.parquet",
    ...             options=SweepOptions(scheduler="synchronous"))
    >>> res.complete, res.counts["converged"], res.counts["bounded"], res.path.suffix
    (True, 1, 1, '.parquet')
    """

    item: str
    path: Path
    table: object
    meta: dict
    counts: dict
    complete: bool
    reused: int
    seconds: float
    errors: tuple = ()
    plan: object = None
    timings: dict = dataclasses.field(default_factory=dict)

    def _repr_html_(self) -> str:
        """Jupyter: the item, the points per simulated class and where the table is."""
        import html

        rows = "".join(f"<tr><td>{html.escape(str(k))}</td><td>{v}</td></tr>" for k, v in self.counts.items())
        state = "complete" if self.complete else "incomplete (budget spent; a rerun resumes)"
        return (f"<div><p><b>sweep of {html.escape(self.item)}</b>: {self.table.num_rows} points, {state}, "
                f"{self.seconds:.1f} s</p><table><tr><th>class</th><th>points</th></tr>{rows}</table>"
                f"<p>table: <code>{html.escape(str(self.path))}</code></p></div>")


def sweep(item, *, grid: Sequence[str] | Grid, sets: Sequence[str] = (), out, options: SweepOptions = SweepOptions(),
          progress: Callable[[int, int, float], None] | None = None,
          prove_progress: Callable[[int, int, float], None] | None = None) -> SweepResult:
    """Sweep ``item`` over ``grid`` and write the table to ``out`` (Parquet).

    Parameters
    ----------
    item : str
        A catalogued example with one run (``aleksandrov2023.fig1``).
    grid : sequence of str or Grid
        ``NAME=START:STOP:N`` per axis.
    sets : sequence of str
        ``NAME=VALUE`` overrides; a value may use the swept names (``F=diag(h,h,h)``).
    out : path
        The table; finished chunks are kept in ``out + ".parts"`` until the table is written.
    options : SweepOptions
    progress : callable, optional
        ``progress(points_done, points_total, seconds)`` after every finished chunk.
    prove_progress : callable, optional
        ``prove_progress(cells_done, cells_total, seconds)`` after every proved cell (``options.prove``).

    Raises
    ------
    InputError
        Bad item, names, values, grid, output path or scheduler address (nothing computed).

    Notes
    -----
    The default LocalCluster's workers fork from a fork server on Linux and are new Python processes
    elsewhere (Dask's ``spawn``); either way they import the calling script's main module:
    a script that calls :func:`sweep` must do so under ``if __name__ == "__main__":``, as
    for any Dask cluster started from a script (``lkverify sweep`` does not need it).

    Examples
    --------
    In this process (no cluster), x' = −a x(t − 1) over a: stable iff a < π/2 (a = 1.5 decays too
    slowly to reach 1e-2 by t = 60; a = 2 grows, but stays below the divergence bound 1e6 by then).

    >>> import tempfile, pathlib
    >>> from lkverify import Equation, Example, Parameters, Run, Series, System, Term, Vector, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); system = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> ex = Example("user.decay", runs=[Run("x ≡ 1", system, {}, {"x": [1]})], t_end=60,
    ...              series=[Series("x", lambda S: S["x"][:, 0])], distance=lambda S: abs(S["x"][:, 0]))
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "decay.parquet"
    >>> res = sweep(ex, grid=["a=0.5:2:4"], out=out, options=SweepOptions(scheduler="synchronous"))
    >>> res.table.column("simulated").to_pylist()
    ['converged', 'converged', 'bounded', 'bounded']
    """
    start = time.monotonic()
    grid = grid if isinstance(grid, Grid) else Grid.parse(grid)
    out = check_table_path(out)
    if grid.size >= IN_PROCESS_POINTS or options.workers is not None or options.prove:
        prepare(options, also=_proof_package(item))   # a fork server imports while the plan is made
    plan = build_plan(item, grid=grid, sets=sets, t_end=options.t_end, samples=options.samples, rtol=options.rtol,
                      atol=options.atol, level=options.level, max_steps=options.max_steps)
    timings = {"plan": time.monotonic() - start}
    meta = _meta(plan, options)
    parts = Path(str(out) + ".parts")
    chunks = [np.arange(k, min(k + options.chunk_size, grid.size)) for k in range(0, grid.size, options.chunk_size)]
    done = _finished_chunks(parts, meta["fingerprint"], len(chunks), options.fresh)
    mark = time.monotonic()
    checks = _exact_columns(plan, grid)
    meta["theorem_status"] = checks.pop("_how")      # how each theorem's region was decided (weakest point)
    timings["exact checks"] = time.monotonic() - mark
    todo = [k for k in range(len(chunks)) if k not in done]
    reported = [sum(len(chunks[k]) for k in done)]

    def finished(k, cols):
        _write_chunk(parts, k, meta["fingerprint"], chunks[k], cols)
        done[k] = cols
        reported[0] += len(chunks[k])
        if progress:
            progress(reported[0], grid.size, time.monotonic() - start)

    deadline = None if options.budget is None else start + options.budget
    reused = len(done)
    errors: dict = {}
    mark = time.monotonic()
    if todo:
        _run(plan, grid, chunks, todo, checks["valid"], options, finished, deadline, errors, timings)
    timings["simulation"] = time.monotonic() - mark
    if options.prove:
        from .prove import prove_grid

        mark = time.monotonic()
        checks.update(prove_grid(plan, grid, checks, options, deadline, progress=prove_progress))
        timings["proofs"] = time.monotonic() - mark
        meta["proved"] = {th.short: {st: int(np.sum(checks[f"proved:{th.short}"] == st))
                                     for st in ("established", "failed", "undecided")} for th in plan.theorems}
    complete = len(done) == len(chunks)
    table = _assemble(plan, grid, chunks, done, checks, meta)
    _write_table(table, out)
    if complete:
        _remove_parts(parts)
    counts = {c: int(np.sum(np.asarray(table.column("simulated").to_pylist(), dtype=object) == c)) for c in CLASSES}
    return SweepResult(plan.item, out, table, meta, counts, complete, reused, time.monotonic() - start,
                       tuple(errors.values()), plan, timings)


def _proof_package(item) -> tuple[str, ...]:
    """The shipped proof package of a catalogued item's name (the workers unpickle its objects), or nothing.

    >>> _proof_package("aleksandrov2023.fig1"), _proof_package("my_proof.py::fig")
    (('lkverify.proofs.aleksandrov2023',), ())
    """
    from ..catalogue.loader import proof_module_names

    name = f"lkverify.proofs.{item.split('.')[0]}" if isinstance(item, str) else None
    return (name,) if name in proof_module_names() else ()


# -- the exact part (client) -------------------------------------------------------------------


def _exact_columns(plan: Plan, grid: Grid) -> dict:
    """valid / invalid_reason and, per theorem, applies + margins: exact, on the client, each check on its sub-grid."""
    checks = PointChecks(plan)
    shape = grid.shape
    reason = np.full(shape, "", dtype=object)
    for name, deps in checks.depends.items():
        for idx, point in sub_grids(grid, deps):
            why = checks.reason(name, point)
            block = reason[idx]
            if why and isinstance(block, np.ndarray):       # the first reason found is kept
                block[block == ""] = why
            elif why and block == "":
                reason[idx] = why
    valid = reason == ""
    cols = {}
    how = {}
    for th in plan.theorems:
        applies = valid.copy()
        seen = set()
        for k, h in enumerate(th.hypotheses):
            margin = np.full(shape, np.nan)
            ok = np.zeros(shape, dtype=bool)
            for idx, point in sub_grids(grid, checks.hypothesis_names(h)):
                status, m, decided = checks.hypothesis(h, point)
                margin[idx], ok[idx] = m, holds(status)
                if decided is not None:
                    seen.add(decided)
            applies &= ok
            cols[f"margin:{th.short}:{k}"] = np.where(valid, margin, np.nan).ravel()
        cols[f"applies:{th.short}"] = applies.ravel()
        how[th.short] = weakest(seen).value
    return {"valid": valid.ravel(), "invalid_reason": reason.ravel(), **cols, "_how": how}


# -- running the chunks ------------------------------------------------------------------------------


def _run(plan, grid, chunks, todo, valid, options, finished, deadline, errors, timings) -> None:
    sim = plan.simulation
    points = sum(len(chunks[k]) for k in todo)
    small = options.scheduler is None and options.workers is None and points < IN_PROCESS_POINTS
    if sim.family is not None and not small and options.scheduler != "synchronous":
        # the integrator kernel is compiled once per machine (numba's disk cache): here, before the workers
        # start, rather than by every worker at once on a first run
        from ..simulate import dop853  # noqa: F401
    tasks = {k: (grid.floats(chunks[k]), valid[chunks[k]]) for k in todo}
    # a small sweep runs in process: starting a cluster costs more than it saves
    for k, cols, exc in run_tasks(run_chunk, tasks, options, in_process=small, shared=sim, deadline=deadline,
                                  timings=timings):
        if exc is not None:   # a point the integrator could not take: keep the others
            errors[k] = f"chunk {k} failed: {type(exc).__name__}: {exc}"
            continue
        finished(k, cols)


# -- files -------------------------------------------------------------------------------------------


def check_table_path(out) -> Path:
    """The table's path, refused (InputError) unless it ends in .parquet and can be written there."""
    return check_writable_file(out, option=f"--out {out}", suffixes=(".parquet",))


def _meta(plan: Plan, options: SweepOptions) -> dict:
    from .._version import __version__

    sim = plan.simulation
    meta = {
        "item": plan.item,
        "grid": [{"name": a.name, "start": str(a.start), "stop": str(a.stop), "n": a.n} for a in plan.grid.axes],
        "sets": dict(plan.sets),
        "fixed": {k: str(v) for k, v in plan.fixed.items()},
        "t_end": sim.t_end, "samples": len(sim.t_eval), "rtol": sim.rtol, "atol": sim.atol, "level": sim.level,
        "max_steps": sim.max_steps, "divergence_bound": sim.divergence_bound, "chunk_size": options.chunk_size,
        "theorems": {th.short: [h.name for h in th.hypotheses] for th in plan.theorems},
        "linear": "" if sim.linear is not None else plan.linear_note,
        "simulation": plan.simulation_note or "compiled once, parameters as runtime arguments",
        "lkverify": __version__,
    }
    meta["fingerprint"] = hashlib.sha256(json.dumps(meta, sort_keys=True).encode()).hexdigest()[:16]
    return meta


def _finished_chunks(parts: Path, fingerprint: str, n_chunks: int, fresh: bool) -> dict:
    import pyarrow.parquet as pq

    done = {}
    if not parts.is_dir():
        return done
    for f in sorted(parts.glob("chunk-*.parquet")):
        try:
            tbl = pq.read_table(f)
            same = (tbl.schema.metadata or {}).get(b"lkverify.fingerprint", b"").decode() == fingerprint
        except Exception:   # a chunk cut short while being written: recompute it
            same = False
            tbl = None
        if fresh or not same:
            f.unlink()
            continue
        k = int(f.stem.split("-")[1])
        if k < n_chunks:
            done[k] = {name: _numpy(tbl.column(name)) for name in tbl.column_names if name != "point"}
    return done


def _numpy(column):
    import pyarrow as pa

    if pa.types.is_string(column.type):
        return np.asarray(column.to_pylist(), dtype=object)
    return column.to_numpy()


def _write_chunk(parts: Path, k: int, fingerprint: str, idx, cols) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    parts.mkdir(exist_ok=True)
    data = {"point": np.asarray(idx, dtype=np.int64)}
    data.update({name: _arrow(v) for name, v in cols.items() if name != "seconds"})
    tbl = pa.table(data).replace_schema_metadata({b"lkverify.fingerprint": fingerprint.encode()})
    tmp = parts / f".chunk-{k:06d}.tmp"
    pq.write_table(tbl, tmp)
    os.replace(tmp, parts / f"chunk-{k:06d}.parquet")


def _arrow(v):
    import pyarrow as pa

    v = np.asarray(v)
    return pa.array(v.tolist(), type=pa.string()) if v.dtype == object else pa.array(v)


def _assemble(plan, grid, chunks, done, checks, meta):
    import pyarrow as pa

    n = grid.size
    sim_cols = {"outcome": np.full(n, "", dtype=object), "simulated": np.full(n, "undecided", dtype=object),
                "t_to_level": np.full(n, np.nan), "final_distance": np.full(n, np.nan),
                "max_distance": np.full(n, np.nan), "t_fail": np.full(n, np.nan),
                "n_steps": np.zeros(n, dtype=np.int64), "linear_abscissa": np.full(n, np.nan),
                "linear_verdict": np.full(n, "", dtype=object)}
    for k, cols in done.items():
        for name, col in sim_cols.items():
            col[chunks[k]] = np.asarray(cols[name], dtype=col.dtype)
    not_run = np.ones(n, dtype=bool)
    for k in done:
        not_run[chunks[k]] = False
    sim_cols["outcome"][not_run & checks["valid"]] = "budget"
    sim_cols["simulated"][~checks["valid"]] = "invalid"
    floats = grid.floats()
    data = {"point": np.arange(n, dtype=np.int64)}
    data.update({name: floats[:, j] for j, name in enumerate(grid.names)})
    data.update({f"{name}:exact": texts for name, texts in grid.exact_texts().items()})  # the exact grid values
    data.update({"valid": checks["valid"], "invalid_reason": checks["invalid_reason"]})
    data.update({k: v for k, v in checks.items() if k.startswith(("applies:", "margin:", "proved"))})
    data.update(sim_cols)
    data[f"t_to_{_level(plan.simulation.level)}"] = data.pop("t_to_level")
    tbl = pa.table({k: _arrow(v) for k, v in data.items()})
    return tbl.replace_schema_metadata({b"lkverify.sweep": json.dumps(meta).encode()})


def _level(level: float) -> str:
    return f"{level:.0e}".replace("e-0", "e-").replace("e+0", "e")


def _write_table(table, out: Path) -> None:
    import pyarrow.parquet as pq

    tmp = out.with_name(f".{out.name}.tmp")
    pq.write_table(table, tmp)
    os.replace(tmp, out)


def _remove_parts(parts: Path) -> None:
    if parts.is_dir():
        for f in parts.glob("*"):
            f.unlink()
        parts.rmdir()
