"""Compile once, run many: a System compiled with some parameters left as runtime arguments.

:func:`compile_family` does the SymPy work of :func:`~lkverify.simulate.compile.compile_system`
once for a whole family of parameter points: the names in ``grid`` stay symbolic and
become the argument ``p`` of a generated right-hand side::

    def rhs(t, y, Z, p, out)     # y: states then auxiliary states, Z: (n_lags, n_states) delayed states

written as Python source (common subexpressions eliminated by ``sympy.cse``, printed for
the ``math`` module) and compiled with numba on first use in each process.  A
:class:`CompiledFamily` holds the source and SymPy data only, so it pickles with plain
:mod:`pickle` (a sweep ships it to its Dask workers), and
:meth:`CompiledFamily.integrate` runs many points with the numba integrator of
:mod:`lkverify.simulate.batch`.

What ``compile_system`` does per run is done here once: the same layout, window integrals
as auxiliary states ``ż = g(x(t)) − g(x(t−c))``, sum-of-exponential memory kernels as
auxiliary ODE states (shared helpers of :mod:`lkverify.simulate.compile`).  Lags are
expressions in the grid symbols (``tau``, ``2*tau/3``); two lags are one when they are the
same expression after the fixed values are substituted.  Quadrature terms (general
kernels) are not supported here: :class:`~lkverify.errors.UnsupportedInput` (run such a
system point by point with :func:`~lkverify.simulate.runs.simulate`).

Examples
--------
``x' = −a x(t − τ)`` with ``a`` and ``τ`` swept:

>>> import numpy as np
>>> from lkverify import Parameters, Vector, System, Equation, Term, t
>>> P = Parameters(); a = P.scalar("a", positive=True, default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)
>>> fam = compile_family(sys, grid=("a", "tau"))
>>> fam.exact_lags, fam.lags([2.0, 0.5]).tolist()
((tau,), [0.5])
>>> res = fam.integrate(np.array([[1.0, 1.0], [2.0, 0.5]]), {"x": [1]}, t_end=1.0, t_eval=[0.5, 1.0])
>>> (res.y[:, :, 0].round(10) + 0.0).tolist()     # x = 1 − a t on [0, τ]; a = 2, τ = 1/2: x(1) = −2∫_{1/2}^1 (2 − 2s) ds
[[0.5, 0.0], [0.0, -0.5]]
"""

from __future__ import annotations

import dataclasses
import hashlib
import threading
from collections.abc import Mapping, Sequence

import numpy as np
import sympy
from sympy.printing.codeprinter import PrintMethodNotImplementedError
from sympy.printing.pycode import PythonCodePrinter

from ..declare.symbols import t
from ..declare.system import System
from ..errors import InputError, UnsupportedInput
from ..memo import Memo
from .compile import _parse, symbolic_system

__all__ = ["CompiledFamily", "compile_family"]



@dataclasses.dataclass(frozen=True, eq=False)
class CompiledFamily:
    """A System compiled with the parameters ``grid`` as runtime arguments.

    Attributes
    ----------
    name : str
        The system's name.
    grid : tuple of str
        The runtime parameters, in the order of a point's coordinates.
    grid_symbols : tuple of sympy.Symbol
        The symbols standing for them in :attr:`exact_lags` and :attr:`rhs`.
    layout : dict
        state name → slice of the state vector (auxiliary states follow the states).
    n_states, n : int
        Number of state components; with the auxiliary states.
    aux : tuple of (str, str)
        (kind, detail) of every auxiliary state: ``("window", length)`` or
        ``("exponential memory", "rate r, weight w, from lower")``.
    exact_lags : tuple of SymPy expressions
        The distinct lags, in the grid symbols.
    rhs : tuple of SymPy expressions
        The right-hand side the source was generated from (in ``y_i``, ``Z_k_i``, ``p_j``, ``t``).
    source : str
        Python source of ``rhs(t, y, Z, p, out)`` and ``win(t, y, Z, p, g)`` (``Z`` flat, the fallback
        compiled by numba), ``lags(p)`` and ``aux_start(t0, p, x)``.
    windows : tuple of (int, int)
        Every window auxiliary state as (its component in the state vector, the index of its length
        in :attr:`exact_lags`): the integrator re-synchronises them by quadrature.
    native : str or None
        LLVM IR of ``rhs`` and ``win`` (:mod:`lkverify.simulate.native`), ``None`` when an expression
        has no native form (then numba compiles :attr:`source`).

    Examples
    --------
    A window integral of length τ becomes one auxiliary state; its initial value is
    τ·g(x0) for a constant history:

    >>> import sympy
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); tau = P.delay("tau", default=1); x = Vector("x", 1); s = sympy.Symbol("s")
    >>> sys = System([Equation(x, [Term(-sympy.Integral(x(s)[0] ** 2, (s, t - tau, t)))])], parameters=P)
    >>> fam = compile_family(sys, grid=["tau"])
    >>> fam.aux, fam.n_states, fam.n
    ((('window', 'tau'),), 1, 2)
    >>> fam.initial_state([0.5], {"x": [3]}).tolist()
    [3.0, 4.5]
    >>> import pickle; pickle.loads(pickle.dumps(fam)).lags([0.5]).tolist()
    [0.5]
    """

    name: str
    grid: tuple
    grid_symbols: tuple
    layout: dict
    n_states: int
    n: int
    aux: tuple
    exact_lags: tuple
    rhs: tuple
    source: str
    windows: tuple = ()
    native: str | None = None

    @property
    def key(self) -> str:
        """SHA-256 of :attr:`source` and :attr:`native`: the key of the per-process cache of compiled functions."""
        return hashlib.sha256((self.source + "\n" + (self.native or "")).encode()).hexdigest()

    def functions(self):
        """``(rhs, win, lags, aux_start)``: the native (or numba) ``rhs`` and ``win``, and the plain Python
        helpers (compiled once per process)."""
        return _compiled(self.source, self.native, self.key)

    @property
    def backend(self) -> str:
        """``"native"`` (LLVM IR compiled by llvmlite) or ``"numba"`` (the Python source, when no native form)."""
        return "native" if self.native is not None else "numba"

    def lags(self, p) -> np.ndarray:
        """The lags (floats) at the point ``p`` (one value per grid name)."""
        return np.array(self.functions()[2](self._point(p)), dtype=float)

    def initial_state(self, p, history: Mapping[str, object], *, t0: float = 0.0) -> np.ndarray:
        """The full initial vector at the point ``p``: the constant history, then the auxiliary states.

        A window ``∫_{t0−c}^{t0} g(x)`` starts at ``c·g(x0)`` (exact for a constant history); an
        exponential memory ``∫_{lo}^{t0} w e^{−r(t0−ξ)} g(x(ξ)) dξ`` at
        ``w g(x0) (1 − e^{−r(t0−lo)})/r`` (0 when the lower limit is ``t0``).

        Raises
        ------
        UnsupportedInput
            A history that is not constant (a function of t).
        InputError
            An unknown or missing state, or a vector of the wrong length.
        """
        x0 = self.constant_history(history)
        return np.concatenate([x0, self.aux_start(p, x0, t0=t0)])

    def aux_start(self, p, x0, *, t0: float = 0.0) -> np.ndarray:
        """The auxiliary states' initial values at the point ``p`` for the constant history ``x0`` (states)."""
        aux = np.asarray(self.functions()[3](float(t0), self._point(p), np.asarray(x0, dtype=float)), dtype=float)
        if np.isnan(aux).any():
            raise UnsupportedInput(f"{self.name}: a memory integral whose integrand depends on the integration "
                                   f"variable itself starts before t0 = {t0:g}; start at its lower limit, or "
                                   f"simulate it with simulate()")
        return aux

    def constant_history(self, history: Mapping[str, object]) -> np.ndarray:
        """The states of a constant history as one vector (layout order); see :meth:`initial_state`."""
        return _constant_history(history, self.layout, self.n_states)

    def integrate(self, points, history: Mapping[str, object] | Sequence[Mapping], *, t_end: float, t_eval, rtol: float = 1e-8,
                  atol: float = 1e-10, divergence_bound: float = 1e8, max_steps: int = 10**6, t0: float = 0.0):
        """Integrate every point of ``points`` (an (N, len(grid)) array); see :func:`lkverify.simulate.batch.integrate`."""
        from .batch import integrate

        return integrate(self, points, history, t_end=t_end, t_eval=t_eval, rtol=rtol, atol=atol,
                         divergence_bound=divergence_bound, max_steps=max_steps, t0=t0)

    def _point(self, p) -> np.ndarray:
        p = np.ascontiguousarray(np.asarray(p, dtype=float).ravel())
        if p.shape != (len(self.grid),):
            raise InputError(f"point: expected {len(self.grid)} values ({', '.join(self.grid)}), got {p.size}")
        return p


def compile_family(system: System, values: Mapping[str, object] | None = None, *, grid: Sequence[str],
                   integrals: str = "auto") -> CompiledFamily:
    """Compile ``system`` once with the names ``grid`` left as runtime parameters.

    Parameters
    ----------
    system : System
    values : mapping, optional
        The other parameters: name → value (strings or SymPy, exact, as
        :meth:`~lkverify.declare.parameters.Parameters.resolve` takes them); the paper's
        defaults fill in.  A value may contain free grid names (e.g. ``F = diag(h,h,h)``
        with ``grid=("b", "h")``): it is substituted symbolically and not validated (per
        point validation is the caller's job).  A swept parameter may appear as its own
        symbol (``{"b": Symbol("b")}``).
    grid : sequence of str, keyword-only
        Scalar parameters of the system or free names used in ``values``, in the order of
        a point's coordinates.
    integrals : {"auto"}
        Windows and exponential kernels as auxiliary states; ``"quadrature"`` is refused.

    Raises
    ------
    UnsupportedInput
        A quadrature term (general kernel, time-varying window), or a function the code
        printer does not know.
    InputError
        An unknown name, a grid name that is neither a scalar parameter nor used in a value,
        a parameter without a value, a delay that is not an expression in the grid names.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> P = Parameters(); F = P.spd_matrix("F", 2, default=sympy.eye(2)); x = Vector("x", 2)
    >>> sys = System([Equation(x, [Term(-F * x(t - 1))])], parameters=P)
    >>> h = sympy.Symbol("h")
    >>> fam = compile_family(sys, {"F": sympy.diag(h, 2 * h)}, grid=["h"])
    >>> fam.rhs, fam.exact_lags
    ((-Z_0_0*p_0, -2*Z_0_1*p_0), (1,))
    >>> compile_family(sys, grid=["k"])
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: grid k: expected a scalar parameter of the system (it has none) or a name used in a value, got neither; e.g. values={"F": "diag(k,k)"} with grid=["k"]
    """
    if integrals != "auto":
        raise InputError(f"integrals: expected 'auto' (the fast path has no quadrature), got {integrals!r}; "
                         f"use simulate(..., integrals={integrals!r}) for the reference path")
    name = system.name or "system"
    sym = symbolic_system(system, values, grid=tuple(grid))
    symbols, sr = list(sym.symbols), sym.rhs
    if sr.quads:
        raise UnsupportedInput(f"{name}: the compiled family integrates windows and sums of exponential kernels "
                               f"as auxiliary states; got {len(sr.quads)} quadrature term(s) such as "
                               f"{sr.quads[0].integral}; simulate such a system point by point with simulate()")
    names = _print_names(sr, symbols)
    exprs = tuple(e.xreplace(names) for e in sr.exprs)
    lags = tuple(c.xreplace(names) for c in sr.exact_lags)
    starts = _aux_starts(sr, names)
    windows, integrands = _windows(sr, names, lags)
    allowed = set(names.values()) | {t, _T0} | set(_x0_symbols(sr.n_states))
    for e in exprs + lags + tuple(starts) + tuple(integrands):
        extra = e.free_symbols - allowed
        if extra:
            raise InputError(f"{name}: symbols {sorted(map(str, extra))} left after substituting the values; "
                             f"expected a value for every parameter, or its name in grid")
    source = _source(exprs, integrands, lags, starts, sr.n_states, len(sr.exprs), len(symbols),
                     len(sr.exact_lags), name)
    aux = tuple((a.kind, str(a.exact_lag) if a.kind == "window" else
                 f"rate {a.lag:g}, weight {a.coeff:g}, from {a.lower:g}") for a in sr.aux)
    return CompiledFamily(name, tuple(grid), tuple(symbols), dict(sr.layout), sr.n_states, len(sr.exprs), aux,
                          sr.exact_lags, exprs, source, windows,
                          _native(exprs, integrands, len(sr.exprs), sr.n_states, len(sr.exact_lags), len(symbols)))


# -- code generation ---------------------------------------------------------------

_T0 = sympy.Symbol("t0", real=True)


def _x0_symbols(n: int) -> list:
    return [sympy.Symbol(f"x_{i}", real=True) for i in range(n)]


def _print_names(sr, grid_symbols) -> dict:
    """SymPy symbol → a symbol with the name the generated source uses."""
    names = {s: sympy.Symbol(f"y_{i}", real=True) for i, s in enumerate([*sr.ysyms, *sr.aux_syms])}
    for k, row in enumerate(sr.zsyms):
        names.update({s: sympy.Symbol(f"Z_{k}_{i}", real=True) for i, s in enumerate(row)})
    names.update({s: sympy.Symbol(f"p_{j}", real=True) for j, s in enumerate(grid_symbols)})
    return names


def _aux_starts(sr, names) -> list:
    """Initial value of every auxiliary state for a constant history x(ξ) = x0 (in t0, x_i, p_j)."""
    x0 = _x0_symbols(sr.n_states)
    to_x0 = {y: x0[i] for i, y in enumerate(sr.ysyms)}
    to_x0.update({z: x0[i] for row in sr.zsyms for i, z in enumerate(row)})    # constant history: x(ξ − c) = x0
    out = []
    for a in sr.aux:
        g0 = sr.to_symbols(a.g.subs(a.var, t), t).xreplace(to_x0).xreplace(names)
        if a.kind == "window":
            out.append(a.exact_lag.xreplace(names) * g0)
        elif t in g0.free_symbols:      # an integrand depending on ξ itself: only the empty start is known
            out.append(sympy.Piecewise((0, _T0 <= sympy.Float(a.lower)), (sympy.nan, True)))
        else:
            span = sympy.Max(0, _T0 - sympy.Float(a.lower))
            out.append(sympy.Float(a.coeff) * g0 * (1 - sympy.exp(-sympy.Float(a.lag) * span)) / sympy.Float(a.lag))
    return out


def _windows(sr, names, lags) -> tuple:
    """((component, lag index) of every window auxiliary state, their integrands in ``y_i``, ``p_j``)."""
    windows, integrands = [], []
    for k, a in enumerate(sr.aux):
        if a.kind != "window":
            continue
        length = a.exact_lag.xreplace(names)
        index = next((j for j, c in enumerate(lags) if sympy.simplify(c - length) == 0), None)
        if index is None:   # not expected: the window's ODE reads x(t − c), so c is one of the lags
            raise UnsupportedInput(f"window {a.integral}: its length {length} is not one of the lags {lags}")
        windows.append((sr.n_states + k, index))
        integrands.append(sr.to_symbols(a.g.subs(a.var, t), t).xreplace(names))
    return tuple(windows), integrands


def _native(exprs, integrands, n: int, n_states: int, n_lags: int, n_grid: int) -> str | None:
    """LLVM IR of ``rhs`` and ``win`` (:func:`lkverify.simulate.native.native_source`), or None."""
    from .native import NotPrintable, native_source

    arguments = {sympy.Symbol(f"y_{i}", real=True): ("y", i) for i in range(n)}
    arguments.update({sympy.Symbol(f"Z_{k}_{i}", real=True): ("Z", k * n_states + i)
                      for k in range(n_lags) for i in range(n_states)})
    arguments.update({sympy.Symbol(f"p_{j}", real=True): ("p", j) for j in range(n_grid)})
    try:
        return native_source({"rhs": exprs, "win": integrands}, arguments, time=t)
    except NotPrintable:
        return None


class _Printer(PythonCodePrinter):
    """Python (math module) code; floats printed with all their digits."""

    def _print_Float(self, expr):
        return repr(float(expr))


def _source(exprs, integrands, lags, starts, n_states: int, n: int, n_grid: int, n_lags: int, name: str) -> str:
    """The module source: ``rhs`` and ``win`` (common subexpressions eliminated; Z flat), ``lags``, ``aux_start``."""
    printer = _Printer({"fully_qualified_modules": True, "strict": True})
    unpack = [f"    y_{i} = y[{i}]" for i in range(n)]
    unpack += [f"    Z_{k}_{i} = Z[{k * n_states + i}]" for k in range(n_lags) for i in range(n_states)]
    unpack += [f"    p_{j} = p[{j}]" for j in range(n_grid)]
    unpack_win = [line for line in unpack if not line.startswith("    y_")] + [f"    y_{i} = y[{i}]"
                                                                            for i in range(n_states)]

    def body(values, out):
        repl, reduced = sympy.cse(list(values), symbols=sympy.numbered_symbols("w_"), order="none")
        lines = [f"    {s} = {printer.doprint(e)}" for s, e in repl]
        return lines + [f"    {out}[{i}] = {printer.doprint(e)}" for i, e in enumerate(reduced)] or ["    pass"]

    try:
        rhs_body, win_body = body(exprs, "out"), body(integrands, "g")
        lag_text = ", ".join(printer.doprint(c) for c in lags)
        start_text = ", ".join(printer.doprint(e) for e in starts)
    except PrintMethodNotImplementedError as exc:
        raise UnsupportedInput(f"{name}: the compiled family cannot print a function of the right-hand side as "
                               f"Python ({str(exc).splitlines()[0]}); simulate it point by point with "
                               f"simulate()") from None
    params = [f"    p_{j} = p[{j}]" for j in range(n_grid)]
    states = [f"    x_{i} = x[{i}]" for i in range(n_states)]
    return "\n".join([
        f"# generated by lkverify.simulate.family for {name}", "import math", "",
        "def rhs(t, y, Z, p, out):", *unpack, *rhs_body, "", "",
        "def win(t, y, Z, p, g):", *unpack_win, *win_body, "", "",
        "def lags(p):", *params, f"    return ({lag_text}{',' if lags else ''})", "", "",
        "def aux_start(t0, p, x):", *params, *states, f"    return ({start_text}{',' if starts else ''})", ""])


# -- compiled functions, per process ------------------------------------------------------

_CACHE = Memo(64)  # key → compiled functions
_LOCK = threading.Lock()


def _compiled(source: str, native: str | None, key: str):
    """(rhs, win, Python lags, Python aux_start): native code of ``native``, else numba of ``source``; once per process."""
    with _LOCK:
        hit = _CACHE.get(key)
        if hit is None:
            namespace: dict = {}
            exec(compile(source, f"<lkverify family {key[:12]}>", "exec"), namespace)  # noqa: S102 - generated
            if native is not None:
                from .native import load

                funcs = load(native)
                rhs, win = funcs["rhs"], funcs["win"]
            else:
                rhs, win = (_numba_function(namespace[f]) for f in ("rhs", "win"))
            hit = (rhs, win, namespace["lags"], namespace["aux_start"])
            _CACHE[key] = hit
        return hit


def _numba_function(py_func):
    """``py_func(t, y, Z, p, out)`` compiled by numba as a C callback with pointer arguments (IEEE: x/0 is inf or nan)."""
    import numba
    from .dop853 import FUNCTION

    return numba.cfunc(FUNCTION.signature, error_model="numpy")(py_func)     # a C callback: also ``.ctypes``


def _constant_history(history: Mapping[str, object], layout: dict, n_states: int) -> np.ndarray:
    """The constant history as a state vector; UnsupportedInput for a function of t."""
    if not isinstance(history, Mapping):
        raise InputError(f"history: expected a mapping state name → constant vector, got {type(history).__name__}")
    unknown = set(history) - set(layout)
    missing = set(layout) - set(history)
    if unknown or missing:
        raise InputError(f"history: expected one constant vector for each state ({', '.join(layout)}), got "
                         f"{', '.join(map(str, history)) or 'none'}; e.g. {next(iter(layout))}=[0.1, ...]")
    x0 = np.empty(n_states)
    for state, sl in layout.items():
        h = history[state]
        dim = sl.stop - sl.start
        if callable(h) and not isinstance(h, sympy.Basic):
            raise UnsupportedInput(f"history of {state}: the compiled family takes constant histories, got a "
                                   f"function; simulate a non-constant history with simulate()")
        try:                                  # numbers and numeric arrays: no SymPy
            x = np.asarray(h, dtype=float).ravel()
        except (TypeError, ValueError):
            x = None
        if x is not None and x.size == dim and np.all(np.isfinite(x)):
            x0[sl] = x
            continue
        values = [h] if isinstance(h, (str, int, float, np.number, sympy.Expr)) else h
        try:
            values = [_parse(v, f"history of {state}", {}) if isinstance(v, str) else v
                      for v in np.asarray(values, dtype=object).ravel()]
            if len(values) == 1 and isinstance(values[0], sympy.MatrixBase):
                values = list(values[0])
            values = [sympy.sympify(v) for v in values]
        except (TypeError, ValueError, sympy.SympifyError):
            raise InputError(f"history of {state}: expected {dim} numbers, got {h!r}") from None
        if any(v.free_symbols for v in values):
            raise UnsupportedInput(f"history of {state}: the compiled family takes constant histories, got "
                                   f"{[str(v) for v in values]}; simulate a non-constant history with simulate()")
        if len(values) != dim:
            raise InputError(f"history of {state}: expected {dim} components, got {len(values)}")
        x = np.array([float(v) for v in values])
        if not np.all(np.isfinite(x)):
            raise InputError(f"history of {state}: expected finite numbers, got {x.tolist()}")
        x0[sl] = x
    return x0
