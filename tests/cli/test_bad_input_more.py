"""Bad input that still crashed (issue 22, point 8): one line on stderr, exit 1 or 2, never exit 3.

* a hypothesis that fails stops the chain before any costly link (choices, bound steps,
  decay): the verdict is ``failed``, exit 1, naming the hypothesis and its margin;
* a time-varying ``--history`` is simulated (the simulator takes functions of t) or, where
  the example needs a constant history (‖χ‖_τ of an envelope), refused with one line;
* a theorem with nothing to check is refused when it is declared (exit 2 from a file);
* a theorem that is not established exits 1 under ``check``;
* siblings tried as a new user would: NaN, inf, strings, unknown names, wrong shapes, …

The commands run in process (``lkverify.cli.main``), as in ``test_bad_input.py``; no
wall-clock limit is asserted (a refused input is refused before anything costly starts).
"""

import json
import textwrap

import pytest

from lkverify import InputError
from lkverify.cli import main


BASE = '''
from lkverify import (DerivativeClaim, Equation, Functional, Hypothesis, Parameters, System, Term,
                      Theorem, Vector, t)
P = Parameters()
a = P.scalar("a", positive=True, default=2)
x = Vector("x", 1)
system = System([Equation(x, [Term(-a * x(t)[0], text="-a x")])], parameters=P)
V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")])
'''


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def one_line(err: str) -> str:
    """The single stderr line (asserts there is exactly one and no traceback)."""
    assert "Traceback" not in err and "internal error" not in err, err
    lines = err.strip("\n").split("\n")
    assert len(lines) == 1, err
    return lines[0]


# -- time-varying histories ----------------------------------------------------------------------------


def test_a_time_varying_history_is_simulated(capsys):
    code, out, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--history", "omega=[sin(t)/10,0,0]",
                         "--t-end", "5", "--json", "--quiet")
    assert code in (0, 1), err
    assert "Traceback" not in err and "internal error" not in err
    doc = json.loads(out)
    assert doc["history_overridden"] is True
    assert doc["runs"][0]["history_override"]["omega"] == ["sin(t)/10", "0", "0"]
    assert "sin(t)/10" in doc["title"]
    runs = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert runs and runs[0]["value"]["outcome"] == "success"


def test_a_time_varying_history_in_the_text_report(capsys):
    code, out, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--history", "omega=[sin(t),0,0]",
                         "--t-end", "1", "--quiet")
    assert code in (0, 1) and "Traceback" not in err and "internal error" not in err
    assert "omega = (sin(t), 0, 0)" in out and "Matrix" not in out


def test_a_time_varying_history_for_an_envelope_is_refused(capsys, no_computing):
    # ‖χ‖_τ of Fig. 7's envelope is computed from a constant history
    code, _, err = run(capsys, "simulate", "aleksandrov2023.fig7", "--history", "omega=[sin(t),0,0]")
    assert code == 2
    line = one_line(err)
    assert "--history" in line and "constant" in line and "omega=[" in line


@pytest.mark.parametrize("arg,expect", [("omega=[1/t,0,0]", "finite"), ("omega=[log(t),0,0]", "finite"),
                                        ("omega=[sin(q),0,0]", "unknown name 'q'"), ("omega=[nan,0,0]", "finite"),
                                        ("omega=[inf,0,0]", "finite"), ("omega=[a,0,0]", "unknown name 'a'"),
                                        ("omega=[[1,0],[0,1]]", "3 components"), ("omega=[1,0,0,0]", "3 components"),
                                        ("omega=[x,0,0]", "unknown name 'x'"), ("omega=abc", "")])
def test_bad_histories_are_one_line(capsys, no_computing, arg, expect):
    code, _, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--history", arg)
    assert code == 2, err
    line = one_line(err)
    assert expect in line and "--history" in line


# -- a theorem with nothing to check ----------------------------------------------------------------------



def test_an_empty_theorem_is_refused_when_declared():
    ns: dict = {}
    exec(textwrap.dedent(BASE), ns)
    with pytest.raises(InputError, match="expected at least one hypothesis") as info:
        ns["Theorem"]("empty", system=ns["system"], functional=ns["V"])
    assert "got none" in str(info.value) and "claims=" in str(info.value)
    with pytest.raises(InputError, match="expected at least one hypothesis"):
        ns["Theorem"]("empty", system=ns["system"])


def test_an_empty_theorem_in_a_proof_file_is_exit_2(capsys, tmp_path):
    path = tmp_path / "empty.py"
    path.write_text(textwrap.dedent(BASE + 'th = Theorem("th", system=system, functional=V)\n'))
    code, _, err = run(capsys, "check", str(path))
    assert code == 2
    line = one_line(err)
    assert str(path) in line and "theorem th" in line and "expected at least one hypothesis" in line


# -- not established: exit 1 -------------------------------------------------------------------------------


@pytest.mark.parametrize("body", [
    # a claim only: V ≥ φ and V̇ ≤ −ψ are missing
    'th = Theorem("th", system=system, functional=V, claims=[DerivativeClaim("Vdot", V, system, '
    '[Term(-a * x(t)[0] ** 2)])])',
    # a hypothesis only: V̇ along the system is missing
    'th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("a > 0", a)])',
])
def test_a_theorem_not_established_exits_1(capsys, tmp_path, body):
    path = tmp_path / "partial.py"
    path.write_text(textwrap.dedent(BASE + body + "\n"))
    code, out, err = run(capsys, "check", str(path), "--json")
    doc = json.loads(out)
    assert all(r["status"] in ("exact", "certified") for r in doc["results"])   # every result holds …
    assert doc["verdict"].startswith("not established")                        # … but the chain does not close
    assert code == 1, doc["verdict"]


def test_a_failed_hypothesis_exits_1(capsys, tmp_path):
    path = tmp_path / "hyp.py"
    path.write_text(textwrap.dedent(BASE + 'th = Theorem("th", system=system, functional=V, '
                                           'hypotheses=[Hypothesis("a > 3", a - 3)])\n'))
    code, out, _ = run(capsys, "check", str(path), "--json")
    assert code == 1 and json.loads(out)["verdict"].startswith("failed: hypotheses")


def test_an_undecided_link_exits_1(capsys):
    # a budget spent before the identities: undecided, exit 1
    code, out, err = run(capsys, "check", "aleksandrov2023.theorem3", "--budget", "0.001", "--json", "--quiet")
    assert code == 1 and "internal error" not in err
    assert not json.loads(out)["verdict"].startswith("established")


def test_the_readme_proof_still_exits_0_when_established(capsys, tmp_path):
    import re
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    (block,) = re.findall(r"```python\n(# my_proof.py.*?)```", readme, flags=re.S)
    path = tmp_path / "my_proof.py"
    path.write_text(block)
    code, out, _ = run(capsys, "check", str(path), "--set", "a=3", "--json")
    assert code == 0 and json.loads(out)["verdict"].startswith("established")
