"""Fig. 7 of paper 002: the gains of Fig. 6 from (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1).

The run is compared with estimate (15) as printed:
‖s(t) − r‖ ≤ 9.21‖χ‖_τ (1 + 0.23‖χ‖_τ (t − t0))^{−1}, valid for ‖χ‖_τ < 0.28.
"""

import numpy as np

from lkverify.simulate import Converges, EnvelopeSpec, Series
from lkverify.simulate.rigidbody import chi_norm

from .section6 import FIG6, FIG7_HISTORY, PRINTED_15, R_TARGET, figure, s_minus_r

__all__ = ["fig7", "chi_of_history", "printed_15_envelope"]

TITLE = "Fig. 7: Fig. 6 gains, (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1)"


def chi_of_history(run):
    """‖χ‖_τ of the run's constant history (the one used, after --history): the uniform norm of (s − r, ω) in R⁶ (lkverify.simulate.rigidbody.chi_norm)."""
    s = np.asarray(run.history["s"], dtype=float).ravel()  # a --history value is a (3, 1) column
    w = np.asarray(run.history["omega"], dtype=float).ravel()
    return float(chi_norm(s - R_TARGET, w))


def printed_15_envelope(tt, chi):
    """(15) as printed for ‖s − r‖: d1‖χ‖_τ / (1 + d3‖χ‖_τ (t − t0)), t0 = 0."""
    return PRINTED_15["d1"] * chi / (1 + PRINTED_15["d3"] * chi * tt)


ENVELOPE_CAPTION = (rf"(15) as printed: $\|s(t) - r\| \leq {PRINTED_15['d1']:g}\,\|\chi\|_\tau"
                    rf"\,(1 + {PRINTED_15['d3']:g}\,\|\chi\|_\tau\, t)^{{-1}}$")

fig7 = figure("fig7", TITLE, FIG6, [Converges(TITLE)], t_end=1500, history=FIG7_HISTORY,
              envelope=EnvelopeSpec("(15) as printed: ‖s − r‖ ≤ 9.21‖χ‖_τ/(1 + 0.23‖χ‖_τ t)",
                                    Series("‖s − r‖", s_minus_r), printed_15_envelope, chi_of_history, TITLE,
                                    valid_below=PRINTED_15["delta_tilde"]),
              envelope_caption=ENVELOPE_CAPTION)
