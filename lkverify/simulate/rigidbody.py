"""Rigid-body attitude: aircraft angles, quaternions, MRP, Euler/Poisson, initial data.

Plain NumPy helpers for the rigid-body papers (000 ``aleksandrov2026``, 001
``aleksandrov2017``, 002 ``aleksandrov2023``): building the initial inertial unit
vectors s_i from the papers' "aircraft angles" (Russian: самолётные углы — крен φ
roll, тангаж θ pitch, рыскание ψ yaw), converting attitudes, the right-hand sides of
Euler's and Poisson's equations, and the phase norm ‖χ‖_τ of paper 002.

Frames and matrices
-------------------
Every attitude matrix ``R`` returned here maps **body coordinates to base
coordinates**: ``v_base = R @ v_body``; its columns are the body axes x, y, z
expressed in the base frame.  The base frame is the inertial frame of the papers,
and it coincides with the body frame at the equilibrium (``R = I``).  The
base→body matrix (the direction-cosine table of Russian textbooks, whose *rows*
are the body axes) is ``R.T``; ``rotation_from_angles(..., direction="base_to_body")``
returns it.

Angle conventions
-----------------
A convention is an *intrinsic* sequence of three right-handed elementary
rotations about the successively moved axes (scipy's upper-case ``"ZYX"`` etc.):

``"yzx"`` (default; aliases ``"gost"``, ``"krylov"``)
    Russian flight mechanics, GOST 20058-80: vertical axis y, x forward, z to the
    right.  Yaw ψ about the vertical y, then pitch θ about the new z, then roll φ
    about the body x:  ``R = R_y(ψ) R_z(θ) R_x(φ)``.
``"zyx"`` (aliases ``"aerospace"``, ``"nasa"``)
    Aerospace/NASA (x forward, z down): yaw ψ about z, pitch θ about the new y,
    roll φ about the body x:  ``R = R_z(ψ) R_y(θ) R_x(φ)``.
``"xyz"``
    Roll φ about x, then pitch θ about the new y, then yaw ψ about the new z:
    ``R = R_x(φ) R_y(θ) R_z(ψ)``.

Why ``"yzx"`` is the default: papers 001 and 002 give the initial attitude by the
"самолётные углы крена, тангажа и рыскания" of Russian flight mechanics, whose
standard (GOST 20058-80, Krylov's aircraft angles) is the sequence ψ about the
vertical y, θ about z, φ about x.  The papers print no matrix, so this is an
assumption, not a reading; every function takes ``convention=`` and
:func:`chi_norm_table` shows how much the choice matters.

Inertial vectors in body axes
-----------------------------
The papers stabilize body-fixed unit vectors r_i (body coordinates) to inertial
unit vectors s_i written in body axes, ṡ_i = −ω × s_i, target s_i = r_i.  At the
equilibrium the body frame is the base frame, so the inertial vector whose body
image is r_i has base coordinates r_i.  A body turned to attitude ``R`` sees it as

    s_i = Rᵀ r_i      (:func:`inertial_vectors_in_body`),

and the triad S = [s1 s2 s3] (columns) for base-axis targets is S = Rᵀ.

>>> import numpy as np
>>> R = rotation_from_angles(0.0, 0.0, np.pi / 2, convention="zyx")
>>> np.round(R, 12) + 0.0
array([[ 0., -1.,  0.],
       [ 1.,  0.,  0.],
       [ 0.,  0.,  1.]])
>>> np.round(mrp_from_rotation(R), 6) + 0.0
array([0.      , 0.      , 0.414214])
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from lkverify.errors import InputError

__all__ = [
    "AxisAngle",
    "CHI_DEFINITIONS", "CONVENTIONS", "ChiNormRow", "ChiNormTable", "DEFAULT_CONVENTION",
    "axis_angle_from_rotation", "check_rotation", "chi_norm", "euler_rhs", "chi_norm_table",
    "inertial_vectors_from_angles", "inertial_vectors_in_body", "mrp_from_quaternion",
    "mrp_from_rotation", "poisson_rhs", "quaternion_from_mrp", "quaternion_from_rotation",
    "rotation_from_angles", "rotation_from_axis_angle", "rotation_from_mrp",
    "rotation_from_quaternion", "skew",
]

# --------------------------------------------------------------------------------------
# conventions

#: canonical convention name -> (axes of the 1st, 2nd, 3rd intrinsic rotation, angles used)
_SEQUENCES = {
    "yzx": (("y", "yaw"), ("z", "pitch"), ("x", "roll")),
    "zyx": (("z", "yaw"), ("y", "pitch"), ("x", "roll")),
    "xyz": (("x", "roll"), ("y", "pitch"), ("z", "yaw")),
}

#: the supported conventions, with a one-line description each
CONVENTIONS = {
    "yzx": "GOST 20058-80 / Krylov (y vertical): R = R_y(yaw) R_z(pitch) R_x(roll)",
    "zyx": "aerospace/NASA (z down): R = R_z(yaw) R_y(pitch) R_x(roll)",
    "xyz": "roll-pitch-yaw about moving axes: R = R_x(roll) R_y(pitch) R_z(yaw)",
}

_ALIASES = {"gost": "yzx", "krylov": "yzx", "aerospace": "zyx", "nasa": "zyx"}

#: the default convention (see the module docstring for why)
DEFAULT_CONVENTION = "yzx"

_DIRECTIONS = ("body_to_base", "base_to_body")

def _canonical_convention(convention: str) -> str:
    name = str(convention).lower()
    name = _ALIASES.get(name, name)
    if name not in _SEQUENCES:
        known = ", ".join(sorted(_SEQUENCES) + sorted(_ALIASES))
        raise InputError(f"unknown angle convention {convention!r}; expected one of: {known}")
    return name


def _direction(direction: str) -> str:
    if direction not in _DIRECTIONS:
        raise InputError(f"direction must be 'body_to_base' or 'base_to_body', got {direction!r}")
    return direction


# --------------------------------------------------------------------------------------
# small validators


def _vector(v, name: str, *, shape=(3,)) -> np.ndarray:
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be a real array of shape {shape}, got {v!r}; pass numbers") from exc
    if a.shape != shape:
        raise InputError(f"{name} must have shape {shape}, got shape {a.shape}; pass {shape[0]} components")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite, got {a.tolist()}; remove NaN/inf entries")
    return a


def _scalar(x, name: str) -> float:
    try:
        v = float(x)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be a real number, got {x!r}") from exc
    if not math.isfinite(v):
        raise InputError(f"{name} must be finite, got {v}")
    return v


def skew(v) -> np.ndarray:
    """The cross-product matrix [v×], with ``skew(v) @ u == np.cross(v, u)``.

    >>> skew([1, 2, 3])
    array([[ 0., -3.,  2.],
           [ 3.,  0., -1.],
           [-2.,  1.,  0.]])
    """
    x, y, z = _vector(v, "v")
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def check_rotation(R, *, atol: float = 1e-9, name: str = "R") -> np.ndarray:
    """Validate an orthonormal right-handed frame and return it as a float array.

    Parameters
    ----------
    R : array_like, shape (3, 3)
        A rotation matrix, or a triad of unit vectors as its columns.
    atol : float
        Largest accepted max |RᵀR − I| and |det R − 1|.
    name : str
        How the matrix is called in the error message.

    Raises
    ------
    InputError
        If ``R`` is not 3×3 and finite, not orthonormal, or not right-handed
        (det R = −1); the one-line message gives the measured max |RᵀR − I| and
        det R and how to fix it.

    Examples
    --------
    >>> check_rotation(np.array([[0, 2, -1], [0, 1, 2], [5 ** 0.5, 0, 0]]) / 5 ** 0.5).shape
    (3, 3)
    >>> check_rotation([[1, 0, 0], [0, 1, 0], [0, 0, -1]])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: R is not a right-handed frame: det R = -1, max|RᵀR − I| = 0 ...
    """
    M = _vector(R, name, shape=(3, 3))
    defect = float(np.max(np.abs(M.T @ M - np.eye(3))))
    det = float(np.linalg.det(M))
    if defect > atol:
        raise InputError(
            f"{name} is not orthonormal: max|RᵀR − I| = {defect:.3g}, det R = {det:.6g} "
            f"(expected ≤ {atol:g}): give unit, mutually orthogonal axes, "
            f"e.g. re-orthonormalise with scipy.linalg.polar or a QR step")
    if abs(det - 1.0) > atol:
        raise InputError(
            f"{name} is not a right-handed frame: det R = {det:.6g}, max|RᵀR − I| = {defect:.3g} "
            f"(expected det R = +1): reverse one axis (e.g. replace s3 by s1 × s2)")
    return M


def _unit_quaternion(q, atol: float) -> np.ndarray:
    a = _vector(q, "q", shape=(4,))
    n = float(np.linalg.norm(a))
    if abs(n - 1.0) > atol:
        raise InputError(f"q must be a unit quaternion (q0, q1, q2, q3): ‖q‖ = {n:.12g} "
                         f"(expected 1 within {atol:g}); divide q by its norm")
    return a


def _canonical_sign(q: np.ndarray) -> np.ndarray:
    """q or −q: q0 > 0, or for q0 = 0 the first nonzero component positive."""
    for c in q:
        if c != 0.0:
            return q if c > 0 else -q
    return q


# --------------------------------------------------------------------------------------
# aircraft angles


def _elementary(axis: str, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    if axis == "x":
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    if axis == "y":
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_from_angles(roll, pitch, yaw, *, convention: str = DEFAULT_CONVENTION,
                         direction: str = "body_to_base") -> np.ndarray:
    """Attitude matrix from the aircraft angles roll φ, pitch θ, yaw ψ (radians).

    Parameters
    ----------
    roll, pitch, yaw : float
        φ (крен), θ (тангаж), ψ (рыскание), in radians.
    convention : {"yzx", "zyx", "xyz"} or an alias ("gost", "krylov", "aerospace", "nasa")
        The intrinsic rotation sequence, see the module docstring.  Default
        ``"yzx"`` (GOST 20058-80): ``R = R_y(ψ) R_z(θ) R_x(φ)``.
    direction : {"body_to_base", "base_to_body"}
        ``"body_to_base"`` (default) returns R with ``v_base = R @ v_body``: the
        **columns are the body axes x, y, z expressed in the base frame**.
        ``"base_to_body"`` returns Rᵀ (rows are the body axes).

    Returns
    -------
    ndarray, shape (3, 3)

    Examples
    --------
    Pure roll is the same rotation in every convention; pitch is about y in
    ``"zyx"`` but about z in ``"yzx"``:

    >>> np.allclose(rotation_from_angles(0.3, 0, 0, convention="zyx"),
    ...             rotation_from_angles(0.3, 0, 0, convention="yzx"))
    True
    >>> np.round(rotation_from_angles(0, np.pi / 2, 0), 12) + 0.0   # default "yzx": about z
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    conv = _canonical_convention(convention)
    _direction(direction)
    values = {"roll": _scalar(roll, "roll"), "pitch": _scalar(pitch, "pitch"), "yaw": _scalar(yaw, "yaw")}
    R = np.eye(3)
    for axis, which in _SEQUENCES[conv]:
        R = R @ _elementary(axis, values[which])
    return R if direction == "body_to_base" else R.T


# --------------------------------------------------------------------------------------
# quaternions, MRP, axis-angle


def rotation_from_quaternion(q, *, atol: float = 1e-9) -> np.ndarray:
    """Rotation matrix of a unit quaternion q = (q0, λ), scalar first.

    R = (q0² − λᵀλ) I + 2 λλᵀ + 2 q0 [λ×]: the rotation by Φ about e when
    q = (cos Φ/2, e sin Φ/2).  q and −q give the same matrix.

    Raises
    ------
    InputError
        If |‖q‖ − 1| > ``atol``.

    Examples
    --------
    >>> h = np.sqrt(0.5)
    >>> np.round(rotation_from_quaternion([h, 0, 0, h]), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    q = _unit_quaternion(q, atol)
    q0, lam = q[0], q[1:]
    return (q0 * q0 - lam @ lam) * np.eye(3) + 2.0 * np.outer(lam, lam) + 2.0 * q0 * skew(lam)


def quaternion_from_rotation(R, *, atol: float = 1e-9) -> np.ndarray:
    """Unit quaternion (q0, q1, q2, q3), scalar first, of a rotation matrix.

    Shepperd's method (the largest of 1 + tr R, 1 + 2R_ii − tr R under the root),
    sign-canonical: q0 ≥ 0, and for q0 = 0 (half-turns) the first nonzero
    component is positive.

    Raises
    ------
    InputError
        If R is not orthonormal and right-handed (see :func:`check_rotation`).

    Examples
    --------
    >>> np.round(quaternion_from_rotation(np.eye(3)), 12) + 0.0
    array([1., 0., 0., 0.])
    >>> np.round(quaternion_from_rotation([[0, -1, 0], [1, 0, 0], [0, 0, 1]]), 6) + 0.0
    array([0.707107, 0.      , 0.      , 0.707107])
    """
    M = check_rotation(R, atol=atol)
    tr = M[0, 0] + M[1, 1] + M[2, 2]
    k = int(np.argmax([tr, M[0, 0], M[1, 1], M[2, 2]]))
    if k == 0:
        w = 0.5 * math.sqrt(max(1.0 + tr, 0.0))
        q = [w, (M[2, 1] - M[1, 2]) / (4 * w), (M[0, 2] - M[2, 0]) / (4 * w), (M[1, 0] - M[0, 1]) / (4 * w)]
    elif k == 1:
        x = 0.5 * math.sqrt(max(1.0 + M[0, 0] - M[1, 1] - M[2, 2], 0.0))
        q = [(M[2, 1] - M[1, 2]) / (4 * x), x, (M[0, 1] + M[1, 0]) / (4 * x), (M[0, 2] + M[2, 0]) / (4 * x)]
    elif k == 2:
        y = 0.5 * math.sqrt(max(1.0 - M[0, 0] + M[1, 1] - M[2, 2], 0.0))
        q = [(M[0, 2] - M[2, 0]) / (4 * y), (M[0, 1] + M[1, 0]) / (4 * y), y, (M[1, 2] + M[2, 1]) / (4 * y)]
    else:
        z = 0.5 * math.sqrt(max(1.0 - M[0, 0] - M[1, 1] + M[2, 2], 0.0))
        q = [(M[1, 0] - M[0, 1]) / (4 * z), (M[0, 2] + M[2, 0]) / (4 * z), (M[1, 2] + M[2, 1]) / (4 * z), z]
    q = np.asarray(q)
    return _canonical_sign(q / np.linalg.norm(q))


def mrp_from_quaternion(q, *, atol: float = 1e-9) -> np.ndarray:
    """Modified Rodrigues parameters σ = λ/(1 + λ0) of the short rotation (‖σ‖ ≤ 1).

    σ = e tan(Φ/4) (paper 003, DIGEST section 003).  q is first made sign-canonical
    (q0 ≥ 0), so the rotation angle Φ ∈ [0, π] and ‖σ‖ ≤ 1; the shadow set
    −σ/‖σ‖² describes the same attitude.

    Examples
    --------
    >>> np.round(mrp_from_quaternion([0, 0, 0, 1]), 12) + 0.0    # half-turn about z
    array([0., 0., 1.])
    >>> np.round(mrp_from_quaternion([-1, 0, 0, 0]), 12) + 0.0   # −q is the identity
    array([0., 0., 0.])
    """
    q = _canonical_sign(_unit_quaternion(q, atol))
    return q[1:] / (1.0 + q[0])


def quaternion_from_mrp(sigma) -> np.ndarray:
    """Unit quaternion (sign-canonical, q0 ≥ 0) of modified Rodrigues parameters σ.

    λ0 = (1 − σ²)/(1 + σ²), λ = 2σ/(1 + σ²), σ² = σᵀσ; any σ is accepted (for
    ‖σ‖ > 1, the long rotation, the result is the canonical −q).

    Examples
    --------
    >>> np.round(quaternion_from_mrp([0, 0, np.tan(np.pi / 8)]), 6) + 0.0
    array([0.707107, 0.      , 0.      , 0.707107])
    """
    s = _vector(sigma, "sigma")
    n2 = float(s @ s)
    q = np.concatenate([[(1.0 - n2) / (1.0 + n2)], 2.0 * s / (1.0 + n2)])
    return _canonical_sign(q / np.linalg.norm(q))


def mrp_from_rotation(R, *, atol: float = 1e-9) -> np.ndarray:
    """Modified Rodrigues parameters (‖σ‖ ≤ 1) of a rotation matrix."""
    return mrp_from_quaternion(quaternion_from_rotation(R, atol=atol))


def rotation_from_mrp(sigma) -> np.ndarray:
    """Rotation matrix of modified Rodrigues parameters σ.

    >>> np.round(rotation_from_mrp([0, 0, 1]), 12) + 0.0   # σ = e tan(π/4): half-turn about z
    array([[-1.,  0.,  0.],
           [ 0., -1.,  0.],
           [ 0.,  0.,  1.]])
    """
    return rotation_from_quaternion(quaternion_from_mrp(sigma))


@dataclasses.dataclass(frozen=True)
class AxisAngle:
    """A rotation by ``angle`` ∈ [0, π] about the unit ``axis`` (right-hand rule).

    For the identity (angle 0) the axis is undefined; it is reported as (1, 0, 0).
    """

    axis: tuple
    angle: float

    def rotation(self) -> np.ndarray:
        """The rotation matrix (Rodrigues' formula)."""
        return rotation_from_axis_angle(self.axis, self.angle)


def rotation_from_axis_angle(axis, angle) -> np.ndarray:
    """R = I + sin Φ [e×] + (1 − cos Φ)[e×]² for the rotation by Φ about e.

    The axis is normalised; a zero axis raises :class:`InputError`.

    >>> np.round(rotation_from_axis_angle([0, 0, 2], np.pi / 2), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    e = _vector(axis, "axis")
    n = float(np.linalg.norm(e))
    if n == 0.0:
        raise InputError("axis must be a nonzero 3-vector, got (0, 0, 0); give the rotation axis")
    phi = _scalar(angle, "angle")
    K = skew(e / n)
    return np.eye(3) + math.sin(phi) * K + (1.0 - math.cos(phi)) * (K @ K)


def axis_angle_from_rotation(R, *, atol: float = 1e-9) -> AxisAngle:
    """Axis and angle Φ ∈ [0, π] of a rotation matrix (via the canonical quaternion).

    >>> aa = axis_angle_from_rotation(rotation_from_axis_angle([1, 1, 0], 2.0))
    >>> np.round(aa.axis, 6) + 0.0, round(aa.angle, 12)
    (array([0.707107, 0.707107, 0.      ]), 2.0)
    """
    q = quaternion_from_rotation(R, atol=atol)
    n = float(np.linalg.norm(q[1:]))
    if n == 0.0:
        return AxisAngle(axis=(1.0, 0.0, 0.0), angle=0.0)
    return AxisAngle(axis=tuple(float(c) for c in q[1:] / n), angle=2.0 * math.atan2(n, q[0]))


# --------------------------------------------------------------------------------------
# dynamics


def _inertia(Theta_diag) -> np.ndarray:
    a = np.asarray(Theta_diag, dtype=float)
    if a.shape == (3,):
        if not np.all(np.isfinite(a)) or np.any(a <= 0):
            raise InputError(f"Theta_diag must hold three positive principal moments, got {a.tolist()}")
        return np.diag(a)
    if a.shape == (3, 3):
        if not np.all(np.isfinite(a)) or not np.allclose(a, a.T) or np.any(np.linalg.eigvalsh(a) <= 0):
            raise InputError("Theta_diag as a 3x3 matrix must be symmetric positive definite; "
                             "or pass the principal moments (A, B, C)")
        return a
    raise InputError(f"Theta_diag must be (A, B, C) or a 3x3 matrix, got shape {a.shape}")


def euler_rhs(Theta_diag, omega, torque) -> np.ndarray:
    """Euler's equations solved for ω̇:  ω̇ = Θ⁻¹(M − ω × Θω).

    Parameters
    ----------
    Theta_diag : array_like, shape (3,) or (3, 3)
        Principal moments (A, B, C), or a symmetric positive definite inertia tensor.
    omega, torque : array_like, shape (3,)
        Angular velocity and torque in body axes.

    Examples
    --------
    >>> euler_rhs([5, 6, 4], [1, 1, 1], [0, 0, 0])     # free body: ((B−C)qr, (C−A)rp, (A−B)pq)/(A,B,C)
    array([ 0.4       , -0.16666667, -0.25      ])
    """
    J = _inertia(Theta_diag)
    w = _vector(omega, "omega")
    m = _vector(torque, "torque")
    return np.linalg.solve(J, m - np.cross(w, J @ w))


def poisson_rhs(omega, s, *, layout: str = "columns") -> np.ndarray:
    """Poisson's equation ṡ = −ω × s for inertial unit vectors written in body axes.

    Parameters
    ----------
    omega : array_like, shape (3,)
    s : array_like, shape (3,) or (3, 3)
        One vector, or a triad.  With ``layout="columns"`` (default) the columns are
        s1, s2, s3 (S = Rᵀ for base-axis targets, and the result is −[ω×] S); with
        ``layout="rows"`` the rows are s1, s2, s3.

    Examples
    --------
    >>> poisson_rhs([0, 0, 1], [1, 0, 0])
    array([-0., -1., -0.])
    >>> np.allclose(poisson_rhs([1, 2, 3], np.eye(3)), -skew([1, 2, 3]))
    True
    """
    w = _vector(omega, "omega")
    a = np.asarray(s, dtype=float)
    if layout not in ("columns", "rows"):
        raise InputError(f"layout must be 'columns' or 'rows', got {layout!r}")
    if a.shape == (3,):
        return -np.cross(w, a)
    if a.shape == (3, 3):
        if layout == "columns":
            return -np.cross(w, a.T).T
        return -np.cross(w, a)
    raise InputError(f"s must be one 3-vector or a 3x3 triad, got shape {a.shape}")


def inertial_vectors_in_body(R, e_inertial, *, atol: float = 1e-9) -> np.ndarray:
    """Inertial unit vectors in body axes: s = Rᵀ e.

    Parameters
    ----------
    R : array_like, shape (3, 3)
        Body→base attitude (columns = body axes in the base frame), validated by
        :func:`check_rotation`.
    e_inertial : array_like, shape (3,) or (3, k)
        Base-frame coordinates of the inertial unit vector(s), one per column.
        Since the body frame is the base frame at the equilibrium s = r, the
        inertial vector to stabilize the body axis r to has e = r.

    Returns
    -------
    ndarray, same shape as ``e_inertial``
        s = Rᵀ e: the vector(s) as seen in the body axes (columns for a triad).

    Examples
    --------
    >>> R = rotation_from_angles(0, 0, np.pi / 2, convention="zyx")   # body x points along base y
    >>> np.round(inertial_vectors_in_body(R, [0, 1, 0]), 12) + 0.0   # base y seen from the body
    array([1., 0., 0.])
    """
    M = check_rotation(R, atol=atol)
    e = np.asarray(e_inertial, dtype=float)
    if e.ndim not in (1, 2) or e.shape[0] != 3 or not np.all(np.isfinite(e)):
        raise InputError(f"e_inertial must be a 3-vector or a 3xk matrix of column vectors, got shape {e.shape}")
    norms = np.linalg.norm(e, axis=0)
    bad = np.abs(norms - 1.0) > atol
    if np.any(bad):
        raise InputError(f"e_inertial must hold unit vectors, got norms {np.round(np.atleast_1d(norms), 12).tolist()}; "
                         f"divide each vector by its norm")
    return M.T @ e


def inertial_vectors_from_angles(roll, pitch, yaw, targets=None, *,
                                 convention: str = DEFAULT_CONVENTION) -> np.ndarray:
    """Initial inertial vectors s = Rᵀ r for a body turned by the aircraft angles.

    The body is deviated from the equilibrium (body frame = base frame) to the
    attitude ``R = rotation_from_angles(roll, pitch, yaw, convention=...)``; the
    inertial vectors that coincide with the body vectors r at the equilibrium are
    seen from the body as s = Rᵀ r.

    Parameters
    ----------
    roll, pitch, yaw : float
        Radians.
    targets : array_like, shape (3,) or (3, k), optional
        Body-fixed unit vectors r (columns).  Default: the base axes, giving the
        triad S = [s1 s2 s3] = Rᵀ (orthonormal, right-handed, columns).

    Examples
    --------
    Paper 002, Figs. 1–6 (default convention "yzx"), and paper 001's triad:

    >>> r = np.full(3, 3 ** -0.5)
    >>> np.round(inertial_vectors_from_angles(0.5, 0.6, -0.8, r), 4) + 0.0
    array([ 0.9998,  0.0079, -0.0179])
    >>> S = inertial_vectors_from_angles(0.5, 0.5, -0.5)
    >>> np.round(S, 4) + 0.0
    array([[ 0.7702,  0.4794,  0.4207],
           [-0.5991,  0.7702,  0.219 ],
           [-0.219 , -0.4207,  0.8803]])
    >>> np.allclose(np.cross(S[:, 0], S[:, 1]), S[:, 2])
    True
    """
    R = rotation_from_angles(roll, pitch, yaw, convention=convention)
    e = np.eye(3) if targets is None else targets
    return inertial_vectors_in_body(R, e)


# --------------------------------------------------------------------------------------
# the phase norm of paper 002

#: the definitions :func:`chi_norm` accepts
CHI_DEFINITIONS = {
    "uniform": "max over ξ of the Euclidean norm of χ(ξ) = (s − r, ω) in R⁶ (paper 002, section 5)",
    "theorem1": "max over ξ of ‖χ(ξ)‖ + ‖χ̇(ξ)‖, χ ∈ R⁶ (paper 002, general Theorem 1)",
    "sum": "‖s − r‖_τ + ‖ω‖_τ, each the max over ξ "
           "(proof of Theorem 3: ‖s_t − r‖_τ + ‖ω‖ < δ)",
    "max": "max(‖s − r‖_τ, ‖ω‖_τ)",
}


def _samples(x, name: str) -> np.ndarray:
    a = np.asarray(x, dtype=float)
    if a.ndim == 1:
        a = a[None, :]
    if a.ndim != 2 or a.shape[1] != 3 or a.shape[0] == 0:
        raise InputError(f"{name} must be a 3-vector or an (N, 3) array of samples over ξ ∈ [−τ, 0], "
                         f"got shape {np.shape(x)}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite; remove NaN/inf samples")
    return a


def chi_norm(s_minus_r, omega, *, definition: str = "uniform", derivative=None) -> float:
    """The phase norm ‖χ‖_τ of an initial function χ = (s − r, ω) of system (10), (12).

    Parameters
    ----------
    s_minus_r, omega : array_like, shape (3,) or (N, 3)
        χ on [−τ, 0]: one sample for a constant history, or N samples (rows) at
        common instants ξ_k.  The maximum is taken over the samples: exact for a
        constant (or piecewise constant) history, otherwise a lower bound of the sup.
    definition : {"uniform", "theorem1", "sum", "max"}
        See :data:`CHI_DEFINITIONS`.  ``"uniform"`` (default) is the norm paper 002
        defines for system (10), (12): max_ξ ‖χ(ξ)‖ in R⁶.
    derivative : pair of array_like, optional
        (ṡ, ω̇) samples, same shapes, used only by ``"theorem1"``.  Omitted, the
        history must be constant (all samples equal) and χ̇ = 0.

    Examples
    --------
    >>> round(chi_norm([0.3, 0, 0], [0, 0.4, 0]), 12)
    0.5
    >>> round(chi_norm([0.3, 0, 0], [0, 0.4, 0], definition="sum"), 12)
    0.7
    >>> round(chi_norm([0.3, 0, 0], [0, 0.4, 0], definition="theorem1", derivative=([0, 0, 0.1], [0, 0, 0])), 12)
    0.6
    """
    if definition not in CHI_DEFINITIONS:
        raise InputError(f"unknown definition {definition!r}; expected one of {', '.join(CHI_DEFINITIONS)}")
    d = _samples(s_minus_r, "s_minus_r")
    w = _samples(omega, "omega")
    if d.shape != w.shape:
        raise InputError(f"s_minus_r and omega must have the same number of samples, got {d.shape} and {w.shape}")
    if derivative is not None and definition != "theorem1":
        raise InputError(f"derivative is used only by definition='theorem1', not {definition!r}; drop it")
    nd = np.linalg.norm(d, axis=1)
    nw = np.linalg.norm(w, axis=1)
    if definition == "uniform":
        return float(np.max(np.hypot(nd, nw)))
    if definition == "sum":
        return float(np.max(nd) + np.max(nw))
    if definition == "max":
        return float(max(np.max(nd), np.max(nw)))
    # theorem1
    if derivative is None:
        if not (np.all(d == d[0]) and np.all(w == w[0])):
            raise InputError("definition='theorem1' needs χ̇ for a non-constant history; "
                             "pass derivative=(ṡ samples, ω̇ samples)")
        chi_dot = np.zeros(len(d))
    else:
        try:
            dd, dw = derivative
        except (TypeError, ValueError) as exc:
            raise InputError("derivative must be a pair (ṡ samples, ω̇ samples)") from exc
        dd, dw = _samples(dd, "derivative[0]"), _samples(dw, "derivative[1]")
        if dd.shape != d.shape or dw.shape != d.shape:
            raise InputError(f"derivative samples must have shape {d.shape}, got {dd.shape} and {dw.shape}")
        chi_dot = np.hypot(np.linalg.norm(dd, axis=1), np.linalg.norm(dw, axis=1))
    return float(np.max(np.hypot(nd, nw) + chi_dot))


@dataclasses.dataclass(frozen=True)
class ChiNormRow:
    """‖χ‖_τ of a constant initial function under one reading of the paper.

    Attributes
    ----------
    convention : str
        Canonical angle convention.
    direction : str
        How the angles' matrix M is taken: ``"body_to_base"`` (M = R) or ``"base_to_body"`` (M = Rᵀ).
    s_from : str
        ``"transpose"``: s = Mᵀ r;  ``"direct"``: s = M r.  The reading of this module is
        body_to_base + transpose (s = Rᵀ r); base_to_body + direct is the same vector.
    angle_unit : str
        ``"rad"`` (as printed) or ``"deg"`` (a misreading, tabulated as a check).
    definition : str
        A key of :data:`CHI_DEFINITIONS`.
    chi_dot : str
        ``"zero"`` (the constant history has χ̇ = 0) or, for ``"theorem1"`` only,
        ``"poisson"``: χ̇ = (−ω × s, 0) as if s obeyed (10) on [−τ, 0].
    s : tuple of float
        The initial s.
    value : float
    """

    convention: str
    direction: str
    s_from: str
    angle_unit: str
    definition: str
    chi_dot: str
    s: tuple
    value: float


@dataclasses.dataclass(frozen=True)
class ChiNormTable:
    """Every tabulated reading of ‖χ‖_τ for one constant initial function.

    Attributes
    ----------
    rows : tuple of ChiNormRow
    reported : float
        The value the paper prints (0.25 for Fig. 7).
    """

    rows: tuple
    reported: float

    def value(self, *, convention: str = DEFAULT_CONVENTION, direction: str = "body_to_base",
              s_from: str = "transpose", angle_unit: str = "rad", definition: str = "uniform",
              chi_dot: str = "zero") -> float:
        """The value under one reading (defaults: this module's reading)."""
        conv = _canonical_convention(convention)
        for row in self.rows:
            if (row.convention, row.direction, row.s_from, row.angle_unit, row.definition, row.chi_dot) == (
                    conv, direction, s_from, angle_unit, definition, chi_dot):
                return row.value
        raise InputError(f"no tabulated reading convention={conv!r}, direction={direction!r}, s_from={s_from!r}, "
                         f"angle_unit={angle_unit!r}, definition={definition!r}, chi_dot={chi_dot!r}")

    @property
    def default(self) -> float:
        """The value under the module's reading: "yzx", s = Rᵀ r, radians, "uniform"."""
        return self.value()

    def matches(self, decimals: int = 2) -> tuple:
        """The rows whose value rounds to ``reported`` at ``decimals`` decimals."""
        return tuple(row for row in self.rows if round(row.value, decimals) == round(self.reported, decimals))

    @property
    def reproduced(self) -> bool:
        """True when some tabulated reading gives the reported value to two decimals."""
        return bool(self.matches(2))

    def distinct_values(self, decimals: int = 4) -> tuple:
        """The sorted distinct values, rounded, for a quick overview."""
        return tuple(sorted({round(row.value, decimals) for row in self.rows}))


def chi_norm_table(angles, omega, r, *, reported: float) -> ChiNormTable:
    """‖χ‖_τ of a constant history given by aircraft angles, ω and r, under every supported reading.

    Tabulated: every convention × matrix direction × way to build s × angle unit ×
    norm definition (with χ̇ = 0, and for ``"theorem1"`` also the Poisson-consistent
    χ̇ = (−ω × s, 0)), to compare with a ``reported`` value.  Paper 002's Fig. 7
    data (the catalogue item ``aleksandrov2023.fig7_chi``) is the case in point:
    no reading reproduces its 0.25.

    Examples
    --------
    >>> table = chi_norm_table((0.8, 0.8, -0.8), (0.1, 0.1, 0.1), [3 ** -0.5] * 3, reported=0.25)
    >>> round(table.default, 4), table.reproduced
    (0.954, False)
    """
    angles = tuple(_scalar(a, "angle") for a in angles)
    w = _vector(omega, "omega")
    rv = _vector(r, "r")
    rows = []
    for conv, direction, s_from, unit in itertools.product(
            sorted(_SEQUENCES), _DIRECTIONS, ("transpose", "direct"), ("rad", "deg")):
        scale = 1.0 if unit == "rad" else math.pi / 180.0
        M = rotation_from_angles(*(a * scale for a in angles), convention=conv, direction=direction)
        s = M.T @ rv if s_from == "transpose" else M @ rv
        readings = [(definition, "zero") for definition in CHI_DEFINITIONS] + [("theorem1", "poisson")]
        for definition, chi_dot in readings:
            derivative = (poisson_rhs(w, s), np.zeros(3)) if chi_dot == "poisson" else None
            value = chi_norm(s - rv, w, definition=definition, derivative=derivative)
            rows.append(ChiNormRow(convention=conv, direction=direction, s_from=s_from, angle_unit=unit,
                                   definition=definition, chi_dot=chi_dot, s=tuple(float(c) for c in s),
                                   value=value))
    return ChiNormTable(rows=tuple(rows), reported=float(reported))
