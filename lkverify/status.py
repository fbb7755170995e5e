"""The status vocabulary: how sure lkverify is of a result.

Every result lkverify prints carries exactly one of these statuses; see the
table in the design card.  Only ``EXACT`` and ``CERTIFIED`` are proofs.
"""

from __future__ import annotations

import enum

__all__ = ["Status"]


class Status(str, enum.Enum):
    """How a result was obtained.

    Examples
    --------
    >>> Status.EXACT.is_proof
    True
    >>> Status.ESTIMATED.is_proof
    False
    >>> str(Status.FAILED)
    'failed'
    """

    EXACT = "exact"
    CERTIFIED = "certified"
    ESTIMATED = "estimated"
    SIMULATED = "simulated"
    FAILED = "failed"
    UNDECIDED = "undecided"

    def __str__(self) -> str:
        return self.value

    @property
    def is_proof(self) -> bool:
        """True for the statuses a verdict "established" may rest on."""
        return self in (Status.EXACT, Status.CERTIFIED)

    @property
    def holds(self) -> bool:
        """True unless the result failed or is undecided."""
        return self not in (Status.FAILED, Status.UNDECIDED)
