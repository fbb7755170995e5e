"""Conditions (5), (10)/(15), (11) of paper 001 on h(t): must-pass and must-fail cases."""

import pytest
import sympy

from lkverify import InputError, t
from lkverify.proofs.aleksandrov2017.conditions_h import decide_h_conditions
from lkverify.status import Status

R = sympy.Rational
beta = sympy.Symbol("beta", positive=True)


def statuses(res):
    return [r.status for r in res]


def test_power_7_8_holds_nu_range():
    res = decide_h_conditions((t + 1) ** R(-7, 8))
    assert all(r.status is Status.EXACT for r in res)
    assert res[-1].value["nu"] == sympy.Interval(1, R(8, 7))


def test_power_8_7_fails_11_for_every_nu():
    res = decide_h_conditions((t + 1) ** R(-8, 7))
    assert res[0].status is Status.EXACT and res[1].status is Status.EXACT   # (5), (10) hold
    assert res[2].status is Status.FAILED and res[-1].status is Status.FAILED
    assert "(11) fails for every ν ≥ 1" in res[-1].detail and "= 7 < ∞" in res[-1].detail


def test_symbolic_beta_corollary1():
    res = decide_h_conditions((t + 1) ** (-beta))
    last = res[-1]
    assert last.status is Status.EXACT
    assert last.value["condition"] == (beta <= 1)
    assert last.value["nu"] == sympy.Interval(1, 1 / beta)


def test_exp_fails_11():
    res = decide_h_conditions(sympy.exp(-t))
    assert res[2].status is Status.FAILED and res[-1].status is Status.FAILED
    assert "exp(-t) dt = 1 < ∞" in res[-1].detail


def test_inverse_log_holds_for_every_nu():
    # |ḣ| = 1/((t+2) log²(t+2)) ≤ L h^((3−ν)/2) and ∫ 1/log^ν(t+2) = ∞ for every ν: correct
    res = decide_h_conditions(1 / sympy.log(t + 2))
    assert all(r.status is Status.EXACT for r in res)
    assert res[-1].value["nu"] == sympy.Interval(1, sympy.oo)


def test_constant_fails_5():
    res = decide_h_conditions(sympy.Integer(2))
    assert res[0].status is Status.FAILED and "≠ 0" in res[0].detail
    assert res[-1].status is Status.FAILED


def test_constant_fails_5_with_nu():
    res = decide_h_conditions(sympy.Integer(1), nu=1)
    assert res[0].status is Status.FAILED and res[-1].status is Status.FAILED


def test_nonpositive_h_fails_5():
    res = decide_h_conditions(-(t + 1) ** -1, nu=1)
    assert res[0].status is Status.FAILED and res[-1].status is Status.FAILED


@pytest.mark.parametrize("h", [(t + 1) ** -0.5, 0.5 / (t + 1)])
def test_float_refused(h):
    with pytest.raises(InputError, match="expected an exact"):
        decide_h_conditions(h)


def test_float_nu_refused():
    with pytest.raises(InputError):
        decide_h_conditions((t + 1) ** -1, nu=1.5)


def test_non_positive_symbol_refused():
    with pytest.raises(InputError, match="positive"):
        decide_h_conditions((t + 1) ** -sympy.Symbol("b"))


def test_nu_1_sqrt_holds_with_exact_L():
    res = decide_h_conditions((t + 1) ** R(-1, 2), nu=1)
    assert statuses(res) == [Status.EXACT] * 4
    assert res[1].value == R(1, 2)          # sup |ḣ|/h = 1/(2(t+1)) at t = 0
    assert res[2].value is sympy.oo


def test_nu_3_sqrt_fails_11():
    res = decide_h_conditions((t + 1) ** R(-1, 2), nu=3)
    assert res[2].status is Status.FAILED and res[2].value == 2
    assert res[-1].status is Status.FAILED


def test_exp_nu_1():
    res = decide_h_conditions(sympy.exp(-t), nu=1)
    assert res[1].status is Status.EXACT and res[1].value == 1
    assert res[2].status is Status.FAILED and res[2].value == 1


def test_10_fails_for_gaussian():
    # h = exp(-t²), ν = 1: |ḣ|/h = 2t → ∞, so no L
    res = decide_h_conditions(sympy.exp(-t**2), nu=1)
    assert res[1].status is Status.FAILED and "→ ∞" in res[1].detail


def test_theorem2_mu_3():
    res = decide_h_conditions((t + 1) ** R(-1, 2), mu=3)
    assert all(r.status is Status.EXACT for r in res)
    assert res[1].name.startswith("(15)")
    assert res[-1].value["nu"] == sympy.Interval(1, 2)


def test_theorem2_mu_3_given_nu():
    res = decide_h_conditions((t + 1) ** R(-1, 2), nu=1, mu=3)
    assert statuses(res) == [Status.EXACT] * 4 and res[1].value == R(1, 2)


def test_mu_must_exceed_1():
    with pytest.raises(InputError):
        decide_h_conditions((t + 1) ** -1, mu=1)


def test_budget_undecided():
    res = decide_h_conditions((t + 1) ** (-beta), budget=1e-9)
    assert res and all(r.status is Status.UNDECIDED for r in res)


# -- wired into the catalogue item aleksandrov2017.theorem1 ------------------------------------------


def _theorem1_run(values):
    from lkverify.catalogue.loader import find_items

    (th,) = find_items("aleksandrov2017.theorem1")
    rep = th.run(values, budget=60)
    return rep, {r.name: r for r in rep.results}


@pytest.mark.slow  # about 25 s on a loaded machine; a fast-decaying h is refuted by default
def test_theorem1_decides_the_conditions_on_h_at_the_papers_h():
    rep, res = _theorem1_run({})
    assert res["(5), (10), (11) on h"].status is Status.EXACT
    assert "conditions (10), (11) on h" not in rep.verdict


def test_theorem1_refutes_the_conditions_for_a_fast_decaying_h_and_still_proves_the_identity():
    from lkverify.declare.parse import parse_value

    h = parse_value("(1+t)**(-6/5)", name="h", variables={"t": t})
    rep, res = _theorem1_run({"h": h})
    cond = res["(5), (10), (11) on h"]
    assert cond.status is Status.FAILED and "no ν ≥ 1 works" in cond.detail and "= 5 < ∞" in cond.detail
    assert res["Vdot_printed"].status is Status.EXACT and "proved for every value of the parameters, hence for h = " in res["Vdot_printed"].detail
    assert rep.verdict.startswith("failed: hypotheses")


@pytest.mark.slow  # about 15 s on a loaded machine
def test_theorem1_with_a_slower_h_and_its_nu():
    from lkverify.declare.parse import parse_value

    h = parse_value("(1+t)**(-1/2)", name="h", variables={"t": t})
    _, res = _theorem1_run({"h": h, "nu": sympy.Integer(2)})
    assert res["(5), (10), (11) on h"].status is Status.EXACT
    _, res = _theorem1_run({"h": h, "nu": sympy.Integer(3)})  # ∫(1+t)^{−3/2} = 2 < ∞
    assert res["(5), (10), (11) on h"].status is Status.FAILED


def test_corollary1_item_derives_beta_le_1_and_section6():
    from lkverify.catalogue.loader import find_items

    (item,) = find_items("aleksandrov2017.corollary1")
    rep = item.run({}, budget=60)
    res = {r.name: r for r in rep.results}
    assert res["Corollary 1: (10), (11) for h = (t+1)^(−β) ⇔ (14) β ≤ 1"].status is Status.EXACT
    assert res["section 6: β = 7/8"].status is Status.EXACT and "hold for β = 7/8" in res["section 6: β = 7/8"].detail
    assert res["section 6: β = 8/7"].status is Status.EXACT and "no ν ≥ 1 works" in res["section 6: β = 8/7"].detail
    assert rep.holds


def test_corollary1_comparison_refutes_a_wrong_printed_condition(monkeypatch):
    """Were the derived condition different from (14), the item must say so (failed)."""
    from lkverify.proofs.aleksandrov2017 import conditions_h

    real = conditions_h.decide_h_conditions

    def wrong(h, **kw):
        out = real(h, **kw)
        last = out[-1]
        if kw.get("nu") is None and isinstance(last.value, dict) and "condition" in last.value:
            beta = sympy.Symbol("beta", positive=True)
            out[-1] = type(last)(last.kind, last.name, last.status, {**last.value, "condition": beta <= 2}, last.detail)
        return out

    monkeypatch.setattr(conditions_h, "decide_h_conditions", wrong)
    res = {r.name: r for r in conditions_h._corollary1_check({}, budget=30)}
    assert res["Corollary 1: (10), (11) for h = (t+1)^(−β) ⇔ (14) β ≤ 1"].status is Status.FAILED
