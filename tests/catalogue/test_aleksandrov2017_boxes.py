"""Paper 001 Theorem 2 over boxes of parameters (issue 23): a1, a2 intervals, and what the exponent μ = σ allows.

The Lemma 6 certificate (:func:`lkverify.proofs.aleksandrov2017.theorem1_chain.lemma6`) takes the boxed
ε, a1, a2 into its box, so V̇ ≤ W closes over a box; :func:`...theorem2_chain.find_choices` picks the
choices at the box's worst ends.  μ = σ = 3 is fixed in the system and the chain (not a parameter): the
V̇ identity is exact for every μ = σ (slow test), the other links per exponent (μ = σ = 3 here; 5 and 7 in
tests/catalogue/test_aleksandrov2017_theorem2_exponents.py).
"""

import pytest

from lkverify import InputError, Status
from lkverify.catalogue.boxrun import BoxStatus
from lkverify.proofs.aleksandrov2017.theorem2 import theorem2

SMALL = {"a1": ("19/20", "21/20")}


def test_a_small_box_of_a1_is_established_in_one_piece():
    """≈ 10 s: the measured failure of issue 23 (Lemma 6 at a point) closes with the certificate over the box."""
    rep = theorem2.run({}, box=SMALL, max_boxes=1)
    assert rep.status is BoxStatus.ESTABLISHED, rep.as_text()
    by = {r.name: r for r in rep.pieces[0].report.results}
    assert by["V̇ ≤ W"].status is Status.CERTIFIED
    lemma = next(r for n, r in by.items() if n.startswith("V̇ ≤ W: −γh^ν‖η‖^{σ+1}"))
    assert lemma.status is Status.CERTIFIED and "certified lemma" in lemma.detail
    assert rep.pieces[0].choices  # picked for the whole box (find_choices(values, box=...))


def test_a_box_of_eps_reaching_1_is_not_established():
    """ε ∈ [1/2, 99/100] on δ1 = 1/2: Lemma 1's F ≥ 0 is not certified on the whole box (near ε = 1 it needs
    σ ≲ √(1 − ε)), so the ‖η‖^{σ+1} bound is undecided: never established."""
    rep = theorem2.run({}, box={"eps": ("1/2", "99/100")}, max_boxes=1)
    assert rep.status is not BoxStatus.ESTABLISHED
    assert "‖η‖^{σ+1}" in rep.verdict


def test_a_wrong_rate_is_not_established():
    """α8 = 1/1000 (five orders above what the chain allows) over the small box: the conclusion is refuted."""
    rep = theorem2.run({"alpha8": "1/1000"}, box=SMALL, max_boxes=1)
    assert rep.status is not BoxStatus.ESTABLISHED
    assert "refuted" in rep.verdict


def test_a_box_where_a_hypothesis_fails_is_not_established():
    """h = (1+t)^(−8/7) (Corollary 2: β > 1, (11) fails) over the small box of a1: not established."""
    rep = theorem2.run({"h": "(1+t)**(-8/7)"}, box=SMALL, max_boxes=1)
    assert rep.status is not BoxStatus.ESTABLISHED
    hyp = next(r for r in rep.pieces[0].report.results if r.name == "(5), (15), (11) on h")
    assert hyp.status is Status.FAILED


def test_a_box_of_nu_is_undecided_at_the_hypotheses():
    """(15), (11) depend on ν and are decided at points only (ConditionsOnH): a box of ν stays undecided."""
    rep = theorem2.run({}, box={"nu": ("1", "2")}, max_boxes=2)
    assert rep.status is BoxStatus.UNDECIDED
    assert "decided at points only" in rep.verdict


def test_the_exponent_is_not_a_parameter():
    """μ = σ = 3 is fixed in the catalogued system and chain: a box of μ is bad input, not a silent pass."""
    with pytest.raises(InputError, match="mu"):
        theorem2.run({}, box={"mu": ("2", "4")}, max_boxes=1)


@pytest.mark.slow  # ≈ 15 s (2 pieces) on an idle machine
def test_a1_over_two_decades_is_established():
    rep = theorem2.run({}, box={"a1": ("1/10", "10")}, max_boxes=8)
    assert rep.status is BoxStatus.ESTABLISHED, rep.as_text()


@pytest.mark.slow  # ≈ 10 s
def test_a1_and_a2_together_are_established():
    rep = theorem2.run({}, box={"a1": ("9/10", "11/10"), "a2": ("9/10", "11/10")}, max_boxes=1)
    assert rep.status is BoxStatus.ESTABLISHED, rep.as_text()


@pytest.mark.slow  # ≈ 60 s: exact in ≈ 11 s, then the mutation refuted
def test_vdot_is_exact_for_every_exponent_and_a_dropped_term_is_refuted():
    from lkverify import DerivativeClaim
    from lkverify.proofs.aleksandrov2017.theorem2_functional import derivation_every_exponent

    claim = derivation_every_exponent()
    assert claim.check({}, values={}, budget=None).status is Status.EXACT
    dropped = DerivativeClaim("dropped", claim.functional, claim.system,
                              [x for x in claim.terms if x.text != "−γh^ν‖η‖^{μ+1}"])
    assert dropped.check({}, values={}, budget=None).status is Status.FAILED
