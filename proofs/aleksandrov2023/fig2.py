"""Fig. 2 of paper 002: the gains of Fig. 1 with b = −2 (μ = 1) — no convergence."""

from lkverify.simulate import DoesNotConverge

from .section6 import FIG1, figure

__all__ = ["fig2"]

fig2 = figure("fig2", "Fig. 2: b = −2, μ = 1", {**FIG1, "b": "-2"},
              [DoesNotConverge("Fig. 2: b = −2, μ = 1", floor=0.05)], t_end=100)
