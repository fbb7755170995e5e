"""Aleksandrov & Tikhonov (2023), Avtomatika i Telemekhanika — paper 002.

"Stability analysis of mechanical systems with essentially nonlinear positional
forces in the presence of distributed delay", section 5: monoaxial
stabilization of a rigid body with a distributed-delay torque.

Euler (9) with the control of (12), Poisson (10) for one inertial unit vector s:

    (10)  ṡ = −ω × s,
    (12)  Θω̇ + ω × (Θω) = −Fω − a‖s−r‖^{μ−1} s×r + b ∫_{t−τ}^t ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ,

target (11): s = r, ω = 0.  Theorem 3: μ > 1 and (14) bτ < a imply asymptotic
stability (Remark 3: a = 0, b < 0 is allowed).  The proof's functional is

    V = ½λ ωᵀΘω + ½‖s−r‖² + (s×r)ᵀF⁻¹Θω
        + b (s×r)ᵀF⁻¹ ∫_{t−τ}^t (ξ+τ−t) ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
        + ∫_{t−τ}^t (α + β(ξ+τ−t)) ‖s(ξ)−r‖^{μ+1} dξ,      λ, α, β > 0.

The paper prints only bounds on V̇ (with c5 … c9).  The claim checked here is
the exact V̇ in the structured form those bounds rest on; its key term is
−(a − τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r), which is where (14) enters.

Defaults are the section 6 data of Fig. 6: Θ = diag(5,6,4), r = (1,1,1)/√3,
F = h·I with h = 1, a = 0, b = −1, τ = 1, μ = 2.

Modules: :mod:`.equations` (parameters, states, (10), (12)), :mod:`.theorem3`,
:mod:`.theorem3_constants` (the constants for μ = 2, estimate (15)),
:mod:`.theorem3_chain` (the bound steps V ≥ L, V ≤ U, V̇ ≤ W and the decay),
:mod:`.theorem3_bound` (the printed V̇ bound, refuted, and corrected), :mod:`.theorem3_caps` (the best d1 and δ̃
of estimate (15) for this functional), :mod:`.section6` (the data of the
figures), :mod:`.fig1` … :mod:`.fig7`, :mod:`.fig7_chi` (‖χ‖_τ of the Fig. 7 data).
Theorem 1 (system (3), functional (П.1)): :mod:`.theorem1` on the radial Π̃ of :mod:`.system3`,
:mod:`.theorem1_nonradial` on a non-radial Π̃ (a general quartic form, the same chain with
‖∂Π̃/∂q‖ ≤ κ_g‖q‖^μ certified), :mod:`.corollary1` (the decay estimate).
The items are re-exported here under their names: ``aleksandrov2023.theorem3`` is the
item (the module is ``aleksandrov2023.theorem3`` in ``sys.modules``; import names from
it with ``from lkverify.proofs.aleksandrov2023.theorem3 import functional``).
"""

from .equations import PAPER, F, F_inv, J, K, P, Theta, a, alpha, b, beta, lam, mu, n, omega, r, s, system, tau
from .theorem3 import functional, structured_Vdot, theorem3
from .fig1 import fig1
from .fig2 import fig2
from .fig3 import fig3
from .fig4 import fig4
from .fig5 import fig5
from .fig6 import fig6
from .fig7 import fig7
from .theorem3_bound import theorem3_bound
from .theorem3_caps import theorem3_caps
from .fig7_chi import fig7_chi
from .section6 import FIG7_HISTORY, PRINTED_15, R_TARGET, SECTION6
from .theorem3_constants import THEOREM3_CONSTANTS
from .section6_conditions import section6
from .theorem1 import theorem1
from .theorem1_nonradial import theorem1_nonradial
from .theorem1_bound import theorem1_bound
from .corollary1 import corollary1
from .theorem2 import theorem2
from .theorem2_example import theorem2_counter, theorem2_example
from .linear_mu1 import linear_mu1

__all__ = [
    "PAPER",
    # parameters, states and the system (10), (12)
    "P", "Theta", "F", "F_inv", "a", "b", "tau", "mu", "r", "lam", "alpha", "beta", "omega", "s", "n", "J", "K",
    "system",
    # Theorem 3
    "functional", "structured_Vdot", "theorem3", "THEOREM3_CONSTANTS", "theorem3_bound", "theorem3_caps",
    # section 6
    "R_TARGET", "SECTION6", "FIG7_HISTORY", "PRINTED_15",
    "fig1", "fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig7_chi", "section6",
    # Theorem 1 (system (3), functional (П.1))
    "theorem1", "theorem1_bound", "corollary1", "theorem1_nonradial",
    # Theorem 2 (decomposition, section 4)
    "theorem2", "theorem2_example", "theorem2_counter",
    # the linear case μ = 1 (linearisation, damping threshold)
    "linear_mu1",
]
