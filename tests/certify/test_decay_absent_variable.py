"""A decay model whose L does not involve a history variable (V ≥ l‖x(t)‖² only).

The outer face j = h of such a variable contains the point w = e = 0 where L − l·e² = 0, so
strict positivity there cannot be proved; L ≥ l·e² follows from the other faces.  Before the
fix the certificate stayed undecided on that face (paper 002, Corollary 1 with μ = 3).
"""

import sympy

from lkverify import Status
from lkverify.certify.decay import DecayModel, certify_model


def _model(lower):
    w, e, j = sympy.symbols("w e j", nonnegative=True)
    half = sympy.Rational(1, 2)
    upper = w**2 + e**2 + j**2
    vdot = -(w**3 + e**3 + j**3)
    return DecayModel("toy", (w, e, j), {w: half, e: half, j: half}, lower(w, e, j), upper, vdot,
                      sympy.Rational(3, 2), (w, e), {j: sympy.Integer(1)}, {"d1": e, "d2": w})


def test_a_history_variable_absent_from_L_is_certified():
    cert = certify_model(_model(lambda w, e, j: w**2 + e**2), budget=30)
    assert cert is not None and cert.status is Status.CERTIFIED, cert and cert.detail


def test_a_lower_bound_that_is_not_positive_still_fails():
    """L = w² − e² is not ≥ l·e² for any l > 0: no certificate."""
    cert = certify_model(_model(lambda w, e, j: w**2 - e**2 / 4 + e**3), budget=10)
    assert cert is None or cert.status is not Status.CERTIFIED
