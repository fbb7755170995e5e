"""Functional (14) of paper 000 (Theorem 2) and its derivative along (2), (13), for a general kernel.

With G(ζ) = g(ζ)I (so ‖G‖ = |g|) and the tails K(u) = ∫_u^∞ g(ζ)dζ, K₊(u) = ∫_u^∞ |g(ζ)|dζ:

    (14)  V = f + (γ/2)ωᵀΘω + LᵀD⁻¹Θω + μ∫_0^t K₊(t−ξ)(‖s1(ξ)−r1‖^{2ν+2} + ‖s2(ξ)−r2‖^{2ν+2})dξ
              − LᵀD⁻¹∫_0^t K(t−ξ) f^ν(ξ)L(ξ)dξ,            γ, μ > 0.

The proof prints only bounds on V̇.  The derivation along (2), (13) gives, with
J = ∫_0^t f^ν(ξ)g(t−ξ)L(ξ)dξ (the integral torque), M = α1(ω×s1)×r1 + α2(ω×s2)×r2 = −L̇ and
Ξ = (β + ∫_0^∞ g)I,

    V̇ = −γωᵀDω − γβf^ν ωᵀL − γωᵀJ − f^ν LᵀD⁻¹ΞL − LᵀD⁻¹(ω×Θω) − MᵀD⁻¹Θω
        + MᵀD⁻¹∫_0^t K(t−ξ)f^ν(ξ)L(ξ)dξ + μ∫_0^∞|g| W(t) − μ∫_0^t |g(t−ξ)| W(ξ)dξ,

W = ‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}: the integral torque in d/dt LᵀD⁻¹Θω cancels the
lower-limit term of the last integral of (14), and its upper limit joins βf^νL into
f^ν LᵀD⁻¹ΞL — the term where Assumption 2 enters.  This structured form is the claim
``Vdot_structured``, proved for every g (the kernel stays a symbol), the form on which the
printed bounds with c5 … c10 rest (each of its terms appears there).
"""

import sympy

from lkverify import DerivativeClaim, Functional, Term, cross, dot, memory_integral, norm_power, quad, t, \
    tail_integral, xi, zeta
from lkverify.declare.rigidbody import restoring_torque_rate

from .equations import (D, D_inv, L, Theta, alpha1, alpha2, beta, f, g, gamma, mu, nu, omega, r1, r2, s1, s2,
                        system_pid)

__all__ = ["J", "derivation", "functional", "structured_Vdot"]

K = tail_integral(g(zeta), t - xi)  # ∫_{t−ξ}^∞ g(ζ)dζ
K_abs = tail_integral(sympy.Abs(g(zeta)), t - xi)  # ∫_{t−ξ}^∞ ‖G(ζ)‖dζ
W_at = [norm_power(s(xi) - r, 2 * nu + 2) for s, r in ((s1, r1), (s2, r2))]
int_KfL = memory_integral(K * f(xi) ** nu * L(xi))  # ∫_0^t ∫_{t−ξ}^∞ G(ζ)dζ f^ν(ξ)L(ξ)dξ
J = memory_integral(f(xi) ** nu * g(t - xi) * L(xi))  # ∫_0^t f^ν(ξ)G(t−ξ)L(ξ)dξ
int_g = sympy.Integral(g(zeta), (zeta, 0, sympy.oo))
int_abs_g = sympy.Integral(sympy.Abs(g(zeta)), (zeta, 0, sympy.oo))

# (14)
functional = Functional([
    Term(f(t), text="f", latex="f"),
    Term(gamma / 2 * quad(omega(t), Theta), text="(γ/2)ωᵀΘω", latex=r"\frac{\gamma}{2}\omega^\top\Theta\omega"),
    Term(quad(L(t), D_inv * Theta, omega(t)), text="LᵀD⁻¹Θω", latex=r"L^\top D^{-1}\Theta\omega"),
    Term(mu * memory_integral(K_abs * sum(W_at, sympy.S.Zero)), text="μ∫∫_{t−ξ}^∞‖G‖dζ W(ξ)dξ",
         latex=r"\mu\int_0^t\int_{t-\xi}^{\infty}\|G(\zeta)\|d\zeta\,W(\xi)\,d\xi"),
    Term(-quad(L(t), D_inv, int_KfL), text="−LᵀD⁻¹∫∫_{t−ξ}^∞G dζ f^ν(ξ)L(ξ)dξ",
         latex=r"-L^\top D^{-1}\int_0^t\int_{t-\xi}^{\infty}G(\zeta)d\zeta f^\nu(\xi)L(\xi)d\xi"),
], name="(14)")

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (alpha1, alpha2))  # −L̇ by (2)
W_t = sum((norm_power(s(t) - r, 2 * nu + 2) for s, r in ((s1, r1), (s2, r2))), sympy.S.Zero)

structured_Vdot = [
    Term(-gamma * quad(omega(t), D), text="−γωᵀDω"),
    Term(-gamma * beta * f(t) ** nu * dot(omega(t), L(t)), text="−γβf^ν ωᵀL"),
    Term(-gamma * dot(omega(t), J), text="−γωᵀ∫f^ν(ξ)G(t−ξ)L(ξ)dξ"),
    Term(-(beta + int_g) * f(t) ** nu * quad(L(t), D_inv), text="−f^ν LᵀD⁻¹ΞL"),
    Term(-quad(L(t), D_inv, cross(omega(t), Theta * omega(t))), text="−LᵀD⁻¹(ω×(Θω))"),
    Term(-quad(M, D_inv * Theta, omega(t)), text="−MᵀD⁻¹Θω"),
    Term(quad(M, D_inv, int_KfL), text="MᵀD⁻¹∫∫G dζ f^νL dξ"),
    Term(mu * int_abs_g * W_t, text="μ∫_0^∞‖G‖dζ W(t)"),
    Term(-mu * memory_integral(sympy.Abs(g(t - xi)) * sum(W_at, sympy.S.Zero)), text="−μ∫‖G(t−ξ)‖W(ξ)dξ"),
]

derivation = DerivativeClaim("Vdot_structured", functional, system_pid, structured_Vdot,
                             description="V̇ of (14) along (2),(13) for every kernel g: the integral torque cancels, "
                                         "βf^νL and ∫G join into f^ν LᵀD⁻¹ΞL")
