"""Paper 001 Theorem 2 for other exponents μ = σ (proofs/aleksandrov2017/theorem2_exponents.py, issue 23).

The chain for W = (ωᵀDω)³ (μ = σ = 5, λ = 3) at the section 6 gains: the item established, the Young
exponents of the splits, and mutations that must not pass: a wrong Young exponent, a non-conjugate pair,
a dropped term, a flipped sign, a wrong rate, σ < μ (refuted at the conclusion), an even μ (refused).
μ = 7 and the catalogued μ = 3 rebuilt by the general builder: slow / cheap checks below.

σ > μ (μ = 3, σ = 5, at ν = 1 and ν = 9/8; μ = 5, σ = 7 slow): the damping's power raised on the region
(RaiseOnRegion, half of the term) and the ḣ-term split with (μ+1, (μ+1)/μ); mutations: a wrong δ_ω exponent,
the raise dropped (the rewrite, or the whole idea: then the conclusion fails at w⁶).
"""

import dataclasses

import pytest
import sympy

from lkverify import InputError, Status
from lkverify.certify.steps.rewrites import YoungEach
from lkverify.proofs.aleksandrov2017 import theorem2_chain as chain
from lkverify.proofs.aleksandrov2017.equations import P
from lkverify.proofs.aleksandrov2017.theorem2_exponents import theorem2_for, theorem2_mu5
from lkverify.proofs.aleksandrov2017.theorem2_functional import instance

R = sympy.Rational
HDOT = "γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη"
DAMP = "−(μ+1)hW"


@pytest.fixture(scope="module")
def values():
    return P.resolve(chain.find_choices(P.resolve({}, use_defaults=True), mu=5), use_defaults=True)


@pytest.fixture(scope="module")
def checked(values):
    return {s.role: (s, s.check(values, budget=120)) for s in theorem2_mu5.steps}


def _replace(step, text, **changes):
    """The V̇ step with the term bound of ``text`` changed (the rhs follows the stated bound)."""
    tb = next(b for b in step.bounds if b.terms == (text,))
    new = dataclasses.replace(tb, **changes)
    return step.with_bounds(bounds=[new if b is tb else b for b in step.bounds], rhs=step.rhs - tb.bound + new.bound)


def test_the_item_is_established_at_the_defaults():
    """≈ 8 s: hypotheses with μ = 5 in (15), the degree-6 identity, (16), V̇ ≤ W, the rate with λ = 3."""
    rep = theorem2_mu5.run({})
    assert rep.verdict.startswith("established"), rep.verdict
    by = {r.name: r for r in rep.results}
    assert by["Vdot_structured"].status is Status.EXACT
    assert "μ = 5" in by["(5), (15), (11) on h"].detail
    rate = by["V̇ ≤ −α8 h^ν V^λ"]
    assert rate.status is Status.CERTIFIED and rate.value["lam"] == "3"
    assert R(rate.value["alpha"]) <= rate.value["alpha_largest"]


def test_the_young_exponents_are_conjugate_and_reach_the_target_powers():
    """ḣ-term: (σ+1, (σ+1)/σ) then (σ/a, σ/(σ−a)); mixed terms: ((σ+1)/2, (σ+1)/(σ−1)) then ((σ−1)/a, …)."""
    first, second = chain.hdot_young(5)
    assert {p[2:4] for p in first.pairs} == {(6, R(6, 5))} and len(first.pairs) == 6
    assert sorted(p[2:4] for p in second.pairs) == sorted([(R(5, 4), 5), (R(5, 3), R(5, 2)), (R(5, 3), R(5, 2)),
                                                          (R(5, 4), 5)])
    mixed, mixed2 = chain.mixed_young(5)
    assert {p[2:4] for p in mixed.pairs} == {(3, R(3, 2))} and len(mixed.pairs) == 5
    assert sorted(p[2:4] for p in mixed2.pairs) == [(R(4, 3), 4), (R(4, 3), 4), (2, 2)]
    for x, y, p, q, _ in (*second.pairs, *mixed2.pairs):
        # each factor to its power is h^ν e_i^{σ+1} (ν = 1 here)
        for f, k in ((x, p), (y, q)):
            assert sympy.powsimp(sympy.expand_power_base((f ** k).subs(chain.nu, 1), force=True), force=True) in (
                chain.hh * chain.e1**6, chain.hh * chain.e2**6)


def test_the_vdot_step_is_proved_term_by_term(checked):
    res = checked["vdot"][1]
    assert res.status is Status.CERTIFIED, res.detail  # Lemma 1 certified on the region, the other six exact
    assert len(res.terms) == 7 and sum(tr.status is Status.EXACT for tr in res.terms) == 6
    assert all(checked[r][1].status is Status.EXACT for r in ("lower", "upper"))


def test_a_wrong_young_exponent_is_not_proved(values, checked):
    """The ḣ-term split with (σ, σ/(σ−1)) = (5, 5/4) instead of (σ+1, (σ+1)/σ): not the stated bound."""
    step = checked["vdot"][0]
    tb = next(b for b in step.bounds if b.terms == (HDOT,))
    first = tb.then[2]
    wrong = YoungEach(tuple((x, y, 5, R(5, 4), e) for x, y, _, _, e in first.pairs))
    res = _replace(step, HDOT, then=(*tb.then[:2], wrong, *tb.then[3:])).check(values, search=False)
    bad = [tr for tr in res.terms if tr.terms == (HDOT,)][0]
    assert not res.status.is_proof and not bad.status.is_proof, res.detail


def test_a_non_conjugate_pair_fails_its_side_condition(values, checked):
    step = checked["vdot"][0]
    tb = next(b for b in step.bounds if b.terms == (HDOT,))
    wrong = YoungEach(tuple((x, y, 6, R(5, 4), e) for x, y, _, _, e in tb.then[2].pairs))
    res = _replace(step, HDOT, then=(*tb.then[:2], wrong, *tb.then[3:])).check(values, search=False)
    bad = [tr for tr in res.terms if tr.terms == (HDOT,)][0]
    # the side condition is refuted; the term stays unproved (no witness search here)
    assert not bad.status.is_proof and "side condition fails: p = 6, q = 5/4 conjugate" in bad.detail, bad.detail
    assert "1/p + 1/q = 29/30" in bad.detail


def test_a_dropped_term_leaves_it_uncovered(values, checked):
    step = checked["vdot"][0]
    res = step.with_bounds(bounds=step.bounds[:-1]).check(values, search=False)
    assert res.status is Status.UNDECIDED and "lhs terms without a bound: −γh^ν‖η‖^{σ−1}ωᵀJM" in res.detail


def test_a_flipped_sign_is_not_proved(values, checked):
    step = checked["vdot"][0]
    last = step.bounds[-1]
    res = step.with_bounds(bounds=[type(last)(last.terms, -last.bound, last.rule, then=last.then)], part=last.terms,
                           rhs=-last.bound).check(values, search=False)
    assert not res.status.is_proof and "the stated bound is not the rule's" in res.terms[0].detail


def test_a_wrong_rate_is_refuted_at_a_monomial(values, checked):
    rows, status, _ = theorem2_mu5.decay.certify(checked, values)
    too_big = sympy.nsimplify(rows[0].value["alpha_largest"]) * R(11, 10)
    status, detail = theorem2_mu5.decay.certify(checked, {**values, "alpha8": too_big})[1:]
    assert status is Status.FAILED and detail.startswith("fails at the monomial")


def test_sigma_below_mu_fails_at_the_conclusion():
    """σ = 3 < μ = 5: every link holds but the Young splits leave h^ν‖ω‖⁴ that −h‖ω‖⁶ cannot absorb near 0."""
    rep = theorem2_for(5, 3).run({})
    assert rep.verdict.startswith("not established"), rep.verdict
    rate = next(r for r in rep.results if r.name == "V̇ ≤ −α8 h^ν V^λ")
    assert rate.status is Status.FAILED and "fails at the monomial w**4" in rate.detail
    assert all(r.status.is_proof for r in rep.results if r.kind in ("identity", "bound"))


def test_an_even_exponent_is_refused():
    with pytest.raises(InputError, match="odd integer"):
        instance(4)
    with pytest.raises(InputError, match="odd integer"):
        theorem2_for(5, 2)


def test_the_general_builder_at_mu_3_is_the_catalogued_chain():
    """chain_steps(3) rebuilds theorem 2's steps: same stated bounds, rules and rewrites."""
    rebuilt = chain.chain_steps(3)
    assert rebuilt[0].functional is chain.steps[0].functional and rebuilt[2].system is chain.steps[2].system
    for a, b in zip(rebuilt, chain.steps):
        assert [(t.terms, t.bound) for t in a.bounds] == [(t.terms, t.bound) for t in b.bounds]
        assert sympy.expand(a.rhs - b.rhs) == 0


@pytest.mark.slow  # ≈ 80 s alone (the degree-8 identity ≈ 77 s), several minutes on a loaded machine
def test_mu_7_is_established():
    rep = theorem2_for(7).run({})
    assert rep.verdict.startswith("established"), rep.verdict
    assert next(r for r in rep.results if r.name == "V̇ ≤ −α8 h^ν V^λ").value["lam"] == "4"


# -- σ > μ: the damping's power raised on the region ---------------------------------------------------
@pytest.fixture(scope="module")
def item35():
    return theorem2_for(3, 5)


@pytest.fixture(scope="module")
def values35():
    return P.resolve(chain.find_choices(P.resolve({}, use_defaults=True), mu=3, sigma=5), use_defaults=True)


@pytest.fixture(scope="module")
def checked35(item35, values35):
    return {s.role: (s, s.check(values35, budget=120)) for s in item35.steps}


@pytest.mark.parametrize("nu", ["1", "9/8"])
def test_sigma_above_mu_is_established(item35, nu):
    """μ = 3, σ = 5 (λ = 3): ≈ 7 s each.  ν = 9/8 needs the ḣ-term's (μ+1, (μ+1)/μ) split: (15) with μ gives
    h^{ν−1}|ḣ| ≤ Lh^{35/32}, and the (σ+1, (σ+1)/σ) pair would need h^{53/48}."""
    rep = item35.run({"nu": nu})
    assert rep.verdict.startswith("established"), rep.verdict
    by = {r.name: r for r in rep.results}
    assert by["Vdot_structured"].status is Status.EXACT
    rate = by["V̇ ≤ −α8 h^ν V^λ"]
    assert rate.status is Status.CERTIFIED and rate.value["lam"] == "3"
    assert R(rate.value["alpha"]) <= rate.value["alpha_largest"]


def test_sigma_above_mu_raises_half_of_the_damping(checked35):
    step, res = checked35["vdot"]
    assert res.status is Status.CERTIFIED, res.detail
    tb = next(b for b in step.bounds if b.terms == (DAMP,))
    w, hh, dw, dmin = chain.w, chain.hh, chain.delta_w, chain.d_min
    assert sympy.expand(tb.bound + 2 * dmin**2 * hh * (w**4 + dw**-2 * w**6)) == 0
    assert type(tb.then[-1]).__name__ == "RaiseOnRegion" and tb.then[-1].share == R(1, 2)
    first = next(b for b in step.bounds if b.terms == (HDOT,)).then[2]
    assert {p[2:4] for p in first.pairs} == {(4, R(4, 3))}       # (μ+1, (μ+1)/μ)


def test_a_wrong_delta_exponent_is_not_proved(values35, checked35):
    """−4d²h w⁴ ≤ −2d²h(w⁴ + δ_ω^{μ−σ−1}w⁶): δ_ω^{−3} instead of δ_ω^{−2}, false at w = δ_ω."""
    step = checked35["vdot"][0]
    w, hh, dw, dmin = chain.w, chain.hh, chain.delta_w, chain.d_min
    res = _replace(step, DAMP, bound=-2 * dmin**2 * hh * (w**4 + dw**-3 * w**6)).check(values35, search=False)
    bad = next(tr for tr in res.terms if tr.terms == (DAMP,))
    assert not res.status.is_proof and not bad.status.is_proof
    assert "the stated bound is not the rule's" in bad.detail, bad.detail


def test_without_the_raise_the_chain_does_not_close(values35, checked35, item35):
    step = checked35["vdot"][0]
    tb = next(b for b in step.bounds if b.terms == (DAMP,))
    # the raised bound stated but the rewrite dropped: not the rule's bound
    res = _replace(step, DAMP, then=tb.then[:-1]).check(values35, search=False)
    assert not next(tr for tr in res.terms if tr.terms == (DAMP,)).status.is_proof
    # the damping left at w⁴: the step holds, the conclusion fails at w⁶ (nothing absorbs h^ν w⁶ near 0)
    w, hh, dmin = chain.w, chain.hh, chain.d_min
    plain = _replace(step, DAMP, bound=-4 * dmin**2 * hh * w**4, then=tb.then[:-1])
    res = plain.check(values35, search=False)
    assert res.status.is_proof, res.detail
    status, detail = item35.decay.certify({**checked35, "vdot": (plain, res)}, values35)[1:]
    assert status is Status.FAILED and "fails at the monomial w**6" in detail, detail


@pytest.mark.slow  # ≈ 36 s alone (μ = 5, σ = 7: the degree-8 identity)
def test_sigma_above_mu_5_7_is_established():
    rep = theorem2_for(5, 7).run({})
    assert rep.verdict.startswith("established"), rep.verdict
    assert next(r for r in rep.results if r.name == "V̇ ≤ −α8 h^ν V^λ").value["lam"] == "4"
