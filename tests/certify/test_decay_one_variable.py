"""A decay model in one measure (a scalar Lyapunov chain): estimated and certified, no crash."""

import sympy

from lkverify.certify.decay import DecayModel, certify_model, estimate_decay
from lkverify.status import Status


def _model(vdot):
    w = sympy.Symbol("w", positive=True)
    return DecayModel("one", (w,), {w: 1}, w**2, w**2, vdot(w), sympy.Rational(3, 2), (w,), {}, {"d1": w})


def test_one_variable_model_is_estimated_and_certified():
    model = _model(lambda w: -w**3)
    est = estimate_decay(model)
    assert est is not None and est["d1"] > 0 and est["c_tilde"] > 0
    cert = certify_model(model, budget=20)
    assert cert is not None and cert.status is Status.CERTIFIED


def test_one_variable_model_with_growth_is_not_certified():
    model = _model(lambda w: w**3)  # V̇ > 0: no decay
    assert estimate_decay(model) is None
    assert certify_model(model, budget=5) is None
