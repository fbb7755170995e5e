"""Numerical examples of the papers as catalogue items.

An :class:`Example` holds one or more :class:`~lkverify.simulate.experiments.Run`
objects, the quantities the paper plots, a convergence measure, and the
:class:`~lkverify.simulate.experiments.RunClaim` objects stating what the paper says
about the runs.  Running it integrates the runs and checks the claims; the
vocabulary of runs and claims lives in :mod:`lkverify.simulate.experiments`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..errors import InputError
from ..options import Budget, Deadline
from ..report.results import Report, Result
from ..simulate.control import StepControl
from ..simulate.envelope import EnvelopeCheck, cross_check
from ..simulate.experiments import EnvelopeSpec, Run, RunSummary, Series, _time_to, along, reach_text
# transitional: proof modules written before the move import the run claims from here; new code
# imports them from lkverify.simulate (lkverify.simulate.experiments)
from ..simulate.experiments import (BoundedNotAttractive, Converges, DoesNotConverge, FasterThan,  # noqa: F401
                                    Sensitive, SmootherThan)
from ..simulate.runs import MAX_STEPS, Trajectory, prepare_run, simulate
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
                 distance: Callable, claims: Sequence = (), title: str = "", ylabel: str = "",
                 envelope: EnvelopeSpec | None = None, samples: int = 4001, logy: bool = False,
                 step: StepControl = StepControl(), paper: str = "", plot_until: float | None = None,
                 equilibrium: Mapping | None = None):
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
        t_end = self.t_end if t_end is None else float(t_end)
        out = {}
        for k, run in enumerate(self.runs):
            vals = {**dict(run.values), **dict(values or {})}
            hist = {**dict(run.history), **dict(histories or {})}
            if progress:
                progress(f"{self.qualified_name}: run {k + 1}/{len(self.runs)} {run.label} to t = {t_end:g}")
            t_eval = np.linspace(0.0, t_end, self.samples)
            out[run.label] = simulate(run.system, history=hist, t_end=t_end, values=vals, step=self.step,
                                      t_eval=t_eval,
                                      progress=fraction(run.label) if fraction else None, deadline=deadline)
        return out

    def summary(self, label: str, tr: Trajectory) -> RunSummary:
        d = np.asarray(along(self.distance, tr.states, tr.values), dtype=float)
        finals = {s.label: float(np.asarray(along(s.fn, tr.states, tr.values))[-1]) for s in self.series}
        t1, t2 = _time_to(tr.t, d, 1e-2), _time_to(tr.t, d, 1e-3)
        return RunSummary(label, tr.outcome, bool(tr.outcome is Outcome.SUCCESS and d[-1] < 1e-3), t1, t2,
                          float(d[-1]), finals, float(np.max(d)), tr.constraint_drift, tr.n_steps, tr.seconds,
                          float(tr.t[-1]))

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
        """Write the figure (PNG, or PDF/SVG by the suffix of ``path``): each series against t, a panel per run.

        The shared style of the catalogue's figures: the whole simulated interval (the paper's
        window, ``plot_until``, shaded), mathtext labels, legends outside the axes, and with
        ``envelope=True`` a log-scale panel of the envelope against the trajectory.
        """
        from matplotlib.figure import Figure  # no pyplot: the backend (and a notebook's inline one) is left alone

        from ..simulate.figures import _tex

        show_env = envelope and self.envelope is not None
        n = len(trajectories) + (1 if show_env else 0)
        fig = Figure(figsize=(9.0, 3.0 * n), layout="constrained")
        axes = fig.subplots(n, 1, squeeze=False)[:, 0]
        title = self.title or self.qualified_name
        fig.suptitle(_tex(title), fontsize=10)
        for ax, (label, tr) in zip(axes, trajectories.items()):
            for s in self.series:
                ax.plot(tr.t, np.asarray(along(s.fn, tr.states, tr.values), dtype=float), lw=1.2, label=_tex(s.label))
            T = float(tr.t[-1])
            if self.plot_until is not None and float(self.plot_until) < T:
                ax.axvspan(float(tr.t[0]), float(self.plot_until), color="0.85", alpha=0.5, lw=0,
                           label=f"the paper's window t ≤ {float(self.plot_until):g}")
            ax.set_title(("" if label == title else _tex(label) + ": ") + f"t ∈ [{float(tr.t[0]):g}, {T:g}]",
                         fontsize=9)
            ax.set_xlabel("$t$")
            ax.set_ylabel(_tex(self.ylabel))
            if self.logy:
                ax.set_yscale("log")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        if show_env:
            e = self.envelope
            tr = trajectories[e.run]
            run = next(r for r in self.runs if r.label == e.run)
            chi = float(e.chi(run))
            ax = axes[-1]
            q = np.asarray(along(e.quantity.fn, tr.states, tr.values), dtype=float)
            ax.semilogy(tr.t, np.maximum(q, 1e-300), lw=1.2, label=_tex(e.quantity.label) + " (trajectory)")
            ax.semilogy(tr.t, np.asarray(e.bound(tr.t, chi), dtype=float), "--", lw=1.2, label="envelope")
            ax.set_title(_tex(e.label) + rf",  $\|\chi\|_\tau = {chi:.4g}$", fontsize=9)
            ax.set_xlabel("$t$")
            ax.set_ylabel(_tex(e.quantity.label))
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        fig.savefig(path, dpi=110)
