"""The figure of ``lkverify linear --plot``: the spectrum at one delay and the spectral abscissa over h.

Examples
--------
>>> import tempfile, os
>>> from lkverify.linear.model import LinearDelaySystem
>>> from lkverify.linear.crossing import stability_intervals
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> path = os.path.join(tempfile.mkdtemp(), "s.png")
>>> plot_linear(sys, path, intervals=stability_intervals(sys, h_max=8), points=40) == path
True
"""

from __future__ import annotations

import numpy as np

from .spectrum import rightmost_roots

__all__ = ["plot_linear"]


def plot_linear(system, path, *, intervals, h=None, certified=(), points: int = 160, title: str | None = None):
    """Two panels: characteristic roots at h (default: the margin) and max Re λ over [0, h_max].

    Parameters
    ----------
    system : LinearDelaySystem
    path : str or Path
        PNG, PDF or SVG (by the suffix).
    intervals : StabilityIntervals
    h : float, optional
    certified : sequence of (method, value dict)
        Certified delays (``upper``, ``lower``) drawn as markers on the abscissa panel.
    points : int
        Delays sampled for the abscissa curve.

    Returns
    -------
    str
        The path written.

    Examples
    --------
    >>> import tempfile, os
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> from lkverify.linear.crossing import stability_intervals
    >>> sys = LinearDelaySystem([[0]], Ad=[[-1]])
    >>> out = os.path.join(tempfile.mkdtemp(), "s.svg")
    >>> plot_linear(sys, out, intervals=stability_intervals(sys, h_max=3), points=20).endswith("s.svg")
    True
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h_show = h if h is not None else (intervals.margin if intervals.margin is not None else
                                      (intervals.intervals[0][1] if intervals.intervals else intervals.h_max / 2))
    sp = rightmost_roots(system, h_show)
    zoom = intervals.margin is not None
    fig, axes = plt.subplots(1, 3 if zoom else 2, figsize=(16 if zoom else 11, 4.3))
    ax1, ax2 = axes[0], axes[1]
    ev = sp.discretised
    ax1.plot(ev.real, ev.imag, ".", color="0.6", ms=4, label="pseudospectral eigenvalues")
    ax1.plot(sp.roots.real, sp.roots.imag, "o", mfc="none", color="C3", ms=7, label="Newton-refined roots")
    ax1.axvline(0, color="k", lw=0.8)
    span = max(1.0, 2.5 * float(np.max(np.abs(sp.roots[:2 * system.n].imag))))
    ax1.set_ylim(-span, span)
    ax1.set_xlim(min(-1.0, 1.5 * float(sp.roots.real.min())), max(0.5, 1.5 * float(sp.abscissa)))
    ax1.set_xlabel(r"Re $\lambda$")
    ax1.set_ylabel(r"Im $\lambda$")
    ax1.set_title(f"roots at h = {h_show:.6g} (max Re λ = {sp.abscissa:.2e})")
    ax1.legend(loc="lower left", fontsize=8)
    grid = np.linspace(intervals.h_max / points, intervals.h_max, points)
    ab = [rightmost_roots(system, x, count=0).abscissa for x in grid]  # unrefined: the curve only
    ax2.plot(grid, ab, color="C0", label=r"max Re $\lambda$ (spectral)")
    ax2.axhline(0, color="k", lw=0.8)
    for k, (lo, hi) in enumerate(intervals.intervals):
        ax2.axvspan(lo, hi, color="C2", alpha=0.15, label="stable (spectral)" if k == 0 else None)
    for k, (method, value) in enumerate(certified):
        for end in ("lower", "upper"):
            if value.get(end) is not None:
                ax2.plot([value[end]], [0], "v" if end == "upper" else "^", color=f"C{(k + 3) % 10}",
                         label=f"{method}: {value[end]:.6g}" if end == "upper" else None)
    for c in intervals.crossings:
        ax2.axvline(c.h, color="0.5", lw=0.6, ls="--")
    top = max(0.05, 1.3 * max(ab))
    ax2.set_ylim(max(min(ab), -4 * top if top > 0.05 else -1.0), top)  # the crossings, not deep dips
    ax2.set_xlabel("delay h (dashed: crossing delays)")
    ax2.set_ylabel(r"max Re $\lambda$")
    ax2.set_title(title or "spectral abscissa and certified delays")
    if zoom:
        _zoom_panel(axes[2], system, intervals, certified)
        ax2.legend(loc="lower right", fontsize=7)
    else:
        ax2.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8)
    fig.tight_layout()
    from ..report.files import save_figure

    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return str(path)


def _zoom_panel(ax, system, intervals, certified, points: int = 41) -> None:
    """The abscissa around the first crossing: the certified delays apart, the instability beyond visible."""
    margin = float(intervals.margin)
    ends = [float(v[e]) for _, v in certified for e in ("lower", "upper") if v.get(e) is not None]
    near = [e for e in ends if 0.97 * margin <= e <= margin]   # the delays certified close to the margin
    width = max(margin - min(near, default=margin), 0.005 * margin, 1e-4)
    grid = np.linspace(max(margin - 1.5 * width, 1e-9), margin + 1.5 * width, points)
    ab = np.array([rightmost_roots(system, x, count=0).abscissa for x in grid])
    ax.plot(grid, ab, ".-", color="C0", ms=3, label=r"max Re $\lambda$ (spectral)")
    ax.axhline(0, color="k", lw=0.8)
    ax.axvline(margin, color="0.5", lw=0.8, ls="--", label=f"first crossing h = {margin:.6g}")
    ax.fill_between(grid, 0, ab, where=ab > 0, color="C3", alpha=0.2, label="unstable (Re λ > 0)")
    styles = ("-", "--", "-.", ":")
    for k, (method, value) in enumerate(certified):
        if value.get("upper") is not None and grid[0] <= float(value["upper"]) <= grid[-1]:
            ax.axvline(float(value["upper"]), color=f"C{(k + 3) % 10}", lw=1.2, ls=styles[k % len(styles)],
                       label=f"certified by {method} up to {float(value['upper']):.6g}")
    span = float(np.max(np.abs(ab))) if len(ab) else 1.0
    ax.set_ylim(-1.2 * span, 1.2 * span)
    ax.set_xlabel("delay h (zoom on the crossing)")
    ax.set_ylabel(r"max Re $\lambda$")
    ax.set_title("around the delay margin", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8)
