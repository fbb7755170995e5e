"""Aleksandrov & Tikhonov (2017), Vestnik SPbSU — paper 001.

"Attitude stabilization of a rigid body in conditions of decreasing
dissipation".  Euler (1) with the torque (4), Poisson (2) for the inertial unit
vectors s1, s2, s3 (an orthonormal right-handed triad in body axes); here the
linear damping W = ωᵀDω:

    (9)  Jω̇ + ω×Jω = −2h(t)Dω − a1 s1×r1 − a2 s2×r2,      h(t) > 0, h(t) → 0 (5).

Theorem 1 (conditions (10), (11) on h): the equilibrium (3) ω = 0, sᵢ = rᵢ is
asymptotically stable.  Its Lyapunov function

    V = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² + γ h^ν(t) ωᵀJη,   η = a1 s1×r1 + a2 s2×r2,

and the paper prints V̇ along (2),(9) exactly; that print is checked term by term
(a time-varying coefficient: ḣ enters through ∂/∂t).

Section 6 example: A = 5, B = 6, C = 4, D = diag(4,4,4), a1 = a2 = 1,
h = (1+t)^{−7/8} (converges, oscillations die out near t ≈ 200) and
h = (1+t)^{−8/7} (bounded, not attractive).  The rᵢ are not printed: the
base-frame axes are assumed.

Modules: :mod:`.equations` (parameters, states, (2), (9)), :mod:`.theorem1`,
:mod:`.theorem1_bound` (the printed h^{ν−1}ḣ step, refuted for decreasing h, and its corrected form),
:mod:`.example` (section 6), :mod:`.lemma1` (Lemma 1 with a certified δ(ε)),
:mod:`.conditions_h` (conditions (5), (10), (11) on h decided symbolically; Corollary 1),
:mod:`.theorem2` (nonlinear damping), :mod:`.theorem2_example` (Theorem 2 / Corollary 2 simulated),
:mod:`.theorem2_envelope` (the algebraic envelope with α8 estimated),
:mod:`.theorem2_exponents` (Theorem 2 with W = (ωᵀDω)^{(μ+1)/2}, σ = μ odd ≥ 3: the item for μ = 5).
"""

from .equations import PAPER, D, J, P, a1, a2, eps, eta, gamma, h, nu, omega, r1, r2, r3, s1, s2, s3, system
from .theorem1 import functional, printed_Vdot, theorem1
from .theorem1_bound import theorem1_bound
from .example import HISTORY, example, remark2_energy
from .lemma1 import EPSILONS, Lemma1Constants, lemma1, lemma1_delta, lemma1_F
from .conditions_h import ConditionsOnH, corollary1, decide_h_conditions
from .remark2 import remark2
from .theorem2 import system4, theorem2
from .theorem2_exponents import theorem2_for, theorem2_mu5
from .theorem2_example import theorem2_example
from .corollary2 import corollary2

__all__ = [
    "PAPER",
    # parameters, states and the system (2), (9)
    "P", "J", "D", "a1", "a2", "h", "r1", "r2", "r3", "gamma", "nu", "eps", "omega", "s1", "s2", "s3", "eta", "system",
    # Theorem 1
    "functional", "printed_Vdot", "theorem1", "theorem1_bound",
    # section 6
    "HISTORY", "example", "remark2_energy",
    # Lemma 1
    "EPSILONS", "Lemma1Constants", "lemma1", "lemma1_F", "lemma1_delta",
    # conditions (5), (10), (11) on h; Corollary 1
    "ConditionsOnH", "corollary1", "decide_h_conditions",
    # Remark 2
    "remark2",
    # Theorem 2 (nonlinear damping)
    "system4", "theorem2",
    # Theorem 2 for other exponents μ = σ (odd ≥ 3)
    "theorem2_for", "theorem2_mu5",
    # Theorem 2 / Corollary 2 simulated (β = 7/8 and 8/7), the algebraic envelope with α8 estimated
    "theorem2_example",
    # Corollary 2
    "corollary2",
]
