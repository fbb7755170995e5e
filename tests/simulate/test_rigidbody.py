"""Rigid-body attitude helpers: conventions, conversions, dynamics, initial data, ‖χ‖_τ of paper 002."""

import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from lkverify.errors import InputError
from lkverify.simulate.rigidbody import (axis_angle_from_rotation, check_rotation, CHI_DEFINITIONS, chi_norm,
                                chi_norm_table, CONVENTIONS, DEFAULT_CONVENTION, euler_rhs,
                                inertial_vectors_from_angles, inertial_vectors_in_body, mrp_from_quaternion,
                                mrp_from_rotation, poisson_rhs, quaternion_from_mrp,
                                quaternion_from_rotation, rotation_from_angles, rotation_from_axis_angle,
                                rotation_from_mrp, rotation_from_quaternion, skew)


# The papers' initial data (constant on [−τ, 0]), as printed.
ALEKSANDROV2017_ANGLES = (0.5, 0.5, -0.5)  # paper 001 section 6: roll, pitch, yaw (rad)
ALEKSANDROV2023_ANGLES = (0.5, 0.6, -0.8)  # paper 002 section 6, Figs. 1–6
ALEKSANDROV2023_FIG7_ANGLES = (0.8, 0.8, -0.8)  # paper 002 Fig. 7; the paper reports ‖χ‖_τ = 0.25
ALEKSANDROV2023_FIG7_OMEGA = (0.1, 0.1, 0.1)
ALEKSANDROV2023_R = tuple([1.0 / math.sqrt(3.0)] * 3)
ALEKSANDROV2026_TRIAD = np.array([[0.0, 2.0, -1.0], [0.0, 1.0, 2.0], [math.sqrt(5.0), 0.0, 0.0]]) / math.sqrt(5.0)


def fig7_chi_norms(*, reported=0.25):
    return chi_norm_table(ALEKSANDROV2023_FIG7_ANGLES, ALEKSANDROV2023_FIG7_OMEGA, ALEKSANDROV2023_R,
                          reported=reported)


R3 = np.array(ALEKSANDROV2023_R)
#: scipy's intrinsic sequence and the order of (roll, pitch, yaw) it takes, per convention
SCIPY = {"yzx": ("YZX", lambda p, t, y: [y, t, p]),
         "zyx": ("ZYX", lambda p, t, y: [y, t, p]),
         "xyz": ("XYZ", lambda p, t, y: [p, t, y])}


@pytest.fixture(scope="module")
def rotations():
    return Rotation.random(300, random_state=20240601).as_matrix()


# ---------------------------------------------------------------------------- conventions

def test_default_convention_is_documented_gost():
    assert DEFAULT_CONVENTION == "yzx"
    assert set(CONVENTIONS) == {"yzx", "zyx", "xyz"}
    np.testing.assert_allclose(rotation_from_angles(0.1, 0.2, 0.3),
                               rotation_from_angles(0.1, 0.2, 0.3, convention="gost"), atol=0)


@pytest.mark.parametrize("convention", sorted(SCIPY))
def test_angles_match_scipy_intrinsic_sequences(convention):
    rng = np.random.default_rng(7)
    seq, order = SCIPY[convention]
    for roll, pitch, yaw in rng.uniform(-3, 3, size=(50, 3)):
        ours = rotation_from_angles(roll, pitch, yaw, convention=convention)
        ref = Rotation.from_euler(seq, order(roll, pitch, yaw)).as_matrix()
        np.testing.assert_allclose(ours, ref, atol=1e-13)
        np.testing.assert_allclose(rotation_from_angles(roll, pitch, yaw, convention=convention,
                                                        direction="base_to_body"), ours.T, atol=0)


def test_conventions_differ_for_the_papers_angles():
    angles = ALEKSANDROV2023_FIG7_ANGLES
    Rg = rotation_from_angles(*angles, convention="yzx")
    Ra = rotation_from_angles(*angles, convention="zyx")
    Rx = rotation_from_angles(*angles, convention="xyz")
    assert np.max(np.abs(Rg - Ra)) > 0.5
    assert np.max(np.abs(Ra - Rx)) > 0.5
    assert np.max(np.abs(Rg - Rx)) > 0.5


def test_single_axis_rotations_agree_where_they_should():
    a = 0.7
    # pure roll: about the body x axis in every convention
    for conv in CONVENTIONS:
        np.testing.assert_allclose(rotation_from_angles(a, 0, 0, convention=conv),
                                   rotation_from_angles(a, 0, 0, convention="zyx"), atol=1e-15)
    # zyx and xyz use the same axes for pitch (y) and yaw (z)
    np.testing.assert_allclose(rotation_from_angles(0, a, 0, convention="zyx"),
                               rotation_from_angles(0, a, 0, convention="xyz"), atol=1e-15)
    np.testing.assert_allclose(rotation_from_angles(0, 0, a, convention="zyx"),
                               rotation_from_angles(0, 0, a, convention="xyz"), atol=1e-15)
    # the y-vertical convention swaps the pitch and yaw axes: pitch about z, yaw about y
    np.testing.assert_allclose(rotation_from_angles(0, a, 0, convention="yzx"),
                               rotation_from_angles(0, 0, a, convention="zyx"), atol=1e-15)
    np.testing.assert_allclose(rotation_from_angles(0, 0, a, convention="yzx"),
                               rotation_from_angles(0, a, 0, convention="zyx"), atol=1e-15)
    assert np.max(np.abs(rotation_from_angles(0, a, 0, convention="yzx")
                         - rotation_from_angles(0, a, 0, convention="zyx"))) > 0.5


def test_physical_meaning_of_positive_angles():
    e_x = np.array([1.0, 0, 0])
    # GOST (y up, z right): positive pitch raises the nose (+y), positive yaw turns it to −z (left)
    nose = rotation_from_angles(0, 0.3, 0, convention="yzx") @ e_x
    assert nose[1] > 0.29 and abs(nose[2]) < 1e-15
    nose = rotation_from_angles(0, 0, 0.3, convention="yzx") @ e_x
    assert nose[2] < -0.29
    # aerospace (z down, y right): positive pitch raises the nose (−z), positive yaw turns it right (+y)
    nose = rotation_from_angles(0, 0.3, 0, convention="zyx") @ e_x
    assert nose[2] < -0.29
    nose = rotation_from_angles(0, 0, 0.3, convention="zyx") @ e_x
    assert nose[1] > 0.29
    # the columns are the body axes in the base frame
    R = rotation_from_angles(0.2, -0.4, 1.1)
    np.testing.assert_allclose(R @ np.eye(3), R, atol=0)
    check_rotation(R)


def test_bad_convention_and_direction_rejected():
    with pytest.raises(InputError, match="unknown angle convention 'zxz'"):
        rotation_from_angles(0, 0, 0, convention="zxz")
    with pytest.raises(InputError, match="direction"):
        rotation_from_angles(0, 0, 0, direction="inertial")


# ---------------------------------------------------------------------------- conversions

def test_known_small_cases():
    np.testing.assert_allclose(quaternion_from_rotation(np.eye(3)), [1, 0, 0, 0], atol=0)
    np.testing.assert_allclose(mrp_from_rotation(np.eye(3)), [0, 0, 0], atol=0)
    Rz90 = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    h = math.sqrt(0.5)
    np.testing.assert_allclose(quaternion_from_rotation(Rz90), [h, 0, 0, h], atol=1e-15)
    np.testing.assert_allclose(mrp_from_rotation(Rz90), [0, 0, math.tan(math.pi / 8)], atol=1e-15)
    np.testing.assert_allclose(rotation_from_axis_angle([0, 0, 1], math.pi / 2), Rz90, atol=1e-15)
    aa = axis_angle_from_rotation(Rz90)
    np.testing.assert_allclose(aa.axis, [0, 0, 1], atol=1e-15)
    assert aa.angle == pytest.approx(math.pi / 2, abs=1e-15)
    aa = axis_angle_from_rotation(np.eye(3))
    assert aa.angle == 0.0 and aa.axis == (1.0, 0.0, 0.0)


def test_round_trips_at_random_rotations(rotations):
    worst = 0.0
    for R in rotations:
        q = quaternion_from_rotation(R)
        assert q[0] >= 0 and abs(np.linalg.norm(q) - 1) < 1e-14
        sigma = mrp_from_quaternion(q)
        assert np.linalg.norm(sigma) <= 1 + 1e-15
        aa = axis_angle_from_rotation(R)
        assert 0 <= aa.angle <= math.pi
        worst = max(worst,
                    np.max(np.abs(rotation_from_quaternion(q) - R)),
                    np.max(np.abs(quaternion_from_mrp(sigma) - q)),
                    np.max(np.abs(rotation_from_mrp(sigma) - R)),
                    np.max(np.abs(mrp_from_rotation(rotation_from_mrp(sigma)) - sigma)),
                    np.max(np.abs(aa.rotation() - R)),
                    # σ = e tan(Φ/4)
                    np.max(np.abs(np.array(aa.axis) * math.tan(aa.angle / 4) - sigma)))
    assert worst < 1e-12


def test_quaternion_agrees_with_scipy_up_to_sign(rotations):
    for R in rotations[:50]:
        x, y, z, w = Rotation.from_matrix(R).as_quat()   # scipy: scalar last
        ref = np.array([w, x, y, z])
        ours = quaternion_from_rotation(R)
        assert min(np.max(np.abs(ours - ref)), np.max(np.abs(ours + ref))) < 1e-12


def test_half_turns_are_sign_canonical():
    for axis in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, -2, 2]):
        e = np.array(axis, float) / np.linalg.norm(axis)
        R = rotation_from_axis_angle(e, math.pi)
        q = quaternion_from_rotation(R)
        assert abs(q[0]) < 1e-15
        first = q[np.flatnonzero(np.abs(q) > 1e-12)[0]]
        assert first > 0
        sigma = mrp_from_rotation(R)
        assert np.linalg.norm(sigma) == pytest.approx(1.0, abs=1e-12)
        np.testing.assert_allclose(rotation_from_mrp(sigma), R, atol=1e-12)
    # the long rotation (‖σ‖ > 1) comes back as its short shadow −σ/‖σ‖²
    sigma = np.array([0.0, 0.0, 2.0])
    short = mrp_from_rotation(rotation_from_mrp(sigma))
    np.testing.assert_allclose(short, -sigma / 4.0, atol=1e-15)
    # −q is the same attitude: it has the same MRP
    q = quaternion_from_rotation(rotation_from_axis_angle([1, 2, 3], 1.0))
    np.testing.assert_allclose(mrp_from_quaternion(-q), mrp_from_quaternion(q), atol=0)


# ---------------------------------------------------------------------------- validation

def test_not_orthonormal_frame_rejected_with_measured_defect():
    with pytest.raises(InputError) as info:
        check_rotation(1.1 * np.eye(3))
    msg = str(info.value)
    assert "\n" not in msg
    assert "not orthonormal" in msg and "max|RᵀR − I| = 0.21" in msg and "det R = 1.331" in msg
    assert "re-orthonormalise" in msg
    with pytest.raises(InputError, match="not orthonormal"):
        quaternion_from_rotation([[1, 0.1, 0], [0, 1, 0], [0, 0, 1]])


def test_left_handed_frame_rejected_with_determinant():
    with pytest.raises(InputError) as info:
        inertial_vectors_in_body(np.diag([1.0, 1.0, -1.0]), [1, 0, 0])
    msg = str(info.value)
    assert "\n" not in msg
    assert "not a right-handed frame" in msg and "det R = -1" in msg and "max|RᵀR − I| = 0" in msg
    assert "s1 × s2" in msg


def test_other_bad_inputs_rejected():
    with pytest.raises(InputError, match=r"shape \(3, 3\)"):
        check_rotation(np.eye(2))
    with pytest.raises(InputError, match="unit quaternion"):
        rotation_from_quaternion([1, 1, 0, 0])
    with pytest.raises(InputError, match="nonzero"):
        rotation_from_axis_angle([0, 0, 0], 1.0)
    with pytest.raises(InputError, match="unit vectors"):
        inertial_vectors_in_body(np.eye(3), [1, 1, 1])       # r not normalised
    with pytest.raises(InputError, match="positive principal moments"):
        euler_rhs([5, -6, 4], [0, 0, 0], [0, 0, 0])


def test_paper000_triad_is_orthonormal_right_handed():
    S = check_rotation(ALEKSANDROV2026_TRIAD, atol=1e-15)
    s1, s2, s3 = S.T
    np.testing.assert_allclose(s1, [0, 0, 1], atol=0)
    np.testing.assert_allclose(np.cross(s1, s2), s3, atol=1e-15)
    assert np.linalg.det(S) == pytest.approx(1.0, abs=1e-15)


# ---------------------------------------------------------------------------- dynamics

def test_poisson_preserves_norms_and_orthogonality():
    rng = np.random.default_rng(3)
    for _ in range(200):
        w, s = rng.normal(size=3), rng.normal(size=3)
        # d/dt ‖s‖² = 2 sᵀṡ = −2 sᵀ(ω × s) = 0
        assert abs(s @ poisson_rhs(w, s)) < 1e-14 * (1 + np.linalg.norm(w) * (s @ s))
    S = inertial_vectors_from_angles(0.3, -0.2, 1.0)
    w = np.array([0.4, -1.2, 0.7])
    Sdot = poisson_rhs(w, S)
    # d/dt SᵀS = ṠᵀS + SᵀṠ = 0: the triad stays orthonormal
    np.testing.assert_allclose(Sdot.T @ S + S.T @ Sdot, 0, atol=1e-14)
    np.testing.assert_allclose(poisson_rhs(w, S.T, layout="rows"), Sdot.T, atol=0)
    np.testing.assert_allclose(Sdot[:, 1], poisson_rhs(w, S[:, 1]), atol=0)


def test_poisson_matches_attitude_kinematics():
    """S = Rᵀ with Ṙ = R[ω×] (ω in body axes): the finite difference of S is −ω × S."""
    R = rotation_from_angles(0.5, 0.6, -0.8)
    w = np.array([1.0, -0.5, 0.25])
    h = 1e-6
    S_plus, S_minus = (R @ expm(h * skew(w))).T, (R @ expm(-h * skew(w))).T
    np.testing.assert_allclose((S_plus - S_minus) / (2 * h), poisson_rhs(w, R.T), atol=1e-9)


def test_euler_rhs():
    J = np.array([5.0, 6.0, 4.0])
    rng = np.random.default_rng(11)
    for _ in range(50):
        w, m = rng.normal(size=3), rng.normal(size=3)
        wdot = euler_rhs(J, w, m)
        np.testing.assert_allclose(J * wdot + np.cross(w, J * w), m, atol=1e-13)
        np.testing.assert_allclose(euler_rhs(np.diag(J), w, m), wdot, atol=1e-13)
        # torque-free: energy and ‖angular momentum‖ are conserved
        wdot0 = euler_rhs(J, w, np.zeros(3))
        assert abs(w @ (J * wdot0)) < 1e-13
        assert abs((J * w) @ (J * wdot0)) < 1e-12


# ---------------------------------------------------------------------------- inertial vectors

def test_inertial_vectors_composition():
    R = rotation_from_angles(*ALEKSANDROV2023_ANGLES)
    s = inertial_vectors_in_body(R, R3)
    # the inertial vector is fixed: mapped back to the base frame it is r again
    np.testing.assert_allclose(R @ s, R3, atol=1e-15)
    # at the equilibrium (R = I) s = r
    np.testing.assert_allclose(inertial_vectors_in_body(np.eye(3), R3), R3, atol=0)
    # triad for base-axis targets is Rᵀ
    np.testing.assert_allclose(inertial_vectors_from_angles(*ALEKSANDROV2023_ANGLES), R.T, atol=0)


def test_initial_data_under_default_convention():
    s = inertial_vectors_from_angles(*ALEKSANDROV2023_ANGLES, R3)
    np.testing.assert_allclose(s, [0.9998083523821073, 0.007911635434692076, -0.01790710841327467], atol=1e-12)
    s = inertial_vectors_from_angles(*ALEKSANDROV2023_FIG7_ANGLES, R3)
    np.testing.assert_allclose(s, [0.9829637351454699, -0.13633701958013542, 0.12326602322161813], atol=1e-12)
    S = inertial_vectors_from_angles(*ALEKSANDROV2017_ANGLES)
    c, n = math.cos(0.5), math.sin(0.5)
    np.testing.assert_allclose(S, [[0.7701511529340699, 0.479425538604203, 0.42073549240394825],
                                   [-0.5990789783679945, 0.7701511529340699, 0.21902415234828082],
                                   [-0.21902415234828082, -0.42073549240394825, 0.8803465602362086]], atol=1e-12)
    # closed form (yzx): S = Rᵀ, R = R_y(ψ)R_z(θ)R_x(φ), so S[0,0] = cos ψ cos θ and S[0,1] = sin θ
    assert S[0, 0] == pytest.approx(c * c, abs=1e-15) and S[0, 1] == pytest.approx(n, abs=1e-15)
    check_rotation(S, atol=1e-14)
    np.testing.assert_allclose(np.cross(S[:, 0], S[:, 1]), S[:, 2], atol=1e-15)


# ---------------------------------------------------------------------------- ‖χ‖_τ

def test_chi_norm_definitions():
    d, w = [0.3, 0.0, 0.0], [0.0, 0.4, 0.0]
    assert chi_norm(d, w) == pytest.approx(0.5, abs=1e-15)
    assert chi_norm(d, w, definition="sum") == pytest.approx(0.7, abs=1e-15)
    assert chi_norm(d, w, definition="max") == pytest.approx(0.4, abs=1e-15)
    assert chi_norm(d, w, definition="theorem1") == pytest.approx(0.5, abs=1e-15)   # constant: χ̇ = 0
    assert chi_norm(d, w, definition="theorem1", derivative=([0, 0, 0.3], [0, 0.4, 0])) == pytest.approx(1.0)
    # sampled history: maximum over ξ; "sum" takes each sup separately
    D = np.array([[0.3, 0, 0], [0.0, 0, 0]])
    W = np.array([[0.0, 0, 0], [0.0, 0.4, 0]])
    assert chi_norm(D, W) == pytest.approx(0.4)
    assert chi_norm(D, W, definition="sum") == pytest.approx(0.7)
    with pytest.raises(InputError, match="non-constant history"):
        chi_norm(D, W, definition="theorem1")
    with pytest.raises(InputError, match="only by definition='theorem1'"):
        chi_norm(d, w, derivative=(d, w))
    with pytest.raises(InputError, match="unknown definition"):
        chi_norm(d, w, definition="l1")
    assert set(CHI_DEFINITIONS) == {"uniform", "theorem1", "sum", "max"}


#: (convention, unit, definition, chi_dot) -> ‖χ‖_τ for paper 002 Fig. 7, s = Rᵀ r
FIG7 = {
    ("yzx", "rad", "uniform", "zero"): 0.9539729201358808,
    ("yzx", "rad", "theorem1", "zero"): 0.9539729201358808,
    ("yzx", "rad", "sum", "zero"): 1.111322521354055,
    ("yzx", "rad", "max", "zero"): 0.9381174405971672,
    ("yzx", "rad", "theorem1", "poisson"): 1.0974758147146433,
    ("zyx", "rad", "uniform", "zero"): 1.376396645999083,
    ("zyx", "rad", "sum", "zero"): 1.538660216276735,
    ("zyx", "rad", "max", "zero"): 1.3654551355198474,
    ("zyx", "rad", "theorem1", "poisson"): 1.5492035686687342,
    ("xyz", "rad", "uniform", "zero"): 0.9539729201358808,
    ("xyz", "rad", "sum", "zero"): 1.111322521354055,
    ("yzx", "deg", "uniform", "zero"): 0.17468891641080758,
    ("yzx", "deg", "sum", "zero"): 0.19592550145682436,
    ("yzx", "deg", "max", "zero"): 0.17320508075688776,
    ("zyx", "deg", "uniform", "zero"): 0.1747096897969302,
    ("zyx", "deg", "sum", "zero"): 0.19608467229475324,
}


@pytest.fixture(scope="module")
def fig7():
    return fig7_chi_norms()


def test_fig7_values_pinned(fig7):
    for (conv, unit, definition, chi_dot), value in FIG7.items():
        assert fig7.value(convention=conv, angle_unit=unit, definition=definition, chi_dot=chi_dot) \
            == pytest.approx(value, abs=1e-12), (conv, unit, definition, chi_dot)
    assert fig7.default == pytest.approx(0.9539729201358808, abs=1e-12)


def test_fig7_independent_reference(fig7):
    """Slow path: scipy's matrix, ‖s − r‖² = 2 − 2 rᵀRr, and ‖ω‖ = 0.1√3."""
    w = 0.1 * math.sqrt(3)
    for conv, (seq, order) in SCIPY.items():
        R = Rotation.from_euler(seq, order(*ALEKSANDROV2023_FIG7_ANGLES)).as_matrix()
        d = math.sqrt(2 - 2 * R3 @ R @ R3)
        assert fig7.value(convention=conv) == pytest.approx(math.hypot(d, w), abs=1e-12)
        assert fig7.value(convention=conv, definition="sum") == pytest.approx(d + w, abs=1e-12)
        assert fig7.value(convention=conv, definition="max") == pytest.approx(max(d, w), abs=1e-12)
        s = R.T @ R3
        assert fig7.value(convention=conv, definition="theorem1", chi_dot="poisson") == pytest.approx(
            math.hypot(d, w) + np.linalg.norm(np.cross(ALEKSANDROV2023_FIG7_OMEGA, s)), abs=1e-12)


def test_fig7_matrix_direction_and_construction_of_s_do_not_matter(fig7):
    """‖Rᵀr − r‖ = ‖Rr − r‖: the four (direction, s_from) readings agree, while s itself differs."""
    keys = {}
    for row in fig7.rows:
        keys.setdefault((row.convention, row.angle_unit, row.definition, row.chi_dot), []).append(row)
    assert len(fig7.rows) == 3 * 2 * 2 * 2 * 5
    for group in keys.values():
        assert len(group) == 4
        assert max(r.value for r in group) - min(r.value for r in group) < 1e-14
        assert len({tuple(np.round(r.s, 12)) for r in group}) == 2   # s = Rᵀr and s = Rr


def test_fig7_reported_025_is_not_reproduced(fig7):
    assert fig7.reported == 0.25
    assert not fig7.reproduced and fig7.matches() == ()
    closest = min(abs(row.value - 0.25) for row in fig7.rows)
    assert closest > 0.05                                # nearest: 0.196 ("zyx", degrees, sum)
    # read in radians, as printed, every reading exceeds the paper's bound 0.28 by far
    assert min(row.value for row in fig7.rows if row.angle_unit == "rad") > 0.93
    # while the table would recognise the value if it occurred
    assert fig7_chi_norms(reported=0.95).reproduced
