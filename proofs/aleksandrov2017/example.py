"""Section 6 of paper 001: decreasing dissipation h = (1+t)^{−7/8} and h = (1+t)^{−8/7}.

Initial aircraft angles (0.5, 0.5, −0.5), ω = (0.3, 0.3, 0.3).  With h = (1+t)^{−7/8} the
body converges (oscillations die out near t ≈ 200); with h = (1+t)^{−8/7} the motion stays
bounded and is not attractive: the energy Ṽ of Remark 2 tends to a positive limit.
"""

import numpy as np
import sympy

from lkverify import t
from lkverify.catalogue.examples import Example
from lkverify.simulate import BoundedNotAttractive, Converges, DoesNotConverge, FromValues, Run, Series
from lkverify.simulate.rigidbody import inertial_vectors_from_angles

from .equations import PAPER, P, gamma, system
from .theorem1 import functional

__all__ = ["example", "HISTORY", "remark2_energy", "distance"]

_DEFAULTS = P.resolve({})  # the declared defaults: J, a1, a2, r1, r2, r3 of section 6, never retyped
_R = {name: np.array([float(x) for x in _DEFAULTS[name]]) for name in ("r1", "r2", "r3")}

_S0 = inertial_vectors_from_angles(0.5, 0.5, -0.5)  # columns s1, s2, s3 (r_i = base axes)
HISTORY = {"omega": [0.3, 0.3, 0.3], "s1": list(_S0[:, 0]), "s2": list(_S0[:, 1]), "s3": list(_S0[:, 2])}


def _state_arguments():
    """The state components in the order the energy is evaluated in: ω, s1, s2, s3."""
    return [c for state in system.states for c in state(t)]


def remark2_energy(values=None):
    """Ṽ = ½ωᵀJω + (a1/2)‖s1−r1‖² + (a2/2)‖s2−r2‖², the energy of Remark 2 (V of Theorem 1 at γ = 0).

    Parameters
    ----------
    values : mapping, optional
        Parameter values (checked by :meth:`~lkverify.Parameters.resolve`); the declared
        defaults otherwise.

    Returns
    -------
    callable
        ``energy(states)`` → array along a trajectory (``states``: name → (len(t), 3) array).
    """
    resolved = P.resolve(dict(values or {}))
    expr = functional.expr.subs(gamma, 0).subs(P.substitution(resolved))
    f = sympy.lambdify(_state_arguments(), expr, "numpy")

    def energy(states):
        return f(*[states[state.name][:, i] for state in system.states for i in range(state.dim)])

    return energy


def _e(i):
    return lambda states: np.linalg.norm(states[f"s{i}"] - _R[f"r{i}"], axis=1)


def distance(states):
    """‖(s1 − r1, s2 − r2, s3 − r3, ω)‖ along a trajectory."""
    return np.sqrt(sum(_e(i)(states) ** 2 for i in (1, 2, 3)) + np.sum(states["omega"] ** 2, axis=1))


CONVERGING, BOUNDED = "h = (1+t)^(−7/8)", "h = (1+t)^(−8/7)"
example = Example(
    "example",
    title="Section 6: decreasing dissipation h = (1+t)^(−β)",
    runs=[Run(CONVERGING, system, {"h": "(1+t)**(-7/8)"}, HISTORY),
          Run(BOUNDED, system, {"h": "(1+t)**(-8/7)"}, HISTORY)],
    t_end=2400,
    series=[Series("ω_x", lambda st: st["omega"][:, 0]), Series("ω_y", lambda st: st["omega"][:, 1]),
            Series("ω_z", lambda st: st["omega"][:, 2])],
    distance=distance,
    claims=[Converges(CONVERGING, tol=1e-3, by=800),
            BoundedNotAttractive(BOUNDED, FromValues(remark2_energy), "(1+t)**(-8/7)", bound=3.0),
            DoesNotConverge(BOUNDED, floor=1e-2)],
    ylabel="ω components",
    samples=12001,
    plot_until=600,
    paper=PAPER,
)
