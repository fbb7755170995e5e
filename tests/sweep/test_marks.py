"""The paper's gains in a swept plane (lkverify.sweep.marks), at paper 002's figures."""

import dataclasses

import pytest
import sympy

from lkverify import Equation, Example, InputError, Parameters, Run, System, Term, Vector, t
from lkverify.catalogue.loader import find_items
from lkverify.simulate import Converges, DoesNotConverge
from lkverify.sweep.marks import Mark, expectation, mark_label, paper_marks

h, k = sympy.symbols("h k")
R = sympy.Rational


def diag(*entries):
    return sympy.ImmutableMatrix(sympy.diag(*entries))


@pytest.fixture(scope="module")
def paper():
    """Paper 002's examples by name (the paper is loaded once)."""
    return {x.name: x for x in find_items("aleksandrov2023")}


def summary(marks):
    return [(m.label, m.item, m.coords, m.expected) for m in marks]


def test_acceptance_plane_holds_fig1_and_fig2_only(paper):
    # lkverify sweep aleksandrov2023.fig1 --set "F=diag(h,h,h)" --grid b=… --grid h=…
    marks = paper_marks(paper["fig1"], ("b", "h"), {"F": diag(h, h, h)})
    assert summary(marks) == [
        ("Fig. 1", "aleksandrov2023.fig1", {"b": 2, "h": R(7, 10)}, "converges"),
        ("Fig. 2", "aleksandrov2023.fig2", {"b": -2, "h": R(7, 10)}, "does not converge"),
    ]
    for m in marks:                                    # exact coordinates, the catalogued runs
        assert all(isinstance(v, sympy.Rational) for v in m.coords.values())
    assert marks[0].run is paper["fig1"].runs[0] and marks[1].run is paper["fig2"].runs[0]
    assert marks[1].to_meta() == {"label": "Fig. 2", "item": "aleksandrov2023.fig2", "coords": {"b": -2.0, "h": 0.7},
                                  "expected": "does not converge"}


def test_same_plane_from_fig2(paper):
    marks = paper_marks(paper["fig2"], ("b", "h"), {"F": diag(h, h, h)})
    assert [m.label for m in marks] == ["Fig. 1", "Fig. 2"]


def test_four_axes_find_figs_1_to_5_but_not_6_or_7(paper):
    # Fig. 6 has τ = 1 (not swept, the swept example has 0.9); Fig. 7 also another initial history
    marks = paper_marks(paper["fig1"], ("a", "b", "mu", "h"), {"F": diag(h, h, h)})
    assert summary(marks) == [
        ("Fig. 1", "aleksandrov2023.fig1", {"a": 2, "b": 2, "mu": 1, "h": R(7, 10)}, "converges"),
        ("Fig. 2", "aleksandrov2023.fig2", {"a": 2, "b": -2, "mu": 1, "h": R(7, 10)}, "does not converge"),
        ("Fig. 3", "aleksandrov2023.fig3", {"a": 2, "b": -2, "mu": 2, "h": R(7, 10)}, "converges"),
        ("Fig. 4", "aleksandrov2023.fig4", {"a": R(3, 5), "b": R(-3, 5), "mu": 1, "h": R(1, 5)}, "does not converge"),
        ("Fig. 5", "aleksandrov2023.fig5", {"a": R(3, 5), "b": R(-3, 5), "mu": 2, "h": R(1, 5)}, "converges"),
    ]


def test_a_plane_with_no_other_figure(paper):
    # Fig. 6's plane (a = 0, τ = 1, μ = 2): Fig. 7 has the same gains but another initial history
    assert summary(paper_marks(paper["fig6"], ("b", "h"), {"F": diag(h, h, h)})) == [
        ("Fig. 6", "aleksandrov2023.fig6", {"b": -1, "h": 1}, "converges")]
    # Fig. 3's (a, b) plane: Fig. 5 has h = 0.2, not 0.7
    assert [m.label for m in paper_marks(paper["fig3"], ("a", "b"), {})] == ["Fig. 3"]


def test_the_sweeps_history_decides(paper):
    from lkverify.proofs.aleksandrov2023.section6 import FIG7_HISTORY

    marks = paper_marks(paper["fig6"], ("b", "h"), {"F": diag(h, h, h)}, history=FIG7_HISTORY)
    assert [(m.label, m.coords) for m in marks] == [("Fig. 7", {"b": -1, "h": 1})]


def test_fixed_values_must_match(paper):
    # --set a=1: no catalogued figure has a = 1, not even the swept one
    assert paper_marks(paper["fig1"], ("b", "h"), {"F": diag(h, h, h)}, fixed={"a": "1"}) == ()
    same = paper_marks(paper["fig1"], ("b", "h"), {"F": diag(h, h, h)}, fixed={"a": "2", "tau": "9/10"})
    assert [m.label for m in same] == ["Fig. 1", "Fig. 2"]


def test_template_with_two_grid_names(paper):
    # F = diag(h, k, h): both solved from Fig. 1's F = 0.7·I
    marks = paper_marks(paper["fig1"], ("b", "h", "k"), {"F": diag(h, k, h)})
    assert [(m.label, m.coords) for m in marks] == [("Fig. 1", {"b": 2, "h": R(7, 10), "k": R(7, 10)}),
                                                    ("Fig. 2", {"b": -2, "h": R(7, 10), "k": R(7, 10)})]
    # a linear system in h, k: h + k = h − k = 7/10 gives k = 0
    marks = paper_marks(paper["fig1"], ("h", "k"), {"F": diag(h + k, h - k, h + k)})
    assert [(m.label, m.coords) for m in marks] == [("Fig. 1", {"h": R(7, 10), "k": 0})]


def test_no_unique_real_solution_no_mark(paper):
    # h + k = 7/10 on the diagonal does not fix h and k
    assert paper_marks(paper["fig1"], ("h", "k"), {"F": diag(h + k, h + k, h + k)}) == ()
    # h² = 7/10 has two real solutions
    assert paper_marks(paper["fig1"], ("b", "h"), {"F": diag(h ** 2, h ** 2, h ** 2)}) == ()
    # h² = −7/10 has none
    assert paper_marks(paper["fig1"], ("b", "h"), {"F": diag(-h ** 2, -h ** 2, -h ** 2)}) == ()
    # the template's constant entry is not Fig. 1's
    assert paper_marks(paper["fig1"], ("b", "h"), {"F": diag(h, h, 1)}) == ()


def test_expectations_from_the_claims(paper):
    assert expectation(paper["fig4"], paper["fig4"].runs[0]) == "does not converge"   # DoesNotConverge + Sensitive
    assert expectation(paper["fig5"], paper["fig5"].runs[0]) == "converges"
    assert expectation(paper["fig5"], paper["fig4"].runs[0]) == ""                     # claims on another run
    assert mark_label(paper["fig6"], paper["fig6"].runs[0]) == "Fig. 6"


def test_bad_arguments(paper):
    with pytest.raises(InputError, match="at least one grid name"):
        paper_marks(paper["fig1"], (), {})
    with pytest.raises(InputError, match="G are not parameters"):
        paper_marks(paper["fig1"], ("h",), {"G": diag(h, h, h)})
    with pytest.raises(InputError, match="expected a >= 0, got a=-1"):
        paper_marks(paper["fig1"], ("b",), {}, fixed={"a": "-1"})     # a ≥ 0 in paper 002


def user_examples():
    P = Parameters()
    a = P.scalar("a", default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P)

    def fig(name, values, claims=(), history=None):
        return Example(name, runs=[Run(name, sys, values, history or {"x": [1]})], t_end=10, series=[],
                       distance=lambda s: abs(s["x"][:, 0]), claims=list(claims))

    return sys, fig


def test_user_example_outside_the_catalogue():
    _, fig = user_examples()
    mine = fig("fig1", {"a": "1/10"}, [DoesNotConverge("fig1")])
    mine.paper = "nosuchpaper"                     # not a catalogued paper: the example alone
    assert summary(paper_marks(mine, ("a",), {})) == [("Fig. 1", "nosuchpaper.fig1", {"a": R(1, 10)},
                                                       "does not converge")]


def test_candidates_need_the_same_system_and_history():
    _, fig = user_examples()
    swept = fig("fig1", {"a": "1/10"}, [Converges("fig1")])
    other_history = fig("fig2", {"a": "1/2"}, history={"x": [2]})
    _, fig_b = user_examples()                     # an equal but distinct System object
    other_system = fig_b("fig3", {"a": "1/2"})
    same = fig("fig4", {"a": "-1/2"})
    marks = paper_marks(swept, ("a",), {}, candidates=[swept, other_history, other_system, same])
    assert summary(marks) == [("Fig. 1", "fig1", {"a": R(1, 10)}, "converges"), ("Fig. 4", "fig4", {"a": R(-1, 2)}, "")]


def test_mark_is_frozen():
    m = Mark("Fig. 1", "p.fig1", {"b": 2}, "converges")
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.label = "Fig. 2"
    assert m.floats() == {"b": 2.0}
