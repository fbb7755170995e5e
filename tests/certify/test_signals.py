"""The signal-argument links (lkverify.certify.steps.signals): each side condition violated alone is
refuted or left undecided, never proved; true claims written differently are proved."""

import dataclasses

import pytest
import sympy

from lkverify import Equation, Parameters, Status, System, Term, Vector, t
from lkverify.certify.steps.limits import BoundedSignal, Comparison, FiniteLimit, Follows, LinearLimit, negative_on
from lkverify.certify.steps.signals import (Barbalat, BoundedStates, Conserved, Dissipation, Facts, LevelSet,
                                            SquareIntegrable, bounded_in_t)
from lkverify.errors import UnsupportedInput
from lkverify.symbolic.polynomial import time_derivative

X, Y = Vector("x", 1), Vector("y", 1)
x, y = X(t)[0], Y(t)[0]
z = sympy.Function("z", real=True)(t)
P = Parameters()
V = (x ** 2 + y ** 2) / 2
q = sympy.Matrix([x])


def loop(fx=-x + y * z, fy=-x * z):
    return System([Equation(X, [Term(fx)]), Equation(Y, [Term(fy)])], parameters=P)


def run(links, system=None, reference=sympy.cos(t)):
    facts = Facts(system or loop(), {}, {"z": reference})
    return [link.decide(facts) for link in links], facts


def chain(**replace):
    links = {"diss": Dissipation(V, q, sympy.eye(1)),
             "level": LevelSet(V, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), sympy.eye(2)),
             "states": BoundedStates(), "l2": SquareIntegrable("x", q, sympy.eye(1), storage=V),
             "barbalat": Barbalat("x")}
    links.update(replace)
    return [v for v in links.values() if v is not None]


def statuses(results):
    return [r.status for r in results]


def test_the_toy_loop_is_established():
    res, facts = run(chain())
    assert statuses(res) == [Status.EXACT] * 5
    assert facts.converges["x"][0] is Status.EXACT


def test_dissipation_refutes_a_dropped_term_and_a_non_psd_S():
    res, _ = run(chain(), system=loop(fx=-x + y * z + x * y))       # an extra term in ẋ: V̇ ≠ −x²
    assert res[0].status is Status.FAILED
    # the identity holds with S = −1 along ẋ = x (V̇ = +x²), but S ⪰ 0 fails alone
    up = System([Equation(X, [Term(x)]), Equation(Y, [Term(0)])], parameters=P)
    res, _ = run([Dissipation(V, q, -sympy.eye(1))], system=up)
    assert res[0].status is Status.FAILED and "S ⪰ 0: failed" in res[0].detail


def test_level_set_each_side_condition_alone():
    indefinite = (x ** 2 - y ** 2) / 2
    sysd = System([Equation(X, [Term(-x)]), Equation(Y, [Term(y)])], parameters=P)   # d/dt of x² − y²: −2x² − 2y²
    res, _ = run([Dissipation(indefinite, sympy.Matrix([x, y]), sympy.eye(2)),
                  LevelSet(indefinite, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), sympy.diag(1, -1))],
                 system=sysd)
    assert res[0].status is Status.EXACT and res[1].status is Status.FAILED          # Q not ≻ 0 alone
    res, _ = run(chain(level=LevelSet(V, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), 2 * sympy.eye(2))))
    assert res[1].status is Status.FAILED                                             # V ≠ ½zᵀQz alone
    res, _ = run(chain(diss=None))
    assert res[0].status is Status.UNDECIDED and "nonincreasing" in res[0].detail     # no dissipation link


def test_conserved_norm():
    rot = System([Equation(X, [Term(y)]), Equation(Y, [Term(-x)])], parameters=P)
    xy = sympy.Matrix([x, y])
    assert run([Conserved("xy", xy)], system=rot)[0][0].status is Status.EXACT
    stretched = System([Equation(X, [Term(y)]), Equation(Y, [Term(-2 * x)])], parameters=P)
    assert run([Conserved("xy", xy)], system=stretched)[0][0].status is Status.FAILED


def test_bounded_states_needs_every_state_and_bounded_references():
    only_x = LevelSet((x ** 2) / 2, (("x", sympy.Matrix([x])),), sympy.eye(1))
    sysx = loop(fx=-x, fy=-x * z)
    res, _ = run([Dissipation(x ** 2 / 2, q, sympy.eye(1)), only_x, BoundedStates()], system=sysx)
    assert res[2].status is Status.UNDECIDED and "y" in res[2].detail                 # y is not bounded by anything
    # the state x is bounded through a signal that is an affine function of it and the reference
    shifted = LevelSet(V, (("w", sympy.Matrix([x - z])), ("y", sympy.Matrix([y]))), sympy.eye(2))
    facts = Facts(loop(), {}, {"z": sympy.cos(t)})
    facts.nonincreasing[facts.plain(V)] = Status.EXACT
    shifted_v = (x - z) ** 2 / 2 + y ** 2 / 2
    shifted = dataclasses.replace(shifted, V=shifted_v)
    facts.nonincreasing[facts.plain(shifted_v)] = Status.EXACT
    assert shifted.decide(facts).status is Status.EXACT
    assert BoundedStates().decide(facts).status is Status.EXACT
    facts.references["z"] = t                                                         # an unbounded reference
    assert BoundedStates().decide(facts).status is Status.FAILED


def test_square_integrable_side_conditions():
    assert run(chain(l2=SquareIntegrable("x", q, -sympy.eye(1), storage=-V)))[0][3].status is Status.FAILED
    tiny = sympy.Matrix([[1 + sympy.Rational(1, 10 ** 30)]])                      # a tiny exact difference
    assert run(chain(l2=SquareIntegrable("x", q, tiny, storage=V)))[0][3].status is Status.FAILED
    # dominated by a signal nobody proved square integrable
    dom = SquareIntegrable("x", q, sympy.eye(1), dominated=(("w", q, sympy.eye(1)),))    # x² = x², w = x not in L2
    res, _ = run(chain(l2=dom))
    assert res[3].status is Status.UNDECIDED and "w ∈ L2" in res[3].detail


def test_barbalat_needs_l2_and_a_bounded_rate():
    res, _ = run(chain(l2=None))
    assert res[-1].status is Status.UNDECIDED
    res, _ = run(chain(), reference=t * sympy.sin(t))                                 # a time-varying argument
    assert res[2].status is Status.EXACT and res[-1].status is Status.UNDECIDED       # ẋ contains z = t·sin t
    res, _ = run(chain(), reference=t)
    assert res[-1].status is Status.FAILED                                            # ẋ contains z = t


def test_linear_limit_and_bounded_signal():
    extra = [LinearLimit("2x", 2 * q, {"x": 2}), LinearLimit("2x?", 2 * q, {"x": 3}),
             BoundedSignal("xy", sympy.Matrix([x * y * z])), BoundedSignal("1/x", sympy.Matrix([1 / (1 + x ** 2)]))]
    res, _ = run(chain() + extra)
    assert statuses(res[-4:]) == [Status.EXACT, Status.FAILED, Status.EXACT, Status.UNDECIDED]
    res, _ = run([LinearLimit("w", q, {"nothing": 1})])
    assert res[0].status is Status.UNDECIDED


def test_finite_limit():
    rot = System([Equation(X, [Term(-y * z)]), Equation(Y, [Term(x * z)])], parameters=P)   # on the circle
    facts = Facts(rot, {}, {"z": sympy.cos(t)})
    facts.states_bounded = Status.EXACT
    xs = facts.plain(sympy.Matrix([x, y]))
    facts.converges["g"] = (Status.EXACT, sympy.Matrix([xs[0] * xs[1]]))
    circle = [x ** 2 + y ** 2 - 1]
    res = FiniteLimit("(x, y)", "g", sympy.Matrix([x, y]), circle).decide(facts)
    assert res.status is Status.EXACT and len(res.value["points"]) == 4
    facts.converges["g"] = (Status.EXACT, sympy.Matrix([xs[0] ** 2 + xs[1] ** 2 - 1]))   # the whole circle
    assert FiniteLimit("(x, y)", "g", sympy.Matrix([x, y]), circle).decide(facts).status is Status.UNDECIDED
    facts.converges["g"] = (Status.EXACT, sympy.Matrix([xs[0] * xs[1]]))
    ellipse = [x ** 2 + 2 * y ** 2 - 1]                                                  # not invariant
    res = FiniteLimit("(x, y)", "g", sympy.Matrix([x, y]), ellipse).decide(facts)
    assert res.status is Status.UNDECIDED and "not shown invariant" in res.detail


def test_negative_on():
    r = sympy.Symbol("r", nonnegative=True)
    assert negative_on(-r + r ** 2, r, 0, 1)[0] is Status.EXACT
    assert negative_on(-r + (1 + sympy.Rational(1, 10 ** 30)) * r ** 2, r, 0, 1)[0] is Status.FAILED  # root < 1
    assert negative_on(sympy.Min(-r, -r + r ** 3), r, 0, 2)[0] is Status.EXACT       # written with Min
    assert negative_on(-r + 3 * sympy.Max(0, r - sympy.Rational(1, 4)), r, 0, sympy.Rational(3, 8))[0] is Status.EXACT
    assert negative_on(sympy.sqrt(r) - 1, r, 0, 1)[0] is Status.UNDECIDED


def test_comparison_each_side_condition_alone():
    r = sympy.Symbol("r", nonnegative=True)
    phi = -r + 3 * sympy.Max(0, r - sympy.Rational(1, 4))
    ok = (("D⁺r ≤ φ(r)", Status.EXACT),)
    assert Comparison(phi, r, sympy.Rational(3, 8), ok).decide().status is Status.EXACT
    assert Comparison(phi, r, sympy.Rational(1, 2), ok).decide().status is Status.FAILED          # ρ too large
    assert Comparison(phi + 1, r, sympy.Rational(1, 10), ok).decide().status is Status.FAILED     # φ(0) ≠ 0
    assert Comparison(phi, r, sympy.Rational(3, 8), (("D⁺r ≤ φ(r)", Status.FAILED),)).decide().status \
        is Status.FAILED
    assert Comparison(phi, r, sympy.Rational(3, 8)).decide().status is Status.UNDECIDED          # nothing proves it


def test_follows_takes_the_weakest():
    assert Follows("a", (("p", Status.EXACT), ("q", Status.CERTIFIED)), "").decide().status is Status.CERTIFIED
    assert Follows("a", (), "").decide().status is Status.UNDECIDED


def test_bounded_in_t():
    assert bounded_in_t(sympy.sin(t ** 2) * sympy.cos(t) + sympy.exp(-2 * t + 1))[0] is Status.EXACT
    assert bounded_in_t(t ** 2 - 1)[0] is Status.FAILED
    assert bounded_in_t(sympy.exp(t))[0] is Status.UNDECIDED
    assert bounded_in_t(sympy.Integer(3))[0] is Status.EXACT
    assert bounded_in_t(sympy.sin(sympy.I * t))[0] is not Status.EXACT             # i·sinh t: unbounded
    assert bounded_in_t(t + sympy.sin(t))[0] is not Status.EXACT


def test_time_derivative_refuses_the_rate_of_a_coefficient():
    with pytest.raises(UnsupportedInput, match="rate of a coefficient"):
        time_derivative(x * z.diff(t), loop())


def _lasalle(fx, fy, q, S):
    from lkverify.certify.steps.limits import LaSalle

    sys_ = System([Equation(X, [Term(fx)]), Equation(Y, [Term(fy)])], parameters=P)
    links = [Dissipation(V, q, S), LevelSet(V, (("x", sympy.Matrix([x])), ("y", sympy.Matrix([y]))), sympy.eye(2)),
             BoundedStates(), LaSalle()]
    return run(links, system=sys_)[0]


def test_lasalle_each_side_condition_alone():
    res = _lasalle(y, -x - y, sympy.Matrix([y]), sympy.eye(1))                # damped: the origin
    assert res[-1].status is Status.EXACT and res[-1].value["points"] == [["0", "0"]]
    res = _lasalle(y, -x - y ** 3, sympy.Matrix([y ** 2]), sympy.eye(1))      # V̇ = −y⁴, written differently
    assert res[-1].status is Status.EXACT
    res = _lasalle(y, -x, sympy.Matrix([y]), sympy.zeros(1))                  # V̇ = 0: the invariant circles
    assert res[-1].status is Status.UNDECIDED and "not a finite set" in res[-1].detail
    res = _lasalle(y, -x - y * z, sympy.Matrix([y]), sympy.eye(1))            # a time-varying argument
    assert res[0].status is Status.FAILED and res[-1].status is Status.UNDECIDED
    res = _lasalle(y, -x - y, sympy.Matrix([y]), 2 * sympy.eye(1))            # a wrong V̇: dissipation refuted
    assert res[0].status is Status.FAILED and res[-1].status is Status.FAILED
    from lkverify.certify.steps.limits import LaSalle

    assert LaSalle().decide(Facts(loop(), {}, {})).status is Status.UNDECIDED   # nothing established before


def test_a_signal_theorem_leaves_an_untreatable_link_undecided():
    from lkverify import Result, SignalTheorem

    def argument(values):
        root = sympy.sqrt(1 + x ** 2)                                       # not a polynomial
        return [Dissipation(root, q, sympy.eye(1)), Barbalat("x")], {}

    ok = lambda v: [Result("hypothesis", "none", Status.EXACT, None, "")]   # noqa: E731
    rep = SignalTheorem("demo", system=loop(), hypotheses=[ok], argument=argument).run()
    assert rep.exit_code == 1 and rep.verdict.startswith("undecided")


def test_chetaev_each_condition_alone():
    from lkverify.certify.steps.limits import Chetaev

    a, b, e = sympy.symbols("a b epsilon", real=True)
    ok = ("V̇ < 0 where V < 0", Status.EXACT)
    assert Chetaev(a**2 - b**2, {a: 0, b: 0}, {b: e}, e, ok).decide().status is Status.EXACT
    assert Chetaev(a**2 - b**2 + 1, {a: 0, b: 0}, {b: e}, e, ok).decide().status is Status.FAILED   # V(x*) ≠ 0
    assert Chetaev(a**2 - b**2, {a: 0, b: 0}, {a: e}, e, ok).decide().status is Status.FAILED      # V > 0 there
    assert Chetaev(a**2 - b**2, {a: 0, b: 0}, {b: 1 + e}, e, ok).decide().status is Status.UNDECIDED  # not at x*
    bad_rate = ("V̇ < 0 where V < 0", Status.FAILED)
    assert Chetaev(a**2 - b**2, {a: 0, b: 0}, {b: e}, e, bad_rate).decide().status is Status.FAILED
    # V = −ε²/(1 − 2ε) along the curve: negative only for ε < 1/2, the denominator vanishes inside (0, 1)
    assert Chetaev(-b**2 / (1 - 2 * b), {a: 0, b: 0}, {b: e}, e, ok).decide().status is not Status.EXACT


def test_a_signal_theorem_names_its_additional_hypotheses_only_when_established():
    from lkverify import Result, SignalTheorem
    from lkverify.certify.steps import Decided

    def argument(status):
        def build(values):
            extra = Decided("extra", lambda facts: Result("hypothesis", "k > 1 (derived)", status, None, "k = 2"))
            V = (x ** 2 + y ** 2) / 2
            return [extra, Dissipation(V, q, sympy.eye(1)),
                    LevelSet(V, (("x", q), ("y", sympy.Matrix([y]))), sympy.eye(2)), BoundedStates(),
                    SquareIntegrable("x", q, sympy.eye(1), storage=V), Barbalat("x")], {"z": sympy.cos(t)}
        return build

    ok = lambda v: [Result("hypothesis", "none", Status.EXACT, None, "")]   # noqa: E731
    rep = SignalTheorem("demo", system=loop(), hypotheses=[ok], argument=argument(Status.EXACT)).run()
    assert rep.verdict.startswith("established") and "under the additional hypotheses" in rep.verdict
    assert "extra (k = 2)" in rep.verdict
    rep = SignalTheorem("demo", system=loop(), hypotheses=[ok], argument=argument(Status.FAILED)).run()
    assert rep.verdict.startswith("not established: extra refuted") and "under the additional" not in rep.verdict
    # an ordinary link (kind "bound") is not an additional hypothesis
    plain = SignalTheorem("demo", system=loop(), hypotheses=[ok],
                          argument=lambda v: ([Dissipation(x ** 2 / 2, q, sympy.eye(1))], {})).run()
    assert "under the additional" not in plain.verdict


def test_follows_rests_on_the_status_an_earlier_link_got():
    from lkverify.certify.steps.signals import decide_all
    links = [Dissipation(V, q, sympy.eye(1)),
             Follows("V bounded", (("V̇ ≤ 0", lambda facts: facts.link_status("V̇ = −qᵀSq ≤ 0")),), "V(t) ≤ V(0)")]
    res = decide_all(links, Facts(loop(), {}, {"z": sympy.cos(t)}))
    assert [r.status for r in res] == [Status.EXACT, Status.EXACT]
    wrong = [Dissipation(V, q, 2 * sympy.eye(1)), links[1]]                # the earlier link refuted: so is this one
    assert decide_all(wrong, Facts(loop(), {}, {"z": sympy.cos(t)}))[1].status is Status.FAILED
    # a name no earlier link had: undecided
    alone = Follows("V bounded", (("V̇ ≤ 0", lambda facts: facts.link_status("no such link")),), "V(t) ≤ V(0)")
    assert alone.decide(Facts(loop(), {}, {})).status is Status.UNDECIDED
