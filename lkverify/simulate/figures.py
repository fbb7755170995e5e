"""Figures and run options of numerical examples, from plain run descriptions.

What a reader of a run needs beyond the claims, for :class:`~lkverify.catalogue.examples.Example`
(this module knows no catalogue class):

* the initial data of the examples as aircraft angles (:class:`AngleHistory`), rebuilt in
  another angle convention (:data:`lkverify.simulate.rigidbody.CONVENTIONS`);
* two distances for the convergence claims: ``combined`` (√Σ of every ‖s_i − r_i‖² and
  ‖ω‖², the default) and ``per-vector`` (max_i ‖s_i − r_i‖, what a reader compares on
  the figures), see :data:`DISTANCES`;
* the figure (:func:`plot_runs`): per run the plotted series, and with ``distance_panel``
  a log-scale distance panel over the whole simulated interval with the 1e-2 and 1e-3
  crossings marked; the envelope panel (with ‖χ‖_τ of the history used); mathtext symbols
  and legends outside the axes.  The whole run is always on the figure: the series over the
  paper's window with the distance panel below, or the series over the whole run with the
  paper's window shaded;
* the values as a reader writes them (:func:`show_value`, :func:`show_vector`,
  :func:`plain`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..errors import InputError
from .experiments import _time_to, along, level_text, reach_text
from .rigidbody import CONVENTIONS, DEFAULT_CONVENTION, _ALIASES, _canonical_convention

__all__ = ["AngleHistory", "DISTANCES", "LEVELS", "convention_name", "plain", "plot_runs", "reach_text", "show_value",
           "show_vector", "resolved_values"]

#: the distances the convergence claims can use (``--distance``)
DISTANCES = {
    "combined": "√(Σ_i ‖s_i − r_i‖² + ‖ω‖²): every vector and the angular velocity together",
    "per-vector": "max_i ‖s_i − r_i‖: each vector against its target separately, as read off the figures",
}

#: the levels whose first-stay-below times are reported and marked on the figures
LEVELS = (1e-2, 1e-3)


def show_value(v) -> str:
    """A parameter value as a reader writes it: 1/2 → 0.5, −1 with a minus sign, diag(h,h,h)."""
    import sympy

    if isinstance(v, sympy.MatrixBase):
        M = sympy.Matrix(v)
        if M.shape[1] == 1 or M.shape[0] == 1:
            return "(" + ", ".join(show_value(x) for x in M) + ")"
        if M.is_square and M == sympy.diag(*[M[i, i] for i in range(M.shape[0])]):
            return "diag(" + ", ".join(show_value(M[i, i]) for i in range(M.shape[0])) + ")"
        return "[" + ", ".join("[" + ", ".join(show_value(x) for x in M.row(i)) + "]" for i in range(M.shape[0])) + "]"
    try:
        x = sympy.sympify(v)
    except (sympy.SympifyError, TypeError):
        return str(v)
    if x.is_Rational:
        q = int(x.q)
        while q % 2 == 0:
            q //= 2
        while q % 5 == 0:
            q //= 5
        text = f"{float(x):g}" if q == 1 else str(x)
    elif x.is_Float:
        text = f"{float(x):g}"
    else:
        text = str(x).replace("**", "^")
    return text.replace("-", "−")


def show_vector(v) -> str:
    """A constant vector: 0.1(1,1,1) when the components are equal, else (a, b, c) to 4 digits.

    A vector with entries in t (a time-varying history) is shown entry by entry: (sin(t), 0, 0).

    >>> import sympy
    >>> show_vector([0.1, 0.1, 0.1]), show_vector(sympy.Matrix([sympy.sin(sympy.Symbol("t")), 0, -1]))
    ('0.1(1,1,1)', '(sin(t), 0, −1)')
    """
    try:
        a = np.asarray(v, dtype=float).ravel()
    except (TypeError, ValueError):  # entries in t: not numbers
        import sympy

        return "(" + ", ".join(show_value(x) for x in sympy.Matrix(v)) + ")"
    if a.size > 1 and np.allclose(a, a[0], rtol=0, atol=1e-12) and a[0] != 0:
        c = a[0]
        return ("(" + ",".join("1" for _ in a) + ")") if c == 1 else f"{c:g}(" + ",".join("1" for _ in a) + ")"
    return ("(" + ", ".join(f"{x:.4g}" for x in a) + ")").replace("-", "−")


def resolved_values(run, values: Mapping | None = None) -> dict:
    """The run's parameter values after the user's (name → checked value, the declared defaults filled in)."""
    return dict(run.system.parameters.resolve({**dict(run.values), **dict(values or {})}, use_defaults=True))


@dataclasses.dataclass(frozen=True)
class AngleHistory:
    """A constant initial history given by aircraft angles (roll φ, pitch θ, yaw ψ) and ω.

    ``build(angles, omega, convention)`` returns the history (state name → constant vector).
    """

    angles: tuple
    omega: tuple
    build: Callable

    def history(self, convention: str = DEFAULT_CONVENTION) -> dict:
        return dict(self.build(self.angles, self.omega, convention))


def convention_name(name: str | None) -> str:
    """The canonical convention name (``gost`` → ``yzx``); bad input names the conventions."""
    if name is None:
        return DEFAULT_CONVENTION
    try:
        return _canonical_convention(name)
    except (InputError, ValueError, KeyError):
        raise InputError(f"--convention: expected one of {', '.join(CONVENTIONS)} (aliases "
                         f"{', '.join(f'{k}={v}' for k, v in _ALIASES.items())}), got {name!r}") from None


def plot_runs(trajectories: Mapping, path, *, title: str, series: Sequence, distance: Callable,
              run_labels: Mapping | None = None, plot_until: float | None = None, ylabel: str = "",
              logy: bool = False, targets: Sequence | None = None, distance_panel: bool = False,
              distance_name: str | None = None, vectors: Sequence = (), envelope=None, chi: float | None = None,
              envelope_caption: str = "") -> None:
    """Write the figure of simulated runs (PNG, or PDF/SVG by the suffix of ``path``).

    Parameters
    ----------
    trajectories : mapping
        Run label → :class:`~lkverify.simulate.runs.Trajectory`.
    title : str
        The figure title (mathtext).
    series : sequence of Series
        What is plotted against t, one panel per run.
    distance : callable
        ``distance(states)``: the distance to the equilibrium (the distance panel).
    run_labels : mapping, optional
        Run label → the label shown (several runs); none for one run.
    plot_until : float, optional
        The paper's window t ≤ plot_until.
    ylabel : str
        The y label of the series panels (mathtext).
    targets : sequence of float, optional
        Target values of the series (dashed lines).
    distance_panel : bool
        Below each series panel, the log distance over the whole run with the 1e-2 and 1e-3
        crossings; the series panel then shows the paper's window only.
    distance_name : str, optional
        The name of the distance in the legend (``combined``, ``per-vector``).
    vectors : sequence of (label, callable)
        Further distances drawn on the distance panel (‖s_i − r_i‖).
    envelope : EnvelopeSpec, optional
        With ``chi`` (‖χ‖_τ of the history used): a last panel of the envelope against its quantity.
    envelope_caption : str
        Mathtext title of the envelope panel (default: its label).
    """
    from matplotlib.figure import Figure  # no pyplot: the backend (and a notebook's inline one) is left alone

    per_run = 2 if distance_panel else 1
    n = per_run * len(trajectories) + (1 if envelope is not None else 0)
    fig = Figure(figsize=(9.0, (2.9 if distance_panel else 3.0) * n), layout="constrained")
    axes = fig.subplots(n, 1, squeeze=False)[:, 0]
    fig.suptitle(title, fontsize=10)
    for k, (label, tr) in enumerate(trajectories.items()):
        run_label = dict(run_labels or {}).get(label, "")
        stop = _series_panel(axes[per_run * k], tr, series, run_label, plot_until, ylabel, logy, targets,
                             window_only=distance_panel)
        if distance_panel:
            _distance_panel(axes[per_run * k + 1], tr, distance, distance_name, vectors, stop, run_label)
    if envelope is not None:
        _envelope_panel(axes[-1], trajectories[envelope.run], envelope, chi, envelope_caption)
    from ..report.files import save_figure

    save_figure(fig, path, dpi=110)


def _series_panel(ax, tr, series, run_label, plot_until, ylabel, logy, targets, *, window_only) -> float:
    """The plotted series of one run; returns the end of the window drawn (the whole run unless ``window_only``)."""
    T = float(tr.t[-1])
    stop = T if plot_until is None else min(T, float(plot_until))
    m = int(np.searchsorted(tr.t, stop, side="right")) if window_only else len(tr.t)
    same = targets is not None and np.allclose(targets, targets[0])
    for j, s in enumerate(series):
        line, = ax.plot(tr.t[:m], np.asarray(along(s.fn, tr.states, tr.values), dtype=float)[:m], lw=1.2,
                        label=_tex(s.label))
        if targets is not None and not same:
            ax.axhline(targets[j], color=line.get_color(), ls="--", lw=0.8, alpha=0.7)
    if same:
        ax.axhline(targets[0], color="k", ls="--", lw=0.9, label=f"target {targets[0]:.4g}")
    elif targets is not None:
        ax.plot([], [], "k--", lw=0.8, label="targets")
    prefix = _tex(run_label) + ": " if run_label else ""
    if window_only:
        window = "" if stop >= T else f" (t ≤ {stop:g} of {T:g}; the whole run below)"
        ax.set_title(prefix + "plotted series" + window, fontsize=9)
    else:
        if stop < T:
            ax.axvspan(float(tr.t[0]), stop, color="0.85", alpha=0.5, lw=0, label=f"the paper's window t ≤ {stop:g}")
        ax.set_title(prefix + f"t ∈ [{float(tr.t[0]):g}, {T:g}]", fontsize=9)
    ax.set_xlabel("$t$")
    ax.set_ylabel(ylabel)
    if logy:
        ax.set_yscale("log")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    return stop


def _distance_panel(ax, tr, distance, distance_name, vectors, stop, run_label) -> None:
    d = np.maximum(np.asarray(along(distance, tr.states, tr.values), dtype=float), 1e-300)
    T = float(tr.t[-1])
    for lab, fn in vectors:
        ax.semilogy(tr.t, np.maximum(np.asarray(along(fn, tr.states, tr.values), dtype=float), 1e-300),
                    lw=0.8, alpha=0.6, label=_tex(lab))
    ax.semilogy(tr.t, d, "k", lw=1.4, label=f"{distance_name} distance" if distance_name else "distance")
    for level, color in zip(LEVELS, ("tab:orange", "tab:red")):
        ax.axhline(level, color=color, ls=":", lw=1)
        t_l = _time_to(tr.t, d, level)
        if t_l is not None:
            ax.axvline(t_l, color=color, ls="--", lw=0.8)
            ax.plot([t_l], [level], "o", color=color, ms=4, label=f"stays below {level_text(level)} from t = {t_l:.4g}")
        else:
            ax.plot([], [], "o", color=color, ms=4, label=f"does not reach {level_text(level)} by t = {T:g}")
    if stop < T:
        ax.axvspan(float(tr.t[0]), stop, color="0.85", alpha=0.5, lw=0, label="window of the panel above")
    ax.set_title((_tex(run_label) + ": " if run_label else "") + f"distance to the equilibrium, the whole run "
                 f"t ∈ [0, {T:g}]", fontsize=9)
    ax.set_xlabel("$t$")
    ax.set_ylabel("distance (log)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def _envelope_panel(ax, tr, e, chi, caption) -> None:
    q = np.asarray(along(e.quantity.fn, tr.states, tr.values), dtype=float)
    ax.semilogy(tr.t, np.maximum(q, 1e-300), lw=1.2, label=_tex(e.quantity.label) + " (trajectory)")
    ax.semilogy(tr.t, np.asarray(e.bound(tr.t, chi), dtype=float), "--", lw=1.2, label="envelope")
    outside = e.valid_below is not None and not chi < e.valid_below
    note = (rf"$\geq {e.valid_below:g}$" + "\noutside the estimate's region: the envelope is not claimed for "
            "this history" if outside else "")
    ax.set_title((caption or _tex(e.label)) + rf",  $\|\chi\|_\tau = {chi:.4g}$ " + note,
                 fontsize=9, color="firebrick" if outside else "black")
    ax.set_xlabel("$t$")
    ax.set_ylabel(_tex(e.quantity.label))
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)

_TEX = {"‖χ‖_τ": r"$\|\chi\|_\tau$", "‖s − r‖": r"$\|s - r\|$", "s_x": "$s_x$", "s_y": "$s_y$", "s_z": "$s_z$",
        "ω_x": r"$\omega_x$", "ω_y": r"$\omega_y$", "ω_z": r"$\omega_z$", "‖s1 − r1‖": r"$\|s_1 - r_1\|$",
        "‖s2 − r2‖": r"$\|s_2 - r_2\|$", "‖s3 − r3‖": r"$\|s_3 - r_3\|$", "‖s_i − r_i‖": r"$\|s_i - r_i\|$"}


def plain(text: str) -> str:
    """A mathtext caption as plain text (for the reports): ``$\\tau$`` → τ."""
    for k, v in ((r"\varphi", "φ"), (r"\theta", "θ"), (r"\psi", "ψ"), (r"\omega", "ω"), (r"\tau", "τ"),
                 (r"\mu", "μ"), (r"\chi", "χ"), (r"\beta", "β"), (r"\|", "‖"), (r"\leq", "≤"), (r"\,", ""),
                 ("$", "")):
        text = text.replace(k, v)
    return text


def _tex(text: str) -> str:
    """Plain labels of the catalogue in mathtext (no literal ``_τ``)."""
    if text in _TEX:
        return _TEX[text]
    for k, v in _TEX.items():
        text = text.replace(k, v)
    return text
