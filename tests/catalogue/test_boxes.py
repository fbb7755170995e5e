"""Theorems over boxes of parameters (issue 23): every link for every point of the box, split until it closes.

The toy theorem: x' = −kx (x ∈ R²), V = ‖x‖²/2, V ≥ ½n², V ≤ ½n², V̇ = −k‖x‖² ≤ −k n², decay
V̇ ≤ −c̃V.  Over k ∈ [1/2, 2] it is established; mutations of it (a hypothesis failing at a
corner, a margin 0 at a corner, a step that is false at the centre, a liar rule, a float end)
are refuted or weakened, never established.
"""

import dataclasses

import pytest
import sympy

from lkverify import DerivativeClaim, Equation, Functional, Hypothesis, Parameters, System, Term, Vector, t
from lkverify.catalogue.boxrun import BoxStatus, run_over_box
from lkverify.catalogue.items import Theorem
from lkverify.certify.steps import Rayleigh, Region, TermBound, lyapunov_steps, norm_measure
from lkverify.certify.steps.chain import Decay
from lkverify.certify.steps.rules import Application, Condition, Rule
from lkverify.declare.boxes import ParameterBox, parse_boxes
from lkverify.errors import InputError, RuleSoundnessError
from lkverify.status import Status

R = sympy.Rational
P = Parameters()
k = P.scalar("k", default=1)
c = P.scalar("c", default=0)
x = Vector("x", 2)
n = norm_measure("n", x(t))
N = n.symbol
SYS = System([Equation(x, [Term(-k * x(t))])], parameters=P)
V = Functional([Term(x(t).dot(x(t)) / 2, text="½‖x‖²")])
VDOT = DerivativeClaim("Vdot", V, SYS, [Term(-k * x(t).dot(x(t)), text="−k‖x‖²")])
EYE = sympy.eye(2)


def _theorem(vdot_bound=None, vdot_rule=None, hypotheses=None):
    half = [TermBound("½‖x‖²", N**2 / 2, Rayleigh(x(t), EYE / 2, eigenvalue=R(1, 2), norm_squared=N**2))]
    bound = -k * N**2 if vdot_bound is None else vdot_bound
    rule = vdot_rule or Rayleigh(x(t), -EYE, factor=k, eigenvalue=-1, norm_squared=N**2)
    steps = lyapunov_steps(V, SYS, half, half, [TermBound("−k‖x‖²", bound, rule)], [n], derivation=VDOT,
                           region=Region({n: 1}))
    return Theorem("toy", system=SYS, functional=V, claims=[VDOT], steps=steps,
                   hypotheses=hypotheses if hypotheses is not None else [Hypothesis("k > 0", k)],
                   decay=Decay(1, ("n",), {}, {"d1": "n"}))


TOY = _theorem()


# -- the box itself -------------------------------------------------------------------------------
def test_box_ends_are_exact_rationals_and_a_float_end_is_marked():
    B = parse_boxes(["k=1/2:2"])
    assert B.bounds["k"] == (R(1, 2), 2) and B.from_float == frozenset()
    D = parse_boxes(["k=0.1:2"])            # a decimal typed on the command line is the exact rational it reads
    assert D.bounds["k"][0] == R(1, 10) and D.from_float == frozenset()
    F = ParameterBox({"k": (0.1, 2)})          # a Python float: its exact binary value, marked
    assert F.bounds["k"][0] == R(0.1) and F.bounds["k"][0] != R(1, 10) and F.from_float == {"k"}


@pytest.mark.parametrize("texts, needle", [
    (["k=2:1"], "LO ≤ HI"), (["k=1"], "NAME=LO:HI"), (["k=1:2", "k=2:3"], "twice"), (["k=nan:1"], "finite"),
    (["k=sqrt(2):2"], "rational end"), (["k=__import__('os'):1"], "k"),
])
def test_bad_boxes_are_input_errors(texts, needle):
    with pytest.raises(InputError, match=needle.replace("(", r"\(")):
        parse_boxes(texts)


def test_split_halves_the_widest_interval_and_fractions_are_exact():
    B = ParameterBox({"k": (0, 1), "c": (0, 4)})
    left, right = B.split(B.widest())
    assert left.bounds["c"] == (0, 2) and right.bounds["c"] == (2, 4) and left.bounds["k"] == (0, 1)
    assert left.fraction_of(B) + right.fraction_of(B) == 1
    assert left.split("k")[0].fraction_of(B) == R(1, 4)


# -- a theorem over a box ----------------------------------------------------------------------------
def test_toy_theorem_is_established_for_every_point_of_the_box():
    rep = TOY.run(box={"k": ("1/2", "2")})
    assert rep.status is BoxStatus.ESTABLISHED and rep.exit_code == 0 and rep.proved_fraction == 1
    piece = rep.pieces[0].report
    assert piece.verdict.startswith("established")
    vdot = next(r for r in piece.results if r.name == "Vdot")
    assert vdot.status is Status.EXACT and "symbolic: for every value" in vdot.detail
    hyp = next(r for r in piece.results if r.name == "k > 0")
    assert hyp.status is Status.EXACT and "over the whole box" in hyp.detail
    # the decay's rate is the uniform one: W = −k n² ≤ −(1/2) n² on the whole box, so c̃ ≤ 1
    c_tilde = next(r for r in piece.results if r.name == "c_tilde")
    assert c_tilde.status is Status.CERTIFIED and c_tilde.value["value"] > 0 and c_tilde.value["value"] <= 1.0 + 1e-12


def test_a_box_reaching_where_the_hypothesis_fails_is_failed_at_that_point():
    rep = TOY.run(box={"k": ("-1/2", "2")})
    assert rep.status is BoxStatus.FAILED and rep.exit_code == 1
    (f,) = rep.failing
    assert f.point == {"k": R(-1, 2)} and "k > 0" in f.link and rep.proved_fraction == 0


def test_a_margin_exactly_zero_at_a_corner_fails_and_a_tiny_exact_step_inside_holds():
    assert TOY.run(box={"k": ("0", "1")}).failing[0].point == {"k": 0}           # k > 0 is 0 there
    tiny = R(1, 10**30)
    assert TOY.run(box={"k": (tiny, 1)}).status is BoxStatus.ESTABLISHED


def test_a_margin_interval_arithmetic_cannot_separate_is_split_and_left_undecided_not_established():
    # (k − 1)² + 1/1000 written k(k − 2) + 1001/1000: > 0 everywhere, but interval arithmetic loses the
    # correlation of the two k's; the pieces near the ends close, those near k = 1 stay open
    hyp = Hypothesis("k(k−2) + 1001/1000 > 0", k * (k - 2) + R(1001, 1000))
    th = _theorem(hypotheses=[Hypothesis("k > 0", k), hyp])
    rep = run_over_box(th, {}, {"k": (R(1, 2), R(3, 2))}, max_boxes=15)
    assert rep.status is BoxStatus.UNDECIDED and not rep.failing and rep.exit_code == 1
    assert rep.proved_fraction > 0 and rep.proved_fraction < 1 and rep.checked == 15
    assert all(p.box.fraction_of(rep.box) <= R(1, 2) for p in rep.pieces)


def test_a_step_false_at_the_centre_of_the_box_is_a_failing_point():
    wrong = _theorem(vdot_bound=-2 * k * N**2)       # V̇ = −k‖x‖² ≤ −2k n² is false for every k > 0
    rep = wrong.run(box={"k": ("1/2", "3/2")})
    assert rep.status is BoxStatus.FAILED
    (f,) = rep.failing
    assert f.point == {"k": 1} and f.link == "V̇ ≤ W" and "centre" in f.detail


def test_a_dropped_term_in_the_vdot_bound_is_not_established():
    dropped = _theorem(vdot_bound=sympy.S.Zero * N)   # W = 0: no decay; the step holds but the chain does not close
    rep = dropped.run(box={"k": ("1/2", "2")}, max_boxes=3)
    assert rep.status is not BoxStatus.ESTABLISHED and rep.proved_fraction == 0


@dataclasses.dataclass(frozen=True)
class Liar(Rule):
    """An unsound rule: claims ``bound`` with one 'exact' side condition that checks nothing."""

    bound: object = None
    name = "the liar's rule"

    def apply(self, term, direction, ctx):
        return Application(self.name, ctx.at(self.bound), (Condition("trust me", Status.EXACT, ""),))


def test_a_liar_rule_over_a_box_is_caught_at_the_centre():
    liar = _theorem(vdot_bound=-2 * k * N**2, vdot_rule=Liar(-2 * k * N**2))
    with pytest.raises(RuleSoundnessError, match="centre k = 1"):
        liar.run(box={"k": ("1/2", "3/2")})


def test_a_float_end_makes_results_that_depend_on_it_at_most_certified():
    rep = TOY.run(box={"k": (0.5, 2)})
    assert rep.status is BoxStatus.ESTABLISHED
    rows = {r.name: r for r in rep.pieces[0].report.results}
    assert rows["k > 0"].status is Status.CERTIFIED
    assert not any(r.status is Status.EXACT and r.kind == "bound" and "k" in r.name for r in rows.values())


def test_bad_box_names_are_input_errors():
    with pytest.raises(InputError, match="no such parameter"):
        TOY.run(box={"q": (0, 1)})
    with pytest.raises(InputError, match="also given with --set"):
        TOY.run({"k": 1}, box={"k": (0, 1)})
    with pytest.raises(InputError, match="max_boxes"):
        run_over_box(TOY, {}, {"k": (1, 2)}, max_boxes=0)


def test_the_box_report_json_and_text_name_the_pieces():
    rep = TOY.run(box={"k": ("1/2", "2")})
    js = rep.to_json()
    assert js["status"] == "established" and js["proved_fraction"] == "1" and js["box"] == {"k": ["1/2", "2"]}
    assert js["pieces"][0]["chain"][-1]["link"] == "conclusion"
    text = rep.as_text()
    assert "over the box k ∈ [1/2, 2]" in text and "verdict: established for every point" in text


# -- paper 002, Theorem 3 over a box around the Fig. 6 gains --------------------------------------------
@pytest.mark.slow
def test_theorem3_is_established_over_a_box_around_fig6():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    rep = theorem3.run(box={"b": ("-11/10", "-9/10"), "tau": ("9/10", "11/10")})
    assert rep.status is BoxStatus.ESTABLISHED, rep.verdict
    first = rep.pieces[0].report
    assert any(r.name == "c_tilde" and r.status is Status.CERTIFIED for r in first.results)


def test_theorem3_box_across_b_tau_equal_a_is_failed_at_a_corner():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    rep = theorem3.run(box={"b": ("-1/10", "1/10"), "tau": ("9/10", "11/10")})   # a = 0: bτ < 0 fails for b > 0
    assert rep.status is BoxStatus.FAILED
    point = rep.failing[0].point
    assert point["b"] * point["tau"] >= 0 and "b*tau < a" in rep.failing[0].link


def test_a_matrix_hypothesis_on_a_boxed_parameter_is_undecided_not_split_and_one_off_the_box_is_decided():
    from lkverify import MatrixHypothesis

    on_k = _theorem(hypotheses=[Hypothesis("k > 0", k), MatrixHypothesis("[[2, k], [k, 2]] ≻ 0",
                                                                         sympy.Matrix([[2, k], [k, 2]]))])
    rep = on_k.run(box={"k": ("1/2", "1")})
    assert rep.status is BoxStatus.UNDECIDED and rep.checked == 1      # splitting cannot decide it: not split
    row = next(r for r in rep.pieces[0].report.results if r.name.startswith("[[2, k]"))
    assert row.status is Status.UNDECIDED and "decided at points only" in row.detail
    off = _theorem(hypotheses=[Hypothesis("k > 0", k), MatrixHypothesis("[[2, c], [c, 2]] ≻ 0",
                                                                        sympy.Matrix([[2, c], [c, 2]]))])
    assert off.run(box={"k": ("1/2", "1")}).status is BoxStatus.ESTABLISHED


# -- boxes of variables written in the given values ---------------------------------------------------
G = sympy.Symbol("g")


def test_a_box_of_a_variable_written_in_a_value_covers_every_point():
    rep = TOY.run({"k": 2 * G}, box={"g": ("1/4", "1")})
    assert rep.status is BoxStatus.ESTABLISHED and rep.parameters["k"] == "2*g"
    c_tilde = next(r for r in rep.pieces[0].report.results if r.name == "c_tilde")
    assert c_tilde.value["value"] <= 1.0 + 1e-12             # the worst point k = 1/2


def test_a_hypothesis_failing_through_a_written_variable_is_failed_at_that_point():
    rep = TOY.run({"k": G - R(1, 2)}, box={"g": (0, 1)})
    assert rep.status is BoxStatus.FAILED and rep.failing[0].point == {"g": 0}


def test_written_variables_need_an_interval_and_matrices_must_stay_positive_definite():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    h = sympy.Symbol("h")
    with pytest.raises(InputError, match="no interval"):
        TOY.run({"k": 2 * G, "c": h}, box={"g": (1, 2)})
    with pytest.raises(InputError, match="positive-definite matrix at every point"):
        theorem3.run({"F": sympy.diag(h, h, h)}, box={"h": ("-1/10", "1")})
    with pytest.raises(InputError, match="positive-definite matrix at every point"):
        theorem3.run({"F": sympy.diag(h, 1, 1 - h)}, box={"h": ("1/2", "1")})   # 1 − h = 0 at h = 1


@pytest.mark.slow
def test_theorem3_over_b_and_the_gain_h_of_f_around_fig6():
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    h = sympy.Symbol("h")
    rep = theorem3.run({"F": sympy.diag(h, h, h)}, box={"b": ("-11/10", "-9/10"), "h": ("9/10", "11/10")})
    assert rep.status is BoxStatus.ESTABLISHED, rep.verdict
    kappa = next(r for r in rep.pieces[0].report.results if "(s×r)ᵀF⁻¹Θω ≤" in r.name)
    assert "parameter box" in str(kappa.value)             # κ1 is a supremum over the chart × h ∈ [9/10, 11/10]


def test_a_float_end_of_a_written_variable_makes_what_depends_on_it_at_most_certified():
    rep = TOY.run({"k": 2 * G}, box={"g": (0.25, 1)})
    assert rep.status is BoxStatus.ESTABLISHED
    rows = {r.name: r for r in rep.pieces[0].report.results}
    assert rows["k > 0"].status is Status.CERTIFIED
    assert rows["V̇ ≤ W"].status is Status.CERTIFIED          # −k‖x‖² ≤ −k n² with k = 2g, g from a float


def test_a_certified_constant_per_piece_is_a_piecewise_bound_over_the_box():
    rep = run_over_box(TOY, {}, {"k": ("1/2", "2")})
    ((box, c),) = rep.constant("c_tilde")
    assert box == rep.box and c > 0 and c <= 1 + 1e-12          # the worst point k = 1/2 bounds the whole box
    assert rep.constant("no_such_constant") == ()
    wide = run_over_box(TOY, {}, {"k": ("-1", "2")})             # failed: no established piece, no bound
    assert wide.constant("c_tilde") == ()


def test_a_spent_budget_leaves_the_rest_undecided_never_established():
    hyp = Hypothesis("k(k−2) + 1001/1000 > 0", k * (k - 2) + R(1001, 1000))
    th = _theorem(hypotheses=[Hypothesis("k > 0", k), hyp])
    rep = run_over_box(th, {}, {"k": (R(1, 2), R(3, 2))}, max_boxes=15, budget=1e-3)
    assert rep.status is BoxStatus.UNDECIDED and rep.exit_code == 1
    assert any("budget" in p.verdict for p in rep.pieces)


def test_a_decay_refuted_by_a_positive_lowest_order_part_is_not_retried_on_smaller_regions(monkeypatch):
    # V̇ = −k‖x‖² ≤ k n² is a true (loose) step; W = k n² > 0 at n = 1 and along its whole ray near 0,
    # so no region scaled by REGION_FACTORS can give a decay: certified once, refuted, not retried
    loose = _theorem(vdot_bound=k * N**2, vdot_rule=Rayleigh(x(t), -EYE, factor=k, eigenvalue=1, norm_squared=N**2))
    calls = []
    certify = Decay.certify
    monkeypatch.setattr(Decay, "certify", lambda self, *a, **kw: calls.append(kw.get("region")) or certify(self, *a, **kw))
    rep = run_over_box(loose, {}, {"k": (1, 2)}, max_boxes=1)
    assert rep.status is BoxStatus.UNDECIDED and not rep.failing                 # not a refutation of the theorem
    decay = next(r for r in rep.pieces[0].report.results if r.name == "decay on the region")
    assert decay.status is Status.FAILED and "no smaller region helps" in decay.detail
    assert calls == [None]
    # the toy's own step W = −k n²: lowest-order part negative, established on the first region
    calls.clear()
    assert run_over_box(TOY, {}, {"k": (1, 2)}, max_boxes=1).status is BoxStatus.ESTABLISHED and calls == [None]


# -- the search of the choices over a box: stopped early, remembered per process, checked over the piece ----------
Pg = Parameters()
kg = Pg.scalar("k", default=1)
g = Pg.scalar("g", default=1)                    # a choice of the proof (the stub chain below reads it)
xg = Vector("x", 2)
ng = norm_measure("n", xg(t))
SYSg = System([Equation(xg, [Term(-kg * xg(t))])], parameters=Pg)
Vg = Functional([Term(xg(t).dot(xg(t)) / 2, text="½‖x‖²")])
VDOTg = DerivativeClaim("Vdot", Vg, SYSg, [Term(-kg * xg(t).dot(xg(t)), text="−k‖x‖²")])


def _chosen_theorem(job):
    half = [TermBound("½‖x‖²", ng.symbol**2 / 2, Rayleigh(xg(t), EYE / 2, eigenvalue=R(1, 2), norm_squared=ng.symbol**2))]
    rule = Rayleigh(xg(t), -EYE, factor=kg, eigenvalue=-1, norm_squared=ng.symbol**2)
    steps = lyapunov_steps(Vg, SYSg, half, half, [TermBound("−k‖x‖²", -kg * ng.symbol**2, rule)], [ng],
                           derivation=VDOTg, region=Region({ng: 1}))
    return Theorem("toy_choices", system=SYSg, functional=Vg, claims=[VDOTg], steps=steps,
                   hypotheses=[Hypothesis("k > 0", kg)], decay=Decay(1, ("n",), {}, {"d1": "n"}),
                   choices={"g": "1"}, constants=job)


def _decay_closes_only_at(monkeypatch, good: str):
    """The chain's decay link refuted unless the choice g is ``good`` (the rest of the chain as it is)."""
    from lkverify.catalogue import boxrun
    from lkverify.catalogue.links import Link

    real = boxrun._State._chain_at

    def chain_at(self, box, sym_values, *args):
        rows, checked, cut, failing, decay = real(self, box, sym_values, *args)
        if str(sym_values["g"]) != good:
            decay = Link(decay.name, Status.FAILED, "stub: refuted unless g = " + good)
        return rows, checked, cut, failing, decay

    monkeypatch.setattr(boxrun._State, "_chain_at", chain_at)


def _search_job(found, calls):
    from types import SimpleNamespace

    def search_choices(name, values, *, progress=None, stall=None):
        calls.append((str(values["k"]), stall))
        return (dict(found), "stub search") if found else (None, "stub: the search found none")

    return SimpleNamespace(steps=True, free={"g": (0, 10)}, search_choices=search_choices)


def test_the_box_search_stops_early_and_what_it_finds_is_checked_over_the_piece(monkeypatch):
    from lkverify.catalogue.boxrun import BOX_SEARCH_STALL

    _decay_closes_only_at(monkeypatch, "7")
    calls = []
    rep = run_over_box(_chosen_theorem(_search_job({"g": "7"}, calls)), {}, {"k": ("1/2", "2")}, max_boxes=1)
    assert rep.status is BoxStatus.ESTABLISHED and rep.pieces[0].choices["g"] == "7"
    assert calls and all(stall == BOX_SEARCH_STALL for _, stall in calls)


@pytest.mark.parametrize("found", [None, {"g": "3"}])
def test_choices_an_early_stopped_search_returns_that_do_not_close_leave_the_box_undecided(monkeypatch, found):
    # the search stopped early with choices that do not close (or none): nothing is claimed for them
    _decay_closes_only_at(monkeypatch, "7")
    calls = []
    rep = run_over_box(_chosen_theorem(_search_job(found, calls)), {}, {"k": ("1/2", "2")}, max_boxes=1)
    assert calls and rep.status is BoxStatus.UNDECIDED and not rep.proved and rep.exit_code == 1
    assert not rep.failing                       # refuted at some choices is not a failing point of the theorem


def test_a_search_at_a_corner_is_reused_by_a_neighbouring_box_of_the_same_job_only(monkeypatch):
    _decay_closes_only_at(monkeypatch, "7")
    calls = []
    th = _chosen_theorem(_search_job({"g": "7"}, calls))
    first = run_over_box(th, {}, {"k": ("1/2", "1")}, max_boxes=1)
    searched = list(calls)
    second = run_over_box(th, {}, {"k": ("1/2", "1")}, max_boxes=1)   # the same corners: no new search
    assert first.status is second.status is BoxStatus.ESTABLISHED and calls == searched
    assert first.pieces[0].choices == second.pieces[0].choices
    other = []                                   # another job at the same corners searches for itself
    third = run_over_box(_chosen_theorem(_search_job({"g": "5"}, other)), {}, {"k": ("1/2", "1")}, max_boxes=1)
    assert other and third.status is BoxStatus.UNDECIDED
