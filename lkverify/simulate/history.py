"""The dense solution of a DDE run: initial history, then the accepted steps' polynomials.

:class:`DenseHistory` is what the right-hand side sees as ``past`` during a run of
:func:`lkverify.simulate.solver.solve_dde` and what :attr:`DDESolution.sol` holds after it.

SciPy's dense outputs are converted to polynomials by exact linear maps for the two
layouts SciPy uses today (``Dop853DenseOutput.F``, ``RkDenseOutput.Q``: private
attributes); the map is checked once per run against SciPy's public ``__call__``
and, if it disagrees (a changed layout), every step is converted by sampling the
public dense output at Chebyshev nodes instead.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from math import comb

import numpy as np

from ..errors import InputError

__all__ = ["DenseHistory"]

_EPS = np.finfo(float).eps
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)   # 8 Gauss–Legendre nodes: exact to degree 15
_SMALL_BATCH = 16                           # up to this many points: batched matmul, else Horner

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
    >>> from lkverify.simulate.solver import solve_dde
    >>> res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 1.0), [1.0], lags=[1.0])
    >>> past = res.sol
    >>> past(0.25).round(12).tolist(), past([0.5, 0.75]).round(12).tolist()
    ([0.75], [[0.5], [0.25]])
    >>> round(float(past.integrate(lambda Y: Y[:, 0], -1.0, 1.0)), 12)   # 1 + 1/2
    1.5
    """

    def __init__(self, history, t0: float, y0: np.ndarray, degree: int, piece: float, *,
                 converter: str = "auto"):
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
        if converter not in ("auto", "generic"):
            raise InputError(f"converter: expected 'auto' or 'generic', got {converter!r}")
        # "dop853" | "rk45" (exact coefficient maps) | "generic" (sampling); "auto" chooses on the first step
        self._converter = None if converter == "auto" else "generic"
        self._fit_u, self._fit_inv = _chebyshev_fit(degree)

    @classmethod
    def from_dop853(cls, y0: np.ndarray, t0: float, tb: np.ndarray, coeffs: np.ndarray, piece: float) -> "DenseHistory":
        """The dense solution of a compiled run (:mod:`lkverify.simulate.dop853`) with a constant history ``y0``.

        ``tb`` (m + 1,) the step boundaries, ``coeffs`` (m, 8, n) every step's ``y_old`` and SciPy's
        ``Dop853DenseOutput.F`` rows, converted to this class's polynomials by the exact map.
        """
        out = cls(None, t0, np.asarray(y0, dtype=float), 7, piece)
        m = coeffs.shape[0]
        out._m = m
        out._tb = np.array(tb, dtype=float)
        h = np.diff(out._tb)
        out._mid = out._tb[:-1] + 0.5 * h
        out._ihw = 2.0 / h
        out._C = np.einsum("ij,mjn->min", _DOP853_U, coeffs[:, 1:])
        out._C[:, 0] += coeffs[:, 0]
        out._Y = np.empty((m + 1, out._n))
        out._Y[0] = y0
        out._Y[1:] = coeffs[:, 0] + coeffs[:, 1]         # y_old + F0: the end of each step (x = 1)
        out._converter = "dop853"
        return out

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

    @property
    def converter(self) -> str | None:
        """How SciPy's dense output is turned into polynomials: ``"dop853"``, ``"rk45"``, ``"generic"``
        (``None`` before the first step)."""
        return self._converter

    def append(self, dense, ta: float, tb: float, y: np.ndarray) -> None:
        """Store one accepted step ``[ta, tb]``: SciPy's ``dense`` output and the state ``y`` at ``tb``."""
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

