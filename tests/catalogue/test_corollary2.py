"""Corollary 2 of paper 001: h = (t+1)^(−β) with the nonlinear damping W = (ωᵀDω)²."""

import sympy
import pytest

from lkverify import DerivativeClaim, Status, Term, t
from lkverify.proofs.aleksandrov2017 import P, corollary2
from lkverify.proofs.aleksandrov2017.corollary2 import corollary2_constants, energy_rate4, limit_energy_bound
from lkverify.proofs.aleksandrov2017.equations import D, J, h, omega
from lkverify.proofs.aleksandrov2017.remark2 import energy
from lkverify.proofs.aleksandrov2017.theorem2 import W, system4
from lkverify.certify.matrices import matrix_positive_definite


@pytest.fixture(scope="module")
def report():
    return corollary2.run({})


def _row(report, start):
    return next(r for r in report.results if r.name.startswith(start))


def test_every_check_holds_at_the_section6_data(report):
    assert report.exit_code == 0
    assert _row(report, "Corollary 2, if").status is Status.EXACT
    assert _row(report, "Vtilde_dot").status is Status.EXACT
    limit = _row(report, "Corollary 2, only if")
    assert limit.status is Status.CERTIFIED and limit.value["tail"] == "7"
    # independent: Ṽ∞ = 1/(1/Ṽ0 + 16·7) for κ = 2, c = 16
    V0 = limit.value["V0"]
    assert limit.value["value"] == pytest.approx(1 / (1 / V0 + 112), rel=1e-12)


def test_constants_are_the_eigenvalue_bounds():
    v = P.resolve({"J": "diag(5,6,4)", "D": "diag(1,4,2)"}, use_defaults=True)
    c = corollary2_constants(v)
    assert c["k"] == 2 and c["c"] == 16
    v = P.resolve({"J": "diag(8,6,10)", "D": "diag(3,3,3)"}, use_defaults=True)
    assert corollary2_constants(v)["k"] == 1


def test_a_smaller_k_is_refuted_as_a_matrix_inequality():
    v = P.resolve({}, use_defaults=True)
    k = corollary2_constants(v)["k"]
    Jm, Dm = sympy.Matrix(v["J"]), sympy.Matrix(v["D"])
    assert matrix_positive_definite(k * Jm / 2 - Dm, semidefinite=True).status is Status.EXACT
    assert matrix_positive_definite((k - sympy.Rational(1, 100)) * Jm / 2 - Dm,
                                    semidefinite=True).status is Status.FAILED


@pytest.mark.parametrize("mutated", [
    [Term(-h(t) * W, text="−hW (factor μ+1 dropped)")],
    [Term(4 * h(t) * W, text="+4hW (sign flipped)")],
])
def test_a_mutated_energy_rate_is_refuted(mutated):
    claim = DerivativeClaim("mutated", energy, system4, mutated)
    v = P.resolve({}, use_defaults=True)
    assert claim.check(P.substitution(v), values=v, budget=30).status is Status.FAILED


def test_the_energy_rate_written_differently_is_exact():
    # −4h(ωᵀDω)² written as −h ωᵀ grad W with grad W = 4(ωᵀDω)Dω
    wDw = (omega(t).T * D * omega(t))[0]
    other = DerivativeClaim("other", energy, system4, [Term(-h(t) * 4 * wDw * wDw, text="−h ωᵀgrad W")])
    v = P.resolve({}, use_defaults=True)
    assert other.check(P.substitution(v), values=v, budget=30).status is Status.EXACT
    assert energy_rate4.check(P.substitution(v), values=v, budget=30).status is Status.EXACT


def test_limit_bound_is_the_solution_of_the_comparison_equation():
    # V' = −c h V^κ with h = (1+t)^(−8/7), κ = 2, c = 16, V(0) = 1: V(∞) = 1/(1 + 16·7) exactly
    assert limit_energy_bound(1, 16, 2, 7) == sympy.Rational(1, 113)
    # κ = 3/2: V(∞) = (V0^(−1/2) + c·tail/2)^(−2) = (1/2 + 3)^(−2)
    assert limit_energy_bound(4, 2, sympy.Rational(3, 2), 3) == sympy.Rational(4, 49)
    assert limit_energy_bound(1, 16, 2, 8) < limit_energy_bound(1, 16, 2, 7)   # more damping, lower floor
