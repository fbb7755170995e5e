"""Certified constants: suprema, best constants and sign proofs on boxes.

Papers say "there exist positive constants c_k"; this module computes them and
proves them.  Every job has two halves:

* an **estimate** -- multistart local maximisation in floating point
  (SciPy); for a supremum it is a *lower* bound, status ``estimated``;
* a **certificate** -- branch and bound with outward-rounded ball arithmetic
  (python-flint's ``arb``); it is a *proved upper* bound, status
  ``certified``.

This module is the public face of the stages below; each lives in its own module:

:func:`compile_arb` (:mod:`.functions`)
    a SymPy expression in named real variables → a function on ``arb`` balls
    returning a ball that contains every value the expression takes on the
    argument balls (an *enclosure*), optionally with the enclosure of the
    gradient.
:func:`sup_bound` (:mod:`.suprema`, on the engine of :mod:`.engine` and the estimator of :mod:`.estimate`)
    the supremum of an expression over a box.
:func:`best_constant` / :func:`check_constant` (:mod:`.ratios`)
    the best ``c`` in "lhs ≤ c·template on the region", and a claimed ``c``
    proved or refuted.
:func:`certify_nonpositive` / :func:`certify_positive`
    prove ``expr ≤ 0`` (``expr > 0``) on a box, or find a proved
    counterexample.
:func:`unit_vector_angles`, :func:`unit_vector_near`,
:func:`rotation_axis_angle`, :func:`ball_point` (:mod:`.charts`)
    charts that turn the papers' manifold regions (a unit sphere, a cap
    ‖s − r‖ ≤ d, rotations near a reference frame, a ball in R³) into boxes.

What "certified" means here
---------------------------
A ``certified`` upper bound ``U`` of ``sup f`` over a box is proved like
this.  The box is covered by finitely many sub-boxes (the leaves of the
branch and bound).  On every leaf the compiled function returns a ball that
contains ``f`` of every point of the leaf, computed by arb with outward
rounding; ``U`` is the largest upper end of these balls (converted to a float
rounded *up*).  Up to three enclosures are intersected on each leaf: the
natural one (the expression evaluated on the leaf's balls), the mean-value
form ``f(c) + Σ ∂ᵢf(leaf)·(xᵢ − cᵢ)`` with the arb-enclosed gradient, and an
affine form (each quantity carried as ``c + Σ gᵢεᵢ ± e`` with arb
coefficients, nonlinear functions linearised at the centre with a
mean-value remainder; see ``enclosure=`` and :mod:`.engine`).  When an enclosed partial
derivative has a constant sign on a leaf, the leaf is replaced by the face
where ``f`` is largest (monotonicity).  Derivatives of
``Abs``/``Min``/``Max`` enclose Clarke's generalised gradient (``sign`` and
``Heaviside`` of a ball that contains 0 are ``[-1, 1]`` and ``[0, 1]``), so
the mean-value and monotonicity arguments hold for these Lipschitz kinks too.
Expressions with jumps (``sign``, ``Heaviside``) get no gradient.

Lower bounds of a supremum, and counterexamples, are point values evaluated in
arb at exact binary (dyadic rational) points inside the region; a point value
whose ball lies above a threshold proves that the threshold is exceeded.

Nothing is certified with floats: floats only store ball endpoints that arb
produced, rounded outward (an upper end up, a lower end down).

Domains.  A function is *undefined* where SymPy's real function is
(``log`` of a nonpositive number, a non-integer power or ``sqrt`` of a
negative number, division by zero).  A ball on which the expression may be
undefined gets the enclosure "not finite" and can never be certified, so a
problem that is not defined on its whole region ends ``undecided``.  A
nonnegative base that touches 0 (``‖s − r‖**(2ν + 2)`` at ``s = r``) is
recognised structurally (sums of squares, ``Abs``, ``sqrt``, even powers,
``exp``, products of those) or by SymPy's assumptions (declare
``Symbol("x", nonnegative=True)`` or give a box with ``lo ≥ 0``).

The examples are in :mod:`lkverify.certify.suprema` and :mod:`lkverify.certify.ratios`.
"""

from .charts import Chart, ball_point, rotation_axis_angle, unit_vector_angles, unit_vector_near
from .engine import ENCLOSURES, BranchProgress, Enclosure
from .functions import ArbFunction, compile_arb
from .ratios import best_constant, check_constant
from .suprema import (DEFAULT_BUDGET_BOXES, DEFAULT_BUDGET_SECONDS, CheckResult, SupResult, certify_nonpositive,
                      certify_positive, sup_bound)

__all__ = [
    "ArbFunction", "BranchProgress", "Chart", "CheckResult", "DEFAULT_BUDGET_BOXES", "DEFAULT_BUDGET_SECONDS",
    "ENCLOSURES", "Enclosure", "SupResult", "ball_point", "best_constant", "certify_nonpositive", "certify_positive",
    "check_constant", "compile_arb", "rotation_axis_angle", "sup_bound", "unit_vector_angles", "unit_vector_near",
]
