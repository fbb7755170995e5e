"""Parameters of a system or a functional, with the assumptions they carry.

A proof module declares its parameters through a :class:`Parameters` registry,
which hands back plain SymPy objects (symbols, matrices, undefined functions) to
write formulas with, and keeps for each one a :class:`ParameterSpec`: its kind,
the paper's default value, how to validate a user's value, and how to draw a
random admissible value for numeric witnesses.

>>> P = Parameters()
>>> tau = P.delay("tau", default=1)
>>> F = P.spd_matrix("F", 2, default="diag(1,1)")
>>> F.inv()[0, 0]
F_22/(F_11*F_22 - F_12**2)
>>> sorted(P.names)
['F', 'tau']
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterable, Mapping, Sequence

import numpy as np
import sympy

from ..status import Label
from sympy.core.function import AppliedUndef

from ..errors import InputError
from .symbols import t as _t, zeta as _zeta
from .vectors import dot

__all__ = ["ParameterKind", "ParameterSpec", "Parameters", "SymmetricMatrix"]


class ParameterKind(Label):
    """What a parameter is, and so which values are admissible.

    Examples
    --------
    >>> P = Parameters()
    >>> tau = P.delay("tau")
    >>> P["tau"].kind is ParameterKind.DELAY, P["tau"].kind == "delay (positive scalar)"
    (True, True)
    >>> str(ParameterKind.SPD_MATRIX)
    'symmetric positive-definite matrix'
    """

    REAL = "real scalar"
    POSITIVE = "positive scalar"
    NONNEGATIVE = "nonnegative scalar"
    DELAY = "delay (positive scalar)"
    SPD_MATRIX = "symmetric positive-definite matrix"
    MATRIX = "real matrix"
    DIAGONAL = "diagonal matrix with positive entries"
    UNIT_VECTOR = "constant unit vector"
    COEFFICIENT = "function of t"
    KERNEL = "kernel function of zeta"


class SymmetricMatrix(sympy.ImmutableDenseMatrix):
    """A symbolic symmetric matrix whose inverse is written as adj(M)/det(M).

    SymPy's default symbolic inverse is correct but sprawling; the adjugate form
    keeps derived expressions polynomial up to one determinant.
    """

    def inv(self, *args, **kwargs):  # noqa: D102 - same contract as Matrix.inv
        return sympy.ImmutableMatrix(self.adjugate() / self.det(method="berkowitz"))


_SCALAR_KINDS = (ParameterKind.REAL, ParameterKind.POSITIVE, ParameterKind.NONNEGATIVE, ParameterKind.DELAY)


@dataclasses.dataclass(frozen=True)
class ParameterSpec:
    """One declared parameter.

    Attributes
    ----------
    name : str
        The name users pass to ``--set``.
    kind : ParameterKind
    obj : sympy object
        What formulas use: a Symbol, a Matrix, or an undefined function.
    symbols : tuple
        The SymPy atoms a value replaces (symbols, or the undefined function).
    default : sympy object or None
        The paper's value.
    latex : str
    description : str

    Examples
    --------
    >>> P = Parameters()
    >>> k = P.scalar("k", positive=True, default="1/2")
    >>> spec = P["k"]
    >>> spec.kind, spec.default, spec.check("3/4")
    (<ParameterKind.POSITIVE: 'positive scalar'>, 1/2, 3/4)
    >>> spec.check(-1)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: k: expected k > 0 (it must be positive), got k=-1
    """

    name: str
    kind: ParameterKind
    obj: object
    symbols: tuple
    default: object = None
    latex: str = ""
    description: str = ""
    shape: tuple[int, int] | None = None

    # -- validation -----------------------------------------------------------------
    def check(self, value) -> object:
        """Return ``value`` converted to this parameter's form, or raise InputError."""
        name = self.name
        if self.kind in _SCALAR_KINDS:
            if isinstance(value, sympy.MatrixBase):
                raise InputError(f"{name}: expected a {self.kind.value}, got a {value.shape[0]}x{value.shape[1]} matrix")
            value = sympy.sympify(value)
            if value.free_symbols:
                raise InputError(f"{name}: expected a number, got the expression {value}; "
                                 f"{name} is a constant ({self.kind.value})")
            if value.has(sympy.nan, sympy.zoo) or value in (sympy.oo, -sympy.oo):
                raise InputError(f"{name}: expected a finite real number, got {value}")
            if not value.is_real:
                raise InputError(f"{name}: expected a real number, got {value}")
            if self.kind in (ParameterKind.POSITIVE, ParameterKind.DELAY) and not value.is_positive:
                what = "a delay must be positive" if self.kind is ParameterKind.DELAY else "it must be positive"
                raise InputError(f"{name}: expected {name} > 0 ({what}), got {name}={value}")
            if self.kind is ParameterKind.NONNEGATIVE and value.is_negative:
                raise InputError(f"{name}: expected {name} >= 0, got {name}={value}")
            return value
        if self.kind in (ParameterKind.SPD_MATRIX, ParameterKind.DIAGONAL):
            n = self.shape[0]
            if not isinstance(value, sympy.MatrixBase):
                raise InputError(f"{name}: expected a {n}x{n} matrix such as diag({','.join(['1'] * n)}), got {value}")
            if value.shape != (n, n):
                raise InputError(f"{name}: expected a {n}x{n} matrix, got a {value.shape[0]}x{value.shape[1]} one")
            if any(e.free_symbols for e in value):
                raise InputError(f"{name}: expected numeric entries, got {list(value)}")
            if any(e.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo) for e in value):
                raise InputError(f"{name}: expected finite entries, got {list(value)}")
            if self.kind is ParameterKind.DIAGONAL and not value.is_diagonal():
                raise InputError(f"{name}: expected a diagonal matrix like diag(5,6,4), got {value.tolist()}")
            if not (value - value.T).is_zero_matrix:
                raise InputError(f"{name}: expected a symmetric matrix, got {value.tolist()}")
            _check_positive_definite(name, value, n)
            return sympy.ImmutableMatrix(value)
        if self.kind is ParameterKind.MATRIX:
            rows, cols = self.shape
            if not isinstance(value, sympy.MatrixBase):
                example = "[" + ",".join("[" + ",".join(["0"] * cols) + "]" for _ in range(rows)) + "]"
                raise InputError(f"{name}: expected a {rows}x{cols} matrix such as {example}, got {value}")
            if value.shape != (rows, cols):
                raise InputError(f"{name}: expected a {rows}x{cols} matrix, got a {value.shape[0]}x{value.shape[1]} "
                                 f"one")
            if any(e.free_symbols for e in value):
                raise InputError(f"{name}: expected numeric entries, got {value.tolist()}")
            if any(e.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo) for e in value):
                raise InputError(f"{name}: expected finite entries, got {value.tolist()}")
            if not all(e.is_real for e in value):
                raise InputError(f"{name}: expected real entries, got {value.tolist()}")
            return sympy.ImmutableMatrix(value)
        if self.kind is ParameterKind.UNIT_VECTOR:
            n = self.shape[0]
            if not isinstance(value, sympy.MatrixBase) or value.shape not in ((n, 1), (1, n)):
                raise InputError(f"{name}: expected a unit {n}-vector such as [0,0,1], got {value}")
            value = sympy.ImmutableMatrix(value.reshape(n, 1))
            if any(e.free_symbols or e.has(sympy.nan, sympy.zoo, sympy.oo) for e in value):
                raise InputError(f"{name}: expected numeric finite entries, got {list(value)}")
            if sympy.simplify(dot(value, value) - 1) != 0:
                raise InputError(f"{name}: expected a unit vector, got norm {_fmt(sympy.sqrt(dot(value, value)))}; "
                                 f"divide each entry by the norm, e.g. [1/sqrt(3),1/sqrt(3),1/sqrt(3)]")
            return value
        if self.kind in (ParameterKind.COEFFICIENT, ParameterKind.KERNEL):
            var = _t if self.kind is ParameterKind.COEFFICIENT else _zeta
            if isinstance(value, sympy.MatrixBase):
                raise InputError(f"{name}: expected a scalar function of {var}, got a matrix")
            value = sympy.sympify(value)
            if self.kind is ParameterKind.KERNEL:
                value = value.subs(_t, _zeta)  # users write kernels in t as well
            extra = value.free_symbols - {var}
            if extra:
                raise InputError(f"{name}: expected an expression in {var} only, got symbols {sorted(map(str, extra))}")
            if value.has(sympy.nan, sympy.zoo):
                raise InputError(f"{name}: expected a finite function, got {value}")
            return value
        raise AssertionError(self.kind)  # pragma: no cover - every kind is handled above

    def substitution(self, value) -> dict:
        """The replacement of this parameter's atoms by ``value`` (already checked)."""
        if self.kind in _SCALAR_KINDS:
            return {self.obj: value}
        if self.kind in (ParameterKind.SPD_MATRIX, ParameterKind.DIAGONAL, ParameterKind.UNIT_VECTOR,
                         ParameterKind.MATRIX):
            return {s: v for s, v in zip(self.obj, value) if isinstance(s, sympy.Symbol)}
        # functions: replace f(arg) by value(arg)
        var = _t if self.kind is ParameterKind.COEFFICIENT else _zeta
        return {self.obj: sympy.Lambda(var, value)}

    # -- random admissible values for numeric witnesses ------------------------------------
    def random_value(self, rng: np.random.Generator):
        """A random admissible value with simple rational entries."""
        def rat(lo, hi):
            return sympy.Rational(int(rng.integers(int(lo * 64), int(hi * 64))), 64)

        if self.kind is ParameterKind.REAL:
            return rat(-2, 2)
        if self.kind in (ParameterKind.POSITIVE, ParameterKind.NONNEGATIVE):
            return rat(0.4, 2.2)
        if self.kind is ParameterKind.DELAY:
            return rat(0.4, 1.6)
        if self.kind is ParameterKind.DIAGONAL:
            return sympy.ImmutableMatrix(sympy.diag(*[rat(1, 4) for _ in range(self.shape[0])]))
        if self.kind is ParameterKind.SPD_MATRIX:
            n = self.shape[0]
            m = sympy.Matrix(n, n, lambda i, j: rat(-1, 1))
            return sympy.ImmutableMatrix(m * m.T + sympy.eye(n))
        if self.kind is ParameterKind.MATRIX:
            return sympy.ImmutableMatrix(*self.shape, lambda i, j: rat(-2, 2))
        if self.kind is ParameterKind.UNIT_VECTOR:
            v = rng.normal(size=self.shape[0])
            v = [sympy.Rational(int(round(x * 16)), 16) for x in v]
            m = sympy.Matrix(v)
            if m.norm() == 0:
                m[0] = 1
            return sympy.ImmutableMatrix(m / m.norm())
        if self.kind is ParameterKind.COEFFICIENT:
            return 1 + rat(0.1, 0.6) * sympy.sin(rat(0.5, 2) * _t + rat(0, 3))
        if self.kind is ParameterKind.KERNEL:
            return rat(0.5, 2) * sympy.exp(-rat(0.5, 2) * _zeta)
        raise AssertionError(self.kind)  # pragma: no cover


def _check_positive_definite(name: str, value, n: int) -> None:
    """Raise InputError unless ``value ≻ 0`` is proved (exact LDLᵀ, or arb balls for irrational entries)."""
    from ..certify.matrices import matrix_positive_definite
    from ..status import Status

    res = matrix_positive_definite(value, name=name)
    if res.status.is_proof:
        return
    example = f"diag({','.join(['1'] * n)})"
    if res.status is Status.FAILED:
        raise InputError(f"{name}: expected a positive-definite matrix, got one that is not: {res.detail}; "
                         f"use e.g. {example}")
    raise InputError(f"{name}: expected a positive-definite matrix, but positivity could not be proved "
                     f"({res.detail}); give exact rational entries, e.g. {example}")


def _fmt(x) -> str:
    return str(x) if len(str(x)) < 20 else f"{float(x):.6g}"


class Parameters:
    """A registry of declared parameters; each declaration returns the SymPy object to use.

    Names must be unique within one registry.

    Examples
    --------
    >>> P = Parameters()
    >>> k = P.scalar("k", positive=True, default=2)
    >>> tau = P.delay("tau")
    >>> P.resolve({"tau": "1/10"})                      # checked values, defaults filled in
    {'tau': 1/10, 'k': 2}
    >>> P.resolve({"taw": 1})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: taw: no such parameter; did you mean tau?
    """

    def __init__(self):
        self._specs: dict[str, ParameterSpec] = {}
        self._groups: list[tuple[str, ...]] = []

    # -- declarations ---------------------------------------------------------------------
    def _add(self, spec: ParameterSpec):
        if not spec.name.isidentifier():
            raise InputError(f"parameter name must be an identifier, got {spec.name!r}")
        if spec.name in self._specs:
            raise InputError(f"parameter {spec.name!r} declared twice")
        if spec.default is not None:
            object.__setattr__(spec, "default", spec.check(_coerce(spec.default, spec.name)))
        self._specs[spec.name] = spec
        return spec.obj

    def scalar(self, name: str, *, positive: bool = False, nonnegative: bool = False,
               default=None, latex: str | None = None, description: str = "") -> sympy.Symbol:
        """A constant real scalar; ``positive`` / ``nonnegative`` restrict it."""
        kind = ParameterKind.POSITIVE if positive else ParameterKind.NONNEGATIVE if nonnegative else ParameterKind.REAL
        assumptions = {"positive": True} if positive else {"nonnegative": True} if nonnegative else {"real": True}
        sym = sympy.Symbol(name, **assumptions)
        return self._add(ParameterSpec(name, kind, sym, (sym,), default, latex or name, description))

    def delay(self, name: str = "tau", *, default=None, latex: str | None = r"\tau", description: str = "") -> sympy.Symbol:
        """A constant delay τ > 0."""
        sym = sympy.Symbol(name, positive=True)
        return self._add(ParameterSpec(name, ParameterKind.DELAY, sym, (sym,), default, latex or name, description))

    def spd_matrix(self, name: str, n: int = 3, *, default=None, latex: str | None = None,
                   description: str = "") -> SymmetricMatrix:
        """A constant symmetric positive-definite n×n matrix with entries ``name_ij``."""
        syms = {}
        def entry(i, j):
            i, j = min(i, j), max(i, j)
            return syms.setdefault((i, j), sympy.Symbol(f"{name}_{i + 1}{j + 1}", real=True))
        m = SymmetricMatrix(n, n, lambda i, j: entry(i, j))
        return self._add(ParameterSpec(name, ParameterKind.SPD_MATRIX, m, tuple(syms.values()), default,
                                       latex or name, description, (n, n)))

    def matrix(self, name: str, rows: int, cols: int | None = None, *, default=None, latex: str | None = None,
               description: str = "") -> sympy.ImmutableMatrix:
        """A constant real ``rows × cols`` matrix (square by default) with entries ``name_ij``, e.g. A of ẋ = Ax.

        Any real entries are admissible (no symmetry, no sign); ``--set "A=[[0,1],[-2,-3]]"`` sets it.

        Examples
        --------
        >>> P = Parameters()
        >>> A = P.matrix("A", 2, default=[[0, 1], [-2, -3]])
        >>> A
        Matrix([
        [A_11, A_12],
        [A_21, A_22]])
        >>> P.resolve({})["A"]
        Matrix([
        [ 0,  1],
        [-2, -3]])
        >>> P["A"].check(sympy.Matrix([[1, 2, 3]]))
        Traceback (most recent call last):
        ...
        lkverify.errors.InputError: A: expected a 2x2 matrix, got a 1x3 one
        """
        cols = rows if cols is None else cols
        if not (isinstance(rows, int) and isinstance(cols, int) and rows > 0 and cols > 0):
            raise InputError(f"{name}: expected positive integer dimensions, got {rows}x{cols}")
        syms = [[sympy.Symbol(f"{name}_{i + 1}{j + 1}", real=True) for j in range(cols)] for i in range(rows)]
        m = sympy.ImmutableMatrix(syms)
        if default is not None and not isinstance(default, sympy.MatrixBase):
            default = sympy.ImmutableMatrix(default) if isinstance(default, (list, tuple)) else default
        return self._add(ParameterSpec(name, ParameterKind.MATRIX, m, tuple(m), default, latex or name, description,
                                       (rows, cols)))

    def diagonal_matrix(self, name: str, entries: Sequence[str], *, default=None, latex: str | None = None,
                        description: str = "") -> sympy.ImmutableMatrix:
        """A constant diagonal matrix with positive entries named ``entries`` (e.g. Θ = diag(A, B, C))."""
        syms = tuple(sympy.Symbol(e, positive=True) for e in entries)
        m = sympy.ImmutableMatrix(sympy.diag(*syms))
        return self._add(ParameterSpec(name, ParameterKind.DIAGONAL, m, syms, default, latex or name, description,
                                       (len(syms), len(syms))))

    def unit_vector(self, name: str, n: int = 3, *, default=None, latex: str | None = None,
                    description: str = "") -> sympy.ImmutableMatrix:
        """A constant unit vector with components ``name_x, name_y, name_z``."""
        comps = ("x", "y", "z") if n == 3 else tuple(str(i + 1) for i in range(n))
        syms = tuple(sympy.Symbol(f"{name}_{c}", real=True) for c in comps)
        m = sympy.ImmutableMatrix(syms)
        return self._add(ParameterSpec(name, ParameterKind.UNIT_VECTOR, m, syms, default, latex or name, description, (n, 1)))

    def orthonormal(self, *names: str) -> None:
        """Declare already-declared constant unit vectors mutually orthogonal."""
        for n in names:
            if n not in self._specs or self._specs[n].kind is not ParameterKind.UNIT_VECTOR:
                raise InputError(f"orthonormal(): {n!r} is not a declared unit vector")
        self._groups.append(tuple(names))

    def coefficient(self, name: str, *, default=None, latex: str | None = None,
                    description: str = "") -> sympy.FunctionClass:
        """A time-varying coefficient h(t); formulas write ``h(t)``."""
        f = sympy.Function(name, real=True)
        return self._add(ParameterSpec(name, ParameterKind.COEFFICIENT, f, (f,), default, latex or name, description))

    def kernel(self, name: str, *, default=None, latex: str | None = None, description: str = "") -> sympy.FunctionClass:
        """A scalar memory kernel g(ζ), ζ ≥ 0; formulas write ``g(zeta)`` or ``g(t - xi)``."""
        f = sympy.Function(name, real=True)
        return self._add(ParameterSpec(name, ParameterKind.KERNEL, f, (f,), default, latex or name, description))

    # -- queries ---------------------------------------------------------------------------
    @property
    def names(self) -> list[str]:
        return list(self._specs)

    def __iter__(self):
        return iter(self._specs.values())

    def __getitem__(self, name: str) -> ParameterSpec:
        return self._specs[name]

    def __contains__(self, name: str) -> bool:
        return name in self._specs

    def constraint_polynomials(self) -> list[sympy.Expr]:
        """Polynomials vanishing for admissible constant vectors (‖r‖ = 1, rᵢ·rⱼ = 0)."""
        polys = [dot(s.obj, s.obj) - 1 for s in self._specs.values() if s.kind is ParameterKind.UNIT_VECTOR]
        for group in self._groups:
            for i, a in enumerate(group):
                for b in group[i + 1:]:
                    polys.append(dot(self._specs[a].obj, self._specs[b].obj))
        return polys

    def resolve(self, given: Mapping[str, object], *, use_defaults: bool = True) -> dict[str, object]:
        """Check user values (by name), fill in defaults; return name → checked value.

        Raises
        ------
        InputError
            For an unknown name (with close names suggested) or an inadmissible value.
        """
        import difflib

        values = ResolvedValues()
        floated = set(getattr(given, "from_float", ()))
        for name, value in given.items():
            if name not in self._specs:
                close = difflib.get_close_matches(name, self.names, n=3)
                hint = f"; did you mean {', '.join(close)}?" if close else f"; known: {', '.join(self.names)}"
                raise InputError(f"{name}: no such parameter{hint}")
            if _has_float(value):
                floated.add(name)
            values[name] = self._specs[name].check(_coerce(value, name))
        if use_defaults:
            for spec in self._specs.values():
                if spec.name not in values and spec.default is not None:
                    values[spec.name] = spec.default
        for group in self._groups:
            present = [n for n in group if n in values]
            for i, a in enumerate(present):
                for b in present[i + 1:]:
                    if sympy.simplify(dot(values[a], values[b])) != 0:
                        raise InputError(f"{a}, {b}: expected orthogonal unit vectors, got {a}·{b} = "
                                         f"{_fmt(sympy.simplify(dot(values[a], values[b])))}")
        values.from_float = frozenset(floated & set(values))
        return values

    def float_symbols(self, values: Mapping[str, object]) -> frozenset:
        """The atoms of the parameters whose values came from floating-point numbers.

        A result that depends on them went through floating point and is never ``exact``
        (see :mod:`lkverify.status`).
        """
        out: set = set()
        for name in getattr(values, "from_float", ()):
            out.update(self._specs[name].symbols)
        return frozenset(out)

    def substitution(self, values: Mapping[str, object]) -> dict:
        """The atom replacement for checked values (see :meth:`resolve`)."""
        sub: dict = {}
        for name, value in values.items():
            sub.update(self._specs[name].substitution(value))
        return sub


class ResolvedValues(dict):
    """Checked parameter values by name; ``from_float`` names those given as floats."""

    from_float: frozenset = frozenset()


def _has_float(value) -> bool:
    if isinstance(value, (float, np.floating, sympy.Float)):
        return True
    if isinstance(value, (list, tuple)):
        return any(_has_float(v) for v in value)
    if isinstance(value, sympy.MatrixBase):
        return any(isinstance(v, sympy.Float) for v in value)
    if isinstance(value, np.ndarray):
        return value.dtype.kind == "f"
    if isinstance(value, sympy.Basic):
        return bool(value.atoms(sympy.Float))
    return False


def _coerce(value, name: str = "value"):
    """Accept Python numbers, lists and strings (parsed safely) as values."""
    if isinstance(value, str):
        from .parse import parse_value

        return parse_value(value, name=name, variables={"t": _t, "zeta": _zeta})
    if isinstance(value, (list, tuple)):
        return _coerce(sympy.ImmutableMatrix(value), name)
    if isinstance(value, (float, np.floating, sympy.Float)):
        # a float is taken at its exact binary value (0.5 → 1/2, 0.1 → 3602879701896397/2**55),
        # never snapped to a "nearby" simple number; text such as "0.1" is read as exactly 1/10
        if not np.isfinite(float(value)):
            return sympy.nan
        return sympy.Rational(sympy.Float(value)) if isinstance(value, sympy.Float) else sympy.Rational(float(value))
    if isinstance(value, sympy.MatrixBase) and any(x.atoms(sympy.Float) for x in value):
        return value.applyfunc(lambda x: _coerce(x, name))
    if isinstance(value, sympy.Basic) and value.atoms(sympy.Float):
        return value.xreplace({f: sympy.Rational(f) for f in value.atoms(sympy.Float)})
    return value


def apply_substitution(expr, sub: Mapping):
    """Replace parameter atoms in ``expr`` (symbols by values, functions by Lambdas)."""
    funcs = {k: v for k, v in sub.items() if isinstance(k, sympy.FunctionClass)}
    syms = {k: v for k, v in sub.items() if not isinstance(k, sympy.FunctionClass)}
    if funcs and isinstance(expr, (sympy.Basic, sympy.MatrixBase)):
        # the two rewrites below walk and rebuild the whole tree; one traversal tells whether either has work
        found = expr.atoms(sympy.Function, sympy.Derivative, sympy.Subs)
        if not any(isinstance(e, (sympy.Derivative, sympy.Subs)) or e.func in funcs for e in found):
            funcs = {}
    if funcs:
        expr = expr.replace(lambda e: isinstance(e, sympy.Function) and e.func in funcs,
                            lambda e: funcs[e.func](*e.args))
        # derivatives of the replaced functions (ḣ(t) of a time-varying delay) are evaluated;
        # derivatives of states stay as they are
        expr = expr.replace(lambda e: isinstance(e, (sympy.Derivative, sympy.Subs))
                            and not e.atoms(AppliedUndef),
                            lambda e: e.doit())
    if syms:
        expr = expr.xreplace(syms)
    return expr
