"""Section 1–2 of paper 004: the linear parametrisation (1.5), passivity (1.6), the errors (2.1),
Lemmas 2 and 3.

* (1.5) for principal axes, N = Mω, θ = (A, B, C): the printed Y(ω, ω_r, ω̇_r) is compared with
  ∂(Mω̇_r + ω_r × Mω)/∂θ entry by entry (every vector symbolic; the identity is linear in θ, so
  it holds for every inertia).
* (1.6): ωᵀ(Mω̇ + ω × Mω) = d/dt(½ωᵀMω) along (1.3) (the gyroscopic torque does no work).
* (2.1): v = ω_e + Λe, and ė = −Σkᵢ(ω_e × sᵢ) × cᵢ along (1.4) as printed in the proof of Theorem 1.
* Lemma 2 (2.4): ω_eᵀe = d/dt(−Σkᵢcᵢᵀsᵢ) along (1.4), hence ∫_0^T ω_eᵀe = −Σkᵢcᵢᵀsᵢ|_0^T ≥ −2Σkᵢ
  (|cᵢᵀsᵢ| ≤ 1 for unit vectors).
* Lemma 3 (2.5): the printed ∫ω_e² + ∫e² = ∫v² − 2Λ∫ω_eᵀe is compared with the pointwise identity
  ‖v‖² = ‖ω_e‖² + 2Λω_eᵀe + Λ²‖e‖²: the derivation has Λ²‖e‖² where the print has ‖e‖²
  (equal only for Λ = 1).  The lemma survives: ∫e² ≤ (∫v² + 2Λγ²)/Λ².
"""

from __future__ import annotations

import sympy

from lkverify import Check, Result, Status, cross, dot, t

from lkverify.symbolic.polynomial import compare_polynomials as compare, time_derivative, plain
from .equations import (PAPER, EDOT, P, Lam, M, Y, c1, c2, c3, e, k1, k2, k3, omega, omega_e, s1, s2, s3, system1,
                        theta, v)

__all__ = ["parametrisation", "regressor_results", "lemma_results"]

_w = sympy.Matrix(sympy.symbols("w1:4", real=True))        # ω
_wr = sympy.Matrix(sympy.symbols("wr1:4", real=True))      # ω_r
_wrd = sympy.Matrix(sympy.symbols("wrd1:4", real=True))    # ω̇_r


def regressor_results(Y_printed=Y) -> list:
    """(1.5): the printed Y against ∂(Mω̇_r + ω_r × Mω)/∂θ, row by row (exact or refuted)."""
    lhs = M * _wrd + cross(_wr, M * _w)                     # Mω̇_r + ω_r × N(ω, L0), N = Mω
    Yp = Y_printed(_w, _wr, _wrd)
    out = []
    for i in range(3):
        printed = [(f"Y[{i + 1},{j + 1}]·θ{j + 1}", Yp[i, j] * theta[j]) for j in range(3)]
        derived = [(f"(∂/∂θ{j + 1})·θ{j + 1}", lhs[i].diff(theta[j]) * theta[j]) for j in range(3)]
        out.append(compare(f"(1.5) row {i + 1}: (Yθ)_{i + 1} = (Mω̇_r + ω_r×Mω)_{i + 1}", printed, derived,
                           reference=f"row {i + 1} of the printed Y"))
    return out


def _values_sub(values):
    return P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})


def lemma_results(values) -> list:
    """(1.6), (2.1), ė, Lemma 2 and Lemma 3 at the run's values (states and ω_d symbolic)."""
    sub = _values_sub(values)
    S, Cs, K = (s1(t), s2(t), s3(t)), (c1, c2, c3), (k1, k2, k3)
    out = []
    w = omega(t)
    out.append(compare("(1.6): ωᵀ(ω × Mω) = 0", [("ωᵀ(ω×Mω)", plain(dot(w, cross(w, M * w))))], [("0", 0)],
                       reference="the gyroscopic torque's power"))
    out.append(compare("(2.1): v = ω_e + Λe", [(f"v_{i + 1}", plain((v[i]).xreplace(sub))) for i in range(3)],
                       [(f"(ω_e + Λe)_{i + 1}", plain((omega_e[i] + Lam * e[i]).xreplace(sub))) for i in range(3)],
                       reference="v of (2.1)"))
    for i in range(3):
        out.append(compare(f"ė_{i + 1} = −Σkᵢ((ω_e×sᵢ)×cᵢ)_{i + 1} along (1.4)",
                           [("printed ė", plain(EDOT[i].xreplace(sub)))],
                           [("d/dt e along (1.4)", time_derivative(e[i], system1, sub))],
                           reference="ė as printed in the proof of Theorem 1"))
    W = -sum((k * dot(c, s) for k, s, c in zip(K, S, Cs)), sympy.Integer(0))
    out.append(compare("Lemma 2: ω_eᵀe = d/dt(−Σkᵢcᵢᵀsᵢ) along (1.4)",
                       [("ω_eᵀe", plain(dot(omega_e, e).xreplace(sub)))],
                       [("d/dt(−Σkᵢcᵢᵀsᵢ)", time_derivative(W, system1, sub))],
                       reference="the integrand of (2.4)"))
    gamma2 = 2 * sum(K).xreplace(sub)
    out.append(Result("bound", "Lemma 2: −Σkᵢcᵢᵀsᵢ|_0^T ≥ −γ², γ² = 2Σkᵢ", Status.EXACT, str(gamma2),
                      f"each |cᵢᵀsᵢ(τ)| ≤ 1 (unit vectors, Cauchy–Schwarz) and kᵢ > 0, so "
                      f"−Σkᵢ(cᵢᵀsᵢ(T) − cᵢᵀsᵢ(0)) ≥ −2Σkᵢ = −{gamma2}"))
    we, ee = plain(omega_e.xreplace(sub)), plain(e.xreplace(sub))
    vv, lam = plain(v.xreplace(sub)), Lam.xreplace(sub)
    printed = [("‖ω_e‖²", dot(we, we)), ("‖e‖²", dot(ee, ee))]
    rhs = [("‖v‖²", dot(vv, vv)), ("−2Λω_eᵀe", -2 * lam * dot(we, ee))]
    derived = [("‖ω_e‖²", dot(we, we)),
               ("‖v‖² − 2Λω_eᵀe − ‖ω_e‖² (= Λ²‖e‖²)", dot(vv, vv) - 2 * lam * dot(we, ee) - dot(we, we))]
    out.append(compare("Lemma 3 (2.5) as printed: ‖ω_e‖² + ‖e‖² = ‖v‖² − 2Λω_eᵀe", printed, derived,
                       reference="the integrand of (2.5) as printed"))
    out.append(compare("Lemma 3 (2.5) derived: ‖ω_e‖² + Λ²‖e‖² = ‖v‖² − 2Λω_eᵀe",
                       [("‖ω_e‖²", dot(we, we)), ("Λ²‖e‖²", lam ** 2 * dot(ee, ee))], rhs,
                       reference="the corrected integrand (Λ² on ‖e‖²)"))
    return out


def _check(values):
    return regressor_results() + lemma_results(values)


parametrisation = Check("parametrisation", parameters=P, checks=[_check], paper=PAPER,
                        relevant=("k1", "k2", "k3", "Lam", "c1", "c2", "c3"),
                        title="(1.5) the printed Y term by term; (1.6); (2.1); ė; Lemma 2 (2.4); Lemma 3 (2.5)")
