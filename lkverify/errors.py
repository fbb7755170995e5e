"""Exceptions lkverify raises for problems of the caller's making."""

from __future__ import annotations

__all__ = ["InputError", "LkverifyError", "UnsupportedInput"]


class LkverifyError(Exception):
    """Base class of lkverify's own exceptions."""


class InputError(LkverifyError, ValueError):
    """Bad user input; the message is one line: what was expected, what came, how to fix it."""


class UnsupportedInput(LkverifyError, ValueError):
    """Input lkverify cannot handle (yet): a model, an expression or an option outside what it supports.

    Never reported as ``failed``: nothing was refuted.  The message says what is supported.
    """
