"""Step control of a simulation: tolerances and step limits, in one option object.

:class:`StepControl` is taken by :func:`lkverify.simulate.runs.simulate`, by
:class:`lkverify.catalogue.examples.Example` and by the run claims; the limits that
apply to a run, and why, are reported in its
:class:`~lkverify.simulate.runs.Trajectory` (``max_step``, ``max_step_reason``).

Every step is also at most the shortest delay long (the method of steps), whatever
``max_step`` says.
"""

from __future__ import annotations

import dataclasses
import math
import numbers

from ..errors import InputError

__all__ = ["StepControl", "QUADRATURE_MAX_STEP"]

#: largest step when the right-hand side has a quadrature term (a memory kernel that is not a sum
#: of exponentials, a window with a weight depending on t): the piece of such an integral over the
#: current step is a trapezoid outside the step error control, so steps are kept short
QUADRATURE_MAX_STEP = 0.05


@dataclasses.dataclass(frozen=True)
class StepControl:
    """Tolerances and step limits of the integrator.

    Parameters
    ----------
    rtol : float, default 1e-8
        Relative tolerance of the step error control.
    atol : float, default 1e-10
        Absolute tolerance.
    max_step : float, default inf
        Largest step (steps are also at most the shortest delay long).
    quadrature_max_step : float, default :data:`QUADRATURE_MAX_STEP` (0.05)
        Largest step when a quadrature term is present (see :data:`QUADRATURE_MAX_STEP`).

    Examples
    --------
    >>> StepControl(rtol=1e-10).atol
    1e-10
    >>> StepControl().limit(has_quadrature=True)
    (0.05, 'quadrature_max_step')
    >>> StepControl(rtol=0)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: StepControl: rtol: expected a positive number, got 0
    """

    rtol: float = 1e-8
    atol: float = 1e-10
    max_step: float = math.inf
    quadrature_max_step: float = QUADRATURE_MAX_STEP

    def __post_init__(self):
        problems = []
        for name, allow_zero, allow_inf in (("rtol", False, False), ("atol", True, False),
                                            ("max_step", False, True), ("quadrature_max_step", False, True)):
            v = getattr(self, name)
            ok = (isinstance(v, numbers.Real) and not isinstance(v, bool) and not math.isnan(v)
                  and (v > 0 or (allow_zero and v == 0)) and (allow_inf or math.isfinite(v)))
            if not ok:
                want = "a non-negative number" if allow_zero else "a positive number"
                problems.append(f"{name}: expected {want}, got {v!r}")
        if problems:
            raise InputError("StepControl: " + "; ".join(problems))

    def limit(self, *, has_quadrature: bool) -> tuple[float, str]:
        """The step limit of a run (before the delay cap) and the option that sets it."""
        if has_quadrature and self.quadrature_max_step < self.max_step:
            return float(self.quadrature_max_step), "quadrature_max_step"
        return float(self.max_step), "max_step"
