"""The proof cache (issue 25 item 3): keys, integrity, the command line, the bare report."""

import json

import pytest
import sympy

from lkverify import cache as cache_mod
from lkverify.cache import CachedReport, ProofCache, cached_run, item_key, report_payload
from lkverify.catalogue import report_job
from lkverify.cli import main
from lkverify.report.results import Report, Result
from lkverify.status import Status


def _report(name="demo.item", note="m > 0"):
    return Report(name, {"k": "2"}, (Result("bound", "m", Status.CERTIFIED, sympy.Rational(1, 4), note),), "holds")


@pytest.fixture
def cache(tmp_path):
    return ProofCache(tmp_path / "cache")


@pytest.fixture
def on(tmp_path, monkeypatch):
    """The cache switched on in a fresh directory, for the command line."""
    monkeypatch.setenv("LKVERIFY_CACHE", "on")
    monkeypatch.setenv("LKVERIFY_CACHE_DIR", str(tmp_path / "cli-cache"))
    return ProofCache(tmp_path / "cli-cache")


# -- keys ------------------------------------------------------------------------------------------
def test_the_key_changes_with_every_thing_it_depends_on(cache, monkeypatch):
    base = cache.key("check", "p.item", values={"a": sympy.Integer(1)}, options={"box": []})
    assert base == cache.key("check", "p.item", values={"a": sympy.Integer(1)}, options={"box": []})
    assert base != cache.key("check", "p.other", values={"a": sympy.Integer(1)}, options={"box": []})
    assert base != cache.key("check", "p.item", values={"a": sympy.Float(1.0)}, options={"box": []})   # 1 ≠ 1.0
    assert base != cache.key("check", "p.item", values={"a": sympy.Rational(1, 3)}, options={"box": []})
    assert base != cache.key("check", "p.item", values={"a": sympy.Integer(1)}, options={"box": ["b=0:1"]})
    assert base != cache.key("report", "p.item", values={"a": sympy.Integer(1)}, options={"box": []})
    monkeypatch.setitem(cache_mod._DIGEST, "source", "0" * 64)                  # another source tree
    assert base != cache.key("check", "p.item", values={"a": sympy.Integer(1)}, options={"box": []})
    monkeypatch.undo()
    monkeypatch.setitem(cache_mod._DIGEST, "versions", {"sympy": "0.0"})         # another library version
    assert base != cache.key("check", "p.item", values={"a": sympy.Integer(1)}, options={"box": []})


def test_the_source_digest_reads_the_proof_modules_too():
    import lkverify.proofs

    cache_mod._DIGEST.pop("source", None)
    assert len(cache_mod.source_digest()) == 64
    assert lkverify.proofs.__path__                                               # what it hashed besides lkverify


def test_a_malformed_key_is_refused(cache):
    with pytest.raises(Exception, match="64 hex digits"):
        cache.get("../../etc/passwd")


# -- integrity -------------------------------------------------------------------------------------
def test_an_entry_round_trips(cache):
    key = item_key(cache, "demo.item")
    assert cache.put(key, report_payload(_report()))
    got = CachedReport(cache.get(key))
    assert got.as_text() == _report().as_text()
    assert got.as_text(verbose=True) == _report().as_text(verbose=True)
    assert got.to_json() == json.loads(json.dumps(_report().to_json()))
    assert got.exit_code == 0 and got.holds


def _entry_path(cache, key):
    return cache._path(key)


def test_an_edited_entry_is_detected_deleted_and_not_served(cache):
    key = item_key(cache, "demo.item")
    cache.put(key, report_payload(_report()))
    path = _entry_path(cache, key)
    entry = json.loads(path.read_text())
    entry["payload"] = entry["payload"].replace("m > 0", "m > 1")              # a tampered detail
    path.write_text(json.dumps(entry))
    assert cache.get(key) is None
    assert not path.exists()


def test_a_truncated_or_foreign_entry_is_not_served(cache):
    key, other = item_key(cache, "demo.item"), item_key(cache, "demo.other")
    cache.put(key, report_payload(_report()))
    path = _entry_path(cache, key)
    good = path.read_text()
    path.write_text(good[: len(good) // 2])                                      # a cut write
    assert cache.get(key) is None
    cache.put(key, report_payload(_report()))
    target = _entry_path(cache, other)                                          # an entry copied under another key
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(path.read_text())
    assert cache.get(other) is None
    assert cache.get(key) is not None


def test_entries_of_another_secret_are_not_served(cache):
    key = item_key(cache, "demo.item")
    cache.put(key, report_payload(_report()))
    (cache.directory / "key").write_bytes(b"x" * 32)                            # the key replaced
    assert cache.get(key) is None
    (cache.directory / "key").unlink()                                          # or gone
    cache.put(key, report_payload(_report()))
    (cache.directory / "key").unlink()
    assert cache.get(key) is None


def test_an_unwritable_directory_costs_the_cache_not_the_job(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    cache = ProofCache(blocker / "cache")
    key = item_key(cache, "demo.item")
    assert cache.put(key, report_payload(_report())) is False
    assert cached_run(cache, key, _report).as_text() == _report().as_text()


def test_clear_and_stats(cache):
    for name in ("a.x", "a.y"):
        cache.put(item_key(cache, name), report_payload(_report(name)))
    assert cache.stats()["entries"] == 2
    assert cache.clear() == 2
    assert cache.stats()["entries"] == 0


# -- the command line ------------------------------------------------------------------------------
def _fail_if_run(*args, **kwargs):
    raise AssertionError("the item was run although its report is cached")


def test_check_twice_serves_the_second_from_the_cache_with_the_same_output(on, capsys, monkeypatch):
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    first = capsys.readouterr().out
    assert on.stats()["entries"] == 1
    from lkverify.catalogue.items import Check

    monkeypatch.setattr(Check, "run", _fail_if_run)
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    assert capsys.readouterr().out == first
    assert main(["check", "somov.kinematics", "--quiet", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["item"] == "somov.kinematics"


def test_no_cache_and_the_switch_recompute(on, capsys, monkeypatch):
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    capsys.readouterr()
    from lkverify.catalogue.items import Check

    calls = []
    real = Check.run
    monkeypatch.setattr(Check, "run", lambda self, *a, **k: calls.append(1) or real(self, *a, **k))
    assert main(["check", "somov.kinematics", "--quiet", "--no-cache"]) == 0
    monkeypatch.setenv("LKVERIFY_CACHE", "off")
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    assert len(calls) == 2


def test_other_values_and_a_budget_are_not_served_from_the_cache(on, capsys):
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    assert main(["check", "somov.kinematics", "--quiet", "--budget", "100"]) == 0    # a capped run: not stored
    assert on.stats()["entries"] == 1
    capsys.readouterr()


def test_a_tampered_entry_is_recomputed_by_the_command_line(on, capsys):
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    first = capsys.readouterr().out
    path = next((on.directory / f"v{cache_mod.CACHE_FORMAT}").rglob("*.json"))
    entry = json.loads(path.read_text())
    entry["payload"] = entry["payload"].replace("every check holds", "every check holds (edited)")
    path.write_text(json.dumps(entry))
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    assert capsys.readouterr().out == first


def test_cache_info_and_clear(on, capsys):
    assert main(["check", "somov.kinematics", "--quiet"]) == 0
    capsys.readouterr()
    assert main(["cache", "info", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["entries"] == 1 and info["directory"] == str(on.directory)
    assert main(["cache", "clear"]) == 0
    assert "1 entries deleted" in capsys.readouterr().out
    assert main(["cache", "nonsense"]) == 2


# -- the bare report -------------------------------------------------------------------------------
class _Item:
    def __init__(self, name):
        self.qualified_name = name
        self.calls = 0

    def run(self, values, progress=None):
        self.calls += 1
        return _report(self.qualified_name)


class _File:
    def __init__(self, items):
        self.items = {it.qualified_name: it for it in items}


def test_the_bare_report_warm_loads_no_proof_and_runs_no_item(cache, monkeypatch):
    items = [_Item("p.a"), _Item("p.b")]
    loads = []
    monkeypatch.setattr(report_job, "catalogue", lambda: loads.append(1) or [_File(items)])
    cold = report_job.catalogue_report(cache=cache)
    assert [it.calls for it in items] == [1, 1] and len(loads) == 1
    warm = report_job.catalogue_report(cache=cache)
    assert warm == cold
    assert [it.calls for it in items] == [1, 1] and len(loads) == 1                # nothing imported, nothing run
    path = cache._path(item_key(cache, "p.b"))
    path.write_text("{}")                                                          # one entry corrupt
    again = report_job.catalogue_report(cache=cache)
    assert again == cold
    assert [it.calls for it in items] == [1, 2]                                    # only that item re-run


def test_the_bare_report_without_a_cache_runs_every_item(monkeypatch):
    items = [_Item("p.a")]
    monkeypatch.setattr(report_job, "catalogue", lambda: [_File(items)])
    report_job.catalogue_report(cache=None)
    report_job.catalogue_report(cache=None)
    assert items[0].calls == 2
