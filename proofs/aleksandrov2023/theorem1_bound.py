"""The printed estimates with c1 … c12 of the proof of Theorem 1 of paper 002, as bound steps.

After (П.1) and its V̇ the appendix prints ("by the properties of homogeneous functions")

    λc1‖q̇‖² + c2‖q‖² − c3‖q‖‖q̇‖ − c4τ‖q‖∫‖q‖^μ + α∫‖q‖^{μ+1} ≤ V
        ≤ λc5‖q̇‖² + c6‖q‖² + c3‖q̇‖‖q̇‖ + c4τ‖q‖∫‖q‖^μ + (α + βτ)∫‖q‖^{μ+1},

    V̇ ≤ −(λc7 − c8)‖q̇‖² + λ‖q̇‖(c9‖q‖^μ + c10∫‖q‖^μ + p0‖q‖^σ) − c11‖q‖^{μ+1}
        + c12τ‖q̇‖∫‖q‖^μ − β∫‖q‖^{μ+1} + (α + βτ)‖q‖^{μ+1} − α‖q(t − τ)‖^{μ+1},

(integrals over [t − τ, t], of q(ξ)).  Each is checked term by term on the exact terms of V
and of the structured V̇ (:mod:`.theorem1_functional`), with, for the instance,

    c1 = λ_min(A)/2, c2 = λ_min(B)/2, c3 = ‖A‖, c4 = κ̃ (‖∂Π̃/∂q‖ = κ̃‖q‖³), c5 = λ_max(A)/2,
    c6 = λ_max(B)/2, c7 = λ_min(B), c8 = λ_max(A), c10 = c12 = κ̃,
    λc9 = sup −λq̇ᵀ∂Π/∂q/(‖q̇‖‖q‖³) and −c11 = sup −qᵀ(∂Π/∂q + τ∂Π̃/∂q)/‖q‖⁴ = −4 min(Π + τΠ̃)|_{‖q‖=1}
    (template constants certified with arb on the circle), λp0 ≥ sup −λq̇ᵀP(q)q/(‖q̇‖‖q‖^σ) (by (4)).

Finding: the upper bound prints c3‖q̇(t)‖‖q̇(t)‖ where the term it bounds, qᵀAq̇, needs
c3‖q(t)‖‖q̇(t)‖.  As printed, with the c3 of the lower bound (the same symbol, c3 = ‖A‖), the
step is refuted by a witness (qᵀAq̇ = 0.375 > c3‖q̇‖² = 0.1875 at the defaults); no other c3
saves the term either, since qᵀAq̇/‖q̇‖² is unbounded as q̇ → 0 with q fixed.  With ‖q‖‖q̇‖ it
is proved (:data:`upper_corrected`).
"""

import sympy

from lkverify import Check, t, xi
from lkverify.certify.steps.chain import TermBound, TermwiseBound
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm, window_integral_measure
from lkverify.certify.steps.rules import (CauchySchwarz, Equal, Printed, Rayleigh, Template, WindowWeight,
                                          integral_of, measured, scaled)
from lkverify import norm_squared

from .equations import PAPER
from .system3 import A, B, P3, alpha, beta, kappa_t, lam, mu, p0, q, sigma, system3, tau, v
from .theorem1_functional import J_int, K_int, derivation, functional

__all__ = ["extreme_eigenvalue", "MEASURES", "REGION", "DEFINITIONS", "lower", "upper_printed", "upper_corrected", "vdot", "theorem1_bound",
           "eig", "c1", "c2", "c3", "c4", "c5", "c6", "c7", "c8", "c10", "c12", "gradient_tree", "functional_terms",
           "vdot_terms"]

W_ = norm_measure("w", v(t), text="‖q̇(t)‖")
E_ = norm_measure("e", q(t), text="‖q(t)‖")
D_ = norm_measure("d", q(t - tau), text="‖q(t−τ)‖")
K_ = window_integral_measure("K", q(xi), p=mu, window=tau, text="∫‖q(ξ)‖^μ dξ")
I_ = window_integral_measure("I", q(xi), p=mu + 1, window=tau, text="∫‖q(ξ)‖^{μ+1} dξ")
SUP_ = sup_norm("m", q(xi), window=tau, text="max_{[t−τ,t]} ‖q(ξ)‖")
MEASURES = (W_, E_, D_, K_, I_)
w, e, d, K, I = (m.symbol for m in MEASURES)
#: the printed estimates hold on all of R^n (the region only serves the witness search)
REGION = Region({SUP_: sympy.Rational(1, 2), W_: sympy.Rational(1, 2)})

c1, c2, c3, c4, c5, c6, c7, c8, c10, c12 = sympy.symbols("c1 c2 c3 c4 c5 c6 c7 c8 c10 c12", positive=True)


def extreme_eigenvalue(M, which):
    """λ_min (``which="min"``) or λ_max of a symmetric matrix: exact when rational, else a rational bound.

    An irrational eigenvalue is replaced by a rational within 10⁻¹² below λ_min (above λ_max),
    so that M − mI ⪰ 0 (mI − M ⪰ 0) is decided exactly by the rules instead of staying undecided.
    """
    ev = sympy.Matrix(M).eigenvals(multiple=True)
    x = min(ev, key=lambda z: sympy.N(z, 50)) if which == "min" else max(ev, key=lambda z: sympy.N(z, 50))
    if x.is_Rational:
        return x
    scaled = sympy.N(x, 50) * 10**12
    return sympy.Rational(int(sympy.floor(scaled)) - 1 if which == "min" else int(sympy.ceiling(scaled)) + 1, 10**12)


def eig(which, name):
    """The extreme eigenvalue of the matrix parameter ``name`` at resolved values (:func:`extreme_eigenvalue`)."""
    return lambda values: extreme_eigenvalue(values[name], which)


def _ctx_eig(which, M):
    return lambda ctx: extreme_eigenvalue(ctx.at(M), which)


DEFINITIONS = {c1: lambda v_: eig("min", "A")(v_) / 2, c2: lambda v_: eig("min", "B")(v_) / 2, c3: eig("max", "A"),
               c4: kappa_t, c5: lambda v_: eig("max", "A")(v_) / 2, c6: lambda v_: eig("max", "B")(v_) / 2,
               c7: eig("min", "B"), c8: eig("max", "A"), c10: kappa_t, c12: kappa_t}


def gradient_tree(measure, *, holder=None, weight=1):
    """‖∫ g(ξ) ∂Π̃/∂q(q(ξ)) dξ‖ ≤ max|g|·κ̃·(measure): ∂Π̃/∂q = κ̃‖q‖²q, so ‖κ̃‖q(ξ)‖²q(ξ)‖ = κ̃‖q(ξ)‖³."""
    pointwise = scaled(norm_squared(q(xi)), measured(measure, at=xi))
    return integral_of(pointwise, measure=measure, power=mu, weight=kappa_t * weight, holder=holder)


def functional_terms(direction, measure, *, cross_bound, holder=None):
    """The five terms of (П.1) bounded below or above; ``cross_bound`` the stated bound of qᵀAq̇ and its rule."""
    up = direction == "upper"
    weight = alpha + beta * (xi - t + tau)
    return [
        TermBound("½λq̇ᵀAq̇", lam * (c5 if up else c1) * w**2,
                  Rayleigh(v(t), A, factor=lam / 2, eigenvalue=_ctx_eig("max" if up else "min", A), norm_squared=w**2)),
        TermBound("½qᵀBq", (c6 if up else c2) * e**2,
                  Rayleigh(q(t), B, factor=sympy.Rational(1, 2), eigenvalue=_ctx_eig("max" if up else "min", B),
                           norm_squared=e**2)),
        TermBound("qᵀAq̇", *cross_bound),
        TermBound("−qᵀ∫(ξ−t+τ)∂Π̃/∂q dξ", (1 if up else -1) * c4 * tau * e * K,
                  CauchySchwarz(q(t), K_int, (measured(E_), gradient_tree(measure, weight=xi - t + tau,
                                                                          holder=holder)), factor=-1)),
        TermBound("∫(α+β(ξ−t+τ))‖q(ξ)‖^{μ+1}dξ", (alpha + beta * tau if up else alpha) * I,
                  WindowWeight("I", mu + 1, weight=weight)),
    ]


_cs_A = CauchySchwarz(q(t), v(t), (measured(E_), measured(W_)), matrix=A, operator_norm=_ctx_eig("max", A))
_common = dict(region=REGION, definitions=DEFINITIONS)

lower_terms = functional_terms("lower", K_, cross_bound=(-c3 * e * w, _cs_A))
#: V ≥ λc1‖q̇‖² + c2‖q‖² − c3‖q‖‖q̇‖ − c4τ‖q‖∫‖q‖^μ + α∫‖q‖^{μ+1}
lower = TermwiseBound("printed V ≥ … (c1…c4)", functional, system3,
                      "V", lower_terms, sum((tb.bound for tb in lower_terms), sympy.S.Zero), MEASURES, relation=">=",
                      **_common)

_printed_terms = functional_terms("upper", K_, cross_bound=(c3 * w * w, Printed("the upper estimate after (П.1)")))
#: as printed: V ≤ λc5‖q̇‖² + c6‖q‖² + c3‖q̇‖‖q̇‖ + … (c3 = ‖A‖, the c3 of the lower bound)
upper_printed = TermwiseBound("printed V ≤ … + c3‖q̇‖‖q̇‖ + … (c3…c6)",
                              functional, system3, "V", _printed_terms,
                              sum((tb.bound for tb in _printed_terms), sympy.S.Zero), MEASURES,
                              witness_seconds=10.0, **_common)
_upper_terms = functional_terms("upper", K_, cross_bound=(c3 * e * w, _cs_A))
#: corrected: c3‖q‖‖q̇‖ in place of c3‖q̇‖‖q̇‖
upper_corrected = TermwiseBound("corrected V ≤ … + c3‖q‖‖q̇‖ + … (c3…c6)",
                                functional, system3, "V", _upper_terms,
                                sum((tb.bound for tb in _upper_terms), sympy.S.Zero), MEASURES, **_common)

lam_c9, k11, lam_skew = sympy.symbols("lam_c9 k11 lam_skew", real=True)


def vdot_terms(measure, *, holder=None):
    """The ten terms of the structured V̇ bounded above as the printed estimate bounds them."""
    return [
        TermBound("−λq̇ᵀBq̇", -lam * c7 * w**2,
                  Rayleigh(v(t), B, factor=-lam, eigenvalue=_ctx_eig("min", B), norm_squared=w**2)),
        TermBound("q̇ᵀAq̇", c8 * w**2, Rayleigh(v(t), A, eigenvalue=_ctx_eig("max", A), norm_squared=w**2)),
        TermBound("−λq̇ᵀ∂Π/∂q", lam_c9 * w * e**mu, Template("lam_c9", {"w": 1, "e": 3})),
        TermBound("−λq̇ᵀ∫∂Π̃/∂q dξ", lam * c10 * w * K,
                  CauchySchwarz(v(t), J_int, (measured(W_), gradient_tree(measure, holder=holder)), factor=-lam)),
        TermBound("−λq̇ᵀP(q)q", lam * p0 * w * e**sigma, Template("lam_skew", {"w": 1, "e": 3})),
        TermBound("−qᵀ(∂Π/∂q+τ∂Π̃/∂q)", k11 * e ** (mu + 1), Template("k11", {"e": 4})),
        TermBound("−q̇ᵀ∫(ξ−t+τ)∂Π̃/∂q dξ", c12 * tau * w * K,
                  CauchySchwarz(v(t), K_int, (measured(W_), gradient_tree(measure, weight=xi - t + tau,
                                                                          holder=holder)), factor=-1)),
        TermBound("−β∫‖q(ξ)‖^{μ+1}dξ", -beta * I, Equal(-beta * I)),
        TermBound("(α+βτ)‖q‖^{μ+1}", (alpha + beta * tau) * e ** (mu + 1), Equal((alpha + beta * tau) * e ** (mu + 1))),
        TermBound("−α‖q(t−τ)‖^{μ+1}", -alpha * d ** (mu + 1), Equal(-alpha * d ** (mu + 1))),
    ]


_vdot_terms = vdot_terms(K_)
#: V̇ ≤ −(λc7 − c8)‖q̇‖² + λ‖q̇‖(c9‖q‖^μ + c10∫‖q‖^μ + p0‖q‖^σ) − c11‖q‖^{μ+1} + c12τ‖q̇‖∫‖q‖^μ − …
vdot = TermwiseBound("printed V̇ ≤ … (c7…c12)", functional, system3, "Vdot", _vdot_terms,
                     sum((tb.bound for tb in _vdot_terms), sympy.S.Zero), MEASURES, derivation=derivation, **_common)

#: the proof's free parameters for this check (every step holds for all λ, α, β > 0; λ enters the templates)
CHECK_VALUES = {"lam": "10", "alpha": "1/10", "beta": "1/10"}


def _steps(values):
    values = {**P3.resolve(CHECK_VALUES, use_defaults=False), **values}
    out = []
    for step in (lower, upper_printed, upper_corrected, vdot):
        out += step.check(values, budget=30).results()
    return out


theorem1_bound = Check("theorem1_bound", parameters=P3, checks=[_steps], paper=PAPER,
                       relevant=("A", "B", "tau", "mu", "sigma", "p0", "pi40", "pi31", "pi22", "pi13", "pi04", "kappa_t",
                                 "p11", "p12", "p22", "lam", "alpha", "beta"),
                       title="The printed estimates with c1…c12 of Theorem 1's proof (paper 002): V's two-sided "
                             "bounds (c3‖q̇‖‖q̇‖ refuted, c3‖q‖‖q̇‖ proved) and the V̇ bound")
