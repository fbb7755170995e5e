"""The papers' printed inequality steps (issue 9, item 6): refuted with a witness inside the hypotheses, or proved."""

import pytest

from lkverify.catalogue.loader import find_items
from lkverify.proofs.aleksandrov2017 import P as P001
from lkverify.proofs.aleksandrov2017.theorem1_bound import corrected as c001, printed as p001
from lkverify.proofs.aleksandrov2023 import P as P002
from lkverify.proofs.aleksandrov2023.theorem3_bound import corrected as c002, printed as p002
from lkverify.proofs.aleksandrov2026 import P as P000
from lkverify.proofs.aleksandrov2026.theorem2_bound import REMARK3, corrected as c000, printed as p000
from lkverify.status import Status


def _refuted(res):
    assert res.status is Status.FAILED, res.detail
    (term,) = res.terms
    assert term.witness is not None and term.witness.violation[0] > 0
    return term.witness


@pytest.mark.slow  # about 35 s on a loaded machine
def test_paper000_theorem2_gamma_beta_c7_refuted_for_beta_negative_and_corrected():
    v = P000.resolve(REMARK3, use_defaults=True)
    (theorem2,) = find_items("aleksandrov2026.theorem2")
    hyps = theorem2.run(REMARK3).results
    assert all(r.status.is_proof for r in hyps if r.kind == "hypothesis")  # inside Assumption 2
    w = _refuted(p000.check(v))
    assert "c7" in w.coefficients  # for every c7 ≥ 0
    assert c000.check(v).status is Status.CERTIFIED


def test_paper000_theorem2_printed_step_is_proved_for_beta_positive():
    v = P000.resolve({}, use_defaults=True)  # the section 5 example: β = 1
    res = p000.check(v)
    assert res.status is Status.CERTIFIED, res.detail
    assert res.constants["c7"] >= 1.0 and res.constants["c7"] <= 1.01  # sup of f^ν(e1 + e2)/(e1^{1.6} + e2^{1.6}) = 1 at e1 = e2


@pytest.mark.slow
def test_paper001_theorem1_h_dot_refuted_for_decreasing_h_and_corrected():
    v = P001.resolve({}, use_defaults=True)  # h = (1 + t)^{−7/8}
    w = _refuted(p001.check(v))
    assert w.exact["t"] == "1"
    assert c001.check(v).status is Status.EXACT


@pytest.mark.parametrize("h", ["1 + t", "2"])
def test_paper001_theorem1_printed_step_is_proved_where_h_does_not_decrease(h):
    v = P001.resolve({"h": h}, use_defaults=True)
    assert p001.check(v).status is Status.EXACT


def test_paper002_theorem3_b_lambda_c7_refuted_and_corrected():
    v = P002.resolve({}, use_defaults=True)
    w = _refuted(p002.check(v))
    assert {"c7", "lam"} <= set(w.coefficients)
    assert c002.check(v).status is Status.EXACT


def test_the_audit_items_report_failed_with_the_witness(capsys):
    from lkverify.cli import main

    assert main(["check", "aleksandrov2017.theorem1_bound"]) == 1
    out = capsys.readouterr().out
    assert "refuted: at t = 1" in out and "corrected" in out


def test_theorem3_caps_are_exact_and_below_the_print():
    import sympy

    from lkverify.proofs.aleksandrov2023.theorem3_caps import caps

    v = P002.resolve({}, use_defaults=True)
    theta_star, theta_max, d1_min, dt_sup = caps(v)
    assert sympy.simplify(theta_star - (5 + sympy.sqrt(3) / 3)) == 0 and theta_max == 6
    assert abs(float(d1_min) - 11.5696) < 1e-3 and abs(float(dt_sup) - 0.17287) < 1e-4
    # the certified chain's d1 cannot beat the cap
    assert 13.95 > float(d1_min)
    (item,) = find_items("aleksandrov2023.theorem3_caps")
    rows = {r.name: r for r in item.run({}).results}
    assert rows["d1 ≥ 2√(θ*θ_max) for every λ, α, β"].status is Status.EXACT
    # a body with equal moments: θ* = θ_max = 5, d1 ≥ 10 (still above 9.21)
    v2 = P002.resolve({"Theta": "diag(5,5,5)"}, use_defaults=True)
    assert caps(v2)[2] == 10


@pytest.mark.slow  # about 30 s on a loaded machine
def test_paper000_theorem1_c5_to_c10_bound_is_proved_on_the_exact_vdot():
    import dataclasses

    import sympy

    from lkverify.proofs.aleksandrov2026.theorem1_bound import BOUNDS, d1, d2, derivation, mu, printed_bound

    v = P000.resolve({}, use_defaults=True)
    assert derivation.check(P000.substitution(v), values=v, budget=None).status is Status.EXACT
    res = printed_bound.check(v, search=False)
    assert res.status is Status.CERTIFIED, res.detail
    assert set(res.constants) == {"c8", "c10p"}
    assert all(1.0 <= res.constants[c] <= 1.01 for c in ("c8", "c10p"))
    # a wrong constant in an exact term is refuted with a witness (frames, delayed values)
    i = next(k for k, tb in enumerate(BOUNDS) if tb.terms == ("−μW(t−τ)",))
    wrong = -2 * mu * (d1 ** sympy.Rational(13, 5) + d2 ** sympy.Rational(13, 5))  # W(t−τ) with ν = 3/10, twice
    from lkverify.certify.steps.rules import Equal

    tb = dataclasses.replace(BOUNDS[i], bound=wrong, rule=Equal(wrong))
    step = dataclasses.replace(printed_bound, bounds=(tb,), rhs=wrong, part=tb.terms)
    bad = step.check(v)
    assert bad.status is Status.FAILED, bad.detail
    assert bad.terms[0].witness.violation[0] > 0
