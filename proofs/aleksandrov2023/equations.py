"""Section 5 of paper 002: the parameters, the states and the closed loop (10), (12).

Euler (9) with the control of (12), Poisson (10) for one inertial unit vector s:

    (10)  ṡ = −ω × s,
    (12)  Θω̇ + ω × (Θω) = −Fω − a‖s−r‖^{μ−1} s×r + b ∫_{t−τ}^t ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ,

target (11): s = r, ω = 0.  Defaults are the section 6 data of Fig. 6: Θ = diag(5,6,4),
r = (1,1,1)/√3, F = h·I with h = 1, a = 0, b = −1, τ = 1, μ = 2.
"""

from lkverify import Parameters, System, Term, UnitVector, Vector, cross, norm_power, t, window_integral, xi
from lkverify.declare.rigidbody import euler_equation, poisson_equation

__all__ = ["PAPER", "P", "Theta", "F", "a", "b", "tau", "mu", "r", "lam", "alpha", "beta", "delta_e", "delta_w", "omega", "s", "n", "F_inv",
           "system", "J", "K"]

PAPER = "aleksandrov2023"

P = Parameters()
Theta = P.diagonal_matrix("Theta", ["A", "B", "C"], default="diag(5,6,4)", latex=r"\Theta",
                          description="inertia tensor diag(A, B, C)")
F = P.spd_matrix("F", 3, default="diag(1,1,1)", description="damping matrix, F = h·I in section 6")
a = P.scalar("a", nonnegative=True, default=0, description="restoring-torque gain, a ≥ 0")
b = P.scalar("b", default=-1, description="distributed-delay gain")
tau = P.delay("tau", default=1)
mu = P.scalar("mu", positive=True, default=2, latex=r"\mu", description="order of the restoring torque, μ ≥ 1")
r = P.unit_vector("r", default="[1/sqrt(3), 1/sqrt(3), 1/sqrt(3)]", description="target direction in the body")
# parameters of the functional of Theorem 3 (free: the identity holds for all of them)
lam = P.scalar("lam", positive=True, latex=r"\lambda")
alpha = P.scalar("alpha", positive=True, latex=r"\alpha")
beta = P.scalar("beta", positive=True, latex=r"\beta")
# the region of the proof's estimates: max_{[t−τ,t]} ‖s(ξ) − r‖ ≤ δ_e, ‖ω(t)‖ ≤ δ_w (free, chosen by the proof)
delta_e = P.scalar("delta_e", positive=True, latex=r"\delta_e", description="region: max over the window of ‖s − r‖")
delta_w = P.scalar("delta_w", positive=True, latex=r"\delta_\omega", description="region: ‖ω(t)‖")

omega = Vector("omega", latex=r"\omega", text="ω")
s = UnitVector("s")


def n(time):
    """‖s(time) − r‖^{μ−1}, the factor of the restoring torque in (12)."""
    return norm_power(s(time) - r, mu - 1)


F_inv = F.inv()

# (10), (12)
system = System([
    euler_equation(omega, Theta, [
        Term(-F * omega(t), text="−Fω", latex=r"-F\omega"),
        Term(-a * n(t) * cross(s(t), r), text="−a‖s−r‖^{μ−1}s×r", latex=r"-a\|s-r\|^{\mu-1}s\times r"),
        Term(b * window_integral(n(xi) * cross(s(xi), r), tau), text="b∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
             latex=r"b\int_{t-\tau}^{t}\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    ]),
    poisson_equation(omega, s),
], parameters=P, name="(10),(12)")

J = window_integral(n(xi) * cross(s(xi), r), tau)  # ∫_{t−τ}^t ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
K = window_integral(n(xi) * cross(s(xi), r), tau, weight=xi + tau - t)  # ∫_{t−τ}^t (ξ+τ−t) ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
