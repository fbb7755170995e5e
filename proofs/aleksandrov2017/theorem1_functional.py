"""The Lyapunov function of Theorem 1 of paper 001 and its V̇ along (2), (9) as printed.

    V = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² + γ h^ν(t) ωᵀJη,   η = a1 s1×r1 + a2 s2×r2.

The theorem (:mod:`.theorem1`) and its chain (:mod:`.theorem1_chain`) both read these.
"""

from lkverify import Functional, Term, cross, dot, norm_squared, quad, t
from lkverify.declare.rigidbody import restoring_torque_rate

from .equations import D, J, a1, a2, eta, gamma, h, nu, omega, r1, r2, s1, s2

__all__ = ["functional", "printed_Vdot", "M", "h_dot"]

# The Lyapunov function of the proof of Theorem 1
functional = Functional([
    Term(quad(omega(t), J) / 2, text="½ωᵀJω", latex=r"\tfrac12\omega^\top J\omega"),
    Term(a1 / 2 * norm_squared(s1(t) - r1), text="(a1/2)‖s1−r1‖²", latex=r"\tfrac{a_1}{2}\|s_1-r_1\|^2"),
    Term(a2 / 2 * norm_squared(s2(t) - r2), text="(a2/2)‖s2−r2‖²", latex=r"\tfrac{a_2}{2}\|s_2-r_2\|^2"),
    Term(gamma * h(t) ** nu * quad(omega(t), J, eta), text="γh^ν(t)ωᵀJη", latex=r"\gamma h^\nu(t)\omega^\top J\eta"),
], name="V of Theorem 1")

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (a1, a2))  # a1(ω×s1)×r1 + a2(ω×s2)×r2 = −η̇ by (2)
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
