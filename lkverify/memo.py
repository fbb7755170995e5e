"""One small in-process cache class: bounded, least recently used out first.

The expensive certified sub-results (a template supremum, an identity proof, a compiled
kernel) are kept per process in a :class:`Memo`.  ``functools.lru_cache`` would keep every
result, but only *decided* ones may be reused (a supremum certified without a wall-clock cap,
an identity proved or refuted), so the callers decide what to store and this class only
bounds the memory.

Examples
--------
>>> m = Memo(2)
>>> m["a"] = 1; m["b"] = 2
>>> m.get("a")                       # "a" is now the most recently used
1
>>> m["c"] = 3                       # evicts "b", the least recently used
>>> sorted(m), "b" in m, len(m)
(['a', 'c'], False, 2)
>>> Memo(0)
Traceback (most recent call last):
    ...
lkverify.errors.InputError: Memo: expected a positive maxsize, got 0
"""

from __future__ import annotations

import threading
from collections import OrderedDict

from .errors import InputError

__all__ = ["Memo"]


class Memo:
    """A bounded mapping that evicts the least recently used entry (thread-safe)."""

    def __init__(self, maxsize: int):
        if not isinstance(maxsize, int) or maxsize < 1:
            raise InputError(f"Memo: expected a positive maxsize, got {maxsize!r}")
        self.maxsize = maxsize
        self._data: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key, default=None):
        with self._lock:
            if key not in self._data:
                return default
            self._data.move_to_end(key)
            return self._data[key]

    def __getitem__(self, key):
        with self._lock:
            value = self._data[key]
            self._data.move_to_end(key)
            return value

    def __setitem__(self, key, value) -> None:
        with self._lock:
            self._data[key] = value
            self._data.move_to_end(key)
            while len(self._data) > self.maxsize:
                self._data.popitem(last=False)

    def owned(self, owner, key=(), default=None):
        """The value :meth:`keep` stored for ``owner`` (an object, by identity) and ``key``, or ``default``.

        For results that belong to an object without a usable hash or equality (a claim, a system,
        a job): the entry holds the object itself, so its ``id`` is not reused while the entry lives.

        >>> m, owner = Memo(4), object()
        >>> m.keep(owner, "k", 1); m.owned(owner, "k"), m.owned(object(), "k", "none")
        (1, 'none')
        """
        hit = self.get((id(owner), key))
        return hit[1] if hit is not None and hit[0] is owner else default

    def keep(self, owner, key, value) -> None:
        """Store ``value`` for ``owner`` and ``key`` (see :meth:`owned`)."""
        self[(id(owner), key)] = (owner, value)

    def __contains__(self, key) -> bool:
        return key in self._data

    def __len__(self) -> int:
        return len(self._data)

    def __iter__(self):
        return iter(list(self._data))

    def pop(self, key, *default):
        with self._lock:
            return self._data.pop(key, *default)

    def clear(self) -> None:
        with self._lock:
            self._data.clear()
