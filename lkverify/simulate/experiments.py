"""Experiments on simulated runs: what a paper says about its numerical examples.

A :class:`Run` is one simulation (a system, parameter values, an initial history);
:class:`Series` a plotted quantity; :class:`EnvelopeSpec` a predicted decay envelope.
A :class:`RunClaim` states what the paper says about runs ("converges", "does not
converge", "bounded but not attractive", "faster", "smoother", "sensitive"); checking
one returns a :class:`~lkverify.report.results.Result` with status ``simulated``
(observed along numerical trajectories — never ``exact`` or ``certified``) or
``failed``, with the numbers that show it.  :class:`RunSummary` is what one run did.

The catalogue item that holds runs and claims is :class:`lkverify.catalogue.examples.Example`.

>>> import numpy as np
>>> _time_to(np.array([0.0, 1.0, 2.0]), np.array([1.0, 0.5, 0.001]), 1e-2)
2.0
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping

import numpy as np

from ..errors import InputError
from ..report.results import Result
from ..status import Status
from ..declare.system import System
from .runs import Trajectory, simulate
from .solver import Outcome

__all__ = ["BoundedNotAttractive", "Converges", "DoesNotConverge", "EnvelopeSpec", "FasterThan", "FromValues", "Run", "along",
           "RunClaim", "RunSummary", "Sensitive", "Series", "SmootherThan", "Until"]


@dataclasses.dataclass(frozen=True)
class FromValues:
    """A quantity along a run that depends on the run's parameter values.

    ``build(values)`` returns ``f(states)``; the claims call it with the run's resolved
    values (:attr:`lkverify.simulate.runs.Trajectory.values`), so that an energy or a
    distance follows ``J``, ``r1``… set by the user instead of retyping the defaults.

    >>> energy = FromValues(lambda v: (lambda states: v["k"] * states["x"][:, 0] ** 2))
    >>> import numpy as np
    >>> float(along(energy, {"x": np.array([[2.0]])}, {"k": 3})[0])
    12.0
    """

    build: Callable

    def bind(self, values: Mapping) -> Callable:
        return self.build(values)


def along(quantity, states: Mapping, values: Mapping | None = None):
    """``quantity(states)``, binding a :class:`FromValues` quantity to ``values`` first.

    Examples
    --------
    >>> import numpy as np
    >>> states = {"x": np.array([[1.0], [-2.0]])}
    >>> along(lambda s: np.abs(s["x"][:, 0]), states).tolist()          # a plain callable
    [1.0, 2.0]
    >>> along(FromValues(lambda v: lambda s: v["k"] * s["x"][:, 0]), states, {"k": 10}).tolist()
    [10.0, -20.0]
    """
    if isinstance(quantity, FromValues):
        quantity = quantity.bind(dict(values or {}))
    return quantity(states)


@dataclasses.dataclass(frozen=True)
class Run:
    """One simulation of an example: a label, a system, parameter values, an initial history.

    ``values`` override the parameters' defaults for this run only; an
    :class:`~lkverify.catalogue.examples.Example` integrates each of its runs.

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> runs = [Run("a = 1", sys, {"a": 1, "tau": "1/10"}, {"x": [1]}),
    ...         Run("a = 1/10", sys, {"a": "1/10", "tau": "1/10"}, {"x": [1]})]
    >>> ex = Example("demo", runs=runs, t_end=10, series=[], distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> [(r.name, r.status.value, r.value["converged"]) for r in ex.run().results]
    [('run a = 1', 'simulated', True), ('run a = 1/10', 'simulated', False)]
    """

    label: str
    system: System
    values: Mapping = dataclasses.field(default_factory=dict)
    history: Mapping = dataclasses.field(default_factory=dict)
    until: "Until | None" = None


@dataclasses.dataclass(frozen=True)
class Until:
    """Run on until ``distance(trajectory)`` (an array over the samples) ends below ``tol``.

    The example's horizon is doubled (the run integrated again from t0, the sample density kept)
    until the last sample is below ``tol`` or the horizon reaches ``t_max``; the claims then report
    the time from which the signal stays below its target.

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); x = Vector("x", 1); sys = System([Equation(x, [Term(-x(t)[0] / 10)])], parameters=P)
    >>> slow = Run("slow", sys, {}, {"x": [1]}, until=Until(lambda tr: abs(tr.states["x"][:, 0]), 1e-3, t_max=200))
    >>> tr = Example("demo", runs=[slow], t_end=10, series=[], distance=lambda s: abs(s["x"][:, 0]),
    ...              samples=101).simulate()["slow"]
    >>> float(tr.t[-1]), bool(abs(tr.states["x"][-1, 0]) < 1e-3)     # e^(−t/10) < 1e-3 needs t > 69
    (80.0, True)
    """

    distance: object
    tol: float
    t_max: float

    def __post_init__(self):
        from ..errors import InputError

        if not (float(self.tol) > 0 and float(self.t_max) > 0):
            raise InputError(f"Until: expected tol > 0 and t_max > 0, got tol = {self.tol}, t_max = {self.t_max}")


@dataclasses.dataclass(frozen=True)
class Series:
    """A plotted quantity: ``fn(states)`` → array over the samples (states: name → (m, dim) array).

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.simulate import simulate
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-x(t - 1)[0])])], parameters=Parameters())
    >>> tr = simulate(sys, history={"x": [1]}, t_end=2.0, t_eval=[0.0, 1.0, 2.0])
    >>> square = Series("x²", lambda s: s["x"][:, 0] ** 2)
    >>> [round(float(v), 10) for v in along(square.fn, tr.states)]   # x = 1, 0, −1/2 at t = 0, 1, 2
    [1.0, 0.0, 0.25]
    """

    label: str
    fn: Callable


@dataclasses.dataclass(frozen=True)
class EnvelopeSpec:
    """A predicted envelope: ``bound(t, chi)`` for the quantity ``quantity(states)``, with ‖χ‖_τ = ``chi``.

    ``valid_below``: the envelope is claimed only for ‖χ‖_τ below it (the estimate's region, e.g. 0.28
    for (15) as printed); a history outside it is said so in the figure.

    Examples
    --------
    An :class:`~lkverify.catalogue.examples.Example` checks it along the named run:

    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> env = EnvelopeSpec("e^(−t/2)", Series("|x|", lambda s: abs(s["x"][:, 0])),
    ...                    bound=lambda tt, chi: chi * np.exp(-tt / 2), chi=lambda run: 1.0, run="r")
    >>> ex = Example("demo", runs=[Run("r", sys, {"tau": "1/10"}, {"x": [1]})], t_end=10, series=[],
    ...              distance=lambda s: abs(s["x"][:, 0]), envelope=env, samples=201)
    >>> chk = ex.check_envelope(ex.simulate())
    >>> chk.status.value, chk.max_ratio, chk.t_max_ratio, chk.first_violation   # tight at t = 0 only
    ('simulated', 1.0, 0.0, None)
    """

    label: str
    quantity: Series
    bound: Callable
    chi: Callable  # chi(run) -> float, the history norm the envelope is stated in
    run: str
    valid_below: float | None = None


@dataclasses.dataclass(frozen=True)
class RunSummary:
    """What a run did: outcome, convergence, times to reach 1e-2 and 1e-3, final values.

    Examples
    --------
    :meth:`lkverify.catalogue.examples.Example.summary` makes one from a trajectory:

    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> ex = Example("demo", runs=[Run("r", sys, {"tau": "1/10"}, {"x": [1]})], t_end=10,
    ...              series=[Series("x", lambda s: s["x"][:, 0])], distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> s = ex.summary("r", ex.simulate()["r"])
    >>> s.outcome, s.status.value, s.converged, s.t_1e2, s.t_1e3, s.max_distance
    (<Outcome.SUCCESS: 'success'>, 'simulated', True, 4.15, 6.2, 1.0)
    >>> s.to_json()["outcome"]
    'success'
    """

    label: str
    outcome: Outcome
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
    integrator: str = ""

    @property
    def status(self) -> Status:
        """The status of what the run showed (see :attr:`Outcome.status`)."""
        return self.outcome.status

    def to_json(self) -> dict:
        out = dataclasses.asdict(self)
        out["outcome"] = self.outcome.value
        return out


def _time_to(t, d, level) -> float | None:
    """First time after which d stays below level (None if it does not by the end)."""
    above = np.nonzero(d >= level)[0]
    if above.size == 0:
        return float(t[0])
    k = above[-1]
    if k == len(d) - 1:
        return None
    return float(t[k + 1])


def _fmt(x) -> str:
    """A time or, for None, "not by the end" (prefer :func:`reach_text`, which names the level and T)."""
    return "not by the end of the run" if x is None else f"t = {x:.4g}"


def level_text(level: float) -> str:
    """1e-2 for 0.01 (the levels as the reports write them).

    >>> level_text(0.01), level_text(0.05)
    ('1e-2', '0.05')
    """
    exponent = np.log10(level)
    if level > 0 and abs(exponent - round(exponent)) < 1e-12:
        return f"1e{int(round(exponent))}"
    return f"{level:g}"


def reach_text(level: float, t_reach, t_end: float) -> str:
    """``reaches 1e-2 at t = 12.3`` or ``does not reach 1e-2 by t = 300``.

    >>> reach_text(1e-2, None, 300.0)
    'does not reach 1e-2 by t = 300'
    >>> reach_text(1e-3, 12.25, 300.0)
    'reaches 1e-3 at t = 12.25'
    """
    if t_reach is None:
        return f"does not reach {level_text(level)} by t = {t_end:g}"
    return f"reaches {level_text(level)} at t = {t_reach:.4g}"


def _damping_expr(h):
    """The damping as a SymPy expression in t (accepts an expression or a string, parsed safely)."""
    import sympy

    from ..declare.parse import parse_value
    from ..declare.symbols import t

    expr = parse_value(h, name="damping", variables={"t": t}) if isinstance(h, str) else sympy.sympify(h)
    if expr.free_symbols - {t}:
        raise InputError(f"damping: expected an expression in t, got {expr}; write the damping h as a function "
                         f"of t alone")
    return expr


def _tail_integral(h, T: float) -> float:
    """∫_T^∞ h(t) dt, exactly by SymPy (inf when it diverges)."""
    import sympy

    from ..declare.symbols import t

    val = sympy.integrate(_damping_expr(h), (t, sympy.Rational(T) if isinstance(T, float) else sympy.sympify(T), sympy.oo))
    return float("inf") if val in (sympy.oo, sympy.zoo) or not val.is_finite else float(val)


# -- claims about runs --------------------------------------------------------------------------
class RunClaim:
    """A statement a paper makes about a run; ``check`` returns a simulation Result.

    A subclass sets ``name`` and implements ``check(example, trajectories)``
    (trajectories: run label → :class:`~lkverify.simulate.runs.Trajectory`);
    ``_res(ok, value, detail)`` makes the Result, ``simulated`` if ``ok`` else ``failed``.

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.simulate import simulate
    >>> class EndsPositive(RunClaim):
    ...     name = "x ends positive"
    ...     def check(self, example, trajectories):
    ...         end = float(trajectories["r"].states["x"][-1, 0])
    ...         return self._res(end > 0, end, f"x(T) = {end:.3g}")
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-x(t - 1)[0])])], parameters=Parameters())
    >>> res = EndsPositive().check(None, {"r": simulate(sys, history={"x": [1]}, t_end=2.0)})
    >>> res.kind.value, res.status.value, res.detail               # x(2) = −1/2
    ('simulation', 'failed', 'x(T) = -0.5')
    """

    name = "claim"

    def check(self, example, trajectories: Mapping[str, Trajectory]) -> Result:  # pragma: no cover
        raise NotImplementedError

    def _res(self, ok: bool, value, detail: str) -> Result:
        return Result("simulation", self.name, Status.SIMULATED if ok else Status.FAILED, value, detail)


@dataclasses.dataclass(frozen=True)
class Converges(RunClaim):
    """The distance to the equilibrium ends below ``tol`` and the run succeeded.

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> runs = [Run("fast", sys, {"a": 1, "tau": "1/10"}, {"x": [1]}),
    ...         Run("slow", sys, {"a": "1/10", "tau": "1/10"}, {"x": [1]})]
    >>> ex = Example("demo", runs=runs, t_end=10, series=[Series("x", lambda s: s["x"][:, 0])],
    ...              distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> trs = ex.simulate()
    >>> res = Converges("fast").check(ex, trs)
    >>> res.status.value, res.detail
    ('simulated', 'distance 1.4e-05 at t = 10 (need < 0.001); reaches 1e-3 at t = 6.2')
    >>> Converges("fast", by=5).check(ex, trs).status.value, Converges("slow").check(ex, trs).status.value
    ('failed', 'failed')
    """

    run: str
    tol: float = 1e-3
    by: float | None = None  # ... and is below tol by this time

    @property
    def name(self):
        return f"{self.run}: converges"

    def check(self, example, trajectories):
        s = example.summary(self.run, trajectories[self.run])
        ok = s.outcome is Outcome.SUCCESS and s.final_distance < self.tol
        if self.by is not None:
            tr = trajectories[self.run]
            t_tol = _time_to(tr.t, np.asarray(along(example.distance, tr.states, tr.values)), self.tol)
            ok = ok and t_tol is not None and t_tol <= self.by
        return self._res(ok, {"final_distance": s.final_distance, "t_1e2": s.t_1e2, "t_1e3": s.t_1e3},
                         f"distance {s.final_distance:.3g} at t = {s.t_end:g}"
                         + (f" ({example.distance_name})" if getattr(example, "distance_name", None) else "")
                         + f" (need < {self.tol:g}"
                         + (f" by t = {self.by:g}" if self.by is not None else "") + f"); {reach_text(1e-3, s.t_1e3, s.t_end)}")


@dataclasses.dataclass(frozen=True)
class DoesNotConverge(RunClaim):
    """Over the last ``tail`` fraction of the run the distance keeps returning above ``floor``.

    The tail is cut into ``windows`` consecutive windows and in every one of them the
    largest distance must exceed ``floor``: a trajectory that converges ends below the
    floor for a whole window and fails.  The criterion is not the smallest distance: an
    oscillation that does not settle may pass close to the equilibrium (with the
    ``per-vector`` distance, max_i ‖s_i − r_i‖, the vectors of paper 001's Fig. 2 do
    while ω is not small), and it still does not converge.

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> runs = [Run("fast", sys, {"a": 1, "tau": "1/10"}, {"x": [1]}),
    ...         Run("slow", sys, {"a": "1/10", "tau": "1/10"}, {"x": [1]})]
    >>> ex = Example("demo", runs=runs, t_end=10, series=[Series("x", lambda s: s["x"][:, 0])],
    ...              distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> trs = ex.simulate()
    >>> res = DoesNotConverge("slow").check(ex, trs)
    >>> res.status.value, res.detail
    ('simulated', 'max distance in each of 4 windows of t ∈ [7.5, 10] is at least 0.385 (need > 0.01); min distance 0.364')
    >>> DoesNotConverge("fast").check(ex, trs).status.value
    'failed'
    """

    run: str
    floor: float = 1e-2
    tail: float = 0.25
    windows: int = 4

    def __post_init__(self):
        if not (0 < self.tail <= 1) or int(self.windows) < 1:
            raise InputError(f"DoesNotConverge({self.run!r}): expected 0 < tail ≤ 1 and windows ≥ 1, got "
                             f"tail={self.tail}, windows={self.windows}")

    @property
    def name(self):
        return f"{self.run}: does not converge"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        d = np.asarray(along(example.distance, tr.states, tr.values), dtype=float)
        k = min(int(len(d) * (1 - self.tail)), len(d) - 1)
        parts = [p for p in np.array_split(d[k:], int(self.windows)) if len(p)]
        peaks = [float(np.max(p)) for p in parts]
        lo, low_peak = float(np.min(d[k:])), min(peaks)
        ok = tr.outcome is Outcome.SUCCESS and low_peak > self.floor
        return self._res(ok, {"window_maxima": peaks, "min_distance_tail": lo, "t_from": float(tr.t[k])},
                         f"max distance in each of {len(parts)} windows of t ∈ [{tr.t[k]:.4g}, {tr.t[-1]:.4g}] is "
                         f"at least {low_peak:.3g} (need > {self.floor:g}); min distance {lo:.3g}")


@dataclasses.dataclass(frozen=True)
class BoundedNotAttractive(RunClaim):
    """Bounded, and the energy tends to a positive limit (Remark 2 of paper 001).

    With damping h, Remark 2's inequality −α̃ h Ṽ ≤ dṼ/dt gives Ṽ(∞) ≥ Ṽ(T) exp(−α̃ ∫_T^∞ h).
    The rate α̃ is *measured*: the largest ln(Ṽ(a)/Ṽ(b)) / ∫_a^b h over consecutive windows of
    the second half of the run; the extrapolated lower bound Ṽ(T) exp(−α̃ ∫_T^∞ h) must exceed
    ``fraction`` · Ṽ(T).  For a non-integrable h the tail is infinite and the bound is 0, so the
    claim fails, as it should for an attractive equilibrium.

    Examples
    --------
    ``x' = −h(t) x``: with h = (1+t)⁻² the energy x² tends to e⁻² > 0; with h = 1/(1+t) to 0.

    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> x = Vector("x", 1)
    >>> def check(h, damping):
    ...     sys = System([Equation(x, [Term(-h * x(t)[0])])], parameters=Parameters())
    ...     ex = Example("demo", runs=[Run("r", sys, history={"x": [1]})], t_end=10, series=[],
    ...                  distance=lambda s: abs(s["x"][:, 0]), samples=201)
    ...     claim = BoundedNotAttractive("r", measure=lambda s: s["x"][:, 0] ** 2, damping=damping, bound=2)
    ...     return claim.check(ex, ex.simulate())
    >>> res = check((1 + t) ** -2, "(1+t)**(-2)")
    >>> res.status.value, round(res.value["tail_integral"], 6), res.value["energy_limit_lower"] > 0.1
    ('simulated', 0.090909, True)
    >>> res = check(1 / (1 + t), "1/(1+t)")
    >>> res.status.value, res.value["tail_integral"], res.value["energy_limit_lower"]
    ('failed', inf, 0.0)
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
        d = np.asarray(along(example.distance, tr.states, tr.values))
        E = np.asarray(along(self.measure, tr.states, tr.values))
        edges = np.linspace(tr.t[-1] / 2, tr.t[-1], self.windows + 1)
        idx = np.searchsorted(tr.t, edges).clip(0, len(tr.t) - 1)
        rates = []
        for i, j in zip(idx[:-1], idx[1:]):
            H = scipy.integrate.quad(h, tr.t[i], tr.t[j], limit=200)[0]
            rates.append(np.log(E[i] / E[j]) / H)
        rate = max(0.0, float(max(rates)))
        tail = _tail_integral(self.damping, float(tr.t[-1]))
        lower = float(E[-1] * np.exp(-rate * tail)) if np.isfinite(tail) else 0.0
        ok = tr.outcome is Outcome.SUCCESS and float(np.max(d)) <= self.bound and lower > self.fraction * E[-1]
        return self._res(ok, {"max_distance": float(np.max(d)), "measured_rate": rate, "tail_integral": tail,
                              "energy_end": float(E[-1]), "energy_limit_lower": lower},
                         f"max distance {np.max(d):.3g} (bound {self.bound:g}); measured decay rate α̃ = {rate:.3g} per "
                         f"unit ∫h; ∫_T^∞ h = {tail:.3g}; energy {E[-1]:.3g} at T, limit ≥ {lower:.3g} (extrapolated)")


@dataclasses.dataclass(frozen=True)
class Sensitive(RunClaim):
    """Chaotic-looking: a perturbation of ``perturbation`` in ω's history grows to ``level`` in the plotted series.

    The run must have a state named ``omega`` with a constant history: its components
    are shifted by ``perturbation`` and the run is integrated again.

    Examples
    --------
    ``ω' = ω(t − 1)`` is unstable: a difference of 1e-3 grows about 19-fold by t = 5.

    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> w = Vector("omega", 1); sys = System([Equation(w, [Term(w(t - 1)[0])])], parameters=Parameters())
    >>> ex = Example("demo", runs=[Run("r", sys, history={"omega": [1]})], t_end=5, samples=101,
    ...              series=[Series("ω", lambda s: s["omega"][:, 0])], distance=lambda s: abs(s["omega"][:, 0]))
    >>> trs = ex.simulate()
    >>> res = Sensitive("r", perturbation=1e-3).check(ex, trs)
    >>> res.status.value, round(res.value["max_separation"], 4)
    ('simulated', 0.0192)
    >>> Sensitive("r").check(ex, trs).detail                       # 1e-8 stays far below 1e-2
    'histories 1e-08 apart separate to 1.92e-07 (never above 0.01)'
    """

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
                         step=example.step, t_eval=tr.t)
        sep = np.max([np.abs(np.asarray(along(s.fn, tr.states, tr.values)) - np.asarray(along(s.fn, other.states, other.values))) for s in example.series],
                     axis=0)
        k = np.nonzero(sep > self.level)[0]
        t_sep = float(tr.t[k[0]]) if k.size else None
        ok = other.outcome is Outcome.SUCCESS and t_sep is not None
        return self._res(ok, {"perturbation": self.perturbation, "max_separation": float(np.max(sep)),
                              "t_separation": t_sep},
                         f"histories {self.perturbation:g} apart separate to {np.max(sep):.3g} "
                         + (f"(above {self.level:g} from t = {t_sep:.4g})" if t_sep is not None else
                            f"(never above {self.level:g})"))


@dataclasses.dataclass(frozen=True)
class FasterThan(RunClaim):
    """Run ``a`` reaches ``level`` (and stays below) earlier than run ``b``.

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> runs = [Run("fast", sys, {"a": 1, "tau": "1/10"}, {"x": [1]}),
    ...         Run("slow", sys, {"a": "1/10", "tau": "1/10"}, {"x": [1]})]
    >>> ex = Example("demo", runs=runs, t_end=10, series=[Series("x", lambda s: s["x"][:, 0])],
    ...              distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> trs = ex.simulate()
    >>> res = FasterThan("fast", "slow").check(ex, trs)
    >>> res.status.value, res.detail
    ('simulated', 'fast reaches 1e-2 at t = 4.15; slow does not reach 1e-2 by t = 10')
    >>> FasterThan("slow", "fast").check(ex, trs).status.value
    'failed'
    """

    a: str
    b: str
    level: float = 1e-2

    @property
    def name(self):
        return f"{self.a} reaches {self.level:g} before {self.b}"

    def check(self, example, trajectories):
        ta, tb = (_time_to(tr.t, np.asarray(along(example.distance, tr.states, tr.values)), self.level)
                  for tr in (trajectories[self.a], trajectories[self.b]))
        ok = ta is not None and (tb is None or ta < tb)
        T = float(trajectories[self.a].t[-1])
        return self._res(ok, {"t_a": ta, "t_b": tb}, f"{self.a} {reach_text(self.level, ta, T)}; "
                         f"{self.b} {reach_text(self.level, tb, float(trajectories[self.b].t[-1]))}")


@dataclasses.dataclass(frozen=True)
class SmootherThan(RunClaim):
    """The plotted series of run ``a`` have fewer local extrema (oscillations) than those of ``b``.

    Examples
    --------
    ``x' = −a x(t − 1)`` decays monotonically for a = 1/10 (a·τ < 1/e) and oscillates for a = 1:

    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> runs = [Run("a = 1/10", sys, {"a": "1/10"}, {"x": [1]}), Run("a = 1", sys, {"a": 1}, {"x": [1]})]
    >>> ex = Example("demo", runs=runs, t_end=10, series=[Series("x", lambda s: s["x"][:, 0])],
    ...              distance=lambda s: abs(s["x"][:, 0]), samples=201)
    >>> trs = ex.simulate()
    >>> res = SmootherThan("a = 1/10", "a = 1").check(ex, trs)
    >>> res.status.value, res.value
    ('simulated', {'extrema_a': 0, 'extrema_b': 4})
    >>> SmootherThan("a = 1", "a = 1/10").check(ex, trs).status.value
    'failed'
    """

    a: str
    b: str

    @property
    def name(self):
        return f"{self.a} smoother than {self.b}"

    def check(self, example, trajectories):
        def extrema(tr):
            n = 0
            for s in example.series:
                y = np.asarray(along(s.fn, tr.states, tr.values))
                dy = np.diff(y)
                dy = dy[np.abs(dy) > 1e-12 * max(1.0, float(np.max(np.abs(y))))]
                n += int(np.sum(np.sign(dy[1:]) != np.sign(dy[:-1])))
            return n

        na, nb = extrema(trajectories[self.a]), extrema(trajectories[self.b])
        return self._res(na < nb, {"extrema_a": na, "extrema_b": nb},
                         f"local extrema of the plotted series: {self.a} {na}, {self.b} {nb}")
