"""Theorem 2 of paper 001: the algebraic envelope, with α8 *estimated* (sampled), against the simulation.

The proof ends with

    V̇ ≤ −α7(h‖ω‖^{μ+1} + h^ν(‖s1−r1‖^{σ+1} + ‖s2−r2‖^{σ+1})) ≤ −α8 h^ν V^λ,   λ = (σ+1)/2,      (after (16))

on ‖ω‖² + ‖s1−r1‖² + ‖s2−r2‖² < δ2², for 0 < γ < γ0, and integrates it to the envelope

    V̂(t) ≤ V̂(t0) (1 + α8(λ−1) V̂^{λ−1}(t0) ∫_{t0}^t h^ν)^{−1/(λ−1)}.

Here α8 is not proved: it is the smallest value of −V̇ / (h^ν V^λ) found by sampling the
region (states from rotations near the identity and ω, h and ḣ/h over the ranges the run's
h takes after t0) and refining the worst samples locally, with V̇ the exact derivative of
:mod:`.theorem2` (its structured form, proved equal to dV/dt along (2),(4)).  A sampled
infimum is an upper estimate of the true α8, so the envelope built from it is *estimated*:
it is then compared with V̂ along the simulated run from the first time t0 after which the
run stays in the region (status ``simulated`` if it holds at every sample).  Certifying α8
(arb branch and bound over the six-dimensional region, with V̇ and V^λ both vanishing to
fourth order at the equilibrium) is not done.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import sympy

from lkverify import Status, t
from lkverify.simulate import RunClaim

from .equations import P, gamma, h
from .theorem2_functional import functional2, sigma, structured, system4

__all__ = ["Alpha8Estimate", "AlgebraicEnvelope", "LAMBDA", "ProvedEnvelopeAgainstRun", "algebraic_envelope",
           "estimate_alpha8"]

#: λ = (σ + 1)/2, the power of V in V̇ ≤ −α8 h^ν V^λ
LAMBDA = (sigma + 1) / 2

_H, _RHO = sympy.symbols("H rho", positive=True)  # h(t) and ḣ/h at a fixed t
_STATE_ARGS = [c for state in system4.states for c in state(t)]


def algebraic_envelope(V0: float, alpha8: float, integral, lam: float = float(LAMBDA)):
    """V0 (1 + α8(λ−1)V0^{λ−1} ∫_{t0}^t h^ν)^{−1/(λ−1)} for an array ``integral`` of ∫_{t0}^t h^ν.

    >>> algebraic_envelope(1.0, 2.0, np.array([0.0, 1.0]), 2.0).tolist()      # V0 / (1 + α8 V0 ∫)
    [1.0, 0.3333333333333333]
    """
    return V0 * (1.0 + alpha8 * (lam - 1.0) * V0 ** (lam - 1.0) * np.asarray(integral, dtype=float)) ** (-1.0 / (lam - 1.0))


@functools.lru_cache(maxsize=8)
def _numeric(items: tuple):
    """V and V̇ as numpy functions of (state components, H = h, ρ = ḣ/h, γ) at the parameter values ``items``."""
    values = dict(items)
    sub = {k: v for k, v in P.substitution(P.resolve(values)).items() if k is not h}

    def prep(e):
        return e.subs(sympy.Derivative(h(t), t), _RHO * h(t)).subs(h(t), _H).subs(sub)

    Vd = prep(sum((term.expr for term in structured), sympy.S.Zero))
    V = prep(functional2.expr)
    nu = sub.get(sympy.Symbol("nu", positive=True), values.get("nu", 1))
    args = [*_STATE_ARGS, _H, _RHO, gamma]
    return sympy.lambdify(args, V, "numpy"), sympy.lambdify(args, Vd, "numpy"), float(sympy.sympify(nu))


@dataclasses.dataclass(frozen=True)
class Alpha8Estimate:
    """The smallest sampled −V̇ / (h^ν V^λ) on the region: an *estimated* α8 (an upper estimate of the true one).

    Attributes
    ----------
    alpha8 : float
    gamma, delta : float
        γ in V and the radius δ2 of the region ‖ω‖² + ‖s1−r1‖² + ‖s2−r2‖² < δ2².
    h_max, rho_range : float, (float, float)
        The ranges of h and ḣ/h sampled.
    worst : dict
        The state, h and ḣ/h where the smallest ratio was found.
    samples : int
    status : Status
        Always ``estimated``.
    """

    alpha8: float
    gamma: float
    delta: float
    h_max: float
    rho_range: tuple
    worst: dict
    samples: int
    status: Status = Status.ESTIMATED


def _targets(values) -> np.ndarray:
    """The resolved r1, r2, r3 as the columns of a 3×3 array."""
    resolved = P.resolve(dict(values or {}))
    return np.array([[float(c) for c in resolved[name]] for name in ("r1", "r2", "r3")]).T


def _states(x, R0):
    """Rows of x = (ω, rotation vector) → (ω, s_i = R r_i) components and ‖ω‖² + ‖s1−r1‖² + ‖s2−r2‖²."""
    from scipy.spatial.transform import Rotation

    x = np.atleast_2d(x)
    S = Rotation.from_rotvec(x[:, 3:6]).as_matrix() @ R0  # columns s1, s2, s3; s_i = r_i at the identity
    w = x[:, :3]
    d2 = np.sum(w ** 2, 1) + np.sum((S[:, :, 0] - R0[:, 0]) ** 2, 1) + np.sum((S[:, :, 1] - R0[:, 1]) ** 2, 1)
    cols = [w[:, i] for i in range(3)] + [S[:, i, j] for j in range(3) for i in range(3)]
    return cols, d2


def estimate_alpha8(values=None, *, gamma_value: float, delta: float, h_max: float, rho_range, samples: int = 20000,
                    refine: int = 6, seed: int = 0) -> Alpha8Estimate:
    """Sample −V̇ / (h^ν V^λ) on the region and refine the worst points (Nelder–Mead); the smallest value found.

    Parameters
    ----------
    values : mapping, optional
        Parameter values (J, D, a1, a2, r1, r2, ν); the declared defaults otherwise.
    gamma_value : float
        γ in V.
    delta : float
        δ2: the region is ‖ω‖² + ‖s1−r1‖² + ‖s2−r2‖² < δ2².
    h_max : float
        h ranges over (0, h_max] (h after t0).
    rho_range : (float, float)
        ḣ/h ranges over it (V̇ is affine in ḣ: the two ends are sampled).
    samples, refine, seed : int
        Points sampled in the region; worst samples refined by Nelder–Mead; the random seed.
    """
    import scipy.optimize

    fV, fVd, nu = _numeric(_key(values))
    R0 = _targets(values)
    lam = float(LAMBDA)
    rng = np.random.default_rng(seed)
    x = rng.uniform(-delta, delta, size=(4 * samples, 6))           # (ω, rotation vector)
    x *= rng.uniform(0, 1, size=(len(x), 1)) ** 2                    # more points near the equilibrium
    cols, d2 = _states(x, R0)
    x = x[(d2 < delta ** 2) & (d2 > 0)][:samples]
    Hs = h_max * np.array([1e-6, 0.25, 0.5, 0.75, 1.0])

    def ratio(xx, Hv, rho):
        c, _ = _states(xx, R0)
        return -fVd(*c, Hv, rho, gamma_value) / (Hv ** nu * fV(*c, Hv, rho, gamma_value) ** lam)

    found = []  # (ratio, point, h, ḣ/h) of the two worst samples at every (h, ḣ/h)
    for Hv in Hs:
        for rho in rho_range:
            r = ratio(x, Hv, rho)
            found += [(float(r[k]), x[k], Hv, rho) for k in np.argsort(r)[:2]]
    found.sort(key=lambda f: f[0])
    best = found[0]
    for r0, x0, Hv, rho in found[:refine]:  # Nelder–Mead from the worst samples, kept inside the region
        res = scipy.optimize.minimize(lambda z: _penalised(ratio, z, Hv, rho, delta, R0), x0, method="Nelder-Mead",
                                      options={"maxiter": 300, "xatol": 1e-6, "fatol": 1e-9})
        if res.fun < best[0] and _states(res.x, R0)[1][0] < delta ** 2:
            best = (float(res.fun), res.x, Hv, rho)
    _, xw, Hw, rhow = best
    return Alpha8Estimate(best[0], gamma_value, delta, h_max, tuple(float(r) for r in rho_range),
                          {"omega": xw[:3].tolist(), "rotation_vector": xw[3:].tolist(), "h": float(Hw),
                           "rho": float(rhow)}, len(x))


def _key(values) -> tuple:
    """Parameter values as a hashable key (matrices made immutable)."""
    return tuple(sorted(((k, sympy.ImmutableMatrix(v) if isinstance(v, sympy.MatrixBase) else v)
                         for k, v in dict(values or {}).items()), key=lambda kv: kv[0]))


def _penalised(ratio, z, Hv, rho, delta, R0):
    d2 = _states(z, R0)[1][0]
    return float(ratio(z, Hv, rho)[0]) if 0 < d2 < delta ** 2 else 1e9


def proof_V(values=None, *, gamma_value: float):
    """V of Theorem 2 along a run: ``V(t, states)`` with the run's h and the given γ."""
    resolved = P.resolve(dict(values or {}))
    expr = functional2.expr.subs(gamma, gamma_value).subs(P.substitution(resolved))
    f = sympy.lambdify([t, *_STATE_ARGS], expr, "numpy")

    def V(tt, states):
        return f(tt, *[states[state.name][:, i] for state in system4.states for i in range(state.dim)])

    return V


def _region_norm2(states, values):
    R0 = _targets(values)
    return (np.sum(states["omega"] ** 2, 1) + np.sum((states["s1"] - R0[:, 0]) ** 2, 1)
            + np.sum((states["s2"] - R0[:, 1]) ** 2, 1))


@dataclasses.dataclass(frozen=True)
class AlgebraicEnvelope(RunClaim):
    """V̂(t) ≤ V̂(t0)(1 + α8(λ−1)V̂(t0)^{λ−1}∫_{t0}^t h^ν)^{−1/(λ−1)} along ``run``, α8 estimated on the region.

    t0 is the first sample after which the run stays in the region of radius ``delta``; α8
    is :func:`estimate_alpha8` with h ∈ (0, h(t0)] and ḣ/h over its range after t0.  The
    result is ``simulated`` when the envelope holds at every sample after t0, ``failed``
    otherwise or when the run never settles in the region or α8 ≤ 0 was found (γ too large).
    With ``alpha8`` given, that constant is used instead of the estimate (said so in the detail).

    Examples
    --------
    ``lkverify simulate aleksandrov2017.theorem2_example`` checks it along the β = 7/8 run; the
    formula itself, for λ = 2, is V0 / (1 + α8 V0 ∫h):

    >>> float(algebraic_envelope(0.2, 0.5, 10.0)), 0.2 / (1 + 0.5 * 0.2 * 10.0)
    (0.1, 0.1)
    """

    run: str
    gamma_value: float = 0.1
    delta: float = 0.5
    samples: int = 20000
    alpha8: float | None = None  # a given α8 (e.g. proved elsewhere) instead of the estimate

    @property
    def name(self):
        return f"{self.run}: algebraic envelope of Theorem 2 (α8 estimated)"

    def check(self, example, trajectories):
        tr = trajectories[self.run]
        outside = np.nonzero(_region_norm2(tr.states, tr.values) >= self.delta ** 2)[0]
        k0 = 0 if outside.size == 0 else int(outside[-1]) + 1
        if k0 >= len(tr.t) - 1:
            return self._res(False, None, f"the run does not settle in the region δ2 = {self.delta:g} by t = {tr.t[-1]:g}")
        t_after = tr.t[k0:]
        hv, rho, integ = _h_after(tr.values, t_after)
        est = estimate_alpha8(tr.values, gamma_value=self.gamma_value, delta=self.delta, h_max=float(np.max(hv)),
                              rho_range=(float(min(np.min(rho), 0.0)), float(max(np.max(rho), 0.0))),
                              samples=self.samples)
        a8 = est.alpha8 if self.alpha8 is None else float(self.alpha8)
        V = proof_V(tr.values, gamma_value=self.gamma_value)(tr.t, tr.states)[k0:]
        source = (f"α8 = {a8:.3g} given (the estimate is {est.alpha8:.3g}" if self.alpha8 is not None else
                  f"α8 = {a8:.3g} estimated (smallest sampled −V̇/(h^ν V^λ)")
        head = (f"{source}, γ = {self.gamma_value:g}, δ2 = {self.delta:g}, {est.samples} samples; not proved); "
                f"from t0 = {tr.t[k0]:.4g}: V̂ {V[0]:.3g} → {V[-1]:.3g}")
        value = {"alpha8": a8, "alpha8_estimated": est.alpha8, "alpha8_status": est.status.value,
                 "alpha8_worst_point": est.worst, "gamma": self.gamma_value, "delta": self.delta,
                 "t0": float(tr.t[k0]), "V_t0": float(V[0]), "V_end": float(V[-1])}
        if not a8 > 0:
            return self._res(False, value, head + f"; no envelope: α8 ≤ 0 (γ = {self.gamma_value:g} too large "
                                                  f"for this region)")
        ratio = V[1:] / algebraic_envelope(float(V[0]), a8, integ)[1:]
        k = int(np.argmax(ratio))
        value.update(envelope_end=float(algebraic_envelope(float(V[0]), a8, integ[-1:])[0]),
                     max_ratio=float(ratio[k]), t_max_ratio=float(t_after[k + 1]))
        return self._res(bool(np.all(ratio <= 1 + 1e-9)), value,
                         head + f", envelope → {value['envelope_end']:.3g}; max V̂/envelope after t0 = {ratio[k]:.3g} "
                                f"at t = {t_after[k + 1]:.4g}")


def _h_after(values, t_after):
    """h, ḣ/h and ∫_{t0}^t h^ν at the samples t_after (t0 = t_after[0]) for the run's h and ν."""
    import scipy.integrate

    hexpr = _h_of(values)
    hf = sympy.lambdify([t], hexpr, "numpy")
    nu = float(sympy.sympify(P.resolve(dict(values)).get("nu", 1)))
    rho = sympy.lambdify([t], sympy.diff(hexpr, t) / hexpr, "numpy")(t_after)
    pieces = [scipy.integrate.quad(lambda s: hf(s) ** nu, a, b)[0] for a, b in zip(t_after[:-1], t_after[1:])]
    return hf(t_after), np.broadcast_to(rho, np.shape(t_after)), np.concatenate([[0.0], np.cumsum(pieces)])


def _h_of(values):
    """The run's h(t) as an expression in t."""
    resolved = P.resolve(dict(values or {}))
    return h(t).subs(P.substitution(resolved)).doit()


class ProvedEnvelopeAgainstRun:
    """The constants job of Theorem 2: the *proved* α8 and its algebraic envelope against a run of (2),(4).

    ``lkverify constants aleksandrov2017.theorem2`` checks the chain of :mod:`.theorem2_chain` at the
    run's values (γ, α8, … found as in ``check``; V̇ ≤ −α8 h^ν V^λ certified), takes the section 6
    initial attitude and ω scaled down until ‖x(t0)‖ < δ2 (so the solution stays in the region),
    simulates (2),(4) and compares along it, with the proved γ in V,

        V(t) ≤ V(t0)(1 + α8(λ−1)V(t0)^{λ−1}∫_0^t h^ν)^{−1/(λ−1)}     (status ``simulated``).

    For comparison only, the sampled α8 of :func:`estimate_alpha8` at the same γ and δ2 is reported
    (labelled estimated: an upper estimate of the best α8, not a proof).
    """

    goals = ["default"]
    T_END = 400.0

    def run(self, item_name, values, shown, *, budget=120.0, progress=None, goal=None):
        """(Report, data for :meth:`plot`)."""
        from lkverify import Report, Result
        from lkverify.catalogue import find_items
        from lkverify.simulate import simulate

        from .example import INITIAL, initial_history

        (theorem2,) = find_items(item_name)  # the theorem this job belongs to (the catalogue passes its name)

        progress = progress or (lambda msg: None)
        progress(f"{item_name}: the chain at the run's values")
        report = theorem2.run(values, budget=budget)
        rate = next((r for r in report.results if r.name == "V̇ ≤ −α8 h^ν V^λ"), None)
        if rate is None or rate.value is None or rate.value.get("delta2") is None or not rate.status.is_proof:
            row = Result("simulation", "proved envelope against a run", Status.UNDECIDED, None,
                         f"the chain gives no proved envelope at these values: {report.verdict}")
            return Report(item_name, dict(shown), tuple(report.results) + (row,), report.verdict), {}
        v = {**values, **{k: sympy.Rational(x) for k, x in theorem2.chosen(values).items()}}
        a8, delta2, g = float(sympy.Rational(rate.value["alpha"])), rate.value["delta2"], float(v["gamma"])
        R0 = _targets(v)
        scale = 1.0
        for _ in range(12):  # the section 6 history, scaled until ‖x(t0)‖ < δ2
            hist = initial_history(tuple(scale * a for a in INITIAL.angles), tuple(scale * x for x in INITIAL.omega))
            x0 = float(np.sqrt(sum(np.sum((np.array(hist[f"s{i}"], dtype=float) - R0[:, i - 1]) ** 2) for i in (1, 2))
                               + np.sum((scale * np.array(INITIAL.omega)) ** 2)))
            if x0 < 0.9 * delta2:
                break
            scale /= 2
        progress(f"{item_name}: simulating (2),(4) to t = {self.T_END:g} from ‖x(t0)‖ = {x0:.4g} < δ2 = {delta2:.4g}")
        times = np.linspace(0.0, self.T_END, 2001)
        tr = simulate(system4, history=hist, t_end=self.T_END, t_eval=times,
                      values={k: v[k] for k in ("J", "D", "a1", "a2", "h", "r1", "r2", "r3")})
        V = proof_V(v, gamma_value=g)(tr.t, tr.states)
        _, _, integ = _h_after(v, tr.t)
        env = algebraic_envelope(float(V[0]), a8, integ)
        ratio = float(np.max(V / env))
        est = estimate_alpha8(v, gamma_value=g, delta=float(delta2), h_max=1.0, rho_range=(-1.0, 0.0), samples=4000)
        ok = ratio <= 1 + 1e-9
        detail = (f"α8 = {a8:.4g} proved (certified chain), γ = {g:.3g}, from the section 6 attitude and ω scaled by "
                  f"{scale:g} (‖x(t0)‖ = {x0:.4g} < δ2 = {delta2:.4g}), h = {_h_of(v)}, t ∈ [0, {self.T_END:g}], "
                  f"{tr.outcome.value}: max V(t)/envelope = {ratio:.4g} ({'≤ 1: holds' if ok else '> 1: VIOLATED'}); "
                  f"V(t_end)/V(t0) = {V[-1] / V[0]:.3g} against the envelope's {env[-1] / env[0]:.3g}; for comparison "
                  f"only, α8 estimated by sampling at the same γ, δ2: {est.alpha8:.3g} (not proved)")
        row = Result("simulation", "proved algebraic envelope V(t) ≤ V(t0)(1 + α8(λ−1)V(t0)^(λ−1)∫h^ν)^(−1/(λ−1))",
                     Status.SIMULATED if ok else Status.FAILED,
                     {"largest_ratio": ratio, "alpha8": a8, "alpha8_estimated_for_comparison": est.alpha8,
                      "gamma": g, "delta2": delta2, "scale": scale, "x0": x0, "t_end": self.T_END}, detail)
        verdict = f"{report.verdict.split(';')[0]}; proved envelope along the run: {row.status.value} ({ratio:.4g})"
        data = {"t": tr.t, "V": V, "envelope": env, "ratio": ratio}
        return Report(item_name, dict(shown), tuple(report.results) + (row,), verdict), data

    def plot(self, extra, path, *, values=None):
        """V(t) and its proved algebraic envelope."""
        from matplotlib.figure import Figure

        fig = Figure(figsize=(7.5, 4.5))
        ax = fig.subplots()
        if extra:
            ax.semilogy(extra["t"], extra["envelope"], "k--", lw=1.2, label="proved algebraic envelope")
            ax.semilogy(extra["t"], extra["V"], lw=1.4, label="$V(t)$ (simulated)")
            ax.set_title(f"Theorem 2 of paper 001: the proved envelope along a run (largest ratio {extra['ratio']:.3g})",
                         fontsize=10)
        ax.set_xlabel("$t$")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        fig.tight_layout()
        from lkverify.report.files import save_figure

        save_figure(fig, path, dpi=120)
