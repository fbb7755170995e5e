"""Certified constants (lkverify.certify.bounds) against closed forms and slow reference paths.

Reference paths: enclosures are checked against point values at sampled points
(mpmath at 50 digits, an independent evaluator), certified suprema against dense
float grids and closed forms, counterexamples against exact SymPy evaluation at
the reported rational point.
"""

import json
import math

import mpmath
import numpy as np
import pytest
import sympy
from flint import arb

from lkverify.certify.affine import AffineForm
from lkverify.certify.bounds import (
    ArbFunction, ball_point, best_constant, certify_nonpositive, certify_positive, check_constant,
    compile_arb, rotation_axis_angle, sup_bound, unit_vector_angles, unit_vector_near,
)
from lkverify.certify.functions import lambdify_real
from lkverify.errors import InputError
from lkverify.options import Accuracy, Budget
from lkverify.status import Status

x, y, z = sympy.symbols("x y z")
R = sympy.Rational


def exact_value(expr, point):
    """expr at a point of exact binary floats, by SymPy at 50 digits (the slow path)."""
    by_name = {str(s): s for s in expr.free_symbols}
    subs = {by_name[k]: sympy.Rational(v) for k, v in point.items() if k in by_name}
    assert set(subs) == expr.free_symbols
    return sympy.N(expr.subs(subs), 50)


# ---------------------------------------------------------------------------
# the compiler
# ---------------------------------------------------------------------------

def test_real_power_of_a_ball_touching_zero_is_0_to_hi_p():
    xn = sympy.Symbol("x", nonnegative=True)
    f = compile_arb(xn ** R(13, 10), [xn])
    for hi in (1.0, 1e-4, 3.0):
        y_ = f((0, hi))
        assert y_.is_finite()
        assert y_.contains(0) and y_.contains(arb(hi) ** arb(1.3))
        assert float(y_.upper()) <= hi ** 1.3 * (1 + 1e-8)        # radius rounding (30-bit) only
        assert float(y_.lower()) >= -1e-8 * hi ** 1.3          # ball rounding only
    # p < 1: the same, and the derivative (p x^(p-1)) is honestly unbounded at 0
    g = compile_arb(xn ** R(3, 10), [xn])
    assert g((0, 1)).contains(0) and g((0, 1)).contains(1)
    assert not g.value_and_gradient((0, 1))[1][0].is_finite()
    # base of unknown sign: a ball reaching below 0 is "possibly undefined" -> not finite
    h = compile_arb(x ** R(13, 10), [x])
    assert not h((-0.5, 1)).is_finite()
    assert not h(-2).is_finite()
    assert h(2).contains(arb(2) ** arb(1.3))


def test_norm_power_at_the_origin_is_structurally_nonnegative():
    f = compile_arb(sympy.sqrt(x**2 + y**2) ** R(13, 5), [x, y])   # ‖v‖^(2ν+2), ν = 0.3
    assert f.nonnegative
    v = f((-1e-3, 1e-3), (0, 1e-3))
    assert v.is_finite() and v.contains(0)
    assert float(v.upper()) <= (math.sqrt(2) * 1e-3) ** 2.6 * (1 + 1e-6)


def test_enclosures_contain_the_values_at_sampled_points():
    """Fast path (ball enclosures on boxes) against the slow path (mpmath at 50 digits)."""
    exprs = [
        x * sympy.exp(-x) + sympy.sin(3 * y) * sympy.cos(x * y),
        sympy.Abs(x - y) + sympy.Max(x, y ** 2) - sympy.Min(x, R(1, 3)),
        sympy.sqrt(x ** 2 + y ** 2 + R(1, 10)) / (2 + sympy.cos(x + y)),
        sympy.log(2 + x) * (1 + y ** 2) ** R(-3, 2) - sympy.pi * x ** 3,
        sympy.atan(x * y) + sympy.sinc(x) + sympy.tanh(y) ** 2,
    ]
    rng = np.random.default_rng(1)
    mpmath.mp.dps = 50
    for expr in exprs:
        f = compile_arb(expr, [x, y])
        ref = sympy.lambdify([x, y], expr, modules="mpmath")
        for _ in range(25):
            c = rng.uniform(-1, 1, 2)
            w = rng.uniform(0, 0.7, 2)
            box = [(float(ci), float(ci + wi)) for ci, wi in zip(c, w)]
            enc = f(*box)
            assert enc.is_finite(), (expr, box)
            for _ in range(10):
                p = [rng.uniform(a, b) for a, b in box]
                val = ref(*[mpmath.mpf(t) for t in p])
                assert float(enc.lower()) - 1e-12 <= float(val) <= float(enc.upper()) + 1e-12, (expr, box, p)


def test_affine_forms_contain_the_values_at_sampled_points():
    """The affine evaluator (a fast path of the branch and bound) against mpmath."""
    zero = arb(0)
    exprs = [
        sympy.Abs(x - y) + sympy.Max(x, y ** 2) - sympy.Min(x, R(1, 3)) + sympy.sign(x) * y,
        (x ** 2 + y ** 2) ** R(13, 10) - x ** 5 + y ** 4 + 1 / (3 + x * y) + sympy.sqrt(x ** 2 + y ** 2),
        sympy.cosh(x) - sympy.sinh(y) + sympy.asin(x / 2) + sympy.acos(y / 3) + sympy.tan(x / 2) + 2 ** (x * y),
        sympy.sin(x) * sympy.cos(x) - sympy.sin(2 * x) / 2 + sympy.log(3 + y) * sympy.exp(-x * y),
    ]
    rng = np.random.default_rng(7)
    mpmath.mp.dps = 40
    for expr in exprs:
        f = compile_arb(expr, [x, y])
        ref = sympy.lambdify([x, y], expr, modules="mpmath")
        for _ in range(40):
            lo = rng.uniform(-1, 1, 2)
            hi = lo + rng.uniform(0, 0.8, 2) * rng.choice([1.0, 0.01])
            forms = []
            for i in range(2):
                m = arb(float(lo[i] + (hi[i] - lo[i]) / 2))
                r = (arb(float(hi[i])) - m).union(m - arb(float(lo[i]))).abs_upper()
                forms.append(AffineForm(m, (r, zero) if i == 0 else (zero, r), zero))
            out = f.affine_program(*forms)[0]
            ball = out.ball() if isinstance(out, AffineForm) else out
            assert ball.is_finite(), (expr, lo, hi)
            for _ in range(10):
                p = [rng.uniform(a, b) for a, b in zip(lo, hi)]
                v = float(ref(*[mpmath.mpf(t) for t in p]))
                assert float(ball.lower()) - 1e-12 <= v <= float(ball.upper()) + 1e-12, (expr, lo, hi, p)
    # 2 sin x cos x − sin 2x = 0: the affine form cancels the first-order parts (its excess is
    # second order in the width), the ball extension does not
    g = compile_arb(2 * sympy.sin(x) * sympy.cos(x) - sympy.sin(2 * x), [x])
    form = g.affine_program(AffineForm(arb(0.5005), (arb(0.0005),), zero))[0]
    assert float(form.ball().rad()) < 1e-2 * float(g((0.5, 0.501)).rad())


def test_gradient_enclosure_contains_difference_quotients():
    expr = x * sympy.exp(-x) * sympy.sin(y) + sympy.sqrt(1 + x ** 2 * y ** 2)
    f = compile_arb(expr, [x, y])
    assert f.has_gradient
    fl = lambdify_real([x, y], expr)
    box = [(0.2, 0.6), (-1.0, -0.4)]
    _, grad = f.value_and_gradient(*box)
    rng = np.random.default_rng(0)
    for _ in range(50):
        p = np.array([rng.uniform(a, b) for a, b in box])
        for i in range(2):
            e = np.zeros(2)
            e[i] = 1e-6
            q = (float(fl(*(p + e))) - float(fl(*(p - e)))) / 2e-6
            assert float(grad[i].lower()) - 1e-6 <= q <= float(grad[i].upper()) + 1e-6


def test_kinks_get_clarke_gradients_and_jumps_get_none():
    f = compile_arb(sympy.Abs(x) + sympy.Max(x, y), [x, y])
    _, (gx, gy) = f.value_and_gradient((-1, 1), (-1, 1))
    assert gx.contains(2) and gx.contains(-1) and gx.contains(0)     # sign ∈ [-1, 1], H ∈ [0, 1]
    assert gy.contains(0) and gy.contains(1)
    g = compile_arb(sympy.sign(x) * y, [x, y])
    assert not g.has_gradient
    with pytest.raises(InputError):
        g.value_and_gradient(1, 1)


def test_constants_are_enclosed_exactly():
    f = compile_arb(R(1, 3) * x + sympy.pi - sympy.sqrt(2), [x])
    v = f(3)
    assert v.contains(1 + arb.pi() - arb(2).sqrt())
    assert float(v.rad()) < 1e-14
    # a Float is its exact binary value (documented); Rational(3, 10) is the decimal
    assert compile_arb(sympy.Float(0.5) * x, [x])(2) == 1
    assert compile_arb(R(3, 10) * x, [x])(10).contains(3)


def test_compiler_rejects_bad_input_with_clear_messages():
    with pytest.raises(InputError, match="string"):
        compile_arb("x**2", [x])
    with pytest.raises(InputError, match=r"\['y'\]"):
        compile_arb(x + y, [x])
    with pytest.raises(InputError, match="gamma"):
        compile_arb(sympy.gamma(x), [x])
    with pytest.raises(InputError, match="Symbol"):
        compile_arb(x, ["x"])
    assert isinstance(compile_arb(x, [x]), ArbFunction)


# ---------------------------------------------------------------------------
# suprema
# ---------------------------------------------------------------------------

def test_sup_of_x_exp_minus_x_is_one_over_e():
    res = sup_bound(x * sympy.exp(-x), {x: (0, 5)})
    e_inv = arb(-1).exp()
    assert res.status is Status.CERTIFIED
    assert arb(res.certified) >= e_inv                 # the certified bound is ≥ the true sup
    assert arb(res.lower) <= e_inv                     # and the proved lower bound ≤ it
    assert res.certified <= 1.01 * float(e_inv)        # within 1 %
    assert res.gap <= 1e-2
    assert abs(res.estimate - math.exp(-1)) < 1e-9 and abs(res.maximiser["x"] - 1) < 1e-3
    assert res.estimate_status is Status.ESTIMATED
    assert json.loads(json.dumps(res.to_json()))["estimate"]["status"] == "estimated"


@pytest.mark.parametrize("enclosure", ["both", "mean-value", "affine", "taylor"])
def test_certified_sup_dominates_a_dense_grid(enclosure):
    expr = sympy.sin(3 * x) * sympy.cos(2 * y) * sympy.exp(-(x ** 2 + y ** 2) / 4) + x * y / 5
    res = sup_bound(expr, {x: (-2, 2), y: (-1, 2)}, enclosure=enclosure)
    assert res.status is Status.CERTIFIED
    fl = lambdify_real([x, y], expr)
    g = np.meshgrid(np.linspace(-2, 2, 801), np.linspace(-1, 2, 601))
    grid_max = float(np.max(fl(*g)))
    assert res.certified >= grid_max
    assert res.lower <= grid_max + 1e-9 or res.lower <= res.certified
    assert res.certified <= grid_max * 1.011


def test_budget_of_one_box_is_undecided_never_certified():
    res = sup_bound(x * sympy.exp(-x), {x: (0, 5)}, budget=Budget(seconds=30, boxes=1))
    assert res.status is Status.UNDECIDED
    assert res.certified >= math.exp(-1)               # still a valid (loose) bound
    assert "undecided" in res.detail and "valid" in res.detail
    assert res.boxes <= 1


def test_estimate_only_is_estimated_never_certified():
    res = sup_bound(x * (1 - x), {x: (0, 1)}, certify=False)
    assert res.status is Status.ESTIMATED
    assert res.certified is None
    assert abs(res.estimate - 0.25) < 1e-9


def test_region_with_irrational_bounds_keeps_points_inside():
    theta = sympy.Symbol("theta")
    res = sup_bound(theta, {theta: (0, sympy.pi)})
    assert res.status is Status.CERTIFIED
    assert res.maximiser["theta"] <= math.pi and arb(res.maximiser["theta"]) < arb.pi()
    assert arb(res.certified) >= arb.pi()


def test_options_are_validated():
    with pytest.raises(InputError, match="enclosure"):
        sup_bound(x, {x: (0, 1)}, enclosure="interval-newton")
    with pytest.raises(InputError, match="progress"):
        sup_bound(x, {x: (0, 1)}, progress=3)
    with pytest.raises(InputError, match="rel_gap"):
        best_constant(x, 1 + x ** 2, {x: (0, 1)}, accuracy=Accuracy(rel_gap=-1))
    with pytest.raises(InputError, match="Budget"):
        sup_bound(x, {x: (0, 1)}, budget=30)


def test_box_validation():
    with pytest.raises(InputError, match="exceeds"):
        sup_bound(x, {x: (1, 0)})
    with pytest.raises(InputError, match="no range"):
        sup_bound(x + y, {x: (0, 1)})
    with pytest.raises(InputError, match="boxes"):
        sup_bound(x, {x: (0, 1)}, budget=Budget(boxes=0))
    with pytest.raises(InputError, match="nonnegative"):
        sup_bound(sympy.Symbol("p", nonnegative=True), {sympy.Symbol("p", nonnegative=True): (-1, 1)})


# ---------------------------------------------------------------------------
# unit vectors: closed forms on the sphere cap ‖s − r‖ ≤ d
# ---------------------------------------------------------------------------

R_DIR = sympy.Matrix([1, 1, 1]) / sympy.sqrt(3)


@pytest.fixture(scope="module")
def cap():
    return unit_vector_near(R_DIR, distance_max=1)       # ρ ≤ π/3


def test_cross_and_difference_identity_is_exact_on_the_cap(cap):
    s = cap.value
    lhs = s.cross(R_DIR).dot(s.cross(R_DIR))
    d2 = (s - R_DIR).dot(s - R_DIR)
    assert sympy.simplify(sympy.expand(lhs - d2 * (1 - d2 / 4))) == 0
    assert sympy.simplify(d2 - cap.extras["distance"] ** 2) == 0


@pytest.mark.slow
def test_best_constant_cross_squared_over_difference_squared_is_one(cap):
    s = cap.value
    lhs = s.cross(R_DIR).dot(s.cross(R_DIR))            # ‖s×r‖²
    tmpl = (s - R_DIR).dot(s - R_DIR)                   # ‖s−r‖², vanishes at s = r
    res = best_constant(lhs, tmpl, cap.region, name="c_cross", ratio=1 - tmpl / 4)
    assert res.status is Status.CERTIFIED
    assert res.certified >= 1.0 and res.certified <= 1.01                # sup = 1, approached at s → r
    assert res.maximiser["rho"] < 1e-3
    out = json.loads(json.dumps(res.to_json()))
    assert out["status"] == "certified" and out["estimate"]["status"] == "estimated"
    assert res.to_result().kind == "constant"


@pytest.mark.slow
def test_best_constant_with_finite_sup_at_the_cap_edge(cap):
    s = cap.value
    cross2 = s.cross(R_DIR).dot(s.cross(R_DIR))
    d2 = (s - R_DIR).dot(s - R_DIR)
    # ‖s−r‖² ≤ c‖s×r‖²: c = 1/(1 − d²/4) = 4/3 at ‖s − r‖ = d = 1
    res = best_constant(d2, cross2, cap.region, ratio=1 / (1 - d2 / 4))
    assert res.status is Status.CERTIFIED
    assert arb(res.certified) >= arb(4) / 3
    assert res.certified <= 4 / 3 * 1.01
    assert abs(res.maximiser["rho"] - math.pi / 3) < 1e-6


def test_norm_ratio_by_the_charts_closed_forms(cap):
    # ‖s×r‖ / ‖s−r‖ = sin ρ / (2 sin(ρ/2)) = cos(ρ/2): sup 1 at ρ → 0
    res = best_constant(cap.extras["cross_norm"], cap.extras["distance"], cap.region,
                        ratio=sympy.cos(cap.parameters[0] / 2))
    assert res.status is Status.CERTIFIED and 1.0 <= res.certified <= 1.01


def test_removable_singularity_without_cancellation_is_never_certified(cap):
    s = cap.value
    lhs = s.cross(R_DIR).dot(s.cross(R_DIR))
    tmpl = (s - R_DIR).dot(s - R_DIR)
    res = best_constant(lhs, tmpl, cap.region, budget=Budget(seconds=10, boxes=400))
    assert res.status is Status.UNDECIDED
    assert res.certified == math.inf
    assert "template" in res.detail
    assert 0.99 <= res.estimate <= 1.01     # the float estimate still sees sup ≈ 1 (0/0 in floats)


def test_wrong_ratio_is_rejected(cap):
    rho = cap.parameters[0]
    with pytest.raises(InputError, match="not lhs/template"):
        best_constant(sympy.sin(rho), 2 * sympy.sin(rho / 2), cap.region, ratio=sympy.cos(rho))


def test_negative_template_is_rejected():
    with pytest.raises(InputError, match="negative"):
        best_constant(x ** 2, x, {x: (-1, 1)}, ratio=x)


# ---------------------------------------------------------------------------
# claimed constants
# ---------------------------------------------------------------------------

def test_too_small_constant_is_refuted_with_a_real_violation(cap):
    s = cap.value
    lhs = (s - R_DIR).dot(s - R_DIR)
    tmpl = s.cross(R_DIR).dot(s.cross(R_DIR))
    claimed = R(13, 10)                                 # below the true 4/3
    res = check_constant(lhs, tmpl, cap.region, claimed, ratio=1 / (1 - lhs / 4))
    assert res.status is Status.FAILED
    assert res.margin > 0
    violation = exact_value(lhs - claimed * tmpl, res.point)
    assert violation > 0 and violation >= res.margin * (1 - 1e-9)
    rho = res.point["rho"]
    assert 0 <= rho <= math.pi / 3


def test_constant_above_the_sup_is_certified(cap):
    s = cap.value
    lhs = (s - R_DIR).dot(s - R_DIR)
    tmpl = s.cross(R_DIR).dot(s.cross(R_DIR))
    res = check_constant(lhs, tmpl, cap.region, 1.35, ratio=1 / (1 - lhs / 4))
    assert res.status is Status.CERTIFIED
    assert res.bound <= 1.35 and res.margin >= 0
    assert res.point is None


def test_refutation_where_the_template_vanishes_moves_inside():
    # ratio 2 − x has its sup 2 at x = 0 where the template x vanishes; 1.9 is still too small
    res = check_constant(x * (2 - x), x, {x: (0, 2)}, 1.9)
    assert res.status is Status.FAILED
    assert res.point["x"] > 0
    assert exact_value(x * (2 - x) - R(19, 10) * x, res.point) > 0


def test_claimed_float_is_read_as_its_decimal():
    # sup of 2 - x over [0, 2] is exactly 2: the decimal 2.0 is certified (not refuted by rounding)
    assert check_constant(x * (2 - x), x, {x: (0, 2)}, 2.0).status is Status.CERTIFIED


# ---------------------------------------------------------------------------
# sign proofs
# ---------------------------------------------------------------------------

def test_certify_nonpositive_proves_and_refutes():
    ok = certify_nonpositive(x ** 2 + y ** 2 - 2.01, {x: (-1, 1), y: (-1, 1)})
    assert ok.status is Status.CERTIFIED and ok.bound <= 0
    bad = certify_nonpositive(x * y - R(9, 10), {x: (-1, 1), y: (-1, 1)})
    assert bad.status is Status.FAILED
    assert exact_value(x * y - R(9, 10), bad.point) > 0
    assert json.loads(json.dumps(bad.to_json()))["status"] == "failed"


def test_certify_positive_proves_and_refutes():
    ok = certify_positive(1 + x * sympy.exp(-x) - sympy.cos(y) / 2, {x: (0, 3), y: (-1, 1)})
    assert ok.status is Status.CERTIFIED and ok.bound > 0
    bad = certify_positive(sympy.cos(x) - R(1, 2), {x: (0, 2)})
    assert bad.status is Status.FAILED
    assert exact_value(sympy.cos(x) - R(1, 2), bad.point) <= 0


def test_touching_zero_is_undecided_not_certified():
    res = certify_nonpositive(-(x - R(1, 3)) ** 2, {x: (-1, 1)}, budget=Budget(seconds=30, boxes=300))
    assert res.status is Status.UNDECIDED
    assert res.bound >= 0


# ---------------------------------------------------------------------------
# charts
# ---------------------------------------------------------------------------

def _numeric(M, subs):
    return np.array(M.subs(subs).evalf(), dtype=float)


@pytest.mark.parametrize("make", [
    lambda: rotation_axis_angle(rho_max=sympy.pi / 4),
])
def test_rotation_charts_give_rotations(make):
    ch = make()
    rng = np.random.default_rng(3)
    for _ in range(5):
        subs = {p: rng.uniform(float(lo), float(hi)) for p, (lo, hi) in ch.region.items()}
        M = _numeric(ch.value, subs)
        assert np.allclose(M.T @ M, np.eye(3), atol=1e-12)
        assert abs(np.linalg.det(M) - 1) < 1e-12


def test_axis_angle_chart_distance_and_reference():
    ref = sympy.Matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    ch = rotation_axis_angle(rho_max=1, reference=ref)
    rho, theta, phi = ch.parameters
    subs = {rho: 0.7, theta: 1.1, phi: 2.3}
    M = _numeric(ch.value, subs)
    fro = float(ch.extras["frobenius_distance"].subs(subs))
    assert abs(np.linalg.norm(M - np.array(ref, dtype=float)) - fro) < 1e-12
    with pytest.raises(InputError, match="rotation"):
        rotation_axis_angle(rho_max=1, reference=sympy.diag(1, 1, 2))


def test_sphere_and_ball_charts():
    ch = unit_vector_angles()
    assert sympy.simplify(ch.value.dot(ch.value)) == 1
    b = ball_point(r_max=2)
    rho = b.parameters[0]
    assert sympy.simplify(b.value.dot(b.value) - rho ** 2) == 0
    with pytest.raises(InputError):
        unit_vector_near(sympy.Matrix([1, 1, 0]), rho_max=1)          # not a unit vector
    with pytest.raises(InputError, match="exactly one"):
        unit_vector_near(R_DIR)


@pytest.mark.slow
def test_cap_chart_sup_matches_closed_form():
    # sup over the cap ρ ≤ π/6 and u ∈ S² of cos(ρ/2)·(a×r)·Θu = σ_max((I − rrᵀ)Θ)
    cap = unit_vector_near(R_DIR, rho_max=sympy.pi / 6)
    sph = unit_vector_angles()
    rho, psi = cap.parameters
    a = sympy.cos(psi) * cap.extras["e1"] + sympy.sin(psi) * cap.extras["e2"]
    theta_m = sympy.diag(5, 6, 4)
    f = sympy.cos(rho / 2) * a.cross(R_DIR).dot(theta_m * sph.value)
    region = dict(cap.region) | dict(sph.region)
    res = sup_bound(f, region)
    P = np.eye(3) - np.ones((3, 3)) / 3
    true = float(np.linalg.svd(P @ np.diag([5.0, 6.0, 4.0]), compute_uv=False).max())
    assert res.status is Status.CERTIFIED
    assert res.certified >= true and res.lower <= true + 1e-12
    assert res.certified <= 1.01 * true


# ---------------------------------------------------------------------------
# the Taylor strategy (lkverify.certify.engine.Taylor) and its quadratic bound
# ---------------------------------------------------------------------------

def _exact_cube_max(b, S):
    """max of b·e + eᵀSe over [-1, 1]^m, exactly (Fractions): every face's stationary point, the slow path."""
    from fractions import Fraction
    import itertools
    m = len(b)
    best = None
    for pattern in itertools.product((None, 1, -1), repeat=m):
        free = [i for i in range(m) if pattern[i] is None]
        e = [Fraction(0) if p is None else Fraction(p) for p in pattern]
        if free:                       # 2 S_FF e_F = −(b_F + 2 S_F,fixed e_fixed), by Gauss–Jordan
            A = [[2 * S[i][j] for j in free] + [-(b[i] + 2 * sum(S[i][j] * e[j] for j in range(m)
                                                                  if pattern[j] is not None))] for i in free]
            k = len(free)
            singular = False
            for c in range(k):
                piv = next((r for r in range(c, k) if A[r][c] != 0), None)
                if piv is None:
                    singular = True    # a flat face: its maximum is also attained on a smaller face
                    break
                A[c], A[piv] = A[piv], A[c]
                for r in range(k):
                    if r != c and A[r][c] != 0:
                        f = A[r][c] / A[c][c]
                        A[r] = [u - f * v for u, v in zip(A[r], A[c])]
            if singular:
                continue
            sol = [A[r][k] / A[r][r] for r in range(k)]
            if any(abs(v) > 1 for v in sol):
                continue
            for i, v in zip(free, sol):
                e[i] = v
        val = sum(b[i] * e[i] for i in range(m)) + sum(S[i][j] * e[i] * e[j] for i in range(m) for j in range(m))
        best = val if best is None or val > best else best
    return best


def test_cube_quadratic_sup_dominates_the_exact_maximum():
    """The proved bound of a quadratic on the cube against its exact maximum; tight for concave ones."""
    from fractions import Fraction
    from lkverify.certify.engine import cube_quadratic_sup
    from lkverify.certify.intervals import upper_fraction
    rng = np.random.default_rng(3)
    for trial in range(120):
        m = int(rng.integers(1, 4))
        b = [Fraction(int(v), 16) for v in rng.integers(-40, 41, m)]
        M = rng.integers(-30, 31, (m, m))
        shift = [0, 0, 40 * m, 8 * m][trial % 4]          # indefinite, …, concave, mildly indefinite
        S = [[Fraction(int(M[i, j] + M[j, i]), 32) - (Fraction(shift, 32) if i == j else 0) for j in range(m)]
             for i in range(m)]
        exact = _exact_cube_max(b, S)
        ball = lambda q, rad=0.0: arb(float(q), rad) if rad else arb(q.numerator) / q.denominator
        bound = cube_quadratic_sup([ball(v) for v in b], [[ball(v) for v in row] for row in S])
        assert upper_fraction(bound) >= exact, (b, S)
        if trial % 4 == 2:                                 # strictly concave: the dual bound is exact
            assert float(upper_fraction(bound) - exact) <= 1e-7 * (1 + abs(float(exact)))
        # with radii, every quadratic inside the balls is dominated
        rad = 0.05
        wide = cube_quadratic_sup([arb(float(v), rad) for v in b], [[arb(float(v), rad) for v in row] for row in S])
        for _ in range(3):
            bp = [v + Fraction(int(rng.integers(-9, 10)), 200) for v in b]
            d = [[Fraction(int(rng.integers(-9, 10)), 200) for _ in range(m)] for _ in range(m)]
            Sp = [[S[i][j] + d[min(i, j)][max(i, j)] for j in range(m)] for i in range(m)]
            assert upper_fraction(wide) >= _exact_cube_max(bp, Sp)


TAYLOR_EXPRS = [
    sympy.sin(3 * x) * sympy.cos(2 * y) + x * y ** 2,
    sympy.exp(-x ** 2 - y ** 2) * (x - y) + sympy.atan(x * y),
    (x ** 2 + y ** 2 + R(1, 10)) ** R(13, 10) - x * y + sympy.sqrt(2 + x),
    x ** 3 - 3 * x * y ** 2 + y ** 4 / 5 + sympy.log(3 + x * y),
    sympy.tanh(x + y) * sympy.cosh(x - y) / (2 + x ** 2),
    sympy.sin(x) * sympy.sin(y) * sympy.sin(z) + (x - z) ** 2 * y,
    -((x - R(1, 3)) ** 2 + 2 * (y - R(1, 5)) ** 2 - (x - R(1, 3)) * (y - R(1, 5))) * (1 + z ** 2) + z ** 3,
]


def test_taylor_programs_enclose_sympys_derivatives():
    """The compiled derivatives (after common-subexpression elimination) against mpmath values of
    SymPy's diff, at points (balls must contain the value) and on boxes (values at points inside)."""
    from lkverify.certify.engine import Objective
    from lkverify.certify.regions import parse_region
    mpmath.mp.dps = 40
    expr = (sympy.asin(x / 2) * sympy.acos(y / 3) + sympy.sinh(x * y) - sympy.tan(x / 3) + sympy.sinc(x + y)
            + 2 ** (x * y) + x ** y + sympy.atan(x) / (3 + y) + sympy.exp(x) ** R(1, 3) + sympy.sqrt(1 + x * y))
    region = parse_region({x: (R(1, 10), 1), y: (R(1, 5), 1)}, [expr])
    tp = Objective(expr, region).taylor_programs(3)
    assert tp is not None and tp.order == 3
    vs = [x, y]
    grads = [sympy.diff(expr, v) for v in vs]
    pairs = [(0, 0), (0, 1), (1, 1)]
    hess = [sympy.diff(grads[i], vs[j]) for i, j in pairs]
    third = [sympy.diff(hess[m], vs[k]) for m, (i, j) in enumerate(pairs) for k in range(j, 2)]
    ref = sympy.lambdify(vs, [expr, *grads, *hess, *third], modules="mpmath")
    rng = np.random.default_rng(5)
    for _ in range(15):
        p = [float(v) for v in rng.uniform(0.1, 1, 2)]
        want = [float(v) for v in ref(*[mpmath.mpf(v) for v in p])]
        for balls in (tp.box(*[arb(v) for v in p]), tp.point(*[arb(v) for v in p])):
            for ball, v in zip(balls, want):
                assert float(ball.lower()) - 1e-12 * (1 + abs(v)) <= v <= float(ball.upper()) + 1e-12 * (1 + abs(v))
        lo = [float(v) for v in rng.uniform(0.1, 0.8, 2)]
        hi = [a + 0.2 * float(rng.uniform()) for a in lo]
        balls = tp.box(*[arb(a).union(arb(b)) for a, b in zip(lo, hi)])
        for _ in range(5):
            q = [float(rng.uniform(a, b)) for a, b in zip(lo, hi)]
            for ball, v in zip(balls, ref(*[mpmath.mpf(t) for t in q])):
                assert float(ball.lower()) - 1e-12 <= float(v) <= float(ball.upper()) + 1e-12


@pytest.mark.parametrize("collapse", [pytest.param(False, marks=pytest.mark.slow), True])
def test_taylor_box_bounds_dominate_the_values_at_sampled_points(collapse):
    """One box at a time: the Taylor strategy's bound ≥ mpmath values at random points and corners of the box."""
    from lkverify.certify.engine import Objective, Taylor
    from lkverify.certify.regions import parse_region
    rng = np.random.default_rng(11)
    mpmath.mp.dps = 40
    for expr in TAYLOR_EXPRS:
        vs = sorted(expr.free_symbols, key=str)
        ref = sympy.lambdify(vs, expr, modules="mpmath")
        region = parse_region({v: (-1, 2) for v in vs}, [expr])
        enc = Taylor(Objective(expr, region), collapse=collapse)
        assert enc.tp is not None and enc.tp.order == 3
        for _ in range(25):
            lo = rng.uniform(-1, 0.9, len(vs))
            hi = lo + rng.uniform(0.0, 0.6, len(vs)) * rng.choice([1.0, 0.05], len(vs))
            out = enc.bound(0, tuple(map(float, lo)), tuple(map(float, hi)))
            pts = [[rng.uniform(a, c) for a, c in zip(lo, hi)] for _ in range(60)]
            pts += [[rng.choice([a, c]) for a, c in zip(lo, hi)] for _ in range(8)]
            top = max(float(ref(*[mpmath.mpf(t) for t in p])) for p in pts)
            assert out.upper >= top, (expr, lo, hi, out.upper, top)
            assert all(a <= c <= h for a, c, h in zip(out.lo, out.centre, out.hi))
            assert out.centre_value.contains(ref(*[mpmath.mpf(t) for t in out.centre])) or \
                abs(float(out.centre_value.mid()) - float(ref(*[mpmath.mpf(t) for t in out.centre]))) < 1e-12


def test_taylor_bound_is_tight_at_an_interior_maximum():
    """Near an interior maximum the third-order form's excess is third order in the width, the
    mean-value form's second order: on a box of width 2h around the maximiser of a concave quadratic
    plus a cubic the Taylor bound exceeds the maximum by O(h³) (a wrong factor in the form shows here)."""
    from lkverify.certify.engine import MeanValue, Objective, Taylor
    from lkverify.certify.regions import parse_region
    expr = -((x - R(1, 3)) ** 2 + 2 * (y - R(1, 5)) ** 2 - (x - R(1, 3)) * (y - R(1, 5))) + (x - R(1, 3)) ** 3
    for h in (R(1, 10), R(1, 100)):
        box = {x: (R(1, 3) - h, R(1, 3) + h), y: (R(1, 5) - h, R(1, 5) + h)}
        region = parse_region(box, [expr])
        obj = Objective(expr, region)
        t = Taylor(obj, collapse=False).bound(0, region.lo_out, region.hi_out)
        m = MeanValue(obj, collapse=False).bound(0, region.lo_out, region.hi_out)
        hf = float(h)
        assert t.upper >= 0.0                              # the maximum is 0, at (1/3, 1/5)
        assert t.upper <= 2 * hf ** 3                      # the cubic's ⅙·6·h³ = h³, doubled for rounding
        assert m.upper >= 0.5 * hf ** 2                    # while the mean-value form stays second order
        assert t.upper < m.upper


def test_taylor_falls_back_where_second_derivatives_jump():
    """Abs and Max have no Hessian: the strategy is the mean-value form there, still sound."""
    from lkverify.certify.engine import Objective, Taylor
    from lkverify.certify.regions import parse_region
    expr = sympy.Abs(x - R(1, 3)) * (1 - y ** 2) + sympy.Max(x, y) / 4
    region = parse_region({x: (0, 1), y: (-1, 1)}, [expr])
    assert Taylor(Objective(expr, region)).tp is None
    res = sup_bound(expr, {x: (0, 1), y: (-1, 1)}, enclosure="taylor")
    assert res.status is Status.CERTIFIED
    assert arb(res.certified) >= arb(2) / 3 + arb(1) / 4        # at x = 1, y = 0
    assert res.certified <= 1.01 * (2 / 3 + 1 / 4)


@pytest.mark.slow
def test_taylor_certifies_a_flat_quadratic_form_with_fewer_boxes():
    """sup over t ∈ [0, 1] and unit ω of ωᵀA(t)ω = max over t of λ_max(A(t)): a quadratic form in ω
    (flat directions in the angles), like the c_A template of aleksandrov2023.theorem3."""
    t, th, ph = sympy.symbols("t theta phi")
    w = unit_vector_angles(th, ph).value
    A0 = sympy.Matrix([[5, 1, R(1, 2)], [1, R(49, 10), R(3, 10)], [R(1, 2), R(3, 10), 1]])
    A1 = sympy.Matrix([[0, 1, 0], [1, 0, 1], [0, 1, -1]])
    A = A0 + sympy.sin(t) * A1 - t ** 2 * sympy.eye(3)
    expr = (w.T * A * w)[0]
    box = {t: (0, 1), th: (0, sympy.pi / 2), ph: (0, 2 * sympy.pi)}   # even in ω: a hemisphere suffices
    from scipy.optimize import minimize_scalar
    An = sympy.lambdify(t, A, "numpy")
    lam = lambda tt: float(np.linalg.eigvalsh(np.array(An(tt), dtype=float))[-1])
    slow = -minimize_scalar(lambda tt: -lam(tt), bounds=(0, 1), method="bounded", options={"xatol": 1e-10}).fun
    out = {}
    for enc in ("mean-value", "taylor"):
        res = sup_bound(expr, box, accuracy=Accuracy(rel_gap=1e-3), enclosure=enc)
        assert res.status is Status.CERTIFIED
        assert res.certified >= slow - 1e-12 and res.lower <= slow + 1e-9
        assert res.certified <= slow * (1 + 1.1e-3)
        out[enc] = res
    assert out["taylor"].boxes * 3 < out["mean-value"].boxes


@pytest.mark.slow  # about 15 s: a 4-variable cap; the Taylor strategy's own tests below run by default
def test_c_A_template_is_certified_within_one_percent_by_taylor():
    """The c_A template of aleksandrov2023.theorem3 (Θ = diag(5, 6, 4), F = I, r = (1,1,1)/√3) against
    the slow path sup over the cap of λ_max(M(s)), M(s) the symmetric matrix of the form in ω."""
    rho, psi, th, ph = sympy.symbols("rho psi theta phi", real=True)
    theta_m = sympy.diag(5, 6, 4)
    cap = unit_vector_near(R_DIR, rho_max=R(1, 2), rho=rho, psi=psi)
    sph = unit_vector_angles(th, ph)
    s, w = cap.value, sph.value
    expr = -(w.cross(s).cross(R_DIR).T * theta_m * w)[0]
    box = {**cap.region, **sph.region, th: (0, sympy.pi / 2)}
    W = sympy.Matrix(sympy.symbols("w0:3"))
    M = sympy.lambdify((rho, psi), sympy.hessian(-(W.cross(s).cross(R_DIR).T * theta_m * W)[0], list(W)) / 2)
    slow = max(float(np.linalg.eigvalsh(np.array(M(a, p), dtype=float))[-1])
               for a in np.linspace(0, 0.5, 51) for p in np.linspace(0, 2 * np.pi, 91))   # ≤ the sup
    res = sup_bound(expr, box, accuracy=Accuracy(rel_gap=5e-3), budget=Budget(boxes=40_000),
                    enclosure="taylor")
    assert res.status is Status.CERTIFIED
    assert res.certified >= slow and res.certified >= res.lower >= slow - 1e-3
    assert res.gap <= 5e-3 and res.certified <= 1.01 * slow


# ---------------------------------------------------------------------------
# longer cases
# ---------------------------------------------------------------------------

@pytest.mark.slow
def test_lemma1_constant_by_axis_angle():
    """Paper 001, Lemma 1 with a1 = a2 = 1, r1 ⟂ r2, rotations up to π/4: after cancelling
    2 sin(ρ/2), 1/ε = sup Σ‖w_i‖² / ‖Σ r_i × w_i‖² over (ρ, θ, φ); the estimate is 4 − 2√2."""
    rho, th, ph = sympy.symbols("rho theta phi")
    r1 = sympy.Matrix([1, 1, 0]) / sympy.sqrt(2)
    r2 = sympy.Matrix([-1, 1, 0]) / sympy.sqrt(2)
    n = sympy.Matrix([sympy.sin(th) * sympy.cos(ph), sympy.sin(th) * sympy.sin(ph), sympy.cos(th)])

    def w(r):
        return sympy.cos(rho / 2) * n.cross(r) + sympy.sin(rho / 2) * n.cross(n.cross(r))

    w1, w2 = w(r1), w(r2)
    num = w1.dot(w1) + w2.dot(w2)
    den = (r1.cross(w1) + r2.cross(w2)).dot(r1.cross(w1) + r2.cross(w2))
    res = best_constant(num, den, {rho: (0, sympy.pi / 4), th: (0, sympy.pi), ph: (0, 2 * sympy.pi)})
    assert res.status is Status.CERTIFIED
    assert res.certified >= 4 - 2 * math.sqrt(2)
    assert res.certified <= 1.01 * (4 - 2 * math.sqrt(2))


# ---------------------------------------------------------------------------
# the shared interval layer (lkverify.certify.intervals)

def test_cosh_of_a_wide_ball_away_from_zero_contains_both_end_values():
    # regression: the wide-ball cosh negated the whole hull, -(min ∪ max), dropping cosh(lo)
    x = sympy.Symbol("x")
    f = compile_arb(sympy.cosh(x), [x], gradient=False)
    for lo, hi in [(-3, -1), (1, 3), (sympy.Rational(-7, 10), sympy.Rational(-1, 5))]:
        ball = f((lo, hi))
        small, large = sorted([abs(lo), abs(hi)])
        assert ball.lower() <= math.cosh(small) * (1 - 1e-12) and ball.upper() >= math.cosh(large) * (1 + 1e-12)
        assert ball.lower() > 0


def test_compile_arb_is_the_shared_converter_at_any_precision():
    from lkverify.certify.intervals import UnsupportedExpression, enclose, lower_fraction, upper_fraction
    import flint
    x, y = sympy.symbols("x y")
    expr = sympy.atan(x) * sympy.exp(-y) + sympy.sqrt(x ** 2 + 1) - sympy.Rational(1, 3)
    with flint.ctx.workprec(200):        # constants are enclosed when compiled: compile at 200 bits too
        ball = compile_arb(expr, [x, y])(sympy.Rational(1, 7), 2)
    with mpmath.workprec(400):
        truth = mpmath.atan(mpmath.mpf(1) / 7) * mpmath.exp(-2) + mpmath.sqrt(mpmath.mpf(1) / 49 + 1) - mpmath.mpf(1) / 3
    ref = enclose(expr, {x: sympy.Rational(1, 7), y: 2}, prec=200)
    for b in (ball, ref):
        assert lower_fraction(b) <= sympy.Rational(mpmath.nstr(truth, 120)) + sympy.Rational(1, 10**100)
        assert upper_fraction(b) >= sympy.Rational(mpmath.nstr(truth, 120)) - sympy.Rational(1, 10**100)
        assert upper_fraction(b) - lower_fraction(b) < sympy.Rational(1, 2**180)
    with pytest.raises(UnsupportedExpression, match=r"gamma \(in gamma\(x\)\)"):
        compile_arb(sympy.gamma(x), [x])
