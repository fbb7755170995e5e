"""Aleksandrov (2026), Avtomatika i Telemekhanika — paper 000.

"Control of the triaxial orientation of a rigid body with delay in the
feedback", section 3: a delayed essentially nonlinear restoring torque.

Euler (1) and Poisson (2) for the inertial unit vectors s1, s2, s3 (an
orthonormal right-handed triad in body axes):

    (2)  ṡᵢ = −ω × sᵢ,  i = 1, 2, 3,
    (5)  L = α1 s1×r1 + α2 s2×r2,      f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²),
    (7)  Θω̇ + ω×(Θω) = −f^ν(t−τ) L(t−τ) − Dω.

Theorem 1: for every τ > 0 the equilibrium (3) ω = 0, sᵢ = rᵢ is
asymptotically stable.  Functional (9) (printed with the label (1)):

    V = f + (γ/2)ωᵀΘω + LᵀD⁻¹Θω + ∫_{t−τ}^t (λ(ξ+τ−t)+μ) W(ξ) dξ − LᵀD⁻¹ ∫_{t−τ}^t f^ν(ξ)L(ξ) dξ,
    W = ‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}.

The paper then prints V̇ along (2),(7).  That print is entered exactly as
printed, term by term; the one liberty is its ``ω^⊤(t) L^⊤(t−τ)``, a row times
a row, read as the scalar product ωᵀL(t−τ).  Whatever the comparison with the
derivation finds is the result.  Section 4, Theorem 2: the nonlinear PID (13).

Defaults are the example of section 5: A = 20, B = 25, C = 35,
r1 = (1/√2, 1/√2, 0), r2 = (−1/√2, 1/√2, 0), r3 = (0, 0, 1), α1 = α2 = 1,
ν = 0.3, D = 2I, τ = 1.

Modules: :mod:`.equations` (parameters, states, (2), (7), (13)), :mod:`.theorem1`,
:mod:`.theorem1_bound` (the printed V̇ bound with c5…c10 on the exact V̇, proved),
:mod:`.functional9`, :mod:`.theorem1_chain` (the proof's chain to the conclusion, its choices),
:mod:`.remark1` (the certified δ against τ and α), :mod:`.remark1_runs`
(simulations at τ = 2, 5, 10 with α scaled), :mod:`.remark3` (β ≤ 0 with G = a g I: the threshold a*),
:mod:`.theorem2`, :mod:`.theorem2_bound` (the printed γβc7 step, refuted for β < 0, and its
corrected form), :mod:`.theorem2_chain` (the proof of Theorem 2 to its conclusion with memory
measures, its choices, the printed V̇ bound and final estimates), :mod:`.example` (section 5).
"""

from .equations import (PAPER, D, D_inv, L, P, Theta, W, alpha1, alpha2, beta, f, g, gamma, lam, mu, nu, omega, r1, r2, r3,
                        s1, s2, s3, system, system_pid, tau)
from .theorem1 import functional, int_fL, printed_Vdot, theorem1
from .theorem1_bound import theorem1_bound
from .remark1 import remark1
from .remark3 import remark3
from .theorem2 import Xi, theorem2
from .theorem2_bound import theorem2_bound
from .example import HISTORY, example

__all__ = [
    "PAPER",
    # parameters, states and the systems (2), (7) and (2), (13)
    "P", "Theta", "D", "D_inv", "alpha1", "alpha2", "nu", "tau", "r1", "r2", "r3", "gamma", "lam", "mu", "beta", "g",
    "omega", "s1", "s2", "s3", "L", "f", "W", "system", "system_pid",
    # Theorem 1
    "functional", "int_fL", "printed_Vdot", "theorem1", "theorem1_bound", "remark1", "remark3",
    # Theorem 2
    "Xi", "theorem2", "theorem2_bound",
    # section 5
    "HISTORY", "example",
]
