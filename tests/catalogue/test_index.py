"""The catalogue's index (issue 25, cold start): ``lkverify list`` and an unknown name import no proof, no SymPy.

The committed index (lkverify/catalogue/index_data.py) must be the loaded catalogue's; the names of
``lkverify`` and ``lkverify.catalogue`` are imported on first use.  What is imported is checked in a
fresh interpreter (``sys.modules``); how long it takes is benchmarks/bench_startup.py's business.
"""

import json
import subprocess
import sys

import pytest

import lkverify
import lkverify.catalogue
from lkverify.catalogue import index
from lkverify.catalogue import loader
from lkverify.catalogue.loader import catalogue, find_items
from lkverify.errors import InputError

HEAVY = ("sympy", "numpy", "scipy", "numba", "dask", "cvxpy", "matplotlib")


def _imported_after(code: str) -> dict:
    """Run ``code`` in a fresh interpreter; which heavy libraries and proof modules it imported."""
    probe = (f"import sys\n{code}\n"
             f"import json\n"
             f"print(json.dumps({{'heavy': sorted(m for m in {HEAVY!r} if m in sys.modules), "
             f"'proofs': sorted(m for m in sys.modules if m.startswith('lkverify.proofs'))}}))")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_committed_index_is_the_catalogue_s():
    rows = index.index_rows(catalogue())
    assert rows == index.read_index(), (f"lkverify/catalogue/index_data.py is stale (an item was added, renamed or "
                                        f"retitled): run `{index.REGENERATE}` and commit the file")


def test_the_index_has_every_item_once_with_its_kind():
    rows = index.read_index()
    assert len({r.item for r in rows}) == len(rows)
    by = {r.item: r for r in rows}
    assert by["aleksandrov2023.theorem3"].kind == "theorem"
    assert by["aleksandrov2023.fig6"].kind == "example"
    assert {r.kind for r in rows} == {"theorem", "check", "example"}
    assert index.package_of("aleksandrov2017.lemma1") == "lkverify.proofs.aleksandrov2017"
    assert index.package_of("somov") == "lkverify.proofs.somov"
    assert index.package_of("somov.nothing") is None


def test_an_unknown_name_suggests_the_close_ones():
    message = index.unknown_item_message("aleksandrov2023.theorm3")
    assert message.startswith("aleksandrov2023.theorm3: unknown item; did you mean aleksandrov2023.theorem3")
    assert message.endswith("?")
    assert index.unknown_item_message("aleksandrov203") .startswith(
        "aleksandrov203: unknown item; did you mean aleksandrov2023")  # a paper's name is suggested too
    assert index.unknown_item_message("qqqq") == "qqqq: unknown item; see `lkverify list`"
    with pytest.raises(InputError) as err:
        find_items("aleksandrov2023.theorm3")
    assert str(err.value) == message


def test_a_known_name_and_a_paper_are_found():
    (item,) = find_items("aleksandrov2017.lemma1")
    assert item.qualified_name == "aleksandrov2017.lemma1"
    names = [it.qualified_name for it in find_items("zaremba1997")]
    assert names == [r.item for r in index.read_index() if r.paper == "zaremba1997"]


def test_a_stale_index_falls_back_to_the_whole_catalogue(monkeypatch):
    # the index points at the wrong package (as after moving an item): the item is still found
    monkeypatch.setattr(loader, "package_of", lambda name: "lkverify.proofs.somov")
    (item,) = find_items("aleksandrov2023.theorem3")
    assert item.qualified_name == "aleksandrov2023.theorem3"
    with pytest.raises(InputError, match="unknown item; did you mean aleksandrov2023.theorem3"):
        find_items("aleksandrov2023.theorm3")


def test_an_unknown_name_imports_no_proof_and_no_sympy():
    seen = _imported_after("from lkverify.catalogue.loader import find_items\n"
                           "try:\n    find_items('aleksandrov2023.theorm3')\nexcept ValueError:\n    pass")
    assert seen == {"heavy": [], "proofs": []}


def test_list_and_an_unknown_check_import_no_proof_and_no_sympy():
    seen = _imported_after("import contextlib, io, lkverify.cli\n"
                           "with contextlib.redirect_stdout(io.StringIO()):\n"
                           "    assert lkverify.cli.main(['list']) == 0\n"
                           "    assert lkverify.cli.main(['list', '--json']) == 0\n"
                           "    assert lkverify.cli.main(['check', 'aleksandrov2023.theorm3']) == 2")
    assert seen == {"heavy": [], "proofs": []}


def test_help_and_version_import_no_heavy_library():
    seen = _imported_after("import contextlib, io, lkverify.cli\n"
                           "with contextlib.redirect_stdout(io.StringIO()):\n"
                           "    assert lkverify.cli.main(['--help']) == 0\n"
                           "    assert lkverify.cli.main(['--version']) == 0")
    assert seen == {"heavy": [], "proofs": []}


def test_import_lkverify_loads_no_sympy():
    assert _imported_after("import lkverify\nimport lkverify.catalogue") == {"heavy": [], "proofs": []}


def test_every_public_name_resolves_and_is_listed():
    for module in (lkverify, lkverify.catalogue):
        for name in module.__all__:
            assert getattr(module, name) is not None, name
        assert set(module.__all__) <= set(dir(module))
    assert lkverify.Theorem is lkverify.catalogue.Theorem
    assert lkverify.__version__
    with pytest.raises(AttributeError, match="module 'lkverify' has no attribute 'Theorm'"):
        lkverify.Theorm  # noqa: B018
    with pytest.raises(AttributeError, match="module 'lkverify.catalogue' has no attribute 'nothing'"):
        lkverify.catalogue.nothing  # noqa: B018


def test_star_import_gives_every_public_name():
    namespace = {}
    exec("from lkverify import *", namespace)
    assert set(lkverify.__all__) <= set(namespace)
    assert namespace["Theorem"] is lkverify.Theorem
