"""Declaring a proof: parameters, states, labelled terms, systems and functionals.

This is the vocabulary proof modules write in (re-exported by :mod:`lkverify`):
:class:`Parameters` hands back SymPy objects and keeps what values are admissible;
:class:`Vector`, :class:`UnitVector` and :class:`Frame` are states with their
constraints; :class:`Term` labels an expression as the paper prints it;
:class:`System` (of :class:`Equation` objects) and :class:`Functional` are what
the later stages derive, check and simulate.  :mod:`lkverify.declare.rigidbody`
declares Euler's and Poisson's equations once.
"""

from .functional import Functional, memory_integral, outer_integrals, split_outer, tail_integral, window_integral
from .parameters import ParameterKind, Parameters, ParameterSpec
from .parse import parse_assignment, parse_value
from .states import Frame, UnitVector, Vector
from .symbols import t, xi, zeta
from .system import Equation, System
from .terms import Term
from .vectors import cross, dot, norm, norm_power, norm_squared, quad

__all__ = [
    "Equation", "Frame", "Functional", "ParameterKind", "ParameterSpec", "Parameters", "System", "Term",
    "UnitVector", "Vector", "cross", "dot", "memory_integral", "norm", "norm_power", "norm_squared",
    "outer_integrals", "parse_assignment", "parse_value", "quad", "split_outer", "t", "tail_integral",
    "window_integral", "xi", "zeta",
]
