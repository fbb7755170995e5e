"""Paper 002, μ = 1: the linearisation against an independent Jacobian, the figures decided, h* brackets."""

import sympy
import pytest

from lkverify.linear import rightmost_roots
from lkverify.proofs.aleksandrov2023.equations import P
from lkverify.proofs.aleksandrov2023.linear_mu1 import (FIGURE_GAINS, _damping_family, linear_mu1, linearisation,
                                                         tangent_basis, threshold)


def _jacobian_reference(gains):
    """ẏ, δω̇ as the Jacobian of (10), (12) in R³ at s = r, ω = 0 (SymPy diff), mapped to y by s = r + E y/‖u‖."""
    v = P.resolve(dict(gains), use_defaults=True)
    Theta, F, a, b, r = v["Theta"], v["F"], v["a"], v["b"], v["r"]
    u, E = tangent_basis(r)
    nu = sympy.sqrt((u.T * u)[0])
    y = sympy.Matrix(sympy.symbols("y1 y2"))
    Y = sympy.Matrix(sympy.symbols("Y1 Y2"))      # ∫ y over the window
    w = sympy.Matrix(sympy.symbols("w1 w2 w3"))
    s = r + E * y / nu
    S = r * sympy.Symbol("tau_") + E * Y / nu     # ∫ s(ξ) dξ for the linear torque (μ = 1)
    sdot = -w.cross(s)
    wdot = Theta.inv() * (-w.cross(Theta * w) - F * w - a * s.cross(r) + b * S.cross(r))   # (12), μ = 1
    ydot = nu * (E.T * E).inv() * E.T * sdot
    x, X = list(y) + list(w), list(Y) + [0, 0, 0]
    f = list(ydot) + list(wdot)
    zero = {sym: 0 for sym in list(y) + list(Y) + list(w)}
    A = sympy.Matrix(5, 5, lambda i, j: sympy.simplify(sympy.diff(f[i], x[j]).subs(zero)))
    D = sympy.Matrix(5, 2, lambda i, j: sympy.simplify(sympy.diff(f[i], Y[j]).subs(zero)))
    return A, D


@pytest.mark.parametrize("number", [1, 4])
def test_linearisation_matches_an_independent_jacobian(number):
    sys = linearisation(FIGURE_GAINS[number])
    A, D = _jacobian_reference(FIGURE_GAINS[number])
    assert sympy.simplify(sys.A - A) == sympy.zeros(5, 5)
    assert sympy.simplify(sys.kernel[0][:, :2] - D) == sympy.zeros(5, 2)
    assert sys.is_rational


@pytest.mark.parametrize("number", [1, 2, 4])
def test_linearisation_matches_the_catalogued_system(number):
    from lkverify.proofs.aleksandrov2023.linear_mu1 import linearisation_from_system
    a, b = linearisation_from_system(FIGURE_GAINS[number]), linearisation(FIGURE_GAINS[number])
    assert (a.A - b.A).is_zero_matrix and (a.kernel[0] - b.kernel[0]).is_zero_matrix


def test_catalogued_linearisation_refuses_mu_2():
    from lkverify.errors import InputError
    from lkverify.proofs.aleksandrov2023.linear_mu1 import linearisation_from_system
    with pytest.raises(InputError, match="μ = 1"):
        linearisation_from_system({**FIGURE_GAINS[1], "mu": "2"})


def test_a_wrong_sign_of_b_is_a_different_system():
    A, D = _jacobian_reference({**FIGURE_GAINS[1], "b": "-2"})
    assert sympy.simplify(linearisation(FIGURE_GAINS[1]).kernel[0][:, :2] - D) != sympy.zeros(5, 2)


def test_figures_decided():
    # Fig. 1 stable (and certified by the item), Fig. 2 and Fig. 4 unstable at their printed h
    for number, stable in ((1, True), (2, False), (4, False)):
        g = FIGURE_GAINS[number]
        tau = P.resolve(dict(g), use_defaults=True)["tau"]
        assert (rightmost_roots(linearisation(g), float(tau), nodes=16).abscissa < 0) is stable


def test_threshold_brackets_fig2():
    th = threshold(2, -2, sympy.Rational(9, 10), base=FIGURE_GAINS[2])["h_star"]
    assert 0.70 < th < 0.80
    family = _damping_family(FIGURE_GAINS[2])
    tau = 0.9
    assert rightmost_roots(family(sympy.Rational(th) * sympy.Rational(99, 100)), tau).abscissa > 0
    assert rightmost_roots(family(sympy.Rational(th) * sympy.Rational(101, 100)), tau).abscissa < 0


@pytest.mark.slow
def test_item_runs():
    rep = linear_mu1.run()
    names = [r.name for r in rep.results]
    assert "Fig. 1: LK certificate at τ = 9/10" in names
    cert = next(r for r in rep.results if r.name.startswith("Fig. 1: LK"))
    assert cert.status.value == "exact"
    assert rep.exit_code == 0


@pytest.mark.slow
def test_threshold_job_reports_and_plots(tmp_path, monkeypatch):
    from lkverify.proofs.aleksandrov2023.linear_mu1 import ThresholdJob
    job = ThresholdJob()
    monkeypatch.setattr(ThresholdJob, "bs", (-2.0, 2.0))
    values = P.resolve({**FIGURE_GAINS[2]}, use_defaults=True)
    rep, extra = job.run("aleksandrov2023.linear_mu1", values, {}, budget=None)
    # the --set point's own row (issue 27), then the six thresholds h*(a, b, τ)
    assert rep.results[0].name.startswith("this point: b = ")
    assert [r.status.value for r in rep.results] == ["estimated"] * 7
    assert sum(r.name.startswith("h*(a = ") for r in rep.results) == 6
    path = job.plot(extra, tmp_path / "h.png")
    assert (tmp_path / "h.png").stat().st_size > 10_000 and path.endswith("h.png")
    rep, _ = job.run("aleksandrov2023.linear_mu1", values, {}, budget=0)   # no time: undecided, never estimated
    assert rep.verdict.startswith("undecided")


@pytest.mark.parametrize("number, verdict", [(1, "stable"), (2, "unstable"), (4, "unstable")])
def test_the_constants_report_states_the_set_point(number, verdict):
    """``constants linear_mu1 --set …``: the run's own gains get a row and the verdict (issue 27), not only the figure."""
    from lkverify.proofs.aleksandrov2023.linear_mu1 import point_row

    row = point_row(P.resolve(dict(FIGURE_GAINS[number]), use_defaults=True))
    assert row.detail.startswith(f"{verdict} at this point")
    assert (row.value["value"] < 0) == (verdict == "stable")
    if verdict == "unstable":
        assert row.value["h_star"] > row.value["h"]       # below the threshold h*
