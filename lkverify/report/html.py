"""Reports in Jupyter: HTML tables with coloured statuses, exact values in LaTeX.

:class:`~lkverify.report.results.Report`, :class:`~lkverify.report.results.Result` and
the box and sweep results call these from their ``_repr_html_`` / ``_repr_latex_``, so a
notebook cell that ends with a report shows a table instead of a wall of text.  Every
string from a report is HTML-escaped; exact SymPy values are shown as ``$…$`` (MathJax).
"""

from __future__ import annotations

import html

__all__ = ["STATUS_COLOURS", "status_badge", "report_html", "result_html", "report_latex", "box_html"]

#: the colour of each status (and of the box statuses) in HTML reports
STATUS_COLOURS = {"exact": "#1a7f37", "certified": "#0969da", "established": "#1a7f37", "estimated": "#9a6700",
                  "simulated": "#8250df", "failed": "#cf222e", "undecided": "#6e7781"}

_STYLE = ("border-collapse:collapse;font-size:0.9em;text-align:left", "padding:2px 8px;vertical-align:top;"
          "border-bottom:1px solid #d0d7de;text-align:left")


def status_badge(status: str) -> str:
    """A coloured label for a status.

    >>> status_badge("exact")
    '<span style="color:#fff;background:#1a7f37;border-radius:3px;padding:0 4px">exact</span>'
    """
    colour = STATUS_COLOURS.get(status, "#57606a")
    return (f'<span style="color:#fff;background:{colour};border-radius:3px;padding:0 4px">'
            f'{html.escape(status)}</span>')


def _value_cell(result) -> str:
    latex, text = result.display_value()
    return f"${latex}$" if latex is not None else html.escape(text)


def result_html(result, *, row: bool = False) -> str:
    """One result as a table row (``row=True``) or as a one-row table."""
    cells = (html.escape(str(result.kind)), html.escape(result.label or result.name), status_badge(result.status.value),
             _value_cell(result), html.escape(result.detail))
    tr = "<tr>" + "".join(f'<td style="{_STYLE[1]}">{c}</td>' for c in cells) + "</tr>"
    return tr if row else f'<table style="{_STYLE[0]}">{_head()}{tr}</table>'


def _head() -> str:
    return "<tr>" + "".join(f'<th style="{_STYLE[1]}">{h}</th>' for h in ("kind", "name", "status", "value",
                                                                            "detail")) + "</tr>"


def _verdict_colour(verdict: str) -> str:
    head = verdict.split(":", 1)[0].strip()
    if head.startswith("established") or head == "holds":
        return STATUS_COLOURS["exact"]
    if head.startswith(("failed", "unstable", "not established")):
        return STATUS_COLOURS["failed"]
    return STATUS_COLOURS["undecided"]


def report_html(report) -> str:
    """A report as HTML: the item, its parameters, the results table, the details and the verdict.

    >>> from lkverify.report.results import Report, Result
    >>> from lkverify.status import Status
    >>> import sympy
    >>> rep = Report("demo", {"k": "2"}, (Result("bound", "a<b", Status.EXACT, sympy.Rational(1, 3)),), "established")
    >>> text = report_html(rep)
    >>> "a&lt;b" in text and "$\\\\frac{1}{3}$" in text and "#1a7f37" in text
    True
    """
    parts = [f'<div class="lkverify-report"><p><b>{html.escape(report.item)}</b></p>']
    if report.parameters:
        shown = ", ".join(f"{k} = {v}" for k, v in report.parameters.items())
        parts.append(f'<p style="font-size:0.85em">parameters: {html.escape(shown)}</p>')
    rows = "".join(result_html(r, row=True) for r in report.results)
    parts.append(f'<table style="{_STYLE[0]}">{_head()}{rows}</table>')
    for block in report.text_details:
        first, _, rest = block.partition("\n")
        parts.append(f"<details><summary>{html.escape(first[:160])}</summary>"
                     f"<pre style=\"white-space:pre-wrap\">{html.escape(block)}</pre></details>")
    parts.append(f'<p><b style="color:{_verdict_colour(report.verdict)}">verdict</b>: '
                 f"{html.escape(report.verdict)}</p></div>")
    return "".join(parts)


def _latex_text(s: str) -> str:
    out = s
    for a, b in (("\\", r"\textbackslash{}"), ("{", r"\{"), ("}", r"\}"), ("_", r"\_"), ("&", r"\&"), ("%", r"\%"),
                 ("#", r"\#"), ("$", r"\$"), ("^", r"\^{}")):
        out = out.replace(a, b)
    return r"\text{" + out + "}"


def report_latex(report) -> str:
    """A report as a LaTeX array (kind, name, status, value): exact values as formulas.

    >>> from lkverify.report.results import Report, Result
    >>> from lkverify.status import Status
    >>> import sympy
    >>> print(report_latex(Report("demo", {}, (Result("bound", "m_1", Status.EXACT, sympy.sqrt(2)),), "holds")))
    $$\\begin{array}{llll}\\text{kind} & \\text{name} & \\text{status} & \\text{value}\\\\ \\hline \\text{bound} & \\text{m\\_1} & \\text{exact} & \\sqrt{2}\\\\ \\end{array}$$
    """
    lines = [r"\text{kind} & \text{name} & \text{status} & \text{value}\\ \hline"]
    for r in report.results:
        latex, text = r.display_value()
        value = latex if latex is not None else _latex_text(text)
        lines.append(f"{_latex_text(str(r.kind))} & {_latex_text(r.label or r.name)} & "
                     f"{_latex_text(r.status.value)} & {value}\\\\")
    return r"$$\begin{array}{llll}" + " ".join(lines) + r" \end{array}$$"


def box_html(box) -> str:
    """A box report: the pieces with their statuses, the failing points, the chain on one piece, the verdict."""
    parts = [f'<div class="lkverify-box"><p><b>{html.escape(box.item)}</b> over the box '
             f"{html.escape(str(box.box))}: {status_badge(box.status.value)} "
             f"({float(box.proved_fraction):.1%} proved, {len(box.pieces)} pieces)</p>"]
    rows = "".join(f'<tr><td style="{_STYLE[1]}">{status_badge(p.status.value)}</td>'
                   f'<td style="{_STYLE[1]}">{html.escape(str(p.box))}</td>'
                   f'<td style="{_STYLE[1]}">{html.escape(p.verdict)}</td></tr>' for p in box.pieces)
    parts.append(f'<table style="{_STYLE[0]}">{rows}</table>')
    for f in box.failing:
        where = ", ".join(f"{k} = {v}" for k, v in f.point.items())
        parts.append(f"<p>failing point {html.escape(where)}: {html.escape(f.link)}: {html.escape(f.detail)}</p>")
    parts.append(f'<p><b style="color:{STATUS_COLOURS.get(box.status.value, "#57606a")}">verdict</b>: '
                 f"{html.escape(box.verdict)}</p></div>")
    return "".join(parts)
