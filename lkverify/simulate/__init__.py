"""The simulation stage: a symbolic System integrated numerically, and what the papers say about the runs.

* :mod:`~lkverify.simulate.dop853` — the one integrator: SciPy's DOP853 method of steps compiled with
  numba (once per machine), the right-hand side as native code (:mod:`~lkverify.simulate.native`,
  llvmlite); :func:`simulate` runs on it (:mod:`~lkverify.simulate.compiled`), the sweeps through
  :mod:`~lkverify.simulate.batch`;
* :mod:`~lkverify.simulate.solver` — the same method of steps on SciPy's steppers with a Python
  right-hand side (:func:`solve_dde`), for what only it handles: quadrature terms (general kernels),
  histories that are functions of t, RK45; with :mod:`~lkverify.simulate.history` (dense
  output), :mod:`~lkverify.simulate.events` (breakpoints, divergence, the step floor) and
  :mod:`~lkverify.simulate.checks` (argument checks);
* :mod:`~lkverify.simulate.compile` — :func:`compile_system`: the right-hand side generated from the System;
* :mod:`~lkverify.simulate.family` — :func:`compile_family`: compiled once with the swept parameters as
  runtime arguments, integrated many times by :mod:`~lkverify.simulate.batch`;
* :mod:`~lkverify.simulate.control` — :class:`StepControl`: tolerances and step limits;
* :mod:`~lkverify.simulate.runs` — :func:`simulate` and the :class:`Trajectory`;
* :mod:`~lkverify.simulate.experiments` — runs, plotted series and claims about runs;
* :mod:`~lkverify.simulate.trend` — algebraic decay claims (E' ≈ −k h E^λ judged in tail windows);
* :mod:`~lkverify.simulate.envelope` — a predicted envelope against a trajectory;
* :mod:`~lkverify.simulate.rigidbody` — numeric attitude conventions (rotations, ‖χ‖_τ).
"""

from .compile import CompiledSystem, compile_system
from .family import CompiledFamily, compile_family
from .control import QUADRATURE_MAX_STEP, StepControl
from .envelope import EnvelopeCheck, cross_check
from .experiments import (BoundedNotAttractive, Converges, DoesNotConverge, EnvelopeSpec, FasterThan, FromValues, Run,
                          RunClaim, RunSummary, Sensitive, Series, SmootherThan, Until, along)
from .runs import MAX_STEPS, PreparedRun, Trajectory, prepare_run, simulate
from .solver import DDESolution, DenseHistory, Outcome, solve_dde
from .trend import DecaysAlgebraically, LimitAboveFloor

__all__ = [
    "FromValues", "along",
    "BoundedNotAttractive", "CompiledSystem", "Converges", "DDESolution", "DenseHistory", "DoesNotConverge",
    "EnvelopeCheck", "EnvelopeSpec", "FasterThan", "MAX_STEPS", "Outcome", "PreparedRun", "QUADRATURE_MAX_STEP",
    "Run", "RunClaim", "RunSummary", "Sensitive", "Series", "SmootherThan", "StepControl", "Trajectory",
    "compile_system", "CompiledFamily", "compile_family", "cross_check", "prepare_run", "simulate", "solve_dde",
    "DecaysAlgebraically", "LimitAboveFloor", "Until",
]
