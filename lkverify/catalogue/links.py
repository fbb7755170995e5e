"""The links of a theorem's chain and its verdict, computed from their statuses.

A :class:`Link` is one step from the functional to the conclusion with how sure lkverify
is of it; :func:`theorem_verdict` reads a chain of them ("established" only when every
link is exact or certified; "failed" only for a refuted hypothesis or a counterexample to
the conclusion).
"""

from __future__ import annotations

import dataclasses

from ..status import Status

__all__ = ["Link", "theorem_verdict"]


@dataclasses.dataclass(frozen=True)
class Link:
    """One link of a theorem's chain: what it states and how sure lkverify is of it.

    Attributes
    ----------
    name : str
    status : Status or None
        ``None`` when nothing of this run checks the link (it is missing).
    detail : str

    Examples
    --------
    >>> from lkverify.status import Status
    >>> link = Link("V ≥ φ", None, "no bound step checks it")
    >>> link.missing, link.to_json()
    (True, {'link': 'V ≥ φ', 'status': None, 'detail': 'no bound step checks it'})
    >>> Link("V̇ along the system", Status.EXACT).missing
    False
    """

    name: str
    status: Status | None
    detail: str = ""

    @property
    def missing(self) -> bool:
        return self.status is None

    def to_json(self) -> dict:
        return {"link": self.name, "status": None if self.status is None else self.status.value,
                "detail": self.detail}


def _combined(statuses) -> Status | None:
    """The weakest of several statuses (failed < undecided < estimated/simulated < certified < exact)."""
    statuses = list(statuses)
    if not statuses:
        return None
    for s in (Status.FAILED, Status.UNDECIDED, Status.SIMULATED, Status.ESTIMATED, Status.CERTIFIED):
        if s in statuses:
            return s
    return Status.EXACT


def theorem_verdict(links, *, at: str | None = None) -> str:
    """The verdict of a chain of links (see :meth:`Theorem.chain`), computed from their statuses.

    "established" only when every link is ``exact`` or ``certified``; otherwise the
    verdict names the first link, in the chain's order, that is failed, undecided or
    missing (with its detail), counts the links after it that are not proved, and lists
    the links proved.  "failed" is reserved for a refuted hypothesis or a counterexample to
    the conclusion; any other refuted link leaves the theorem "not established" (``at``: the
    proof's choices it was checked at, e.g. "these choices" or "the searched choices").

    Examples
    --------
    >>> theorem_verdict([Link("V̇", Status.EXACT), Link("V ≥ φ", None, "no bound step")])
    'not established: missing: V ≥ φ (no bound step); checked: V̇ (exact)'
    >>> theorem_verdict([Link("hypotheses", Status.FAILED, "k > 0"), Link("V ≥ φ", None, "no bound step"),
    ...                  Link("conclusion", None)])
    'failed: hypotheses (k > 0); 1 later link not proved (V ≥ φ)'
    >>> theorem_verdict([Link("hypotheses", Status.EXACT), Link("decay", Status.FAILED, "W ≥ 0 at a point")],
    ...                 at="these choices")
    'not established at these choices: decay refuted (W ≥ 0 at a point); checked: hypotheses (exact)'
    >>> theorem_verdict([Link("V̇", Status.EXACT), Link("conclusion", Status.EXACT)])
    'established: every link exact or certified (V̇, conclusion)'
    """
    links = list(links)
    bad = [link for link in links if link.name != "conclusion"
           and (link.status is None or not link.status.is_proof)]
    proved = [link for link in links if link.status is not None and link.status.is_proof]
    if not bad and all(not link.missing for link in links):
        return f"established: every link exact or certified ({', '.join(link.name for link in links)})"
    if not bad:
        return "not established: the conclusion does not follow from the links"
    first, later = bad[0], bad[1:]
    where = f" at {at}" if at else ""
    if first.status is Status.FAILED and first.name in ("hypotheses", "conclusion"):
        text = f"failed: {first.name} ({first.detail})"
    elif first.status is Status.FAILED:
        text = f"not established{where}: {first.name} refuted ({first.detail})"
    elif first.status is not None:
        text = f"undecided: {first.name} ({first.status}: {first.detail})"
    else:
        text = f"not established{where}: missing: {first.name} ({first.detail})"
    if later:
        text += (f"; {len(later)} later link{'s' if len(later) > 1 else ''} not proved "
                 f"({', '.join(link.name for link in later)})")
    if proved:
        text += "; checked: " + ", ".join(f"{link.name} ({link.status})" for link in proved)
    return text


def _concluded(links: list, results, own, printed=()) -> tuple:
    """The links with the intermediate identities and the conclusion appended."""
    skip = {c.name for c in own} | set(printed)
    others = [r for r in results if r.kind == "identity" and r.name not in skip]
    if others:
        links.append(Link("intermediate identities", _combined([r.status for r in others]),
                          ", ".join(f"{r.name}: {r.status}" for r in others)))
    ready = all(link.status is not None and link.status.is_proof for link in links)
    links.append(Link("conclusion", Status.EXACT if ready else None,
                      "follows from the links above" if ready else "rests on the links above"))
    return tuple(links)


def _best_step(steps, by_name, definite):
    """(status, detail) of the first step of a role whose statement and bound are both proved, else None."""
    for b in steps:
        st, bound = by_name[b.name].status, definite.get(b.name)
        if st.is_proof and bound is not None and bound.status.is_proof:
            status = Status.EXACT if st is Status.EXACT and bound.status is Status.EXACT else Status.CERTIFIED
            return status, f"{b.name}: {st}; {bound.detail}"
    return None
