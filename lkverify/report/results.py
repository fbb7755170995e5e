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

__all__ = ["Kind", "Result", "Report", "jsonable"]


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

    Examples
    --------
    >>> import sympy
    >>> from lkverify.status import Status
    >>> r = Result("bound", "margin > 0", Status.CERTIFIED, sympy.Rational(1, 3), "margin 1/3")
    >>> r.kind, r.to_json()
    (<Kind.BOUND: 'bound'>, {'kind': 'bound', 'name': 'margin > 0', 'status': 'certified', 'value': 0.3333333333333333, 'detail': 'margin 1/3'})
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

    def __post_init__(self):
        if not isinstance(self.kind, Kind):
            if self.kind not in KINDS:
                raise InputError(f"result kind: expected one of {', '.join(KINDS)}, got {self.kind!r}")
            object.__setattr__(self, "kind", Kind(self.kind))
        if not isinstance(self.status, Status):
            raise InputError(f"result status: expected a Status, got {self.status!r}")

    def to_json(self) -> dict:
        return {"kind": self.kind.value, "name": self.name, "status": self.status.value,
                "value": jsonable(self.value), "detail": self.detail}


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
        out = {"item": self.item, "parameters": jsonable(self.parameters),
               "results": [r.to_json() for r in self.results], "verdict": self.verdict}
        if self.chain:
            out["chain"] = [link.to_json() for link in self.chain]
        return out

    def dumps(self) -> str:
        return json.dumps(self.to_json(), indent=2, ensure_ascii=False)

    def as_text(self) -> str:
        """A readable table: kind, name, status, value, detail; then details and the verdict."""
        rows = [(str(r.kind), r.name, r.status.value, _fmt_value(r.value), r.detail) for r in self.results]
        head = ("kind", "name", "status", "value", "detail")
        widths = [max(len(h), *(len(row[i]) for row in rows)) if rows else len(h) for i, h in enumerate(head[:4])]
        lines = [f"{self.item}"]
        if self.parameters:
            lines.append("  parameters: " + ", ".join(f"{k}={v}" for k, v in self.parameters.items()))
        lines.append("  " + "  ".join(h.ljust(w) for h, w in zip(head[:4], widths)) + "  detail")
        for row in rows:
            lines.append("  " + "  ".join(c.ljust(w) for c, w in zip(row[:4], widths)) + "  " + row[4])
        for block in self.text_details:
            lines.append("")
            lines.extend("  " + line for line in block.splitlines())
        lines.append(f"  verdict: {self.verdict}")
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
