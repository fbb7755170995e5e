"""Numerical examples of the papers as catalogue items: runs, plotted series, claims.

An :class:`Example` holds one or more :class:`Run` objects (a system, parameter
values and an initial history), the quantities the paper plots, a convergence
measure, and :class:`RunClaim` objects stating what the paper says about the
runs ("converges", "does not converge", "bounded but not attractive", "faster
and smoother with the PID").  Checking a claim integrates the runs and returns
a result with status ``simulated`` (observed along numerical trajectories —
never ``exact`` or ``certified``) or ``failed``, with the numbers that show it.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..options import Deadline
from ..simulate.envelope import EnvelopeCheck, cross_check
from .items import Item
from ..report.results import Report, Result
from ..simulate.compile import MAX_STEPS, Trajectory, check_simulation, simulate
from ..status import Status
from ..declare.system import System

#: default time budget of ``lkverify simulate`` (all runs of an example together), seconds
DEFAULT_SIMULATE_BUDGET = 600.0

__all__ = ["Run", "Series", "Example", "RunSummary", "Converges", "DoesNotConverge", "BoundedNotAttractive",
           "FasterThan", "SmootherThan", "Sensitive", "EnvelopeSpec", "DEFAULT_SIMULATE_BUDGET", "MAX_STEPS"]


@dataclasses.dataclass(frozen=True)
class Run:
    """One simulation of an example: a label, a system, parameter values, an initial history."""

    label: str
    system: System
    values: Mapping = dataclasses.field(default_factory=dict)
    history: Mapping = dataclasses.field(default_factory=dict)


@dataclasses.dataclass(frozen=True)
class Series:
    """A plotted quantity: ``fn(states)`` → array over the samples (states: name → (m, dim) array)."""

    label: str
    fn: Callable


@dataclasses.dataclass(frozen=True)
class EnvelopeSpec:
    """A predicted envelope: ``bound(t, chi)`` for the quantity ``quantity(states)``, with ‖χ‖_τ = ``chi``."""

    label: str
    quantity: Series
    bound: Callable
    chi: Callable  # chi(run) -> float, the history norm the envelope is stated in
    run: str


@dataclasses.dataclass(frozen=True)
class RunSummary:
    """What a run did: outcome, convergence, times to reach 1e-2 and 1e-3, final values."""

    label: str
    outcome: str
    converged: bool
    t_1e2: float | None
    t_1e3: float | None
    final_distance: float
    final_series: dict
    max_distance: float
    constraint_drift: dict
    steps: int
    seconds: float
    t_end: float

    def to_json(self) -> dict:
        return dataclasses.asdict(self)


def _time_to(t, d, level) -> float | None:
    """First time after which d stays below level (None if it does not by the end)."""
    above = np.nonzero(d >= level)[0]
    if above.size == 0:
        return float(t[0])
    k = above[-1]
    if k == len(d) - 1:
        return None
    return float(t[k + 1])


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
    """

    def __init__(self, name: str, *, runs: Sequence[Run], t_end: float, series: Sequence[Series],
                 distance: Callable, claims: Sequence = (), title: str = "", ylabel: str = "",
                 envelope: EnvelopeSpec | None = None, samples: int = 4001, logy: bool = False,
                 rtol: float = 1e-8, atol: float = 1e-10, paper: str = "", plot_until: float | None = None):
        if not runs:
            raise ValueError(f"example {name}: expected at least one run")
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
        self.rtol, self.atol = rtol, atol
        self.paper = paper
        self.plot_until = plot_until

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
            check_simulation(run.system, history={**dict(run.history), **dict(histories or {})}, t_end=t_end,
                             values={**dict(run.values), **dict(values or {})})

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
            out[run.label] = simulate(run.system, history=hist, t_end=t_end, values=vals, rtol=self.rtol,
                                      atol=self.atol, t_eval=t_eval,
                                      progress=fraction(run.label) if fraction else None, deadline=deadline)
        return out

    def summary(self, label: str, tr: Trajectory) -> RunSummary:
        d = np.asarray(self.distance(tr.states), dtype=float)
        finals = {s.label: float(np.asarray(s.fn(tr.states))[-1]) for s in self.series}
        t1, t2 = _time_to(tr.t, d, 1e-2), _time_to(tr.t, d, 1e-3)
        return RunSummary(label, tr.outcome.value, bool(tr.outcome.value == "success" and d[-1] < 1e-3), t1, t2,
                          float(d[-1]), finals, float(np.max(d)), tr.constraint_drift, tr.n_steps, tr.seconds,
                          float(tr.t[-1]))

    def check_envelope(self, trajectories: Mapping[str, Trajectory]) -> EnvelopeCheck | None:
        if self.envelope is None:
            return None
        e = self.envelope
        tr = trajectories[e.run]
        run = next(r for r in self.runs if r.label == e.run)
        chi = float(e.chi(run))
        q = np.asarray(e.quantity.fn(tr.states), dtype=float)
        return cross_check(tr.t, q, np.asarray(e.bound(tr.t, chi), dtype=float), name=e.label)

    def run(self, values: Mapping | None = None, *, budget: float | None = None, t_end: float | None = None,
            progress: Callable[[str], None] | None = None, envelope: bool = True,
            trajectories: Mapping[str, Trajectory] | None = None) -> Report:
        """Simulate, summarise every run and check every claim."""
        if trajectories is None:
            trajectories = self.simulate(values, t_end=t_end, progress=progress,
                                         deadline=Deadline(budget) if budget is not None else None)
        results = []
        cut = {}
        for label, tr in trajectories.items():
            s = self.summary(label, tr)
            ok = s.outcome == "success"
            if s.outcome in ("budget", "step_collapse"):  # not integrated to the end: nothing observed
                cut[label] = tr
                status = Status.UNDECIDED
                detail = f"undecided ({s.outcome}): {tr.message}; distance {s.final_distance:.3g} at t = {s.t_end:g}"
            elif not ok:
                status = Status.FAILED
                when = f" at t = {tr.t_fail:.6g}" if tr.t_fail is not None else ""
                detail = f"{s.outcome}{when}: {tr.message}"
            else:
                status = Status.SIMULATED
                detail = (f"{s.outcome}; {'converged' if s.converged else 'not converged'}: distance "
                          f"{s.final_distance:.3g} at t = {s.t_end:g}; reaches 1e-2 at {_fmt(s.t_1e2)}, "
                          f"1e-3 at {_fmt(s.t_1e3)}")
            value = s.to_json()
            value["t_fail"] = tr.t_fail
            value["message"] = tr.message
            results.append(Result("simulation", f"run {label}", status, value, detail))
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
        failed = [r.name for r in results if r.status is Status.FAILED]
        undecided = [r.name for r in results if r.status is Status.UNDECIDED]
        verdict = (f"failed: {', '.join(failed)}" if failed else
                   f"undecided: a run stopped before t_end (time budget or step floor): {', '.join(undecided)}"
                   if undecided else
                   f"every claim observed along the simulated trajectories (status simulated: observed, not proved)")
        params = {k: str(v) for k, v in (values or {}).items()}
        return Report(self.qualified_name, params, tuple(results), verdict)

    # -- figures ---------------------------------------------------------------------------
    def plot(self, trajectories: Mapping[str, Trajectory], path, *, envelope: bool = False) -> None:
        """Write a PNG in the paper's style: each plotted series against t, one panel per run."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        show_env = envelope and self.envelope is not None
        n = len(trajectories) + (1 if show_env else 0)
        fig, axes = plt.subplots(n, 1, figsize=(7.5, 3.2 * n), squeeze=False)
        for ax, (label, tr) in zip(axes[:, 0], trajectories.items()):
            k = len(tr.t) if self.plot_until is None else int(np.searchsorted(tr.t, self.plot_until, side="right"))
            for s in self.series:
                ax.plot(tr.t[:k], np.asarray(s.fn(tr.states))[:k], lw=1.2, label=s.label)
            title = self.title or self.qualified_name
            ax.set_title(title if label == title else f"{title}\n{label}", fontsize=10)
            ax.set_xlabel("t")
            ax.set_ylabel(self.ylabel)
            if self.logy:
                ax.set_yscale("log")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8, loc="best")
        if show_env:
            e = self.envelope
            tr = trajectories[e.run]
            run = next(r for r in self.runs if r.label == e.run)
            chi = float(e.chi(run))
            ax = axes[-1, 0]
            ax.semilogy(tr.t, np.asarray(e.quantity.fn(tr.states)), lw=1.2, label=e.quantity.label)
            ax.semilogy(tr.t, np.asarray(e.bound(tr.t, chi)), "--", lw=1.2, label=e.label)
            ax.set_title(f"envelope vs trajectory (‖χ‖_τ = {chi:.4g})", fontsize=10)
            ax.set_xlabel("t")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


def _fmt(x) -> str:
    return "never" if x is None else f"t = {x:.4g}"


def _damping_expr(h):
    """The damping as a SymPy expression in t (accepts an expression or a string, parsed safely)."""
    import sympy

    from ..declare.parse import parse_value
    from ..declare.symbols import t

    expr = parse_value(h, name="damping", variables={"t": t}) if isinstance(h, str) else sympy.sympify(h)
    if expr.free_symbols - {t}:
        raise ValueError(f"damping: expected an expression in t, got {expr}")
    return expr


def _tail_integral(h, T: float) -> float:
    """∫_T^∞ h(t) dt, exactly by SymPy (inf when it diverges)."""
    import sympy

    from ..declare.symbols import t

    val = sympy.integrate(_damping_expr(h), (t, sympy.nsimplify(T), sympy.oo))
    return float("inf") if val in (sympy.oo, sympy.zoo) or not val.is_finite else float(val)


# -- claims about runs --------------------------------------------------------------------------
class RunClaim:
    """A statement a paper makes about a run; ``check`` returns a simulation Result."""

    name = "claim"

    def check(self, example: Example, trajectories: Mapping[str, Trajectory]) -> Result:  # pragma: no cover
        raise NotImplementedError

    def _res(self, ok: bool, value, detail: str) -> Result:
        return Result("simulation", self.name, Status.SIMULATED if ok else Status.FAILED, value, detail)


@dataclasses.dataclass(frozen=True)
class Converges(RunClaim):
    """The distance to the equilibrium ends below ``tol`` and the run succeeded."""

    run: str
    tol: float = 1e-3
    by: float | None = None  # ... and is below tol by this time

    @property
    def name(self):
        return f"{self.run}: converges"

    def check(self, example, trajectories):
        s = example.summary(self.run, trajectories[self.run])
        ok = s.outcome == "success" and s.final_distance < self.tol
        if self.by is not None:
            t_tol = _time_to(trajectories[self.run].t, np.asarray(example.distance(trajectories[self.run].states)), self.tol)
            ok = ok and t_tol is not None and t_tol <= self.by
        return self._res(ok, {"final_distance": s.final_distance, "t_1e2": s.t_1e2, "t_1e3": s.t_1e3},
                         f"distance {s.final_distance:.3g} at t = {s.t_end:g} (need < {self.tol:g}"
                         + (f" by t = {self.by:g}" if self.by is not None else "") + f"); 1e-3 reached at {_fmt(s.t_1e3)}")


@dataclasses.dataclass(frozen=True)
class DoesNotConverge(RunClaim):
    """Over the last ``tail`` fraction of the run the distance stays above ``floor``."""

    run: str
    floor: float = 1e-2
    tail: float = 0.25

    @property
    def name(self):
        return f"{self.run}: does not converge"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        d = np.asarray(example.distance(tr.states))
        k = int(len(d) * (1 - self.tail))
        lo = float(np.min(d[k:]))
        ok = tr.outcome.value == "success" and lo > self.floor
        return self._res(ok, {"min_distance_tail": lo, "t_from": float(tr.t[k])},
                         f"min distance over t ∈ [{tr.t[k]:.4g}, {tr.t[-1]:.4g}] is {lo:.3g} (need > {self.floor:g})")


@dataclasses.dataclass(frozen=True)
class BoundedNotAttractive(RunClaim):
    """Bounded, and the energy tends to a positive limit (Remark 2 of paper 001).

    With damping h, Remark 2's inequality −α̃ h Ṽ ≤ dṼ/dt gives Ṽ(∞) ≥ Ṽ(T) exp(−α̃ ∫_T^∞ h).
    The rate α̃ is *measured*: the largest ln(Ṽ(a)/Ṽ(b)) / ∫_a^b h over consecutive windows of
    the second half of the run; the extrapolated lower bound Ṽ(T) exp(−α̃ ∫_T^∞ h) must exceed
    ``fraction`` · Ṽ(T).  For a non-integrable h the tail is infinite and the bound is 0, so the
    claim fails, as it should for an attractive equilibrium.
    """

    run: str
    measure: Callable
    damping: object  # the damping h as an expression in t (or a string)
    bound: float
    fraction: float = 1e-3
    windows: int = 8

    @property
    def name(self):
        return f"{self.run}: bounded but not attractive"

    def check(self, example, trajectories):
        import scipy.integrate
        import sympy

        from ..declare.symbols import t as tsym

        h = sympy.lambdify([tsym], _damping_expr(self.damping), modules="numpy")
        tr = trajectories[self.run]
        d = np.asarray(example.distance(tr.states))
        E = np.asarray(self.measure(tr.states))
        edges = np.linspace(tr.t[-1] / 2, tr.t[-1], self.windows + 1)
        idx = np.searchsorted(tr.t, edges).clip(0, len(tr.t) - 1)
        rates = []
        for i, j in zip(idx[:-1], idx[1:]):
            H = scipy.integrate.quad(h, tr.t[i], tr.t[j], limit=200)[0]
            rates.append(np.log(E[i] / E[j]) / H)
        rate = max(0.0, float(max(rates)))
        tail = _tail_integral(self.damping, float(tr.t[-1]))
        lower = float(E[-1] * np.exp(-rate * tail)) if np.isfinite(tail) else 0.0
        ok = tr.outcome.value == "success" and float(np.max(d)) <= self.bound and lower > self.fraction * E[-1]
        return self._res(ok, {"max_distance": float(np.max(d)), "measured_rate": rate, "tail_integral": tail,
                              "energy_end": float(E[-1]), "energy_limit_lower": lower},
                         f"max distance {np.max(d):.3g} (bound {self.bound:g}); measured decay rate α̃ = {rate:.3g} per "
                         f"unit ∫h; ∫_T^∞ h = {tail:.3g}; energy {E[-1]:.3g} at T, limit ≥ {lower:.3g} (extrapolated)")


@dataclasses.dataclass(frozen=True)
class Sensitive(RunClaim):
    """Chaotic-looking: a perturbation of ``perturbation`` in ω's history grows to ``level`` in the plotted series."""

    run: str
    perturbation: float = 1e-8
    level: float = 1e-2

    @property
    def name(self):
        return f"{self.run}: sensitive dependence on the initial data"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        base = next(r for r in example.runs if r.label == self.run)
        hist = dict(base.history)
        hist["omega"] = list(np.asarray(hist["omega"], dtype=float) + self.perturbation)
        other = simulate(base.system, history=hist, t_end=float(tr.t[-1]), values=base.values,
                         rtol=example.rtol, atol=example.atol, t_eval=tr.t)
        sep = np.max([np.abs(np.asarray(s.fn(tr.states)) - np.asarray(s.fn(other.states))) for s in example.series],
                     axis=0)
        k = np.nonzero(sep > self.level)[0]
        t_sep = float(tr.t[k[0]]) if k.size else None
        ok = other.outcome.value == "success" and t_sep is not None
        return self._res(ok, {"perturbation": self.perturbation, "max_separation": float(np.max(sep)),
                              "t_separation": t_sep},
                         f"histories {self.perturbation:g} apart separate to {np.max(sep):.3g} "
                         + (f"(above {self.level:g} from t = {t_sep:.4g})" if t_sep is not None else
                            f"(never above {self.level:g})"))


@dataclasses.dataclass(frozen=True)
class FasterThan(RunClaim):
    """Run ``a`` reaches ``level`` (and stays below) earlier than run ``b``."""

    a: str
    b: str
    level: float = 1e-2

    @property
    def name(self):
        return f"{self.a} reaches {self.level:g} before {self.b}"

    def check(self, example, trajectories):
        ta = _time_to(trajectories[self.a].t, np.asarray(example.distance(trajectories[self.a].states)), self.level)
        tb = _time_to(trajectories[self.b].t, np.asarray(example.distance(trajectories[self.b].states)), self.level)
        ok = ta is not None and (tb is None or ta < tb)
        return self._res(ok, {"t_a": ta, "t_b": tb}, f"{self.a}: {_fmt(ta)}; {self.b}: {_fmt(tb)}")


@dataclasses.dataclass(frozen=True)
class SmootherThan(RunClaim):
    """The plotted series of run ``a`` have fewer local extrema (oscillations) than those of ``b``."""

    a: str
    b: str

    @property
    def name(self):
        return f"{self.a} smoother than {self.b}"

    def check(self, example, trajectories):
        def extrema(tr):
            n = 0
            for s in example.series:
                y = np.asarray(s.fn(tr.states))
                dy = np.diff(y)
                dy = dy[np.abs(dy) > 1e-12 * max(1.0, float(np.max(np.abs(y))))]
                n += int(np.sum(np.sign(dy[1:]) != np.sign(dy[:-1])))
            return n

        na, nb = extrema(trajectories[self.a]), extrema(trajectories[self.b])
        return self._res(na < nb, {"extrema_a": na, "extrema_b": nb},
                         f"local extrema of the plotted series: {self.a} {na}, {self.b} {nb}")
