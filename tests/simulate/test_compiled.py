"""simulate() on the compiled integrator (lkverify.simulate.dop853) against the SciPy path and closed forms.

The compiled path is SciPy's DOP853 method of steps compiled: the same steps (counts equal), states equal to
rounding, the same outcomes; a run it does not support goes to the SciPy path, and the trajectory says which ran.
"""

import numpy as np
import pytest
import sympy

from lkverify import Equation, InputError, Parameters, System, Term, UnsupportedInput, Vector, t, xi
from lkverify.catalogue.loader import find_items
from lkverify.declare.functional import memory_integral, window_integral
from lkverify.options import Deadline
from lkverify.simulate import Outcome, StepControl, simulate

COMPILED, SCIPY = "compiled DOP853 (native code)", "SciPy DOP853 (Python right-hand side)"


def both(system, **kw):
    """(compiled run, SciPy run) of the same arguments."""
    a = simulate(system, **kw)
    b = simulate(system, integrator="scipy", **kw)
    assert a.integrator == COMPILED and b.integrator == SCIPY
    return a, b


def diff(a, b) -> float:
    return max(float(np.max(np.abs(a.states[k] - b.states[k]))) for k in a.states)


def delay_system(sign=-1):
    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    return System([Equation(x, [Term(sign * a * x(t - tau)[0])])], parameters=P)


def exact_solution(n_pieces: int):
    """x' = −x(t − 1), x ≡ 1 on [−1, 0]: the method-of-steps polynomials, exactly."""
    s = sympy.Symbol("s")
    pieces, value = [sympy.Integer(1)], sympy.Integer(1)
    for k in range(n_pieces):
        q = sympy.expand(value - sympy.integrate(pieces[-1].subs(s, s - 1), (s, k, s)))
        pieces.append(q)
        value = q.subs(s, k + 1)
    return lambda u: float(pieces[min(int(np.floor(u)), n_pieces - 1) + 1].subs(s, sympy.Rational(str(u))))


@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-10])
def test_closed_form_as_accurate_as_the_scipy_path(rtol):
    grid = np.linspace(0.0, 6.0, 61)
    exact = exact_solution(6)
    ref = np.array([exact(u) for u in grid])
    a, b = both(delay_system(), history={"x": [1]}, t_end=6.0, t_eval=grid, step=StepControl(rtol=rtol, atol=rtol / 100))
    err_a, err_b = (float(np.max(np.abs(tr.states["x"][:, 0] - ref))) for tr in (a, b))
    assert a.n_steps == b.n_steps and a.solution.n_rejected == b.solution.n_rejected
    assert err_a <= 1.01 * err_b + 1e-14
    assert err_a < 100 * rtol


def test_window_auxiliaries_resynchronised_as_simulate():
    """x' = −∫_{t−1}^t x: the window is re-synchronised; a long run keeps z = ∫ x (no drift)."""
    P = Parameters()
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-window_integral(x(xi)[0], 1))])], parameters=P)
    grid = np.linspace(0.0, 200.0, 401)
    a, b = both(sys, history={"x": [1]}, t_end=200.0, t_eval=grid)
    assert diff(a, b) < 1e-12
    sol = a.solution
    z_end, x_int = float(sol.y[-1, 1]), float(sol.sol.integrate(lambda Y: Y[:, 0], 199.0, 200.0))
    assert abs(z_end - x_int) < 1e-13


def test_exponential_kernel_and_two_lags():
    P = Parameters()
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    kernel = memory_integral(sympy.exp(-2 * (t - xi)) * x(xi)[0])
    sys = System([Equation(x, [Term(-x(t - tau)[0] / 2 - x(t - 2 * tau / 3)[0] / 2 - kernel)])], parameters=P)
    a, b = both(sys, history={"x": [1]}, t_end=30.0, t_eval=np.linspace(0, 30, 301))
    assert a.n_steps == b.n_steps and diff(a, b) < 1e-11


def test_catalogue_rigid_body_monitors_and_dense_output():
    (ex,) = find_items("aleksandrov2026.example")
    run = ex.runs[0]
    a, b = both(run.system, history=run.history, t_end=40.0, values=run.values, t_eval=np.linspace(0, 40, 201))
    assert a.n_steps == b.n_steps and diff(a, b) < 1e-11
    (name,) = a.constraint_drift
    assert abs(a.constraint_drift[name] - b.constraint_drift[name]) < 1e-12
    times = [0.3, 7.77, 39.9]
    for k in a.states:
        assert np.max(np.abs(a.at(times)[k] - b.at(times)[k])) < 1e-11


def test_divergence_time_and_outcome_as_scipy():
    a, b = both(delay_system(+1), history={"x": [1]}, t_end=30.0, divergence_bound=1e3)
    assert a.outcome is b.outcome is Outcome.DIVERGED
    assert abs(a.t_fail - b.t_fail) < 1e-9 and a.message == b.message
    assert a.message.startswith("‖y‖ exceeded divergence_bound=1000 at t=")


def test_a_history_in_t_and_rk45_go_to_scipy():
    sys = delay_system()
    assert simulate(sys, history={"x": [sympy.cos(t)]}, t_end=2.0).integrator == SCIPY
    assert simulate(sys, history={"x": [1]}, t_end=2.0, method="RK45").integrator == SCIPY
    with pytest.raises(UnsupportedInput, match="a history that is a function of t"):
        simulate(sys, history={"x": [sympy.cos(t)]}, t_end=2.0, integrator="compiled")
    with pytest.raises(InputError, match="integrator: expected 'auto', 'compiled' or 'scipy'"):
        simulate(sys, history={"x": [1]}, t_end=2.0, integrator="fast")


class ExpiresAfter(Deadline):
    """A deadline that expires after ``k`` looks (deterministic, unlike the clock)."""

    def __init__(self, k):
        super().__init__(100.0)
        self.looks = k

    @property
    def expired(self):
        self.looks -= 1
        return self.looks < 0


def test_a_deadline_is_checked_between_kernel_calls():
    # steps are at most τ = 1/100 long: t_end = 10⁴ needs 10⁶ of them; the first call stops at 20,000 steps
    run = dict(history={"x": [1]}, t_end=1e4, values={"tau": "1/100"})
    tr = simulate(delay_system(), deadline=ExpiresAfter(1), **run)      # alive at the start, spent after call 1
    assert tr.integrator == COMPILED and tr.outcome is Outcome.BUDGET and tr.n_steps == 20_000
    assert 0 < tr.t_fail < 1e4 and "incomplete" in tr.message
    tr = simulate(delay_system(), deadline=ExpiresAfter(2), **run)      # a second call of 4 × 20,000 steps
    assert tr.outcome is Outcome.BUDGET and tr.n_steps == 80_000
    tr = simulate(delay_system(), deadline=ExpiresAfter(0), **run)      # spent before the run: one step
    assert tr.outcome is Outcome.BUDGET and tr.n_steps == 1
    assert simulate(delay_system(), deadline=ExpiresAfter(1), **{**run, "t_end": 10.0}).outcome is Outcome.SUCCESS


def test_a_step_collapse_is_reported():
    """x' = −10⁶ x (stiff; steps ~1e-6) on [0, 1e3]: the step floor (1e3/1e7 = 1e-4) stops the run."""
    P = Parameters()
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-10**6 * x(t)[0] + x(t - 1)[0])])], parameters=P)
    a, b = both(sys, history={"x": [1]}, t_end=1e3)
    assert a.outcome is b.outcome is Outcome.STEP_COLLAPSE
    assert a.message.startswith("steps collapsed at t=") and a.n_steps == b.n_steps
