"""`lkverify simulate` output (issue 10): JSON fields, history override, wording, progress, --quiet, help."""

import json
import re
from pathlib import Path

import pytest

from lkverify import cli


@pytest.fixture
def fast_progress(monkeypatch):
    monkeypatch.setattr(cli, "PROGRESS_GRACE_SECONDS", 0.0)
    monkeypatch.setattr(cli, "PROGRESS_INTERVAL_SECONDS", 0.0)


def test_json_has_parameters_history_figures_versions(run_cli, tmp_path):
    path = tmp_path / "f.png"
    code, out, err = run_cli("simulate", "aleksandrov2023.fig6", "--set", "b=2", "--set", "mu=1", "--t-end", "20",
                             "--history", "omega=[0.1,0.1,0.1]", "--plot", str(path), "--json", "--quiet")
    assert code == 1 and err == ""  # does not converge by t = 20
    d = json.loads(out)
    assert d["parameters"]["b"] == "2" and d["parameters"]["mu"] == "1" and d["parameters"]["a"] == "0"
    run = d["runs"][0]
    assert run["history_overridden"] == ["omega"] and run["history"]["omega"] == [0.1, 0.1, 0.1]
    assert d["history_overridden"] is True
    assert "b = 2" in d["title"] and "ω = 0.1(1,1,1) (--history)" in d["title"]
    assert d["figures"] == [str(path)] and path.stat().st_size > 0
    assert set(d["versions"]) == {"lkverify", "numpy", "scipy", "sympy"}
    assert d["convention"] == "yzx" and d["distance"]["name"] == "combined"
    assert all("never" not in r["detail"] for r in d["results"])
    assert any("does not reach 1e-2 by t = 20" in r["detail"] for r in d["results"])


def test_text_report_states_the_history_override_and_distance(run_cli):
    code, out, _ = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "20", "--history", "omega=[0.1,0.1,0.1]",
                           "--distance", "per-vector", "--quiet")
    assert "overridden by --history: omega = 0.1(1,1,1)" in out
    assert "distance: per-vector" in out and "(per-vector)" in out
    assert "never" not in out


@pytest.mark.slow
def test_convention_on_the_command_line(run_cli):
    code, out, _ = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "5", "--convention", "zyx", "--json",
                           "--quiet")
    code2, out2, _ = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "5", "--json", "--quiet")
    a, b = json.loads(out), json.loads(out2)
    assert a["convention"] == "zyx" and b["convention"] == "yzx"
    assert a["runs"][0]["history"]["s"] != b["runs"][0]["history"]["s"]


def test_unknown_convention_is_one_line_of_bad_input(run_cli, no_computing, fast_progress):
    code, out, err = run_cli("simulate", "aleksandrov2023.fig6", "--convention", "nope")
    assert code == 2 and out == ""
    assert len(err.strip().split("\n")) == 1 and "--convention" in err and "yzx" in err


def test_bad_history_is_one_line_even_with_immediate_progress(run_cli, no_computing, fast_progress):
    code, _, err = run_cli("simulate", "aleksandrov2023.fig6", "--history", "omega=0.1")
    assert code == 2 and len(err.strip().split("\n")) == 1 and err.startswith("lkverify: error:")


def test_progress_on_a_non_terminal_stderr_and_quiet(run_cli, fast_progress):
    code, _, err = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "10")
    assert "run 1/1" in err and "% of the run" in err and "\r" not in err  # capsys: not a terminal
    code, _, err = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "10", "--quiet")
    assert err == ""
    code, _, err = run_cli("--quiet", "list")
    assert code == 0 and err == ""


def test_progress_waits_for_the_grace_period(run_cli, monkeypatch):
    monkeypatch.setattr(cli, "PROGRESS_GRACE_SECONDS", 1e6)
    code, _, err = run_cli("simulate", "aleksandrov2023.fig6", "--t-end", "5")
    assert err == ""


def _actions(parser):
    import argparse

    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for choice in action._choices_actions:
                yield "subcommand " + choice.dest, choice.help
            for sub in action.choices.values():
                yield from _actions(sub)
        elif not isinstance(action, argparse._HelpAction):
            yield "/".join(action.option_strings) or action.dest, action.help


def test_every_subcommand_and_option_has_help():
    helps = list(_actions(cli._build_parser()))
    assert any(name == "subcommand report" for name, _ in helps)
    missing = [name for name, text in helps if not text]
    assert not missing
    assert not any("design card" in text for _, text in helps)
    convention = next(text for name, text in helps if name == "--convention")
    assert all(c in convention for c in ("yzx", "zyx", "xyz"))


@pytest.mark.slow  # about 40 s: the whole check of Theorem 3; the variant below checks the README's proof file
def test_check_json_carries_the_versions_of_the_proof_libraries(run_cli):
    code, out, _ = run_cli("check", "aleksandrov2023.theorem3", "--set", "a=0.5", "--set", "b=1", "--json", "--quiet")
    assert code == 1
    d = json.loads(out)
    assert {"lkverify", "sympy", "python-flint", "numpy", "scipy"} <= set(d["versions"])
    assert all(isinstance(v, str) for v in d["versions"].values() if v is not None)


def test_check_json_of_a_proof_file_carries_the_versions_of_the_proof_libraries(run_cli, tmp_path):
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    (block,) = re.findall(r"```python\n(# my_proof.py.*?)```", readme, flags=re.S)
    (tmp_path / "my_proof.py").write_text(block, encoding="utf-8")
    code, out, _ = run_cli("check", str(tmp_path / "my_proof.py"), "--set", "a=3", "--json", "--quiet")
    assert code == 0
    d = json.loads(out)
    assert {"lkverify", "sympy", "python-flint", "numpy", "scipy"} <= set(d["versions"])
    assert all(isinstance(v, str) for v in d["versions"].values() if v is not None)
