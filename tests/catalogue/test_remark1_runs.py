"""Remark 1 of paper 000 simulated (issue 24 item 5): the finding is computed from the runs' classes."""

import pytest

from lkverify.proofs.aleksandrov2026 import P, remark1
from lkverify.proofs.aleksandrov2026.remark1_runs import _finding, _finding_text, simulated_advice
from lkverify.status import Status

SCALES = ("1/4", "1", "4")


def test_the_check_states_what_the_runs_show_at_tau_2_5_10():
    """The issue measured: from the section 5 data, α × 1/4 converges at τ = 2, 5, 10, α × 1 and × 4 do not."""
    report = remark1.run()
    rows = {r.name: r for r in report.results}
    finding = rows["Remark 1: increasing α1, α2 at large delays (simulated)"]
    assert finding.status is Status.SIMULATED
    assert finding.value["contradicted_at"] == ["2", "5", "10"]
    assert finding.value["supported_at"] == []
    assert "contradict" in finding.detail and "τ = 2, 5, 10" in finding.detail
    for tau in ("2", "5", "10"):
        row = rows[f"Remark 1 runs at tau = {tau}"]
        assert row.value["classes"] == {"1/4": "converged", "1": "bounded", "4": "bounded"}
        big = [r for r in row.value["runs"] if r["scale"] != "1/4"]
        assert all(r["tail_min"] > 0.1 for r in big)          # far from the equilibrium, not slow convergence
    assert report.holds


@pytest.mark.parametrize("classes, contra, support", [
    ({"1/4": "converged", "1": "bounded", "4": "bounded"}, ["2"], []),
    ({"1/4": "bounded", "1": "converged", "4": "converged"}, [], ["2"]),      # larger α helps: supported
    ({"1/4": "converged", "1": "converged", "4": "converged"}, [], []),       # every factor alike
    ({"1/4": "bounded", "1": "bounded", "4": "bounded"}, [], []),
    ({"1/4": "bounded", "1": "converged", "4": "bounded"}, ["2"], ["2"]),     # both directions seen
])
def test_the_finding_follows_the_classes(classes, contra, support):
    c, s, o = _finding({"2": classes}, SCALES)
    assert (c, s, o) == (contra, support, [])
    text = _finding_text({"2": classes}, SCALES, c, s, o)
    assert ("runs contradict" in text) == bool(contra)
    assert ("support it" in text) == bool(support)


def test_a_run_that_did_not_end_normally_gives_no_conclusion_at_its_delay():
    by_tau = {"2": {"1/4": "converged", "1": "undecided", "4": "bounded"},
              "5": {"1/4": "converged", "1": "bounded", "4": "bounded"}}
    c, s, o = _finding(by_tau, SCALES)
    assert (c, s, o) == (["5"], [], ["2"])
    assert "no conclusion at τ = 2" in _finding_text(by_tau, SCALES, c, s, o)


def test_the_scales_are_ordered_as_numbers_not_as_strings():
    """'10' < '4' as strings: a converging α × 4 and a non-converging α × 10 contradict the advice."""
    c, s, _ = _finding({"2": {"10": "bounded", "4": "converged"}}, ("10", "4"))
    assert (c, s) == (["2"], [])


def test_the_runs_follow_the_given_gains():
    """The factors scale the given α1, α2: base 4 × 1/16, 1/4 are α = 1/4, 1 again (computed, not copied)."""
    v = P.resolve({"alpha1": "4", "alpha2": "4"}, use_defaults=True)
    rows = simulated_advice(v, taus=("2",), scales=("1/16", "1/4"))
    assert rows[0].value["classes"] == {"1/16": "converged", "1/4": "bounded"}   # α = 1/4 and α = 1 again
