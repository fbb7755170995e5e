"""The time-varying conclusion V̇ ≤ −α h^ν(t) V (lkverify.certify.steps.timevarying) and its pieces."""

import pytest
import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t
from lkverify.certify.steps import (Rayleigh, Region, TermBound, TermwiseBound, TimeVaryingRate, UpperBound,
                                    norm_measure, sup_in_t, sup_on)
from lkverify.certify.steps.rules import Condition, Context
from lkverify.certify.steps.timevarying import inf_on
from lkverify.status import Status

R = sympy.Rational
X = sympy.Symbol("x", positive=True)


# -- sup over 0 < x ≤ H, term by term ----------------------------------------------------------------
def test_sup_on_bounds_each_term_by_its_sign_and_power():
    assert sup_on(-2 * X + 3 * X**2, X, R(1, 2)) == (R(3, 4), None)  # −2x ≤ 0, 3x² ≤ 3/4
    assert sup_on(5 - X**-1, X, 1) == (4, None)  # −1/x ≤ −1 on (0, 1]
    assert sup_on(sympy.sqrt(2) * X**R(3, 2), X, 4)[0] == 8 * sympy.sqrt(2)


def test_sup_on_refuses_an_unbounded_term_and_a_symbolic_coefficient():
    s, why = sup_on(X ** R(-1, 2) - 1, X, 1)
    assert s is None and "unbounded" in why
    s, why = sup_on(sympy.Symbol("a") * X, X, 1)
    assert s is None and "not a sum" in why


def test_inf_on_is_minus_the_sup_of_minus():
    assert inf_on(2 - X, X, 1) == (1, None)
    assert inf_on(X**-1, X, 2) == (R(1, 2), None)


def test_sup_in_t_monotone_limit_critical_and_unbounded():
    assert sup_in_t((1 + t) ** R(-7, 8))[0] == 1
    assert sup_in_t(1 - 1 / (2 * (1 + t)))[0] == 1  # increasing: the limit
    assert sup_in_t(t * sympy.exp(-t))[0] == sympy.exp(-1)  # one critical point
    assert sup_in_t((1 + t) ** R(-7, 8), 3)[0] == 4 ** R(-7, 8)  # t ≥ t0 = 3
    H, why = sup_in_t(1 + t)
    assert H is None and "not bounded" in why


# -- the explicit-time normalisation of Context.zero -------------------------------------------------
def _ctx():
    P = Parameters()
    x = Vector("x", 2)
    return Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {})


def test_context_zero_takes_time_nonnegative():
    ctx = _ctx()
    h = (1 + t) ** R(-7, 8)
    assert ctx.zero(sympy.sqrt(h**2) - h)  # |h| = h on t ≥ 0
    assert ctx.zero(sympy.diff(h, t) * (1 + t) + R(7, 8) * h)  # ḣ over one denominator
    assert not ctx.zero(sympy.sqrt(h**2) - (1 + t) ** R(-9, 10))
    assert not ctx.zero(sympy.diff(h, t) * (1 + t) + R(7, 9) * h)


# -- UpperBound ---------------------------------------------------------------------------------------
def _measures_ctx():
    P = Parameters()
    x = Vector("x", 2)
    a, n = norm_measure("a", x(t)), norm_measure("n", x(t) / 2)
    return Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"a": a, "n": n}), a, n


def test_upper_bound_substitutes_where_the_bound_increases_and_reports_the_condition():
    ctx, a, n = _measures_ctx()
    ok = UpperBound("n", a.symbol, lambda c: Condition("‖x/2‖ ≤ ‖x‖", Status.EXACT), "‖x/2‖ ≤ ‖x‖")
    app = ok.rewrite(3 * n.symbol**2 + a.symbol, ctx)
    assert app.status is Status.EXACT and app.bound == 3 * a.symbol**2 + a.symbol
    assert ok.rewrite(-3 * n.symbol**2, ctx, "lower").status is Status.EXACT  # −3n² ≥ −3a²


def test_upper_bound_refuses_the_wrong_monotonicity_and_a_failed_condition():
    ctx, a, n = _measures_ctx()
    ok = UpperBound("n", a.symbol, lambda c: Condition("‖x/2‖ ≤ ‖x‖", Status.EXACT))
    assert ok.rewrite(-3 * n.symbol**2, ctx).status is Status.UNDECIDED  # −3n² ≤ −3a² does not follow
    bad = UpperBound("n", a.symbol / 4, lambda c: Condition("‖x/2‖ ≤ ‖x‖/4", Status.FAILED, "x = (1, 0)"))
    app = bad.rewrite(3 * n.symbol**2, ctx)
    assert app.status is Status.FAILED and "x = (1, 0)" in app.detail


# -- TimeVaryingRate on x' = −h(t)x, h = 1/(1+t) ------------------------------------------------------------
P = Parameters()
x = Vector("x", 2)
HT = 1 / (1 + t)
N = norm_measure("n", x(t))
HM = norm_measure("hh", sympy.Matrix([HT]))
n, hh = N.symbol, HM.symbol
SYS = System([Equation(x, [Term(-HT * x(t))])], parameters=P)


def _step(role, bound, factor, rel="<="):
    rule = Rayleigh(x(t), sympy.eye(2), factor=factor, eigenvalue=1, norm_squared=n**2)
    expr = sympy.sympify(factor).subs(hh, HT) * x(t).dot(x(t))
    return TermwiseBound(role, None, SYS, "terms", [TermBound("T", bound, rule)], bound, [N, HM], relation=rel,
                         region=Region({N: 1}), role=role, witness_time=1, terms=(Term(expr, text="T"),))


def _steps(lower=(1, sympy.S.One), upper=(1, sympy.S.One), vdot=(-2 * hh, -2 * hh)):
    out = {}
    for role, (c, f), rel in (("lower", lower, ">="), ("upper", upper, "<="), ("vdot", vdot, "<=")):
        s = _step(role, c * n**2, f, rel)
        out[role] = (s, s.check(P.resolve({})))
        assert out[role][1].status.is_proof
    return out


@pytest.fixture(scope="module")
def steps():
    return _steps()


def test_rate_exact_with_its_constants(steps):
    rows, status, detail = TimeVaryingRate(("n",), "hh", 1, 2).certify(steps, P.resolve({}))
    assert status is Status.EXACT
    value = rows[0].value
    assert value["H"] == "1" and value["alpha1"] == 1 and value["alpha2"] == 1 and value["alpha_largest"] == 2
    assert value["delta2"] == 1  # δ1·√(α1/α2)
    assert rows[1].kind == "envelope" and "stays in the region" in rows[1].detail


def test_rate_written_differently_passes(steps):
    for alpha in (sympy.Integer(1), R(4, 2), sympy.sqrt(2)):  # any α ≤ 2; √2 decided in arb
        status = TimeVaryingRate(("n",), "hh", 1, alpha).certify(steps, P.resolve({}))[1]
        assert status in (Status.EXACT, Status.CERTIFIED)
    assert TimeVaryingRate(("n",), "hh", 1, sympy.sqrt(2)).certify(steps, P.resolve({}))[1] is Status.CERTIFIED


def test_rate_too_large_fails_at_the_monomial(steps):
    rows, status, detail = TimeVaryingRate(("n",), "hh", 1, R(201, 100)).certify(steps, P.resolve({}))
    assert status is Status.FAILED and detail.startswith("fails at the monomial n**2") and "0.01 > 0" in detail
    assert rows and rows[0].status is Status.FAILED


def test_rate_with_a_higher_power_of_h_fails():
    # V̇ ≤ −2h n² does not give V̇ ≤ −α h^0 V for any α > 0 (h → 0): the power h^{ν} matters
    rows, status, detail = TimeVaryingRate(("n",), "hh", 0, R(1, 100)).certify(_steps(), P.resolve({}))
    assert status is Status.FAILED and "n**2" in detail


def test_flipped_sign_of_w_fails():
    steps = _steps(vdot=(2 * hh, 2 * hh))
    status = TimeVaryingRate(("n",), "hh", 1, R(1, 100)).certify(steps, P.resolve({}))[1]
    assert status is Status.FAILED


def test_a_positive_constant_in_w_is_not_dominated_as_h_goes_to_0():
    steps = _steps(vdot=(-2 * hh + R(1, 100), -2 * hh))  # a true, weaker W
    status, detail = TimeVaryingRate(("n",), "hh", 1, R(1, 100)).certify(steps, P.resolve({}))[1:]
    assert status is Status.FAILED and "n**2" in detail


def test_lower_bound_not_positive_fails():
    steps = _steps(lower=(-1, -sympy.S.One))
    status, detail = TimeVaryingRate(("n",), "hh", 1, 1).certify(steps, P.resolve({}))[1:]
    assert status is Status.FAILED and detail.startswith("V ≥ L fails")


def test_side_conditions_are_reported_and_fail_the_link(steps):
    cond = lambda v: [Condition("∫h = ∞", Status.EXACT), Condition("h ≤ 1/2", Status.FAILED, "h(0) = 1")]  # noqa: E731
    rows, status, detail = TimeVaryingRate(("n",), "hh", 1, 2, conditions=cond).certify(steps, P.resolve({}))
    assert status is Status.FAILED and detail.startswith("side condition h ≤ 1/2: failed (h(0) = 1)")
    assert rows[0].status is Status.EXACT  # the rate itself holds
    assert [r.status for r in rows if r.kind == "hypothesis"] == [Status.EXACT, Status.FAILED]


def test_unknown_measures_and_symbolic_power_are_undecided(steps):
    assert TimeVaryingRate(("q",), "hh", 1, 2).certify(steps, P.resolve({}))[1] is Status.UNDECIDED
    status, detail = TimeVaryingRate(("n",), "hh", sympy.Symbol("nu"), 2).certify(steps, P.resolve({}))[1:]
    assert status is Status.UNDECIDED and "numbers" in detail


def test_zero_or_negative_rate_fails(steps):
    assert TimeVaryingRate(("n",), "hh", 1, 0).certify(steps, P.resolve({}))[1] is Status.FAILED
    assert TimeVaryingRate(("n",), "hh", 1, -1).certify(steps, P.resolve({}))[1] is Status.FAILED


def test_a_floating_point_exponent_is_never_rounded_to_a_rational():
    import sympy as _sp
    from lkverify.certify.steps.timevarying import sup_on as _sup_on
    x = _sp.Symbol("x", positive=True)
    bound, why = _sup_on(x ** _sp.Float(0.5) - 1, x, 1)
    assert bound is None and "not a sum" in why
    assert _sup_on(x ** _sp.Rational(1, 2) - 1, x, 1) == (0, None)


# -- the power rate V̇ ≤ −α h^ν V^λ (lam=): x' = −h‖x‖²x, y' = −h‖y‖²y, V = ‖x‖² (+ ‖y‖²), V̇ = −2h‖x‖⁴ (− 2h‖y‖⁴) ----
Y = Vector("y", 2)
NY = norm_measure("ny", Y(t))
ny = NY.symbol
SYS4 = System([Equation(x, [Term(-HT * x(t).dot(x(t)) * x(t))]), Equation(Y, [Term(-HT * Y(t).dot(Y(t)) * Y(t))])],
              parameters=P)


def _quartic_steps(upper=1, vdot=-2, both=False):
    """V ≥ L, V ≤ U, V̇ ≤ W on SYS4, term by term (Rayleigh with a factor in the measures), all exact."""
    vecs = ((x, N, n), (Y, NY, ny)) if both else ((x, N, n),)

    def step(role, rel, c, extra):
        bounds, terms = [], []
        for vec, _, m in vecs:
            f = sympy.sympify(c) * (hh * m**2 if extra else 1)
            bounds.append(TermBound(f"T{m}", f * m**2, Rayleigh(vec(t), sympy.eye(2), factor=f, eigenvalue=1,
                                                                   norm_squared=m**2)))
            terms.append(Term(f.subs({hh: HT, m: sympy.sqrt(vec(t).dot(vec(t)))}) * vec(t).dot(vec(t)), text=f"T{m}"))
        rhs = sum((b.bound for b in bounds), sympy.S.Zero)
        return TermwiseBound(role, None, SYS4, "terms", bounds, rhs, [N, NY, HM], relation=rel,
                             region=Region({N: 1, NY: 1}), role=role, witness_time=1, terms=tuple(terms))

    out = {}
    for role, rel, c, extra in (("lower", ">=", 1, False), ("upper", "<=", upper, False), ("vdot", "<=", vdot, True)):
        s = step(role, rel, c, extra)
        out[role] = (s, s.check(P.resolve({})))
        assert out[role][1].status.is_proof, out[role][1].detail
    return out


@pytest.fixture(scope="module")
def quartic():
    return _quartic_steps()


def test_power_rate_exact_with_the_algebraic_envelope(quartic):
    rate = TimeVaryingRate(("n",), "hh", 1, 2, lam=2)
    rows, status, detail = rate.certify(quartic, P.resolve({}))
    assert status is Status.EXACT and rows[0].name == "V̇ ≤ −α8 h^ν V^λ" and "V^λ" in rate.link
    assert rows[0].value["alpha_largest"] == 2 and rows[0].value["lam"] == "2"
    assert "(1 + 2·(2−1)V(t0)^(2−1)∫h^1)^(−1/(2−1))" in detail and "exp" not in rows[1].detail
    assert TimeVaryingRate(("n",), "hh", 1, 2).link.startswith("(12)")  # λ = 1 keeps its name


def test_power_rate_written_differently_passes(quartic):
    for alpha, lam in ((1, R(4, 2)), (sympy.sqrt(3), 2), (R(1, 2), sympy.Integer(2))):
        assert TimeVaryingRate(("n",), "hh", 1, alpha, lam=lam).certify(quartic, P.resolve({}))[1].is_proof


def test_power_rate_too_large_or_wrong_power_fails(quartic):
    status, detail = TimeVaryingRate(("n",), "hh", 1, R(201, 100), lam=2).certify(quartic, P.resolve({}))[1:]
    assert status is Status.FAILED and detail.startswith("fails at the monomial n**4")
    # a quartic W gives no V̇ ≤ −α h V (λ = 1): the n² monomial is not dominated
    status, detail = TimeVaryingRate(("n",), "hh", 1, R(1, 100)).certify(quartic, P.resolve({}))[1:]
    assert status is Status.FAILED and "n**2" in detail
    # nor λ = 3/2 (V^{3/2} ~ n³ is not dominated by n⁴ near 0)
    assert TimeVaryingRate(("n",), "hh", 1, R(1, 100), lam=R(3, 2)).certify(quartic, P.resolve({}))[1] is Status.FAILED


def test_power_rate_flipped_sign_and_lambda_below_one():
    status = TimeVaryingRate(("n",), "hh", 1, R(1, 100), lam=2).certify(_quartic_steps(vdot=2), P.resolve({}))[1]
    assert status is Status.FAILED
    status, detail = TimeVaryingRate(("n",), "hh", 1, 1, lam=R(1, 2)).certify(_quartic_steps(), P.resolve({}))[1:]
    assert status is Status.UNDECIDED and "≥ 1" in detail


def test_power_rate_uses_sup_u_to_the_power_and_the_number_of_squares():
    # U = 2n²: U² = 4n⁴, so α ≤ 2/4
    steps = _quartic_steps(upper=2)
    assert TimeVaryingRate(("n",), "hh", 1, R(1, 2), lam=2).certify(steps, P.resolve({}))[1] is Status.EXACT
    assert TimeVaryingRate(("n",), "hh", 1, R(51, 100), lam=2).certify(steps, P.resolve({}))[1] is Status.FAILED
    # two squares: (n² + ny²)² ≤ 2(n⁴ + ny⁴), so α ≤ 2/2
    steps = _quartic_steps(both=True)
    assert TimeVaryingRate(("n", "ny"), "hh", 1, 1, lam=2).certify(steps, P.resolve({}))[1] is Status.EXACT
    assert TimeVaryingRate(("n", "ny"), "hh", 1, R(101, 100), lam=2).certify(steps, P.resolve({}))[1] is Status.FAILED
