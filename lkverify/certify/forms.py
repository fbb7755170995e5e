"""Homogeneous forms: positive definiteness as a certified minimum on the unit sphere.

For f homogeneous of even degree d, f(x) = ‖x‖^d f(x/‖x‖), so f is positive
definite iff min f on ‖x‖ = 1 is > 0.  :func:`homogeneous_positive_on_sphere`
covers the sphere by the faces x_i = 1 of the cube and bounds
g(y) = f(x)/‖x‖^d on each face with arb balls (:class:`FaceEnclosure`), on the
one branch-and-bound engine and the one estimator of :mod:`lkverify.certify`.

Examples
--------
>>> import sympy
>>> x, y = sympy.symbols("x y")
>>> homogeneous_positive_on_sphere(x**2 + x*y + y**2, [x, y]).status
<Status.CERTIFIED: 'certified'>
"""

from __future__ import annotations

import itertools
import math
import time
from fractions import Fraction

import flint
import numpy as np
import sympy
from flint import arb

from ..errors import InputError
from ..options import Accuracy, Budget
from ..status import Status
from .conditions import ConditionResult, Estimate
from .conditions import Margin
from .engine import BoxBound, BranchAndBound, Enclosure, Goal, Refutation, Stop
from .estimate import maximise
from .intervals import enclose, float_down, float_up, lower_fraction, sign_of, to_ball, upper_fraction
from .intervals.balls import _ipow

__all__ = ["CubeFace", "FORM_ACCURACY", "FORM_BUDGET", "FaceEnclosure", "homogeneous_positive_on_sphere"]

#: the highest arb precision (bits) tried when deciding the sign of f at a point with irrational coefficients
SIGN_PRECISION = 512
#: the default budget of the branch and bound
FORM_BUDGET = Budget(seconds=10.0, boxes=200_000)
#: the default accuracy: the relative gap of the certified minimum, and the estimator's starts per face
FORM_ACCURACY = Accuracy(rel_gap=1e-3, starts=2)
#: denominators of the rational points tried near the estimated minimiser
CANDIDATE_DENOMINATORS = (1, 2, 4, 10, 100, 10**4, 10**6, 10**9)


def _pow_table(Y: arb, kmax: int) -> list[arb]:
    """Enclosures of Y^0 … Y^kmax that are tight for even powers of a ball containing 0."""
    out = [arb(1)]
    if Y.rad() == 0:
        for _ in range(kmax):
            out.append(out[-1] * Y)
        return out
    lo, hi = Y.lower(), Y.upper()
    plo, phi = arb(1), arb(1)
    straddle = not (lo >= 0 or hi <= 0)
    for k in range(1, kmax + 1):
        plo, phi = plo * lo, phi * hi
        if k % 2 == 0 and straddle:
            out.append(arb.union(arb(0), plo if abs(lo) > abs(hi) else phi))
        else:
            out.append(arb.union(plo, phi))
    return out


class _ArbPoly:
    """Σ c·Π y_j^k_j with arb coefficients, evaluated on tables of powers."""

    __slots__ = ("terms",)

    def __init__(self, poly: sympy.Poly):
        self.terms = [(enclose(c, prec=None), m) for m, c in poly.terms() if c != 0]

    def __call__(self, powers: list[list[arb]]) -> arb:
        total = arb(0)
        for c, m in self.terms:
            t = c
            for j, k in enumerate(m):
                if k:
                    t = t * powers[j][k]
            total = total + t
        return total


class CubeFace:
    """The face x_i = 1 of the cube: g(y) = f(x)/‖x‖^d, its natural and centred (mean-value) enclosures."""

    def __init__(self, poly: sympy.Poly, variables, i: int, d: int):
        self.i, self.d, self.h = i, d, d // 2
        self.ys = [v for j, v in enumerate(variables) if j != i]
        fface = sympy.Poly(poly.as_expr().subs(variables[i], 1), *self.ys)
        r = sympy.Poly(1 + sum(y**2 for y in self.ys), *self.ys)
        self.F = _ArbPoly(fface)
        # ∂g/∂y_j = (∂_j F · r − d·y_j·F) / r^(h+1); the numerator is expanded exactly so that
        # cancellations (g constant on the sphere, e.g. f = ‖x‖²) are not lost to interval dependency
        self.dN = [_ArbPoly(fface.diff(y) * r - d * sympy.Poly(y, *self.ys) * fface) for y in self.ys]

    def bounds(self, lo: tuple, hi: tuple) -> tuple[float, float]:
        """(lower bound of g on the box, certified upper bound of g at the box centre)."""
        lower, gc, _ = self.enclose(lo, hi)
        return lower, float_up(gc)

    def enclose(self, lo: tuple, hi: tuple) -> tuple[float, arb, tuple]:
        """(lower bound of g on the box, the ball of g at the box centre, the centre)."""
        m = len(lo)
        lo, hi = [float(a) for a in lo], [float(b) for b in hi]   # Python floats: arb takes them exactly
        mids = [(a + b) / 2 for a, b in zip(lo, hi)]
        rads = [math.nextafter(max(b - m_, m_ - a), math.inf) if b > a else 0.0
                for a, b, m_ in zip(lo, hi, mids)]                    # rounded up: the ball covers [a, b]
        Y = [arb(c, r) for c, r in zip(mids, rads)]
        C = [arb(c) for c in mids]
        PY = [_pow_table(y, self.d + 1) for y in Y]   # the gradient numerators have degree d + 1
        PC = [_pow_table(c, self.d) for c in C]
        RY = arb(1) + sum((p[2] for p in PY), arb(0))
        RC = arb(1) + sum((p[2] for p in PC), arb(0))
        FY, FC = self.F(PY), self.F(PC)
        RYh = _ipow(RY, self.h)          # from the endpoints: a wide ball times itself may straddle 0
        natural = FY / RYh
        gc = FC / _ipow(RC, self.h)
        centred = gc
        RYh1 = _ipow(RY, self.h + 1)
        for j in range(m):
            grad = self.dN[j](PY) / RYh1
            centred = centred + grad * arb(0, rads[j])
        return max(float_down(natural), float_down(centred)), gc, tuple(mids)


class FaceEnclosure(Enclosure):
    """The engine's strategy for −g on the faces of the cube (piece i: the face x_i = 1).

    ``bound`` returns −(the better of the natural and the centred lower bound
    of g), the centre of the box and −g there (so the engine maximises −g).
    """

    def __init__(self, faces: list):
        self.faces = faces

    def bound(self, piece: int, lo, hi, enough: float = -math.inf) -> BoxBound:
        lower, gc, mids = self.faces[piece].enclose(lo, hi)
        return BoxBound(-lower, tuple(lo), tuple(hi), -1, mids, -gc, True)


def _homogeneity_error(poly: sympy.Poly, name: str) -> str:
    terms = [f"{sympy.Mul(c, *(v**k for v, k in zip(poly.gens, m)))}: degree {sum(m)}"
             for m, c in poly.terms()]
    return (f"{name}: expected a homogeneous polynomial (every term of the same degree), got terms of degrees "
            + "; ".join(terms) + "; split f into its homogeneous parts or fix the exponents")


class _Form:
    """A parsed homogeneous form: exact values and signs at rational points, and counterexample results."""

    def __init__(self, poly: sympy.Poly, variables: tuple, d: int, name: str, prec: int):
        self.poly, self.variables, self.d, self.name, self.prec = poly, variables, d, name, prec
        self.n = len(variables)
        self.rational = all(c.is_Rational for c in poly.coeffs())
        self.qterms = [(Fraction(int(c.p), int(c.q)) if self.rational else c, m) for m, c in poly.terms()]
        self.estimate = None

    def value_sign(self, x: tuple) -> tuple[object, int | None]:
        """f(x) and its proved sign (exact for rational coefficients, arb balls otherwise; None if unknown)."""
        if self.rational:
            v = sum((c * math.prod((xi**k for xi, k in zip(x, m)), start=Fraction(1)) for c, m in self.qterms),
                    Fraction(0))
            return v, (v > 0) - (v < 0)
        v = self.poly.as_expr().xreplace({var: sympy.Rational(c.numerator, c.denominator)
                                          for var, c in zip(self.variables, x)})
        if v == 0:
            return v, 0
        return v, sign_of(v, max_prec=SIGN_PRECISION).sign

    def g_upper(self, x: tuple) -> Fraction | None:
        """A proved upper bound of f(x/‖x‖) at the rational point x (exact for rational coefficients)."""
        nrm = sum((c * c for c in x), Fraction(0)) ** (self.d // 2)
        v, _ = self.value_sign(x)
        if self.rational:
            return v / nrm
        with flint.ctx.workprec(self.prec):
            b = enclose(v, prec=None) / to_ball(nrm)
        return upper_fraction(b)

    def failed(self, x: tuple, how: str):
        """The ``failed`` result at the rational point x, after proving f(x) ≤ 0."""
        name, d = self.name, self.d
        v, sign = self.value_sign(x)
        if sign is None or sign > 0:
            raise RuntimeError(f"internal error: a counterexample with {name}(x) = {v} not proved ≤ 0")
        nrm2 = sum((c * c for c in x), Fraction(0))
        hi = v / nrm2 ** (d // 2) if self.rational and d % 2 == 0 else None
        margin = Margin(None, hi, point=x) if hi is not None else None
        detail = (f"{name} is not positive definite: at the rational point x = ({', '.join(map(str, x))}) "
                  f"{name}(x) = {v}{' < 0' if v != 0 else ''} ({'exact' if self.rational else 'certified'}); "
                  f"{how}.")
        return ConditionResult(name, Status.FAILED, margin=margin, estimate=self.estimate, witness=x,
                               detail=detail)


def _parse(f, variables, degree, name):
    """(poly, variables, degree d) of a homogeneous form; InputError with the reason otherwise."""
    variables = tuple(variables)
    if (not variables or not all(isinstance(v, sympy.Symbol) for v in variables)
            or len(set(variables)) != len(variables)):
        raise InputError(f"{name}: expected distinct SymPy Symbols as variables, got {variables!r}; "
                         "pass e.g. sympy.symbols('x y z')")
    try:
        poly = sympy.Poly(sympy.sympify(f), *variables)
    except (sympy.PolynomialError, sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{name}: expected a polynomial in {', '.join(map(str, variables))}, got {f} ({exc}); "
                         "expand powers with integer exponents") from None
    extra = sorted(map(str, poly.free_symbols - set(variables)))
    if extra:
        raise InputError(f"{name}: expected numeric coefficients, got the free symbols {extra}; substitute values "
                         "with .subs or add them to variables")
    if not all(c.is_real is not False and not c.has(sympy.I) for c in poly.coeffs()):
        raise InputError(f"{name}: expected real coefficients, got {poly.coeffs()}; take the real part")
    degrees = {sum(m) for m in poly.monoms()} if not poly.is_zero else set()
    if len(degrees) > 1:
        raise InputError(_homogeneity_error(poly, name))
    if poly.is_zero:
        return poly, variables, None
    d = degrees.pop()
    if degree is not None and degree != d:
        raise InputError(f"{name}: expected degree {degree}, got degree {d}; pass degree={d} or fix {name}")
    if d == 0:
        raise InputError(f"{name}: expected a form of degree ≥ 1, got the constant {poly.as_expr()}; a nonzero "
                         "constant is not positive definite (it does not vanish at 0)")
    return poly, variables, d


def _odd_degree(form: _Form):
    """An odd form takes both signs: the failed result at a grid point where f ≠ 0."""
    for pt in itertools.product(range(-1, form.d + 1), repeat=form.n):
        if any(pt):
            x = tuple(Fraction(c) for c in pt)
            _, s = form.value_sign(x)
            if s:
                return form.failed(x if s < 0 else tuple(-c for c in x),
                                   f"odd degree {form.d}: {form.name}(−x) = −{form.name}(x)")
    raise RuntimeError("internal error: a nonzero odd form vanished on a grid finer than its degree")


def _one_variable(form: _Form):
    """The sphere in R¹ is {±1}: decide f(1)."""
    x = (Fraction(1),)
    v, s = form.value_sign(x)
    if s is not None and s <= 0:
        return form.failed(x, "the unit sphere in R¹ is {±1}")
    if s is None:
        return ConditionResult(form.name, Status.UNDECIDED, detail=f"the sign of {form.name}(1) = {v} is not "
                               "decided; raise the precision (prec=) or simplify the coefficient")
    if form.rational:
        margin = Margin(v, v, exact=sympy.Rational(v.numerator, v.denominator), point=x)
    else:
        with flint.ctx.workprec(form.prec):
            ball = enclose(v, prec=None)
        margin = Margin(lower_fraction(ball), upper_fraction(ball), exact=v, point=x)
    return ConditionResult(form.name, Status.EXACT if form.rational else Status.CERTIFIED, margin=margin,
                           detail=f"one variable: {form.name}(±1) = {v} > 0.")


def _estimate(form: _Form, accuracy: Accuracy, deadline: float):
    """The float minimum of g over the faces (the one estimator on each face): (value, face, y*)."""
    fnum = sympy.lambdify(form.variables, form.poly.as_expr(), "numpy")
    n, d = form.n, form.d
    best = None
    for i in range(n):
        def neg_g(*ys, i=i):
            xs = [np.asarray(y, dtype=float) for y in ys]
            xs.insert(i, np.ones(np.broadcast_shapes(*(np.shape(y) for y in xs))))
            with np.errstate(all="ignore"):
                return -np.asarray(fnum(*xs), dtype=float) / sum(x * x for x in xs) ** (d / 2)
        cands = maximise(neg_g, [-1.0] * (n - 1), [1.0] * (n - 1), starts=accuracy.starts, seed=accuracy.seed,
                         deadline=deadline)
        if cands and (best is None or -cands[0].value < best[0]):
            best = (-cands[0].value, i, cands[0].point)
    value, face, ystar = best
    xstar = np.insert(np.asarray(ystar, dtype=float), face, 1.0)
    form.estimate = Estimate(value, "the minimum of g = f/‖x‖^d over the cube faces: Sobol samples on every "
                             "face refined by SLSQP", point=tuple(xstar / np.linalg.norm(xstar)))
    return face, ystar


class _Best:
    """The best proved upper bound of min g so far, at a rational point; the probe the engine calls."""

    def __init__(self, form: _Form):
        self.form, self.hi, self.point = form, None, None

    def offer(self, x: tuple):
        u = self.form.g_upper(x)
        if u is not None and (self.hi is None or u < self.hi):
            self.hi, self.point = u, x

    def probe(self, piece: int, centre: tuple, value: arb):
        cub = -float_down(value)         # the certified upper bound of g at the box centre
        if self.hi is not None and not cub < self.hi:
            return None
        y = [Fraction(c) for c in centre]
        x = tuple(y[:piece]) + (Fraction(1),) + tuple(y[piece:])
        if cub <= 0:
            v, s = self.form.value_sign(x)
            if s is not None and s <= 0:
                return Refutation(float(-cub), x)
        self.offer(x)
        return None


def _rational_candidates(form: _Form, best: _Best, face: int, ystar):
    """Rational points near the estimated minimiser: a failed result, or None after updating ``best``."""
    for den in CANDIDATE_DENOMINATORS:
        yq = [min(max(Fraction(float(c)).limit_denominator(den), Fraction(-1)), Fraction(1)) for c in ystar]
        x = tuple(yq[:face]) + (Fraction(1),) + tuple(yq[face:])
        _, s = form.value_sign(x)
        if s is not None and s <= 0:
            return form.failed(x, "found near the estimated minimiser")
        best.offer(x)
    return None


def _branch_and_bound(form: _Form, best: _Best, budget: Budget, accuracy: Accuracy, start: float):
    """Run the engine over the n faces; the certified, failed or undecided result."""
    n, name = form.n, form.name
    seconds = math.inf if budget.seconds is None else budget.seconds
    boxes = FORM_BUDGET.boxes if budget.boxes is None else budget.boxes
    with flint.ctx.workprec(form.prec):
        faces = [CubeFace(form.poly, form.variables, i, form.d) for i in range(n)]
        roots = [(i, (-1.0,) * (n - 1), (1.0,) * (n - 1)) for i in range(n)]
        lower0 = -float_up(best.hi) if best.hi is not None else -math.inf
        out = BranchAndBound(FaceEnclosure(faces), roots).run(
            Goal.SUPREMUM, below=0.0, rel_gap=accuracy.rel_gap, abs_gap=accuracy.abs_gap, boxes=boxes,
            deadline=time.monotonic() + seconds, lower=lower0, probe=best.probe)
    if out.stop is Stop.FAILED:
        return form.failed(out.refutation.point, f"found by the branch and bound after {out.boxes} boxes")
    lower = Fraction(-out.upper) if math.isfinite(out.upper) else None
    margin = Margin(lower, best.hi, point=best.point)
    where = f"{out.boxes} boxes on {n} cube faces, {time.monotonic() - start:.2f} s"
    stop = "" if out.stop is Stop.DONE else out.reason
    if lower is not None and lower > 0:
        detail = (f"{name} > 0 on the unit sphere (certified, arb branch and bound, {where}): "
                  f"min {name}|_S ∈ [{float_down(lower):.8g}, {float_up(best.hi):.8g}]"
                  + (f"; refinement stopped: {stop}" if stop else "") + ".")
        return ConditionResult(name, Status.CERTIFIED, margin=margin, estimate=form.estimate, detail=detail)
    lo_s = "−∞" if lower is None else f"{float_down(lower):.6g}"
    detail = (f"undecided ({stop}; {where}): the certified lower bound {lo_s} of min {name}|_S is not "
              f"positive and no rational point with {name} ≤ 0 was found (estimated min "
              f"{form.estimate.value:.6g}); raise Budget.seconds, or the minimum may be exactly 0 at an "
              "irrational point.")
    return ConditionResult(name, Status.UNDECIDED, margin=margin, estimate=form.estimate, detail=detail)


def _check_options(budget, accuracy, name: str) -> None:
    problems = [f"{what}: expected a lkverify.options.{cls.__name__} or None, got {v!r}"
                for what, v, cls in (("budget", budget, Budget), ("accuracy", accuracy, Accuracy))
                if v is not None and not isinstance(v, cls)]
    if problems:
        raise InputError(f"{name}: " + "; ".join(problems) + "; pass e.g. budget=Budget(seconds=5)")


def _zero_form(name: str, n: int) -> ConditionResult:
    x = tuple(Fraction(int(j == 0)) for j in range(n))
    return ConditionResult(name, Status.FAILED, margin=Margin(0, 0, exact=sympy.Integer(0)), witness=x,
                           detail=f"{name} ≡ 0, so {name}(e_1) = 0: not positive definite.")


def homogeneous_positive_on_sphere(f, variables, *, degree: int | None = None, name: str = "f",
                                   budget: Budget | None = None, accuracy: Accuracy | None = None,
                                   prec: int = 64) -> ConditionResult:
    """Prove a homogeneous polynomial f positive definite: a certified lower bound of min f on ‖x‖ = 1.

    For f homogeneous of degree d, f(x) = ‖x‖^d f(x/‖x‖), so f is positive
    definite iff m = min_{‖x‖=1} f > 0.  The sphere is covered by the faces
    x_i = 1 (the others in [−1, 1]) of the cube; since d is even,
    f(−x) = f(x) covers the faces x_i = −1.  On each face
    g(y) = f(x)/‖x‖^d takes exactly the values of f on the matching part of
    the sphere, and a best-first arb branch and bound encloses its minimum:
    on every box the lower bound is the better of the natural interval
    extension and the mean-value (centred) form with the arb gradient
    (:class:`FaceEnclosure`, run by :class:`lkverify.certify.engine.BranchAndBound`).

    Parameters
    ----------
    f : sympy.Expr
        A homogeneous polynomial in ``variables`` with numeric coefficients
        (rationals, radicals, ``pi`` …).
    variables : sequence of sympy.Symbol
    degree : int, optional
        The expected degree; checked.
    name : str
    budget : lkverify.options.Budget, optional
        The branch and bound stops at ``seconds`` or ``boxes`` (default
        :data:`FORM_BUDGET`); with a positive lower bound the result is still
        ``certified`` (with a wider margin).
    accuracy : lkverify.options.Accuracy, optional
        Stop when the certified gap hi − lo ≤ rel_gap·|hi| (default
        :data:`FORM_ACCURACY`); ``starts`` and ``seed`` steer the float estimate
        (:func:`lkverify.certify.estimate.maximise` on every face).
    prec : int
        arb precision in bits.

    Returns
    -------
    ConditionResult
        ``certified``: ``margin.lo`` > 0 is a proved lower bound of min f on
        the sphere; ``margin.hi`` is f at the rational point ``margin.point``
        divided by its norm^d (exact for rational coefficients).
        ``failed``: ``witness`` is a rational point with f ≤ 0 (checked
        exactly; odd degrees fail at once since f(−x) = −f(x)).
        ``undecided``: the budget ran out with a lower bound ≤ 0.
        ``estimate``: the sampled/optimised minimum and its minimiser.

    Raises
    ------
    InputError
        Not a polynomial in ``variables``, free symbols in the coefficients,
        not homogeneous (the message lists each term's degree), wrong degree.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> res = homogeneous_positive_on_sphere(x**4 + y**4, [x, y])
    >>> res.status, res.margin.lo <= sympy.Rational(1, 2) <= res.margin.hi     # min is 1/2 at |x| = |y|
    (<Status.CERTIFIED: 'certified'>, True)
    >>> homogeneous_positive_on_sphere(x**4 - x**2*y**2 / 4 - y**4, [x, y]).status
    <Status.FAILED: 'failed'>
    """
    start = time.monotonic()
    _check_options(budget, accuracy, name)
    poly, variables, d = _parse(f, variables, degree, name)
    if d is None:
        return _zero_form(name, len(variables))
    form = _Form(poly, variables, d, name, prec)
    if d % 2 == 1:
        return _odd_degree(form)
    if form.n == 1:
        return _one_variable(form)
    budget, accuracy = budget or FORM_BUDGET, accuracy or FORM_ACCURACY
    seconds = math.inf if budget.seconds is None else budget.seconds
    face, ystar = _estimate(form, accuracy, deadline=start + seconds / 2)
    best = _Best(form)
    hit = _rational_candidates(form, best, face, ystar)
    if hit is not None:
        return hit
    return _branch_and_bound(form, best, budget, accuracy, start)
