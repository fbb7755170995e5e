"""Fig. 5 of paper 002: the gains of Fig. 4 with μ = 2 — convergence."""

from lkverify.simulate import Converges

from .section6 import FIG4, figure

__all__ = ["fig5"]

fig5 = figure("fig5", "Fig. 5: a = 0.6, h = 0.2, b = −0.6, μ = 2", {**FIG4, "mu": "2"},
              [Converges("Fig. 5: a = 0.6, h = 0.2, b = −0.6, μ = 2", tol=1e-3)], t_end=1000)
