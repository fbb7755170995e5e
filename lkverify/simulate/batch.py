"""The numba DDE integrator of a :class:`~lkverify.simulate.family.CompiledFamily`: many points, one compiled loop.

:func:`integrate` runs every point of a batch on its own (its own adaptive steps), so a
point's result does not depend on the batch it is in: a batch equals its points run one
by one, bit for bit.

The integrator is :mod:`lkverify.simulate.dop853` (SciPy's DOP853 compiled: its dense output,
the method of steps, breakpoints, window auxiliaries re-synchronised by quadrature), the same
one :func:`~lkverify.simulate.runs.simulate` runs.

Outcomes (codes index :data:`OUTCOMES`, the members of :class:`~lkverify.simulate.solver.Outcome`)
-------------------------------------------------------------------------------------------------
* ``success`` — reached ``t_end``;
* ``diverged`` — a non-finite value, or ``‖y‖₂ > divergence_bound`` (``t_fail``: the
  crossing on the last step's dense output), or steps collapsing while ``‖y‖`` grew
  :data:`~lkverify.simulate.events.BLOWUP_GROWTH`-fold;
* ``step_collapse`` — a step below 10 units in the last place of t, or the mean of the
  last :data:`~lkverify.simulate.events.FLOOR_WINDOW` steps below ``(t_end − t0)/MAX_STEPS``
  (the step floor of :func:`~lkverify.simulate.runs.simulate`);
* ``budget`` — ``max_steps`` accepted steps without reaching ``t_end`` (at once, without
  stepping, when the steps capped at ``min(lags)`` cannot reach ``t_end`` in ``max_steps``).

A point never raises for numerical trouble; bad arguments raise
:class:`~lkverify.errors.InputError`.

>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> from lkverify.simulate.family import compile_family
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); x = Vector("x", 1)
>>> fam = compile_family(System([Equation(x, [Term(a * x(t - 1)[0])])], parameters=P), grid=["a"])
>>> res = fam.integrate([[-1.0], [1.0]], {"x": [1]}, t_end=30.0, t_eval=[0.0, 2.0], divergence_bound=1e3)
>>> [o.value for o in res.outcomes], round(float(res.y[0, -1, 0]), 10)     # x = 1 − t + (t − 1)²/2 at t = 2
(['success', 'diverged'], -0.5)
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import InputError
from .dop853 import OUTCOMES, run_batch
from .events import DISCONTINUITY_ORDER, MAX_STEPS, breakpoints
from .solver import Outcome

__all__ = ["BatchResult", "DISCONTINUITY_ORDER", "OUTCOMES", "first_steps", "integrate"]

_SUCCESS, _BUDGET = OUTCOMES.index(Outcome.SUCCESS), OUTCOMES.index(Outcome.BUDGET)


@dataclasses.dataclass(frozen=True, eq=False)
class BatchResult:
    """The runs of a batch of points.

    Attributes
    ----------
    outcome : ndarray (N,) of int
        Codes into :data:`OUTCOMES`; :attr:`outcomes` gives the :class:`Outcome` members.
    t_fail : ndarray (N,)
        Time of the failure (NaN for ``success``).
    t : ndarray (m,)
        The sample times (``t_eval``).
    y : ndarray (N, m, n_states)
        The states at ``t`` (no auxiliary states); NaN after the last accepted step of a failed run.
    layout : dict
        state name → slice of the last axis of ``y``.
    n_steps, nfev, n_rejected : ndarray (N,) of int
        Accepted steps, right-hand-side evaluations and rejected steps per point.
    seconds : float
        Wall-clock time of the batch.

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.simulate.family import compile_family
    >>> P = Parameters(); a = P.scalar("a", default=1); x = Vector("x", 2)
    >>> fam = compile_family(System([Equation(x, [Term(-a * x(t - 1))])], parameters=P), grid=["a"])
    >>> res = fam.integrate([[1.0], [0.5]], {"x": [1, 2]}, t_end=1.0, t_eval=[0.0, 1.0])
    >>> res.outcomes, res.y.shape, res.states(1)["x"].round(12).tolist()      # x = x0 (1 − a t) on [0, 1]
    ([<Outcome.SUCCESS: 'success'>, <Outcome.SUCCESS: 'success'>], (2, 2, 2), [[1.0, 2.0], [0.5, 1.0]])
    """

    outcome: np.ndarray
    t_fail: np.ndarray
    t: np.ndarray
    y: np.ndarray
    layout: dict
    n_steps: np.ndarray
    nfev: np.ndarray
    n_rejected: np.ndarray
    seconds: float

    @property
    def outcomes(self) -> list:
        """The outcome of every point, as :class:`Outcome` members."""
        return [OUTCOMES[int(c)] for c in self.outcome]

    def states(self, i: int) -> dict:
        """state name → array (len(t), dim) of point ``i`` (the shape of ``Trajectory.states``)."""
        return {name: self.y[i][:, sl] for name, sl in self.layout.items()}


def integrate(family, points, history, *, t_end: float, t_eval, rtol: float = 1e-8, atol: float = 1e-10,
              divergence_bound: float = 1e8, max_steps: int = 10**6, t0: float = 0.0) -> BatchResult:
    """Integrate ``family`` at every row of ``points`` from the constant ``history`` on [t0, t_end].

    Parameters
    ----------
    family : CompiledFamily
    points : array_like (N, len(family.grid))
        One point per row, coordinates in the order of ``family.grid``.
    history : mapping, or sequence of N mappings
        state name → constant vector: the same for every point, or one mapping per point
        (row ``i`` starts from ``history[i]``; e.g. a grid of initial states).
    t_end : float
    t_eval : array_like
        Nondecreasing sample times in [t0, t_end].
    rtol, atol : float
        Tolerances of the step-size control (both > 0).
    divergence_bound : float
        ``‖y‖₂`` above it ends a run as ``diverged``.
    max_steps : int
        Accepted steps per point; more ends the run as ``budget``.
    t0 : float

    Raises
    ------
    InputError
        Bad arguments, or a point whose lags are not positive and finite.

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.simulate.family import compile_family
    >>> P = Parameters(); tau = P.delay("tau", default=1); x = Vector("x", 1)
    >>> fam = compile_family(System([Equation(x, [Term(-x(t - tau)[0])])], parameters=P), grid=["tau"])
    >>> res = integrate(fam, [[0.5], [2.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0])
    >>> (res.y[:, 0, 0].round(12) + 0.0).tolist()       # τ = 1/2: 1 − t + (t − 1/2)²/2 at t = 1; τ = 2: 1 − t
    [0.125, 0.0]

    One history per point (x' = −x(t − 1/2) from x ≡ 1 and x ≡ 2: the solution scales with it):

    >>> res = integrate(fam, [[0.5], [0.5]], [{"x": [1]}, {"x": [2]}], t_end=1.0, t_eval=[1.0])
    >>> res.y[:, 0, 0].round(12).tolist()
    [0.125, 0.25]
    >>> integrate(fam, [[-1.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0])
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: points[0]: expected positive finite lags, got [-1.0] for tau at {'tau': -1.0}; drop the point or fix the delay
    """
    start = time.perf_counter()
    pts, te = _check(family, points, t_end, t_eval, rtol, atol, divergence_bound, max_steps, t0)
    rhs, win = family.functions()[:2]
    N, nl = pts.shape[0], len(family.exact_lags)
    x0s = _histories(family, history, N)
    lags = np.array([family.lags(p) for p in pts], dtype=float).reshape(N, nl)
    for i in np.nonzero(~np.all(np.isfinite(lags) & (lags > 0), axis=1))[0][:1]:
        raise InputError(f"points[{i}]: expected positive finite lags, got {lags[i].tolist()} for "
                         f"{', '.join(map(str, family.exact_lags))} at {dict(zip(family.grid, pts[i].tolist()))}; "
                         f"drop the point or fix the delay")
    y0 = np.array([np.concatenate([x0, family.aux_start(p, x0, t0=t0)]) for p, x0 in zip(pts, x0s)]).reshape(
        N, family.n)
    targets, counts = _targets(lags, float(t0), float(t_end))
    # steps are at most min(lags) long: a point that cannot reach t_end in max_steps steps is not stepped
    skip = (nl > 0) & ((t_end - t0) / np.where(nl > 0, lags.min(axis=1, initial=np.inf), 1.0) > max_steps)
    y = np.full((N, te.shape[0], family.n_states), np.nan)
    code = np.where(skip, _BUDGET, _SUCCESS).astype(np.int64)
    t_fail = np.where(skip, float(t0), np.nan)
    stats = np.zeros((N, 4), dtype=np.int64)
    distinct, group = np.unique(x0s, axis=0, return_inverse=True)
    windows = np.array(family.windows, dtype=np.int64).reshape(-1, 2)
    no_store = (np.zeros(1), np.zeros((0, 8, family.n)))
    first = first_steps(rhs, pts, y0, x0s, nl, targets[:, 0] - t0, float(t0), float(rtol), float(atol))
    for g, x0 in enumerate(distinct):      # the kernel takes one history: one call per distinct history
        run_batch(rhs, win, pts, y0, np.ascontiguousarray(x0), lags, windows, targets, counts, float(t0), te,
                  float(rtol), float(atol), math.inf, float(divergence_bound), int(max_steps),
                  (t_end - t0) / MAX_STEPS, (skip | (group.ravel() != g)).astype(np.int64), first, y, code,
                  t_fail, stats, *no_store)
    stats[:, 1] += np.where(skip, 0, np.where(first > 0, 2, 1))     # first_steps' evaluations
    t_fail[code == _SUCCESS] = np.nan
    return BatchResult(code, t_fail, te, y, dict(family.layout), stats[:, 0].copy(), stats[:, 1].copy(),
                       stats[:, 2].copy(), time.perf_counter() - start)


def first_steps(rhs, P, Y0, X0, n_lags: int, spans, t0: float, rtol: float, atol: float) -> np.ndarray:
    """SciPy's ``select_initial_step`` (error order 7, DOP853) for every point: the kernel's ``H0``.

    ``rhs`` a compiled function (its ``ctypes``), ``P`` (N, k) the points, ``Y0`` (N, n) the initial
    vectors, ``X0`` (N, n_states) the constant histories (every delayed value of the two evaluations),
    ``spans`` (N,) the first segment's lengths.  The step is not capped here (the kernel caps it at
    its largest step); −1 where f(t0, y0) is not finite.
    """
    import ctypes

    N, n = Y0.shape
    out = np.empty(N)
    f0, f1, yt = (np.empty(n) for _ in range(3))
    addr = [a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)) for a in (f0, f1, yt)]
    call = rhs.ctypes
    with np.errstate(all="ignore"):
        for i in range(N):
            y, p = np.ascontiguousarray(Y0[i]), np.ascontiguousarray(P[i])
            Z = np.ascontiguousarray(np.tile(X0[i], max(n_lags, 1)))
            yp, Zp, pp = (a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)) for a in (y, Z, p))
            call(t0, yp, Zp, pp, addr[0])
            if not np.all(np.isfinite(f0)):
                out[i] = -1.0
                continue
            scale = atol + np.abs(y) * rtol
            d0, d1 = (float(np.sqrt(np.mean((v / scale) ** 2))) for v in (y, f0))
            h0 = min(1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1, float(spans[i]))
            yt[:] = y + h0 * f0
            call(t0 + h0, addr[2], Zp, pp, addr[1])
            d2 = float(np.sqrt(np.mean(((f1 - f0) / scale) ** 2))) / h0
            h1 = max(1e-6, h0 * 1e-3) if (d1 <= 1e-15 and d2 <= 1e-15) else (0.01 / max(d1, d2)) ** (1 / 8)
            h = min(100 * h0, h1, float(spans[i]))
            out[i] = h if (h > 0 and np.isfinite(h)) else float(spans[i])
    return out


def _histories(family, history, n: int) -> np.ndarray:
    """The constant history of every point as an (n, n_states) array (one mapping for all, or one per point)."""
    if isinstance(history, Mapping):
        return np.tile(family.constant_history(history), (n, 1))
    if not isinstance(history, Sequence) or isinstance(history, str) or len(history) != n:
        raise InputError(f"history: expected a mapping state name → constant vector, or a sequence of one such "
                         f"mapping per point ({n}), got {type(history).__name__}"
                         f"{f' of length {len(history)}' if isinstance(history, Sequence) else ''}")
    return np.array([family.constant_history(h) for h in history], dtype=float).reshape(n, family.n_states)


def _targets(lags: np.ndarray, t0: float, t_end: float):
    """The breakpoints of every point, then t_end, as a padded (N, k) array and the counts (shared lags computed once)."""
    memo: dict = {}
    rows = []
    for lg in lags:
        key = lg.tobytes()
        if key not in memo:
            memo[key] = np.append(breakpoints(t0, t_end, lg, DISCONTINUITY_ORDER), t_end)
        rows.append(memo[key])
    counts = np.array([r.size for r in rows], dtype=np.int64)
    out = np.full((len(rows), int(counts.max())), t_end)
    for i, r in enumerate(rows):
        out[i, :r.size] = r
    return out, counts


def _check(family, points, t_end, t_eval, rtol, atol, bound, max_steps, t0):
    """(points as a C-contiguous (N, k) array, t_eval as an array), or InputError."""
    k = len(family.grid)
    try:
        pts = np.array(points, dtype=float, ndmin=2)
    except (TypeError, ValueError):
        raise InputError(f"points: expected an (N, {k}) array of numbers ({', '.join(family.grid)}), got "
                         f"{type(points).__name__}") from None
    if pts.ndim != 2 or pts.shape[1] != k or pts.shape[0] == 0:
        raise InputError(f"points: expected an (N, {k}) array, N ≥ 1, one column per grid name "
                         f"({', '.join(family.grid)}), got shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise InputError("points: expected finite coordinates, got NaN or inf; drop those points")
    for name, v in (("t0", t0), ("t_end", t_end), ("rtol", rtol), ("atol", atol), ("divergence_bound", bound)):
        if not (isinstance(v, (int, float, np.number)) and math.isfinite(v)):
            raise InputError(f"{name}: expected a finite number, got {v!r}")
    if not t_end > t0:
        raise InputError(f"t_end: expected a number greater than t0 = {t0:g}, got {t_end!r}")
    if not (rtol > 0 and atol > 0 and bound > 0):
        raise InputError(f"rtol, atol, divergence_bound: expected positive numbers (atol > 0: components that pass "
                         f"through 0 need it), got {rtol!r}, {atol!r}, {bound!r}")
    if not (isinstance(max_steps, (int, np.integer)) and max_steps >= 1):
        raise InputError(f"max_steps: expected a whole number ≥ 1, got {max_steps!r}")
    te = np.ascontiguousarray(np.atleast_1d(np.asarray(t_eval, dtype=float)))
    if te.ndim != 1 or te.size == 0 or not np.all(np.isfinite(te)) or np.any(np.diff(te) < 0) \
            or te[0] < t0 or te[-1] > t_end:
        raise InputError(f"t_eval: expected nondecreasing sample times in [t0, t_end] = [{t0:g}, {t_end:g}], got "
                         f"{len(te)} values from {te.min() if te.size else '-'} to {te.max() if te.size else '-'}; "
                         f"e.g. numpy.linspace(t0, t_end, 1001)")
    return np.ascontiguousarray(pts), te
