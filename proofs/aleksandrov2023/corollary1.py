"""Corollary 1 of paper 002: the decay estimate of system (3) under the conditions of Theorem 1.

"Using (П.2), (П.3), for ‖q_t‖ < δ the functional satisfies V̇ ≤ −c̃V^{(μ+1)/2}; integrating it":
there are d1, d2, d3, δ̃ > 0 such that for t0 ≥ 0, ‖χ‖_τ < δ̃

    ‖q(t)‖ ≤ d1‖χ‖_τ (1 + d3‖χ‖_τ^{μ−1}(t − t0))^{−1/(μ−1)},
    ‖q̇(t)‖ ≤ d2‖χ‖_τ (1 + d3‖χ‖_τ^{μ−1}(t − t0))^{−1/(μ−1)}.

For the instance of :mod:`.system3` (μ = 3) the checked steps V ≥ L, V ≤ U, V̇ ≤ W of
:mod:`.theorem1_chain` (the same objects as Theorem 1's) form the decay model
V̇ ≤ −c̃V² (p = (μ + 1)/2 = 2), whose constants :func:`lkverify.certify.decay.certify_model`
estimates and certifies in arb on the region: l_e, l_w (V ≥ l_e‖q‖², V ≥ l_w‖q̇‖²), c̃, C0
(V(t0) ≤ C0‖χ‖_τ², with (∫‖q‖⁴)^{1/4} ≤ τ^{1/4}‖χ‖_τ at t0) and δ̃ (the trajectory stays in
the region), hence d1 = (C0/l_e)^{1/2}, d2 = (C0/l_w)^{1/2}, d3 = c̃C0; the exponent
−1/(2(p − 1)) = −1/2 = −1/(μ − 1) and ‖χ‖^{2(p−1)} = ‖χ‖^{μ−1} are those of the corollary.
``lkverify constants aleksandrov2023.corollary1`` also simulates (3) from histories inside
the certified region and compares the trajectories with the certified envelopes.
"""

import sympy

from lkverify import Theorem
from lkverify.certify.steps.chain import Decay

from .equations import PAPER
from .system3 import system3
from .theorem1 import HYPOTHESES
from .theorem1_chain import find_choices, steps, tau_j
from .theorem1_functional import derivation, functional

__all__ = ["DECAY", "corollary1"]

#: V̇ ≤ −c̃V^{(μ+1)/2} for μ = 3; at t0 (∫‖q‖⁴)^{1/4} ≤ τ^{1/4}‖χ‖_τ
DECAY = Decay(sympy.Integer(2), ("w", "e"), {"j": tau_j}, {"d1": "e", "d2": "w"}, "d3",
              descriptions={"d1": "‖q(t)‖ ≤ d1‖χ‖_τ(1 + d3‖χ‖_τ²(t−t0))^{−1/2}:",
                            "d2": "‖q̇(t)‖ ≤ d2‖χ‖_τ(1 + d3‖χ‖_τ²(t−t0))^{−1/2}:", "d3": "the rate of Corollary 1:",
                            "delta_tilde": "valid for ‖χ‖_τ < δ̃:", "C0": "V(t0) ≤ C0‖χ‖_τ²",
                            "c_tilde": "V̇ ≤ −c̃V² on the region", "l_e": "V ≥ l_e‖q‖²", "l_w": "V ≥ l_w‖q̇‖²"})

corollary1 = Theorem(
    "corollary1",
    title="Corollary 1: ‖q‖, ‖q̇‖ ≤ d‖χ‖_τ(1 + d3‖χ‖_τ^{μ−1}(t−t0))^{−1/(μ−1)} for (3) (instance n = 2, μ = 3)",
    system=system3,
    functional=functional,
    hypotheses=HYPOTHESES,
    claims=[derivation],
    steps=steps,
    decay=DECAY,
    choices=find_choices,
    paper=PAPER,
)
