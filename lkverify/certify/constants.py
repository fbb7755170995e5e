"""The ``constants`` job: certified constants, parameters, region and envelope of a proof.

A proof module attaches a :class:`ConstantsJob` to an item.  The job

1. computes the best constants of the proof's bound templates (each a
   supremum over a chart of the state manifold): estimate and certified upper
   bound (:func:`lkverify.certify.bounds.sup_bound`);
2. builds the proof's :class:`~lkverify.certify.decay.DecayModel` with those constants,
   searches its free parameters (estimated), and proves the result
   (:func:`~lkverify.certify.decay.certify_decay`), shrinking the candidate constants
   until the proof goes through or the budget is spent;
3. optionally cross-checks the envelope against simulated trajectories.

The whole job honours one time budget (``budget`` seconds, ``lkverify constants
--budget``): each phase gets what is left of it, and the job is interrupted
(``SIGALRM``, :meth:`lkverify.options.Deadline.enforced`) when it runs out; what
was finished is reported, the rest is ``undecided`` with the phase that was cut.

Every number in the report carries its status; a certified constant is compared
with the paper's value when the paper prints one.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping, Sequence

import sympy

from . import bounds
from ..options import BudgetExceeded, Deadline
from .decay import DecayCertificate, DecayModel, certify_decay, estimate_decay, search_parameters, tighten
from ..report.results import Report, Result
from ..status import Status

__all__ = ["Template", "ConstantsJob"]


@dataclasses.dataclass(frozen=True)
class Template:
    """A bound template ``lhs ≤ c·template``: c = sup of ``expr`` over ``box`` (a chart of the region).

    ``expr`` is a function of the checked parameter values returning the SymPy
    expression whose supremum is the best constant (the ratio lhs/template
    written without the removable singularity), and ``box`` the chart's box.
    """

    name: str
    text: str
    expr: Callable
    box: Callable
    paper: float | None = None


@dataclasses.dataclass
class ConstantsJob:
    """How to compute and certify an item's constants.

    Parameters
    ----------
    templates : sequence of Template
    model : callable
        ``model(values, constants)`` → ``build(free) → DecayModel``: the proof's final
        inequalities with the templates' certified constants substituted; ``free``
        holds the free parameters of the functional and of the region.
    free : dict
        free parameter name → (low, high) for the search.
    objective : callable or dict
        estimate dict → number to minimise; or goal name → such a callable
        (the first is the default goal).
    paper : dict
        The paper's printed values of the outputs (name → value).
    applies : callable, optional
        ``applies(values)`` → None, or the reason the model does not apply
        (e.g. a hypothesis of the derivation fails); that is bad input (InputError).
    cross_check : callable, optional
        ``cross_check(values, certificate)`` → list of Results (simulations).
    """

    templates: Sequence[Template]
    model: Callable
    free: Mapping
    objective: Callable
    paper: Mapping = dataclasses.field(default_factory=dict)
    applies: Callable | None = None
    cross_check: Callable | None = None
    descriptions: Mapping = dataclasses.field(default_factory=dict)

    plot_fn: Callable | None = None

    def plot(self, extra: dict, path, *, values=None) -> None:
        """Write the job's figure (default: the certified envelopes on log axes)."""
        (self.plot_fn or _plot_envelopes)(extra, path, values=values)

    @property
    def goals(self) -> list[str]:
        return list(self.objective) if isinstance(self.objective, Mapping) else ["default"]

    def run(self, item_name: str, values: Mapping, shown: Mapping, *, budget: float = 120.0,
            progress: Callable[[str], None] | None = None, seed: int = 0,
            goal: str | None = None) -> tuple[Report, dict]:
        """Compute and certify the constants within ``budget`` seconds (the whole job).

        Returns
        -------
        (Report, dict)
            The report (``undecided`` results when the budget ran out) and the data
            for the figure.

        Raises
        ------
        InputError
            An unknown goal, or values outside the hypotheses the model rests on.
        """
        from ..errors import InputError

        if isinstance(self.objective, Mapping):
            if goal is not None and goal not in self.objective:
                raise InputError(f"--goal: expected one of {', '.join(self.objective)}, got {goal}")
        elif goal not in (None, "default"):
            raise InputError(f"--goal: this item has a single goal (default), got {goal}; drop --goal")
        if self.applies is not None:
            why = self.applies(values)
            if why:  # outside the hypotheses the derivation rests on: bad input, not a result
                raise InputError(f"{item_name}: {why}")
        deadline = Deadline(budget)
        results: list[Result] = []
        phase = ["starting"]
        try:
            with deadline.enforced():
                return self._run(item_name, values, shown, deadline=deadline, results=results, phase=phase,
                                 progress=progress, seed=seed, goal=goal)
        except BudgetExceeded:
            pass
        results.append(Result("region", "budget", Status.UNDECIDED, {"budget": budget, "phase": phase[0]},
                              f"time budget of {budget:g} s ran out during {phase[0]} (after "
                              f"{deadline.elapsed:.1f} s); raise --budget to finish"))
        return Report(item_name, dict(shown), tuple(results),
                      f"undecided: the time budget of {budget:g} s ran out during {phase[0]}"), {}

    def _run(self, item_name, values, shown, *, deadline: Deadline, results: list, phase: list, progress, seed,
             goal) -> tuple[Report, dict]:
        say = progress or (lambda msg: None)
        budget = deadline.seconds
        start = deadline.start
        if isinstance(self.objective, Mapping):
            objective = self.objective[goal or next(iter(self.objective))]
        else:
            objective = self.objective
        consts = {}
        for k, tpl in enumerate(self.templates):
            phase[0] = f"the template constant {tpl.name}"
            say(f"{item_name}: constant {tpl.name} = sup {tpl.text}")
            # half the budget for the templates, shared by those still to do
            share = (0.5 * budget - deadline.elapsed) / (len(self.templates) - k)
            res = bounds.sup_bound(tpl.expr(values), tpl.box(values), rel_gap=5e-3, budget_boxes=40_000,
                                   enclosure="mean-value", budget_seconds=max(share, 1e-3))
            # The upper bound is proved whenever it is finite, even if the accuracy target
            # (the gap to the estimate) was not reached within the budget.
            proved = res.certified is not None and res.certified < float("inf")
            status = Status.CERTIFIED if proved else Status.UNDECIDED
            consts[tpl.name] = res.certified
            detail = (f"{tpl.text}: estimate {res.estimate:.6g} at {_fmt_point(res.maximiser)}, "
                      f"certified ≤ {res.certified:.6g} (gap {res.gap:.2g}"
                      f"{'' if res.status is Status.CERTIFIED else ', accuracy target not reached in the budget'}"
                      f", {res.boxes} boxes, {res.seconds:.1f} s)")
            if tpl.paper is not None:
                detail += f"; paper: {tpl.paper:g}"
            results.append(Result("constant", tpl.name, status,
                                  {"estimate": res.estimate, "certified": res.certified, "gap": res.gap,
                                   "maximiser": res.maximiser, "boxes": res.boxes}, detail))
        if any(r.status is not Status.CERTIFIED for r in results if r.name in consts):
            return Report(item_name, dict(shown), tuple(results),
                          "undecided: a template constant was not certified" + _spent(deadline, budget)), consts
        build = self.model(values, consts)
        extra_points: list = []
        cert = None
        for round_ in range(5):  # search, certify; a refuted point joins the samples of the next search
            phase[0] = f"the search of the free parameters (round {round_ + 1})"
            say(f"{item_name}: searching the free parameters {', '.join(self.free)} (estimated)")
            params, est = search_parameters(build, self.free, objective=objective, seed=seed + round_,
                                            extra_points=extra_points)
            if est is None:
                break
            params = {k: sympy.Rational(v).limit_denominator(10**4) for k, v in params.items()}
            model = build(params)
            found: list = []
            est = estimate_decay(model, grid=31, violations=found)
            if est is None:
                extra_points += found  # the search's samples missed these: show them next round
                continue
            ct = sympy.Rational(est["c_tilde"]).limit_denominator(10**6) * sympy.Rational(99, 100)
            ls = {v: sympy.Rational(est[f"l_{v}"]).limit_denominator(10**6) * sympy.Rational(99, 100)
                  for v in model.outputs.values()}
            dt = sympy.Rational(est["delta_tilde"]).limit_denominator(10**6)
            infeasible = False
            for attempt in range(6):
                remaining = deadline.remaining
                if remaining <= 0:
                    break
                phase[0] = f"the certification (round {round_ + 1}, attempt {attempt + 1})"
                say(f"{item_name}: certifying (round {round_ + 1}, attempt {attempt + 1}, c̃ = {float(ct):.5g})")
                cert = certify_decay(model, c_tilde=ct, lower_coefficients=ls, delta_tilde=dt,
                                     budget_seconds=min(remaining, 60.0), progress=say)
                if cert.status is Status.CERTIFIED:
                    break
                if cert.counterexamples:  # counterexample-guided: lower the refuted candidates
                    tightened = tighten(model, ct, ls, cert.counterexamples)
                    if tightened is None:
                        say(f"{item_name}: the chosen parameters violate V̇ < 0 at a point of the region")
                        extra_points += [pt for _, pt in cert.counterexamples]
                        infeasible = True
                        break
                    ct, ls = tightened
                else:
                    ct, ls = ct * sympy.Rational(9, 10), {k: v * sympy.Rational(9, 10) for k, v in ls.items()}
            if not infeasible or budget - (time.monotonic() - start) <= 20:
                break
        if est is None:
            results.append(Result("region", "parameters", Status.UNDECIDED, None,
                                  "the search found no parameters for which the final inequalities hold on the "
                                  "sampled region (not a proof that none exist)"))
            return Report(item_name, dict(shown), tuple(results), "undecided: no admissible parameters found" + _spent(deadline, budget)), consts
        for k, v in params.items():
            results.append(Result("region", k, Status.ESTIMATED, float(v),
                                  f"free parameter chosen by the search (exact value {v} used in the proof)"))
        if cert is not None and cert.status is not Status.CERTIFIED:
            results.append(Result("region", "certificate", cert.status, None, cert.detail))
        if cert is None:
            results.append(Result("region", "certificate", Status.UNDECIDED, None, "budget spent before certifying"))
            return Report(item_name, dict(shown), tuple(results),
                          "undecided: no certificate" + (_spent(deadline, budget) or " (every attempt failed)")), consts
        results += cert.results(self.paper, self.descriptions)
        for env in cert.envelopes:
            results.append(Result("envelope", f"envelope {env.name}", cert.status,
                                  {"d": env.d, "rate": env.kappa, "p": env.p}, env.text()))
        if cert.status is Status.CERTIFIED and self.cross_check is not None:
            phase[0] = "the simulations cross-checking the envelope"
            say(f"{item_name}: simulating histories inside the proved region")
            checked = self.cross_check(values, cert)
            curves = {}
            if isinstance(checked, tuple):  # (results, curves for the figure)
                checked, curves = checked
            results += checked
        verdict = _verdict(results, self.paper, cert)
        extra = {"certificate": cert, "params": params}
        if cert.status is Status.CERTIFIED and self.cross_check is not None:
            extra["trajectories"] = curves
        return Report(item_name, dict(shown), tuple(results), verdict), extra


def _plot_envelopes(extra: dict, path, *, values=None, simulate_fn=None) -> None:
    """Certified envelopes (log scale), with the cross-check trajectories when given."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    cert = extra.get("certificate")
    if cert is None:
        return
    fig, axes = plt.subplots(1, len(cert.envelopes), figsize=(6 * len(cert.envelopes), 4), squeeze=False)
    dt = cert.constants["delta_tilde"]
    tt = np.geomspace(1e-2, 1e6, 400)
    for ax, env in zip(axes[0], cert.envelopes):
        for frac in (1.0, 0.5, 0.1):
            ax.loglog(tt + 1, env(tt, frac * dt), label=f"‖χ‖_τ = {frac:g} δ̃")
        for label, (t_, q) in extra.get("trajectories", {}).get(env.name, {}).items():
            ax.loglog(t_ + 1, q, ":", lw=1, label=label)
        ax.set_title(env.text(), fontsize=9)
        ax.set_xlabel("1 + t − t0")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _fmt_point(p) -> str:
    if not p:
        return "—"
    return "(" + ", ".join(f"{k}={v:.4g}" for k, v in p.items()) + ")"


def _spent(deadline, budget) -> str:
    """`` (the time budget of B s ran out)`` when it did, else ``""``."""
    return f" (the time budget of {budget:g} s ran out)" if deadline.expired else ""


def _verdict(results, paper, cert: DecayCertificate) -> str:
    bad = [r.name for r in results if r.status in (Status.FAILED, Status.UNDECIDED)]
    if bad:
        return f"{'failed' if any(r.status is Status.FAILED for r in results) else 'undecided'}: {', '.join(bad)}"
    cmp = []
    for k, pv in paper.items():
        v = cert.constants.get(k)
        if v is None:
            continue
        better = v <= pv if k in ("d1", "d2") else v >= pv
        cmp.append(f"{k} {'≤' if k in ('d1', 'd2') else '≥'} paper: {'yes' if better else 'no'}")
    return ("certified constants and envelope for the proof module's bound templates" + (f" ({'; '.join(cmp)})" if cmp else "")
            + "; not established: the templates (V ≥ L, V ≤ U, V̇ ≤ W) are declared by the proof module, not yet "
              "checked against the derived V and V̇ (bound steps)")
