"""Paper 003's simulated grid on the library's batch integrator (issue 24 item 4): references, mutations, budgets."""

import importlib

import numpy as np
import pytest
import scipy.integrate
import sympy

from lkverify import Equation, Status, System, Term, t
from lkverify.simulate import Outcome

eq = importlib.import_module("lkverify.proofs.somov.equations")
grid = importlib.import_module("lkverify.proofs.somov.grid")
reg = importlib.import_module("lkverify.proofs.somov.region")

DEFAULTS = eq.P.resolve({})
#: (σ0, ω0) columns: inside the region, saturating, a general direction, ω along σ
S0 = np.array([[0.05, 0.5, 0.3 * 2 / 3, 0.6], [0.0, 0.0, 0.3 * 2 / 3, 0.0], [0.0, 0.0, 0.3 / 3, 0.0]])
W0 = np.array([[0.0, 0.0, 0.05 / 3, 0.1], [0.0, 0.1, -0.1 / 3, 0.0], [0.0, 0.0, 0.1 / 3, 0.0]])
TE = np.array([0.0, 10.0, 50.0, 100.0, 300.0])


def reference(system, s0, w0):
    """(σ, ω) at TE by scipy's DOP853 at rtol 1e-12 from the symbolic right-hand side (numpy lambdify)."""
    sub = eq.P.substitution(DEFAULTS)
    rhs = [e.xreplace(sub) for x in (eq.sigma, eq.omega) for e in system.rhs(x)]
    f = sympy.lambdify([*eq.sigma(t), *eq.omega(t)], rhs, modules="numpy", cse=True)
    sol = scipy.integrate.solve_ivp(lambda _, y: np.asarray(f(*y), dtype=float), (0.0, TE[-1]),
                                    np.concatenate([s0, w0]), method="DOP853", t_eval=TE, rtol=1e-12, atol=1e-14)
    assert sol.success
    return sol.y.T


def mutated_loop():
    """(3), (11) with σ̇ = −¼B(σ)ω: a wrong sign in the kinematics."""
    return System([Equation(eq.sigma, [Term(-eq.B(eq.sigma_s) * eq.omega_s / 4)]),
                   Equation(eq.omega, [Term(eq.SC(eq.u_linear(eq.sigma_s, eq.omega_s), eq.a_m))])],
                  parameters=eq.P, name="(3),(11) mutated")


def test_batch_runs_agree_with_a_tight_scipy_reference():
    res = grid.integrate_runs(DEFAULTS, S0, W0, t_end=TE[-1], t_eval=TE)
    assert res.outcomes == [Outcome.SUCCESS] * S0.shape[1]
    for i in range(S0.shape[1]):
        err = np.max(np.abs(res.y[i] - reference(eq.closed_loop, S0[:, i], W0[:, i])))
        assert err <= 1e-6, (i, err)


def test_unsaturated_loop_agrees_with_the_closed_form():
    """(3), (10): σ̈ = −k0σ − k1σ̇ exactly, so σ = e^{−αt}(σ0 cos βt + (σ̇0 + ασ0) sin βt / β), σ̇0 = ¼B(σ0)ω0."""
    al, be = float(DEFAULTS["alpha"]), float(DEFAULTS["beta"])
    res = grid.integrate_runs(DEFAULTS, S0, W0, t_end=TE[-1], t_eval=TE, system=eq.closed_loop_10)
    for i in range(S0.shape[1]):
        s0 = S0[:, i]
        sd0 = np.array(eq.B(sympy.Matrix(s0)), dtype=float) @ W0[:, i] / 4
        exact = np.exp(-al * TE)[:, None] * (np.outer(np.cos(be * TE), s0) + np.outer(np.sin(be * TE), sd0 + al * s0) / be)
        err = np.max(np.abs(res.y[i][:, res.layout["sigma"]] - exact))
        assert err <= 1e-6, (i, err)


def test_classes_of_runs():
    res = grid.integrate_runs(DEFAULTS, [[0.05, 0.9], [0, 0], [0, 0]], [[0.0, 0.4], [0, 0], [0, 0]], t_end=300.0)
    assert grid.classify_runs(res).tolist() == [grid.CONVERGED, grid.NOT_CONVERGED]
    assert res.outcomes[1] is Outcome.DIVERGED          # the long way round: |σ| → ∞ as Φ → 2π
    # a tolerance never reached: the run ended away from 0
    assert grid.classify_runs(res, tol=1e-30).tolist() == [grid.NOT_CONVERGED] * 2


def test_wrong_sign_in_the_kinematics_changes_the_classification():
    R = reg.certified_region(DEFAULTS)
    s = np.linspace(0.0, 1.0, 4)
    w = np.linspace(0.0, reg.W_RANGE * float(R.w_max), 4)
    good = grid.run_grid(DEFAULTS, s, w, t_end=300.0)
    bad = grid.run_grid(DEFAULTS, s, w, t_end=300.0, system=mutated_loop())
    assert good.converged[0, 0] and good.converged.sum() > 1
    assert not np.array_equal(good.classes, bad.classes)
    assert bad.converged.sum() <= 1                              # only the equilibrium itself stays
    assert _status(reg.grid_rows(R, good))["region inside the converged grid"] is Status.SIMULATED
    sb = np.linspace(0.0, 0.999 * float(R.s_max), 4)
    cls = grid.run_points(DEFAULTS, sb[1:], 0.999 * R.w_boundary(sb[1:]), t_end=300.0, system=mutated_loop())
    assert (cls == grid.NOT_CONVERGED).all()
    assert reg.boundary_row(cls, float(R.s_max), 300.0).status is Status.FAILED


def test_a_spent_step_budget_is_undecided_not_failed():
    R = reg.certified_region(DEFAULTS)
    g = grid.run_grid(DEFAULTS, np.linspace(0.0, 1.0, 3), np.linspace(0.0, 0.4, 3), t_end=300.0, max_steps=5)
    assert g.undecided.all() and not g.converged.any()
    assert _status(reg.grid_rows(R, g))["region inside the converged grid"] is Status.UNDECIDED
    cls = grid.run_points(DEFAULTS, [0.01, 0.02], [0.0, 0.0], t_end=300.0, max_steps=5)
    row = reg.boundary_row(cls, float(R.s_max), 300.0)
    assert row.status is Status.UNDECIDED and "ran out of steps" in row.detail


def test_one_failed_direction_makes_the_point_not_converged():
    """(|σ0|, ‖ω0‖) = (0.5, 0.3): ω against σ and across converge, ω along σ goes the long way round."""
    along, against, across = (grid.DIRECTIONS[k:k + 1] for k in range(3))
    assert grid.run_points(DEFAULTS, [0.5], [0.3], t_end=300.0, directions=against + across).tolist() == [grid.CONVERGED]
    assert grid.run_points(DEFAULTS, [0.5], [0.3], t_end=300.0, directions=along).tolist() == [grid.NOT_CONVERGED]
    assert grid.run_points(DEFAULTS, [0.5], [0.3], t_end=300.0).tolist() == [grid.NOT_CONVERGED]


def _status(rows):
    return {r.name: r.status for r in rows}
