"""Limits and regions of a signal argument: linear combinations and finite zero sets of converging signals,
bounded outputs, and the comparison lemma (with its exact sign test :func:`negative_on`).

Split from :mod:`lkverify.certify.steps.signals`, which re-exports every name.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import sympy

from ...report.results import Result
from ...status import Status
from ...declare.vectors import as_column
from .signals import Facts, _demo, _result, _weakest  # noqa: F401 - _demo: the doctests

__all__ = ["BoundedSignal", "Chetaev", "Comparison", "Decided", "FiniteLimit", "Follows", "LaSalle", "LinearLimit",
           "negative_on"]


@dataclasses.dataclass(frozen=True)
class LinearLimit:
    """**g → 0**: g = Σ cⱼfⱼ identically (constants cⱼ) with every fⱼ → 0 by an earlier link.

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> LinearLimit("2x", 2 * q, {"x": 2}).decide(facts).status.value   # rests on x → 0, not established
    'undecided'
    """

    signal: str
    g: object
    combination: Mapping

    @property
    def name(self) -> str:
        return f"{self.signal} → 0"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        g = facts.plain(as_column(self.g))
        parts, total = [], sympy.zeros(len(g), 1)
        for n, c in self.combination.items():
            st, why = facts.needs(facts.converges, n, "→ 0")
            parts.append((st, why))
            if n in facts.converges:
                total += sympy.sympify(c).xreplace(facts.sub) * facts.converges[n][1]
        if any(n not in facts.converges for n in self.combination):
            status = Status.UNDECIDED
            detail = "; ".join(why for st, why in parts if st is Status.UNDECIDED)
        else:
            idents = [compare_polynomials(self.name, [("g", g[i])], [("Σcf", total[i])], reference=f"{self.signal}_{i + 1}")
                      for i in range(len(g))]
            same = _weakest(r.status for r in idents)
            combo = " + ".join(f"({sympy.sympify(c).xreplace(facts.sub)})·{n}" for n, c in self.combination.items())
            parts.append((same, f"{self.signal} = {combo} identically ({same})"))
            status = _weakest(st for st, _ in parts)
            detail = "; ".join(why for _, why in parts) + (f": {self.signal}(t) → 0" if status.is_proof else "")
        facts.converges[self.signal] = (status, g)
        return _result(self.name, status, detail)


@dataclasses.dataclass(frozen=True)
class BoundedSignal:
    """**g bounded**: every component a polynomial in the bounded states and references.

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> BoundedSignal("x²", q.applyfunc(lambda c: c**2)).decide(facts).detail
    'x²_1 depends on the states, and no link has bounded them'
    """

    signal: str
    g: object

    @property
    def name(self) -> str:
        return f"{self.signal} bounded"

    def decide(self, facts: Facts) -> Result:
        g = facts.plain(as_column(self.g))
        parts = [facts.polynomial_in_states(c, f"{self.signal}_{k + 1}") for k, c in enumerate(g)]
        status = _weakest(st for st, _ in parts)
        facts.signals[self.signal] = g
        facts.bounded[self.signal] = (status, "a polynomial in bounded signals")
        bad = [why for st, why in parts if not st.is_proof]
        return _result(self.name, status, "; ".join(bad) if bad else
                       f"{self.signal} is a polynomial in the bounded states and references")


def negative_on(phi, r, lo, hi) -> tuple:
    """``(status, why)``: φ(r) < 0 for every r in the open interval (lo, hi), decided exactly.

    φ is a polynomial in r with rational coefficients, possibly with Max/Min of such polynomials;
    the interval is cut at every real root of the pieces and of their pairwise differences (exact
    root isolation), φ is one polynomial on each sub-interval, and it must have no root in its
    closure (except at lo) and be negative at a rational interior point.  A failure names an exact
    point where φ ≥ 0.

    >>> r = sympy.Symbol("r", nonnegative=True)
    >>> negative_on(-r + sympy.Max(0, r**2 - sympy.Rational(1, 4)), r, 0, 1)[0].value
    'exact'
    >>> negative_on(-r + 3 * sympy.Max(0, r - sympy.Rational(1, 4)), r, 0, 1)[0].value   # φ(3/8) = 0
    'failed'
    """
    phi = sympy.sympify(phi)
    lo, hi = sympy.sympify(lo), sympy.sympify(hi)
    pieces = [a for m in phi.atoms(sympy.Max, sympy.Min) for a in m.args]
    cuts = set()
    try:
        for p in pieces:
            for q in pieces:
                d = sympy.expand(p - q)
                if d != 0 and d.has(r):
                    cuts |= set(sympy.Poly(d, r).real_roots())
            if sympy.expand(p).has(r):
                cuts |= set(sympy.Poly(p, r).real_roots())
    except sympy.PolynomialError:
        return Status.UNDECIDED, f"φ = {phi} is not built from polynomials in {r}"
    cuts = sorted({c for c in cuts if (c - lo).is_positive and (hi - c).is_positive}, key=lambda c: sympy.N(c, 30))
    ends = [lo, *cuts, hi]
    for a, b in zip(ends, ends[1:]):
        mid = sympy.nsimplify(sympy.Rational(sympy.N((a + b) / 2, 30)))
        if not ((mid - a).is_positive and (b - mid).is_positive):
            return Status.UNDECIDED, f"no rational point found in ({a}, {b})"
        piece = phi.replace(lambda x: isinstance(x, (sympy.Max, sympy.Min)),
                            lambda x: (max if isinstance(x, sympy.Max) else min)(x.args, key=lambda y: y.subs(r, mid)))
        try:
            poly = sympy.Poly(sympy.expand(piece), r)
        except sympy.PolynomialError:
            return Status.UNDECIDED, f"φ on ({a}, {b}) is not a polynomial in {r}"
        value = poly.eval(mid)
        if value >= 0:
            return Status.FAILED, f"φ({mid}) = {value} ≥ 0 with {mid} in ({lo}, {hi}) (exact)"
        closed_hi = b is not hi
        for root in poly.real_roots():
            if (root - a).is_positive and ((b - root).is_positive or (closed_hi and (b - root).is_zero)):
                return Status.FAILED, f"φ({root}) = 0 with {root} ≈ {float(root):.6g} in ({lo}, {hi}) (exact root)"
    shown = hi if hi.is_Rational else f"{float(hi):.6g} (exact: {hi})"
    return Status.EXACT, f"φ < 0 on ({lo}, {shown}): {len(ends) - 1} pieces between the exact roots, no root inside"


@dataclasses.dataclass(frozen=True)
class Comparison:
    """**{‖V‖ < ρ} positively invariant and ‖V‖ → 0** (the comparison lemma).

    From D⁺r ≤ φ(r), r = ‖V(t)‖ (the comparison system, a link proved before and named by
    ``rests_on``), φ continuous, φ(0) = 0 and φ < 0 on (0, ρ): r(t) ≤ the solution of ρ̇ = φ(ρ)
    from r(t0), which decreases to 0.

    Parameters
    ----------
    phi : expression in ``r``
    r : Symbol
    rho : the radius (an exact number, e.g. an algebraic root)
    rests_on : sequence of (name, Status)
        The links the comparison system D⁺r ≤ φ(r) is proved by.

    Examples
    --------
    >>> r = sympy.Symbol("r", nonnegative=True)
    >>> link = Comparison(-r + r**2, r, 1, rests_on=(("D⁺r ≤ −r + r²", Status.EXACT),))
    >>> link.decide().status.value, Comparison(-r + r**2, r, 2, link.rests_on).decide().status.value
    ('exact', 'failed')
    """

    phi: object
    r: object
    rho: object
    rests_on: Sequence = ()
    name: str = "comparison lemma: ‖V‖ < ρ invariant, ‖V‖ → 0"

    def decide(self, facts: Facts | None = None) -> Result:
        phi = sympy.sympify(self.phi)
        zero = sympy.simplify(phi.subs(self.r, 0))
        parts = [(st, f"{n} ({st})") for n, st in self.rests_on]
        if not self.rests_on:
            parts.append((Status.UNDECIDED, "no link proves the comparison system D⁺‖V‖ ≤ φ(‖V‖)"))
        parts.append((Status.EXACT if zero == 0 else Status.FAILED, f"φ(0) = {zero}"))
        st, why = negative_on(phi, self.r, 0, self.rho)
        parts.append((st, why))
        status = _weakest(s for s, _ in parts)
        detail = "; ".join(w for _, w in parts)
        if status.is_proof:
            detail += f": every solution with ‖V(t0)‖ < ρ = {float(self.rho):.6g} keeps ‖V‖ < ρ and ‖V(t)‖ → 0"
        if facts is not None:
            facts.converges["‖V‖"] = (status, None)
        return _result(self.name, status, detail, {"rho": float(self.rho), "exact": str(self.rho)}, kind="region")


@dataclasses.dataclass(frozen=True)
class FiniteLimit:
    """**x(t) → one of finitely many points**: g(x) → 0 by an earlier link, x bounded, the constraints
    c(x) = 0 invariant along the system (each ċ in the ideal of the constraints, so c ≡ 0 from c(0) = 0),
    and the set {g = 0, c = 0} finite (a zero-dimensional Gröbner basis, its points solved exactly).

    The ω-limit set of the bounded solution is nonempty and connected and, as g → 0, lies in that
    finite set: it is one point.

    Parameters
    ----------
    signal : str
        The name of x in the report.
    g : str
        The converging signal (an earlier :class:`Barbalat` or :class:`LinearLimit`), a polynomial in x.
    x : column
        The state components (at t) the limit is about.
    constraints : sequence of expressions
        Polynomials in x vanishing on the state manifold (unit vectors, orthogonality).

    Examples
    --------
    >>> facts, x, q = _demo()                    # ẋ = −x, nothing established yet
    >>> FiniteLimit("x", "x", q).decide(facts).status.value       # rests on x → 0
    'undecided'
    """

    signal: str
    g: str
    x: object
    constraints: Sequence = ()

    @property
    def name(self) -> str:
        return f"{self.signal} → a point of {{{self.g} = 0}} (finite)"

    def decide(self, facts: Facts) -> Result:
        parts = [facts.needs(facts.converges, self.g, "→ 0")]
        xs = list(facts.plain(as_column(self.x)))
        cons = [sympy.expand(facts.plain(c)) for c in self.constraints]
        if self.g not in facts.converges or facts.converges[self.g][1] is None:
            return _result(self.name, Status.UNDECIDED, parts[0][1])
        g = [sympy.expand(c) for c in facts.converges[self.g][1]]
        if any(c.free_symbols - set(xs) for c in g + cons):
            return _result(self.name, Status.UNDECIDED, f"{self.g} or a constraint depends on more than {self.signal}")
        parts.append((facts.states_bounded or Status.UNDECIDED, f"the states bounded ({facts.states_bounded})"))
        if cons:
            rates = [sympy.expand(facts.rate(c_t)) for c_t in self.constraints]
            others = sorted(set().union(*(r.free_symbols for r in rates)) - set(xs), key=str)
            basis = sympy.groebner(cons, *xs, *others, order="grevlex")  # the ideal of c in the larger ring
            stuck = 0
            for c, rate in zip(cons, rates):
                _, rem = basis.reduce(rate)
                if rem != 0:
                    stuck += 1
                    parts.append((Status.UNDECIDED, f"the constraint {c} = 0 is not shown invariant (its rate "
                                                    f"leaves the remainder {rem} modulo the constraints)"))
            if not stuck:
                parts.append((Status.EXACT, f"{len(cons)} constraints invariant (each rate in their ideal): for "
                                            f"initial data on them"))
        full = sympy.groebner([c for c in g + cons if c != 0], *xs, order="lex")
        if not full.is_zero_dimensional:
            parts.append((Status.UNDECIDED, f"{{{self.g} = 0}} on the constraints is not finite"))
            points = []
        else:
            st, points, why = _real_points(full, xs)
            parts.append((st, f"{{{self.g} = 0}} on the constraints: {why}"))
        status = _weakest(st for st, _ in parts)
        shown = "; ".join("(" + ", ".join(map(str, p)) + ")" for p in points[:8])
        detail = "; ".join(w for _, w in parts) + (
            f": the ω-limit set of {self.signal} is connected and lies in this finite set, so {self.signal}(t) "
            f"converges to one of {shown}" if status.is_proof else "")
        return _result(self.name, status, detail, {"points": [[str(v) for v in p] for p in points]})


@dataclasses.dataclass(frozen=True)
class Follows:
    """A conclusion licensed by named steps proved before: ``licence`` states the argument, and the link
    holds exactly as well as the weakest of ``rests_on`` ((name, Status) pairs, e.g. |σ| ≤ ‖V‖ with ‖V‖ → 0;
    a pair (name, None) takes the status an earlier link gave the convergence of ``name``, e.g. ("V", None)
    after a :class:`Comparison`; a pair (name, callable) the status ``callable(facts)`` gives when this link is
    decided, e.g. ``lambda facts: facts.link_status("v ∈ L2")``, the status an earlier link of the chain got).

    >>> Follows("σ → 0", (("|σ| ≤ ‖V‖", Status.EXACT), ("‖V‖ → 0", Status.FAILED)), "squeezed").decide().status.value
    'failed'
    """

    name: str
    rests_on: Sequence
    licence: str

    def decide(self, facts: Facts | None = None) -> Result:
        if not self.rests_on:
            return _result(self.name, Status.UNDECIDED, "rests on no proved step")
        def status_of(n, st):
            if callable(st):
                return st(facts) if facts is not None else Status.UNDECIDED
            if st is not None:
                return st
            return facts.converges.get(n, (Status.UNDECIDED,))[0] if facts is not None else Status.UNDECIDED

        pairs = [(n, status_of(n, st)) for n, st in self.rests_on]
        status = _weakest(st for _, st in pairs)
        used = ", ".join(f"{n} ({st})" for n, st in pairs)
        return _result(self.name, status, f"{self.licence}; rests on {used}")


@dataclasses.dataclass(frozen=True)
class Decided:
    """A link decided by a computation of the proof (``compute(facts) → Result``: an exact witness, a
    certified constant); the chain takes the Result's status as it is.

    >>> Decided("β1 > 0", lambda facts: Result("constant", "β1 > 0", Status.CERTIFIED, 0.5, "certified")).decide().status.value
    'certified'
    """

    name: str
    compute: object

    def decide(self, facts: Facts | None = None) -> Result:
        res = self.compute(facts)
        return Result(res.kind, self.name, res.status, res.value, res.detail)


@dataclasses.dataclass(frozen=True)
class LaSalle:
    """**x(t) → a point of the largest invariant set in {V̇ = 0}** (LaSalle), for an autonomous polynomial ODE.

    Side conditions, each decided: the system is autonomous (no t, no reference signal) with polynomial
    right-hand sides; V̇ = −qᵀSq ≤ 0 (an earlier :class:`~.signals.Dissipation`); the solutions are
    bounded (an earlier :class:`~.signals.BoundedStates`).  A solution that stays in {V̇ = 0} has every
    Lie derivative of the generators of {V̇ = 0} vanish ({q = 0} when S ≻ 0, {qᵀSq = 0} otherwise),
    so the largest invariant set lies in the variety of the ideal I = ⟨g, L_f g, L_f²g, …⟩, computed by
    Gröbner bases until the chain stops (every L_f g reduces to 0 modulo I).  When that variety is finite
    its points are solved exactly, and the ω-limit set (connected, in it) is one of them; otherwise
    ``undecided``, naming the ideal.

    Examples
    --------
    ẋ = y, ẏ = −x − y, V = (x² + y²)/2, V̇ = −y²: {y = 0} holds no solution but the origin.

    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import BoundedStates, Dissipation, LevelSet
    >>> X, Y = Vector("x", 1), Vector("y", 1); x, y = X(t)[0], Y(t)[0]
    >>> sys_ = System([Equation(X, [Term(y)]), Equation(Y, [Term(-x - y)])], parameters=Parameters())
    >>> facts = Facts(sys_, {}, {})
    >>> V = (x**2 + y**2) / 2
    >>> _ = [link.decide(facts) for link in (Dissipation(V, sympy.Matrix([y]), sympy.eye(1)),
    ...      LevelSet(V, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), sympy.eye(2)), BoundedStates())]
    >>> res = LaSalle().decide(facts)
    >>> res.status.value, res.value["points"]
    ('exact', [['0', '0']])
    """

    max_rounds: int = 12
    name: str = "LaSalle: the largest invariant set in {V̇ = 0}"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import plain

        if facts.dissipation is None:
            return _result(self.name, Status.UNDECIDED, "rests on V̇ = −qᵀSq ≤ 0, which no earlier link established")
        d_status, q, S, psd = facts.dissipation
        xs = list(facts.states)
        rates = {}
        for state in facts.system.states:
            rhs = facts.system.rhs(state)
            for i, f in enumerate(state.functions):
                rates[sympy.Symbol(f.__name__, real=True)] = sympy.expand(plain(
                    rhs[i].xreplace(facts.sub) if facts.sub else rhs[i]))
        others = set().union(*(r.free_symbols for r in rates.values())) - set(xs)
        from ...declare.symbols import t as time

        if others or any(r.has(time) for r in rates.values()):
            return _result(self.name, Status.UNDECIDED, f"LaSalle needs an autonomous system; the right-hand sides "
                                                        f"contain {', '.join(sorted(map(str, others))) or 't'}")
        try:
            for r in rates.values():
                sympy.Poly(r, *xs)
        except sympy.PolynomialError:
            return _result(self.name, Status.UNDECIDED, "the right-hand sides are not polynomials in the states")
        from ..matrices import matrix_positive_definite

        pd = matrix_positive_definite(S, name="S")
        gens = list(q) if pd.status.is_proof else [sympy.expand((q.T * S * q)[0, 0])]

        def lie(g):
            return sympy.expand(sum((sympy.diff(g, x) * rates[x] for x in xs), sympy.Integer(0)))

        ideal = [sympy.expand(g) for g in gens if sympy.expand(g) != 0]
        for _ in range(self.max_rounds):
            basis = sympy.groebner(ideal, *xs, order="grevlex") if ideal else None
            new = []
            for g in ideal:
                lg = lie(g)
                rem = basis.reduce(lg)[1] if basis is not None else lg
                if rem != 0:
                    new.append(rem)
            if not new:
                break
            ideal += new
        else:
            return _result(self.name, Status.UNDECIDED, f"the chain of Lie derivatives did not stop in "
                                                        f"{self.max_rounds} rounds")
        parts = [(d_status, f"V̇ = −qᵀSq ≤ 0 ({d_status})"),
                 (facts.states_bounded or Status.UNDECIDED, f"the states bounded ({facts.states_bounded})")]
        full = sympy.groebner(ideal, *xs, order="lex")
        if not full.is_zero_dimensional:
            parts.append((Status.UNDECIDED, f"the largest invariant set lies in {{{', '.join(map(str, full.exprs))} "
                                            f"= 0}}, not a finite set"))
            points = []
        else:
            st, points, why = _real_points(full, xs)
            parts.append((st, f"the ideal ⟨g, L_f g, …⟩ ({len(ideal)} generators) is zero-dimensional: {why}"))
        status = _weakest(st for st, _ in parts)
        shown = "; ".join("(" + ", ".join(map(str, p)) + ")" for p in points[:8])
        detail = "; ".join(w for _, w in parts) + (f": every solution converges to one of {shown}"
                                                   if status.is_proof else "")
        facts.converges["x"] = (status, None)
        return _result(self.name, status, detail, {"points": [[str(v) for v in p] for p in points]})


def _real_points(basis, xs) -> tuple:
    """``(status, points, why)``: every real point of a zero-dimensional Gröbner basis, solved exactly.

    ``undecided`` when SymPy does not solve the system, finds no real point (a bounded solution has a
    nonempty ω-limit set, so that would be a failure of the solver), or cannot decide whether a
    coordinate is real: a point is never dropped on a guess.
    """
    try:
        found = sympy.solve_poly_system(list(basis), *xs)
    except (NotImplementedError, sympy.PolynomialError) as exc:
        return Status.UNDECIDED, [], f"not solved ({exc})"
    if not found:
        return Status.UNDECIDED, [], "not solved (no solution returned)"
    flags = [[sympy.sympify(v).is_real for v in p] for p in found]
    if any(f is None for fl in flags for f in fl):
        return Status.UNDECIDED, [], "a coordinate's reality is not decided"
    real = [p for p, fl in zip(found, flags) if all(fl)]
    if not real:
        return Status.UNDECIDED, [], "no real point found"
    return Status.EXACT, real, f"{len(real)} real points (a zero-dimensional Gröbner basis, solved exactly)"


@dataclasses.dataclass(frozen=True)
class Chetaev:
    """**The equilibrium x* is unstable** (Chetaev's theorem): V(x*) = 0, V < 0 at points arbitrarily near
    x*, and V̇ < 0 wherever V < 0 near x* (the last from ``rate``, a (name, Status) pair of an earlier
    proof), so a solution started where V < 0 cannot stay near x*.

    The middle condition is decided here exactly: ``curve`` maps ε to states (rational functions of ε)
    with curve(0) = x*; V along it is a rational function of ε whose sign on (0, ε0) is decided by exact
    root isolation (:func:`negative_on` on numerator·sign(denominator)).

    Parameters
    ----------
    V : expression in plain state symbols
    point : mapping
        x*, plain symbol → exact value.
    curve : mapping
        Plain symbol → expression in ``eps`` equal to x* at ε = 0 (states absent keep x*'s value).
    eps : Symbol
    rate : (str, Status)
    eps0 : the end of the interval of ε (default 1)

    Examples
    --------
    >>> a, b, e = sympy.symbols("a b epsilon", real=True)
    >>> link = Chetaev(a**2 - b**2, {a: 0, b: 0}, {b: e}, e, ("V̇ < 0 where V < 0", Status.EXACT))
    >>> link.decide().status.value
    'exact'
    >>> Chetaev(a**2 + b**2, {a: 0, b: 0}, {b: e}, e, ("V̇ < 0 where V < 0", Status.EXACT)).decide().status.value
    'failed'
    """

    V: object
    point: Mapping
    curve: Mapping
    eps: object
    rate: tuple
    eps0: object = 1
    name: str = "Chetaev: the equilibrium is unstable"

    def decide(self, facts: Facts | None = None) -> Result:
        V = sympy.sympify(self.V)
        at = {k: sympy.sympify(v) for k, v in self.point.items()}
        parts = []
        v0 = sympy.simplify(V.xreplace(at))
        parts.append((Status.EXACT if v0 == 0 else Status.FAILED, f"V(x*) = {v0}"))
        starts = {k: sympy.simplify(sympy.sympify(c).subs(self.eps, 0) - at.get(k, 0)) for k, c in self.curve.items()}
        if any(d != 0 for d in starts.values()):
            return _result(self.name, Status.UNDECIDED, "the curve does not start at x*")
        along = sympy.cancel(sympy.together(V.xreplace({**at, **{k: sympy.sympify(c) for k, c in self.curve.items()}})))
        num, den = sympy.fraction(along)
        probe = sympy.Rational(sympy.sympify(self.eps0)) / 2
        sign = sympy.sign(den.subs(self.eps, probe))
        st, why = negative_on(sympy.expand(num * sign), self.eps, 0, self.eps0)
        if st is Status.EXACT:
            st_den, why_den = negative_on(sympy.expand(-sign * den), self.eps, 0, self.eps0)  # den keeps its sign
            st = st if st_den is Status.EXACT else Status.UNDECIDED
            why = why if st_den is Status.EXACT else f"the denominator of V along the curve may vanish: {why_den}"
        parts.append((st, f"V along the curve = {sympy.factor(along)}: {why.replace('φ', 'V')}"))
        name, rate_status = self.rate
        parts.append((rate_status, f"{name} ({rate_status})"))
        status = _weakest(s for s, _ in parts)
        return _result(self.name, status, "; ".join(w for _, w in parts)
                       + (": the equilibrium is unstable" if status.is_proof else ""), {"V_along": str(along)})
