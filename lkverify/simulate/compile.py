"""Simulation: the symbolic System integrated numerically.

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
  quadrature at every stage (``tests/test_simulate.py``, ``tests/test_dde.py``);
* memory integrals ``∫_{t0}^{t} K(t−ξ) g(x(ξ)) dξ`` with ``K`` a sum of exponentials
  ``Σ c_j e^{−a_j u}`` become exact auxiliary ODE states ``ṁ_j = c_j g(x(t)) − a_j m_j``;
  other kernels (and windows with weights depending on t) are computed by
  quadrature over the dense history plus a trapezoid over the current step;
* coefficients ``h(t)`` are evaluated as given.

The right-hand side is one ``lambdify``-generated function with common
subexpressions eliminated: about 20 µs per evaluation for the 12-dimensional
system of paper 000 (``benchmarks/bench_jitcdde.py``).

>>> import numpy as np
>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
>>> tr = simulate(sys, history={"x": [1]}, t_end=1.0)
>>> tr.outcome.value, abs(round(float(tr.states["x"][-1, 0]), 10))   # x = 1 − t on [0, 1]
('success', 0.0)
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from .solver import DDESolution, Outcome, solve_dde
from ..errors import InputError
from ..declare.functional import outer_integrals as _outer_integrals
from ..declare.parameters import apply_substitution
from ..declare.symbols import t
from ..declare.system import System

__all__ = ["CompiledSystem", "Trajectory", "compile_system", "simulate", "check_simulation", "MAX_STEPS"]

#: The step floor.  Steps are at most ``min(delays)`` long (the method of steps), so a run
#: needs at least ``(t_end − t0) / min(delays)`` steps: a run needing more than MAX_STEPS is
#: refused up front (a tiny delay, a huge t_end).  During a run, when the mean of the last
#: :data:`lkverify.simulate.solver.FLOOR_WINDOW` steps falls below ``(t_end − t0) / MAX_STEPS`` the run
#: stops: a blow-up (``diverged``) if ‖y‖ has grown, else a step collapse (a stiff system).
MAX_STEPS = 10**7

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
    aux : tuple
        Descriptions of the auxiliary states, in order.
    fun : callable
        ``fun(t, y, Z, past)`` → ẏ.
    symbolic : dict
        The generated right-hand side before compilation: ``rhs`` (SymPy expressions),
        ``y`` (state then auxiliary symbols), ``Z`` (lag symbols, one row per lag),
        ``t``, ``quadratures`` (placeholders of quadrature terms).  Other back ends
        (e.g. the jitcdde benchmark) translate from it.
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
    x = sympy.sympify(x)
    if x.free_symbols or not x.is_real:
        raise InputError(f"{what}: expected a number after substituting the parameters, got {x}")
    return float(x)


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
        A parameter the system needs has no value, a delay is not positive, a
        kernel is not integrable, or a term is of a kind the simulator does not take.
    """
    P = system.parameters
    checked = P.resolve(values or {}, use_defaults=True)
    sub = P.substitution(checked)
    funcs = system.state_functions()
    layout, n = {}, 0
    ysyms, index = [], {}
    for s in system.states:
        layout[s.name] = slice(n, n + s.dim)
        for i, f in enumerate(s.functions):
            index[f] = n + i
            ysyms.append(sympy.Dummy(f"y{n + i}"))
        n += s.dim
    rhs = []
    for s in system.states:
        col = apply_substitution(system.rhs(s), sub)
        rhs += list(col)
    missing = set().union(*[e.free_symbols for e in rhs]) - {t}
    missing = {m for m in missing if not any(m in i.variables for i in _outer_integrals_all(rhs))}
    if missing:
        names = sorted(str(m) for m in missing)
        raise InputError(f"{system.name or 'system'}: parameters without a value: {', '.join(names)}; "
                         f"pass them with --set NAME=VALUE")
    aux: list[_Aux] = []
    quads: list[_Quad] = []
    aux_expr: dict = {}
    quad_holders: dict = {}
    for I in dict.fromkeys(i for e in rhs for i in _outer_integrals(e)):
        if len(I.limits) != 1 or len(I.limits[0]) != 3:
            raise InputError(f"{system.name or 'system'}: the simulator integrates right-hand sides with single "
                             f"definite integrals; got {I}; write the inner integral as an auxiliary state")
        (var, lo, hi), = I.limits
        g = I.function
        width = sympy.simplify(hi - lo)
        if integrals not in ("auto", "quadrature"):
            raise InputError(f"integrals: expected 'auto' or 'quadrature', got {integrals!r}")
        if integrals == "quadrature":
            quads.append(_Quad(I))
            quad_holders[I] = sympy.Dummy(f"q{len(quads)}")
            continue
        if hi == t and not width.free_symbols:
            c = _numeric(width, f"window of {I}")
            if c <= 0:
                raise InputError(f"window length must be positive, got {c} in {I}")
            if t not in g.free_symbols:
                aux.append(_Aux("window", I, c, g, var))
                aux_expr[I] = sympy.Dummy(f"z{len(aux)}")
                continue
        if hi == t and not lo.free_symbols:
            split = _split_kernel(g, var, funcs)
            if split is not None:
                exps = [(_exponential_terms(K), gg) for K, gg in split]
                if all(e is not None for e, _ in exps):
                    total = sympy.S.Zero
                    for terms, gg in exps:
                        for coeff, rate in terms:
                            aux.append(_Aux("exponential memory", I, rate, gg, var, coeff, _numeric(lo, "lower limit")))
                            d = sympy.Dummy(f"m{len(aux)}")
                            aux_expr.setdefault(("m", len(aux)), d)
                            total += d
                    aux_expr[I] = total
                    continue
                for K, _ in split:
                    _check_integrable(K)
        quads.append(_Quad(I))
        quad_holders[I] = sympy.Dummy(f"q{len(quads)}")
    # lags
    lag_values = []
    for e in rhs + [a.g for a in aux]:
        for a in e.atoms(AppliedUndef):
            if a.func in funcs and a.args[0] != t:
                c = sympy.simplify(t - a.args[0])
                if t in c.free_symbols:
                    continue  # inside an integral, handled there
                lag_values.append(_numeric(c, f"delay of {a}"))
    lags = tuple(sorted(set(round(v, 15) for v in lag_values if v != 0)))
    for c in lags:
        if c <= 0:
            raise InputError(f"delays must be positive, got {c}")
    for a in aux:
        if a.kind == "window" and a.lag not in lags:
            lags = tuple(sorted(set(lags) | {a.lag}))
    zsyms = [[sympy.Dummy(f"Z{k}_{i}") for i in range(n)] for k in range(len(lags))]

    def states_to_symbols(e, arg_time):
        """Replace state applications by y/Z symbols."""
        rep = {}
        for a in e.atoms(AppliedUndef):
            if a.func not in funcs:
                continue
            arg = a.args[0]
            if arg == arg_time:
                rep[a] = ysyms[index[a.func]]
            else:
                c = float(sympy.simplify(arg_time - arg))
                k = min(range(len(lags)), key=lambda j: abs(lags[j] - c))
                rep[a] = zsyms[k][index[a.func]]
        return e.xreplace(rep)

    # right-hand side of the states
    exprs = []
    for e in rhs:
        e = e.xreplace({I: aux_expr[I] for I in aux_expr if isinstance(I, sympy.Integral)})
        e = e.xreplace(quad_holders)
        exprs.append(states_to_symbols(e, t))
    # auxiliary right-hand sides
    aux_syms = []
    mcount = 0
    for k, a in enumerate(aux):
        if a.kind == "window":
            sym = aux_expr[a.integral]
            dz = a.g.subs(a.var, t) - a.g.subs(a.var, t - a.lag)
            exprs.append(states_to_symbols(dz, t))
        else:
            sym = aux_expr[("m", k + 1)]
            exprs.append(states_to_symbols(a.coeff * a.g.subs(a.var, t), t) - a.lag * sym)
        aux_syms.append(sym)
    args = [t, *ysyms, *aux_syms, *[z for row in zsyms for z in row], *quad_holders.values()]
    f = sympy.lambdify(args, exprs, modules="numpy", cse=True)
    # g(x(ξ)) for auxiliaries, as functions of an (m, n) array of states
    gsym = sympy.Dummy("xi")
    g_funcs = []
    for a in aux:
        ge = states_to_symbols(a.g.subs(a.var, gsym), gsym)
        gl = sympy.lambdify([gsym, *ysyms], ge, modules="numpy")
        g_funcs.append(lambda Y, gl=gl, n=n: np.broadcast_to(
            gl(0.0, *np.asarray(Y)[:, :n].T), (np.asarray(Y).shape[0],))[:, None])
    quad_funcs = []
    for q in quads:
        (var, lo, hi), = q.integral.limits
        integrand = states_to_symbols(q.integral.function, var)
        il = sympy.lambdify([t, var, *ysyms], integrand, modules="numpy")
        flo = sympy.lambdify([t], lo, modules="numpy")
        quad_funcs.append((il, flo))
    n_states = n
    nl = len(lags)

    def fun(tt, y, Z, past):
        qs = []
        for il, flo in quad_funcs:
            qs.append(_quad_now(il, float(flo(tt)), tt, y[:n_states], past))
        zs = Z[:, :n_states].ravel() if nl else ()
        return np.asarray(f(tt, *y, *zs, *qs), dtype=float)

    symbolic = {"rhs": exprs, "y": ysyms + aux_syms, "Z": zsyms, "t": t, "quadratures": list(quad_holders.values())}
    return CompiledSystem(system, layout, n_states, lags, tuple(aux), tuple(quads), fun, tuple(g_funcs),
                          tuple(quad_funcs), symbolic)


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


@dataclasses.dataclass(frozen=True)
class Trajectory:
    """A simulated solution.

    Attributes
    ----------
    outcome : Outcome
        success, diverged or step-size collapse.
    message : str
    t : ndarray
        Output times.
    states : dict
        state name → array (len(t), dim).
    t_fail : float or None
    constraint_drift : dict
        constraint name → max |defect| along the run (‖s‖ − 1, frame orthonormality).
    nfev, n_steps : int
    seconds : float
    solution : DDESolution
        The integrator's full output (dense ``sol``).
    """

    system_name: str
    outcome: Outcome
    message: str
    t: np.ndarray
    states: dict
    t_fail: float | None
    constraint_drift: dict
    nfev: int
    n_steps: int
    seconds: float
    solution: DDESolution
    layout: dict

    def at(self, times) -> dict:
        """Dense values of every state at ``times`` (array)."""
        Y = np.atleast_2d(self.solution.sol(np.atleast_1d(np.asarray(times, dtype=float))))
        return {name: Y[:, sl] for name, sl in self.layout.items()}


def _example_history(s) -> str:
    comps = ",".join(["0.1"] * s.dim)
    return f"--history {s.name}={comps if s.dim == 1 else '[' + comps + ']'}"


def _history_function(system: System, history: Mapping[str, object], layout: dict, n: int):
    """The initial history as phi(s) → state vector (validated)."""
    known = {s.name: s for s in system.states}
    unknown = set(history) - set(known)
    if unknown:
        raise InputError(f"history for unknown state(s) {', '.join(sorted(unknown))}: expected one of the states "
                         f"{', '.join(sorted(known))}; fix the name (e.g. {_example_history(system.states[0])})")
    missing = set(known) - set(history)
    if missing:
        raise InputError(f"no history given for state(s) {sorted(missing)}; give a constant vector or a function of t")
    parts = []
    for s in system.states:
        h = history[s.name]
        if isinstance(h, (int, float, np.number)) or (isinstance(h, sympy.Basic) and not isinstance(h, sympy.MatrixBase)):
            if s.dim != 1:
                raise InputError(f"history of {s.name}: expected {s.dim} components (a vector), got the scalar "
                                 f"{h}; pass e.g. {_example_history(s)}")
            h = [h]
        if callable(h) and not isinstance(h, sympy.Basic):
            fn = h
        else:
            if isinstance(h, str) or (isinstance(h, (list, tuple)) and any(isinstance(x, str) for x in h)):
                from ..declare.parse import parse_value

                h = [parse_value(x, name=f"history of {s.name}", variables={"t": t}) if isinstance(x, str) else x
                     for x in (h if isinstance(h, (list, tuple)) else [h])]
                h = h[0] if len(h) == 1 and isinstance(h[0], sympy.MatrixBase) else h
            try:
                m = sympy.Matrix(h) if not isinstance(h, sympy.MatrixBase) else h
            except (TypeError, ValueError, sympy.SympifyError):
                raise InputError(f"history of {s.name}: expected {s.dim} numbers, got {h!r}; pass e.g. "
                                 f"{_example_history(s)}") from None
            if m.shape not in ((s.dim, 1), (1, s.dim)):
                raise InputError(f"history of {s.name}: expected {s.dim} components, got shape {m.shape}; "
                                 f"pass e.g. {_example_history(s)}")
            extra = m.free_symbols - {t}
            if extra:
                raise InputError(f"history of {s.name}: expected an expression in t only, got symbols {sorted(map(str, extra))}")
            if m.free_symbols:
                lf = sympy.lambdify([t], list(m), modules="numpy")
                fn = lambda s_, lf=lf: np.asarray(lf(s_), dtype=float)  # noqa: E731
            else:
                const = np.array([float(v) for v in m], dtype=float)
                fn = lambda s_, c=const: c  # noqa: E731
        v = np.asarray(fn(0.0), dtype=float).ravel()
        if v.shape != (s.dim,):
            raise InputError(f"history of {s.name}: expected {s.dim} components, got {v.size}; "
                             f"pass e.g. {_example_history(s)}")
        if not np.all(np.isfinite(v)):
            raise InputError(f"history of {s.name}: not finite at t0: {v}")
        parts.append((layout[s.name], fn))
    frames = []
    for s in system.states:
        if s.frame is not None and s.frame not in frames:
            frames.append(s.frame)
            M = np.column_stack([np.asarray(dict((st.name, f) for (sl, f), st in zip(parts, system.states))[v.name](0.0),
                                            dtype=float).ravel() for v in s.frame.vectors])
            defect = float(np.max(np.abs(M.T @ M - np.eye(3))))
            det = float(np.linalg.det(M))
            if defect > 1e-9 or det < 0:
                raise InputError(f"initial frame {[v.name for v in s.frame.vectors]} is not orthonormal and right-handed: "
                                 f"max|RᵀR − I| = {defect:.3g}, det = {det:.6g}; normalise it (e.g. from angles)")
        elif s.unit and s.frame is None:
            v = np.asarray(dict((st.name, f) for (sl, f), st in zip(parts, system.states))[s.name](0.0), dtype=float).ravel()
            if abs(np.linalg.norm(v) - 1) > 1e-9:
                raise InputError(f"initial {s.name} is not a unit vector: ‖{s.name}‖ = {np.linalg.norm(v):.12g}")

    def phi(s_):
        y = np.zeros(n)
        for sl, fn in parts:
            y[sl] = np.asarray(fn(s_), dtype=float).ravel()
        return y

    return phi


def _monitors(system: System, layout: dict) -> dict:
    mons = {}
    frames = []
    for s in system.states:
        if s.frame is not None:
            if s.frame in frames:
                continue
            frames.append(s.frame)
            sls = [layout[v.name] for v in s.frame.vectors]
            name = "frame " + ",".join(v.name for v in s.frame.vectors)
            mons[name] = lambda tt, y, sls=sls: float(np.max(np.abs(
                np.column_stack([y[sl] for sl in sls]).T @ np.column_stack([y[sl] for sl in sls]) - np.eye(3))))
        elif s.unit:
            sl = layout[s.name]
            mons[f"‖{s.name}‖−1"] = lambda tt, y, sl=sl: float(np.linalg.norm(y[sl]) - 1.0)
    return mons


def _check_coefficients(system: System, checked: Mapping, lo: float, hi: float) -> None:
    """Refuse a time-varying coefficient that is not finite (or not real) somewhere on [lo, hi]."""
    from ..declare.parameters import Kind

    grid = np.unique(np.concatenate([np.linspace(lo, hi, 4001), [lo, 0.0, hi]] if lo <= 0 <= hi
                                    else [np.linspace(lo, hi, 4001), [lo, hi]]))
    for spec in system.parameters:
        if spec.kind is not Kind.COEFFICIENT or spec.name not in checked:
            continue
        value = checked[spec.name]
        bad = None
        try:
            f = sympy.lambdify([t], value, modules="numpy")
            with np.errstate(all="ignore"):
                vals = np.broadcast_to(np.asarray(f(grid)), grid.shape)
            if np.iscomplexobj(vals):
                nonreal = np.abs(np.imag(vals)) > 0
                vals = np.where(nonreal, np.nan, np.real(vals))
            vals = vals.astype(float)
            idx = np.nonzero(~np.isfinite(vals))[0]
            if idx.size:
                bad = float(grid[idx[0]])
        except (ZeroDivisionError, OverflowError, ValueError, TypeError, FloatingPointError):
            bad = lo
        if bad is not None:
            raise InputError(f"{spec.name}: expected a coefficient finite and real on the simulated horizon "
                             f"[{lo:g}, {hi:g}], got {spec.name}(t) = {value}, which is not at t = {bad:.6g}; "
                             f"pass a function defined on the whole horizon, e.g. --set \"{spec.name}=1/(1+t)\"")


def check_simulation(system: System, *, history: Mapping[str, object], t_end: float,
                     values: Mapping[str, object] | None = None, t0: float = 0.0, max_step: float = np.inf,
                     integrals: str = "auto"):
    """Validate a run before integrating it; returns ``(compiled, phi, max_step)``.

    Checks the parameter values, that every time-varying coefficient is finite on the
    horizon ``[t0 − max delay, t_end]``, the initial history, and the step floor:
    steps are at most ``min(delays)`` (and ``max_step``) long, so a run needing more
    than :data:`MAX_STEPS` steps is refused.

    Raises
    ------
    InputError
        With the reason (one line).
    """
    if not (isinstance(t_end, (int, float)) and np.isfinite(t_end)) or t_end <= t0:
        raise InputError(f"t_end: expected a number greater than t0 = {t0}, got {t_end}")
    comp = compile_system(system, values, integrals=integrals)
    checked = system.parameters.resolve(values or {}, use_defaults=True)
    _check_coefficients(system, checked, t0 - (max(comp.lags) if comp.lags else 0.0), float(t_end))
    phi = _history_function(system, history, comp.layout, comp.n_states)
    if comp.quads:
        max_step = min(max_step, 0.05)  # the current-step piece of a general kernel is not error-controlled
    cap = min([max_step, *comp.lags])
    if np.isfinite(cap):
        needed = (t_end - t0) / cap
        if needed > MAX_STEPS:
            why = (f"the shortest delay {min(comp.lags):g}" if comp.lags and cap == min(comp.lags)
                   else f"the largest step {cap:g}")
            raise InputError(f"system {system.name or ''}: a run to t_end = {t_end:g} needs at least {needed:.3g} "
                             f"steps (steps are at most {why} long); expected at most {MAX_STEPS:.0e} (the step "
                             f"floor); shorten --t-end or lengthen the delay")
    return comp, phi, max_step


def simulate(system: System, *, history: Mapping[str, object], t_end: float, values: Mapping[str, object] | None = None,
             t0: float = 0.0, rtol: float = 1e-8, atol: float = 1e-10, method: str = "DOP853",
             divergence_bound: float = 1e8, max_step: float = np.inf, t_eval=None,
             progress: Callable[[float], None] | None = None, integrals: str = "auto",
             deadline=None) -> Trajectory:
    """Integrate ``system`` from the initial ``history`` on [t0 − τ, t0] to ``t_end``.

    Parameters
    ----------
    system : System
    history : mapping
        state name → constant vector, a callable of t, or a SymPy vector in t.
    t_end : float
    values : mapping, optional
        Parameter values (name → value or string); the paper's defaults fill in.
    t0, rtol, atol, method, divergence_bound, max_step, t_eval, progress
        Passed to :func:`lkverify.simulate.solver.solve_dde`.
    integrals : {"auto", "quadrature"}
        See :func:`compile_system`.
    deadline : lkverify.options.Deadline, optional
        When it passes the run stops with outcome ``budget`` (incomplete, undecided).

    The step floor (:data:`MAX_STEPS` = 1e7): a run that needs more than 1e7 steps
    because steps are capped at the shortest delay is refused up front; a run whose
    last 200 steps average less than ``(t_end − t0)/1e7`` stops with outcome
    ``diverged`` (a blow-up: ‖y‖ grew 1000-fold) or ``step_collapse`` (stiff).

    Returns
    -------
    Trajectory
        With an outcome (never an exception for numerical trouble).

    Raises
    ------
    InputError
        Bad values, a coefficient not finite on the horizon, a bad history, or a run
        needing more steps than the floor allows (see :func:`check_simulation`).
    """
    comp, phi, max_step = check_simulation(system, history=history, t_end=t_end, values=values, t0=t0,
                                           max_step=max_step, integrals=integrals)
    n_aux = len(comp.aux)
    aux0 = np.zeros(n_aux)

    def full_history(s_):
        return np.concatenate([phi(s_), aux0]) if n_aux else phi(s_)

    if n_aux:
        aux0[:] = comp.aux_initial(t0, _InitialPast(full_history, t0))
    start = time.monotonic()
    sol = solve_dde(comp.fun, (t0, t_end), full_history, lags=comp.lags, method=method, rtol=rtol, atol=atol,
                    max_step=max_step, divergence_bound=divergence_bound, t_eval=t_eval,
                    resync=comp.resync if any(a.kind == "window" for a in comp.aux) else None,
                    monitors=_monitors(system, comp.layout), progress=progress, deadline=deadline,
                    min_mean_step=(t_end - t0) / MAX_STEPS)
    seconds = time.monotonic() - start
    if t_eval is not None and sol.y_eval is not None:
        times, Y = np.asarray(sol.t_eval), np.asarray(sol.y_eval)
        keep = times <= sol.t[-1] + 1e-12
        times, Y = times[keep], Y[keep]
    else:
        times, Y = sol.t, sol.y
    states = {name: Y[:, sl] for name, sl in comp.layout.items()}
    drift = {name: float(v) for name, v in sol.monitor_max.items()}
    return Trajectory(system.name, sol.outcome, sol.message, times, states, sol.t_fail, drift, sol.nfev,
                      sol.n_steps, seconds, sol, dict(comp.layout))


class _InitialPast:
    """The initial history seen as a 'past' for quadrature at t0 (before any step)."""

    def __init__(self, phi, t0):
        self.phi, self.t_last = phi, t0

    def __call__(self, s_):
        return np.array([self.phi(x) for x in np.atleast_1d(s_)])

    def integrate(self, g, a, b, *, with_time=False):
        nodes, weights = np.polynomial.legendre.leggauss(32)
        edges = np.linspace(a, b, 17)
        total = 0.0
        for lo, hi in zip(edges[:-1], edges[1:]):
            s_ = 0.5 * (hi - lo) * nodes + 0.5 * (hi + lo)
            Y = self(s_)
            vals = np.asarray(g(s_, Y) if with_time else g(Y), dtype=float).reshape(len(s_), -1)
            total = total + 0.5 * (hi - lo) * (weights @ vals)
        return np.atleast_1d(total)
