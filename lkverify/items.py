"""Catalogue items: a theorem with its system, functional, hypotheses and claims.

A proof module declares items; ``lkverify check`` runs them.

>>> import sympy
>>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t
>>> from lkverify.claims import DerivativeClaim, Hypothesis
>>> P = Parameters(); k = P.scalar("k", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-k * x(t)[0], text="-kx")])], parameters=P)
>>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")])
>>> th = Theorem("demo", system=sys, functional=V, hypotheses=[Hypothesis("k > 0", k)],
...              claims=[DerivativeClaim("Vdot", V, sys, [Term(-k * x(t)[0] ** 2, text="-kx²")])])
>>> report = th.run({"k": "2"})
>>> [(r.name, r.status.value) for r in report.results]
[('k > 0', 'exact'), ('Vdot', 'exact')]
>>> report.exit_code
0
"""

from __future__ import annotations

import dataclasses
import sys as _sys
from collections.abc import Callable, Mapping, Sequence

from .claims import DerivativeClaim, Hypothesis, IdentityClaim, MatrixHypothesis
from .functional import Functional
from .parameters import Parameters
from .results import Report, Result
from .status import Status
from .system import System

__all__ = ["Item", "Theorem", "Check"]


class Item:
    """Base class of catalogue items (anything ``lkverify check`` can run)."""

    name: str = ""
    title: str = ""
    paper: str = ""
    constants = None  # a lkverify.constants.ConstantsJob, for `lkverify constants`

    @property
    def qualified_name(self) -> str:
        return f"{self.paper}.{self.name}" if self.paper else self.name

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = 60.0,
            progress: Callable[[str], None] | None = None) -> Report:
        raise NotImplementedError

    def run_constants(self, values: Mapping[str, object] | None = None, *, budget: float = 120.0,
                      progress: Callable[[str], None] | None = None, goal: str | None = None) -> tuple[Report, dict]:
        """The ``constants`` job: certified constants, parameters, region and envelope.

        Raises
        ------
        InputError
            The item has no constants job, or the values are bad.
        """
        from .errors import InputError

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
        Steps of the proof this item does not check (reported in the verdict,
        so that a verdict never claims more than was checked).
    constants : ConstantsJob, optional
        What ``lkverify constants`` computes and certifies for this item.
    """

    def __init__(self, name: str, *, system: System, functional: Functional | None = None,
                 hypotheses: Sequence[Hypothesis] = (), claims: Sequence = (), title: str = "",
                 unchecked: Sequence[str] = (), paper: str = "", constants=None):
        if not name.isidentifier():
            raise ValueError(f"item name must be an identifier, got {name!r}")
        for c in claims:
            if not isinstance(c, (DerivativeClaim, IdentityClaim)):
                raise TypeError(f"item {name}: claims must be DerivativeClaim or IdentityClaim, got {type(c).__name__}")
        self.name = name
        self.system = system
        self.functional = functional
        self.hypotheses = tuple(hypotheses)
        self.claims = tuple(claims)
        self.title = title
        self.unchecked = tuple(unchecked)
        self.paper = paper
        self.constants = constants

    @property
    def parameters(self) -> Parameters:
        return self.system.parameters

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = 60.0,
            progress: Callable[[str], None] | None = None) -> Report:
        """Check the hypotheses (at the given values, else the paper's defaults) and the claims.

        Identity claims are checked with the *given* values substituted and every
        other parameter left symbolic, so an ``exact`` identity holds for all of them.

        Raises
        ------
        InputError
            Unknown parameter names or inadmissible values.
        """
        progress = progress or (lambda msg: None)
        P = self.parameters
        given = P.resolve(values or {}, use_defaults=False)
        everything = P.resolve(values or {}, use_defaults=True)
        results: list[Result] = []
        progress(f"{self.qualified_name}: hypotheses")
        sub_all = P.substitution(everything)
        for h in self.hypotheses:
            results.append(h.evaluate(sub_all))
        details = []
        sub_given = P.substitution(given)
        for k, claim in enumerate(self.claims):
            progress(f"{self.qualified_name}: identity {k + 1}/{len(self.claims)} {claim.name}")
            res = claim.check(sub_given, values=given, budget=budget)
            results.append(Result("identity", claim.name, res.status, res.to_json(),
                                  f"{claim.description + ': ' if claim.description else ''}{res.detail}"))
            if res.differences:
                details.append(res.as_text())
        return Report(self.qualified_name, {k: _show(v) for k, v in everything.items()}, tuple(results),
                      self._verdict(results), tuple(details))

    def _verdict(self, results) -> str:
        failed = [r.name for r in results if r.status is Status.FAILED]
        undecided = [r.name for r in results if r.status is Status.UNDECIDED]
        if failed:
            return f"failed: {', '.join(failed)}" + (f"; undecided: {', '.join(undecided)}" if undecided else "")
        if undecided:
            return f"undecided: {', '.join(undecided)}"
        n_h = sum(r.kind == "hypothesis" for r in results)
        n_i = sum(r.kind == "identity" for r in results)
        text = f"all checked results hold ({n_h} hypotheses, {n_i} identities; every one exact or certified)"
        if self.unchecked:
            text += "; the conclusion is not established here: not yet checked: " + "; ".join(self.unchecked)
        else:
            text += "; conclusion established"
        return text


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
    inequality step refuted at an exact witness.
    """

    def __init__(self, name: str, *, parameters: Parameters, checks: Sequence[Callable], title: str = "",
                 paper: str = "", relevant: Sequence[str] | None = None):
        if not name.isidentifier():
            raise ValueError(f"item name must be an identifier, got {name!r}")
        self.name, self.title, self.paper = name, title, paper
        self.relevant = tuple(relevant) if relevant is not None else None
        self._parameters = parameters
        self.checks = tuple(checks)

    @property
    def parameters(self) -> Parameters:
        return self._parameters

    def run(self, values: Mapping[str, object] | None = None, *, budget: float | None = 60.0,
            progress: Callable[[str], None] | None = None) -> Report:
        everything = self.parameters.resolve(values or {}, use_defaults=True)
        results: list[Result] = []
        for check in self.checks:
            results += check(everything)
        failed = [r.name for r in results if r.status is Status.FAILED]
        undecided = [r.name for r in results if r.status is Status.UNDECIDED]
        verdict = (f"failed: {', '.join(failed)}" if failed else f"undecided: {', '.join(undecided)}" if undecided
                   else "every check holds")
        return Report(self.qualified_name, self.shown(everything), tuple(results), verdict)

    def shown(self, values: Mapping) -> dict:
        return {k: _show(v) for k, v in values.items() if self.relevant is None or k in self.relevant}
