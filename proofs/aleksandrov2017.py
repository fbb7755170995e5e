"""Aleksandrov & Tikhonov (2017), Vestnik SPbSU — paper 001.

"Attitude stabilization of a rigid body in conditions of decreasing
dissipation".  Euler (1) with the torque (4), Poisson (2) for the inertial unit
vectors s1, s2, s3 (an orthonormal right-handed triad in body axes); here the
linear damping W = ωᵀDω:

    (9)  Jω̇ + ω×Jω = −2h(t)Dω − a1 s1×r1 − a2 s2×r2,      h(t) > 0, h(t) → 0 (5).

Theorem 1 (conditions (10), (11) on h): the equilibrium (3) ω = 0, sᵢ = rᵢ is
asymptotically stable.  Its Lyapunov function

    V = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² + γ h^ν(t) ωᵀJη,   η = a1 s1×r1 + a2 s2×r2,

and the paper prints V̇ along (2),(9) exactly; that print is checked below term
by term (a time-varying coefficient: ḣ enters through ∂/∂t).

Section 6 example: A = 5, B = 6, C = 4, D = diag(4,4,4), a1 = a2 = 1,
h = (1+t)^{−7/8} (converges, oscillations die out near t ≈ 200) and
h = (1+t)^{−8/7} (bounded, not attractive).  The rᵢ are not printed: the
base-frame axes are assumed.
"""

from lkverify import (DerivativeClaim, Equation, Frame, Functional, Hypothesis, Parameters, System, Term, Theorem,
                      Vector, cross, dot, norm_squared, quad, t)

PAPER = "aleksandrov2017"

P = Parameters()
J = P.diagonal_matrix("J", ["A", "B", "C"], default="diag(5,6,4)", latex="J", description="inertia tensor")
D = P.spd_matrix("D", 3, default="diag(4,4,4)", description="damping matrix of W = ωᵀDω")
a1 = P.scalar("a1", positive=True, default=1, latex="a_1")
a2 = P.scalar("a2", positive=True, default=1, latex="a_2")
h = P.coefficient("h", default="(1+t)**(-7/8)", description="vanishing damping factor h(t) > 0, h → 0")
r1 = P.unit_vector("r1", default="[1, 0, 0]")
r2 = P.unit_vector("r2", default="[0, 1, 0]")
r3 = P.unit_vector("r3", default="[0, 0, 1]")
P.orthonormal("r1", "r2", "r3")
# parameters of the Lyapunov function of Theorem 1
gamma = P.scalar("gamma", positive=True, latex=r"\gamma")
nu = P.scalar("nu", positive=True, default=1, latex=r"\nu", description="exponent ν ≥ 1 of conditions (10), (11)")

omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))

eta = a1 * cross(s1(t), r1) + a2 * cross(s2(t), r2)  # η

# (2), (9)
system = System([
    Equation(omega, [
        Term(-cross(omega(t), J * omega(t)), text="−ω×Jω", latex=r"-\omega\times J\omega"),
        Term(-2 * h(t) * D * omega(t), text="−2h(t)Dω", latex=r"-2h(t)D\omega"),
        Term(-eta, text="−(a1 s1×r1 + a2 s2×r2)", latex=r"-(a_1 s_1\times r_1 + a_2 s_2\times r_2)"),
    ], mass=J, mass_text="J", mass_latex="J"),
    *[Equation(si, [Term(-cross(omega(t), si(t)), text=f"−ω×{si.name}", latex=rf"-\omega\times {si.latex}")])
      for si in (s1, s2, s3)],
], parameters=P, name="(2),(9)")

# The Lyapunov function of the proof of Theorem 1
functional = Functional([
    Term(quad(omega(t), J) / 2, text="½ωᵀJω", latex=r"\tfrac12\omega^\top J\omega"),
    Term(a1 / 2 * norm_squared(s1(t) - r1), text="(a1/2)‖s1−r1‖²", latex=r"\tfrac{a_1}{2}\|s_1-r_1\|^2"),
    Term(a2 / 2 * norm_squared(s2(t) - r2), text="(a2/2)‖s2−r2‖²", latex=r"\tfrac{a_2}{2}\|s_2-r_2\|^2"),
    Term(gamma * h(t) ** nu * quad(omega(t), J, eta), text="γh^ν(t)ωᵀJη", latex=r"\gamma h^\nu(t)\omega^\top J\eta"),
], name="V of Theorem 1")

M = a1 * cross(cross(omega(t), s1(t)), r1) + a2 * cross(cross(omega(t), s2(t)), r2)
h_dot = h(t).diff(t)

# V̇ as printed in the proof of Theorem 1
printed_Vdot = [
    Term(-2 * h(t) * quad(omega(t), D), text="−2h(t)ωᵀDω", latex=r"-2h(t)\omega^\top D\omega"),
    Term(gamma * nu * h(t) ** (nu - 1) * h_dot * quad(omega(t), J, eta), text="γνh^{ν−1}ḣ ωᵀJη",
         latex=r"\gamma\nu h^{\nu-1}(t)\dot h(t)\omega^\top J\eta"),
    Term(gamma * h(t) ** nu * dot(eta, -cross(omega(t), J * omega(t)) - 2 * h(t) * D * omega(t) - eta),
         text="γh^ν ηᵀ(−ω×Jω − 2h(t)Dω − η)", latex=r"\gamma h^\nu(t)\eta^\top(-\omega\times J\omega-2h(t)D\omega-\eta)"),
    Term(-gamma * h(t) ** nu * quad(omega(t), J, M), text="−γh^ν ωᵀJ(a1(ω×s1)×r1 + a2(ω×s2)×r2)",
         latex=r"-\gamma h^\nu(t)\omega^\top J(a_1(\omega\times s_1)\times r_1+a_2(\omega\times s_2)\times r_2)"),
]

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: linear damping 2h(t)Dω with h → 0; the printed V̇ checked",
    system=system,
    functional=functional,
    hypotheses=[Hypothesis("nu >= 1", nu - 1, strict=False, reference="(10), (11)")],
    claims=[DerivativeClaim("Vdot_printed", functional, system, printed_Vdot,
                            description="the printed V̇ along (2),(9), as printed")],
    unchecked=["conditions (10), (11) on h", "the bounds with α1…α7 and the region δ2", "Lemma 1"],
)


# ---------------------------------------------------------------------------------------------
# Section 6: the example.  Initial aircraft angles (0.5, 0.5, −0.5), ω = (0.3, 0.3, 0.3).
import numpy as np  # noqa: E402

from lkverify.example import BoundedNotAttractive, Converges, DoesNotConverge, Example, Run, Series  # noqa: E402
from lkverify.rigidbody import inertial_vectors_from_angles  # noqa: E402

_S0 = inertial_vectors_from_angles(0.5, 0.5, -0.5)  # columns s1, s2, s3 (r_i = base axes)
HISTORY = {"omega": [0.3, 0.3, 0.3], "s1": list(_S0[:, 0]), "s2": list(_S0[:, 1]), "s3": list(_S0[:, 2])}
_E = np.eye(3)


def _e(i):
    return lambda states: np.linalg.norm(states[f"s{i}"] - _E[i - 1], axis=1)


def _distance(states):
    return np.sqrt(sum(_e(i)(states) ** 2 for i in (1, 2, 3)) + np.sum(states["omega"] ** 2, axis=1))


def _energy(states):
    """Ṽ = ½ωᵀJω + ½‖s1−r1‖² + ½‖s2−r2‖² (a1 = a2 = 1), the energy of Remark 2."""
    w = states["omega"]
    return 0.5 * (5 * w[:, 0] ** 2 + 6 * w[:, 1] ** 2 + 4 * w[:, 2] ** 2) + 0.5 * (_e(1)(states) ** 2 + _e(2)(states) ** 2)


CONVERGING, BOUNDED = "h = (1+t)^(−7/8)", "h = (1+t)^(−8/7)"
example = Example(
    "example",
    title="Section 6: decreasing dissipation h = (1+t)^(−β)",
    runs=[Run(CONVERGING, system, {"h": "(1+t)**(-7/8)"}, HISTORY),
          Run(BOUNDED, system, {"h": "(1+t)**(-8/7)"}, HISTORY)],
    t_end=2400,
    series=[Series("ω_x", lambda st: st["omega"][:, 0]), Series("ω_y", lambda st: st["omega"][:, 1]),
            Series("ω_z", lambda st: st["omega"][:, 2])],
    distance=_distance,
    claims=[Converges(CONVERGING, tol=1e-3, by=800),
            BoundedNotAttractive(BOUNDED, _energy, "(1+t)**(-8/7)", bound=3.0),
            DoesNotConverge(BOUNDED, floor=1e-2)],
    ylabel="ω components",
    samples=12001,
    plot_until=600,
)
