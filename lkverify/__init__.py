"""lkverify: check Lyapunov–Krasovskii stability proofs.

The pipeline is in the subpackages, one per stage (data flows one way):

:mod:`lkverify.declare`
    the vocabulary: parameters, states, terms, systems, functionals;
:mod:`lkverify.symbolic`
    the exact V̇ along a system, identity claims proved or refuted term by term;
:mod:`lkverify.certify`
    one interval layer (python-flint arb): hypotheses, suprema and constants, matrix
    and form positivity, LMIs, decay models, regions and envelopes;
:mod:`lkverify.simulate`
    the same system integrated, experiments and envelope checks;
:mod:`lkverify.linear`
    linear delay systems: spectra, stability intervals, LK LMI hierarchies with exact certificates;
:mod:`lkverify.sweep`
    gain sweeps on Dask: hypotheses, linear margin and simulation at every grid point, a table and a map;
:mod:`lkverify.catalogue`
    items (theorems, checks, examples) and the loading of proof files;
:mod:`lkverify.report` and :mod:`lkverify.cli`
    results, JSON, text and the command line.

This module re-exports what a proof file needs, so that a proof imports from
``lkverify`` alone.
"""

from .catalogue.items import Check, Item, Link, Theorem
from .certify.hypotheses import Hypothesis, MatrixHypothesis
from .certify.steps import BoundClaim, QuadraticForms
from .declare.functional import Functional, memory_integral, tail_integral, window_integral
from .declare.parameters import ParameterKind, Parameters, ParameterSpec
from .declare.rigidbody import (distance_sum, euler_equation, gyroscopic_term, poisson_equation, poisson_equations,
                                restoring_torque, restoring_torque_rate)
from .declare.states import Frame, UnitVector, Vector
from .declare.symbols import t, xi, zeta
from .declare.system import Equation, System
from .declare.terms import Term
from .declare.vectors import cross, dot, norm, norm_power, norm_squared, quad
from .errors import InputError, LkverifyError, UnsupportedInput
from .options import Accuracy, Budget, BudgetExceeded, Deadline
from .report.results import Kind, Report, Result
from .status import Status
from .symbolic.claims import DerivativeClaim, IdentityClaim
from .symbolic.derivative import Block, DerivativeResult, derivative_along
from .symbolic.identity import IdentityResult, TermDifference, check_identity
from .catalogue.examples import Example
from .catalogue.boxrun import BoxPiece, BoxReport, BoxStatus, FailingPoint, run_over_box
from .declare.boxes import ParameterBox
from .certify.constants import ConstantsJob, Template
from .linear import (LinearDelaySystem, certified_interval, certify_delay, linear_report, rightmost_roots,
                     stability_intervals)
from .linear import linear_family, linearise, linearise_at
from .simulate import (BoundedNotAttractive, Converges, DoesNotConverge, EnvelopeSpec, FasterThan, FromValues, Run,
                       Sensitive, Series, SmootherThan, StepControl, compile_family)
from .sweep import SweepOptions, SweepResult  # the job itself is lkverify.sweep.sweep (the name is the subpackage's)

__all__ = [
    "Accuracy", "Block", "BoundClaim", "Budget", "QuadraticForms", "BudgetExceeded", "Check", "Deadline", "DerivativeClaim", "DerivativeResult",
    "Equation", "Frame", "Functional", "Hypothesis", "IdentityClaim", "IdentityResult", "InputError", "Item",
    "Kind", "Link", "LkverifyError", "MatrixHypothesis", "ParameterKind", "ParameterSpec", "Parameters", "Report",
    "Result", "Status", "System", "Term", "TermDifference", "Theorem", "UnitVector", "UnsupportedInput",
    "Vector", "check_identity", "cross", "derivative_along", "dot", "memory_integral", "norm", "norm_power",
    "norm_squared", "quad", "t", "tail_integral", "window_integral", "xi", "zeta",
    # rigid bodies (declare.rigidbody)
    "distance_sum", "euler_equation", "gyroscopic_term", "poisson_equation", "poisson_equations", "restoring_torque",
    "restoring_torque_rate",
    # examples, runs and claims about them (simulate), constants jobs (certify)
    "BoundedNotAttractive", "ConstantsJob", "Converges", "DoesNotConverge", "EnvelopeSpec", "Example", "FasterThan",
    "FromValues", "Run", "Sensitive", "Series", "SmootherThan", "StepControl", "Template",
    # linear delay systems (linear)
    "LinearDelaySystem", "certified_interval", "certify_delay", "linear_report", "rightmost_roots",
    "stability_intervals",
    "linearise", "linearise_at", "linear_family",
    # sweeps (simulate.family, sweep)
    "compile_family", "SweepOptions", "SweepResult",
    # theorems over boxes of parameters (declare.boxes, catalogue.boxrun)
    "BoxPiece", "BoxReport", "BoxStatus", "FailingPoint", "ParameterBox", "run_over_box",
]

from ._version import __version__  # noqa: E402

