"""Remark 1 of paper 000, made quantitative: the region δ that the proof of Theorem 1 certifies.

Remark 1: "… an increase of the delay leads to a decrease of the value δ that determines the
region in which the estimates (11), (12) hold.  … In such situations, to stabilise the
programmed orientation one has to increase the parameters α1, α2 of the control torque."

For each delay τ (and each scaling k of α1 = kα1⁰, α2 = kα2⁰) the proof's free choices are
optimised (:func:`~lkverify.proofs.aleksandrov2026.theorem1_chain.optimal_choices`, a
geometric programme) to maximise δ, and the whole chain (V ≥ L, V ≤ U, V̇ ≤ W, Krasovskii) is then proved at those exact
choices: the δ reported is certified.  It is the δ *this proof* certifies — a lower bound on
the largest region where (11), (12) hold — so comparing two of them supports or does not
support the remark; it cannot refute it.

The check evaluates three points (τ = 1/4 and 4 at the run's α, and 4α at τ = 4) with the
optimised δ only (estimated, about a second), and simulates (2), (7) from the paper's initial
data of section 5 at τ ∈ :data:`SIM_TAUS` with α1, α2 scaled by :data:`SIM_SCALES`
(:mod:`.remark1_runs`: the batch integrator, one compiled loop; status simulated); the certification of the whole table
(τ ∈ {1/4, 1/2, 1, 2, 4} × k ∈ {1, 2, 4}, about 75 s) and its figure are the constants job:
``lkverify constants aleksandrov2026.remark1 --plot delta_tau.png``.
"""

from __future__ import annotations

import time

import numpy as np
import sympy

from lkverify import Check, Report, Result, Status

from .equations import PAPER, P
from .remark1_runs import SIM_SCALES, SIM_TAUS, simulated_advice
from .theorem1_chain import CONCLUSION, optimal_choices, steps

__all__ = ["TAUS", "SCALES", "SIM_TAUS", "SIM_SCALES", "PIECE_ENDS", "certified_delta", "delta_pieces",
           "optimised_delta", "remark1"]

TAUS = ("1/4", "1/2", "1", "2", "4")
#: the ends of the pieces of τ ∈ [1/10, 10] on which δ(τ) is certified piecewise (ratio about 10^(1/6))
PIECE_ENDS = ("1/10", "3/20", "11/50", "8/25", "47/100", "17/25", "1", "147/100", "43/20", "16/5", "47/10",
              "34/5", "10")
SCALES = ("1", "2", "4")
_CHOICES = ("gamma", "lam", "mu", "epsilon", "delta", "eta_w", "eta_K", "eta")


def _gains(values, tau, scale):
    """The run's gains with τ and α1, α2 scaled by ``scale`` (exact)."""
    given = {k: v for k, v in values.items() if k not in _CHOICES}
    k = sympy.Rational(scale)
    return {**given, "tau": sympy.Rational(tau), "alpha1": k * given["alpha1"], "alpha2": k * given["alpha2"]}


def certified_delta(values, *, budget=60.0) -> Result:
    """The region δ the proof of Theorem 1 certifies at these gains (choices optimised, chain proved).

    Returns
    -------
    Result
        kind ``region``; ``value`` = {"delta", "tau", "alpha1", "alpha2", "choices", "seconds"};
        status certified when every step and the Krasovskii conditions are proved.

    Examples
    --------
    >>> r = certified_delta(P.resolve({"tau": "4"}, use_defaults=True))
    >>> r.status.value, 1e-5 < r.value["delta"] < 1e-3
    ('certified', True)
    """
    start = time.perf_counter()
    base = P.resolve({k: v for k, v in values.items() if k not in _CHOICES}, use_defaults=True)
    choices = optimal_choices(base)
    at = P.resolve({**{k: v for k, v in values.items() if k not in _CHOICES}, **choices}, use_defaults=True)
    checked = {s.role: (s, s.check(at, budget=budget)) for s in steps}
    bad = [f"{s.name}: {res.detail}" for s, res in checked.values() if not res.status.is_proof]
    if bad:
        status, detail = Status.UNDECIDED, "; ".join(bad)
    else:
        _, status, detail = CONCLUSION.certify(checked, at)
    d = sympy.Rational(choices["delta"])
    name = f"delta(tau={at['tau']}, alpha1={at['alpha1']}, alpha2={at['alpha2']})"
    value = {"delta": float(d), "delta_exact": str(d), "tau": float(at["tau"]), "alpha1": float(at["alpha1"]),
             "alpha2": float(at["alpha2"]), "choices": choices, "seconds": time.perf_counter() - start}
    text = (f"the proof of Theorem 1 certifies (11), (12) on ‖s_i(ξ) − r_i‖ ≤ δ = {float(d):.3g} (choices optimised: "
            f"γ = {choices['gamma']}, λ = {choices['lam']}, μ = {choices['mu']}): {detail}")
    return Result("region", name, status, value, text)


def _compare(a: Result, b: Result, what: str, claim: str, expect_smaller: bool) -> Result:
    """A row comparing two certified δ with the remark's statement (estimated: they are lower bounds)."""
    if a.value is None or b.value is None:
        return Result("region", what, Status.UNDECIDED, None, f"{claim}: a δ is missing")
    da, db = a.value["delta"], b.value["delta"]
    smaller = db < da
    agrees = smaller == expect_smaller
    return Result("region", what, Status.ESTIMATED, {"ratio": db / da},
                  f"{claim}: δ goes from {da:.3g} to {db:.3g} (×{db / da:.3g}), which "
                  f"{'supports' if agrees else 'does not support'} the remark; both are regions this proof gives "
                  f"(lower bounds on the largest region), so the comparison is evidence, not a proof")


def optimised_delta(values) -> Result:
    """The δ the chain allows at these gains after optimising its choices (a geometric programme; not proved).

    Status ``estimated``: floating point picked it; :func:`certified_delta` (and the constants
    job) proves the chain there.

    Examples
    --------
    >>> r = optimised_delta(P.resolve({"tau": "4"}, use_defaults=True))
    >>> r.status.value, 1e-4 < r.value["delta"] < 1e-2
    ('estimated', True)
    """
    base = P.resolve({k: v for k, v in values.items() if k not in _CHOICES}, use_defaults=True)
    choices = optimal_choices(base)
    d = sympy.Rational(choices["delta"])
    name = f"delta(tau={base['tau']}, alpha1={base['alpha1']}, alpha2={base['alpha2']})"
    return Result("region", name, Status.ESTIMATED,
                  {"delta": float(d), "delta_exact": str(d), "tau": float(base["tau"]), "alpha1": float(base["alpha1"]),
                   "alpha2": float(base["alpha2"]), "choices": choices},
                  f"the chain of Theorem 1 allows ‖s_i(ξ) − r_i‖ ≤ δ = {float(d):.3g} at the choices that maximise it "
                  f"(γ = {choices['gamma']}, λ = {choices['lam']}, μ = {choices['mu']}, ε = {choices['epsilon']}); "
                  f"estimated here, proved by `lkverify constants aleksandrov2026.remark1`")


def delta_pieces(values, ends=PIECE_ENDS, *, budget=None, progress=None) -> list:
    """δ(τ) certified piecewise: Theorem 1 over each interval [τ_k, τ_k+1] of ``ends`` (a box run, the
    choices picked for the whole interval), so every τ of a piece has the region δ of that piece.

    One Result per established piece (kind ``region``, status ``certified``: the chain proved for every
    τ of the piece at those exact choices); a piece that does not close is ``undecided`` (or
    ``failed`` with the box run's failing point).  The pieces' δ form a piecewise-constant certified
    lower bound of the region δ(τ) this proof allows.
    """
    from lkverify.catalogue.boxrun import BoxStatus
    from lkverify.catalogue.items import _show

    from .theorem1 import theorem1

    base = {k: v for k, v in values.items() if k not in _CHOICES and k != "tau"}
    start = time.perf_counter()
    out = []
    for a, b in zip(ends, ends[1:]):
        name = f"delta on tau in [{a}, {b}]"
        if budget is not None and time.perf_counter() - start > budget:
            out.append(Result("region", name, Status.UNDECIDED, None, f"not computed: the budget of {budget:g} s was spent"))
            continue
        if progress:
            progress(f"aleksandrov2026.remark1: Theorem 1 over τ ∈ [{a}, {b}]")
        rep = theorem1.run({k: _show(v) for k, v in base.items()}, box={"tau": (a, b)}, max_boxes=4)
        for piece in rep.pieces:
            lo, hi = piece.box.bounds["tau"]
            label = f"delta on tau in [{lo}, {hi}]"
            if piece.status is not BoxStatus.ESTABLISHED or piece.report is None:
                st = Status.FAILED if piece.failing is not None else Status.UNDECIDED
                out.append(Result("region", label, st, None, f"Theorem 1 over τ ∈ [{lo}, {hi}]: {piece.verdict}"))
                continue
            d = sympy.Rational(piece.choices["delta"])
            out.append(Result("region", label, Status.CERTIFIED,
                              {"tau": [str(lo), str(hi)], "delta": float(d), "delta_exact": str(d)},
                              f"Theorem 1 established for every τ ∈ [{lo}, {hi}] with the region ‖s_i(ξ) − r_i‖ ≤ "
                              f"δ = {d} ({float(d):.3g}): δ(τ) ≥ {float(d):.3g} on the piece"))
    return out


def _remark1_check(v, *, budget=60.0):
    low, high = optimised_delta(_gains(v, "1/4", 1)), optimised_delta(_gains(v, "4", 1))
    strong = optimised_delta(_gains(v, "4", 4))
    rows = [low, high, strong,
            _compare(low, high, "Remark 1: δ decreases as τ grows",
                     "“an increase of the delay leads to a decrease of δ” (τ = 1/4 → 4)", True),
            _compare(high, strong, "Remark 1: larger α1, α2 help at a large delay",
                     "“one has to increase α1, α2” (α × 4 at τ = 4)", False)]
    return rows + simulated_advice(v, budget=budget)


class Remark1Table:
    """The constants job of Remark 1: δ over τ ∈ :data:`TAUS` × α scaled by :data:`SCALES`, and its figure.

    It has the interface ``lkverify constants`` expects (``goals``, ``run``, ``plot``).
    """

    goals = ["default", "pieces"]

    def run(self, item_name, values, shown, *, budget=300.0, progress=None, goal=None):
        """Certify δ at every grid point within ``budget`` seconds (points left over are undecided); with
        ``goal="pieces"`` δ(τ) piecewise on :data:`PIECE_ENDS` (:func:`delta_pieces`)."""
        if goal == "pieces":
            rows = delta_pieces(values, budget=budget, progress=progress)
            bad = [r.name for r in rows if not r.status.is_proof]
            verdict = ("δ(τ) certified on every piece of τ ∈ [1/10, 10]" if not bad else
                       f"undecided: {', '.join(bad)}")
            return Report(item_name, dict(shown), tuple(rows), verdict), {"pieces": rows}
        start = time.perf_counter()
        results = []
        for scale in SCALES:
            for tau in TAUS:
                gains = _gains(values, tau, scale)
                name = f"delta(tau={gains['tau']}, alpha1={gains['alpha1']}, alpha2={gains['alpha2']})"
                if time.perf_counter() - start > budget:
                    results.append(Result("region", name, Status.UNDECIDED, None,
                                          f"not computed: the budget of {budget:g} s was spent"))
                    continue
                if progress:
                    progress(f"{item_name}: δ at τ = {tau}, α × {scale}")
                results.append(certified_delta(gains))
        bad = [r.name for r in results if not r.status.is_proof]
        verdict = "certified δ(τ, α) at every grid point" if not bad else f"undecided: {', '.join(bad)}"
        return Report(item_name, dict(shown), tuple(results), verdict), {"results": results}

    def plot(self, extra, path, *, values=None):
        """δ against τ (log–log), one curve per α scaling; open markers where a point is not certified."""
        from matplotlib.figure import Figure

        if "pieces" in extra:
            return _plot_pieces(extra["pieces"], path)

        fig = Figure(figsize=(8.4, 4.6))
        ax = fig.subplots()
        rows = [r for r in extra["results"] if r.value]
        for scale in SCALES:
            pts = [r for r in rows if abs(r.value["alpha1"] / float(sympy.Rational(scale)) -
                                          _base_alpha(rows)) < 1e-9]
            if not pts:
                continue
            taus = np.array([r.value["tau"] for r in pts])
            ds = np.array([r.value["delta"] for r in pts])
            ok = np.array([r.status.is_proof for r in pts])
            line, = ax.loglog(taus, ds, "-", lw=1.4, label=rf"$\alpha_1 = \alpha_2 = {pts[0].value['alpha1']:g}$")
            ax.loglog(taus[ok], ds[ok], "o", color=line.get_color())
            ax.loglog(taus[~ok], ds[~ok], "o", mfc="none", color=line.get_color())
        ticks = [float(sympy.Rational(x)) for x in TAUS]
        ax.set_xticks(ticks, labels=list(TAUS))
        ax.set_xticks([], minor=True)
        ax.set_xlabel(r"delay $\tau$")
        ax.set_ylabel(r"certified $\delta$ (region $\|s_i(\xi) - r_i\| \leq \delta$)")
        ax.set_title("Remark 1 of paper 000: the region the proof of Theorem 1 certifies\n"
                     "(choices optimised at each point; filled: certified)", fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        fig.tight_layout()
        from lkverify.report.files import save_figure

        save_figure(fig, path, dpi=120)


def _plot_pieces(rows, path):
    """The piecewise-constant certified δ(τ) on [1/10, 10] (log–log), pieces not established hatched."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.4, 4.4))
    ax = fig.subplots()
    done = False
    for r in rows:
        lo, hi = (float(sympy.Rational(x)) for x in r.name.split("[")[1].rstrip("]").split(", "))
        if r.status.is_proof:
            ax.hlines(r.value["delta"], lo, hi, colors="tab:blue", lw=2.2,
                      label=None if done else "certified δ on the piece (Theorem 1 proved for every τ in it)")
            done = True
        else:
            ax.axvspan(lo, hi, color="tab:red", alpha=0.15)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"delay $\tau$")
    ax.set_ylabel(r"certified $\delta$ (region $\|s_i(\xi) - r_i\| \leq \delta$)")
    ax.set_title("Remark 1 of paper 000: δ(τ) certified piecewise on τ ∈ [1/10, 10]\n"
                 "(each piece a box run of Theorem 1, the choices picked for the whole piece)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    from lkverify.report.files import save_figure

    save_figure(fig, path, dpi=120)


def _base_alpha(rows):
    return min(r.value["alpha1"] for r in rows)


remark1 = Check("remark1", parameters=P, checks=[_remark1_check], constants=Remark1Table(), paper=PAPER,
                relevant=("Theta", "D", "alpha1", "alpha2", "nu", "tau", "r1", "r2"),
                title="Remark 1: the region δ the proof of Theorem 1 allows against τ and α1, α2 (certified: the constants "
                      "job), and runs with α1, α2 scaled at τ = 2, 5, 10")
