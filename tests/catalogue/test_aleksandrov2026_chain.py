"""Theorem 1 of paper 000 from functional (9) to the conclusion: the chain proved at the section 5
gains, and refused where a choice, a stated bound or the lemma is wrong."""

import sympy
import pytest

from lkverify import Status
from lkverify.certify.steps.chain import TermBound
from lkverify.certify.steps.rules import Equal
from lkverify.proofs.aleksandrov2026.equations import P
from lkverify.proofs.aleksandrov2026.theorem1 import theorem1
from lkverify.proofs.aleksandrov2026.theorem1_chain import (CONCLUSION, _coefficient_functions, _largest_delta_at,
                                                            find_choices, optimal_choices, steps)
from lkverify.proofs.aleksandrov2026.theorem1_bound import d1, d2, mu


@pytest.fixture(scope="module")
def defaults():
    base = P.resolve({}, use_defaults=True)
    choices = optimal_choices(base)
    values = P.resolve(choices, use_defaults=True)
    checked = {s.role: (s, s.check(values, budget=120)) for s in steps}
    return choices, values, checked


def test_the_chain_is_proved_at_the_section5_gains(defaults):
    choices, values, checked = defaults
    assert all(res.status.is_proof for _, res in checked.values()), [res.detail for _, res in checked.values()]
    rows, status, detail = CONCLUSION.certify(checked, values)
    assert status is Status.CERTIFIED, detail
    # the optimised region (a geometric programme) is larger than the recipe's, and both are small
    assert sympy.Rational(find_choices(P.resolve({}, use_defaults=True))["delta"]) < sympy.Rational(choices["delta"])
    assert sympy.Rational(choices["delta"]) < sympy.Rational(1, 100) and choices["epsilon"] == "99/100"


def test_a_region_too_large_is_refused_with_the_monomial(defaults):
    choices, values, checked = defaults
    big = P.resolve({**choices, "delta": "1/100"}, use_defaults=True)
    vdot = steps[2]
    res = vdot.check(big, budget=60)
    assert res.status.is_proof                        # every rule still applies on the larger region …
    rows, status, detail = CONCLUSION.certify({**checked, "vdot": (vdot, res)}, big)
    assert status is Status.FAILED and "W has the monomial" in detail  # … but W is no longer negative


@pytest.mark.slow
def test_gamma_too_small_fails_the_lower_bound(defaults):
    choices, values, checked = defaults
    small = P.resolve({**choices, "gamma": "1"}, use_defaults=True)
    lower = steps[0]
    rows, status, detail = CONCLUSION.certify({**checked, "lower": (lower, lower.check(small, budget=60))}, small)
    assert status is Status.FAILED and "V ≥ φ fails" in detail and "w**2" in detail


@pytest.mark.slow
def test_epsilon_outside_0_1_fails_inequality_10(defaults):
    choices, values, checked = defaults
    bad = P.resolve({**choices, "epsilon": "1"}, use_defaults=True)
    res = steps[2].check(bad, budget=60)
    term = next(tr for tr in res.terms if "−f^ν LᵀD⁻¹L" in tr.statement)
    assert term.status is not Status.EXACT and term.status is not Status.CERTIFIED


@pytest.mark.slow
def test_a_flipped_sign_in_a_stated_bound_is_not_proved(defaults):
    choices, values, checked = defaults
    vdot = steps[2]
    flipped = [tb if tb.terms != ("−μW(t−τ)",) else TermBound("−μW(t−τ)", mu * (d1**2 + d2**2), Equal(mu * (d1**2 + d2**2)))
               for tb in vdot.bounds]
    res = vdot.with_bounds(bounds=flipped, witness_seconds=1).check(values, budget=None)
    assert not res.status.is_proof


def test_the_coefficient_model_agrees_with_the_proved_steps(defaults):
    choices, values, checked = defaults
    fns = _coefficient_functions(P.resolve({}, use_defaults=True), choices["epsilon"])
    names = ("gamma", "lam", "mu", "eta_w", "eta_K", "eta")
    x = [float(sympy.Rational(choices[n])) for n in names]
    assert _largest_delta_at(fns, x) >= float(sympy.Rational(choices["delta"]))


@pytest.mark.slow
@pytest.mark.parametrize("gains", [{}, {"tau": "3"}, {"alpha1": "2", "alpha2": "2"}])
def test_theorem1_is_established_and_the_printed_vdot_is_a_finding(gains):
    rep = theorem1.run(gains, budget=None)
    assert rep.verdict.startswith("established"), rep.verdict
    printed = next(r for r in rep.results if r.name == "Vdot_printed")
    assert printed.status is Status.FAILED and "transposition" in printed.detail
    assert "printed formulas (findings, not links of the chain): Vdot_printed failed" in rep.verdict
    assert "not yet checked" not in rep.verdict
