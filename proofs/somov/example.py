"""Closed-loop simulations of paper 003 (the paper prints none): (3), (11) saturating and not.

The documented instance (:mod:`.equations`): S° = {−1/10 ± i/10}, a_m = 1/100 rad/s²,
J = diag(1000, 1200, 800) kg·m².  The initial attitude is a large rotation, Φ0 = 150° about
e0 = (2, 2, 1)/3 (:mod:`.kinematics`: σ0 = e0 tan(Φ0/4), |σ0| = 0.767 ≤ 1), with
ω0 = (0.01, −0.02, 0.01) rad/s.  Three runs of the same symbolic closed loop:

* ``(11) saturating``: a_m = 1/100 — SC is active at the start (‖D(v − a)‖_∞ > a_m), the loop is
  (11), not (10);
* ``(10) without saturation``: the loop (3), (10) from the same state — σ̈ = v, so ‖V(t)‖e^{αt}
  stays constant (V̇ = AV of :mod:`.comparison`: checked along the run); it asks for up to 2.8 a_m;
* ``inside the region``: σ0 = 0.05e0 (Φ0 ≈ 11.4°), ω0 = 0, a_m = 1/100 — inside the
  region of :mod:`.region`; ‖V‖ must not increase and SC must stay inactive.

Every run must converge (the limits (5)).  ``lkverify simulate somov.example --plot f.png``
writes σ, ‖V‖ and the factor c = min(1, a_m/‖D(v − a)‖_∞) of SC = c·D(v − a) (c < 1: SC active) of
each run.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy

from lkverify import FromValues, Series, t
from lkverify.catalogue.examples import Example
from lkverify.simulate import Converges, Run
from lkverify.simulate.experiments import RunClaim

from .comparison import jordan_transform
from .equations import PAPER, P, B, closed_loop, closed_loop_10, omega, omega_s, sigma, sigma_s, u_linear
from .kinematics import mrp_of

__all__ = ["example", "HISTORY", "HISTORY_INSIDE", "saturation_ratio", "lyapunov_norm"]

_K = sympy.Rational
_SIG0 = mrp_of(150 * sympy.pi / 180, [_K(2, 3), _K(2, 3), _K(1, 3)])
HISTORY = {"sigma": [float(x) for x in _SIG0], "omega": [0.01, -0.02, 0.01]}
HISTORY_INSIDE = {"sigma": [0.05 * 2 / 3, 0.05 * 2 / 3, 0.05 / 3], "omega": [0.0, 0.0, 0.0]}


def _compiled(values, exprs):
    sub = P.substitution(P.resolve(dict(values)))
    return sympy.lambdify([*sigma(t), *omega(t)], [e.xreplace(sub) for e in exprs], modules="numpy", cse=True)


def saturation_ratio(values):
    """‖D(σ)(v − a)‖_∞/a_m along a trajectory (SC of (11) is active where it exceeds 1)."""
    f = _compiled(values, list(u_linear(sigma_s, omega_s)))
    am = float(P.resolve(dict(values))["a_m"])

    def ratio(states):
        s, w = states["sigma"], states["omega"]
        u = np.array([np.broadcast_to(np.asarray(c, float), s.shape[:1]) for c in f(*s.T, *w.T)])
        return np.max(np.abs(u), axis=0) / am

    return ratio


def lyapunov_norm(values):
    """‖V‖ = (Σᵢ‖T⁻¹(σᵢ, σ̇ᵢ)‖²)^{1/2} along a trajectory, σ̇ = ¼B(σ)ω (:mod:`.comparison`)."""
    T, _ = jordan_transform(P.resolve(dict(values)))
    Ti = np.array(T.inv(), dtype=float)
    f = _compiled(values, list(B(sigma_s) * omega_s / 4))

    def norm(states):
        s, w = states["sigma"], states["omega"]
        sd = np.array([np.broadcast_to(np.asarray(c, float), s.shape[:1]) for c in f(*s.T, *w.T)]).T
        return np.sqrt(sum(np.sum((Ti @ np.stack([s[:, i], sd[:, i]])) ** 2, axis=0) for i in range(3)))

    return norm


@dataclasses.dataclass(frozen=True)
class Saturates(RunClaim):
    """SC is active somewhere along the run (``active=True``) or nowhere (``active=False``)."""

    run: str
    active: bool

    @property
    def name(self):
        return f"{self.run}: SC {'active at some time' if self.active else 'never active'}"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        r = saturation_ratio(tr.values)(tr.states)
        peak = float(np.max(r))
        share = float(np.mean(r > 1))
        ok = (peak > 1) if self.active else (peak <= 1)
        return self._res(ok, {"peak_ratio": peak, "time_share_active": share},
                         f"max ‖D(v − a)‖_∞/a_m = {peak:.3g} along the run; SC active on {100 * share:.0f} % of "
                         f"the samples")


@dataclasses.dataclass(frozen=True)
class LinearDecay(RunClaim):
    """‖V(t)‖e^{αt} constant (``exact_rate``: the loop (10), V̇ = AV) or ‖V‖ non-increasing."""

    run: str
    exact_rate: bool
    rtol: float = 1e-5

    @property
    def name(self):
        return f"{self.run}: " + ("‖V(t)‖e^(αt) constant (V̇ = AV)" if self.exact_rate else "‖V(t)‖ non-increasing")

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        Vn = lyapunov_norm(tr.values)(tr.states)
        if self.exact_rate:
            scaled = Vn * np.exp(float(tr.values["alpha"]) * tr.t)
            big = Vn >= 1e-3 * Vn[0]  # below, the integrator's absolute tolerance dominates
            dev = float(np.max(np.abs(scaled[big] / scaled[0] - 1)))
            return self._res(dev <= self.rtol, {"max_relative_deviation": dev, "until": float(tr.t[big][-1])},
                             f"‖V(t)‖e^(αt)/‖V(0)‖ stays within {dev:.2g} of 1 (rtol {self.rtol:g}) while ‖V‖ ≥ "
                             f"10⁻³‖V(0)‖ (t ≤ {tr.t[big][-1]:.4g})")
        rise = float(np.max(np.diff(Vn) / Vn[:-1].clip(1e-300)))
        return self._res(rise <= self.rtol, {"max_relative_rise": rise, "V0": float(Vn[0])},
                         f"‖V(0)‖ = {Vn[0]:.4g}; largest relative rise between samples {rise:.2g}")


SAT, LIN, INSIDE = "(11): saturating", "(10): without saturation", "(11): inside the region"
example = Example(
    "example",
    title="Paper 003: MRP feedback linearisation (10) with the saturation SC of (11)",
    runs=[Run(SAT, closed_loop, {}, HISTORY), Run(LIN, closed_loop_10, {}, HISTORY),
          Run(INSIDE, closed_loop, {}, HISTORY_INSIDE)],
    t_end=150,
    series=[Series("σ_x", lambda S: S["sigma"][:, 0]), Series("σ_y", lambda S: S["sigma"][:, 1]),
            Series("σ_z", lambda S: S["sigma"][:, 2]), Series("‖V‖", FromValues(lyapunov_norm)),
            Series("SC factor c = min(1, a_m/‖D(v−a)‖_∞) (1: inactive)",
                   FromValues(lambda v: (lambda f: lambda S: np.minimum(1.0, 1.0 / f(S)))(saturation_ratio(v))))],
    distance=lambda S: np.sqrt(np.sum(S["sigma"] ** 2, axis=1) + np.sum(S["omega"] ** 2, axis=1)),
    claims=[Converges(SAT), Converges(LIN), Converges(INSIDE), Saturates(SAT, True), Saturates(INSIDE, False),
            LinearDecay(LIN, True), LinearDecay(INSIDE, False)],
    ylabel="σ, ‖V‖, c",
    samples=2001,
    paper=PAPER,
)
