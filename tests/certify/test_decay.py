"""Decay models and the constants job: input checks, the search's deadline, the job's tuning."""

import dataclasses

import pytest
import sympy

from lkverify.certify.constants import ConstantsJob, ConstantsTuning
from lkverify.certify.decay import DecayModel, certify_decay, estimate_decay, search_parameters
from lkverify.errors import InputError, UnsupportedInput
from lkverify.options import Budget
from lkverify.status import Status

w, e = sympy.symbols("w e", nonnegative=True)
a = sympy.Symbol("a", positive=True)


def family(params):
    """V = w² + e², V̇ ≤ −a(w³ + e³) on 0 ≤ w, e ≤ 1/2: c̃ = a/√2."""
    half, Q = sympy.Rational(1, 2), w**2 + e**2
    return DecayModel("family", (w, e), {w: half, e: half}, Q, Q, -params["a"] * (w**3 + e**3),
                      sympy.Rational(3, 2), (w, e), {}, {"d1": e, "d2": w})


def test_estimate_matches_the_closed_form():
    est = estimate_decay(family({"a": 2}))
    assert est["c_tilde"] == pytest.approx(2 / 2**0.5, rel=1e-6)
    assert est["l_e"] == pytest.approx(1.0) and est["l_w"] == pytest.approx(1.0)


def test_a_model_outside_the_scaling_argument_is_unsupported_not_failed():
    bad = dataclasses.replace(family({"a": 1}), vdot=-w**2 + e**2)
    with pytest.raises(UnsupportedInput, match="positive term"):
        certify_decay(bad, c_tilde=1, lower_coefficients={e: 1}, delta_tilde=sympy.Rational(1, 10))
    assert estimate_decay(bad) is None            # for a search: these values do not work, try others


def test_models_are_validated_when_created():
    with pytest.raises(InputError, match="got none for e"):
        DecayModel("m", (w, e), {w: 1}, w**2, w**2, -w**3, sympy.Rational(3, 2), (w,), {}, {"d1": w})
    with pytest.raises(UnsupportedInput, match="one or two point variables"):
        DecayModel("m", (w, e), {w: 1, e: 1}, w**2, w**2, -w**3, sympy.Rational(3, 2), (), {}, {"d1": w})


def test_certificate_budget_is_a_budget_object():
    cert = certify_decay(family({"a": 1}), c_tilde=sympy.Rational(7, 10), delta_tilde=sympy.Rational(1, 4),
                         lower_coefficients={e: sympy.Rational(9, 10), w: sympy.Rational(9, 10)},
                         budget=Budget(seconds=30))
    assert cert.status is Status.CERTIFIED
    assert cert.constants["c_tilde"] == pytest.approx(0.7)


class _ExpiresAfter:
    """A deadline that runs out at its ``after``-th look (a stub clock: no wall-clock assertion)."""

    def __init__(self, after):
        self.after, self.reads = after, 0

    @property
    def expired(self):
        self.reads += 1
        return self.reads > self.after


def test_search_stops_cleanly_at_its_deadline_with_the_best_point():
    deadline, calls = _ExpiresAfter(3), [0]

    def objective(r):
        calls[0] += 1
        return -r["c_tilde"]

    params, est = search_parameters(family, {"a": (0.5, 2.0)}, objective=objective, maxiter=10_000,
                                    popsize=5, deadline=deadline)
    # stopped by the callback at its first look after the deadline, not by maxiter (10 000 generations
    # of 5 would be 50 000 evaluations)
    assert deadline.reads <= deadline.after + 2 and calls[0] <= 3 * 5
    assert 0.5 <= params["a"] <= 2.0 and est is not None


def test_search_without_deadline_finds_the_best_parameter():
    params, est = search_parameters(family, {"a": (0.5, 2.0)}, objective=lambda r: -r["c_tilde"], maxiter=20)
    assert params["a"] == pytest.approx(2.0, rel=1e-2)


def test_constants_tuning_is_frozen_and_documented_defaults():
    tune = ConstantsTuning()
    assert (tune.rounds, tune.attempts, tune.grid, tune.certify_seconds) == (5, 6, 31, 60.0)
    assert tune.shrink == sympy.Rational(9, 10) and tune.candidate_margin == sympy.Rational(99, 100)
    with pytest.raises(dataclasses.FrozenInstanceError):
        tune.rounds = 1  # type: ignore[misc]


def test_goal_messages_speak_the_library_language():
    job = ConstantsJob(templates=[], model=None, free={}, objective={"paper": None, "region": None})
    with pytest.raises(InputError) as info:
        job.run("x", {}, {}, goal="fastest")
    assert "--" not in str(info.value) and "paper" in str(info.value)


def test_search_finds_a_feasible_set_that_is_a_small_part_of_a_wide_range():
    """Feasible only for a < 0.01 of a ∈ [1e-4, 10]: searched in log10 and seeded with feasible samples."""
    import sympy

    from lkverify.certify.decay import DecayModel, search_parameters

    w, e = sympy.symbols("w e", nonnegative=True)
    Q, half = w**2 + e**2, sympy.Rational(1, 2)

    def build(p):
        return DecayModel("narrow", (w, e), {w: half, e: half}, Q, Q, (p["a"] - sympy.Rational(1, 100)) * (w**3 + e**3),
                          sympy.Rational(3, 2), (w, e), {}, {"d1": e, "d2": w})

    params, est = search_parameters(build, {"a": (1e-4, 10.0)}, objective=lambda est: -est["c_tilde"],
                                    maxiter=20, popsize=5, grid=9)
    assert est is not None and params["a"] < 0.01


def test_the_early_stop_ends_a_flat_search_sooner_with_the_same_best_point():
    calls = {"full": 0, "stall": 0}

    def counted(which):
        def objective(r):
            calls[which] += 1
            return -r["c_tilde"]
        return objective

    full, est_full = search_parameters(family, {"a": (0.5, 2.0)}, objective=counted("full"), maxiter=60, popsize=5,
                                       grid=9)
    early, est = search_parameters(family, {"a": (0.5, 2.0)}, objective=counted("stall"), maxiter=60, popsize=5,
                                   grid=9, stall=5)
    assert calls["stall"] < calls["full"]                       # stopped before scipy's own convergence
    assert early["a"] == pytest.approx(full["a"], rel=1e-3) and est["c_tilde"] == pytest.approx(est_full["c_tilde"],
                                                                                             rel=1e-3)
    # what it returns is the estimate at the point it returns (recomputed there), not a stale score
    again = estimate_decay(family({"a": sympy.Rational(early["a"])}), grid=9, refine=False)
    assert est["c_tilde"] == pytest.approx(again["c_tilde"], rel=1e-9)


def test_an_early_stopped_search_that_found_nothing_feasible_claims_nothing():
    def nowhere(params):                                        # V̇ ≤ +a(w³ + e³): no admissible constants anywhere
        return dataclasses.replace(family(params), vdot=params["a"] * (w**3 + e**3))

    params, est = search_parameters(nowhere, {"a": (0.5, 2.0)}, objective=lambda r: -r["c_tilde"], maxiter=200,
                                    popsize=5, grid=9, stall=3)
    assert est is None and 0.5 <= params["a"] <= 2.0


@pytest.mark.parametrize("stall", [0, -1, 2.5, True])
def test_the_early_stop_needs_a_positive_number_of_generations(stall):
    with pytest.raises(InputError, match="stall"):
        search_parameters(family, {"a": (0.5, 2.0)}, objective=lambda r: -r["c_tilde"], maxiter=5, popsize=5,
                          grid=9, stall=stall)
