"""Adversarial witnesses: states and histories that refute a bound ``lhs ≤ rhs``, rechecked in interval arithmetic.

A bound step claims ``lhs ≤ rhs`` for every admissible state and history in a region.
:func:`search_witness` looks for a state and a history where ``lhs − rhs > 0`` and
reports one only after the violation has been *proved* at an exact point: its
parameters are rationals, the point is substituted into the exact expression and the
value enclosed with :func:`~lkverify.certify.intervals.convert.enclose` (arb).  A float
that merely looks positive is never a refutation.

The witness family
------------------
The claim is written in the state functions at ``t`` (``s_x(t)``), at delayed times
``t − c`` (c a constant once the parameters have values) and under window integrals
``∫_{t−h}^{t−h'} F(ξ, t, x(ξ), x(t), …) dξ``; the right-hand side also in
:class:`~lkverify.certify.steps.measures.Measure` symbols.  The search ranges over

* the value of every state at ``t`` and at every delayed time that appears — these are
  independent of each other and of the window integrals: a continuous history can take
  any values at finitely many points while changing every integral arbitrarily little;
* a **piecewise-constant history** on the window ``[t − H, t]`` (H the longest window)
  with m equal pieces (``m`` in ``pieces``; the ends of shorter windows are extra
  break points, so no piece straddles a window end), for every state that appears
  under an integral or in a window measure.

On such a history every window integral is an exact finite sum: the state values are
constant on a piece and the integrand's explicit ξ-dependence (weights such as
``ξ + τ − t``) is integrated exactly — by a closed Newton–Cotes rule of the weight's
degree, which is exact for polynomials (the weight is polynomial in ξ for every claim
of the papers; other weights go through ``sympy.integrate``).  Then ``t = 0`` is set
for an autonomous claim; an explicit t that does not cancel (a time-varying coefficient
h(t) or its derivative ḣ(t), which ``values`` turn into functions of t) needs the witness
time ``time=``: t is set to that number before the pieces are summed (the windows are
[time − h, time − h']), or ``time=(lo, hi)`` searches it as one more parameter (the exact
recheck at a rational time in [lo, hi]); without it :class:`~lkverify.errors.InputError`.

Why a strict violation at a piecewise-constant history refutes the claim: let
``x̂`` be the piecewise-constant history with the chosen point values.  Join
consecutive pieces, and each point value to the piece around its instant (there and
back), by paths traversed in time ε: minor great-circle arcs for unit vectors, segments
for vectors.  Along a segment ‖x − c‖ is at most its larger end value (convexity); along
a minor arc ‖s − c‖ is too while both ends are within √2 of c (caps smaller than a
hemisphere are geodesically convex).  So the continuous history obtained has the same
point values, stays in the region (every region cap of the papers is far smaller than a
hemisphere), and its sups of ‖x(ξ) − c‖ are the maxima over the pieces and point values
that the witness reports.  It differs from ``x̂`` on a set of measure O(ε) where both
are bounded, so every window integral and window measure changes by O(ε) (the
integrands are continuous on the compact admissible set).  The violation ``lhs − rhs``
is a continuous function of these finitely many numbers, so a violation > 0 at ``x̂``
persists for ε small enough: the claim fails at a continuous, piecewise-smooth
admissible history.  A frame is joined through its reference triad: from ``Q R0`` the
path ``Q(λ) R0``, Q(λ) the rotation by λθ about Q's axis n, has ``‖s_i − r_i‖ =
2 sin(λθ/2)‖n × r_i‖``, increasing in λ, so both halves of a join stay in the region and
its sups are again the larger end values.  (For a region cap of radius ≥ √2 the joins can be taken inside the
sub-cap of the larger end value — caps are path-connected — but a ``sup`` measure about
another centre is then only bounded below by the reported maximum.)

Unit vectors (``state.unit``, dimension 3) are parametrised by angles, so every point
is exactly unit: in a cap around ``r`` (a region bound of kind ``sup`` on ``s(ξ) − r``
or ``norm`` on ``s(t) − r``) by ``s = cos ρ r + sin ρ (cos ψ e1 + sin ψ e2)`` with (e1,
e2) the exact orthonormal basis of r⊥ of :func:`~lkverify.certify.charts.unit_vector_near`
and ``ρ = ρmax sin² u``, ``2 sin(ρmax/2) = d``; elsewhere by the same chart around
(0, 0, 1) with ρmax = π.  A vector with a region bound ``‖ω − c‖ ≤ δ`` is
``c + δ sin²(u) · (a unit direction in angles)``; an unbounded vector has free
components.

A **frame** (``state.frame``: s1, s2, s3 orthonormal with s3 = s1 × s2) is one rotation:
``s_i = Q r_i`` with ``R0 = [r1 r2 r3]`` its reference — the centres of the region bounds
on its vectors, completed by r3 = r1 × r2 (cyclically) or an exact orthonormal basis, or
I without bounds — and Q the Cayley rotation ``I + 2(K + K²)/(1 + ‖k‖²)``, ``K = [k]×``, of
``k = tan(θ/2) n``: n a direction in angles and ``θ = θmax(n) sin² u``, θmax(n) the largest
angle about n keeping every bounded vector in its cap (``‖Q r_i − r_i‖ = 2 sin(θ/2)‖n ×
r_i‖``).  At the recheck k is rational, so Q is exactly orthogonal with rational entries and
the triad exactly orthonormal and right-handed; admissibility ``4‖k × r_i‖² ≤ δ_i²(1 +
‖k‖²)`` is checked exactly (k shrunk towards 0 if rounding left the cap).  Delayed values
and history pieces of a frame are rotations of the same kind.

The optimisation variables are thus unconstrained and map smoothly into the admissible
set; the rational recheck point is admissible (by construction, or checked exactly).

Constants that are "some c ≥ 0" (``exists``) or free nonnegative symbols
(``nonnegative``, e.g. λ) must enter affinely: ``lhs − rhs = A + Σ B_k c_k``.  The claim
is refuted for every value of them when ``A > 0`` and every ``B_k ≥ 0`` (rigorously);
the search maximises ``min(A, B_1, …)`` and :attr:`Witness.violation` encloses A, the
value at all c_k = 0 (and the infimum over them).  A constant whose symbol is positive
(γ > 0 of ``P.scalar(..., positive=True)``) and that divides ``lhs − rhs`` (it vanishes at
γ = 0 and is linear in γ) is first divided out — the sign is the quotient's — so
``γ(A + B c7)`` is refuted for every γ > 0 and c7 ≥ 0 (:attr:`Witness.violation` then
encloses the quotient; ``exact["factors"]`` names γ).

A **memory integral** ``∫_c^t κ(t − ξ)F dξ`` (and a memory measure of
:mod:`~lkverify.certify.steps.memory`, ``∫_0^t κ(t − ξ)‖v‖^p``) is a window over [c, t] once t
is fixed: the witness time ``time=``, or t = :data:`MEMORY_TIME` = 1 when none is given (a
bound step holds at every t ≥ 0 for every admissible history, so one time suffices); the
kernel is integrated exactly over each piece (one antiderivative, reused), and a region bound
``sup_{ξ ≤ t}‖x(ξ) − c‖`` (window ∞) holds on every piece and point value.

The search builds the exact parametric expression once per piece count, lambdifies it
(vectorised over points, so a finite-difference gradient costs one call), and runs
SciPy's L-BFGS-B from ``starts`` random starts (``numpy.random.default_rng(seed)``; one BLAS
thread, via threadpoolctl, since threaded BLAS only spins on this tiny algebra), every second
one a *rotation start* (when a state has a history or delayed values): the history
pieces and delayed values along a rotation of the value at t in a random plane (for
unit vectors often the plane through the centre r, the papers' counterexample; for
frames about a random axis or one of r1, r2, r3), with an angle profile of one or
several modes (for frames also turning t and the oldest time in opposite senses).  Piece counts are
tried in order and the first that yields a rechecked witness wins.  Then the structured
starts and grids of :mod:`.witness_seeds` (exact top eigenvectors of quadratic forms,
histories concentrated at one end of a window on ``("ends", ε)`` grids, power profiles near
Hölder's equality case on a fine grid); a positive candidate that does not recheck at the
rounding 1/10⁶ is rechecked at 1/10¹² and 1/10¹⁸.

The work is fixed — ``pieces``, ``starts``, ``maxiter``, ``seeds`` and the seed of the
random generator — so the result is the same on every machine; a wall clock cuts it only
when a ``budget`` is given (:func:`find_witness` then says the search was cut).  Candidates whose
float violation is below about 10⁻¹³ of the size of the terms are rounding noise and
are not rechecked, so violations that small are not found.

Errors: bad arguments raise :class:`~lkverify.errors.InputError` ("expected / got /
how to fix").  Claims outside the witness family — unit vectors of dimension ≠ 3,
nested or merged integrals, memory integrals with a searched time, states at future times or at shifted ξ
under an integral, derivatives of states, region bounds of other forms (for a frame:
bounds about centres that are not orthonormal) — raise :class:`UnsupportedClaim`, which is both an
:class:`~lkverify.errors.UnsupportedInput` and an :class:`~lkverify.errors.InputError`
(a caller may catch either and report ``undecided``).  ``None`` means: searched, nothing
rechecked (the claim may well be true).

The modules: this one holds the search (:func:`search_witness`, :func:`find_witness`, the
optimiser and the exact recheck), :class:`Witness` and :class:`SearchOutcome`;
:mod:`.witness_charts` the charts (and :class:`UnsupportedClaim`), :mod:`.witness_problem`
the claim's atoms, windows and region, :mod:`.witness_model` the claim on one piece grid,
:mod:`.witness_seeds` the structured starts.

Examples
--------
>>> import sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, t, window_integral, xi
>>> from lkverify.certify.steps.measures import norm_measure, window_integral_measure
>>> P = Parameters(); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys_ = System([Equation(x, [Term(-x(t - tau)[0])])], parameters=P)
>>> e, I = norm_measure("e", x(t)), window_integral_measure("I", x(xi), p=2, window=tau)
>>> lhs = x(t)[0] * window_integral(x(xi)[0], tau)     # x(t)∫x ≤ (e² + I)/2: Young and Cauchy–Schwarz
>>> search_witness(lhs, (e.symbol ** 2 + I.symbol) / 2, system=sys_, values=P.resolve({}),
...                measures=[e, I], starts=4) is None
True
>>> w = search_witness(lhs, (e.symbol ** 2 + I.symbol) / 4, system=sys_, values=P.resolve({}),
...                    measures=[e, I], starts=4)
>>> w.violation[0] > 0
True
"""

from __future__ import annotations

import dataclasses
import functools
import numbers
from collections.abc import Mapping

import numpy as np
import sympy

from ...declare.symbols import t
from ...errors import InputError
from ...options import Budget, Deadline
from ..intervals.convert import enclose
from ..intervals.rounding import float_down, float_up
from .witness_charts import _DENOMINATOR, _PREC, UnsupportedClaim  # re-exported: moved to witness_charts
from .witness_model import _Model  # re-exported: moved to witness_model
from .witness_problem import MEMORY, MEMORY_TIME, _Problem  # noqa: F401 (re-exported: moved to witness_problem)

__all__ = ["MAXITER", "PIECES", "STARTS", "SearchOutcome", "UnsupportedClaim", "Witness", "find_witness",
           "search_witness"]

#: how many of the best candidates of one piece count are rechecked
_RECHECKS = 6
#: finer roundings tried when a positive candidate does not recheck at 1/10⁶ (violations of 10⁻¹² relative)
_FINE_DENOMINATORS = (10 ** 12, 10 ** 18)
#: the default, deterministic work of a search: equal-piece grids, starts per grid, iterations per start
PIECES = (1, 2, 3, 5)
STARTS = 24
MAXITER = 200
#: the most structured starts per piece grid (lkverify.certify.steps.witness_seeds)
SEEDS = 12


# ---------------------------------------------------------------------------------------------
# the result
# ---------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Witness:
    """A state and a piecewise-constant history at which ``lhs − rhs > 0`` is proved.

    Attributes
    ----------
    violation : tuple of float
        ``(lo, hi)``, an outward-rounded enclosure of ``lhs − rhs`` at the exact witness
        (with every ``exists`` / ``nonnegative`` constant at 0, divided by the positive
        factors of ``exact["factors"]``); ``lo > 0``.
    state : dict
        ``"s_x(t)"``, ``"s_x(t - 1)"`` … → value (the state at t and at delayed times).
    history : dict
        State name → one list of component values per piece, oldest piece first.
    measures : dict
        Measure name → value at the witness.
    terms : dict
        Term label → value (``"lhs"`` for a plain expression), ``"rhs"`` → value; a term
        that depends on a constant c also has ``"label [coefficient of c]"`` (a factored
        positive constant is taken as 1).
    exact : dict
        What reproduces the witness exactly: ``"t"`` (the witness time; ``"0"`` for an
        autonomous claim), ``"time"`` (``"autonomous"``, ``"given"`` or ``"searched in
        [lo, hi]"``), ``"factors"`` (positive constants divided out), ``"pieces"``,
        ``"breakpoints"``, the rational chart parameters (for a frame: the Cayley vector
        k) and the exact vectors (strings; a frame's nine components s1, s2, s3).
    coefficients : dict
        Constant name → ``(lo, hi)`` enclosure of its coefficient ``B_k ≥ 0`` in
        ``lhs − rhs`` (empty without ``exists`` / ``nonnegative``).

    Examples
    --------
    >>> w = Witness((0.5, 0.5), {"x_1(t)": 1.0}, {}, {}, {"lhs": 1.0, "rhs": 0.5}, {"t": "0"})
    >>> w.text()
    'x(t) = (1); lhs − rhs ∈ [0.5, 0.5] > 0'
    """

    violation: tuple
    state: dict
    history: dict
    measures: dict
    terms: dict
    exact: dict
    coefficients: dict = dataclasses.field(default_factory=dict)

    def to_json(self) -> dict:
        """A JSON-serialisable dict (lists for tuples, floats and strings only)."""
        def clean(x):
            if isinstance(x, Mapping):
                return {str(k): clean(v) for k, v in x.items()}
            if isinstance(x, (list, tuple)):
                return [clean(v) for v in x]
            if isinstance(x, (bool, str)) or x is None:
                return x
            if isinstance(x, numbers.Integral):
                return int(x)
            if isinstance(x, numbers.Real):
                return float(x)
            return str(x)

        return clean({"violation": self.violation, "state": self.state, "history": self.history,
                      "measures": self.measures, "terms": self.terms, "exact": self.exact,
                      "coefficients": self.coefficients})

    def text(self) -> str:
        """One line: the state values, the history, the proved violation."""
        groups: dict = {}
        for key, value in self.state.items():
            name, _, when = key.partition("(")
            base = name.rsplit("_", 1)[0]
            groups.setdefault((base, when.rstrip(")")), []).append(value)
        texts = self.exact.get("texts", {})
        parts = [f"{texts.get(base, base)}({when}) = ({', '.join(f'{v:.4g}' for v in vals)})"
                 for (base, when), vals in groups.items()]
        if self.history:
            n = len(next(iter(self.history.values())))
            window = self.exact.get("window", "")
            parts.append(f"history: {n} piece{'s' if n != 1 else ''}" + (f" on [t − {window}, t]" if window else "")
                         + " (" + "; ".join(f"{texts.get(k, k)}: " + ", ".join(
                             "(" + ", ".join(f"{c:.3g}" for c in piece) + ")" for piece in v)
                             for k, v in self.history.items()) + ")")
        if self.exact.get("time", "autonomous") != "autonomous":
            parts.insert(0, f"at t = {self.exact.get('t')}")
        line = ", ".join(parts)
        lo, hi = self.violation
        factors = list(self.exact.get("factors", ()))
        head = "lhs − rhs" if not factors else f"(lhs − rhs)/{'·'.join(factors)}"
        line += ("; " if line else "") + f"{head} ∈ [{lo:.6g}, {hi:.6g}] > 0"
        every = [f"{c} > 0" for c in factors] + [f"{c} ≥ 0" for c in self.coefficients]
        if every:
            line += " for every " + ", ".join(every)
        return line


# ---------------------------------------------------------------------------------------------
# the search
# ---------------------------------------------------------------------------------------------

def _ball(expr, zballs):
    expr = sympy.sympify(expr)
    return enclose(expr, {z: zballs[z] for z in expr.free_symbols}, prec=_PREC)


class _Stop(Exception):
    """Raised from inside the optimiser when the budget runs out (the best point is kept)."""


def _optimise(model: _Model, p0: np.ndarray, deadline: Deadline, best: list, maxiter: int = 200):
    """One local maximisation of the objective from ``p0`` (SciPy's L-BFGS-B); ``best`` = [value, point] is updated.

    The finite-difference gradient is one vectorised call of the objective (n + 1 points).
    """
    from scipy.optimize import minimize

    n = model.nparams
    scale = model.scale

    def values(P):
        return model.objective(P) / scale

    def note(f, x):
        if f > best[0]:
            best[0], best[1] = float(f), np.array(x, dtype=float).copy()

    if n == 0:
        note(float(values(p0.reshape(0, 1))[0]), p0)
        return
    idx = np.arange(n)

    def negative(x):
        if deadline.expired:
            raise _Stop
        h = 1e-7 * np.maximum(1.0, np.abs(x))
        P = np.tile(x[:, None], (1, n + 1))
        P[idx, idx + 1] += h
        v = values(P)
        f = float(v[0])
        if not np.isfinite(f):
            return np.inf, np.zeros(n)
        note(f, x)
        g = (v[1:] - v[0]) / h
        return -f, -np.where(np.isfinite(g), g, 0.0)

    try:
        minimize(negative, np.array(p0, dtype=float), jac=True, method="L-BFGS-B",
                 options={"maxiter": maxiter, "ftol": max(model.tol, 1e-15)})
    except _Stop:
        return


def _recheck(model: _Model, p: np.ndarray, denominator: int = _DENOMINATOR):
    """The Witness at the rational point near ``p``, or None if the violation is not proved there."""
    records, zexact, zballs = model.exact_point(p, denominator)
    return _recheck_at(model, records, zexact, zballs)


def _recheck_values(model: _Model, zexact: dict):
    """The Witness at exact slot values ``zexact`` (slot symbol → rational; admissibility checked by the
    caller), or None if the violation is not proved there."""
    records = {slot.label: [str(zexact[z]) for z in slot.z] for slot in model.slots}
    zballs = {z: enclose(v, prec=_PREC) for z, v in zexact.items()}
    return _recheck_at(model, records, zexact, zballs)


def _recheck_at(model: _Model, records, zexact, zballs):
    A = _ball(model.A, zballs)
    if not A > 0:
        return None
    coefficients = {}
    for c, b in model.B:
        ball = _ball(b, zballs)
        if not ball >= 0:
            return None
        coefficients[str(c)] = (float_down(ball), float_up(ball))
    return _witness(model, records, zexact, zballs, A, coefficients)


def _mid(ball) -> float:
    return float(ball.mid())


def _witness(model: _Model, records, zexact, zballs, A, coefficients) -> Witness:
    problem = model.problem
    state, history, params, vectors, charts = {}, {}, {}, {}, {}
    when = str(problem.time) if problem.time is not None else "0"
    for slot in model.slots:
        kind, c = slot.where
        vals = [_mid(zballs[z]) for z in slot.z]
        if kind == "time":
            when = str(zexact[slot.z[0]])
        elif kind == "point":
            for f, v in zip(slot.state.functions, vals):
                state[str(f(t - c))] = v
        elif getattr(slot.state, "is_frame", False):
            for i, v in enumerate(slot.state.vectors):
                history.setdefault(v.name, []).append(vals[3 * i:3 * i + 3])
        else:
            history.setdefault(slot.state.name, []).append(vals)
        label = slot.label
        params[label] = records[label]
        vectors[label] = [str(zexact[z]) for z in slot.z]
        charts[label] = slot.chart.describe()
    cs, zero = model.rest, model.base
    ones = {c: 1 for c in model.factors}
    terms = {}
    for label, e in model.terms_z:
        terms[label] = _mid(_ball(e.xreplace(zero), zballs))
        for c in cs:
            d = sympy.diff(e.xreplace(ones), c)
            if d != 0:
                terms[f"{label} [coefficient of {c}]"] = _mid(_ball(d, zballs))
    terms["rhs"] = _mid(_ball(model.rhs_z.xreplace(zero), zballs))
    for c in cs:
        d = sympy.diff(model.rhs_z.xreplace(ones), c)
        if d != 0:
            terms[f"rhs [coefficient of {c}]"] = _mid(_ball(d, zballs))
    measures = {}
    for m in problem.measures:  # shown with the witness; one not written in the witness's coordinates is left out
        e = sympy.sympify(model.measure_z[m.symbol])
        if e.free_symbols <= set(zballs):
            measures[m.name] = _mid(_ball(e, zballs))
    texts = {}
    for st in problem.states:
        texts[st.name] = st.text
        for v in getattr(st, "vectors", ()):
            texts[v.name] = v.text
    lo, hi = problem.time_range or (None, None)
    exact = {
        "t": when,
        "time": ("given" if problem.time is not None else f"searched in [{lo}, {hi}]" if lo is not None
                 else "autonomous"),
        "factors": [str(c) for c in model.factors],
        "pieces": model.npieces,
        "window": str(problem.H) if model.npieces else "",
        "breakpoints": [f"t - {o}" if o != 0 else "t" for o in model.offsets] if model.npieces else [],
        "parameters": params,
        "vectors": vectors,
        "charts": charts,
        "texts": texts,
        "constants": [str(c) for c in problem.constants],
    }
    return Witness((float_down(A), float_up(A)), state, history, measures, terms, exact, coefficients)


def _single_threaded(search):
    """Run the search with one BLAS thread: its algebra is tiny and threaded BLAS only spins (threadpoolctl)."""

    @functools.wraps(search)
    def run(*args, **kwargs):
        from threadpoolctl import threadpool_limits

        with threadpool_limits(limits=1):
            return search(*args, **kwargs)

    return run


@_single_threaded
def search_witness(lhs, rhs, *, system, values, measures, region=None, exists=(), nonnegative=(),
                   pieces=PIECES, starts=STARTS, budget=None, seed=0, time=None, maxiter=MAXITER,
                   structured=True) -> Witness | None:
    """Search for a state and a history that refute ``lhs ≤ rhs``; return a rechecked :class:`Witness` or None.

    Parameters
    ----------
    lhs : sympy expression or sequence of Term
        In the model's vocabulary: state functions at t, at t − c and under window
        integrals, parameters of ``system``.  Labelled terms are summed; their values at
        the witness are reported by label.
    rhs : sympy expression
        In the measures' symbols (``m.symbol``), parameters, constants of ``exists`` /
        ``nonnegative`` (and possibly state functions).
    system : System
    values : mapping
        Resolved parameter values (``system.parameters.resolve(...)``).
    measures : sequence of Measure
        The measures the right-hand side is written in (all are evaluated at the witness).
    region : Region, optional
        Bounds of kind ``norm`` on ``x(t) − c`` and ``sup`` on ``x(ξ) − c``; a witness stays inside.
    exists : sequence of Symbol or str
        Constants "some c ≥ 0": the refutation must hold for every value ≥ 0.
    nonnegative : sequence of Symbol or str
        Free nonnegative symbols (λ) without a value: likewise, every value.
    pieces : sequence of int, default (1, 2, 3, 5)
        Numbers of equal history pieces tried, in order; the first that gives a
        rechecked witness wins.
    starts : int, default 24
        Local optimisations per piece count (every second a rotation start).
    budget : Budget, Deadline, float or None
        Wall-clock limit (None, the default: none — the work is fixed by ``pieces``,
        ``starts`` and ``maxiter``, so the result is the same on every machine), checked
        between optimisation steps; when it runs out the best candidates so far are
        rechecked.  Building the exact expression of a piece count is not interrupted.
        :func:`find_witness` also says whether the search was cut.
    seed : int, default 0
    maxiter : int, default 200
        Iterations of each local optimisation (L-BFGS-B).
    structured : bool, default True
        Also try the structured starts of :mod:`.witness_seeds` (eigenvectors of the
        quadratic part at t, histories concentrated near one end of a window, power
        profiles) and their concentrated piece grids.
    time : number, pair (lo, hi) or None
        The witness time for a claim with an explicit t (time-varying coefficients h(t),
        ḣ(t) after ``values``): t is set to it before the window integrals are summed (the
        windows are [time − h, time]).  A pair searches the time in [lo, hi] as well; the
        exact recheck is at a rational time there.  None (default): the claim must be
        autonomous, and t = 0.  A float is taken at its exact binary value.

    Returns
    -------
    Witness or None
        None: no violation could be proved (not a proof of the claim).

    Raises
    ------
    InputError
        Malformed arguments; symbols without a value; ``lhs − rhs`` not affine in the
        constants; an explicit (time-varying) t without ``time=``.
    UnsupportedClaim
        A claim outside the witness family (see the module notes); it is an
        :class:`~lkverify.errors.UnsupportedInput` and an InputError.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, t
    >>> P = Parameters(); s = UnitVector("s")
    >>> sys_ = System([Equation(s, [Term(sympy.zeros(3, 1))])], parameters=P)
    >>> search_witness(s(t).dot(s(t)), 1, system=sys_, values={}, measures=[], starts=2) is None
    True
    >>> w = search_witness(s(t)[0], sympy.Rational(99, 100), system=sys_, values={}, measures=[], starts=2)
    >>> w.violation[0] > 0
    True
    """
    return find_witness(lhs, rhs, system=system, values=values, measures=measures, region=region, exists=exists,
                        nonnegative=nonnegative, pieces=pieces, starts=starts, budget=budget, seed=seed, time=time,
                        maxiter=maxiter, structured=structured).witness


@dataclasses.dataclass(frozen=True)
class SearchOutcome:
    """What a witness search did: the witness (or None), and whether it ran to its end.

    Attributes
    ----------
    witness : Witness or None
    complete : bool
        False when the wall-clock budget cut the search (a None witness then says less).
    starts : int
        Local optimisations run (structured starts included).
    pieces : tuple
        The piece grids searched (an int: equal pieces; ``("ends", ε)``: pieces of relative
        length ε at both ends of every window).

    Examples
    --------
    >>> SearchOutcome(None, True, 48, (1, 2)).text()
    'no witness in 48 local searches on the piece grids (1, 2)'
    >>> SearchOutcome(None, False, 3, (1,)).text()
    'the budget was spent before this witness search finished (3 local searches)'
    """

    witness: Witness | None
    complete: bool
    starts: int = 0
    pieces: tuple = ()

    def text(self) -> str:
        if self.witness is not None:
            return self.witness.text()
        if not self.complete:
            return f"the budget was spent before this witness search finished ({self.starts} local searches)"
        grids = ", ".join(str(m) if isinstance(m, int) else f"{m[0]} {m[1]}" for m in self.pieces)
        return f"no witness in {self.starts} local searches on the piece grids ({grids})"


def _grid_ok(m) -> bool:
    """An equal-piece count (a positive int) or an end grid ``("ends", ε)`` with 0 < ε < 1/2 rational."""
    if isinstance(m, tuple):
        if len(m) != 2 or m[0] != "ends":
            return False
        try:
            eps = sympy.Rational(m[1])
        except (TypeError, ValueError, sympy.SympifyError):
            return False
        return bool(0 < eps < sympy.Rational(1, 2))
    return not isinstance(m, bool) and isinstance(m, numbers.Integral) and m >= 1


def _validated(pieces, starts, seed, maxiter) -> tuple:
    if isinstance(pieces, numbers.Integral) or (isinstance(pieces, tuple) and pieces[:1] == ("ends",)):
        pieces = (pieces,)
    pieces = tuple(pieces)
    if not pieces or not all(_grid_ok(m) for m in pieces):
        raise InputError(f"pieces: expected positive integers such as (1, 2, 3, 5) or end grids ('ends', '1/1000'), "
                         f"got {pieces!r}")
    for value, what in ((starts, "starts"), (maxiter, "maxiter")):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
            raise InputError(f"{what}: expected a positive integer, got {value!r}")
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
        raise InputError(f"seed: expected an integer, got {seed!r}")
    return pieces


@_single_threaded
def find_witness(lhs, rhs, *, system, values, measures, region=None, exists=(), nonnegative=(), pieces=PIECES,
                 starts=STARTS, budget=None, seed=0, time=None, maxiter=MAXITER, structured=True,
                 seeds=SEEDS, cse=True) -> SearchOutcome:
    """:func:`search_witness`, telling also whether the search ran to its end (:class:`SearchOutcome`).

    ``seeds`` caps the structured starts per grid (default :data:`SEEDS`; None: all); with ``structured`` the end
    grids :data:`~.witness_seeds.END_GRIDS` are added unless ``pieces`` names an end grid.  ``cse``: the models'
    numeric forms with common subexpressions eliminated (cheaper evaluations, a dearer build).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> out = find_witness(x(t).dot(x(t)), n.symbol ** 2, system=sys_, values={}, measures=[n], starts=2)
    >>> out.witness is None, out.complete, out.text()
    (True, True, 'no witness in 2 local searches on the piece grids (1)')
    """
    problem = _Problem(lhs, rhs, system, values, measures, region, exists, nonnegative, time)
    pieces = _validated(pieces, starts, seed, maxiter)
    deadline = budget if isinstance(budget, Deadline) else Budget.of(budget).deadline()
    rng = np.random.default_rng(seed)
    grids = list(pieces[:1] if not problem.history_states else pieces)
    if structured and problem.history_states and all(isinstance(m, int) for m in grids):
        from .witness_seeds import END_GRIDS, PROFILE_GRIDS

        grids += [g for g in END_GRIDS + PROFILE_GRIDS if g not in grids]
    done, runs = [], 0
    for m in grids:
        if deadline.expired:
            return SearchOutcome(None, False, runs, tuple(done))
        model = _Model(problem, m, cse=cse)
        model.calibrate(rng)
        p0s = []
        if structured:
            from .witness_seeds import structured_starts

            p0s = structured_starts(model, rng, seeds)
        n_random = starts if m in pieces else 0          # the structured grids get structured starts only
        cands = []
        for k in range(n_random + len(p0s)):
            if deadline.expired:
                break
            if k < len(p0s):
                p0 = p0s[k]
            else:
                rotation = (k - len(p0s)) % 2 == 1 and bool(problem.rotating)
                p0 = model.rotation_params(rng) if rotation else model.random_params(rng)
            best = [-np.inf, p0]
            _optimise(model, p0, deadline, best, maxiter=maxiter)
            runs += 1
            if np.isfinite(best[0]):
                cands.append((best[0], best[1]))
        w = _recheck_best(model, cands)
        if w is None and structured:
            from .witness_seeds import exact_eigen_points

            w = next((w for w in (_recheck_values(model, z) for z in exact_eigen_points(model)) if w is not None),
                     None)
        if w is not None:
            return SearchOutcome(w, True, runs, tuple(done) + (m,))
        if deadline.expired:
            return SearchOutcome(None, False, runs, tuple(done))
        done.append(m)
    return SearchOutcome(None, True, runs, tuple(done))


def _recheck_best(model: _Model, cands: list):
    """The first of the best candidates that rechecks (at the coarse rounding, then at finer ones)."""
    ok = sorted((c for c in cands if c[0] > model.tol or model.locally_positive(c[1])), key=lambda c: -c[0])
    for _, p in ok[:_RECHECKS]:
        for denominator in (_DENOMINATOR,) + _FINE_DENOMINATORS:
            w = _recheck(model, p, denominator)
            if w is not None:
                return w
    return None
