"""Suprema and sign proofs on boxes: :func:`sup_bound`, :func:`certify_nonpositive`, :func:`certify_positive`.

Every job has two halves: an estimate (:mod:`lkverify.certify.estimate`,
status ``estimated``, a lower bound of the supremum) and a certificate (the
branch and bound of :mod:`lkverify.certify.engine`, a proved upper bound,
status ``certified``).  Options come as objects: a
:class:`~lkverify.options.Budget` (seconds, boxes) and an
:class:`~lkverify.options.Accuracy` (rel_gap, abs_gap, starts, seed).

Examples
--------
>>> import sympy
>>> x = sympy.Symbol("x")
>>> res = sup_bound(x * sympy.exp(-x), {x: (0, 5)})
>>> res.status
<Status.CERTIFIED: 'certified'>
>>> res.lower <= float(sympy.exp(-1)) <= res.certified <= 1.01 * res.lower
True
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Mapping

import numpy as np

from ..errors import InputError
from ..options import Accuracy, Budget
from ..report.results import Kind, Result
from ..status import Status
from .engine import BranchAndBound, BranchProgress, Goal, Objective, Outcome, Refutation, Stop, enclosure_class
from .estimate import maximise
from .functions import sympify_expr
from .intervals import float_down
from .regions import parse_region

__all__ = [
    "CheckResult", "DEFAULT_BUDGET_BOXES", "DEFAULT_BUDGET_SECONDS", "SupResult", "certify_nonpositive",
    "certify_positive", "sup_bound",
]

_INF = math.inf
#: default budgets: a constant should certify in seconds; these are the ceilings
DEFAULT_BUDGET_BOXES = 200_000
DEFAULT_BUDGET_SECONDS = 30.0
#: the share of the time budget the estimate may take before the branch and bound starts
ESTIMATE_SHARE_SUP = 0.5
ESTIMATE_SHARE_DECIDE = 0.25
#: the best estimate candidates whose arb point values seed the proved lower bound
LOWER_CANDIDATES = 3


@dataclasses.dataclass(frozen=True)
class Limits:
    """A :class:`~lkverify.options.Budget` resolved against the defaults: seconds (``inf``: none) and boxes."""

    seconds: float
    boxes: int

    @classmethod
    def of(cls, budget: Budget | None) -> Limits:
        """The limits of ``budget`` (``None``: :data:`DEFAULT_BUDGET_SECONDS`, :data:`DEFAULT_BUDGET_BOXES`).

        Inside :func:`lkverify.options.work_limits` the seconds are no limit (only the boxes are).
        """
        from ..options import ceiling

        seconds = DEFAULT_BUDGET_SECONDS if budget is None else budget.seconds
        seconds = ceiling(None if seconds is None else float(seconds))
        return cls(_INF if seconds is None else seconds,
                   DEFAULT_BUDGET_BOXES if budget is None or budget.boxes is None else budget.boxes)

    def share(self, fraction: float, *, boxes: float = 1.0) -> Limits:
        """A part of these limits (at least one box)."""
        return Limits(self.seconds * fraction, max(1, int(self.boxes * boxes)))


def check_options(*, budget, accuracy, enclosure="both", progress=None) -> tuple:
    """Validate the option objects (all problems in one InputError); (Limits, Accuracy, Enclosure class)."""
    problems = []
    if budget is not None and not isinstance(budget, Budget):
        problems.append(f"budget: expected a lkverify.options.Budget or None, got {budget!r}; "
                        "pass e.g. Budget(seconds=10, boxes=50_000)")
    if accuracy is not None and not isinstance(accuracy, Accuracy):
        problems.append(f"accuracy: expected a lkverify.options.Accuracy or None, got {accuracy!r}; "
                        "pass e.g. Accuracy(rel_gap=1e-3)")
    if progress is not None and not callable(progress):
        problems.append(f"progress: expected a callable or None, got {progress!r}")
    try:
        strategy = enclosure_class(enclosure)
    except InputError as exc:
        problems.append(str(exc))
    if problems:
        raise InputError("; ".join(problems))
    return Limits.of(budget), accuracy or Accuracy(), strategy


def _fmt(x) -> str:
    if x is None:
        return "none"
    return f"{x:.6g}" if math.isfinite(x) else str(x)


def _json_float(x):
    if x is None:
        return None
    return x if math.isfinite(x) else str(x)


@dataclasses.dataclass(frozen=True)
class SupResult:
    """The supremum of an expression over a box (:func:`sup_bound`), or a best constant (:func:`best_constant`).

    Attributes
    ----------
    expr_text : str
        The expression bounded (for a best constant: the ratio lhs/template).
    variables : tuple of str
    estimate : float
        The best value found by sampling and local maximisation -- status
        ``estimated`` (a lower bound of the supremum up to float rounding,
        never a proof).
    maximiser : dict of str to float
        Where the estimate was found (inside the box).
    lower : float
        A proved lower bound of the supremum: the arb value at a point of the
        box, rounded down (``-inf`` if no point value was finite).
    certified : float or None
        A proved upper bound of the supremum (rounded up).  It is valid
        whatever ``status`` says -- also when a budget ran out -- unless it
        is ``None`` (not attempted) or ``inf`` (nothing proved).
    gap : float
        ``(certified − lower) / |lower|``.
    status : Status
        ``certified`` if the gap target was met, ``undecided`` if a budget ran
        out first, ``estimated`` if certification was not asked for.
    boxes : int
        Boxes evaluated by the branch and bound.
    seconds : float
    detail : str
    name : str
        For a best constant: its name (``""`` for a plain supremum).
    lhs_text, template_text : str
        For a best constant: the two sides of "lhs ≤ c·template".

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> res = sup_bound(x * (1 - x), {x: (0, 1)})            # sup = 1/4 at x = 1/2
    >>> res.status, res.maximiser, res.lower
    (<Status.CERTIFIED: 'certified'>, {'x': 0.5}, 0.25)
    >>> 0.25 <= res.certified <= 0.26, res.gap <= 1e-2
    (True, True)
    """

    expr_text: str
    variables: tuple
    estimate: float
    maximiser: dict
    lower: float
    certified: float | None
    gap: float
    status: Status
    boxes: int
    seconds: float
    detail: str
    name: str = ""
    lhs_text: str = ""
    template_text: str = ""

    @property
    def estimate_status(self) -> Status:
        """The status of :attr:`estimate` alone: always ``estimated``."""
        return Status.ESTIMATED

    def to_json(self) -> dict:
        return {"expr": self.expr_text, "variables": list(self.variables),
                "estimate": {"value": _json_float(self.estimate), "status": Status.ESTIMATED.value},
                "maximiser": dict(self.maximiser), "lower": _json_float(self.lower),
                "certified": _json_float(self.certified), "gap": _json_float(self.gap),
                "status": self.status.value, "boxes": self.boxes, "seconds": self.seconds,
                "detail": self.detail, **({"name": self.name, "lhs": self.lhs_text, "template": self.template_text}
                                          if self.name else {})}

    def to_result(self) -> Result:
        """This bound as a :class:`lkverify.report.results.Result` of kind ``constant``."""
        value = self.certified if self.status is Status.CERTIFIED else self.estimate
        return Result(Kind.CONSTANT, self.name or self.expr_text, self.status, value, self.detail)


def _gap(upper, lower) -> float:
    if upper is None or not math.isfinite(upper) or not math.isfinite(lower):
        return _INF
    if upper <= lower:
        return 0.0
    return (upper - lower) / abs(lower) if lower != 0 else _INF


@dataclasses.dataclass(frozen=True)
class Supremum:
    """The estimate and the branch and bound's outcome of one supremum."""

    estimate: float
    point: tuple | None
    outcome: Outcome


def supremum(obj: Objective, *, limits: Limits, accuracy: Accuracy, certify: bool = True, progress=None,
             start: float, strategy: type) -> Supremum:
    """Estimate sup f, seed the proved lower bound from the best candidates, then branch and bound."""
    deadline = start + limits.seconds
    reg = obj.region
    cands = maximise(obj.np_f, reg.lo_in, reg.hi_in, starts=accuracy.starts, seed=accuracy.seed,
                     deadline=start + ESTIMATE_SHARE_SUP * limits.seconds)
    estimate, est_point = (cands[0].value, cands[0].point) if cands else (-_INF, None)
    lower, lower_point = -_INF, None
    for c in cands[:LOWER_CANDIDATES]:
        if reg.contains(c.point):
            pl = float_down(obj.point_ball(c.point))
            if pl > lower:
                lower, lower_point = pl, c.point
    if not certify:
        return Supremum(estimate, est_point, Outcome(Stop.SKIPPED, _INF, lower, lower_point))
    bb = BranchAndBound(strategy(obj), obj.roots())
    out = bb.run(Goal.SUPREMUM, rel_gap=accuracy.rel_gap, abs_gap=accuracy.abs_gap, boxes=limits.boxes,
                 deadline=deadline, start=start, lower=lower, lower_point=lower_point, progress=progress)
    if out.lower_point is not None and math.isfinite(out.lower):
        v = obj.f_float(np.array(out.lower_point))
        if v > estimate:
            estimate, est_point = v, out.lower_point
    return Supremum(estimate, est_point, out)


def sup_detail(out: Outcome, rel_gap: float, singular_note: str | None = None) -> str:
    """The sentence that says what an outcome proved (and what to do when it is undecided)."""
    if out.stop is Stop.SKIPPED:
        return ("estimate only (certify=False): sampled and locally maximised in floating point; "
                "a lower bound of the supremum, not a proof")
    proved = (f"sup ≤ {_fmt(out.upper)} is proved by arb enclosures on {out.boxes} boxes covering the "
              f"box; sup ≥ {_fmt(out.lower)} by an arb point value")
    if out.stop is Stop.DONE:
        return proved + f"; relative gap {_fmt(_gap(out.upper, out.lower))} ≤ {rel_gap:g}"
    head = f"undecided: {out.reason or 'budget spent'} before the relative gap reached {rel_gap:g}; "
    if math.isfinite(out.upper):
        return head + (f"the upper bound {_fmt(out.upper)} is nevertheless proved (valid, just not "
                       f"tight); sup ≥ {_fmt(out.lower)} by an arb point value")
    return head + "no finite upper bound was proved: " + (
        singular_note or "some box's enclosure is not finite (the expression may be undefined or "
                         "singular there; reparametrise or cancel the singular factor)")


def sup_bound(expr, box: Mapping, *, budget: Budget | None = None, accuracy: Accuracy | None = None,
              certify: bool = True, enclosure="both",
              progress: Callable[[BranchProgress], None] | None = None) -> SupResult:
    """The supremum of an expression over a box: an estimate and a proved upper bound.

    Parameters
    ----------
    expr : sympy.Expr
        See :func:`~lkverify.certify.functions.compile_arb` for what may appear.
    box : mapping of sympy.Symbol to (lo, hi)
        Finite bounds: numbers or SymPy constants (``sympy.pi``); a float is
        taken at its exact binary value (pass ``sympy.Rational(1, 10)`` for 1/10).
    budget : lkverify.options.Budget, optional
        Ceilings for the whole job (estimate included); default
        :data:`DEFAULT_BUDGET_SECONDS` seconds and :data:`DEFAULT_BUDGET_BOXES` boxes.
    accuracy : lkverify.options.Accuracy, optional
        Stop when ``certified − lower ≤ max(rel_gap·|lower|, abs_gap)``; ``starts``
        local maximisations (SLSQP) from the best Sobol samples, ``seed``.
    certify : bool, default True
        False: only the estimate (status ``estimated``).
    enclosure : str or Enclosure subclass, default "both"
        The strategy that bounds a box (:data:`lkverify.certify.engine.ENCLOSURES`):
        ``"mean-value"`` (cheap; also gives the monotonicity test and the split
        direction), ``"affine"`` (tighter on wide boxes of trigonometric
        expressions, about 2× costlier), ``"both"`` intersected, ``"natural"``,
        ``"taylor"`` (mean-value ∩ second- and third-order Taylor forms,
        :class:`~lkverify.certify.engine.Taylor`: compiles the derivatives up to
        third order once, costs about 4× per box, and needs far fewer boxes where
        the supremum is attained inside the box or along flat directions -- a
        quadratic form on a sphere, say).  Any choice is sound; it only changes
        speed.
    progress : callable, optional
        Called with a :class:`~lkverify.certify.engine.BranchProgress` about twice a second.

    Returns
    -------
    SupResult

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> res = sup_bound(sympy.sin(x) * sympy.cos(y), {x: (0, 3), y: (-1, 1)})
    >>> res.status, res.certified >= 1.0, res.gap <= 1e-2
    (<Status.CERTIFIED: 'certified'>, True, True)
    >>> sup_bound(x * (1 - x), {x: (0, 1)}, certify=False).status
    <Status.ESTIMATED: 'estimated'>
    """
    start = time.monotonic()
    limits, accuracy, strategy = check_options(budget=budget, accuracy=accuracy, enclosure=enclosure,
                                               progress=progress)
    expr = sympify_expr(expr)
    region = parse_region(box, [expr])
    obj = Objective(expr, region)
    sp = supremum(obj, limits=limits, accuracy=accuracy, certify=certify, progress=progress, start=start,
                  strategy=strategy)
    out = sp.outcome
    if not certify:
        status, certified = Status.ESTIMATED, None
    else:
        status = Status.CERTIFIED if out.stop is Stop.DONE else Status.UNDECIDED
        certified = out.upper
    return SupResult(expr_text=str(expr), variables=region.names, estimate=sp.estimate,
                     maximiser=region.point_dict(sp.point) if sp.point is not None else {},
                     lower=out.lower, certified=certified, gap=_gap(certified, out.lower),
                     status=status, boxes=out.boxes, seconds=time.monotonic() - start,
                     detail=sup_detail(out, accuracy.rel_gap))


# ---------------------------------------------------------------------------
# yes/no checks: expr ≤ 0, expr > 0
# ---------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class CheckResult:
    """A claim about a box, proved, refuted or left open.

    Attributes
    ----------
    name : str
    claim : str
        The claim in words, e.g. ``"x**2 - 1 <= 0 on {x ∈ [-1, 1]}"``.
    status : Status
        ``certified`` (proved on the whole box), ``failed`` (refuted at
        :attr:`point`), ``undecided`` (budget spent, or a prerequisite such as
        the template's sign could not be proved).
    point : dict of str to float or None
        For ``failed``: a point of the box (exact binary floats) where the
        claim is false, proved with arb.
    margin : float or None
        For ``failed``: a proved lower bound of the violation at
        :attr:`point` (``lhs − c·template``, ``expr``, or ``−expr`` for a
        positivity claim).  For ``certified``: the proved slack
        (``c − certified sup of lhs/template``, ``−sup expr``, ``inf expr``).
    bound : float or None
        The proved bound behind the verdict: the certified supremum
        (of ``expr``, or of ``lhs/template``), or for a positivity claim the
        certified infimum of ``expr``.  Valid also for ``undecided``.
    boxes : int
    seconds : float
    detail : str

    Examples
    --------
    >>> import sympy
    >>> from lkverify.certify.ratios import check_constant
    >>> x = sympy.Symbol("x")
    >>> ok = check_constant(x**2 * (1 - x), x**2, {x: (0, 1)}, 1)     # x²(1 − x) ≤ 1·x²
    >>> ok.status, ok.claim
    (<Status.CERTIFIED: 'certified'>, 'x**2*(1 - x) <= 1*(x**2) on {x ∈ [0, 1]}')
    >>> bad = check_constant(x**2 * (1 - x), x**2, {x: (0, 1)}, sympy.Rational(1, 2))
    >>> bad.status, bad.point, bad.margin > 0                  # refuted at x = 1/16
    (<Status.FAILED: 'failed'>, {'x': 0.0625}, True)
    """

    name: str
    claim: str
    status: Status
    point: dict | None
    margin: float | None
    bound: float | None
    boxes: int
    seconds: float
    detail: str

    def to_result(self, kind: Kind | str = Kind.HYPOTHESIS) -> Result:
        """This check as a :class:`lkverify.report.results.Result` (``kind`` as the report needs it)."""
        value = self.margin if self.status is not Status.UNDECIDED else self.bound
        return Result(kind, self.name, self.status, value, self.detail)

    def to_json(self) -> dict:
        return {"name": self.name, "claim": self.claim, "status": self.status.value,
                "point": self.point, "margin": _json_float(self.margin),
                "bound": _json_float(self.bound), "boxes": self.boxes, "seconds": self.seconds,
                "detail": self.detail}


def decide(obj: Objective, *, threshold: float, strict: bool, refute: Callable, limits: Limits,
           accuracy: Accuracy, progress, start: float, strategy: type) -> Outcome:
    """Estimate (to find counterexamples fast), then prove ``sup ≤ threshold`` by branch and bound.

    ``refute(point)`` returns a :class:`~lkverify.certify.engine.Refutation` where
    the claim is proved false, or None.
    """
    deadline = start + limits.seconds
    reg = obj.region
    cands = maximise(obj.np_f, reg.lo_in, reg.hi_in, starts=accuracy.starts, seed=accuracy.seed,
                     deadline=start + ESTIMATE_SHARE_DECIDE * limits.seconds)
    for c in cands[:max(LOWER_CANDIDATES, accuracy.starts)]:
        if (c.value > threshold or (strict and c.value >= threshold)) and reg.contains(c.point):
            hit = refute(c.point)
            if hit is not None:
                return Outcome(Stop.FAILED, _INF, refutation=hit)

    def probe(piece, centre, value):
        if not value.is_finite():
            return None
        m = float(value.mid())
        return refute(centre) if m > threshold or (strict and m >= threshold) else None

    bb = BranchAndBound(strategy(obj), obj.roots())
    return bb.run(Goal.DECIDE, threshold=threshold, strict=strict, boxes=limits.boxes, deadline=deadline,
                  start=start, probe=probe, progress=progress)


def _sign_check(expr, box, *, positive: bool, name, budget, accuracy, progress, enclosure) -> CheckResult:
    start = time.monotonic()
    limits, accuracy, strategy = check_options(budget=budget, accuracy=accuracy, enclosure=enclosure,
                                               progress=progress)
    expr = sympify_expr(expr)
    region = parse_region(box, [expr])
    claim = f"{expr} {'> 0' if positive else '<= 0'} on {region.text()}"
    obj = Objective(-expr if positive else expr, region)

    def refute(p):
        val = obj.point_ball(p)
        if positive:      # −expr ≥ 0 proves expr ≤ 0
            return Refutation(float_down(val), tuple(p)) if val >= 0 else None
        return Refutation(float_down(val), tuple(p)) if val > 0 else None

    out = decide(obj, threshold=0.0, strict=positive, refute=refute, limits=limits, accuracy=accuracy,
                 progress=progress, start=start, strategy=strategy)
    seconds = time.monotonic() - start
    if out.stop is Stop.FAILED:
        margin = out.refutation.margin
        point = region.point_dict(out.refutation.point)
        what = (f"{expr} ≤ 0 at {point} (arb: −expr ≥ {_fmt(margin)})" if positive
                else f"{expr} ≥ {_fmt(margin)} > 0 at {point} (arb point value)")
        return CheckResult(name or claim, claim, Status.FAILED, point, margin, None, out.boxes, seconds,
                           f"refuted: {what}")
    bound = -out.upper if positive else out.upper
    if out.stop is Stop.DONE:
        what = (f"{expr} ≥ {_fmt(bound)} > 0" if positive else f"{expr} ≤ {_fmt(bound)} ≤ 0")
        return CheckResult(name or claim, claim, Status.CERTIFIED, None, -out.upper, bound, out.boxes,
                           seconds, f"proved by arb enclosures on {out.boxes} boxes: {what} on the box")
    return CheckResult(name or claim, claim, Status.UNDECIDED, None, None, bound, out.boxes, seconds,
                       f"undecided: {out.reason}; no counterexample found; the proved "
                       f"{'lower' if positive else 'upper'} bound of {expr} is {_fmt(bound)}")


def certify_nonpositive(expr, box: Mapping, *, name: str | None = None, budget: Budget | None = None,
                        accuracy: Accuracy | None = None, enclosure="both",
                        progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove ``expr ≤ 0`` on a box, or refute it at a point.

    Parameters
    ----------
    expr : sympy.Expr
    box : mapping of sympy.Symbol to (lo, hi)
    name : str, optional
        Defaults to the claim's text.
    budget, accuracy, enclosure, progress
        As for :func:`sup_bound` (of the accuracy only ``starts`` and ``seed`` matter).

    Returns
    -------
    CheckResult
        ``certified``: every box's enclosure has upper end ≤ 0.  ``failed``:
        ``point`` is a point of the box with an arb value > 0 (``margin`` is
        its proved lower bound).  ``undecided``: the budget ran out -- which is
        what happens when ``expr`` touches 0 at a point where no enclosure is
        exact (a maximum of exactly 0 cannot be separated from 0 by boxes;
        prove ``expr ≤ -m`` on a region that excludes the touching point, or
        divide the touching factor out).

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> certify_nonpositive(x**2 + y**2 - 3, {x: (-1, 1), y: (-1, 1)}).status
    <Status.CERTIFIED: 'certified'>
    >>> res = certify_nonpositive(x**2 + y**2 - 1.5, {x: (-1, 1), y: (-1, 1)})
    >>> res.status, res.margin > 0
    (<Status.FAILED: 'failed'>, True)
    """
    return _sign_check(expr, box, positive=False, name=name, budget=budget, accuracy=accuracy,
                       progress=progress, enclosure=enclosure)


def certify_positive(expr, box: Mapping, *, name: str | None = None, budget: Budget | None = None,
                     accuracy: Accuracy | None = None, enclosure="both",
                     progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove ``expr > 0`` on a box, or refute it at a point (where ``expr ≤ 0`` is proved).

    ``bound`` is then a proved lower bound of ``expr`` on the box (> 0).  See
    :func:`certify_nonpositive` for the options and for what ``undecided`` means.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> res = certify_positive(sympy.cos(x), {x: (-1, 1)})
    >>> res.status, res.bound > 0.5
    (<Status.CERTIFIED: 'certified'>, True)
    >>> certify_positive(sympy.cos(x), {x: (0, 2)}).status
    <Status.FAILED: 'failed'>
    """
    return _sign_check(expr, box, positive=True, name=name, budget=budget, accuracy=accuracy,
                       progress=progress, enclosure=enclosure)
