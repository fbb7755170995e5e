"""Algebraic decay claims (lkverify.simulate.trend): E' ≈ −k h E^λ judged in tail windows.

Reference: x' = −h x³ has E = x² with E' = −2hE² exactly, so 1/E = 1/E(0) + 2∫h (k = 2, λ = 2);
it tends to 0 iff ∫h = ∞.  The claims must fail on a trajectory that does not decay, on one that
settles at a positive energy under a non-integrable h, and on the wrong side of the dichotomy.
"""

import numpy as np
import pytest
import sympy

from lkverify import Equation, InputError, Parameters, Status, System, Term, Vector, t
from lkverify.catalogue.examples import Example
from lkverify.simulate import DecaysAlgebraically, LimitAboveFloor, Run
from lkverify.simulate.trend import window_rates

x = Vector("x", 1)
HALF, TWO = "(1+t)**(-1/2)", "(1+t)**(-2)"


def _example(rhs, t_end=50.0):
    sys = System([Equation(x, [Term(rhs)])], parameters=Parameters())
    ex = Example("demo", runs=[Run("r", sys, history={"x": [1]})], t_end=t_end, series=[],
                 distance=lambda s: abs(s["x"][:, 0]), samples=501)
    return ex, ex.simulate()


def _h(expr):
    return sympy.sympify(expr.replace("t", "T")).subs(sympy.Symbol("T"), t)


@pytest.fixture(scope="module")
def cubic():
    """x' = −h x³ for h = (1+t)^{−1/2} (decays) and h = (1+t)^{−2} (positive limit 1/3)."""
    return {h: _example(-_h(h) * x(t)[0] ** 3) for h in (HALF, TWO)}


def energy(s):
    return s["x"][:, 0] ** 2


def test_window_rates_of_the_exact_law():
    tt = np.linspace(0.0, 10.0, 101)
    edges, rates = window_rates(tt, (1 + 3 * tt) ** -0.5, lambda a, b: b - a, order=3, tail=1.0, windows=4)
    assert edges[0] == 0.0 and edges[-1] == 10.0 and np.allclose(rates, 1.5)     # (E^{−2})' = 3 = (λ−1)k


def test_decay_to_zero_is_observed_with_the_rate_of_the_law(cubic):
    res = DecaysAlgebraically("r", energy, HALF).check(*cubic[HALF])
    assert res.status is Status.SIMULATED
    assert np.allclose(res.value["rates"], 2.0, rtol=1e-3)
    assert res.value["tail_integral"] == float("inf") and res.value["t_fraction"] > 50


def test_the_same_claim_written_differently_passes(cubic):
    ex, trs = cubic[HALF]
    # 3x² obeys (3x²)' = −(2/3)h(3x²)²: another rate, the same verdict; x⁴ obeys (x⁴)' = −4h(x⁴)^{3/2}
    three = DecaysAlgebraically("r", lambda s: 3 * s["x"][:, 0] ** 2, sympy.sympify("(1+t)**(-1/2)")
                                .subs(sympy.Symbol("t"), t)).check(ex, trs)
    assert three.status is Status.SIMULATED and np.allclose(three.value["rates"], 2 / 3, rtol=1e-3)
    quartic = DecaysAlgebraically("r", lambda s: s["x"][:, 0] ** 4, HALF, order=1.5).check(ex, trs)
    assert quartic.status is Status.SIMULATED and np.allclose(quartic.value["rates"], 4.0, rtol=1e-3)


def test_decay_fails_on_a_trajectory_that_does_not_decay():
    res = DecaysAlgebraically("r", energy, HALF).check(*_example(0 * x(t)[0]))
    assert res.status is Status.FAILED and max(res.value["rates"]) == 0


def test_decay_fails_when_the_energy_settles_at_a_positive_level():
    # x' = −h x (x − 1/2)... settles at 1/2 although ∫h = ∞: the rates fall to 0 (not steady)
    res = DecaysAlgebraically("r", energy, HALF).check(*_example(-_h(HALF) * 5 * x(t)[0] * (x(t)[0] - sympy.S.Half)))
    assert res.status is Status.FAILED
    assert min(res.value["rates"]) < 0.25 * max(res.value["rates"])


def test_decay_fails_for_an_integrable_damping(cubic):
    res = DecaysAlgebraically("r", energy, TWO).check(*cubic[TWO])
    assert res.status is Status.FAILED and np.isfinite(res.value["tail_integral"])


def test_positive_limit_is_observed_and_fails_on_the_other_side(cubic):
    res = LimitAboveFloor("r", energy, TWO, bound=2).check(*cubic[TWO])
    assert res.status is Status.SIMULATED and res.value["energy_limit_lower"] == pytest.approx(1 / 3, rel=1e-3)
    assert LimitAboveFloor("r", energy, HALF, bound=2).check(*cubic[HALF]).status is Status.FAILED
    assert LimitAboveFloor("r", energy, TWO, bound=0.5).check(*cubic[TWO]).status is Status.FAILED  # |x(0)| = 1


def test_a_proved_rate_bound_is_used_and_a_too_weak_floor_fails(cubic):
    ok = LimitAboveFloor("r", energy, TWO, rate=2.0).check(*cubic[TWO])
    assert ok.status is Status.SIMULATED and ok.value["rate_used"] == 2.0
    assert "proved rate" in ok.detail
    # an enormous rate bound makes the extrapolated floor tiny: the claim is not shown
    assert LimitAboveFloor("r", energy, TWO, rate=1e6, fraction=1e-3).check(*cubic[TWO]).status is Status.FAILED


@pytest.mark.parametrize("kw", [{"order": 1}, {"tail": 0}, {"windows": 1}, {"damping": "x + t"}])
def test_bad_arguments_are_refused(kw):
    args = {"run": "r", "measure": energy, "damping": HALF, **kw}
    with pytest.raises(InputError):
        DecaysAlgebraically(**args)


def test_damping_none_follows_the_runs_h():
    P = Parameters()
    h = P.coefficient("h", default="(1+t)**(-1/2)")
    sys = System([Equation(x, [Term(-h(t) * x(t)[0] ** 3)])], parameters=P)
    ex = Example("demo", runs=[Run("r", sys, history={"x": [1]})], t_end=50, series=[],
                 distance=lambda s: abs(s["x"][:, 0]), samples=501)
    claim = DecaysAlgebraically("r", energy)
    assert claim.check(ex, ex.simulate()).status is Status.SIMULATED
    other = claim.check(ex, ex.simulate({"h": "(1+t)**(-2)"}))           # the run's h changed: ∫h < ∞ now
    assert other.status is Status.FAILED and other.value["tail_integral"] == pytest.approx(1 / 51)
    with pytest.raises(InputError, match="no h"):
        claim.check(*_example(-x(t)[0] ** 3))
