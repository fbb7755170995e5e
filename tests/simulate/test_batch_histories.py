"""lkverify.simulate.batch.integrate with one constant history per point (issue 24 item 4): closed forms, one by one, bad input."""

import math

import numpy as np
import pytest
import sympy

from lkverify import Equation, InputError, Parameters, System, Term, Vector, t
from lkverify.simulate import Outcome
from lkverify.simulate.family import compile_family


@pytest.fixture(scope="module")
def delay_family():
    """x' = −a x(t − 1): x = x0(1 − a t) on [0, 1], x0(1 − a t + a²(t − 1)²/2) on [1, 2]."""
    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    x = Vector("x", 1)
    return compile_family(System([Equation(x, [Term(-a * x(t - 1)[0])])], parameters=P), grid=("a",))


@pytest.fixture(scope="module")
def ode_family():
    """x' = A x with no parameter left (grid=()) and no delay: x = e^{At} x0, A = [[0, 1], [−1, 0]]."""
    x = Vector("x", 2)
    A = sympy.Matrix([[0, 1], [-1, 0]])
    return compile_family(System([Equation(x, [Term(A * sympy.Matrix(x(t)))])], parameters=Parameters()), grid=())


def test_ode_without_parameters_from_per_point_initial_states(ode_family):
    assert ode_family.exact_lags == () and ode_family.grid == ()
    x0 = np.array([[1.0, 0.0], [0.0, 2.0], [3.0, -1.0]])
    te = np.array([0.0, 1.0, 5.0])
    res = ode_family.integrate(np.zeros((3, 0)), [{"x": row} for row in x0], t_end=5.0, t_eval=te)
    assert res.outcomes == [Outcome.SUCCESS] * 3
    for i, row in enumerate(x0):
        exact = np.array([[math.cos(s) * row[0] + math.sin(s) * row[1], -math.sin(s) * row[0] + math.cos(s) * row[1]]
                          for s in te])
        assert np.max(np.abs(res.y[i] - exact)) <= 1e-7


def test_per_point_histories_equal_the_points_run_one_by_one(delay_family):
    pts = np.array([[1.0], [0.5], [1.0], [2.0]])
    hist = [{"x": [1.0]}, {"x": [2.0]}, {"x": [-3.0]}, {"x": [1.0]}]
    te = np.linspace(0.0, 2.0, 5)
    res = delay_family.integrate(pts, hist, t_end=2.0, t_eval=te)
    for i in range(len(pts)):
        one = delay_family.integrate(pts[i:i + 1], hist[i], t_end=2.0, t_eval=te)
        assert np.array_equal(one.y[0], res.y[i]) and one.n_steps[0] == res.n_steps[i]
    # the history enters the delayed terms too: x(2) = x0(1 − a·2 + a²/2)
    for i, (a,) in enumerate(pts):
        assert res.y[i, -1, 0] == pytest.approx(hist[i]["x"][0] * (1 - 2 * a + a * a / 2), abs=1e-9)


def test_a_shared_history_is_unchanged(delay_family):
    te = [1.0, 2.0]
    shared = delay_family.integrate([[1.0], [0.5]], {"x": [2.0]}, t_end=2.0, t_eval=te)
    listed = delay_family.integrate([[1.0], [0.5]], [{"x": [2.0]}, {"x": [2.0]}], t_end=2.0, t_eval=te)
    assert np.array_equal(shared.y, listed.y) and np.array_equal(shared.outcome, listed.outcome)


def test_bad_histories(delay_family):
    with pytest.raises(InputError, match="one such mapping per point"):
        delay_family.integrate([[1.0], [0.5]], [{"x": [1.0]}], t_end=1.0, t_eval=[1.0])
    with pytest.raises(InputError, match="one such mapping per point"):
        delay_family.integrate([[1.0]], "x=1", t_end=1.0, t_eval=[1.0])
    with pytest.raises(InputError, match="one constant vector for each state"):
        delay_family.integrate([[1.0], [0.5]], [{"x": [1.0]}, {"y": [1.0]}], t_end=1.0, t_eval=[1.0])
