"""Compilation: a symbolic System turned into the right-hand side of a DDE.

:func:`compile_system` turns a :class:`~lkverify.declare.system.System` with numeric
parameter values into the right-hand side of a delay differential equation for
:func:`lkverify.simulate.solver.solve_dde`; it is generated from the same symbolic terms the
proofs use, never retyped:

* delayed values ``x(t − c)`` become rows of the lag array;
* window integrals ``∫_{t−c}^{t} g(x(ξ)) dξ`` become auxiliary states ``z`` with
  ``ż = g(x(t)) − g(x(t−c))`` (exact in exact arithmetic), started and re-synchronised
  after every accepted step by Gauss–Legendre quadrature over the dense history,
  so that no drift accumulates.  Measured: for x' = −∫_{t−1}^t x on [0, 200],
  |z − ∫x| stays 5.6e-11 without the re-synchronisation (it never decays: the
  difference is conserved) and 1e-16 with it; the auxiliary path agrees with the
  pure-quadrature reference path to 1e-7 and costs one extra state instead of a
  quadrature at every stage (``tests/simulate/test_simulate.py``, ``tests/simulate/test_dde.py``);
* memory integrals ``∫_{t0}^{t} K(t−ξ) g(x(ξ)) dξ`` with ``K`` a sum of exponentials
  ``Σ c_j e^{−a_j u}`` become exact auxiliary ODE states ``ṁ_j = c_j g(x(t)) − a_j m_j``;
  other kernels (and windows with weights depending on t) are computed by
  quadrature over the dense history plus a trapezoid over the current step;
* coefficients ``h(t)`` are evaluated as given;
* lags are resolved exactly: every delay ``t − arg`` is simplified to an exact SymPy
  number after substituting the parameter values (``CompiledSystem.exact_lags``); two
  delays are one lag only if they are equal numbers; a delay that does not resolve to a
  number is refused with the reason.

The right-hand side is one ``lambdify``-generated function with common
subexpressions eliminated: about 20 µs per evaluation for the 12-dimensional
system of paper 000 (``benchmarks/bench_jitcdde.py``).

>>> import sympy
>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - tau)[0] - x(t - 2 * tau / 3)[0])])], parameters=P)
>>> comp = compile_system(sys, {"tau": sympy.Rational(3, 2)})
>>> comp.exact_lags, comp.lags
((1, 3/2), (1.0, 1.5))
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from ..errors import InputError, UnsupportedInput
from ..declare.functional import outer_integrals as _outer_integrals
from ..declare.parameters import ParameterKind, apply_substitution
from ..declare.symbols import t, zeta
from ..declare.system import System
from ..memo import Memo

__all__ = ["CompiledSystem", "SymbolicSystem", "compile_system", "symbolic_system"]

_u = sympy.Symbol("u", real=True)


@dataclasses.dataclass(frozen=True)
class _Aux:
    kind: str  # "window" or "exponential memory"
    integral: sympy.Integral
    lag: float  # window length (window) or decay rate a (exponential)
    g: sympy.Expr  # integrand part in the integration variable
    var: sympy.Symbol
    coeff: float = 1.0
    lower: float = 0.0
    exact_lag: object = None  # window length as an exact SymPy number (window)


@dataclasses.dataclass(frozen=True)
class _Quad:
    integral: sympy.Integral


@dataclasses.dataclass(frozen=True)
class CompiledSystem:
    """A System ready for :func:`lkverify.simulate.solver.solve_dde`.

    Attributes
    ----------
    layout : dict
        state name → slice of the state vector.
    n_states : int
        Number of state components (auxiliary states follow them).
    lags : tuple of float
        The lags as floats, for the integrator.
    exact_lags : tuple of SymPy numbers
        The same lags, exactly as the system and the parameter values give them.
    aux : tuple
        Descriptions of the auxiliary states, in order.
    fun : callable
        ``fun(t, y, Z, past)`` → ẏ.
    symbolic : dict
        The generated right-hand side before compilation: ``rhs`` (SymPy expressions),
        ``y`` (state then auxiliary symbols), ``Z`` (lag symbols, one row per lag),
        ``t``, ``quadratures`` (placeholders of quadrature terms).  Other back ends
        (e.g. the jitcdde benchmark) translate from it.

    Examples
    --------
    A window integral becomes one auxiliary state after the state ``x``:

    >>> import numpy as np, sympy
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); tau = P.delay("tau", default=1); x = Vector("x", 1); s = sympy.Symbol("s")
    >>> sys = System([Equation(x, [Term(-sympy.Integral(x(s)[0], (s, t - tau, t)))])], parameters=P)
    >>> comp = compile_system(sys)
    >>> comp.layout, comp.n_states, comp.n, [(aux.kind, aux.lag) for aux in comp.aux]
    ({'x': slice(0, 1, None)}, 1, 2, [('window', 1.0)])
    >>> comp.fun(0.0, np.array([2.0, 3.0]), np.array([[1.0, 0.0]]), None).tolist()   # ẋ = −z, ż = x(t) − x(t−1)
    [-3.0, 1.0]
    """

    system: System
    layout: dict
    n_states: int
    lags: tuple
    aux: tuple
    quads: tuple
    fun: Callable
    _g_funcs: tuple
    _quad_funcs: tuple
    symbolic: dict = dataclasses.field(default_factory=dict)
    exact_lags: tuple = ()

    @property
    def n(self) -> int:
        return self.n_states + len(self.aux)

    def aux_initial(self, t0: float, past) -> np.ndarray:
        """Initial values of the auxiliary states from the history (quadrature)."""
        out = np.zeros(len(self.aux))
        for k, (a, g) in enumerate(zip(self.aux, self._g_funcs)):
            if a.kind == "window":
                out[k] = float(np.ravel(past.integrate(g, t0 - a.lag, t0))[0])
            elif t0 > a.lower:  # exponential memory accumulated on [lower, t0]
                out[k] = float(np.ravel(past.integrate(
                    lambda s, Y, a=a, g=g: a.coeff * np.exp(-a.lag * (t0 - s)) * g(Y)[:, 0],
                    a.lower, t0, with_time=True))[0])
        return out

    def resync(self, t_now: float, y: np.ndarray, past) -> np.ndarray:
        """Recompute window auxiliaries exactly over the accepted history (no drift)."""
        if not any(a.kind == "window" for a in self.aux):
            return y
        y = np.array(y, dtype=float)
        for k, (a, g) in enumerate(zip(self.aux, self._g_funcs)):
            if a.kind == "window":
                y[self.n_states + k] = float(np.ravel(past.integrate(g, t_now - a.lag, t_now))[0])
        return y


def _numeric(x, what: str) -> float:
    return float(_exact(x, what))


def _exact(x, what: str):
    """``x`` as an exact real SymPy number, or an InputError saying why not."""
    x = sympy.sympify(x)
    if x.free_symbols or not x.is_real:
        raise InputError(f"{what}: expected a number after substituting the parameters, got {x}; "
                         f"give every parameter it contains a numeric value")
    return x


def _split_kernel(integrand, var, state_funcs):
    """integrand = Σ K_j(t − var) · g_j(var): return [(K_j(u), g_j)] or None."""
    out = []
    for term in sympy.Add.make_args(sympy.expand(integrand, power_exp=False, power_base=False, mul=True,
                                                 multinomial=False)):
        kern, g = [], []
        for f in sympy.Mul.make_args(term):
            has_state = any(isinstance(a, AppliedUndef) and a.func in state_funcs for a in f.atoms(AppliedUndef))
            (g if has_state or (var in f.free_symbols and t not in f.free_symbols) else kern).append(f)
        K = sympy.Mul(*kern).subs(var, t - _u)
        if t in sympy.simplify(K).free_symbols:
            return None
        out.append((sympy.simplify(K), sympy.Mul(*g)))
    return out


def _exponential_terms(K):
    """K(u) = Σ c_j e^{−a_j u} with numeric c_j, a_j > 0, or None."""
    terms = []
    for term in sympy.Add.make_args(sympy.expand(sympy.powsimp(K))):
        c, rest = term.as_independent(_u)
        rest = sympy.powsimp(rest)
        if rest == 1:
            return None  # a constant part of a kernel is not integrable on [0, ∞)
        if not isinstance(rest, sympy.exp):
            return None
        rate = sympy.expand(rest.args[0] / _u)
        if rate.free_symbols or not (rate.is_real and rate < 0) or not c.is_number:
            return None
        terms.append((float(c), float(-rate)))
    return terms


def compile_system(system: System, values: Mapping[str, object] | None = None, *,
                   integrals: str = "auto") -> CompiledSystem:
    """Compile ``system`` at the given parameter values (names → values, defaults fill in).

    ``integrals="auto"`` uses auxiliary states for windows and exponential kernels
    and quadrature otherwise; ``integrals="quadrature"`` computes every integral by
    quadrature over the dense history (the slow reference path the fast one is
    tested against).

    Raises
    ------
    InputError
        A parameter the system needs has no value, a delay does not resolve to a
        positive number, or a kernel is not integrable.
    UnsupportedInput
        A term of a kind the simulator does not take (a multiple integral).

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a"); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> comp = compile_system(sys, {"a": 2})
    >>> comp.lags, comp.symbolic["rhs"]
    ((1.0,), [-2*_Z0_0])
    >>> comp.fun(0.0, np.array([1.0]), np.array([[0.5]]), None).tolist()     # ẋ = −2 x(t − 1)
    [-1.0]
    >>> compile_system(sys)
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: system: parameters without a value: a; expected a value for every parameter the system uses; give them in the parameter values (NAME=VALUE)
    """
    if integrals not in ("auto", "quadrature"):
        raise InputError(f"integrals: expected 'auto' or 'quadrature', got {integrals!r}")
    name = system.name or "system"
    rhs = _resolved_rhs(system, values, name)
    sr = _symbolic_rhs(system, rhs, integrals, name)
    n = sr.n_states
    lags = tuple(float(c) for c in sr.exact_lags)
    args = [t, *sr.ysyms, *sr.aux_syms, *[z for row in sr.zsyms for z in row], *sr.quad_holders.values()]
    f = _Lambdified(args, sr.exprs)      # lambdified on first call: the compiled integrator never calls it
    g_funcs = _aux_integrands(sr.aux, sr.to_symbols, sr.ysyms, n)
    quad_funcs = _quadrature_integrands(sr.quads, sr.to_symbols, sr.ysyms)
    fun = _right_hand_side(f, quad_funcs, n, len(lags))
    symbolic = {"rhs": sr.exprs, "y": sr.ysyms + sr.aux_syms, "Z": sr.zsyms, "t": t,
                "quadratures": list(sr.quad_holders.values())}
    return CompiledSystem(system, sr.layout, n, lags, sr.aux, sr.quads, fun, tuple(g_funcs),
                          tuple(quad_funcs), symbolic, sr.exact_lags)


@dataclasses.dataclass(frozen=True)
class _SymbolicRHS:
    """The right-hand side in symbols, before any back end compiles it (shared by compile_system and compile_family).

    ``exprs``: one expression per state component, then one per auxiliary state, in ``t``, ``ysyms``
    (states), ``aux_syms``, ``zsyms[k][i]`` (component i delayed by ``exact_lags[k]``), the quadrature
    placeholders and any symbols the caller kept free (``keep`` of :func:`_symbolic_rhs`).
    """

    layout: dict
    n_states: int
    ysyms: list
    aux: tuple
    quads: tuple
    quad_holders: dict
    exact_lags: tuple
    zsyms: list
    aux_syms: list
    exprs: list
    to_symbols: "_StateSymbols"


def _symbolic_rhs(system: System, rhs: list, integrals: str, name: str, keep=frozenset()) -> _SymbolicRHS:
    """Layout, auxiliary states, lags and the expressions of the right-hand side ``rhs`` (parameters substituted).

    ``keep``: symbols that stay free (a family's grid symbols); window lengths and delays may be
    expressions in them instead of numbers.
    """
    funcs = system.state_functions()
    layout, ysyms, index, n = _layout(system)
    aux, quads, aux_expr, quad_holders = _integral_states(rhs, funcs, integrals, name, keep)
    exact = _exact_lags(rhs, aux, funcs, keep)
    zsyms = [[sympy.Dummy(f"Z{k}_{i}") for i in range(n)] for k in range(len(exact))]
    to_symbols = _StateSymbols(funcs, index, ysyms, zsyms, exact, name)
    exprs = [to_symbols(e.xreplace({I: aux_expr[I] for I in aux_expr if isinstance(I, sympy.Integral)})
                         .xreplace(quad_holders), t) for e in rhs]
    aux_syms = []
    for k, a in enumerate(aux):
        if a.kind == "window":
            sym = aux_expr[a.integral]
            exprs.append(to_symbols(a.g.subs(a.var, t) - a.g.subs(a.var, t - a.exact_lag), t))
        else:
            sym = aux_expr[("m", k + 1)]
            exprs.append(to_symbols(a.coeff * a.g.subs(a.var, t), t) - a.lag * sym)
        aux_syms.append(sym)
    return _SymbolicRHS(layout, n, ysyms, tuple(aux), tuple(quads), quad_holders, exact, zsyms, aux_syms, exprs,
                        to_symbols)


@dataclasses.dataclass(frozen=True)
class SymbolicSystem:
    """A System's right-hand side in symbols, as the back ends read it (:func:`symbolic_system`).

    Attributes
    ----------
    symbols : tuple of sympy.Symbol
        The symbols of the names kept free (``grid``), in their order.
    substitution : dict
        Parameter atom → value (the kept names' values contain their symbols).
    rhs : object
        Layout, auxiliary states (``aux``: kind, integrand ``g``, variable ``var``, ``exact_lag``),
        quadrature terms (``quads``), the distinct lags (``exact_lags``) and the expressions
        (``exprs``: states, then auxiliary states) in the symbols ``ysyms``, ``aux_syms``,
        ``zsyms[k][i]`` (component i delayed by lag k) and ``symbols``.
    """

    symbols: tuple
    substitution: dict
    rhs: _SymbolicRHS


def symbolic_system(system: System, values: Mapping[str, object] | None = None, *, grid=(),
                    integrals: str = "auto") -> SymbolicSystem:
    """The right-hand side :func:`compile_system` compiles (``grid=()``), or with the names ``grid`` kept free.

    With ``grid`` it is what :func:`lkverify.simulate.family.compile_family` compiles (values
    as it takes them); :mod:`lkverify.linear` linearises it.  No code is generated.

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); a = P.scalar("a", default=1); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1); sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
    >>> sym = symbolic_system(sys, grid=("tau",))
    >>> sym.symbols, sym.rhs.exact_lags, sym.rhs.exprs
    ((tau,), (tau,), [-_Z0_0])
    """
    name = system.name or "system"
    if grid:
        symbols, sub = _grid_substitution(system, dict(values or {}), tuple(grid))
    else:
        P = system.parameters
        symbols, sub = [], P.substitution(P.resolve(values or {}, use_defaults=True))
    keep = frozenset(symbols)
    rhs = _substituted_rhs(system, sub, name, keep)
    return SymbolicSystem(tuple(symbols), sub, _symbolic_rhs(system, rhs, integrals, name, keep))


def _layout(system: System):
    """State name → slice; a dummy symbol per component; component function → index; n."""
    layout, n = {}, 0
    ysyms, index = [], {}
    for s in system.states:
        layout[s.name] = slice(n, n + s.dim)
        for i, f in enumerate(s.functions):
            index[f] = n + i
            ysyms.append(sympy.Dummy(f"y{n + i}"))
        n += s.dim
    return layout, ysyms, index, n


def _resolved_rhs(system: System, values, name: str) -> list:
    """The right-hand side, component by component, at the parameter values; refuses parameters without one."""
    P = system.parameters
    return _substituted_rhs(system, P.substitution(P.resolve(values or {}, use_defaults=True)), name)


#: system, (replacement, kept symbols) → the substituted right-hand side (:meth:`Memo.owned`): a run's
#: compile_system and its compile_family substitute the same values, and the runs of an example mostly share them
_SUBSTITUTED = Memo(64)


def _memo_key(system: System, sub: dict, keep) -> tuple | None:
    """The key of :data:`_SUBSTITUTED` for ``system``, or None (an unhashable value, or a Float: 2.0 == 2 in SymPy)."""
    if any(isinstance(v, sympy.Basic) and v.has(sympy.Float) for v in sub.values()):
        return None
    try:
        key = (frozenset(sub.items()), frozenset(keep))
        hash(key)
    except TypeError:
        return None
    return key


def _substituted_rhs(system: System, sub: dict, name: str, keep=frozenset()) -> list:
    """The right-hand side with the atom replacement ``sub``; refuses free symbols other than t and ``keep``."""
    key = _memo_key(system, sub, keep)
    hit = _SUBSTITUTED.owned(system, key) if key is not None else None
    if hit is not None:
        return list(hit)
    rhs = _substitute_rhs(system, sub, name, keep)
    if key is not None:
        _SUBSTITUTED.keep(system, key, tuple(rhs))
    return rhs


def _substitute_rhs(system: System, sub: dict, name: str, keep) -> list:
    rhs = []
    for s in system.states:
        rhs += list(apply_substitution(system.rhs(s), sub))
    missing = set().union(*[e.free_symbols for e in rhs]) - {t} - set(keep)
    missing = {m for m in missing if not any(m in i.variables for i in _outer_integrals_all(rhs))}
    if missing:
        names = sorted(str(m) for m in missing)
        raise InputError(f"{name}: parameters without a value: {', '.join(names)}; expected a value for every "
                         f"parameter the system uses; give them in the parameter values (NAME=VALUE)",
                         topic="parameters", example=f"{names[0]}=1")
    return rhs


def _integral_states(rhs, funcs, integrals: str, name: str, keep=frozenset()):
    """Auxiliary states (windows, exponential memory) and quadratures for the integrals of ``rhs``.

    A window length may be an expression in the symbols ``keep`` (a family's grid symbols).
    """
    aux: list[_Aux] = []
    quads: list[_Quad] = []
    aux_expr: dict = {}
    quad_holders: dict = {}

    def quadrature(I):
        quads.append(_Quad(I))
        quad_holders[I] = sympy.Dummy(f"q{len(quads)}")

    for I in dict.fromkeys(i for e in rhs for i in _outer_integrals(e)):
        if len(I.limits) != 1 or len(I.limits[0]) != 3:
            raise UnsupportedInput(f"{name}: the simulator integrates right-hand sides with single definite "
                                   f"integrals; got {I}; write the inner integral as an auxiliary state")
        (var, lo, hi), = I.limits
        g = I.function
        width = sympy.simplify(hi - lo)
        if integrals == "quadrature":
            quadrature(I)
            continue
        if hi == t and width.free_symbols <= set(keep):
            c = _positive_lag(width, f"window of {I}", keep, f"window length must be positive, got {width} in {I}")
            if t not in g.free_symbols:
                aux.append(_Aux("window", I, float(c) if c.is_number else math.nan, g, var, exact_lag=c))
                aux_expr[I] = sympy.Dummy(f"z{len(aux)}")
                continue
        if hi == t and not lo.free_symbols and _exponential_memory(I, g, var, lo, funcs, aux, aux_expr):
            continue
        quadrature(I)
    return aux, quads, aux_expr, quad_holders


def _exponential_memory(I, g, var, lo, funcs, aux, aux_expr) -> bool:
    """Add auxiliary ODE states for a memory integral with a sum-of-exponentials kernel; False if it is not one."""
    split = _split_kernel(g, var, funcs)
    if split is None:
        return False
    exps = [(_exponential_terms(K), gg) for K, gg in split]
    if not all(e is not None for e, _ in exps):
        for K, _ in split:
            if not K.free_symbols - {_u}:      # a kernel in a family's grid symbols is not checked here
                _check_integrable(K)
        return False
    total = sympy.S.Zero
    for terms, gg in exps:
        for coeff, rate in terms:
            aux.append(_Aux("exponential memory", I, rate, gg, var, coeff, _numeric(lo, "lower limit")))
            d = sympy.Dummy(f"m{len(aux)}")
            aux_expr.setdefault(("m", len(aux)), d)
            total += d
    aux_expr[I] = total
    return True


def _exact_lags(rhs, aux, funcs, keep=frozenset()) -> tuple:
    """The distinct lags, exact and sorted: delays of the states outside integrals, and window lengths.

    With ``keep`` (a family's grid symbols) a lag may be an expression in them; expressions
    sort after numbers and are distinct unless they simplify to the same expression.
    """
    found, seen = [], set()
    bound = {v for e in rhs + [a.g for a in aux] for I in e.atoms(sympy.Integral) for v in I.variables}
    bound |= {a.var for a in aux}
    for e in rhs + [a.g for a in aux]:
        for a in e.atoms(AppliedUndef):
            if a.func in funcs and a.args[0] != t and a.args[0] not in seen:
                seen.add(a.args[0])
                if a.args[0].free_symbols & bound:
                    continue  # in an integration variable: inside an integral, handled there
                c = sympy.expand(t - a.args[0])
                if t in c.free_symbols:   # simplify (slow) only where expanding did not cancel t
                    c = sympy.simplify(c)
                if t in c.free_symbols:
                    continue  # inside an integral, handled there
                if not c.free_symbols or not c.free_symbols <= set(keep):
                    c = _exact(c, f"delay of {a}")
                if c != 0:
                    found.append(c)
    for c in found:
        _positive_lag(c, "delay", keep, f"delays must be positive, got {c}; expected delayed values "
                                          f"x(t - tau) with tau > 0")
    found += [a.exact_lag for a in aux if a.kind == "window"]
    distinct = []
    for c in sorted(found, key=_lag_key):
        if not any(c == d or ((c.free_symbols or d.free_symbols) and sympy.simplify(c - d) == 0)
                   for d in distinct):
            distinct.append(c)
    return tuple(distinct)


def _lag_key(c):
    return (0, float(c), ()) if not c.free_symbols else (1, 0.0, sympy.default_sort_key(c))


def _positive_lag(c, what: str, keep, message: str):
    """``c`` as an exact number > 0, or an expression in ``keep`` not known to be ≤ 0; else InputError."""
    if c.free_symbols and c.free_symbols <= set(keep):
        if c.is_positive is False:
            raise InputError(message)
        return c
    c = _exact(c, what)
    if not c > 0:
        raise InputError(message)
    return c


class _StateSymbols:
    """Replace state applications x(time) by the y symbols and x(time − c) by the Z symbols of lag c."""

    def __init__(self, funcs, index, ysyms, zsyms, exact_lags, name):
        self.funcs, self.index, self.ysyms, self.zsyms = funcs, index, ysyms, zsyms
        self.exact_lags, self.name = exact_lags, name

    def lag_index(self, c) -> int:
        for k, d in enumerate(self.exact_lags):
            if c == d or sympy.simplify(c - d) == 0:
                return k
        raise InputError(f"{self.name}: the delay {c} is not one of the resolved lags "
                         f"{', '.join(map(str, self.exact_lags)) or '(none)'}; expected delays that are numbers "
                         f"once the parameter values are substituted")

    def __call__(self, e, arg_time):
        rep = {}
        for a in e.atoms(AppliedUndef):
            if a.func not in self.funcs:
                continue
            arg = a.args[0]
            if arg == arg_time:
                rep[a] = self.ysyms[self.index[a.func]]
            else:
                k = self.lag_index(sympy.simplify(arg_time - arg))
                rep[a] = self.zsyms[k][self.index[a.func]]
        return e.xreplace(rep)


def _aux_integrands(aux, to_symbols, ysyms, n) -> list:
    """g(x(ξ)) of every auxiliary state, as functions of an (m, n) array of states returning (m, 1)."""
    gsym = sympy.Dummy("xi")
    g_funcs = []
    for a in aux:
        ge = to_symbols(a.g.subs(a.var, gsym), gsym)
        gl = sympy.lambdify([gsym, *ysyms], ge, modules="numpy")
        g_funcs.append(lambda Y, gl=gl, n=n: np.broadcast_to(
            gl(0.0, *np.asarray(Y)[:, :n].T), (np.asarray(Y).shape[0],))[:, None])
    return g_funcs


def _quadrature_integrands(quads, to_symbols, ysyms) -> list:
    """(integrand(t, ξ, y), lower limit(t)) of every quadrature term."""
    out = []
    for q in quads:
        (var, lo, hi), = q.integral.limits
        integrand = to_symbols(q.integral.function, var)
        il = sympy.lambdify([t, var, *ysyms], integrand, modules="numpy")
        flo = sympy.lambdify([t], lo, modules="numpy")
        out.append((il, flo))
    return out


class _Lambdified:
    """``sympy.lambdify(args, exprs)`` (NumPy, CSE) made on the first call."""

    def __init__(self, args, exprs):
        self.args, self.exprs, self.f = args, exprs, None

    def __call__(self, *values):
        if self.f is None:
            self.f = sympy.lambdify(self.args, self.exprs, modules="numpy", cse=True, docstring_limit=0)
        return self.f(*values)


def _right_hand_side(f, quad_funcs, n_states: int, nl: int) -> Callable:
    def fun(tt, y, Z, past):
        qs = [_quad_now(il, float(flo(tt)), tt, y[:n_states], past) for il, flo in quad_funcs]
        zs = Z[:, :n_states].ravel() if nl else ()
        return np.asarray(f(tt, *y, *zs, *qs), dtype=float)

    return fun


def _check_integrable(K) -> None:
    """Refuse a memory kernel whose ∫_0^L |K| keeps growing with L (not integrable on [0, ∞))."""
    import warnings

    import scipy.integrate

    f = sympy.lambdify([_u], sympy.Abs(K), modules="numpy")
    vals = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for L in (1e2, 1e4, 1e6):
            edges = np.concatenate([[0.0], np.geomspace(1e-3, L, 60)])
            vals.append(sum(scipy.integrate.quad(f, a, b, limit=200)[0] for a, b in zip(edges[:-1], edges[1:])))
    if not np.all(np.isfinite(vals)) or vals[2] > 1.01 * vals[1] + 1e-12:
        raise InputError(f"kernel {K.subs(_u, sympy.Symbol('zeta'))} is not integrable on [0, ∞) "
                         f"(∫_0^L |K| = {vals[0]:.3g}, {vals[1]:.3g}, {vals[2]:.3g} for L = 1e2, 1e4, 1e6); "
                         f"fading memory needs an integrable kernel such as exp(-2*zeta)")


def _outer_integrals_all(exprs):
    return [i for e in exprs for i in _outer_integrals(e)]


def _quad_now(il, a, tt, y_now, past):
    """∫_a^tt integrand(tt, ξ, y(ξ)) dξ: the accepted history, then a trapezoid over the current step.

    The current-step piece is second order and outside the step-size control:
    cap ``max_step`` when a general kernel is present (:func:`simulate` does).
    """
    t_hist = min(tt, past.t_last)
    total = 0.0
    if t_hist > a:
        total = float(np.ravel(past.integrate(
            lambda s, Y: np.broadcast_to(il(tt, s, *np.asarray(Y)[:, :len(y_now)].T), np.shape(s)), a, t_hist,
            with_time=True))[0])
    if tt > t_hist:
        y_hist = np.asarray(past(t_hist)).ravel()[:len(y_now)]
        total += 0.5 * (tt - t_hist) * (il(tt, t_hist, *y_hist) + il(tt, tt, *y_now))
    return total


# -- grid names kept free (compile_family, linear_family) ------------------------------------------

_SCALAR = (ParameterKind.REAL, ParameterKind.POSITIVE, ParameterKind.NONNEGATIVE, ParameterKind.DELAY)


def _grid_substitution(system: System, values: dict, grid: tuple):
    """(grid symbols in grid order, the atom replacement of every other parameter)."""
    P = system.parameters
    if len(set(grid)) != len(grid):
        raise InputError(f"grid: expected distinct names, got {list(grid)}")
    for g in grid:
        if not (isinstance(g, str) and g.isidentifier()):
            raise InputError(f"grid: expected parameter names (identifiers), got {g!r}")
    symbols = {g: (P[g].obj if g in P else sympy.Symbol(g, real=True)) for g in grid}
    for g in grid:
        if g in P and P[g].kind not in _SCALAR:
            raise InputError(f"grid {g}: expected a scalar parameter, got a {P[g].kind.value}; sweep it through a "
                             f"scalar, e.g. values={{\"{g}\": \"diag(h,h,h)\"}} with grid=[\"h\"]")
    fixed, symbolic = {}, {}
    for k, v in values.items():
        if k in grid:
            if not (isinstance(v, sympy.Symbol) and v.name == k):
                raise InputError(f"{k}: a grid name has no fixed value, got {k}={v}; drop it from the values "
                                 f"(its value is a coordinate of each point)")
            continue
        v = _parse(v, k, symbols)
        if _free_names(v) & set(grid):
            symbolic[k] = v.xreplace({s: symbols[s.name] for s in _free(v) if s.name in symbols})
        else:
            fixed[k] = v
    used = set().union(*[_free_names(v) for v in symbolic.values()]) if symbolic else set()
    for g in grid:
        if g not in P and g not in used:
            scalars = ", ".join(s.name for s in P if s.kind in _SCALAR)
            matrix = next((s for s in P if s.shape is not None and s.shape[0] == s.shape[1]), None)
            example = (f"values={{\"{matrix.name}\": \"diag({','.join([g] * matrix.shape[0])})\"}}" if matrix
                       else f"values={{\"NAME\": \"2*{g}\"}}")
            raise InputError(f"grid {g}: expected a scalar parameter of the system "
                             f"({'one of ' + scalars if scalars else 'it has none'}) or a name used in a value, "
                             f"got neither; e.g. {example} with grid=[\"{g}\"]")
    for k in symbolic:
        if k not in P:
            raise InputError(f"{k}: no such parameter; known: {', '.join(P.names)}")
    resolved = P.resolve(fixed, use_defaults=True)
    sub = P.substitution({k: v for k, v in resolved.items() if k not in grid and k not in symbolic})
    for k, v in symbolic.items():
        spec = P[k]
        if spec.shape is not None:
            if not isinstance(v, sympy.MatrixBase) or v.shape not in (spec.shape, spec.shape[::-1]):
                raise InputError(f"{k}: expected a {spec.shape[0]}x{spec.shape[1]} matrix, got {v}")
            v = sympy.ImmutableMatrix(v.reshape(*spec.shape))
        elif isinstance(v, sympy.MatrixBase):
            raise InputError(f"{k}: expected a {spec.kind.value}, got a matrix {v}")
        sub.update(spec.substitution(v))
    return [symbols[g] for g in grid], sub


def _parse(v, name: str, symbols: dict):
    if isinstance(v, str):
        from ..declare.parse import parse_value

        return parse_value(v, name=name, variables={"t": t, "zeta": zeta, **symbols})
    if isinstance(v, (list, tuple, np.ndarray)):
        return sympy.ImmutableMatrix(v)
    return sympy.sympify(v)


def _free(v) -> set:
    return set(getattr(v, "free_symbols", set()))


def _free_names(v) -> set:
    return {s.name for s in _free(v)}
