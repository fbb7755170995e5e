"""Numeric witnesses: random admissible histories and parameters, and exact-enough evaluation.

A witness is a point of the constraint manifold in the space of histories: every
state gets a smooth history on the whole real line that satisfies its
constraints exactly (unit vectors and frames are rotations of fixed vectors,
built from rational Cayley rotations and the Rodrigues formula), every free
parameter a random admissible value, and the evaluation time ``t_eval``.
Integrals are evaluated by adaptive quadrature (``scipy.integrate.quad``), nested
integrals recursively.

>>> import numpy as np, sympy
>>> from lkverify import Parameters, UnitVector, t
>>> s = UnitVector("s"); P = Parameters()
>>> w = make_witness([s], P, rng=np.random.default_rng(0))
>>> round(evaluate(sum(c**2 for c in s(t)), w), 12)
1.0
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence

import numpy as np
import scipy.integrate
import sympy
from sympy.core.function import AppliedUndef

from ..declare.functional import outer_integrals, split_outer
from ..declare.parameters import ParameterKind, Parameters, apply_substitution
from ..declare.states import Frame, Vector
from ..declare.symbols import t
from ..errors import UnsupportedInput
from .floateval import NotEvaluable, float_values

__all__ = ["Witness", "make_witness", "evaluate", "witness_constant"]

_theta = sympy.Symbol("theta", real=True)


def _rat(rng, lo, hi, den=32):
    return sympy.Rational(int(rng.integers(int(lo * den), int(hi * den) + 1)), den)


def _cayley_rotation(rng) -> sympy.Matrix:
    """A random rotation with rational entries: (I − S)(I + S)⁻¹, S skew-symmetric."""
    a, b, c = (_rat(rng, -1, 1, 8) for _ in range(3))
    S = sympy.Matrix([[0, -c, b], [c, 0, -a], [-b, a, 0]])
    return (sympy.eye(3) - S) * (sympy.eye(3) + S).inv()


def _rotation_about(rng) -> sympy.Matrix:
    """R(θ): rotation by angle c·θ + φ0 about a fixed random unit axis (Rodrigues' formula)."""
    n = _cayley_rotation(rng)[:, 0]  # a rational unit axis
    K = sympy.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    ang = _rat(rng, 0.3, 1.5) * _theta + _rat(rng, 0, 3)
    return sympy.eye(3) + sympy.sin(ang) * K + (1 - sympy.cos(ang)) * K * K


@dataclasses.dataclass(frozen=True)
class Witness:
    """A concrete admissible point: parameter values, state histories, evaluation time.

    Attributes
    ----------
    parameter_values : dict
        name → SymPy value (what the user fixed, else random admissible).
    histories : dict
        component function → ``Lambda(θ, expression)``.
    t_eval : sympy.Rational

    Examples
    --------
    >>> import numpy as np, sympy
    >>> from lkverify import Parameters, UnitVector
    >>> P = Parameters(); a = P.scalar("a", positive=True); s = UnitVector("s")
    >>> w = make_witness([s], P, fixed={"a": sympy.Integer(3)}, rng=np.random.default_rng(0))
    >>> w.parameter_values, w.drawn, sorted(f.__name__ for f in w.histories)
    ({'a': 3}, (), ['s_x', 's_y', 's_z'])
    >>> round(sum(v ** 2 for v in w.state_values([s])["s"]), 12)     # the history stays on ‖s‖ = 1
    1.0
    """

    parameter_values: dict
    substitution: dict
    histories: dict
    t_eval: sympy.Rational
    drawn: tuple = ()  # the parameters drawn at random (not fixed by the caller)

    def state_values(self, states: Sequence[Vector]) -> dict[str, list[float]]:
        """The states' values at ``t_eval`` (for reports)."""
        return {s.name: [float(self.histories[f](self.t_eval)) for f in s.functions] for s in states}

    def describe(self, states: Sequence[Vector]) -> dict:
        vals = {}
        for k, v in self.parameter_values.items():
            if isinstance(v, sympy.MatrixBase):
                vals[k] = [[float(x) for x in row] for row in v.tolist()]
            elif isinstance(v, sympy.Expr) and v.free_symbols:
                vals[k] = str(v)
            else:
                vals[k] = float(v)
        return {"t": float(self.t_eval), "parameters": vals,
                "states_at_t": self.state_values(states),
                "drawn_at_random": list(self.drawn),
                "histories": "smooth random histories satisfying the constraints (rotations for unit vectors)",
                "why": ("an identity must hold for every admissible history and every admissible value of "
                        "the parameters it leaves free, so a random admissible point is a valid witness")}

    def explain(self) -> str:
        """One phrase saying what the witness is (for reports)."""
        free = f"; random admissible values of {', '.join(self.drawn)}" if self.drawn else ""
        return (f"random smooth admissible histories evaluated at t = {self.t_eval}{free}: an identity must hold "
                f"at every such point; the values are in --json")


def make_witness(states: Sequence[Vector], parameters: Parameters, *, fixed: Mapping[str, object] | None = None,
                 rng: np.random.Generator) -> Witness:
    """Draw a random admissible witness.

    Parameters
    ----------
    states : sequence of Vector
    parameters : Parameters
    fixed : mapping, optional
        Checked parameter values to keep (name → value); the rest are random.
    rng : numpy Generator

    Examples
    --------
    >>> import numpy as np
    >>> from lkverify import Parameters, UnitVector
    >>> P = Parameters(); a = P.scalar("a", positive=True); tau = P.delay("tau"); s = UnitVector("s")
    >>> w = make_witness([s], P, fixed={"tau": 1}, rng=np.random.default_rng(0))
    >>> w.drawn, w.parameter_values["tau"], w.parameter_values["a"] > 0
    (('a',), 1, True)
    >>> w == make_witness([s], P, fixed={"tau": 1}, rng=np.random.default_rng(0))    # reproducible
    True
    """
    fixed = dict(fixed or {})
    values = dict(fixed)
    # orthonormal groups of constant vectors share one rotation
    for group in parameters._groups:
        free = [n for n in group if n not in values]
        if free:
            R = _cayley_rotation(rng)
            for i, n in enumerate(free):
                values[n] = sympy.ImmutableMatrix(R[:, i])
    for spec in parameters:
        if spec.name in values:
            continue
        if spec.kind is ParameterKind.UNIT_VECTOR:
            values[spec.name] = sympy.ImmutableMatrix(_cayley_rotation(rng)[:, 0])
        else:
            values[spec.name] = spec.random_value(rng)
    substitution = parameters.substitution(values)
    histories: dict = {}
    done_frames = []
    for s in states:
        if s.frame is not None:
            if s.frame in done_frames:
                continue
            done_frames.append(s.frame)
            M = _rotation_about(rng) * _cayley_rotation(rng)
            for k, v in enumerate(s.frame.vectors):
                for i, f in enumerate(v.functions):
                    histories[f] = sympy.Lambda(_theta, M[i, k])
        elif s.unit:
            v0 = _cayley_rotation(rng)[:, 0]
            col = _rotation_about(rng) * v0
            for i, f in enumerate(s.functions):
                histories[f] = sympy.Lambda(_theta, col[i])
        else:
            for f in s.functions:
                expr = (_rat(rng, -1, 1) + _rat(rng, -1, 1) * sympy.sin(_rat(rng, 0.5, 2) * _theta + _rat(rng, 0, 3))
                        + _rat(rng, -0.5, 0.5) * sympy.cos(_rat(rng, 0.5, 3) * _theta))
                histories[f] = sympy.Lambda(_theta, expr)
    t_eval = _rat(rng, 1.5, 2.5, 8)
    drawn = tuple(n for n in values if n not in fixed)
    return Witness(values, substitution, histories, t_eval, drawn)


def _substitute_parameters(expr, w: Witness):
    expr = apply_substitution(sympy.sympify(expr), w.substitution)
    if expr.has(sympy.Derivative, sympy.Subs):
        expr = expr.replace(lambda e: isinstance(e, (sympy.Derivative, sympy.Subs)), lambda e: e.doit())
    return expr


def witness_constant(expr, w: Witness):
    """``expr`` at the witness as an exact SymPy constant (histories and parameters substituted).

    Returns ``None`` when the expression keeps integrals or undefined functions; the
    result is exact (rational rotations, ``sin``/``cos`` of rationals) and can be
    enclosed by :mod:`lkverify.certify.intervals`.

    Examples
    --------
    >>> import numpy as np, sympy
    >>> from lkverify import Parameters, UnitVector, t, xi
    >>> P = Parameters(); a = P.scalar("a", positive=True); s = UnitVector("s")
    >>> w = make_witness([s], P, fixed={"a": sympy.Integer(3)}, rng=np.random.default_rng(0))
    >>> witness_constant(a * t, w) == 3 * w.t_eval
    True
    >>> sympy.trigsimp(witness_constant(s(t).dot(s(t)), w))     # exactly on the unit sphere
    1
    >>> witness_constant(sympy.Integral(s(xi)[0], (xi, 0, t)), w) is None
    True
    """
    expr = _substitute_parameters(expr, w)
    expr = expr.replace(lambda e: isinstance(e, AppliedUndef) and e.func in w.histories,
                        lambda e: w.histories[e.func](*e.args))
    if expr.has(sympy.Derivative, sympy.Subs):  # differentiate the histories before t is fixed
        expr = expr.replace(lambda e: isinstance(e, (sympy.Derivative, sympy.Subs)), lambda e: e.doit())
    expr = expr.xreplace({t: w.t_eval})
    if expr.free_symbols or expr.has(sympy.Integral) or expr.atoms(AppliedUndef):
        return None
    return expr


def evaluate(expr, w: Witness) -> float:
    """The value of ``expr`` at the witness (quadrature for integrals).

    Examples
    --------
    >>> import numpy as np, sympy
    >>> from lkverify import Parameters, UnitVector, t, xi
    >>> P = Parameters(); a = P.scalar("a", positive=True); s = UnitVector("s")
    >>> w = make_witness([s], P, fixed={"a": sympy.Integer(3)}, rng=np.random.default_rng(0))
    >>> abs(evaluate(sympy.Integral(a * xi, (xi, 0, t)), w) - 3 * float(w.t_eval) ** 2 / 2) < 1e-12
    True
    >>> round(evaluate(sympy.Integral(s(xi).dot(s(xi)), (xi, t - 1, t)), w), 9)
    1.0
    >>> evaluate(sympy.Symbol("q"), w)
    Traceback (most recent call last):
    ...
    lkverify.errors.UnsupportedInput: cannot evaluate numerically: unassigned symbols ['q']
    """
    return evaluate_many([expr], w)[0]


def evaluate_many(exprs, w: Witness) -> list[float]:
    """The values of several expressions at the witness, sharing compiled integrals."""
    exprs = [_expand_state_derivatives(_substitute_parameters(e, w), w) for e in exprs]
    histories = {f: sympy.lambdify([lam.variables[0]], lam.expr, modules="math") for f, lam in w.histories.items()}
    fn = _compile(exprs, (t,), histories, once=True)
    return [float(v) for v in fn(float(w.t_eval))]


def _expand_state_derivatives(expr, w: Witness):
    """Derivatives of states (``Derivative(s_x(t), t)``) replaced by the derivatives of their histories."""
    derivs = [d for d in expr.atoms(sympy.Derivative)
              if any(a.func in w.histories for a in d.atoms(AppliedUndef))]
    if not derivs:
        return expr
    done = {}
    for d in derivs:
        funcs = {a.func for a in d.atoms(AppliedUndef) if a.func in w.histories}
        done[d] = d.subs({f: w.histories[f] for f in funcs}).doit()
    return expr.xreplace(done)


def _compile(exprs, bound: tuple, histories: dict, *, once: bool = False):
    """A callable of the bound variables' values returning the values of ``exprs``.

    Integrals (outermost, shared between the expressions) become placeholders
    computed by adaptive quadrature of their compiled integrands; state values
    ``x_i(arg)`` become placeholders computed from the histories.  ``once``: the callable
    is called once (the top level of :func:`evaluate_many`), so the expressions themselves are
    evaluated by walking their trees (:func:`~lkverify.symbolic.floateval.float_values`) rather
    than printed and compiled; the integrands, called by the quadrature, are compiled either way.
    """
    ints = list(dict.fromkeys(i for e in exprs for i in outer_integrals(e)))
    holders = [sympy.Dummy(f"q{k}") for k in range(len(ints))]
    bodies = [e.xreplace(dict(zip(ints, holders))) for e in exprs]
    apps = list(dict.fromkeys(a for b in bodies for a in b.atoms(AppliedUndef) if a.func in histories))
    app_holders = [sympy.Dummy(f"x{k}") for k in range(len(apps))]
    bodies = [b.xreplace(dict(zip(apps, app_holders))) for b in bodies]
    unknown = sorted({str(a.func) for b in bodies for a in b.atoms(AppliedUndef)} - {str(f) for f in histories})
    if unknown:
        raise UnsupportedInput(f"cannot evaluate numerically: no history for the functions {unknown}; pass the "
                               f"states they belong to (states=[...])")
    leftovers = set().union(*[b.free_symbols for b in bodies]) - set(bound) - set(holders) - set(app_holders)
    if leftovers:
        raise UnsupportedInput(f"cannot evaluate numerically: unassigned symbols {sorted(map(str, leftovers))}")
    args = list(bound) + holders + app_holders
    compile_ = _walker if once else _lambdified
    f = compile_(args, bodies)
    arg_fns = [(histories[a.func], compile_(list(bound), a.args[0], scalar=True)) for a in apps]
    quads = []
    for I in ints:
        var, lo, hi, inner = split_outer(I)
        g = _compile([inner], bound + (var,), histories)
        quads.append((g, compile_(list(bound), lo, scalar=True), compile_(list(bound), hi, scalar=True)))

    def call(*vals):
        qs = []
        for g, flo, fhi in quads:
            val, _err = scipy.integrate.quad(lambda x: g(*vals, x)[0], float(flo(*vals)), float(fhi(*vals)),
                                             epsabs=1e-13, epsrel=1e-12, limit=200)
            qs.append(val)
        xs = [h(float(a(*vals))) for h, a in arg_fns]
        out = f(*vals, *qs, *xs)
        return [complex(v).real if isinstance(v, complex) else float(v) for v in out]

    return call


def _lambdified(args: list, exprs, *, scalar: bool = False):
    """``sympy.lambdify`` of ``exprs`` (a list, or one expression with ``scalar``), common subexpressions shared."""
    if scalar:
        return sympy.lambdify(args, exprs, modules="math")
    return sympy.lambdify(args, exprs, modules="math", cse=True, docstring_limit=0)


def _walker(args: list, exprs, *, scalar: bool = False):
    """The same callable as :func:`_lambdified` for one call: the trees walked at call time, no code printed.

    A node :func:`float_values` does not know is compiled by lambdify after all."""
    items = [exprs] if scalar else list(exprs)

    def call(*vals):
        try:
            out = float_values(items, dict(zip(args, map(float, vals))))
        except NotEvaluable:
            out = list(_lambdified(args, items)(*vals))
        return out[0] if scalar else out

    return call

