"""Assumption 1 of paper 000 on the kernel G = g(ζ)I: must-pass and must-fail cases, and its wiring
into the catalogue item aleksandrov2026.theorem2."""

import pytest
import sympy

from lkverify import InputError, zeta
from lkverify.proofs.aleksandrov2026.assumption1 import Assumption1, Assumption1Result, decide_assumption1
from lkverify.status import Status

R = sympy.Rational
a = sympy.Symbol("a", positive=True)
TINY = R(1, 10**30)


def tail_ratio(g, at):
    """The reference R(ζ) = ∫_ζ^∞|g| / |g(ζ)| at one point, integrated directly (g > 0 there)."""
    s = sympy.Symbol("s", positive=True)
    return sympy.simplify(sympy.integrate(g.subs(zeta, s), (s, at, sympy.oo)) / g.subs(zeta, at))


# -- kernels that satisfy it, written differently ---------------------------------------------------

@pytest.mark.parametrize("g, sigma", [
    (sympy.exp(-2 * zeta), R(1, 2)),                       # the paper's default
    (3 * sympy.exp(-2 * zeta), R(1, 2)),                   # a constant factor changes nothing
    ("exp(-2*zeta)", R(1, 2)),                             # text, parsed safely
    ("exp(-2*t)", R(1, 2)),                                # kernels written in t are read in ζ
    (sympy.Lambda(zeta, sympy.exp(-2 * zeta)), R(1, 2)),
    (sympy.exp(-2 * zeta) * (1 + zeta), R(3, 4)),          # R = (2ζ+3)/(4(ζ+1)), sup at ζ = 0
    ((1 + zeta) * sympy.exp(-zeta), 2),                    # R = (ζ+2)/(ζ+1)
    (-sympy.exp(-zeta), 1),                                # the norm: |g|
    (sympy.exp(-a * zeta), 1 / a),                         # Remark 2: σ = 1/a
])
def test_holds_with_the_smallest_sigma(g, sigma):
    r = decide_assumption1(g)
    assert isinstance(r, Assumption1Result) and r.status is Status.EXACT and r.holds
    assert sympy.simplify(r.sigma - sigma) == 0
    assert f"σ = {sigma}" in r.detail


def test_sigma_cross_checked_against_direct_integration():
    g = sympy.exp(-2 * zeta) * (1 + zeta)
    r = decide_assumption1(g)
    assert r.sigma == tail_ratio(g, 0)                     # the sup is R(0)
    assert sympy.simplify(r.ratio.subs(zeta, 5) - tail_ratio(g, 5)) == 0


@pytest.mark.slow
def test_sup_at_an_interior_critical_point():
    g = sympy.exp(-zeta) * (zeta**2 - zeta + 1)
    r = decide_assumption1(g)
    crit = (sympy.sqrt(7) - 1) / 2
    assert r.status is Status.EXACT and sympy.simplify(r.sigma - (7 + 2 * sympy.sqrt(7)) / 3) == 0
    assert sympy.simplify(r.sigma - tail_ratio(g, crit)) == 0
    below = decide_assumption1(g, sigma=r.sigma - TINY)
    assert below.status is Status.FAILED and sympy.simplify(below.witness - crit) == 0
    assert decide_assumption1(g, sigma=r.sigma).status is Status.EXACT


# -- a tiny exact difference: just below the sup fails, at it holds ---------------------------------

@pytest.mark.parametrize("g, sup", [(sympy.exp(-2 * zeta), R(1, 2)), ((1 + zeta) * sympy.exp(-zeta), 2)])
def test_tiny_exact_difference(g, sup):
    assert decide_assumption1(g, sigma=sup).status is Status.EXACT
    assert decide_assumption1(g, sigma=sup + TINY).status is Status.EXACT
    r = decide_assumption1(g, sigma=sup - TINY)
    assert r.status is Status.FAILED and r.witness == 0
    assert tail_ratio(g, r.witness) - (sup - TINY) > 0


@pytest.mark.slow
def test_sup_only_as_a_limit():
    u = 1 / (1 + zeta)
    g = sympy.exp(-zeta) * (1 + u + u**2)                  # R = (ζ²+3ζ+2)/(ζ²+3ζ+3) ↑ 1, never reached
    assert decide_assumption1(g, sigma=1).status is Status.EXACT
    r = decide_assumption1(g, sigma=1 - R(1, 10**6))
    assert r.status is Status.FAILED and r.witness is not None
    assert r.ratio.subs(zeta, r.witness) > 1 - R(1, 10**6)


# -- kernels that fail it, each way ----------------------------------------------------------------

def test_ratio_unbounded():
    g = 1 / (1 + zeta) ** 2                                # integrable, but R = 1 + ζ → ∞
    r = decide_assumption1(g)
    assert r.status is Status.FAILED and r.sigma is None
    assert "R(ζ) → ∞" in r.detail and r.ratio == 1 + zeta
    for sigma in (1, 100, R(10**9, 7)):                    # ζ(σ) beats every proposed σ
        z = r.witness(sigma)
        assert z >= 0 and tail_ratio(g, z) > sigma


def test_ratio_unbounded_at_a_given_sigma():
    g = 1 / (1 + zeta) ** 2
    r = decide_assumption1(g, sigma=1000)
    assert r.status is Status.FAILED and "R(ζ) → ∞" in r.detail
    assert tail_ratio(g, r.witness) > 1000


@pytest.mark.parametrize("g, z0", [(sympy.exp(-zeta) * sympy.cos(zeta), sympy.pi / 2),
                                   (zeta * sympy.exp(-zeta), 0),
                                   ((zeta - 1) ** 2 * sympy.exp(-zeta), 1)])
def test_zero_of_the_kernel(g, z0):
    r = decide_assumption1(g)
    assert r.status is Status.FAILED and r.witness == z0
    assert g.subs(zeta, z0) == 0 and "∫_" in r.detail and "> 0" in r.detail


@pytest.mark.parametrize("g", [1 / (1 + zeta), sympy.Integer(2), sympy.exp(zeta)])
def test_not_integrable(g):
    r = decide_assumption1(g)
    assert r.status is Status.FAILED and r.integral is sympy.oo and "diverges" in r.detail


def test_not_continuous():
    r = decide_assumption1(1 / (zeta - 1) ** 2)
    assert r.status is Status.FAILED and r.witness == 1 and "continuous" in r.detail


def test_zero_kernel_holds_trivially():
    assert decide_assumption1(sympy.Integer(0)).status is Status.EXACT


# -- undecided, budget ------------------------------------------------------------------------------

def test_budget_undecided():
    r = decide_assumption1(sympy.exp(-2 * zeta), budget=1e-9)
    assert r.status is Status.UNDECIDED and "budget" in r.detail


def test_undecided_says_what_was_tried():
    r = decide_assumption1(sympy.exp(-zeta) * (2 + sympy.sin(zeta)), budget=0.5)
    assert r.status is Status.UNDECIDED and r.tried and "tried:" in r.detail


# -- floats and bad input ---------------------------------------------------------------------------

@pytest.mark.parametrize("g", [sympy.exp(-0.5 * zeta), 0.5 * sympy.exp(-zeta)])
def test_float_kernel_refused(g):
    with pytest.raises(InputError, match="expected an exact"):
        decide_assumption1(g)


@pytest.mark.parametrize("sigma", [0.5, sympy.Float(0.5), 0, -1, "abc"])
def test_bad_sigma(sigma):
    with pytest.raises(InputError):
        decide_assumption1(sympy.exp(-zeta), sigma=sigma)


@pytest.mark.parametrize("g", ["exp(-2*zeta", "exp(-2*x)", "__import__('os')", sympy.exp(-2 * sympy.Symbol("x")),
                               sympy.eye(2), sympy.exp(-sympy.Symbol("b") * zeta), [1, 2]])
def test_bad_input(g):
    with pytest.raises(InputError):
        decide_assumption1(g)


# -- wired into aleksandrov2026.theorem2 ------------------------------------------------------------

def _theorem2_run(values):
    from lkverify.catalogue.loader import find_items

    (th,) = find_items("aleksandrov2026.theorem2")
    rep = th.run(values, budget=60)
    return th, rep, {r.name: r for r in rep.results}


@pytest.mark.slow  # about 15 s on a loaded machine; the float kernel and tiny exact differences run by default
def test_theorem2_decides_assumption1_at_the_papers_kernel():
    th, rep, res = _theorem2_run({})
    a1 = res["Assumption 1"]
    assert a1.status is Status.EXACT and a1.value == R(1, 2) and "(Assumption 1)" in a1.detail
    assert not any("Assumption 1" in u for u in th.unchecked)
    assert "Assumption 1 (∫" not in rep.verdict


@pytest.mark.slow  # about 25 s on a loaded machine
def test_theorem2_with_other_kernels():
    from lkverify.declare.parse import parse_value

    def kernel(text):
        return parse_value(text, name="g", variables={"zeta": zeta, "t": zeta})

    _, _, res = _theorem2_run({"g": kernel("exp(-3*zeta)")})
    assert res["Assumption 1"].status is Status.EXACT and "σ = 1/3" in res["Assumption 1"].detail
    _, rep, res = _theorem2_run({"g": kernel("1/(1+zeta)**2")})
    assert res["Assumption 1"].status is Status.FAILED and "R(ζ) → ∞" in res["Assumption 1"].detail
    assert rep.verdict.startswith("failed: hypotheses")


@pytest.mark.slow
def test_theorem2_float_kernel_is_never_exact():
    _, _, res = _theorem2_run({"g": sympy.exp(-0.5 * zeta)})
    assert res["Assumption 1"].status is Status.CERTIFIED and "floating-point" in res["Assumption 1"].detail


def test_hypothesis_without_a_value_and_at_a_given_sigma():
    from lkverify.proofs.aleksandrov2026.equations import g

    assert Assumption1("A1", g).evaluate({}).status is Status.UNDECIDED
    sub = {g: sympy.Lambda(zeta, sympy.exp(-2 * zeta))}
    assert Assumption1("A1", g, sigma=R(1, 2)).evaluate(sub).status is Status.EXACT
    assert Assumption1("A1", g, sigma=R(1, 2) - TINY).evaluate(sub).status is Status.FAILED
    with pytest.raises(InputError):
        Assumption1("A1", g, sigma=0.5)
