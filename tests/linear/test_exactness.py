"""One exactness policy (lkverify.status): a float input makes a linear result at most ``certified``.

A Python float delay (6.17), float matrix entries or a NumPy float array are taken at their
exact binary value, but a float may have been rounded before lkverify saw it: the result is
never ``exact``.  The same systems written exactly (text "0.9", rationals) stay ``exact``.
"""

import json

import numpy as np
import pytest
import sympy

from lkverify.cli import main
from lkverify.linear import (LinearDelaySystem, certified_interval, certify_cover, certify_delay, certify_interval,
                             check_certificate, linear_report)
from lkverify.linear.hierarchy import LmiCertificate
from lkverify.status import Status

CLASSIC_EXACT = dict(A=[[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])


def classic(**kw):
    return LinearDelaySystem(CLASSIC_EXACT["A"], Ad=CLASSIC_EXACT["Ad"], **kw)


def classic_floats():
    return LinearDelaySystem(np.array([[-2.0, 0.0], [0.0, -0.9]]), Ad=np.array([[-1.0, 0.0], [-1.0, -1.0]]))


def test_float_inputs_are_flagged_and_exact_inputs_are_not():
    assert classic_floats().from_float
    assert LinearDelaySystem([[-2, 0], [0, -0.9]], Ad=[[-1, 0], [-1, -1]]).from_float       # one Python float
    assert LinearDelaySystem([[sympy.Float("-0.9")]]).from_float                           # a SymPy Float
    assert not classic().from_float
    assert not LinearDelaySystem([[sympy.Rational(-9, 10)]], Ad=np.array([[1, 0], [0, 1]])[:1, :1]).from_float


def test_float_delay_6_17_is_certified_not_exact():
    sys = classic()
    exact = certify_delay(sys, "6.17", order=3)
    floated = certify_delay(sys, 6.17, order=3)
    assert exact.status is Status.EXACT
    assert floated.status is Status.CERTIFIED and "float" in floated.detail
    assert floated.h == sympy.Rational(*(6.17).as_integer_ratio())        # the binary value, not 617/100


def test_float_matrices_are_certified_not_exact():
    assert certify_delay(classic(), 4, order=0).status is Status.EXACT
    res = certify_delay(classic_floats(), 4, order=0)
    assert res.status is Status.CERTIFIED and "float" in res.detail
    m = certified_interval(classic_floats(), (0, 6.17258), order=0)
    assert m.status is Status.CERTIFIED


def test_check_certificate_with_a_float_delay_or_float_certificate():
    sys = LinearDelaySystem([[-1]], Ad=[[0]])
    one = sympy.eye(1)
    cert = LmiCertificate(0, one, one / 10, one / 10)
    assert check_certificate(sys, 1, cert).status is Status.EXACT
    assert check_certificate(sys, 1.0, cert).status is Status.CERTIFIED
    floated = LmiCertificate(0, sympy.Matrix([[sympy.Float(1.0)]]), one / 10, one / 10)
    assert check_certificate(sys, 1, floated).status is Status.CERTIFIED
    # a refutation stays a refutation
    assert check_certificate(sys, 1.0, LmiCertificate(0, -one, one, one)).status is Status.FAILED


def test_certify_interval_and_cover_with_floats():
    sys = LinearDelaySystem([[-1]], Ad=[["0.5"]])
    assert certify_interval(sys, ("0.1", "10"), order=0).status is Status.EXACT
    assert certify_interval(sys, (0.1, 10), order=0).status is Status.CERTIFIED
    floated = LinearDelaySystem([[-1.0]], Ad=[[0.5]])
    assert certify_interval(floated, ("0.1", "10"), order=0).status is Status.CERTIFIED
    assert all(p.status is Status.CERTIFIED for p in certify_cover(sys, (0.1, 10), order=0))


def test_linear_report_from_python_never_exact_with_floats():
    rep = linear_report({"A": [[-2.0, 0.0], [0.0, -0.9]], "Ad": [[-1.0, 0.0], [-1.0, -1.0]]}, orders=(0,), h=4,
                        h_max=8)
    assert Status.EXACT not in [r.status for r in rep.results]
    assert any(r.status is Status.CERTIFIED for r in rep.results)
    rep = linear_report(CLASSIC_EXACT, orders=(0,), h=6.17 / 1.5, h_max=8)    # a float delay
    assert Status.EXACT not in [r.status for r in rep.results]
    rep = linear_report(CLASSIC_EXACT, orders=(0,), h="4", h_max=8)
    assert Status.EXACT in [r.status for r in rep.results]


def _statuses(capsys, *args):
    code = main(["linear", *args, "--json", "--quiet"])
    data = json.loads(capsys.readouterr().out)
    return code, {r["name"]: r["status"] for r in data["results"]}


def test_cli_text_is_exact_decimal_an_irrational_entry_is_certified(capsys):
    # on the command line 6.17 is the decimal 617/100 (lkverify.status, rule 2): exact
    code, st = _statuses(capsys, "--set", "A=[[-2,0],[0,-0.9]]", "--set", "Ad=[[-1,0],[-1,-1]]", "--orders", "3",
                         "--h", "6.17", "--h-max", "8")
    assert code == 0 and st["bessel-legendre N=3 at h = 617/100"] == "exact"
    # an irrational entry goes through enclosures: never exact
    code, st = _statuses(capsys, "--set", "A=[[-2,0],[0,-sqrt(2)/2]]", "--set", "Ad=[[-1,0],[-1,-1]]", "--orders",
                         "0", "--h", "1", "--h-max", "4")
    assert "exact" not in st.values() and st["jensen at h = 1"] == "certified"


def test_linear_family_and_linearisation_carry_float_values():
    from lkverify import Equation, Parameters, System, Term, Vector, t
    from lkverify.linear import linear_family, linearise_at

    P = Parameters()
    a = P.scalar("a", default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    sys = System([Equation(x, [Term(-x(t)[0] - a * x(t - tau)[0])])], parameters=P, name="toy")
    fam = linear_family(sys, {"x": [0]}, grid=("a",))
    assert not fam.at({"a": sympy.Rational(1, 2)}).from_float
    assert fam.at({"a": 0.5}).from_float
    assert certify_delay(fam.at({"a": 0.5}), 1, order=0).status is Status.CERTIFIED
    assert certify_delay(fam.at({"a": sympy.Rational(1, 2)}), 1, order=0).status is Status.EXACT
    assert linearise_at(sys, {"x": [0]}, {"a": 0.5}).system.from_float
    assert not linearise_at(sys, {"x": [0]}, {"a": "1/2"}).system.from_float
    fam_f = linear_family(sys, {"x": [0]}, {"tau": 1.5}, grid=("a",))
    assert fam_f.from_float and fam_f.at({"a": 1}).from_float
