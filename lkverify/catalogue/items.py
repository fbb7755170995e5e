"""Catalogue items: a theorem with its system, functional, hypotheses and claims.

A proof module declares items; ``lkverify check`` runs them.

>>> import sympy
>>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t
>>> from lkverify import DerivativeClaim, Hypothesis
>>> P = Parameters(); k = P.scalar("k", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-k * x(t)[0], text="-kx")])], parameters=P)
>>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")])
>>> th = Theorem("demo", system=sys, functional=V, hypotheses=[Hypothesis("k > 0", k)],
...              claims=[DerivativeClaim("Vdot", V, sys, [Term(-k * x(t)[0] ** 2, text="-kx²")])])
>>> report = th.run({"k": "2"})
>>> [(r.name, r.status.value) for r in report.results]
[('k > 0', 'exact'), ('Vdot', 'exact')]
>>> report.exit_code       # every result holds, but no bound step: the theorem is not established
1
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence

from ..errors import InputError
from ..certify.hypotheses import Hypothesis
from ..certify.steps import BoundClaim, quadratic_upper_bound
from ..symbolic.claims import DerivativeClaim, IdentityClaim
from ..declare.functional import Functional
from ..declare.parameters import Parameters
from ..report.results import Report, Result
from ..status import Status
from ..declare.system import System
from ..memo import Memo
from .links import Link, _best_step, _combined, _concluded, theorem_verdict
from .statements import _capped, _checked_rows, _cut_text, _not_exact_if_floats, _symbols_of

__all__ = ["Check", "Item", "Link", "Theorem", "theorem_verdict"]


class Item:
    """Base class of catalogue items (anything ``lkverify check`` can run).

    A subclass sets ``name`` (and ``paper``, filled in by the loader from the proof
    file) and implements :meth:`run`, returning a :class:`~lkverify.report.results.Report`.

    Examples
    --------
    >>> class Demo(Item):
    ...     name, paper = "demo", "mypaper"
    >>> Demo().qualified_name
    'mypaper.demo'
    >>> Demo().run_constants()
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: mypaper.demo: no constants job is declared for this item; items with one: see `lkverify list`
    """

    name: str = ""
    title: str = ""
    paper: str = ""
    constants = None  # a lkverify.certify.constants.ConstantsJob, for `lkverify constants`

    @property
    def qualified_name(self) -> str:
        return f"{self.paper}.{self.name}" if self.paper else self.name

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = None,
            progress: Callable[[str], None] | None = None) -> Report:
        """Check the item on deterministic work limits; ``budget`` (seconds) is the caller's own cap."""
        raise NotImplementedError

    def run_constants(self, values: Mapping[str, object] | None = None, *, budget: float = 120.0,
                      progress: Callable[[str], None] | None = None, goal: str | None = None) -> tuple[Report, dict]:
        """The ``constants`` job: certified constants, parameters, region and envelope.

        Raises
        ------
        InputError
            The item has no constants job, or the values are bad.
        """
        from ..errors import InputError

        if self.constants is None:
            raise InputError(f"{self.qualified_name}: no constants job is declared for this item; "
                             f"items with one: see `lkverify list`")
        P = self.parameters
        everything = P.resolve(values or {}, use_defaults=True)
        shown = self.shown(everything) if hasattr(self, "shown") else {k: _show(v) for k, v in everything.items()}
        return self.constants.run(self.qualified_name, everything, shown, budget=budget, progress=progress, goal=goal)


class Theorem(Item):
    """A theorem: hypotheses on the parameters and identity claims of its proof.

    Parameters
    ----------
    name : str
        Item name within the paper, e.g. ``"theorem3"``.
    system : System
    functional : Functional
    hypotheses : sequence of Hypothesis
    claims : sequence of DerivativeClaim or IdentityClaim
    title : str
    unchecked : sequence of str
        The proof module's note of steps it does not encode yet; the verdict never uses it
        (it names the first link of the computed chain that is not proved).
    constants : ConstantsJob, optional
        What ``lkverify constants`` computes and certifies for this item.
    steps : sequence of TermwiseBound
        The proof's estimates V ≥ L, V ≤ U, V̇ ≤ W (roles ``lower``, ``upper``, ``vdot``),
        each proved term by term (:mod:`lkverify.certify.steps.chain`).
    decay : Decay, optional
        The last link: the certified decay of the checked L, U, W on the region.
    choices : mapping or callable
        Values of the proof's free parameters (λ, α, β, the region) used when the user
        does not set them (``--set lam=…``); they appear in the report's parameters.  A
        callable ``choices(resolved values) → mapping`` finds them at the run's gains.
    printed : sequence of DerivativeClaim or IdentityClaim
        The paper's printed formulas compared with the derivation: their results are
        findings about the paper, reported with the verdict but not links of the chain
        (the chain rests on ``claims``, the derived identities).

    Examples
    --------
    ``x' = −kx`` with ``V = x²/2``: the identity V̇ = −kx² is exact for every k, but the
    hypothesis k > 0 fails at k = −1, and the verdict says so:

    >>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t, DerivativeClaim, Hypothesis
    >>> P = Parameters(); k = P.scalar("k", default=1); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t)[0])])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2)])
    >>> th = Theorem("demo", system=sys, functional=V, hypotheses=[Hypothesis("k > 0", k)],
    ...              claims=[DerivativeClaim("Vdot", V, sys, [Term(-k * x(t)[0] ** 2)])])
    >>> rep = th.run({"k": "-1"})
    >>> [(r.name, r.status.value) for r in rep.results], rep.exit_code
    ([('k > 0', 'failed'), ('Vdot', 'exact')], 1)
    >>> rep.verdict.startswith("failed: hypotheses")
    True
    >>> Theorem("demo", system=sys, hypotheses=[Hypothesis("k > 0", k), Hypothesis("k > 0", k)])
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: theorem demo: hypotheses and claims need distinct names, got 'k > 0' twice
    """

    def __init__(self, name: str, *, system: System, functional: Functional | None = None,
                 hypotheses: Sequence[Hypothesis] = (), claims: Sequence = (), bounds: Sequence = (),
                 title: str = "", unchecked: Sequence[str] = (), paper: str = "", constants=None,
                 steps: Sequence = (), decay=None, choices: Mapping | None = None, printed: Sequence = ()):
        if not name.isidentifier():
            raise InputError(f"item name must be an identifier, got {name!r}")
        problems = []
        for b in bounds:
            if not isinstance(b, BoundClaim):
                problems.append(f"bounds must be BoundClaim objects, got {type(b).__name__}")
            elif b.system is not system or (functional is not None and b.functional is not functional):
                problems.append(f"bound step {b.name!r} is not stated for this theorem's own system and functional")
        for c in (*claims, *printed):
            if not isinstance(c, (DerivativeClaim, IdentityClaim)):
                problems.append(f"claims must be DerivativeClaim or IdentityClaim, got {type(c).__name__}")
            elif c.system is not system:
                problems.append(f"claim {c.name!r} is stated along the system {c.system.name or c.system!r}, not "
                                f"along this theorem's system {system.name or system!r}; declare it with the "
                                f"theorem's own System object")
        names = [h.name for h in hypotheses] + [c.name for c in (*claims, *printed) if hasattr(c, "name")] \
            + [b.name for b in bounds if hasattr(b, "name")]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            problems.append(f"hypotheses and claims need distinct names, got {', '.join(map(repr, twice))} twice")
        if not (hypotheses or claims or printed or bounds or steps):
            problems.append("expected at least one hypothesis, claim or bound step to check, got none; declare "
                            "hypotheses=[Hypothesis(...)] or claims=[DerivativeClaim(...)]")
        if problems:
            raise InputError(f"theorem {name}: " + "; ".join(problems))
        self.name = name
        self.system = system
        self.functional = functional
        self.hypotheses = tuple(hypotheses)
        self.claims = tuple(claims)
        self.printed = tuple(printed)
        self.bounds = tuple(bounds)
        self.title = title
        self.unchecked = tuple(unchecked)
        self.paper = paper
        self.constants = constants
        self.steps = tuple(steps)
        self.decay = decay
        self.choices = choices if callable(choices) else dict(choices or {})

    @property
    def parameters(self) -> Parameters:
        return self.system.parameters

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = None,
            progress: Callable[[str], None] | None = None, box=None, max_boxes: int | None = None):
        """Check the hypotheses (at the given values, else the paper's defaults), the claims and the chain.

        With ``box`` (a :class:`~lkverify.declare.boxes.ParameterBox` or a mapping name → (lo, hi)),
        the chain is checked for every point of the box and split until it closes
        (:func:`lkverify.catalogue.boxrun.run_over_box`); the result is a
        :class:`~lkverify.catalogue.boxrun.BoxReport`.

        Identity claims are checked with the *given* values substituted and every
        other parameter left symbolic, so an ``exact`` identity holds for all of them.
        The work is bounded by deterministic work limits (:func:`lkverify.options.work_limits`);
        ``budget`` (seconds, default None) is the caller's own wall-clock cap: what it cuts is
        ``undecided`` ("the budget was spent before this step"), never missing.  When the
        proof's documented choices do not close the chain and the theorem's constants job can
        search them (:meth:`lkverify.certify.constants.ConstantsJob.search_choices`), the chain
        is checked again at the choices found.

        Raises
        ------
        InputError
            Unknown parameter names or inadmissible values.
        """
        from ..options import Budget, Deadline, work_limits

        if box is not None:
            from .boxrun import DEFAULT_MAX_BOXES, run_over_box

            return run_over_box(self, values or {}, box, budget=budget, progress=progress,
                                max_boxes=DEFAULT_MAX_BOXES if max_boxes is None else max_boxes)
        with work_limits():
            cap = Deadline(Budget.of(budget).seconds, cap=True)
            return self._run(values or {}, cap, progress or (lambda msg: None))

    def _run(self, values: Mapping, cap, progress) -> Report:
        P = self.parameters
        given = P.resolve(values, use_defaults=False)
        everything = P.resolve(values, use_defaults=True)
        results, details = self._statements(given, everything, cap, progress)
        definite, upper = {}, None
        stop = _stopped_by_hypotheses(self.hypotheses, results)  # a failed hypothesis: no costly link is started
        if stop is not None:
            return self._stopped(results, details, everything, stop)
        if self.bounds and self.functional is not None:
            upper = quadratic_upper_bound(self.functional, self.system, everything)
        floated_all = P.float_symbols(everything)
        for k, step in enumerate(self.bounds):
            progress(f"{self.qualified_name}: bound step {k + 1}/{len(self.bounds)} {step.name}")
            res, cut = _capped(cap, lambda: (step.check(everything), step.positive_definite_bound(everything)
                                             if step.role is not None else None))
            if cut:
                results.append(Result("bound", step.name, Status.UNDECIDED, None, _cut_text(cap, cut)))
                continue
            results.append(_not_exact_if_floats(res[0].to_result(), _symbols_of(step), floated_all))
            if res[1] is not None:
                definite[step.name] = res[1]
        chosen, run = {}, _StepsRun([], {}, {}, None)
        if self.steps:
            chosen = self.chosen(values)
            run = self._steps_run({**chosen, **dict(values)}, cap, progress)
            found = self._search(values, chosen, results, run, definite, upper, cap, progress)
            if found is not None:
                chosen, run = found
            everything = P.resolve({**chosen, **dict(values)}, use_defaults=True)
        results = results + run.results
        links = self.chain(results, definite=definite, upper=upper, steps=run.checked, decay=run.decay, cut=run.cut)
        return Report(self.qualified_name, self.shown(everything, chosen), tuple(results),
                      self._verdict(results, definite, upper, run.checked, run.decay, cut=run.cut,
                                    at=run.at),
                      tuple(details), links)

    def _stopped(self, results, details, everything, stop: str) -> Report:
        """The report of a run whose hypotheses failed: the bound steps, choices and decay are not started."""
        results = results + [Result("bound", step.name, Status.UNDECIDED, None, stop)
                             for step in (*self.bounds, *self.steps)]
        cut = {step.role: stop for step in self.steps}
        decay = None if self.decay is None else Link(getattr(self.decay, "link", "decay on the region"),
                                                     Status.UNDECIDED, stop)
        links = self.chain(results, steps={}, decay=decay, cut=cut)
        return Report(self.qualified_name, self.shown(everything, {}), tuple(results),
                      self._verdict(results, {}, None, {}, decay, cut=cut), tuple(details), links)

    def _statements(self, given, everything, cap, progress) -> tuple[list, list]:
        """The hypotheses at every value, the claims at the given ones: (results, details of differences)."""
        P = self.parameters
        results: list[Result] = []
        progress(f"{self.qualified_name}: hypotheses")
        sub_all = P.substitution(everything)
        floated_all = P.float_symbols(everything)
        for h in self.hypotheses:
            res, cut = _capped(cap, lambda: h.evaluate(sub_all, budget=None))
            results.append(Result("hypothesis", h.name, Status.UNDECIDED, None, _cut_text(cap, cut, "hypothesis"))
                           if cut else _not_exact_if_floats(res, _symbols_of(h), floated_all))
        claims, details = self.claim_results(given, cap, progress)
        return results + claims, details

    def claim_results(self, given, cap, progress) -> tuple[list, list]:
        """The identity claims with the given values substituted, every other parameter symbolic."""
        from ..options import Deadline

        P = self.parameters
        results: list[Result] = []
        floated_given = P.float_symbols(given)
        details = []
        sub_given = P.substitution(given)
        every_claim = (*self.claims, *self.printed)
        unlimited = Deadline(None)
        for k, claim in enumerate(every_claim):
            progress(f"{self.qualified_name}: identity {k + 1}/{len(every_claim)} {claim.name}")
            res, cut = _capped(cap, lambda: _check_claim(claim, P, given, sub_given, unlimited))
            if cut:
                results.append(Result("identity", claim.name, Status.UNDECIDED, None, _cut_text(cap, cut, "claim")))
                continue
            results.append(_not_exact_if_floats(
                Result("identity", claim.name, res.status, res.to_json(),
                       f"{claim.description + ': ' if claim.description else ''}{res.detail}"),
                _symbols_of(claim), floated_given))
            if res.differences:
                details.append(res.as_text())
        return results, details

    def _steps_run(self, values: Mapping, cap, progress) -> "_StepsRun":
        """The bound steps V ≥ L, V ≤ U, V̇ ≤ W and the decay at these values (the choices included)."""
        P = self.parameters
        everything = P.resolve(values, use_defaults=True)
        floated_all = P.float_symbols(everything)
        results, checked, cut = [], {}, {}
        for k, step in enumerate(self.steps):
            progress(f"{self.qualified_name}: bound step {k + 1}/{len(self.steps)} {step.name}")
            res, how = _capped(cap, lambda: step.check(everything))
            if how:
                results.append(Result("bound", step.name, Status.UNDECIDED, None, _cut_text(cap, how)))
                cut[step.role] = _cut_text(cap, how)
                continue
            results += [_not_exact_if_floats(r, _symbols_of(step), floated_all) for r in res.results()]
            checked[step.role] = (step, res)
        decay = None
        link = getattr(self.decay, "link", "decay on the region (V̇ ≤ −c̃V^p, envelope)")
        if self.decay is not None and all(r in checked and checked[r][1].status.is_proof
                                          for r in ("lower", "upper", "vdot")):
            progress(f"{self.qualified_name}: {getattr(self.decay, 'link', 'the decay on the region')}")
            out, how = _capped(cap, lambda: self.decay.certify(checked, everything, budget=None, progress=progress))
            rows, status, detail = ([], Status.UNDECIDED, _cut_text(cap, how, "link")) if how else out
            if not rows and not status.is_proof:  # a refuted or undecided conclusion is a result too (exit code)
                rows = [Result("region", getattr(self.decay, "link", "decay on the region"), status, None, detail)]
            results += rows
            decay = Link(link, status, detail)
        elif self.decay is not None and cut:
            decay = Link(link, Status.UNDECIDED, "the budget was spent before this link")
        return _StepsRun(results, checked, cut, decay)

    def _search(self, values, chosen, results, run, definite, upper, cap, progress):
        """``(choices, run)`` at the choices the constants job finds when the documented ones do not close
        the chain (the hypotheses and V̇ proved, no choice set by the user, nothing cut by the budget);
        ``(chosen, run)`` marked "at the searched choices" when it finds none; None when no search applies."""
        job = self.constants
        search = getattr(job, "search_choices", None)
        free = list(getattr(job, "free", None) or {})
        if search is None or not getattr(job, "steps", False) or any(k in values for k in free) or run.cut:
            return None
        links = self.chain([*results, *run.results], definite=definite, upper=upper, steps=run.checked,
                           decay=run.decay)
        bad = [link for link in links if link.name != "conclusion" and (link.status is None
                                                                       or not link.status.is_proof)]
        if not bad or bad[0].name in ("hypotheses", "V̇ along the system"):
            return None
        first = bad[0]
        why = f"{first.name}: {first.status or 'missing'}"
        shown = ", ".join(f"{k} = {v}" for k, v in chosen.items() if k in free)
        progress(f"{self.qualified_name}: the documented choices do not close the chain ({why}); searching "
                 + ", ".join(free))
        everything = self.parameters.resolve(dict(values), use_defaults=True)
        out, how = _capped(cap, lambda: search(self.qualified_name, everything, progress=progress))
        found, detail = out if not how else (None, _cut_text(cap, how, "search"))
        if found is None:
            row = Result("region", "choices", Status.UNDECIDED, None,
                         f"the documented choices ({shown}) do not close the chain ({why}); the search of "
                         f"{', '.join(free)} found none that does: {detail}")
            return chosen, dataclasses.replace(run, results=[*run.results, row], at="the searched choices")
        found = {k: str(v) for k, v in found.items()}
        again = self._steps_run({**chosen, **found, **dict(values)}, cap, progress)
        row = Result("region", "choices", Status.ESTIMATED, dict(found),
                     f"the documented choices ({shown}) do not close the chain ({why}); the chain is checked at "
                     f"the choices found by the search ({', '.join(f'{k} = {v}' for k, v in found.items())}): "
                     f"{detail}")
        return {**chosen, **found}, dataclasses.replace(again, results=[row, *again.results],
                                                        at="the searched choices")

    def chosen(self, values: Mapping, *, box: Mapping | None = None) -> dict:
        """The proof's free choices at these values: the fixed ``choices``, or those its callable finds.

        A callable ``choices(resolved)`` gets the resolved values (the given ones and the
        defaults) and returns the choices as exact strings; values the user gives win.  Over a
        box (name → (lo, hi) of scalar parameters) a callable that takes ``box=`` picks choices
        for every point of it.
        """
        if not callable(self.choices):
            return dict(self.choices)
        resolved = self.parameters.resolve(dict(values), use_defaults=True)
        import inspect

        try:
            takes_box = "box" in inspect.signature(self.choices).parameters
        except (TypeError, ValueError):
            takes_box = False
        found = self.choices(resolved, box=dict(box)) if box and takes_box else self.choices(resolved)
        return {k: v for k, v in dict(found).items() if k not in values}

    def shown(self, values: Mapping, chosen: Mapping | None = None) -> dict:
        """The parameters the theorem uses (its system, functional, hypotheses, claims and steps), shown.

        A paper's registry holds the parameters of all its theorems; a report lists only
        those this theorem's statements are written in.
        """
        used: set = set()
        for statement in (*self.hypotheses, *self.claims, *self.printed, *self.bounds, *self.steps):
            used |= _symbols_of(statement)
        exprs = [term.expr for eq in self.system.equations for term in eq.terms]
        if self.functional is not None:
            exprs.append(self.functional.expr)
        import sympy
        from sympy.core.function import AppliedUndef

        for e in exprs:
            e = sympy.sympify(e) if not isinstance(e, sympy.MatrixBase) else e
            used |= e.free_symbols | {a.func for a in e.atoms(AppliedUndef)}
        P = self.parameters
        out = {}
        for name, value in values.items():
            atoms = set(P[name].substitution(value))
            if atoms & used or name in (chosen if chosen is not None else
                                        {} if callable(self.choices) else self.choices):
                out[name] = _show(value)
        return out

    def _verdict(self, results, definite=None, upper=None, steps=None, decay=None, cut=None, at=None) -> str:
        if at is None and self.steps and self.choices:
            at = "these choices"
        text = theorem_verdict(self.chain(results, definite=definite, upper=upper, steps=steps, decay=decay,
                                          cut=cut), at=at)
        if decay is not None and text.startswith("established") and decay.status is not None \
                and decay.status.is_proof:
            text += f"; on the certified region: {decay.detail}"
        by_name = {r.name: r for r in results}
        printed = [by_name[c.name] for c in self.printed if c.name in by_name]
        if printed:
            text += "; the paper's printed formulas (findings, not links of the chain): " + ", ".join(
                f"{r.name} {r.status}" for r in printed)
        return text

    def chain(self, results, *, definite: Mapping | None = None, upper=None, steps: Mapping | None = None,
              decay: "Link | None" = None, cut: Mapping | None = None) -> tuple:
        """The links from the functional to the conclusion, each with what was checked of it.

        Computed from the results, never from the author's ``unchecked`` list: a link
        holds only when a result of this run proves it (``exact`` or ``certified``)
        along this theorem's own system.

        Parameters
        ----------
        results : sequence of Result
            This run's results (hypotheses, identities, bound steps).
        definite : mapping, optional
            Bound-step name → the check that its bound φ / ψ is positive definite.
        upper : StepResult, optional
            The check of V ≤ U(‖x_t‖) (:func:`lkverify.certify.steps.quadratic_upper_bound`).
        steps : mapping, optional
            Role → (TermwiseBound, ChainResult) of the checked estimates V ≥ L, V ≤ U, V̇ ≤ W.
        decay : Link, optional
            The certified decay of the checked estimates (:class:`~lkverify.certify.steps.chain.Decay`).
        cut : mapping, optional
            Role → why the budget cut that step: its link is ``undecided``, never missing.

        Returns
        -------
        tuple of Link
        """
        by_name = {r.name: r for r in results}
        hyps = [by_name[h.name] for h in self.hypotheses if h.name in by_name]
        not_proved = [r for r in hyps if not r.status.is_proof]
        links = [Link("hypotheses", _combined([r.status for r in hyps]) if hyps else Status.EXACT,
                      "; ".join(f"{r.name} {r.status}: {r.detail}" for r in not_proved) if not_proved else
                      f"{len(hyps)} hypothes{'is' if len(hyps) == 1 else 'es'} on the parameters"
                      if hyps else "none declared")]
        own = [c for c in self.claims if isinstance(c, DerivativeClaim) and self.functional is not None
               and c.functional is self.functional]
        if self.functional is None:
            links.append(Link("V̇ along the system", None, "the theorem declares no functional"))
        elif not own:
            links.append(Link("V̇ along the system", None,
                              "no claim states V̇ of the theorem's functional along its system"))
        else:
            sts = [by_name[c.name].status for c in own if c.name in by_name]
            links.append(Link("V̇ along the system", _combined(sts),
                              ", ".join(f"{c.name}: {by_name[c.name].status}" for c in own if c.name in by_name)))
        definite = dict(definite or {})
        if self.steps:
            steps = dict(steps or {})
            for role, text in (("lower", "V ≥ L (bound step, term by term)"), ("upper", "V ≤ U (bound step, term by term)"),
                               ("vdot", "V̇ ≤ W on the region (bound step, term by term)")):
                if role in (cut or {}):
                    links.append(Link(text, Status.UNDECIDED, cut[role]))
                elif role not in steps:
                    links.append(Link(text, None, "no bound step of this theorem states it"))
                else:
                    step, res = steps[role]
                    links.append(Link(text, res.status, f"{step.name}: {res.detail}"))
            if self.decay is None:
                links.append(Link("decay on the region", None, "the theorem declares no decay link"))
            elif decay is None:
                links.append(Link(getattr(self.decay, "link", "decay on the region"), None,
                                  "not attempted: a bound step is not proved"))
            else:
                links.append(decay)
            return _concluded(links, results, own, [c.name for c in self.printed])
        links.append(Link("V ≤ U(‖x_t‖), U continuous, U(0) = 0", None if upper is None else upper.status,
                          "no bound step of this theorem checks it" if upper is None else upper.detail))
        for role, text in (("lower", "V ≥ φ(‖state‖), φ positive definite"),
                           ("decrease", "V̇ ≤ −ψ(‖state‖) on a stated region, ψ positive definite")):
            steps = [b for b in self.bounds if b.role == role and b.name in by_name]
            if not steps:
                links.append(Link(text, None, "no bound step of this theorem checks it"))
                continue
            parts = [by_name[b.name].status for b in steps] + [definite[b.name].status for b in steps
                                                               if b.name in definite]
            best = _best_step(steps, by_name, definite)
            links.append(Link(text, _combined(parts) if best is None else best[0], best[1] if best else
                              "; ".join(f"{b.name}: {by_name[b.name].status}"
                                        + (f", bound: {definite[b.name].detail}" if b.name in definite else "")
                                        for b in steps)))
        return _concluded(links, results, own, [c.name for c in self.printed])


def _stopped_by_hypotheses(hypotheses, results) -> str | None:
    """Why the chain stops after the hypotheses (the failed ones, with their margins), or None when none failed.

    >>> from lkverify.certify.hypotheses import Hypothesis
    >>> import sympy
    >>> k = sympy.Symbol("k")
    >>> _stopped_by_hypotheses([Hypothesis("k > 0", k)], [Result("hypothesis", "k > 0", Status.FAILED, -1, "margin -1")])
    'not checked: the hypothesis k > 0 failed (margin -1), so the chain stops at the hypotheses'
    """
    names = {h.name for h in hypotheses}
    failed = [r for r in results if r.kind == "hypothesis" and r.name in names and r.status is Status.FAILED]
    if not failed:
        return None
    return (f"not checked: the hypothes{'is' if len(failed) == 1 else 'es'} "
            + "; ".join(f"{r.name} failed ({r.detail})" for r in failed) + ", so the chain stops at the hypotheses")


def _left(deadline):
    """The seconds left of a deadline (None: unlimited), never below a millisecond."""
    r = deadline.remaining
    return None if r is None else max(r, 1e-3)


@dataclasses.dataclass(frozen=True)
class _StepsRun:
    """The bound steps and the decay of one run: rows, role → (step, result), role → why cut, the decay link."""

    results: list
    checked: dict
    cut: dict
    decay: "Link | None"
    at: str | None = None  # "the searched choices" after a search of the proof's choices


def _check_claim(claim, P, given, sub_given, deadline):
    """A claim at the given values; a user's function of t (or of ζ) is first kept as a symbol.

    An identity that holds for every function h(t) holds for the given one, and it is much
    cheaper to prove with h symbolic than with, say, (1+t)^(−6/5) substituted; only when it
    is not proved that way is it checked again with the function substituted.
    """
    from ..declare.parameters import ParameterKind

    if given:  # an identity for every value of the parameters holds for the given ones (proved once per process)
        left = _left(deadline)
        general = _cached_check(claim, {}, lambda: claim.check({}, values={}, budget=None if left is None else left / 2))
        if general.status is Status.EXACT:
            shown = ", ".join(f"{k} = {v}" for k, v in given.items())
            return dataclasses.replace(general, detail=f"proved for every value of the parameters, hence for {shown}: "
                                                       f"{general.detail}")
    functions = [k for k in given if P[k].kind in (ParameterKind.COEFFICIENT, ParameterKind.KERNEL)]
    if not functions:
        return _cached_check(claim, given, lambda: claim.check(sub_given, values=given, budget=_left(deadline)))
    rest = {k: v for k, v in given.items() if k not in functions}
    left = _left(deadline)
    general = _cached_check(claim, rest, lambda: claim.check(P.substitution(rest), values=rest,
                                                             budget=None if left is None else left / 2))
    if general.status is Status.EXACT:
        shown = ", ".join(f"{k} = {given[k]}" for k in functions)
        return dataclasses.replace(general, detail=f"proved for every {', '.join(functions)}, hence for {shown}: "
                                                   f"{general.detail}")
    return claim.check(sub_given, values=given, budget=_left(deadline))


_CLAIM_CACHE = Memo(1024)  # (claim, the values it was checked at) → a decided result: one proof per process


def _cached_check(claim, values: Mapping, check):
    """``check()`` once per claim and values in this process; only decided results (exact, failed) are kept.

    A claim's check is deterministic in its values (the identity is proved or refuted exactly),
    so a theorem run again at the same values — or, for a claim first proved with the user's
    functions symbolic, at another h or kernel — reuses it.
    """
    key = tuple(sorted((k, str(v)) for k, v in values.items()))
    hit = _CLAIM_CACHE.owned(claim, key)
    if hit is not None:
        return hit
    res = check()
    if res.status in (Status.EXACT, Status.FAILED):
        _CLAIM_CACHE.keep(claim, key, res)
    return res


def _show(value) -> str:
    import sympy

    if isinstance(value, sympy.MatrixBase):
        if value.is_diagonal() and value.shape[0] == value.shape[1]:
            return f"diag({','.join(str(x) for x in value.diagonal())})"
        if value.shape[1] == 1:
            return f"[{', '.join(str(x) for x in value)}]"
        return str(value.tolist())
    return str(value)


class Check(Item):
    """An item made of direct checks: callables ``check(values) → list of Result``.

    Used for statements of a proof that are not identities, e.g. a printed
    inequality step refuted at an exact witness.  ``constants`` is what
    ``lkverify constants`` runs for the item (a ConstantsJob, or an object with
    its ``goals``, ``run`` and ``plot``), as for :class:`Theorem`.

    Examples
    --------
    >>> from lkverify import Parameters
    >>> from lkverify.report.results import Result
    >>> P = Parameters(); k = P.scalar("k", default=1)
    >>> below3 = lambda v: [Result("bound", "k < 3", Status.EXACT if v["k"] < 3 else Status.FAILED, v["k"])]
    >>> item = Check("demo", parameters=P, checks=[below3], paper="mypaper")
    >>> rep = item.run()
    >>> rep.item, rep.parameters, [(r.name, r.status.value) for r in rep.results], rep.verdict
    ('mypaper.demo', {'k': '1'}, [('k < 3', 'exact')], 'every check holds')
    >>> rep = item.run({"k": "5"})
    >>> rep.verdict, rep.exit_code
    ('failed: k < 3', 1)
    """

    def __init__(self, name: str, *, parameters: Parameters, checks: Sequence[Callable], title: str = "",
                 paper: str = "", relevant: Sequence[str] | None = None, constants=None):
        if not name.isidentifier():
            raise InputError(f"item name must be an identifier, got {name!r}")
        self.name, self.title, self.paper = name, title, paper
        self.constants = constants
        self.relevant = tuple(relevant) if relevant is not None else None
        self._parameters = parameters
        self.checks = tuple(checks)

    @property
    def parameters(self) -> Parameters:
        return self._parameters

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = None,
            progress: Callable[[str], None] | None = None) -> Report:
        """Run every check on deterministic work limits; ``budget`` (seconds) is the caller's own cap."""
        from ..options import Budget, Deadline, work_limits

        everything = self.parameters.resolve(values or {}, use_defaults=True)
        results: list[Result] = []
        with work_limits():
            cap = Deadline(Budget.of(budget).seconds, cap=True)
            results += _checked_rows(self.checks, everything, cap)
        failed = [r.name for r in results if r.status is Status.FAILED]
        undecided = [r.name for r in results if r.status is Status.UNDECIDED]
        verdict = (f"failed: {', '.join(failed)}" if failed else f"undecided: {', '.join(undecided)}" if undecided
                   else "every check holds")
        return Report(self.qualified_name, self.shown(everything), tuple(results), verdict)

    def shown(self, values: Mapping) -> dict:
        return {k: _show(v) for k, v in values.items() if self.relevant is None or k in self.relevant}
