"""Theorem 2 of paper 001: nonlinear damping h(t) grad W(ω), W homogeneous of order μ + 1 > 2.

    (4)  Jω̇ + ω×Jω = −h(t) grad W(ω) − a1 s1×r1 − a2 s2×r2,

catalogued with the instance W = (ωᵀDω)^{(μ+1)/2} for μ = 3, i.e. W = (ωᵀDω)² (positive definite,
homogeneous of order μ + 1 = 4, grad W = 4(ωᵀDω)Dω), and σ = μ = 3.  Theorem 2: if (5), (15) |ḣ| ≤ L h^{1+(1−ν)/(μ+1)}
and (11) ∫h^ν = ∞ hold for some ν ≥ 1, the equilibrium is asymptotically stable.  The proof's
function, with η = a1 s1×r1 + a2 s2×r2, γ > 0 and σ ≥ 1 (σ ≥ μ in its last step),

    V = ½ωᵀJω + (a1/2)‖s1 − r1‖² + (a2/2)‖s2 − r2‖² + γh^ν(t)‖η‖^{σ−1}ωᵀJη,

and its derivative along (2), (4) in the structured form the printed estimate with α3 … α6
bounds term by term (M = a1(ω×s1)×r1 + a2(ω×s2)×r2 = −η̇):

    V̇ = −(μ+1)h(ωᵀDω)^{(μ+1)/2} + γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη − γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)
        − γh^ν‖η‖^{σ−1}(ω×Jω)ᵀη − γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη − γh^ν‖η‖^{σ+1} − γh^ν‖η‖^{σ−1}ωᵀJM.

The first term is −h·ωᵀgrad W = −(μ+1)hW (Euler's theorem for homogeneous W): the energy
only decreases through the damping.  The claim is proved for every h, ν, γ, J, D, a1, a2.

The system, V and V̇ are in :mod:`.theorem2_functional`; the chain (16), V̇ ≤ W, V̇ ≤ −α8h^νV^λ and the
algebraic envelope, checked exact/certified at choices found at the run's values, in :mod:`.theorem2_chain`.
Other odd exponents μ = σ (the item ``theorem2_mu5``, :func:`.theorem2_exponents.theorem2_for`): :mod:`.theorem2_exponents`.
"""

from lkverify import Theorem

from .conditions_h import ConditionsOnH
from .equations import PAPER, h, nu
from .theorem2_chain import CONCLUSION, find_choices, steps
from .theorem2_envelope import ProvedEnvelopeAgainstRun
from .theorem2_functional import W, derivation2, functional2, grad_W, mu, sigma, structured, system4

__all__ = ["W", "grad_W", "functional2", "derivation2", "system4", "theorem2", "mu", "sigma", "structured"]

theorem2 = Theorem(
    "theorem2",
    title="Theorem 2: nonlinear damping h(t)grad W, instance W = (ωᵀDω)² (μ = 3), σ = 3, to V̇ ≤ −α8h^νV^λ",
    system=system4,
    functional=functional2,
    hypotheses=[ConditionsOnH("(5), (15), (11) on h", h, nu, mu=mu, reference="(5), (15) with μ = 3, (11)")],
    claims=[derivation2],
    steps=steps,
    decay=CONCLUSION,
    choices=find_choices,
    constants=ProvedEnvelopeAgainstRun(),
    paper=PAPER,
)
