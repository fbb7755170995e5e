"""Verdicts that depend only on the mathematics (issue 22, point 6).

* The catalogue's checks stop at deterministic work limits (boxes, iterations, starts), not
  at wall-clock time: with a clock running 100× too fast (a machine 100× slower, as seen by
  every time check) they give the same statuses and verdicts.
* A step cut by the caller's ``budget`` is undecided ("the budget was spent before this
  step"), never "missing".
* Printed constants are compared only at the data where the paper states them.
* ``failed`` for a theorem is reserved for a refuted hypothesis (or a counterexample to the
  conclusion); a chain that does not close at the proof's choices is "not established".

No test asserts a wall-clock limit: the clocks are stubs.
"""

import time
from types import SimpleNamespace

import pytest
import sympy

from lkverify.catalogue import Link, find_items, theorem_verdict
from lkverify.catalogue import items as items_module
from lkverify.certify.bounds import sup_bound
from lkverify.certify.decay import DecayCertificate, StatedAt
from lkverify.options import Budget, Deadline, work_limits
from lkverify.status import Status


def _fast_clock(monkeypatch, factor=100.0):
    """time.monotonic and time.perf_counter advance ``factor`` times faster than real time."""
    real_mono, real_perf = time.monotonic, time.perf_counter
    m0, p0 = real_mono(), real_perf()
    monkeypatch.setattr(time, "monotonic", lambda: m0 + factor * (real_mono() - m0))
    monkeypatch.setattr(time, "perf_counter", lambda: p0 + factor * (real_perf() - p0))


def _outcome(report):
    return report.verdict, [(r.kind, r.name, r.status) for r in report.results]


# -- work limits, not seconds ----------------------------------------------------------------------

def test_an_internal_time_ceiling_is_no_limit_inside_work_limits():
    x = sympy.Symbol("x")
    expr, box = sympy.sin(3 * x) * x, {x: (0, 2)}
    with work_limits():  # 1 µs: a wall-clock ceiling; only the boxes count here
        inside = sup_bound(expr, box, budget=Budget(seconds=1e-6, boxes=5000))
        assert Deadline(1e-6).seconds is None and not Deadline(1e-6).expired
    assert inside.status is Status.CERTIFIED
    outside = sup_bound(expr, box, budget=Budget(seconds=1e-6, boxes=5000))  # a direct call: as given
    assert outside.status is Status.UNDECIDED


def test_the_users_cap_is_enforced_inside_work_limits():
    with work_limits():
        cap = Deadline(1e-6, cap=True)
        time.sleep(1e-3)
        assert cap.seconds == 1e-6 and cap.expired


@pytest.mark.parametrize("name", ["aleksandrov2023.theorem3_caps",
                                  pytest.param("aleksandrov2017.theorem1_bound", marks=pytest.mark.slow)])
def test_a_clock_100_times_faster_gives_the_same_statuses_and_verdict(monkeypatch, name):
    (item,) = find_items(name)
    idle = _outcome(item.run({}))
    _fast_clock(monkeypatch)
    loaded = _outcome(item.run({}))
    assert loaded == idle


def _lower_step_outcome():
    """V ≥ L of Theorem 3 at the Fig. 6 choices (a Template supremum certified by branch and bound)."""
    from lkverify.proofs.aleksandrov2023 import P
    from lkverify.proofs.aleksandrov2023 import theorem3_chain as C
    from lkverify.proofs.aleksandrov2023.theorem3 import steps

    from lkverify.certify.steps import rules

    getattr(rules, "_HOMOGENEOUS_CACHE", {}).clear()  # one proof per process: prove it again here
    res = steps[0].check(P.resolve(dict(C.CHOICES), use_defaults=True))
    return res.status, [(r.name, r.status) for r in res.results()], {str(k): v for k, v in res.constants.items()}


def _toy_decay():
    """certify_model of V = w² + e², V̇ ≤ −w³ − e³ on the box [0, 1/2]² (its default budget: 60 s)."""
    from lkverify.certify.decay import DecayModel, certify_model

    w, e = sympy.symbols("w e", nonnegative=True)
    half, Q = sympy.Rational(1, 2), w**2 + e**2
    m = DecayModel("toy", (w, e), {w: half, e: half}, Q, Q, -w**3 - e**3 - w * e**2, sympy.Rational(3, 2),
                   (w, e), {}, {"d1": e, "d2": w})
    cert = certify_model(m)
    return (None, {}) if cert is None else (cert.status, cert.constants)


def test_the_decay_certificate_is_decided_by_work_limits_not_by_the_clock(monkeypatch):
    with work_limits():
        idle = _toy_decay()
    assert idle[0] is Status.CERTIFIED
    _fast_clock(monkeypatch, factor=1e7)  # its 60 s are 6 µs of real time
    with work_limits():
        assert _toy_decay() == idle
    assert _toy_decay() != idle  # the control: outside work_limits the internal ceilings are seconds


@pytest.mark.slow  # about 20 s: the step twice
def test_a_template_supremum_is_decided_by_its_box_limit_not_by_the_clock(monkeypatch):
    with work_limits():
        idle = _lower_step_outcome()
    assert idle[0] is Status.CERTIFIED
    _fast_clock(monkeypatch, factor=1e6)  # 30 s of internal ceiling would be 30 µs of real time
    with work_limits():
        assert _lower_step_outcome() == idle


@pytest.mark.slow  # the whole report twice: many minutes
def test_the_whole_report_is_the_same_with_a_clock_100_times_faster(monkeypatch):
    from lkverify.catalogue import catalogue

    todo = [item for pf in catalogue() for item in pf.items.values()]
    idle = [_outcome(item.run({})) for item in todo]
    _fast_clock(monkeypatch)
    assert [_outcome(item.run({})) for item in todo] == idle


# -- a budget cut is undecided, never missing -------------------------------------------------------

def _links(report):
    return {link.name: link for link in report.chain}


def test_a_tiny_budget_leaves_every_link_undecided_never_missing():
    (theorem,) = find_items("aleksandrov2026.theorem1")
    report = theorem.run({}, budget=1e-3)
    assert not any(link.missing for link in report.chain if link.name != "conclusion"), report.chain
    assert "missing" not in report.verdict and report.verdict.startswith("undecided"), report.verdict
    steps = [link for name, link in _links(report).items() if "bound step" in name]
    assert len(steps) == 3 and all(link.status is Status.UNDECIDED for link in steps)
    assert all("the budget was spent before this step" in link.detail for link in steps)
    assert report.exit_code == 1


def test_steps_cut_after_the_identities_are_undecided_by_name(monkeypatch):
    """The budget runs out while the V̇ identity is checked: the three steps are 'spent before', not missing."""
    (theorem,) = find_items("aleksandrov2023.theorem3")
    offset = [0.0]
    real = time.monotonic
    monkeypatch.setattr(time, "monotonic", lambda: real() + offset[0])
    check_claim = items_module._check_claim

    def claim_then_a_long_wait(*args):
        res = check_claim(*args)
        offset[0] += 1e5  # the clock jumps past the cap: a loaded machine
        return res

    monkeypatch.setattr(items_module, "_check_claim", claim_then_a_long_wait)
    report = theorem.run({}, budget=3600)
    links = _links(report)
    assert links["V̇ along the system"].status is Status.EXACT
    for text in ("V ≥ L", "V ≤ U", "V̇ ≤ W"):
        (link,) = [v for k, v in links.items() if k.startswith(text)]
        assert link.status is Status.UNDECIDED and "the budget was spent before this step" in link.detail
    assert report.verdict.startswith("undecided: V ≥ L"), report.verdict
    assert "missing" not in report.verdict


def test_a_cut_role_is_an_undecided_link():
    (theorem,) = find_items("aleksandrov2023.theorem3")
    links = theorem.chain([], steps={}, cut={"lower": "the budget was spent before this step"})
    (lower,) = [link for link in links if link.name.startswith("V ≥ L")]
    (upper,) = [link for link in links if link.name.startswith("V ≤ U")]
    assert lower.status is Status.UNDECIDED and upper.missing


# -- failed is reserved for a refuted hypothesis ----------------------------------------------------

@pytest.mark.parametrize("links, start", [
    ([Link("hypotheses", Status.FAILED, "k > 0")], "failed: hypotheses"),
    ([Link("hypotheses", Status.EXACT), Link("V̇ ≤ W", Status.FAILED, "a witness")], "not established: V̇ ≤ W refuted"),
    ([Link("hypotheses", Status.EXACT), Link("decay", Status.FAILED, "W ≥ 0")], "not established at these choices"),
])
def test_only_a_refuted_hypothesis_fails_a_theorem(links, start):
    at = "these choices" if links[-1].name == "decay" else None
    assert theorem_verdict([*links, Link("conclusion", None)], at=at).startswith(start)


# -- printed values compared only where the paper states them --------------------------------------

FIG3 = {"F": "diag(0.7,0.7,0.7)", "a": "2", "b": "-2", "tau": "0.9", "mu": "2"}
FIG5 = {"F": "diag(0.2,0.2,0.2)", "a": "0.6", "b": "-0.6", "tau": "0.9", "mu": "2"}


def _resolved(values):
    from lkverify.proofs.aleksandrov2023 import P

    return P.resolve(values, use_defaults=True)


def _certificate():
    return DecayCertificate(Status.CERTIFIED, {"d1": 19.9, "d2": 1.82, "d3": 0.5, "delta_tilde": 5e-6}, (), (), "",
                            0.0)


@pytest.mark.parametrize("values", [FIG3, FIG5, {"a": "1/1000000"}, {"r": "[1, 0, 0]"}])
def test_15_is_not_compared_at_other_data(values):
    from lkverify.proofs.aleksandrov2023.section6 import PRINTED_15_STATED, at_printed_15
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    v = _resolved(values)
    assert not at_printed_15(v)
    rows = _certificate().results(PRINTED_15_STATED, {}, v)
    assert all(r.value["paper"] is None and "paper:" not in r.detail for r in rows)
    assert all("only at the Fig. 6/7 data" in r.detail for r in rows if r.name in ("d1", "d2", "d3"))
    assert theorem3.constants.stated(v) == {}


@pytest.mark.parametrize("values", [{}, {"F": "diag(1.0, 1, 1)", "tau": "1.0"}, {"r": "[1/sqrt(3), sqrt(3)/3, 3**(-1/2)]"}])
def test_15_is_compared_at_the_fig6_data_however_written(values):
    from lkverify.proofs.aleksandrov2023.section6 import PRINTED_15, PRINTED_15_STATED, at_printed_15
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    v = _resolved(values)
    assert at_printed_15(v)
    rows = {r.name: r for r in _certificate().results(PRINTED_15_STATED, {}, v)}
    assert rows["d1"].value["paper"] == 9.21 and rows["d1"].value["equal_or_better"] is False
    assert rows["d2"].value["equal_or_better"] is True
    assert theorem3.constants.stated(v) == PRINTED_15


def test_a_plain_mapping_is_still_compared_everywhere():
    rows = {r.name: r for r in _certificate().results({"d1": 20.0}, {})}
    assert rows["d1"].value["equal_or_better"] is True
    assert StatedAt({"d1": 1.0}, {}, "anywhere").at({}) == {"d1": 1.0}


# -- check at the Fig. 3 and Fig. 5 gains searches the choices --------------------------------------

@pytest.mark.slow  # the chain at the Fig. 6 choices, the search of λ, α, β, δ_e, δ_w, the chain again: minutes
@pytest.mark.parametrize("gains", [FIG3, FIG5])
def test_check_at_the_fig3_and_fig5_gains_searches_the_choices_and_is_established(gains):
    (theorem,) = find_items("aleksandrov2023.theorem3")
    report = theorem.run(gains)
    assert report.verdict.startswith("established"), report.verdict
    (row,) = [r for r in report.results if r.name == "choices"]
    assert row.status is Status.ESTIMATED and set(row.value) == {"lam", "alpha", "beta", "delta_e", "delta_w"}
    assert all(report.parameters[k] == v for k, v in row.value.items())
    assert not any(r.status is Status.FAILED for r in report.results)
    assert report.exit_code == 0


@pytest.mark.parametrize("values, printed", [({}, True), (FIG3, False), (FIG5, False), ({"a": "1/2"}, False)])
def test_the_caps_meet_the_print_only_at_the_fig6_data(values, printed):
    (caps,) = find_items("aleksandrov2023.theorem3_caps")
    rep = caps.run(values)
    names = [r.name for r in rep.results]
    assert any(n.startswith("printed d1") for n in names) is printed
    assert (rep.exit_code == 1) is printed  # at the Fig. 6 data the print is above the cap: a finding
    assert (rep.results[0].value["paper"] is not None) is printed


class _Stub:
    """A checked step's result (status, detail) for the stubbed chain below."""

    def __init__(self, status):
        self.status, self.detail = status, f"stub {status}"


def _stub_chain(monkeypatch, theorem, good_lam):
    """Theorem 3's steps and decay replaced by a stub: the decay holds only at λ = good_lam."""
    from lkverify.catalogue.items import _StepsRun
    from lkverify.report.results import Result

    def steps_run(values, cap, progress):
        ok = str(values.get("lam")) == good_lam
        checked = {s.role: (s, _Stub(Status.CERTIFIED)) for s in theorem.steps}
        decay = Link("decay on the region", Status.CERTIFIED if ok else Status.FAILED, "stub decay")
        rows = [] if ok else [Result("region", "decay on the region", Status.FAILED, None, "stub: W ≥ 0 at a point")]
        return _StepsRun(rows, checked, {}, decay)

    monkeypatch.setattr(theorem, "_steps_run", steps_run)
    exact = SimpleNamespace(status=Status.EXACT, to_json=dict, detail="stub: exact", differences=())
    monkeypatch.setattr(items_module, "_check_claim", lambda *args: exact)  # the V̇ identity: proved elsewhere


@pytest.mark.parametrize("found", [None, {"lam": "20"}])
def test_choices_that_do_not_close_the_chain_are_searched(monkeypatch, found):
    from lkverify.proofs.aleksandrov2023.theorem3 import theorem3

    _stub_chain(monkeypatch, theorem3, good_lam="20")
    calls = []

    def search_choices(name, values, *, progress=None):
        calls.append(values["a"])
        return (found, "stub search") if found else (None, "stub: the search found none")

    monkeypatch.setattr(theorem3, "constants", SimpleNamespace(steps=True, free={"lam": (1, 40)},
                                                                search_choices=search_choices))
    rep = theorem3.run(FIG3)
    assert calls == [2]
    (row,) = [r for r in rep.results if r.name == "choices"]
    if found is None:
        assert rep.verdict.startswith("not established at the searched choices: decay on the region refuted")
        assert row.status is Status.UNDECIDED and "found none" in row.detail and rep.exit_code == 1
    else:
        assert rep.verdict.startswith("established"), rep.verdict
        assert row.status is Status.ESTIMATED and rep.parameters["lam"] == "20" and rep.exit_code == 0
    assert not rep.verdict.startswith("failed")
    rep = theorem3.run({**FIG3, "lam": "7"})  # a choice set by the user is checked as given, not searched
    assert len(calls) == 1 and rep.verdict.startswith("not established at these choices"), rep.verdict
