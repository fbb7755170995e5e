"""The proof of Theorem 2 of paper 000 from functional (14) to its conclusion, as checked bound steps.

The paper proves Theorem 2 in the steps of Theorem 1, with memory integrals over [0, t]
instead of windows: two-sided bounds on V with c1 … c4, the V̇ bound with c5 … c10, then
"taking Assumption 2 into account" f^ν LᵀD⁻¹ΞL ≥ εc11(‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}) near the
target, "using Assumption 1 and Hölder's inequality"

    ∫_0^t ∫_{t−ξ}^∞‖G(ζ)‖dζ W(ξ)dξ ≤ σ∫_0^t ‖G(t−ξ)‖W(ξ)dξ,
    ∫_0^t ‖G(t−ξ)‖‖s_j(ξ)−r_j‖^{2ν+1}dξ ≤ c12(∫_0^t ‖G(t−ξ)‖‖s_j(ξ)−r_j‖^{2ν+2}dξ)^{(2ν+1)/(2ν+2)},

and "for δ, μ small and γ large" the final estimates on ‖s_{1t}−r1‖_{[−t,0]} + ‖s_{2t}−r2‖_{[−t,0]} < δ.
Here each step is a rule with checked side conditions on the region

    ‖s_i(ξ) − r_i‖ ≤ δ for ξ ∈ [0, t], i = 1, 2,

in w = ‖ω(t)‖, e_i = ‖s_i(t) − r_i‖, l = ‖L(t)‖ and the memory measures
(:mod:`lkverify.certify.steps.memory`; k = 2ν+1, P = 2ν+2, K₊(u) = ∫_u^∞|g|, G = g(ζ)I):

    Q_i = ∫_0^t K₊(t−ξ)‖s_i−r_i‖^P,  R_i = ∫_0^t K₊(t−ξ)‖s_i−r_i‖^k,
    J_i = ∫_0^t |g(t−ξ)|‖s_i−r_i‖^P,  S_i = ∫_0^t |g(t−ξ)|‖s_i−r_i‖^k.

* V ≥ L, V ≤ U: as for Theorem 1; μ∫K₊W = μ(Q1 + Q2); ‖∫K f^νL‖ ≤ c10′(R1 + R2) (|K| ≤ K₊,
  c10′ the certified homogeneous supremum), then Hölder on the memory R_i ≤ K̄^{1/P}Q_i^{k/P}
  (K̄ = ∫_0^∞K₊), Young (η_K) and e_i^P ≤ δ^{P−2}e_i².
* V̇ ≤ W, on the exact structured V̇ of :mod:`.functional14`: −γβf^νωᵀL by |β| (the printed
  γβc7 needs β ≥ 0, :mod:`.theorem2_bound`), c7 certified, Young (η), e_i^{2k} ≤ δ^{2ν}e_i^P;
  the εc11 step: Rayleigh with λ_min(D⁻¹)(β + ∫g) (Assumption 2), (10) by Lemma 1 of paper
  001 (:func:`.theorem1_chain.lemma10`, certified), (ΣA)^ν ≥ A_i^ν; the integral torque
  ‖J‖ ≤ c9(S1 + S2) then Hölder with c12 = ḡ^{1/P} (ḡ = ∫_0^∞|g|); the memory torque
  ‖∫K f^νL‖ ≤ c10′(R1 + R2), R_i ≤ σS_i (Assumption 1, σ of :mod:`.assumption1`), Hölder c12;
  Young (η) and J_i^{2k/P} ≤ (ḡδ^P)^{2k/P−1}J_i on the region.

The conclusion ([9, pp. 211, 212]) is Krasovskii's sign test with the memory measures bounded
by the history's sup (:class:`~lkverify.certify.steps.memory.MemoryKrasovskii`); the paper's final
estimates V ≥ ½(f + μ∫∫‖G‖W + c1γ‖ω‖²) (c1 = θ_min/2) and V̇ ≤ −½(γc6‖ω‖² + εc11ΣW(t) +
μ∫‖G(t−ξ)‖W) are then compared with the checked L and W coefficient by coefficient (findings).  The choices
γ, μ, ε, δ, η_w, η_K, η are found at the run's gains by :func:`find_choices` (floating point
only picks them; every step is proved at those exact values).
"""

from __future__ import annotations

import functools
import math

import sympy

from lkverify import Status, t, xi, zeta
from lkverify.certify.steps.chain import TermBound, TermwiseBound, collect_monomials, lyapunov_steps
from lkverify.certify.steps.measures import Region, sup_norm
from lkverify.certify.steps.memory import (U, Evaluated, KernelBound, MemoryHolder, MemoryKrasovskii, MemoryWeight,
                                           evaluate_constant_integrals, kernel_integral, memory_integral_of,
                                           memory_measure)
from lkverify.certify.steps.rewrites import LowerBound, OnRegion, PowerSplit, YoungEach
from lkverify.certify.steps.rules import (Application, CauchySchwarz, Condition, Equal, Homogeneous, Rayleigh, Rule,
                                          crossed, measured, scaled, summed, unit)
from lkverify import tail_integral
from lkverify.declare.parameters import apply_substitution

from .assumption1 import decide_assumption1
from .equations import (D, D_inv, L, P, Theta, alpha1, alpha2, beta, delta, epsilon, eta, eta_K, eta_w, g, gamma, mu,
                        nu, omega, r1, r2, s1, s2, system_pid)
from .functional14 import J, K as K_signed, M, derivation, functional, int_KfL
from .theorem1_bound import MEASURES as _T1, L_norm_tree, M_norm_tree, Theta_w_tree, dinv, eig_of, f_of
from .theorem1_chain import _homogeneous_estimate, _rational_above, _rational_below, lemma10

__all__ = ["CONCLUSION", "MEASURES", "PRINTED_LOWER", "PRINTED_VDOT", "REGION", "chain_steps", "find_choices",
           "printed_upper", "printed_vdot_bound", "steps"]

K = 2 * nu + 1  # k
Pw = 2 * nu + 2  # P
_by = {m.name: m for m in _T1}
w_, e1_, e2_, l_ = (_by[n] for n in ("w", "e1", "e2", "l"))
w, e1, e2, l = (m.symbol for m in (w_, e1_, e2_, l_))


def K_plus(u):
    """K₊(u) = ∫_u^∞ ‖G(ζ)‖dζ = ∫_u^∞ |g(ζ)|dζ, the weight of (14)."""
    return tail_integral(sympy.Abs(g(zeta)), u)


def G_norm(u):
    """‖G(u)‖ = |g(u)|."""
    return sympy.Abs(g(u))


def _memory(name, kernel, power, k, s, r, what):
    return memory_measure(f"{name}{k}", s(xi) - r, p=power, kernel=kernel,
                          text=f"∫_0^t {what}‖s{k}(ξ)−r{k}‖^{{{'2ν+2' if power == Pw else '2ν+1'}}}dξ")


_axes = ((1, s1, r1), (2, s2, r2))
Q1, Q2 = (_memory("Q", K_plus, Pw, k, s, r, "K₊(t−ξ)") for k, s, r in _axes)
R1, R2 = (_memory("R", K_plus, K, k, s, r, "K₊(t−ξ)") for k, s, r in _axes)
J1, J2 = (_memory("J", G_norm, Pw, k, s, r, "‖G(t−ξ)‖") for k, s, r in _axes)
S1, S2 = (_memory("S", G_norm, K, k, s, r, "‖G(t−ξ)‖") for k, s, r in _axes)
q1, q2, j1, j2 = (m.symbol for m in (Q1, Q2, J1, J2))
MEASURES = (w_, e1_, e2_, l_, Q1, Q2, R1, R2, J1, J2, S1, S2)

SUP1, SUP2 = (sup_norm(f"m{k}", s(xi) - r, window=sympy.oo, text=f"max_{{[0,t]}} ‖s{k}(ξ) − r{k}‖")
              for k, s, r in _axes)
REGION = Region({SUP1: delta, SUP2: delta})

theta_min, theta_max, c6, dmin, Dinv_norm = sympy.symbols("theta_min theta_max c6 lambda_Dinv Dinv_norm",
                                                          positive=True)
gbar, Kbar, sigma, Xi_c = sympy.symbols("gbar Kbar sigma Xi_c", positive=True)
c7, c9, c10p = sympy.symbols("c7 c9 c10p", positive=True)


def _at_values(expr):
    """A named constant: ``expr`` at the run's values, its constant integrals evaluated exactly."""
    def value(v):
        return evaluate_constant_integrals(apply_substitution(expr, P.substitution(v)))
    return value


def _kbar(v):
    """K̄ = ∫_0^∞ K₊(u)du (∞ when it diverges: the memory steps then fail)."""
    val = kernel_integral(sympy.Lambda(U, K_plus(U)), P.substitution(v))
    return sympy.oo if val is None else val


def _sigma(v):
    """σ of Assumption 1 at the run's kernel (:func:`.assumption1.decide_assumption1`); 0 when it fails."""
    return _sigma_of(sympy.sympify(v["g"]).subs(sympy.Symbol("zeta"), zeta))


@functools.lru_cache(maxsize=32)
def _sigma_of(g_expr):
    res = decide_assumption1(g_expr, budget=10)
    return res.sigma if res.holds and res.sigma is not None else sympy.S.Zero


DEFINITIONS = {theta_min: eig_of("Theta", "min"), theta_max: eig_of("Theta", "max"), c6: eig_of("D", "min"),
               dmin: eig_of("D", "max", True), Dinv_norm: eig_of("D", "min", True),
               gbar: _at_values(sympy.Integral(sympy.Abs(g(zeta)), (zeta, 0, sympy.oo))), Kbar: _kbar,
               sigma: _sigma, Xi_c: _at_values(beta + sympy.Integral(g(zeta), (zeta, 0, sympy.oo)))}


def _pointwise(m1, m2):
    """f^ν(ξ)‖L(ξ)‖ ≤ f^ν(ξ)(α1‖s1(ξ)−r1‖ + α2‖s2(ξ)−r2‖) in the memory measures' pointwise norms."""
    return scaled(f_of(m1.pointwise_symbol, m2.pointwise_symbol),
                  summed(scaled(alpha1, crossed(measured(m1, at=xi), unit(r1))),
                         scaled(alpha2, crossed(measured(m2, at=xi), unit(r2)))))


_memory_torque = memory_integral_of(_pointwise(R1, R2), measures=(R1, R2), power=K, weight=K_signed, constant="c10p")
_integral_torque = memory_integral_of(_pointwise(S1, S2), measures=(S1, S2), power=K, weight=g(t - xi),
                                      constant="c9")
_Qk = [q ** (K / Pw) for q in (q1, q2)]
_Jk = [j ** (K / Pw) for j in (j1, j2)]
_c12 = gbar ** (1 / Pw)  # the paper's c12 = (∫_0^∞‖G‖)^{1/(2ν+2)}


def _lower_bounds():
    qy = Pw / K
    return [
        TermBound("f", (alpha1 * e1**2 + alpha2 * e2**2) / 2, Equal((alpha1 * e1**2 + alpha2 * e2**2) / 2)),
        TermBound("(γ/2)ωᵀΘω", gamma / 2 * theta_min * w**2,
                  Rayleigh(omega(t), Theta, factor=gamma / 2, eigenvalue=eig_of("Theta", "min"), norm_squared=w**2)),
        TermBound("LᵀD⁻¹Θω",
                  -Dinv_norm * theta_max * sum(a * (eta_w * e**2 / 2 + w**2 / (2 * eta_w))
                                               for a, e in ((alpha1, e1), (alpha2, e2))),
                  CauchySchwarz(L(t), Theta * omega(t), (L_norm_tree(e1_, e2_), Theta_w_tree), matrix=D_inv,
                                operator_norm=dinv),
                  then=(YoungEach(((e1, w, 2, 2, eta_w), (e2, w, 2, 2, eta_w))),)),
        TermBound("μ∫∫_{t−ξ}^∞‖G‖dζ W(ξ)dξ", mu * (q1 + q2), MemoryWeight(("Q1", "Q2"))),
        TermBound("−LᵀD⁻¹∫∫_{t−ξ}^∞G dζ f^ν(ξ)L(ξ)dξ",
                  -Dinv_norm * c10p * Kbar ** (1 / Pw) * sum(
                      a * (eta_K * delta ** (Pw - 2) * e**2 / Pw + eta_K ** (-qy / Pw) * q / qy)
                      for a, e in ((alpha1, e1), (alpha2, e2)) for q in (q1, q2)),
                  CauchySchwarz(L(t), int_KfL, (L_norm_tree(e1_, e2_), _memory_torque), matrix=D_inv, factor=-1,
                                operator_norm=dinv),
                  then=(MemoryHolder("R1", "Q1"), MemoryHolder("R2", "Q2"),
                        YoungEach(tuple((e, y, Pw, qy, eta_K) for e in (e1, e2) for y in _Qk)),
                        OnRegion("e1", 2), OnRegion("e2", 2))),
    ]


def _upper_bounds():
    cross = sum(a * e for a, e in ((alpha1, e1), (alpha2, e2)))
    return [
        TermBound("f", (alpha1 * e1**2 + alpha2 * e2**2) / 2, Equal((alpha1 * e1**2 + alpha2 * e2**2) / 2)),
        TermBound("(γ/2)ωᵀΘω", gamma / 2 * theta_max * w**2,
                  Rayleigh(omega(t), Theta, factor=gamma / 2, eigenvalue=eig_of("Theta", "max"), norm_squared=w**2)),
        TermBound("LᵀD⁻¹Θω", Dinv_norm * theta_max * cross * w,
                  CauchySchwarz(L(t), Theta * omega(t), (L_norm_tree(e1_, e2_), Theta_w_tree), matrix=D_inv,
                                operator_norm=dinv)),
        TermBound("μ∫∫_{t−ξ}^∞‖G‖dζ W(ξ)dξ", mu * (q1 + q2), MemoryWeight(("Q1", "Q2"))),
        TermBound("−LᵀD⁻¹∫∫_{t−ξ}^∞G dζ f^ν(ξ)L(ξ)dξ", Dinv_norm * c10p * cross * (R1.symbol + R2.symbol),
                  CauchySchwarz(L(t), int_KfL, (L_norm_tree(e1_, e2_), _memory_torque), matrix=D_inv, factor=-1,
                                operator_norm=dinv)),
    ]


def _young_J(factor):
    """factor·w(J1^{k/P} + J2^{k/P}) ≤ factor(ηw² + B^{2k/P−1}(J1 + J2)/(2η)), B = ḡδ^P the region's bound on J_i."""
    B = gbar * delta**Pw
    return factor * (eta * w**2 + B ** (2 * K / Pw - 1) * (j1 + j2) / (2 * eta))


_J_THEN = (MemoryHolder("S1", "J1"), MemoryHolder("S2", "J2"), YoungEach(tuple((w, y, 2, 2, eta) for y in _Jk)),
           OnRegion("J1", 1), OnRegion("J2", 1))


class _UnlessZero(Rule):
    """``rule`` then the rewrites ``then``, unless the term is 0 at the values (β = 0: bound 0, exact)."""

    def __init__(self, rule, then):
        self.rule, self.then = rule, tuple(then)
        self.name = rule.name

    def apply(self, term, direction, ctx):
        if sympy.expand(ctx.at(term)) == 0:
            return Application("the term vanishes at these values", sympy.S.Zero,
                               (Condition("the term is 0 (β = 0)", Status.EXACT),))
        apps = [self.rule.apply(term, direction, ctx)]
        for rewrite in self.then:
            if apps[-1].bound is None:
                break
            apps.append(rewrite.rewrite(apps[-1].bound, ctx, direction) if getattr(rewrite, "directional", False)
                        else rewrite.rewrite(apps[-1].bound, ctx))
        return Application(" then ".join(a.rule for a in apps), apps[-1].bound,
                           tuple(c for a in apps for c in a.conditions),
                           tuple(c for a in apps for c in a.constants))


def _vdot_bounds():
    a = (alpha1, alpha2)
    ten = LowerBound("l", sympy.sqrt(epsilon * (alpha1**2 * e1**2 + alpha2**2 * e2**2)), lemma10,
                     "(10): ‖L‖² ≥ ε(α1²‖s1−r1‖² + α2²‖s2−r2‖²)")
    return [
        TermBound("−γωᵀDω", -gamma * c6 * w**2, Rayleigh(omega(t), D, factor=-gamma, eigenvalue=eig_of("D", "min"),
                                                       norm_squared=w**2)),
        TermBound("−γβf^ν ωᵀL",
                  gamma * abs(beta) * c7 * (eta * w**2 + delta ** (2 * nu) * (e1**Pw + e2**Pw) / (2 * eta)),
                  _UnlessZero(CauchySchwarz(omega(t), L(t), (measured(w_), L_norm_tree(e1_, e2_)),
                                            factor=-gamma * beta * f_of(e1, e2)),
                              (Homogeneous(("e1", "e2"), e1**K + e2**K, "c7", factor=gamma * abs(beta) * w),
                               YoungEach(((w, e1**K, 2, 2, eta), (w, e2**K, 2, 2, eta))), OnRegion("e1", Pw),
                               OnRegion("e2", Pw)))),
        TermBound("−γωᵀ∫f^ν(ξ)G(t−ξ)L(ξ)dξ", _young_J(gamma * c9 * _c12),
                  CauchySchwarz(omega(t), J, (measured(w_), _integral_torque), factor=-gamma), then=_J_THEN),
        # the εc11 step: Assumption 2 (Ξ = (β + ∫g)I, λ_min(D⁻¹Ξ) = (β + ∫g)λ_min(D⁻¹)), (10), (ΣA)^ν ≥ A_i^ν
        TermBound("−f^ν LᵀD⁻¹ΞL",
                  -Xi_c * dmin * epsilon * sum((ai / 2) ** nu * ai**2 * e**Pw for ai, e in zip(a, (e1, e2))),
                  Evaluated(Rayleigh(L(t), D_inv, factor=-Xi_c * f_of(e1, e2), eigenvalue=eig_of("D", "max", True),
                                     norm_squared=l**2)),
                  then=(ten, PowerSplit())),
        TermBound("−LᵀD⁻¹(ω×(Θω))", Dinv_norm * theta_max * (alpha1 + alpha2) * delta * w**2,
                  CauchySchwarz(L(t), omega(t).cross(Theta * omega(t)),
                                (L_norm_tree(e1_, e2_), crossed(measured(w_), Theta_w_tree)),
                                matrix=D_inv, factor=-1, operator_norm=dinv),
                  then=(OnRegion("e1", 0), OnRegion("e2", 0))),
        TermBound("−MᵀD⁻¹Θω", Dinv_norm * theta_max * (alpha1 + alpha2) * w**2,
                  CauchySchwarz(M, Theta * omega(t), (M_norm_tree, Theta_w_tree), matrix=D_inv, factor=-1,
                                operator_norm=dinv)),
        TermBound("MᵀD⁻¹∫∫G dζ f^νL dξ", _young_J(Dinv_norm * (alpha1 + alpha2) * c10p * sigma * _c12),
                  CauchySchwarz(M, int_KfL, (M_norm_tree, _memory_torque), matrix=D_inv, operator_norm=dinv),
                  then=(KernelBound("R1", "S1", sigma), KernelBound("R2", "S2", sigma), *_J_THEN)),
        TermBound("μ∫_0^∞‖G‖dζ W(t)", mu * gbar * (e1**Pw + e2**Pw), Evaluated(Equal(mu * gbar * (e1**Pw + e2**Pw)))),
        TermBound("−μ∫‖G(t−ξ)‖W(ξ)dξ", -mu * (j1 + j2), MemoryWeight(("J1", "J2"))),
    ]


def _sum(bounds):
    return sum((tb.bound for tb in bounds), sympy.S.Zero)


def chain_steps():
    """(V ≥ L, V ≤ U, V̇ ≤ W) of the proof of Theorem 2 on :data:`REGION`."""
    lower, upper, vdot = _lower_bounds(), _upper_bounds(), _vdot_bounds()
    return lyapunov_steps(functional, system_pid, lower, upper, vdot, MEASURES,
                          region=REGION, definitions=DEFINITIONS, derivation=derivation)


steps = chain_steps()

# ---- the printed V̇ bound with c5 … c10 -----------------------------------------------------------
c8p, c5p, c10 = Dinv_norm * theta_max, Dinv_norm * theta_max * (alpha1 + alpha2), Dinv_norm * (alpha1 + alpha2) * c10p


def printed_vdot_bound(c10_sign=1):
    """The printed V̇ bound with c5 … c10 on the exact V̇ (a step of its own, not a link of the chain).

    The print reads ``… dξ − + c10‖ω‖∫∫‖G‖…``: with ``c10_sign=-1`` the step is the "−" reading,
    which the rules refuse (they give +c10).  c5 = ‖D⁻¹‖θ_max(α1 + α2), c6 = λ_min(D),
    c8 = ‖D⁻¹‖θ_max, c10 = ‖D⁻¹‖(α1 + α2)c10′ and c7, c9, c10′ the certified homogeneous
    supremum; −f^νLᵀD⁻¹ΞL is kept (≤ −(β + ∫g)λ_min(D⁻¹)f^ν‖L‖², Assumption 2); γβc7 as printed
    (it needs β ≥ 0, :mod:`.theorem2_bound`).
    """
    kS = S1.symbol + S2.symbol
    kR = R1.symbol + R2.symbol
    bounds = [
        TermBound("−γωᵀDω", -gamma * c6 * w**2, Rayleigh(omega(t), D, factor=-gamma, eigenvalue=eig_of("D", "min"),
                                                       norm_squared=w**2)),
        TermBound("−γβf^ν ωᵀL", gamma * beta * c7 * w * (e1**K + e2**K),
                  _UnlessZero(CauchySchwarz(omega(t), L(t), (measured(w_), L_norm_tree(e1_, e2_)),
                                            factor=-gamma * beta * f_of(e1, e2)),
                              (Homogeneous(("e1", "e2"), e1**K + e2**K, "c7", factor=gamma * abs(beta) * w),))),
        TermBound("−γωᵀ∫f^ν(ξ)G(t−ξ)L(ξ)dξ", gamma * c9 * w * kS,
                  CauchySchwarz(omega(t), J, (measured(w_), _integral_torque), factor=-gamma)),
        TermBound("−f^ν LᵀD⁻¹ΞL", -Xi_c * dmin * f_of(e1, e2) * l**2,
                  Evaluated(Rayleigh(L(t), D_inv, factor=-Xi_c * f_of(e1, e2), eigenvalue=eig_of("D", "max", True),
                                     norm_squared=l**2))),
        TermBound("−LᵀD⁻¹(ω×(Θω))", c8p * w**2 * (alpha1 * e1 + alpha2 * e2),
                  CauchySchwarz(L(t), omega(t).cross(Theta * omega(t)),
                                (L_norm_tree(e1_, e2_), crossed(measured(w_), Theta_w_tree)),
                                matrix=D_inv, factor=-1, operator_norm=dinv)),
        TermBound("−MᵀD⁻¹Θω", c5p * w**2, CauchySchwarz(M, Theta * omega(t), (M_norm_tree, Theta_w_tree), matrix=D_inv,
                                                      factor=-1, operator_norm=dinv)),
        TermBound("MᵀD⁻¹∫∫G dζ f^νL dξ", c10_sign * c10 * w * kR,
                  CauchySchwarz(M, int_KfL, (M_norm_tree, _memory_torque), matrix=D_inv, operator_norm=dinv)),
        TermBound("μ∫_0^∞‖G‖dζ W(t)", mu * gbar * (e1**Pw + e2**Pw), Evaluated(Equal(mu * gbar * (e1**Pw + e2**Pw)))),
        TermBound("−μ∫‖G(t−ξ)‖W(ξ)dξ", -mu * (j1 + j2), MemoryWeight(("J1", "J2"))),
    ]
    sign = "+" if c10_sign > 0 else "−"
    return TermwiseBound(f"printed V̇ bound with c5…c10 ({sign}c10)", functional, system_pid, "Vdot", bounds,
                         _sum(bounds), MEASURES, derivation=derivation, region=REGION, definitions=DEFINITIONS,
                         witness_seconds=1.0)


# ---- the printed final estimates ---------------------------------------------------------------
c11 = Xi_c * dmin * sympy.Min(*[(a / 2) ** nu * a**2 for a in (alpha1, alpha2)])  # εc11: Assumption 2 and (10)
#: V ≥ ½(f + μ∫∫‖G‖W + c1γ‖ω‖²) with c1 = θ_min/2 (the constant of (γ/2)ωᵀΘω ≥ c1γ‖ω‖²)
PRINTED_LOWER = ((alpha1 * e1**2 + alpha2 * e2**2) / 2 + mu * (q1 + q2) + theta_min / 2 * gamma * w**2) / 2
#: V̇ ≤ −½(γc6‖ω‖² + εc11(‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}) + μ∫‖G(t−ξ)‖W)
PRINTED_VDOT = -(gamma * c6 * w**2 + epsilon * c11 * (e1**Pw + e2**Pw) + mu * (j1 + j2)) / 2


def printed_upper():
    """V ≤ 2(f + c4γ‖ω‖² + μ∫∫‖G‖W), c4 = θ_max/2: the upper bounds of V ≤ U, then Young on the cross terms.

    e_iw ≤ (η_U e_i² + w²/η_U)/2 with η_U = 1/(2‖D⁻¹‖θ_max); R_j ≤ K̄^{1/P}Q_j^{k/P} (Hölder on the memory),
    e_iQ_j^{k/P} ≤ η_K e_i^P/P + η_K^{−q/P}Q_j/q and e_i^P ≤ δ^{P−2}e_i²; the sum must be at most the
    printed right-hand side (coefficient by coefficient, at the checked values).
    """
    qy, eta_U = Pw / K, 1 / (2 * Dinv_norm * theta_max)
    bounds = list(_upper_bounds())
    cs, memory = bounds[2], bounds[4]
    bounds[2] = TermBound(cs.terms, Dinv_norm * theta_max * sum(a * (eta_U * e**2 / 2 + w**2 / (2 * eta_U))
                                                                 for a, e in ((alpha1, e1), (alpha2, e2))),
                          cs.rule, then=(YoungEach(((e1, w, 2, 2, eta_U), (e2, w, 2, 2, eta_U))),))
    bounds[4] = TermBound(memory.terms, Dinv_norm * c10p * Kbar ** (1 / Pw) * sum(
        a * (eta_K * delta ** (Pw - 2) * e**2 / Pw + eta_K ** (-qy / Pw) * q / qy)
        for a, e in ((alpha1, e1), (alpha2, e2)) for q in (q1, q2)), memory.rule,
        then=(MemoryHolder("R1", "Q1"), MemoryHolder("R2", "Q2"),
              YoungEach(tuple((e, y, Pw, qy, eta_K) for e in (e1, e2) for y in _Qk)),
              OnRegion("e1", 2), OnRegion("e2", 2)))
    rhs = 2 * ((alpha1 * e1**2 + alpha2 * e2**2) / 2 + theta_max / 2 * gamma * w**2 + mu * (q1 + q2))
    return TermwiseBound("V ≤ 2(f + c4γ‖ω‖² + μ∫∫‖G‖W)", functional, system_pid, "V", bounds, rhs, MEASURES,
                         region=REGION, definitions=DEFINITIONS, witness_seconds=1.0)


def _printed_gaps(lower_rhs, vdot_rhs):
    """(name, L − printed lower, printed V̇ − W): both must have every coefficient ≥ 0."""
    return (("V ≥ ½(f + μ∫∫‖G‖W + c1γ‖ω‖²)", lower_rhs - PRINTED_LOWER),
            ("V̇ ≤ −½(γc6‖ω‖² + εc11ΣW(t) + μ∫‖G(t−ξ)‖W)", PRINTED_VDOT - vdot_rhs))


class _Conclusion(MemoryKrasovskii):
    """Krasovskii with memory, and the paper's final estimates compared with the checked L and W (findings)."""

    def certify(self, checked, values, **kw):
        from lkverify import Result
        from lkverify.certify.steps.chain import coefficient_sign

        rows, status, detail = super().certify(checked, values, **kw)
        sub = dict(system_pid.parameters.substitution(values))
        sub.update(steps[0].named_constants(values))
        meas = {m.symbol for m in MEASURES}
        for name, gap in _printed_gaps(checked["lower"][1].rhs, checked["vdot"][1].rhs):
            gap = apply_substitution(sympy.sympify(gap).xreplace(sub), sub)
            worst, why = Status.EXACT, ""
            for mono, coeff in collect_monomials(sympy.expand(gap), meas).items():
                sign, st = coefficient_sign(coeff)
                if sign is None or sign < 0:
                    worst = Status.UNDECIDED if sign is None else Status.FAILED
                    why = f"the coefficient of {mono} falls short by {float(coeff):.4g}"
                    break
                worst = Status.CERTIFIED if st is Status.CERTIFIED else worst
            rows.append(Result("bound", f"printed final estimate {name}", worst, None,
                               why or f"follows from the checked {'L' if 'V ≥' in name else 'W'}, coefficient by "
                                      f"coefficient ({worst})"))
        up = printed_upper().check(values, search=False)
        rows.append(Result("bound", f"printed final estimate {up.name}", up.status, None, up.detail))
        return rows, status, detail


#: the conclusion: V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖_[0,t]), V̇ ≤ −ψ(‖x(t)‖), x(t) = (ω, s1 − r1, s2 − r2)
CONCLUSION = _Conclusion(("w", "e1", "e2"))


# ---- the free choices ---------------------------------------------------------------------------
_CHOICES = ("gamma", "mu", "eta_w", "eta_K", "eta")


def _coefficients(values, choice):
    """[(sign wanted, f(δ))] for every coefficient of L and W at the choices (c7, c9, c10′ estimated 2 % high)."""
    f = lambda x: float(sympy.N(x, 30))  # noqa: E731
    ch = 1.02 * _homogeneous_estimate(f(2 * values["nu"] + 1), f(values["nu"]), f(values["alpha1"]),
                                      f(values["alpha2"]))
    base = {k: v for k, v in values.items() if k not in (*_CHOICES, "delta", "epsilon")}
    sub = dict(system_pid.parameters.substitution(base))
    sub.update(steps[0].named_constants(values))
    sub.update({c7: ch, c9: ch, c10p: ch, epsilon: sympy.Rational(choice["epsilon"])})
    sub.update({sympy.Symbol(n, positive=True): sympy.Rational(choice[n]) for n in _CHOICES})
    meas = {m.symbol for m in MEASURES}
    out = []
    for step in steps:  # every coefficient of its sign (U's are positive for every positive choice)
        if step.role == "upper":
            continue
        rhs = apply_substitution(sympy.sympify(step.rhs).xreplace(sub), sub)
        for mono, coeff in collect_monomials(rhs, meas).items():
            out.append((1 if step.role == "lower" else -1, sympy.lambdify([delta], coeff, "math")))
    for _, gap in _printed_gaps(steps[0].rhs, steps[2].rhs):  # and the paper's final estimates
        gap = apply_substitution(sympy.sympify(gap).xreplace(sub), sub)
        for mono, coeff in collect_monomials(sympy.expand(gap), meas).items():
            out.append((1, sympy.lambdify([delta], coeff, "math")))
    return out


def _largest_delta(fns, hi=0.5):
    def ok(d):
        try:
            return all(want * fn(d) > 0 for want, fn in fns)
        except (ValueError, OverflowError, ZeroDivisionError):
            return False
    lo_, hi_ = -400.0, math.log(hi)
    if ok(hi):
        return hi
    if not ok(math.exp(lo_)):
        return 0.0
    for _ in range(80):
        mid = (lo_ + hi_) / 2
        lo_, hi_ = (mid, hi_) if ok(math.exp(mid)) else (lo_, mid)
    return math.exp(lo_)


def find_choices(values) -> dict:
    """γ, μ, ε, δ, η_w, η_K, η for which every coefficient of L and W has its sign (exact strings).

    The recipe follows the proof ("δ, μ small, γ large") and aims at the paper's final
    estimates with their factors ½: ε = 1/2; η_w leaves 3α_i/8 of f's e_i² in L; μḡ is an
    eighth of εc11; η_K leaves μ/2 of the Q_i; η gives the γ-terms a quarter of γc6; γ is 10 %
    above what the ω-terms need; then δ is the largest value (bisection, times 0.9, three
    digits) with every coefficient of L and W of its sign and the printed estimates implied.
    Floating point only picks the numbers; the steps prove them.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.proofs.aleksandrov2026.equations import P
    >>> ch = find_choices(P.resolve({}, use_defaults=True))
    >>> sorted(ch), 0 < float(sympy.Rational(ch["delta"])) < 0.5
    (['delta', 'epsilon', 'eta', 'eta_K', 'eta_w', 'gamma', 'mu'], True)
    """
    try:
        return _recipe(values)
    except (ValueError, TypeError, ZeroDivisionError, OverflowError):
        # gains outside the theorem's hypotheses (Ξ ≤ 0, a kernel failing Assumption 1): the recipe has no
        # positive numbers; the defaults' choices are checked instead, and the chain says which step fails
        return dict(_FALLBACK)


_FALLBACK = {"gamma": "123", "mu": "19/125", "eta_w": "57/2000", "eta_K": "25/2", "eta": "277/1000",
             "epsilon": "1/2", "delta": "1/1000000"}


def _recipe(values) -> dict:
    f = lambda x: float(sympy.N(x, 30))  # noqa: E731
    v = values
    nc = {str(k): f(x) for k, x in steps[0].named_constants(v).items()}
    a1, a2, nu_ = f(v["alpha1"]), f(v["alpha2"]), f(v["nu"])
    k, P_ = 2 * nu_ + 1, 2 * nu_ + 2
    ch = 1.02 * _homogeneous_estimate(k, nu_, a1, a2)
    eps = sympy.Rational(1, 2) if v.get("epsilon") is None else sympy.Rational(v["epsilon"])
    dn, thmax, thmin, c6_ = nc["Dinv_norm"], nc["theta_max"], nc["theta_min"], nc["c6"]
    gb, kb, sg, b = nc["gbar"], nc["Kbar"], nc["sigma"], abs(f(v["beta"]))
    c12 = gb ** (1 / P_)
    if not all(math.isfinite(x) and x > 0 for x in (gb, kb, sg, nc["Xi_c"])):
        raise ValueError("outside the hypotheses")
    eta_w_ = _rational_below(1 / (4 * dn * thmax))
    E = min(float(eps) * nc["Xi_c"] * nc["lambda_Dinv"] * (a / 2) ** nu_ * a**2 for a in (a1, a2))
    mu_ = _rational_below(E / (8 * gb))
    q = P_ / k
    eta_K_ = _rational_above((2 * dn * ch * kb ** (1 / P_) * (a1 + a2) / (q * float(mu_))) ** k)
    eta_ = _rational_below(c6_ / (4 * (b * ch + ch * c12)))
    rest = dn * thmax * (a1 + a2) * 1.5 + dn * (a1 + a2) * ch * sg * c12 * float(eta_)
    gamma_ = _rational_above(max(2.2 * dn * thmax * (a1 + a2) / float(eta_w_) / thmin, 4.4 * rest / c6_))
    choice = {"gamma": str(gamma_), "mu": str(mu_), "eta_w": str(eta_w_), "eta_K": str(eta_K_), "eta": str(eta_),
              "epsilon": str(eps)}
    d = _largest_delta(_coefficients(v, choice))
    choice["delta"] = str(_rational_below(0.9 * d)) if d > 0 else "1/1000000"
    return choice
