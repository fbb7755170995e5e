"""Stability for every delay (issue 27, item 5): decided exactly, certified by V = xᵀPx + ∫xᵀQx.

Known answers: for ẋ = a x + b x(t−h) the crossing frequency solves ω² = b² − a², so with
a + b < 0 the system is stable for every delay iff |b| ≤ −a (Hayes); a = b < 0 is stable for
every delay but no delay-independent LMI certificate exists (the scaled small-gain LMI needs
|b| < −a).  Every exact decision is cross-checked against the spectral route (estimated) or a
certified right half-plane root.
"""

import json
import random

import sympy

from lkverify.cli import main
from lkverify.linear import (IndependentCertificate, LinearDelaySystem, check_independent_certificate,
                             delay_independence, linear_report, refute_stability, spectral_abscissa)
from lkverify.linear.independent import count_positive_roots

ACCEPT = ["--set", "A=[[-2]]", "--set", "Ad=[[1]]"]
TWO_STATE = {"A": [[-3, 1], [0, -2]], "Ad": [[1, 0], ["1/2", "1/2"]]}


def _system(values):
    return LinearDelaySystem(values["A"], Ad=values.get("Ad"))


def _cert_from_json(row):
    P = sympy.Matrix([[sympy.Rational(e) for e in r] for r in row["value"]["P"]])
    Q = sympy.Matrix([[sympy.Rational(e) for e in r] for r in row["value"]["Q"]])
    return IndependentCertificate(P, Q)


# ------------------------------------------------------------------ the acceptance case, through the CLI
def test_cli_acceptance_text_says_stable_for_every_delay_no_finite_margin(capsys):
    code = main(["linear", *ACCEPT, "--quiet"])
    text = " ".join(capsys.readouterr().out.split())   # the table wraps its cells: read the words
    assert code == 0
    assert "stable for every delay h ≥ 0" in text and "delay margin infinite" in text
    assert "delay margin 20" not in text and "19.99" not in text and "certified delays" not in text
    assert "P and Q verified exactly (exact)" in text   # the certificate row wraps: the verdict names it


def test_cli_acceptance_json_carries_the_exact_certificate_and_an_infinite_margin(capsys):
    code = main(["linear", *ACCEPT, "--json", "--quiet"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    rows = {r["name"]: r for r in data["results"]}
    assert set(rows) == {"stable for every delay h ≥ 0", "delay-independent LK certificate"}
    every = rows["stable for every delay h ≥ 0"]
    assert every["status"] == "exact" and every["value"]["margin_infinite"] is True
    assert every["value"]["delay_margin"] == "infinite" and every["value"]["positive_crossing_frequencies"] == 0
    cert = rows["delay-independent LK certificate"]
    assert cert["status"] == "exact" and cert["value"]["certified"] is True
    assert all("/" in e or e.lstrip("-").isdigit() for M in ("P", "Q") for r in cert["value"][M] for e in r)
    # the printed strings are the certificate: parsed back, they verify exactly
    res = check_independent_certificate(_system({"A": [[-2]], "Ad": [[1]]}), _cert_from_json(cert))
    assert res.status.value == "exact" and [p.status.value for p in res.parts] == ["exact"] * 3
    assert "20" not in data["verdict"] and "infinite" in data["verdict"]


# ------------------------------------------------------------------ a 2-state case, with reference paths
def test_two_state_delay_independent_is_exact_and_certified():
    sys = _system(TWO_STATE)
    di = delay_independence(sys)
    assert di.applies and di.stable and di.status.value == "exact" and di.margin == float("inf")
    assert di.margin_infinite and di.certified and di.check.status.value == "exact"
    assert di.certificate.P.shape == (2, 2) and all(e.is_Rational for e in di.certificate.P)
    for h in (0.5, 5.0, 50.0):                          # the spectral route (estimated) agrees
        assert spectral_abscissa(sys, h) < 0
    rep = linear_report(TWO_STATE)
    assert rep.exit_code == 0 and [r.status.value for r in rep.results] == ["exact", "exact"]


def test_a_float_input_is_at_most_certified():
    di = delay_independence(LinearDelaySystem([[-2.0]], Ad=[[1.0]]))
    assert di.stable and di.status.value == "certified" and di.check.status.value == "certified"


# ------------------------------------------------------------------ mutations that are not delay-independent
def test_ad_3_has_a_crossing_and_keeps_todays_analysis():
    sys = _system({"A": [[-2]], "Ad": [[3]]})
    di = delay_independence(sys)
    assert not di.applies and di.stable is None and di.positive_roots == 1 and di.status.value == "undecided"
    rep = linear_report({"A": [[-2]], "Ad": [[3]]}, orders=(0,), h_max=5)
    names = [r.name for r in rep.results]
    assert "stable for every delay h ≥ 0" not in names and "stability intervals (spectral)" in names
    assert "infinite" not in rep.verdict and rep.exit_code == 1


def test_the_classic_crossing_example_is_untouched():
    di = delay_independence(LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]]))
    assert not di.applies and di.positive_roots == 1


def test_boundary_ad_2_is_stable_for_no_delay():
    """ẋ = −2x + 2x(t−h): A + A_d = 0, so λ = 0 is a root for every h — never asymptotically stable."""
    values = {"A": [[-2]], "Ad": [[2]]}
    sys = _system(values)
    di = delay_independence(sys)
    assert di.applies and di.stable is False and di.status.value == "failed" and not di.margin_infinite
    assert "λ = 0 is a characteristic root for every h" in di.detail
    h, lam = sympy.symbols("h lam")
    assert sympy.simplify((lam + 2 - 2 * sympy.exp(-lam * h)).subs(lam, 0)) == 0
    assert spectral_abscissa(sys, 1.0) > -1e-6           # the rightmost root sits at 0
    rep = linear_report(values)
    assert rep.exit_code == 1 and rep.results[0].status.value == "failed" and "no delay" in rep.verdict


def test_a_plus_ad_not_hurwitz_is_unstable_for_every_delay():
    values = {"A": [[1]], "Ad": [["-1/2"]]}             # no crossing; A + A_d = 1/2 > 0
    sys = _system(values)
    di = delay_independence(sys)
    assert di.applies and di.stable is False and di.status.value == "failed"
    assert di.detail.startswith("unstable for every delay h ≥ 0")
    for h in ("1/10", "3", "30"):                        # a right half-plane root certified at each delay
        assert refute_stability(sys, h).refuted
    rep = linear_report(values)
    assert rep.exit_code == 1 and rep.verdict.startswith("unstable for every delay h ≥ 0")


def test_two_state_unstable_for_every_delay():
    values = {"A": [[1, 0], [0, -3]], "Ad": [["-1/2", 0], [0, 1]]}   # two decoupled scalar systems
    di = delay_independence(_system(values))
    assert di.applies and di.stable is False and not di.hurwitz


def test_stable_for_every_delay_without_an_lk_certificate():
    """ẋ = −x − x(t−h): stable for every h, but [[−2p + q, −p], [−p, −q]] ≺ 0 has no solution."""
    values = {"A": [[-1]], "Ad": [[-1]]}
    di = delay_independence(_system(values))
    assert di.stable and di.status.value == "exact" and not di.certified
    for h in (1.0, 10.0):
        assert spectral_abscissa(_system(values), h) < 0
    rep = linear_report(values)
    rows = {r.name: r for r in rep.results}
    assert rows["stable for every delay h ≥ 0"].status.value == "exact"
    assert rows["delay-independent LK certificate"].status.value == "undecided"
    assert "no delay-independent LK certificate found" in rep.verdict and rep.exit_code == 1


def test_a_distributed_term_falls_back():
    di = delay_independence(LinearDelaySystem([[-1]], Ad=[["1/2"]], kernel=[[["-1/10"]]]))
    assert not di.applies and "distributed" in di.detail


# ------------------------------------------------------------------ the exact check rejects tampering
def test_a_tampered_certificate_is_rejected():
    sys = _system(TWO_STATE)
    good = delay_independence(sys).certificate
    assert check_independent_certificate(sys, good).status.value == "exact"
    P = good.P.copy()
    P[0, 1] = P[1, 0] = P[0, 1] + 10 * good.P[0, 0]     # P may stay positive definite: the LMI must fail
    bad = check_independent_certificate(sys, IndependentCertificate(P, good.Q))
    assert bad.status.value == "failed" and bad.witness is not None
    assert [p.status.value for p in bad.parts][2] == "failed"
    negative = check_independent_certificate(sys, IndependentCertificate(-good.P, good.Q))
    assert negative.status.value == "failed" and negative.parts[0].status.value == "failed"


# ------------------------------------------------------------------ exact decisions against the spectral route
def test_count_positive_roots_against_numpy():
    w = sympy.Symbol("omega")
    rng = random.Random(5)
    for _ in range(40):
        roots = [sympy.Rational(rng.randint(-9, 9), rng.randint(1, 4)) for _ in range(rng.randint(1, 5))]
        P = sympy.Poly(sympy.prod([w - r for r in roots]) * (w ** 2 + rng.randint(1, 5)) * w ** rng.randint(0, 2), w)
        assert count_positive_roots(P) == len({r for r in roots if r > 0})


def test_scalar_decisions_against_the_known_answer_and_the_spectrum():
    rng = random.Random(27)
    for _ in range(25):
        a, b = (sympy.Rational(rng.randint(-12, 12), rng.randint(1, 3)) for _ in range(2))
        sys = LinearDelaySystem([[a]], Ad=[[b]])
        di = delay_independence(sys, certify=False)
        if b != 0 and b * b > a * a:                     # a crossing frequency √(b² − a²)
            assert not di.applies, (a, b)
            continue
        assert di.applies, (a, b)
        assert di.stable == (a + b < 0), (a, b)          # Hayes: |b| ≤ −a and a + b < 0
        if di.stable:
            assert all(spectral_abscissa(sys, h) < 0 for h in (0.3, 3.0)), (a, b)
        elif a + b > 0:
            assert refute_stability(sys, "2").refuted, (a, b)
