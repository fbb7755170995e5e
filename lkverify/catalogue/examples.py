"""Numerical examples of the papers as catalogue items.

An :class:`Example` holds one or more :class:`~lkverify.simulate.experiments.Run`
objects, the quantities the paper plots, a convergence measure, and the
:class:`~lkverify.simulate.experiments.RunClaim` objects stating what the paper says
about the runs.  Running it integrates the runs and checks the claims; the
vocabulary of runs and claims lives in :mod:`lkverify.simulate.experiments`.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..errors import InputError
from ..options import Budget, Deadline
from ..report.results import Report, Result
from ..simulate.control import StepControl
from ..simulate.envelope import EnvelopeCheck, cross_check
from ..simulate.figures import AngleHistory, convention_name, plain, plot_runs, resolved_values, show_value
from ..simulate.experiments import EnvelopeSpec, Run, RunSummary, Series, _time_to, along, reach_text
# transitional: proof modules written before the move import the run claims from here; new code
# imports them from lkverify.simulate (lkverify.simulate.experiments)
from ..simulate.experiments import (BoundedNotAttractive, Converges, DoesNotConverge, FasterThan,  # noqa: F401
                                    Sensitive, SmootherThan)
from ..simulate.runs import MAX_STEPS, Trajectory, prepare_run, simulate
from ..simulate.rigidbody import DEFAULT_CONVENTION
from ..simulate.solver import Outcome
from ..status import Status
from .items import Item

#: default time budget of a simulation of an example (all its runs together), seconds
DEFAULT_SIMULATE_BUDGET = 600.0

__all__ = ["DEFAULT_SIMULATE_BUDGET", "Example", "MAX_STEPS"]


class Example(Item):
    """A catalogue item reproducing a paper's numerical example.

    Parameters
    ----------
    name, title : str
    runs : sequence of Run
    t_end : float
    series : sequence of Series
        What the paper plots.
    distance : callable
        ``distance(states)`` → array, the distance to the equilibrium used for
        "converged" and the times to reach 1e-2 and 1e-3.
    claims : sequence of RunClaim
    ylabel : str
    envelope : EnvelopeSpec, optional
    samples : int
        Output samples per run (dense output between steps).
    plot_until : float, optional
        The figure shows [0, plot_until] (the paper's horizon); claims use the whole run.
    step : StepControl
        Tolerances and step limits of every run.
    equilibrium : mapping, optional
        State name → value of the equilibrium the distance measures convergence to (as
        :func:`lkverify.linear.linearise` takes it); ``lkverify sweep`` linearises there.
    caption : callable, optional
        ``caption(values, history, convention, overridden)`` → the figure title (mathtext),
        computed from the resolved values and the history of the first run (``overridden``: the
        states ``--history`` replaced).  An example with a caption reports its resolved values
        and names its runs after the values and histories used (:meth:`with_options`).
    run_caption : callable, optional
        ``run_caption(label, values, history, convention, overridden)`` → the label of one run
        (examples with several runs).
    initial : AngleHistory, optional
        The initial data as aircraft angles (rebuilt for ``--convention``).
    distances : mapping, optional
        Named distances for the convergence claims, ``{"combined": f, "per-vector": g}``
        (``--distance``); ``distance`` defaults to the combined one.
    vectors : sequence of (label, callable), optional
        The per-vector distances ‖s_i − r_i‖ drawn on the distance panel.
    targets : sequence of float, optional
        Target values of the plotted series (drawn as dashed lines).
    envelope_caption, ylabel_tex : str, optional
        Mathtext forms of the envelope (its panel's title) and of the y label.
    distance_panel : bool, optional
        Draw the log distance over the whole run below each run's series (default: when
        ``distances`` are named); see :func:`lkverify.simulate.figures.plot_runs`.

    Examples
    --------
    x' = −a x(t − τ) from x ≡ 1, with the claim that it converges:

    >>> from lkverify import Equation, Parameters, Series, System, Term, Vector, t
    >>> from lkverify.simulate import Converges, Run
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); system = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> ex = Example("user.decay", runs=[Run("x ≡ 1", system, {"a": "1/2"}, {"x": [1]})], t_end=40,
    ...              series=[Series("x", lambda S: S["x"][:, 0])], distance=lambda S: abs(S["x"][:, 0]),
    ...              claims=[Converges("x ≡ 1", tol=1e-3)], samples=401)
    >>> report = ex.run()
    >>> [(r.name, str(r.status)) for r in report.results]
    [('run x ≡ 1', 'simulated'), ('x ≡ 1: converges', 'simulated')]
    >>> report.holds
    True
    """

    def __init__(self, name: str, *, runs: Sequence[Run], t_end: float, series: Sequence[Series],
                 distance: Callable | None = None, claims: Sequence = (), title: str = "", ylabel: str = "",
                 envelope: EnvelopeSpec | None = None, samples: int = 4001, logy: bool = False,
                 step: StepControl = StepControl(), paper: str = "", plot_until: float | None = None,
                 equilibrium: Mapping | None = None, caption: Callable | None = None,
                 run_caption: Callable | None = None, initial: AngleHistory | None = None,
                 distances: Mapping | None = None, vectors: Sequence = (), targets: Sequence | None = None,
                 envelope_caption: str = "", ylabel_tex: str = "", distance_panel: bool | None = None):
        distances = dict(distances or {})
        if distance is None:
            distance = distances.get("combined")
        if distance is None:
            raise InputError(f"example {name}: expected a distance (distance=callable, or distances with a "
                             f"'combined' entry), got none")
        if not runs:
            raise InputError(f"example {name}: expected at least one run; pass runs=[Run(label, system, values, "
                             f"history)]")
        if not isinstance(step, StepControl):
            raise InputError(f"example {name}: step: expected a StepControl, got {type(step).__name__}")
        self.name = name
        self.title = title
        self.runs = tuple(runs)
        self.t_end = float(t_end)
        self.series = tuple(series)
        self.distance = distance
        self.claims = tuple(claims)
        self.ylabel = ylabel
        self.envelope = envelope
        self.samples = samples
        self.logy = logy
        self.step = step
        self.paper = paper
        self.plot_until = plot_until
        self.equilibrium = None if equilibrium is None else dict(equilibrium)
        self.caption = caption
        self.run_caption = run_caption
        self.initial = initial
        self.distances = distances
        self.distance_name = "combined" if distances else None
        self.vectors = tuple(vectors)
        self.targets = None if targets is None else tuple(targets)
        self.envelope_caption = envelope_caption
        self.ylabel_tex = ylabel_tex
        self.distance_panel = bool(distances) if distance_panel is None else bool(distance_panel)
        self.convention = DEFAULT_CONVENTION if initial is not None else None
        self.overridden: dict = {}     # state name → the --history value that replaced the catalogue's
        self.user_values: dict = {}

    # -- options ---------------------------------------------------------------------------
    def with_options(self, values: Mapping | None = None, *, histories: Mapping | None = None,
                     convention: str | None = None, distance: str | None = None) -> "Example":
        """A copy whose runs carry the values and histories used (so claims and envelope see them).

        ``convention`` rebuilds the angle-given initial data (:class:`AngleHistory`) in that
        convention; ``histories`` then replace states of it; ``distance`` picks one of the named
        ``distances`` for the convergence claims.  An example with a caption names its runs after
        the values and data used.

        Raises
        ------
        InputError
            An unknown convention or distance.
        """
        ex = copy.copy(self)
        conv = convention_name(convention) if convention is not None else self.convention
        if distance is not None:
            if distance not in self.distances:
                raise InputError(f"--distance: expected one of {', '.join(self.distances)}, got {distance!r}"
                                 if self.distances else
                                 f"--distance: {self.qualified_name} has a single distance (no named ones); "
                                 f"got {distance!r}; omit --distance")
            ex.distance = self.distances[distance]
            ex.distance_name = distance
        runs = []
        for run in self.runs:
            hist = dict(run.history)
            if self.initial is not None and convention is not None:
                hist.update(self.initial.history(conv))
            hist.update(dict(histories or {}))
            runs.append(dataclasses.replace(run, history=hist))
        ex.runs = tuple(runs)
        ex.convention = conv if self.initial is not None else None
        ex.overridden = {k: v for k, v in dict(histories or {}).items()}
        ex.user_values = dict(values or {})
        if (values or histories or convention is not None) and (self.caption or self.run_caption):
            ex._relabel()
        return ex

    def _relabel(self) -> None:
        """Name the runs (and the claims and envelope that refer to them) after the values and data used."""
        new = {}
        for run in self.runs:
            if len(self.runs) == 1:
                new[run.label] = plain(self.title_for())
            elif self.run_caption is not None:
                new[run.label] = plain(self.label_for(run.label))
        if len(set(new.values())) != len(new):  # two runs would get one name: keep the catalogue's
            return
        self.runs = tuple(dataclasses.replace(r, label=new.get(r.label, r.label)) for r in self.runs)

        def moved(obj):
            if not dataclasses.is_dataclass(obj):
                return obj
            changes = {f.name: new[getattr(obj, f.name)] for f in dataclasses.fields(obj)
                       if f.name in ("run", "a", "b") and isinstance(getattr(obj, f.name), str)
                       and getattr(obj, f.name) in new}
            return dataclasses.replace(obj, **changes) if changes else obj

        self.claims = tuple(moved(c) for c in self.claims)
        if self.envelope is not None:
            self.envelope = moved(self.envelope)

    # -- captions --------------------------------------------------------------------------
    def title_for(self, values: Mapping | None = None) -> str:
        """The figure title computed from the values and history of the first run."""
        run = self.runs[0]
        vals = resolved_values(run, values if values is not None else self.user_values)
        if self.caption is not None:
            return self.caption(vals, dict(run.history), self.convention, set(self.overridden))
        title = self.title or self.qualified_name
        changed = values if values is not None else self.user_values
        if changed:
            title += " with " + ", ".join(f"{k} = {show_value(vals[k])}" for k in changed if k in vals)
        return title

    def label_for(self, label: str, values: Mapping | None = None) -> str:
        """The label of a run computed from its values and history."""
        run = next(r for r in self.runs if r.label == label)
        if self.run_caption is None:
            return label
        vals = resolved_values(run, values if values is not None else self.user_values)
        return self.run_caption(label, vals, dict(run.history), self.convention, set(self.overridden))

    def chi_used(self) -> float:
        """‖χ‖_τ of the envelope's run, from the history used (after --history and --convention)."""
        e = self.envelope
        run = next(r for r in self.runs if r.label == e.run)
        return float(e.chi(run))

    # -- simulation ------------------------------------------------------------------------
    def prepare(self, values: Mapping | None = None, *, t_end: float | None = None,
                histories: Mapping | None = None) -> None:
        """Check every run before integrating any (values, coefficients on the horizon, histories, step floor).

        Raises
        ------
        InputError
            The first problem found, in one line.
        """
        t_end = self.t_end if t_end is None else float(t_end)
        for run in self.runs:
            prepare_run(run.system, history={**dict(run.history), **dict(histories or {})}, t_end=t_end,
                        values={**dict(run.values), **dict(values or {})}, step=self.step)

    def simulate(self, values: Mapping | None = None, *, t_end: float | None = None,
                 histories: Mapping | None = None, progress: Callable[[str], None] | None = None,
                 fraction: Callable | None = None, deadline: Deadline | None = None) -> dict[str, Trajectory]:
        """Integrate every run.

        User ``values`` override the runs' parameter values and ``histories`` their
        initial histories (state name → constant vector); ``fraction(label)`` may
        return a callable receiving the fraction of each run done (a progress bar).
        ``deadline`` is shared by the runs: once it has passed, the current run stops
        with outcome ``budget`` and later runs are not started (outcome ``budget``,
        no samples beyond t0).
        """
        given = t_end is not None
        t_end = self.t_end if t_end is None else float(t_end)
        out = {}
        for k, run in enumerate(self.runs):
            vals = {**dict(run.values), **dict(values or {})}
            hist = {**dict(run.history), **dict(histories or {})}
            horizon = t_end
            while True:
                if progress:
                    progress(f"{self.qualified_name}: run {k + 1}/{len(self.runs)} {run.label} to t = {horizon:g}")
                samples = max(self.samples, int(round(self.samples * horizon / t_end)))
                tr = simulate(run.system, history=hist, t_end=horizon, values=vals, step=self.step,
                              t_eval=np.linspace(0.0, horizon, samples),
                              progress=fraction(run.label) if fraction else None, deadline=deadline)
                u = run.until
                if given or u is None or tr.outcome is not Outcome.SUCCESS or horizon >= float(u.t_max):
                    break  # a user's --t-end is kept as given
                if float(np.asarray(u.distance(tr))[-1]) < float(u.tol):
                    break
                horizon = min(2 * horizon, float(u.t_max))
            out[run.label] = tr
        return out

    def summary(self, label: str, tr: Trajectory) -> RunSummary:
        d = np.asarray(along(self.distance, tr.states, tr.values), dtype=float)
        finals = {s.label: float(np.asarray(along(s.fn, tr.states, tr.values))[-1]) for s in self.series}
        t1, t2 = _time_to(tr.t, d, 1e-2), _time_to(tr.t, d, 1e-3)
        return RunSummary(label, tr.outcome, bool(tr.outcome is Outcome.SUCCESS and d[-1] < 1e-3), t1, t2,
                          float(d[-1]), finals, float(np.max(d)), tr.constraint_drift, tr.n_steps, tr.seconds,
                          float(tr.t[-1]), tr.integrator)

    def check_envelope(self, trajectories: Mapping[str, Trajectory]) -> EnvelopeCheck | None:
        if self.envelope is None:
            return None
        e = self.envelope
        tr = trajectories[e.run]
        run = next(r for r in self.runs if r.label == e.run)
        chi = float(e.chi(run))
        q = np.asarray(along(e.quantity.fn, tr.states, tr.values), dtype=float)
        return cross_check(tr.t, q, np.asarray(e.bound(tr.t, chi), dtype=float), name=e.label)

    def run(self, values: Mapping | None = None, *, budget: Budget | float | None = None, t_end: float | None = None,
            progress: Callable[[str], None] | None = None, envelope: bool = True,
            trajectories: Mapping[str, Trajectory] | None = None) -> Report:
        """Simulate (all runs share ``budget``, the caller's own cap), summarise every run and check every claim.

        The runs are bounded by their step limits (deterministic); ``budget`` (seconds, default None)
        cuts them short (outcome ``budget``, undecided).
        """
        if trajectories is None:
            trajectories = self.simulate(values, t_end=t_end, progress=progress,
                                         deadline=Budget.of(budget).deadline(cap=True) if budget is not None else None)
        results, cut = self._run_results(trajectories)
        self._claim_results(trajectories, cut, envelope, results)
        failed = [r.name for r in results if r.status is Status.FAILED]
        undecided = [r.name for r in results if r.status is Status.UNDECIDED]
        verdict = (f"failed: {', '.join(failed)}" if failed else
                   f"undecided: a run stopped before t_end (time budget or step floor): {', '.join(undecided)}"
                   if undecided else
                   f"every claim observed along the simulated trajectories (status simulated: observed, not proved)")
        if self.caption is not None:  # its captions show the resolved values: so does its report (common to every run)
            per_run = [{k: show_value(v) for k, v in resolved_values(r, values).items()} for r in self.runs]
            params = {k: v for k, v in per_run[0].items() if all(p.get(k) == v for p in per_run[1:])}
        else:
            params = {k: str(v) for k, v in (values or {}).items()}
        return Report(self.qualified_name, params, tuple(results), verdict)

    def _run_results(self, trajectories):
        """One result per run; the runs cut short (budget, step floor), by label."""
        results = []
        cut = {}
        for label, tr in trajectories.items():
            s = self.summary(label, tr)
            ok = s.outcome is Outcome.SUCCESS
            if not s.outcome.reached_end:  # not integrated to the end: nothing observed
                cut[label] = tr
                status = Status.UNDECIDED
                detail = f"undecided ({s.outcome}): {tr.message}; distance {s.final_distance:.3g} at t = {s.t_end:g}"
            elif not ok:
                status = Status.FAILED
                when = f" at t = {tr.t_fail:.6g}" if tr.t_fail is not None else ""
                detail = f"{s.outcome}{when}: {tr.message}"
            else:
                status = Status.SIMULATED
                which = getattr(self, "distance_name", None)
                detail = (f"{s.outcome}; {'converged' if s.converged else 'not converged'}: distance "
                          f"{s.final_distance:.3g} at t = {s.t_end:g}{f' ({which})' if which else ''}; "
                          f"{reach_text(1e-2, s.t_1e2, s.t_end)}, {reach_text(1e-3, s.t_1e3, s.t_end)}")
            value = s.to_json()
            value["t_fail"] = tr.t_fail
            value["message"] = tr.message
            if getattr(self, "distance_name", None):
                value["distance"] = self.distance_name
            results.append(Result("simulation", f"run {label}", status, value, detail))
        return results, cut

    def _claim_results(self, trajectories, cut, envelope, results) -> None:
        for claim in self.claims:
            if cut:
                results.append(Result("simulation", claim.name, Status.UNDECIDED, None,
                                      f"not checked: run(s) {', '.join(cut)} stopped before t_end "
                                      f"({', '.join(sorted({tr.outcome.value for tr in cut.values()}))})"))
                continue
            results.append(claim.check(self, trajectories))
        if envelope and self.envelope is not None and cut:
            results.append(Result("envelope", self.envelope.label, Status.UNDECIDED, None,
                                  "not checked: a run stopped before t_end (time budget or step floor)"))
        elif envelope and self.envelope is not None:
            chk = self.check_envelope(trajectories)
            detail = (f"max trajectory/envelope = {chk.max_ratio:.4g} at t = {chk.t_max_ratio:.4g}"
                      + (f"; first violation at t = {chk.first_violation:.4g}" if chk.first_violation is not None
                         else "; no violation at the samples"))
            results.append(Result("envelope", chk.name, chk.status, chk.to_json(), detail))

    # -- figures ---------------------------------------------------------------------------
    def plot(self, trajectories: Mapping[str, Trajectory], path, *, envelope: bool = False) -> None:
        """Write the figure (PNG, or PDF/SVG by the suffix of ``path``), drawn by :func:`~lkverify.simulate.figures.plot_runs`.

        Per run the plotted series (and, with ``distance_panel``, the log distance over the whole
        run); with ``envelope=True`` a log-scale panel of the envelope against the trajectory.
        """
        from ..simulate.figures import _tex

        show_env = envelope and self.envelope is not None
        title = self.title_for() if self.caption is not None else _tex(self.title_for())
        labels = {k: self.label_for(k) for k in trajectories} if len(trajectories) > 1 else None
        plot_runs(trajectories, path, title=title, series=self.series, distance=self.distance, run_labels=labels,
                  plot_until=self.plot_until, ylabel=self.ylabel_tex or _tex(self.ylabel), logy=self.logy,
                  targets=self.targets, distance_panel=self.distance_panel, distance_name=self.distance_name,
                  vectors=self.vectors, envelope=self.envelope if show_env else None,
                  chi=self.chi_used() if show_env else None, envelope_caption=self.envelope_caption)
