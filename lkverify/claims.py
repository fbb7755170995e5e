"""What a proof claims: hypotheses with margins, and identities.

Proof modules declare these; :class:`~lkverify.items.Theorem` checks them.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import mpmath
import sympy

from .derivative import derivative_along
from .functional import Functional
from .identity import IdentityResult, check_identity
from .parameters import Parameters, apply_substitution
from .results import Result
from .status import Status
from .system import System
from .terms import Term

__all__ = ["Hypothesis", "MatrixHypothesis", "DerivativeClaim", "IdentityClaim"]


@dataclasses.dataclass(frozen=True)
class Hypothesis:
    """A hypothesis ``margin > 0`` (or ``≥ 0``) on the parameters.

    Parameters
    ----------
    name : str
        As printed, e.g. ``"b*tau < a"``; the margin of ``x < y`` is ``y − x``.
    margin : sympy expression in the parameters
    strict : bool
    reference : str
        The paper's label, e.g. ``"(14)"``.

    Examples
    --------
    >>> import sympy
    >>> mu = sympy.Symbol("mu", positive=True)
    >>> h = Hypothesis("mu > 1", mu - 1)
    >>> h.evaluate({mu: 2}).status.value, h.evaluate({mu: 2}).value
    ('exact', 1)
    >>> h.evaluate({mu: sympy.Rational(1, 2)}).status.value
    'failed'
    """

    name: str
    margin: object
    strict: bool = True
    reference: str = ""

    def evaluate(self, substitution) -> Result:
        m = apply_substitution(sympy.sympify(self.margin), substitution)
        ref = f" {self.reference}" if self.reference else ""
        if m.free_symbols:
            return Result("hypothesis", self.name, Status.UNDECIDED, None,
                          f"hypothesis{ref} depends on unset parameters {sorted(map(str, m.free_symbols))}")
        m = sympy.nsimplify(m) if isinstance(m, sympy.Float) else sympy.simplify(m)
        if m.has(sympy.oo, -sympy.oo, sympy.zoo, sympy.nan):
            return Result("hypothesis", self.name, Status.FAILED, None,
                          f"fails{ref}: the margin {m} is not finite (a divergent integral?)")
        positive, zero = m.is_positive, m.is_zero
        status = Status.EXACT
        if positive is None and zero is None:  # undecidable symbolically: certify with an interval
            with mpmath.workprec(200):
                iv = mpmath.iv.mpf(str(sympy.N(m, 80)))
            positive = iv.a > 0 if iv.a > 0 or iv.b < 0 else None
            status = Status.CERTIFIED
            if positive is None:
                return Result("hypothesis", self.name, Status.UNDECIDED, m, f"hypothesis{ref}: margin too close to 0")
        holds = bool(positive) or (not self.strict and bool(zero))
        rel = ">" if self.strict else "≥"
        if holds:
            return Result("hypothesis", self.name, status, m, f"holds{ref}: margin {_show(m)} {rel} 0")
        return Result("hypothesis", self.name, Status.FAILED, m, f"fails{ref}: margin {_show(m)}, need {rel} 0")


@dataclasses.dataclass(frozen=True)
class MatrixHypothesis:
    """A hypothesis ``M ≻ 0`` on a matrix built from the parameters (e.g. ΞD + DΞᵀ of paper 000).

    Decided exactly (rational LDLᵀ) when the entries are rational, with arb balls
    otherwise; the margin is a lower bound of λ_min (:func:`lkverify.conditions.matrix_positive_definite`).
    """

    name: str
    matrix: object
    reference: str = ""

    def evaluate(self, substitution) -> Result:
        from .conditions import matrix_positive_definite

        M = sympy.Matrix(self.matrix).applyfunc(lambda x: sympy.nsimplify(apply_substitution(sympy.sympify(x), substitution)))
        ref = f" {self.reference}" if self.reference else ""
        if M.free_symbols:
            return Result("hypothesis", self.name, Status.UNDECIDED, None,
                          f"hypothesis{ref} depends on unset parameters {sorted(map(str, M.free_symbols))}")
        if any(x.has(sympy.oo, -sympy.oo, sympy.zoo, sympy.nan) for x in M):
            return Result("hypothesis", self.name, Status.FAILED, None,
                          f"fails{ref}: the matrix has entries that are not finite (a divergent integral?)")
        res = matrix_positive_definite(M, name=self.name, symmetrize=True)
        r = res.to_result("hypothesis")
        return Result("hypothesis", self.name, r.status, r.value, f"{ref.strip()} {r.detail}".strip())


def _show(m) -> str:
    return str(m) if m.is_Rational else f"{m} ≈ {float(m):.6g}"


@dataclasses.dataclass(frozen=True)
class DerivativeClaim:
    """The claim ``V̇ along system = Σ terms``.

    Parameters
    ----------
    name : str
    functional : Functional
    system : System
    terms : sequence of Term
        The claimed V̇, one labelled term per printed term.
    description : str
    """

    name: str
    functional: Functional
    system: System
    terms: tuple
    description: str = ""

    def __init__(self, name: str, functional: Functional, system: System, terms: Sequence[Term], description: str = ""):
        terms = tuple(terms)
        for term in terms:
            if not isinstance(term, Term) or term.is_vector:
                raise TypeError(f"claim {name}: expected scalar Term objects, got {term!r}")
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "functional", functional)
        object.__setattr__(self, "system", system)
        object.__setattr__(self, "terms", terms)
        object.__setattr__(self, "description", description)

    def check(self, substitution, *, values, budget=60.0) -> IdentityResult:
        """Derive V̇ with ``substitution`` applied, and compare it with the claim."""
        system, functional = self.system, self.functional
        derived = derivative_along(functional, system)
        reference = [Term(apply_substitution(b.expr, substitution), text=b.text, latex=b.latex)
                     for b in derived.blocks]
        claimed = [Term(apply_substitution(c.expr, substitution), text=c.text, latex=c.latex) for c in self.terms]
        return check_identity(claimed, reference, name=self.name, states=system.states,
                              parameters=system.parameters, constraints=system.constraint_polynomials,
                              values=values, budget=budget)


@dataclasses.dataclass(frozen=True)
class IdentityClaim:
    """The claim ``Σ lhs = Σ rhs`` (an intermediate equality of a proof)."""

    name: str
    lhs: tuple
    rhs: tuple
    system: System
    description: str = ""

    def check(self, substitution, *, values, budget=60.0) -> IdentityResult:
        lhs = [Term(apply_substitution(c.expr, substitution), text=c.text, latex=c.latex) for c in self.lhs]
        rhs = [Term(apply_substitution(c.expr, substitution), text=c.text, latex=c.latex) for c in self.rhs]
        return check_identity(lhs, rhs, name=self.name, states=self.system.states,
                              parameters=self.system.parameters, constraints=self.system.constraint_polynomials,
                              values=values, budget=budget)
