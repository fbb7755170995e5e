"""Matrix positivity decided exactly, or certified: M ≻ 0 (or M ⪰ 0) and λ_min enclosures.

:func:`matrix_positive_definite`
    rational entries: an exact LDLᵀ in fractions (all pivots > 0 ⇔ PD) →
    ``exact`` or ``failed`` with an exact witness x, xᵀMx ≤ 0; algebraic or
    transcendental entries (``sqrt(2)``, ``pi``): an LDLᵀ in arb balls whose
    pivots all have positive lower ends → ``certified``; a rational x with a
    certified negative xᵀMx → ``failed``; otherwise ``undecided``.  The
    margin is a certified enclosure [lo, hi] of λ_min.

The statuses are those of :mod:`lkverify.certify.conditions`.  The input helpers
(numbers, square matrices, symmetric parts) are shared with :mod:`lkverify.certify.lmi`.

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
import math
from fractions import Fraction

import flint
import numpy as np
import sympy
from flint import arb, fmpq, fmpq_mat

from ..errors import InputError
from ..status import Status
from .conditions import ConditionResult, Margin, _frac
from .intervals import enclose, float_down, float_up, lower_fraction, to_ball, upper_fraction

__all__ = ["EXACT_EIGEN_LIMIT", "PRECISIONS", "matrix_positive_definite"]

#: arb working precisions (bits) tried in turn by the certified matrix path
PRECISIONS = (64, 128, 256, 512)
#: largest size for which λ_min is computed exactly (characteristic polynomial, exact roots)
EXACT_EIGEN_LIMIT = 8

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
    """Symmetric Gaussian elimination with diagonal pivoting, exactly in python-flint's ``fmpq``.

    Invariant: the current Schur complement is S[i][j] = v_iᵀ M v_j, with v_j
    the original-coordinate vector of the remaining index j; so a nonpositive
    S-entry pattern maps back to an exact witness x.  Each elimination step is one rank-one
    update of python-flint ``fmpq_mat`` matrices (in C; ``benchmarks/bench_ldl.py`` measures it
    against the same elimination in ``Fraction``s); pivots and the witness are ``Fraction``.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> _exact_ldl([[F(2), F(1)], [F(1), F(2)]]).pivots
    (Fraction(2, 1), Fraction(3, 2))
    >>> r = _exact_ldl([[F(1), F(2)], [F(2), F(1)]]); r.kind, r.value <= 0
    ('indefinite', True)
    """
    n = len(M)
    S = fmpq_mat([[fmpq(x.numerator, x.denominator) for x in row] for row in M])
    V = fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])     # row j: v_j
    remaining = list(range(n))
    pivots = []
    while remaining:
        p = max(remaining, key=lambda i: S[i, i])
        d = S[p, p]
        if d <= 0:
            break
        pivots.append(Fraction(int(d.p), int(d.q)))
        remaining.remove(p)
        keep = set(remaining)
        col = fmpq_mat(n, 1, [S[i, p] if i in keep else 0 for i in range(n)]) / d   # S[i][p]/d = S[p][i]/d
        row = fmpq_mat(1, n, [S[p, j] if j in keep else 0 for j in range(n)])
        S = S - col * row                                   # the Schur complement on the remaining indices
        V = V - col * fmpq_mat(1, n, [V[p, j] for j in range(n)])                   # v_j -= (S_pj/d) v_p
    V = [[Fraction(int(V[i, j].p), int(V[i, j].q)) for j in range(n)] for i in range(n)]
    S = [[Fraction(int(S[i, j].p), int(S[i, j].q)) for j in range(n)] for i in range(n)]
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


def _exact_lambda_min(M: sympy.Matrix) -> Margin:
    """λ_min exactly: the smallest real root of the characteristic polynomial (exact SymPy root)."""
    lam = sympy.Dummy("lambda")
    cp = fmpq_mat([[fmpq(int(e.p), int(e.q)) for e in row] for row in M.tolist()]).charpoly()
    poly = sympy.Poly([sympy.Rational(int(c.p), int(c.q)) for c in reversed(cp.coeffs())], lam)
    root = poly.real_roots()[0]
    return _enclose_exact(root)


def _enclose_exact(root) -> Margin:
    if root.is_Rational:
        return Margin(root, root, exact=root)
    if isinstance(root, sympy.CRootOf):
        iv = root._get_interval()
        a, b = sympy.Rational(iv.a), sympy.Rational(iv.b)
        width = max(abs(a), abs(b)) * sympy.Rational(1, 2**64)
        a, b = root.poly.refine_root(a, b, eps=width)
        return Margin(_frac(sympy.Rational(a)), _frac(sympy.Rational(b)), exact=root)
    ball = enclose(root, prec=128)
    return Margin(lower_fraction(ball), upper_fraction(ball), exact=root)


# ---------------------------------------------------------------------------------------------
# arb helpers

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


def _arb_lambda_min(Ma: list[list[arb]], x_hi, *, steps: int = 120) -> Margin:
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
        return Margin(lo, hi, point=xs)
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
    return Margin(lo, hi, point=xs)


# ---------------------------------------------------------------------------------------------
# the decision


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
    rel = "⪰ 0" if semidefinite else "≻ 0"
    what = name if name.rstrip().endswith(("≻ 0", "⪰ 0", "> 0", ">= 0")) else f"{name} {rel}"
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


def _describe_margin(m: Margin) -> str:
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
                margin = Margin(max(margin.lo, Fraction(0)), margin.hi, point=margin.point)
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
