"""Paper 001 Theorem 2: the estimates (16) as bound steps (proofs/aleksandrov2017/theorem2_chain.py).

The chain at the section 6 gains with h = (1+t)^{−7/8} (choices by find_choices), L and U compared
with closed forms computed here, and mutations: a flipped sign, a dropped term, a wrong constant, a
region that does not bound ‖s2 − r2‖, an h that fails (11).  V̇ ≤ W is not encoded yet (LEFT), so the
verdict names it; the power conclusion (lam = λ = 2) is tested in tests/certify/test_timevarying.py.
"""

import pytest
import sympy

from lkverify.certify.steps.measures import Region
from lkverify.certify.steps.rules import Context
from lkverify.proofs.aleksandrov2017 import theorem2_chain as chain
from lkverify.proofs.aleksandrov2017.equations import P
from lkverify.proofs.aleksandrov2017.theorem2 import theorem2
from lkverify.status import Status

R = sympy.Rational


@pytest.fixture(scope="module")
def chosen():
    return chain.find_choices(P.resolve({}, use_defaults=True))


@pytest.fixture(scope="module")
def values(chosen):
    return P.resolve(chosen, use_defaults=True)


@pytest.fixture(scope="module")
def checked(values):
    return {s.role: (s, s.check(values, budget=60)) for s in chain.steps}


def test_choices_are_exact(chosen):
    assert chosen == {"gamma": "833/10000", "delta1": "1/2", "delta_w": "1/2"}  # γ ≈ ½·min(4/12, 1/6), rounded down


def test_estimates_16_proved_with_closed_form_coefficients(checked, values, chosen):
    g = R(chosen["gamma"])
    w, e1, e2, hh = chain.w, chain.e1, chain.e2, chain.hh
    sub = {chain.j_min: 4, chain.j_max: 6, sympy.Symbol("nu", positive=True): 1}
    for role, sign, jj in (("lower", -1, 4), ("upper", 1, 6)):
        step, res = checked[role]
        assert res.status is Status.EXACT, res.detail
        # ½ωᵀJω, (a_i/2)e_i², ±γh‖J‖(a1+a2)²δ1²·Σa_i(w² + e_i²)/2 with ‖J‖ = 6, a_i = 1, δ1 = 1/2
        want = R(jj, 2) * w**2 + (e1**2 + e2**2) / 2 + sign * 6 * g * hh * (2 * w**2 + e1**2 + e2**2) / 2
        got = step.rhs.xreplace(P.substitution(values)).xreplace(sub)
        got = got.subs({chain.gamma: g, chain.delta1: R(1, 2), chain.a1: 1, chain.a2: 1})
        assert sympy.expand(got - want) == 0


def test_the_eta_bound_is_the_norm_tree_and_the_region(values):
    step = chain.steps[0]
    ctx = Context(step.system, values, {m.name: m for m in chain.MEASURES}, chain.REGION)
    ok = chain.eta_on_region(ctx)
    assert ok.status is Status.EXACT and ok.text.endswith("≤ 1"), ok.text  # (a1 + a2)δ1 = 2·1/2
    bad = Context(step.system, values, {m.name: m for m in chain.MEASURES}, Region({chain.E1: R(1, 2)}))
    assert chain.eta_on_region(bad).status is Status.UNDECIDED


def test_flipped_sign_not_proved(values):
    step = chain.steps[1]
    last = step.bounds[-1]
    flipped = step.with_bounds(bounds=[type(last)(last.terms, -last.bound, last.rule)], part=last.terms,
                               rhs=-last.bound)
    res = flipped.check(values, search=False)
    assert res.status is Status.UNDECIDED and "the stated bound is not the rule's" in res.terms[0].detail


def test_a_dropped_term_leaves_the_cross_term_uncovered(values):
    step = chain.steps[0]
    res = step.with_bounds(bounds=step.bounds[:-1]).check(values, search=False)
    assert res.status is Status.UNDECIDED and "lhs terms without a bound: γh^ν‖η‖^{σ−1}ωᵀJη" in res.detail


def test_a_wrong_constant_is_not_the_rules_bound(values):
    step = chain.steps[1]
    last = step.bounds[-1]
    smaller = last.bound / 4  # (a1 + a2)² dropped
    res = step.with_bounds(bounds=[type(last)(last.terms, smaller, last.rule)], part=last.terms,
                           rhs=smaller).check(values, search=False)
    assert not res.status.is_proof


def test_the_conclusion_is_the_power_rate_and_11_is_decided():
    assert chain.CONCLUSION.lam == 2 and "V^λ" in chain.CONCLUSION.link
    (ok,) = chain.condition11(P.resolve({}, use_defaults=True))
    assert ok.status is Status.EXACT
    (bad,) = chain.condition11(P.resolve({"h": "(1+t)**(-8/7)"}, use_defaults=True))
    assert bad.status is Status.FAILED and "(11)" in bad.text


@pytest.mark.slow  # about 9 s: the V̇ identity
def test_the_verdict_names_vdot_and_set_h_fails_at_11():
    report = theorem2.run({}, budget=60)
    assert report.verdict.startswith("not established: missing: V̇ ≤ W on the region")
    assert "V ≥ L (bound step, term by term) (exact), V ≤ U (bound step, term by term) (exact)" in report.verdict
    report = theorem2.run({"h": "(1+t)**(-8/7)"}, budget=60)
    hyp = next(r for r in report.results if r.kind == "hypothesis")
    assert hyp.status is Status.FAILED and "(11)" in hyp.detail
    assert "failed" in report.verdict.split(";")[0], report.verdict
