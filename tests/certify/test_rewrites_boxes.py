"""The rewrites (and the window-weight rule) over a box of parameters: a side condition that holds on part
of the box only is not proved — and not refuted either (it is undecided: the box runner splits it).

A boxed parameter is a symbol carrying its interval's sign (:func:`lkverify.certify.boxes.box_symbol`):
c ∈ [1/10, 1] is a positive symbol, c ∈ [−1/10, 1] a real one; h ∈ [1/2, 1] (a delay) is positive.
"""

import sympy

from lkverify import Equation, Parameters, System, Term, Vector, norm_power, t, window_integral, xi
from lkverify.certify.boxes import box_symbol
from lkverify.certify.steps.measures import Region, norm_measure, window_integral_measure
from lkverify.certify.steps.rewrites import OnRegion, WindowHolder, YoungEach
from lkverify.certify.steps.rules import Context, WindowWeight
from lkverify.status import Status

R = sympy.Rational
P = Parameters()
c = P.scalar("c", default=1)
h = P.delay("h", default=1)
x, y = Vector("x", 2), Vector("y", 2)
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
I = window_integral_measure("I", x(xi), p=2, window=h)
K = window_integral_measure("K", x(xi), p=1, window=h)
Ic = window_integral_measure("Ic", x(xi), p=2, window=c)   # a window of length c
Kc = window_integral_measure("Kc", x(xi), p=1, window=c)
a, b = norm_measure("a", x(t)), norm_measure("b", y(t))
A, B = a.symbol, b.symbol

POSITIVE = {"c": ("1/10", "1"), "h": ("1/2", "1")}
ACROSS_0 = {"c": ("-1/10", "1"), "h": ("1/2", "1")}     # c < 0 on [−1/10, 0): part of the box


def _ctx(box, region=None):
    values = P.resolve({}, use_defaults=True)
    intervals = {n: (R(lo), R(hi)) for n, (lo, hi) in box.items()}
    syms = {n: box_symbol(n, iv, positive=(n == "h")) for n, iv in intervals.items()}
    values = type(values)({**values, **syms})
    return Context(SYS, values, {"I": I, "K": K, "Ic": Ic, "Kc": Kc, "a": a, "b": b}, region,
                   parameter_box={syms[n]: iv for n, iv in intervals.items()})


def _at(value, region=None):
    """The context at the point c = value (no box)."""
    return Context(SYS, P.resolve({"c": value}, use_defaults=True), {"I": I, "K": K, "Ic": Ic, "Kc": Kc, "a": a,
                                                                     "b": b}, region)


def test_on_region_needs_the_bound_h_nonnegative_on_the_whole_box():
    rule = OnRegion("a", 2)  # a ≤ c on the region: a³ ≤ c·a²
    ok = rule.rewrite(5 * A**3 * B, _ctx(POSITIVE, Region({a: c})), "upper")
    assert ok.status is Status.EXACT and ok.bound == 5 * A**2 * B * box_symbol("c", (R(1, 10), 1))
    part = rule.rewrite(5 * A**3 * B, _ctx(ACROSS_0, Region({a: c})), "upper")
    assert part.status is Status.UNDECIDED and "not shown for every value" in part.detail
    assert rule.rewrite(5 * A**3 * B, _at("-1/10", Region({a: c})), "upper").status is Status.FAILED  # refuted


def test_on_region_needs_the_factor_of_its_sign_on_the_whole_box():
    rule = OnRegion("a", 2)
    assert rule.rewrite(_ctx(POSITIVE).at(c * A**3), _ctx(POSITIVE, Region({a: R(1, 4)})), "upper").status.is_proof
    part = rule.rewrite(_ctx(ACROSS_0).at(c * A**3), _ctx(ACROSS_0, Region({a: R(1, 4)})), "upper")
    assert part.status is Status.UNDECIDED and "not shown for every value" in part.detail


def test_window_holder_needs_the_window_length_and_the_monotonicity_on_the_whole_box():
    bound = lambda box: _ctx(box).at(c * K.symbol * A)  # noqa: E731  c·K·a, nondecreasing in K iff c ≥ 0
    assert WindowHolder("K", "I").rewrite(bound(POSITIVE), _ctx(POSITIVE), "upper").status is Status.EXACT
    assert not WindowHolder("K", "I").rewrite(bound(ACROSS_0), _ctx(ACROSS_0), "upper").status.is_proof
    # a window of length c: ≥ 0 on [1/10, 1], not on [−1/10, 1] (undecided there), refuted at c = −1/10
    assert WindowHolder("Kc", "Ic").rewrite(Kc.symbol * A, _ctx(POSITIVE), "upper").status is Status.EXACT
    part = WindowHolder("Kc", "Ic").rewrite(Kc.symbol * A, _ctx(ACROSS_0), "upper")
    assert part.status is Status.UNDECIDED and "window length" in part.detail
    assert WindowHolder("Kc", "Ic").rewrite(Kc.symbol * A, _at("-1/10"), "upper").status is Status.FAILED


def test_young_needs_its_parameter_positive_on_the_whole_box():
    rule = YoungEach(((A, B, 2, 2, c),))
    assert rule.rewrite(4 * A * B, _ctx(POSITIVE), "upper").status is Status.EXACT
    assert rule.rewrite(4 * A * B, _ctx(ACROSS_0), "upper").status is Status.UNDECIDED


def test_window_weight_needs_the_weight_nonnegative_on_the_whole_box():
    """∫(ξ − t + h + c)‖x‖² between c·I and (c + h)·I: the weight's ends c and c + h must be ≥ 0."""
    for box, proved in ((POSITIVE, True), (ACROSS_0, False)):
        ctx = _ctx(box)
        g = xi - t + h + c
        term = ctx.at(window_integral(norm_power(x(xi), 2), h, weight=g))
        for direction in ("lower", "upper"):
            app = WindowWeight("I", 2, weight=g).apply(term, direction, ctx)
            assert app.status.is_proof is proved, (box, direction, app.detail)
