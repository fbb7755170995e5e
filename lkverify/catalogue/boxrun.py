"""A theorem over a box of parameters: the chain decided for every point, split until it closes.

:func:`run_over_box` checks a :class:`~lkverify.catalogue.items.Theorem` for every point of a
:class:`~lkverify.declare.boxes.ParameterBox` (the other parameters at the given values or
the paper's defaults, the proof's choices fixed per box):

* **hypotheses** — each margin enclosed over the box (:func:`lkverify.certify.boxes.margin_over_box`):
  held on the whole box (``certified``), or failed at a corner or the centre (that point is
  reported), or undecided (the box is split);
* **identities** — checked with the boxed parameters symbolic, so an ``exact`` identity holds
  for every value (the report says so);
* **bound steps** — checked with each boxed parameter a symbol of its interval's sign
  (:func:`lkverify.certify.boxes.box_symbol`): a proved step holds at every point of the box;
  template suprema are taken over the chart × the box; the witness searches run at the centre;
* **decay** — the steps' right-hand sides made uniform over the box, coefficient by
  coefficient (:func:`lkverify.certify.boxes.uniform_bound`), then certified as at a point: one
  set of constants (c̃, δ̃, the envelope) for every point of the box.

A box that does not close is split in two along its widest interval (relative to the
whole box), breadth first, until every piece is established, a point with a failing link is
found (the run stops there and reports it), or the work limit ``max_boxes`` (pieces
checked; deterministic, not a wall clock) is reached, the rest ``undecided``.

Examples
--------
``x' = −kx``, ``V = x²/2``, hypothesis k > 0: established on k ∈ [1/2, 2]; on k ∈ [−1, 1]
the hypothesis fails at the corner k = −1:

>>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t, DerivativeClaim, Hypothesis
>>> from lkverify.catalogue.items import Theorem
>>> P = Parameters(); k = P.scalar("k", default=1); x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-k * x(t)[0])])], parameters=P)
>>> V = Functional([Term(x(t)[0] ** 2 / 2)])
>>> th = Theorem("demo", system=sys, functional=V, hypotheses=[Hypothesis("k > 0", k)],
...              claims=[DerivativeClaim("Vdot", V, sys, [Term(-k * x(t)[0] ** 2)])])
>>> rep = th.run(box={"k": ("-1", "1")})
>>> rep.status.value, rep.failing[0].point
('failed', {'k': -1})
>>> th.run(box={"k": ("1/2", "2")}).pieces[0].status.value     # no bound steps: not established
'undecided'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping

import sympy

from ..certify.boxes import box_symbol, margin_over_box, uniform_bound
from ..declare.boxes import ParameterBox
from ..declare.parameters import ParameterKind, ResolvedValues, apply_substitution
from ..errors import InputError, UnsupportedInput
from ..memo import Memo
from ..report.results import Report, Result
from ..report.schema import SCHEMA_ID
from ..report.text import MAX_LINES, REPORT_WIDTH, wrap_block
from ..status import Label, Status
from .links import Link, theorem_verdict
from .statements import _capped, _cut_text, _not_exact_if_floats, _symbols_of

__all__ = ["BoxPiece", "BoxReport", "BoxStatus", "DEFAULT_MAX_BOXES", "FailingPoint", "run_over_box"]

#: pieces checked at most by one run over a box (the work limit of the subdivision)
DEFAULT_MAX_BOXES = 16

#: the region of the decay is a choice of the proof: over a box it is tried as stated, then shrunk by these
#: factors (its parameters in the choices, so a check at a point repeats the proof; or, when a bound is not
#: a parameter, the decay's region itself: V̇ ≤ W proved on a region holds on every smaller one)
REGION_FACTORS = (1, sympy.Rational(1, 2), sympy.Rational(1, 4), sympy.Rational(1, 8))

_SCALARS = (ParameterKind.REAL, ParameterKind.POSITIVE, ParameterKind.NONNEGATIVE, ParameterKind.DELAY)

#: the search of the proof's choices at a corner of a piece stops after this many generations without
#: improvement (:func:`lkverify.certify.decay.search_parameters`, ``stall``): what it finds is a candidate,
#: checked by the chain over the whole piece like any other, so the early stop changes which choices are
#: tried, never what is claimed for them (a point check, ``lkverify check`` without ``--box``, and
#: ``lkverify constants`` search to the end)
BOX_SEARCH_STALL = 25

#: the searches' outcomes per process: job, (theorem, stall, the values at the corner) → choices or None
#: (:meth:`Memo.owned`).  The search is deterministic (seeded), so a neighbouring cell sharing the corner gets
#: the same choices without searching again; stored only for a search that returned (one the caller's cap
#: cut stores none)
_SEARCHED = Memo(256)
_NOT_SEARCHED = object()


class BoxStatus(Label):
    """What a run over a box found for a piece (or the whole box).

    >>> BoxStatus.ESTABLISHED == "established", str(BoxStatus.FAILED)
    (True, 'failed')
    """

    ESTABLISHED = "established"   # the chain holds at every point of the piece
    FAILED = "failed"             # a point of the piece where a link fails was found
    UNDECIDED = "undecided"       # neither, within the work limit


@dataclasses.dataclass(frozen=True)
class FailingPoint:
    """A point of the box where a link of the chain fails, with the link and why.

    >>> FailingPoint({"k": -1}, "hypothesis k > 0", "margin -1").to_json()
    {'point': {'k': '-1'}, 'link': 'hypothesis k > 0', 'detail': 'margin -1'}
    """

    point: dict
    link: str
    detail: str

    def to_json(self) -> dict:
        return {"point": {k: str(v) for k, v in self.point.items()}, "link": self.link, "detail": self.detail}


@dataclasses.dataclass(frozen=True)
class BoxPiece:
    """One piece of the subdivision: its box, status, the chain's report on it.

    >>> piece = BoxPiece(ParameterBox({"k": (0, 1)}), BoxStatus.UNDECIDED, None, note="not checked")
    >>> piece.verdict, piece.to_json()["box"]
    ('not checked', {'k': ['0', '1']})
    """

    box: ParameterBox
    status: BoxStatus
    report: Report | None
    failing: FailingPoint | None = None
    note: str = ""
    choices: dict = dataclasses.field(default_factory=dict)  # the proof's choices the chain was checked at

    @property
    def verdict(self) -> str:
        return self.report.verdict if self.report is not None else self.note

    def to_json(self) -> dict:
        return {"box": self.box.to_json(), "status": self.status.value, "verdict": self.verdict,
                "choices": dict(self.choices),
                "failing": None if self.failing is None else self.failing.to_json(),
                "chain": [link.to_json() for link in (self.report.chain if self.report else ())]}


@dataclasses.dataclass(frozen=True)
class BoxReport:
    """A theorem over a box: the pieces, the proved part and the first failing points.

    Attributes
    ----------
    item : str
    parameters : dict
        The fixed parameters shown (the boxed ones as intervals).
    box : ParameterBox
    pieces : tuple of BoxPiece
        The subdivision's leaves, in the order they were decided.
    checked : int
        Pieces whose chain was run (the work, at most ``max_boxes``).
    max_boxes : int

    Examples
    --------
    >>> B = ParameterBox({"k": (0, 1)})
    >>> left, right = B.split()
    >>> rep = BoxReport("demo", {}, B, (BoxPiece(left, BoxStatus.ESTABLISHED, None),
    ...                                 BoxPiece(right, BoxStatus.UNDECIDED, None, note="limit")), 3, 3)
    >>> rep.status.value, rep.proved_fraction, rep.exit_code
    ('undecided', 1/2, 1)
    """

    item: str
    parameters: dict
    box: ParameterBox
    pieces: tuple
    checked: int
    max_boxes: int

    @property
    def proved(self) -> tuple:
        """The established pieces (their union is the proved part)."""
        return tuple(p for p in self.pieces if p.status is BoxStatus.ESTABLISHED)

    @property
    def proved_fraction(self) -> sympy.Rational:
        """The measure of the proved part as a fraction of the box's (exact)."""
        return sum((p.box.fraction_of(self.box) for p in self.proved), sympy.S.Zero)

    @property
    def failing(self) -> tuple:
        return tuple(p.failing for p in self.pieces if p.failing is not None)

    def constant(self, name: str) -> tuple:
        """``((piece box, value), …)`` of a certified constant (``delta_tilde``, ``c_tilde``, …) over the
        established pieces: a piecewise-constant bound valid at every point of each piece (a lower bound
        for a region's radius δ̃, the value certified for the whole piece)."""
        out = []
        for p in self.proved:
            row = next((r for r in p.report.results if r.name == name and isinstance(r.value, dict)), None)
            if row is not None and row.status.is_proof:
                out.append((p.box, row.value.get("value")))
        return tuple(out)

    @property
    def status(self) -> BoxStatus:
        if self.failing:
            return BoxStatus.FAILED
        if self.pieces and all(p.status is BoxStatus.ESTABLISHED for p in self.pieces):
            return BoxStatus.ESTABLISHED
        return BoxStatus.UNDECIDED

    @property
    def verdict(self) -> str:
        n, frac = len(self.pieces), self.proved_fraction
        if self.status is BoxStatus.ESTABLISHED:
            first = self.pieces[0].report
            tail = "" if first is None else "; " + first.verdict
            return (f"established for every point of {self.box}" + (f" ({n} pieces)" if n > 1 else "") + tail)
        if self.status is BoxStatus.FAILED:
            f = self.failing[0]
            where = ", ".join(f"{k} = {v}" for k, v in f.point.items())
            return (f"failed at the point {where} of the box: {f.link} ({f.detail}); proved on "
                    f"{float(frac):.1%} of the box before it was found")
        undecided = [p for p in self.pieces if p.status is BoxStatus.UNDECIDED]
        why = undecided[0].verdict if undecided else ""
        return (f"undecided: established on {len(self.proved)} of {n} pieces ({float(frac):.1%} of the box) within "
                f"the work limit of {self.max_boxes} pieces; first undecided piece {undecided[0].box}: {why}"
                if undecided else "undecided")

    @property
    def holds(self) -> bool:
        return self.status is BoxStatus.ESTABLISHED

    @property
    def exit_code(self) -> int:
        return 0 if self.holds else 1

    @property
    def results(self) -> tuple:
        """The results of the first piece's chain (for code that reads a report's rows)."""
        return self.pieces[0].report.results if self.pieces and self.pieces[0].report else ()

    def to_json(self) -> dict:
        return {"schema": SCHEMA_ID, "item": self.item, "parameters": dict(self.parameters), "box": self.box.to_json(),
                "status": self.status.value, "verdict": self.verdict, "proved_fraction": str(self.proved_fraction),
                "checked": self.checked, "max_boxes": self.max_boxes,
                "pieces": [p.to_json() for p in self.pieces],
                "failing": [f.to_json() for f in self.failing],
                "first": None if not self.pieces or self.pieces[0].report is None else self.pieces[0].report.to_json()}

    def _repr_html_(self) -> str:
        from ..report.html import box_html

        return box_html(self)

    def as_text(self, *, verbose: bool = False, width: int = REPORT_WIDTH) -> str:
        """The pieces, failing points and one piece's chain; lines at most ``width`` wide (as
        :meth:`Report.as_text <lkverify.report.results.Report.as_text>`)."""
        lines = wrap_block(f"{self.item} over the box {self.box}", width, limit=None)
        if self.parameters:
            shown = ", ".join(f"{k}={v}" for k, v in self.parameters.items())
            lines += wrap_block("parameters: " + shown, width, indent="  ", limit=None)
        lines += wrap_block(f"pieces: {len(self.pieces)} (checked {self.checked}, limit {self.max_boxes}); proved "
                            f"{len(self.proved)}, {float(self.proved_fraction):.1%} of the box", width, indent="  ")
        for p in self.pieces:
            lines += wrap_block(f"{p.status.value:<11}  {p.box}", width, indent="    ", hang=13, limit=None)
        limit = None if verbose else MAX_LINES
        for f in self.failing:
            lines += wrap_block(f"failing point: {', '.join(f'{k} = {v}' for k, v in f.point.items())}: {f.link}: "
                                f"{f.detail}", width, indent="  ", limit=limit)
        show = next((p for p in self.pieces if p.status is not BoxStatus.ESTABLISHED and p.report is not None),
                    self.pieces[0] if self.pieces else None)
        if show is not None and show.report is not None:
            lines.append("")
            lines += wrap_block(f"the chain on {show.box}:", width, indent="  ", limit=None)
            lines.extend("  " + line for line in show.report.as_text(verbose=verbose, width=width - 2).splitlines()[1:])
        lines += wrap_block(f"verdict: {self.verdict}", width, indent="  ", limit=None)
        return "\n".join(lines)


def _template_names(values: Mapping) -> set:
    """Names of the free symbols in given values (``F = diag(h,h,h)``): a box may take them as variables."""
    out = set()
    for v in values.values():
        if isinstance(v, (sympy.Basic, sympy.MatrixBase)):
            out |= {str(s_) for s_ in v.free_symbols}
    return out


def _written(values: Mapping, box: ParameterBox) -> list:
    """The given values written in the box's variables."""
    return [k for k, v in values.items() if isinstance(v, (sympy.Basic, sympy.MatrixBase))
            and {str(s_) for s_ in v.free_symbols} & set(box.names)]


def _validated(theorem, values: Mapping, box) -> ParameterBox:
    box = box if isinstance(box, ParameterBox) else ParameterBox(box)
    P = theorem.parameters
    templates = _template_names(values) - set(P.names)
    for name, (lo, hi) in box.bounds.items():
        if name in templates:
            continue
        if name not in P.names:
            import difflib

            close = difflib.get_close_matches(name, P.names, n=3)
            raise InputError(f"--box {name}: no such parameter of {theorem.qualified_name}, nor a variable of a "
                             f"--set value" + (f"; did you mean {', '.join(close)}?" if close else
                                                f"; known: {', '.join(P.names)}"))
        if P[name].kind not in _SCALARS:
            raise InputError(f"--box {name}: expected a scalar parameter, got a {P[name].kind.value}; a box has "
                             f"intervals of scalars (fix {name} with --set, or write it in a variable, e.g. --set "
                             f"\"F=diag(h,h,h)\" --box h=1/2:1)")
        if name in values:
            raise InputError(f"--box {name}: {name} is also given with --set; give it one value or one interval")
        for end in (lo, hi):
            P[name].check(end)  # each end admissible (a scalar's admissible set is an interval)
    unboxed = sorted(templates - set(box.names))
    if unboxed:
        raise InputError(f"--set: the variables {', '.join(unboxed)} have no interval; give each one with --box "
                         f"NAME=LO:HI")
    _admissible_over_box(P, values, box)
    return box


def _admissible_over_box(P, values: Mapping, box: ParameterBox) -> None:
    """Each value written in box variables is admissible at every point of the box (else InputError).

    Scalars: the sign their kind needs; positive-definite and diagonal matrices: symmetric, and every
    leading principal minor > 0 over the box (:func:`lkverify.certify.boxes.margin_over_box`).
    """
    symbols = {n: sympy.Symbol(n) for n in box.names}
    intervals = {symbols[n]: b for n, b in box.bounds.items()}
    for name, v in values.items():
        if not isinstance(v, (sympy.Basic, sympy.MatrixBase)) or not v.free_symbols & set(symbols.values()):
            continue
        spec = P[name]
        P[name].check(v.xreplace({symbols[n]: c for n, c in box.center().items()}))  # its shape and kind
        if spec.kind in _SCALARS:
            need = {ParameterKind.POSITIVE: True, ParameterKind.DELAY: True, ParameterKind.NONNEGATIVE: False}
            if spec.kind in need:
                _, holds, detail, _ = margin_over_box(v, intervals, strict=need[spec.kind])
                if not holds:
                    raise InputError(f"{name} = {v}: expected {name} {'>' if need[spec.kind] else '≥'} 0 at every "
                                     f"point of the box {box}; {detail}")
            continue
        if spec.kind is ParameterKind.MATRIX:  # any real entries: nothing to hold over the box
            continue
        if spec.kind not in (ParameterKind.SPD_MATRIX, ParameterKind.DIAGONAL):
            raise InputError(f"{name} = {v}: a {spec.kind.value} written in box variables is not supported; fix it")
        M = sympy.Matrix(v)
        if spec.kind is ParameterKind.DIAGONAL and not M.is_diagonal():
            raise InputError(f"{name} = {v}: expected a diagonal matrix")
        if sympy.expand(M - M.T) != sympy.zeros(*M.shape):
            raise InputError(f"{name} = {v}: expected a symmetric matrix")
        for k in range(1, M.shape[0] + 1):
            minor = sympy.factor(M[:k, :k].det())
            _, holds, detail, _ = margin_over_box(minor, intervals, strict=True)
            if holds is None and not (minor.free_symbols & set(intervals)):
                holds = bool(minor > 0)
            if not holds:
                raise InputError(f"{name} = {v}: expected a positive-definite matrix at every point of the box "
                                 f"{box}; its leading {k}×{k} minor {minor}: {detail}")


def run_over_box(theorem, values: Mapping, box, *, budget: float | None = None,
                 progress: Callable[[str], None] | None = None, max_boxes: int = DEFAULT_MAX_BOXES,
                 hint: Mapping | None = None) -> BoxReport:
    """The chain of ``theorem`` for every point of ``box``, split until it closes (see the module).

    Parameters
    ----------
    theorem : Theorem
    values : mapping
        The fixed parameters (the rest at the paper's defaults).
    box : ParameterBox or mapping name → (lo, hi)
    budget : float, optional
        The caller's wall-clock cap of the whole run (what it cuts is ``undecided``; default none: the
        run stops at its deterministic work limits).
    progress : callable, optional
    max_boxes : int
        The work limit: pieces whose chain is run.
    hint : mapping, optional
        Choices to try after the documented ones and before a search (a neighbouring cell's).

    Raises
    ------
    InputError
        An unknown or non-scalar boxed name, a name both set and boxed, an inadmissible end.

    Examples
    --------
    >>> from lkverify import Parameters, Vector, System, Equation, Functional, Term, t, DerivativeClaim, Hypothesis
    >>> from lkverify.catalogue.items import Theorem
    >>> P = Parameters(); k = P.scalar("k", default=1); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(-k * x(t)[0])])], parameters=P)
    >>> th = Theorem("demo", system=sys, hypotheses=[Hypothesis("k > 0", k)])
    >>> rep = run_over_box(th, {}, {"k": ("1/2", "2")})
    >>> rep.pieces[0].report.results[0].detail
    'margin > 0 over the whole box (enclosure [1/2, 2] by rational interval arithmetic)'
    """
    from ..options import Budget, Deadline, work_limits

    if isinstance(max_boxes, bool) or not isinstance(max_boxes, int) or max_boxes < 1:
        raise InputError(f"max_boxes: expected a positive integer, got {max_boxes!r}")
    say = progress or (lambda msg: None)
    box = _validated(theorem, values, box)
    state = _State(theorem, dict(values))
    theorem.parameters.resolve(state.point_values(box.center()), use_defaults=True)  # the fixed values admissible
    queue, leaves, checked = [(box, dict(hint) if hint else None)], [], 0
    cap = Deadline(Budget.of(budget).seconds, cap=True)  # one wall-clock cap for the whole run (none by default)
    with work_limits():
        while queue:
            piece_box, hint = queue.pop(0)
            if checked >= max_boxes or cap.expired:
                why = (f"the work limit of {max_boxes} pieces was reached" if checked >= max_boxes else
                       f"the budget of {cap.seconds:g} s was spent")
                leaves.append(BoxPiece(piece_box, BoxStatus.UNDECIDED, None, note=f"not checked: {why}"))
                continue
            checked += 1
            say(f"{theorem.qualified_name}: piece {checked} {piece_box}")
            piece = state.piece(piece_box, cap, say, hint)
            if piece.status is BoxStatus.UNDECIDED and not piece_box.is_point \
                    and checked + len(queue) + 2 <= max_boxes and not piece.note:
                queue.extend((half, piece.choices or hint) for half in piece_box.split(piece_box.widest(relative_to=box)))
                continue
            leaves.append(piece)
            if piece.status is BoxStatus.FAILED:
                leaves.extend(BoxPiece(b, BoxStatus.UNDECIDED, None, note="not checked: a failing point was found")
                              for b, _ in queue)
                break
    documented = state.choices_at(box)  # the choices are the pieces' own (each piece's report shows them)
    shown = {**{k: v for k, v in theorem.shown(theorem.parameters.resolve(
        {**documented, **state.point_values(box.center())}, use_defaults=True)).items()
        if k not in box.names and k not in documented},
             **{k: str(v) for k, v in values.items() if k in _written(values, box)},
             **{n: f"[{lo}, {hi}]" for n, (lo, hi) in box.bounds.items()}}
    return BoxReport(theorem.qualified_name, shown, box, tuple(leaves), checked, max_boxes)


class _State:
    """What the pieces of one run share: the identity results, the step results per sign pattern."""

    def __init__(self, theorem, values: dict):
        self.theorem, self.values = theorem, values
        self.claims = None
        self.steps: dict = {}
        self.searched: dict = {}  # the tightest corner → the choices the constants job found there
        self.smaller_region_helps = True  # False after a decay refuted near 0 (its lowest-order part > 0)

    def point_values(self, point: Mapping) -> dict:
        """The given values at one point of the box (name → value; variables of given values substituted)."""
        names = set(self.theorem.parameters.names)
        rep = {sympy.Symbol(n): sympy.Rational(v) for n, v in point.items() if n not in names}
        out = {k: (v.xreplace(rep) if isinstance(v, (sympy.Basic, sympy.MatrixBase)) else v)
               for k, v in self.values.items()}
        return {**out, **{n: v for n, v in point.items() if n in names}}

    def choices_at(self, box: ParameterBox) -> dict:
        """The proof's choices for the box (fixed for it): picked at its centre, or for the whole box by
        a choices function that takes ``box=``."""
        names = set(self.theorem.parameters.names)
        scalars = {n: b for n, b in box.bounds.items() if n in names}
        return self.theorem.chosen(self.point_values(box.center()), box=scalars or None)

    def _values(self, box: ParameterBox, chosen: Mapping):
        """(given, everything with the boxed symbols, intervals, fixed point values) for a piece and choices.

        A boxed name is a scalar parameter (replaced by its symbol) or a variable of a given value
        (``F = diag(h,h,h)``: the value is written in the variable's symbol); the values are
        resolved — defaults and checks — at the piece's centre, then the boxed symbols put in.
        """
        P = self.theorem.parameters
        fixed = {n: lo for n, (lo, hi) in box.bounds.items() if lo == hi}
        moving = {n: b for n, b in box.bounds.items() if b[0] != b[1]}
        kinds = {n: P[n].kind if n in P.names else None for n in box.names}
        symbols = {n: box_symbol(n, b, positive=kinds[n] in (ParameterKind.POSITIVE, ParameterKind.DELAY),
                                 nonnegative=kinds[n] is ParameterKind.NONNEGATIVE) for n, b in moving.items()}
        plain = {sympy.Symbol(n): symbols[n] if n in symbols else fixed[n] for n in box.names if kinds[n] is None}
        centre = {sympy.Symbol(n): c for n, c in box.center().items() if kinds[n] is None}
        written = {k: v for k, v in self.values.items()
                   if isinstance(v, (sympy.Basic, sympy.MatrixBase)) and v.free_symbols & set(plain)}
        at_centre = {**self.values, **{k: v.xreplace(centre) for k, v in written.items()}}
        scalars_fixed = {n: v for n, v in fixed.items() if kinds[n] is not None}
        chosen = {k: v for k, v in chosen.items() if k not in box.names and k not in self.values}
        given = P.resolve({**at_centre, **scalars_fixed}, use_defaults=False)
        everything = P.resolve({**chosen, **at_centre, **scalars_fixed}, use_defaults=True)
        boxed = {k: sympy.ImmutableMatrix(v.xreplace(plain)) if isinstance(v, sympy.MatrixBase) else v.xreplace(plain)
                 for k, v in written.items()}
        for k, v in boxed.items():
            given[k] = v
        sym_values = ResolvedValues({**everything, **boxed, **{n: s_ for n, s_ in symbols.items()
                                                              if kinds[n] is not None}})
        floated_written = {k for k, v in written.items() if {str(s_) for s_ in v.free_symbols} & box.from_float}
        sym_values.from_float = frozenset(getattr(everything, "from_float", ())) | (box.from_float & set(P.names)) \
            | floated_written  # a value written in a variable with a float end went through floating point
        given.from_float = frozenset(getattr(given, "from_float", ())) | (box.from_float & set(scalars_fixed))
        return given, sym_values, {symbols[n]: b for n, b in moving.items()}, fixed

    def piece(self, box: ParameterBox, cap, say, hint: Mapping | None = None) -> BoxPiece:
        """The chain on one piece: hypotheses over it, the identities, then the steps and the decay at the
        documented choices, the choices that closed the parent piece (``hint``), and the choices the
        constants job finds at the piece's tightest corner, in that order, until one closes."""

        th, P = self.theorem, self.theorem.parameters
        documented = self.choices_at(box)
        given, sym_values, intervals, fixed = self._values(box, documented)
        floated = P.float_symbols(sym_values)
        sub = P.substitution(sym_values)
        results: list[Result] = []
        say(f"{th.qualified_name}: hypotheses over {box}")
        failing, margins, unsupported = None, [], []
        written = [k for k, v in self.values.items() if isinstance(v, (sympy.Basic, sympy.MatrixBase))
                   and {str(s_) for s_ in v.free_symbols} & set(box.names)]
        boxed = {s_ for n in [*(n for n in box.names if n in P.names), *written] for s_ in P[n].symbols}
        for h in th.hypotheses:
            if not hasattr(h, "margin"):  # a matrix or a composite hypothesis: decided at a point only
                if _symbols_of(h) & boxed:
                    unsupported.append(h.name)
                    results.append(Result("hypothesis", h.name, Status.UNDECIDED, None,
                                          f"not decided over a box: this kind of hypothesis "
                                          f"({type(h).__name__}) depends on {', '.join(box.names)} and is decided "
                                          f"at points only; fix the parameter with --set"))
                else:
                    results.append(_not_exact_if_floats(h.evaluate(sub, budget=None), _symbols_of(h), floated))
                continue
            margin = apply_substitution(sympy.sympify(h.margin), sub)
            margins.append(margin)
            status, holds, detail, point = margin_over_box(margin, intervals, strict=h.strict)
            if status is None:  # free of the box: as at a point
                res = h.evaluate(sub, budget=None)
            else:
                st = Status.FAILED if holds is False else status
                res = Result("hypothesis", h.name, st, None, f"{h.reference + ': ' if h.reference else ''}{detail}")
                if holds is False and failing is None:
                    failing = FailingPoint({**{str(s): v for s, v in point.items()}, **fixed},
                                           f"hypothesis {h.name}", detail)
            results.append(_not_exact_if_floats(res, _symbols_of(h), floated))
        if failing is not None:
            links = th.chain(results, steps={}, decay=None, cut={st.role: "not checked: a hypothesis fails"
                                                                for st in th.steps})
            report = Report(th.qualified_name, {}, tuple(results), theorem_verdict(links), (), links)
            return BoxPiece(box, BoxStatus.FAILED, report, failing)
        if not all(r.status.is_proof for r in results):  # a margin not decided on this piece: split it
            links = th.chain(results, steps={}, decay=None, cut={st.role: "not checked: a hypothesis is undecided "
                                                                "on this piece" for st in th.steps})
            report = Report(th.qualified_name, {}, tuple(results), theorem_verdict(links), (), links)
            return BoxPiece(box, BoxStatus.UNDECIDED, report, note=report.verdict if unsupported else "")
        if self.claims is None:
            self.claims = th.claim_results(given, cap, say)
        claims, details = self.claims
        moving = [str(s_) for s_ in intervals]
        note = f" (with {', '.join(moving)} symbolic: for every value)" if moving else ""
        results += [dataclasses.replace(r, detail=r.detail + note) if r.status is Status.EXACT else r for r in claims]
        tried, at, last = [], None, {}
        closed = False
        for label, base in self._candidates(box, documented, hint, margins, intervals, fixed, say, last):
            for chosen, shrunk in self._shrunk(base):
                if chosen is None or chosen in tried:
                    continue
                tried.append(chosen)
                _, sym_values, _, _ = self._values(box, chosen)
                rows, checked, cut, failing, decay = self._chain_at(box, sym_values, intervals, fixed, cap, say)
                last.update(checked)
                at = label + shrunk
                closed = failing is not None or (decay is not None and decay.status.is_proof) or not checked
                # a shrunk region only helps the decay, and not one refuted by W's lowest-order part (a search
                # heuristic: the shrunk choices re-derive W, so this may skip a closing choice; never a verdict,
                # what it cuts short stays undecided)
                if closed or decay is None or not self.smaller_region_helps:
                    break
            if closed:
                break
        links = th.chain(results + rows, steps=checked, decay=decay, cut=cut)
        verdict = th._verdict(results + rows, {}, None, checked, decay, cut=cut, at=f"every point of {box}")
        shown = {k: str(v) for k, v in tried[-1].items()} if tried else {}
        report = Report(th.qualified_name, {"choices": f"{at}: " + ", ".join(f"{k} = {v}" for k, v in shown.items())}
                        if shown else {}, tuple(results + rows), verdict, tuple(details), links)
        if failing is not None:
            return BoxPiece(box, BoxStatus.FAILED, report, failing)
        if verdict.startswith("established"):
            return BoxPiece(box, BoxStatus.ESTABLISHED, report, choices=dict(shown))
        if not th.steps:  # nothing a split can change: the theorem has no bound steps
            return BoxPiece(box, BoxStatus.UNDECIDED, report, note=verdict)
        return BoxPiece(box, BoxStatus.UNDECIDED, report, choices=dict(shown))

    def region_names(self) -> list | None:
        """The parameters the V̇ step's region bounds are (``delta_e``, ``delta_w``), or None when a bound
        is not one scalar parameter (then the decay shrinks the region itself, :data:`REGION_FACTORS`)."""
        vdot = next((st for st in self.theorem.steps if st.role == "vdot"), None)
        if vdot is None or vdot.region is None:
            return None
        P = self.theorem.parameters
        by_symbol = {P[n].obj: n for n in P.names if P[n].kind in _SCALARS}
        names = [by_symbol.get(sympy.sympify(b)) for b in vdot.region.bounds.values()]
        return None if None in names else names

    def _shrunk(self, chosen):
        """(choices, note): the choices, then with the region's parameters shrunk by :data:`REGION_FACTORS`
        (the region is a choice of the proof; recorded in the choices, so a check at a point repeats it)."""
        yield chosen, ""
        names = self.region_names()
        if chosen is None or not names or not all(n in chosen for n in names):
            return
        for f in REGION_FACTORS[1:]:
            yield ({**chosen, **{n: str(sympy.Rational(chosen[n]) * f) for n in names}},
                   f", with the region shrunk by {f}")

    def _candidates(self, box, documented, hint, margins, intervals, fixed, say, last):
        """(label, choices) to try on a piece, the search's only when the earlier ones did not close.

        The search runs at the corner whose steps' right-hand sides are closest to the uniform ones
        over the piece (``last``: the steps checked at the earlier choices), then at the corner of
        the smallest hypothesis margins: where the choices must be hardest (a heuristic; what is
        proved does not depend on it)."""
        yield "the documented choices", documented
        if hint:
            yield "the choices of the enclosing piece (or a neighbouring cell)", {**documented, **hint}
        job = self.theorem.constants
        search = getattr(job, "search_choices", None)
        free = list(getattr(job, "free", None) or {})
        if search is None or not getattr(job, "steps", False) or any(k in self.values for k in free):
            return
        worst = _worst_corner(box, last, intervals, fixed) if all(r in last for r in ("lower", "upper", "vdot")) \
            else None
        tightest = _tightest_corner(box, margins, intervals, fixed)
        for corner in ([worst] if worst else []) + ([tightest] if tightest != worst else []):
            key = tuple(sorted((k, str(v)) for k, v in corner.items()))
            if key not in self.searched:
                at = self.theorem.parameters.resolve({**{k: v for k, v in documented.items() if k not in free},
                                                      **self.point_values(corner)}, use_defaults=True)
                memo_key = (self.theorem.qualified_name, BOX_SEARCH_STALL,
                            tuple(sorted((k, str(v)) for k, v in at.items())))
                found = _SEARCHED.owned(job, memo_key, _NOT_SEARCHED)
                if found is _NOT_SEARCHED:
                    say(f"{self.theorem.qualified_name}: searching {', '.join(free)} at the point "
                        + ", ".join(f"{k} = {v}" for k, v in corner.items()))
                    found, _ = search(self.theorem.qualified_name, at, progress=say, stall=BOX_SEARCH_STALL)
                    _SEARCHED.keep(job, memo_key, found)
                else:
                    say(f"{self.theorem.qualified_name}: the choices searched at the point "
                        + ", ".join(f"{k} = {v}" for k, v in corner.items()) + " earlier in this process")
                self.searched[key] = None if found is None else {**documented,
                                                                 **{k: str(v) for k, v in found.items()}}
            where = ", ".join(f"{k} = {v}" for k, v in corner.items())
            yield f"the choices found by the search at {where}", self.searched[key]

    def _chain_at(self, box, sym_values, intervals, fixed, cap, say):
        """(rows, checked, cut, failing, decay link) of the steps and the decay at these values."""

        th, P = self.theorem, self.theorem.parameters
        floated = P.float_symbols(sym_values)
        rows, checked, cut, failing = [], {}, {}, None
        for step in th.steps:
            say(f"{th.qualified_name}: {step.name} over {box}")
            res, how = _capped(cap, lambda: self._step(step, sym_values, intervals, box))
            if how:
                cut[step.role] = _cut_text(cap, how)
                rows.append(Result("bound", step.name, Status.UNDECIDED, None, cut[step.role]))
                continue
            if isinstance(res, str):
                cut[step.role] = res
                rows.append(Result("bound", step.name, Status.UNDECIDED, None, res))
                continue
            rows += [_not_exact_if_floats(r, _symbols_of(step), floated) for r in res.results()]
            checked[step.role] = (step, res)
            bad = next((tr for tr in res.terms if tr.status is Status.FAILED and tr.witness is not None), None)
            if bad is not None and failing is None:
                centre = {str(s_): (sympy.Rational(lo) + sympy.Rational(hi)) / 2 for s_, (lo, hi) in intervals.items()}
                failing = FailingPoint({**centre, **fixed}, step.name, f"{bad.statement}: {bad.detail}")
        decay = None
        if th.decay is not None and all(r in checked and checked[r][1].status.is_proof
                                        for r in ("lower", "upper", "vdot")):
            say(f"{th.qualified_name}: decay over {box}")
            out = self._decay(checked, sym_values, intervals, cap, say)
            if not out[0] and not out[1].is_proof:
                rows.append(Result("region", getattr(th.decay, "link", "decay on the region"), out[1], None, out[2]))
            rows += out[0]
            decay = Link(getattr(th.decay, "link", "decay on the region (V̇ ≤ −c̃V^p, envelope)"), out[1], out[2])
        return rows, checked, cut, failing, decay

    def _step(self, step, sym_values, intervals, box):
        """The step's ChainResult for every point of the box, or why not (a str).

        Kept for the run, keyed by the step, the boxed symbols with their intervals and the values; the
        region's parameters (``delta_e`` …) are left out of the key of a step not written in them (V ≥ L
        and V ≤ U do not change when the region is shrunk)."""

        names = set(self.region_names() or ())
        P = self.theorem.parameters
        used = _symbols_of(step)
        skip = {n for n in names if n in P.names and not (set(P[n].symbols) & used)}
        key = (step.role, step.name,
               tuple(sorted((str(s), tuple(sorted(s.assumptions0.items())), str(b)) for s, b in intervals.items())),
               tuple(sorted((k, str(v)) for k, v in sym_values.items() if k not in skip)))
        hit = self.steps.get(key)
        if hit is not None:
            return hit
        try:
            res = step.check(sym_values, parameter_box=intervals)
        except (InputError, UnsupportedInput, TypeError, ValueError, AttributeError) as exc:
            res = (f"not decided over the box: a rule of this step does not support the boxed parameters "
                   f"symbolically ({type(exc).__name__}: {str(exc).splitlines()[0][:200]})")
        self.steps[key] = res
        return res

    def _decay(self, checked, sym_values, intervals, cap, say):
        """(rows, status, detail) of the decay certified with the steps made uniform over the box."""

        uniform = {}
        try:
            for role, (step, res) in checked.items():
                variables = {m.symbol for m in step.measures}
                direction = "lower" if role == "lower" else "upper"
                uniform[role] = (step, dataclasses.replace(res, rhs=uniform_bound(res.rhs, intervals, variables,
                                                                                   direction)))
        except UnsupportedInput as exc:
            return [], Status.UNDECIDED, f"the steps' bounds cannot be made uniform over the box: {exc}"
        region = getattr(checked.get("vdot", (None,))[0], "region", None)
        first = None
        self.smaller_region_helps = True
        for factor in REGION_FACTORS if region is not None and self.region_names() is None else (1,):
            scaled = None if factor == 1 else region.scaled(factor)
            explain = {}
            out, how = _capped(cap, lambda: self.theorem.decay.certify(uniform, sym_values, budget=None, progress=say,
                                                                        parameter_box=intervals, region=scaled,
                                                                        explain=explain))
            if how:
                return [], Status.UNDECIDED, _cut_text(cap, how, "link")
            rows, status, detail = out
            if status.is_proof:
                if factor != 1:
                    detail = f"on the proof's region scaled by {factor} ({scaled.describe()}): {detail}"
                return rows, status, detail
            first = first or out
            if not explain.get("smaller_region_helps", True):  # refuted near 0: no smaller region helps
                self.smaller_region_helps = False
                break
        return first


def _tightest_corner(box: ParameterBox, margins, intervals: Mapping, fixed: Mapping) -> dict:
    """The corner of the piece where the hypotheses' margins are smallest (their sum, exact): where the
    proof's choices are most constrained; the search runs there (a heuristic: what is proved does not
    depend on it)."""
    by_name = {str(s_): s_ for s_ in intervals}
    best, best_value = None, None
    for corner in box.corners():
        rep = {by_name[k]: v for k, v in corner.items() if k in by_name}
        total = sum((sympy.sympify(m).xreplace(rep) for m in margins), sympy.S.Zero)
        try:
            value = float(total)
        except (TypeError, ValueError):
            value = 0.0
        if best is None or value < best_value:
            best, best_value = corner, value
    return {**best, **fixed}


def _worst_corner(box: ParameterBox, checked: Mapping, intervals: Mapping, fixed: Mapping) -> dict | None:
    """The corner where the steps' right-hand sides are nearest their uniform bounds over the piece
    (the sum over monomials of the relative gaps), or None when they cannot be compared."""
    from ..certify.monomials import collect_monomials

    by_name = {str(s_): s_ for s_ in intervals}
    parts = []
    try:
        for role, (step, res) in checked.items():
            variables = {m.symbol for m in step.measures}
            uniform = collect_monomials(uniform_bound(res.rhs, intervals, variables,
                                                      "lower" if role == "lower" else "upper"), variables)
            parts.append((sympy.expand(res.rhs), variables, uniform))
    except UnsupportedInput:
        return None
    best, best_score = None, None
    for corner in box.corners():
        rep = {by_name[k]: v for k, v in corner.items() if k in by_name}
        score = 0.0
        for rhs, variables, uniform in parts:
            at = collect_monomials(sympy.expand(rhs.xreplace(rep)), variables)
            for mono, u in uniform.items():
                try:
                    score += abs(float(u) - float(at.get(mono, 0))) / (abs(float(u)) + 1e-300)
                except (TypeError, ValueError):
                    return None
        if best is None or score < best_score:
            best, best_score = corner, score
    return None if best is None else {**best, **fixed}
