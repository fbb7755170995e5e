"""A grid of closed-loop runs of paper 003, integrated together (vectorised RK4).

The right-hand side is generated from the catalogue's symbolic :data:`~.equations.closed_loop`
(``System.rhs``, lambdified with numpy: the saturation prints as ``numpy.maximum``), never
retyped.  The grid runs every initial state at once with a fixed-step classical Runge–Kutta
scheme — the library's adaptive integrator runs one trajectory at a time, which is too slow for
the thousands of initial states a sampled region of attraction needs.  A run has converged when
|σ(T)| and ‖ω(T)‖ are below ``tol``; a run whose |σ| exceeds ``blowup`` (the MRP of the long way
round, Φ → 2π) or turns non-finite has not.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy

from lkverify import t

from .equations import P, closed_loop, omega, sigma

__all__ = ["DIRECTIONS", "GridRuns", "closed_loop_rhs", "integrate_batch", "run_grid", "run_points"]


def closed_loop_rhs(values):
    """f(σ (3, n), ω (3, n)) → (σ̇, ω̇) of (3), (11) at the given parameter values (numpy, vectorised)."""
    sub = P.substitution(P.resolve(dict(values)))
    args = [*sigma(t), *omega(t)]
    rhs = [closed_loop.rhs(s).xreplace(sub) for s in (sigma, omega)]
    f = sympy.lambdify(args, [list(r) for r in rhs], modules="numpy", cse=True)

    def rhs_fn(s, w):
        out = f(*s, *w)
        n = s.shape[1]
        return tuple(np.array([np.broadcast_to(np.asarray(c, dtype=float), (n,)) for c in part]) for part in out)

    return rhs_fn


def integrate_batch(values, s0, w0, *, t_end, dt):
    """RK4 from the columns of s0, w0 (3 × n) to t_end; returns σ(T), ω(T) and the max |σ| along the runs."""
    f = closed_loop_rhs(values)
    s, w = np.array(s0, dtype=float), np.array(w0, dtype=float)
    smax = np.linalg.norm(s, axis=0)
    steps = int(np.ceil(t_end / dt))
    h = t_end / steps
    with np.errstate(all="ignore"):
        for _ in range(steps):
            k1 = f(s, w)
            k2 = f(s + h / 2 * k1[0], w + h / 2 * k1[1])
            k3 = f(s + h / 2 * k2[0], w + h / 2 * k2[1])
            k4 = f(s + h * k3[0], w + h * k3[1])
            s = s + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            w = w + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            smax = np.fmax(smax, np.linalg.norm(s, axis=0))
            bad = ~np.isfinite(s).all(axis=0) | (smax > 1e3)
            s[:, bad], w[:, bad] = np.nan, np.nan
    return s, w, smax


#: direction pairs (σ0 direction, ω0 direction) sampled at each grid point
DIRECTIONS = ((np.array([1.0, 0, 0]), np.array([1.0, 0, 0])),       # ω along σ: rotating further away
              (np.array([1.0, 0, 0]), np.array([-1.0, 0, 0])),      # towards the target
              (np.array([1.0, 0, 0]), np.array([0, 1.0, 0])),       # across
              (np.array([2, 2, 1.0]) / 3, np.array([1.0, -2, 2]) / 3))


@dataclasses.dataclass(frozen=True)
class GridRuns:
    """Converged or not at each (|σ0|, ‖ω0‖) grid point (all sampled directions must converge)."""

    s: np.ndarray
    w: np.ndarray
    converged: np.ndarray  # (len(s), len(w)) bool
    t_end: float
    dt: float
    directions: int


def run_points(values, s_pts, w_pts, *, t_end, dt, tol=1e-3, directions=DIRECTIONS) -> np.ndarray:
    """Converged (bool per point) from |σ0| = s_pts, ‖ω0‖ = w_pts, every direction pair converging."""
    s_pts, w_pts = np.asarray(s_pts, float).ravel(), np.asarray(w_pts, float).ravel()
    s0 = np.hstack([np.outer(es, s_pts) for es, _ in directions])
    w0 = np.hstack([np.outer(ew, w_pts) for _, ew in directions])
    s, w, _ = integrate_batch(values, s0, w0, t_end=t_end, dt=dt)
    ok = (np.linalg.norm(s, axis=0) < tol) & (np.linalg.norm(w, axis=0) < tol)
    return ok.reshape(len(directions), len(s_pts)).all(axis=0)


def run_grid(values, s_values, w_values, *, t_end, dt, tol=1e-3, directions=DIRECTIONS) -> GridRuns:
    """:func:`run_points` on the grid s_values × w_values."""
    S, Wg = np.meshgrid(np.asarray(s_values, float), np.asarray(w_values, float), indexing="ij")
    ok = run_points(values, S, Wg, t_end=t_end, dt=dt, tol=tol, directions=directions).reshape(S.shape)
    return GridRuns(np.asarray(s_values, float), np.asarray(w_values, float), ok, float(t_end), float(dt),
                    len(directions))
