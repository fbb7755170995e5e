"""Tests of lkverify.declare.parse: safe parsing of ``--set NAME=VALUE`` values."""

from __future__ import annotations

import time

import pytest
import sympy

from lkverify.declare.parse import InputError, parse_assignment, parse_value

t = sympy.Symbol("t")
VARIABLES = {"t": t}


def _error(text: str, name: str = "mu", **kwargs) -> str:
    """Parse ``text`` expecting an InputError; return its message."""
    with pytest.raises(InputError) as info:
        parse_value(text, name=name, **kwargs)
    message = str(info.value)
    assert message.startswith(f"{name}: "), message
    assert "\n" not in message, message
    return message


# -- numbers ------------------------------------------------------------------


def test_integer_is_exact():
    value = parse_value("42")
    assert value == sympy.Integer(42)
    assert isinstance(value, sympy.Integer)


def test_negative_integer():
    assert parse_value("-3") == sympy.Integer(-3)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.5", sympy.Rational(1, 2)),
        ("0.1", sympy.Rational(1, 10)),
        (".25", sympy.Rational(1, 4)),
        ("2.75", sympy.Rational(11, 4)),
        ("1_000.5", sympy.Rational(2001, 2)),
    ],
)
def test_decimals_are_exact_rationals(text, expected):
    value = parse_value(text)
    assert value == expected
    assert isinstance(value, sympy.Rational)


def test_decimal_sum_is_exact():
    # 0.1 + 0.2 != 0.3 in floating point, but these are exact rationals.
    assert parse_value("0.1+0.2") == sympy.Rational(3, 10)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1e-3", sympy.Rational(1, 1000)),
        ("2.5e-2", sympy.Rational(1, 40)),
        ("1.5E3", sympy.Integer(1500)),
        ("1e-400", sympy.Rational(1, 10**400)),
    ],
)
def test_scientific_notation_is_exact(text, expected):
    assert parse_value(text) == expected


# -- expressions --------------------------------------------------------------


def test_expression_in_t():
    value = parse_value("(1+t)**(-7/8)", variables=VARIABLES)
    assert value == (1 + t) ** sympy.Rational(-7, 8)


def test_expression_with_functions_and_variables():
    value = parse_value("exp(-0.5*t)*sin(t) + Abs(t)", variables=VARIABLES)
    assert value == sympy.exp(-t / 2) * sympy.sin(t) + sympy.Abs(t)


def test_division_of_integers_is_rational():
    assert parse_value("7/8") == sympy.Rational(7, 8)


def test_constants_pi_and_sqrt():
    assert parse_value("pi/2") == sympy.pi / 2
    assert parse_value("sqrt(2)") == sympy.sqrt(2)
    assert parse_value("E") == sympy.E


def test_lowercase_aliases():
    assert parse_value("abs(-3)") == 3
    assert parse_value("max(1, 2, 0.5)") == 2
    assert parse_value("min(t, 1)", variables=VARIABLES) == sympy.Min(t, 1)


def test_surrounding_spaces_ignored():
    assert parse_value("  2 * 3  ") == 6


# -- matrices -----------------------------------------------------------------


def test_diag():
    value = parse_value("diag(2,2,2)")
    assert isinstance(value, sympy.ImmutableMatrix)
    assert value == sympy.ImmutableMatrix(sympy.diag(2, 2, 2))


def test_nested_list_matrix():
    value = parse_value("[[2,0,0],[0,2,0],[0,0,2]]")
    assert isinstance(value, sympy.ImmutableMatrix)
    assert value.shape == (3, 3)
    assert value == 2 * sympy.eye(3)


def test_matrix_entries_are_expressions():
    value = parse_value("[[1+t, 0.5], [pi, sqrt(2)]]", variables=VARIABLES)
    assert value == sympy.ImmutableMatrix([[1 + t, sympy.Rational(1, 2)], [sympy.pi, sympy.sqrt(2)]])


def test_flat_list_is_column_vector():
    value = parse_value("[1,2,3]")
    assert isinstance(value, sympy.ImmutableMatrix)
    assert value.shape == (3, 1)
    assert list(value) == [1, 2, 3]


def test_tuples_like_lists():
    assert parse_value("((1,2),(3,4))") == sympy.ImmutableMatrix([[1, 2], [3, 4]])


def test_scalar_times_matrix():
    assert parse_value("2*diag(1,1)") == sympy.ImmutableMatrix([[2, 0], [0, 2]])


def test_ragged_matrix_rejected():
    message = _error("[[1,2],[3]]")
    assert "ragged" in message
    assert "row 2" in message


def test_matrix_plus_scalar_rejected():
    assert "cannot add" in _error("diag(1,1)+1")


# -- rejected values ----------------------------------------------------------


@pytest.mark.parametrize("text", ["nan", "inf", "-inf", "NaN", "Infinity", "oo", "1e999"])
def test_non_finite_rejected(text):
    message = _error(text)
    assert "expected a finite real number" in message
    assert "pass e.g. mu=2" in message and "--set" not in message  # the library names no CLI flag


def test_the_command_line_option_is_named_when_given():
    with pytest.raises(InputError, match="pass e.g. --set mu=2"):
        parse_value("nan", name="mu", option="--set")


def test_division_by_zero_rejected():
    assert "finite" in _error("1/0")


def test_imaginary_rejected():
    assert "real" in _error("sqrt(-1)")


def test_unknown_name_lists_allowed_names():
    message = _error("x + 1", variables=VARIABLES)
    assert "unknown name 'x'" in message
    assert "allowed names: E, pi, t" in message


def test_name_without_variables_is_unknown():
    assert "unknown name 't'" in _error("t")


def test_caret_suggests_double_star():
    message = _error("t^2", variables=VARIABLES)
    assert "'^'" in message
    assert "**" in message


def test_import_injection_rejected_and_not_executed(tmp_path):
    sentinel = tmp_path / "pwned"
    message = _error(f"__import__('os').system('touch {sentinel}')")
    assert "not allowed: call of __import__" in message
    assert not sentinel.exists()


def test_plain_import_call_rejected():
    assert "not allowed: call of __import__" in _error("__import__('os')")


def test_attribute_access_rejected():
    message = _error("t.subs", variables=VARIABLES)
    assert "not allowed: attribute access" in message


def test_lambda_rejected():
    assert "not allowed: lambda" in _error("lambda: 1")
    assert "not allowed: call of (lambda: 1)" in _error("(lambda: 1)()")


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("t[0]", "subscript"),
        ("sqrt(x=2)", "keyword argument"),
        ("sqrt(*[2])", "starred argument"),
        ("'abc'", "string"),
        ("b'abc'", "bytes"),
        ("f'{t}'", "f-string"),
        ("[x for x in t]", "comprehension"),
        ("t < 1", "comparison"),
        ("print(1)", "call of print"),
        ("t // 2", "operator //"),
        ("True", "constant True"),
    ],
)
def test_other_constructs_rejected(text, fragment):
    assert fragment in _error(text, variables=VARIABLES)


def test_wrong_number_of_arguments():
    assert "sin takes 1 argument" in _error("sin(1, 2)")


def test_huge_power_rejected_quickly():
    start = time.perf_counter()
    message = _error("10**10**10")
    assert "too large" in message
    assert time.perf_counter() - start < 2.0


@pytest.mark.parametrize(
    "text", ["(10**1000)**1000", "sqrt(2)**(10**10)", "exp(10**10*log(2))", "(2*t)**20000"]
)
def test_other_huge_computations_rejected_quickly(text):
    start = time.perf_counter()
    assert "too large" in _error(text, variables=VARIABLES)
    assert time.perf_counter() - start < 2.0


def test_moderate_power_allowed():
    assert parse_value("2**100") == sympy.Integer(2) ** 100


def test_too_long_rejected():
    assert "too long" in _error("1+" * 1500 + "1")


def test_too_deep_rejected():
    assert "nested too deeply" in _error("-" * 500 + "1")


def test_empty_rejected():
    assert "empty" in _error("   ")


def test_syntax_error_message():
    message = _error("1+*2", name="a", variables=VARIABLES)
    assert message == (
        "a: cannot parse '1+*2' (invalid syntax at column 3); expected a number, "
        "a matrix like diag(2,2,2) or [[2,0],[0,2]], or an expression in t"
    )


def test_input_error_is_value_error():
    assert issubclass(InputError, ValueError)


# -- parse_assignment ---------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("mu=2", ("mu", "2")),
        ("a = 3", ("a", "3")),
        ("P=diag(2, 2)", ("P", "diag(2, 2)")),
        ("h=a==b", ("h", "a==b")),
    ],
)
def test_parse_assignment_good(text, expected):
    assert parse_assignment(text) == expected


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("a", "expected NAME=VALUE"),
        ("=3", "name before '='"),
        ("1a=3", "got '1a'"),
        ("a b=3", "got 'a b'"),
        ("a=", "expected a value"),
    ],
)
def test_parse_assignment_bad(text, fragment):
    with pytest.raises(InputError) as info:
        parse_assignment(text)
    message = str(info.value)
    assert fragment in message
    assert "\n" not in message


def test_parse_assignment_then_value():
    name, text = parse_assignment("mu = 0.25")
    assert parse_value(text, name=name) == sympy.Rational(1, 4)
