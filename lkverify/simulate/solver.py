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
* Every step is capped at ``min(lags)``, so every delayed argument
  ``t_n + c h - lag`` of a stage lies in already-accepted history (or the initial
  history).  Delayed values are looked up from the accepted steps' dense output
  (7th order for DOP853, 4th order for RK45), so the interpolation error of the
  history is of the order of the dense output and is covered by the step error
  control of the step it came from.
* With a general initial history ``y'`` jumps at ``t0``; the jump propagates to
  ``t0 + sum_i k_i lag_i``.  Steps land exactly on these breakpoints (the SciPy
  solver is restarted at each, with its last step size as ``first_step``) up to
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

import dataclasses
import enum
import math
import numbers
import types
from collections.abc import Callable, Mapping, Sequence
from math import comb

import numpy as np
from scipy.integrate import DOP853, RK45
from scipy.optimize import brentq

from ..errors import InputError

__all__ = ["DDESolution", "DenseHistory", "Outcome", "solve_dde"]

_EPS = np.finfo(float).eps
_METHODS = {"DOP853": DOP853, "RK45": RK45}
_DEGREE = {"DOP853": 7, "RK45": 4}          # degree of the dense-output polynomial
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)   # 8 Gauss–Legendre nodes: exact to degree 15
_SMALL_BATCH = 16                           # up to this many points: batched matmul, else Horner
#: number of accepted steps whose mean is compared with ``min_mean_step``
FLOOR_WINDOW = 200
#: a step collapse with ‖y‖ grown by this factor over its initial size (at least 1) is reported as a blow-up
BLOWUP_GROWTH = 1e3


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


# -- polynomial representation of a step -------------------------------------
#
# Every accepted step [ta, tb] is stored as a polynomial in u = 2 (s - mid) / h in [-1, 1]:
#     y(s) = sum_d C[d] u**d,  C of shape (D + 1, n).
# SciPy's dense outputs are converted by exact linear maps (coefficients are dyadic rationals).


def _x_to_u(degree: int) -> np.ndarray:
    """B with c_u = B @ c_x for x = (u + 1) / 2 (monomial coefficients, lowest first)."""
    B = np.zeros((degree + 1, degree + 1))
    for j in range(degree + 1):
        for i in range(j + 1):
            B[i, j] = comb(j, i) / 2.0 ** j
    return B


def _dop853_map() -> np.ndarray:
    """M (8, 7) with u-coefficients = M @ F for SciPy's ``Dop853DenseOutput`` (minus y_old).

    SciPy evaluates y_old + x(F0 + (1-x)(F1 + x(F2 + (1-x)(F3 + ...)))); expand it.
    """
    A = np.zeros((8, 7))
    for col in range(7):
        p = np.zeros(8)
        for i, row in enumerate(range(6, -1, -1)):
            p[0] += row == col
            shifted = np.concatenate(([0.0], p[:-1]))
            p = shifted if i % 2 == 0 else p - shifted
        A[:, col] = p
    return _x_to_u(7) @ A


_DOP853_U = _dop853_map()
_RK45_U = _x_to_u(4)


def _chebyshev_fit(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes in u and the inverse Vandermonde: the generic conversion of any dense output."""
    u = np.cos(np.pi * (2 * np.arange(degree + 1) + 1) / (2 * (degree + 1)))
    return u, np.linalg.inv(np.vander(u, degree + 1, increasing=True))


def _horner(C: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Evaluate polynomials C (..., D+1, n) at u (...): returns (..., n)."""
    u = u[..., None]
    y = C[..., -1, :]
    for d in range(C.shape[-2] - 2, -1, -1):
        y = y * u + C[..., d, :]
    return y


class DenseHistory:
    """The solution on ``(-inf, t_last]``: initial history, then the accepted steps.

    The object passed as ``past`` to the right-hand side during a run, and
    :attr:`DDESolution.sol` after it.  Each accepted step is stored as its
    dense-output polynomial; points are located by :func:`numpy.searchsorted` on
    the step boundaries and evaluated vectorised.

    Created by :func:`solve_dde`; not meant to be constructed by users.

    Examples
    --------
    >>> res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 1.0), [1.0], lags=[1.0])
    >>> past = res.sol
    >>> past(0.25).round(12).tolist(), past([0.5, 0.75]).round(12).tolist()
    ([0.75], [[0.5], [0.25]])
    >>> round(float(past.integrate(lambda Y: Y[:, 0], -1.0, 1.0)), 12)   # 1 + 1/2
    1.5
    """

    def __init__(self, history, t0: float, y0: np.ndarray, degree: int, piece: float):
        self._t0 = float(t0)
        self._y0 = y0
        self._n = n = y0.shape[0]
        if callable(history):
            self._phi, self._const = history, None
        else:
            self._phi, self._const = None, y0
        self._piece = float(piece)   # sub-interval length for quadrature over the initial history
        self._D = degree
        self._pows = np.arange(degree + 1)
        self._m = 0                  # number of accepted steps
        cap = 64
        self._tb = np.empty(cap + 1)             # step boundaries t0 = tb[0] < tb[1] < ...
        self._tb[0] = t0
        self._mid = np.empty(cap)
        self._ihw = np.empty(cap)                # 2 / h
        self._C = np.empty((cap, degree + 1, n))
        self._Y = np.empty((cap + 1, n))         # y at the step boundaries (after resync)
        self._Y[0] = y0
        self._converter = None                   # "dop853" | "rk45" | "generic", chosen on the first step
        self._fit_u, self._fit_inv = _chebyshev_fit(degree)

    # -- properties --------------------------------------------------------
    @property
    def t0(self) -> float:
        """Initial time: history before, accepted steps after."""
        return self._t0

    @property
    def t_last(self) -> float:
        """End of the last accepted step (``t0`` before the first)."""
        return float(self._tb[self._m])

    @property
    def n(self) -> int:
        """Dimension of the state."""
        return self._n

    @property
    def n_steps(self) -> int:
        """Number of accepted steps stored."""
        return self._m

    # -- building (private) ------------------------------------------------
    def _grow(self) -> None:
        cap = 2 * self._mid.shape[0]

        def grown(a, size):
            b = np.empty((size,) + a.shape[1:])
            b[: a.shape[0]] = a
            return b

        self._tb = grown(self._tb, cap + 1)
        self._Y = grown(self._Y, cap + 1)
        self._mid = grown(self._mid, cap)
        self._ihw = grown(self._ihw, cap)
        self._C = grown(self._C, cap)

    def _convert(self, dense, ta: float, tb: float, out: np.ndarray) -> None:
        """Write the u-coefficients of SciPy's dense output into ``out`` (D+1, n)."""
        conv = self._converter
        if conv is None:
            conv = self._converter = self._choose_converter(dense, ta, tb)
        if conv == "dop853":
            np.matmul(_DOP853_U, dense.F, out=out)
            out[0] += dense.y_old
        elif conv == "rk45":
            np.matmul(_RK45_U[:, 1:], dense.Q.T, out=out)
            out *= tb - ta
            out[0] += dense.y_old
        else:
            s = 0.5 * (ta + tb) + 0.5 * (tb - ta) * self._fit_u
            np.matmul(self._fit_inv, np.asarray(dense(s)).T, out=out)

    def _choose_converter(self, dense, ta, tb) -> str:
        """Use the exact map for SciPy's known dense-output layouts; check it once against SciPy."""
        n, D = self._n, self._D
        name = type(dense).__name__
        conv = "generic"
        if name == "Dop853DenseOutput" and D == 7 and getattr(dense, "F", np.empty(0)).shape == (7, n):
            conv = "dop853"
        elif name == "RkDenseOutput" and D == 4 and getattr(dense, "Q", np.empty(0)).shape == (n, 4):
            conv = "rk45"
        if conv != "generic":
            self._converter = conv
            trial = np.empty((D + 1, n))
            self._convert(dense, ta, tb, trial)
            u = np.array([-0.61, 0.37, 0.93])
            ours = _horner(np.broadcast_to(trial, (3, D + 1, n)), u)
            theirs = np.asarray(dense(0.5 * (ta + tb) + 0.5 * (tb - ta) * u)).T
            scale = np.max(np.abs(theirs)) + 1e-300
            if not np.all(np.abs(ours - theirs) <= 1e-12 * scale):
                conv = "generic"          # SciPy's private layout changed: fall back to sampling
        return conv

    def _append(self, dense, ta: float, tb: float, y: np.ndarray) -> None:
        if self._m == self._mid.shape[0]:
            self._grow()
        m = self._m
        self._convert(dense, ta, tb, self._C[m])
        self._tb[m + 1] = tb
        self._mid[m] = 0.5 * (ta + tb)
        self._ihw[m] = 2.0 / (tb - ta)
        self._Y[m + 1] = y
        self._m = m + 1

    def _shift_last(self, delta: np.ndarray) -> None:
        """Add the ramp ``delta * (s - ta) / h`` to the last step (after a resync moved its end)."""
        m = self._m
        self._C[m - 1, 0] += 0.5 * delta
        self._C[m - 1, 1] += 0.5 * delta
        self._Y[m] += delta

    def _freeze(self) -> None:
        """Trim the buffers to the accepted steps (after the run)."""
        m = self._m
        self._tb = self._tb[: m + 1].copy()
        self._Y = self._Y[: m + 1].copy()
        self._mid = self._mid[:m].copy()
        self._ihw = self._ihw[:m].copy()
        self._C = self._C[:m].copy()

    # -- evaluation --------------------------------------------------------
    def _history(self, s: np.ndarray) -> np.ndarray:
        """Initial history at times s (1-d, all < t0): (len(s), n)."""
        if self._const is not None:
            return np.broadcast_to(self._const, (s.shape[0], self._n))
        phi, n = self._phi, self._n
        return np.array([np.reshape(np.asarray(phi(float(x)), dtype=float), (n,)) for x in s])

    def _steps(self, s: np.ndarray) -> np.ndarray:
        """Accepted-step polynomials at times s (1-d, all >= t0); beyond t_last extrapolates the last step."""
        m = self._m
        if m == 0:
            return np.broadcast_to(self._y0, (s.shape[0], self._n))
        idx = self._tb[1:m].searchsorted(s, side="right")
        u = (s - self._mid[idx]) * self._ihw[idx]
        if s.shape[0] <= _SMALL_BATCH:
            U = np.power.outer(u, self._pows)
            return np.matmul(U[:, None, :], self._C[idx])[:, 0, :]
        return _horner(self._C[idx], u)

    def _eval(self, s: np.ndarray) -> np.ndarray:
        """Solution at times s (1-d float array): (len(s), n)."""
        before = s < self._t0
        if not before.any():
            return self._steps(s)
        if before.all():
            return np.array(self._history(s))
        out = np.empty((s.shape[0], self._n))
        out[before] = self._history(s[before])
        out[~before] = self._steps(s[~before])
        return out

    def _lookup(self, s: np.ndarray, s_min: float) -> np.ndarray:
        """Fast path of the right-hand side: delayed values Z at s = t - lags."""
        m = self._m
        if s_min >= self._t0 and m:
            idx = self._tb[1:m].searchsorted(s, side="right")
            U = np.power.outer((s - self._mid[idx]) * self._ihw[idx], self._pows)
            return np.matmul(U[:, None, :], self._C[idx])[:, 0, :]
        return self._eval(s)

    def _slack(self) -> float:
        return 16 * _EPS * max(1.0, abs(self.t_last), abs(self._t0))

    def __call__(self, s, *, extrapolate: bool = False) -> np.ndarray:
        """The solution at time(s) ``s``.

        Parameters
        ----------
        s : float or array_like
            Times in ``(-inf, t_last]``; before ``t0`` the initial history is returned.
        extrapolate : bool, keyword-only
            Allow ``s > t_last``: the last accepted step's polynomial is continued (the
            current-step piece of a memory integral inside the right-hand side).
            Before the first step, the constant ``y(t0)`` is used.

        Returns
        -------
        ndarray
            Shape ``(n,)`` for a scalar ``s``, ``s.shape + (n,)`` for an array.
        """
        arr = np.asarray(s, dtype=float)
        flat = arr.reshape(-1)
        if flat.size and not np.isfinite(flat).all():
            raise InputError(f"DenseHistory: expected finite times, got {s!r}; remove NaN/inf times")
        if not extrapolate and flat.size and flat.max() > self.t_last + self._slack():
            raise InputError(
                f"DenseHistory: expected times <= t_last={self.t_last:.17g}, got {flat.max():.17g}; "
                "evaluate within the integrated range or pass extrapolate=True")
        out = self._eval(flat)
        return np.array(out.reshape(arr.shape + (self._n,)))

    def integrate(self, g: Callable, a: float, b: float, *, with_time: bool = False,
                  extrapolate: bool = False):
        """``∫_a^b g(y(s)) ds`` by 8-point Gauss–Legendre on every step piece.

        The interval is split exactly at the step boundaries (where the solution may
        have derivative jumps); each piece gets 8 nodes (exact for polynomials of
        degree 15, so for g linear or quadratic the only error is that of the dense
        output).  Over the initial history the pieces have length at most ``min(lags)``.

        Parameters
        ----------
        g : callable
            ``g(Y)`` with Y of shape (m, n) returning (m, k) or (m,); with
            ``with_time=True`` it is called as ``g(s, Y)`` with the node times s (m,)
            (kernels ``K(t - s)``).
        a, b : float
            ``a <= b <= t_last`` (``b`` beyond with ``extrapolate=True``).
        with_time, extrapolate : bool, keyword-only

        Returns
        -------
        ndarray (k,) or float
        """
        a, b = float(a), float(b)
        if not (math.isfinite(a) and math.isfinite(b) and a <= b):
            raise InputError(f"DenseHistory.integrate: expected finite a <= b, got a={a!r}, b={b!r}; "
                             "swap or fix the limits")
        if not extrapolate and b > self.t_last + self._slack():
            raise InputError(
                f"DenseHistory.integrate: expected b <= t_last={self.t_last:.17g}, got b={b:.17g}; "
                "integrate within the integrated range or pass extrapolate=True")
        S, Y, W = [], [], []
        t0 = self._t0
        if a < t0:                                   # initial history
            hb = min(b, t0)
            p = max(1, math.ceil((hb - a) / self._piece - 1e-12))
            edges = np.linspace(a, hb, p + 1)
            half = 0.5 * np.diff(edges)
            s = ((0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * _GL_X).ravel()
            S.append(s)
            Y.append(self._history(s))
            W.append((half[:, None] * _GL_W).ravel())
        lo = max(a, t0)
        hi = min(b, self.t_last)
        m = self._m
        if hi > lo and m:                             # accepted steps, split at their boundaries
            i0 = int(np.searchsorted(self._tb[1:m], lo, side="right"))
            i1 = int(np.searchsorted(self._tb[1:m], hi, side="left"))
            left = np.maximum(self._tb[i0:i1 + 1], lo)
            right = np.minimum(self._tb[i0 + 1:i1 + 2], hi)
            mid, ihw = self._mid[i0:i1 + 1], self._ihw[i0:i1 + 1]
            half = 0.5 * (right - left)
            s = (0.5 * (left + right))[:, None] + half[:, None] * _GL_X          # (p, 8)
            u = (s - mid[:, None]) * ihw[:, None]
            Y.append(_horner(self._C[i0:i1 + 1, None], u).reshape(-1, self._n))
            S.append(s.ravel())
            W.append((half[:, None] * _GL_W).ravel())
        lo = max(lo, self.t_last)
        if b > lo:                                    # extrapolated piece (or the constant y0)
            half = 0.5 * (b - lo)
            s = 0.5 * (lo + b) + half * _GL_X
            S.append(s)
            Y.append(self._steps(s))
            W.append(half * _GL_W)
        if not S:                                     # a == b: zero with g's shape
            S, Y, W = [np.array([a])], [self._eval(np.array([a]))], [np.zeros(1)]
        S, Y, W = np.concatenate(S), np.concatenate(Y), np.concatenate(W)
        G = np.asarray(g(S, Y) if with_time else g(Y), dtype=float)
        if G.ndim not in (1, 2) or G.shape[0] != S.shape[0]:
            raise InputError(
                f"DenseHistory.integrate: expected g to map ({S.shape[0]}, {self._n}) states to "
                f"({S.shape[0]}, k) or ({S.shape[0]},), got shape {G.shape}; vectorise g over rows")
        out = W @ G
        return float(out) if G.ndim == 1 else out

    def __repr__(self) -> str:
        return f"DenseHistory(n={self._n}, t0={self._t0:g}, t_last={self.t_last:g}, steps={self._m})"


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


# -- validation ----------------------------------------------------------------


def _breakpoints(t0: float, t_end: float, lags: np.ndarray, order: int) -> np.ndarray:
    """t0 + sum k_i lag_i for 1 <= sum k_i <= order, inside (t0, t_end), merged within rounding."""
    span = t_end - t0
    tol = 64 * _EPS * max(1.0, abs(t0), abs(t_end))
    if lags.size == 0 or order < 1:
        return np.empty(0)
    lags = np.unique(lags)
    level = lags[lags < span]
    found = [level]
    for _ in range(order - 1):
        level = np.unique((level[:, None] + lags[None, :]).ravel())
        level = level[level < span]
        if level.size == 0:
            break
        found.append(level)
    b = np.unique(np.concatenate(found)) + t0
    b = b[(b > t0 + tol) & (b < t_end - tol)]
    if b.size > 1:
        keep = np.concatenate(([True], np.diff(b) > tol))
        b = b[keep]
    return b


def _number(value, name: str, problems: list, *, allow_inf=False, allow_zero=False):
    """A positive (or non-negative) real number, else a problem is recorded and None returned."""
    v = float(value) if isinstance(value, numbers.Real) and not isinstance(value, bool) else math.nan
    if math.isnan(v) or not (allow_inf or math.isfinite(v)) or not (v > 0 or (allow_zero and v == 0)):
        want = "a non-negative number" if allow_zero else "a positive number"
        problems.append(f"{name}: expected {want}, got {value!r}")
        return None
    return v


def _named_monitors(monitors) -> list[tuple[str, Callable]]:
    items = list(monitors.items()) if isinstance(monitors, Mapping) else [
        (getattr(f, "__name__", ""), f) for f in monitors]
    named, seen = [], set()
    for i, (name, f) in enumerate(items):
        name = str(name) if name and name != "<lambda>" else f"monitor{i}"
        if name in seen:
            name = f"{name}_{i}"
        seen.add(name)
        named.append((name, f))
    return named


def _validate(fun, t_span, history, lags, method, rtol, atol, max_step, first_step, divergence_bound,
              discontinuity_order, t_eval, resync, monitors, progress):
    problems: list[str] = []
    if not callable(fun):
        problems.append(f"fun: expected a callable fun(t, y, Z, past) -> array (n,), got {type(fun).__name__}")
    t0 = t_end = None
    try:
        t0, t_end = (float(v) for v in t_span)
        if not (math.isfinite(t0) and math.isfinite(t_end) and t_end > t0):
            problems.append(f"t_span: expected finite (t0, t_end) with t_end > t0, got {tuple(t_span)!r}; "
                            "integrate forward in time")
            t0 = None
    except (TypeError, ValueError):
        problems.append(f"t_span: expected a pair (t0, t_end) of numbers, got {t_span!r}")
        t0 = None
    lag_list = [lags] if isinstance(lags, numbers.Real) else lags
    try:
        lag_arr = np.asarray(lag_list, dtype=float).reshape(-1)
        bad = [v for v in lag_arr if not (math.isfinite(v) and v > 0)]
        if bad:
            problems.append(f"lags: expected positive finite constant lags, got {list(lag_arr)!r}; "
                            "drop zero lags (use y itself) and give each lag > 0")
    except (TypeError, ValueError):
        problems.append(f"lags: expected a sequence of positive numbers, got {lags!r}")
        lag_arr = np.empty(0)
    if method not in _METHODS:
        problems.append(f"method: expected one of {sorted(_METHODS)}, got {method!r}")
    rtol = _number(rtol, "rtol", problems)
    if rtol is not None and rtol < 100 * _EPS:
        problems.append(f"rtol: expected rtol >= {100 * _EPS:.3g} (100 machine epsilons), got {rtol!r}")
    if np.ndim(atol) == 0:
        _number(atol, "atol", problems, allow_zero=True)
    elif not (np.all(np.isfinite(np.asarray(atol, dtype=float))) and np.all(np.asarray(atol, dtype=float) >= 0)):
        problems.append(f"atol: expected non-negative finite tolerance(s), got {atol!r}")
    max_step = _number(max_step, "max_step", problems, allow_inf=True)
    if first_step is not None:
        _number(first_step, "first_step", problems)
    _number(divergence_bound, "divergence_bound", problems, allow_inf=True)
    if not (isinstance(discontinuity_order, numbers.Integral) and not isinstance(discontinuity_order, bool)
            and discontinuity_order >= 0):
        problems.append(f"discontinuity_order: expected an integer >= 0, got {discontinuity_order!r}")
    for name, f in (("resync", resync), ("progress", progress)):
        if f is not None and not callable(f):
            problems.append(f"{name}: expected a callable or None, got {type(f).__name__}")
    try:
        named = _named_monitors(monitors)
        for name, f in named:
            if not callable(f):
                problems.append(f"monitors: expected callables monitor(t, y) -> float, "
                                f"got {type(f).__name__} for {name!r}")
    except (TypeError, AttributeError):
        problems.append(f"monitors: expected a sequence or mapping of callables, got {monitors!r}")
        named = []
    if t_eval is not None and t0 is not None:
        te = np.asarray(t_eval, dtype=float)
        if te.ndim != 1 or not np.isfinite(te).all() or (te.size and (te.min() < t0 or te.max() > t_end)):
            problems.append(f"t_eval: expected a 1-d array of times in [t0, t_end] = [{t0:g}, {t_end:g}], "
                            f"got {np.asarray(t_eval).shape} array spanning "
                            f"[{np.min(te) if te.size else 'nan'}, {np.max(te) if te.size else 'nan'}]")
    y0 = None
    if t0 is not None:
        y0 = _check_history(history, t0, lag_arr, problems)
    if problems:
        raise InputError("; ".join(problems))
    if atol is not None and np.ndim(atol) == 1 and np.shape(atol) != y0.shape:
        raise InputError(f"atol: expected a scalar or {y0.shape[0]} tolerances (one per state), got {np.shape(atol)}")
    return t0, t_end, lag_arr, y0, rtol, max_step, named


def _check_history(history, t0, lag_arr, problems):
    """y0 = history(t0) as (n,), checking dimension and finiteness at a few points."""
    points = [t0]
    if lag_arr.size:
        points += sorted(set(float(t0 - v) for v in lag_arr)) + [t0 - 0.5 * float(lag_arr.max())]
    values = []
    for s in points:
        try:
            v = np.asarray(history(s) if callable(history) else history, dtype=float)
        except (TypeError, ValueError) as exc:
            problems.append(f"history: expected a callable phi(s) -> array (n,) or a constant array, got an error "
                            f"at s={s:g}: {exc}")
            return None
        if v.ndim == 0:
            v = v.reshape(1)
        if v.ndim != 1 or v.size == 0:
            problems.append(f"history: expected a 1-d state of n >= 1 components, got shape {v.shape} at s={s:g}; "
                            "return a flat array with every state component")
            return None
        if values and v.shape != values[0].shape:
            problems.append(f"history: expected the same dimension n={values[0].shape[0]} at every s, "
                            f"got {v.shape[0]} at s={s:g}")
            return None
        if not np.isfinite(v).all():
            problems.append(f"history: expected finite values, got {v.tolist()} at s={s:g}; "
                            "fix the initial function (NaN/inf in the history)")
            return None
        values.append(v)
        if not callable(history):
            break
    return values[0].copy()


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
    t0, t_end, lag_arr, y0, rtol, max_step, named = _validate(
        fun, t_span, history, lags, method, rtol, atol, max_step, first_step, divergence_bound,
        discontinuity_order, t_eval, resync, monitors, progress)
    n = y0.shape[0]
    solver_cls = _METHODS[method]
    n_stages = solver_cls.n_stages
    nlag = lag_arr.shape[0]
    lag_min = float(lag_arr.min()) if nlag else math.inf
    lag_max = float(lag_arr.max()) if nlag else 0.0
    hmax = min(max_step, lag_min)
    bound = float(divergence_bound)
    past = DenseHistory(history, t0, y0, _DEGREE[method], lag_min if nlag else 1.0)

    # -- the right-hand side seen by SciPy ---------------------------------
    Z_empty = np.empty((0, n))
    lookup = past._lookup
    nfev = 0
    bad_t = None            # first time fun returned non-finite values since the last accepted step

    def call(t, y, Z):
        try:
            return np.asarray(fun(t, y, Z, past), dtype=float)
        except (ZeroDivisionError, OverflowError, FloatingPointError):
            return np.full(n, np.nan)

    def rhs(t, y):
        nonlocal nfev, bad_t
        nfev += 1
        Z = lookup(t - lag_arr, t - lag_max) if nlag else Z_empty
        f = call(t, y, Z)
        if bad_t is None and not np.isfinite(f).all():
            bad_t = t
        return f

    f0 = call(t0, y0.copy(), lookup(t0 - lag_arr, t0 - lag_max) if nlag else Z_empty)
    nfev += 1
    if f0.shape == (n,) and not np.isfinite(f0).all():
        raise InputError(f"fun: the right-hand side is not finite at t0={t0:g} (got {f0.tolist()}); expected "
                         f"finite values at the initial state; check coefficients and the history at t0")
    if f0.shape != (n,):
        raise InputError(f"fun: expected fun(t0, y, Z, past) to return shape ({n},) like the history phi(t0), "
                         f"got {f0.shape}; return every state component (auxiliary states included) or fix the history")

    breaks = _breakpoints(t0, t_end, lag_arr, discontinuity_order)
    targets = list(breaks) + [t_end]
    mon_values = {name: [float(f(t0, y0.copy()))] for name, f in named}
    span = t_end - t0
    next_progress = 0.01
    n_rejected = 0
    outcome, message, t_fail = Outcome.SUCCESS, "", None
    t, y = t0, y0.copy()
    h_next = None if first_step is None else float(first_step)
    floor = None if min_mean_step is None else float(min_mean_step)
    recent = np.zeros(FLOOR_WINDOW)        # lengths of the last accepted steps (ring buffer)
    y_scale = max(1.0, float(np.linalg.norm(y0)))

    if not float(np.dot(y0, y0)) <= bound * bound:
        outcome, t_fail = Outcome.DIVERGED, t0
        message = f"‖y(t0)‖ = {np.linalg.norm(y0):g} already exceeds divergence_bound={bound:g}"
        targets = []
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        for target in targets:
            fs = None if h_next is None else min(h_next, hmax, target - t)
            solver = solver_cls(rhs, t, y, target, max_step=hmax, rtol=rtol, atol=atol, first_step=fs)
            while solver.status == "running":
                calls = nfev
                msg = solver.step()
                if solver.status == "failed":
                    t_fail = float(solver.t)
                    if bad_t is not None:
                        outcome = Outcome.DIVERGED
                        message = (f"the right-hand side returned non-finite values at t={bad_t:.10g}; "
                                   f"the step size collapsed while retrying from t={t_fail:.10g}")
                    else:
                        outcome = Outcome.STEP_COLLAPSE
                        message = f"{method} failed at t={t_fail:.10g}: {msg}"
                    break
                n_rejected += max(0, (nfev - calls) // n_stages - 1)
                ta, t = float(solver.t_old), float(solver.t)
                if t == ta:
                    continue
                past._append(solver.dense_output(), ta, t, solver.y)
                y = solver.y
                if resync is not None:
                    y_new = np.asarray(resync(t, y, past), dtype=float)
                    if y_new.shape != (n,):
                        raise InputError(f"resync: expected resync(t, y, past) to return shape ({n},), "
                                         f"got {y_new.shape}; return the whole state")
                    if not np.array_equal(y_new, y):
                        past._shift_last(y_new - y)
                        solver.y = y = y_new.copy()
                        solver.f = solver.fun(t, y)        # the FSAL derivative must follow the new state
                bad_t = None
                for name, f in named:
                    mon_values[name].append(float(f(t, y)))
                yy = float(np.dot(y, y))
                if not yy <= bound * bound:
                    outcome = Outcome.DIVERGED
                    t_fail = _crossing(past, ta, t, bound)
                    message = (f"y became non-finite at t={t:.10g}" if not np.isfinite(y).all() else
                               f"‖y‖ exceeded divergence_bound={bound:g} at t={t_fail:.10g}")
                    break
                if floor is not None:
                    recent[past._m % FLOOR_WINDOW] = t - ta
                    if past._m >= FLOOR_WINDOW and recent.mean() < floor:
                        t_fail = t
                        mean = float(recent.mean())
                        ny = float(np.sqrt(yy))
                        if ny > BLOWUP_GROWTH * y_scale:
                            outcome = Outcome.DIVERGED
                            message = (f"blow-up at t≈{t:.6g}: ‖y‖ grew to {ny:.3g} (from {np.linalg.norm(y0):.3g}) "
                                       f"while the steps shrank to {mean:.3g} on average, below the floor "
                                       f"{floor:.3g}")
                        else:
                            outcome = Outcome.STEP_COLLAPSE
                            message = (f"steps collapsed at t={t:.6g}: the last {FLOOR_WINDOW} steps average "
                                       f"{mean:.3g}, below the floor {floor:.3g}; at this step size t_end={t_end:g} "
                                       f"needs about {(t_end - t) / mean:.2g} more steps (a stiff system: an "
                                       f"explicit method needs steps of its fastest time scale; or a t_end too "
                                       f"long for the system's time scale)")
                        break
                if deadline is not None and deadline.expired:
                    outcome, t_fail = Outcome.BUDGET, t
                    message = (f"{deadline.message()} at t={t:.6g} of t_end={t_end:g} after {past._m} steps; "
                               f"the run is incomplete (raise --budget, or shorten --t-end)")
                    break
                # the step size before a landing step truncated at the target is the better restart guess
                h_abs = float(getattr(solver, "h_abs", solver.step_size))
                h_next = h_abs if (t != target or h_next is None) else max(h_next, h_abs)
                if progress is not None and (t - t0) >= next_progress * span:
                    fraction = (t - t0) / span
                    progress(min(1.0, fraction))
                    next_progress = math.floor(fraction * 100 + 1e-9) / 100 + 0.01
            if outcome is not Outcome.SUCCESS:
                break

    m = past._m
    past._freeze()
    if outcome is Outcome.SUCCESS:
        message = f"integrated to t_end={t_end:g} in {m} steps ({n_rejected} rejected, {nfev} evaluations)"
    te = ye = None
    if t_eval is not None:
        te = np.asarray(t_eval, dtype=float)
        te = te[te <= past.t_last]
        ye = past(te)
    mons = {name: np.asarray(v) for name, v in mon_values.items()}
    return DDESolution(
        outcome=outcome, message=message, t=past._tb.copy(), y=past._Y.copy(), sol=past,
        t_fail=t_fail, nfev=nfev, n_steps=m, n_rejected=n_rejected,
        monitors=types.MappingProxyType(mons),
        monitor_max=types.MappingProxyType({k: float(np.max(np.abs(v))) for k, v in mons.items()}),
        breakpoints=breaks, t_eval=te, y_eval=ye)


def _crossing(past: DenseHistory, ta: float, tb: float, bound: float) -> float:
    """First time in [ta, tb] where ‖y‖ reaches the bound (on the last step's polynomial); tb if unknown."""
    def excess(s):
        return float(np.linalg.norm(past._steps(np.array([s]))[0])) - bound

    try:
        ea, eb = excess(ta), excess(tb)
        if ea < 0 < eb and math.isfinite(eb):
            return float(brentq(excess, ta, tb, xtol=4 * _EPS * max(1.0, abs(tb))))
    except (ValueError, FloatingPointError):
        pass
    return float(tb)
