"""Stronger witnesses (issue 22, point 4): false steps that were ``undecided`` become ``failed``.

Each false claim below was ``undecided`` before the structured starts of
lkverify.certify.steps.witness_seeds (checked against the previous commit); each true
variant, written next to it, must not be refuted.  The steps use the Printed rule, so only
a witness decides them: ``failed`` (a rechecked witness) or ``undecided``.
"""

import pytest
import sympy

from lkverify import (Equation, Functional, Parameters, System, Term, Vector, memory_integral, norm_power, t,
                      window_integral, xi)
from lkverify.certify.steps import Region, TermBound, TermwiseBound, norm_measure
from lkverify.certify.steps.measures import sup_norm, window_integral_measure, window_norm
from lkverify.certify.steps.memory import memory_measure
from lkverify.certify.steps.rules import Printed
from lkverify.status import Status

R = sympy.Rational
P = Parameters()
x = Vector("x", 2)
y = Vector("y", 3)
n = norm_measure("n", x(t))
ny = norm_measure("ny", y(t))
N, NY = n.symbol, ny.symbol
SYS = System([Equation(x, [Term(-x(t))]), Equation(y, [Term(-y(t))])], parameters=P)
I = window_integral_measure("I", x(xi), p=2, window=1)
J = window_norm("J", x(xi), p=2, window=1)                  # (∫‖x‖²)^{1/2}
M3 = sympy.Matrix([[4, 1, 0], [1, 3, 1], [0, 1, 2]])        # λ_max = 3 + √3, irrational
LMAX = 3 + sympy.sqrt(3)
QY = (y(t).T * M3 * y(t))[0]
WEIGHTED = window_integral(x(xi).dot(x(xi)) * (2 + xi - t), 1)          # weight 1 (oldest) … 2 (newest)
HOLDER = window_integral(sympy.sqrt(x(xi).dot(x(xi))) * (xi - t + 1), 1)   # ≤ (∫σ²)^{1/2}·J = J/√3
Q = memory_measure("Q", x(xi), p=2, kernel=lambda u: sympy.exp(-2 * u))   # ∫_0^t e^{−2(t−ξ)}‖x‖² dξ
MEMORY = 3 * memory_integral(sympy.exp(-2 * (t - xi)) * norm_power(x(xi), 2))
WHOLE = Region({sup_norm("m", x(xi), window=sympy.oo): R(1, 10)})        # sup over the whole history
V_WITH_WINDOW = x(t).dot(x(t)) / 2 + R(1, 10 ** 13) * window_integral(x(xi).dot(x(xi)), 1)


def near(v, gap):
    """v rounded at 60 digits, plus gap (a rational)."""
    return sympy.Rational(str(sympy.N(v, 60))) + gap


def step(expr, bound, measures, relation="<=", region=None):
    V = Functional([Term(expr, text="T")])
    return TermwiseBound("S", V, SYS, "V", [TermBound("T", bound, Printed("test"))], bound, list(measures),
                         relation=relation, region=region)


CAP = Region({ny: R(1, 10)})
FALSE = {   # undecided before, failed now
    "Rayleigh: m = λ_max − 10⁻²⁰": step(QY, near(LMAX, -R(1, 10 ** 20)) * NY ** 2, [ny]),
    "Rayleigh on ‖y‖ ≤ 1/10: m = λ_max − 10⁻²⁰": step(QY, near(LMAX, -R(1, 10 ** 20)) * NY ** 2, [ny], region=CAP),
    "window weight: max g − 10⁻⁶": step(WEIGHTED, (2 - R(1, 10 ** 6)) * I.symbol, [n, I]),
    "window weight (≥): min g + 10⁻⁶": step(WEIGHTED, (1 + R(1, 10 ** 6)) * I.symbol, [n, I], ">="),
    "V ≤ x²/2, the window term 10⁻¹³∫x² dropped": step(V_WITH_WINDOW, N ** 2 / 2, [n]),
    "Hölder: the constant 0.1 % too small": step(HOLDER, near(1 / sympy.sqrt(3), -R(1, 1732)) * J.symbol, [n, J]),
    "memory: 3∫e^{−2(t−ξ)}‖x‖² ≤ (3 − 10⁻⁹)Q": step(MEMORY, (3 - R(1, 10 ** 9)) * Q.symbol, [n, Q]),
    "memory on the region: ≤ 2Q": step(MEMORY, 2 * Q.symbol, [n, Q], region=WHOLE),
}
TRUE = {
    "Rayleigh: m = λ_max + 10⁻²⁰": step(QY, near(LMAX, R(1, 10 ** 20)) * NY ** 2, [ny]),
    "Rayleigh on ‖y‖ ≤ 1/10: m = λ_max + 10⁻²⁰": step(QY, near(LMAX, R(1, 10 ** 20)) * NY ** 2, [ny], region=CAP),
    "window weight: max g": step(WEIGHTED, 2 * I.symbol, [n, I]),
    "window weight (≥): min g": step(WEIGHTED, I.symbol, [n, I], ">="),
    "V ≤ x²/2 + 10⁻¹³·I": step(V_WITH_WINDOW, N ** 2 / 2 + R(1, 10 ** 13) * I.symbol, [n, I]),
    "Hölder: the constant 1/√3 (+10⁻¹²)": step(HOLDER, near(1 / sympy.sqrt(3), R(1, 10 ** 12)) * J.symbol, [n, J]),
    "memory on the region: ≤ 3Q": step(MEMORY, 3 * Q.symbol, [n, Q], region=WHOLE),
}


@pytest.mark.parametrize("name", list(FALSE))
def test_a_false_step_once_undecided_is_refuted(name):
    res = FALSE[name].check({})
    term = res.terms[0]
    assert res.status is Status.FAILED and term.status is Status.FAILED, term.detail
    assert term.witness is not None and term.witness.violation[0] > 0


@pytest.mark.parametrize("name", list(TRUE))
def test_the_true_variant_is_not_refuted(name):
    res = TRUE[name].check({})
    assert res.status is Status.UNDECIDED, res.terms[0].detail      # Printed: nothing proves it either


def test_the_rayleigh_witness_is_the_eigenvector():
    w = FALSE["Rayleigh: m = λ_max − 10⁻²⁰"].check({}).terms[0].witness
    v = sympy.Matrix([sympy.Rational(s) for s in w.exact["vectors"]["y(t)"]])
    gap = sympy.expand((v.T * M3 * v)[0] - near(LMAX, -R(1, 10 ** 20)) * v.dot(v))
    assert gap.is_Rational and gap > 0                   # exactly, at the rational point
    assert abs(float(w.violation[0]) - 1e-20 * float(v.dot(v))) < 1e-24


def test_the_window_witness_concentrates_the_history_at_the_newest_end():
    w = FALSE["window weight: max g − 10⁻⁶"].check({}).terms[0].witness
    newest = w.history["x"][-1]
    assert any(abs(c) > 0 for c in newest) and all(c == 0 for piece in w.history["x"][:-1] for c in piece)


def test_the_dropped_window_term_is_refuted_by_a_history_with_mass():
    w = FALSE["V ≤ x²/2, the window term 10⁻¹³∫x² dropped"].check({}).terms[0].witness
    assert any(c != 0 for piece in w.history["x"] for c in piece)


def _race(monkeypatch):
    from lkverify import options

    class Fast:
        now = 0.0

        def monotonic(self):
            Fast.now += 1000.0
            return Fast.now

    monkeypatch.setattr(options, "time", Fast())


def test_a_step_without_a_budget_is_decided_the_same_under_a_racing_clock(monkeypatch):
    # deterministic work limits (issue 22, point 6): no wall clock unless the user gives a budget
    cases = [FALSE["window weight: max g − 10⁻⁶"], TRUE["window weight: max g"]]
    before = [(r.status, r.terms[0].detail) for r in (s.check({}) for s in cases)]
    _race(monkeypatch)
    after = [(r.status, r.terms[0].detail) for r in (s.check({}) for s in cases)]
    assert before == after and before[0][0] is Status.FAILED


def test_a_users_budget_cut_says_so(monkeypatch):
    _race(monkeypatch)
    res = TRUE["window weight: max g"].check({}, budget=10)
    assert res.status is Status.UNDECIDED
    assert "the budget was spent before this witness search finished" in res.terms[0].detail


def test_the_memory_witness_is_a_history_on_0_t_inside_the_region():
    w = FALSE["memory on the region: ≤ 2Q"].check({}).terms[0].witness
    assert w.exact["t"] == "1" and w.exact["window"] == "1"            # t = 1, pieces on [0, 1]
    assert all(sum(c * c for c in piece) <= 0.01 + 1e-12 for piece in w.history["x"])
    assert w.measures["Q"] > 0
