"""Results and reports: what every lkverify job returns, prints and serialises.

A :class:`Report` is the JSON object of the design card::

    {"item": str, "parameters": {...},
     "results": [{"kind", "name", "status", "value", "detail"}], "verdict": str}
"""

from __future__ import annotations

import dataclasses
import enum
import json
import math
import numbers

import numpy as np

import sympy

from ..status import Label, Status
from ..errors import InputError
from .schema import SCHEMA_ID
from .text import MAX_LINES, REPORT_WIDTH, table, wrap_block

__all__ = ["Kind", "Result", "Report", "jsonable", "value_json"]


class Kind(Label):
    """What a result is about (the ``kind`` of the JSON card).

    >>> Kind("identity") is Kind.IDENTITY
    True
    >>> str(Kind.BOUND)
    'bound'
    """

    HYPOTHESIS = "hypothesis"
    IDENTITY = "identity"
    BOUND = "bound"
    CONSTANT = "constant"
    REGION = "region"
    ENVELOPE = "envelope"
    SIMULATION = "simulation"
    LINEAR = "linear"


KINDS = tuple(k.value for k in Kind)


def jsonable(value):
    """Convert SymPy/NumPy values to JSON-friendly ones (integers stay integers).

    Exact numbers become ints or floats, matrices nested lists, other expressions and
    non-finite floats strings, enums their values; containers are converted item by item.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.status import Status
    >>> import numpy as np
    >>> jsonable([np.int64(2), np.bool_(True), np.float64("nan")])
    [2, True, 'nan']
    >>> jsonable({"half": sympy.Rational(1, 2), "three": sympy.Integer(3), "k": sympy.Symbol("k"),
    ...           "M": sympy.eye(2), "bad": float("inf"), "status": Status.EXACT, 1: (None, True)})
    {'half': 0.5, 'three': 3, 'k': 'k', 'M': [[1, 0], [0, 1]], 'bad': 'inf', 'status': 'exact', '1': [None, True]}
    """
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, enum.Enum):
        return jsonable(value.value)
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, sympy.MatrixBase):
        return [[jsonable(x) for x in row] for row in value.tolist()]
    if isinstance(value, sympy.Basic):
        if value.is_Integer:
            return int(value)
        if value.is_number and value.is_finite:
            return float(value)
        return str(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, numbers.Integral):  # int and NumPy integers stay integers
        return int(value)
    try:
        x = float(value)
    except (TypeError, ValueError):
        return str(value)
    return x if math.isfinite(x) else str(x)


def _exact(value) -> dict:
    """``exact`` and ``latex`` of an exact SymPy value (nothing for a float or a non-SymPy value)."""
    if isinstance(value, (sympy.Basic, sympy.MatrixBase)) and not value.has(sympy.Float):
        return {"exact": str(value), "latex": sympy.latex(value)}
    return {}


def value_json(value):
    r"""A result's ``value`` in the JSON card: ``None`` or an object (one shape for every result).

    A plain value becomes ``{"value": …}``; an exact SymPy value adds its exact string and
    LaTeX (so 1/3 is not only 0.333…); a dict keeps its keys (its ``value`` gets the same
    ``exact``/``latex`` when it is exact).

    Examples
    --------
    >>> import sympy
    >>> value_json(sympy.Rational(1, 3))
    {'value': 0.3333333333333333, 'exact': '1/3', 'latex': '\\frac{1}{3}'}
    >>> value_json(2), value_json(None), value_json([1, 2])
    ({'value': 2}, None, {'value': [1, 2]})
    >>> value_json({"value": sympy.sqrt(2), "paper": 1.41})["exact"]
    'sqrt(2)'
    >>> value_json(sympy.Interval(1, sympy.oo))
    {'value': 'Interval(1, oo)', 'exact': 'Interval(1, oo)', 'latex': '\\left[1, \\infty\\right)'}
    """
    if value is None:
        return None
    if isinstance(value, dict):
        out = jsonable(value)
        if "value" in value and "exact" not in value:
            out.update(_exact(value["value"]))
        return out
    return {"value": jsonable(value), **_exact(value)}


@dataclasses.dataclass(frozen=True)
class Result:
    """One checked statement.

    Attributes
    ----------
    kind : Kind
        What the result is about; a string such as ``"hypothesis"`` is converted.
    name : str
    status : Status
    value : object
        The number (a margin, a constant) or a structured value (term differences).
    detail : str
        One readable sentence.
    label : str
        A short name for the text table (a term's label, not its SymPy statement); empty:
        the ``name``.  The full name is in ``--verbose`` and in the JSON.

    Examples
    --------
    >>> import sympy
    >>> from lkverify.status import Status
    >>> r = Result("bound", "margin > 0", Status.CERTIFIED, sympy.Rational(1, 3), "margin 1/3")
    >>> r.kind, r.to_json()
    (<Kind.BOUND: 'bound'>, {'kind': 'bound', 'name': 'margin > 0', 'status': 'certified', 'value': {'value': 0.3333333333333333, 'exact': '1/3', 'latex': '\\\\frac{1}{3}'}, 'detail': 'margin 1/3'})
    >>> Result("proof", "x", Status.EXACT)
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: result kind: expected one of hypothesis, identity, bound, constant, region, envelope, simulation, linear, got 'proof'
    >>> Result("bound", "x", "exact")
    Traceback (most recent call last):
        ...
    lkverify.errors.InputError: result status: expected a Status, got 'exact'
    """

    kind: Kind
    name: str
    status: Status
    value: object = None
    detail: str = ""
    label: str = ""

    def __post_init__(self):
        if not isinstance(self.kind, Kind):
            if self.kind not in KINDS:
                raise InputError(f"result kind: expected one of {', '.join(KINDS)}, got {self.kind!r}")
            object.__setattr__(self, "kind", Kind(self.kind))
        if not isinstance(self.status, Status):
            raise InputError(f"result status: expected a Status, got {self.status!r}")
        if not isinstance(self.label, str):
            raise InputError(f"result label: expected a string (a short name), got {self.label!r}")

    def to_json(self) -> dict:
        return {"kind": self.kind.value, "name": self.name, "status": self.status.value,
                "value": value_json(self.value), "detail": self.detail}

    def display_value(self) -> tuple:
        r"""(LaTeX or None, text) of the value: LaTeX for an exact SymPy value of a readable size.

        >>> import sympy
        >>> Result("bound", "m", Status.EXACT, sympy.Rational(1, 3)).display_value()
        ('\\frac{1}{3}', '0.333333')
        >>> Result("bound", "m", Status.ESTIMATED, 0.25).display_value()
        (None, '0.25')
        """
        js = value_json(self.value)
        latex = js.get("latex") if js else None
        return (latex if latex is not None and len(latex) <= 200 else None), _fmt_value(self.value)

    def _repr_html_(self) -> str:
        from .html import result_html

        return result_html(self)


@dataclasses.dataclass(frozen=True)
class Report:
    """Everything one job established about one item.

    It holds (exit code 0) only when no result is ``failed`` or ``undecided``.

    Examples
    --------
    >>> from lkverify.status import Status
    >>> rep = Report("demo", {"k": "2"}, (Result("bound", "margin", Status.CERTIFIED, 0.25, "margin > 0"),
    ...                                   Result("identity", "Vdot", Status.UNDECIDED, None, "budget spent")),
    ...              "undecided: Vdot")
    >>> rep.holds, rep.exit_code, [r["status"] for r in rep.to_json()["results"]]
    (False, 1, ['certified', 'undecided'])
    >>> print(rep.as_text())
    demo
      parameters: k=2
      kind      name    status     value  detail
      bound     margin  certified  0.25   margin > 0
      identity  Vdot    undecided         budget spent
      verdict: undecided: Vdot
    """

    item: str
    parameters: dict
    results: tuple
    verdict: str
    text_details: tuple = ()
    chain: tuple = ()

    @property
    def holds(self) -> bool:
        """True when every result holds (no ``failed``, no ``undecided``)."""
        return all(r.status.holds for r in self.results)

    @property
    def exit_code(self) -> int:
        """0 when every result holds and, for a theorem, its chain reaches the conclusion; else 1.

        A theorem that is not established exits 1 even when every result it has holds (a
        missing link is not a result)."""
        conclusion = [link for link in (self.chain or ()) if link.name == "conclusion"]
        not_established = bool(conclusion) and (conclusion[-1].status is None or not conclusion[-1].status.is_proof)
        return 0 if self.holds and not not_established else 1

    def to_json(self) -> dict:
        out = {"schema": SCHEMA_ID, "item": self.item, "parameters": jsonable(self.parameters),
               "results": [r.to_json() for r in self.results], "verdict": self.verdict}
        if self.chain:
            out["chain"] = [link.to_json() for link in self.chain]
        return out

    def dumps(self) -> str:
        return json.dumps(self.to_json(), indent=2, ensure_ascii=False)

    def _repr_html_(self) -> str:
        """Jupyter: a table with coloured statuses, exact values in LaTeX (:mod:`lkverify.report.html`)."""
        from .html import report_html

        return report_html(self)

    def _repr_latex_(self) -> str:
        from .html import report_latex

        return report_latex(self)

    def __repr__(self) -> str:
        return f"<Report {self.item}: {self.verdict[:80]}{'…' if len(self.verdict) > 80 else ''}>"

    def as_text(self, *, verbose: bool = False, width: int = REPORT_WIDTH) -> str:
        """A readable table: kind, name, status, value, detail; then details and the verdict.

        Every line is at most ``width`` characters: cells wrap in their columns and, unless
        ``verbose``, a result's short ``label`` stands for its name and a cell or a detail line
        longer than three lines is cut with ``…``
        (:mod:`lkverify.report.text`); the parameters and the verdict are always whole.
        """
        rows = [(str(r.kind), r.name if verbose or not r.label else r.label, r.status.value, _fmt_value(r.value),
                 r.detail) for r in self.results]
        limit = None if verbose else MAX_LINES
        lines = [f"{self.item}"]
        if self.parameters:
            shown = ", ".join(f"{k}={v}" for k, v in self.parameters.items())
            lines.extend(wrap_block("parameters: " + shown, width, indent="  ", limit=None))
        lines.extend(table(("kind", "name", "status", "value", "detail"), rows, width=width, flexible=(1, 3, 4),
                           weights=(2, 1, 3), floors=(30, 10, 34), limit=limit))
        for block in self.text_details:
            lines.append("")
            lines.extend(wrap_block(block, width, indent="  ", limit=limit))
        lines.extend(wrap_block(f"verdict: {self.verdict}", width, indent="  ", limit=None))
        return "\n".join(lines)


#: the keys under which a result's dict value carries its headline number, in order of preference
_HEADLINE = ("value", "certified", "cap")


def _fmt_value(value) -> str:
    """The value column of the text table: a number, or the headline number of a dict value.

    >>> _fmt_value({"value": 13.951640472760788, "paper": 9.21}), _fmt_value({"certified": 5.63583}), _fmt_value(None)
    ('13.9516', '5.63583', '')
    """
    if value is None:
        return ""
    if isinstance(value, dict):
        if value.get("differences"):
            return "see below"
        for key in _HEADLINE:
            x = value.get(key)
            if isinstance(x, (int, float)) and not isinstance(x, bool):
                return f"{x:.6g}"
        return ""
    v = jsonable(value)
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)
