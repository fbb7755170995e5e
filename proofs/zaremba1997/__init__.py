"""Zaremba (1997), Izv. RAN MTT — paper 004.

"Stabilisation of programmed motions of a rigid body under uncertain parameters of the
equations of dynamics".  Euler (1.3) Mω̇ + ω × N(ω, L0) = u with unknown inertia (principal
axes: N = Mω, θ = (A, B, C)), Poisson (1.4) ṡᵢ = −(ω − ω_d) × sᵢ, target sᵢ = cᵢ, ω = ω_d(t).

* Theorem 1 (adaptive): V (2.6) = ½(vᵀMv + θ_eᵀΓ⁻¹θ_e), control (2.7), adaptation (2.8),
  V̇ = −vᵀK_dv (2.9); the regulation example (2.10).
* Theorem 2 (composite): V (3.1), laws (3.2)–(3.4), V̇ ≤ (3.10), V̇ + γV ≤ 0 on D (3.6), (3.12);
  the pointing example (3.13), (3.14).

The paper prints no numerical example: the catalogued instance is documented in
:mod:`.equations` (M = diag(3, 4, 5), kᵢ = 1, 2, 3, Λ = 2, …, ω_d(t) = (½ sin t, ½ cos(3t/4),
⅓ sin(t/3))).

Modules: :mod:`.equations` (parameters, states, Y, the errors (2.1), the closed loops),
:mod:`.parametrisation` ((1.5), (1.6), (2.1), Lemmas 2, 3), :mod:`.theorem1`, :mod:`.example210`,
:mod:`.theorem2`, :mod:`.example313`, :mod:`.excitation` ((3.5) β1, β2), :mod:`.example` (the
simulations); the exact V̇ and the term-by-term comparisons come from :mod:`lkverify.symbolic.polynomial`.
"""

from .equations import PAPER, P, system1, system2, closed_loop2, Y
from .parametrisation import parametrisation
from .theorem1 import theorem1
from .example210 import example210
from .theorem2 import theorem2
from .example313 import example313
from .excitation import excitation
from .example import example

__all__ = [
    "PAPER", "P", "system1", "system2", "closed_loop2", "Y",
    # section 1–2: (1.5), (1.6), (2.1), Lemmas 2, 3
    "parametrisation",
    # Theorem 1 and the regulation example (2.10)
    "theorem1", "example210",
    # Theorem 2 and the pointing example (3.13), (3.14)
    "theorem2", "example313",
    # persistent excitation (3.5) and the simulations
    "excitation", "example",
]
