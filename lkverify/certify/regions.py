"""Regions: boxes of real variables parsed from ``{symbol: (lo, hi)}``, and exact numbers.

Examples
--------
>>> import sympy
>>> exact_number(0.1, "x") == sympy.Rational(3602879701896397, 36028797018963968)   # a float is exact binary
True
"""

from __future__ import annotations

import dataclasses
import fractions
import math
from collections.abc import Mapping, Sequence

import sympy

from ..errors import InputError
from .intervals import float_down, float_up
from .intervals.convert import _sympy_number_ball

__all__ = ["Region", "exact_number", "parse_region", "prove_zero"]


def exact_number(value, what: str):
    """A user number as a SymPy number; a float is taken at its exact binary value (see :mod:`lkverify.status`)."""
    if isinstance(value, bool):
        raise InputError(f"{what}: expected a number, got {value!r}")
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InputError(f"{what}: expected a finite number, got {value!r}")
        return sympy.Rational(value)
    if isinstance(value, (int, fractions.Fraction)):
        return sympy.Rational(value)
    if isinstance(value, sympy.Float):
        return sympy.Rational(value)
    if isinstance(value, str):
        raise InputError(f"{what}: expected a number, got the string {value!r}; "
                         f"pass a number or a SymPy expression such as sympy.pi")
    try:
        out = sympy.sympify(value, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"{what}: expected a number, got {value!r}") from exc
    if not (isinstance(out, sympy.Expr) and out.is_number) or out.free_symbols:
        raise InputError(f"{what}: expected a number, got {out}")
    if out.is_real is False or not out.is_finite:
        raise InputError(f"{what}: expected a finite real number, got {out}")
    return out


@dataclasses.dataclass(frozen=True)
class Region:
    """A box of real variables, as parsed from ``{symbol: (lo, hi)}``.

    ``bounds`` keeps the exact SymPy end points; ``lo_out``/``hi_out`` are floats
    covering the box (the branch and bound's root), ``lo_in``/``hi_in`` floats
    inside it (sample and test points).

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x")
    >>> r = parse_region({x: (0, sympy.pi)}, [x])
    >>> r.lo_out[0] <= 0 and r.hi_in[0] < r.hi_out[0]      # π is between two floats
    True
    """

    variables: tuple
    bounds: tuple            # SymPy numbers (lo, hi) per variable
    lo_out: tuple            # floats ≤ lo  (the boxes of the branch and bound cover the region)
    hi_out: tuple            # floats ≥ hi
    lo_in: tuple             # floats ≥ lo  (sample and test points stay inside the region)
    hi_in: tuple             # floats ≤ hi

    @property
    def names(self) -> tuple:
        return tuple(str(v) for v in self.variables)

    @property
    def signs(self) -> list:
        return [(lo >= 0, lo > 0) for lo in self.lo_out]

    def text(self) -> str:
        return "{" + ", ".join(f"{v} ∈ [{lo}, {hi}]" for v, (lo, hi) in zip(self.variables, self.bounds)) + "}"

    def contains(self, point: Sequence[float]) -> bool:
        return all(lo <= x <= hi for x, lo, hi in zip(point, self.lo_in, self.hi_in))

    def point_dict(self, point) -> dict:
        return {name: float(x) for name, x in zip(self.names, point)}


def parse_region(box, exprs: Sequence[sympy.Expr], what: str = "box") -> Region:
    """Check a box ``{symbol: (lo, hi)}`` against the expressions' symbols; all problems in one InputError."""
    if not isinstance(box, Mapping):
        raise InputError(f"{what}: expected a mapping {{symbol: (lo, hi)}}, got {type(box).__name__}")
    problems = []
    variables, bounds, lo_out, hi_out, lo_in, hi_in = [], [], [], [], [], []
    for var, pair in box.items():
        if not isinstance(var, sympy.Symbol):
            problems.append(f"key {var!r} is not a sympy.Symbol")
            continue
        if not (isinstance(pair, Sequence) and not isinstance(pair, str) and len(pair) == 2):
            problems.append(f"{var}: expected a pair (lo, hi), got {pair!r}")
            continue
        try:
            lo, hi = (exact_number(v, f"{what} bound of {var}") for v in pair)
        except InputError as exc:
            problems.append(str(exc))
            continue
        lo_b, hi_b = _sympy_number_ball(lo), _sympy_number_ball(hi)
        if not (lo_b.is_finite() and hi_b.is_finite()):
            problems.append(f"{var}: bounds {lo}, {hi} are not finite")
            continue
        if lo_b > hi_b:
            problems.append(f"{var}: lower bound {lo} exceeds upper bound {hi}")
            continue
        lo_o, hi_o, lo_i, hi_i = float_down(lo_b), float_up(hi_b), float_up(lo_b), float_down(hi_b)
        if lo_i > hi_i:
            if lo == hi:
                problems.append(f"{var}: the zero-width range [{lo}, {hi}] has no float inside; "
                                f"substitute {var} = {lo} into the expression instead")
            else:
                problems.append(f"{var}: the range [{lo}, {hi}] is too narrow for float points")
            continue
        if var.is_nonnegative and lo_o < 0:
            problems.append(f"{var} is declared nonnegative but its range starts at {lo}")
        if var.is_positive and lo_o <= 0:
            problems.append(f"{var} is declared positive but its range starts at {lo}")
        variables.append(var)
        bounds.append((lo, hi))
        lo_out.append(lo_o), hi_out.append(hi_o), lo_in.append(lo_i), hi_in.append(hi_i)
    free = set().union(*(e.free_symbols for e in exprs)) if exprs else set()
    missing = free - set(variables)
    if missing:
        problems.append(f"symbols {sorted(map(str, missing))} have no range; add them to the {what} "
                        f"or substitute their values")
    if problems:
        raise InputError(f"{what}: " + "; ".join(problems))
    return Region(tuple(variables), tuple(bounds), tuple(lo_out), tuple(hi_out), tuple(lo_in),
                   tuple(hi_in))


def prove_zero(expr: sympy.Expr) -> bool:
    """True if SymPy reduces expr to 0 (a proof); False means 'not proved', not 'nonzero'."""
    for attempt in (lambda e: sympy.expand(e), sympy.cancel, sympy.simplify,
                    lambda e: sympy.simplify(sympy.expand_trig(e)),
                    lambda e: sympy.simplify(sympy.expand(sympy.expand_trig(e), trig=True))):
        try:
            if attempt(expr) == 0:
                return True
        except Exception:  # noqa: BLE001 -- a failed simplification proves nothing
            continue
    return False
