"""Certification: everything proved with outward-rounded interval arithmetic (python-flint arb).

One interval layer (:mod:`lkverify.certify.intervals`: the only SymPy→arb converter and
the only outward rounding), one branch-and-bound engine with pluggable enclosure
strategies (:mod:`lkverify.certify.engine`) and one estimator
(:mod:`lkverify.certify.estimate`), and what is built on them:

* hypotheses on the parameters with their margins (:mod:`~lkverify.certify.hypotheses`);
* suprema, signs and best template constants (:mod:`~lkverify.certify.suprema`,
  :mod:`~lkverify.certify.ratios`; :mod:`~lkverify.certify.bounds` is the public face),
  over manifold charts (:mod:`~lkverify.certify.charts`);
* matrix and form positivity (:mod:`~lkverify.certify.matrices`, :mod:`~lkverify.certify.forms`),
  LMIs re-verified exactly (:mod:`~lkverify.certify.lmi`), their results
  (:mod:`~lkverify.certify.conditions`);
* decay models, regions and envelopes (:mod:`~lkverify.certify.decay`) and the job behind
  ``lkverify constants`` (:mod:`~lkverify.certify.constants`).
"""

from .bounds import (Chart, CheckResult, SupResult, ball_point, best_constant, certify_nonpositive, certify_positive,
                     check_constant, compile_arb, rotation_axis_angle, sup_bound, unit_vector_angles, unit_vector_near)
from .conditions import ConditionResult, Estimate, Margin
from .constants import ConstantsJob, ConstantsTuning, Template
from .decay import DecayCertificate, DecayModel, Envelope, certify_decay, estimate_decay, search_parameters
from .engine import Affine, BranchAndBound, Enclosure, MeanValue, MeanValueAffine, NaturalBalls
from .forms import homogeneous_positive_on_sphere
from .hypotheses import Hypothesis, MatrixHypothesis
from .intervals import enclose, float_down, float_up, lower_fraction, sign_of, upper_fraction
from .lmi import best_quadratic_upper_bound, check_lyapunov_matrix, check_quadratic_bound, find_lyapunov_matrix, lmi_feasible
from .matrices import matrix_positive_definite
from .steps import BoundClaim, QuadraticForms, StepResult, quadratic_upper_bound

__all__ = [
    "Affine", "BoundClaim", "BranchAndBound", "QuadraticForms", "StepResult", "quadratic_upper_bound", "Chart", "CheckResult", "ConditionResult", "ConstantsJob", "ConstantsTuning",
    "DecayCertificate", "DecayModel", "Enclosure", "Envelope", "Estimate", "Hypothesis", "Margin",
    "MatrixHypothesis", "MeanValue", "MeanValueAffine", "NaturalBalls", "SupResult", "Template", "ball_point",
    "best_constant", "best_quadratic_upper_bound", "certify_decay", "certify_nonpositive", "certify_positive",
    "check_constant", "check_lyapunov_matrix", "check_quadratic_bound", "compile_arb", "enclose", "estimate_decay",
    "find_lyapunov_matrix", "float_down", "float_up", "homogeneous_positive_on_sphere", "lmi_feasible",
    "lower_fraction", "matrix_positive_definite", "rotation_axis_angle", "search_parameters", "sign_of",
    "sup_bound", "unit_vector_angles", "unit_vector_near", "upper_fraction",
]
