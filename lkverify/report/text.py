"""The text layout of reports: a table and paragraphs that fit a terminal.

Every line of a report is at most :data:`REPORT_WIDTH` characters (100) wide: table
cells wrap inside their column, long paragraphs wrap with a hanging indent, and, unless
``verbose``, a cell or a detail line that would take more than :data:`MAX_LINES` lines is
cut with ``…`` (the full text is in ``--verbose`` and in ``--json``).  The layout uses
the standard library's :mod:`textwrap`; nothing here knows what a report is about.
"""

from __future__ import annotations

import textwrap

__all__ = ["REPORT_WIDTH", "MAX_LINES", "wrap_block", "wrap_lines", "table"]

#: the width of every line of a text report (without ``--verbose`` long cells are cut)
REPORT_WIDTH = 100
#: the lines a table cell or a detail line may take before it is cut (without ``verbose``)
MAX_LINES = 3
_ELLIPSIS = "…"
#: a column narrower than this is not worth wrapping into
_MIN_COLUMN = 8


def _cut(lines: list, limit: int | None, width: int) -> list:
    """At most ``limit`` lines (``None``: all), the last one ending in an ellipsis when cut."""
    if limit is None or len(lines) <= limit:
        return lines
    kept = lines[:limit]
    last = kept[-1]
    kept[-1] = (last[: width - 1] if len(last) >= width else last) + _ELLIPSIS
    return kept


def wrap_lines(text: str, width: int, *, limit: int | None = MAX_LINES) -> list:
    """``text`` wrapped to ``width`` columns, at most ``limit`` lines (``None``: all).

    Long words (a SymPy expression without spaces) are broken; an empty text is one empty line.

    Examples
    --------
    >>> wrap_lines("alpha beta gamma delta", 11)
    ['alpha beta', 'gamma delta']
    >>> wrap_lines("x" * 30, 10, limit=2)
    ['xxxxxxxxxx', 'xxxxxxxxx…']
    >>> wrap_lines("", 10)
    ['']
    """
    width = max(width, _MIN_COLUMN)
    lines = textwrap.wrap(text, width=width, break_long_words=True, break_on_hyphens=False,
                          replace_whitespace=True, drop_whitespace=True) or [""]
    return _cut(lines, limit, width)


def wrap_block(text: str, width: int = REPORT_WIDTH, *, indent: str = "", hang: int = 4,
               limit: int | None = MAX_LINES) -> list:
    """Every line of ``text`` wrapped to ``width`` after ``indent``, continuation lines
    indented ``hang`` more than the line's own leading spaces; each source line at most
    ``limit`` output lines (``None``: all).

    Examples
    --------
    >>> for line in wrap_block("verdict: failed because of a long reason", 24, indent="  "):
    ...     print(repr(line))
    '  verdict: failed'
    '      because of a long'
    '      reason'
    >>> all(len(line) <= 30 for line in wrap_block("  a " + "b" * 200, 30, limit=None))
    True
    """
    out = []
    for source in text.splitlines() or [""]:
        body = source.lstrip(" ")
        lead = indent + " " * (len(source) - len(body))
        room = max(width - len(lead), _MIN_COLUMN + hang)
        first, *rest = wrap_lines(body, room, limit=None) if body else [""]
        wrapped = [lead + first]
        if rest:
            wrapped += [lead + " " * hang + line for line in wrap_lines(" ".join(rest), room - hang, limit=None)]
        out.extend(_cut(wrapped, limit, width))
    return out


def table(head: tuple, rows: list, *, width: int = REPORT_WIDTH, indent: str = "  ", flexible: tuple = (),
          weights: tuple | None = None, floors: tuple | None = None, limit: int | None = MAX_LINES) -> list:
    """The lines of a table whose cells wrap inside their columns.

    Columns are as wide as their widest cell, except the ``flexible`` ones (indices),
    which share what is left of ``width``: the narrowest keep their natural width, the
    others get shares in proportion to ``weights`` (default equal), none narrower than its
    entry of ``floors`` (or its content; the floors shrink together when the table is narrow),
    8 or its heading; a wrapped cell takes at most ``limit`` lines.

    Examples
    --------
    >>> rows = [("bound", "a rather long name of a step", "exact", "a detail that is long as well")]
    >>> for line in table(("kind", "name", "status", "detail"), rows, width=40, flexible=(1, 3), limit=None):
    ...     print(line.rstrip())
      kind   name        status  detail
      bound  a rather    exact   a detail
             long name           that is
             of a step           long as
                                 well
    >>> for line in table(("kind", "name", "status", "detail"), rows, width=40, flexible=(1, 3), limit=2):
    ...     print(line.rstrip())
      kind   name        status  detail
      bound  a rather    exact   a detail
             long name…          that is…
    """
    ncol = len(head)
    natural = [max([len(head[i])] + [len(row[i]) for row in rows]) for i in range(ncol)]
    fixed = sum(natural[i] for i in range(ncol) if i not in flexible)
    room = width - len(indent) - 2 * (ncol - 1) - fixed
    widths = list(natural)
    left = max(room, _MIN_COLUMN * len(flexible))
    weight = dict(zip(flexible, weights or (1,) * len(flexible)))
    floor = dict(zip(flexible, floors or (0,) * len(flexible)))

    def least(i):  # the width a column keeps whatever the others take
        return max(min(natural[i], floor[i]), min(_MIN_COLUMN, natural[i]), len(head[i]))

    need = sum(least(i) for i in flexible)
    if need > left:  # a narrow table: the floors shrink together
        floor = {i: floor[i] * left // need for i in flexible}
    # weighted max-min fair shares: the narrowest flexible columns keep their natural width, the rest share
    # what is left in proportion to their weights, none under its floor and leaving the later ones theirs
    order = sorted(flexible, key=lambda j: natural[j] / weight[j])
    for k, i in enumerate(order):
        share = left * weight[i] // sum(weight[j] for j in order[k:])
        room_i = left - sum(least(j) for j in order[k + 1:])
        widths[i] = max(min(natural[i], max(share, least(i)), room_i), min(_MIN_COLUMN, natural[i]), len(head[i]))
        left -= widths[i]
    lines = [indent + "  ".join(h.ljust(w) for h, w in zip(head, widths)).rstrip()]
    for row in rows:
        cells = [wrap_lines(str(c), w, limit=limit) if i in flexible else [str(c)]
                 for i, (c, w) in enumerate(zip(row, widths))]
        for k in range(max(len(c) for c in cells)):
            parts = [(c[k] if k < len(c) else "").ljust(w) for c, w in zip(cells, widths)]
            lines.append((indent + "  ".join(parts)).rstrip())
    return lines
