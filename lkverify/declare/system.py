"""Symbolic delayed / time-varying systems.

A :class:`System` is a list of :class:`Equation` objects, one per state:
``M ẋ(t) = Σ_k term_k``, where each right-hand-side term is labelled so that the
derivative of a functional along the system can be reported term by term.
Terms may contain delayed values ``x(t - tau)``, window integrals
``∫_{t-τ}^t g(x(ξ)) dξ``, memory integrals ``∫_0^t K(t-ξ) g(x(ξ)) dξ`` and
time-varying coefficients ``h(t)``.

>>> import sympy
>>> from lkverify import Parameters, UnitVector, Vector, System, Equation, Term, cross, t
>>> P = Parameters(); k = P.scalar("k", positive=True)
>>> w, s = Vector("w"), UnitVector("s")
>>> sys = System([Equation(w, [Term(-k * w(t), text="-k w")]),
...               Equation(s, [Term(-cross(w(t), s(t)), text="-w×s")])], parameters=P)
>>> sys.rhs(s)[0] == s(t)[1] * w(t)[2] - s(t)[2] * w(t)[1]
True
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import sympy
from sympy.core.function import AppliedUndef

from .parameters import Parameters
from .states import Frame, Vector
from .symbols import t
from .terms import Term
from ..errors import InputError

__all__ = ["Equation", "System"]


@dataclasses.dataclass(frozen=True)
class Equation:
    """``mass · ẋ(t) = Σ terms`` for one state ``x``.

    Parameters
    ----------
    state : Vector
    terms : sequence of Term
        Vector-valued terms (n × 1) of the right-hand side, each with a label.
    mass : matrix, optional
        An invertible matrix (Θ in Euler's equations); identity if omitted.
    mass_text, mass_latex : str
        How the mass is printed in block labels ("Θ").

    Examples
    --------
    >>> import sympy
    >>> k, x = sympy.Symbol("k", positive=True), Vector("x", 1)
    >>> eq = Equation(x, [Term(-k * x(t), text="−k x")], mass=[[2]], mass_text="m")
    >>> [(term.text, term.expr) for term in eq.solved_terms()]     # ẋ = m⁻¹(−k x)
    [('m⁻¹(−k x)', Matrix([[-k*x_1(t)/2]]))]
    >>> Equation(Vector("w"), [Term(x(t), text="x")])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: Equation for w: term 'x' has shape (1, 1), expected (3, 1)
    """

    state: Vector
    terms: tuple
    mass: object = None
    mass_text: str = ""
    mass_latex: str = ""

    def __init__(self, state: Vector, terms: Sequence[Term], mass=None, *, mass_text: str = "", mass_latex: str = ""):
        if not isinstance(state, Vector):
            raise InputError(f"Equation: expected a state (Vector), got {type(state).__name__}")
        terms = tuple(terms)
        if not terms:
            raise InputError(f"Equation for {state.name}: expected at least one right-hand-side term")
        for i, term in enumerate(terms):
            if not isinstance(term, Term):
                raise InputError(f"Equation for {state.name}: expected Term objects, got {type(term).__name__}")
            if state.dim == 1 and not term.is_vector:
                term = Term(sympy.ImmutableMatrix([term.expr]), text=term.text, latex=term.latex)
                terms = terms[:i] + (term,) + terms[i + 1:]
            if not term.is_vector or term.shape != (state.dim, 1):
                raise InputError(f"Equation for {state.name}: term {term.text!r} has shape {term.shape}, "
                                 f"expected ({state.dim}, 1)")
        if mass is not None:
            mass = sympy.ImmutableMatrix(mass)
            if mass.shape != (state.dim, state.dim):
                raise InputError(f"Equation for {state.name}: mass has shape {mass.shape}, expected "
                                 f"({state.dim}, {state.dim})")
        object.__setattr__(self, "state", state)
        object.__setattr__(self, "terms", terms)
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "mass_text", mass_text or ("M" if mass is not None else ""))
        object.__setattr__(self, "mass_latex", mass_latex or self.mass_text)

    def solved_terms(self) -> list[Term]:
        """The terms of ẋ = M⁻¹ Σ terms, one per right-hand-side term, labelled."""
        if self.mass is None:
            return list(self.terms)
        minv = self.mass.inv()
        out = []
        for term in self.terms:
            out.append(Term(minv * term.expr, text=f"{self.mass_text}⁻¹({term.text})",
                            latex=rf"{self.mass_latex}^{{-1}}\left({term.latex}\right)"))
        return out


class System:
    """A system of delay / functional differential equations in the states.

    Parameters
    ----------
    equations : sequence of Equation
        One per state.
    parameters : Parameters
        The registry of every parameter the equations use.
    name : str
        The paper's label, e.g. "(10),(12)".

    Examples
    --------
    >>> P = Parameters(); k = P.scalar("k", positive=True); tau = P.delay("tau")
    >>> x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t - tau), text="−k x(t−τ)")])], parameters=P, name="(1)")
    >>> sys, sys.rhs(x)
    (System('(1)', states=['x']), Matrix([[-k*x_1(t - tau)]]))
    >>> sys.derivative_substitution(t - tau)            # ẋ at the delayed time
    {x_1(t - tau): -k*x_1(t - 2*tau)}
    """

    def __init__(self, equations: Sequence[Equation], *, parameters: Parameters, name: str = ""):
        equations = tuple(equations)
        seen = set()
        for eq in equations:
            if eq.state.name in seen:
                raise InputError(f"System {name}: two equations for state {eq.state.name}")
            seen.add(eq.state.name)
        self.equations = equations
        self.parameters = parameters
        self.name = name
        self.states = tuple(eq.state for eq in equations)
        self._solved = {eq.state.name: eq.solved_terms() for eq in equations}

    def equation(self, state: Vector) -> Equation:
        for eq in self.equations:
            if eq.state is state:
                return eq
        raise KeyError(f"no equation for state {state.name}")

    def solved_terms(self, state: Vector) -> list[Term]:
        """Labelled terms of ẋ (mass already inverted)."""
        return self._solved[state.name]

    def rhs(self, state: Vector) -> sympy.Matrix:
        """ẋ(t) as one column."""
        return sum((term.expr for term in self.solved_terms(state)), sympy.zeros(state.dim, 1))

    def state_functions(self) -> dict:
        """Component function → (state, index)."""
        return {f: (s, i) for s in self.states for i, f in enumerate(s.functions)}

    def derivative_substitution(self, time) -> dict:
        """``{x_i(time): ẋ_i at time}`` for every component; delayed times shift every argument."""
        shift = time - t
        out = {}
        for s in self.states:
            rhs = self.rhs(s)
            for i, f in enumerate(s.functions):
                out[f(time)] = rhs[i] if shift == 0 else _shift_time(rhs[i], shift)
        return out

    def constraint_polynomials(self, times) -> list[sympy.Expr]:
        """Vanishing polynomials of the state manifold at each time in ``times``, and of the constants."""
        polys = list(self.parameters.constraint_polynomials())
        frames = []
        for s in self.states:
            if s.frame is not None:
                if s.frame not in frames:
                    frames.append(s.frame)
                continue
            for time in times:
                polys += s.constraint_polynomials(time)
        for fr in frames:
            for time in times:
                polys += fr.constraint_polynomials(time)
        return polys

    def __repr__(self) -> str:
        return f"System({self.name!r}, states={[s.name for s in self.states]})"


def _shift_time(expr, shift):
    """expr with t replaced by t + shift everywhere (states, coefficients, integral limits)."""
    return expr.subs(t, t + shift)


def applied_state_functions(expr, system: System) -> set:
    """The applied component functions of the system's states in ``expr``."""
    funcs = system.state_functions()
    return {a for a in expr.atoms(AppliedUndef) if a.func in funcs}
