"""One certificate for a whole interval of delays: stability for every h in [h1, h2].

A certificate of :mod:`.hierarchy` proves stability at one delay.  Here one rational
(P, S, R) is sought for all h in [h1, h2] (the SDP imposes the LMI at several delays of the
interval at once) and verified for every h of the interval:

* P + (1/h) diag(0, S, 3S, …) ≻ 0 for all h ≤ h2 follows from h = h2 (S ≻ 0: the shift
  decreases in h), checked exactly there, with S ≻ 0 and R ≻ 0;
* −Φ_N(h) ≻ 0 on [h1, h2]: Φ_N(h) = Σ_k h^k C_k is a matrix polynomial (degree ≤ 4) whose
  rational coefficients C_k are obtained exactly (interpolation in fractions).  With a
  discrete delay only, C_3 = C_4 = 0 and C_2 = −FᵀRF ⪯ 0 (checked exactly): xᵀ(−Φ_N(h))x is
  concave in h, so −Φ_N ≻ 0 at h1 and at h2 (exact) gives it on the whole interval
  (``exact``).  Otherwise, on each piece of a subdivision of [h1, h2] the matrix is
  evaluated with h as an arb ball covering the piece and an LDLᵀ in balls must have
  positive pivots (pieces that fail are halved): ``certified`` when every piece passes
  (an LDLᵀ in balls amplifies radii: thin margins need many pieces, and the budget of
  halvings may end ``undecided``).

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> certify_interval(sys, ("1", "4"), order=1).status.value
'exact'
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from fractions import Fraction

import numpy as np
import sympy
from flint import arb, ctx

from ..certify.conditions import combine
from ..certify.lmi import solve_sdp
from ..certify.matrices import _arb_ldl_pd, matrix_positive_definite
from ..errors import InputError
from ..status import Status
from .hierarchy import PHI_DEGREE, LmiCertificate, _conditions, _phi_at, _round, method_name
from .model import FLOAT_NOTE, LinearDelaySystem, at_most_certified, has_float, parse_delay

__all__ = ["IntervalCertificate", "certify_cover", "certify_interval"]

#: delays of the interval at which the SDP imposes the LMI
SDP_POINTS = 7
#: subdivision of [h1, h2] for the ball check: initial pieces, and the deepest halving
PIECES, MAX_DEPTH = 64, 14
#: arb precision (bits)
PRECISION = 128


@dataclasses.dataclass(frozen=True)
class IntervalCertificate:
    """One certificate verified for every delay of [h1, h2].

    >>> IntervalCertificate(1, 0, 1, Status.UNDECIDED, None, 0, 0.0, "").holds
    False
    """

    order: int
    h1: sympy.Rational
    h2: sympy.Rational
    status: Status
    certificate: LmiCertificate | None
    pieces: int
    seconds: float
    detail: str

    @property
    def holds(self) -> bool:
        return self.status.is_proof


def _solve_on(system, order, hs):
    import cvxpy as cp
    n, q = system.n, (order + 1) * system.n
    P = cp.Variable((q, q), symmetric=True)
    S = cp.Variable((n, n), symmetric=True)
    R = cp.Variable((n, n), symmetric=True)
    t = cp.Variable()
    cons = [P << np.eye(q), P >> -np.eye(q), S << np.eye(n), R << np.eye(n), S >> t * np.eye(n),
            R >> t * np.eye(n)]
    for h in hs:
        Phi = _phi_at(system, order, h, P, S, R)
        cons.append(-(Phi + Phi.T) / 2 >> t * np.eye(Phi.shape[0]))
    h2 = max(hs)
    if order:
        shift = cp.bmat([[((2 * i - 1) / h2 * S if (i == j and i > 0) else np.zeros((n, n)))
                          for j in range(order + 1)] for i in range(order + 1)])
        cons.append(P + shift >> t * np.eye(q))
    else:
        cons.append(P >> t * np.eye(q))
    prob = cp.Problem(cp.Maximize(t), cons)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        status = solve_sdp(prob)
    if t.value is None or not t.value > 0 or P.value is None:
        return None, status
    return LmiCertificate(order, _round(P.value), _round(S.value), _round(R.value)), status


def _coefficients(system, cert):
    """The exact rational C_k of −Φ_N(h) = Σ_k h^k C_k (interpolation at h = 1, …, 5 in fractions)."""
    nodes = [sympy.Integer(k + 1) for k in range(PHI_DEGREE + 1)]
    samples = [dict(_conditions(system, x, cert))["−Φ_N(h)"] for x in nodes]
    V = sympy.Matrix(len(nodes), len(nodes), lambda i, j: nodes[i] ** j)
    Vinv = V.inv()
    return [sum((Vinv[k, j] * samples[j] for j in range(len(nodes))), sympy.zeros(*samples[0].shape))
            for k in range(len(nodes))]


def _ball(lo: Fraction, hi: Fraction) -> arb:
    mid, rad = (lo + hi) / 2, (hi - lo) / 2
    return arb(mid.numerator) / mid.denominator + arb(0, float(rad) * (1 + 1e-12) + 1e-300)


def _piece_ok(C, lo: Fraction, hi: Fraction) -> bool:
    h = _ball(lo, hi)
    powers = [arb(1)]
    for _ in range(len(C) - 1):
        powers.append(powers[-1] * h)
    m = C[0].shape[0]
    M = [[sum((powers[k] * (arb(int(C[k][i, j].p)) / int(C[k][i, j].q)) for k in range(len(C))
               if C[k][i, j] != 0), arb(0)) for j in range(m)] for i in range(m)]
    return _arb_ldl_pd(M)[0]


def _concave(C):
    """The exact proof that h ↦ xᵀ(−Φ_N(h))x is concave for every x (C_3 = C_4 = 0, C_2 ⪯ 0), or None."""
    if any(any(e != 0 for e in Ck) for Ck in C[3:]):
        return None
    res = matrix_positive_definite(-C[2], name="−C_2 (the h² coefficient of −Φ_N)", semidefinite=True)
    return res if res.holds else None


def _by_concavity(system, cert, C, concave, ends, name, h1, h2, t0):
    """−Φ_N(h) concave in h: ≻ 0 at h1 and h2 (exact) gives ≻ 0 on [h1, h2]."""
    at1 = matrix_positive_definite(dict(_conditions(system, h1, cert))["−Φ_N(h)"], name="−Φ_N(h1)")
    at2 = matrix_positive_definite(dict(_conditions(system, h2, cert))["−Φ_N(h)"], name="−Φ_N(h2)")
    res = combine(name, [*ends.parts, concave, at1, at2], certificate=cert)
    seconds = time.perf_counter() - t0
    if not res.holds:
        return IntervalCertificate(cert.order, h1, h2, Status.UNDECIDED, cert, 0, seconds,
                                   f"{name}: the rounded certificate fails: {res.detail}")
    detail = (f"{name}: one rational (P, S, R) (Clarabel at {SDP_POINTS} delays, rounded to 2^-40); −Φ_N(h) = "
              f"C_0 + hC_1 + h²C_2 with C_2 ⪯ 0 ({concave.status.value}), so xᵀ(−Φ_N(h))x is concave in h and "
              f"−Φ_N ≻ 0 at h1 and h2 ({at1.status.value}, {at2.status.value}) gives it on [h1, h2]; positivity "
              f"at h2 covers every h ≤ h2: stable for every h in the interval; {seconds:.2f} s")
    return IntervalCertificate(cert.order, h1, h2, res.status, cert, 2, seconds, detail)


def _capped(res: IntervalCertificate, inexact: bool) -> IntervalCertificate:
    """``res`` at most ``certified`` when an input went through floating point (:mod:`lkverify.status`)."""
    status = at_most_certified(res.status, inexact)
    if status is res.status:
        return res
    return dataclasses.replace(res, status=status, detail=f"{res.detail}; {FLOAT_NOTE}")


def certify_interval(system: LinearDelaySystem, interval, *, order: int = 2) -> IntervalCertificate:
    """One rational certificate, verified for every delay h in [h1, h2] (``certified``).

    Parameters
    ----------
    system : LinearDelaySystem
        Constant kernel.
    interval : (h1, h2)
        Delays read exactly (text such as "0.1002" is a decimal), 0 < h1 < h2.
    order : int

    Returns
    -------
    IntervalCertificate
        ``exact`` (concave case, rational data) or ``certified`` (pieces in arb, or a float input: the
        system's or an end given as a float, at its binary value); ``undecided`` otherwise (the detail
        says which step stopped: no common solution, a rounded condition, or a piece of the subdivision).

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> certify_interval(LinearDelaySystem([[-1]], Ad=[["0.5"]]), ("0.1", "10"), order=0).status.value
    'exact'
    >>> certify_interval(LinearDelaySystem([[-1]], Ad=[[0.5]]), ("0.1", "10"), order=0).status.value
    'certified'
    """
    return _capped(_certify_interval(system, interval, order), system.from_float or has_float(list(interval)))


def _certify_interval(system: LinearDelaySystem, interval, order: int) -> IntervalCertificate:
    h1, h2 = (parse_delay(v) for v in interval)
    if not 0 < h1 < h2:
        raise InputError(f"interval: expected 0 < h1 < h2, got {interval}")
    t0 = time.perf_counter()
    name = f"{method_name(order)} on [{h1}, {h2}]"
    hs = [float(h1 + (h2 - h1) * sympy.Rational(k, SDP_POINTS - 1)) for k in range(SDP_POINTS)]
    cert, status = _solve_on(system, order, hs)
    if cert is None:
        return IntervalCertificate(order, h1, h2, Status.UNDECIDED, None, 0, time.perf_counter() - t0,
                                   f"{name}: no common strictly feasible solution at {SDP_POINTS} delays "
                                   f"(solver status {status!r})")
    at_end = dict(_conditions(system, h2, cert))
    parts = [matrix_positive_definite(at_end[k], name=k) for k in ("P + (1/h)diag(0, S, 3S, …)", "S", "R")]
    ends = combine(f"{name}: positivity at h2 (implies every h ≤ h2)", parts)
    if not ends.holds:
        return IntervalCertificate(order, h1, h2, Status.UNDECIDED, cert, 0, time.perf_counter() - t0,
                                   f"{name}: the rounded certificate fails: {ends.detail}")
    C = _coefficients(system, cert)
    concave = _concave(C)
    if concave is not None:
        return _by_concavity(system, cert, C, concave, ends, name, h1, h2, t0)
    a, b = Fraction(int(h1.p), int(h1.q)), Fraction(int(h2.p), int(h2.q))
    stack = [(a + (b - a) * k / PIECES, a + (b - a) * (k + 1) / PIECES, 0) for k in range(PIECES)]
    done = 0
    with ctx.workprec(PRECISION):
        while stack:
            lo, hi, depth = stack.pop()
            if _piece_ok(C, lo, hi):
                done += 1
                continue
            if depth >= MAX_DEPTH:
                return IntervalCertificate(order, h1, h2, Status.UNDECIDED, cert, done, time.perf_counter() - t0,
                                           f"{name}: −Φ_N(h) ≻ 0 not certified on [{float(lo):.7g}, {float(hi):.7g}] "
                                           f"after {MAX_DEPTH} halvings")
            mid = (lo + hi) / 2
            stack += [(lo, mid, depth + 1), (mid, hi, depth + 1)]
    seconds = time.perf_counter() - t0
    detail = (f"{name}: one rational (P, S, R) (Clarabel at {SDP_POINTS} delays, rounded to 2^-40); positivity "
              f"exact at h2 ({ends.status.value}); −Φ_N(h) = Σ h^k C_k with exact C_k, LDLᵀ in arb balls positive "
              f"on {done} pieces covering [{h1}, {h2}]: stable for every h in the interval; {seconds:.2f} s")
    return IntervalCertificate(order, h1, h2, Status.CERTIFIED, cert, done, seconds, detail)


def certify_cover(system: LinearDelaySystem, interval, *, order: int = 2, depth: int = 4) -> list:
    """[h1, h2] covered by interval certificates, halving a sub-interval without one (at most ``depth`` times).

    Returns the list of :class:`IntervalCertificate` in order; they cover [h1, h2] when all hold.

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> gu = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
    >>> parts = certify_cover(gu, ("0.11", "1.7"), order=2)
    >>> all(p.holds for p in parts), parts[0].h1, parts[-1].h2
    (True, 11/100, 17/10)
    """
    h1, h2 = (parse_delay(v) for v in interval)
    inexact = system.from_float or has_float(list(interval))
    res = _capped(certify_interval(system, (h1, h2), order=order), inexact)
    if res.holds or depth == 0:
        return [res]
    mid = sympy.Rational(round(float(h1 + h2) / 2 * 10 ** 6), 10 ** 6)
    if not h1 < mid < h2:
        return [res]
    return [_capped(r, inexact) for r in certify_cover(system, (h1, mid), order=order, depth=depth - 1)
            + certify_cover(system, (mid, h2), order=order, depth=depth - 1)]
