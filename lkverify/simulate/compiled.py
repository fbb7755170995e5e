"""One run of :func:`~lkverify.simulate.runs.simulate` on the compiled integrator (:mod:`lkverify.simulate.dop853`).

:func:`solve_compiled` runs what the compiled path supports — windows and sums of exponential
kernels as auxiliary states, constant initial histories, SciPy's DOP853 — and returns the
:class:`~lkverify.simulate.solver.DDESolution` :func:`~lkverify.simulate.solver.solve_dde` would
(its dense solution, monitors at the accepted steps, outcome and message), or ``None`` when the
run needs the SciPy path (a quadrature term, a history that is a function of t, another method).

The integrator is the one :func:`~lkverify.simulate.solver.solve_dde` drives with SciPy's
stepper, compiled: the same tableau, error estimate, step-size control, first step, breakpoints,
window re-synchronisation and outcomes, so the two paths agree to rounding
(``tests/simulate/test_compiled.py``).  A time budget is honoured between calls of the kernel:
it runs with a step limit (20,000 accepted steps, ×4 per call) and the deadline is checked when
the limit is reached (a deadline already passed: one step, as the SciPy path takes).

Examples
--------
>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> from lkverify.simulate.runs import prepare_run
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - 1)[0])])], parameters=P)
>>> prep = prepare_run(sys, history={"x": [1]}, t_end=2.0)
>>> sol, how, seconds = solve_compiled(prep, sys, history={"x": [1]}, values=None, t_end=2.0)
>>> how, sol.outcome.value, round(float(sol.sol(1.5)[0]), 12)      # x = 1 − t + (t − 1)²/2 on [1, 2]
('compiled DOP853 (native code)', 'success', -0.375)
"""

from __future__ import annotations

import time
import types

import numpy as np

from ..errors import InputError, UnsupportedInput
from .control import StepControl
from .events import DISCONTINUITY_ORDER, FLOOR_WINDOW, MAX_STEPS, breakpoints
from .history import DenseHistory
from .solver import DDESolution, Outcome

__all__ = ["SCIPY", "solve_compiled"]

#: the label of the SciPy path (``Trajectory.integrator``)
SCIPY = "SciPy DOP853 (Python right-hand side)"
_FIRST_LIMIT = 20_000
_FIRST_STORE = 4096


def solve_compiled(prep, system, *, history, values, t_end: float, step=None, t0: float = 0.0, method: str = "DOP853",
                   divergence_bound: float = 1e8, t_eval=None, deadline=None, monitors=None, min_mean_step=None,
                   integrals: str = "auto"):
    """``(DDESolution, integrator label, seconds in the kernel)`` of the run ``prep`` (:func:`~lkverify.simulate.runs.prepare_run`), or None.

    None when the compiled path does not apply: ``method`` other than DOP853, ``integrals`` not
    ``"auto"``, a quadrature term, a function of the system the compiled family cannot print, or a
    history that is a function of t.
    """
    from .family import compile_family

    comp = prep.compiled
    if method != "DOP853" or integrals != "auto" or comp.quads:
        return None
    try:
        fam = compile_family(system, values, grid=())
        x0 = fam.constant_history(history)
    except UnsupportedInput:
        return None
    p = np.zeros(0)
    y0 = np.concatenate([x0, fam.aux_start(p, x0, t0=t0)])
    lags = np.array(fam.lags(p), dtype=float).reshape(1, -1)
    breaks = breakpoints(t0, t_end, lags[0], DISCONTINUITY_ORDER)
    targets = np.append(breaks, t_end).reshape(1, -1)
    te = np.zeros(0) if t_eval is None else np.asarray(t_eval, dtype=float)
    step = StepControl() if step is None else step
    run = _Kernel(fam, p, y0, x0, lags, targets, t0, step, prep.max_step, divergence_bound, min_mean_step)
    run.until_done(deadline)
    label = f"compiled DOP853 ({'native code' if fam.backend == 'native' else 'numba'})"
    return run.solution(te, monitors or {}, deadline, breaks), label, run.seconds


class _Kernel:
    """The kernel's arguments for one point, its calls (step limit ×4 until done), and the DDESolution."""

    def __init__(self, fam, p, y0, x0, lags, targets, t0, step, hcap, bound, floor):
        self.fam, self.p, self.y0, self.x0, self.lags, self.targets = fam, p, y0, x0, lags, targets
        self.t0, self.bound, self.hcap = float(t0), float(bound), float(hcap)
        self.rtol, self.atol = float(step.rtol), float(step.atol)
        self.floor = 0.0 if floor is None else float(floor)
        self.n = fam.n
        self.store = _FIRST_STORE

    def prepare(self) -> None:
        """The compiled functions, the windows and the first step (once per run, whatever the calls)."""
        from .batch import first_steps          # numba: imported when a run starts

        rhs = self.fam.functions()[0]
        self.windows = np.array(self.fam.windows, dtype=np.int64).reshape(-1, 2)
        self.first = first_steps(rhs, self.p.reshape(1, -1), self.y0.reshape(1, -1), self.x0.reshape(1, -1),
                                 self.lags.shape[1], self.targets[:, 0] - self.t0, self.t0, self.rtol, self.atol)
        if self.first[0] < 0:
            raise InputError(f"the right-hand side is not finite at t0={self.t0:g}; expected finite values at the "
                             f"initial state; check coefficients and the history at t0")

    def call(self, limit: int):
        from .dop853 import run_batch

        fam, n = self.fam, self.n
        rhs, win = fam.functions()[:2]
        te = np.zeros(0)                # the samples are taken from the dense solution afterwards
        out = np.zeros((1, 0, fam.n_states))
        code, t_fail = np.zeros(1, dtype=np.int64), np.zeros(1)
        stats = np.zeros((1, 4), dtype=np.int64)
        store_t, store_c = np.zeros(self.store + 1), np.zeros((self.store, 8, n))
        store_t[0] = self.t0
        windows, first = self.windows, self.first
        run_batch(rhs, win, self.p.reshape(1, -1), self.y0.reshape(1, -1), np.ascontiguousarray(self.x0), self.lags,
                  windows, self.targets, np.array([self.targets.shape[1]], dtype=np.int64), self.t0, te,
                  self.rtol, self.atol, float(self.hcap), self.bound, int(limit), self.floor,
                  np.zeros(1, dtype=np.int64), first, out, code, t_fail, stats, store_t, store_c)
        stats[0, 1] += 2                           # first_steps' evaluations
        return int(code[0]), float(t_fail[0]), stats[0].copy(), store_t, store_c

    def until_done(self, deadline) -> None:
        limit = _FIRST_LIMIT if deadline is not None else MAX_STEPS
        if deadline is not None and deadline.expired:   # spent before the run: one step, as the SciPy path takes
            limit = 1
        self.fam.functions()                       # compiled once per process, before the clock starts
        start = time.monotonic()
        self.prepare()
        while True:
            code, t_fail, stats, store_t, store_c = self.call(limit)
            if stats[3] < 0:                       # the store was too small: four times larger, again
                self.store *= 4
                continue
            budget = code == list(Outcome).index(Outcome.BUDGET) and stats[0] >= limit
            if budget and limit < MAX_STEPS and not (deadline is not None and deadline.expired):
                limit *= 4
                continue
            break
        self.result = (code, t_fail, stats, store_t[:stats[3] + 1], store_c[:stats[3]])
        self.seconds = time.monotonic() - start

    def solution(self, t_eval, monitors, deadline, breaks) -> DDESolution:
        code, t_fail, stats, tb, C = self.result
        outcome = list(Outcome)[code]
        m = int(stats[3])
        past = DenseHistory.from_dop853(self.y0, self.t0, tb, C, float(self.lags.min()) if self.lags.size else 1.0)
        Y = past._Y
        mons = {name: np.array([float(f(tt, yy)) for tt, yy in zip(tb, Y)]) for name, f in monitors.items()}
        message, fail = self.message(outcome, t_fail, tb, Y, stats, deadline), t_fail
        if outcome is Outcome.SUCCESS:
            fail = None
        te = ye = None
        if t_eval.size:
            te = t_eval[t_eval <= tb[-1]]
            ye = past(te)
        return DDESolution(outcome=outcome, message=message, t=tb.copy(), y=Y.copy(), sol=past, t_fail=fail,
                           nfev=int(stats[1]), n_steps=m, n_rejected=int(stats[2]),
                           monitors=types.MappingProxyType(mons),
                           monitor_max=types.MappingProxyType({k: float(np.max(np.abs(v))) for k, v in mons.items()}),
                           breakpoints=breaks, t_eval=te, y_eval=ye)

    def message(self, outcome, t_fail, tb, Y, stats, deadline) -> str:
        m, bound = int(stats[0]), self.bound
        if outcome is Outcome.SUCCESS:
            return f"integrated to t_end={self.targets[0, -1]:g} in {m} steps ({stats[2]} rejected, {stats[1]} evaluations)"
        if outcome is Outcome.BUDGET:
            what = deadline.message() if deadline is not None else "the step limit was reached"
            return (f"{what} at t={t_fail:.6g} of t_end={self.targets[0, -1]:g} after {m} steps; the run is "
                    f"incomplete (give a larger time budget, or a shorter t_end)")
        if m == 0 and outcome is Outcome.DIVERGED and not float(self.y0 @ self.y0) <= bound * bound:
            return (f"‖y(t0)‖ = {np.linalg.norm(self.y0):g} already exceeds divergence_bound={bound:g}")
        h = np.diff(tb)
        if m >= FLOOR_WINDOW and h[-FLOOR_WINDOW:].mean() < self.floor:
            mean = float(h[-FLOOR_WINDOW:].mean())
            if outcome is Outcome.DIVERGED:
                return (f"blow-up at t≈{t_fail:.6g}: ‖y‖ grew to {np.linalg.norm(Y[-1]):.3g} (from "
                        f"{np.linalg.norm(self.y0):.3g}) while the steps shrank to {mean:.3g} on average, below "
                        f"the floor {self.floor:.3g}")
            return (f"steps collapsed at t={t_fail:.6g}: the last {FLOOR_WINDOW} steps average {mean:.3g}, below "
                    f"the floor {self.floor:.3g}; at this step size t_end={self.targets[0, -1]:g} needs about "
                    f"{(self.targets[0, -1] - t_fail) / mean:.2g} more steps (a stiff system: an explicit method "
                    f"needs steps of its fastest time scale; or a t_end too long for the system's time scale)")
        if outcome is Outcome.DIVERGED and m and not np.isfinite(Y[-1]).all():
            return f"y became non-finite at t={t_fail:.10g}"
        if outcome is Outcome.DIVERGED and m and not float(Y[-1] @ Y[-1]) <= bound * bound:
            return f"‖y‖ exceeded divergence_bound={bound:g} at t={t_fail:.10g}"
        if outcome is Outcome.DIVERGED:
            return (f"the right-hand side returned non-finite values; the step size collapsed while retrying from "
                    f"t={t_fail:.10g}")
        return f"DOP853 failed at t={t_fail:.10g}: Required step size is less than spacing between numbers."
