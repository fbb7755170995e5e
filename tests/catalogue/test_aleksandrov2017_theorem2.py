"""Theorem 2 of paper 001 (nonlinear damping, instance W = (ωᵀDω)²): V̇ exact for every h, mutations refuted,
conditions (5), (15), (11) decided for the run's h."""

import dataclasses

import pytest

from lkverify import Status, Term
from lkverify.proofs.aleksandrov2017.theorem2 import derivation2, theorem2


def _check(terms):
    return dataclasses.replace(derivation2, terms=tuple(terms)).check({}, values={}, budget=120)


def test_vdot_is_exact_for_every_h():
    assert derivation2.check({}, values={}, budget=120).status is Status.EXACT


@pytest.mark.slow  # 40 s: a refuted claim is explained term by term
def test_a_dropped_term_or_a_flipped_sign_is_refuted():
    dropped = [x for x in derivation2.terms if x.text != "−γh^ν‖η‖^{σ+1}"]
    assert _check(dropped).status is Status.FAILED
    flipped = [Term(-x.expr, text=x.text) if x.text == "γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη" else x for x in derivation2.terms]
    assert _check(flipped).status is Status.FAILED


@pytest.mark.slow  # 23 s: two runs of the item
def test_conditions_on_h_follow_corollary2():
    by = {r.name: r for r in theorem2.run({}).results}
    assert by["(5), (15), (11) on h"].status is Status.EXACT            # β = 7/8 ≤ 1
    bad = {r.name: r for r in theorem2.run({"h": "(1+t)**(-8/7)"}).results}
    assert bad["(5), (15), (11) on h"].status is Status.FAILED           # β = 8/7 > 1: (11) fails
