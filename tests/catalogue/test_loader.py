"""The catalogue loader: one import path per item, user files by path, proof modules declarative."""

import ast
import importlib
import pkgutil
import sys
from pathlib import Path

import pytest

import lkverify.proofs
from lkverify import InputError, Item
from lkverify.catalogue.loader import PROOFS_PACKAGE, catalogue, find_items, load_proof_file

PROOFS_DIR = Path(lkverify.proofs.__file__).resolve().parent
PAPERS = sorted(info.name for info in pkgutil.iter_modules(lkverify.proofs.__path__))
PROOF_SOURCES = sorted(PROOFS_DIR.rglob("*.py"))


def test_the_papers_are_packages():
    assert PAPERS == ["aleksandrov2017", "aleksandrov2023", "aleksandrov2026", "somov", "zaremba1997"]  # DESIGN.md names
    for paper in PAPERS:
        assert hasattr(importlib.import_module(f"{PROOFS_PACKAGE}.{paper}"), "__path__")


def test_the_catalogue_item_is_the_imported_item():
    import lkverify.proofs.aleksandrov2023 as paper

    (item,) = find_items("aleksandrov2023.theorem3")
    assert lkverify.proofs.aleksandrov2023.theorem3 is item
    assert paper.theorem3.constants is item.constants


def test_every_catalogue_item_has_one_import_path():
    for pf in catalogue():
        module = importlib.import_module(f"{PROOFS_PACKAGE}.{pf.paper}")
        for name, item in pf.items.items():
            assert getattr(module, name) is item
    assert not [name for name in sys.modules if name.startswith("lkverify_proof_aleksandrov")]


def test_items_know_their_paper_without_the_loader():
    from lkverify.proofs.aleksandrov2017 import lemma1
    from lkverify.proofs.aleksandrov2026 import theorem2

    assert lemma1.qualified_name == "aleksandrov2017.lemma1"
    assert theorem2.qualified_name == "aleksandrov2026.theorem2"


@pytest.mark.parametrize("paper", PAPERS)
def test_every_item_of_a_paper_is_exported(paper):
    package = importlib.import_module(f"{PROOFS_PACKAGE}.{paper}")
    assert all(hasattr(package, name) for name in package.__all__)
    exported = {id(getattr(package, name)) for name in package.__all__}
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        assert all(hasattr(module, name) for name in module.__all__), info.name
        for value in vars(module).values():
            if isinstance(value, Item):
                assert id(value) in exported, f"{paper}.{info.name}: item {value.name} is not re-exported"


def test_a_catalogue_path_is_imported_under_its_real_name():
    (item,) = find_items("aleksandrov2023.theorem3")
    pf = load_proof_file(PROOFS_DIR / "aleksandrov2023" / "__init__.py")
    assert pf.items["theorem3"] is item
    pf = load_proof_file(PROOFS_DIR / "aleksandrov2023" / "theorem3.py")
    assert list(pf.items) == ["theorem3"] and pf.items["theorem3"] is item


USER_FILE = '''
from lkverify import Check
from lkverify.proofs.aleksandrov2023 import P, system, theorem3

PAPER = "mine"
own = Check("own", parameters=P, checks=[lambda v: []])
'''


def test_a_user_file_building_on_the_catalogue_keeps_its_items_apart(tmp_path):
    path = tmp_path / "mine.py"
    path.write_text(USER_FILE)
    pf = load_proof_file(path)
    assert list(pf.items) == ["own"] and pf.paper == "mine"
    (item,) = find_items("aleksandrov2023.theorem3")
    assert item.qualified_name == "aleksandrov2023.theorem3"


def test_a_user_file_with_only_catalogue_items_declares_none(tmp_path):
    path = tmp_path / "reexport.py"
    path.write_text("from lkverify.proofs.aleksandrov2023 import theorem3\n")
    with pytest.raises(InputError, match="declares no item"):
        load_proof_file(path)


# -- the proof modules are declarative -------------------------------------------------------------

def _tree(path):
    return ast.parse(path.read_text(), filename=str(path))


@pytest.mark.parametrize("path", PROOF_SOURCES, ids=lambda p: str(p.relative_to(PROOFS_DIR)))
def test_imports_only_at_the_top_and_only_public_names(path):
    assert "noqa: E402" not in path.read_text()
    body = _tree(path).body
    first = next((k for k, node in enumerate(body) if not isinstance(node, (ast.Import, ast.ImportFrom))
                  and not (k == 0 and isinstance(node, ast.Expr))), len(body))
    late = [node.lineno for node in body[first:] if isinstance(node, (ast.Import, ast.ImportFrom))]
    assert not late, f"module-level imports after the declarations at lines {late}"
    for node in body[:first]:
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("lkverify"):
            assert not any(part.startswith("_") for part in node.module.split(".")), node.module
            assert not any(alias.name.startswith("_") for alias in node.names), node.module


@pytest.mark.parametrize("path", PROOF_SOURCES, ids=lambda p: str(p.relative_to(PROOFS_DIR)))
def test_no_attribute_is_assigned_at_module_level(path):
    patched = [node.lineno for node in _tree(path).body if isinstance(node, (ast.Assign, ast.AugAssign))
               for target in (node.targets if isinstance(node, ast.Assign) else [node.target])
               if isinstance(target, ast.Attribute)]
    assert not patched, f"attributes assigned after construction at lines {patched}"
