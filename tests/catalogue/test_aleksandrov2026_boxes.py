"""Paper 000 Theorem 1 over intervals of τ (issue 23, deliverable 3): the chain for every τ of an interval.

Theorem 1 says "asymptotically stable for every delay τ > 0".  Over a box of τ the bound steps
are checked with τ a positive symbol (every rule's side conditions decided for every τ > 0), the
Krasovskii conditions with the coefficients of L, U, W enclosed over the interval.

* At the proof's choices for the interval's centre (``theorem1.run(box=…)``) an interval closes
  when those choices still have their margin at its ends: [9/10, 11/10] does, and the 33 intervals
  of :data:`PIECES` cover [1/10, 10] (slow; found by a float-level greedy search, then each run).
* Every τ-dependent coefficient of L and W is worst at the interval's upper end (λτ + μ, τ^{1/P},
  (τδ^P)^{2k/P−1} all grow with τ), so choices picked for both ends at once
  (:func:`~lkverify.proofs.aleksandrov2026.theorem1_chain.box_choices`) establish all of
  [1/10, 10] in one piece.
* Mutations: the decade's choices over [1/10, 11] (the I_i coefficient of L is negative at
  τ = 11); a bound of the chain with τ frozen at the box's lower end (true there, false above);
  an end τ = 0 (not a delay: bad input — the hypothesis τ > 0 is the admissible set of τ, so no
  admissible box can fail it).
"""

import dataclasses

import pytest
import sympy

from lkverify.catalogue.boxrun import BoxStatus
from lkverify.certify.boxes import box_symbol
from lkverify.certify.steps.chain import lyapunov_steps
from lkverify.errors import InputError
from lkverify.proofs.aleksandrov2026 import theorem1_chain as chain
from lkverify.proofs.aleksandrov2026.equations import P, system, tau
from lkverify.proofs.aleksandrov2026.functional9 import functional
from lkverify.proofs.aleksandrov2026.theorem1 import theorem1
from lkverify.proofs.aleksandrov2026.theorem1_bound import derivation
from lkverify.proofs.aleksandrov2026.theorem1_chain import box_choices
from lkverify.status import Status

R = sympy.Rational

#: intervals of τ covering [1/10, 10] on each of which theorem1.run(box=…) is established in one piece
#: (measured: 2.4 s – 5.7 s each, 9.7 s for the first with the identity; about 2 min in all)
ENDS = ["1/10", "329/2500", "329/1250", "407/1250", "1007/2500", "4983/10000", "1233/2000", "7627/10000",
        "2359/2500", "1167/1000", "1443/1000", "357/200", "276/125", "13/5", "1531/500", "347/100", "3817/1000",
        "4199/1000", "4619/1000", "993/200", "5337/1000", "5737/1000", "303/50", "6401/1000", "6761/1000",
        "7141/1000", "7543/1000", "7967/1000", "8303/1000", "8653/1000", "4509/500", "4699/500", "4897/500", "10"]
PIECES = list(zip(ENDS[:-1], ENDS[1:]))


def _rows(piece, kind):
    return [r for r in piece.report.results if r.kind == kind]


def _assert_established_in_one_piece(rep):
    assert rep.status is BoxStatus.ESTABLISHED, rep.verdict
    assert len(rep.pieces) == 1 and rep.checked == 1
    piece = rep.pieces[0]
    bounds, region = _rows(piece, "bound"), _rows(piece, "region")
    assert bounds and all(r.status.is_proof for r in bounds)
    assert region and all(r.status.is_proof for r in region)
    return piece


def test_a_small_interval_of_tau_is_established_at_the_centre_choices():
    rep = theorem1.run(box={"tau": ("9/10", "11/10")}, max_boxes=1)
    piece = _assert_established_in_one_piece(rep)
    # the steps are proved with τ symbolic: τ stays in their bounds, so they hold for every τ of the box
    assert any("tau**(1/(2*nu + 2))" in r.name for r in _rows(piece, "bound"))
    assert rep.verdict.startswith("established for every point of tau ∈ [9/10, 11/10]")


def test_choices_for_both_ends_establish_the_whole_decade_in_one_piece():
    B = {"tau": ("1/10", "10")}
    choices = box_choices(B)
    assert set(choices) == {"gamma", "lam", "mu", "eta_w", "eta_K", "eta", "epsilon", "delta"}
    _assert_established_in_one_piece(theorem1.run(choices, box=B, max_boxes=1))


def test_the_plain_box_run_picks_choices_for_the_whole_decade():
    """`check aleksandrov2026.theorem1 --box tau=1/10:10`: the theorem's choices function takes the box."""
    rep = theorem1.run(box={"tau": ("1/10", "10")}, max_boxes=1)
    _assert_established_in_one_piece(rep)
    assert rep.verdict.startswith("established for every point of tau ∈ [1/10, 10]")


def test_the_decade_choices_are_not_established_beyond_the_decade():
    """A wrong constant: the decade's choices on [1/10, 11]; at τ = 11 the I_i coefficient of L is < 0."""
    choices = box_choices({"tau": ("1/10", "10")})
    rep = theorem1.run(choices, box={"tau": ("1/10", "11")}, max_boxes=1)
    assert rep.status is not BoxStatus.ESTABLISHED and not rep.proved
    region = _rows(rep.pieces[0], "region")
    assert any(r.status is Status.FAILED and "L has the monomial I1" in r.detail for r in region), region


def test_tau_zero_is_not_an_end_of_a_box():
    with pytest.raises(InputError, match="tau"):
        theorem1.run(box={"tau": ("0", "1")})


def _lower_step_with(term_name, replace):
    lower, _ = chain._lower_bounds()
    lower = [dataclasses.replace(tb, bound=replace(tb.bound)) if tb.terms == (term_name,) else tb for tb in lower]
    return lyapunov_steps(functional, system, lower, chain._upper_bounds(), chain._vdot_bounds(), chain.MEASURES,
                          region=chain.REGION, definitions=chain.DEFINITIONS, derivation=derivation)[0]


def test_a_bound_true_at_the_lower_end_only_is_not_proved_over_the_box():
    """−LᵀD⁻¹∫f^νL ≥ −c·τ^{1/P}(…) with τ frozen at 9/10: the claimed bound is stronger than the rule's
    for every τ > 9/10, so over τ ∈ [9/10, 11/10] it must not be proved (at τ = 9/10 itself it is)."""
    name = "−LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ"
    interval = (R(9, 10), R(11, 10))
    T = box_symbol("tau", interval, positive=True)
    values = P.resolve({**theorem1.chosen({"tau": "1"}), "tau": "1"}, use_defaults=True)
    boxed = type(values)({**values, "tau": T})

    def term(step, vals, box):
        res = step.check(vals, parameter_box=box, search=False)
        return next(tr for tr in res.terms if tr.terms == (name,))

    assert term(chain.steps[0], boxed, {T: interval}).status.is_proof        # the chain's own bound: for every τ
    frozen = _lower_step_with(name, lambda b: b.xreplace({tau: interval[0]}))
    over_box = term(frozen, boxed, {T: interval})
    assert not over_box.status.is_proof and "the stated bound is not the rule's" in over_box.detail
    at_end = type(values)({**values, "tau": interval[0]})
    assert term(frozen, at_end, None).status.is_proof                          # at τ = 9/10 it is the rule's


@pytest.mark.slow
def test_intervals_covering_tau_from_one_tenth_to_ten_are_established():
    assert ENDS[0] == "1/10" and ENDS[-1] == "10" and all(R(a) < R(b) for a, b in PIECES)
    for lo, hi in PIECES:
        rep = theorem1.run(box={"tau": (lo, hi)}, max_boxes=3)
        assert rep.status is BoxStatus.ESTABLISHED, f"[{lo}, {hi}]: {rep.verdict}"


@pytest.mark.slow
def test_remark1_delta_certified_piecewise(tmp_path):
    """δ(τ) of Remark 1 as a certified piecewise-constant lower bound: each piece a box run of Theorem 1."""
    from lkverify.proofs.aleksandrov2026.remark1 import Remark1Table, delta_pieces

    values = P.resolve({}, use_defaults=True)
    rows = delta_pieces(values, ends=("1/10", "1/2", "4"))
    assert [r.status for r in rows] == [Status.CERTIFIED, Status.CERTIFIED]
    assert rows[0].value["delta"] > rows[1].value["delta"]             # "the delay decreases δ", per piece
    assert rows[1].value["tau"] == ["1/2", "4"]
    rep, extra = Remark1Table().run("aleksandrov2026.remark1", values, {}, goal="pieces", budget=0.0)
    assert rep.results and all(r.status is Status.UNDECIDED for r in rep.results)       # the budget is honoured
    path = tmp_path / "pieces.png"
    Remark1Table().plot({"pieces": rows}, path)
    assert path.stat().st_size > 0
