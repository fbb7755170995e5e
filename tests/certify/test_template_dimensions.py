"""Template constants for measured vectors of dimension 2 (the chart was three-dimensional only).

A 2-vector state q with ‖q‖ = e is charted as e·(cos θ, sin θ); before the fix the 3-D
angles were added to a 2-vector (a ShapeError).  Other dimensions are refused clearly.
"""

import sympy
import pytest

from lkverify import Equation, Parameters, System, Term, Vector, t, xi
from lkverify.certify.steps.measures import Region, norm_measure, sup_norm
from lkverify.certify.steps.rules import Context, Template
from lkverify.errors import InputError


def _ctx(dim):
    P = Parameters()
    x, y = Vector("x", dim), Vector("y", dim)
    sys_ = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
    e, w, m = norm_measure("e", x(t)), norm_measure("w", y(t)), sup_norm("m", x(xi), window=1)
    return x, y, Context(sys_, P.resolve({}), {"e": e, "w": w}, Region({m: sympy.Rational(1, 2)}))


def test_template_on_a_quartic_form_of_a_2_vector_is_its_extremum_on_the_circle():
    x, _, ctx = _ctx(2)
    x1, x2 = x(t)
    form = x1**4 + x1**3 * x2 / 2 + x2**4  # min on the circle ≈ 0.3681, max ≈ 1.0303
    low = Template("k", {"e": 4}).apply(-form, "upper", ctx)
    assert low.status.value == "certified"
    kappa = low.constants[0][1]
    assert -0.3682 < kappa < -0.36  # −min of the form on the circle, not 0 (a disk would give 0)
    up = Template("k", {"e": 4}).apply(form, "upper", ctx)
    value = up.constants[0][1]
    assert value > 1.0303 and value < 1.04


def test_template_with_two_2_vectors_bounds_a_mixed_term():
    x, y, ctx = _ctx(2)
    term = 3 * (y(t).T * x(t))[0] * (x(t).T * x(t))[0]  # 3 (yᵀx)‖x‖² ≤ 3‖y‖‖x‖³
    app = Template("c", {"w": 1, "e": 3}).apply(term, "upper", ctx)
    assert app.status.value == "certified" and 3 <= app.constants[0][1] < 3.02
    # a wrong exponent is refused (not homogeneous of the stated degree)
    assert Template("c", {"w": 1, "e": 2}).apply(term, "upper", ctx).status.value == "failed"


def test_template_refuses_other_dimensions():
    x, _, ctx = _ctx(4)
    with pytest.raises(InputError, match="dimension 1, 2 or 3"):
        Template("k", {"e": 2}).apply((x(t).T * x(t))[0], "upper", ctx)
