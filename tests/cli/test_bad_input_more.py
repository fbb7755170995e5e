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


@pytest.fixture
def no_chain(monkeypatch):
    """Fail if a bound step, the search of the choices or the decay link starts."""
    from lkverify.certify.steps.chain import TermwiseBound
    from lkverify.catalogue.items import Theorem

    def boom(*a, **k):
        raise AssertionError("a costly link started although a hypothesis failed")

    monkeypatch.setattr(TermwiseBound, "check", boom)
    monkeypatch.setattr(Theorem, "chosen", boom)


# -- a failing hypothesis stops the chain ------------------------------------------------------------


def test_a_failing_hypothesis_mu_stops_the_chain(capsys, no_chain):
    code, out, err = run(capsys, "check", "aleksandrov2023.theorem3", "--set", "mu=0.5", "--json", "--quiet")
    assert code == 1, err
    assert "internal error" not in err
    doc = json.loads(out)
    assert doc["verdict"].startswith("failed: hypotheses")
    assert "mu > 1" in doc["verdict"] and "margin -1/2" in doc["verdict"]
    by = {r["name"]: r for r in doc["results"]}
    assert by["mu > 1"]["status"] == "failed"
    steps = [r for r in doc["results"] if r["kind"] == "bound"]
    assert steps and all(r["status"] == "undecided" and "hypothes" in r["detail"] for r in steps)
    assert not any(r["kind"] == "region" for r in doc["results"])
    (hyp,) = [link for link in doc["chain"] if link["link"] == "hypotheses"]
    assert hyp["status"] == "failed" and "mu > 1" in hyp["detail"]


def test_a_failing_hypothesis_text_report(capsys, no_chain):
    code, out, err = run(capsys, "check", "aleksandrov2023.theorem3", "--set", "mu=0.5", "--quiet")
    assert code == 1 and "Traceback" not in err and "internal error" not in err
    assert "verdict: failed: hypotheses" in out and "mu > 1" in out


@pytest.mark.parametrize("h", ["-1", "0", "1", "-(1+t)**(-1)"])
def test_h_outside_5_fails_the_hypothesis_first(capsys, no_chain, h):
    # h ≤ 0 (or h ↛ 0) is outside (5): decided first (failed, exit 1), as --set "h=(1+t)**(-6/5)" fails (11)
    code, out, err = run(capsys, "check", "aleksandrov2017.theorem1", "--set", f"h={h}", "--json", "--quiet")
    assert code == 1, err
    assert "internal error" not in err
    doc = json.loads(out)
    assert doc["verdict"].startswith("failed: hypotheses") and "(5)" in doc["verdict"]
    assert all(r["status"] == "undecided" for r in doc["results"] if r["kind"] == "bound")


def test_failing_hypothesis_in_a_users_file_stops_the_bound_claims(capsys, tmp_path):
    path = tmp_path / "mine.py"
    path.write_text(BASE + textwrap.dedent('''
        from lkverify import BoundClaim
        step = BoundClaim("V̇ ≤ −ax²", V, system, lhs="Vdot", rhs=-a * x(t)[0] ** 2, role="decrease")
        th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("a > 1", a - 1)], bounds=[step])
    '''))
    code, out, err = run(capsys, "check", str(path), "--set", "a=1/2", "--json")
    assert code == 1, err
    doc = json.loads(out)
    assert doc["verdict"].startswith("failed: hypotheses") and "a > 1" in doc["verdict"]
    (step,) = [r for r in doc["results"] if r["kind"] == "bound"]
    assert step["status"] == "undecided" and "a > 1" in step["detail"]


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


# -- siblings: a parameter inside the hypotheses that the decay argument does not cover --------------------------


def test_a_non_polynomial_decay_model_is_unsupported_not_a_crash():
    import sympy

    from lkverify import UnsupportedInput
    from lkverify.certify.decay import DecayModel, certify_model, estimate_decay

    w, e = sympy.symbols("w e", nonnegative=True)
    half, Q = sympy.Rational(1, 2), w ** 2 + e ** 2
    m = DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -w ** 3 - e ** sympy.Rational(5, 2),
                   sympy.Rational(3, 2), (w, e), {}, {"d1": e, "d2": w})
    with pytest.raises(UnsupportedInput, match="must be polynomials in w, e"):  # was PolynomialError (exit 3)
        estimate_decay(m)
    with pytest.raises(UnsupportedInput, match="non-integer exponent"):
        certify_model(m)


@pytest.mark.slow  # the whole chain of Theorem 3 at μ = 3/2 (about 50 s on a loaded machine)
def test_theorem3_at_a_fractional_order_is_undecided_not_exit_3(capsys):
    code, out, err = run(capsys, "check", "aleksandrov2023.theorem3", "--set", "mu=3/2", "--json", "--quiet")
    assert code == 1 and "internal error" not in err, err
    doc = json.loads(out)
    assert doc["verdict"].startswith("undecided: decay") and "polynomials" in doc["verdict"]


@pytest.mark.parametrize("value,entry", [("[[nan,0],[0,-0.9]]", "nan"), ("[[inf,0],[0,-0.9]]", "inf"),
                                         ("diag(1,nan)", "nan")])
def test_a_non_finite_matrix_entry_is_named(capsys, value, entry):
    code, _, err = run(capsys, "linear", "--set", f"A={value}")
    assert code == 2
    line = one_line(err)
    assert f"got {entry} in '{value}'" in line and "finite" in line and "A=2" not in line
