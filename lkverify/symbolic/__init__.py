"""Symbolic derivation and identities: the exact V̇ along a system, and printed formulas checked.

:func:`derivative_along` applies the chain rule at every argument θ(t) and the Leibniz
rule to every integral term; :func:`check_identity` proves (``exact``) or refutes
(``failed``, with the residual terms at a witness) an equality of labelled terms modulo
the state constraints; :class:`DerivativeClaim` and :class:`IdentityClaim` are how a
proof states them.  :mod:`~lkverify.symbolic.polynomial` is the fast path: an identity whose
difference is the zero polynomial in the canonical atoms is proved before any reduction modulo
the constraints, and the delay-free closed loops of paper 004 are decided there directly
(:func:`compare_polynomials`, :func:`time_derivative`).
"""

from .canonical import Canonicalizer, NormalForms
from .claims import DerivativeClaim, IdentityClaim
from .derivative import Block, DerivativeResult, derivative_along
from .identity import IdentityResult, TermDifference, check_identity
from .polynomial import compare_polynomials, time_derivative, zero_difference
from .witness import Witness, evaluate, make_witness, witness_constant

__all__ = [
    "Block", "Canonicalizer", "DerivativeClaim", "DerivativeResult", "IdentityClaim", "IdentityResult",
    "NormalForms", "TermDifference", "Witness", "check_identity", "compare_polynomials", "derivative_along",
    "evaluate", "make_witness", "time_derivative", "witness_constant", "zero_difference",
]
