"""``lkverify sweep ITEM --grid NAME=START:STOP:N … [--set …] [--t-end T]``: the command line of a sweep.

Input is checked before anything is computed (item, names, values, grid, output paths,
scheduler address); the sweep then prints a progress bar on stderr, writes the Parquet
table and the map, and prints a report: points per simulated class, where each theorem's
hypotheses hold, the linearisation's verdicts, and the paper's gains in the plane with the
outcome simulated at each (compared with what the figure shows).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from ..errors import InputError
from ..status import Status

# NumPy, the engine and the report are imported where they are used: ``lkverify --help`` reads HELP and builds no
# sweep (the command line adds the arguments, add_arguments, when ``sweep`` is parsed or its help shown)

__all__ = ["HELP", "add_arguments", "add_parser", "run"]

EXAMPLE = 'lkverify sweep aleksandrov2023.fig1 --set "F=diag(h,h,h)" --grid b=-3:3:61 --grid h=0.1:2:40'

#: the one-line help of ``lkverify sweep``
HELP = ("map where in the gain plane a theorem applies and the system converges: hypotheses, linear margin and "
        "simulation at every grid point, on Dask; e.g. " + EXAMPLE)


def add_parser(sub, *, quiet, seconds, json_help) -> None:
    """Register ``sweep`` on the subcommand parser ``sub``."""
    add_arguments(sub.add_parser("sweep", help=HELP), quiet=quiet, seconds=seconds, json_help=json_help)


def add_arguments(p, *, quiet, seconds, json_help) -> None:
    """The arguments of ``lkverify sweep`` on its parser ``p``."""
    from .engine import DEFAULT_CHUNK_SIZE

    p.add_argument("item", help="a catalogued example with one run, e.g. aleksandrov2023.fig1")
    p.add_argument("--grid", dest="grids", action="append", default=[], metavar="NAME=START:STOP:N",
                   help="a swept name: N values from START to STOP (read exactly); repeat for a plane")
    p.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value; it may use swept names, e.g. F=diag(h,h,h) with --grid h=0.1:2:40")
    p.add_argument("--t-end", type=float, default=None, metavar="T", help="horizon of every run (default: the example's)")
    p.add_argument("--out", default=None, metavar="FILE.parquet",
                   help="the table, one row per point (default sweep-ITEM.parquet in the current folder)")
    p.add_argument("--plot", default=None, metavar="FILE.png",
                   help="the map (default: the table's name with .png); PNG, PDF or SVG by the suffix")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="a running Dask scheduler (tcp://host:8786); default: in this process for a sweep of "
                        "fewer than 300 points to simulate (lkverify.sweep.engine.IN_PROCESS_POINTS) unless "
                        "--workers is given, else a local cluster, one worker per core; 'local': a local cluster "
                        "whatever the size; 'synchronous': no cluster, in this process")
    p.add_argument("--workers", type=int, default=None, metavar="N", help="workers of the local cluster (default: cores)")
    p.add_argument("--chunk-size", type=int, default=DEFAULT_CHUNK_SIZE, metavar="N",
                   help=f"points per task (default {DEFAULT_CHUNK_SIZE})")
    p.add_argument("--fresh", action="store_true", help="discard finished chunks of an earlier run of this sweep "
                   "(by default they are reused: an interrupted sweep resumes)")
    p.add_argument("--budget", type=seconds, default=None, metavar="SECONDS",
                   help="time budget of the sweep; unfinished points are then undecided (a rerun resumes)")
    p.add_argument("--max-steps", type=int, default=10**6, metavar="N",
                   help="step budget of one run; a run needing more is undecided (default 1e6)")
    p.add_argument("--prove", action="store_true",
                   help="also run each catalogued theorem's chain for every point of each grid cell (a box): the "
                        "columns proved:THEOREM and the proved layer of the map")
    p.add_argument("--prove-max-boxes", type=int, default=3, metavar="N",
                   help="pieces of one cell's subdivision with --prove (default 3)")
    p.add_argument("--json", action="store_true", help=json_help)
    quiet(p)


def run_chunk(sim, points, valid):
    """:func:`lkverify.sweep.evaluate.run_chunk` (imported on first use; a test replaces this name)."""
    from .evaluate import run_chunk as evaluate

    return evaluate(sim, points, valid)


def run(args, *, check_output_path, emit) -> int:
    """Run ``lkverify sweep`` from parsed ``args``; returns the exit code."""
    from .engine import SweepOptions, check_table_path, sweep

    if not args.grids:
        raise InputError(f"sweep: expected at least one --grid NAME=START:STOP:N; e.g. {EXAMPLE}")
    if args.t_end is not None and not (math.isfinite(args.t_end) and args.t_end > 0):
        raise InputError(f"--t-end: expected a positive finite number, got {args.t_end}")
    if args.max_steps is not None and args.max_steps < 1:
        raise InputError(f"--max-steps: expected a whole number ≥ 1, got {args.max_steps}")
    out = check_table_path(args.out or f"sweep-{Path(args.item).name.replace('::', '.')}.parquet")
    plot = args.plot or str(out.with_suffix(".png"))
    check_output_path(plot)
    options = SweepOptions(t_end=args.t_end, chunk_size=args.chunk_size, scheduler=args.scheduler,
                           workers=args.workers, budget=args.budget, fresh=args.fresh, max_steps=args.max_steps,
                           prove=args.prove, prove_max_boxes=args.prove_max_boxes)
    from ..report.progress import Progress

    bar = Progress("sweep", unit="points", enabled=not args.quiet)
    cells = Progress("prove", unit="cells", enabled=not args.quiet)
    result = sweep(args.item, grid=args.grids, sets=args.sets, out=out, options=options, progress=bar,
                   prove_progress=cells)
    bar.close()
    cells.close()
    marks = _marks(result)
    meta = {**result.meta, "marks": [m for m, _ in marks]}
    figure_note = _figure(result, meta, plot)
    return emit([_report(result, marks, plot, figure_note)], json_out=args.json)


def _marks(result: SweepResult) -> list:
    """The paper's gains in the swept plane: (mark description, Mark) with the outcome simulated there.

    Each mark is simulated at its exact gains over its own figure's horizon (what the figure
    shows), whatever the sweep's ``--t-end``; the map's class at the nearest grid point is
    reported beside it.
    """
    import dataclasses

    import numpy as np

    from ..catalogue.loader import find_items
    from .marks import paper_marks

    plan = result.plan
    found = paper_marks(plan.example, plan.grid.names, plan.templates, fixed=plan.fixed,
                        history=plan.example.runs[0].history)
    out = []
    sim = plan.simulation
    for m in found:
        horizon = float(find_items(m.item)[0].t_end)
        own = dataclasses.replace(sim, t_end=horizon, t_eval=np.linspace(0.0, horizon, len(sim.t_eval)))
        pt = np.array([[float(m.coords[n]) for n in plan.grid.names]])
        cols = run_chunk(own, pt, np.array([True]))
        observed = str(cols["simulated"][0])
        region = _region_at(result, plan.grid, m.coords)
        out.append(({"label": m.label, "item": m.item, "coords": {k: float(v) for k, v in m.coords.items()},
                     "exact": {k: str(v) for k, v in m.coords.items()}, "expected": m.expected,
                     "observed": observed, "region": region, "t_end": horizon,
                     "t_to_level": float(cols["t_to_level"][0]),
                     "final_distance": float(cols["final_distance"][0])}, m))
    return out


def _region_at(result: SweepResult, grid, coords) -> str:
    """The simulated class of the grid point nearest to ``coords``, or "outside the grid"."""
    import numpy as np

    idx = []
    for a in grid.axes:
        x = float(coords[a.name])
        vals = np.array([float(v) for v in a.values])
        half = 0.5 * (abs(vals[-1] - vals[0]) / (a.n - 1) if a.n > 1 else 0.0)
        if x < vals.min() - half - 1e-12 or x > vals.max() + half + 1e-12:
            return "outside the grid"
        idx.append(int(np.argmin(np.abs(vals - x))))
    k = int(np.ravel_multi_index(tuple(idx), grid.shape))
    return str(result.table.column("simulated")[k].as_py())


def _agrees(expected: str, observed: str):
    if expected == "converges":
        return observed == "converged"
    if expected == "does not converge":
        return observed in ("bounded", "diverged")
    return None


def _figure(result: SweepResult, meta: dict, plot: str) -> str:
    from .figure import plot_map

    try:
        plot_map(result.table, meta, plot)
    except InputError as exc:
        return f"no map: {exc}"
    return ""


def _report(result: SweepResult, marks, plot: str, figure_note: str) -> Report:
    import numpy as np

    from ..report.results import Report, Result
    from .evaluate import CLASSES

    meta = result.meta
    n = result.table.num_rows
    grid_text = " × ".join(f"{a['name']} ∈ [{a['start']}, {a['stop']}] ({a['n']})" for a in meta["grid"])
    counts = ", ".join(f"{c} {result.counts[c]}" for c in CLASSES if result.counts[c])
    results = [Result("simulation", "sweep", Status.SIMULATED if result.complete else Status.UNDECIDED,
                      {c: result.counts[c] for c in CLASSES},
                      f"{n} points ({grid_text}), t_end = {meta['t_end']:g}: {counts}"
                      + ("" if result.complete else "; incomplete (budget spent or a chunk failed): rerun to resume")
                      + (f"; reused {result.reused} finished chunk(s)" if result.reused else ""))]
    valid = np.asarray(result.table.column("valid").to_pylist(), dtype=bool)
    for th, names in meta["theorems"].items():
        applies = np.asarray(result.table.column(f"applies:{th}").to_pylist(), dtype=bool)
        where = f"at {int(applies.sum())} of {int(valid.sum())} valid points" if applies.any() else "nowhere on this grid"
        status = Status(meta["theorem_status"][th])
        how = {Status.EXACT: "decided exactly at each point",
               Status.CERTIFIED: "decided at each point, some by interval enclosures or on float inputs",
               Status.UNDECIDED: "undecided at some points, counted as not holding there"}[status]
        results.append(Result("hypothesis", f"{th}: {' and '.join(names)}", status, int(applies.sum()),
                              f"the hypotheses hold {where} ({how})"))
    for th, counts in meta.get("proved", {}).items():
        proved = np.asarray(result.table.column(f"proved:{th}").to_pylist(), dtype=object) == "established"
        applies = np.asarray(result.table.column(f"applies:{th}").to_pylist(), dtype=bool)
        inside = bool(np.all(applies[proved]))
        frac = f"{proved.sum() / applies.sum():.0%} of the hypotheses' cells" if applies.any() else "no cell"
        results.append(Result("bound", f"{th}: proved for every point of the cell", Status.CERTIFIED if inside
                              else Status.FAILED, dict(counts),
                              f"cells established {counts['established']} ({frac}), failed {counts['failed']}, "
                              f"undecided {counts['undecided']}; every proved cell's run from inside its certified "
                              f"region stayed under its envelope"
                              + ("" if inside else "; a proved cell outside the hypotheses' region (a bug)")))
    verdicts = np.asarray(result.table.column("linear_verdict").to_pylist(), dtype=object)
    if meta["linear"]:
        results.append(Result("linear", "linearisation", Status.UNDECIDED, None, meta["linear"]))
    else:
        vc = {v: int(np.sum(verdicts == v)) for v in ("stable", "unstable", "critical")}
        results.append(Result("linear", "linearisation", Status.ESTIMATED, vc,
                              "spectral abscissa at every valid point: " + ", ".join(f"{k} {v}" for k, v in vc.items())))
    for m, _ in marks:
        ok = _agrees(m["expected"], m["observed"])
        at = ", ".join(f"{k} = {v}" for k, v in m["exact"].items())
        status = Status.SIMULATED if ok or ok is None else Status.FAILED
        results.append(Result("simulation", f"{m['label']} ({at})", status, m["observed"],
                              f"simulated {m['observed']} at the paper's gains to t = {m['t_end']:g} (the figure's "
                              f"horizon); the figure: {m['expected'] or '—'}; the map at t = {meta['t_end']:g}, "
                              f"nearest point: {m['region']}"))
    where = f"table {result.path} ({n} rows)" + ("" if figure_note else f", map {plot}")
    verdict = (f"{'complete' if result.complete else 'incomplete'}: {where}; {result.seconds:.1f} s"
               + (f"; {figure_note}" if figure_note else ""))
    params = {"grid": [f"{a['name']}={a['start']}:{a['stop']}:{a['n']}" for a in meta["grid"]], **meta["fixed"],
              **meta["sets"], "t_end": meta["t_end"]}
    return Report(meta["item"], params, tuple(results), verdict)
