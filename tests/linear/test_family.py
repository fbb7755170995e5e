"""lkverify.linear.family: one symbolic linearisation, evaluated at many grid points."""

import pickle

import numpy as np
import pytest
import sympy
from scipy.special import lambertw

from lkverify import Equation, InputError, Parameters, System, Term, UnsupportedInput, Vector, t
from lkverify.linear import linearise, rightmost_roots
from lkverify.linear.family import TOL, LinearFamily, linear_family
from lkverify.proofs.aleksandrov2023.equations import system as system_002
from lkverify.proofs.aleksandrov2023.linear_mu1 import FIGURE_GAINS
from lkverify.proofs.aleksandrov2023.section6 import FIG6
from lkverify.proofs.aleksandrov2026.equations import system_pid as system_000_pid

AT_R = {"omega": [0, 0, 0], "s": "r"}
H = sympy.Symbol("h")
#: the (a, b, h) of Figs. 1, 2, 4 (F = h·I, τ = 0.9, μ = 1), the verdict and the abscissa linear_mu1.py reports
#: (rounded: half a unit of its last digit)
FIGS = {1: ((2, 2, 0.7), "stable", (-0.143, 5e-4)), 2: ((2, -2, 0.7), "unstable", (0.0061, 5e-5)),
        4: ((0.6, -0.6, 0.2), "unstable", (0.0041, 5e-5))}


@pytest.fixture(scope="module")
def fam002():
    """Paper 002 at μ = 1, τ = 0.9, swept in (a, b, h) with F = diag(h, h, h)."""
    return linear_family(system_002, AT_R, {"F": sympy.ImmutableMatrix(sympy.diag(H, H, H)), "tau": "0.9", "mu": "1"},
                         grid=("a", "b", "h"))


def _toy(name="toy"):
    """x' = −a x(t − τ)."""
    P = Parameters()
    a = P.scalar("a", default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    return System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P, name=name)


# ------------------------------------------------------------------------ paper 002, μ = 1


@pytest.mark.parametrize("number", [1, 2, 4])
def test_figures_equal_the_exact_linearisation(fam002, number):
    point, verdict, (reported, rounding) = FIGS[number]
    batch = fam002.evaluate([point])
    exact = rightmost_roots(linearise(system_002, AT_R, FIGURE_GAINS[number]), 0.9)
    assert abs(batch.abscissa[0] - exact.abscissa) < 1e-8
    assert batch.verdict == (verdict,) and batch.status == "estimated"
    assert abs(batch.abscissa[0] - reported) <= rounding
    assert batch.converged[0] and batch.residual[0] < 1e-10


def test_family_matrices_are_the_exact_linearisation_at_a_point(fam002):
    # the symbolic path and the exact path are one path: substituting Fig. 1's values gives linearise's matrices
    at = fam002.at({"a": 2, "b": 2, "h": sympy.Rational(7, 10)})
    lin = linearise(system_002, AT_R, FIGURE_GAINS[1])
    assert at.A == lin.A and at.kernel == lin.kernel and at.Ad == lin.Ad
    assert fam002.delay == sympy.Rational(9, 10) and not fam002.structural_zero
    assert fam002.D.free_symbols == {fam002.symbols[1]}          # the delayed torque is b's alone


def test_flipped_b_is_not_fig1(fam002):
    # a family built wrongly (b's sign lost) would give Fig. 1's verdict at Fig. 2's gains
    fig1, fig2 = fam002.evaluate([FIGS[1][0], FIGS[2][0]]).abscissa
    assert fig1 < -0.1 and fig2 > 0


def test_fig2_threshold_h_star(fam002):
    # linear_mu1.py: at a = 2, b = −2, τ = 0.9 the linearisation is stable above h* = 0.766
    assert fam002.evaluate([[2, -2, 0.76], [2, -2, 0.77]]).verdict == ("unstable", "stable")


def test_mu2_has_no_stiffness_critical_not_stable():
    values = {**{k: v for k, v in FIG6.items() if k not in ("b", "F")}, "F": sympy.diag(H, H, H)}
    fam = linear_family(system_002, AT_R, values, grid=("b", "h"))
    assert fam.structural_zero
    batch = fam.evaluate([[-1, 1], [2, 0.7], [-3, 2]])
    assert batch.verdict == ("critical",) * 3
    assert np.all(batch.abscissa == 0)


def test_swept_delay_matches_linearise_at_each_tau():
    values = {k: v for k, v in FIGURE_GAINS[2].items() if k != "tau"}
    fam = linear_family(system_002, AT_R, values, grid=("tau",))
    assert fam.delay == fam.symbols[0]
    assert fam.delay_at({"tau": sympy.Rational(3, 2)}) == sympy.Rational(3, 2)
    taus = ["1/2", "9/10", "3/2"]
    batch = fam.evaluate([[float(sympy.Rational(x))] for x in taus])
    for x, got in zip(taus, batch.abscissa):
        exact = rightmost_roots(linearise(system_002, AT_R, {**values, "tau": x}), float(sympy.Rational(x)))
        assert abs(got - exact.abscissa) < 1e-8
    assert batch.verdict == ("stable", "unstable", "unstable")         # Fig. 2's damping suffices for τ = 1/2 only
    np.testing.assert_array_equal(batch.delay, [0.5, 0.9, 1.5])


# ------------------------------------------------------------------------ closed forms


def test_scalar_dde_lambert_w_closed_form():
    # x' = −a x(t − τ): the rightmost root is W_0(−aτ)/τ (principal branch of Lambert's W)
    fam = linear_family(_toy(), {"x": [0]}, grid=("a", "tau"))
    pts = np.array([[0.3, 1.0], [1.0, 1.0], [1.0, 2.0], [2.5, 0.4], [0.2, 6.0]])
    batch = fam.evaluate(pts)
    expected = [lambertw(-a * tau, 0).real / tau for a, tau in pts]
    np.testing.assert_allclose(batch.abscissa, expected, rtol=0, atol=1e-10)


def test_scalar_dde_boundary_a_tau_pi_over_2():
    fam = linear_family(_toy(), {"x": [0]}, grid=("a", "tau"))
    tau = 1.3
    a0 = np.pi / 2 / tau
    batch = fam.evaluate([[a0 * (1 - 1e-3), tau], [a0, tau], [a0 * (1 + 1e-3), tau]])
    assert batch.verdict == ("stable", "critical", "unstable")
    assert abs(batch.abscissa[1]) <= TOL
    assert abs(abs(batch.rightmost[1].imag) - np.pi / (2 * tau)) < 1e-9      # the crossing frequency π/(2τ)


def test_structural_zero_is_never_stable():
    # x1' = a x1, x2' = x1: λ ∈ {a, 0} for every a: a < 0 is critical, a > 0 unstable
    P = Parameters()
    a = P.scalar("a", default=1)
    x = Vector("x", 2)
    sys = System([Equation(x, [Term(sympy.Matrix([a * x(t)[0], x(t)[0]]))])], parameters=P, name="zero")
    fam = linear_family(sys, {"x": [0, 0]}, grid=("a",))
    assert fam.structural_zero and fam.delay is None
    assert fam.evaluate([[-1.0], [1.0]]).verdict == ("critical", "unstable")


def test_undefined_points():
    fam = linear_family(_toy(), {"x": [0]}, grid=("a", "tau"))
    batch = fam.evaluate([[1.0, -0.5], [np.nan, 1.0], [1.0, 0.0]])
    assert batch.verdict[:2] == ("undefined", "undefined") and np.isnan(batch.abscissa[:2]).all()
    assert batch.verdict[2] == "stable" and batch.abscissa[2] == -1.0           # τ = 0: x' = −x


# ------------------------------------------------------------------------ refusals


def test_not_an_equilibrium_for_every_grid_value():
    P = Parameters()
    k = P.scalar("k", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(k - x(t)[0])])], parameters=P, name="shifted")
    with pytest.raises(InputError, match=r"at every grid point.*residual dx/dt = k - 1.*for all values of k"):
        linear_family(sys, {"x": [1]}, grid=("k",))
    with pytest.raises(InputError, match=r"residual .*domega_3/dt"):
        linear_family(system_002, {"omega": [0, 0, "1/10"], "s": "r"}, {"mu": 1}, grid=("b",))


def test_not_differentiable_refused():
    with pytest.raises(InputError, match="differentiable"):
        linear_family(system_002, AT_R, {"mu": "1/2"}, grid=("b",))


def test_memory_integral_and_several_delays_refused():
    with pytest.raises(UnsupportedInput, match="memory"):
        linear_family(system_000_pid, {"omega": [0, 0, 0], "s1": "r1", "s2": "r2", "s3": "r3"}, grid=("nu",))
    P = Parameters()
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-x(t - tau)[0] - x(t - 2 * tau)[0])])], parameters=P, name="two")
    with pytest.raises(InputError, match="one delay"):
        linear_family(sys, {"x": [0]}, grid=("tau",))


def test_bad_grid_and_points():
    with pytest.raises(InputError, match="grid k"):
        linear_family(_toy(), {"x": [0]}, grid=("k",))
    with pytest.raises(InputError, match="grid"):
        linear_family(_toy(), {"x": [0]}, grid=())
    with pytest.raises(InputError, match="scalar"):
        linear_family(system_002, AT_R, {"mu": 1}, grid=("F",))
    fam = linear_family(_toy(), {"x": [0]}, grid=("a", "tau"))
    with pytest.raises(InputError, match=r"\(N, 2\)"):
        fam.evaluate([1.0, 2.0, 3.0])
    with pytest.raises(InputError, match="real numbers"):
        fam.evaluate([["x", 1.0]])


# ------------------------------------------------------------------------ shipping to workers


def test_pickle_round_trip_after_use(fam002):
    pts = [FIGS[k][0] for k in FIGS]
    before = fam002.evaluate(pts)                      # the generated function is cached now: it must not travel
    copy = pickle.loads(pickle.dumps(fam002))
    assert isinstance(copy, LinearFamily) and "_fn" not in copy.__dict__
    after = copy.evaluate(pts)
    np.testing.assert_array_equal(before.abscissa, after.abscissa)
    assert before.verdict == after.verdict
