"""Theorem 3 of paper 002: μ > 1 and (14) bτ < a imply asymptotic stability of (11).

Remark 3: a = 0, b < 0 is allowed.  The proof's functional is

    V = ½λ ωᵀΘω + ½‖s−r‖² + (s×r)ᵀF⁻¹Θω
        + b (s×r)ᵀF⁻¹ ∫_{t−τ}^t (ξ+τ−t) ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
        + ∫_{t−τ}^t (α + β(ξ+τ−t)) ‖s(ξ)−r‖^{μ+1} dξ,      λ, α, β > 0.

The paper prints only bounds on V̇ (with c5 … c9).  The claim checked here is the exact
V̇ in the structured form those bounds rest on; its key term is
−(a − τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r), which is where (14) enters.  The constants of the
proof for μ = 2 (estimate (15)) are :data:`THEOREM3_CONSTANTS`
(:mod:`.theorem3_constants`).  The functional, V̇ and the steps are declared in
:mod:`.theorem3_functional`.
"""

from lkverify import Hypothesis, Theorem

from .equations import PAPER, a, b, mu, system, tau
from .theorem3_chain import CHOICES, DECAY
from .theorem3_constants import THEOREM3_CONSTANTS
from .theorem3_functional import derivation, functional, steps, structured_Vdot

__all__ = ["derivation", "functional", "steps", "structured_Vdot", "theorem3"]

theorem3 = Theorem(
    "theorem3",
    title="Theorem 3: monoaxial stabilization with a distributed-delay torque, μ > 1 and bτ < a",
    system=system,
    functional=functional,
    hypotheses=[
        Hypothesis("mu > 1", mu - 1, reference="(Theorem 3)"),
        Hypothesis("b*tau < a", a - b * tau, reference="(14)"),
    ],
    claims=[derivation],
    steps=steps,
    decay=DECAY,
    choices=CHOICES,
    constants=THEOREM3_CONSTANTS,
    paper=PAPER,
)
