"""The verdict on a positivity condition: :class:`ConditionResult`, :class:`Margin`, :class:`Estimate`.

The papers' hypotheses are positivity statements: "ΞD + DΞᵀ is positive
definite" (paper 000, Assumption 2), "Π + τΠ̃ is positive definite" for a
homogeneous form (paper 002, Theorem 1), "there is P ≻ 0 with AᵀP + PA ≺ 0"
(paper 002, Theorem 2, the linear part), "xᵀMx ≤ c·xᵀNx" (a best quadratic
bound).  They are decided for concrete numbers by

:mod:`lkverify.certify.matrices`
    :func:`~lkverify.certify.matrices.matrix_positive_definite`: an exact LDLᵀ in
    fractions for rational entries, an LDLᵀ in arb balls otherwise; the margin is
    a certified enclosure of λ_min.
:mod:`lkverify.certify.forms`
    :func:`~lkverify.certify.forms.homogeneous_positive_on_sphere`: a certified
    lower bound of min f on the unit sphere (arb branch and bound on cube faces).
:mod:`lkverify.certify.lmi`
    Lyapunov matrices, best quadratic bounds and general LMIs: solved with
    cvxpy + Clarabel, rounded to rationals and re-verified exactly.

and every one of them returns a :class:`ConditionResult`, defined here.

What the statuses mean here
---------------------------
``exact``
    decided in exact rational arithmetic (fractions): the verified
    statement holds for the data as given.
``certified``
    proved with outward-rounded ball arithmetic (arb): every ball contains
    the true value, and the decisive sign is that of a whole ball.
``failed``
    refuted with a counterexample that is re-checked: a rational vector or
    point (exactly, or with a certified ball when the data are irrational), a
    non-Hurwitz eigenvalue with the failing Hurwitz minor, or a rational
    dual certificate of an infeasible LMI.
``undecided``
    no proof either way: precision, the time budget, a solver status other
    than ``optimal`` or a rounded solver answer that did not verify.
``estimated``
    only inside :class:`Estimate` (a solver value or a sampled minimum); an
    estimate is never the status of a :class:`ConditionResult`.

Floats given as input (a NumPy array, ``0.1``) are taken as the exact binary
rationals they store; pass ``sympy.Rational(1, 10)`` to mean one tenth.

Floats given as input (a NumPy array, ``0.1``) are taken as the exact binary
rationals they store; pass ``sympy.Rational(1, 10)`` to mean one tenth.

Examples
--------
>>> from fractions import Fraction
>>> res = ConditionResult("x > 0", Status.EXACT, margin=Margin(Fraction(1, 2), Fraction(1, 2)))
>>> res.holds, res.to_result().value
(True, 0.5)
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from fractions import Fraction

import sympy

from ..report.results import Result
from ..status import Status
from .intervals import float_down, float_up
from ..errors import InputError

__all__ = ["ConditionResult", "Margin", "Estimate", "combine"]

# ---------------------------------------------------------------------------------------------
# result types


def _frac(value) -> Fraction | None:
    if value is None:
        return None
    if isinstance(value, Fraction):
        return value
    if isinstance(value, sympy.Rational):
        return Fraction(int(value.p), int(value.q))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InputError(f"an enclosure end must be finite, got {value!r}")
        return Fraction(value)
    return Fraction(value)


def _exact_str(value) -> str:
    return str(value) if not isinstance(value, Fraction) or value.denominator != 1 else str(value.numerator)


def _json_vector(v):
    if v is None:
        return None
    if isinstance(v, sympy.MatrixBase):
        return [[_json_scalar(e) for e in row] for row in v.tolist()]
    if isinstance(v, (tuple, list)):
        return [_json_vector(e) if isinstance(e, (tuple, list, sympy.MatrixBase)) else _json_scalar(e) for e in v]
    return _json_scalar(v)


def _json_scalar(e):
    """Integers as JSON integers, other exact rationals as "p/q" strings, the rest as text."""
    if isinstance(e, Fraction):
        return e.numerator if e.denominator == 1 else _exact_str(e)
    if isinstance(e, (bool, int, str)) or e is None:
        return e
    if isinstance(e, float):
        return e if math.isfinite(e) else str(e)
    if isinstance(e, sympy.Integer):
        return int(e)
    return str(e)


@dataclasses.dataclass(frozen=True)
class Margin:
    """A certified interval ``lo ≤ value ≤ hi`` with exact rational ends.

    Attributes
    ----------
    lo, hi : Fraction or None
        Proved bounds (``None``: no bound on that side).
    exact : sympy.Expr or None
        The exact value when it is known (a Rational, a radical, a ``CRootOf``).
    point : tuple of Fraction or None
        The rational point at which the attained bound was evaluated: ``hi``
        for a minimum (a Rayleigh quotient, a value of f), ``lo`` for a maximum.

    Examples
    --------
    >>> from fractions import Fraction
    >>> e = Margin(Fraction(1, 3), Fraction(1, 2))
    >>> e.contains(Fraction(2, 5)), e.contains(1)
    (True, False)
    >>> e.to_json()["lo_exact"]
    '1/3'
    """

    lo: Fraction | None
    hi: Fraction | None
    exact: object = None
    point: tuple | None = None

    def __post_init__(self):
        object.__setattr__(self, "lo", _frac(self.lo))
        object.__setattr__(self, "hi", _frac(self.hi))
        if self.lo is not None and self.hi is not None and self.lo > self.hi:
            raise InputError(f"an enclosure needs lo <= hi, got [{self.lo}, {self.hi}]")
        if self.point is not None:
            object.__setattr__(self, "point", tuple(_frac(c) for c in self.point))

    def contains(self, value) -> bool:
        """True if ``value`` (a number) lies in [lo, hi]."""
        v = _frac(value)
        return (self.lo is None or self.lo <= v) and (self.hi is None or v <= self.hi)

    @property
    def width(self) -> Fraction | None:
        return None if self.lo is None or self.hi is None else self.hi - self.lo

    def to_json(self) -> dict:
        """Floats rounded outward (``lo`` down, ``hi`` up) and the exact rationals as strings."""
        return {
            "lo": None if self.lo is None else float_down(self.lo),
            "hi": None if self.hi is None else float_up(self.hi),
            "lo_exact": None if self.lo is None else _exact_str(self.lo),
            "hi_exact": None if self.hi is None else _exact_str(self.hi),
            "exact": None if self.exact is None else str(self.exact),
            "point": _json_vector(self.point),
        }


@dataclasses.dataclass(frozen=True)
class Estimate:
    """A floating-point value from a solver or from sampling: never a proof.

    Attributes
    ----------
    value : float
    method : str
        How it was obtained ("clarabel SDP", "2000 samples + L-BFGS-B").
    point : tuple of float or None
        Where (a minimiser), when it applies.
    status : Status
        Always ``Status.ESTIMATED``; any other status is refused.

    Examples
    --------
    >>> Estimate(0.5, "sampling").status
    <Status.ESTIMATED: 'estimated'>
    >>> Estimate(0.5, "sampling", status=Status.CERTIFIED)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: an Estimate is never a proof: expected status estimated, got certified; put proved values in a margin
    """

    value: float
    method: str
    point: tuple | None = None
    status: Status = Status.ESTIMATED

    def __post_init__(self):
        if self.status is not Status.ESTIMATED:
            raise InputError(f"an Estimate is never a proof: expected status estimated, got {self.status}; "
                             "put proved values in a margin")
        object.__setattr__(self, "value", float(self.value))
        if self.point is not None:
            object.__setattr__(self, "point", tuple(float(c) for c in self.point))

    def to_json(self) -> dict:
        return {"value": _json_scalar(self.value), "method": self.method, "point": _json_vector(self.point),
                "status": self.status.value}


@dataclasses.dataclass(frozen=True)
class ConditionResult:
    """The verdict on one positivity condition.

    Attributes
    ----------
    name : str
    status : Status
        ``exact``, ``certified``, ``failed`` or ``undecided`` (see the module
        docstring); never ``estimated``.
    margin : Margin or None
        The certified value: an enclosure of λ_min, of min f on the unit
        sphere, of the best constant.  Required when the status is a proof.
    estimate : Estimate or None
        The solver's or the sampler's value (status ``estimated``).
    witness : object
        The counterexample of a ``failed`` result (required then): a tuple of
        Fractions x, a rational point, an eigenvalue, a dual matrix.
    detail : str
        One readable paragraph.
    certificate : object
        What proves a positive result and can be re-checked: a rational
        matrix P, a rational constant c, a rational vector y.
    parts : tuple of ConditionResult
        The sub-conditions the verdict rests on.

    Examples
    --------
    >>> from lkverify.certify.matrices import matrix_positive_definite
    >>> ok = matrix_positive_definite([[2, 1], [1, 2]])         # eigenvalues 1 and 3
    >>> ok.status.value, ok.holds, ok.margin.exact
    ('exact', True, 1)
    >>> bad = matrix_positive_definite([[1, 2], [2, 1]])
    >>> bad.holds, [str(c) for c in bad.witness]               # xᵀMx < 0 at the witness
    (False, ['-2', '1'])
    >>> ConditionResult("x > 0", Status.FAILED)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: a failed result needs a witness (the counterexample)
    """

    name: str
    status: Status
    margin: Margin | None = None
    estimate: Estimate | None = None
    witness: object = None
    detail: str = ""
    certificate: object = None
    parts: tuple = ()

    def __post_init__(self):
        if not isinstance(self.status, Status):
            raise InputError(f"status must be a Status, got {self.status!r}")
        if self.status in (Status.ESTIMATED, Status.SIMULATED):
            raise InputError(f"a condition is exact, certified, failed or undecided, got {self.status}; "
                             "put estimates in ConditionResult.estimate")
        if self.margin is not None and not isinstance(self.margin, Margin):
            raise InputError(f"margin must be a Margin, got {type(self.margin).__name__}")
        if self.estimate is not None and not isinstance(self.estimate, Estimate):
            raise InputError(f"estimate must be an Estimate, got {type(self.estimate).__name__}")
        if self.status.is_proof and self.margin is None:
            raise InputError(f"a {self.status} result needs a certified margin")
        if self.status is Status.FAILED and self.witness is None:
            raise InputError("a failed result needs a witness (the counterexample)")
        object.__setattr__(self, "parts", tuple(self.parts))

    @property
    def holds(self) -> bool:
        """True when the condition is proved (``exact`` or ``certified``)."""
        return self.status.is_proof

    def to_json(self) -> dict:
        """A JSON-ready dict: integers as integers, other exact rationals as ``"p/q"``.

        The margin is given both exactly and as outward-rounded floats.

        >>> import json
        >>> from lkverify.certify.matrices import matrix_positive_definite
        >>> res = matrix_positive_definite([[2, 1], [1, 2]])
        >>> d = res.to_json(); d["status"], d["margin"]["lo_exact"]
        ('exact', '1')
        >>> isinstance(json.dumps(d), str)
        True
        """
        return {
            "name": self.name,
            "status": self.status.value,
            "margin": None if self.margin is None else self.margin.to_json(),
            "estimate": None if self.estimate is None else self.estimate.to_json(),
            "witness": _json_vector(self.witness),
            "certificate": _json_vector(self.certificate),
            "detail": self.detail,
            "parts": [p.to_json() for p in self.parts],
        }

    def to_result(self, kind: str = "hypothesis") -> Result:
        """This verdict as a :class:`lkverify.report.results.Result` row (value: the margin's lower end, rounded down)."""
        value = None if self.margin is None or self.margin.lo is None else float_down(self.margin.lo)
        return Result(kind, self.name, self.status, value, self.detail)



def combine(name: str, parts: Sequence[ConditionResult], *, certificate=None) -> ConditionResult:
    """AND of sub-conditions: failed if one failed, undecided if one is, exact only if all are.

    Examples
    --------
    >>> from fractions import Fraction
    >>> yes = ConditionResult("a", Status.EXACT, margin=Margin(1, 1))
    >>> no = ConditionResult("b", Status.FAILED, witness=(Fraction(1),), detail="x = 1 refutes it")
    >>> combine("a and b", [yes, no]).status
    <Status.FAILED: 'failed'>
    """
    parts = tuple(parts)
    failed = [p for p in parts if p.status is Status.FAILED]
    if failed:
        return ConditionResult(name, Status.FAILED, margin=failed[0].margin, witness=failed[0].witness,
                               detail=f"{failed[0].name} is false: {failed[0].detail}", parts=parts,
                               certificate=certificate)
    open_ = [p for p in parts if not p.status.is_proof]
    if open_:
        return ConditionResult(name, Status.UNDECIDED, margin=parts[-1].margin,
                               detail=f"{open_[0].name} is undecided: {open_[0].detail}", parts=parts,
                               certificate=certificate)
    status = Status.EXACT if all(p.status is Status.EXACT for p in parts) else Status.CERTIFIED
    detail = " ".join(p.detail for p in parts)
    return ConditionResult(name, status, margin=parts[-1].margin, detail=detail, parts=parts,
                           certificate=certificate)

