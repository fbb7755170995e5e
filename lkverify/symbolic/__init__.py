"""Symbolic derivation and identities: the exact V̇ along a system, and printed formulas checked.

:func:`derivative_along` applies the chain rule at every argument θ(t) and the Leibniz
rule to every integral term; :func:`check_identity` proves (``exact``) or refutes
(``failed``, with the residual terms at a witness) an equality of labelled terms modulo
the state constraints; :class:`DerivativeClaim` and :class:`IdentityClaim` are how a
proof states them.
"""

from .canonical import Canonicalizer, NormalForms
from .claims import DerivativeClaim, IdentityClaim
from .derivative import Block, DerivativeResult, derivative_along
from .identity import IdentityResult, TermDifference, check_identity
from .witness import Witness, evaluate, make_witness, witness_constant

__all__ = [
    "Block", "Canonicalizer", "DerivativeClaim", "DerivativeResult", "IdentityClaim", "IdentityResult",
    "NormalForms", "TermDifference", "Witness", "check_identity", "derivative_along", "evaluate",
    "make_witness", "witness_constant",
]
