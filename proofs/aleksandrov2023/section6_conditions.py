"""Section 6 of paper 002, statement by statement: conditions (13), (14) exactly, behaviour from the runs.

Section 5 prints two conditions on the gains of (12):

    (13)  |b|τ < a      — the condition of [30] for μ = 1 (with, in addition, a large h),
    (14)  bτ < a        — Theorem 3, for μ > 1;

and Remark 3: "compared with condition (13), inequality (14) gives a wider region of
admissible parameters … unlike the linear case (see [30]), Theorem 3 implies that with an
essentially nonlinear torque M_τ monoaxial stabilisation can be guaranteed with a = 0,
b < 0".  Section 6 then says, of its figures (translated from the Russian):

* Fig. 1 (h = 0.7, a = 2, b = 2, τ = 0.9, μ = 1): "The stabilisation process of the body
  … is shown in Fig. 1."  "Inequality (13) holds in this case."
* Fig. 2 (b = −2): "Likewise, inequality (13) holds if the sign of b is reversed.  However,
  numerical integration shows that with b = −2 … the chosen control does not cope with
  stabilising the axis of the body (see Fig. 2)."
* Fig. 3 (b = −2, μ = 2): "The result shown in Fig. 3 testifies to the convergence of the
  stabilisation process of the body axis, which fully agrees with the statement of
  Theorem 3."
* Fig. 4 (a = 0.6, h = 0.2, b = −0.6, μ = 1; τ = 0.9 unchanged): "Inequality (13) does not
  hold in this case, and the stabilisation process of the body axis does not converge.
  The chaotic process, shown for clarity on a short time interval in Fig. 4, continues in
  the same way on a time interval 100 times longer."
* Fig. 5 (μ = 2, the rest as in Fig. 4): "In this case inequality (14) holds."  "It is
  seen that the process of monoaxial stabilisation converges to the programmed position,
  which agrees with the statement of Theorem 3."
* Fig. 6 (a = 0, h = 1, τ = 1, b = −1, μ = 2): "Remark 3 also notes that the conclusion of
  Theorem 3 admits a = 0 … The simulation results presented in Fig. 6 confirm the
  theoretical conclusion."
* Fig. 7 (the gains of Fig. 6, (φ, θ, ψ) = (0.8, 0.8, −0.8), ω = 0.1(1,1,1)): "for the case
  considered, using the proof of Theorem 3, we obtain the estimates (15) … for
  ‖χ‖_τ < 0.28"; "Fig. 7 shows … ‖s(t) − r‖ from numerical integration (solid) and the
  estimate given by the right-hand side of (15) (dashed)"; "with this choice ‖χ‖_τ is
  0.25 and hence ‖χ‖_τ < 0.28 holds."

Each statement is one :class:`Statement` and one result row.  A statement about a
condition is decided exactly: (13), (14), μ > 1 are SymPy relations in the declared
symbols a, b, τ, μ of :mod:`.equations`, evaluated at the figure's gains as resolved from
the figure item's own run (``figN.runs[0].values``, exact rationals): ``exact`` where
the text's claim agrees, ``failed`` where it does not.  A statement about behaviour reuses
the figure item's run (:meth:`Example.simulate`, cached per figure) and its claim objects
(``Converges``, ``DoesNotConverge``, ``Sensitive``, the envelope of Fig. 7), so it is
``simulated`` or ``failed`` exactly as ``lkverify simulate aleksandrov2023.figN`` reports
it.  For every figure the conditions the text does not mention are also evaluated (rows
marked "not stated in the text", status ``exact``).

Findings (at the printed gains):

* Fig. 4: the text says (13) does not hold; exactly, |b|τ = 27/50 < 3/5 = a, so (13)
  *holds* (margin 3/50).  The contrast between Figs. 4 and 5 is μ = 1 against μ = 2, not
  (13) against (14): (13) holds at the Fig. 5 gains as well.
* Fig. 4, "chaotic": the figure item's ``Sensitive`` claim (histories 1e-8 apart) does not
  separate to 1e-2 by t = 200 (``failed``, as in ``aleksandrov2023.fig4``).
* Fig. 7: ‖χ‖_τ = 0.25 is not reproduced (:mod:`.fig7_chi`, reused).
* "100 times longer" (t = 10⁴ for the Fig. 4 run) is not integrated by default (≈ 25 s);
  the row is ``undecided`` unless :func:`statement_rows` is called with ``long=True``.

Not made rows: "[30] guarantees stabilisation only for sufficiently large h" (a statement
about [30], not about a figure) and "slow convergence" of Fig. 5 (no threshold printed).
The check evaluates each figure at its own gains: ``--set`` does not change them.

Examples
--------
(13) at the gains of Fig. 4 (a = 0.6, b = −0.6, τ = 0.9), exactly:

>>> from lkverify.proofs.aleksandrov2023.section6_conditions import (C13, Statement, condition_value, evaluate,
...                                                                  figure_gains)
>>> value = condition_value(C13, figure_gains(4))
>>> value["holds"], value["parts"][0]["lhs"], value["parts"][0]["rhs"], value["parts"][0]["margin"]
(True, '27/50', '3/5', '3/50')
>>> row = evaluate(Statement(4, '"Inequality (13) does not hold in this case"', condition=C13, says=False))
>>> row.status.value, row.value["holds"]
('failed', True)
>>> evaluate(Statement(1, "(13) holds", condition=C13, says=True)).status.value
'exact'
"""

from __future__ import annotations

import dataclasses
import functools

import sympy

from lkverify import Check, InputError, Result, Status
from lkverify.simulate import Converges, DoesNotConverge, Sensitive
from lkverify.simulate.figures import resolved_values

from .equations import PAPER, P, a, b, mu, tau
from .fig1 import fig1
from .fig2 import fig2
from .fig3 import fig3
from .fig4 import fig4
from .fig5 import fig5
from .fig6 import fig6
from .fig7 import fig7
from .fig7_chi import fig7_chi, fig7_chi_check

__all__ = ["section6", "Statement", "STATEMENTS", "FIGURES", "C13", "C14", "MU_GT_1", "THEOREM3", "REMARK3",
           "figure_gains", "condition_value", "evaluate", "statement_rows", "trajectories"]

#: the figure items of section 6, by figure number
FIGURES = {1: fig1, 2: fig2, 3: fig3, 4: fig4, 5: fig5, 6: fig6, 7: fig7}

C13 = sympy.Abs(b) * tau < a                  # (13) |b|τ < a
C14 = b * tau < a                             # (14) bτ < a
MU_GT_1 = mu > 1                              # Theorem 3: μ > 1
THEOREM3 = sympy.And(MU_GT_1, C14, evaluate=False)               # the hypotheses of Theorem 3
REMARK3 = sympy.And(sympy.Eq(a, 0), b < 0, evaluate=False)        # Remark 3: a = 0, b < 0

#: behaviours a statement may assert, by keyword: the claim class of lkverify.simulate
BEHAVIOURS = {"converges": Converges, "does not converge": DoesNotConverge, "sensitive": Sensitive}
#: what a statement may rest on besides a claim: the envelope (15) of a figure, ‖χ‖_τ of Fig. 7
OTHER_EVIDENCE = ("envelope", "chi")

_SYMBOLS = {"a": a, "b": b, "tau": tau, "mu": mu}
_PRETTY = (("Abs(b)", "|b|"), ("tau", "τ"), ("mu", "μ"), ("*", ""))
#: the printed forms of the paper's conditions (other relations are shown as SymPy prints them)
LABELS = {C13: "(13) |b|τ < a", C14: "(14) bτ < a", MU_GT_1: "μ > 1", sympy.Eq(a, 0): "a = 0", b < 0: "b < 0"}


def _pretty(expr) -> str:
    if expr in LABELS:
        return LABELS[expr]
    if isinstance(expr, sympy.And):
        return " and ".join(_pretty(p) for p in expr.args)
    text = str(expr)
    for old, new in _PRETTY:
        text = text.replace(old, new)
    return text


@dataclasses.dataclass(frozen=True)
class Statement:
    """One statement of section 6 about one figure.

    Parameters
    ----------
    figure : int
        1 … 7; its gains are those of the item ``aleksandrov2023.fig<figure>``.
    quote : str
        The statement (translated), with its equation / figure numbers.
    condition : sympy relation, optional
        A condition in a, b, τ, μ (:data:`C13`, :data:`C14`, :data:`THEOREM3`, … or any
        equivalent relation), decided exactly at the figure's gains.
    says : bool or None
        What the text says of ``condition``: holds (True), violated (False), or nothing
        (None: the condition is only evaluated).
    behaviour : str, optional
        What the text says the run does: a key of :data:`BEHAVIOURS` or one of
        :data:`OTHER_EVIDENCE`.
    t_end : float, optional
        A horizon longer than the figure item's (a statement about a longer run).
    """

    figure: int
    quote: str
    condition: object = None
    says: bool | None = True
    behaviour: str | None = None
    t_end: float | None = None

    def __post_init__(self):
        problems = []
        if self.figure not in FIGURES:
            problems.append(f"figure: expected one of {sorted(FIGURES)}, got {self.figure!r}")
        if (self.condition is None) == (self.behaviour is None):
            problems.append("expected exactly one of condition= (a relation in a, b, tau, mu) and behaviour=")
        if self.condition is not None:
            if not isinstance(self.condition, sympy.logic.boolalg.Boolean):
                problems.append(f"condition: expected a SymPy relation in a, b, tau, mu, got {self.condition!r}")
            elif not self.condition.free_symbols <= set(_SYMBOLS.values()):
                problems.append(f"condition: expected a relation in a, b, tau, mu only, got free symbols "
                                f"{sorted(map(str, self.condition.free_symbols - set(_SYMBOLS.values())))}")
        if self.behaviour is not None and self.behaviour not in (*BEHAVIOURS, *OTHER_EVIDENCE):
            problems.append(f"behaviour: expected one of {', '.join((*BEHAVIOURS, *OTHER_EVIDENCE))}, "
                            f"got {self.behaviour!r}")
        if self.figure in FIGURES and self.behaviour == "envelope" and FIGURES[self.figure].envelope is None:
            problems.append(f"behaviour='envelope': Fig. {self.figure} has no envelope (only Fig. 7 has, (15))")
        if self.behaviour == "chi" and self.figure != 7:
            problems.append(f"behaviour='chi': ‖χ‖_τ is printed for the Fig. 7 data only, got {self.figure}")
        if problems:
            raise InputError(f"Statement(figure={self.figure!r}, {self.quote!r}): " + "; ".join(problems))

    @property
    def name(self) -> str:
        return f"Fig. {self.figure}: {self.quote}"


# -- the gains and the exact conditions -----------------------------------------------------------

def figure_gains(number: int) -> dict:
    """The exact gains of Fig. ``number``: a, b, τ, μ, h as resolved from the figure item's run."""
    values = resolved_values(FIGURES[number].runs[0])
    F = values["F"]
    out = {k: values[k] for k in _SYMBOLS}
    out["h"] = F[0, 0] if F == F[0, 0] * sympy.eye(F.shape[0]) else F
    return out


def _gains_text(g) -> str:
    return ", ".join(f"{_pretty(k)} = {g[k]}" for k in ("h", "a", "b", "tau", "mu"))


def _exact(v, name):
    """An exact value: SymPy numbers without floats, integers, or decimal strings ("0.6" → 3/5)."""
    if isinstance(v, str):
        try:
            v = sympy.Rational(v)
        except (TypeError, ValueError):
            v = sympy.sympify(v, rational=True)
    elif isinstance(v, int) and not isinstance(v, bool):
        v = sympy.Integer(v)
    if not isinstance(v, sympy.Basic) or v.has(sympy.Float) or not v.is_number:
        raise InputError(f"gain {name}: expected an exact number (a SymPy rational, an int or a decimal string such "
                         f"as '0.6'), got {v!r}; a float is never exact")
    return v


def condition_value(condition, gains) -> dict:
    """Decide ``condition`` exactly at ``gains``: ``holds`` (True / False / None) and each part's sides.

    ``value`` is a margin rhs − lhs (positive when the inequality holds) as a float for the
    table: of the first violated strict inequality, else of the last one; the exact sides
    and margins are strings.
    """
    subs = {sym: _exact(gains[name], name) for name, sym in _SYMBOLS.items()}
    parts = list(condition.args) if isinstance(condition, sympy.And) else [condition]
    rows, headline = [], None
    for part in parts:
        decided = part.xreplace(subs)
        row = {"condition": _pretty(part), "holds": bool(decided) if decided in (sympy.true, sympy.false) else None}
        if isinstance(part, sympy.core.relational.Relational):
            lhs, rhs = part.lhs.xreplace(subs), part.rhs.xreplace(subs)
            big, small = (rhs, lhs) if isinstance(part, (sympy.StrictLessThan, sympy.LessThan)) else (lhs, rhs)
            row.update(lhs=str(lhs), op=part.rel_op, rhs=str(rhs))
            if not isinstance(part, (sympy.Equality, sympy.Unequality)):
                row["margin"] = str(big - small)
                if headline is None or headline[0]:  # keep the first violated part's margin
                    headline = (row["holds"] is not False, float(big - small))
        rows.append(row)
    whole = condition.xreplace(subs)
    holds = bool(whole) if whole in (sympy.true, sympy.false) else None
    return {"value": None if headline is None else headline[1], "holds": holds, "parts": rows,
            "condition": _pretty(condition), "gains": {_pretty(k): str(v) for k, v in gains.items()}}


def _parts_text(value) -> str:
    out = []
    for p in value["parts"]:
        verdict = {True: "true", False: "false", None: "undecided"}[p["holds"]]
        if "lhs" in p:
            op = {"==": "=", "!=": "≠", "<=": "≤", ">=": "≥"}.get(p["op"], p["op"])
            out.append(f"{p['condition']}: {p['lhs']} {op} {p['rhs']} is {verdict}"
                       + (f" (margin {p['margin']})" if "margin" in p else ""))
        else:
            out.append(f"{p['condition']} — {verdict}")
    return "; ".join(out)


def _condition_row(st: Statement) -> Result:
    gains = figure_gains(st.figure)
    value = condition_value(st.condition, gains)
    value["text_says"] = st.says
    holds = value["holds"]
    where = f"at the Fig. {st.figure} gains ({_gains_text(gains)}): {_parts_text(value)}"
    word = "holds" if holds else "is violated"
    if holds is None:
        status, detail = Status.UNDECIDED, f"not decided exactly {where}"
    elif st.says is None:
        status, detail = Status.EXACT, f"{value['condition']} {word} {where} (the text says nothing of it)"
    elif holds == st.says:
        status, detail = Status.EXACT, f"{value['condition']} {word} {where}, as the text says"
    else:
        status = Status.FAILED
        detail = (f"the text says {value['condition']} {'holds' if st.says else 'does not hold'}; exactly, it "
                  f"{word} {where}")
    return Result("hypothesis", st.name, status, value, detail)


# -- behaviour: the figure items' runs and claims --------------------------------------------------

@functools.lru_cache(maxsize=None)
def trajectories(number: int, t_end: float | None = None) -> dict:
    """The trajectories of the figure item ``fig<number>`` (its :meth:`simulate`), computed once per horizon."""
    return FIGURES[number].simulate(t_end=t_end)


def _headline(value):
    """The number of a claim's value shown in the table: final distance, window minimum, separation."""
    if isinstance(value.get("final_distance"), float):
        return value["final_distance"]
    if value.get("window_maxima"):
        return float(min(value["window_maxima"]))
    return value.get("max_separation")


def _claim(example, behaviour):
    cls = BEHAVIOURS[behaviour]
    own = [c for c in example.claims if type(c) is cls]
    return own[0] if own else cls(example.runs[0].label)


def _behaviour_row(st: Statement, *, long: bool) -> Result:
    example = FIGURES[st.figure]
    item = example.qualified_name
    if st.behaviour == "chi":
        (row,) = fig7_chi_check(None)[:1]
        value = dict(row.value)
        value.setdefault("value", value.get("default"))
        return Result(row.kind, st.name, row.status, value, f"{fig7_chi.qualified_name}: {row.detail}")
    horizon = example.t_end if st.t_end is None else float(st.t_end)
    kind = "envelope" if st.behaviour == "envelope" else "simulation"
    if st.t_end is not None and not long:
        return Result(kind, st.name, Status.UNDECIDED, {"t_end": horizon},
                      f"not integrated by default (the run of {item} to t = {horizon:g} takes about 25 s); "
                      f"`lkverify simulate {item} --t-end {horizon:g}` checks it "
                      f"(or statement_rows(long=True))")
    trs = trajectories(st.figure, None if st.t_end is None else horizon)
    cut = [label for label, tr in trs.items() if not tr.outcome.reached_end]
    if cut:
        return Result(kind, st.name, Status.UNDECIDED, None,
                      f"{item}: run(s) {', '.join(cut)} stopped before t = {horizon:g}: nothing observed")
    if st.behaviour == "envelope":
        chk = example.check_envelope(trs)
        value = dict(chk.to_json())
        value.setdefault("value", chk.max_ratio)
        return Result(kind, st.name, chk.status, value,
                      f"{item}, {chk.name}: max trajectory/envelope = {chk.max_ratio:.4g} at t = {chk.t_max_ratio:.4g}"
                      + (f"; first violation at t = {chk.first_violation:.4g}" if chk.first_violation is not None
                         else "; no violation at the samples"))
    claim = _claim(example, st.behaviour)
    res = claim.check(example, trs)
    value = dict(res.value) if isinstance(res.value, dict) else {"value": res.value}
    value.update(item=item, claim=claim.name, t_end=horizon)
    value.setdefault("value", _headline(value))
    caveat = (" — the figure item's test of sensitivity; a failure says the runs did not separate, it does not "
              "prove the motion regular" if st.behaviour == "sensitive" and res.status is Status.FAILED else "")
    return Result(kind, st.name, res.status, value,
                  f"{item}, claim '{claim.name}' (to t = {horizon:g}): {res.detail}{caveat}")


def evaluate(statement: Statement, *, long: bool = False) -> Result:
    """The result row of one statement (``long``: integrate statements about longer horizons too)."""
    if statement.condition is not None:
        return _condition_row(statement)
    return _behaviour_row(statement, long=long)


# -- the statements of section 6 --------------------------------------------------------------------

_T3 = "Theorem 3's hypotheses μ > 1 and (14) bτ < a"
_LONG_FIG4 = 100 * fig4.plot_until  # "a time interval 100 times longer" than the one shown in Fig. 4

STATEMENTS = (
    # Fig. 1: h = 0.7, a = 2, b = 2, τ = 0.9, μ = 1
    Statement(1, '"the stabilisation process of the body … is shown in Fig. 1": the axis is stabilised',
              behaviour="converges"),
    Statement(1, '"Inequality (13) [|b|τ < a] holds in this case"', condition=C13, says=True),
    Statement(1, f"{_T3} (not stated in the text)", condition=THEOREM3, says=None),
    # Fig. 2: b = −2
    Statement(2, '"Likewise, inequality (13) holds if the sign of b is reversed" (b = −2)', condition=C13, says=True),
    Statement(2, '"with b = −2 … the chosen control does not cope with stabilising the axis (see Fig. 2)"',
              behaviour="does not converge"),
    Statement(2, f"{_T3} (not stated in the text)", condition=THEOREM3, says=None),
    # Fig. 3: b = −2, μ = 2
    Statement(3, '"the result shown in Fig. 3 testifies to the convergence of the stabilisation process"',
              behaviour="converges"),
    Statement(3, f'"… which fully agrees with the statement of Theorem 3": {_T3}', condition=THEOREM3, says=True),
    Statement(3, "(13) |b|τ < a (not stated in the text)", condition=C13, says=None),
    # Fig. 4: a = 0.6, h = 0.2, b = −0.6, μ = 1 (τ = 0.9 unchanged)
    Statement(4, '"Inequality (13) does not hold in this case" (a = 0.6, h = 0.2, b = −0.6, μ = 1)',
              condition=C13, says=False),
    Statement(4, '"… and the stabilisation process of the body axis does not converge"',
              behaviour="does not converge"),
    Statement(4, '"The chaotic process, shown … in Fig. 4": sensitive dependence on the initial data',
              behaviour="sensitive"),
    Statement(4, '"… continues in the same way on a time interval 100 times longer": no convergence up to '
                 f't = {_LONG_FIG4:g}', behaviour="does not converge", t_end=_LONG_FIG4),
    Statement(4, f"{_T3} (not stated in the text)", condition=THEOREM3, says=None),
    # Fig. 5: μ = 2, the rest as in Fig. 4
    Statement(5, '"In this case inequality (14) [bτ < a] holds" (μ = 2, the rest as in Fig. 4)', condition=C14,
              says=True),
    Statement(5, '"the process of monoaxial stabilisation converges to the programmed position" (Fig. 5)',
              behaviour="converges"),
    Statement(5, f'"… which agrees with the statement of Theorem 3": {_T3}', condition=THEOREM3, says=True),
    Statement(5, "(13) |b|τ < a (not stated in the text)", condition=C13, says=None),
    # Fig. 6: a = 0, h = 1, τ = 1, b = −1, μ = 2 (Remark 3)
    Statement(6, 'Remark 3: stabilisation "can be guaranteed with a = 0, b < 0"; the gains of Fig. 6 are such',
              condition=REMARK3, says=True),
    Statement(6, f'"the conclusion of Theorem 3 admits a = 0": {_T3}', condition=THEOREM3, says=True),
    Statement(6, 'Remark 3, "unlike the linear case (see [30])": (13) |b|τ < a fails at a = 0', condition=C13,
              says=False),
    Statement(6, '"The simulation results presented in Fig. 6 confirm the theoretical conclusion"',
              behaviour="converges"),
    # Fig. 7: the gains of Fig. 6, other initial data
    Statement(7, f'"for the case considered, using the proof of Theorem 3, we obtain the estimates (15)": {_T3}',
              condition=THEOREM3, says=True),
    Statement(7, '"with this choice ‖χ‖_τ is 0.25 and hence ‖χ‖_τ < 0.28 holds"', behaviour="chi"),
    Statement(7, '"Fig. 7 shows ‖s(t) − r‖ (solid) and the right-hand side of (15) (dashed)": the run stays '
                 'below (15)', behaviour="envelope"),
    Statement(7, "(13) |b|τ < a (not stated in the text)", condition=C13, says=None),
)


def statement_rows(statements=STATEMENTS, *, long: bool = False) -> list[Result]:
    """One result row per statement (``long=True``: also integrate the statements about longer runs)."""
    return [evaluate(st, long=long) for st in statements]


def _check(values):
    return statement_rows()


section6 = Check("section6", parameters=P, checks=[_check], relevant=(), paper=PAPER,
                 title="Section 6: each statement about Figs. 1–7 — (13), (14), μ > 1 exactly at the figure's "
                       "gains, behaviour from the figure items' runs")
