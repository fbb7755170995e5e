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

import sympy

from ...declare.symbols import t, xi
from ...declare.vectors import as_column
from ...errors import InputError
from ...status import Status
from ..matrices import matrix_positive_definite
# re-exported: moved to steps.context (what a rule works with and returns) and steps.norms (how a norm tree is checked)
from .context import (Application, Condition, Context, Rule, _abs_factor, _cond, _factor_sign, _sign, decided,  # noqa: F401
                      nonnegative, sign_of)
from .measures import Measure
from .norms import (FieldNorm, Norm, _integrand, _resolve_norm, _window_factor, conjugate_exponents,  # noqa: F401
                    operator_norm_conditions, pointwise_constant, resolve_norm)

__all__ = ["Application", "CauchySchwarz", "Context", "Equal", "Nonpositive", "Norm", "Printed", "Rayleigh", "Rule",
           "Template", "WindowWeight", "Young", "Homogeneous", "crossed", "integral_of", "mapped", "measured", "nonnegative",
           "scaled", "summed", "unit", "decided", "sign_of", "ProductCS", "resolve_norm", "homogeneous_field"]


# -- norm trees: the constructors (the class and how a tree is checked: steps.norms) ---------------
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


def homogeneous_field(field, variables, measure: Measure, *, degree, kappa, at=None) -> Norm:
    """‖F(v)‖ ≤ κ‖v‖^k for a polynomial field F homogeneous of degree k, as the tree of F(v)/κ with bound ‖v‖^k.

    ``field`` is F written in the plain ``variables`` (a column, e.g. ∂Π̃/∂x of a form Π̃ of
    degree k + 1), ``measure`` the measure whose vector v is substituted (``at=xi``: its
    pointwise norm inside a window integral).  The tree bounds the vector F(v)/κ by ‖v‖^k, so
    that κ goes into the weight of :func:`integral_of` (``weight=kappa * g``), where the
    integrand g(ξ)F(v(ξ)) = κg(ξ)·F(v(ξ))/κ is matched.  κ is an expression of the
    parameters (a declared constant, so that a wrong one can be stated and refuted).

    ==============================  ==========================================================
    licenses                        ‖F(v)‖ ≤ κ‖v‖^k for every v (so ‖F(v)/κ‖ ≤ ‖v‖^k)
    side conditions                 the vector is F(v)/κ exactly; F has numeric coefficients
                                    and each component is a form of degree k (exact); κ > 0;
                                    κ²‖x‖^{2k} − ‖F(x)‖² ≥ 0: identically 0 (exact) or
                                    positive on the unit sphere (certified with arb), refuted
                                    at a rational point otherwise
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t, window_integral, xi
    >>> from lkverify.certify.steps.measures import norm_measure, window_integral_measure
    >>> P = Parameters(); x, y = Vector("x", 2), Vector("y", 2)
    >>> sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> w, K = norm_measure("w", y(t)), window_integral_measure("K", x(xi), p=3, window=1)
    >>> ctx = Context(sys_, P.resolve({}), {"w": w, "K": K})
    >>> X = sympy.symbols("x1 x2", real=True)
    >>> F = sympy.Matrix([X[0] ** 3, X[1] ** 3])                 # ∂/∂x (x1⁴ + x2⁴)/4, max‖F(u)‖ = 1
    >>> J = window_integral(F.xreplace(dict(zip(X, list(x(xi))))), 1)
    >>> def tree(kappa):
    ...     return integral_of(homogeneous_field(F, X, K, degree=3, kappa=kappa, at=xi), measure=K, power=3,
    ...                        weight=kappa)
    >>> app = CauchySchwarz(y(t), J, (measured(w), tree(1))).apply(y(t).dot(J), "upper", ctx)
    >>> app.status.value, app.bound                   # κ = 1 is the maximum, attained at u = e1: not decided
    ('undecided', K*w)
    >>> app = CauchySchwarz(y(t), J, (measured(w), tree(sympy.Rational(101, 100)))).apply(y(t).dot(J), "upper", ctx)
    >>> app.status.value, app.bound
    ('certified', 101*K*w/100)
    >>> CauchySchwarz(y(t), J, (measured(w), tree(sympy.Rational(9, 10)))).apply(y(t).dot(J), "upper",
    ...                                                                              ctx).status.value
    'failed'
    """
    xs = tuple(variables)
    F = sympy.ImmutableMatrix(sympy.Matrix(field))
    vec = sympy.Matrix(measure.vector)
    if at is not None and measure.kind == "norm":
        vec = vec.subs(t, at)
    k, c = sympy.sympify(degree), sympy.sympify(kappa)
    return FieldNorm(f"‖F(v)‖ ≤ κ‖v‖^k (F homogeneous of degree {k})",
                     sympy.ImmutableMatrix(F.xreplace(dict(zip(xs, list(vec)))) / c), None,
                     data=(F, xs, measure, k, c, at is not None))


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


# -- rules --------------------------------------------------------------------------------------
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


# the certified-supremum rules live in steps.templates (on steps.context, like this module)
from .templates import (_HOMOGENEOUS_CACHE, TEMPLATE_ACCURACY, TEMPLATE_BOXES, TEMPLATE_ENCLOSURE,  # noqa: E402
                        Homogeneous, Template, _homogeneous_sup)
