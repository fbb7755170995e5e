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

The whole job honours one time budget (a :class:`~lkverify.options.Budget`): each phase
gets what is left of it (the shares are in :class:`ConstantsTuning`), and the job is interrupted
(``SIGALRM``, :meth:`lkverify.options.Deadline.enforced`) when it runs out; what
was finished is reported, the rest is ``undecided`` with the phase that was cut.

Every number in the report carries its status; a certified constant is compared
with the paper's value when the paper prints one.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence

import sympy

from ..errors import InputError
from ..options import Accuracy, Budget, BudgetExceeded, Deadline
from ..report.results import Report, Result
from ..status import Status
from . import bounds
from .decay import DecayCertificate, StatedAt, certify_decay, estimate_decay, search_parameters, tighten

__all__ = ["ConstantsJob", "ConstantsTuning", "Template"]


@dataclasses.dataclass(frozen=True)
class Template:
    """A bound template ``lhs ≤ c·template``: c = sup of ``expr`` over ``box`` (a chart of the region).

    ``expr`` is a function of the checked parameter values returning the SymPy
    expression whose supremum is the best constant (the ratio lhs/template
    written without the removable singularity), and ``box`` the chart's box.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.bounds import sup_bound
    >>> x = sympy.Symbol("x")
    >>> tpl = Template("c", "sup x(1 − x)", expr=lambda values: x * (1 - x), box=lambda values: {x: (0, 1)})
    >>> res = sup_bound(tpl.expr({}), tpl.box({}))          # what the job certifies for it
    >>> res.status.value, res.lower, res.certified <= 0.26
    ('certified', 0.25, True)
    """

    name: str
    text: str
    expr: Callable
    box: Callable
    paper: float | None = None


@dataclasses.dataclass(frozen=True)
class ConstantsTuning:
    """How a :class:`ConstantsJob` spends its budget: every tuning constant of the job, in one place.

    Parameters
    ----------
    template_share : float, default 1/2
        Fraction of the job's budget for the template constants (shared by those still to do).
    template_accuracy : lkverify.options.Accuracy, default rel_gap 5e-3
        When a template constant's certified bound is tight enough.
    template_boxes : int, default 40 000
        Branch-and-bound boxes per template constant.
    template_enclosure : str, default "taylor"
        The enclosure strategy of :func:`lkverify.certify.bounds.sup_bound`.
    rounds : int, default 5
        Search-then-certify rounds; a refuted point joins the samples of the next search.
    attempts : int, default 6
        Certification attempts per round (the candidate constants lowered in between).
    parameter_denominator : int, default 10⁴
        The searched parameters are rounded to rationals with this denominator bound.
    constant_denominator : int, default 10⁶
        The estimated c̃, l_v and δ̃ are rounded to rationals with this denominator bound …
    candidate_margin : Rational, default 99/100
        … and c̃, l_v multiplied by this factor before the first certification.
    shrink : Rational, default 9/10
        Factor lowering c̃ and l_v after an attempt that was undecided without a counterexample.
    grid : int, default 31
        Points per axis of the estimator's face grids.
    certify_seconds : float, default 60
        At most this much of the remaining budget for one certification attempt.
    retry_seconds : float, default 20
        A round whose parameters proved infeasible is retried only with more than this left.
    search_share : float, default 1/2
        A search may use at most this fraction of the remaining budget; it then stops with the
        best point found so far (leaving time to certify it).

    Examples
    --------
    >>> ConstantsTuning().rounds, ConstantsTuning(attempts=2).attempts
    (5, 2)
    """

    template_share: float = 0.5
    template_accuracy: Accuracy = Accuracy(rel_gap=5e-3)
    template_boxes: int = 40_000
    template_enclosure: str = "taylor"
    rounds: int = 5
    attempts: int = 6
    parameter_denominator: int = 10**4
    constant_denominator: int = 10**6
    candidate_margin: sympy.Rational = sympy.Rational(99, 100)
    shrink: sympy.Rational = sympy.Rational(9, 10)
    grid: int = 31
    certify_seconds: float = 60.0
    retry_seconds: float = 20.0
    search_share: float = 0.5


@dataclasses.dataclass(frozen=True)
class _Progress:
    """What the job had finished when it stopped: the results so far and the phase it was in."""

    results: list
    phase: list  # one element, the current phase (a mutable cell the budget handler reads)

    def enter(self, phase: str) -> None:
        self.phase[0] = phase


@dataclasses.dataclass(frozen=True)
class _Candidate:
    """The outcome of one search-and-certify round."""

    params: dict | None          # the exact parameters used (None: the search found none)
    certificate: DecayCertificate | None
    infeasible: bool             # the parameters violate V̇ < 0 at a point of the region


@dataclasses.dataclass(frozen=True)
class ConstantsJob:
    """How to compute and certify an item's constants.

    Parameters
    ----------
    templates : sequence of Template
    model : callable
        ``model(values, constants)`` → ``build(free) → DecayModel``: the proof's final
        inequalities with the templates' certified constants substituted; ``free``
        holds the free parameters of the functional and of the region.  With
        ``steps=True``: ``model(values, constants, budget=, progress=)`` → ``(build or None,
        results)``: the final inequalities are the right-hand sides of checked bound steps
        (:mod:`lkverify.certify.steps.chain`), whose results join the report.
    free : dict
        free parameter name → (low, high) for the search.
    objective : callable or dict
        estimate dict → number to minimise; or goal name → such a callable
        (the first is the default goal).
    paper : dict or StatedAt
        The paper's printed values of the outputs (name → value); a
        :class:`~lkverify.certify.decay.StatedAt` compares them only at the data where the
        paper states them.
    applies : callable, optional
        ``applies(values)`` → None, or the reason the model does not apply
        (e.g. a hypothesis of the derivation fails); that is bad input (InputError).
    cross_check : callable, optional
        ``cross_check(values, certificate)`` → list of Results (simulations).
    descriptions : dict
        Output name → the sentence shown before its value.
    plot_fn : callable, optional
        ``plot_fn(extra, path, values=...)``; default: the certified envelopes on log axes.
    tuning : ConstantsTuning
        How the job spends its budget.
    wider : dict, optional
        Wider ranges searched when ``free`` holds no feasible point (gains far from the
        paper's need, say, a much larger λ or a much smaller region).
    steps : bool, default False
        The model checks the proof's bound steps first (see ``model``).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.decay import DecayModel
    >>> x = sympy.Symbol("x"); w, e = sympy.symbols("w e", nonnegative=True)
    >>> tpl = Template("c", "sup x(1 − x)", expr=lambda v: x * (1 - x), box=lambda v: {x: (0, 1)})
    >>> def model(values, consts):                      # build(free) → DecayModel with c certified
    ...     return lambda p: DecayModel("toy", (w, e), {w: 1, e: 1}, w**2 + e**2, w**2 + e**2,
    ...                                 -p["a"] * (1 - consts["c"]) * (w**3 + e**3), sympy.Rational(3, 2),
    ...                                 (w, e), {}, {"d1": e, "d2": w})
    >>> goals = {"rate": lambda est: -est["c_tilde"], "size": lambda est: -est["delta_tilde"]}
    >>> job = ConstantsJob([tpl], model, {"a": (1, 2)}, goals,
    ...                    applies=lambda values: "needs b < 1" if values.get("b", 0) >= 1 else None)
    >>> job.goals
    ['rate', 'size']
    >>> job.run("toy", {"b": 2}, {})                    # checked before any computation
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: toy: needs b < 1
    >>> job.run("toy", {}, {}, goal="speed")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: goal: expected one of rate, size, got speed; pass one of them
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
    tuning: ConstantsTuning = ConstantsTuning()
    steps: bool = False
    wider: Mapping | None = None

    def plot(self, extra: dict, path, *, values=None) -> None:
        """Write the job's figure (default: the certified envelopes on log axes)."""
        (self.plot_fn or _plot_envelopes)(extra, path, values=values)

    def stated(self, values: Mapping) -> dict:
        """The paper's printed values to compare with at these values: all of :attr:`paper`, or, for a
        :class:`~lkverify.certify.decay.StatedAt`, only at the data where the paper states them."""
        return self.paper.at(values) if isinstance(self.paper, StatedAt) else dict(self.paper or {})

    @property
    def goals(self) -> list[str]:
        return list(self.objective) if isinstance(self.objective, Mapping) else ["default"]

    def run(self, item_name: str, values: Mapping, shown: Mapping, *, budget: Budget | float = Budget(seconds=120),
            progress: Callable[[str], None] | None = None, seed: int = 0,
            goal: str | None = None) -> tuple[Report, dict]:
        """Compute and certify the constants within the budget (the whole job).

        Parameters
        ----------
        item_name : str
        values, shown : mapping
            The resolved parameter values, and how they are shown in the report.
        budget : lkverify.options.Budget or float
            The whole job's time (a number is seconds).
        progress : callable, optional
            Called with a line at each step.
        seed : int
            Seed of the parameter search (round k uses ``seed + k``).
        goal : str, optional
            Which objective to minimise (see :attr:`goals`).

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
        if not isinstance(budget, Budget):
            budget = Budget(seconds=budget)
        if isinstance(self.objective, Mapping):
            if goal is not None and goal not in self.objective:
                raise InputError(f"goal: expected one of {', '.join(self.objective)}, got {goal}; pass one of them")
        elif goal not in (None, "default"):
            raise InputError(f"goal: this item has a single goal (default), got {goal}; do not pass a goal")
        if self.applies is not None:
            why = self.applies(values)
            if why:  # outside the hypotheses the derivation rests on: bad input, not a result
                raise InputError(f"{item_name}: {why}")
        deadline = budget.deadline()
        state = _Progress([], ["starting"])
        try:
            with deadline.enforced():
                return self._run(item_name, values, shown, deadline=deadline, state=state,
                                 say=progress or (lambda msg: None), seed=seed, goal=goal)
        except BudgetExceeded:
            pass
        seconds, phase = budget.seconds, state.phase[0]
        state.results.append(Result("region", "budget", Status.UNDECIDED, {"budget": seconds, "phase": phase},
                                    f"time budget of {seconds:g} s ran out during {phase} (after "
                                    f"{deadline.elapsed:.1f} s); raise the budget to finish"))
        return Report(item_name, dict(shown), tuple(state.results),
                      f"undecided: the time budget of {seconds:g} s ran out during {phase}"), {}

    def _run(self, item_name, values, shown, *, deadline: Deadline, state: _Progress, say, seed,
             goal) -> tuple[Report, dict]:
        results = state.results
        consts = self._template_constants(item_name, values, deadline=deadline, state=state, say=say)
        if any(r.status is not Status.CERTIFIED for r in results if r.name in consts):
            return Report(item_name, dict(shown), tuple(results),
                          "undecided: a template constant was not certified" + _spent(deadline)), consts
        objective = self.objective[goal or next(iter(self.objective))] if isinstance(self.objective, Mapping) \
            else self.objective
        state.enter("the bound steps")
        build = self.model(values, consts, budget=deadline.remaining, progress=say) if self.steps \
            else self.model(values, consts)
        if isinstance(build, tuple):  # (build or None, the bound steps' results)
            build, rows = build
            results += rows
            if build is None:
                return Report(item_name, dict(shown), tuple(results),
                              "not established: a bound step of the chain is not proved (see the bound rows)"
                              + _spent(deadline)), consts
        found = self._search_and_certify(item_name, build, objective, deadline=deadline,
                                         state=state, say=say, seed=seed)
        if found.params is None:
            results.append(Result("region", "parameters", Status.UNDECIDED, None,
                                  "the search found no parameters for which the final inequalities hold on the "
                                  "sampled region (not a proof that none exist)"))
            return Report(item_name, dict(shown), tuple(results),
                          "undecided: no admissible parameters found" + _spent(deadline)), consts
        params, cert = found.params, found.certificate
        for k, v in params.items():
            results.append(Result("region", k, Status.ESTIMATED, float(v),
                                  f"free parameter chosen by the search (exact value {v} used in the proof)"))
        if cert is None:
            results.append(Result("region", "certificate", Status.UNDECIDED, None, "budget spent before certifying"))
            return Report(item_name, dict(shown), tuple(results),
                          "undecided: no certificate" + (_spent(deadline) or " (every attempt failed)")), consts
        if cert.status is not Status.CERTIFIED:
            results.append(Result("region", "certificate", cert.status, None, cert.detail))
        results += cert.results(self.paper, self.descriptions, values)
        for env in cert.envelopes:
            results.append(Result("envelope", f"envelope {env.name}", cert.status,
                                  {"d": env.d, "rate": env.kappa, "p": env.p}, env.text()))
        extra = {"certificate": cert, "params": params}
        if cert.status is Status.CERTIFIED and self.cross_check is not None:
            state.enter("the simulations cross-checking the envelope")
            say(f"{item_name}: simulating histories inside the proved region")
            checked = self.cross_check(values, cert)
            curves = {}
            if isinstance(checked, tuple):  # (results, curves for the figure)
                checked, curves = checked
            results += checked
            extra["trajectories"] = curves
        return Report(item_name, dict(shown), tuple(results), _verdict(results, self.stated(values), cert)), extra

    def search_choices(self, item_name: str, values: Mapping, *, progress: Callable[[str], None] | None = None,
                       seed: int = 0, goal: str | None = None, stall: int | None = None) -> tuple[dict | None, str]:
        """The free parameters (the proof's choices) at which the decay is certified, found as :meth:`run` does.

        What ``lkverify check`` runs when a proof's documented choices do not close its chain
        (:meth:`lkverify.catalogue.Theorem.run`): the template constants, the bound steps (``steps=True``),
        the search and the certification of :meth:`run`, without the simulations; on the job's work
        limits (no time budget of its own: the caller's cap interrupts it).  ``stall``: the searches stop
        early after that many generations without improvement (:func:`~lkverify.certify.decay.search_parameters`;
        default none, as :meth:`run`); the parameters they return are certified all the same, so only which
        parameters are found can change, never what is claimed for them.

        Returns
        -------
        (dict or None, str)
            The exact parameters (name → Rational) and what was certified there, or None and why not.
        """
        say = progress or (lambda msg: None)
        if not self.steps:
            return None, "the constants job does not check the bound steps"
        why = self.applies(values) if self.applies is not None else None
        if why:
            return None, why
        deadline, state = Deadline(None), _Progress([], ["starting"])
        consts = self._template_constants(item_name, values, deadline=deadline, state=state, say=say)
        if any(r.status is not Status.CERTIFIED for r in state.results if r.name in consts):
            return None, "a template constant was not certified"
        objective = self.objective[goal or next(iter(self.objective))] if isinstance(self.objective, Mapping) \
            else self.objective
        build, _ = self.model(values, consts, budget=None, progress=say)
        if build is None:
            return None, "a bound step of the chain is not proved with the free parameters open"
        found = self._search_and_certify(item_name, build, objective, deadline=deadline, state=state, say=say,
                                         seed=seed, stall=stall)
        ranges = ", ".join(f"{k} ∈ [{lo:g}, {hi:g}]" for k, (lo, hi) in (self.wider or self.free).items())
        if found.params is None:
            return None, (f"the search ({ranges}) found no parameters for which the final inequalities hold on the "
                          f"sampled region (not a proof that none exist)")
        cert = found.certificate
        if cert is None or cert.status is not Status.CERTIFIED:
            return None, (f"the decay was not certified at the parameters the search found "
                          f"({', '.join(f'{k} = {v}' for k, v in found.params.items())})"
                          + (f": {cert.detail}" if cert is not None else ""))
        c = cert.constants
        return dict(found.params), (f"the constants job certified V̇ ≤ −c̃V^p there (c̃ = {c.get('c_tilde', 0):.4g}, "
                                    f"δ̃ = {c.get('delta_tilde', 0):.4g}); searched {ranges}")

    def _template_constants(self, item_name, values, *, deadline: Deadline, state: _Progress, say) -> dict:
        """Step 1: the certified constant of every template (a Result each); name → certified bound."""
        tune = self.tuning
        consts = {}
        for k, tpl in enumerate(self.templates):
            state.enter(f"the template constant {tpl.name}")
            say(f"{item_name}: constant {tpl.name} = sup {tpl.text}")
            # the templates' share of the budget, shared by those still to do
            share = (tune.template_share * deadline.seconds - deadline.elapsed) / (len(self.templates) - k) \
                if deadline.seconds is not None else float("inf")
            acc = tune.template_accuracy
            res = bounds.sup_bound(tpl.expr(values), tpl.box(values), accuracy=acc,
                                   budget=Budget(seconds=max(share, 1e-3), boxes=tune.template_boxes),
                                   enclosure=tune.template_enclosure)
            # The upper bound is proved whenever it is finite, even if the accuracy target
            # (the gap to the estimate) was not reached within the budget.
            proved = res.certified is not None and res.certified < float("inf")
            consts[tpl.name] = res.certified
            detail = (f"{tpl.text}: estimate {res.estimate:.6g} at {_fmt_point(res.maximiser)}, "
                      f"certified ≤ {res.certified:.6g} (gap {res.gap:.2g}"
                      f"{'' if res.status is Status.CERTIFIED else ', accuracy target not reached in the budget'}"
                      f", {res.boxes} boxes, {res.seconds:.1f} s)")
            if tpl.paper is not None:
                detail += f"; paper: {tpl.paper:g}"
            state.results.append(Result("constant", tpl.name, Status.CERTIFIED if proved else Status.UNDECIDED,
                                        {"estimate": res.estimate, "certified": res.certified, "gap": res.gap,
                                         "maximiser": res.maximiser, "boxes": res.boxes}, detail))
        return consts

    def _search_and_certify(self, item_name, build, objective, *, deadline: Deadline, state: _Progress, say,
                            seed, stall: int | None = None) -> _Candidate:
        """Steps 2–3: search the free parameters, certify; a refuted point joins the next round's samples."""
        tune = self.tuning
        extra_points: list = []
        found = _Candidate(None, None, False)
        ranges = self.free

        def widen() -> bool:
            """Switch to the wider ranges (once): True when there are some and time is left."""
            nonlocal ranges
            left = deadline.remaining
            if not self.wider or ranges is self.wider or (left is not None and left <= tune.retry_seconds):
                return False
            ranges = self.wider
            say(f"{item_name}: nothing certified in the search ranges; searching the wider ranges "
                + ", ".join(f"{k} ∈ [{lo:g}, {hi:g}]" for k, (lo, hi) in self.wider.items()))
            return True

        for round_ in range(tune.rounds):
            state.enter(f"the search of the free parameters (round {round_ + 1})")
            say(f"{item_name}: searching the free parameters {', '.join(self.free)} (estimated)")
            left = deadline.remaining
            search_deadline = Deadline(max(tune.search_share * left, 1e-3)) if left is not None else None
            params, est = search_parameters(build, ranges, objective=objective, seed=seed + round_,
                                            extra_points=extra_points, deadline=search_deadline, stall=stall)
            if est is None and widen():
                params, est = search_parameters(build, ranges, objective=objective, seed=seed + round_,
                                                extra_points=extra_points, deadline=search_deadline, stall=stall)
            if est is None:
                return _Candidate(None, found.certificate, False)
            params = {k: sympy.Rational(v).limit_denominator(tune.parameter_denominator) for k, v in params.items()}
            model = build(params)
            violations: list = []
            est = estimate_decay(model, grid=tune.grid, violations=violations)
            if est is None:
                extra_points += violations  # the search's samples missed these: show them next round
                found = _Candidate(None, found.certificate, False)
                continue
            found = self._certify(item_name, model, params, est, round_, deadline=deadline, state=state, say=say,
                                  extra_points=extra_points, previous=found.certificate)
            certified = found.certificate is not None and found.certificate.status is Status.CERTIFIED
            if not certified and widen():
                continue
            left = deadline.remaining
            if not found.infeasible or (left is not None and left <= tune.retry_seconds):
                break
        return found

    def _certify(self, item_name, model, params, est, round_, *, deadline: Deadline, state: _Progress, say,
                 extra_points: list, previous) -> _Candidate:
        """Step 3: certify the estimated constants, lowering them after each attempt that did not go through."""
        tune = self.tuning
        cert = previous
        den, margin = tune.constant_denominator, tune.candidate_margin
        ct = sympy.Rational(est["c_tilde"]).limit_denominator(den) * margin
        ls = {v: sympy.Rational(est[f"l_{v}"]).limit_denominator(den) * margin for v in model.outputs.values()}
        dt = sympy.Rational(est["delta_tilde"]).limit_denominator(den)
        for attempt in range(tune.attempts):
            remaining = deadline.remaining
            if remaining is not None and remaining <= 0:
                break
            state.enter(f"the certification (round {round_ + 1}, attempt {attempt + 1})")
            say(f"{item_name}: certifying (round {round_ + 1}, attempt {attempt + 1}, c̃ = {float(ct):.5g})")
            seconds = None if remaining is None else min(remaining, tune.certify_seconds)  # none: box limits
            cert = certify_decay(model, c_tilde=ct, lower_coefficients=ls, delta_tilde=dt,
                                 budget=Budget(seconds=seconds), progress=say)
            if cert.status is Status.CERTIFIED:
                break
            if cert.counterexamples:  # counterexample-guided: lower the refuted candidates
                tightened = tighten(model, ct, ls, cert.counterexamples)
                if tightened is None:
                    say(f"{item_name}: the chosen parameters violate V̇ < 0 at a point of the region")
                    extra_points += [pt for _, pt in cert.counterexamples]
                    return _Candidate(params, cert, True)
                ct, ls = tightened
            else:
                ct, ls = ct * tune.shrink, {k: v * tune.shrink for k, v in ls.items()}
        return _Candidate(params, cert, False)


def _plot_envelopes(extra: dict, path, *, values=None, simulate_fn=None) -> None:
    """Certified envelopes (log scale), with the cross-check trajectories when given.

    One panel per envelope, titled with the envelope itself: ‖s(t) − r‖ ≤ d1‖χ‖_τ(…) with the
    certified constant d1 (a constant, not a function of t), in mathtext; a y-axis label on
    every panel; the legend outside the axes.
    """
    import numpy as np
    from matplotlib.figure import Figure  # no pyplot: the backend (and a notebook's inline one) is left alone

    cert = extra.get("certificate")
    if cert is None:
        return
    quantity = extra.get("quantities", {}) if isinstance(extra.get("quantities"), Mapping) else {}
    fig = Figure(figsize=(7.2 * len(cert.envelopes), 4.4))
    axes = fig.subplots(1, len(cert.envelopes), squeeze=False)
    dt = cert.constants["delta_tilde"]
    tt = np.geomspace(1e-2, 1e6, 400)
    for ax, env in zip(axes[0], cert.envelopes):
        lhs = quantity.get(env.name) or _ENVELOPE_QUANTITY.get(env.name, f"bounded quantity (${env.name}$)")
        for frac in (1.0, 0.5, 0.1):
            ax.loglog(tt + 1, env(tt, frac * dt), label=rf"envelope, $\|\chi\|_\tau = {frac:g}\,\tilde\delta$")
        for label, curve in extra.get("trajectories", {}).get(env.name, {}).items():
            t_, q = curve[0], curve[1]
            text = (str(label).replace("‖χ‖_τ", r"$\|\chi\|_\tau$").replace("δ̃", r"$\tilde\delta$")
                    .replace(" δ)", r" $\tilde\delta$)"))
            line, = ax.loglog(t_ + 1, np.maximum(q, 1e-300), ":", lw=1.4, label=text)
            if len(curve) > 2:  # the sample's ‖χ‖_τ: its own envelope, which it must stay below
                ax.loglog(tt + 1, env(tt, curve[2]), "--", lw=0.9, color=line.get_color(),
                          label="its envelope")
        ax.set_title(_envelope_tex(env, lhs) + rf"   ($\tilde\delta = {dt:.3g}$)", fontsize=9)
        ax.set_xlabel(r"$1 + t - t_0$")
        ax.set_ylabel(lhs)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    from ..report.files import save_figure

    save_figure(fig, path, dpi=120)


#: the quantity each envelope bounds (by the envelope's constant name), in mathtext
_ENVELOPE_QUANTITY = {"d1": r"$\|s(t) - r\|$", "d2": r"$\|\omega(t)\|$"}


def _envelope_tex(env, lhs: str) -> str:
    """``‖s(t) − r‖ ≤ d1‖χ‖_τ(1 + κ‖χ‖_τ(t − t0))^{−1}`` with the certified numbers, in mathtext."""
    name = env.name.replace("d", "d_", 1) if env.name[:1] == "d" and env.name[1:].isdigit() else env.name
    chi = r"\|\chi\|_\tau"
    if env.p == 1:
        rhs = rf"{name}\,{chi}\,e^{{-{env.kappa / 2:.3g}(t - t_0)}}"
    elif env.p == 1.5:
        rhs = rf"{name}\,{chi}\,(1 + {env.kappa:.3g}\,{chi}\,(t - t_0))^{{-1}}"
    else:
        rhs = (rf"{name}\,{chi}\,(1 + {env.kappa:.3g}\,{chi}^{{{2 * (env.p - 1):g}}}(t - t_0))"
               rf"^{{-{1 / (2 * (env.p - 1)):.3g}}}")
    return lhs[:-1] + r" \leq " + rhs + rf",\ {name} = {env.d:.4g}$"


def _fmt_point(p) -> str:
    if not p:
        return "—"
    return "(" + ", ".join(f"{k}={v:.4g}" for k, v in p.items()) + ")"


def _spent(deadline: Deadline) -> str:
    """`` (the time budget of B s ran out)`` when it did, else ``""``."""
    return f" (the time budget of {deadline.seconds:g} s ran out)" if deadline.expired else ""


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
    versus = f" ({'; '.join(cmp)})" if cmp else ""
    steps = [r for r in results if r.kind == "bound"]
    if steps and all(r.status.is_proof for r in steps):
        return (f"established: certified constants and envelope{versus}; the final inequalities V ≥ L, V ≤ U, "
                f"V̇ ≤ W are the checked bound steps ({len(steps)} bound results, all exact or certified)")
    return (f"certified constants and envelope for the proof module's bound templates{versus}; not established: "
            f"the templates (V ≥ L, V ≤ U, V̇ ≤ W) are declared by the proof module, not checked against the "
            f"derived V and V̇ (bound steps)")
