"""Bound steps: the inequality chain of a proof, refuted by witnesses or proved by checked rules.

* :mod:`.quadratic` — :class:`BoundClaim` for unconstrained states, decided exactly by
  the rule :class:`QuadraticForms` (PSD forms plus nonnegative window integrals).
* :mod:`.measures` — the scalar measures a bound is written in (‖s(t) − r‖, window
  norms (∫‖·‖^p)^{1/p}, window integrals of norm powers, sups over the window) and the
  region that bounds them.
* :mod:`.rules` — the checked rules a proof names (triangle, Cauchy–Schwarz with an
  operator norm, ‖a × b‖ ≤ ‖a‖‖b‖, unit-vector identities, Young, Hölder on a window,
  a bound on a weight, a template constant over a chart, ‖F(v)‖ ≤ κ‖v‖^k for a homogeneous
  polynomial field F).
* :mod:`.witnesses` — adversarial witnesses: states with piecewise-constant histories,
  pushed by local optimisation, rechecked in interval arithmetic.
* :mod:`.memory` — memory integrals ∫_0^t κ(t − ξ)‖v(ξ)‖^p dξ as measures, and their rules
  (the integral written in its measures, a kernel bound, Hölder on the memory, the region's
  bound, Krasovskii's conclusion with integrable kernels).
* :mod:`.timevarying` — time-varying rates: :class:`TimeVaryingRate` (V̇ ≤ −α h^ν(t) V from
  steps whose coefficients are powers of h(t), and the envelope) and :class:`UpperBound`
  (a measure replaced by a bound a decided condition gives).
* :mod:`.signals`, :mod:`.limits` — conclusions by signal arguments: a nonincreasing V bounds the signals
  (:class:`Dissipation`, :class:`LevelSet`, :class:`Conserved`, :class:`BoundedStates`), square
  integrability (:class:`SquareIntegrable`), Barbalat's lemma (:class:`Barbalat`), limits
  (:class:`LinearLimit`, :class:`FiniteLimit`), the comparison lemma (:class:`Comparison`), LaSalle
  (:class:`LaSalle`), Chetaev's instability (:class:`Chetaev`).
* :mod:`.forgetting` — :class:`Forgetting`: least squares with bounded-gain forgetting keeps its gain
  positive definite and bounded (Ẋ = κ(FFᵀ − λX), λ = λ0(1 − N(X⁻¹)/k0) ⇒ X ⪰ I/k0, 0 ≤ λ ≤ λ0).
* :mod:`.auto` — :class:`Auto`: a term bound whose rule lkverify finds (candidates tried in a
  documented order, the report naming the one that proved it).
* :mod:`.chain` — :class:`TermwiseBound`: ``lhs ≤ rhs`` with lhs a sum of labelled terms
  of V or of the exact V̇, each term bounded by a rule, the bounds summed and compared
  with rhs on the region.
"""

from .auto import Auto
from .chain import ChainResult, Decay, TermBound, TermResult, TermwiseBound, lyapunov_steps
from .measures import Measure, Region, norm_measure, sup_norm, window_integral_measure, window_norm
from .memory import (Evaluated, KernelBound, MemoryHolder, MemoryKrasovskii, MemoryMeasure, MemoryWeight,
                     memory_integral_of, memory_measure)
from .quadratic import BoundClaim, QuadraticForms, StepResult, quadratic_upper_bound
from .rules import (CauchySchwarz, Context, Equal, Nonpositive, Printed, Rayleigh, Template, WindowWeight, Young,
                    crossed, homogeneous_field, integral_of, measured, scaled, unit)
from .witnesses import UnsupportedClaim, Witness, search_witness
from .timevarying import TimeVaryingRate, UpperBound, sup_in_t, sup_on
from .signals import Barbalat, BoundedStates, Conserved, Dissipation, Facts, LevelSet, SquareIntegrable
from .forgetting import Forgetting
from .limits import BoundedSignal, Chetaev, Comparison, Decided, FiniteLimit, Follows, LaSalle, LinearLimit

__all__ = ["Auto", "BoundClaim", "CauchySchwarz", "ChainResult", "Context", "Decay", "Equal", "Measure", "Nonpositive",
           "Printed", "QuadraticForms", "Rayleigh", "Region", "StepResult", "Template", "TermBound", "TermResult",
           "TermwiseBound", "UnsupportedClaim", "WindowWeight", "Witness", "Young", "crossed", "homogeneous_field",
           "integral_of",
           "measured", "norm_measure", "quadratic_upper_bound", "scaled", "search_witness", "sup_norm", "unit",
           "window_integral_measure", "window_norm",
           "Evaluated", "KernelBound", "MemoryHolder", "MemoryKrasovskii", "MemoryMeasure", "MemoryWeight",
           "memory_integral_of", "memory_measure"]
__all__ += ["TimeVaryingRate", "UpperBound", "sup_in_t", "sup_on", "lyapunov_steps"]
__all__ += ["Barbalat", "BoundedSignal", "BoundedStates", "Chetaev", "Comparison", "Conserved", "Dissipation", "Facts",
            "Decided", "FiniteLimit", "Follows", "Forgetting", "LaSalle", "LevelSet", "LinearLimit", "SquareIntegrable"]
