"""Paper 004 (Zaremba 1997): the catalogue's checks hold where the paper is right, fail where it is not,
and every checker refutes a mutated claim (a wrong term of Y, a flipped sign in (2.8), a wrong γ, a
region too large) while accepting a true claim written differently."""

import dataclasses
import importlib

import numpy as np
import pytest
import sympy

from lkverify import Status, cross
from lkverify.proofs.zaremba1997 import P, example210, example313, excitation, parametrisation, theorem1, theorem2

eq = importlib.import_module("lkverify.proofs.zaremba1997.equations")
par = importlib.import_module("lkverify.proofs.zaremba1997.parametrisation")
th1 = importlib.import_module("lkverify.proofs.zaremba1997.theorem1")
th2 = importlib.import_module("lkverify.proofs.zaremba1997.theorem2")
cor = importlib.import_module("lkverify.proofs.zaremba1997.corrected")
ex210 = importlib.import_module("lkverify.proofs.zaremba1997.example210")
ex313 = importlib.import_module("lkverify.proofs.zaremba1997.example313")
exc = importlib.import_module("lkverify.proofs.zaremba1997.excitation")

DEFAULTS = P.resolve({}, use_defaults=True)


def statuses(results):
    return {r.name: r.status for r in results}


# -- (1.5) and Lemmas 2, 3 ---------------------------------------------------------------------------------------

def test_printed_regressor_is_exact():
    assert all(r.status is Status.EXACT for r in par.regressor_results())


def test_wrong_term_in_Y_is_refuted():
    def Y_wrong(w, wr, wrd):  # the sign of Y[1,2] flipped
        Y = eq.Y(w, wr, wrd)
        Y[0, 1] = -Y[0, 1]
        return Y

    res = par.regressor_results(Y_wrong)
    assert [r.status for r in res] == [Status.FAILED, Status.EXACT, Status.EXACT]
    assert "Y[1,2]·θ2" in res[0].detail and res[0].value["witness_value"] != "0"


def test_Y_written_differently_passes():
    def Y_other(w, wr, wrd):  # row 1 from the cross product itself, not retyped
        Y = eq.Y(w, wr, wrd)
        M = sympy.diag(*sympy.symbols("a b c"))
        row = [sympy.diff((M * wrd + cross(wr, M * w))[0], x) for x in sympy.symbols("a b c")]
        Y[0, :] = sympy.Matrix([row])
        return Y

    assert all(r.status is Status.EXACT for r in par.regressor_results(Y_other))


def test_lemma3_print_lacks_Lambda_squared_but_holds_at_Lambda_1():
    st = statuses(par.lemma_results(DEFAULTS))
    assert st["Lemma 3 (2.5) as printed: ‖ω_e‖² + ‖e‖² = ‖v‖² − 2Λω_eᵀe"] is Status.FAILED
    assert st["Lemma 3 (2.5) derived: ‖ω_e‖² + Λ²‖e‖² = ‖v‖² − 2Λω_eᵀe"] is Status.EXACT
    assert st["Lemma 2: ω_eᵀe = d/dt(−Σkᵢcᵢᵀsᵢ) along (1.4)"] is Status.EXACT
    at1 = statuses(par.lemma_results(P.resolve({"Lam": "1"}, use_defaults=True)))
    assert at1["Lemma 3 (2.5) as printed: ‖ω_e‖² + ‖e‖² = ‖v‖² − 2Λω_eᵀe"] is Status.EXACT


# -- Theorem 1 and (2.10) ----------------------------------------------------------------------------------------

def test_theorem1_identity_exact_and_flipped_adaptation_refuted():
    assert [r.status for r in th1.theorem1_results(DEFAULTS)] == [Status.EXACT, Status.EXACT]
    flipped = th1.theorem1_results(DEFAULTS, system=eq.closed_loop1(+1))
    assert flipped[1].status is Status.FAILED                      # (2.9) with θ̇_r = +ΓYᵀv
    assert flipped[0].status is Status.FAILED                      # the first line writes θ̇_e by (2.8) as printed


def test_theorem1_at_other_gains_and_bad_gain():
    rep = theorem1.run({"Kd": "[[3,1,0],[1,3,0],[0,0,2]]", "Gamma": "diag(1,2,3)", "Lam": "3/2"})
    assert rep.exit_code == 0
    rep = theorem1.run({"k2": "1"})                                  # k1 = k2: not distinct
    assert rep.exit_code == 1 and "kᵢ > 0 pairwise distinct" in rep.verdict


def test_example210_print_wrong_unless_Lambda_1():
    res = ex210.example210_results(DEFAULTS)
    assert all(r.status is Status.FAILED for r in res)
    assert all("−ΛY(ω, e, ė)θ_r" in r.detail.split("not in the derivation")[0] for r in res)  # that term confirmed
    at1 = ex210.example210_results(P.resolve({"Lam": "1"}, use_defaults=True))
    assert all(r.status is Status.EXACT for r in at1)
    written = [("−K_d(ω + Λe)", -eq.Kd * (eq.omega(eq.t) + eq.Lam * eq.e)),
               ("−ΛY(ω, e, ė)θ_r", -eq.Lam * eq.Y(eq.omega(eq.t), eq.e, eq.EDOT) * eq.theta_r(eq.t))]
    assert all(r.status is Status.EXACT for r in ex210.example210_results(DEFAULTS, written))


# -- Theorem 2 ---------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def theorem2_default():
    return theorem2.run({})


def test_theorem2_findings(theorem2_default):
    st = statuses(theorem2_default.results)
    assert st["(3.7): T1 = d/dt ½vᵀMv"] is Status.EXACT
    assert st["(3.8): T2 + T3"] is Status.EXACT
    assert st["(3.9) first line: T4 = d/dt ½‖η‖²"] is Status.FAILED
    assert st["(3.9) first line − T4 derived = ηᵀ(v × Mω)"] is Status.EXACT
    assert st["T4 derived: −λ_c‖η‖² − ηᵀ(v × Mω)"] is Status.EXACT
    assert st["(3.9) second line = first line (as printed)"] is Status.FAILED
    assert st["(3.9) second line with −(λ_c/2)‖η‖² = first line"] is Status.EXACT
    assert st["(3.10) from the printed pieces: Q ⪰ 0 (Young's step, μ = 2σ_M)"] is Status.EXACT
    assert st["(3.10) along the true loop (1.3), (3.2)–(3.4)"] is Status.FAILED   # a finding: the chain runs on (3.10′)
    assert th2.gamma_results(DEFAULTS)[0].status is Status.EXACT               # the step from (3.10) itself
    assert st["γ of (3.12) against the largest γ of this step"] is Status.EXACT
    assert st["(3.11): the signed sum has the rate of V_δ along (1.4)"] is Status.EXACT
    assert st["(3.11) as printed: V̇_c = 2V̇ (3.10)"] is Status.FAILED
    assert st["(3.11) with K_p and ‖η‖²: V̇_c = 2V̇"] is Status.EXACT
    assert st["(b) of (3.4) as printed: λ(t) ≥ λ1 for every t ≥ 0"] is Status.FAILED       # λ(0) = 0 at ‖Γ(0)‖ = k0


def test_wrong_gamma_refuted_and_reordered_gamma_passes():
    lc, l1 = sympy.Integer(1), sympy.Rational(1, 2)
    res = th2.gamma_results(DEFAULTS, gamma=sympy.Min(2 * lc, lc * l1, 4))     # twice the printed γ
    assert res[0].status is Status.FAILED and "negative" in res[0].detail
    res = th2.gamma_results(DEFAULTS, gamma=sympy.Min(2, lc * l1 / 2, lc))
    assert res[0].status is Status.EXACT
    gamma, coeffs, gmax = th2.gamma_coefficients(P.resolve({"lam_c": "3", "lam1": "4"}, use_defaults=True))
    assert gmax == 2 and gamma == 2                                              # min{3, 6, 2}


def test_alpha_below_threshold_fails_young_step():
    v = P.resolve({"alpha": "20"}, use_defaults=True)                           # λ_cσ_M² = 25
    assert th2.hypotheses2(v)[0].status is Status.FAILED
    a = th2.Abstract(v)
    vs, ws, zs = (sympy.Matrix(sympy.symbols(f"{n}1:4", real=True)) for n in ("qv", "qw", "qz"))
    from lkverify.certify.matrices import matrix_positive_definite
    form = 20 * vs.dot(vs) - vs.dot(a.M * zs) + zs.dot(zs) / 4 + ws.dot(ws) / 2
    H = sympy.hessian(form, list(vs) + list(ws) + list(zs)) / 2
    assert matrix_positive_definite(H, semidefinite=True).status is Status.FAILED
    v = P.resolve({"alpha": "25"}, use_defaults=True)                           # the exact threshold: still ⪰ 0
    form = 25 * vs.dot(vs) - vs.dot(a.M * zs) + zs.dot(zs) / 4 + ws.dot(ws) / 2
    H = sympy.hessian(form, list(vs) + list(ws) + list(zs)) / 2
    assert matrix_positive_definite(H, semidefinite=True).status is Status.EXACT


# -- (3.13), (3.14) ----------------------------------------------------------------------------------------------

def test_example313_control_and_region():
    assert all(r.status is Status.EXACT for r in ex313.control_313_results(DEFAULTS))
    wrong = ex313.control_313_results(DEFAULTS, printed_Ke=lambda kp, a, L, lc, Mr: (kp + a) * sympy.eye(3) + lc * L * Mr)
    assert all(r.status is Status.FAILED for r in wrong)
    assert [r.status for r in ex313.region_314(DEFAULTS)] == [Status.EXACT, Status.EXACT]
    too_large = ex313.region_314(DEFAULTS, printed_threshold=lambda L: 1 / L - 1)[-1]
    assert too_large.status is Status.FAILED and "too large" in too_large.detail
    rewritten = ex313.region_314(DEFAULTS, printed_threshold=lambda L: (2 - L) / L)[-1]
    assert rewritten.status is Status.EXACT


def test_region_fraction_grows_with_Lambda():
    fr = [ex313.region_fraction(x) for x in ("1/2", "1", "2", "4", "100")]
    assert fr == [0, 0, sympy.Rational(1, 2), sympy.Rational(3, 4), sympy.Rational(99, 100)]
    rep = example313.run({"Lam": "4"})
    assert rep.exit_code == 1 and rep.verdict == "failed: text: 'as Λ decreases D tends to the unit sphere'"


# -- (3.5) -------------------------------------------------------------------------------------------------------

def test_excitation_certified_for_catalogued_motion_and_failed_for_constant_axis():
    bounds = exc.excitation_bounds(DEFAULTS)
    for pe in bounds.values():
        assert pe.status is Status.CERTIFIED
        assert pe.beta1 > 0
        assert pe.beta1 <= pe.beta1_estimate and pe.beta2_estimate <= pe.beta2
    assert bounds["φᵀφ"].beta1 > 0.5 and bounds["φᵀφ"].beta2 < 1.9     # sampled 0.577, 1.844
    still = P.resolve({"wd1": "1/2", "wd2": "0", "wd3": "0"}, use_defaults=True)
    assert all(pe.status is Status.FAILED for pe in exc.excitation_bounds(still).values())
    # ω_d along one axis but time-varying: Y_c has a zero column, the Gram a zero direction (exact)
    one_axis = P.resolve({"wd1": "sin(t)/2", "wd2": "0", "wd3": "0"}, use_defaults=True)
    pe = exc.excitation_bounds(one_axis)["φᵀφ"]
    assert pe.status is Status.FAILED and "exactly 0" in pe.detail


def test_excitation_constants_too_large_are_refuted():
    bounds = exc.excitation_bounds(DEFAULTS)["φᵀφ"]
    too_big = sympy.Rational(bounds.beta1_estimate).limit_denominator(1000) + sympy.Rational(1, 50)
    res = exc.claimed_results(DEFAULTS, beta1=too_big, beta2=sympy.Rational(9, 5))
    assert [r.status for r in res] == [Status.FAILED, Status.FAILED]      # β1 too large, β2 too small
    assert "t0 =" in res[0].detail and "(arb)" in res[0].detail
    res = exc.claimed_results(DEFAULTS, beta1=sympy.Rational(1, 2), beta2=2)   # below/above the certified ones
    assert [r.status for r in res] == [Status.UNDECIDED, Status.UNDECIDED]


def test_theorem2_chain_runs_on_the_corrected_step():
    rep = theorem2.run({})
    links = {link.name: link for link in rep.chain}
    # at the defaults the chain stops at property (b): the bound k1 of ‖Γ‖ exceeds k0 (not refuted)
    assert rep.exit_code == 1 and rep.verdict.startswith("undecided: (b) of (3.4)")
    assert "≥ k0 = 10: this bound gives no λ1 > 0" in rep.verdict
    assert links["additional hypothesis (derived)"].status is Status.EXACT
    assert links["persistent excitation (3.5): β1, β2 along the programmed motion"].status is Status.CERTIFIED
    assert links["(2.3): e → 0, ω → ω_d (Barbalat, Lemma 1)"].status is Status.EXACT
    chetaev = links["(в) Chetaev: s = (−c1, c2, −c3) unstable"]
    assert chetaev.status is Status.EXACT and "(3.10′)" in chetaev.detail
    assert "V(x*) = 0" in chetaev.detail and "V < 0 on (0, 1)" in chetaev.detail
    assert links["conclusion"].status is None


def test_theorem2_established_under_the_additional_hypothesis():
    rep = theorem2.run({"lam0": "1/100", "k0": "100", "lam1": "1/200"})
    assert rep.verdict.startswith("established")            # exit 1: the printed formulas it refutes
    assert "under the additional hypotheses (derived where the paper's step is false)" in rep.verdict
    assert "α = 50, λ_cσ_M² + σ_M²w̄²/λ_c = " in rep.verdict
    assert "(3.10) along the true loop (1.3), (3.2)–(3.4) failed" in rep.verdict   # the print stays refuted
    # λ1 above what the bound gives: undecided, not established
    rep = theorem2.run({"lam0": "1/100", "k0": "100", "lam1": "1/50"})
    assert rep.verdict.startswith("undecided: (b) of (3.4)") and "below the λ1 = 1/50" in rep.verdict


def test_theorem2_alpha_below_the_derived_threshold():
    rep = theorem2.run({"alpha": "40"})                        # > λ_cσ_M² = 25 (the paper's), < 40.28 (derived)
    links = {link.name: link for link in rep.chain}
    assert links["hypotheses"].status is Status.EXACT
    assert links["additional hypothesis (derived)"].status is Status.FAILED
    assert rep.verdict.startswith("not established: additional hypothesis (derived)")
    assert links["(в) Chetaev: s = (−c1, c2, −c3) unstable"].status is Status.FAILED
    v = P.resolve({"alpha": "41"}, use_defaults=True)          # just above: a small level set
    k = cor.level_constants(v)
    assert k["status"] is Status.EXACT and k["V0"] > 0 and k["V0"] < sympy.Rational(1, 10 ** 4)


def _corrected(values=DEFAULTS, **kw):
    out, a, derived, printed = th2.theorem2_results(values)
    return a, derived, cor.corrected_results(a, derived, values, **kw)


def test_corrected_step_pieces_and_mutations():
    from lkverify import cross, dot
    from lkverify.symbolic.polynomial import compare_polynomials
    a, derived, r = _corrected()
    assert [r[x].status for x in ("identity", "A", "lagrange", "level")] == [Status.EXACT] * 4
    k = r["constants"]
    # the level set keeps ‖ω‖ ≤ W: w̄ + κ_V·V0^{1/2} ≤ W, exactly
    assert k["W"] > k["w_bar"] and k["kappa_V"] ** 2 * k["V0"] <= (k["W"] - k["w_bar"]) ** 2
    assert k["w_bar"] ** 2 >= sympy.Rational(1, 4) + sympy.Rational(1, 4) + sympy.Rational(1, 9)
    # a larger W: the identity still holds (c cancels), A ⪰ 0 is refuted
    _, _, big = _corrected(W=k["W"] + sympy.Rational(1, 10 ** 6))
    assert big["identity"].status is Status.EXACT and big["A"].status is Status.FAILED
    # dropping the gyroscopic term from B (the paper's omission) is refuted
    lc, g = a.q["lam_c"], cross(a.v, a.M * a.w)
    full = derived["T1"] + derived["T23"] + derived["T4"]
    rhs = a.poly(-lc * dot(a.v, a.M * a.v) - lc / 4 * dot(a.eta, a.eta) - a.q["Kp"] * a.q["Lam"] * dot(a.e, a.e)
                 - lc / 4 * th2.lam * (a.th_e.T * a.Gm * a.th_e)[0, 0])
    z, mv_e, c = a.ph.T * a.th_e, a.M * a.v - a.ep, k["c"]
    A = ((a.q["alpha"] - c) * dot(a.v, a.v) - lc * dot(a.v, a.M * z) + lc / 4 * dot(z, z)
         + lc / 2 * dot(mv_e, mv_e))
    C = c * dot(a.v, a.v) - dot(g, g) / lc
    dropped = compare_polynomials("x", [("R′", rhs), ("−A", -A), ("−(λ_c/4)‖η‖²", -lc / 4 * dot(a.eta, a.eta)),
                                        ("−C", -C)], [("V̇", full)], R=a.R)
    assert dropped.status is Status.FAILED
    flipped = compare_polynomials("x", [("R′", rhs), ("−A", -A), ("−B", -lc / 4 * dot(a.eta - 2 * g / lc, a.eta - 2 * g / lc)),
                                        ("−C", -C)], [("V̇", full)], R=a.R)
    assert flipped.status is Status.FAILED                                   # the sign inside the square


def test_sqrt_roundings():
    for q in (sympy.Rational(2), sympy.Rational(1, 3), sympy.Rational(10 ** 9 + 7, 3), sympy.Rational(49, 4)):
        up, down = cor.sqrt_up(q), cor.sqrt_down(q)
        assert down ** 2 <= q <= up ** 2 and up - down <= sympy.Rational(2, 10 ** 6) * (1 + up)
    with pytest.raises(ValueError):
        cor.sqrt_up(-1)


def test_property_b_bound():
    v = P.resolve({"lam0": "1/100", "k0": "100", "lam1": "1/200"}, use_defaults=True)
    st, why = th2.property_b(v, 0.1985)
    assert st is Status.CERTIFIED and "≥ λ1 = 1/200" in why
    st, why = th2.property_b(v, 0.01)                         # a weaker excitation: k1 ≥ k0
    assert st is Status.UNDECIDED and "gives no λ1 > 0" in why
    assert th2.property_b(v, None)[0] is Status.UNDECIDED


def test_items_at_defaults():
    assert parametrisation.run({}).exit_code == 1       # Lemma 3 as printed
    assert example210.run({}).exit_code == 1            # (2.10) as printed
    assert theorem1.run({}).exit_code == 0
    assert excitation.run({}).exit_code == 0


@pytest.mark.slow
def test_example_simulations():
    ex = importlib.import_module("lkverify.proofs.zaremba1997.example").example
    rep = ex.run()
    assert rep.exit_code == 0, rep.as_text()
    # the tracking claims say from when ‖e‖ and ‖ω − ω_d‖ stay below their tolerance (issue 24 item 4)
    mod = importlib.import_module("lkverify.proofs.zaremba1997.example")
    trs = ex.simulate()
    for claim in [c for c in ex.claims if isinstance(c, mod.Tracks)]:
        res = claim.check(ex, trs)
        t_below = res.value["t_below"]
        assert t_below is not None and f"from t = {t_below:.4g} on" in res.detail
        err = mod.errors(trs[claim.run])
        after = trs[claim.run].t >= t_below
        assert np.all(np.maximum(err["e"], err["omega_e"])[after] < claim.tol)
        strict = dataclasses.replace(claim, tol=1e-12)   # a tolerance never reached: failed, no time
        res = strict.check(ex, trs)
        assert res.status is Status.FAILED and res.value["t_below"] is None


def test_theorem1_identity_for_every_parameter():
    r = th1.general_result()
    assert r.status is Status.EXACT and "every parameter symbolic" in r.detail


# -- Theorem 1 as a signal argument (Barbalat) -------------------------------------------------------------------

def _decide(links, system=None, values=DEFAULTS):
    from lkverify.certify.steps.signals import Facts

    facts = Facts(system or eq.system1, P.substitution({k: v for k, v in values.items() if not k.startswith("wd")}),
                  {f"wd{i}": values[f"wd{i}"] for i in (1, 2, 3)})
    return {link.name: link.decide(facts).status for link in links}


def test_theorem1_established_by_the_barbalat_chain():
    rep = theorem1.run({})
    names = [link.name for link in rep.chain]
    assert rep.exit_code == 0 and rep.verdict.startswith("established")
    for expected in ("v → 0 (Barbalat)", "e → 0 (Barbalat)", "every state bounded", "v ∈ L2", "e ∈ L2", "ω_e → 0"):
        assert expected in names
    finite = next(r for r in rep.results if r.name.startswith("(s1, s2, s3) →"))
    assert len(finite.value["points"]) == 4                           # sᵢ = ±cᵢ with det = 1


def test_theorem1_chain_along_a_flipped_adaptation_law_is_refuted():
    links, _ = th1.argument(DEFAULTS)
    st = _decide(links, system=eq.closed_loop1(+1))
    assert st["(2.9): V̇ = −vᵀK_dv ≤ 0"] is Status.FAILED
    assert st["v ∈ L2"] is Status.FAILED and st["v → 0 (Barbalat)"] is not Status.EXACT


def test_theorem1_mutated_links_are_refuted():
    from lkverify.certify.steps.signals import LevelSet, SquareIntegrable

    links, _ = th1.argument(DEFAULTS)
    by = {type(link).__name__ + getattr(link, "signal", ""): k for k, link in enumerate(links)}
    # Γ in place of Γ⁻¹ in the level set: V ≠ ½zᵀQz
    lv = links[by["LevelSet"]]
    wrong_q = sympy.diag(eq.M, sympy.Matrix(DEFAULTS["Gamma"]))
    st = _decide([links[0], dataclasses.replace(lv, Q=wrong_q)])
    assert st[lv.name] is Status.FAILED
    # Lemma 3 as printed (‖e‖² in place of Λ²‖e‖²) gives a false identity at Λ = 2
    k = by["SquareIntegrablee"]
    printed = dataclasses.replace(links[k], K=sympy.eye(3))
    st = _decide(links[:k] + [printed] + links[k + 1:])
    assert st["e ∈ L2"] is Status.FAILED and st["e → 0 (Barbalat)"] is not Status.EXACT
    assert isinstance(printed, SquareIntegrable) and isinstance(lv, LevelSet)
    # a dropped term of V̇: the dissipation −vᵀ(K_d/2)v
    diss = dataclasses.replace(links[0], S=eq.Kd / 2)
    assert _decide([diss])[diss.name] is Status.FAILED


def test_theorem1_needs_distinct_k_and_a_bounded_reference():
    same = P.resolve({"k2": "1"}, use_defaults=True)                  # k1 = k2: {e = 0} is not finite
    links, _ = th1.argument(same)
    st = _decide(links, values=same)
    assert st["(s1, s2, s3) → a point of {e = 0} (finite)"] is Status.UNDECIDED
    rep = theorem1.run({"wd1": "t/10"})                               # an unbounded programmed motion
    assert rep.exit_code == 1 and rep.verdict.startswith("failed: hypotheses")
    rep = theorem1.run({"wd1": "t*sin(t)/10"})
    assert rep.exit_code == 1 and "undecided" in rep.verdict


def test_excitation_of_a_motion_it_cannot_certify_is_undecided_not_bad_input():
    v = P.resolve({"wd1": "sin(sqrt(2)*t)/2"}, use_defaults=True)      # an irrational frequency: valid input
    assert all(r.status is Status.UNDECIDED for r in excitation.run({"wd1": "sin(sqrt(2)*t)/2"}).results)
    assert all(pe.status is Status.UNDECIDED for pe in exc.excitation_bounds(v).values())


def _level_run(initial=None, values=None, t_end=8):
    mod = importlib.import_module("lkverify.proofs.zaremba1997.example")
    from lkverify.catalogue.examples import Example
    run = dataclasses.replace([r for r in mod.example.runs if r.label == mod.T2_LEVEL][0], history=initial or mod.LEVEL)
    ex = Example("level", runs=[run], t_end=t_end, series=[], distance=lambda st: np.zeros(len(st["omega"])),
                 claims=[mod.InLevelSet(mod.T2_LEVEL)], samples=401, step=mod.example.step)
    rep = ex.run(values or {})
    return [r for r in rep.results if r.name.startswith(mod.T2_LEVEL + ":")][0]


def test_simulation_stays_in_the_level_set_of_the_corrected_step():
    res = _level_run()
    assert res.status is Status.SIMULATED and res.value["V_end"] < res.value["V_start"] < res.value["V0"]
    assert res.value["omega_max"] <= res.value["W"]
    mod = importlib.import_module("lkverify.proofs.zaremba1997.example")
    outside = {**mod.LEVEL, "omega": list(np.array(mod.LEVEL["omega"]) + np.array([0.1, 0.0, 0.0]))}
    res = _level_run(outside)                                   # V(0) ≈ 0.07 > V0: the claim does not hold
    assert res.status is Status.FAILED and res.value["V_start"] > res.value["V0"]
    res = _level_run(values={"alpha": "40"})                    # below the derived threshold: no level set
    assert res.status is Status.FAILED and "no level set" in res.detail


def test_isolated_equilibrium_and_rates_check():
    assert th2.isolated_equilibrium(DEFAULTS).status is Status.EXACT              # det = −32
    same = P.resolve({"k2": "3"}, use_defaults=True)                              # k2 = k3: det = 0, not shown
    assert th2.isolated_equilibrium(same).status is Status.UNDECIDED

    class Stub:                                    # a loop whose v̇ would contain the gain Γ (DINV) or a non-polynomial
        def __init__(self, extra):
            self.extra = extra

        def plain(self, x):
            from lkverify.symbolic.polynomial import plain
            return plain(x)

        def rate(self, x):
            return self.extra

        def reference_bounded(self, x):
            return Status.EXACT, "bounded"

    from lkverify.symbolic.polynomial import plain
    w = plain(importlib.import_module("lkverify.proofs.zaremba1997.equations").omega(eq.t)[0])
    check = th2._rates_bounded(DEFAULTS)
    assert check(Stub(w ** 2 + 1)).status is Status.EXACT
    assert check(Stub(w * th2._DINV)).status is Status.FAILED and "DINV" in check(Stub(w * th2._DINV)).detail
    assert check(Stub(sympy.sin(w))).status is Status.UNDECIDED
