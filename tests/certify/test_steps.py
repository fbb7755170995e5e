"""Bound steps (first slice of issue 9): the rule of quadratic forms and window integrals, and the verdict chain.

Every mutation must be refuted or left undecided, never proved; true steps written
differently must be proved; a failed step's witness must violate the step exactly.
"""

import pytest
import sympy

from lkverify import (BoundClaim, DerivativeClaim, Equation, Functional, Hypothesis, InputError, Parameters, Status,
                      System, Term, Theorem, UnitVector, Vector, cross, t, window_integral, xi)
from lkverify.certify.steps import quadratic_upper_bound

R = sympy.Rational
P = Parameters()
a = P.scalar("a", positive=True, default=2)
b = P.scalar("b", default=1)
c = P.scalar("c", positive=True, default=1)
eps = P.scalar("eps", positive=True, default=R(1, 4))
tau = P.delay("tau", default=1)
x = Vector("x", 1)
X, Xd = x(t)[0], x(t - tau)[0]
SYSTEM = System([Equation(x, [Term(-a * X), Term(b * Xd)])], parameters=P)
V = Functional([Term(X ** 2 / 2), Term(c * window_integral(x(xi)[0] ** 2, tau))])
VDOT = DerivativeClaim("Vdot", V, SYSTEM, [Term((c - a) * X ** 2), Term(b * X * Xd), Term(-c * Xd ** 2)])


def lower(rhs=X ** 2 / 2, name="V ≥ x²/2"):
    return BoundClaim(name, V, SYSTEM, lhs="V", relation=">=", rhs=rhs, role="lower")


def decrease(rhs=-eps * (X ** 2 + Xd ** 2), name="V̇ ≤ −ε(x² + x(t−τ)²)"):
    return BoundClaim(name, V, SYSTEM, lhs="Vdot", rhs=rhs, role="decrease")


def theorem(bounds):
    return Theorem("stable", system=SYSTEM, functional=V, hypotheses=[Hypothesis("|b| < a", a - abs(b))],
                   claims=[VDOT], bounds=bounds)


def status(step, **values):
    return step.check(P.resolve({k: str(v) for k, v in values.items()})).status


# -- the verdict of the README's proof ---------------------------------------------------------------

def test_readme_proof_is_established_at_a2_b1():
    report = theorem([lower(), decrease()]).run({"a": "2", "b": "1"})
    assert report.verdict.startswith("established")
    assert all(link.status is Status.EXACT for link in report.chain)
    assert [r.kind.value for r in report.results].count("bound") == 2


@pytest.mark.parametrize("values, failing", [({"a": "1", "b": "2"}, "hypotheses"),
                                             ({"a": "2", "c": "5"}, "V̇ ≤ −ψ")])
def test_readme_proof_is_not_established_and_names_the_failing_link(values, failing):
    report = theorem([lower(), decrease()]).run(values)
    assert not report.verdict.startswith("established")
    # failed is reserved for a refuted hypothesis; a refuted step leaves the theorem not established
    assert report.verdict.startswith("failed" if failing == "hypotheses" else "not established"), report.verdict
    assert failing in report.verdict


def test_without_bound_steps_the_links_are_missing():
    report = theorem([]).run({})
    names = [link.name for link in report.chain if link.missing]
    assert any(n.startswith("V ≥") for n in names) and any(n.startswith("V̇ ≤") for n in names)
    assert any(n.startswith("V ≤ U") for n in names)


# -- mutated steps: refuted (with an exact witness) or undecided, never proved ------------------------

@pytest.mark.parametrize("step, values", [
    (lower(X ** 2), {}),                                   # a constant too large: V − x² = −x²/2 + ∫…
    (lower(X ** 2 / 2 + R(1, 10**9) * X ** 2), {}),        # a tiny exact excess
    (lower(X ** 2 / 2 + Xd ** 2), {}),                     # a dropped/added term
    (decrease(), {"eps": "3/4"}),                          # ε too large: a − c − ε < 0 at a = 2, c = 1 … (1/4)
    (decrease(-(X ** 2 + Xd ** 2)), {}),                   # a constant 4× its right value
    (decrease(), {"a": "1"}),                              # a gain outside the region of the step
    (decrease(), {"b": "-2"}),                             # |b| too large: the cross term wins
    (decrease(-eps * (X ** 2 + Xd ** 2) - R(1, 10**12) * X * Xd), {"eps": "1/2"}),
])
def test_mutated_steps_are_refuted_with_a_true_witness(step, values):
    res = step.check(P.resolve(values))
    assert res.status is Status.FAILED
    at = {sympy.sympify(k, locals={"x_1": sympy.Function("x_1")}): sympy.Rational(v)
          for k, v in res.witness["state_values"].items()}
    point = sympy.Add(*[term for term in sympy.Add.make_args(res.slack) if not term.has(sympy.Integral)])
    value = point.xreplace({k: at[kk] for k in point.atoms(sympy.core.function.AppliedUndef)
                            for kk in at if str(kk) == str(k)})
    assert value < 0 and str(value) == res.witness["slack"]


def test_negative_window_weight_is_never_proved():
    step = BoundClaim("V ≥ x²/2 + 2∫x²", V, SYSTEM, lhs="V", relation=">=",
                      rhs=X ** 2 / 2 + 2 * window_integral(x(xi)[0] ** 2, tau))
    res = step.check(P.resolve({}))
    assert res.status is Status.UNDECIDED and "coefficient" in res.detail


def test_bound_that_is_not_positive_definite_leaves_the_link_open():
    # V̇ ≤ −ε x(t−τ)²: true at a = 2, c = 1, but ψ does not bound the state at t
    weak = decrease(-eps * Xd ** 2, name="V̇ ≤ −ε x(t−τ)²")
    report = theorem([lower(), weak]).run({})
    assert report.results[-1].status is Status.EXACT
    assert not report.verdict.startswith("established")


def test_unset_parameters_and_constrained_states_are_undecided():
    Q = Parameters()
    k = Q.scalar("k", positive=True)
    y = Vector("y", 1)
    sys_ = System([Equation(y, [Term(-k * y(t)[0])])], parameters=Q)
    W = Functional([Term(y(t)[0] ** 2)])
    step = BoundClaim("V ≥ y²", W, sys_, lhs="V", relation=">=", rhs=y(t)[0] ** 2 / k, role="lower")
    assert step.check(Q.resolve({})).status is Status.UNDECIDED
    s = UnitVector("s")
    w = Vector("w")
    sys_s = System([Equation(w, [Term(-w(t))]), Equation(s, [Term(-cross(w(t), s(t)))])], parameters=Q)
    Ws = Functional([Term(w(t).dot(w(t)) / 2)])
    step_s = BoundClaim("V ≥ 0", Ws, sys_s, lhs="V", relation=">=", rhs=0)
    assert step_s.check(Q.resolve({})).status is Status.UNDECIDED


def test_misdeclared_steps_are_bad_input():
    with pytest.raises(InputError, match="role 'lower'"):
        BoundClaim("x", V, SYSTEM, lhs="Vdot", relation=">=", rhs=0, role="lower")
    with pytest.raises(InputError, match="relation"):
        BoundClaim("x", V, SYSTEM, lhs="V", relation="<", rhs=0)
    other = System([Equation(x, [Term(-X)])], parameters=P)
    with pytest.raises(InputError, match="own system"):
        Theorem("t", system=other, functional=V, bounds=[lower()])


# -- true steps written differently: proved ------------------------------------------------------------

@pytest.mark.parametrize("step", [
    lower(X * X / 2),
    lower(X ** 2 / 4 + X ** 2 / 4),
    lower(R(1, 2) * X ** 2 + 0 * Xd ** 2),
    BoundClaim("V ≥ 0", V, SYSTEM, lhs="V", relation=">=", rhs=0),
    decrease(-(eps * X ** 2) - eps * Xd ** 2),
    decrease(-R(1, 4) * (X - Xd) ** 2 - R(1, 4) * (X + Xd) ** 2 + 0 * X * Xd),
    decrease(-(X ** 2) / 2 + 0 * Xd),                          # at a = 2, b = 0 below
    decrease(eps * (X ** 2 + Xd ** 2)),
])
def test_true_steps_written_differently_are_proved(step):
    # (a weaker bound is true too: V̇ ≤ +ε(x² + x(t−τ)²) holds and is proved, it is just not a decrease)
    values = {"b": "0"} if step.rhs == -(X ** 2) / 2 else {}
    assert step.check(P.resolve(values)).status is Status.EXACT


def test_upper_bound_is_structural_and_refuses_what_it_cannot_bound():
    assert quadratic_upper_bound(V, SYSTEM, P.resolve({})).status is Status.EXACT
    quartic = Functional([Term(X ** 4)])
    assert quadratic_upper_bound(quartic, SYSTEM, P.resolve({})).status is Status.UNDECIDED
    Q = Parameters()
    h = Q.coefficient("h")  # a time-varying argument is not a fixed delay
    y = Vector("y", 1)
    sys_ = System([Equation(y, [Term(-y(t)[0])])], parameters=Q)
    moving = Functional([Term(y(t - h(t))[0] ** 2)])
    assert quadratic_upper_bound(moving, sys_, Q.resolve({})).status is Status.UNDECIDED
