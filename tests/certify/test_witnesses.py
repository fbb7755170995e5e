"""Adversarial witnesses (lkverify.certify.steps.witnesses): true bounds are never refuted, mutations are.

The model is paper 002's (unit vector s, angular velocity ω, target r, window integrals J, K).
A refutation must be proved at an exact point (lo > 0); the reported witness is recomputed
here independently from its floats (the sums over the pieces, the weight ξ + τ − t integrated
by hand) and must lie in the region.
"""

import json
import time
from fractions import Fraction

import numpy as np
import pytest
import sympy

from lkverify import (Equation, InputError, Parameters, System, Term, UnsupportedInput, Vector, cross, dot,
                      memory_integral, norm_squared, t, window_integral, xi, zeta)
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure, window_norm
from lkverify.certify.steps.witnesses import UnsupportedClaim, Witness, search_witness
from lkverify.proofs.aleksandrov2023.equations import P, b, lam, mu, omega, r, s, system, tau
from lkverify.proofs.aleksandrov2023.theorem3 import structured_Vdot

R = sympy.Rational
VALUES = P.resolve({}, use_defaults=True)               # λ has no default: free
VALUES_LAM = P.resolve({"lam": 10}, use_defaults=True)
E = norm_measure("e", s(t) - r)
W = norm_measure("w", omega(t))
JM = window_norm("j", s(xi) - r, p=3, window=tau)
IM = window_integral_measure("I", s(xi) - r, p=mu, window=tau)
MEASURES = [E, W, JM, IM]
SUP = sup_norm("m", s(xi) - r, window=tau)
REGION = Region({SUP: R(1, 10), W: R(1, 5)})
e, w, I = E.symbol, W.symbol, IM.symbol
c7 = sympy.Symbol("c7", nonnegative=True)

# the two ω–history terms of the exact V̇, λbωᵀJ and −b((ω×s)×r)ᵀF⁻¹K (found by structure, not label)
HISTORY_TERMS = [term for term in structured_Vdot
                 if term.expr.has(sympy.Integral) and term.expr.has(omega.functions[0](t))]
LAMBDA_J = next(term for term in HISTORY_TERMS if term.expr.has(lam))
OMEGA_K = next(term for term in HISTORY_TERMS if not term.expr.has(lam))
assert len(HISTORY_TERMS) == 2
RV = np.ones(3) / np.sqrt(3)


def search(lhs, rhs, values=VALUES_LAM, **kw):
    kw.setdefault("region", REGION)
    return search_witness(lhs, rhs, system=system, values=values, measures=MEASURES, **kw)


def vec(witness, name, when="t"):
    return np.array([witness.state[f"{name}_{a}({when})"] for a in "xyz"])


def pieces(witness):
    """(offsets from t, piece values) of the witness's history of s, oldest piece first."""
    offsets = [Fraction(0) if p == "t" else Fraction(str(sympy.sympify(p.replace("t - ", "")))) for p in
               witness.exact["breakpoints"]]
    return [float(o) for o in offsets], [np.array(v) for v in witness.history["s"]]


def assert_in_region(witness):
    st = vec(witness, "s")
    _, hist = pieces(witness)
    for v in [st] + hist:
        assert abs(np.linalg.norm(v) - 1) < 1e-12                     # exactly unit (angles)
        assert np.linalg.norm(v - RV) <= 0.1 + 1e-12                  # sup ‖s(ξ) − r‖ ≤ 1/10, s(t) included
    assert np.linalg.norm(vec(witness, "omega")) <= 0.2 + 1e-12       # ‖ω(t)‖ ≤ 1/5
    assert witness.measures["I"] <= 1 * 0.1 ** 2 + 1e-12


def sums(witness):
    """J, K, I recomputed from the witness's pieces at t = 0 (τ = 1, μ = 2)."""
    offsets, hist = pieces(witness)
    J, K, Iv = np.zeros(3), np.zeros(3), 0.0
    for k, v in enumerate(hist):
        a, c = -offsets[k], -offsets[k + 1]            # the piece is [a, c] ⊂ [−1, 0]
        d = np.linalg.norm(v - RV)
        q = d * np.cross(v, RV)
        J += (c - a) * q
        K += ((c + 1) ** 2 - (a + 1) ** 2) / 2 * q     # ∫_a^c (ξ + τ − t) dξ
        Iv += (c - a) * d ** 2
    return J, K, Iv


# -- 1. true bounds are not refuted ------------------------------------------------------------

def test_cauchy_schwarz_bound_is_not_refuted():
    # |λbωᵀJ| ≤ λ|b|‖ω‖∫‖s − r‖^μ since ‖‖s−r‖^{μ−1} s×r‖ ≤ ‖s − r‖^μ
    assert search([LAMBDA_J], lam * abs(b) * w * I) is None


def test_an_equality_is_not_refuted():
    # ½‖s − r‖² = e²/2: the float difference is rounding noise; the exact recheck never confirms it
    assert search(norm_squared(s(t) - r) / 2, e ** 2 / 2) is None


# -- 2. mutations are refuted, at an exact point inside the region -----------------------------------

def test_dropped_absolute_value_is_refuted():
    wit = search([LAMBDA_J], lam * b * w * I)        # b = −1: a negative right-hand side
    assert isinstance(wit, Witness) and wit.violation[0] > 0
    assert wit.violation[0] <= wit.violation[1]
    assert_in_region(wit)
    J, _, Iv = sums(wit)
    om = vec(wit, "omega")
    expected = 10 * (-1) * om @ J - 10 * (-1) * np.linalg.norm(om) * Iv
    assert expected == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    assert wit.terms["rhs"] == pytest.approx(-10 * np.linalg.norm(om) * Iv, rel=1e-6)
    assert wit.measures["I"] == pytest.approx(Iv, rel=1e-9)


def test_constant_too_small_is_refuted():
    wit = search(norm_squared(s(t) - r) / 2, R(49, 100) * e ** 2)
    assert wit is not None and 0 < wit.violation[0] <= wit.violation[1] <= R(1, 100) * R(1, 100) + 1e-15
    assert_in_region(wit)
    d = np.linalg.norm(vec(wit, "s") - RV)
    assert wit.measures["e"] == pytest.approx(d, rel=1e-9)
    assert d ** 2 / 100 == pytest.approx(sum(wit.violation) / 2, rel=1e-6)


def test_exponent_off_by_one_is_refuted():
    # ‖s × r‖² ≈ e² near r: ≤ e³ fails on the small region
    sxr = cross(s(t), r)
    wit = search(dot(sxr, sxr), e ** 3)
    assert wit is not None and wit.violation[0] > 0
    assert_in_region(wit)
    st = vec(wit, "s")
    value = np.linalg.norm(np.cross(st, RV)) ** 2 - np.linalg.norm(st - RV) ** 3
    assert value == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    assert "lhs" in wit.terms and "rhs" in wit.terms


# -- 3. the printed bound of Theorem 3 (paper 002) ---------------------------------------------------

def test_printed_theorem3_bound_is_refuted_for_every_c7_and_lambda():
    start = time.monotonic()
    wit = search([LAMBDA_J, OMEGA_K], b * (lam + c7 * tau) * w * I, values=VALUES, exists=[c7], nonnegative=[lam])
    assert time.monotonic() - start < 10
    assert wit is not None and wit.violation[0] > 0
    assert set(wit.coefficients) == {"c7", "lam"}
    assert all(lo >= 0 for lo, hi in wit.coefficients.values())
    assert_in_region(wit)
    # recompute A (λ = c7 = 0) and the coefficient of λ from the witness's floats
    J, K, Iv = sums(wit)
    st, om = vec(wit, "s"), vec(wit, "omega")
    A = np.cross(np.cross(om, st), RV) @ K            # −b((ω×s)×r)ᵀF⁻¹K with b = −1, F = I
    B_lam = -om @ J + np.linalg.norm(om) * Iv         # bωᵀJ − b‖ω‖I
    assert A == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    assert B_lam == pytest.approx(sum(wit.coefficients["lam"]) / 2, rel=1e-6, abs=1e-15)
    assert wit.coefficients["c7"][0] == pytest.approx(np.linalg.norm(om) * Iv, rel=1e-6)   # −bτ‖ω‖I
    assert wit.terms[OMEGA_K.text] == pytest.approx(A, rel=1e-6)
    assert "for every c7 ≥ 0, lam ≥ 0" in wit.text()


def test_printed_theorem3_bound_with_a_value_of_lambda_is_refuted():
    wit = search([LAMBDA_J, OMEGA_K], b * (lam + c7 * tau) * w * I, exists=["c7"])
    assert wit is not None and wit.violation[0] > 0 and set(wit.coefficients) == {"c7"}


def test_corrected_theorem3_bound_is_not_refuted():
    # with |b| a large c7 makes the bound true: no witness can work for every c7 ≥ 0
    assert search([LAMBDA_J, OMEGA_K], abs(b) * (lam + c7 * tau) * w * I, exists=[c7]) is None


# -- 4. the unit-vector constraint is used ----------------------------------------------------------

def test_true_only_because_s_is_unit():
    st = s(t)
    assert search(dot(st, st), 1, region=None) is None
    sxr = cross(st, r)                                # ‖s × r‖² + (s·r)² = ‖s‖²‖r‖² = 1
    assert search(dot(sxr, sxr) + dot(st, r) ** 2, 1, region=None) is None


def test_the_same_claim_for_a_free_vector_is_refuted():
    om = omega(t)
    wit = search(dot(om, om), 1, region=None)
    assert wit is not None and wit.violation[0] > 0
    assert np.linalg.norm(vec(wit, "omega")) > 1


# -- the witness family: delayed values, pieces, weights ----------------------------------------------

PX = Parameters()
TAUX = PX.delay("tau", default=1)
HX = PX.coefficient("h", default="1 + t")
x = Vector("x", 1)
SYSX = System([Equation(x, [Term(-x(t - TAUX)[0])])], parameters=PX)
X, XD = x(t)[0], x(t - TAUX)[0]
IX = window_integral_measure("Ix", x(xi), p=2, window=TAUX)


def search_x(lhs, rhs, **kw):
    return search_witness(lhs, rhs, system=SYSX, values=PX.resolve({}), measures=[IX], starts=8, **kw)


def test_delayed_values_are_independent_of_the_value_at_t():
    wit = search_x(X * XD, X ** 2)
    assert wit is not None and wit.violation[0] > 0
    a, d = wit.state["x_1(t)"], wit.state["x_1(t - 1)"]
    assert a * d - a ** 2 == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    assert search_x(X * XD, (X ** 2 + XD ** 2) / 2) is None


def test_a_history_with_several_pieces_is_needed():
    # ½∫x² ≤ (∫x)² holds for constant histories and fails for oscillating ones
    lhs = window_integral(x(xi)[0] ** 2, TAUX) / 2 - window_integral(x(xi)[0], TAUX) ** 2
    assert search_x(lhs, 0, pieces=(1,)) is None
    wit = search_x(lhs, 0)
    assert wit is not None and wit.exact["pieces"] >= 2
    values = [p[0] for p in wit.history["x"]]
    assert min(values) < 0 < max(values)


def test_weights_are_integrated_exactly():
    # ∫(ξ + τ − t)x² ≤ ½∫x²: an equality for constant histories (exact sums: not refuted), false otherwise
    lhs = window_integral(x(xi)[0] ** 2, TAUX, weight=xi + TAUX - t)
    assert search_x(lhs, IX.symbol / 2, pieces=(1,)) is None
    wit = search_x(lhs, IX.symbol / 2, pieces=(2, 3))
    assert wit is not None and wit.violation[0] > 0
    assert search_x(lhs, IX.symbol) is None             # the weight is ≤ 1


# -- 5. bad input ---------------------------------------------------------------------------------------

def test_frames_are_unsupported():
    from lkverify.proofs.aleksandrov2017.equations import P as P17, s1, system as system17

    with pytest.raises(UnsupportedClaim, match="frame") as info:
        search_witness(s1(t)[0], 2, system=system17, values=P17.resolve({}), measures=[])
    assert isinstance(info.value, UnsupportedInput) and isinstance(info.value, InputError)


@pytest.mark.parametrize("lhs, match", [
    (sympy.Integral(sympy.Integral(x(zeta)[0] ** 2, (zeta, xi, t)), (xi, t - TAUX, t)), "nested"),
    (memory_integral(x(xi)[0] ** 2), "memory integrals"),
    (x(t + 1)[0], "future"),
    (window_integral(x(xi - 1)[0], TAUX), "shifted"),
    (sympy.Derivative(X, t), "derivative"),
])
def test_unsupported_constructs(lhs, match):
    with pytest.raises(UnsupportedClaim, match=match):
        search_x(lhs, 0)


@pytest.mark.parametrize("lhs, rhs, kw, match", [
    (HX(t) * X ** 2, -1, {}, "time-varying"),
    (X ** 2, sympy.Symbol("c") ** 2, {"exists": ["c"]}, "affine"),
    (X ** 2, sympy.Symbol("c"), {}, "without one"),
    ("x**2", 0, {}, "string"),
    (X ** 2, 0, {"pieces": (0,)}, "pieces"),
])
def test_bad_input(lhs, rhs, kw, match):
    with pytest.raises(InputError, match=match):
        search_x(lhs, rhs, **kw)


def test_missing_parameter_value():
    with pytest.raises(InputError, match="lam"):
        search([LAMBDA_J], 0, values=VALUES)


# -- 6. output, budget ----------------------------------------------------------------------------------

def test_witness_json_and_text():
    wit = search_x(X * XD, X ** 2)
    data = json.loads(json.dumps(wit.to_json()))
    assert data["violation"][0] > 0 and "x_1(t - 1)" in data["state"]
    assert "parameters" in data["exact"] and "vectors" in data["exact"]
    line = wit.text()
    assert "\n" not in line and line.endswith("> 0") and "x(t - 1)" in line


def test_budget_is_honoured():
    lhs = window_integral(x(xi)[0] ** 2, TAUX) / 2 - window_integral(x(xi)[0], TAUX) ** 2
    start = time.monotonic()
    search_witness(lhs, 0, system=SYSX, values=PX.resolve({}), measures=[IX], starts=10 ** 6, budget=0.5)
    assert time.monotonic() - start < 5


def test_recheck_requires_every_coefficient_nonnegative():
    # white box: lhs − rhs = 1 − c·x(t)²; a point with x ≠ 0 works only for small c, x = 0 for every c
    from lkverify.certify.steps.witnesses import _Model, _Problem, _recheck

    c = sympy.Symbol("c", nonnegative=True)
    model = _Model(_Problem(sympy.Integer(1), c * X ** 2, SYSX, PX.resolve({}), [], None, [c], []), 1)
    assert model.nparams == 1
    assert _recheck(model, np.array([0.5])) is None
    wit = _recheck(model, np.array([0.0]))
    assert wit is not None and wit.violation == (1.0, 1.0) and wit.coefficients == {"c": (0.0, 0.0)}
