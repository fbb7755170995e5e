"""Theorem 1 of paper 004: the adaptive control (2.7), (2.8) and its Lyapunov function (2.6).

    (2.6)  V = ½[vᵀMv + θ_eᵀΓ⁻¹θ_e],  θ_e = θ_r − θ,
    (2.7)  u = M_rω̇_r + ω_r × N(ω, L_0r) − K_d v,     M_r = diag(θ_r), N = M_rω,
    (2.8)  θ̇_r = −ΓYᵀ(ω, ω_r, ω̇_r)v,
    (2.9)  V̇ = −vᵀK_d v.

Checked at the run's values (states and ω_d(t) symbolic): the first line of the proof
V̇ = vᵀ(u − ω_r × N − Mω̇_r) + θ_eᵀΓ⁻¹θ̇_e (exact: vᵀ(v × Mω) = 0), and (2.9) (exact; it rests on
(1.5): with a wrong Y it fails).  The hypotheses K_d ≻ 0, Γ ≻ 0, Λ > 0, kᵢ > 0 distinct and
ω_d, ω̇_d bounded (the theorem's L∞ programmed motion) are exact.

The rest of the proof is a signal argument (:func:`argument`, the links of
:mod:`lkverify.certify.steps.signals`, each decided along the closed loop (2.7), (2.8)):

1. (2.9) with K_d ≻ 0: V nonincreasing; V = ½zᵀQz, z = (v, θ_e), Q = diag(M, Γ⁻¹) ≻ 0: v, θ_e bounded;
2. ‖sᵢ‖ conserved by (1.4); ω = v + ω_d − Λe, θ_r = θ_e + θ: every state bounded;
3. vᵀK_dv = −V̇: v ∈ L2; v̇ bounded: v → 0 (Lemma 1 = Barbalat);
4. Lemma 3 as derived, ‖ω_e‖² + Λ²‖e‖² = ‖v‖² − 2Λω_eᵀe, with Lemma 2's ω_eᵀe = d/dt(−Σkᵢcᵢᵀsᵢ): e ∈ L2
   (the printed ‖e‖² in place of Λ²‖e‖² is refuted in ``zaremba1997.parametrisation``); ė bounded:
   e → 0; ω_e = v − Λe → 0;
5. {e = 0} on the orthonormal triads (an invariant set of (1.4)) is four points sᵢ = ±cᵢ (a
   zero-dimensional Gröbner basis, kᵢ distinct): the triad converges to one of them;
6. θ_r and u are polynomials in bounded signals: bounded.

The verdict is computed from these links (:class:`~lkverify.catalogue.signal_theorem.SignalTheorem`).
"""

from __future__ import annotations

import sympy

from lkverify import Result, Status, cross, dot, quad, t
from lkverify.catalogue.signal_theorem import SignalTheorem
from lkverify.certify.matrices import matrix_positive_definite

from lkverify.symbolic.polynomial import compare_polynomials as compare, time_derivative, plain, poly_ring, to_ring
from .equations import (PAPER, Gamma, Kd, Lam, M, P, Y, c1, c2, c3, e, k1, k2, k3, omega, omega_e, omega_r,
                        omega_r_dot, reference_bounded, s1, s2, s3, system1, theta, theta_r, v)

__all__ = ["theorem1", "functional1", "theorem1_results", "hypotheses", "general_result", "argument"]


def _sub(values):
    return P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})


def functional1(values):
    """V of (2.6) at the run's values (Γ⁻¹ of the run's Γ, exact)."""
    sub = _sub(values)
    th_e = theta_r(t) - theta
    Ginv = sympy.Matrix(values["Gamma"]).inv()
    return (quad(v, M) / 2).xreplace(sub) + (th_e.T * Ginv * th_e)[0, 0] / 2


def _pd(matrix, name, reference):
    res = matrix_positive_definite(sympy.Matrix(matrix), name=name)
    return Result("hypothesis", f"{name} ≻ 0 {reference}".strip(), res.status, None, res.detail)


def hypotheses(values) -> list:
    """K_d ≻ 0, Γ ≻ 0, M ≻ 0, Λ > 0 and kᵢ > 0 pairwise distinct (exact)."""
    ks = [values["k1"], values["k2"], values["k3"]]
    distinct = len(set(ks)) == 3 and all(sympy.sympify(k) > 0 for k in ks)
    out = [_pd(values["Kd"], "K_d", "(2.7)"), _pd(values["Gamma"], "Γ", "(2.6), (2.8)"), _pd(values["M"], "M", "(1.3)")]
    out.append(Result("hypothesis", "kᵢ > 0 pairwise distinct (2.1)", Status.EXACT if distinct else Status.FAILED,
                      [str(k) for k in ks], f"k = {', '.join(map(str, ks))}"))
    lam = sympy.sympify(values["Lam"])
    out.append(Result("hypothesis", "Λ > 0 (2.1)", Status.EXACT if lam > 0 else Status.FAILED, str(lam), f"Λ = {lam}"))
    return out


def theorem1_results(values, *, system=system1) -> list:
    """The identities of the proof of Theorem 1 along ``system`` (default: (2.7), (2.8))."""
    sub = _sub(values)
    V = functional1(values)
    Vdot = time_derivative(V, system, sub)
    th_e = theta_r(t) - theta
    Ginv = sympy.Matrix(values["Gamma"]).inv()
    M_r = sympy.diag(*theta_r(t))
    u = M_r * omega_r_dot + cross(omega_r, M_r * omega(t)) - Kd * v                # (2.7)
    theta_r_dot = -Gamma * Y(omega(t), omega_r, omega_r_dot).T * v                  # (2.8)
    first = [("vᵀ(u − ω_r×Mω − Mω̇_r)", plain(dot(v, u - cross(omega_r, M * omega(t)) - M * omega_r_dot).xreplace(sub))),
             ("θ_eᵀΓ⁻¹θ̇_e", plain((th_e.T * Ginv * theta_r_dot.xreplace(sub))[0, 0].xreplace(sub)))]
    return [
        compare("V̇ of (2.6): first line of the proof", first, [("V̇ derived", Vdot)],
                reference="vᵀ(u − ω_r × N − Mω̇_r) + θ_eᵀΓ⁻¹θ̇_e"),
        compare("(2.9): V̇ = −vᵀK_d v", [("−vᵀK_d v", plain(-quad(v, Kd).xreplace(sub)))], [("V̇ derived", Vdot)],
                reference="(2.9)"),
    ]


def general_result():
    """(2.9) for every M = diag(A, B, C), K_d, Γ (symmetric, symbolic) and every ω_r, ω̇_r (exact).

    One level up, as in :class:`~.theorem2.Abstract`: ω, θ_r are the states, ω_r and its rate ω̇_r
    signals (symbols; d/dt of the state function ω_r is the ω̇_r the control uses, by ė of
    ``zaremba1997.parametrisation``); Γ⁻¹ = adj(Γ)·DINV, reduced with det(Γ)·DINV = 1.
    """
    from .theorem2 import _DINV, reduce_det

    w, wr, wrd, th = (sympy.Matrix(sympy.symbols(f"{n}1:4", real=True)) for n in ("w", "wr", "wrd", "th"))
    Mg = sympy.diag(*sympy.symbols("A B C", positive=True))
    sym = lambda n: sympy.Matrix(3, 3, lambda i, j: sympy.Symbol(f"{n}_{min(i, j) + 1}{max(i, j) + 1}", real=True))
    Kg, Gg = sym("Kd"), sym("Gamma")
    vv = w - wr
    th_e = th - sympy.Matrix([Mg[i, i] for i in range(3)])
    M_r = sympy.diag(*th)
    u = M_r * wrd + cross(wr, M_r * w) - Kg * vv                                       # (2.7)
    wdot = Mg.inv() * (-cross(w, Mg * w) + u)                                          # (1.3)
    thdot = -Gg * Y(w, wr, wrd).T * vv                                                 # (2.8)
    V = dot(vv, Mg * vv) / 2 + (th_e.T * Gg.adjugate() * th_e)[0, 0] * _DINV / 2      # (2.6)
    # the mass M of (1.3): ∂V/∂ωᵢ·ω̇ᵢ with ω̇ᵢ = Fᵢ/Mᵢᵢ, the division done exactly term by term
    w_part = [sympy.cancel(V.diff(w[i]) * wdot[i]) for i in range(3)]
    R = poly_ring([V, *w_part, *thdot], extra=[_DINV])
    Vr = to_ring(R, V)
    g = {str(x): x for x in R.gens}
    total = sum((to_ring(R, x) for x in w_part), R.zero)
    for xs, rs, name in ((wr, wrd, "wr"), (th, thdot, "th")):
        for i in range(3):
            total += Vr.diff(g[f"{name}{i + 1}"]) * to_ring(R, rs[i])
    Vdot = reduce_det(total, to_ring(R, Gg.det()))
    return compare("(2.9) for every M = diag(A, B, C), K_d, Γ", [("−vᵀK_d v", -dot(vv, Kg * vv))],
                   [("V̇ derived", Vdot)], reference="(2.9), every parameter symbolic", R=R)


def _hypotheses(values):
    out = hypotheses(values)
    out.append(Result("hypothesis", "ω_d, ω̇_d bounded (the theorem's programmed motion)", *reference_bounded(values)))
    return out


def argument(values):
    """The signal argument of the proof of Theorem 1 at the run's values: (links, reference signals).

    (2.6), (2.9) ⇒ V nonincreasing ⇒ v, θ_e bounded; ‖sᵢ‖ conserved (1.4); so ω = v + ω_d − Λe and
    θ_r = θ_e + θ are bounded; −V̇ = vᵀK_dv ⇒ v ∈ L2; v̇ bounded ⇒ v → 0 (Lemma 1, Barbalat);
    ‖ω_e‖² + Λ²‖e‖² = ‖v‖² − 2Λω_eᵀe with ω_eᵀe = d/dt(−Σkᵢcᵢᵀsᵢ) (Lemmas 2, 3, corrected: Λ² on ‖e‖²)
    ⇒ e ∈ L2; ė bounded ⇒ e → 0; ω_e = v − Λe → 0; e = 0 on the triads is four points ⇒ sᵢ → ±cᵢ;
    θ_r, u bounded.
    """
    from lkverify.certify.steps import (Barbalat, BoundedSignal, BoundedStates, Conserved, Dissipation,
                                        FiniteLimit, LevelSet, LinearLimit, SquareIntegrable)

    V = functional1(values)
    th_e = theta_r(t) - theta
    Ginv = sympy.Matrix(values["Gamma"]).inv()
    Q = sympy.diag(M, Ginv)
    M_r = sympy.diag(*theta_r(t))
    u = M_r * omega_r_dot + cross(omega_r, M_r * omega(t)) - Kd * v                    # (2.7)
    S = (s1(t), s2(t), s3(t))
    Cs, K = (c1, c2, c3), (k1, k2, k3)
    storage = -2 * Lam * sum((k * dot(c, s) for k, s, c in zip(K, S, Cs)), sympy.Integer(0))
    triad = sympy.Matrix.vstack(*S)
    constraints = [dot(S[0], S[0]) - 1, dot(S[1], S[1]) - 1, dot(S[0], S[1]), *(S[2] - cross(S[0], S[1]))]
    links = [
        Dissipation(V, v, Kd, name="(2.9): V̇ = −vᵀK_dv ≤ 0"),
        LevelSet(V, (("v", v), ("θ_e", th_e)), Q),
        *(Conserved(f"s{i + 1}", s) for i, s in enumerate(S)),
        BoundedStates(),
        SquareIntegrable("v", v, Kd, storage=V),
        Barbalat("v"),
        SquareIntegrable("e", e, Lam ** 2 * sympy.eye(3), storage=storage, dominated=(("v", v, sympy.eye(3)),),
                         remainder=((omega_e, sympy.eye(3)),)),
        Barbalat("e"),
        LinearLimit("ω_e", omega_e, {"v": 1, "e": -Lam}),
        FiniteLimit("(s1, s2, s3)", "e", triad, constraints),
        BoundedSignal("θ_r", theta_r(t)),
        BoundedSignal("u", u),
    ]
    return links, {f"wd{i}": values[f"wd{i}"] for i in (1, 2, 3)}


def _identities(values):
    return theorem1_results(values) + [general_result()]


theorem1 = SignalTheorem(
    "theorem1", system=system1, hypotheses=[_hypotheses], derivations=[_identities], argument=argument, paper=PAPER,
    relevant=("M", "k1", "k2", "k3", "Lam", "Kd", "Gamma", "c1", "c2", "c3", "wd1", "wd2", "wd3"),
    conclusion="v → 0, e → 0, ω → ω_d, sᵢ → ±cᵢ, θ_r and u bounded",
    title="Theorem 1: V (2.6) along (1.3), (1.4), (2.7), (2.8): V̇ = −vᵀK_d v (2.9), then bounded signals, "
          "v, e ∈ L2 and Barbalat's lemma: e → 0, ω → ω_d, sᵢ → ±cᵢ")
