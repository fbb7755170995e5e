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
``lkverify`` alone.  The names are imported on first use (``from lkverify import Theorem``
imports :mod:`lkverify.catalogue.items` then), so ``import lkverify`` itself is light.
"""

import os as _os
import sys as _sys

from ._version import __version__

#: SymPy's cache of pure operations (``cacheit``: ``Mul.flatten``, assumptions, ``expand`` …) holds this many
#: entries per function in a process that imports lkverify before SymPy.  SymPy's default of 1,000 is far below
#: the working set of one theorem's derivative, identities and chain (they rebuild the same sub-expressions over
#: and over): the bare report takes 14 % less time at 100,000 for ~80 MB more memory (``benchmarks/bench_report.py``).
#: The cache is transparent (results do not depend on it); ``SYMPY_CACHE_SIZE`` set by the user wins.
SYMPY_CACHE_SIZE = 100_000
if "sympy" not in _sys.modules:
    _os.environ.setdefault("SYMPY_CACHE_SIZE", str(SYMPY_CACHE_SIZE))

from ._lazy import lazy_exports

#: public name → the submodule that defines it; imported on first use (PEP 562), so that
#: ``import lkverify`` (and the command line's ``--help``, ``--version``, ``list``) loads no SymPy
_SOURCES = {
    "Check": ".catalogue.items", "Item": ".catalogue.items", "Link": ".catalogue.items",
    "Theorem": ".catalogue.items", "SignalTheorem": ".catalogue.signal_theorem",
    "Hypothesis": ".certify.hypotheses", "MatrixHypothesis": ".certify.hypotheses",
    "Auto": ".certify.steps", "BoundClaim": ".certify.steps", "QuadraticForms": ".certify.steps",
    "Functional": ".declare.functional", "memory_integral": ".declare.functional",
    "tail_integral": ".declare.functional", "window_integral": ".declare.functional",
    "ParameterKind": ".declare.parameters", "Parameters": ".declare.parameters",
    "ParameterSpec": ".declare.parameters",
    "distance_sum": ".declare.rigidbody", "euler_equation": ".declare.rigidbody",
    "gyroscopic_term": ".declare.rigidbody", "poisson_equation": ".declare.rigidbody",
    "poisson_equations": ".declare.rigidbody", "restoring_torque": ".declare.rigidbody",
    "restoring_torque_rate": ".declare.rigidbody",
    "Frame": ".declare.states", "UnitVector": ".declare.states", "Vector": ".declare.states",
    "t": ".declare.symbols", "xi": ".declare.symbols", "zeta": ".declare.symbols",
    "Equation": ".declare.system", "System": ".declare.system",
    "Term": ".declare.terms",
    "cross": ".declare.vectors", "dot": ".declare.vectors", "norm": ".declare.vectors",
    "norm_power": ".declare.vectors", "norm_squared": ".declare.vectors", "quad": ".declare.vectors",
    "InputError": ".errors", "LkverifyError": ".errors", "UnsupportedInput": ".errors",
    "Accuracy": ".options", "Budget": ".options", "BudgetExceeded": ".options", "Deadline": ".options",
    "Kind": ".report.results", "Report": ".report.results", "Result": ".report.results",
    "Status": ".status",
    "DerivativeClaim": ".symbolic.claims", "IdentityClaim": ".symbolic.claims",
    "Block": ".symbolic.derivative", "DerivativeResult": ".symbolic.derivative",
    "derivative_along": ".symbolic.derivative",
    "IdentityResult": ".symbolic.identity", "TermDifference": ".symbolic.identity",
    "check_identity": ".symbolic.identity",
    "Example": ".catalogue.examples",
    "BoxPiece": ".catalogue.boxrun", "BoxReport": ".catalogue.boxrun", "BoxStatus": ".catalogue.boxrun",
    "FailingPoint": ".catalogue.boxrun", "run_over_box": ".catalogue.boxrun",
    "ParameterBox": ".declare.boxes",
    "ConstantsJob": ".certify.constants", "Template": ".certify.constants",
    "LinearDelaySystem": ".linear", "certified_interval": ".linear", "certify_delay": ".linear",
    "linear_report": ".linear", "rightmost_roots": ".linear", "stability_intervals": ".linear",
    "linear_family": ".linear", "linearise": ".linear", "linearise_at": ".linear",
    "BoundedNotAttractive": ".simulate", "Converges": ".simulate", "DoesNotConverge": ".simulate",
    "EnvelopeSpec": ".simulate", "FasterThan": ".simulate", "FromValues": ".simulate", "Run": ".simulate", "Until": ".simulate",
    "Sensitive": ".simulate", "Series": ".simulate", "SmootherThan": ".simulate", "StepControl": ".simulate",
    "compile_family": ".simulate",
    "SweepOptions": ".sweep", "SweepResult": ".sweep",  # the job itself is lkverify.sweep.sweep (the subpackage's name)
}

__all__ = [
    "Accuracy", "Auto", "Block", "BoundClaim", "Budget", "QuadraticForms", "BudgetExceeded", "Check", "Deadline", "DerivativeClaim", "DerivativeResult",
    "Equation", "Frame", "Functional", "Hypothesis", "IdentityClaim", "IdentityResult", "InputError", "Item",
    "Kind", "Link", "LkverifyError", "MatrixHypothesis", "ParameterKind", "ParameterSpec", "Parameters", "Report",
    "Result", "SignalTheorem", "Status", "System", "Term", "TermDifference", "Theorem", "UnitVector", "UnsupportedInput",
    "Vector", "check_identity", "cross", "derivative_along", "dot", "memory_integral", "norm", "norm_power",
    "norm_squared", "quad", "t", "tail_integral", "window_integral", "xi", "zeta",
    # rigid bodies (declare.rigidbody)
    "distance_sum", "euler_equation", "gyroscopic_term", "poisson_equation", "poisson_equations", "restoring_torque",
    "restoring_torque_rate",
    # examples, runs and claims about them (simulate), constants jobs (certify)
    "BoundedNotAttractive", "ConstantsJob", "Converges", "DoesNotConverge", "EnvelopeSpec", "Example", "FasterThan",
    "FromValues", "Run", "Sensitive", "Series", "SmootherThan", "StepControl", "Template", "Until",
    # linear delay systems (linear)
    "LinearDelaySystem", "certified_interval", "certify_delay", "linear_report", "rightmost_roots",
    "stability_intervals",
    "linearise", "linearise_at", "linear_family",
    # sweeps (simulate.family, sweep)
    "compile_family", "SweepOptions", "SweepResult",
    # theorems over boxes of parameters (declare.boxes, catalogue.boxrun)
    "BoxPiece", "BoxReport", "BoxStatus", "FailingPoint", "ParameterBox", "run_over_box",
]


__getattr__, __dir__ = lazy_exports(__name__, _SOURCES, __all__)

