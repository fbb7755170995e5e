"""Paper 000: the parameters, the states, the delayed loop (2), (7) and the PID loop (2), (13).

Euler (1) and Poisson (2) for the inertial unit vectors s1, s2, s3 (an orthonormal
right-handed triad in body axes):

    (2)  ṡᵢ = −ω × sᵢ,  i = 1, 2, 3,
    (5)  L = α1 s1×r1 + α2 s2×r2,      f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²),
    (7)  Θω̇ + ω×(Θω) = −f^ν(t−τ) L(t−τ) − Dω,
    (13) Θω̇ + ω×(Θω) = −βf^ν L − Dω − ∫_0^t f^ν(ξ)G(t−ξ)L(ξ)dξ,   G(ζ) = g(ζ)I (Remark 3).

Defaults are the example of section 5: A = 20, B = 25, C = 35, r1 = (1/√2, 1/√2, 0),
r2 = (−1/√2, 1/√2, 0), r3 = (0, 0, 1), α1 = α2 = 1, ν = 0.3, D = 2I, τ = 1, β = 1,
g = e^{−2ζ}.
"""

from lkverify import Frame, Parameters, System, Term, Vector, memory_integral, t, xi
from lkverify.declare.rigidbody import distance_sum, euler_equation, poisson_equations, restoring_torque

__all__ = ["PAPER", "P", "Theta", "D", "alpha1", "alpha2", "nu", "tau", "r1", "r2", "r3", "gamma", "lam", "mu", "epsilon", "delta", "eta_w", "eta_K", "eta", "beta", "g",
           "omega", "s1", "s2", "s3", "L", "f", "W", "D_inv", "system", "system_pid"]

PAPER = "aleksandrov2026"

P = Parameters()
Theta = P.diagonal_matrix("Theta", ["A", "B", "C"], default="diag(20,25,35)", latex=r"\Theta")
D = P.spd_matrix("D", 3, default="diag(2,2,2)", description="damping matrix, constant PD")
alpha1 = P.scalar("alpha1", positive=True, default=1, latex=r"\alpha_1")
alpha2 = P.scalar("alpha2", positive=True, default=1, latex=r"\alpha_2")
nu = P.scalar("nu", positive=True, default="0.3", latex=r"\nu")
tau = P.delay("tau", default=1)
r1 = P.unit_vector("r1", default="[1/sqrt(2), 1/sqrt(2), 0]")
r2 = P.unit_vector("r2", default="[-1/sqrt(2), 1/sqrt(2), 0]")
r3 = P.unit_vector("r3", default="[0, 0, 1]")
P.orthonormal("r1", "r2", "r3")
# parameters of the functional (9)
gamma = P.scalar("gamma", positive=True, latex=r"\gamma")
lam = P.scalar("lam", positive=True, latex=r"\lambda")
mu = P.scalar("mu", positive=True, latex=r"\mu")
# the proof's other free choices (Theorem 1): ε of (10), the region δ, and Young's parameters of its steps
epsilon = P.scalar("epsilon", positive=True, latex=r"\epsilon", description="ε ∈ (0, 1) of inequality (10)")
delta = P.scalar("delta", positive=True, latex=r"\delta",
                 description="the region: ‖s_i(ξ) − r_i‖ ≤ δ on [t − τ, t], i = 1, 2")
eta_w = P.scalar("eta_w", positive=True, latex=r"\eta_\omega", description="Young's parameter of V ≥ L (ω terms)")
eta_K = P.scalar("eta_K", positive=True, latex=r"\eta_K", description="Young's parameter of V ≥ L (memory terms)")
eta = P.scalar("eta", positive=True, latex=r"\eta", description="Young's parameter of V̇ ≤ W")
# section 4: the nonlinear PID (8), (13)
beta = P.scalar("beta", default=1, latex=r"\beta", description="proportional gain β (β ≤ 0 allowed)")
g = P.kernel("g", default="exp(-2*zeta)", description="memory kernel, G(ζ) = g(ζ) I")

omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))


def L(time):
    """(5) L = α1 s1×r1 + α2 s2×r2."""
    return restoring_torque((s1, s2), (r1, r2), (alpha1, alpha2), time=time)


def f(time):
    """(5) f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²)."""
    return distance_sum((s1, s2), (r1, r2), 2, (alpha1 / 2, alpha2 / 2), time=time)


def W(time):
    """‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}, the integrand of (9)."""
    return distance_sum((s1, s2), (r1, r2), 2 * nu + 2, time=time)


D_inv = D.inv()

# (2), (7)
system = System([
    euler_equation(omega, Theta, [
        Term(-f(t - tau) ** nu * L(t - tau), text="−f^ν(t−τ)L(t−τ)", latex=r"-f^\nu(t-\tau)L(t-\tau)"),
        Term(-D * omega(t), text="−Dω", latex=r"-D\omega"),
    ]),
    *poisson_equations(omega, (s1, s2, s3)),
], parameters=P, name="(2),(7)")

# (2), (13)
system_pid = System([
    euler_equation(omega, Theta, [
        Term(-beta * f(t) ** nu * L(t), text="−βf^ν L", latex=r"-\beta f^\nu L"),
        Term(-D * omega(t), text="−Dω", latex=r"-D\omega"),
        Term(-memory_integral(f(xi) ** nu * g(t - xi) * L(xi)), text="−∫_0^t f^ν(ξ)G(t−ξ)L(ξ)dξ",
             latex=r"-\int_0^t f^\nu(\xi)G(t-\xi)L(\xi)d\xi"),
    ]),
    *poisson_equations(omega, (s1, s2, s3)),
], parameters=P, name="(2),(13)")
