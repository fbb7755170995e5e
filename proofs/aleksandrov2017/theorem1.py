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

from lkverify import DerivativeClaim, Hypothesis, Theorem

from .conditions_h import ConditionsOnH
from .equations import PAPER, h, nu, system
from .theorem1_chain import CONCLUSION, EnvelopeAgainstRun, find_choices, split, steps
from .theorem1_functional import functional, printed_Vdot

__all__ = ["functional", "printed_Vdot", "theorem1"]

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
