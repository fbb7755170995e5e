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

:class:`Objective` (with its Taylor derivative programs) is in :mod:`.objective` and
:func:`cube_quadratic_sup` in :mod:`.cube_quadratic`; both are re-exported here.

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
import math
import time
from collections.abc import Callable, Sequence

from flint import arb

from ..errors import InputError
from .affine import AffineForm
from .cube_quadratic import QUADRATIC_BRANCH_DEPTH, cube_quadratic_sup  # re-exported: moved to cube_quadratic
from .intervals import float_down, float_up
from .intervals.balls import _ZERO
from .objective import (TAYLOR2_MAX_DIMENSION, TAYLOR3_MAX_DIMENSION,  # re-exported: moved to objective
                        TAYLOR_CACHE_SIZE, Objective, TaylorPrograms)

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
