"""Identity claims: is a printed expression equal to the derived one?

:func:`check_identity` compares two sums of labelled terms, ``claimed`` (the
paper's print, or any intermediate equality) and ``reference`` (usually the
blocks of a derived V̇):

1. a fast randomized numeric check at witnesses on the constraint manifold
   (:mod:`lkverify.witness`); a difference well above the quadrature accuracy
   refutes the claim, and the witness is reported;
2. the exact check: canonical normal forms modulo the constraints
   (:mod:`lkverify.canonical`); a zero difference proves the claim ``exact``;
3. the term-by-term report: terms on both sides are grouped by the monomials
   they share, and every group whose difference is nonzero is described
   (opposite sign, wrong coefficient, missing from the claim, absent from the
   derivation, or different), with the difference in plain text and LaTeX and
   its value at the witness.

A budget that runs out gives ``undecided``; so does a residue that the normal
form cannot cancel but no witness can separate from zero.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping, Sequence

import numpy as np
import sympy

from .budget import BudgetExceeded, Deadline
from .canonical import Canonicalizer
from .parameters import Parameters
from .status import Status
from .terms import Term
from .witness import Witness, evaluate_many, make_witness

__all__ = ["TermDifference", "IdentityResult", "check_identity"]

#: relative size of a numeric difference that refutes (quadrature is accurate to ~1e-12)
REFUTE_TOL = 1e-7
#: relative size below which a numeric difference counts as zero
ZERO_TOL = 1e-9


@dataclasses.dataclass(frozen=True)
class TermDifference:
    """One group of terms whose claimed and derived sums differ.

    Attributes
    ----------
    kind : str
        ``"sign"``, ``"coefficient"``, ``"missing from claim"``,
        ``"not in derivation"`` or ``"differs"``.
    claimed, derived : tuple of str
        Labels of the claimed terms and of the derived terms in the group.
    message : str
        One readable sentence.
    difference_text, difference_latex : str
        claimed − derived for this group.
    value : float or None
        claimed − derived for this group at the witness.
    """

    kind: str
    claimed: tuple
    derived: tuple
    message: str
    difference_text: str
    difference_latex: str
    value: float | None

    def to_json(self) -> dict:
        return dataclasses.asdict(self) | {"claimed": list(self.claimed), "derived": list(self.derived)}


@dataclasses.dataclass(frozen=True)
class IdentityResult:
    """The outcome of an identity check."""

    name: str
    status: Status
    detail: str
    differences: tuple = ()
    witness: dict | None = None
    difference_at_witness: float | None = None
    numeric_points: int = 0
    seconds: float = 0.0

    @property
    def holds(self) -> bool:
        return self.status is Status.EXACT

    def to_json(self) -> dict:
        return {"differences": [d.to_json() for d in self.differences], "witness": self.witness,
                "difference_at_witness": self.difference_at_witness, "numeric_points": self.numeric_points,
                "seconds": round(self.seconds, 3)}

    def as_text(self) -> str:
        lines = [f"{self.name}: {self.status} — {self.detail}"]
        for d in self.differences:
            lines.append(f"  - {d.message}")
            lines.append(f"      difference: {d.difference_text}"
                         + (f"  (= {d.value:.6g} at the witness)" if d.value is not None else ""))
        return "\n".join(lines)


def _short(s: str, n: int = 300) -> str:
    return s if len(s) <= n else s[: n - 1] + "…"


def check_identity(claimed: Sequence[Term], reference: Sequence[Term], *, name: str = "identity",
                   states: Sequence = (), parameters: Parameters | None = None,
                   constraints=None, values: Mapping[str, object] | None = None,
                   budget: float | None = 60.0, points: int = 3, seed: int = 0) -> IdentityResult:
    """Check ``Σ claimed == Σ reference`` on the constraint manifold.

    Parameters
    ----------
    claimed, reference : sequence of Term
        Scalar labelled terms (the reference is typically the blocks of V̇).
    name : str
    states : sequence of Vector
        The states whose histories the witnesses draw.
    parameters : Parameters
    constraints : callable, optional
        ``constraints(times)`` → vanishing polynomials (``System.constraint_polynomials``).
    values : mapping, optional
        Checked parameter values already substituted in the terms (kept in witnesses).
    budget : float or None
        Seconds for the whole check; when spent, the result is ``undecided``.
    points : int
        Random witnesses for the numeric check.
    seed : int

    Returns
    -------
    IdentityResult
    """
    start = time.monotonic()
    deadline = Deadline(budget)
    parameters = parameters or Parameters()
    rng = np.random.default_rng(seed)
    claimed, reference = list(claimed), list(reference)
    all_terms = claimed + reference
    witness: Witness | None = None
    worst = None  # (relative difference, witness, value, scale)
    try:
        with deadline.enforced():
            # 1. numeric witnesses
            for _ in range(points):
                deadline.check()
                w = make_witness(states, parameters, fixed=values, rng=rng)
                vals = evaluate_many([term.expr for term in all_terms], w)
                diff = sum(vals[: len(claimed)]) - sum(vals[len(claimed):])
                scale = max(1.0, sum(abs(v) for v in vals))
                rel = abs(diff) / scale
                if worst is None or rel > worst[0]:
                    worst = (rel, w, diff, scale)
            witness = worst[1] if worst else None
            refuted = worst is not None and worst[0] > REFUTE_TOL
            numeric_zero = worst is None or worst[0] < ZERO_TOL
            # 2. exact normal forms (also needed for the term-by-term report)
            canon = Canonicalizer(constraints, deadline=deadline)
            nf = canon.normal_forms([term.expr for term in all_terms])
            total = sum(nf.polys[: len(claimed)], nf.ring.zero) - sum(nf.polys[len(claimed):], nf.ring.zero)
            exact_zero = total == 0
            differences = () if exact_zero else _term_report(claimed, reference, nf, witness)
    except BudgetExceeded as exc:
        return IdentityResult(name, Status.UNDECIDED, f"{exc} before the check finished",
                              witness=witness.describe(states) if witness else None,
                              numeric_points=points, seconds=time.monotonic() - start)
    seconds = time.monotonic() - start
    wjson = witness.describe(states) if witness else None
    wdiff = worst[2] if worst else None
    if exact_zero:
        note = "" if not refuted else (" (a numeric witness disagreed by a relative "
                                       f"{worst[0]:.2g}; the exact proof stands, the quadrature was inaccurate)")
        return IdentityResult(name, Status.EXACT,
                              f"the difference reduces to 0 modulo the constraints; checked numerically at "
                              f"{points} random witnesses first{note}",
                              (), wjson, wdiff, points, seconds)
    if refuted:
        return IdentityResult(name, Status.FAILED,
                              f"claimed − derived = {wdiff:.6g} at a witness (relative {worst[0]:.2g}); "
                              f"{len(differences)} differing group(s) of terms",
                              differences, wjson, wdiff, points, seconds)
    why = ("the normal form leaves a residue that vanishes at every witness (a relation between atoms "
           "the reduction does not know)") if numeric_zero else \
        f"the normal form is nonzero but the witnesses show only a relative {worst[0]:.2g}"
    return IdentityResult(name, Status.UNDECIDED, why, differences, wjson, wdiff, points, seconds)


def _term_report(claimed, reference, nf, witness) -> tuple:
    """Group terms by shared monomials and describe each group that does not cancel."""
    n = len(claimed)
    polys = nf.polys
    parent = list(range(len(polys)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict = {}
    for i, p in enumerate(polys):
        for mono in p.keys():
            j = owner.setdefault(mono, i)
            ri, rj = find(i), find(j)
            if ri != rj:
                parent[ri] = rj
    groups: dict = {}
    for i in range(len(polys)):
        groups.setdefault(find(i), []).append(i)
    out = []
    zero = nf.ring.zero
    for members in groups.values():
        C = [i for i in members if i < n]
        D = [i for i in members if i >= n]
        sc = sum((polys[i] for i in C), zero)
        sd = sum((polys[i] for i in D), zero)
        delta = sc - sd
        if delta == 0:
            continue
        ctext = tuple(claimed[i].text for i in C)
        dtext = tuple(reference[i - n].text for i in D)
        clat = [claimed[i].latex for i in C]
        dlat = [reference[i - n].latex for i in D]
        value = None
        if witness is not None:
            try:
                vals = evaluate_many([claimed[i].expr for i in C] + [reference[i - n].expr for i in D], witness)
                value = sum(vals[: len(C)]) - sum(vals[len(C):])
            except Exception:  # noqa: BLE001 - the value is an aid, the report stands without it
                value = None
        csum = sympy.Add(*[claimed[i].expr for i in C])
        dsum = sympy.Add(*[reference[i - n].expr for i in D])
        ctxt = " + ".join(f"[{c}]" for c in ctext)
        dtxt = " + ".join(f"[{d}]" for d in dtext)
        if sd == 0:
            kind, expr = "not in derivation", csum
            msg = f"printed term(s) {ctxt} do not occur in the derivation"
            dtext_, dlatex = f"+({ctxt})", " + ".join(clat)
        elif sc == 0:
            kind, expr = "missing from claim", -dsum
            msg = f"derived term(s) {dtxt} are missing from the claim"
            dtext_, dlatex = f"−({dtxt})", "-\\left(" + " + ".join(dlat) + "\\right)"
        elif sc == -sd:
            kind, expr = "sign", 2 * csum
            msg = f"opposite sign: printed {ctxt} = −(derived {dtxt})"
            dtext_, dlatex = f"2·({ctxt})", "2\\left(" + " + ".join(clat) + "\\right)"
        else:
            ratio = _ratio(sc, sd)
            if ratio is not None:
                kind, expr = "coefficient", (ratio - 1) * dsum
                msg = f"wrong coefficient: printed {ctxt} = {ratio} × (derived {dtxt})"
                dtext_ = f"({ratio} − 1)·({dtxt})"
                dlatex = rf"\left({sympy.latex(ratio)} - 1\right)\left(" + " + ".join(dlat) + r"\right)"
            else:
                kind, expr = "differs", csum - dsum
                msg = f"printed {ctxt or '(nothing)'} ≠ derived {dtxt or '(nothing)'}"
                dtext_ = f"({ctxt or '0'}) − ({dtxt or '0'})"
                dlatex = "\\left(" + (" + ".join(clat) or "0") + "\\right) - \\left(" + (" + ".join(dlat) or "0") + "\\right)"
        out.append(TermDifference(kind, ctext, dtext, msg, f"{dtext_} = {_short(sympy.sstr(expr))}",
                                  dlatex, value))
    return tuple(out)


def _ratio(a, b):
    """The rational k ≠ 1 with a == k·b, if any (a, b polynomials of one ring)."""
    if not b:
        return None
    lm = b.LM
    ka, kb = a.get(lm), b.get(lm)
    if not ka or not kb:
        return None
    k = ka / kb
    return sympy.Rational(k.numerator, k.denominator) if a == b * k else None
