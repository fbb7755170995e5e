"""Theorem 1 of paper 001: under conditions (10), (11) on h the equilibrium (3) ω = 0, sᵢ = rᵢ
of (2), (9) is asymptotically stable.

Its Lyapunov function

    V = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² + γ h^ν(t) ωᵀJη,   η = a1 s1×r1 + a2 s2×r2,

and the paper prints V̇ along (2),(9) exactly; that print is checked below term by term
(a time-varying coefficient: ḣ enters through ∂/∂t).  Conditions (5), (10), (11) on the run's
h and ν are decided symbolically (:mod:`.conditions_h`): e.g. ``--set "h=(1+t)**(-6/5)"`` fails
(11) for every ν ≥ 1 (Corollary 1: β ≤ 1 is needed).

The proof is checked to its conclusion by :mod:`.theorem1_chain`: V ≥ L, V ≤ U, V̇ ≤ W term by
term on ‖s_i − r_i‖ ≤ δ1 (Lemma 1 certified there, (10) decided with its exact L), then (12)
V̇ ≤ −α7 h^ν V for 0 < h ≤ sup h and the envelope (:class:`~lkverify.certify.steps.timevarying.TimeVaryingRate`),
(11) decided; the choices γ, ε, δ1, η_h, η_D, α7 are found at the run's gains.
"""

from lkverify import DerivativeClaim, Functional, Hypothesis, Term, Theorem, cross, dot, norm_squared, quad, t
from lkverify.declare.rigidbody import restoring_torque_rate

from .conditions_h import ConditionsOnH
from .equations import PAPER, D, J, a1, a2, eta, gamma, h, nu, omega, r1, r2, s1, s2, system

__all__ = ["functional", "printed_Vdot", "theorem1"]

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

from .theorem1_chain import CONCLUSION, EnvelopeAgainstRun, find_choices, split, steps  # noqa: E402  (it imports functional)

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: linear damping 2h(t)Dω with h → 0; the printed V̇ and the proof checked to (12) and the envelope",
    system=system,
    functional=functional,
    hypotheses=[Hypothesis("nu >= 1", nu - 1, strict=False, reference="(10), (11)"),
                ConditionsOnH("(5), (10), (11) on h", h, nu, reference="(5), (10), (11)")],
    claims=[DerivativeClaim("Vdot_printed", functional, system, printed_Vdot,
                            description="the printed V̇ along (2),(9), as printed"), split],
    steps=steps,
    decay=CONCLUSION,
    choices=find_choices,
    constants=EnvelopeAgainstRun(),
    paper=PAPER,
)
