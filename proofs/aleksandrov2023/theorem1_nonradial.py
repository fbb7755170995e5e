"""Theorem 1 of paper 002 on a non-radial Π̃: the same functional (П.1) and chain, Π̃ not a function of ‖q‖.

The catalogued :mod:`.theorem1` uses the instance of :mod:`.system3`, whose Π̃ = (κ̃/4)‖q‖⁴ is
radial (∂Π̃/∂q = κ̃‖q‖²q).  Theorem 1 asks of Π̃ only what it asks of Π: C¹ and homogeneous of
order μ + 1 > 2; with μ > 1, Π + τΠ̃ positive definite and (6) 2σ > μ + 1.  This module checks
it on (3) with n = 2, μ = σ = 3 and a general quartic form Π̃ (every coefficient a parameter):

    Π̃ = π̃40 q1⁴ + π̃31 q1³q2 + π̃22 q1²q2² + π̃13 q1q2³ + π̃04 q2⁴   (default −½q1³q2 + ¾q1²q2² + ½q2⁴),

the rest as :mod:`.system3` (Π = ¼q1⁴ + ½q1³q2 − ⅛q2⁴, A, B, φ, p0, τ = 1).  The default Π̃ is
not radial (Π̃(1, 0) = 0, Π̃(0, 1) = ½; ∂Π̃/∂q is not parallel to q) and not even positive
definite (Π̃(1, 1/2) < 0), while Π + τΠ̃ = ¼q1⁴ + ¾q1²q2² + ⅜q2⁴ is.

* Hypotheses: those of :mod:`.theorem1_hypotheses` on these forms (μ > 1, (6), Π and Π̃
  homogeneous of order μ + 1, Π + τΠ̃ positive definite, (4)); A, B ≻ 0 are checked when
  the values are read (symmetric positive-definite parameters).
* V̇ of (П.1) along (3): the structured and the printed V̇ (:func:`.theorem1_functional.instance`).
* The chain: the term bounds of :mod:`.theorem1_chain` (:func:`~.theorem1_chain.chain_steps`), with
  one change.  The radial chain bounds ‖∂Π̃/∂q(q(ξ))‖ = κ̃‖q(ξ)‖³ by matching the integrand
  with κ̃‖q‖²·q (:func:`.theorem1_bound.gradient_tree`) and sets c4 = c10 = c12 = κ̃ — true
  only for the radial Π̃.  Here ‖∂Π̃/∂q(q)‖ ≤ κ_g‖q‖^μ is the library's
  :func:`~lkverify.certify.steps.rules.homogeneous_field` (the field homogeneous of degree μ,
  exact; κ_g ≥ max over the unit circle, κ_g²‖x‖⁶ − ‖∂Π̃/∂x‖² > 0 certified on the circle),
  and c4 = c10 = c12 = κ_g, a choice of the proof (:func:`find_choices`: the sampled maximum
  of ‖∂Π̃/∂q‖ on the circle plus 1 %, three digits; ``--set kappa_g=…`` states another).
* The conclusion: Krasovskii's sign test and (П.3) compared, as for :mod:`.theorem1`.

The parameters are declared under the names of :mod:`.system3`, so the symbols are the same
SymPy symbols and the chain's term bounds apply unchanged; only Π̃ (π̃ij, no κ̃) and κ_g differ.
"""

import numpy as np
import sympy

from lkverify import Equation, Hypothesis, Parameters, System, Term, Theorem, Vector, t, window_integral, xi
from lkverify.certify.steps.rules import homogeneous_field, integral_of

from . import system3 as S3
from . import theorem1_chain as T1C
from .equations import PAPER
from .theorem1_bound import DEFINITIONS, c4, c10, c12
from .theorem1_functional import instance
from .theorem1_hypotheses import FormHypothesis, Homogeneity, SkewBound

__all__ = ["PN", "Pi", "Pi_t", "GRAD_PI_T", "PT_COEFFS", "kappa_g", "system_nonradial", "functional", "derivation",
           "printed", "K_int", "J_int", "gradient_tree", "DEFINITIONS_NONRADIAL", "HYPOTHESES", "steps",
           "find_choices", "kappa_g_estimate", "theorem1_nonradial"]

PN = Parameters()
A = PN.spd_matrix("A", 2, default="[[2, 1], [1, 2]]", description="inertia matrix A of (3), symmetric, A ≻ 0")
B = PN.spd_matrix("B", 2, default="[[3, 1], [1, 2]]", description="damping matrix B of (3), symmetric, B ≻ 0")
tau = PN.delay("tau", default=1)
mu = PN.scalar("mu", positive=True, default=3, latex=r"\mu", description="Π, Π̃ homogeneous of order μ + 1")
sigma = PN.scalar("sigma", positive=True, default=3, latex=r"\sigma", description="order in (4): ‖P(q)‖ ≤ p0‖q‖^{σ−1}")
p0 = PN.scalar("p0", positive=True, default="11/10", latex="p_0", description="the constant of (4)")
_pi_defaults = {"pi40": "1/4", "pi31": "1/2", "pi22": 0, "pi13": 0, "pi04": "-1/8"}
_pi = {ij: PN.scalar(name, default=_pi_defaults[name], description=f"coefficient of q1^{ij[0]} q2^{ij[1]} in Π")
       for ij, name in S3.PI_COEFFS.items()}
#: Π̃(q) = Σ π̃_ij q1^i q2^j (i + j = 4)
PT_COEFFS = {(4, 0): "pt40", (3, 1): "pt31", (2, 2): "pt22", (1, 3): "pt13", (0, 4): "pt04"}
_pt_defaults = {"pt40": 0, "pt31": "-1/2", "pt22": "3/4", "pt13": 0, "pt04": "1/2"}
_pt = {ij: PN.scalar(name, default=_pt_defaults[name], latex=rf"\tilde\pi_{{{ij[0]}{ij[1]}}}",
                     description=f"coefficient of q1^{ij[0]} q2^{ij[1]} in Π̃")
       for ij, name in PT_COEFFS.items()}
_phi_defaults = {"p11": 1, "p12": "1/2", "p22": 0}
_phi = {ij: PN.scalar(name, default=_phi_defaults[name], description=f"coefficient of q1^{ij[0]} q2^{ij[1]} in φ")
        for ij, name in S3.PHI_COEFFS.items()}
# the proof's free choices (as in system3) and the bound constant of ∂Π̃/∂q
lam, alpha, beta, delta_q, delta_v, eta_w, eta_K, eta, eta_j = S3.declare_choices(PN)
kappa_g = PN.scalar("kappa_g", positive=True, latex=r"\kappa_g",
                    description="‖∂Π̃/∂q(q)‖ ≤ κ_g‖q‖^μ (c4 = c10 = c12; chosen by the proof)")

X = S3.X
Pi = sum((c * X[0] ** i * X[1] ** j for (i, j), c in _pi.items()), sympy.S.Zero)
Pi_t = sum((c * X[0] ** i * X[1] ** j for (i, j), c in _pt.items()), sympy.S.Zero)
#: ∂Π̃/∂x in the plain variables x = (x1, x2)
GRAD_PI_T = sympy.ImmutableMatrix([sympy.diff(Pi_t, x) for x in X])
q, v = S3.q, S3.v


def grad_Pi_t(time):
    """∂Π̃/∂q(q(time)) (a vector of cubic forms, not a multiple of q)."""
    return S3.grad(Pi_t, q(time))


# (3) as q̇ = v, A v̇ = … (Π, P(q) as in system3)
system_nonradial = System([
    Equation(q, [Term(v(t), text="q̇", latex=r"\dot q")]),
    Equation(v, [
        Term(-B * v(t), text="−Bq̇", latex=r"-B\dot q"),
        Term(-S3.grad(Pi, q(t)), text="−∂Π/∂q", latex=r"-\partial\Pi/\partial q"),
        Term(-S3.skew(t) * q(t), text="−P(q)q", latex=r"-P(q)q"),
        Term(-window_integral(grad_Pi_t(xi), tau), text="−∫∂Π̃/∂q(q(ξ))dξ",
             latex=r"-\int_{t-\tau}^t\partial\tilde\Pi/\partial q(q(\xi))\,d\xi"),
    ], mass=A, mass_text="A", mass_latex="A"),
], parameters=PN, name="(3), Π̃ not radial")

functional, _structured, _printed_terms, derivation, printed, K_int, J_int = instance(grad_Pi_t, system_nonradial)


def gradient_tree(measure, *, holder=None, weight=1):
    """‖∫ g(ξ) ∂Π̃/∂q(q(ξ)) dξ‖ ≤ κ_g·(max|g| or Hölder)·(measure): ‖∂Π̃/∂q(q)‖ ≤ κ_g‖q‖^μ by homogeneity.

    The pointwise bound is :func:`~lkverify.certify.steps.rules.homogeneous_field` of ∂Π̃/∂x,
    of degree μ, with κ_g moved into the weight (as κ̃ in :func:`.theorem1_bound.gradient_tree`).

    Examples
    --------
    >>> tree = gradient_tree(T1C.J_, holder=T1C._holder)
    >>> tree.how
    'window integral'
    """
    pointwise = homogeneous_field(GRAD_PI_T, X, measure, degree=mu, kappa=kappa_g, at=xi)
    return integral_of(pointwise, measure=measure, power=mu, weight=kappa_g * weight, holder=holder)


#: c1 … c12 as in theorem1_bound, except c4 = c10 = c12 = κ_g (the radial instance has κ̃)
DEFINITIONS_NONRADIAL = {**DEFINITIONS, c4: kappa_g, c10: kappa_g, c12: kappa_g}

steps = T1C.chain_steps(functional=functional, system=system_nonradial, derivation=derivation, K=K_int, J=J_int,
                        tree=gradient_tree, definitions=DEFINITIONS_NONRADIAL)


def kappa_g_estimate(values):
    """A rational κ_g above the sampled max of ‖∂Π̃/∂q‖ on the unit circle (×1.01, three digits; ≥ 1/1000).

    Only a choice: the chain's steps certify κ_g²‖x‖^{2μ} − ‖∂Π̃/∂x‖² > 0 on the circle.

    Examples
    --------
    >>> kappa_g_estimate(PN.resolve({}, use_defaults=True))          # the max is 2, at q = (0, 1)
    101/50
    """
    from lkverify.declare.parameters import apply_substitution

    g = apply_substitution(GRAD_PI_T, PN.substitution(values))
    sampled = float(np.max(np.sqrt(T1C._circle(g[0] ** 2 + g[1] ** 2))))
    return T1C._above(max(sampled * 1.01, 1e-3))


def find_choices(values) -> dict:
    """κ_g, then λ, α, β, δ_q, δ_v and the η's by the recipe of :func:`.theorem1_chain.find_choices` with kt = κ_g.

    Examples
    --------
    >>> ch = find_choices(PN.resolve({}, use_defaults=True))
    >>> sorted(ch)
    ['alpha', 'beta', 'delta_q', 'delta_v', 'eta', 'eta_K', 'eta_j', 'eta_w', 'kappa_g', 'lam']
    """
    kg = sympy.sympify(values["kappa_g"]) if "kappa_g" in values else kappa_g_estimate(values)
    found = T1C.find_choices(values, parameters=PN, forms=(Pi, Pi_t), kt=kg)
    return {**found, "kappa_g": str(kg)} if found else {}


HYPOTHESES = [
    Hypothesis("mu > 1", mu - 1, reference="(Theorem 1)"),
    Hypothesis("2*sigma > mu + 1", 2 * sigma - mu - 1, reference="(6)"),
    Homogeneity("Pi, Pi~ homogeneous of order mu+1", {"Π": Pi, "Π̃": Pi_t}, mu + 1, reference="(3)"),
    FormHypothesis("Pi + tau*Pi~ positive definite", Pi + tau * Pi_t, reference="(Theorem 1)"),
    SkewBound("||P(q)|| <= p0 ||q||^(sigma-1)", S3.phi, p0, sigma, reference="(4)"),
]

theorem1_nonradial = Theorem(
    "theorem1_nonradial",
    title="Theorem 1 of paper 002 on a non-radial Π̃ (n = 2, μ = 3, Π̃ a general quartic form): the chain of "
          "theorem1 with ‖∂Π̃/∂q‖ ≤ κ_g‖q‖^μ certified",
    system=system_nonradial,
    functional=functional,
    hypotheses=HYPOTHESES,
    claims=[derivation],
    printed=[printed],
    steps=steps,
    decay=T1C.CONCLUSION,
    choices=find_choices,
    paper=PAPER,
)
