"""The library's certificate checker for polynomial inequalities and its rational identity engine:
mutated claims are refuted or left undecided, true claims written differently are proved."""

import sympy

from lkverify import Status
from lkverify.certify.certificates import inequality_step
from lkverify.symbolic.rational import matrix_identity, rational_is_zero

x, y = sympy.symbols("x y", real=True)


def test_inequality_step_mutations():
    ok = inequality_step("amgm", x**2 + y**2 - 2 * x * y, [(1, [], x - y)], text="")
    assert ok.status is Status.EXACT
    assert inequality_step("flip", -(x**2 + y**2 - 2 * x * y), [(1, [], x - y)], text="").status is Status.FAILED
    tiny = inequality_step("tiny", x**2 + y**2 - 2 * x * y - sympy.Rational(1, 10**30), [(1, [], x - y)], text="")
    assert tiny.status is not Status.EXACT                          # a tiny exact difference is not proved
    neg = inequality_step("neg c", -(x - y) ** 2, [(-1, [], x - y)], text="")
    assert neg.status is Status.FAILED                              # a negative constant is no certificate
    unlisted = inequality_step("hyp", x**3, [(1, [x], x)], hyps=[], text="")
    assert unlisted.status is not Status.EXACT                      # x is not a hypothesis: x³ ≥ 0 is false
    written = inequality_step("same", (x - y) ** 2, [(1, [], y - x)], text="")   # q written differently
    assert written.status is Status.EXACT


def test_rational_identities():
    s = sympy.Symbol("s", real=True)
    assert rational_is_zero(1 / (1 + s**2) - (1 - s**2) / (1 - s**4))
    assert not rational_is_zero(1 / (1 + s**2) - 1 / (1 + s**2 + sympy.Rational(1, 10**30)))
    r = matrix_identity("m", sympy.Matrix([[s / (1 + s**2), 1]]), sympy.Matrix([[-s / (1 + s**2), 1]]), text="sign")
    assert r.status is Status.FAILED and "(1, 1)" in r.value["differences"]
