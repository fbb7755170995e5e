"""Remark 2 of paper 001: the energy inequality, its constants and the certified lower bound on the limit
energy for β > 1; mutated claims refuted."""

import dataclasses
import math

import pytest
import sympy

from lkverify import Status, Term, dot, t
from lkverify.proofs.aleksandrov2017.equations import D, P, h, omega
from lkverify.proofs.aleksandrov2017.remark2 import energy_rate, remark2, remark2_constants


def test_constants_at_the_section6_data():
    assert remark2_constants(P.resolve({}, use_defaults=True)) == {
        "alpha1": sympy.Rational(1, 2), "alpha2": 3, "alpha3": 4}


@pytest.mark.slow
def test_energy_rate_is_exact_for_every_h_and_a_wrong_factor_is_refuted():
    assert energy_rate.check({}, values={}, budget=120).status is Status.EXACT
    wrong = dataclasses.replace(energy_rate, terms=(Term(-h(t) * dot(omega(t), D * omega(t)), text="−hωᵀDω"),))
    assert wrong.check({}, values={}, budget=120).status is Status.FAILED


def test_the_report_certifies_the_limit_energy_bound_and_compares_it_with_the_simulation():
    rep = remark2.run({})
    by = {r.name: r for r in rep.results}
    ct = by["c_tilde (h = (t + 1)**(-8/7))"]
    assert ct.status is Status.EXACT and math.isclose(ct.value["value"], math.exp(-28), rel_tol=1e-12)
    lower = by["limit energy lower bound (section 6, β = 8/7)"]
    sim = by["simulated limit energy (section 6, β = 8/7)"]
    assert lower.status is Status.CERTIFIED and sim.status is Status.SIMULATED
    assert sim.value["energy_end"] > sim.value["extrapolated_limit"] > lower.value["value"] > 0
    assert by["c_tilde (h = (t + 1)**(-7/8))"].value == {"tail": "oo"}   # β < 1: no bound, attraction
    assert all(r.status.is_proof for r in rep.results if r.kind == "bound")


@pytest.mark.slow
def test_another_integrable_damping_gets_its_own_constant():
    rep = remark2.run({"h": "(1+t)**(-2)"})
    r = next(r for r in rep.results if r.name == "c_tilde (h = (t + 1)**(-2))")
    assert math.isclose(r.value["value"], math.exp(-4), rel_tol=1e-12)    # α̃3 ∫_0^∞ (1+t)^{-2} = 4
