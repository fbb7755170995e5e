"""Forgetting (bounded-gain least squares): every side condition violated alone; sup_bound."""

import math

import numpy as np
import pytest
import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t
from lkverify.certify.steps import Forgetting
from lkverify.certify.steps.signals import Facts, sup_bound
from lkverify.errors import InputError
from lkverify.status import Status

lam = sympy.Symbol("lambda", nonnegative=True)
Xs, Fs = Vector("X", 3), Vector("f", 2)
x11, x12, x22 = Xs(t)
f1, f2 = Fs(t)
X = sympy.Matrix([[x11, x12], [x12, x22]])
F = sympy.Matrix([[f1], [f2]])


def _system(rate, extra=0):
    R = rate
    return System([Equation(Xs, [Term(sympy.Matrix([R[0, 0] + extra, R[0, 1], R[1, 1]]))]),
                   Equation(Fs, [Term(sympy.Matrix([-f1 + sympy.sin(t), -f2]))])], parameters=Parameters())


def _decide(system, X=X, kappa=sympy.Rational(1, 2), lam0=2, k0=10, lam_=lam):
    return Forgetting("Γ⁻¹", X, F, kappa, lam_, lam0, k0).decide(Facts(system, {}, {}))


GOOD = _system(sympy.Rational(1, 2) * (F * F.T - lam * X))


def test_the_law_holds():
    res = _decide(GOOD)
    assert res.status is Status.EXACT and "⪰ I/10" in res.detail


@pytest.mark.parametrize("kw, why", [({"kappa": sympy.Rational(-1, 2)}, "κ"), ({"lam0": 0}, "λ0"), ({"k0": -1}, "k0")])
def test_nonpositive_constants_fail(kw, why):
    system = _system(kw.get("kappa", sympy.Rational(1, 2)) * (F * F.T - lam * X))
    res = _decide(system, **kw)
    assert res.status is Status.FAILED and why in res.detail


def test_a_wrong_rate_fails():
    assert _decide(_system(sympy.Rational(1, 2) * (-F * F.T - lam * X))).status is Status.FAILED   # −FFᵀ
    assert _decide(_system(sympy.Rational(1, 2) * (F * F.T - lam * X), extra=x12 ** 2 / 10 ** 9)).status \
        is Status.FAILED                                                                         # a tiny extra term
    assert _decide(GOOD, kappa=sympy.Rational(1, 3)).status is Status.FAILED                      # the wrong κ
    mixed = sympy.Rational(1, 2) * (F * F.T - lam * X)
    mixed[1, 1] = sympy.Rational(1, 2) * (f2 ** 2 - 2 * lam * x22)                               # λ not one scalar
    assert _decide(_system(mixed)).status is Status.FAILED


def test_a_time_varying_rate_written_differently_holds():
    rate = (F * F.T) / 2 - (lam / 2) * X                                                          # the same law
    assert _decide(_system(sympy.expand(rate))).status is Status.EXACT


def test_structure_of_the_link():
    assert _decide(GOOD, X=sympy.Matrix([[x11, x12], [x22, x22]])).status is Status.FAILED        # not symmetric
    state = sympy.Symbol("X_x", real=True)
    res = _decide(GOOD, lam_=state)
    assert res.status is Status.FAILED and "is a state" in res.detail                             # λ is a state
    assert _decide(GOOD, k0=sympy.Symbol("k")).status is Status.UNDECIDED                         # not a number
    with pytest.raises(InputError, match="norm"):
        Forgetting("Γ⁻¹", X, F, 1, lam, 1, 1, norm="max")
    with pytest.raises(InputError, match="symbol"):
        Forgetting("Γ⁻¹", X, F, 1, lam * 2, 1, 1)


def test_sup_bound_is_sound_and_refuses_the_unbounded():
    exprs = [sympy.sin(t) / 2 - sympy.cos(3 * t / 4) / 3, sympy.sin(t) * sympy.cos(t) + sympy.exp(-t / 2) / 5,
             (sympy.sin(t / 3) - 1) ** 2, -sympy.Rational(7, 3) * sympy.cos(t) ** 3]
    ts = np.linspace(0, 200, 20001)
    for e in exprs:
        b = sup_bound(e)
        f = sympy.lambdify(t, e, "numpy")
        assert b is not None and float(b) >= np.max(np.abs(f(ts))) - 1e-12
    assert sup_bound(sympy.sin(t) + sympy.cos(t)) == 2               # sound, not tight (√2)
    for e in (t, t * sympy.sin(t), sympy.exp(t / 10), sympy.sin(t) / (2 + sympy.cos(t)), sympy.sqrt(2 + sympy.sin(t))):
        assert sup_bound(e) is None
    assert sup_bound(sympy.exp(-t + 1)) == sympy.E and sup_bound(sympy.Rational(-3, 2)) == sympy.Rational(3, 2)
    assert math.isclose(float(sup_bound(sympy.pi * sympy.sin(t))), math.pi)
