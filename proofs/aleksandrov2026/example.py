"""Section 5 of paper 000: the delayed restoring torque (Fig. 1) and the nonlinear PID (Fig. 2).

t0 = 0, constant initial functions on [−1, 0]; the PID run converges faster and more smoothly.
"""

import numpy as np

from lkverify.simulate import Converges, FasterThan, Run, Series, SmootherThan
from lkverify.catalogue.examples import Example
from lkverify.simulate.figures import show_vector

from .equations import PAPER, P, system, system_pid

__all__ = ["example", "HISTORY"]

HISTORY = {"omega": [0.3, -0.4, 0.4], "s1": [0, 0, 1], "s2": [2 / np.sqrt(5), 1 / np.sqrt(5), 0],
           "s3": [-1 / np.sqrt(5), 2 / np.sqrt(5), 0]}
R1, R2 = (np.array([float(x) for x in P[name].default]) for name in ("r1", "r2"))  # the declared r1, r2


def _e1(states):
    return np.linalg.norm(states["s1"] - R1, axis=1)


def _e2(states):
    return np.linalg.norm(states["s2"] - R2, axis=1)


def _distance(states):
    return np.sqrt(_e1(states) ** 2 + _e2(states) ** 2 + np.sum(states["omega"] ** 2, axis=1))


def _per_vector(states):
    return np.maximum(_e1(states), _e2(states))


def _caption(values, history, convention, overridden):
    shown = ", ".join(f"{k} = {show_vector(history[k])}" for k in sorted(overridden))
    return ("Section 5 of paper 000: delayed restoring torque (7) and nonlinear PID (13)"
            + (f"; --history {shown}" if shown else ""))


DELAYED, PID = "delayed feedback (7)", "PID (13), G = exp(−2ζ)I"
example = Example(
    "example",
    caption=_caption, distances={"combined": _distance, "per-vector": _per_vector},
    vectors=[("‖s1 − r1‖", _e1), ("‖s2 − r2‖", _e2)], targets=[0.0, 0.0], ylabel_tex=r"$\|s_i - r_i\|$",
    title="Section 5: delayed restoring torque (Fig. 1) and nonlinear PID (Fig. 2)",
    runs=[Run(DELAYED, system, {}, HISTORY), Run(PID, system_pid, {}, HISTORY)],
    t_end=1000,
    series=[Series("‖s1 − r1‖", _e1), Series("‖s2 − r2‖", _e2)],
    claims=[Converges(DELAYED), Converges(PID), FasterThan(PID, DELAYED, level=1e-2), SmootherThan(PID, DELAYED)],
    ylabel="‖s_i − r_i‖",
    plot_until=400,
    paper=PAPER,
)
