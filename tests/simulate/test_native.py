"""The native code printer (lkverify.simulate.native) against SymPy's own numbers, and its refusals."""

import ctypes
import math

import numpy as np
import pytest
import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t
from lkverify.simulate import simulate
from lkverify.simulate.family import compile_family
from lkverify.simulate.native import NotPrintable, load, native_source

y0, y1, z0, p0 = sympy.symbols("y_0 y_1 Z_0_0 p_0", real=True)
ARGS = {y0: ("y", 0), y1: ("y", 1), z0: ("Z", 0), p0: ("p", 0)}


def call(exprs, y=(0.7, -1.3), z=(0.4,), p=(2.5,), time=0.25):
    fn = load(native_source({"f": exprs}, ARGS, time=t))["f"]
    cy, cz, cp = ((ctypes.c_double * len(v))(*v) for v in (y, z, p))
    out = (ctypes.c_double * len(exprs))()
    fn.ctypes(time, cy, cz, cp, out)
    return list(out)


def reference(e, y=(0.7, -1.3), z=(0.4,), p=(2.5,), time=0.25):
    return float(e.subs({y0: y[0], y1: y[1], z0: z[0], p0: p[0], t: time}).evalf(30))


EXPRESSIONS = [
    y0 * y1 + p0 * z0 - 3, y0 ** 7, y1 ** -3, sympy.sqrt(p0), 1 / sympy.sqrt(p0), p0 ** sympy.Rational(3, 10),
    y0 ** y0, sympy.exp(y1) * sympy.log(p0), sympy.sin(y0) + sympy.cos(y1) + sympy.tan(z0), sympy.atan(y1),
    sympy.asin(z0) + sympy.acos(z0), sympy.sinh(y1) + sympy.cosh(y0) + sympy.tanh(p0), sympy.Abs(y1),
    sympy.sign(y1) + sympy.sign(y0) + sympy.sign(0 * y0), sympy.Max(y0, y1, z0), sympy.Min(y0, y1, z0),
    sympy.floor(y1 * 3) + sympy.ceiling(y0 * 3), sympy.atan2(y1, y0), sympy.pi * t + sympy.E,
    sympy.Piecewise((y0, y1 > 0), (y1 ** 2, sympy.And(y0 > 0, z0 <= 1)), (0, True)),
    -y0 / 20 + sympy.Rational(3, 5) * y1 * z0 - sympy.Rational(1, 7) * p0,
    (y0 + y1) ** 2 * sympy.exp(-(y0 + y1) ** 2) + (y0 + y1) ** 2,       # a common subexpression
]


@pytest.mark.parametrize("expr", EXPRESSIONS, ids=[str(i) for i in range(len(EXPRESSIONS))])
def test_every_printed_node_agrees_with_sympy(expr):
    (got,) = call([expr])
    assert math.isclose(got, reference(expr), rel_tol=1e-14, abs_tol=1e-15)


def test_several_outputs_and_the_arguments_read_where_declared():
    got = call([y0, y1, z0, p0, t], y=(1.0, 2.0), z=(3.0,), p=(4.0,), time=5.0)
    assert got == [1.0, 2.0, 3.0, 4.0, 5.0]


def test_ieee_semantics_not_exceptions():
    inf, nan = call([1 / y0, p0 ** sympy.Rational(1, 3)], y=(0.0, 1.0), p=(-8.0,))
    assert inf == math.inf and math.isnan(nan)           # Python would raise; numba's error_model="numpy" agrees


def test_refusals_name_the_node():
    with pytest.raises(NotPrintable, match="erf"):
        native_source({"f": [sympy.erf(y0)]}, ARGS)
    with pytest.raises(NotPrintable, match="symbol q is not an argument"):
        native_source({"f": [sympy.Symbol("q") + y0]}, ARGS)


def test_a_family_without_native_form_falls_back_to_numba():
    """erf has no native form here: the family compiles its Python source with numba and agrees with SciPy."""
    P = Parameters()
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-sympy.erf(x(t - 1)[0]))])], parameters=P)
    fam = compile_family(sys, grid=())
    assert fam.native is None and fam.backend == "numba"
    grid = np.linspace(0, 10, 101)
    res = fam.integrate(np.zeros((1, 0)), {"x": [1]}, t_end=10.0, t_eval=grid)
    tr = simulate(sys, history={"x": [1]}, t_end=10.0, t_eval=grid, integrator="scipy")
    assert tr.integrator.startswith("SciPy")
    assert float(np.max(np.abs(res.y[0, :, 0] - tr.states["x"][:, 0]))) < 1e-12
    assert simulate(sys, history={"x": [1]}, t_end=1.0).integrator == "compiled DOP853 (numba)"
