"""The one branch-and-bound engine, with pluggable enclosure strategies.

:class:`BranchAndBound` bounds the supremum of a function over a union of
boxes (or decides ``sup ≤ threshold``).  It knows nothing about SymPy: what it
needs from the function is an :class:`Enclosure`, a strategy object with one
method (the contract, as scipy's ``OdeSolver`` is for ODE steps):

``bound(piece, lo, hi, enough) -> BoxBound``
    a proved upper bound of the function on the box ``[lo, hi]`` of piece
    ``piece`` (floats storing arb end points), the box to keep (a strategy
    may shrink it to a face where the function is provably largest), the
    preferred split dimension (``-1``: the engine picks the widest), a
    centre point in the box with the arb enclosure of the value there, and
    whether that point lies in the region (so that its value counts as a
    proved lower bound of the supremum).  ``enough`` is a hint: a strategy
    may skip costly work once its bound is ``≤ enough``.

Strategies for compiled SymPy expressions (:class:`Objective`):
:class:`NaturalBalls`, :class:`MeanValue` (mean-value form, monotonicity and
the gradient's split direction), :class:`Affine` (affine arithmetic),
:class:`MeanValueAffine` (both, intersected) and :class:`Taylor` (mean-value ∩
second- and third-order Taylor forms, whose excess near an interior maximum is
third order in the width; the supremum of the quadratic part over the box is
proved by :func:`cube_quadratic_sup`).  :mod:`lkverify.certify.forms` plugs in
its own strategy for the faces of the cube.

Examples
--------
>>> import sympy
>>> from lkverify.certify.regions import parse_region
>>> x = sympy.Symbol("x")
>>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x * (1 - x)]))
>>> bb = BranchAndBound(MeanValue(obj), obj.roots())
>>> out = bb.run(Goal.SUPREMUM, rel_gap=1e-3, boxes=10_000, deadline=math.inf)
>>> out.stop, out.lower <= 0.25 <= out.upper <= 0.2503
(<Stop.DONE: 'done'>, True)
"""

from __future__ import annotations

import dataclasses
import enum
import heapq
import itertools
import math
import time
from collections.abc import Callable, Sequence

import flint
import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from .affine import AffineForm
from .functions import compile_arb, lambdify_real
from .intervals import compile_program, float_down, float_up
from .intervals.balls import _JUMPS, _ZERO
from .intervals.convert import _real_dummies
from .regions import Region

__all__ = [
    "Affine", "BoxBound", "BranchAndBound", "BranchProgress", "ENCLOSURES", "Enclosure", "Goal", "MeanValue",
    "MeanValueAffine", "NaturalBalls", "Objective", "Outcome", "PROGRESS_SECONDS", "Refutation", "Stop",
    "QUADRATIC_BRANCH_DEPTH", "TAYLOR2_MAX_DIMENSION", "TAYLOR3_MAX_DIMENSION", "TAYLOR_CACHE_SIZE", "Taylor",
    "TaylorPrograms", "cube_quadratic_sup",
    "enclosure_class",
]

_INF = math.inf
#: how often (seconds) a ``progress`` callback is called
PROGRESS_SECONDS = 0.5
#: :class:`Taylor` compiles third derivatives (n(n+1)(n+2)/6 of them) up to this many variables ...
TAYLOR3_MAX_DIMENSION = 6
#: ... and second derivatives (n(n+1)/2) up to this many; beyond, it is :class:`MeanValue`
TAYLOR2_MAX_DIMENSION = 12
#: compiled derivative programs kept for objectives seen again (the same template in two bound steps)
TAYLOR_CACHE_SIZE = 16
_TAYLOR_CACHE: dict = {}



def _collapse(G, lo, hi, indices):
    """Monotonicity: where ∂f/∂x_i ≥ 0 on the box the maximum is at x_i = hi_i (≤ 0: at lo_i).

    Returns the collapsed (lo, hi) and whether anything changed.
    """
    lo, hi, changed = list(lo), list(hi), False
    for i in indices:
        if G[i] >= 0:
            lo[i] = hi[i]
            changed = True
        elif G[i] <= 0:
            hi[i] = lo[i]
            changed = True
    return lo, hi, changed

class Goal(enum.Enum):
    """What :meth:`BranchAndBound.run` is asked for."""

    SUPREMUM = "supremum"   #: bound sup f to a gap
    DECIDE = "decide"       #: prove sup f ≤ threshold (< if strict) or refute it


class Stop(enum.Enum):
    """Why the branch and bound stopped."""

    DONE = "done"           #: the goal is met
    FAILED = "failed"       #: a refutation was found
    BUDGET = "budget"       #: the box or time budget ran out
    STUCK = "stuck"         #: boxes shrank to float resolution without meeting the goal
    SKIPPED = "skipped"     #: not run (an estimate only)


@dataclasses.dataclass(frozen=True)
class BranchProgress:
    """What a ``progress`` callback receives about twice a second.

    Attributes
    ----------
    boxes : int
        Boxes evaluated so far.
    lower, upper : float
        The proved lower bound and the current upper bound of the supremum
        (in a yes/no check: ``upper`` is the largest unresolved bound).
    seconds : float
    """

    boxes: int
    lower: float
    upper: float
    seconds: float


@dataclasses.dataclass(frozen=True)
class Refutation:
    """A proved counterexample: ``margin`` is a proved lower bound of the violation at ``point``."""

    margin: float
    point: tuple


@dataclasses.dataclass(frozen=True)
class Outcome:
    """The end of a branch and bound.

    ``upper`` (the largest upper bound over the leaves) is a proved upper bound
    of the supremum whatever ``stop`` says; ``lower`` is a proved lower bound
    (an arb point value at ``lower_point``).
    """

    stop: Stop
    upper: float
    lower: float = -_INF
    lower_point: tuple | None = None
    boxes: int = 0
    refutation: Refutation | None = None
    reason: str = ""


@dataclasses.dataclass(frozen=True)
class BoxBound:
    """What an :class:`Enclosure` returns for one box (see the module docstring)."""

    upper: float
    lo: tuple
    hi: tuple
    split: int
    centre: tuple
    centre_value: arb
    inside: bool


class Objective:
    """A SymPy expression on a region, compiled to arb (value; value and gradient; affine) and to NumPy.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> Objective(x**2, parse_region({x: (0, 2)}, [x**2])).f_float(np.array([1.5]))
    2.25
    """

    def __init__(self, expr: sympy.Expr, region: Region, *, gradient: bool = True):
        self.expr = expr
        self.region = region
        self.n = len(region.variables)
        self.compiled = compile_arb(expr, region.variables, gradient=gradient, signs=region.signs)
        self.np_f = lambdify_real(list(region.variables), expr)

    def roots(self) -> list:
        """The region as the engine's list of root boxes ``(piece, lo, hi)``."""
        return [(0, tuple(self.region.lo_out), tuple(self.region.hi_out))]

    def point_ball(self, point: Sequence[float]) -> arb:
        """The enclosure of f at an exact binary point."""
        return self.compiled.balls(*[arb(float(x)) for x in point])

    def f_float(self, x: np.ndarray) -> float:
        """f at a point in floating point (``-inf`` where not finite)."""
        v = float(self.np_f(*x))
        return v if math.isfinite(v) else -_INF

    def taylor_programs(self, order: int) -> TaylorPrograms | None:
        """The derivatives up to ``order`` (2 or 3) compiled to arb, or None where Taylor forms do not apply.

        Compiled once per order, on first use (and kept for :data:`TAYLOR_CACHE_SIZE`
        expressions, per variables, signs and arb precision).  None if the expression has no
        gradient, or a derivative up to ``order`` has a jump (``sign``, ``Heaviside``: the
        derivatives of ``Abs``, ``Min``, ``Max``) or cannot be enclosed.
        """
        cache = self.__dict__.setdefault("_taylor", {})
        if order not in cache:
            if not self.compiled.has_gradient:
                cache[order] = None
            else:
                key = (self.expr, self.region.variables, tuple(self.region.signs), order, flint.ctx.prec)
                try:
                    cache[order] = _TAYLOR_CACHE[key]
                except KeyError:
                    cache[order] = _TAYLOR_CACHE[key] = TaylorPrograms.compile(self, order)
                    while len(_TAYLOR_CACHE) > TAYLOR_CACHE_SIZE:
                        _TAYLOR_CACHE.pop(next(iter(_TAYLOR_CACHE)))
        return cache[order]


def _shared_subexpressions(exprs: list) -> list:
    """The expressions rebuilt so that their common subexpressions (SymPy's ``cse``) are shared nodes.

    The interval compiler emits one line per distinct node; sums of products that
    share factors (the derivatives of a trigonometric expression) become shared
    partial products.  The rebuilt trees (``evaluate=False``, so SymPy does not
    flatten them again) are the same functions, only grouped differently.
    """
    replacements, reduced = sympy.cse(exprs)
    table: dict = {}

    def rebuild(node):
        hit = table.get(node)
        if hit is not None:
            return hit
        if not node.args:
            return node
        return node.func(*[rebuild(a) for a in node.args], evaluate=False)

    for sym, e in replacements:
        table[sym] = rebuild(e)
    return [rebuild(e) for e in reduced]


@dataclasses.dataclass(frozen=True)
class TaylorPrograms:
    """An objective's derivatives up to second or third order, compiled to arb (for :class:`Taylor`).

    ``box(*balls)`` returns ``[f, ∂₁f, …, ∂ₙf, H…, T…]`` (the Hessian's upper
    triangle, then for ``order`` 3 the third derivatives ∂ᵢ∂ⱼ∂ₖf, i ≤ j ≤ k);
    ``point(*balls)`` returns ``[f, ∇f, H…]`` (no third derivatives), for the
    expansion point.  ``hess[i][j]`` is the position of ∂ᵢ∂ⱼf in both lists,
    ``third`` lists ``(position, i, j, k, shares)`` per third derivative, with
    ``shares`` the pairs ``(q, ball)`` of the weight the derivative's term
    |∂ᵢⱼₖf| rᵢrⱼrₖ gets in the remainder bound of coordinate q.  The derivatives
    are SymPy's (``diff``), compiled after common-subexpression elimination.
    """

    order: int
    box: Callable
    point: Callable
    hess: tuple
    third: tuple

    @classmethod
    def compile(cls, obj: Objective, order: int) -> TaylorPrograms | None:
        reg = obj.region
        n = obj.n
        if n == 0 or n > (TAYLOR3_MAX_DIMENSION if order >= 3 else TAYLOR2_MAX_DIMENSION):
            return None
        # the same real Dummy variables (with the region's signs) as compile_arb
        dummies = _real_dummies(reg.variables, reg.signs)
        dexpr = obj.expr.xreplace(dummies)
        dv = [dummies[v] for v in reg.variables]
        flags = [bool(d.is_nonnegative) for d in dv]
        back = {d: v for v, d in dummies.items()}
        # Taylor's theorem with the Lagrange remainder needs f smooth on the box: no derivative
        # may jump (sign, Heaviside: the derivatives of Abs, Min, Max) or be left unevaluated
        bad = (sympy.Derivative, sympy.Subs, sympy.DiracDelta, *_JUMPS)
        pairs = [(i, j) for i in range(n) for j in range(i, n)]
        triples = [(i, j, k) for i, j in pairs for k in range(j, n)] if order >= 3 else []
        try:
            grads = [sympy.diff(dexpr, d) for d in dv]
            if any(g.has(*bad) for g in grads):
                return None
            hess = {(i, j): sympy.diff(grads[i], dv[j]) for i, j in pairs}
            if any(h.has(*bad) for h in hess.values()):
                return None
            base = [dexpr, *grads, *hess.values()]
            third = [sympy.diff(hess[i, j], dv[k]) for i, j, k in triples]
            if any(t.has(*bad) for t in third):
                return None
            # the derivatives share most of their products: common subexpressions, evaluated once
            shared = _shared_subexpressions([*base, *third])
            point = compile_program(shared[:len(base)], dv, nonnegative=flags, originals=back).function()
            box = compile_program(shared, dv, nonnegative=flags, originals=back).function() if third else point
        except (InputError, NotImplementedError):
            return None
        index = [[0] * n for _ in range(n)]
        for k, (i, j) in enumerate(pairs):
            index[i][j] = index[j][i] = 1 + n + k
        top = 1 + n + len(pairs)
        third_index = []
        for m, (i, j, k) in enumerate(triples):
            # the remainder ⅙ Σ over the mult ordered triples; an index that occurs c times comes first
            # in c/3 of them, and takes that share of the triple's term (see Taylor._third_order_weights)
            mult = len(set(itertools.permutations((i, j, k))))
            shares = tuple((q, arb(mult * ((q == i) + (q == j) + (q == k))) / 18) for q in sorted({i, j, k}))
            third_index.append((top + m, i, j, k, shares))
        third_index = tuple(third_index)
        return cls(3 if order >= 3 else 2, box, point, tuple(map(tuple, index)), third_index)


class Enclosure:
    """The strategy contract: ``bound(piece, lo, hi, enough) -> BoxBound`` (see the module docstring).

    This base class implements it for an :class:`Objective` from the natural
    ball extension, optionally intersected with the mean-value form
    (:attr:`use_gradient`: also collapses a box to the face where a partial
    derivative's sign proves the maximum, and splits along the largest
    |∂f|·width) and with an affine form (:attr:`use_affine`, skipped once the
    bound is ``≤ enough``).  Subclasses choose the flags or override
    :meth:`bound` altogether.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> b = Enclosure(obj).bound(0, (0.0,), (1.0,))         # natural balls: [0, 1]·[0, 1]
    >>> round(b.upper, 6), b.centre, float(b.centre_value), b.inside
    (1.0, (0.5,), 0.25, True)
    >>> Enclosure.use_gradient, MeanValueAffine.use_gradient, MeanValueAffine.use_affine
    (False, True, True)
    """

    use_gradient = False
    use_affine = False

    def __init__(self, objective: Objective, *, collapse: bool = True):
        self.obj = objective
        self.fv = objective.compiled.value_program
        fvg = objective.compiled.gradient_program
        self.fvg = fvg if self.use_gradient else None
        self.faff = objective.compiled.affine_program if self.use_affine else None
        self.collapse = collapse
        reg = objective.region
        self.w0 = [max(h - l, 1e-300) for l, h in zip(reg.lo_out, reg.hi_out)]

    def _natural(self, lo, hi):
        """(value ball, gradient balls or None, the box's balls, lo, hi) after monotone collapsing."""
        n = self.obj.n
        while True:
            X = [arb(lo[i]) if lo[i] == hi[i] else arb(lo[i]).union(arb(hi[i])) for i in range(n)]
            G = None
            if self.fvg is not None:
                out = self.fvg(*X)
                v, G = out[0], out[1:]
                if not all(g.is_finite() for g in G):
                    G = None
            else:
                v = self.fv(*X)[0]
            if G is None or not self.collapse:
                return v, G, X, lo, hi
            lo, hi, changed = _collapse(G, lo, hi, [i for i in range(n) if lo[i] < hi[i]])
            if not changed:
                return v, G, X, lo, hi

    def _centre(self, lo, hi):
        """A centre point of the box, moved into the region where possible, and whether it is inside."""
        reg = self.obj.region
        c, inside = [], True
        for i in range(self.obj.n):
            a, b = lo[i], hi[i]
            m = a + (b - a) * 0.5
            if not a <= m <= b:
                m = a
            p, q = max(a, reg.lo_in[i]), min(b, reg.hi_in[i])
            if p <= q:
                m = min(max(m, p), q)
            else:
                inside = False
            c.append(m)
        return c, inside

    def _mean_value(self, fc, G, X, C, lo, hi):
        """(upper bound of the mean-value form, split dimension or -1)."""
        cen, best, dim = fc, -1.0, -1
        for i in range(self.obj.n):
            if lo[i] < hi[i]:
                g = G[i]
                cen = cen + g * (X[i] - C[i])
                score = float(g.abs_upper()) * (hi[i] - lo[i])
                if score > best:
                    best, dim = score, i
        return float_up(cen), (dim if best > 0.0 else -1)

    def _affine(self, C, lo, hi) -> float:
        n = self.obj.n
        zero = (_ZERO,) * n
        xs = []
        for i in range(n):
            m = C[i]
            if lo[i] == hi[i]:
                xs.append(AffineForm(m, zero, _ZERO))
                continue
            r = (arb(hi[i]) - m).union(m - arb(lo[i])).abs_upper()
            xs.append(AffineForm(m, zero[:i] + (r,) + zero[i + 1:], _ZERO))
        A = self.faff(*xs)[0]
        return float_up(A.ball()) if A.__class__ is AffineForm else float_up(A)

    def bound(self, piece: int, lo, hi, enough: float = -_INF) -> BoxBound:
        v, G, X, lo, hi = self._natural(lo, hi)
        upper = float_up(v)
        c, inside = self._centre(lo, hi)
        C = [arb(x) for x in c]
        fc = self.fv(*C)[0]
        dim = -1
        if G is not None:
            cu, dim = self._mean_value(fc, G, X, C, lo, hi)
            upper = min(upper, cu)
        if self.faff is not None and not upper <= enough:
            upper = min(upper, self._affine(C, lo, hi))
        return BoxBound(upper, tuple(lo), tuple(hi), dim, tuple(c), fc, inside)


class NaturalBalls(Enclosure):
    """The expression evaluated on the box's balls (the cheapest enclosure).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> round(NaturalBalls(obj).bound(0, (0.0,), (1.0,)).upper, 6)            # x ∈ [0, 1], 1 − x ∈ [0, 1]
    1.0
    >>> round(NaturalBalls(obj).bound(0, (0.4,), (0.6,)).upper, 6)            # 0.6 · 0.6
    0.36
    """


class MeanValue(Enclosure):
    """Natural balls ∩ the mean-value form with the arb-enclosed gradient (plus monotonicity).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> round(MeanValue(obj).bound(0, (0.0,), (1.0,)).upper, 6)               # f(1/2) + |f'|·1/2
    0.75
    >>> b = MeanValue(obj).bound(0, (0.0,), (0.25,))      # f' > 0: collapsed to the face x = 1/4
    >>> b.lo, b.hi, b.upper
    ((0.25,), (0.25,), 0.1875)
    """

    use_gradient = True


class Affine(Enclosure):
    """Natural balls ∩ affine arithmetic (tighter on wide boxes of trigonometric expressions).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> round(Affine(obj).bound(0, (0.0,), (1.0,)).upper, 6)                  # natural balls give 1
    0.5
    >>> round(Affine(obj).bound(0, (0.4,), (0.6,)).upper, 6)                  # natural balls give 0.36
    0.26
    """

    use_affine = True


class MeanValueAffine(Enclosure):
    """Natural balls ∩ mean-value form ∩ affine form (the default).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> [round(E(obj).bound(0, (0.4,), (0.6,)).upper, 6) for E in (NaturalBalls, MeanValue, MeanValueAffine)]
    [0.36, 0.27, 0.26]
    """

    use_gradient = True
    use_affine = True


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


def _intersect(a: arb, b: arb) -> arb:
    """The intersection of two enclosures of one value (a, should they not overlap -- impossible if both are sound)."""
    try:
        return a.intersection(b)
    except ValueError:
        return a


class Taylor(Enclosure):
    """Natural balls ∩ mean-value form ∩ a second- or third-order Taylor form, with monotonicity.

    On a box X with expansion point c (the centre), half-widths r and
    d = x − c = r∘ε, ε ∈ [-1, 1]ⁿ, for every x in X (Taylor's theorem with the
    Lagrange remainder on the segment [c, x] ⊂ X):

    * order 3: ``f(x) ≤ f(c) + ∇f(c)·d + ½ dᵀH(c)d + Σᵢ wᵢεᵢ²`` with
      ``wᵢ = ⅙ Σⱼₖ |∂ᵢⱼₖf(X)| rᵢrⱼrₖ`` (|εᵢεⱼεₖ| ≤ (εᵢ² + εⱼ²)/2 bounds the cubic
      remainder; ``Σ wᵢ`` is its plain bound);
    * order 2, where a third derivative's enclosure is not finite:
      ``f(x) ≤ f(c) + ∇f(c)·d + ½ dᵀH(X)d``;

    with ∇f(c), H(c) arb enclosures at the point c and H(X), ∂ᵢⱼₖf(X)
    enclosures on the box; the supremum of the quadratic in ε over the cube is
    proved by :func:`cube_quadratic_sup`.  Where the mean-value form's excess
    is first order in the width (``Σ |∂ᵢf(X)| rᵢ``: large near a maximum, where
    ∇f vanishes but its enclosure does not), the Taylor form captures the
    curvature and its excess is third order.  The gradient's enclosure is
    tightened by its own mean-value form ``∇f(c) + H(X)(X − c)`` before the
    monotonicity test and the mean-value form.

    Needs a gradient, a Hessian without jumps (no ``Abs``/``Min``/``Max``)
    and finite derivative enclosures on the box; otherwise the box gets the
    :class:`MeanValue` bound.  Third derivatives are compiled up to
    :data:`TAYLOR3_MAX_DIMENSION` variables, second up to
    :data:`TAYLOR2_MAX_DIMENSION`, once per objective (SymPy ``diff``; about
    0.2–2 s for the template constants of aleksandrov2023.theorem3).  A box
    costs about 4× a ``"mean-value"`` box there, but 5–10× fewer boxes are
    needed, and the c_A template (a quadratic form on the sphere, flat along
    the cap) is certified to 0.5 % where the mean-value form stalls at 5 %.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x, y = sympy.symbols("x y")
    >>> f = sympy.sin(x) * sympy.cos(y) - (x - 1)**2 * y**2
    >>> obj = Objective(f, parse_region({x: (0, 3), y: (-1, 1)}, [f]))
    >>> out = BranchAndBound(Taylor(obj), obj.roots()).run(Goal.SUPREMUM, rel_gap=1e-4, boxes=10_000,
    ...                                                    deadline=math.inf)
    >>> out.stop, out.lower <= 1.0 <= out.upper <= 1.0001
    (<Stop.DONE: 'done'>, True)
    """

    use_gradient = True
    #: the highest order of the Taylor forms (3, or 2 for the second-order form only)
    order = 3

    def __init__(self, objective: Objective, *, collapse: bool = True):
        super().__init__(objective, collapse=collapse)
        tp = None
        if self.fvg is not None:
            tp = objective.taylor_programs(self.order)
            if tp is None and self.order > 2:
                tp = objective.taylor_programs(2)
        self.tp = tp

    def bound(self, piece: int, lo, hi, enough: float = -_INF) -> BoxBound:
        tp = self.tp
        if tp is None:
            return super().bound(piece, lo, hi, enough)
        n = self.obj.n
        hess = tp.hess
        while True:
            X = [arb(lo[i]) if lo[i] == hi[i] else arb(lo[i]).union(arb(hi[i])) for i in range(n)]
            out = tp.box(*X)
            v = out[0]
            c, inside = self._centre(lo, hi)
            C = [arb(x) for x in c]
            G = list(out[1:n + 1])
            if not all(g.is_finite() for g in G):
                return BoxBound(float_up(v), tuple(lo), tuple(hi), -1, tuple(c), self.fv(*C)[0], inside)
            pc = tp.point(*C)
            fc, gc = pc[0], pc[1:n + 1]
            act = [i for i in range(n) if lo[i] < hi[i]]
            h_ok = all(out[hess[i][j]].is_finite() for i in act for j in act) and all(g.is_finite() for g in gc)
            if h_ok:
                D = [X[j] - C[j] for j in range(n)]
                for i in act:
                    alt = gc[i]
                    for j in act:
                        alt = alt + out[hess[i][j]] * D[j]
                    G[i] = _intersect(G[i], alt)
            if not self.collapse:
                break
            lo, hi, changed = _collapse(G, lo, hi, act)
            if not changed:
                break
        upper = float_up(v)
        mv, dim = self._mean_value(fc, G, X, C, lo, hi)
        upper = min(upper, mv)
        if not h_ok or not act or upper <= enough:
            return BoxBound(upper, tuple(lo), tuple(hi), dim, tuple(c), fc, inside)
        r = [_ZERO] * n
        for i in act:
            r[i] = (arb(hi[i]) - C[i]).union(C[i] - arb(lo[i])).abs_upper()
        b = [gc[i] * r[i] for i in act]
        w = self._third_order_weights(out, r, lo, hi) if tp.order >= 3 else None
        if w is not None and all(pc[hess[i][j]].is_finite() for i in act for j in act):
            # third order: the Hessian at the centre, the third derivatives on the box
            # (the remainder's bound Σ wᵢεᵢ² joins the quadratic: smaller than Σ wᵢ inside the cube)
            base, H = fc, pc
            S = self._scaled_hessian(H, r, act)
            for p, i in enumerate(act):
                S[p][p] = S[p][p] + w[i]
        else:
            base, H = fc, out               # second order: the Hessian on the box
            S = self._scaled_hessian(H, r, act)
        # (a hint only: below ``need`` the cheaper bound of the quadratic is good enough)
        need = enough - float(base.mid()) if enough > -_INF else -_INF
        upper = min(upper, float_up(base + cube_quadratic_sup(b, S, need)))
        return BoxBound(upper, tuple(lo), tuple(hi), dim, tuple(c), fc, inside)

    def _scaled_hessian(self, H, r, act) -> list:
        """½ Hᵢⱼ rᵢ rⱼ over the active coordinates (a symmetric matrix of balls)."""
        hess = self.tp.hess
        m = len(act)
        S = [[_ZERO] * m for _ in range(m)]
        for p in range(m):
            i = act[p]
            for q in range(p, m):
                j = act[q]
                S[p][q] = S[q][p] = H[hess[i][j]] * r[i] * r[j] / 2
        return S

    def _third_order_weights(self, out, r, lo, hi) -> list | None:
        """wᵢ = ⅙ Σⱼₖ |∂ᵢⱼₖf(X)| rᵢrⱼrₖ (ordered j, k), or None if an enclosure is not finite.

        ``|⅙ Σᵢⱼₖ ∂ᵢⱼₖf dᵢdⱼdₖ| ≤ Σᵢ wᵢ εᵢ²`` for d = r∘ε on the cube, since
        ``|εᵢεⱼεₖ| ≤ (εᵢ² + εⱼ²)/2`` and the sum is symmetric.
        """
        w = [_ZERO] * len(r)
        for pos, i, j, k, shares in self.tp.third:
            if lo[i] < hi[i] and lo[j] < hi[j] and lo[k] < hi[k]:
                t = out[pos]
                if not t.is_finite():
                    return None
                t = t.abs_upper() * r[i] * r[j] * r[k]
                for q, share in shares:
                    w[q] = w[q] + t * share
        return [x.upper() for x in w]


#: the enclosure strategies by name (``enclosure=`` of the public functions)
ENCLOSURES = {"both": MeanValueAffine, "mean-value": MeanValue, "affine": Affine, "natural": NaturalBalls,
              "taylor": Taylor}


def enclosure_class(enclosure) -> type:
    """The :class:`Enclosure` subclass named by ``enclosure`` (a name of :data:`ENCLOSURES` or a subclass).

    Examples
    --------
    >>> enclosure_class("mean-value").__name__
    'MeanValue'
    """
    if isinstance(enclosure, type) and issubclass(enclosure, Enclosure):
        return enclosure
    if isinstance(enclosure, str) and enclosure in ENCLOSURES:
        return ENCLOSURES[enclosure]
    raise InputError(f"enclosure: expected one of {tuple(ENCLOSURES)} or an Enclosure subclass, got "
                     f"{enclosure!r}; pass e.g. enclosure='mean-value'")


class _Search:
    """The mutable state of one run: the heap, the bounds, the counters."""

    def __init__(self, lower, lower_point):
        self.heap = []
        self.counter = 0
        self.boxes = 0
        self.lower, self.lower_point = lower, lower_point
        self.resolved = -_INF        # leaves set aside: pruned (supremum) or proved (decide)
        self.stuck = -_INF
        self.last_report = time.monotonic()

    def upper(self) -> float:
        top = -self.heap[0][0] if self.heap else -_INF
        return max(top, self.resolved, self.stuck)

    def outcome(self, stop: Stop, upper=None, reason="", refutation=None) -> Outcome:
        return Outcome(stop, self.upper() if upper is None else upper, self.lower, self.lower_point, self.boxes,
                       refutation, reason)


class BranchAndBound:
    """Best-first branch and bound for the supremum of a function over boxes.

    Parameters
    ----------
    enclosure : Enclosure
        The strategy that bounds the function on a box (see the module docstring).
    roots : sequence of (piece, lo, hi)
        The boxes whose union is the region (float end points covering it).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.regions import parse_region
    >>> x = sympy.Symbol("x")
    >>> obj = Objective(x * (1 - x), parse_region({x: (0, 1)}, [x]))          # sup 1/4 at x = 1/2
    >>> bb = BranchAndBound(MeanValue(obj), obj.roots())
    >>> out = bb.run(Goal.SUPREMUM, rel_gap=1e-3, boxes=1000, deadline=math.inf)
    >>> out.stop, out.lower, out.upper <= 0.25 * (1 + 1e-3)
    (<Stop.DONE: 'done'>, 0.25, True)
    >>> out = BranchAndBound(NaturalBalls(obj), obj.roots()).run(Goal.DECIDE, threshold=0.3, boxes=1000,
    ...                                                            deadline=math.inf)
    >>> out.stop, out.upper <= 0.3                         # sup f ≤ 0.3 proved
    (<Stop.DONE: 'done'>, True)
    """

    def __init__(self, enclosure: Enclosure, roots: Sequence):
        self.enclosure = enclosure
        self.roots = [(p, tuple(lo), tuple(hi)) for p, lo, hi in roots]
        n = len(self.roots[0][1]) if self.roots else 0
        self.n = n
        self.w0 = [max(max(h[i] - l[i] for _, l, h in self.roots), 1e-300) for i in range(n)]

    def _split(self, lo, hi, dim):
        """Two halves along dim (or another splittable dimension); None if the box is a float point."""
        rest = sorted((i for i in range(self.n) if i != dim or dim < 0), key=lambda i: -(hi[i] - lo[i]) / self.w0[i])
        for d in ([dim] + rest if dim >= 0 else rest):
            a, b = lo[d], hi[d]
            m = a + (b - a) * 0.5
            if a < m < b:
                return (tuple(lo), hi[:d] + (m,) + hi[d + 1:]), (lo[:d] + (m,) + lo[d + 1:], tuple(hi))
        return None

    def _widest(self, lo, hi) -> int:
        best, dim = -1.0, -1
        for i in range(self.n):
            w = (hi[i] - lo[i]) / self.w0[i]
            if w > best and lo[i] < hi[i]:
                best, dim = w, i
        return dim

    def _visit(self, s: _Search, piece, b: BoxBound, probe):
        """Update the lower bound from the box's centre; the probe's refutation, if any."""
        if not b.inside:
            return None
        pl = float_down(b.centre_value)
        if pl > s.lower:
            s.lower, s.lower_point = pl, b.centre
        return probe(piece, b.centre, b.centre_value) if probe is not None else None

    def _push(self, s: _Search, piece, b: BoxBound):
        dim = b.split if b.split >= 0 else self._widest(b.lo, b.hi)
        heapq.heappush(s.heap, (-b.upper, s.counter, piece, b.lo, b.hi, dim))
        s.counter += 1

    def run(self, goal: Goal, *, threshold: float = 0.0, strict: bool = False, below: float | None = None,
            rel_gap: float = 1e-2, abs_gap: float = 0.0, boxes: int, deadline: float, start: float | None = None,
            lower: float = -_INF, lower_point=None,
            probe: Callable[[int, tuple, arb], Refutation | None] | None = None,
            progress: Callable[[BranchProgress], None] | None = None) -> Outcome:
        """Run to the goal, a refutation, or the budget.

        ``Goal.SUPREMUM``: stop when ``upper − lower ≤ max(rel_gap·|lower|, abs_gap)``
        (and, if ``below`` is given, ``upper < below``).  ``Goal.DECIDE``: prove
        every box's bound ≤ ``threshold`` (< if ``strict``).  ``probe(piece,
        centre, value)`` is called at every box centre inside the region and
        may return a :class:`Refutation`, which ends the run ``Stop.FAILED``.
        ``deadline`` is a :func:`time.monotonic` time; ``boxes`` the box budget.
        """
        s = _Search(lower, lower_point)
        start = time.monotonic() if start is None else start

        def ok(u):
            return u < threshold if strict else u <= threshold

        def tol():
            return max(rel_gap * abs(s.lower), abs_gap) if math.isfinite(s.lower) else -_INF

        def settled(u) -> bool:
            return u <= s.lower if goal is Goal.SUPREMUM else ok(u)

        def met(U) -> bool:
            return U - s.lower <= tol() and (below is None or U < below)

        for piece, lo, hi in self.roots:
            b = self.enclosure.bound(piece, lo, hi)
            s.boxes += 1
            hit = self._visit(s, piece, b, probe)
            if hit is not None:
                return s.outcome(Stop.FAILED, _INF, refutation=hit)
            self._push(s, piece, b)
        if goal is Goal.DECIDE:
            enough = math.nextafter(threshold, -_INF) if strict else threshold
        while s.heap:
            stop = self._check(s, goal, met, tol, boxes, deadline, start, progress)
            if stop is not None:
                return stop
            negu, _, piece, lo, hi, dim = heapq.heappop(s.heap)
            u = -negu
            if settled(u):
                s.resolved = max(s.resolved, u)
                continue
            halves = self._split(lo, hi, dim)
            if halves is None:
                s.stuck = max(s.stuck, u)
                if goal is Goal.DECIDE:
                    return s.outcome(Stop.STUCK, max(u, s.upper()),
                                     reason="a box shrank to float resolution without a decision")
                continue
            for clo, chi in halves:
                b = self.enclosure.bound(piece, clo, chi, s.lower if goal is Goal.SUPREMUM else enough)
                s.boxes += 1
                hit = self._visit(s, piece, b, probe)
                if hit is not None:
                    return s.outcome(Stop.FAILED, _INF, refutation=hit)
                if settled(b.upper):
                    s.resolved = max(s.resolved, b.upper)
                else:
                    self._push(s, piece, b)
        if goal is Goal.DECIDE or met(s.upper()):
            return s.outcome(Stop.DONE)
        return s.outcome(Stop.STUCK, reason="boxes shrank to float resolution without closing the gap")

    def _check(self, s: _Search, goal, met, tol, boxes, deadline, start, progress) -> Outcome | None:
        """Report progress; the outcome if the goal is met, the search is stuck, or the budget is spent."""
        top = -s.heap[0][0]
        now = time.monotonic()
        U = s.upper()
        if progress is not None and now - s.last_report >= PROGRESS_SECONDS:
            s.last_report = now
            progress(BranchProgress(s.boxes, s.lower, U, now - start))
        if goal is Goal.SUPREMUM:
            if met(U):
                return s.outcome(Stop.DONE)
            if top <= s.stuck and s.stuck - s.lower > tol():
                return s.outcome(Stop.STUCK, reason="boxes shrank to float resolution without closing the gap")
        if s.boxes >= boxes or now > deadline:
            why = f"box budget of {boxes} spent" if s.boxes >= boxes else "time budget spent"
            return s.outcome(Stop.BUDGET, reason=why)
        return None
