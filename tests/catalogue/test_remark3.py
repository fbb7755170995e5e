"""Remark 3 of paper 000: β ≤ 0 with G = a g I; Assumption 2 ⇔ β + a∫g > 0, the exact threshold a*."""

import sympy
import pytest

from lkverify import InputError, Status, zeta
from lkverify.proofs.aleksandrov2026 import remark3
from lkverify.proofs.aleksandrov2026.remark3 import threshold


def _by_name(report):
    return {r.name: r for r in report.results}


def test_default_kernel_gives_the_threshold_two():
    rep = remark3.run({})
    rows = _by_name(rep)
    assert rep.exit_code == 0
    star = rows["a* (Assumption 2 holds iff a > a*)"]
    assert star.status is Status.EXACT and star.value["exact"] == "2"      # −(−1) / ∫e^{−2ζ} = 1/(1/2)
    assert rows["(a), (b) Assumption 1 for G = a g I"].value == sympy.Rational(1, 2)


@pytest.mark.parametrize("a, ok", [("3", True), ("2", False), ("19/10", False), ("2001/1000", True)])
def test_a_is_decided_against_the_threshold_exactly(a, ok):
    rows = _by_name(remark3.run({"a": a}))
    row = rows[f"Assumption 2 at a = {sympy.Rational(a)}"]
    assert row.status is (Status.EXACT if ok else Status.FAILED)


def test_threshold_scales_with_beta_and_the_kernel_written_differently():
    # the same kernel written as exp(−ζ)·exp(−ζ): the same a*
    assert threshold(-3, sympy.exp(-2 * zeta)) == 6
    rows = _by_name(remark3.run({"beta": "-3", "g": "exp(-zeta)*exp(-zeta)"}))
    assert rows["a* (Assumption 2 holds iff a > a*)"].value["exact"] == "6"


def test_a_kernel_with_negative_integral_admits_no_a():
    rep = remark3.run({"g": "exp(-zeta)*(1-2*zeta)"})
    rows = _by_name(rep)
    assert rows["(c) ∫_0^∞ g > 0"].status is Status.FAILED
    assert "a* (Assumption 2 holds iff a > a*)" not in rows
    assert rep.exit_code == 1


def test_a_slowly_decaying_kernel_fails_assumption1():
    rows = _by_name(remark3.run({"g": "1/(1+zeta)**3", "a": "3"}))
    assert rows["(a), (b) Assumption 1 for G = a g I"].status is Status.FAILED
    assert rows["Assumption 2 at a = 3"].status is Status.EXACT


def test_positive_beta_is_outside_the_remark():
    with pytest.raises(InputError, match="β ≤ 0"):
        remark3.run({"beta": "1/10"})
