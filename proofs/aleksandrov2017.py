"""Aleksandrov & Tikhonov (2017), Vestnik SPbSU — paper 001.

"Attitude stabilization of a rigid body in conditions of decreasing
dissipation".  Euler (1) with the torque (4), Poisson (2) for the inertial unit
vectors s1, s2, s3 (an orthonormal right-handed triad in body axes); here the
linear damping W = ωᵀDω:

    (9)  Jω̇ + ω×Jω = −2h(t)Dω − a1 s1×r1 − a2 s2×r2,      h(t) > 0, h(t) → 0 (5).

Theorem 1 (conditions (10), (11) on h): the equilibrium (3) ω = 0, sᵢ = rᵢ is
asymptotically stable.  Its Lyapunov function

    V = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² + γ h^ν(t) ωᵀJη,   η = a1 s1×r1 + a2 s2×r2,

and the paper prints V̇ along (2),(9) exactly; that print is checked below term
by term (a time-varying coefficient: ḣ enters through ∂/∂t).

Section 6 example: A = 5, B = 6, C = 4, D = diag(4,4,4), a1 = a2 = 1,
h = (1+t)^{−7/8} (converges, oscillations die out near t ≈ 200) and
h = (1+t)^{−8/7} (bounded, not attractive).  The rᵢ are not printed: the
base-frame axes are assumed.
"""

from lkverify import (DerivativeClaim, Equation, Frame, Functional, Hypothesis, Parameters, System, Term, Theorem,
                      Vector, cross, dot, norm_squared, quad, t)

PAPER = "aleksandrov2017"

P = Parameters()
J = P.diagonal_matrix("J", ["A", "B", "C"], default="diag(5,6,4)", latex="J", description="inertia tensor")
D = P.spd_matrix("D", 3, default="diag(4,4,4)", description="damping matrix of W = ωᵀDω")
a1 = P.scalar("a1", positive=True, default=1, latex="a_1")
a2 = P.scalar("a2", positive=True, default=1, latex="a_2")
h = P.coefficient("h", default="(1+t)**(-7/8)", description="vanishing damping factor h(t) > 0, h → 0")
r1 = P.unit_vector("r1", default="[1, 0, 0]")
r2 = P.unit_vector("r2", default="[0, 1, 0]")
r3 = P.unit_vector("r3", default="[0, 0, 1]")
P.orthonormal("r1", "r2", "r3")
# parameters of the Lyapunov function of Theorem 1
gamma = P.scalar("gamma", positive=True, latex=r"\gamma")
nu = P.scalar("nu", positive=True, default=1, latex=r"\nu", description="exponent ν ≥ 1 of conditions (10), (11)")

omega = Vector("omega", latex=r"\omega", text="ω")
s1, s2, s3 = Frame(("s1", "s2", "s3"), latex=("s_1", "s_2", "s_3"))

eta = a1 * cross(s1(t), r1) + a2 * cross(s2(t), r2)  # η

# (2), (9)
system = System([
    Equation(omega, [
        Term(-cross(omega(t), J * omega(t)), text="−ω×Jω", latex=r"-\omega\times J\omega"),
        Term(-2 * h(t) * D * omega(t), text="−2h(t)Dω", latex=r"-2h(t)D\omega"),
        Term(-eta, text="−(a1 s1×r1 + a2 s2×r2)", latex=r"-(a_1 s_1\times r_1 + a_2 s_2\times r_2)"),
    ], mass=J, mass_text="J", mass_latex="J"),
    *[Equation(si, [Term(-cross(omega(t), si(t)), text=f"−ω×{si.name}", latex=rf"-\omega\times {si.latex}")])
      for si in (s1, s2, s3)],
], parameters=P, name="(2),(9)")

# The Lyapunov function of the proof of Theorem 1
functional = Functional([
    Term(quad(omega(t), J) / 2, text="½ωᵀJω", latex=r"\tfrac12\omega^\top J\omega"),
    Term(a1 / 2 * norm_squared(s1(t) - r1), text="(a1/2)‖s1−r1‖²", latex=r"\tfrac{a_1}{2}\|s_1-r_1\|^2"),
    Term(a2 / 2 * norm_squared(s2(t) - r2), text="(a2/2)‖s2−r2‖²", latex=r"\tfrac{a_2}{2}\|s_2-r_2\|^2"),
    Term(gamma * h(t) ** nu * quad(omega(t), J, eta), text="γh^ν(t)ωᵀJη", latex=r"\gamma h^\nu(t)\omega^\top J\eta"),
], name="V of Theorem 1")

M = a1 * cross(cross(omega(t), s1(t)), r1) + a2 * cross(cross(omega(t), s2(t)), r2)
h_dot = h(t).diff(t)

# V̇ as printed in the proof of Theorem 1
printed_Vdot = [
    Term(-2 * h(t) * quad(omega(t), D), text="−2h(t)ωᵀDω", latex=r"-2h(t)\omega^\top D\omega"),
    Term(gamma * nu * h(t) ** (nu - 1) * h_dot * quad(omega(t), J, eta), text="γνh^{ν−1}ḣ ωᵀJη",
         latex=r"\gamma\nu h^{\nu-1}(t)\dot h(t)\omega^\top J\eta"),
    Term(gamma * h(t) ** nu * dot(eta, -cross(omega(t), J * omega(t)) - 2 * h(t) * D * omega(t) - eta),
         text="γh^ν ηᵀ(−ω×Jω − 2h(t)Dω − η)", latex=r"\gamma h^\nu(t)\eta^\top(-\omega\times J\omega-2h(t)D\omega-\eta)"),
    Term(-gamma * h(t) ** nu * quad(omega(t), J, M), text="−γh^ν ωᵀJ(a1(ω×s1)×r1 + a2(ω×s2)×r2)",
         latex=r"-\gamma h^\nu(t)\omega^\top J(a_1(\omega\times s_1)\times r_1+a_2(\omega\times s_2)\times r_2)"),
]

theorem1 = Theorem(
    "theorem1",
    title="Theorem 1: linear damping 2h(t)Dω with h → 0; the printed V̇ checked",
    system=system,
    functional=functional,
    hypotheses=[Hypothesis("nu >= 1", nu - 1, strict=False, reference="(10), (11)")],
    claims=[DerivativeClaim("Vdot_printed", functional, system, printed_Vdot,
                            description="the printed V̇ along (2),(9), as printed")],
    unchecked=["conditions (10), (11) on h", "the bounds with α1…α7 and the region δ2", "Lemma 1"],
)


# ---------------------------------------------------------------------------------------------
# Section 6: the example.  Initial aircraft angles (0.5, 0.5, −0.5), ω = (0.3, 0.3, 0.3).
import numpy as np  # noqa: E402

from lkverify.catalogue.examples import BoundedNotAttractive, Converges, DoesNotConverge, Example, Run, Series  # noqa: E402
from lkverify.simulate.rigidbody import inertial_vectors_from_angles  # noqa: E402

_S0 = inertial_vectors_from_angles(0.5, 0.5, -0.5)  # columns s1, s2, s3 (r_i = base axes)
HISTORY = {"omega": [0.3, 0.3, 0.3], "s1": list(_S0[:, 0]), "s2": list(_S0[:, 1]), "s3": list(_S0[:, 2])}
_E = np.eye(3)


def _e(i):
    return lambda states: np.linalg.norm(states[f"s{i}"] - _E[i - 1], axis=1)


def _distance(states):
    return np.sqrt(sum(_e(i)(states) ** 2 for i in (1, 2, 3)) + np.sum(states["omega"] ** 2, axis=1))


def _energy(states):
    """Ṽ = ½ωᵀJω + ½‖s1−r1‖² + ½‖s2−r2‖² (a1 = a2 = 1), the energy of Remark 2."""
    w = states["omega"]
    return 0.5 * (5 * w[:, 0] ** 2 + 6 * w[:, 1] ** 2 + 4 * w[:, 2] ** 2) + 0.5 * (_e(1)(states) ** 2 + _e(2)(states) ** 2)


CONVERGING, BOUNDED = "h = (1+t)^(−7/8)", "h = (1+t)^(−8/7)"
example = Example(
    "example",
    title="Section 6: decreasing dissipation h = (1+t)^(−β)",
    runs=[Run(CONVERGING, system, {"h": "(1+t)**(-7/8)"}, HISTORY),
          Run(BOUNDED, system, {"h": "(1+t)**(-8/7)"}, HISTORY)],
    t_end=2400,
    series=[Series("ω_x", lambda st: st["omega"][:, 0]), Series("ω_y", lambda st: st["omega"][:, 1]),
            Series("ω_z", lambda st: st["omega"][:, 2])],
    distance=_distance,
    claims=[Converges(CONVERGING, tol=1e-3, by=800),
            BoundedNotAttractive(BOUNDED, _energy, "(1+t)**(-8/7)", bound=3.0),
            DoesNotConverge(BOUNDED, floor=1e-2)],
    ylabel="ω components",
    samples=12001,
    plot_until=600,
)


# ---------------------------------------------------------------------------------------------
# Lemma 1 (= inequality (10) of paper 000): for a1, a2 > 0 and ε ∈ (0, 1) there is δ > 0 with
#   (6)  ‖a1 r1×s1 + a2 r2×s2‖² ≥ ε(a1²‖r1−s1‖² + a2²‖r2−s2‖²)  when ‖s1−r1‖² + ‖s2−r2‖² < δ².
# s_i = R r_i for a rotation R (the triad moves rigidly).  With the unit quaternion (q0, σu),
# σ = sin(φ/2) ∈ [0, 1] for the rotation angle φ ∈ [0, π]:  s_i − r_i = σ Δ_i,
#   Δ_i = 2q0 u×r_i + 2σ u×(u×r_i),  q0 = √(1 − σ²)   (no division: no removable singularity),
# and (6) divided by σ² reads F(σ, u) = ‖Σ a_i r_i×Δ_i‖² − εΣ a_i²‖Δ_i‖² ≥ 0.
# By (8), ‖s_i − r_i‖ = 2|sin χ_i| σ with χ_i the angle between u and r_i, and for orthonormal
# r1, r2: sin²χ1 + sin²χ2 = 2 − (u·r1)² − (u·r2)² ≥ 1, so ‖s1−r1‖² + ‖s2−r2‖² < δ² forces σ < δ/2.
# Hence F ≥ 0 on σ ∈ [0, σ̄] for every u proves the lemma with δ = 2σ̄.
import sympy as _sp  # noqa: E402

from lkverify.certify import bounds as _bounds  # noqa: E402
from lkverify.catalogue.items import Check as _Check  # noqa: E402
from lkverify.report.results import Result as _Result  # noqa: E402
from lkverify.status import Status as _Status  # noqa: E402

_sig, _th, _ph = _sp.symbols("sigma theta phi", real=True)
EPSILONS = (_sp.Rational(1, 2), _sp.Rational(9, 10), _sp.Rational(99, 100))


def lemma1_F(eps, a1_=1, a2_=1, r1_=(1, 0, 0), r2_=(0, 1, 0)):
    """F(σ, θ, φ) of the comment above (u in spherical angles)."""
    u = _sp.Matrix([_sp.sin(_th) * _sp.cos(_ph), _sp.sin(_th) * _sp.sin(_ph), _sp.cos(_th)])
    q0 = _sp.sqrt(1 - _sig**2)
    terms, norms = _sp.zeros(3, 1), 0
    for a, r in ((a1_, _sp.Matrix(r1_)), (a2_, _sp.Matrix(r2_))):
        D = 2 * q0 * u.cross(r) + 2 * _sig * u.cross(u.cross(r))
        terms += a * r.cross(D)
        norms += a**2 * D.dot(D)
    return _sp.expand(terms.dot(terms) - eps * norms)


def _lemma1_sigma_estimate(eps, r1_=(1, 0, 0), r2_=(0, 1, 0), n=121):
    """The first σ where min_u F(σ, u) ≤ 0 (sampled, then bisected): an estimate of σ̄."""
    f = _sp.lambdify((_sig, _th, _ph), lemma1_F(eps, r1_=r1_, r2_=r2_), "numpy")
    T, Ph = np.meshgrid(np.linspace(0, np.pi, n), np.linspace(0, 2 * np.pi, 2 * n))

    def m(s):
        return float(np.min(f(s, T, Ph)))

    lo, hi = 0.0, 0.999
    if m(hi) > 0:
        return hi
    for _ in range(50):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if m(mid) > 0 else (lo, mid)
    return lo


def lemma1_delta(eps, *, budget_seconds=20.0):
    """Certified δ(ε) (a1 = a2 = 1, r_i the base axes) and the sampled estimate of the largest δ."""
    eps = _sp.Rational(eps)
    est = _lemma1_sigma_estimate(float(eps))
    F = lemma1_F(eps)
    sbar = _sp.Rational(est * 0.995).limit_denominator(10**6)
    chk = None
    for _ in range(6):
        box = {_sig: (0, sbar), _th: (0, _sp.pi), _ph: (0, 2 * _sp.pi)}
        chk = _bounds.certify_positive(F, box, name=f"F ≥ 0 for σ ≤ {sbar}", budget_seconds=budget_seconds / 3)
        if chk.status is _Status.CERTIFIED:
            break
        sbar = sbar * _sp.Rational(9, 10)
    return chk, 2 * sbar, 2 * est


def _lemma1_check(v, *, budget=60.0):
    eps_values = [v["eps"]] if v.get("eps") is not None else list(EPSILONS)
    out = []
    from lkverify.errors import InputError

    for eps in eps_values:
        if not (0 < eps < 1):
            raise InputError(f"eps: Lemma 1 needs 0 < ε < 1, got eps={eps}; e.g. --set eps=0.9")
        chk, delta, est = lemma1_delta(eps, budget_seconds=budget / len(eps_values))
        others = [2 * _lemma1_sigma_estimate(float(eps), r1_=R[:, 0], r2_=R[:, 1]) for R in _ROTATED_PAIRS]
        status = _Status.CERTIFIED if chk.status is _Status.CERTIFIED else chk.status
        out.append(_Result("region", f"delta(eps={eps})", status,
                           {"certified": float(delta), "estimate_largest": est, "eps": float(eps),
                            "estimates_other_orthonormal_pairs": others, "boxes": chk.boxes},
                           f"(6) holds when ‖s1−r1‖² + ‖s2−r2‖² < δ² with δ = {float(delta):.6g} (certified: F ≥ 0 "
                           f"on σ ≤ δ/2, {chk.boxes} boxes, {chk.seconds:.1f} s); sampled largest δ ≈ {est:.6g}; "
                           f"other orthonormal r1, r2 give {', '.join(f'{x:.6g}' for x in others)} (the problem is "
                           f"invariant under rotating the pair)"))
    return out


_Q = np.linalg.qr(np.random.default_rng(7).normal(size=(3, 3)))[0]
_ROTATED_PAIRS = (np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]]), _Q)

P.scalar("eps", positive=True, description="ε ∈ (0, 1) of Lemma 1 (unset: 0.5, 0.9 and 0.99)")


class _Lemma1Constants:
    """`lkverify constants aleksandrov2017.lemma1`: certified δ(ε) and the plot of δ(ε)."""

    goals = ["default"]

    def run(self, item_name, values, shown, *, budget=150.0, progress=None, goal=None):
        from lkverify.report.results import Report

        if progress:
            progress(f"{item_name}: certifying δ(ε)")
        results = tuple(_lemma1_check(values, budget=budget))
        bad = [r.name for r in results if not r.status.holds]
        verdict = "certified δ(ε)" if not bad else f"undecided: {', '.join(bad)}"
        return Report(item_name, dict(shown), results, verdict), {"results": results}

    def plot(self, extra, path, *, values=None):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        eps_grid = np.linspace(0.05, 0.99, 40)
        est = [2 * _lemma1_sigma_estimate(e, n=61) for e in eps_grid]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(eps_grid, est, label="largest δ (sampled estimate)")
        pts = [(r.value["eps"], r.value["certified"]) for r in extra["results"] if r.value]
        if pts:
            ax.plot(*zip(*pts), "o", label="certified δ(ε)")
        ax.set_xlabel("ε")
        ax.set_ylabel("δ(ε)")
        ax.set_title("Lemma 1 of paper 001 (a1 = a2 = 1)")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


lemma1 = _Check("lemma1", parameters=P, checks=[_lemma1_check], relevant=("eps",),
                title="Lemma 1: ‖a1 r1×s1 + a2 r2×s2‖² ≥ ε(…) for ‖s−r‖ < δ(ε); certified δ(ε)")
lemma1.constants = _Lemma1Constants()
