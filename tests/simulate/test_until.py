"""Runs that go on until a signal is below its target (lkverify.Until)."""

import pytest

from lkverify import Equation, InputError, Parameters, Run, System, Term, Until, Vector, t
from lkverify.catalogue.examples import Example

x = Vector("x", 1)
SLOW = System([Equation(x, [Term(-x(t)[0] / 10)])], parameters=Parameters())
dist = lambda tr: abs(tr.states["x"][:, 0])                          # noqa: E731


def example(tol, t_max):
    return Example("demo", runs=[Run("slow", SLOW, {}, {"x": [1]}, until=Until(dist, tol, t_max)),
                                 Run("plain", SLOW, {}, {"x": [1]})],
                   t_end=10, series=[], distance=lambda s: abs(s["x"][:, 0]), samples=101)


def test_the_horizon_doubles_until_the_target_and_stops_at_t_max():
    out = example(1e-3, 200).simulate()
    assert float(out["slow"].t[-1]) == 80.0 and float(out["plain"].t[-1]) == 10.0
    assert abs(out["slow"].states["x"][-1, 0]) < 1e-3
    assert float(example(1e-9, 50).simulate()["slow"].t[-1]) == 50.0     # capped, target not reached


def test_a_given_horizon_is_kept():
    assert float(example(1e-3, 200).simulate(t_end=15)["slow"].t[-1]) == 15.0


@pytest.mark.parametrize("tol, t_max", [(0, 10), (-1, 10), (1e-3, 0)])
def test_bad_targets_are_refused(tol, t_max):
    with pytest.raises(InputError, match="Until"):
        Until(dist, tol, t_max)
