"""The sweep's map: where the system converges, where the proofs apply, where the linearisation is stable.

:func:`plot_map` draws a sweep table (one row per grid point) as a figure:

* 2 axes — a map in the plane (first axis across, second up): the simulated outcome as filled
  cells (converged / bounded / diverged / undecided / invalid, Okabe–Ito colours, a legend with
  the counts); per theorem the cells where every hypothesis holds (decided exactly), hatched,
  with their boundary drawn; the boundary of the linear-stable region (spectral abscissa = 0,
  ticks on the stable side); the paper's gains as labelled markers, filled when the simulation
  at those gains agrees with what the paper says, empty when it does not; and a second panel
  with the time to reach the 1e-2 level;
* 1 axis — a strip: the outcome along the axis with a band per theorem, the linear abscissa,
  the hypotheses' margins and the time to 1e-2, the marks on every panel;
* more axes — :class:`~lkverify.errors.InputError` (the table is written; the map needs 1 or 2).

A region that is empty is still named in the legend ("Theorem 3: hypotheses hold nowhere on
this grid"), and so is one that covers the whole grid.

The table (a :class:`pyarrow.Table`, a pandas DataFrame or a mapping of columns) has the
columns ``point``, one per axis, ``valid``, ``invalid_reason``, ``applies:T`` and
``margin:T:k`` (k = 0, 1, … in the order of ``meta["theorems"][T]``), ``linear_abscissa``,
``linear_verdict``, ``simulated``, ``t_to_1e-2`` (or ``t_to_<level>``) and ``final_distance``; ``meta`` has ``item``,
``t_end``, ``grid`` (``[{name, start, stop, n}, …]``, the first axis varying slowest),
``theorems`` (T → hypothesis names) and ``marks`` (``[{label, coords, expected, observed}, …]``),
and optionally ``sets`` (the ``--set`` texts, templates such as ``F: diag(h,h,h)`` among them) and
``fixed`` (name → text), shown in the title, and ``linear`` (why there is no linear margin, ``""``
when there is one).

Examples
--------
>>> import pathlib, shutil, tempfile
>>> import numpy as np
>>> b, h = np.meshgrid(np.linspace(-1, 1, 5), np.linspace(0, 1, 3), indexing="ij")
>>> n = b.size
>>> table = {"point": np.arange(n), "b": b.ravel(), "h": h.ravel(), "valid": np.ones(n, bool),
...          "invalid_reason": [""] * n, "simulated": np.where(b.ravel() > 0, "converged", "diverged"),
...          "linear_abscissa": -b.ravel(), "linear_verdict": [""] * n, "t_to_1e-2": np.full(n, 5.0),
...          "final_distance": np.zeros(n)}
>>> meta = {"item": "demo.fig1", "t_end": 10, "theorems": {},
...         "grid": [{"name": "b", "start": -1, "stop": 1, "n": 5}, {"name": "h", "start": 0, "stop": 1, "n": 3}],
...         "marks": [{"label": "Fig. 1", "coords": {"b": 0.5, "h": 0.5}, "expected": "converges",
...                    "observed": "converged"}]}
>>> folder = pathlib.Path(tempfile.mkdtemp()); path = folder / "map.png"
>>> plot_map(table, meta, path)
>>> path.stat().st_size > 10_000
True
>>> three = meta["grid"] + [{"name": "tau", "start": 1, "stop": 2, "n": 2}]
>>> plot_map(table, {**meta, "grid": three}, path)          # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
lkverify.errors.InputError: sweep map: 3 axes (b, h, tau); the table was written, but the map needs 1 or 2 axes; ...
>>> shutil.rmtree(folder)
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Mapping
from fractions import Fraction

import numpy as np
import sympy

from ..errors import InputError

__all__ = ["OUTCOMES", "COLOURS", "plot_map", "agrees", "theorem_label"]

#: the simulated classes, in legend order
OUTCOMES = ("converged", "bounded", "diverged", "undecided", "invalid")
#: Okabe–Ito colours (colour-blind safe); white is a grid point without a row
COLOURS = {"converged": "#009E73", "bounded": "#F0E442", "diverged": "#D55E00", "undecided": "#CC79A7",
           "invalid": "#BBBBBB"}
_MISSING = "#FFFFFF"
#: per theorem: hatch pattern and colour of its region
_HATCHES = (("//", "#000000"), ("\\\\", "#0072B2"), ("xx", "#56B4E9"), ("..", "#444444"))
_LINEAR = "#0072B2"
_GREEK = {"alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "kappa", "lambda", "mu", "nu", "xi",
          "rho", "sigma", "tau", "phi", "chi", "psi", "omega", "Theta", "Lambda", "Phi", "Psi", "Omega"}


def plot_map(table, meta: Mapping, path, *, title: str | None = None) -> None:
    """Write the sweep's map (PNG, or PDF/SVG by the suffix of ``path``); see the module docstring.

    Parameters
    ----------
    table : pyarrow.Table, pandas.DataFrame or mapping of columns
        One row per grid point (rows in any order; ``point`` places them).
    meta : mapping
        ``item``, ``t_end``, ``grid``, ``theorems``, ``marks`` (and optionally ``sets``,
        ``fixed``, ``linear``).
    path : str or Path
    title : str, optional, keyword-only
        Replaces the computed title (item, fixed parameters, t_end).

    Raises
    ------
    InputError
        More than 2 axes (the table is kept, the map needs 1 or 2), no axis, or a table
        without the columns the map needs.

    Examples
    --------
    A 1-D strip (one swept name):

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> a = np.array([0.5, 1.0, 2.0])
    >>> table = {"point": np.arange(3), "a": a, "valid": np.ones(3, bool), "invalid_reason": [""] * 3,
    ...          "simulated": ["converged", "converged", "bounded"], "linear_abscissa": a - 1.5,
    ...          "linear_verdict": ["stable", "stable", "unstable"], "t_to_1e-2": np.array([9.0, 40.0, np.nan]),
    ...          "final_distance": np.array([1e-4, 1e-3, 0.5])}
    >>> meta = {"item": "demo.decay", "t_end": 60, "theorems": {}, "marks": [],
    ...         "grid": [{"name": "a", "start": "1/2", "stop": "2", "n": 3}]}
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "strip.png"
    >>> plot_map(table, meta, path)
    >>> path.stat().st_size > 5_000
    True
    """
    from matplotlib.figure import Figure  # no pyplot: the backend (and a notebook's) is left alone

    axes = _grid(meta)
    cols = _columns(table)
    data = _Fields(cols, axes, meta)
    text = title if title is not None else _title(meta, axes)
    if len(axes) == 2:
        fig = Figure(figsize=(10.5, 10.0), layout="constrained")
        top, bottom = fig.subplots(2, 1)
        _map_2d(top, data, meta)
        _time_2d(fig, bottom, data, meta)
    else:
        fig = Figure(figsize=(10.5, 10.0), layout="constrained")
        panels = fig.subplots(4, 1, sharex=True, height_ratios=(1.2 + 0.4 * len(data.theorems), 1, 1, 1))
        _strip_1d(panels, data, meta)
    fig.suptitle(text, fontsize=10)
    from ..report.files import save_figure

    save_figure(fig, path, dpi=110)


def agrees(expected: str, observed: str) -> bool | None:
    """Whether the simulation at a mark agrees with the paper (None: nothing to compare).

    >>> agrees("converges", "converged"), agrees("does not converge", "bounded"), agrees("converges", "diverged")
    (True, True, False)
    >>> agrees("", "converged"), agrees("converges", "undecided")
    (None, None)
    """
    if expected not in ("converges", "does not converge") or observed not in ("converged", "bounded", "diverged"):
        return None
    return (observed == "converged") == (expected == "converges")


def theorem_label(name: str) -> str:
    """``aleksandrov2023.theorem3`` → ``"Theorem 3"`` (other names unchanged).

    >>> theorem_label("aleksandrov2023.theorem3"), theorem_label("corollary12"), theorem_label("x.main")
    ('Theorem 3', 'Corollary 12', 'main')
    """
    short = name.rpartition(".")[2]
    m = re.fullmatch(r"(theorem|corollary|lemma|remark|proposition)(\d+)", short)
    return f"{m.group(1).capitalize()} {m.group(2)}" if m else short


# -- reading the table ---------------------------------------------------------------------------------


def _grid(meta: Mapping) -> list:
    """The axes of ``meta["grid"]`` as (name, values), checked."""
    grid = meta.get("grid") if isinstance(meta, Mapping) else None
    if not grid:
        raise InputError("sweep map: meta['grid'] is empty; expected a list of {name, start, stop, n}, one per axis")
    if len(grid) > 2:
        names = ", ".join(str(a.get("name")) for a in grid)
        raise InputError(f"sweep map: {len(grid)} axes ({names}); the table was written, but the map needs 1 or 2 "
                         f"axes; sweep at most two names, or plot the table yourself")
    out = []
    for a in grid:
        try:
            start, stop, n = _num(a["start"]), _num(a["stop"]), int(a["n"])
        except (KeyError, TypeError, ValueError, ZeroDivisionError):
            raise InputError(f"sweep map: grid axis {a!r}; expected {{name, start, stop, n}} with numbers") from None
        if n < 1:
            raise InputError(f"sweep map: grid axis {a.get('name')} has n = {n}; expected n ≥ 1")
        out.append((str(a["name"]), np.linspace(start, stop, n)))
    return out


def _num(v) -> float:
    return float(Fraction(v)) if isinstance(v, str) else float(v)


def _columns(table) -> dict:
    """Column name → numpy array, from a pyarrow Table, a DataFrame or a mapping."""
    if hasattr(table, "column_names") and hasattr(table, "column"):  # pyarrow
        return {n: np.asarray(table.column(n).to_pylist(), dtype=object) if _is_text(table.column(n).type)
                else table.column(n).to_numpy(zero_copy_only=False) for n in table.column_names}
    if hasattr(table, "columns") and hasattr(table, "__getitem__"):  # pandas
        return {str(n): np.asarray(table[n].to_numpy()) for n in table.columns}
    if isinstance(table, Mapping):
        return {str(k): np.asarray(v) for k, v in table.items()}
    raise InputError(f"sweep map: expected a pyarrow Table, a pandas DataFrame or a mapping of columns, got "
                     f"{type(table).__name__}")


def _is_text(typ) -> bool:
    import pyarrow as pa

    return pa.types.is_string(typ) or pa.types.is_large_string(typ)


class _Fields:
    """The table's columns laid out on the grid (arrays of the grid's shape; NaN / "" where no row)."""

    def __init__(self, cols: dict, axes: list, meta: Mapping):
        missing = [c for c in ("point", "simulated") if c not in cols]
        if missing:
            raise InputError(f"sweep map: the table has no column {', '.join(missing)}; expected the sweep's "
                             f"columns (point, one per axis, simulated, …)")
        self.names = [a[0] for a in axes]
        self.values = [a[1] for a in axes]
        self.shape = tuple(len(v) for v in self.values)
        point = np.asarray(cols["point"], dtype=np.int64)
        size = int(np.prod(self.shape))
        if point.size and (point.min() < 0 or point.max() >= size):
            raise InputError(f"sweep map: point numbers {point.min()}…{point.max()} outside the grid of {size} "
                             f"points; expected 0 ≤ point < {size} (the grid in meta must be the table's)")
        self.index = np.unravel_index(point, self.shape)
        self.cols = cols
        self.present = self.put(np.ones(point.size, bool), False)
        self.theorems = dict(meta.get("theorems") or {})
        self.outcome = self._outcome()

    def put(self, column, fill):
        out = np.full(self.shape, fill, dtype=object if isinstance(fill, str) else np.asarray(column).dtype)
        out[self.index] = column
        return out

    def floats(self, name: str) -> np.ndarray:
        """A float column on the grid (NaN where absent)."""
        if name not in self.cols:
            return np.full(self.shape, np.nan)
        col = self.cols[name]
        if col.dtype.kind not in "fiub":
            col = np.array([np.nan if v is None else v for v in col], dtype=float)
        return self.put(col.astype(float), np.nan)

    def flags(self, name: str):
        """A boolean column on the grid (False where absent); None when the column is missing."""
        if name not in self.cols:
            return None
        col = self.cols[name]
        if col.dtype.kind != "b":
            col = np.array([bool(v) if v is not None else False for v in col], dtype=bool)
        return self.put(col, False)

    def texts(self, name: str) -> np.ndarray:
        if name not in self.cols:
            return np.full(self.shape, "", dtype=object)
        return self.put(np.array(["" if v is None else str(v) for v in self.cols[name]], dtype=object), "")

    def _outcome(self) -> np.ndarray:
        """Index into OUTCOMES per grid point; −1 where no row; ``valid`` False counts as invalid."""
        sim = self.texts("simulated")
        code = np.full(self.shape, -1, dtype=int)
        for k, name in enumerate(OUTCOMES):
            code[sim == name] = k
        code[self.present & (code < 0)] = OUTCOMES.index("undecided")
        valid = self.flags("valid")
        if valid is not None:
            code[self.present & ~valid] = OUTCOMES.index("invalid")
        return code

    def applies(self, theorem: str):
        return self.flags(f"applies:{theorem}")

    def proved(self, theorem: str):
        """The cells where the theorem's chain is established for the whole cell (None: not computed)."""
        if f"proved:{theorem}" not in self.cols:
            return None
        return self.texts(f"proved:{theorem}") == "established"

    def abscissa(self) -> np.ndarray:
        """The linear spectral abscissa (or −1 / 0 / +1 from the verdict where it is NaN), NaN at invalid points."""
        a = self.floats("linear_abscissa")
        verdict = self.texts("linear_verdict")
        coded = np.select([verdict == "stable", verdict == "critical", verdict == "unstable"], [-1.0, 0.0, 1.0],
                          np.nan)
        a = np.where(np.isnan(a), coded, a)
        a[self.outcome == OUTCOMES.index("invalid")] = np.nan
        return a

    def time_to(self) -> tuple:
        """(level text, the time to reach it on the grid) from the ``t_to_<level>`` column (1e-2 preferred)."""
        names = sorted(c for c in self.cols if c.startswith("t_to_"))
        name = "t_to_1e-2" if "t_to_1e-2" in names or not names else names[0]
        return name[len("t_to_"):], self.floats(name)

    def linear_note(self, meta: Mapping) -> str:
        note = meta.get("linear_note") or meta.get("linear")
        return textwrap.fill(note if isinstance(note, str) and note else "no linear margin for this item", 60)

    def invalid_reason(self) -> str:
        reasons = [r for r in self.texts("invalid_reason")[self.outcome == OUTCOMES.index("invalid")] if r]
        return reasons[0] if reasons else ""


# -- titles and legend texts ---------------------------------------------------------------------------


def _title(meta: Mapping, axes: list) -> str:
    item = meta.get("item", "sweep")
    names = [n for n, _ in axes]
    sets = dict(meta.get("sets") or {})
    parts = [f"{k} = {_shown(v, names)}" for k, v in sets.items()]
    parts += [f"{k} = {_shown(v, names)}" for k, v in (meta.get("fixed") or {}).items() if k not in sets]
    swept = ", ".join(f"{n} ∈ [{v[0]:g}, {v[-1]:g}] ({len(v)})" for n, v in axes)
    line = f"{item}: sweep of {swept}"
    t_end = meta.get("t_end")
    if t_end is not None:
        line += f", simulated to t = {float(t_end):g}"
    fixed = textwrap.fill(("fixed: " + ", ".join(parts)) if parts else "", 140)
    return line + ("\n" + fixed if fixed else "")


def _shown(text, names) -> str:
    """A value's text as a reader writes it (``Matrix([[h, 0], [0, h]])`` → ``diag(h, h)``), else as given."""
    from ..declare.parse import parse_value
    from ..simulate.figures import show_value

    text = str(text).strip()
    inner = text[len("Matrix("):-1] if text.startswith("Matrix(") and text.endswith(")") else text
    try:
        return show_value(parse_value(inner, variables={n: sympy.Symbol(n) for n in names}))
    except (InputError, TypeError, ValueError):
        return text


def _axis_label(name: str) -> str:
    return f"${chr(92)}{name}$" if name in _GREEK else name


def _region_label(what: str, mask: np.ndarray, present: np.ndarray) -> str:
    """``what`` with 'nowhere' / 'everywhere' on this grid when that is so, else the share of points."""
    n = int(present.sum())
    k = int((mask & present).sum())
    if k == 0:
        return f"{what} nowhere on this grid"
    if k == n:
        return f"{what} everywhere on this grid"
    return f"{what} ({k} of {n} points)"


def _outcome_labels(data: _Fields) -> list:
    labels = []
    for k, name in enumerate(OUTCOMES):
        count = int((data.outcome == k).sum())
        text = f"{name} ({count})"
        if name == "invalid" and count:
            reason = data.invalid_reason()
            if reason:
                text += ":\n" + textwrap.fill(reason if len(reason) <= 110 else reason[:107] + "…", 45)
        labels.append(text)
    return labels


# -- the 2-D map ---------------------------------------------------------------------------------------


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around the grid values (halfway between neighbours; ±½ step at the ends)."""
    if len(values) == 1:
        half = 0.5 * (abs(values[0]) if values[0] else 1.0)
        return np.array([values[0] - half, values[0] + half])
    mid = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[2 * values[0] - mid[0]], mid, [2 * values[-1] - mid[-1]]])


def _map_2d(ax, data: _Fields, meta: Mapping) -> None:
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    xe, ye = (_edges(v) for v in data.values)
    cmap = ListedColormap([_MISSING] + [COLOURS[o] for o in OUTCOMES])
    ax.pcolormesh(xe, ye, (data.outcome + 1).T, cmap=cmap, vmin=-0.5, vmax=len(OUTCOMES) + 0.5, shading="flat")
    handles = [Patch(facecolor=COLOURS[o], edgecolor="0.3", label=lab)
               for o, lab in zip(OUTCOMES, _outcome_labels(data))]
    if not data.present.all():
        handles.append(Patch(facecolor=_MISSING, edgecolor="0.3", label=f"no row ({int((~data.present).sum())})"))
    handles += _theorems_2d(ax, data, xe, ye)
    handles += _linear_2d(ax, data, meta)
    handles += _marks(ax, meta, data, labels=True)
    ax.set_xlim(xe[0], xe[-1])
    ax.set_ylim(ye[0], ye[-1])
    ax.set_xlabel(_axis_label(data.names[0]))
    ax.set_ylabel(_axis_label(data.names[1]))
    ax.set_title("simulated outcome, proved regions and the linearisation", fontsize=9)
    ax.legend(handles=handles, fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def _theorems_2d(ax, data: _Fields, xe, ye) -> list:
    """Per theorem: its cells hatched, the boundary of the region drawn; the legend entries."""
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.patches import Patch

    handles = []
    for k, (name, hyps) in enumerate(data.theorems.items()):
        hatch, colour = _HATCHES[k % len(_HATCHES)]
        mask = data.applies(name)
        what = f"{theorem_label(name)}: hypotheses hold"
        if mask is None:
            handles.append(Patch(facecolor="none", edgecolor="none", label=f"{what}: not computed"))
            continue
        ax.add_collection(PatchCollection(_rectangles(mask, xe, ye), facecolor="none", edgecolor="none",
                                          hatch=hatch, hatchcolor=colour, linewidth=0))
        ax.add_collection(LineCollection(_boundary(mask, data.present, xe, ye), colors=colour, linewidths=2.0))
        handles.append(Patch(facecolor="none", edgecolor=colour, hatch=hatch, hatchcolor=colour,
                             label=_region_label(what, mask, data.present)
                             + (f"\n({', '.join(hyps)})" if hyps else "")))
        proved = data.proved(name)
        if proved is not None:  # the cells where the chain is established for every point: outlined, dotted
            ax.add_collection(PatchCollection(_rectangles(proved, xe, ye), facecolor="none", edgecolor="black",
                                              hatch="..", hatchcolor="black", linewidth=1.2))
            handles.append(Patch(facecolor="none", edgecolor="black", hatch="..", hatchcolor="black",
                                 label=f"{theorem_label(name)}: proved for every point of the cell "
                                       f"({int(proved.sum())} cells)"))
    return handles


def _rectangles(mask: np.ndarray, xe, ye) -> list:
    """One rectangle per run of consecutive True cells along the first axis, row by row."""
    from matplotlib.patches import Rectangle

    out = []
    for j in range(mask.shape[1]):
        col = np.concatenate([[False], mask[:, j], [False]]).astype(int)
        starts = np.flatnonzero(np.diff(col) == 1)
        stops = np.flatnonzero(np.diff(col) == -1)
        out += [Rectangle((xe[a], ye[j]), xe[b] - xe[a], ye[j + 1] - ye[j]) for a, b in zip(starts, stops)]
    return out


def _boundary(mask: np.ndarray, present: np.ndarray, xe, ye) -> list:
    """Cell edges between a point in the region and a point outside it (both with rows)."""
    segs = []
    change = (mask[1:, :] != mask[:-1, :]) & present[1:, :] & present[:-1, :]
    for i, j in zip(*np.nonzero(change)):
        segs.append([(xe[i + 1], ye[j]), (xe[i + 1], ye[j + 1])])
    change = (mask[:, 1:] != mask[:, :-1]) & present[:, 1:] & present[:, :-1]
    for i, j in zip(*np.nonzero(change)):
        segs.append([(xe[i], ye[j + 1]), (xe[i + 1], ye[j + 1])])
    return segs


def _linear_2d(ax, data: _Fields, meta: Mapping) -> list:
    """The abscissa = 0 contour, ticked on the stable side; the legend entry."""
    from matplotlib import patheffects
    from matplotlib.lines import Line2D

    a = data.abscissa()
    known = ~np.isnan(a)
    if not known.any():
        return [Line2D([], [], color="none", label=f"linearisation: {data.linear_note(meta)}")]
    stable = known & (a < 0)
    label = _linear_label(a, known)
    ticks = patheffects.withTickedStroke(angle=90, spacing=7, length=0.6)  # 90°: ticks on the left of the path
    if stable.any() and (known & (a > 0)).any():
        for seg in _linear_boundary(a, data.values):
            ax.plot(seg[:, 0], seg[:, 1], color=_LINEAR, lw=2.0, path_effects=[ticks], zorder=4)
        label = f"{label}:\nboundary (abscissa = 0), ticks on the stable side"
    return [Line2D([], [], color=_LINEAR, lw=2.0, path_effects=[ticks], label=label)]


def _linear_label(a: np.ndarray, known: np.ndarray) -> str:
    """The legend of the linear layer: where the linearisation is stable, or, when nowhere, what it is instead.

    A grid where every point is critical (abscissa 0: the linear test decides nothing) is
    not "stable nowhere" as if it were unstable.

    >>> import numpy as np
    >>> _linear_label(np.array([0.0, 0.0]), np.array([True, True]))
    'linearisation critical (abscissa 0) at every point: the linear test decides nothing'
    >>> _linear_label(np.array([0.0, 0.5, 0.2]), np.array([True, True, True]))
    'linearisation stable nowhere on this grid: unstable at 2, critical at 1 of 3 points'
    >>> _linear_label(np.array([-1.0, 0.5]), np.array([True, True]))
    'linearisation stable (1 of 2 points)'
    """
    stable = known & (a < 0)
    if stable.any():
        return _region_label("linearisation stable", stable, known)
    n, critical, unstable = int(known.sum()), int((known & (a == 0)).sum()), int((known & (a > 0)).sum())
    if critical == n:
        return "linearisation critical (abscissa 0) at every point: the linear test decides nothing"
    parts = [f"unstable at {unstable}" if unstable else "", f"critical at {critical}" if critical else ""]
    return f"linearisation stable nowhere on this grid: {', '.join(p for p in parts if p)} of {n} points"


def _linear_boundary(a: np.ndarray, values) -> list:
    """Lines between stable and unstable points, each directed with the stable side on its left.

    The abscissa = 0 contour when both axes have two values or more; else the cell edges
    between a stable and an unstable point (a grid one cell thick has no contour).
    """
    import contourpy

    xc, yc = values
    if min(a.shape) > 1:
        gen = contourpy.contour_generator(xc, yc, np.ma.masked_invalid(a).T, line_type="Separate")
        return [_stable_on_left(seg, a, xc, yc) for seg in gen.lines(0.0) if len(seg) > 1]
    xe, ye = _edges(xc), _edges(yc)
    stable, unstable = a < 0, a > 0
    segs = []
    for i, j in zip(*np.nonzero((stable[1:, :] & unstable[:-1, :]) | (unstable[1:, :] & stable[:-1, :]))):
        up = [(xe[i + 1], ye[j]), (xe[i + 1], ye[j + 1])]               # walking up, the left is cell i
        segs.append(np.array(up if stable[i, j] else up[::-1]))
    for i, j in zip(*np.nonzero((stable[:, 1:] & unstable[:, :-1]) | (unstable[:, 1:] & stable[:, :-1]))):
        right = [(xe[i], ye[j + 1]), (xe[i + 1], ye[j + 1])]            # walking right, the left is cell j + 1
        segs.append(np.array(right if stable[i, j + 1] else right[::-1]))
    return segs


def _stable_on_left(seg: np.ndarray, a: np.ndarray, xc, yc) -> np.ndarray:
    """The contour line ``seg`` directed so that the stable side (a < 0) is on its left (majority of vertices).

    Left is decided in grid-index coordinates (a positive rescaling of the axes keeps the side).
    """
    u = (seg[:, 0] - xc[0]) / (xc[1] - xc[0])
    w = (seg[:, 1] - yc[0]) / (yc[1] - yc[0])
    du, dw = np.gradient(u), np.gradient(w)
    norm = np.hypot(du, dw)
    norm[norm == 0] = 1.0
    i = np.clip(np.rint(u - 0.75 * dw / norm), 0, a.shape[0] - 1).astype(int)  # left normal (−dw, du)
    j = np.clip(np.rint(w + 0.75 * du / norm), 0, a.shape[1] - 1).astype(int)
    left = a[i, j]
    votes = np.sum(left < 0) - np.sum(left > 0)
    return seg if votes >= 0 else seg[::-1]


def _marks(ax, meta: Mapping, data: _Fields, *, labels: bool) -> list:
    """The paper's gains as markers (filled: simulation agrees with the paper; empty: it does not)."""
    from matplotlib import patheffects
    from matplotlib.lines import Line2D

    style = {True: ("black", "agrees with the paper (filled)"), False: ("white", "disagrees with the paper (empty)"),
             None: ("0.6", "no claim or not simulated (grey)")}
    seen, outside = set(), []
    lo = [v.min() for v in data.values]
    hi = [v.max() for v in data.values]
    for m in meta.get("marks") or ():
        coords = m.get("coords") or {}
        if any(n not in coords for n in data.names):
            continue
        xy = [float(coords[n]) for n in data.names]
        if any(not (lo[i] - 1e-12 <= xy[i] <= hi[i] + 1e-12) for i in range(len(xy))):
            outside.append(f"{m.get('label', '?')} ({', '.join(f'{n} = {v:g}' for n, v in zip(data.names, xy))})")
            continue
        ok = agrees(m.get("expected", ""), m.get("observed", ""))
        seen.add(ok)
        x, y = (xy[0], xy[1]) if len(xy) == 2 else (xy[0], 1.5)
        ax.plot([x], [y], "o", ms=9, mfc=style[ok][0], mec="black", mew=1.6, zorder=5)
        if labels:
            ax.annotate(m.get("label", "?"), (x, y), xytext=(6, 6), textcoords="offset points", fontsize=8.5,
                        fontweight="bold", zorder=6, path_effects=[patheffects.withStroke(linewidth=3, foreground="w")])
    handles = [Line2D([], [], ls="none", marker="o", ms=8, mfc=style[k][0], mec="black", mew=1.6,
                      label=f"paper's gains: simulation {style[k][1]}" if k is not None else
                      f"paper's gains: {style[k][1]}") for k in (True, False, None) if k in seen]
    if outside:
        handles.append(Line2D([], [], color="none", label="outside the grid: " + "; ".join(outside)))
    return handles


def _time_2d(fig, ax, data: _Fields, meta: Mapping) -> None:
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.patches import Patch

    xe, ye = (_edges(v) for v in data.values)
    level, t = data.time_to()
    t[data.outcome == OUTCOMES.index("invalid")] = np.nan
    finite = t[np.isfinite(t)]
    norm = (LogNorm(max(finite.min(), 1e-3 * finite.max()), finite.max())
            if finite.size and finite.max() > 0 and finite.max() > 100 * max(finite.min(), 1e-300)
            else Normalize(*(finite.min(), finite.max()) if finite.size else (0, 1)))
    mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(t).T, cmap="viridis", norm=norm, shading="flat")
    ax.set_facecolor("#E5E5E5")
    fig.colorbar(mesh, cax=ax.inset_axes([1.02, 0.0, 0.025, 1.0]), label=f"time to reach distance {level}")
    handles = [Patch(facecolor="#E5E5E5", edgecolor="0.3", label=f"never below {level} by t_end, or invalid")]
    handles += _marks(ax, meta, data, labels=True)
    ax.set_xlim(xe[0], xe[-1])
    ax.set_ylim(ye[0], ye[-1])
    ax.set_xlabel(_axis_label(data.names[0]))
    ax.set_ylabel(_axis_label(data.names[1]))
    ax.set_title(f"time to converge (distance < {level})", fontsize=9)
    ax.legend(handles=handles, fontsize=7.5, loc="upper left", bbox_to_anchor=(0.0, -0.12), borderaxespad=0, ncols=2)


# -- the 1-D strip -------------------------------------------------------------------------------------


def _strip_1d(panels, data: _Fields, meta: Mapping) -> None:
    strip, lin, margins, time = panels
    x = data.values[0]
    _outcome_strip(strip, data, meta)
    _abscissa_1d(lin, data, meta)
    _margins_1d(margins, data)
    level, t = data.time_to()
    time.plot(x, t, ".-", color="#000000", lw=1.2, label=f"time to distance < {level} (gaps: never by t_end)")
    time.set_ylabel(f"t to {level}")
    time.set_xlabel(_axis_label(data.names[0]))
    for ax in (lin, margins, time):
        for m in meta.get("marks") or ():
            c = (m.get("coords") or {}).get(data.names[0])
            if c is not None:
                ax.axvline(float(c), color="0.3", ls=":", lw=1.0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def _outcome_strip(ax, data: _Fields, meta: Mapping) -> None:
    """Outcome band at y ∈ [0, 1], one band per theorem below it, the marks above it."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    xe = _edges(data.values[0])
    cmap = ListedColormap([_MISSING] + [COLOURS[o] for o in OUTCOMES])
    ax.pcolormesh(xe, [0, 1], (data.outcome + 1)[None, :], cmap=cmap, vmin=-0.5, vmax=len(OUTCOMES) + 0.5)
    handles = [Patch(facecolor=COLOURS[o], edgecolor="0.3", label=lab)
               for o, lab in zip(OUTCOMES, _outcome_labels(data))]
    ticks, names = [0.5], ["outcome"]
    for k, (name, _) in enumerate(data.theorems.items()):
        hatch, colour = _HATCHES[k % len(_HATCHES)]
        y0 = -1.0 - k
        mask = data.applies(name)
        what = f"{theorem_label(name)}: hypotheses hold"
        if mask is None:
            handles.append(Patch(facecolor="none", edgecolor="none", label=f"{what}: not computed"))
        else:
            for a, b in _runs(mask):
                ax.add_patch(_band(xe[a], xe[b], y0, hatch, colour))
            handles.append(Patch(facecolor="none", edgecolor=colour, hatch=hatch, hatchcolor=colour,
                                 label=_region_label(what, mask, data.present)))
        ticks.append(y0 + 0.5)
        names.append(theorem_label(name))
    handles += _marks(ax, meta, data, labels=True)
    ax.set_ylim(-len(data.theorems) - 0.1, 2.1)
    ax.set_yticks(ticks, names)
    ax.set_xlim(xe[0], xe[-1])
    ax.set_title("simulated outcome and where the theorems' hypotheses hold", fontsize=9)
    ax.legend(handles=handles, fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def _runs(mask: np.ndarray) -> list:
    col = np.concatenate([[False], mask, [False]]).astype(int)
    return list(zip(np.flatnonzero(np.diff(col) == 1), np.flatnonzero(np.diff(col) == -1)))


def _band(x0, x1, y0, hatch, colour):
    from matplotlib.patches import Rectangle

    return Rectangle((x0, y0), x1 - x0, 0.9, facecolor="none", edgecolor=colour, hatch=hatch, hatchcolor=colour,
                     linewidth=1.5)


def _abscissa_1d(ax, data: _Fields, meta: Mapping) -> None:
    x = data.values[0]
    a = data.abscissa()
    if np.isnan(a).all():
        ax.plot([], [], color="none", label=f"linearisation: {data.linear_note(meta)}")
    else:
        ax.plot(x, a, ".-", color=_LINEAR, lw=1.2, label="linear spectral abscissa")
        stable = ~np.isnan(a) & (a < 0)
        ax.fill_between(x, 0, 1, where=stable, transform=ax.get_xaxis_transform(), color=_LINEAR, alpha=0.12,
                        step="mid", label=_linear_label(a, ~np.isnan(a)))
        ax.axhline(0.0, color="0.2", lw=0.8)
    ax.set_ylabel("abscissa")


def _margins_1d(ax, data: _Fields) -> None:
    x = data.values[0]
    drawn = False
    for name, hyps in data.theorems.items():
        for k, hyp in enumerate(hyps):
            m = data.floats(f"margin:{name}:{k}")
            if np.isnan(m).all():
                continue
            ax.plot(x, m, ".-", lw=1.0, label=f"{theorem_label(name)}: {hyp}")
            drawn = True
    if drawn:
        ax.axhline(0.0, color="0.2", lw=0.8)
    else:
        ax.plot([], [], color="none", label="no hypothesis margins in the table")
    ax.set_ylabel("hypothesis margin")
