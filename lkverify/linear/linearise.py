"""Linearisation of a catalogued System at an equilibrium, exactly (SymPy), as a :class:`LinearDelaySystem`.

The System is read through the simulator's symbolic right-hand side (the one
:func:`lkverify.simulate.compile.compile_system` compiles, generated from the declared terms):
delayed values x(t − c) are the lag rows Z_c, and each window integral
z = ∫_{t−c}^t g(x(ξ)) dξ is an auxiliary state with ż = g(x(t)) − g(x(t − c)).  At an
equilibrium p (x ≡ p, z* = c·g(p)) the linearisation is

    δẋ = A δx(t) + A_d δx(t − h) + ∫_{t−h}^t D δx(ξ) dξ,
    A = ∂f/∂x,  A_d = ∂f/∂Z_h,  D = Σ_windows (∂f/∂z)(∂g/∂x)      (all at p, exact),

with one delay h (every discrete lag and window length must be the same number, or the same
expression in the names kept symbolic).
Constrained states are written in coordinates of their manifold, δx = T ξ, ξ = L δx:

* a unit vector s (‖s‖ = 1) at r: s = r + B η, B a basis of r^⊥ — ``"tangent"``: B = E/‖u‖
  with u ∥ r rational when r allows (u = r/r_k) and E a rational basis of u^⊥
  (:func:`tangent_basis`); ``"orthonormal"``: the Gram–Schmidt of E (exact, radicals);
* a frame (s1, s2, s3) at (r1, r2, r3): the three small-rotation coordinates θ,
  δsᵢ = θ × rᵢ, θ = ½ Σ rᵢ × δsᵢ;
* any other state (ω) in its own coordinates.

The reduction is checked exactly: T L must fix the image of every Jacobian on the tangent
space (the manifold is invariant for the linear part), else the input is refused.

Where a Jacobian entry is undefined by substitution (0·∞, e.g. f^ν L with ν < 1 at f = 0,
or ‖s − r‖^{μ−1}(s × r) with 1 < μ < 2), or a kink (|·|, sign, min, max, a piecewise
definition) sits at the point, it is taken as the partial derivative by its
definition, the one-sided limits of the difference quotient (SymPy ``limit``, exact); an
infinite or two-valued limit means the right-hand side is not differentiable there and the
point is refused.  Such entries are listed in :attr:`Linearisation.limits`: partial
derivatives, whose Fréchet differentiability is the user's to check (for the torques of
papers 000 and 002 it holds: they are O(‖s − r‖^{1+κ}), κ > 0).

The same path serves a whole gain grid: :func:`lkverify.linear.family.linear_family` keeps
some names symbolic (those of :func:`lkverify.simulate.family.compile_family`: scalar
parameters, or free names inside a value such as F = diag(h, h, h)); the point must then be
an equilibrium for every value of them, and A, A_d, D and the delay are expressions in them.

Examples
--------
>>> import sympy
>>> from lkverify import Parameters, Vector, System, Equation, Term, t, window_integral, xi
>>> P = Parameters(); k = P.scalar("k", default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-k * sympy.sin(x(t - tau)[0]) - x(t)[0] ** 3
...                                 - window_integral(x(xi)[0], tau))])], parameters=P)
>>> lin = linearise_at(sys, {"x": [0]}, {"k": 2})
>>> lin.system.A, lin.system.Ad, lin.system.kernel[0], lin.delay
(Matrix([[0]]), Matrix([[-2]]), Matrix([[-1]]), 1)
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import sympy
from sympy.core.function import AppliedUndef

from ..errors import InputError, UnsupportedInput
from ..declare.parameters import ParameterKind, apply_substitution
from ..declare.states import UnitVector
from ..declare.symbols import t
from .model import LinearDelaySystem, has_float

__all__ = ["Linearisation", "linearise", "linearise_at", "tangent_basis", "COORDINATES"]

#: the coordinates of unit vectors: a rational tangent basis (scaled by 1/‖u‖) or an orthonormal one
COORDINATES = ("tangent", "orthonormal")


@dataclasses.dataclass(frozen=True)
class Linearisation:
    """A linearisation and how it was obtained.

    Attributes
    ----------
    system : LinearDelaySystem
        In the reduced coordinates ξ.
    delay : SymPy number or None
        The one delay h (None for an ODE).
    labels : tuple of str
        The name of each coordinate of ξ (``ω_1``, ``η_s_1``, ``θ_1``, …).
    T, L : sympy.Matrix
        δx = T ξ (ambient state from coordinates) and ξ = L δx.
    full : dict
        The ambient Jacobians ``A``, ``Ad``, ``D`` (in the simulator's state order).
    limits : tuple of str
        The Jacobian entries taken as limits (undefined by substitution).

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); x = Vector("x", 2)
    >>> sys = System([Equation(x, [Term(sympy.Matrix([x(t)[1], -x(t)[0] - x(t)[1] ** 3]))])], parameters=P)
    >>> lin = linearise_at(sys, {"x": [0, 0]})
    >>> lin.system.A, lin.delay, lin.labels
    (Matrix([
    [ 0, 1],
    [-1, 0]]), None, ('x_1', 'x_2'))
    """

    system: LinearDelaySystem
    delay: object
    labels: tuple
    T: object
    L: object
    full: dict
    limits: tuple = ()


def tangent_basis(r):
    """(u, E): a rational u ∥ r (r/r_k for the first nonzero r_k) and a basis E of u^⊥ (rational when u is).

    >>> u, E = tangent_basis(sympy.Matrix([1, 1, 1]) / sympy.sqrt(3))
    >>> list(u), list(E.T * u)
    ([1, 1, 1], [0, 0])
    """
    r = sympy.Matrix(r)
    k = next(i for i in range(3) if sympy.simplify(r[i]) != 0)
    u = (r / r[k]).applyfunc(sympy.simplify)
    cols = []
    for j in (j for j in range(3) if j != k):
        e = sympy.zeros(3, 1)
        e[j] = 1
        e[k] = -u[j] / u[k]
        cols.append(e)
    return u, sympy.Matrix.hstack(*cols)


def _cross_matrix(u):
    return sympy.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def _is_zero(e) -> bool:
    e = sympy.simplify(e)
    if e.is_zero:
        return True
    return bool(e.equals(0)) if e.is_zero is None else False


def _finite(e) -> bool:
    return not e.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo)


def linearise(system, equilibrium: Mapping, values: Mapping | None = None, *, coordinates: str = "tangent",
              order: Sequence[str] | None = None) -> LinearDelaySystem:
    """The linearisation of ``system`` at ``equilibrium``, exact, as a :class:`LinearDelaySystem`.

    See :func:`linearise_at` (which also returns the delay, the coordinates and the lift).

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", default=2); tau = P.delay("tau", default=1)
    >>> x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-x(t)[0] - k * x(t - tau)[0] ** 3 + k * x(t - tau)[0])])], parameters=P)
    >>> lin = linearise(sys, {"x": [0]})                 # ẋ = −x + k x(t−τ) near 0
    >>> lin.A, lin.Ad
    (Matrix([[-1]]), Matrix([[2]]))
    """
    return linearise_at(system, equilibrium, values, coordinates=coordinates, order=order).system


def linearise_at(system, equilibrium: Mapping, values: Mapping | None = None, *, coordinates: str = "tangent",
                 order: Sequence[str] | None = None) -> Linearisation:
    """Linearise ``system`` (parameter ``values``, defaults fill in) at ``equilibrium``, exactly.

    Parameters
    ----------
    system : lkverify.System
        States: vectors, unit vectors, frames; delays x(t − c) and window integrals.
    equilibrium : mapping
        State name → its value (a list, a SymPy matrix, or the name of a parameter such as
        ``"r1"``); every state, each vector of a frame by its own name.
    values : mapping, optional
        Parameter values; a time-varying coefficient h(t) must be frozen at a number here.
    coordinates : {"tangent", "orthonormal"}
        The basis of the tangent plane of unit vectors (frames always use small rotations).
    order : sequence of str, optional
        The state blocks of ξ in this order (names; a frame by any of its vectors);
        default the system's.

    Raises
    ------
    InputError
        Not an equilibrium (the residual printed), not on the state manifold, a time-varying
        coefficient without a value, several different delays, not differentiable at the point.
    UnsupportedInput
        Memory integrals or other integrals than windows of the states.

    See Also
    --------
    lkverify.linear.family.linear_family : the same linearisation with some names kept symbolic.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); tau = P.delay("tau", default=2)
    >>> x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(1 - x(t)[0] * x(t - tau)[0])])], parameters=P)
    >>> lin = linearise_at(sys, {"x": [1]})              # x ≡ 1: ẋ ≈ −ξ(t) − ξ(t−τ)
    >>> lin.system.A, lin.system.Ad, lin.delay
    (Matrix([[-1]]), Matrix([[-1]]), 2)
    >>> linearise_at(sys, {"x": [2]})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: system: expected an equilibrium (ẋ = 0), got the residual ... at the given point; give a point where the right-hand side vanishes
    """
    parts = _linear_parts(system, equilibrium, values, coordinates=coordinates, order=order)
    h = parts.delay
    lin = LinearDelaySystem(parts.A, Ad=parts.Ad, kernel=[parts.D] if parts.windows else (),
                            name=f"{system.name or 'system'} linearised" + (f", h = {h}" if h is not None else ""),
                            from_float=has_float(dict(values or {})))     # a float value: at most certified
    return Linearisation(lin, h, parts.labels, parts.T, parts.L, parts.full, parts.limits)


@dataclasses.dataclass(frozen=True)
class _Parts:
    """The reduced matrices of a linearisation, exact, possibly in the kept symbols (``symbols``)."""

    A: object
    Ad: object
    D: object
    windows: bool
    delay: object
    labels: tuple
    T: object
    L: object
    full: dict
    limits: tuple
    symbols: tuple = ()


def _linear_parts(system, equilibrium: Mapping, values: Mapping | None, *, coordinates: str = "tangent",
                  order: Sequence[str] | None = None, keep: Sequence[str] = ()) -> _Parts:
    """The one path of :func:`linearise_at` and :func:`lkverify.linear.family.linear_family`.

    ``keep``: names (scalar parameters, or free names inside ``values``) that stay symbolic;
    the equilibrium must then be one for every value of them, and the matrices and the delay
    are expressions in their symbols (``_Parts.symbols``, in the order of ``keep``).
    """
    from ..simulate.compile import symbolic_system     # the simulator's symbolic right-hand side (module docstring)

    if coordinates not in COORDINATES:
        raise InputError(f"coordinates: expected one of {', '.join(COORDINATES)}, got {coordinates!r}")
    name = system.name or "system"
    sym = symbolic_system(system, values, grid=tuple(keep))
    symbols, sub, sr = sym.symbols, sym.substitution, sym.rhs
    _refuse_time_varying(sr, system, name)
    if sr.quads or any(a.kind != "window" for a in sr.aux):
        raise UnsupportedInput(f"{name}: expected discrete delays and window integrals ∫_{{t−τ}}^t g(x) dξ only; "
                               f"got a memory or weighted integral; linearise a system without them")
    if len(sr.exact_lags) > 1:
        raise InputError(f"{name}: expected one delay (a LinearDelaySystem has one h), got the lags "
                         f"{', '.join(map(str, sr.exact_lags))}; set the delays equal or linearise by hand")
    point = _point(system, equilibrium, sub, name)
    n = sr.n_states
    real = {v: sympy.Dummy(v.name, real=True) for v in [*sr.ysyms, *sr.aux_syms, *(z for row in sr.zsyms for z in row)]}
    x, z = [real[v] for v in sr.ysyms], [real[v] for v in sr.aux_syms]
    Zh = [real[v] for v in sr.zsyms[0]] if sr.exact_lags else []
    limits: list = []
    zstar = [a.exact_lag * _g_at(a, system, point, limits) for a in sr.aux]
    at = {**dict(zip(x, point)), **dict(zip(Zh, point)), **dict(zip(z, zstar))}
    f = sympy.Matrix(sr.exprs[:n]).xreplace(real)          # real states: d|x|/dx = sign(x), not re/im parts
    gnow = sympy.Matrix(sr.exprs[n:]).xreplace(real) if z else sympy.zeros(0, 1)
    _check_equilibrium(f, at, limits, system, symbols, name)
    A = _jacobian(f, x, at, limits, system, "x(t)")
    Ad = _jacobian(f, Zh, at, limits, system, "x(t−h)") if Zh else sympy.zeros(n, n)
    D = sympy.zeros(n, n)
    if z:
        D = _jacobian(f, z, at, limits, system, "z") * _jacobian(gnow, x, at, limits, system, "g")
    T, L, labels = _reduction(system, point, sr.layout, coordinates, order, name)
    for label, M in (("A", A), ("A_d", Ad), ("D", D)):
        leak = ((sympy.eye(n) - T * L) * M * T).applyfunc(sympy.simplify)
        if not leak.is_zero_matrix:
            raise InputError(f"{name}: expected the linear part to keep the states on their manifold, got {label} "
                             f"moving them off it ({leak.T}); check the equilibrium and the constraints")
    red = [(L * M * T).applyfunc(sympy.simplify) for M in (A, Ad, D)]
    h = sr.exact_lags[0] if sr.exact_lags else None
    return _Parts(red[0], red[1], red[2], bool(z), h, tuple(labels), T, L, {"A": A, "Ad": Ad, "D": D},
                  tuple(limits), tuple(symbols))


# ---------------------------------------------------------------------------------------------- inputs


def _refuse_time_varying(sr, system, name):
    if any(t in sympy.sympify(e).free_symbols for e in sr.exprs):
        coeffs = [s.name for s in system.parameters if s.kind is ParameterKind.COEFFICIENT]
        which = f" (the coefficient{'s' if len(coeffs) > 1 else ''} {', '.join(coeffs)})" if coeffs else ""
        ex = f"{coeffs[0]}=1/2" if coeffs else None
        raise InputError(f"{name}: expected an autonomous right-hand side, got one depending on t{which}; "
                         f"freeze it at a value to linearise" + (f" ({ex})" if ex else ""),
                         topic="parameters", example=ex)


def _point(system, equilibrium, sub, name) -> list:
    """The equilibrium as one list (state order); a parameter's name stands for its value (``sub`` applied)."""
    P = system.parameters
    eq = dict(equilibrium)
    unknown = sorted(set(eq) - {s.name for s in system.states})
    missing = [s.name for s in system.states if s.name not in eq]
    if unknown or missing:
        raise InputError(f"{name}: expected a value for each state ({', '.join(s.name for s in system.states)}), "
                         f"got {'unknown ' + ', '.join(unknown) if unknown else ''}"
                         f"{'; ' if unknown and missing else ''}{'missing ' + ', '.join(missing) if missing else ''}; "
                         f"give every state, e.g. {system.states[0].name}={[0] * system.states[0].dim}")
    point = []
    for s in system.states:
        v = eq[s.name]
        if isinstance(v, str) and v in P:
            v = apply_substitution(P[v].obj, sub)
        m = sympy.Matrix(sympy.sympify(v) if isinstance(v, str) else v)
        if m.shape not in ((s.dim, 1), (1, s.dim)):
            raise InputError(f"{name}: state {s.name}: expected {s.dim} components, got shape {m.shape}")
        point += list(m)
    _check_manifold(system, point, name)
    return point


def _check_equilibrium(f, at, limits, system, symbols, name):
    """ẋ = 0 at the point (identically in the kept ``symbols``), else InputError with the residual."""
    residual = [_value(e, at, limits, _component(system, i)) for i, e in enumerate(f)]
    bad = [(i, r) for i, r in enumerate(residual) if not _is_zero(r)]
    if bad:
        shown = ", ".join(f"{_component(system, i)} = {sympy.simplify(r)}" for i, r in bad)
        every = " at every grid point" if symbols else ""
        which = f" for all values of {', '.join(map(str, symbols))}" if symbols else ""
        raise InputError(f"{name}: expected an equilibrium (ẋ = 0){every}, got the residual {shown} at the given "
                         f"point; give a point where the right-hand side vanishes{which}")


def _check_manifold(system, point, name):
    idx, frames = 0, []
    blocks = {}
    for s in system.states:
        blocks[s.name] = sympy.Matrix(point[idx: idx + s.dim])
        idx += s.dim
        if s.frame is not None and s.frame not in frames:
            frames.append(s.frame)
        elif s.frame is None and isinstance(s, UnitVector) and not _is_zero((blocks[s.name].T * blocks[s.name])[0] - 1):
            raise InputError(f"{name}: unit vector {s.name}: expected ‖{s.name}‖ = 1, got {list(blocks[s.name])}")
    for fr in frames:
        vs = [blocks[v.name] for v in fr]
        G = sympy.Matrix(3, 3, lambda i, j: (vs[i].T * vs[j])[0])
        if not (G - sympy.eye(3)).applyfunc(sympy.simplify).is_zero_matrix:
            raise InputError(f"{name}: frame {', '.join(v.name for v in fr)}: expected orthonormal vectors, got "
                             f"the Gram matrix {G.applyfunc(sympy.simplify).tolist()}")


def _g_at(aux, system, point, limits) -> sympy.Expr:
    """The window integrand g at the constant state p (its continuous extension where 0·∞)."""
    funcs = system.state_functions()
    offset, start = 0, {}
    for s in system.states:
        start[s.name] = offset
        offset += s.dim
    rep, at = {}, {}
    for a in aux.g.atoms(AppliedUndef):
        if a.func in funcs:
            rep[a] = sympy.Dummy(str(a.func), real=True)
            at[rep[a]] = point[start[funcs[a.func][0].name] + funcs[a.func][1]]
    g = _value(aux.g.xreplace(rep), at, limits, "g")
    if g.free_symbols:
        raise UnsupportedInput(f"window integrand {aux.g} depends on ξ itself at a constant state; expected g(x(ξ))")
    return g


def _component(system, i) -> str:
    for s in system.states:
        if i < s.dim:
            return f"d{s.name}_{i + 1}/dt" if s.dim > 1 else f"d{s.name}/dt"
        i -= s.dim
    return f"y_{i}"


# ---------------------------------------------------------------------------------------------- derivatives


def _value(e, at, limits, what):
    """e at the point; the continuous extension (a limit) where substitution gives 0·∞."""
    v = sympy.sympify(e).xreplace(at)
    if _finite(v):
        return v
    eps = sympy.Dummy("epsilon", positive=True)
    ray = {k: val + (j + 1) * eps for j, (k, val) in enumerate(at.items())}     # along one ray into the point
    ext = sympy.limit(sympy.sympify(e).xreplace(ray), eps, 0)
    if not _finite(ext):
        raise InputError(f"{what}: expected a right-hand side defined (or continuous) at the point, got {ext} as its "
                         f"limit; linearise at another point")
    limits.append(f"{what} at the point = {ext} (the limit along a ray)")
    return ext


def _jacobian(F, syms, at, limits, system, what):
    """∂F/∂syms at the point, exact; undefined entries by one-sided limits of the difference quotient."""
    J = sympy.zeros(F.rows, len(syms))
    for i in range(F.rows):
        Fi = sympy.sympify(F[i])
        base = None
        for j, s in enumerate(syms):
            if s not in Fi.free_symbols:
                continue
            d = sympy.diff(Fi, s).xreplace(at)
            if not _finite(d) or _kink_at(Fi, at):
                row = _component(system, i) if what != "g" else f"g_{i + 1}"
                label = f"∂({row})/∂{what if what != 'g' else 'x(ξ)'}_{j + 1}"
                if base is None:
                    base = _value(Fi, at, limits, row)
                d = _partial_by_limit(Fi, s, at, base, f"{system.name or 'system'}: {label}")
                limits.append(f"{label} = {d}")
            J[i, j] = d
    return J


#: functions whose derivative SymPy writes finitely even where they have a kink (|x|' = sign(x), sign(0) = 0)
_KINKS = (sympy.Abs, sympy.sign, sympy.Heaviside, sympy.Piecewise, sympy.Min, sympy.Max, sympy.floor, sympy.ceiling)


def _kink_at(F, at) -> bool:
    """True when a non-smooth function of F has its kink at the point (its arguments hit a switching value)."""
    for k in F.atoms(*_KINKS):
        if isinstance(k, sympy.Piecewise):
            return True
        args = [sympy.simplify(a.xreplace(at)) for a in k.args]
        if isinstance(k, (sympy.Min, sympy.Max)):
            if any(_is_zero(a - b) for i, a in enumerate(args) for b in args[i + 1:]):
                return True
        elif isinstance(k, (sympy.floor, sympy.ceiling)):
            if args[0].is_integer is not False:
                return True
        elif not (args[0].is_zero is False):
            return True
    return False


def _partial_by_limit(Fi, s, at, base, what):
    eps = sympy.Dummy("epsilon", real=True)
    shifted = Fi.xreplace({k: (v + eps if k is s else v) for k, v in at.items()})
    q = (shifted - base) / eps
    left, right = (sympy.limit(q, eps, 0, d) for d in ("-", "+"))
    if not (_finite(left) and _finite(right)) or not _is_zero(left - right):
        raise InputError(f"{what}: expected a right-hand side differentiable at the point, got the one-sided "
                         f"derivatives {left} and {right}; linearise where it is differentiable (e.g. μ ≥ 1 for "
                         f"‖s − r‖^(μ−1) at s = r) or analyse this point without linearisation")
    return sympy.simplify(right)


# ---------------------------------------------------------------------------------------------- coordinates


def _unit_basis(r, coordinates):
    u, E = tangent_basis(r)
    if coordinates == "tangent":
        return (E / sympy.sqrt((u.T * u)[0])).applyfunc(sympy.simplify)
    cols = sympy.GramSchmidt([E[:, 0], E[:, 1]], True)
    return sympy.Matrix.hstack(*cols).applyfunc(sympy.simplify)


def _reduction(system, point, layout, coordinates, order, name):
    """(T, L, labels): δx = T ξ, ξ = L δx, block by block in ``order``."""
    n = len(point)
    blocks, seen = [], set()
    for s in system.states:
        if s.frame is not None:
            if s.frame in seen:
                continue
            seen.add(s.frame)
            blocks.append(("frame", [v.name for v in s.frame]))
        elif isinstance(s, UnitVector):
            blocks.append(("unit", [s.name]))
        else:
            blocks.append(("vector", [s.name]))
    if order is not None:
        pos = {nm: k for k, (_, names) in enumerate(blocks) for nm in names}
        ks = [pos.get(o) for o in order]
        if None in ks or sorted(ks) != list(range(len(blocks))):
            raise InputError(f"order: expected each state block once ({', '.join('/'.join(b[1]) for b in blocks)}), "
                             f"got {list(order)}")
        blocks = [blocks[k] for k in ks]
    cols_T, rows_L, labels = [], [], []
    for kind, names in blocks:
        if kind == "vector":
            sl = layout[names[0]]
            for i in range(sl.stop - sl.start):
                e = sympy.zeros(n, 1)
                e[sl.start + i] = 1
                cols_T.append(e)
                rows_L.append(e.T)
                labels.append(f"{names[0]}_{i + 1}")
        elif kind == "unit":
            sl = layout[names[0]]
            B = _unit_basis(point[sl.start:sl.stop], coordinates)
            Lb = ((B.T * B).inv() * B.T).applyfunc(sympy.simplify)
            for i in range(2):
                c, row = sympy.zeros(n, 1), sympy.zeros(1, n)
                c[sl.start:sl.stop, 0] = B[:, i]
                row[0, sl.start:sl.stop] = Lb[i, :]
                cols_T.append(c)
                rows_L.append(row)
                labels.append(f"η_{names[0]}_{i + 1}")
        else:
            sls = [layout[nm] for nm in names]
            rs = [sympy.Matrix(point[sl.start:sl.stop]) for sl in sls]
            Tb = sympy.zeros(n, 3)
            Lb = sympy.zeros(3, n)
            for sl, r in zip(sls, rs):
                Tb[sl.start:sl.stop, :] = -_cross_matrix(r)          # δsᵢ = θ × rᵢ = −[rᵢ]ₓ θ
                Lb[:, sl.start:sl.stop] = _cross_matrix(r) / 2        # θ = ½ Σ rᵢ × δsᵢ
            cols_T += [Tb[:, i] for i in range(3)]
            rows_L += [Lb[i, :] for i in range(3)]
            labels += [f"θ_{i + 1}" for i in range(3)]
    return sympy.Matrix.hstack(*cols_T), sympy.Matrix.vstack(*rows_L), labels
