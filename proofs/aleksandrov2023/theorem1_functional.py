"""Functional (П.1) of the proof of Theorem 1 of paper 002 and its derivative along (3).

    (П.1)  V = ½λ q̇ᵀAq̇ + ½ qᵀBq + qᵀAq̇ − qᵀ∫_{t−τ}^t (ξ − t + τ) ∂Π̃/∂q(q(ξ)) dξ
               + ∫_{t−τ}^t (α + β(ξ − t + τ)) ‖q(ξ)‖^{μ+1} dξ,        λ, α, β > 0.

The paper prints V̇ along (3) as

    V̇ = −λq̇ᵀBq̇ + q̇ᵀAq̇ − λq̇ᵀ(∂Π/∂q + ∫∂Π̃/∂q(q(ξ))dξ + P(q)q) − qᵀ(∂Π/∂q + τ∂Π̃/∂q)
        − q̇ᵀ∫(ξ − t + τ)∂Π̃/∂q(q(ξ))dξ − β∫‖q(ξ)‖^{μ+1}dξ + (α + βτ)‖q‖^{μ+1} − α‖q(t − τ)‖^{μ+1}.

``derivation`` is that V̇ with the groups split into the terms the bounds with c7 … c12
bound one by one (the chain rests on it); ``printed`` is the formula as printed, grouped
as printed (a finding about the paper).  Both are checked against the library's own
derivative (chain rule, Leibniz rule for the window integrals); qᵀP(q)q = 0 (P skew) and
qᵀA q̈ cancels against d/dt of the memory term, which is why no such terms remain.
"""

from lkverify import DerivativeClaim, Functional, Term, dot, norm_power, quad, t, window_integral, xi

from .system3 import A, B, alpha, beta, grad_Pi, grad_Pi_t, lam, mu, q, skew, system3, tau, v

__all__ = ["functional", "derivation", "printed", "K_int", "J_int", "structured_Vdot", "printed_Vdot", "instance"]


def instance(grad_tilde, system, *, suffix=""):
    """(functional, structured V̇, printed V̇, derivation, printed claim, K, J) of (П.1) for ∂Π̃/∂q = ``grad_tilde``.

    ``grad_tilde(time)`` is ∂Π̃/∂q(q(time)); ``system`` is (3) with that Π̃.  The functional and
    both V̇ are the same formulas for every Π̃ (the radial instance of :mod:`.system3` and the
    non-radial one of :mod:`.theorem1_nonradial`); ``suffix`` is appended to the claims' names.
    """
    K = window_integral(grad_tilde(xi), tau, weight=xi - t + tau)  # ∫(ξ − t + τ) ∂Π̃/∂q(q(ξ)) dξ
    J = window_integral(grad_tilde(xi), tau)  # ∫ ∂Π̃/∂q(q(ξ)) dξ
    mem = window_integral(norm_power(q(xi), mu + 1), tau)  # ∫‖q(ξ)‖^{μ+1} dξ
    # (П.1)
    V = Functional([
        Term(lam / 2 * quad(v(t), A), text="½λq̇ᵀAq̇", latex=r"\tfrac12\lambda\dot q^\top A\dot q"),
        Term(quad(q(t), B) / 2, text="½qᵀBq", latex=r"\tfrac12 q^\top Bq"),
        Term(quad(q(t), A, v(t)), text="qᵀAq̇", latex=r"q^\top A\dot q"),
        Term(-dot(q(t), K), text="−qᵀ∫(ξ−t+τ)∂Π̃/∂q dξ",
             latex=r"-q^\top\int_{t-\tau}^t(\xi-t+\tau)\frac{\partial\tilde\Pi}{\partial q}d\xi"),
        Term(window_integral(norm_power(q(xi), mu + 1), tau, weight=alpha + beta * (xi - t + tau)),
             text="∫(α+β(ξ−t+τ))‖q(ξ)‖^{μ+1}dξ",
             latex=r"\int_{t-\tau}^t(\alpha+\beta(\xi-t+\tau))\|q(\xi)\|^{\mu+1}d\xi"),
    ], name="(П.1)")
    tail = [
        Term(-dot(v(t), K), text="−q̇ᵀ∫(ξ−t+τ)∂Π̃/∂q dξ",
             latex=r"-\dot q^\top\int_{t-\tau}^t(\xi-t+\tau)\frac{\partial\tilde\Pi}{\partial q}d\xi"),
        Term(-beta * mem, text="−β∫‖q(ξ)‖^{μ+1}dξ", latex=r"-\beta\int_{t-\tau}^t\|q(\xi)\|^{\mu+1}d\xi"),
        Term((alpha + beta * tau) * norm_power(q(t), mu + 1), text="(α+βτ)‖q‖^{μ+1}",
             latex=r"(\alpha+\beta\tau)\|q\|^{\mu+1}"),
        Term(-alpha * norm_power(q(t - tau), mu + 1), text="−α‖q(t−τ)‖^{μ+1}", latex=r"-\alpha\|q(t-\tau)\|^{\mu+1}"),
    ]
    # V̇ split into the terms the bounds with c7 … c12 bound one by one
    structured = [
        Term(-lam * quad(v(t), B), text="−λq̇ᵀBq̇", latex=r"-\lambda\dot q^\top B\dot q"),
        Term(quad(v(t), A), text="q̇ᵀAq̇", latex=r"\dot q^\top A\dot q"),
        Term(-lam * dot(v(t), grad_Pi(t)), text="−λq̇ᵀ∂Π/∂q", latex=r"-\lambda\dot q^\top\partial\Pi/\partial q"),
        Term(-lam * dot(v(t), J), text="−λq̇ᵀ∫∂Π̃/∂q dξ",
             latex=r"-\lambda\dot q^\top\int_{t-\tau}^t\frac{\partial\tilde\Pi}{\partial q}d\xi"),
        Term(-lam * quad(v(t), skew(t), q(t)), text="−λq̇ᵀP(q)q", latex=r"-\lambda\dot q^\top P(q)q"),
        Term(-dot(q(t), grad_Pi(t) + tau * grad_tilde(t)), text="−qᵀ(∂Π/∂q+τ∂Π̃/∂q)",
             latex=r"-q^\top(\partial\Pi/\partial q+\tau\partial\tilde\Pi/\partial q)"),
        *tail,
    ]
    # V̇ as the appendix prints it (groups as printed)
    printed_terms = [
        Term(-lam * quad(v(t), B), text="−λq̇ᵀBq̇", latex=r"-\lambda\dot q^\top B\dot q"),
        Term(quad(v(t), A), text="q̇ᵀAq̇", latex=r"\dot q^\top A\dot q"),
        Term(-lam * dot(v(t), grad_Pi(t) + J + skew(t) * q(t)), text="−λq̇ᵀ(∂Π/∂q+∫∂Π̃/∂q dξ+P(q)q)",
             latex=r"-\lambda\dot q^\top\left(\frac{\partial\Pi}{\partial q}+\int_{t-\tau}^t\frac{\partial\tilde\Pi}"
                   r"{\partial q}d\xi+P(q)q\right)"),
        Term(-dot(q(t), grad_Pi(t) + tau * grad_tilde(t)), text="−qᵀ(∂Π/∂q+τ∂Π̃/∂q)",
             latex=r"-q^\top(\partial\Pi/\partial q+\tau\partial\tilde\Pi/\partial q)"),
        *tail,
    ]
    derived = DerivativeClaim(f"Vdot_structured{suffix}", V, system, structured,
                              description="V̇ of (П.1) along (3), the groups of the printed V̇ split term by term")
    as_printed = DerivativeClaim(f"Vdot_printed{suffix}", V, system, printed_terms,
                                 description="the appendix's printed V̇ of (П.1) along (3)")
    return V, structured, printed_terms, derived, as_printed, K, J


#: the radial instance of :mod:`.system3`: (П.1), V̇ split into the terms the bounds with c7 … c12 bound one by one
#: (exact; the terms the bound steps bound), the appendix's printed V̇ (a finding about the paper, not a link)
functional, structured_Vdot, printed_Vdot, derivation, printed, K_int, J_int = instance(grad_Pi_t, system3)
