"""Fig. 3 of paper 002: b = −2 as in Fig. 2, but μ = 2 — slow convergence."""

from lkverify.simulate import Converges

from .section6 import FIG1, figure

__all__ = ["fig3"]

fig3 = figure("fig3", "Fig. 3: b = −2, μ = 2", {**FIG1, "b": "-2", "mu": "2"},
              [Converges("Fig. 3: b = −2, μ = 2")], t_end=1000)
