"""Every claim the papers make about their numerical examples, with numbers; and what they get wrong."""

import json

import numpy as np
import pytest

from lkverify.catalogue.loader import find_items
from lkverify.cli import main
from lkverify.status import Status


def report(name, **kw):
    (ex,) = find_items(name)
    rep = ex.run(**kw)
    return ex, rep, {r.name: r for r in rep.results}


def runs(res):
    return {k[4:]: v.value for k, v in res.items() if k.startswith("run ")}


# -- paper 002, Figs. 1–7: a distributed delay ----------------------------------------------------------
def test_fig1_converges():
    _, rep, res = report("aleksandrov2023.fig1")
    (s,) = runs(res).values()
    assert s["converged"] and s["t_1e2"] < s["t_1e3"] < 100
    assert rep.holds


def test_fig2_does_not_stabilize():
    _, rep, res = report("aleksandrov2023.fig2")
    (claim,) = [r for n, r in res.items() if n.endswith("does not converge")]
    assert claim.status is Status.SIMULATED and claim.value["min_distance_tail"] > 0.5


@pytest.mark.slow
def test_fig3_converges_with_mu_2():
    _, rep, res = report("aleksandrov2023.fig3")
    assert rep.holds and runs(res)["Fig. 3: b = −2, μ = 2"]["t_1e3"] is not None


@pytest.mark.slow
def test_fig4_does_not_converge_but_is_not_chaotic():
    """The paper calls the Fig. 4 motion chaotic; nearby histories do not separate (a finding)."""
    _, rep, res = report("aleksandrov2023.fig4")
    (nc,) = [r for n, r in res.items() if n.endswith("does not converge")]
    (sens,) = [r for n, r in res.items() if n.endswith("sensitive dependence on the initial data")]
    assert nc.status is Status.SIMULATED and nc.value["min_distance_tail"] > 0.5
    assert sens.status is Status.FAILED
    assert sens.value["max_separation"] < 1e-5  # a 1e-8 perturbation stays tiny over [0, 200]
    assert not rep.holds


@pytest.mark.slow
def test_fig4_over_a_100_times_longer_interval():
    ex, rep, res = report("aleksandrov2023.fig4", t_end=20000.0)
    (nc,) = [r for n, r in res.items() if n.endswith("does not converge")]
    (sens,) = [r for n, r in res.items() if n.endswith("sensitive dependence on the initial data")]
    assert nc.status is Status.SIMULATED and nc.value["min_distance_tail"] > 0.4
    assert sens.value["max_separation"] < 1e-5


@pytest.mark.slow
def test_fig5_converges_slowly():
    _, rep, res = report("aleksandrov2023.fig5")
    (s,) = runs(res).values()
    assert rep.holds and s["t_1e2"] > 300  # slow, as the paper says


def test_fig6_converges():
    _, rep, res = report("aleksandrov2023.fig6")
    (s,) = runs(res).values()
    assert rep.holds and 50 < s["t_1e2"] < 100 and s["t_1e3"] is not None
    assert max(s["constraint_drift"].values()) < 1e-8


def test_fig7_printed_estimate_15_holds_along_the_simulation():
    ex, rep, res = report("aleksandrov2023.fig7")
    env = [r for r in rep.results if r.kind == "envelope"][0]
    assert env.status is Status.SIMULATED
    assert 0.1 < env.value["max_ratio"] < 1 and env.value["first_violation"] is None


def test_fig7_history_norm_is_above_the_printed_region():
    """‖χ‖_τ of the Fig. 7 data is 0.954 here, not the paper's 0.25 < 0.28 (see test_rigidbody)."""
    (ex,) = find_items("aleksandrov2023.fig7")
    chi = ex.envelope.chi(ex.runs[0])
    assert chi == pytest.approx(0.953973, abs=1e-6)
    assert chi > 0.28


# -- paper 000: discrete delay vs the PID with an exponential kernel ------------------------------------
@pytest.mark.slow
def test_delayed_and_pid_converge_and_the_pid_is_faster_and_smoother():
    _, rep, res = report("aleksandrov2026.example")
    assert rep.holds, rep.as_text()
    faster = [r for n, r in res.items() if "reaches" in n][0]
    assert faster.value["t_a"] < faster.value["t_b"]
    smoother = [r for n, r in res.items() if "smoother" in n][0]
    assert smoother.value["extrema_a"] < smoother.value["extrema_b"]
    for s in runs(res).values():
        assert s["converged"] and max(s["constraint_drift"].values()) < 1e-8


# -- paper 001: a time-varying coefficient -------------------------------------------------------------
@pytest.mark.slow
def test_decreasing_dissipation_beta_7_8_converges_and_8_7_does_not():
    _, rep, res = report("aleksandrov2017.example")
    assert rep.holds, rep.as_text()
    r = runs(res)
    assert r["h = (1+t)^(−7/8)"]["converged"] and 100 < r["h = (1+t)^(−7/8)"]["t_1e2"] < 250
    bounded = res["h = (1+t)^(−8/7): bounded but not attractive"]
    assert bounded.value["energy_limit_lower"] > 0 and np.isfinite(bounded.value["tail_integral"])
    assert r["h = (1+t)^(−8/7)"]["final_distance"] > 1e-2


@pytest.mark.slow
def test_bounded_not_attractive_claim_fails_for_the_converging_case():
    """The same claim applied to β = 7/8 must fail: ∫h diverges, so no positive energy limit."""
    from lkverify.simulate import BoundedNotAttractive

    (ex,) = find_items("aleksandrov2017.example")
    claim = ex.claims[1]
    trs = ex.simulate()
    wrong = BoundedNotAttractive("h = (1+t)^(−7/8)", claim.measure, "(1+t)**(-7/8)", bound=3.0)
    assert wrong.check(ex, trs).status is Status.FAILED


# -- the command line --------------------------------------------------------------------------------------
def test_cli_simulate_fig6_json_and_png(tmp_path, capsys):
    png = tmp_path / "f.png"
    code = main(["simulate", "aleksandrov2023.fig6", "--plot", str(png), "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    assert png.exists() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (run,) = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert run["status"] == "simulated" and run["value"]["converged"]
    assert run["value"]["t_1e2"] is not None and run["value"]["t_1e3"] is not None


@pytest.mark.slow
def test_cli_simulate_2017_shows_both_cases(capsys):
    """Both runs of the 2017 example are reported: β = 7/8 converges, β = 8/7 stays bounded, not attractive.

    The text table wraps long names over lines (issue 27), so the claims are read from ``--json``;
    the text report is checked for the row of each run.
    """
    code = main(["simulate", "aleksandrov2017.example", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    by_name = {r["name"]: r for r in doc["results"]}
    assert by_name["h = (1+t)^(−7/8): converges"]["status"] == "simulated"
    assert by_name["h = (1+t)^(−8/7): bounded but not attractive"]["status"] == "simulated"
    assert by_name["run h = (1+t)^(−7/8)"]["value"]["converged"]
    assert not by_name["run h = (1+t)^(−8/7)"]["value"]["converged"]
    code = main(["simulate", "aleksandrov2017.example"])
    out = capsys.readouterr().out
    assert code == 0 and "converged: distance" in out and "not converged: distance" in out


@pytest.mark.parametrize("argv, needle", [
    (["simulate", "aleksandrov2023.fig6", "--t-end", "0"], "--t-end"),
    (["simulate", "aleksandrov2023.fig6", "--set", "tau=-1"], "tau"),
    (["simulate", "aleksandrov2023.fig6", "--history", "omega=[1,2]"], "3 components"),
    (["simulate", "aleksandrov2026.example", "--set", "g=1"], "not integrable"),
    (["simulate", "aleksandrov2026.example", "--history", "s1=[1,0,0]"], "orthonormal"),
    (["simulate", "aleksandrov2023.theorem3"], "not a numerical example"),
])
def test_cli_simulate_bad_input(capsys, argv, needle):
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_fig7_printed_history_norm_is_not_reproduced_by_any_reading():
    (item,) = find_items("aleksandrov2023.fig7_chi")
    (r,) = item.run({}).results
    assert r.status is Status.FAILED
    assert r.value["default"] == pytest.approx(0.953973, abs=1e-6)
    assert abs(r.value["nearest"] - 0.25) > 0.05 and not r.value["reproduced"]


def test_does_not_converge_is_judged_by_returns_above_the_floor_not_by_the_minimum():
    """An undamped oscillation passes through 0 and still does not converge; a decay does."""
    from lkverify import Equation, Parameters, Series, System, Term, Vector, t
    from lkverify.catalogue.examples import Example
    from lkverify.simulate.experiments import DoesNotConverge, Run

    P = Parameters()
    c = P.scalar("c", nonnegative=True, default=0)
    x = Vector("x", 2)
    system = System([Equation(x, [Term(sympy_matrix_rotation(x, c))])], parameters=P)
    runs_ = [Run("undamped", system, {"c": 0}, {"x": [1, 0]}), Run("damped", system, {"c": 1}, {"x": [1, 0]})]
    ex = Example("osc", runs=runs_, t_end=40, series=[Series("x", lambda S: S["x"][:, 0])],
                 distance=lambda S: np.abs(S["x"][:, 0]), samples=4001)
    trs = ex.simulate()
    undamped = DoesNotConverge("undamped").check(ex, trs)
    assert undamped.status is Status.SIMULATED
    assert undamped.value["min_distance_tail"] < 1e-2 < min(undamped.value["window_maxima"])
    damped = DoesNotConverge("damped").check(ex, trs)
    assert damped.status is Status.FAILED and max(damped.value["window_maxima"]) < 1e-2
    with pytest.raises(Exception, match="windows ≥ 1"):
        DoesNotConverge("undamped", windows=0)


def sympy_matrix_rotation(x, c):
    """x' = [[−c, 1], [−1, −c]] x."""
    import sympy

    from lkverify import t

    X = x(t)
    return sympy.Matrix([-c * X[0] + X[1], -X[0] - c * X[1]])
