"""lkverify: check Lyapunov–Krasovskii stability proofs.

The public API: declare parameters, states, a system and a functional; derive
V̇ along the system; check identity claims; run catalogue items.  The
numeric layers are modules of their own: :mod:`lkverify.simulate.compile` (and the
integrator :mod:`lkverify.simulate.solver`), :mod:`lkverify.certify.bounds` (certified constants),
:mod:`lkverify.certify.conditions` (positivity), :mod:`lkverify.certify.decay` (parameters,
region and envelope), :mod:`lkverify.simulate.rigidbody`, :mod:`lkverify.simulate.envelope`.
"""

from .options import BudgetExceeded, Deadline
from .symbolic.claims import DerivativeClaim, Hypothesis, IdentityClaim
from .symbolic.derivative import Block, DerivativeResult, derivative_along
from .errors import InputError, LkverifyError
from .declare.functional import Functional, memory_integral, tail_integral, window_integral
from .symbolic.identity import IdentityResult, TermDifference, check_identity
from .catalogue.items import Check, Item, Theorem
from .declare.parameters import Kind, ParameterSpec, Parameters
from .report.results import Report, Result
from .declare.states import Frame, UnitVector, Vector
from .status import Status
from .declare.symbols import t, xi, zeta
from .declare.system import Equation, System
from .declare.terms import Term
from .declare.vectors import cross, dot, norm, norm_power, norm_squared, quad

__all__ = [
    "Block", "BudgetExceeded", "Check", "Deadline", "DerivativeClaim", "DerivativeResult", "Equation", "Frame",
    "Functional", "Hypothesis", "IdentityClaim", "IdentityResult", "InputError", "Item", "Kind",
    "LkverifyError", "ParameterSpec", "Parameters", "Report", "Result", "Status", "System", "Term",
    "TermDifference", "Theorem", "UnitVector", "Vector", "check_identity", "cross",
    "derivative_along", "dot", "memory_integral", "norm", "norm_power", "norm_squared", "quad",
    "t", "tail_integral", "window_integral", "xi", "zeta",
]

__version__ = "0.1.0"
