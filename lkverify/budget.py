"""Time budgets: long symbolic work stops with ``undecided``, never hangs.

A :class:`Deadline` is checked cooperatively between steps; in the main thread
it also arms ``SIGALRM`` so that a single long SymPy call is interrupted too.
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time

__all__ = ["BudgetExceeded", "Deadline"]


class BudgetExceeded(Exception):
    """The time budget ran out; the result is ``undecided``."""


class Deadline:
    """A wall-clock budget in seconds (``None`` = unlimited).

    >>> d = Deadline(None)
    >>> d.check()  # never raises
    >>> d.remaining is None
    True
    """

    def __init__(self, seconds: float | None):
        if seconds is not None and not seconds > 0:
            raise ValueError(f"budget must be a positive number of seconds, got {seconds!r}")
        self.seconds = seconds
        self.start = time.monotonic()

    @property
    def remaining(self) -> float | None:
        if self.seconds is None:
            return None
        return self.seconds - (time.monotonic() - self.start)

    def check(self) -> None:
        """Raise :class:`BudgetExceeded` if the budget is spent."""
        r = self.remaining
        if r is not None and r <= 0:
            raise BudgetExceeded(f"time budget of {self.seconds:g} s exhausted")

    @contextlib.contextmanager
    def enforced(self):
        """Interrupt the enclosed block when the budget runs out (main thread only)."""
        r = self.remaining
        if r is None or threading.current_thread() is not threading.main_thread():
            yield
            return
        if r <= 0:
            raise BudgetExceeded(f"time budget of {self.seconds:g} s exhausted")

        def handler(signum, frame):
            raise BudgetExceeded(f"time budget of {self.seconds:g} s exhausted")

        old = signal.signal(signal.SIGALRM, handler)
        signal.setitimer(signal.ITIMER_REAL, r)
        try:
            yield
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old)
