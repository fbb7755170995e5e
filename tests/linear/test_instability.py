"""Instability certified: a characteristic root enclosed in the open right half-plane (interval Newton in arb).

Known answers: the classic example (Gu, Kharitonov & Chen) is unstable beyond its margin 6.17258,
Gu's example outside [0.1001683, 1.7178582], x′ = x − x(t−h)/2 at every h (its real root is
1 + W₀(−e^{−h}·…); at h = 1, s = 1 + W₀(−1/(2e)) = 0.768039…).  Mutations: a box that misses the
root, a tiny exact change of the system, a root with Re s < 0, roots exactly on the imaginary axis
and a double root must never make "stable at h" failed.
"""

import json

import mpmath
import numpy as np
import pytest

from lkverify.cli import main
from lkverify.linear import LinearDelaySystem
from lkverify.linear.instability import newton_test, refute_stability
from lkverify.status import Status

CLASSIC = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
GU = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
HALF = LinearDelaySystem([[1]], Ad=[["-1/2"]])                 # x′ = x − x(t−h)/2


@pytest.mark.parametrize("system, h", [(CLASSIC, "6.18"), (CLASSIC, 7), (GU, "0.05"), (GU, 2), (HALF, 1),
                                       (HALF, "0.001"), (HALF, 20), (HALF, 0)])
def test_unstable_delays_are_refuted_with_a_root(system, h):
    res = refute_stability(system, h)
    assert res.status is Status.FAILED and res.refuted
    assert res.root.unique and res.root.in_rhp and res.root.real[0] > 0
    assert "open right half-plane" in res.detail


@pytest.mark.parametrize("system, h", [(CLASSIC, 1), (CLASSIC, "6.17"), (GU, 1), (GU, "0.11")])
def test_stable_delays_are_not_refuted(system, h):
    res = refute_stability(system, h)
    assert res.status is Status.UNDECIDED and res.root is None


def test_the_enclosure_contains_the_closed_form_root():
    s = 1 + mpmath.lambertw(-1 / (2 * mpmath.e))                   # s − 1 = −e^{−s}/2
    root = refute_stability(HALF, 1).root
    assert root.real[0] <= float(s.real) <= root.real[1] and root.real[1] - root.real[0] < 1e-9
    assert root.imag[0] <= 0 <= root.imag[1]


def test_a_box_that_misses_the_root_does_not_certify():
    root = refute_stability(CLASSIC, 7).root
    for shift in (1e-3, 1e-3j, 10 * root.radius * (1 + 1j)):
        ball = newton_test(CLASSIC, 7, root.centre + shift, root.radius)
        assert not ball.unique and not ball.in_rhp and ball.status is Status.UNDECIDED
    assert newton_test(CLASSIC, 7, root.centre, root.radius).in_rhp        # the unshifted box does


def test_a_tiny_exact_change_of_the_system_moves_the_root_out_of_the_box():
    root = refute_stability(CLASSIC, 7).root
    other = LinearDelaySystem([[-2, 0], [0, "-0.9000001"]], Ad=[[-1, 0], [-1, -1]])
    assert not newton_test(other, 7, root.centre, root.radius).unique
    assert not newton_test(CLASSIC, "7.000001", root.centre, root.radius).unique   # another delay


def test_a_root_with_negative_real_part_is_enclosed_but_not_in_the_rhp():
    from lkverify.linear import rightmost_roots
    lam = complex(rightmost_roots(CLASSIC, 1.0).roots[0])
    assert lam.real < 0
    ball = newton_test(CLASSIC, 1, lam, 1e-9)
    assert ball.unique and not ball.in_rhp


def test_roots_on_the_imaginary_axis_are_not_in_the_open_rhp():
    rotation = LinearDelaySystem([[0, 1], [-1, 0]])              # s = ±i
    zero = LinearDelaySystem([[-1]], Ad=[[1]])                   # s + 1 − e^{−sh} = 0 at s = 0, every h
    for system in (rotation, zero):
        res = refute_stability(system, 1)
        assert res.status is Status.UNDECIDED
    ball = newton_test(zero, 1, 0.0, 1e-6)
    assert ball.unique and not ball.in_rhp                        # enclosed, on the axis: not in the open RHP
    assert not newton_test(rotation, 1, 1j, 1e-6).in_rhp


def test_a_double_root_is_never_certified_unique():
    double = LinearDelaySystem([[1, 0], [0, 1]])                  # (s − 1)² : f′ vanishes at the root
    assert not newton_test(double, 0, 1.0, 1e-6).unique
    assert refute_stability(double, 0).status is Status.UNDECIDED


def test_the_same_system_written_with_floats_is_refuted_too():
    floats = LinearDelaySystem(np.array([[-2.0, 0.0], [0.0, -0.9]]), Ad=np.array([[-1.0, 0.0], [-1.0, -1.0]]))
    res = refute_stability(floats, 7.0)
    assert res.refuted and "binary value" in res.detail


def test_a_distributed_delay_root_is_certified():
    # ẋ = x − ∫_{t−h}^t x/2: f(s) = s − 1 + (1 − e^{−sh})/(2s) has a real root in the RHP for every h ≥ 0
    res = refute_stability(LinearDelaySystem([[1]], kernel=[[["-1/2"]]]), 1)
    assert res.refuted and res.root.real[0] > 0


def _run(capsys, *args):
    code = main(["linear", *args, "--json", "--quiet"])
    return code, json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("args", [
    ["--set", "A=[[-2,0],[0,-0.9]]", "--set", "Ad=[[-1,0],[-1,-1]]", "--h", "7"],
    ["--set", "A=[[0,1],[-2,0.1]]", "--set", "Ad=[[0,0],[1,0]]", "--h", "0.05"],
    ["--set", "A=[[0,1],[-2,0.1]]", "--set", "Ad=[[0,0],[1,0]]", "--h", "2"],
    ["--set", "A=1", "--set", "Ad=-1/2", "--h", "1"],
])
def test_cli_unstable_delay_is_failed_with_the_root_exit_1(capsys, args):
    code, data = _run(capsys, *args, "--orders", "0", "--h-max", "8")
    row = next(r for r in data["results"] if r["name"].startswith("stable at h"))
    assert code == 1 and row["status"] == "failed"
    assert row["value"]["root"]["real"][0] > 0 and "+/-" in row["value"]["root"]["ball"]
    assert data["verdict"].startswith("unstable at h")
    assert not any(r["name"].startswith("jensen") for r in data["results"])      # no LMI for an unstable system


def test_cli_stable_delay_is_not_failed(capsys):
    code, data = _run(capsys, "--set", "A=[[-2,0],[0,-0.9]]", "--set", "Ad=[[-1,0],[-1,-1]]", "--h", "1",
                      "--orders", "0", "--h-max", "8")
    statuses = {r["name"]: r["status"] for r in data["results"]}
    assert code == 0 and statuses["stable at h = 1"] == "exact" and "failed" not in statuses.values()


def test_a_polynomial_kernel_root_matches_an_independent_quadrature():
    # ẋ = x − ∫_{t−1}^t (t − s) x(s) ds / 2: f(s) = s − 1 + ½∫_0^1 u e^{−su} du (a zero D_0 keeps its place)
    f = lambda x: x - 1 + mpmath.quad(lambda u: u * mpmath.e ** (-x * u), [0, 1]) / 2   # noqa: E731
    s = float(mpmath.findroot(f, 0.8))
    for kernel in ([[[0]], [["-1/2"]]], [[["1/3"]], [["-1/2"]]]):
        system = LinearDelaySystem([[1]], kernel=kernel)
        root = refute_stability(system, 1).root
        g = (lambda x: f(x) - (1 - mpmath.e ** (-x)) / (3 * x)) if kernel[0] != [[0]] else f
        ref = float(mpmath.findroot(g, root.centre.real))
        assert root.real[0] <= ref <= root.real[1]
    assert abs(refute_stability(LinearDelaySystem([[1]], kernel=[[[0]], [["-1/2"]]]), 1).root.centre.real - s) < 1e-12


def test_a_ball_arithmetic_that_disagrees_with_the_model_is_an_internal_error(monkeypatch):
    from lkverify.errors import InternalError
    from lkverify.linear import instability

    real = instability._balls

    def shifted(system):          # the kernel's D_1 read as D_0: another function than the model's
        A, Ad, D = real(system)
        return A, Ad, [d for d in D if any(e != 0 for row in d for e in row)]

    monkeypatch.setattr(instability, "_balls", shifted)
    with pytest.raises(InternalError, match="float characteristic matrix"):
        refute_stability(LinearDelaySystem([[1]], kernel=[[[0]], [["-1/2"]]]), 1)
