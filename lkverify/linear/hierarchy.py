"""The Lyapunov–Krasovskii LMI hierarchy: Jensen, Wirtinger, Bessel–Legendre of order N.

Formulation (Seuret & Gouaisbaut, "Hierarchy of LMI conditions for the stability analysis of
time-delay systems", Systems & Control Letters 81 (2015) 1–7, Theorem 1; the distributed
term enters through ∫_{t−h}^t x = hΩ_0 as in their section on distributed delays).  With the
Legendre polynomials ℓ_k of [t−h, t] (ℓ_k(t) = 1, ℓ_k(t−h) = (−1)^k) and
Ω_k = (1/h)∫_{t−h}^t ℓ_k(s)x(s) ds, the functional of order N is

    V_N = ξ_Nᵀ P ξ_N + ∫_{t−h}^t xᵀ S x ds + h ∫_{t−h}^t (s − t + h) ẋᵀ R ẋ ds,
    ξ_N = (x, hΩ_0, …, hΩ_{N−1}).

Along ẋ = A x + A_d x(t−h) + D hΩ_0 (constant kernel D), d(hΩ_k)/dt = Γ_k with
Γ_k = x − (−1)^k x(t−h) − Σ_{j<k} (2j+1)(1 − (−1)^{k+j}) Ω_j, and the Bessel–Legendre
inequality h∫ẋᵀRẋ ≥ Σ_{k=0}^{N} (2k+1) Γ_kᵀ R Γ_k gives V̇ ≤ ζᵀ Φ_N(h) ζ with
ζ = (x, x(t−h), Ω_0, …):

    Φ_N(h) = He(G_Nᵀ P H_N) + diag(S, −S, 0) + h² Fᵀ R F − Σ_{k=0}^{N} (2k+1) E_kᵀ R E_k,

(F: ẋ as a row of ζ, E_k: Γ_k, G_N: ξ_N, H_N: ξ̇_N), and Bessel's inequality on the S term
gives V_N ≥ ξ_Nᵀ (P + (1/h) diag(0, S, 3S, …, (2N−1)S)) ξ_N.  The conditions

    P + (1/h) diag(0, S, 3S, …) ≻ 0,   S ≻ 0,   R ≻ 0,   −Φ_N(h) ≻ 0

imply exponential stability at the delay h.  N = 0 is the Jensen-based condition,
N = 1 the Wirtinger-based one.

The SDP is solved with cvxpy + Clarabel; P, S, R are rounded to dyadic rationals and
the four conditions re-verified by :func:`lkverify.certify.matrices.matrix_positive_definite`
(an LDLᵀ in fractions for rational data: ``exact``; in arb balls otherwise: ``certified``).
The solver's status is never a certificate.

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> certify_delay(sys, 4, order=0).status.value
'exact'
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from fractions import Fraction

import numpy as np
import sympy
from flint import fmpq, fmpq_mat

from ..certify.conditions import ConditionResult, combine
from ..certify.lmi import solve_sdp
from ..certify.matrices import _exact_ldl, _fractions, matrix_positive_definite
from ..errors import InputError, UnsupportedInput
from ..status import Status
from .model import FLOAT_NOTE, LinearDelaySystem, at_most_certified, has_float, parse_delay

__all__ = ["LmiCertificate", "LmiResult", "METHODS", "build_lmi", "certify_delay", "check_certificate", "method_name",
           "quick_check", "solve_certificate"]

#: the orders named after their inequality
METHODS = {"jensen": 0, "wirtinger": 1}
#: rounding of the solver's P, S, R: multiples of 2^−ROUNDING_BITS (relative to the largest entry)
ROUNDING_BITS = 40


def method_name(order: int) -> str:
    """``jensen`` (N = 0), ``wirtinger`` (N = 1), ``bessel-legendre N=…`` otherwise.

    >>> method_name(0), method_name(3)
    ('jensen', 'bessel-legendre N=3')
    """
    return {0: "jensen", 1: "wirtinger"}.get(order, f"bessel-legendre N={order}")


@dataclasses.dataclass(frozen=True)
class LmiCertificate:
    """Rational matrices P ((N+1)n), S, R (n) of the order-N functional.

    >>> import sympy
    >>> LmiCertificate(0, sympy.eye(1), sympy.eye(1), sympy.eye(1)).order
    0
    """

    order: int
    P: sympy.Matrix
    S: sympy.Matrix
    R: sympy.Matrix


@dataclasses.dataclass(frozen=True)
class LmiResult:
    """The order-N LMI at one delay: solved, rounded, re-verified.

    Attributes
    ----------
    order : int
    h : sympy.Rational
    status : Status
        ``exact``/``certified``: the rounded certificate verified (stability at h proved);
        ``undecided``: the solver found no strictly feasible point, or its rounded solution
        did not verify (``check`` is then ``failed`` with its witness) — an LMI never refutes
        stability, so this result is never ``failed``.
    solver_status : str
    certificate : LmiCertificate or None
    check : ConditionResult or None
    solve_seconds, check_seconds : float
    detail : str

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> certify_delay(LinearDelaySystem([[-1]], Ad=[[0]]), 1, order=0).holds
    True
    """

    order: int
    h: sympy.Rational
    status: Status
    solver_status: str
    certificate: LmiCertificate | None
    check: ConditionResult | None
    solve_seconds: float
    check_seconds: float
    detail: str

    @property
    def holds(self) -> bool:
        return self.status.is_proof


# ------------------------------------------------------------------ the LMI, for any matrix algebra
def _blocks(system: LinearDelaySystem, order: int):
    """Number of Ω blocks in ζ: N (the Bessel terms need Ω_0 … Ω_{N−1}), at least 1 with a distributed delay."""
    return max(order, 1 if system.has_distributed else 0)


def build_lmi(system: LinearDelaySystem, order: int, h, P, S, R, *, zeros, eye, kron_row):
    """(positivity matrix, −Φ_N(h)) built from P, S, R with the given matrix constructors.

    ``zeros(r, c)``, ``eye(n)`` and ``kron_row(blocks)`` (a row of n×n blocks, horizontally
    stacked) let the same code build cvxpy expressions and exact SymPy matrices.
    """
    n, N = system.n, order
    M = _blocks(system, N)
    nb = 2 + M
    A, Ad = system.A, system.Ad
    D = system.kernel[0] if system.has_distributed else None

    def row(entries):  # entries: {block index: n×n matrix}
        return kron_row([entries.get(b, zeros(n, n)) for b in range(nb)])

    I = eye(n)
    F = row({0: A, 1: Ad, **({2: h * D} if D is not None else {})})
    E = []
    for k in range(N + 1):
        e = {0: I, 1: -((-1) ** k) * I}
        for j in range(k):
            c = (2 * j + 1) * (1 - (-1) ** (k + j))
            if c:
                e[2 + j] = -c * I
        E.append(row(e))
    G = [row({0: I})] + [row({2 + j: h * I}) for j in range(N)]
    H = [F] + E[:N]
    return G, H, F, E, row({0: I}), row({1: I})


#: the degree in h of Φ_N(h): He(GᵀPH) ≤ 2, h²FᵀRF ≤ 4 (F has hD with a distributed delay)
PHI_DEGREE = 4


def _phi_at(system, order, h, P, S, R):
    """Φ_N(h) as a cvxpy expression at a numeric h (float matrices; the solver's copy)."""
    n = system.n
    A, Ad, D = system.floats_cached()
    fsys = _FloatView(system, A, Ad, D[0] if D else None)
    G, H, F, E, e0, e1 = build_lmi(fsys, order, h, P, S, R, zeros=lambda r, c: np.zeros((r, c)), eye=np.eye,
                                   kron_row=np.hstack)
    G, H = np.vstack(G), np.vstack(H)
    Phi = G.T @ P @ H + H.T @ P.T @ G + e0.T @ S @ e0 - e1.T @ S @ e1 + h ** 2 * F.T @ R @ F
    for k, Ek in enumerate(E):
        Phi = Phi - (2 * k + 1) * Ek.T @ R @ Ek
    return Phi


class _FloatView:
    """The float matrices of a system, shaped like it for :func:`build_lmi`."""

    def __init__(self, system, A, Ad, D):
        self.n, self.A, self.Ad = system.n, A, Ad
        self.has_distributed = D is not None
        self.kernel = (D,) if D is not None else ()


class _Sdp:
    """The order-N SDP of a system, compiled once (cvxpy DPP): the delay enters through parameters h^k, 1/h.

    Φ_N(h) = Σ_k h^k C_k with C_k affine in (P, S, R), obtained by interpolating Φ_N at
    h = 0, …, 4; the problem: maximise t with −Φ ⪰ tI, P + (1/h)diag(0, S, 3S, …) ⪰ tI,
    S, R ⪰ tI and −I ⪯ P ⪯ I, S, R ⪯ I (a normalisation: the conditions are homogeneous).
    """

    def __init__(self, system, order):
        import cvxpy as cp
        n, N = system.n, order
        q = (N + 1) * n
        self.P = cp.Variable((q, q), symmetric=True)
        self.S = cp.Variable((n, n), symmetric=True)
        self.R = cp.Variable((n, n), symmetric=True)
        self.t = cp.Variable()
        nodes = np.arange(PHI_DEGREE + 1, dtype=float)
        samples = [_phi_at(system, N, x, self.P, self.S, self.R) for x in nodes]
        Vinv = np.linalg.inv(np.vander(nodes, increasing=True))
        self.powers = [cp.Parameter(nonneg=True) for _ in range(PHI_DEGREE + 1)]
        self.hinv = cp.Parameter(nonneg=True)
        Phi = 0
        for k in range(PHI_DEGREE + 1):
            Ck = sum(Vinv[k, j] * samples[j] for j in range(len(nodes)) if Vinv[k, j] != 0)
            Phi = Phi + self.powers[k] * Ck
        Phi = (Phi + Phi.T) / 2
        if N:
            shift = cp.bmat([[((2 * i - 1) * self.S if (i == j and i > 0) else np.zeros((n, n)))
                              for j in range(N + 1)] for i in range(N + 1)])
            pos = self.P + self.hinv * shift
        else:
            pos = self.P
        m = Phi.shape[0]
        cons = [-Phi >> self.t * np.eye(m), pos >> self.t * np.eye(q), self.S >> self.t * np.eye(n),
                self.R >> self.t * np.eye(n), self.P << np.eye(q), self.P >> -np.eye(q), self.S << np.eye(n),
                self.R << np.eye(n)]
        self.problem = cp.Problem(cp.Maximize(self.t), cons)

    def solve(self, h: float):
        import cvxpy as cp
        if not h > 0:  # the functional's shift term is 1/h: no certificate is sought at h ≤ 0
            return None, "h ≤ 0 (the hierarchy needs a positive delay)", None
        for k, par in enumerate(self.powers):
            par.value = h ** k
        self.hinv.value = 1 / h
        with warnings.catch_warnings():  # "may be inaccurate": the status is reported, never trusted
            warnings.simplefilter("ignore", UserWarning)
            status = solve_sdp(self.problem)
        t = self.t.value
        if status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or t is None or not t > 0:
            return None, status, None if t is None else float(t)
        return (np.asarray(self.P.value), np.asarray(self.S.value), np.asarray(self.R.value)), status, float(t)


_SDP_CACHE: dict = {}


def _solve(system, order, h: float):
    """The float solution (P, S, R) at h, the solver status and the margin t (None: no strictly feasible point)."""
    key = (id(system), order)
    entry = _SDP_CACHE.get(key)
    if entry is None or entry[0] is not system:
        if len(_SDP_CACHE) > 32:
            _SDP_CACHE.clear()
        entry = (system, _Sdp(system, order))
        _SDP_CACHE[key] = entry
    return entry[1].solve(h)


def _round(X: np.ndarray) -> sympy.Matrix:
    scale = 2 ** ROUNDING_BITS
    S = (X + X.T) / 2
    return sympy.Matrix(S.shape[0], S.shape[1], lambda i, j: sympy.Rational(int(round(S[i, j] * scale)), scale))


# ------------------------------------------------------------------ exact re-verification
def _q(M) -> fmpq_mat:
    """A rational SymPy matrix as a flint fmpq_mat (exact)."""
    return fmpq_mat(M.rows, M.cols, [fmpq(int(e.p), int(e.q)) for e in M])


def _q_hstack(blocks) -> fmpq_mat:
    rows = blocks[0].nrows()
    tables = [b.table() for b in blocks]
    return fmpq_mat([sum((t[i] for t in tables), []) for i in range(rows)])


def _q_vstack(blocks) -> fmpq_mat:
    return fmpq_mat(sum((b.table() for b in blocks), []))


def _q_eye(n) -> fmpq_mat:
    return fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])


def _conditions(system, hq, c):
    """The four matrices that must be positive definite: P + (1/h)diag(0, S, 3S, …), S, R, −Φ_N(h).

    Rational data is assembled in flint's exact fmpq_mat (fast), other data in SymPy; SymPy
    matrices are returned either way.
    """
    n, N = system.n, c.order
    rational = system.is_rational and all(e.is_Rational for M in (c.P, c.S, c.R) for e in M) and hq.is_Rational
    if rational:
        qsys = _FloatView(system, _q(system.A), _q(system.Ad), _q(system.kernel[0]) if system.has_distributed else None)
        P, S, R, h = _q(c.P), _q(c.S), _q(c.R), fmpq(int(hq.p), int(hq.q))
        ops = dict(zeros=lambda r, k: fmpq_mat(r, k), eye=_q_eye, kron_row=_q_hstack)
        vstack, T = _q_vstack, lambda M: M.transpose()
    else:
        qsys, P, S, R, h = system, c.P, c.S, c.R, hq
        ops = dict(zeros=sympy.zeros, eye=sympy.eye, kron_row=lambda bl: sympy.Matrix.hstack(*bl))
        vstack, T = lambda bl: sympy.Matrix.vstack(*bl), lambda M: M.T
    G, H, F, E, e0, e1 = build_lmi(qsys, N, h, P, S, R, **ops)
    G, H = vstack(G), vstack(H)
    Phi = T(G) * P * H + T(H) * P * G + T(e0) * S * e0 - T(e1) * S * e1 + h * h * (T(F) * R * F)
    for k, Ek in enumerate(E):
        Phi = Phi - (2 * k + 1) * (T(Ek) * R * Ek)
    if rational:
        Phi = sympy.Matrix(Phi.nrows(), Phi.ncols(), lambda i, j: _r(Phi[i, j]))
    shift = sympy.diag(sympy.zeros(n, n), *[(2 * i - 1) / hq * c.S for i in range(1, N + 1)])
    return [("P + (1/h)diag(0, S, 3S, …)", c.P + shift), ("S", c.S), ("R", c.R), ("−Φ_N(h)", -Phi)]


def _r(x: fmpq) -> sympy.Rational:
    return sympy.Rational(int(x.p), int(x.q))


def quick_check(system: LinearDelaySystem, h, certificate: LmiCertificate) -> bool:
    """The decision of :func:`check_certificate` for rational data (the same LDLᵀ in fractions), without λ_min.

    Used to steer bisections; a reported delay is always re-checked by :func:`check_certificate`.

    >>> import sympy
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> one = sympy.eye(1)
    >>> quick_check(LinearDelaySystem([[-1]], Ad=[[0]]), 1, LmiCertificate(0, one, one / 10, one / 10))
    True
    """
    hq = parse_delay(h) if not isinstance(h, sympy.Basic) else h
    if not system.is_rational:
        return check_certificate(system, hq, certificate).holds
    return all(_exact_ldl(_fractions(M)).kind == "pd" for _, M in _conditions(system, hq, certificate))


def check_certificate(system: LinearDelaySystem, h, certificate: LmiCertificate, *,
                      name: str | None = None) -> ConditionResult:
    """Re-verify a rational certificate at the delay h: the four matrix conditions, exactly (or in arb).

    Returns
    -------
    ConditionResult
        ``exact`` (rational data) or ``certified`` (irrational entries, arb; or a float input: the
        system's, the delay's or the certificate's, at its exact binary value) when all four hold;
        ``failed`` with the witness of the first that does not.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys = LinearDelaySystem([[-1]], Ad=[[0]])
    >>> one = sympy.eye(1)
    >>> check_certificate(sys, 1, LmiCertificate(0, one, one / 10, one / 10)).status
    <Status.EXACT: 'exact'>
    >>> check_certificate(sys, 1, LmiCertificate(0, -one, one, one)).status
    <Status.FAILED: 'failed'>
    >>> check_certificate(sys, 1.0, LmiCertificate(0, one, one / 10, one / 10)).status   # a float delay
    <Status.CERTIFIED: 'certified'>
    """
    hq = parse_delay(h) if not isinstance(h, sympy.Basic) else h
    if not hq > 0:
        raise InputError(f"h: expected a positive delay for an LMI certificate, got {h}")
    c = certificate
    n, N = system.n, c.order
    if c.P.shape != ((N + 1) * n, (N + 1) * n) or c.S.shape != (n, n) or c.R.shape != (n, n):
        raise InputError(f"certificate of order {N}: expected P of size {(N + 1) * n}, S and R of size {n}, got "
                         f"{c.P.shape}, {c.S.shape}, {c.R.shape}")
    parts = [matrix_positive_definite(M, name=label) for label, M in _conditions(system, hq, c)]
    res = combine(name or f"{method_name(N)} LMI at h = {hq}", parts, certificate=c)
    return _capped(res, system.from_float or has_float(h) or has_float([c.P, c.S, c.R]))


def _capped(res, inexact: bool):
    """``res`` at most ``certified`` when an input went through floating point (:mod:`lkverify.status`)."""
    status = at_most_certified(res.status, inexact)
    if status is res.status:
        return res
    return dataclasses.replace(res, status=status, detail=f"{res.detail}; {FLOAT_NOTE}")


def solve_certificate(system: LinearDelaySystem, h, order: int):
    """The solver's solution at h rounded to a rational :class:`LmiCertificate`, or None (not verified here).

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> solve_certificate(LinearDelaySystem([[-1]], Ad=[[0]]), 1, 0).order
    0
    """
    sol, _, _ = _solve(system, order, float(h))
    return None if sol is None else LmiCertificate(order, *(_round(X) for X in sol))


def certify_delay(system: LinearDelaySystem, h, *, order: int = 2) -> LmiResult:
    """Solve the order-N LMI at the delay h, round the solution to rationals, verify it exactly.

    Parameters
    ----------
    system : LinearDelaySystem
        Constant kernel only (a polynomial kernel is :class:`UnsupportedInput`).
    h : number or str
        The delay, read exactly (``"6.1725"`` is 2469/400; a float such as 6.17 at its binary
        value, and the result is then at most ``certified``).
    order : int
        N ≥ 0 (0 Jensen, 1 Wirtinger, ≥ 2 Bessel–Legendre).

    Returns
    -------
    LmiResult
        ``exact`` (rational data), ``certified`` (irrational data, or a float input), or ``undecided``.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
    >>> certify_delay(sys, 5, order=0).status.value      # beyond Jensen's reach (≈ 4.47)
    'undecided'
    """
    if not isinstance(order, int) or isinstance(order, bool) or order < 0:
        raise InputError(f"order: expected an integer N ≥ 0 (0 Jensen, 1 Wirtinger, ≥ 2 Bessel–Legendre), got {order!r}")
    if not system.constant_kernel:
        raise UnsupportedInput("the LMI hierarchy supports constant distributed kernels; the kernel of this system "
                               f"has degree {system.kernel_order} (the spectral route handles it)")
    hq = parse_delay(h)
    if not hq > 0:
        raise InputError(f"h: expected a positive delay, got {h}")
    name = f"{method_name(order)} LMI at h = {hq}"
    t0 = time.perf_counter()
    sol, status, margin = _solve(system, order, float(hq))
    t1 = time.perf_counter()
    if sol is None:
        return LmiResult(order, hq, Status.UNDECIDED, status, None, None, t1 - t0, 0.0,
                         f"{name}: Clarabel found no strictly feasible point (status {status!r}, margin "
                         f"{margin if margin is None else f'{margin:.2e}'}); no certificate, nothing refuted")
    cert = LmiCertificate(order, *(_round(X) for X in sol))
    check = check_certificate(system, h, cert, name=name)
    t2 = time.perf_counter()
    verdict = ("verified" if check.holds else f"{check.status.value}: {check.detail}")
    detail = (f"{name}: Clarabel status {status!r}, margin {margin:.2e}; P, S, R rounded to multiples of "
              f"2^-{ROUNDING_BITS} and re-verified ({'LDLᵀ in fractions' if system.is_rational else 'arb'}): "
              f"{verdict}" + (f"; {FLOAT_NOTE}" if check.holds and FLOAT_NOTE in check.detail else ""))
    # a candidate that does not verify refutes nothing about the system: the delay stays undecided
    verdict_status = check.status if check.holds else Status.UNDECIDED
    return LmiResult(order, hq, verdict_status, status, cert, check, t1 - t0, t2 - t1, detail)
