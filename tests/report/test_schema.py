"""Every ``--json`` output validates against the documented schema (``lkverify/report/schema.json``)."""

import copy
import json

import pytest

from lkverify.cli import main
from lkverify.report.schema import SCHEMA_ID, schema, validate

T3 = "aleksandrov2023.theorem3"

COMMANDS = {
    "list": ["list", "--json"],
    "check": ["check", T3, "--set", "a=0", "--set", "b=-1", "--json"],                # a hypothesis fails
    "check several": ["check", "aleksandrov2017.lemma1", "--json"],
    "check box": ["check", T3, "--box", "b=-1/10:1/10", "--box", "tau=9/10:11/10", "--json"],
    "constants": ["constants", "aleksandrov2017.lemma1", "--set", "eps=0.9", "--json"],
    "simulate": ["simulate", "aleksandrov2023.fig6", "--t-end", "5", "--json"],
    "linear": ["linear", "--set", "A=[[-2,0],[0,-0.9]]", "--set", "Ad=[[-1,0],[-1,-1]]", "--orders", "0",
               "--h-max", "8", "--json"],
    "sweep": ["sweep", "aleksandrov2023.fig1", "--set", "F=diag(h,h,h)", "--scheduler", "synchronous",
              "--grid", "b=2:2:1", "--grid", "h=0.7:0.7:1", "--t-end", "1", "--json"],
}


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """Each command's JSON, run once in process."""
    import contextlib
    import io

    folder = tmp_path_factory.mktemp("schema")
    docs = {}
    for name, argv in COMMANDS.items():
        extra = ["--out", str(folder / "sweep.parquet")] if name == "sweep" else []
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            code = main([*argv, *extra, "--quiet"])
        assert code in (0, 1), (name, code)
        docs[name] = json.loads(buf.getvalue())
    return docs


@pytest.mark.parametrize("name", list(COMMANDS))
def test_every_command_output_validates(outputs, name):
    doc = outputs[name]
    validate(doc)
    tops = doc if isinstance(doc, list) else [doc]
    assert tops and all(d["schema"] == SCHEMA_ID for d in tops)


def test_values_have_one_shape_and_exact_strings(outputs):
    results = [r for name in ("check", "constants", "linear") for d in [outputs[name]]
               for r in (d if isinstance(d, list) else [d])[0]["results"]]
    assert all(r["value"] is None or isinstance(r["value"], dict) for r in results)
    # an exact margin keeps its exact string and LaTeX beside the float
    exact = [r["value"] for r in results if r["value"] and "exact" in r["value"]]
    assert exact and all(isinstance(v["latex"], str) for v in exact)


@pytest.mark.parametrize("mutate, where", [
    (lambda d: d.pop("schema"), "schema"),
    (lambda d: d.update(schema="lkverify-report/0"), "schema"),
    (lambda d: d["results"][0].update(status="proved"), "status"),
    (lambda d: d["results"][0].update(value=3), "value"),
    (lambda d: d["results"][0].update(kind="proof"), "kind"),
    (lambda d: d["results"][0].pop("detail"), "detail"),
    (lambda d: d["results"][0]["value"].update(exact="1/3") if d["results"][0]["value"] else
     d["results"][0].update(value={"exact": "1/3"}), "latex"),
])
def test_a_mutated_document_is_refused(outputs, mutate, where):
    doc = copy.deepcopy(outputs["check"])
    doc["results"][0]["value"] = {"value": 1} if doc["results"][0]["value"] is None else doc["results"][0]["value"]
    doc["results"][0]["value"].pop("latex", None)
    doc["results"][0]["value"].pop("exact", None)
    validate(doc)                                   # the unmutated copy is valid
    mutate(doc)
    with pytest.raises(ValueError, match="not lkverify JSON output"):
        validate(doc)


def test_the_schema_is_a_valid_json_schema():
    import jsonschema

    jsonschema.Draft202012Validator.check_schema(schema())
    assert schema()["$id"] == SCHEMA_ID
