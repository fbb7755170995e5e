"""Term-by-term bound steps: Theorem 3 of paper 002 proved, and its mutations refuted with witnesses."""

import dataclasses
import json

import pytest
import sympy

from lkverify.certify.steps.chain import TermBound
from lkverify.certify.steps.rules import CauchySchwarz, Template
from lkverify.proofs.aleksandrov2023 import P
from lkverify.proofs.aleksandrov2023.theorem3_bound import corrected as CORRECTED, printed as PRINTED
from lkverify.proofs.aleksandrov2023 import theorem3_chain as C
from lkverify.proofs.aleksandrov2023.theorem3 import steps, theorem3
from lkverify.status import Status

LOWER, UPPER, VDOT = steps
J_LABEL = "λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ"
CB_LABEL = "−(s×r)ᵀF⁻¹(ω×Θω)"


@pytest.fixture(scope="module")
def values():
    return P.resolve(dict(C.CHOICES), use_defaults=True)


def _bound(step, label):
    return next(tb for tb in step.bounds if label in tb.terms)


def _only(step, label, **changes):
    """The step restricted to one labelled term, with its TermBound changed."""
    tb = dataclasses.replace(_bound(step, label), **changes)
    return dataclasses.replace(step, bounds=(tb,), rhs=tb.bound, part=(label,))


@pytest.fixture(scope="module")
def checked(values):
    return {step.role: (step, step.check(values)) for step in steps}


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_the_chain_of_theorem3_is_proved_term_by_term(checked):
    for role, (step, res) in checked.items():
        assert res.status in (Status.EXACT, Status.CERTIFIED), (role, res.detail)
        assert len(res.terms) == len(step.lhs_terms())
        assert all(tr.status.is_proof for tr in res.terms)
    consts = checked["vdot"][1].constants
    assert set(consts) == {"c_A", "c_B"}
    assert 5.6 < consts["c_A"] < 5.67 and 0.9 < consts["c_B"] < 0.92  # estimates 5.608, 0.908 (bench_templates)


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_every_template_constant_is_certified_within_one_percent_of_its_estimate(checked):
    seen = 0
    for _, res in checked.values():
        for tr in res.terms:
            for app in tr.applications:
                for name, value, info in app.constants:
                    assert value >= info["estimate"]  # a certified upper bound of the supremum
                    assert (value - info["estimate"]) / info["estimate"] <= 0.01, (name, value, info)
                    seen += 1
    assert seen == 4  # κ1 (twice: V ≥ L and V ≤ U), c_A, c_B


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_the_decay_of_the_checked_chain_is_certified(checked, values):
    rows, status, detail = C.DECAY.certify(checked, values, budget=None)
    assert status is Status.CERTIFIED, detail
    got = {r.name: r.value["value"] for r in rows if r.kind == "constant"}
    assert got["delta_tilde"] > 0 and got["d1"] > 0 and got["d3"] > 0


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_a_region_twice_too_large_fails_with_a_witness_point(checked, values):
    rows, status, detail = C.DECAY.certify(checked, values, budget=None)
    claimed = {r.name: sympy.Rational(r.value["value"]) for r in rows if r.kind == "constant"}
    claimed = {k: claimed[k] for k in ("c_tilde", "delta_tilde", "l_e", "l_w")}
    # the same constants on the same region hold …
    _, same, _ = C.DECAY.certify(checked, values, budget=None, claimed=claimed)
    assert same is Status.CERTIFIED
    # … and fail on a region twice too large, with the point where W + c̃U^{3/2} > 0
    _, status2, detail2 = C.DECAY.certify(checked, values, budget=None, claimed=claimed, region=C.REGION.scaled(2))
    assert status2 is Status.FAILED, detail2
    assert "witness" in detail2


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_a_template_constant_at_090_of_its_certified_value_is_refuted(values, checked):
    kappa = checked["lower"][1].constants["kappa1"]
    step = _only(LOWER, "(s×r)ᵀF⁻¹Θω", bound=-sympy.Rational(9, 10) * sympy.Rational(kappa) * C.e * C.w)
    res = step.check(values)
    assert res.status is Status.FAILED
    tr = res.terms[0]
    assert tr.witness is not None and tr.witness.violation[0] > 0
    json.dumps(tr.to_json())


def test_an_absolute_value_dropped_is_refuted(values):
    bad = _bound(VDOT, J_LABEL).bound.replace(sympy.Abs, lambda x: x)
    assert bad != _bound(VDOT, J_LABEL).bound
    res = _only(VDOT, J_LABEL, bound=bad).check(values)
    assert res.status is Status.FAILED, res.detail
    assert res.terms[0].witness.violation[0] > 0


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_an_exponent_off_by_one_is_refuted(values, checked):
    # Hölder's measure to the power μ + 1 instead of μ
    bad = _bound(VDOT, J_LABEL).bound * C.j
    res = _only(VDOT, J_LABEL, bound=bad).check(values)
    assert res.status is Status.FAILED, res.detail
    # the template c_B e w² stated as c_B e² w²: not divisible, and refuted near s = r
    cB = sympy.Rational(checked["vdot"][1].constants["c_B"])
    res2 = _only(VDOT, CB_LABEL, bound=cB * C.e**2 * C.w**2,
                 rule=Template("c_B", {"e": 2, "w": 2}, rho_max=C.RHO_CAP)).check(values)
    assert res2.status is Status.FAILED, res2.detail
    assert "not divisible" in res2.terms[0].detail


def test_a_misapplied_rule_is_rejected_and_the_side_condition_named(values):
    tb = _bound(VDOT, J_LABEL)
    u, v, norms = tb.rule.u, tb.rule.v, tb.rule.norms
    from lkverify.certify.steps.rules import integral_of

    nb = norms[1]
    _, pointwise, measure, k, weight, window, holder = nb.vector
    wrong = integral_of(pointwise, measure=measure, power=k, weight=weight, holder=(2, 2))
    rule = CauchySchwarz(u, v, (norms[0], wrong), factor=tb.rule.factor)
    step = dataclasses.replace(_only(VDOT, J_LABEL, rule=rule), witness_seconds=1.0)
    res = step.check(values)
    assert res.status is Status.UNDECIDED  # the bound is true: no witness, but the justification is rejected
    assert "Hölder exponents" in res.terms[0].detail or "k·p" in res.terms[0].detail


def test_an_uncovered_or_doubly_covered_term_is_reported(values):
    res = dataclasses.replace(LOWER, bounds=LOWER.bounds[1:]).check(values, search=False)
    assert res.status is Status.UNDECIDED and "without a bound" in res.detail
    res2 = dataclasses.replace(LOWER, bounds=LOWER.bounds + LOWER.bounds[:1]).check(values, search=False)
    assert "twice" in res2.detail


def test_the_printed_bound_is_refuted_and_the_corrected_one_proved():
    v = P.resolve({}, use_defaults=True)
    printed = PRINTED.check(v)
    assert printed.status is Status.FAILED
    w = printed.terms[0].witness
    assert w.violation[0] > 0 and set(w.coefficients) >= {"c7"}
    corrected = CORRECTED.check(v)
    assert corrected.status is Status.EXACT, corrected.detail


@pytest.mark.slow
def test_the_printed_bound_holds_for_b_positive():
    # with b > 0 the printed sign is right: the witness search finds nothing
    v = P.resolve({"b": "1/2", "a": "1"}, use_defaults=True)
    printed = dataclasses.replace(PRINTED, witness_seconds=3.0).check(v)
    assert printed.status is Status.UNDECIDED


@pytest.mark.slow  # about 70 s: the whole report of Theorem 3
def test_theorem3_report_lists_the_chain(values):
    report = theorem3.run({}, budget=None)
    names = [link.name for link in report.chain]
    assert any("V ≥ L" in n for n in names) and any("decay" in n for n in names)
    assert report.verdict.startswith("established"), report.verdict
    bound_rows = [r for r in report.results if r.kind == "bound"]
    assert len(bound_rows) == 5 + 1 + 5 + 1 + 10 + 1
    card = report.to_json() if hasattr(report, "to_json") else None
    if card is not None:
        json.dumps(card)


@pytest.mark.slow  # the module fixture `checked` proves all three steps (about 40 s)
def test_the_chain_on_a_region_twice_too_large_names_the_failed_decay_link_with_a_point(checked):
    choices = dict(C.CHOICES)
    values = P.resolve({**choices, "delta_e": "1/100", "delta_w": "3142/9995"}, use_defaults=True)
    steps_at = {role: (step, res) for role, (step, res) in checked.items()}  # the steps hold on any smaller cap
    rows, status, detail = C.DECAY.certify(steps_at, values, budget=None)
    assert status is Status.FAILED, detail
    assert "W =" in detail and "≥ 0" in detail


def test_a_short_budget_never_reads_as_a_failure():
    report = theorem3.run({}, budget=3)
    assert not report.verdict.startswith("failed"), report.verdict
    assert all(r.status is not Status.FAILED for r in report.results), [r.name for r in report.results
                                                                         if r.status is Status.FAILED]
