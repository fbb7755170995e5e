"""lkverify.linear.linearise: exact linearisation of catalogued Systems at an equilibrium."""

import numpy as np
import pytest
import sympy

from lkverify import Equation, InputError, Parameters, System, Term, UnsupportedInput, Vector, t, window_integral, xi
from lkverify.linear import linearise, linearise_at
from lkverify.proofs.aleksandrov2017.equations import system as system_001
from lkverify.proofs.aleksandrov2023.equations import system as system_002
from lkverify.proofs.aleksandrov2023.linear_mu1 import FIGURE_GAINS, linearisation
from lkverify.proofs.aleksandrov2026.equations import system as system_000, system_pid as system_000_pid

AT_R = {"omega": [0, 0, 0], "s": "r"}
AT_FRAME = {"omega": [0, 0, 0], "s1": "r1", "s2": "r2", "s3": "r3"}


def _scalar():
    """ẋ = −k sin x(t−τ) + 1 − x(t)·(1/τ)∫_{t−τ}^t x(ξ)² dξ."""
    P = Parameters()
    k = P.scalar("k", default=1)
    tau = P.delay("tau", default=2)
    x = Vector("x", 1)
    rhs = -k * sympy.sin(x(t - tau)[0]) + 1 - x(t)[0] * window_integral(x(xi)[0] ** 2, tau) / tau
    return System([Equation(x, [Term(rhs)])], parameters=P, name="scalar")


def _no_floats(M):
    return not any(e.has(sympy.Float) for e in M)


# ------------------------------------------------------------------------ closed forms


def test_scalar_dde_closed_form():
    # x ≡ 1 with k = 0: z* = τ, f = 1 − 1·τ/τ = 0
    lin = linearise_at(_scalar(), {"x": [1]}, {"k": 0, "tau": 2})
    # ∂f/∂x = −z*/τ = −1, A_d = −k cos 1 = 0, D = (∂f/∂z)(∂g/∂x) = (−1/τ)(2·1) = −1
    assert (lin.system.A, lin.system.Ad, lin.system.kernel[0], lin.delay) == (
        sympy.Matrix([[-1]]), sympy.Matrix([[0]]), sympy.Matrix([[-1]]), 2)
    with pytest.raises(InputError, match=r"residual dx/dt = -sin\(1\)"):       # k = 1: not an equilibrium
        linearise(_scalar(), {"x": [1]}, {"k": 1, "tau": 2})
    with pytest.raises(InputError, match="one delay"):
        P = Parameters()
        x = Vector("x", 1)
        linearise(System([Equation(x, [Term(-x(t - 1)[0] - x(t - 2)[0])])], parameters=P), {"x": [0]}, {})


def test_scalar_dde_irrational_point_exact():
    P = Parameters()
    k = P.scalar("k", default=3)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-k * sympy.sin(x(t - tau)[0]) + sympy.Integral(x(xi)[0] - sympy.pi, (xi, t - tau, t)))])],
                 parameters=P)
    lin = linearise_at(sys, {"x": [sympy.pi]}, {})
    # −k cos π = +k: the delayed term destabilises at x = π; the window gives D = 1
    assert lin.system.A == sympy.Matrix([[0]]) and lin.system.Ad == sympy.Matrix([[3]])
    assert lin.system.kernel[0] == sympy.Matrix([[1]]) and lin.limits == ()


# ------------------------------------------------------------------------ paper 002


@pytest.mark.parametrize("number", [1, 2, 4])
def test_paper002_equals_the_hand_made_linearisation(number):
    gains = FIGURE_GAINS[number]
    lin = linearise(system_002, AT_R, gains, order=("s", "omega"))
    ref = linearisation(gains)
    assert lin.A == ref.A and lin.kernel == ref.kernel and not lin.has_discrete
    assert _no_floats(lin.A) and _no_floats(lin.kernel[0])


def test_paper002_irrational_target_symbolic():
    r = sympy.Matrix([1, sympy.sqrt(2), 0]) / sympy.sqrt(3)
    values = {**FIGURE_GAINS[1], "r": r}
    lin = linearise_at(system_002, {"omega": [0, 0, 0], "s": r}, values, order=("s", "omega"))
    ref = linearisation(values)
    assert (lin.system.A - ref.A).applyfunc(sympy.simplify).is_zero_matrix
    assert (lin.system.kernel[0] - ref.kernel[0]).applyfunc(sympy.simplify).is_zero_matrix
    assert any(e.has(sympy.sqrt(2)) for e in lin.system.A) and _no_floats(lin.system.A)
    on = linearise_at(system_002, {"omega": [0, 0, 0], "s": r}, values, coordinates="orthonormal")
    B = on.T[3:, 3:]
    assert (B.T * B - sympy.eye(2)).applyfunc(sympy.simplify).is_zero_matrix
    # a change of tangent basis: similar matrices, same characteristic polynomial
    lam = sympy.Symbol("lam")
    assert sympy.expand(on.system.A.charpoly(lam).as_expr() - lin.system.A.charpoly(lam).as_expr()) == 0


def test_mutated_equilibrium_refused_with_residual():
    with pytest.raises(InputError, match=r"residual .*domega_3/dt = -7/400"):      # −hω₃/C = −(7/10)(1/10)/4
        linearise(system_002, {"omega": [0, 0, "1/10"], "s": "r"}, {**FIGURE_GAINS[1], "mu": 1})
    with pytest.raises(InputError, match="residual"):           # s ≠ r with a ≠ 0: the torque does not vanish
        linearise(system_002, {"omega": [0, 0, 0], "s": [1, 0, 0]}, {**FIGURE_GAINS[1], "mu": 1})
    with pytest.raises(InputError, match="‖s‖ = 1"):
        linearise(system_002, {"omega": [0, 0, 0], "s": [1, 1, 1]}, {**FIGURE_GAINS[1], "mu": 1})
    with pytest.raises(InputError, match="missing s"):
        linearise(system_002, {"omega": [0, 0, 0]}, {})


def test_non_differentiable_point_refused():
    with pytest.raises(InputError, match="differentiable"):
        linearise(system_002, AT_R, {**FIGURE_GAINS[1], "mu": "1/2"})


def test_mu_between_1_and_2_is_differentiable_and_degenerate():
    # ‖s − r‖^{μ−1}(s × r) = O(‖s − r‖^μ): C¹ with zero Jacobian for μ > 1 (by one-sided limits)
    lin = linearise_at(system_002, AT_R, {**FIGURE_GAINS[1], "mu": "3/2"}, order=("s", "omega"))
    A = lin.system.A
    assert A[2:, :2].is_zero_matrix and lin.system.kernel[0].is_zero_matrix and lin.limits


# ------------------------------------------------------------------------ frames (papers 000, 001)


def test_paper001_time_varying_coefficient_refused_unless_frozen():
    with pytest.raises(InputError, match=r"depending on t .*coefficient h"):
        linearise(system_001, AT_FRAME, {})
    lam, h = sympy.Symbol("lam"), sympy.Rational(1, 2)
    lin = linearise_at(system_001, AT_FRAME, {"h": h})
    assert lin.labels == ("omega_1", "omega_2", "omega_3", "θ_1", "θ_2", "θ_3") and lin.delay is None
    # per axis λ² + (2hD_i/J_i)λ + k_i/J_i, stiffness k = (1, 1, a1 + a2): stable for every frozen h > 0
    expected = ((lam ** 2 + 2 * h * 4 / 5 * lam + sympy.Rational(1, 5)) * (lam ** 2 + 2 * h * 4 / 6 * lam + sympy.Rational(1, 6))
                * (lam ** 2 + 2 * h * 4 / 4 * lam + sympy.Rational(2, 4)))
    assert sympy.expand(lin.system.A.charpoly(lam).as_expr() - expected) == 0


def _fd_jacobian(comp, y0, Z0, wrt, step=1e-7):
    n = comp.n_states
    J = np.zeros((n, n))
    for j in range(n):
        yp, ym, Zp, Zm = y0.copy(), y0.copy(), Z0.copy(), Z0.copy()
        if wrt == "y":
            yp[j] += step
            ym[j] -= step
        else:
            Zp[0, j] += step
            Zm[0, j] -= step
        J[:, j] = (comp.fun(0.0, yp, Zp, None)[:n] - comp.fun(0.0, ym, Zm, None)[:n]) / (2 * step)
    return J


@pytest.mark.parametrize("which", ["001", "000"])
def test_frame_against_finite_differences_of_the_simulator(which):
    from lkverify.simulate.compile import compile_system
    system, values = (system_001, {"h": "1/2", "a1": 2}) if which == "001" else (system_000, {"nu": 1})
    lin = linearise_at(system, AT_FRAME, values)
    comp = compile_system(system, values)
    p = np.array([float(v) for v in _point(system, values)])
    Z0 = np.array([p]) if comp.lags else np.zeros((0, comp.n_states))
    fdA = _fd_jacobian(comp, p, Z0, "y")
    assert np.allclose(fdA, np.array(lin.full["A"], dtype=float), atol=1e-6)
    T, L = np.array(lin.T, dtype=float), np.array(lin.L, dtype=float)
    assert np.allclose(L @ fdA @ T, np.array(lin.system.A, dtype=float), atol=1e-6)
    if comp.lags:
        fdAd = _fd_jacobian(comp, p, Z0, "Z")
        assert np.allclose(L @ fdAd @ T, np.array(lin.system.Ad, dtype=float), atol=1e-6)


def _point(system, values):
    P = system.parameters
    v = P.resolve(values, use_defaults=True)
    return [0, 0, 0, *v["r1"], *v["r2"], *v["r3"]]


def test_paper000_degenerate_linearisation():
    # (2),(7) at section 5's gains: the torque f^ν L is O(‖s − r‖^{2ν+1}): no stiffness and no delayed term
    lin = linearise_at(system_000, AT_FRAME, {})
    A = lin.system.A
    assert lin.delay == 1 and not lin.system.has_discrete and lin.limits
    assert A[:3, 3:].is_zero_matrix and A[3:, 3:].is_zero_matrix and A[3:, :3] == -sympy.eye(3)
    lam = sympy.Symbol("lam")
    assert sympy.factor(A.charpoly(lam).as_expr()) == sympy.factor(
        lam ** 3 * (lam + sympy.Rational(2, 20)) * (lam + sympy.Rational(2, 25)) * (lam + sympy.Rational(2, 35)))


def test_memory_integral_refused():
    with pytest.raises(UnsupportedInput, match="memory"):
        linearise(system_000_pid, AT_FRAME, {})


def test_frame_not_orthonormal_refused():
    with pytest.raises(InputError, match="orthonormal"):
        linearise(system_001, {**AT_FRAME, "s3": [0, 1, 0]}, {"h": 1})


def test_flipped_sign_gives_another_linearisation():
    # b → −b in the System's values is not the hand-made linearisation of the original gains
    gains = FIGURE_GAINS[1]
    lin = linearise(system_002, AT_R, {**gains, "b": "-2"}, order=("s", "omega"))
    assert lin.kernel != linearisation(gains).kernel and lin.kernel[0] == -linearisation(gains).kernel[0]


def test_linear_mu1_row_is_exact():
    from lkverify import Status
    from lkverify.proofs.aleksandrov2023.linear_mu1 import _from_system_row
    row = _from_system_row(1)
    assert row.status is Status.EXACT and row.value is True


def test_orthonormal_basis_rational_when_r_allows():
    r = sympy.Matrix([sympy.Rational(3, 5), sympy.Rational(4, 5), 0])
    values = {**FIGURE_GAINS[1], "r": r}
    lin = linearise_at(system_002, {"omega": [0, 0, 0], "s": r}, values, coordinates="orthonormal")
    B = lin.T[3:, 3:]
    assert B.T * B == sympy.eye(2) and B.T * r == sympy.zeros(2, 1)
    assert all(e.is_Rational for e in lin.system.A) and all(e.is_Rational for e in lin.system.kernel[0])


def test_kink_refused_and_smooth_abs_away_from_it():
    P = Parameters()
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-sympy.Abs(x(t - 1)[0]) - x(t)[0])])], parameters=P, name="kink")
    with pytest.raises(InputError, match="differentiable"):      # SymPy alone would say d|x|/dx = sign(0) = 0
        linearise(sys, {"x": [0]}, {})
    sys2 = System([Equation(x, [Term(sympy.Abs(x(t - 1)[0]) - x(t)[0] ** 2)])], parameters=P, name="away")
    lin = linearise(sys2, {"x": [1]}, {})
    assert lin.A == sympy.Matrix([[-2]]) and lin.Ad == sympy.Matrix([[1]])
