"""Reports in Jupyter: HTML with coloured statuses, exact values as LaTeX, everything escaped."""

import sympy

from lkverify.report.html import STATUS_COLOURS, report_html, report_latex
from lkverify.report.results import Report, Result
from lkverify.status import Status


def _report(verdict="established: every link exact"):
    return Report("demo<1>", {"A": "[[1, 2], [3, 4]]"},
                  tuple(Result("bound", f"step {s.value}", s, sympy.Rational(1, 3) if s is Status.EXACT else 0.25,
                               "d<etail>", label=f"short {s.value}") for s in Status),
                  verdict, text_details=("a finding\n  with <lines>",))


def test_every_status_has_its_colour_and_nothing_is_unescaped():
    text = _report()._repr_html_()
    for s in Status:
        assert STATUS_COLOURS[s.value] in text
    assert "<1>" not in text and "demo&lt;1&gt;" in text and "d&lt;etail&gt;" in text and "&lt;lines&gt;" in text
    assert "short exact" in text and "step exact" not in text          # the label, as in the text table
    assert text.count("<tr>") == 1 + len(Status)


def test_exact_values_are_latex():
    text = report_html(_report())
    assert "$\\frac{1}{3}$" in text and "0.25" in text
    assert "\\frac{1}{3}" in report_latex(_report()) and report_latex(_report()).startswith("$$")


def test_the_verdict_colour_follows_the_verdict():
    assert STATUS_COLOURS["exact"] in report_html(_report()).split("verdict")[-2]
    assert STATUS_COLOURS["failed"] in report_html(_report("not established: V ≥ L refuted")).split("verdict")[-2]


def test_a_result_and_the_plain_repr():
    r = Result("hypothesis", "a > 0", Status.FAILED, -1, "fails")
    assert "<table" in r._repr_html_() and STATUS_COLOURS["failed"] in r._repr_html_()
    assert repr(_report()).startswith("<Report demo<1>: established")
