"""The vector Lyapunov function of paper 003 per channel, and the comparison system of the saturated loop.

Section 3 of the text: per channel i the state xⁱ = (σᵢ, σ̇ᵢ) of σ̈ᵢ = vᵢ = −k0σᵢ − k1σ̇ᵢ is brought
by the Vandermonde matrix of the spectrum S° to the real Jordan form, xⁱ = T x̃ⁱ, and
Vᵢ = ‖x̃ⁱ‖ = (x̃₁² + x̃₂²)^{1/2}; the vector function V = {Vᵢ} satisfies V̇ = AV, V = exp(A(t − t0))V°.
For S° = {−α ± iβ}: W = [[1, 1], [s₁, s₂]], T = [Re, Im] of its first column = [[1, 0], [−α, β]],
T⁻¹A_cT = [[−α, β], [−β, −α]], so d(Vᵢ²)/dt = −2αVᵢ²: V̇ = AV with A = −αI₃ exactly.

For the closed loop (3), (11) in the coordinates (σ, σ̇): u = SC(D(v − a), a_m) = cD(v − a) with
c = a_m/max(a_m, ‖D(v − a)‖_∞) ∈ (0, 1], so by (8) σ̈ = v + p, p = −(1 − c)(v − a), and

    d(½Vᵢ²)/dt = −αVᵢ² + x̃₂ⁱpᵢ/β          ⇒   V̇ᵢ ≤ −αVᵢ + |pᵢ|/β.

The majorant f̃ (the text's "polynomial type"), each step an identity proved here or a norm rule:

* ‖v − a‖ = ¼(1 + σ²)‖u_lin‖₂, u_lin = D(v − a) (BᵀB = (1 + σ²)²I, :mod:`.kinematics`);
* (1 − c)‖u_lin‖₂ ≤ √3·max(0, ‖u_lin‖₂ − a_m) (‖u‖₂ ≤ √3‖u‖_∞, ‖u‖_∞ ≤ ‖u‖₂), hence
  ‖p‖ ≤ √3·max(0, ‖v‖ + ‖a‖ − a_m/4);
* |σᵢ| = |x̃₁ⁱ| ≤ Vᵢ, |σ̇ᵢ| ≤ √k0·Vᵢ, |vᵢ| ≤ k0Vᵢ (row norms of T and of (k0, k1)T: 1, √k0, k0);
* a = ¼Ḃω (Dσ̇ = ω), Ḃω = −2(σ·σ̇)ω + 2σ̇×ω + 2σ̇(σ·ω) + 2σ(σ̇·ω), ‖ω‖ = 4|σ̇|/(1 + σ²), so
  ‖a‖ ≤ 2|σ̇|²(1 + 3|σ|) ≤ 2k0‖V‖²(1 + 3‖V‖);

so V̇ ≤ AV + f̃(V)·(1, 1, 1), each norm step a checked polynomial inequality with an exact certificate
(:mod:`.norm_steps`; the row's status is the weakest of the steps'), f̃(V) = (√3/β)·g(‖V‖), g(r) = max(0, k0r + 2k0r² + 6k0r³ − a_m/4), and
for the Euclidean norm D⁺‖V‖ ≤ φ(‖V‖) = −α‖V‖ + (3/β)g(‖V‖) (ΣVᵢ ≤ √3‖V‖).  :mod:`.region`
turns φ into the certified region.  The identities and the steps are exact; :func:`sampled_majorant` also
cross-checks the bound ``V̇ᵢ ≤ −αVᵢ + f̃`` at random states of the closed loop (status ``estimated``:
sampled, not a proof; in the tests and the notebook — it compiles the loop, ~3 s).

Text and reconstruction (a finding, ``failed``): the extracted text says that Vᵢ, in the state of
(3), is the square root of a quadratic form in x₁ⁱ = σᵢ and x₂ⁱ = ωᵢ/4 ("4/2 ii ix").  The state of
the channel is x₂ⁱ = σ̇ᵢ = ¼(B(σ)ω)ᵢ, which equals ωᵢ/4 only at σ = 0 (the linearisation): the
difference ¼((B(σ) − I)ω)ᵢ = ¼(−σ²ωᵢ + 2(σ×ω)ᵢ + 2σᵢ(σ·ω)) is reported term by term.
"""

from __future__ import annotations

import numpy as np
import sympy

from lkverify import Check, Result, Status

from .equations import PAPER, P, B, B_rate, D, SC, alpha, beta, k0, k1, u_linear
from .identities import A, OMEGA, SD, SIG, V, matrix_identity
from .norm_steps import chain_status, norm_steps

__all__ = ["comparison", "majorant_steps", "comparison_row", "vandermonde", "jordan_transform", "channel_form", "majorant", "phi", "sampled_majorant"]


def _val(x, v):
    return sympy.sympify(x).subs({alpha: v["alpha"], beta: v["beta"], P["a_m"].obj: v["a_m"]})


def vandermonde(al, be):
    """W = [[1, 1], [s₁, s₂]] on S° = {−α ± iβ} and T = [Re, Im] of its first column."""
    s1, s2 = -al + sympy.I * be, -al - sympy.I * be
    W = sympy.Matrix([[1, 1], [s1, s2]])
    T = sympy.Matrix([[sympy.re(W[0, 0]), sympy.im(W[0, 0])], [sympy.re(W[1, 0]), sympy.im(W[1, 0])]])
    return W, T, (s1, s2)


def jordan_transform(v):
    """T and the channel matrix A_c = [[0, 1], [−k0, −k1]] at the run's values."""
    al, be = sympy.sympify(v["alpha"]), sympy.sympify(v["beta"])
    Ac = sympy.Matrix([[0, 1], [-_val(k0, v), -_val(k1, v)]])
    return vandermonde(al, be)[1], Ac


def channel_form(v):
    """Q = T⁻ᵀT⁻¹: Vᵢ² = xⁱᵀQxⁱ, xⁱ = (σᵢ, σ̇ᵢ)."""
    T, _ = jordan_transform(v)
    Ti = T.inv()
    return Ti.T * Ti


def majorant(v):
    """(g, φ) as polynomials pieces at the run's values: g(r) = k0r + 2k0r² + 6k0r³ − a_m/4 (where > 0)."""
    r = sympy.Symbol("r", nonnegative=True)
    K0, am, al, be = _val(k0, v), sympy.sympify(v["a_m"]), sympy.sympify(v["alpha"]), sympy.sympify(v["beta"])
    g = K0 * r + 2 * K0 * r ** 2 + 6 * K0 * r ** 3 - am / 4
    return r, g, -al * r + 3 * g / be


def phi(v):
    """φ(r) = −αr + (3/β)max(0, g(r)) as a callable on floats (for figures)."""
    r, g, _ = majorant(v)
    gf = sympy.lambdify(r, g)
    al, be = float(v["alpha"]), float(v["beta"])
    return lambda x: -al * x + 3 / be * np.maximum(0.0, gf(x))


def _linear_rows(v) -> list:
    al, be = sympy.sympify(v["alpha"]), sympy.sympify(v["beta"])
    W, T, (s1, s2) = vandermonde(al, be)
    _, Ac = jordan_transform(v)
    rows = [matrix_identity("Vandermonde: W^-1 A_c W = diag(s1, s2)", W.inv() * Ac * W, sympy.diag(s1, s2),
                            text=f"W = [[1, 1], [s₁, s₂]], s₁,₂ = {sympy.sstr(s1)}, {sympy.sstr(s2)}"),
            matrix_identity("real Jordan form: T^-1 A_c T", T.inv() * Ac * T, sympy.Matrix([[-al, be], [-be, -al]]),
                            text=f"T = {sympy.sstr(T)}: T⁻¹A_cT = [[−α, β], [−β, −α]]")]
    # d(½‖x̃‖²)/dt along x̃' = T⁻¹A_cT x̃ (+ T⁻¹e₂ p): −α‖x̃‖² + x̃₂ p/β
    xt = sympy.Matrix(sympy.symbols("xt1:3", real=True))
    p = sympy.Symbol("p", real=True)
    xdot = T.inv() * (Ac * T * xt + sympy.Matrix([0, p]))
    rows.append(matrix_identity("d(V_i^2/2)/dt = -alpha V_i^2 + xt2 p_i/beta", (xt.T * xdot)[0],
                                -al * (xt.T * xt)[0] + xt[1] * p / be,
                                text="along σ̈ᵢ = vᵢ + pᵢ: d(½Vᵢ²)/dt = −αVᵢ² + x̃₂ⁱpᵢ/β; p = 0 (the loop (10)): V̇ = AV, "
                                     f"A = −αI₃ = {sympy.sstr(-al)}·I₃, V(t) = e^(−α(t−t0))V(t0)"))
    Q = channel_form(v)
    rows.append(Result("constant", "channel form Q", Status.EXACT, {"Q": Q, "lambda_max": max(Q.eigenvals())},
                       f"Vᵢ² = xⁱᵀQxⁱ with Q = T⁻ᵀT⁻¹ = {sympy.sstr(Q)} in (σᵢ, σ̇ᵢ); λ_max(Q) = "
                       f"{sympy.sstr(sympy.nsimplify(max(Q.eigenvals())))}"))
    return rows


def _saturated_rows(v) -> list:
    c = sympy.Symbol("c", positive=True)
    s = SIG
    rows = [matrix_identity("(11): sigma'' = v - (1-c)(v-a)", A + B(s) * (c * D(s) * (V - A)) / 4, V - (1 - c) * (V - A),
                            text="with u = SC(D(v − a), a_m) = cD(v − a) (the direction kept, :mod:`.saturation`), "
                                 "σ̈ = a + ¼Bu = v + p, p = −(1 − c)(v − a)")]
    T, _ = jordan_transform(v)
    K0, K1 = _val(k0, v), _val(k1, v)
    norms = {"row norm: sigma_i": (T[0, :], 1), "row norm: sigmadot_i": (T[1, :], K0),
             "row norm: v_i": (sympy.Matrix([[K0, K1]]) * T, K0 ** 2)}
    for name, (row, sq) in norms.items():
        rows.append(matrix_identity(name, (row * row.T)[0], sq, kind="bound",
                                    text=f"the row {sympy.sstr(row)} of xⁱ = Tx̃ⁱ (Cauchy–Schwarz below): its squared norm is "
                                         f"{sympy.sstr(sq)}"))
    sd, w = SD, OMEGA
    terms = (-2 * (s.T * sd)[0] * w + 2 * sd.cross(w) + 2 * sd * (s.T * w)[0] + 2 * s * (sd.T * w)[0])
    rows.append(matrix_identity("B_rate omega: four terms", B_rate(s, sd) * w, terms, kind="bound",
                                text="Ḃω = −2(σ·σ̇)ω + 2σ̇×ω + 2σ̇(σ·ω) + 2σ(σ̇·ω): by the triangle and Cauchy–Schwarz "
                                     "inequalities ‖Ḃω‖ ≤ 2|σ̇|‖ω‖(1 + 3|σ|) (the steps below)"))
    n2 = (s.T * s)[0]
    rows.append(matrix_identity("|D sigmadot|^2 = 16|sigmadot|^2/(1+|sigma|^2)^2", (D(s) * sd).T * (D(s) * sd),
                                sympy.Matrix([16 * (sd.T * sd)[0] / (1 + n2) ** 2]), kind="bound",
                                text="‖ω‖ = ‖D(σ)σ̇‖ = 4|σ̇|/(1 + σ²), so ‖a‖ = ¼‖Ḃω‖ ≤ 2|σ̇|²(1 + 3|σ|)/(1 + σ²)"))
    rows.append(matrix_identity("|v - a| = (1+|sigma|^2)|u_lin|/4", ((B(s) * V / 4).T * (B(s) * V / 4))[0],
                                (1 + n2) ** 2 * (V.T * V)[0] / 16, kind="bound",
                                text="v − a = ¼B(σ)u_lin, ‖B x‖ = (1 + σ²)‖x‖: ‖p‖ = (1 − c)‖v − a‖ ≤ "
                                     "√3·max(0, ‖v‖ + ‖a‖ − a_m/4) (the steps below)"))
    return rows + norm_steps(v, T)


def majorant_steps(v) -> list:
    """Every row the comparison system rests on: the identities and the checked norm steps (no sampling)."""
    return _linear_rows(v) + _saturated_rows(v)


def comparison_row(v, steps) -> Result:
    """The comparison system, with the weakest status of ``steps`` (exact only if every step is)."""
    r, g, ph = majorant(v)
    status, missing = chain_status(steps)
    how = ("every identity and every norm step above is proved (exact)" if not missing
           else f"not proved: {', '.join(missing)}")
    return Result("bound", "comparison system", status, {"g": str(g), "phi": str(sympy.expand(ph)),
                                                         "steps": len(steps), "not_proved": missing},
                  f"V̇ᵢ ≤ −αVᵢ + f̃(V), f̃ = (√3/β)max(0, g(‖V‖)), g(r) = {sympy.sstr(g)}; D⁺‖V‖ ≤ φ(‖V‖) = "
                  f"−αr + (3/β)max(0, g(r)) = {sympy.sstr(sympy.expand(ph))} where g > 0: {how}; the rules "
                  f"x² ≤ y², x, y ≥ 0 ⇒ x ≤ y and X ≤ Y ⇒ max(0, X) ≤ max(0, Y) link the steps")


def _lambdas(v):
    sub = P.substitution({k: x for k, x in v.items() if k in ("alpha", "beta", "a_m")})
    s, w = SIG, OMEGA
    ul = u_linear(s, w).xreplace(sub)
    u = SC(ul, sympy.sympify(v["a_m"]))
    sd = B(s) * w / 4
    sdd = B_rate(s, sd) * w / 4 + B(s) * u / 4
    return sympy.lambdify([*s, *w], [sd, sdd], modules="numpy", cse=True)


def sampled_majorant(v, n=4000, seed=0) -> Result:
    """V̇ᵢ ≤ −αVᵢ + f̃(V) at random closed-loop states (floats: a cross-check, status estimated)."""
    rng = np.random.default_rng(seed)
    T, _ = jordan_transform(v)
    Ti = np.array(T.inv(), dtype=float)
    al, be = float(v["alpha"]), float(v["beta"])
    f = _lambdas(v)
    _, g, _ = majorant(v)
    gf = sympy.lambdify(sympy.Symbol("r", nonnegative=True), g)
    scale = rng.uniform(0, 1, (n, 1)) ** 2
    s = rng.normal(size=(n, 3)) * scale
    w = rng.normal(size=(n, 3)) * scale * np.sqrt(float(_val(k0, v))) * 4
    sd, sdd = (np.stack([np.asarray(c, dtype=float).ravel() * np.ones(n) for c in np.asarray(x, dtype=object).ravel()], 1)
               for x in f(*s.T, *w.T))
    worst = -np.inf
    for i in range(3):
        xt = np.stack([s[:, i], sd[:, i]]) ; xd = np.stack([sd[:, i], sdd[:, i]])
        xt, xd = Ti @ xt, Ti @ xd
        Vi = np.linalg.norm(xt, axis=0)
        Vdot = np.sum(xt * xd, axis=0) / Vi
        Vn = np.linalg.norm(np.stack([np.linalg.norm(Ti @ np.stack([s[:, j], sd[:, j]]), axis=0) for j in range(3)]), axis=0)
        bound = -al * Vi + np.sqrt(3) / be * np.maximum(0, gf(Vn))
        worst = max(worst, float(np.max((Vdot - bound) / (1e-12 + np.abs(bound) + np.abs(Vdot)))))
    ok = worst <= 1e-9
    return Result("bound", "comparison system (sampled)", Status.ESTIMATED if ok else Status.FAILED,
                  {"points": n, "worst_relative_excess": worst},
                  f"V̇ᵢ ≤ −αVᵢ + f̃(V) at {n} random states of (3),(11) (floats; a cross-check, not a proof): worst "
                  f"(V̇ᵢ − bound)/scale = {worst:.3g}")


def _finding_rows() -> list:
    return [matrix_identity("text: x2 = omega/4", B(SIG) * OMEGA / 4, OMEGA / 4,
                            text="finding — the extracted text writes Vᵢ in x₂ⁱ = ωᵢ/4; the channel state is "
                                 "x₂ⁱ = σ̇ᵢ = ¼(B(σ)ω)ᵢ, equal to ωᵢ/4 only at σ = 0; σ̇ − ω/4 = ¼(B(σ) − I)ω")]


def _check(v) -> list:
    steps = majorant_steps(v)
    return steps + [comparison_row(v, steps), sampled_majorant(v, n=1000)] + _finding_rows()


comparison = Check("comparison", parameters=P, checks=[_check], paper=PAPER, relevant=("alpha", "beta", "a_m"),
                   title="Section 3: Vandermonde/real Jordan form per channel, V̇ = AV for (10), V̇ ≤ AV + f̃(V) for (11)")
