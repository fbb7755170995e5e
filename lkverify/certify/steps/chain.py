"""Term-by-term bound steps: ``lhs ≤ rhs`` with lhs a sum of labelled terms of V or of the exact V̇.

A :class:`TermwiseBound` takes its left-hand side from the model — the terms of the
functional (``lhs="V"``) or the terms of a structured V̇ that a
:class:`~lkverify.DerivativeClaim` proves equal to the exact derivative (``lhs="Vdot"``)
— never retyped.  Each term (or group of terms) gets a :class:`TermBound`: the stated
bound in measures and constants, and the rule that justifies it
(:mod:`lkverify.certify.steps.rules`).  The check:

1. every lhs term is covered exactly once;
2. each rule application is matched against its term and its side conditions decided;
   the stated bound must be the rule's or weaker by a structurally nonnegative
   remainder; a template constant is the certified supremum (its value replaces the
   constant's name in the bounds);
3. a term bound that is not proved is searched for an adversarial witness
   (:func:`lkverify.certify.steps.witnesses.find_witness`): found and rechecked in
   interval arithmetic → ``failed`` with the witness; otherwise ``undecided`` with the
   failing side condition.  The search does a fixed amount of work (the same result on
   every machine); only the budget passed to :meth:`TermwiseBound.check` cuts it, and then
   the term says "the budget was spent before this witness search finished".  A term
   bound that *is* proved is cross-examined by a cheap search (:data:`CROSS_EXAMINATION`):
   a rechecked witness against it is a bug of the rule and raises
   :class:`~lkverify.errors.RuleSoundnessError` (exit 3), never an ``exact`` row;
4. the bounds add up to rhs: rhs − Σ bounds (upper) is 0 or structurally ≥ 0 on the
   region.

The step is as strong as its weakest term: ``exact`` when every application is exact,
``certified`` when some rests on interval arithmetic, else ``failed`` / ``undecided``.
"""

from __future__ import annotations

import dataclasses
import time as _time
from collections.abc import Mapping, Sequence

import sympy

from ...declare.symbols import t as _t
from ...errors import InputError
from ...options import Deadline
from ...report.results import Kind, Result
from ...status import Status
from .measures import Measure, Region
from .rules import Application, Context, Rule, Young, nonnegative

__all__ = ["ChainResult", "Decay", "TermBound", "TermResult", "TermwiseBound", "lyapunov_steps"]

#: the cheap witness search run against every proved term bound (a fixed amount of work)
CROSS_EXAMINATION = {"starts": 2, "pieces": (("ends", "1/1000"),), "maxiter": 40, "seeds": 6, "cse": False}

def _constant_text(name, value, info) -> str:
    """``c = 5.636 (certified; estimate 5.608, gap 0.50 %)``."""
    est = (info or {}).get("estimate")
    if est is None or not est:
        return f"{name} = {float(value):.6g} (certified)"
    return f"{name} = {float(value):.6g} (certified; estimate {est:.6g}, gap {(float(value) - est) / abs(est):.2%})"


def _put(expr, constants: Mapping):
    """``expr`` with the symbols named like certified constants replaced by their (rational) values."""
    expr = sympy.sympify(expr)
    rep = {s_: sympy.Rational(constants[s_.name]) for s_ in expr.free_symbols if s_.name in constants}
    return expr.xreplace(rep)


_weakest = Status.weakest


@dataclasses.dataclass(frozen=True)
class TermBound:
    """One term (or group of terms) of lhs, its stated bound and the rule that justifies it.

    Parameters
    ----------
    terms : str or tuple of str
        Labels (``Term.text``) of the lhs terms bounded together.
    bound : sympy expression
        In measures, parameters and the step's constants.
    rule : Rule
    then : tuple of Young
        Rewrites applied to the rule's bound, in order (e.g. Young's inequality).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
    >>> V = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> tb = TermBound("xᵀMx", 3 * N**2, Rayleigh(x(t), M, eigenvalue=3, norm_squared=N**2))
    >>> tb.terms, tb.bound
    (('xᵀMx',), 3*n**2)
    >>> TermBound("xᵀMx", 3 * N**2, rule="Rayleigh")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: term bound ('xᵀMx',): rule: expected a rule of lkverify.certify.steps.rules, got str
    """

    terms: object
    bound: object
    rule: Rule
    then: tuple = ()

    def __post_init__(self):
        labels = (self.terms,) if isinstance(self.terms, str) else tuple(self.terms)
        object.__setattr__(self, "terms", labels)
        object.__setattr__(self, "bound", sympy.sympify(self.bound))
        if not isinstance(self.rule, Rule):
            raise InputError(f"term bound {labels}: rule: expected a rule of lkverify.certify.steps.rules, got "
                             f"{type(self.rule).__name__}")
        object.__setattr__(self, "then", tuple(self.then))


@dataclasses.dataclass(frozen=True)
class TermResult:
    """The check of one term bound.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
    >>> V = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> tb = TermBound("xᵀMx", 3 * N**2, Rayleigh(x(t), M, eigenvalue=3, norm_squared=N**2))
    >>> tr = TermwiseBound("V ≤ 3n²", V, sys_, "V", [tb], 3 * N**2, [n]).check(P.resolve({})).terms[0]
    >>> tr.statement, tr.status.value, tr.bound
    ('xᵀMx ≤ 3*n**2', 'exact', 3*n**2)
    >>> tr.detail
    'Rayleigh quotient (eigenvalue bound): 4 side conditions hold'
    """

    terms: tuple
    statement: str
    status: Status
    detail: str
    rule: str
    applications: tuple = ()
    witness: object = None
    bound: object = None

    def to_json(self) -> dict:
        return {"terms": list(self.terms), "statement": self.statement, "status": self.status.value,
                "detail": self.detail, "rule": self.rule,
                "applications": [a.to_json() for a in self.applications],
                "witness": None if self.witness is None else self.witness.to_json()}


@dataclasses.dataclass(frozen=True)
class ChainResult:
    """The check of a :class:`TermwiseBound`: per term, the sum, and the constants certified.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
    >>> V = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> tb = TermBound("xᵀMx", 3 * N**2, Rayleigh(x(t), M, eigenvalue=3, norm_squared=N**2))
    >>> res = TermwiseBound("V ≤ 3n²", V, sys_, "V", [tb], 3 * N**2, [n]).check(P.resolve({}))
    >>> res.status.value, res.detail
    ('exact', 'proved term by term (1 bounds, every application exact); Σ bounds = rhs')
    >>> [(row.kind.value, row.name) for row in res.results()]      # one row per term, then the step
    [('bound', 'V ≤ 3n²: xᵀMx ≤ 3*n**2'), ('bound', 'V ≤ 3n²')]
    """

    name: str
    status: Status
    detail: str
    terms: tuple
    constants: Mapping
    rhs: object = None
    seconds: float = 0.0
    box_used: bool = False  # a rule's result depends on the ends of the parameter box (a template over it)

    @property
    def rule(self) -> str:
        return "term by term"

    def results(self) -> list[Result]:
        """Report rows of kind ``bound``: one per term, then the step."""
        rows = []
        for tr in self.terms:
            rows.append(Result(Kind.BOUND, f"{self.name}: {tr.statement}", tr.status,
                               {"rule": tr.rule, "witness": None if tr.witness is None else tr.witness.to_json(),
                                "applications": [a.to_json() for a in tr.applications]}, tr.detail,
                               label=f"{self.name}: {' + '.join(tr.terms)}"))
        rows.append(self.to_result())
        return rows

    def to_result(self) -> Result:
        return Result(Kind.BOUND, self.name, self.status,
                      {"rule": self.rule, "rhs": str(self.rhs), "constants": {k: float(v) for k, v in
                                                                              self.constants.items()},
                       "terms": [t.to_json() for t in self.terms], "seconds": self.seconds}, self.detail)


@dataclasses.dataclass(frozen=True)
class TermwiseBound:
    """``lhs ≤ rhs`` (or ``≥``) proved term by term on a region.

    Parameters
    ----------
    name : str
    functional : Functional
    system : System
    lhs : {"V", "Vdot", "terms"}
    bounds : sequence of TermBound
    rhs : sympy expression
        In the measures' symbols, parameters and the constants of Template rules.
    measures : sequence of Measure
    relation : {"<=", ">="}
    region : Region, optional
    derivation : DerivativeClaim, optional
        For ``lhs="Vdot"``: the claim whose structured terms are lhs (proved exact by it).
    role : {None, "lower", "upper", "vdot"}
        What the step is in a theorem's chain: V ≥ L, V ≤ U, V̇ ≤ W.
    definitions : mapping
        Named constants of the bounds: symbol → expression in the parameters or a
        callable ``f(values)`` (an eigenvalue of a matrix parameter), evaluated exactly
        at the checked values.
    witness_seconds : float
        Accepted for backwards compatibility and ignored: the witness search of a term
        does a fixed amount of work (``witness_starts`` local searches on each grid of
        ``witness_pieces``), so its result is the same on every machine; only the budget
        passed to :meth:`check` (the user's wall-clock cap) can cut it, and a cut search
        leaves the term ``undecided`` saying so.
    witness_starts : int
        Random local searches per piece grid of the witness search of an unproved term.
    witness_pieces : tuple of int
        The equal-piece grids of that search (structured grids are added).
    cross_examine : bool
        Run a cheap witness search also on every term a rule proved
        (:data:`CROSS_EXAMINATION`); a rechecked witness there is a bug of the rule:
        :class:`~lkverify.errors.RuleSoundnessError`.
    part : tuple of str, optional
        Only these labelled terms form lhs (a step about part of V̇, as papers print them).
    exists : tuple of Symbol
        Constants the step only claims to exist ("c7 > 0"): a witness must refute the
        step for every nonnegative value of them.
    terms : tuple of Term
        For ``lhs="terms"``: labelled terms computed from the model by the caller (e.g. the
        β-part of a derivative from :func:`~lkverify.symbolic.derivative.derivative_along`).
    witness_time : number, optional
        For time-varying systems: the time t at which witnesses are sought (every t ≥ t0
        is admissible, so a violation at one is a refutation).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
    >>> V = Functional([Term((x(t).T * M * x(t))[0], text="xᵀMx")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> tb = TermBound("xᵀMx", 3 * N**2, Rayleigh(x(t), M, eigenvalue=3, norm_squared=N**2))
    >>> step = TermwiseBound("V ≤ 3n²", V, sys_, "V", [tb], 3 * N**2, [n])
    >>> step.check(P.resolve({})).status.value
    'exact'
    >>> step.with_bounds(rhs=2 * N**2).check(P.resolve({})).detail
    'the term bounds do not add up to the right-hand side: rhs − Σ bounds = -n**2 is not shown ≥ 0'
    >>> low = TermBound("xᵀMx", 2 * N**2, Rayleigh(x(t), M, eigenvalue=2, norm_squared=N**2))   # 2 < λ_max
    >>> tr = step.with_bounds(bounds=[low], rhs=2 * N**2, witness_seconds=1).check(P.resolve({})).terms[0]
    >>> tr.status.value, tr.witness.violation[0] > 0                # refuted near x = (1, 1)/√2
    ('failed', True)
    """

    name: str
    functional: object
    system: object
    lhs: str
    bounds: Sequence
    rhs: object
    measures: Sequence
    relation: str = "<="
    region: Region | None = None
    derivation: object = None
    role: str | None = None
    definitions: Mapping = dataclasses.field(default_factory=dict)
    witness_seconds: float = 5.0
    part: tuple | None = None
    exists: tuple = ()
    terms: tuple = ()
    witness_time: object = None
    witness_starts: int = 24
    witness_pieces: tuple = (1, 2, 3, 5)
    cross_examine: bool = True

    def __post_init__(self):
        problems = []
        if self.lhs not in ("V", "Vdot", "terms"):
            problems.append(f"lhs: expected 'V', 'Vdot' or 'terms', got {self.lhs!r}")
        if self.lhs == "terms" and not self.terms:
            problems.append("lhs 'terms' needs terms= the labelled terms computed from the model")
        if self.lhs == "Vdot" and self.derivation is None:
            problems.append("lhs 'Vdot' needs derivation= the DerivativeClaim of the structured V̇ (its terms are "
                            "the lhs)")
        if self.relation not in ("<=", ">="):
            problems.append(f"relation: expected '<=' or '>=', got {self.relation!r}")
        if self.role not in (None, "lower", "upper", "vdot"):
            problems.append(f"role: expected None, 'lower', 'upper' or 'vdot', got {self.role!r}")
        if not all(isinstance(m, Measure) for m in self.measures):
            problems.append("measures: expected Measure objects (lkverify.certify.steps.measures)")
        if not all(isinstance(b, TermBound) for b in self.bounds):
            problems.append("bounds: expected TermBound objects")
        if problems:
            raise InputError(f"bound step {self.name}: " + "; ".join(problems))
        object.__setattr__(self, "bounds", tuple(self.bounds))
        object.__setattr__(self, "measures", tuple(self.measures))
        object.__setattr__(self, "rhs", sympy.sympify(self.rhs))

    @property
    def direction(self) -> str:
        return "upper" if self.relation == "<=" else "lower"

    def lhs_terms(self) -> list:
        """The labelled terms of lhs (the functional's, or the derivation's structured V̇)."""
        terms = list(self.functional.terms if self.lhs == "V" else self.terms if self.lhs == "terms"
                     else self.derivation.terms)
        if self.part is not None:
            unknown = [p for p in self.part if p not in {t_.text for t_ in terms}]
            if unknown:
                raise InputError(f"bound step {self.name}: part: no term is labelled {unknown[0]!r}; labels: "
                                 + ", ".join(t_.text for t_ in terms))
            terms = [t_ for t_ in terms if t_.text in self.part]
        return terms

    def with_bounds(self, **changes) -> "TermwiseBound":
        """A copy with fields replaced (for mutation tests: ``step.with_bounds(region=...)``)."""
        return dataclasses.replace(self, **changes)

    def named_constants(self, values: Mapping) -> dict:
        """The named constants of :attr:`definitions` at the values (symbol → exact value)."""
        sub = self.system.parameters.substitution(values)
        out = {}
        from ...declare.parameters import apply_substitution

        for sym, d in self.definitions.items():
            v = d(values) if callable(d) and not isinstance(d, sympy.Basic) else apply_substitution(sympy.sympify(d), sub)
            out[sym] = sympy.sympify(v)
        return out

    # -- checking ------------------------------------------------------------------------
    def check(self, values: Mapping, *, budget=None, search: bool = True,
              parameter_box: Mapping | None = None) -> ChainResult:
        """Check every term bound and the sum at resolved parameter values.

        ``parameter_box`` (symbol → (lo, hi)): the values hold these symbols for boxed
        parameters (:mod:`lkverify.certify.boxes`); what is proved then holds at every point
        of the box, template suprema are taken over the chart × the box, and the witness
        searches run at the box's centre (a witness there refutes the step for the box).
        """
        start = _time.perf_counter()
        measures = {m.name: m for m in self.measures}
        from ...options import Budget

        deadline = Budget.of(budget).deadline() if budget is not None else None
        ctx = Context(self.system, values, measures, self.region, budget=deadline, parameter_box=parameter_box)
        ctx.constants = self.named_constants(values)
        terms = self.lhs_terms()
        by_label = {}
        for term in terms:
            by_label.setdefault(term.text, []).append(term)
        covered: dict = {}
        problems = []
        for tb in self.bounds:
            for label in tb.terms:
                if label not in by_label:
                    problems.append(f"no lhs term is labelled {label!r}")
                covered[label] = covered.get(label, 0) + 1
        missing = [t.text for t in terms if t.text not in covered]
        twice = [label for label, n in covered.items() if n > 1]
        if missing:
            problems.append(f"lhs terms without a bound: {', '.join(missing)}")
        if twice:
            problems.append(f"lhs terms bounded twice: {', '.join(twice)}")
        if problems:
            return ChainResult(self.name, Status.UNDECIDED, "; ".join(problems), (), {}, self.rhs,
                               _time.perf_counter() - start)
        constants: dict = {}
        results = []
        sym = "≤" if self.direction == "upper" else "≥"
        for tb in self.bounds:
            expr = sum((term.expr for label in tb.terms for term in by_label[label]), sympy.S.Zero)
            statement = f"{' + '.join(tb.terms)} {sym} {tb.bound}"
            results.append(self._check_term(tb, expr, statement, ctx, constants, search))
        total = sum((_put(tb.bound, constants) for tb in self.bounds), sympy.S.Zero)
        rhs = ctx.at(_put(self.rhs, constants))
        slack = sympy.expand(ctx.at(rhs - total) if self.direction == "upper" else ctx.at(total - rhs))
        sum_ok = slack == 0 or nonnegative(slack)
        statuses = [r.status for r in results]
        if not sum_ok:  # numeric coefficients of monomials in the measures: their signs, exact or in arb
            sum_ok, how = _coefficients_nonnegative(slack, {m.symbol for m in self.measures})
            statuses.append(how)
        worst = _weakest(statuses)
        if not sum_ok:
            status = Status.UNDECIDED if worst.is_proof else worst
            detail = (f"the term bounds do not add up to the right-hand side: rhs − Σ bounds = {slack} is not "
                      f"shown ≥ 0")
        elif worst.is_proof:
            status = worst
            detail = (f"proved term by term ({len(results)} bounds, every application {status}); "
                      f"Σ bounds {'=' if slack == 0 else sym} rhs")
        else:
            status = worst
            bad = [r for r in results if r.status is worst]
            detail = f"{len(bad)} of {len(results)} term bounds {worst}: " + "; ".join(
                f"{r.statement}: {r.detail}" for r in bad[:3])
        return ChainResult(self.name, status, detail, tuple(results), constants, rhs, _time.perf_counter() - start,
                           box_used=ctx.box_used)

    def _check_auto(self, tb: TermBound, expr, statement, ctx: Context, constants: dict, search: bool) -> TermResult:
        """``rule=Auto()``: each candidate checked as if named, the first that proves the step wins; otherwise
        the witness search decides (failed) or the step stays undecided with what every candidate said."""
        from .rules import Printed

        tried = []
        for rule in tb.rule.candidates(expr, ctx.at(_put(tb.bound, constants)), ctx):
            trial = dict(constants)
            res = self._check_term(dataclasses.replace(tb, rule=rule), expr, statement, ctx, trial, False)
            if res.status.is_proof:
                constants.update(trial)
                note = f" (tried first: {', '.join(name for name, _ in tried)})" if tried else ""
                return dataclasses.replace(res, rule=f"{res.rule}, found by Auto",
                                           detail=f"found by Auto: {res.detail}{note}")
            tried.append((rule.name, res.detail.split("; no witness search")[0]))
        res = self._check_term(dataclasses.replace(tb, rule=Printed("Auto: no candidate rule proved it")), expr,
                               statement, ctx, constants, search)
        said = "; ".join(f"{name}: {why}" for name, why in tried)
        return dataclasses.replace(res, rule="Auto (no rule found)",
                                   detail=f"{res.detail}; Auto tried {len(tried)} rules: {said}")

    def _check_term(self, tb: TermBound, expr, statement, ctx: Context, constants: dict, search: bool) -> TermResult:
        if getattr(tb.rule, "finds_rule", False):  # Auto (by its marker: one class however it was imported)
            return self._check_auto(tb, expr, statement, ctx, constants, search)
        direction = self.direction
        apps: list[Application] = []
        ctx.certified = {}
        try:
            app = tb.rule.apply(expr, direction, ctx)
        except InputError as exc:
            return TermResult(tb.terms, statement, Status.UNDECIDED, f"the rule does not apply: {exc}",
                              tb.rule.name)
        apps.append(app)
        bound = app.bound
        for rewrite in tb.then:
            if bound is None:
                break
            if getattr(rewrite, "directional", False):
                nxt = rewrite.rewrite(bound, ctx, direction)
            elif hasattr(rewrite, "rewrite"):
                nxt = rewrite.rewrite(bound, ctx)
            else:
                nxt = rewrite.apply(bound, direction, ctx)
            apps.append(nxt)
            bound = nxt.bound
        if ctx.certified:  # constants certified inside the rule's norm trees
            apps[0] = dataclasses.replace(apps[0], constants=tuple(apps[0].constants) + tuple(
                (name, value, info) for name, (value, info) in ctx.certified.items()))
        for a in apps:
            for name, value, _ in a.constants:
                constants[name] = value
        stated = ctx.at(_put(tb.bound, constants))
        status = _weakest(a.status for a in apps)
        rule = " then ".join(a.rule for a in apps)
        detail = next((a.detail for a in apps if not a.status.is_proof), None)
        if status.is_proof and bound is not None:
            rest = sympy.expand(stated - bound if direction == "upper" else bound - stated)
            if not (rest == 0 or nonnegative(rest)):  # 6875^(1/5) and 5^(4/5)·11^(1/5): one number, two forms
                rest = sympy.expand(_prime_powers(rest))
            if not (rest == 0 or nonnegative(rest)):
                status = Status.UNDECIDED
                detail = (f"the stated bound is not the rule's: the rule gives {bound}, the step states {stated} "
                          f"(difference {rest} not shown ≥ 0)")
        if status.is_proof:
            constant_note = "; ".join(_constant_text(n, v, info) for a in apps for n, v, info in a.constants)
            detail = f"{rule}: {len(sum((list(a.conditions) for a in apps), []))} side conditions hold" + (
                f"; {constant_note}" if constant_note else "")
            if self.cross_examine:
                self._cross_examine(tb, statement, rule, status, stated, ctx)
            return TermResult(tb.terms, statement, status, detail, rule, tuple(apps), bound=bound)
        witness, outcome = None, None
        if search:
            # constants only claimed to exist stay symbols: the witness refutes every value of them
            names = {str(c) for c in self.exists}
            keep = {k: v for k, v in constants.items() if k not in names}
            saved = ctx.constants
            ctx.constants = {k: v for k, v in (saved or {}).items() if str(k) not in names}
            generic = ctx.at(_put(tb.bound, keep))
            ctx.constants = saved
            at, where = _search_point(ctx)
            outcome = self._witness(self._signed_terms(tb, at), sympy.sympify(generic).xreplace(_rationals(ctx)), at)
            witness = None if outcome is None else outcome.witness
        if witness is not None:
            from .rules import Printed

            terms = ", ".join(f"{k} = {v:.4g}" for k, v in witness.terms.items() if isinstance(v, float))
            why = "" if isinstance(tb.rule, Printed) else f"; the rule's check: {detail}"
            return TermResult(tb.terms, statement, Status.FAILED,
                              f"refuted{where}: {witness.text()}" + (f"; at the witness: {terms}" if terms else "")
                              + why, rule, tuple(apps), witness, bound)
        if outcome is None:
            searched = "no witness search (search=False)" if not search else "no witness search (outside its family)"
        elif not outcome.complete:
            searched = "undecided: the budget was spent before this witness search finished"
        else:
            searched = outcome.text()
        return TermResult(tb.terms, statement, Status.UNDECIDED, f"not proved ({detail}); {searched}", rule,
                          tuple(apps), None, bound)

    def _signed_terms(self, tb: TermBound, ctx: Context) -> list:
        """The lhs terms of a term bound at the values, negated for a lower bound (the search refutes ≤)."""
        from ...declare.terms import Term

        sign = 1 if self.direction == "upper" else -1
        return [Term(sign * ctx.at(term.expr), text=term.text) for label in tb.terms
                for term in self.lhs_terms() if term.text == label]

    def _cross_examine(self, tb: TermBound, statement, rule, status, stated, ctx: Context) -> None:
        """A cheap witness search against a proved term bound; a rechecked witness is a bug of the rule.

        The bound searched is the stated one with the constants the rules certified (what the
        result row calls proved); constants only claimed to exist that no rule valued stay
        symbols (the witness must then refute every value).  Raises
        :class:`~lkverify.errors.RuleSoundnessError` naming the rule and the witness.
        """
        from ...errors import RuleSoundnessError

        if isinstance(ctx.budget, Deadline) and ctx.budget.expired:
            return
        used = sympy.sympify(stated).free_symbols  # only the measures the bound is written in: each costs a model
        measures = [m for m in self.measures if m.symbol in used]
        at, where = _search_point(ctx)  # over a box: at its centre (the bound is proved for every point)
        outcome = self._witness(self._signed_terms(tb, at), sympy.sympify(stated).xreplace(_rationals(ctx)), at,
                                measures=measures, **CROSS_EXAMINATION)
        if outcome is not None and outcome.witness is not None:
            raise RuleSoundnessError(
                f"the rule {rule!r} proved {self.name}: {statement} ({status.value}), but the witness "
                f"{outcome.witness.text()}{where} refutes it (rechecked in interval arithmetic); a bug of that rule",
                rule=rule, witness=outcome.witness)

    def _witness(self, expr, stated, ctx: Context, measures=None, **limits):
        """The SearchOutcome of the witness search of ``expr ≤ stated`` (None: outside the witness family).

        No wall clock unless the check has a budget (then its deadline cuts the search).
        """
        from .witnesses import find_witness

        limits = {"starts": self.witness_starts, "pieces": self.witness_pieces, **limits}
        lhs = expr  # labelled terms, already signed for an upper bound
        rhs = ctx.at(stated if self.direction == "upper" else -stated)
        measure_syms = {m.symbol for m in self.measures}
        exists = {sympy.Symbol(str(c)) if isinstance(c, str) else c for c in self.exists}
        lhs_syms = set().union(*[sympy.sympify(term.expr).free_symbols for term in lhs]) if lhs else set()
        free = (lhs_syms | sympy.sympify(rhs).free_symbols) - measure_syms - exists - {_t}
        nonneg = tuple(s_ for s_ in free if s_.is_nonnegative)  # free positive parameters: every value
        budget = ctx.budget if isinstance(ctx.budget, Deadline) and ctx.budget.seconds is not None else None
        try:
            return find_witness(lhs, rhs, system=self.system, values=ctx.values,
                                measures=list(self.measures if measures is None else measures),
                                region=self.region, exists=tuple(exists), nonnegative=nonneg, budget=budget,
                                **limits, **({} if self.witness_time is None else {"time": self.witness_time}))
        except InputError:
            return None


def _rationals(ctx: Context) -> dict:
    """The boxed symbols → the box's centre (empty without a parameter box)."""
    return ctx.box_center()


def _search_point(ctx: Context):
    """(context, text): where the witness searches run — the context itself, or its box's centre."""
    if not ctx.parameter_box:
        return ctx, ""
    centre = ctx.box_center()
    return ctx.at_point(centre), " at the centre " + ", ".join(f"{s_} = {v}" for s_, v in centre.items()) + \
        " of the parameter box"


def lyapunov_steps(functional, system, lower, upper, vdot, measures, *, region=None, definitions=None,
                   derivation=None, vdot_terms=(), **options) -> tuple:
    """The three bound steps of an LK proof, V ≥ L, V ≤ U and V̇ ≤ W, each rhs the sum of its term bounds.

    Parameters
    ----------
    functional, system
        The theorem's functional and system.
    lower, upper, vdot : sequence of TermBound
        The term bounds of V ≥ L, V ≤ U and V̇ ≤ W; L, U, W are their sums.
    measures : sequence of Measure
    region : Region, optional
    definitions : mapping, optional
        Named constants of the bounds (see :class:`TermwiseBound`).
    derivation : DerivativeClaim, optional
        V̇ ≤ W bounds the structured terms of this claim (``lhs="Vdot"``) …
    vdot_terms : tuple of Term, optional
        … or these terms computed from the model (``lhs="terms"``).
    **options
        Passed to each :class:`TermwiseBound` (``witness_time``, ``witness_seconds``).

    Returns
    -------
    (TermwiseBound, TermwiseBound, TermwiseBound)
        Roles ``lower``, ``upper``, ``vdot``: a Theorem's ``steps``.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import DerivativeClaim, Equation, Functional, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, TermBound, lyapunov_steps, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> V = Functional([Term((x(t).T * x(t))[0] / 2, text="½‖x‖²")])
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> vdot = DerivativeClaim("Vdot", V, sys_, [Term(-(x(t).T * x(t))[0], text="−‖x‖²")])
    >>> half = lambda c: [TermBound("½‖x‖²", c * N**2, Rayleigh(x(t), sympy.eye(2) / 2, eigenvalue=c,
    ...                                                             norm_squared=N**2))]
    >>> steps = lyapunov_steps(V, sys_, half(sympy.Rational(1, 2)), half(sympy.Rational(1, 2)),
    ...                        [TermBound("−‖x‖²", -N**2, Rayleigh(x(t), -sympy.eye(2), eigenvalue=-1,
    ...                                                           norm_squared=N**2))], [n], derivation=vdot)
    >>> [(s.name, s.role, s.rhs) for s in steps]
    [('V ≥ L', 'lower', n**2/2), ('V ≤ U', 'upper', n**2/2), ('V̇ ≤ W', 'vdot', -n**2)]
    >>> [s.check(P.resolve({})).status.value for s in steps]
    ['exact', 'exact', 'exact']
    """
    def total(bounds):
        return sum((tb.bound for tb in bounds), sympy.S.Zero)

    common = dict(region=region, definitions=dict(definitions or {}), **options)
    vdot_lhs = dict(terms=tuple(vdot_terms)) if vdot_terms else dict(derivation=derivation)
    return (TermwiseBound("V ≥ L", functional, system, "V", tuple(lower), total(lower), tuple(measures),
                          relation=">=", role="lower", **common),
            TermwiseBound("V ≤ U", functional, system, "V", tuple(upper), total(upper), tuple(measures),
                          relation="<=", role="upper", **common),
            TermwiseBound("V̇ ≤ W", functional, system, "terms" if vdot_terms else "Vdot", tuple(vdot), total(vdot),
                          tuple(measures), relation="<=", role="vdot", **vdot_lhs, **common))


# the conclusions of a chain live in steps.conclusions (they use this module's helpers)
from .conclusions import (Decay, Krasovskii, coefficient_sign, _coefficients_nonnegative,  # noqa: E402,F401
                          _positive_rate_point, _prime_powers, collect_monomials)
