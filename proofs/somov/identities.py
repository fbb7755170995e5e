"""The plain symbols of paper 003's vector identities (rational functions of σ, ω, σ̇, u, v, a).

The kinematic and linearisation identities of paper 003 are rational in the components of σ and
polynomial in the rest; they are decided by the library's rational-function engine,
:func:`lkverify.symbolic.rational.matrix_identity` (re-exported here).  Symbols: σ = (σ1, σ2, σ3), ω, σ̇ (``sd``), u, and v, a
as generic vectors where a claim holds for every v and a.
"""

from __future__ import annotations

import sympy

from lkverify.symbolic.rational import matrix_identity, nonzero_witness

__all__ = ["vec", "SIG", "OMEGA", "SD", "U", "V", "A", "matrix_identity", "nonzero_witness"]


def vec(name: str, text: str) -> sympy.Matrix:
    """A column of three real symbols ``text1, text2, text3``."""
    return sympy.Matrix(sympy.symbols(f"{text}1:4", real=True))


SIG, OMEGA, SD, U, V, A = (vec(n, s) for n, s in (("sigma", "σ"), ("omega", "ω"), ("sigmadot", "σ̇"),
                                                   ("u", "u"), ("v", "v"), ("a", "a")))
