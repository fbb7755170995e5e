"""The one estimator: Sobol sampling of a box, then local maximisation (SciPy SLSQP).

An estimate is a float value, status ``estimated`` -- never a proof.  It finds
good lower bounds of a supremum (and counterexamples) fast; the branch and
bound (:mod:`lkverify.certify.engine`) proves the upper bound.

Examples
--------
>>> import numpy as np
>>> best = maximise(lambda x: x * (1 - x), [0.0], [1.0], starts=2, seed=0)[0]
>>> round(best.value, 6), round(float(best.point[0]), 4)
(0.25, 0.5)
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from collections.abc import Callable, Sequence

import numpy as np

__all__ = ["Candidate", "MAX_CORNER_DIMENSION", "SAMPLES_PER_DIMENSION", "SLSQP_MAXITER", "maximise"]

#: Sobol points per dimension (rounded up to a power of two, at least 128)
SAMPLES_PER_DIMENSION = 128
#: the box's corners are sampled too up to this dimension (2ⁿ points)
MAX_CORNER_DIMENSION = 8
#: iterations of one local maximisation
SLSQP_MAXITER = 200
#: relative step of the central differences of the local maximisation
DIFF_STEP = 1e-6
#: a local maximiser this close (relative to the width) to a face of the box is also tried on the face
SNAP_TOLERANCE = 1e-7


@dataclasses.dataclass(frozen=True)
class Candidate:
    """A point of the box and the float value there (an estimate, not a proof)."""

    value: float
    point: tuple


def _quiet_float(f: Callable, x) -> float:
    v = float(f(*x))
    return v if math.isfinite(v) else -math.inf


def _samples(f: Callable, lo: np.ndarray, hi: np.ndarray, *, starts: int, seed: int) -> list:
    """The best ``starts`` Sobol samples (with the centre and, in low dimension, the corners)."""
    from scipy.stats import qmc

    n = len(lo)
    m = 1 << max(7, int(math.ceil(math.log2(SAMPLES_PER_DIMENSION * n))))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        u = qmc.Sobol(d=n, scramble=True, seed=seed).random(m)
    pts = [lo + u * (hi - lo), ((lo + hi) / 2)[None, :]]
    if n <= MAX_CORNER_DIMENSION:
        pts.append(np.array(np.meshgrid(*[[a, b] for a, b in zip(lo, hi)], indexing="ij")).reshape(n, -1).T)
    pts = np.vstack(pts)
    vals = np.asarray(f(*pts.T), dtype=float)
    vals = np.where(np.isfinite(vals), vals, -np.inf)
    order = np.argsort(-vals, kind="stable")
    return [Candidate(float(vals[i]), tuple(pts[i])) for i in order[: max(1, starts)] if np.isfinite(vals[i])]


def _negated_with_gradient(f: Callable, lo: np.ndarray, hi: np.ndarray):
    """−f and its central-difference gradient (one-sided at the box's faces), for SLSQP."""
    n = len(lo)

    def negf_grad(x):
        v = _quiet_float(f, x)
        if not math.isfinite(v):
            return 1e300, np.zeros(n)
        g = np.zeros(n)
        for i in range(n):
            h = DIFF_STEP * max(1.0, abs(x[i]))
            a, b = max(x[i] - h, lo[i]), min(x[i] + h, hi[i])
            if b <= a:
                continue
            xa, xb = x.copy(), x.copy()
            xa[i], xb[i] = a, b
            va, vb = _quiet_float(f, xa), _quiet_float(f, xb)
            if math.isfinite(va) and math.isfinite(vb):
                g[i] = (vb - va) / (b - a)
        return -v, -g

    return negf_grad


def maximise(f: Callable, lo: Sequence[float], hi: Sequence[float], *, starts: int, seed: int,
             deadline: float = math.inf) -> list:
    """Candidate maximisers of a float function on a box, best first.

    Parameters
    ----------
    f : callable
        ``f(x1, …, xn)``, vectorised over NumPy arrays (as :func:`~lkverify.certify.functions.lambdify_real`).
    lo, hi : sequence of float
        The box (points stay inside it).
    starts : int
        Local maximisations (SLSQP with bounds), from the best Sobol samples.
    seed : int
    deadline : float
        A :func:`time.monotonic` time after which no new local maximisation starts.

    Returns
    -------
    list of Candidate
        Finite values only, sorted by decreasing value.
    """
    from scipy.optimize import minimize

    n = len(lo)
    if n == 0:
        v = _quiet_float(f, ())
        return [Candidate(v, ())] if math.isfinite(v) else []
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    cands = _samples(f, lo, hi, starts=starts, seed=seed)
    negf_grad = _negated_with_gradient(f, lo, hi)
    bounds = list(zip(lo, hi))
    found = list(cands)
    for cand in cands:
        if time.monotonic() > deadline:
            break
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            # SLSQP, not L-BFGS-B: the latter spends milliseconds per iteration in threaded
            # OpenBLAS calls on tiny problems
            res = minimize(negf_grad, np.array(cand.point), jac=True, method="SLSQP", bounds=bounds,
                           options={"maxiter": SLSQP_MAXITER})
        x = np.clip(res.x, lo, hi)
        v = _quiet_float(f, x)
        if not math.isfinite(v):
            continue
        found.append(Candidate(v, tuple(float(t) for t in x)))
        # snap coordinates that sit on the box's edge exactly onto it
        tol = SNAP_TOLERANCE
        snapped = tuple(float(a if abs(t - a) <= tol * (b - a) else b if abs(t - b) <= tol * (b - a) else t)
                        for t, a, b in zip(x, lo, hi))
        if snapped != tuple(x):
            vs = _quiet_float(f, np.array(snapped))
            if math.isfinite(vs):
                found.append(Candidate(vs, snapped))
    found.sort(key=lambda c: -c.value)
    return found
