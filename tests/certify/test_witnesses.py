"""Adversarial witnesses (lkverify.certify.steps.witnesses): true bounds are never refuted, mutations are.

The main model is paper 002's (unit vector s, angular velocity ω, target r, window integrals
J, K); frames are paper 000's (s1, s2, s3 one rotation, L = s1×r1 + s2×r2) and, with the
time-varying damping h(t) = (1+t)^{−7/8} at a given witness time, paper 001's.  A
refutation must be proved at an exact point (lo > 0); the reported witness is recomputed
here independently from its floats (the sums over the pieces, the weight ξ + τ − t integrated
by hand, ḣ(1) by hand) and must lie in the region; a frame must be exactly orthonormal and
right-handed at the exact point.
"""

import json
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

@pytest.mark.slow
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
    wit = search([LAMBDA_J, OMEGA_K], b * (lam + c7 * tau) * w * I, values=VALUES, exists=[c7], nonnegative=[lam])
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


@pytest.mark.slow
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
    assert search_x(lhs, 0, pieces=(1,), structured=False) is None
    wit = search_x(lhs, 0)
    assert wit is not None and wit.exact["pieces"] >= 2
    values = [p[0] for p in wit.history["x"]]
    assert min(values) < 0 < max(values)


def test_weights_are_integrated_exactly():
    # ∫(ξ + τ − t)x² ≤ ½∫x²: an equality for constant histories (exact sums: not refuted), false otherwise
    lhs = window_integral(x(xi)[0] ** 2, TAUX, weight=xi + TAUX - t)
    assert search_x(lhs, IX.symbol / 2, pieces=(1,), structured=False) is None
    wit = search_x(lhs, IX.symbol / 2, pieces=(2, 3))
    assert wit is not None and wit.violation[0] > 0
    assert search_x(lhs, IX.symbol) is None             # the weight is ≤ 1


# -- 5. bad input ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("lhs, match", [
    (sympy.Integral(sympy.Integral(x(zeta)[0] ** 2, (zeta, xi, t)), (xi, t - TAUX, t)), "nested"),
    (x(t + 1)[0], "future"),
    (window_integral(x(xi - 1)[0], TAUX), "shifted"),
    (sympy.Derivative(X, t), "derivative"),
])
def test_unsupported_constructs(lhs, match):
    with pytest.raises(UnsupportedClaim, match=match) as info:
        search_x(lhs, 0)
    assert isinstance(info.value, UnsupportedInput) and isinstance(info.value, InputError)


@pytest.mark.parametrize("lhs, rhs, kw, match", [
    (HX(t) * X ** 2, -1, {}, "time-varying"),
    (X ** 2, 0, {"time": "1"}, "time: expected a real number"),
    (X ** 2, 0, {"time": (1, 0)}, "lo < hi"),
    (X ** 2, 0, {"time": (0, 1, 2)}, "pair"),
    (X ** 2, 0, {"time": float("nan")}, "finite"),
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


class _FastClock:
    """A stub of the time module for lkverify.options: every reading is 1000 s after the last."""

    def __init__(self):
        self.now = 0.0

    def monotonic(self):
        self.now += 1000.0
        return self.now


def test_budget_is_honoured(monkeypatch):
    # a clock that races: a wall-clock budget is spent at once, the search says it was cut (no timing)
    from lkverify import options
    from lkverify.certify.steps.witnesses import find_witness

    lhs = window_integral(x(xi)[0] ** 2, TAUX) / 2 - window_integral(x(xi)[0], TAUX) ** 2
    monkeypatch.setattr(options, "time", _FastClock())
    out = find_witness(lhs, 0, system=SYSX, values=PX.resolve({}), measures=[IX], starts=10 ** 6, budget=0.5)
    assert out.witness is None and not out.complete and out.starts < 10
    assert out.text().startswith("the budget was spent before this witness search finished")


def test_without_a_budget_the_result_does_not_depend_on_the_clock(monkeypatch):
    # deterministic work limits: the same witness with a normal clock and with one that races
    from lkverify import options

    lhs = window_integral(x(xi)[0] ** 2, TAUX) / 2 - window_integral(x(xi)[0], TAUX) ** 2
    normal = search_witness(lhs, 0, system=SYSX, values=PX.resolve({}), measures=[IX], starts=4)
    monkeypatch.setattr(options, "time", _FastClock())
    raced = search_witness(lhs, 0, system=SYSX, values=PX.resolve({}), measures=[IX], starts=4)
    assert normal is not None and raced is not None and normal.to_json() == raced.to_json()
    assert search_x(X * XD, (X ** 2 + XD ** 2) / 2) is None       # a true claim: searched to its end


def test_structured_grids_and_bad_grids():
    from lkverify.certify.steps.witnesses import find_witness

    lhs = window_integral(x(xi)[0] ** 2, TAUX, weight=xi + TAUX - t)       # ≤ I, weight 1 at ξ = t only
    out = find_witness(lhs, IX.symbol * (1 - R(1, 10 ** 5)), system=SYSX, values=PX.resolve({}), measures=[IX],
                       pieces=(("ends", "1/1000000"),), starts=1)
    assert out.witness is not None and out.pieces == (("ends", "1/1000000"),)
    with pytest.raises(InputError, match="end grids"):
        find_witness(lhs, IX.symbol, system=SYSX, values=PX.resolve({}), measures=[IX], pieces=(("ends", 2),))


def test_recheck_requires_every_coefficient_nonnegative():
    # white box: lhs − rhs = 1 − c·x(t)²; a point with x ≠ 0 works only for small c, x = 0 for every c
    from lkverify.certify.steps.witnesses import _Model, _Problem, _recheck

    c = sympy.Symbol("c", nonnegative=True)
    model = _Model(_Problem(sympy.Integer(1), c * X ** 2, SYSX, PX.resolve({}), [], None, [c], []), 1)
    assert model.nparams == 1
    assert _recheck(model, np.array([0.5])) is None
    wit = _recheck(model, np.array([0.0]))
    assert wit is not None and wit.violation == (1.0, 1.0) and wit.coefficients == {"c": (0.0, 0.0)}


# -- 7. frames: s1, s2, s3 are one rotation (paper 000) ------------------------------------------------

from lkverify.proofs.aleksandrov2026 import equations as eq0  # noqa: E402

V0 = eq0.P.resolve({"beta": "-1"}, use_defaults=True)          # β < 0 (Theorem 2); γ has no value
E1, E2 = norm_measure("e1", eq0.s1(t) - eq0.r1), norm_measure("e2", eq0.s2(t) - eq0.r2)
W0 = norm_measure("w", eq0.omega(t))
M1, M2 = sup_norm("m1", eq0.s1(xi) - eq0.r1, window=eq0.tau), sup_norm("m2", eq0.s2(xi) - eq0.r2, window=eq0.tau)
REGION0 = Region({M1: R(1, 5), M2: R(1, 5), W0: R(1, 5)})
MEASURES0 = [E1, E2, W0, M1, M2]
e1, e2, w0, m1, m2 = E1.symbol, E2.symbol, W0.symbol, M1.symbol, M2.symbol
R0 = np.array([[1, 1, 0], [-1, 1, 0], [0, 0, np.sqrt(2)]]) / np.sqrt(2)      # rows r1, r2, r3
FRAME = ("s1", "s2", "s3")


def search0(lhs, rhs, **kw):
    kw.setdefault("region", REGION0)
    return search_witness(lhs, rhs, system=eq0.system, values=V0, measures=MEASURES0, **kw)


def torque(triad, refs=R0):
    """L = s1×r1 + s2×r2 (α1 = α2 = 1) and f = ½(‖s1 − r1‖² + ‖s2 − r2‖²) from floats."""
    L = np.cross(triad[0], refs[0]) + np.cross(triad[1], refs[1])
    f = (np.linalg.norm(triad[0] - refs[0]) ** 2 + np.linalg.norm(triad[1] - refs[1]) ** 2) / 2
    return L, f


def assert_frame(triad, refs=R0, delta=0.2):
    """Orthonormal, right-handed, s1 and s2 inside their caps (floats)."""
    T = np.array(triad)
    assert np.allclose(T @ T.T, np.eye(3), atol=1e-12) and np.allclose(np.cross(T[0], T[1]), T[2], atol=1e-12)
    for i in (0, 1):
        assert np.linalg.norm(T[i] - refs[i]) <= delta + 1e-12


def assert_exact_frame(witness, label):
    """The exact triad of the slot ``label`` is exactly orthonormal with s3 = s1 × s2."""
    S = sympy.Matrix(3, 3, [sympy.sympify(v) for v in witness.exact["vectors"][label]]).T     # columns s_i
    assert all(sympy.expand(e) == 0 for e in S.T * S - sympy.eye(3))
    assert all(sympy.expand(e) == 0 for e in S[:, 2] - S[:, 0].cross(S[:, 1]))
    assert len(witness.exact["parameters"][label]) == 3               # the rational Cayley vector k
    assert all(sympy.Rational(q).is_Rational for q in witness.exact["parameters"][label])


NU0 = 0.3
THEOREM2_LHS = -eq0.gamma * eq0.beta * eq0.f(t) ** eq0.nu * dot(eq0.omega(t), eq0.L(t))


def test_printed_theorem2_step_with_negative_beta_is_refuted():
    # −γβf^ν ωᵀL ≤ γβc7‖ω‖(e1^{2ν+1} + e2^{2ν+1}): with β < 0 the right-hand side is ≤ 0
    rhs = eq0.gamma * eq0.beta * c7 * w0 * (e1 ** (2 * eq0.nu + 1) + e2 ** (2 * eq0.nu + 1))
    wit = search0(THEOREM2_LHS, rhs, exists=[c7], nonnegative=[eq0.gamma])
    assert wit is not None and wit.violation[0] > 0
    assert wit.exact["factors"] == ["gamma"] and set(wit.coefficients) == {"c7"}
    assert wit.coefficients["c7"][0] >= 0
    triad = [vec(wit, n) for n in FRAME]
    assert_frame(triad)
    assert_exact_frame(wit, "s1,s2,s3(t)")
    om = vec(wit, "omega")
    assert np.linalg.norm(om) <= 0.2 + 1e-12
    L, f = torque(triad)
    A = f ** NU0 * om @ L                                          # (lhs − rhs)/γ at c7 = 0, β = −1
    d1, d2 = (np.linalg.norm(triad[i] - R0[i]) for i in (0, 1))
    assert A == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    assert np.linalg.norm(om) * (d1 ** 1.6 + d2 ** 1.6) == pytest.approx(sum(wit.coefficients["c7"]) / 2, rel=1e-6)
    assert wit.terms["lhs"] == pytest.approx(A, rel=1e-6)         # per unit γ
    assert wit.measures["e1"] == pytest.approx(d1, rel=1e-9)
    assert "(lhs − rhs)/gamma" in wit.text() and "gamma > 0, c7 ≥ 0" in wit.text()


def test_theorem2_step_with_abs_beta_is_not_refuted():
    # with |β| the bound holds for c7 large: no witness works for every c7 ≥ 0
    rhs = eq0.gamma * abs(eq0.beta) * c7 * w0 * (e1 ** (2 * eq0.nu + 1) + e2 ** (2 * eq0.nu + 1))
    assert search0(THEOREM2_LHS, rhs, exists=[c7], nonnegative=[eq0.gamma]) is None


def test_triangle_bound_on_the_torque_is_not_refuted():
    # ‖L‖ ≤ α1‖s1 × r1‖ + α2‖s2 × r2‖ ≤ α1 e1 + α2 e2 (‖s × r‖ = ‖(s − r) × r‖ ≤ ‖s − r‖)
    norm_L = sympy.sqrt(norm_squared(eq0.L(t)))
    assert search0(norm_L, eq0.alpha1 * e1 + eq0.alpha2 * e2) is None
    assert search0(norm_squared(eq0.L(t)), 2 * (eq0.alpha1 ** 2 * e1 ** 2 + eq0.alpha2 ** 2 * e2 ** 2)) is None


def test_false_torque_bound_is_refuted():
    # about r3 by θ: ‖L‖² = 4 sin²θ, e1² + e2² = 8 sin²(θ/2): ‖L‖² ≤ 1.9(e1² + e2²) fails for θ < 25°
    wit = search0(norm_squared(eq0.L(t)), R(19, 10) * (eq0.alpha1 ** 2 * e1 ** 2 + eq0.alpha2 ** 2 * e2 ** 2))
    assert wit is not None and wit.violation[0] > 0
    triad = [vec(wit, n) for n in FRAME]
    assert_frame(triad)
    assert_exact_frame(wit, "s1,s2,s3(t)")
    L, _ = torque(triad)
    d2 = sum(np.linalg.norm(triad[i] - R0[i]) ** 2 for i in (0, 1))
    assert L @ L - 1.9 * d2 == pytest.approx(sum(wit.violation) / 2, rel=1e-6)


def test_frame_constraints_are_used():
    s1, s2, s3 = (v(t) for v in (eq0.s1, eq0.s2, eq0.s3))
    # orthonormal and right-handed at every exact point (no region: all of SO(3))
    assert search0(dot(s1, s2) ** 2 + norm_squared(s3 - cross(s1, s2)), 0, region=None) is None
    wit = search0(-dot(s3, eq0.r3), -R(99, 100), region=None)        # large rotations are reachable
    assert wit is not None and vec(wit, "s3") @ R0[2] < -0.99
    assert_exact_frame(wit, "s1,s2,s3(t)")


@pytest.mark.slow
def test_delayed_frame_values_are_rotations_of_their_own():
    # ‖L(t) − L(t − τ)‖ ≤ ‖L(t)‖ + ‖L(t − τ)‖ ≤ 2(m1 + m2); the factor 2 dropped fails (±θ about r3)
    lhs = dot(eq0.omega(t), eq0.L(t) - eq0.L(t - eq0.tau))
    assert search0(lhs, 2 * w0 * (m1 + m2)) is None
    wit = search0(lhs, w0 * (m1 + m2))
    assert wit is not None and wit.violation[0] > 0
    now, before = ([vec(wit, n, when) for n in FRAME] for when in ("t", "t - 1"))
    assert_frame(now)
    assert_frame(before)
    assert_exact_frame(wit, "s1,s2,s3(t - 1)")
    assert wit.measures["m1"] == pytest.approx(max(np.linalg.norm(v[0] - R0[0]) for v in (now, before)), rel=1e-9)
    om = vec(wit, "omega")
    value = om @ (torque(now)[0] - torque(before)[0]) - np.linalg.norm(om) * (wit.measures["m1"] + wit.measures["m2"])
    assert value == pytest.approx(sum(wit.violation) / 2, rel=1e-6)


def test_frame_histories_are_rotations():
    # ½∫(s1·r3)² ≤ (∫ s1·r3)² holds for constant histories and fails when s1 tips both ways
    q = window_integral(dot(eq0.s1(xi), eq0.r3) ** 2, eq0.tau) / 2 - window_integral(dot(eq0.s1(xi), eq0.r3), eq0.tau) ** 2
    assert search0(q, 0, pieces=(1,)) is None
    wit = search0(q, 0)
    assert wit is not None and wit.exact["pieces"] >= 2
    offsets = [0.0 if b == "t" else float(sympy.sympify(b.replace("t - ", ""))) for b in wit.exact["breakpoints"]]
    tips = []
    for k in range(wit.exact["pieces"]):
        triad = [np.array(wit.history[n][k]) for n in FRAME]
        assert_frame(triad)
        tips.append((offsets[k] - offsets[k + 1], triad[0] @ R0[2]))
    assert min(v for _, v in tips) < 0 < max(v for _, v in tips)
    value = sum(h * v ** 2 for h, v in tips) / 2 - sum(h * v for h, v in tips) ** 2
    assert value == pytest.approx(sum(wit.violation) / 2, rel=1e-6)


# -- 8. explicit time: h(t), ḣ(t) at the witness time (paper 001) ---------------------------------------

from lkverify.proofs.aleksandrov2017 import equations as eq1  # noqa: E402

V1 = eq1.P.resolve({}, use_defaults=True)                       # h = (1+t)^(−7/8), ν = 1
F1, F2 = norm_measure("e1", eq1.s1(t) - eq1.r1), norm_measure("e2", eq1.s2(t) - eq1.r2)
W1 = norm_measure("w", eq1.omega(t))
REGION1 = Region({F1: R(1, 5), F2: R(1, 5), W1: R(1, 5)})       # bounds at t (kind norm)
alpha6 = sympy.Symbol("alpha6", nonnegative=True)
HDOT = eq1.h(t).diff(t)
THEOREM1_LHS = eq1.gamma * eq1.nu * eq1.h(t) ** (eq1.nu - 1) * HDOT * dot(eq1.omega(t), eq1.J * eq1.eta)


def search1(lhs, rhs, **kw):
    return search_witness(lhs, rhs, system=eq1.system, values=V1, measures=[F1, F2, W1], region=REGION1,
                          exists=[alpha6], nonnegative=[eq1.gamma], **kw)


def test_printed_theorem1_term_is_refuted_at_time_1():
    # γνh^{ν−1}ḣ ωᵀJη ≤ γα6(e1 + e2)h^{ν−1}ḣ‖ω‖: ḣ < 0 makes the printed right-hand side ≤ 0
    rhs = eq1.gamma * alpha6 * (F1.symbol + F2.symbol) * eq1.h(t) ** (eq1.nu - 1) * HDOT * W1.symbol
    wit = search1(THEOREM1_LHS, rhs, time=1)
    assert wit is not None and wit.violation[0] > 0
    assert wit.exact["t"] == "1" and wit.exact["time"] == "given" and wit.text().startswith("at t = 1, ")
    assert wit.exact["factors"] == ["gamma"] and wit.coefficients["alpha6"][0] >= 0
    refs = np.eye(3)
    triad = [vec(wit, n) for n in FRAME]
    assert_frame(triad, refs)
    assert_exact_frame(wit, "s1,s2,s3(t)")
    om = vec(wit, "omega")
    hdot = -7 / 8 * 2 ** (-15 / 8)                                  # ḣ(1)
    eta = np.cross(triad[0], refs[0]) + np.cross(triad[1], refs[1])
    assert hdot * om @ (np.diag([5, 6, 4]) @ eta) == pytest.approx(sum(wit.violation) / 2, rel=1e-6)
    d = sum(np.linalg.norm(triad[i] - refs[i]) for i in (0, 1))
    assert -hdot * d * np.linalg.norm(om) == pytest.approx(sum(wit.coefficients["alpha6"]) / 2, rel=1e-6)


def test_theorem1_term_with_abs_hdot_is_not_refuted():
    # |ωᵀJη| ≤ ‖J‖‖ω‖‖η‖ ≤ 6(e1 + e2)‖ω‖: true for α6 ≥ 6, so never refuted for every α6
    rhs = eq1.gamma * alpha6 * (F1.symbol + F2.symbol) * eq1.h(t) ** (eq1.nu - 1) * abs(HDOT) * W1.symbol
    assert search1(THEOREM1_LHS, rhs, time=1) is None


def test_explicit_time_needs_time_argument():
    rhs = eq1.gamma * alpha6 * (F1.symbol + F2.symbol) * HDOT * W1.symbol
    with pytest.raises(InputError, match="time=") as info:
        search1(THEOREM1_LHS, rhs)
    assert not isinstance(info.value, UnsupportedInput)


def test_the_witness_time_is_used():
    # h(t) = 1 + t: h x² ≤ (3/2)x² holds at t = 0 and fails at t = 1; searched in [0, 1] at t > 1/2
    lhs, rhs = HX(t) * X ** 2, R(3, 2) * X ** 2
    assert search_x(lhs, rhs, time=0) is None
    wit = search_x(lhs, rhs, time=1)
    assert wit is not None and wit.exact["t"] == "1"
    assert wit.violation[0] == pytest.approx(wit.state["x_1(t)"] ** 2 / 2, rel=1e-6)
    wit = search_x(lhs, rhs, time=(0, 1))
    t_w = sympy.Rational(wit.exact["t"])
    assert wit.exact["time"] == "searched in [0, 1]" and R(1, 2) < t_w <= 1
    assert json.loads(json.dumps(wit.to_json()))["exact"]["t"] == str(t_w)


def test_windows_end_at_the_witness_time():
    # ∫_{t−1}^t (1 + ξ)x(ξ)² dξ: at t = 1 the weight is in [1, 2] (3/2 for a constant history), at t = 0 in [0, 1]
    lhs = window_integral(HX(xi) * x(xi)[0] ** 2, TAUX)
    assert search_x(lhs, R(7, 5) * IX.symbol, time=0) is None
    wit = search_x(lhs, R(7, 5) * IX.symbol, time=1)
    assert wit is not None and wit.violation[0] > 0
    assert search_x(lhs, 2 * IX.symbol, time=1) is None
