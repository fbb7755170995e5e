"""Every side condition of every bound-step rule, violated alone: the rule must not prove the step.

Each test violates one condition of one rule (the others hold) and asserts that the
application is neither ``exact`` nor ``certified`` and that the detail names the
condition; beside it, a true variant (often the same claim written differently) that
the rule must prove.  The four defects found by the independent suites are here with
their variants in 1-D, 2-D and 3-D and in both directions:

* the Template parity test halved the direction domain of odd ratios (−ω_z ≤ κ‖ω‖ came
  out with κ ≈ 1.6e-16);
* CauchySchwarz without ``matrix=`` took ``operator_norm`` unchecked (xᵀy ≤ ½‖x‖‖y‖);
* Young and Homogeneous were not directional (2ab ≥ a² + b², a⁴ + b⁴ ≥ (a² + b²)²);
* Homogeneous ignored the sign of its factor (−(a⁴ + b⁴) ≤ −(a² + b²)²).
"""

import numpy as np
import pytest
import sympy

from lkverify import Equation, Parameters, System, Term, UnitVector, Vector, cross, norm_power, t, window_integral, xi
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure, window_norm
from lkverify.certify.steps.rules import (CauchySchwarz, Context, Equal, Homogeneous, Nonpositive, Printed, ProductCS,
                                          Rayleigh, Template, WindowWeight, Young, conjugate_exponents, crossed,
                                          integral_of, mapped, measured, scaled, summed, unit)
from lkverify.errors import InputError
from lkverify.status import Status

P = Parameters()
k = P.scalar("k", positive=True, default=2)
tau = P.delay("tau", default=1)
z = Vector("z", 1)
x, y = Vector("x", 2), Vector("y", 2)
omega = Vector("omega")
s = UnitVector("s")
R = sympy.Matrix([0, 0, 1])
SYS = System([Equation(z, [Term(-z(t))]), Equation(x, [Term(-k * x(t))]), Equation(y, [Term(-y(t))]),
              Equation(omega, [Term(-omega(t))]), Equation(s, [Term(-cross(omega(t), s(t)))])], parameters=P)
ZM, XM, YM, WM, EM = (norm_measure("ez", z(t)), norm_measure("a", x(t)), norm_measure("b", y(t)),
                      norm_measure("w", omega(t)), norm_measure("e", s(t) - R))
IM = window_integral_measure("I", x(xi), p=2, window=tau)
JM = window_norm("j", x(xi), p=3, window=tau)
MEASURES = {m.name: m for m in (ZM, XM, YM, WM, EM, IM, JM)}
REGION = Region({sup_norm("m", s(xi) - R, window=tau): sympy.Rational(1, 10)})
ez, a, b, w, e, I, j = (m.symbol for m in (ZM, XM, YM, WM, EM, IM, JM))


@pytest.fixture(scope="module")
def ctx():
    return Context(SYS, P.resolve({}, use_defaults=True), MEASURES, REGION)


def proved(app) -> bool:
    return app.status in (Status.EXACT, Status.CERTIFIED)


def refused(app, *words) -> bool:
    """Not proved, and the detail names the failing condition (each of ``words`` occurs in it)."""
    return not proved(app) and all(word in app.detail for word in words)


def kappa(app) -> float:
    return float(app.constants[0][1])


# -- Template: the direction domain, in 1-D, 2-D and 3-D, both directions -----------------------------
@pytest.mark.parametrize("term, measure, want", [
    (-z(t)[0], "ez", 1.0), (z(t)[0], "ez", 1.0),                       # 1-D: ±z ≤ |z|
    (-x(t)[1], "a", 1.0), (-x(t)[0], "a", 1.0), (x(t)[1], "a", 1.0),   # 2-D: odd in the direction
    (-omega(t)[2], "w", 1.0), (omega(t)[2], "w", 1.0), (-omega(t)[0], "w", 1.0),   # 3-D
])
def test_template_of_an_odd_ratio_is_its_supremum_over_all_directions(ctx, term, measure, want):
    app = Template("c", {measure: 1}).apply(term, "upper", ctx)
    assert app.status is Status.CERTIFIED
    assert want <= kappa(app) <= want * 1.01  # κ ≈ 1.6e-16 before the fix for −ω_z


@pytest.mark.parametrize("term, measure", [(z(t)[0], "ez"), (x(t)[1], "a"), (omega(t)[2], "w")])
def test_template_lower_direction_of_an_odd_term(ctx, term, measure):
    # v_k ≥ −κ‖v‖ needs κ = sup(−v_k/‖v‖) = 1 over all directions
    app = Template("c", {measure: 1}).apply(term, "lower", ctx)
    assert app.status is Status.CERTIFIED and 1.0 <= kappa(app) <= 1.01
    assert app.bound == -sympy.Rational(app.constants[0][1]) * MEASURES[measure].symbol


@pytest.mark.parametrize("term, measure, power, want", [
    (x(t)[0] ** 2 + 3 * x(t)[1] ** 2, "a", 2, 3.0),                   # even: half the circle is enough
    (omega(t)[0] * omega(t)[2] + omega(t)[2] ** 2, "w", 2, (1 + 2 ** 0.5) / 2),
    (x(t)[0] ** 3 * x(t)[1] - x(t)[1] ** 4, "a", 4, None),              # even of degree 4
])
def test_template_of_an_even_ratio_still_halves_and_is_right(ctx, term, measure, power, want):
    app = Template("c", {measure: power}).apply(term, "upper", ctx)
    assert app.status is Status.CERTIFIED
    if want is None:  # the maximum over a fine grid of the circle
        th = np.linspace(0, 2 * np.pi, 200_001)
        want = float(np.max(np.cos(th) ** 3 * np.sin(th) - np.sin(th) ** 4))
    assert want <= kappa(app) <= want * 1.01 + 1e-9


def test_template_mixed_parity_in_two_vectors(ctx):
    # (xᵀy)·x_1 is even in (x, y) jointly but odd in x alone and in y alone: no half domain
    term = x(t).dot(y(t)) * x(t)[0]
    app = Template("c", {"a": 2, "b": 1}).apply(term, "upper", ctx)
    assert app.status is Status.CERTIFIED and 1.0 <= kappa(app) <= 1.01
    low = Template("c", {"a": 2, "b": 1}).apply(term, "lower", ctx)
    assert low.status is Status.CERTIFIED and 1.0 <= kappa(low) <= 1.01


def test_template_catalogue_case_gradient_of_a_quartic_on_the_circle(ctx):
    # the shape of paper 002 Theorem 1's step −λq̇ᵀ∂Π/∂q ≤ λc9‖q̇‖‖q‖³ (λ = 10): the ratio is odd in q̇
    x1, x2 = sympy.symbols("x1 x2", real=True)
    Pi = x1**4 / 4 + x1**2 * x2**2 / 4 + x2**4 / 8 + x1**3 * x2 / 4   # a quartic with an odd gradient ratio
    grad = sympy.Matrix([Pi.diff(x1), Pi.diff(x2)]).subs({x1: x(t)[0], x2: x(t)[1]})
    term = -10 * y(t).dot(grad)
    app = Template("lam_c9", {"b": 1, "a": 3}).apply(term, "upper", ctx)
    th = np.linspace(0, 2 * np.pi, 400_001)
    g = sympy.lambdify((x1, x2), [Pi.diff(x1), Pi.diff(x2)], "numpy")
    gx, gy = g(np.cos(th), np.sin(th))
    want = 10 * float(np.max(np.hypot(gx, gy)))
    assert app.status is Status.CERTIFIED and want <= kappa(app) <= want * 1.01


def test_template_side_condition_region_inside_the_chart(ctx):
    far = Context(SYS, ctx.values, MEASURES, Region({sup_norm("m", s(xi) - R, window=tau): sympy.Rational(3, 2)}))
    sxr = s(t).cross(R)
    ok = Template("c", {"e": 2}).apply(sxr.dot(sxr), "upper", ctx)
    bad = Template("c", {"e": 2}).apply(sxr.dot(sxr), "upper", far)
    assert proved(ok) and refused(bad, "inside the chart")


def test_template_side_condition_degree(ctx):
    assert refused(Template("c", {"a": 3}).apply(x(t).dot(x(t)), "upper", ctx), "not divisible")
    assert refused(Template("c", {"a": 1}).apply(x(t).dot(x(t)), "upper", ctx), "homogeneous")
    assert refused(Template("c", {"a": 1}).apply(x(t).dot(x(t)) * x(t)[0] ** 0 + x(t)[0], "upper", ctx),
                   "the ratio is well defined")


def test_template_side_condition_every_state_charted(ctx):
    assert refused(Template("c", {"a": 2}).apply(x(t).dot(y(t)) * x(t)[0] / 1, "upper", ctx), "states")


def test_template_side_condition_no_explicit_time(ctx):
    # a time-varying coefficient: a supremum over the chart alone does not bound it for every t
    assert refused(Template("c", {"a": 2}).apply(x(t).dot(x(t)) * sympy.exp(-t), "upper", ctx), "depends on t")


def test_template_refuses_two_measures_of_one_state(ctx):
    other = dict(MEASURES, a2=norm_measure("a2", x(t)))
    c2 = Context(SYS, ctx.values, other, REGION)
    with pytest.raises(InputError, match="one state"):
        Template("c", {"a": 1, "a2": 1}).apply(x(t).dot(x(t)), "upper", c2)


# -- CauchySchwarz: κ against the true operator norm, the identity included ----------------------------
def test_cauchy_schwarz_checks_kappa_against_the_identity(ctx):
    term = x(t).dot(x(t))
    half = CauchySchwarz(x(t), x(t), (measured(XM), measured(XM)), operator_norm=sympy.Rational(1, 2))
    assert refused(half.apply(term, "upper", ctx), "‖M‖")      # xᵀx ≤ ½‖x‖² is false at x = e1
    assert refused(half.apply(term, "lower", ctx), "‖M‖")
    one = CauchySchwarz(x(t), x(t), (measured(XM), measured(XM)), operator_norm=1).apply(term, "upper", ctx)
    two = CauchySchwarz(x(t), x(t), (measured(XM), measured(XM)), operator_norm=2).apply(term, "upper", ctx)
    assert one.status is Status.EXACT and two.status is Status.EXACT and two.bound == 2 * a**2


@pytest.mark.parametrize("u, v, mu, mv", [(x(t), y(t), XM, YM), (omega(t), omega(t), WM, WM), (z(t), z(t), ZM, ZM)])
def test_cauchy_schwarz_kappa_below_one_in_every_dimension(ctx, u, v, mu, mv):
    rule = CauchySchwarz(u, v, (measured(mu), measured(mv)), operator_norm=sympy.Rational(99, 100))
    assert refused(rule.apply(sympy.Matrix(u).dot(sympy.Matrix(v)), "upper", ctx), "‖M‖")


def test_cauchy_schwarz_side_condition_negative_kappa(ctx):
    M = sympy.diag(2, 1)
    term = (x(t).T * M * y(t))[0]
    bad = CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)), matrix=M, operator_norm=-2).apply(term, "upper", ctx)
    assert refused(bad, "≥ 0")


def test_cauchy_schwarz_side_condition_the_term_is_the_form(ctx):
    M = sympy.diag(2, 1)
    term = (x(t).T * M * y(t))[0] + x(t)[0] * y(t)[0] / 10**12
    assert refused(CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)), matrix=M, operator_norm=2).apply(
        term, "upper", ctx), "the term is")


def test_cauchy_schwarz_factor_of_unknown_sign_is_bounded_by_its_absolute_value(ctx):
    c = sympy.Symbol("c", real=True)  # |c·xᵀy| ≤ |c|·‖x‖‖y‖ whatever the sign of c
    app = CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)), factor=c).apply(c * x(t).dot(y(t)), "upper", ctx)
    assert app.status is Status.EXACT and app.bound == sympy.Abs(c) * a * b
    assert refused(CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)), factor=c).apply(
        2 * c * x(t).dot(y(t)), "upper", ctx), "the term is")


def test_cauchy_schwarz_side_condition_norm_tree_matches(ctx):
    rule = CauchySchwarz(x(t), y(t), (measured(XM), measured(XM)))       # ‖y‖ bounded by ‖x‖'s measure
    assert refused(rule.apply(x(t).dot(y(t)), "upper", ctx), "vector")


# -- norm trees ---------------------------------------------------------------------------------------
def test_mapped_checks_kappa_sign_and_size(ctx):
    A = sympy.Matrix([[0, 2], [0, 0]])
    v = A * y(t)
    term = x(t).dot(v)
    ok = CauchySchwarz(x(t), v, (measured(XM), mapped(A, measured(YM), 2))).apply(term, "upper", ctx)
    small = CauchySchwarz(x(t), v, (measured(XM), mapped(A, measured(YM), sympy.Rational(199, 100)))).apply(
        term, "upper", ctx)
    negative = CauchySchwarz(x(t), v, (measured(XM), mapped(A, measured(YM), -2))).apply(term, "upper", ctx)
    assert ok.status is Status.EXACT
    assert refused(small, "‖M‖") and refused(negative, "≥ 0")


def test_scaled_needs_a_nonnegative_factor(ctx):
    c = sympy.Symbol("c", real=True)
    v = c * y(t)
    rule = CauchySchwarz(x(t), v, (measured(XM), scaled(c, measured(YM))))
    assert not proved(rule.apply(x(t).dot(v), "upper", ctx))
    v2 = -2 * y(t)
    assert not proved(CauchySchwarz(x(t), v2, (measured(XM), scaled(-2, measured(YM)))).apply(
        x(t).dot(v2), "upper", ctx))
    assert proved(CauchySchwarz(x(t), 2 * y(t), (measured(XM), scaled(2, measured(YM)))).apply(
        x(t).dot(2 * y(t)), "upper", ctx))


def test_unit_needs_a_unit_vector_and_crossed_the_cross_product(ctx):
    term = omega(t).dot(s(t).cross(R))
    ok = CauchySchwarz(omega(t), s(t).cross(R), (measured(WM), crossed(measured(EM), unit(R)))).apply(
        term, "upper", ctx)
    assert ok.status is Status.EXACT
    not_unit = CauchySchwarz(omega(t), s(t).cross(2 * R), (measured(WM), crossed(measured(EM), unit(2 * R))))
    assert refused(not_unit.apply(omega(t).dot(s(t).cross(2 * R)), "upper", ctx), "unit")
    swapped = CauchySchwarz(omega(t), s(t).cross(R), (measured(WM), crossed(unit(R), measured(EM))))
    assert not proved(swapped.apply(term, "upper", ctx))  # r × (s − r) = −(s × r): not the vector


def test_summed_needs_the_parts_to_add_up(ctx):
    v = x(t) + y(t)
    ok = CauchySchwarz(x(t), v, (measured(XM), summed(measured(XM), measured(YM)))).apply(x(t).dot(v), "upper", ctx)
    assert ok.status is Status.EXACT and sympy.expand(ok.bound - a * (a + b)) == 0
    v2 = x(t) + 2 * y(t)
    assert refused(CauchySchwarz(x(t), v2, (measured(XM), summed(measured(XM), measured(YM)))).apply(
        x(t).dot(v2), "upper", ctx), "vector")


def test_integral_of_weight_window_power_and_holder(ctx):
    J1 = window_integral(norm_power(x(xi), 1) * x(xi), tau)       # ‖∫‖x‖x‖ ≤ (∫‖x‖³)^{2/3} = j²
    pw = scaled(norm_power(x(xi), 1), measured(JM, at=xi))
    good = integral_of(pw, measure=JM, power=2, holder=(sympy.Rational(3, 2), 3))
    assert CauchySchwarz(x(t), J1, (measured(XM), good)).apply(x(t).dot(J1), "upper", ctx).status is Status.EXACT
    for holder, word in [((2, 2), "k·p"), ((3, 2), "conjugate"), ((sympy.Rational(1, 2), -1), "conjugate")]:
        bad = integral_of(pw, measure=JM, power=2, holder=holder)
        assert refused(CauchySchwarz(x(t), J1, (measured(XM), bad)).apply(x(t).dot(J1), "upper", ctx), word)
    # a weight that changes sign on the window: max|g| is not max g
    Jg = window_integral((xi - t + tau / 2) * x(xi), tau)
    wg = integral_of(measured(IM, at=xi), measure=IM, power=1, weight=xi - t + tau / 2)
    assert not proved(CauchySchwarz(x(t), Jg, (measured(XM), wg)).apply(x(t).dot(Jg), "upper", ctx))


# -- Young --------------------------------------------------------------------------------------------
def test_young_is_directional(ctx):
    up = Young(a, b).rewrite(2 * a * b, ctx, "upper")
    assert up.status is Status.EXACT and up.bound == a**2 + b**2
    assert refused(Young(a, b).rewrite(2 * a * b, ctx, "lower"), "≤ 0")          # 2ab ≥ a² + b² is false
    low = Young(a, b).rewrite(-2 * a * b, ctx, "lower")                           # −2ab ≥ −(a² + b²) is true
    assert low.status is Status.EXACT and low.bound == -(a**2 + b**2)
    assert refused(Young(a, b).rewrite(-2 * a * b, ctx, "upper"), "≥ 0")


def test_young_in_a_lower_step_of_a_chain_is_refused():
    from lkverify import Functional
    from lkverify.certify.steps.chain import TermBound, TermwiseBound

    V = Functional([Term(2 * x(t).dot(x(t)) ** sympy.Rational(1, 2) * y(t).dot(y(t)) ** sympy.Rational(1, 2),
                         text="2‖x‖‖y‖")])
    tb = TermBound("2‖x‖‖y‖", a**2 + b**2, Equal(2 * a * b), then=(Young(a, b),))
    step = TermwiseBound("V ≥ a² + b²", V, SYS, "V", [tb], a**2 + b**2, [XM, YM], relation=">=", witness_seconds=2)
    res = step.check(P.resolve({}, use_defaults=True))
    assert res.status not in (Status.EXACT, Status.CERTIFIED)


@pytest.mark.parametrize("p, q, eps, word", [(3, 2, 1, "conjugate"), (2, 2, -1, "ε"), (2, 2, 0, "ε"),
                                             (sympy.Rational(1, 2), -1, 1, "conjugate")])
def test_young_side_conditions(ctx, p, q, eps, word):
    assert refused(Young(a, b, p=p, q=q, eps=eps).rewrite(2 * a * b, ctx), word)


def test_young_side_condition_the_bound_is_c_x_y(ctx):
    assert refused(Young(a, b).rewrite(2 * a * b + a**2, ctx), "c·")


def test_young_side_condition_x_y_nonnegative(ctx):
    u = sympy.Symbol("u", real=True)
    assert refused(Young(u, b).rewrite(2 * u * b, ctx), "x, y ≥ 0")


def test_conjugate_exponents_symbolic_is_undecided_not_an_error():
    p = sympy.Symbol("p", real=True)
    assert conjugate_exponents(p, p / (p - 1)).status is Status.UNDECIDED
    assert conjugate_exponents(sympy.Symbol("p", positive=True) + 1, 2).status is not Status.EXACT


# -- Homogeneous --------------------------------------------------------------------------------------
def test_homogeneous_is_directional(ctx):
    g, T = a**4 + b**4, (a**2 + b**2) ** 2                       # ½T ≤ g ≤ T
    up = Homogeneous(("a", "b"), T, "c").rewrite(g, ctx, "upper")
    assert up.status is Status.CERTIFIED and 1.0 <= kappa(up) <= 1.01
    low = Homogeneous(("a", "b"), T, "c").rewrite(g, ctx, "lower")
    assert low.status is Status.CERTIFIED and 0.495 <= kappa(low) <= 0.5       # never the supremum 1
    assert sympy.expand(low.bound - sympy.Rational(low.constants[0][1]) * T) == 0


def test_homogeneous_respects_the_sign_of_the_factor(ctx):
    g, T = a**4 + b**4, (a**2 + b**2) ** 2
    # −(a⁴ + b⁴) ≤ −κ(a² + b²)² needs κ ≤ inf g/T = ½: the supremum 1 would prove a false step
    neg = Homogeneous(("a", "b"), T, "c", factor=-1).rewrite(-g, ctx, "upper")
    assert neg.status is Status.CERTIFIED and 0.495 <= kappa(neg) <= 0.5
    neg_low = Homogeneous(("a", "b"), T, "c", factor=-1).rewrite(-g, ctx, "lower")
    assert neg_low.status is Status.CERTIFIED and 1.0 <= kappa(neg_low) <= 1.01
    # a factor with a measure in it (γ‖ω‖): its sign is that of the constant
    wf = Homogeneous(("a", "b"), T, "c", factor=-3 * w).rewrite(-3 * w * g, ctx, "upper")
    assert wf.status is Status.CERTIFIED and 0.495 <= kappa(wf) <= 0.5


def test_homogeneous_side_condition_factor_sign_known(ctx):
    c = sympy.Symbol("c", real=True)
    assert refused(Homogeneous(("a", "b"), (a**2 + b**2) ** 2, "k", factor=c).rewrite(c * (a**4 + b**4), ctx),
                   "sign of the factor")


def test_homogeneous_side_condition_template_positive(ctx):
    # T = a² − b² changes sign: g ≤ κT does not follow from g/T ≤ κ
    assert refused(Homogeneous(("a", "b"), a**2 - b**2, "k").rewrite(a**2 + b**2, ctx), "> 0")
    assert refused(Homogeneous(("a", "b"), -(a**2 + b**2), "k").rewrite(a**2 + b**2, ctx), "> 0")


def test_homogeneous_side_conditions_degree_and_other_measures(ctx):
    assert refused(Homogeneous(("a", "b"), a**2 + b**2, "k").rewrite(a**3 + b**3, ctx), "homogeneous")
    assert refused(Homogeneous(("a", "b"), a**2 + b**2, "k").rewrite(a**2 + w**2, ctx), "other measures")


# -- Rayleigh -----------------------------------------------------------------------------------------
M2 = sympy.Matrix([[2, 1], [1, 2]])   # eigenvalues 1, 3


@pytest.mark.parametrize("direction, factor, eig, ok", [
    ("upper", 1, 3, True), ("upper", 1, 1, False), ("lower", 1, 1, True), ("lower", 1, 3, False),
    ("upper", -1, 1, True), ("upper", -1, 3, False), ("lower", -1, 3, True), ("lower", -1, 1, False)])
def test_rayleigh_direction_and_factor_sign(ctx, direction, factor, eig, ok):
    term = factor * (x(t).T * M2 * x(t))[0]
    app = Rayleigh(x(t), M2, factor=factor, eigenvalue=eig, norm_squared=a**2).apply(term, direction, ctx)
    assert proved(app) is ok
    if not ok:
        assert "eigenvalue bound" in app.detail


def test_rayleigh_side_conditions(ctx):
    quad = (x(t).T * M2 * x(t))[0]
    Mn = sympy.Matrix([[2, 1], [0, 2]])
    assert refused(Rayleigh(x(t), Mn, eigenvalue=3, norm_squared=a**2).apply((x(t).T * Mn * x(t))[0], "upper", ctx),
                   "symmetric")
    assert refused(Rayleigh(x(t), M2, eigenvalue=3, norm_squared=2 * a**2).apply(quad, "upper", ctx), "‖u‖²")
    c = sympy.Symbol("c", real=True)
    assert not proved(Rayleigh(x(t), M2, factor=c, eigenvalue=3, norm_squared=a**2).apply(c * quad, "upper", ctx))
    assert refused(Rayleigh(x(t), M2, eigenvalue=3, norm_squared=a**2).apply(quad + x(t)[0] / 10**9, "upper", ctx),
                   "the term is")


# -- WindowWeight -------------------------------------------------------------------------------------
def test_window_weight_directions_and_side_conditions(ctx):
    g = 2 + (xi + tau - t)                                      # 2 at ξ = t − τ, 3 at ξ = t
    term = window_integral(norm_power(x(xi), 2), tau, weight=g)
    up, lo = (WindowWeight("I", 2, weight=g).apply(term, d, ctx) for d in ("upper", "lower"))
    assert (up.status, up.bound, lo.status, lo.bound) == (Status.EXACT, 3 * I, Status.EXACT, 2 * I)
    neg_up = WindowWeight("I", 2, weight=g, factor=-1).apply(-term, "upper", ctx)   # −∫g‖x‖² ≤ −2I
    assert neg_up.status is Status.EXACT and neg_up.bound == -2 * I
    assert refused(WindowWeight("I", 3, weight=g).apply(window_integral(norm_power(x(xi), 3), tau, weight=g),
                                                        "upper", ctx), "order")
    assert refused(WindowWeight("I", 2, weight=g).apply(window_integral(norm_power(x(xi), 2), 2 * tau, weight=g),
                                                        "upper", ctx), "the term is")
    quad = (xi + tau - t) ** 2
    assert refused(WindowWeight("I", 2, weight=quad).apply(window_integral(norm_power(x(xi), 2), tau, weight=quad),
                                                           "upper", ctx), "affine")
    holder_low = WindowWeight("j", 1, weight=1, holder=(3, sympy.Rational(3, 2)))
    assert refused(holder_low.apply(window_integral(norm_power(x(xi), 1), tau), "lower", ctx), "upper bounds only")


# -- Equal, Nonpositive, ProductCS, Printed -----------------------------------------------------------
def test_equal_nonpositive_printed(ctx):
    assert refused(Equal(a**2 + sympy.Rational(1, 10**40)).apply(x(t).dot(x(t)), "upper", ctx), "exactly")
    assert Equal(a**2).apply(x(t)[0] ** 2 + x(t)[1] ** 2, "lower", ctx).status is Status.EXACT
    assert Nonpositive().apply(-x(t).dot(x(t)), "upper", ctx).status is Status.EXACT
    assert refused(Nonpositive().apply(-x(t).dot(x(t)), "lower", ctx), "≥ 0")
    assert Nonpositive().apply(x(t).dot(x(t)), "lower", ctx).status is Status.EXACT
    assert Printed("Lemma 2").apply(x(t).dot(x(t)), "upper", ctx).status is Status.UNDECIDED


def test_product_cs_side_conditions(ctx):
    f1 = CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)))
    f2 = CauchySchwarz(omega(t), omega(t), (measured(WM), measured(WM)))
    term = 3 * x(t).dot(y(t)) * omega(t).dot(omega(t))
    ok = ProductCS(f1, f2, factor=3).apply(term, "upper", ctx)
    assert ok.status is Status.EXACT and sympy.expand(ok.bound - 3 * a * b * w**2) == 0
    assert proved(ProductCS(f1, f2, factor=3).apply(term, "lower", ctx))
    assert refused(ProductCS(f1, f2, factor=2).apply(term, "upper", ctx), "the term is")
    half = CauchySchwarz(x(t), y(t), (measured(XM), measured(YM)), operator_norm=sympy.Rational(1, 2))
    assert refused(ProductCS(half, f2, factor=3).apply(term, "upper", ctx), "‖M‖")
