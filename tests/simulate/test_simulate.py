"""The simulator from the symbolic System: accuracy against independent references, outcomes, bad input."""

import numpy as np
import pytest
import scipy.integrate
import sympy

from lkverify import Equation, InputError, Parameters, System, Term, UnitVector, Vector, cross, t, xi
from lkverify.declare.functional import memory_integral, window_integral
from lkverify.simulate import Outcome, StepControl, compile_system, simulate


def method_of_steps(a, tau, history, intervals):
    """Exact piecewise solution of x' = −a x(t−τ) by integrating interval by interval (SymPy)."""
    s = sympy.Symbol("s")
    pieces = [sympy.sympify(history)]  # on [−τ, 0]
    x0 = sympy.sympify(history).subs(t, 0)
    for k in range(intervals):
        prev = pieces[-1]
        lo = k * tau
        start = x0 if k == 0 else pieces[-1].subs(t, lo)
        piece = start + sympy.integrate((-a * prev.subs(t, s - tau)), (s, lo, t))
        pieces.append(sympy.expand(piece))
    return pieces[1:]


def scalar_delay_system():
    P = Parameters()
    a = P.scalar("a", positive=True, default=sympy.Rational(13, 10))
    tau = P.delay("tau", default=sympy.Rational(7, 10))
    x = Vector("x", 1)
    return System([Equation(x, [Term(-a * x(t - tau)[0], text="−a x(t−τ)")])], parameters=P)


@pytest.mark.parametrize("history", [1, pytest.param(sympy.cos(t), marks=pytest.mark.slow)])
def test_discrete_delay_matches_the_method_of_steps(history):
    a, tau = sympy.Rational(13, 10), sympy.Rational(7, 10)
    pieces = method_of_steps(a, tau, history, 5)
    hist = [history] if history == 1 else sympy.Matrix([history])
    grid = np.linspace(0, 5 * float(tau), 501)
    tr = simulate(scalar_delay_system(), history={"x": hist}, t_end=float(5 * tau),
                  step=StepControl(rtol=1e-11, atol=1e-13), t_eval=grid)
    assert tr.outcome is Outcome.SUCCESS
    exact = np.array([float(pieces[min(int(g // float(tau)), 4)].subs(t, g)) for g in grid])
    err = np.max(np.abs(tr.states["x"][:, 0] - exact)) / np.max(np.abs(exact))
    assert err < 1e-8, err


def test_distributed_delay_matches_closed_form_and_does_not_drift():
    """x' = −∫_{t−1}^t x(ξ)dξ with x ≡ 1 on [−1, 0]: on [0, 1], x = 1 − sin t (checked symbolically)."""
    P = Parameters()
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-window_integral(x(xi)[0], tau))])], parameters=P)
    # on [0, 1]: x' = −(∫_{t−1}^0 1 dξ + ∫_0^t x) = −(1 − t) − ∫_0^t x, x(0) = 1
    s = sympy.Symbol("s")
    cand = 1 - sympy.sin(t)
    assert sympy.simplify(sympy.diff(cand, t) + (1 - t) + sympy.integrate(cand.subs(t, s), (s, 0, t))) == 0
    grid = np.linspace(0, 1, 101)
    tr = simulate(sys, history={"x": [1]}, t_end=1.0, step=StepControl(rtol=1e-11, atol=1e-13), t_eval=grid)
    exact = 1 - np.sin(grid)
    assert np.max(np.abs(tr.states["x"][:, 0] - exact)) < 1e-9
    # long run: the auxiliary window state stays equal to the quadrature of the dense history
    long = simulate(sys, history={"x": [1]}, t_end=200.0)
    sol = long.solution
    z_end = sol.y[-1, 1]
    direct = float(np.ravel(sol.sol.integrate(lambda Y: Y[:, 0], 199.0, 200.0))[0])
    assert abs(z_end - direct) < 1e-12


def test_exponential_kernel_is_exact_and_matches_the_quadrature_path():
    """x' = −∫_0^t e^{−2(t−ξ)} x dξ  ⇔  x' = −m, m' = x − 2m."""
    P = Parameters()
    g = P.kernel("g", default="exp(-2*zeta)")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-memory_integral(g(t - xi) * x(xi)[0]))])], parameters=P)
    comp = compile_system(sys)
    assert [a.kind for a in comp.aux] == ["exponential memory"]
    grid = np.linspace(0, 10, 201)
    tr = simulate(sys, history={"x": [1]}, t_end=10.0, step=StepControl(rtol=1e-11, atol=1e-13), t_eval=grid)
    ref = scipy.integrate.solve_ivp(lambda _, y: [-y[1], y[0] - 2 * y[1]], (0, 10), [1, 0], rtol=1e-12,
                                    atol=1e-14, t_eval=grid, method="DOP853")
    assert np.max(np.abs(tr.states["x"][:, 0] - ref.y[0])) < 1e-9
    slow = simulate(sys, history={"x": [1]}, t_end=10.0, step=StepControl(rtol=1e-10, atol=1e-12, max_step=0.02), t_eval=grid,
                    integrals="quadrature")
    assert np.max(np.abs(slow.states["x"][:, 0] - ref.y[0])) < 1e-6


@pytest.mark.slow
def test_window_auxiliary_path_matches_the_quadrature_path():
    P = Parameters()
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-x(t)[0] ** 3), Term(-window_integral(sympy.sin(x(xi)[0]), tau))])],
                 parameters=P)
    grid = np.linspace(0, 6, 61)
    fast = simulate(sys, history={"x": [0.8]}, t_end=6.0, step=StepControl(rtol=1e-11, atol=1e-13), t_eval=grid)
    slow = simulate(sys, history={"x": [0.8]}, t_end=6.0, step=StepControl(rtol=1e-10, atol=1e-12, max_step=0.01), t_eval=grid,
                    integrals="quadrature")
    assert np.max(np.abs(fast.states["x"] - slow.states["x"])) < 1e-7


def test_time_varying_coefficient():
    P = Parameters()
    h = P.coefficient("h", default="1/(1+t)")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-h(t) * x(t)[0])])], parameters=P)
    grid = np.linspace(0, 20, 41)
    tr = simulate(sys, history={"x": [2]}, t_end=20.0, step=StepControl(rtol=1e-11, atol=1e-13), t_eval=grid)
    assert np.max(np.abs(tr.states["x"][:, 0] - 2 / (1 + grid))) < 1e-9
    tr = simulate(sys, history={"x": [2]}, t_end=20.0, values={"h": "(1+t)**(-2)"}, t_eval=grid,
                  step=StepControl(rtol=1e-11, atol=1e-13))
    assert np.max(np.abs(tr.states["x"][:, 0] - 2 * np.exp(-(1 - 1 / (1 + grid))))) < 1e-9


def test_rotation_keeps_the_unit_norm_and_reports_the_drift():
    P = Parameters()
    w, s = Vector("w"), UnitVector("s")
    sys = System([Equation(w, [Term(sympy.zeros(3, 1))]), Equation(s, [Term(-cross(w(t), s(t)))])], parameters=P)
    tr = simulate(sys, history={"w": [0.3, -0.2, 1.0], "s": [0, 0, 1]}, t_end=50.0)
    assert tr.outcome is Outcome.SUCCESS
    (name, drift), = tr.constraint_drift.items()
    assert "s" in name and 0 <= drift < 1e-7


def test_divergence_is_an_outcome_with_a_time():
    P = Parameters()
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(3 * x(t - 1)[0])])], parameters=P)
    tr = simulate(sys, history={"x": [1]}, t_end=100.0, divergence_bound=1e6)
    assert tr.outcome is Outcome.DIVERGED
    assert tr.t_fail is not None and 0 < tr.t_fail < 100


def test_bad_input():
    sys = scalar_delay_system()
    with pytest.raises(InputError, match="t_end"):
        simulate(sys, history={"x": [1]}, t_end=-1.0)
    with pytest.raises(InputError, match="tau"):
        simulate(sys, history={"x": [1]}, t_end=1.0, values={"tau": "-1"})
    with pytest.raises(InputError, match="1 components"):
        simulate(sys, history={"x": [1, 2]}, t_end=1.0)
    with pytest.raises(InputError, match="no history"):
        simulate(sys, history={}, t_end=1.0)
    P = Parameters()
    g = P.kernel("g", default="1")
    x = Vector("x", 1)
    bad = System([Equation(x, [Term(-memory_integral(g(t - xi) * x(xi)[0]))])], parameters=P)
    with pytest.raises(InputError, match="not integrable"):
        compile_system(bad)


def test_lags_are_resolved_exactly_and_step_limits_reported():
    import sympy as sp

    from lkverify import Equation, Parameters, System, Term, Vector
    from lkverify.declare.symbols import t as tt
    P = Parameters()
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-x(tt - tau)[0] - x(tt - tau / 3)[0] / 2)])], parameters=P)
    comp = compile_system(sys, {"tau": sp.Rational(3, 10)})
    assert comp.exact_lags == (sp.Rational(1, 10), sp.Rational(3, 10)) and comp.lags == (0.1, 0.3)
    tr = simulate(sys, history={"x": [1]}, t_end=1.0)
    assert (tr.max_step, tr.max_step_reason) == (pytest.approx(1 / 3), "shortest delay")
    tr = simulate(sys, history={"x": [1]}, t_end=1.0, step=StepControl(max_step=0.01))
    assert (tr.max_step, tr.max_step_reason) == (0.01, "max_step")
    assert tr.status.value == "simulated"


def test_quadrature_step_limit_is_an_option():
    from lkverify.simulate.control import QUADRATURE_MAX_STEP
    sys = scalar_delay_system()
    tr = simulate(sys, history={"x": [1]}, t_end=1.0, integrals="quadrature")
    assert tr.max_step_reason in ("quadrature_max_step", "shortest delay")
    assert StepControl().limit(has_quadrature=True) == (QUADRATURE_MAX_STEP, "quadrature_max_step")
