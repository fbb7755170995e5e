"""Time budgets: long work stops with ``undecided``, never hangs.

A :class:`Deadline` is checked cooperatively between steps (:meth:`Deadline.check`,
:attr:`Deadline.expired`); in the main thread :meth:`Deadline.enforced` also arms
``SIGALRM`` so that a single long SymPy call is interrupted too.

Enforced deadlines nest: a job-wide budget (``lkverify constants --budget``) may
enclose per-step budgets (one identity).  The interval timer is always armed for
the earliest of the enclosing deadlines, so an inner block never outlives an
outer budget.  Once an outer budget has run out, the alarm keeps firing every
:data:`RETRY_SECONDS` until the code has left that outer block, so a step that
catches :class:`BudgetExceeded` and carries on is interrupted again.

The operating system's interval timer cannot be armed arbitrarily far ahead
(``setitimer`` overflows ``time_t`` for about 1e300 s): it is armed at most
:data:`TIMER_CAP_SECONDS` ahead and re-armed when it fires before the deadline.
``Deadline(math.inf)`` is the same as ``Deadline(None)`` (unlimited).  The command
line accepts budgets up to :data:`MAX_BUDGET_SECONDS` and refuses larger ones.
"""

from __future__ import annotations

import contextlib
import math
import numbers
import signal
import sys
import threading
import time

__all__ = ["BudgetExceeded", "Deadline", "MAX_BUDGET_SECONDS", "TIMER_CAP_SECONDS", "RETRY_SECONDS"]

#: the largest ``--budget`` the command line accepts (seconds, about 11.6 days)
MAX_BUDGET_SECONDS = 1e6
#: the interval timer is never armed further ahead than this (it is re-armed when it fires early)
TIMER_CAP_SECONDS = 1e6
#: after an enclosing budget ran out, the alarm fires again at this interval until its block is left
RETRY_SECONDS = 0.05

_active: list = []          # enforced deadlines, outermost first (main thread only)
_saved_handler = [None]     # the SIGALRM handler before the outermost enforced block


class BudgetExceeded(Exception):
    """The time budget ran out; the result is ``undecided``."""


class Deadline:
    """A wall-clock budget in seconds (``None`` or ``math.inf`` = unlimited).

    Parameters
    ----------
    seconds : float or None
        A positive number of seconds; ``None`` or ``inf`` for no limit.

    Raises
    ------
    ValueError
        If ``seconds`` is not a positive number (zero, negative, NaN, not a number).

    Examples
    --------
    >>> d = Deadline(None)
    >>> d.check()  # never raises
    >>> d.remaining is None
    True
    >>> Deadline(float("inf")).seconds is None
    True
    >>> Deadline(1e300).remaining > 1e299      # far deadlines are fine; the timer is capped
    True
    """

    def __init__(self, seconds: float | None):
        if seconds is not None:
            if isinstance(seconds, bool) or not isinstance(seconds, numbers.Real) or not seconds > 0:
                raise ValueError(f"budget: expected a positive number of seconds (or None for no limit), "
                                 f"got {seconds!r}")
            seconds = None if math.isinf(seconds) else float(seconds)
        self.seconds = seconds
        self.start = time.monotonic()

    @property
    def remaining(self) -> float | None:
        """Seconds left (negative once spent), ``None`` when unlimited."""
        if self.seconds is None:
            return None
        return self.seconds - (time.monotonic() - self.start)

    @property
    def elapsed(self) -> float:
        """Seconds since the deadline was created."""
        return time.monotonic() - self.start

    @property
    def expired(self) -> bool:
        """True once the budget is spent."""
        r = self.remaining
        return r is not None and r <= 0

    def message(self) -> str:
        """The one-line reason used in :class:`BudgetExceeded`."""
        return f"time budget of {self.seconds:g} s exhausted"

    def check(self) -> None:
        """Raise :class:`BudgetExceeded` if the budget is spent."""
        if self.expired:
            raise BudgetExceeded(self.message())

    @contextlib.contextmanager
    def enforced(self):
        """Interrupt the enclosed block when this budget, or an enclosing one, runs out (main thread only).

        Raises
        ------
        BudgetExceeded
            On entry if this or an enclosing enforced budget is already spent, and from
            inside the block (at the next Python bytecode) when one runs out.
        """
        if threading.current_thread() is not threading.main_thread():
            self.check()
            yield
            return
        for d in (*_active, self):
            d.check()
        _block()
        try:
            if not _active:
                _saved_handler[0] = signal.signal(signal.SIGALRM, _on_alarm)
                _saved_hook[0] = sys.unraisablehook
                sys.unraisablehook = _quiet_unraisable
            _active.append(self)
            _arm()
        finally:
            _unblock()
        try:
            yield
        finally:
            _block()
            try:
                if self in _active:
                    _active.remove(self)
                if _active:
                    _arm()
                else:
                    signal.setitimer(signal.ITIMER_REAL, 0)
                    signal.signal(signal.SIGALRM, _saved_handler[0] or signal.SIG_DFL)
                    _saved_handler[0] = None
                    sys.unraisablehook = _saved_hook[0] or sys.__unraisablehook__
                    _saved_hook[0] = None
            finally:
                _unblock()


_saved_hook: list = [None]


def _quiet_unraisable(unraisable) -> None:
    """The alarm may fire inside code that cannot propagate exceptions (a finaliser, a Cython
    callback): its BudgetExceeded is then dropped silently, and the timer's retry raises it again
    at the next Python bytecode that can."""
    if isinstance(unraisable.exc_value, BudgetExceeded):
        return
    (_saved_hook[0] or sys.__unraisablehook__)(unraisable)


def _block():
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGALRM})


def _unblock():
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGALRM})


def _arm() -> None:
    """Arm the interval timer for the earliest active deadline (capped; at least a short retry)."""
    left = [d.remaining for d in _active if d.seconds is not None]
    if not left:
        signal.setitimer(signal.ITIMER_REAL, 0)
        return
    r = min(left)
    signal.setitimer(signal.ITIMER_REAL, RETRY_SECONDS if r <= 0 else min(r, TIMER_CAP_SECONDS))


def _on_alarm(signum, frame):
    expired = [d for d in _active if d.expired]
    _arm()  # re-arm: early wake-up of a capped timer, or the retry while an expired block is unwinding
    if expired:
        raise BudgetExceeded(expired[0].message())
