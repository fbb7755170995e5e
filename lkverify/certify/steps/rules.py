"""The checked rules of bound steps: each application is matched, its side conditions decided.

A proof bounds one term of V or of the exact V̇ at a time and names the rule, the way
the paper does.  A rule *derives* the bound from the term and its arguments; the step
then accepts the author's stated bound only if it is the derived one or weaker by a
nonnegative remainder.  Every application records its side conditions with a status:

===========================  ==========================================================
:class:`Equal`               term = bound once the measures are replaced by their definitions
:class:`Nonpositive`         term ≤ 0 (a nonpositive constant times nonnegative factors)
:class:`Rayleigh`            c·uᵀMu between c·m·‖u‖² (m ≤ λ_min(M) or m ≥ λ_max(M), exact)
:class:`CauchySchwarz`       |c·uᵀMv| ≤ |c|·κ·‖u‖·‖v‖ with κ ≥ ‖M‖ (κ²I − MᵀM ⪰ 0, exact)
:class:`WindowWeight`        ∫ g·‖v‖^k between (min g)·(measure) and (max g)·(measure), or
                             Hölder with conjugate exponents (p, q), kp = the measure's order
:class:`Template`            term ≤ κ·(monomial of measures): κ the supremum over a chart
                             of the region (certified with arb)
:class:`Young`               c·x·y ≤ c(ε x^p/p + ε^{−q/p} y^q/q), p, q conjugate, ε > 0, c ≥ 0
                             (≤ steps) or c ≤ 0 (≥ steps)
:class:`Homogeneous`         factor·g ≤ factor·κ·T (g, T homogeneous, T > 0 certified): κ the
                             supremum or the infimum of g/T, as the direction and the factor's
                             sign need
:class:`ProductCS`           two Cauchy–Schwarz bounds on a product of two bilinear forms
:class:`Printed`             nothing (the step as printed: only a witness decides it)
===========================  ==========================================================

Each rule's docstring has a table of the inequality it licenses, the directions (≤ steps,
≥ steps) in which it may be used and every side condition; the rule decides each
condition and an application is ``exact`` / ``certified`` only when all hold
(tests/certify/test_rule_side_conditions.py violates each alone).

Vector norms inside the rules are bounded by :class:`Norm` trees: a measure's vector
(:func:`measured`), a unit vector (:func:`unit`), a cross product ‖a × b‖ ≤ ‖a‖‖b‖
(:func:`crossed`), a nonnegative scalar factor (:func:`scaled`) and a window integral
‖∫ g v‖ ≤ ∫ |g|·‖v‖ followed by a weight bound or Hölder (:func:`integral_of`).  A tree
is matched against the vector it bounds exactly (modulo the unit-vector constraints).

Examples
--------
>>> import sympy
>>> from lkverify import Parameters, System, Equation, Term, Vector, t
>>> P = Parameters(); k = P.scalar("k", positive=True, default=2)
>>> x = Vector("x", 2)
>>> sys_ = System([Equation(x, [Term(-k * x(t))])], parameters=P)
>>> from lkverify.certify.steps.measures import norm_measure
>>> n = norm_measure("n", x(t))
>>> ctx = Context(sys_, P.resolve({}), {"n": n})
>>> M = sympy.Matrix([[2, 1], [1, 2]])
>>> app = Rayleigh(x(t), M, eigenvalue=3, norm_squared=n.symbol**2).apply((x(t).T * M * x(t))[0], "upper", ctx)
>>> app.status.value, app.bound
('exact', 3*n**2)
>>> Rayleigh(x(t), M, eigenvalue=2, norm_squared=n.symbol**2).apply((x(t).T * M * x(t))[0], "upper", ctx).detail
'side condition fails: 2·I − M ⪰ 0 (the eigenvalue bound): D ⪰ 0 is false: x = (1, 1) gives xᵀDx = -2 < 0 (exact); λ_min = -1.'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy
from sympy.core.function import AppliedUndef

from ...declare.parameters import apply_substitution
from ...declare.symbols import t, xi
from ...declare.vectors import as_column
from ...errors import InputError
from ...status import Status
from ..matrices import matrix_positive_definite
from .measures import Measure, Region

_T_NONNEGATIVE = sympy.Symbol("t", nonnegative=True)  # t on its domain t ≥ 0 (Context.zero)


def _explicit_time(e) -> bool:
    """Does ``e`` have t outside the state functions (a coefficient h(t), ḣ(t) after the values)?"""
    return any(a.has(t) and not a.atoms(AppliedUndef) for a in sympy.sympify(e).atoms(sympy.Pow, sympy.Function))

__all__ = ["Application", "CauchySchwarz", "Context", "Equal", "Nonpositive", "Norm", "Printed", "Rayleigh", "Rule",
           "Template", "WindowWeight", "Young", "Homogeneous", "crossed", "integral_of", "mapped", "measured", "nonnegative",
           "scaled", "summed", "unit", "decided", "sign_of", "ProductCS", "resolve_norm"]




# -- context --------------------------------------------------------------------------------
@dataclasses.dataclass
class Context:
    """What a rule needs: the system, the parameter values, the measures by name, the region.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); s = UnitVector("s")
    >>> sys_ = System([Equation(s, [Term(0 * s(t))])], parameters=P)
    >>> ctx = Context(sys_, P.resolve({}), {"e": norm_measure("e", s(t))})
    >>> ctx.zero(s(t).dot(s(t)) - 1), ctx.zero(s(t)[0])     # exact modulo ‖s‖ = 1
    (True, False)
    >>> ctx.measure("q")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: unknown measure 'q': expected one of e; declare it with the step's measures
    """

    system: object
    values: Mapping
    measures: Mapping
    region: Region | None = None
    budget: object = None
    constants: Mapping | None = None

    def __post_init__(self):
        self.sub = self.system.parameters.substitution(self.values)
        self.certified = {}  # constants certified inside norm trees: name → (value, info)

    def seconds_left(self, default: float | None = None) -> float | None:
        """Wall-clock seconds for one certification: what is left of the user's budget, at most ``default``.

        Without a budget (the catalogue's default) this is ``default`` — None for the rules'
        suprema, which are then limited by boxes alone, so a verdict does not depend on the
        machine's speed or load.
        """
        from ...options import Deadline

        if isinstance(self.budget, Deadline):
            left = self.budget.remaining
            if left is None:
                return default
            return max(left if default is None else min(left, default), 1e-3)
        if self.budget is None:
            return default
        return max(float(self.budget) if default is None else min(float(self.budget), default), 1e-3)

    def __getitem__(self, name):
        """The resolved value of a parameter (so a callable of the values also works with the context)."""
        return self.values[name]

    def at(self, expr):
        """``expr`` with the parameter values (and the step's named constants) substituted.

        A callable is evaluated as ``expr(ctx)`` (a constant computed from the values,
        e.g. an eigenvalue of a matrix parameter)."""
        if callable(expr) and not isinstance(expr, sympy.Basic):
            expr = expr(self)
        e = sympy.sympify(expr) if not isinstance(expr, sympy.MatrixBase) else expr
        e = apply_substitution(e, self.sub)
        if self.constants:
            e = e.xreplace(self.constants)
        return e

    def definitions(self, expr):
        """``expr`` with every measure symbol replaced by its definition (parameters substituted)."""
        rep = {m.symbol: m.definition for m in self.measures.values() if m.definition is not None}
        return self.at(sympy.sympify(expr).xreplace(rep))

    def measure(self, name: str) -> Measure:
        try:
            return self.measures[name]
        except KeyError:
            raise InputError(f"unknown measure {name!r}: expected one of {', '.join(self.measures)}; declare it "
                             f"with the step's measures") from None

    def pointwise(self, expr):
        """``expr`` with the pointwise-norm symbols of the window measures replaced by their definitions."""
        expr = sympy.sympify(expr)
        present = expr.free_symbols  # only the symbols that occur: each substitution costs
        rep = {m.pointwise_symbol: self.at(m.pointwise()) for m in self.measures.values()
               if m.kind != "norm" and m.pointwise_symbol in present}
        return expr.xreplace(rep)

    def zero(self, expr) -> bool:
        """Is ``expr`` exactly 0 on the state manifold (unit vectors, frames) for t ≥ 0?

        Time runs on t ≥ 0, so explicit powers of t are normalised with t nonnegative
        (√((1+t)^(−7/4)) = (1+t)^(−7/8), as a coefficient h(t) and its measure |h(t)| give) and
        an expression with explicit t is put over one denominator before its numerator is tested.
        """
        e = self.pointwise(self.at(expr))
        if _explicit_time(e):  # on t ≥ 0; then over one denominator (nonzero for t ≥ 0), its numerator
            e = sympy.expand(e.xreplace({t: _T_NONNEGATIVE}).xreplace({_T_NONNEGATIVE: t}))
            if e != 0:
                e = sympy.expand(sympy.fraction(sympy.together(e))[0])
        else:
            e = sympy.expand(e)
        if e == 0:
            return True
        from ...symbolic.canonical import Canonicalizer

        canon = self.__dict__.get("_canonicalizer")  # one per context: its Gröbner bases are reused
        if canon is None:
            canon = self._canonicalizer = Canonicalizer(self.system.constraint_polynomials)
        return canon.normal_forms([e]).polys[0] == 0


@dataclasses.dataclass(frozen=True)
class Condition:
    """A side condition of a rule application and how it was decided."""

    text: str
    status: Status
    detail: str = ""

    def to_json(self) -> dict:
        return {"condition": self.text, "status": self.status.value, "detail": self.detail}


@dataclasses.dataclass(frozen=True)
class Application:
    """One rule applied to one term: the bound it derives and the side conditions checked.

    ``status`` is the weakest of the conditions; ``detail`` names the first that fails.
    """

    rule: str
    bound: object
    conditions: tuple
    constants: tuple = ()  # (name, value, Result-like dict) of constants the rule certified

    @property
    def status(self) -> Status:
        sts = [c.status for c in self.conditions]
        for s in (Status.FAILED, Status.UNDECIDED, Status.CERTIFIED):
            if s in sts:
                return s
        return Status.EXACT

    @property
    def detail(self) -> str:
        for c in self.conditions:
            if not c.status.is_proof:
                return f"side condition fails: {c.text}: {c.detail}"
        return f"{self.rule}: " + "; ".join(c.text for c in self.conditions)

    def to_json(self) -> dict:
        return {"rule": self.rule, "bound": str(self.bound), "status": self.status.value,
                "conditions": [c.to_json() for c in self.conditions],
                "constants": {name: value for name, value, _ in self.constants}}


def decided(text, ok, detail="", *, certified=False) -> Condition:
    """The :class:`Condition` of a decision: ``ok`` True holds, False fails, None is undecided.

    A holding condition is ``exact``, or ``certified`` when the decision went through interval
    arithmetic (``certified=True``).

    Examples
    --------
    >>> decided("q is rational", True).status.value, decided("κ certified", True, certified=True).status.value
    ('exact', 'certified')
    >>> c = decided("the region bounds ‖x‖", None); c.status.value, c.detail
    ('undecided', 'not decided')
    >>> decided("b ≥ 0", False).status.value
    'failed'
    """
    if ok is None:
        return Condition(text, Status.UNDECIDED, detail or "not decided")
    if ok:
        return Condition(text, Status.CERTIFIED if certified else Status.EXACT, detail)
    return Condition(text, Status.FAILED, detail or "does not hold")


_cond = decided


def _fails(rule: str, text: str, detail: str, bound=None) -> Application:
    return Application(rule, bound, (Condition(text, Status.FAILED, detail),))


# -- nonnegativity, structurally --------------------------------------------------------------
def nonnegative(expr) -> bool:
    """True when ``expr`` is ≥ 0 by its structure (sums and products of nonnegative factors).

    Nonnegative factors: nonnegative numbers and symbols, even integer powers, powers
    with a nonnegative base, sums of squares, integrals over windows of nonnegative
    length of nonnegative integrands.  False means "not shown", not "negative".

    >>> import sympy
    >>> x, y = sympy.symbols("x y", real=True)
    >>> nonnegative(3 * (x**2 + y**2) ** sympy.Rational(3, 2)), nonnegative(x * y)
    (True, False)
    """
    e = sympy.sympify(expr)
    if e.is_number:
        return bool(e.is_nonnegative)
    if e.is_nonnegative:
        return True
    if isinstance(e, sympy.Add):
        return all(nonnegative(a) for a in e.args)
    if isinstance(e, sympy.Mul):
        neg = [a for a in e.args if a.is_number and a.is_negative]
        rest = [a for a in e.args if not (a.is_number and a.is_negative)]
        return len(neg) % 2 == 0 and all(nonnegative(a) for a in rest)
    if isinstance(e, sympy.Pow):
        if e.exp.is_Integer and e.exp % 2 == 0:
            return True
        return nonnegative(e.base)
    if isinstance(e, sympy.Integral):
        if any(len(lim) != 3 for lim in e.limits):
            return False
        widths = [sympy.simplify(lim[2] - lim[1]) for lim in e.limits]
        return all(w.is_nonnegative for w in widths) and nonnegative(e.function)
    if isinstance(e, sympy.Abs):
        return True
    return False


def _constant_and_monomial(expr, symbols):
    """(c, monomial) with expr = c·monomial, c free of ``symbols``; None if expr is not a single product."""
    e = sympy.factor_terms(sympy.sympify(expr))
    if isinstance(e, sympy.Add):
        return None
    c, m = sympy.S.One, sympy.S.One
    for f in sympy.Mul.make_args(e):
        if f.free_symbols & set(symbols):
            m *= f
        else:
            c *= f
    return c, m


def _factor_sign(c, measure_symbols) -> int | None:
    """The sign of a factor: a constant of known sign times nonnegative measures, or structurally signed."""
    c = sympy.sympify(c)
    if nonnegative(c):
        return 1
    if nonnegative(-c):
        return -1
    cm = _constant_and_monomial(c, measure_symbols)
    if cm is not None and nonnegative(cm[1]):
        return _sign(cm[0])
    return None


def _abs_factor(c, measure_symbols):
    """|c| as an expression: ±c when the sign is known, else |constant|·(nonnegative measures)."""
    sign = _factor_sign(c, measure_symbols)
    if sign is not None:
        return sign * sympy.sympify(c)
    cm = _constant_and_monomial(c, measure_symbols)
    if cm is not None and nonnegative(cm[1]):
        return sympy.Abs(cm[0]) * cm[1]
    return None


def sign_of(expr) -> int | None:
    """+1 (≥ 0), −1 (≤ 0) or None, for a constant expression (parameters with assumptions allowed).

    Examples
    --------
    >>> import sympy
    >>> a = sympy.Symbol("a", positive=True)
    >>> sign_of(a ** 2 + 1), sign_of(-3 * a), sign_of(a - 1)
    (1, -1, None)
    """
    e = sympy.sympify(expr)
    if e.is_nonnegative or nonnegative(e):
        return 1
    if e.is_nonpositive or nonnegative(-e):
        return -1
    return None


_sign = sign_of


# -- norm trees -------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Norm:
    """An upper bound ``‖vector‖ ≤ bound``, with how it follows (see the constructors below).

    ``vector`` is in the model's vocabulary, ``bound`` in measures (at t) or in pointwise
    norms at ξ (inside a window integral).
    """

    how: str
    vector: object
    bound: object
    parts: tuple = ()
    conditions: tuple = ()
    data: tuple = ()

    def all_conditions(self) -> list:
        out = list(self.conditions)
        for p in self.parts:
            if isinstance(p, Norm):
                out += p.all_conditions()
        return out


def measured(measure: Measure, *, at=None) -> Norm:
    """‖v‖ = the measure, for its own vector (``at=xi``: pointwise inside a window integral).

    Examples
    --------
    >>> from lkverify import Vector, t, xi
    >>> from lkverify.certify.steps.measures import norm_measure, window_norm
    >>> x = Vector("x", 2)
    >>> measured(norm_measure("n", x(t))).bound                    # ‖x(t)‖ = n
    n
    >>> measured(window_norm("j", x(xi), p=3, window=1), at=xi).bound   # ‖x(ξ)‖ inside a window integral
    j_xi
    """
    if measure.kind == "norm" and at is None:
        return Norm(f"{measure.text} = {measure.name}", measure.vector, measure.symbol)
    if measure.kind == "sup":
        raise InputError(f"measured({measure.name}): a sup measure bounds norms pointwise; use it in a region")
    vec = measure.vector if measure.kind != "norm" else measure.vector.subs(t, xi)
    return Norm(f"‖v(ξ)‖ of {measure.name}", vec, measure.pointwise_symbol)


def unit(vector) -> Norm:
    """‖u‖ = 1 for a unit state or a unit parameter vector (checked where it is used).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, Vector, cross, t
    >>> P = Parameters(); s, omega = UnitVector("s"), Vector("omega")
    >>> sys_ = System([Equation(omega, [Term(-omega(t))]), Equation(s, [Term(-cross(omega(t), s(t)))])], parameters=P)
    >>> ctx = Context(sys_, P.resolve({}), {})
    >>> CauchySchwarz(s(t), s(t), (unit(s(t)), unit(s(t)))).apply(s(t).dot(s(t)), "upper", ctx).bound
    1
    >>> CauchySchwarz(omega(t), s(t), (unit(omega(t)), unit(s(t)))).apply(omega(t).dot(s(t)), "upper", ctx).detail
    'side condition fails: it is a unit vector: not a unit state or unit parameter'
    """
    return Norm("unit vector", sympy.ImmutableMatrix(as_column(vector)), sympy.S.One)


def crossed(a: Norm, b: Norm) -> Norm:
    """‖a × b‖ ≤ ‖a‖‖b‖.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, Vector, cross, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); s, omega = UnitVector("s"), Vector("omega"); r = sympy.Matrix([0, 0, 1])
    >>> sys_ = System([Equation(omega, [Term(-omega(t))]), Equation(s, [Term(-cross(omega(t), s(t)))])], parameters=P)
    >>> w, e = norm_measure("w", omega(t)), norm_measure("e", s(t) - r)
    >>> ctx = Context(sys_, P.resolve({}), {"w": w, "e": e})
    >>> nb = crossed(measured(e), unit(r))                # ‖(s − r) × r‖ = ‖s × r‖ ≤ e·1
    >>> app = CauchySchwarz(omega(t), s(t).cross(r), (measured(w), nb)).apply(omega(t).dot(s(t).cross(r)), "upper", ctx)
    >>> nb.bound, app.status.value, app.bound
    (e, 'exact', e*w)
    """
    va, vb = sympy.Matrix(a.vector), sympy.Matrix(b.vector)
    bound = None if a.bound is None or b.bound is None else a.bound * b.bound
    return Norm("‖a×b‖ ≤ ‖a‖‖b‖", sympy.ImmutableMatrix(va.cross(vb)), bound, (a, b))


def scaled(factor, inner: Norm) -> Norm:
    """‖c·v‖ = |c|·‖v‖ for a scalar factor c that is nonnegative (checked structurally) or constant.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"n": n})
    >>> rule = CauchySchwarz(x(t), 2 * x(t), (measured(n), scaled(2, measured(n))))
    >>> app = rule.apply(2 * x(t).dot(x(t)), "upper", ctx)
    >>> app.status.value, app.bound                        # ‖2x‖ = 2‖x‖
    ('exact', 2*n**2)
    >>> CauchySchwarz(x(t), 2 * x(t), (measured(n), scaled(3, measured(n)))).apply(
    ...     2 * x(t).dot(x(t)), "upper", ctx).status.value   # 3x is not the vector 2x
    'failed'
    """
    c = sympy.sympify(factor)
    cond = _cond(f"the factor {c} is ≥ 0", nonnegative(c) or None if not c.is_number else bool(c >= 0),
                 "" if nonnegative(c) else "not shown nonnegative")
    return Norm(f"|c|·‖v‖ (c = {c})", sympy.ImmutableMatrix(sympy.Matrix(inner.vector) * c),
                None if inner.bound is None else c * inner.bound, (inner,), (cond,), data=(c,))


def summed(*parts: Norm) -> Norm:
    """‖a + b + …‖ ≤ ‖a‖ + ‖b‖ + … (the triangle inequality)."""
    vec = sympy.zeros(*sympy.Matrix(parts[0].vector).shape)
    for p in parts:
        vec += sympy.Matrix(p.vector)
    bound = None if any(p.bound is None for p in parts) else sum((p.bound for p in parts), sympy.S.Zero)
    return Norm("‖a+b‖ ≤ ‖a‖+‖b‖", sympy.ImmutableMatrix(vec), bound, parts)


def mapped(matrix, inner: Norm, operator_norm) -> Norm:
    """‖M v‖ ≤ κ‖v‖ with κ ≥ ‖M‖: κ ≥ 0 and κ²I − MᵀM ⪰ 0, both decided where it is used.

    κ may be a callable of the context.  Side conditions: the vector is exactly M·v (on the
    state manifold); κ ≥ 0; κ²I − MᵀM ⪰ 0; the inner tree's own conditions.
    """
    return Norm("‖Mv‖ ≤ κ‖v‖", sympy.ImmutableMatrix(sympy.Matrix(matrix) * sympy.Matrix(inner.vector)), None,
                (inner,), data=(sympy.ImmutableMatrix(matrix), operator_norm))


def integral_of(pointwise: Norm, *, measure=None, power, weight=1, window=None, holder=None, measures=(),
                constant: str | None = None) -> Norm:
    """‖∫_{t−h}^t g(ξ) v(ξ) dξ‖ ≤ ∫ |g|‖v(ξ)‖ ≤ (weight bound or Hölder)·(measure).

    ``pointwise`` bounds ‖v(ξ)‖ by the measure's pointwise norm to ``power`` k.  With
    ``holder=None`` the measure must be ``window_integral`` of order k (or
    ``window_norm`` of order k) and the bound is max|g|·measure; with ``holder=(p, q)``
    (1/p + 1/q = 1, k·p = the measure's order) it is (∫|g|^q)^{1/q}·measure^k.

    With ``measures=(M1, M2, …)`` (window integrals of order k of several vectors) the
    pointwise bound B(ξ) in their pointwise norms P_i(ξ) is compared with Σ P_i^k: equal, or
    (``constant`` named) homogeneous of degree k with κ = sup B/Σ P_i^k certified
    (:class:`Homogeneous`); the bound is then max g·κ·Σ M_i.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, norm_power, t, window_integral, xi
    >>> from lkverify.certify.steps.measures import norm_measure, window_norm
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> w, j = norm_measure("w", y(t)), window_norm("j", x(xi), p=3, window=1)
    >>> ctx = Context(sys_, P.resolve({}), {"w": w, "j": j})
    >>> J = window_integral(norm_power(x(xi), 1) * x(xi), 1)    # ‖∫‖x‖x‖ ≤ (∫‖x‖³)^{2/3} = j²
    >>> pw = scaled(norm_power(x(xi), 1), measured(j, at=xi))
    >>> holder = integral_of(pw, measure=j, power=2, holder=(sympy.Rational(3, 2), 3))
    >>> CauchySchwarz(y(t), J, (measured(w), holder)).apply(y(t).dot(J), "upper", ctx).bound
    j**2*w
    >>> wrong = integral_of(pw, measure=j, power=2, holder=(2, 2))
    >>> CauchySchwarz(y(t), J, (measured(w), wrong)).apply(y(t).dot(J), "upper", ctx).status.value
    'failed'
    """
    if measures:
        return Norm("window integral of a sum", ("integrals", pointwise, tuple(measures), sympy.sympify(power),
                                                 sympy.sympify(weight), constant), None, (pointwise,))
    return Norm("window integral", ("integral", pointwise, measure, sympy.sympify(power), sympy.sympify(weight),
                                    window, holder), None, (pointwise,))


def _window_factor(g, lo, hi, measure: Measure, k, holder, ctx: Context, *, lower=False):
    """(factor, conditions): ∫_{lo}^{hi} g·P^k ≤ factor·(measure-power), P the pointwise norm."""
    conds = []
    g = sympy.expand(ctx.at(g))
    order = ctx.at(measure.power)
    width = sympy.simplify(hi - lo)
    mw = sympy.simplify(ctx.at(measure.window))
    conds.append(_cond(f"the window [{lo}, {hi}] is the measure's window of length {mw}",
                       bool(sympy.simplify(width - mw) == 0) and bool(sympy.simplify(hi - t) == 0),
                       f"window of length {width}"))
    # g on the window: a polynomial in ξ, bounded at the ends and critical points
    try:
        poly = sympy.Poly(g, xi)
    except sympy.PolynomialError:
        return None, conds + [_cond("the weight is a polynomial in ξ", False, f"got {g}")]
    crit = [lo, hi]
    d = poly.diff(xi)
    if d.degree() > 0:
        for root in sympy.roots(d.as_expr(), xi, multiple=True):
            crit.append(root)
    vals = [sympy.simplify(g.subs(xi, c)) for c in crit]
    # only interior critical points matter; with parameters in g we use the ends for linear weights
    if poly.degree() > 1:
        return None, conds + [_cond("the weight is affine in ξ", False, f"degree {poly.degree()}")]
    vals = [sympy.simplify(g.subs(xi, lo)), sympy.simplify(g.subs(xi, hi))]
    if holder is None:
        if measure.kind == "window_integral":
            ok = bool(sympy.simplify(order - k) == 0)
            conds.append(_cond(f"the integrand's power {k} is the measure's order {order}", ok))
            mpow = 1
        elif measure.kind == "window_norm":
            ok = bool(sympy.simplify(order - k) == 0)
            conds.append(_cond(f"the integrand's power {k} is the measure's order {order}", ok))
            mpow = order
        else:
            return None, conds + [_cond("a window measure", False, f"{measure.name} is a {measure.kind}")]
        if lower:
            lo_vals = [v for v in vals]
            gmin = sympy.Min(*lo_vals) if len(set(lo_vals)) > 1 else lo_vals[0]
            s_ = _sign(gmin)
            conds.append(_cond(f"the weight is ≥ {gmin} ≥ 0 on the window (affine: its ends)", s_ == 1 or None))
            return (gmin, mpow), conds
        signs = [_sign(v) for v in vals]
        conds.append(_cond("the weight is ≥ 0 on the window (affine: its ends)", all(s_ == 1 for s_ in signs) or None,
                           f"ends {vals}"))
        gmax = vals[0] if len(set(vals)) == 1 else _max_of(vals)
        return (gmax, mpow), conds
    p, q = (ctx.at(x) for x in holder)
    conds.append(conjugate_exponents(p, q))
    if measure.kind != "window_norm":
        return None, conds + [_cond("Hölder needs a window norm (∫‖v‖^p)^{1/p}", False, f"{measure.name} is a "
                                    f"{measure.kind}")]
    conds.append(_cond(f"k·p = {k}·{p} is the measure's order {order}", bool(sympy.simplify(k * p - order) == 0),
                       f"k·p = {k * p}"))
    signs = [_sign(v) for v in vals]
    conds.append(_cond("the weight is ≥ 0 on the window (affine: its ends)", all(s_ == 1 for s_ in signs) or None))
    gq = sympy.integrate(g ** q, (xi, lo, hi))
    return (sympy.simplify(gq) ** (1 / q), k), conds


def _max_of(vals):
    d = sympy.simplify(vals[0] - vals[1])
    if d.is_nonnegative:
        return vals[0]
    if d.is_nonpositive:
        return vals[1]
    return sympy.Max(*vals)


def resolve_norm(nb: Norm, vector, ctx: Context) -> tuple:
    """(bound, conditions) proving ‖vector‖ ≤ bound by the norm tree ``nb`` (vector matched exactly).

    What a rule with a norm tree does inside; public for proof modules whose own conditions need a
    norm bound (a ``LowerBound``/``UpperBound`` check).  ``bound`` is None when the tree does not
    match; each condition carries its status.
    """
    conds = []
    vec = sympy.Matrix(ctx.at(sympy.Matrix(vector)))
    if callable(getattr(nb, "resolve", None)):  # a norm bound that resolves itself (steps.memory)
        return nb.resolve(vec, ctx, vector)
    if isinstance(nb.vector, tuple) and nb.vector[0] == "integrals":
        _, pointwise, measures, k, weight, constant = nb.vector
        return _resolve_integrals(vec, pointwise, measures, ctx.at(k), weight, constant, ctx, vector)
    if isinstance(nb.vector, tuple) and nb.vector[0] == "integral":
        _, pointwise, measure, k, weight, _window, holder = nb.vector
        k = ctx.at(k)
        parsed = _integrand(vec, pointwise, weight, ctx, vector)
        if parsed[0] is None:
            return None, parsed[1]
        (g, lo, hi, pb), pconds = parsed
        conds += pconds
        if pb is None:
            return None, conds
        P = measure.pointwise()
        conds.append(_cond(f"‖v(ξ)‖ ≤ ‖{measure.name}(ξ)‖^{k}", ctx.zero(ctx.pointwise(pb) - P ** k),
                           f"the pointwise bound is {pb}"))
        fac, wconds = _window_factor(g, lo, hi, measure, k, holder, ctx)
        conds += wconds
        if fac is None:
            return None, conds
        factor, mpow = fac
        return factor * measure.symbol ** mpow, conds
    if nb.how.startswith("‖Mv‖"):
        (inner,), (Mraw, kappa_raw) = nb.parts, nb.data
        M = sympy.Matrix(ctx.at(sympy.Matrix(Mraw)))
        kappa = ctx.at(kappa_raw)
        target = M * sympy.Matrix(ctx.at(sympy.Matrix(inner.vector)))
        if target.shape != vec.shape or not all(ctx.zero(x) for x in vec - target):
            return None, [_cond("the vector is M·v (‖Mv‖ ≤ κ‖v‖)", False, f"{list(vec)} is not {list(target)}")]
        conds += operator_norm_conditions(M, kappa)
        bi, ci = _resolve_norm(inner, inner.vector, ctx)
        conds += ci
        return (None if bi is None else kappa * bi), conds
    target = sympy.Matrix(ctx.at(sympy.Matrix(nb.vector)))
    if target.shape != vec.shape or not all(ctx.zero(x) for x in vec - target):
        return None, [_cond(f"the vector matches the norm bound's ({nb.how})", False,
                            f"{list(vec)} is not {list(target)}")]
    conds.append(_cond(f"the vector matches ({nb.how})", True))
    if nb.how == "unit vector":
        conds.append(_cond("it is a unit vector", _is_unit(vec, ctx), "not a unit state or unit parameter"))
        return sympy.S.One, conds
    if nb.how.startswith("‖a+b‖"):
        total = sympy.S.Zero
        for part in nb.parts:
            bp, cp = _resolve_norm(part, part.vector, ctx)
            conds += cp
            if bp is None:
                return None, conds
            total += bp
        return total, conds
    if nb.how.startswith("‖a×b‖"):
        a, b = nb.parts
        ba, ca = _resolve_norm(a, a.vector, ctx)
        bb, cb = _resolve_norm(b, b.vector, ctx)
        conds += ca + cb
        if ba is None or bb is None:
            return None, conds
        return ba * bb, conds
    if nb.how.startswith("|c|"):
        (inner,) = nb.parts
        bi, ci = _resolve_norm(inner, inner.vector, ctx)
        conds += ci + list(nb.conditions)
        if bi is None:
            return None, conds
        return ctx.at(nb.data[0]) * bi, conds
    return nb.bound, conds


_resolve_norm = resolve_norm


def _integrand(vec, pointwise, weight, ctx: Context, vector):
    """((g, lo, hi, pointwise bound), conditions) of a window integral ∫_{lo}^{hi} g(ξ)v(ξ)dξ, or (None, conditions)."""
    ints = list(vec)
    if not all(isinstance(c, sympy.Integral) and len(c.limits) == 1 for c in ints):
        return None, [_cond("the vector is a window integral ∫ g(ξ)v(ξ)dξ", False, f"got {vector}")]
    var, lo, hi = ints[0].limits[0]
    if any(c.limits[0] != (var, lo, hi) for c in ints):
        return None, [_cond("the components integrate over one window", False)]
    inner = sympy.Matrix([c.function for c in ints]).subs(var, xi)
    g = ctx.at(weight)
    pv = sympy.Matrix(ctx.at(sympy.Matrix(pointwise.vector)))
    conds = [_cond(f"the integrand is g(ξ)·v(ξ) with g = {g}", all(ctx.zero(x) for x in inner - g * pv), "it is not")]
    pb, pconds = _resolve_norm(pointwise, pv, ctx)
    return (g, lo, hi, pb), conds + pconds


def pointwise_constant(pb, measures, ps, k, constant, ctx: Context, same) -> tuple:
    """(κ, conditions) with B ≤ κ Σ‖v_i(ξ)‖^k for the pointwise bound ``pb`` of an integrand (κ None: not proved).

    ``pb`` is written in the measures' pointwise norms, renamed to ``ps``; B = Σ p_i^k gives κ = 1 when
    ``same(B − Σ p_i^k)`` holds, otherwise the homogeneous supremum is certified as ``constant`` (recorded
    in ``ctx.certified``).  Shared by window integrals (:func:`integral_of`) and memory integrals
    (``steps.memory``).
    """
    B = sympy.sympify(ctx.at(pb)).xreplace({m.pointwise_symbol: p for m, p in zip(measures, ps)})
    if B.atoms(AppliedUndef):
        return None, [_cond("the pointwise bound is written in the measures' pointwise norms", False, f"got {pb}")]
    T = sum((p**k for p in ps), sympy.S.Zero)
    if same(B - T):
        return sympy.S.One, []
    if constant is None:
        return None, [_cond(f"the pointwise bound is Σ‖v_i(ξ)‖^{k}", False, f"got {B}; name a constant= to "
                            f"certify a homogeneous bound")]
    kappa, hconds, info = _homogeneous_sup(B, T, ps, ctx.seconds_left())
    if kappa is not None:
        ctx.certified[constant] = (info["certified"], info)
    return kappa, list(hconds)


def _resolve_integrals(vec, pointwise, measures, k, weight, constant, ctx: Context, vector):
    """‖∫ g v‖ ≤ max g · κ · Σ M_i for window-integral measures M_i of order k (see :func:`integral_of`)."""
    parsed = _integrand(vec, pointwise, weight, ctx, vector)
    if parsed[0] is None:
        return None, parsed[1]
    (g, lo, hi, pb), conds = parsed
    if pb is None:
        return None, conds
    ps = [sympy.Symbol(f"p_{m.name}", nonnegative=True) for m in measures]
    for m in measures:
        conds.append(_cond(f"{m.name} is a window integral of order {k}", m.kind == "window_integral"
                           and sympy.simplify(ctx.at(m.power) - k) == 0, f"{m.kind} of order {m.power}"))
    kappa, kconds = pointwise_constant(pb, measures, ps, k, constant, ctx, ctx.zero)
    conds += kconds
    if kappa is None:
        return None, conds
    fac, wconds = _window_factor(g, lo, hi, measures[0], k, None, ctx)
    conds += [c for c in wconds if "the integrand's power" not in c.text]
    if fac is None:
        return None, conds
    gmax, _ = fac
    return gmax * kappa * sum((m.symbol for m in measures), sympy.S.Zero), conds


def operator_norm_conditions(M, kappa) -> list:
    """The side conditions of ‖M v‖ ≤ κ‖v‖: κ ≥ 0 and κ²I − MᵀM ⪰ 0 (decided exactly, or in arb).

    Both are needed: κ²I − MᵀM ⪰ 0 alone also holds for κ = −‖M‖.

    Examples
    --------
    >>> import sympy
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), 1)]
    ['exact', 'exact']
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), sympy.Rational(1, 2))]
    ['exact', 'failed']
    >>> [c.status.value for c in operator_norm_conditions(sympy.eye(2), -1)]
    ['failed', 'exact']
    """
    M = sympy.Matrix(M)
    kappa = sympy.sympify(kappa)
    sk = _sign(kappa)
    conds = [_cond(f"κ = {kappa} ≥ 0", True if sk == 1 else (False if kappa.is_negative else None),
                   "κ is negative" if kappa.is_negative else "the sign of κ is not known")]
    res = matrix_positive_definite(kappa**2 * sympy.eye(M.shape[1]) - M.T * M, name="κ²I − MᵀM", semidefinite=True)
    conds.append(Condition(f"κ = {kappa} ≥ ‖M‖ (κ²I − MᵀM ⪰ 0)", res.status if res.status.is_proof else
                           (Status.FAILED if res.status is Status.FAILED else Status.UNDECIDED),
                           "" if res.status.is_proof else f"the operator norm is larger: {res.detail}"))
    return conds


def _is_unit(vec, ctx: Context) -> bool:
    return ctx.zero(sum(x**2 for x in vec) - 1)


# -- rules --------------------------------------------------------------------------------------
class Rule:
    """A checked rule.  ``apply(term, direction, ctx)`` → :class:`Application` (direction "upper": term ≤ bound)."""

    name = "rule"

    def apply(self, term, direction: str, ctx: Context) -> Application:  # pragma: no cover - interface
        raise NotImplementedError


@dataclasses.dataclass(frozen=True)
class Printed(Rule):
    """The step as the paper prints it, with no checkable rule ("there exist constants c_k …").

    It never proves anything: the step is only decided by an adversarial witness
    (``failed``) or stays ``undecided``.


    ==============================  ==========================================================
    licenses                        nothing: the application is ``undecided``
    direction                       both
    side conditions                 none can hold: only a witness decides the step (``failed``)
    ==============================  ==========================================================

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); x = Vector("x", 2)
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {})
    >>> app = Printed("Lemma 2").apply(x(t)[0] * x(t)[1], "upper", ctx)
    >>> app.status.value, app.bound
    ('undecided', None)
    >>> app.detail
    'side condition fails: a rule for the printed step (Lemma 2): the paper names none; only a witness can decide it'
    """

    reference: str = ""
    name = "as printed (no checkable rule named)"

    def apply(self, term, direction, ctx):
        where = f" ({self.reference})" if self.reference else ""
        return Application(self.name, None, (Condition(f"a rule for the printed step{where}", Status.UNDECIDED,
                                                       "the paper names none; only a witness can decide it"),))


@dataclasses.dataclass(frozen=True)
class Equal(Rule):
    """The term equals the bound once the measures are replaced by their definitions (exactly).


    ==============================  ==========================================================
    licenses                        term = bound (measures replaced by their definitions)
    direction                       both (an equality)
    side conditions                 the difference is 0 exactly on the state manifold (unit
                                    vectors, frames), t ≥ 0
    ==============================  ==========================================================

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"n": n})
    >>> Equal(n.symbol ** 2).apply(x(t).dot(x(t)), "upper", ctx).status.value     # ‖x‖² = n²
    'exact'
    >>> Equal(2 * n.symbol ** 2).apply(x(t).dot(x(t)), "upper", ctx).detail
    'side condition fails: the term is 2*n**2 exactly: they differ'
    """

    name = "equality (definition of the measures)"
    bound: object = None

    def apply(self, term, direction, ctx):
        diff = ctx.definitions(self.bound) - ctx.at(term)
        ok = ctx.zero(diff)
        return Application(self.name, ctx.at(self.bound),
                           (_cond(f"the term is {self.bound} exactly", ok, "they differ"),))


@dataclasses.dataclass(frozen=True)
class Nonpositive(Rule):
    """term ≤ 0 (direction "upper") or term ≥ 0 ("lower"): a signed constant times nonnegative factors.


    ==============================  ==========================================================
    licenses                        term ≤ 0 (≤ step), term ≥ 0 (≥ step)
    direction                       both, with the sign the direction needs
    side conditions                 −term (≤ step) or term (≥ step) is structurally ≥ 0
                                    (:func:`nonnegative`)
    ==============================  ==========================================================

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); x = Vector("x", 2)
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {})
    >>> app = Nonpositive().apply(-3 * x(t)[0] ** 2, "upper", ctx)
    >>> app.status.value, app.bound
    ('exact', 0)
    >>> Nonpositive().apply(x(t)[0] * x(t)[1], "upper", ctx).detail
    'side condition fails: the term is ≤ 0: x_1(t)*x_2(t) is not shown to have that sign'
    """

    name = "a term of known sign dropped"

    def apply(self, term, direction, ctx):
        e = ctx.at(term)
        target = -e if direction == "upper" else e
        ok = nonnegative(sympy.factor_terms(target)) or nonnegative(sympy.expand(target))
        return Application(self.name, sympy.S.Zero,
                           (_cond(f"the term is {'≤' if direction == 'upper' else '≥'} 0", ok or None,
                                  f"{e} is not shown to have that sign"),))


@dataclasses.dataclass(frozen=True)
class Rayleigh(Rule):
    """c·uᵀMu ≤ c·m·‖u‖² (c ≥ 0, m ≥ λ_max) or ≥ (c ≥ 0, m ≤ λ_min), and the reverse for c ≤ 0.

    ``factor`` c may contain measures (e.g. −(a − τb)‖s − r‖^{μ−1} = −(a − τb)e^{μ−1});
    ``norm_squared`` is ‖u‖² in measures, checked exactly (modulo unit constraints, so
    ‖s × r‖² = e²(1 − e²/4) is an allowed unit-vector identity).


    ==============================  ==========================================================
    licenses                        λ_min‖u‖² ≤ uᵀMu ≤ λ_max‖u‖², multiplied by c
    direction                       ≤ with c ≥ 0 or ≥ with c ≤ 0: m ≥ λ_max (mI − M ⪰ 0);
                                    ≥ with c ≥ 0 or ≤ with c ≤ 0: m ≤ λ_min (M − mI ⪰ 0)
    side conditions                 M symmetric; the term is c·uᵀMu; the sign of c known; the
                                    eigenvalue bound (exact LDLᵀ, or arb); ‖u‖² = the stated
                                    expression in measures (exact on the state manifold)
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"n": n})
    >>> M = sympy.Matrix([[2, 1], [1, 2]]); quad = (x(t).T * M * x(t))[0]    # eigenvalues 1, 3
    >>> app = Rayleigh(x(t), M, eigenvalue=1, norm_squared=n.symbol ** 2).apply(quad, "lower", ctx)
    >>> app.status.value, app.bound
    ('exact', n**2)
    >>> Rayleigh(x(t), M, eigenvalue=2, norm_squared=n.symbol ** 2).apply(quad, "lower", ctx).status.value
    'failed'
    """

    vector: object
    matrix: object
    factor: object = 1
    eigenvalue: object = None
    norm_squared: object = None
    name = "Rayleigh quotient (eigenvalue bound)"

    def apply(self, term, direction, ctx):
        u = sympy.Matrix(ctx.at(sympy.Matrix(as_column(self.vector))))
        M = sympy.Matrix(ctx.at(sympy.Matrix(self.matrix)))
        c = ctx.at(self.factor)
        conds = [_cond("M is symmetric", M.is_square and all(ctx.zero(d) for d in M - M.T), "M ≠ Mᵀ")]
        conds.append(_cond(f"the term is ({self.factor})·uᵀMu", ctx.zero(ctx.definitions(c) * (u.T * M * u)[0]
                                                                          - ctx.at(term)), "it is not"))
        if not conds[0].status.is_proof:  # the eigenvalue bounds below are those of a symmetric M
            return Application(self.name, None, tuple(conds))
        sign = _factor_sign(c, [m.symbol for m in ctx.measures.values()])
        if sign is None:
            conds.append(_cond("the factor's sign is known", None, f"{c}"))
            return Application(self.name, None, tuple(conds))
        m = ctx.at(self.eigenvalue)
        want_max = (direction == "upper") == (sign > 0)
        n = M.shape[0]
        D = m * sympy.eye(n) - M if want_max else M - m * sympy.eye(n)
        res = matrix_positive_definite(D, name="D", semidefinite=True)
        text = f"{m}·I − M ⪰ 0 (the eigenvalue bound)" if want_max else f"M − {m}·I ⪰ 0 (the eigenvalue bound)"
        conds.append(Condition(text, res.status if res.status.is_proof else
                               (Status.FAILED if res.status is Status.FAILED else Status.UNDECIDED),
                               res.detail if not res.status.is_proof else ""))
        ns = ctx.at(self.norm_squared)
        conds.append(_cond(f"‖u‖² = {ns}", ctx.zero(ctx.definitions(ns) - (u.T * u)[0]),
                           "not an identity on the state manifold"))
        return Application(self.name, sympy.expand(c * m * ns), tuple(conds))


@dataclasses.dataclass(frozen=True)
class CauchySchwarz(Rule):
    """|c·uᵀMv| ≤ |c|·κ·‖u‖·‖v‖ with κ ≥ ‖M‖ (κ ≥ 0 and κ²I − MᵀM ⪰ 0, exact).

    ``norms`` are the :class:`Norm` trees of u and v; ``matrix`` defaults to I
    (κ = 1).  For ``direction="lower"`` the bound is −|c|κ‖u‖‖v‖.


    ==============================  ==========================================================
    licenses                        |c·uᵀMv| ≤ |c|·κ·‖u‖·‖v‖ ≤ |c|·κ·B_u·B_v
    direction                       both (≤ gives +|c|κB_uB_v, ≥ gives −|c|κB_uB_v)
    side conditions                 the term is c·uᵀMv; κ ≥ 0 and κ²I − MᵀM ⪰ 0 — also for
                                    M = I (κ ≥ 1) when no matrix is given; |c| known; the norm
                                    trees B_u, B_v match u, v and their own conditions hold
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"n": n})
    >>> A = sympy.Matrix([[3, 0], [0, 1]]); term = (x(t).T * A * x(t))[0]
    >>> ok = CauchySchwarz(x(t), x(t), (measured(n), measured(n)), matrix=A, operator_norm=3).apply(term, "upper", ctx)
    >>> ok.status.value, ok.bound
    ('exact', 3*n**2)
    >>> small = CauchySchwarz(x(t), x(t), (measured(n), measured(n)), matrix=A, operator_norm=2)
    >>> small.apply(term, "upper", ctx).status.value          # ‖A‖ = 3 > 2
    'failed'
    """

    u: object
    v: object
    norms: tuple
    matrix: object = None
    factor: object = 1
    operator_norm: object = None
    name = "Cauchy–Schwarz with an operator norm"

    def apply(self, term, direction, ctx):
        u = sympy.Matrix(ctx.at(sympy.Matrix(as_column(self.u))))
        v = sympy.Matrix(ctx.at(sympy.Matrix(as_column(self.v))))
        n = u.shape[0]
        M = sympy.eye(n) if self.matrix is None else sympy.Matrix(ctx.at(sympy.Matrix(self.matrix)))
        c = ctx.at(self.factor)
        conds = [_cond(f"the term is ({self.factor})·uᵀMv",
                       ctx.zero(ctx.definitions(c) * (u.T * M * v)[0] - ctx.at(term)), "it is not")]
        kappa = sympy.S.One if self.operator_norm is None and self.matrix is None else ctx.at(self.operator_norm)
        if kappa is None:
            return Application(self.name, None, tuple(conds) + (_cond("an operator norm κ is given", False),))
        # κ is checked against the true operator norm whether M is given or is the identity (‖I‖ = 1)
        conds += operator_norm_conditions(M, kappa)
        bu, cu = _resolve_norm(self.norms[0], u, ctx)
        bv, cv = _resolve_norm(self.norms[1], v, ctx)
        conds += cu + cv
        absc = _abs_factor(c, [m.symbol for m in ctx.measures.values()])
        if absc is None:
            conds.append(_cond("|factor| is known (a constant times nonnegative measures, or of known sign)", None,
                               f"{c}"))
            return Application(self.name, None, tuple(conds))
        if bu is None or bv is None:
            return Application(self.name, None, tuple(conds))
        bound = sympy.expand(absc * kappa * bu * bv)
        return Application(self.name, bound if direction == "upper" else -bound, tuple(conds))


@dataclasses.dataclass(frozen=True)
class ProductCS(Rule):
    """|c·(uᵀAv)(xᵀBy)| ≤ |c|·κ_A‖u‖‖v‖·κ_B‖x‖‖y‖: two Cauchy–Schwarz bounds of a product of two bilinear forms.

    ``first`` and ``second`` are :class:`~lkverify.certify.steps.rules.CauchySchwarz` rules (factor 1) for
    the two forms; the term must be exactly ``factor``·(first form)·(second form) (checked on the state
    manifold, measures in the factor by their definitions); every side condition of both is kept.

    ==============================  ==========================================================
    licenses                        |c·(uᵀAv)(xᵀBy)| ≤ |c|·(κ_A B_u B_v)(κ_B B_x B_y)
    direction                       both (±)
    side conditions                 the term is the product; every condition of both
                                    :class:`CauchySchwarz` applications; |c| known
    ==============================  ==========================================================
    """

    first: CauchySchwarz
    second: CauchySchwarz
    factor: object = 1
    name = "Cauchy–Schwarz on each factor of a product of two bilinear forms"

    @staticmethod
    def _form(cs, ctx):
        u, v = (sympy.Matrix(ctx.at(sympy.Matrix(x))) for x in (cs.u, cs.v))
        M = sympy.eye(u.shape[0]) if cs.matrix is None else sympy.Matrix(ctx.at(sympy.Matrix(cs.matrix)))
        return (u.T * M * v)[0]

    def apply(self, term, direction, ctx):
        c = ctx.at(self.factor)
        p1, p2 = self._form(self.first, ctx), self._form(self.second, ctx)
        conds = [_cond(f"the term is ({self.factor})·(uᵀAv)(xᵀBy)",
                       ctx.zero(ctx.definitions(c) * p1 * p2 - ctx.at(term)), "it is not")]
        a1_, a2_ = self.first.apply(p1, "upper", ctx), self.second.apply(p2, "upper", ctx)
        conds += list(a1_.conditions) + list(a2_.conditions)
        absc = _abs_factor(c, [m.symbol for m in ctx.measures.values()])
        if absc is None or a1_.bound is None or a2_.bound is None:
            conds.append(_cond("|factor| is known and both forms are bounded", None, f"{c}"))
            return Application(self.name, None, tuple(conds))
        bound = sympy.expand(absc * a1_.bound * a2_.bound)
        return Application(self.name, bound if direction == "upper" else -bound, tuple(conds))


@dataclasses.dataclass(frozen=True)
class WindowWeight(Rule):
    """c·∫_{t−h}^t g(ξ)‖v(ξ)‖^k dξ between c·(min g)·m and c·(max g)·m (m the window measure).

    With ``holder=(p, q)``: ∫ g‖v‖^k ≤ (∫ g^q)^{1/q} (∫‖v‖^{kp})^{1/p} = (∫g^q)^{1/q}·m^k
    (upper only).  ``weight`` is g (affine in ξ), ``factor`` c a constant of known sign.


    ==============================  ==========================================================
    licenses                        (min g)·m ≤ ∫ g‖v‖^k ≤ (max g)·m (m = ∫‖v‖^k, or the
                                    window norm's power); Hölder: ∫g‖v‖^k ≤ (∫g^q)^{1/q}m^k
    direction                       ≤ with c ≥ 0 or ≥ with c ≤ 0: max g (or Hölder);
                                    ≥ with c ≥ 0 or ≤ with c ≤ 0: min g (Hölder refused)
    side conditions                 the term is c·∫_{t−h}^t g‖v‖^k over the measure's own
                                    window; the sign of c known; g affine in ξ (its extrema at
                                    the ends); g ≥ 0 at the ends; k = the measure's order
                                    (Hölder: p, q conjugate, k·p = the order, a window norm)
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, norm_power, t, window_integral, xi
    >>> from lkverify.certify.steps.measures import window_integral_measure
    >>> P = Parameters(); x = Vector("x", 2); I = window_integral_measure("I", x(xi), p=2, window=1)
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"I": I})
    >>> g = 3 + xi - t                                   # from 2 at ξ = t − 1 to 3 at ξ = t
    >>> term = window_integral(norm_power(x(xi), 2), 1, weight=g)
    >>> [WindowWeight("I", 2, weight=g).apply(term, d, ctx).bound for d in ("upper", "lower")]
    [3*I, 2*I]
    >>> WindowWeight("I", 2, weight=xi - t).apply(term, "upper", ctx).status.value   # not the term's weight
    'failed'
    """

    measure: str
    power: object
    weight: object = 1
    factor: object = 1
    holder: tuple | None = None
    name = "bound on a window weight"

    def apply(self, term, direction, ctx):
        m = ctx.measure(self.measure)
        c = ctx.at(self.factor)
        k = ctx.at(self.power)
        g = ctx.at(self.weight)
        I = sympy.Integral(g * m.pointwise() ** k, (xi, t - ctx.at(m.window), t))
        conds = [_cond(f"the term is ({self.factor})·∫ g·‖v(ξ)‖^{k} with g = {self.weight}",
                       ctx.zero(c * I - ctx.at(term)), "it is not")]
        sc = _sign(c)
        if sc is None:
            return Application(self.name, None, tuple(conds) + (_cond("the factor's sign is known", None, f"{c}"),))
        lower = (direction == "lower") == (sc > 0)
        if lower and self.holder is not None:
            return Application(self.name, None, tuple(conds) + (_cond("Hölder gives upper bounds only", False),))
        fac, wconds = _window_factor(g, t - ctx.at(m.window), t, m, k, self.holder, ctx, lower=lower)
        conds += wconds
        if fac is None:
            return Application(self.name, None, tuple(conds))
        factor, mpow = fac
        name = self.name if self.holder is None else "Hölder on the window"
        return Application(name, sympy.expand(c * factor * m.symbol ** mpow), tuple(conds))


@dataclasses.dataclass(frozen=True)
class Young(Rule):
    """c·x·y ≤ c(ε x^p/p + ε^{−q/p} y^q/q) for x, y ≥ 0, c ≥ 0; and ≥ for c ≤ 0 (ε > 0, 1/p + 1/q = 1).

    Applied after another rule (``then=``): it rewrites that rule's bound c·x·y.

    ==============================  ==========================================================
    licenses                        x·y ≤ ε x^p/p + ε^{−q/p} y^q/q, multiplied by c
    direction                       ≤ steps with c ≥ 0; ≥ steps with c ≤ 0 (c·x·y ≥ c(…))
    side conditions                 the bound is c·x·y with c free of measures; the sign of c
                                    as the direction needs; p, q conjugate with p > 1;
                                    ε > 0; x, y ≥ 0
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); y = Vector("y", 2)
    >>> a, b = norm_measure("a", x(t)), norm_measure("b", y(t))
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> ctx = Context(sys_, P.resolve({}), {"a": a, "b": b})
    >>> app = Young(a.symbol, b.symbol, eps=sympy.Rational(1, 2)).rewrite(4 * a.symbol * b.symbol, ctx)
    >>> app.status.value, app.bound                     # 4ab ≤ 4(a²/4 + b²)
    ('exact', a**2 + 4*b**2)
    >>> Young(a.symbol, b.symbol, p=3, q=2).rewrite(4 * a.symbol * b.symbol, ctx).status.value
    'failed'
    >>> Young(a.symbol, b.symbol).rewrite(2 * a.symbol * b.symbol, ctx, "lower").detail   # 2ab ≥ a² + b² is false
    'side condition fails: c = 2 ≤ 0 (a ≥ step needs c ≤ 0): it has the other sign'
    """

    x: object
    y: object
    p: object = 2
    q: object = 2
    eps: object = 1
    name = "Young's inequality with a parameter"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        x, y = ctx.at(self.x), ctx.at(self.y)
        p, q, eps = (ctx.at(v) for v in (self.p, self.q, self.eps))
        c = sympy.simplify(previous / (x * y))
        sc = _sign(c)
        if direction == "upper":
            sign_cond = _cond(f"c = {c} ≥ 0 (a ≤ step needs c ≥ 0)", True if sc == 1 else (False if sc == -1 and c != 0
                                                                                          else None),
                              "it has the other sign" if sc == -1 else "the sign of c is not known")
        else:
            sign_cond = _cond(f"c = {c} ≤ 0 (a ≥ step needs c ≤ 0)", True if sc == -1 else (False if sc == 1 and c != 0
                                                                                           else None),
                              "it has the other sign" if sc == 1 else "the sign of c is not known")
        conds = [_cond(f"the bound is c·({self.x})·({self.y}) with c constant",
                       not (c.free_symbols & {m.symbol for m in ctx.measures.values()}), f"c = {c}"),
                 sign_cond,
                 conjugate_exponents(p, q),
                 _cond(f"ε = {eps} > 0", True if eps.is_positive else (False if eps.is_nonpositive else None)),
                 _cond("x, y ≥ 0", nonnegative(x) and nonnegative(y))]
        bound = sympy.expand(c * (eps * x**p / p + eps ** (-q / p) * y**q / q))
        return Application(self.name, bound, tuple(conds))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


def conjugate_exponents(p, q) -> Condition:
    """The side condition "p, q conjugate": 1/p + 1/q = 1 exactly and p > 1 (then q > 1 too).

    Decided exactly; symbolic exponents whose sign cannot be decided give ``undecided``.

    Examples
    --------
    >>> conjugate_exponents(3, sympy.Rational(3, 2)).status.value, conjugate_exponents(3, 2).status.value
    ('exact', 'failed')
    >>> conjugate_exponents(sympy.Rational(1, 2), -1).status.value     # 2 − 1 = 1 but p < 1
    'failed'
    """
    p, q = sympy.sympify(p), sympy.sympify(q)
    text = f"p = {p}, q = {q} conjugate (1/p + 1/q = 1, p > 1)"
    d = sympy.simplify(1 / p + 1 / q - 1)
    gt = sympy.simplify(p - 1)
    if d.is_zero is False or gt.is_positive is False:
        return _cond(text, False, f"1/p + 1/q = {sympy.simplify(1 / p + 1 / q)}, p − 1 = {gt}")
    if d == 0 and gt.is_positive:
        return _cond(text, True)
    return _cond(text, None, f"1/p + 1/q − 1 = {d}, p − 1 = {gt} not decided")


# the certified-supremum rules live in steps.templates (they import this module's conditions)
from .templates import (_HOMOGENEOUS_CACHE, TEMPLATE_ACCURACY, TEMPLATE_BOXES, TEMPLATE_ENCLOSURE,  # noqa: E402
                        Homogeneous, Template, _homogeneous_sup)
