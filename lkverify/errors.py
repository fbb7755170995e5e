"""Exceptions lkverify raises for problems of the caller's making."""

from __future__ import annotations

__all__ = ["InputError", "LkverifyError"]


class LkverifyError(Exception):
    """Base class of lkverify's own exceptions."""


class InputError(LkverifyError, ValueError):
    """Bad user input; the message is one line: what was expected, what came, how to fix it."""
