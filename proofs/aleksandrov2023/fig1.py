"""Fig. 1 of paper 002: h = 0.7, a = 2, b = 2, τ = 0.9, μ = 1 — the trajectory converges."""

from lkverify.simulate import Converges

from .section6 import FIG1, figure

__all__ = ["fig1"]

fig1 = figure("fig1", "Fig. 1: b = 2, μ = 1", FIG1, [Converges("Fig. 1: b = 2, μ = 1")], t_end=100)
