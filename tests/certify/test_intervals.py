"""The one interval layer (lkverify.certify.intervals): outward rounding, the SymPy → arb converter, signs.

References: exact rationals (fractions.Fraction) for every rounding, mpmath at
600 bits for every whitelisted function, SymPy's exact rational arithmetic for
the signs; and the source tree itself for "one converter, one rounding routine".
"""

import ast
import math
import pathlib
import random
from fractions import Fraction

import flint
import mpmath
import pytest
import sympy
from flint import arb, fmpq

import lkverify
from lkverify.errors import InputError
from lkverify.certify.intervals import (
    SUPPORTED, SignResult, UnsupportedExpression, compile_program, enclose, float_down, float_up,
    lower_fraction, sign_of, to_ball, upper_fraction,
)

R = sympy.Rational
x, y = sympy.symbols("x y", real=True)


# ---------------------------------------------------------------------------------------------
# outward rounding


def _random_ball(rng: random.Random, prec: int) -> arb:
    """A ball at ``prec`` bits: a random rational midpoint (any sign, wide exponent range), random radius."""
    num = rng.randrange(1, 2 ** prec) * rng.choice((-1, 1))
    den = rng.randrange(1, 2 ** prec)
    scale = Fraction(2) ** rng.randrange(-80, 80)
    q = Fraction(num, den) * scale
    with flint.ctx.workprec(prec):
        mid = arb(fmpq(q.numerator, q.denominator))
        if rng.random() < 0.3:
            return mid
        rad = arb(fmpq(q.numerator, q.denominator)).abs_upper() * arb(2) ** -rng.randrange(20, prec + 40)
        return mid + arb(0, 1) * rad


def _naive_up(b: arb) -> float:
    with flint.ctx.workprec(128):      # float() of a 128-bit end rounds to nearest
        return float(b.upper())


@pytest.mark.parametrize("prec", [53, 128, 300])
def test_float_bounds_enclose_the_exact_ends_of_random_balls(prec):
    rng = random.Random(prec)
    for _ in range(2000):
        b = _random_ball(rng, prec)
        lo, hi = lower_fraction(b), upper_fraction(b)
        fd, fu = float_down(b), float_up(b)
        assert Fraction(fd) <= lo <= hi <= Fraction(fu)
        # and they are the nearest floats outside: one step inward leaves the ball's end
        assert Fraction(math.nextafter(fd, math.inf)) > lo or Fraction(fd) == lo
        assert Fraction(math.nextafter(fu, -math.inf)) < hi or Fraction(fu) == hi


def test_float_of_an_upper_end_is_not_outward_at_128_bits():
    # the bug this module fixes: float(ball.upper()) rounds to nearest, about half the time inward
    rng = random.Random(1)
    inward = 0
    for _ in range(400):
        b = _random_ball(rng, 128)
        if Fraction(_naive_up(b)) < upper_fraction(b):
            inward += 1
    assert inward > 50


@pytest.mark.parametrize("prec", [53, 128, 300])
def test_float_bounds_are_evaluated_at_any_context_precision(prec):
    with flint.ctx.workprec(300):
        third = arb(1) / 3
    with flint.ctx.workprec(prec):
        assert Fraction(float_down(third)) < Fraction(1, 3) < Fraction(float_up(third))
        assert lower_fraction(third) < Fraction(1, 3) < upper_fraction(third)
        assert upper_fraction(third) - lower_fraction(third) < Fraction(1, 2 ** 290)


def test_fraction_rounding_is_directed_and_tight():
    rng = random.Random(7)
    for _ in range(3000):
        q = Fraction(rng.randrange(-10 ** 30, 10 ** 30), rng.randrange(1, 10 ** 30))
        d, u = float_down(q), float_up(q)
        assert Fraction(d) <= q <= Fraction(u)
        assert (d == u) == (Fraction(d) == q)
        if d != u:
            assert math.nextafter(d, math.inf) == u
    assert float_down(Fraction(1, 3)) == 1 / 3 < float_up(Fraction(1, 3))
    assert float_up(Fraction(1, 10)) == 0.1 > float_down(Fraction(1, 10))
    assert float_down(0.1) == float_up(0.1) == 0.1          # a float is exact
    assert float_down(sympy.Rational(-1, 3)) < -1 / 3


@pytest.mark.parametrize("q, down, up", [
    (Fraction(10) ** 400, 1.7976931348623157e308, math.inf),
    (-Fraction(10) ** 400, -math.inf, -1.7976931348623157e308),
    (Fraction(1, 10 ** 400), 0.0, 5e-324),
    (-Fraction(1, 10 ** 400), -5e-324, -0.0),
    (Fraction(3, 10 ** 320), 2.99e-320, 3.01e-320),    # subnormal range
    (Fraction(0), 0.0, 0.0),
])
def test_rounding_at_the_ends_of_the_float_range(q, down, up):
    d, u = float_down(q), float_up(q)
    assert Fraction(d) <= q if math.isfinite(d) else d == -math.inf
    assert q <= Fraction(u) if math.isfinite(u) else u == math.inf
    if q.denominator == 1 or abs(q) > 1 or q == 0:
        assert (d, u) == (down, up)
    else:
        assert down <= d <= u <= up
    with flint.ctx.workprec(200):
        b = arb(fmpq(q.numerator, q.denominator))
    assert float_down(b) <= d and float_up(b) >= u


def test_balls_that_are_not_finite():
    nan, inf = arb("nan"), arb("inf")
    assert float_down(nan) == -math.inf and float_up(nan) == math.inf
    assert float_up(inf) == math.inf
    assert lower_fraction(nan) is None and upper_fraction(arb(0, math.inf)) is None


def test_rounding_refuses_what_is_not_exact():
    with pytest.raises(InputError, match="expected an arb ball or an exact rational"):
        float_down(sympy.sqrt(2))
    with pytest.raises(InputError):
        float_up("0.1")


# ---------------------------------------------------------------------------------------------
# the converter: every whitelisted function against mpmath at 600 bits

def _mp_fraction(v) -> Fraction:
    """The exact value of an mpmath number."""
    sign, man, exp, _ = mpmath.mpf(v)._mpf_
    return (-1) ** sign * Fraction(int(man)) * Fraction(2) ** int(exp)


A, B = Fraction(3, 7), Fraction(-5, 11)
CASES = [
    ("+", x + y, lambda a, b: a + b),
    ("-", x - y, lambda a, b: a - b),
    ("*", x * y, lambda a, b: a * b),
    ("/", x / y, lambda a, b: a / b),
    ("integer power", x ** 5 * y ** -3, lambda a, b: a ** 5 * b ** -3),
    ("real power", x ** R(13, 10), lambda a, b: a ** (mpmath.mpf(13) / 10)),
    ("negative real power", x ** R(-7, 3), lambda a, b: a ** (-mpmath.mpf(7) / 3)),
    ("power with a symbolic exponent", x ** (y + 2), lambda a, b: a ** (b + 2)),
    ("sqrt", sympy.sqrt(x), lambda a, b: mpmath.sqrt(a)),
    ("exp", sympy.exp(y), lambda a, b: mpmath.exp(b)),
    ("log", sympy.log(x), lambda a, b: mpmath.log(a)),
    ("sin", sympy.sin(y), lambda a, b: mpmath.sin(b)),
    ("cos", sympy.cos(y), lambda a, b: mpmath.cos(b)),
    ("tan", sympy.tan(y), lambda a, b: mpmath.tan(b)),
    ("atan", sympy.atan(y), lambda a, b: mpmath.atan(b)),
    ("asin", sympy.asin(y), lambda a, b: mpmath.asin(b)),
    ("acos", sympy.acos(y), lambda a, b: mpmath.acos(b)),
    ("sinh", sympy.sinh(y), lambda a, b: mpmath.sinh(b)),
    ("cosh", sympy.cosh(y), lambda a, b: mpmath.cosh(b)),
    ("tanh", sympy.tanh(y), lambda a, b: mpmath.tanh(b)),
    ("sinc", sympy.sinc(y), lambda a, b: mpmath.sin(b) / b),
    ("Abs", sympy.Abs(y), lambda a, b: abs(b)),
    ("sign", sympy.sign(y), lambda a, b: mpmath.sign(b)),
    ("Heaviside", sympy.Heaviside(y), lambda a, b: mpmath.mpf(1) if b > 0 else mpmath.mpf(0)),
    ("Min", sympy.Min(x, y, R(1, 5)), lambda a, b: min(a, b, mpmath.mpf(1) / 5)),
    ("Max", sympy.Max(x, y, R(1, 5)), lambda a, b: max(a, b, mpmath.mpf(1) / 5)),
    ("pi", sympy.pi * x, lambda a, b: mpmath.pi * a),
    ("E", sympy.E * x, lambda a, b: mpmath.e * a),
    ("rational constant", x + R(1, 3), lambda a, b: a + mpmath.mpf(1) / 3),
    ("float constant", x + sympy.Float(0.1), lambda a, b: a + mpmath.mpf(0.1)),
    ("constant subexpression", x * sympy.cos(1) + sympy.sqrt(2), lambda a, b: a * mpmath.cos(1) + mpmath.sqrt(2)),
]


def test_the_cases_cover_the_whitelist():
    named = {c[0] for c in CASES}
    for item in SUPPORTED:
        if item in ("integer and real powers", "rational and float constants"):
            continue
        assert item in named, item


@pytest.mark.parametrize("name, expr, ref", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("prec", [53, 128, 300])
def test_enclose_contains_the_mpmath_value(name, expr, ref, prec):
    ball = enclose(expr, {x: A, y: B}, prec=prec)
    with mpmath.workprec(600):
        truth = _mp_fraction(ref(mpmath.mpf(A.numerator) / A.denominator, mpmath.mpf(B.numerator) / B.denominator))
    lo, hi = lower_fraction(ball), upper_fraction(ball)
    assert lo <= truth <= hi
    assert hi - lo <= abs(truth) * Fraction(2) ** (16 - prec) + Fraction(2) ** (-prec)


BOXES = [((Fraction(3, 10), Fraction(9, 10)), (Fraction(-7, 10), Fraction(-1, 5))),
         ((Fraction(1, 10), Fraction(3)), (Fraction(-9, 10), Fraction(1, 2))),
         ((Fraction(2), Fraction(5)), (Fraction(1, 4), Fraction(19, 20)))]


@pytest.mark.parametrize("bx, by", BOXES)
@pytest.mark.parametrize("name, expr, ref", CASES, ids=[c[0] for c in CASES])
def test_enclose_on_wide_balls_contains_every_sampled_value(name, expr, ref, bx, by):
    ball = enclose(expr, {x: bx, y: by})
    if not ball.is_finite():     # may be undefined on the box (1/y, asin): no claim is made
        return
    lo, hi = lower_fraction(ball), upper_fraction(ball)
    rng = random.Random(0)
    for _ in range(40):
        a = bx[0] + (bx[1] - bx[0]) * Fraction(rng.randrange(0, 1001), 1000)
        b = by[0] + (by[1] - by[0]) * Fraction(rng.randrange(0, 1001), 1000)
        with mpmath.workprec(600):
            v = _mp_fraction(ref(mpmath.mpf(a.numerator) / a.denominator, mpmath.mpf(b.numerator) / b.denominator))
        assert lo <= v <= hi


def test_rationals_are_exact_at_the_working_precision():
    one_minus = 1 - R(1, 10 ** 20)
    assert enclose(one_minus, prec=128) < 1
    assert enclose(one_minus, prec=53).contains(1)          # honest at 53 bits: not decided, not wrong
    b = enclose(R(1, 3), prec=300)
    assert lower_fraction(b) < Fraction(1, 3) < upper_fraction(b)
    assert upper_fraction(b) - lower_fraction(b) < Fraction(1, 2 ** 295)
    b = enclose(Fraction(2, 7), prec=64)
    assert lower_fraction(b) < Fraction(2, 7) < upper_fraction(b)
    assert enclose(10 ** 40 + 1, prec=200) > 10 ** 40


def test_floats_are_taken_at_their_exact_binary_value():
    for v in (sympy.Float(0.1), 0.1):
        b = enclose(v, prec=300)
        assert lower_fraction(b) == upper_fraction(b) == Fraction(0.1) != Fraction(1, 10)


def test_values_may_be_balls_numbers_pairs_or_sympy_constants():
    e = x ** 2 + y
    assert enclose(e, {x: arb(2), y: 1}) == 5
    assert enclose(e, {x: (0, 1), y: sympy.sqrt(2)}).contains(1 + arb(2).sqrt())
    assert to_ball(Fraction(1, 4)) == arb(0.25)
    with pytest.raises(InputError, match="have no value"):
        enclose(e, {x: 1})
    with pytest.raises(InputError, match="keys must be sympy.Symbol"):
        enclose(e, {"x": 1, y: 1})
    with pytest.raises(InputError, match="prec"):
        enclose(e, {x: 1, y: 1}, prec=0)


def test_undefined_values_give_balls_that_are_not_finite():
    assert not enclose(sympy.log(x), {x: (-1, 1)}).is_finite()
    assert not enclose(sympy.sqrt(x), {x: (-1, 1)}).is_finite()
    assert not enclose(1 / x, {x: (-1, 1)}).is_finite()


@pytest.mark.parametrize("expr", [
    sympy.gamma(x), sympy.floor(x), sympy.Piecewise((x, x > 0), (0, True)), x + sympy.I, x ** sympy.I,
    sympy.oo + x, sympy.zoo * x, sympy.Integral(x * y, (y, 0, 1)), sympy.Derivative(sympy.Function("f")(x), x),
    sympy.besselj(0, x), sympy.EulerGamma * x,
])
def test_unsupported_nodes_raise_never_approximate(expr):
    with pytest.raises(UnsupportedExpression, match="cannot enclose") as info:
        enclose(expr, {x: 1})
    assert isinstance(info.value, InputError)
    assert "_x" not in str(info.value)        # the caller's symbols, not internal copies


def test_complex_values_say_so():
    with pytest.raises(UnsupportedExpression, match="complex"):
        sign_of(sympy.log(-2))


def test_compiled_programs_and_enclose_agree():
    exprs = [sympy.sin(x) * sympy.exp(y) - x ** 2, sympy.sqrt(x ** 2 + y ** 2)]
    f = compile_program(exprs, [x, y]).function()
    for a, b in [(Fraction(1, 3), Fraction(-2, 5)), ((0, 1), (-1, 0))]:
        with flint.ctx.workprec(128):
            out = f(to_ball(a), to_ball(b))
        for e, o in zip(exprs, out):
            ref = enclose(e, {x: a, y: b}, prec=128)
            assert o.overlaps(ref) and o.rad() == ref.rad() and o.mid() == ref.mid()
    assert compile_program(exprs, [x, y]).nonnegative == (False, True)


# ---------------------------------------------------------------------------------------------
# signs


def test_the_float_cancellation_margin_is_negative():
    # 1e16 − 1 − 1e16 + 1/2 is +1/2 in floats; the truth is −1/2
    assert 1e16 - 1 - 1e16 + 0.5 == 0.5
    exact = sympy.Integer(10) ** 16 - 1 - sympy.Integer(10) ** 16 + R(1, 2)
    assert sign_of(exact) == SignResult(-1, Fraction(-1, 2), Fraction(-1, 2), 0, "exact rational")
    unevaluated = sympy.Add(10 ** 16, -1, -(10 ** 16), R(1, 2), evaluate=False)
    assert not unevaluated.is_Rational
    res = sign_of(unevaluated)
    assert res.sign == -1 and res.lower <= Fraction(-1, 2) <= res.upper < 0 and res.prec >= 64


def test_sign_of_raises_the_precision_until_it_decides():
    for digits, bits in ((30, 128), (100, 512), (300, 2000)):
        q = R(math.isqrt(2 * 10 ** (2 * digits)), 10 ** digits)       # √2 to `digits` digits, below
        res = sign_of(sympy.sqrt(2) - q)
        assert res.sign == 1 and 0 < res.lower <= res.upper and res.prec <= bits
        assert Fraction(0) < res.lower < Fraction(1, 10 ** digits)
        assert sign_of(q - sympy.sqrt(2)).sign == -1
    deep = R(math.isqrt(2 * 10 ** 1400), 10 ** 700)
    res = sign_of(sympy.sqrt(2) - deep)
    assert res.sign is None and res.prec == 2000 and res.lower < 0 < res.upper


def test_sign_of_zero_and_undefined():
    z = sign_of(sympy.sin(sympy.pi / 7) ** 2 + sympy.cos(sympy.pi / 7) ** 2 - 1, max_prec=300)
    assert z.sign is None and z.lower < 0 < z.upper and z.prec == 300 and not z.is_zero
    assert sign_of(0).is_zero and sign_of(0).sign is None
    u = sign_of(sympy.log(sympy.sin(sympy.pi / 7) ** 2 + sympy.cos(sympy.pi / 7) ** 2 - 1), max_prec=256)
    assert u.sign is None and u.lower is None and "undefined" in u.detail


def test_sign_of_validates_its_input():
    with pytest.raises(InputError, match="expected a constant"):
        sign_of(x + 1)
    with pytest.raises(InputError, match="max_prec"):
        sign_of(sympy.pi, max_prec=1.5)
    with pytest.raises(InputError, match="string"):
        sign_of("1/2")
    res = sign_of(sympy.pi - R(355, 113))
    assert res.sign == -1 and res.upper < 0
    with pytest.raises(AttributeError):
        res.sign = 1   # frozen


# ---------------------------------------------------------------------------------------------
# one converter and one rounding routine in the whole tree

FORBIDDEN_DEFS = {"_up", "_down", "_lower", "_upper", "_float_up", "_float_down", "_arb_of", "_const_ball",
                  "_Emitter", "_build", "_to_ball", "_sympy_number_ball"}


def _sources():
    root = pathlib.Path(lkverify.__file__).parent
    layer = root / "certify" / "intervals"          # the interval layer itself: rounding, balls, convert
    return [p for p in root.rglob("*.py") if layer not in p.parents]


def test_one_converter_and_one_rounding_routine():
    problems = []
    for path in _sources():
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name in FORBIDDEN_DEFS:
                problems.append(f"{path.name}:{node.lineno} defines {node.name}")
            # float(<ball>.upper()) / float(<ball>.lower()) rounds to nearest: use float_up / float_down
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "float"
                    and node.args and isinstance(node.args[0], ast.Call)
                    and isinstance(node.args[0].func, ast.Attribute)
                    and node.args[0].func.attr in ("upper", "lower")):
                problems.append(f"{path.name}:{node.lineno} rounds a ball end with float()")
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "man_exp"):
                problems.append(f"{path.name}:{node.lineno} reads a ball end by hand (man_exp)")
    assert not problems, problems
