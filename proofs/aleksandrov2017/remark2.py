"""Remark 2 of paper 001: for h = (t+1)^{−β} with β > 1 the equilibrium is not attractive.

For the energy

    Ṽ = ½ωᵀJω + (a1/2)‖s1 − r1‖² + (a2/2)‖s2 − r2‖²

the paper states, for all t ≥ 0, ω and admissible s1, s2,

    α̃1(‖ω‖² + ‖s1−r1‖² + ‖s2−r2‖²) ≤ Ṽ ≤ α̃2(…),     −α̃3(t+1)^{−β} Ṽ ≤ dṼ/dt ≤ 0,

hence Ṽ(t) ≥ Ṽ(t0) exp(−α̃3 ∫_{t0}^t (τ+1)^{−β}dτ) ≥ c̃ Ṽ(t0), c̃ > 0 for β > 1.  Here:

* dṼ/dt = −2h(t)ωᵀDω along (2), (9), exact for every h (a DerivativeClaim);
* α̃1 = min(λ_min(J), a1, a2)/2, α̃2 = max(λ_max(J), a1, a2)/2 and α̃3 = 4λ_max(D)/λ_min(J), each
  inequality proved exactly as a matrix inequality (α̃3J/2 − 2D ⪰ 0 gives dṼ/dt + α̃3hṾ ≥ 0);
* c̃ = exp(−α̃3 ∫_{t0}^∞ h) computed exactly for the run's h (β > 1: finite; β ≤ 1: ∫h = ∞ and
  the inequality gives no bound — then Corollary 1 gives attraction);
* the certified lower bound c̃Ṽ(t0) on the limit energy of the section 6 run (β = 8/7), compared
  with the simulated energy and its extrapolated limit (``BoundedNotAttractive``).
"""

from __future__ import annotations

import sympy

from lkverify import Check, DerivativeClaim, Functional, Result, Status, Term, dot, norm_squared, quad, t
from lkverify.certify.matrices import matrix_positive_definite

from .equations import PAPER, D, J, P, a1, a2, h, omega, r1, r2, s1, s2, system
from .example import BOUNDED, HISTORY, example, remark2_energy

__all__ = ["energy", "energy_rate", "remark2", "remark2_constants"]

#: Ṽ of Remark 2
energy = Functional([
    Term(quad(omega(t), J) / 2, text="½ωᵀJω"),
    Term(a1 / 2 * norm_squared(s1(t) - r1), text="(a1/2)‖s1−r1‖²"),
    Term(a2 / 2 * norm_squared(s2(t) - r2), text="(a2/2)‖s2−r2‖²"),
], name="Ṽ")

#: dṼ/dt along (2), (9)
energy_rate = DerivativeClaim("Vtilde_dot", energy, system, [Term(-2 * h(t) * dot(omega(t), D * omega(t)),
                                                                text="−2h(t)ωᵀDω")],
                              description="dṼ/dt along (2),(9) = −2h(t)ωᵀDω")


def remark2_constants(values) -> dict:
    """α̃1, α̃2, α̃3 at resolved values (exact): the eigenvalue bounds of the module docstring.

    Examples
    --------
    >>> remark2_constants(P.resolve({}, use_defaults=True))
    {'alpha1': 1/2, 'alpha2': 3, 'alpha3': 4}
    """
    ej = sympy.Matrix(values["J"]).eigenvals(multiple=True)
    ed = sympy.Matrix(values["D"]).eigenvals(multiple=True)
    A1, A2 = sympy.sympify(values["a1"]), sympy.sympify(values["a2"])
    return {"alpha1": sympy.Min(min(ej), A1, A2) / 2, "alpha2": sympy.Max(max(ej), A1, A2) / 2,
            "alpha3": 4 * max(ed) / min(ej)}


def _psd(M, name):
    res = matrix_positive_definite(sympy.Matrix(M), name=name, semidefinite=True)
    return res.status, res.detail


def _remark2_check(v, *, budget=60.0):
    rows = []
    res = energy_rate.check(P.substitution({k: x for k, x in v.items() if k != "h"}), values=v, budget=budget)
    rows.append(Result("identity", energy_rate.name, res.status, None, f"{energy_rate.description}: {res.detail}"))
    c = remark2_constants(v)
    Jm, Dm, I3 = sympy.Matrix(v["J"]), sympy.Matrix(v["D"]), sympy.eye(3)
    A1, A2 = sympy.sympify(v["a1"]), sympy.sympify(v["a2"])
    # α̃1‖x‖² ≤ Ṽ ≤ α̃2‖x‖²: ½ωᵀ(J − 2α̃1 I)ω + Σ(a_i/2 − α̃1)e_i² ≥ 0 and the same with α̃2
    low = sympy.diag(Jm / 2 - c["alpha1"] * I3, A1 / 2 - c["alpha1"], A2 / 2 - c["alpha1"])
    up = sympy.diag(c["alpha2"] * I3 - Jm / 2, c["alpha2"] - A1 / 2, c["alpha2"] - A2 / 2)
    for name, M, text in (("alpha1 |x|^2 <= Vtilde", low, f"α̃1 = {c['alpha1']}: Ṽ − α̃1(‖ω‖² + e1² + e2²) ⪰ 0"),
                          ("Vtilde <= alpha2 |x|^2", up, f"α̃2 = {c['alpha2']}: α̃2(‖ω‖² + e1² + e2²) − Ṽ ⪰ 0")):
        st, det = _psd(M, name)
        rows.append(Result("bound", name, st, {"value": float(c["alpha1" if "alpha1" in name else "alpha2"])},
                           f"{text} (the form in (ω, e1, e2) is diagonal in blocks): {det}"))
    # −α̃3 h Ṽ ≤ dṼ/dt ≤ 0 (h > 0): α̃3 J/2 − 2D ⪰ 0 (the e_i terms enter with α̃3 a_i/2 ≥ 0) and D ⪰ 0
    st, det = _psd(c["alpha3"] * Jm / 2 - 2 * Dm, "alpha3 J/2 - 2D")
    rows.append(Result("bound", "-alpha3 h Vtilde <= Vtilde_dot", st, {"value": float(c["alpha3"])},
                       f"α̃3 = 4λ_max(D)/λ_min(J) = {c['alpha3']}: dṼ/dt + α̃3hṼ = h[ωᵀ(α̃3J/2 − 2D)ω + "
                       f"α̃3(a1e1² + a2e2²)/2] ≥ 0 since α̃3J/2 − 2D ⪰ 0: {det}"))
    st, det = _psd(Dm, "D")
    rows.append(Result("bound", "Vtilde_dot <= 0", st, None, f"dṼ/dt = −2hωᵀDω ≤ 0 (h > 0, D ⪰ 0): {det}"))
    # c̃ = exp(−α̃3 ∫_0^∞ h): the section 6 damping with β = 8/7, and the run's h if it is another
    bounded = P.resolve({"h": example.runs[1].values["h"]})["h"]  # parsed in lkverify's t
    hs = [bounded] + ([sympy.sympify(v["h"])] if sympy.simplify(sympy.sympify(v["h"]) - bounded) != 0 else [])
    for hv in hs:
        rows += _lower_bound(hv, c["alpha3"], hv == bounded, v)
    return rows


def _lower_bound(hv, alpha3, section6, v) -> list:
    tail = sympy.gammasimp(sympy.integrate(hv, (t, 0, sympy.oo)))
    if tail is sympy.oo or not tail.is_finite:
        return [Result("constant", f"c_tilde (h = {hv})", Status.EXACT, {"tail": "oo"},
                       f"∫_0^∞ h = ∞ for h = {hv}: the energy inequality gives no positive lower bound on lim Ṽ "
                       f"(Corollary 1: the equilibrium is attractive when (10), (11) hold)")]
    ct = sympy.exp(-alpha3 * tail)
    rows = [Result("constant", f"c_tilde (h = {hv})", Status.EXACT, {"value": float(ct), "exact": str(ct),
                                                                       "tail": str(tail)},
                   f"c̃ = exp(−α̃3∫_0^∞ h) = exp(−{alpha3}·{tail}) = {float(ct):.4g} (exact): Ṽ(t) ≥ c̃Ṽ(0) for "
                   f"every t ≥ 0, so the equilibrium is not attractive")]
    if section6:
        rows += _against_simulation(v, ct)
    return rows


def _against_simulation(v, ct) -> list:
    """c̃Ṽ(0) for the section 6 history (β = 8/7) against the simulated energy and its extrapolated limit."""
    sub = P.substitution({k: x for k, x in v.items() if k != "h"})
    state = {c_: sympy.Rational(x) for st in system.states for c_, x in zip(st(t), HISTORY[st.name])}
    V0 = sympy.sympify(energy.expr).xreplace(sub).xreplace(state)  # exact at the (floating-point) history
    lower = sympy.sympify(ct) * V0
    tr = example.simulate()[BOUNDED]
    claim = next(c_ for c_ in example.claims if getattr(c_, "run", None) == BOUNDED and hasattr(c_, "measure"))
    sim = claim.check(example, {BOUNDED: tr})
    ok = sim.value["energy_end"] > float(lower) * (1 + 1e-9)
    return [Result("constant", "limit energy lower bound (section 6, β = 8/7)", Status.CERTIFIED,
                   {"value": float(lower), "V0": float(V0)},
                   f"lim Ṽ ≥ c̃Ṽ(0) = {float(ct):.4g}·{float(V0):.4g} = {float(lower):.3g} (certified: Ṽ(0) of the "
                   f"section 6 history, whose entries are floating point, taken exactly)"),
            Result("simulation", "simulated limit energy (section 6, β = 8/7)",
                   Status.SIMULATED if ok else Status.FAILED,
                   {"energy_end": sim.value["energy_end"], "extrapolated_limit": sim.value["energy_limit_lower"],
                    "certified_lower": float(lower)},
                   f"simulated Ṽ(T = {tr.t[-1]:g}) = {sim.value['energy_end']:.3g}, extrapolated limit ≥ "
                   f"{sim.value['energy_limit_lower']:.3g}: {'above' if ok else 'BELOW'} the certified "
                   f"{float(lower):.3g} (×{sim.value['energy_end'] / float(lower):.3g}: valid, and loose)")]


remark2 = Check("remark2", parameters=P, checks=[_remark2_check], paper=PAPER,
                relevant=("J", "D", "a1", "a2", "h", "r1", "r2"),
                title="Remark 2: for h = (t+1)^(−β), β > 1, the energy keeps c̃Ṽ(0) > 0 (certified c̃, simulated limit)")
