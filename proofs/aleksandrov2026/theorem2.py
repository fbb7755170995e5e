"""Theorem 2 of paper 000: under Assumptions 1–2 the equilibrium of (2), (13) is asymptotically stable.

With G = g(ζ)I: Ξ = βI + ∫_0^∞ G = (β + ∫_0^∞ g) I, Assumption 2: ΞD + DΞᵀ ≻ 0; Remark 3
reduces it to β + ∫_0^∞ g > 0 (D ≻ 0); Assumption 1 for g = e^{−aζ} holds with σ = 1/a
(decided for any g: :mod:`.assumption1`).  V̇ of functional (14) along (2), (13) is the
structured form of :mod:`.functional14`, proved for every kernel g.  The proof's chain
(:mod:`.theorem2_chain`): V ≥ L, V ≤ U, V̇ ≤ W on ‖s_i(ξ) − r_i‖ ≤ δ for ξ ∈ [0, t] with the memory
measures, the εc11 step, Assumption 1's σ and Hölder's c12, then Krasovskii's conclusion with the
memory kernels integrable; the choices (γ, μ, ε, δ, η's) found at the run's gains.
"""

import sympy

from lkverify import Hypothesis, MatrixHypothesis, Theorem, zeta

from .assumption1 import Assumption1
from .equations import PAPER, D, beta, g, system_pid
from .functional14 import derivation, functional
from .theorem2_chain import CONCLUSION, find_choices, steps

__all__ = ["theorem2", "Xi"]

int_g = sympy.Integral(g(zeta), (zeta, 0, sympy.oo))  # ∫_0^∞ g(ζ)dζ
Xi = (beta + int_g) * sympy.eye(3)  # Ξ = βI + ∫_0^∞ G(ζ)dζ

theorem2 = Theorem(
    "theorem2",
    title="Theorem 2: nonlinear PID with a fading-memory kernel (the proof checked to the end)",
    system=system_pid,
    functional=functional,
    hypotheses=[MatrixHypothesis("Xi*D + D*Xi^T > 0", Xi * D + D * Xi.T, reference="(Assumption 2)"),
                Hypothesis("beta + int g > 0", beta + int_g, reference="(Remark 3)"),
                Assumption1("Assumption 1", g, reference="(Assumption 1)")],
    claims=[derivation],
    steps=steps,
    decay=CONCLUSION,
    choices=find_choices,
    paper=PAPER,
)
