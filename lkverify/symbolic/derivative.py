"""The exact derivative of a functional along a system, term by term.

``derivative_along(V, system)`` applies the chain rule to every term of V:
for each state value x(t) in the term, ∂/∂x · ẋ with ẋ replaced by each
right-hand-side term of the system in turn; for each integral, the Leibniz rule
(upper limit, lower limit, derivative of the weight under the integral sign);
for delayed values x(t−τ), ∂/∂x(t−τ) · ẋ(t−τ); and the explicit dependence on t.
Each piece is a labelled :class:`Block`, so differences with a printed formula
can be named.

>>> import sympy
>>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t, xi
>>> from lkverify.declare.functional import window_integral
>>> P = Parameters(); k = P.scalar("k", positive=True); tau = P.delay("tau")
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-k * x(t - tau), text="-k x(t-τ)")])], parameters=P)
>>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2"),
...                 Term(window_integral(x(xi)[0] ** 2, tau), text="∫x²")])
>>> d = derivative_along(V, sys)
>>> sympy.expand(d.expr - (x(t)[0]**2 - k*x(t)[0]*x(t - tau)[0] - x(t - tau)[0]**2))
0
>>> [b.kind for b in d.blocks]
['dynamics', 'upper limit', 'lower limit']
"""

from __future__ import annotations

import dataclasses

import sympy
from sympy.core.function import AppliedUndef

from ..declare.functional import Functional, outer_integrals, split_outer
from ..declare.system import System
from ..declare.symbols import t

__all__ = ["Block", "DerivativeResult", "derivative_along"]


@dataclasses.dataclass(frozen=True)
class Block:
    """One labelled piece of V̇.

    Attributes
    ----------
    source : str
        The functional term it comes from.
    kind : str
        ``"dynamics"`` (∂/∂x · a right-hand-side term), ``"delayed"``,
        ``"upper limit"``, ``"lower limit"``, ``"under the integral"`` or ``"explicit t"``.
    text, latex : str
        Readable labels.
    expr : sympy.Expr

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", positive=True); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t), text="−k x")])], parameters=P)
    >>> (b,) = derivative_along(Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")]), sys).blocks
    >>> b.source, b.kind, b.text, b.expr
    ('x²/2', 'dynamics', '∂/∂x [x²/2] · (−k x)', -k*x_1(t)**2)
    """

    source: str
    kind: str
    text: str
    latex: str
    expr: sympy.Expr


@dataclasses.dataclass(frozen=True)
class DerivativeResult:
    """V̇ along a system, as labelled blocks.

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t, xi
    >>> from lkverify.declare.functional import window_integral
    >>> P = Parameters(); k = P.scalar("k", positive=True); tau = P.delay("tau"); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t), text="−k x")])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2"),
    ...                 Term(window_integral(x(xi)[0] ** 2, tau), text="∫x²")])
    >>> d = derivative_along(V, sys)
    >>> d.grouped()
    {'point': -k*x_1(t)**2 + x_1(t)**2, 'delayed': -x_1(t - tau)**2, 'integral': 0}
    >>> print(d.as_text())
    dV/dt of V along the system: 3 blocks
      [dynamics] ∂/∂x [x²/2] · (−k x)
      [upper limit] ∫ in [∫x²]: upper limit
      [lower limit] ∫ in [∫x²]: lower limit
    """

    functional: Functional
    system: System
    blocks: tuple

    @property
    def expr(self) -> sympy.Expr:
        """V̇ as one expression (the sum of the blocks)."""
        return sympy.Add(*[b.expr for b in self.blocks])

    def grouped(self) -> dict[str, sympy.Expr]:
        """V̇ split into point terms, delayed terms and integral terms.

        Every additive term of the expanded V̇ goes to ``"integral"`` if it
        contains an integral, else to ``"delayed"`` if it contains a delayed state
        value, else to ``"point"``.
        """
        funcs = self.system.state_functions()
        groups = {"point": [], "delayed": [], "integral": []}
        expanded = sympy.expand(self.expr, power_exp=False, power_base=False, log=False)
        for term in sympy.Add.make_args(expanded):
            if term.has(sympy.Integral):
                groups["integral"].append(term)
            elif any(a.func in funcs and a.args[0] != t for a in term.atoms(AppliedUndef)):
                groups["delayed"].append(term)
            else:
                groups["point"].append(term)
        return {k: sympy.Add(*v) for k, v in groups.items()}

    def as_text(self) -> str:
        lines = [f"dV/dt of {self.functional.name or 'V'} along {self.system.name or 'the system'}: "
                 f"{len(self.blocks)} blocks"]
        for b in self.blocks:
            lines.append(f"  [{b.kind}] {b.text}")
        return "\n".join(lines)


def derivative_along(functional: Functional, system: System) -> DerivativeResult:
    """The exact derivative of ``functional`` along the solutions of ``system``.

    Parameters
    ----------
    functional : Functional
    system : System

    Returns
    -------
    DerivativeResult
        Labelled blocks whose sum is V̇, with the dynamics substituted.

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", positive=True); tau = P.delay("tau"); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t - tau), text="−k x(t−τ)")])], parameters=P)
    >>> d = derivative_along(Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")]), sys)
    >>> d.expr                                  # x·ẋ with ẋ = −k x(t−τ)
    -k*x_1(t)*x_1(t - tau)
    """
    funcs = system.state_functions()
    blocks: list[Block] = []
    for term in functional.terms:
        blocks += _term_blocks(term, system, funcs)
    # Any derivative of a state value left inside a block (e.g. a state at t
    # under an integral sign) is replaced by the dynamics.
    sub_now = system.derivative_substitution(t)
    derivs = {}
    for b in blocks:
        for d in b.expr.atoms(sympy.Derivative):
            if isinstance(d.expr, AppliedUndef) and d.expr.func in funcs and d.expr.args[0] == t \
                    and d.variables == (t,):
                derivs[d] = sub_now[d.expr]
    if derivs:
        blocks = [dataclasses.replace(b, expr=b.expr.xreplace(derivs)) for b in blocks]
    return DerivativeResult(functional, system, tuple(b for b in blocks if b.expr != 0))


def _term_blocks(term, system: System, funcs) -> list[Block]:
    P = term.expr
    src_text, src_latex = term.text, term.latex
    # 1. integrals that depend on t → placeholders
    integrals = [I for I in outer_integrals(P) if t in I.free_symbols]  # those that depend on t
    Y = [sympy.Dummy(f"I{k}") for k in range(len(integrals))]
    Pt = P.xreplace(dict(zip(integrals, Y)))
    # 2. state values: now (arg == t) and delayed (arg depends on t otherwise)
    now: dict = {}
    delayed: dict = {}
    for a in Pt.atoms(AppliedUndef):
        if a.func not in funcs:
            continue
        arg = a.args[0]
        if arg == t:
            now[a] = sympy.Dummy(a.func.__name__)
        elif t in arg.free_symbols:
            delayed[a] = sympy.Dummy(f"{a.func.__name__}_d")
    Pt = Pt.xreplace({**now, **delayed})
    back = {v: k for k, v in {**now, **delayed}.items()}
    back.update(dict(zip(Y, integrals)))

    def finish(expr):
        return expr.xreplace(back)

    out: list[Block] = []
    # dynamics: ∂P/∂x(t) · (each right-hand-side term)
    for state in system.states:
        partials = []
        for i, f in enumerate(state.functions):
            d = now.get(f(t))
            partials.append(sympy.diff(Pt, d) if d is not None else sympy.S.Zero)
        if all(p == 0 for p in partials):
            continue
        for rterm in system.solved_terms(state):
            expr = sympy.Add(*[p * rterm.expr[i] for i, p in enumerate(partials) if p != 0])
            out.append(Block(src_text, "dynamics",
                             f"∂/∂{state.text} [{src_text}] · ({rterm.text})",
                             rf"\partial_{{{state.latex}}}\left[{src_latex}\right]\cdot\left({rterm.latex}\right)",
                             finish(expr)))
    # delayed values: ∂P/∂x(t-τ) · ẋ(t-τ)
    by_time: dict = {}
    for a, d in delayed.items():
        by_time.setdefault(a.args[0], []).append((a, d))
    for time, pairs in by_time.items():
        sub = system.derivative_substitution(time)
        # chain rule: d/dt x(θ(t)) = ẋ(θ(t)) · θ′(t)  (θ = t − h(t), t/2, …)
        inner = sympy.diff(time, t)
        expr = inner * sympy.Add(*[sympy.diff(Pt, d) * sub[a] for a, d in pairs])
        factor, factor_latex = ("", "") if inner == 1 else (f" · ({inner})", rf"\cdot\left({sympy.latex(inner)}\right)")
        out.append(Block(src_text, "delayed", f"∂/∂x({time}) [{src_text}] · ẋ({time}){factor}",
                         rf"\partial_{{x({sympy.latex(time)})}}\left[{src_latex}\right]\cdot\dot x({sympy.latex(time)})"
                         + factor_latex,
                         finish(expr)))
    # Leibniz rule for each integral
    for kind, pieces, how in _leibniz(Pt, integrals, Y):
        out.append(Block(src_text, kind, f"∫ in [{src_text}]: {how}",
                         rf"\textstyle\int \text{{ in }} \left[{src_latex}\right]\text{{: {how}}}",
                         finish(sympy.Add(*pieces))))
    # explicit time dependence (weights, coefficients h(t))
    explicit = sympy.diff(Pt, t)
    if explicit != 0:
        out.append(Block(src_text, "explicit t", f"∂/∂t [{src_text}]",
                         rf"\partial_t\left[{src_latex}\right]", finish(explicit)))
    return out


def _leibniz(Pt, integrals, placeholders) -> list:
    """d/dt of the integrals of one term: (kind, pieces, how) for the upper limit, lower limit, integrand."""
    upper, lower, inner = [], [], []
    for I, y in zip(integrals, placeholders):
        dPdI = sympy.diff(Pt, y)
        if dPdI == 0:
            continue
        var, lo, hi, g = split_outer(I)
        dhi, dlo = sympy.diff(hi, t), sympy.diff(lo, t)
        if dhi != 0:
            upper.append(dPdI * g.subs(var, hi) * dhi)
        if dlo != 0:
            lower.append(-dPdI * g.subs(var, lo) * dlo)
        dg = sympy.diff(g, t)
        if dg != 0:
            inner.append(dPdI * sympy.Integral(dg, (var, lo, hi)))
    named = (("upper limit", upper, "upper limit"), ("lower limit", lower, "lower limit"),
             ("under the integral", inner, "∂/∂t under the integral sign"))
    return [(kind, pieces, how) for kind, pieces, how in named if pieces]
