"""Identity claims: the two catalogued proofs, and mutated claims that must be refuted."""

import dataclasses

import pytest
import sympy

from lkverify import Status, Term, check_identity, derivative_along
from lkverify.catalogue.loader import find_items


def item(name):
    (it,) = find_items(name)
    return it


@pytest.fixture(scope="module")
def theorem3():
    return item("aleksandrov2023.theorem3")


@pytest.fixture(scope="module")
def theorem3_derived(theorem3):
    claim = theorem3.claims[0]
    d = derivative_along(claim.functional, claim.system)
    return claim, [Term(b.expr, text=b.text, latex=b.latex) for b in d.blocks]


def check(claim, terms, reference):
    s = claim.system
    return check_identity(terms, reference, states=s.states, parameters=s.parameters,
                          constraints=s.constraint_polynomials, budget=120)


def test_theorem3_structured_form_is_exact(theorem3_derived):
    claim, reference = theorem3_derived
    res = check(claim, claim.terms, reference)
    assert res.status is Status.EXACT, res.as_text()
    assert res.differences == ()


def _by_text(terms, prefix):
    (i,) = [k for k, term in enumerate(terms) if term.text.startswith(prefix)]
    return i


@pytest.mark.slow
def test_theorem3_flipped_sign_is_refuted(theorem3_derived):
    claim, reference = theorem3_derived
    terms = list(claim.terms)
    i = _by_text(terms, "−(a−τb)")
    terms[i] = Term(-terms[i].expr, text="+(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)")
    res = check(claim, terms, reference)
    assert res.status is Status.FAILED
    (diff,) = res.differences
    assert diff.kind == "sign"
    assert diff.claimed == ("+(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)",)
    assert diff.value is not None and abs(diff.value) > 1e-6
    # the report is term by term: every other printed term is listed as confirmed, none twice
    confirmed = [c for group in res.confirmed for c in group[0]]
    assert set(confirmed) == {t.text for k, t in enumerate(terms) if k != i}
    assert len(confirmed) == len(set(confirmed))
    text = res.as_text()
    assert text.count("✓ confirmed") >= 1 and "+(a−τb)" in text
    assert {g["claimed_latex"][0] for g in res.to_json()["confirmed"] if g["claimed"]} <= {t.latex for t in terms}


@pytest.mark.slow
def test_theorem3_dropped_term_is_refuted(theorem3_derived):
    claim, reference = theorem3_derived
    terms = [term for term in claim.terms if not term.text.startswith("−α‖s(t−τ)")]
    res = check(claim, terms, reference)
    assert res.status is Status.FAILED
    (diff,) = res.differences
    assert diff.kind == "missing from claim"
    assert any("Leibniz" in d or "lower limit" in d for d in diff.derived), diff.derived


@pytest.mark.slow
def test_theorem3_wrong_coefficient_is_refuted(theorem3_derived):
    claim, reference = theorem3_derived
    terms = list(claim.terms)
    i = _by_text(terms, "−λωᵀFω")
    terms[i] = Term(2 * terms[i].expr, text="−2λωᵀFω")
    res = check(claim, terms, reference)
    assert res.status is Status.FAILED
    (diff,) = res.differences
    assert diff.kind == "coefficient"
    assert diff.claimed == ("−2λωᵀFω",)
    assert "2 ×" in diff.message


@pytest.mark.slow  # about 35 s; tests/cli/test_cli.py checks the same sign difference by default
def test_theorem1_printed_vdot_differs_in_exactly_one_sign():
    """Paper 000 prints +γ f^ν(t−τ) ωᵀL(t−τ); the derivation gives −γ f^ν(t−τ) ωᵀL(t−τ)."""
    th = item("aleksandrov2026.theorem1")
    claim = th.printed[0]
    res = claim.check({}, values={}, budget=None)
    assert res.status is Status.FAILED
    (diff,) = res.differences
    assert diff.kind == "sign"
    assert diff.claimed == ("+γf^ν(t−τ)ωᵀL(t−τ)",)
    assert diff.derived == ("∂/∂ω [(γ/2)ωᵀΘω] · (Θ⁻¹(−f^ν(t−τ)L(t−τ)))",)


@pytest.mark.slow  # about 35 s; the Theorem 3 forms below are exact by default
def test_theorem1_printed_vdot_with_that_sign_corrected_is_exact():
    th = item("aleksandrov2026.theorem1")
    claim = th.printed[0]
    terms = [Term(-term.expr, text="−γf^ν(t−τ)ωᵀL(t−τ)") if term.text.startswith("+γf^ν") else term
             for term in claim.terms]
    res = dataclasses.replace(claim, terms=tuple(terms)).check({}, values={}, budget=None)
    assert res.status is Status.EXACT, res.as_text()


def test_budget_exhaustion_is_undecided(theorem3_derived):
    claim, reference = theorem3_derived
    s = claim.system
    res = check_identity(claim.terms, reference, states=s.states, parameters=s.parameters,
                         constraints=s.constraint_polynomials, budget=0.05)
    assert res.status is Status.UNDECIDED
    assert "budget" in res.detail


def test_identity_on_the_constraint_manifold_needs_the_constraint():
    """‖s‖² − 1 is zero only because s is a unit vector: exact with the constraint, refuted without."""
    from lkverify import Parameters, System, Equation, UnitVector, Vector, t, cross, dot

    P = Parameters()
    w, s = Vector("w"), UnitVector("s")
    sys = System([Equation(w, [Term(sympy.zeros(3, 1))]), Equation(s, [Term(-cross(w(t), s(t)))])], parameters=P)
    res = check_identity([Term(dot(s(t), s(t)))], [Term(sympy.S.One)], states=sys.states, parameters=P,
                         constraints=sys.constraint_polynomials)
    assert res.status is Status.EXACT
    w2 = Vector("w2")
    res = check_identity([Term(dot(w2(t), w2(t)))], [Term(sympy.S.One)], states=[w2], parameters=P)
    assert res.status is Status.FAILED
