"""The checked rules of bound steps: each must reject a misapplication and name the failing side condition."""

import pytest
import sympy

from lkverify import Equation, Parameters, System, Term, UnitVector, Vector, cross, norm_power, t, window_integral, xi
from lkverify.certify.steps.measures import (Region, norm_measure, sup_norm, window_integral_measure, window_norm)
from lkverify.certify.steps.rules import (CauchySchwarz, Context, Equal, Nonpositive, Rayleigh, WindowWeight, Young,
                                          crossed, integral_of, measured, nonnegative, scaled, unit)
from lkverify.status import Status

P = Parameters()
k = P.scalar("k", positive=True, default=2)
tau = P.delay("tau", default=1)
x = Vector("x", 2)
s = UnitVector("s")
omega = Vector("omega")
R = sympy.Matrix([0, 0, 1])
SYS = System([Equation(x, [Term(-k * x(t))]), Equation(omega, [Term(-omega(t))]),
              Equation(s, [Term(-cross(omega(t), s(t)))])], parameters=P)
N = norm_measure("n", x(t))
W = norm_measure("w", omega(t))
E = norm_measure("e", s(t) - R)
J = window_norm("j", s(xi) - R, p=3, window=tau)
I2 = window_integral_measure("I", s(xi) - R, p=2, window=tau)
MEASURES = {m.name: m for m in (N, W, E, J, I2)}
REGION = Region({sup_norm("m", s(xi) - R, window=tau): sympy.Rational(1, 10), W: 1})
n, w, e, j, I = (m.symbol for m in (N, W, E, J, I2))


@pytest.fixture
def ctx():
    return Context(SYS, P.resolve({}, use_defaults=True), MEASURES, REGION)


M = sympy.Matrix([[2, 1], [1, 2]])
QUAD = (x(t).T * M * x(t))[0]


def test_rayleigh_proves_both_directions(ctx):
    up = Rayleigh(x(t), M, eigenvalue=3, norm_squared=n**2).apply(QUAD, "upper", ctx)
    lo = Rayleigh(x(t), M, eigenvalue=1, norm_squared=n**2).apply(QUAD, "lower", ctx)
    assert (up.status, up.bound) == (Status.EXACT, 3 * n**2)
    assert (lo.status, lo.bound) == (Status.EXACT, n**2)


@pytest.mark.parametrize("direction, eig", [("upper", sympy.Rational(299, 100)), ("lower", sympy.Rational(101, 100))])
def test_rayleigh_rejects_a_wrong_eigenvalue_and_names_it(ctx, direction, eig):
    app = Rayleigh(x(t), M, eigenvalue=eig, norm_squared=n**2).apply(QUAD, direction, ctx)
    assert app.status is Status.FAILED
    assert "the eigenvalue bound" in app.detail


def test_rayleigh_with_a_negative_factor_needs_the_smallest_eigenvalue(ctx):
    ok = Rayleigh(x(t), M, factor=-k, eigenvalue=1, norm_squared=n**2).apply(-k * QUAD, "upper", ctx)
    bad = Rayleigh(x(t), M, factor=-k, eigenvalue=3, norm_squared=n**2).apply(-k * QUAD, "upper", ctx)
    assert ok.status is Status.EXACT and ok.bound == -2 * n**2
    assert bad.status is Status.FAILED


def test_rayleigh_rejects_a_term_that_is_not_the_form(ctx):
    app = Rayleigh(x(t), M, eigenvalue=3, norm_squared=n**2).apply(QUAD + x(t)[0] ** 2 / 10**9, "upper", ctx)
    assert app.status is Status.FAILED and "the term is" in app.detail


def test_unit_vector_identity_is_an_allowed_norm(ctx):
    sxr = s(t).cross(R)
    ok = Rayleigh(sxr, sympy.eye(3), eigenvalue=1, norm_squared=e**2 * (1 - e**2 / 4)).apply(
        sxr.dot(sxr), "upper", ctx)
    bad = Rayleigh(sxr, sympy.eye(3), eigenvalue=1, norm_squared=e**2).apply(sxr.dot(sxr), "upper", ctx)
    assert ok.status is Status.EXACT
    assert bad.status is Status.FAILED and "‖u‖²" in bad.detail


def test_cauchy_schwarz_operator_norm(ctx):
    A = sympy.Matrix([[3, 0], [0, 1]])
    term = (x(t).T * A * x(t))[0]
    ok = CauchySchwarz(x(t), x(t), (measured(N), measured(N)), matrix=A, operator_norm=3).apply(term, "upper", ctx)
    small = CauchySchwarz(x(t), x(t), (measured(N), measured(N)), matrix=A, operator_norm=sympy.Rational(29, 10)
                          ).apply(term, "upper", ctx)
    assert ok.status is Status.EXACT and ok.bound == 3 * n**2
    assert small.status is Status.FAILED and "operator norm is larger" in small.detail


def test_cross_product_norms_and_unit_vectors(ctx):
    term = omega(t).dot(s(t).cross(R))
    app = CauchySchwarz(omega(t), s(t).cross(R), (measured(W), crossed(measured(E), unit(R)))).apply(term, "upper", ctx)
    assert app.status is Status.EXACT and app.bound == e * w
    # ω is not a unit vector: the unit rule must refuse it
    wrong = CauchySchwarz(omega(t), s(t).cross(R), (unit(omega(t)), crossed(measured(E), unit(R)))).apply(
        term, "upper", ctx)
    assert wrong.status is Status.FAILED and "unit vector" in wrong.detail


def _J_integral():
    return window_integral(norm_power(s(xi) - R, 1) * s(xi).cross(R), tau)


def test_holder_on_a_window(ctx):
    term = omega(t).dot(_J_integral())
    pw = scaled(norm_power(s(xi) - R, 1), crossed(measured(J, at=xi), unit(R)))
    ok = CauchySchwarz(omega(t), _J_integral(), (measured(W), integral_of(pw, measure=J, power=2,
                                                                            holder=(sympy.Rational(3, 2), 3)))
                       ).apply(term, "upper", ctx)
    assert ok.status is Status.EXACT and ok.bound == w * j**2
    bad = CauchySchwarz(omega(t), _J_integral(), (measured(W), integral_of(pw, measure=J, power=2, holder=(2, 2)))
                        ).apply(term, "upper", ctx)
    assert bad.status is Status.FAILED
    assert "conjugate" in bad.detail or "k·p" in bad.detail
    bad2 = CauchySchwarz(omega(t), _J_integral(), (measured(W), integral_of(pw, measure=J, power=2,
                                                                              holder=(3, 2)))).apply(term, "upper", ctx)
    assert bad2.status is Status.FAILED and "conjugate" in bad2.detail


def test_window_weight_bounds(ctx):
    g = 2 + (xi + tau - t)
    term = window_integral(norm_power(s(xi) - R, 2), tau, weight=g)
    up = WindowWeight("I", 2, weight=g).apply(term, "upper", ctx)
    lo = WindowWeight("I", 2, weight=g).apply(term, "lower", ctx)
    assert (up.status, up.bound) == (Status.EXACT, 3 * I)
    assert (lo.status, lo.bound) == (Status.EXACT, 2 * I)
    neg = WindowWeight("I", 2, weight=xi - t).apply(window_integral(norm_power(s(xi) - R, 2), tau, weight=xi - t),
                                                    "upper", ctx)
    assert not neg.status.is_proof


def test_young_checks_the_weight_and_the_exponents(ctx):
    ok = Young(w, j**2, p=2, q=2, eps=sympy.Rational(1, 3)).rewrite(5 * w * j**2, ctx)
    assert ok.status is Status.EXACT
    assert sympy.expand(ok.bound - 5 * (w**2 / 6 + sympy.Rational(3, 2) * j**4)) == 0
    bad = Young(w, j**2, p=3, q=2, eps=1).rewrite(5 * w * j**2, ctx)
    assert bad.status is Status.FAILED and "conjugate" in bad.detail
    neg = Young(w, j**2, p=2, q=2, eps=-1).rewrite(5 * w * j**2, ctx)
    assert not neg.status.is_proof and "ε" in neg.detail


def test_equal_and_a_tiny_exact_difference(ctx):
    term = norm_power(s(t) - R, 2) / 2
    assert Equal(e**2 / 2).apply(term, "upper", ctx).status is Status.EXACT
    # the same written differently: ‖s − r‖² = 2 − 2 s·r on the sphere
    assert Equal(1 - s(t).dot(R)).apply(term, "upper", ctx).status is Status.EXACT
    assert Equal(e**2 / 2 + sympy.Rational(1, 10**30) * e**2).apply(term, "upper", ctx).status is Status.FAILED


def test_nonpositive(ctx):
    assert Nonpositive().apply(-k * norm_power(s(t - tau) - R, 3), "upper", ctx).status is Status.EXACT
    assert not Nonpositive().apply(k * norm_power(s(t - tau) - R, 3), "upper", ctx).status.is_proof
    assert not Nonpositive().apply(-x(t)[0] * x(t)[1], "upper", ctx).status.is_proof


def test_nonnegative_structure():
    a, b = sympy.symbols("a b", real=True)
    assert nonnegative((a**2 + b**2) ** sympy.Rational(3, 2))
    assert not nonnegative(a - b)
    assert nonnegative(sympy.Integral(a**2, (xi, t - 1, t)))
    assert not nonnegative(sympy.Integral(a**2, (xi, t, t - 1)))


def test_triangle_inequality_and_operator_norm_nodes(ctx):
    from lkverify.certify.steps.rules import mapped, summed

    A = sympy.Matrix([[0, 2, 0], [0, 0, 0], [0, 0, 1]])
    v = 3 * s(t).cross(R) + A * omega(t)
    term = omega(t).dot(v)
    nb = summed(scaled(3, crossed(measured(E), unit(R))), mapped(A, measured(W), 2))
    ok = CauchySchwarz(omega(t), v, (measured(W), nb)).apply(term, "upper", ctx)
    assert ok.status is Status.EXACT and sympy.expand(ok.bound - w * (3 * e + 2 * w)) == 0
    small = summed(scaled(3, crossed(measured(E), unit(R))), mapped(A, measured(W), sympy.Rational(19, 10)))
    bad = CauchySchwarz(omega(t), v, (measured(W), small)).apply(term, "upper", ctx)
    assert bad.status is Status.FAILED and "operator norm is larger" in bad.detail
    # a triangle whose parts do not add up to the vector
    wrong = summed(scaled(2, crossed(measured(E), unit(R))), mapped(A, measured(W), 2))
    assert CauchySchwarz(omega(t), v, (measured(W), wrong)).apply(term, "upper", ctx).status is Status.FAILED


def test_homogeneous_rewrite_certifies_the_constant_and_checks_the_degree(ctx):
    from lkverify.certify.steps.rules import Homogeneous

    MEAS = dict(MEASURES)
    e2m = norm_measure("e2", x(t))
    MEAS["e2"] = e2m
    c2 = Context(SYS, P.resolve({}, use_defaults=True), MEAS, REGION)
    e2 = e2m.symbol
    g = (e**2 + e2**2) ** sympy.Rational(3, 10) * (e + e2)  # degree 8/5, sup of g/T at e = e2: 2^{3/10}·2/2
    T = e ** sympy.Rational(8, 5) + e2 ** sympy.Rational(8, 5)
    ok = Homogeneous(("e", "e2"), T, "c", factor=w).rewrite(w * g, c2)
    assert ok.status is Status.CERTIFIED
    kappa = ok.constants[0][1]
    assert 2 ** 0.3 <= kappa <= 2 ** 0.3 * 1.01
    bad = Homogeneous(("e", "e2"), e**2 + e2**2, "c", factor=w).rewrite(w * g, c2)
    assert bad.status is Status.FAILED and "homogeneous" in bad.detail


def test_young_with_the_wrong_weight_is_rejected_as_a_justification():
    from lkverify import Functional
    from lkverify.certify.steps.chain import TermBound, TermwiseBound

    T = Term(omega(t).dot(s(t).cross(R)), text="ωᵀ(s×r)")
    V = Functional([T])
    cs = CauchySchwarz(omega(t), s(t).cross(R), (measured(W), crossed(measured(E), unit(R))))
    eps = sympy.Rational(1, 3)
    right = eps * w**2 / 2 + e**2 / (2 * eps)            # w·e ≤ εw²/2 + e²/(2ε)
    wrong = eps * w**2 / 2 + e**2 / 2                     # the weight of e² forgotten
    values = P.resolve({}, use_defaults=True)

    def step(bound):
        return TermwiseBound("Young", V, SYS, "V", [TermBound("ωᵀ(s×r)", bound, cs, then=(Young(w, e, eps=eps),))],
                             bound, tuple(MEASURES.values()), region=REGION, witness_seconds=2.0)

    assert step(right).check(values).status is Status.EXACT
    res = step(wrong).check(values)
    assert not res.status.is_proof
    assert "the stated bound is not the rule's" in res.terms[0].detail
    # and it is false: e = 1/10, w = 1/10·… gives ωᵀ(s×r) close to w·e > εw²/2 + e²/2 for w ≈ 3e
    assert res.status is Status.FAILED
