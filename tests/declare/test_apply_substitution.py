"""apply_substitution: the fast path (no parameter function, no derivative in the expression) changes nothing."""

import sympy

from lkverify import t
from lkverify.declare.parameters import apply_substitution

h, x = sympy.Function("h"), sympy.Function("x")
a = sympy.Symbol("a")
SUB = {h: sympy.Lambda(sympy.Symbol("u"), 1 + sympy.sin(sympy.Symbol("u"))), a: sympy.Integer(3)}


def test_a_parameter_function_is_replaced_and_its_derivative_evaluated():
    out = apply_substitution(a * h(t) + sympy.Derivative(h(t), t), SUB)
    assert sympy.simplify(out - (3 * (1 + sympy.sin(t)) + sympy.cos(t))) == 0


def test_without_parameter_functions_only_the_symbols_are_replaced():
    e = a * x(t) ** 2 + sympy.sin(a * t)
    assert apply_substitution(e, SUB) == 3 * x(t) ** 2 + sympy.sin(3 * t)


def test_a_derivative_of_an_expression_is_still_evaluated_without_parameter_functions():
    out = apply_substitution(sympy.Derivative(t ** 2, t) + sympy.Derivative(x(t), t), SUB)
    assert out == 2 * t + sympy.Derivative(x(t), t)      # the state's derivative stays


def test_the_fast_path_agrees_with_the_full_rewrite():
    s, y = sympy.symbols("s y")
    exprs = [a * x(t - a) * sympy.exp(-t), h(t - 1) * x(t), sympy.Integral(h(s), (s, 0, t)),
             sympy.Subs(sympy.Derivative(h(y), y), y, t), sympy.Integer(7)]
    undef = sympy.core.function.AppliedUndef
    for e in exprs:
        slow = e.replace(lambda q: isinstance(q, sympy.Function) and q.func in {h},
                         lambda q: SUB[h](*q.args))
        slow = slow.replace(lambda q: isinstance(q, (sympy.Derivative, sympy.Subs)) and not q.atoms(undef),
                            lambda q: q.doit()).xreplace({a: 3})
        assert apply_substitution(e, SUB) == slow


def test_a_column_is_substituted_entry_by_entry_on_both_paths():
    col = sympy.Matrix([a * x(t), h(t) * x(t - 1)])
    assert apply_substitution(col, SUB) == sympy.Matrix([3 * x(t), (1 + sympy.sin(t)) * x(t - 1)])
    assert apply_substitution(sympy.Matrix([a * x(t)]), SUB) == sympy.Matrix([3 * x(t)])
