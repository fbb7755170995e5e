"""Shared fixtures of the command-line tests."""

import pytest

from lkverify import cli


@pytest.fixture
def no_computing(monkeypatch):
    """Fail if a simulation or a constants job starts."""
    import lkverify.certify.constants
    import lkverify.catalogue.examples

    def boom(*a, **k):
        raise AssertionError("computing started before the bad input was refused")

    monkeypatch.setattr(lkverify.catalogue.examples.Example, "simulate", boom)
    monkeypatch.setattr(lkverify.certify.constants.ConstantsJob, "run", boom)
    monkeypatch.setattr(type(cli.find_items("aleksandrov2017.lemma1")[0].constants), "run", boom)


@pytest.fixture
def run_cli(capsys):
    """``run_cli(*argv)`` → (exit code, stdout, stderr) of ``lkverify`` in-process."""

    def run(*argv):
        code = cli.main(list(argv))
        out = capsys.readouterr()
        return code, out.out, out.err

    return run
