"""Mutation suite (issue 7, deliverable 8): wrong claims are refuted, true ones are proved.

Kinds, each with many instances (see tests/mutations_cases.py for the hand-derived V̇):

1. time-varying arguments y(t − h(t)), y(t/2), (y − c y(t − h(t)))², ∫_{t−h(t)}^t, ∫_{t/2}^t:
   the claim without the inner derivative θ′(t) is ``failed``, the right one ``exact``;
2. one term with the opposite sign;  3. one wrong constant (×2, ×(1 + 10⁻⁹) exactly);
4. one term dropped;  5. a tiny exact extra term 10⁻⁹·m or 10⁻³⁰·m: ``failed``, not ``undecided``;
6. near-singular matrices in :class:`MatrixHypothesis`, with the sign of the determinant known;
7. floating point in hypotheses and claims: never ``exact``, never decided against the float's
   exact binary value, never snapped to a nearby "nice" number;
8. verdicts: an indefinite V̇, a theorem with no claims, a claim along another system.

True claims of the same systems written differently (reordered, expanded, split, factored,
using ‖s‖ = 1, Rational versus integer forms) are ``exact``.

Assertions are on :class:`lkverify.Status` and on whether the verdict affirms
"established" (a verdict that says "not established" does not).
"""

from __future__ import annotations

import importlib.util
import pathlib
import re
import sys

import pytest
import sympy

from lkverify import (DerivativeClaim, Equation, Functional, Hypothesis, IdentityClaim, InputError, Parameters,
                      Status, System, Term, Theorem, Vector, derivative_along, t, window_integral, xi)
from lkverify import MatrixHypothesis


def _load_cases():
    name = "lkverify_tests_mutations_cases"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, pathlib.Path(__file__).with_name("mutations_cases.py"))
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


cases = _load_cases()
R = sympy.Rational
PROOF = (Status.EXACT, Status.CERTIFIED)


def says_established(verdict: str) -> bool:
    """True when the verdict affirms that the conclusion is established ("not established" does not)."""
    v = verdict.lower()
    v = re.sub(r"\b(?:not|never|nor|cannot be|can't be|isn't|un)[\s-]*(?:yet\s+|been\s+|here\s+)*established", " ", v)
    return "established" in v


def test_says_established_reads_negations():
    assert says_established("all checked results hold; conclusion established")
    assert says_established("established: every link exact or certified (V̇, conclusion)")
    assert not says_established("all hold; the conclusion is not established here: not yet checked: x")
    assert not says_established("not established: missing: V ≥ φ (no bound step)")
    assert not says_established("failed: Vdot")


def _params(items):
    return [pytest.param(c, id=c.id, marks=[pytest.mark.slow] if c.slow else []) for c in items]


# ------------------------------------------------------------------------------------------------------
# kinds 1–5: mutated V̇ claims are refuted; true claims written differently are exact
# ------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("case", _params(cases.MUTATED))
def test_mutated_claim_is_failed(case):
    result, report = cases.run_claim(case.family, case.terms, case.values)
    assert result.status not in PROOF, f"false {result.status} for a wrong claim ({case.kind}): {result.detail}"
    assert result.status is Status.FAILED, f"a wrong claim ({case.kind}) is {result.status}: {result.detail}"
    assert not says_established(report.verdict), report.verdict


@pytest.mark.parametrize("case", _params(cases.TRUE))
def test_true_claim_is_exact(case):
    result, report = cases.run_claim(case.family, case.terms, case.values)
    assert result.status is not Status.FAILED, f"a true claim is refuted: {result.detail}"
    if case.exact_required:
        assert result.status is Status.EXACT, f"a true claim is {result.status}: {result.detail}"


def _alpha(expr):
    """Single integrals with their bound variable renamed to one name (∫x(ζ)²dζ ≡ ∫x(ξ)²dξ)."""
    bound = sympy.Symbol("_bound", real=True)

    def rename(integral):
        if len(integral.limits) != 1:
            return integral
        (var, lo, hi), = integral.limits
        return sympy.Integral(integral.function.xreplace({var: bound}), (bound, lo, hi))

    return sympy.expand(expr.replace(lambda e: isinstance(e, sympy.Integral), rename))


@pytest.mark.parametrize("name,family", cases.CLOSED_FORMS, ids=[n for n, _ in cases.CLOSED_FORMS])
def test_derivative_along_matches_hand_derived_closed_form(name, family):
    """derivative_along itself (no identity checker): the chain rule with θ′(t), the Leibniz rule."""
    derived = derivative_along(family.functional, family.system).expr
    difference = _alpha(sympy.expand((derived - sympy.Add(*family.terms)).doit()))
    if difference != 0:
        difference = sympy.simplify(difference)
    assert difference == 0, f"V̇ − hand-derived = {difference}"


def test_time_varying_delay_given_with_set_has_the_inner_derivative():
    """The issue's example: ẏ = −a y, V = y(t − h(t))², h = ½ + sin(t)/4 given as a value."""
    fam = next(f for f in cases.FAMILIES if f.name == "tv-delay-set-h")
    a = fam.system.parameters["a"].obj
    y = fam.system.states[0]
    he = R(1, 2) + sympy.sin(t) / 4
    right = [-2 * a * (1 - sympy.cos(t) / 4) * y(t - he)[0] ** 2]
    wrong = [-2 * a * y(t - he)[0] ** 2]
    assert cases.run_claim(fam, right)[0].status is Status.EXACT
    assert cases.run_claim(fam, wrong)[0].status is Status.FAILED


# ------------------------------------------------------------------------------------------------------
# kind 6: near-singular matrices, exact rational entries
# ------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("e", [R(45, 10**9), R(9, 10**9)], ids=["issue-det-2.025e-15", "det-8.1e-17"])
def test_issue_near_pd_matrix_with_negative_determinant_fails(e):
    M = [[1, 1 + e], [1 + e, 1 + 2 * e]]  # e = 45/10⁹: the issue's [[1, 1+4.5e-8], [1+4.5e-8, 1+9e-8]]
    assert sympy.Matrix(M).det() == -e ** 2
    res = MatrixHypothesis("M > 0", M).evaluate({})
    assert res.status is Status.FAILED, res.detail


def test_pd_matrix_within_1e_20_of_singular_holds_exactly():
    e = R(1, 10**20)
    M = [[1, 1 - e], [1 - e, 1]]
    assert sympy.Matrix(M).det() > 0
    res = MatrixHypothesis("M > 0", M).evaluate({})
    assert res.status is Status.EXACT, res.detail


NEAR_SINGULAR = cases.near_singular_matrices(36)


@pytest.mark.parametrize("M,pd", NEAR_SINGULAR,
                         ids=[f"{'pd' if pd else 'indefinite'}-{M.shape[0]}x{M.shape[0]}-{j}"
                              for j, (M, pd) in enumerate(NEAR_SINGULAR)])
def test_near_singular_rational_matrix(M, pd):
    n = M.shape[0]
    assert all(M[:k, :k].det() > 0 for k in range(1, n + 1)) == pd  # Sylvester's criterion, the test's premise
    res = MatrixHypothesis("M > 0", M).evaluate({})
    if pd:
        assert res.status is Status.EXACT, f"a PD rational matrix (det {M.det()}) is {res.status}: {res.detail}"
    else:
        assert res.status is Status.FAILED, f"an indefinite matrix (det {M.det()}) is {res.status}: {res.detail}"


@pytest.mark.parametrize("M", [sympy.Matrix([[1, 2], [2, 4]]), sympy.Matrix([[1, 1, 0], [1, 1, 0], [0, 0, 1]]),
                               sympy.Matrix([[0, 0], [0, 0]])], ids=["psd-2x2", "psd-3x3", "zero"])
def test_singular_psd_matrix_is_not_positive_definite(M):
    res = MatrixHypothesis("M > 0", M).evaluate({})
    assert res.status is Status.FAILED, res.detail


def _readme_form():
    P = Parameters()
    a = P.scalar("a", positive=True, default=2)
    b = P.scalar("b", default=1)
    c = P.scalar("c", positive=True, default=1)
    return P, a, b, c, [[a - c, -b / 2], [-b / 2, c]]  # −V̇ of the README proof as a form in (x, x(t−τ))


@pytest.mark.parametrize("values,pd", [
    ({"a": "2.00000009", "b": "2.00000009", "c": "1.00000009"}, False),  # det −2.025e-15 (the issue)
    ({"a": 2 + R(1, 10**20), "b": 2, "c": 1}, True),                     # det 10⁻²⁰
    ({"a": 2 - R(1, 10**20), "b": 2, "c": 1}, False),                    # det −10⁻²⁰
    ({"a": "3", "b": "2", "c": "1"}, True),
], ids=["issue-det-2e-15", "det+1e-20", "det-1e-20", "plain-pd"])
def test_readme_form_matrix_hypothesis(values, pd):
    P, a, b, c, form = _readme_form()
    sub = P.substitution(P.resolve(values))
    res = MatrixHypothesis("-Vdot form > 0", form).evaluate(sub)
    assert res.status is (Status.EXACT if pd else Status.FAILED), res.detail


def _float_verdict_allowed(res_or_exc, truth_holds: bool):
    """A value that went through floating point: refused (InputError), or never ``exact`` and never
    decided against its exact binary value."""
    if isinstance(res_or_exc, InputError):
        return
    status = res_or_exc.status
    assert status is not Status.EXACT, f"a float input came out exact: {res_or_exc.detail}"
    if truth_holds:
        assert status is not Status.FAILED, f"refuted, but it holds at the floats' binary values: {res_or_exc.detail}"
    else:
        assert status is not Status.CERTIFIED, f"certified, but false at the floats' binary values: {res_or_exc.detail}"


def _evaluate(h, sub):
    try:
        return h.evaluate(sub)
    except InputError as exc:
        return exc


def _binary_pd(M):
    """Is M ≻ 0 with every Float entry read at its exact binary value?"""
    exact = sympy.Matrix(M).applyfunc(lambda e: e.xreplace({f: R(f) for f in e.atoms(sympy.Float)}))
    return all(exact[:k, :k].det() > 0 for k in range(1, exact.shape[0] + 1))


F2 = sympy.Float(float(sympy.sqrt(2)))  # 1.4142135623730951454… > √2
F3 = sympy.Float(float(sympy.sqrt(3)))  # 1.7320508075688771931… < √3


@pytest.mark.parametrize("M", [
    [[1, sympy.Float(1 + 45e-9)], [sympy.Float(1 + 45e-9), sympy.Float(1 + 9e-8)]],
    [[F2, 1], [1, sympy.sqrt(2) / 2]],   # binary PD (det ≈ 1e-17); with √2 snapped: singular
    [[F2, 1], [1, F2 / 2]],              # binary PD; snapped: singular
    [[F3, 1], [1, 1 / sympy.sqrt(3)]],   # binary not PD
    [[sympy.Float(0.1), 0], [0, 1]],
], ids=["issue-matrix-as-floats", "float-sqrt2-vs-sqrt2/2", "float-sqrt2-twice", "float-sqrt3", "float-0.1"])
def test_matrix_with_float_entries_is_never_exact(M):
    truth = _binary_pd(M)
    _float_verdict_allowed(_evaluate(MatrixHypothesis("M > 0", M), {}), truth)


# ------------------------------------------------------------------------------------------------------
# kind 7: floating point and cancellation in hypothesis margins
# ------------------------------------------------------------------------------------------------------

a_, b_ = sympy.symbols("a b", real=True)

#: (id, margin, substitution, strict, truth: margin > 0 at exact / binary values?) — exact inputs
EXACT_MARGINS = [
    ("issue-1e16-cancellation", 10**16 - 1 - 10**16 + R(1, 2), {}, True, False),
    ("unevaluated-1e16-cancellation", sympy.Add(10**16, -1, -10**16, R(1, 2), evaluate=False), {}, True, False),
    ("symbolic-1e16-cancellation", a_ - 1 - b_ + R(1, 2), {a_: sympy.Integer(10**16), b_: sympy.Integer(10**16)},
     True, False),
    ("symbolic-1e17-plus-one", a_ + 1 - b_, {a_: sympy.Integer(10**17), b_: sympy.Integer(10**17)}, True, True),
    ("tiny-positive", R(1, 10**30), {}, True, True),
    ("tiny-negative", -R(1, 10**30), {}, True, False),
    ("sqrt2-below-decimal", sympy.sqrt(2) - R(14142135623730951, 10**16), {}, True, False),
    ("sqrt2-above-decimal", sympy.sqrt(2) - R(1414213562373095, 10**15), {}, True, True),
    ("pi-above-decimal", sympy.pi - R(314159265358979323846, 10**20), {}, True, True),
    ("decimal-above-pi", R(314159265358979323847, 10**20) - sympy.pi, {}, True, True),
    ("decimal-below-pi", R(314159265358979323846, 10**20) - sympy.pi, {}, True, False),
    ("exact-zero-strict", (a_ + 1) / a_ - 1 - 1 / a_, {a_: sympy.Integer(10**16)}, True, False),
    ("exact-zero-nonstrict", (a_ + 1) / a_ - 1 - 1 / a_, {a_: sympy.Integer(10**16)}, False, True),
    ("sqrt6-zero-strict", sympy.sqrt(2) * sympy.sqrt(3) - sympy.sqrt(6), {}, True, False),
    ("sqrt-near-cancellation", sympy.sqrt(10**20 + 1) - 10**10, {}, True, True),
    ("sqrt-near-cancellation-negative", sympy.sqrt(10**20 - 1) - 10**10, {}, True, False),
]


@pytest.mark.parametrize("name,margin,sub,strict,truth", EXACT_MARGINS, ids=[c[0] for c in EXACT_MARGINS])
def test_exact_margin(name, margin, sub, strict, truth):
    res = Hypothesis(name, margin, strict=strict).evaluate(sub)
    if truth:
        assert res.status in PROOF, f"{res.status}: {res.detail}"
    else:
        assert res.status is Status.FAILED, f"{res.status}: {res.detail}"


def _binary(x: float):
    return R(x)  # the exact binary value of a Python / SymPy float


#: (id, margin, substitution with Floats, truth at the floats' exact binary values)
FLOAT_MARGINS = [
    ("float-1e16-cancellation", a_ - 1 - b_ + R(1, 2), {a_: sympy.Float(1e16), b_: sympy.Float(1e16)}, False),
    ("float-1e17-plus-one", a_ + 1 - b_, {a_: sympy.Float(1e17), b_: sympy.Float(1e17)}, True),
    ("float-half", sympy.Float(0.5), {}, True),
    ("float-0.1-above-tenth", a_ - R(1, 10), {a_: sympy.Float(0.1)}, True),
    ("float-0.1-below-tenth", R(1, 10) - a_, {a_: sympy.Float(0.1)}, False),
    ("float-sqrt2-minus-sqrt2", F2 - sympy.sqrt(2), {}, True),
    ("sqrt3-minus-float-sqrt3", sympy.sqrt(3) - F3, {}, True),
    ("float-sqrt2-squared-minus-2", a_ ** 2 - 2, {a_: F2}, True),
    ("two-minus-float-sqrt2-squared", 2 - a_ ** 2, {a_: F2}, False),
    ("float-0.1-times-10", a_ * b_ - 1, {a_: sympy.Float(0.1), b_: sympy.Integer(10)}, True),
    ("float-0.3-minus-0.1-minus-0.2", a_ - b_ - sympy.Symbol("c"),
     {a_: sympy.Float(0.3), b_: sympy.Float(0.1), sympy.Symbol("c"): sympy.Float(0.2)}, False),
    ("float-1e-3-scaled", (a_ - R(1, 1000)) * 10**20, {a_: sympy.Float(1e-3)}, True),
]


@pytest.mark.parametrize("name,margin,sub,truth", FLOAT_MARGINS, ids=[c[0] for c in FLOAT_MARGINS])
def test_float_margin_is_never_exact(name, margin, sub, truth):
    exact_sub = {k: v.xreplace({f: _binary(f) for f in v.atoms(sympy.Float)}) for k, v in sub.items()}
    exact_margin = sympy.sympify(margin).xreplace({f: _binary(f) for f in sympy.sympify(margin).atoms(sympy.Float)})
    assert (sympy.N(exact_margin.xreplace(exact_sub), 60) > 0) == truth  # the test's own premise
    _float_verdict_allowed(_evaluate(Hypothesis(name, margin), sub), truth)


def _margin_theorem():
    P = Parameters()
    a = P.scalar("a")
    b = P.scalar("b")
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    V = Functional([Term(x(t)[0] ** 2)])
    claim = DerivativeClaim("Vdot", V, system, [Term(-2 * x(t)[0] ** 2)])
    return Theorem("margins", system=system, functional=V, claims=[claim],
                   hypotheses=[Hypothesis("a - 1 - b + 1/2 > 0", a - 1 - b + R(1, 2)),
                               Hypothesis("a > 1/10", a - R(1, 10))])


@pytest.mark.parametrize("values,truths", [
    ({"a": "1e16", "b": "1e16"}, None),                           # strings are exact: −½ fails, a > 1/10 holds
    ({"a": 10**16, "b": 10**16}, None),
    ({"a": 1e16, "b": 1e16}, (False, True)),                      # Python floats, exact binary 10¹⁶
    ({"a": sympy.Float(1e16), "b": sympy.Float(1e16)}, (False, True)),
    ({"a": 0.1, "b": 0}, (False, True)),                          # binary 0.1 > 1/10: a > 1/10 holds
], ids=["strings", "ints", "python-floats", "sympy-floats", "python-float-0.1"])
def test_margins_through_theorem_run(values, truths):
    th = _margin_theorem()
    try:
        report = th.run(values)
    except InputError:
        assert truths is not None, "exact values refused"
        return
    hyps = [r for r in report.results if r.kind == "hypothesis"]
    if truths is None:
        assert [r.status for r in hyps] == [Status.FAILED, Status.EXACT], [r.detail for r in hyps]
    else:
        for r, truth in zip(hyps, truths):
            _float_verdict_allowed(r, truth)
    assert not says_established(report.verdict) or all(r.status in PROOF for r in hyps), report.verdict


FLOAT_CLAIMS = [
    # (id, family, index of the term, factor as a Float, claim true at the binary value?)
    ("float-1.0-coefficient", "numeric-window", 1, sympy.Float(1.0), True),
    ("float-0.5-exactly-binary", "scalar-window-values", 1, sympy.Float(1.0), True),
    ("float-near-one", "scalar-window-values", 2, sympy.Float(1.0000001), False),
    ("float-30-digits-near-one", "numeric-window", 0, sympy.Float("0.99999999999999999999", 30), False),
    ("float-in-time-varying", "tv-delay-explicit", 1, sympy.Float(1.0), True),
]


@pytest.mark.parametrize("name,family,i,factor,truth", FLOAT_CLAIMS, ids=[c[0] for c in FLOAT_CLAIMS])
def test_claim_with_float_coefficient_is_never_exact(name, family, i, factor, truth):
    fam = next(f for f in cases.FAMILIES if f.name == family)
    terms = list(fam.terms)
    terms[i] = factor * terms[i]
    assert factor.atoms(sympy.Float) or isinstance(factor, sympy.Float)
    try:
        result, report = cases.run_claim(fam, terms)
    except InputError as exc:
        assert "float" in str(exc).lower(), f"refused without saying it is about a float: {exc}"
        return
    assert result.status is not Status.EXACT, f"a claim with a Float came out exact: {result.detail}"
    if truth:
        assert result.status is not Status.FAILED, result.detail
    else:
        assert result.status not in PROOF, result.detail
    assert not says_established(report.verdict), report.verdict


# ------------------------------------------------------------------------------------------------------
# kind 8: verdicts never say more than was checked
# ------------------------------------------------------------------------------------------------------

def _readme_theorem():
    """The README's "Check your own proof" file (the scalar delay system of the mutation families)."""
    P, a, b, c, tau, x, system = cases._scalar_delay()
    V = Functional([Term(x(t)[0] ** 2 / 2, text="x²/2"),
                    Term(c * window_integral(x(xi)[0] ** 2, tau), text="c∫x²")])
    claim = DerivativeClaim("Vdot", V, system, [
        Term((c - a) * x(t)[0] ** 2, text="(c-a)x²"),
        Term(b * x(t)[0] * x(t - tau)[0], text="b x x(t-τ)"),
        Term(-c * x(t - tau)[0] ** 2, text="-c x(t-τ)²"),
    ])
    theorem = Theorem("stable", system=system, functional=V, hypotheses=[Hypothesis("|b| < a", a - abs(b))],
                      claims=[claim])
    return P, system, V, claim, theorem


@pytest.mark.parametrize("values", [
    {"a": "2", "c": "5"},            # the issue's example: (c − a) x² > 0
    {"a": "1", "b": "0", "c": "2"},
    {"a": "3", "b": "1/2", "c": "4"},
    {"a": "2", "b": "1", "c": "2"},  # c = a: V̇ = b x x(t−τ) − c x(t−τ)², indefinite
], ids=["a2-c5", "a1-b0-c2", "a3-c4", "c-equals-a"])
def test_indefinite_vdot_is_not_established(values):
    *_, theorem = _readme_theorem()
    report = theorem.run(values)
    (vdot,) = [r for r in report.results if r.name == "Vdot"]
    assert vdot.status is Status.EXACT, vdot.detail  # the printed V̇ is right; it is just not negative
    assert not says_established(report.verdict), report.verdict


def test_theorem_without_claims_is_not_established():
    P, system, V, claim, _ = _readme_theorem()
    with pytest.raises(InputError, match="expected at least one hypothesis"):  # refused when declared (issue 22)
        Theorem("empty", system=system, functional=V)


def test_theorem_with_hypotheses_only_is_not_established():
    P, system, V, claim, _ = _readme_theorem()
    a, b = P["a"].obj, P["b"].obj
    report = Theorem("hyps", system=system, functional=V, hypotheses=[Hypothesis("|b| < a", a - abs(b))]).run({})
    assert [r.status for r in report.results] == [Status.EXACT]
    assert not says_established(report.verdict), report.verdict


def test_theorem_without_functional_is_not_established():
    P, system, V, claim, _ = _readme_theorem()
    with pytest.raises(InputError, match="expected at least one hypothesis"):  # refused when declared (issue 22)
        Theorem("nofunctional", system=system)


def test_theorem_with_only_an_intermediate_identity_is_not_established():
    P, system, V, claim, _ = _readme_theorem()
    x = system.states[0]
    X = x(t)[0]
    ident = IdentityClaim("square", (Term((X + 1) ** 2),), (Term(X ** 2 + 2 * X + 1),), system)
    report = Theorem("ident", system=system, functional=V, claims=[ident]).run({})
    assert [r.status for r in report.results] == [Status.EXACT]
    assert not says_established(report.verdict), report.verdict


def _other_systems():
    P, system, V, claim, _ = _readme_theorem()
    a, b, tau = P["a"].obj, P["b"].obj, P["tau"].obj
    x = system.states[0]
    flipped = System([Equation(x, [Term(a * x(t)[0]), Term(b * x(t - tau)[0])])], parameters=P, name="flipped")
    extra = System([Equation(x, [Term(-a * x(t)[0]), Term(b * x(t - tau)[0]), Term(-x(t)[0] ** 3)])],
                   parameters=P, name="with cubic")
    P2 = Parameters()
    a2 = P2.scalar("a", positive=True, default=2)
    b2 = P2.scalar("b", default=1)
    P2.scalar("c", positive=True, default=1)
    tau2 = P2.delay("tau", default=1)
    other_registry = System([Equation(x, [Term(-a2 * x(t)[0]), Term(b2 * x(t - tau2)[0])])], parameters=P2,
                            name="other registry")
    return P, system, V, claim, flipped, extra, other_registry


@pytest.mark.parametrize("which", ["flipped", "extra", "other-registry", "identity-claim", "second-claim"])
def test_claim_along_another_system_is_bad_input(which):
    P, system, V, claim, flipped, extra, other_registry = _other_systems()
    other = {"flipped": flipped, "extra": extra, "other-registry": other_registry}.get(which, flipped)
    x = system.states[0]
    if which == "identity-claim":
        claims = [claim, IdentityClaim("square", (Term((x(t)[0] + 1) ** 2),), (Term(x(t)[0] ** 2 + 2 * x(t)[0] + 1),),
                                       other)]
    elif which == "second-claim":
        claims = [claim, DerivativeClaim("Vdot2", V, other, claim.terms)]
    else:
        claims = [DerivativeClaim("Vdot", V, other, claim.terms)]
    with pytest.raises(InputError):
        theorem = Theorem("mixed", system=system, functional=V, claims=claims)
        theorem.run({})
