"""Exceptions lkverify raises for problems of the caller's making."""

from __future__ import annotations

__all__ = ["InputError", "InternalError", "LkverifyError", "RuleSoundnessError", "UnsupportedInput"]


class _OwnNames(type):
    """Metaclass of the exceptions: ``dir(cls)`` lists what lkverify's classes define.

    ``help()`` then documents the exception (its docstring, its own attributes) without the
    ~25 members every exception inherits from ``BaseException`` (``args``,
    ``with_traceback``, …); instances keep them all.
    """

    def __dir__(cls):
        names = set()
        for base in cls.__mro__:
            if base.__module__.startswith("lkverify"):
                names.update(base.__dict__)
        return sorted(names - {"__weakref__", "__dict__"})


class LkverifyError(Exception, metaclass=_OwnNames):
    """Base class of lkverify's own exceptions.

    Examples
    --------
    >>> from lkverify import LkverifyError, dot
    >>> try:
    ...     dot([1, 2], [1, 2, 3])
    ... except LkverifyError as exc:          # catches InputError and UnsupportedInput alike
    ...     print(type(exc).__name__, "-", exc)
    InputError - dot product of vectors of shapes (2, 1) and (3, 1)
    """


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
    >>> from lkverify import Parameters
    >>> P = Parameters(); tau = P.delay("tau")
    >>> P.resolve({"tau": -1})
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: tau: expected tau > 0 (a delay must be positive), got tau=-1
    """

    def __init__(self, message: str = "", *, topic: str | None = None, example: str | None = None):
        super().__init__(message)
        self.topic = topic
        self.example = example


class UnsupportedInput(LkverifyError, ValueError):
    """Input lkverify cannot handle (yet): a model, an expression or an option outside what it supports.

    Never reported as ``failed``: nothing was refuted.  The message says what is supported.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.symbolic import Canonicalizer
    >>> Canonicalizer().normal_expr(sympy.Eq(sympy.Symbol("a"), 1))
    Traceback (most recent call last):
    ...
    lkverify.errors.UnsupportedInput: cannot put Equality in normal form: Eq(a, 1); identities support polynomial operations, powers, integrals and function values
    >>> issubclass(UnsupportedInput, ValueError)    # callers catching ValueError see it too
    True
    """


class InternalError(LkverifyError, RuntimeError):
    """A bug of lkverify found by its own checks (the command line exits with code 3).

    Never caused by the caller's input; the message is one line saying what lkverify
    caught itself doing.

    Examples
    --------
    >>> issubclass(InternalError, LkverifyError), issubclass(InternalError, ValueError)
    (True, False)
    """


class RuleSoundnessError(InternalError):
    """A bound-step rule proved a term bound that a rechecked witness refutes: a bug of the rule.

    Parameters
    ----------
    message : str
        One line naming the rule, the step and the witness.
    rule : str
        The rule's name.
    witness : object
        The :class:`~lkverify.certify.steps.witnesses.Witness` (rechecked in interval
        arithmetic) at which the proved bound fails.

    Examples
    --------
    >>> e = RuleSoundnessError("the rule 'R' proved x ≤ 0 (exact), but x = 1 refutes it", rule="R")
    >>> e.rule, isinstance(e, InternalError)
    ('R', True)
    """

    def __init__(self, message: str = "", *, rule: str = "", witness=None):
        super().__init__(message)
        self.rule = rule
        self.witness = witness
