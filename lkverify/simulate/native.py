"""SymPy expressions compiled to native code with llvmlite: the generated right-hand sides of the compiled integrator.

:func:`native_source` prints straight-line expressions (after :func:`sympy.cse`) as an LLVM IR
module of functions with one C signature, :data:`NATIVE_SIGNATURE`::

    void f(double t, double *y, double *Z, double *p, double *out)

(``Z`` flat: the delayed value of state ``i`` at lag ``k`` is ``Z[k * n_states + i]``), and
:func:`load` compiles the module with LLVM's MCJIT (about 15 ms for a 12-state system, against
0.3–0.5 s for numba compiling the same function) and returns objects numba's kernel calls as
first-class functions (the wrapper address protocol).  The IR is a string: it pickles with the
:class:`~lkverify.simulate.family.CompiledFamily` it belongs to, and each process compiles it once.

Semantics are IEEE (division by zero gives ±inf or nan, a negative base to a fractional power
nan, as numba's ``error_model="numpy"``); no fast-math.  Printed: numbers, symbols, ``+``, ``*``,
powers (integer powers by multiplication, ``1/2`` by ``sqrt``, others by ``pow``), ``exp``, ``log``,
the trigonometric and hyperbolic functions and their inverses, ``Abs``, ``sign``, ``Max``, ``Min``,
``floor``, ``ceiling`` and ``Piecewise`` with relational conditions.  Anything else raises
:class:`NotPrintable` (the caller falls back to numba compiling the Python source).

SymPy's own ``sympy.printing.llvmjitcode`` does this for single functions but fails to import
with llvmlite ≥ 0.44 (it calls the removed ``llvmlite.binding.initialize``), hence this module.

Examples
--------
>>> import ctypes, sympy
>>> y0, y1, p0 = sympy.symbols("y_0 y_1 p_0", real=True)
>>> text = native_source({"rhs": [-p0 * y1, y0 ** 2 + sympy.sqrt(y1)]}, {y0: ("y", 0), y1: ("y", 1), p0: ("p", 0)})
>>> funcs = load(text)
>>> y, p, out = (ctypes.c_double * 2)(3.0, 4.0), (ctypes.c_double * 1)(0.5), (ctypes.c_double * 2)()
>>> funcs["rhs"].ctypes(0.0, y, y, p, out); list(out)
[-2.0, 11.0]
"""

from __future__ import annotations

import ctypes
import importlib
import threading
from collections.abc import Mapping, Sequence

import sympy

__all__ = ["NATIVE_SIGNATURE", "NativeFunction", "NotPrintable", "load", "native_source"]

#: the C signature of every generated function: f(t, y, Z, p, out)
NATIVE_SIGNATURE = "void(double, double*, double*, double*, double*)"
_ARGS = ("t", "y", "Z", "p", "out")
_UNARY = {  # SymPy function → (LLVM intrinsic or libm name)
    sympy.exp: "llvm.exp.f64", sympy.log: "llvm.log.f64", sympy.sin: "llvm.sin.f64", sympy.cos: "llvm.cos.f64",
    sympy.tan: "tan", sympy.asin: "asin", sympy.acos: "acos", sympy.atan: "atan", sympy.sinh: "sinh",
    sympy.cosh: "cosh", sympy.tanh: "tanh", sympy.asinh: "asinh", sympy.acosh: "acosh", sympy.atanh: "atanh",
    sympy.Abs: "llvm.fabs.f64", sympy.floor: "llvm.floor.f64", sympy.ceiling: "llvm.ceil.f64",
}
_COMPARE = {sympy.StrictLessThan: "<", sympy.LessThan: "<=", sympy.StrictGreaterThan: ">",
            sympy.GreaterThan: ">=", sympy.Equality: "==", sympy.Unequality: "!="}


class NotPrintable(ValueError):
    """An expression :func:`native_source` cannot print (the message names the node)."""


class NativeFunction:
    """One compiled function: numba calls it as a first-class function (a ``numba.types.WrapperAddressProtocol``).

    :func:`load` returns instances of a subclass that also derives from numba's protocol class (created
    on first use, so that printing IR does not import numba).

    Attributes
    ----------
    name : str
    address : int
        Its machine-code address (valid while the object lives: it holds the execution engine).
    ctypes : ctypes function
        The same function callable from Python (for tests and doctests).
    """

    def __init__(self, name: str, address: int, engine):
        self.name, self.address, self._engine = name, int(address), engine
        double_p = ctypes.POINTER(ctypes.c_double)
        self.ctypes = ctypes.CFUNCTYPE(None, ctypes.c_double, double_p, double_p, double_p, double_p)(self.address)

    def __wrapper_address__(self) -> int:
        return self.address

    def signature(self):
        from numba import types

        ptr = types.CPointer(types.float64)
        return types.void(types.float64, ptr, ptr, ptr, ptr)

    def __repr__(self) -> str:
        return f"NativeFunction({self.name!r}, address={self.address:#x})"


def native_source(functions: Mapping[str, Sequence[sympy.Expr]], arguments: Mapping[sympy.Symbol, tuple], *,
                  time: sympy.Symbol | None = None) -> str:
    """LLVM IR of ``name → expressions`` (each written to ``out[i]``), common subexpressions eliminated.

    ``arguments`` maps each symbol to ``(pointer, index)`` with pointer one of ``"y"``, ``"Z"``, ``"p"``;
    ``time`` is the symbol read from the argument ``t``.  Raises :class:`NotPrintable` for a node outside the
    module docstring's list.
    """
    from llvmlite import ir

    module = ir.Module(name="lkverify")
    for name, exprs in functions.items():
        _Function(module, name, list(exprs), arguments, time).emit()
    return str(module)


_INIT = threading.Lock()
_READY = []


def _binding():
    """llvmlite's binding, the native target initialised once; a new target machine per engine (it owns it)."""
    from llvmlite import binding as llvm

    with _INIT:
        if not _READY:
            try:                        # needed before llvmlite 0.45; deprecated (raises) after it
                llvm.initialize()
            except RuntimeError:
                pass
            llvm.initialize_native_target()
            llvm.initialize_native_asmprinter()
            _READY.append(llvm.Target.from_default_triple())
    return llvm, _READY[0].create_target_machine(opt=2)


def load(source: str) -> dict:
    """Compile the IR ``source`` of :func:`native_source` (MCJIT, ``-O2``); ``name → NativeFunction``."""
    llvm, machine = _binding()
    mod = llvm.parse_assembly(source)
    mod.verify()
    engine = llvm.create_mcjit_compiler(mod, machine)
    engine.finalize_object()
    cls = _wrapper_class()
    return {f.name: cls(f.name, engine.get_function_address(f.name), engine)
            for f in mod.functions if not f.is_declaration}


_WRAPPER = []


def _wrapper_class():
    """NativeFunction with numba's WrapperAddressProtocol as a base (numba types it as a first-class function)."""
    if not _WRAPPER:
        importlib.import_module("numba.experimental.function_type")   # registers the typing of protocol objects
        from numba.core.types import WrapperAddressProtocol

        _WRAPPER.append(type("NativeFunction", (NativeFunction, WrapperAddressProtocol), {}))
    return _WRAPPER[0]


class _Function:
    """The IR of one function: arguments loaded on first use, then the CSE'd expressions in order."""

    def __init__(self, module, name, exprs, arguments, time):
        from llvmlite import ir

        self.ir, self.module, self.arguments, self.time = ir, module, arguments, time
        self.dbl = ir.DoubleType()
        ptr = self.dbl.as_pointer()
        self.fn = ir.Function(module, ir.FunctionType(ir.VoidType(), [self.dbl, ptr, ptr, ptr, ptr]), name=name)
        for arg, label in zip(self.fn.args, _ARGS):
            arg.name = label
        self.b = ir.IRBuilder(self.fn.append_basic_block("entry"))
        self.values: dict = {}
        self.exprs = exprs

    def emit(self) -> None:
        repl, reduced = sympy.cse(self.exprs, symbols=sympy.numbered_symbols("_cse_"), order="none")
        for sym, e in repl:
            self.values[sym] = self.value(e)
        out = self.fn.args[4]
        for i, e in enumerate(reduced):
            self.b.store(self.value(e), self.b.gep(out, [self.ir.Constant(self.ir.IntType(64), i)]))
        self.b.ret_void()

    # -- nodes --------------------------------------------------------------------------------
    def const(self, x: float):
        return self.ir.Constant(self.dbl, float(x))

    def call(self, name: str, args):
        fn = self.module.globals.get(name)
        if fn is None:
            fn = self.ir.Function(self.module, self.ir.FunctionType(self.dbl, [self.dbl] * len(args)), name=name)
        return self.b.call(fn, list(args))

    def value(self, e):
        if e in self.values:
            return self.values[e]
        v = self._value(e)
        self.values[e] = v
        return v

    def _value(self, e):
        b = self.b
        if e.is_Symbol:
            return self.symbol(e)
        if e.is_Number or e.is_NumberSymbol:
            return self.const(e)
        if e.is_Add:
            terms = [self.value(a) for a in e.args]
            acc = terms[0]
            for v in terms[1:]:
                acc = b.fadd(acc, v)
            return acc
        if e.is_Mul:
            return self.product(e)
        if e.is_Pow:
            return self.power(e.base, e.exp)
        if isinstance(e, sympy.Piecewise):
            return self.piecewise(e)
        if e.func in _UNARY and len(e.args) == 1:
            return self.call(_UNARY[e.func], [self.value(e.args[0])])
        if e.func is sympy.atan2:
            return self.call("atan2", [self.value(a) for a in e.args])
        if isinstance(e, (sympy.Max, sympy.Min)):
            vals = [self.value(a) for a in e.args]
            acc = vals[0]
            op = ">" if isinstance(e, sympy.Max) else "<"
            for v in vals[1:]:
                acc = b.select(b.fcmp_ordered(op, acc, v), acc, v)
            return acc
        if e.func is sympy.sign:
            x = self.value(e.args[0])
            zero = self.const(0)
            return b.select(b.fcmp_ordered(">", x, zero), self.const(1),
                            b.select(b.fcmp_ordered("<", x, zero), self.const(-1), x))
        raise NotPrintable(f"cannot print {type(e).__name__} ({e}) as native code")

    def symbol(self, s):
        if s == self.time:
            return self.fn.args[0]
        where = self.arguments.get(s)
        if where is None:
            raise NotPrintable(f"symbol {s} is not an argument (expected y_i, Z_k_i, p_j or t)")
        ptr = self.fn.args[_ARGS.index(where[0])]
        return self.b.load(self.b.gep(ptr, [self.ir.Constant(self.ir.IntType(64), int(where[1]))]))

    def product(self, e):
        num, den = [], []
        for f in e.args:
            if f.is_Pow and f.exp.is_Integer and f.exp < 0:
                den.append(self.power(f.base, -f.exp))
            elif f.is_Rational and not f.is_Integer and f.p == 1:
                den.append(self.const(f.q))
            else:
                num.append(self.value(f))
        acc = num[0] if num else self.const(1)
        for v in num[1:]:
            acc = self.b.fmul(acc, v)
        for v in den:
            acc = self.b.fdiv(acc, v)
        return acc

    def power(self, base, exp):
        b = self.b
        if exp.is_Integer:
            n = int(exp)
            if n < 0:
                return b.fdiv(self.const(1), self.power(base, -exp))
            if n == 0:
                return self.const(1)
            x, acc = self.value(base), None
            while n:                          # square and multiply
                if n & 1:
                    acc = x if acc is None else b.fmul(acc, x)
                n >>= 1
                if n:
                    x = b.fmul(x, x)
            return acc
        if exp == sympy.Rational(1, 2):
            return self.call("llvm.sqrt.f64", [self.value(base)])
        if exp == sympy.Rational(-1, 2):
            return b.fdiv(self.const(1), self.call("llvm.sqrt.f64", [self.value(base)]))
        if base == sympy.E:
            return self.call("llvm.exp.f64", [self.value(exp)])
        return self.call("llvm.pow.f64", [self.value(base), self.value(exp)])

    def condition(self, c):
        b, ir = self.b, self.ir
        if c is sympy.true:
            return ir.Constant(ir.IntType(1), 1)
        if c is sympy.false:
            return ir.Constant(ir.IntType(1), 0)
        if type(c) in _COMPARE:
            return b.fcmp_ordered(_COMPARE[type(c)], self.value(c.lhs), self.value(c.rhs))
        if isinstance(c, (sympy.And, sympy.Or)):
            vals = [self.condition(a) for a in c.args]
            acc = vals[0]
            for v in vals[1:]:
                acc = b.and_(acc, v) if isinstance(c, sympy.And) else b.or_(acc, v)
            return acc
        if isinstance(c, sympy.Not):
            return b.not_(self.condition(c.args[0]))
        raise NotPrintable(f"cannot print the condition {c} as native code")

    def piecewise(self, e):
        """The first true branch (all branches evaluated: straight-line code; nan where none holds)."""
        acc = self.const(float("nan"))
        for expr, cond in reversed(e.args):
            acc = self.b.select(self.condition(cond), self.value(expr), acc)
        return acc
