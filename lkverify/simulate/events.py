"""Events of a DDE run: derivative breakpoints, the divergence bound, the step floor.

* :func:`breakpoints` — the times ``t0 + Σ kᵢ lagᵢ`` where a general initial history
  makes derivatives of the solution jump; the integrator lands steps on them.
* :func:`crossing` — the time the norm of the solution reaches the divergence bound.
* :class:`StepFloor` — the mean of the last :data:`FLOOR_WINDOW` accepted steps
  against a floor: a blow-up (``‖y‖`` grew :data:`BLOWUP_GROWTH`-fold) or a step
  collapse (stiff).

>>> import numpy as np
>>> breakpoints(0.0, 3.5, np.array([1.0, 1.5]), 2).tolist()
[1.0, 1.5, 2.0, 2.5, 3.0]
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["BLOWUP_GROWTH", "DISCONTINUITY_ORDER", "FLOOR_WINDOW", "MAX_STEPS", "FloorHit", "StepFloor", "breakpoints", "crossing"]

_EPS = np.finfo(float).eps
#: The step floor.  Steps are at most ``min(delays)`` long (the method of steps), so a run
#: needs at least ``(t_end − t0) / min(delays)`` steps: a run needing more than MAX_STEPS is
#: refused up front (a tiny delay, a huge t_end).  During a run, when the mean of the last
#: :data:`FLOOR_WINDOW` steps falls below ``(t_end − t0) / MAX_STEPS`` the run
#: stops: a blow-up (``diverged``) if ‖y‖ has grown, else a step collapse (a stiff system).
MAX_STEPS = 10**7
#: breakpoints t0 + Σ kᵢ lagᵢ with Σ kᵢ up to this order are landed on (solve_dde's default)
DISCONTINUITY_ORDER = 4
#: number of accepted steps whose mean is compared with ``min_mean_step``
FLOOR_WINDOW = 200
#: a step collapse with ‖y‖ grown by this factor over its initial size (at least 1) is reported as a blow-up
BLOWUP_GROWTH = 1e3


def breakpoints(t0: float, t_end: float, lags: np.ndarray, order: int) -> np.ndarray:
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



def crossing(past, ta: float, tb: float, bound: float) -> float:
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


@dataclasses.dataclass(frozen=True)
class FloorHit:
    """The step floor was hit: a blow-up (``blow_up``) or a step collapse, with the numbers that show it."""

    t: float
    mean_step: float
    norm: float
    blow_up: bool


class StepFloor:
    """The mean length of the last :data:`FLOOR_WINDOW` accepted steps against ``floor``.

    Parameters
    ----------
    floor : float or None
        ``None`` disables the check.
    y0_norm : float
        ``‖y(t0)‖``; a blow-up is ``‖y‖ > BLOWUP_GROWTH · max(1, ‖y(t0)‖)``.

    Examples
    --------
    >>> f = StepFloor(0.5, 1.0)
    >>> [f.record(k, 1.0 + k, 0.1, 2.0) for k in range(1, FLOOR_WINDOW + 1)][-1]
    FloorHit(t=201.0, mean_step=0.1, norm=2.0, blow_up=False)
    """

    def __init__(self, floor: float | None, y0_norm: float):
        self.floor = None if floor is None else float(floor)
        self.scale = max(1.0, float(y0_norm))
        self.recent = np.zeros(FLOOR_WINDOW)        # lengths of the last accepted steps (ring buffer)

    def record(self, n_steps: int, t: float, h: float, norm: float) -> FloorHit | None:
        """Record the ``n_steps``-th accepted step (length ``h``, ending at ``t``); a :class:`FloorHit` or None."""
        if self.floor is None:
            return None
        self.recent[n_steps % FLOOR_WINDOW] = h
        if n_steps >= FLOOR_WINDOW and self.recent.mean() < self.floor:
            mean = float(self.recent.mean())
            return FloorHit(t, mean, norm, norm > BLOWUP_GROWTH * self.scale)
        return None
