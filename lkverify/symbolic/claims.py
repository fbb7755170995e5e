"""What a proof claims about V̇: derivative and identity claims, checked exactly.

Proof modules declare these; :class:`~lkverify.catalogue.items.Theorem` checks them.
Hypotheses on the parameters live in :mod:`lkverify.certify.hypotheses`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

from ..declare.functional import Functional
from ..declare.parameters import apply_substitution
from ..declare.system import System
from ..declare.terms import Term
from .derivative import derivative_along
from .identity import IdentityResult, check_identity
from ..errors import InputError

__all__ = ["DerivativeClaim", "IdentityClaim"]


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

    Examples
    --------
    >>> from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", positive=True); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t), text="−k x")])], parameters=P)
    >>> V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")])
    >>> claim = DerivativeClaim("(3)", V, sys, [Term(-k * x(t)[0] ** 2, text="−k x²")])
    >>> str(claim.check({}, values={}).status)
    'exact'
    >>> wrong = DerivativeClaim("(3')", V, sys, [Term(-2 * k * x(t)[0] ** 2, text="−2k x²")])
    >>> r = wrong.check({}, values={})
    >>> str(r.status), r.differences[0].message
    ('failed', 'wrong coefficient: printed [−2k x²] = 2 × (derived [∂/∂x [x²/2] · (−k x)])')
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
                raise InputError(f"claim {name}: expected scalar Term objects, got {term!r}")
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
    """The claim ``Σ lhs = Σ rhs`` (an intermediate equality of a proof).

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, UnitVector, t
    >>> s = UnitVector("s")
    >>> sys = System([Equation(s, [Term(0 * s(t), text="0")])], parameters=Parameters())
    >>> claim = IdentityClaim("(5)", (Term(1 - s(t)[2] ** 2, text="1 − s_z²"),),
    ...                       (Term(s(t)[0] ** 2 + s(t)[1] ** 2, text="s_x² + s_y²"),), sys)
    >>> r = claim.check({}, values={})                  # uses ‖s‖ = 1
    >>> str(r.status), r.holds
    ('exact', True)
    """

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
