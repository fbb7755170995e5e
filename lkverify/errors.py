"""Exceptions lkverify raises for problems of the caller's making."""

from __future__ import annotations

__all__ = ["InputError", "LkverifyError", "UnsupportedInput"]


class LkverifyError(Exception):
    """Base class of lkverify's own exceptions."""


class InputError(LkverifyError, ValueError):
    """Bad user input; the message is one line: what was expected, what came, how to fix it.

    Parameters
    ----------
    message : str
    topic : str, optional
        What the input was, for front ends that name their own options: ``"history"``,
        ``"parameters"``, ``"t_end"``, ``"budget"``.  The library's message never names a
        command-line flag; :mod:`lkverify.cli` adds the flag for the topic.
    example : str, optional
        A corrected value in ``NAME=VALUE`` form, e.g. ``"omega=[0.1,0.1,0.1]"``.

    Examples
    --------
    >>> e = InputError("history of omega: expected 3 components", topic="history", example="omega=[0,0,1]")
    >>> e.topic, e.example
    ('history', 'omega=[0,0,1]')
    """

    def __init__(self, message: str = "", *, topic: str | None = None, example: str | None = None):
        super().__init__(message)
        self.topic = topic
        self.example = example


class UnsupportedInput(LkverifyError, ValueError):
    """Input lkverify cannot handle (yet): a model, an expression or an option outside what it supports.

    Never reported as ``failed``: nothing was refuted.  The message says what is supported.
    """
