"""Kinematics of paper 003: the MRP σ, its relation to the quaternion, σ̇ = ¼B(σ)ω and its inverse (7).

Text (section 1): Λ = (λ0, λ) = (cos(Φ/2), e sin(Φ/2)), σ = e tan(Φ/4), "one-to-one" with Λ by
σ = λ/(1 + λ0) and λ0 = (1 − σ²)/(1 + σ²), λ = 2σ/(1 + σ²); the quaternion equation of (1)
Λ̇ = ½Λ∘ω gives (2), written with the dyad [ab] = abᵀ as (6) σ̇ = ¼B(σ)ω, inverted by (7)
ω = D(σ)σ̇.  Checked here, each exactly (rational functions, :mod:`.identities`):

* (6) from (1): σ̇ = d/dt[λ/(1 + λ0)] along λ̇0 = −½λ·ω, λ̇ = ½(λ0ω + λ×ω) equals ¼B(σ)ω — this
  fixes the sign of the 2[σ×] term of B (the extracted text lost every sign);
* (3) as read from the text, σ̇ = ¼(1 − σ²)ω + ½σ×ω + ½(σ·ω)σ, is (6) written with the dyad;
* BᵀB = (1 + σ²)²I (B/(1 + σ²) is a rotation), det B = (1 + σ²)³ > 0, D(σ)B(σ) = 4I: (7)
  inverts (6) for every σ;
* the quaternion relations: λ0² + ‖λ‖² = 1 and λ/(1 + λ0) = σ, and σ = e tan(Φ/4) through the
  half-angle parametrisation;
* the short rotation: the shadow MRP σˢ = −σ/σ² gives −Λ, the same attitude, with |σ||σˢ| = 1,
  so every attitude has an MRP with |σ| ≤ 1 (|Φ| ≤ π), and |σ| = 1 exactly at Φ = π where the
  text's quaternion is two-valued (tan(π/4) = 1).

Text and reconstruction: ``DIGEST.md`` reads the condition on σ(t0) in (3) as |σ(t0)| ≤ 1 (the
short rotation); the extracted text has only "2|| o" there (every Greek letter lost), which
fits "|Φ°| ≤ 2π" as well — a condition on the angle that puts no bound on |σ°| = |tan(Φ°/4)|.
Both readings describe an arbitrary initial attitude (the Conclusion's "произвольное начальное
угловое положение"); the shadow-set identity above is why |σ°| ≤ 1 loses no attitude.  The
item evaluates the documented initial attitude Φ0, e0 (``--set Phi0_deg=… --set e0=[…]``).
"""

from __future__ import annotations

import sympy

from lkverify import Check, Parameters, Result, Status

from .equations import PAPER, B, D, I3, cross_matrix
from .identities import OMEGA, SIG, matrix_identity

__all__ = ["K", "Phi0_deg", "e0", "kinematics", "kinematics_results", "mrp_of", "quaternion_of"]

#: the documented initial attitude of the examples (its own parameters: an Euler axis and angle)
K = Parameters()
Phi0_deg = K.scalar("Phi0_deg", default=150, description="initial Euler angle Φ0 in degrees")
e0 = K.unit_vector("e0", default="[2/3, 2/3, 1/3]", description="initial Euler axis e0")

_s2 = (SIG.T * SIG)[0]


def quaternion_of(s):
    """(λ0, λ) of an MRP σ: ((1 − σ²)/(1 + σ²), 2σ/(1 + σ²))."""
    s = sympy.Matrix(s)
    n2 = (s.T * s)[0]
    return (1 - n2) / (1 + n2), 2 * s / (1 + n2)


def mrp_of(angle, axis):
    """σ = e tan(Φ/4) of an Euler angle and axis (exact)."""
    return sympy.Matrix(axis) * sympy.tan(sympy.sympify(angle) / 4)


def kinematics_results(Bf=B) -> list:
    """The identities of the module docstring for the matrix function ``Bf`` (a mutation: another B)."""
    s, w = SIG, OMEGA
    rows = []
    # (1) → (2)/(6): σ = λ/(1 + λ0) differentiated along Λ̇ = ½Λ∘ω, expressed in σ
    l0, lam = quaternion_of(s)
    l0dot, lamdot = -(lam.T * w)[0] / 2, (l0 * w + cross_matrix(lam) * w) / 2
    sdot = (lamdot * (1 + l0) - lam * l0dot) / (1 + l0) ** 2
    rows.append(matrix_identity("(6) from (1)", sdot, Bf(s) * w / 4,
                                text="d/dt[λ/(1+λ0)] along Λ̇ = ½Λ∘ω equals ¼B(σ)ω, B = (1−σ²)I + 2[σ×] + 2[σσ]"))
    n2 = (s.T * s)[0]
    rows.append(matrix_identity("(3) = (6)", (1 - n2) * w / 4 + s.cross(w) / 2 + (s.T * w)[0] * s / 2, Bf(s) * w / 4,
                                text="(3) as read, σ̇ = ¼(1 − σ²)ω + ½σ×ω + ½(σ·ω)σ, equals (6) ¼B(σ)ω"))
    rows.append(matrix_identity("B^T B = (1+|sigma|^2)^2 I", Bf(s).T * Bf(s), (1 + _s2) ** 2 * I3,
                                text="BᵀB = (1 + σ²)²I: B/(1 + σ²) is orthogonal"))
    rows.append(matrix_identity("det B = (1+|sigma|^2)^3", Bf(s).det(), (1 + _s2) ** 3,
                                text="det B(σ) = (1 + σ²)³ > 0: B is invertible for every σ"))
    rows.append(matrix_identity("(7) D(sigma) B(sigma) = 4I", D(s) * Bf(s), 4 * I3,
                                text="(7): ω = D(σ)σ̇ with D = 4Bᵀ/(1+σ²)² inverts σ̇ = ¼B(σ)ω"))
    return rows


def _quaternion_rows() -> list:
    s = SIG
    l0, lam = quaternion_of(s)
    rows = [matrix_identity("lambda0^2 + |lambda|^2 = 1", l0 ** 2 + (lam.T * lam)[0], 1,
                            text="λ0 = (1−σ²)/(1+σ²), λ = 2σ/(1+σ²) is a unit quaternion"),
            matrix_identity("sigma = lambda/(1+lambda0)", lam / (1 + l0), s, text="the direct relation σ = λ/(1+λ0)")]
    tq, e = sympy.Symbol("t_q", real=True), sympy.Matrix(sympy.symbols("e1:4", real=True))
    # σ = e tan(Φ/4): with τ = tan(Φ/4), cos(Φ/2) = (1−τ²)/(1+τ²), sin(Φ/2) = 2τ/(1+τ²) (half angle)
    rows.append(matrix_identity("sigma = e tan(Phi/4)", (2 * tq / (1 + tq ** 2)) * e / (1 + (1 - tq ** 2) / (1 + tq ** 2)),
                                e * tq, text="λ/(1+λ0) with λ0 = cos(Φ/2), λ = e sin(Φ/2), ‖e‖ = 1, equals e tan(Φ/4)"))
    sh = -s / _s2
    l0s, lams = quaternion_of(sh)
    rows.append(matrix_identity("shadow MRP gives -Lambda", sympy.Matrix([l0s, *lams]), -sympy.Matrix([l0, *lam]),
                                text="σˢ = −σ/σ² gives (λ0, λ)(σˢ) = −(λ0, λ)(σ): the same attitude, |σ||σˢ| = 1, "
                                     "so every attitude has an MRP with |σ| ≤ 1 (short rotation |Φ| ≤ π)"))
    one = sympy.tan(sympy.pi / 4)
    rows.append(Result("identity", "tan(pi/4) = 1", Status.EXACT if one == 1 else Status.FAILED, None,
                       f"at Φ = π (cos(Φ/2) = 0: Λ and −Λ both describe it) |σ| = tan(π/4) = {one}: the short-rotation "
                       f"ball |σ| ≤ 1 is the whole attitude space"))
    return rows


def _initial_rows(v) -> list:
    Phi = sympy.sympify(v["Phi0_deg"]) * sympy.pi / 180
    s0 = mrp_of(Phi, v["e0"])
    n = sympy.sqrt(sympy.simplify((s0.T * s0)[0]))
    short = bool(sympy.Abs(Phi) <= sympy.pi)
    inside = (n - 1).is_nonpositive
    status = Status.EXACT if inside is not None else Status.UNDECIDED
    return [Result("constant", "initial MRP sigma0", status,
                   {"sigma0": [float(x) for x in s0], "norm": float(n), "short_rotation": short},
                   f"σ0 = e0 tan(Φ0/4) = {[round(float(x), 6) for x in s0]}, |σ0| = tan({sympy.sstr(Phi / 4)}) = "
                   f"{float(n):.6g} {'≤' if inside else '>'} 1 (|Φ0| {'≤' if short else '>'} π"
                   f"{'' if inside else ': the shadow σˢ = −σ0/|σ0|² describes the same attitude with |σˢ| < 1'})")]


def _check(v) -> list:
    return kinematics_results() + _quaternion_rows() + _initial_rows(v)


kinematics = Check("kinematics", parameters=K, checks=[_check], paper=PAPER,
                   title="(2), (6), (7): MRP kinematics σ̇ = ¼B(σ)ω, its inverse, the quaternion and the short rotation")
