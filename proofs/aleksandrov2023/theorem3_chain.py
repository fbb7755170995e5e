"""The inequality chain of the proof of Theorem 3 of paper 002, as checked bound steps.

The paper prints (after the functional) "for this functional and its derivative along
(10), (12) the estimates … hold" with constants c1 … c9.  Here each estimate is a
:class:`~lkverify.certify.steps.TermwiseBound`: every term of V (the functional of
:mod:`.theorem3`) and every term of the structured V̇ (the claim ``Vdot_structured``,
proved equal to the exact derivative) is bounded by a named rule.  Measures:

    w = ‖ω(t)‖,   e = ‖s(t) − r‖,   j = (∫_{t−τ}^t ‖s(ξ) − r‖^{μ+1} dξ)^{1/(μ+1)},

region: max_{[t−τ, t]} ‖s(ξ) − r‖ ≤ δ_e, ‖ω(t)‖ ≤ δ_w.  The steps (for μ = 2, estimate (15)):

    V ≥ L = ½λθ_min w² + ½e² − κ1 e w − |b|‖F⁻¹‖k_τ e j² + α j³,
    V ≤ U = ½λθ_max w² + ½e² + κ1⁺ e w + |b|‖F⁻¹‖k_τ e j² + (α + βτ) j³,
    V̇ ≤ W = −λφ_min w² + c_A w² + c_B e w² + λa e² w + λ|b|τ^{1/3} w j² + |b|‖F⁻¹‖k_τ w j²
            − (a − τb)ψ_min e³(1 − e²/4) + (α + βτ) e³ − β j³,

with k_τ = (τ⁴/4)^{1/3} (Hölder with p = 3/2, q = 3 on the weight ξ + τ − t), θ and
φ, ψ the extreme eigenvalues of Θ, F, F⁻¹, and κ1, κ1⁺, c_A, c_B template constants
certified over the cap ‖s − r‖ ≤ 2 sin(1/4) (which must contain the region).
The term −α‖s(t − τ) − r‖³ ≤ 0 is dropped.

Each step holds for all λ, α, β > 0; the decay model (:mod:`.theorem3_constants`) then
chooses them.
"""

import sympy

from lkverify import t, xi
from lkverify.certify.steps.chain import Decay, TermBound, TermwiseBound
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_norm
from lkverify.certify.steps.rules import (CauchySchwarz, Equal, Nonpositive, Rayleigh, Template, WindowWeight,
                                          crossed, integral_of, measured, scaled, unit)

from .equations import F, F_inv, J, K, Theta, a, alpha, b, beta, delta_e, delta_w, lam, mu, n, omega, r, s, system, tau
from .section6 import PRINTED_15_STATED

__all__ = ["CHOICES", "DECAY", "DEFINITIONS", "MEASURES", "REGION", "RHO_CAP", "chain_steps", "e", "eigen_bounds",
           "j", "w"]

RHO_CAP = sympy.Rational(1, 2)  # the cap ‖s − r‖ ≤ 2 sin(1/4) ≈ 0.4948 of the template constants

W_ = norm_measure("w", omega(t), text="‖ω(t)‖")
E_ = norm_measure("e", s(t) - r, text="‖s(t) − r‖")
J_ = window_norm("j", s(xi) - r, p=mu + 1, window=tau, text="(∫‖s(ξ) − r‖^{μ+1}dξ)^{1/(μ+1)}")
SUP_ = sup_norm("m", s(xi) - r, window=tau, text="max_{[t−τ,t]} ‖s(ξ) − r‖")
MEASURES = (W_, E_, J_)
w, e, j = (m.symbol for m in MEASURES)

REGION = Region({SUP_: delta_e, W_: delta_w})


def _eig(which, M):
    """The extreme eigenvalue of a symmetric matrix parameter at the checked values (exact)."""
    def value(ctx):
        ev = sympy.Matrix(ctx.at(M)).eigenvals(multiple=True)
        return min(ev) if which == "min" else max(ev)
    return value


def eigen_bounds(values):
    """θ_min, θ_max, φ_min (of F), ψ_min (of F⁻¹), ‖F⁻¹‖ at resolved values (exact rationals)."""
    Th, Fv = sympy.Matrix(values["Theta"]), sympy.Matrix(values["F"])
    et, ef = Th.eigenvals(multiple=True), Fv.eigenvals(multiple=True)
    return {"theta_min": min(et), "theta_max": max(et), "phi_min": min(ef), "psi_min": 1 / max(ef),
            "Finv_norm": 1 / min(ef)}


theta_min, theta_max, phi_min, psi_min, Finv_norm = sympy.symbols(
    "theta_min theta_max phi_min psi_min Finv_norm", positive=True)
kappa1, kappa1_up, c_A, c_B = sympy.symbols("kappa1 kappa1_up c_A c_B", nonnegative=True)
k_tau = (tau ** (mu + 2) / (mu + 2)) ** (1 / (mu + 1))  # (∫_{t−τ}^t (ξ+τ−t)^{μ+1} dξ)^{1/(μ+1)}
tau_j = tau ** (1 / (mu + 1))  # (∫_{t−τ}^t 1 dξ)^{1/(μ+1)}

# norm trees reused by several steps
_sxr = crossed(measured(E_), unit(r))  # ‖s×r‖ = ‖(s − r)×r‖ ≤ e
_wxsxr = crossed(crossed(measured(W_), unit(s(t))), unit(r))  # ‖(ω×s)×r‖ ≤ w
_pointwise = scaled(n(xi), crossed(measured(J_, at=xi), unit(r)))  # ‖n(ξ) s(ξ)×r‖ ≤ ‖s(ξ) − r‖^μ
_J = integral_of(_pointwise, measure=J_, power=mu, holder=((mu + 1) / mu, mu + 1))  # ‖J‖ ≤ τ^{1/(μ+1)} j^μ
_K = integral_of(_pointwise, measure=J_, power=mu, weight=xi + tau - t,
                 holder=((mu + 1) / mu, mu + 1))  # ‖K‖ ≤ k_τ j^μ
_sxr_vec = s(t).cross(r)
_wxsxr_vec = omega(t).cross(s(t)).cross(r)


# ---- V ≥ L and V ≤ U: the terms of the functional -----------------------------------------
def _functional_bounds(direction):
    up = direction == "upper"
    return [
        TermBound("½λωᵀΘω", lam / 2 * (theta_max if up else theta_min) * w**2,
                  Rayleigh(omega(t), Theta, factor=lam / 2, eigenvalue=_eig("max" if up else "min", Theta),
                           norm_squared=w**2)),
        TermBound("½‖s−r‖²", e**2 / 2, Equal(e**2 / 2)),
        TermBound("(s×r)ᵀF⁻¹Θω", (kappa1_up if up else -kappa1) * e * w,
                  Template("kappa1_up" if up else "kappa1", {"e": 1, "w": 1}, rho_max=RHO_CAP)),
        TermBound("b(s×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
                  (1 if up else -1) * abs(b) * Finv_norm * k_tau * e * j**mu,
                  CauchySchwarz(_sxr_vec, K, (_sxr, _K), matrix=F_inv, factor=b, operator_norm=_eig_inv_norm())),
        TermBound("∫(α+β(ξ+τ−t))‖s(ξ)−r‖^{μ+1}dξ",
                  (alpha + beta * tau if up else alpha) * j ** (mu + 1),
                  WindowWeight("j", mu + 1, weight=alpha + beta * (xi + tau - t))),
    ]


def _eig_inv_norm():
    def value(ctx):
        ef = sympy.Matrix(ctx.at(F)).eigenvals(multiple=True)
        return 1 / min(ef)
    return value


def _vdot_bounds():
    return [
        TermBound("−λωᵀFω", -lam * phi_min * w**2,
                  Rayleigh(omega(t), F, factor=-lam, eigenvalue=_eig("min", F), norm_squared=w**2)),
        TermBound("−λa‖s−r‖^{μ−1}ωᵀ(s×r)", lam * a * e**mu * w,
                  CauchySchwarz(omega(t), _sxr_vec, (measured(W_), _sxr), factor=-lam * a * e ** (mu - 1))),
        TermBound("λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ", lam * abs(b) * tau_j * w * j**mu,
                  CauchySchwarz(omega(t), J, (measured(W_), _J), factor=lam * b)),
        TermBound("−((ω×s)×r)ᵀF⁻¹Θω", c_A * w**2, Template("c_A", {"w": 2, "e": 0}, rho_max=RHO_CAP)),
        TermBound("−(s×r)ᵀF⁻¹(ω×Θω)", c_B * e * w**2, Template("c_B", {"e": 1, "w": 2}, rho_max=RHO_CAP)),
        TermBound("−(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)", -(a - tau * b) * psi_min * e ** (mu - 1) * e**2 * (1 - e**2 / 4),
                  Rayleigh(_sxr_vec, F_inv, factor=-(a - tau * b) * e ** (mu - 1), eigenvalue=_eig_inv_min(),
                           norm_squared=e**2 * (1 - e**2 / 4))),
        TermBound("−b((ω×s)×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ", abs(b) * Finv_norm * k_tau * w * j**mu,
                  CauchySchwarz(_wxsxr_vec, K, (_wxsxr, _K), matrix=F_inv, factor=-b, operator_norm=_eig_inv_norm())),
        TermBound("(α+βτ)‖s−r‖^{μ+1}", (alpha + beta * tau) * e ** (mu + 1), Equal((alpha + beta * tau) * e ** (mu + 1))),
        TermBound("−α‖s(t−τ)−r‖^{μ+1}", 0, Nonpositive()),
        TermBound("−β∫‖s(ξ)−r‖^{μ+1}dξ", -beta * j ** (mu + 1), Equal(-beta * j ** (mu + 1))),
    ]


def _eig_inv_min():
    def value(ctx):
        ef = sympy.Matrix(ctx.at(F)).eigenvals(multiple=True)
        return 1 / max(ef)
    return value


def _sum(bounds):
    return sum((tb.bound for tb in bounds), sympy.S.Zero)


def _named(name):
    return lambda values: eigen_bounds(values)[name]


DEFINITIONS = {theta_min: _named("theta_min"), theta_max: _named("theta_max"), phi_min: _named("phi_min"),
               psi_min: _named("psi_min"), Finv_norm: _named("Finv_norm")}


def _sum(bounds):
    return sum((tb.bound for tb in bounds), sympy.S.Zero)


def chain_steps(functional, derivation):
    """(V ≥ L, V ≤ U, V̇ ≤ W) for the functional of Theorem 3 and its structured V̇ (``derivation``)."""
    L, U, W = _functional_bounds("lower"), _functional_bounds("upper"), _vdot_bounds()
    common = dict(region=REGION, definitions=DEFINITIONS)
    return (TermwiseBound("V ≥ L", functional, system, "V", L, _sum(L), MEASURES, relation=">=", role="lower",
                          **common),
            TermwiseBound("V ≤ U", functional, system, "V", U, _sum(U), MEASURES, relation="<=", role="upper",
                          **common),
            TermwiseBound("V̇ ≤ W", functional, system, "Vdot", W, _sum(W), MEASURES, relation="<=",
                          derivation=derivation, role="vdot", **common))


#: the decay of estimate (15): V̇ ≤ −c̃V^{3/2} for μ = 2; at t0 (∫‖s − r‖³)^{1/3} ≤ τ^{1/3}‖χ‖_τ
DECAY = Decay(sympy.Rational(3, 2), ("w", "e"), {"j": tau_j}, {"d1": "e", "d2": "w"}, "d3",
              descriptions={"d1": "‖s(t)−r‖ ≤ d1‖χ‖_τ(1 + d3‖χ‖_τ(t−t0))^{−1}:",
                            "d2": "‖ω(t)‖ ≤ d2‖χ‖_τ(1 + d3‖χ‖_τ(t−t0))^{−1}:", "d3": "the rate in (15):",
                            "delta_tilde": "valid for ‖χ‖_τ < δ̃:", "C0": "V(t0) ≤ C0‖χ‖_τ²",
                            "c_tilde": "V̇ ≤ −c̃V^{3/2} on the region", "l_e": "V ≥ l_e‖s−r‖²",
                            "l_w": "V ≥ l_w‖ω‖²"},
              paper=PRINTED_15_STATED)  # compared only at the Fig. 6/7 data, where the paper states (15)

#: the proof's free choices at the Fig. 6 gains (found by `lkverify constants aleksandrov2023.theorem3`)
CHOICES = {"lam": "23648/1601", "alpha": "9/10", "beta": "202/5957", "delta_e": "1/200", "delta_w": "1571/9995"}
