"""Boxes of parameters: closed intervals of scalar parameters over which a theorem is checked.

A :class:`ParameterBox` is a product of closed intervals ``name ∈ [lo, hi]`` with exact
rational ends (a float end is taken at its exact binary value and marks the name, so a
result that depends on it is at most ``certified``).  It is pure data: validation at
construction, the centre, the corners, a split in two, the fraction of a bigger box it
covers.  What is *proved* over a box is the business of :mod:`lkverify.catalogue.boxrun`.

Examples
--------
>>> B = parse_boxes(["b=-11/10:-9/10", "tau=9/10:11/10"])
>>> B.names, B.center()
(('b', 'tau'), {'b': -1, 'tau': 1})
>>> [str(piece) for piece in B.split()]
['b ∈ [-11/10, -1], tau ∈ [9/10, 11/10]', 'b ∈ [-1, -9/10], tau ∈ [9/10, 11/10]']
>>> B.split()[0].fraction_of(B)
1/2
>>> parse_boxes(["tau=2:1"])
Traceback (most recent call last):
...
lkverify.errors.InputError: --box tau=2:1: expected LO:HI with LO ≤ HI, got LO = 2 > HI = 1
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Iterable, Mapping

import sympy

from ..errors import InputError

__all__ = ["ParameterBox", "parse_box", "parse_boxes"]


def _end(value, where: str) -> tuple[sympy.Rational, bool]:
    """(exact rational, came from a float) of one end of an interval."""
    from .parameters import _has_float

    if isinstance(value, str):  # text is read exactly, as on the command line (0.9 is 9/10)
        from .parse import parse_value

        value = parse_value(value, name=where, option="--box")
    floated = _has_float(value)
    try:
        v = sympy.Rational(float(value)) if floated else sympy.sympify(value)  # a float: its exact binary value
    except (TypeError, ValueError, sympy.SympifyError):
        raise InputError(f"{where}: expected a number, got {value!r}") from None
    if isinstance(v, sympy.MatrixBase) or v.free_symbols or v.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo) \
            or not v.is_real:
        raise InputError(f"{where}: expected a finite real number, got {value}")
    if not v.is_Rational:
        raise InputError(f"{where}: expected a rational end such as 9/10 or 0.9, got {value} (an irrational end "
                         f"cannot be split exactly; give a rational just inside it)")
    return sympy.Rational(v), floated


@dataclasses.dataclass(frozen=True)
class ParameterBox:
    """A product of closed intervals of scalar parameters, ``name ∈ [lo, hi]``, ends exact rationals.

    Parameters
    ----------
    bounds : mapping
        Parameter name → ``(lo, hi)`` (numbers, exact strings or floats; lo ≤ hi).
    from_float : frozenset of str
        Names one of whose ends came from a float (filled in for float ends).

    Examples
    --------
    >>> B = ParameterBox({"tau": ("1/2", 1)})
    >>> B.bounds["tau"], B.width("tau"), B.is_point
    ((1/2, 1), 1/2, False)
    >>> ParameterBox({"tau": (0.5, 1)}).from_float
    frozenset({'tau'})
    >>> ParameterBox({})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: box: expected at least one NAME=LO:HI interval, got none
    """

    bounds: Mapping
    from_float: frozenset = frozenset()

    def __post_init__(self):
        if isinstance(self.bounds, ParameterBox):
            object.__setattr__(self, "from_float", self.bounds.from_float | frozenset(self.from_float))
            object.__setattr__(self, "bounds", self.bounds.bounds)
        if not isinstance(self.bounds, Mapping):
            raise InputError(f"box: expected a mapping name → (lo, hi), got {type(self.bounds).__name__}")
        if not self.bounds:
            raise InputError("box: expected at least one NAME=LO:HI interval, got none")
        out, floated = {}, set(self.from_float)
        for name, pair in self.bounds.items():
            where = f"--box {name}"
            if not isinstance(name, str) or not name.isidentifier():
                raise InputError(f"box: expected parameter names, got {name!r}")
            if isinstance(pair, str) or not isinstance(pair, Iterable):
                raise InputError(f"{where}: expected a pair (lo, hi), got {pair!r}")
            pair = tuple(pair)
            if len(pair) != 2:
                raise InputError(f"{where}: expected a pair (lo, hi), got {len(pair)} values")
            (lo, f_lo), (hi, f_hi) = _end(pair[0], where), _end(pair[1], where)
            if lo > hi:
                raise InputError(f"{where}={lo}:{hi}: expected LO:HI with LO ≤ HI, got LO = {lo} > HI = {hi}")
            if f_lo or f_hi:
                floated.add(name)
            out[name] = (lo, hi)
        object.__setattr__(self, "bounds", dict(out))
        object.__setattr__(self, "from_float", frozenset(floated))

    @property
    def names(self) -> tuple:
        return tuple(self.bounds)

    @property
    def is_point(self) -> bool:
        return all(lo == hi for lo, hi in self.bounds.values())

    def width(self, name: str) -> sympy.Rational:
        lo, hi = self.bounds[name]
        return hi - lo

    def center(self) -> dict:
        """name → the midpoint (exact)."""
        return {n: (lo + hi) / 2 for n, (lo, hi) in self.bounds.items()}

    def corners(self) -> list[dict]:
        """The 2^k corners (fewer when an interval is a point), as name → value."""
        axes = [sorted({lo, hi}) for lo, hi in self.bounds.values()]
        return [dict(zip(self.names, c)) for c in itertools.product(*axes)]

    def contains(self, point: Mapping) -> bool:
        return all(lo <= sympy.Rational(point[n]) <= hi for n, (lo, hi) in self.bounds.items())

    def widest(self, relative_to: "ParameterBox | None" = None) -> str:
        """The name whose interval is widest (relative to ``relative_to``'s widths); ties: the first."""
        def rel(n):
            ref = relative_to.width(n) if relative_to is not None else 1
            return self.width(n) / ref if ref else 0
        return max(self.names, key=rel)

    def split(self, name: str | None = None) -> tuple["ParameterBox", "ParameterBox"]:
        """The two halves along ``name`` (default: the widest interval)."""
        name = self.widest() if name is None else name
        lo, hi = self.bounds[name]
        if lo == hi:
            raise InputError(f"box: cannot split the point interval {name} = {lo}")
        mid = (lo + hi) / 2
        return (ParameterBox({**self.bounds, name: (lo, mid)}, self.from_float),
                ParameterBox({**self.bounds, name: (mid, hi)}, self.from_float))

    def fraction_of(self, outer: "ParameterBox") -> sympy.Rational:
        """This box's measure as a fraction of ``outer``'s (point intervals count as factor 1)."""
        out = sympy.S.One
        for n in self.names:
            w = outer.width(n)
            if w:
                out *= self.width(n) / w
        return out

    def intervals(self, symbols: Mapping) -> dict:
        """symbol → (lo, hi) for the given name → symbol map (the form interval arithmetic takes)."""
        return {symbols[n]: b for n, b in self.bounds.items()}

    def __str__(self) -> str:
        return ", ".join(f"{n} ∈ [{lo}, {hi}]" if lo != hi else f"{n} = {lo}" for n, (lo, hi) in self.bounds.items())

    def to_json(self) -> dict:
        return {n: [str(lo), str(hi)] for n, (lo, hi) in self.bounds.items()}


def parse_box(text: str, *, option: str = "--box") -> tuple[str, tuple]:
    """``'NAME=LO:HI'`` → ``(name, (lo, hi))`` parsed without executing anything.

    >>> parse_box("tau = 1/2 : 1")
    ('tau', (1/2, 1))
    >>> parse_box("tau=1")
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: --box tau=1: expected NAME=LO:HI, e.g. --box tau=1/2:1
    """
    from .parse import parse_assignment, parse_value

    name, rest = parse_assignment(text, option=option)
    parts = rest.split(":")
    if len(parts) != 2 or not all(p.strip() for p in parts):
        raise InputError(f"{option} {name}={rest}: expected NAME=LO:HI, e.g. {option} {name}=1/2:1")
    ends = tuple(parse_value(p.strip(), name=f"{option} {name}", option=option) for p in parts)
    return name, ends


def parse_boxes(texts: Iterable[str], *, option: str = "--box") -> ParameterBox:
    """Several ``NAME=LO:HI`` into one :class:`ParameterBox` (a name twice is an error)."""
    bounds: dict = {}
    for text in texts:
        name, ends = parse_box(text, option=option)
        if name in bounds:
            raise InputError(f"{option} {name}: given twice; give each parameter one interval")
        bounds[name] = ends
    return ParameterBox(bounds)
