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

Work limits, not wall-clock time, decide the catalogue's results.  Inside
:func:`work_limits` (every catalogue item's ``run`` enters it) the seconds of internal
ceilings -- a :class:`Deadline` created without ``cap=True``, a :class:`Budget`'s
``seconds`` read through :func:`ceiling` -- are ignored: each job stops at its
deterministic work limit (boxes, iterations, optimiser evaluations, starts, seeds), so a
verdict is the same on an idle and on a loaded machine.  The only wall-clock limit there is
the user's own cap (``--budget SECONDS``, ``Item.run(budget=…)``): a ``Deadline(…, cap=True)``,
enforced between the steps and by ``SIGALRM`` inside them; what it cuts is ``undecided``
with the phase it cut.  Outside :func:`work_limits` (a direct call of a checker with
``budget=``) every deadline is enforced as given.
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import math
import numbers
import signal
import sys
import threading
import time

from .errors import InputError, _OwnNames

__all__ = ["Accuracy", "Budget", "BudgetExceeded", "Deadline", "LOAD_LIMIT_SECONDS", "MAX_BUDGET_SECONDS",
           "TIMER_CAP_SECONDS", "RETRY_SECONDS", "ceiling", "wall_clock_ceilings", "work_limits"]

#: the largest ``--budget`` the command line accepts (seconds, about 11.6 days)
MAX_BUDGET_SECONDS = 1e6
#: default time limit for loading (importing) one proof file, in seconds (``--load-limit``; not a ``--budget``)
LOAD_LIMIT_SECONDS = 60.0
#: the interval timer is never armed further ahead than this (it is re-armed when it fires early)
TIMER_CAP_SECONDS = 1e6
#: after an enclosing budget ran out, the alarm fires again at this interval until its block is left
RETRY_SECONDS = 0.05

_active: list = []          # enforced deadlines, outermost first (main thread only)
_work_limits = contextvars.ContextVar("lkverify_work_limits", default=0)  # depth of work_limits() blocks


@contextlib.contextmanager
def work_limits():
    """Run a block on deterministic work limits: internal time ceilings are ignored inside it.

    A :class:`Deadline` created inside without ``cap=True`` is unlimited, and :func:`ceiling`
    returns None: only the jobs' own work limits (boxes, iterations, starts) and a user's cap
    (``Deadline(seconds, cap=True)``) stop the work.  Blocks nest.

    Examples
    --------
    >>> with work_limits():
    ...     Deadline(1e-9).seconds is None, Deadline(5, cap=True).seconds, ceiling(30.0), wall_clock_ceilings()
    (True, 5.0, None, False)
    >>> Deadline(5).seconds, ceiling(30.0), wall_clock_ceilings()
    (5.0, 30.0, True)
    """
    token = _work_limits.set(_work_limits.get() + 1)
    try:
        yield
    finally:
        _work_limits.reset(token)


def wall_clock_ceilings() -> bool:
    """True outside :func:`work_limits`: internal time ceilings are enforced."""
    return _work_limits.get() == 0


def ceiling(seconds: float | None) -> float | None:
    """An internal time ceiling in seconds, or None (no wall-clock limit) inside :func:`work_limits`."""
    return seconds if wall_clock_ceilings() else None
_saved_handler = [None]     # the SIGALRM handler before the outermost enforced block


class BudgetExceeded(Exception, metaclass=_OwnNames):
    """The time budget ran out; the result is ``undecided``.

    Examples
    --------
    >>> import time
    >>> d = Deadline(1e-6); time.sleep(0.001)
    >>> d.check()
    Traceback (most recent call last):
    ...
    lkverify.options.BudgetExceeded: time budget of 1e-06 s exhausted

    The checkers catch it and report ``undecided``:

    >>> from lkverify import Term, UnitVector, t
    >>> from lkverify.symbolic import check_identity
    >>> s = UnitVector("s")
    >>> r = check_identity([Term(s(t)[0])], [Term(s(t)[0])], states=[s], budget=1e-6)
    >>> str(r.status), r.detail
    ('undecided', 'time budget of 1e-06 s exhausted before the check finished')
    """


class Deadline:
    """A wall-clock budget in seconds (``None`` or ``math.inf`` = unlimited).

    Parameters
    ----------
    seconds : float or None
        A positive number of seconds; ``None`` or ``inf`` for no limit.
    cap : bool, default False
        The user's own cap (``--budget``): enforced also inside :func:`work_limits`, where
        any other deadline is an internal ceiling and unlimited.

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

    def __init__(self, seconds: float | None, *, cap: bool = False):
        if seconds is not None:
            if isinstance(seconds, bool) or not isinstance(seconds, numbers.Real) or not seconds > 0:
                raise InputError(f"budget: expected a positive number of seconds (or None for no limit), "
                                 f"got {seconds!r}")
            seconds = None if math.isinf(seconds) else float(seconds)
        self.cap = bool(cap)
        self.seconds = seconds if cap else ceiling(seconds)
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

    def enforced(self) -> "_Enforced":
        """Interrupt the enclosed block when this budget, or an enclosing one, runs out (main thread only).

        The alarm never interrupts the block's own entry and exit (the bookkeeping of the active
        deadlines and of the signal handler): an alarm due there is retried after
        :data:`RETRY_SECONDS`, so leaving the block always restores the handler and the timer.

        Raises
        ------
        BudgetExceeded
            On entry if this or an enclosing enforced budget is already spent, and from
            inside the block (at the next Python bytecode) when one runs out.

        Examples
        --------
        >>> import signal
        >>> with Deadline(5).enforced():
        ...     signal.getsignal(signal.SIGALRM) is _on_alarm
        True
        >>> signal.getsignal(signal.SIGALRM) is _on_alarm, _active
        (False, [])
        """
        return _Enforced(self)


class _Enforced:
    """The context manager of :meth:`Deadline.enforced` (a class, not a generator: the alarm
    handler recognises its ``__enter__``/``__exit__`` frames and does not raise inside them)."""

    __slots__ = ("deadline", "armed")

    def __init__(self, deadline: Deadline):
        self.deadline = deadline
        self.armed = False

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            self.deadline.check()
            return self
        for d in (*_active, self.deadline):
            d.check()
        _block()
        try:
            if not _active:
                _saved_handler[0] = signal.signal(signal.SIGALRM, _on_alarm)
                _saved_hook[0] = sys.unraisablehook
                sys.unraisablehook = _quiet_unraisable
            _active.append(self.deadline)
            self.armed = True
            _arm()
        finally:
            _unblock()
        return self

    def __exit__(self, *exc):
        if not self.armed:
            return False
        _block()
        try:
            self.armed = False
            if self.deadline in _active:
                _active.remove(self.deadline)
            if _active:
                _arm()
            else:
                signal.setitimer(signal.ITIMER_REAL, 0)
                _drain_pending_alarm()  # else it reaches the restored handler (SIG_DFL: the process ends)
                signal.signal(signal.SIGALRM, _saved_handler[0] or signal.SIG_DFL)
                _saved_handler[0] = None
                sys.unraisablehook = _saved_hook[0] or sys.__unraisablehook__
                _saved_hook[0] = None
        finally:
            _unblock()
        return False


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


def _drain_pending_alarm() -> None:
    """Consume a SIGALRM that arrived while blocked (our own timer's), before the handler is restored."""
    if hasattr(signal, "sigpending") and signal.SIGALRM in signal.sigpending():
        signal.sigtimedwait({signal.SIGALRM}, 0)


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
    if expired and _in_bookkeeping(frame):
        # inside the bookkeeping of entering or leaving an enforced block: raising here would leave
        # the handler installed after the block (an alarm in whatever runs next); retry shortly
        signal.setitimer(signal.ITIMER_REAL, RETRY_SECONDS)
        return
    _arm()  # re-arm: early wake-up of a capped timer, or the retry while an expired block is unwinding
    if expired:
        raise BudgetExceeded(expired[0].message())


def _in_bookkeeping(frame) -> bool:
    """Whether ``frame`` runs inside the entry or exit of an enforced block (its callees included:
    a signal caught by C before the mask was set is handled at the next bytecode, in any callee)."""
    while frame is not None:
        if frame.f_code in _UNINTERRUPTIBLE:
            return True
        frame = frame.f_back
    return False


#: code objects the alarm never interrupts (the entry and exit of an enforced block)
_UNINTERRUPTIBLE = frozenset(f.__code__ for f in (_Enforced.__enter__, _Enforced.__exit__, _block, _unblock, _arm))


# ---------------------------------------------------------------------------------------------
# option objects: one place for what every long job takes
# ---------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Budget:
    """How much work a job may do before it ends ``undecided``.

    Parameters
    ----------
    seconds : float or None, default 60
        Wall-clock seconds for the whole job; ``None`` for no limit.  Inside :func:`work_limits`
        an internal ceiling: no limit (a caller's cap is ``deadline(cap=True)``).
    boxes : int or None, default None
        For branch and bound: the most boxes examined (``None``: the job's default).

    Examples
    --------
    >>> Budget(seconds=5).deadline().seconds
    5.0
    >>> Budget(seconds=-1)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: Budget.seconds: expected a positive number of seconds or None, got -1
    """

    seconds: float | None = 60.0
    boxes: int | None = None

    def __post_init__(self):
        from .errors import InputError

        s = self.seconds
        if s is not None and (isinstance(s, bool) or not isinstance(s, numbers.Real) or not s > 0):
            raise InputError(f"Budget.seconds: expected a positive number of seconds or None, got {s!r}")
        b = self.boxes
        if b is not None and (isinstance(b, bool) or not isinstance(b, numbers.Integral) or b < 1):
            raise InputError(f"Budget.boxes: expected a positive integer or None, got {b!r}")

    def deadline(self, *, cap: bool = False) -> Deadline:
        """A :class:`Deadline` starting now for :attr:`seconds` (``cap``: the user's own, see :class:`Deadline`)."""
        return Deadline(self.seconds, cap=cap)

    @classmethod
    def of(cls, value) -> "Budget":
        """A Budget from a Budget, a number of seconds, or ``None`` (no limit).

        >>> Budget.of(5).seconds, Budget.of(None).seconds, Budget.of(Budget(seconds=2)).seconds
        (5, None, 2)
        """
        if isinstance(value, Budget):
            return value
        return cls(seconds=value)


@dataclasses.dataclass(frozen=True)
class Accuracy:
    """When a certified bound is tight enough, and how its estimate is searched.

    Parameters
    ----------
    rel_gap : float, default 1e-2
        Stop when ``certified − estimate ≤ rel_gap·|estimate|``.
    abs_gap : float, default 0
        Or when ``certified − estimate ≤ abs_gap`` (needed when the value is 0).
    starts : int, default 8
        Local optimisations started by the estimator.
    seed : int, default 0
        Seed of the estimator's random starts (results are reproducible).

    Examples
    --------
    >>> Accuracy(rel_gap=1e-3).starts
    8
    """

    rel_gap: float = 1e-2
    abs_gap: float = 0.0
    starts: int = 8
    seed: int = 0

    def __post_init__(self):
        from .errors import InputError

        problems = []
        for name in ("rel_gap", "abs_gap"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Real) or not v >= 0 or math.isinf(v):
                problems.append(f"{name}: expected a finite number ≥ 0, got {v!r}")
        if isinstance(self.starts, bool) or not isinstance(self.starts, numbers.Integral) or self.starts < 1:
            problems.append(f"starts: expected a positive integer, got {self.starts!r}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, numbers.Integral):
            problems.append(f"seed: expected an integer, got {self.seed!r}")
        if problems:
            raise InputError("Accuracy: " + "; ".join(problems))
