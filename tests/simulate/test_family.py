"""The compiled family and its numba integrator against the reference path simulate(), closed forms and outcomes.

Families are compiled once per module (numba compilation counts): module-scoped fixtures.
"""

import math
import pickle

import numpy as np
import pytest
import scipy.optimize
import sympy

from lkverify import Equation, InputError, Parameters, System, Term, UnsupportedInput, Vector, t, xi
from lkverify.catalogue.loader import find_items
from lkverify.declare.functional import memory_integral, window_integral
from lkverify.simulate import Outcome, StepControl, simulate
from lkverify.simulate import family as family_module
from lkverify.simulate.family import compile_family

REF = StepControl(rtol=1e-10, atol=1e-12)
TOL = 1e-6


def max_error(tr, res, i) -> float:
    """Largest difference over t_eval and every state between simulate() and point i of a batch."""
    states = res.states(i)
    assert set(states) == set(tr.states)
    return max(float(np.max(np.abs(tr.states[k] - states[k]))) for k in tr.states)


def delay_system():
    """x' = −a x(t − τ) − x(t − 2τ/3)/2: two lags that are expressions in τ."""
    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    return System([Equation(x, [Term(-a * x(t - tau)[0] - x(t - 2 * tau / 3)[0] / 2)])], parameters=P)


# -- paper 002, Fig. 1 and Fig. 2: window integrals, a unit vector, b and h swept --------------------


@pytest.fixture(scope="module")
def fig1():
    (example,) = find_items("aleksandrov2023.fig1")
    run = example.runs[0]
    h = sympy.Symbol("h")
    values = {k: v for k, v in run.values.items() if k not in ("b", "F")}
    values["F"] = sympy.ImmutableMatrix(sympy.diag(h, h, h))
    return run, compile_family(run.system, values, grid=("b", "h"))


FIG_POINTS = np.array([[2.0, 0.7], [-2.0, 0.7], [0.5, 1.5]])   # Fig. 1, Fig. 2 (b = −2), a third point


@pytest.fixture(scope="module")
def fig1_batch(fig1):
    run, fam = fig1
    te = np.linspace(0.0, 60.0, 601)
    return te, fam.integrate(FIG_POINTS, run.history, t_end=60.0, t_eval=te)


def test_fig1_family_layout_and_lags(fig1):
    run, fam = fig1
    assert fam.grid == ("b", "h")
    assert fam.exact_lags == (sympy.Rational(9, 10),)
    assert [kind for kind, _ in fam.aux] == ["window"] * 3
    assert fam.layout == {"omega": slice(0, 3), "s": slice(3, 6)}
    assert fam.lags([2.0, 0.7]).tolist() == [0.9]
    x0 = fam.constant_history(run.history)
    y0 = fam.initial_state([2.0, 0.7], run.history)
    assert y0.shape == (9,) and np.array_equal(y0[:6], x0)


def test_fig1_matches_simulate_at_three_points(fig1, fig1_batch):
    run, _ = fig1
    te, res = fig1_batch
    assert res.outcomes == [Outcome.SUCCESS] * 3
    assert res.y.shape == (3, len(te), 6) and np.array_equal(res.t, te)
    for i, (b, h) in enumerate(FIG_POINTS):
        values = {**run.values, "b": str(b), "F": f"diag({h},{h},{h})"}
        tr = simulate(run.system, history=run.history, t_end=60.0, values=values, t_eval=te, step=REF)
        assert tr.outcome is Outcome.SUCCESS
        assert max_error(tr, res, i) <= TOL, (b, h)


def test_fig1_initial_windows_equal_the_reference_path(fig1):
    """The auxiliary window states start where simulate's quadrature starts them (τ g(x0))."""
    from lkverify.simulate import compile_system

    run, fam = fig1
    values = {**run.values, "b": "2", "F": "diag(0.7,0.7,0.7)"}
    comp = compile_system(run.system, values)
    x0 = fam.constant_history(run.history)

    class Constant:
        t_last = 0.0

        def integrate(self, g, a, b, *, with_time=False):
            return np.atleast_1d((b - a) * np.asarray(g(np.concatenate([x0, np.zeros(3)])[None, :]))[0])

    expected = comp.aux_initial(0.0, Constant())
    assert np.allclose(fam.initial_state([2.0, 0.7], run.history)[6:], expected, rtol=1e-14, atol=1e-15)


def test_a_batch_equals_its_points_run_one_by_one(fig1, fig1_batch):
    run, fam = fig1
    te, res = fig1_batch
    for i in range(len(FIG_POINTS)):
        one = fam.integrate(FIG_POINTS[i:i + 1], run.history, t_end=60.0, t_eval=te)
        assert np.array_equal(one.y[0], res.y[i], equal_nan=True)
        assert (one.outcome[0], one.n_steps[0], one.nfev[0]) == (res.outcome[i], res.n_steps[i], res.nfev[i])


def test_pickle_round_trip_compiles_in_the_new_object(fig1, fig1_batch):
    run, fam = fig1
    te, res = fig1_batch
    data = pickle.dumps(fam)
    assert b"CPUDispatcher" not in data
    copy = pickle.loads(data)
    assert copy.source == fam.source and copy.key == fam.key
    family_module._CACHE.pop(fam.key)          # the copy compiles its own rhs, as a fresh worker process would
    again = copy.integrate(FIG_POINTS[1:2], run.history, t_end=60.0, t_eval=te)
    assert np.array_equal(again.y[0], res.y[1], equal_nan=True)


# -- paper 000: a discrete delay, 12 states --------------------------------------------------------


def test_aleksandrov2026_example_matches_simulate():
    (example,) = find_items("aleksandrov2026.example")
    run = example.runs[0]
    fam = compile_family(run.system, run.values, grid=("alpha1", "alpha2"))
    assert fam.n_states == 12 and fam.n == 12 and fam.exact_lags == (1,)
    te = np.linspace(0.0, 60.0, 601)
    res = fam.integrate([[1.0, 1.0]], run.history, t_end=60.0, t_eval=te)
    tr = simulate(run.system, history=run.history, t_end=60.0, values=run.values, t_eval=te, step=REF)
    assert res.outcomes == [Outcome.SUCCESS] and tr.outcome is Outcome.SUCCESS
    assert max_error(tr, res, 0) <= TOL


# -- toys: a swept delay, an exponential memory, a window over a long run ------------------------------


@pytest.fixture(scope="module")
def delay_family():
    return compile_family(delay_system(), grid=("tau",))


def test_swept_delay_matches_simulate_at_two_delays(delay_family):
    fam = delay_family
    assert fam.exact_lags == (2 * sympy.Symbol("tau", positive=True) / 3, sympy.Symbol("tau", positive=True))
    assert fam.lags([0.6]) == pytest.approx([0.4, 0.6], rel=1e-15)
    te = np.linspace(0.0, 20.0, 201)
    res = fam.integrate([[0.6], [1.3]], {"x": [1]}, t_end=20.0, t_eval=te)
    for i, tau in enumerate(("3/5", "13/10")):
        tr = simulate(delay_system(), history={"x": [1]}, t_end=20.0, values={"tau": tau}, t_eval=te, step=REF)
        assert max_error(tr, res, i) <= TOL, tau
    # on [0, 2τ/3] both delayed values are the history: x = 1 − 1.5 t exactly
    early = te <= 0.4
    assert np.max(np.abs(res.y[0, early, 0] - (1 - 1.5 * te[early]))) < 1e-12


def test_exponential_memory_matches_simulate():
    """x' = −a ∫_0^t e^{−2(t−ξ)} x dξ − x(t−1)/4: one auxiliary ODE state."""
    P = Parameters()
    a = P.scalar("a", positive=True, default=1)
    g = P.kernel("g", default="exp(-2*zeta)")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-a * memory_integral(g(t - xi) * x(xi)[0])), Term(-x(t - 1)[0] / 4)])],
                 parameters=P)
    fam = compile_family(sys, grid=("a",))
    assert [kind for kind, _ in fam.aux] == ["exponential memory"]
    assert fam.initial_state([3.0], {"x": [1]}).tolist() == [1.0, 0.0]
    te = np.linspace(0.0, 15.0, 151)
    res = fam.integrate([[3.0]], {"x": [1]}, t_end=15.0, t_eval=te)
    tr = simulate(sys, history={"x": [1]}, t_end=15.0, values={"a": 3}, t_eval=te, step=REF)
    assert max_error(tr, res, 0) <= TOL


def test_window_without_resync_stays_close_to_simulate_on_a_long_run():
    """x' = −k ∫_{t−1}^t x: the auxiliary state is not re-synchronised; on [0, 200] the states agree."""
    P = Parameters()
    k = P.scalar("k", positive=True, default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-k * window_integral(x(xi)[0], tau))])], parameters=P)
    fam = compile_family(sys, grid=("k",))
    te = np.linspace(0.0, 200.0, 401)
    res = fam.integrate([[1.0]], {"x": [1]}, t_end=200.0, t_eval=te)
    tr = simulate(sys, history={"x": [1]}, t_end=200.0, t_eval=te, step=REF)
    assert max_error(tr, res, 0) <= TOL
    # on [0, 1]: x = 1 − sin t exactly (tests/simulate/test_simulate.py derives it)
    early = te <= 1.0
    assert np.max(np.abs(res.y[0, early, 0] - (1 - np.sin(te[early])))) < 1e-7


# -- outcomes --------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def growth_family():
    """x' = a x(t − 1): the exact solution from x ≡ 1 is Σ_{k ≤ ⌊t⌋+1} (t − k + 1)^k / k!."""
    P = Parameters()
    a = P.scalar("a", default=1)
    x = Vector("x", 1)
    return compile_family(System([Equation(x, [Term(a * x(t - 1)[0])])], parameters=P), grid=("a",))


def exact_growth(s: float) -> float:
    return sum((s - k + 1) ** k / math.factorial(k) for k in range(int(math.floor(s)) + 2))


def test_divergence_time_is_the_bound_crossing(growth_family):
    bound = 1e3
    te = np.linspace(0.0, 40.0, 81)
    res = growth_family.integrate([[1.0], [-1.0]], {"x": [1]}, t_end=40.0, t_eval=te, divergence_bound=bound)
    assert res.outcomes == [Outcome.DIVERGED, Outcome.SUCCESS]
    crossing = scipy.optimize.brentq(lambda s: exact_growth(s) - bound, 5.0, 15.0, xtol=1e-14)
    assert abs(res.t_fail[0] - crossing) < 1e-6
    assert np.isnan(res.t_fail[1])
    after = te > res.t_fail[0] + 1.0
    assert np.all(np.isnan(res.y[0, after])) and not np.any(np.isnan(res.y[1]))


def test_an_ode_diverges_at_log_of_the_bound():
    """x' = a x (no delay): ‖x‖ = e^{a t} reaches the bound at ln(bound)/a."""
    P = Parameters()
    a = P.scalar("a", default=1)
    x = Vector("x", 1)
    fam = compile_family(System([Equation(x, [Term(a * x(t)[0])])], parameters=P), grid=("a",))
    assert fam.exact_lags == ()
    res = fam.integrate([[1.0], [2.0]], {"x": [1]}, t_end=30.0, t_eval=[0.0, 30.0], divergence_bound=1e6)
    assert res.outcomes == [Outcome.DIVERGED] * 2
    assert res.t_fail == pytest.approx([math.log(1e6), math.log(1e6) / 2], rel=1e-7)


def test_budget_and_step_collapse(growth_family):
    te = np.linspace(0, 4, 41)
    res = growth_family.integrate([[-1.0]], {"x": [1]}, t_end=4.0, t_eval=te, max_steps=5)
    assert res.outcomes == [Outcome.BUDGET] and res.n_steps[0] == 5
    assert 0 < res.t_fail[0] < 4.0
    assert np.all(np.isnan(res.y[0, te > res.t_fail[0]])) and not np.any(np.isnan(res.y[0, te <= res.t_fail[0]]))
    # steps capped at the delay: 1e3 steps of at most 1 cannot reach t_end = 2000, decided without stepping
    res = growth_family.integrate([[-1.0]], {"x": [1]}, t_end=2000.0, t_eval=[0.0], max_steps=1000)
    assert res.outcomes == [Outcome.BUDGET] and res.n_steps[0] == 0 and res.t_fail[0] == 0.0
    # stiff: x' = −a x with a = 1e8 needs steps ~3e-8, below the floor (t_end − t0)/1e7 = 1e-7
    P = Parameters()
    a = P.scalar("a", default=1)
    x = Vector("x", 1)
    fam = compile_family(System([Equation(x, [Term(-a * x(t)[0])])], parameters=P), grid=("a",))
    res = fam.integrate([[1e8], [1.0]], {"x": [1]}, t_end=1.0, t_eval=[0.0, 1.0])
    assert res.outcomes == [Outcome.STEP_COLLAPSE, Outcome.SUCCESS]
    assert res.y[1, -1, 0] == pytest.approx(math.exp(-1), rel=1e-7)


def test_non_finite_values_are_divergence_not_an_exception():
    """x' = −1/(a − x) ... with a = 1 and x0 = 1 the right-hand side is infinite at t0."""
    P = Parameters()
    a = P.scalar("a", default=2)
    x = Vector("x", 1)
    fam = compile_family(System([Equation(x, [Term(1 / (a - x(t)[0]))])], parameters=P), grid=("a",))
    res = fam.integrate([[1.0], [3.0]], {"x": [1]}, t_end=1.0, t_eval=[0.0, 1.0])
    assert res.outcomes[0] is Outcome.DIVERGED and res.t_fail[0] == 0.0
    # a = 3: x' = 1/(3 − x), x = 3 − sqrt(4 − 2t) on [0, 1]
    assert res.outcomes[1] is Outcome.SUCCESS and res.y[1, -1, 0] == pytest.approx(3 - math.sqrt(2), rel=1e-7)


# -- what the fast path refuses --------------------------------------------------------------------


def test_quadrature_kernel_is_unsupported():
    P = Parameters()
    g = P.kernel("g", default="1/(1+zeta)**2")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-memory_integral(g(t - xi) * x(xi)[0]))])], parameters=P)
    with pytest.raises(UnsupportedInput, match="quadrature"):
        compile_family(sys, grid=())


def test_non_constant_history_is_unsupported(delay_family):
    with pytest.raises(UnsupportedInput, match="constant"):
        delay_family.initial_state([1.0], {"x": [sympy.cos(t)]})
    with pytest.raises(UnsupportedInput, match="constant"):
        delay_family.integrate([[1.0]], {"x": lambda s: [1.0]}, t_end=1.0, t_eval=[1.0])


def test_bad_input(delay_family):
    sys = delay_system()
    with pytest.raises(InputError, match="neither"):
        compile_family(sys, grid=("k",))
    with pytest.raises(InputError, match="grid name has no fixed value"):
        compile_family(sys, {"tau": 1}, grid=("tau",))
    with pytest.raises(InputError, match="a > 0"):
        compile_family(sys, {"a": -1}, grid=("tau",))
    with pytest.raises(InputError, match="parameters without a value"):
        compile_family(System(sys.equations, parameters=_no_default_parameters()), grid=("tau",))
    fam = delay_family
    with pytest.raises(InputError, match=r"\(N, 1\)"):
        fam.integrate([[1.0, 2.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0])
    with pytest.raises(InputError, match="t_eval"):
        fam.integrate([[1.0]], {"x": [1]}, t_end=1.0, t_eval=[2.0])
    with pytest.raises(InputError, match="t_end"):
        fam.integrate([[1.0]], {"x": [1]}, t_end=0.0, t_eval=[0.0])
    with pytest.raises(InputError, match="positive numbers"):
        fam.integrate([[1.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0], atol=0.0)
    with pytest.raises(InputError, match="max_steps"):
        fam.integrate([[1.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0], max_steps=0)
    with pytest.raises(InputError, match="positive finite lags"):
        fam.integrate([[1.0], [-1.0]], {"x": [1]}, t_end=1.0, t_eval=[1.0])
    with pytest.raises(InputError, match="history"):
        fam.integrate([[1.0]], {"y": [1]}, t_end=1.0, t_eval=[1.0])
    with pytest.raises(InputError, match="1 components"):
        fam.integrate([[1.0]], {"x": [1, 2]}, t_end=1.0, t_eval=[1.0])


def _no_default_parameters():
    P = Parameters()
    P.scalar("a", positive=True)
    P.delay("tau", default=1)
    return P


def test_matrix_parameter_is_swept_through_a_template():
    P = Parameters()
    F = P.spd_matrix("F", 2, default=sympy.eye(2))
    x = Vector("x", 2)
    sys = System([Equation(x, [Term(-F * x(t))])], parameters=P)
    with pytest.raises(InputError, match="scalar parameter"):
        compile_family(sys, grid=("F",))
    fam = compile_family(sys, {"F": "diag(h, 2*h)"}, grid=("h",))
    res = fam.integrate([[0.5]], {"x": [1, 1]}, t_end=2.0, t_eval=[2.0])
    assert res.y[0, 0] == pytest.approx([math.exp(-1), math.exp(-2)], rel=1e-7)
