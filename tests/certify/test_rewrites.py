"""The rewrites of lkverify.certify.steps.rewrites and the Krasovskii conclusion: true steps proved,
mutated steps (a wrong direction, a wrong sign, a power the region does not allow, a lemma that
fails) refused."""

import sympy
import pytest

from lkverify import Equation, Parameters, Status, System, Term, Vector, t, xi
from lkverify.certify.steps.chain import Krasovskii, TermBound, TermwiseBound, collect_monomials
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, PowerSplit, WindowHolder, YoungEach
from lkverify.certify.steps.rules import Condition, Context, Rayleigh

P = Parameters()
c = P.scalar("c", positive=True, default=2)
x, y = Vector("x", 2), Vector("y", 2)
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
A_, B_ = norm_measure("a", x(t)), norm_measure("b", y(t))
SUP = sup_norm("m", x(xi), window=2)
K_ = window_integral_measure("K", x(xi), p=1, window=2)
I_ = window_integral_measure("I", x(xi), p=2, window=2)
A, B, K, I = A_.symbol, B_.symbol, K_.symbol, I_.symbol
H = sympy.Rational(1, 10)


def ctx(region=True):
    return Context(SYS, P.resolve({}, use_defaults=True), {"a": A_, "b": B_, "K": K_, "I": I_},
                   Region({SUP: H, B_: H}) if region else None)


# -- Young, term by term -------------------------------------------------------------------------
def test_young_each_upper_and_lower_with_a_parameter():
    app = YoungEach(((A, B, 2, 2, sympy.Rational(1, 3)),)).rewrite(6 * A * B + A**3, ctx(), "upper")
    assert app.status is Status.EXACT
    assert sympy.expand(app.bound - (A**2 + 9 * B**2 + A**3)) == 0
    low = YoungEach(((A, B),)).rewrite(-2 * A * B, ctx(), "lower")
    assert low.status is Status.EXACT and sympy.expand(low.bound + A**2 + B**2) == 0


def test_young_each_refuses_the_wrong_sign_and_non_conjugate_exponents():
    assert YoungEach(((A, B),)).rewrite(2 * A * B, ctx(), "lower").status is Status.FAILED
    assert YoungEach(((A, B, 3, 2),)).rewrite(2 * A * B, ctx(), "upper").status is Status.FAILED
    assert YoungEach(((A, B),)).rewrite(A**2, ctx(), "upper").status is Status.FAILED  # nothing matches


def test_young_each_with_fractional_exponents():
    p = sympy.Rational(13, 5)
    q = p / (p - 1)
    app = YoungEach(((A, I ** (1 / q), p, q),)).rewrite(A * I ** (1 / q), ctx(), "upper")
    assert app.status is Status.EXACT
    assert sympy.expand(app.bound - (A**p / p + I / q)) == 0


# -- powers lowered on the region ------------------------------------------------------------------
def test_on_region_uses_the_region_bound_of_the_measure():
    app = OnRegion("a", 2).rewrite(c * A**3 * B, ctx(), "upper")
    assert app.status is Status.EXACT and sympy.expand(app.bound - 2 * H * A**2 * B) == 0
    app = OnRegion("I", 1).rewrite(I**2, ctx(), "upper")           # I ≤ 2·h²: I² ≤ (2h²) I
    assert app.status is Status.EXACT and sympy.expand(app.bound - 2 * H**2 * I) == 0


def test_on_region_refuses_the_wrong_direction_and_no_region():
    assert OnRegion("a", 2).rewrite(-A**3, ctx(), "upper").status is Status.FAILED
    assert OnRegion("a", 2).rewrite(A**3, ctx(), "lower").status is Status.FAILED
    assert OnRegion("a", 2).rewrite(A**3, ctx(region=False), "upper").status is Status.FAILED
    assert OnRegion("a", 4).rewrite(A**3, ctx(), "upper").status is Status.FAILED  # no power above 4


# -- Hölder on the window ---------------------------------------------------------------------------
def test_window_holder_bound_and_monotonicity():
    app = WindowHolder("K", "I").rewrite(3 * B * K, ctx(), "upper")
    assert app.status is Status.EXACT and sympy.expand(app.bound - 3 * sympy.sqrt(2) * B * sympy.sqrt(I)) == 0
    # −K ≤ … would need K ≥ its replacement: refused
    assert WindowHolder("K", "I").rewrite(-3 * B * K, ctx(), "upper").status is Status.UNDECIDED
    assert WindowHolder("K", "I").rewrite(-3 * B * K, ctx(), "lower").status is Status.EXACT
    # orders the wrong way round
    assert WindowHolder("I", "K").rewrite(I, ctx(), "upper").status is Status.FAILED


# -- a power of a sum split --------------------------------------------------------------------------
def test_power_split_in_an_expanded_bound():
    nu = sympy.Rational(3, 10)
    prev = -c * ((A**2 + B**2) / 2) ** nu * (A**2 + 4 * B**2)
    app = PowerSplit().rewrite(prev, ctx(), "upper")
    assert app.status is Status.EXACT
    want = -2 * (2 ** -nu * A ** (2 * nu + 2) + 4 * 2 ** -nu * B ** (2 * nu + 2))
    assert sympy.simplify(app.bound - want) == 0
    assert PowerSplit().rewrite(-prev, ctx(), "upper").status is Status.FAILED   # would lower an upper bound
    assert PowerSplit().rewrite(-prev, ctx(), "lower").status is Status.EXACT


# -- a certified lemma -------------------------------------------------------------------------------
def _lemma(status):
    return lambda ctx: Condition("‖y‖ ≥ ‖x‖ on the region", status, "decided by the test")


def test_lower_bound_needs_the_lemma_and_monotonicity():
    good = LowerBound("b", A, _lemma(Status.CERTIFIED), "‖y‖ ≥ ‖x‖").rewrite(-c * B**2, ctx(), "upper")
    assert good.status is Status.CERTIFIED and sympy.expand(good.bound + 2 * A**2) == 0
    assert LowerBound("b", A, _lemma(Status.FAILED)).rewrite(-c * B**2, ctx(), "upper").status is Status.FAILED
    # +c b² ≤ c a² would replace b by something smaller in an increasing term: refused
    assert LowerBound("b", A, _lemma(Status.CERTIFIED)).rewrite(c * B**2, ctx(), "upper").status is Status.UNDECIDED


# -- the Krasovskii conclusion -------------------------------------------------------------------------
def _steps(cl, cu, cw, extra_w=0):
    n = norm_measure("n", x(t))
    N = n.symbol

    def step(role, coeff, rel, extra=0):
        rule = Rayleigh(x(t), sympy.eye(2), factor=coeff, eigenvalue=1, norm_squared=N**2)
        return TermwiseBound(role, None, SYS, "terms", [TermBound("T", coeff * N**2, rule)], coeff * N**2 + extra, [n],
                             relation=rel, region=Region({n: 1}), role=role,
                             terms=(Term(coeff * x(t).dot(x(t)), text="T"),))
    values = P.resolve({}, use_defaults=True)
    out = {}
    for role, coeff, rel in (("lower", cl, ">="), ("upper", cu, "<="), ("vdot", cw, "<=")):
        s_ = step(role, coeff, rel)
        out[role] = (s_, s_.check(values))
    return out, values


def test_krasovskii_proves_and_refutes_by_the_signs():
    steps, values = _steps(1, 2, -3)
    rows, status, detail = Krasovskii(("n",)).certify(steps, values)
    assert status is Status.EXACT and rows[0].status is Status.EXACT
    for bad, what in (((-1, 2, -3), "V ≥ φ fails"), ((1, 2, 3), "V̇ ≤ −ψ fails"), ((1, -2, -3), "V ≤ U fails")):
        steps, values = _steps(*bad)
        rows, status, detail = Krasovskii(("n",)).certify(steps, values)
        assert status is Status.FAILED and detail.startswith(what), detail


def test_krasovskii_certifies_irrational_coefficients_and_a_tiny_exact_difference():
    steps, values = _steps(sympy.sqrt(2) - sympy.Rational(141421356237, 10**11), 1, -1)
    assert Krasovskii(("n",)).certify(steps, values)[1] is Status.CERTIFIED      # √2 − 1.41421356237 > 0
    steps, values = _steps(sympy.Rational(141421356237, 10**11) - sympy.sqrt(2), 1, -1)
    assert Krasovskii(("n",)).certify(steps, values)[1] is Status.FAILED


def test_krasovskii_needs_each_point_measure():
    steps, values = _steps(1, 2, -3)
    assert "not measures of the steps" in Krasovskii(("n", "q")).certify(steps, values)[2]


def test_collect_monomials_sums_like_terms():
    got = collect_monomials(A**2 * 3 + c * A**2 - A * B, {A, B})
    assert got == {A**2: c + 3, A * B: -1}


@pytest.mark.parametrize("rewrite", [YoungEach(((A, B),)), OnRegion("a", 1), WindowHolder("K", "I"), PowerSplit(),
                                     LowerBound("b", A, _lemma(Status.EXACT))])
def test_every_rewrite_is_directional(rewrite):
    assert rewrite.directional
