"""Certified stable and unstable delay intervals (lkverify.linear.stretches).

Known answers: the classic example is stable exactly on [0, 6.172581…) (crossing at ω = √0.19),
Gu's example on (0.1001683, 1.7178582), the distributed example on (0.2, 2.041285); x′ = x − x(t−h)/2
is unstable at every h.  Every certified stretch is cross-examined by the spectral abscissa on a
grid (an independent estimate); where no exact crossing analysis exists only points are claimed.
"""

import numpy as np
import pytest

from lkverify.linear import LinearDelaySystem, rightmost_roots, spectral_abscissa, stability_intervals
from lkverify.linear.stretches import certify_stretches, crossing_enclosures
from lkverify.status import Status

CLASSIC = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
GU = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
DISTRIBUTED = LinearDelaySystem([["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]])


def kinds(stretches):
    return [(s.kind, round(s.lo, 6), round(s.hi, 6)) for s in stretches]


def cross_examine(system, stretches, samples=9):
    """The spectral abscissa at points inside each certified stretch has the certified sign."""
    for s in stretches:
        assert s.status is Status.CERTIFIED and not s.point
        for h in np.linspace(s.lo, s.hi, samples + 2)[1:-1]:
            a = spectral_abscissa(system, h)
            assert (a < 0) if s.kind == "stable" else (a > 0), (s.kind, h, a)


def test_classic_stable_then_unstable():
    st = certify_stretches(CLASSIC, 10)
    assert kinds(st) == [("stable", 0.0, 6.172581), ("unstable", 6.172581, 10.0)]
    assert st[0].hi < st[1].lo and st[1].lo - st[0].hi < 1e-12
    cross_examine(CLASSIC, st)


def test_gu_unstable_stable_unstable():
    st = certify_stretches(GU, 4)
    assert [s.kind for s in st] == ["unstable", "stable", "unstable"]
    assert abs(st[1].lo - 0.1001683) < 1e-7 and abs(st[1].hi - 1.7178582) < 1e-7
    cross_examine(GU, st)


def test_distributed_delay_with_a_zero_root_crossing():
    st = certify_stretches(DISTRIBUTED, 3)
    stable = [s for s in st if s.kind == "stable"]
    assert len(stable) == 1 and abs(stable[0].lo - 0.2) < 1e-12 and abs(stable[0].hi - 2.041285) < 1e-6
    assert all(s.holds for s in st)
    cross_examine(DISTRIBUTED, st, samples=3)


def test_the_enclosures_contain_the_estimated_crossings_and_are_thin():
    for system, h_max in ((CLASSIC, 20), (GU, 10), (DISTRIBUTED, 8)):
        enc, how = crossing_enclosures(system, h_max)
        estimated = [c.h for c in stability_intervals(system, h_max=h_max).crossings]
        assert len(enc) == len(estimated)
        for (a, b), h in zip(enc, estimated):
            assert float(b - a) < 1e-20 and float(a) - 1e-9 < h < float(b) + 1e-9
        for a, b in enc:            # a root on the imaginary axis at the enclosed delay (estimate)
            roots = rightmost_roots(system, float((a + b) / 2)).roots
            assert min(abs(r.real) for r in roots) < 1e-8


def test_unstable_at_every_delay():
    st = certify_stretches(LinearDelaySystem([[1]], Ad=[["-1/2"]]), 5)
    assert kinds(st) == [("unstable", 0.0, 5.0)]


@pytest.mark.parametrize("system, why", [
    (LinearDelaySystem([[-1]], Ad=[[1]]), "every delay"),                      # s = 0 at every h
    (LinearDelaySystem([[1, 0], [0, -1]]), "no exact crossing analysis"),         # an ODE
])
def test_only_points_or_nothing_without_an_exact_crossing_analysis(system, why):
    enc, how = crossing_enclosures(system, 5)
    assert enc is None and why in how
    st = certify_stretches(system, 5, estimated=stability_intervals(system, h_max=5).intervals)
    assert all(s.point and s.lo == s.hi == float(s.sample) for s in st)
    assert all("single delay" in s.detail for s in st)


def test_an_irrational_entry_gives_points_only():
    system = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
    import sympy
    system = LinearDelaySystem(system.A, Ad=sympy.Matrix([[-1, 0], [-1, -sympy.sqrt(2) / 2]]))
    st = certify_stretches(system, 10, estimated=stability_intervals(system, h_max=10).intervals, orders=(1,))
    assert [(s.kind, s.sample, s.point, s.status) for s in st] == [("stable", 5, True, Status.CERTIFIED)]
    assert "single delay h = 5 only, not on an interval" in st[0].detail


def test_hayes_closed_form_pi_over_2():
    # x′ = −x(t − h): stable iff h < π/2; further root pairs cross at h = π/2 + 2πk (ω = 1, z = e^{−iωh} = −i)
    import math
    system = LinearDelaySystem([[0]], Ad=[[-1]])
    enc, _ = crossing_enclosures(system, 10)
    assert [round(float(a), 12) for a, _ in enc] == [round(math.pi / 2 + 2 * math.pi * k, 12) for k in range(2)]
    assert all(float(a) <= math.pi / 2 + 2 * math.pi * k <= float(b) + 1e-15 for k, (a, b) in enumerate(enc))
    st = certify_stretches(system, 10)
    assert [s.kind for s in st] == ["stable", "unstable", "unstable"] and all(s.holds for s in st)
    assert abs(st[0].hi - math.pi / 2) < 1e-14


def test_the_phase_is_enclosed_across_the_branch_cut():
    from flint import acb, arb

    from lkverify.linear.stretches import _phase
    z = acb(arb(-1, 1e-20), arb(0, 1e-20))        # z = −1 with a ball that straddles the negative real axis
    phi = _phase(z)
    assert phi.overlaps(arb.pi()) and phi.contains(3.141592653589793) and float(phi.rad()) < 1e-15
    assert _phase(acb(0, -1)).overlaps(-arb.pi() / 2) and abs(float(_phase(acb(0, -1)).mid()) + 1.5707963267948966) < 1e-15
