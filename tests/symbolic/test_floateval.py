"""float_values: one evaluation by walking the tree agrees with lambdify; unknown nodes and domain errors."""

import math

import pytest
import sympy

from lkverify.symbolic.floateval import NotEvaluable, float_values
from lkverify.symbolic.witness import _lambdified, _walker

x, y, z = sympy.symbols("x y z", real=True)
EXPRS = [
    x ** 2 * y - sympy.Rational(1, 3) * z + sympy.pi,
    sympy.sin(x * y) ** 3 / (1 + z ** 2) - sympy.exp(-x) * sympy.cos(2 * z),
    sympy.sqrt(1 + x ** 2) * sympy.log(2 + y ** 2) + sympy.Abs(z - 1) + sympy.atan2(y, x),
    (1 + x ** 2) ** sympy.Rational(-7, 4) + sympy.Max(x, y) - sympy.Min(y, z) + sympy.sign(z) * sympy.tanh(x),
    ((x + y) ** 2 - (x - y) ** 2) ** 2 + sympy.E ** y,     # a shared subtree, evaluated once
]


@pytest.mark.parametrize("point", [(0.3, -1.2, 2.5), (-0.7, 0.4, -1.1), (1.0, 0.0, 0.0)])
def test_the_values_are_lambdifys(point):
    env = dict(zip((x, y, z), point))
    want = sympy.lambdify((x, y, z), EXPRS, modules="math")(*point)
    got = float_values(EXPRS, env)
    assert got == pytest.approx(want, rel=1e-14, abs=1e-14)


def test_a_real_power_of_a_negative_number_raises_as_math_does():
    with pytest.raises(ValueError):
        float_values([sympy.sqrt(x)], {x: -1.0})
    with pytest.raises(ValueError):
        float_values([x ** sympy.Rational(1, 3)], {x: -8.0})
    assert float_values([x ** 3], {x: -2.0}) == [-8.0]      # integer powers are fine


def test_an_unknown_node_or_a_symbol_without_value_is_not_evaluable():
    with pytest.raises(NotEvaluable):
        float_values([sympy.Piecewise((x, x > 0), (0, True))], {x: 1.0})
    with pytest.raises(NotEvaluable):
        float_values([x + y], {x: 1.0})


def test_the_walker_falls_back_to_lambdify_for_nodes_it_does_not_know():
    e = [sympy.Piecewise((x, x > 0), (-x, True)) + sympy.sin(x)]
    assert _walker([x], e)(-2.0) == pytest.approx(_lambdified([x], e)(-2.0)) == [2 + math.sin(-2.0)]
    assert _walker([x], x ** 2, scalar=True)(3.0) == 9.0
