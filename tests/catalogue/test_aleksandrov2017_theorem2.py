"""Theorem 2 of paper 001 (nonlinear damping, instance W = (ωᵀDω)²): V̇ exact for every h, mutations refuted,
conditions (5), (15), (11) decided for the run's h; the instance simulated for β = 7/8 and 8/7 (Corollary 2's
dichotomy in tail windows) and the algebraic envelope with α8 estimated."""

import dataclasses

import pytest

from lkverify import Status, Term
from lkverify.proofs.aleksandrov2017.theorem2 import derivation2, theorem2


def _check(terms):
    return dataclasses.replace(derivation2, terms=tuple(terms)).check({}, values={}, budget=120)


@pytest.mark.slow  # about 30 s on a loaded machine
def test_vdot_is_exact_for_every_h():
    assert derivation2.check({}, values={}, budget=None).status is Status.EXACT


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


# -- the catalogued instance simulated (Corollary 2's dichotomy) and the algebraic envelope ---------------------------
import numpy as np  # noqa: E402

from lkverify.proofs.aleksandrov2017.example import remark2_energy  # noqa: E402
from lkverify.proofs.aleksandrov2017.theorem2_envelope import AlgebraicEnvelope, estimate_alpha8  # noqa: E402
from lkverify.proofs.aleksandrov2017.theorem2_example import BOUNDED, DECAYING, ORDER, theorem2_example  # noqa: E402
from lkverify.simulate import DecaysAlgebraically, FromValues, LimitAboveFloor  # noqa: E402

_E = FromValues(remark2_energy)


@pytest.fixture(scope="module")
def runs():
    return theorem2_example.simulate()  # both runs to T = 2000, about 2 s


def test_corollary2_dichotomy_is_observed_on_both_sides(runs):
    decays = DecaysAlgebraically(DECAYING, _E, order=ORDER).check(theorem2_example, runs)
    floor = LimitAboveFloor(BOUNDED, _E, order=ORDER, bound=3.0).check(theorem2_example, runs)
    assert decays.status is Status.SIMULATED and floor.status is Status.SIMULATED
    assert -0.25 < decays.value["loglog_slope"] < -1 / 8      # Ṽ ~ t^{−1/8}, approached from below
    assert floor.value["energy_limit_lower"] > 0.5 * floor.value["energy_end"]
    # the wrong side of the dichotomy fails
    assert DecaysAlgebraically(BOUNDED, _E, order=ORDER).check(theorem2_example, runs).status is Status.FAILED
    assert LimitAboveFloor(DECAYING, _E, order=ORDER).check(theorem2_example, runs).status is Status.FAILED


def test_measured_rates_against_closed_form_integrals(runs):
    """k_w = (1/Ṽ(b) − 1/Ṽ(a)) / ∫_a^b h with ∫_a^b (1+t)^{−7/8} = 8((1+b)^{1/8} − (1+a)^{1/8}), independently."""
    res = DecaysAlgebraically(DECAYING, _E, order=ORDER).check(theorem2_example, runs)
    tr = runs[DECAYING]
    E = remark2_energy()(tr.states)
    edges = res.value["window_edges"]
    idx = [int(np.argmin(abs(tr.t - e))) for e in edges]
    ref = [(1 / E[j] - 1 / E[i]) / (8 * ((1 + tr.t[j]) ** (1 / 8) - (1 + tr.t[i]) ** (1 / 8)))
           for i, j in zip(idx[:-1], idx[1:])]
    assert np.allclose(res.value["rates"], ref, rtol=1e-6)
    assert 2 < min(ref) and max(ref) < 5                       # the law Ṽ' ≈ −k h Ṽ² with a steady k


def test_an_undamped_run_is_not_shown_to_decay():
    trs = theorem2_example.simulate({"h": "0"}, t_end=400)
    res = DecaysAlgebraically(DECAYING, _E, "(1+t)**(-7/8)", order=ORDER).check(theorem2_example, trs)
    assert res.status is Status.FAILED                         # Ṽ is conserved: no steady positive rate


def test_the_claims_follow_set_h():
    trs = theorem2_example.simulate({"h": "(1+t)**(-8/7)"}, t_end=400)
    res = DecaysAlgebraically(DECAYING, _E, order=ORDER).check(theorem2_example, trs)
    assert res.status is Status.FAILED and np.isfinite(res.value["tail_integral"])


@pytest.mark.slow
def test_algebraic_envelope_holds_with_the_estimated_alpha8(runs):
    res = AlgebraicEnvelope(DECAYING, gamma_value=0.1, delta=0.5).check(theorem2_example, runs)
    assert res.status is Status.SIMULATED and res.value["alpha8_status"] == "estimated"
    assert 0 < res.value["alpha8"] and res.value["max_ratio"] <= 1
    assert "estimated" in res.detail and "not proved" in res.detail


@pytest.mark.slow  # 6 s: two more α8 estimates
def test_algebraic_envelope_fails_with_a_wrong_constant_or_a_too_large_gamma(runs):
    too_fast = AlgebraicEnvelope(DECAYING, alpha8=50.0).check(theorem2_example, runs)
    assert too_fast.status is Status.FAILED and too_fast.value["max_ratio"] > 1 and "given" in too_fast.detail
    big_gamma = AlgebraicEnvelope(DECAYING, gamma_value=1.0, delta=0.5).check(theorem2_example, runs)
    assert big_gamma.status is Status.FAILED and big_gamma.value["alpha8"] < 0


@pytest.mark.slow  # 7 s: three estimates
def test_alpha8_estimate_is_stable_and_shrinks_with_a_larger_h_range():
    """Seeds agree within 10 %; over h ∈ (0, 1], ḣ/h ∈ [−7/8, 0] (all t ≥ 0) the ḣ term makes α8 much smaller."""
    late = [estimate_alpha8({}, gamma_value=0.1, delta=0.5, h_max=0.27, rho_range=(-0.2, 0.0), seed=s).alpha8
            for s in (0, 1)]
    assert abs(late[0] - late[1]) < 0.1 * late[0]
    early = estimate_alpha8({}, gamma_value=0.1, delta=0.5, h_max=1.0, rho_range=(-7 / 8, 0.0)).alpha8
    assert 0 < early < 0.5 * min(late)


@pytest.mark.slow  # about 5–10 s: the whole item as the bare report and `lkverify simulate` run it
def test_the_example_item_holds():
    rep = theorem2_example.run({})
    assert rep.holds, rep.as_text()
    assert [r.status for r in rep.results] == [Status.SIMULATED] * 6


def test_the_floor_with_corollary2s_proved_rate_is_above_its_certified_bound(runs):
    """Corollary 2 proves −dṼ/dt ≤ cṼ², c = 16: the measured rates must not exceed c, and the floor
    extrapolated from Ṽ(T) with c must lie above the bound (1/Ṽ(0) + c∫_0^∞h)^{−1} from t = 0."""
    from lkverify.proofs.aleksandrov2017 import P
    from lkverify.proofs.aleksandrov2017.corollary2 import corollary2_constants, limit_energy_bound

    c = corollary2_constants(P.resolve({}, use_defaults=True))
    assert float(c["kappa"]) == ORDER
    res = LimitAboveFloor(BOUNDED, _E, order=ORDER, rate=float(c["c"])).check(theorem2_example, runs)
    assert res.status is Status.SIMULATED and "proved rate" in res.detail
    assert max(res.value["rates"]) < c["c"]
    V0 = float(remark2_energy()(runs[BOUNDED].states)[0])
    assert res.value["energy_limit_lower"] > float(limit_energy_bound(V0, c["c"], c["kappa"], 7))


# -- V̇ with σ symbolic (powers ‖η‖^{σ−3}, ‖η‖^{σ−1}, ‖η‖^{σ+1} share one atom in the normal forms) --------------------
def _sigma_claim(mutate=False):
    import copy
    import importlib

    import sympy

    from lkverify import DerivativeClaim, Functional, System, dot, norm_squared, quad, t
    from lkverify.proofs.aleksandrov2017.equations import P, J, eta, gamma, h, nu, omega

    T2 = importlib.import_module("lkverify.proofs.aleksandrov2017.theorem2_functional")
    P2 = copy.deepcopy(P)                        # paper 001's parameters and a symbolic σ > 0
    sg = P2.scalar("sigma", positive=True)
    e2, hd, M = norm_squared(eta), sympy.Derivative(h(t), t), T2.M
    system = System(T2.system4.equations, parameters=P2, name="(2),(4)")
    V = Functional([*T2.functional2.terms[:3],
                    Term(gamma * h(t) ** nu * e2 ** ((sg - 1) / 2) * quad(omega(t), J, eta), text="γh^ν‖η‖^{σ−1}ωᵀJη")])
    third = (sg - 2) if mutate else (sg - 1)     # the mutation: (σ−2) for the chain-rule factor (σ−1)
    terms = [Term(-(T2.mu + 1) * h(t) * T2.W, text="−(μ+1)hW"),
             Term(gamma * nu * h(t) ** (nu - 1) * hd * e2 ** ((sg - 1) / 2) * quad(omega(t), J, eta), text="ḣ"),
             Term(-gamma * third * h(t) ** nu * e2 ** ((sg - 3) / 2) * dot(eta, M) * quad(omega(t), J, eta), text="σ−1"),
             Term(-gamma * h(t) ** nu * e2 ** ((sg - 1) / 2) * dot(omega(t).cross(J * omega(t)), eta), text="ω×Jω"),
             Term(-gamma * h(t) ** (nu + 1) * e2 ** ((sg - 1) / 2) * dot(T2.grad_W, eta), text="grad W"),
             Term(-gamma * h(t) ** nu * e2 ** ((sg + 1) / 2), text="‖η‖^{σ+1}"),
             Term(-gamma * h(t) ** nu * e2 ** ((sg - 1) / 2) * quad(omega(t), J, M), text="ωᵀJM")]
    return DerivativeClaim("Vdot_sigma", V, system, terms)


@pytest.mark.slow  # about 1 min: the identity with σ symbolic exact (~15 s), then a mutation refuted
def test_vdot_with_symbolic_sigma_is_exact_and_a_mutation_is_refuted():
    assert _sigma_claim().check({}, values={}, budget=None).status is Status.EXACT
    assert _sigma_claim(mutate=True).check({}, values={}, budget=None).status is Status.FAILED
