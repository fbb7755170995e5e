"""Persistent excitation (3.5) of paper 004 along the programmed motion.

    (3.5)  β1 I ≤ ∫_t^{t+δ} φᵀ(τ)φ(τ) dτ ≤ β2 I   for every t ≥ 0,     φ̇ = −λ_cφ + Y_cᵀ (3.2).

On the programmed motion (ω = ω_d, sᵢ = cᵢ: e = 0, v = 0, ω_r = ω_d, ω̇_c = ω̇_d) the filter is driven by
Y_c = Y(ω_d, ω_d, ω̇_d) — obtained here from the symbolic Y_c of (3.3) by that substitution, never
retyped.  φ is integrated from φ(0) = 0 (scipy, rtol 1e-9) over [0, T], the first 10/λ_c of it
(the filter's transient) dropped, and the Gram matrices over every window [t, t + δ] of the
sampled grid give β1 (the smallest eigenvalue met) and β2 (the largest); the same for φφᵀ,
the p × p matrix the parameter error sees.  Status ``estimated``: floating point and sampled
windows.  A constant ω_d along one axis (``--set wd1=1/2 --set wd2=0 --set wd3=0``) gives Y_c = 0:
no excitation, β1 = 0 (failed).
"""

from __future__ import annotations

import numpy as np
import sympy
from scipy.integrate import cumulative_trapezoid, solve_ivp

from lkverify import Check, Result, Status, t

from .equations import PAPER, P, Y_c, c1, c2, c3, omega, s1, s2, s3, wd

__all__ = ["excitation", "excitation_bounds", "HORIZON"]

#: the simulated horizon of the reference motion
HORIZON = 150.0


def _reference_regressor(values):
    """Y_c(t) on the programmed motion, as a numpy function of t, at the run's values."""
    sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
    on_motion = {**{f(t): wd[i] for i, f in enumerate(omega.functions)}}
    for s, c in ((s1, c1), (s2, c2), (s3, c3)):
        on_motion.update({f(t): c[i] for i, f in enumerate(s.functions)})
    Yr = Y_c.xreplace(on_motion).xreplace(sub)
    coeffs = {sympy.Function(f"wd{i}", real=True): sympy.Lambda(t, sympy.sympify(values[f"wd{i}"])) for i in (1, 2, 3)}
    Yr = Yr.subs(coeffs).doit()
    return sympy.lambdify(t, Yr, "numpy")


def excitation_bounds(values, *, horizon=HORIZON, samples=6001):
    """(β1, β2) of (3.5) for φᵀφ and for φφᵀ along the programmed motion, with the window grid used."""
    lc, delta = float(values["lam_c"]), float(values["delta"])
    Yf = _reference_regressor(values)

    def rhs(tt, y):
        return (-lc * y.reshape(3, 3) + np.asarray(Yf(tt), float).T).ravel()

    ts = np.linspace(0.0, horizon, samples)
    sol = solve_ivp(rhs, (0.0, horizon), np.zeros(9), t_eval=ts, rtol=1e-9, atol=1e-12)
    phis = sol.y.T.reshape(-1, 3, 3)
    out = {}
    for name, gram in (("φᵀφ", np.einsum("kji,kjl->kil", phis, phis)), ("φφᵀ", np.einsum("kij,klj->kil", phis, phis))):
        cum = cumulative_trapezoid(gram, ts, axis=0, initial=0)
        step = ts[1] - ts[0]
        w = int(round(delta / step))
        start = int(np.searchsorted(ts, 10.0 / lc))
        lo, hi = np.inf, 0.0
        for k in range(start, len(ts) - w):
            ev = np.linalg.eigvalsh(cum[k + w] - cum[k])
            lo, hi = min(lo, ev[0]), max(hi, ev[-1])
        out[name] = (float(lo), float(hi))
    return out, {"horizon": horizon, "from": 10.0 / lc, "delta": delta, "windows": len(ts) - w - start}


def _check(values):
    bounds, grid = excitation_bounds(values)
    out = []
    for name, (b1, b2) in bounds.items():
        ok = b1 > 1e-8 * max(b2, 1e-300)
        out.append(Result("constant", f"(3.5) β1, β2 for ∫{name} over δ = {grid['delta']:g}",
                          Status.ESTIMATED if ok else Status.FAILED, {"beta1": b1, "beta2": b2, **grid},
                          f"along ω = ω_d(t), sᵢ = cᵢ from φ(0) = 0: β1 = {b1:.4g}, β2 = {b2:.4g} over "
                          f"{grid['windows']} windows [t, t + {grid['delta']:g}], t ∈ [{grid['from']:g}, "
                          f"{grid['horizon'] - grid['delta']:g}] (sampled, floating point)"
                          + ("" if ok else ": no persistent excitation (β1 = 0 to rounding)")))
    return out


excitation = Check("excitation", parameters=P, checks=[_check], paper=PAPER,
                   relevant=("M", "Lam", "lam_c", "delta", "wd1", "wd2", "wd3"),
                   title="Persistent excitation (3.5): β1, β2 from the filter φ̇ = −λ_cφ + Y_cᵀ along the programmed "
                         "motion ω_d(t)")
