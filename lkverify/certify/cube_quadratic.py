"""The proved supremum of a quadratic ``b·ε + εᵀSε`` over the cube [-1, 1]^m (:func:`cube_quadratic_sup`),
for the Taylor forms of :class:`~lkverify.certify.engine.Taylor`: convex coordinates fixed at ±1, a
Lagrangian dual bound certified by an LDLᵀ factorisation in arb, the separable bound as the fallback.

Split from :mod:`lkverify.certify.engine`, which re-exports :func:`cube_quadratic_sup` and
:data:`QUADRATIC_BRANCH_DEPTH`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from flint import arb

from .intervals.balls import _ZERO

__all__ = ["QUADRATIC_BRANCH_DEPTH", "cube_quadratic_sup"]

_INF = math.inf


# ---------------------------------------------------------------------------
# the supremum of a quadratic over the cube [-1, 1]^m, proved (for the Taylor forms)
# ---------------------------------------------------------------------------

def _separable_sup(b, S) -> arb:
    """Σᵢ maxₜ(|bᵢ|t + aᵢt²) over t ∈ [0, 1], aᵢ = Sᵢᵢ + Σⱼ≠ᵢ |Sᵢⱼ|: a bound of sup b·ε + εᵀSε on the cube.

    Valid because 2|εᵢεⱼ| ≤ εᵢ² + εⱼ² (so Σᵢ≠ⱼ Sᵢⱼεᵢεⱼ ≤ Σᵢ εᵢ² Σⱼ≠ᵢ |Sᵢⱼ|) and the
    bound is increasing in |bᵢ| and aᵢ (upper ends are used throughout).
    """
    m = len(b)
    total = _ZERO
    for i in range(m):
        Si = S[i]
        a = Si[i].upper()
        for j in range(m):
            if j != i:
                a = a + Si[j].abs_upper()
        beta = b[i].abs_upper()
        if a < 0 and not beta >= -2 * a:
            phi = beta * beta / (-4 * a)        # the vertex (always ≥ the constrained maximum for a < 0)
        else:
            phi = beta + a                      # t = 1 (a ≥ 0, or the vertex lies beyond 1)
        total = total + phi.upper()
    return total


def _cholesky(A):
    """The lower Cholesky factor of a symmetric float matrix (list of rows), or None if not positive definite."""
    m = len(A)
    L = [[0.0] * m for _ in range(m)]
    for k in range(m):
        Lk = L[k]
        d = A[k][k]
        for p in range(k):
            d -= Lk[p] * Lk[p]
        if not d > 1e-300:
            return None
        d = math.sqrt(d)
        Lk[k] = d
        for i in range(k + 1, m):
            Li = L[i]
            v = A[i][k]
            for p in range(k):
                v -= Li[p] * Lk[p]
            Li[k] = v / d
    return L


def _chol_solve(A, rhs):
    """Solve A x = rhs for a symmetric positive definite float matrix (None if not positive definite)."""
    L = _cholesky(A)
    if L is None:
        return None
    m = len(A)
    y = [0.0] * m
    for i in range(m):
        Li = L[i]
        v = rhs[i]
        for p in range(i):
            v -= Li[p] * y[p]
        y[i] = v / Li[i]
    x = [0.0] * m
    for i in range(m - 1, -1, -1):
        v = y[i]
        for p in range(i + 1, m):
            v -= L[p][i] * x[p]
        x[i] = v / L[i][i]
    return x


def _cube_qp_float(b, S, max_iter: int = 24):
    """An approximate maximiser of b·e + eᵀSe on the cube [-1, 1]^m (floats; a primal active-set method).

    Only the quality of the proved bound depends on it, never its validity.
    """
    m = len(b)
    e = [0.0] * m
    fixed = set()
    for _ in range(max_iter):
        free = [i for i in range(m) if i not in fixed]
        if free:
            A = [[-2.0 * S[i][j] for j in free] for i in free]
            rhs = [b[i] + 2.0 * sum(S[i][j] * e[j] for j in fixed) for i in free]
            x = _chol_solve(A, rhs)
            if x is None:
                # not concave on the free coordinates: the most convex one goes to the face its
                # partial derivative points to, and the search goes on with the others
                i = max(free, key=lambda k: S[k][k])
                g = b[i] + 2.0 * sum(S[i][k] * e[k] for k in range(m) if k != i)
                e[i] = 1.0 if g >= 0.0 else -1.0
                fixed.add(i)
                continue
            # step from e towards the free maximiser x, stopping at the first face reached
            step, hit = 1.0, -1
            for i, xi in zip(free, x):
                d = xi - e[i]
                if d > 0.0 and e[i] + d > 1.0:
                    t = (1.0 - e[i]) / d
                elif d < 0.0 and e[i] + d < -1.0:
                    t = (-1.0 - e[i]) / d
                else:
                    continue
                if t < step:
                    step, hit = t, i
            for i, xi in zip(free, x):
                e[i] = min(1.0, max(-1.0, e[i] + step * (xi - e[i])))
            if hit >= 0:
                e[hit] = 1.0 if e[hit] > 0.0 else -1.0
                fixed.add(hit)
                continue
        # free coordinates optimal: release a face whose multiplier has the wrong sign
        worst, out = 0.0, -1
        for j in fixed:
            g = (b[j] + 2.0 * sum(S[j][k] * e[k] for k in range(m))) * e[j]
            if g < worst:
                worst, out = g, j
        if out < 0:
            break
        fixed.discard(out)
    return e


def _dual_sup(b, S, mu) -> arb | None:
    """Σμᵢ + ¼ bᵀ(diag μ − S)⁻¹b, proved, or None if diag μ − S is not proved positive definite.

    For μ ≥ 0 and P = diag μ − S ≻ 0: b·ε + εᵀSε = b·ε − εᵀPε + Σμᵢεᵢ² ≤ sup over
    all ε of (b·ε − εᵀPε) + Σμᵢ = ¼ bᵀP⁻¹b + Σμᵢ on the cube.  P ≻ 0 is proved by
    an LDLᵀ factorisation in arb whose pivots are all certainly > 0.
    """
    m = len(b)
    L = [[_ZERO] * m for _ in range(m)]
    D = []
    for k in range(m):
        d = arb(mu[k]) - S[k][k]
        for p in range(k):
            d = d - L[k][p] * L[k][p] * D[p]
        if not d > 0:
            return None
        D.append(d)
        for i in range(k + 1, m):
            v = -S[i][k]
            for p in range(k):
                v = v - L[i][p] * L[k][p] * D[p]
            L[i][k] = v / d
    total = _ZERO
    y = []
    for i in range(m):
        v = b[i]
        for p in range(i):
            v = v - L[i][p] * y[p]
        y.append(v)
        total = total + v * v / D[i]
    total = total / 4
    for x in mu:
        total = total + arb(x)
    return total


#: at most this many convex coordinates are fixed at ±1 (both ways) in :func:`cube_quadratic_sup`
QUADRATIC_BRANCH_DEPTH = 4


def _point_quadratic_sup(b, S, SA, depth: int = QUADRATIC_BRANCH_DEPTH) -> arb:
    """A proved bound of sup b·ε + εᵀSε on the cube for a point matrix S (floats; SA: the same as arb) and balls b.

    A coordinate with Sᵢᵢ ≥ 0 enters convexly, so the supremum is attained at
    εᵢ = ±1: both faces are bounded (recursively, ``depth`` levels at most) and
    the larger bound kept.  On the rest the Lagrangian dual bound of
    :func:`_dual_sup` is used, with the multipliers of an approximate maximiser
    (floats), or the separable bound where that does not prove positive definite.
    """
    m = len(b)
    if m == 0:
        return _ZERO
    k = max(range(m), key=lambda i: S[i][i])
    if S[k][k] >= 0 and depth > 0:
        rest = [i for i in range(m) if i != k]
        Sr = [[S[i][j] for j in rest] for i in rest]
        SAr = [[SA[i][j] for j in rest] for i in rest]
        # the face bⱼ points to first; the other one only if its separable bound does not settle it
        first = 1 if float(b[k].mid()) >= 0 else -1
        best = None
        for sgn in (first, -first):
            br = [b[i] + 2 * sgn * SA[i][k] for i in rest]
            head = sgn * b[k] + SA[k][k]
            if best is not None and (head + _separable_sup(br, SAr)).upper() <= best:
                continue
            v = (head + _point_quadratic_sup(br, Sr, SAr, depth - 1)).upper()
            best = v if best is None or v > best else best.union(v).upper()
        return best
    fallback = _separable_sup(b, SA)
    bm = [float(x.mid()) for x in b]
    Sm = S
    if not all(math.isfinite(x) for x in bm):
        return fallback
    e = _cube_qp_float(bm, Sm)
    scale = max(abs(x) for row in Sm for x in row) * 1e-9 + 1e-300
    mu = []
    for i in range(m):
        if abs(e[i]) >= 1.0:
            g = bm[i] + 2.0 * sum(Sm[i][j] * e[j] for j in range(m))
            mu.append(max(0.0, g * e[i] / 2.0) + scale)
        else:
            mu.append(scale)
    # a float Cholesky first: the proof in arb is tried only where it can succeed
    if _cholesky([[(mu[i] if i == j else 0.0) - Sm[i][j] for j in range(m)] for i in range(m)]) is None:
        return fallback
    dual = _dual_sup(b, SA, mu)
    if dual is None:
        return fallback
    dual = dual.upper()
    return dual if dual < fallback else fallback


def cube_quadratic_sup(b: Sequence[arb], S: Sequence[Sequence[arb]], enough: float = -_INF) -> arb:
    """A proved upper bound of sup ``Σᵢ bᵢεᵢ + Σᵢⱼ Sᵢⱼεᵢεⱼ`` over ε ∈ [-1, 1]^m, for all b, S in the balls.

    ``S`` must be symmetric (``S[i][j]`` and ``S[j][i]`` the same ball).  Two
    bounds, the smaller is returned:

    * separable: ``2|εᵢεⱼ| ≤ εᵢ² + εⱼ²`` moves the off-diagonal terms to the
      diagonal, then each coordinate's parabola is maximised exactly;
    * at the midpoints of S (the radii add ``Σ rad Sᵢⱼ``): coordinates that
      enter convexly (Sᵢᵢ ≥ 0) are fixed at ±1, both ways; then Lagrangian
      duality: an approximate maximiser (floats) gives multipliers μ ≥ 0 of
      the constraints εᵢ² ≤ 1 and ``Σμᵢ + ¼ bᵀ(diag μ − S)⁻¹b`` is proved in
      arb (exact for a concave quadratic at the optimal μ).

    ``enough``: the second bound is skipped when the first is already ≤ it.

    Examples
    --------
    >>> from flint import arb
    >>> b, S = [arb(1), arb(0)], [[arb(-1), arb(-0.5)], [arb(-0.5), arb(-1)]]
    >>> u = cube_quadratic_sup(b, S)       # the maximum is 1/3, at ε = (2/3, -1/3)
    >>> u >= arb(1) / 3, float(u.upper()) < 0.3334
    (True, True)
    """
    m = len(b)
    if m == 0:
        return _ZERO
    best = _separable_sup(b, S)
    if best <= enough:
        return best
    Sm = [[float(x.mid()) for x in row] for row in S]
    if not all(math.isfinite(x) for row in Sm for x in row) or not all(x.is_finite() for x in b):
        return best
    SA = [[arb(x) for x in row] for row in Sm]
    slack = _ZERO                           # εᵀSε − εᵀ(mid S)ε ≤ slack on the cube
    for i in range(m):
        for j in range(m):
            slack = slack + (S[i][j] - SA[i][j]).abs_upper()
    v = (_point_quadratic_sup(list(b), Sm, SA) + slack).upper()
    return v if v < best else best
