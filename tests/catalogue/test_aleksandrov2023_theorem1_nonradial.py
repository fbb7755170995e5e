"""Paper 002 Theorem 1 on a non-radial Π̃ (``aleksandrov2023.theorem1_nonradial``).

The verdict at the defaults (established), and where it must not be: Π̃ not homogeneous of the
stated order, Π + τΠ̃ indefinite after a flipped sign, a bound constant κ_g below max‖∂Π̃/∂q‖ on
the circle (and c4 stated below the certified κ_g); the radial chain's norm tree, which matches
∂Π̃/∂q = κ̃‖q‖²q, does not apply to this Π̃ (the finding).
"""

import importlib

import sympy

from lkverify import Status, t, window_integral, xi
from lkverify.certify.steps.rules import CauchySchwarz, Context, homogeneous_field, integral_of, measured
from lkverify.proofs.aleksandrov2023 import system3 as S3
from lkverify.proofs.aleksandrov2023 import theorem1_chain as T1C
from lkverify.proofs.aleksandrov2023.theorem1_bound import c4
from lkverify.proofs.aleksandrov2023.theorem1_hypotheses import Homogeneity

# the module (the package attribute of that name is the item)
NR = importlib.import_module("lkverify.proofs.aleksandrov2023.theorem1_nonradial")
theorem = NR.theorem1_nonradial
X = S3.X


def _choices(**over):
    given = {k: str(v) for k, v in over.items()}
    return NR.PN.resolve({**NR.find_choices(NR.PN.resolve(given, use_defaults=True)), **given}, use_defaults=True)


def _by_name(report):
    return {r.name: r for r in report.results}


def _conditions(result):
    return [c for a in result.value["applications"] for c in a["conditions"]]


# ---- the instance ----------------------------------------------------------------------------------
def test_the_default_pi_tilde_is_not_radial_and_not_itself_definite():
    sub = NR.PN.substitution(NR.PN.resolve({}, use_defaults=True))
    Pt = sympy.expand(NR.Pi_t.xreplace(sub))
    assert Pt.xreplace({X[0]: 1, X[1]: 0}) == 0 and Pt.xreplace({X[0]: 0, X[1]: 1}) == sympy.Rational(1, 2)
    g = NR.GRAD_PI_T.xreplace(sub).xreplace({X[0]: 1, X[1]: 1})
    assert g[0] * 1 - g[1] * 1 != 0  # ∂Π̃/∂q(1, 1) is not parallel to q = (1, 1)
    assert Pt.xreplace({X[0]: 1, X[1]: sympy.Rational(1, 2)}) < 0  # Π̃ alone indefinite; Π + τΠ̃ is not
    # the shared symbols: the chain's term bounds of theorem1_chain are written in them
    assert (NR.lam, NR.mu, NR.tau, NR.A, NR.B) == (S3.lam, S3.mu, S3.tau, S3.A, S3.B)


# ---- the verdict at the defaults ----------------------------------------------------------------
def test_the_theorem_is_established_at_the_defaults():
    rep = theorem.run({}, budget=120)
    assert rep.verdict.startswith("established"), rep.verdict
    assert rep.exit_code == 0
    by = _by_name(rep)
    assert by["Vdot_structured"].status is Status.EXACT and by["Vdot_printed"].status is Status.EXACT
    assert all(by[h.name].status.is_proof for h in NR.HYPOTHESES)
    assert by["Krasovskii conditions"].status is Status.CERTIFIED
    assert rep.parameters["kappa_g"] == "101/50"
    # the four terms with ∂Π̃/∂q rest on κ_g ≥ max‖∂Π̃/∂q‖ on the circle, certified
    rows = [r for r in rep.results if r.kind.value == "bound" and "∫" in r.name and "Π̃" in r.name and ":" in r.name]
    assert len(rows) == 4 and all(r.status is Status.CERTIFIED for r in rows)
    for r in rows:
        (kappa,) = [c for c in _conditions(r) if c["condition"].startswith("κ = 101/50 ≥ max")]
        assert kappa["status"] == "certified"


# ---- the finding: the radial chain's norm tree -------------------------------------------------------
def test_the_radial_norm_tree_does_not_match_a_non_radial_gradient():
    radial = T1C.chain_steps(functional=NR.functional, system=NR.system_nonradial, derivation=NR.derivation,
                             K=NR.K_int, J=NR.J_int, definitions=NR.DEFINITIONS_NONRADIAL)  # tree: κ̃‖q‖²q
    res = radial[1].check(_choices(), budget=30)
    assert not res.status.is_proof
    (row,) = [r for r in res.results() if "Π̃" in r.name and ":" in r.name]
    assert row.status is Status.UNDECIDED
    assert "the integrand is g(ξ)·v(ξ) with g = kappa_t" in row.detail


# ---- mutations that must fail ---------------------------------------------------------------------
def test_pi_tilde_of_another_order_than_mu_plus_one_fails_the_hypothesis():
    rep = theorem.run({"mu": "2"}, budget=60)
    assert rep.exit_code == 1 and rep.verdict.startswith("failed: hypotheses"), rep.verdict
    assert _by_name(rep)["Pi, Pi~ homogeneous of order mu+1"].status is Status.FAILED


def test_a_non_homogeneous_pi_tilde_fails_homogeneity_and_the_norm_tree():
    sub = NR.PN.substitution(NR.PN.resolve({}, use_defaults=True))
    mutant = NR.Pi_t + X[0] ** 2 * X[1]  # a cubic term: Π̃ no longer homogeneous
    hyp = Homogeneity("Pi~ homogeneous", {"Π̃": mutant}, NR.mu + 1).evaluate(sub)
    assert hyp.status is Status.FAILED and "[3, 4]" in hyp.detail
    # the norm tree refuses the non-homogeneous field: ‖F(q)‖ ≤ κ‖q‖³ is not licensed
    F = sympy.Matrix([sympy.diff(mutant, x) for x in X])
    Jm = window_integral(S3.grad(mutant, S3.q(xi)), NR.tau)
    measures = {m.name: m for m in T1C.MEASURES}
    ctx = Context(NR.system_nonradial, _choices(), measures, T1C.REGION)
    tree = integral_of(homogeneous_field(F, X, T1C.J_, degree=NR.mu, kappa=NR.kappa_g, at=xi), measure=T1C.J_,
                       power=NR.mu, weight=NR.kappa_g, holder=T1C._holder)
    app = CauchySchwarz(S3.v(t), Jm, (measured(T1C.W_), tree)).apply(S3.v(t).dot(Jm), "upper", ctx)
    assert app.status is Status.FAILED and "form of degree 3" in app.detail


def test_a_flipped_sign_in_pi_tilde_makes_pi_plus_tau_pi_tilde_indefinite():
    rep = theorem.run({"pt04": "-1/2"}, budget=60)
    assert rep.exit_code == 1 and rep.verdict.startswith("failed: hypotheses"), rep.verdict
    row = _by_name(rep)["Pi + tau*Pi~ positive definite"]
    assert row.status is Status.FAILED and "x = (0, 1)" in row.detail
    # the whole Π̃ flipped: indefinite too (Π alone is)
    rep = theorem.run({"pt31": "1/2", "pt22": "-3/4", "pt04": "-1/2"}, budget=60)
    assert _by_name(rep)["Pi + tau*Pi~ positive definite"].status is Status.FAILED


def test_kappa_g_below_the_maximum_of_the_gradient_is_refuted():
    rep = theorem.run({"kappa_g": "19/10"}, budget=120)  # max‖∂Π̃/∂q‖ = 2 on the circle, at q = (0, 1)
    assert rep.exit_code == 1 and not rep.verdict.startswith("established"), rep.verdict
    by = _by_name(rep)
    assert by["V ≤ U"].status is Status.FAILED  # a rechecked witness against the stated bound
    (row,) = [r for r in rep.results if r.name.startswith("V ≥ L: −qᵀ∫")]
    assert not row.status.is_proof
    assert "at x = (0, 1) ‖F(x)‖ = 2 > κ‖x‖^k" in row.detail


def test_c4_stated_below_the_certified_kappa_is_refuted():
    upper = NR.steps[1]
    defs = {**NR.DEFINITIONS_NONRADIAL, c4: NR.kappa_g / 2}
    res = upper.with_bounds(definitions=defs).check(_choices(), budget=30)
    assert res.status is Status.FAILED
    (row,) = [r for r in res.results() if r.name.startswith("V ≤ U: −qᵀ∫")]
    assert row.status is Status.FAILED


def test_kappa_g_at_the_exact_maximum_is_undecided_not_refuted():
    """κ_g = 2 = max‖∂Π̃/∂q‖: ≥ holds (with equality at (0, 1)); the strict sphere test cannot show it."""
    res = NR.steps[1].check(_choices(kappa_g=2), budget=30)
    (row,) = [r for r in res.results() if r.name.startswith("V ≤ U: −qᵀ∫")]
    (kappa,) = [c for c in _conditions(row) if c["condition"].startswith("κ = 2 ≥ max")]
    assert kappa["status"] == "undecided", kappa
