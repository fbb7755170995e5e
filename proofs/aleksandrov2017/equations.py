"""Paper 001: the parameters, the states and the closed loop (2), (9).

Euler (1) with the torque (4), Poisson (2) for the inertial unit vectors s1, s2, s3 (an
orthonormal right-handed triad in body axes); here the linear damping W = ωᵀDω:

    (2)  ṡᵢ = −ω × sᵢ,  i = 1, 2, 3,
    (9)  Jω̇ + ω×Jω = −2h(t)Dω − a1 s1×r1 − a2 s2×r2,      h(t) > 0, h(t) → 0 (5).

Defaults are the section 6 example: A = 5, B = 6, C = 4, D = diag(4,4,4), a1 = a2 = 1,
h = (1+t)^{−7/8}.  The rᵢ are not printed: the base-frame axes are assumed.
"""

from lkverify import Frame, Parameters, System, Term, Vector, t
from lkverify.declare.rigidbody import euler_equation, poisson_equations, restoring_torque

__all__ = ["PAPER", "P", "J", "D", "a1", "a2", "h", "r1", "r2", "r3", "gamma", "nu", "eps", "omega", "s1", "s2", "s3", "eta",
           "system"]

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
# the ε of Lemma 1
eps = P.scalar("eps", positive=True, description="ε ∈ (0, 1) of Lemma 1 (unset: 0.5, 0.9 and 0.99)")

omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))

eta = restoring_torque((s1, s2), (r1, r2), (a1, a2))  # η = a1 s1×r1 + a2 s2×r2

# (2), (9)
system = System([
    euler_equation(omega, J, [
        Term(-2 * h(t) * D * omega(t), text="−2h(t)Dω", latex=r"-2h(t)D\omega"),
        Term(-eta, text="−(a1 s1×r1 + a2 s2×r2)", latex=r"-(a_1 s_1\times r_1 + a_2 s_2\times r_2)"),
    ], mass_text="J", mass_latex="J", gyroscopic_text="−ω×Jω", gyroscopic_latex=r"-\omega\times J\omega"),
    *poisson_equations(omega, (s1, s2, s3)),
], parameters=P, name="(2),(9)")
