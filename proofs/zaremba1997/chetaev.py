"""The Chetaev function (3.11) of paper 004 (instability of s = (−c1, c2, −c3), Theorem 2 (в)).

    (3.11)  V_c = [vᵀMv + θ_eᵀΓ⁻¹θ_e − k1(c1 + s1)² + k2(c2 − s2)² − k3(c3 + s3)²] + ‖Mv − ε − φᵀθ_e‖²/2,

said to have "the sign-negative derivative (3.10)", i.e. V̇_c = 2V̇ of (3.1).  On unit vectors
−(c + s)² = (c − s)² − 4, so the signed sum has the rate of V_δ (exact along (1.4)); but (3.1) weighs
V_δ by K_p and ‖η‖² by 1 (inside ½[…]), (3.11) by 1 and ½: V̇_c = 2V̇ only when K_p = 1 and the η-term
is dropped.  With K_p in front of the signed sum and ‖η‖² (no ½), V_c = 2V + const and V̇_c = 2V̇ (exact).
"""

from __future__ import annotations


from lkverify import dot, t

from lkverify.symbolic.polynomial import compare_polynomials as compare, time_derivative, plain
from .equations import c1, c2, c3, k1, k2, k3, omega_e, e, s1, s2, s3, system1

__all__ = ["chetaev_results"]


def chetaev_results(a, derived):
    """(3.11) against 2V̇ of (3.1), on the abstract loop ``a`` of :class:`~.theorem2.Abstract`."""
    signed = (-k1 * dot(c1 + s1(t), c1 + s1(t)) + k2 * dot(c2 - s2(t), c2 - s2(t))
              - k3 * dot(c3 + s3(t), c3 + s3(t)))
    out = [compare("(3.11): the signed sum has the rate of V_δ along (1.4)",
                   [("d/dt[−k1(c1+s1)² + k2(c2−s2)² − k3(c3+s3)²]", time_derivative(signed, system1, a.sub))],
                   [("2ω_eᵀe = d/dt V_δ", plain(2 * dot(omega_e, e).xreplace(a.sub)))],
                   reference="the signed sum of (3.11)")]
    twice = 2 * (derived["T1"] + derived["T23"] + derived["T4"])
    # V̇_c by linearity from the derived pieces: d/dt vᵀMv = 2T1, d/dt ‖η‖²/2 = T4 (the big ones, derived once)
    d_theta = a.derivative((a.th_e.T * a.Gm * a.th_e)[0, 0])
    d_vd = a.derivative(a.Vd)                                          # the signed sum has V_δ's rate
    printed = 2 * derived["T1"] + d_theta + d_vd + derived["T4"]       # … + ‖η‖²/2
    fixed = 2 * derived["T1"] + d_theta + a.q["Kp"] * d_vd + 2 * derived["T4"]
    out.append(compare("(3.11) as printed: V̇_c = 2V̇ (3.10)", [("V̇_c", printed)], [("2V̇", twice)],
                       reference="V̇_c of (3.11) as printed", R=a.R))
    out.append(compare("(3.11) with K_p and ‖η‖²: V̇_c = 2V̇", [("V̇_c", fixed)], [("2V̇", twice)],
                       reference="V̇_c with K_p on the signed sum and ‖η‖² without ½", R=a.R))
    return out
