"""Theorem 2 and Corollary 2 of paper 001 simulated: nonlinear damping W = (ωᵀDω)², h = (1+t)^{−β}, β = 7/8 and 8/7.

The paper has no figure for section 5; this example runs system (2),(4) of :mod:`.theorem2`
(μ = 3: torque −h(t)·4(ωᵀDω)Dω) from the section 6 initial data (aircraft angles
(0.5, 0.5, −0.5), ω = (0.3, 0.3, 0.3); A = 5, B = 6, C = 4, D = diag(4,4,4), a1 = a2 = 1)
with the two dampings of section 6.  Corollary 2: the equilibrium is asymptotically stable
iff β ≤ 1.

The energy Ṽ = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖² (Remark 2) obeys

    dṼ/dt = −(μ+1) h W = −4h(ωᵀDω)²,

so it decays only through a fourth-order term: along the runs, 1/Ṽ grows in proportion to
∫h (the law Ṽ' ≈ −k h Ṽ^λ with λ = (μ+1)/2 = 2 and a steady measured k), which for β = 7/8
gives the slow algebraic decay Ṽ ~ t^{−1/8} (a local log-log slope near −0.2 at t ≈ 2000),
and for β = 8/7, ∫_T^∞ h < ∞, a positive limit.  The claims are those of
:mod:`lkverify.simulate.trend` (judged in tail windows, not on the last sample):

* β = 7/8: :class:`~lkverify.simulate.DecaysAlgebraically` — Ṽ → 0 along the law;
* β = 8/7: :class:`~lkverify.simulate.LimitAboveFloor` — bounded, Ṽ tends to a positive limit
  (the extrapolated floor), and the distance keeps returning above 1e-2 (does not converge);
* β = 7/8: the algebraic envelope of the proof with α8 *estimated*
  (:class:`.theorem2_envelope.AlgebraicEnvelope`, γ = 0.1, δ2 = 0.5), a comparison only: the *proved*
  α8 (valid with its own, much smaller γ, from a start inside its region δ2 ≈ 0.2 only) is
  compared with a run started inside δ2 by ``lkverify constants aleksandrov2017.theorem2``
  (:class:`.theorem2_envelope.ProvedEnvelopeAgainstRun`).

Why not ``Converges``: at T = 2000 the distance for β = 7/8 is still about 0.25; a "below
1e-3 at the end" claim would need t of order 10^{20}.
"""

from lkverify.simulate import DecaysAlgebraically, DoesNotConverge, FromValues, LimitAboveFloor, Run, Series
from lkverify.catalogue.examples import Example

from .equations import PAPER
from .example import HISTORY, INITIAL, distance, example, per_vector_distance, remark2_energy
from .theorem2 import mu, system4
from .theorem2_envelope import AlgebraicEnvelope

__all__ = ["theorem2_example", "ORDER", "DECAYING", "BOUNDED"]

#: λ of the energy law Ṽ' ≈ −k h Ṽ^λ: W is homogeneous of order μ + 1, Ṽ is quadratic in ω
ORDER = float((mu + 1) / 2)

DECAYING, BOUNDED = "h = (1+t)^(−7/8)", "h = (1+t)^(−8/7)"
_H = {DECAYING: "(1+t)**(-7/8)", BOUNDED: "(1+t)**(-8/7)"}
_ENERGY = FromValues(remark2_energy)


def _caption(values, history, convention, overridden):
    return (r"Theorem 2 of paper 001: damping $-h(t)\,\mathrm{grad}\,W$, $W = (\omega^\top D\omega)^2$; "
            r"section 6 initial data")


theorem2_example = Example(
    "theorem2_example",
    caption=_caption, run_caption=example.run_caption, initial=INITIAL,
    distances={"combined": distance, "per-vector": per_vector_distance},
    vectors=example.vectors, targets=[0.0, 0.0, 0.0], ylabel_tex=r"$\omega$ components",
    title="Theorem 2 / Corollary 2: W = (ωᵀDω)², h = (1+t)^(−β), β = 7/8 and 8/7",
    runs=[Run(label, system4, {"h": h}, HISTORY) for label, h in _H.items()],
    t_end=2000,
    series=[Series("ω_x", lambda st: st["omega"][:, 0]), Series("ω_y", lambda st: st["omega"][:, 1]),
            Series("ω_z", lambda st: st["omega"][:, 2])],
    claims=[DecaysAlgebraically(DECAYING, _ENERGY, order=ORDER),          # h: the run's (follows --set h=…)
            LimitAboveFloor(BOUNDED, _ENERGY, order=ORDER, bound=3.0),
            DoesNotConverge(BOUNDED, floor=1e-2),
            AlgebraicEnvelope(DECAYING, gamma_value=0.1, delta=0.5)],
    ylabel="ω components",
    samples=4001,
    plot_until=600,
    paper=PAPER,
)
