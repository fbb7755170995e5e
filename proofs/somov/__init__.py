"""Somov, Butyrin, Somov et al. — paper 003.

"Nonlinear analysis and estimates of the dynamic properties of a spacecraft attitude control
system": MRP kinematics, feedback linearisation with bounded control and a vector Lyapunov
function.  With the gyro-cluster angular momentum balanced (G ≡ 0) and u = J⁻¹M_g,

    (3)  σ̇ = ¼B(σ)ω,  ω̇ = u,    B(σ) = (1 − σ²)I + 2[σ×] + 2σσᵀ   (6), ω = D(σ)σ̇ (7),
    (8)  σ̈ = a(σ, σ̇) + ¼B(σ)u,  (10) u = 4B⁻¹(v − a),  (11) u = SC(4B⁻¹(v − a), a_m),

v = −k0σ − k1σ̇ on one spectrum for the three channels, and per channel a Vandermonde (real
Jordan) transform with Vᵢ = ‖x̃ⁱ‖.  The paper prints no numerical example: the catalogued
instance is S° = {−1/10 ± i/10}, a_m = 1/100 rad/s², J = diag(1000, 1200, 800) kg·m²
(:mod:`.equations`), the initial attitude Φ0 = 150° about (2, 2, 1)/3 (:mod:`.example`).

The extracted text lost its Greek letters and most operators; the formulas are those of
``DIGEST.md``'s reconstruction, checked here; where the extracted text reads otherwise the
module says so (findings: the factors ¼ and 4 missing from (8), (10), (11); x₂ⁱ = ωᵢ/4).

Modules: :mod:`.equations` (parameters, B, D, a, v, u, SC and the closed loop),
:mod:`.kinematics` (σ̇ = ¼Bω from the quaternion equation, (7), the short rotation),
:mod:`.linearisation` ((8)–(10): σ̈ = v exactly), :mod:`.saturation` (SC of (11): bound, direction,
inactive set), :mod:`.comparison` (the vector Lyapunov function and the comparison system),
:mod:`.norm_steps` (the comparison system's norm inequalities as steps with exact certificates),
:mod:`.region` (the certified region of attraction; against a simulated grid with ``lkverify
constants``), :mod:`.grid` (batch runs), :mod:`.example` (closed loops saturating and not).
"""

from .equations import PAPER, B, D, P, SC, a_m, alpha, beta, closed_loop, k0, k1, omega, sigma, u_linear
from .kinematics import kinematics
from .linearisation import linearisation
from .saturation import saturation
from .comparison import comparison
from .region import certified_region, region
from .example import HISTORY, HISTORY_INSIDE, example

__all__ = [
    "PAPER",
    # parameters, states, the matrices of (6), (7), the laws (10), (11) and the closed loop (3), (11)
    "P", "alpha", "beta", "a_m", "k0", "k1", "sigma", "omega", "B", "D", "SC", "u_linear", "closed_loop",
    # items
    "kinematics", "linearisation", "saturation", "comparison", "region", "certified_region",
    "HISTORY", "HISTORY_INSIDE", "example",
]
