"""Corollary 1 of paper 002: the decay estimate of system (3) under the conditions of Theorem 1.

"Using (П.2), (П.3), for ‖q_t‖ < δ the functional satisfies V̇ ≤ −c̃V^{(μ+1)/2}; integrating it":
there are d1, d2, d3, δ̃ > 0 such that for t0 ≥ 0, ‖χ‖_τ < δ̃

    ‖q(t)‖ ≤ d1‖χ‖_τ (1 + d3‖χ‖_τ^{μ−1}(t − t0))^{−1/(μ−1)},
    ‖q̇(t)‖ ≤ d2‖χ‖_τ (1 + d3‖χ‖_τ^{μ−1}(t − t0))^{−1/(μ−1)}.

For the instance of :mod:`.system3` (μ = 3) the checked steps V ≥ L, V ≤ U, V̇ ≤ W of
:mod:`.theorem1_chain` (the same objects as Theorem 1's) form the decay model
V̇ ≤ −c̃V² (p = (μ + 1)/2 = 2), whose constants :func:`lkverify.certify.decay.certify_model`
estimates and certifies in arb on the region: l_e, l_w (V ≥ l_e‖q‖², V ≥ l_w‖q̇‖²), c̃, C0
(V(t0) ≤ C0‖χ‖_τ², with (∫‖q‖⁴)^{1/4} ≤ τ^{1/4}‖χ‖_τ at t0) and δ̃ (the trajectory stays in
the region), hence d1 = (C0/l_e)^{1/2}, d2 = (C0/l_w)^{1/2}, d3 = c̃C0; the exponent
−1/(2(p − 1)) = −1/2 = −1/(μ − 1) and ‖χ‖^{2(p−1)} = ‖χ‖^{μ−1} are those of the corollary.
``lkverify constants aleksandrov2023.corollary1`` also simulates (3) from histories inside
the certified region and compares the trajectories with the certified envelopes.
"""

import numpy as np
import sympy

from lkverify import Result, Status, Theorem
from lkverify.certify.constants import ConstantsJob
from lkverify.certify.steps.chain import Decay

from .equations import PAPER
from .system3 import system3
from .theorem1 import HYPOTHESES
from .theorem1_chain import find_choices, steps, tau_j
from .theorem1_functional import derivation, functional

__all__ = ["DECAY", "COROLLARY1_CONSTANTS", "corollary1", "corollary1_model"]

#: V̇ ≤ −c̃V^{(μ+1)/2} for μ = 3; at t0 (∫‖q‖⁴)^{1/4} ≤ τ^{1/4}‖χ‖_τ
DECAY = Decay(sympy.Integer(2), ("w", "e"), {"j": tau_j}, {"d1": "e", "d2": "w"}, "d3",
              descriptions={"d1": "‖q(t)‖ ≤ d1‖χ‖_τ(1 + d3‖χ‖_τ²(t−t0))^{−1/2}:",
                            "d2": "‖q̇(t)‖ ≤ d2‖χ‖_τ(1 + d3‖χ‖_τ²(t−t0))^{−1/2}:", "d3": "the rate of Corollary 1:",
                            "delta_tilde": "valid for ‖χ‖_τ < δ̃:", "C0": "V(t0) ≤ C0‖χ‖_τ²",
                            "c_tilde": "V̇ ≤ −c̃V² on the region", "l_e": "V ≥ l_e‖q‖²", "l_w": "V ≥ l_w‖q̇‖²"})

def corollary1_model(v, c, *, budget=None, progress=None):
    """Check the chain at the run's choices; ``build(free)`` → the DecayModel with the searched δ_v.

    The right-hand sides of V ≥ L, V ≤ U, V̇ ≤ W do not involve δ_v (no step lowers a power of
    ‖q̇‖ on the region), so the steps checked once hold for every δ_v: only the decay model's box
    ‖q̇‖ ≤ δ_v changes, and the search picks it.  Returns ``(build, results)``; ``build`` is None
    when a step is not proved.
    """
    chosen = {**v, **system3.parameters.resolve(find_choices(v), use_defaults=False)}
    rows, checked = [], {}
    for step in steps:
        if progress:
            progress(f"bound step {step.name} at the choices of Theorem 1")
        res = step.check(chosen, budget=budget)
        rows += res.results()
        checked[step.role] = (step, res)
    if not all(res.status.is_proof for _, res in checked.values()):
        return None, rows

    def build(free):
        at = {**chosen, **{k: sympy.Rational(x) if not isinstance(x, sympy.Basic) else x for k, x in free.items()}}
        return DECAY.model(checked, at)

    return build, rows


def _histories(rng, chi, n):
    """Constant histories (q, q̇) ≡ (q0, v0) with ‖(q0, v0)‖ = χ, random split and directions."""
    out = []
    for _ in range(n):
        th, a, b = rng.uniform(0, np.pi / 2), rng.uniform(0, 2 * np.pi), rng.uniform(0, 2 * np.pi)
        out.append({"q": [chi * np.sin(th) * np.cos(a), chi * np.sin(th) * np.sin(a)],
                    "v": [chi * np.cos(th) * np.cos(b), chi * np.cos(th) * np.sin(b)]})
    return out


def _cross_check(v, cert, *, samples=6, t_end=400.0, seed=3):
    """Simulate (3) from histories inside the certified region against the certified envelopes."""
    from lkverify.simulate import cross_check, simulate

    rng = np.random.default_rng(seed)
    env = {e.name: e for e in cert.envelopes}
    dt = cert.constants["delta_tilde"]
    grid = np.linspace(0, t_end, 2001)
    vals = {k: val for k, val in v.items() if k in system3.parameters.names}
    worst, violations, curves = {"d1": 0.0, "d2": 0.0}, [], {"d1": {}, "d2": {}}
    for k, hist in enumerate(_histories(rng, dt * 0.999, samples)):
        chi = float(np.hypot(np.linalg.norm(hist["q"]), np.linalg.norm(hist["v"])))
        tr = simulate(system3, history=hist, t_end=t_end, values=vals, t_eval=grid)
        for name, x in (("d1", np.linalg.norm(tr.states["q"], axis=1)), ("d2", np.linalg.norm(tr.states["v"], axis=1))):
            chk = cross_check(tr.t, x, env[name](tr.t, chi), name=name)
            worst[name] = max(worst[name], chk.max_ratio)
            if chk.first_violation is not None:
                violations.append(f"sample {k + 1} ({name}) at t = {chk.first_violation:.4g}")
            if k < 2:
                curves[name][f"sample {k + 1}"] = (tr.t, x, chi)
    status = Status.FAILED if violations else Status.SIMULATED
    row = Result("envelope", "histories inside the certified region", status,
                 {"samples": samples, "max_ratio_d1": worst["d1"], "max_ratio_d2": worst["d2"], "violations": violations},
                 f"{samples} constant histories with ‖χ‖_τ = 0.999 δ̃ = {dt * 0.999:.4g}, t ∈ [0, {t_end:g}]: largest "
                 f"trajectory/envelope ratio {worst['d1']:.3g} for ‖q‖ and {worst['d2']:.3g} for ‖q̇‖; "
                 + ("violations: " + ", ".join(violations) if violations else "no violation (simulated, not a proof)"))
    return [row], curves


def _objective(est):
    """The largest δ̃ (a margin on c̃ keeps V̇ < 0 away from the sampling's blind spots)."""
    return -est["delta_tilde"] + 10 * max(0.0, 0.002 - est["c_tilde"])


#: ``lkverify constants aleksandrov2023.corollary1``: the chain at Theorem 1's choices, δ_v searched, the
#: decay certified, then simulations from histories inside the certified region
COROLLARY1_CONSTANTS = ConstantsJob(
    templates=[], model=corollary1_model, steps=True, free={"delta_v": (1e-4, 0.05)},
    objective={"region": _objective}, cross_check=_cross_check, descriptions=DECAY.descriptions,
    applies=lambda v: None if v["mu"] == 3 else f"the instance is of order μ + 1 = 4; got μ = {v['mu']}")

corollary1 = Theorem(
    "corollary1",
    title="Corollary 1: ‖q‖, ‖q̇‖ ≤ d‖χ‖_τ(1 + d3‖χ‖_τ^{μ−1}(t−t0))^{−1/(μ−1)} for (3) (instance n = 2, μ = 3)",
    system=system3,
    functional=functional,
    hypotheses=HYPOTHESES,
    claims=[derivation],
    steps=steps,
    decay=DECAY,
    choices=find_choices,
    constants=COROLLARY1_CONSTANTS,
    paper=PAPER,
)
