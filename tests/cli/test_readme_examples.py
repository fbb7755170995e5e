"""The README's console examples do what the README says: extracted from README.md and run.

Each ``$ lkverify …`` line of a ``console`` block is run in a fresh process (from a
temporary directory holding the README's proof file, so ``--plot`` files and
``my_proof.py`` resolve there).  The expected exit code is the one the README's comment
states (``# exit 1: …``), 0 otherwise; ``--json`` output must parse; no traceback ever.
The quick ones (the README's own proof file) run by default, the catalogue's items,
simulations, constants and linear examples with ``-m slow``.
"""

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"
#: commands whose run takes more than a few seconds (long simulations, the bare report, estimate (15))
SLOW = ("lkverify simulate", "lkverify report", "lkverify constants aleksandrov2023",
        "lkverify constants aleksandrov2017.lemma1 --plot", "lkverify check aleksandrov2026.theorem1",
        "lkverify check aleksandrov2026.remark1", "lkverify constants aleksandrov2026.remark1",
        "lkverify check aleksandrov2023.theorem", "lkverify check aleksandrov2017.theorem1",
        'lkverify linear --set "A=[[-2,0],[0,-0.9]]" --set "Ad=[[-1,0],[-1,-1]]" --plot', "lkverify constants somov",
        "lkverify sweep",
        # 10–50 s each on a loaded 2-core machine
        "lkverify list", "lkverify check", "lkverify constants", "lkverify linear")
#: the examples the default run keeps (a few seconds: the README's own proof files)
FAST = ("lkverify check my_proof.py", "lkverify check matrix_proof.py")


def _console_lines():
    text = README.read_text(encoding="utf-8")
    for block in re.findall(r"```console\n(.*?)```", text, flags=re.S):
        for line in block.splitlines():
            if line.startswith("$ lkverify"):
                yield line[2:]


def _proof_files() -> dict:
    """The README's proof files: every python block whose first line is ``# NAME.py: …``."""
    text = README.read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    return {m.group(1): b for b in blocks for m in [re.match(r"# (\w+\.py):", b)] if m}


def test_the_readme_has_its_proof_files():
    assert {"my_proof.py", "matrix_proof.py"} <= set(_proof_files())


def _cases():
    for line in _console_lines():
        command, _, comment = line.partition("#")
        m = re.match(r"\s*exit (\d+)", comment)
        expected = int(m.group(1)) if m else 0
        marks = [pytest.mark.slow] if command.startswith(SLOW) and not command.startswith(FAST) else []
        yield pytest.param(command.strip(), expected, id=command.strip()[9:60], marks=marks)


def test_the_readme_has_console_examples():
    lines = list(_console_lines())
    assert len(lines) >= 10 and any("exit 1" in line for line in lines)


@pytest.mark.parametrize("command, expected", list(_cases()))
def test_readme_console_example(command, expected, tmp_path):
    for name, source in _proof_files().items():
        (tmp_path / name).write_text(source, encoding="utf-8")
    argv = shlex.split(command)
    proc = subprocess.run([sys.executable, "-m", "lkverify", *argv[1:], "--quiet"] if "--quiet" not in argv
                          else [sys.executable, "-m", "lkverify", *argv[1:]],
                          cwd=tmp_path, capture_output=True, text=True, timeout=900)
    assert "Traceback" not in proc.stderr, proc.stderr[-2000:]
    assert proc.returncode == expected, f"{command}: exit {proc.returncode}, README says {expected}\n{proc.stderr[-1000:]}"
    if "--json" in argv:
        json.loads(proc.stdout)
    for i, a in enumerate(argv):
        if a == "--plot":
            assert (tmp_path / argv[i + 1]).stat().st_size > 10_000  # a figure was written


def test_every_readme_command_writes_its_own_file():
    """Two README lines must not write the same figure or table (one would overwrite the other)."""
    written = [m for line in _console_lines() for m in re.findall(r"--(?:plot|out) (\S+)", line)]
    assert written and len(written) == len(set(written)), sorted(written)
