"""Best constants: the best ``c`` in "lhs ≤ c·template on the region", and a claimed ``c`` proved or refuted.

Examples
--------
>>> import sympy
>>> x = sympy.Symbol("x")
>>> check_constant(x * (2 - x), x, {x: (0, 2)}, 2.01).status     # lhs/template = 2 - x ≤ 2
<Status.CERTIFIED: 'certified'>
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Mapping

import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from ..options import Accuracy, Budget
from ..status import Status
from .engine import BranchProgress, Objective, Refutation, Stop
from .functions import compile_arb, lambdify_real, sympify_expr
from .intervals import float_down
from .intervals.convert import _real_dummies, _sympy_number_ball
from .regions import Region, exact_number, parse_region, prove_zero
from .suprema import (CheckResult, Limits, SupResult, _fmt, _gap, certify_nonpositive, check_options, decide,
                      sup_detail, supremum)

__all__ = ["CHECK_SHARE", "REFUTE_STEPS", "TEMPLATE_SIGN_SHARE", "best_constant", "check_constant"]

#: the share of the budget (time and boxes) for proving template ≥ 0
TEMPLATE_SIGN_SHARE = 0.25
#: the share of the time budget for deciding a claimed constant (the rest: the template's sign)
CHECK_SHARE = 0.75
#: where the template vanishes, counterexamples are retried this far towards the region's centre
REFUTE_STEPS = (0.0, 2.0 ** -30, 2.0 ** -20, 2.0 ** -10, 2.0 ** -6, 2.0 ** -3)
#: random points at which a caller's ratio is compared with lhs/template before the identity is proved
RATIO_SAMPLES = 16


@dataclasses.dataclass(frozen=True)
class _Prepared:
    """lhs, template and the ratio to bound, on the parsed region, with how the ratio was obtained."""

    region: Region
    lhs: sympy.Expr
    template: sympy.Expr
    ratio: sympy.Expr
    ratio_note: str
    ratio_proved: bool


def _prepare_constant(lhs, template, region, ratio, seed) -> _Prepared:
    lhs = sympify_expr(lhs, "lhs")
    template = sympify_expr(template, "template")
    exprs = [lhs, template]
    if ratio is not None:
        ratio = sympify_expr(ratio, "ratio")
        exprs.append(ratio)
    reg = parse_region(region, exprs, "region")
    if template.is_zero:
        raise InputError("template is identically 0; a best constant needs a template > 0")
    if ratio is None:
        num, den = sympy.fraction(sympy.together(lhs / template))
        try:
            g = sympy.gcd(num, den)
        except Exception:  # noqa: BLE001
            g = sympy.S.One
        if g.free_symbols:
            ratio = sympy.cancel(lhs / template)
            return _Prepared(reg, lhs, template, ratio,
                             f"the common factor {g} of lhs and template was cancelled exactly "
                             f"(polynomial gcd)", True)
        return _Prepared(reg, lhs, template, lhs / template, "", True)
    # a caller's ratio: refute numerically first, then prove the identity symbolically
    dummies = _real_dummies(reg.variables, reg.signs)
    diff = (ratio * template - lhs).xreplace(dummies)
    f = lambdify_real([dummies[v] for v in reg.variables], diff)
    scale = lambdify_real([dummies[v] for v in reg.variables], (abs(lhs) + abs(ratio * template)).xreplace(dummies))
    rng = np.random.default_rng(seed)
    pts = [rng.uniform(a, b, RATIO_SAMPLES) for a, b in zip(reg.lo_in, reg.hi_in)]
    d = np.abs(f(*pts))
    sc = np.abs(scale(*pts))
    bad = np.isfinite(d) & (d > 1e-8 * np.maximum(sc, 1.0))
    if bad.any():
        i = int(np.argmax(bad))
        where = {n: float(p[i]) for n, p in zip(reg.names, pts)}
        raise InputError(f"ratio {ratio} is not lhs/template: ratio*template - lhs = {float(d[i]):.3g} "
                         f"at {where}; pass the simplified lhs/template or omit ratio")
    proved = prove_zero(diff)
    note = ("the ratio's identity ratio·template = lhs was proved symbolically (SymPy)" if proved else
            "the ratio's identity ratio·template = lhs was NOT proved symbolically (only checked at "
            f"{RATIO_SAMPLES} random points), so the result cannot be certified")
    return _Prepared(reg, lhs, template, ratio, note, proved)


def _template_sign(prep: _Prepared, *, limits: Limits, seed: int):
    """(status, text): is template ≥ 0 on the region proved?"""
    reg = prep.region
    tf = compile_arb(prep.template, reg.variables, gradient=False, signs=reg.signs)
    dummies = _real_dummies(reg.variables, reg.signs)
    if tf.nonnegative or prep.template.xreplace(dummies).is_nonnegative:
        return Status.EXACT, "template ≥ 0 structurally (exact)"
    res = certify_nonpositive(-prep.template, dict(zip(reg.variables, reg.bounds)),
                              budget=Budget(seconds=limits.seconds, boxes=limits.boxes), accuracy=Accuracy(seed=seed))
    if res.status is Status.FAILED:
        raise InputError(f"template {prep.template} is negative at {res.point} (proved: "
                         f"≤ {-res.margin:.3g}); a best constant needs template ≥ 0 on the region")
    if res.status is Status.CERTIFIED:
        return Status.CERTIFIED, f"template ≥ 0 proved by arb on {res.boxes} boxes"
    return Status.UNDECIDED, "template ≥ 0 could not be proved within budget"


_SINGULAR_NOTE = ("where the template's enclosure contains 0 the ratio's enclosure is not finite and no "
                  "bound is certified there; cancel the vanishing factor (ratio=...) or reparametrise "
                  "so that it cancels")


def best_constant(lhs, template, region: Mapping, *, name: str = "c", ratio=None, budget: Budget | None = None,
                  accuracy: Accuracy | None = None, enclosure="both",
                  progress: Callable[[BranchProgress], None] | None = None) -> SupResult:
    """The best ``c`` in "lhs ≤ c·template on the region", i.e. ``sup lhs/template``.

    Parameters
    ----------
    lhs, template : sympy.Expr
        ``template`` must be ≥ 0 on the region and > 0 except on a set with
        empty interior (where it vanishes, ``lhs`` must vanish too).
    region : mapping of sympy.Symbol to (lo, hi)
        A box; parametrise manifolds and balls with the charts of this module
        (:func:`unit_vector_near`, :func:`rotation_axis_angle`, ...).
    name : str, default "c"
    ratio : sympy.Expr, optional
        ``lhs/template`` with the vanishing factor cancelled (e.g.
        ``cos(rho/2)`` for ``sin(rho) / (2 sin(rho/2))``).  It is checked at
        random points (a mismatch raises :class:`InputError`) and the identity
        ``ratio·template = lhs`` is proved with SymPy; if SymPy cannot prove
        it the result is at most ``undecided``.  Without ``ratio`` a common
        polynomial factor of lhs and template is cancelled exactly
        (``sympy.cancel``) when there is one.
    budget, accuracy, enclosure, progress
        As for :func:`~lkverify.certify.suprema.sup_bound`; the template's sign
        proof uses :data:`TEMPLATE_SIGN_SHARE` of the budget.

    Returns
    -------
    SupResult
        ``certified`` when (1) template ≥ 0 is proved (structurally or by
        branch and bound), (2) the ratio identity, if any, is proved, and
        (3) the supremum of the ratio is bounded to ``rel_gap``.

    Notes
    -----
    Removable singularities.  At a point where the template vanishes (the
    origin, ``s = r``) the quotient ``lhs/template`` is 0/0 and its enclosure
    on every box around that point is not finite: such boxes get an
    infinite upper bound, are split again and again, and the result is
    ``undecided`` with ``certified = inf`` -- never a bogus certificate.  The
    cure is to hand over the quotient with the vanishing factor cancelled:
    either pass ``ratio=``, or reparametrise so the factor is explicit (the
    charts expose ``‖s − r‖ = 2 sin(ρ/2)`` and ``‖s × r‖ = sin ρ``) and cancel
    it in the expressions you pass.

    Why the certificate is sound: on every leaf box the ratio's enclosure is
    finite, so its denominator does not vanish there and ``lhs = ratio ·
    template`` holds pointwise; with ``template ≥ 0`` and ``ratio ≤ c`` this
    gives ``lhs ≤ c·template`` on the leaf, also where ``template = 0``.

    Examples
    --------
    For unit vectors s, r with angle ρ: ‖s × r‖ = sin ρ, ‖s − r‖ = 2 sin(ρ/2),
    so ‖s × r‖ ≤ c‖s − r‖ with best c = 1 (at s → r):

    >>> import sympy
    >>> rho = sympy.Symbol("rho")
    >>> res = best_constant(sympy.sin(rho), 2 * sympy.sin(rho / 2), {rho: (0, sympy.pi / 3)},
    ...                     ratio=sympy.cos(rho / 2))
    >>> res.status, 1.0 <= res.certified <= 1.01
    (<Status.CERTIFIED: 'certified'>, True)
    >>> best_constant(sympy.sin(rho), 2 * sympy.sin(rho / 2), {rho: (0, 1)},
    ...               budget=Budget(seconds=30, boxes=300)).status          # 0/0 at rho = 0: never certified
    <Status.UNDECIDED: 'undecided'>
    """
    start = time.monotonic()
    limits, accuracy, strategy = check_options(budget=budget, accuracy=accuracy, enclosure=enclosure,
                                               progress=progress)
    if not isinstance(name, str):
        raise InputError(f"name: expected a string, got {name!r}")
    prep = _prepare_constant(lhs, template, region, ratio, accuracy.seed)
    sign = _template_sign(prep, limits=limits.share(TEMPLATE_SIGN_SHARE, boxes=TEMPLATE_SIGN_SHARE),
                          seed=accuracy.seed)
    remaining = max(limits.seconds - (time.monotonic() - start), 1e-3)
    sp = supremum(Objective(prep.ratio, prep.region), limits=Limits(remaining, limits.boxes), accuracy=accuracy,
                  progress=progress, start=time.monotonic(), strategy=strategy)
    return _constant_result(name, prep, sign, sp, accuracy, time.monotonic() - start)


def _constant_result(name, prep: _Prepared, sign: tuple, sp, accuracy: Accuracy, seconds: float) -> SupResult:
    sign_status, sign_text = sign
    out, reg = sp.outcome, prep.region
    notes = [sign_text] + ([prep.ratio_note] if prep.ratio_note else [])
    ok = out.stop is Stop.DONE and sign_status.is_proof and prep.ratio_proved
    if ok:
        head = (f"lhs ≤ {_fmt(out.upper)}·template proved on the region "
                f"({out.boxes} boxes; best constant ≥ {_fmt(out.lower)}, relative gap "
                f"{_fmt(_gap(out.upper, out.lower))})")
    else:
        head = sup_detail(out, accuracy.rel_gap, _SINGULAR_NOTE) if out.stop is not Stop.DONE else (
            f"sup lhs/template ≤ {_fmt(out.upper)} is proved, but not every prerequisite is")
    return SupResult(expr_text=str(prep.ratio), variables=reg.names, estimate=sp.estimate,
                     maximiser=reg.point_dict(sp.point) if sp.point is not None else {}, lower=out.lower,
                     certified=out.upper, gap=_gap(out.upper, out.lower),
                     status=Status.CERTIFIED if ok else Status.UNDECIDED, boxes=out.boxes, seconds=seconds,
                     detail="; ".join([head] + notes), name=name, lhs_text=str(prep.lhs),
                     template_text=str(prep.template))


def _violation_refuter(prep: _Prepared, c_ball: arb) -> Callable:
    """refute(point): a Refutation where lhs − c·template is proved > 0 at or near the point, else None."""
    reg = prep.region
    c_symbol = sympy.Symbol("_c_lkverify")
    violation = compile_arb(prep.lhs - c_symbol * prep.template, list(reg.variables) + [c_symbol],
                            gradient=False, signs=list(reg.signs) + [(False, False)])
    centre = [a + (b - a) / 2 for a, b in zip(reg.lo_in, reg.hi_in)]

    def refute(p):
        # where the template vanishes the violation is 0 even if the ratio exceeds c there:
        # then try points slightly inside, towards the centre of the region
        best = None
        for t in REFUTE_STEPS:
            q = tuple(float(a + t * (m - a)) for a, m in zip(p, centre))
            if not reg.contains(q):
                continue
            val = violation.balls(*[arb(x) for x in q], c_ball)
            if val > 0 and (best is None or float_down(val) > best.margin):
                best = Refutation(float_down(val), q)
        return best

    return refute


def check_constant(lhs, template, region: Mapping, claimed_c, *, name: str = "c", ratio=None,
                   budget: Budget | None = None, accuracy: Accuracy | None = None, enclosure="both",
                   progress: Callable[[BranchProgress], None] | None = None) -> CheckResult:
    """Prove or refute a claimed constant: "lhs ≤ claimed_c·template on the region".

    Parameters
    ----------
    lhs, template, region, name, ratio
        As for :func:`best_constant`.
    claimed_c : number or SymPy number
        A float is taken at its exact binary value (pass ``sympy.Rational(921, 100)`` for 9.21).
    budget, accuracy, enclosure, progress
        As for :func:`~lkverify.certify.suprema.sup_bound`.

    Returns
    -------
    CheckResult
        ``failed``: at :attr:`~CheckResult.point` (exact binary floats inside the
        region) the arb value of ``lhs − claimed_c·template`` has a lower
        bound ``margin > 0`` -- a proof that the constant is too small, which
        needs neither the template's sign nor the ratio.  ``certified``: the
        template is proved ≥ 0, the ratio identity (if any) is proved, and
        the certified supremum of lhs/template (``bound``) is ≤ claimed_c.
        ``undecided`` otherwise.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> check_constant(x * (2 - x), x, {x: (0, 2)}, 2.01).status     # lhs/template = 2 - x ≤ 2
    <Status.CERTIFIED: 'certified'>
    >>> res = check_constant(x * (2 - x), x, {x: (0, 2)}, 1.9)
    >>> res.status, res.point["x"] < 0.1, res.margin > 0
    (<Status.FAILED: 'failed'>, True, True)
    """
    start = time.monotonic()
    limits, accuracy, strategy = check_options(budget=budget, accuracy=accuracy, enclosure=enclosure,
                                               progress=progress)
    c_exact = exact_number(claimed_c, "claimed_c")
    c_ball = _sympy_number_ball(c_exact)
    prep = _prepare_constant(lhs, template, region, ratio, accuracy.seed)
    reg = prep.region
    claim = f"{prep.lhs} <= {c_exact}*({prep.template}) on {reg.text()}"
    out = decide(Objective(prep.ratio, reg), threshold=float_down(c_ball), strict=False,
                 refute=_violation_refuter(prep, c_ball), limits=limits.share(CHECK_SHARE), accuracy=accuracy,
                 progress=progress, start=start, strategy=strategy)
    if out.stop is Stop.FAILED:
        point = reg.point_dict(out.refutation.point)
        return CheckResult(name, claim, Status.FAILED, point, out.refutation.margin, None, out.boxes,
                           time.monotonic() - start,
                           f"refuted: lhs − {c_exact}·template ≥ {_fmt(out.refutation.margin)} > 0 at {point} "
                           f"(arb point value at exact binary coordinates)")
    sign_limits = Limits(max(limits.seconds * TEMPLATE_SIGN_SHARE, 1e-3),
                         max(1, int(limits.boxes * TEMPLATE_SIGN_SHARE)))
    sign_status, sign_text = _template_sign(prep, limits=sign_limits, seed=accuracy.seed)
    notes = [sign_text] + ([prep.ratio_note] if prep.ratio_note else [])
    seconds = time.monotonic() - start
    if out.stop is Stop.DONE and sign_status.is_proof and prep.ratio_proved:
        return CheckResult(name, claim, Status.CERTIFIED, None, float_down(c_ball - arb(out.upper)), out.upper,
                           out.boxes, seconds,
                           "; ".join([f"proved: sup lhs/template ≤ {_fmt(out.upper)} ≤ {c_exact} by arb "
                                      f"enclosures on {out.boxes} boxes"] + notes))
    why = (out.reason if out.stop is not Stop.DONE else "a prerequisite is not proved")
    bound_note = "" if math.isfinite(out.upper) else "; " + _SINGULAR_NOTE
    return CheckResult(name, claim, Status.UNDECIDED, None, None, out.upper, out.boxes, seconds,
                       "; ".join([f"undecided: {why}; no counterexample found{bound_note}"] + notes))
