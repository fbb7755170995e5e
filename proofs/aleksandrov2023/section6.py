"""Section 6 of paper 002: the data shared by the numerical examples (Figs. 1–7).

Θ = diag(5,6,4), r = (1,1,1)/√3, F = h·I; constant initial functions on [−τ, 0] from the
aircraft angles (φ, θ, ψ) = (0.5, 0.6, −0.8) and ω = (1,1,1) (Figs. 1–6), or
(0.8, 0.8, −0.8) and ω = 0.1(1,1,1) (Fig. 7).  The target r is taken from the declared
default of the parameter r, never retyped.
"""

import numpy as np
import sympy

from lkverify.certify.decay import StatedAt
from lkverify.simulate import Run, Series
from lkverify.catalogue.examples import Example
from lkverify.simulate.figures import AngleHistory, show_value, show_vector
from lkverify.simulate.rigidbody import DEFAULT_CONVENTION, inertial_vectors_from_angles

from .equations import PAPER, P, system

__all__ = ["R_TARGET", "initial_history", "SECTION6", "FIG7_HISTORY", "DIRECTION_COSINES", "s_minus_r", "distance",
           "gains", "figure", "EQUILIBRIUM", "caption", "SECTION6_ANGLES", "FIG7_ANGLES", "INITIAL", "FIG1", "FIG4", "FIG6", "PRINTED_15",
           "PRINTED_15_DATA", "PRINTED_15_STATED", "at_printed_15"]

R_TARGET = np.array([float(x) for x in P["r"].default])  # r = (1,1,1)/√3 of section 6


def initial_history(angles, omega0, convention=DEFAULT_CONVENTION):
    """Constant history: s from the aircraft angles (a convention of lkverify.simulate.rigidbody), ω."""
    return {"s": list(inertial_vectors_from_angles(*angles, R_TARGET, convention=convention)),
            "omega": list(omega0)}


SECTION6_ANGLES = AngleHistory((0.5, 0.6, -0.8), (1.0, 1.0, 1.0), initial_history)
FIG7_ANGLES = AngleHistory((0.8, 0.8, -0.8), (0.1, 0.1, 0.1), initial_history)
SECTION6 = SECTION6_ANGLES.history()
FIG7_HISTORY = FIG7_ANGLES.history()


def s_minus_r(states):
    """‖s(t) − r‖ along a trajectory."""
    return np.linalg.norm(states["s"] - R_TARGET, axis=1)


def distance(states):
    """‖χ(t)‖ = ‖(s − r, ω)‖ in R⁶."""
    return np.sqrt(s_minus_r(states) ** 2 + np.sum(states["omega"] ** 2, axis=1))


DIRECTION_COSINES = [Series(f"s_{c}", lambda st, i=i: st["s"][:, i]) for i, c in enumerate("xyz")]


def gains(h, a, b, tau, mu):
    """The parameter values of a figure: F = h·I and the gains a, b, τ, μ (as printed)."""
    return {"F": f"diag({h},{h},{h})", "a": a, "b": b, "tau": tau, "mu": mu}


def caption(number):
    """``caption(values, history, convention, overridden)`` of Fig. ``number``: the gains and data used."""

    def text(values, history, convention, overridden):
        F = values["F"]
        h = (f"h = {show_value(F[0, 0])}" if F == F[0, 0] * sympy.eye(F.shape[0]) else f"F = {show_value(F)}")
        gains = (f"a = {show_value(values['a'])}, {h}, $\\tau$ = {show_value(values['tau'])}, "
                 f"b = {show_value(values['b'])}, $\\mu$ = {show_value(values['mu'])}")
        angles = INITIAL[number]
        if "s" in overridden:
            s_text = "s = " + show_vector(history["s"]) + " (--history)"
        else:
            s_text = ("($\\varphi, \\theta, \\psi$) = " + show_vector(angles.angles)
                      + (f" [{convention}]" if convention != DEFAULT_CONVENTION else ""))
        w_text = "$\\omega$ = " + show_vector(history["omega"]) + (" (--history)" if "omega" in overridden else "")
        return f"Fig. {number}: {gains}; {s_text}, {w_text}"

    return text


def figure(name, title, values, claims, *, t_end, history=SECTION6, envelope=None, samples=4001, envelope_caption=""):
    """One figure of section 6: a single run of (10), (12), the direction cosines plotted up to t = 100.

    The title shown on the figure is computed from the values and history used (:func:`caption`);
    ``title`` is the catalogue's name of the run, which the claims refer to.
    """
    number = int(name[3:])
    return Example(name, title=title, runs=[Run(title, system, values, history)], t_end=t_end,
                         series=DIRECTION_COSINES, distances={"combined": distance, "per-vector": s_minus_r},
                         claims=claims, ylabel="direction cosines", envelope=envelope, samples=samples,
                         plot_until=100, paper=PAPER, caption=caption(number), initial=INITIAL[number],
                         vectors=[("‖s − r‖", s_minus_r)], targets=list(R_TARGET), envelope_caption=envelope_caption,
                         equilibrium=EQUILIBRIUM)


#: the target (11): s = r, ω = 0 (the distances measure convergence to it; ``lkverify sweep`` linearises there)
EQUILIBRIUM = {"s": "r", "omega": [0, 0, 0]}

FIG1 = gains("0.7", a="2", b="2", tau="0.9", mu="1")
FIG4 = gains("0.2", a="0.6", b="-0.6", tau="0.9", mu="1")
FIG6 = gains("1", a="0", b="-1", tau="1", mu="2")
INITIAL = {1: SECTION6_ANGLES, 2: SECTION6_ANGLES, 3: SECTION6_ANGLES, 4: SECTION6_ANGLES, 5: SECTION6_ANGLES,
           6: SECTION6_ANGLES, 7: FIG7_ANGLES}

# Estimate (15) as printed: ‖s(t) − r‖ ≤ 9.21‖χ‖_τ (1 + 0.23‖χ‖_τ (t − t0))^{−1} for ‖χ‖_τ < 0.28.
PRINTED_15 = {"d1": 9.21, "d2": 7.44, "d3": 0.23, "delta_tilde": 0.28}
#: the data at which the paper states (15): the gains of Fig. 6 (Fig. 7 keeps them), section 6's Θ and r (resolved)
PRINTED_15_DATA = {k: v for k, v in P.resolve(FIG6, use_defaults=True).items()
                   if k in ("Theta", "F", "a", "b", "tau", "mu", "r")}
#: (15) compared only there: at other gains the paper states no constants
PRINTED_15_STATED = StatedAt(PRINTED_15, PRINTED_15_DATA,
                             "the Fig. 6/7 data (a = 0, F = I, b = −1, τ = 1, μ = 2, Θ = diag(5,6,4), r = (1,1,1)/√3)")


def at_printed_15(values) -> bool:
    """True when ``values`` (resolved) are the data at which the paper states (15), exactly."""
    return PRINTED_15_STATED.applies(values)
