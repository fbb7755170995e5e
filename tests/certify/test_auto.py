"""``rule=Auto()``: the rule of a term bound found by lkverify, never more than a named rule would prove."""

import pytest
import sympy

from lkverify import Equation, Functional, Parameters, System, Term, Vector, t
from lkverify.certify.steps import (Auto, CauchySchwarz, Equal, TermBound, TermwiseBound, measured, norm_measure)
from lkverify.errors import InputError
from lkverify.status import Status

P = Parameters()
x, y = Vector("x", 2), Vector("y", 2)
n, m = norm_measure("n", x(t)), norm_measure("m", y(t))
N, Mm = n.symbol, m.symbol
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
M = sympy.Matrix([[2, 1], [1, 2]])                  # eigenvalues 1 and 3


def _term(expr, bound, *, direction="<=", rule=None, measures=(n, m)):
    V = Functional([Term(expr, text="q")])
    step = TermwiseBound("step", V, SYS, "V", [TermBound("q", bound, rule or Auto())], bound, list(measures),
                         relation=direction)
    return step.check(P.resolve({})).terms[0]


QUAD = (x(t).T * M * x(t))[0]


@pytest.mark.parametrize("expr, bound, direction, found", [
    (QUAD, 3 * N**2, "<=", "Rayleigh"),                                     # λ_max = 3
    (QUAD, N**2, ">=", "Rayleigh"),                                         # λ_min = 1
    (QUAD, 4 * N**2, "<=", "Rayleigh"),                                     # a weaker bound, still implied
    (-x(t)[0] ** 2, 0, "<=", "known sign"),
    (-x(t)[0] ** 2, N**2, "<=", "known sign"),                              # 0 ≤ n²
    (x(t).dot(x(t)), N**2, "<=", "equality"),
    (((x(t) - sympy.Matrix([1, 2])).T * M * (x(t) - sympy.Matrix([1, 2])))[0], 3 * Mm**2, "<=", None),
])
def test_true_steps_are_proved_and_the_rule_named(expr, bound, direction, found):
    r = _term(expr, bound, direction=direction)
    if found is None:     # a form in x − c bounded by a measure of y: no candidate fits, and it is false
        assert r.status is Status.FAILED
        return
    assert r.status is Status.EXACT and found in r.rule and r.rule.endswith("found by Auto")
    assert r.detail.startswith("found by Auto")


def test_a_quadratic_form_around_a_centre():
    c = sympy.Matrix([1, 2])
    e = norm_measure("e", x(t) - c)
    r = _term(((x(t) - c).T * M * (x(t) - c))[0], 3 * e.symbol**2, measures=(e,))
    assert r.status is Status.EXACT and "Rayleigh" in r.rule


@pytest.mark.parametrize("expr, bound, direction", [
    (QUAD, 2 * N**2, "<="),                                    # a wrong constant: λ_max = 3
    (QUAD, (3 - sympy.Rational(1, 10**12)) * N**2, "<="),      # a tiny exact difference
    (QUAD, (1 + sympy.Rational(1, 10**9)) * N**2, ">="),       # λ_min = 1, claimed a hair more
    (x(t)[0] ** 2, 0, "<="),                                   # a flipped sign
    (QUAD + x(t)[0] ** 2, 3 * N**2, "<="),                     # a dropped term (the bound ignores x1²)
])
def test_false_steps_are_never_proved(expr, bound, direction):
    r = _term(expr, bound, direction=direction)
    assert r.status is Status.FAILED and r.witness is not None          # refuted by a rechecked witness
    assert r.rule == "Auto (no rule found)" and "Auto tried" in r.detail


def test_a_time_varying_coefficient_is_not_proved():
    r = _term((2 + sympy.sin(t)) * x(t).dot(x(t)), 2 * N**2)   # (2 + sin t)‖x‖² ≤ 2‖x‖² is false for sin t > 0
    assert not r.status.is_proof and "Auto tried" in r.detail


def test_given_rules_are_tried_after_the_automatic_ones():
    cross = 2 * x(t).dot(y(t))
    r = _term(cross, 2 * N * Mm, rule=Auto(CauchySchwarz(x(t), y(t), (measured(n), measured(m)), factor=2)))
    assert r.status is Status.EXACT and "Cauchy" in r.rule and "tried first" in r.detail
    assert not _term(cross, 2 * N * Mm).status.is_proof                # without it no automatic rule fits


def test_auto_validates_its_candidates_and_is_not_applied_alone():
    with pytest.raises(InputError, match="expected rules"):
        Auto("Rayleigh")
    with pytest.raises(InputError, match="expected rules"):
        Auto(Auto())
    with pytest.raises(InputError, match="stated bound"):
        Auto().apply(QUAD, "upper", None)
    assert isinstance(Auto(Equal(N**2)).rules[0], Equal)
