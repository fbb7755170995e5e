"""Paper 004: parameters, states, the regressor Y of (1.5), the errors (2.1) and the closed loops.

A rigid body driven by jet torques in principal axes, N(ω, L0) = Mω, θ = (A, B, C):

    (1.3)  Mω̇ + ω × Mω = u,            M = diag(A, B, C)  (unknown to the controller),
    (1.4)  ṡᵢ = −(ω − ω_d) × sᵢ,       i = 1, 2, 3  (the programmed triad in body axes),
    (1.5)  Mω̇_r + ω_r × Mω = Y(ω, ω_r, ω̇_r)θ,
    (2.1)  e = Σ kᵢ sᵢ × cᵢ,  ω_r = ω_d − Λe,  v = ω − ω_r = ω_e + Λe,  ω_e = ω − ω_d.

The target is sᵢ = cᵢ (constant body vectors), ω = ω_d(t).  Along (1.4)
ė = −Σ kᵢ(ω_e × sᵢ) × cᵢ, so ω̇_r = ω̇_d − Λė is a function of the state, as the controller
needs it.

The paper prints no numerical example; the catalogued instance (every value can be changed
with ``--set``):

* inertia M = diag(3, 4, 5) (true; the estimates θ_r start at (2, 2, 2), i.e. a third to
  a half too small);
* kᵢ = 1, 2, 3 (distinct, as (2.1) requires), Λ = 2, K_d = 4I, Γ = 2I (Theorem 1);
* K_p = 10, α = 50, λ_c = 1, λ0 = 2, k0 = 10, λ1 = 1/2 (Theorem 2; α > λ_cσ_M² = 25, and α > 40.28,
  the additional hypothesis of the corrected (3.10′), :mod:`.corrected`);
* cᵢ the body axes; ω_d(t) = (½ sin t, ½ cos(3t/4), ⅓ sin(t/3)) — a bounded motion with
  ω̇_d bounded (Theorem 1's hypothesis), rich enough for persistent excitation (3.5).

The two closed loops are built by :func:`closed_loop1` ((2.7), (2.8)) and
:func:`closed_loop2` ((3.2)–(3.4)); the simulator integrates the same System objects the
identities are proved along.
"""

from __future__ import annotations

import sympy

from lkverify import Equation, Frame, Parameters, System, Term, Vector, cross, t

__all__ = ["PAPER", "P", "M", "A", "B", "C", "k1", "k2", "k3", "Lam", "Kd", "Gamma", "Kp", "alpha", "lam_c",
           "lam0", "k0", "lam1", "delta", "lam", "c1", "c2", "c3", "wd", "wd_dot", "omega", "s1", "s2", "s3", "theta_r", "eps",
           "phi", "G", "theta", "Y", "e", "e_dot", "omega_e", "omega_r", "omega_r_dot", "v", "Y_c",
           "phi_matrix", "G_matrix", "reference_bounded", "system1", "system2", "closed_loop2", "EDOT", "DINV", "frobenius_law", "upper", "composite_laws", "closed_loop1"]

PAPER = "zaremba1997"

P = Parameters()
M = P.diagonal_matrix("M", ["A", "B", "C"], default="diag(3,4,5)", description="true inertia (principal axes)")
A, B, C = (M[i, i] for i in range(3))
k1 = P.scalar("k1", positive=True, default=1, latex="k_1")
k2 = P.scalar("k2", positive=True, default=2, latex="k_2")
k3 = P.scalar("k3", positive=True, default=3, latex="k_3")
Lam = P.scalar("Lam", positive=True, default=2, latex=r"\Lambda", description="Λ > 0 of (2.1)")
Kd = P.spd_matrix("Kd", 3, default="diag(4,4,4)", latex="K_d", description="gain of (2.7)")
Gamma = P.spd_matrix("Gamma", 3, default="diag(2,2,2)", latex=r"\Gamma", description="adaptation gain of (2.8)")
Kp = P.scalar("Kp", positive=True, default=10, latex="K_p", description="K_p of (3.1), (3.2)")
alpha = P.scalar("alpha", positive=True, default=50, latex=r"\alpha", description="α > λ_c σ_M² of (3.2)")
lam_c = P.scalar("lam_c", positive=True, default=1, latex=r"\lambda_c")
lam0 = P.scalar("lam0", positive=True, default=2, latex=r"\lambda_0", description="λ0 of (3.4)")
k0 = P.scalar("k0", positive=True, default=10, latex="k_0", description="k0 ≥ ‖Γ(0)‖ of (3.4)")
lam1 = P.scalar("lam1", positive=True, default="1/2", latex=r"\lambda_1",
                description="λ1 ≤ λ(t) of property (b) of (3.4), in γ of (3.12)")
delta = P.scalar("delta", positive=True, default=25, latex=r"\delta", description="window δ of (3.5)")
c1 = P.unit_vector("c1", default="[1, 0, 0]")
c2 = P.unit_vector("c2", default="[0, 1, 0]")
c3 = P.unit_vector("c3", default="[0, 0, 1]")
P.orthonormal("c1", "c2", "c3")
_wd = [P.coefficient("wd1", default="sin(t)/2", latex=r"\omega_{d1}"),
       P.coefficient("wd2", default="cos(3*t/4)/2", latex=r"\omega_{d2}"),
       P.coefficient("wd3", default="sin(t/3)/3", latex=r"\omega_{d3}")]

#: the forgetting factor λ(t) of (3.4) in the identities: any value it takes (V does not contain λ)
lam = sympy.Symbol("lambda", nonnegative=True)

# states
omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))
theta_r = Vector("theta_r", latex=r"\theta_r", text="θ_r")
eps = Vector("eps", latex=r"\varepsilon", text="ε")
phi = Vector("phi", 9, latex=r"\varphi", text="φ")        # the p × 3 matrix φ, row by row
G = Vector("G", 6, latex=r"\Gamma^{-1}", text="Γ⁻¹")       # the symmetric p × p matrix Γ⁻¹ of (3.4): its upper triangle

theta = sympy.Matrix([A, B, C])
wd = sympy.Matrix([f(t) for f in _wd])
wd_dot = wd.diff(t)


def Y(w, wr, wr_dot):
    """The regressor Y(ω, ω_r, ω̇_r) of (1.5) for principal axes, as printed."""
    return sympy.Matrix([[wr_dot[0], -w[1] * wr[2], wr[1] * w[2]],
                         [w[0] * wr[2], wr_dot[1], -wr[0] * w[2]],
                         [-w[0] * wr[1], wr[0] * w[1], wr_dot[2]]])


def phi_matrix(time=t):
    """φ (p × 3) from the state ``phi``."""
    return sympy.Matrix(3, 3, list(phi(time)))


_UPPER = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))


def G_matrix(time=t):
    """Γ⁻¹ (p × p, symmetric) from the state ``G`` (its upper triangle g11, g12, g13, g22, g23, g33)."""
    g = dict(zip(_UPPER, G(time)))
    return sympy.Matrix(3, 3, lambda i, j: g[(min(i, j), max(i, j))])


def upper(X):
    """The upper triangle of a symmetric 3 × 3 matrix, as the column the state ``G`` stores."""
    return sympy.Matrix([X[i, j] for i, j in _UPPER])


_S = (s1(t), s2(t), s3(t))
_C = (c1, c2, c3)
_K = (k1, k2, k3)

omega_e = omega(t) - wd                                                        # ω_e = ω − ω_d
e = sum((k * cross(s, c) for k, s, c in zip(_K, _S, _C)), sympy.zeros(3, 1))  # (2.1)
#: ė along (1.4), as printed in the proof of Theorem 1
EDOT = -sum((k * cross(cross(omega_e, s), c) for k, s, c in zip(_K, _S, _C)), sympy.zeros(3, 1))
e_dot = EDOT
omega_r = wd - Lam * e                                                         # (2.1)
omega_r_dot = wd_dot - Lam * e_dot
v = omega(t) - omega_r                                                         # (2.1)
#: Y_c of (3.3): Y with ω̇_c = ω̇_r − λ_c v in place of ω̇_r
Y_c = Y(omega(t), omega_r, omega_r_dot - lam_c * v)

_M_r = sympy.diag(*theta_r(t))  # M_r = diag(θ_r): the estimated inertia


def _poisson():
    return [Equation(s, [Term(-cross(omega_e, s(t)), text=f"−(ω − ω_d)×{s.name}",
                              latex=rf"-(\omega-\omega_d)\times {s.latex}")]) for s in (s1, s2, s3)]


def _euler(torques):
    return Equation(omega, [Term(-cross(omega(t), M * omega(t)), text="−ω×Mω", latex=r"-\omega\times M\omega"),
                            *torques], mass=M, mass_text="M", mass_latex="M")


def closed_loop1(sign=-1, *, name="(1.3),(1.4),(2.7),(2.8)"):
    """(1.3), (1.4) with the control (2.7) and the adaptation (2.8) θ̇_r = sign·ΓYᵀv (the paper: sign = −1)."""
    return System([
        _euler([Term(_M_r * omega_r_dot + cross(omega_r, _M_r * omega(t)), text="M_r ω̇_r + ω_r×M_r ω",
                     latex=r"M_r\dot\omega_r+\omega_r\times M_r\omega"),
                Term(-Kd * v, text="−K_d v", latex="-K_d v")]),
        *_poisson(),
        Equation(theta_r, [Term(sign * Gamma * Y(omega(t), omega_r, omega_r_dot).T * v, text="−ΓYᵀv",
                                latex=r"-\Gamma Y^\top v")]),
    ], parameters=P, name=name)


system1 = closed_loop1()


#: 1/det(Γ⁻¹) in the identities' copy of the loop (Γ = adj(Γ⁻¹)·DINV): V̇ is then a polynomial, linear in DINV
DINV = sympy.Symbol("DINV", real=True)


def composite_laws(w, wd_, wd_dot_, e_, e_dot_, th_r, eps_, ph, Gm, Gam, lam_expr):
    """The laws (3.2)–(3.4) as functions of their arguments — one definition for the loop and the identities.

    Parameters
    ----------
    w, wd_, wd_dot_, e_, e_dot_ : 3 × 1
        ω, ω_d, ω̇_d, e and ė (the loop passes the states' expressions, the identities symbols).
    th_r, eps_ : 3 × 1
        θ_r and ε.
    ph, Gm, Gam : 3 × 3
        φ, Γ⁻¹ and Γ.
    lam_expr
        λ(t) of (3.4).

    Returns
    -------
    dict
        ``u`` (3.2), ``theta_r``, ``eps``, ``phi`` (3 × 3), ``G`` (3 × 3): the right-hand sides,
        and ``v``, ``omega_r``, ``Y_c`` (3.3).
    """
    wr = wd_ - Lam * e_                                       # (2.1)
    wr_dot = wd_dot_ - Lam * e_dot_
    vv = w - wr
    Yc = Y(w, wr, wr_dot - lam_c * vv)                        # (3.3): ω̇_c = ω̇_r − λ_c v
    return {
        "u": Yc * th_r - Kp * e_ - alpha * vv,                                                   # (3.2)
        "theta_r": -Gam * Yc.T * vv + lam_c * Gam * ph * eps_,
        "eps": (-lam_c * eps_ - alpha * vv - Kp * e_ + ph.T * Gam * Yc.T * vv - lam_c * ph.T * Gam * ph * eps_),
        "phi": -lam_c * ph + Yc.T,
        "G": lam_c / 2 * (ph * ph.T - lam_expr * Gm),                                             # (3.4)
        "v": vv, "omega_r": wr, "Y_c": Yc,
    }


def closed_loop2(lam_expr=lam, *, det_inverse=None, name="(1.3),(1.4),(3.2)-(3.4)"):
    """(1.3), (1.4) with the composite laws (3.2), (3.3) and the least squares (3.4).

    Parameters
    ----------
    lam_expr : sympy expression
        λ(t) of (3.4).  The identities use the symbol ``λ`` (V of (3.1) does not contain λ,
        so V̇ at a time depends only on the value λ takes then); the simulation passes
        λ0(1 − ‖Γ‖_F/k0) (the Frobenius norm: ‖Γ‖_2 ≤ ‖Γ‖_F, so ‖Γ‖_F ≤ k0 is the stronger
        bound of property (a)).
    det_inverse : sympy expression, optional
        1/det(Γ⁻¹) in Γ = adj(Γ⁻¹)/det(Γ⁻¹); the identities pass the symbol :data:`DINV`
        (reduced afterwards with det(Γ⁻¹)·DINV = 1), the simulation the true reciprocal.
    """
    Gm = G_matrix()
    Gam = Gm.adjugate() * (1 / Gm.det() if det_inverse is None else det_inverse)  # Γ = (Γ⁻¹)⁻¹
    law = composite_laws(omega(t), wd, wd_dot, e, EDOT, theta_r(t), eps(t), phi_matrix(), Gm, Gam, lam_expr)
    return System([
        _euler([Term(law["u"], text="Y_c θ_r − K_p e − αv", latex=r"Y_c\theta_r-K_pe-\alpha v")]),
        *_poisson(),
        Equation(theta_r, [Term(law["theta_r"], text="−ΓY_cᵀv + λ_cΓφε",
                                latex=r"-\Gamma Y_c^\top v+\lambda_c\Gamma\varphi\varepsilon")]),
        Equation(eps, [Term(law["eps"], text="−λ_cε − αv − K_p e + φᵀΓY_cᵀv − λ_cφᵀΓφε",
                            latex=r"-\lambda_c\varepsilon-\alpha v-K_pe+\varphi^\top\Gamma Y_c^\top v"
                                  r"-\lambda_c\varphi^\top\Gamma\varphi\varepsilon")]),
        Equation(phi, [Term(law["phi"].reshape(9, 1), text="−λ_cφ + Y_cᵀ", latex=r"-\lambda_c\varphi+Y_c^\top")]),
        Equation(G, [Term(upper(law["G"]), text="(λ_c/2)(φφᵀ − λΓ⁻¹)",
                          latex=r"\tfrac{\lambda_c}{2}(\varphi\varphi^\top-\lambda\Gamma^{-1})")]),
    ], parameters=P, name=name)


#: the loop of the identities: λ(t) and 1/det(Γ⁻¹) as the symbols λ and DINV
system2 = closed_loop2(lam, det_inverse=DINV)


def frobenius_law():
    """λ(t) = λ0(1 − ‖Γ‖_F/k0) of (3.4) in the state Γ⁻¹ (the simulated law)."""
    Gm = G_matrix()
    Gam = Gm.adjugate() / Gm.det()
    return lam0 * (1 - sympy.sqrt(sum(x ** 2 for x in Gam)) / k0)


def reference_bounded(values) -> tuple:
    """(status, value, detail) of the hypothesis "ω_d, ω̇_d bounded" at the run's values (Theorems 1 and 2)."""
    from lkverify.certify.steps.signals import bounded_in_t
    from lkverify.status import Status

    rows = [(f"{name}{'′' if k else ''}", *bounded_in_t(sympy.diff(sympy.sympify(values[name]), t, k)))
            for name in ("wd1", "wd2", "wd3") for k in (0, 1)]
    status = Status.weakest(st for _, st, _ in rows)
    return status, None, "; ".join(f"{n}: {why}" for n, _, why in rows)
