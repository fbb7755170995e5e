"""The notebooks in notebooks/ run in a real Jupyter kernel and their committed outputs are up to date.

Each notebook is executed from scratch (nbclient, ipykernel's python3 kernel, working
directory the repository root) by ``notebooks/regenerate.py``; its text outputs and the
presence of its figures are compared cell by cell with what is committed (volatile parts
normalised). Regenerate with ``python3 notebooks/regenerate.py``.
"""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytest.importorskip("nbclient", reason='the notebook check needs the test extra: python3 -m pip install -e ".[test]"')
pytest.importorskip("ipykernel", reason='the notebook check needs the test extra: python3 -m pip install -e ".[test]"')

_spec = importlib.util.spec_from_file_location("notebooks_regenerate", ROOT / "notebooks" / "regenerate.py")
regenerate = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(regenerate)

import nbformat  # noqa: E402 - after the skip above

NOTEBOOKS = regenerate.notebooks()


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 3


@pytest.mark.slow  # 1–4 min per notebook; the default run executes the small notebook below in a real kernel
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs_and_outputs_are_up_to_date(path):
    committed = nbformat.read(path, as_version=4)
    assert sum(c.cell_type == "code" for c in committed.cells) >= 2
    try:
        fresh = regenerate.execute(path)
    except regenerate.NotebookError as err:
        pytest.fail(str(err), pytrace=False)
    problems = regenerate.compare(committed, fresh, f"notebooks/{path.name}")
    if problems:
        pytest.fail("\n\n".join(problems) + f"\n\nThe committed outputs are out of date: regenerate them with "
                    f"`{regenerate.REGENERATE}` (see notebooks/README.md).", pytrace=False)


def test_a_small_notebook_runs_in_a_real_kernel_and_a_raising_cell_is_named(tmp_path):
    """The cheap stand-in of the notebook check: a two-cell notebook importing lkverify, then one that raises."""
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# a small notebook"),
                nbformat.v4.new_code_cell("import lkverify\nfrom lkverify.status import Status\nprint(Status.EXACT.value)"),
                nbformat.v4.new_code_cell("print(sum(range(4)))")]
    path = tmp_path / "small.ipynb"
    nbformat.write(nb, path)
    fresh = regenerate.execute(path)
    outputs = ["".join(o.get("text", "") for o in c.outputs) for c in fresh.cells if c.cell_type == "code"]
    assert outputs == ["exact\n", "6\n"]
    stale = nbformat.from_dict(fresh)
    stale.cells[2].outputs[0]["text"] = "7\n"
    assert regenerate.compare(fresh, fresh, "small.ipynb") == []
    (msg,) = regenerate.compare(stale, fresh, "small.ipynb")
    assert "code cell 2" in msg and "text output differs" in msg
    raising = nbformat.v4.new_notebook()
    raising.cells = [nbformat.v4.new_code_cell("x = 1"), nbformat.v4.new_code_cell("x / 0")]
    nbformat.write(raising, tmp_path / "raising.ipynb")
    with pytest.raises(regenerate.NotebookError, match=r"raising.ipynb, code cell 2: the cell raised ZeroDivisionError"):
        regenerate.execute(tmp_path / "raising.ipynb")


# -- the comparison itself (no kernel) --------------------------------------------------------
def test_volatile_parts_are_normalised():
    same = regenerate.same_text
    assert same("done in 1.2 s at 0x7f00aa", "done in 13.05 s at 0x5500bb")
    assert same("took 30 ms", "took 2.5 seconds")
    assert same("certified 1.4071424945662958", "certified 1.4071424945669")
    assert same("reaches 1e-2 at t = 188.70000000000002", "reaches 1e-2 at t = 188.7")
    assert not same("certified 1.40714", "certified 1.40716")
    assert not same("status exact", "status certified")
    assert not same("distance at t = 300: 0.00248", "distance at t = 400: 0.00248")
    assert not same("margin −0.5", "margin 0.5")


def _nb(*cells):
    nb = nbformat.v4.new_notebook()
    for text, images in cells:
        c = nbformat.v4.new_code_cell("print(1)")
        c.outputs = ([nbformat.v4.new_output("stream", name="stdout", text=text)] if text is not None else [])
        c.outputs += [nbformat.v4.new_output("display_data", data={"image/png": "AAAA", "text/plain": "<Figure>"})
                      for _ in range(images)]
        nb.cells.append(c)
    return nb


def test_compare_names_the_cell():
    fresh = _nb(("a 1\n", 0), ("b\n", 1))
    assert regenerate.compare(_nb(("a 1.0000000001\n", 0), ("b\n", 1)), fresh, "x.ipynb") == []
    (msg,) = regenerate.compare(_nb(("a 1\n", 0), ("b\n", 0)), fresh, "x.ipynb")
    assert msg.startswith("x.ipynb, code cell 2") and "0 image(s) committed, 1 produced" in msg
    (msg,) = regenerate.compare(_nb(("a 2\n", 0), ("b\n", 1)), fresh, "x.ipynb")
    assert "code cell 1" in msg and "text output differs" in msg
    (msg,) = regenerate.compare(_nb((None, 0), ("b\n", 1)), fresh, "x.ipynb")
    assert "committed without outputs" in msg
