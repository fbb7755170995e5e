"""Paper 003 (somov): the catalogued claims hold, mutations are refuted, true claims written differently pass."""

import importlib

import numpy as np
import pytest
import sympy

from lkverify import Status

equations = importlib.import_module("lkverify.proofs.somov.equations")
kin = importlib.import_module("lkverify.proofs.somov.kinematics")
lin = importlib.import_module("lkverify.proofs.somov.linearisation")
sat = importlib.import_module("lkverify.proofs.somov.saturation")
comp = importlib.import_module("lkverify.proofs.somov.comparison")
reg = importlib.import_module("lkverify.proofs.somov.region")
ids = importlib.import_module("lkverify.proofs.somov.identities")
ns = importlib.import_module("lkverify.proofs.somov.norm_steps")

DEFAULTS = equations.P.resolve({})


def _status(rows):
    return {r.name: r.status for r in rows}


# -- kinematics ---------------------------------------------------------------------------------
def test_kinematics_identities_exact():
    rows = kin.kinematics_results()
    assert all(r.status is Status.EXACT for r in rows), [r.detail for r in rows]


def test_wrong_sign_in_B_refuted_by_the_quaternion_equation():
    rows = _status(kin.kinematics_results(lambda s: equations.B(s, sign=-1)))
    assert rows["(6) from (1)"] is Status.FAILED and rows["(3) = (6)"] is Status.FAILED
    # the transposed B is still orthogonal up to (1+σ²): only the derivation from (1) catches the sign
    assert rows["B^T B = (1+|sigma|^2)^2 I"] is Status.EXACT


def test_B_written_differently_passes():
    def B_vec(s):  # (1 − σ²)I + 2[σ×] + 2σσᵀ assembled column by column from its action on e_k
        s = sympy.Matrix(s)
        cols = [(1 - (s.T * s)[0]) * e + 2 * s.cross(e) + 2 * s * (s.T * e)[0] for e in sympy.eye(3).columnspace()]
        return sympy.Matrix.hstack(*cols)
    assert all(r.status is Status.EXACT for r in kin.kinematics_results(B_vec))


def test_kinematics_item_and_initial_attitude():
    rep = kin.kinematics.run({})
    assert rep.exit_code == 0
    init = next(r for r in rep.results if r.name == "initial MRP sigma0")
    assert init.value["norm"] == pytest.approx(np.tan(np.radians(150) / 4))
    rep = kin.kinematics.run({"Phi0_deg": "300"})      # the long way round: |σ0| > 1, shadow suggested
    init = next(r for r in rep.results if r.name == "initial MRP sigma0")
    assert init.value["norm"] > 1 and not init.value["short_rotation"] and "shadow" in init.detail


# -- linearisation ------------------------------------------------------------------------------
@pytest.mark.slow
def test_linearisation_exact_and_findings():
    rep = lin.linearisation.run({})
    st = _status(rep.results)
    assert st["(8),(9) along (3)"] is Status.EXACT and st["(10): sigma'' = v"] is Status.EXACT
    assert st["(9) a = -B Ddot sigmadot/4"] is Status.EXACT and st["spectrum of each channel"] is Status.EXACT
    # the extracted (8), (10) without ¼ and 4: findings, σ̈ − v = −¾(v − a)
    assert st["printed (8) as extracted"] is Status.FAILED
    r10 = next(r for r in rep.results if r.name.startswith("printed (10)"))
    assert r10.status is Status.FAILED and "-3*(-a1 + v1)/4" in r10.value["differences"]["(1, 1)"]
    assert rep.exit_code == 1


@pytest.mark.parametrize("factor", [2, 8, -4])
def test_wrong_factor_in_10_refuted(factor):
    law = lambda s, v, a: factor * lin._inverse(equations.B(s)) * (v - a)
    assert lin.closes_loop(law, label="mutant").status is Status.FAILED


def test_law_10_written_with_D_passes():
    assert lin.closes_loop(lambda s, v, a: equations.D(s) * (v - a), label="u = D(v − a)").status is Status.EXACT


def test_spectrum_follows_set_values():
    spec = lin._modal(equations.P.resolve({"alpha": "1/2", "beta": "3"}))
    assert spec.status is Status.EXACT and spec.value["k0"] == sympy.Rational(37, 4) and spec.value["k1"] == 1


# -- saturation ---------------------------------------------------------------------------------
def test_SC_proved():
    rows = sat.saturation_results(equations.SC, sympy.Rational(1, 100))
    assert [r.status for r in rows] == [Status.EXACT] * 4


def test_componentwise_clip_does_not_keep_the_direction():
    clip = lambda x, am: x.applyfunc(lambda v: sympy.Max(-am, sympy.Min(am, v)))
    rows = _status(sat.saturation_results(clip, 1))
    assert rows == {"SC: direction (witness)": Status.FAILED}


def test_saturations_that_are_not_SC_refuted():
    always = lambda x, am: x * am / max(abs(v) for v in x) if any(x) else x       # scales small x up
    assert _status(sat.saturation_results(always, 1))["SC: inactive (witness)"] is Status.FAILED
    forgets_am = lambda x, am: x / sympy.Max(1, *[abs(v) for v in x])             # bound 1, not a_m
    assert _status(sat.saturation_results(forgets_am, sympy.Rational(1, 100)))["SC: bound (witness)"] is Status.FAILED


def test_SC_written_with_min_passes():
    def sc_min(x, am):
        q = sympy.Max(*[sympy.Abs(v) for v in x])
        return x * sympy.Min(1, am / q) if any(v != 0 for v in x) else x
    rows = sat.saturation_results(sc_min, 2)
    assert all(r.status is Status.EXACT for r in rows), [r.detail for r in rows]


# -- vector Lyapunov function, comparison system ------------------------------------------------
def test_comparison_rows():
    rep = comp.comparison.run({})
    st = _status(rep.results)
    assert all(s is Status.EXACT for n, s in st.items() if n not in ("text: x2 = omega/4", "comparison system (sampled)"))
    assert st["text: x2 = omega/4"] is Status.FAILED      # finding: x₂ = σ̇ = ¼Bω ≠ ω/4 away from σ = 0
    # every norm step is a checked inequality: the comparison system is exact; the sampled cross-check stays
    assert st["comparison system"] is Status.EXACT
    assert st["comparison system (sampled)"] is Status.ESTIMATED
    assert rep.exit_code == 1


# -- the norm steps of the comparison system as checked inequalities ------------------------------
def _T(v):
    return comp.jordan_transform(v)[0]


def test_norm_steps_exact_at_two_instances():
    for v in (DEFAULTS, equations.P.resolve({"alpha": "2", "beta": "1/3", "a_m": "1/7"})):
        steps = ns.norm_steps(v, _T(v))
        assert len(steps) == 21 and all(r.status is Status.EXACT for r in steps), [r.detail for r in steps
                                                                                    if r.status is not Status.EXACT]
        assert ns.chain_status(steps) == (Status.EXACT, [])


def _refuted(row):
    assert row.status is Status.FAILED, row.detail
    assert row.value["witness"], row.detail
    return row


def test_norm_steps_dropped_sqrt3_refuted():
    rows = {r.name: r for r in ns._rows_saturation(DEFAULTS, root3=1)}
    _refuted(rows["|u|_2 <= sqrt(3) |u|_inf"])          # ‖u‖₂ ≤ ‖u‖_∞ is false at u = (1, 1, 1)
    _refuted(rows["sum V_i <= sqrt(3) ||V||"])           # ΣVᵢ ≤ ‖V‖ is false at V = (1, 1, 1)


def test_norm_steps_wrong_power_refuted():
    K0 = ns._val(equations.k0, DEFAULTS)
    rows = {r.name: r for r in ns._rows_channel(DEFAULTS, _T(DEFAULTS), K={"sigma": 1, "sigmadot": K0, "v": K0})}
    _refuted(rows["|sigmadot_i| <= sqrt(k0) V_i"])       # k0 in place of √k0
    _refuted(ns._rows_a(DEFAULTS, cube=4)[1])             # 2k0r²(1 + 3r²) in place of 2k0r²(1 + 3r)


def test_norm_steps_saturation_with_a_m_over_2_refuted():
    rows = {r.name: r for r in ns._rows_saturation(DEFAULTS, quarter=sympy.Rational(1, 2))}
    row = _refuted(rows["|v - a| - a_m(1+s^2)/4 <= |v| + |a| - a_m/4"])
    assert row.value["witness"]["s"] == "0"


def test_inequality_step_true_claims_written_differently_pass():
    m, n = sympy.symbols("m n", nonnegative=True)
    am = sympy.Rational(1, 100)
    # the saturation step without √3 also holds: (1 − c)n ≤ n − a_m (times m: a_m(n − m) ≥ 0)
    hs = [n - m, m - am]
    assert ns.inequality_step("sharper", m * (n - am) - (m - am) * n, [(am, [hs[0]], 1)], hyps=hs,
                              text="").status is Status.EXACT
    # a weaker constant than needed (|σᵢ| ≤ 2Vᵢ) passes with the same form of certificate
    rows = {r.name: r for r in ns._rows_channel(DEFAULTS, _T(DEFAULTS), K={"sigma": 2, "sigmadot": 1, "v": 1})}
    assert all(r.status is Status.EXACT for r in rows.values())
    # a true claim with a certificate that does not match is undecided, not refuted
    x = sympy.Symbol("x", real=True)
    assert ns.inequality_step("x", x ** 2 + 1, [(1, [], x)], text="").status is Status.UNDECIDED


def test_region_exact_only_when_every_step_is(monkeypatch):
    good = comp.majorant_steps(DEFAULTS)
    for mutated, expected in ((ns._rows_saturation(DEFAULTS, root3=1)[1], Status.FAILED),
                              (ns.inequality_step("unproved", sympy.Symbol("x", real=True) ** 2 + 1, [], text=""),
                               Status.UNDECIDED)):
        steps = good + [mutated]
        assert comp.comparison_row(DEFAULTS, steps).status is expected
        monkeypatch.setattr(reg, "majorant_steps", lambda v, steps=steps: steps)
        st = _status(reg.region.run({}).results)
        assert st["initial data in the region"] is expected
        assert st["rho* (comparison system)"] is Status.EXACT


def test_majorant_holds_at_random_states():
    res = comp.sampled_majorant(DEFAULTS, n=1500)
    assert res.status is Status.ESTIMATED and res.value["worst_relative_excess"] < 0


def test_linear_channel_is_V_dot_equals_A_V_at_other_spectrum():
    v = equations.P.resolve({"alpha": "2", "beta": "1/3"})
    rows = _status(comp._linear_rows(v))
    assert all(s is Status.EXACT for s in rows.values())


def test_wrong_jordan_block_refuted():
    T, Ac = comp.jordan_transform(DEFAULTS)
    al, be = DEFAULTS["alpha"], DEFAULTS["beta"]
    assert ids.matrix_identity("x", T.inv() * Ac * T, sympy.Matrix([[-al, -be], [be, -al]]), text="").status \
        is Status.FAILED


# -- region ---------------------------------------------------------------------------------------
def test_region_exact_and_consistent():
    rows = reg.region.run({}).results
    st = _status(rows)
    # r0, ρ* exact; the initial-data region rests on the comparison system, whose steps are all checked: exact
    assert all(s is Status.EXACT for s in st.values()), st
    R = reg.certified_region(DEFAULTS)
    # ψ(ρ*) = 0, g(r0) = 0 (numerically, at 30 digits) and 0 < r0 < ρ*
    r, g, psi = comp.majorant(DEFAULTS)
    assert abs(float(sympy.N(psi.subs(r, R.rho), 30))) < 1e-25 and abs(float(sympy.N(g.subs(r, R.r0), 30))) < 1e-25
    assert 0 < float(R.r0) < float(R.rho)
    assert float(R.s_max) == pytest.approx(float(R.rho) / np.sqrt(2))


def test_region_too_large_refuted():
    R = reg.certified_region(DEFAULTS)
    assert reg.check_radius(DEFAULTS, "1/10").status is Status.EXACT
    bad = reg.check_radius(DEFAULTS, sympy.Rational(12, 100))
    assert bad.status is Status.FAILED and sympy.Rational(bad.value["witness"]) > R.rho


def test_region_grows_with_a_m():
    small = reg.certified_region(DEFAULTS)
    large = reg.certified_region(equations.P.resolve({"a_m": "1/10"}))
    assert float(large.rho) > float(small.rho)


def test_region_contains_and_boundary():
    R = reg.certified_region(DEFAULTS)
    s = np.linspace(0, float(R.s_max) * 0.999, 7)
    wb = R.w_boundary(s)
    assert R.contains(s, 0.999 * wb).all() and not R.contains(s, 1.01 * wb + 1e-9).any()


def test_grid_rows_detect_a_region_too_large():
    R = reg.certified_region(DEFAULTS)
    big = reg.CertifiedRegion(R.r0, R.rho * 100, R.Q)
    grid = importlib.import_module("lkverify.proofs.somov.grid").GridRuns(
        np.linspace(0, 1, 3), np.linspace(0, 0.3, 3), np.array([[1, 1, 0], [1, 1, 0], [1, 0, 0]], np.int8), 300.0,
        1e-8, 1e-10, 4)
    rows = _status(reg.grid_rows(big, grid))
    assert rows["region inside the converged grid"] is Status.FAILED
    assert _status(reg.grid_rows(R, grid))["region inside the converged grid"] is Status.SIMULATED


def test_region_against_simulated_grid():
    job = reg.RegionConstants(n_s=6, n_w=6)
    rep, extra = job.run("somov.region", DEFAULTS, {})
    st = _status(rep.results)
    assert st["region inside the converged grid"] is Status.SIMULATED
    assert st["region boundary converges"] is Status.SIMULATED


@pytest.mark.slow
def test_example_runs():
    ex = importlib.import_module("lkverify.proofs.somov.example").example
    rep = ex.run()
    assert rep.exit_code == 0, rep.as_text()


def test_region_is_a_theorem_established_by_the_comparison_lemma(monkeypatch):
    rep = reg.region.run({})
    assert rep.exit_code == 0 and rep.verdict.startswith("established")
    assert any(link.name.startswith("comparison lemma") and link.status is Status.EXACT for link in rep.chain)
    bad = comp.majorant_steps(DEFAULTS) + [ns._rows_saturation(DEFAULTS, root3=1)[1]]  # a refuted norm step
    monkeypatch.setattr(reg, "majorant_steps", lambda v: bad)
    rep = reg.region.run({})
    assert rep.exit_code == 1 and not rep.verdict.startswith("established")
    lemma = next(link for link in rep.chain if link.name.startswith("comparison lemma"))
    assert lemma.status is Status.FAILED


def test_comparison_link_refutes_a_radius_beyond_rho_star():
    from lkverify.certify.steps import Comparison

    R = reg.certified_region(DEFAULTS)
    r, g, _ = comp.majorant(DEFAULTS)
    phi = -DEFAULTS["alpha"] * r + 3 * sympy.Max(0, g) / DEFAULTS["beta"]
    ok = (("comparison system", Status.EXACT),)
    assert Comparison(phi, r, R.rho, ok).decide().status is Status.EXACT
    assert Comparison(phi, r, R.rho + sympy.Rational(1, 10 ** 6), ok).decide().status is Status.FAILED
