"""The polynomial fast path of the identity engine (lkverify.symbolic.polynomial, issue 24 item 3).

Mutated claims must be refuted (flipped sign, wrong constant, dropped term, a tiny exact
difference), true claims written differently must be proved, floats and delayed arguments never
give ``exact``; ``check_identity`` takes the fast path without losing a refutation.
"""

import pytest
import sympy

from lkverify import Term, UnitVector, Vector, t
from lkverify.errors import UnsupportedInput
from lkverify.status import Status
from lkverify.symbolic.identity import check_identity
from lkverify.symbolic.polynomial import (
    compare_polynomials, plain, time_derivative, witness_point, zero_difference)

x, y, k = sympy.symbols("x y k", real=True)
TRUE = (x + y) ** 3 - k * x * y
EXPANDED = [("x³", x**3), ("3x²y", 3 * x**2 * y), ("3xy²", 3 * x * y**2), ("y³", y**3), ("−kxy", -k * x * y)]


def test_true_identity_written_differently_is_exact():
    r = compare_polynomials("cube", [("(x+y)³ − kxy", TRUE)], EXPANDED)
    assert r.status is Status.EXACT


@pytest.mark.parametrize("mutation, printed", [
    ("flipped sign", [*EXPANDED[:4], ("+kxy", k * x * y)]),
    ("wrong constant", [EXPANDED[0], ("4x²y", 4 * x**2 * y), *EXPANDED[2:]]),
    ("dropped term", EXPANDED[1:]),
    ("tiny exact difference", [*EXPANDED, ("10⁻³⁰", sympy.Rational(1, 10**30))]),
])
def test_mutated_claim_is_refuted_at_an_exact_witness(mutation, printed):
    r = compare_polynomials(mutation, printed, [("(x+y)³ − kxy", TRUE)])
    assert r.status is Status.FAILED, mutation
    assert sympy.Rational(r.value["witness_value"]) != 0
    # the witness is exact: the residue evaluated there is the reported value
    point = {sympy.Symbol(s, real=True): sympy.Rational(v) for s, v in r.value["witness"].items()}
    residue = sum(e for _, e in printed) - TRUE
    assert sympy.expand(residue).xreplace(point) == sympy.Rational(r.value["witness_value"])


def test_float_values_are_never_exact():
    r = compare_polynomials("float", [("0.5x", 0.5 * x)], [("x/2", x / 2)])
    assert r.status is Status.UNDECIDED
    assert not zero_difference([0.5 * x], [x / 2])


def test_delayed_argument_is_refused_not_identified_with_the_current_value():
    f = sympy.Function("f", real=True)
    with pytest.raises(UnsupportedInput, match="functions of t only"):
        plain(f(t) - f(t - 1))
    with pytest.raises(UnsupportedInput, match="d/dt of a function of t"):
        plain(sympy.Derivative(f(t - 1), t))


def test_time_derivative_includes_time_varying_coefficients():
    from lkverify import Equation, Parameters, System
    xv = Vector("x", 1)
    w = sympy.Function("w", real=True)
    sys = System([Equation(xv, [Term(-xv(t)[0])])], parameters=Parameters())
    x1, w_, wdot = sympy.symbols("x_1 w w_dot", real=True)
    assert sympy.expand(time_derivative(w(t) * xv(t)[0] ** 2, sys) - (-2 * w_ * x1**2 + wdot * x1**2)) == 0


def test_witness_point_lies_on_the_triad_manifold():
    syms = sympy.symbols("s1_x s1_y s1_z s2_x s2_y s2_z", real=True)
    p = witness_point(sum(syms))
    s1, s2 = sympy.Matrix(syms[:3]).xreplace(p), sympy.Matrix(syms[3:]).xreplace(p)
    assert (s1.dot(s1), s2.dot(s2), s1.dot(s2)) == (1, 1, 0)


def test_zero_difference_is_conservative_on_non_polynomials():
    assert zero_difference([(x - y) * (x + y)], [x**2, -y**2])
    assert not zero_difference([sympy.sqrt(x)], [sympy.sqrt(x)])
    assert not zero_difference([x * y], [x * y + sympy.Rational(1, 10**30)])


# -- check_identity takes the fast path -----------------------------------------------------------------

def _unit(s):
    return lambda times: [p for u in times for p in s.constraint_polynomials(u)]


def test_check_identity_fast_path_proves_without_the_constraints():
    s = UnitVector("s")
    lhs = [Term((s(t)[0] + s(t)[1]) ** 2, text="(s_x + s_y)²")]
    rhs = [Term(s(t)[0] ** 2, text="s_x²"), Term(2 * s(t)[0] * s(t)[1], text="2 s_x s_y"),
           Term(s(t)[1] ** 2, text="s_y²")]
    r = check_identity(lhs, rhs, states=[s], constraints=_unit(s))
    assert r.status is Status.EXACT
    assert "no constraint needed" in r.as_text()


def test_check_identity_still_uses_the_constraints_when_needed():
    s = UnitVector("s")
    lhs = [Term(s(t)[0] ** 2, text="s_x²")]
    rhs = [Term(1 - s(t)[1] ** 2 - s(t)[2] ** 2, text="1 − s_y² − s_z²")]
    r = check_identity(lhs, rhs, states=[s], constraints=_unit(s))
    assert r.status is Status.EXACT
    assert "modulo the constraints" in r.as_text()


@pytest.mark.parametrize("wrong", [
    Term(-2 * Vector("x", 1)(t)[0] * Vector("x", 1)(t - 1)[0], text="sign flipped"),
    Term(3 * Vector("x", 1)(t)[0] * Vector("x", 1)(t - 1)[0], text="wrong constant"),
    Term(2 * Vector("x", 1)(t)[0] ** 2, text="time-varying argument replaced by t"),
])
def test_check_identity_refutes_mutations_with_delays(wrong):
    xv = Vector("x", 1)
    a, b = xv(t)[0], xv(t - 1)[0]
    lhs = [Term((a + b) ** 2, text="(x + x_τ)²")]
    rhs = [Term(a**2, text="x²"), wrong, Term(b**2, text="x_τ²")]
    r = check_identity(lhs, rhs, states=[xv])
    assert r.status is Status.FAILED, wrong.text


def test_check_identity_tiny_exact_difference_is_refuted():
    s = UnitVector("s")
    lhs = [Term(s(t)[0] ** 2 + sympy.Rational(1, 10**30), text="s_x² + 10⁻³⁰")]
    rhs = [Term(1 - s(t)[1] ** 2 - s(t)[2] ** 2, text="1 − s_y² − s_z²")]
    r = check_identity(lhs, rhs, states=[s], constraints=_unit(s))
    assert r.status is not Status.EXACT
