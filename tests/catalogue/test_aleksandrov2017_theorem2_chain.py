"""Paper 001 Theorem 2 checked to its conclusion (proofs/aleksandrov2017/theorem2_chain.py).

The chain at the section 6 gains with h = (1+t)^{−7/8} (choices by find_choices): (16), V̇ ≤ W over the
seven terms of the exact V̇, V̇ ≤ −α8 h^ν V^λ (λ = 2) and the algebraic envelope; L and U compared with
closed forms computed here, and mutations: a wrong α8, a dropped term, a flipped sign, a region too large,
a dropped Lemma 1 term in W, an h that fails (11).  The power conclusion itself: tests/certify/test_timevarying.py.
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


def _rate(checked, values, **over):
    return chain.CONCLUSION.certify(checked, {**values, **{k: sympy.sympify(v) for k, v in over.items()}})


def test_choices_are_exact_and_positive(chosen):
    assert set(chosen) == {"gamma", "eps", "delta1", "delta_w", "eta_w", "eta_h2", "alpha8"}
    assert all(R(v) > 0 for v in chosen.values()) and chosen["eps"] == chosen["delta1"] == chosen["delta_w"] == "1/2"


def test_estimates_16_proved_with_closed_form_coefficients(checked, values, chosen):
    g = R(chosen["gamma"])
    w, e1, e2, hh = chain.w, chain.e1, chain.e2, chain.hh
    sub = {chain.j_min: 4, chain.j_max: 6, sympy.Symbol("nu", positive=True): 1}
    for role, sign, jj in (("lower", -1, 4), ("upper", 1, 6)):
        step, res = checked[role]
        assert res.status is Status.EXACT, res.detail
        # ½ωᵀJω, (a_i/2)e_i², ±γh‖J‖(a1+a2)²δ1²·Σa_i(w² + e_i²)/2 with ‖J‖ = 6, a_i = 1, δ1 = 1/2
        want = R(jj, 2) * w**2 + (e1**2 + e2**2) / 2 + sign * 6 * g * hh * (2 * w**2 + e1**2 + e2**2) / 2
        got = step.rhs.xreplace(sub).subs({chain.gamma: g, chain.delta1: R(1, 2), chain.a1: 1, chain.a2: 1})
        assert sympy.expand(got - want) == 0


def test_vdot_bound_proved_term_by_term(checked):
    res = checked["vdot"][1]
    assert res.status is Status.CERTIFIED, res.detail  # Lemma 1 certified on the region, every other rule exact
    assert len(res.terms) == 7 and sum(tr.status is Status.EXACT for tr in res.terms) == 6
    fifteen = next(tr for tr in res.terms if tr.terms == ("γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη",))
    assert "L = 7/8" in str([a.to_json() for a in fifteen.applications])  # (15): sup |ḣ|/h = 7/8


def test_conclusion_certified_with_its_constants(checked, values, chosen):
    rows, status, detail = _rate(checked, values)
    assert status is Status.CERTIFIED, detail  # certified: the V̇ step's Lemma 1
    v = rows[0].value
    g = R(chosen["gamma"])
    assert v["H"] == "1" and v["lam"] == "2"
    assert v["alpha1"] == pytest.approx(float(min(2 - 6 * g, R(1, 2) - 3 * g)), rel=1e-12)
    assert v["alpha2"] == pytest.approx(float(max(3 + 6 * g, R(1, 2) + 3 * g)), rel=1e-12)
    assert v["delta2"] == pytest.approx(0.5 * (v["alpha1"] / v["alpha2"]) ** 0.5, rel=1e-12)
    assert float(R(chosen["alpha8"])) <= v["alpha_largest"]
    assert rows[1].kind == "envelope" and "∫_(t0)^t h^1)^(−1/(2−1))" in rows[1].detail


def test_wrong_alpha8_refuted_at_a_monomial(checked, values):
    too_big = sympy.nsimplify(_rate(checked, values)[0][0].value["alpha_largest"]) * R(11, 10)
    status, detail = _rate(checked, values, alpha8=too_big)[1:]
    assert status is Status.FAILED and detail.startswith("fails at the monomial")


def test_a_smaller_alpha8_written_differently_passes(checked, values, chosen):
    half = R(chosen["alpha8"]) / 2
    assert _rate(checked, values, alpha8=sympy.sqrt(half**2))[1] is Status.CERTIFIED


@pytest.mark.slow
def test_dropped_lemma_term_in_w_refuted_by_the_conclusion(checked, values):
    step, res = checked["vdot"]
    lemma = next(tb for tb in step.bounds if tb.terms == ("−γh^ν‖η‖^{σ+1}",))
    weaker = step.with_bounds(bounds=[tb if tb is not lemma else type(tb)(tb.terms, sympy.S.Zero, tb.rule)
                                      for tb in step.bounds], rhs=step.rhs - lemma.bound)
    res2 = weaker.check(values, search=False)
    status, detail = chain.CONCLUSION.certify({**checked, "vdot": (weaker, res2)}, values)[1:]
    assert status is Status.FAILED and "e1**4" in detail


@pytest.mark.slow
def test_a_region_too_large_fails_lemma1(values):
    res = chain.steps[2].check({**values, "delta1": R(2)}, search=False)
    bad = [tr for tr in res.terms if not tr.status.is_proof]
    assert not res.status.is_proof and [tr.terms for tr in bad] == [("−γh^ν‖η‖^{σ+1}",)]
    assert "the region allows σ = sin(φ/2) up to" in bad[0].detail  # Lemma 1 needs σ < 1


def test_a_dropped_vdot_bound_leaves_a_term_uncovered(values):
    step = chain.steps[2]
    res = step.with_bounds(bounds=step.bounds[:-1]).check(values, search=False)
    assert res.status is Status.UNDECIDED and "lhs terms without a bound: −γh^ν‖η‖^{σ−1}ωᵀJM" in res.detail


def test_flipped_sign_in_vdot_not_proved(values):
    step = chain.steps[2]
    last = step.bounds[-1]
    res = step.with_bounds(bounds=[type(last)(last.terms, -last.bound, last.rule)], part=last.terms,
                           rhs=-last.bound).check(values, search=False)
    assert not res.status.is_proof and "the stated bound is not the rule's" in res.terms[0].detail


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


@pytest.mark.slow  # about 12 s: the V̇ identity and the chain, twice
def test_established_and_set_h_fails_at_11():
    report = theorem2.run({}, budget=None)
    assert report.verdict.startswith("established"), report.verdict
    report = theorem2.run({"h": "(1+t)**(-8/7)"}, budget=None)
    hyp = next(r for r in report.results if r.kind == "hypothesis")
    assert hyp.status is Status.FAILED and "(11)" in hyp.detail
    assert "failed" in report.verdict.split(";")[0], report.verdict


@pytest.mark.slow  # about 15 s: the chain, a 400 s run and the sampled comparison
def test_proved_envelope_holds_along_a_run_inside_delta2():
    report, data = theorem2.run_constants({}, budget=None)
    row = report.results[-1]
    assert row.status is Status.SIMULATED and row.value["largest_ratio"] <= 1 + 1e-9
    assert row.value["x0"] < row.value["delta2"]
    # the proved α8 is below the sampled one at the same γ, δ2 (the estimate is an upper estimate)
    assert row.value["alpha8"] <= row.value["alpha8_estimated_for_comparison"]
    assert "for comparison only" in row.detail and "(not proved)" in row.detail


def test_product_rule_refuses_a_wrong_factor_and_proves_the_same_bound_written_differently(values):
    import dataclasses

    step = chain.steps[2]
    tb = next(b for b in step.bounds if b.terms == ("−γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)",))
    half = dataclasses.replace(tb.rule, factor=tb.rule.factor / 2)  # −γh^ν(ηᵀM)(ωᵀJη): not the term
    res = step.with_bounds(bounds=[type(tb)(tb.terms, tb.bound / 2, half, then=tb.then)], part=tb.terms,
                           rhs=tb.bound / 2).check(values, search=False)
    assert not res.status.is_proof and "the term is" in res.terms[0].detail
    swapped = dataclasses.replace(tb.rule, first=tb.rule.second, second=tb.rule.first)  # the factors swapped
    res = step.with_bounds(bounds=[type(tb)(tb.terms, tb.bound, swapped, then=tb.then)], part=tb.terms,
                           rhs=tb.bound).check(values, search=False)
    assert res.status is Status.EXACT, res.detail
