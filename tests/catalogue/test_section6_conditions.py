"""aleksandrov2023.section6: the statements of section 6 of paper 002 about Figs. 1–7.

(13) |b|τ < a and (14) bτ < a are recomputed here by hand (fractions.Fraction) from the
gains as the paper prints them, independently of the figure modules; mutated statements
(a flipped inequality, another figure's gains, the opposite behaviour) must fail, and
true statements written differently must be accepted.
"""

import doctest
import json
import subprocess
import sys
from fractions import Fraction

import pytest
import sympy

from lkverify import InputError
from lkverify.catalogue import find_items
from lkverify.status import Status

import lkverify.proofs.aleksandrov2023 as paper
from lkverify.proofs.aleksandrov2023.equations import a, b, mu, tau
from lkverify.proofs.aleksandrov2023.section6_conditions import (C13, C14, REMARK3, STATEMENTS, THEOREM3, Statement,
                                                                 condition_value, evaluate, figure_gains, section6)

# (h, a, b, τ, μ) as printed in section 6 (typed from the paper; Fig. 7 uses the gains of Fig. 6)
PRINTED = {
    1: ("0.7", "2", "2", "0.9", "1"),
    2: ("0.7", "2", "-2", "0.9", "1"),
    3: ("0.7", "2", "-2", "0.9", "2"),
    4: ("0.2", "0.6", "-0.6", "0.9", "1"),
    5: ("0.2", "0.6", "-0.6", "0.9", "2"),
    6: ("1", "0", "-1", "1", "2"),
    7: ("1", "0", "-1", "1", "2"),
}


def hand(n):
    h, a_, b_, tau_, mu_ = map(Fraction, PRINTED[n])
    return {"h": h, "a": a_, "b": b_, "tau": tau_, "mu": mu_}


@pytest.mark.parametrize("n", sorted(PRINTED))
def test_figure_gains_are_the_printed_ones(n):
    g, ref = figure_gains(n), hand(n)
    for k in ("h", "a", "b", "tau", "mu"):
        assert g[k] == sympy.Rational(ref[k].numerator, ref[k].denominator), (n, k)


@pytest.mark.parametrize("n", sorted(PRINTED))
def test_13_and_14_against_a_hand_computation(n):
    g = hand(n)
    lhs13, lhs14 = abs(g["b"]) * g["tau"], g["b"] * g["tau"]
    v13, v14 = condition_value(C13, figure_gains(n)), condition_value(C14, figure_gains(n))
    (p13,), (p14,) = v13["parts"], v14["parts"]
    assert Fraction(p13["lhs"]) == lhs13 and Fraction(p13["rhs"]) == g["a"]
    assert Fraction(p13["margin"]) == g["a"] - lhs13 and v13["holds"] is (lhs13 < g["a"])
    assert Fraction(p14["lhs"]) == lhs14 and v14["holds"] is (lhs14 < g["a"])
    t3 = condition_value(THEOREM3, figure_gains(n))
    assert t3["holds"] is (g["mu"] > 1 and lhs14 < g["a"])


def test_hand_values_of_13():
    # Fig. 1/2/3: 2·0.9 = 1.8 < 2; Fig. 4/5: 0.6·0.9 = 0.54 < 0.6; Fig. 6/7: 1·1 = 1 < 0 is false
    expected = {1: ("9/5", "2", True), 4: ("27/50", "3/5", True), 5: ("27/50", "3/5", True), 6: ("1", "0", False),
                7: ("1", "0", False)}
    for n, (lhs, rhs, holds) in expected.items():
        v = condition_value(C13, figure_gains(n))
        assert (v["parts"][0]["lhs"], v["parts"][0]["rhs"], v["holds"]) == (lhs, rhs, holds), n


def test_decimal_strings_are_read_exactly_and_floats_refused():
    g = dict(zip(("h", "a", "b", "tau", "mu"), PRINTED[4]))
    v = condition_value(C13, g)
    assert v["holds"] is True and v["parts"][0]["margin"] == "3/50"
    with pytest.raises(InputError, match="never exact"):
        condition_value(C13, {**g, "a": 0.6})


def test_condition_statements_of_the_text():
    """Only Fig. 4's "(13) does not hold" disagrees with the exact evaluation."""
    rows = {st: evaluate(st) for st in STATEMENTS if st.condition is not None}
    failed = [st for st, r in rows.items() if r.status is Status.FAILED]
    assert [(st.figure, st.condition, st.says) for st in failed] == [(4, C13, False)]
    assert all(r.status is Status.EXACT for st, r in rows.items() if st not in failed)
    (row,) = [rows[st] for st in failed]
    assert row.value["holds"] is True and row.value["parts"][0]["margin"] == "3/50"
    assert "27/50 < 3/5 is true" in row.detail
    # every figure has (13) and Theorem 3's hypotheses evaluated
    for n in PRINTED:
        conds = {st.condition for st in STATEMENTS if st.figure == n and st.condition is not None}
        assert {C13, THEOREM3} <= conds, n


# -- mutations ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("st", [
    Statement(1, "(13) with the inequality flipped", condition=sympy.Abs(b) * tau > a),
    Statement(1, "(13) said to be violated", condition=C13, says=False),
    Statement(5, "(14) with the inequality flipped", condition=b * tau > a),
    Statement(3, "Theorem 3 with μ < 1", condition=sympy.And(mu < 1, C14)),
    Statement(6, "Fig. 1's '(13) holds' at the Fig. 6 gains", condition=C13, says=True),
    Statement(7, "Fig. 1's '(13) holds' at the Fig. 7 gains", condition=C13, says=True),
    Statement(2, "Fig. 3's 'agrees with Theorem 3' at the Fig. 2 gains (μ = 1)", condition=THEOREM3, says=True),
    Statement(4, "Fig. 5's 'Theorem 3 applies' at the Fig. 4 gains", condition=THEOREM3, says=True),
    Statement(4, "Remark 3's a = 0, b < 0 at the Fig. 4 gains", condition=REMARK3, says=True),
], ids=lambda st: st.quote)
def test_mutated_conditions_fail(st):
    assert evaluate(st).status is Status.FAILED


@pytest.mark.parametrize("st", [
    Statement(2, "Fig. 2 converges", behaviour="converges"),
    pytest.param(Statement(6, "Fig. 6 does not converge", behaviour="does not converge"), marks=pytest.mark.slow),
    pytest.param(Statement(3, "Fig. 3 does not converge", behaviour="does not converge"), marks=pytest.mark.slow),
    Statement(1, "Fig. 1 does not converge", behaviour="does not converge"),
], ids=lambda st: st.quote)
def test_mutated_behaviour_fails(st):
    assert evaluate(st).status is Status.FAILED


@pytest.mark.parametrize("st, status", [
    (Statement(4, "a − τ|b| > 0", condition=a - tau * sympy.Abs(b) > 0, says=True), Status.EXACT),
    (Statement(1, "|b| < a/τ", condition=sympy.Abs(b) < a / tau, says=True), Status.EXACT),
    (Statement(5, "not (14) is false", condition=sympy.Not(C14), says=False), Status.EXACT),
    (Statement(6, "μ ≥ 2 and bτ − a < 0", condition=sympy.And(mu >= 2, b * tau - a < 0)), Status.EXACT),
    (Statement(7, "(13) fails at the Fig. 7 gains", condition=C13, says=False), Status.EXACT),
    (Statement(6, "μ − 1 > 0", condition=mu - 1 > 0), Status.EXACT),
    (Statement(4, "Fig. 4 keeps oscillating", behaviour="does not converge"), Status.SIMULATED),
    pytest.param(Statement(5, "the axis of Fig. 5 is stabilised", behaviour="converges"), Status.SIMULATED,
                 marks=pytest.mark.slow),
], ids=lambda x: getattr(x, "quote", str(x)))
def test_true_statements_written_differently_are_accepted(st, status):
    assert evaluate(st).status is status


@pytest.mark.parametrize("kw, match", [
    ({"figure": 8, "condition": C13}, "figure"),
    ({"figure": 1, "condition": C13, "behaviour": "converges"}, "exactly one"),
    ({"figure": 1}, "exactly one"),
    ({"figure": 1, "condition": sympy.Symbol("h") < a}, "free symbols"),
    ({"figure": 1, "behaviour": "stable"}, "behaviour"),
    ({"figure": 6, "behaviour": "envelope"}, "no envelope"),
    ({"figure": 6, "behaviour": "chi"}, "Fig. 7 data only"),
])
def test_bad_statements_are_refused(kw, match):
    with pytest.raises(InputError, match=match):
        Statement(quote="bad", **kw)


# -- the item ----------------------------------------------------------------------------------------

@pytest.mark.slow
def test_item_registered_and_rows():
    (item,) = find_items("aleksandrov2023.section6")
    assert item is section6 is paper.section6 and "section6" in paper.__all__
    rep = item.run()
    assert len(rep.results) == len(STATEMENTS) and len({r.name for r in rep.results}) == len(STATEMENTS)
    by = {}
    for st, r in zip(STATEMENTS, rep.results):
        assert r.name.startswith(f"Fig. {st.figure}: ")
        by.setdefault(r.status, []).append(st)
    assert {(st.figure, st.behaviour or "condition") for st in by[Status.FAILED]} == {
        (4, "condition"), (4, "sensitive"), (7, "chi")}
    assert [(st.figure, st.t_end) for st in by[Status.UNDECIDED]] == [(4, 10000.0)]
    assert all(st.behaviour for st in by[Status.SIMULATED])
    assert all(st.condition is not None for st in by[Status.EXACT])
    assert rep.verdict.startswith("failed:") and rep.exit_code == 1
    json.dumps(rep.to_json())


def test_module_doctests():
    import lkverify.proofs.aleksandrov2023.section6_conditions as mod
    assert doctest.testmod(mod).failed == 0


def test_data_module_still_importable():
    from lkverify.proofs.aleksandrov2023.section6 import PRINTED_15, R_TARGET  # the data of the figures
    assert PRINTED_15["d1"] == 9.21 and R_TARGET.shape == (3,)


@pytest.mark.slow
def test_fig4_on_a_100_times_longer_interval():
    (st,) = [st for st in STATEMENTS if st.t_end is not None]
    row = evaluate(st, long=True)
    assert row.status is Status.SIMULATED and row.value["t_end"] == 10000.0


@pytest.mark.slow
def test_cli_json():
    out = subprocess.run([sys.executable, "-m", "lkverify", "check", "aleksandrov2023.section6", "--json"],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 1, out.stderr
    obj = json.loads(out.stdout)
    assert obj["item"] == "aleksandrov2023.section6" and len(obj["results"]) == len(STATEMENTS)
