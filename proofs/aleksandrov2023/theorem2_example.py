"""Theorem 2 of paper 002 simulated: the catalogued instance of (1) and two counter-instances.

The system is :data:`.decomposition.system1`, the same symbolic (1) the checks of Theorem 2 use; the
history is constant, q ≡ (1/2, −1/2), q̇ ≡ 0 on [−τ, 0].

* ``theorem2_example`` — the instance (A, B not symmetric, μ = 3, τ = 1): (7), (8) asymptotically
  stable, so Theorem 2 predicts convergence; the decay is algebraic, ‖(q, q̇)‖ ~ t^{−1/(μ−1)} = t^{−1/2},
  so the claims are "below 0.05 at t = 1000" (the distance is about 0.035 there, not the catalogue's
  usual 1e-3) and the law E' ≈ −kE^λ with E = ‖(q, q̇)‖², λ = (μ + 1)/2 = 2 and a steady rate k in
  the tail windows (:class:`~lkverify.simulate.DecaysAlgebraically`), so that E → 0.
* ``theorem2_counter`` — τ = 1/4 ((8) loses asymptotic stability: k1 + τd1 < 0, an escaping ray) and
  b11 = −1/4 ((7) loses it: −A⁻¹B has a positive eigenvalue); both distances at least double by t = 27
  (both blow up soon after; the runs stop before that).
"""

import dataclasses

import numpy as np

from lkverify import Converges, Example, Run, Series
from lkverify.simulate import DecaysAlgebraically
from lkverify.simulate.experiments import RunClaim, along

from .decomposition import PAPER, system1

__all__ = ["HISTORY", "Grows", "distance", "theorem2_example", "theorem2_counter"]

HISTORY = {"q": [0.5, -0.5], "p": [0.0, 0.0]}


def distance(states):
    """‖(q, q̇)‖ along a trajectory."""
    return np.sqrt(np.sum(states["q"] ** 2, axis=1) + np.sum(states["p"] ** 2, axis=1))


@dataclasses.dataclass(frozen=True)
class Grows(RunClaim):
    """The distance at the end is at least ``factor`` times its initial value (the run did not converge).

    Examples
    --------
    >>> from lkverify.simulate.runs import simulate
    >>> tr = simulate(system1, history=HISTORY, t_end=27.0, values={"tau": "1/4"}, t_eval=np.linspace(0, 27, 55))
    >>> Grows("τ = 1/4").check(theorem2_counter, {"τ = 1/4": tr}).status.value
    'simulated'
    """

    run: str
    factor: float = 2.0

    @property
    def name(self):
        return f"{self.run}: the distance grows ×{self.factor:g}"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        d = np.asarray(along(example.distance, tr.states, tr.values), dtype=float)
        ratio = float(d[-1] / d[0])
        return self._res(ratio >= self.factor, {"initial": float(d[0]), "final": float(d[-1]), "ratio": ratio},
                         f"distance {d[0]:.3g} at t = {tr.t[0]:g}, {d[-1]:.3g} at t = {tr.t[-1]:g} "
                         f"(×{ratio:.3g}, need ≥ ×{self.factor:g})")


_SERIES = [Series("q_1", lambda s: s["q"][:, 0]), Series("q_2", lambda s: s["q"][:, 1])]

theorem2_example = Example(
    "theorem2_example",
    title="Theorem 2: the catalogued instance of (1) (A, B not symmetric, μ = 3, τ = 1) converges",
    runs=[Run("instance", system1, {}, HISTORY)],
    t_end=1000, series=_SERIES, distance=distance, ylabel="q", samples=2001,
    claims=[Converges("instance", tol=0.05),
            DecaysAlgebraically("instance", lambda s: distance(s) ** 2, "1", order=2)],
    paper=PAPER, plot_until=100,
)

theorem2_counter = Example(
    "theorem2_counter",
    title="Theorem 2: counter-instances, (8) unstable (τ = 1/4) and (7) unstable (b11 = −1/4)",
    runs=[Run("τ = 1/4", system1, {"tau": "1/4"}, HISTORY), Run("b11 = −1/4", system1, {"b11": "-1/4"}, HISTORY)],
    t_end=27, series=_SERIES, distance=distance, ylabel="q", samples=541,
    claims=[Grows("τ = 1/4"), Grows("b11 = −1/4")], paper=PAPER,
)
