"""RaiseOnRegion: x^a ≥ h^{a−k}x^k on 0 ≤ x ≤ h, h > 0, a < k (a power raised on the region).

Each side condition is violated alone and the rule refuses (``failed`` when refuted, ``undecided`` when it
holds on part of a parameter box only, as for OnRegion in test_rewrites.py / test_rewrites_boxes.py); then
the rule inside a bound step: a raised bound with a constant 1 % too large is not accepted, a true one
written differently is.
"""

import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t
from lkverify.certify.boxes import box_symbol
from lkverify.certify.steps import Rayleigh, TermBound, TermwiseBound
from lkverify.certify.steps.measures import Region, norm_measure
from lkverify.certify.steps.rewrites import RaiseOnRegion
from lkverify.certify.steps.rules import Context
from lkverify.status import Status

R = sympy.Rational
P = Parameters()
c = P.scalar("c", default=2)
x, y = Vector("x", 2), Vector("y", 2)
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
a, b = norm_measure("a", x(t)), norm_measure("b", y(t))
A, B = a.symbol, b.symbol
H = R(1, 10)


def _ctx(region=H, box=None):
    """The context with the region a ≤ ``region`` (None: no region), c boxed in ``box`` = (lo, hi) if given."""
    values = P.resolve({}, use_defaults=True)
    pbox = None
    if box is not None:
        sym = box_symbol("c", (R(box[0]), R(box[1])))
        values, pbox = type(values)({**values, "c": sym}), {sym: (R(box[0]), R(box[1]))}
    reg = None if region is None else Region({a: region})
    return Context(SYS, values, {"a": a, "b": b}, reg, parameter_box=pbox)


def test_raises_the_power_in_both_directions():
    up = RaiseOnRegion("a", 4).rewrite(-c * A**2 * B, _ctx(), "upper")           # −2a²b ≤ −2·100·a⁴b
    assert up.status is Status.EXACT and sympy.expand(up.bound + 200 * A**4 * B) == 0
    low = RaiseOnRegion("a", 4).rewrite(3 * A**2 + B, _ctx(), "lower")          # 3a² ≥ 300a⁴; b kept
    assert low.status is Status.EXACT and sympy.expand(low.bound - 300 * A**4 - B) == 0
    # powers at or above k and terms without a are kept
    kept = RaiseOnRegion("a", 4).rewrite(-A**2 + A**5 + A**4 - B**3, _ctx(), "upper")
    assert kept.status is Status.EXACT and sympy.expand(kept.bound - (-100 * A**4 + A**5 + A**4 - B**3)) == 0
    # a fractional power, a fractional keep
    frac = RaiseOnRegion("a", R(7, 2)).rewrite(-A ** R(3, 2), _ctx(R(1, 4)), "upper")   # −a^{3/2} ≤ −16a^{7/2}
    assert frac.status is Status.EXACT and sympy.expand(frac.bound + 16 * A ** R(7, 2)) == 0


def test_the_rule_is_directional():
    assert RaiseOnRegion("a", 4).directional


def test_a_share_raises_part_of_the_term():
    app = RaiseOnRegion("a", 4, share=R(1, 4)).rewrite(-4 * A**2, _ctx(), "upper")
    assert app.status is Status.EXACT and sympy.expand(app.bound - (-100 * A**4 - 3 * A**2)) == 0


# -- each side condition violated alone ---------------------------------------------------------------
def test_refused_without_a_region_bound_on_the_measure():
    app = RaiseOnRegion("a", 4).rewrite(-A**2, _ctx(region=None), "upper")
    assert app.status is Status.FAILED and "the region bounds" in app.detail
    app = RaiseOnRegion("b", 4).rewrite(-B**2, _ctx(), "upper")                  # the region bounds a, not b
    assert app.status is Status.FAILED


def test_refused_unless_h_is_positive_for_every_value():
    assert RaiseOnRegion("a", 4).rewrite(-A**2, _ctx(region=0), "upper").status is Status.FAILED      # h = 0
    assert RaiseOnRegion("a", 4).rewrite(-A**2, _ctx(region=-H), "upper").status is Status.FAILED     # h < 0
    # h = c with c ∈ [0, 1]: h ≥ 0 (OnRegion would take it) but h > 0 is not shown: undecided
    ctx = _ctx(region=c, box=("0", "1"))
    part = RaiseOnRegion("a", 4).rewrite(-A**2, ctx, "upper")
    assert part.status is Status.UNDECIDED and "h > 0 is not shown" in part.detail
    ctx = _ctx(region=c, box=("-1/10", "1"))
    assert RaiseOnRegion("a", 4).rewrite(-A**2, ctx, "upper").status is Status.UNDECIDED
    ok = RaiseOnRegion("a", 4).rewrite(-A**2, _ctx(region=c, box=("1/10", "1")), "upper")
    assert ok.status is Status.EXACT


def test_refused_when_a_raised_factor_has_the_wrong_sign():
    assert RaiseOnRegion("a", 4).rewrite(A**2, _ctx(), "upper").status is Status.FAILED     # a² ≤ 100a⁴ false
    assert RaiseOnRegion("a", 4).rewrite(-A**2, _ctx(), "lower").status is Status.FAILED    # −a² ≥ −100a⁴ false
    mixed = RaiseOnRegion("a", 4).rewrite(-A**2 + A**3 * B, _ctx(), "upper")                # one good, one bad
    assert mixed.status is Status.FAILED and "of a^3 is ≤ 0" in mixed.detail
    ctx = _ctx(box=("-1/10", "1"))                          # c·a² with c of both signs on the box
    part = RaiseOnRegion("a", 4).rewrite(ctx.at(c * A**2), ctx, "upper")
    assert part.status is Status.UNDECIDED and "not shown for every value" in part.detail


def test_refused_when_the_share_is_out_of_range():
    for theta in (0, R(-1, 2), R(3, 2)):
        app = RaiseOnRegion("a", 4, share=theta).rewrite(-A**2, _ctx(), "upper")
        assert app.status is Status.FAILED and "0 < θ ≤ 1" in app.detail


def test_refused_when_no_term_has_a_power_below_k():
    assert RaiseOnRegion("a", 4).rewrite(-A**5, _ctx(), "upper").status is Status.FAILED
    assert RaiseOnRegion("a", 4).rewrite(-A**4, _ctx(), "upper").status is Status.FAILED
    assert RaiseOnRegion("a", 4).rewrite(-B**2, _ctx(), "upper").status is Status.FAILED   # a absent


# -- inside a bound step: the stated bound must be the rule's or weaker ---------------------------------
def _step(stated):
    """−c‖x‖² ≤ stated on ‖x‖ ≤ 1/10: Rayleigh (−c a²), then a² raised to a⁴."""
    rule = Rayleigh(x(t), sympy.eye(2), factor=-c, eigenvalue=1, norm_squared=A**2)
    tb = TermBound("T", stated, rule, then=(RaiseOnRegion("a", 4),))
    return TermwiseBound("−c‖x‖² ≤ …", None, SYS, "terms", [tb], stated, [a, b], region=Region({a: H}),
                         terms=(Term(-c * x(t).dot(x(t)), text="T"),))


def test_a_raised_bound_with_a_constant_too_large_is_not_accepted():
    values = P.resolve({}, use_defaults=True)
    wrong = _step(-c * H**-2 * R(101, 100) * A**4).check(values)     # −2a² ≤ −202a⁴ is false at a = 1/10
    assert wrong.status is Status.FAILED, wrong.detail                 # refuted by a rechecked witness
    assert "refuted" in wrong.terms[0].detail and "the stated bound is not the rule's" in wrong.terms[0].detail


def test_a_true_raised_bound_written_differently_is_accepted():
    values = P.resolve({}, use_defaults=True)
    for stated in (-c * (A**2 / H) ** 2, -c * (10 * A) ** 4 / 100, -199 * A**4):   # the last one weaker
        res = _step(stated).check(values)
        assert res.status is Status.EXACT, res.detail
