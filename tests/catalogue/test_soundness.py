"""Soundness regressions (issue 7): each test failed on the code before the fix.

No false ``exact``: the chain rule at time-varying arguments, exact inputs kept
exact, floats never exact; no false ``failed``; verdicts computed from the chain;
an exact nonzero residue is refuted.
"""

import textwrap

import pytest
import sympy

from lkverify import (DerivativeClaim, Equation, Functional, Hypothesis, InputError, Parameters, Status,
                      System, Term, Theorem, Vector, derivative_along, t, window_integral, xi)
from lkverify import MatrixHypothesis
from lkverify.cli import main

# ẏ = −a y, states and parameters shared by the tests below --------------------------------------------------
P = Parameters()
a = P.scalar("a", positive=True, default=1)
c = P.scalar("c", default=sympy.Rational(1, 2))
h = P.coefficient("h", default="1/2 + sin(t)/4")
y = Vector("y", 1)


def Y(arg):
    return y(arg)[0]


SYS = System([Equation(y, [Term(-a * Y(t), text="−a y")])], parameters=P, name="ẏ = −ay")
HDOT = sympy.Derivative(h(t), t)


def _status(functional, claimed, values=None):
    th = Theorem("th", system=SYS, functional=functional,
                 claims=[DerivativeClaim("Vdot", functional, SYS, [Term(e) for e in claimed])])
    return th.run(values or {}, budget=60).results[-1].status


# 1. the chain rule at every argument θ(t) --------------------------------------------------------------------

@pytest.mark.parametrize("values", [{}, {"h": "1/2 + sin(t)/4"}, {"h": "1/(2 + t**2)"}])
def test_time_varying_delay_needs_the_inner_derivative(values):
    V = Functional([Term(Y(t - h(t)) ** 2, text="y(t−h)²")])
    right = -2 * a * (1 - HDOT) * Y(t - h(t)) ** 2
    wrong = -2 * a * Y(t - h(t)) ** 2
    assert _status(V, [right], values) is Status.EXACT
    assert _status(V, [wrong], values) is Status.FAILED


def test_time_varying_delay_with_its_closed_form_derivative():
    V = Functional([Term(Y(t - h(t)) ** 2)])
    right = -2 * a * (1 - sympy.cos(t) / 4) * Y(t - h(t)) ** 2
    assert _status(V, [right], {"h": "1/2 + sin(t)/4"}) is Status.EXACT
    assert _status(V, [-2 * a * Y(t - h(t)) ** 2], {"h": "1/2 + sin(t)/4"}) is Status.FAILED


def test_proportional_delay():
    V = Functional([Term(Y(t / 2) ** 2)])
    d = derivative_along(V, SYS)
    assert sympy.expand(d.expr - (-a * Y(t / 2) ** 2)) == 0  # 2y(t/2)·(−a y(t/2))·½
    assert _status(V, [-a * Y(t / 2) ** 2]) is Status.EXACT
    assert _status(V, [-2 * a * Y(t / 2) ** 2]) is Status.FAILED


def test_neutral_type_term():
    V = Functional([Term((Y(t) - c * Y(t - h(t))) ** 2)])
    right = 2 * (Y(t) - c * Y(t - h(t))) * (-a * Y(t) + c * a * (1 - HDOT) * Y(t - h(t)))
    wrong = 2 * (Y(t) - c * Y(t - h(t))) * (-a * Y(t) + c * a * Y(t - h(t)))
    assert _status(V, [right]) is Status.EXACT
    assert _status(V, [wrong]) is Status.FAILED


def test_window_with_time_varying_lower_limit():
    V = Functional([Term(sympy.Integral(Y(xi) ** 2, (xi, t - h(t), t)))])
    assert _status(V, [Y(t) ** 2 - (1 - HDOT) * Y(t - h(t)) ** 2]) is Status.EXACT
    assert _status(V, [Y(t) ** 2 - Y(t - h(t)) ** 2]) is Status.FAILED


def test_time_varying_delay_from_the_command_line(tmp_path, capsys):
    proof = tmp_path / "tv_proof.py"
    proof.write_text(textwrap.dedent("""
        import sympy
        from lkverify import DerivativeClaim, Equation, Functional, Parameters, System, Term, Theorem, Vector, t
        P = Parameters()
        a = P.scalar("a", positive=True, default=1)
        h = P.coefficient("h", default="1/2")
        y = Vector("y", 1)
        sys_ = System([Equation(y, [Term(-a * y(t)[0])])], parameters=P)
        V = Functional([Term(y(t - h(t))[0] ** 2)])
        right = Theorem("right", system=sys_, functional=V, claims=[DerivativeClaim(
            "Vdot", V, sys_, [Term(-2 * a * (1 - sympy.cos(t) / 4) * y(t - h(t))[0] ** 2)])])
        wrong = Theorem("wrong", system=sys_, functional=V, claims=[DerivativeClaim(
            "Vdot", V, sys_, [Term(-2 * a * y(t - h(t))[0] ** 2)])])
    """))
    # every result holds, but V ≥ φ and V̇ ≤ −ψ are missing: not established, exit 1 (issue 22)
    assert main(["check", f"{proof}::right", "--set", "h=1/2 + sin(t)/4", "--json"]) == 1
    out = capsys.readouterr().out
    assert '"status": "exact"' in out
    assert main(["check", f"{proof}::wrong", "--set", "h=1/2 + sin(t)/4", "--json"]) == 1
    assert '"status": "failed"' in capsys.readouterr().out


# 2. one exactness policy ---------------------------------------------------------------------------------------

E = sympy.Rational(45, 10**9)


@pytest.mark.parametrize("matrix, status", [
    ([[1, 1 + E], [1 + E, 1 + sympy.Rational(9, 10**8)]], Status.FAILED),          # det −8.1e-17
    ([[1, 1 - sympy.Rational(1, 10**20)], [1 - sympy.Rational(1, 10**20), 1]], Status.EXACT),
    ([[2, 1], [1, 2]], Status.EXACT),
])
def test_near_positive_definite_matrices_are_not_rounded(matrix, status):
    assert MatrixHypothesis("M", matrix).evaluate({}).status is status


def test_float_entries_are_never_snapped_nor_exact():
    r = MatrixHypothesis("M", [[float(sympy.sqrt(2)), 0], [0, 1]]).evaluate({})
    assert r.status is Status.CERTIFIED
    # float(√2) < √2: the difference keeps its sign, it is not snapped to 0
    r = Hypothesis("float(√2) − √2 > 0", sympy.Float(float(sympy.sqrt(2))) - sympy.sqrt(2)).evaluate({})
    assert r.status is Status.CERTIFIED and r.value > 0  # the binary value of float(√2) is above √2


def test_float_cancellation_in_a_margin_is_decided_exactly():
    F = sympy.Float
    m = sympy.Add(F(1e16), -1, -F(1e16), sympy.Rational(1, 2), evaluate=False)  # floats would say +1/2
    r = Hypothesis("m > 0", m).evaluate({})
    assert r.status is Status.FAILED and r.value == sympy.Rational(-1, 2)


def test_float_parameter_values_do_not_compute_in_floating_point():
    Q = Parameters()
    u, v = Q.scalar("u"), Q.scalar("v")
    hyp = Hypothesis("u - 1 - v + 1/2 > 0", u - 1 - v + sympy.Rational(1, 2))
    values = Q.resolve({"u": sympy.Float(1e16), "v": 1e16})
    r = hyp.evaluate(Q.substitution(values))
    assert r.status is Status.FAILED and r.value == sympy.Rational(-1, 2)


def test_python_floats_are_taken_at_their_binary_value():
    Q = Parameters()
    u = Q.scalar("u")
    assert Q.resolve({"u": 0.5})["u"] == sympy.Rational(1, 2)
    assert Q.resolve({"u": 0.1})["u"] == sympy.Rational(3602879701896397, 36028797018963968)
    assert Q.resolve({"u": "0.1"})["u"] == sympy.Rational(1, 10)  # text is read as the exact decimal


def test_irrational_margin_is_certified_not_exact():
    r = Hypothesis("√2 − 1 > 0", sympy.sqrt(2) - 1).evaluate({})
    assert r.status is Status.CERTIFIED


def test_margin_too_close_to_decide_is_undecided():
    m = sympy.exp(sympy.pi * sympy.sqrt(163)) - 262537412640768744  # ≈ −7.5e-13
    assert Hypothesis("m > 0", m).evaluate({}).status is Status.FAILED
    r = Hypothesis("sin² + cos² − 1 ≥ 0", sympy.sin(1) ** 2 + sympy.cos(1) ** 2 - 1, strict=False).evaluate({})
    assert r.status.holds  # decided by exact simplification, not refuted


def test_complex_margin_fails_without_a_traceback():
    r = Hypothesis("sqrt(-2) > 0", sympy.sqrt(-2)).evaluate({})
    assert r.status is Status.FAILED and "not a real number" in r.detail


def test_float_in_an_identity_claim_is_refused():
    V = Functional([Term(Y(t) ** 2 / 2)])
    with pytest.raises(InputError, match="floating-point"):
        _status(V, [-a * sympy.Float(1.0) * Y(t) ** 2 * sympy.Float(0.1) * 10])


def test_spd_parameter_near_singular_is_refused_exactly():
    Q = Parameters()
    Q.spd_matrix("F", 2)
    with pytest.raises(InputError, match="positive-definite"):
        Q.resolve({"F": "[[1, 1+45/10**9], [1+45/10**9, 1+9/10**8]]"})
    assert Q.resolve({"F": "[[1, 1-10**-20], [1-10**-20, 1]]"})["F"][0, 1] == 1 - sympy.Rational(1, 10**20)


# 3. verdicts computed, not declared ----------------------------------------------------------------------------

def _readme_theorem():
    Q = Parameters()
    a_ = Q.scalar("a", positive=True, default=2)
    b_ = Q.scalar("b", default=1)
    c_ = Q.scalar("c", positive=True, default=1)
    tau = Q.delay("tau", default=1)
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-a_ * x(t)[0]), Term(b_ * x(t - tau)[0])])], parameters=Q)
    V = Functional([Term(x(t)[0] ** 2 / 2), Term(c_ * window_integral(x(xi)[0] ** 2, tau))])
    claim = DerivativeClaim("Vdot", V, system, [Term((c_ - a_) * x(t)[0] ** 2),
                                                 Term(b_ * x(t)[0] * x(t - tau)[0]),
                                                 Term(-c_ * x(t - tau)[0] ** 2)])
    return Q, x, system, V, claim, Hypothesis("|b| < a", a_ - abs(b_))


@pytest.mark.parametrize("values", [{}, {"a": 2, "c": 5}])
def test_readme_proof_is_not_established_and_names_the_missing_links(values):
    Q, x, system, V, claim, hyp = _readme_theorem()
    report = Theorem("stable", system=system, functional=V, hypotheses=[hyp], claims=[claim]).run(values)
    assert all(r.status.is_proof for r in report.results)
    assert not report.verdict.startswith("established")
    missing = [link.name for link in report.chain if link.missing]
    assert any("V ≥" in n for n in missing) and any("V̇ ≤" in n for n in missing)
    assert "V ≥" in report.verdict and "V̇ ≤" in report.verdict
    assert report.to_json()["chain"][-1]["status"] is None


def test_theorem_without_claims_is_not_established():
    Q, x, system, V, claim, hyp = _readme_theorem()
    with pytest.raises(InputError, match="expected at least one hypothesis"):  # refused when declared (issue 22)
        Theorem("empty", system=system)


def test_claim_along_another_system_is_bad_input():
    Q, x, system, V, claim, hyp = _readme_theorem()
    other = System([Equation(x, [Term(-x(t)[0])])], parameters=Q)
    with pytest.raises(InputError, match="not along this theorem's system"):
        Theorem("mixed", system=other, functional=V, claims=[claim])


def test_repeated_names_are_bad_input():
    Q, x, system, V, claim, hyp = _readme_theorem()
    with pytest.raises(InputError, match="distinct names"):
        Theorem("twice", system=system, functional=V, hypotheses=[hyp, hyp], claims=[claim])


def test_catalogue_theorems_are_not_established():
    from lkverify.catalogue.loader import catalogue

    for pf in catalogue():
        for item in pf.items.values():
            if isinstance(item, Theorem):
                chain = item.chain([])
                assert any(link.missing for link in chain), item.qualified_name


# 4. refutation at the right scale ------------------------------------------------------------------------------

@pytest.mark.parametrize("extra", [sympy.Rational(1, 10**9) * Y(t) ** 2,
                                   sympy.Rational(1, 10**30) * Y(t) * Y(t - 1),
                                   -sympy.Rational(1, 10**12) * a * Y(t) ** 2])
def test_tiny_exact_difference_is_failed(extra):
    V = Functional([Term(Y(t) ** 2 / 2)])
    th = Theorem("tiny", system=SYS, functional=V,
                 claims=[DerivativeClaim("Vdot", V, SYS, [Term(-a * Y(t) ** 2 + extra)])])
    r = th.run({})
    res = r.results[-1]
    assert res.status is Status.FAILED
    assert "residue" in res.detail


def test_true_claim_written_differently_is_exact():
    V = Functional([Term(Y(t) ** 2 / 2)])
    assert _status(V, [-a * Y(t) * Y(t) / 2, -a * Y(t) ** 2 / 2]) is Status.EXACT


# 5. no false refutations ---------------------------------------------------------------------------------------

@pytest.mark.slow  # 7–20 s each (the whole chain); the default run refuses a kernel violating Assumption 2 (test_aleksandrov2026_theorem2_chain.py)
@pytest.mark.parametrize("beta", ["0", "-1/2 + 10**-9", "1"])
def test_aleksandrov2026_theorem2_assumption2_holds(beta):
    from lkverify.catalogue.loader import find_items

    (item,) = find_items("aleksandrov2026.theorem2")
    report = item.run({"beta": beta})
    hyps = [r.status for r in report.results if r.kind == "hypothesis"]
    assert hyps == [Status.EXACT] * 3  # Assumption 2, Remark 3, Assumption 1


def test_aleksandrov2026_theorem2_fails_for_negative_xi():
    from lkverify.catalogue.loader import find_items

    (item,) = find_items("aleksandrov2026.theorem2")
    report = item.run({"beta": "-1/2 - 10**-9"})
    # Assumption 2 and Remark 3 fail; Assumption 1 (on the kernel alone) still holds
    hyps = [r.status for r in report.results if r.kind == "hypothesis"]
    assert hyps == [Status.FAILED, Status.FAILED, Status.EXACT]


def test_readme_negative_vdot_form_near_singular_is_failed():
    # −V̇ of the README proof is the form [[a − c, −b/2], [−b/2, c]] in (x(t), x(t−τ)); at a = b = 2.00000009,
    # c = 1.00000009 its determinant is −2.025e-15 < 0: rounding the entries would call it positive definite
    Q, x, system, V, claim, hyp = _readme_theorem()
    a_, b_, c_ = (Q[n].obj for n in ("a", "b", "c"))
    form = MatrixHypothesis("−V̇ ≻ 0", [[a_ - c_, -b_ / 2], [-b_ / 2, c_]])
    th = Theorem("form", system=system, functional=V, hypotheses=[form], claims=[claim])
    bad = th.run({"a": "2.00000009", "b": "2.00000009", "c": "1.00000009"}).results[0]
    assert bad.status is Status.FAILED
    good = th.run({"a": "2.0000001", "b": "2.00000009", "c": "1.00000009"}).results[0]
    assert good.status is Status.EXACT


def test_integral_orientation_and_tiny_integral_terms():
    # ∫_t^{t−τ} = −∫_{t−τ}^t is one normal form; a residue 10⁻⁹·∫… is refuted (floating point with quadrature)
    Q, x, system, V, claim, hyp = _readme_theorem()
    tau = Q["tau"].obj
    X = x(t)[0]
    base = [term.expr for term in claim.terms]
    flipped = sympy.Integral(x(xi)[0] ** 2, (xi, t, t - tau)) + sympy.Integral(x(xi)[0] ** 2, (xi, t - tau, t))
    tiny = sympy.Rational(1, 10**9) * sympy.Integral(x(xi)[0] ** 2, (xi, t, t - tau))
    for extra, status in ((flipped, Status.EXACT), (tiny, Status.FAILED), (tiny * X, Status.FAILED)):
        c = DerivativeClaim("Vdot", V, system, [Term(e) for e in base] + [Term(extra)])
        assert Theorem("o", system=system, functional=V, claims=[c]).run({}).results[-1].status is status


def test_witness_constant_differentiates_histories_before_fixing_t():
    import numpy as np

    from lkverify.symbolic import make_witness, witness_constant

    x = Vector("x", 1)
    w = make_witness([x], Parameters(), rng=np.random.default_rng(0))
    theta = sympy.Symbol("theta")
    h = w.histories[x.functions[0]]
    expected = sympy.diff(h(theta) ** 2, theta).subs(theta, w.t_eval)
    value = witness_constant(sympy.Derivative(x(t)[0] ** 2, t), w)
    assert abs(float(value - expected)) < 1e-15
