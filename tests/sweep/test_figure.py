"""The sweep's map (lkverify.sweep.figure) on synthetic tables whose regions are known."""

import numpy as np
import pyarrow as pa
import pytest
from matplotlib.figure import Figure

from lkverify import InputError
from lkverify.sweep.figure import COLOURS, OUTCOMES, agrees, plot_map, theorem_label

PNG = b"\x89PNG\r\n\x1a\n"


def plane(nb=13, nh=8, *, h_range=(0.1, 2), theorem=True, linear=True):
    """A (b, h) table: linear abscissa b − 1/2 (stable for b < 1/2), converged where stable and h > 0.3,
    invalid for h < 0.15, Theorem 3's hypotheses where −1 < b < 0 and h > 1; Theorem 1's nowhere."""
    b = np.linspace(-3, 3, nb)
    h = np.linspace(*h_range, nh)
    B, H = (x.ravel() for x in np.meshgrid(b, h, indexing="ij"))
    n = B.size
    absc = B - 0.5
    valid = H > 0.15
    sim = np.where(absc < 0, np.where(H > 0.3, "converged", "bounded"), "diverged").astype(object)
    sim[~valid] = "invalid"
    cols = {"point": np.arange(n), "b": B, "h": H, "valid": valid,
            "invalid_reason": np.where(valid, "", "F: expected a positive definite matrix").astype(object),
            "linear_abscissa": absc if linear else np.full(n, np.nan),
            "linear_verdict": np.where(absc < 0, "stable", "unstable") if linear else np.full(n, ""),
            "simulated": sim, "t_to_1e-2": np.where(sim == "converged", 10.0 + H, np.nan),
            "final_distance": np.zeros(n)}
    theorems = {}
    if theorem:
        cols["applies:theorem3"] = (B > -1) & (B < 0) & (H > 1) & valid
        cols["margin:theorem3:0"] = H - 1
        cols["applies:theorem1"] = np.zeros(n, bool)
        cols["margin:theorem1:0"] = -np.ones(n)
        theorems = {"theorem3": ["h > 1"], "theorem1": ["mu > 1"]}
    meta = {"item": "aleksandrov2023.fig1", "t_end": 100.0,
            "grid": [{"name": "b", "start": "-3", "stop": "3", "n": nb},
                     {"name": "h", "start": "1/10", "stop": "2", "n": nh}],
            "theorems": theorems, "sets": {"F": "diag(h,h,h)"}, "fixed": {"a": "2", "tau": "9/10", "mu": "1"},
            "linear": "" if linear else "aleksandrov2023.fig1 declares no equilibrium to linearise at",
            "marks": [{"label": "Fig. 1", "coords": {"b": 0.0, "h": 0.7}, "expected": "converges",
                       "observed": "converged"},
                      {"label": "Fig. 2", "coords": {"b": 2.0, "h": 0.7}, "expected": "converges",
                       "observed": "diverged"}]}
    return cols, meta


@pytest.fixture
def captured(monkeypatch):
    """The Figure objects plot_map saves (the file is still written)."""
    figures = []
    save = Figure.savefig

    def spy(self, *args, **kwargs):
        figures.append(self)
        return save(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", spy)
    return figures


def legend_texts(fig):
    return [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]


def written(path):
    data = path.read_bytes()
    return data[:8] == PNG and len(data) > 20_000


def test_2d_map_written_with_every_layer(tmp_path, captured):
    cols, meta = plane()
    path = tmp_path / "map.png"
    plot_map(pa.table(cols), meta, path)
    assert written(path)
    fig, = captured
    texts = legend_texts(fig)
    for name in OUTCOMES:                              # counts computed from the table, not from the figure
        count = int(np.sum(cols["simulated"] == name))
        assert any(t.startswith(f"{name} ({count})") for t in texts), (name, texts)
    in_region = int(cols["applies:theorem3"].sum())
    assert in_region == 4
    assert any(t.startswith(f"Theorem 3: hypotheses hold ({in_region} of {cols['point'].size} points)") for t in texts)
    assert any(t.startswith("Theorem 1: hypotheses hold nowhere on this grid") for t in texts)
    assert any("linearisation stable" in t and "ticks on the stable side" in t for t in texts)
    assert any("simulation agrees" in t for t in texts) and any("simulation disagrees" in t for t in texts)
    assert "fixed: F = diag(h, h, h), a = 2, tau = 0.9, mu = 1" in fig.get_suptitle()
    assert "aleksandrov2023.fig1" in fig.get_suptitle() and "t = 100" in fig.get_suptitle()


@pytest.mark.slow
def test_title_shows_values_as_a_reader_writes_them(tmp_path, captured):
    cols, meta = plane()
    meta = {**meta, "sets": {"F": "Matrix([[h, 0, 0], [0, h, 0], [0, 0, h]])"}, "fixed": {"a": "2", "F": "x"}}
    plot_map(pa.table(cols), meta, tmp_path / "map.png", title=None)
    assert captured[0].get_suptitle().endswith("fixed: F = diag(h, h, h), a = 2")
    plot_map(pa.table(cols), meta, tmp_path / "map.png", title="my map")
    assert captured[1].get_suptitle() == "my map"


def test_marks_filled_when_the_simulation_agrees(tmp_path, captured):
    cols, meta = plane()
    plot_map(pa.table(cols), meta, tmp_path / "map.png")
    top = captured[0].axes[0]
    dots = {(float(l.get_xdata()[0]), float(l.get_ydata()[0])): l.get_markerfacecolor() for l in top.get_lines()
            if l.get_marker() == "o"}
    assert dots[(0.0, 0.7)] == "black"                 # Fig. 1: converges, converged
    assert dots[(2.0, 0.7)] == "white"                 # Fig. 2: converges, diverged
    labels = {t.get_text() for t in top.texts}
    assert {"Fig. 1", "Fig. 2"} <= labels


@pytest.mark.slow
def test_outcome_cells_follow_the_point_column(tmp_path, captured):
    cols, meta = plane()
    order = np.random.default_rng(1).permutation(cols["point"].size)
    shuffled = {k: np.asarray(v)[order] for k, v in cols.items()}
    plot_map(pa.table(cols), meta, tmp_path / "a.png")
    plot_map(pa.table(shuffled), meta, tmp_path / "b.png")
    a, b = (f.axes[0].collections[0].get_array() for f in captured)
    assert np.array_equal(a, b)
    # cell (b = −3, h = 0.1) is invalid, (b = −3, h = 2) converged, (b = 3, h = 2) diverged
    cells = np.asarray(a).reshape(8, 13)               # (h, b): rows up the second axis
    assert cells[0, 0] == 1 + OUTCOMES.index("invalid")
    assert cells[-1, 0] == 1 + OUTCOMES.index("converged") and cells[-1, -1] == 1 + OUTCOMES.index("diverged")


@pytest.mark.parametrize("stable_below", [True, False])
def test_linear_boundary_ticked_on_the_stable_side(tmp_path, captured, stable_below):
    cols, meta = plane(theorem=False)
    cols["linear_abscissa"] = cols["b"] - 0.5 if stable_below else 0.5 - cols["b"]
    plot_map(pa.table(cols), meta, tmp_path / "map.png")
    lines = [l for l in captured[0].axes[0].get_lines() if l.get_path_effects()]
    assert lines
    for line in lines:
        x, y = line.get_xdata(), line.get_ydata()
        assert np.allclose(x, 0.5)                     # the boundary b = 1/2
        # walking up (+h) the left is −b: the stable side b < 1/2 must be on the left (ticks at +90°)
        assert (y[-1] > y[0]) == stable_below


def test_empty_and_full_regions_said_in_the_legend(tmp_path, captured):
    cols, meta = plane()
    cols["applies:theorem3"] = np.zeros_like(cols["applies:theorem3"])
    cols["applies:theorem1"] = np.ones_like(cols["applies:theorem1"])
    plot_map(pa.table(cols), meta, tmp_path / "map.png")
    texts = legend_texts(captured[0])
    assert any(t.startswith("Theorem 3: hypotheses hold nowhere on this grid") for t in texts)
    assert any(t.startswith("Theorem 1: hypotheses hold everywhere on this grid") for t in texts)


@pytest.mark.slow
def test_no_linear_margin_said(tmp_path, captured):
    cols, meta = plane(linear=False)
    plot_map(pa.table(cols), meta, tmp_path / "map.png")
    texts = [" ".join(t.split()) for t in legend_texts(captured[0])]
    assert "linearisation: aleksandrov2023.fig1 declares no equilibrium to linearise at" in texts
    assert not [l for l in captured[0].axes[0].get_lines() if l.get_path_effects()]


def test_1d_strip(tmp_path, captured):
    cols, meta = plane(nb=13, nh=1, h_range=(1.5, 1.5))
    meta = {**meta, "grid": [{"name": "b", "start": -3, "stop": 3, "n": 13}]}
    cols = {k: v for k, v in cols.items() if k != "h"}
    path = tmp_path / "strip.png"
    plot_map(pa.table(cols), meta, path)
    assert written(path)
    fig, = captured
    assert len(fig.axes) == 4
    texts = legend_texts(fig)
    assert any(t.startswith("Theorem 1: hypotheses hold nowhere on this grid") for t in texts)
    stable = int(np.sum(cols["linear_abscissa"] < 0))
    assert f"linearisation stable ({stable} of 13 points)" in texts
    assert "Theorem 3: h > 1" in texts                 # the margin curve of Theorem 3's hypothesis
    assert any(t.startswith("Theorem 3: hypotheses hold (1 of 13 points)") for t in texts)   # b = −1/2 only


def test_2d_with_a_single_value_axis_and_a_mark_outside(tmp_path, captured):
    cols, meta = plane(nb=5, nh=1, h_range=(0.7, 0.7))
    meta = {**meta, "grid": [meta["grid"][0], {"name": "h", "start": 0.7, "stop": 0.7, "n": 1}]}
    meta["marks"] = meta["marks"] + [{"label": "Fig. 9", "coords": {"b": 7.0, "h": 0.7}, "expected": "",
                                      "observed": ""}]
    path = tmp_path / "thin.png"
    plot_map(pa.table(cols), meta, path)
    assert written(path)
    texts = legend_texts(captured[0])
    assert "outside the grid: Fig. 9 (b = 7, h = 0.7)" in texts             # Figs. 1 and 2 are on it
    assert sum(1 for l in captured[0].axes[0].get_lines() if l.get_marker() == "o") == 2
    # one row of cells has no contour: the boundary is the cell edge b = 3/4 between b = 0 (stable) and
    # b = 3/2 (unstable), walked upwards so that the stable side is on its left
    boundary, = [l for l in captured[0].axes[0].get_lines() if l.get_path_effects()]
    assert np.allclose(boundary.get_xdata(), 0.75) and boundary.get_ydata()[1] > boundary.get_ydata()[0]


class Frame:
    """What plot_map uses of a pandas DataFrame (pandas is not a dependency)."""

    class Column:
        def __init__(self, values):
            self.values = values

        def to_numpy(self):
            return np.asarray(self.values)

    def __init__(self, cols):
        self.cols = cols
        self.columns = list(cols)

    def __getitem__(self, name):
        return self.Column(self.cols[name])


def test_dataframe_and_mapping_accepted(tmp_path):
    cols, meta = plane()
    plot_map(Frame(cols), meta, tmp_path / "frame.png")
    plot_map(cols, meta, tmp_path / "dict.svg")
    assert written(tmp_path / "frame.png")
    assert (tmp_path / "dict.svg").read_text().lstrip().startswith("<?xml")


def test_more_than_two_axes_refused(tmp_path):
    cols, meta = plane()
    meta = {**meta, "grid": meta["grid"] + [{"name": "tau", "start": 1, "stop": 2, "n": 2}]}
    with pytest.raises(InputError, match="3 axes .b, h, tau.; the table was written, but the map needs 1 or 2 axes"):
        plot_map(pa.table(cols), meta, tmp_path / "map.png")
    assert not (tmp_path / "map.png").exists()


def test_bad_tables_refused(tmp_path):
    cols, meta = plane()
    with pytest.raises(InputError, match="no column simulated"):
        plot_map({k: v for k, v in cols.items() if k != "simulated"}, meta, tmp_path / "map.png")
    with pytest.raises(InputError, match="outside the grid of 104 points"):
        plot_map({**cols, "point": cols["point"] + 1}, meta, tmp_path / "map.png")
    with pytest.raises(InputError, match="meta\\['grid'\\] is empty"):
        plot_map(cols, {**meta, "grid": []}, tmp_path / "map.png")
    with pytest.raises(InputError, match="expected a pyarrow Table"):
        plot_map([1, 2, 3], meta, tmp_path / "map.png")


def test_agreement_and_labels():
    assert agrees("converges", "converged") is True
    assert agrees("converges", "bounded") is False
    assert agrees("does not converge", "diverged") is True
    assert agrees("does not converge", "converged") is False
    assert agrees("", "converged") is None and agrees("converges", "invalid") is None
    assert theorem_label("theorem3") == "Theorem 3" and theorem_label("aleksandrov2017.lemma1") == "Lemma 1"
    assert len(set(COLOURS.values())) == len(OUTCOMES)
