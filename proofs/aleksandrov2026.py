"""Aleksandrov (2026), Avtomatika i Telemekhanika — paper 000.

"Control of the triaxial orientation of a rigid body with delay in the
feedback", section 3: a delayed essentially nonlinear restoring torque.

Euler (1) and Poisson (2) for the inertial unit vectors s1, s2, s3 (an
orthonormal right-handed triad in body axes):

    (2)  ṡᵢ = −ω × sᵢ,  i = 1, 2, 3,
    (5)  L = α1 s1×r1 + α2 s2×r2,      f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²),
    (7)  Θω̇ + ω×(Θω) = −f^ν(t−τ) L(t−τ) − Dω.

Theorem 1: for every τ > 0 the equilibrium (3) ω = 0, sᵢ = rᵢ is
asymptotically stable.  Functional (9) (printed with the label (1)):

    V = f + (γ/2)ωᵀΘω + LᵀD⁻¹Θω + ∫_{t−τ}^t (λ(ξ+τ−t)+μ) W(ξ) dξ − LᵀD⁻¹ ∫_{t−τ}^t f^ν(ξ)L(ξ) dξ,
    W = ‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}.

The paper then prints V̇ along (2),(7).  That print is entered below exactly as
printed, term by term; the one liberty is its ``ω^⊤(t) L^⊤(t−τ)``, a row times
a row, read as the scalar product ωᵀL(t−τ).  Whatever the comparison with the
derivation finds is the result.

Defaults are the example of section 5: A = 20, B = 25, C = 35,
r1 = (1/√2, 1/√2, 0), r2 = (−1/√2, 1/√2, 0), r3 = (0, 0, 1), α1 = α2 = 1,
ν = 0.3, D = 2I, τ = 1.
"""

from lkverify import (Equation, Frame, Functional, Parameters, System, Term, Vector, cross, dot, memory_integral,
                      norm_power, norm_squared, quad, t, window_integral, xi)
from lkverify.symbolic.claims import DerivativeClaim, Hypothesis, MatrixHypothesis
from lkverify.catalogue.items import Theorem

PAPER = "aleksandrov2026"

P = Parameters()
Theta = P.diagonal_matrix("Theta", ["A", "B", "C"], default="diag(20,25,35)", latex=r"\Theta")
D = P.spd_matrix("D", 3, default="diag(2,2,2)", description="damping matrix, constant PD")
alpha1 = P.scalar("alpha1", positive=True, default=1, latex=r"\alpha_1")
alpha2 = P.scalar("alpha2", positive=True, default=1, latex=r"\alpha_2")
nu = P.scalar("nu", positive=True, default="0.3", latex=r"\nu")
tau = P.delay("tau", default=1)
r1 = P.unit_vector("r1", default="[1/sqrt(2), 1/sqrt(2), 0]")
r2 = P.unit_vector("r2", default="[-1/sqrt(2), 1/sqrt(2), 0]")
r3 = P.unit_vector("r3", default="[0, 0, 1]")
P.orthonormal("r1", "r2", "r3")
# parameters of the functional (9)
gamma = P.scalar("gamma", positive=True, latex=r"\gamma")
lam = P.scalar("lam", positive=True, latex=r"\lambda")
mu = P.scalar("mu", positive=True, latex=r"\mu")

omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))


def L(time):
    """(5) L = α1 s1×r1 + α2 s2×r2."""
    return alpha1 * cross(s1(time), r1) + alpha2 * cross(s2(time), r2)


def f(time):
    """f = ½(α1‖s1−r1‖² + α2‖s2−r2‖²)."""
    return (alpha1 * norm_squared(s1(time) - r1) + alpha2 * norm_squared(s2(time) - r2)) / 2


def W(time):
    """‖s1−r1‖^{2ν+2} + ‖s2−r2‖^{2ν+2}."""
    return norm_power(s1(time) - r1, 2 * nu + 2) + norm_power(s2(time) - r2, 2 * nu + 2)


D_inv = D.inv()

# (2), (7)
system = System([
    Equation(omega, [
        Term(-cross(omega(t), Theta * omega(t)), text="−ω×(Θω)", latex=r"-\omega\times(\Theta\omega)"),
        Term(-f(t - tau) ** nu * L(t - tau), text="−f^ν(t−τ)L(t−τ)", latex=r"-f^\nu(t-\tau)L(t-\tau)"),
        Term(-D * omega(t), text="−Dω", latex=r"-D\omega"),
    ], mass=Theta, mass_text="Θ", mass_latex=r"\Theta"),
    *[Equation(si, [Term(-cross(omega(t), si(t)), text=f"−ω×{si.name}", latex=rf"-\omega\times {si.latex}")])
      for si in (s1, s2, s3)],
], parameters=P, name="(2),(7)")

int_fL = window_integral(f(xi) ** nu * L(xi), tau)  # ∫_{t−τ}^t f^ν(ξ)L(ξ)dξ

# (9)
functional = Functional([
    Term(f(t), text="f", latex="f"),
    Term(gamma / 2 * quad(omega(t), Theta), text="(γ/2)ωᵀΘω", latex=r"\frac{\gamma}{2}\omega^\top\Theta\omega"),
    Term(quad(L(t), D_inv * Theta, omega(t)), text="LᵀD⁻¹Θω", latex=r"L^\top D^{-1}\Theta\omega"),
    Term(window_integral(W(xi), tau, weight=lam * (xi + tau - t) + mu), text="∫(λ(ξ+τ−t)+μ)(‖s1−r1‖^{2ν+2}+‖s2−r2‖^{2ν+2})dξ",
         latex=r"\int_{t-\tau}^t(\lambda(\xi+\tau-t)+\mu)(\|s_1-r_1\|^{2\nu+2}+\|s_2-r_2\|^{2\nu+2})d\xi"),
    Term(-quad(L(t), D_inv, int_fL), text="−LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ", latex=r"-L^\top D^{-1}\int_{t-\tau}^t f^\nu(\xi)L(\xi)d\xi"),
], name="(9)")

M = alpha1 * cross(cross(omega(t), s1(t)), r1) + alpha2 * cross(cross(omega(t), s2(t)), r2)

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

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: delayed nonlinear restoring torque, stable for every τ > 0 (printed V̇ checked)",
    system=system,
    functional=functional,
    hypotheses=[Hypothesis("tau > 0", tau), Hypothesis("nu > 0", nu),
                Hypothesis("alpha1 > 0", alpha1), Hypothesis("alpha2 > 0", alpha2)],
    claims=[DerivativeClaim("Vdot_printed", functional, system, printed_Vdot,
                            description="the printed V̇ along (2),(7), as printed")],
    unchecked=["the bounds with c1…c10, inequality (10) and the estimates (11), (12)"],
)


# ---------------------------------------------------------------------------------------------
# Section 4: the nonlinear PID (8), (13), with the scalar kernel G(ζ) = g(ζ)·I (Remark 3).
beta = P.scalar("beta", default=1, latex=r"\beta", description="proportional gain β (β ≤ 0 allowed)")
g = P.kernel("g", default="exp(-2*zeta)", description="memory kernel, G(ζ) = g(ζ) I")

system_pid = System([
    Equation(omega, [
        Term(-cross(omega(t), Theta * omega(t)), text="−ω×(Θω)", latex=r"-\omega\times(\Theta\omega)"),
        Term(-beta * f(t) ** nu * L(t), text="−βf^ν L", latex=r"-\beta f^\nu L"),
        Term(-D * omega(t), text="−Dω", latex=r"-D\omega"),
        Term(-memory_integral(f(xi) ** nu * g(t - xi) * L(xi)), text="−∫_0^t f^ν(ξ)G(t−ξ)L(ξ)dξ",
             latex=r"-\int_0^t f^\nu(\xi)G(t-\xi)L(\xi)d\xi"),
    ], mass=Theta, mass_text="Θ", mass_latex=r"\Theta"),
    *[Equation(si, [Term(-cross(omega(t), si(t)), text=f"−ω×{si.name}", latex=rf"-\omega\times {si.latex}")])
      for si in (s1, s2, s3)],
], parameters=P, name="(2),(13)")

# Theorem 2: under Assumptions 1–2 the equilibrium of (2),(13) is asymptotically stable.
# With G = g(ζ)I: Ξ = βI + ∫_0^∞ G = (β + ∫_0^∞ g) I, Assumption 2: ΞD + DΞᵀ ≻ 0;
# Remark 3 reduces it to β + ∫_0^∞ g > 0 (D ≻ 0); Assumption 1 for g = e^{−aζ} holds with σ = 1/a.
import sympy as _sp  # noqa: E402

from lkverify.declare.symbols import zeta as _zeta  # noqa: E402

_int_g = _sp.Integral(g(_zeta), (_zeta, 0, _sp.oo))
_Xi = (beta + _int_g) * _sp.eye(3)

theorem2 = Theorem(
    "theorem2",
    title="Theorem 2: nonlinear PID with a fading-memory kernel; Assumption 2 checked with its margin",
    system=system_pid,
    hypotheses=[MatrixHypothesis("Xi*D + D*Xi^T > 0", _Xi * D + D * _Xi.T, reference="(Assumption 2)"),
                Hypothesis("beta + int g > 0", beta + _int_g, reference="(Remark 3)")],
    unchecked=["Assumption 1 (∫_ζ^∞|G| ≤ σ|G(ζ)|)", "functional (14) and the bounds with c1…c12"],
)

# ---------------------------------------------------------------------------------------------
# Section 5: the example.  t0 = 0, constant initial functions on [−1, 0].
import numpy as np  # noqa: E402

from lkverify.catalogue.examples import Converges, Example, FasterThan, Run, Series, SmootherThan  # noqa: E402

HISTORY = {"omega": [0.3, -0.4, 0.4], "s1": [0, 0, 1], "s2": [2 / np.sqrt(5), 1 / np.sqrt(5), 0],
           "s3": [-1 / np.sqrt(5), 2 / np.sqrt(5), 0]}
R1 = np.array([1, 1, 0]) / np.sqrt(2)
R2 = np.array([-1, 1, 0]) / np.sqrt(2)


def _e1(states):
    return np.linalg.norm(states["s1"] - R1, axis=1)


def _e2(states):
    return np.linalg.norm(states["s2"] - R2, axis=1)


def _distance(states):
    return np.sqrt(_e1(states) ** 2 + _e2(states) ** 2 + np.sum(states["omega"] ** 2, axis=1))


DELAYED, PID = "delayed feedback (7)", "PID (13), G = exp(−2ζ)I"
example = Example(
    "example",
    title="Section 5: delayed restoring torque (Fig. 1) and nonlinear PID (Fig. 2)",
    runs=[Run(DELAYED, system, {}, HISTORY), Run(PID, system_pid, {}, HISTORY)],
    t_end=1000,
    series=[Series("‖s1 − r1‖", _e1), Series("‖s2 − r2‖", _e2)],
    distance=_distance,
    claims=[Converges(DELAYED), Converges(PID), FasterThan(PID, DELAYED, level=1e-2), SmootherThan(PID, DELAYED)],
    ylabel="‖s_i − r_i‖",
    plot_until=400,
)
