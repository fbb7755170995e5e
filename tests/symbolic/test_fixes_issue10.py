"""Regressions found while writing the API examples (issue 10): each case where the code must fail, and must not."""

import numpy as np
import pytest
import sympy

from lkverify import Functional, InputError, Parameters, Term, UnitVector, Vector, check_identity, t
from lkverify.certify.hypotheses import MatrixHypothesis
from lkverify.status import Status
from lkverify.symbolic.witness import evaluate, make_witness
from lkverify.errors import UnsupportedInput


def test_identity_with_derivatives_of_states():
    x = Vector("x", 1)
    X = x(t)[0]
    d = sympy.Derivative
    true = check_identity([Term(d(X**2, t), text="d/dt x²")], [Term(2 * X * d(X, t), text="2xẋ")], states=[x])
    assert true.status is Status.EXACT
    wrong = check_identity([Term(d(X**2, t), text="d/dt x²")], [Term(3 * X * d(X, t), text="3xẋ")], states=[x])
    assert wrong.status is Status.FAILED
    tiny = check_identity([Term(d(X**2, t))], [Term((2 + sympy.Rational(1, 10**30)) * X * d(X, t))], states=[x])
    assert tiny.status is Status.FAILED


def test_derivative_of_a_state_is_evaluated_from_its_history():
    x = Vector("x", 1)
    w = make_witness([x], Parameters(), rng=np.random.default_rng(1))
    h = w.histories[x.functions[0]]
    expected = float(sympy.diff(h.expr, h.variables[0]).subs(h.variables[0], w.t_eval))
    assert evaluate(sympy.Derivative(x(t)[0], t), w) == pytest.approx(expected, rel=1e-12)


def test_unit_vector_constraint_is_taken_from_the_states():
    s = UnitVector("s")
    lhs = [Term(s(t)[0] ** 2)]
    assert check_identity(lhs, [Term(1 - s(t)[1] ** 2 - s(t)[2] ** 2)], states=[s]).status is Status.EXACT
    # a dropped term is still refuted
    assert check_identity(lhs, [Term(1 - s(t)[1] ** 2)], states=[s]).status is Status.FAILED


def test_states_missing_from_an_identity_are_a_clear_error():
    s = UnitVector("s")
    with pytest.raises(UnsupportedInput, match="no history for the functions"):
        check_identity([Term(s(t)[0])], [Term(s(t)[0])], constraints=lambda times: [])


def test_functional_validation_says_what_is_wrong():
    with pytest.raises(InputError, match="at least one term"):
        Functional([])
    with pytest.raises(InputError, match="expected Term objects"):
        Functional([sympy.Integer(1)])


def test_matrix_hypothesis_with_plain_numbers_and_its_name():
    b = sympy.Symbol("b", real=True)
    h = MatrixHypothesis("M ≻ 0", sympy.Matrix([[2, b], [b, 2]]))
    ok = h.evaluate({b: 1})  # a Python int, not a SymPy Integer
    assert ok.status is Status.EXACT and "≻ 0 ≻ 0" not in ok.detail
    assert h.evaluate({b: 2}).status is Status.FAILED  # singular: not positive definite
