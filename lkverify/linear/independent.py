"""Stability for every delay: decided exactly, certified by a delay-independent LK functional.

For ẋ = A x + A_d x(t−h) (rational matrices, no distributed term) the roots of
det(λI − A − A_d e^{−λh}) depend continuously on h ≥ 0 and, the equation being of retarded
type, reach the closed right half-plane only across the imaginary axis (at h = 0⁺ the new
roots come from Re λ = −∞).  A root λ = iω, ω > 0, at some delay makes ω a real root of the
crossing-frequency polynomial P ∈ ℚ[ω] (:mod:`.frequency`; z = e^{−iωh} = 1 covers h = 0), and
λ = 0 is a root for some h exactly when det(A + A_d) = 0 — then for every h.  So when P has
no root in (0, ∞) (counted exactly: a Sturm count of P/ω^m on rational coefficients, SymPy),

* A + A_d Hurwitz (exact Hurwitz minors of its characteristic polynomial,
  :func:`lkverify.certify.lmi._routh_hurwitz`) ⇒ exponentially stable for every delay
  h ≥ 0: the delay margin is infinite;
* det(A + A_d) = 0 ⇒ λ = 0 is a characteristic root for every h: asymptotically stable for no h;
* otherwise A + A_d has a root with Re λ > 0, and the system keeps one for every h: unstable
  for every delay.

Stability for every delay is then also certified by the Lyapunov–Krasovskii functional
V = xᵀPx + ∫_{t−h}^t x(s)ᵀQx(s) ds, whose derivative is V̇ = ζᵀMζ, ζ = (x, x(t−h)),

    M = [[AᵀP + PA + Q, PA_d], [A_dᵀP, −Q]],

with no h anywhere: P ≻ 0, Q ≻ 0 and M ≺ 0 prove exponential stability for every h ≥ 0.  P, Q
come from an SDP (cvxpy + Clarabel), are rounded to dyadic rationals and verified by an exact
LDLᵀ in fractions (:func:`lkverify.certify.matrices.matrix_positive_definite`).  The LMI is only
sufficient (it is a scaled small-gain condition, det(sI − A − A_d z) ≠ 0 for Re s ≥ 0 and
|z| ≤ 1): ẋ = −x − x(t−h) is stable for every delay (its only "crossing" is at ω = 0, z = −1,
never reached) but has no such certificate.  The exact frequency-domain decision then stands
alone and the certificate is reported as not found.

A positive root of P, an irrational entry or a distributed term: this route does not decide
(``applies`` False) and the delay-dependent analysis (:mod:`.crossing`, :mod:`.stretches`,
:mod:`.margin`) answers instead.

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> di = delay_independence(LinearDelaySystem([[-2]], Ad=[[1]]))      # ẋ = −2x + x(t−h)
>>> di.stable, di.status.value, di.margin, di.check.status.value
(True, 'exact', inf, 'exact')
>>> delay_independence(LinearDelaySystem([[-2]], Ad=[[3]])).applies  # ω = √5 crosses
False
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
import sympy

from ..certify.conditions import ConditionResult, combine
from ..certify.lmi import _routh_hurwitz, solve_sdp
from ..certify.matrices import _as_matrix, matrix_positive_definite
from ..errors import InputError
from ..status import Status
from .frequency import frequency_polynomial
from .hierarchy import ROUNDING_BITS, _round
from .model import FLOAT_NOTE, LinearDelaySystem, at_most_certified, has_float

__all__ = ["DelayIndependence", "IndependentCertificate", "certificate_detail", "check_independent_certificate",
           "count_positive_roots", "delay_independence", "solve_independent_certificate"]

#: the functional the certificate belongs to
FUNCTIONAL = "V = xᵀPx + ∫_{t−h}^t x(s)ᵀQx(s) ds"
#: the name of the LMI matrix in messages
LMI_NAME = "−[[AᵀP + PA + Q, PA_d], [A_dᵀP, −Q]]"


@dataclasses.dataclass(frozen=True)
class IndependentCertificate:
    """Rational P, Q (n × n) of the delay-independent functional V = xᵀPx + ∫_{t−h}^t xᵀQx.

    >>> IndependentCertificate(sympy.eye(1), sympy.eye(1) / 3).to_json()
    {'P': [['1']], 'Q': [['1/3']]}
    """

    P: sympy.Matrix
    Q: sympy.Matrix

    def to_json(self) -> dict:
        """P and Q as exact rational strings (``"p/q"``)."""
        return {name: [[str(e) for e in row] for row in M.tolist()] for name, M in (("P", self.P), ("Q", self.Q))}


@dataclasses.dataclass(frozen=True)
class DelayIndependence:
    """Whether ẋ = A x + A_d x(t−h) is stable for every delay h ≥ 0, decided exactly, and its LK certificate.

    Attributes
    ----------
    applies : bool
        The route decided: no crossing frequency ω > 0 exists, so stability is the same for
        every delay.  False when a positive root of P exists (stability may depend on h), or
        for unsupported data (irrational entries, a distributed term); ``stable`` is then None.
    stable : bool or None
        True: exponentially stable for every h ≥ 0 (the delay margin is infinite).  False:
        asymptotically stable for no h ≥ 0 (unstable for every delay, or λ = 0 a root for every
        delay).  None: not decided here.
    status : Status
        Of that decision: ``exact`` (``certified`` for float inputs) when stability for every
        delay is proved; ``failed`` when it is refuted for every delay; ``undecided`` when the
        route does not apply.
    polynomial : sympy.Poly or None
        The crossing-frequency polynomial P(ω) (None without a delayed term or when unsupported).
    positive_roots : int or None
        The number of distinct roots of P in (0, ∞) (exact Sturm count).
    hurwitz : bool or None
        A + A_d Hurwitz (exact), the system at h = 0.
    certificate : IndependentCertificate or None
        The rounded solution of the SDP (None: the solver found no strictly feasible point).
    check : ConditionResult or None
        Its exact verification: P ≻ 0, Q ≻ 0, M ≺ 0.
    solver_status : str
    seconds : float
    detail : str

    >>> DelayIndependence(False, None, Status.UNDECIDED, None, 2, None, None, None, "", 0.0, "").margin is None
    True
    """

    applies: bool
    stable: bool | None
    status: Status
    polynomial: sympy.Poly | None
    positive_roots: int | None
    hurwitz: bool | None
    certificate: IndependentCertificate | None
    check: ConditionResult | None
    solver_status: str
    seconds: float
    detail: str

    @property
    def margin(self) -> float | None:
        """``math.inf`` when stable for every delay; 0.0 when stable for none; None when not decided here."""
        return None if self.stable is None else (math.inf if self.stable else 0.0)

    @property
    def margin_infinite(self) -> bool:
        """True when the delay margin is infinite (stable for every delay h ≥ 0, proved)."""
        return self.stable is True and self.status.is_proof

    @property
    def certified(self) -> bool:
        """True when the delay-independent LK certificate verified."""
        return self.check is not None and self.check.holds


def count_positive_roots(P: sympy.Poly) -> int:
    """The number of distinct real roots of P in the open interval (0, ∞), exactly (Sturm count on ℚ).

    The factor ω^m (roots at ω = 0) is removed first, so 0 is never counted.

    >>> w = sympy.Symbol("omega")
    >>> count_positive_roots(sympy.Poly(-w**2 * (w**2 + 3), w)), count_positive_roots(sympy.Poly(w**2 * (w**2 - 5), w))
    (0, 1)
    """
    coeffs = list(P.all_coeffs())
    while coeffs and coeffs[-1] == 0:
        coeffs.pop()
    Q = sympy.Poly(coeffs, *P.gens, domain=P.domain)
    if Q.degree() <= 0:
        return 0
    return int(Q.sqf_part().count_roots(0, None))


def _lmi_matrix(A, Ad, P, Q):
    """M = [[AᵀP + PA + Q, PA_d], [A_dᵀP, −Q]] (exact SymPy)."""
    return sympy.Matrix(sympy.BlockMatrix([[A.T * P + P * A + Q, P * Ad], [Ad.T * P, -Q]]))


def check_independent_certificate(system: LinearDelaySystem, certificate: IndependentCertificate) -> ConditionResult:
    """Verify P ≻ 0, Q ≻ 0 and [[AᵀP + PA + Q, PA_d], [A_dᵀP, −Q]] ≺ 0 exactly (LDLᵀ in fractions).

    Parameters
    ----------
    system : LinearDelaySystem
        ẋ = A x + A_d x(t−h) (a distributed term is refused: the functional does not cover it).
    certificate : IndependentCertificate

    Returns
    -------
    ConditionResult
        ``exact`` when all three hold for rational data (``certified`` for irrational data, in
        arb, or for a float input); ``failed`` with the exact witness of the first that does not.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys = LinearDelaySystem([[-2]], Ad=[[1]])
    >>> check_independent_certificate(sys, IndependentCertificate(sympy.eye(1), sympy.eye(1) * 2)).status.value
    'exact'
    >>> bad = check_independent_certificate(sys, IndependentCertificate(sympy.eye(1), sympy.eye(1) * 5))
    >>> bad.status.value, bad.detail.startswith(LMI_NAME), bad.witness     # xᵀ(−M)x < 0 at the witness
    ('failed', True, (Fraction(1, 1), Fraction(0, 1)))
    """
    if system.has_distributed:
        raise InputError("delay-independent certificate: expected ẋ = A x + A_d x(t−h) without a distributed term "
                         "(V = xᵀPx + ∫xᵀQx does not cover ∫D x); use lkverify.linear.certify_delay")
    n = system.n
    P, Q = _as_matrix(certificate.P, "P"), _as_matrix(certificate.Q, "Q")
    if P.shape != (n, n) or Q.shape != (n, n):
        raise InputError(f"delay-independent certificate: expected P and Q of size {n}×{n}, got {P.shape} and "
                         f"{Q.shape}")
    M = _lmi_matrix(sympy.Matrix(system.A), sympy.Matrix(system.Ad), P, Q)
    parts = [matrix_positive_definite(P, name="P"), matrix_positive_definite(Q, name="Q"),
             matrix_positive_definite(-M, name=LMI_NAME)]
    res = combine(f"delay-independent LK certificate ({FUNCTIONAL})", parts, certificate=certificate)
    inexact = system.from_float or has_float([certificate.P, certificate.Q])
    status = at_most_certified(res.status, inexact)
    if status is not res.status:
        res = dataclasses.replace(res, status=status, detail=f"{res.detail}; {FLOAT_NOTE}")
    return res


def solve_independent_certificate(system: LinearDelaySystem):
    """``(certificate or None, solver status, margin)``: the SDP for P, Q, rounded to rationals (not verified here).

    maximise t subject to P ⪰ tI, Q ⪰ tI, −M ⪰ tI, P ⪯ I, Q ⪯ I (the conditions are homogeneous);
    None when the solver finds no t > 0.

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> cert, status, t = solve_independent_certificate(LinearDelaySystem([[-2]], Ad=[[1]]))
    >>> status, cert.P.shape, t > 0
    ('optimal', (1, 1), True)
    """
    import cvxpy as cp

    n = system.n
    A, Ad, _ = system.floats_cached()
    P = cp.Variable((n, n), symmetric=True)
    Q = cp.Variable((n, n), symmetric=True)
    t = cp.Variable()
    M = cp.bmat([[A.T @ P + P @ A + Q, P @ Ad], [Ad.T @ P, -Q]])
    M = (M + M.T) / 2
    I, I2 = np.eye(n), np.eye(2 * n)
    problem = cp.Problem(cp.Maximize(t), [P >> t * I, Q >> t * I, -M >> t * I2, P << I, Q << I])
    with warnings.catch_warnings():  # "may be inaccurate": the status is reported, never trusted
        warnings.simplefilter("ignore", UserWarning)
        status = solve_sdp(problem)
    tv = t.value
    if status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or tv is None or not tv > 0:
        return None, status, None if tv is None else float(tv)
    return IndependentCertificate(_round(np.asarray(P.value)), _round(np.asarray(Q.value))), status, float(tv)


def _undecided(reason: str, t0: float, polynomial=None, positive=None) -> DelayIndependence:
    return DelayIndependence(False, None, Status.UNDECIDED, polynomial, positive, None, None, None, "",
                             time.perf_counter() - t0, reason)


def _crossings(system, t0):
    """``(P, number of positive roots, how)``, or a DelayIndependence that says why the route does not apply."""
    if not system.has_discrete:
        return None, 0, "no delayed term: the characteristic equation det(λI − A) = 0 does not depend on h"
    found = frequency_polynomial(system)
    if found is None:
        return _undecided("the crossing-frequency resultant vanishes identically: no exact decision for every "
                          "delay", t0)
    P = found[0]
    k = count_positive_roots(P)
    how = (f"the crossing-frequency polynomial P(ω) = {sympy.factor(P.as_expr())} has no root in (0, ∞) (exact "
           "Sturm count): no characteristic root reaches the imaginary axis at λ = iω, ω > 0, for any h")
    if k:
        return _undecided(f"the crossing-frequency polynomial has {k} root(s) in (0, ∞) (exact Sturm count): a "
                          "root may cross the imaginary axis, stability may depend on h", t0, P, k)
    return P, 0, how


def delay_independence(system: LinearDelaySystem, *, certify: bool = True) -> DelayIndependence:
    """Decide exactly whether ẋ = A x + A_d x(t−h) is stable for every delay h ≥ 0; certify it by an LK functional.

    Parameters
    ----------
    system : LinearDelaySystem
        Rational matrices, no distributed term (otherwise the route does not apply).
    certify : bool
        When stable for every delay, also solve the SDP for V = xᵀPx + ∫_{t−h}^t xᵀQx and verify
        the rounded P, Q exactly.

    Returns
    -------
    DelayIndependence
        ``stable`` True (``exact``; margin ``inf``), False (``failed``: asymptotically stable for
        no delay), or None (``undecided``: a crossing frequency exists or unsupported data;
        ``detail`` says which).  The certificate's own verdict is ``check``: an LMI that is
        infeasible (it is only sufficient) leaves ``check`` None and ``stable`` True.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> di = delay_independence(LinearDelaySystem([[-1]], Ad=[[-1]]))     # stable for every h, no LMI certificate
    >>> di.stable, di.status.value, di.certified
    (True, 'exact', False)
    >>> di = delay_independence(LinearDelaySystem([[-2]], Ad=[[2]]))      # λ = 0 is a root for every h
    >>> di.stable, di.status.value, di.margin
    (False, 'failed', 0.0)
    >>> delay_independence(LinearDelaySystem([[1]], Ad=[["-1/2"]])).detail[:33]
    'unstable for every delay h ≥ 0: A'
    """
    t0 = time.perf_counter()
    if system.has_distributed or not system.constant_kernel:
        return _undecided("the delay-independent route covers ẋ = A x + A_d x(t−h) without a distributed term", t0)
    if not system.is_rational:
        return _undecided("the delay-independent route needs rational matrices (exact algebra)", t0)
    got = _crossings(system, t0)
    if isinstance(got, DelayIndependence):
        return got
    P, _, how = got
    M0 = sympy.Matrix(system.A + system.Ad)
    ok, k, delta, charpoly = _routh_hurwitz(M0)
    floated = system.from_float
    note = f"; {FLOAT_NOTE}" if floated else ""
    if not ok:
        det = M0.det(method="bareiss")
        if det == 0:
            detail = (f"asymptotically stable for no delay h ≥ 0: det(A + A_d) = 0 (exact), so λ = 0 is a "
                      f"characteristic root for every h; {how}{note}")
        else:
            detail = (f"unstable for every delay h ≥ 0: A + A_d is not Hurwitz (exact: the Hurwitz minor Δ_{k} = "
                      f"{delta} ≤ 0 of det(sI − A − A_d) = {charpoly.as_expr()}) and det(A + A_d) = {det} ≠ 0, so a "
                      f"root with Re λ > 0 at h = 0 stays in the right half-plane for every h: {how}{note}")
        return DelayIndependence(True, False, Status.FAILED, P, 0, False, None, None, "",
                                 time.perf_counter() - t0, detail)
    status = at_most_certified(Status.EXACT, floated)
    detail = (f"stable for every delay h ≥ 0 (delay margin infinite): A + A_d is Hurwitz (exact Hurwitz minors of "
              f"{charpoly.as_expr()}, all > 0) and {how}{note}")
    cert, check, solver = None, None, ""
    if certify:
        cert, solver, _ = solve_independent_certificate(system)
        if cert is not None:
            check = check_independent_certificate(system, cert)
    return DelayIndependence(True, True, status, P, 0, True, cert, check, solver, time.perf_counter() - t0, detail)


def certificate_detail(di: DelayIndependence) -> str:
    """One sentence on the LK certificate of ``di`` (verified, rejected, or not found).

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> certificate_detail(delay_independence(LinearDelaySystem([[-1]], Ad=[[-1]])))[:40]
    'no delay-independent LK certificate foun'
    """
    if di.certificate is None:
        return (f"no delay-independent LK certificate found: Clarabel found no strictly feasible P, Q for "
                f"{FUNCTIONAL} (status {di.solver_status!r}); the LMI is only sufficient (a scaled small-gain "
                "condition), the exact frequency-domain decision stands alone")
    if di.check is not None and di.check.holds:
        return (f"{FUNCTIONAL} with P, Q rounded to multiples of 2^-{ROUNDING_BITS} (Clarabel status "
                f"{di.solver_status!r}); P ≻ 0, Q ≻ 0 and [[AᵀP + PA + Q, PA_d], [A_dᵀP, −Q]] ≺ 0 re-verified "
                f"(LDLᵀ in fractions): V̇ ≤ −ε(‖x(t)‖² + ‖x(t−h)‖²) with no h in the conditions, so stable for "
                f"every delay h ≥ 0 ({di.check.status.value})")
    return (f"no delay-independent LK certificate found: the rounded P, Q of {FUNCTIONAL} (Clarabel status "
            f"{di.solver_status!r}) did not verify ({di.check.detail if di.check is not None else 'not checked'}); "
            "the LMI is only sufficient, nothing is refuted: the exact frequency-domain decision stands alone")
