"""Numeric integration of delay differential equations (the method of steps).

The problem::

    y'(t) = fun(t, y(t), Z(t), past),        t in [t0, t_end],  y in R^n,
    Z(t)  = [y(t - lag_1), ..., y(t - lag_k)]  (an array of shape (k, n), constant lags > 0),
    y(s)  = history(s)                         for s <= t0.

``past`` is the :class:`DenseHistory` of the run: the solution on ``(-inf, t_n]``
(the initial history, then every accepted step), for right-hand sides that need
quadrature over the past (window integrals, general memory kernels).

The integrator drives SciPy's explicit Runge–Kutta steppers
(:class:`scipy.integrate.DOP853`, or :class:`scipy.integrate.RK45`) step by step.
It knows nothing about SymPy: the simulator compiles symbolic systems into the
callables taken here.

Method
------
* The SciPy stepper is a documented subclass (:class:`RestartableDOP853`,
  :class:`RestartableRK45`); see :class:`Restartable` for the two attributes beyond
  SciPy's public ``OdeSolver`` API it relies on.
* Every step is capped at ``min(lags)``, so every delayed argument
  ``t_n + c h - lag`` of a stage lies in already-accepted history (or the initial
  history).  Delayed values are looked up from the accepted steps' dense output
  (7th order for DOP853, 4th order for RK45), so the interpolation error of the
  history is of the order of the dense output and is covered by the step error
  control of the step it came from.
* With a general initial history ``y'`` jumps at ``t0``; the jump propagates to
  ``t0 + sum_i k_i lag_i``.  Steps land exactly on these breakpoints (the SciPy
  stepper is restarted at each by public construction, with its proposed step size as
  ``first_step``) up to
  the propagation order ``discontinuity_order``; beyond it the solution is smooth
  enough for the error control.
* Numerical trouble is an :class:`Outcome`, never an exception: ``DIVERGED``
  (non-finite values, or ``‖y‖`` above ``divergence_bound``, or steps collapsing
  while ``‖y‖`` grows: a blow-up), ``STEP_COLLAPSE`` (the SciPy solver failed, or
  the mean of the last :data:`FLOOR_WINDOW` steps fell below ``min_mean_step``:
  stiff) and ``BUDGET`` (the ``deadline`` passed), each with the time.  Bad
  arguments raise :class:`~lkverify.errors.InputError`.

Examples
--------
``x'(t) = -x(t - 1)`` with history 1: ``x = 1 - t`` on [0, 1],
``x = 1 - t + (t - 1)**2 / 2`` on [1, 2].

>>> res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 2.0), [1.0], lags=[1.0])
>>> res.outcome
<Outcome.SUCCESS: 'success'>
>>> round(float(res.sol(1.5)[0]), 10)
-0.375
>>> res.sol([-3.0, 0.5]).round(10).tolist()     # before t0: the history
[[1.0], [0.5]]
"""

from __future__ import annotations


from __future__ import annotations

import dataclasses
import enum
import math
import types
from collections.abc import Callable, Mapping, Sequence

import numpy as np
from scipy.integrate import DOP853, RK45

from ..errors import InputError
from ..status import Status
from .checks import _validate
from .events import BLOWUP_GROWTH, FLOOR_WINDOW, FloorHit, StepFloor, breakpoints, crossing
from .history import DenseHistory

__all__ = ["BLOWUP_GROWTH", "DDESolution", "DenseHistory", "FLOOR_WINDOW", "Outcome", "Restartable",
           "RestartableDOP853", "RestartableRK45", "solve_dde"]

_DEGREE = {"DOP853": 7, "RK45": 4}          # degree of the dense-output polynomial


class Outcome(str, enum.Enum):
    """How a run ended.

    Examples
    --------
    >>> str(Outcome.DIVERGED)
    'diverged'
    """

    SUCCESS = "success"
    DIVERGED = "diverged"
    STEP_COLLAPSE = "step_collapse"
    BUDGET = "budget"

    def __str__(self) -> str:
        return self.value

    @property
    def status(self) -> Status:
        """The status of a result observed along this run.

        ``success`` → ``simulated`` (observed, not proved); ``diverged`` → ``failed``;
        ``step_collapse`` and ``budget`` → ``undecided`` (the run did not reach its end).

        >>> Outcome.BUDGET.status.value
        'undecided'
        """
        return {Outcome.SUCCESS: Status.SIMULATED, Outcome.DIVERGED: Status.FAILED}.get(self, Status.UNDECIDED)

    @property
    def reached_end(self) -> bool:
        """True for ``success`` and ``diverged`` (the run ended by itself, not by a budget or the step floor)."""
        return self in (Outcome.SUCCESS, Outcome.DIVERGED)



# -- the SciPy stepper -----------------------------------------------------------


class Restartable:
    """Mixin for SciPy's explicit Runge–Kutta steppers: the proposed step, and a state replaced between steps.

    Everything else the integrator uses is SciPy's public ``OdeSolver`` API (construction
    with ``first_step``/``max_step``/``rtol``/``atol``, ``step()``, ``status``, ``t``,
    ``t_old``, ``y``, ``step_size``, ``fun``, ``dense_output()``).  Beyond it this class
    relies on two attributes of ``scipy.integrate._ivp.rk.RungeKutta`` (unchanged from
    SciPy 1.0 to 1.15):

    * ``h_abs`` — the step size the next ``step()`` tries (read by :meth:`proposed_step`;
      without it the public ``step_size``, the last step taken, is used);
    * ``y`` and ``f`` — the state and its derivative ``fun(t, y)`` (FSAL) the next step
      starts from, plain attributes read by ``_step_impl`` (written by :meth:`replace_state`,
      used only when ``resync`` changes the state).

    ``tests/simulate/test_dde.py`` checks both against a restart by public construction.
    """

    def proposed_step(self) -> float:
        """The step size the next ``step()`` will try."""
        h = getattr(self, "h_abs", None)
        return float(self.step_size if h is None else h)

    def replace_state(self, y: np.ndarray) -> None:
        """Continue from state ``y`` at the current time (its derivative is evaluated once)."""
        self.y = y
        self.f = self.fun(self.t, y)


class RestartableDOP853(Restartable, DOP853):
    """:class:`scipy.integrate.DOP853` with :class:`Restartable`."""


class RestartableRK45(Restartable, RK45):
    """:class:`scipy.integrate.RK45` with :class:`Restartable`."""


_METHODS = {"DOP853": RestartableDOP853, "RK45": RestartableRK45}


# -- result --------------------------------------------------------------------


# -- result --------------------------------------------------------------------


@dataclasses.dataclass(frozen=True, eq=False)
class DDESolution:
    """The outcome of :func:`solve_dde`.

    Attributes
    ----------
    outcome : Outcome
    message : str
        One readable sentence.
    t : ndarray (N,)
        Accepted step times, ``t[0] = t0``; includes the breakpoints landed on.
    y : ndarray (N, n)
        The solution at ``t`` (after ``resync``).
    sol : DenseHistory
        Dense solution on ``(-inf, t[-1]]``: ``sol(s)`` for scalar or array ``s``.
    t_fail : float or None
        Time of divergence or of the step collapse.
    nfev : int
        Right-hand-side evaluations.
    n_steps, n_rejected : int
        Accepted and rejected steps.
    monitors : Mapping[str, ndarray (N,)]
        Every monitor's value at ``t``.
    monitor_max : Mapping[str, float]
        ``max |monitor|`` over the run.
    breakpoints : ndarray
        The derivative-discontinuity times in ``(t0, t_end)`` the steps landed on.
    t_eval, y_eval : ndarray or None
        The requested sample times up to ``t[-1]`` and the solution there (shape (m, n)).

    Examples
    --------
    >>> res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 3.0), [1.0], lags=[1.0])
    >>> res.success, res.breakpoints.tolist(), float(res.t[-1]), res.y.shape[1]
    (True, [1.0, 2.0], 3.0, 1)
    >>> res = solve_dde(lambda t, y, Z, past: y, (0.0, 30.0), [1.0], lags=[1.0], divergence_bound=1e3)
    >>> res.success, res.outcome.value, round(res.t_fail, 3)       # e^t passes 1e3 at t = ln 1000
    (False, 'diverged', 6.908)
    >>> res.message
    '‖y‖ exceeded divergence_bound=1000 at t=6.907755277'
    """

    outcome: Outcome
    message: str
    t: np.ndarray
    y: np.ndarray
    sol: DenseHistory
    t_fail: float | None
    nfev: int
    n_steps: int
    n_rejected: int
    monitors: Mapping[str, np.ndarray]
    monitor_max: Mapping[str, float]
    breakpoints: np.ndarray
    t_eval: np.ndarray | None = None
    y_eval: np.ndarray | None = None

    @property
    def success(self) -> bool:
        """True if the run reached ``t_end``."""
        return self.outcome is Outcome.SUCCESS

    def __repr__(self) -> str:
        return (f"DDESolution(outcome={self.outcome.value}, t=[{self.t[0]:g}, {self.t[-1]:g}], "
                f"n_steps={self.n_steps}, nfev={self.nfev}, message={self.message!r})")



# -- the integrator ------------------------------------------------------------


def solve_dde(fun: Callable, t_span: tuple[float, float], history, *, lags: Sequence[float],
              method: str = "DOP853", rtol: float = 1e-8, atol=1e-10, max_step: float = math.inf,
              first_step: float | None = None, divergence_bound: float = 1e8,
              discontinuity_order: int = 4, t_eval=None, resync: Callable | None = None,
              monitors: Sequence[Callable] | Mapping[str, Callable] = (),
              progress: Callable | None = None, deadline=None,
              min_mean_step: float | None = None) -> DDESolution:
    """Integrate ``y'(t) = fun(t, y(t), Z(t), past)`` with constant lags by the method of steps.

    Parameters
    ----------
    fun : callable
        ``fun(t, y, Z, past) -> array (n,)``: ``y`` the state (n,), ``Z`` the delayed
        states, shape ``(len(lags), n)``, row k = ``y(t - lags[k])``; ``past`` the
        :class:`DenseHistory` on ``(-inf, t_n]`` (``past(s)``, ``past.integrate``;
        use ``extrapolate=True`` for the current-step piece ``(t_n, t]``).  The arrays
        belong to the solver: do not modify them in place.
    t_span : (float, float)
        ``(t0, t_end)``, ``t_end > t0``.
    history : callable or array_like
        ``phi(s) -> array (n,)`` for ``s <= t0``, or a constant state.  ``y(t0) = phi(t0)``
        and ``n`` is taken from it (auxiliary states included).
    lags : sequence of float, keyword-only
        Constant delays > 0; ``()`` makes it a plain ODE (steps are then not capped).
    method : {"DOP853", "RK45"}
        SciPy stepper.  DOP853: order 8, 7th-order dense output; RK45: order 5, 4th-order dense output.
    rtol, atol : float
        Tolerances of the step error control (``atol`` may be one per state).
    max_step : float
        Largest step; also capped at ``min(lags)`` so that every delayed stage
        argument lies in accepted history, looked up from the accepted steps' dense
        output whose interpolation error is covered by those steps' error control.
    first_step : float, optional
        Initial step (SciPy's estimate if omitted).
    divergence_bound : float
        ``‖y‖₂`` above it ends the run with ``Outcome.DIVERGED``.
    discontinuity_order : int
        Land steps on the breakpoints ``t0 + sum k_i lag_i``, ``1 <= sum k_i <= order``;
        0 disables.  Default 4: later jumps are in derivatives of order >= 6.
    t_eval : array_like, optional
        Sample times in ``[t0, t_end]``; the dense solution there is in ``y_eval``.
    resync : callable, optional
        ``resync(t, y, past) -> y_new`` after each accepted step (``past`` already
        contains it); the run continues from ``y_new``.  For auxiliary states that
        should be recomputed exactly, e.g. a window integral by ``past.integrate``.
        The last step's dense output is corrected by a linear ramp so that the
        solution stays continuous.
    monitors : sequence or mapping of callables
        ``monitor(t, y) -> float`` recorded at ``t0`` and after every accepted step
        (after ``resync``); named by the mapping keys or the functions' names.
    progress : callable, optional
        ``progress(fraction)`` with fraction in (0, 1], called at most 100 times.
    deadline : lkverify.options.Deadline, optional
        Checked after every accepted step; once it has passed the run ends with
        ``Outcome.BUDGET`` at the time reached (the solution so far is kept).
    min_mean_step : float, optional
        The step floor: when the mean length of the last :data:`FLOOR_WINDOW`
        accepted steps falls below it, the run ends: ``Outcome.DIVERGED`` (a
        blow-up) if ``‖y‖`` has grown :data:`BLOWUP_GROWTH`-fold over
        ``max(1, ‖y(t0)‖)``, else ``Outcome.STEP_COLLAPSE`` (stiff: an explicit
        method cannot take steps of the system's time scale).

    Returns
    -------
    DDESolution
        Numerical trouble is reported in ``outcome`` (``DIVERGED`` / ``STEP_COLLAPSE``
        / ``BUDGET`` with ``t_fail``), never raised.  Arithmetic errors raised by
        ``fun`` (ZeroDivisionError, OverflowError) count as non-finite values; other
        exceptions raised by ``fun`` propagate.

    Raises
    ------
    InputError
        Invalid arguments (non-positive lag, ``t_end <= t0``, bad history, ``rtol <= 0``, ...).

    Examples
    --------
    Distributed delay ``x' = -∫_{t-1}^t x`` via the auxiliary state ``z = ∫_{t-1}^t x``
    (``z' = x(t) - x(t-1)``), with ``z`` resynchronised by quadrature:

    >>> def f(t, y, Z, past):
    ...     return np.array([-y[1], y[0] - Z[0, 0]])
    >>> def resync(t, y, past):
    ...     return np.array([y[0], past.integrate(lambda Y: Y[:, 0], t - 1.0, t)])
    >>> res = solve_dde(f, (0.0, 3.0), [1.0, 1.0], lags=[1.0], resync=resync)
    >>> res.success, res.y.shape[1]
    (True, 2)
    >>> bool(abs(res.y[-1, 1] - res.sol.integrate(lambda Y: Y[:, 0], 2.0, 3.0)) < 1e-14)
    True
    """
    args = _validate(fun, t_span, history, lags, method, rtol, atol, max_step, first_step, divergence_bound,
                     discontinuity_order, t_eval, resync, monitors, progress)
    run = _Integration(fun, history, args, method=method, atol=atol, first_step=first_step, bound=float(divergence_bound),
                       discontinuity_order=discontinuity_order, resync=resync, progress=progress,
                       deadline=deadline, min_mean_step=min_mean_step)
    run.start()
    run.integrate()
    return run.solution(t_eval)


class _Integration:
    """One run of :func:`solve_dde`: the right-hand side seen by SciPy, the segments, the checks after each step."""

    def __init__(self, fun, history, args, *, method, atol, first_step, bound, discontinuity_order, resync, progress,
                 deadline, min_mean_step):
        t0, t_end, lag_arr, y0, rtol, max_step, named = args
        self.fun, self.method, self.rtol, self.atol = fun, method, rtol, atol
        self.t0, self.t_end, self.lags, self.y0 = t0, t_end, lag_arr, y0
        self.n = y0.shape[0]
        self.stepper = _METHODS[method]
        nlag = lag_arr.shape[0]
        lag_min = float(lag_arr.min()) if nlag else math.inf
        self.lag_max = float(lag_arr.max()) if nlag else 0.0
        self.hmax = min(max_step, lag_min)
        self.bound, self.resync, self.progress, self.deadline = bound, resync, progress, deadline
        self.named = named
        self.past = DenseHistory(history, t0, y0, _DEGREE[method], lag_min if nlag else 1.0)
        self.Z_empty = np.empty((0, self.n))
        self.nfev = self.n_rejected = 0
        self.bad_t = None        # first time fun returned non-finite values since the last accepted step
        self.breaks = breakpoints(t0, t_end, lag_arr, discontinuity_order)
        self.h_next = None if first_step is None else float(first_step)
        self.floor = StepFloor(min_mean_step, float(np.linalg.norm(y0)))
        self.outcome, self.message, self.t_fail = Outcome.SUCCESS, "", None
        self.next_progress = 0.01
        self.mon_values = {}

    # -- the right-hand side -----------------------------------------------
    def delayed(self, t):
        return self.past._lookup(t - self.lags, t - self.lag_max) if self.lags.shape[0] else self.Z_empty

    def call(self, t, y, Z):
        try:
            return np.asarray(self.fun(t, y, Z, self.past), dtype=float)
        except (ZeroDivisionError, OverflowError, FloatingPointError):
            return np.full(self.n, np.nan)

    def rhs(self, t, y):
        self.nfev += 1
        f = self.call(t, y, self.delayed(t))
        if self.bad_t is None and not np.isfinite(f).all():
            self.bad_t = t
        return f

    def start(self) -> None:
        """Check the right-hand side at t0, record the monitors there, check the initial state."""
        t0, y0, n = self.t0, self.y0, self.n
        f0 = self.call(t0, y0.copy(), self.delayed(t0))
        self.nfev += 1
        if f0.shape == (n,) and not np.isfinite(f0).all():
            raise InputError(f"fun: the right-hand side is not finite at t0={t0:g} (got {f0.tolist()}); expected "
                             f"finite values at the initial state; check coefficients and the history at t0")
        if f0.shape != (n,):
            raise InputError(f"fun: expected fun(t0, y, Z, past) to return shape ({n},) like the history "
                             f"phi(t0), got {f0.shape}; return every state component (auxiliary states "
                             f"included) or fix the history")
        self.mon_values = {name: [float(f(t0, y0.copy()))] for name, f in self.named}
        if not float(np.dot(y0, y0)) <= self.bound * self.bound:
            self.outcome, self.t_fail = Outcome.DIVERGED, t0
            self.message = f"‖y(t0)‖ = {np.linalg.norm(y0):g} already exceeds divergence_bound={self.bound:g}"

    # -- stepping ------------------------------------------------------------
    def integrate(self) -> None:
        """Integrate segment by segment: a new stepper (public construction) at every breakpoint."""
        if self.outcome is not Outcome.SUCCESS:
            return
        t, y = self.t0, self.y0.copy()
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            for target in [*self.breaks, self.t_end]:
                fs = None if self.h_next is None else min(self.h_next, self.hmax, target - t)
                solver = self.stepper(self.rhs, t, y, target, max_step=self.hmax, rtol=self.rtol, atol=self.atol,
                                      first_step=fs)
                t, y = self.segment(solver, target)
                if self.outcome is not Outcome.SUCCESS:
                    return

    def segment(self, solver, target):
        """Step ``solver`` to ``target``; returns the time and state reached."""
        n_stages = solver.n_stages
        t, y = float(solver.t), solver.y
        while solver.status == "running":
            calls = self.nfev
            msg = solver.step()
            if solver.status == "failed":
                self.failed(float(solver.t), msg)
                break
            self.n_rejected += max(0, (self.nfev - calls) // n_stages - 1)
            ta, t = float(solver.t_old), float(solver.t)
            if t == ta:
                continue
            y = self.accept(solver, ta, t)
            if self.stopped(ta, t, y):
                break
            # the step size before a landing step truncated at the target is the better restart guess
            h = solver.proposed_step()
            self.h_next = h if (t != target or self.h_next is None) else max(self.h_next, h)
            self.report_progress(t)
        return t, y

    def accept(self, solver, ta: float, t: float) -> np.ndarray:
        """Store an accepted step, resynchronise, record the monitors; returns the state."""
        past = self.past
        past.append(solver.dense_output(), ta, t, solver.y)
        y = solver.y
        if self.resync is not None:
            y_new = np.asarray(self.resync(t, y, past), dtype=float)
            if y_new.shape != (self.n,):
                raise InputError(f"resync: expected resync(t, y, past) to return shape ({self.n},), "
                                 f"got {y_new.shape}; return the whole state")
            if not np.array_equal(y_new, y):
                past._shift_last(y_new - y)
                y = y_new.copy()
                solver.replace_state(y)        # the FSAL derivative follows the new state
        self.bad_t = None
        for name, f in self.named:
            self.mon_values[name].append(float(f(t, y)))
        return y

    def failed(self, t_fail: float, msg) -> None:
        self.t_fail = t_fail
        if self.bad_t is not None:
            self.outcome = Outcome.DIVERGED
            self.message = (f"the right-hand side returned non-finite values at t={self.bad_t:.10g}; "
                            f"the step size collapsed while retrying from t={t_fail:.10g}")
        else:
            self.outcome = Outcome.STEP_COLLAPSE
            self.message = f"{self.method} failed at t={t_fail:.10g}: {msg}"

    def stopped(self, ta: float, t: float, y: np.ndarray) -> bool:
        """The checks after an accepted step: divergence bound, step floor, deadline."""
        yy = float(np.dot(y, y))
        bound = self.bound
        if not yy <= bound * bound:
            self.outcome = Outcome.DIVERGED
            self.t_fail = crossing(self.past, ta, t, bound)
            self.message = (f"y became non-finite at t={t:.10g}" if not np.isfinite(y).all() else
                            f"‖y‖ exceeded divergence_bound={bound:g} at t={self.t_fail:.10g}")
            return True
        hit = self.floor.record(self.past._m, t, t - ta, float(np.sqrt(yy)))
        if hit is not None:
            self.floor_hit(hit)
            return True
        deadline = self.deadline
        if deadline is not None and deadline.expired:
            self.outcome, self.t_fail = Outcome.BUDGET, t
            self.message = (f"{deadline.message()} at t={t:.6g} of t_end={self.t_end:g} after {self.past._m} "
                            f"steps; the run is incomplete (give a larger time budget, or a shorter t_end)")
            return True
        return False

    def floor_hit(self, hit: FloorHit) -> None:
        self.t_fail = hit.t
        floor = self.floor.floor
        if hit.blow_up:
            self.outcome = Outcome.DIVERGED
            self.message = (f"blow-up at t≈{hit.t:.6g}: ‖y‖ grew to {hit.norm:.3g} (from "
                            f"{np.linalg.norm(self.y0):.3g}) while the steps shrank to {hit.mean_step:.3g} on "
                            f"average, below the floor {floor:.3g}")
        else:
            self.outcome = Outcome.STEP_COLLAPSE
            self.message = (f"steps collapsed at t={hit.t:.6g}: the last {FLOOR_WINDOW} steps average "
                            f"{hit.mean_step:.3g}, below the floor {floor:.3g}; at this step size "
                            f"t_end={self.t_end:g} needs about {(self.t_end - hit.t) / hit.mean_step:.2g} more "
                            f"steps (a stiff system: an explicit method needs steps of its fastest time scale; "
                            f"or a t_end too long for the system's time scale)")

    def report_progress(self, t: float) -> None:
        span = self.t_end - self.t0
        if self.progress is not None and (t - self.t0) >= self.next_progress * span:
            fraction = (t - self.t0) / span
            self.progress(min(1.0, fraction))
            self.next_progress = math.floor(fraction * 100 + 1e-9) / 100 + 0.01

    # -- the result ----------------------------------------------------------
    def solution(self, t_eval) -> DDESolution:
        past = self.past
        m = past._m
        past._freeze()
        message = self.message
        if self.outcome is Outcome.SUCCESS:
            message = (f"integrated to t_end={self.t_end:g} in {m} steps ({self.n_rejected} rejected, "
                       f"{self.nfev} evaluations)")
        te = ye = None
        if t_eval is not None:
            te = np.asarray(t_eval, dtype=float)
            te = te[te <= past.t_last]
            ye = past(te)
        mons = {name: np.asarray(v) for name, v in self.mon_values.items()}
        return DDESolution(
            outcome=self.outcome, message=message, t=past._tb.copy(), y=past._Y.copy(), sol=past,
            t_fail=self.t_fail, nfev=self.nfev, n_steps=m, n_rejected=self.n_rejected,
            monitors=types.MappingProxyType(mons),
            monitor_max=types.MappingProxyType({k: float(np.max(np.abs(v))) for k, v in mons.items()}),
            breakpoints=self.breaks, t_eval=te, y_eval=ye)
