"""Fig. 4 of paper 002: a = 0.6, h = 0.2, b = −0.6, μ = 1 — no convergence; the paper's
irregular-looking curves are tested for sensitive dependence on the initial data."""

from lkverify.simulate import DoesNotConverge, Sensitive

from .section6 import FIG4, figure

__all__ = ["fig4"]

fig4 = figure("fig4", "Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1", FIG4,
              [DoesNotConverge("Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1", floor=0.05),
               Sensitive("Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1")], t_end=200)
