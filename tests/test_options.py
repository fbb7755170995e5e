"""Enforced deadlines leave no alarm behind (the CI crash of stop 31).

An alarm that fired while an enforced block was being left used to raise from the
generator's ``finally`` before the bookkeeping ran: the SIGALRM handler stayed installed
and the retry timer kept firing into whatever ran next (pytest's report of the test).
"""

import signal
import time
from types import SimpleNamespace

import pytest

from lkverify import options
from lkverify.options import BudgetExceeded, Deadline


def _nothing_left_armed():
    return (not options._active and signal.getsignal(signal.SIGALRM) is not options._on_alarm
            and signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0))


def _spend():
    """Run until the enforced budget interrupts (the real alarm)."""
    try:
        while True:
            time.monotonic()
    except BudgetExceeded:
        pass


@pytest.mark.parametrize("where", ["__enter__", "__exit__"])
def test_an_alarm_due_during_entry_or_exit_is_retried_not_raised(where):
    frame = SimpleNamespace(f_code=getattr(options._Enforced, where).__code__, f_back=None)
    with pytest.raises(BudgetExceeded):
        with Deadline(1e-3).enforced():
            _spend()
            options._on_alarm(signal.SIGALRM, frame)   # inside the bookkeeping: no exception ...
            assert signal.getitimer(signal.ITIMER_REAL)[0] > 0   # ... but a retry is armed
            while True:
                time.monotonic()
    assert _nothing_left_armed()


def test_the_same_alarm_outside_the_bookkeeping_raises():
    frame = SimpleNamespace(f_code=test_the_same_alarm_outside_the_bookkeeping_raises.__code__, f_back=None)
    with Deadline(1e-3).enforced():
        _spend()
        with pytest.raises(BudgetExceeded):
            options._on_alarm(signal.SIGALRM, frame)
        _spend()                                    # the retry armed by that call
    assert _nothing_left_armed()


@pytest.mark.timeout(120)
def test_many_tiny_budgets_never_leave_the_handler_installed():
    """Deadlines expiring at every point of a block, its entry and its exit included."""
    for k in range(300):
        try:
            with Deadline(1e-5 * (1 + k % 30)).enforced():
                with Deadline(1e-5 * (1 + k % 7)).enforced():
                    sum(range(k))
        except BudgetExceeded:
            pass
        assert _nothing_left_armed(), k


def test_the_handler_before_the_outermost_block_is_restored():
    def mine(signum, frame):
        pass

    old = signal.signal(signal.SIGALRM, mine)
    try:
        with pytest.raises(BudgetExceeded):
            with Deadline(1e-3).enforced():
                while True:
                    time.monotonic()
        assert signal.getsignal(signal.SIGALRM) is mine and not options._active
    finally:
        signal.signal(signal.SIGALRM, old)
