"""The LMI hierarchy: margins against the anchors, exact re-verification, mutated certificates never pass."""

import dataclasses

import pytest
import sympy

from lkverify.errors import InputError, UnsupportedInput
from lkverify.linear import LinearDelaySystem
from lkverify.linear.hierarchy import LmiCertificate, certify_delay, check_certificate, quick_check
from lkverify.linear.margin import certified_interval
from lkverify.status import Status

CLASSIC_MARGIN = 6.172581371  # the spectral route's margin (tests/linear/test_spectrum.py)


@pytest.fixture(scope="module")
def classic():
    return LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])


@pytest.fixture(scope="module")
def top(classic):
    """The order-4 certificate at h = 6.1725 (the issue's anchor), exactly verified."""
    res = certify_delay(classic, "6.1725", order=4)
    assert res.status is Status.EXACT and res.check.status is Status.EXACT
    return res


@pytest.mark.parametrize("order, anchor", [(0, 4.4715), (1, 6.0593)])
def test_jensen_and_wirtinger_margins_match_the_anchors(classic, order, anchor):
    m = certified_interval(classic, (0, CLASSIC_MARGIN), order=order)
    assert m.status is Status.EXACT and m.upper_check.check.status is Status.EXACT
    assert abs(m.upper - anchor) < 1e-3
    assert m.upper < CLASSIC_MARGIN


def test_highest_order_certifies_6_1725(top):
    assert float(top.h) == 6.1725 and top.h == sympy.Rational(2469, 400)
    assert all(p.status is Status.EXACT for p in top.check.parts)


@pytest.mark.slow
@pytest.mark.parametrize("order, anchor", [(2, 6.1689), (3, 6.1724), (4, 6.1725)])
def test_bessel_legendre_margins(classic, order, anchor):
    m = certified_interval(classic, (0, CLASSIC_MARGIN), order=order)
    assert m.status is Status.EXACT and anchor - 1e-3 < m.upper < CLASSIC_MARGIN


def test_a_perturbed_matrix_is_refuted(classic, top):
    c = top.certificate
    for field in ("P", "S", "R"):
        M = sympy.Matrix(getattr(c, field))
        M[0, 0] = -M[0, 0]  # one entry with its sign flipped
        bad = dataclasses.replace(c, **{field: M})
        assert check_certificate(classic, top.h, bad).status is Status.FAILED
        assert not quick_check(classic, top.h, bad)
    # a perturbation at the rounding scale of the margin: −Φ loses definiteness
    M = sympy.Matrix(c.P)
    M[0, 2] += sympy.Rational(1, 10**3)
    M[2, 0] += sympy.Rational(1, 10**3)
    assert check_certificate(classic, top.h, dataclasses.replace(c, P=M)).status is Status.FAILED
    flipped = dataclasses.replace(c, R=-c.R)
    res = check_certificate(classic, top.h, flipped)
    assert res.status is Status.FAILED and res.witness is not None


def test_the_certificate_fails_above_the_margin(classic, top):
    for h in ("6.18", "6.2", "7"):
        assert check_certificate(classic, sympy.Rational(h), top.certificate).status is Status.FAILED
        assert not certify_delay(classic, h, order=4).holds   # beyond the exact margin 6.17258: never certified


def test_the_certificate_fails_for_a_changed_system(classic, top):
    changed = LinearDelaySystem([[-2, 0], [0, "-0.8"]], Ad=[[-1, 0], [-1, -1]])  # a dropped 0.1 of damping
    assert check_certificate(changed, top.h, top.certificate).status is Status.FAILED


def test_a_scaled_certificate_still_passes(classic, top):
    c = top.certificate
    scaled = LmiCertificate(4, 7 * c.P, 7 * c.S, 7 * c.R)  # the conditions are homogeneous
    assert check_certificate(classic, top.h, scaled).status is Status.EXACT


def test_same_system_written_differently(classic):
    other = LinearDelaySystem(sympy.Matrix([[-2, 0], [0, sympy.Rational(-9, 10)]]),
                              Ad=sympy.Matrix([[-1, 0], [-1, -1]]), kernel=[sympy.zeros(2, 2)])
    assert certify_delay(other, 6, order=1).status is Status.EXACT


@pytest.mark.slow
def test_gu_interval_certified_at_both_ends():
    gu = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
    m = certified_interval(gu, (0.1001683, 1.7178582), order=2)
    assert m.status is Status.EXACT
    assert 0.1001683 < m.lower < 0.1003 and 1.70 < m.upper < 1.7178582
    assert m.lower_check.check.status is Status.EXACT


def test_distributed_delay_inside_and_outside():
    d = LinearDelaySystem([["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]])
    assert certify_delay(d, 1, order=1).status is Status.EXACT
    assert not certify_delay(d, "0.19", order=2).holds   # unstable there: λ = 0 crosses at h = 0.2


@pytest.mark.slow
def test_distributed_interval_certified_at_both_ends():
    d = LinearDelaySystem([["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]])
    m = certified_interval(d, (0.2, 2.0412847), order=2)
    assert m.status is Status.EXACT
    assert 0.2 < m.lower < 0.2001 and 2.03 < m.upper < 2.0412847
    assert not certify_delay(d, "0.19", order=3).holds   # unstable there: λ = 0 crosses at h = 0.2
    assert not certify_delay(d, "2.05", order=3).holds


def test_bad_input():
    sys = LinearDelaySystem([[-1]], Ad=[[0]])
    with pytest.raises(InputError):
        certify_delay(sys, -1, order=0)
    with pytest.raises(InputError):
        certify_delay(sys, 1, order=-1)
    with pytest.raises(UnsupportedInput):
        certify_delay(LinearDelaySystem([[-1]], kernel=[[[0]], [[1]]]), 1, order=1)
    with pytest.raises(InputError):
        certified_interval(sys, (2, 1), order=0)
