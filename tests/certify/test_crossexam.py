"""Every proved term bound is cross-examined by a cheap witness search (issue 22, point 3).

A rule that claims a false bound as exact is a bug of lkverify: the check raises
RuleSoundnessError (an InternalError, exit 3 on the command line) naming the rule and the
witness, and never returns a row that says ``exact``.  Sound proved steps pass untouched.
"""

import dataclasses

import pytest
import sympy

from lkverify import (Equation, Functional, Parameters, System, Term, Vector, memory_integral, norm_power, t,
                      window_integral, xi)
from lkverify.certify.steps import Rayleigh, Region, TermBound, TermwiseBound, norm_measure
from lkverify.certify.steps.measures import window_integral_measure
from lkverify.certify.steps.memory import memory_measure
from lkverify.certify.steps.rules import Application, Condition, Rule
from lkverify.errors import InternalError, RuleSoundnessError
from lkverify.status import Status

R = sympy.Rational
P = Parameters()
x = Vector("x", 2)
n = norm_measure("n", x(t))
N = n.symbol
SYS = System([Equation(x, [Term(-x(t))])], parameters=P)
M = sympy.Matrix([[2, 1], [1, 2]])                     # eigenvalues 1 and 3
QUAD = (x(t).T * M * x(t))[0]
V = Functional([Term(QUAD, text="xᵀMx")])


@dataclasses.dataclass(frozen=True)
class Liar(Rule):
    """An unsound rule: it claims ``bound`` with one 'exact' side condition that checks nothing."""

    bound: object = None
    name = "the liar's rule"

    def apply(self, term, direction, ctx):
        return Application(self.name, self.bound, (Condition("trust me", Status.EXACT, ""),))


def step(bound, rule, relation="<=", **kw):
    return TermwiseBound("V ≤ U", V, SYS, "V", [TermBound("xᵀMx", bound, rule)], bound, [n], relation=relation, **kw)


def test_an_unsound_rule_claiming_a_false_upper_bound_is_an_internal_error():
    with pytest.raises(RuleSoundnessError) as info:
        step(2 * N ** 2, Liar(2 * N ** 2)).check(P.resolve({}))     # xᵀMx ≤ 2‖x‖² is false (λ_max = 3)
    exc = info.value
    assert isinstance(exc, InternalError)
    assert exc.rule == "the liar's rule" and exc.witness is not None and exc.witness.violation[0] > 0
    text = str(exc)
    assert "\n" not in text and "the liar's rule" in text and "x(t) = (" in text and "> 0" in text


def test_an_unsound_rule_claiming_a_false_lower_bound_is_an_internal_error():
    with pytest.raises(RuleSoundnessError, match="the liar's rule"):
        step(2 * N ** 2, Liar(2 * N ** 2), relation=">=").check(P.resolve({}))   # λ_min = 1 < 2


def test_an_unsound_rule_a_hair_off_is_caught_at_the_eigenvector():
    bound = (3 - R(1, 10 ** 9)) * N ** 2
    with pytest.raises(RuleSoundnessError, match="the liar's rule"):
        step(bound, Liar(bound)).check(P.resolve({}))


def test_an_unsound_rule_on_a_window_term_is_caught():
    tau = 1
    I = window_integral_measure("I", x(xi), p=2, window=tau)
    term = window_integral(x(xi).dot(x(xi)) * (xi - t + 2), tau)            # weight from 1 to 2
    bound = R(3, 2) * I.symbol                                               # needs 2
    W = Functional([Term(term, text="∫g‖x‖²")])
    s = TermwiseBound("V ≤ U", W, SYS, "V", [TermBound("∫g‖x‖²", bound, Liar(bound))], bound, [n, I])
    with pytest.raises(RuleSoundnessError, match="the liar's rule"):
        s.check(P.resolve({}))


def test_an_unsound_rule_on_a_memory_term_is_caught():
    Q = memory_measure("Q", x(xi), p=2, kernel=lambda u: sympy.exp(-2 * u))    # ∫_0^t e^{−2(t−ξ)}‖x‖² dξ
    term = 3 * memory_integral(sympy.exp(-2 * (t - xi)) * norm_power(x(xi), 2))
    W = Functional([Term(term, text="3∫e^{−2(t−ξ)}‖x‖²")])
    for bound, caught in [((3 - R(1, 10 ** 6)) * Q.symbol, True), (3 * Q.symbol, False)]:   # 3Q is the truth
        s = TermwiseBound("V ≤ U", W, SYS, "V", [TermBound("3∫e^{−2(t−ξ)}‖x‖²", bound, Liar(bound))], bound, [n, Q])
        if caught:
            with pytest.raises(RuleSoundnessError, match="the liar's rule"):
                s.check(P.resolve({}))
        else:
            assert s.check(P.resolve({})).status is Status.EXACT


def test_the_liar_telling_the_truth_is_not_an_error():
    res = step(3 * N ** 2, Liar(3 * N ** 2)).check(P.resolve({}))
    assert res.status is Status.EXACT


def test_a_sound_proved_step_is_untouched():
    tb = Rayleigh(x(t), M, eigenvalue=3, norm_squared=N ** 2)
    res = step(3 * N ** 2, tb).check(P.resolve({}))
    assert res.status is Status.EXACT and res.terms[0].status is Status.EXACT
    low = step(N ** 2, Rayleigh(x(t), M, eigenvalue=1, norm_squared=N ** 2), relation=">=").check(P.resolve({}))
    assert low.status is Status.EXACT


def test_a_sound_step_on_a_region_is_untouched():
    region = Region({n: R(1, 10)})
    res = step(3 * N ** 2, Rayleigh(x(t), M, eigenvalue=3, norm_squared=N ** 2), region=region).check(P.resolve({}))
    assert res.status is Status.EXACT


def test_cross_examination_can_be_switched_off():
    res = step(2 * N ** 2, Liar(2 * N ** 2), cross_examine=False).check(P.resolve({}))
    assert res.status is Status.EXACT          # what the liar says, unexamined: only for experiments


def test_the_command_line_maps_the_error_to_exit_3(monkeypatch, capsys):
    from lkverify import cli

    def boom(args):
        raise RuleSoundnessError("the rule 'R' proved x ≤ 0 (exact), but the witness x = 1 refutes it", rule="R")

    monkeypatch.setattr(cli, "_dispatch", boom)
    assert cli.main(["list"]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "RuleSoundnessError" in err and "the rule 'R'" in err


def _paper002_lam_c9_step(constant):
    """Paper 002 Theorem 1's term −λq̇ᵀ∂Π/∂q ≤ κ‖q̇‖‖q‖³ at λ = 10, 'proved' by the liar with κ = constant."""
    import importlib

    T = importlib.import_module("lkverify.proofs.aleksandrov2023.theorem1_bound")
    label = "−λq̇ᵀ∂Π/∂q"
    bound = constant * T.W_.symbol * T.E_.symbol ** 3
    step = T.vdot.with_bounds(bounds=[TermBound(label, bound, Liar(bound))], rhs=bound, part=(label,))
    return step, T.P3.resolve(T.CHECK_VALUES, use_defaults=True)


def test_the_halved_direction_domain_of_issue_22_would_have_been_caught():
    # the Template defect certified λc9 = 12.83 at λ = 10; the supremum is 13.452 (at q ∝ (0.95, 0.31))
    step, values = _paper002_lam_c9_step(R(1283, 100))
    with pytest.raises(RuleSoundnessError) as info:
        step.check(values)
    q = [info.value.witness.state[f"q_{i}(t)"] for i in (1, 2)]
    assert abs(abs(q[1] / q[0]) - 0.31 / 0.95) < 0.05
    step, values = _paper002_lam_c9_step(R(1346, 100))                # above the supremum: not refuted
    assert step.check(values).status is Status.EXACT
