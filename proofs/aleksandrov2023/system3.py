"""System (3) of paper 002 (section 3) for a catalogued instance, n = 2, μ = 3.

    (3)  A q̈ + B q̇ + ∂Π/∂q(q(t)) + P(q(t)) q(t) + ∫_{t−τ}^t ∂Π̃/∂q(q(ξ)) dξ = 0,

A, B symmetric positive definite, Π and Π̃ homogeneous of order μ + 1 > 2, P(q) skew with
(4) ‖P(q)‖ ≤ p0‖q‖^{σ−1}.  Written as a first-order system in q and v = q̇:

    q̇ = v,      A v̇ = −B v − ∂Π/∂q(q) − P(q) q − ∫_{t−τ}^t ∂Π̃/∂q(q(ξ)) dξ.

The instance (every coefficient a parameter, overridable with ``--set``):

* Π(q) = π40 q1⁴ + π31 q1³q2 + π22 q1²q2² + π13 q1q2³ + π04 q2⁴, a general quartic form;
  default Π = ¼q1⁴ + ½q1³q2 − ⅛q2⁴, which is **not** positive definite (Remark 1: the
  potential need not be);
* Π̃(q) = (κ̃/4)‖q‖⁴, κ̃ > 0 (∂Π̃/∂q = κ̃‖q‖²q); default κ̃ = 1, so that with τ = 1
  Π + τΠ̃ = ½q1⁴ + ½q1³q2 + ½q1²q2² + ⅛q2⁴ is positive definite (certified on the circle);
* P(q) = φ(q)·[[0, 1], [−1, 0]] with φ(q) = p11 q1² + p12 q1q2 + p22 q2², so σ = 3 and
  ‖P(q)‖ = |φ(q)| ≤ p0‖q‖²; defaults φ = q1² + ½q1q2, p0 = 11/10;
* A = [[2, 1], [1, 2]], B = [[3, 1], [1, 2]], τ = 1, μ = 3, σ = 3.

μ and σ are parameters so that the hypotheses can be tried at other values
(``--set mu=…``, ``--set sigma=…``); the forms of the instance fix their degrees, and the
hypotheses check that they agree (:mod:`.theorem1_hypotheses`).
"""

import sympy

from lkverify import Equation, Parameters, System, Term, Vector, norm_squared, t, window_integral, xi

__all__ = ["P3", "A", "B", "tau", "mu", "sigma", "p0", "kappa_t", "lam", "alpha", "beta", "q", "v", "x1", "x2",
           "X", "Pi", "Pi_t", "phi", "J2", "grad", "grad_Pi", "grad_Pi_t", "skew", "system3", "PI_COEFFS",
           "PHI_COEFFS", "delta_q", "delta_v", "eta_w", "eta_K", "eta", "eta_j"]

P3 = Parameters()
A = P3.spd_matrix("A", 2, default="[[2, 1], [1, 2]]", description="inertia matrix A of (3), symmetric, A ≻ 0")
B = P3.spd_matrix("B", 2, default="[[3, 1], [1, 2]]", description="damping matrix B of (3), symmetric, B ≻ 0")
tau = P3.delay("tau", default=1)
mu = P3.scalar("mu", positive=True, default=3, latex=r"\mu", description="Π, Π̃ homogeneous of order μ + 1")
sigma = P3.scalar("sigma", positive=True, default=3, latex=r"\sigma", description="order in (4): ‖P(q)‖ ≤ p0‖q‖^{σ−1}")
p0 = P3.scalar("p0", positive=True, default="11/10", latex="p_0", description="the constant of (4)")
#: Π(q) = Σ π_ij q1^i q2^j (i + j = 4)
PI_COEFFS = {(4, 0): "pi40", (3, 1): "pi31", (2, 2): "pi22", (1, 3): "pi13", (0, 4): "pi04"}
_pi_defaults = {"pi40": "1/4", "pi31": "1/2", "pi22": 0, "pi13": 0, "pi04": "-1/8"}
_pi = {ij: P3.scalar(name, default=_pi_defaults[name], description=f"coefficient of q1^{ij[0]} q2^{ij[1]} in Π")
       for ij, name in PI_COEFFS.items()}
kappa_t = P3.scalar("kappa_t", positive=True, default=1, latex=r"\tilde\kappa",
                    description="Π̃(q) = (κ̃/4)‖q‖⁴")
#: φ(q) = p11 q1² + p12 q1q2 + p22 q2², P(q) = φ(q) J
PHI_COEFFS = {(2, 0): "p11", (1, 1): "p12", (0, 2): "p22"}
_phi_defaults = {"p11": 1, "p12": "1/2", "p22": 0}
_phi = {ij: P3.scalar(name, default=_phi_defaults[name], description=f"coefficient of q1^{ij[0]} q2^{ij[1]} in φ")
        for ij, name in PHI_COEFFS.items()}
def declare_choices(P):
    """The proof's free choices of Theorem 1, declared on the registry ``P``:
    λ, α, β of the functional (П.1) (free: the identity holds for all of them), the region of (П.2),
    (П.3) max_{[t−τ,t]} ‖q(ξ)‖ ≤ δ_q, ‖q̇(t)‖ ≤ δ_v, and the parameters of Young's inequality in the chain.

    >>> names = [s.name for s in declare_choices(Parameters())]
    >>> names[:5], len(names)
    (['lam', 'alpha', 'beta', 'delta_q', 'delta_v'], 9)
    """
    return (P.scalar("lam", positive=True, latex=r"\lambda"),
            P.scalar("alpha", positive=True, latex=r"\alpha"),
            P.scalar("beta", positive=True, latex=r"\beta"),
            P.scalar("delta_q", positive=True, latex=r"\delta_q", description="region: max over the window of ‖q‖"),
            P.scalar("delta_v", positive=True, latex=r"\delta_v", description="region: ‖q̇(t)‖"),
            P.scalar("eta_w", positive=True, latex=r"\eta_w", description="Young: ‖q‖‖q̇‖ in V ≥ L"),
            P.scalar("eta_K", positive=True, latex=r"\eta_K",
                     description="Young: ‖q‖(∫‖q‖^{μ+1})^{μ/(μ+1)} in V ≥ L"),
            P.scalar("eta", positive=True, latex=r"\eta", description="Young: ‖q̇‖‖q‖^μ in V̇ ≤ W"),
            P.scalar("eta_j", positive=True, latex=r"\eta_j",
                     description="Young: ‖q̇‖(∫‖q‖^{μ+1})^{μ/(μ+1)} in V̇ ≤ W"))


lam, alpha, beta, delta_q, delta_v, eta_w, eta_K, eta, eta_j = declare_choices(P3)

q = Vector("q", 2)
v = Vector("v", 2, latex=r"\dot q", text="q̇")

# the forms in plain variables x = (x1, x2)
x1, x2 = sympy.symbols("x1 x2", real=True)
X = (x1, x2)
Pi = sum((c * x1**i * x2**j for (i, j), c in _pi.items()), sympy.S.Zero)
Pi_t = kappa_t / 4 * (x1**2 + x2**2) ** 2
phi = sum((c * x1**i * x2**j for (i, j), c in _phi.items()), sympy.S.Zero)
J2 = sympy.ImmutableMatrix([[0, 1], [-1, 0]])


def grad(form, at):
    """∂form/∂q evaluated at the vector ``at`` (a column of state values)."""
    g = sympy.Matrix([sympy.diff(form, x) for x in X])
    return sympy.ImmutableMatrix(g.xreplace(dict(zip(X, list(at)))))


def grad_Pi(time):
    """∂Π/∂q(q(time))."""
    return grad(Pi, q(time))


def grad_Pi_t(time):
    """∂Π̃/∂q(q(time)) = κ̃‖q‖²q."""
    return sympy.ImmutableMatrix(kappa_t * norm_squared(q(time)) * q(time))


def skew(time):
    """P(q(time)) = φ(q)·J."""
    return sympy.ImmutableMatrix(phi.xreplace(dict(zip(X, list(q(time))))) * J2)


# (3) as q̇ = v, A v̇ = …
system3 = System([
    Equation(q, [Term(v(t), text="q̇", latex=r"\dot q")]),
    Equation(v, [
        Term(-B * v(t), text="−Bq̇", latex=r"-B\dot q"),
        Term(-grad_Pi(t), text="−∂Π/∂q", latex=r"-\partial\Pi/\partial q"),
        Term(-skew(t) * q(t), text="−P(q)q", latex=r"-P(q)q"),
        Term(-window_integral(grad_Pi_t(xi), tau), text="−∫∂Π̃/∂q(q(ξ))dξ",
             latex=r"-\int_{t-\tau}^t\partial\tilde\Pi/\partial q(q(\xi))\,d\xi"),
    ], mass=A, mass_text="A", mass_latex="A"),
], parameters=P3, name="(3)")
