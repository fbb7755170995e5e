"""The proof of Theorem 1 of paper 002 from (П.1) to its conclusion, as checked bound steps.

"Using Young's inequality, λ, α, β, δ can be chosen so that for ‖q_t‖_τ < δ"

    (П.2)  ½(λc1‖q̇‖² + c2‖q‖² + α∫‖q‖^{μ+1}) ≤ V ≤ 2(λc5‖q̇‖² + c6‖q‖² + (α + βτ)∫‖q‖^{μ+1}),
    (П.3)  V̇ ≤ −½(λc7‖q̇‖² + c11‖q‖^{μ+1} + β∫‖q‖^{μ+1}).

Here each printed estimate of :mod:`.theorem1_bound` is followed by the rewrites that turn
it into (П.2), (П.3), on the region

    max_{[t−τ, t]} ‖q(ξ)‖ ≤ δ_q,   ‖q̇(t)‖ ≤ δ_v,

in the measures w = ‖q̇(t)‖, e = ‖q(t)‖, j = (∫‖q(ξ)‖^{μ+1}dξ)^{1/(μ+1)} (so ∫‖q‖^{μ+1} = j^{μ+1};
∫‖q‖^μ ≤ τ^{1/(μ+1)} j^μ and ∫(ξ−t+τ)‖q‖^μ ≤ k_τ j^μ by Hölder, k_τ = (τ^{μ+2}/(μ+2))^{1/(μ+1)}):

* V ≥ L: −c3‖q‖‖q̇‖ by Young (η_w); −c4 k_τ‖q‖j^μ by Young with exponents μ+1, (μ+1)/μ (η_K)
  and ‖q‖^{μ+1} ≤ δ_q^{μ−1}‖q‖² on the region; its j^{μ+1} part is absorbed by αj^{μ+1}
  (so L is a quadratic form in ‖q̇‖, ‖q‖, as (П.2) without its integral term);
* V ≤ U: the printed upper bound (with ‖q‖‖q̇‖, :mod:`.theorem1_bound`), Hölder on the window;
* V̇ ≤ W: λc9‖q̇‖‖q‖^μ and λp0‖q̇‖‖q‖^σ by Young (η) and ‖q‖^{2μ} ≤ δ_q^{μ−1}‖q‖^{μ+1},
  ‖q‖^{2σ} ≤ δ_q^{2σ−μ−1}‖q‖^{μ+1} — the place where (6) 2σ > μ + 1 enters; the memory terms
  by Hölder, Young (η_j) and j^{2μ} ≤ (τ^{1/(μ+1)}δ_q)^{μ−1} j^{μ+1}; −α‖q(t−τ)‖^{μ+1} ≤ 0 dropped.

The conclusion (Krasovskii's theorem) is the sign test of
:class:`~lkverify.certify.steps.chain.Krasovskii` on the coefficients of L, U, W; the choices
λ, α, β, δ_q, δ_v and Young's η's are found at the run's gains by :func:`find_choices`
(floating point only picks them; every step is proved at those exact values).
"""

from __future__ import annotations

import numpy as np
import sympy

from lkverify import t, xi
from lkverify.certify.steps.chain import Krasovskii, TermBound, lyapunov_steps
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_norm
from lkverify.certify.steps.rewrites import OnRegion, YoungEach
from lkverify.certify.steps.rules import (CauchySchwarz, Equal, Nonpositive, Rayleigh, Template, WindowWeight,
                                          measured)

from .system3 import (A, B, X, Pi, Pi_t, alpha, beta, delta_q, delta_v, eta, eta_K, eta_j, eta_w, grad, lam, mu, p0, q,
                      sigma, system3, tau, v)
from .theorem1_bound import DEFINITIONS, _ctx_eig, c1, c2, c3, c4, c5, c6, c7, c8, c10, c12, extreme_eigenvalue, \
    gradient_tree
from .theorem1_functional import J_int, K_int, derivation, functional

__all__ = ["CONCLUSION", "MEASURES", "REGION", "chain_steps", "find_choices", "printed_p3", "steps", "k_tau", "tau_j"]

W_ = norm_measure("w", v(t), text="‖q̇(t)‖")
E_ = norm_measure("e", q(t), text="‖q(t)‖")
D_ = norm_measure("d", q(t - tau), text="‖q(t−τ)‖")
J_ = window_norm("j", q(xi), p=mu + 1, window=tau, text="(∫‖q(ξ)‖^{μ+1}dξ)^{1/(μ+1)}")
SUP_ = sup_norm("m", q(xi), window=tau, text="max_{[t−τ,t]} ‖q(ξ)‖")
MEASURES = (W_, E_, D_, J_)
w, e, d, j = (m.symbol for m in MEASURES)
REGION = Region({SUP_: delta_q, W_: delta_v})

k_tau = (tau ** (mu + 2) / (mu + 2)) ** (1 / (mu + 1))  # (∫(ξ−t+τ)^{μ+1}dξ)^{1/(μ+1)}
tau_j = tau ** (1 / (mu + 1))  # (∫1 dξ)^{1/(μ+1)}
_holder = ((mu + 1) / mu, mu + 1)
lam_c9, k11, lam_skew = sympy.symbols("lam_c9 k11 lam_skew", real=True)


def _lower(K=K_int, tree=gradient_tree):
    q_ = mu + 1
    return [
        TermBound("½λq̇ᵀAq̇", lam * c1 * w**2,
                  Rayleigh(v(t), A, factor=lam / 2, eigenvalue=_ctx_eig("min", A), norm_squared=w**2)),
        TermBound("½qᵀBq", c2 * e**2,
                  Rayleigh(q(t), B, factor=sympy.Rational(1, 2), eigenvalue=_ctx_eig("min", B), norm_squared=e**2)),
        TermBound("qᵀAq̇", -c3 * (eta_w * e**2 / 2 + w**2 / (2 * eta_w)),
                  CauchySchwarz(q(t), v(t), (measured(E_), measured(W_)), matrix=A, operator_norm=_ctx_eig("max", A)),
                  then=(YoungEach(((e, w, 2, 2, eta_w),)),)),
        TermBound("−qᵀ∫(ξ−t+τ)∂Π̃/∂q dξ",
                  -c4 * k_tau * (eta_K * delta_q ** (mu - 1) * e**2 / q_ + eta_K ** (-1 / mu) * mu * j**q_ / q_),
                  CauchySchwarz(q(t), K, (measured(E_), tree(J_, weight=xi - t + tau, holder=_holder)),
                                factor=-1),
                  then=(YoungEach(((e, j**mu, q_, q_ / mu, eta_K),)), OnRegion("e", 2))),
        # ≥ αj^{μ+1}, stated as the part the Young remainder above needs (α ≥ it: checked), so that L is
        # quadratic in (w, e): V ≥ L then gives ‖q‖², ‖q̇‖² ≤ V/l for the decay of Corollary 1
        TermBound("∫(α+β(ξ−t+τ))‖q(ξ)‖^{μ+1}dξ", c4 * k_tau * eta_K ** (-1 / mu) * mu * j**q_ / q_,
                  WindowWeight("j", mu + 1, weight=alpha + beta * (xi - t + tau))),
    ]


def _upper(K=K_int, tree=gradient_tree):
    return [
        TermBound("½λq̇ᵀAq̇", lam * c5 * w**2,
                  Rayleigh(v(t), A, factor=lam / 2, eigenvalue=_ctx_eig("max", A), norm_squared=w**2)),
        TermBound("½qᵀBq", c6 * e**2,
                  Rayleigh(q(t), B, factor=sympy.Rational(1, 2), eigenvalue=_ctx_eig("max", B), norm_squared=e**2)),
        TermBound("qᵀAq̇", c3 * e * w,
                  CauchySchwarz(q(t), v(t), (measured(E_), measured(W_)), matrix=A, operator_norm=_ctx_eig("max", A))),
        TermBound("−qᵀ∫(ξ−t+τ)∂Π̃/∂q dξ", c4 * k_tau * e * j**mu,
                  CauchySchwarz(q(t), K, (measured(E_), tree(J_, weight=xi - t + tau, holder=_holder)),
                                factor=-1)),
        TermBound("∫(α+β(ξ−t+τ))‖q(ξ)‖^{μ+1}dξ", (alpha + beta * tau) * j ** (mu + 1),
                  WindowWeight("j", mu + 1, weight=alpha + beta * (xi - t + tau))),
    ]


def _young_e(c, power):
    """c·w·e^power ≤ c(ηw²/2 + δ_q^{2·power−μ−1}e^{μ+1}/(2η)) (Young, then the region)."""
    return c * (eta * w**2 / 2 + delta_q ** (2 * power - mu - 1) * e ** (mu + 1) / (2 * eta))


def _young_j(c):
    """c·w·j^μ ≤ c(η_j w²/2 + (τ^{1/(μ+1)}δ_q)^{μ−1} j^{μ+1}/(2η_j)) (Young, then the region)."""
    return c * (eta_j * w**2 / 2 + (tau_j * delta_q) ** (mu - 1) * j ** (mu + 1) / (2 * eta_j))


def _vdot(K=K_int, J=J_int, tree=gradient_tree):
    young_e = (YoungEach(((w, e**mu, 2, 2, eta),)), OnRegion("e", mu + 1))
    young_j = (YoungEach(((w, j**mu, 2, 2, eta_j),)), OnRegion("j", mu + 1))
    return [
        TermBound("−λq̇ᵀBq̇", -lam * c7 * w**2,
                  Rayleigh(v(t), B, factor=-lam, eigenvalue=_ctx_eig("min", B), norm_squared=w**2)),
        TermBound("q̇ᵀAq̇", c8 * w**2, Rayleigh(v(t), A, eigenvalue=_ctx_eig("max", A), norm_squared=w**2)),
        TermBound("−λq̇ᵀ∂Π/∂q", _young_e(lam_c9, mu), Template("lam_c9", {"w": 1, "e": 3}), then=young_e),
        TermBound("−λq̇ᵀ∫∂Π̃/∂q dξ", _young_j(lam * c10 * tau_j),
                  CauchySchwarz(v(t), J, (measured(W_), tree(J_, holder=_holder)), factor=-lam),
                  then=young_j),
        TermBound("−λq̇ᵀP(q)q", _young_e(lam * p0, sigma), Template("lam_skew", {"w": 1, "e": 3}),
                  then=(YoungEach(((w, e**sigma, 2, 2, eta),)), OnRegion("e", mu + 1))),
        TermBound("−qᵀ(∂Π/∂q+τ∂Π̃/∂q)", k11 * e ** (mu + 1), Template("k11", {"e": 4})),
        TermBound("−q̇ᵀ∫(ξ−t+τ)∂Π̃/∂q dξ", _young_j(c12 * k_tau),
                  CauchySchwarz(v(t), K, (measured(W_), tree(J_, weight=xi - t + tau, holder=_holder)),
                                factor=-1),
                  then=young_j),
        TermBound("−β∫‖q(ξ)‖^{μ+1}dξ", -beta * j ** (mu + 1), Equal(-beta * j ** (mu + 1))),
        TermBound("(α+βτ)‖q‖^{μ+1}", (alpha + beta * tau) * e ** (mu + 1), Equal((alpha + beta * tau) * e ** (mu + 1))),
        TermBound("−α‖q(t−τ)‖^{μ+1}", 0, Nonpositive()),
    ]


def chain_steps(*, functional=functional, system=system3, derivation=derivation, K=K_int, J=J_int,
                tree=gradient_tree, definitions=DEFINITIONS):
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 1 on :data:`REGION`.

    By default for the instance of :mod:`.system3`; another instance of (3) in the same symbols
    passes its functional, system, derivation, the window integrals K = ∫(ξ−t+τ)∂Π̃/∂q and
    J = ∫∂Π̃/∂q, the norm tree ``tree(measure, *, holder, weight)`` of ‖∫ g ∂Π̃/∂q‖ and the
    definitions of c1 … c12 (:mod:`.theorem1_nonradial`).  The term bounds are the same.
    """
    lower, upper, vdot = _lower(K, tree), _upper(K, tree), _vdot(K, J, tree)
    return lyapunov_steps(functional, system, lower, upper, vdot, MEASURES,
                          region=REGION, definitions=definitions, derivation=derivation)


steps = chain_steps()

# ---- the printed (П.3) against the checked W ---------------------------------------------------------
def printed_p3(k11_value):
    """(П.3): −½(λc7‖q̇‖² + c11‖q‖^{μ+1} + β∫‖q‖^{μ+1}) with c11 = −k11 (the certified constant of the steps)."""
    return -(lam * c7 * w**2 - k11_value * e ** (mu + 1) + beta * j ** (mu + 1)) / 2


class _Conclusion(Krasovskii):
    """Krasovskii's sign test, and the printed (П.3) compared with the checked W coefficient by coefficient."""

    def certify(self, steps, values, **kw):
        from lkverify import Result, Status
        from lkverify.certify.steps.chain import coefficient_sign, collect_monomials
        from lkverify.declare.parameters import apply_substitution

        rows, status, detail = super().certify(steps, values, **kw)
        if not status.is_proof:  # compared only on a region where the chain concludes
            return rows, status, detail
        step, res = steps["vdot"]
        sub = dict(step.system.parameters.substitution(values))
        sub.update(step.named_constants(values))
        gap = printed_p3(sympy.Rational(res.constants["k11"])) - res.rhs
        gap = sympy.expand(apply_substitution(sympy.sympify(gap).xreplace(sub), sub))
        worst, why = Status.EXACT, ""
        for mono, coeff in collect_monomials(gap, {m.symbol for m in MEASURES}).items():
            sign, st = coefficient_sign(coeff)
            if sign is None or sign < 0:
                worst = Status.UNDECIDED if sign is None else Status.FAILED
                why = f"the coefficient of {mono} in W exceeds the printed one by {-float(coeff):.4g}"
                break
            worst = Status.CERTIFIED if st is Status.CERTIFIED else worst
        rows.append(Result("bound", "printed (П.3) V̇ ≤ −½(λc7‖q̇‖² + c11‖q‖^{μ+1} + β∫‖q‖^{μ+1})", worst, None,
                           why or f"follows from the checked W, coefficient by coefficient ({worst})"))
        return rows, status, detail


#: the conclusion: V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖), V̇ ≤ −ψ(‖x(t)‖) with x(t) = (q̇, q); and (П.3) compared
CONCLUSION = _Conclusion(("w", "e"))


# ---- the free choices -----------------------------------------------------------------------
def _circle(f, n=4001):
    th = np.linspace(0.0, 2 * np.pi, n)
    fn = sympy.lambdify(X, f, "numpy")
    return np.broadcast_to(fn(np.cos(th), np.sin(th)), th.shape)


def _below(x, digits=3):
    x = float(x)
    k = int(np.floor(np.log10(x))) - digits + 1
    return sympy.Rational(int(np.floor(x / 10.0**k)), 1) * sympy.Rational(10) ** k


def _above(x, digits=3):
    x = float(x)
    k = int(np.floor(np.log10(x))) - digits + 1
    return sympy.Rational(int(np.ceil(x / 10.0**k)), 1) * sympy.Rational(10) ** k


def _estimates(values, parameters, forms, kt):
    """Float estimates of the constants of the steps at the run's gains (c9, c11 sampled on the circle)."""
    from lkverify.declare.parameters import apply_substitution

    Pi, Pi_t = forms
    sub = parameters.substitution(values)
    f = lambda x: float(sympy.N(x, 30))  # noqa: E731
    at = lambda ex: apply_substitution(sympy.sympify(ex), sub)  # noqa: E731
    gP = grad(at(Pi), X)
    c9 = float(np.max(np.sqrt(_circle(gP[0] ** 2 + gP[1] ** 2)))) * 1.02
    c11 = 4 * float(np.min(_circle(at(Pi + tau * Pi_t)))) * 0.98
    mu_, tau_ = f(values["mu"]), f(values["tau"])
    return {"a_min": f(extreme_eigenvalue(values["A"], "min")), "a_max": f(extreme_eigenvalue(values["A"], "max")),
            "b_min": f(extreme_eigenvalue(values["B"], "min")), "b_max": f(extreme_eigenvalue(values["B"], "max")),
            "kt": f(kt), "p0": f(values["p0"]), "mu": mu_, "sigma": f(values["sigma"]), "tau": tau_,
            "c9": c9, "c11": c11, "k_tau": (tau_ ** (mu_ + 2) / (mu_ + 2)) ** (1 / (mu_ + 1)),
            "tau_j": tau_ ** (1 / (mu_ + 1))}


def find_choices(values, *, parameters=None, forms=(Pi, Pi_t), kt=None) -> dict:
    """λ, α, β, δ_q, δ_v, η_w, η_K, η, η_j for which every coefficient of L, U, W has its sign (exact strings).

    The recipe follows the proof and aims at its (П.3): λ large (λc7/2 beats c8 and the Young
    remainders, λc1 beats c3²/c2), α = c11/8, β = c11/(8τ) (so α + βτ = c11/4), the η's split the ‖q̇‖²
    budget, then δ_q is the largest value (three digits, times 0.9) that keeps every
    δ-term below half its budget (needs μ > 1 and 2σ > μ + 1; returns {} otherwise).  When
    Π + τΠ̃ is not positive definite (c11 ≤ 0) the recipe runs with c11 = 0.01, and the chain
    fails at the sign of the ‖q‖^{μ+1} coefficient of W.

    Another instance of (3) in the same symbols passes its ``parameters``, ``forms`` = (Π, Π̃)
    and ``kt``, the exact constant of ‖∂Π̃/∂q(q)‖ ≤ kt‖q‖^μ (c4 = c10 = c12; default κ̃).

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2023.system3 import P3
    >>> ch = find_choices(P3.resolve({}, use_defaults=True))
    >>> sorted(ch)
    ['alpha', 'beta', 'delta_q', 'delta_v', 'eta', 'eta_K', 'eta_j', 'eta_w', 'lam']
    """
    parameters = system3.parameters if parameters is None else parameters
    kt_exact = sympy.sympify(values["kappa_t"] if kt is None else kt)
    c = _estimates(values, parameters, forms, kt_exact)
    if not (c["mu"] > 1 and 2 * c["sigma"] > c["mu"] + 1):
        return {}
    if c["c11"] <= 0:  # Π + τΠ̃ not positive definite: choices anyway, the chain then fails where it must
        c["c11"] = 0.01
    am, aM, bm, kt, mu_, sg, tau_ = c["a_min"], c["a_max"], c["b_min"], c["kt"], c["mu"], c["sigma"], c["tau"]
    lam_ = _above(1.2 * max(4 * aM / bm, 8 * aM**2 / (am * bm)))
    L = float(lam_)
    alpha_ = _below(c["c11"] / 8)  # α + βτ = c11/4: (П.3)'s −c11/2 leaves c11/4 for the δ-terms
    beta_ = _below(c["c11"] / (8 * tau_))
    eta_w_ = _above(2 * aM / (L * am))  # c3/(2η_w) ≤ λc1/2
    cj = L * kt * c["tau_j"] + kt * c["k_tau"]  # the coefficient of w·j^μ
    eta_ = _below(bm / (4 * (c["c9"] + c["p0"])))  # (λc9 + λp0)η/2 ≤ λc7/8
    eta_j_ = _below(L * bm / (4 * cj))  # c_j η_j/2 ≤ λc7/8
    q_ = mu_ + 1
    # η_K exact: the j^{μ+1} part of the Young remainder is exactly αj^{μ+1} (L quadratic in w, e)
    from lkverify.declare.parameters import apply_substitution

    mu_x = sympy.sympify(values["mu"])
    kt_x = apply_substitution(k_tau, parameters.substitution(values))
    eta_K_ = (kt_exact * kt_x * mu_x / ((mu_x + 1) * alpha_)) ** mu_x
    e9 = (L * (c["c9"] + c["p0"]))
    cands = [0.5,
             # e^{μ+1}: (λc9)δ^{μ−1}/(2η) + λp0 δ^{2σ−μ−1}/(2η) ≤ c11/8
             (c["c11"] * float(eta_) / (4 * e9)) ** (1 / max(min(mu_ - 1, 2 * sg - mu_ - 1), 1e-9)),
             # j^{μ+1}: c_j (τ^{1/(μ+1)}δ)^{μ−1}/(2η_j) ≤ β/2
             (float(beta_) * float(eta_j_) / cj) ** (1 / (mu_ - 1)) / c["tau_j"],
             # e² in L: c4 k_τ η_K δ^{μ−1}/(μ+1) ≤ c2/4
             (bm / 8 * q_ / (kt * c["k_tau"] * float(eta_K_))) ** (1 / (mu_ - 1))]
    delta_ = _below(0.9 * min(cands))
    return {"lam": str(lam_), "alpha": str(alpha_), "beta": str(beta_), "delta_q": str(delta_),
            "delta_v": str(delta_), "eta_w": str(eta_w_), "eta_K": str(eta_K_), "eta": str(eta_),
            "eta_j": str(eta_j_)}
