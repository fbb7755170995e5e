"""The constants of the proof of Theorem 3 of paper 002 for μ = 2 (the case of estimate (15)).

Derivation of the final inequalities (each step is a standard inequality; the exact V̇ is the
claim ``Vdot_structured`` of :mod:`.theorem3`, proved exact).  Scalar quantities at time t:

    w = ‖ω(t)‖,  e = ‖s(t) − r‖,  j = (∫_{t−τ}^t ‖s(ξ) − r‖³ dξ)^{1/3},  q = s × r,

on the region max_{[t−τ,t]} ‖s(ξ) − r‖ ≤ δ_e, w ≤ δ_w (so e ≤ δ_e, j ≤ τ^{1/3} δ_e):

    ‖q‖² = e²(1 − e²/4) for unit s, r;  ‖q‖ ≤ e;  ‖(ω×s)×r‖ ≤ w;
    ‖J‖ = ‖∫ ‖s(ξ)−r‖ s(ξ)×r dξ‖ ≤ ∫ e² ≤ τ^{1/3} j²  (Hölder);
    ‖K‖ = ‖∫ (ξ+τ−t) ‖s(ξ)−r‖ s(ξ)×r dξ‖ ≤ (τ⁴/4)^{1/3} j²  (Hölder);
    κ1 = sup |qᵀF⁻¹Θω|/(e w),  c_A = sup −((ω×s)×r)ᵀF⁻¹Θω / w²,  c_B = sup |qᵀF⁻¹(ω×Θω)|/(e w²)

over the cap ‖s − r‖ ≤ 2 sin(1/4) and ω ≠ 0 (certified: the templates below, on the chart
:func:`lkverify.certify.bounds.unit_vector_near`).  Then, with θ_min, θ_max the eigenvalues of
Θ, φ_min = λ_min(F), ψ_min = λ_min(F⁻¹):

    V ≥ L = ½λθ_min w² + ½e² − κ1 e w − |b|‖F⁻¹‖k_τ e j² + α j³,
    V ≤ U = ½λθ_max w² + ½e² + κ1 e w + |b|‖F⁻¹‖k_τ e j² + (α + βτ) j³,
    V̇ ≤ W = −(λφ_min − c_A) w² + c_B e w² + λa e² w + (λ|b|τ^{1/3} + |b|‖F⁻¹‖k_τ) w j²
            − (a − τb)ψ_min e³(1 − e²/4) + (α + βτ) e³ − β j³      (using (14): a − τb > 0),

dropping −α‖s(t−τ) − r‖³ ≤ 0.  At t0: w² + e² ≤ ‖χ‖_τ², j ≤ τ^{1/3}‖χ‖_τ.
"""

import numpy as np
import sympy

from lkverify import Result, Status
from lkverify.certify.bounds import unit_vector_angles, unit_vector_near
from lkverify.certify.constants import ConstantsJob, Template
from lkverify.certify.decay import DecayModel
from lkverify.simulate import cross_check, simulate
from lkverify.simulate.rigidbody import chi_norm

from .equations import system
from .section6 import FIG7_HISTORY, PRINTED_15

__all__ = ["THEOREM3_CONSTANTS", "RHO_CAP", "cap_chart", "theorem3_model"]

RHO_CAP = sympy.Rational(1, 2)  # the cap ‖s − r‖ ≤ 2 sin(1/4) ≈ 0.4948 contains every region searched
_rho, _psi, _th, _ph = sympy.symbols("rho psi theta phi", real=True)
_w, _e, _j = sympy.symbols("w e j", nonnegative=True)
_OMEGA = unit_vector_angles(_th, _ph)  # the direction of ω ≠ 0


def cap_chart(v):
    """s on the cap around r (angle ρ ≤ RHO_CAP, azimuth ψ): the chart of lkverify.certify.bounds."""
    return unit_vector_near(v["r"], rho_max=RHO_CAP, rho=_rho, psi=_psi)


def _chart(v):
    """r, s on the cap, a unit ω (θ, φ), and q/e = cos(ρ/2) n×r with n = (s − cos ρ r)/sin ρ."""
    cap = cap_chart(v)
    rv = sympy.Matrix(v["r"])
    n = sympy.cos(_psi) * cap.extras["e1"] + sympy.sin(_psi) * cap.extras["e2"]
    return rv, cap.value, _OMEGA.value, sympy.cos(_rho / 2) * n.cross(rv)


def _box(v):
    """The cap's (ρ, ψ) and the sphere's (θ, φ)."""
    return {**cap_chart(v).region, **_OMEGA.region}


def _box_even(v):
    """For templates even in ω (quadratic forms): ω and −ω give one value, the upper hemisphere suffices."""
    return {**_box(v), _th: (0, sympy.pi / 2)}


def _kappa1(v):
    rv, s_, om, qe = _chart(v)
    return (qe.T * v["F"].inv() * v["Theta"] * om)[0]  # ω → −ω makes the sign irrelevant


def _cA(v):
    rv, s_, om, qe = _chart(v)
    return -(om.cross(s_).cross(rv).T * v["F"].inv() * v["Theta"] * om)[0]


def _cB(v):
    rv, s_, om, qe = _chart(v)
    return (qe.T * v["F"].inv() * om.cross(v["Theta"] * om))[0]  # ψ → ψ + π flips q


def _eig(M):
    ev = [sympy.nsimplify(x) for x in sympy.Matrix(M).eigenvals(multiple=True)]
    return min(ev), max(ev)


def theorem3_model(v, c):
    """The final inequalities L ≤ V ≤ U, V̇ ≤ W above, with the certified κ1, c_A, c_B (``c``)."""
    th_min, th_max = _eig(v["Theta"])
    f_min, f_max = _eig(v["F"])
    a_, b_, tau_ = v["a"], v["b"], v["tau"]
    k_tau = (tau_**4 / 4) ** sympy.Rational(1, 3)
    Finv_norm, psi_min = 1 / f_min, 1 / f_max
    k1, cA_, cB_ = (sympy.Rational(c[n]).limit_denominator(10**9) + sympy.Rational(1, 10**9)
                    for n in ("kappa1", "c_A", "c_B"))

    def build(free):
        lam_, al, be, de, dw = (sympy.nsimplify(free[n]) for n in ("lam", "alpha", "beta", "delta_e", "delta_w"))
        m = lam_ * abs(b_) * tau_ ** sympy.Rational(1, 3) + abs(b_) * Finv_norm * k_tau
        cross = abs(b_) * Finv_norm * k_tau * _e * _j**2
        L = lam_ * th_min / 2 * _w**2 + _e**2 / 2 - k1 * _e * _w - cross + al * _j**3
        U = lam_ * th_max / 2 * _w**2 + _e**2 / 2 + k1 * _e * _w + cross + (al + be * tau_) * _j**3
        W = (-(lam_ * f_min - cA_) * _w**2 + cB_ * _e * _w**2 + lam_ * a_ * _e**2 * _w + m * _w * _j**2
             - (a_ - tau_ * b_) * psi_min * _e**3 * (1 - _e**2 / 4) + (al + be * tau_) * _e**3 - be * _j**3)
        return DecayModel("Theorem 3, μ = 2", (_w, _e, _j), {_w: dw, _e: de, _j: tau_ ** sympy.Rational(1, 3) * de},
                          L, U, W, sympy.Rational(3, 2), (_w, _e), {_j: tau_ ** sympy.Rational(1, 3)},
                          {"d1": _e, "d2": _w}, "d3")

    return build


def _applies(v):
    if v["mu"] != 2:
        return f"the scalar model is derived for μ = 2 (estimate (15)); got μ = {v['mu']}"
    if not v["a"] - v["tau"] * v["b"] > 0:
        return f"(14) bτ < a fails (margin {v['a'] - v['tau'] * v['b']}): the derivation needs it"
    return None


def _objective_paper(est):
    """d1, d2 no worse than printed and d3 no smaller (with a 0.5% margin for certification); then largest δ̃."""
    worst = max(est["d1"] / PRINTED_15["d1"], est["d2"] / PRINTED_15["d2"], PRINTED_15["d3"] / est["d3"])
    return 100 * max(0.0, worst - 0.995) - est["delta_tilde"] / PRINTED_15["delta_tilde"]


def _objective_region(est):
    """Largest δ̃, whatever the other constants (a margin on c̃ keeps V̇ < 0 away from the sampling's blind spots)."""
    return -est["delta_tilde"] + 10 * max(0.0, 0.02 - est["c_tilde"])


def _random_history(rng, rv, chi):
    """A constant history with ‖(s − r, ω)‖ = χ: a random split between ‖s − r‖ and ‖ω‖, random directions."""
    th = rng.uniform(0, np.pi / 2)
    e0, w0 = chi * np.sin(th), chi * np.cos(th)
    ax = rng.normal(size=3)
    ax -= (ax @ rv) * rv
    ax /= np.linalg.norm(ax)
    ang = 2 * np.arcsin(e0 / 2)  # ‖s − r‖ = 2 sin(angle/2)
    s0 = np.cos(ang) * rv + np.sin(ang) * np.cross(ax, rv)
    w = rng.normal(size=3)
    w *= w0 / np.linalg.norm(w)
    return {"s": list(s0), "omega": list(w)}


def _cross_check(v, cert, *, samples=8, t_end=300.0, seed=11):
    """Simulate histories inside the proved region and the Fig. 7 data against the certified envelope."""
    rng = np.random.default_rng(seed)
    rv = np.array([float(x) for x in v["r"]])
    vals = {k: val for k, val in v.items() if k in ("Theta", "F", "a", "b", "tau", "mu", "r")}
    env = {e.name: e for e in cert.envelopes}
    grid = np.linspace(0, t_end, 1501)
    worst = {"d1": 0.0, "d2": 0.0}
    violations = []
    cases = []
    dt = cert.constants["delta_tilde"]
    for k in range(samples):
        cases.append((f"sample {k + 1}", _random_history(rng, rv, dt * 0.999 * rng.uniform(0.5, 1.0))))
    cases.append(("Fig. 7 data", FIG7_HISTORY))
    out = []
    curves = {"d1": {}, "d2": {}}
    for label, hist in cases:
        tr = simulate(system, history=hist, t_end=t_end, values=vals, t_eval=grid)
        e = np.linalg.norm(tr.states["s"] - rv, axis=1)
        wn = np.linalg.norm(tr.states["omega"], axis=1)
        if label in ("sample 1", "sample 2"):
            c = float(chi_norm(np.asarray(hist["s"]) - rv, np.asarray(hist["omega"])))
            name = f"{label} (‖χ‖_τ = {c / dt:.2f} δ̃)"
            curves["d1"][name] = (tr.t, e)
            curves["d2"][name] = (tr.t, wn)
        chi = float(chi_norm(np.asarray(hist["s"]) - rv, np.asarray(hist["omega"])))
        for name, q in (("d1", e), ("d2", wn)):
            chk = cross_check(tr.t, q, env[name](tr.t, chi), name=name)
            if label != "Fig. 7 data":
                worst[name] = max(worst[name], chk.max_ratio)
                if chk.first_violation is not None:
                    violations.append(f"{label} ({name}) at t = {chk.first_violation:.4g}")
            else:
                inside = chi < dt
                out.append(Result("envelope", f"Fig. 7 data vs certified envelope ({name})",
                                  chk.status if inside else Status.SIMULATED,
                                  {"chi": chi, "max_ratio": chk.max_ratio, "first_violation": chk.first_violation,
                                   "inside_proved_region": inside},
                                  f"‖χ‖_τ = {chi:.4g} {'<' if inside else '≥'} δ̃ = {dt:.4g} "
                                  f"({'inside' if inside else 'outside: the estimate does not apply'}); "
                                  f"max trajectory/envelope = {chk.max_ratio:.4g}"))
    # The printed estimate (15) itself, from histories with ‖χ‖_τ just inside its printed region 0.28.
    worst15, viol15 = 0.0, []
    for k in range(samples):
        chi = 0.27
        tr = simulate(system, history=_random_history(rng, rv, chi), t_end=t_end, values=vals, t_eval=grid)
        denom = 1 + PRINTED_15["d3"] * chi * tr.t
        for name, q, d in (("d1", np.linalg.norm(tr.states["s"] - rv, axis=1), PRINTED_15["d1"]),
                           ("d2", np.linalg.norm(tr.states["omega"], axis=1), PRINTED_15["d2"])):
            chk = cross_check(tr.t, q, d * chi / denom, name=name)
            worst15 = max(worst15, chk.max_ratio)
            if chk.first_violation is not None:
                viol15.append(f"sample {k + 1} ({name}) at t = {chk.first_violation:.4g}")
    out.append(Result("envelope", "printed (15) at ‖χ‖_τ = 0.27", Status.FAILED if viol15 else Status.SIMULATED,
                      {"samples": samples, "max_ratio": worst15, "violations": viol15},
                      f"{samples} constant histories with ‖χ‖_τ = 0.27 < 0.28 against the printed constants: largest "
                      f"trajectory/envelope ratio {worst15:.3g}; "
                      + ("violations: " + ", ".join(viol15) if viol15 else "no violation (not a proof: simulated)")))
    status = Status.FAILED if violations else Status.SIMULATED
    out.insert(0, Result("envelope", "histories inside the proved region", status,
                         {"samples": samples, "max_ratio_d1": worst["d1"], "max_ratio_d2": worst["d2"],
                          "violations": violations},
                         f"{samples} constant histories with ‖χ‖_τ < δ̃, t ∈ [0, {t_end:g}]: largest trajectory/"
                         f"envelope ratio {worst['d1']:.3g} for ‖s − r‖ and {worst['d2']:.3g} for ‖ω‖; "
                         + ("violations: " + ", ".join(violations) if violations else "no violation")))
    return out, curves


THEOREM3_CONSTANTS = ConstantsJob(
    templates=[
        Template("kappa1", "|(s×r)ᵀF⁻¹Θω| / (‖s−r‖‖ω‖) on the cap", _kappa1, _box),
        Template("c_A", "−((ω×s)×r)ᵀF⁻¹Θω / ‖ω‖² on the cap", _cA, _box_even),
        Template("c_B", "|(s×r)ᵀF⁻¹(ω×Θω)| / (‖s−r‖‖ω‖²) on the cap", _cB, _box_even),
    ],
    model=theorem3_model,
    free={"lam": (5.0, 40.0), "alpha": (0.001, 0.9), "beta": (0.001, 0.99), "delta_e": (0.005, 0.45),
          "delta_w": (0.005, 1.0)},
    objective={"paper": _objective_paper, "region": _objective_region},
    paper=PRINTED_15,
    applies=_applies,
    cross_check=_cross_check,
    descriptions={"d1": "‖s(t)−r‖ ≤ d1‖χ‖_τ(1 + d3‖χ‖_τ(t−t0))^{−1}:",
                  "d2": "‖ω(t)‖ ≤ d2‖χ‖_τ(1 + d3‖χ‖_τ(t−t0))^{−1}:",
                  "d3": "the rate in (15):", "delta_tilde": "valid for ‖χ‖_τ < δ̃:",
                  "C0": "V(t0) ≤ C0‖χ‖_τ²", "c_tilde": "V̇ ≤ −c̃V^{3/2} on the region",
                  "l_e": "V ≥ l_e‖s−r‖²", "l_w": "V ≥ l_w‖ω‖²"},
)
