"""Section 6 of paper 001: decreasing dissipation h = (1+t)^{−7/8} and h = (1+t)^{−8/7}.

Initial aircraft angles (0.5, 0.5, −0.5), ω = (0.3, 0.3, 0.3).  With h = (1+t)^{−7/8} the
body converges (oscillations die out near t ≈ 200); with h = (1+t)^{−8/7} the motion stays
bounded and is not attractive: the energy Ṽ of Remark 2 tends to a positive limit.
"""

import numpy as np
import sympy

from lkverify import t
from lkverify.simulate import BoundedNotAttractive, Converges, DoesNotConverge, FromValues, Run, Series
from lkverify.catalogue.examples import Example
from lkverify.simulate.figures import AngleHistory, show_value, show_vector
from lkverify.simulate.rigidbody import DEFAULT_CONVENTION, inertial_vectors_from_angles

from .equations import PAPER, P, gamma, system
from .theorem1_functional import functional

__all__ = ["example", "HISTORY", "INITIAL", "initial_history", "remark2_energy", "distance", "per_vector_distance"]

_DEFAULTS = P.resolve({})  # the declared defaults: J, a1, a2, r1, r2, r3 of section 6, never retyped
_R = {name: np.array([float(x) for x in _DEFAULTS[name]]) for name in ("r1", "r2", "r3")}



def initial_history(angles, omega0, convention=DEFAULT_CONVENTION):
    """The triad s1, s2, s3 (columns of Rᵀ, r_i = base axes) from the aircraft angles, and ω."""
    S = inertial_vectors_from_angles(*angles, convention=convention)
    return {"omega": list(omega0), "s1": list(S[:, 0]), "s2": list(S[:, 1]), "s3": list(S[:, 2])}


INITIAL = AngleHistory((0.5, 0.5, -0.5), (0.3, 0.3, 0.3), initial_history)
HISTORY = INITIAL.history()


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


def per_vector_distance(states):
    """max_i ‖s_i − r_i‖ along a trajectory (each vector against its target)."""
    return np.max([_e(i)(states) for i in (1, 2, 3)], axis=0)


def _describe_history(history, convention, overridden):
    parts = []
    if overridden & {"s1", "s2", "s3"}:
        parts.append(", ".join(f"{k} = {show_vector(history[k])}" for k in ("s1", "s2", "s3")) + " (--history)")
    else:
        parts.append(r"($\varphi, \theta, \psi$) = " + show_vector(INITIAL.angles)
                     + (f" [{convention}]" if convention != DEFAULT_CONVENTION else ""))
    parts.append(r"$\omega$ = " + show_vector(history["omega"]) + (" (--history)" if "omega" in overridden else ""))
    return ", ".join(parts)


def _caption(values, history, convention, overridden):
    return "Section 6 of paper 001: decreasing dissipation; " + _describe_history(history, convention, overridden)


def _run_caption(label, values, history, convention, overridden):
    return f"h = {show_value(values['h'])}"


CONVERGING, BOUNDED = "h = (1+t)^(−7/8)", "h = (1+t)^(−8/7)"
example = Example(
    "example",
    caption=_caption, run_caption=_run_caption, initial=INITIAL,
    distances={"combined": distance, "per-vector": per_vector_distance},
    vectors=[(f"‖s{i} − r{i}‖", _e(i)) for i in (1, 2, 3)], targets=[0.0, 0.0, 0.0], ylabel_tex=r"$\omega$ components",
    title="Section 6: decreasing dissipation h = (1+t)^(−β)",
    runs=[Run(CONVERGING, system, {"h": "(1+t)**(-7/8)"}, HISTORY),
          Run(BOUNDED, system, {"h": "(1+t)**(-8/7)"}, HISTORY)],
    t_end=2400,
    series=[Series("ω_x", lambda st: st["omega"][:, 0]), Series("ω_y", lambda st: st["omega"][:, 1]),
            Series("ω_z", lambda st: st["omega"][:, 2])],
    claims=[Converges(CONVERGING, tol=1e-3, by=800),
            BoundedNotAttractive(BOUNDED, FromValues(remark2_energy), "(1+t)**(-8/7)", bound=3.0),
            DoesNotConverge(BOUNDED, floor=1e-2)],
    ylabel="ω components",
    samples=12001,
    plot_until=600,
    paper=PAPER,
)
