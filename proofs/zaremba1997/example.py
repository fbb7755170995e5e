"""Simulations of paper 004 (the paper prints none): the closed loops of Theorems 1 and 2.

The catalogued instance of :mod:`.equations` (true inertia M = diag(3, 4, 5), estimates from
θ_r(0) = (2, 2, 2); ω_d(t) = (½ sin t, ½ cos(3t/4), ⅓ sin(t/3))), four runs of the same System
objects the identities are proved along:

* **Theorem 1, tracking**: (2.7), (2.8) from the triad turned by 0.8 rad about (1, 1, 1)/√3,
  ω(0) = ω_d(0) — e → 0, ω → ω_d, θ_r bounded (it need not converge to θ).
* **Theorem 1, near s = (−c1, c2, −c3)**: the same loop from 0.01 rad off that equilibrium, θ_r = θ.
* **Theorem 2, composite**: (3.2)–(3.4) with λ(t) = λ0(1 − ‖Γ‖_F/k0), Γ(0) = 5I (‖Γ(0)‖_F = 8.66 ≤ k0),
  φ(0) = 0, ε(0) = 0 — e → 0, ω → ω_d, and θ_r → θ (Theorem 2 (a)).
* **Theorem 2, near s = (−c1, c2, −c3)**: θ_e = ε = 0 there (Theorem 2 (в): unstable).

The runs start with the horizon t = 20 (rtol 1e-6); the two tracking runs go on (the horizon doubled,
:class:`~lkverify.Until`) until max(‖e‖, ‖ω − ω_d‖) < 1e-2 at the end, at most to t = 1280, and the
claims report the time from which that error stays below 1e-2 (about 9 s for the four runs);
``lkverify simulate zaremba1997.example --t-end 60`` runs every one exactly to t = 60.

Claims (status ``simulated``): the tracking runs converge (Theorem 1 slowly at this instance: its run
goes to t = 320 and the error stays below 1e-2 from t ≈ 270, while θ_r drifts far from θ, even through
negative "inertias" — nothing in Theorem 1 keeps θ_r near θ; Theorem 2's error is below 1e-2 from
t ≈ 6.7 at α = 50); θ_r stays bounded; the composite run's
θ_r approaches θ, at an observed exponential rate compared with the γ/2 that (3.12) gives for
‖θ_e‖ (γ = min{λ_c, λ_cλ1/2, 2} with λ1 the smallest λ(t) of the run); both runs started 0.01 rad
from the other equilibrium leave it (distance 0.014 → past 0.5) and reach the programmed motion.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy

from lkverify import Run, Series, Status, StepControl, Until, t
from lkverify.catalogue.examples import Example
from lkverify.simulate.experiments import RunClaim

from .equations import PAPER, P, closed_loop2, frobenius_law, system1

__all__ = ["example", "system2_sim", "INITIAL", "NEAR_OTHER", "LEVEL", "Tracks", "Leaves", "EstimatesBounded", "InLevelSet",
           "lyapunov_along",
           "EstimatesConverge", "rotation", "reference", "errors", "lambda_along"]

#: the loop of Theorem 2 as simulated: λ(t) = λ0(1 − ‖Γ‖_F/k0), Γ = (Γ⁻¹)⁻¹
system2_sim = closed_loop2(frobenius_law(), name="(1.3),(1.4),(3.2)-(3.4), λ = λ0(1 − ‖Γ‖_F/k0)")


def rotation(axis, angle):
    """The rotation matrix of ``angle`` about ``axis`` (Rodrigues)."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


_D = P.resolve({}, use_defaults=True)
_WD0 = [float(sympy.sympify(_D[f"wd{i}"]).subs(t, 0)) for i in (1, 2, 3)]
_THETA = [float(_D["M"][i, i]) for i in range(3)]
_OTHER = np.diag([-1.0, 1.0, -1.0])  # s1 = −c1, s2 = c2, s3 = −c3 (c_i the body axes)


def _triad(R):
    return {"s1": list(R[:, 0]), "s2": list(R[:, 1]), "s3": list(R[:, 2])}


INITIAL = {"omega": _WD0, **_triad(rotation([1, 1, 1], 0.8)), "theta_r": [2.0, 2.0, 2.0]}
NEAR_OTHER = {"omega": _WD0, **_triad(rotation([1, 1, 1], 0.01) @ _OTHER), "theta_r": _THETA}
_COMPOSITE = {"eps": [0.0] * 3, "phi": [0.0] * 9, "G": [0.2, 0.0, 0.0, 0.2, 0.0, 0.2]}


def reference(values, times):
    """ω_d at ``times`` (the run's coefficients)."""
    f = sympy.lambdify(t, sympy.Matrix([values[f"wd{i}"] for i in (1, 2, 3)]), "numpy")
    return np.stack([np.broadcast_to(np.asarray(f(x), float).ravel(), (3,)) for x in times])


def _c(values):
    return [np.array([float(x) for x in values[f"c{i}"]]) for i in (1, 2, 3)]


def errors(tr):
    """‖e‖, ‖ω − ω_d‖, ‖θ_r − θ‖ and the attitude distance √Σ‖sᵢ − cᵢ‖² along a trajectory."""
    v = tr.values
    cs = _c(v)
    ks = [float(v[f"k{i}"]) for i in (1, 2, 3)]
    S = [tr.states[f"s{i}"] for i in (1, 2, 3)]
    e = sum(k * np.cross(s, c) for k, s, c in zip(ks, S, cs))
    we = tr.states["omega"] - reference(v, tr.t)
    theta = np.array([float(v["M"][i, i]) for i in range(3)])
    att = np.sqrt(sum(np.sum((s - c) ** 2, axis=1) for s, c in zip(S, cs)))
    return {"e": np.linalg.norm(e, axis=1), "omega_e": np.linalg.norm(we, axis=1),
            "theta_e": np.linalg.norm(tr.states["theta_r"] - theta, axis=1), "attitude": att}


def lambda_along(tr):
    """λ(t) = λ0(1 − ‖Γ‖_F/k0) of (3.4) along a run of the composite loop."""
    v = tr.values
    out = []
    for g in tr.states["G"]:
        Gm = np.array([[g[0], g[1], g[2]], [g[1], g[3], g[4]], [g[2], g[4], g[5]]])
        out.append(float(v["lam0"]) * (1 - np.linalg.norm(np.linalg.inv(Gm)) / float(v["k0"])))
    return np.array(out)


def _other_distance(tr):
    cs = _c(tr.values)
    signs = (-1, 1, -1)
    return np.sqrt(sum(np.sum((tr.states[f"s{i + 1}"] - sg * c) ** 2, axis=1) for i, (sg, c) in enumerate(zip(signs, cs))))


@dataclasses.dataclass(frozen=True)
class Tracks(RunClaim):
    """‖e‖ and ‖ω − ω_d‖ end below ``tol`` (the auxiliary goal (2.3))."""

    run: str
    tol: float = 1e-3

    @property
    def name(self):
        return f"{self.run}: e → 0, ω → ω_d"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        err = errors(tr)
        e_T, w_T = float(err["e"][-1]), float(err["omega_e"][-1])
        ok = e_T < self.tol and w_T < self.tol
        t_below = _time_below(tr.t, np.maximum(err["e"], err["omega_e"]), self.tol)
        when = (f"both below {self.tol:g} from t = {t_below:.4g} on" if t_below is not None
                else f"not both below {self.tol:g} to the end of the run")
        return self._res(ok, {"e": e_T, "omega_e": w_T, "t_below": t_below},
                         f"‖e‖ = {e_T:.3g}, ‖ω − ω_d‖ = {w_T:.3g} at t = {tr.t[-1]:g} "
                         f"(need < {self.tol:g}); {when} (samples); attitude distance {float(err['attitude'][-1]):.3g}")


def _time_below(times, signal, tol):
    """The first sample time from which ``signal`` stays below ``tol`` to the end of the run (None: never).

    >>> _time_below(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.0, 0.1, 0.5, 0.1]), 0.2)
    3.0
    >>> _time_below(np.array([0.0, 1.0]), np.array([1.0, 0.3]), 0.2) is None
    True
    """
    above = np.nonzero(~(np.asarray(signal) < tol))[0]
    if above.size == 0:
        return float(times[0])
    k = int(above[-1]) + 1
    return float(times[k]) if k < len(times) else None


@dataclasses.dataclass(frozen=True)
class EstimatesBounded(RunClaim):
    """max ‖θ_r(t)‖ over the run stays below ``bound``."""

    run: str
    bound: float = 100.0

    @property
    def name(self):
        return f"{self.run}: θ_r bounded"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        m = float(np.max(np.linalg.norm(tr.states["theta_r"], axis=1)))
        end = tr.states["theta_r"][-1]
        low = float(np.min(tr.states["theta_r"]))
        return self._res(m < self.bound, m, f"max ‖θ_r‖ = {m:.4g} (< {self.bound:g}); smallest component {low:.3g}; θ_r(T) = "
                                            f"({', '.join(f'{x:.3g}' for x in end)}), θ = {tuple(_THETA)}")


@dataclasses.dataclass(frozen=True)
class EstimatesConverge(RunClaim):
    """‖θ_r − θ‖ falls below ``ratio`` of its initial value, and its observed exponential rate."""

    run: str
    ratio: float = 0.1

    @property
    def name(self):
        return f"{self.run}: θ_r → θ"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        th = errors(tr)["theta_e"]
        r = float(th[-1] / th[0])
        half = len(tr.t) // 2
        slope = float(np.polyfit(tr.t[half:], np.log(np.maximum(th[half:], 1e-300)), 1)[0])
        lam_t = lambda_along(tr)
        v = tr.values
        lc, l1 = float(v["lam_c"]), float(np.min(lam_t))
        gamma = min(lc, lc * l1 / 2, 2.0)
        ok = r < self.ratio and -slope >= gamma / 2
        return self._res(ok, {"ratio": r, "rate": -slope, "lambda1": l1, "gamma": gamma},
                         f"‖θ_r − θ‖ from {th[0]:.3g} to {th[-1]:.3g} (ratio {r:.3g}, need < {self.ratio:g}); "
                         f"observed rate on the second half ‖θ_e‖ ∝ e^(−{-slope:.3g} t) against γ/2 = {gamma / 2:.3g} "
                         f"from (3.12) (λ1 = min λ(t) = {l1:.3g}, γ = min{{λ_c, λ_cλ1/2, 2}} = {gamma:.3g})")


@dataclasses.dataclass(frozen=True)
class Leaves(RunClaim):
    """The distance to the equilibrium s = (−c1, c2, −c3) grows past ``beyond``."""

    run: str
    beyond: float = 0.5

    @property
    def name(self):
        return f"{self.run}: leaves the equilibrium (unstable)"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        d = _other_distance(tr)
        k = int(np.argmax(d > self.beyond)) if np.any(d > self.beyond) else None
        att = float(errors(tr)["attitude"][-1])
        return self._res(k is not None, {"start": float(d[0]), "max": float(np.max(d)), "t_leave": None if k is None
                                         else float(tr.t[k]), "final_attitude_error": att},
                         f"distance to s = (−c1, c2, −c3) from {d[0]:.3g}" + (f" past {self.beyond:g} at t = {tr.t[k]:.3g}"
                                                                             if k is not None else " never past "
                                                                             f"{self.beyond:g}")
                         + f"; at the end the distance to the programmed s = c is {att:.3g}")


def lyapunov_along(tr):
    """V of (3.1) along a run of the composite loop: ½[vᵀMv + θ_eᵀΓ⁻¹θ_e + K_pV_δ + ‖Mv − ε − φᵀθ_e‖²]."""
    v = tr.values
    M = np.array(v["M"].tolist(), dtype=float)
    cs = _c(v)
    ks = [float(v[f"k{i}"]) for i in (1, 2, 3)]
    S = [tr.states[f"s{i}"] for i in (1, 2, 3)]
    e = sum(k * np.cross(s, c) for k, s, c in zip(ks, S, cs))
    vv = tr.states["omega"] - (reference(v, tr.t) - float(v["Lam"]) * e)
    th_e = tr.states["theta_r"] - np.diag(M)
    out = []
    for i in range(len(tr.t)):
        g = tr.states["G"][i]
        Gm = np.array([[g[0], g[1], g[2]], [g[1], g[3], g[4]], [g[2], g[4], g[5]]])
        ph = tr.states["phi"][i].reshape(3, 3)
        eta = M @ vv[i] - tr.states["eps"][i] - ph.T @ th_e[i]
        Vd = sum(k * np.sum((c - s[i]) ** 2) for k, s, c in zip(ks, S, cs))
        out.append(0.5 * (vv[i] @ M @ vv[i] + th_e[i] @ Gm @ th_e[i] + float(v["Kp"]) * Vd + eta @ eta))
    return np.array(out)


@dataclasses.dataclass(frozen=True)
class InLevelSet(RunClaim):
    """The corrected step (3.10′) along a run from V(0) < V0: V stays nonincreasing (to ``rtol`` of V(0)) and
    ‖ω‖ ≤ W (the constants of :func:`~.corrected.level_constants`)."""

    run: str
    rtol: float = 1e-4

    @property
    def name(self):
        return f"{self.run}: V nonincreasing, ‖ω‖ ≤ W (3.10′)"

    def check(self, example, trajectories):
        from .corrected import level_constants

        tr = trajectories[self.run]
        k = level_constants(tr.values)
        if k["w_bar"] is None or k["status"] is not Status.EXACT:
            return self._res(False, None, f"no level set at these values: {k.get('why', 'the additional hypothesis fails')}")
        V = lyapunov_along(tr)
        V0, W = float(k["V0"]), float(k["W"])
        rise = float(np.max(np.diff(V))) if len(V) > 1 else 0.0
        w_max = float(np.max(np.linalg.norm(tr.states["omega"], axis=1)))
        ok = V[0] < V0 and rise <= self.rtol * V[0] and w_max <= W
        return self._res(ok, {"V0": V0, "V_start": float(V[0]), "V_end": float(V[-1]), "largest_rise": rise,
                              "omega_max": w_max, "W": W},
                         f"V from {V[0]:.3g} (< V0 = {V0:.3g}) to {V[-1]:.3g}, largest rise between samples {rise:.2g} "
                         f"(allowed {self.rtol:g}·V(0)); max ‖ω‖ = {w_max:.3g} ≤ W = {W:.3g}")


#: the tracking runs go on (the horizon doubled from t = 20) until max(‖e‖, ‖ω − ω_d‖) < TARGET, at most to T_MAX
TARGET, T_MAX = 1e-2, 1280.0


def tracking_error(tr):
    """max(‖e‖, ‖ω − ω_d‖) along a trajectory (the auxiliary goal (2.3))."""
    err = errors(tr)
    return np.maximum(err["e"], err["omega_e"])


T1, T1_OTHER, T2, T2_OTHER = ("Theorem 1", "Theorem 1 near (−c1, c2, −c3)", "Theorem 2", "Theorem 2 near (−c1, c2, −c3)")
T2_LEVEL = "Theorem 2 in {V < V0}"
_R_LEVEL = rotation([1, 1, 1], 0.005)
_E_LEVEL = sum(k * np.cross(_R_LEVEL[:, i], np.eye(3)[i]) for i, k in enumerate((1.0, 2.0, 3.0)))
#: V(0) ≈ 1.3e-3 < V0 = 5.3e-3: a 0.005 rad attitude error, v(0) = (0.01, 0, 0), θ_r(0) = θ + (0.05, 0, 0)
LEVEL = {"omega": list(np.array(_WD0) - 2.0 * _E_LEVEL + np.array([0.01, 0.0, 0.0])), **_triad(_R_LEVEL),
         "theta_r": [_THETA[0] + 0.05, _THETA[1], _THETA[2]], **{"eps": [0.0] * 3, "phi": [0.0] * 9,
                                                                 "G": [0.2, 0.0, 0.0, 0.2, 0.0, 0.2]}}

example = Example(
    "example",
    title="Paper 004: adaptive tracking with unknown inertia, Theorems 1 and 2",
    runs=[Run(T1, system1, {}, INITIAL, until=Until(tracking_error, TARGET, T_MAX)), Run(T1_OTHER, system1, {}, NEAR_OTHER),
          Run(T2, system2_sim, {}, {**INITIAL, **_COMPOSITE}, until=Until(tracking_error, TARGET, T_MAX)),
          Run(T2_OTHER, system2_sim, {}, {**NEAR_OTHER, **_COMPOSITE}), Run(T2_LEVEL, system2_sim, {}, LEVEL)],
    t_end=20,
    series=[Series("‖θ_r − θ‖", lambda st: np.linalg.norm(st["theta_r"] - np.array(_THETA), axis=1)),
            Series("θ_r,1", lambda st: st["theta_r"][:, 0]), Series("θ_r,2", lambda st: st["theta_r"][:, 1]),
            Series("θ_r,3", lambda st: st["theta_r"][:, 2])],
    targets=[0.0, *_THETA],   # dashed: ‖θ_r − θ‖ → 0 and the true inertia θ each estimate should reach
    distance=lambda st: np.sqrt(sum(np.sum((st[f"s{i + 1}"] - np.eye(3)[i]) ** 2, axis=1) for i in range(3))),
    distance_panel=True,      # the attitude error √Σ‖sᵢ − cᵢ‖² on its own (log) panel below each run
    claims=[Tracks(T1, tol=TARGET), EstimatesBounded(T1), Leaves(T1_OTHER), Tracks(T2, tol=TARGET), EstimatesBounded(T2),
            EstimatesConverge(T2, ratio=0.5), Leaves(T2_OTHER), InLevelSet(T2_LEVEL)],
    ylabel="θ_r (dashed: the true θ)",
    samples=601,
    step=StepControl(rtol=1e-6, atol=1e-8),
    paper=PAPER,
)
