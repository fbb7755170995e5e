"""One interval layer: SymPy → arb balls, outward rounding, certified signs.

Every certified number in lkverify passes through this package, so it is kept
small and self-contained (python-flint's ``arb`` and SymPy only).  Three modules:
:mod:`.rounding` (outward rounding), :mod:`.balls` (the ball primitives of
generated code), :mod:`.convert` (the SymPy → arb converter and signs).

:func:`enclose`
    the ball of a SymPy expression, at a stated precision, with the symbols'
    values given as balls.  This is the *only* SymPy → arb converter:
    :func:`compile_program` (used by :mod:`lkverify.certify.engine` for branch and
    bound) and :func:`enclose` share one tree walk and one whitelist
    (:data:`SUPPORTED`); a node outside it raises
    :class:`UnsupportedExpression`, it is never approximated.
:func:`float_down` / :func:`float_up`, :func:`lower_fraction` / :func:`upper_fraction`
    the *only* outward rounding: a ball (or an exact rational) to a float
    below / above it, or to the exact rational end points of the ball.
    Correct at any arb precision: the end point is read exactly (mantissa and
    exponent) and rounded in the stated direction.
:func:`sign_of`
    the sign of a real constant, decided by enclosures at increasing
    precision, with the enclosure that decided it (:class:`SignResult`).

Numbers are read exactly: a SymPy ``Rational`` p/q is the ball of ``arb(p)/arb(q)``
at the working precision, a SymPy ``Float`` (or Python float) its exact binary
value; ``pi`` and ``E`` are arb's enclosures.

Examples
--------
>>> import sympy
>>> ball = enclose(sympy.sqrt(2), prec=128)
>>> lo, hi = lower_fraction(ball), upper_fraction(ball)
>>> lo ** 2 < 2 < hi ** 2
True
>>> float_down(ball) < float_up(ball)
True
>>> m = sympy.Integer(10)**16 - 1 - sympy.Integer(10)**16 + sympy.Rational(1, 2)
>>> sign_of(m).sign                  # floats say +1/2
-1
"""

from .balls import SUPPORTED
from .convert import (DEFAULT_PREC, Program, SignResult, UnsupportedExpression, compile_program, enclose, sign_of,
                      to_ball)
from .rounding import float_down, float_up, lower_fraction, upper_fraction

__all__ = [
    "DEFAULT_PREC", "SUPPORTED", "Program", "SignResult", "UnsupportedExpression", "compile_program", "enclose",
    "float_down", "float_up", "lower_fraction", "sign_of", "to_ball", "upper_fraction",
]
