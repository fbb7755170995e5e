"""What a decay proof is stated in: :class:`DecayModel` (the final inequalities L(x) ≤ V ≤ U(x),
V̇ ≤ W(x) in scalar quantities on a box), the :class:`Envelope` they yield, and :class:`StatedAt` (the
constants a paper prints and the data at which it states them), with their exact comparisons.

Split from :mod:`lkverify.certify.decay`, which re-exports these names and proves the envelope
(:func:`~lkverify.certify.decay.certify_decay`); the scaling argument is described there.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np
import sympy

from ..errors import InputError, UnsupportedInput

__all__ = ["DecayModel", "Envelope", "StatedAt"]


@dataclasses.dataclass(frozen=True)
class DecayModel:
    """The final inequalities of a proof, in scalar quantities.

    Parameters
    ----------
    name : str
    variables : tuple of Symbol
        The scalar quantities, all ≥ 0.
    region : dict
        variable → its upper bound h_i on the region (an expression in the parameters).
    lower, upper, vdot : sympy expressions
        L, U and W (polynomials in the variables once the parameters have values).
    p : Rational
        The target V̇ ≤ −c̃ V^p.
    point_variables : tuple of Symbol
        Quantities bounded jointly at t0 by the history norm: Σ x_i² ≤ ‖χ‖² (at most two).
    history_variables : dict
        variable → κ with x ≤ κ‖χ‖ at t0 (e.g. (∫‖s−r‖³)^{1/3} ≤ τ^{1/3}‖χ‖).
    outputs : dict
        result name → variable whose decay is bounded (``{"d1": e, "d2": w}``).
    rate_name : str
        Name of the rate constant (``"d3"``).
    derivation : str
        How L, U and W follow from the exact V̇ (shown in reports).

    Examples
    --------
    >>> import sympy
    >>> w, e = sympy.symbols("w e", nonnegative=True)
    >>> a = sympy.Symbol("a", positive=True)
    >>> Q = w**2 + e**2
    >>> m = DecayModel("toy", (w, e), {w: sympy.Rational(1, 2), e: sympy.Rational(1, 2)}, Q, Q, -a * (w**3 + e**3),
    ...                sympy.Rational(3, 2), (w, e), {}, {"d1": e, "d2": w})
    >>> m.at({a: 2}).vdot
    -2*e**3 - 2*w**3
    >>> DecayModel("bad", (w, e), {w: 1}, Q, Q, -w**3, sympy.Rational(3, 2), (w,), {}, {"d1": e})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: DecayModel bad: region: expected an upper bound for every variable, got none for e
    """

    name: str
    variables: tuple
    region: dict
    lower: sympy.Expr
    upper: sympy.Expr
    vdot: sympy.Expr
    p: sympy.Rational
    point_variables: tuple
    history_variables: dict
    outputs: dict
    rate_name: str = "d3"
    derivation: str = ""

    def __post_init__(self):
        problems = []
        missing = [str(v) for v in self.variables if v not in self.region]
        if missing:
            problems.append(f"region: expected an upper bound for every variable, got none for {', '.join(missing)}")
        strays = [str(v) for v in (*self.point_variables, *self.history_variables, *self.outputs.values())
                  if v not in self.variables]
        if strays:
            problems.append(f"point, history and output variables: expected some of the variables "
                            f"{', '.join(map(str, self.variables))}, got {', '.join(strays)}")
        if problems:
            raise InputError(f"DecayModel {self.name}: " + "; ".join(problems))
        if len(self.point_variables) not in (1, 2):
            raise UnsupportedInput(f"DecayModel {self.name}: expected one or two point variables (Σ x_i² ≤ ‖χ‖² "
                                   f"at t0), got {len(self.point_variables)}; bound the others as history "
                                   "variables (x ≤ κ‖χ‖)")

    def at(self, values: Mapping) -> "DecayModel":
        """The model with parameter values substituted (exact rationals recommended)."""
        sub = dict(values)
        return dataclasses.replace(
            self, region={v: _exact_floats(sympy.sympify(h).xreplace(sub)) for v, h in self.region.items()},
            lower=sympy.expand(self.lower.xreplace(sub)), upper=sympy.expand(self.upper.xreplace(sub)),
            vdot=sympy.expand(self.vdot.xreplace(sub)),
            history_variables={v: sympy.sympify(k).xreplace(sub) for v, k in self.history_variables.items()})


@dataclasses.dataclass(frozen=True)
class Envelope:
    """x(t) ≤ d‖χ‖ (1 + κ‖χ‖^{2(p−1)} H(t))^{−1/(2(p−1))}, or d‖χ‖ e^{−κH(t)/2} for p = 1; H(t) = t − t0 or ∫h.

    Examples
    --------
    >>> env = Envelope("d1", d=2.0, kappa=0.5, p=1.5)
    >>> env.text()
    'd1(t) ≤ 2‖χ‖ (1 + 0.5‖χ‖(t − t0))^(−1)'
    >>> float(env(2.0, 1.0))                           # 2·1·(1 + 0.5·1·2)^(−1)
    1.0
    >>> Envelope("d1", d=2.0, kappa=0.5, p=1).text()  # p = 1: exponential decay
    'd1(t) ≤ 2‖χ‖ exp(−0.25(t − t0))'
    """

    name: str
    d: float
    kappa: float
    p: float

    def __call__(self, t, chi):
        t = np.asarray(t, dtype=float)
        if self.p == 1:
            return self.d * chi * np.exp(-0.5 * self.kappa * t)
        return self.d * chi * (1 + self.kappa * chi ** (2 * (self.p - 1)) * t) ** (-1 / (2 * (self.p - 1)))

    def text(self) -> str:
        if self.p == 1:
            return f"{self.name}(t) ≤ {self.d:.4g}‖χ‖ exp(−{self.kappa / 2:.4g}(t − t0))"
        if self.p == 1.5:
            return f"{self.name}(t) ≤ {self.d:.4g}‖χ‖ (1 + {self.kappa:.4g}‖χ‖(t − t0))^(−1)"
        return (f"{self.name}(t) ≤ {self.d:.4g}‖χ‖ (1 + {self.kappa:.4g}‖χ‖^{2 * (self.p - 1):g}(t − t0))"
                f"^(−{1 / (2 * (self.p - 1)):.4g})")


@dataclasses.dataclass(frozen=True)
class StatedAt:
    """Values a paper prints (constants, an estimate) and the data at which it states them.

    They are compared with lkverify's only there: at other gains the paper says nothing.

    Parameters
    ----------
    values : mapping
        Output name → the printed value (``{"d1": 9.21, …}``).
    at_values : mapping
        Parameter name → its exact value where the paper states them (resolved, as
        :meth:`lkverify.declare.parameters.Parameters.resolve` gives it).
    where : str
        The data in words ("the Fig. 6/7 data").

    Examples
    --------
    >>> import sympy
    >>> stated = StatedAt({"d1": 9.21}, {"a": sympy.Integer(0), "F": sympy.eye(2)}, "Fig. 6")
    >>> stated.at({"a": sympy.Integer(0), "F": sympy.eye(2), "lam": 3}), stated.at({"a": sympy.Rational(1, 10**9),
    ...                                                                              "F": sympy.eye(2)})
    ({'d1': 9.21}, {})
    >>> stated.at(None), stated.applies({"a": 0.0, "F": sympy.Matrix([[1, 0], [0, 1.0]])})
    ({}, True)
    """

    values: Mapping
    at_values: Mapping
    where: str

    def applies(self, values: Mapping | None) -> bool:
        """True when every parameter of :attr:`at_values` has exactly that value in ``values``."""
        if values is None:
            return False
        return all(k in values and _same(values[k], v) for k, v in self.at_values.items())

    def at(self, values: Mapping | None) -> dict:
        """The printed values at these data: all of them where the paper states them, else none."""
        return dict(self.values) if self.applies(values) else {}

    def __iter__(self):  # the outputs it names (so ``list(paper)`` lists them as for a plain mapping)
        return iter(self.values)


def _same(x, y) -> bool:
    """Exactly equal values: numbers, vectors or matrices (a float at its exact binary value)."""
    if isinstance(x, sympy.MatrixBase) or isinstance(y, sympy.MatrixBase):
        if not (isinstance(x, sympy.MatrixBase) and isinstance(y, sympy.MatrixBase)) or x.shape != y.shape:
            return False
        return all(_same(a, b) for a, b in zip(x, y))
    try:
        d = _exact_floats(sympy.sympify(x)) - _exact_floats(sympy.sympify(y))
    except (sympy.SympifyError, TypeError):
        return False
    return d == 0 or sympy.simplify(d) == 0


def _exact_floats(expr):
    """``expr`` with every Float at its exact binary value (never a guessed closed form)."""
    expr = sympy.sympify(expr)
    return expr.xreplace({f: sympy.Rational(f) for f in expr.atoms(sympy.Float)})
