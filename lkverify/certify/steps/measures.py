"""Scalar measures of a state and its history, and the region that bounds them.

A bound step's right-hand side is written in a few nonnegative scalars — the papers'
‖ω(t)‖, ‖s(t) − r‖, ∫_{t−τ}^t ‖s(ξ) − r‖^μ dξ, (∫‖s(ξ) − r‖³ dξ)^{1/3},
max_{[t−τ, t]} ‖s(ξ) − r‖ — and named constants.  A :class:`Measure` is such a scalar:
a symbol (nonnegative) and its definition in the model's own vocabulary (the state
functions at t, at ξ under a window integral), so that a rule can substitute the
definition and compare with the exact term, and a witness can evaluate it.

A :class:`Region` bounds measures of kind ``norm`` (at t) and ``sup`` (over the window);
it implies a box for every measure (:meth:`Region.box`): a window norm of order p over a
window of length h is at most h^{1/p} times the sup of the same vector.

Examples
--------
>>> import sympy
>>> from lkverify import UnitVector, Vector, t, xi
>>> s, omega = UnitVector("s"), Vector("omega")
>>> r = sympy.Matrix([0, 0, 1])
>>> e = norm_measure("e", s(t) - r, text="‖s(t) − r‖")
>>> j = window_norm("j", s(xi) - r, p=3, window=1, text="(∫‖s(ξ) − r‖³dξ)^{1/3}")
>>> m = sup_norm("m", s(xi) - r, window=1, text="max ‖s(ξ) − r‖")
>>> w = norm_measure("w", omega(t))
>>> region = Region({m: sympy.Rational(1, 10), w: sympy.Rational(1, 5)})
>>> region.box([e, j, w])
{e: 1/10, j: 1/10, w: 1/5}
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import sympy

from ...declare.symbols import t, xi
from ...declare.vectors import as_column, norm_squared
from ...errors import InputError

__all__ = ["KINDS", "Measure", "Region", "attitude_measures", "norm_measure", "sup_norm", "window_integral_measure",
           "window_norm"]

#: the kinds of measure: ‖v(t)‖, (∫‖v(ξ)‖^p)^{1/p}, ∫‖v(ξ)‖^p, max over the window of ‖v(ξ)‖
KINDS = ("norm", "window_norm", "window_integral", "sup")


@dataclasses.dataclass(frozen=True)
class Measure:
    """A nonnegative scalar of the state and its history.

    Parameters
    ----------
    name : str
        The symbol's name in bounds (``"e"``, ``"w"``, ``"j"``).
    kind : {"norm", "window_norm", "window_integral", "sup"}
    vector : sympy.Matrix
        The vector measured: at ``t`` for ``norm``, at ``xi`` for the window kinds.
    power : Rational
        p of ``window_norm`` / ``window_integral`` (1 otherwise).
    window : sympy expression
        The window length h (the window is [t − h, t]); unused for ``norm``.
    text : str
        How reports print it.

    Examples
    --------
    >>> from lkverify import Vector, t, xi
    >>> x = Vector("x", 2)
    >>> n = Measure("n", "norm", x(t))
    >>> n.definition, n.substitute(n.symbol ** 2)
    (sqrt(x_1(t)**2 + x_2(t)**2), x_1(t)**2 + x_2(t)**2)
    >>> Measure("n", "norm", x(xi))
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: measure n: a norm measure is written at t or at one delayed time t − c, got xi
    """

    name: str
    kind: str
    vector: object
    power: object = 1
    window: object = 0
    text: str = ""

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise InputError(f"measure name: expected an identifier such as 'e', got {self.name!r}")
        if self.kind not in KINDS:
            raise InputError(f"measure {self.name}: kind: expected one of {', '.join(KINDS)}, got {self.kind!r}")
        vec = as_column(self.vector)
        object.__setattr__(self, "vector", sympy.ImmutableMatrix(vec))
        p = sympy.sympify(self.power)
        if not (p.is_number and p.is_positive) and not p.free_symbols:
            raise InputError(f"measure {self.name}: power: expected a positive number, got {self.power!r}")
        object.__setattr__(self, "power", p)
        object.__setattr__(self, "window", sympy.sympify(self.window))
        times = {a.args[0] for a in vec.atoms(sympy.core.function.AppliedUndef)}
        if self.kind == "norm":
            # at t, or at one delayed time t − c (c ≥ 0 a constant): ‖s(t − τ) − r‖
            bad = [x for x in times if (t - x).has(t) or (t - x).is_negative]
            if bad or len(times) > 1:
                raise InputError(f"measure {self.name}: a norm measure is written at t or at one delayed time t − c, "
                                 f"got {', '.join(sorted(map(str, times)))}")
        elif times - {xi}:
            raise InputError(f"measure {self.name}: the vector must be written at xi for kind {self.kind!r}, "
                             f"got {sorted(map(str, times - {xi}))[0]}")
        if not self.text:
            object.__setattr__(self, "text", self.name)

    @property
    def time(self):
        """The time a norm measure is taken at (t or t − c); ξ for the window kinds."""
        if self.kind != "norm":
            return xi
        times = {a.args[0] for a in self.vector.atoms(sympy.core.function.AppliedUndef)}
        return next(iter(times)) if times else t

    @property
    def symbol(self) -> sympy.Symbol:
        """The nonnegative symbol that stands for the measure in bounds."""
        return sympy.Symbol(self.name, nonnegative=True)

    @property
    def pointwise_symbol(self) -> sympy.Symbol:
        """A nonnegative symbol for the pointwise norm ‖v(ξ)‖ inside window integrals (see :meth:`pointwise`)."""
        return sympy.Symbol(f"{self.name}_xi", nonnegative=True)

    def pointwise(self, at=xi) -> sympy.Expr:
        """‖vector‖ at time ``at`` (the integrand's norm for the window kinds)."""
        v = self.vector if at == self.time else self.vector.subs(self.time, at)
        return sympy.sqrt(norm_squared(v))

    @property
    def definition(self) -> sympy.Expr | None:
        """The measure as an expression of the model (None for ``sup``: a maximum has no closed form)."""
        if self.kind == "norm":
            return sympy.sqrt(norm_squared(self.vector))
        if self.kind == "sup":
            return None
        integral = sympy.Integral(norm_squared(self.vector) ** (self.power / 2), (xi, t - self.window, t))
        return integral if self.kind == "window_integral" else integral ** (1 / self.power)

    def substitute(self, expr) -> sympy.Expr:
        """``expr`` with this measure's symbol replaced by its definition."""
        if self.definition is None:
            raise InputError(f"measure {self.name} ({self.text}) is a maximum over the window and has no "
                             f"closed form; bound it with a rule instead of substituting it")
        return sympy.sympify(expr).xreplace({self.symbol: self.definition})

    def __str__(self) -> str:
        return self.text


def norm_measure(name: str, vector, *, text: str = "") -> Measure:
    """‖vector(t)‖, e.g. ``norm_measure("w", omega(t))``.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import UnitVector, t
    >>> s = UnitVector("s")
    >>> e = norm_measure("e", s(t) - sympy.Matrix([0, 0, 1]))
    >>> e.kind, e.text, e.definition
    ('norm', '‖e‖', sqrt((s_z(t) - 1)**2 + s_x(t)**2 + s_y(t)**2))
    """
    return Measure(name, "norm", vector, text=text or f"‖{name}‖")


def window_norm(name: str, vector, *, p, window, text: str = "") -> Measure:
    """(∫_{t−h}^t ‖vector(ξ)‖^p dξ)^{1/p} with h = ``window``.

    Examples
    --------
    >>> from lkverify import Vector, xi
    >>> x = Vector("x", 2)
    >>> window_norm("j", x(xi), p=3, window=2).definition
    Integral((x_1(xi)**2 + x_2(xi)**2)**(3/2), (xi, t - 2, t))**(1/3)
    """
    return Measure(name, "window_norm", vector, power=p, window=window, text=text)


def window_integral_measure(name: str, vector, *, p, window, text: str = "") -> Measure:
    """∫_{t−h}^t ‖vector(ξ)‖^p dξ with h = ``window`` (no root: the papers' ∫‖s(ξ) − r‖^μ dξ).

    Examples
    --------
    >>> from lkverify import Vector, xi
    >>> x = Vector("x", 2)
    >>> window_integral_measure("I", x(xi), p=2, window=2).definition
    Integral(x_1(xi)**2 + x_2(xi)**2, (xi, t - 2, t))
    """
    return Measure(name, "window_integral", vector, power=p, window=window, text=text)


def sup_norm(name: str, vector, *, window, text: str = "") -> Measure:
    """max over [t − h, t] of ‖vector(ξ)‖ (the papers' ‖x_t‖_τ when the vector is the state).

    Examples
    --------
    >>> from lkverify import Vector, xi
    >>> m = sup_norm("m", Vector("x", 2)(xi), window=2)
    >>> m.definition is None                     # a maximum has no closed form
    True
    >>> m.substitute(m.symbol)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: measure m (m) is a maximum over the window and has no closed form; bound it with a rule instead of substituting it
    """
    return Measure(name, "sup", vector, window=window, text=text)


@dataclasses.dataclass(frozen=True)
class Region:
    """Upper bounds on measures: the region of a step (``{measure: bound}``).

    Only ``norm`` and ``sup`` measures are bounded directly; the others get the box
    that follows (:meth:`box`).

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Vector, t, xi
    >>> x = Vector("x", 2)
    >>> m = sup_norm("m", x(xi), window=2)
    >>> n, j = norm_measure("n", x(t)), window_norm("j", x(xi), p=3, window=2)
    >>> region = Region({m: sympy.Rational(1, 3)})
    >>> region.box([n, j])                       # j ≤ 2^{1/3}·max‖x‖
    {n: 1/3, j: 2**(1/3)/3}
    >>> region.scaled(2).describe()
    'm ≤ 2/3'
    >>> Region({j: 1})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: region: bound a norm at t or a sup over the window, got window_norm j; its bound follows from the sup of the same vector
    """

    bounds: Mapping

    def __post_init__(self):
        fixed = {}
        for m, b in dict(self.bounds).items():
            if not isinstance(m, Measure):
                raise InputError(f"region: expected Measure keys, got {type(m).__name__}")
            if m.kind not in ("norm", "sup"):
                raise InputError(f"region: bound a norm at t or a sup over the window, got {m.kind} {m.text}; "
                                 f"its bound follows from the sup of the same vector")
            fixed[m] = sympy.sympify(b)
        object.__setattr__(self, "bounds", fixed)

    def at(self, substitution: Mapping) -> "Region":
        """The region with parameter values substituted in the bounds."""
        return Region({m: sympy.sympify(b).xreplace(dict(substitution)) for m, b in self.bounds.items()})

    def bound_of(self, measure: Measure, substitution: Mapping | None = None):
        """The upper bound the region implies for ``measure`` (None: unbounded)."""
        sub = dict(substitution or {})
        for m, b in self.bounds.items():
            if m == measure:
                return sympy.sympify(b).xreplace(sub)
        for m, b in self.bounds.items():
            if m.kind != "sup":
                continue
            b = sympy.sympify(b).xreplace(sub)
            h = sympy.sympify(m.window).xreplace(sub)
            if measure.kind == "norm":
                lag = sympy.simplify(sympy.sympify(t - measure.time).xreplace(sub))
                if measure.vector == m.vector.subs(xi, measure.time) and lag.is_nonnegative \
                        and sympy.simplify(h - lag).is_extended_nonnegative:  # h = ∞: the whole history
                    return b
                continue
            if measure.kind in ("window_norm", "window_integral") and measure.vector == m.vector:
                hm = sympy.sympify(measure.window).xreplace(sub)
                if sympy.simplify(hm - h).is_positive:
                    continue  # a longer window than the sup's: no bound
                power = sympy.sympify(measure.power).xreplace(sub)
                return hm ** (1 / power) * b if measure.kind == "window_norm" else hm * b ** power
        own = getattr(measure, "bound_from", None)  # a kind defined elsewhere bounds itself (steps.memory)
        return own(self, sub) if own is not None else None

    def box(self, measures: Sequence[Measure], substitution: Mapping | None = None) -> dict:
        """``{symbol: upper bound}`` for each measure (raises InputError if one is unbounded)."""
        out = {}
        for m in measures:
            b = self.bound_of(m, substitution)
            if b is None:
                raise InputError(f"region: no bound on {m.text} follows from {self.describe()}; bound it, or the "
                                 f"sup of its vector over the window")
            out[m.symbol] = b
        return out

    def scaled(self, factor) -> "Region":
        """Every bound times ``factor`` (a region twice too large: ``scaled(2)``)."""
        return Region({m: sympy.sympify(b) * factor for m, b in self.bounds.items()})

    def describe(self) -> str:
        return ", ".join(f"{m.text} ≤ {b}" for m, b in self.bounds.items()) or "no bounds"


def attitude_measures(omega, vectors, targets, *, bound, window=1):
    """‖ω(t)‖ and ‖s_i(t) − r_i‖ as measures ``w, e1, e2, …``, and the region bounding them all by ``bound``.

    The region bounds ‖ω(t)‖ and the sup over [t − window, t] of every ‖s_i(ξ) − r_i‖.

    >>> import sympy
    >>> from lkverify import Frame, Vector
    >>> s1, s2, s3 = Frame(); r1, r2 = sympy.Matrix([1, 0, 0]), sympy.Matrix([0, 1, 0])
    >>> (w, e1, e2), region = attitude_measures(Vector("omega"), (s1, s2), (r1, r2), bound=sympy.Rational(1, 5))
    >>> e1.text, len(region.bounds)
    ('‖s1(t) − r1‖', 3)
    """
    w = norm_measure("w", omega(t), text="‖ω(t)‖")
    es = [norm_measure(f"e{k}", v(t) - sympy.Matrix(r), text=f"‖{v.name}(t) − r{k}‖")
          for k, (v, r) in enumerate(zip(vectors, targets), start=1)]
    sups = {sup_norm(f"m{k}", v(xi) - sympy.Matrix(r), window=window): bound
            for k, (v, r) in enumerate(zip(vectors, targets), start=1)}
    return (w, *es), Region({**sups, w: bound})
