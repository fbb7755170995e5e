"""Gain grids: ``NAME=START:STOP:N`` read exactly, and the points they span.

A grid axis is ``N`` equally spaced values from ``START`` to ``STOP`` (both included;
``N = 1`` is ``START`` alone).  The values are exact rationals (decimal literals are read
as fractions, as ``--set`` reads them), so a grid value such as ``b = 2`` is the same number
as the paper's ``b = 2`` and hypotheses are decided exactly at it.  Several axes span the
Cartesian product, the first axis varying slowest (row-major), so point ``k`` of a grid is
the same point whatever the number of workers or the chunk size.

>>> g = Grid.parse(["b=-1:1:3", "h=0.5:1:2"])
>>> g.names, g.shape, g.size
(('b', 'h'), (3, 2), 6)
>>> g.point(3)
{'b': 0, 'h': 1}
>>> g.floats()[:2].tolist()
[[-1.0, 0.5], [-1.0, 1.0]]
>>> Grid.parse(["b=0:1:0"])
Traceback (most recent call last):
    ...
lkverify.errors.InputError: --grid b=0:1:0: a grid of zero points; expected N ≥ 1 points, e.g. b=0:1:11
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np
import sympy

from ..declare.parse import parse_assignment, parse_value
from ..errors import InputError

__all__ = ["Axis", "Grid", "MAX_POINTS"]

#: the most points one sweep takes (the table holds one row per point)
MAX_POINTS = 10**7


@dataclasses.dataclass(frozen=True)
class Axis:
    """One swept name: ``n`` values from ``start`` to ``stop`` (exact rationals).

    >>> Axis.parse("h=0.1:2:3").values
    (1/10, 21/20, 2)
    """

    name: str
    start: sympy.Rational
    stop: sympy.Rational
    n: int

    @classmethod
    def parse(cls, text: str) -> "Axis":
        """Read ``NAME=START:STOP:N`` (START, STOP numbers read exactly; N a positive integer)."""
        name, value = parse_assignment(text, option="--grid")
        where = f"--grid {text.strip()}"
        parts = value.split(":")
        if len(parts) != 3:
            raise InputError(f"{where}: expected NAME=START:STOP:N (three fields separated by ':'), got "
                             f"{len(parts)} field(s); e.g. {name}=0:1:11")
        start, stop = (_number(p, where, what) for p, what in zip(parts[:2], ("START", "STOP")))
        n = _count(parts[2], where, name)
        if n > 1 and start == stop:
            raise InputError(f"{where}: START = STOP with N = {n} repeats one value; expected START ≠ STOP, "
                             f"or N = 1 for a single value")
        return cls(name, start, stop, n)

    @property
    def values(self) -> tuple:
        """The exact values, ``start`` first."""
        if self.n == 1:
            return (self.start,)
        step = (self.stop - self.start) / (self.n - 1)
        return tuple(self.start + k * step for k in range(self.n))

    def text(self) -> str:
        return f"{self.name}={self.start}:{self.stop}:{self.n}"


@dataclasses.dataclass(frozen=True)
class Grid:
    """The Cartesian product of the axes, the first axis varying slowest.

    Raises
    ------
    InputError
        No axis, a name swept twice, or more than :data:`MAX_POINTS` points.

    Examples
    --------
    >>> g = Grid.parse(["a=0:1:3", "b=1:2:2"])
    >>> g.size, g.point(5)
    (6, {'a': 1, 'b': 2})
    """

    axes: tuple

    def __post_init__(self):
        if not self.axes:
            raise InputError("--grid: expected at least one axis NAME=START:STOP:N, got none; e.g. --grid b=-3:3:61")
        names = [a.name for a in self.axes]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise InputError(f"--grid: {', '.join(twice)} swept twice; expected each name once")
        if self.size > MAX_POINTS:
            raise InputError(f"--grid: {self.size:.3g} points; expected at most {MAX_POINTS:.0e}; use fewer points "
                             f"per axis")

    @classmethod
    def parse(cls, texts: Sequence[str]) -> "Grid":
        return cls(tuple(Axis.parse(t) for t in texts))

    @property
    def names(self) -> tuple:
        return tuple(a.name for a in self.axes)

    @property
    def shape(self) -> tuple:
        return tuple(a.n for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def index(self, k: int) -> tuple:
        """The axis indices of point ``k``."""
        return tuple(int(i) for i in np.unravel_index(k, self.shape))

    def point(self, k: int) -> dict:
        """Point ``k`` as name → exact value."""
        return {a.name: a.values[i] for a, i in zip(self.axes, self.index(k))}

    def floats(self, indices=None) -> np.ndarray:
        """Points (all, or those of ``indices``) as an (N, len(axes)) float array."""
        idx = np.arange(self.size) if indices is None else np.asarray(indices, dtype=np.int64)
        cols = np.unravel_index(idx, self.shape)
        return np.stack([np.array([float(v) for v in a.values])[c] for a, c in zip(self.axes, cols)], axis=1)

    def exact_texts(self) -> dict:
        """Each axis's values at every point as exact strings (``"7/10"``), name → array of str.

        >>> Grid.parse(["h=0.7:1.4:2"]).exact_texts()["h"].tolist()
        ['7/10', '7/5']
        """
        cols = np.unravel_index(np.arange(self.size), self.shape)
        return {a.name: np.array([str(v) for v in a.values], dtype=object)[c] for a, c in zip(self.axes, cols)}

    def text(self) -> list:
        return [a.text() for a in self.axes]


def _number(text: str, where: str, what: str) -> sympy.Rational:
    value = parse_value(text, name=f"{where}: {what}", option="--grid")
    if not (isinstance(value, sympy.Expr) and value.is_Rational):
        raise InputError(f"{where}: {what} = {text.strip()!r}; expected a rational number such as 0.5 or -3 "
                         f"(read exactly)")
    return value


def _count(text: str, where: str, name: str) -> int:
    text = text.strip()
    if not text.isdigit():
        raise InputError(f"{where}: N = {text!r}; expected a whole number of points ≥ 1, e.g. {name}=0:1:11")
    n = int(text)
    if n < 1:
        raise InputError(f"{where}: a grid of zero points; expected N ≥ 1 points, e.g. {name}=0:1:11")
    return n
