"""derivative_along against a slow reference path: d/dt of V along a closed-form solution.

For ẏ = −a y (solution y(θ) = y0·e^{−aθ}) and the rotation ẏ = (y₂, −y₁) (solution
(cos θ, −sin θ)), every functional below is evaluated on the solution and
differentiated directly by SymPy; V̇ from :func:`lkverify.derivative_along`, evaluated
on the same solution, must agree exactly.  The functionals use values at t, t − τ,
t − h(t), t/2, neutral combinations and integrals with time-varying limits and
t-dependent weights: the chain rule at every argument and the Leibniz rule.
"""

import pytest
import sympy
from sympy.core.function import AppliedUndef

from lkverify import Equation, Functional, Parameters, System, Term, Vector, derivative_along, t, xi

P = Parameters()
a = P.scalar("a", positive=True)
c = P.scalar("c")
tau = P.delay("tau")
y0 = sympy.Symbol("y0", positive=True)
H = sympy.Rational(1, 2) + sympy.sin(t) / 4  # a time-varying delay, written out

y = Vector("y", 1)
decay = System([Equation(y, [Term(-a * y(t)[0])])], parameters=P)
z = Vector("z", 2)
rotation = System([Equation(z, [Term(sympy.Matrix([z(t)[1], -z(t)[0]]))])], parameters=P)


def _solution(system):
    if system is decay:
        return {y.functions[0]: sympy.Lambda(xi, y0 * sympy.exp(-a * xi))}
    return {z.functions[0]: sympy.Lambda(xi, sympy.cos(xi)), z.functions[1]: sympy.Lambda(xi, -sympy.sin(xi))}


def _on(expr, sol):
    return expr.replace(lambda e: isinstance(e, AppliedUndef) and e.func in sol, lambda e: sol[e.func](*e.args))


Y = lambda arg: y(arg)[0]  # noqa: E731
Z1 = lambda arg: z(arg)[0]  # noqa: E731
Z2 = lambda arg: z(arg)[1]  # noqa: E731

CASES = [
    (decay, Y(t) ** 2),
    (decay, Y(t - tau) * Y(t)),
    (decay, Y(t - H) ** 2),
    (decay, Y(t / 2) ** 3),
    (decay, (Y(t) - c * Y(t - H)) ** 2),
    (decay, sympy.Integral(Y(xi) ** 2, (xi, t - H, t))),
    (decay, sympy.Integral((xi - t + tau) * Y(xi) ** 2, (xi, t - tau, t))),
    (decay, Y(t) * sympy.Integral(Y(xi), (xi, t / 2, t))),
    (decay, sympy.Integral(sympy.exp(xi - t) * Y(xi - tau) ** 2, (xi, t - H, t))),
    (rotation, Z1(t) ** 2 + Z2(t) ** 2),
    (rotation, Z1(t - H) * Z2(t)),
    (rotation, Z1(t / 3) ** 2 * Z2(t - tau)),
    (rotation, (Z1(t) - c * Z1(t - H)) ** 2 + Z2(t - H / 2) ** 2),
    (rotation, sympy.Integral(Z1(xi) ** 2 + Z2(xi) * Z1(xi), (xi, t - H, t))),
]


@pytest.mark.parametrize("system, expr", CASES, ids=[str(i) for i in range(len(CASES))])
def test_derivative_along_matches_direct_differentiation(system, expr):
    sol = _solution(system)
    V = Functional([Term(expr)])
    fix = {a: sympy.Rational(3, 2)} if expr.has(sympy.exp) else {}  # no Piecewise at a = 1/2 from integrate
    derived = _on(derivative_along(V, system).expr, sol).xreplace(fix).doit()
    direct = sympy.diff(_on(expr, sol).xreplace(fix).doit(), t)
    assert sympy.simplify(sympy.expand(derived - direct)) == 0


def test_the_reference_path_sees_a_missing_inner_derivative():
    # the mutation the old code made: ẏ(t − h(t)) without (1 − ḣ)
    sol = _solution(decay)
    wrong = -2 * a * Y(t - H) ** 2
    direct = sympy.diff(_on(Y(t - H) ** 2, sol).doit(), t)
    assert sympy.simplify(_on(wrong, sol).doit() - direct) != 0
