"""Runs: a compiled System integrated from an initial history, and the trajectory it gives.

:func:`simulate` checks a run (:func:`prepare_run`: parameter values, coefficients on the
horizon, the initial history, the step floor), integrates it with
:func:`lkverify.simulate.solver.solve_dde` and returns a :class:`Trajectory`.  Tolerances
and step limits come in one :class:`~lkverify.simulate.control.StepControl`; the time
budget is a :class:`lkverify.options.Budget` (or a running
:class:`~lkverify.options.Deadline` shared by several runs).

>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
>>> tr = simulate(sys, history={"x": [1]}, t_end=1.0)
>>> tr.outcome, tr.status.value, abs(round(float(tr.states["x"][-1, 0]), 10))   # x = 1 − t on [0, 1]
(<Outcome.SUCCESS: 'success'>, 'simulated', 0.0)
>>> tr.max_step, tr.max_step_reason
(1.0, 'shortest delay')
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping

import numpy as np
import sympy

from ..errors import InputError, UnsupportedInput
from ..options import Budget, Deadline
from ..status import Status
from ..declare.symbols import t
from ..declare.system import System
from .compile import CompiledSystem, compile_system
from .control import StepControl
from .compiled import SCIPY, solve_compiled
from .events import MAX_STEPS
from .solver import DDESolution, Outcome, solve_dde

__all__ = ["MAX_STEPS", "PreparedRun", "Trajectory", "prepare_run", "simulate"]


@dataclasses.dataclass(frozen=True)
class Trajectory:
    """A simulated solution.

    Attributes
    ----------
    outcome : Outcome
        success, diverged, step collapse or budget; :attr:`status` is its Status.
    message : str
    t : ndarray
        Output times.
    states : dict
        state name → array (len(t), dim).
    t_fail : float or None
    constraint_drift : dict
        constraint name → max |defect| along the run (‖s‖ − 1, frame orthonormality).
    nfev, n_steps : int
    seconds : float
    solution : DDESolution
        The integrator's full output (dense ``sol``).
    layout : dict
        state name → slice of the integrator's state vector.
    step : StepControl
        The tolerances and step limits asked for.
    max_step : float
        The largest step the run allowed: ``min(shortest delay, step limit)``.
    max_step_reason : str
        What set it: ``"shortest delay"``, ``"max_step"``, ``"quadrature_max_step"`` or ``"none"``.
    values : dict
        The run's resolved parameter values (name → checked value), for quantities along the
        run that depend on them (:class:`lkverify.simulate.experiments.FromValues`).
    integrator : str
        Which integrator ran: ``"compiled DOP853 (native code)"`` (or ``(numba)``), or
        ``"SciPy DOP853 (Python right-hand side)"`` (see :func:`simulate`).

    Examples
    --------
    ``x' = −x(t − 1)`` with history 1: x = 1 − t on [0, 1], then 1 − t + (t − 1)²/2.

    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> tr = simulate(sys, history={"x": [1]}, t_end=2.0)
    >>> tr.status.value, tr.values, float(tr.t[-1])
    ('simulated', {'a': 1, 'tau': 1}, 2.0)
    >>> tr.at([0.5, 1.5])["x"].round(10).tolist()     # dense output between the samples
    [[0.5], [-0.375]]
    """

    system_name: str
    outcome: Outcome
    message: str
    t: np.ndarray
    states: dict
    t_fail: float | None
    constraint_drift: dict
    nfev: int
    n_steps: int
    seconds: float
    solution: DDESolution
    layout: dict
    step: StepControl = StepControl()
    max_step: float = np.inf
    max_step_reason: str = "none"
    values: dict = dataclasses.field(default_factory=dict)
    integrator: str = ""

    @property
    def status(self) -> Status:
        """The status of what was observed along this run (see :attr:`Outcome.status`)."""
        return self.outcome.status

    def at(self, times) -> dict:
        """Dense values of every state at ``times`` (array)."""
        Y = np.atleast_2d(self.solution.sol(np.atleast_1d(np.asarray(times, dtype=float))))
        return {name: Y[:, sl] for name, sl in self.layout.items()}


def _example_history(s) -> str:
    comps = ",".join(["0.1"] * s.dim)
    return f"{s.name}={comps if s.dim == 1 else '[' + comps + ']'}"


def _numpy_values(lf, s_) -> np.ndarray:
    """A lambdified history at ``s_`` in NumPy floats: a pole or a log of a negative number is inf/NaN (refused
    by the finiteness checks), never a ZeroDivisionError of Python floats or a RuntimeWarning on stderr."""
    with np.errstate(all="ignore"):
        return np.asarray(lf(np.asarray(s_, dtype=float)), dtype=float)


def _history_function(system: System, history: Mapping[str, object], layout: dict, n: int):
    """The initial history as phi(s) → state vector (validated)."""
    known = {s.name: s for s in system.states}
    unknown = set(history) - set(known)
    if unknown:
        raise InputError(f"history for unknown state(s) {', '.join(sorted(unknown))}: expected one of the states "
                         f"{', '.join(sorted(known))}; fix the name (e.g. history {_example_history(system.states[0])})")
    missing = set(known) - set(history)
    if missing:
        raise InputError(f"no history given for state(s) {sorted(missing)}; give a constant vector or a function of t")
    parts = []
    for s in system.states:
        h = history[s.name]
        if isinstance(h, (int, float, np.number)) or (isinstance(h, sympy.Basic) and not isinstance(h, sympy.MatrixBase)):
            if s.dim != 1:
                raise InputError(f"history of {s.name}: expected {s.dim} components (a vector), got the scalar "
                                 f"{h}; pass e.g. the history {_example_history(s)}",
                                 topic="history", example=_example_history(s))
            h = [h]
        if callable(h) and not isinstance(h, sympy.Basic):
            fn = h
        else:
            if isinstance(h, str) or (isinstance(h, (list, tuple)) and any(isinstance(x, str) for x in h)):
                from ..declare.parse import parse_value

                h = [parse_value(x, name=f"history of {s.name}", variables={"t": t}) if isinstance(x, str) else x
                     for x in (h if isinstance(h, (list, tuple)) else [h])]
                h = h[0] if len(h) == 1 and isinstance(h[0], sympy.MatrixBase) else h
            try:
                m = sympy.Matrix(h) if not isinstance(h, sympy.MatrixBase) else h
            except (TypeError, ValueError, sympy.SympifyError):
                raise InputError(f"history of {s.name}: expected {s.dim} numbers, got {h!r}; pass e.g. "
                                 f"{_example_history(s)}", topic="history", example=_example_history(s)) from None
            if m.shape not in ((s.dim, 1), (1, s.dim)):
                raise InputError(f"history of {s.name}: expected {s.dim} components, got shape {m.shape}; "
                                 f"pass e.g. the history {_example_history(s)}", topic="history",
                                 example=_example_history(s))
            extra = m.free_symbols - {t}
            if extra:
                raise InputError(f"history of {s.name}: expected an expression in t only, got symbols {sorted(map(str, extra))}")
            if m.free_symbols:
                lf = sympy.lambdify([t], list(m), modules="numpy")
                fn = lambda s_, lf=lf: _numpy_values(lf, s_)  # noqa: E731
            else:
                const = np.array([float(v) for v in m], dtype=float)
                fn = lambda s_, c=const: c  # noqa: E731
        try:
            v = np.asarray(fn(0.0), dtype=float).ravel()
        except (ArithmeticError, TypeError, ValueError) as exc:
            raise InputError(f"history of {s.name}: expected values at t0 = 0, got {type(exc).__name__}: {exc}; "
                             f"pass e.g. the history {_example_history(s)}", topic="history",
                             example=_example_history(s)) from None
        if v.shape != (s.dim,):
            raise InputError(f"history of {s.name}: expected {s.dim} components, got {v.size}; "
                             f"pass e.g. the history {_example_history(s)}", topic="history",
                             example=_example_history(s))
        if not np.all(np.isfinite(v)):
            raise InputError(f"history of {s.name}: expected finite values, got {v} (not finite at t0); pass "
                             f"e.g. the history {_example_history(s)}", topic="history", example=_example_history(s))
        parts.append((layout[s.name], fn))
    frames = []
    for s in system.states:
        if s.frame is not None and s.frame not in frames:
            frames.append(s.frame)
            M = np.column_stack([np.asarray(dict((st.name, f) for (sl, f), st in zip(parts, system.states))[v.name](0.0),
                                            dtype=float).ravel() for v in s.frame.vectors])
            defect = float(np.max(np.abs(M.T @ M - np.eye(3))))
            det = float(np.linalg.det(M))
            if defect > 1e-9 or det < 0:
                raise InputError(f"initial frame {[v.name for v in s.frame.vectors]} is not orthonormal and right-handed: "
                                 f"max|RᵀR − I| = {defect:.3g}, det = {det:.6g}; normalise it (e.g. from angles)")
        elif s.unit and s.frame is None:
            v = np.asarray(dict((st.name, f) for (sl, f), st in zip(parts, system.states))[s.name](0.0), dtype=float).ravel()
            if abs(np.linalg.norm(v) - 1) > 1e-9:
                raise InputError(f"initial {s.name} is not a unit vector: ‖{s.name}‖ = {np.linalg.norm(v):.12g}")

    def phi(s_):
        y = np.zeros(n)
        for sl, fn in parts:
            y[sl] = np.asarray(fn(s_), dtype=float).ravel()
        return y

    return phi


def _monitors(system: System, layout: dict) -> dict:
    mons = {}
    frames = []
    for s in system.states:
        if s.frame is not None:
            if s.frame in frames:
                continue
            frames.append(s.frame)
            sls = [layout[v.name] for v in s.frame.vectors]
            name = "frame " + ",".join(v.name for v in s.frame.vectors)
            mons[name] = lambda tt, y, sls=sls: float(np.max(np.abs(
                np.column_stack([y[sl] for sl in sls]).T @ np.column_stack([y[sl] for sl in sls]) - np.eye(3))))
        elif s.unit:
            sl = layout[s.name]
            mons[f"‖{s.name}‖−1"] = lambda tt, y, sl=sl: float(np.linalg.norm(y[sl]) - 1.0)
    return mons


def _check_coefficients(system: System, checked: Mapping, lo: float, hi: float) -> None:
    """Refuse a time-varying coefficient that is not finite (or not real) somewhere on [lo, hi]."""
    from ..declare.parameters import ParameterKind

    grid = np.unique(np.concatenate([np.linspace(lo, hi, 4001), [lo, 0.0, hi]] if lo <= 0 <= hi
                                    else [np.linspace(lo, hi, 4001), [lo, hi]]))
    for spec in system.parameters:
        if spec.kind is not ParameterKind.COEFFICIENT or spec.name not in checked:
            continue
        value = checked[spec.name]
        bad = None
        try:
            f = sympy.lambdify([t], value, modules="numpy")
            with np.errstate(all="ignore"):
                vals = np.broadcast_to(np.asarray(f(grid)), grid.shape)
            if np.iscomplexobj(vals):
                nonreal = np.abs(np.imag(vals)) > 0
                vals = np.where(nonreal, np.nan, np.real(vals))
            vals = vals.astype(float)
            idx = np.nonzero(~np.isfinite(vals))[0]
            if idx.size:
                bad = float(grid[idx[0]])
        except (ZeroDivisionError, OverflowError, ValueError, TypeError, FloatingPointError):
            bad = lo
        if bad is not None:
            raise InputError(f"{spec.name}: expected a coefficient finite and real on the simulated horizon "
                             f"[{lo:g}, {hi:g}], got {spec.name}(t) = {value}, which is not at t = {bad:.6g}; "
                             f"give a function defined on the whole horizon, e.g. {spec.name} = 1/(1+t)",
                             topic="parameters", example=f'"{spec.name}=1/(1+t)"')


@dataclasses.dataclass(frozen=True)
class PreparedRun:
    """A run checked by :func:`prepare_run`, ready to integrate.

    Attributes
    ----------
    compiled : CompiledSystem
    history : callable
        ``phi(s)`` → the state vector (without auxiliary states) for ``s <= t0``.
    max_step : float
        The step limit asked for (``StepControl.max_step``, or ``quadrature_max_step``
        when the right-hand side has a quadrature term).
    max_step_reason : str
        The option that set ``max_step``.
    step_cap : float
        ``min(max_step, shortest delay)``: the largest step the run takes.
    step_cap_reason : str
        ``"shortest delay"``, the option name, or ``"none"`` (no limit).

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> prep = prepare_run(sys, history={"x": [1]}, t_end=5.0, values={"tau": "1/2"})
    >>> prep.step_cap, prep.step_cap_reason, prep.max_step_reason, prep.compiled.lags
    (0.5, 'shortest delay', 'max_step', (0.5,))
    >>> prep.history(-0.3).tolist()                   # the initial history, as phi(s)
    [1.0]
    """

    compiled: CompiledSystem
    history: Callable
    max_step: float
    max_step_reason: str
    step_cap: float
    step_cap_reason: str


def prepare_run(system: System, *, history: Mapping[str, object], t_end: float,
                values: Mapping[str, object] | None = None, t0: float = 0.0,
                step: StepControl = StepControl(), integrals: str = "auto") -> PreparedRun:
    """Validate a run before integrating it.

    Checks the parameter values, that every time-varying coefficient is finite on the
    horizon ``[t0 − max delay, t_end]``, the initial history, and the step floor:
    steps are at most ``min(delays)`` (and the step limit of ``step``) long, so a run
    needing more than :data:`MAX_STEPS` steps is refused.

    Raises
    ------
    InputError
        With the reason (one line).

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> prepare_run(sys, history={"x": [1]}, t_end=2.0).step_cap
    1.0
    >>> prepare_run(sys, history={"y": [1]}, t_end=2.0)
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: history for unknown state(s) y: expected one of the states x; fix the name (e.g. history x=0.1)
    >>> prepare_run(sys, history={"x": [1]}, t_end=2.0, values={"tau": "1/10000000"})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: ...needs at least 2e+07 steps (steps are at most the shortest delay 1e-07 long); expected at most 1e+07 (the step floor); shorten t_end or lengthen the delay
    """
    if not isinstance(step, StepControl):
        raise InputError(f"step: expected a StepControl, got {type(step).__name__}; "
                         f"pass e.g. step=StepControl(rtol=1e-10, atol=1e-12)")
    if not (isinstance(t_end, (int, float)) and np.isfinite(t_end)) or t_end <= t0:
        raise InputError(f"t_end: expected a number greater than t0 = {t0}, got {t_end}")
    comp = compile_system(system, values, integrals=integrals)
    checked = system.parameters.resolve(values or {}, use_defaults=True)
    _check_coefficients(system, checked, t0 - (max(comp.lags) if comp.lags else 0.0), float(t_end))
    phi = _history_function(system, history, comp.layout, comp.n_states)
    max_step, reason = step.limit(has_quadrature=bool(comp.quads))
    cap, cap_reason = max_step, reason if np.isfinite(max_step) else "none"
    if comp.lags and min(comp.lags) <= cap:
        cap, cap_reason = min(comp.lags), "shortest delay"
    if np.isfinite(cap):
        needed = (t_end - t0) / cap
        if needed > MAX_STEPS:
            why = (f"the shortest delay {cap:g}" if cap_reason == "shortest delay"
                   else f"the largest step {cap:g}")
            raise InputError(f"{'system ' + system.name if system.name else 'the system'}: a run to t_end = {t_end:g} needs at least {needed:.3g} "
                             f"steps (steps are at most {why} long); expected at most {MAX_STEPS:.0e} (the step "
                             f"floor); shorten t_end or lengthen the delay", topic="t_end")
    return PreparedRun(comp, phi, max_step, reason, float(cap), cap_reason)


def simulate(system: System, *, history: Mapping[str, object], t_end: float, values: Mapping[str, object] | None = None,
             t0: float = 0.0, step: StepControl = StepControl(), method: str = "DOP853",
             divergence_bound: float = 1e8, t_eval=None, progress: Callable[[float], None] | None = None,
             integrals: str = "auto", budget: Budget | None = None, deadline: Deadline | None = None,
             integrator: str = "auto") -> Trajectory:
    """Integrate ``system`` from the initial ``history`` on [t0 − τ, t0] to ``t_end``.

    Parameters
    ----------
    system : System
    history : mapping
        state name → constant vector, a callable of t, or a SymPy vector in t.
    t_end : float
    values : mapping, optional
        Parameter values (name → value or string); the paper's defaults fill in.
    t0 : float
    step : StepControl
        Tolerances and step limits (reported in the trajectory).
    method, divergence_bound, t_eval, progress
        Passed to :func:`lkverify.simulate.solver.solve_dde`.

    The integrator: SciPy's DOP853 method of steps compiled (:mod:`lkverify.simulate.dop853`, the
    right-hand side as native code) for every run it supports — window integrals and sums of
    exponential kernels as auxiliary states, constant initial histories, ``method="DOP853"``; the
    same steps as the SciPy path to rounding.  The SciPy path (:func:`~lkverify.simulate.solver.solve_dde`
    with a Python right-hand side) runs the rest: quadrature terms (general kernels), histories that
    are functions of t, ``method="RK45"``.  :attr:`Trajectory.integrator` says which ran.
    integrals : {"auto", "quadrature"}
        See :func:`lkverify.simulate.compile.compile_system`.
    budget : lkverify.options.Budget, optional
        The time budget of this run (``Budget.seconds``); when it is spent the run stops
        with outcome ``budget`` (incomplete, undecided).
    deadline : lkverify.options.Deadline, optional
        A running deadline shared with other runs (used instead of ``budget``'s).
    integrator : {"auto", "compiled", "scipy"}
        ``"auto"``: the compiled integrator where it applies (below), else SciPy's; ``"compiled"``
        refuses a run it does not support (:class:`~lkverify.errors.UnsupportedInput`);
        ``"scipy"``: SciPy's steppers with the Python right-hand side (the reference path).

    The step floor (:data:`MAX_STEPS` = 1e7): a run that needs more than 1e7 steps
    because steps are capped at the shortest delay is refused up front; a run whose
    last 200 steps average less than ``(t_end − t0)/1e7`` stops with outcome
    ``diverged`` (a blow-up: ‖y‖ grew 1000-fold) or ``step_collapse`` (stiff).

    Returns
    -------
    Trajectory
        With an outcome (never an exception for numerical trouble).

    Raises
    ------
    InputError
        Bad values, a coefficient not finite on the horizon, a bad history, or a run
        needing more steps than the floor allows (see :func:`prepare_run`).

    Examples
    --------
    ``x' = −a x(t − 1)`` decays for a = 1; ``x' = +x(t − 1)`` grows and stops at the bound:

    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> tr = simulate(sys, history={"x": [1]}, t_end=1.0)
    >>> tr.outcome.value, round(float(tr.states["x"][-1, 0]), 10) + 0.0      # x = 1 − t on [0, 1]
    ('success', 0.0)
    >>> grows = System([Equation(x, [Term(x(t - 1)[0])])], parameters=P)
    >>> tr = simulate(grows, history={"x": [1]}, t_end=20.0, divergence_bound=100)
    >>> tr.outcome.value, tr.status.value, 7 < tr.t_fail < 8
    ('diverged', 'failed', True)
    >>> simulate(sys, history={"x": [1]}, t_end=1.0, values={"a": -1})
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: a: expected a > 0 (it must be positive), got a=-1
    """
    prep = prepare_run(system, history=history, t_end=t_end, values=values, t0=t0, step=step, integrals=integrals)
    if deadline is None and budget is not None:
        deadline = budget.deadline()
    if integrator not in ("auto", "compiled", "scipy"):
        raise InputError(f"integrator: expected 'auto', 'compiled' or 'scipy', got {integrator!r}")
    compiled = None if integrator == "scipy" else solve_compiled(
        prep, system, history=history, values=values, t_end=t_end, step=step, t0=t0, method=method,
        divergence_bound=divergence_bound, t_eval=t_eval, deadline=deadline,
        monitors=_monitors(system, prep.compiled.layout), min_mean_step=(t_end - t0) / MAX_STEPS, integrals=integrals)
    if compiled is None and integrator == "compiled":
        raise UnsupportedInput(f"{system.name or 'the system'}: the compiled integrator takes windows and sums of "
                               f"exponential kernels, constant histories and method='DOP853'; this run has "
                               f"{_why_scipy(prep, history, method, integrals)}; use integrator='auto' or 'scipy'")
    if compiled is not None:
        if progress is not None:
            progress(1.0)
        return _trajectory(system, prep, compiled[0], compiled[2], values, step, compiled[1])
    comp, phi = prep.compiled, prep.history
    n_aux = len(comp.aux)
    aux0 = np.zeros(n_aux)

    def full_history(s_):
        return np.concatenate([phi(s_), aux0]) if n_aux else phi(s_)

    if n_aux:
        aux0[:] = comp.aux_initial(t0, _InitialPast(full_history, t0))
    start = time.monotonic()
    sol = solve_dde(comp.fun, (t0, t_end), full_history, lags=comp.lags, method=method, rtol=step.rtol,
                    atol=step.atol, max_step=prep.max_step, divergence_bound=divergence_bound, t_eval=t_eval,
                    resync=comp.resync if any(a.kind == "window" for a in comp.aux) else None,
                    monitors=_monitors(system, comp.layout), progress=progress, deadline=deadline,
                    min_mean_step=(t_end - t0) / MAX_STEPS)
    return _trajectory(system, prep, sol, time.monotonic() - start, values, step, SCIPY)


def _why_scipy(prep, history, method, integrals) -> str:
    """What keeps a run off the compiled integrator (for the error message)."""
    if method != "DOP853":
        return f"method={method!r}"
    if integrals != "auto" or prep.compiled.quads:
        return "a quadrature term (a general kernel)" if prep.compiled.quads else f"integrals={integrals!r}"
    def in_t(h):
        if isinstance(h, (list, tuple)):
            return any(in_t(v) for v in h)
        if isinstance(h, str):
            return "t" in h
        return callable(h) and not isinstance(h, sympy.Basic) or (isinstance(h, sympy.Basic) and bool(h.free_symbols))

    if any(in_t(h) for h in history.values()):
        return "a history that is a function of t"
    return "a right-hand side the compiled family refuses (see compile_family)"


def _trajectory(system, prep, sol, seconds, values, step, integrator) -> Trajectory:
    """The Trajectory of a solved run (either integrator)."""
    comp = prep.compiled
    if sol.t_eval is not None and sol.y_eval is not None:
        times, Y = np.asarray(sol.t_eval), np.asarray(sol.y_eval)
        keep = times <= sol.t[-1] + 1e-12
        times, Y = times[keep], Y[keep]
    else:
        times, Y = sol.t, sol.y
    states = {name: Y[:, sl] for name, sl in comp.layout.items()}
    drift = {name: float(v) for name, v in sol.monitor_max.items()}
    resolved = dict(system.parameters.resolve(values or {}, use_defaults=True))
    return Trajectory(system.name, sol.outcome, sol.message, times, states, sol.t_fail, drift, sol.nfev,
                      sol.n_steps, seconds, sol, dict(comp.layout), step, prep.step_cap, prep.step_cap_reason,
                      resolved, integrator)


class _InitialPast:
    """The initial history seen as a 'past' for quadrature at t0 (before any step)."""

    def __init__(self, phi, t0):
        self.phi, self.t_last = phi, t0

    def __call__(self, s_):
        return np.array([self.phi(x) for x in np.atleast_1d(s_)])

    def integrate(self, g, a, b, *, with_time=False):
        nodes, weights = np.polynomial.legendre.leggauss(32)
        edges = np.linspace(a, b, 17)
        total = 0.0
        for lo, hi in zip(edges[:-1], edges[1:]):
            s_ = 0.5 * (hi - lo) * nodes + 0.5 * (hi + lo)
            Y = self(s_)
            vals = np.asarray(g(s_, Y) if with_time else g(Y), dtype=float).reshape(len(s_), -1)
            total = total + 0.5 * (hi - lo) * (weights @ vals)
        return np.atleast_1d(total)
