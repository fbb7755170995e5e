"""Theorem 2 of paper 001 for other exponents: W = (ωᵀDω)^{(μ+1)/2} and σ ≥ μ, μ, σ odd integers ≥ 3 (issue 23).

The paper (section 5) takes W positive definite, C¹, homogeneous of order μ + 1 with μ > 1; the proof's
V = ½ωᵀJω + Σ(a_i/2)‖s_i − r_i‖² + γh^ν‖η‖^{σ−1}ωᵀJη with σ ≥ 1, and its last step needs σ ≥ μ and (15)
|ḣ| ≤ L h^{1+(1−ν)/(μ+1)}; then V̇ ≤ −α8 h^ν V^λ, λ = (σ + 1)/2.  Here the instance is
W = (ωᵀDω)^{(μ+1)/2} with σ ≥ μ, for μ, σ odd: (μ+1)/2 and (σ−1)/2 are integers, so W, grad W and
‖η‖^{σ−1} = (‖η‖²)^{(σ−1)/2} are polynomials and every rule works on polynomial identities (even μ would
put ‖η‖ and (ωᵀDω)^{1/2} under square roots: refused, :func:`.theorem2_functional.instance`).

What is proved symbolically, what per exponent
----------------------------------------------
* The identity V̇ = (the seven structured terms) holds for *every* μ = σ > 0 at once:
  :func:`.theorem2_functional.derivation_every_exponent` (μ a positive symbol, ``exact``; a slow test of
  tests/catalogue/test_aleksandrov2017_boxes.py).  Each item here also proves its own instance's identity.
* The bound chain is checked *per exponent*: the term bounds, their side conditions and the conclusion
  are decided at one integer μ (and at the run's numbers), since the Young splits below have as many
  pairs as the binomial expansion of (a1e1 + a2e2)^σ has terms.  The splits are derived by hand for a
  general odd μ = σ (:func:`~.theorem2_chain.hdot_young`, :func:`~.theorem2_chain.mixed_young`); the
  rules check each application (conjugate exponents, signs, weights, the matched monomials) — nothing
  is declared.

The splits (E = a1e1 + a2e2 ≥ ‖η‖ by the norm tree, A = a1 + a2, R = Aδ1 ≥ ‖η‖ on the region):

* ḣ-term: Cauchy–Schwarz and (15) give γνjL h^{(σν+1)/(σ+1)} w E^σ; Young with (p, q) = (σ+1, (σ+1)/σ)
  on x = h^{1/(σ+1)}w, y = h^{σν/(σ+1)}e1^a e2^{σ−a} (weight η_h), then (σ/a, σ/(σ−a)) on the mixed
  powers: ≤ γνjL(η_h A^σ h w^{σ+1}/(σ+1) + σ/(σ+1)·η_h^{−1/σ}A^{σ−1}h^ν Σa_i e_i^{σ+1}).
* the ηᵀM-, ω×Jω-, ωᵀJM- and grad W-terms: each becomes c·h^{ν(+1)} w² E^{σ−1} (for grad W after
  w^μ ≤ δ_ω^{μ−2}w² on the region), then Young with ((σ+1)/2, (σ+1)/(σ−1)) on x = h^{2ν/(σ+1)}w²,
  y = h^{(σ−1)ν/(σ+1)}e1^a e2^{σ−1−a} (weight η_w) and ((σ−1)/a, (σ−1)/(σ−1−a)) on the mixed powers.
* −(μ+1)hW ≤ −(μ+1)λ_min(D)^{(μ+1)/2}h w^{μ+1} and −γh^ν‖η‖^{σ+1} ≤ −γε^λh^ν(a1²e1² + a2²e2²)^λ (Lemma 1).
* the conclusion with λ = (σ+1)/2 (:class:`~lkverify.certify.steps.timevarying.TimeVaryingRate`):
  W + α8 h^ν 3^{λ−1}Σū_k^λ x_k^{2λ} ≤ 0 coefficient-wise, x_k^{2λ} = w^{σ+1}, e_i^{σ+1}: the damping must
  reach the w^{σ+1} of the splits (σ < μ leaves h^ν w^{σ+1} with a positive coefficient and nothing to
  absorb it: the conclusion fails at that monomial).

σ > μ (proved, the paper's "if σ ≥ μ"): on the region w ≤ δ_ω half of the damping is raised,
−w^{μ+1} ≤ −½w^{μ+1} − ½δ_ω^{μ−σ}w^{σ+1} (:class:`~lkverify.certify.steps.rewrites.RaiseOnRegion`, its
factor ≤ 0 and δ_ω > 0 decided); the ḣ-term is split with (μ+1, (μ+1)/μ) as in the paper, so its w-part
h w^{μ+1} meets the kept half and its e-parts e_i^{σ(μ+1)/μ} ≤ δ1^{(σ−μ)/μ}e_i^{σ+1} are lowered on the region
(:class:`~lkverify.certify.steps.rewrites.OnRegion`); this holds for every ν ≥ 1 (the (σ+1)-split would
need (15) with σ in place of μ once ν > 1).  W then has h w^{μ+1} with a negative coefficient besides the
monomials of the conclusion.  ``theorem2_for(3, 5)`` (λ = 3) is established at the section 6 gains, at
ν = 1 and at ν = 9/8 (α8 ≈ 9·10⁻¹² and 6·10⁻¹² with :func:`~.theorem2_chain.find_choices`), in about 7 s;
``theorem2_for(5, 7)`` (λ = 4) in about 36 s (a slow test).  Neither is catalogued.

Catalogued: ``aleksandrov2017.theorem2_mu5`` (W = (ωᵀDω)³, λ = 3), at the section 6 gains with choices from
:func:`~.theorem2_chain.find_choices`; ``aleksandrov2017.theorem2`` is μ = σ = 3 (:mod:`.theorem2`).
``theorem2_for(7)`` (W = (ωᵀDω)⁴, λ = 4) is established the same way but is not catalogued: its identity
alone takes about 77 s (a degree-8 polynomial identity; the chain about 6 s), too long for the bare report
that runs every item; any odd μ ≥ 3 can be built with :func:`theorem2_for`.
"""

from __future__ import annotations

import functools

from lkverify import Theorem

from .conditions_h import ConditionsOnH
from .equations import PAPER, h, nu
from .theorem2_chain import chain_steps, conclusion, find_choices
from .theorem2_functional import instance

__all__ = ["EXPONENTS", "theorem2_for", "theorem2_mu5"]

#: the exponents catalogued besides μ = 3 (:mod:`.theorem2`)
EXPONENTS = (5,)


def theorem2_for(mu_value, sigma_value=None, *, name=None) -> Theorem:
    """Theorem 2's item for W = (ωᵀDω)^{(μ+1)/2} and ‖η‖^{σ−1} in V (σ = μ unless given), μ, σ odd ≥ 3.

    Hypotheses (5), (15) with this μ, (11); the claim V̇ = structured terms along this instance's system;
    the chain :func:`~.theorem2_chain.chain_steps`, the conclusion with λ = (σ+1)/2 and the choices of
    :func:`~.theorem2_chain.find_choices` at the run's values.

    Parameters
    ----------
    mu_value, sigma_value : int
        Odd integers ≥ 3; σ > μ is proved as σ = μ is (the damping raised on the region); σ < μ builds the
        chain all the same (to see where it breaks: at the conclusion).
    name : str, optional
        The item's name (default ``theorem2_mu<μ>``, with ``_sigma<σ>`` when σ ≠ μ).

    Examples
    --------
    >>> item = theorem2_for(5)
    >>> item.name, item.decay.lam, item.system.name
    ('theorem2_mu5', 3, '(2),(4) with μ = 5')
    """
    inst = instance(mu_value, sigma_value)
    m, sg = int(inst.mu), int(inst.sigma)
    name = name or (f"theorem2_mu{m}" + ("" if sg == m else f"_sigma{sg}"))
    return Theorem(
        name,
        title=(f"Theorem 2 with W = (ωᵀDω)^{(m + 1) // 2} (μ = {m}), σ = {sg}: the chain to V̇ ≤ −α8h^νV^λ, "
               f"λ = {(sg + 1) // 2}"),
        system=inst.system,
        functional=inst.functional,
        hypotheses=[ConditionsOnH("(5), (15), (11) on h", h, nu, mu=inst.mu, reference=f"(5), (15) with μ = {m}, (11)")],
        claims=[inst.derivation],
        steps=chain_steps(m, sg),
        decay=conclusion(sg),
        choices=functools.partial(find_choices, mu=m, sigma=sg),
        paper=PAPER,
    )


theorem2_mu5 = theorem2_for(5)
