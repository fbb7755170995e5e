"""Conclusions by signal arguments: the links of theorems whose conclusion is not Krasovskii's.

An adaptive controller's Lyapunov function is only nonincreasing (V̇ = −vᵀK_dv ≤ 0): it bounds
the signals and makes some of them square integrable, and Barbalat's lemma turns that into
convergence.  Each class below is one link of such an argument; it states the inequality it
licenses and decides every side condition along the theorem's own system (exact polynomial
identities in the state values, exact matrix definiteness), so a chain of them is a proof:

* :class:`Dissipation` — V̇ = −qᵀSq along the system with S ⪰ 0: **V(t) ≤ V(0)**.
* :class:`LevelSet` — V = ½zᵀQz with Q ≻ 0 and V nonincreasing: **‖z(t)‖² ≤ 2V(0)/λ_min(Q)**.
* :class:`Conserved` — d/dt‖x‖² = 0 along the system: **‖x(t)‖ = ‖x(0)‖**.
* :class:`BoundedStates` — every state component is a polynomial in bounded signals and in the
  bounded reference functions of t (found by solving the signals' definitions for the states):
  **every state is bounded** along every solution.
* :class:`SquareIntegrable` — fᵀKf + Σ rᵀSr = Σ gᵀAg − dB/dt along the system, K ≻ 0, S, A ⪰ 0,
  g ∈ L2, B bounded: **∫_0^∞ ‖f‖² < ∞**.
* :class:`Barbalat` — f ∈ L2 and ḟ a polynomial in the bounded states and references (so f and
  ḟ are bounded, d/dt‖f‖² is bounded, ‖f‖² is uniformly continuous and integrable): **f → 0**
  (Barbalat's lemma; the paper's Lemma 1).
* :class:`LinearLimit` — g = Σ cⱼfⱼ identically with constants cⱼ and every fⱼ → 0: **g → 0**.
* :class:`BoundedSignal` — g a polynomial in the bounded states and references: **g bounded**.
* :class:`Comparison` — D⁺r ≤ φ(r) for r = ‖V‖ (a checked comparison system) with φ(0) = 0 and
  φ < 0 on (0, ρ): **{r < ρ} is positively invariant and r → 0** (the comparison lemma).

:class:`LinearLimit`, :class:`FiniteLimit`, :class:`BoundedSignal`, :class:`Comparison` and
:class:`Follows` are in :mod:`lkverify.certify.steps.limits`.

Each link's :meth:`decide` returns a :class:`~lkverify.report.results.Result` and records what it
established in a :class:`Facts` (by name, with the weakest status it rests on): a later link that
needs a fact nobody established is ``undecided``, naming it; a refuted side condition is ``failed``.

Examples
--------
ẋ = −x + y·z, ẏ = −x·z (a toy "adaptive" loop): V = ½(x² + y²) has V̇ = −x², so x ∈ L2, both states
are bounded, ẋ is a polynomial in them, and x → 0:

>>> import sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, t
>>> P = Parameters(); X = Vector("x", 1); Yv = Vector("y", 1); z = sympy.Function("z", real=True)(t)
>>> x, y = X(t)[0], Yv(t)[0]
>>> sys_ = System([Equation(X, [Term(-x + y * z)]), Equation(Yv, [Term(-x * z)])], parameters=P)
>>> V = (x**2 + y**2) / 2
>>> links = [Dissipation(V, sympy.Matrix([x]), sympy.eye(1)),
...          LevelSet(V, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), sympy.eye(2)),
...          BoundedStates(), SquareIntegrable("x", sympy.Matrix([x]), sympy.eye(1), storage=V),
...          Barbalat("x")]
>>> facts = Facts(sys_, {}, {"z": sympy.cos(t)})
>>> [(r.name, r.status.value) for r in (link.decide(facts) for link in links)]  # doctest: +NORMALIZE_WHITESPACE
[('V̇ = −qᵀSq ≤ 0', 'exact'), ('V = ½zᵀQz, Q ≻ 0: x, y bounded', 'exact'),
 ('every state bounded', 'exact'), ('x ∈ L2', 'exact'), ('x → 0 (Barbalat)', 'exact')]
>>> Facts(sys_, {}, {"z": t}).reference_bounded(sympy.Symbol("z", real=True))[0].value   # z = t is unbounded
'failed'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import sympy

from ...errors import InputError
from ...report.results import Result
from ...status import Status
from ...declare.vectors import as_column, quad as _quad
from ..matrices import matrix_positive_definite

__all__ = ["Barbalat", "BoundedStates", "Conserved", "Dissipation", "Facts", "LevelSet", "SquareIntegrable",
           "bounded_in_t", "decide_all", "sup_bound"]


_weakest = Status.weakest


def bounded_in_t(expr) -> tuple:
    """``(status, why)``: is the function ``expr`` of t bounded on t ≥ 0?

    ``exact`` for expressions built from rationals, sin and cos (of anything real), exp(a·t + b)
    with a ≤ 0, sums, products and nonnegative integer powers; ``failed`` for a nonconstant
    polynomial in t (unbounded); ``undecided`` otherwise.

    >>> t = sympy.Symbol("t", real=True)
    >>> [bounded_in_t(e)[0].value for e in (sympy.sin(t) / 2, sympy.cos(3 * t / 4) ** 2 + sympy.exp(-t), t, t * sympy.sin(t))]
    ['exact', 'exact', 'failed', 'undecided']
    """
    from ...declare.symbols import t

    e = sympy.sympify(expr)
    if not e.free_symbols:
        return (Status.EXACT, "a constant") if e.is_finite is not False else (Status.FAILED, "not finite")
    try:
        poly = sympy.Poly(e, t)
        if poly.degree() >= 1 and not any(c.free_symbols for c in poly.all_coeffs()):
            return Status.FAILED, f"{e} is a nonconstant polynomial in t: unbounded"
    except sympy.PolynomialError:
        pass

    def ok(x) -> bool:
        if not x.free_symbols:
            return x.is_finite is True
        if isinstance(x, (sympy.sin, sympy.cos)):
            return x.args[0].is_real is True
        if isinstance(x, sympy.exp):
            arg = sympy.expand(x.args[0])
            a = arg.coeff(t, 1)
            rest = sympy.expand(arg - a * t)
            return (not (a.free_symbols or rest.free_symbols)) and a.is_real and a <= 0 and rest.is_real
        if isinstance(x, (sympy.Add, sympy.Mul)):
            return all(ok(a) for a in x.args)
        if isinstance(x, sympy.Pow):
            return x.exp.is_Integer and x.exp >= 0 and ok(x.base)
        return False

    if ok(e):
        return Status.EXACT, f"{e}: built from constants, sin, cos and decaying exponentials (bounded on t ≥ 0)"
    return Status.UNDECIDED, f"{e}: not recognised as bounded on t ≥ 0 (sums and products of sin, cos, exp(−at))"


def sup_bound(expr):
    """An exact upper bound of sup_{t ≥ 0} |expr(t)|, or None when it cannot be read off.

    Built term by term: |c| for a real constant, 1 for sin and cos of a real argument, exp(b) for
    exp(a·t + b) with a ≤ 0 (a, b real numbers), sums by the triangle inequality, products and
    nonnegative integer powers multiplicatively.  The bound is sound, not tight
    (|sin t + cos t| ≤ 2, the supremum is √2).

    >>> t = sympy.Symbol("t", real=True)
    >>> [sup_bound(e) for e in (sympy.sin(t) / 2 - sympy.cos(3 * t / 4) / 3, 2 * sympy.exp(-t) * sympy.cos(t) ** 2)]
    [5/6, 2]
    >>> sup_bound(t * sympy.sin(t)) is None, sup_bound(sympy.exp(t)) is None
    (True, True)
    """
    from ...declare.symbols import t

    def bound(x):
        if not x.free_symbols:
            return abs(x) if x.is_real is True and x.is_finite is True else None
        if isinstance(x, (sympy.sin, sympy.cos)):
            return sympy.Integer(1) if x.args[0].is_real is True else None
        if isinstance(x, sympy.exp):
            arg = sympy.expand(x.args[0])
            a, rest = arg.coeff(t, 1), sympy.expand(arg - arg.coeff(t, 1) * t)
            ok = not (a.free_symbols or rest.free_symbols) and a.is_real and a <= 0 and rest.is_real
            return sympy.exp(rest) if ok else None
        if isinstance(x, sympy.Add):
            parts = [bound(y) for y in x.args]
            return None if any(b is None for b in parts) else sympy.Add(*parts)
        if isinstance(x, sympy.Mul):
            parts = [bound(y) for y in x.args]
            return None if any(b is None for b in parts) else sympy.Mul(*parts)
        if isinstance(x, sympy.Pow) and x.exp.is_Integer and x.exp >= 0:
            b = bound(x.base)
            return None if b is None else b ** x.exp
        return None

    return bound(sympy.sympify(expr))


class Facts:
    """What the links of a signal argument have established so far, along one system at one set of values.

    Parameters
    ----------
    system : System
        The closed loop every identity is derived along.
    substitution : mapping
        The parameter values (``Parameters.substitution``), applied to every expression.
    references : mapping
        Name of each time-varying coefficient of the system → its value as a function of t (the
        reference signals ω_d(t)); a coefficient with no value here is not known to be bounded.

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> facts.states, facts.reference_bounded(sympy.Symbol("w"))[0].value
    ([x_1], 'undecided')
    """

    def __init__(self, system, substitution: Mapping, references: Mapping):
        from ...symbolic.polynomial import plain

        self.system, self.sub = system, dict(substitution)
        self.references = {str(k): sympy.sympify(v) for k, v in references.items()}
        self.plain = lambda x: plain(sympy.sympify(x).xreplace(self.sub) if self.sub else sympy.sympify(x))
        self.states = [sympy.Symbol(f.__name__, real=True) for s in system.states for f in s.functions]
        self.bounded: dict = {}        # signal name → (status, why)
        self.square_integrable: dict = {}
        self.converges: dict = {}      # name → (status, expression in plain symbols)
        self.signals: dict = {}        # name → the signal in plain symbols
        self.signals_t: dict = {}      # name → the signal in the states at t
        self.nonincreasing: dict = {}  # V (plain) → status
        self.states_bounded: Status | None = None
        self.dissipation = None        # (status, q, S, S ⪰ 0 check) of the last Dissipation: V̇ = −qᵀSq
        self.links: dict = {}          # link name → the status it was decided with (by decide_all, SignalTheorem)

    # -- reference signals -------------------------------------------------------------------------------------
    def reference_bounded(self, symbol) -> tuple:
        """``(status, why)`` for a plain reference symbol (``wd1`` or its rate ``wd1_dot``)."""
        from ...declare.symbols import t

        name = str(symbol)
        base, order = (name[:-4], 1) if name.endswith("_dot") else (name, 0)
        if base not in self.references:
            return Status.UNDECIDED, f"{name} is not a state and no bounded value of it is known"
        value = self.references[base]
        if order:
            value = sympy.diff(value, t)
        status, why = bounded_in_t(value)
        return status, f"{name} = {value}: {why}"

    def polynomial_in_states(self, expr, what: str) -> tuple:
        """``(status, why)``: is ``expr`` (plain) a polynomial in the states and bounded references?

        Bounded only when the states are (:class:`BoundedStates` decided before) and every
        reference function it contains is.
        """
        expr = sympy.expand(sympy.sympify(expr))
        others = sorted(expr.free_symbols - set(self.states), key=str)
        gens = list(self.states) + others
        try:
            poly = sympy.Poly(expr, *gens) if gens else None
        except sympy.PolynomialError:
            return Status.UNDECIDED, f"{what} is not a polynomial in the states and references"
        if poly is not None and any(c.free_symbols for c in poly.coeffs()):
            return Status.UNDECIDED, f"{what} has coefficients that are not numbers"
        statuses, whys = [], []
        uses_states = bool(expr.free_symbols & set(self.states))
        if uses_states:
            if self.states_bounded is None:
                return Status.UNDECIDED, f"{what} depends on the states, and no link has bounded them"
            statuses.append(self.states_bounded)
        for s in others:
            st, why = self.reference_bounded(s)
            statuses.append(st)
            if st is not Status.EXACT:
                whys.append(why)
        status = _weakest(statuses)
        if status is Status.EXACT or status is Status.CERTIFIED:
            return status, f"{what} is a polynomial in the bounded states" + (
                f" and the bounded references {', '.join(map(str, others))}" if others else "")
        return status, f"{what}: " + "; ".join(whys or ["the states are not bounded"])

    def link_status(self, name: str) -> Status:
        """The status an earlier link of the chain named ``name`` was decided with (``undecided`` if none was)."""
        return self.links.get(name, Status.UNDECIDED)

    def rate(self, expr):
        """d/dt of ``expr`` (in the states at t) along the system, in plain symbols."""
        from ...symbolic.polynomial import time_derivative

        return time_derivative(expr, self.system, self.sub)

    def needs(self, table: Mapping, name: str, what: str) -> tuple:
        if name not in table:
            return Status.UNDECIDED, f"rests on “{name} {what}”, which no earlier link established"
        st = table[name][0]
        return st, f"{name} {what} ({st})"


def _demo():
    """(facts, x, q) for the doctests: ẋ = −x, no link decided yet, q = (x)."""
    from ...declare.parameters import Parameters
    from ...declare.states import Vector
    from ...declare.symbols import t
    from ...declare.system import Equation, System
    from ...declare.terms import Term as _Term

    X = Vector("x", 1)
    x = X(t)[0]
    return Facts(System([Equation(X, [_Term(-x)])], parameters=Parameters()), {}, {}), x, sympy.Matrix([x])


def _result(name, status, detail, value=None, kind="bound") -> Result:
    return Result(kind, name, status, value, detail)


@dataclasses.dataclass(frozen=True)
class Dissipation:
    """**V(t) ≤ V(0)**: V̇ = −qᵀSq identically along the system (a polynomial identity) and S ⪰ 0.

    Parameters
    ----------
    V : expression in the states at t
    q : column
    S : square matrix (numbers)

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> Dissipation(x**2 / 2, q, sympy.eye(1)).decide(facts).status.value      # V̇ = −x²
    'exact'
    >>> Dissipation(x**2 / 2, q, 2 * sympy.eye(1)).decide(facts).status.value  # the claimed −2x² is refuted
    'failed'
    """

    V: object
    q: object
    S: object
    name: str = "V̇ = −qᵀSq ≤ 0"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        Vdot = facts.rate(self.V)
        ident = compare_polynomials(self.name, [("V̇ derived", Vdot)], [("−qᵀSq", facts.plain(-_quad(self.q, self.S)))],
                                    reference="V̇ along the system")
        psd = matrix_positive_definite(sympy.Matrix(self.S).xreplace(facts.sub), name="S", semidefinite=True)
        status = _weakest([ident.status, psd.status])
        facts.nonincreasing[facts.plain(self.V)] = status
        facts.dissipation = (status, facts.plain(as_column(self.q)), sympy.Matrix(self.S).xreplace(facts.sub), psd)
        detail = (f"V̇ along the system equals −qᵀSq: {ident.detail}; S ⪰ 0: {psd.detail}; hence V(t) ≤ V(0) "
                  f"on every solution" if status.is_proof else
                  f"identity: {ident.status} ({ident.detail}); S ⪰ 0: {psd.status} ({psd.detail})")
        return _result(self.name, status, detail, ident.value)


@dataclasses.dataclass(frozen=True)
class LevelSet:
    """**‖z(t)‖² ≤ 2V(0)/λ_min(Q)**: V = ½zᵀQz identically, Q ≻ 0, and V nonincreasing (a :class:`Dissipation`).

    Parameters
    ----------
    V : expression in the states at t
    signals : sequence of (name, column)
        The blocks of z; each becomes a bounded signal.
    Q : matrix (numbers)

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> _ = Dissipation(x**2 / 2, q, sympy.eye(1)).decide(facts)
    >>> LevelSet(x**2 / 2, (("x", q),), sympy.eye(1)).decide(facts).status.value
    'exact'
    """

    V: object
    signals: Sequence
    Q: object

    @property
    def name(self) -> str:
        return f"V = ½zᵀQz, Q ≻ 0: {', '.join(n for n, _ in self.signals)} bounded"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        z = sympy.Matrix.vstack(*[as_column(x) for _, x in self.signals])
        Q = sympy.Matrix(self.Q).xreplace(facts.sub)
        ident = compare_polynomials(self.name, [("V", facts.plain(self.V))], [("½zᵀQz", facts.plain(_quad(z, Q) / 2))],
                                    reference="V as a quadratic form in z")
        pd = matrix_positive_definite(Q, name="Q")
        down = facts.nonincreasing.get(facts.plain(self.V))
        rest = Status.UNDECIDED if down is None else down
        status = _weakest([ident.status, pd.status, rest])
        why = ("V nonincreasing: no earlier link proves it" if down is None else f"V nonincreasing ({down})")
        for n, x in self.signals:
            facts.signals[n] = facts.plain(as_column(x))
            facts.bounded[n] = (status, "a block of z in the level set of V")
        detail = (f"V = ½zᵀQz identically ({ident.status}), Q ≻ 0 ({pd.status}: {pd.detail}), {why}: "
                  f"λ_min(Q)‖z(t)‖² ≤ 2V(t) ≤ 2V(0), so {', '.join(n for n, _ in self.signals)} stay bounded"
                  + ("" if ident.status.is_proof else f"; the identity: {ident.detail}"))
        return _result(self.name, status, detail)


@dataclasses.dataclass(frozen=True)
class Conserved:
    """**‖x(t)‖ = ‖x(0)‖**: d/dt‖x‖² = 0 identically along the system.

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> Conserved("x", q).decide(facts).status.value                        # ẋ = −x shrinks ‖x‖
    'failed'
    """

    signal: str
    x: object

    @property
    def name(self) -> str:
        return f"‖{self.signal}‖ conserved"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        x = as_column(self.x)
        res = compare_polynomials(self.name, [("d/dt‖x‖²", facts.rate(_quad(x, sympy.eye(len(x)))))], [("0", 0)],
                                  reference=f"d/dt‖{self.signal}‖²")
        facts.signals[self.signal] = facts.plain(x)
        facts.bounded[self.signal] = (res.status, "its norm is conserved")
        return _result(self.name, res.status, f"d/dt‖{self.signal}‖² = 0 along the system: {res.detail}")


@dataclasses.dataclass(frozen=True)
class BoundedStates:
    """**Every state is bounded**: the states solved (linearly) from the bounded signals' definitions are
    polynomials in those signals and in the bounded reference functions.

    A state that is itself a bounded signal's component is bounded; the others must be determined
    uniquely by the equations ζ = z(states) of the bounded signals z (ζ fresh symbols).

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> BoundedStates().decide(facts).status.value                           # nothing bounds x yet
    'undecided'
    >>> _ = [link.decide(facts) for link in (Dissipation(x**2 / 2, q, sympy.eye(1)),
    ...                                      LevelSet(x**2 / 2, (("x", q),), sympy.eye(1)))]
    >>> BoundedStates().decide(facts).status.value
    'exact'
    """

    name: str = "every state bounded"

    def decide(self, facts: Facts) -> Result:
        known, statuses = {}, []
        eqs, fresh = [], []
        for n, (st, _) in facts.bounded.items():
            x = facts.signals[n]
            statuses.append(st)
            for k, comp in enumerate(x):
                if comp in facts.states:
                    known[comp] = n
                else:
                    zeta = sympy.Symbol(f"zeta_{n}_{k}", real=True)
                    fresh.append(zeta)
                    eqs.append(zeta - comp)
        unknown = [s for s in facts.states if s not in known]
        solution = {}
        if unknown:
            sol = sympy.linsolve(eqs, unknown) if eqs else sympy.EmptySet
            sols = list(sol) if isinstance(sol, sympy.FiniteSet) else []
            if len(sols) != 1:
                return self._fail(facts, f"the bounded signals' definitions do not determine the states "
                                         f"{', '.join(map(str, unknown))} (not linear in them, or not uniquely)")
            solution = dict(zip(unknown, sols[0]))
        whys = []
        for s, expr in solution.items():
            expr = sympy.expand(expr)
            if expr.free_symbols & set(unknown):
                return self._fail(facts, f"{s} is not determined by the bounded signals")
            gens = sorted(expr.free_symbols, key=str)
            try:
                poly = sympy.Poly(expr, *gens) if gens else None
            except sympy.PolynomialError:
                return self._fail(facts, f"{s} = {expr} is not a polynomial in the bounded signals")
            if poly is not None and any(c.free_symbols for c in poly.coeffs()):
                return self._fail(facts, f"{s} = {expr}: coefficients that are not numbers")
            for g in gens:
                if g in fresh or g in known:
                    continue
                st, why = facts.reference_bounded(g)
                statuses.append(st)
                if st is not Status.EXACT:
                    whys.append(why)
        status = _weakest(statuses) if statuses else Status.UNDECIDED
        facts.states_bounded = status
        used = ", ".join(f"{n} ({st})" for n, (st, _) in facts.bounded.items())
        detail = (f"{len(facts.states)} state components: {len(known)} are components of bounded signals, the other "
                  f"{len(solution)} solved exactly from the definitions of {used} as polynomials in them and in the "
                  f"reference signals" + (f"; not bounded: {'; '.join(whys)}" if whys else ""))
        return _result(self.name, status, detail)

    def _fail(self, facts, why) -> Result:
        facts.states_bounded = Status.UNDECIDED
        return _result(self.name, Status.UNDECIDED, why)


@dataclasses.dataclass(frozen=True)
class SquareIntegrable:
    """**∫_0^∞ ‖f‖² < ∞**: fᵀKf + Σ rᵀSr = Σ gᵀAg − dB/dt identically along the system, with K ≻ 0,
    S ⪰ 0, A ⪰ 0, every g ∈ L2 (earlier links) and B bounded along solutions (a polynomial in the
    bounded states).  Integrating: λ_min(K)∫_0^T‖f‖² ≤ Σ λ_max(A)∫_0^T‖g‖² + B(0) − B(T).

    Parameters
    ----------
    signal : str
    f : column
    K : matrix
    storage : expression B (e.g. V itself: fᵀKf = −V̇)
    dominated : sequence of (name, column g, matrix A)
    remainder : sequence of (column r, matrix S)

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> SquareIntegrable("x", q, sympy.eye(1), storage=x**2 / 2).decide(facts).status.value  # x² = −d/dt(x²/2)
    'undecided'
    >>> facts.states_bounded = Status.EXACT        # (what BoundedStates would establish)
    >>> SquareIntegrable("x", q, sympy.eye(1), storage=x**2 / 2).decide(facts).status.value
    'exact'
    """

    signal: str
    f: object
    K: object
    storage: object = 0
    dominated: Sequence = ()
    remainder: Sequence = ()

    @property
    def name(self) -> str:
        return f"{self.signal} ∈ L2"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        f = as_column(self.f)
        left = [("fᵀKf", facts.plain(_quad(f, sympy.Matrix(self.K).xreplace(facts.sub))))]
        left += [(f"r{k + 1}ᵀS{k + 1}r{k + 1}", facts.plain(_quad(r, sympy.Matrix(S).xreplace(facts.sub))))
                 for k, (r, S) in enumerate(self.remainder)]
        right = [(f"{n}ᵀA{n}", facts.plain(_quad(g, sympy.Matrix(A).xreplace(facts.sub)))) for n, g, A in self.dominated]
        right.append(("−dB/dt", -facts.rate(self.storage)))
        ident = compare_polynomials(self.name, left, right, reference="fᵀKf + ΣrᵀSr = ΣgᵀAg − dB/dt")
        parts = [(ident.status, f"the identity ({ident.status})")]
        pd = matrix_positive_definite(sympy.Matrix(self.K).xreplace(facts.sub), name="K")
        parts.append((pd.status, f"K ≻ 0 ({pd.status})"))
        for k, (_, S) in enumerate(self.remainder):
            r = matrix_positive_definite(sympy.Matrix(S).xreplace(facts.sub), name=f"S{k + 1}", semidefinite=True)
            parts.append((r.status, f"S{k + 1} ⪰ 0 ({r.status})"))
        for n, _, A in self.dominated:
            r = matrix_positive_definite(sympy.Matrix(A).xreplace(facts.sub), name=f"A_{n}", semidefinite=True)
            parts.append((r.status, f"A_{n} ⪰ 0 ({r.status})"))
            parts.append(facts.needs(facts.square_integrable, n, "∈ L2"))
        parts.append(facts.polynomial_in_states(facts.plain(self.storage), "B"))
        status = _weakest(st for st, _ in parts)
        facts.signals[self.signal] = facts.plain(f)
        facts.signals_t[self.signal] = f
        facts.square_integrable[self.signal] = (status, "")
        detail = "; ".join(why for _, why in parts)
        if not ident.status.is_proof:
            detail += f"; {ident.detail}"
        elif status.is_proof:
            detail += f": ∫_0^∞ ‖{self.signal}‖² < ∞"
        return _result(self.name, status, detail, ident.value)


@dataclasses.dataclass(frozen=True)
class Barbalat:
    """**f → 0** (Barbalat's lemma): f ∈ L2 (an earlier :class:`SquareIntegrable`) and every component
    of f and of ḟ (derived along the system) a polynomial in the bounded states and references, so
    d/dt‖f‖² = 2fᵀḟ is bounded, ‖f‖² uniformly continuous and integrable, hence ‖f(t)‖ → 0.

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> Barbalat("x").decide(facts).status.value        # no earlier link shows x ∈ L2
    'undecided'
    """

    signal: str

    @property
    def name(self) -> str:
        return f"{self.signal} → 0 (Barbalat)"

    def decide(self, facts: Facts) -> Result:
        parts = [facts.needs(facts.square_integrable, self.signal, "∈ L2")]
        f = facts.signals.get(self.signal)
        if f is None or self.signal not in facts.signals_t:
            facts.converges[self.signal] = (Status.UNDECIDED, f)
            return _result(self.name, Status.UNDECIDED, f"rests on “{self.signal} ∈ L2”, which no earlier link "
                                                       f"established")
        for k, (comp, at_t) in enumerate(zip(f, facts.signals_t[self.signal])):
            parts.append(facts.polynomial_in_states(comp, f"{self.signal}_{k + 1}"))
            dot = facts.rate(at_t)
            parts.append(facts.polynomial_in_states(dot, f"d/dt {self.signal}_{k + 1}"))
        status = _weakest(st for st, _ in parts)
        facts.converges[self.signal] = (status, f)
        bad = [why for st, why in parts if not st.is_proof]
        detail = ("; ".join(bad) if bad else f"{self.signal} ∈ L2, {self.signal} and d/dt {self.signal} are polynomials "
                  f"in the bounded states and references: d/dt‖{self.signal}‖² is bounded, so ‖{self.signal}‖² is "
                  f"uniformly continuous and integrable: {self.signal}(t) → 0")
        return _result(self.name, status, detail)


def decide_all(links: Sequence, facts: Facts) -> list:
    """Every link in order (each may use what the earlier ones established)."""
    if not links:
        raise InputError("a signal argument needs at least one link")
    out = []
    for link in links:
        res = link.decide(facts)
        facts.links[res.name] = res.status
        out.append(res)
    return out
