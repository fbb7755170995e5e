"""The largest (and smallest) delay certified by an LMI of the hierarchy, by bisection.

The bisection is steered by the solver and the exact LDLᵀ of its rounded solution
(:func:`lkverify.linear.hierarchy.quick_check`: a delay counts as feasible only when the
rational certificate passes); the delay reported is then re-verified with the full check
(:func:`lkverify.linear.hierarchy.certify_delay`, λ_min enclosures included); if that fresh
certificate does not verify, the next feasible delay inward is tried.  The
reported end is thus always a delay at which a rational certificate was checked, never one
the solver merely accepted.  The search runs inside a stability interval of the spectral
route (no LMI can be feasible where the system is unstable).

Trial delays are decimals of :data:`DIGITS` significant digits (6.1725, not a binary float).

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> m = certified_interval(sys, (0, 6.17258), order=0)
>>> m.status.value, abs(m.upper - 4.4715) < 1e-3
('exact', True)
"""

from __future__ import annotations

import dataclasses
import math
import time

import sympy

from ..errors import InputError
from ..status import Status
from .hierarchy import LmiResult, certify_delay, method_name, quick_check, solve_certificate
from .model import LinearDelaySystem

__all__ = ["CertifiedInterval", "certified_interval"]

#: significant digits of the trial delays
DIGITS = 7
#: bisection stops when the bracket is below this fraction of the end searched
RELATIVE_TOL = 5e-6
#: delays tried (as fractions of the interval) to find a first feasible point
STARTS = (0.5, 0.25, 0.75, 0.1, 0.9, 0.05, 0.95)
#: feasible delays tried inward when the exact check at the reported end fails
FALLBACKS = 6


@dataclasses.dataclass(frozen=True)
class CertifiedInterval:
    """The delays certified by the order-N LMI inside one stability interval.

    Attributes
    ----------
    order : int
    method : str
    lower, upper : float or None
        The smallest / largest delay with an exactly verified certificate (``lower`` is None
        when the interval starts at 0: the search then stops at the first start point).
    lower_check, upper_check : LmiResult or None
    status : Status
        ``exact``/``certified`` when the reported ends were verified (``certified``, never
        ``exact``, for a system with float inputs: :mod:`lkverify.status`); ``undecided`` when no
        delay of the interval gave a verified certificate.  The ends of ``interval`` are only
        search bounds: the delays reported are lkverify's own decimals, whatever their type.
    solves : int
    seconds : float
    detail : str

    >>> CertifiedInterval(0, "jensen", None, None, None, None, Status.UNDECIDED, 0, 0.0, "").holds
    False
    """

    order: int
    method: str
    lower: float | None
    upper: float | None
    lower_check: LmiResult | None
    upper_check: LmiResult | None
    status: Status
    solves: int
    seconds: float
    detail: str

    @property
    def holds(self) -> bool:
        return self.status.is_proof


def _decimal(x: float) -> sympy.Rational:
    digits = DIGITS - 1 - int(math.floor(math.log10(abs(x)))) if x else DIGITS
    return sympy.Rational(round(x * 10 ** digits), 10 ** digits) if digits >= 0 else sympy.Rational(round(x))


def _feasible(system, order, h, counter) -> bool:
    """The solver finds a strictly feasible point at h AND its rounding passes the exact LDLᵀ."""
    counter[0] += 1
    cert = solve_certificate(system, h, order)
    return cert is not None and quick_check(system, h, cert)


def _bisect(system, order, good, bad, counter, tol):
    """Move ``good`` (feasible) toward ``bad``; the feasible delays met, innermost last."""
    met = [good]
    while abs(bad - good) > tol:
        mid = _decimal((good + bad) / 2)
        if mid in (good, bad):
            break
        if _feasible(system, order, mid, counter):
            good = mid
            met.append(mid)
        else:
            bad = mid
    return met


def _verify_end(system, order, met) -> LmiResult | None:
    """The first delay of ``met`` (outermost first) whose rounded certificate verifies."""
    last = None
    for h in list(reversed(met))[:FALLBACKS]:
        res = certify_delay(system, h, order=order)
        if res.holds:
            return res
        last = res
    return last


def certified_interval(system: LinearDelaySystem, interval, *, order: int = 2) -> CertifiedInterval:
    """Bisect the order-N LMI inside a stability interval (lo, hi); verify the ends exactly.

    Parameters
    ----------
    system : LinearDelaySystem
    interval : (float, float)
        A stability interval of the spectral route (lo = 0: only the upper end is searched).
    order : int

    Returns
    -------
    CertifiedInterval

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> gu = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
    >>> m = certified_interval(gu, (0.1001683, 1.7178582), order=3)
    >>> m.status.value, 0.1001683 <= m.lower < 0.1002 and 1.717 < m.upper <= 1.7178582
    ('exact', True)
    """
    lo, hi = (float(v) for v in interval)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi):
        raise InputError(f"interval: expected 0 ≤ lo < hi (finite delays), got {interval}")
    t0 = time.perf_counter()
    counter = [0]
    name = method_name(order)
    start = next((x for f in STARTS if _feasible(system, order, x := _decimal(lo + f * (hi - lo)), counter)), None)
    if start is None:
        return CertifiedInterval(order, name, None, None, None, None, Status.UNDECIDED, counter[0],
                                 time.perf_counter() - t0,
                                 f"{name}: no strictly feasible delay among {len(STARTS)} points of ({lo:g}, {hi:g})")
    up = _verify_end(system, order, _bisect(system, order, start, sympy.Rational(hi), counter, RELATIVE_TOL * hi))
    down = None
    if lo > 0:  # the tolerance relative to this end: a lower end near 0 is resolved as finely as the upper one
        down = _verify_end(system, order, _bisect(system, order, start, _decimal(lo), counter, RELATIVE_TOL * lo))
    ends = [r for r in (down, up) if r is not None]
    ok = all(r.holds for r in ends) and (lo == 0 or down is not None)
    status = (Status.EXACT if all(r.status is Status.EXACT for r in ends) else Status.CERTIFIED) if ok \
        else Status.UNDECIDED
    seconds = time.perf_counter() - t0
    where = (f"the delays h = {float(down.h):.7g} and h = {float(up.h):.7g}" if down is not None
             else f"the delay h = {float(up.h):.7g}")
    detail = (f"{name}: stability certified at {where} (each re-verified: "
              f"{'; '.join(r.detail for r in ends)}); {counter[0]} SDP solves, {seconds:.2f} s. "
              "Each reported delay has its own rational certificate; the delays between are not covered by "
              "them (lkverify.linear.certify_interval covers a whole interval).") if ok else (
        f"{name}: the ends did not verify: {'; '.join(r.detail for r in ends)}")
    return CertifiedInterval(order, name, float(down.h) if ok and down is not None else None,
                             float(up.h) if ok else None, down, up, status, counter[0], seconds, detail)
