"""The JSON Schema of lkverify's ``--json`` output (``lkverify/report/schema.json``).

Every object a command prints at the top level carries ``"schema": SCHEMA_ID``; the schema
file in the package documents every key, and :func:`validate` checks a document against it
with the ``jsonschema`` library (installed with the test extras).

Examples
--------
>>> from lkverify.report.results import Report, Result
>>> from lkverify.status import Status
>>> doc = Report("demo", {}, (Result("bound", "margin", Status.EXACT, 1, "margin > 0"),), "holds").to_json()
>>> doc["schema"], doc["results"][0]["value"]
('lkverify-report/1', {'value': 1})
>>> validate(doc)
>>> validate({"schema": SCHEMA_ID, "item": "demo"})        # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
ValueError: not lkverify JSON output (schema lkverify-report/1): ...
"""

from __future__ import annotations

import functools
import json
from importlib import resources

__all__ = ["SCHEMA_ID", "schema", "validate"]

#: the value of the ``schema`` key of every top-level JSON object lkverify prints
SCHEMA_ID = "lkverify-report/1"


@functools.lru_cache(maxsize=1)
def schema() -> dict:
    """The JSON Schema (draft 2020-12) of the ``--json`` output, as a dict."""
    return json.loads(resources.files(__package__).joinpath("schema.json").read_text(encoding="utf-8"))


def validate(doc) -> None:
    """Raise ``ValueError`` (with the first violation) unless ``doc`` is valid ``--json`` output.

    Examples
    --------
    >>> validate({"schema": SCHEMA_ID, "items": [{"item": "p.t", "kind": "theorem", "title": "T"}]})
    >>> validate({"schema": SCHEMA_ID, "items": [{"item": "p.t", "kind": "lemma", "title": "T"}]})
    Traceback (most recent call last):
        ...
    ValueError: not lkverify JSON output (schema lkverify-report/1): at items/0/kind: 'lemma' is not one of ['theorem', 'check', 'example']
    """
    try:
        import jsonschema
    except ImportError as exc:  # pragma: no cover - jsonschema comes with the test extras
        raise ImportError("validating lkverify's JSON needs the jsonschema package: "
                          "python3 -m pip install jsonschema") from exc
    validator = jsonschema.Draft202012Validator(schema())
    error = jsonschema.exceptions.best_match(validator.iter_errors(doc))
    if error is not None:
        where = "/".join(str(p) for p in error.absolute_path) or "the document"
        raise ValueError(f"not lkverify JSON output (schema {SCHEMA_ID}): at {where}: {error.message}")
