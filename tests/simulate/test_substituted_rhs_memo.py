"""The substituted right-hand side is kept per process: the same values give the same rhs, others their own."""

import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t
from lkverify.simulate import compile as C


def _system():
    P = Parameters()
    a = P.scalar("a", default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    return System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P), a, tau, x


def test_the_same_values_reuse_the_rhs_and_other_values_do_not():
    sys_, a, tau, x = _system()
    first = C._substituted_rhs(sys_, {a: sympy.Integer(2), tau: sympy.Integer(1)}, "s")
    again = C._substituted_rhs(sys_, {a: sympy.Integer(2), tau: sympy.Integer(1)}, "s")
    other = C._substituted_rhs(sys_, {a: sympy.Integer(3), tau: sympy.Integer(1)}, "s")
    assert first == again == [-2 * x.functions[0](t - 1)]
    assert other == [-3 * x.functions[0](t - 1)]
    again.append("changed")                       # a caller's list is its own
    assert C._substituted_rhs(sys_, {a: sympy.Integer(2), tau: sympy.Integer(1)}, "s") == first


def test_a_float_value_or_another_system_is_never_served_from_the_memo():
    sys_, a, tau, x = _system()
    assert C._memo_key(sys_, {a: sympy.Float(2.0), tau: sympy.Integer(1)}, ()) is None   # 2.0 == 2 in SymPy
    assert C._memo_key(sys_, {a: sympy.Matrix([1])}, ()) is None                            # unhashable
    C._substituted_rhs(sys_, {a: sympy.Integer(2), tau: sympy.Integer(1)}, "s")
    sys2, a2, tau2, x2 = _system()
    assert C._substituted_rhs(sys2, {a2: sympy.Integer(2), tau2: sympy.Integer(1)}, "s") == \
        [-2 * x2.functions[0](t - 1)]
