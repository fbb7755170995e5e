"""Functional (9) of paper 000 (printed with the label (1)), shared by Theorem 1 and its proof's steps.

    V = f + (γ/2)ωᵀΘω + LᵀD⁻¹Θω + ∫_{t−τ}^t (λ(ξ+τ−t)+μ) W(ξ) dξ − LᵀD⁻¹ ∫_{t−τ}^t f^ν(ξ)L(ξ) dξ,
    W = ‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2},

with γ, λ, μ > 0.  The weighted integral is entered as two terms, one per axis (their sum is
the printed term), so that each can be bounded by its own window measure.
"""

from lkverify import Functional, Term, norm_power, quad, t, window_integral, xi

from .equations import D_inv, L, Theta, f, gamma, lam, mu, nu, omega, r1, r2, s1, s2, tau

__all__ = ["functional", "int_fL"]

int_fL = window_integral(f(xi) ** nu * L(xi), tau)  # ∫_{t−τ}^t f^ν(ξ)L(ξ)dξ

# (9)
functional = Functional([
    Term(f(t), text="f", latex="f"),
    Term(gamma / 2 * quad(omega(t), Theta), text="(γ/2)ωᵀΘω", latex=r"\frac{\gamma}{2}\omega^\top\Theta\omega"),
    Term(quad(L(t), D_inv * Theta, omega(t)), text="LᵀD⁻¹Θω", latex=r"L^\top D^{-1}\Theta\omega"),
    *(Term(window_integral(norm_power(s(xi) - r, 2 * nu + 2), tau, weight=lam * (xi + tau - t) + mu),
           text=f"∫(λ(ξ+τ−t)+μ)‖s{k}−r{k}‖^{{2ν+2}}dξ",
           latex=rf"\int_{{t-\tau}}^t(\lambda(\xi+\tau-t)+\mu)\|s_{k}-r_{k}\|^{{2\nu+2}}d\xi")
      for k, s, r in ((1, s1, r1), (2, s2, r2))),
    Term(-quad(L(t), D_inv, int_fL), text="−LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ", latex=r"-L^\top D^{-1}\int_{t-\tau}^t f^\nu(\xi)L(\xi)d\xi"),
], name="(9)")
