"""Charts: the papers' manifold regions (a unit sphere, a cap ‖s − r‖ ≤ d, rotations near a frame, a ball) as boxes.

One chart per manifold: :func:`unit_vector_angles` (S²), :func:`unit_vector_near`
(a cap around r), :func:`rotation_axis_angle` (rotations near R0),
:func:`ball_point` (a ball in R³).

Examples
--------
>>> ch = unit_vector_angles()
>>> sympy.simplify(ch.value.dot(ch.value))
1
"""

from __future__ import annotations

import dataclasses
import types
from collections.abc import Mapping

import numpy as np  # noqa: F401 -- used by the doctests
import sympy

from ..errors import InputError
from .regions import exact_number, prove_zero

__all__ = ["Chart", "ball_point", "rotation_axis_angle", "unit_vector_angles", "unit_vector_near"]


@dataclasses.dataclass(frozen=True)
class Chart:
    """A parametrisation ``value(parameters)`` with the parameters in a box.

    Attributes
    ----------
    value : sympy.Matrix
        A 3-vector or a 3×3 rotation matrix in the parameters; substitute it
        for the state (``expr.subs(dict(zip(s, chart.value)))``).
    region : mapping of sympy.Symbol to (lo, hi)
        The parameter box; pass it (or a sub-box) to
        :func:`~lkverify.certify.suprema.sup_bound`, :func:`~lkverify.certify.ratios.best_constant`, ...
    extras : mapping of str to sympy.Expr
        Closed forms the chart knows (``"distance"``: ‖s − r‖, ``"angle"``, ...),
        for cancelling vanishing factors by hand.
    description : str

    Examples
    --------
    >>> from lkverify.certify.suprema import sup_bound
    >>> ch = unit_vector_angles()
    >>> ch.description, ch.parameters
    ('unit vector s(θ, φ) on the sphere', (theta, phi))
    >>> res = sup_bound(ch.value[2], ch.region)                 # the largest z-component of a unit vector
    >>> res.status.value, res.lower, res.certified < 1.0001
    ('certified', 1.0, True)
    """

    value: sympy.Matrix
    region: Mapping
    extras: Mapping
    description: str

    @property
    def parameters(self) -> tuple:
        """The chart's parameters (the region's symbols), in order."""
        return tuple(self.region)


def _mapping(d: dict):
    return types.MappingProxyType(dict(d))


def _symbols(given, names: str) -> tuple:
    if given is None:
        return sympy.symbols(names, real=True)
    given = tuple(given) if isinstance(given, (list, tuple)) else (given,)
    if not all(isinstance(s, sympy.Symbol) for s in given):
        raise InputError(f"chart parameters must be sympy Symbols, got {given!r}")
    return given


def _positive_bound(value, what: str, upper=None):
    v = exact_number(value, what)
    if not v.is_positive:
        raise InputError(f"{what} must be > 0, got {v}")
    if upper is not None and (v - upper).is_positive:
        raise InputError(f"{what} must be ≤ {upper}, got {v}")
    return v


def _sphere(theta, phi) -> sympy.Matrix:
    return sympy.Matrix([sympy.sin(theta) * sympy.cos(phi), sympy.sin(theta) * sympy.sin(phi),
                         sympy.cos(theta)])


def _skew(v) -> sympy.Matrix:
    return sympy.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def _reference(reference) -> sympy.Matrix | None:
    if reference is None:
        return None
    R0 = sympy.Matrix(reference)
    if R0.shape != (3, 3) or R0.free_symbols:
        raise InputError(f"reference must be a numeric 3×3 rotation matrix, got shape {R0.shape}")
    if not all(prove_zero(e) for e in (R0.T * R0 - sympy.eye(3))) or not prove_zero(R0.det() - 1):
        raise InputError("reference must be a rotation matrix (R0ᵀR0 = I, det R0 = 1), checked exactly")
    return R0


def unit_vector_angles(theta=None, phi=None) -> Chart:
    """A unit vector on S² by spherical angles, θ ∈ [0, π], φ ∈ [0, 2π].

    ``s = (sin θ cos φ, sin θ sin φ, cos θ)``.

    Examples
    --------
    >>> ch = unit_vector_angles()
    >>> sympy.simplify(ch.value.dot(ch.value))
    1
    >>> [str(p) for p in ch.parameters]
    ['theta', 'phi']
    """
    theta, phi = _symbols(None if theta is None else (theta, phi), "theta phi")
    return Chart(_sphere(theta, phi), _mapping({theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({}), "unit vector s(θ, φ) on the sphere")


def unit_vector_near(r, *, rho_max=None, distance_max=None, rho=None, psi=None) -> Chart:
    """Unit vectors near a unit vector ``r``: angle ρ from r and azimuth ψ.

    ``s = cos ρ · r + sin ρ (cos ψ · e1 + sin ψ · e2)`` with (e1, e2, r) a
    right-handed orthonormal frame, so ``‖s − r‖ = 2 sin(ρ/2)`` and
    ``‖s × r‖ = sin ρ`` exactly (extras ``"distance"``, ``"cross_norm"``).

    Parameters
    ----------
    r : 3-vector of SymPy numbers with ‖r‖ = 1 (checked exactly)
    rho_max : number, optional
        ρ ∈ [0, rho_max], rho_max ≤ π.
    distance_max : number, optional
        Instead of rho_max: the cap ‖s − r‖ ≤ d (d ≤ 2), i.e. ρ ≤ 2 asin(d/2).
    rho, psi : sympy.Symbol, optional

    Examples
    --------
    >>> r = sympy.Matrix([1, 1, 1]) / sympy.sqrt(3)
    >>> ch = unit_vector_near(r, distance_max=1)
    >>> rho, psi = ch.parameters
    >>> s = ch.value
    >>> sympy.simplify((s - r).dot(s - r) - ch.extras["distance"] ** 2)
    0
    >>> ch.region[rho]
    (0, pi/3)
    """
    r = sympy.Matrix(r)
    if r.shape not in ((3, 1), (1, 3)) or r.free_symbols:
        raise InputError(f"r must be a numeric 3-vector, got {r}")
    r = r.reshape(3, 1)
    if not prove_zero(r.dot(r) - 1):
        raise InputError(f"r must be a unit vector (checked exactly), got ‖r‖² = {sympy.simplify(r.dot(r))}")
    if (rho_max is None) == (distance_max is None):
        raise InputError("give exactly one of rho_max (angle from r) and distance_max (‖s − r‖ ≤ d)")
    if distance_max is not None:
        d = _positive_bound(distance_max, "distance_max", 2)
        top = 2 * sympy.asin(d / 2)
    else:
        top = _positive_bound(rho_max, "rho_max", sympy.pi)
    rho, psi = _symbols(None if rho is None else (rho, psi), "rho psi")
    k = min(range(3), key=lambda i: abs(float(r[i])))
    a = sympy.Matrix([1 if i == k else 0 for i in range(3)])
    w = a - a.dot(r) * r
    e1 = (w / sympy.sqrt(w.dot(w))).applyfunc(sympy.radsimp)
    e2 = r.cross(e1).applyfunc(sympy.radsimp)
    s = sympy.cos(rho) * r + sympy.sin(rho) * (sympy.cos(psi) * e1 + sympy.sin(psi) * e2)
    return Chart(s, _mapping({rho: (0, top), psi: (0, 2 * sympy.pi)}),
                 _mapping({"distance": 2 * sympy.sin(rho / 2), "cross_norm": sympy.sin(rho),
                           "angle": rho, "e1": e1, "e2": e2}),
                 f"unit vector s(ρ, ψ) at angle ρ ≤ {top} from r = {list(r)}")


def rotation_axis_angle(*, rho_max, rho=None, theta=None, phi=None, reference=None) -> Chart:
    """Rotations near a reference frame by angle ρ ∈ [0, rho_max] about an axis n(θ, φ).

    ``R = R0 (I + sin ρ N + (1 − cos ρ) N²)``, ``N = [n]×`` (Rodrigues), with
    ``n`` the unit vector of :func:`unit_vector_angles`; no singularity at
    ρ = 0 (the rotation vector is ρ·n).  ``‖R − R0‖_F = 2√2 sin(ρ/2)``
    (extra ``"frobenius_distance"``).

    Examples
    --------
    >>> ch = rotation_axis_angle(rho_max=sympy.pi / 6)
    >>> rho, theta, phi = ch.parameters
    >>> R = np.array(ch.value.subs({rho: 0.5, theta: 1.0, phi: 2.0}).evalf(), dtype=float)
    >>> bool(np.allclose(R.T @ R, np.eye(3)))
    True
    """
    top = _positive_bound(rho_max, "rho_max", sympy.pi)
    rho, theta, phi = _symbols(None if rho is None else (rho, theta, phi), "rho theta phi")
    n = _sphere(theta, phi)
    N = _skew(n)
    R = sympy.eye(3) + sympy.sin(rho) * N + (1 - sympy.cos(rho)) * N * N
    R0 = _reference(reference)
    if R0 is not None:
        R = R0 * R
    return Chart(R, _mapping({rho: (0, top), theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({"angle": rho, "axis": n,
                           "frobenius_distance": 2 * sympy.sqrt(2) * sympy.sin(rho / 2)}),
                 f"rotation by angle ρ ≤ {top} about n(θ, φ)" + (" after R0" if R0 is not None else ""))


def ball_point(*, r_max, radius=None, theta=None, phi=None) -> Chart:
    """A point of the closed ball ‖x‖ ≤ r_max in R³: radius × direction.

    ``x = ρ (sin θ cos φ, sin θ sin φ, cos θ)``, ρ ∈ [0, r_max]; ``‖x‖ = ρ``
    (extra ``"norm"``).  For homogeneous bounds divide by the right power of
    ρ before bounding (the ratio then depends on the direction only).

    Examples
    --------
    >>> ch = ball_point(r_max=2)
    >>> rho, theta, phi = ch.parameters
    >>> sympy.simplify(ch.value.dot(ch.value))
    rho**2
    """
    top = _positive_bound(r_max, "r_max")
    radius, theta, phi = _symbols(None if radius is None else (radius, theta, phi), "rho theta phi")
    return Chart(radius * _sphere(theta, phi),
                 _mapping({radius: (0, top), theta: (0, sympy.pi), phi: (0, 2 * sympy.pi)}),
                 _mapping({"norm": radius}), f"point of the ball of radius {top} in R³")
