"""Remark 1 of paper 000 simulated: does increasing α1, α2 help at large delays?

Remark 1 advises, when the delay is large, "to increase the parameters α1, α2 of the control
torque".  The certified δ of :mod:`.remark1` is a lower bound on the region, so it cannot
decide the advice; simulations can give evidence.  System (2), (7) is integrated from the
initial data of section 5 (:data:`~.example.HISTORY`, the data of Fig. 1) at every delay of
:data:`SIM_TAUS` with α1, α2 both scaled by each factor of :data:`SIM_SCALES` (the run's other
values unchanged), on the library's batch integrator (:func:`lkverify.simulate.batch.integrate`,
one compiled loop, the integrator of ``lkverify sweep``), to t = :data:`T_END`.  A run is
classified by :func:`lkverify.sweep.evaluate.classify` on the distance
√(‖s1 − r1‖² + ‖s2 − r2‖² + ‖ω‖²) at the level :data:`LEVEL`: *converged* when it stays below
from some time on, *bounded* (not converging) when it is above at t = :data:`T_END`.

The finding is computed from the classes: at a delay where a run with a smaller factor
converges and one with a larger factor does not, the simulations contradict the advice there;
where the larger factor converges and the smaller does not, they support it.  Status
``simulated``: observed along numerical trajectories from one initial history, not proved.

>>> from .equations import P
>>> rows = simulated_advice(P.resolve({}, use_defaults=True), taus=("2",), scales=("1/4", "4"))
>>> [r.value["classes"] for r in rows[:1]], str(rows[-1].status)
([{'1/4': 'converged', '4': 'bounded'}], 'simulated')
>>> rows[-1].value["contradicted_at"]
['2']
"""

from __future__ import annotations

import numpy as np
import sympy

from lkverify import Result, Status
from lkverify.simulate.batch import integrate
from lkverify.simulate.family import compile_family
from lkverify.sweep.evaluate import classify

from .equations import system

__all__ = ["LEVEL", "SIM_SCALES", "SIM_TAUS", "T_END", "figure", "simulated_advice"]

#: the delays of the issue's question (the section 5 example has τ = 1)
SIM_TAUS = ("2", "5", "10")
#: factors of α1, α2 (both scaled together)
SIM_SCALES = ("1/4", "1", "4")
#: horizon of every run (the horizon of the section 5 example)
T_END = 1000.0
#: a run has converged when its distance stays below this level to T_END (the sweep's level)
LEVEL = 1e-2
_SAMPLES = 4001
_SYSTEM_VALUES = ("Theta", "D", "nu", "r1", "r2")


def _vector(value) -> np.ndarray:
    return np.array([float(x) for x in sympy.Matrix(value)], dtype=float)


def _distance(y: np.ndarray, r1: np.ndarray, r2: np.ndarray) -> np.ndarray:
    """√(‖s1 − r1‖² + ‖s2 − r2‖² + ‖ω‖²) along one run (states ω, s1, s2, s3 in the family's layout)."""
    return np.sqrt(np.sum((y[:, 3:6] - r1) ** 2, axis=1) + np.sum((y[:, 6:9] - r2) ** 2, axis=1)
                   + np.sum(y[:, 0:3] ** 2, axis=1))


def _integrate(values, taus, scales):
    """(grid of (τ, factor), sample times, distance per point (rows), outcomes) on the batch integrator."""
    from .example import HISTORY  # here, not at the top: the catalogue lists items in their modules' import order

    fam = compile_family(system, {k: values[k] for k in _SYSTEM_VALUES}, grid=["tau", "alpha1", "alpha2"])
    a1, a2 = sympy.sympify(values["alpha1"]), sympy.sympify(values["alpha2"])
    grid = [(tau, k) for tau in taus for k in scales]
    pts = [[float(sympy.Rational(tau)), float(sympy.Rational(k) * a1), float(sympy.Rational(k) * a2)]
           for tau, k in grid]
    t_eval = np.linspace(0.0, T_END, _SAMPLES)
    res = integrate(fam, pts, HISTORY, t_end=T_END, t_eval=t_eval, divergence_bound=1e6)
    r1, r2 = _vector(values["r1"]), _vector(values["r2"])
    return grid, t_eval, np.array([_distance(res.y[i], r1, r2) for i in range(len(grid))]), res.outcomes


def _runs(values, taus, scales):
    """Per (τ, factor) point: (τ, factor, class, t below LEVEL, tail min, tail max, outcome)."""
    grid, t_eval, distances, outcomes = _integrate(values, taus, scales)
    tail = t_eval >= 0.8 * T_END
    out = []
    for i, (tau, k) in enumerate(grid):
        d = distances[i]
        cls, t_level = classify(outcomes[i], t_eval, d, LEVEL)
        finite = np.isfinite(d[tail])
        lo, hi = (float(d[tail][finite].min()), float(d[tail][finite].max())) if finite.any() else (np.nan, np.nan)
        out.append((tau, k, cls, t_level, lo, hi, outcomes[i].value))
    return out


def _run_text(k, cls, t_level, lo, hi, outcome) -> str:
    if cls == "converged":
        return f"α × {k}: converges (< {LEVEL:g} from t = {t_level:.4g})"
    if cls == "bounded":
        return f"α × {k}: not ({lo:.2g} to {hi:.2g} on [{0.8 * T_END:g}, {T_END:g}])"
    return f"α × {k}: {cls} ({outcome})"


def _finding(by_tau, scales):
    """(contradicted τ's, supported τ's, undecided τ's) from the classes at each delay."""
    order = sorted(scales, key=sympy.Rational)
    contra, support, open_ = [], [], []
    for tau, classes in by_tau.items():
        if any(classes[k] not in ("converged", "bounded") for k in order):
            open_.append(tau)
            continue
        pairs = [(a, b) for i, a in enumerate(order) for b in order[i + 1:]]
        if any(classes[a] == "converged" and classes[b] == "bounded" for a, b in pairs):
            contra.append(tau)
        if any(classes[a] == "bounded" and classes[b] == "converged" for a, b in pairs):
            support.append(tau)
    return contra, support, open_


def _finding_text(by_tau, scales, contra, support, open_) -> str:
    def grouped(taus, good, bad):
        """'τ = 2, 5: α × 1/4 converges, α × 1, 4 do not' with the delays of one pattern together."""
        patterns: dict = {}
        for tau in taus:
            key = (tuple(k for k in scales if by_tau[tau][k] == good), tuple(k for k in scales if by_tau[tau][k] == bad))
            patterns.setdefault(key, []).append(tau)
        def verb(ks, yes):
            return ("converges" if len(ks) == 1 else "converge") if yes else ("does not" if len(ks) == 1 else "do not")

        return "; ".join(f"τ = {', '.join(ts)}: α × {', '.join(c)} {verb(c, good == 'converged')}, "
                         f"× {', '.join(n)} {verb(n, good != 'converged')}"
                         for (c, n), ts in patterns.items())

    parts = []
    if contra:
        parts.append("runs contradict “increase α1, α2” at " + grouped(contra, "converged", "bounded"))
    if support:
        parts.append("they support it at " + grouped(support, "bounded", "converged"))
    if not contra and not support:
        parts.append("the runs neither contradict nor support “increase α1, α2” (every factor behaves alike)")
    if open_:
        parts.append(f"no conclusion at τ = {', '.join(open_)} (a run did not end normally)")
    return "; ".join(parts) + f" (section 5's data, t ≤ {T_END:g})"


def simulated_advice(values, *, taus=SIM_TAUS, scales=SIM_SCALES, budget=None) -> list[Result]:
    """One ``simulation`` row per delay and the finding about the advice "increase α1, α2".

    Parameters
    ----------
    values : mapping
        The run's resolved values (Θ, D, ν, r1, r2 and the base α1, α2 are used; τ is replaced).
    taus, scales : sequence of str
        Delays and factors of α1 = α2 scaling, exact rationals as strings.
    budget : float, optional
        Unused (the runs are bounded by the integrator's step limit, deterministic).

    Returns
    -------
    list of Result
        Per delay: status simulated, value {"tau", "classes", "runs"}; then the finding, value
        {"contradicted_at", "supported_at", "undecided_at"}, status simulated (undecided when no
        delay could be judged).

    Examples
    --------
    >>> from .equations import P
    >>> rows = simulated_advice(P.resolve({}, use_defaults=True), taus=("5",), scales=("1/4", "1"))
    >>> rows[0].value["classes"], rows[-1].value["contradicted_at"]
    ({'1/4': 'converged', '1': 'bounded'}, ['5'])
    """
    runs = _runs(values, taus, scales)
    by_tau: dict = {tau: {} for tau in taus}
    rows = []
    for tau in taus:
        mine = [r for r in runs if r[0] == tau]
        for _, k, cls, *_ in mine:
            by_tau[tau][k] = cls
        ok = all(r[2] in ("converged", "bounded") for r in mine)
        rows.append(Result("simulation", f"Remark 1 runs at tau = {tau}", Status.SIMULATED if ok else Status.UNDECIDED,
                           {"tau": tau, "classes": dict(by_tau[tau]),
                            "runs": [{"scale": k, "class": cls, "t_below": None if np.isnan(tl) else tl,
                                      "tail_min": lo, "tail_max": hi, "outcome": oc}
                                     for _, k, cls, tl, lo, hi, oc in mine]},
                           "; ".join(_run_text(k, cls, tl, lo, hi, oc) for _, k, cls, tl, lo, hi, oc in mine)))
    contra, support, open_ = _finding(by_tau, scales)
    status = Status.UNDECIDED if len(open_) == len(taus) else Status.SIMULATED
    rows.append(Result("simulation", "Remark 1: increasing α1, α2 at large delays (simulated)", status,
                       {"contradicted_at": contra, "supported_at": support, "undecided_at": open_},
                       _finding_text(by_tau, scales, contra, support, open_)))
    return rows


def figure(values, *, taus=SIM_TAUS, scales=SIM_SCALES):
    """The runs of :func:`simulated_advice`: the distance against t, one panel per delay, one line per factor.

    Returns a :class:`matplotlib.figure.Figure` (log scale; the dashed line is :data:`LEVEL`).

    >>> from .equations import P
    >>> fig = figure(P.resolve({}, use_defaults=True), taus=("2",), scales=("1/4", "4"))
    >>> [ax.get_title() for ax in fig.axes]
    ['τ = 2']
    """
    from matplotlib.figure import Figure

    grid, t_eval, distances, _ = _integrate(values, taus, scales)
    fig = Figure(figsize=(9.0, 3.4))
    axes = fig.subplots(1, len(taus), sharey=True, squeeze=False)[0]
    for ax, tau in zip(axes, taus):
        for i, (t_, k) in enumerate(grid):
            if t_ == tau:
                ax.semilogy(t_eval, distances[i], lw=0.9, label=f"α1, α2 × {k}")
        ax.axhline(LEVEL, ls="--", lw=0.8, color="0.4")
        ax.set_title(f"τ = {tau}")
        ax.set_xlabel("t")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("distance to (3)")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=len(scales), frameon=False)
    fig.suptitle("Remark 1 of paper 000: (2), (7) from the section 5 data, α1, α2 scaled", fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig
