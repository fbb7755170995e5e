"""Progress on stderr, one implementation for every job: a tqdm bar on a terminal, plain lines otherwise.

``simulate`` (the fraction of each run), ``sweep`` (points, proved cells) use :class:`Progress`;
when stderr is not a terminal (a log, CI) it prints one plain line per tenth instead of
redrawing a bar, through ``say`` when given (the commands' throttled progress lines).

Examples
--------
>>> import io
>>> out = io.StringIO()
>>> p = Progress("sweep", unit="points", stream=out, tty=False)
>>> for done in (1, 5, 10):
...     p.update_to(done, 10)
>>> p.close()
>>> print(out.getvalue().strip())
sweep: 1/10 points (10%)
sweep: 5/10 points (50%)
sweep: 10/10 points (100%)
"""

from __future__ import annotations

import sys

__all__ = ["Progress"]


class Progress:
    """A progress indicator: ``update_to(done, total)`` (counts) or ``fraction(f)`` (0 … 1).

    Parameters
    ----------
    label : str
    unit : str
        What is counted ("points", "cells"); a fraction is shown in per cent.
    enabled : bool
        False: nothing is shown.
    say : callable, optional
        Where plain lines go when not on a terminal (default: the stream).
    stream : file, optional
        Default ``sys.stderr``.
    tty : bool, optional
        Whether to draw a bar (default: the stream is a terminal).
    """

    def __init__(self, label: str, *, unit: str = "", enabled: bool = True, say=None, stream=None,
                 tty: bool | None = None):
        self.label, self.unit, self.enabled, self.say = label, unit, enabled, say
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty() if tty is None else tty
        self._bar = None
        self._tenth = -1

    def update_to(self, done: int, total: int, seconds: float | None = None) -> None:
        """``done`` of ``total`` finished (``seconds``: unused; tqdm measures the rate itself)."""
        if not self.enabled:
            return
        if self.tty:
            if self._bar is None:
                from tqdm import tqdm

                self._bar = tqdm(total=total, desc=self.label, unit=f" {self.unit}" if self.unit else "it",
                                 file=self.stream, leave=True, dynamic_ncols=True, smoothing=0.1)
            self._bar.total = total
            self._bar.n = done
            self._bar.refresh()
            return
        tenth = int(10 * done / total) if total else 10
        if tenth != self._tenth:
            self._tenth = tenth
            what = f" {self.unit}" if self.unit else ""
            self._line(f"{self.label}: {done}/{total}{what} ({100 * done / total if total else 100:.0f}%)")

    __call__ = update_to  # a sweep's progress callback: progress(done, total, seconds)

    def fraction(self, f: float) -> None:
        """A fraction done in [0, 1] (a run's time reached over its horizon)."""
        f = min(max(float(f), 0.0), 1.0)
        if self.tty:
            self.update_to(round(1000 * f), 1000)
            if f >= 1.0:
                self.close()
            return
        if not self.enabled:
            return
        tenth = int(10 * f)
        if tenth != self._tenth:
            self._tenth = tenth
            self._line(f"  {self.label}: {10 * tenth}% of the run")

    def _line(self, text: str) -> None:
        if self.say is not None:
            self.say(text)
        else:
            print(text, file=self.stream, flush=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
