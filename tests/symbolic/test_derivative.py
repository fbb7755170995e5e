"""The derivative of each kind of term against a hand-derived closed form."""

import sympy
import pytest

from lkverify import (Equation, Functional, Parameters, System, Term, UnitVector, Vector, cross, derivative_along,
                      memory_integral, norm_squared, tail_integral, t, window_integral, xi, zeta)
from lkverify.symbolic.canonical import Canonicalizer


def same(a, b, system=None):
    """Exact equality through the normal form (independent of SymPy's term ordering)."""
    c = Canonicalizer(system.constraint_polynomials if system else None)
    nf = c.normal_forms([a, b])
    return nf.polys[0] == nf.polys[1]


@pytest.fixture
def scalar_delay():
    P = Parameters()
    k = P.scalar("k", positive=True)
    tau = P.delay("tau")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-k * x(t - tau)[0], text="-k x(t-τ)")])], parameters=P)
    return P, k, tau, x, sys


def test_point_term(scalar_delay):
    P, k, tau, x, sys = scalar_delay
    d = derivative_along(Functional([Term(x(t)[0] ** 4)]), sys)
    assert same(d.expr, -4 * k * x(t)[0] ** 3 * x(t - tau)[0])
    assert [b.kind for b in d.blocks] == ["dynamics"]


def test_window_integral_with_weight(scalar_delay):
    P, k, tau, x, sys = scalar_delay
    lam, mu = sympy.symbols("lam mu", positive=True)
    V = Functional([Term(window_integral(x(xi)[0] ** 2, tau, weight=lam * (xi + tau - t) + mu))])
    d = derivative_along(V, sys)
    # d/dt ∫_{t−τ}^t (λ(ξ+τ−t)+μ) x² dξ = (λτ+μ)x(t)² − μx(t−τ)² − λ∫x²
    expected = (lam * tau + mu) * x(t)[0] ** 2 - mu * x(t - tau)[0] ** 2 - lam * window_integral(x(xi)[0] ** 2, tau)
    assert same(d.expr, expected)
    assert {b.kind for b in d.blocks} == {"upper limit", "lower limit", "under the integral"}


def test_delayed_point_value(scalar_delay):
    P, k, tau, x, sys = scalar_delay
    d = derivative_along(Functional([Term(x(t - tau)[0] ** 2)]), sys)
    # d/dt x(t−τ)² = 2x(t−τ)·(−k x(t−2τ))
    assert same(d.expr, -2 * k * x(t - tau)[0] * x(t - 2 * tau)[0])
    assert d.blocks[0].kind == "delayed"


def test_product_of_point_value_and_integral(scalar_delay):
    P, k, tau, x, sys = scalar_delay
    I = window_integral(x(xi)[0], tau)
    d = derivative_along(Functional([Term(x(t)[0] * I)]), sys)
    expected = -k * x(t - tau)[0] * I + x(t)[0] * (x(t)[0] - x(t - tau)[0])
    assert same(d.expr, expected)


def test_memory_integral_and_kernel_tail():
    """The double-integral kernel term of paper 000's (14)."""
    P = Parameters()
    G = P.kernel("G")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    tail = tail_integral(G(zeta), t - xi)  # ∫_{t−ξ}^∞ G(ζ)dζ
    V = Functional([Term(memory_integral(tail * x(xi)[0] ** 2))])
    d = derivative_along(V, sys)
    # d/dt ∫_0^t ∫_{t−ξ}^∞ G dζ x(ξ)² dξ = ∫_0^∞ G dζ · x(t)² − ∫_0^t G(t−ξ) x(ξ)² dξ
    expected = sympy.Integral(G(zeta), (zeta, 0, sympy.oo)) * x(t)[0] ** 2 \
        - memory_integral(G(t - xi) * x(xi)[0] ** 2)
    assert same(d.expr, expected)


def test_time_varying_coefficient():
    P = Parameters()
    h = P.coefficient("h")
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-h(t) * x(t)[0])])], parameters=P)
    d = derivative_along(Functional([Term(h(t) * x(t)[0] ** 2)]), sys)
    expected = sympy.Derivative(h(t), t) * x(t)[0] ** 2 - 2 * h(t) ** 2 * x(t)[0] ** 2
    assert same(d.expr, expected)
    assert "explicit t" in {b.kind for b in d.blocks}


def test_poisson_identity_on_the_sphere():
    """d/dt ½‖s−r‖² = ωᵀ(s×r), the identity the digest says to check."""
    P = Parameters()
    r = P.unit_vector("r")
    w, s = Vector("w"), UnitVector("s")
    sys = System([Equation(w, [Term(sympy.zeros(3, 1))]),
                  Equation(s, [Term(-cross(w(t), s(t)))])], parameters=P)
    d = derivative_along(Functional([Term(norm_squared(s(t) - r) / 2)]), sys)
    assert same(d.expr, (w(t).T * cross(s(t), r))[0], sys)
    assert not same(d.expr, -(w(t).T * cross(s(t), r))[0], sys)


def test_grouped_split(scalar_delay):
    P, k, tau, x, sys = scalar_delay
    V = Functional([Term(x(t)[0] ** 2 / 2), Term(window_integral(x(xi)[0] ** 2, tau, weight=xi - t + tau))])
    g = derivative_along(V, sys).grouped()
    assert g["integral"].has(sympy.Integral)
    assert not g["point"].has(sympy.Integral) and g["point"] != 0
    assert g["delayed"].has(x(t - tau)[0])
