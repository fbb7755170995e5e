"""Figures and run options of the papers' numerical examples.

:class:`FigureExample` is the catalogue's :class:`~lkverify.catalogue.examples.Example`
with what a reader of a run needs beyond the claims:

* titles and run labels **computed from the values and histories actually used**
  (``caption(values, history, convention)`` and ``run_caption(label, values, history,
  convention)``), never the catalogue's printed text when ``--set`` or ``--history``
  changed them;
* the initial data of the examples as aircraft angles (:class:`AngleHistory`), rebuilt in
  another angle convention (:data:`lkverify.simulate.rigidbody.CONVENTIONS`) by
  :meth:`FigureExample.with_options`;
* two distances for the convergence claims: ``combined`` (√Σ of every ‖s_i − r_i‖² and
  ‖ω‖², the default) and ``per-vector`` (max_i ‖s_i − r_i‖, what a reader compares on
  the figures), see :data:`DISTANCES`;
* the figure: the plotted series over the paper's window with the target drawn, a
  log-scale distance panel over the whole simulated interval with the 1e-2 and 1e-3
  crossings marked, the envelope panel (with ‖χ‖_τ of the history used), mathtext
  symbols and legends outside the axes.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from ..catalogue.examples import Example
from ..errors import InputError
from .experiments import _time_to, along, level_text, reach_text
from .rigidbody import CONVENTIONS, DEFAULT_CONVENTION, _ALIASES, _canonical_convention

__all__ = ["AngleHistory", "DISTANCES", "FigureExample", "LEVELS", "plain", "reach_text", "show_value", "show_vector",
           "resolved_values"]

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


class FigureExample(Example):
    """An :class:`~lkverify.catalogue.examples.Example` with computed captions, conventions and distances.

    Extra parameters
    ----------------
    caption : callable, optional
        ``caption(values, history, convention)`` → the figure title (a mathtext string);
        ``values`` are the resolved values of the first run, ``history`` its history.
    run_caption : callable, optional
        ``run_caption(label, values, history, convention)`` → the label of one run (for
        examples with several runs).
    initial : AngleHistory, optional
        The initial data as aircraft angles (rebuilt for ``--convention``).
    distances : mapping, optional
        ``{"combined": f, "per-vector": g}``; ``distance`` defaults to the combined one.
    vectors : sequence of (label, callable), optional
        The per-vector distances ‖s_i − r_i‖ drawn on the distance panel.
    targets : sequence of float, optional
        Target values of the plotted series (drawn as dashed lines).
    envelope_caption : str, optional
        Mathtext form of the envelope (the panel title).
    """

    def __init__(self, name: str, *, caption: Callable | None = None, run_caption: Callable | None = None,
                 initial: AngleHistory | None = None, distances: Mapping | None = None,
                 vectors: Sequence = (), targets: Sequence | None = None, envelope_caption: str = "",
                 ylabel_tex: str = "", **kw):
        distances = dict(distances or {})
        if "distance" not in kw and "combined" in distances:
            kw["distance"] = distances["combined"]
        super().__init__(name, **kw)
        self.caption = caption
        self.run_caption = run_caption
        self.initial = initial
        self.distances = distances or {"combined": self.distance}
        self.distance_name = "combined"
        self.vectors = tuple(vectors)
        self.targets = None if targets is None else tuple(targets)
        self.envelope_caption = envelope_caption
        self.ylabel_tex = ylabel_tex
        self.convention = DEFAULT_CONVENTION if initial is not None else None
        self.overridden: dict = {}     # state name → the --history value that replaced the catalogue's
        self.user_values: dict = {}

    # -- options -------------------------------------------------------------------------------
    def with_options(self, values: Mapping | None = None, *, histories: Mapping | None = None,
                     convention: str | None = None, distance: str | None = None) -> "FigureExample":
        """A copy whose runs carry the values and histories used (so claims and envelope see them).

        ``convention`` rebuilds the angle-given initial data (:class:`AngleHistory`) in that
        convention; ``histories`` then replace states of it; ``distance`` picks a
        :data:`DISTANCES` entry for the convergence claims.

        Raises
        ------
        InputError
            An unknown convention or distance.
        """
        ex = copy.copy(self)
        conv = convention_name(convention) if convention is not None else self.convention
        if distance is not None:
            if distance not in self.distances:
                raise InputError(f"--distance: expected one of {', '.join(self.distances)}, got {distance!r}")
            ex.distance = self.distances[distance]
            ex.distance_name = distance
        runs = []
        for run in self.runs:
            hist = dict(run.history)
            if self.initial is not None and convention is not None:
                hist.update(self.initial.history(conv))
            hist.update(dict(histories or {}))
            runs.append(dataclasses.replace(run, history=hist))
        ex.runs = tuple(runs)
        ex.convention = conv if self.initial is not None else None
        ex.overridden = {k: v for k, v in dict(histories or {}).items()}
        ex.user_values = dict(values or {})
        if values or histories or convention is not None:
            ex._relabel()
        return ex

    def _relabel(self) -> None:
        """Name the runs (and the claims and envelope that refer to them) after the values and data used."""
        new = {}
        for run in self.runs:
            if len(self.runs) == 1:
                new[run.label] = plain(self.title_for())
            elif self.run_caption is not None:
                new[run.label] = plain(self.label_for(run.label))
        if len(set(new.values())) != len(new):  # two runs would get one name: keep the catalogue's
            return
        self.runs = tuple(dataclasses.replace(r, label=new.get(r.label, r.label)) for r in self.runs)

        def moved(obj):
            if not dataclasses.is_dataclass(obj):
                return obj
            changes = {f.name: new[getattr(obj, f.name)] for f in dataclasses.fields(obj)
                       if f.name in ("run", "a", "b") and isinstance(getattr(obj, f.name), str)
                       and getattr(obj, f.name) in new}
            return dataclasses.replace(obj, **changes) if changes else obj

        self.claims = tuple(moved(c) for c in self.claims)
        if self.envelope is not None:
            self.envelope = moved(self.envelope)

    # -- captions ------------------------------------------------------------------------------
    def title_for(self, values: Mapping | None = None) -> str:
        """The figure title computed from the values and history of the first run."""
        run = self.runs[0]
        vals = resolved_values(run, values if values is not None else self.user_values)
        if self.caption is not None:
            return self.caption(vals, dict(run.history), self.convention, set(self.overridden))
        title = self.title or self.qualified_name
        changed = values if values is not None else self.user_values
        if changed:
            title += " with " + ", ".join(f"{k} = {show_value(vals[k])}" for k in changed if k in vals)
        return title

    def label_for(self, label: str, values: Mapping | None = None) -> str:
        """The label of a run computed from its values and history."""
        run = next(r for r in self.runs if r.label == label)
        if self.run_caption is None:
            return label
        vals = resolved_values(run, values if values is not None else self.user_values)
        return self.run_caption(label, vals, dict(run.history), self.convention, set(self.overridden))

    # -- results -------------------------------------------------------------------------------
    def run(self, values=None, *, budget=None, t_end=None, progress=None, envelope=True, trajectories=None):
        """As :meth:`Example.run`, with the resolved parameters in the report (common to every run)."""
        report = super().run(values, budget=budget, t_end=t_end, progress=progress, envelope=envelope,
                             trajectories=trajectories)
        per_run = [{k: show_value(v) for k, v in resolved_values(r, values).items()} for r in self.runs]
        common = {k: v for k, v in per_run[0].items() if all(p.get(k) == v for p in per_run[1:])}
        return dataclasses.replace(report, parameters=common) if dataclasses.is_dataclass(report) else report

    # -- figures ------------------------------------------------------------------------------
    def plot(self, trajectories, path, *, envelope: bool = False) -> None:
        """Write the PNG: per run the plotted series (paper window) and the log distance (whole run)."""
        from matplotlib.figure import Figure  # no pyplot: the backend (and a notebook's inline one) is left alone

        show_env = envelope and self.envelope is not None
        n = 2 * len(trajectories) + (1 if show_env else 0)
        fig = Figure(figsize=(9.0, 2.9 * n), layout="constrained")
        axes = fig.subplots(n, 1, squeeze=False)
        axes = axes[:, 0]
        fig.suptitle(self.title_for(), fontsize=10)
        for k, (label, tr) in enumerate(trajectories.items()):
            ax, axd = axes[2 * k], axes[2 * k + 1]
            run_label = self.label_for(label) if len(trajectories) > 1 else ""
            T = float(tr.t[-1])
            stop = T if self.plot_until is None else min(T, float(self.plot_until))
            m = int(np.searchsorted(tr.t, stop, side="right"))
            same = self.targets is not None and np.allclose(self.targets, self.targets[0])
            for j, s in enumerate(self.series):
                line, = ax.plot(tr.t[:m], np.asarray(along(s.fn, tr.states, tr.values))[:m], lw=1.2,
                                label=_tex(s.label))
                if self.targets is not None and not same:
                    ax.axhline(self.targets[j], color=line.get_color(), ls="--", lw=0.8, alpha=0.7)
            if same:
                ax.axhline(self.targets[0], color="k", ls="--", lw=0.9, label=f"target {self.targets[0]:.4g}")
            elif self.targets is not None:
                ax.plot([], [], "k--", lw=0.8, label="targets")
            window = "" if stop >= T else f" (t ≤ {stop:g} of {T:g}; the whole run below)"
            ax.set_title((run_label + ": " if run_label else "") + "plotted series" + window, fontsize=9)
            ax.set_xlabel("$t$")
            ax.set_ylabel(self.ylabel_tex or _tex(self.ylabel))
            if self.logy:
                ax.set_yscale("log")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
            self._distance_panel(axd, tr, stop, run_label)
        if show_env:
            self._envelope_panel(axes[-1], trajectories)
        fig.savefig(path, dpi=110)

    def _distance_panel(self, ax, tr, stop, run_label) -> None:
        d = np.maximum(np.asarray(along(self.distance, tr.states, tr.values), dtype=float), 1e-300)
        T = float(tr.t[-1])
        for lab, fn in self.vectors:
            ax.semilogy(tr.t, np.maximum(np.asarray(along(fn, tr.states, tr.values), dtype=float), 1e-300),
                        lw=0.8, alpha=0.6, label=_tex(lab))
        ax.semilogy(tr.t, d, "k", lw=1.4, label=f"{self.distance_name} distance")
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
        ax.set_title((run_label + ": " if run_label else "") + f"distance to the equilibrium, the whole run "
                     f"t ∈ [0, {T:g}]", fontsize=9)
        ax.set_xlabel("$t$")
        ax.set_ylabel("distance (log)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)

    def chi_used(self) -> float:
        """‖χ‖_τ of the envelope's run, from the history used (after --history and --convention)."""
        e = self.envelope
        run = next(r for r in self.runs if r.label == e.run)
        return float(e.chi(run))

    def _envelope_panel(self, ax, trajectories) -> None:
        e = self.envelope
        tr = trajectories[e.run]
        chi = self.chi_used()
        q = np.asarray(along(e.quantity.fn, tr.states, tr.values), dtype=float)
        ax.semilogy(tr.t, np.maximum(q, 1e-300), lw=1.2, label=_tex(e.quantity.label) + " (trajectory)")
        ax.semilogy(tr.t, np.asarray(e.bound(tr.t, chi), dtype=float), "--", lw=1.2, label="envelope")
        outside = e.valid_below is not None and not chi < e.valid_below
        note = (rf"$\geq {e.valid_below:g}$" + "\noutside the estimate's region: the envelope is not claimed for "
                "this history" if outside else "")
        ax.set_title((self.envelope_caption or _tex(e.label)) + rf",  $\|\chi\|_\tau = {chi:.4g}$ " + note,
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
