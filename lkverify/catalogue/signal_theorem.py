"""A theorem concluded by a signal argument (Barbalat, level sets, the comparison lemma), not Krasovskii's.

:class:`SignalTheorem` runs its hypotheses, the identities of its proof, and then the links of
its argument (:mod:`lkverify.certify.steps.signals`) in order, each decided along the theorem's
own system; the verdict is computed from the chain exactly as for :class:`~.items.Theorem`
(:func:`~.links.theorem_verdict`): "established" only when every link is exact or certified.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from ..errors import InputError
from ..report.results import Report, Result
from ..status import Status
from .items import Theorem, _show
from .links import Link, _combined, theorem_verdict
from .statements import _capped, _checked_rows, _cut_text

__all__ = ["SignalTheorem"]


class SignalTheorem(Theorem):
    """A theorem whose conclusion is reached by a chain of signal-argument links.

    Parameters
    ----------
    name : str
    system : System
        The closed loop every identity and link is derived along.
    hypotheses : sequence of callables ``values → list of Result``
        The theorem's hypotheses on the parameters (kind ``hypothesis``).
    derivations : sequence of callables ``values → list of Result``
        The identities of the proof (links "intermediate identities").
    argument : callable ``values → (links, references)``
        The links (objects with ``decide(facts) → Result``) at these values and the reference
        signals (coefficient name → function of t) the boundedness links may use.  A link whose
        Result has kind ``hypothesis`` is an *additional* hypothesis (derived where the paper's step
        is false, e.g. a bound on α the corrected step needs): the verdict of an established theorem
        says "under the additional hypotheses …" and names them.
    findings : sequence of callables ``values → list of Result``
        The paper's printed formulas compared with the derivation: reported, not links.
    conclusion : str
        What the theorem concludes (shown with the verdict when every link holds).
    derivations_link : str
        The name of the chain's link made of the derivations' results.
    relevant : sequence of str
        The parameters shown in the report.

    Examples
    --------
    ẋ = −kx with V = x²/2: V̇ = −kx², x bounded, x ∈ L2, ẋ bounded, so x → 0 when k > 0:

    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.signals import Barbalat, BoundedStates, Dissipation, LevelSet, SquareIntegrable
    >>> P = Parameters(); k = P.scalar("k", default=1); X = Vector("x", 1); x = X(t)[0]
    >>> sys_ = System([Equation(X, [Term(-k * x)])], parameters=P)
    >>> def argument(values):
    ...     V, q = x**2 / 2, sympy.Matrix([x])
    ...     kk = sympy.Matrix([[k]])
    ...     return [Dissipation(V, q, kk), LevelSet(V, (("x", q),), sympy.eye(1)), BoundedStates(),
    ...             SquareIntegrable("x", q, kk, storage=V), Barbalat("x")], {}
    >>> positive = lambda v: [Result("hypothesis", "k > 0", Status.EXACT if v["k"] > 0 else Status.FAILED,
    ...                               v["k"], f"k = {v['k']}")]
    >>> th = SignalTheorem("demo", system=sys_, hypotheses=[positive], argument=argument, conclusion="x → 0")
    >>> rep = th.run()
    >>> rep.verdict.split(" (")[0], rep.exit_code
    ('established: every link exact or certified', 0)
    >>> th.run({"k": "-1"}).verdict.split(";")[0]
    'failed: hypotheses (k > 0 failed: k = -1)'
    """

    def __init__(self, name: str, *, system, hypotheses: Sequence[Callable] = (), derivations: Sequence[Callable] = (),
                 argument: Callable, findings: Sequence[Callable] = (), conclusion: str = "", title: str = "",
                 paper: str = "", relevant: Sequence[str] | None = None, constants=None,
                 derivations_link: str = "identities of the proof"):
        if not name.isidentifier():
            raise InputError(f"item name must be an identifier, got {name!r}")
        if not callable(argument):
            raise InputError(f"theorem {name}: argument must be a callable values → (links, references), "
                             f"got {type(argument).__name__}")
        self.name, self.system, self.title, self.paper = name, system, title, paper
        self.functional, self.hypotheses, self.claims, self.printed, self.bounds = None, (), (), (), ()
        self.steps, self.decay, self.choices, self.unchecked, self.constants = (), None, {}, (), constants
        self.hypothesis_checks, self.derivations = tuple(hypotheses), tuple(derivations)
        self.findings, self.argument, self.conclusion = tuple(findings), argument, conclusion
        self.relevant = tuple(relevant) if relevant is not None else None
        self.derivations_link = derivations_link

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = None,
            progress: Callable[[str], None] | None = None, box=None, max_boxes: int | None = None) -> Report:
        """Hypotheses, identities, then every link of the argument; the verdict from the chain.

        ``budget`` (seconds) is the caller's own cap: a part it cuts is ``undecided``.
        """
        from ..certify.steps.signals import Facts
        from ..options import Budget, Deadline, work_limits

        if box is not None:
            raise InputError(f"--box: {self.qualified_name} is concluded by a signal argument, checked at one "
                             f"point of the parameters; run it without --box (boxes: the Krasovskii theorems)")
        say = progress or (lambda msg: None)
        everything = self.parameters.resolve(values or {}, use_defaults=True)
        results, links = [], []
        with work_limits():
            cap = Deadline(Budget.of(budget).seconds, cap=True)

            def rows(fns, what):
                return _checked_rows(fns, everything, cap, what, lambda msg: say(f"{self.qualified_name}: {msg}"))

            hyps = rows(self.hypothesis_checks, "hypotheses")
            bad = [r for r in hyps if not r.status.is_proof]
            links.append(Link("hypotheses", _combined([r.status for r in hyps]) if hyps else Status.EXACT,
                              "; ".join(f"{r.name} {r.status}: {r.detail}" for r in bad) if bad else
                              f"{len(hyps)} hypotheses on the parameters"))
            results += hyps
            if any(r.status is Status.FAILED for r in hyps):
                links.append(Link("conclusion", None, "not checked: a hypothesis failed"))
                verdict = theorem_verdict(links)
                return Report(self.qualified_name, self.shown(everything), tuple(results), verdict, (), tuple(links))
            idents = rows(self.derivations, "identities")
            results += idents
            if idents:
                links.append(Link(self.derivations_link, _combined([r.status for r in idents]),
                                  ", ".join(f"{r.name}: {r.status}" for r in idents)))
            say(f"{self.qualified_name}: the signal argument")
            built, how = _capped(cap, lambda: self.argument(everything))
            if how:
                links.append(Link("signal argument", Status.UNDECIDED, _cut_text(cap, how, "link")))
            else:
                chain, references = built
                facts = Facts(self.system, self.parameters.substitution(everything), references)
                for link in chain:
                    say(f"{self.qualified_name}: {link.name}")
                    res, how = _capped(cap, lambda: _decided(link, facts))
                    res = res if not how else Result("bound", link.name, Status.UNDECIDED, None,
                                                     _cut_text(cap, how, "link"))
                    results.append(res)
                    facts.links[res.name] = res.status     # a later link may rest on it (Follows)
                    links.append(Link(res.name, res.status, res.detail))
            findings = rows(self.findings, "the paper's printed formulas")
            results += findings
        ready = all(link.status is not None and link.status.is_proof for link in links)
        links.append(Link("conclusion", Status.EXACT if ready else None,
                          f"{self.conclusion}: follows from the links above" if ready else "rests on the links above"))
        verdict = theorem_verdict(links)
        extra = [r for r in results if r.kind == "hypothesis" and r not in hyps]
        if ready and extra:
            verdict += "; under the additional hypotheses (derived where the paper's step is false): " + "; ".join(
                f"{r.name} ({r.detail})" for r in extra)
        if ready and self.conclusion:
            verdict += f"; concluded: {self.conclusion}"
        if findings:
            verdict += "; the paper's printed formulas (findings, not links of the chain): " + ", ".join(
                f"{r.name} {r.status}" for r in findings)
        return Report(self.qualified_name, self.shown(everything), tuple(results), verdict, (), tuple(links))

    def shown(self, values: Mapping, chosen: Mapping | None = None) -> dict:
        return {k: _show(v) for k, v in values.items() if self.relevant is None or k in self.relevant}


def _decided(link, facts) -> Result:
    """``link.decide(facts)``; an expression the link's exact machinery cannot treat leaves it ``undecided``."""
    import sympy

    from ..errors import UnsupportedInput

    try:
        return link.decide(facts)
    except (UnsupportedInput, sympy.PolynomialError, sympy.CoercionFailed, NotImplementedError) as exc:
        return Result("bound", link.name, Status.UNDECIDED, None, f"not decided: {exc}")
