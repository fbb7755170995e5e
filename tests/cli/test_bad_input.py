"""Bad input, budgets and hangs (issue 7, deliverable 7): one line on stderr, the documented exit code.

Every case of "What was measured" that used to give a traceback, an unclear
message, an ignored option or a hang.  Budgets are asserted through the status
(``undecided``), never through wall-clock limits.
"""

import math
import sys
import textwrap
import time

import numpy as np
import pytest

from lkverify import cli
from lkverify.options import BudgetExceeded, Deadline
from lkverify.cli import main
from lkverify.simulate.solver import Outcome, solve_dde
from lkverify.errors import InputError


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def one_line(err: str) -> str:
    """The single stderr line (asserts there is exactly one and no traceback)."""
    assert "Traceback" not in err
    lines = err.strip("\n").split("\n")
    assert len(lines) == 1, err
    return lines[0]


# -- budgets ---------------------------------------------------------------------------------


@pytest.mark.parametrize("value", ["1e300", "inf", "nan", "0", "-1", "abc"])
@pytest.mark.parametrize("command", ["check", "constants", "simulate"])
def test_budget_out_of_range_is_bad_input(capsys, command, value):
    item = {"check": "aleksandrov2026.theorem1", "constants": "aleksandrov2017.lemma1",
            "simulate": "aleksandrov2023.fig6"}[command]
    code, _, err = run(capsys, command, item, "--budget", value)
    assert code == 2
    line = one_line(err)
    assert "--budget" in line and "seconds" in line


def test_deadline_with_a_huge_budget_arms_a_capped_timer():
    with Deadline(1e300).enforced():   # used to overflow setitimer
        pass
    with Deadline(math.inf).enforced():
        pass
    assert Deadline(math.inf).seconds is None
    with pytest.raises(ValueError):
        Deadline(float("nan"))


@pytest.mark.timeout(60)  # a hang guard (the inner 100 s budget outliving the outer one), not a speed assertion
def test_nested_deadlines_respect_the_outer_budget():
    with pytest.raises(BudgetExceeded):
        with Deadline(0.2).enforced():
            with Deadline(100).enforced():   # the inner budget must not outlive the outer one
                try:
                    while True:
                        time.monotonic()
                except BudgetExceeded:
                    pass
                while True:                  # caught and carried on: interrupted again
                    time.monotonic()


@pytest.mark.slow  # about 20 s on a loaded machine: a whole check
def test_check_with_the_largest_accepted_budget_runs(capsys):
    code, out, err = run(capsys, "check", "aleksandrov2026.theorem1", "--budget", "1e6")
    assert code == 1 and "Traceback" not in err      # the printed formula is refuted: exit 1
    assert "theorem1" in out


# -- output paths, before any computing --------------------------------------------------------


@pytest.mark.parametrize("command,item", [("simulate", "aleksandrov2023.fig6"),
                                          ("constants", "aleksandrov2023.theorem3"),
                                          ("constants", "aleksandrov2017.lemma1")])
def test_plot_into_a_missing_directory_is_refused_first(capsys, tmp_path, no_computing, command, item):
    code, _, err = run(capsys, command, item, "--plot", str(tmp_path / "missing" / "f.png"))
    assert code == 2
    line = one_line(err)
    assert "--plot" in line and "does not exist" in line and "mkdir" in line


@pytest.mark.parametrize("command,item", [("simulate", "aleksandrov2023.fig6"),
                                          ("constants", "aleksandrov2023.theorem3")])
def test_plot_onto_a_directory_is_refused_first(capsys, tmp_path, no_computing, command, item):
    d = tmp_path / "d.png"
    d.mkdir()
    code, _, err = run(capsys, command, item, "--plot", str(d))
    assert code == 2
    assert "directory" in one_line(err)


# -- histories and coefficients -----------------------------------------------------------------


def test_scalar_history_for_a_vector_state(capsys, no_computing):
    code, _, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--history", "omega=0.1")
    assert code == 2
    line = one_line(err)
    assert "omega" in line and "3 components" in line and "--history omega=[" in line
    assert "--set" not in line


@pytest.mark.parametrize("arg,expect", [("omega=[0.1,0.2]", "3 components"), ("omega=", "--history"),
                                        ("omega", "--history"), ("om=[1,0,0]", "unknown state"),
                                        ("omega=import os", "--history")])
def test_history_errors_talk_about_history(capsys, no_computing, arg, expect):
    code, _, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--history", arg)
    assert code == 2
    line = one_line(err)
    assert expect in line and "--set" not in line


def test_coefficient_not_finite_on_the_horizon(capsys, no_computing):
    code, _, err = run(capsys, "simulate", "aleksandrov2017.example", "--set", "h=1/t")
    assert code == 2
    line = one_line(err)
    assert line.startswith("lkverify: error: h:") and "finite" in line and "t = 0" in line


def test_coefficient_not_real_on_the_horizon(capsys, no_computing):
    code, _, err = run(capsys, "simulate", "aleksandrov2017.example", "--set", "h=sqrt(t-5)")
    assert code == 2
    assert "h:" in one_line(err)


# -- proof files ----------------------------------------------------------------------------------

BASE = '''
from lkverify import (DerivativeClaim, Equation, Functional, Hypothesis, Parameters, System, Term,
                      Theorem, Vector, t)
P = Parameters()
a = P.scalar("a", positive=True, default=2)
x = Vector("x", 1)
system = System([Equation(x, [Term(-a * x(t)[0], text="-a x")])], parameters=P)
V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2")])
'''

PROOFS = {
    "foreign_state": (BASE + '''
y = Vector("y", 1)
W = Functional([Term(y(t)[0] ** 2 / 2, text="y²/2")])
th = Theorem("th", system=system, functional=W, hypotheses=[Hypothesis("a>0", a)])
''', ["functional", "does not have", "states: x"]),
    "foreign_state_in_claim": (BASE + '''
y = Vector("y", 1)
W = Functional([Term(y(t)[0] ** 2 / 2, text="y²/2")])
th = Theorem("th", system=system, functional=V, claims=[DerivativeClaim("Vdot", W, system, [Term(-a*y(t)[0]**2)])])
''', ["claim 'Vdot'", "does not have"]),
    "hypothesis_on_a_state": (BASE + '''
th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("x>0", x(t)[0])])
''', ["hypothesis 'x>0'", "state"]),
    "hypothesis_on_t": (BASE + '''
th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("t>0", t)])
''', ["hypothesis 't>0'", "time t"]),
    "hypothesis_undeclared": (BASE + '''
import sympy
q = sympy.Symbol("q")
th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("q>0", q)])
''', ["hypothesis 'q>0'", "undeclared symbol", "q", "declare"]),
    "exits": ("import sys\nsys.exit(0)\n", ["sys.exit(0)", "while loading"]),
    "exits_3": ("raise SystemExit(3)\n", ["sys.exit(3)"]),
    "duplicate": (BASE + '''
th1 = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("a>0", a)])
th2 = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("a>1", a - 1)])
''', ["two items are named 'th'", "th1", "th2", "rename"]),
    "multiline_error": ('raise ValueError("first line\\nsecond line\\n  third line")\n', ["first line second line third line"]),
    "shape": (BASE + '''
z = Vector("z", 2)
w = x(t) + z(t)
''', ["ShapeError", "mismatch"]),
}


@pytest.mark.parametrize("case", sorted(PROOFS))
def test_bad_proof_files_are_refused_in_one_line(capsys, tmp_path, case):
    text, expected = PROOFS[case]
    path = tmp_path / f"{case}.py"
    path.write_text(textwrap.dedent(text))
    code, out, err = run(capsys, "check", str(path))
    assert code == 2, (out, err)
    line = one_line(err)
    assert str(path) in line
    for e in expected:
        assert e in line, line
    assert "set t" not in line


def test_an_alias_of_one_item_is_not_a_duplicate(capsys, tmp_path):
    path = tmp_path / "alias.py"
    path.write_text(BASE + 'th = Theorem("th", system=system, functional=V, hypotheses=[Hypothesis("a>0", a)])\n'
                    "alias = th\n")
    code, out, err = run(capsys, "check", str(path))
    assert code in (0, 1) and "Traceback" not in err and "error" not in err


def test_a_proof_file_that_hangs_at_import_hits_the_load_limit(capsys, tmp_path):
    path = tmp_path / "hangs.py"
    path.write_text("import time\nwhile True:\n    time.sleep(0.01)\n")
    code, _, err = run(capsys, "check", str(path), "--load-limit", "0.5")
    assert code == 2
    line = one_line(err)
    assert "load limit of 0.5 s" in line and "--load-limit" in line


# -- options that were ignored ---------------------------------------------------------------------


def test_goal_on_an_item_with_one_goal(capsys, no_computing):
    code, _, err = run(capsys, "constants", "aleksandrov2017.lemma1", "--goal", "region")
    assert code == 2
    line = one_line(err)
    assert "--goal" in line and "default" in line and "region" in line


def test_unknown_goal_names_the_goals(capsys, no_computing):
    code, _, err = run(capsys, "constants", "aleksandrov2023.theorem3", "--goal", "fastest")
    assert code == 2
    line = one_line(err)
    assert "paper" in line and "region" in line and "fastest" in line


def test_constants_budget_is_honoured_by_a_job_that_ignores_it(capsys):
    code, out, err = run(capsys, "constants", "aleksandrov2017.lemma1", "--budget", "0.001", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    assert doc["verdict"].startswith("undecided") and "budget" in doc["verdict"]
    assert all(r["status"] == "undecided" for r in doc["results"])


def test_constants_budget_is_honoured_by_theorem3(capsys):
    code, out, err = run(capsys, "constants", "aleksandrov2023.theorem3", "--budget", "0.5", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    assert doc["verdict"].startswith("undecided") and "0.5 s" in doc["verdict"]
    assert not any(r["status"] == "certified" for r in doc["results"] if r["kind"] in ("region", "envelope"))


# -- simulate: budgets, floors, blow-ups -------------------------------------------------------------


@pytest.mark.parametrize("args,expect", [(["--t-end", "1e12"], "1e+12 steps"),
                                         (["--set", "tau=1e-9"], "shortest delay 1e-09")])
def test_runs_below_the_step_floor_are_refused_up_front(capsys, no_computing, args, expect):
    code, _, err = run(capsys, "simulate", "aleksandrov2023.fig6", *args)
    assert code == 2
    line = one_line(err)
    assert expect in line and "step floor" in line


def test_simulate_budget_ends_undecided(capsys):
    # t_end = 10⁵ needs more than 10⁵ steps (they are at most τ = 1 long): the compiled integrator checks the
    # budget after 20,000 and 100,000 steps, far beyond 0.3 s
    code, out, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--budget", "0.3", "--t-end", "100000", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    runs = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert runs and all(r["status"] == "undecided" for r in runs)
    assert "time budget of 0.3 s" in runs[0]["detail"]
    assert all(r["status"] == "undecided" for r in doc["results"])
    assert doc["verdict"].startswith("undecided")


@pytest.mark.slow
def test_negative_damping_is_a_blow_up_with_its_time(capsys):
    code, out, err = run(capsys, "simulate", "aleksandrov2017.example", "--set", "h=-1", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    runs = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert runs and all(r["status"] == "failed" and r["value"]["outcome"] == "diverged" for r in runs)
    assert all(0 < r["value"]["t_fail"] < 100 for r in runs)
    assert "blow-up" in runs[0]["detail"]


def test_huge_gain_stops_at_the_step_floor(capsys):
    code, out, err = run(capsys, "simulate", "aleksandrov2023.fig6", "--set", "b=1e6", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    (r,) = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert (r["status"], r["value"]["outcome"]) in (("failed", "diverged"), ("undecided", "step_collapse"))
    assert r["value"]["t_fail"] is not None and "floor" in r["detail"]


def test_a_t_end_too_long_for_an_ode_stops_at_the_step_floor_undecided(capsys):
    code, out, err = run(capsys, "simulate", "aleksandrov2017.example", "--t-end", "1e9", "--json")
    assert code == 1 and "Traceback" not in err
    import json

    doc = json.loads(out)
    runs = [r for r in doc["results"] if r["name"].startswith("run ")]
    assert runs and all(r["status"] == "undecided" and r["value"]["outcome"] == "step_collapse" for r in runs)
    assert all(r["status"] == "undecided" for r in doc["results"])


def test_stiff_ode_is_a_step_collapse():
    res = solve_dde(lambda t, y, Z, past: -1e7 * (y - np.cos(t)), (0.0, 10.0), [1.0], lags=[],
                    min_mean_step=1e-5)
    assert res.outcome is Outcome.STEP_COLLAPSE and res.t_fail is not None and "stiff" in res.message


def test_dde_deadline_ends_with_budget_outcome():
    d = Deadline(0.05)
    time.sleep(0.06)
    res = solve_dde(lambda t, y, Z, past: -Z[0], (0.0, 1e4), [1.0], lags=[1.0], deadline=d)
    assert res.outcome is Outcome.BUDGET and res.t_fail is not None and res.t[-1] < 1e4


def test_dde_arithmetic_errors_are_an_outcome_not_a_traceback():
    def pole_at_half(t, y, Z, past):           # Python floats raise ZeroDivisionError at the pole
        return np.array([0.0 ** -1.0 if t >= 0.5 else 1.0])

    res = solve_dde(pole_at_half, (0.0, 1.0), [0.0], lags=[])
    assert res.outcome is Outcome.DIVERGED and res.t_fail is not None
    with pytest.raises(InputError, match="not finite at t0"):
        solve_dde(lambda t, y, Z, past: np.array([0.0 ** -1.0]), (0.0, 1.0), [0.0], lags=[])


# -- the safety net ----------------------------------------------------------------------------------


def test_an_unexpected_exception_is_one_line_with_exit_3(capsys, monkeypatch):
    def broken(*a, **k):
        raise RuntimeError("something\nunexpected")

    monkeypatch.setattr(cli, "find_items", broken)
    monkeypatch.delenv("LKVERIFY_TRACEBACK", raising=False)
    code, _, err = run(capsys, "check", "aleksandrov2026.theorem1")
    assert code == cli.EXIT_INTERNAL == 3
    line = one_line(err)
    assert "internal error" in line and "RuntimeError" in line and "something unexpected" in line


def test_usage_errors_return_2_instead_of_raising(capsys):
    code, _, err = run(capsys, "check")
    assert code == 2
    one_line(err)


def test_nothing_user_supplied_is_executed(capsys, tmp_path, no_computing):
    marker = tmp_path / "pwned"
    code, _, err = run(capsys, "simulate", "aleksandrov2017.example", "--set",
                       f"h=__import__('os').system('touch {marker}')")
    assert code == 2 and not marker.exists()
    one_line(err)


@pytest.mark.parametrize("jobs", ["0", "-2"])
def test_report_jobs_must_be_positive(capsys, jobs):
    code = main(["report", "--jobs", jobs, "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and "--jobs" in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
