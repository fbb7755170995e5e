"""Lemma 1 of paper 001 (= inequality (10) of paper 000), with a certified δ(ε).

For a1, a2 > 0 and ε ∈ (0, 1) there is δ > 0 with

    (6)  ‖a1 r1×s1 + a2 r2×s2‖² ≥ ε(a1²‖r1−s1‖² + a2²‖r2−s2‖²)  when ‖s1−r1‖² + ‖s2−r2‖² < δ².

sᵢ = R rᵢ for a rotation R (the triad moves rigidly).  With the unit quaternion (q0, σu),
σ = sin(φ/2) ∈ [0, 1] for the rotation angle φ ∈ [0, π]:  sᵢ − rᵢ = σ Δᵢ,

    Δᵢ = 2q0 u×rᵢ + 2σ u×(u×rᵢ),  q0 = √(1 − σ²)   (no division: no removable singularity),

and (6) divided by σ² reads F(σ, u) = ‖Σ aᵢ rᵢ×Δᵢ‖² − εΣ aᵢ²‖Δᵢ‖² ≥ 0.  By (8),
‖sᵢ − rᵢ‖ = 2|sin χᵢ| σ with χᵢ the angle between u and rᵢ, and for orthonormal r1, r2:
sin²χ1 + sin²χ2 = 2 − (u·r1)² − (u·r2)² ≥ 1, so ‖s1−r1‖² + ‖s2−r2‖² < δ² forces σ < δ/2.
Hence F ≥ 0 on σ ∈ [0, σ̄] for every u proves the lemma with δ = 2σ̄.
"""

import numpy as np
import sympy

from lkverify import Budget, Check, InputError, Report, Result, Status
from lkverify.certify.bounds import certify_positive, unit_vector_angles
from lkverify.memo import Memo

from .equations import PAPER, P

__all__ = ["lemma1", "lemma1_F", "lemma1_delta", "Lemma1Constants", "EPSILONS"]

_sig, _th, _ph = sympy.symbols("sigma theta phi", real=True)
_U = unit_vector_angles(_th, _ph)  # the rotation axis u(θ, φ)
EPSILONS = (sympy.Rational(1, 2), sympy.Rational(9, 10), sympy.Rational(99, 100))
_DEFAULTS = P.resolve({})  # a1 = a2 = 1 and the base axes r1, r2 of section 6, from the declarations

_Q = np.linalg.qr(np.random.default_rng(7).normal(size=(3, 3)))[0]
_ROTATED_PAIRS = (np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]]), _Q)  # other orthonormal pairs (r1, r2)


def lemma1_F(eps, a1_=None, a2_=None, r1_=None, r2_=None):
    """F(σ, θ, φ) of the module docstring (u in spherical angles); unset arguments: the declared defaults."""
    T, N = _lemma1_parts(a1_, a2_, r1_, r2_)
    return sympy.expand(T - eps * N)


def _lemma1_parts(a1_=None, a2_=None, r1_=None, r2_=None):
    """(‖Σ aᵢ rᵢ×Δᵢ‖², Σ aᵢ²‖Δᵢ‖²), each expanded, with q0 = √(1 − σ²) written out: F = first − ε·second.

    Kept per process by its arguments (F is asked for at every ε and every check of the lemma).
    """
    a1_ = _DEFAULTS["a1"] if a1_ is None else a1_
    a2_ = _DEFAULTS["a2"] if a2_ is None else a2_
    r1_ = sympy.Matrix(_DEFAULTS["r1"] if r1_ is None else r1_)
    r2_ = sympy.Matrix(_DEFAULTS["r2"] if r2_ is None else r2_)
    key = (sympy.sympify(a1_), sympy.sympify(a2_), sympy.ImmutableMatrix(r1_), sympy.ImmutableMatrix(r2_))
    if key not in _PARTS:
        u = _U.value
        q0 = sympy.sqrt(1 - _sig**2)
        terms, norms = sympy.zeros(3, 1), 0
        for a, r in ((a1_, r1_), (a2_, r2_)):
            D = 2 * q0 * u.cross(r) + 2 * _sig * u.cross(u.cross(r))  # Δᵢ
            terms += a * r.cross(D)
            norms += a**2 * D.dot(D)
        _PARTS[key] = (sympy.expand(terms.dot(terms)), sympy.expand(norms))
    return _PARTS[key]


_PARTS = Memo(32)
_q = sympy.Symbol("q", positive=True)   # q0 = √(1 − σ²) in the sampled estimate


def _lemma1_sigma_estimate(eps, r1_=None, r2_=None, n=121):
    """The first σ where min_u F(σ, u) ≤ 0 (sampled, then bisected): an estimate of σ̄.

    F is a polynomial in σ and q0 whose coefficients are functions of the axis u: they are
    evaluated on the (θ, φ) grid once, and each σ of the bisection costs a few array operations.
    """
    T, N = _lemma1_parts(r1_=r1_, r2_=r2_)
    grid = np.meshgrid(np.linspace(0, np.pi, n), np.linspace(0, 2 * np.pi, 2 * n))
    root = sympy.sqrt(1 - _sig**2)
    poly = sympy.Poly((T - sympy.Rational(eps) * N).xreplace({root: _q}), _sig, _q)
    terms = []
    for (i, j), c in poly.terms():
        values = np.broadcast_to(sympy.lambdify((_th, _ph), c, "numpy")(*grid), grid[0].shape)
        terms.append((i, j, np.asarray(values, dtype=float)))

    def m(s):
        q0 = np.sqrt(1 - s * s)
        return float(np.min(sum(c * (s**i * q0**j) for i, j, c in terms)))

    lo, hi = 0.0, 0.999
    if m(hi) > 0:
        return hi
    for _ in range(50):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if m(mid) > 0 else (lo, mid)
    return lo


def lemma1_delta(eps, *, budget_seconds=20.0):
    """Certified δ(ε) (a1, a2, r1, r2 the declared defaults) and the sampled estimate of the largest δ.

    Returns
    -------
    (CheckResult, sympy.Rational, float)
        The certification of F ≥ 0 on σ ≤ δ/2, the certified δ, the estimate of the largest δ.
    """
    eps = sympy.Rational(eps)
    est = _lemma1_sigma_estimate(float(eps))
    F = lemma1_F(eps)
    sbar = sympy.Rational(est * 0.995).limit_denominator(10**6)
    chk = None
    for _ in range(6):
        box = {_sig: (0, sbar), **_U.region}
        chk = certify_positive(F, box, name=f"F ≥ 0 for σ ≤ {sbar}", budget=Budget(seconds=budget_seconds / 3))
        if chk.status is Status.CERTIFIED:
            break
        sbar = sbar * sympy.Rational(9, 10)
    return chk, 2 * sbar, 2 * est


def _lemma1_check(v, *, budget=60.0):
    eps_values = [v["eps"]] if v.get("eps") is not None else list(EPSILONS)
    out = []
    for eps in eps_values:
        if not (0 < eps < 1):
            raise InputError(f"eps: Lemma 1 needs 0 < ε < 1, got eps={eps}; e.g. --set eps=0.9")
        chk, delta, est = lemma1_delta(eps, budget_seconds=budget / len(eps_values))
        # the invariance under rotating the pair, illustrated on a coarser grid (61 × 122 axes: 4× faster, the
        # same estimate to about 1e-7 here)
        others = [2 * _lemma1_sigma_estimate(float(eps), r1_=R[:, 0], r2_=R[:, 1], n=61) for R in _ROTATED_PAIRS]
        status = Status.CERTIFIED if chk.status is Status.CERTIFIED else chk.status
        out.append(Result("region", f"delta(eps={eps})", status,
                          {"certified": float(delta), "estimate_largest": est, "eps": float(eps),
                           "estimates_other_orthonormal_pairs": others, "boxes": chk.boxes},
                          f"(6) holds when ‖s1−r1‖² + ‖s2−r2‖² < δ² with δ = {float(delta):.6g} (certified: with "
                          f"s_i = R r_i, R the rotation by angle φ about the unit axis u and σ = sin(φ/2), (6) "
                          f"divided by σ² is F(σ, u) = ‖Σ a_i r_i×Δ_i‖² − εΣ a_i²‖Δ_i‖² ≥ 0, Δ_i = (s_i − r_i)/σ; "
                          f"F ≥ 0 proved for all u and 0 ≤ σ ≤ δ/2, which the distance bound forces; "
                          f"{chk.boxes} boxes, {chk.seconds:.1f} s); sampled largest δ ≈ {est:.6g}; "
                          f"other orthonormal r1, r2 give {', '.join(f'{x:.6g}' for x in others)} (the problem is "
                          f"invariant under rotating the pair)"))
    return out


class Lemma1Constants:
    """The constants job of Lemma 1: certified δ(ε), and the figure of δ(ε).

    It has the interface ``lkverify constants`` expects of an item's ``constants`` (the one of
    :class:`lkverify.certify.constants.ConstantsJob`): ``goals``, ``run`` and ``plot``.  Unlike a
    ConstantsJob it has no templates and no decay model: the result is the region δ(ε) itself.
    """

    #: the goals ``lkverify constants --goal`` accepts
    goals = ["default"]

    def run(self, item_name, values, shown, *, budget=150.0, progress=None, goal=None):
        """Certify δ(ε) for ``values["eps"]`` (unset: each of :data:`EPSILONS`) within ``budget`` seconds.

        Returns
        -------
        (Report, dict)
            The report and the data of :meth:`plot` (``{"results": ...}``).
        """
        if progress:
            progress(f"{item_name}: certifying δ(ε)")
        results = tuple(_lemma1_check(values, budget=budget))
        bad = [r.name for r in results if not r.status.holds]
        verdict = "certified δ(ε)" if not bad else f"undecided: {', '.join(bad)}"
        return Report(item_name, dict(shown), results, verdict), {"results": results}

    def plot(self, extra, path, *, values=None):
        """Write δ(ε): the sampled largest δ, the closed form 2√(1−ε), the certified points, and their gaps.

        Top: the curves and points.  Bottom: the relative gaps (sampled − certified)/sampled at
        the certified ε and (sampled − 2√(1−ε))/(2√(1−ε)) along the grid, on a log scale.
        """
        from matplotlib.figure import Figure  # matplotlib only for figures: not at catalogue load time

        eps_grid = np.linspace(0.05, 0.99, 40)
        est = np.array([2 * _lemma1_sigma_estimate(e, n=61) for e in eps_grid])
        closed = 2 * np.sqrt(1 - eps_grid)
        fig = Figure(figsize=(7.5, 6.4))
        ax, gap = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 2]})
        ax.plot(eps_grid, est, lw=1.6, label="largest δ (sampled estimate)")
        ax.plot(eps_grid, closed, "k--", lw=1, label=r"closed form $2\sqrt{1-\varepsilon}$")
        pts = [(r.value["eps"], r.value["certified"], r.value["estimate_largest"]) for r in extra["results"]
               if r.value]
        if pts:
            e_c, d_c, d_s = (np.array(x, dtype=float) for x in zip(*pts))
            ax.plot(e_c, d_c, "o", label=r"certified $\delta(\varepsilon)$")
            rel = (d_s - d_c) / d_s
            gap.semilogy(e_c, np.maximum(rel, 1e-16), "o-", label="(sampled − certified) / sampled")
            for x, y in zip(e_c, rel):
                gap.annotate(f"{100 * y:.2g} %", (x, max(y, 1e-16)), textcoords="offset points", xytext=(4, 6),
                             fontsize=7)
        rel_closed = np.abs(est - closed) / closed
        gap.semilogy(eps_grid, np.maximum(rel_closed, 1e-16), ".", ms=4,
                     label=r"|sampled − $2\sqrt{1-\varepsilon}$| / $2\sqrt{1-\varepsilon}$"
                           f" (max {np.max(rel_closed):.1e}; 0 drawn at 1e-16)")
        gap.set_ylim(1e-17, 1.0)
        ax.set_ylabel(r"$\delta(\varepsilon)$")
        ax.set_title(r"Lemma 1 of paper 001 ($a_1 = a_2 = 1$): $\delta(\varepsilon)$", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
        gap.set_xlabel(r"$\varepsilon$")
        gap.set_ylabel("relative gap (log)")
        gap.grid(alpha=0.3, which="both")
        gap.legend(fontsize=7, loc="center left")
        fig.tight_layout()
        from lkverify.report.files import save_figure

        save_figure(fig, path, dpi=120)


lemma1 = Check("lemma1", parameters=P, checks=[_lemma1_check], relevant=("eps",), constants=Lemma1Constants(),
               paper=PAPER, title="Lemma 1: ‖a1 r1×s1 + a2 r2×s2‖² ≥ ε(…) for ‖s−r‖ < δ(ε); certified δ(ε)")
