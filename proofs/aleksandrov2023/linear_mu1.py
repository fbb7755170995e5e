"""Paper 002, the linear case μ = 1: local stability of (10), (12) at s = r, ω = 0, and the damping it needs.

For μ = 1 the torque of (12) is linear in s, and the linearisation of (10), (12) at the
target (11) s = r, ω = 0 is

    (10)  δṡ = r × δω,
    (12)  Θ δω̇ = −F δω − a δs × r + b ∫_{t−τ}^t δs(ξ) × r dξ,

with δs ⊥ r (s stays on the sphere).  In tangent coordinates δs = E y/‖u‖, where
u ∥ r is rational (r = u/‖u‖, u = (1,1,1) for section 6) and E = (e_1, e_2) is a rational
basis of u^⊥, the state x = (y, δω) ∈ R⁵ obeys ẋ = A x + ∫_{t−τ}^t D x(ξ) dξ with

    ẏ = E⁺ (u × δω),
    δω̇ = Θ⁻¹(−F δω + (a/‖u‖²) [u]ₓ E y − (b/‖u‖²) [u]ₓ E ∫ y),

(E⁺ = (EᵀE)⁻¹Eᵀ; (Ey) × u = −[u]ₓEy), rational whenever Θ, F, a, b and u are.  Paper 002
quotes ref. [30] for this case: stability for |b|τ < a (13) "and a large enough damping".
Here "large enough" is computed: the threshold h*(a, b, τ) of F = h·I above which the
linearisation is exponentially stable (the spectral route of :mod:`lkverify.linear`,
``estimated``), and, where it is stable, a Lyapunov–Krasovskii certificate of the
hierarchy at the delay τ, re-verified exactly (:mod:`lkverify.linear.hierarchy`).
Exponential stability of the linearisation gives local exponential stability of (10),
(12) for μ = 1 (the linearisation principle for retarded equations); a positive spectral
abscissa gives instability.

The linearisation is also obtained from the catalogued System by the general
:func:`lkverify.linear.linearise` (:func:`linearisation_from_system`); the item checks that
both agree exactly at Fig. 1's gains (the tests at Figs. 1, 2, 4 and at an irrational r).

Findings (section 6 data, Θ = diag(5, 6, 4), r = (1,1,1)/√3):

* Fig. 1 (a = 2, b = 2, τ = 0.9, h = 0.7): spectral abscissa −0.143; stable for every
  damping tried (h* ≤ 0.01); Wirtinger certificate at τ = 0.9, exact.  Agrees with the
  simulated convergence.
* Fig. 2 (b = −2): abscissa +0.0061, unstable; h* = 0.766 — the printed h = 0.7 is 9 %
  short of "large enough".  Agrees with the simulated non-convergence (the text's "(13)
  holds but h is not large").
* Fig. 4 (a = 0.6, b = −0.6, h = 0.2): abscissa +0.0041, unstable; h* = 0.237.  The
  equilibrium is linearly unstable, consistent with the non-convergence of the figure.
* (13) is not necessary for μ = 1: at Fig. 6's gains with μ = 1 (a = 0, b = −1, τ = 1,
  h = 1) the linearisation is stable (h* = 0.487) and certified by an exact Wirtinger LMI,
  although |b|τ = 1 > 0 = a.  Remark 3's contrast ("unlike the linear case, … a = 0,
  b < 0") holds for what (13) guarantees, not for the linear system itself.
* For b > 0 the threshold vanishes while bτ < a; for bτ > a no damping stabilises (the
  static stiffness a − bτ of the linearisation is negative): the linear boundary on the
  b > 0 side is (14), not (13).  For b < 0, h* grows with |b| and τ (figure:
  ``python -m lkverify.proofs.aleksandrov2023.linear_mu1 h_star.png``).

Examples
--------
>>> from lkverify.proofs.aleksandrov2023.section6 import FIG1
>>> sys = linearisation(FIG1)
>>> sys.n, sys.has_distributed, sys.has_discrete
(5, True, False)
"""

from __future__ import annotations

import math
import time

import numpy as np
import sympy

from lkverify import Check, InputError, Result, Status
from lkverify.linear import LinearDelaySystem, certify_delay, linearise, rightmost_roots, tangent_basis

from .equations import PAPER, P
from .section6 import FIG1, FIG4, FIG6

__all__ = ["linearisation", "linearisation_from_system", "threshold", "threshold_curves", "linear_mu1", "FIGURE_GAINS",
           "plot_threshold", "tangent_basis", "ThresholdJob"]

#: the μ = 1 figures of section 6 and their gains (F = h·I), as the figure items declare them
FIGURE_GAINS = {1: FIG1, 2: {**FIG1, "b": "-2"}, 4: FIG4}
#: Remark 3's case a = 0, b < 0 at μ = 1: the Fig. 6 gains (a = 0, b = −1, τ = 1, h = 1) with μ = 1
REMARK3_LINEAR = {**FIG6, "mu": "1"}
#: the dampings scanned for the threshold: a grid on [H_MIN, H_MAX], then bisection
H_MIN, H_MAX, H_GRID = 0.01, 6.0, 24
BISECTIONS = 18
#: Chebyshev degree of the spectral route here (τ ≤ 2)
NODES = 16
#: order of the LMI certificate at a stable figure (1 = Wirtinger)
LMI_ORDER = 1


def _cross_matrix(u):
    return sympy.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def linearisation(values) -> LinearDelaySystem:
    """The linearisation of (10), (12) with μ = 1 at s = r, ω = 0, in the coordinates (y, δω) ∈ R⁵.

    Parameters
    ----------
    values : dict
        Parameter values of :mod:`.equations` (Θ, F, a, b, τ, r); missing ones take the defaults.

    Returns
    -------
    LinearDelaySystem
        ẋ = A x + ∫_{t−τ}^t D x; the delay τ is not part of the system (it is the h of the analysis).
    """
    v = P.resolve(dict(values), use_defaults=True)
    Theta, F, a, b, r = v["Theta"], v["F"], v["a"], v["b"], v["r"]
    u, E = tangent_basis(r)
    Ux = _cross_matrix(u)
    Epinv = (E.T * E).inv() * E.T
    n2 = (u.T * u)[0]
    Ti = Theta.inv()
    A = sympy.zeros(5, 5)
    A[:2, 2:] = Epinv * Ux
    A[2:, :2] = (a / n2) * Ti * Ux * E
    A[2:, 2:] = -Ti * F
    D = sympy.zeros(5, 5)
    D[2:, :2] = -(b / n2) * Ti * Ux * E
    return LinearDelaySystem(A, kernel=[D], name="(10),(12) linearised, μ = 1")


def linearisation_from_system(values) -> LinearDelaySystem:
    """The same linearisation from the catalogued System (10), (12) itself (a second, independent path).

    :func:`lkverify.linear.linearise` reads the simulator's right-hand side (generated from the
    declared terms; the window integral as an auxiliary state z = ∫ g(x(ξ)) dξ with
    ż = g(x(t)) − g(x(t−τ))), takes its exact Jacobians at ω = 0, s = r, z = τ·g(r) = 0 and
    writes s in the tangent coordinates δs = E y/‖u‖ of :func:`linearisation` (``order``: y
    first, then δω).  Only for μ = 1: for μ > 1 the torque is O(‖s − r‖^μ) and the general
    function returns the degenerate linearisation (no stiffness, no delay term), for μ < 1 it
    refuses (not differentiable).

    >>> from lkverify.proofs.aleksandrov2023.section6 import FIG1
    >>> (linearisation_from_system(FIG1).A - linearisation(FIG1).A).is_zero_matrix
    True
    """
    from .equations import system

    v = P.resolve(dict(values), use_defaults=True)
    if v["mu"] != 1:
        raise InputError(f"mu: expected μ = 1 (the case of linearisation()), got mu={v['mu']}; for μ > 1 the "
                         f"linearisation at s = r has no stiffness and no delay term, for μ < 1 the torque is not "
                         f"differentiable there (lkverify.linear.linearise says which)")
    lin = linearise(system, {"omega": [0, 0, 0], "s": "r"}, dict(values), order=("s", "omega"))
    return LinearDelaySystem(lin.A, Ad=lin.Ad, kernel=list(lin.kernel),
                             name="(10),(12) linearised from the catalogued system, μ = 1")


def _damping_family(values):
    """h ↦ the linearisation with F = h·I, built from one exact linearisation (A − (h − h0)·diag(0, Θ⁻¹))."""
    base = linearisation(values)
    v = P.resolve(dict(values), use_defaults=True)
    h0 = v["F"][0, 0]
    if v["F"] != h0 * sympy.eye(3):
        raise ValueError("the damping family needs F = h·I")
    B = sympy.diag(sympy.zeros(2, 2), v["Theta"].inv())

    def at(h):
        hq = sympy.Rational(h) if not isinstance(h, sympy.Basic) else h
        return LinearDelaySystem(base.A - (hq - h0) * B, kernel=list(base.kernel))

    return at


def _abscissa(family, h, tau, *, refine=True) -> float:
    return rightmost_roots(family(h), float(tau), nodes=NODES, count=None if refine else 0).abscissa


def threshold(a, b, tau, *, base=None) -> dict:
    """h*(a, b, τ): the least damping of F = h·I above which (up to H_MAX) the linearisation is stable.

    The spectral abscissa (eigenvalues of the pseudospectral generator, N = :data:`NODES`) is
    sampled on a grid of h in [H_MIN, H_MAX]; the last change from unstable to stable is
    bisected.  ``estimated`` (floating point); the tests check the bracket with Newton-refined roots.

    Returns
    -------
    dict
        ``h_star`` (None when unstable at H_MAX; H_MIN when stable on the whole grid) and
        ``stable_at_max``.

    Examples
    --------
    >>> round(threshold(2, 2, sympy.Rational(9, 10))["h_star"], 3) < 0.7      # Fig. 1's gains: 0.7 suffices
    True
    """
    values = dict(base or FIG1)
    values.update(a=a, b=b, tau=tau)
    family = _damping_family(values)
    grid = np.geomspace(H_MIN, H_MAX, H_GRID)
    ab = [_abscissa(family, h, tau, refine=False) for h in grid]
    if ab[-1] >= 0:
        return {"h_star": None, "stable_at_max": False}
    k = next((i for i in range(len(grid) - 1, -1, -1) if ab[i] >= 0), None)
    if k is None:
        return {"h_star": float(grid[0]), "stable_at_max": True}
    lo, hi = grid[k], grid[k + 1]
    for _ in range(BISECTIONS):
        mid = (lo + hi) / 2
        if _abscissa(family, mid, tau, refine=False) < 0:
            hi = mid
        else:
            lo = mid
    return {"h_star": float(hi), "stable_at_max": True}


def _figure_rows(number: int) -> list[Result]:
    gains = FIGURE_GAINS[number]
    v = P.resolve(dict(gains), use_defaults=True)
    h, a, b, tau = v["F"][0, 0], v["a"], v["b"], v["tau"]
    sys = linearisation(gains)
    sp = rightmost_roots(sys, float(tau), nodes=NODES)
    th = threshold(a, b, tau, base=gains)
    hs = th["h_star"]
    where = (f"unstable up to h = {H_MAX}" if hs is None else
             f"stable for every h in [{H_MIN}, {H_MAX}] (h* ≤ {H_MIN})" if hs <= H_MIN else
             f"h* = {hs:.4f}: the figure's h = {h} is {'below' if h < hs else 'above'} it")
    stable = sp.abscissa < 0
    rows = [Result("linear", f"Fig. {number}: linearisation at s = r, ω = 0 (μ = 1)", Status.ESTIMATED,
                   {"value": sp.abscissa, "h": float(h), "h_star": hs},
                   f"a = {a}, b = {b}, τ = {tau}, F = {h}·I: spectral abscissa {sp.abscissa:.4g} → "
                   f"{'exponentially stable' if stable else 'unstable'} (locally, for (10),(12) with μ = 1); "
                   f"threshold {where}; (13) |b|τ < a {'holds' if abs(b) * tau < a else 'fails'}; {sp.detail}")]
    if stable:
        res = certify_delay(sys, tau, order=LMI_ORDER)
        rows.append(Result("linear", f"Fig. {number}: LK certificate at τ = {tau}", res.status, float(tau),
                           res.detail))
    return rows


def _remark3_rows() -> list[Result]:
    """Fig. 6's gains (a = 0, b = −1, τ = 1, h = 1) with μ = 1: stable linearisation, certified."""
    v = P.resolve(dict(REMARK3_LINEAR), use_defaults=True)
    sys = linearisation(REMARK3_LINEAR)
    sp = rightmost_roots(sys, float(v["tau"]), nodes=NODES)
    rows = [Result("linear", "Fig. 6 gains at μ = 1 (a = 0, b = −1): linearisation", Status.ESTIMATED, sp.abscissa,
                   f"spectral abscissa {sp.abscissa:.4g}: {'stable' if sp.abscissa < 0 else 'unstable'} although "
                   f"(13) |b|τ < a fails (|b|τ = 1 > 0 = a); Remark 3 contrasts a = 0, b < 0 with the linear case")]
    if sp.abscissa < 0:
        res = certify_delay(sys, v["tau"], order=LMI_ORDER)
        rows.append(Result("linear", "Fig. 6 gains at μ = 1: LK certificate at τ = 1", res.status, 1.0,
                           res.detail + " — so at μ = 1, a = 0, b < 0 is locally exponentially stable with this "
                           "damping: (13) is sufficient (with damping), not necessary"))
    return rows


def _from_system_row(number: int = 1) -> Result:
    """The hand-made linearisation equal to the one of :func:`lkverify.linear.linearise` (exact; tests: Figs. 1, 2, 4)."""
    gains = FIGURE_GAINS[number]
    a, b = linearisation_from_system(gains), linearisation(gains)
    same = a.A == b.A and a.Ad == b.Ad and a.kernel == b.kernel
    return Result("identity", f"Fig. {number}: linearisation from the catalogued System (10),(12) = the hand-made one",
                  Status.EXACT if same else Status.FAILED, same,
                  "lkverify.linear.linearise (exact Jacobians of the simulator's generated right-hand side at "
                  "ω = 0, s = r, tangent coordinates) " + ("equals" if same else "differs from") +
                  " linearisation(): A, A_d and the kernel D entry by entry in exact arithmetic")


def _check(values) -> list[Result]:
    rows = [_from_system_row(1)]
    for number in FIGURE_GAINS:
        rows += _figure_rows(number)
    return rows + _remark3_rows()


def threshold_curves(a, taus, bs, *, budget: float | None = None) -> dict:
    """h*(a, b, τ) on a grid of b for each τ: ``{τ: [h* or None, …]}`` (``estimated``); stops at the budget.

    >>> curves = threshold_curves(2, ["0.9"], [2])
    >>> curves["0.9"][0] <= H_MIN       # b = 2, bτ < a: every damping tried is enough
    True
    """
    start = time.perf_counter()
    out = {}
    for tau in taus:
        row = []
        for b in bs:
            if budget is not None and time.perf_counter() - start > budget:
                row.append(math.nan)
                continue
            row.append(threshold(sympy.Rational(str(a)), sympy.Rational(str(b)), sympy.Rational(str(tau)))["h_star"])
        out[str(tau)] = row
    return out


def plot_threshold(path, *, a=2, taus=("0.5", "0.9", "1.5"), bs=None, curves=None, points=None):
    """h*(a, b, τ) over b for several τ, with the Fig. 1 and Fig. 2 gains (h = 0.7) placed on it.

    The (13) boundaries b = ±a/τ are dotted.  ``points``: extra (b, h, label) markers.
    Returns the path written.

    >>> import os, tempfile
    >>> plot_threshold(os.path.join(tempfile.mkdtemp(), "h.png"), taus=("0.9",), bs=[-2, 2]).endswith("h.png")
    True
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bs = np.linspace(-2.5, 2.5, 21) if bs is None else np.asarray(bs, dtype=float)
    curves = curves if curves is not None else threshold_curves(a, taus, bs)
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for k, (tau, hs) in enumerate(curves.items()):
        ys = np.array([np.nan if x is None else x for x in hs], dtype=float)
        floor = ys <= H_MIN   # stable at every damping tried: h* ≤ H_MIN, drawn on the floor
        ax.plot(bs, np.where(floor, np.nan, ys), "-o", ms=3, color=f"C{k}", label=f"h*(a = {a}, b, τ = {tau})")
        ax.plot(bs[floor], ys[floor], "v", ms=5, mfc="none", color=f"C{k}")
        if float(a) > 0:
            for sgn in (-1, 1):
                ax.axvline(sgn * float(a) / float(sympy.Rational(tau)), color=f"C{k}", ls=":", lw=0.8)
    if points is None:
        points = []
        for number in (1, 2):
            g = P.resolve(dict(FIGURE_GAINS[number]), use_defaults=True)
            points.append((float(g["b"]), float(g["F"][0, 0]), f"Fig. {number}: b = {g['b']}, h = {g['F'][0, 0]}"))
    for (b, h, label), marker in zip(points, ("s", "X", "D", "P")):
        ax.plot([b], [h], marker, color="k", ms=9, label=label)
    ax.set_xlabel("b")
    ax.set_ylabel("damping threshold h* (F = h·I)")
    ax.set_yscale("log")
    ax.set_title(f"paper 002, μ = 1: stable above h* (▽: h* ≤ {H_MIN}; no point: unstable up to h = {H_MAX:g};\n"
                 "dotted: |b|τ = a, the edges of (13))", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8)
    fig.tight_layout()
    from lkverify.report.files import save_figure

    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return str(path)


def point_row(values) -> Result:
    """The run's own point (a, b, τ, F = h·I): the linearisation's verdict there, beside h*(a, b, τ).

    ``estimated``: the spectral abscissa of the pseudospectral generator at the point.

    >>> r = point_row(P.resolve(dict(FIGURE_GAINS[2]), use_defaults=True))      # Fig. 2: h = 0.7 < h* = 0.766
    >>> r.status.value, r.detail.startswith("unstable at this point")
    ('estimated', True)
    """
    a, b, tau, h = values["a"], values["b"], values["tau"], values["F"][0, 0]
    abscissa = _abscissa(_damping_family(values), h, tau)
    hstar = threshold(a, b, tau, base=values)["h_star"]
    where = (f"h* = {hstar:.4g}" if hstar is not None and hstar > H_MIN else f"h* ≤ {H_MIN}" if hstar is not None
             else f"unstable up to h = {H_MAX:g}")
    verdict = "stable" if abscissa < 0 else "unstable"
    return Result("linear", f"this point: b = {b}, h = {h}, τ = {tau}", Status.ESTIMATED,
                  {"value": abscissa, "h_star": hstar, "h": float(h)},
                  f"{verdict} at this point: spectral abscissa {abscissa:+.3g} at h = {h} ({where})")


class ThresholdJob:
    """``lkverify constants aleksandrov2023.linear_mu1 [--set a=… --set tau=…] [--plot f.png]``: h*(a, b, τ) over b.

    For the run's a and τ (and τ/2, 3τ/2) on b ∈ [−2.5, 2.5]; each h* ``estimated``; the run's
    own (b, h) is placed on the figure.

    >>> ThresholdJob.goals
    ('default',)
    """

    goals = ("default",)
    bs = tuple(np.linspace(-2.5, 2.5, 21))

    def run(self, name, values, shown, *, budget=150.0, progress=None, goal=None):
        from lkverify.report.results import Report
        a, tau, h = values["a"], values["tau"], values["F"][0, 0]
        taus = [str(tau / 2), str(tau), str(3 * tau / 2)]
        curves = threshold_curves(a, taus, self.bs, budget=budget)
        rows = [point_row(values)]
        for t_, hs in curves.items():
            for b, hstar in zip(self.bs, hs):
                status = Status.UNDECIDED if isinstance(hstar, float) and math.isnan(hstar) else Status.ESTIMATED
                text = ("budget spent" if status is Status.UNDECIDED else "unstable up to h = 6" if hstar is None
                        else f"h* ≤ {H_MIN}" if hstar <= H_MIN else f"h* = {hstar:.4g}")
                rows.append(Result("linear", f"h*(a = {a}, b = {b:.2f}, τ = {t_})", status,
                                   None if status is Status.UNDECIDED else hstar, text))
        verdict = "h*(a, b, τ) computed (spectral route, estimated)" if all(
            r.status is Status.ESTIMATED for r in rows) else "undecided: the budget ran out"
        verdict = f"{verdict}; {rows[0].detail}"
        extra = {"curves": curves, "a": a, "point": (float(values["b"]), float(h), f"this run: b = {values['b']}, h = {h}")}
        return Report(name, shown, tuple(rows), verdict), extra

    def plot(self, extra, path, values=None):
        return plot_threshold(path, a=extra["a"], bs=self.bs, curves=extra["curves"], points=[extra["point"]])


linear_mu1 = Check("linear_mu1", parameters=P, checks=[_check], paper=PAPER, relevant=(), constants=ThresholdJob(),
                   title="μ = 1: the linearisation at the Fig. 1, 2, 4 gains decided, the damping threshold h*(a, b, τ)")


if __name__ == "__main__":  # pragma: no cover - python -m …linear_mu1 FIGURE.png
    import sys
    print(plot_threshold(sys.argv[1] if len(sys.argv) > 1 else "h_star.png"))
