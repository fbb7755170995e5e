"""Theorem 1 of paper 002: μ > 1, Π + τΠ̃ positive definite and (6) 2σ > μ + 1 imply asymptotic stability.

System (3) (section 3), A q̈ + B q̇ + ∂Π/∂q + P(q)q + ∫_{t−τ}^t ∂Π̃/∂q(q(ξ)) dξ = 0, is
catalogued for the instance of :mod:`.system3` (n = 2, μ = 3, σ = 3):

    Π = π40 q1⁴ + π31 q1³q2 + π22 q1²q2² + π13 q1q2³ + π04 q2⁴   (default ¼q1⁴ + ½q1³q2 − ⅛q2⁴, indefinite),
    Π̃ = (κ̃/4)‖q‖⁴,   P(q) = (p11 q1² + p12 q1q2 + p22 q2²)·[[0, 1], [−1, 0]],   ‖P(q)‖ ≤ p0‖q‖²,
    A = [[2, 1], [1, 2]],   B = [[3, 1], [1, 2]],   τ = 1,   κ̃ = 1,   φ = q1² + ½q1q2,   p0 = 11/10;

every coefficient can be set (``lkverify check aleksandrov2023.theorem1 --set pi04=-1/2``).

* Hypotheses (:mod:`.theorem1_hypotheses`): μ > 1, (6) 2σ > μ + 1 (exact), Π and Π̃
  homogeneous of order μ + 1 (exact), Π + τΠ̃ positive definite (certified on the unit
  circle), (4) ‖P(q)‖ ≤ p0‖q‖^{σ−1} (certified).
* V̇ of the functional (П.1) along (3) (:mod:`.theorem1_functional`): the structured form
  the chain bounds (exact with every parameter symbolic, μ included), and the appendix's
  printed V̇ (a finding; exact as printed).
* The chain (:mod:`.theorem1_chain`): the printed two-sided bounds with c1 … c6 and the V̇
  bound with c7 … c12, then Young's inequality and the region ‖q_t‖_τ ≤ δ_q, ‖q̇‖ ≤ δ_v to
  (П.2), (П.3), then Krasovskii's theorem; λ, α, β, δ_q, δ_v are found at the run's gains.
"""

from lkverify import Hypothesis, Theorem

from .equations import PAPER
from .system3 import mu, sigma, system3
from .theorem1_chain import CONCLUSION, find_choices, steps
from .theorem1_functional import derivation, functional, printed
from .theorem1_hypotheses import homogeneity, positive_definite, skew_bound

__all__ = ["theorem1", "HYPOTHESES"]

HYPOTHESES = [
    Hypothesis("mu > 1", mu - 1, reference="(Theorem 1)"),
    Hypothesis("2*sigma > mu + 1", 2 * sigma - mu - 1, reference="(6)"),
    homogeneity,
    positive_definite,
    skew_bound,
]

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: (3) with distributed-delay potential forces, μ > 1, Π + τΠ̃ ≻ 0, 2σ > μ + 1 (instance n = 2, μ = 3)",
    system=system3,
    functional=functional,
    hypotheses=HYPOTHESES,
    claims=[derivation],
    printed=[printed],
    steps=steps,
    decay=CONCLUSION,
    choices=find_choices,
    paper=PAPER,
)
