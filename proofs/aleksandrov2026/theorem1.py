"""Theorem 1 of paper 000: for every τ > 0 the equilibrium (3) ω = 0, sᵢ = rᵢ of (2), (7) is
asymptotically stable.

Functional (9) (printed with the label (1)):

    V = f + (γ/2)ωᵀΘω + LᵀD⁻¹Θω + ∫_{t−τ}^t (λ(ξ+τ−t)+μ) W(ξ) dξ − LᵀD⁻¹ ∫_{t−τ}^t f^ν(ξ)L(ξ) dξ,
    W = ‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}.

The paper then prints V̇ along (2),(7).  That print is entered below exactly as printed,
term by term; the one liberty is its ``ω^⊤(t) L^⊤(t−τ)``, a row times a row, read as the
scalar product ωᵀL(t−τ).  Whatever the comparison with the derivation finds is the result.
"""

from lkverify import DerivativeClaim, Hypothesis, Term, Theorem, cross, dot, quad, t, window_integral, xi
from lkverify.declare.rigidbody import restoring_torque_rate

from .equations import (PAPER, D, D_inv, L, Theta, W, alpha1, alpha2, f, gamma, lam, mu, nu, omega, r1, r2, s1, s2, system,
                        tau)
from .functional9 import functional, int_fL
from .theorem1_bound import derivation  # V̇ in the structured form, exact
from .theorem1_chain import CONCLUSION, optimal_choices, steps

__all__ = ["functional", "printed_Vdot", "printed_claim", "theorem1", "int_fL"]

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (alpha1, alpha2))  # α1(ω×s1)×r1 + α2(ω×s2)×r2 = −L̇ by (2)

# V̇ as printed after (9), line by line.
printed_Vdot = [
    Term(-gamma * quad(omega(t), D), text="−γωᵀDω", latex=r"-\gamma\omega^\top D\omega"),
    Term(-f(t) ** nu * quad(L(t), D_inv), text="−f^ν LᵀD⁻¹L", latex=r"-f^\nu L^\top D^{-1}L"),
    Term(-quad(L(t), D_inv, cross(omega(t), Theta * omega(t))), text="−LᵀD⁻¹(ω×(Θω))",
         latex=r"-L^\top D^{-1}(\omega\times(\Theta\omega))"),
    Term(gamma * f(t - tau) ** nu * dot(omega(t), L(t - tau)), text="+γf^ν(t−τ)ωᵀL(t−τ)",
         latex=r"+\gamma f^\nu(t-\tau)\omega^\top L(t-\tau)"),
    Term(quad(M, D_inv, int_fL - Theta * omega(t)), text="(α1(ω×s1)×r1+α2(ω×s2)×r2)ᵀD⁻¹(∫f^νL dξ − Θω)",
         latex=r"(\alpha_1(\omega\times s_1)\times r_1+\alpha_2(\omega\times s_2)\times r_2)^\top D^{-1}"
               r"\left(\int_{t-\tau}^t f^\nu L\,d\xi-\Theta\omega\right)"),
    Term(-lam * window_integral(W(xi), tau), text="−λ∫(‖s1−r1‖^{2ν+2}+‖s2−r2‖^{2ν+2})dξ",
         latex=r"-\lambda\int_{t-\tau}^t(\|s_1-r_1\|^{2\nu+2}+\|s_2-r_2\|^{2\nu+2})d\xi"),
    Term((lam * tau + mu) * W(t), text="(λτ+μ)(‖s1−r1‖^{2ν+2}+‖s2−r2‖^{2ν+2})",
         latex=r"(\lambda\tau+\mu)(\|s_1-r_1\|^{2\nu+2}+\|s_2-r_2\|^{2\nu+2})"),
    Term(-mu * W(t - tau), text="−μ(‖s1(t−τ)−r1‖^{2ν+2}+‖s2(t−τ)−r2‖^{2ν+2})",
         latex=r"-\mu(\|s_1(t-\tau)-r_1\|^{2\nu+2}+\|s_2(t-\tau)-r_2\|^{2\nu+2})"),
]

#: the printed V̇, compared with the derivation: a finding about the paper, not a link
_row, _col = omega(t).T.shape, L(t - tau).T.shape  # the printed ω^⊤(t)L^⊤(t−τ): a row times a row
printed_claim = DerivativeClaim(
    "Vdot_printed", functional, system, printed_Vdot,
    description=f"the printed V̇ along (2),(7), as printed (its ω^⊤(t)L^⊤(t−τ) is a {_row[0]}×{_row[1]} row times a "
                f"{_col[0]}×{_col[1]} row, undefined: a transposition typo, read as ωᵀL(t−τ))")

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: delayed nonlinear restoring torque, stable for every τ > 0 (the proof checked to the end)",
    system=system,
    functional=functional,
    hypotheses=[Hypothesis("tau > 0", tau), Hypothesis("nu > 0", nu),
                Hypothesis("alpha1 > 0", alpha1), Hypothesis("alpha2 > 0", alpha2)],
    claims=[derivation],
    printed=[printed_claim],
    steps=steps,
    decay=CONCLUSION,
    choices=optimal_choices,
    paper=PAPER,
)
