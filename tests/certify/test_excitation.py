"""Persistent excitation certified (lkverify.certify.excitation): the exact filter response, the
certified bounds against dense samples, refutations of claims, and inputs it must refuse."""

import numpy as np
import pytest
import sympy

from lkverify import Status
from lkverify.certify.excitation import _Gram, excitation_bounds, filter_gram, refute_claim
from lkverify.errors import UnsupportedInput

t = sympy.Symbol("t", real=True)
Y = sympy.Matrix([[sympy.cos(t), sympy.sin(2 * t) / 3], [sympy.Rational(1, 2), sympy.cos(t / 2)]])


def test_filter_response_is_exact():
    # φ̇ = −2φ + Yᵀ with Y = cos t: φ = (2cos t + sin t − 2e^{−2t})/5, so φ² has the e^{−4t} coefficient 4/25
    gram = filter_gram(sympy.Matrix([[sympy.cos(t)]]), t, 2)
    assert gram[-4] == sympy.Matrix([[sympy.Rational(4, 25)]])
    phi = (2 * sympy.cos(t) + sympy.sin(t) - 2 * sympy.exp(-2 * t)) / 5
    assert sympy.simplify(sympy.diff(phi, t) + 2 * phi - sympy.cos(t)) == 0 and phi.subs(t, 0) == 0
    total = sum((C[0, 0] * sympy.exp(k * t) for k, C in gram.items()), sympy.Integer(0))
    assert sympy.simplify((total - phi ** 2).rewrite(sympy.exp)) == 0


def test_certified_bounds_enclose_dense_samples():
    pe = excitation_bounds(Y, t, lam=1, delta=3)
    assert pe.status is Status.CERTIFIED
    gram = _Gram(filter_gram(Y, t, 1), 3)
    ev = np.linalg.eigvalsh(gram.floats(np.linspace(0, 60, 20001)))
    assert pe.beta1 <= ev[:, 0].min() and ev[:, -1].max() <= pe.beta2
    assert pe.beta1 > 0.85 * ev[:, 0].min()                      # the loss asked for is 10 %


def test_claims_beyond_the_bounds_are_refuted_at_exact_points():
    gram = _Gram(filter_gram(Y, t, 1), 3)
    ts = np.linspace(0, 60, 6001)
    ev = np.linalg.eigvalsh(gram.floats(ts))
    k = int(np.argmin(ev[:, 0]))
    t0 = sympy.Rational(ts[k]).limit_denominator(1000)
    assert refute_claim(gram, t0, sympy.Rational(ev[k, 0]).limit_denominator(1000) + sympy.Rational(1, 100))
    assert refute_claim(gram, t0, sympy.Rational(ev[k, 0]).limit_denominator(1000) / 2) is None
    j = int(np.argmax(ev[:, -1]))
    t1 = sympy.Rational(ts[j]).limit_denominator(1000)
    assert refute_claim(gram, t1, sympy.Rational(ev[j, -1]).limit_denominator(1000) - sympy.Rational(1, 100),
                        lower=False)


def test_no_excitation_is_never_certified():
    same = sympy.Matrix([sympy.cos(t), sympy.cos(t)])          # φᵀφ ∝ [[1, 1], [1, 1]]: singular, no zero row
    assert excitation_bounds(same, t, lam=1, delta=2).status is not Status.CERTIFIED
    zero_row = sympy.Matrix([sympy.cos(t), 0])
    res = excitation_bounds(zero_row, t, lam=1, delta=2)
    assert res.status is Status.FAILED and "exactly 0" in res.detail
    tiny = sympy.Matrix([sympy.cos(t), sympy.cos(t) + sympy.sin(t) / 10 ** 6])   # nearly singular: β1 ~ 1e-13
    res = excitation_bounds(tiny, t, lam=1, delta=2)
    assert res.status is not Status.FAILED                     # it is excited, barely: never refuted
    if res.status is Status.CERTIFIED:                         # then below every sampled window
        ev = np.linalg.eigvalsh(_Gram(filter_gram(tiny, t, 1), 2).floats(np.linspace(0, 40, 8001)))
        assert res.beta1 > 0
        assert res.beta1 <= ev[:, 0].min()


@pytest.mark.parametrize("bad", [sympy.Matrix([[t * sympy.sin(t)]]), sympy.Matrix([[sympy.sin(sympy.sqrt(2) * t)]]),
                                 sympy.Matrix([[sympy.sqrt(2) * sympy.sin(t)]]), sympy.Matrix([[sympy.exp(t)]])])
def test_regressors_it_cannot_treat_are_refused(bad):
    with pytest.raises(UnsupportedInput):
        excitation_bounds(bad, t, lam=1, delta=2)


def test_lambda_must_be_positive():
    with pytest.raises(UnsupportedInput, match="λ > 0"):
        filter_gram(Y, t, 0)
