"""Execute the walkthrough notebooks with a real Jupyter kernel and store their outputs.

Run from anywhere (the notebooks are always executed with the repository root as the
working directory)::

    python3 notebooks/regenerate.py                      # every notebook, outputs written back
    python3 notebooks/regenerate.py aleksandrov2017      # only the named notebook(s)
    python3 notebooks/regenerate.py --check              # execute, compare, write nothing

The same functions drive ``tests/test_notebooks.py``: :func:`execute` runs a notebook
from scratch through nbclient (ipykernel's ``python3`` kernel, errors are failures) and
:func:`compare` says which code cells' outputs differ from the committed ones, once the
volatile parts are normalised (see :func:`normalise_text`).
"""

from __future__ import annotations

import argparse
import copy
import difflib
import math
import re
import sys
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "notebooks"
REGENERATE = "python3 notebooks/regenerate.py"
#: seconds a single cell may take before the run is an error
CELL_TIMEOUT = 600
#: relative tolerance on every number printed by a cell (float noise beyond ~6 significant digits)
REL_TOL = 1e-6


def notebooks() -> list[Path]:
    """The walkthroughs, by name."""
    return sorted(NOTEBOOK_DIR.glob("*.ipynb"))


def strip_outputs(nb):
    """A copy of ``nb`` without outputs and execution counts (what the kernel starts from)."""
    nb = copy.deepcopy(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
            cell.metadata.pop("execution", None)
    return nb


def execute(path: Path, *, timeout: int = CELL_TIMEOUT):
    """Execute the notebook at ``path`` from scratch in a fresh kernel; return the executed notebook.

    The kernel's working directory is the repository root; a cell that raises stops the
    run with :class:`nbclient.exceptions.CellExecutionError` (naming the cell).
    """
    nb = strip_outputs(nbformat.read(path, as_version=4))
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", allow_errors=False,
                            record_timing=False, resources={"metadata": {"path": str(ROOT)}})
    try:
        client.execute()
    except CellExecutionError as err:
        index = next((k for k, c in enumerate(nb.cells) if c.cell_type == "code" and
                      any(o.output_type == "error" for o in c.get("outputs", []))), None)
        code_no = None if index is None else sum(c.cell_type == "code" for c in nb.cells[:index + 1])
        tail = "\n".join(_ANSI.sub("", str(err)).strip().splitlines()[-12:])
        raise NotebookError(f"{path.name}, code cell {code_no}: the cell raised {err.ename}: {err.evalue}\n"
                            f"{tail}") from None
    nb.metadata.pop("widgets", None)
    return nb


class NotebookError(RuntimeError):
    """A cell of a notebook raised (the message names the notebook, the cell and the error)."""


_ANSI = re.compile(r"\x1b\[[0-9;]*m")


# -- comparison -------------------------------------------------------------------------------
_ADDRESS = re.compile(r"\b0x[0-9a-fA-F]+\b")
# a duration: "1.2 s", "0.03s", "12 ms", "3.1 seconds", "in 2.0 sec"
_TIMING = re.compile(r"(?<![\w.])\d+(?:\.\d+)?(?:[eE][-+]?\d+)?\s?(?:s|ms|µs|us|sec|secs|seconds?)\b")
_NUMBER = re.compile(r"(?<![\w.])[-+−]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+−]?\d+)?")


def normalise_text(text: str) -> str:
    """Volatile parts replaced: memory addresses by ``0x…``, durations by ``<time>``."""
    text = _ADDRESS.sub("0x…", text)
    return _TIMING.sub("<time>", text)


def _tokens(text: str) -> list:
    """Text pieces and numbers (as floats) of ``normalise_text(text)``."""
    out, pos = [], 0
    for m in _NUMBER.finditer(text):
        out.append(text[pos:m.start()])
        out.append(float(m.group().replace("−", "-")))
        pos = m.end()
    out.append(text[pos:])
    return out


def same_text(a: str, b: str) -> bool:
    """Equal after :func:`normalise_text`, numbers within :data:`REL_TOL` of each other."""
    ta, tb = _tokens(normalise_text(a)), _tokens(normalise_text(b))
    if len(ta) != len(tb):
        return False
    for x, y in zip(ta, tb):
        if isinstance(x, float) != isinstance(y, float):
            return False
        if isinstance(x, float):
            if not math.isclose(x, y, rel_tol=REL_TOL, abs_tol=1e-12):
                return False
        elif x != y:
            return False
    return True


def summary(cell) -> tuple[str, int]:
    """What is compared of a code cell: its text/plain outputs (stdout, results) and its number of images.

    Standard error (warnings, progress) is not compared.
    """
    text, images = [], 0
    for out in cell.get("outputs", []):
        if out.output_type == "stream":
            if out.name == "stdout":
                text.append(out.text)
        elif out.output_type in ("execute_result", "display_data"):
            data = out.get("data", {})
            images += sum(1 for mime in data if mime.startswith("image/"))
            if "text/plain" in data:
                text.append(data["text/plain"] + "\n")
        elif out.output_type == "error":
            text.append(f"{out.ename}: {out.evalue}\n")
    return "".join(text), images


def compare(committed, fresh, name: str) -> list[str]:
    """One message per code cell whose committed outputs differ from the fresh run's (empty: up to date)."""
    problems = []
    old = [c for c in committed.cells if c.cell_type == "code"]
    new = [c for c in fresh.cells if c.cell_type == "code"]
    if len(old) != len(new):
        return [f"{name}: {len(old)} code cells committed, {len(new)} executed"]
    for k, (a, b) in enumerate(zip(old, new)):
        (ta, ia), (tb, ib) = summary(a), summary(b)
        where = f"{name}, code cell {k + 1} (first line: {b.source.splitlines()[0] if b.source else ''!r})"
        if not a.get("outputs") and b.get("outputs"):
            problems.append(f"{where}: committed without outputs")
        elif ia != ib:
            problems.append(f"{where}: {ia} image(s) committed, {ib} produced")
        elif not same_text(ta, tb):
            problems.append(f"{where}: text output differs\n{_diff(ta, tb)}")
    return problems


def _diff(committed: str, fresh: str, *, lines: int = 40) -> str:
    """The differing lines (unified diff, at most ``lines`` lines)."""
    old, new = committed.splitlines(), fresh.splitlines()
    out = [line for line in difflib.unified_diff(old, new, "committed", "fresh run", n=0, lineterm="")
           if not line.startswith("@@")]
    if not out:  # equal line by line once normalised: numbers beyond the tolerance somewhere
        out = ["--- committed", *old, "+++ fresh run", *new]
    return "\n".join(out[:lines] + ([f"... ({len(out) - lines} more lines)"] if len(out) > lines else []))


# -- command line -----------------------------------------------------------------------------
def _select(names) -> list[Path]:
    paths = notebooks()
    if not names:
        return paths
    chosen = []
    for n in names:
        hits = [p for p in paths if p.stem == Path(n).stem]
        if not hits:
            raise SystemExit(f"no notebook {n!r} in {NOTEBOOK_DIR} (have: {', '.join(p.stem for p in paths)})")
        chosen += hits
    return chosen


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="notebooks to run (stem or file name); default all")
    parser.add_argument("--check", action="store_true", help="compare with the committed outputs, write nothing")
    args = parser.parse_args(argv)
    status = 0
    for path in _select(args.names):
        t0 = time.perf_counter()
        try:
            fresh = execute(path)
        except NotebookError as err:
            print(f"ERROR {err}", file=sys.stderr)
            status = 1
            continue
        seconds = time.perf_counter() - t0
        if args.check:
            problems = compare(nbformat.read(path, as_version=4), fresh, path.name)
            print(f"{path.name}: {seconds:.1f} s, " + ("up to date" if not problems else "OUT OF DATE"))
            for p in problems:
                print("  " + p.replace("\n", "\n  "))
            status |= bool(problems)
        else:
            nbformat.validate(fresh)
            nbformat.write(fresh, path)
            print(f"{path.name}: executed in {seconds:.1f} s, outputs written")
    return status


if __name__ == "__main__":
    sys.exit(main())
