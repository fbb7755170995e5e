"""Linear matrix inequalities: solved with cvxpy + Clarabel, rounded to rationals, re-verified exactly.

:func:`check_lyapunov_matrix`, :func:`find_lyapunov_matrix`
    P ≻ 0 and AᵀP + PA ≺ 0, given or found by an SDP (cvxpy + Clarabel),
    rounded to rationals and re-verified exactly.  A rational A that is not
    Hurwitz (exact Routh–Hurwitz test) → ``failed`` with the eigenvalue.
:func:`check_quadratic_bound`, :func:`best_quadratic_upper_bound`
    xᵀMx ≤ c·xᵀNx for all x, for a claimed c (exact PSD test of cN − M) or for
    the best c (SDP, rounded up to a rational, re-verified).
:func:`lmi_feasible`
    a general LMI F0 + Σ yᵢFᵢ ≻ 0: a rational y verified exactly, or an
    exact dual (Farkas) certificate of infeasibility.

A solver status other than ``optimal`` is never a certificate: the result is
then ``undecided``.  Every positive answer is a rational object (P, c, y) whose
conditions :func:`lkverify.certify.matrices.matrix_positive_definite` proved.

Examples
--------
>>> find_lyapunov_matrix([[0, 1], [-2, -3]]).status
<Status.EXACT: 'exact'>
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from fractions import Fraction

import flint
import numpy as np
import sympy
from flint import fmpq, fmpq_mat

from ..errors import InputError
from ..status import Status
from .conditions import ConditionResult, Margin, Estimate, _frac, combine
from .intervals import enclose, float_down, lower_fraction
from .matrices import (_as_matrix, _is_rational, _number, _rational_vector, _short, _symmetric_part,
                       matrix_positive_definite)

__all__ = [
    "best_quadratic_upper_bound", "check_lyapunov_matrix", "check_quadratic_bound", "find_lyapunov_matrix", "lmi_feasible", "round_symmetric", "solve_sdp",
]

#: find_lyapunov_matrix's attempts: (margin ε relative to max |Q|, rounding denominator as a multiple of
#: ``denominator``); a later attempt asks the solver for more slack and rounds finer
LYAPUNOV_ATTEMPTS = ((0.0, 1), (1e-3, 1), (1e-2, 1000))
#: best_quadratic_upper_bound's relative bumps of the solver's c before rounding up and re-verifying
BOUND_BUMPS = (0.0, 1e-9, 1e-6, 1e-3)


def solve_sdp(problem) -> str:
    """Solve a cvxpy problem with clarabel; its status string (``"optimal"``, …, or ``"solver error (…)"``).

    The one call into the SDP solver: a status other than ``"optimal"`` is never a certificate.
    """
    import cvxpy as cp
    try:
        problem.solve(solver=cp.CLARABEL)
    except cp.error.SolverError as exc:
        return f"solver error ({exc})"
    return str(problem.status)


def round_symmetric(X: np.ndarray, den: int) -> sympy.Matrix:
    """The symmetric part of a float matrix rounded to rationals with denominators ≤ ``den`` (then verified exactly)."""
    n = X.shape[0]
    S = (X + X.T) / 2
    return sympy.Matrix(n, n, lambda i, j: _rat(S[min(i, j), max(i, j)], den))


def _rat(v: float, den: int) -> sympy.Rational:
    q = Fraction(float(v)).limit_denominator(den)
    return sympy.Rational(q.numerator, q.denominator)


def _routh_hurwitz(A: sympy.Matrix) -> tuple[bool, int, sympy.Rational, sympy.Poly]:
    """Exact Hurwitz test of the characteristic polynomial (a0 = 1): all Hurwitz minors Δ_k > 0."""
    s = sympy.Symbol("s")
    cp = fmpq_mat([[fmpq(int(e.p), int(e.q)) for e in row] for row in A.tolist()]).charpoly()
    a = [sympy.Rational(int(c.p), int(c.q)) for c in reversed(cp.coeffs())]  # a[0] = 1, …, a[n]
    n = len(a) - 1
    coef = lambda k: a[k] if 0 <= k <= n else sympy.Integer(0)  # noqa: E731
    H = sympy.Matrix(n, n, lambda i, j: coef(2 * j - i + 1))
    for k in range(1, n + 1):
        delta = H[:k, :k].det(method="bareiss")
        if not delta > 0:
            return False, k, delta, sympy.Poly(a, s)
    return True, n, delta, sympy.Poly(a, s)


def check_lyapunov_matrix(A, P, *, Q=None, name: str = "Lyapunov") -> ConditionResult:
    """Verify P ≻ 0 and AᵀP + PA ≺ 0 (or AᵀP + PA ⪯ −Q) for given matrices.

    Parameters
    ----------
    A : square matrix
    P : symmetric matrix of the same size
    Q : symmetric matrix, optional
        With Q the second condition is −(AᵀP + PA) − Q ⪰ 0.
    name : str

    Returns
    -------
    ConditionResult
        ``parts`` holds the two matrix conditions; ``exact`` when both are
        decided in fractions, ``certified`` when one needed arb;
        ``failed`` with the witness of the first failing part; ``margin``
        encloses λ_min of the second matrix; ``certificate`` is P.

    Examples
    --------
    >>> res = check_lyapunov_matrix([[0, 1], [-2, -3]], [[5, 1], [1, 1]])
    >>> res.status, [p.status.value for p in res.parts]
    (<Status.EXACT: 'exact'>, ['exact', 'exact'])
    >>> check_lyapunov_matrix([[0, 1], [-2, -3]], [[-5, -1], [-1, -1]]).status
    <Status.FAILED: 'failed'>
    """
    Am = _as_matrix(A, "A")
    Pm = _as_matrix(P, "P")
    if Am.shape != Pm.shape:
        raise InputError(f"{name}: expected A and P of the same size, got A {Am.shape} and P {Pm.shape}")
    Pm, _ = _symmetric_part(Pm, "P", False)
    part1 = matrix_positive_definite(Pm, name="P")
    L = -(Am.T * Pm + Pm * Am)
    if Q is None:
        part2 = matrix_positive_definite(L, name="−(AᵀP + PA)")
    else:
        Qm = _as_matrix(Q, "Q")
        if Qm.shape != Am.shape:
            raise InputError(f"{name}: expected Q of size {Am.shape}, got {Qm.shape}")
        part2 = matrix_positive_definite(L - Qm, name="−(AᵀP + PA) − Q", semidefinite=True)
    return combine(name, [part1, part2], certificate=Pm)


def find_lyapunov_matrix(A, *, Q=None, name: str = "Lyapunov", denominator: int = 10**6) -> ConditionResult:
    """Find a rational P ≻ 0 with AᵀP + PA ≺ 0 (or ⪯ −Q), proved exactly.

    A rational A is first tested exactly (Routh–Hurwitz on the characteristic
    polynomial): no P exists unless A is Hurwitz, and a non-Hurwitz A gives
    ``failed`` with an eigenvalue of nonnegative real part.  Otherwise the
    SDP min tr P s.t. P ⪰ I, AᵀP + PA ⪯ −Q − εI (Q = I when not given) is
    solved with Clarabel, P is rounded entrywise to rationals with
    denominators ≤ ``denominator`` (symmetrised) and verified by
    :func:`check_lyapunov_matrix`.  If rounding breaks the verification the
    SDP is solved again with a margin ε > 0 (and finer rounding); then the
    result is ``undecided``.

    Parameters
    ----------
    A : square matrix
    Q : symmetric PSD matrix, optional
    name : str
    denominator : int

    Returns
    -------
    ConditionResult
        ``exact``/``certified``: ``certificate`` is the verified rational P,
        ``parts`` the two verified conditions, ``margin`` encloses
        λ_min(−(AᵀP + PA)) (minus Q); ``estimate`` is the solver's value of
        the same eigenvalue for its float P.  ``failed``: A is not Hurwitz
        (exact), ``witness`` is the eigenvalue.  ``undecided``: the solver
        status was not ``optimal`` (it is in the detail) or the rounded P did
        not verify; never a proof.

    Examples
    --------
    >>> res = find_lyapunov_matrix([[0, 1], [-2, -3]])
    >>> res.status, res.certificate.is_symmetric()
    (<Status.EXACT: 'exact'>, True)
    >>> res = find_lyapunov_matrix([[1, 0], [0, -1]])
    >>> res.status, res.witness
    (<Status.FAILED: 'failed'>, 1)
    """
    Am = _as_matrix(A, "A")
    Qm = None if Q is None else _as_matrix(Q, "Q")
    if Qm is not None:
        Qm, _ = _symmetric_part(Qm, "Q", False)
        if Qm.shape != Am.shape:
            raise InputError(f"{name}: expected Q of size {Am.shape}, got {Qm.shape}")
    hurwitz_note = ""
    if _is_rational(Am):
        refuted = _not_hurwitz(Am, name)
        if refuted is not None:
            return refuted
        hurwitz_note = "A is Hurwitz (exact Routh–Hurwitz test), so such a P exists. "
    return _lyapunov_by_sdp(Am, Qm, name=name, denominator=denominator, note=hurwitz_note)


def _not_hurwitz(Am: sympy.Matrix, name: str) -> ConditionResult | None:
    """``failed`` with an eigenvalue of nonnegative real part when the rational A is not Hurwitz, else None."""
    ok, k, delta, charpoly = _routh_hurwitz(Am)
    if ok:
        return None
    roots = charpoly.all_roots()
    lam = max(roots, key=lambda r: (float(sympy.re(r.evalf(30))), float(sympy.im(r.evalf(30)))))
    detail = (f"A is not Hurwitz (exact Routh–Hurwitz test): the Hurwitz minor Δ_{k} = {delta} ≤ 0 for "
              f"the characteristic polynomial {charpoly.as_expr()}; A has the eigenvalue {lam} "
              f"(≈ {complex(lam.evalf(15)):.6g}) with Re λ ≥ 0, so no P ≻ 0 with AᵀP + PA ≺ 0 exists "
              "(for an eigenvector v, v*(AᵀP + PA)v = 2 Re λ · v*Pv ≥ 0).")
    return ConditionResult(name, Status.FAILED, witness=lam, detail=detail)


def _lyapunov_by_sdp(Am: sympy.Matrix, Qm: sympy.Matrix | None, *, name: str, denominator: int,
                     note: str) -> ConditionResult:
    """min tr P s.t. P ⪰ I, AᵀP + PA ⪯ −Q − εI for the margins ε of :data:`LYAPUNOV_ATTEMPTS`; round, verify."""
    import cvxpy as cp

    n = Am.rows
    Af = _floats(Am)
    Qf = np.eye(n) if Qm is None else _floats(Qm)
    qscale = max(1.0, float(np.max(np.abs(Qf))))
    attempts = [(eps * qscale, denominator * finer) for eps, finer in LYAPUNOV_ATTEMPTS]
    last = None
    for k, (eps, den) in enumerate(attempts, start=1):
        P = cp.Variable((n, n), symmetric=True)
        lyap = Af.T @ P + P @ Af
        prob = cp.Problem(cp.Minimize(cp.trace(P)),
                          [P >> np.eye(n), lyap << -(Qf + eps * np.eye(n))])
        status = solve_sdp(prob)
        if status != cp.OPTIMAL:
            return ConditionResult(name, Status.UNDECIDED, detail=(
                f"{note}The SDP solver (Clarabel) returned the status {status!r}, not 'optimal'; a "
                "solver status other than optimal is never a certificate."))
        Pf = np.asarray(P.value, dtype=float)
        est = Estimate(float(np.min(np.linalg.eigvalsh(-(Af.T @ Pf + Pf @ Af) - (0 if Qm is None else Qf)))),
                       "λ_min of the solver's float P (Clarabel)")
        res = check_lyapunov_matrix(Am, round_symmetric(Pf, den), Q=Qm, name=name)
        if res.status.is_proof:
            detail = (f"{note}P found by Clarabel (attempt {k}, margin ε = {eps:g}), rounded to "
                      f"denominators ≤ {den}, verified. " + " ".join(p.detail for p in res.parts))
            return dataclasses.replace(res, estimate=est, detail=detail)
        last = res
    return ConditionResult(name, Status.UNDECIDED, margin=last.margin, estimate=est, certificate=last.certificate,
                           parts=last.parts, detail=(
                               f"{note}The rounded solver P did not verify after {len(attempts)} attempts "
                               f"(margins and finer rounding): {last.detail}"))


def _floats(M: sympy.Matrix) -> np.ndarray:
    """A float array of a numeric SymPy matrix (17 significant digits): the solver's copy, never a proof."""
    return np.array(M.evalf(17).tolist(), dtype=float)


def _matrix_list(M, name: str) -> list[sympy.Matrix]:
    def is_matrix(v):
        return isinstance(v, (sympy.MatrixBase, np.ndarray)) and getattr(v, "ndim", 2) == 2 or (
            isinstance(v, (list, tuple)) and len(v) > 0 and isinstance(v[0], (list, tuple, np.ndarray)))

    if isinstance(M, (list, tuple)) and len(M) > 0 and is_matrix(M[0]):
        out = [_as_matrix(m, f"{name}[{k}]") for k, m in enumerate(M)]
    else:
        out = [_as_matrix(M, name)]
    return [_symmetric_part(m, name if len(out) == 1 else f"{name}[{k}]", False)[0] for k, m in enumerate(out)]


def _check_n(N, n: int, name: str) -> sympy.Matrix:
    if N is None:
        return sympy.eye(n)
    Nm = _symmetric_part(_as_matrix(N, "N"), "N", False)[0]
    if Nm.rows != n:
        raise InputError(f"{name}: expected N of size {n}×{n} like M, got {Nm.rows}×{Nm.rows}")
    res = matrix_positive_definite(Nm, name="N")
    if not res.holds:
        raise InputError(f"{name}: expected a positive definite N (xᵀNx is the comparison form), got N with "
                         f"{res.status}: {res.detail}; pass a positive definite N")
    return Nm


def check_quadratic_bound(M, c, *, N=None, name: str = "quadratic bound") -> ConditionResult:
    """Decide xᵀMx ≤ c·xᵀNx for all x (for every M when a list is given): cN − M ⪰ 0.

    Parameters
    ----------
    M : symmetric matrix, or a list of them
    c : number (int, Fraction, SymPy number; a float is its exact binary value)
    N : symmetric positive definite matrix, optional (default I)
    name : str

    Returns
    -------
    ConditionResult
        ``exact``/``certified``: cN − M ⪰ 0 proved; ``margin`` encloses
        λ_min(cN − M) (the smallest over the list).  ``failed``: ``witness`` is
        an integer vector x with xᵀMx > c·xᵀNx (checked exactly).

    Examples
    --------
    >>> import sympy
    >>> check_quadratic_bound([[2, 1], [1, 2]], 3).status      # largest eigenvalue 3
    <Status.EXACT: 'exact'>
    >>> res = check_quadratic_bound([[2, 1], [1, 2]], sympy.Rational(29, 10))
    >>> res.status, res.witness
    (<Status.FAILED: 'failed'>, (Fraction(1, 1), Fraction(1, 1)))
    """
    Ms = _matrix_list(M, "M")
    n = Ms[0].rows
    if any(m.rows != n for m in Ms):
        raise InputError(f"{name}: expected matrices of one size, got sizes {[m.rows for m in Ms]}")
    problems: list[str] = []
    cv = _number(c, "c", problems)
    if problems:
        raise InputError(f"{name}: " + "; ".join(problems))
    Nm = _check_n(N, n, name)
    parts = []
    for k, m in enumerate(Ms):
        label = "cN − M" if len(Ms) == 1 else f"cN − M[{k}]"
        parts.append(matrix_positive_definite(cv * Nm - m, name=label, semidefinite=True))
    bad = next((p for p in parts if p.status is Status.FAILED), None)
    if bad is not None:
        k = parts.index(bad)
        x = bad.witness
        xs = sympy.Matrix([sympy.Rational(v.numerator, v.denominator) for v in x])
        lhs, rhs = (xs.T * Ms[k] * xs)[0], (xs.T * Nm * xs)[0]
        detail = (f"the bound xᵀMx ≤ {_short(cv)}·xᵀNx is false: at x = ({', '.join(map(str, x))}) "
                  f"xᵀMx = {_short(lhs)} > c·xᵀNx = {_short(cv * rhs)} ({bad.status}). {bad.detail}")
        return ConditionResult(name, Status.FAILED, margin=bad.margin, witness=x, detail=detail, parts=tuple(parts))
    res = combine(name, parts, certificate=cv)
    if res.holds:
        lo = min(p.margin.lo for p in parts)
        hi = min(p.margin.hi for p in parts)
        res = dataclasses.replace(res, margin=Margin(lo, hi), detail=(
            f"xᵀMx ≤ {cv}·xᵀNx for all x: " + "; ".join(p.detail for p in parts)))
    return res


def best_quadratic_upper_bound(M, *, N=None, name: str = "best quadratic bound",
                               denominator: int = 10**6) -> ConditionResult:
    """The smallest c with xᵀMx ≤ c·xᵀNx for all x, solved as an SDP and verified.

    The SDP min c s.t. cN − M ⪰ 0 (for every M of a list) is solved with
    Clarabel; c is rounded *up* to a rational with denominator
    ``denominator`` and cN − M ⪰ 0 is re-verified exactly (bumped up a
    little if needed).  A lower bound of the best constant comes from the
    generalized eigenvector, rounded to a rational x: c* ≥ xᵀMx / xᵀNx.

    Parameters
    ----------
    M : symmetric matrix, or a list of them
    N : symmetric positive definite matrix, optional (default I)
    name : str
    denominator : int

    Returns
    -------
    ConditionResult
        ``exact``/``certified``: ``certificate`` is the verified rational c;
        ``margin`` = [lo, c] encloses the best constant c* (lo a Rayleigh
        quotient at ``margin.point``); ``estimate`` is the solver's c.
        ``undecided``: solver status not ``optimal`` or no rounded c verified.

    Examples
    --------
    >>> res = best_quadratic_upper_bound([[2, 1], [1, 2]])
    >>> res.status, res.certificate, res.margin.lo
    (<Status.EXACT: 'exact'>, 3, Fraction(3, 1))
    """
    import cvxpy as cp

    Ms = _matrix_list(M, "M")
    n = Ms[0].rows
    if any(m.rows != n for m in Ms):
        raise InputError(f"{name}: expected matrices of one size, got sizes {[m.rows for m in Ms]}")
    Nm = _check_n(N, n, name)
    Mf = [_floats(m) for m in Ms]
    Nf = _floats(Nm)
    c = cp.Variable()
    prob = cp.Problem(cp.Minimize(c), [c * Nf - m >> 0 for m in Mf])
    status = solve_sdp(prob)
    if status != cp.OPTIMAL:
        return ConditionResult(name, Status.UNDECIDED, detail=(
            f"the SDP solver (Clarabel) returned {status!r}, not 'optimal'; never a certificate."))
    c_est = float(c.value)
    est = Estimate(c_est, "Clarabel SDP: min c s.t. cN − M ⪰ 0")
    lo, lo_pt = _rayleigh_lower_bound(Ms, Mf, Nm, Nf)
    scale = max(1.0, abs(c_est))
    for bump in BOUND_BUMPS:
        cand = Fraction(math.ceil((c_est + bump * scale) * denominator), denominator)
        if lo is not None and cand < lo:
            continue
        cq = sympy.Rational(cand.numerator, cand.denominator)
        res = check_quadratic_bound(Ms if len(Ms) > 1 else Ms[0], cq, N=Nm, name=name)
        if res.holds:
            exact = cq if lo == cand else None
            lo_s = "−∞" if lo is None else (str(lo) if exact is not None else f"{float_down(lo):.12g}")
            detail = (f"best c: Clarabel estimate {c_est:.12g}; rounded up to {cq} and verified "
                      f"({res.status}): cN − M ⪰ 0; the best constant lies in [{lo_s}, {cq}]"
                      + (" (attained: exact)" if exact is not None else "")
                      + (" (the lower end is xᵀMx/xᵀNx at the rational x = margin.point)" if lo is not None else "")
                      + ".")
            return ConditionResult(name, res.status, margin=Margin(lo, cand, exact=exact, point=lo_pt),
                                   estimate=est, certificate=cq, detail=detail, parts=res.parts)
    return ConditionResult(name, Status.UNDECIDED, estimate=est, detail=(
        f"the solver's c = {c_est:.12g} rounded up (by up to {BOUND_BUMPS[-1]:g} relative) did not verify "
        "cN − M ⪰ 0."))


def _rayleigh_lower_bound(Ms, Mf, Nm, Nf) -> tuple[Fraction | None, tuple | None]:
    """A certified lower bound of the best c: the largest xᵀMx/xᵀNx at rational generalized eigenvectors x."""
    import scipy.linalg

    lo, lo_pt = None, None
    for m, mf in zip(Ms, Mf):
        w, V = scipy.linalg.eigh(mf, Nf)
        x = _rational_vector(V[:, -1], 2**30)
        xs = sympy.Matrix([sympy.Rational(v.numerator, v.denominator) for v in x])
        num, den_ = (xs.T * m * xs)[0], (xs.T * Nm * xs)[0]
        if num.is_Rational and den_.is_Rational:
            r = _frac(num / den_)
        else:
            with flint.ctx.workprec(128):
                r = lower_fraction(enclose(num, prec=None) / enclose(den_, prec=None))
        if r is not None and (lo is None or r > lo):
            lo, lo_pt = r, x
    return lo, lo_pt


def lmi_feasible(F0, F: Sequence = (), *, name: str = "LMI", bound: float = 1e4,
                 denominator: int = 10**6) -> ConditionResult:
    """Find a rational y with F0 + Σ yᵢFᵢ ≻ 0, or prove that none exists.

    The SDP max t s.t. F0 + Σ yᵢFᵢ ⪰ tI, |yᵢ| ≤ ``bound`` is solved with
    Clarabel; if t > 0, y is rounded to rationals and F(y) ≻ 0 verified with
    :func:`matrix_positive_definite`.  If t ≤ 0 and the data are rational, a
    dual (Farkas) certificate is sought: Z ≻ 0 with tr(FᵢZ) = 0 for all i
    and tr(F0 Z) ≤ 0, rounded and projected exactly; it proves that
    F(y) ≻ 0 has no solution for any y (then tr(F(y)Z) > 0 would equal
    tr(F0 Z) ≤ 0).

    Parameters
    ----------
    F0 : symmetric matrix
    F : sequence of symmetric matrices of the same size
    name : str
    bound : float
        Box on y for the primal SDP (it does not restrict the dual proof).
    denominator : int

    Returns
    -------
    ConditionResult
        ``exact``/``certified``: ``certificate`` is the tuple y of Fractions,
        ``margin`` encloses λ_min(F(y)).  ``failed``: ``witness`` is the
        rational dual matrix Z (exact).  ``undecided``: solver status not
        ``optimal``, no verified y and no verified Z.

    Examples
    --------
    >>> res = lmi_feasible([[-1, 0], [0, 3]], [[[1, 0], [0, 1]]])      # y > 1
    >>> res.status, res.certificate[0] > 1
    (<Status.EXACT: 'exact'>, True)
    >>> lmi_feasible([[-1, 0], [0, -1]], [[[1, 0], [0, -1]]]).status
    <Status.FAILED: 'failed'>
    """
    import cvxpy as cp
    F0m = _symmetric_part(_as_matrix(F0, "F0"), "F0", False)[0]
    Fm = [_symmetric_part(_as_matrix(f, f"F[{i}]"), f"F[{i}]", False)[0] for i, f in enumerate(F)]
    n = F0m.rows
    if any(f.rows != n for f in Fm):
        raise InputError(f"{name}: expected every Fᵢ of size {n}×{n} like F0, got sizes {[f.rows for f in Fm]}")
    k = len(Fm)
    F0f, Ff = _floats(F0m), [_floats(f) for f in Fm]
    t = cp.Variable()
    if k:
        y = cp.Variable(k)
        expr = F0f + sum(y[i] * Ff[i] for i in range(k))
        cons = [expr - t * np.eye(n) >> 0, cp.abs(y) <= bound]
    else:
        y = None
        cons = [F0f - t * np.eye(n) >> 0]
    prob = cp.Problem(cp.Maximize(t), cons)
    status = solve_sdp(prob)
    if status != cp.OPTIMAL:
        return ConditionResult(name, Status.UNDECIDED, detail=(
            f"the SDP solver (Clarabel) returned {status!r}, not 'optimal'; never a certificate."))
    est = Estimate(float(t.value), "Clarabel: max t s.t. F(y) ⪰ tI")
    last = None
    if t.value > 0:
        found, last = _verified_point(F0m, Fm, y.value if k else [], denominator)
        if found is not None:
            yq, den, res = found
            return ConditionResult(name, res.status, margin=res.margin, estimate=est, certificate=yq,
                                   parts=(res,), detail=(
                                       f"y = ({', '.join(map(str, yq))}) found by Clarabel, rounded to "
                                       f"denominators ≤ {den}; {res.detail}"))
    if _is_rational(F0m) and all(_is_rational(f) for f in Fm):
        Z = _dual_certificate(F0m, Fm, F0f, Ff)
        if Z is not None:
            tr0 = (F0m * Z).trace()
            return ConditionResult(name, Status.FAILED, estimate=est, witness=Z,
                                   detail=(f"infeasible (exact Farkas certificate): Z ≻ 0 (exact LDLᵀ) with "
                                           f"tr(FᵢZ) = 0 for all i and tr(F0·Z) = {tr0} ≤ 0, so tr(F(y)Z) ≤ 0 "
                                           "for every y while F(y) ≻ 0 would make it positive."))
    why = (f"the solver's best t = {float(t.value):.6g} ≤ 0 (|yᵢ| ≤ {bound:g}) and no exact dual certificate was "
           "found" if t.value <= 0 else f"the rounded y did not verify: {last.detail}")
    return ConditionResult(name, Status.UNDECIDED, estimate=est, detail=f"undecided: {why}.")


def _verified_point(F0m, Fm, yf, denominator: int):
    """The solver's y rounded to rationals (denominator, then 1000× finer) with F(y) ≻ 0 proved.

    Returns ``((y, den, result), None)`` when one verifies, else ``(None, the last result)``.
    """
    n = F0m.rows
    last = None
    for den in (denominator, denominator * 1000):
        yq = tuple(Fraction(float(v)).limit_denominator(den) for v in yf)
        Fy = F0m + sum((sympy.Rational(v.numerator, v.denominator) * f for v, f in zip(yq, Fm)), sympy.zeros(n, n))
        res = matrix_positive_definite(Fy, name="F(y)")
        if res.holds:
            return (yq, den, res), None
        last = res
    return None, last


def _dual_certificate(F0m, Fm, F0f, Ff) -> sympy.Matrix | None:
    """A rational Z ≻ 0 with tr(FᵢZ) = 0 exactly and tr(F0 Z) ≤ 0, or None."""
    import cvxpy as cp
    n = F0m.rows
    Z = cp.Variable((n, n), symmetric=True)
    s = cp.Variable()
    cons = [Z >> s * np.eye(n), cp.trace(Z) == 1, cp.trace(F0f @ Z) <= -s]
    cons += [cp.trace(f @ Z) == 0 for f in Ff]
    prob = cp.Problem(cp.Maximize(s), cons)
    if solve_sdp(prob) != cp.OPTIMAL or not s.value > 0:
        return None
    Zf = np.asarray(Z.value, dtype=float)
    for den in (10**6, 10**9):
        Zq = round_symmetric(Zf, den)
        if Fm:  # project exactly onto {tr(Fᵢ Z) = 0}
            idx = [(i, j) for i in range(n) for j in range(i, n)]
            C = sympy.Matrix([[f[i, j] * (1 if i == j else 2) for (i, j) in idx] for f in Fm])
            rows = C.rowspace()
            if rows:
                B = sympy.Matrix.vstack(*rows)
                z = sympy.Matrix([Zq[i, j] for (i, j) in idx])
                z = z - B.T * (B * B.T).inv() * (B * z)
                Zq = sympy.zeros(n, n)
                for (i, j), v in zip(idx, z):
                    Zq[i, j] = Zq[j, i] = v
        if any((f * Zq).trace() != 0 for f in Fm) or not (F0m * Zq).trace() <= 0:
            continue
        if matrix_positive_definite(Zq, name="Z").status is Status.EXACT:
            return Zq
    return None
