"""The functional of the proof of Theorem 3 of paper 002, V̇ in its structured form, and the bound steps.

Declared here, below :mod:`.theorem3` (the theorem) and :mod:`.theorem3_constants` (its
constants job), which both use them.
"""

from lkverify import DerivativeClaim, Functional, Term, cross, dot, norm_power, norm_squared, quad, t, window_integral, xi

from .equations import F, F_inv, J, K, Theta, a, alpha, b, beta, lam, mu, n, omega, r, s, system, tau
from .theorem3_chain import chain_steps

__all__ = ["derivation", "functional", "steps", "structured_Vdot"]

# The functional of the proof of Theorem 3
functional = Functional([
    Term(lam / 2 * quad(omega(t), Theta), text="½λωᵀΘω", latex=r"\tfrac12\lambda\omega^\top\Theta\omega"),
    Term(norm_squared(s(t) - r) / 2, text="½‖s−r‖²", latex=r"\tfrac12\|s-r\|^2"),
    Term(quad(cross(s(t), r), F_inv * Theta, omega(t)), text="(s×r)ᵀF⁻¹Θω", latex=r"(s\times r)^\top F^{-1}\Theta\omega"),
    Term(b * quad(cross(s(t), r), F_inv, K), text="b(s×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"b(s\times r)^\top F^{-1}\int_{t-\tau}^t(\xi+\tau-t)\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term(window_integral(norm_power(s(xi) - r, mu + 1), tau, weight=alpha + beta * (xi + tau - t)),
         text="∫(α+β(ξ+τ−t))‖s(ξ)−r‖^{μ+1}dξ",
         latex=r"\int_{t-\tau}^t(\alpha+\beta(\xi+\tau-t))\|s(\xi)-r\|^{\mu+1}d\xi"),
], name="V of the proof of Theorem 3")

s_x_r = cross(s(t), r)
omega_x_s_x_r = cross(cross(omega(t), s(t)), r)  # (ω×s)×r = −ṡ×r by (10)

# V̇ in the structured form on which the bounds with c5…c9 rest.
structured_Vdot = [
    Term(-lam * quad(omega(t), F), text="−λωᵀFω", latex=r"-\lambda\omega^\top F\omega"),
    Term(-lam * a * n(t) * dot(omega(t), s_x_r), text="−λa‖s−r‖^{μ−1}ωᵀ(s×r)",
         latex=r"-\lambda a\|s-r\|^{\mu-1}\omega^\top(s\times r)"),
    Term(lam * b * dot(omega(t), J), text="λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"\lambda b\,\omega^\top\int_{t-\tau}^t\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term(-quad(omega_x_s_x_r, F_inv * Theta, omega(t)), text="−((ω×s)×r)ᵀF⁻¹Θω",
         latex=r"-((\omega\times s)\times r)^\top F^{-1}\Theta\omega"),
    Term(-quad(s_x_r, F_inv, cross(omega(t), Theta * omega(t))), text="−(s×r)ᵀF⁻¹(ω×Θω)",
         latex=r"-(s\times r)^\top F^{-1}(\omega\times\Theta\omega)"),
    Term(-(a - tau * b) * n(t) * quad(s_x_r, F_inv), text="−(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)",
         latex=r"-(a-\tau b)\|s-r\|^{\mu-1}(s\times r)^\top F^{-1}(s\times r)"),
    Term(-b * quad(omega_x_s_x_r, F_inv, K), text="−b((ω×s)×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"-b((\omega\times s)\times r)^\top F^{-1}\int_{t-\tau}^t(\xi+\tau-t)\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term((alpha + beta * tau) * norm_power(s(t) - r, mu + 1), text="(α+βτ)‖s−r‖^{μ+1}",
         latex=r"(\alpha+\beta\tau)\|s-r\|^{\mu+1}"),
    Term(-alpha * norm_power(s(t - tau) - r, mu + 1), text="−α‖s(t−τ)−r‖^{μ+1}", latex=r"-\alpha\|s(t-\tau)-r\|^{\mu+1}"),
    Term(-beta * window_integral(norm_power(s(xi) - r, mu + 1), tau), text="−β∫‖s(ξ)−r‖^{μ+1}dξ",
         latex=r"-\beta\int_{t-\tau}^t\|s(\xi)-r\|^{\mu+1}d\xi"),
]

#: V̇ along (10), (12) in the structured form (exact; the terms the bound steps bound)
derivation = DerivativeClaim("Vdot_structured", functional, system, structured_Vdot,
                             description="V̇ along (10),(12) equals the structured form with "
                                         "−(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)")

#: the proof's estimates V ≥ L, V ≤ U, V̇ ≤ W, term by term (:mod:`.theorem3_chain`)
steps = chain_steps(functional, derivation)
