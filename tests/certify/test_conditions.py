"""Positivity conditions (conditions, matrices, forms, lmi) against closed forms and independent references.

References: SymPy's exact eigenvalues and exact evaluation of every witness
(xᵀMx, f(x)) at the reported rational point, mpmath/NumPy eigenvalues, dense
float grids on the sphere; the exact LDLᵀ path is cross-checked against the
arb ball path, and the sphere branch and bound against the matrix path
(for a quadratic form min f on the sphere = λ_min).
"""

import dataclasses
import json
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy

import lkverify.certify.forms as forms
import lkverify.certify.lmi as lmi
from lkverify.certify.conditions import ConditionResult, Margin, Estimate
from lkverify.certify.forms import homogeneous_positive_on_sphere
from lkverify.certify.lmi import (
    best_quadratic_upper_bound, check_lyapunov_matrix, check_quadratic_bound, find_lyapunov_matrix, lmi_feasible,
)
from lkverify.certify.matrices import matrix_positive_definite
from lkverify.errors import InputError
from lkverify.options import Accuracy, Budget
from lkverify.report.results import Result
from lkverify.status import Status

R = sympy.Rational
x, y, z, zeta = sympy.symbols("x y z zeta", real=True)


def quad_exact(M, w):
    """wᵀMw in SymPy, exactly (the witness re-check)."""
    v = sympy.Matrix([sympy.Rational(c.numerator, c.denominator) for c in w])
    return sympy.simplify((v.T * sympy.Matrix(M) * v)[0])


def at(f, variables, point):
    return f.subs({v: sympy.Rational(c.numerator, c.denominator) for v, c in zip(variables, point)})


# ---------------------------------------------------------------------------------------------
# matrices


def test_paper000_assumption2_section5_example_is_exact_with_margin_6():
    # Ξ = βI + ∫_0^∞ G(ζ)dζ with β = 1, G(ζ) = e^{−2ζ} I; D = 2I  ⇒  ΞD + DΞᵀ = 6I
    integral = sympy.integrate(sympy.exp(-2 * zeta), (zeta, 0, sympy.oo))
    assert integral == R(1, 2)
    Xi = (1 + integral) * sympy.eye(3)
    D = 2 * sympy.eye(3)
    res = matrix_positive_definite(Xi * D + D * Xi.T, name="Xi D + D Xi^T")
    assert res.status is Status.EXACT
    assert res.margin.exact == 6 and res.margin.lo == res.margin.hi == 6
    assert res.witness is None and res.holds


@pytest.mark.parametrize("beta, status", [(R(-1, 4), Status.EXACT), (R(-1, 2), Status.FAILED),
                                          (R(-1), Status.FAILED)])
def test_paper000_remark3_beta_nonpositive(beta, status):
    # G = a g(ζ) I with a∫g = 1/2: Assumption 2 ⇔ β + 1/2 > 0 (β ≤ 0 allowed)
    Xi = (beta + R(1, 2)) * sympy.eye(3)
    D = 2 * sympy.eye(3)
    res = matrix_positive_definite(Xi * D + D * Xi.T)
    assert res.status is status
    assert res.margin.exact == 4 * (beta + R(1, 2))
    if status is Status.FAILED:
        assert quad_exact(Xi * D + D * Xi.T, res.witness) <= 0


def test_nonsymmetric_xi_with_commuting_d_fails_exactly():
    Xi = sympy.Matrix([[1, 2], [0, 1]])            # ΞD + DΞᵀ = [[2, 2], [2, 2]]: singular
    res = matrix_positive_definite(Xi + Xi.T)
    assert res.status is Status.FAILED
    assert quad_exact(Xi + Xi.T, res.witness) == 0
    assert res.margin.exact == 0


def test_diag_with_negative_entry_fails_with_exact_witness():
    M = sympy.diag(1, -1, 1)
    res = matrix_positive_definite(M)
    assert res.status is Status.FAILED
    assert any(res.witness)
    assert quad_exact(M, res.witness) < 0
    assert res.margin.exact == -1
    assert "x = (0, 1, 0)" in res.detail


def _rotation():
    return sympy.Matrix([[R(3, 5), R(-4, 5), 0], [R(4, 5), R(3, 5), 0], [0, 0, 1]])


def test_tiny_rational_eigenvalue_is_still_exact():
    Q = _rotation()
    M = Q * sympy.diag(R(1, 10**30), 1, 2) * Q.T
    assert not M.is_diagonal()
    res = matrix_positive_definite(M)
    assert res.status is Status.EXACT
    assert res.margin.exact == R(1, 10**30)
    assert res.margin.lo == res.margin.hi == Fraction(1, 10**30)


def test_tiny_negative_rational_eigenvalue_fails_exactly():
    Q = _rotation()
    M = Q * sympy.diag(R(-1, 10**30), 1, 2) * Q.T   # the mutation: λ_min flipped to −1e−30
    res = matrix_positive_definite(M)
    assert res.status is Status.FAILED
    assert quad_exact(M, res.witness) < 0
    assert res.margin.hi < 0


def test_sqrt_entries_are_certified_with_eigenvalue_enclosure():
    s2 = sympy.sqrt(2)
    M = sympy.Matrix([[2, s2], [s2, 3]])             # eigenvalues 1 and 4
    res = matrix_positive_definite(M)
    assert res.status is Status.CERTIFIED
    assert res.margin.contains(1)
    assert res.margin.width < Fraction(1, 10**9)


def test_pi_and_sqrt_entries_margin_contains_the_mpmath_eigenvalue():
    import mpmath
    M = sympy.Matrix([[2, sympy.sqrt(2), 0], [sympy.sqrt(2), 3, sympy.pi / 10], [0, sympy.pi / 10, 1]])
    res = matrix_positive_definite(M)
    assert res.status is Status.CERTIFIED
    with mpmath.workdps(40):
        lam = min(mpmath.eigsy(mpmath.matrix(M.evalf(45).tolist()))[0])
        assert res.margin.lo <= Fraction(str(lam)) <= res.margin.hi


def test_sqrt_entries_indefinite_fail_with_rational_witness():
    s2 = sympy.sqrt(2)
    M = sympy.Matrix([[1, s2], [s2, 1]])             # eigenvalues 1 ± √2
    res = matrix_positive_definite(M)
    assert res.status is Status.FAILED
    assert all(isinstance(c, Fraction) for c in res.witness)
    assert quad_exact(M, res.witness).is_negative
    assert res.margin.contains(Fraction(str((1 - s2).evalf(30))))


def test_singular_with_irrational_entries_is_undecided_not_failed():
    s2 = sympy.sqrt(2)
    M = sympy.Matrix([[2, s2], [s2, 1]])             # det = 0 exactly, λ_min = 0 at an irrational vector
    for semidefinite in (False, True):
        res = matrix_positive_definite(M, semidefinite=semidefinite)
        assert res.status is Status.UNDECIDED
        assert res.margin.contains(0)


def test_semidefinite_option():
    M = sympy.diag(1, 0, 2)
    assert matrix_positive_definite(M).status is Status.FAILED
    res = matrix_positive_definite(M, semidefinite=True)
    assert res.status is Status.EXACT and res.margin.exact == 0
    assert matrix_positive_definite(sympy.diag(1, R(-1, 10**12), 2), semidefinite=True).status is Status.FAILED


def test_exact_path_agrees_with_arb_path_and_numpy():
    rng = np.random.default_rng(7)
    for n in (2, 3, 5, 10):
        for shift in (0.3, -0.3):
            B = rng.integers(-5, 6, size=(n, n))
            S = sympy.Matrix(B @ B.T) / 10 + sympy.Rational(shift).limit_denominator(10) * sympy.eye(n) \
                - R(int(rng.integers(0, 3)), 10) * sympy.eye(n)
            exact = matrix_positive_definite(S)
            ball = matrix_positive_definite(S, method="arb")
            assert exact.status in (Status.EXACT, Status.FAILED)
            assert ball.status in (Status.CERTIFIED, Status.FAILED)
            assert (exact.status is Status.EXACT) == (ball.status is Status.CERTIFIED)
            lam = min(np.linalg.eigvalsh(np.array(S.evalf(20).tolist(), dtype=float)))
            for res in (exact, ball):
                assert res.margin.lo - Fraction(1, 10**9) <= Fraction(lam) <= res.margin.hi + Fraction(1, 10**9)
            assert exact.margin.lo <= ball.margin.hi and ball.margin.lo <= exact.margin.hi


def test_arb_path_never_certifies_a_singular_matrix():
    # exact zero pivots are balls with lower end 0: not "> 0"
    for M in (sympy.diag(1, 0, 2), sympy.diag(1, 2, 0)):   # a zero pivot in the middle, and last
        res = matrix_positive_definite(M, method="arb")
        assert res.status is Status.FAILED
        assert quad_exact(M, res.witness) == 0
    psd = matrix_positive_definite(sympy.diag(1, 0, 2), method="arb", semidefinite=True)
    assert psd.status is Status.UNDECIDED                  # PSD is only certified when PD


def test_hilbert_10_exact_with_certified_margin():
    import mpmath
    H = sympy.Matrix(10, 10, lambda i, j: R(1, i + j + 1))
    res = matrix_positive_definite(H)
    assert res.status is Status.EXACT
    with mpmath.workdps(60):
        lam = min(mpmath.eigsy(mpmath.hilbert(10))[0])
        assert res.margin.lo <= Fraction(str(lam)) <= res.margin.hi
    assert res.margin.hi < 2 * res.margin.lo          # a tight enclosure of a 1e-13 eigenvalue


def test_nonsymmetric_input_refused_unless_symmetrize():
    M = [[1, 4], [0, 1]]
    with pytest.raises(InputError, match="symmetrize=True"):
        matrix_positive_definite(M)
    res = matrix_positive_definite(M, symmetrize=True)        # (M + Mᵀ)/2 = [[1, 2], [2, 1]]
    assert res.status is Status.FAILED
    assert "symmetric part" in res.detail
    assert quad_exact(sympy.Matrix([[1, 2], [2, 1]]), res.witness) < 0


@pytest.mark.parametrize("bad, message", [
    ([[1, 2, 3], [2, 1]], "square"),
    ([[sympy.Symbol("k"), 0], [0, 1]], "free symbols"),
    ([[1j, 0], [0, 1]], "real number"),
    ([[1, "2"], ["2", 1]], "got str"),
    (np.zeros((2, 2, 2)), "2-D"),
    ([[float("nan"), 0], [0, 1]], "finite"),
])
def test_bad_matrices_raise_input_error(bad, message):
    with pytest.raises(InputError, match=message):
        matrix_positive_definite(bad)


def test_numpy_floats_are_their_exact_binary_values():
    res = matrix_positive_definite(np.array([[2.0, 0.5], [0.5, 1.0]]))
    assert res.status is Status.EXACT
    exact = (3 - sympy.sqrt(2)) / 2
    assert sympy.simplify(res.margin.exact - exact) == 0


# ---------------------------------------------------------------------------------------------
# homogeneous forms on the sphere


def test_quartic_two_variables_certified_min_one_half():
    res = homogeneous_positive_on_sphere(x**4 + y**4, [x, y])
    assert res.status is Status.CERTIFIED
    assert res.margin.lo > 0 and res.margin.contains(R(1, 2))
    assert res.estimate.status is Status.ESTIMATED and abs(res.estimate.value - 0.5) < 1e-6


def test_paper002_pi_plus_tau_pi_tilde():
    # Π = q1⁴ + q2⁴ + q3⁴, Π̃ = −q1²q2²: Π + τΠ̃ PD for τ = 1 (min 1/5 on the sphere, Lagrange), not for τ = 3
    pi_, pit = x**4 + y**4 + z**4, -x**2 * y**2
    res = homogeneous_positive_on_sphere(pi_ + 1 * pit, [x, y, z], budget=Budget(seconds=5))
    assert res.status is Status.CERTIFIED
    assert res.margin.contains(R(1, 5)) and res.margin.lo > R(19, 100)
    bad = homogeneous_positive_on_sphere(pi_ + 3 * pit, [x, y, z], budget=Budget(seconds=5))   # wrong constant τ
    assert bad.status is Status.FAILED
    assert at(pi_ + 3 * pit, [x, y, z], bad.witness) <= 0


def test_flipped_sign_fails_with_exact_point():
    f = -(x**2 + y**2 + z**2)
    res = homogeneous_positive_on_sphere(f, [x, y, z])
    assert res.status is Status.FAILED
    assert at(f, [x, y, z], res.witness) < 0


def test_semidefinite_form_fails_at_its_rational_zero():
    f = (x - y)**2 + z**2
    res = homogeneous_positive_on_sphere(f, [x, y, z])
    assert res.status is Status.FAILED
    assert at(f, [x, y, z], res.witness) == 0 and any(res.witness)


@pytest.mark.parametrize("sign", [1, -1])
def test_odd_degree_fails_immediately(sign):
    f = sign * (x**3 + y**3 + x * y * z)
    res = homogeneous_positive_on_sphere(f, [x, y, z])
    assert res.status is Status.FAILED
    assert at(f, [x, y, z], res.witness) < 0


def test_quadratic_form_min_on_sphere_equals_lambda_min_of_the_matrix_path():
    M = sympy.Matrix([[3, 1, 0], [1, 2, R(1, 2)], [0, R(1, 2), 1]])
    v = sympy.Matrix([x, y, z])
    f = sympy.expand((v.T * M * v)[0])
    sphere = homogeneous_positive_on_sphere(f, [x, y, z], accuracy=Accuracy(rel_gap=1e-6, starts=2))
    matrix = matrix_positive_definite(M)
    assert sphere.status is Status.CERTIFIED and matrix.status is Status.EXACT
    assert sphere.margin.lo <= matrix.margin.lo and matrix.margin.hi <= sphere.margin.hi
    assert sphere.margin.hi - sphere.margin.lo < Fraction(1, 10**5)


def test_irrational_coefficients_against_the_matrix_path():
    f = sympy.sqrt(2) * x**2 + x * y + sympy.pi * y**2
    M = sympy.Matrix([[sympy.sqrt(2), R(1, 2)], [R(1, 2), sympy.pi]])
    sphere = homogeneous_positive_on_sphere(f, [x, y], accuracy=Accuracy(rel_gap=1e-6, starts=2))
    matrix = matrix_positive_definite(M)
    assert sphere.status is Status.CERTIFIED and matrix.status is Status.CERTIFIED
    assert sphere.margin.lo <= matrix.margin.hi and matrix.margin.lo <= sphere.margin.hi


def test_sextic_enclosure_against_a_dense_grid():
    f = x**6 + y**6 + z**6 - R(1, 10) * x**2 * y**2 * z**2 + x**3 * y * z**2
    res = homogeneous_positive_on_sphere(f, [x, y, z], budget=Budget(seconds=5))
    assert res.status is Status.CERTIFIED
    th, ph = np.meshgrid(np.linspace(0, np.pi, 301), np.linspace(0, 2 * np.pi, 601))
    X = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])
    grid_min = float(np.min(sympy.lambdify([x, y, z], f, "numpy")(*X)))
    assert float(res.margin.lo) <= grid_min
    assert abs(grid_min - float(res.margin.hi)) < 1e-3


def test_face_enclosures_are_sound_on_random_boxes():
    # the branch and bound's box bounds against exact values at sampled rational points of each box
    import flint
    f = x**4 + 3 * y**4 + z**4 - 2 * x**3 * y + x * y * z**2 - 5 * x**2 * z**2
    poly = sympy.Poly(f, x, y, z)
    rng = np.random.default_rng(3)
    with flint.ctx.workprec(64):
        for i in range(3):
            face = forms.CubeFace(poly, (x, y, z), i, 4)
            for _ in range(40):
                a = np.sort(rng.uniform(-1, 1, size=(2, 2)), axis=0)
                lo, hi = tuple(a[0]), tuple(a[1])
                lower, upper_at_centre = face.bounds(lo, hi)
                g = sympy.lambdify(face.ys, f.subs((x, y, z)[i], 1) / (1 + sum(v**2 for v in face.ys))**2)
                centre = g(*[(p + q) / 2 for p, q in zip(lo, hi)])
                assert lower <= centre <= upper_at_centre + 1e-12
                for _ in range(20):
                    p = [Fraction(rng.uniform(l_, h_)) for l_, h_ in zip(lo, hi)]
                    pt = p[:i] + [Fraction(1)] + p[i:]
                    value = sum(int(c) * math.prod(v**k for v, k in zip(pt, m)) for m, c in poly.terms())
                    exact = value / sum(v * v for v in pt) ** 2
                    assert Fraction(lower) <= exact              # finite, and below the exact value


def test_budget_exhausted_is_undecided_never_certified():
    f = (x**2 - 2 * y**2)**2 + z**4              # zero at the irrational direction (√2, 1, 0)
    res = homogeneous_positive_on_sphere(f, [x, y, z], budget=Budget(seconds=0.3))
    assert res.status is Status.UNDECIDED
    assert not res.holds
    assert res.margin.lo <= 0 < res.margin.hi
    assert res.estimate.status is Status.ESTIMATED and res.estimate.value < 1e-3


def test_non_homogeneous_reports_each_term_degree():
    with pytest.raises(InputError, match=r"x\*\*4: degree 4.*y\*\*2: degree 2|y\*\*2: degree 2.*x\*\*4: degree 4"):
        homogeneous_positive_on_sphere(x**4 + y**2, [x, y])


@pytest.mark.parametrize("f, variables, kwargs, message", [
    (x**2 + sympy.Symbol("a") * y**2, [x, y], {}, "free symbols"),
    (sympy.sin(x) + y**2, [x, y], {}, "polynomial"),
    (x**2 + y**2, [x, y], {"degree": 4}, "expected degree 4"),
    (sympy.Integer(3), [x], {}, "degree ≥ 1"),
    (x**2, ["x"], {}, "Symbols"),
])
def test_bad_forms_raise_input_error(f, variables, kwargs, message):
    with pytest.raises(InputError, match=message):
        homogeneous_positive_on_sphere(f, variables, **kwargs)


# ---------------------------------------------------------------------------------------------
# LMIs: Lyapunov matrices, quadratic bounds, general LMIs


def test_find_lyapunov_matrix_hurwitz_is_exact_and_independently_checked():
    A = sympy.Matrix([[0, 1], [-2, -3]])
    res = find_lyapunov_matrix(A)
    assert res.status is Status.EXACT
    P = res.certificate
    assert all(e.is_Rational for e in P) and P.is_symmetric()
    assert P.is_positive_definite and (-(A.T * P + P * A)).is_positive_definite
    assert [p.status for p in res.parts] == [Status.EXACT, Status.EXACT]
    assert res.estimate.status is Status.ESTIMATED
    assert res.margin.lo > 0


def test_find_lyapunov_matrix_with_q_needs_the_margin_retry():
    A = sympy.Matrix([[0, 1], [-2, -3]])
    res = find_lyapunov_matrix(A, Q=sympy.eye(2))
    assert res.status is Status.EXACT
    P = res.certificate
    assert (-(A.T * P + P * A) - sympy.eye(2)).is_positive_semidefinite


@pytest.mark.parametrize("A, eigenvalue", [([[1, 0], [0, -1]], 1), ([[0, 1], [-1, 0]], sympy.I),
                                           ([[-1, 0], [0, 0]], 0)])
def test_non_hurwitz_fails_with_the_eigenvalue(A, eigenvalue):
    res = find_lyapunov_matrix(A)
    assert res.status is Status.FAILED
    assert res.witness == eigenvalue
    assert sympy.Matrix(A).charpoly().as_expr().subs(sympy.Symbol("lambda"), res.witness) == 0
    assert "Routh–Hurwitz" in res.detail


def test_check_lyapunov_matrix_flipped_sign_fails():
    A = [[0, 1], [-2, -3]]
    assert check_lyapunov_matrix(A, [[5, 1], [1, 1]]).status is Status.EXACT
    res = check_lyapunov_matrix(A, [[-5, -1], [-1, -1]])
    assert res.status is Status.FAILED
    assert quad_exact([[-5, -1], [-1, -1]], res.witness) <= 0


def test_check_lyapunov_matrix_exact_solution_is_tight_and_a_larger_q_fails():
    A = sympy.Matrix([[0, 1], [-2, -3]])
    P = sympy.Matrix([[R(5, 4), R(1, 4)], [R(1, 4), R(1, 4)]])     # AᵀP + PA = −I exactly
    assert A.T * P + P * A == -sympy.eye(2)
    ok = check_lyapunov_matrix(A, P, Q=sympy.eye(2))
    assert ok.status is Status.EXACT and ok.margin.exact == 0
    bad = check_lyapunov_matrix(A, P, Q=R(11, 10) * sympy.eye(2))
    assert bad.status is Status.FAILED
    w = sympy.Matrix([sympy.Rational(c.numerator, c.denominator) for c in bad.witness])
    assert (w.T * (-(A.T * P + P * A) - R(11, 10) * sympy.eye(2)) * w)[0] < 0


@pytest.mark.parametrize("status", ["optimal_inaccurate", "infeasible_inaccurate", "solver error (x)"])
def test_solver_status_not_optimal_is_never_a_certificate(monkeypatch, status):
    monkeypatch.setattr(lmi, "solve_sdp", lambda problem: status)
    for res in (find_lyapunov_matrix([[0, 1], [-2, -3]]), best_quadratic_upper_bound([[2, 1], [1, 2]]),
                lmi_feasible([[-1, 0], [0, 3]], [[[1, 0], [0, 1]]])):
        assert res.status is Status.UNDECIDED
        assert status in res.detail


def test_rounding_that_breaks_verification_retries_then_undecided(monkeypatch):
    calls = []

    def broken(X, den):
        calls.append(den)
        return -sympy.Matrix(X.tolist()).applyfunc(lambda v: sympy.Rational(round(v * 1000), 1000))

    monkeypatch.setattr(lmi, "round_symmetric", broken)
    res = find_lyapunov_matrix([[0, 1], [-2, -3]])
    assert res.status is Status.UNDECIDED            # a bad rounding never refutes existence
    assert len(calls) == 3 and "did not verify" in res.detail


def test_best_quadratic_upper_bound_exact_and_verified():
    M = sympy.Matrix([[2, 1], [1, 2]])
    res = best_quadratic_upper_bound(M)
    assert res.status is Status.EXACT
    assert res.certificate == 3 and res.margin.exact == 3 and res.margin.lo == res.margin.hi == 3
    assert res.estimate.status is Status.ESTIMATED and abs(res.estimate.value - 3) < 1e-6


def test_best_quadratic_upper_bound_generalized_eigenvalue_enclosed():
    M, N = sympy.Matrix([[2, 1], [1, 2]]), sympy.diag(2, 1)
    res = best_quadratic_upper_bound(M, N=N)
    assert res.status is Status.EXACT
    c_star = (3 + sympy.sqrt(3)) / 2                                  # the generalized eigenvalue
    lo, hi = (sympy.Rational(v.numerator, v.denominator) for v in (res.margin.lo, res.margin.hi))
    assert bool(lo <= c_star) and bool(c_star <= hi)                 # decided exactly by SymPy
    c = res.certificate
    assert c.is_Rational and (c * N - M).is_positive_semidefinite
    assert res.margin.width < Fraction(1, 10**5)


def test_best_quadratic_upper_bound_over_a_list():
    res = best_quadratic_upper_bound([[[2, 1], [1, 2]], [[1, 0], [0, 5]]])
    assert res.status is Status.EXACT and res.certificate == 5


def test_claimed_constant_below_the_generalized_eigenvalue_fails_with_the_vector():
    M, N = sympy.Matrix([[2, 1], [1, 2]]), sympy.diag(2, 1)
    assert check_quadratic_bound(M, R(237, 100), N=N).status is Status.EXACT     # c* ≈ 2.3660
    c = R(236, 100)                                                               # the mutation
    res = check_quadratic_bound(M, c, N=N)
    assert res.status is Status.FAILED
    w = sympy.Matrix([sympy.Rational(v.numerator, v.denominator) for v in res.witness])
    assert (w.T * M * w)[0] > c * (w.T * N * w)[0]


def test_quadratic_bound_requires_positive_definite_n():
    with pytest.raises(InputError, match="positive definite N"):
        check_quadratic_bound([[2, 1], [1, 2]], 3, N=[[1, 0], [0, -1]])


def test_lmi_feasible_and_exact_farkas_certificate():
    ok = lmi_feasible([[-1, 0], [0, 3]], [[[1, 0], [0, 1]]])
    assert ok.status is Status.EXACT and ok.certificate[0] > 1
    F0, F1 = sympy.Matrix([[-1, 0], [0, -1]]), sympy.Matrix([[1, 0], [0, -1]])   # y > 1 and y < −1
    bad = lmi_feasible(F0, [F1])
    assert bad.status is Status.FAILED
    Z = bad.witness
    assert Z.is_positive_definite and (F1 * Z).trace() == 0 and (F0 * Z).trace() <= 0


# ---------------------------------------------------------------------------------------------
# the result types


def test_an_estimate_never_carries_a_proof_status():
    for status in (Status.EXACT, Status.CERTIFIED, Status.FAILED):
        with pytest.raises(ValueError, match="never a proof"):
            Estimate(1.0, "sampling", status=status)
    for status in (Status.ESTIMATED, Status.SIMULATED):
        with pytest.raises(ValueError, match="estimate"):
            ConditionResult("c", status, margin=Margin(0, 1))
    results = [homogeneous_positive_on_sphere(x**2 + y**2, [x, y]), find_lyapunov_matrix([[-1, 0], [0, -2]]),
               best_quadratic_upper_bound([[1, 0], [0, 2]])]
    assert all(r.estimate.status is Status.ESTIMATED for r in results)
    assert all(r.to_json()["estimate"]["status"] == "estimated" for r in results)


def test_result_invariants():
    with pytest.raises(ValueError, match="witness"):
        ConditionResult("c", Status.FAILED)
    with pytest.raises(ValueError, match="margin"):
        ConditionResult("c", Status.CERTIFIED)
    with pytest.raises(ValueError, match="lo <= hi"):
        Margin(2, 1)
    res = matrix_positive_definite([[2, 1], [1, 2]])
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.status = Status.FAILED


def test_to_json_and_to_result():
    res = matrix_positive_definite([[1, R(1, 3)], [R(1, 3), 1]])
    d = json.loads(json.dumps(res.to_json()))
    assert d["status"] == "exact" and d["margin"]["lo_exact"] == "2/3" == d["margin"]["hi_exact"]
    assert d["margin"]["lo"] <= 2 / 3 <= d["margin"]["hi"]
    bad = matrix_positive_definite(sympy.diag(1, -1))
    assert json.loads(json.dumps(bad.to_json()))["witness"] == [0, 1]
    z = json.loads(json.dumps(lmi_feasible([[-1, 0], [0, -1]], [[[1, 0], [0, -1]]]).to_json()))["witness"]
    assert z == [["1/2", 0], [0, "1/2"]]                                        # exact rationals as "p/q"
    row = res.to_result()
    assert isinstance(row, Result) and row.kind == "hypothesis" and row.status is Status.EXACT
    assert row.value <= 2 / 3


# ---------------------------------------------------------------------------------------------
# near-PD matrices: exact inputs stay exact, refutations are true (rechecked here exactly)


def _recheck_refutation(M, res):
    """The witness of a `failed` must give xᵀMx ≤ 0 exactly (a true counterexample)."""
    assert res.status is Status.FAILED and res.witness is not None and any(res.witness)
    value = quad_exact(M, res.witness)
    assert value.is_number and value <= 0
    return value


def test_near_pd_rational_matrix_with_negative_determinant_fails_with_a_true_witness():
    e = 1 + R(45, 10**9)
    M = [[1, e], [e, 1 + R(9, 10**8)]]
    assert sympy.Matrix(M).det() == -R(81, 4 * 10**16)           # det ≈ −2e-15: not PD
    res = matrix_positive_definite(M)
    value = _recheck_refutation(M, res)
    assert value < 0 and value.is_Rational
    assert res.margin.hi < 0                                      # λ_min < 0, certified


def test_pd_matrix_one_minus_1e_minus_20_is_exact():
    a = 1 - R(1, 10**20)
    res = matrix_positive_definite([[1, a], [a, 1]])
    assert res.status is Status.EXACT and res.holds and res.witness is None
    assert res.margin.exact == R(1, 10**20) == res.margin.lo       # λ_min = 1 − a exactly
    # the witness the old float path claimed, x = (−1, 1), gives xᵀMx = 2·10⁻²⁰ > 0
    assert quad_exact([[1, a], [a, 1]], (Fraction(-1), Fraction(1))) == R(2, 10**20)


@pytest.mark.parametrize("shift, status", [(R(1, 10**30), Status.CERTIFIED), (-R(1, 10**30), Status.FAILED)])
def test_irrational_entries_are_decided_in_arb_with_certified_margins(shift, status):
    s2 = sympy.sqrt(2)
    M = [[s2, s2], [s2, s2 + shift]]                               # λ_min ≈ shift/2
    res = matrix_positive_definite(M)
    assert res.status is status
    tol = abs(shift) / 10**6
    assert res.margin.lo <= shift / 2 + tol and res.margin.hi >= shift / 2 - tol
    assert res.margin.lo <= res.margin.hi and (res.margin.lo > 0) == (status is Status.CERTIFIED)
    if status is Status.FAILED:
        assert sympy.simplify(quad_exact(M, res.witness)) < 0


def test_irrational_pd_matrix_margin_encloses_the_exact_lambda_min():
    s2 = sympy.sqrt(2)
    res = matrix_positive_definite([[s2, 1], [1, s2]])
    assert res.status is Status.CERTIFIED
    lam = s2 - 1
    assert sympy.Rational(res.margin.lo) <= lam <= sympy.Rational(res.margin.hi)
    assert res.margin.hi - res.margin.lo < Fraction(1, 10**12)


def test_singular_matrix_with_irrational_entries_is_undecided_not_refuted():
    s2 = sympy.sqrt(2)
    res = matrix_positive_definite([[1, s2], [s2, 2]])             # λ_min = 0 exactly
    assert res.status is Status.UNDECIDED and res.witness is None
    assert res.margin.lo <= 0 <= res.margin.hi


@pytest.mark.parametrize("seed", range(30))
def test_every_refutation_of_a_random_near_singular_matrix_is_true(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 5))
    B = sympy.Matrix(n, n - 1, lambda i, j: R(int(rng.integers(-5, 6)), int(rng.integers(1, 4))))
    eps = R(int(rng.integers(-3, 4)), 10 ** int(rng.integers(8, 25)))
    M = B * B.T + eps * sympy.eye(n)                                 # rank n−1 plus a tiny shift
    res = matrix_positive_definite(M)
    pd = all(M[:k, :k].det() > 0 for k in range(1, n + 1))          # Sylvester, exactly
    if res.status is Status.FAILED:
        assert quad_exact(M, res.witness) <= 0 and not pd
    else:
        assert res.status is Status.EXACT and pd
