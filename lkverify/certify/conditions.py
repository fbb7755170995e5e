"""Theorem hypotheses as positivity conditions: decided exactly, or certified.

The papers' hypotheses are positivity statements: "ΞD + DΞᵀ is positive
definite" (paper 000, Assumption 2), "Π + τΠ̃ is positive definite" for a
homogeneous form (paper 002, Theorem 1), "there is P ≻ 0 with AᵀP + PA ≺ 0"
(paper 002, Theorem 2, the linear part), "xᵀMx ≤ c·xᵀNx" (a best quadratic
bound).  This module decides them for concrete numbers, and says how sure it is.

:func:`matrix_positive_definite`
    rational entries: an exact LDLᵀ in fractions (all pivots > 0 ⇔ PD) →
    ``exact`` or ``failed`` with an exact witness x, xᵀMx ≤ 0; algebraic or
    transcendental entries (``sqrt(2)``, ``pi``): an LDLᵀ in arb balls whose
    pivots all have positive lower ends → ``certified``; a rational x with a
    certified negative xᵀMx → ``failed``; otherwise ``undecided``.  The
    margin is a certified enclosure [lo, hi] of λ_min.
:func:`homogeneous_positive_on_sphere`
    a homogeneous polynomial f of even degree d is positive definite iff
    min f on the unit sphere is > 0; the sphere is covered by the faces of
    the cube (x_i = 1, the others in [−1, 1]; f(−x) = f(x)) and
    f(x)/‖x‖^d is minimised on each face by a small arb branch and bound →
    ``certified`` / ``failed`` (a rational point with f ≤ 0, checked
    exactly) / ``undecided`` (budget).
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

What the statuses mean here
---------------------------
``exact``
    decided in exact rational arithmetic (fractions): the verified
    statement holds for the data as given.
``certified``
    proved with outward-rounded ball arithmetic (arb): every ball contains
    the true value, and the decisive sign is that of a whole ball.
``failed``
    refuted with a counterexample that is re-checked: a rational vector or
    point (exactly, or with a certified ball when the data are irrational), a
    non-Hurwitz eigenvalue with the failing Hurwitz minor, or a rational
    dual certificate of an infeasible LMI.
``undecided``
    no proof either way: precision, the time budget, a solver status other
    than ``optimal`` or a rounded solver answer that did not verify.
``estimated``
    only inside :class:`Estimate` (a solver value or a sampled minimum); an
    estimate is never the status of a :class:`ConditionResult`.

Floats given as input (a NumPy array, ``0.1``) are taken as the exact binary
rationals they store; pass ``sympy.Rational(1, 10)`` to mean one tenth.

Examples
--------
Assumption 2 of paper 000 at the section 5 example: Ξ = βI + ∫_0^∞ e^{−2ζ}I dζ
= (1 + 1/2)I, D = 2I, so ΞD + DΞᵀ = 6I:

>>> import sympy
>>> Xi, D = sympy.Rational(3, 2) * sympy.eye(3), 2 * sympy.eye(3)
>>> res = matrix_positive_definite(Xi * D + D * Xi.T, name="Xi D + D Xi^T")
>>> res.status, res.margin.exact
(<Status.EXACT: 'exact'>, 6)
"""

from __future__ import annotations

import dataclasses
import heapq
import itertools
import math
import time
from collections.abc import Sequence
from fractions import Fraction

import flint
import numpy as np
import sympy
from flint import arb, fmpq, fmpq_mat

from ..options import Deadline
from ..errors import InputError
from .intervals import enclose, float_down, float_up, lower_fraction, sign_of, to_ball, upper_fraction
from ..report.results import Result
from ..status import Status

__all__ = [
    "ConditionResult", "Enclosure", "Estimate", "best_quadratic_upper_bound", "check_lyapunov_matrix",
    "check_quadratic_bound", "find_lyapunov_matrix", "homogeneous_positive_on_sphere", "lmi_feasible",
    "matrix_positive_definite",
]

#: arb working precisions (bits) tried in turn by the certified matrix path
PRECISIONS = (64, 128, 256, 512)
#: largest size for which λ_min is computed exactly (characteristic polynomial, exact roots)
EXACT_EIGEN_LIMIT = 8


# ---------------------------------------------------------------------------------------------
# result types


def _frac(value) -> Fraction | None:
    if value is None:
        return None
    if isinstance(value, Fraction):
        return value
    if isinstance(value, sympy.Rational):
        return Fraction(int(value.p), int(value.q))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"an enclosure end must be finite, got {value!r}")
        return Fraction(value)
    return Fraction(value)


def _exact_str(value) -> str:
    return str(value) if not isinstance(value, Fraction) or value.denominator != 1 else str(value.numerator)


def _json_vector(v):
    if v is None:
        return None
    if isinstance(v, sympy.MatrixBase):
        return [[_json_scalar(e) for e in row] for row in v.tolist()]
    if isinstance(v, (tuple, list)):
        return [_json_vector(e) if isinstance(e, (tuple, list, sympy.MatrixBase)) else _json_scalar(e) for e in v]
    return _json_scalar(v)


def _json_scalar(e):
    """Integers as JSON integers, other exact rationals as "p/q" strings, the rest as text."""
    if isinstance(e, Fraction):
        return e.numerator if e.denominator == 1 else _exact_str(e)
    if isinstance(e, (bool, int, str)) or e is None:
        return e
    if isinstance(e, float):
        return e if math.isfinite(e) else str(e)
    if isinstance(e, sympy.Integer):
        return int(e)
    return str(e)


@dataclasses.dataclass(frozen=True)
class Enclosure:
    """A certified interval ``lo ≤ value ≤ hi`` with exact rational ends.

    Attributes
    ----------
    lo, hi : Fraction or None
        Proved bounds (``None``: no bound on that side).
    exact : sympy.Expr or None
        The exact value when it is known (a Rational, a radical, a ``CRootOf``).
    point : tuple of Fraction or None
        The rational point at which the attained bound was evaluated: ``hi``
        for a minimum (a Rayleigh quotient, a value of f), ``lo`` for a maximum.

    Examples
    --------
    >>> from fractions import Fraction
    >>> e = Enclosure(Fraction(1, 3), Fraction(1, 2))
    >>> e.contains(Fraction(2, 5)), e.contains(1)
    (True, False)
    >>> e.to_json()["lo_exact"]
    '1/3'
    """

    lo: Fraction | None
    hi: Fraction | None
    exact: object = None
    point: tuple | None = None

    def __post_init__(self):
        object.__setattr__(self, "lo", _frac(self.lo))
        object.__setattr__(self, "hi", _frac(self.hi))
        if self.lo is not None and self.hi is not None and self.lo > self.hi:
            raise ValueError(f"an enclosure needs lo <= hi, got [{self.lo}, {self.hi}]")
        if self.point is not None:
            object.__setattr__(self, "point", tuple(_frac(c) for c in self.point))

    def contains(self, value) -> bool:
        """True if ``value`` (a number) lies in [lo, hi]."""
        v = _frac(value)
        return (self.lo is None or self.lo <= v) and (self.hi is None or v <= self.hi)

    @property
    def width(self) -> Fraction | None:
        return None if self.lo is None or self.hi is None else self.hi - self.lo

    def to_json(self) -> dict:
        """Floats rounded outward (``lo`` down, ``hi`` up) and the exact rationals as strings."""
        return {
            "lo": None if self.lo is None else float_down(self.lo),
            "hi": None if self.hi is None else float_up(self.hi),
            "lo_exact": None if self.lo is None else _exact_str(self.lo),
            "hi_exact": None if self.hi is None else _exact_str(self.hi),
            "exact": None if self.exact is None else str(self.exact),
            "point": _json_vector(self.point),
        }


@dataclasses.dataclass(frozen=True)
class Estimate:
    """A floating-point value from a solver or from sampling: never a proof.

    Attributes
    ----------
    value : float
    method : str
        How it was obtained ("clarabel SDP", "2000 samples + L-BFGS-B").
    point : tuple of float or None
        Where (a minimiser), when it applies.
    status : Status
        Always ``Status.ESTIMATED``; any other status is refused.

    Examples
    --------
    >>> Estimate(0.5, "sampling").status
    <Status.ESTIMATED: 'estimated'>
    >>> Estimate(0.5, "sampling", status=Status.CERTIFIED)
    Traceback (most recent call last):
    ...
    ValueError: an Estimate is never a proof: expected status estimated, got certified; put proved values in a margin
    """

    value: float
    method: str
    point: tuple | None = None
    status: Status = Status.ESTIMATED

    def __post_init__(self):
        if self.status is not Status.ESTIMATED:
            raise ValueError(f"an Estimate is never a proof: expected status estimated, got {self.status}; "
                             "put proved values in a margin")
        object.__setattr__(self, "value", float(self.value))
        if self.point is not None:
            object.__setattr__(self, "point", tuple(float(c) for c in self.point))

    def to_json(self) -> dict:
        return {"value": _json_scalar(self.value), "method": self.method, "point": _json_vector(self.point),
                "status": self.status.value}


@dataclasses.dataclass(frozen=True)
class ConditionResult:
    """The verdict on one positivity condition.

    Attributes
    ----------
    name : str
    status : Status
        ``exact``, ``certified``, ``failed`` or ``undecided`` (see the module
        docstring); never ``estimated``.
    margin : Enclosure or None
        The certified value: an enclosure of λ_min, of min f on the unit
        sphere, of the best constant.  Required when the status is a proof.
    estimate : Estimate or None
        The solver's or the sampler's value (status ``estimated``).
    witness : object
        The counterexample of a ``failed`` result (required then): a tuple of
        Fractions x, a rational point, an eigenvalue, a dual matrix.
    detail : str
        One readable paragraph.
    certificate : object
        What proves a positive result and can be re-checked: a rational
        matrix P, a rational constant c, a rational vector y.
    parts : tuple of ConditionResult
        The sub-conditions the verdict rests on.
    """

    name: str
    status: Status
    margin: Enclosure | None = None
    estimate: Estimate | None = None
    witness: object = None
    detail: str = ""
    certificate: object = None
    parts: tuple = ()

    def __post_init__(self):
        if not isinstance(self.status, Status):
            raise TypeError(f"status must be a Status, got {self.status!r}")
        if self.status in (Status.ESTIMATED, Status.SIMULATED):
            raise ValueError(f"a condition is exact, certified, failed or undecided, got {self.status}; "
                             "put estimates in ConditionResult.estimate")
        if self.margin is not None and not isinstance(self.margin, Enclosure):
            raise TypeError(f"margin must be an Enclosure, got {type(self.margin).__name__}")
        if self.estimate is not None and not isinstance(self.estimate, Estimate):
            raise TypeError(f"estimate must be an Estimate, got {type(self.estimate).__name__}")
        if self.status.is_proof and self.margin is None:
            raise ValueError(f"a {self.status} result needs a certified margin")
        if self.status is Status.FAILED and self.witness is None:
            raise ValueError("a failed result needs a witness (the counterexample)")
        object.__setattr__(self, "parts", tuple(self.parts))

    @property
    def holds(self) -> bool:
        """True when the condition is proved (``exact`` or ``certified``)."""
        return self.status.is_proof

    def to_json(self) -> dict:
        """A JSON-ready dict: integers as integers, other exact rationals as ``"p/q"``.

        The margin is given both exactly and as outward-rounded floats.

        >>> import json
        >>> res = matrix_positive_definite([[2, 1], [1, 2]])
        >>> d = res.to_json(); d["status"], d["margin"]["lo_exact"]
        ('exact', '1')
        >>> isinstance(json.dumps(d), str)
        True
        """
        return {
            "name": self.name,
            "status": self.status.value,
            "margin": None if self.margin is None else self.margin.to_json(),
            "estimate": None if self.estimate is None else self.estimate.to_json(),
            "witness": _json_vector(self.witness),
            "certificate": _json_vector(self.certificate),
            "detail": self.detail,
            "parts": [p.to_json() for p in self.parts],
        }

    def to_result(self, kind: str = "hypothesis") -> Result:
        """This verdict as a :class:`lkverify.report.results.Result` row (value: the margin's lower end, rounded down)."""
        value = None if self.margin is None or self.margin.lo is None else float_down(self.margin.lo)
        return Result(kind, self.name, self.status, value, self.detail)


def _combine(name: str, parts: Sequence[ConditionResult], *, certificate=None) -> ConditionResult:
    """AND of sub-conditions: failed if one failed, undecided if one is, exact only if all are."""
    parts = tuple(parts)
    failed = [p for p in parts if p.status is Status.FAILED]
    if failed:
        return ConditionResult(name, Status.FAILED, margin=failed[0].margin, witness=failed[0].witness,
                               detail=f"{failed[0].name} is false: {failed[0].detail}", parts=parts,
                               certificate=certificate)
    open_ = [p for p in parts if not p.status.is_proof]
    if open_:
        return ConditionResult(name, Status.UNDECIDED, margin=parts[-1].margin,
                               detail=f"{open_[0].name} is undecided: {open_[0].detail}", parts=parts,
                               certificate=certificate)
    status = Status.EXACT if all(p.status is Status.EXACT for p in parts) else Status.CERTIFIED
    detail = " ".join(p.detail for p in parts)
    return ConditionResult(name, status, margin=parts[-1].margin, detail=detail, parts=parts,
                           certificate=certificate)


# ---------------------------------------------------------------------------------------------
# input validation


def _number(v, where: str, problems: list):
    """One matrix entry → a real SymPy number (floats exactly as stored), or a problem noted."""
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, bool) or isinstance(v, str):
        problems.append(f"{where}: expected a real number or SymPy expression, got {type(v).__name__} {v!r}")
        return None
    if isinstance(v, int):
        return sympy.Integer(v)
    if isinstance(v, Fraction):
        return sympy.Rational(v.numerator, v.denominator)
    if isinstance(v, float):
        if not math.isfinite(v):
            problems.append(f"{where}: expected a finite number, got {v!r}")
            return None
        return sympy.Rational(*v.as_integer_ratio())
    if isinstance(v, complex):
        problems.append(f"{where}: expected a real number, got the complex {v!r}")
        return None
    if not isinstance(v, sympy.Basic):
        problems.append(f"{where}: expected a real number or SymPy expression, got {type(v).__name__}")
        return None
    if v.free_symbols:
        problems.append(f"{where}: expected a number, got {v} with the free symbols "
                        f"{sorted(map(str, v.free_symbols))} (substitute values with .subs first)")
        return None
    if v.has(sympy.zoo, sympy.oo, -sympy.oo, sympy.nan):
        problems.append(f"{where}: expected a finite number, got {v}")
        return None
    if v.has(sympy.I) or v.is_extended_real is False:
        problems.append(f"{where}: expected a real number, got {v}")
        return None
    if isinstance(v, sympy.Float):
        return sympy.Rational(v)
    return v


def _as_matrix(M, name: str) -> sympy.Matrix:
    """A square real numeric matrix from SymPy / NumPy / nested lists; every problem reported at once."""
    if isinstance(M, sympy.MatrixBase):
        rows = M.tolist()
    elif isinstance(M, np.ndarray):
        if M.ndim != 2:
            raise InputError(f"{name}: expected a 2-D array, got an array of shape {M.shape}; "
                             "pass a square matrix")
        rows = M.tolist()
    elif isinstance(M, (list, tuple)) and all(isinstance(r, (list, tuple, np.ndarray)) for r in M):
        rows = [list(r) for r in M]
    else:
        raise InputError(f"{name}: expected a square matrix (SymPy Matrix, 2-D NumPy array or list of rows), "
                         f"got {type(M).__name__}; pass e.g. [[2, 1], [1, 2]]")
    n = len(rows)
    if n == 0 or any(len(r) != n for r in rows):
        raise InputError(f"{name}: expected a nonempty square matrix, got row lengths {[len(r) for r in rows]}; "
                         "pass n rows of n entries")
    problems: list[str] = []
    out = [[_number(v, f"{name}[{i},{j}]", problems) for j, v in enumerate(r)] for i, r in enumerate(rows)]
    if problems:
        raise InputError("; ".join(problems))
    return sympy.Matrix(out)


def _is_rational(M: sympy.Matrix) -> bool:
    return all(e.is_Rational for e in M)


def _fractions(M: sympy.Matrix) -> list[list[Fraction]]:
    return [[Fraction(int(e.p), int(e.q)) for e in row] for row in M.tolist()]


def _symmetric_part(M: sympy.Matrix, name: str, symmetrize: bool) -> tuple[sympy.Matrix, str]:
    n = M.rows
    bad = []
    for i in range(n):
        for j in range(i + 1, n):
            a, b = M[i, j], M[j, i]
            if a == b:
                continue
            d = a - b
            if d.is_Rational or sympy.simplify(d) != 0:
                bad.append((i, j))
    if not bad:
        return M, ""
    if symmetrize:
        return (M + M.T) / 2, f"{name} is not symmetric; tested its symmetric part ({name} + {name}ᵀ)/2 " \
                              f"(xᵀ{name}x is the same form). "
    i, j = bad[0]
    raise InputError(f"{name}: expected a symmetric matrix, got {name}[{i},{j}] = {M[i, j]} but "
                     f"{name}[{j},{i}] = {M[j, i]} ({len(bad)} asymmetric pair(s)); pass symmetrize=True to "
                     f"test the symmetric part ({name} + {name}ᵀ)/2, which has the same quadratic form")


# ---------------------------------------------------------------------------------------------
# exact linear algebra in fractions


def _quad(M, x) -> Fraction:
    """xᵀMx exactly."""
    n = len(x)
    return sum((x[i] * M[i][j] * x[j] for i in range(n) for j in range(n) if x[i] and x[j]), Fraction(0))


def _integer_vector(x) -> tuple:
    den = math.lcm(*(c.denominator for c in x))
    ints = [int(c * den) for c in x]
    g = math.gcd(*ints) or 1
    return tuple(Fraction(v // g) for v in ints)


@dataclasses.dataclass(frozen=True)
class _LDL:
    kind: str               # "pd", "psd" (singular) or "indefinite"
    pivots: tuple
    witness: tuple | None   # x with xᵀMx = value ≤ 0 (None for "pd")
    value: Fraction | None


def _exact_ldl(M: list[list[Fraction]]) -> _LDL:
    """Symmetric Gaussian elimination with diagonal pivoting, in fractions.

    Invariant: the current Schur complement is S[i][j] = v_iᵀ M v_j, with v_j
    the original-coordinate vector of the remaining index j; so a nonpositive
    S-entry pattern maps back to an exact witness x.
    """
    n = len(M)
    S = [row[:] for row in M]
    V = [[Fraction(int(i == j)) for i in range(n)] for j in range(n)]
    remaining = list(range(n))
    pivots = []
    while remaining:
        p = max(remaining, key=lambda i: S[i][i])
        d = S[p][p]
        if d <= 0:
            break
        pivots.append(d)
        remaining.remove(p)
        for j in remaining:
            f = S[p][j] / d
            if f:
                V[j] = [a - f * b for a, b in zip(V[j], V[p])]
        for i in remaining:
            sip = S[i][p] / d
            if sip:
                for j in remaining:
                    S[i][j] -= sip * S[p][j]
    if not remaining:
        return _LDL("pd", tuple(pivots), None, None)
    neg = [i for i in remaining if S[i][i] < 0]
    if neg:
        q = min(neg, key=lambda i: S[i][i])
        x = V[q]
    else:
        off = [(i, j) for i in remaining for j in remaining if i < j and S[i][j] != 0]
        if off:
            i, j = off[0]
            s = 1 if S[i][j] > 0 else -1
            x = [a - s * b for a, b in zip(V[i], V[j])]
        else:
            x = V[remaining[0]]
    x = _integer_vector(x)
    value = _quad(M, x)
    if value > 0:  # cannot happen: the invariant guarantees value ≤ 0
        raise RuntimeError("internal error: the LDLᵀ witness has xᵀMx > 0")
    x, value = _simplify_witness(M, x, value)
    return _LDL("psd" if value == 0 and not neg and not off else "indefinite", tuple(pivots), x, value)


def _simplify_witness(M, x, value):
    """A witness with small integers along the same direction, if one still has xᵀMx ≤ value's sign."""
    for den in (1, 2, 3, 4, 6, 8, 10, 12, 16, 100, 1000):
        y = _rational_vector(x, den)
        if y == x:
            break
        v = _quad(M, y)
        if (v < 0) if value < 0 else (v <= 0):
            return y, v
    return x, value


def _exact_lambda_min(M: sympy.Matrix) -> Enclosure:
    """λ_min exactly: the smallest real root of the characteristic polynomial (exact SymPy root)."""
    lam = sympy.Dummy("lambda")
    cp = fmpq_mat([[fmpq(int(e.p), int(e.q)) for e in row] for row in M.tolist()]).charpoly()
    poly = sympy.Poly([sympy.Rational(int(c.p), int(c.q)) for c in reversed(cp.coeffs())], lam)
    root = poly.real_roots()[0]
    return _enclose_exact(root)


def _enclose_exact(root) -> Enclosure:
    if root.is_Rational:
        return Enclosure(root, root, exact=root)
    if isinstance(root, sympy.CRootOf):
        iv = root._get_interval()
        a, b = sympy.Rational(iv.a), sympy.Rational(iv.b)
        width = max(abs(a), abs(b)) * sympy.Rational(1, 2**64)
        a, b = root.poly.refine_root(a, b, eps=width)
        return Enclosure(_frac(sympy.Rational(a)), _frac(sympy.Rational(b)), exact=root)
    ball = enclose(root, prec=128)
    return Enclosure(lower_fraction(ball), upper_fraction(ball), exact=root)


# ---------------------------------------------------------------------------------------------
# arb helpers


def _ball_pow(r: arb, k: int) -> arb:
    out = arb(1)
    for _ in range(abs(k)):
        out = out * r
    return out if k >= 0 else 1 / out


def _pos_pow(r: arb, k: int) -> arb:
    """r**k for a ball of positive numbers, from its endpoints (r ↦ r**k is increasing there)."""
    lo, hi = r.lower(), r.upper()
    if not lo > 0:
        raise ValueError(f"internal error: _pos_pow needs a positive ball, got {r}")
    return arb.union(_ball_pow(lo, k), _ball_pow(hi, k))


def _arb_ldl_pd(S: list[list[arb]]) -> tuple[bool, int, str]:
    """LDLᵀ in balls, no pivoting: (all pivots certified > 0, index of the first that is not, "neg"/"unknown")."""
    n = len(S)
    S = [row[:] for row in S]
    for k in range(n):
        d = S[k][k]
        if not d > 0:
            return False, k, ("neg" if d <= 0 else "unknown")
        for i in range(k + 1, n):
            f = S[i][k] / d
            for j in range(k + 1, i + 1):
                S[i][j] = S[i][j] - f * S[j][k]
                S[j][i] = S[i][j]
    return True, n, ""


def _shifted(Ma: list[list[arb]], lam: Fraction) -> list[list[arb]]:
    ab = to_ball(lam)
    return [[v - ab if i == j else v for j, v in enumerate(row)] for i, row in enumerate(Ma)]


def _arb_quad(Ma, x) -> arb:
    xs = [to_ball(c) for c in x]
    n = len(x)
    return sum((xs[i] * Ma[i][j] * xs[j] for i in range(n) for j in range(n) if x[i] and x[j]), arb(0))


def _to_fraction(c) -> Fraction:
    if isinstance(c, (Fraction, int)):
        return Fraction(c)
    if isinstance(c, (float, np.floating)):
        return Fraction(float(c))
    sign, man, exp, _ = c._mpf_  # an mpmath mpf (man_exp drops the sign)
    if not man:
        return Fraction(0)
    return (-1) ** sign * Fraction(int(man)) * Fraction(2) ** int(exp)


def _rational_vector(v, den: int) -> tuple:
    """A nonzero integer vector along v (floats or mpmath numbers), entries rounded at relative 1/den."""
    q = [_to_fraction(c) for c in v]
    scale = max(abs(c) for c in q)
    if scale == 0:
        return tuple(Fraction(int(i == 0)) for i in range(len(q)))
    return _integer_vector([(c / scale).limit_denominator(den) for c in q])


def _mp_eigen(mid: list[list[Fraction]], prec: int):
    """(eigenvalue, eigenvector) estimates of the smallest eigenvalue at ``prec`` bits (mpmath)."""
    import mpmath
    with mpmath.workprec(max(prec, 53)):
        A = mpmath.matrix([[mpmath.mpf(v.numerator) / v.denominator for v in row] for row in mid])
        E, Q = mpmath.eigsy(A)
        k = min(range(len(E)), key=lambda i: E[i])
        return E[k], [Q[i, k] for i in range(len(E))]


def _arb_lambda_min(Ma: list[list[arb]], x_hi, *, steps: int = 120) -> Enclosure:
    """Certified enclosure of λ_min.

    Lower end: the largest λ found (bisection) for which M − λI passes the
    ball LDLᵀ, so λ_min > λ; start: Gershgorin.  Upper end: the Rayleigh
    quotient xᵀMx/xᵀx at the rational vector ``x_hi``, rounded up.
    """
    n = len(Ma)
    # Gershgorin: λ_min ≥ min_i (a_ii − Σ_{j≠i} |a_ij|)
    g = min(Ma[i][i] - sum((abs(Ma[i][j]) for j in range(n) if j != i), arb(0)) for i in range(n))
    lo = lower_fraction(g) if g.is_finite() else None
    xs = x_hi
    xx = sum((c * c for c in xs), Fraction(0))
    ray = _arb_quad(Ma, xs) / to_ball(xx)
    hi = upper_fraction(ray)
    if lo is None or hi is None:
        return Enclosure(lo, hi, point=xs)
    if lo > hi:  # cannot happen for a true enclosure; guard against a bug
        raise RuntimeError("internal error: Gershgorin bound above a Rayleigh quotient")
    top = hi
    scale = max(abs(lo), abs(hi), Fraction(1, 2**200))
    ref = abs(hi) if hi != 0 else scale
    tol = max(ref / 2**45, scale / 2 ** max(flint.ctx.prec - 8, 20))
    # jump near the Rayleigh value first (λ_min is usually very close to it)
    for rel in (Fraction(1, 2**40), Fraction(1, 2**20), Fraction(1, 2**8)):
        cand = hi - rel * ref
        if cand > lo and _arb_ldl_pd(_shifted(Ma, cand))[0]:
            lo = cand
            break
    for _ in range(steps):
        if top - lo <= tol:
            break
        mid = (lo + top) / 2
        if not lo < mid < top:
            break
        if _arb_ldl_pd(_shifted(Ma, mid))[0]:
            lo = mid
        else:
            top = mid
    return Enclosure(lo, hi, point=xs)


# ---------------------------------------------------------------------------------------------
# 1. matrices


def matrix_positive_definite(M, *, name: str = "M", symmetrize: bool = False, semidefinite: bool = False,
                             method: str = "auto") -> ConditionResult:
    """Decide M ≻ 0 (or M ⪰ 0) exactly for rational M, with arb balls otherwise.

    Parameters
    ----------
    M : sympy.Matrix, nested list or 2-D NumPy array
        A real symmetric matrix of numbers (rationals, radicals, ``pi``, …).
        Floats are taken as the exact binary rationals they store.
    name : str
        Used in messages and as the result's name.
    symmetrize : bool
        A non-symmetric M is refused (:class:`InputError`) unless this is
        True; then (M + Mᵀ)/2, which has the same quadratic form, is tested
        and the detail says so.
    semidefinite : bool
        Decide M ⪰ 0 instead of M ≻ 0.  Exact for rational M; with irrational
        entries only a positive definite M is certified.
    method : {"auto", "exact", "arb"}
        ``auto``: exact for rational entries, arb otherwise; ``exact`` refuses
        irrational entries; ``arb`` uses the ball path even for rational
        entries (a reference path; the status is then ``certified``).

    Returns
    -------
    ConditionResult
        ``exact``: decided in fractions by an LDLᵀ (all pivots > 0 ⇔ PD).
        ``certified``: every pivot of a ball LDLᵀ has a positive lower end.
        ``failed``: ``witness`` is an integer vector x with xᵀMx ≤ 0 (< 0 for
        ``semidefinite``), checked exactly (or by a certified negative ball).
        ``undecided``: the ball pivots straddle 0 at every precision tried.
        ``margin`` encloses λ_min: exact roots of the characteristic
        polynomial for rational M up to size 8; otherwise the lower end is
        the largest λ for which M − λI passed the ball LDLᵀ (bisection) and
        the upper end a Rayleigh quotient at the rational vector ``margin.point``.

    Raises
    ------
    InputError
        Not square, not numeric, complex, or not symmetric without ``symmetrize``.

    Examples
    --------
    >>> import sympy
    >>> matrix_positive_definite(6 * sympy.eye(3)).margin.exact
    6
    >>> res = matrix_positive_definite(sympy.diag(1, -1, 1))
    >>> res.status, res.witness
    (<Status.FAILED: 'failed'>, (Fraction(0, 1), Fraction(1, 1), Fraction(0, 1)))
    >>> s2 = sympy.sqrt(2)
    >>> res = matrix_positive_definite([[2, s2], [s2, 3]])
    >>> res.status, res.margin.contains(1)        # eigenvalues 1 and 4
    (<Status.CERTIFIED: 'certified'>, True)
    """
    if method not in ("auto", "exact", "arb"):
        raise InputError(f"method: expected 'auto', 'exact' or 'arb', got {method!r}")
    A = _as_matrix(M, name)
    A, note = _symmetric_part(A, name, symmetrize)
    what = f"{name} ⪰ 0" if semidefinite else f"{name} ≻ 0"
    rational = _is_rational(A)
    if method == "exact" and not rational:
        bad = next(e for e in A if not e.is_Rational)
        raise InputError(f"{name}: method='exact' expects rational entries, got {bad}; use method='auto' "
                         "for a certified (arb) decision")
    if rational and method != "arb":
        return _exact_pd(A, name, what, note, semidefinite)
    return _arb_pd(A, name, what, note, semidefinite)


def _exact_pd(A: sympy.Matrix, name: str, what: str, note: str, semidefinite: bool) -> ConditionResult:
    Mq = _fractions(A)
    ldl = _exact_ldl(Mq)
    n = A.rows
    if n <= EXACT_EIGEN_LIMIT:
        margin = _exact_lambda_min(A)
    else:
        with flint.ctx.workprec(128):
            Ma = [[to_ball(v) for v in row] for row in Mq]
            x = ldl.witness if ldl.witness is not None else _rational_vector(
                _mp_eigen(Mq, 128)[1], 2**60)
            margin = _arb_lambda_min(Ma, x)
    holds = ldl.kind == "pd" or (semidefinite and ldl.kind == "psd")
    # cross-check the decision against the eigenvalue enclosure (two independent exact paths)
    if (holds and margin.hi is not None and margin.hi < 0) or (not holds and margin.lo is not None and margin.lo > 0):
        raise RuntimeError(f"internal error: LDLᵀ ({ldl.kind}) disagrees with λ_min ∈ [{margin.lo}, {margin.hi}]")
    lam = _describe_margin(margin)
    if holds:
        piv = ", ".join(_short(p) for p in ldl.pivots[:6]) + (", …" if len(ldl.pivots) > 6 else "")
        piv = piv or "(none)"
        detail = (f"{note}{what}: exact LDLᵀ in fractions, pivots {piv}"
                  + (" (all > 0)" if ldl.kind == "pd" else f" and a zero Schur complement (rank {len(ldl.pivots)})")
                  + f"; λ_min {lam}.")
        return ConditionResult(what, Status.EXACT, margin=margin, detail=detail)
    x = ldl.witness
    value = _quad(Mq, x)  # the refutation, rechecked exactly on the input matrix before it is reported
    if value > 0 or (semidefinite and value == 0) or not any(x):
        raise RuntimeError(f"internal error: the witness x = {x} gives xᵀ{_paren(name)}x = {value}, which does "
                           f"not refute {what}")
    detail = (f"{note}{what} is false: x = ({', '.join(map(str, x))}) gives xᵀ{_paren(name)}x = {_short(value)}"
              f"{' < 0' if value < 0 else ''} (exact); λ_min {lam}.")
    return ConditionResult(what, Status.FAILED, margin=margin, witness=x, detail=detail)


def _paren(name: str) -> str:
    return f"({name})" if any(c in name for c in " +−-*") else name


def _short(v, n: int = 40) -> str:
    """A number for a message: exact when short, else a float."""
    text = str(v)
    if len(text) <= n:
        return text
    try:
        return f"≈{float(v):.12g}"
    except (TypeError, ValueError):
        return text[: n - 1] + "…"


def _describe_margin(m: Enclosure) -> str:
    if m.exact is not None and m.lo == m.hi:
        return f"= {m.exact}"
    if m.exact is not None:
        text = str(m.exact)
        if len(text) > 40:  # a long radical: the enclosure says more
            return f"∈ [{float_down(m.lo):.12g}, {float_up(m.hi):.12g}] (an exact algebraic number)"
        return f"= {text} ∈ [{float_down(m.lo):.12g}, {float_up(m.hi):.12g}]"
    lo = "−∞" if m.lo is None else f"{float_down(m.lo):.12g}"
    hi = "+∞" if m.hi is None else f"{float_up(m.hi):.12g}"
    return f"∈ [{lo}, {hi}] (certified)"


def _arb_pd(A: sympy.Matrix, name: str, what: str, note: str, semidefinite: bool) -> ConditionResult:
    last = None
    for prec in PRECISIONS:
        with flint.ctx.workprec(prec):
            Ma = [[enclose(e, prec=None) for e in row] for row in A.tolist()]
            if not all(v.is_finite() for row in Ma for v in row):
                raise InputError(f"{name}: an entry has no finite enclosure (got {A}); pass finite real entries")
            mid = [[lower_fraction(v.mid()) for v in row] for row in Ma]
            lam_est, vec = _mp_eigen(mid, prec)
            x = _rational_vector(vec, 2 ** min(prec // 2, 200))
            pd, k, how = _arb_ldl_pd(Ma)
            if not pd:  # prefer a witness with small integers
                for den in (1, 2, 4, 10, 100, 10**4, 10**6):
                    y = _rational_vector(vec, den)
                    if _arb_quad(Ma, y) < 0:
                        x = y
                        break
            q = _arb_quad(Ma, x)
            if pd:
                margin = _arb_lambda_min(Ma, x)
                margin = Enclosure(max(margin.lo, Fraction(0)), margin.hi, point=margin.point)
                detail = (f"{note}{what}: LDLᵀ in arb balls at {prec} bits, every pivot has a positive lower "
                          f"end; λ_min {_describe_margin(margin)}.")
                return ConditionResult(what, Status.CERTIFIED, margin=margin, detail=detail)
            negative = q < 0 if semidefinite else q <= 0
            if not negative:  # try the LDLᵀ direction at the failing pivot
                y = _ldl_direction([[float(v) for v in row] for row in mid], k)
                if y is not None:
                    qy = _arb_quad(Ma, y)
                    if (qy < 0 if semidefinite else qy <= 0):
                        x, q, negative = y, qy, True
            if negative:
                margin = _arb_lambda_min(Ma, x)
                detail = (f"{note}{what} is false: x = ({', '.join(map(str, x))}) gives xᵀ{_paren(name)}x ∈ "
                          f"[{float_down(q):.6g}, {float_up(q):.6g}] < 0 (certified, arb at {prec} bits); "
                          f"λ_min {_describe_margin(margin)}.")
                return ConditionResult(what, Status.FAILED, margin=margin, witness=x, detail=detail)
            last = (prec, Ma, x, lam_est)
    prec, Ma, x, lam_est = last
    with flint.ctx.workprec(prec):
        margin = _arb_lambda_min(Ma, x)
    detail = (f"{note}{what} undecided: at {PRECISIONS[-1]} bits a ball pivot still contains 0 and no rational "
              f"vector with a certified negative xᵀ{name}x was found; λ_min ≈ {float(lam_est):.3g}, "
              f"{_describe_margin(margin)}.  λ_min is too close to 0 for ball arithmetic (singular with "
              "irrational entries?); pass exact rational entries to decide it exactly.")
    return ConditionResult(what, Status.UNDECIDED, margin=margin, detail=detail)


def _ldl_direction(mid: list[list[float]], k: int):
    """x = L⁻ᵀ e_k from a float LDLᵀ of the leading (k+1)×(k+1) block: xᵀMx = d_k (to rounding)."""
    try:
        B = np.array(mid, dtype=float)[: k + 1, : k + 1]
        n = k + 1
        L = np.eye(n)
        S = B.copy()
        for j in range(k):
            L[j + 1:, j] = S[j + 1:, j] / S[j, j]
            S[j + 1:, j + 1:] -= np.outer(L[j + 1:, j], S[j, j + 1:])
        e = np.zeros(n)
        e[k] = 1.0
        y = np.linalg.solve(L.T, e)
        if not np.all(np.isfinite(y)):
            return None
        full = np.zeros(len(mid))
        full[:n] = y
        return _rational_vector(full, 2**30)
    except (np.linalg.LinAlgError, ZeroDivisionError, FloatingPointError):
        return None


# ---------------------------------------------------------------------------------------------
# 2. homogeneous forms on the unit sphere


def _pow_table(Y: arb, kmax: int) -> list[arb]:
    """Enclosures of Y^0 … Y^kmax that are tight for even powers of a ball containing 0."""
    out = [arb(1)]
    if Y.rad() == 0:
        for _ in range(kmax):
            out.append(out[-1] * Y)
        return out
    lo, hi = Y.lower(), Y.upper()
    plo, phi = arb(1), arb(1)
    straddle = not (lo >= 0 or hi <= 0)
    for k in range(1, kmax + 1):
        plo, phi = plo * lo, phi * hi
        if k % 2 == 0 and straddle:
            out.append(arb.union(arb(0), plo if abs(lo) > abs(hi) else phi))
        else:
            out.append(arb.union(plo, phi))
    return out


class _ArbPoly:
    """Σ c·Π y_j^k_j with arb coefficients, evaluated on tables of powers."""

    __slots__ = ("terms",)

    def __init__(self, poly: sympy.Poly):
        self.terms = [(enclose(c, prec=None), m) for m, c in poly.terms() if c != 0]

    def __call__(self, powers: list[list[arb]]) -> arb:
        total = arb(0)
        for c, m in self.terms:
            t = c
            for j, k in enumerate(m):
                if k:
                    t = t * powers[j][k]
            total = total + t
        return total


class _Face:
    """The face x_i = 1 of the cube: g(y) = f(x)/‖x‖^d, its natural and centred (mean-value) enclosures."""

    def __init__(self, poly: sympy.Poly, variables, i: int, d: int):
        self.i, self.d, self.h = i, d, d // 2
        self.ys = [v for j, v in enumerate(variables) if j != i]
        fface = sympy.Poly(poly.as_expr().subs(variables[i], 1), *self.ys)
        r = sympy.Poly(1 + sum(y**2 for y in self.ys), *self.ys)
        self.F = _ArbPoly(fface)
        # ∂g/∂y_j = (∂_j F · r − d·y_j·F) / r^(h+1); the numerator is expanded exactly so that
        # cancellations (g constant on the sphere, e.g. f = ‖x‖²) are not lost to interval dependency
        self.dN = [_ArbPoly(fface.diff(y) * r - d * sympy.Poly(y, *self.ys) * fface) for y in self.ys]

    def bounds(self, lo: tuple, hi: tuple) -> tuple[float, float]:
        """(lower bound of g on the box, certified upper bound of g at the box centre)."""
        m = len(lo)
        lo, hi = [float(a) for a in lo], [float(b) for b in hi]   # Python floats: arb takes them exactly
        mids = [(a + b) / 2 for a, b in zip(lo, hi)]
        rads = [math.nextafter(max(b - m_, m_ - a), math.inf) if b > a else 0.0
                for a, b, m_ in zip(lo, hi, mids)]                    # rounded up: the ball covers [a, b]
        Y = [arb(c, r) for c, r in zip(mids, rads)]
        C = [arb(c) for c in mids]
        PY = [_pow_table(y, self.d + 1) for y in Y]   # the gradient numerators have degree d + 1
        PC = [_pow_table(c, self.d) for c in C]
        RY = arb(1) + sum((p[2] for p in PY), arb(0))
        RC = arb(1) + sum((p[2] for p in PC), arb(0))
        FY, FC = self.F(PY), self.F(PC)
        RYh = _pos_pow(RY, self.h)          # from the endpoints: a wide ball times itself may straddle 0
        natural = FY / RYh
        gc = FC / _ball_pow(RC, self.h)
        centred = gc
        RYh1 = _pos_pow(RY, self.h + 1)
        for j in range(m):
            grad = self.dN[j](PY) / RYh1
            centred = centred + grad * arb(0, rads[j])
        return max(float_down(natural), float_down(centred)), float_up(gc)


def _homogeneity_error(poly: sympy.Poly, name: str) -> str:
    terms = [f"{sympy.Mul(c, *(v**k for v, k in zip(poly.gens, m)))}: degree {sum(m)}"
             for m, c in poly.terms()]
    return (f"{name}: expected a homogeneous polynomial (every term of the same degree), got terms of degrees "
            + "; ".join(terms) + "; split f into its homogeneous parts or fix the exponents")


def homogeneous_positive_on_sphere(f, variables, *, degree: int | None = None, name: str = "f",
                                   budget_seconds: float = 10.0, max_boxes: int = 200_000, rtol: float = 1e-3,
                                   samples: int = 2000, seed: int = 0, prec: int = 64) -> ConditionResult:
    """Prove a homogeneous polynomial f positive definite: a certified lower bound of min f on ‖x‖ = 1.

    For f homogeneous of degree d, f(x) = ‖x‖^d f(x/‖x‖), so f is positive
    definite iff m = min_{‖x‖=1} f > 0.  The sphere is covered by the faces
    x_i = 1 (the others in [−1, 1]) of the cube; since d is even,
    f(−x) = f(x) covers the faces x_i = −1.  On each face
    g(y) = f(x)/‖x‖^d takes exactly the values of f on the matching part of
    the sphere, and a best-first arb branch and bound encloses its minimum:
    on every box the lower bound is the better of the natural interval
    extension and the mean-value (centred) form with the arb gradient.

    Parameters
    ----------
    f : sympy.Expr
        A homogeneous polynomial in ``variables`` with numeric coefficients
        (rationals, radicals, ``pi`` …).
    variables : sequence of sympy.Symbol
    degree : int, optional
        The expected degree; checked.
    name : str
    budget_seconds, max_boxes : float, int
        The branch and bound stops at either; with a positive lower bound the
        result is still ``certified`` (with a wider margin).
    rtol : float
        Stop when the certified gap hi − lo ≤ rtol·|hi|.
    samples, seed : int
        The float estimate: random points on the sphere, refined by L-BFGS-B.
    prec : int
        arb precision in bits.

    Returns
    -------
    ConditionResult
        ``certified``: ``margin.lo`` > 0 is a proved lower bound of min f on
        the sphere; ``margin.hi`` is f at the rational point ``margin.point``
        divided by its norm^d (exact for rational coefficients).
        ``failed``: ``witness`` is a rational point with f ≤ 0 (checked
        exactly; odd degrees fail at once since f(−x) = −f(x)).
        ``undecided``: the budget ran out with a lower bound ≤ 0.
        ``estimate``: the sampled/optimised minimum and its minimiser.

    Raises
    ------
    InputError
        Not a polynomial in ``variables``, free symbols in the coefficients,
        not homogeneous (the message lists each term's degree), wrong degree.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> res = homogeneous_positive_on_sphere(x**4 + y**4, [x, y])
    >>> res.status, res.margin.lo <= sympy.Rational(1, 2) <= res.margin.hi     # min is 1/2 at |x| = |y|
    (<Status.CERTIFIED: 'certified'>, True)
    >>> homogeneous_positive_on_sphere(x**4 - x**2*y**2 / 4 - y**4, [x, y]).status
    <Status.FAILED: 'failed'>
    """
    start = time.monotonic()
    variables = tuple(variables)
    if (not variables or not all(isinstance(v, sympy.Symbol) for v in variables)
            or len(set(variables)) != len(variables)):
        raise InputError(f"{name}: expected distinct SymPy Symbols as variables, got {variables!r}; "
                         "pass e.g. sympy.symbols('x y z')")
    try:
        poly = sympy.Poly(sympy.sympify(f), *variables)
    except (sympy.PolynomialError, sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{name}: expected a polynomial in {', '.join(map(str, variables))}, got {f} ({exc}); "
                         "expand powers with integer exponents") from None
    extra = sorted(map(str, poly.free_symbols - set(variables)))
    if extra:
        raise InputError(f"{name}: expected numeric coefficients, got the free symbols {extra}; substitute values "
                         "with .subs or add them to variables")
    if not all(c.is_real is not False and not c.has(sympy.I) for c in poly.coeffs()):
        raise InputError(f"{name}: expected real coefficients, got {poly.coeffs()}")
    degrees = {sum(m) for m in poly.monoms()} if not poly.is_zero else set()
    if len(degrees) > 1:
        raise InputError(_homogeneity_error(poly, name))
    n = len(variables)
    if poly.is_zero:
        x = tuple(Fraction(int(j == 0)) for j in range(n))
        return ConditionResult(name, Status.FAILED, margin=Enclosure(0, 0, exact=sympy.Integer(0)), witness=x,
                               detail=f"{name} ≡ 0, so {name}(e_1) = 0: not positive definite.")
    d = degrees.pop()
    if degree is not None and degree != d:
        raise InputError(f"{name}: expected degree {degree}, got degree {d}; pass degree={d} or fix {name}")
    if d == 0:
        raise InputError(f"{name}: expected a form of degree ≥ 1, got the constant {poly.as_expr()}; a nonzero "
                         "constant is not positive definite (it does not vanish at 0)")
    rational = all(c.is_Rational for c in poly.coeffs())
    qterms = [(Fraction(int(c.p), int(c.q)) if rational else c, m) for m, c in poly.terms()]

    def value_sign(x: tuple) -> tuple[object, int | None]:
        """f(x) and its proved sign (exact for rational coefficients, arb balls otherwise; None if unknown)."""
        if rational:
            v = sum((c * math.prod((xi**k for xi, k in zip(x, m)), start=Fraction(1)) for c, m in qterms),
                    Fraction(0))
            return v, (v > 0) - (v < 0)
        v = poly.as_expr().xreplace({var: sympy.Rational(c.numerator, c.denominator)
                                     for var, c in zip(variables, x)})
        if v == 0:
            return v, 0
        return v, sign_of(v, max_prec=PRECISIONS[-1]).sign

    def g_upper(x: tuple) -> Fraction | None:
        """A proved upper bound of f(x/‖x‖) at the rational point x (exact for rational coefficients)."""
        nrm = sum((c * c for c in x), Fraction(0)) ** (d // 2)
        v, _ = value_sign(x)
        if rational:
            return v / nrm
        with flint.ctx.workprec(prec):
            b = enclose(v, prec=None) / to_ball(nrm)
        return upper_fraction(b)

    def failed(x: tuple, how: str) -> ConditionResult:
        v, sign = value_sign(x)
        if sign is None or sign > 0:
            raise RuntimeError(f"internal error: a counterexample with {name}(x) = {v} not proved ≤ 0")
        nrm2 = sum((c * c for c in x), Fraction(0))
        hi = v / nrm2 ** (d // 2) if rational and d % 2 == 0 else None
        margin = Enclosure(None, hi, point=x) if hi is not None else None
        detail = (f"{name} is not positive definite: at the rational point x = ({', '.join(map(str, x))}) "
                  f"{name}(x) = {v}{' < 0' if v != 0 else ''} ({'exact' if rational else 'certified'}); {how}.")
        return ConditionResult(name, Status.FAILED, margin=margin, estimate=estimate, witness=x, detail=detail)

    estimate = None
    if d % 2 == 1:
        for pt in itertools.product(range(-1, d + 1), repeat=n):
            if any(pt):
                x = tuple(Fraction(c) for c in pt)
                v, s = value_sign(x)
                if s:
                    return failed(x if s < 0 else tuple(-c for c in x), f"odd degree {d}: {name}(−x) = −{name}(x)")
        raise RuntimeError("internal error: a nonzero odd form vanished on a grid finer than its degree")

    if n == 1:
        x = (Fraction(1),)
        v, s = value_sign(x)
        if s is not None and s <= 0:
            return failed(x, "the unit sphere in R¹ is {±1}")
        if s is None:
            return ConditionResult(name, Status.UNDECIDED, detail=f"the sign of {name}(1) = {v} is not decided")
        if rational:
            margin = Enclosure(v, v, exact=sympy.Rational(v.numerator, v.denominator), point=x)
        else:
            with flint.ctx.workprec(prec):
                ball = enclose(v, prec=None)
            margin = Enclosure(lower_fraction(ball), upper_fraction(ball), exact=v, point=x)
        return ConditionResult(name, Status.EXACT if rational else Status.CERTIFIED, margin=margin,
                               detail=f"one variable: {name}(±1) = {v} > 0.")

    # --- the float estimate: samples on the sphere, then L-BFGS-B on the face of the best sample
    import scipy.optimize
    fnum = sympy.lambdify(variables, poly.as_expr(), "numpy")
    rng = np.random.default_rng(seed)
    pts = rng.standard_normal((max(samples, 1), n))
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)
    vals = np.broadcast_to(np.asarray(fnum(*pts.T), dtype=float), (len(pts),))
    b = int(np.argmin(vals))
    face = int(np.argmax(np.abs(pts[b])))
    y0 = np.delete(pts[b] / pts[b][face], face)

    def gnum(y):
        xx = np.insert(np.asarray(y, dtype=float), face, 1.0)
        return float(fnum(*xx)) / float(np.dot(xx, xx)) ** (d / 2)

    opt = scipy.optimize.minimize(gnum, y0, method="L-BFGS-B", bounds=[(-1.0, 1.0)] * (n - 1))
    ystar = opt.x if opt.fun <= vals[b] else y0
    xstar = np.insert(np.asarray(ystar, dtype=float), face, 1.0)
    estimate = Estimate(min(float(opt.fun), float(vals[b])), f"min of {len(pts)} random points on the sphere, "
                        "refined by L-BFGS-B on a cube face", point=tuple(xstar / np.linalg.norm(xstar)))

    # --- rational candidates near the estimated minimiser (exact checks)
    best_hi, best_pt = None, None
    for den in (1, 2, 4, 10, 100, 10**4, 10**6, 10**9):
        yq = [min(max(Fraction(float(c)).limit_denominator(den), Fraction(-1)), Fraction(1)) for c in ystar]
        x = tuple(yq[:face]) + (Fraction(1),) + tuple(yq[face:])
        v, s = value_sign(x)
        if s is not None and s <= 0:
            return failed(x, "found near the estimated minimiser")
        u = g_upper(x)
        if u is not None and (best_hi is None or u < best_hi):
            best_hi, best_pt = u, x

    # --- branch and bound over the faces x_i = 1
    deadline = Deadline(budget_seconds)
    boxes = 0
    with flint.ctx.workprec(prec):
        faces = [_Face(poly, variables, i, d) for i in range(n)]
        heap = []
        counter = itertools.count()
        m = n - 1
        for fc in faces:
            lo, hi = (-1.0,) * m, (1.0,) * m
            lb, _ = fc.bounds(lo, hi)
            heapq.heappush(heap, (lb, next(counter), fc.i, lo, hi))
            boxes += 1
        stop = ""
        while True:
            lb = heap[0][0]
            if lb > 0 and best_hi is not None and best_hi - Fraction(lb) <= Fraction(rtol) * abs(best_hi):
                break
            if boxes >= max_boxes:
                stop = f"the box limit ({max_boxes})"
                break
            if deadline.remaining is not None and deadline.remaining <= 0:
                stop = f"the time budget ({budget_seconds:g} s)"
                break
            lb, _, i, lo, hi = heapq.heappop(heap)
            j = max(range(m), key=lambda k: hi[k] - lo[k])
            cut = (lo[j] + hi[j]) / 2
            for a, b_ in ((lo[j], cut), (cut, hi[j])):
                clo, chi = lo[:j] + (a,) + lo[j + 1:], hi[:j] + (b_,) + hi[j + 1:]
                clb, cub = faces[i].bounds(clo, chi)
                boxes += 1
                heapq.heappush(heap, (clb, next(counter), i, clo, chi))
                if best_hi is None or cub < best_hi:
                    y = [Fraction((p + q) / 2) for p, q in zip(clo, chi)]
                    x = tuple(y[:i]) + (Fraction(1),) + tuple(y[i:])
                    if cub <= 0:
                        v, s = value_sign(x)
                        if s is not None and s <= 0:
                            return failed(x, f"found by the branch and bound after {boxes} boxes")
                    u = g_upper(x)
                    if u is not None and (best_hi is None or u < best_hi):
                        best_hi, best_pt = u, x
    lower = Fraction(heap[0][0]) if math.isfinite(heap[0][0]) else None
    secs = time.monotonic() - start
    margin = Enclosure(lower, best_hi, point=best_pt)
    where = f"{boxes} boxes on {n} cube faces, {secs:.2f} s"
    if lower is not None and lower > 0:
        detail = (f"{name} > 0 on the unit sphere (certified, arb branch and bound, {where}): "
                  f"min {name}|_S ∈ [{float_down(lower):.8g}, {float_up(best_hi):.8g}]"
                  + (f"; refinement stopped at {stop}" if stop else "") + ".")
        return ConditionResult(name, Status.CERTIFIED, margin=margin, estimate=estimate, detail=detail)
    lo_s = "−∞" if lower is None else f"{float_down(lower):.6g}"
    detail = (f"undecided after {stop} ({where}): the certified lower bound {lo_s} of min {name}|_S is not "
              f"positive and no rational point with {name} ≤ 0 was found (estimated min {estimate.value:.6g}); "
              "raise budget_seconds, or the minimum may be exactly 0 at an irrational point.")
    return ConditionResult(name, Status.UNDECIDED, margin=margin, estimate=estimate, detail=detail)


# ---------------------------------------------------------------------------------------------
# 3. LMIs: solve with cvxpy + Clarabel, round to rationals, re-verify


def _solve(problem) -> str:
    import cvxpy as cp
    try:
        problem.solve(solver=cp.CLARABEL)
    except cp.error.SolverError as exc:
        return f"solver error ({exc})"
    return str(problem.status)


def _round_matrix(X: np.ndarray, den: int) -> sympy.Matrix:
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
    return _combine(name, [part1, part2], certificate=Pm)


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
    import cvxpy as cp
    Am = _as_matrix(A, "A")
    n = Am.rows
    Qm = None if Q is None else _as_matrix(Q, "Q")
    if Qm is not None:
        Qm, _ = _symmetric_part(Qm, "Q", False)
        if Qm.shape != Am.shape:
            raise InputError(f"{name}: expected Q of size {Am.shape}, got {Qm.shape}")
    hurwitz_note = ""
    if _is_rational(Am):
        ok, k, delta, charpoly = _routh_hurwitz(Am)
        if not ok:
            roots = charpoly.all_roots()
            lam = max(roots, key=lambda r: (float(sympy.re(r.evalf(30))), float(sympy.im(r.evalf(30)))))
            detail = (f"A is not Hurwitz (exact Routh–Hurwitz test): the Hurwitz minor Δ_{k} = {delta} ≤ 0 for "
                      f"the characteristic polynomial {charpoly.as_expr()}; A has the eigenvalue {lam} "
                      f"(≈ {complex(lam.evalf(15)):.6g}) with Re λ ≥ 0, so no P ≻ 0 with AᵀP + PA ≺ 0 exists "
                      "(for an eigenvector v, v*(AᵀP + PA)v = 2 Re λ · v*Pv ≥ 0).")
            return ConditionResult(name, Status.FAILED, witness=lam, detail=detail)
        hurwitz_note = "A is Hurwitz (exact Routh–Hurwitz test), so such a P exists. "
    Af = np.array(Am.evalf(17).tolist(), dtype=float)
    Qf = np.eye(n) if Qm is None else np.array(Qm.evalf(17).tolist(), dtype=float)
    qscale = max(1.0, float(np.max(np.abs(Qf))))
    attempts = [(0.0, denominator), (1e-3 * qscale, denominator), (1e-2 * qscale, denominator * 1000)]
    last = None
    for k, (eps, den) in enumerate(attempts, start=1):
        P = cp.Variable((n, n), symmetric=True)
        lyap = Af.T @ P + P @ Af
        prob = cp.Problem(cp.Minimize(cp.trace(P)),
                          [P >> np.eye(n), lyap << -(Qf + eps * np.eye(n))])
        status = _solve(prob)
        if status != cp.OPTIMAL:
            return ConditionResult(name, Status.UNDECIDED, detail=(
                f"{hurwitz_note}The SDP solver (Clarabel) returned the status {status!r}, not 'optimal'; a "
                "solver status other than optimal is never a certificate."))
        Pf = np.asarray(P.value, dtype=float)
        est = Estimate(float(np.min(np.linalg.eigvalsh(-(Af.T @ Pf + Pf @ Af) - (0 if Q is None else Qf)))),
                       "λ_min of the solver's float P (Clarabel)")
        Pq = _round_matrix(Pf, den)
        res = check_lyapunov_matrix(Am, Pq, Q=Qm, name=name)
        if res.status.is_proof:
            detail = (f"{hurwitz_note}P found by Clarabel (attempt {k}, margin ε = {eps:g}), rounded to "
                      f"denominators ≤ {den}, verified. " + " ".join(p.detail for p in res.parts))
            return dataclasses.replace(res, estimate=est, detail=detail)
        last = res
    return ConditionResult(name, Status.UNDECIDED, margin=last.margin, estimate=est, certificate=last.certificate,
                           parts=last.parts, detail=(
                               f"{hurwitz_note}The rounded solver P did not verify after {len(attempts)} attempts "
                               f"(margins and finer rounding): {last.detail}"))


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
    res = _combine(name, parts, certificate=cv)
    if res.holds:
        lo = min(p.margin.lo for p in parts)
        hi = min(p.margin.hi for p in parts)
        res = dataclasses.replace(res, margin=Enclosure(lo, hi), detail=(
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
    import scipy.linalg
    Ms = _matrix_list(M, "M")
    n = Ms[0].rows
    if any(m.rows != n for m in Ms):
        raise InputError(f"{name}: expected matrices of one size, got sizes {[m.rows for m in Ms]}")
    Nm = _check_n(N, n, name)
    Mf = [np.array(m.evalf(17).tolist(), dtype=float) for m in Ms]
    Nf = np.array(Nm.evalf(17).tolist(), dtype=float)
    c = cp.Variable()
    prob = cp.Problem(cp.Minimize(c), [c * Nf - m >> 0 for m in Mf])
    status = _solve(prob)
    if status != cp.OPTIMAL:
        return ConditionResult(name, Status.UNDECIDED, detail=(
            f"the SDP solver (Clarabel) returned {status!r}, not 'optimal'; never a certificate."))
    c_est = float(c.value)
    est = Estimate(c_est, "Clarabel SDP: min c s.t. cN − M ⪰ 0")
    # certified lower bound: Rayleigh quotients at rational generalized eigenvectors
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
    scale = max(1.0, abs(c_est))
    for bump in (0.0, 1e-9, 1e-6, 1e-3):
        cand = Fraction(math.ceil((c_est + bump * scale) * denominator), denominator)
        if lo is not None and cand < lo:
            continue
        res = check_quadratic_bound(Ms if len(Ms) > 1 else Ms[0], sympy.Rational(cand.numerator, cand.denominator),
                                    N=Nm, name=name)
        if res.holds:
            cq = sympy.Rational(cand.numerator, cand.denominator)
            exact = cq if lo == cand else None
            lo_s = "−∞" if lo is None else (str(lo) if exact is not None else f"{float_down(lo):.12g}")
            detail = (f"best c: Clarabel estimate {c_est:.12g}; rounded up to {cq} and verified "
                      f"({res.status}): cN − M ⪰ 0; the best constant lies in [{lo_s}, {cq}]"
                      + (" (attained: exact)" if exact is not None else "")
                      + (" (the lower end is xᵀMx/xᵀNx at the rational x = margin.point)" if lo is not None else "")
                      + ".")
            return ConditionResult(name, res.status, margin=Enclosure(lo, cand, exact=exact, point=lo_pt),
                                   estimate=est, certificate=cq, detail=detail, parts=res.parts)
    return ConditionResult(name, Status.UNDECIDED, estimate=est, detail=(
        f"the solver's c = {c_est:.12g} rounded up (by up to 1e-3 relative) did not verify cN − M ⪰ 0."))


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
    F0f = np.array(F0m.evalf(17).tolist(), dtype=float)
    Ff = [np.array(f.evalf(17).tolist(), dtype=float) for f in Fm]
    t = cp.Variable()
    if k:
        y = cp.Variable(k)
        expr = F0f + sum(y[i] * Ff[i] for i in range(k))
        cons = [expr - t * np.eye(n) >> 0, cp.abs(y) <= bound]
    else:
        y = None
        cons = [F0f - t * np.eye(n) >> 0]
    prob = cp.Problem(cp.Maximize(t), cons)
    status = _solve(prob)
    if status != cp.OPTIMAL:
        return ConditionResult(name, Status.UNDECIDED, detail=(
            f"the SDP solver (Clarabel) returned {status!r}, not 'optimal'; never a certificate."))
    est = Estimate(float(t.value), "Clarabel: max t s.t. F(y) ⪰ tI")
    last = None
    if t.value > 0:
        for den in (denominator, denominator * 1000):
            yq = tuple(Fraction(float(v)).limit_denominator(den) for v in (y.value if k else []))
            Fy = F0m + sum((sympy.Rational(v.numerator, v.denominator) * f for v, f in zip(yq, Fm)),
                           sympy.zeros(n, n))
            res = matrix_positive_definite(Fy, name="F(y)")
            if res.holds:
                return ConditionResult(name, res.status, margin=res.margin, estimate=est, certificate=yq,
                                       parts=(res,), detail=(
                                           f"y = ({', '.join(map(str, yq))}) found by Clarabel, rounded to "
                                           f"denominators ≤ {den}; {res.detail}"))
            last = res
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


def _dual_certificate(F0m, Fm, F0f, Ff) -> sympy.Matrix | None:
    """A rational Z ≻ 0 with tr(FᵢZ) = 0 exactly and tr(F0 Z) ≤ 0, or None."""
    import cvxpy as cp
    n = F0m.rows
    Z = cp.Variable((n, n), symmetric=True)
    s = cp.Variable()
    cons = [Z >> s * np.eye(n), cp.trace(Z) == 1, cp.trace(F0f @ Z) <= -s]
    cons += [cp.trace(f @ Z) == 0 for f in Ff]
    prob = cp.Problem(cp.Maximize(s), cons)
    if _solve(prob) != cp.OPTIMAL or not s.value > 0:
        return None
    Zf = np.asarray(Z.value, dtype=float)
    for den in (10**6, 10**9):
        Zq = _round_matrix(Zf, den)
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
