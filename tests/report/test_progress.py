"""One progress implementation: a tqdm bar on a terminal, a plain line per tenth otherwise."""

import io

from lkverify.report.progress import Progress


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_plain_lines_per_tenth_when_not_a_terminal():
    out = io.StringIO()
    p = Progress("sweep", unit="points", stream=out)
    for done in range(0, 101):
        p(done, 100, 0.0)
    lines = out.getvalue().splitlines()
    assert len(lines) == 11 and lines[-1] == "sweep: 100/100 points (100%)" and "\r" not in out.getvalue()


def test_a_bar_on_a_terminal_and_nothing_when_disabled():
    tty = _Tty()
    p = Progress("prove", unit="cells", stream=tty)
    for done in range(5):
        p.update_to(done + 1, 5)
    p.close()
    assert "5/5" in tty.getvalue() and "prove" in tty.getvalue()
    quiet = io.StringIO()
    q = Progress("sweep", stream=quiet, enabled=False)
    q.update_to(3, 4)
    q.fraction(0.5)
    assert quiet.getvalue() == ""


def test_fractions_go_through_say_when_given():
    said = []
    p = Progress("run x", say=said.append, tty=False)
    for f in (0.0, 0.05, 0.31, 0.99, 1.0, 1.5):
        p.fraction(f)
    assert said == ["  run x: 0% of the run", "  run x: 30% of the run", "  run x: 90% of the run",
                    "  run x: 100% of the run"]
