"""Tests of lkverify.simulate.solver: the numeric DDE integrator core (method of steps on SciPy's RK steppers).

Accuracy is checked against independent closed forms built with SymPy (method of
steps, interval by interval) and against SciPy's own ODE solver; the fast paths
(exact conversion of SciPy's dense output, batched lookups) are cross-checked
against slow reference paths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
import sympy
from scipy.integrate import DOP853, RK45, solve_ivp

from lkverify.simulate.solver import DDESolution, DenseHistory, Outcome, solve_dde
from lkverify.errors import InputError

T = sympy.Symbol("t", real=True)
S = sympy.Symbol("s", real=True)


def _piecewise(pieces, tau, ts):
    """Evaluate a list of SymPy pieces: pieces[k] on [(k-1)tau, k tau] (k >= 1), pieces[0] = history."""
    fs = [sympy.lambdify(T, p, "numpy") for p in pieces]
    k = np.clip(np.floor(ts / tau).astype(int) + 1, 1, len(pieces) - 1)
    return np.array([float(fs[kk](tt)) for kk, tt in zip(k, ts)])


def _err(res, ts, exact, comp=0):
    return float(np.max(np.abs(res.sol(ts)[:, comp] - exact)))


def _gauss_window(sol, comp, a, b, breaks):
    """∫_a^b sol(s)[comp] ds with 16-point Gauss–Legendre per step piece (independent of the 8-point rule)."""
    x, w = np.polynomial.legendre.leggauss(16)
    edges = np.concatenate(([a], breaks[(breaks > a) & (breaks < b)], [b]))
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = (0.5 * (lo + hi) + 0.5 * (hi - lo) * x).ravel()
    weights = (0.5 * (hi - lo) * w).ravel()
    return float(weights @ sol(nodes)[:, comp])


# -- 1. x' = -a x(t - tau), constant history 1 ---------------------------------------------

A, TAU = sympy.Rational(13, 10), sympy.Rational(7, 10)


@pytest.fixture(scope="module")
def steps_closed_form():
    """Method-of-steps pieces by integrating interval by interval; checked against the known sum."""
    pieces = [sympy.Integer(1)]
    for k in range(1, 6):
        start = (k - 1) * TAU
        x_start = pieces[-1].subs(T, start)
        pieces.append(sympy.expand(x_start + sympy.integrate(-A * pieces[-1].subs(T, S - TAU), (S, start, T))))
    for k in range(1, 6):
        # on [(k-1)tau, k tau]:  x(t) = sum_{j=0}^{k} (-a)^j (t - (j-1) tau)^j / j!
        formula = sum((-A) ** j * (T - (j - 1) * TAU) ** j / sympy.factorial(j) for j in range(k + 1))
        assert sympy.expand(formula - pieces[k]) == 0, k
    return pieces


@pytest.mark.parametrize(("method", "tol"), [("DOP853", 1e-11), ("RK45", 1e-9)])
def test_constant_history_matches_method_of_steps(steps_closed_form, method, tol):
    a, tau = float(A), float(TAU)
    res = solve_dde(lambda t, y, Z, past: -a * Z[0], (0.0, 5 * tau), [1.0], lags=[tau],
                    method=method, rtol=1e-10, atol=1e-12)
    assert res.outcome is Outcome.SUCCESS and res.success
    ts = np.linspace(0.0, 5 * tau, 1501)
    exact = _piecewise(steps_closed_form, tau, ts)
    # reached: DOP853 2.4e-15 (the pieces are polynomials of degree <= 5), RK45 8e-11
    assert _err(res, ts, exact) <= tol * np.max(np.abs(exact))
    # steps land exactly on the breakpoints k tau
    assert np.all(np.isin(res.breakpoints, res.t))
    np.testing.assert_allclose(res.breakpoints, tau * np.arange(1, 5), rtol=0, atol=1e-15)


def test_landing_on_breakpoints_matters(steps_closed_form):
    a, tau = float(A), float(TAU)
    ts = np.linspace(0.0, 5 * tau, 1501)
    exact = _piecewise(steps_closed_form, tau, ts)
    errs = [_err(solve_dde(lambda t, y, Z, past: -a * Z[0], (0.0, 5 * tau), [1.0], lags=[tau],
                           discontinuity_order=order), ts, exact) for order in (4, 0)]
    # default rtol 1e-8: landed 2.4e-15, not landed 2.2e-8
    assert errs[0] < 1e-12 and errs[1] > 100 * errs[0]


def test_breakpoints_of_several_lags():
    res = solve_dde(lambda t, y, Z, past: -Z[0] - 0.5 * Z[1], (0.0, 5.0), [1.0], lags=[1.0, 1.5])
    # t0 + i + 1.5 j with 1 <= i + j <= 4, below t_end
    expected = sorted({i + 1.5 * j for i in range(5) for j in range(5) if 1 <= i + j <= 4 and i + 1.5 * j < 5})
    np.testing.assert_allclose(res.breakpoints, expected, atol=1e-14)
    assert np.all(np.isin(res.breakpoints, res.t))


# -- 2. non-constant history: x' = -x(t-1), phi = cos -----------------------------------------


def test_cosine_history_two_intervals():
    x1 = 1 - sympy.integrate(sympy.cos(S - 1), (S, 0, T))
    x2 = x1.subs(T, 1) - sympy.integrate(x1.subs(T, S - 1), (S, 1, T))
    assert sympy.simplify(sympy.diff(x2, T) + x1.subs(T, T - 1)) == 0
    res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 2.0), lambda s: np.array([np.cos(s)]),
                    lags=[1.0], rtol=1e-10, atol=1e-12)
    ts = np.linspace(0.0, 2.0, 801)
    exact = _piecewise([sympy.cos(T), x1, x2], 1.0, ts)
    assert _err(res, ts, exact) <= 1e-9 * np.max(np.abs(exact))   # reached 8.6e-12
    assert np.any(res.t == 1.0)                                           # the breakpoint t0 + tau
    assert res.y[0, 0] == 1.0                                       # y(t0) = phi(t0)


# -- 3. distributed delay through an auxiliary state ------------------------------------------


@pytest.fixture(scope="module")
def distributed_closed_form():
    """x' = -∫_{t-1}^t x, history 1: on each interval x'' + x = x(t - 1), x and x' continuous.

    Built by variation of constants; each piece is checked against the integro-differential
    equation itself at sample points.
    """
    pieces = [sympy.Integer(1)]
    x_a, dx_a = sympy.Integer(1), sympy.Integer(-1)        # x(0) = 1, x'(0) = -z(0) = -1
    for k in range(1, 4):
        a = k - 1
        forcing = sympy.expand(sympy.expand_trig(sympy.sin(T - S) * pieces[-1].subs(T, S - 1)))
        xk = sympy.expand(x_a * sympy.cos(T - a) + dx_a * sympy.sin(T - a) + sympy.integrate(forcing, (S, a, T)))
        pieces.append(xk)
        x_a, dx_a = xk.subs(T, k), sympy.diff(xk, T).subs(T, k)
    for k in (1, 2):
        window = (sympy.integrate(pieces[k - 1].subs(T, S), (S, T - 1, k - 1))
                  + sympy.integrate(pieces[k].subs(T, S), (S, k - 1, T)))
        residual = sympy.lambdify(T, sympy.diff(pieces[k], T) + window)
        assert max(abs(residual(k - 1 + f)) for f in (0.1, 0.5, 0.9)) < 1e-13
    return pieces


def _distributed(t, y, Z, past):
    return np.array([-y[1], y[0] - Z[0, 0]])


def _window_resync(t, y, past):
    return np.array([y[0], past.integrate(lambda Y: Y[:, 0], t - 1.0, t)])


def test_distributed_delay_matches_closed_form(distributed_closed_form):
    res = solve_dde(_distributed, (0.0, 3.0), [1.0, 1.0], lags=[1.0], rtol=1e-10, atol=1e-12)
    ts = np.linspace(0.0, 3.0, 601)
    exact = _piecewise(distributed_closed_form, 1.0, ts)
    assert _err(res, ts, exact) <= 1e-9 * np.max(np.abs(exact))   # reached 7.9e-11
    res_r = solve_dde(_distributed, (0.0, 3.0), [1.0, 1.0], lags=[1.0], rtol=1e-10, atol=1e-12,
                      resync=_window_resync)
    assert _err(res_r, ts, exact) <= 1e-9 * np.max(np.abs(exact))


def test_resync_stops_window_drift():
    """Long run t in [0, 200] at the default tolerances (rtol 1e-8, atol 1e-10).

    d/dt (z - ∫_{t-1}^t x) = 0 exactly, so the drift of the auxiliary state never decays.
    Measured (independent 16-point quadrature): without resync max drift 5.7e-11 (the
    solution settles at x = -drift instead of 0); with resync 1.1e-16.
    """
    runs = [solve_dde(_distributed, (0.0, 200.0), [1.0, 1.0], lags=[1.0], resync=r)
            for r in (None, _window_resync)]
    drifts = []
    for res in runs:
        assert res.success
        times = res.t[res.t >= 1.0][::5]
        drifts.append(max(abs(res.sol(tk)[1] - _gauss_window(res.sol, 0, tk - 1.0, tk, res.t)) for tk in times))
    free, synced = drifts
    assert synced <= 1e-9
    assert synced <= free or free < 1e-14
    ts = np.linspace(0.0, 200.0, 2001)
    np.testing.assert_allclose(runs[0].sol(ts)[:, 0], runs[1].sol(ts)[:, 0], rtol=0, atol=1e-6)
    # the resync ramp keeps the dense solution continuous at the step ends
    res = runs[1]
    inner = res.t[1:-1]
    jumps = np.abs(res.sol(np.nextafter(inner, -np.inf)) - res.sol(inner))
    assert np.max(jumps) < 1e-13


# -- 4. fading memory: a general kernel through past.integrate ---------------------------------


def test_exponential_kernel_matches_ode():
    """x' = -∫_0^t e^{-2(t-ξ)} x(ξ) dξ equals x' = -m, m' = x - 2m, m(0) = 0.

    The memory is integrated each call by ``past.integrate`` over [0, t_n] plus the
    current-step piece (t_n, t] on the extrapolated last step.  Agreement reached with
    max_step 0.025: 2.3e-13 (8.9e-12 with 0.05; the extrapolation error ~ h^8 limits it).
    """
    t_end = 10.0
    ref = solve_ivp(lambda t, y: [-y[1], y[0] - 2 * y[1]], (0.0, t_end), [1.0, 0.0], method="DOP853",
                    rtol=1e-12, atol=1e-15, dense_output=True)

    def memory(t, y, Z, past):
        kernel = past.integrate(lambda s, Y: np.exp(-2.0 * (t - s)) * Y[:, 0], 0.0, t,
                                with_time=True, extrapolate=True)
        return np.array([-kernel])

    res = solve_dde(memory, (0.0, t_end), [1.0], lags=(), rtol=1e-12, atol=1e-14, max_step=0.025)
    assert res.success
    ts = np.linspace(0.0, t_end, 501)
    assert _err(res, ts, ref.sol(ts)[0]) <= 1e-11


# -- 5. outcomes and input errors ---------------------------------------------------------------


def test_growth_diverges_with_time():
    res = solve_dde(lambda t, y, Z, past: Z[0], (0.0, 50.0), [1.0], lags=[0.1], divergence_bound=1e3)
    assert res.outcome is Outcome.DIVERGED and not res.success
    assert 0.0 < res.t_fail < 50.0 and res.t_fail <= res.t[-1]
    assert abs(np.linalg.norm(res.sol(res.t_fail)) - 1e3) < 1e-6     # located on the dense output
    assert "divergence_bound" in res.message


def test_nan_right_hand_side_is_diverged():
    res = solve_dde(lambda t, y, Z, past: -Z[0] if t < 0.5 else np.array([np.nan]), (0.0, 2.0), [1.0],
                    lags=[1.0])
    assert res.outcome is Outcome.DIVERGED
    assert res.t_fail == pytest.approx(0.5, abs=1e-9)
    assert "non-finite" in res.message
    assert np.all(np.isfinite(res.y))


def test_blow_up_collapses_step():
    # y' = y^2, y(0) = 1 blows up at t = 1; without a divergence bound the step size collapses
    res = solve_dde(lambda t, y, Z, past: y * y, (0.0, 2.0), [1.0], lags=(), divergence_bound=math.inf)
    assert res.outcome is Outcome.STEP_COLLAPSE
    assert res.t_fail == pytest.approx(1.0, abs=1e-6)
    assert "DOP853 failed" in res.message and "step size" in res.message
    bounded = solve_dde(lambda t, y, Z, past: y * y, (0.0, 2.0), [1.0], lags=())
    assert bounded.outcome is Outcome.DIVERGED and bounded.t_fail == pytest.approx(1.0, abs=1e-6)


def test_tiny_max_step_is_respected():
    res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 0.5), [1.0], lags=[1.0], max_step=1e-3)
    assert res.success and res.n_steps >= 500
    assert np.max(np.diff(res.t)) <= 1e-3 * (1 + 1e-12)
    np.testing.assert_allclose(res.y[:, 0], 1.0 - res.t, atol=1e-13)


def test_steps_capped_at_min_lag():
    res = solve_dde(lambda t, y, Z, past: -0.1 * Z[0] - 0.1 * Z[1], (0.0, 20.0), [1.0], lags=[0.3, 2.0])
    assert np.max(np.diff(res.t)) <= 0.3 * (1 + 1e-12)


def _input_error(*args, **kwargs) -> str:
    with pytest.raises(InputError) as info:
        solve_dde(*args, **kwargs)
    message = str(info.value)
    assert "\n" not in message and "expected" in message and "got" in message, message
    return message


def _decay(t, y, Z, past):
    return -Z[0]


def test_bad_inputs_raise_clear_errors():
    assert "lags: expected positive" in _input_error(_decay, (0.0, 1.0), [1.0], lags=[0.0])
    assert "lags: expected positive" in _input_error(_decay, (0.0, 1.0), [1.0], lags=[-1.0])
    assert "t_end > t0" in _input_error(_decay, (1.0, 1.0), [1.0], lags=[1.0])
    assert "rtol: expected a positive number, got 0" in _input_error(_decay, (0.0, 1.0), [1.0], lags=[1.0], rtol=0)
    assert "rtol: expected rtol >=" in _input_error(_decay, (0.0, 1.0), [1.0], lags=[1.0], rtol=1e-17)
    assert "method: expected one of" in _input_error(_decay, (0.0, 1.0), [1.0], lags=[1.0], method="LSODA")
    msg = _input_error(_decay, (0.0, 1.0), lambda s: np.array([np.nan if s < -0.5 else 1.0]), lags=[1.0])
    assert "history: expected finite values" in msg and "s=-1" in msg
    msg = _input_error(_decay, (0.0, 1.0), lambda s: np.ones(2) if s < 0 else np.ones(1), lags=[1.0])
    assert "same dimension n=1" in msg
    # the history has 1 component, fun returns 2: the dimension mismatch is named
    msg = _input_error(lambda t, y, Z, past: np.zeros(2), (0.0, 1.0), [1.0], lags=[1.0])
    assert "shape (1,)" in msg and "got (2,)" in msg
    msg = _input_error(_decay, (0.0, 1.0), [1.0], lags=[1.0], t_eval=[0.5, 2.0])
    assert "t_eval: expected" in msg
    # all problems are collected into one message
    msg = _input_error(_decay, (0.0, 1.0), [1.0], lags=[-1.0], rtol=-1, max_step=0)
    assert "lags:" in msg and "rtol:" in msg and "max_step:" in msg


def test_bad_resync_and_past_queries():
    with pytest.raises(InputError, match=r"resync: expected .* shape \(1,\)"):
        solve_dde(_decay, (0.0, 1.0), [1.0], lags=[1.0], resync=lambda t, y, past: np.zeros(3))
    res = solve_dde(_decay, (0.0, 1.0), [1.0], lags=[1.0])
    with pytest.raises(InputError, match="extrapolate=True"):
        res.sol(1.5)
    with pytest.raises(InputError, match="a <= b"):
        res.sol.integrate(lambda Y: Y, 0.5, 0.2)


# -- 6. monitors on a plain ODE (lags=()) --------------------------------------------------------

OMEGA = np.array([0.3, -0.5, 0.8])


def _rotation(t, y, Z, past):
    return -np.cross(OMEGA, y)


def norm_drift(t, y):
    return float(np.linalg.norm(y)) - 1.0


def test_rotation_monitor_records_drift():
    s0 = np.array([1.0, 2.0, 2.0]) / 3.0
    res = solve_dde(_rotation, (0.0, 50.0), s0, lags=(), rtol=1e-10, atol=1e-12,
                    monitors=[norm_drift, lambda t, y: y[2]])
    assert res.success and res.breakpoints.size == 0
    drift = res.monitors["norm_drift"]
    assert drift.shape == res.t.shape and abs(drift[0]) < 1e-15
    assert res.monitor_max["norm_drift"] == pytest.approx(np.max(np.abs(drift)))
    assert 0 < res.monitor_max["norm_drift"] < 1e-8                    # reached ~1e-10
    np.testing.assert_allclose(res.monitors["monitor1"], res.y[:, 2])
    # against the exact rotation s(t) = expm(-[ω]x t) s0
    wx = np.array([[0, -OMEGA[2], OMEGA[1]], [OMEGA[2], 0, -OMEGA[0]], [-OMEGA[1], OMEGA[0], 0]])
    for tk in (7.3, 31.0, 50.0):
        np.testing.assert_allclose(res.sol(tk), scipy.linalg.expm(-wx * tk) @ s0, atol=1e-8)
    # a normalising resync removes the drift
    synced = solve_dde(_rotation, (0.0, 50.0), s0, lags=(), rtol=1e-10, atol=1e-12,
                       monitors={"drift": norm_drift}, resync=lambda t, y, past: y / np.linalg.norm(y))
    assert synced.monitor_max["drift"] < 1e-15


# -- 7. the dense solution ----------------------------------------------------------------------


def test_sol_before_t0_is_history_and_continuous():
    def phi(s):
        return np.array([np.cos(s), np.sin(3 * s)])

    def f(t, y, Z, past):
        return np.array([-Z[0, 1], Z[1, 0] - y[1]])

    res = solve_dde(f, (0.0, 6.0), phi, lags=[0.8, 1.7])
    before = np.linspace(-5.0, -1e-9, 17)
    np.testing.assert_array_equal(res.sol(before), np.array([phi(s) for s in before]))
    np.testing.assert_array_equal(res.sol(-2.0), phi(-2.0))
    inner = res.t[1:-1]
    left = res.sol(np.nextafter(inner, -np.inf))          # previous step's polynomial at its end
    right = res.sol(inner)                                 # next step's polynomial at its start
    assert np.max(np.abs(left - right)) < 1e-13
    np.testing.assert_allclose(res.sol(res.t), res.y, rtol=0, atol=1e-14)
    grid = np.linspace(-1.0, 6.0, 12).reshape(3, 4)
    assert res.sol(grid).shape == (3, 4, 2)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
def test_dense_solution_matches_scipy_dense_output(method):
    """Fast path (exact conversion of SciPy's dense output) vs SciPy's own solution object."""
    def f(t, y):
        return np.array([y[1], -np.sin(y[0]) - 0.1 * y[1]])

    res = solve_dde(lambda t, y, Z, past: f(t, y), (0.0, 20.0), [2.0, 0.0], lags=(), method=method,
                    rtol=1e-9, atol=1e-11, first_step=0.01)
    ref = solve_ivp(f, (0.0, 20.0), [2.0, 0.0], method=method, rtol=1e-9, atol=1e-11, first_step=0.01,
                    dense_output=True)
    np.testing.assert_array_equal(res.t, ref.t)                    # identical steps
    ts = np.linspace(0.0, 20.0, 997)
    np.testing.assert_allclose(res.sol(ts), ref.sol(ts).T, rtol=0, atol=1e-13)
    few = ts[::100]                                               # the batched small-lookup path
    np.testing.assert_allclose(res.sol(few), ref.sol(few).T, rtol=0, atol=1e-13)
    # counted work: 1 validation call, 1 initial f, n_stages per attempt (+3 dense stages for DOP853)
    stages, dense = (12, 3) if method == "DOP853" else (6, 0)
    assert res.nfev == 2 + stages * (res.n_steps + res.n_rejected) + dense * res.n_steps


@pytest.mark.parametrize(("method", "degree"), [("DOP853", 7), ("RK45", 4)])
@pytest.mark.parametrize("converter", ["native", "generic"])
def test_step_polynomials_match_scipy_dense_output(method, degree, converter):
    """Both conversions of SciPy's dense output (exact coefficient map; sampling) vs SciPy's own call."""
    solver = {"DOP853": DOP853, "RK45": RK45}[method](
        lambda t, y: np.array([y[1], -np.sin(y[0]) - 0.1 * y[1]]), 0.0, np.array([2.0, 0.0]), 100.0,
        rtol=1e-8, max_step=0.5)
    past = DenseHistory(np.array([2.0, 0.0]), 0.0, np.array([2.0, 0.0]), degree, 1.0,
                        converter="generic" if converter == "generic" else "auto")
    denses = []
    while solver.status == "running":
        solver.step()
        denses.append(solver.dense_output())
        past.append(denses[-1], solver.t_old, solver.t, solver.y)
    assert len(denses) > 128                  # the buffers grew 64 -> 128 -> 256
    assert past.converter == (method.lower() if converter == "native" else "generic")
    rng = np.random.default_rng(0)
    for dense in denses[::7]:
        ts = rng.uniform(dense.t_old, dense.t, 9)
        np.testing.assert_allclose(past(ts), dense(ts).T, rtol=0, atol=1e-13)
    np.testing.assert_allclose(past(solver.t), solver.y, rtol=0, atol=1e-15)


def test_initial_state_beyond_bound():
    res = solve_dde(_decay, (0.0, 1.0), [10.0], lags=[1.0], divergence_bound=5.0)
    assert res.outcome is Outcome.DIVERGED and res.t_fail == 0.0 and res.n_steps == 0
    assert res.sol(-1.0)[0] == 10.0


def test_integrate_exact_on_polynomial_pieces():
    # x = 1 - t on [0, 1]; history 1:  ∫_{-0.5}^{1} x = 0.5 + 0.5,  ∫ x^2 over [0, 1] = 1/3
    res = solve_dde(_decay, (0.0, 1.0), [1.0], lags=[1.0])
    assert res.sol.integrate(lambda Y: Y[:, 0], -0.5, 1.0) == pytest.approx(1.0, abs=1e-14)
    both = res.sol.integrate(lambda Y: np.column_stack([Y[:, 0], Y[:, 0] ** 2]), 0.0, 1.0)
    np.testing.assert_allclose(both, [0.5, 1.0 / 3.0], atol=1e-14)
    timed = res.sol.integrate(lambda s, Y: s * Y[:, 0], 0.0, 1.0, with_time=True)   # ∫ t(1-t) = 1/6
    assert timed == pytest.approx(1.0 / 6.0, abs=1e-14)
    assert res.sol.integrate(lambda Y: Y[:, 0], 0.3, 0.3) == 0.0


def test_options_t_eval_progress_and_result():
    calls = []
    res = solve_dde(_decay, (0.0, 30.0), [1.0], lags=[1.0], t_eval=[0.5, 1.5, 30.0], progress=calls.append)
    np.testing.assert_allclose(res.y_eval[:, 0], [0.5, -0.375, res.sol(30.0)[0]], atol=1e-12)
    assert len(calls) >= 1 and len(calls) <= 100 and calls[-1] == 1.0 and calls == sorted(calls)
    assert isinstance(res, DDESolution) and "success" in repr(res)
    with pytest.raises(AttributeError):
        res.outcome = Outcome.DIVERGED
    assert res.monitors == {} and res.t[0] == 0.0 and res.t[-1] == 30.0


def test_restartable_stepper_matches_a_restart_by_public_construction():
    """The two SciPy attributes Restartable relies on (h_abs; y and f) behave as documented."""
    from lkverify.simulate.solver import RestartableDOP853, RestartableRK45

    for cls, base in ((RestartableDOP853, DOP853), (RestartableRK45, RK45)):
        def f(t, y):
            return np.array([y[1], -y[0]])
        a = cls(f, 0.0, np.array([1.0, 0.0]), 10.0, rtol=1e-9, atol=1e-12)
        for _ in range(5):
            a.step()
        h = a.proposed_step()
        assert h > 0 and hasattr(a, "h_abs")
        y_new = a.y + np.array([1e-3, 0.0])
        a.replace_state(y_new.copy())
        b = base(f, a.t, y_new.copy(), 10.0, rtol=1e-9, atol=1e-12, first_step=h)
        a.step(), b.step()
        assert a.t == b.t and np.array_equal(a.y, b.y)
