"""The constants of the proof of Theorem 3 of paper 002 for μ = 2 (the case of estimate (15)).

The final inequalities L ≤ V ≤ U, V̇ ≤ W are not typed here: they are the right-hand
sides of the bound steps of :mod:`.theorem3_chain`, checked term by term against the
functional and the exact V̇ (every rule application matched, its side conditions
decided, the template constants κ1, c_A, c_B certified over the cap).  The job checks
the steps once with λ, α, β symbolic (so they hold for all positive values) on the
largest region of the search (δ_e, δ_w at the top of their ranges: a step proved on a
region holds on every smaller one), then searches λ, α, β, δ_e, δ_w for the best
certified estimate (15) (:mod:`lkverify.certify.decay`).
"""

import numpy as np
import sympy

from lkverify import Result, Status
from lkverify.certify.constants import ConstantsJob
from lkverify.simulate import cross_check, simulate
from lkverify.simulate.rigidbody import chi_norm

from .equations import system
from .section6 import FIG7_HISTORY, PRINTED_15, PRINTED_15_STATED, at_printed_15
from .theorem3_chain import DECAY, MEASURES, REGION, RHO_CAP

__all__ = ["THEOREM3_CONSTANTS", "FREE", "WIDER", "theorem3_model"]

#: the search ranges of the proof's free parameters (the region stays inside the cap of the templates)
FREE = {"lam": (5.0, 40.0), "alpha": (0.001, 0.9), "beta": (0.001, 0.99), "delta_e": (0.005, 0.45),
        "delta_w": (0.005, 1.0)}
#: searched when FREE holds no feasible point: Fig. 5 (F = 0.2I) needs λ ≈ 370, Fig. 3 a region δ_e < 0.005
WIDER = {"lam": (1.0, 1000.0), "alpha": (0.001, 0.9), "beta": (0.001, 0.99), "delta_e": (0.0001, 0.45),
         "delta_w": (0.0001, 1.0)}


def theorem3_model(v, c, *, budget=None, progress=None):
    """Check the chain of :mod:`.theorem3_chain` on the largest searched region; ``build(free)`` → DecayModel.

    Returns ``(build, results)``; ``build`` is None when a step is not proved.
    """
    from .theorem3_functional import steps

    top = {k: sympy.Rational(hi).limit_denominator(1000) for k, (lo, hi) in FREE.items() if k.startswith("delta")}
    values = {**v, **top}
    rows, checked = [], {}
    for step in steps:
        if progress:
            progress(f"bound step {step.name} (λ, α, β symbolic; region δ_e ≤ {top['delta_e']}, δ_w ≤ {top['delta_w']})")
        res = step.check(values, budget=budget)
        rows += res.results()
        checked[step.role] = (step, res)
    if not all(res.status.is_proof for _, res in checked.values()):
        return None, rows
    P = system.parameters

    def build(free):
        chosen = {**v, **{k: _exact(x) for k, x in free.items()}}
        sub = P.substitution(chosen)
        at = {role: (step, _At(res, sub)) for role, (step, res) in checked.items()}
        return DECAY.model(at, chosen)

    return build, rows


def _exact(x):
    """A searched value as an exact number (a float at its exact binary value), or the search's symbol."""
    return x if isinstance(x, sympy.Basic) else sympy.Rational(x)


class _At:
    """A checked step's result with the free parameters substituted in its right-hand side."""

    def __init__(self, res, sub):
        from lkverify.declare.parameters import apply_substitution

        self.rhs = sympy.expand(apply_substitution(res.rhs, sub))
        self.status = res.status


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
            name = f"{label} ($\\|\\chi\\|_\\tau = {c / dt:.2f}\\,\\tilde\\delta$)"
            curves["d1"][name] = (tr.t, e, c)  # with its ‖χ‖_τ: the figure draws the sample's own envelope
            curves["d2"][name] = (tr.t, wn, c)
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
    if at_printed_15(v):  # the paper states (15) at the Fig. 6/7 data only: nowhere else is it tested
        out.append(_printed_15_row(rng, rv, vals, samples=samples, t_end=t_end, grid=grid))
    status = Status.FAILED if violations else Status.SIMULATED
    out.insert(0, Result("envelope", "histories inside the proved region", status,
                         {"samples": samples, "max_ratio_d1": worst["d1"], "max_ratio_d2": worst["d2"],
                          "violations": violations},
                         f"{samples} constant histories with ‖χ‖_τ < δ̃, t ∈ [0, {t_end:g}]: largest trajectory/"
                         f"envelope ratio {worst['d1']:.3g} for ‖s − r‖ and {worst['d2']:.3g} for ‖ω‖; "
                         + ("violations: " + ", ".join(violations) if violations else "no violation")))
    return out, curves


def _printed_15_row(rng, rv, vals, *, samples, t_end, grid):
    """The printed estimate (15) itself, from histories with ‖χ‖_τ just inside its printed region 0.28."""
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
    return Result("envelope", "printed (15) at ‖χ‖_τ = 0.27", Status.FAILED if viol15 else Status.SIMULATED,
                  {"samples": samples, "max_ratio": worst15, "violations": viol15},
                  f"{samples} constant histories with ‖χ‖_τ = 0.27 < 0.28 against the printed constants: largest "
                  f"trajectory/envelope ratio {worst15:.3g}; "
                  + ("violations: " + ", ".join(viol15) if viol15 else "no violation (not a proof: simulated)"))


THEOREM3_CONSTANTS = ConstantsJob(
    templates=[],
    model=theorem3_model,
    steps=True,
    free=FREE,
    wider=WIDER,
    objective={"paper": _objective_paper, "region": _objective_region},
    paper=PRINTED_15_STATED,  # (15) is stated at the Fig. 6/7 data only
    applies=_applies,
    cross_check=_cross_check,
    descriptions=DECAY.descriptions,
)
