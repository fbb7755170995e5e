"""The spectral reference and the crossing analysis against the issue's anchors and closed forms."""

import math

import mpmath
import numpy as np
import pytest

from lkverify.errors import InputError
from lkverify.linear import LinearDelaySystem, rightmost_roots, stability_intervals, parse_delay
from lkverify.status import Status

CLASSIC = dict(A=[[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])


def classic():
    import sympy
    return LinearDelaySystem([[-2, 0], [0, sympy.Rational(-9, 10)]], Ad=[[-1, 0], [-1, -1]])


def gu():
    import sympy
    return LinearDelaySystem([[0, 1], [-2, sympy.Rational(1, 10)]], Ad=[[0, 0], [1, 0]])


def distributed():
    import sympy
    return LinearDelaySystem([[sympy.Rational(1, 5), 0], [sympy.Rational(1, 5), sympy.Rational(1, 10)]],
                             kernel=[[[-1, 0], [-1, -1]]])


def test_classic_margin_matches_the_anchor_and_the_closed_form():
    res = stability_intervals(classic(), h_max=10)
    assert res.status is Status.ESTIMATED and res.method == "crossing"
    assert abs(res.margin - 6.17258) < 5e-6
    w = math.sqrt(0.19)  # the binding factor of the characteristic function (Gu, Kharitonov, Chen 2003)
    assert abs(res.margin - (math.pi - math.atan(w / 0.9)) / w) < 1e-9


def test_classic_spectrum_crosses_at_the_margin():
    sys = classic()
    below, above = rightmost_roots(sys, 6.1725), rightmost_roots(sys, 6.1727)
    assert below.abscissa < 0 < above.abscissa
    assert abs(abs(below.roots[0].imag) - math.sqrt(0.19)) < 1e-3
    assert below.residuals.max() < 1e-10


def test_gu_interval_does_not_start_at_zero():
    res = stability_intervals(gu(), h_max=5)
    assert len(res.intervals) == 1 and res.margin is None
    lo, hi = res.intervals[0]
    assert abs(hi - 1.71785) < 1e-5  # the anchor truncates 1.7178582
    assert abs(lo - 0.100174) < 1e-5  # the anchor; the closed form below gives 0.1001683
    # closed form: det = λ² − 0.1λ + 2 − z, |z| = 1 ⇒ ω⁴ − 3.99ω² + 3 = 0
    mpmath.mp.dps = 30
    u = (mpmath.mpf("3.99") - mpmath.sqrt(mpmath.mpf("3.99") ** 2 - 12)) / 2
    w = mpmath.sqrt(u)
    h_exact = float(-mpmath.atan2(-mpmath.mpf("0.1") * w, 2 - u) / w)
    assert abs(lo - h_exact) < 1e-10
    assert rightmost_roots(gu(), 0).abscissa > 0  # A0 + A1 is not Hurwitz


def test_distributed_interval():
    res = stability_intervals(distributed(), h_max=5)
    (lo, hi), = res.intervals
    assert abs(lo - 0.2) < 1e-12 and abs(hi - 2.04128) < 5e-6
    assert {c.h for c in res.crossings if c.omega == 0} == {0.1, 0.2}  # det(A + hD) = 0


def test_scan_reference_path_agrees_with_the_resultant():
    fast = stability_intervals(distributed(), h_max=3)
    slow = stability_intervals(distributed(), h_max=3, method="scan", nodes=24)
    assert slow.method == "scan"
    for (a, b), (c, d) in zip(fast.intervals, slow.intervals):
        assert abs(a - c) < 1e-6 and abs(b - d) < 1e-6


def test_polynomial_kernel_transform_closed_form():
    sys = LinearDelaySystem([[-1]], kernel=[[[0]], [[2]]])  # K(u) = 2u
    lam, h = 0.3 + 0.7j, 1.5
    closed = 2 * (1 - np.exp(-lam * h) * (1 + lam * h)) / lam ** 2
    assert abs(sys.kernel_transform(lam, h)[0, 0] - closed) < 1e-12
    sp = rightmost_roots(sys, h)
    assert sp.residuals[0] < 1e-10  # a root of λ + 1 − K̂(λ) = 0


def test_scalar_closed_form_root():
    # ẋ = −x(t − h): the rightmost roots solve λ = −e^{−λh}; at h = π/2 they are ±i
    sp = rightmost_roots(LinearDelaySystem([[0]], Ad=[[-1]]), math.pi / 2)
    assert abs(sp.abscissa) < 1e-10 and abs(abs(sp.roots[0].imag) - 1) < 1e-10


@pytest.mark.parametrize("kwargs, message", [
    (dict(A=[[1, 2]]), "square"),
    (dict(A=[[1, 0], [0, 1]], Ad=[[1]]), "2×2"),
    (dict(A=[[float("nan")]]), "finite"),
    (dict(A="x"), "square matrix"),
])
def test_bad_matrices_are_refused(kwargs, message):
    with pytest.raises(InputError, match=message):
        LinearDelaySystem(**kwargs)


def test_bad_delays_are_refused():
    for bad in (-1, "nan", "abc", float("inf")):
        with pytest.raises(InputError):
            parse_delay(bad)
    with pytest.raises(InputError):
        stability_intervals(classic(), h_max=-1)
