"""The problem of the witness search: the claim after substitution, its atoms, windows and region.

:class:`_Problem` holds everything about a claim ``lhs ≤ rhs`` that does not depend on the number of
history pieces: the terms and measures with the parameter values substituted, the states at t and at
delayed times, the window and memory integrals (:class:`_Integral`), the region bounds
(:class:`_Constraint`), frames as one state (:class:`_FrameGroup`), the piece grids and the chart of each
slot (:class:`_Slot`); with the parsing helpers of the arguments.  Split from
:mod:`lkverify.certify.steps.witnesses`, which re-exports what is imported from it.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping

import sympy
from sympy.core.function import AppliedUndef

from ...declare.functional import outer_integrals, split_outer
from ...declare.parameters import apply_substitution
from ...declare.symbols import t, xi
from ...declare.system import System
from ...declare.terms import Term
from ...errors import InputError
from ..regions import prove_zero
from .measures import Measure, Region
from .witness_charts import _Chart, _FrameChart, UnsupportedClaim, _lt

__all__ = ["MEMORY", "MEMORY_TIME"]

#: the kind of a memory measure (lkverify.certify.steps.memory) and the witness time of a memory claim
MEMORY = "memory_integral"
MEMORY_TIME = sympy.Integer(1)
_U = sympy.Symbol("_wu", nonnegative=True)


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


def _checked_arguments(system, values, measures, region) -> tuple:
    """The measures as a tuple, after the arguments of a witness search are checked (InputError)."""
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
    return measures


class _Problem:
    """Everything about the claim that does not depend on the number of pieces."""

    def __init__(self, lhs, rhs, system, values, measures, region, exists, nonnegative, time=None):
        measures = _checked_arguments(system, values, measures, region)
        self.system = system
        self._charts: dict = {}
        self.time, self.time_range = _time_argument(time)
        self._group_frames()
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
        self._substitute_measures()
        self._constants_for_every(exists, nonnegative, [m.name for m in measures])
        self._scan_atoms()
        self._windows(region)

    def _group_frames(self) -> None:
        """The state of each component function; a frame's three vectors are one state (a rotation)."""
        system = self.system
        self.funcs = dict(system.state_functions())
        self.groups: dict = {}
        for st in system.states:
            if st.frame is not None and id(st.frame) not in self.groups:
                group = self.groups[id(st.frame)] = _FrameGroup(st.frame)
                for i, f in enumerate(group.functions):
                    self.funcs[f] = (group, i)

    def _substitute_measures(self) -> None:
        """The measures after substitution: (vector, window, power) by name, and the memory kernels."""
        sub, measures = self.sub, self.measures
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

    def _constants_for_every(self, exists, nonnegative, names) -> None:
        """The constants "for every c ≥ 0" (``exists``, ``nonnegative``); every other symbol needs a value."""
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

    def _scan_atoms(self) -> None:
        """The point atoms, the histories and the window integrals of the claim; the states it uses."""
        system, measures = self.system, self.measures
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

    def _windows(self, region) -> None:
        """The longest window H, the region's constraints, the break points of [t − H, t], the rotating states."""
        measures = self.measures
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
