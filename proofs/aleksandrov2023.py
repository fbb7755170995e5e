"""Aleksandrov & Tikhonov (2023), Avtomatika i Telemekhanika — paper 002.

"Stability analysis of mechanical systems with essentially nonlinear positional
forces in the presence of distributed delay", section 5: monoaxial
stabilization of a rigid body with a distributed-delay torque.

Euler (9) with the control of (12), Poisson (10) for one inertial unit vector s:

    (10)  ṡ = −ω × s,
    (12)  Θω̇ + ω × (Θω) = −Fω − a‖s−r‖^{μ−1} s×r + b ∫_{t−τ}^t ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ,

target (11): s = r, ω = 0.  Theorem 3: μ > 1 and (14) bτ < a imply asymptotic
stability (Remark 3: a = 0, b < 0 is allowed).  The proof's functional is

    V = ½λ ωᵀΘω + ½‖s−r‖² + (s×r)ᵀF⁻¹Θω
        + b (s×r)ᵀF⁻¹ ∫_{t−τ}^t (ξ+τ−t) ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
        + ∫_{t−τ}^t (α + β(ξ+τ−t)) ‖s(ξ)−r‖^{μ+1} dξ,      λ, α, β > 0.

The paper prints only bounds on V̇ (with c5 … c9).  The claim checked here is
the exact V̇ in the structured form those bounds rest on; its key term is
−(a − τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r), which is where (14) enters.

Defaults are the section 6 data of Fig. 6: Θ = diag(5,6,4), r = (1,1,1)/√3,
F = h·I with h = 1, a = 0, b = −1, τ = 1, μ = 2.
"""

import sympy

from lkverify import (Equation, Functional, Parameters, System, Term, UnitVector, Vector, cross, dot,
                      norm_power, norm_squared, quad, t, window_integral, xi)
from lkverify.claims import DerivativeClaim, Hypothesis
from lkverify.items import Theorem

PAPER = "aleksandrov2023"

P = Parameters()
Theta = P.diagonal_matrix("Theta", ["A", "B", "C"], default="diag(5,6,4)", latex=r"\Theta",
                          description="inertia tensor diag(A, B, C)")
F = P.spd_matrix("F", 3, default="diag(1,1,1)", description="damping matrix, F = h·I in section 6")
a = P.scalar("a", nonnegative=True, default=0, description="restoring-torque gain, a ≥ 0")
b = P.scalar("b", default=-1, description="distributed-delay gain")
tau = P.delay("tau", default=1)
mu = P.scalar("mu", positive=True, default=2, latex=r"\mu", description="order of the restoring torque, μ ≥ 1")
r = P.unit_vector("r", default="[1/sqrt(3), 1/sqrt(3), 1/sqrt(3)]", description="target direction in the body")
# parameters of the functional (free: the identity holds for all of them)
lam = P.scalar("lam", positive=True, latex=r"\lambda")
alpha = P.scalar("alpha", positive=True, latex=r"\alpha")
beta = P.scalar("beta", positive=True, latex=r"\beta")

omega = Vector("omega", latex=r"\omega", text="ω")
s = UnitVector("s")


def n(time):
    """‖s(time) − r‖^{μ−1}."""
    return norm_power(s(time) - r, mu - 1)


F_inv = F.inv()

# (10), (12)
system = System([
    Equation(omega, [
        Term(-cross(omega(t), Theta * omega(t)), text="−ω×(Θω)", latex=r"-\omega\times(\Theta\omega)"),
        Term(-F * omega(t), text="−Fω", latex=r"-F\omega"),
        Term(-a * n(t) * cross(s(t), r), text="−a‖s−r‖^{μ−1}s×r", latex=r"-a\|s-r\|^{\mu-1}s\times r"),
        Term(b * window_integral(n(xi) * cross(s(xi), r), tau), text="b∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
             latex=r"b\int_{t-\tau}^{t}\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    ], mass=Theta, mass_text="Θ", mass_latex=r"\Theta"),
    Equation(s, [Term(-cross(omega(t), s(t)), text="−ω×s", latex=r"-\omega\times s")]),
], parameters=P, name="(10),(12)")

J = window_integral(n(xi) * cross(s(xi), r), tau)  # ∫ ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ
K = window_integral(n(xi) * cross(s(xi), r), tau, weight=xi + tau - t)  # ∫ (ξ+τ−t) ‖s(ξ)−r‖^{μ−1} s(ξ)×r dξ

# The functional of the proof of Theorem 3
functional = Functional([
    Term(lam / 2 * quad(omega(t), Theta), text="½λωᵀΘω", latex=r"\tfrac12\lambda\omega^\top\Theta\omega"),
    Term(norm_squared(s(t) - r) / 2, text="½‖s−r‖²", latex=r"\tfrac12\|s-r\|^2"),
    Term(quad(cross(s(t), r), F_inv * Theta, omega(t)), text="(s×r)ᵀF⁻¹Θω", latex=r"(s\times r)^\top F^{-1}\Theta\omega"),
    Term(b * quad(cross(s(t), r), F_inv, K), text="b(s×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"b(s\times r)^\top F^{-1}\int_{t-\tau}^t(\xi+\tau-t)\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term(window_integral(norm_power(s(xi) - r, mu + 1), tau, weight=alpha + beta * (xi + tau - t)),
         text="∫(α+β(ξ+τ−t))‖s(ξ)−r‖^{μ+1}dξ",
         latex=r"\int_{t-\tau}^t(\alpha+\beta(\xi+\tau-t))\|s(\xi)-r\|^{\mu+1}d\xi"),
], name="V of the proof of Theorem 3")

s_x_r = cross(s(t), r)
omega_x_s_x_r = cross(cross(omega(t), s(t)), r)  # (ω×s)×r = −ṡ×r

# V̇ in the structured form on which the bounds with c5…c9 rest.
structured_Vdot = [
    Term(-lam * quad(omega(t), F), text="−λωᵀFω", latex=r"-\lambda\omega^\top F\omega"),
    Term(-lam * a * n(t) * dot(omega(t), s_x_r), text="−λa‖s−r‖^{μ−1}ωᵀ(s×r)",
         latex=r"-\lambda a\|s-r\|^{\mu-1}\omega^\top(s\times r)"),
    Term(lam * b * dot(omega(t), J), text="λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"\lambda b\,\omega^\top\int_{t-\tau}^t\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term(-quad(omega_x_s_x_r, F_inv * Theta, omega(t)), text="−((ω×s)×r)ᵀF⁻¹Θω",
         latex=r"-((\omega\times s)\times r)^\top F^{-1}\Theta\omega"),
    Term(-quad(s_x_r, F_inv, cross(omega(t), Theta * omega(t))), text="−(s×r)ᵀF⁻¹(ω×Θω)",
         latex=r"-(s\times r)^\top F^{-1}(\omega\times\Theta\omega)"),
    Term(-(a - tau * b) * n(t) * quad(s_x_r, F_inv), text="−(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)",
         latex=r"-(a-\tau b)\|s-r\|^{\mu-1}(s\times r)^\top F^{-1}(s\times r)"),
    Term(-b * quad(omega_x_s_x_r, F_inv, K), text="−b((ω×s)×r)ᵀF⁻¹∫(ξ+τ−t)‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ",
         latex=r"-b((\omega\times s)\times r)^\top F^{-1}\int_{t-\tau}^t(\xi+\tau-t)\|s(\xi)-r\|^{\mu-1}s(\xi)\times r\,d\xi"),
    Term((alpha + beta * tau) * norm_power(s(t) - r, mu + 1), text="(α+βτ)‖s−r‖^{μ+1}",
         latex=r"(\alpha+\beta\tau)\|s-r\|^{\mu+1}"),
    Term(-alpha * norm_power(s(t - tau) - r, mu + 1), text="−α‖s(t−τ)−r‖^{μ+1}", latex=r"-\alpha\|s(t-\tau)-r\|^{\mu+1}"),
    Term(-beta * window_integral(norm_power(s(xi) - r, mu + 1), tau), text="−β∫‖s(ξ)−r‖^{μ+1}dξ",
         latex=r"-\beta\int_{t-\tau}^t\|s(\xi)-r\|^{\mu+1}d\xi"),
]

theorem3 = Theorem(
    "theorem3",
    title="Theorem 3: monoaxial stabilization with a distributed-delay torque, μ > 1 and bτ < a",
    system=system,
    functional=functional,
    hypotheses=[
        Hypothesis("mu > 1", mu - 1, reference="(Theorem 3)"),
        Hypothesis("b*tau < a", a - b * tau, reference="(14)"),
    ],
    claims=[DerivativeClaim("Vdot_structured", functional, system, structured_Vdot,
                            description="V̇ along (10),(12) equals the structured form with −(a−τb)‖s−r‖^{μ−1}(s×r)ᵀF⁻¹(s×r)")],
    unchecked=["the bounds on V and V̇ with c1…c9 and the region δ (Young's inequality)"],
)


# ---------------------------------------------------------------------------------------------
# Section 6: numerical examples (Figs. 1–7).  Θ = diag(5,6,4), r = (1,1,1)/√3, F = h·I, constant
# initial functions on [−τ, 0] from the aircraft angles (φ, θ, ψ) = (0.5, 0.6, −0.8), ω = (1,1,1).
import numpy as np  # noqa: E402

from lkverify.example import (Converges, DoesNotConverge, EnvelopeSpec, Example, Run,  # noqa: E402
                              Sensitive, Series)
from lkverify.rigidbody import chi_norm, inertial_vectors_from_angles  # noqa: E402

R_TARGET = np.full(3, 1 / np.sqrt(3))


def initial_history(angles, omega0):
    """Constant history: s from the aircraft angles (default convention of lkverify.rigidbody), ω."""
    return {"s": list(inertial_vectors_from_angles(*angles, R_TARGET)), "omega": list(omega0)}


SECTION6 = initial_history((0.5, 0.6, -0.8), (1.0, 1.0, 1.0))
FIG7 = initial_history((0.8, 0.8, -0.8), (0.1, 0.1, 0.1))


def _s_minus_r(states):
    return np.linalg.norm(states["s"] - R_TARGET, axis=1)


def _distance(states):
    """‖χ(t)‖ = ‖(s − r, ω)‖ in R⁶."""
    return np.sqrt(_s_minus_r(states) ** 2 + np.sum(states["omega"] ** 2, axis=1))


DIRECTION_COSINES = [Series(f"s_{c}", lambda st, i=i: st["s"][:, i]) for i, c in enumerate("xyz")]


def _fig(name, title, values, claims, *, t_end, history=SECTION6, envelope=None, samples=4001):
    return Example(name, title=title, runs=[Run(title, system, values, history)], t_end=t_end,
                   series=DIRECTION_COSINES, distance=_distance, claims=claims, ylabel="direction cosines",
                   envelope=envelope, samples=samples, plot_until=100)


def _F(h):
    return f"diag({h},{h},{h})"


FIG1 = {"F": _F("0.7"), "a": "2", "b": "2", "tau": "0.9", "mu": "1"}
fig1 = _fig("fig1", "Fig. 1: b = 2, μ = 1", FIG1, [Converges("Fig. 1: b = 2, μ = 1")], t_end=100)
fig2 = _fig("fig2", "Fig. 2: b = −2, μ = 1", {**FIG1, "b": "-2"},
            [DoesNotConverge("Fig. 2: b = −2, μ = 1", floor=0.05)], t_end=100)
fig3 = _fig("fig3", "Fig. 3: b = −2, μ = 2", {**FIG1, "b": "-2", "mu": "2"},
            [Converges("Fig. 3: b = −2, μ = 2")], t_end=1000)
FIG4 = {"F": _F("0.2"), "a": "0.6", "b": "-0.6", "tau": "0.9", "mu": "1"}
fig4 = _fig("fig4", "Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1", FIG4,
            [DoesNotConverge("Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1", floor=0.05),
             Sensitive("Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1")], t_end=200)
fig5 = _fig("fig5", "Fig. 5: a = 0.6, h = 0.2, b = −0.6, μ = 2", {**FIG4, "mu": "2"},
            [Converges("Fig. 5: a = 0.6, h = 0.2, b = −0.6, μ = 2", tol=1e-3)], t_end=1000)
FIG6 = {"F": _F("1"), "a": "0", "b": "-1", "tau": "1", "mu": "2"}
fig6 = _fig("fig6", "Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2", FIG6,
            [Converges("Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2")], t_end=1000)

# Estimate (15) as printed: ‖s(t) − r‖ ≤ 9.21‖χ‖_τ (1 + 0.23‖χ‖_τ (t − t0))^{−1} for ‖χ‖_τ < 0.28.
PRINTED_15 = {"d1": 9.21, "d2": 7.44, "d3": 0.23, "delta_tilde": 0.28}


def _chi(run):
    """‖χ‖_τ of a constant history: the uniform norm of (s − r, ω) in R⁶ (lkverify.rigidbody.chi_norm)."""
    s = np.asarray(run.history["s"], dtype=float)
    w = np.asarray(run.history["omega"], dtype=float)
    return float(chi_norm(s - R_TARGET, w))


fig7 = _fig("fig7", "Fig. 7: Fig. 6 gains, (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1)", FIG6,
            [Converges("Fig. 7: Fig. 6 gains, (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1)")],
            t_end=1500, history=FIG7,
            envelope=EnvelopeSpec("(15) as printed: 9.21‖χ‖_τ/(1 + 0.23‖χ‖_τ t)",
                                  Series("‖s − r‖", _s_minus_r),
                                  lambda tt, chi: PRINTED_15["d1"] * chi / (1 + PRINTED_15["d3"] * chi * tt),
                                  _chi, "Fig. 7: Fig. 6 gains, (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1)"))
