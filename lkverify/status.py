"""The status vocabulary: how sure lkverify is of a result, and the one exactness policy.

Every result lkverify prints carries exactly one of these statuses (the members of
:class:`Status`, each documented there).  Only ``EXACT`` and ``CERTIFIED`` are proofs.

The exactness policy (every checker follows it; this is where it is written down):

1. **Exact inputs stay exact.**  Entries, margins and user expressions are never
   passed through ``nsimplify`` or rounded: a rational stays that rational, however
   close it is to a simpler one (1 − 10⁻²⁰ is not 1).
2. **Floats are taken at their exact binary value, or refused.**  A Python or SymPy
   float given as a parameter value, a matrix entry or inside a hypothesis becomes
   the rational it stores (0.5 → 1/2; 0.1 → 3602879701896397/2⁵⁵), never a
   "nearby" simple number.  Text such as ``"0.1"`` on the command line is read as the
   exact decimal 1/10.  Identity claims refuse floats (:class:`~lkverify.errors.InputError`):
   only ``exact`` could confirm them, and a float may have been rounded before lkverify
   sees it.
3. **A value that went through floating point is never ``EXACT``.**  It is decided in
   outward-rounded interval arithmetic (:mod:`lkverify.certify.intervals`): ``CERTIFIED`` or
   ``FAILED``, else ``UNDECIDED``.  A point value (mpmath, NumPy) is an estimate, not an
   enclosure.  Irrational constants (√2 − 1) are decided by enclosures too: ``CERTIFIED``.
4. **``EXACT`` means reduced symbolically**: an identity whose difference reduces to 0
   modulo the stated constraints, a rational margin, an LDLᵀ in fractions.
5. **A refutation is rechecked**: an identity is ``FAILED`` when its exact nonzero
   residue is certified nonzero at a witness (interval arithmetic) or is clearly nonzero
   in floating point relative to its own terms; a matrix witness xᵀMx ≤ 0 is checked
   exactly or in intervals.  Otherwise ``UNDECIDED``, with what stopped the proof.
6. **Verdicts are computed** from the chain of links (:meth:`lkverify.catalogue.items.Theorem.chain`):
   "established" only when every link is ``EXACT`` or ``CERTIFIED``.
"""

from __future__ import annotations

import enum

__all__ = ["Label", "Status"]


class _LabelType(enum.EnumType):
    """Metaclass of :class:`Label`: ``dir(cls)`` without the container protocol of ``EnumType``.

    ``help()`` then shows a label enum's members and docstring, not ``__contains__``,
    ``__getitem__``, ``__iter__``, ``__len__`` and ``__members__`` (which still work).
    """

    _HIDDEN = frozenset({"__contains__", "__getitem__", "__iter__", "__len__", "__members__"})

    def __dir__(cls):
        return [n for n in super().__dir__() if n not in _LabelType._HIDDEN]


class Label(enum.Enum, metaclass=_LabelType):
    """An enum whose members stand for their string values.

    A member equals its value, hashes like it and prints as it, so reports and JSON can
    use either — without inheriting the ~80 methods of ``str`` (which fill ``help()``).

    >>> Status.EXACT == "exact", {"exact": 1}[Status.EXACT], f"{Status.FAILED:>8}"
    (True, 1, '  failed')
    """

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)

    def __eq__(self, other) -> bool:
        if isinstance(other, str):
            return self.value == other
        return self is other

    def __hash__(self) -> int:
        return hash(self.value)


class Status(Label):
    """How a result was obtained.

    ============  ==================================================================================
    ``exact``     proved symbolically (an identity reduced to 0, modulo stated constraints such as
                  ‖s‖ = 1)
    ``certified`` proved with outward-rounded interval arithmetic on a stated region
    ``estimated`` a sampled or optimised value: for a supremum a lower bound, not a proof
    ``simulated`` observed along numerical trajectories
    ``failed``    refuted, with the counterexample (point, term or trajectory)
    ``undecided`` budget exhausted (time, boxes, simplification): never silently upgraded
    ============  ==================================================================================

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

    @property
    def is_proof(self) -> bool:
        """True for the statuses a verdict "established" may rest on."""
        return self in (Status.EXACT, Status.CERTIFIED)

    @property
    def holds(self) -> bool:
        """True unless the result failed or is undecided."""
        return self not in (Status.FAILED, Status.UNDECIDED)

    @classmethod
    def weakest(cls, statuses) -> "Status":
        """The weakest of ``statuses`` (failed < undecided < simulated < estimated < certified < exact); exact for none.

        >>> Status.weakest([Status.EXACT, Status.CERTIFIED]).value, Status.weakest([]).value
        ('certified', 'exact')
        """
        statuses = list(statuses)
        for s in (cls.FAILED, cls.UNDECIDED, cls.SIMULATED, cls.ESTIMATED, cls.CERTIFIED):
            if s in statuses:
                return s
        return cls.EXACT
