"""Text reports fit a terminal: every line at most 100 columns, cells cut only without ``verbose``."""

import random
import re

import pytest

from lkverify.report.results import Report, Result
from lkverify.report.text import REPORT_WIDTH, table, wrap_block, wrap_lines
from lkverify.status import Status

LONG_EXPR = "-Dinv_norm*c10p*tau**(1/(2*nu + 2))*(alpha1*(I1*(2*nu + 1)/(eta_K**(1/(2*nu + 1))*(2*nu + 2))))" * 3
LONG_DETAIL = " ".join(f"word{k}" for k in range(300))


def _report(**extra):
    results = (Result("hypothesis", "tau > 0", Status.EXACT, 1, "holds: margin 1 > 0"),
               Result("bound", "V ≥ L: −LᵀD⁻¹∫f^ν(ξ)L(ξ)dξ ≥ " + LONG_EXPR, Status.CERTIFIED, None, LONG_DETAIL),
               Result("identity", "Vdot_printed", Status.FAILED, {"differences": [1]}, "Matrix([\n[1, 2],\n[3, 4]])"))
    params = {f"p{k}": f"{k}/1000" for k in range(60)}
    return Report("demo.item", params, results, "established: " + LONG_DETAIL,
                  text_details=("Vdot_printed: failed — difference: " + LONG_EXPR + "\n  ✓ confirmed: short",), **extra)


def _words(text):
    return re.findall(r"word\d+", text)


@pytest.mark.parametrize("verbose", [False, True])
def test_every_line_fits_100_columns(verbose):
    text = _report().as_text(verbose=verbose)
    assert max(len(line) for line in text.splitlines()) <= REPORT_WIDTH


def test_cells_are_cut_with_an_ellipsis_unless_verbose():
    short, full = _report().as_text(), _report().as_text(verbose=True)
    assert "…" in short and len(short) < len(full)
    # verbose: the whole detail, in order, and the verdict; the short form keeps the verdict whole too
    assert _words(full).count("word299") == 2 and "word299" in short.split("verdict:")[1]
    assert "…" not in full


def test_a_multiline_cell_does_not_break_the_table():
    lines = _report().as_text().splitlines()
    (row,) = [k for k, line in enumerate(lines) if line.startswith("  identity")]
    # the Matrix repr's newlines become spaces inside its cell: no line starts at the margin with "[3, 4]"
    assert "Matrix([ [1, 2], [3, 4]])" in lines[row]
    assert not any(line.startswith("[") for line in lines)


def test_narrow_width_is_honoured():
    text = _report().as_text(width=60)
    assert max(len(line) for line in text.splitlines()) <= 60


def test_the_json_keeps_everything():
    js = _report().to_json()
    assert js["results"][1]["detail"] == LONG_DETAIL and js["results"][1]["name"].endswith(LONG_EXPR)


def test_random_tables_fit():
    rng = random.Random(1)
    for _ in range(200):
        width = rng.randint(50, 140)
        floors = tuple(rng.randint(0, 40) for _ in range(3)) if rng.random() < 0.5 else None
        weights = tuple(rng.randint(1, 4) for _ in range(3)) if rng.random() < 0.5 else None
        rows = [(rng.choice(["bound", "hypothesis"]),)
                + tuple("".join(rng.choice("ab ∫ᵀ*") for _ in range(rng.randint(0, 300))) for _ in range(3))
                for _ in range(rng.randint(1, 5))]
        lines = table(("kind", "name", "value", "detail"), rows, width=width, flexible=(1, 2, 3), limit=None,
                      floors=floors, weights=weights)
        assert max(len(line) for line in lines) <= width
        # nothing is lost when not cut: the non-space characters of every cell are all printed
        printed = "".join(lines[1:]).replace(" ", "")
        assert len(printed) == sum(len(c.replace(" ", "")) for row in rows for c in row)


def test_wrap_block_keeps_indentation_and_width():
    lines = wrap_block("  - item " + "x" * 250, 50, indent="  ", limit=None)
    assert lines[0].startswith("    - item") and all(len(line) <= 50 for line in lines)
    assert all(line.startswith(" " * 8) for line in lines[1:])
    assert "".join(l.strip() for l in lines).count("x") == 250


def test_wrap_lines_limit():
    assert len(wrap_lines("a " * 200, 20, limit=3)) == 3
    assert wrap_lines("a " * 200, 20, limit=3)[-1].endswith("…")
    assert len(wrap_lines("a " * 200, 20, limit=None)) > 3


def test_a_label_stands_for_the_name_unless_verbose():
    from lkverify.errors import InputError

    r = Result("bound", "V ≤ U: xᵀMx ≤ 3*n**2 + " + "y" * 80, Status.EXACT, None, "Rayleigh", label="V ≤ U: xᵀMx")
    rep = Report("demo", {}, (r,), "established")
    assert "V ≤ U: xᵀMx " in rep.as_text() and "yyyy" not in rep.as_text()
    assert "yyyy" in rep.as_text(verbose=True) and rep.to_json()["results"][0]["name"] == r.name
    with pytest.raises(InputError, match="label"):
        Result("bound", "x", Status.EXACT, label=3)
