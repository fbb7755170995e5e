"""Every package of the tree is installed: pyproject's explicit package list misses none.

A package missing from ``[tool.setuptools] packages`` works in an editable install and
fails on a clean ``pip install .`` (it happened with ``lkverify.certify.intervals``).
"""

import pathlib
import pytest

tomllib = pytest.importorskip("tomllib")  # Python ≥ 3.11

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _packages_in_tree():
    found = set()
    for top, name in (("lkverify", "lkverify"), ("proofs", "lkverify.proofs")):
        for init in (ROOT / top).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / top)
            found.add(".".join([name, *rel.parts]) if rel.parts else name)
    return found


def test_every_package_is_listed_in_pyproject():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    listed = set(config["tool"]["setuptools"]["packages"])
    assert _packages_in_tree() - listed == set()
    assert listed - _packages_in_tree() == set()
