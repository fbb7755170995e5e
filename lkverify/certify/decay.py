"""Parameters, regions and decay envelopes from the final inequalities of a proof.

A proof ends with three inequalities in a few scalar quantities x = (x_1, …, x_n),
all ≥ 0 (‖ω(t)‖, ‖s(t) − r‖, (∫ ‖s(ξ) − r‖³ dξ)^{1/3}, …), valid on a region
0 ≤ x_i ≤ h_i:

    L(x) ≤ V ≤ U(x),        V̇ ≤ W(x).

A :class:`DecayModel` holds them.  :func:`certify_decay` proves, on the region,

* ``L(x) ≥ l_v x_v²`` for every bounded output quantity x_v (so x_v ≤ √(V/l_v)),
* ``W(x) + c̃·U(x)^p ≤ 0`` (so V̇ ≤ −c̃ V^p),

and bounds the initial value V(t0) ≤ C0‖χ‖².  The region is a box; the
inequalities are tight at the origin, where no interval method can prove them,
so they are proved on the *outer faces* of the box and carried inside by a
scaling argument whose hypotheses are checked exactly on the monomials:
with k = 2p, ``G(ρx)/ρ^k`` is nondecreasing in ρ ∈ (0, 1] when every monomial of
W with a negative coefficient has degree ≤ k and every positive one degree ≥ k,
and every monomial of U with a positive coefficient has degree ≥ 2 (negative
ones ≤ 2); ``(L − l x_v²)(ρx)/ρ²`` is affine in ρ when L has only degrees 2 and
3, so it is proved at ρ → 0 (the quadratic part, on the faces) and at ρ = 1.

From V̇ ≤ −c̃V^p the envelope follows (:class:`Envelope`): for p > 1
``V(t) ≤ V0 (1 + (p−1) c̃ V0^{p−1} (t − t0))^{−1/(p−1)}``, for p = 1
``V(t) ≤ V0 e^{−c̃(t − t0)}``, and with a factor h(t) (V̇ ≤ −c̃ h V^p) the time
t − t0 is replaced by ∫_{t0}^t h.  Since the right-hand side increases with V0,
V0 ≤ C0‖χ‖² gives, for every output quantity,

    x_v(t) ≤ d_v ‖χ‖ (1 + κ ‖χ‖^{2(p−1)} (t − t0))^{−1/(2(p−1))},   d_v = √(C0/l_v),

valid while the solution stays in the region, which it does for
‖χ‖ < δ̃ = min_v h_v / max(d_v, 1) (continuity).  Every number is computed with
arb and rounded outward; the results carry the status ``certified`` only when
every step was proved.

:class:`DecayModel`, :class:`Envelope` and :class:`StatedAt` are in :mod:`.decay_model`
(re-exported here); this module proves and estimates: :class:`DecayCertificate`,
:func:`certify_decay`, :func:`certify_model`, :func:`tighten`, :func:`estimate_decay`,
:func:`search_parameters`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy
from flint import arb

from ..errors import InputError, UnsupportedInput
from ..options import Accuracy, Budget, Deadline
from ..report.results import Result
from ..status import Status
from . import bounds
from .decay_model import DecayModel, Envelope, StatedAt, _exact_floats  # re-exported: moved to decay_model
from .intervals import enclose, float_down, float_up
from .matrices import matrix_positive_definite

__all__ = ["C0_REL_GAP", "CERTIFY_SECONDS", "DecayCertificate", "DecayModel", "Envelope", "ESTIMATE_GRID", "StatedAt",
           "INFEASIBLE_SCORE", "SEARCH_GRID", "SEARCH_MAXITER", "SEARCH_POPSIZE", "SEARCH_STALL_RTOL", "certify_decay", "certify_model", "estimate_decay", "search_parameters", "tighten"]

#: default time budget of one :func:`certify_decay` (seconds, shared by its interval checks)
CERTIFY_SECONDS = 60.0
#: relative accuracy asked of the certified supremum C0 (V(t0) ≤ C0‖χ‖²)
C0_REL_GAP = 1e-3
#: default points per axis of the estimator's face grids (geometric towards 0)
ESTIMATE_GRID = 41
#: the parameter search: differential evolution's generations and population factor, and its face grid
SEARCH_MAXITER, SEARCH_POPSIZE, SEARCH_GRID = 250, 20, 31
#: the relative improvement of the best score that resets the search's early stop (``stall``)
SEARCH_STALL_RTOL = 1e-3
#: points sampled uniformly before the parameter search, to seed its population with feasible ones
PRESAMPLE = 1000
#: the objective's value at parameters for which the estimator finds no admissible constants
INFEASIBLE_SCORE = 1e6


@dataclasses.dataclass(frozen=True)
class DecayCertificate:
    """What :func:`certify_decay` proved (or failed to).

    Examples
    --------
    >>> import sympy
    >>> from lkverify.options import Budget
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> half, Q = sympy.Rational(1, 2), w**2 + e**2
    >>> m = DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -w**3 - e**3, sympy.Rational(3, 2),
    ...                (w, e), {}, {"d1": e, "d2": w})
    >>> cert = certify_decay(m, c_tilde=sympy.Rational(4, 5), delta_tilde=sympy.Rational(1, 4),   # c̃ > 1/√2
    ...                      lower_coefficients={e: sympy.Rational(9, 10), w: sympy.Rational(9, 10)},
    ...                      budget=Budget(seconds=30))
    >>> cert.status, cert.detail
    (<Status.FAILED: 'failed'>, 'W + c̃U^p ≤ 0 on w = 1/2: failed; W + c̃U^p ≤ 0 on e = 1/2: failed')
    >>> cert.counterexamples[0]                        # at w = e = 1/2: W/U^{3/2} = −1/√2
    ('rate', {'w': 0.5, 'e': 0.5})
    """

    status: Status
    constants: dict  # name → float (upper bounds for d_v, C0; lower bounds for l_v, c̃, the rate, δ̃)
    envelopes: tuple
    checks: tuple  # bounds.CheckResult / SupResult of every step
    detail: str
    seconds: float
    counterexamples: tuple = ()  # (what, point) for refuted face checks: what = "rate" or an output variable

    def results(self, paper: "Mapping[str, float] | StatedAt | None" = None, names: Mapping[str, str] | None = None,
                values: Mapping | None = None) -> list:
        """Results for the report: every constant, compared with the paper's value if given.

        ``paper`` may be a :class:`StatedAt`: its values are compared only at the data where the
        paper states them (``values``, the resolved parameters; None: nowhere).
        """
        note, stated = "", set(paper.values) if isinstance(paper, StatedAt) else set()
        if isinstance(paper, StatedAt):
            if not paper.applies(values):
                note = f"(the paper states a value only at {paper.where})"
            paper = paper.at(values)
        paper = dict(paper or {})
        out = []
        for key, value in self.constants.items():
            pv = paper.get(key)
            better = None
            if pv is not None:
                better = value <= pv if key.startswith("d") and key != "delta_tilde" and key != "d3" else value >= pv
            detail = (names or {}).get(key, "")
            if pv is not None:
                detail += (f" paper: {pv:g}; lkverify: {value:.4g} "
                           f"({'equal or better' if better else 'worse'} than the paper)")
            elif note and key in stated:
                detail += " " + note
            out.append(Result("constant", key, self.status, {"value": value, "paper": pv, "equal_or_better": better},
                              detail.strip()))
        return out


def _q(x) -> sympy.Rational:
    """An exact rational: Rationals and ints as they are, floats by their exact binary value."""
    if isinstance(x, sympy.Rational):
        return x
    if isinstance(x, (int, float)):
        return sympy.Rational(x)
    x = sympy.sympify(x)
    if x.is_Rational:
        return x
    if x.is_Float:
        return sympy.Rational(x)
    raise InputError(f"expected a rational number (an int, a float or a SymPy Rational), got {x}; "
                     "substitute the parameters first (DecayModel.at)")


def _monomials(expr, variables):
    """(total degree, coefficient) of each monomial of a polynomial in ``variables``.

    Raises
    ------
    UnsupportedInput
        ``expr`` is not a polynomial in them (e.g. a power e^(5/2) of a non-integer order μ).
    """
    try:
        poly = sympy.Poly(sympy.expand(expr), *variables)
    except sympy.PolynomialError:
        names = ", ".join(map(str, variables))
        raise UnsupportedInput(f"the decay model's L, U, W must be polynomials in {names} for the scaling argument, "
                               f"got {_short(expr)} (a power with a non-integer exponent, e.g. of an order μ that "
                               f"is not a whole number); choose such a parameter or prove the decay otherwise") from None
    return [(sum(m), c) for m, c in poly.terms()]


def _short(expr, limit: int = 120) -> str:
    text = str(expr)
    return text if len(text) <= limit else text[:limit] + "…"


def _check_structure(model: DecayModel) -> list[str]:
    """The exact hypotheses of the scaling argument (empty list when they hold)."""
    problems = []
    k = 2 * model.p
    for deg, c in _monomials(model.vdot, model.variables):
        if not c.is_number:
            problems.append(f"W has a non-numeric coefficient {c}")
        elif c < 0 and deg > k:
            problems.append(f"W has a negative term of degree {deg} > {k}")
        elif c > 0 and deg < k:
            problems.append(f"W has a positive term of degree {deg} < {k} (coefficient {c}); the decay cannot be proved")
    for deg, c in _monomials(model.upper, model.variables):
        if c > 0 and deg < 2 or c < 0 and deg > 2:
            problems.append(f"U has a term of degree {deg} with coefficient {c}: not of the supported shape")
        if c < 0:
            problems.append(f"U has a negative coefficient {c}; U ≥ 0 cannot be read off")
    for deg, c in _monomials(model.lower, model.variables):
        if deg not in (2, 3):
            problems.append(f"L has a term of degree {deg}; only degrees 2 and 3 are supported")
    return problems


def _faces(model: DecayModel):
    """The outer faces of the region box: (variable, its upper bound, the box of the others)."""
    for v in model.variables:
        yield v, model.region[v], {u: (sympy.S.Zero, model.region[u]) for u in model.variables if u != v}


def certify_decay(model: DecayModel, *, c_tilde, lower_coefficients: Mapping, delta_tilde,
                  budget: Budget = Budget(seconds=CERTIFY_SECONDS),
                  progress: Callable[[str], None] | None = None) -> DecayCertificate:
    """Prove the decay envelope of ``model`` (parameters already substituted) with candidate constants.

    Parameters
    ----------
    model : DecayModel
        With numeric coefficients (see :meth:`DecayModel.at`).
    c_tilde : rational
        Candidate rate in V̇ ≤ −c̃ V^p.
    lower_coefficients : mapping
        output variable → candidate l_v in L ≥ l_v x_v².
    delta_tilde : rational
        Candidate admissible history norm; the result may lower it, never raise it.
    budget : lkverify.options.Budget
        Time for the whole certificate, shared equally by the 3n + 2 interval checks.
    progress : callable, optional
        Called with a line before each check.

    Returns
    -------
    DecayCertificate
        ``certified`` when every face inequality, every quadratic part and C0 were proved;
        ``failed`` with ``counterexamples`` when a face check was refuted at a point;
        ``undecided`` otherwise.

    Raises
    ------
    UnsupportedInput
        The model is not of the shape the scaling argument covers (the message lists why).

    Examples
    --------
    V = w² + e², V̇ ≤ −w³ − e³ on 0 ≤ w, e ≤ 1/2: −W/U^{3/2} ≥ 1/√2 and L ≥ e², L ≥ w².

    >>> import sympy
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> half, Q = sympy.Rational(1, 2), w**2 + e**2
    >>> m = DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -w**3 - e**3, sympy.Rational(3, 2),
    ...                (w, e), {}, {"d1": e, "d2": w})
    >>> cert = certify_decay(m, c_tilde=sympy.Rational(7, 10), delta_tilde=sympy.Rational(1, 4),
    ...                      lower_coefficients={e: sympy.Rational(9, 10), w: sympy.Rational(9, 10)},
    ...                      budget=Budget(seconds=30))
    >>> cert.status, 1 < cert.constants["d1"] < 1.1
    (<Status.CERTIFIED: 'certified'>, True)
    """
    say = progress or (lambda msg: None)
    start = time.monotonic()
    problems = _check_structure(model)
    if problems:
        raise UnsupportedInput(f"{model.name}: expected a model of the shape the scaling argument covers, got: "
                               + "; ".join(problems) + "; rewrite the final inequalities (see DecayModel)")
    each = (budget.seconds if budget.seconds is not None else math.inf) / (3 * len(model.variables) + 2)
    ct, dt = _q(c_tilde), _q(delta_tilde)
    ls = {out: _q(lv) for out, lv in lower_coefficients.items()}
    checks, refuted = _prove_faces(model, ct, ls, each, say)
    checks += _prove_quadratic_parts(model, ls, say)
    c0res = _initial_constant(model, dt, each, say)
    checks.append(c0res)
    ok = all(getattr(c, "status", Status.UNDECIDED).is_proof for c in checks)
    failed = [c for c in checks if getattr(c, "status", None) is Status.FAILED]
    C0 = arb(c0res.certified) if c0res.certified is not None and math.isfinite(c0res.certified) else None
    constants, envelopes = _constants_and_envelopes(model, ct, ls, dt, C0) if C0 is not None else ({}, [])
    status = Status.CERTIFIED if ok and C0 is not None else (Status.FAILED if failed else Status.UNDECIDED)
    detail = ("every face inequality and C0 proved with arb" if status is Status.CERTIFIED else
              "; ".join(f"{getattr(c, 'name', 'C0')}: {c.status.value}" for c in checks
                        if not getattr(c, "status", Status.UNDECIDED).is_proof))
    return DecayCertificate(status, constants, tuple(envelopes), tuple(checks), detail, time.monotonic() - start,
                            tuple(refuted))


def _prove_faces(model: DecayModel, ct, ls: Mapping, each: float, say) -> tuple[list, list]:
    """W + c̃U^p ≤ 0 and L − l_v x_v² > 0 on every outer face: (the checks, the refuted (what, point)s).

    The faces of a variable that L − l_v x_v² does not involve are skipped for it: there it is a
    function of the other variables only, and it is 0 where they all vanish, so strict positivity
    cannot hold while L ≥ l_v x_v² follows from the other faces (scaling in the other variables).
    """
    checks, refuted = [], []
    G = model.vdot + ct * sympy.Pow(model.upper, model.p)
    for v, hi, face in _faces(model):
        say(f"{model.name}: V̇ ≤ −c̃V^p on the face {v} = {hi}")
        chk = bounds.certify_nonpositive(G.subs(v, hi), face, name=f"W + c̃U^p ≤ 0 on {v} = {hi}",
                                         budget=Budget(seconds=each))
        checks.append(chk)
        if chk.status is Status.FAILED and chk.point:
            refuted.append(("rate", {**{str(v): float(hi)}, **chk.point}))
        for out, lv in ls.items():
            if not sympy.expand(model.lower - lv * out ** 2).has(v):
                # L − l·x² does not involve v: on the face v = hi it is the same function of the other
                # variables, ≥ 0 on their box by their own faces (it vanishes where they all do)
                continue
            say(f"{model.name}: L ≥ {lv}·{out}² on the face {v} = {hi}")
            chk = bounds.certify_positive((model.lower - lv * out ** 2).subs(v, hi), face,
                                          name=f"L − l·{out}² > 0 on {v} = {hi}", budget=Budget(seconds=each))
            checks.append(chk)
            if chk.status is Status.FAILED and chk.point:
                refuted.append((out, {**{str(v): float(hi)}, **chk.point}))
    return checks, refuted


def _quadratic_part(lower, variables):
    """The degree-2 part of L (a polynomial in the variables)."""
    return sum((c * sympy.Mul(*[v ** e for v, e in zip(variables, m)])
                for m, c in sympy.Poly(sympy.expand(lower), *variables).terms() if sum(m) == 2), sympy.S.Zero)


def _prove_quadratic_parts(model: DecayModel, ls: Mapping, say) -> list:
    """ρ → 0: the quadratic part Q − l·x_v² must be ≥ 0 on the orthant; its matrix is checked PSD exactly."""
    quad = _quadratic_part(model.lower, model.variables)
    checks = []
    for out, lv in ls.items():
        H = sympy.hessian(sympy.expand(quad - lv * out ** 2), model.variables) / 2
        say(f"{model.name}: quadratic part of L − {lv}·{out}² is positive semidefinite")
        checks.append(matrix_positive_definite(H, name=f"Q − l·{out}²", semidefinite=True))
    return checks


def _initial_constant(model: DecayModel, dt, each: float, say):
    """C0 with V(t0) ≤ C0‖χ‖² (a certified supremum).

    U increases in every variable and U(χy)/χ² in χ; the sup is on the sphere Σ x_i² = δ̃² of
    the point variables, the history variables at their largest.
    """
    theta = sympy.Symbol("theta_", real=True)
    pts = model.point_variables
    if len(pts) == 1:
        sub, box = {pts[0]: dt}, {}
    else:
        sub, box = {pts[0]: dt * sympy.cos(theta), pts[1]: dt * sympy.sin(theta)}, {theta: (0, sympy.pi / 2)}
    for hv, kappa in model.history_variables.items():
        y = sympy.Symbol(f"y_{hv}", nonnegative=True)
        sub[hv] = dt * y
        box[y] = (0, _exact_floats(kappa))
    say(f"{model.name}: C0 = sup U/‖χ‖² at ‖χ‖ = δ̃")
    return bounds.sup_bound(sympy.expand(model.upper.xreplace(sub) / dt ** 2), box,
                            accuracy=Accuracy(rel_gap=C0_REL_GAP), budget=Budget(seconds=each))


def _constants_and_envelopes(model: DecayModel, ct, ls: Mapping, dt, C0: arb) -> tuple[dict, list]:
    """The certified constants (d_v, the rate, δ̃, C0, c̃, l_v; rounded outward) and the envelopes."""
    p = model.p
    ct_a = enclose(sympy.Rational(ct), prec=None)
    kappa = (enclose(p - 1, prec=None) * ct_a * C0 ** enclose(p - 1, prec=None)) if p != 1 else ct_a
    names = {v: k for k, v in model.outputs.items()}
    delta = enclose(sympy.Rational(dt), prec=None)
    constants: dict = {}
    envelopes = []
    for out, lv in ls.items():
        d = (C0 / enclose(lv, prec=None)).sqrt()
        name = names[out]
        constants[name] = float_up(d)
        h = sympy.Rational(model.region[out])
        cap = enclose(h, prec=None) / (d if d.upper() >= 1 else arb(1))
        delta = arb(min(float_down(delta), float_down(cap)))
        envelopes.append(Envelope(name, float_up(d), float_down(kappa), float(p)))
    constants[model.rate_name] = float_down(kappa)
    constants["delta_tilde"] = float_down(delta)
    constants["C0"] = float_up(C0)
    constants["c_tilde"] = float_down(sympy.Rational(ct))
    for out, lv in ls.items():
        constants[f"l_{out}"] = float_down(lv)
    return constants, envelopes


def certify_model(model: DecayModel, *, budget: Budget | float | None = Budget(seconds=CERTIFY_SECONDS),
                  attempts: int = 6, margin=sympy.Rational(99, 100), shrink=sympy.Rational(9, 10),
                  progress: Callable[[str], None] | None = None) -> DecayCertificate | None:
    """Estimate the constants of a numeric model, then certify them (lowered after each failed attempt).

    None when the estimator finds no admissible constants (V̇ ≥ 0 sampled somewhere on the
    region, or the model is not of the shape the scaling argument covers).  The
    candidates are lowered below refuted points (:func:`tighten`) or by ``shrink``.
    """
    say = progress or (lambda msg: None)
    deadline = Budget.of(budget).deadline()
    est = estimate_decay(model)
    if est is None:
        return None
    ct = sympy.Rational(est["c_tilde"]).limit_denominator(10**6) * margin
    ls = {v: sympy.Rational(est[f"l_{v}"]).limit_denominator(10**6) * margin for v in model.outputs.values()}
    dt = sympy.Rational(est["delta_tilde"]).limit_denominator(10**6)
    cert = None
    for attempt in range(attempts):
        left = deadline.remaining
        if left is not None and left <= 0:
            break
        say(f"certifying the decay model (attempt {attempt + 1}, c̃ = {float(ct):.5g})")
        cert = certify_decay(model, c_tilde=ct, lower_coefficients=ls, delta_tilde=dt,
                             budget=Budget(seconds=left if left is not None else CERTIFY_SECONDS), progress=say)
        if cert.status is Status.CERTIFIED:
            break
        if cert.counterexamples:
            tightened = tighten(model, ct, ls, cert.counterexamples)
            if tightened is None:
                break
            ct, ls = tightened
        else:
            ct, ls = ct * shrink, {k: v * shrink for k, v in ls.items()}
    return cert


def tighten(model: DecayModel, c_tilde, lower_coefficients: Mapping, counterexamples, *, factor=sympy.Rational(98, 100)):
    """Lower the candidate constants below their values at refuted points (counterexample-guided).

    Returns None when a refuted point has W ≥ 0: no rate works for these parameters.
    """
    ct = _q(c_tilde)
    ls = {k: _q(v) for k, v in lower_coefficients.items()}
    for what, point in counterexamples:
        sub = {v: _q(point[str(v)]) for v in model.variables}
        if what == "rate":
            U = model.upper.xreplace(sub)
            if model.vdot.xreplace(sub) >= 0:
                return None  # W ≥ 0 at a point of the region: these parameters cannot work
            if U > 0:
                ct = min(ct, sympy.Rational(float(-model.vdot.xreplace(sub) / U ** model.p)).limit_denominator(10**8)
                         * factor)
        else:
            x = sub[what]
            if x > 0:
                ls[what] = min(ls[what], sympy.Rational(float(model.lower.xreplace(sub) / x**2)).limit_denominator(10**8)
                               * factor)
    return ct, ls


# -- estimates and the parameter search ---------------------------------------------------------------
class _FastEstimator:
    """Sampled constants of a model family ``build(params)``, compiled once (NumPy on the box faces).

    By the scaling argument the infimum of −W/U^p and of L/x_v² over the box is
    attained on the outer faces (or, for L, by the quadratic part on the faces),
    so only the faces are sampled.
    """

    def __init__(self, build: Callable[[Mapping], DecayModel], names: Sequence[str], grid: int = ESTIMATE_GRID):
        self.names = list(names)
        self.syms = [sympy.Symbol(f"par_{n}", real=True) for n in self.names]
        model = build(dict(zip(self.names, self.syms)))
        self.model = model
        vs = model.variables
        args = list(vs) + self.syms
        quad = _quadratic_part(model.lower, vs)
        self.f = {k: sympy.lambdify(args, e, "numpy", docstring_limit=0) for k, e in
                  (("L", model.lower), ("U", model.upper), ("W", model.vdot), ("Q", quad))}
        self.h = [sympy.lambdify(self.syms, model.region[v], "numpy") for v in vs]
        self.kappa = {hv: sympy.lambdify(self.syms, k, "numpy") for hv, k in model.history_variables.items()}
        # geometric near 0: the scaling structure makes the small scales decisive
        self.grid = np.concatenate([[0.0], np.geomspace(1e-7, 1.0, grid - 1)])
        self.extra: list[dict] = []  # points (variable name → value) added after refuted certificates
        self.violations: list[dict] = []  # points where the refinement found W ≥ 0
        self.p = float(model.p)

    def _faces(self, n: int) -> list:
        """Per coordinate i, its values on the n outer faces of the unit box sampled on :attr:`grid` (1 on
        face i, the grid elsewhere), concatenated face after face."""
        if getattr(self, "_unit_faces", None) is None or len(self._unit_faces) != n:
            faces = []
            for k in range(n):
                mesh = np.meshgrid(*[self.grid] * (n - 1), indexing="ij")
                shape = mesh[0].shape if mesh else (1,)  # one variable: the face is the single point x = h
                it = iter(mesh)
                faces.append([(np.ones(shape) if i == k else next(it)).ravel() for i in range(n)])
            self._unit_faces = [np.concatenate([f[i] for f in faces]) for i in range(n)]
        return self._unit_faces

    def _refine(self, fn, his, k, start, values):
        """Local minimisation of fn over the face x_k = h_k from a start point (bounded)."""
        import warnings

        from scipy.optimize import minimize

        n = len(his)
        free = [i for i in range(n) if i != k]

        def g(z):
            x = [0.0] * n
            x[k] = his[k]
            for i, zi in zip(free, z):
                x[i] = zi
            return float(fn(x))

        z0 = [start[i] for i in free]
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            if not free:  # one variable: the face is a single point, nothing to minimise
                best, zb = g(z0), z0
            else:
                res = minimize(g, z0, method="L-BFGS-B", bounds=[(0.0, his[i]) for i in free])
                best, zb = (float(res.fun), list(res.x)) if float(res.fun) < g(z0) else (g(z0), z0)
        if not np.isfinite(best):
            best, zb = g(z0), z0
        point = [0.0] * n
        point[k] = his[k]
        for i, zi in zip(free, zb):
            point[i] = float(zi)
        self.last_point = point
        return best

    def __call__(self, values: Sequence[float], *, refine: bool = False) -> dict | None:
        model, vs, p = self.model, self.model.variables, self.p
        his = [float(h(*values)) for h in self.h]
        if min(his) <= 0:
            return None
        n = len(vs)
        # the face points x_k = h_k, the other coordinates grid·h_i: the unit grid's face pattern (built once)
        # times h (the same products as scaling the axes first, so the same floats)
        X = [u * his[i] for i, u in enumerate(self._faces(n))]
        if self.extra:  # counterexample points of earlier attempts, kept inside the region box
            X = [np.concatenate([X[i], np.clip([pt[str(vs[i])] for pt in self.extra], 0, his[i])]) for i in range(n)]
        L, U, W, Q = (np.broadcast_to(self.f[k](*X, *values), X[0].shape) for k in ("L", "U", "W", "Q"))
        if np.any(W >= 0) or np.any(U <= 0):
            return None
        ratio = -W / U ** p
        ct = float(np.min(ratio))
        ls = {}
        for out in model.outputs.values():
            x = X[vs.index(out)]
            with np.errstate(divide="ignore", invalid="ignore"):
                ls[out] = float(min(np.min(np.where(x > 0, L / x**2, np.inf)), np.min(np.where(x > 0, Q / x**2, np.inf))))
            if not ls[out] > 0:
                return None
        if refine:
            sizes = [len(self.grid) ** (n - 1)] * n
            face_of = np.concatenate([np.repeat(np.arange(n), sizes), np.full(len(self.extra), -1)])
            fW, fU, fL, fQ = self.f["W"], self.f["U"], self.f["L"], self.f["Q"]
            order = np.argsort(ratio)
            picks = [i for k in range(n) for i in order[face_of[order] == k][:6]]
            for idx in picks:
                k, start = int(face_of[idx]), [float(Xi[idx]) for Xi in X]
                val = self._refine(lambda x: -fW(*x, *values) / fU(*x, *values) ** p, his, k, start, values)
                if val <= 0:
                    self.violations.append({str(v): x for v, x in zip(vs, self.last_point)})
                ct = min(ct, val)
            for out in model.outputs.values():
                o = vs.index(out)
                for fn in (fL, fQ):
                    vals = np.broadcast_to(fn(*X, *values), X[0].shape)
                    with np.errstate(divide="ignore", invalid="ignore"):
                        r = np.where(X[o] > 0, vals / X[o] ** 2, np.inf)
                    order = np.argsort(r)
                    for idx in [i for k in range(n) for i in order[face_of[order] == k][:6]]:
                        k, start = int(face_of[idx]), [float(Xi[idx]) for Xi in X]
                        if start[o] <= 0:
                            continue
                        ls[out] = min(ls[out], self._refine(
                            lambda x, fn=fn, o=o: fn(*x, *values) / max(x[o], 1e-300) ** 2, his, k, start, values))
            if ct <= 0 or min(ls.values()) <= 0:
                return None
        th = np.linspace(0, np.pi / 2, 61)
        pts = model.point_variables
        dt = min(his)
        names = {v: k for k, v in model.outputs.items()}
        for _ in range(30):
            args = {v: np.zeros_like(th) for v in vs}
            if len(pts) == 1:
                args[pts[0]] = np.full_like(th, dt)
            else:
                args[pts[0]], args[pts[1]] = dt * np.cos(th), dt * np.sin(th)
            for hv, kf in self.kappa.items():
                args[hv] = np.full_like(th, dt * float(kf(*values)))
            C0 = float(np.max(self.f["U"](*[args[v] for v in vs], *values))) / dt**2
            ds = {out: math.sqrt(C0 / l) for out, l in ls.items()}
            new = min(his[vs.index(out)] / max(d, 1.0) for out, d in ds.items())
            if abs(new - dt) <= 1e-12 * dt:
                break
            dt = new
        rate = (p - 1) * ct * C0 ** (p - 1) if p != 1 else ct
        out = {names[v]: d for v, d in ds.items()}
        out.update({model.rate_name: rate, "delta_tilde": dt, "c_tilde": ct, "C0": C0})
        out.update({f"l_{v}": l for v, l in ls.items()})
        return out


def estimate_decay(model: DecayModel, *, grid: int = ESTIMATE_GRID, refine: bool = True,
                   violations: list | None = None) -> dict | None:
    """Sampled (estimated) constants of a numeric model: l_v, c̃, C0, d_v, rate, δ̃; None if infeasible.

    None also when the model, at these parameter values, is not of the shape the scaling
    argument covers (the signs of its coefficients depend on the parameters, so a search
    moves on to other values); :func:`certify_decay` raises
    :class:`~lkverify.errors.UnsupportedInput` for it.  With ``refine`` the face minima are
    polished by local optimisation from the best samples; points where W ≥ 0 is found are
    appended to ``violations``.

    Examples
    --------
    >>> import sympy
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> half, Q = sympy.Rational(1, 2), w**2 + e**2
    >>> m = DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -w**3 - e**3, sympy.Rational(3, 2),
    ...                (w, e), {}, {"d1": e, "d2": w})
    >>> round(estimate_decay(m)["c_tilde"], 4)      # min (w³ + e³)/(w² + e²)^{3/2} = 1/√2 at w = e
    0.7071
    """
    if _check_structure(model):
        return None
    est = _FastEstimator(lambda _: model, [], grid)
    out = est([], refine=refine)
    if violations is not None:
        violations += est.violations
    return out


def search_parameters(build: Callable[[Mapping], DecayModel], bounds_: Mapping[str, tuple], *,
                      objective: Callable[[dict], float], seed: int = 0, maxiter: int = SEARCH_MAXITER,
                      popsize: int = SEARCH_POPSIZE, grid: int = SEARCH_GRID, extra_points: Sequence[dict] = (),
                      deadline: Deadline | None = None, stall: int | None = None,
                      stall_rtol: float = SEARCH_STALL_RTOL) -> tuple[dict, dict | None]:
    """Estimated best free parameters: differential evolution over ``bounds_`` of ``objective(estimate)``.

    ``build(params)`` returns the model for a parameter dict (it is called once with
    symbols and compiled).  The outcome is an estimate (a search, not a proof);
    certify it with :func:`certify_decay`.

    Parameters
    ----------
    build : callable
    bounds_ : mapping
        Free parameter name → (low, high).
    objective : callable
        Estimate dict → number to minimise (infeasible points score :data:`INFEASIBLE_SCORE`).
    seed, maxiter, popsize : int
        Of :func:`scipy.optimize.differential_evolution`.
    grid : int
        Points per axis of the estimator's face grids.
    extra_points : sequence of dict
        Points (variable name → value) sampled in addition to the grids (earlier counterexamples).
    deadline : lkverify.options.Deadline, optional
        The search stops at the end of the generation in which it expires, keeping the best
        point found so far (never interrupted half-way).
    stall : int, optional
        An early stop: the search also stops at the end of the first generation after which
        the best score has not improved by more than ``stall_rtol`` (relative) for ``stall``
        generations; default none (the full ``maxiter`` generations or scipy's convergence).
        It only picks the point sooner: what is returned is the best point evaluated and the
        estimate recomputed there (None when it is infeasible), never a score of another point.
    stall_rtol : float
        The relative improvement that counts for ``stall``.

    Returns
    -------
    (dict, dict or None)
        The parameters, and the estimate there (None when no feasible point was found).

    Examples
    --------
    >>> import sympy
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> Q, half = w**2 + e**2, sympy.Rational(1, 2)
    >>> def build(p):                                  # W = −a(w³ + e³): c̃ = a/√2 grows with a
    ...     return DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -p["a"] * (w**3 + e**3),
    ...                       sympy.Rational(3, 2), (w, e), {}, {"d1": e, "d2": w})
    >>> params, est = search_parameters(build, {"a": (0.5, 2)}, objective=lambda est: -est["c_tilde"],
    ...                                 maxiter=10, popsize=5, grid=9)
    >>> round(float(params["a"]), 2), round(est["c_tilde"], 3)
    (2.0, 1.414)
    >>> params, est = search_parameters(build, {"a": (0.5, 2)}, objective=lambda est: -est["c_tilde"],
    ...                                 maxiter=200, popsize=5, grid=9, stall=5)   # stops after 5 flat generations
    >>> round(float(params["a"]), 2), round(est["c_tilde"], 3)
    (2.0, 1.414)
    """
    from scipy.optimize import differential_evolution

    if stall is not None and (isinstance(stall, bool) or not isinstance(stall, int) or stall < 1):
        raise InputError(f"stall: expected a positive number of generations or None, got {stall!r}")
    names = list(bounds_)
    est = _FastEstimator(build, names, grid)
    est.extra = list(extra_points)
    # a range of positive values spanning a decade or more is searched in log10: a small feasible
    # region (δ ≲ 0.01 of a range up to 0.45) is otherwise missed by every member of the population,
    # and a population that sees only infeasible points has converged at once
    logs = [bool(bounds_[n][0] > 0 and bounds_[n][1] >= 10 * bounds_[n][0]) for n in names]

    def point(z):
        return [10.0 ** zi if lg else zi for zi, lg in zip(z, logs)]

    # the best score evaluated so far (with greedy selection it is the population's best), and the
    # generations since it last improved by more than stall_rtol (the early stop)
    best = {"score": math.inf, "ref": math.inf, "flat": 0}

    def f(z):
        r = est(point(z))
        score = INFEASIBLE_SCORE if r is None else objective(r)
        if score < best["score"]:
            best["score"] = score
        return score

    def expired(xk, convergence=None) -> bool:  # returning True stops differential_evolution cleanly
        if deadline is not None and deadline.expired:
            return True
        if stall is None:
            return False
        score, ref = best["score"], best["ref"]
        if score < ref and (not math.isfinite(ref) or ref - score > stall_rtol * abs(ref)):
            best["ref"], best["flat"] = score, 0
        else:
            best["flat"] += 1
        return best["flat"] >= stall

    ranges = [tuple(np.log10(bounds_[n])) if lg else bounds_[n] for n, lg in zip(names, logs)]
    # a population that sees only infeasible points converges at once: seed it with feasible points
    # found by uniform sampling of the (log) box, as many as half the population, if there are any
    lo, hi = (np.array([r[k] for r in ranges], dtype=float) for k in (0, 1))
    rng = np.random.default_rng(seed)
    npop = popsize * len(names)
    feasible = []
    for _ in range(PRESAMPLE):
        if len(feasible) >= npop // 2 or (deadline is not None and deadline.expired):
            break
        z = lo + rng.random(len(names)) * (hi - lo)
        if est(point(z)) is not None:
            feasible.append(z)
    init = "latinhypercube"
    if feasible:
        init = np.vstack([np.array(feasible), lo + rng.random((npop - len(feasible), len(names))) * (hi - lo)])
    res = differential_evolution(f, ranges, seed=seed, maxiter=maxiter, popsize=popsize, init=init,
                                 tol=1e-12, polish=False, callback=expired)
    x = point(res.x)
    params = dict(zip(names, x))
    return params, est(x)
