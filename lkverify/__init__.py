"""lkverify: check Lyapunov–Krasovskii stability proofs.

The public API: declare parameters, states, a system and a functional; derive
V̇ along the system; check identity claims; run catalogue items.  The
numeric layers are modules of their own: :mod:`lkverify.simulate` (and the
integrator :mod:`lkverify.dde`), :mod:`lkverify.bounds` (certified constants),
:mod:`lkverify.conditions` (positivity), :mod:`lkverify.region` (parameters,
region and envelope), :mod:`lkverify.rigidbody`, :mod:`lkverify.envelope`.
"""

from .budget import BudgetExceeded, Deadline
from .claims import DerivativeClaim, Hypothesis, IdentityClaim
from .derivative import Block, DerivativeResult, derivative_along
from .errors import InputError, LkverifyError
from .functional import Functional, memory_integral, tail_integral, window_integral
from .identity import IdentityResult, TermDifference, check_identity
from .items import Check, Item, Theorem
from .parameters import Kind, ParameterSpec, Parameters
from .results import Report, Result
from .states import Frame, UnitVector, Vector
from .status import Status
from .symbols import t, xi, zeta
from .system import Equation, System
from .terms import Term
from .vectors import cross, dot, norm, norm_power, norm_squared, quad

__all__ = [
    "Block", "BudgetExceeded", "Check", "Deadline", "DerivativeClaim", "DerivativeResult", "Equation", "Frame",
    "Functional", "Hypothesis", "IdentityClaim", "IdentityResult", "InputError", "Item", "Kind",
    "LkverifyError", "ParameterSpec", "Parameters", "Report", "Result", "Status", "System", "Term",
    "TermDifference", "Theorem", "UnitVector", "Vector", "check_identity", "cross",
    "derivative_along", "dot", "memory_integral", "norm", "norm_power", "norm_squared", "quad",
    "t", "tail_integral", "window_integral", "xi", "zeta",
]

__version__ = "0.1.0"
