"""Safe parsing of user-supplied values into SymPy objects.

Values arrive on the command line as ``--set NAME=VALUE``.  ``VALUE`` is
turned into a SymPy expression or an immutable matrix **without executing
any user code**: the text is parsed with :func:`ast.parse` (``mode="eval"``)
and the syntax tree is walked with an explicit whitelist.  Every SymPy object
is built by this module itself; nothing is ever passed to ``eval``, ``exec``,
:func:`sympy.sympify` or :func:`sympy.parsing.sympy_parser.parse_expr`.

Accepted syntax
---------------
* integers (exact :class:`sympy.Integer`) and decimal literals such as
  ``0.5``, ``.25``, ``1e-3`` (exact :class:`sympy.Rational`, built from the
  literal text, so ``0.1`` is exactly ``1/10``);
* ``+ - * / **``, unary ``-`` and ``+``, parentheses;
* the constants ``pi`` and ``E`` and the caller-supplied variables;
* calls of the whitelisted functions listed in :data:`FUNCTION_NAMES`;
* matrices: ``diag(a, b, ...)``, nested lists ``[[2, 0], [0, 2]]`` and flat
  lists ``[1, 2, 3]`` (a column vector); tuples behave like lists.

Everything else (attribute access, subscripts, keyword arguments, lambdas,
comprehensions, strings, comparisons, ...) is rejected with
:class:`InputError`, whose message is a single line starting with the value's
name.  Inside the package, :class:`InputError` is the shared
``lkverify.errors.InputError`` (a :class:`ValueError`), so callers that catch
that exception also catch parse errors.  Sizes are bounded (text length, syntax-tree size and depth, exponent
and integer sizes) so that pathological input such as ``10**10**10`` is
refused quickly instead of hanging.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Callable, Mapping
from typing import TypeAlias

import sympy
from sympy.matrices import MatrixBase

__all__ = [
    "FUNCTION_NAMES",
    "InputError",
    "parse_assignment",
    "parse_value",
]

#: Longest accepted value text, in characters.
MAX_TEXT_LENGTH = 2000
#: Largest accepted syntax tree, in nodes.
MAX_AST_NODES = 2000
#: Deepest accepted syntax tree (``1+1+...`` adds one level per term).
MAX_AST_DEPTH = 100
#: Largest absolute exponent accepted in a power with a non-trivial base.
MAX_EXPONENT = 10_000
#: Largest size, in bits, of any exact integer or rational produced.
MAX_RESULT_BITS = 100_000
#: Largest total size, in bits, of the numbers under fractional powers
#: (SymPy factors those numbers, which is slow for big ones).
MAX_RADICAND_BITS = 1024
#: Largest absolute power of ten written in a decimal literal (``1e-1000``).
MAX_DECIMAL_EXPONENT = 1000
#: Largest number of rows or columns of a matrix.
MAX_MATRIX_DIM = 30
#: Largest exponent of a matrix power ``M**n`` (``0 <= n``).
MAX_MATRIX_POWER = 8

Value: TypeAlias = sympy.Expr | sympy.ImmutableMatrix

_NONFINITE_NAMES = frozenset({"nan", "inf", "infinity", "oo", "zoo"})
_CONSTANTS: dict[str, sympy.Expr] = {"pi": sympy.pi, "E": sympy.E}
_BINOP_SYMBOLS: dict[type[ast.operator], str] = {
    ast.Add: "+",
    ast.Sub: "-",
    ast.Mult: "*",
    ast.Div: "/",
    ast.Pow: "**",
    ast.FloorDiv: "//",
    ast.Mod: "%",
    ast.MatMult: "@",
    ast.BitXor: "^",
    ast.BitAnd: "&",
    ast.BitOr: "|",
    ast.LShift: "<<",
    ast.RShift: ">>",
}
_DECIMAL_RE = re.compile(
    r"(?P<int>[0-9_]*)(?:\.(?P<frac>[0-9_]*))?(?:[eE](?P<exp>[+-]?[0-9_]+))?"
)


try:  # share the package's exception so that callers catching it see ours too
    from ..errors import InputError
except ImportError:  # pragma: no cover - module loaded outside the package

    class InputError(ValueError):  # type: ignore[no-redef]
        """Bad user input; the message is one line: what was expected, what came, how to fix."""


def _diag(*entries: sympy.Expr) -> sympy.ImmutableMatrix:
    return sympy.ImmutableMatrix(sympy.diag(*entries))


# name -> (SymPy callable, minimum number of arguments, maximum or None)
_FUNCTIONS: dict[str, tuple[Callable[..., Value], int, int | None]] = {
    "sqrt": (sympy.sqrt, 1, 1),
    "exp": (sympy.exp, 1, 1),
    "log": (sympy.log, 1, 2),
    "sin": (sympy.sin, 1, 1),
    "cos": (sympy.cos, 1, 1),
    "tan": (sympy.tan, 1, 1),
    "atan": (sympy.atan, 1, 1),
    "sinh": (sympy.sinh, 1, 1),
    "cosh": (sympy.cosh, 1, 1),
    "tanh": (sympy.tanh, 1, 1),
    "Abs": (sympy.Abs, 1, 1),
    "abs": (sympy.Abs, 1, 1),
    "Min": (sympy.Min, 1, None),
    "min": (sympy.Min, 1, None),
    "Max": (sympy.Max, 1, None),
    "max": (sympy.Max, 1, None),
    "diag": (_diag, 1, MAX_MATRIX_DIM),
}

#: Names of the functions that may be called in a value, in display order.
FUNCTION_NAMES: tuple[str, ...] = tuple(_FUNCTIONS)


def _quote(text: str, limit: int = 80) -> str:
    """Quote ``text`` for a one-line message, shortening long text."""
    if len(text) > limit:
        text = text[: limit - 3] + "..."
    if text.isprintable() and "'" not in text:
        return f"'{text}'"
    return repr(text)


def _one_line(text: str, limit: int = 120) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _rational_bits(expr: sympy.Basic) -> int:
    """Total bit size of the exact rational numbers occurring in ``expr``."""
    return sum(
        int(r.p).bit_length() + int(r.q).bit_length()
        for r in expr.atoms(sympy.Rational)
    )


def _max_rational_bits(expr: sympy.Basic) -> int:
    return max(
        (
            max(int(r.p).bit_length(), int(r.q).bit_length())
            for r in expr.atoms(sympy.Rational)
        ),
        default=0,
    )


def _radicand_bits(expr: sympy.Basic) -> int:
    """Total bit size of numbers under fractional powers in ``expr``."""
    return sum(
        _rational_bits(p.base)
        for p in expr.atoms(sympy.Pow)
        if p.exp.is_Rational and not p.exp.is_Integer
    )


def _max_abs_rational(expr: sympy.Basic) -> int:
    """Ceiling of the largest absolute rational number occurring in ``expr``."""
    return max(
        (-(-abs(int(r.p)) // int(r.q)) for r in expr.atoms(sympy.Rational)),
        default=0,
    )


class _Evaluator:
    """Walk a whitelisted expression tree and build the SymPy value."""

    def __init__(self, name: str, text: str, variables: Mapping[str, sympy.Basic], option: str | None = None):
        self.name = name
        self.text = text
        self.variables = variables
        self.option = option
        key = name.split()[-1] if name.split() else "x"
        key = key if key.isidentifier() else "x"
        self.example = f"{option} {key}=2" if option else f"{key}=2"

    # -- messages -----------------------------------------------------------
    def expectation(self) -> str:
        what = "expected a number, a matrix like diag(2,2,2) or [[2,0],[0,2]], "
        if self.variables:
            return what + "or an expression in " + ", ".join(sorted(self.variables))
        return what + "or an expression such as 2*pi"

    def fail(self, problem: str, fix: str | None = None) -> InputError:
        message = f"{self.name}: {_one_line(problem, 300)}"
        if fix:
            message += f"; {_one_line(fix, 300)}"
        return InputError(message)

    def not_allowed(self, what: str, node: ast.AST) -> InputError:
        problem = f"not allowed: {what}"
        if self.source(node) != self.text:
            problem += f" in {_quote(self.text)}"
        return self.fail(
            problem,
            "use only numbers, + - * / **, parentheses, matrices like [[2,0],[0,2]], "
            f"the names {self.allowed_names()} and the functions "
            + ", ".join(FUNCTION_NAMES),
        )

    def nonfinite(self, got: str) -> InputError:
        if self.text.lstrip().startswith(("[", "diag")):  # an entry of a matrix or vector
            return self.fail(f"expected finite real entries, got {got}", "replace it by a finite number")
        return self.fail(
            f"expected a finite real number, got {got}",
            f"pass e.g. {self.example}",
        )

    def source(self, node: ast.AST) -> str:
        segment = ast.get_source_segment(self.text, node)
        if segment is None:
            segment = ast.unparse(node)
        return _one_line(segment, 60)

    def allowed_names(self) -> str:
        names = sorted(set(_CONSTANTS) | set(self.variables))
        return ", ".join(names)

    # -- driver -------------------------------------------------------------
    def run(self) -> Value:
        text = self.text
        if not text:
            raise self.fail("empty value", self.expectation())
        if len(text) > MAX_TEXT_LENGTH:
            raise self.fail(
                f"value is too long ({len(text)} characters, at most {MAX_TEXT_LENGTH})",
                "pass a shorter expression",
            )
        try:
            tree = ast.parse(text, mode="eval")
        except SyntaxError as exc:
            where = f" at column {exc.offset}" if exc.offset else ""
            reason = _one_line(exc.msg or "invalid syntax", 80)
            raise self.fail(
                f"cannot parse {_quote(text)} ({reason}{where})", self.expectation()
            ) from None
        except (ValueError, MemoryError, RecursionError) as exc:
            raise self.fail(
                f"cannot parse {_quote(text)} ({_one_line(str(exc), 80)})",
                self.expectation(),
            ) from None
        self.check_size(tree.body)
        result = self.evaluate(tree.body)
        if isinstance(result, MatrixBase):
            result = sympy.ImmutableMatrix(result)
            entries = list(result)
        else:
            entries = [result]
        for entry in entries:
            bad = [
                str(x)
                for x in (sympy.nan, sympy.zoo, sympy.oo, -sympy.oo)
                if entry.has(x)
            ]
            if entry.has(sympy.AccumBounds):
                bad.append("an interval")
            if bad:
                raise self.nonfinite(f"{_quote(text)}, which evaluates to {bad[0]}")
            if entry.has(sympy.I):
                raise self.fail(
                    f"expected a real value, got {_quote(text)}, which is imaginary",
                    f"pass e.g. {self.example}",
                )
        return result

    def check_size(self, root: ast.expr) -> None:
        count = 0
        stack: list[tuple[ast.AST, int]] = [(root, 1)]
        while stack:
            node, depth = stack.pop()
            count += 1
            if count > MAX_AST_NODES:
                raise self.fail(
                    f"expression is too large (more than {MAX_AST_NODES} parts)",
                    "pass a shorter expression",
                )
            if depth > MAX_AST_DEPTH:
                raise self.fail(
                    f"expression is nested too deeply (more than {MAX_AST_DEPTH} levels)",
                    "simplify the expression",
                )
            for child in ast.iter_child_nodes(node):
                if not isinstance(child, ast.expr_context):
                    stack.append((child, depth + 1))

    # -- evaluation ---------------------------------------------------------
    def evaluate(self, node: ast.expr) -> Value:
        if isinstance(node, ast.Constant):
            return self.constant(node)
        if isinstance(node, ast.Name):
            return self.name_value(node)
        if isinstance(node, ast.UnaryOp):
            return self.unary(node)
        if isinstance(node, ast.BinOp):
            return self.binop(node)
        if isinstance(node, ast.Call):
            return self.call(node)
        if isinstance(node, (ast.List, ast.Tuple)):
            return self.matrix(node)
        raise self.not_allowed(self.describe(node), node)

    def describe(self, node: ast.AST) -> str:
        src = self.source(node)
        kinds: list[tuple[type | tuple[type, ...], str]] = [
            (ast.Attribute, f"attribute access {src}"),
            (ast.Subscript, f"subscript {src}"),
            (ast.Lambda, "lambda"),
            (
                (ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp),
                f"comprehension {src}",
            ),
            (ast.JoinedStr, f"f-string {src}"),
            (ast.FormattedValue, f"f-string {src}"),
            (ast.Starred, f"starred argument {src}"),
            ((ast.Dict, ast.Set), f"dict/set literal {src}"),
            (ast.Compare, f"comparison {src}"),
            (ast.BoolOp, f"and/or {src}"),
            (ast.IfExp, f"conditional expression {src}"),
            (ast.NamedExpr, f"assignment expression {src}"),
            ((ast.Await, ast.Yield, ast.YieldFrom), src),
        ]
        for kind, text in kinds:
            if isinstance(node, kind):
                return text
        return f"{type(node).__name__} {src}"

    def constant(self, node: ast.Constant) -> sympy.Expr:
        value = node.value
        if isinstance(value, bool) or value is None or value is Ellipsis:
            raise self.not_allowed(f"constant {value!r}", node)
        if isinstance(value, int):
            return sympy.Integer(value)
        if isinstance(value, float):
            return self.decimal(node, value)
        if isinstance(value, complex):
            raise self.fail(
                f"expected a real number, got the imaginary literal {self.source(node)}",
                f"pass e.g. {self.example}",
            )
        if isinstance(value, str):
            raise self.not_allowed(f"string {self.source(node)}", node)
        if isinstance(value, bytes):
            raise self.not_allowed(f"bytes literal {self.source(node)}", node)
        raise self.not_allowed(f"constant {self.source(node)}", node)

    def decimal(self, node: ast.Constant, value: float) -> sympy.Expr:
        literal = ast.get_source_segment(self.text, node) or ""
        if value != value or value in (float("inf"), float("-inf")):
            raise self.nonfinite(f"{literal or value} (overflows to infinity)")
        match = _DECIMAL_RE.fullmatch(literal)
        if not literal or match is None:  # pragma: no cover - defensive
            raise self.fail(f"cannot read the number {_quote(literal)}", self.expectation())
        int_part = (match["int"] or "").replace("_", "")
        frac_part = (match["frac"] or "").replace("_", "")
        exponent = int((match["exp"] or "0").replace("_", ""))
        digits = int((int_part + frac_part) or "0")
        if digits == 0:
            return sympy.Integer(0)
        power = exponent - len(frac_part)
        if abs(power) > MAX_DECIMAL_EXPONENT:
            raise self.fail(
                f"the number {literal} is too small or too large "
                f"(more than {MAX_DECIMAL_EXPONENT} decimal places)",
                "pass a number of moderate size",
            )
        if power >= 0:
            return sympy.Integer(digits * 10**power)
        return sympy.Rational(digits, 10**-power)

    def name_value(self, node: ast.Name) -> sympy.Basic:
        ident = node.id
        if ident in self.variables:
            return self.variables[ident]
        if ident in _CONSTANTS:
            return _CONSTANTS[ident]
        if ident.lower() in _NONFINITE_NAMES:
            raise self.nonfinite(ident if self.text.strip() == ident else f"{ident} in {_quote(self.text)}")
        if ident in _FUNCTIONS:
            raise self.fail(
                f"{ident} is a function but is used without arguments in {_quote(self.text)}",
                f"call it, e.g. {ident}(2)" if ident != "diag" else "call it, e.g. diag(2,2,2)",
            )
        raise self.fail(
            f"unknown name {ident!r} in {_quote(self.text)}",
            f"allowed names: {self.allowed_names()}; allowed functions: "
            + ", ".join(FUNCTION_NAMES),
        )

    def unary(self, node: ast.UnaryOp) -> Value:
        if isinstance(node.op, ast.USub):
            return self.apply(node, lambda x: -x, self.evaluate(node.operand))
        if isinstance(node.op, ast.UAdd):
            return self.evaluate(node.operand)
        symbol = {ast.Not: "not", ast.Invert: "~"}.get(type(node.op), "?")
        raise self.not_allowed(f"operator '{symbol}' in {self.source(node)}", node)

    def binop(self, node: ast.BinOp) -> Value:
        op = type(node.op)
        symbol = _BINOP_SYMBOLS.get(op, "?")
        if op is ast.BitXor:
            suggestion = ast.unparse(ast.BinOp(node.left, ast.Pow(), node.right))
            raise self.fail(
                f"'^' is not a power operator (got {self.source(node)})",
                f"write ** instead, e.g. {_one_line(suggestion, 60)}",
            )
        if op in (ast.FloorDiv, ast.Mod):
            raise self.fail(
                f"not allowed: operator {symbol} in {_quote(self.text)}",
                "use / for exact division",
            )
        if op is ast.MatMult:
            raise self.fail(
                f"not allowed: operator @ in {_quote(self.text)}",
                "use * for matrix products",
            )
        if op not in (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow):
            raise self.fail(
                f"not allowed: bitwise operator {symbol} in {_quote(self.text)}",
                "use + - * / ** only",
            )
        left = self.evaluate(node.left)
        right = self.evaluate(node.right)
        left_matrix = isinstance(left, MatrixBase)
        right_matrix = isinstance(right, MatrixBase)
        if op in (ast.Add, ast.Sub) and left_matrix != right_matrix:
            verb = "add" if op is ast.Add else "subtract"
            raise self.fail(
                f"cannot {verb} {self.kind(left)} and {self.kind(right)} "
                f"in {self.source(node)}",
                "scale an identity matrix instead, e.g. 2*diag(1,1)",
            )
        if op is ast.Div and right_matrix:
            raise self.fail(
                f"cannot divide by {self.kind(right)} in {self.source(node)}",
                "divide by a scalar only",
            )
        if op is ast.Pow:
            self.check_power(node, left, right)
        self.check_radicands(node, left, right)
        functions: dict[type[ast.operator], Callable[[Value, Value], Value]] = {
            ast.Add: lambda a, b: a + b,
            ast.Sub: lambda a, b: a - b,
            ast.Mult: lambda a, b: a * b,
            ast.Div: lambda a, b: a / b,
            ast.Pow: lambda a, b: a**b,
        }
        return self.apply(node, functions[op], left, right)

    def kind(self, value: Value) -> str:
        if isinstance(value, MatrixBase):
            return f"a {value.rows}x{value.cols} matrix"
        return "a scalar"

    def too_big(self, node: ast.AST) -> InputError:
        return self.fail(
            f"{self.source(node)} is too large to compute exactly "
            f"(exponents are limited to {MAX_EXPONENT} and numbers to "
            f"{MAX_RESULT_BITS} bits)",
            "pass a smaller number",
        )

    def check_power(self, node: ast.AST, base: Value, exponent: Value) -> None:
        if isinstance(exponent, MatrixBase):
            raise self.fail(
                f"cannot raise to the power of {self.kind(exponent)} in {self.source(node)}",
                "use a scalar exponent",
            )
        if isinstance(base, MatrixBase):
            if base.rows != base.cols:
                raise self.fail(
                    f"cannot take a power of {self.kind(base)} in {self.source(node)}",
                    "only square matrices have powers",
                )
            if not (exponent.is_Integer and 0 <= int(exponent) <= MAX_MATRIX_POWER):
                raise self.fail(
                    f"unsupported matrix power {self.source(node)}",
                    f"matrix exponents must be integers from 0 to {MAX_MATRIX_POWER}",
                )
            estimate = (_max_rational_bits(base) + base.rows.bit_length()) * int(exponent)
            if estimate > MAX_RESULT_BITS:
                raise self.too_big(node)
            return
        self.check_exponential(node, base, exponent)

    def check_exponential(self, node: ast.AST, base: sympy.Basic, exponent: sympy.Basic) -> None:
        """Refuse powers whose exact evaluation would be huge or slow."""
        if exponent.is_Number:
            if base.is_Number and base in (sympy.S.Zero, sympy.S.One, sympy.S.NegativeOne):
                return
            magnitude = _max_abs_rational(exponent)
            if magnitude > MAX_EXPONENT:
                raise self.too_big(node)
            if max(_rational_bits(base), 1) * magnitude > MAX_RESULT_BITS:
                raise self.too_big(node)
            if exponent.is_Rational and not exponent.is_Integer:
                if _rational_bits(base) + _radicand_bits(base) > MAX_RADICAND_BITS:
                    raise self.too_big(node)
        elif exponent.has(sympy.log) or base == sympy.E:
            # exp(c*log(x)) and E**(c*log(x)) evaluate to x**c.
            if not exponent.has(sympy.log):
                return
            magnitude = _max_abs_rational(exponent)
            bits = max(_rational_bits(exponent), 1)
            if (
                magnitude > MAX_EXPONENT
                or bits * magnitude > MAX_RESULT_BITS
                or bits + _radicand_bits(exponent) > MAX_RADICAND_BITS
            ):
                raise self.too_big(node)

    def check_radicands(self, node: ast.AST, *operands: Value) -> None:
        if sum(_radicand_bits(x) for x in operands) > MAX_RADICAND_BITS:
            raise self.fail(
                f"{self.source(node)} involves roots of numbers that are too large "
                f"(more than {MAX_RADICAND_BITS} bits in total)",
                "pass smaller numbers",
            )

    def apply(self, node: ast.AST, function: Callable[..., Value], *args: Value) -> Value:
        """Call a SymPy operation, turning any failure into :class:`InputError`."""
        try:
            result = function(*args)
        except InputError:
            raise
        except Exception as exc:  # noqa: BLE001 - any SymPy failure is bad input
            try:
                detail = _one_line(f"{type(exc).__name__}: {exc}", 100)
            except Exception:  # noqa: BLE001 - e.g. str() of a huge integer
                detail = type(exc).__name__
            raise self.fail(
                f"cannot compute {self.source(node)} ({detail})", self.expectation()
            ) from None
        if isinstance(result, MatrixBase):
            result = sympy.ImmutableMatrix(result)
        elif not isinstance(result, sympy.Expr):
            raise self.fail(
                f"{self.source(node)} does not give a number or matrix", self.expectation()
            )
        if _max_rational_bits(result) > MAX_RESULT_BITS:
            raise self.too_big(node)
        return result

    def call(self, node: ast.Call) -> Value:
        func = node.func
        if not isinstance(func, ast.Name):
            called = self.source(func)
            if not isinstance(func, (ast.Attribute, ast.Call, ast.Subscript)):
                called = f"({called})"
            raise self.not_allowed(f"call of {called}", node)
        ident = func.id
        if ident not in _FUNCTIONS:
            raise self.not_allowed(f"call of {ident}", node)
        if node.keywords:
            keyword = node.keywords[0]
            raise self.not_allowed(f"keyword argument {self.source(keyword)}", keyword)
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                raise self.not_allowed(f"starred argument {self.source(arg)}", arg)
        function, low, high = _FUNCTIONS[ident]
        count = len(node.args)
        if count < low or (high is not None and count > high):
            expected = (
                f"{low}" if low == high else f"{low} to {high}" if high else f"at least {low}"
            )
            example = "diag(2,2,2)" if ident == "diag" else f"{ident}(2)"
            raise self.fail(
                f"{ident} takes {expected} argument{'' if (high or low) == 1 else 's'}, "
                f"got {count} in {self.source(node)}",
                f"write e.g. {example}",
            )
        args = [self.evaluate(arg) for arg in node.args]
        for arg, value in zip(node.args, args):
            if isinstance(value, MatrixBase):
                raise self.fail(
                    f"{ident} needs scalar arguments, got {self.kind(value)} "
                    f"{self.source(arg)}",
                    "write e.g. diag(2,2,2)" if ident == "diag" else f"write e.g. {ident}(2)",
                )
        if ident == "sqrt":
            self.check_exponential(node, args[0], sympy.S.Half)
        elif ident == "exp":
            self.check_exponential(node, sympy.E, args[0])
        self.check_radicands(node, *args)
        return self.apply(node, function, *args)

    def matrix(self, node: ast.List | ast.Tuple) -> sympy.ImmutableMatrix:
        elements = node.elts
        if not elements:
            raise self.fail(
                f"empty matrix {self.source(node)}", "write e.g. [[2,0],[0,2]] or diag(2,2)"
            )
        nested = [isinstance(e, (ast.List, ast.Tuple)) for e in elements]
        if any(nested) and not all(nested):
            raise self.fail(
                f"mixed rows and numbers in {self.source(node)}",
                "write a matrix as a list of rows, e.g. [[2,0],[0,2]]",
            )
        if all(nested):
            rows = [list(e.elts) for e in elements]  # type: ignore[attr-defined]
        else:
            rows = [[e] for e in elements]
        if len(rows) > MAX_MATRIX_DIM or any(len(r) > MAX_MATRIX_DIM for r in rows):
            raise self.fail(
                f"matrix {self.source(node)} is too large "
                f"(at most {MAX_MATRIX_DIM} rows and columns)",
                "pass a smaller matrix",
            )
        width = len(rows[0])
        for number, row in enumerate(rows, start=1):
            if len(row) != width:
                raise self.fail(
                    f"ragged matrix {self.source(node)}: row 1 has {width} entries "
                    f"but row {number} has {len(row)}",
                    "give every row the same number of entries, e.g. [[2,0],[0,2]]",
                )
            if width == 0:
                raise self.fail(
                    f"empty matrix row in {self.source(node)}",
                    "write e.g. [[2,0],[0,2]]",
                )
        entries: list[list[sympy.Expr]] = []
        for row in rows:
            values = []
            for element in row:
                if isinstance(element, (ast.List, ast.Tuple)):
                    raise self.fail(
                        f"matrix {self.source(node)} has more than two dimensions",
                        "write a matrix as a list of rows, e.g. [[2,0],[0,2]]",
                    )
                value = self.evaluate(element)
                if isinstance(value, MatrixBase):
                    raise self.fail(
                        f"matrix entry {self.source(element)} is itself a matrix",
                        "write a matrix as a list of rows of numbers, e.g. [[2,0],[0,2]]",
                    )
                values.append(value)
            entries.append(values)
        return sympy.ImmutableMatrix(entries)


def parse_value(
    text: str,
    *,
    name: str = "value",
    variables: Mapping[str, sympy.Symbol] | None = None,
    option: str | None = None,
) -> sympy.Expr | sympy.ImmutableMatrix:
    """Turn user text into a SymPy expression or matrix without executing it.

    The text is parsed with :func:`ast.parse` and the syntax tree is
    evaluated through a whitelist; nothing is passed to ``eval``, ``exec``
    or :func:`sympy.sympify`.

    Parameters
    ----------
    text : str
        The value, e.g. ``"0.5"``, ``"(1+t)**(-7/8)"``, ``"diag(2,2,2)"`` or
        ``"[[2,0],[0,2]]"``.  Surrounding white space is ignored.
    name : str, optional
        Name of the value, used as the prefix of every error message
        (``"mu: ..."``).
    variables : Mapping[str, sympy.Symbol], optional
        Names that may appear in the expression and the SymPy symbols they
        stand for, e.g. ``{"t": sympy.Symbol("t")}``.  They take precedence
        over the constants ``pi`` and ``E``.
    option : str, optional
        The command-line option the value came from, if any (``"--set"`` or
        ``"--history"``), used in the suggested fixes.

    Returns
    -------
    sympy.Expr or sympy.ImmutableMatrix
        Decimal literals become exact rationals; lists and ``diag`` become
        immutable matrices (a flat list is a column vector).

    Raises
    ------
    InputError
        If the text is empty, does not parse, uses anything outside the
        whitelist, is not finite and real, or is too large to evaluate.  The
        message is one line starting with ``name`` and a colon.

    Examples
    --------
    >>> parse_value("diag(2,2,2)")
    Matrix([
    [2, 0, 0],
    [0, 2, 0],
    [0, 0, 2]])
    >>> parse_value("0.1")
    1/10
    >>> import sympy
    >>> t = sympy.Symbol("t")
    >>> parse_value("(1+t)**(-7/8)", variables={"t": t})
    (t + 1)**(-7/8)
    >>> parse_value("2^3", name="mu")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: mu: '^' is not a power operator (got 2^3); write ** instead, e.g. 2 ** 3
    """
    if not isinstance(text, str):
        raise InputError(f"text must be a str, not {type(text).__name__}")
    checked: dict[str, sympy.Basic] = {}
    for key, symbol in (variables or {}).items():
        if not isinstance(key, str) or not key.isidentifier():
            raise InputError(f"variable names must be identifiers, got {key!r}")
        if not isinstance(symbol, sympy.Basic):
            raise InputError(f"variable {key!r} must be a SymPy object, not {type(symbol).__name__}")
        checked[key] = symbol
    return _Evaluator(name, text.strip(), checked, option).run()


def parse_assignment(text: str, *, option: str = "--set") -> tuple[str, str]:
    """Split ``'NAME=VALUE'`` into ``(name, value_text)``.

    The text is split at the first ``=``; spaces around both parts are
    removed.  ``NAME`` must be a Python identifier and ``VALUE`` must not be
    empty.

    Parameters
    ----------
    text : str
        The argument of ``--set``, e.g. ``"mu=2"`` or ``"P = diag(2,2)"``.
    option : str, optional
        The option it came from (``"--set"`` or ``"--history"``), named in the messages.

    Returns
    -------
    tuple of (str, str)
        The name and the (unparsed) value text.

    Raises
    ------
    InputError
        If there is no ``=``, the name is empty or not an identifier, or the
        value is empty.

    Examples
    --------
    >>> parse_assignment("mu = 0.5")
    ('mu', '0.5')
    """
    if not isinstance(text, str):
        raise InputError(f"text must be a str, not {type(text).__name__}")
    raw_name, sep, value = text.partition("=")
    name, value = raw_name.strip(), value.strip()
    label = _one_line(name, 40) if name else option
    if not sep:
        raise InputError(
            f"{label}: expected NAME=VALUE, got {_quote(text)}; "
            f"write e.g. {option} {name if name.isidentifier() else 'mu'}=2"
        )
    if not name:
        raise InputError(
            f"{option}: expected NAME=VALUE with a name before '=', got {_quote(text)}; "
            f"write e.g. {option} mu={_one_line(value, 40) or '2'}"
        )
    if not name.isidentifier():
        raise InputError(
            f"{label}: expected a name made of letters, digits and _ that does not "
            f"start with a digit, got {_quote(name)}; write e.g. {option} mu=2"
        )
    if not value:
        raise InputError(
            f"{name}: expected a value after '=', got {_quote(text)}; write e.g. {option} {name}=2"
        )
    return name, value
