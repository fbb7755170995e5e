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


def test_help_of_the_package_has_no_inherited_builtin_noise():
    """help(lkverify) documents lkverify's names, not the members of str, BaseException or EnumType."""
    import pydoc

    import lkverify

    text = pydoc.render_doc(lkverify, renderer=pydoc.plaintext)
    assert "inherited from builtins" not in text and "inherited from enum.EnumType" not in text
    assert "casefold" not in text and "with_traceback" not in text
    for name in ("Status", "InputError", "BudgetExceeded"):
        assert f"class {name}" in text
    # the hidden members still work
    assert len(lkverify.Status) == 6 and lkverify.Status["EXACT"] is lkverify.Status.EXACT
    assert lkverify.InputError("x").with_traceback(None).args == ("x",)


def test_every_public_name_has_a_doctest_example():
    import importlib
    import inspect

    missing = []
    for module in ("lkverify", "lkverify.declare", "lkverify.symbolic", "lkverify.certify", "lkverify.certify.steps",
                   "lkverify.certify.intervals", "lkverify.simulate", "lkverify.catalogue", "lkverify.report",
                   "lkverify.linear", "lkverify.sweep"):
        mod = importlib.import_module(module)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if (inspect.isclass(obj) or inspect.isfunction(obj)) and ">>>" not in (inspect.getdoc(obj) or ""):
                missing.append(f"{module}.{name}")
    assert missing == []


def _cache_size_after_import(env_value):
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if k != "SYMPY_CACHE_SIZE"}
    if env_value is not None:
        env["SYMPY_CACHE_SIZE"] = env_value
    code = "import lkverify, sympy.core.cache as c; print(c.SYMPY_CACHE_SIZE)"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return out.stdout.strip()


def test_importing_lkverify_first_enlarges_sympys_cache_unless_the_user_chose_a_size():
    import lkverify

    assert _cache_size_after_import(None) == str(lkverify.SYMPY_CACHE_SIZE) != "1000"
    assert _cache_size_after_import("500") == "500"          # the user's setting wins
    assert _cache_size_after_import("None") == "None"
