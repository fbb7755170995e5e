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
import math
import numbers
from collections.abc import Mapping

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from ...declare.functional import outer_integrals, split_outer
from ...declare.parameters import apply_substitution
from ...declare.symbols import t, xi
from ...declare.system import System
from ...declare.terms import Term
from ...errors import InputError, UnsupportedInput
from ...options import Budget, Deadline
from ..intervals.convert import enclose
from ..intervals.rounding import float_down, float_up
from ..regions import prove_zero
from .measures import Measure, Region

__all__ = ["MAXITER", "PIECES", "STARTS", "SearchOutcome", "UnsupportedClaim", "Witness", "find_witness",
           "search_witness"]

#: rational rounding of the optimiser's point for the exact recheck
_DENOMINATOR = 10 ** 6
#: how many of the best candidates of one piece count are rechecked
_RECHECKS = 6
#: arb precision of the recheck (bits)
_PREC = 128
#: finer roundings tried when a positive candidate does not recheck at 1/10⁶ (violations of 10⁻¹² relative)
_FINE_DENOMINATORS = (10 ** 12, 10 ** 18)
#: the kind of a memory measure (lkverify.certify.steps.memory) and the witness time of a memory claim
MEMORY = "memory_integral"
MEMORY_TIME = sympy.Integer(1)
_U = sympy.Symbol("_wu", nonnegative=True)
#: the default, deterministic work of a search: equal-piece grids, starts per grid, iterations per start
PIECES = (1, 2, 3, 5)
STARTS = 24
MAXITER = 200
#: the most structured starts per piece grid (lkverify.certify.steps.witness_seeds)
SEEDS = 12


class UnsupportedClaim(UnsupportedInput, InputError):
    """A claim outside the witness family (frames, nested integrals, …): nothing was refuted.

    It is both an :class:`~lkverify.errors.UnsupportedInput` and an
    :class:`~lkverify.errors.InputError`.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.errors import UnsupportedInput
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 1); e = norm_measure("e", x(t))
    >>> sys_ = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    >>> try:
    ...     search_witness(x(t + 1)[0], e.symbol, system=sys_, values=P.resolve({}), measures=[e], budget=1)
    ... except UnsupportedInput as exc:               # also an InputError
    ...     print(type(exc).__name__, exc)
    UnsupportedClaim lhs term 'lhs': expected the state at t or at earlier times, got x_1(t + 1) (a future value)
    """


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
# charts: unconstrained parameters → admissible values
# ---------------------------------------------------------------------------------------------

class _Chart:
    """A smooth map from free parameters onto the admissible set of one slot.

    kinds: ``cap`` (unit 3-vector at angle ≤ top from a unit centre), ``ball`` (‖v − c‖ ≤ δ),
    ``free`` (components), ``fixed`` (a bound 0: the centre itself).
    """

    def __init__(self, kind: str, dim: int, *, center=None, bound=None):
        self.kind, self.dim = kind, dim
        self.center = None if center is None else sympy.ImmutableMatrix(center)
        self.bound = bound
        if kind == "cap":
            from ..charts import unit_vector_near

            try:
                if bound is None or bool(sympy.sympify(bound) >= 2):
                    ch = unit_vector_near(self.center, rho_max=sympy.pi)
                else:
                    ch = unit_vector_near(self.center, distance_max=bound)
            except InputError as exc:
                raise UnsupportedClaim(f"a region bound on a unit vector: expected ‖s − r‖ ≤ d with r a "
                                       f"constant unit vector, got centre {list(self.center)} ({exc}); bound "
                                       f"s − r with a unit r") from exc
            self.top = list(ch.region.values())[0][1]
            self.e1, self.e2 = ch.extras["e1"], ch.extras["e2"]
            self.nparams = 2
            self._c = np.array([float(v) for v in self.center])
            self._e1 = np.array([float(v) for v in self.e1])
            self._e2 = np.array([float(v) for v in self.e2])
            self._top = float(self.top)
        elif kind == "ball":
            self.nparams = dim
            self._c = np.array([float(v) for v in self.center])
            self._delta = float(bound)
        elif kind == "free":
            self.nparams = dim
        elif kind == "fixed":
            self.nparams = 0
            self._c = np.array([float(v) for v in self.center])
        else:  # pragma: no cover
            raise AssertionError(kind)

    def describe(self) -> str:
        if self.kind == "cap":
            return (f"cos(rho)·c + sin(rho)(cos(psi)·e1 + sin(psi)·e2), rho = {self.top}·sin(u)², "
                    f"c = {list(self.center)}, e1 = {list(self.e1)}, e2 = {list(self.e2)}")
        if self.kind == "ball":
            return f"c + {self.bound}·sin(u)²·direction(angles), c = {list(self.center)}"
        if self.kind == "fixed":
            return f"the centre {list(self.center)}"
        return "free components"

    # exact (sympy) and numeric forms of the same formulas
    def expr(self, p) -> list:
        """The value (one expression per component) at parameters ``p`` (symbols or rationals)."""
        if self.kind == "cap":
            u, psi = p
            rho = self.top * sympy.sin(u) ** 2
            v = sympy.cos(rho) * self.center + sympy.sin(rho) * (sympy.cos(psi) * self.e1 + sympy.sin(psi) * self.e2)
            return list(v)
        if self.kind == "ball":
            if self.dim == 1:
                return [self.center[0] + self.bound * sympy.sin(p[0])]
            radius = self.bound * sympy.sin(p[0]) ** 2
            return [c + radius * d for c, d in zip(self.center, _direction(p[1:], sympy))]
        if self.kind == "free":
            return list(p)
        return list(self.center)

    def value(self, p: np.ndarray) -> np.ndarray:
        """The numeric value at the parameters ``p``."""
        if self.kind == "cap":
            rho = self._top * math.sin(p[0]) ** 2
            return math.cos(rho) * self._c + math.sin(rho) * (math.cos(p[1]) * self._e1 + math.sin(p[1]) * self._e2)
        if self.kind == "ball":
            if self.dim == 1:
                return self._c + self._delta * math.sin(p[0])
            return self._c + self._delta * math.sin(p[0]) ** 2 * np.array(_direction(p[1:], math))
        if self.kind == "free":
            return np.array(p, dtype=float)
        return self._c.copy()

    def inverse(self, v: np.ndarray) -> np.ndarray:
        """Parameters whose value is ``v`` (projected onto the admissible set)."""
        v = np.asarray(v, dtype=float)
        if self.kind == "cap":
            n = np.linalg.norm(v)
            v = v / n if n > 0 else self._c
            rho = math.acos(min(1.0, max(-1.0, float(v @ self._c))))
            psi = math.atan2(float(v @ self._e2), float(v @ self._e1))
            return np.array([math.asin(math.sqrt(min(1.0, rho / self._top))), psi])
        if self.kind == "ball":
            d = v - self._c
            if self.dim == 1:
                return np.array([math.asin(min(1.0, max(-1.0, float(d[0]) / self._delta)))])
            rad = float(np.linalg.norm(d))
            u = math.asin(math.sqrt(min(1.0, rad / self._delta)))
            return np.concatenate([[u], _angles(d / rad if rad > 0 else np.eye(self.dim)[0])])
        if self.kind == "free":
            return v.copy()
        return np.zeros(0)

    def random(self, rng: np.random.Generator) -> np.ndarray:
        if self.kind == "cap":
            return np.array([rng.uniform(0, math.pi / 2), rng.uniform(0, 2 * math.pi)])
        if self.kind == "ball":
            if self.dim == 1:
                return np.array([rng.uniform(-math.pi / 2, math.pi / 2)])
            return np.concatenate([[rng.uniform(0, math.pi / 2)], _angles(_unit(rng, self.dim))])
        if self.kind == "free":
            return rng.normal(size=self.dim) * rng.choice([0.1, 1.0, 3.0])
        return np.zeros(0)

    def numeric(self, P: np.ndarray) -> list:
        """The values (one array per component) at the parameter columns ``P`` (shape (nparams, N))."""
        if getattr(self, "_lambdified", None) is None:
            syms = [sympy.Symbol(f"_cp{i}", real=True) for i in range(self.nparams)]
            self._lambdified = sympy.lambdify(syms, self.expr(syms), modules="numpy", cse=True)
        return self._lambdified(*P)

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        """``(record, values)`` at the rational point near ``p``: the rational parameters (strings) and the
        exact value (one SymPy number per component), admissible by construction."""
        q = [sympy.Rational(float(x)).limit_denominator(denominator) for x in p]
        return [str(x) for x in q], self.expr(q)


def _skew_np(k: np.ndarray) -> np.ndarray:
    """``[k]×`` for the columns of ``k`` (shape (3, N)) → shape (3, 3, N)."""
    z = np.zeros_like(k[0])
    return np.array([[z, -k[2], k[1]], [k[2], z, -k[0]], [-k[1], k[0], z]])


def _cayley_np(k: np.ndarray) -> np.ndarray:
    """The Cayley rotations ``I + 2(K + K²)/(1 + ‖k‖²)``, ``K = [k]×``, for the columns of ``k`` → (3, 3, N)."""
    K = _skew_np(k)
    K2 = np.einsum("ijn,jln->iln", K, K)
    return np.eye(3)[:, :, None] + 2 * (K + K2) / (1 + np.sum(k ** 2, axis=0))


def _cayley_exact(k) -> sympy.ImmutableMatrix:
    """The Cayley rotation of a rational 3-vector ``k``: exactly orthogonal, det 1, rational entries."""
    K = sympy.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return sympy.ImmutableMatrix(sympy.eye(3) + 2 * (K + K * K) / (1 + sum(x ** 2 for x in k)))


def _rotation_np(a: np.ndarray, phi: float) -> np.ndarray:
    """The rotation by ``phi`` about the unit axis ``a`` (Rodrigues)."""
    A = _skew_np(a[:, None])[:, :, 0]
    return np.eye(3) + math.sin(phi) * A + (1 - math.cos(phi)) * A @ A


#: the largest rotation angle of a frame chart, as a fraction of π (Cayley's k = tan(θ/2)·n stays finite)
_FRAME_TOP = 0.999


class _FrameChart:
    """Frames ``s_i = Q r_i`` (i = 1, 2, 3) with ``R0 = [r1 r2 r3]`` a reference rotation and Q a rotation.

    Q is the Cayley rotation of ``k = tan(θ/2)·n``: ``Q = I + 2(K + K²)/(1 + ‖k‖²)``, ``K = [k]×``,
    the rotation by θ about n.  The parameters are ``(u, a1, a2)``: ``n = direction(a1, a2)`` and
    ``θ = θmax(n)·sin²(u)``, where θmax(n) is the largest angle about n for which every bounded
    vector stays inside its cap: ``‖Q r_i − r_i‖ = 2 sin(θ/2)·‖n × r_i‖ ≤ δ_i``, increasing in θ,
    so the map is onto the admissible set (up to rotations by more than :data:`_FRAME_TOP`·π).
    At the exact point k is rational, so Q is exactly orthogonal with rational entries and the
    triad exactly orthonormal and right-handed; admissibility ``4‖k × r_i‖² ≤ δ_i²(1 + ‖k‖²)``
    (the same identity) is checked exactly, k shrunk towards 0 if rounding left the cap.
    """

    kind = "frame"
    dim = 9
    nparams = 3
    center = None

    def __init__(self, reference, bounds: dict):
        self.reference = sympy.ImmutableMatrix(reference)
        self.bounds = dict(bounds)               # vector index (0, 1, 2) → δ
        self._R0 = np.array([[float(x) for x in row] for row in self.reference.tolist()])
        self._bounds = [(i, float(d)) for i, d in sorted(self.bounds.items())]
        self._top = min([math.pi * _FRAME_TOP] + [2 * math.asin(min(1.0, d / 2)) for _, d in self._bounds])

    def describe(self) -> str:
        cols = [list(self.reference[:, i]) for i in range(3)]
        caps = ", ".join(f"‖s{i + 1} − r{i + 1}‖ ≤ {d}" for i, d in sorted(self.bounds.items())) or "none"
        return (f"s_i = Q r_i, Q = I + 2(K + K²)/(1 + ‖k‖²), K = [k]× (Cayley; the parameters are k), "
                f"r1, r2, r3 = {cols}; k = tan(θ/2)·n(a1, a2), θ = θmax(n)·sin(u)², caps: {caps}")

    def _theta_max(self, n: np.ndarray) -> np.ndarray:
        top = np.full(n.shape[1:], math.pi * _FRAME_TOP)
        with np.errstate(divide="ignore", invalid="ignore"):
            for i, d in self._bounds:
                sin = np.linalg.norm(np.cross(n, self._R0[:, i][:, None], axis=0), axis=0)
                ratio = np.where(sin > 0, d / (2 * np.where(sin > 0, sin, 1.0)), np.inf)
                top = np.minimum(top, 2 * np.arcsin(np.minimum(1.0, ratio)))
        return top

    def _k(self, P: np.ndarray) -> np.ndarray:
        u, a1, a2 = P
        n = np.array(np.broadcast_arrays(*_direction([a1, a2], np)), dtype=float)
        theta = self._theta_max(n) * np.sin(u) ** 2
        return np.tan(theta / 2) * n

    def numeric(self, P: np.ndarray) -> list:
        P = np.asarray(P, dtype=float)
        Q = _cayley_np(self._k(P))
        S = np.einsum("ijn,jl->iln", Q, self._R0)          # S[:, l] = Q r_l
        return [S[a, l] for l in range(3) for a in range(3)]

    def value(self, p: np.ndarray) -> np.ndarray:
        return np.array([v[0] for v in self.numeric(np.asarray(p, dtype=float).reshape(3, 1))])

    def _admissible(self, k) -> bool:
        kk = sympy.Matrix(k)
        for i, d in self.bounds.items():
            gap = sympy.expand(d ** 2 * (1 + kk.dot(kk)) - 4 * _norm2(kk.cross(self.reference[:, i])))
            if gap.is_Rational:
                if gap < 0:
                    return False
            elif not enclose(gap, prec=_PREC) >= 0:
                return False
        return True

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        k = self._k(np.asarray(p, dtype=float).reshape(3, 1))[:, 0]
        q = [sympy.Rational(float(x)).limit_denominator(denominator) for x in k]
        for j in range(8):
            if self._admissible(q):
                break
            shrink = 1 - sympy.Rational(1, 10 ** 6) * 4 ** j
            q = [x * shrink for x in q]
        else:  # pragma: no cover - the shrunk point is inside unless it sits on the boundary
            q = [sympy.Integer(0)] * 3
        S = _cayley_exact(q) * self.reference
        return [str(x) for x in q], [S[a, l] for l in range(3) for a in range(3)]

    def inverse(self, v: np.ndarray) -> np.ndarray:
        T = np.asarray(v, dtype=float).reshape(3, 3).T          # columns s1, s2, s3
        U, _, Vt = np.linalg.svd(T @ self._R0.T)
        Q = U @ Vt
        if np.linalg.det(Q) < 0:
            Q = U @ np.diag([1, 1, -1]) @ Vt
        theta = math.acos(min(1.0, max(-1.0, (float(np.trace(Q)) - 1) / 2)))
        if theta < 1e-12:
            return np.zeros(3)
        w = np.array([Q[2, 1] - Q[1, 2], Q[0, 2] - Q[2, 0], Q[1, 0] - Q[0, 1]])
        if math.sin(theta) > 1e-6:
            n = w / (2 * math.sin(theta))
        else:                                                   # θ ≈ π: the axis from Q + I
            B = Q + np.eye(3)
            n = B[:, int(np.argmax(np.linalg.norm(B, axis=0)))]
        n = n / (np.linalg.norm(n) or 1.0)
        top = float(self._theta_max(n[:, None])[0])
        u = math.asin(math.sqrt(min(1.0, theta / top))) if top > 0 else 0.0
        return np.concatenate([[u], _angles(n)])

    def random(self, rng: np.random.Generator) -> np.ndarray:
        return np.concatenate([[rng.uniform(0, math.pi / 2)], _angles(_unit(rng, 3))])


class _TimeChart:
    """The witness time ``t = lo + (hi − lo) sin²(u)``; the exact time is a rational in [lo, hi]."""

    kind = "time"
    dim = 1
    nparams = 1
    center = None

    def __init__(self, lo, hi):
        self.lo, self.hi = lo, hi
        self._lo, self._hi = float(lo), float(hi)

    def describe(self) -> str:
        return f"t = {self.lo} + ({self.hi} − {self.lo})·sin(u)²"

    def numeric(self, P: np.ndarray) -> list:
        return [self._lo + (self._hi - self._lo) * np.sin(np.asarray(P[0], dtype=float)) ** 2]

    def value(self, p: np.ndarray) -> np.ndarray:
        return np.array([self._lo + (self._hi - self._lo) * math.sin(float(p[0])) ** 2])

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        q = sympy.Rational(float(self.value(p)[0])).limit_denominator(denominator)
        q = self.lo if _lt(q, self.lo) else self.hi if _lt(self.hi, q) else q
        return [str(q)], [q]

    def inverse(self, v: np.ndarray) -> np.ndarray:
        x = (float(np.asarray(v).ravel()[0]) - self._lo) / (self._hi - self._lo)
        return np.array([math.asin(math.sqrt(min(1.0, max(0.0, x))))])

    def random(self, rng: np.random.Generator) -> np.ndarray:
        return np.array([rng.uniform(0, math.pi / 2)])


def _norm2(v) -> sympy.Expr:
    return sympy.Add(*[x ** 2 for x in v])


def _direction(a, lib) -> list:
    """The unit vector of hyperspherical angles ``a`` (len n − 1) in R^n."""
    n = len(a) + 1
    out, prod = [], 1
    for k in range(n - 1):
        out.append(prod * lib.cos(a[k]))
        prod = prod * lib.sin(a[k])
    out.append(prod)
    return out


def _angles(d: np.ndarray) -> np.ndarray:
    """Inverse of :func:`_direction` for a unit vector ``d``."""
    n = len(d)
    a = np.zeros(n - 1)
    for k in range(n - 1):
        a[k] = math.atan2(float(np.linalg.norm(d[k + 1:])), float(d[k]))
    if n >= 2:
        a[n - 2] = math.atan2(float(d[n - 1]), float(d[n - 2]))
    return a


def _unit(rng, n) -> np.ndarray:
    v = rng.normal(size=n)
    return v / (np.linalg.norm(v) or 1.0)


def _plane_rotation(v, a, b, phi):
    """``v`` rotated by ``phi`` in the plane of the orthonormal (a, b)."""
    va, vb = float(v @ a), float(v @ b)
    c, s = math.cos(phi), math.sin(phi)
    return v - va * a - vb * b + (va * c - vb * s) * a + (va * s + vb * c) * b


# ---------------------------------------------------------------------------------------------
# the problem: the claim after substitution, its atoms and windows
# ---------------------------------------------------------------------------------------------

@dataclasses.dataclass
class _Integral:
    node: sympy.Integral
    var: sympy.Symbol
    h1: sympy.Expr          # lower limit t − h1
    h2: sympy.Expr          # upper limit t − h2
    inner: sympy.Expr
    degree: int | None      # degree of the explicit ξ-dependence (None: not polynomial)


@dataclasses.dataclass
class _Constraint:
    state: object
    kind: str               # "norm" (at t) or "sup" (over [t − h, t])
    window: sympy.Expr | None
    center: sympy.ImmutableMatrix
    bound: sympy.Expr
    vector: int | None = None   # for a frame: which of its vectors (0, 1, 2) is bounded


class _FrameGroup:
    """The three vectors of a :class:`~lkverify.declare.states.Frame` as one 9-component state (one rotation)."""

    is_frame = True
    unit = False
    frame = None

    def __init__(self, frame):
        self.vectors = tuple(frame.vectors)
        self.name = ",".join(v.name for v in self.vectors)
        self.text = "(" + ", ".join(v.text for v in self.vectors) + ")"
        self.dim = 9
        self.functions = tuple(f for v in self.vectors for f in v.functions)
        self.reference = sympy.ImmutableMatrix(sympy.eye(3))

    def __repr__(self) -> str:
        return f"frame({self.name})"


def _time_argument(time):
    """``(fixed, (lo, hi))`` from the ``time=`` argument: a number, a pair or None."""
    def number(x, what):
        if isinstance(x, bool) or isinstance(x, str):
            raise InputError(f"time: expected a real number such as 1 or a pair (lo, hi), got {what} {x!r}")
        if isinstance(x, float):
            if not math.isfinite(x):
                raise InputError(f"time: expected a finite real number, got {x!r}")
            return sympy.Rational(x)
        try:
            v = sympy.sympify(x, strict=True)
        except (sympy.SympifyError, TypeError) as exc:
            raise InputError(f"time: expected a real number such as 1 or a pair (lo, hi), got {x!r}") from exc
        if not isinstance(v, sympy.Expr) or v.free_symbols or not v.is_number or v.is_real is not True \
                or v.has(sympy.oo, -sympy.oo, sympy.zoo, sympy.nan):
            raise InputError(f"time: expected a finite real number, got {x!r}")
        return v.xreplace({f: sympy.Rational(f) for f in v.atoms(sympy.Float)})  # a Float at its exact binary value

    if time is None:
        return None, None
    if isinstance(time, (tuple, list)):
        if len(time) != 2:
            raise InputError(f"time: expected a number or a pair (lo, hi), got a sequence of length {len(time)}")
        lo, hi = number(time[0], "the lower end"), number(time[1], "the upper end")
        if not _lt(lo, hi):
            raise InputError(f"time: expected lo < hi in (lo, hi), got ({lo}, {hi}); give a single number for one "
                             f"time")
        return None, (lo, hi)
    return number(time, "the time"), None


@dataclasses.dataclass
class _Slot:
    state: object           # a state, a frame (_FrameGroup), or None for the witness time
    where: tuple            # ("point", c), ("piece", k) or ("time", 0)
    z: tuple                # one symbol per component
    chart: object           # _Chart, _FrameChart or _TimeChart
    start: int              # first index of the chart's parameters

    @property
    def label(self) -> str:
        kind, c = self.where
        if kind == "time":
            return "t"
        if kind == "point":
            return f"{self.state.name}(t)" if c == 0 else f"{self.state.name}(t - {c})"
        return f"{self.state.name}[piece {c}]"


def _sympify_scalar(expr, what: str) -> sympy.Expr:
    """A scalar SymPy expression (a 1×1 matrix taken as its entry), through the interval layer's one conversion."""
    from ..intervals.convert import _sympify

    if isinstance(expr, sympy.MatrixBase):
        if expr.shape != (1, 1):
            raise InputError(f"{what}: expected a scalar, got a {expr.shape[0]}x{expr.shape[1]} matrix; "
                             f"take a component or a dot product")
        expr = expr[0, 0]
    return _sympify(expr, what)


def _lhs_terms(lhs) -> list:
    if isinstance(lhs, Term):
        lhs = [lhs]
    if isinstance(lhs, (list, tuple)):
        if not lhs:
            raise InputError("lhs: expected an expression or a non-empty sequence of Term, got an empty sequence")
        out, seen = [], {}
        for term in lhs:
            if not isinstance(term, Term):
                raise InputError(f"lhs: expected a sequence of lkverify.Term, got an item of type "
                                 f"{type(term).__name__}; wrap each expression in Term(expr, text=...)")
            label = term.text
            if label in seen:
                seen[label] += 1
                label = f"{label} ({seen[term.text]})"
            else:
                seen[label] = 1
            out.append((label, _sympify_scalar(term.expr, f"lhs term {term.text!r}")))
        return out
    return [("lhs", _sympify_scalar(lhs, "lhs"))]


def _names(seq, what: str) -> list:
    if isinstance(seq, (str, sympy.Symbol)):
        seq = (seq,)
    out = []
    for c in seq:
        if isinstance(c, sympy.Symbol):
            out.append(c.name)
        elif isinstance(c, str) and c.isidentifier():
            out.append(c)
        else:
            raise InputError(f"{what}: expected sympy Symbols (or their names), got {c!r}")
    return out


def _number(x, what: str) -> sympy.Expr:
    x = sympy.sympify(x)
    if x.free_symbols:
        raise InputError(f"{what}: expected a number once the parameters have values, got {x} (symbols "
                         f"{sorted(map(str, x.free_symbols))} have no value); give them values")
    if not (x.is_number and x.is_real is not False):
        raise InputError(f"{what}: expected a real number, got {x}")
    return x


def _degree(expr, var) -> int | None:
    """The degree of ``expr`` as a polynomial in ``var`` (structurally), None if it is not one."""
    if not expr.has(var):
        return 0
    if expr == var:
        return 1
    if expr.is_Add:
        ds = [_degree(a, var) for a in expr.args]
        return None if None in ds else max(ds)
    if expr.is_Mul:
        ds = [_degree(a, var) for a in expr.args]
        return None if None in ds else sum(ds)
    if expr.is_Pow and expr.exp.is_Integer and expr.exp >= 0:
        d = _degree(expr.base, var)
        return None if d is None else d * int(expr.exp)
    return None


@functools.lru_cache(maxsize=16)
def _newton_cotes(d: int) -> tuple:
    """Nodes and weights on [0, 1] of the closed Newton–Cotes rule exact for degree ``d``."""
    if d == 0:
        return ((sympy.Integer(0),), (sympy.Integer(1),))
    x = sympy.Symbol("x")
    nodes = tuple(sympy.Rational(i, d) for i in range(d + 1))
    weights = []
    for i, xi_ in enumerate(nodes):
        lag = sympy.Mul(*[(x - xj) / (xi_ - xj) for j, xj in enumerate(nodes) if j != i])
        weights.append(sympy.integrate(lag, (x, 0, 1)))
    return nodes, tuple(weights)


def _lt(a, b) -> bool:
    """a < b for real constants (exact when they are rational)."""
    return bool(sympy.sympify(a - b) < 0)


class _Problem:
    """Everything about the claim that does not depend on the number of pieces."""

    def __init__(self, lhs, rhs, system, values, measures, region, exists, nonnegative, time=None):
        if not isinstance(system, System):
            raise InputError(f"system: expected an lkverify System, got {type(system).__name__}")
        if not isinstance(values, Mapping):
            raise InputError(f"values: expected a mapping name → value (Parameters.resolve), got "
                             f"{type(values).__name__}")
        measures = tuple(measures)
        for m in measures:
            if not isinstance(m, Measure):
                raise InputError(f"measures: expected Measure objects (norm_measure, window_norm, …), got "
                                 f"{type(m).__name__}")
        names = [m.name for m in measures]
        if len(set(names)) != len(names):
            raise InputError(f"measures: expected distinct names, got {names}")
        if region is not None and not isinstance(region, Region):
            raise InputError(f"region: expected a Region or None, got {type(region).__name__}")
        self.system = system
        self._charts: dict = {}
        self.time, self.time_range = _time_argument(time)
        # the state of each component function; a frame's three vectors are one state (a rotation)
        self.funcs = dict(system.state_functions())
        self.groups: dict = {}
        for st in system.states:
            if st.frame is not None and id(st.frame) not in self.groups:
                group = self.groups[id(st.frame)] = _FrameGroup(st.frame)
                for i, f in enumerate(group.functions):
                    self.funcs[f] = (group, i)
        try:
            sub = system.parameters.substitution(values)
        except KeyError as exc:
            raise InputError(f"values: {exc.args[0]!r} is not a parameter of the system; pass "
                             f"system.parameters.resolve(...)") from exc
        self.sub = sub
        self.terms = [(label, apply_substitution(e, sub)) for label, e in _lhs_terms(lhs)]
        self.rhs = apply_substitution(_sympify_scalar(rhs, "rhs"), sub)
        self.measures = measures
        self.msyms = {m.symbol: m for m in measures}
        self._memory_time([e for _, e in self.terms] + [self.rhs], measures)
        # the measures after substitution
        self.mdata = {}
        self.kernels = {}
        for m in measures:
            vec = sympy.ImmutableMatrix(apply_substitution(m.vector, sub))
            if m.kind == MEMORY:         # ∫_0^t κ(t − ξ)‖v‖^p: the history on [0, t] at the witness time
                window = self.time
                self.kernels[m.name] = sympy.Lambda(_U, _evaluated(apply_substitution(m.kernel(_U), sub)))
            else:
                window = _number(apply_substitution(m.window, sub), f"measure {m.name}: window") \
                    if m.kind != "norm" else sympy.Integer(0)
            power = _number(apply_substitution(m.power, sub), f"measure {m.name}: power")
            if vec.free_symbols - {t, xi}:
                extra = sorted(map(str, vec.free_symbols - {t, xi}))
                raise InputError(f"measure {m.name}: expected a vector with parameter values, got one depending "
                                 f"on {extra} without a value; give them values")
            if m.kind != "norm" and not window.is_positive:
                raise InputError(f"measure {m.name}: window: expected a positive length, got {window}")
            self.mdata[m.name] = (vec, window, power)
        # the constants "for every c ≥ 0"
        wanted = set(_names(exists, "exists")) | set(_names(nonnegative, "nonnegative"))
        clash = wanted & set(names)
        if clash:
            raise InputError(f"exists/nonnegative: {sorted(clash)} are measure names; a constant needs its own name")
        everything = [e for _, e in self.terms] + [self.rhs]
        free = set().union(*(e.free_symbols for e in everything))
        self.constants = sorted((s for s in free if s.name in wanted), key=lambda s: s.name)
        left = free - set(self.constants) - set(self.msyms) - {t}
        if xi in left:
            raise InputError("lhs/rhs: expected ξ only as the variable of a window integral, got ξ outside one; "
                             "write the state at ξ under window_integral(...)")
        if left:
            raise InputError(f"lhs/rhs: expected every symbol to have a value, got {sorted(map(str, left))} without "
                             f"one; give them values, list them in exists= (some constant ≥ 0) or nonnegative=, or "
                             f"pass their Measure in measures=")
        # atoms and integrals
        self.points: dict = {}        # (state, c) → set of atoms
        self.history_states: list = []
        self.integrals: dict = {}     # Integral node → _Integral
        for label, e in self.terms:
            self._scan(e, f"lhs term {label!r}")
        self._scan(self.rhs, "rhs")
        for m in measures:
            vec, window, power = self.mdata[m.name]
            states = self._states_of(vec, m)
            for st in states:
                if m.kind in ("norm", "sup"):
                    self.points.setdefault((st, sympy.Integer(0)), set())
                if m.kind in ("window_norm", "window_integral", MEMORY):
                    self._history(st)
        used = {s for s, _ in self.points} | set(self.history_states)
        self.states = []
        for st in system.states:
            st = self.groups[id(st.frame)] if st.frame is not None else st
            if st in used and st not in self.states:
                self.states.append(st)
        for st in self.states:
            if st.unit and st.dim != 3:
                raise UnsupportedClaim(f"state {st.name}: expected a unit vector of dimension 3, got dimension "
                                       f"{st.dim}; other spheres are not supported yet")
        # windows
        hs = [i.h1 for i in self.integrals.values()]
        hs += [self.mdata[m.name][1] for m in measures if m.kind in ("window_norm", "window_integral", MEMORY)]
        self.H = max(hs, key=float) if hs and self.history_states else sympy.Integer(0)
        self.constraints = self._constraints(region)
        for st in self.states:
            if getattr(st, "is_frame", False):
                st.reference = self._frame_reference(st)
        breaks = {sympy.Integer(0), self.H}
        for i in self.integrals.values():
            breaks |= {i.h1, i.h2}
        for m in measures:
            if m.kind != "norm":
                breaks.add(self.mdata[m.name][1])
        for c in self.constraints:
            if c.kind == "sup" and c.window != sympy.oo:
                breaks.add(c.window)
        self.breaks = {b for b in breaks if not _lt(self.H, b)}
        #: the states of rotation starts: those with a history or with delayed values
        self.rotating = list(self.history_states) + [
            st for st in self.states if st not in self.history_states and any(s2 is st and c != 0 for s2, c in self.points)]

    # -- scanning ---------------------------------------------------------------------------------
    def _memory_time(self, exprs, measures) -> None:
        """Fix the witness time t when the claim has memory integrals ∫_0^t (default :data:`MEMORY_TIME`).

        A bound step holds at every t ≥ 0 for every admissible history, so a violation at one time
        refutes it; the memory integral is then a finite sum over the pieces of [0, t].
        """
        def memory(node):
            if len(node.limits) != 1:
                return False
            var, lo, hi = node.limits[0]
            return hi == t and not sympy.sympify(lo).has(t) and not sympy.sympify(lo).has(var)

        if not (any(m.kind == MEMORY for m in measures)
                or any(memory(node) for e in exprs for node in outer_integrals(e))):
            return
        if self.time is None and self.time_range is not None:
            raise UnsupportedClaim("a memory integral ∫_0^t with a searched witness time: give one time (time=1)")
        if self.time is None:
            self.time = MEMORY_TIME
        if self.time.is_negative:
            raise InputError(f"time: expected t ≥ 0 for a memory integral ∫_0^t, got {self.time}")

    def _state(self, atom, where):
        if atom.func not in self.funcs:
            raise InputError(f"{where}: {atom} is not a state of the system and has no value; give the "
                             f"parameter {atom.func} a value (values=) or use the system's states")
        return self.funcs[atom.func][0]

    def _history(self, st):
        if st not in self.history_states:
            self.history_states.append(st)

    def _point(self, atom, where):
        st = self._state(atom, where)
        arg = atom.args[0]
        c = sympy.expand(t - arg)
        if c.has(t) or c.has(xi):
            raise InputError(f"{where}: expected states at t, at t − c or at ξ under a window integral, got {atom}")
        if c.free_symbols:
            raise InputError(f"{where}: the delay of {atom} has no value ({sorted(map(str, c.free_symbols))}); "
                             f"give it a value")
        if not c.is_number or not c.is_real:
            raise UnsupportedClaim(f"{where}: expected a state at t − c with c a real constant, got {atom}")
        if c.is_negative:
            raise UnsupportedClaim(f"{where}: expected the state at t or at earlier times, got {atom} (a future "
                                   f"value)")
        self.points.setdefault((st, c), set()).add(atom)

    def _scan(self, expr, where):
        if expr.has(sympy.Derivative, sympy.Subs):
            raise UnsupportedClaim(f"{where}: expected state values, got a derivative of a state; substitute the "
                                   f"system's right-hand sides first (derivative_along)")
        nodes = outer_integrals(expr)
        for node in nodes:
            self._integral(node, where)
        outside = expr.xreplace({node: sympy.Dummy() for node in nodes})
        for atom in outside.atoms(AppliedUndef):
            self._point(atom, where)

    def _integral(self, node, where):
        if node in self.integrals:
            return
        if len(node.limits) != 1:
            raise UnsupportedClaim(f"{where}: expected single window integrals, got a nested (merged) integral "
                                   f"{_short(node)}; witnesses for nested integrals are not supported yet")
        var, lo, hi, inner = split_outer(node)
        if inner.has(sympy.Integral):
            raise UnsupportedClaim(f"{where}: expected single window integrals, got an integral inside the integrand "
                                   f"of {_short(node)}; not supported yet")
        h1, h2 = sympy.expand(t - lo), sympy.expand(t - hi)
        if self.time is not None and not sympy.sympify(lo).has(t):      # a memory integral ∫_0^t at the time
            h1 = sympy.expand(self.time - lo)
        for h in (h1, h2):
            if h.has(t) or h.has(var) or not h.is_number:
                if h.free_symbols - {t, var}:
                    raise InputError(f"{where}: the window of {_short(node)} has no value "
                                     f"({sorted(map(str, h.free_symbols - {t, var}))}); give it a value")
                raise UnsupportedClaim(f"{where}: expected a window integral over [t − h, t − h'] with constant "
                                       f"h ≥ h' ≥ 0 or a memory integral over [c, t], got limits ({lo}, {hi})")
        if h2.is_negative or _lt(h1, h2):
            raise UnsupportedClaim(f"{where}: expected a window integral over [t − h, t − h'] with h ≥ h' ≥ 0, "
                                   f"got limits ({lo}, {hi})")
        if inner.has(sympy.Derivative, sympy.Subs):
            raise UnsupportedClaim(f"{where}: a derivative of a state under an integral is not supported")
        dummies = {}
        for atom in inner.atoms(AppliedUndef):
            st = self._state(atom, where)
            arg = atom.args[0]
            if arg == var:
                self._history(st)
                dummies[atom] = sympy.Dummy()
            elif not arg.has(var):
                self._point(atom, where)
                dummies[atom] = sympy.Dummy()
            else:
                raise UnsupportedClaim(f"{where}: expected the state at {var} under ∫ d{var}, got {atom}; shifted "
                                       f"histories are not supported yet")
        degree = _degree(inner.xreplace(dummies), var)
        self.integrals[node] = _Integral(node, var, h1, h2, inner, degree)

    def _states_of(self, vec, what) -> list:
        states = []
        for atom in vec.atoms(AppliedUndef):
            st = self._state(atom, f"measure {getattr(what, 'name', what)}")
            if st not in states:
                states.append(st)
        return states

    def _constraints(self, region) -> list:
        out = []
        if region is None:
            return out
        for m, bound in region.bounds.items():
            vec = sympy.ImmutableMatrix(apply_substitution(m.vector, self.sub))
            bound = _number(apply_substitution(sympy.sympify(bound), self.sub), f"region bound on {m.text}")
            if bound.is_negative:
                raise InputError(f"region: expected a bound ≥ 0 on {m.text}, got {bound}")
            states = [st for st in self._states_of(vec, m) if st in self.states]
            if not states:
                continue
            if len(self._states_of(vec, m)) != 1:
                raise UnsupportedClaim(f"region: expected a bound on one state minus a constant, got {m.text} "
                                       f"(several states)")
            st = states[0]
            at = t if m.kind == "norm" else xi
            index, own = None, st
            if getattr(st, "is_frame", False):
                which = {self.funcs[a.func][1] // 3 for a in vec.atoms(AppliedUndef)}
                if len(which) != 1:
                    raise UnsupportedClaim(f"region: expected a bound on one vector of the frame {st.name} minus a "
                                           f"constant, got {m.text}")
                index = which.pop()
                own = st.vectors[index]
            center = sympy.ImmutableMatrix(own(at)) - vec
            if center.shape != (own.dim, 1) or center.atoms(AppliedUndef) or center.free_symbols:
                raise UnsupportedClaim(f"region: expected a bound on ‖{own.name} − c‖ with c constant, got "
                                       f"{m.text}; other region shapes are not supported yet")
            window = None
            if m.kind == "sup":
                window = apply_substitution(sympy.sympify(m.window), self.sub)
                if window != sympy.oo:      # oo: the sup over the whole history (a memory region)
                    window = _number(window, f"region bound on {m.text}: window")
            out.append(_Constraint(st, m.kind, window, center, bound, index))
        return out

    def _frame_reference(self, group) -> sympy.ImmutableMatrix:
        """The reference rotation R0 = [r1 r2 r3] of a frame: the centres of its region bounds, completed.

        Two centres give the third (r3 = r1 × r2 and cyclically), one is completed by an exact
        orthonormal basis of its complement, none gives the identity (the chart is then all of SO(3)).
        """
        centres: dict = {}
        for c in self.constraints:
            if c.state is not group:
                continue
            if c.vector in centres and any(not prove_zero(a - b) for a, b in zip(c.center, centres[c.vector])):
                raise UnsupportedClaim(f"region: two bounds on {group.vectors[c.vector].name} with different "
                                       f"centres; only one centre per vector is supported")
            centres.setdefault(c.vector, sympy.ImmutableMatrix(c.center))
        what = ", ".join(f"{group.vectors[i].name}: {list(v)}" for i, v in sorted(centres.items()))
        for i, v in centres.items():
            if not prove_zero(v.dot(v) - 1):
                raise UnsupportedClaim(f"region: expected the bound on {group.vectors[i].name} of the frame about a "
                                       f"unit vector, got the centre {list(v)}; bound s − r with a unit r")
        r: dict = dict(centres)
        if len(r) == 1:
            (i, c), = r.items()
            from ..charts import unit_vector_near

            extras = unit_vector_near(c, rho_max=sympy.pi).extras
            r[(i + 1) % 3], r[(i + 2) % 3] = sympy.ImmutableMatrix(extras["e1"]), sympy.ImmutableMatrix(extras["e2"])
        elif len(r) == 2:
            (i, a), (j, b) = sorted(r.items())
            if not prove_zero(a.dot(b)):
                raise UnsupportedClaim(f"region: expected the centres of the bounds on a frame to be orthonormal, "
                                       f"got {what}")
            k = 3 - i - j
            r[k] = sympy.ImmutableMatrix(a.cross(b) if (j - i) % 3 == 1 else b.cross(a)).applyfunc(sympy.radsimp)
        elif len(r) == 3:
            R = sympy.Matrix.hstack(r[0], r[1], r[2])
            if not all(prove_zero(e) for e in list(R.T * R - sympy.eye(3)) + list(r[2] - r[0].cross(r[1]))):
                raise UnsupportedClaim(f"region: expected the centres of the bounds on a frame to be a right-handed "
                                       f"orthonormal triad (r3 = r1 × r2), got {what}")
        else:
            return sympy.ImmutableMatrix(sympy.eye(3))
        return sympy.ImmutableMatrix(sympy.Matrix.hstack(r[0], r[1], r[2]))

    # -- per piece count --------------------------------------------------------------------------
    def offsets(self, m) -> list:
        """Break points (offsets from t) of the piece grid, decreasing from H to 0.

        ``m`` an int: m equal pieces (and the window ends); ``("ends", ε)``: pieces of length ε·H
        at both sides of every window end (histories concentrated near one end of a window).
        """
        if not self.history_states:
            return [sympy.Integer(0)]
        if isinstance(m, tuple):
            eps = sympy.Rational(m[1]) * self.H
            near = [b + d for b in self.breaks for d in (-eps, eps)]
            pts = list(self.breaks) + [q for q in near if not _lt(q, 0) and not _lt(self.H, q)]
        else:
            pts = list(self.breaks) + [self.H * sympy.Rational(k, m) for k in range(1, m)]
        out = []
        for p in sorted(pts, key=float, reverse=True):
            if out and abs(float(out[-1] - p)) < 1e-13 and sympy.simplify(out[-1] - p) == 0:
                continue
            out.append(p)
        return out

    def chart(self, st, applicable):
        if getattr(st, "is_frame", False):
            bounds: dict = {}
            for c in applicable:
                if c.vector not in bounds or _lt(c.bound, bounds[c.vector]):
                    bounds[c.vector] = c.bound
            key = ("frame", st.name, tuple(sorted(bounds.items())))
            if key not in self._charts:
                self._charts[key] = _FrameChart(st.reference, bounds)
            return self._charts[key]
        if not applicable:
            key = ("sphere" if st.unit else "free", st.dim)
            if key not in self._charts:
                self._charts[key] = (_Chart("cap", 3, center=sympy.Matrix([0, 0, 1])) if st.unit
                                     else _Chart("free", st.dim))
            return self._charts[key]
        center = applicable[0].center
        for c in applicable[1:]:
            if any(sympy.simplify(a - b) != 0 for a, b in zip(c.center, center)):
                raise UnsupportedClaim(f"region: two bounds on {st.name} with different centres; only one centre "
                                       f"per state is supported")
        bound = min((c.bound for c in applicable), key=float)
        kind = "fixed" if bound == 0 else "cap" if st.unit else "ball"
        key = (kind, st.dim, sympy.ImmutableMatrix(center), bound)
        if key not in self._charts:
            self._charts[key] = _Chart(kind, st.dim, center=center, bound=None if kind == "fixed" else bound)
        return self._charts[key]

    def applicable(self, st, c_start, at_t: bool) -> list:
        """The constraints that hold on a slot starting at offset ``c_start`` (the oldest time of the slot)."""
        out = []
        for c in self.constraints:
            if c.state is not st:
                continue
            if c.kind == "norm" and at_t:
                out.append(c)
            if c.kind == "sup" and not _lt(c.window, c_start):
                out.append(c)
        return out


def _evaluated(expr):
    """``expr`` with its integrals free of states (a kernel's tail ∫_u^∞ e^{−2ζ}dζ, in u or in t − ξ) evaluated
    by SymPy where it finds a closed form; the others are kept."""
    expr = sympy.sympify(expr)
    rep = {}
    for node in expr.atoms(sympy.Integral):
        if node.atoms(AppliedUndef):
            continue
        try:
            done = node.doit()
        except RecursionError:
            continue
        if not done.has(sympy.Integral):
            rep[node] = done
    return expr.xreplace(rep) if rep else expr


def _short(x, n=80) -> str:
    s = str(x)
    return s if len(s) <= n else s[: n - 1] + "…"


class _Model:
    """The claim on the piecewise-constant histories with a given grid: exact and numeric forms."""

    def __init__(self, problem: _Problem, m: int):
        self.problem = problem
        self.m = m
        self.offsets = problem.offsets(m)
        self.npieces = len(self.offsets) - 1 if problem.history_states else 0
        # slots
        self.slots: list = []
        self.point_slot: dict = {}
        self.piece_slot: dict = {}
        count = [0, 0]

        def new_slot(st, where, chart):
            z = tuple(sympy.Symbol(f"_wz{count[0] + i}", real=True) for i in range(chart.dim))
            count[0] += chart.dim
            slot = _Slot(st, where, z, chart, count[1])
            count[1] += chart.nparams
            self.slots.append(slot)
            return slot

        for st in problem.states:
            for (s2, c) in sorted(problem.points, key=lambda k: (problem.states.index(k[0]), float(k[1]))):
                if s2 is st:
                    chart = problem.chart(st, problem.applicable(st, c, c == 0))
                    self.point_slot[(st, c)] = new_slot(st, ("point", c), chart)
            if st in problem.history_states:
                for k in range(self.npieces):
                    chart = problem.chart(st, problem.applicable(st, self.offsets[k], False))
                    self.piece_slot[(st, k)] = new_slot(st, ("piece", k), chart)
        self.time_slot = None
        if problem.time_range is not None:
            self.time_slot = new_slot(None, ("time", 0), _TimeChart(*problem.time_range))
        self.nparams = count[1]
        self.params = [sympy.Symbol(f"_wp{i}", real=True) for i in range(self.nparams)]
        self.free = np.zeros(self.nparams, dtype=bool)
        for slot in self.slots:
            if slot.chart.kind == "free":
                self.free[slot.start:slot.start + slot.chart.nparams] = True
        # the claim in the slot symbols
        self.point_map = {}
        for (st, c), slot in self.point_slot.items():
            for f, z in zip(st.functions, slot.z):
                self.point_map[f(t - c)] = z
            for atom in problem.points.get((st, c), ()):
                self.point_map[atom] = slot.z[[g for g in st.functions].index(atom.func)]
        self.measure_z = {m_.symbol: self._measure(m_) for m_ in problem.measures}
        self.terms_z = [(label, self._convert(e, f"lhs term {label!r}")) for label, e in problem.terms]
        self.rhs_z = self._convert(problem.rhs, "rhs")
        D = sympy.Add(*[e for _, e in self.terms_z]) - self.rhs_z
        # a positive constant (γ > 0) that divides lhs − rhs is factored out: the sign is the quotient's
        self.factors = []
        for c in problem.constants:
            if c.is_positive and D.xreplace({c: 0}) == 0 and not sympy.diff(D, c).has(c):
                self.factors.append(c)
                D = D.xreplace({c: 1})
        cs = self.rest = [c for c in problem.constants if c not in self.factors]
        #: the constants' values at which A, the terms and the sizes are taken (factors 1, the rest 0)
        self.base = {c: 1 for c in self.factors} | {c: 0 for c in cs}
        zero = self.base
        self.A = D.xreplace(zero)
        self.B = []
        for c in cs:
            b = sympy.diff(D, c)
            if b.free_symbols & set(cs):
                raise InputError(f"rhs: expected lhs − rhs affine in the constants {', '.join(map(str, cs))} "
                                 f"(exists= / nonnegative=), got the derivative {_short(b)} by {c}, which still "
                                 f"depends on {', '.join(sorted(str(x) for x in b.free_symbols & set(cs)))}; "
                                 f"write the bound affine in them (a common factor is divided out when its symbol "
                                 f"is positive, Symbol(..., positive=True))")
            self.B.append((c, b))
        self.B_active = [(c, b) for c, b in self.B if b != 0]
        # numeric forms
        outs = [self.A] + [b for _, b in self.B_active]
        zsyms = [z for slot in self.slots for z in slot.z]
        self.zsyms = zsyms
        self._f = sympy.lambdify(zsyms, outs, modules="numpy", cse=True)
        # the sides' sizes Σ|term| + |rhs|, the absolute values taken numerically (SymPy's Abs of a large
        # expression costs seconds deciding its sign)
        parts = sympy.lambdify(zsyms, [e.xreplace(zero) for _, e in self.terms_z] + [self.rhs_z.xreplace(zero)],
                               modules="numpy", cse=True)
        self._size = lambda *z: sum(np.abs(np.asarray(v, dtype=float)) for v in parts(*z))
        self.scale = 1.0        # typical size of the objective (set by :meth:`calibrate`)
        self.tol = 1e-12        # improvements below this (in units of scale) are rounding noise

    # -- building -----------------------------------------------------------------------------
    def _pieces_in(self, h1, h2):
        """(k, σ_lo, σ_hi) of the pieces meeting the offsets [h2, h1]."""
        out = []
        for k in range(self.npieces):
            hi = self.offsets[k] if not _lt(h1, self.offsets[k]) else h1
            lo = self.offsets[k + 1] if _lt(h2, self.offsets[k + 1]) else h2
            if _lt(lo, hi):
                out.append((k, lo, hi))
        return out

    def _piece_map(self, st_atoms_var, k):
        rep = {}
        for atom in st_atoms_var:
            st, i = self.problem.funcs[atom.func]
            rep[atom] = self.piece_slot[(st, k)].z[i]
        return rep

    def _integral_sum(self, I: _Integral, where):
        var = I.var
        hist = [a for a in I.inner.atoms(AppliedUndef) if a.args[0] == var]
        sigma = sympy.Dummy("sigma")
        total = []
        for k, lo, hi in self._pieces_in(I.h1, I.h2):
            F = I.inner.xreplace(self._piece_map(hist, k)).xreplace(self.point_map)
            if self.problem.time is not None:
                F = F.xreplace({t: self.problem.time})
            if I.degree is None:
                G = self._antiderivative(I)
                if G is not None:        # one antiderivative for every piece (and every grid)
                    dummies, s_, g = G
                    rep = {d: (self.piece_slot[(self.problem.funcs[a.func][0], k)].z[self.problem.funcs[a.func][1]]
                               if a.args[0] == var else self.point_map.get(a, a)) for a, d in dummies.items()}
                    total.append((g.xreplace({s_: hi}) - g.xreplace({s_: lo})).xreplace(rep))
                    continue
                val = sympy.integrate(F.xreplace({var: t - sigma}), (sigma, lo, hi))
                if val.has(sympy.Integral):
                    raise UnsupportedClaim(f"{where}: the weight of {_short(I.node)} could not be integrated "
                                           f"exactly over a piece; use a polynomial weight in {var}")
                total.append(val)
                continue
            nodes, weights = _newton_cotes(I.degree)
            length = hi - lo
            total.append(length * sympy.Add(*[w * F.xreplace({var: t - (lo + length * x)})
                                              for x, w in zip(nodes, weights)]))
        return sympy.Add(*total)

    def _kernel_mass(self, name, lo, hi):
        """∫_lo^hi κ(u) du exactly, from one antiderivative of the kernel (cached on the problem)."""
        cache = self.problem.__dict__.setdefault("_kernel_antiderivatives", {})
        kern = self.problem.kernels[name](_U)
        if name not in cache:
            try:
                K = sympy.integrate(kern, _U)
            except RecursionError:  # SymPy's meijerint on an unusual kernel
                K = None
            cache[name] = None if K is None or K.has(sympy.Integral) or K.has(sympy.Piecewise) else K
        K = cache[name]
        if K is None:
            return sympy.Integral(kern, (_U, lo, hi))
        return K.subs(_U, hi) - K.subs(_U, lo)

    def _antiderivative(self, I: _Integral):
        """``(atom → dummy, σ, G)`` with G(σ) an antiderivative of the integrand at ξ = t − σ in dummies for the
        states (cached on the problem), or None when SymPy finds none."""
        cache = self.problem.__dict__.setdefault("_antiderivatives", {})
        if I.node not in cache:
            dummies = {a: sympy.Dummy(real=True) for a in I.inner.atoms(AppliedUndef)}
            sigma = sympy.Dummy("sigma")
            F = _evaluated(I.inner.xreplace(dummies))
            if self.problem.time is not None:
                F = F.xreplace({t: self.problem.time})
            try:
                g = sympy.integrate(F.xreplace({I.var: t - sigma}), sigma)
            except RecursionError:  # SymPy's meijerint on an unusual integrand: summed piece by piece instead
                g = sympy.Integral(F, sigma)
            cache[I.node] = None if g.has(sympy.Integral) or g.has(sympy.Piecewise) else (dummies, sigma, g)
        return cache[I.node]

    def _time_value(self):
        """What t becomes: the given time, the time slot's symbol, or 0 (autonomous claims)."""
        if self.time_slot is not None:
            return self.time_slot.z[0]
        return self.problem.time if self.problem.time is not None else sympy.Integer(0)

    def _convert(self, expr, where):
        rep = {node: self._integral_sum(self.problem.integrals[node], where) for node in outer_integrals(expr)}
        out = expr.xreplace(rep).xreplace(self.point_map).xreplace(self.measure_z)
        if out.has(t):
            if self.problem.time is None and self.problem.time_range is None:
                self._time_check(out, where)
            out = out.xreplace({t: self._time_value()})
        return out

    def _time_check(self, expr, where):
        """Raise InputError unless ``expr`` (in the slot symbols and t) is independent of t numerically."""
        syms = sorted(expr.free_symbols - {t}, key=lambda s: s.name)
        f = sympy.lambdify(syms + [t], expr, modules="numpy")
        rng = np.random.default_rng(1)
        for _ in range(3):
            p = rng.normal(size=len(syms)) * 0.3
            with np.errstate(all="ignore"):
                a, b = complex(f(*p, 0.0)), complex(f(*p, 0.731))
            if abs(a - b) > 1e-9 * (1 + abs(a)):
                raise InputError(f"{where}: expected an autonomous claim (t only through t − ξ and delays), got an "
                                 f"explicit dependence on t (a time-varying coefficient such as h(t)); pass the "
                                 f"witness time: time=1 (a number) or time=(lo, hi) to search it")

    def _measure(self, m: Measure):
        vec, window, power = self.problem.mdata[m.name]
        if m.kind == "norm":
            return sympy.sqrt(sympy.Add(*[c ** 2 for c in vec.xreplace(self.point_map)]))
        xs = [a for a in vec.atoms(AppliedUndef)]
        states = {self.problem.funcs[a.func][0] for a in xs}
        if m.kind == "sup":
            cands = []
            for k, lo, hi in self._pieces_in(window, 0):
                if all((st, k) in self.piece_slot for st in states):
                    v = vec.xreplace(self._piece_map(xs, k))
                    cands.append(sympy.sqrt(sympy.Add(*[c ** 2 for c in v])))
            for (st, c), slot in self.point_slot.items():
                if st in states and not _lt(window, c) and all((s2, c) in self.point_slot for s2 in states):
                    rep = {a: self.point_slot[(self.problem.funcs[a.func][0], c)].z[self.problem.funcs[a.func][1]]
                           for a in xs}
                    cands.append(sympy.sqrt(sympy.Add(*[e ** 2 for e in vec.xreplace(rep)])))
            cands = list(dict.fromkeys(cands))
            return cands[0] if len(cands) == 1 else sympy.Max(*cands, evaluate=False)
        total = []
        for k, lo, hi in self._pieces_in(window, 0):
            v = vec.xreplace(self._piece_map(xs, k))
            weight = hi - lo
            if m.kind == MEMORY:     # ∫ κ(u) du over the piece's offsets u = t − ξ ∈ [lo, hi], exactly
                weight = self._kernel_mass(m.name, lo, hi)
                if weight.has(sympy.Integral):
                    raise UnsupportedClaim(f"measure {m.name}: its kernel could not be integrated exactly over a "
                                           f"piece")
            total.append(weight * sympy.Pow(sympy.Add(*[c ** 2 for c in v]), power / 2))
        integral = sympy.Add(*total)
        return integral if m.kind in ("window_integral", MEMORY) else sympy.Pow(integral, 1 / power)

    # -- numeric ------------------------------------------------------------------------------
    def zvalues(self, P: np.ndarray) -> list:
        """The slot values for parameter columns ``P`` (shape (nparams, N))."""
        n = P.shape[1]
        out = []
        for slot in self.slots:
            vals = slot.chart.numeric(P[slot.start:slot.start + slot.chart.nparams])
            out.extend(np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in vals)
        return out

    def objective(self, P: np.ndarray) -> np.ndarray:
        """``min(A, B_k…)`` (to be maximised), per column of ``P``; −inf where undefined."""
        n = P.shape[1]
        with np.errstate(all="ignore"):
            outs = self._f(*self.zvalues(P))
            vals = np.min(np.array([np.broadcast_to(np.asarray(o, dtype=float), (n,)) for o in outs]), axis=0)
            if self.free.any():
                vals = vals / (1 + np.sum(P[self.free] ** 2, axis=0)) ** 2   # same sign, bounded for degree < 4
        vals = np.where(np.isfinite(vals), vals, -np.inf)
        return vals

    def calibrate(self, rng, n: int = 16) -> None:
        """Set :attr:`scale` and :attr:`tol` from the objective and the sides' sizes at random points."""
        P = np.array([self.random_params(rng) for _ in range(n)]).T.reshape(self.nparams, n)
        vals = self.objective(P)
        with np.errstate(all="ignore"):
            sizes = np.broadcast_to(np.asarray(self._size(*self.zvalues(P)), dtype=float), (n,))
        vals, sizes = np.abs(vals[np.isfinite(vals)]), sizes[np.isfinite(sizes)]
        noise = 1e-14 * (float(np.median(sizes)) if sizes.size else 1.0)
        typical = float(np.median(vals)) if vals.size else 0.0
        self.scale = max(typical, 1e3 * noise, 1e-300)
        self.tol = max(1e-12, 10 * noise / self.scale)

    def locally_positive(self, p: np.ndarray) -> bool:
        """The objective at ``p`` exceeds float noise relative to the sides' sizes *at p* (a small history)."""
        P = np.asarray(p, dtype=float).reshape(self.nparams, 1)
        with np.errstate(all="ignore"):
            val = min(float(np.asarray(o, dtype=float).ravel()[0]) for o in self._f(*self.zvalues(P)))
            size = float(np.asarray(self._size(*self.zvalues(P)), dtype=float).ravel()[0])
        return bool(np.isfinite(val) and np.isfinite(size) and val > 1e-12 * size and val > 0)

    def random_params(self, rng) -> np.ndarray:
        p = np.zeros(self.nparams)
        for slot in self.slots:
            p[slot.start:slot.start + slot.chart.nparams] = slot.chart.random(rng)
        return p

    def rotation_params(self, rng) -> np.ndarray:
        """A start whose history pieces follow a rotation of the value at t."""
        p = self.random_params(rng)
        H = float(self.problem.H) or max([float(c) for _, c in self.point_slot] + [1.0])
        for st in self.problem.rotating:
            s0 = self.point_slot.get((st, 0))
            first = s0 or self.piece_slot.get((st, self.npieces - 1)) or next(
                slot for (s2, _), slot in self.point_slot.items() if s2 is st)
            ch = first.chart
            if ch.kind == "frame":
                self._frame_rotation(st, first, p, rng, H)
                continue
            if ch.kind == "cap" and rng.random() < 0.4:
                p[first.start:first.start + 2] = [0.0, rng.uniform(0, 2 * math.pi)]
            v0 = ch.value(p[first.start:first.start + ch.nparams])
            if st.dim == 1:
                profile = rng.uniform(-1, 1, size=1)
                for k in range(self.npieces):
                    slot = self.piece_slot[(st, k)]
                    v = v0 * (1 + profile[0] * rng.random())
                    p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(v)
                continue
            center = getattr(ch, "_c", None)
            if center is not None and rng.random() < 0.6 and np.linalg.norm(center) > 0:
                a = center / np.linalg.norm(center)
            else:
                a = _unit(rng, st.dim)
            b = _unit(rng, st.dim)
            b = b - (b @ a) * a
            b = b / (np.linalg.norm(b) or 1.0)
            mode = int(rng.integers(0, 4))
            pieces_chart = (self.piece_slot.get((st, 0)) or first).chart
            top = getattr(pieces_chart, "_top", math.pi)
            amp = rng.uniform(0.3, 1.6) * (top if st.unit else math.pi) * rng.choice([-1, 1])

            def phi(sig):
                return amp * (sig, math.sin(math.pi * sig), math.sin(2 * math.pi * sig), sig ** 2)[mode]

            def place(slot, sig):
                v = _plane_rotation(v0, a, b, phi(sig))
                p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(v)

            for k in range(self.npieces):
                sig = float(self.offsets[k] + self.offsets[k + 1]) / 2 / H
                place(self.piece_slot[(st, k)], sig)
            for (s2, c), slot in self.point_slot.items():
                if s2 is st and c != 0 and float(c) <= H:
                    place(slot, float(c) / H)
        return p

    def _frame_rotation(self, st, first, p, rng, H) -> None:
        """Rotation start of a frame: the pieces are the triad at t turned about one axis by φ(σ)."""
        ch = first.chart
        if rng.random() < 0.4:
            p[first.start] = 0.0                                  # the value at t: the reference triad
        T0 = ch.value(p[first.start:first.start + ch.nparams]).reshape(3, 3).T
        a = ch._R0[:, int(rng.integers(0, 3))] if rng.random() < 0.6 else _unit(rng, 3)
        mode = int(rng.integers(0, 5))
        amp = rng.uniform(0.3, 1.6) * ch._top * rng.choice([-1, 1])

        def place(slot, sig):
            # profiles of the angle along the window; the last turns t and the oldest time oppositely
            phi = amp * (sig, math.sin(math.pi * sig), math.sin(2 * math.pi * sig), sig ** 2, sig - 0.5)[mode]
            T = _rotation_np(a, phi) @ T0
            p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(T.T.reshape(-1))

        if mode == 4 and first.where == ("point", 0):
            place(first, 0.0)
        for k in range(self.npieces):
            place(self.piece_slot[(st, k)], float(self.offsets[k] + self.offsets[k + 1]) / 2 / H)
        for (s2, c), slot in self.point_slot.items():
            if s2 is st and c != 0 and float(c) <= H:
                place(slot, float(c) / H)

    # -- exact -----------------------------------------------------------------------------------
    def exact_point(self, p: np.ndarray, denominator: int = _DENOMINATOR):
        """``(records, zexact, zballs)`` at the exact point near ``p``: slot label → exact parameters
        (strings), slot symbol → exact value and → its arb ball."""
        records, zexact, zballs = {}, {}, {}
        for slot in self.slots:
            record, vals = slot.chart.exact(p[slot.start:slot.start + slot.chart.nparams], denominator)
            records[slot.label] = record
            for z, v in zip(slot.z, vals):
                zexact[z] = v
                zballs[z] = enclose(v, prec=_PREC)
        return records, zexact, zballs


# ---------------------------------------------------------------------------------------------
# the search
# ---------------------------------------------------------------------------------------------

def _ball(expr, zballs):
    expr = sympy.sympify(expr)
    return enclose(expr, {z: zballs[z] for z in expr.free_symbols}, prec=_PREC)


#: step lengths tried at once along a search direction (one vectorised evaluation)


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
                 seeds=SEEDS) -> SearchOutcome:
    """:func:`search_witness`, telling also whether the search ran to its end (:class:`SearchOutcome`).

    ``seeds`` caps the structured starts per grid (default :data:`SEEDS`; None: all); with ``structured`` the end
    grids :data:`~.witness_seeds.END_GRIDS` are added unless ``pieces`` names an end grid.

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
        model = _Model(problem, m)
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
