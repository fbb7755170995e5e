"""One certificate for every delay of an interval: concavity (exact) or arb pieces (certified)."""

import pytest

from lkverify.linear import LinearDelaySystem
from lkverify.linear.interval import certify_cover, certify_interval
from lkverify.status import Status


@pytest.fixture(scope="module")
def classic():
    return LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])


def test_classic_interval_exact_by_concavity(classic):
    res = certify_interval(classic, ("0.01", "6"), order=1)
    assert res.status is Status.EXACT and "concave" in res.detail


def test_an_interval_reaching_past_the_margin_is_never_certified(classic):
    assert not certify_interval(classic, ("1", "6.2"), order=4).holds     # the exact margin is 6.17258
    assert not certify_interval(classic, ("1", "6.1"), order=0).holds     # beyond Jensen's reach (4.4719)


def test_distributed_interval_certified_in_pieces():
    d = LinearDelaySystem([["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]])
    res = certify_interval(d, ("0.5", "1.5"), order=2)
    assert res.status is Status.CERTIFIED and res.pieces >= 1
    assert not certify_interval(d, ("0.15", "1"), order=2).holds          # unstable below 0.2


@pytest.mark.slow
def test_acceptance_intervals():
    classic = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
    assert certify_interval(classic, ("0.01", "6.17"), order=4).status is Status.EXACT
    gu = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
    parts = certify_cover(gu, ("0.1002", "1.71"), order=3)
    assert all(p.status is Status.EXACT for p in parts) and str(parts[0].h1) == "501/5000"
    d = LinearDelaySystem([["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]])
    assert certify_interval(d, ("0.21", "2"), order=3).status is Status.CERTIFIED
