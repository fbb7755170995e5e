"""A grid of closed-loop runs of paper 003, on the library's batch integrator.

The closed loop (3), (11) of :data:`~.equations.closed_loop` is compiled once by
:func:`lkverify.simulate.family.compile_family` (the right-hand side is generated from the
symbolic system, never retyped) and every initial state runs in one call of
:func:`lkverify.simulate.batch.integrate` (adaptive DOPRI5, each run with its own steps, one
constant history per run: the loop has no delay, so the history is just the initial state).
Each run is classified at T = ``t_end``:

* ``CONVERGED`` — it reached T with |σ(T)| < ``tol`` and ‖ω(T)‖ < ``tol``;
* ``NOT_CONVERGED`` — it reached T farther out, or diverged: ‖(σ, ω)‖₂ above ``blowup``
  (the MRP of the long way round, Φ → 2π) or a non-finite value;
* ``UNDECIDED`` — its step budget ``max_steps`` ran out or its steps collapsed.

A grid point (|σ0|, ‖ω0‖) is converged when the runs of all its direction pairs
(:data:`DIRECTIONS`) converged, not converged when one of them did not converge, and
undecided otherwise.  Every class is ``simulated``: observed, not proved.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from lkverify.simulate import Outcome, compile_family

from .equations import closed_loop

__all__ = ["ATOL", "BLOWUP", "CONVERGED", "DIRECTIONS", "GridRuns", "MAX_STEPS", "NOT_CONVERGED", "RTOL",
           "UNDECIDED", "classify_runs", "integrate_runs", "run_grid", "run_points"]

#: step-size control of the runs (the batch integrator's defaults)
RTOL, ATOL = 1e-8, 1e-10
#: ‖(σ, ω)‖₂ above it ends a run as diverged
BLOWUP = 1e3
#: accepted steps per run (a run to t = 300 takes about 150)
MAX_STEPS = 10**5
#: the classes of a run and of a grid point
CONVERGED, NOT_CONVERGED, UNDECIDED = 1, 0, -1

#: direction pairs (σ0 direction, ω0 direction) sampled at each grid point
DIRECTIONS = ((np.array([1.0, 0, 0]), np.array([1.0, 0, 0])),       # ω along σ: rotating further away
              (np.array([1.0, 0, 0]), np.array([-1.0, 0, 0])),      # towards the target
              (np.array([1.0, 0, 0]), np.array([0, 1.0, 0])),       # across
              (np.array([2, 2, 1.0]) / 3, np.array([1.0, -2, 2]) / 3))


def integrate_runs(values, s0, w0, *, t_end, t_eval=None, rtol=RTOL, atol=ATOL, blowup=BLOWUP, max_steps=MAX_STEPS,
                   system=closed_loop):
    """Runs of ``system`` (default (3), (11)) from the columns of s0, w0 (3 × n) to t_end: a BatchResult.

    ``t_eval`` defaults to ``[t_end]``; ``res.y[i, k]`` is (σ, ω) of run i at ``t_eval[k]``.

    Examples
    --------
    >>> from lkverify.proofs.somov.equations import P
    >>> res = integrate_runs(P.resolve({}), [[0.0, 0.0], [0, 0], [0, 0]], [[0.0, 0.01], [0, 0], [0, 0]],
    ...                      t_end=300.0, t_eval=[0.0, 300.0])
    >>> [o.value for o in res.outcomes], res.y[:, 0, 3].tolist(), bool(abs(res.y[1, -1]).max() < 1e-6)
    (['success', 'success'], [0.0, 0.01], True)
    """
    s0, w0 = np.atleast_2d(np.asarray(s0, dtype=float)), np.atleast_2d(np.asarray(w0, dtype=float))
    fam = compile_family(system, dict(values), grid=())
    histories = [{"sigma": s0[:, i], "omega": w0[:, i]} for i in range(s0.shape[1])]
    return fam.integrate(np.zeros((len(histories), 0)), histories, t_end=float(t_end),
                         t_eval=[float(t_end)] if t_eval is None else t_eval, rtol=rtol, atol=atol,
                         divergence_bound=blowup, max_steps=max_steps)


def classify_runs(res, tol=1e-3) -> np.ndarray:
    """The class of every run of a BatchResult (int8: CONVERGED, NOT_CONVERGED, UNDECIDED), from its last sample.

    Examples
    --------
    >>> from lkverify.proofs.somov.equations import P
    >>> res = integrate_runs(P.resolve({}), [[0.05, 0.9], [0, 0], [0, 0]], [[0.0, 0.4], [0, 0], [0, 0]], t_end=300.0)
    >>> classify_runs(res).tolist(), classify_runs(res, tol=1e-30).tolist()    # near 0: converged; far out: not
    ([1, 0], [0, 0])
    """
    out = np.full(res.outcome.shape, UNDECIDED, dtype=np.int8)
    last = res.y[:, -1]
    near = (np.linalg.norm(last[:, res.layout["sigma"]], axis=1) < tol) & \
        (np.linalg.norm(last[:, res.layout["omega"]], axis=1) < tol)
    ends = np.array([o is Outcome.SUCCESS for o in res.outcomes])
    out[ends & near] = CONVERGED
    out[ends & ~near] = NOT_CONVERGED
    out[np.array([o is Outcome.DIVERGED for o in res.outcomes], dtype=bool)] = NOT_CONVERGED
    return out


@dataclasses.dataclass(frozen=True)
class GridRuns:
    """The class of each (|σ0|, ‖ω0‖) grid point (all sampled directions must converge)."""

    s: np.ndarray
    w: np.ndarray
    classes: np.ndarray  # (len(s), len(w)) int8: CONVERGED, NOT_CONVERGED, UNDECIDED
    t_end: float
    rtol: float
    atol: float
    directions: int

    @property
    def converged(self) -> np.ndarray:
        """(len(s), len(w)) bool: every direction pair converged."""
        return self.classes == CONVERGED

    @property
    def undecided(self) -> np.ndarray:
        """(len(s), len(w)) bool: no direction pair failed, one ran out of steps."""
        return self.classes == UNDECIDED


def run_points(values, s_pts, w_pts, *, t_end, rtol=RTOL, atol=ATOL, tol=1e-3, directions=DIRECTIONS,
               max_steps=MAX_STEPS, system=closed_loop) -> np.ndarray:
    """The class (int8 per point) from |σ0| = s_pts, ‖ω0‖ = w_pts over all direction pairs.

    Examples
    --------
    >>> from lkverify.proofs.somov.equations import P
    >>> run_points(P.resolve({}), [0.05, 0.9], [0.0, 0.4], t_end=300.0).tolist()
    [1, 0]
    """
    s_pts, w_pts = np.asarray(s_pts, float).ravel(), np.asarray(w_pts, float).ravel()
    s0 = np.hstack([np.outer(es, s_pts) for es, _ in directions])
    w0 = np.hstack([np.outer(ew, w_pts) for _, ew in directions])
    res = integrate_runs(values, s0, w0, t_end=t_end, rtol=rtol, atol=atol, max_steps=max_steps, system=system)
    runs = classify_runs(res, tol).reshape(len(directions), len(s_pts))
    out = np.where((runs == CONVERGED).all(axis=0), CONVERGED, UNDECIDED).astype(np.int8)
    out[(runs == NOT_CONVERGED).any(axis=0)] = NOT_CONVERGED
    return out


def run_grid(values, s_values, w_values, *, t_end, rtol=RTOL, atol=ATOL, tol=1e-3, directions=DIRECTIONS,
             max_steps=MAX_STEPS, system=closed_loop) -> GridRuns:
    """:func:`run_points` on the grid s_values × w_values.

    Examples
    --------
    >>> from lkverify.proofs.somov.equations import P
    >>> g = run_grid(P.resolve({}), [0.0, 0.9], [0.0, 0.4], t_end=300.0)
    >>> g.classes.tolist(), int(g.converged.sum()), bool(g.undecided.any())
    ([[1, 0], [1, 0]], 2, False)
    """
    S, Wg = np.meshgrid(np.asarray(s_values, float), np.asarray(w_values, float), indexing="ij")
    cls = run_points(values, S, Wg, t_end=t_end, rtol=rtol, atol=atol, tol=tol, directions=directions,
                     max_steps=max_steps, system=system).reshape(S.shape)
    return GridRuns(np.asarray(s_values, float), np.asarray(w_values, float), cls, float(t_end), float(rtol),
                    float(atol), len(directions))
