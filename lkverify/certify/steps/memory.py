"""Memory integrals ∫_0^t κ(t − ξ)‖v(ξ)‖^p dξ as measures, and the rules a fading-memory proof needs.

The window measures of :mod:`.measures` cover [t − h, t].  A controller with a fading-memory
kernel (the PID of paper 000, (13)) integrates over the whole past, weighted by a kernel
κ(t − ξ) ≥ 0: ‖G(t − ξ)‖ or its tail ∫_{t−ξ}^∞‖G(ζ)‖dζ.  A :class:`MemoryMeasure` is such an
integral (kind ``"memory_integral"``); a :class:`~.measures.Region` bounding the sup of its
vector over the whole history bounds it by (∫_0^∞κ)·δ^p (:meth:`MemoryMeasure.bound_from`).

Rules (each with its side conditions decided exactly):

=============================  ===============================================================
:class:`MemoryWeight`          c·∫_0^t κ(t−ξ)Σ_i‖v_i(ξ)‖^p dξ = c·Σ_i M_i (the term is the measures)
:func:`memory_integral_of`     ‖∫_0^t w(t−ξ)F(ξ)dξ‖ ≤ κ_h·Σ_i M_i when |w| ≤ κ (the measures'
                               kernel) and ‖F(ξ)‖ ≤ κ_h Σ_i‖v_i(ξ)‖^k (homogeneity, certified)
:class:`KernelBound`           M[κ_s] ≤ c·M[κ_t] when κ_s(u) ≤ c·κ_t(u) for u ≥ 0 (Assumption 1
                               of paper 000 with c = σ: ∫_u^∞‖G‖ ≤ σ‖G(u)‖)
:class:`MemoryHolder`          ∫κ‖v‖^k ≤ (∫_0^∞κ)^{1−k/P}(∫κ‖v‖^P)^{k/P}, κ ≥ 0, k ≤ P (the
                               paper's c12 = (∫_0^∞‖G‖)^{1/(2ν+2)} for k = 2ν+1, P = 2ν+2)
:class:`Evaluated`             a rule applied after the constant integrals of the term
                               (∫_0^∞ g, free of t, ξ and states) are evaluated exactly
:class:`MemoryKrasovskii`      the conclusion: Krasovskii's sign conditions, and U(‖x_t‖)
                               finite: every memory measure has ∫_0^∞κ < ∞ (exact)
=============================  ===============================================================

Examples
--------
>>> import sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
>>> from lkverify.certify.steps.measures import Region, sup_norm
>>> from lkverify.certify.steps.rules import Context
>>> P = Parameters(); x = Vector("x", 2)
>>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
>>> J = memory_measure("J", x(xi), p=2, kernel=lambda u: sympy.exp(-2 * u))
>>> J.definition
Integral((x_1(xi)**2 + x_2(xi)**2)*exp(-2*t + 2*xi), (xi, 0, t))
>>> region = Region({sup_norm("m", x(xi), window=sympy.oo): sympy.Rational(1, 10)})
>>> region.bound_of(J)                          # (∫_0^∞ e^{−2u}du)·(1/10)²
1/200
>>> ctx = Context(sys_, P.resolve({}), {"J": J}, region)
>>> term = 3 * memory_integral(sympy.exp(-2 * (t - xi)) * norm_power(x(xi), 2))
>>> MemoryWeight(("J",)).apply(term, "upper", ctx).bound
3*J
>>> other = 3 * memory_integral(sympy.exp(-3 * (t - xi)) * norm_power(x(xi), 2))
>>> MemoryWeight(("J",)).apply(other, "upper", ctx).status.value      # another kernel is refused
'failed'
"""

from __future__ import annotations

import dataclasses

import sympy
from sympy.core.function import AppliedUndef

from ...declare.symbols import t, xi
from ...declare.vectors import as_column
from ...errors import InputError
from ...report.results import Result
from ...status import Status
from .chain import Krasovskii
from .measures import Measure
from .rewrites import _substitute
from .rules import Application, Condition, Norm, Rule, _cond, _integrand, nonnegative, pointwise_constant

__all__ = ["KIND", "Evaluated", "KernelBound", "MemoryHolder", "MemoryKrasovskii", "MemoryMeasure", "MemoryWeight",
           "evaluate_constant_integrals", "memory_integral_of", "memory_measure"]

KIND = "memory_integral"
U = sympy.Symbol("u", positive=True)  # the kernel's argument u = t − ξ (> 0 but on a null set)


def _lambda(kernel):
    if isinstance(kernel, sympy.Lambda):
        return sympy.Lambda(U, kernel(U))
    if callable(kernel):
        return sympy.Lambda(U, sympy.sympify(kernel(U)))
    raise InputError(f"kernel: expected a callable u ↦ κ(u) or a sympy Lambda, got {type(kernel).__name__}")


_DONE: dict = {}  # a constant integral → its value: SymPy's integrate is slow and its result exact, so once per process


def _doit(node):
    if node not in _DONE:
        _DONE[node] = node.doit()
    return _DONE[node]


def evaluate_constant_integrals(expr):
    """``expr`` with every integral free of t, ξ and states evaluated exactly (``doit``), innermost first.

    >>> from lkverify import zeta
    >>> evaluate_constant_integrals(1 + sympy.Integral(sympy.exp(-2 * zeta), (zeta, 0, sympy.oo)))
    3/2
    """
    e = sympy.sympify(expr)
    for _ in range(8):  # innermost first; an integral SymPy leaves unevaluated stays
        inner = {a for a in e.atoms(sympy.Integral) if not (a.free_symbols & {t, xi}) and not a.atoms(AppliedUndef)
                 and not a.function.has(sympy.Integral)}
        done = {a: _doit(a) for a in inner}
        done = {a: v for a, v in done.items() if v != a and not v.has(a)}
        if not done:
            return e
        e = e.xreplace(done)
    return e


def kernel_integral(kernel, sub=None):
    """∫_0^∞ κ(u)du exactly (None when it diverges or SymPy leaves it unevaluated)."""
    from ...declare.parameters import apply_substitution

    k = kernel(U) if sub is None else apply_substitution(kernel(U), sub)
    val = evaluate_constant_integrals(sympy.Integral(evaluate_constant_integrals(k), (U, 0, sympy.oo)))
    val = sympy.simplify(val.doit()) if isinstance(val, sympy.Integral) else sympy.simplify(val)
    if val.has(sympy.Integral) or not val.is_number or not val.is_finite:
        return None
    return val


@dataclasses.dataclass(frozen=True)
class MemoryMeasure(Measure):
    """∫_0^t κ(t − ξ)‖v(ξ)‖^p dξ, κ ≥ 0 on [0, ∞) (build it with :func:`memory_measure`).

    ``window`` is ∞: the measure reads the whole history, as the region's sup must.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Vector, xi
    >>> from lkverify.certify.steps.measures import Region, sup_norm
    >>> x = Vector("x", 1)
    >>> Q = memory_measure("Q", x(xi), p=2, kernel=lambda u: sympy.exp(-u))
    >>> Q.window, Region({sup_norm("m", x(xi), window=sympy.oo): 3}).bound_of(Q)     # (∫e^{−u})·3²
    (oo, 9)
    >>> Region({sup_norm("m", x(xi), window=1): 3}).bound_of(Q) is None               # a window is not the history
    True
    """

    kernel: object = None

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise InputError(f"measure name: expected an identifier such as 'J', got {self.name!r}")
        object.__setattr__(self, "kind", KIND)
        vec = as_column(self.vector)
        object.__setattr__(self, "vector", sympy.ImmutableMatrix(vec))
        times = {a.args[0] for a in vec.atoms(AppliedUndef)}
        if times - {xi}:
            raise InputError(f"measure {self.name}: the vector must be written at xi, got "
                             f"{sorted(map(str, times - {xi}))[0]}")
        p = sympy.sympify(self.power)
        if not (p.is_positive or p.free_symbols):
            raise InputError(f"measure {self.name}: power: expected a positive number, got {self.power!r}")
        object.__setattr__(self, "power", p)
        object.__setattr__(self, "kernel", _lambda(self.kernel))
        object.__setattr__(self, "window", sympy.oo)
        if not self.text:
            object.__setattr__(self, "text", self.name)

    @property
    def definition(self):
        return sympy.Integral(self.kernel(t - xi) * self.pointwise() ** self.power, (xi, 0, t))

    def bound_from(self, region, sub=None):
        """(∫_0^∞κ)·b^p with b the region's bound on the sup of the vector over the whole history (or None)."""
        from ...declare.parameters import apply_substitution

        sub = dict(sub or {})
        for m, b in region.bounds.items():
            if m.kind == "sup" and m.vector == self.vector and sympy.sympify(m.window) == sympy.oo:
                kint = kernel_integral(self.kernel, sub)
                if kint is None:
                    return None
                return kint * sympy.sympify(b).xreplace(sub) ** apply_substitution(self.power, sub)
        return None


def memory_measure(name: str, vector, *, p, kernel, text: str = "") -> MemoryMeasure:
    """∫_0^t κ(t − ξ)‖vector(ξ)‖^p dξ with κ = ``kernel`` (a callable u ↦ κ(u) or a Lambda).

    >>> from lkverify import Vector, xi
    >>> memory_measure("Q", Vector("x", 1)(xi), p=3, kernel=lambda u: 1 / (1 + u) ** 3).kind
    'memory_integral'
    """
    return MemoryMeasure(name, KIND, vector, power=p, text=text or name, kernel=kernel)


def _memory(ctx, name) -> MemoryMeasure:
    m = ctx.measure(name)
    if not isinstance(m, MemoryMeasure):
        raise InputError(f"measure {name}: expected a memory measure (memory_measure), got a {m.kind}")
    return m


def _kernel_at(m: MemoryMeasure, ctx):
    return evaluate_constant_integrals(ctx.at(m.kernel(U)))


def _outer_memory_integral(expr):
    """(c, integrand) with expr = c·∫_0^t integrand dξ, c free of t, ξ and states; None otherwise."""
    nodes = [a for a in sympy.sympify(expr).atoms(sympy.Integral) if a.limits == ((xi, 0, t),)]
    if len(nodes) != 1:
        return None
    (node,) = nodes
    c = sympy.simplify(expr / node)
    if c.free_symbols & {t, xi} or c.atoms(AppliedUndef) or c.has(sympy.Integral):
        return None
    return c, node.function


@dataclasses.dataclass(frozen=True)
class MemoryWeight(Rule):
    """c·∫_0^t κ(t−ξ)Σ_i‖v_i(ξ)‖^p dξ = c·Σ_i M_i for memory measures M_i of one kernel κ and power p.


    ==============================  ==========================================================
    licenses                        c·∫_0^t κ(t−ξ)Σ‖v_i(ξ)‖^p dξ = c·Σ M_i
    direction                       both (an equality)
    side conditions                 the term is c·∫_0^t(…) with c constant; the integrand is
                                    exactly Σ κ(t−ξ)‖v_i(ξ)‖^p of the named measures
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> J = memory_measure("J", x(xi), p=2, kernel=lambda u: sympy.exp(-u))
    >>> ctx = Context(sys_, P.resolve({}), {"J": J})
    >>> term = -5 * memory_integral(sympy.exp(xi - t) * norm_power(x(xi), 2))
    >>> MemoryWeight(("J",)).apply(term, "upper", ctx).bound
    -5*J
    >>> MemoryWeight(("J",)).apply(-5 * memory_integral(sympy.exp(xi - t) * norm_power(x(xi), 3)), "upper",
    ...                            ctx).status.value                  # another power
    'failed'
    """

    measures: tuple
    name = "a memory integral written in its measures"

    def apply(self, term, direction, ctx):
        ms = [_memory(ctx, n) for n in self.measures]
        parsed = _outer_memory_integral(ctx.at(term))
        if parsed is None:
            return Application(self.name, None, (_cond("the term is c·∫_0^t (…)dξ with c constant", False,
                                                       f"got {term}"),))
        c, integrand = parsed
        mine = sum((ctx.at(m.kernel(t - xi) * m.pointwise() ** m.power) for m in ms), sympy.S.Zero)
        diff = sympy.expand(integrand - mine)
        ok = diff == 0 or ctx.zero(diff)
        return Application(self.name, sympy.expand(c * sum((m.symbol for m in ms), sympy.S.Zero)),
                           (_cond(f"the integrand is Σ κ(t−ξ)‖v_i(ξ)‖^p of {', '.join(self.measures)}", ok,
                                  "it is not (another kernel, vector or power)"),))


@dataclasses.dataclass(frozen=True)
class _MemoryNorm(Norm):
    """‖∫_0^t w(t−ξ)F(ξ)dξ‖ ≤ κ_h Σ M_i (see :func:`memory_integral_of`)."""

    def resolve(self, vec, ctx, vector):
        pointwise, names, k, weight, constant = self.data
        measures = [_memory(ctx, n) if isinstance(n, str) else n for n in names]
        parsed = _integrand(vec, pointwise, weight, ctx, vector)
        if parsed[0] is None:
            return None, parsed[1]
        (w, lo, hi, pb), conds = parsed
        conds.append(_cond("the integral runs over the whole memory [0, t]", lo == 0 and hi == t,
                           f"limits ({lo}, {hi})"))
        k = ctx.at(k)
        for m in measures:
            conds.append(_cond(f"{m.name}: a memory measure of order {k}", sympy.simplify(ctx.at(m.power) - k) == 0,
                               f"order {m.power}"))
        kern = _kernel_at(measures[0], ctx)
        same = all(sympy.simplify(_kernel_at(m, ctx) - kern) == 0 for m in measures)
        conds.append(_cond("the measures share one kernel κ", same, "their kernels differ"))
        conds.append(_dominated(evaluate_constant_integrals(w.subs(t, U + xi) if w.has(t) else w), kern))
        if pb is None or not all(c_.status.is_proof for c_ in conds):
            return None, conds
        ps = [sympy.Symbol(f"x{i + 1}", nonnegative=True) for i in range(len(measures))]
        # no states are left in B: compared by expansion (nothing for the constraints to reduce)
        kappa, kconds = pointwise_constant(pb, measures, ps, k, constant, ctx, lambda e: sympy.expand(e) == 0)
        conds += kconds
        if kappa is None:
            return None, conds
        return kappa * sum((m.symbol for m in measures), sympy.S.Zero), conds


def _dominated(w, kern) -> Condition:
    """|w(u)| ≤ κ(u) for u ≥ 0: equal, structurally, or |∫_a^∞ f| ≤ ∫_a^∞ |f| (the triangle inequality)."""
    w = sympy.sympify(w).xreplace({sympy.Symbol("u"): U})
    text = f"|w(u)| ≤ κ(u) for u ≥ 0 (w = {w}, κ = {kern})"
    diff = sympy.simplify(kern - w)
    if nonnegative(w) and (diff == 0 or nonnegative(diff)):
        return _cond(text, True)
    if nonnegative(-w) and nonnegative(sympy.simplify(kern + w)):
        return _cond(text, True)
    if isinstance(w, sympy.Integral) and isinstance(kern, sympy.Integral) and w.limits == kern.limits \
            and sympy.simplify(kern.function - sympy.Abs(w.function)) == 0:
        return _cond(text + " by |∫f| ≤ ∫|f|", True)
    return _cond(text, None, "not shown")


def memory_integral_of(pointwise: Norm, *, measures, power, weight, constant: str | None = None) -> Norm:
    """‖∫_0^t w(t−ξ)F(ξ)dξ‖ ≤ ∫|w|‖F‖ ≤ κ_h·Σ_i M_i, a :class:`~.rules.Norm` for CauchySchwarz.

    ``pointwise`` bounds ‖F(ξ)‖ in the measures' pointwise norms; ``measures`` (names or
    memory measures) share a kernel κ ≥ |w| (checked: equal, or |∫f| ≤ ∫|f|); the pointwise bound
    is Σ‖v_i‖^k or, with ``constant`` named, κ_h = sup of its ratio to Σ‖v_i‖^k (homogeneity,
    certified).  ``weight`` is w(t − ξ) as it appears in the integrand.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import CauchySchwarz, measured
    >>> y = Vector("y", 2); sys2 = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    >>> M, n = memory_measure("M", x(xi), p=1, kernel=lambda u: sympy.exp(-u)), norm_measure("n", y(t))
    >>> ctx = Context(sys2, P.resolve({}), {"M": M, "n": n})
    >>> I = memory_integral(sympy.exp(xi - t) * x(xi))                   # ‖∫e^{−(t−ξ)}x‖ ≤ ∫e^{−(t−ξ)}‖x‖ = M
    >>> nb = memory_integral_of(measured(M, at=xi), measures=(M,), power=1, weight=sympy.exp(xi - t))
    >>> CauchySchwarz(y(t), I, (measured(n), nb)).apply(y(t).dot(I), "upper", ctx).bound
    M*n
    >>> I2 = memory_integral(2 * sympy.exp(xi - t) * x(xi))               # |w| = 2e^{−u} > κ = e^{−u}
    >>> nb2 = memory_integral_of(measured(M, at=xi), measures=(M,), power=1, weight=2 * sympy.exp(xi - t))
    >>> CauchySchwarz(y(t), I2, (measured(n), nb2)).apply(y(t).dot(I2), "upper", ctx).status.value
    'undecided'
    """
    return _MemoryNorm("memory integral", ("memory",), None, (pointwise,),
                       data=(pointwise, tuple(measures), sympy.sympify(power), sympy.sympify(weight), constant))


@dataclasses.dataclass(frozen=True)
class KernelBound(Rule):
    """M_source ≤ c·M_target when κ_s(u) ≤ c·κ_t(u) for every u ≥ 0 (same vector and power).

    The kernel inequality is decided by ``decide(ctx, c)`` when given (a lemma, e.g.
    Assumption 1 of paper 000) or here: c·κ_t − κ_s simplifies to 0 or to a structurally
    nonnegative expression (proved), or is negative at a sample u (refuted, exactly).


    ==============================  ==========================================================
    licenses                        M_s ≤ c·M_t when κ_s ≤ c·κ_t on [0, ∞)
    direction                       the bound nondecreasing in M_s (≤ steps) or nonincreasing
                                    (≥ steps), checked by ∂/∂M_s
    side conditions                 one vector and one power; c ≥ 0; the kernel inequality
                                    (a lemma, exact, or refuted at a sample u); monotonicity
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> Ms = memory_measure("Ms", x(xi), p=2, kernel=lambda u: sympy.exp(-2 * u) / 2)    # the tail of e^{−2u}
    >>> Mt = memory_measure("Mt", x(xi), p=2, kernel=lambda u: sympy.exp(-2 * u))
    >>> ctx = Context(sys_, P.resolve({}), {"Ms": Ms, "Mt": Mt})
    >>> KernelBound("Ms", "Mt", sympy.Rational(1, 2)).rewrite(3 * Ms.symbol, ctx).bound       # σ = 1/2
    3*Mt/2
    >>> app = KernelBound("Ms", "Mt", sympy.Rational(1, 4)).rewrite(3 * Ms.symbol, ctx)
    >>> app.status.value, app.detail.split(": ")[-1]
    ('failed', 'c·κ_t − κ_s = -1/4 < 0')
    """

    source: str
    target: str
    factor: object
    decide: object = None
    name = "a kernel bound (κ_s ≤ c·κ_t on [0, ∞))"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        s, g = _memory(ctx, self.source), _memory(ctx, self.target)
        c = evaluate_constant_integrals(ctx.at(self.factor))
        conds = [_cond(f"{s.name}, {g.name}: one vector and one power", s.vector == g.vector
                       and sympy.simplify(ctx.at(s.power - g.power)) == 0),
                 _cond(f"c = {c} ≥ 0", bool(c.is_nonnegative) or None)]
        if self.decide is not None:
            conds.append(self.decide(ctx, c))
        else:
            conds.append(_kernel_inequality(_kernel_at(s, ctx), _kernel_at(g, ctx), c))
        bound, more = _substitute(ctx.at(previous), s.symbol, c * g.symbol, "upper", direction,
                                  f"{c}·{g.name} ≥ {s.name}")
        return Application(self.name, bound, tuple(conds + more))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


def _kernel_inequality(ks, kt, c) -> Condition:
    text = f"κ_s(u) = {ks} ≤ {c}·κ_t(u) = {c}·({kt}) for u ≥ 0"
    d = sympy.simplify(c * kt - ks)
    if d == 0 or nonnegative(d):
        return _cond(text, True)
    for u0 in (0, sympy.Rational(1, 2), 1, 2, 5, 10):
        v = sympy.simplify(d.subs(U, u0))
        if v.is_number and v.is_negative:
            return _cond(text, False, f"at u = {u0}: c·κ_t − κ_s = {v} < 0")
    return _cond(text, None, f"c·κ_t − κ_s = {d} not shown ≥ 0")


@dataclasses.dataclass(frozen=True)
class MemoryHolder(Rule):
    """∫_0^tκ‖v‖^k ≤ (∫_0^∞κ)^{1−k/P}(∫_0^tκ‖v‖^P)^{k/P}: Hölder with the weight κ ≥ 0, k ≤ P.

    ``source`` and ``target`` are memory measures of one vector and one kernel, of orders
    k ≤ P; ∫_0^∞κ is evaluated exactly and must be finite; the bound must be monotone in the
    source (checked).


    ==============================  ==========================================================
    licenses                        ∫_0^tκ‖v‖^k ≤ (∫_0^∞κ)^{1−k/P}(∫_0^tκ‖v‖^P)^{k/P}
    direction                       monotone in the source as the direction needs (∂/∂M_s)
    side conditions                 one vector, one kernel; 0 < k ≤ P; κ ≥ 0 on [0, ∞);
                                    ∫_0^∞κ finite (evaluated exactly); monotonicity
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> S, J = (memory_measure(n, x(xi), p=p, kernel=lambda u: sympy.exp(-u)) for n, p in (("S", 1), ("J", 2)))
    >>> ctx = Context(sys_, P.resolve({}), {"S": S, "J": J})
    >>> MemoryHolder("S", "J").rewrite(4 * S.symbol, ctx).bound         # (∫_0^∞e^{−u})^{1/2} = 1
    4*sqrt(J)
    >>> MemoryHolder("J", "S").rewrite(4 * J.symbol, ctx).status.value   # k = 2 > P = 1
    'failed'
    """

    source: str
    target: str
    name = "Hölder on the memory (∫κ‖v‖^k ≤ (∫κ)^{1−k/P}(∫κ‖v‖^P)^{k/P})"
    directional = True

    def rewrite(self, previous, ctx, direction: str = "upper") -> Application:
        s, g = _memory(ctx, self.source), _memory(ctx, self.target)
        k, P = ctx.at(s.power), ctx.at(g.power)
        ks = _kernel_at(s, ctx)
        same = s.vector == g.vector and sympy.simplify(ks - _kernel_at(g, ctx)) == 0
        kint = kernel_integral(s.kernel, ctx.sub)
        conds = [_cond(f"{s.name}, {g.name}: memory integrals of one vector with one kernel", same),
                 _cond(f"orders 0 < k = {k} ≤ P = {P}", _both(sympy.sympify(P - k).is_nonnegative,
                                                              sympy.sympify(k).is_positive), "not shown"),
                 _cond(f"the kernel {ks} ≥ 0 on [0, ∞)", nonnegative(ks) or None, "not shown"),
                 _cond(f"∫_0^∞ κ = {kint} is finite", kint is not None, "it diverges or is not evaluated")]
        if kint is None:
            return Application(self.name, None, tuple(conds))
        bound, more = _substitute(ctx.at(previous), s.symbol, kint ** (1 - k / P) * g.symbol ** (k / P), "upper",
                                  direction, f"(∫κ)^(1−k/P)·{g.name}^(k/P) ≥ {s.name}")
        return Application(self.name, bound, tuple(conds + more))

    def apply(self, term, direction, ctx):
        return self.rewrite(ctx.at(term), ctx, direction)


@dataclasses.dataclass(frozen=True)
class Evaluated(Rule):
    """``rule`` applied to the term with its constant integrals evaluated exactly (e.g. ∫_0^∞ g = 1/2).


    ==============================  ==========================================================
    licenses                        what ``rule`` licenses, on the term with its constant
                                    integrals evaluated exactly
    direction                       that of ``rule``
    side conditions                 no constant integral left unevaluated; every condition of
                                    ``rule``
    ==============================  ==========================================================

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, memory_integral, norm_power, t, xi
    >>> from lkverify.certify.steps.rules import Context
    >>> P = Parameters(); x = Vector("x", 2); sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> from lkverify import zeta
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import Equal
    >>> n = norm_measure("n", x(t)); ctx = Context(sys_, P.resolve({}), {"n": n})
    >>> term = (1 + sympy.Integral(sympy.exp(-2 * zeta), (zeta, 0, sympy.oo))) * x(t).dot(x(t))
    >>> Evaluated(Equal(3 * n.symbol**2 / 2)).apply(term, "upper", ctx).status.value
    'exact'
    >>> Equal(3 * n.symbol**2 / 2).apply(term, "upper", ctx).status.value      # the integral left as it is
    'failed'
    """

    rule: Rule
    name = "constant integrals evaluated"

    def apply(self, term, direction, ctx):
        e = ctx.at(term)
        done = evaluate_constant_integrals(e)
        left = [a for a in done.atoms(sympy.Integral) if not (a.free_symbols & {t, xi}) and not a.atoms(AppliedUndef)]
        app = self.rule.apply(done, direction, ctx)
        cond = _cond("the constant integrals are evaluated exactly (SymPy doit)", not left,
                     f"left unevaluated: {left[:1]}")
        return dataclasses.replace(app, rule=f"{app.rule} ({self.name})", conditions=(cond, *app.conditions))


@dataclasses.dataclass(frozen=True)
class MemoryKrasovskii(Krasovskii):
    """Krasovskii's sign conditions, for functionals with memory measures ([9, pp. 211, 212] of paper 000).

    With memory over the whole past, U(‖x_t‖) must be bounded by a function of the sup of
    the history on [0, t] that vanishes at 0: a memory measure is at most (∫_0^∞κ)·sup^p, so
    every memory measure of L, U, W needs a finite ∫_0^∞κ (evaluated exactly).

    Examples
    --------
    >>> conclusion = MemoryKrasovskii(("w", "e1", "e2"))
    >>> conclusion.point, "memory kernels integrable" in conclusion.link
    (('w', 'e1', 'e2'), True)
    """

    link = ("V ≥ φ(‖x(t)‖), V ≤ U(‖x_t‖_[0,t]), V̇ ≤ −ψ(‖x(t)‖) on the region, memory kernels integrable "
            "(Krasovskii, unbounded memory)")

    def certify(self, steps, values, *, budget=None, progress=None, **kw):
        from ...declare.parameters import apply_substitution

        ms = {m.name: m for s_, _ in steps.values() for m in s_.measures if isinstance(m, MemoryMeasure)}
        sub = next(iter(steps.values()))[0].system.parameters.substitution(values)
        used = set()
        for _, res in steps.values():
            used |= {s_.name for s_ in sympy.sympify(res.rhs).free_symbols}
        rows, parts = [], []
        for name in sorted(n for n in ms if n in used):
            kint = kernel_integral(ms[name].kernel, sub)
            if kint is None:
                return rows, Status.FAILED, (f"the memory measure {name} has ∫_0^∞κ = ∞ or not evaluated: "
                                             f"U is not bounded by a function of ‖x_t‖")
            parts.append(f"{name} ≤ {kint}·sup^({apply_substitution(ms[name].power, sub)})")
        more, status, detail = super().certify(steps, values, budget=budget, progress=progress, **kw)
        if parts:
            rows.append(Result("region", "memory measures bounded by the history's sup", Status.EXACT,
                               None, "; ".join(parts)))
        return rows + list(more), status, detail


def _both(a, b):
    """True when both hold, False when one is shown false, None (undecided) when one is not shown."""
    if a is False or b is False:
        return False
    return True if (a is True and b is True) else None
