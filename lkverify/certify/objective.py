"""The objective of a branch and bound: a SymPy expression on a region, compiled to arb (value; value and
gradient; affine) and to NumPy, with its Taylor derivative programs (:class:`TaylorPrograms`, compiled on
first use and kept for objectives seen again).

Split from :mod:`lkverify.certify.engine`, which re-exports these names; the engine's strategies
(:class:`~lkverify.certify.engine.Enclosure` and its subclasses) bound an :class:`Objective` on a box.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable, Sequence

import flint
import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from .functions import compile_arb, lambdify_real
from .intervals import compile_program
from .intervals.balls import _JUMPS
from .intervals.convert import _real_dummies
from ..memo import Memo
from .regions import Region

__all__ = ["Objective", "TAYLOR2_MAX_DIMENSION", "TAYLOR3_MAX_DIMENSION", "TAYLOR_CACHE_SIZE", "TaylorPrograms"]

_INF = math.inf

#: :class:`Taylor` compiles third derivatives (n(n+1)(n+2)/6 of them) up to this many variables ...
TAYLOR3_MAX_DIMENSION = 6
#: ... and second derivatives (n(n+1)/2) up to this many; beyond, it is :class:`MeanValue`
TAYLOR2_MAX_DIMENSION = 12
#: compiled derivative programs kept for objectives seen again (the same template in two bound steps)
TAYLOR_CACHE_SIZE = 16
_TAYLOR_CACHE = Memo(TAYLOR_CACHE_SIZE)


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
                hit = _TAYLOR_CACHE.get(key)
                if hit is None:
                    hit = _TAYLOR_CACHE[key] = TaylorPrograms.compile(self, order)
                cache[order] = hit
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
