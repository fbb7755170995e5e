"""Linear delay systems: spectra, crossing delays, LK LMI hierarchies, delay margins.

:mod:`.model`
    :class:`LinearDelaySystem` ẋ = A x + A_d x(t−h) + ∫_{t−h}^t K(t−s) x(s) ds, built from matrices;
:mod:`.spectrum`
    the rightmost characteristic roots (Breda–Maset–Vermiglio pseudospectral generator, Newton
    refinement on the characteristic equation), ``estimated``;
:mod:`.crossing`
    the delay margin and the stability intervals from the crossing frequencies (exact resultant),
    ``estimated``;
:mod:`.hierarchy`
    the LK LMI hierarchy (Jensen, Wirtinger, Bessel–Legendre of order N; Seuret & Gouaisbaut 2015),
    solved with cvxpy + Clarabel, rounded to rationals and re-verified exactly;
:mod:`.interval`
    one certificate for every delay of an interval (concavity in h: exact; else arb pieces);
:mod:`.instability`
    instability certified: a characteristic root enclosed in the open right half-plane (interval Newton in arb);
:mod:`.stretches`
    certified stable *and* unstable delay intervals (crossing delays enclosed in arb, one proof per interval);
:mod:`.independent`
    stability for every delay decided exactly (no crossing frequency, A + A_d Hurwitz) and certified by
    V = xᵀPx + ∫_{t−h}^t xᵀQx (an exact rational P, Q): the infinite delay margin;
:mod:`.margin`
    the largest (and smallest) delay of a stability interval with a verified certificate, by bisection;
:mod:`.linearise`
    a catalogued System linearised at an equilibrium, exactly (tangent coordinates of unit vectors and frames);
:mod:`.family`
    the same linearisation with grid names kept symbolic, its spectral verdict at many points (gain sweeps);
:mod:`.run`, :mod:`.figures`
    the job of ``lkverify linear`` (one :class:`lkverify.report.Report`) and its figure.
"""

from .crossing import Crossing, StabilityIntervals, crossing_frequencies, stability_intervals
from .hierarchy import (LmiCertificate, LmiResult, certify_delay, check_certificate, method_name, quick_check,
                        solve_certificate)
from .interval import IntervalCertificate, certify_cover, certify_interval
from .instability import Instability, RootBall, newton_test, refute_stability
from .stretches import CertifiedStretch, certify_stretches, crossing_enclosures
from .margin import CertifiedInterval, certified_interval
from .independent import (DelayIndependence, IndependentCertificate, check_independent_certificate,
                          delay_independence, solve_independent_certificate)
from .linearise import Linearisation, linearise, linearise_at, tangent_basis
from .family import LinearBatch, LinearFamily, linear_family
from .model import LinearDelaySystem, parse_delay
from .run import linear_report, system_from_values
from .figures import plot_linear
from .spectrum import Spectrum, generator_matrix, rightmost_roots, spectral_abscissa

__all__ = [
    "CertifiedInterval", "LmiCertificate", "LmiResult", "certified_interval", "certify_delay", "check_certificate",
    "IntervalCertificate", "certify_cover", "certify_interval", "method_name", "quick_check", "solve_certificate", "linear_report", "plot_linear", "system_from_values",
    "Crossing", "LinearDelaySystem", "Spectrum", "StabilityIntervals", "crossing_frequencies", "generator_matrix",
    "parse_delay", "rightmost_roots", "spectral_abscissa", "stability_intervals",
    "Linearisation", "linearise", "linearise_at", "tangent_basis",
    "LinearBatch", "LinearFamily", "linear_family",
    "Instability", "RootBall", "newton_test", "refute_stability",
    "CertifiedStretch", "certify_stretches", "crossing_enclosures",
    "DelayIndependence", "IndependentCertificate", "check_independent_certificate", "delay_independence",
    "solve_independent_certificate",
]
