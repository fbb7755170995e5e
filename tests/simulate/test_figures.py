"""Figures and run options follow the run (issue 10): titles, ‖χ‖_τ, conventions, distances, wording."""

import numpy as np
import pytest

from lkverify.declare.parse import parse_value
from lkverify.errors import InputError
from lkverify.proofs.aleksandrov2023.fig6 import fig6
from lkverify.proofs.aleksandrov2023.fig7 import fig7
from lkverify.proofs.aleksandrov2023.section6 import R_TARGET, s_minus_r
from lkverify.simulate.experiments import reach_text
from lkverify.simulate.figures import plain
from lkverify.simulate.rigidbody import chi_norm


def _vec(text):
    return parse_value(text, name="omega")


def test_title_is_computed_from_the_values_used():
    ex = fig6.with_options({"b": parse_value("2", name="b"), "mu": parse_value("1", name="mu")})
    title = plain(ex.title_for())
    assert "b = 2" in title and "μ = 1" in title
    assert "b = −1" not in title and "μ = 2" not in title
    assert plain(fig6.title_for()).startswith("Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2")
    # the run, its claims and their result names follow the values too
    assert ex.runs[0].label == title and all(c.run == title for c in ex.claims)


def test_fig7_title_and_chi_follow_the_history():
    ex = fig7.with_options({}, histories={"omega": _vec("[1,1,1]")})
    assert "ω = (1,1,1)" in plain(ex.title_for()) and "0.1(1,1,1)" not in plain(ex.title_for())
    s = np.asarray(ex.runs[0].history["s"], dtype=float)
    assert ex.chi_used() == pytest.approx(chi_norm(s - R_TARGET, np.ones(3)))
    assert ex.chi_used() > 1.5 and fig7.chi_used() == pytest.approx(0.954, abs=1e-3)


def test_convention_changes_the_initial_data():
    base = np.asarray(fig6.runs[0].history["s"], dtype=float)
    other = np.asarray(fig6.with_options({}, convention="zyx").runs[0].history["s"], dtype=float)
    same = np.asarray(fig6.with_options({}, convention="gost").runs[0].history["s"], dtype=float)
    assert not np.allclose(base, other) and np.allclose(base, same)
    assert "[zyx]" in fig6.with_options({}, convention="zyx").title_for()
    with pytest.raises(InputError, match="--convention"):
        fig6.with_options({}, convention="nope")


def test_per_vector_distance_is_selectable():
    ex = fig6.with_options({}, distance="per-vector")
    assert ex.distance is s_minus_r and ex.distance_name == "per-vector"
    with pytest.raises(InputError, match="--distance"):
        fig6.with_options({}, distance="euclid")


def test_reach_wording():
    assert reach_text(1e-2, None, 300) == "does not reach 1e-2 by t = 300"
    assert reach_text(1e-3, 42.0, 300) == "reaches 1e-3 at t = 42"


def test_figure_title_and_labels(tmp_path, monkeypatch):
    """The figure's title is the computed one; every panel has a y label; no literal ‖χ‖_τ subscript."""
    import matplotlib.figure

    seen = {}
    real = matplotlib.figure.Figure.savefig

    def capture(self, *a, **k):
        seen["fig"] = self
        return real(self, *a, **k)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", capture)
    ex = fig7.with_options({"b": parse_value("-2", name="b")}, histories={"omega": _vec("[1,1,1]")})
    trajectories = ex.simulate({"b": parse_value("-2", name="b")}, t_end=20,
                               histories={"omega": _vec("[1,1,1]")})
    ex.plot(trajectories, tmp_path / "f.png", envelope=True)
    fig = seen["fig"]
    title = fig._suptitle.get_text()
    assert "b = −2" in title and "(1,1,1)" in title
    axes = fig.get_axes()
    assert len(axes) == 3 and all(ax.get_ylabel() for ax in axes)
    assert axes[1].get_yscale() == "log"
    texts = [ax.get_title() for ax in axes] + [t.get_text() for ax in axes for t in ax.get_legend().get_texts()]
    assert not any("_τ" in t or "d1(t)" in t for t in texts)
    assert r"\|\chi\|_\tau" in axes[2].get_title()
    assert (tmp_path / "f.png").stat().st_size > 0


def test_fig7_envelope_states_its_region():
    from lkverify.proofs.aleksandrov2023.fig7 import fig7
    from lkverify.proofs.aleksandrov2023.section6 import PRINTED_15

    assert fig7.envelope.valid_below == PRINTED_15["delta_tilde"] == 0.28


def _user_example():
    """A user-built Example (no captions or named distances): x' = −a x(t − τ) from x ≡ 1."""
    import sympy

    from lkverify import Equation, Parameters, Series, System, Term, Vector, t
    from lkverify.catalogue.examples import Example
    from lkverify.simulate.experiments import Run

    P = Parameters()
    a = P.scalar("a", positive=True, default=sympy.Rational(1, 2))
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-a * x(t - tau)[0], text="−a x(t−τ)")])], parameters=P)
    return Example("user.decay", title="x' = −a x(t − τ)", runs=[Run("x ≡ 1", system, {}, {"x": [1]})], t_end=12,
                   series=[Series("x", lambda S: S["x"][:, 0])], distance=lambda S: np.abs(S["x"][:, 0]),
                   ylabel="x", plot_until=6, samples=401)


@pytest.mark.parametrize("suffix,magic", [(".png", b"\x89PNG"), (".svg", b"<?xml"), (".pdf", b"%PDF")])
def test_user_example_figure_in_the_shared_style(tmp_path, suffix, magic):
    from matplotlib.figure import Figure

    ex = _user_example()
    trajectories = ex.simulate()
    drawn = []
    original = Figure.savefig
    try:
        Figure.savefig = lambda self, *a, **k: (drawn.append(self), original(self, *a, **k))[1]
        ex.plot(trajectories, tmp_path / f"f{suffix}")
    finally:
        Figure.savefig = original
    assert (tmp_path / f"f{suffix}").read_bytes().startswith(magic)
    (fig,) = drawn
    (ax,) = fig.axes
    assert ax.get_xlabel() == "$t$" and ax.get_ylabel() == "x"
    assert ax.get_xlim()[1] >= 12 - 1e-9  # the whole run, not only the paper's window t ≤ 6
    assert "t ∈ [0, 12]" in ax.get_title()
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert "the paper's window t ≤ 6" in labels


@pytest.mark.parametrize("name", ["f.jpg", "f", "f.png.txt"])
def test_plot_suffix_other_than_png_pdf_svg_is_refused(name):
    from lkverify.cli import check_output_path

    with pytest.raises(InputError, match=r"\.png, \.pdf, \.svg"):
        check_output_path(name)
