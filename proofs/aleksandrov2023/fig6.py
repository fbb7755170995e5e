"""Fig. 6 of paper 002: a = 0, h = 1, τ = 1, b = −1, μ = 2 (Remark 3: a = 0, b < 0) — convergence."""

from lkverify.simulate import Converges

from .section6 import FIG6, figure

__all__ = ["fig6"]

fig6 = figure("fig6", "Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2", FIG6,
              [Converges("Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2")], t_end=1000)
