"""What a rule works with and what it returns: :class:`Context` (the system, the parameter values, the
measures, the region), :class:`Condition` (a side condition and how it was decided), :class:`Application`
(one rule applied to one term) and :func:`decided`; with the structural sign tests the rules share
(:func:`nonnegative`, :func:`sign_of`, the sign and the absolute value of a factor).

Split from :mod:`lkverify.certify.steps.rules`, which re-exports these names.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import sympy
from sympy.core.function import AppliedUndef

from ...declare.parameters import apply_substitution
from ...declare.symbols import t
from ...errors import InputError
from ...status import Status
from .measures import Measure, Region

__all__ = ["Application", "Condition", "Context", "Rule", "decided", "nonnegative", "sign_of"]

_T_NONNEGATIVE = sympy.Symbol("t", nonnegative=True)  # t on its domain t ≥ 0 (Context.zero)


def _explicit_time(e) -> bool:
    """Does ``e`` have t outside the state functions (a coefficient h(t), ḣ(t) after the values)?"""
    return any(a.has(t) and not a.atoms(AppliedUndef) for a in sympy.sympify(e).atoms(sympy.Pow, sympy.Function))


# -- context --------------------------------------------------------------------------------
@dataclasses.dataclass
class Context:
    """What a rule needs: the system, the parameter values, the measures by name, the region.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); s = UnitVector("s")
    >>> sys_ = System([Equation(s, [Term(0 * s(t))])], parameters=P)
    >>> ctx = Context(sys_, P.resolve({}), {"e": norm_measure("e", s(t))})
    >>> ctx.zero(s(t).dot(s(t)) - 1), ctx.zero(s(t)[0])     # exact modulo ‖s‖ = 1
    (True, False)
    >>> ctx.measure("q")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: unknown measure 'q': expected one of e; declare it with the step's measures
    """

    system: object
    values: Mapping
    measures: Mapping
    region: Region | None = None
    budget: object = None
    constants: Mapping | None = None
    parameter_box: Mapping | None = None  # boxed parameter symbol → (lo, hi): the values hold these symbols

    def __post_init__(self):
        self.sub = self.system.parameters.substitution(self.values)
        self.certified = {}  # constants certified inside norm trees: name → (value, info)
        self.box_used = False  # a rule took a supremum over the parameter box (its result depends on the ends)

    def at_point(self, point: Mapping) -> "Context":
        """This context at one point of the parameter box (boxed symbol → value): numeric values again."""
        rep = {s_: sympy.Rational(v) for s_, v in point.items()}
        values = type(self.values)({k: (v.xreplace(rep) if isinstance(v, (sympy.Basic, sympy.MatrixBase)) else v)
                                    for k, v in self.values.items()})
        if hasattr(self.values, "from_float"):
            values.from_float = self.values.from_float
        ctx = Context(self.system, values, self.measures, self.region, self.budget,
                      None if self.constants is None else {k: sympy.sympify(v).xreplace(rep)
                                                           for k, v in self.constants.items()})
        return ctx

    def box_center(self) -> dict:
        """The centre of the parameter box (boxed symbol → exact value); empty without a box."""
        return {s_: (sympy.Rational(lo) + sympy.Rational(hi)) / 2 for s_, (lo, hi) in (self.parameter_box or {}).items()}

    def seconds_left(self, default: float | None = None) -> float | None:
        """Wall-clock seconds for one certification: what is left of the user's budget, at most ``default``.

        Without a budget (the catalogue's default) this is ``default`` — None for the rules'
        suprema, which are then limited by boxes alone, so a verdict does not depend on the
        machine's speed or load.
        """
        from ...options import Deadline

        if isinstance(self.budget, Deadline):
            left = self.budget.remaining
            if left is None:
                return default
            return max(left if default is None else min(left, default), 1e-3)
        if self.budget is None:
            return default
        return max(float(self.budget) if default is None else min(float(self.budget), default), 1e-3)

    def __getitem__(self, name):
        """The resolved value of a parameter (so a callable of the values also works with the context)."""
        return self.values[name]

    def at(self, expr):
        """``expr`` with the parameter values (and the step's named constants) substituted.

        A callable is evaluated as ``expr(ctx)`` (a constant computed from the values,
        e.g. an eigenvalue of a matrix parameter)."""
        if callable(expr) and not isinstance(expr, sympy.Basic):
            expr = expr(self)
        e = sympy.sympify(expr) if not isinstance(expr, sympy.MatrixBase) else expr
        e = apply_substitution(e, self.sub)
        if self.constants:
            e = e.xreplace(self.constants)
        return e

    def definitions(self, expr):
        """``expr`` with every measure symbol replaced by its definition (parameters substituted)."""
        rep = {m.symbol: m.definition for m in self.measures.values() if m.definition is not None}
        return self.at(sympy.sympify(expr).xreplace(rep))

    def measure(self, name: str) -> Measure:
        try:
            return self.measures[name]
        except KeyError:
            raise InputError(f"unknown measure {name!r}: expected one of {', '.join(self.measures)}; declare it "
                             f"with the step's measures") from None

    def pointwise(self, expr):
        """``expr`` with the pointwise-norm symbols of the window measures replaced by their definitions."""
        expr = sympy.sympify(expr)
        present = expr.free_symbols  # only the symbols that occur: each substitution costs
        rep = {m.pointwise_symbol: self.at(m.pointwise()) for m in self.measures.values()
               if m.kind != "norm" and m.pointwise_symbol in present}
        return expr.xreplace(rep)

    def zero(self, expr) -> bool:
        """Is ``expr`` exactly 0 on the state manifold (unit vectors, frames) for t ≥ 0?

        Time runs on t ≥ 0, so explicit powers of t are normalised with t nonnegative
        (√((1+t)^(−7/4)) = (1+t)^(−7/8), as a coefficient h(t) and its measure |h(t)| give) and
        an expression with explicit t is put over one denominator before its numerator is tested.
        """
        e = self.pointwise(self.at(expr))
        if _explicit_time(e):  # on t ≥ 0; then over one denominator (nonzero for t ≥ 0), its numerator
            e = sympy.expand(e.xreplace({t: _T_NONNEGATIVE}).xreplace({_T_NONNEGATIVE: t}))
            if e != 0:
                e = sympy.expand(sympy.fraction(sympy.together(e))[0])
        else:
            e = sympy.expand(e)
        if e == 0:
            return True
        from ...symbolic.canonical import Canonicalizer

        canon = self.__dict__.get("_canonicalizer")  # one per context: its Gröbner bases are reused
        if canon is None:
            canon = self._canonicalizer = Canonicalizer(self.system.constraint_polynomials)
        return canon.normal_forms([e]).polys[0] == 0


@dataclasses.dataclass(frozen=True)
class Condition:
    """A side condition of a rule application and how it was decided."""

    text: str
    status: Status
    detail: str = ""

    def to_json(self) -> dict:
        return {"condition": self.text, "status": self.status.value, "detail": self.detail}


@dataclasses.dataclass(frozen=True)
class Application:
    """One rule applied to one term: the bound it derives and the side conditions checked.

    ``status`` is the weakest of the conditions; ``detail`` names the first that fails.
    """

    rule: str
    bound: object
    conditions: tuple
    constants: tuple = ()  # (name, value, Result-like dict) of constants the rule certified

    @property
    def status(self) -> Status:
        sts = [c.status for c in self.conditions]
        for s in (Status.FAILED, Status.UNDECIDED, Status.CERTIFIED):
            if s in sts:
                return s
        return Status.EXACT

    @property
    def detail(self) -> str:
        for c in self.conditions:
            if not c.status.is_proof:
                return f"side condition fails: {c.text}: {c.detail}"
        return f"{self.rule}: " + "; ".join(c.text for c in self.conditions)

    def to_json(self) -> dict:
        return {"rule": self.rule, "bound": str(self.bound), "status": self.status.value,
                "conditions": [c.to_json() for c in self.conditions],
                "constants": {name: value for name, value, _ in self.constants}}


class Rule:
    """A checked rule.  ``apply(term, direction, ctx)`` → :class:`Application` (direction "upper": term ≤ bound)."""

    name = "rule"

    def apply(self, term, direction: str, ctx: Context) -> Application:  # pragma: no cover - interface
        raise NotImplementedError


def decided(text, ok, detail="", *, certified=False) -> Condition:
    """The :class:`Condition` of a decision: ``ok`` True holds, False fails, None is undecided.

    A holding condition is ``exact``, or ``certified`` when the decision went through interval
    arithmetic (``certified=True``).

    Examples
    --------
    >>> decided("q is rational", True).status.value, decided("κ certified", True, certified=True).status.value
    ('exact', 'certified')
    >>> c = decided("the region bounds ‖x‖", None); c.status.value, c.detail
    ('undecided', 'not decided')
    >>> decided("b ≥ 0", False).status.value
    'failed'
    """
    if ok is None:
        return Condition(text, Status.UNDECIDED, detail or "not decided")
    if ok:
        return Condition(text, Status.CERTIFIED if certified else Status.EXACT, detail)
    return Condition(text, Status.FAILED, detail or "does not hold")


_cond = decided


# -- nonnegativity, structurally --------------------------------------------------------------
def nonnegative(expr) -> bool:
    """True when ``expr`` is ≥ 0 by its structure (sums and products of nonnegative factors).

    Nonnegative factors: nonnegative numbers and symbols, even integer powers, powers
    with a nonnegative base, sums of squares, integrals over windows of nonnegative
    length of nonnegative integrands.  False means "not shown", not "negative".

    >>> import sympy
    >>> x, y = sympy.symbols("x y", real=True)
    >>> nonnegative(3 * (x**2 + y**2) ** sympy.Rational(3, 2)), nonnegative(x * y)
    (True, False)
    """
    e = sympy.sympify(expr)
    if e.is_number:
        return bool(e.is_nonnegative)
    if e.is_nonnegative:
        return True
    if isinstance(e, sympy.Add):
        return all(nonnegative(a) for a in e.args)
    if isinstance(e, sympy.Mul):
        neg = [a for a in e.args if a.is_number and a.is_negative]
        rest = [a for a in e.args if not (a.is_number and a.is_negative)]
        return len(neg) % 2 == 0 and all(nonnegative(a) for a in rest)
    if isinstance(e, sympy.Pow):
        if e.exp.is_Integer and e.exp % 2 == 0:
            return True
        return nonnegative(e.base)
    if isinstance(e, sympy.Integral):
        if any(len(lim) != 3 for lim in e.limits):
            return False
        widths = [sympy.simplify(lim[2] - lim[1]) for lim in e.limits]
        return all(w.is_nonnegative for w in widths) and nonnegative(e.function)
    if isinstance(e, sympy.Abs):
        return True
    return False


def _constant_and_monomial(expr, symbols):
    """(c, monomial) with expr = c·monomial, c free of ``symbols``; None if expr is not a single product."""
    e = sympy.factor_terms(sympy.sympify(expr))
    if isinstance(e, sympy.Add):
        return None
    c, m = sympy.S.One, sympy.S.One
    for f in sympy.Mul.make_args(e):
        if f.free_symbols & set(symbols):
            m *= f
        else:
            c *= f
    return c, m


def _factor_sign(c, measure_symbols) -> int | None:
    """The sign of a factor: a constant of known sign times nonnegative measures, or structurally signed."""
    c = sympy.sympify(c)
    if nonnegative(c):
        return 1
    if nonnegative(-c):
        return -1
    cm = _constant_and_monomial(c, measure_symbols)
    if cm is not None and nonnegative(cm[1]):
        return _sign(cm[0])
    return None


def _abs_factor(c, measure_symbols):
    """|c| as an expression: ±c when the sign is known, else |constant|·(nonnegative measures)."""
    sign = _factor_sign(c, measure_symbols)
    if sign is not None:
        return sign * sympy.sympify(c)
    cm = _constant_and_monomial(c, measure_symbols)
    if cm is not None and nonnegative(cm[1]):
        return sympy.Abs(cm[0]) * cm[1]
    return None


def sign_of(expr) -> int | None:
    """+1 (≥ 0), −1 (≤ 0) or None, for a constant expression (parameters with assumptions allowed).

    Examples
    --------
    >>> import sympy
    >>> a = sympy.Symbol("a", positive=True)
    >>> sign_of(a ** 2 + 1), sign_of(-3 * a), sign_of(a - 1)
    (1, -1, None)
    """
    e = sympy.sympify(expr)
    if e.is_nonnegative or nonnegative(e):
        return 1
    if e.is_nonpositive or nonnegative(-e):
        return -1
    return None


_sign = sign_of
