"""The one SymPy → arb converter: a tree walk with one whitelist, emitting straight-line code.

:func:`enclose` evaluates an expression on balls, :func:`compile_program` compiles it once to a
Python function on balls (the branch and bound calls it millions of times), :func:`sign_of` decides
the sign of a constant at increasing precision.

Examples
--------
>>> import sympy
>>> enclose(sympy.pi, prec=64).contains(sympy.pi.evalf(30))
True
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable, Mapping, Sequence
from fractions import Fraction

import flint
import sympy
from flint import arb, fmpq, fmpz

from ...errors import InputError
from .balls import SUPPORTED, _HELPERS, _NATIVE, _NONNEG_FUNCS, _ONE, _ZERO
from .rounding import lower_fraction, upper_fraction

__all__ = ["DEFAULT_PREC", "Program", "SignResult", "UnsupportedExpression", "compile_program", "enclose",
           "sign_of", "to_ball"]

#: working precision (bits) of :func:`enclose` when none is given
DEFAULT_PREC = 128


class UnsupportedExpression(InputError):
    """A SymPy node outside the interval whitelist :data:`SUPPORTED` (never approximated).

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> try:
    ...     enclose(sympy.gamma(x), {x: 2})
    ... except UnsupportedExpression as exc:
    ...     print(str(exc).split(";")[0])
    cannot enclose gamma (in gamma(x)) in interval arithmetic
    """


def _const_ball(node: sympy.Expr) -> arb | None:
    """An arb enclosure of an atomic SymPy number, or None if not atomic."""
    if node.is_Integer:
        return arb(fmpz(int(node)))
    if node.is_Rational:
        return arb(fmpq(int(node.p), int(node.q)))
    if node.is_Float:
        sign, man, exp, _ = node._mpf_
        if man == 0:
            return _ZERO
        value = fmpq(int(man) * 2 ** exp) if exp >= 0 else fmpq(int(man), 2 ** (-exp))
        return arb(-value if sign else value)
    if node is sympy.pi:
        return arb.pi()
    if node is sympy.E:
        return _ONE.exp()
    return None


class _Emitter:
    """Walks SymPy trees, emitting one line of Python per distinct node.

    The generated source contains only register names (``r12``), argument
    names (``x0``), constant slots (``K[3]``) and the helper names above --
    never text taken from the user's expression.
    """

    def __init__(self, nvars: int, var_index: dict, var_nonneg: Sequence[bool]):
        self.lines: list[str] = []
        self.memo: dict = {}
        self.consts: list[arb] = []
        self.nonneg: dict[str, bool] = {}
        self.var_index = var_index
        for i in range(nvars):
            self.nonneg[f"x{i}"] = bool(var_nonneg[i])
        self.count = 0
        self.fold = True
        self.originals: Mapping = {}     # Dummy → the caller's symbol, for messages
        self.top = None

    def _show(self, node) -> str:
        return str(node.xreplace(self.originals)) if self.originals else str(node)

    def _new(self, code: str, nonneg: bool) -> str:
        name = f"r{self.count}"
        self.count += 1
        self.lines.append(f"    {name} = {code}")
        self.nonneg[name] = nonneg
        return name

    def _const(self, ball: arb) -> str:
        self.consts.append(ball)
        name = f"K[{len(self.consts) - 1}]"
        self.nonneg[name] = bool(ball >= 0)
        return name

    def emit(self, node) -> str:
        if self.top is None:
            self.top = node
        try:
            return self.memo[node]
        except KeyError:
            pass
        name = self._emit(node)
        self.memo[node] = name
        return name

    def _emit(self, node) -> str:
        if node.is_Symbol:
            if node not in self.var_index:
                raise InputError(f"symbol {self._show(node)} has no interval; give every free symbol a range "
                                 f"or substitute its value first")
            return f"x{self.var_index[node]}"
        ball = _const_ball(node)
        if ball is not None:
            return self._const(ball)
        if self.fold and node.is_number:
            # a constant subexpression (sqrt(2), cos(1), ...): fold it once, now
            sub = _Emitter(0, {}, ())
            sub.fold = False
            sub.originals, sub.top = self.originals, self.top
            out = sub.emit(node)
            fn = _build([out], sub, 0)
            value = fn()[0]
            name = self._const(value)
            if node.is_nonnegative:
                self.nonneg[name] = True
            return name
        if node.is_Add:
            regs = [self.emit(a) for a in node.args]
            return self._new(" + ".join(regs), all(self.nonneg[r] for r in regs))
        if node.is_Mul:
            return self._mul(node)
        if node.is_Pow:
            return self._pow(node.base, node.exp)
        func = node.func
        if func in _NATIVE:
            (arg,) = node.args
            r = self.emit(arg)
            return self._new(f"{_NATIVE[func]}({r})", func in _NONNEG_FUNCS)
        if func is sympy.tan:
            return self._new(f"_tan({self.emit(node.args[0])})", False)
        if func is sympy.log:
            if len(node.args) != 1:
                raise UnsupportedExpression(f"log with a base is not supported: {self._show(node)}; "
                                            f"write log(x)/log(b)")
            return self._new(f"_log({self.emit(node.args[0])})", False)
        if func is sympy.Abs:
            return self._new(f"_abs({self.emit(node.args[0])})", True)
        if func is sympy.sign:
            return self._new(f"_sgn({self.emit(node.args[0])})", False)
        if func is sympy.Heaviside:
            return self._new(f"_heaviside({self.emit(node.args[0])})", True)
        if func in (sympy.Max, sympy.Min):
            regs = [self.emit(a) for a in node.args]
            flags = [self.nonneg[r] for r in regs]
            nonneg = any(flags) if func is sympy.Max else all(flags)
            helper = "_max" if func is sympy.Max else "_min"
            return self._new(f"{helper}({', '.join(regs)})", nonneg)
        if node is sympy.I:
            raise UnsupportedExpression(f"cannot enclose {self._show(self.top)}: its value is complex (it "
                                        f"contains I); arb encloses real values only")
        raise UnsupportedExpression(f"cannot enclose {func.__name__} (in {self._show(node)}) in interval arithmetic; "
                         f"supported: {', '.join(SUPPORTED)}")

    def _mul(self, node) -> str:
        coeff, factors = node.as_coeff_mul()
        num, den = [], []
        for f in factors:
            if f.is_Pow and f.exp.is_Integer and f.exp < 0:
                den.append(self.emit(f.base ** (-f.exp)) if f.exp != -1 else self.emit(f.base))
            else:
                num.append(self.emit(f))
        negative = False
        if coeff == -1:
            negative = True
        elif coeff != 1:
            c = coeff
            if c < 0:
                negative, c = True, -c
            num.insert(0, self.emit(c))
        code = " * ".join(num) if num else self._const(_ONE)
        nonneg = all(self.nonneg[r] for r in num + den) and not negative
        if den:
            code = f"({code}) / ({' * '.join(den)})"
        if negative:
            code = f"-({code})"
        return self._new(code, nonneg)

    def _pow(self, base, exp) -> str:
        if exp.is_Integer:
            n = int(exp)
            if n == 0:
                return self._const(_ONE)
            if n == 1:
                return self.emit(base)
            if n < 0:
                inner = self.emit(base ** (-n)) if n != -1 else self.emit(base)
                return self._new(f"1 / {inner}", self.nonneg[inner])
            r = self.emit(base)
            if n == 2:
                return self._new(f"_sq({r})", True)
            return self._new(f"_ipow({r}, {n})", n % 2 == 0 or self.nonneg[r])
        r = self.emit(base)
        nonneg = self.nonneg[r] or bool(base.is_nonnegative)
        if exp == sympy.S.Half:
            return self._new(f"_sqrt_nn({r})" if nonneg else f"_sqrt({r})", True)
        if exp == -sympy.S.Half:
            inner = self._new(f"_sqrt_nn({r})" if nonneg else f"_sqrt({r})", True)
            return self._new(f"1 / {inner}", True)
        if exp.is_number:
            if not exp.is_real:
                raise UnsupportedExpression(f"cannot enclose {self._show(base ** exp)}: the exponent is not real; "
                                            f"arb encloses real values only")
            p = self.emit(exp)
            if exp.is_positive:
                return self._new(f"_rpow_pos({r}, {p}, {nonneg})", True)
            return self._new(f"_rpow_neg({r}, {p})", True)
        e = self.emit(exp)
        return self._new(f"_powgen({r}, {e})", True)


def _build(outputs: list[str], em: _Emitter, nvars: int, *,
           overrides: Mapping[str, Callable] | None = None) -> Callable:
    """Compile the emitted lines into a function returning a tuple of balls."""
    args = ", ".join(f"x{i}" for i in range(nvars))
    src = (f"def _f({args}):\n" + "\n".join(em.lines) + ("\n" if em.lines else "")
           + f"    return ({', '.join(outputs)},)\n")
    namespace = dict(_HELPERS)
    if overrides:
        namespace.update(overrides)
    namespace["K"] = tuple(em.consts)
    code = compile(src, "<lkverify.certify.intervals generated>", "exec")
    exec(code, namespace)  # noqa: S102 -- source built from our own tokens only
    return namespace["_f"]


def to_ball(value) -> arb:
    """A ball for an argument: an arb ball, an exact number, a SymPy constant or a (lo, hi) pair.

    Floats are taken at their exact binary value; a pair gives the ball containing [lo, hi].

    Examples
    --------
    >>> to_ball((0, 1)).contains(0.5)
    True
    """
    if isinstance(value, arb):
        return value
    if isinstance(value, bool):
        raise InputError(f"expected a number, an arb ball or a (lo, hi) pair, got {value!r}")
    if isinstance(value, (int, float)):
        return arb(value)
    if isinstance(value, fmpq):
        return arb(value)
    if isinstance(value, Fraction):
        return arb(fmpq(value.numerator, value.denominator))
    if isinstance(value, sympy.Basic):
        return _sympy_number_ball(value)
    if isinstance(value, tuple) and len(value) == 2:
        lo, hi = (to_ball(v) for v in value)
        return lo.union(hi)
    raise InputError(f"expected a number, an arb ball or a (lo, hi) pair, got {value!r}")


def _sympy_number_ball(value) -> arb:
    """The ball of a SymPy constant at the current precision (see :func:`enclose`)."""
    value = _sympify(value)
    if value.free_symbols:
        raise InputError(f"expected a number, got {value} with symbols {sorted(map(str, value.free_symbols))}")
    return enclose(value, prec=None)


def _real_dummies(variables, signs: Sequence[tuple[bool, bool]] | None = None) -> dict:
    """Real Dummy copies of the variables (nonnegative / positive when known)."""
    dummies = {}
    for i, v in enumerate(variables):
        nonneg = bool(v.is_nonnegative)
        pos = bool(v.is_positive)
        if signs is not None:
            nonneg = nonneg or signs[i][0]
            pos = pos or signs[i][1]
        kwargs = {"real": True}
        if pos:
            kwargs["positive"] = True
        elif nonneg:
            kwargs["nonnegative"] = True
        dummies[v] = sympy.Dummy(v.name, **kwargs)
    return dummies


# ---------------------------------------------------------------------------
# programs: one or more expressions compiled to straight-line ball code
# ---------------------------------------------------------------------------

class Program:
    """Straight-line arb code for SymPy expressions (built once, called on many balls).

    The expressions are walked once (the converter of this module, with its
    whitelist :data:`SUPPORTED`); :meth:`function` turns the code into a
    Python function of one ball per variable returning a tuple of balls, one
    per expression.  Constant subexpressions are enclosed once, at the arb
    precision in force when the program is built.

    Parameters
    ----------
    exprs : sequence of sympy.Expr
        The outputs.
    variables : sequence of sympy.Symbol
        The argument order; every free symbol of ``exprs`` must be listed.
    nonnegative : sequence of bool, optional
        Variables known to be ≥ 0 (default: from the symbols' assumptions).
    originals : mapping, optional
        Symbols to show instead of ``variables`` in error messages (when the
        variables are Dummy copies).

    Attributes
    ----------
    nonnegative : tuple of bool
        Per output: proved ≥ 0 structurally (sums of squares, ``Abs``, ...)
        wherever it is defined.
    lines : int
        The number of generated lines (one per distinct node).

    Examples
    --------
    >>> import sympy, flint
    >>> x = sympy.Symbol("x")
    >>> prog = Program([x**2 + 1, sympy.sin(x)], [x])
    >>> prog.nonnegative
    (True, False)
    >>> y, s = prog.function()(flint.arb(2))
    >>> y
    5.00000000000000
    """

    def __init__(self, exprs: Sequence, variables: Sequence, nonnegative: Sequence[bool] | None = None, *,
                 originals: Mapping | None = None):
        variables = tuple(variables)
        if nonnegative is None:
            nonnegative = [bool(v.is_nonnegative) for v in variables]
        self.variables = variables
        self._em = _Emitter(len(variables), {v: i for i, v in enumerate(variables)}, list(nonnegative))
        self._em.originals = dict(originals or {})
        self._outputs = [self._em.emit(sympy.sympify(e)) for e in exprs]
        self.nonnegative = tuple(self._em.nonneg[r] for r in self._outputs)
        self.lines = len(self._em.lines)

    def function(self, overrides: Mapping[str, Callable] | None = None) -> Callable:
        """The compiled function; ``overrides`` replaces ball primitives by name (e.g. affine forms)."""
        return _build(self._outputs, self._em, len(self.variables), overrides=overrides)


def compile_program(exprs: Sequence, variables: Sequence, *, nonnegative: Sequence[bool] | None = None,
                    originals: Mapping | None = None) -> Program:
    """Compile SymPy expressions in ``variables`` to straight-line ball code (see :class:`Program`).

    Examples
    --------
    >>> import sympy, flint
    >>> x = sympy.Symbol("x")
    >>> f = compile_program([sympy.exp(x) - 1], [x]).function()
    >>> f(flint.arb(0, 1e-3))[0].contains(0)
    True
    """
    return Program(exprs, variables, nonnegative, originals=originals)


# ---------------------------------------------------------------------------
# enclosures of single expressions, and certified signs
# ---------------------------------------------------------------------------

def _sympify(expr, what: str = "expression") -> sympy.Expr:
    if isinstance(expr, str):
        raise InputError(f"{what}: expected a SymPy expression, got the string {expr!r}; "
                         f"build it with sympy (strings are never evaluated)")
    if isinstance(expr, Fraction):
        return sympy.Rational(expr.numerator, expr.denominator)
    if isinstance(expr, bool):
        raise InputError(f"{what}: expected a number or a SymPy expression, got {expr!r}")
    if isinstance(expr, float):
        if not math.isfinite(expr):
            raise InputError(f"{what}: expected a finite number, got {expr!r}")
        return sympy.Float(expr)               # its exact binary value
    try:
        out = sympy.sympify(expr, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{what}: expected a SymPy expression, got {type(expr).__name__} {expr!r}") from exc
    if not isinstance(out, sympy.Expr):
        raise InputError(f"{what}: expected a scalar SymPy expression, got {type(out).__name__} {out}")
    return out


@functools.lru_cache(maxsize=2048)
def _compiled(expr: sympy.Expr, variables: tuple, prec: int) -> Callable:
    dummies = _real_dummies(variables)
    dvars = [dummies[v] for v in variables]
    with flint.ctx.workprec(prec):
        back = {d: v for v, d in dummies.items()}
        return Program([expr.xreplace(dummies)], dvars, originals=back).function()


def enclose(expr, values: Mapping | None = None, *, prec: int | None = DEFAULT_PREC) -> arb:
    """A ball containing the value of the real expression ``expr``.

    Parameters
    ----------
    expr : sympy.Expr or number
        Built from the operations and functions in :data:`SUPPORTED`.
        Rationals are exact (``arb(p)/arb(q)`` at ``prec`` bits), a ``Float``
        or Python float stands for its exact binary value.
    values : mapping {sympy.Symbol: ball}, optional
        A ball for every free symbol (an ``arb``, an exact number or a
        ``(lo, hi)`` pair); the balls must respect the symbols' assumptions
        (a ``positive=True`` symbol gets a positive ball).
    prec : int or None, default :data:`DEFAULT_PREC`
        Working precision in bits; None: the arb context's current precision.

    Returns
    -------
    flint.arb
        Contains the value at every point of the balls; not finite where the
        expression may be undefined (``log`` of a ball reaching 0, ...).

    Raises
    ------
    UnsupportedExpression
        A node outside :data:`SUPPORTED` (``I``, ``oo``, ``gamma``, ...).

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> enclose(1 - sympy.Rational(1, 10**20), prec=128) < 1
    True
    >>> enclose(sympy.cos(x) ** 2 + sympy.sin(x) ** 2, {x: (0, 1)}).contains(1)
    True
    >>> enclose(sympy.gamma(x), {x: 2})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    lkverify.certify.intervals.convert.UnsupportedExpression: cannot enclose gamma (in gamma(x)) ...
    """
    expr = _sympify(expr)
    values = {} if values is None else values
    if not isinstance(values, Mapping):
        raise InputError(f"values: expected a mapping {{symbol: ball}}, got {type(values).__name__}")
    bad = [k for k in values if not isinstance(k, sympy.Symbol)]
    if bad:
        raise InputError(f"values: keys must be sympy.Symbol objects, got {bad[0]!r}; "
                         f"key the mapping by the symbols of the expression")
    missing = expr.free_symbols - set(values)
    if missing:
        raise InputError(f"free symbols {sorted(map(str, missing))} of {expr} have no value; "
                         f"give each a ball in values= or substitute it first")
    if prec is None:
        prec = flint.ctx.prec
    elif isinstance(prec, bool) or not isinstance(prec, int) or prec < 2:
        raise InputError(f"prec: expected an integer number of bits ≥ 2, got {prec!r}")
    with flint.ctx.workprec(prec):
        ball = _const_ball(expr)
        if ball is not None:
            return ball
        variables = tuple(sorted(expr.free_symbols, key=sympy.default_sort_key))
        balls = [to_ball(values[v]) for v in variables]
        return _compiled(expr, variables, prec)(*balls)[0]


@dataclasses.dataclass(frozen=True)
class SignResult:
    """The sign of a real constant and the enclosure that decided it.

    Attributes
    ----------
    sign : {1, -1, None}
        1: proved > 0, -1: proved < 0, None: not decided (the value is 0, or
        no enclosure up to the precision limit excluded 0, or it is undefined).
    lower, upper : Fraction or None
        Exact rational bounds of the value (None: no finite enclosure);
        ``lower == upper`` when the value is an exact rational.
    prec : int
        The arb precision (bits) of the enclosure; 0 for an exact rational.
    detail : str
        How it was decided, or why not.

    Examples
    --------
    >>> import sympy
    >>> r = sign_of(sympy.sqrt(2) - sympy.Rational(99, 70))     # 1.41421… − 1.41428…
    >>> r.sign, r.upper < 0, r.prec, r.detail
    (-1, True, 64, 'arb enclosure at 64 bits excludes 0')
    >>> r = sign_of(sympy.Rational(-3, 4))
    >>> r.sign, r.lower == r.upper, r.detail
    (-1, True, 'exact rational')
    >>> sign_of(sympy.sin(sympy.pi)).sign is None               # the value is 0
    True
    """

    sign: int | None
    lower: Fraction | None
    upper: Fraction | None
    prec: int
    detail: str = ""

    @property
    def is_zero(self) -> bool:
        """True when the value is proved to be exactly 0."""
        return self.lower == 0 and self.upper == 0


def _precisions(max_prec: int):
    p = 64
    while p < max_prec:
        yield p
        p *= 2
    yield max_prec


def sign_of(expr, *, max_prec: int = 2000) -> SignResult:
    """Decide the sign of a real constant with certified enclosures.

    An exact rational is decided exactly.  Otherwise :func:`enclose` is
    tried at 64, 128, 256, … bits up to ``max_prec`` until the ball excludes 0.

    Parameters
    ----------
    expr : sympy.Expr or number
        A constant (no free symbols) built from :data:`SUPPORTED`.
    max_prec : int, default 2000
        The largest precision tried, in bits.

    Returns
    -------
    SignResult

    Raises
    ------
    UnsupportedExpression
        ``expr`` has a node outside :data:`SUPPORTED` (``I``: a complex value).

    Examples
    --------
    >>> import sympy
    >>> sign_of(sympy.pi - sympy.Rational(355, 113)).sign
    -1
    >>> q = sympy.Rational(sympy.floor(sympy.sqrt(2) * 10**100), 10**100)   # √2 to 100 digits
    >>> r = sign_of(sympy.sqrt(2) - q)
    >>> r.sign, r.prec
    (1, 512)
    >>> z = sign_of(sympy.sin(sympy.pi / 7) ** 2 + sympy.cos(sympy.pi / 7) ** 2 - 1, max_prec=256)
    >>> z.sign is None and z.lower < 0 < z.upper
    True
    >>> sign_of(sympy.Rational(-1, 2))
    SignResult(sign=-1, lower=Fraction(-1, 2), upper=Fraction(-1, 2), prec=0, detail='exact rational')
    """
    expr = _sympify(expr)
    if expr.free_symbols:
        raise InputError(f"expected a constant, got {expr} with free symbols "
                         f"{sorted(map(str, expr.free_symbols))}; substitute their values first")
    if isinstance(max_prec, bool) or not isinstance(max_prec, int) or max_prec < 2:
        raise InputError(f"max_prec: expected an integer number of bits ≥ 2, got {max_prec!r}")
    if expr.is_Rational:
        q = Fraction(int(expr.p), int(expr.q))
        return SignResult((q > 0) - (q < 0) or None, q, q, 0, "exact rational")
    ball, prec = None, 0
    for prec in _precisions(max_prec):
        ball = enclose(expr, prec=prec)
        if ball > 0 or ball < 0:
            return SignResult(1 if ball > 0 else -1, lower_fraction(ball), upper_fraction(ball), prec,
                              f"arb enclosure at {prec} bits excludes 0")
    if not ball.is_finite():
        return SignResult(None, None, None, prec, f"no finite enclosure up to {prec} bits: {expr} may be "
                                                  f"undefined (log or a root of a value ≤ 0, division by 0)")
    return SignResult(None, lower_fraction(ball), upper_fraction(ball), prec,
                      f"the arb enclosure at {prec} bits contains 0 (the value may be exactly 0); "
                      f"prove it symbolically or raise max_prec")
