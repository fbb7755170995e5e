"""Conditions (5), (10)/(15), (11) of paper 001 on the damping coefficient h(t), decided symbolically.

Theorem 1 of paper 001 asks of h(t) > 0 (C¹ on t ≥ 0):

    (5)   h(t) → 0 as t → +∞;
    (10)  |ḣ(t)| ≤ L h^{(3−ν)/2}(t) for t ≥ 0, some constant L, for some ν ≥ 1;
    (11)  ∫_0^t h^ν(τ) dτ → +∞ as t → +∞ (the same ν).

Theorem 2 (nonlinear damping of order μ > 1) replaces (10) by

    (15)  |ḣ(t)| ≤ L h^{1 + (1−ν)/(μ+1)}(t).

Corollary 1: for h = (t+1)^{−β}, β > 0, the conditions hold iff β ≤ 1 (14).

How each condition is decided (all exact, no floating point):

* (5): ``is_positive`` of h on t ≥ 0 and ``sympy.limit(h, t, oo)``.
* (10)/(15) for one ν: R = |ḣ| / h^e is continuous on [0, ∞) (ḣ continuous there and h > 0) and
  ``limit(R, t, oo)`` is finite; then L = sup R exists, computed as the largest of R(0), the limit
  and R at the critical points when ``solveset`` finds them all.
* (11) for one ν: ``integrate(h^ν, (t, 0, oo))``; if that is not conclusive, the limit comparison
  with powers: q = lim log h^ν / log t > −1 diverges, q < −1 converges, q = −1 is compared with
  1/t and 1/(t log² t).
* the set of admissible ν (``nu=None``): with a = lim log h / log t and b = lim log |ḣ| / log t,
  (11) holds for ν < −1/a and fails for ν > −1/a (a = 0: for every ν; a = −∞: for none, since
  h^ν ≤ h once h < 1), the boundary ν = −1/a decided as above; (10)/(15) holds when
  b − e(ν)a < 0, fails when it is > 0, the boundary decided by the limit of R.
"""

from __future__ import annotations

import sympy

from lkverify import InputError, t
from lkverify.options import BudgetExceeded, Deadline
from lkverify.report import Result
from lkverify.status import Status

__all__ = ["ConditionsOnH", "corollary1", "decide_h_conditions"]

_T = sympy.Symbol("t", nonnegative=True)       # t restricted to t ≥ 0 (printed as t)
_W = sympy.Symbol("w", nonnegative=True)       # ν = 1 + w
_NU = sympy.Symbol("nu", positive=True)


class _Undecided(Exception):
    """SymPy could not decide a step (the message says which)."""


def _refuse_floats(name, expr, how):
    floats = expr.atoms(sympy.Float)
    if floats:
        raise InputError(f"{name}: expected an exact SymPy expression (integers, Rationals, symbols), got the "
                         f"float {sorted(floats, key=str)[0]} in {expr}; write it exactly, e.g. {how}")


def _prepare(h, nu, mu):
    try:
        h = sympy.sympify(h)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"h: expected a SymPy expression in lkverify.t, got {h!r}; e.g. (t + 1)**(-beta)") from exc
    _refuse_floats("h", h, "sympy.Rational(1, 2) instead of 0.5")
    others = h.free_symbols - {t}
    bad = [s for s in others if s.is_positive is not True]
    if bad:
        raise InputError(f"h: expected t (lkverify.t) and positive parameter symbols only, got {sorted(bad, key=str)[0]} "
                         f"without positive=True; declare it as sympy.Symbol(name, positive=True)")
    if nu is not None:
        nu = sympy.sympify(nu)
        _refuse_floats("nu", nu, "nu=sympy.Rational(3, 2)")
        if (nu - 1).is_negative:
            raise InputError(f"nu: expected a number ν ≥ 1 (Theorem 1), got {nu}; pass nu ≥ 1 or nu=None")
    if mu is not None:
        mu = sympy.sympify(mu)
        _refuse_floats("mu", mu, "mu=3")
        if (mu - 1).is_nonpositive:
            raise InputError(f"mu: expected μ > 1 (Theorem 2: W homogeneous of order μ + 1), got {mu}; e.g. mu=3")
    return h.subs(t, _T), nu, mu


def _exponent(nu, mu):
    """e(ν) of (10) or (15)."""
    return (3 - nu) / 2 if mu is None else 1 + (1 - nu) / (mu + 1)


def _abs_derivative(h):
    dh = sympy.diff(h, _T)
    if (-dh).is_nonnegative:
        return -dh
    if dh.is_nonnegative:
        return dh
    return sympy.Abs(dh)


def _show(e):
    return str(e.subs(_T, t)) if isinstance(e, sympy.Basic) else str(e)


# ---------------------------------------------------------------- (5)

def _decide5(h):
    pos = h.is_positive
    if pos is False or (h.subs(_T, 0).is_positive is False):
        return Result("hypothesis", "(5) h > 0, h → 0", Status.FAILED, None,
                      f"h(t) = {_show(h)} is not positive on t ≥ 0 (h(0) = {h.subs(_T, 0)})")
    if pos is not True:
        return Result("hypothesis", "(5) h > 0, h → 0", Status.UNDECIDED, None,
                      f"SymPy could not show h(t) = {_show(h)} > 0 for t ≥ 0")
    lim = sympy.limit(h, _T, sympy.oo)
    if lim == 0:
        return Result("hypothesis", "(5) h > 0, h → 0", Status.EXACT, 0,
                      f"h(t) = {_show(h)} > 0 for t ≥ 0 and lim_(t→∞) h = 0")
    if lim.is_nonzero or lim is sympy.oo or lim.is_positive:
        return Result("hypothesis", "(5) h > 0, h → 0", Status.FAILED, lim,
                      f"fails (5): lim_(t→∞) h = {lim} ≠ 0 for h(t) = {_show(h)}")
    return Result("hypothesis", "(5) h > 0, h → 0", Status.UNDECIDED, lim,
                  f"SymPy could not decide lim_(t→∞) h = 0 (it gave {lim})")


# ---------------------------------------------------------------- (10) / (15)

def _label10(mu):
    return "(10)" if mu is None else "(15)"


def _formula10(mu):
    return "|ḣ| ≤ L h^((3−ν)/2)" if mu is None else "|ḣ| ≤ L h^(1+(1−ν)/(μ+1))"


def _continuous_derivative(h):
    from sympy.calculus.util import continuous_domain
    dom = continuous_domain(sympy.diff(h, _T).subs(_T, t), t, sympy.Interval(0, sympy.oo))
    return dom == sympy.Interval(0, sympy.oo)


def _decide10(h, nu, mu):
    """(10)/(15) at one ν: (holds?, Result)."""
    name = f"{_label10(mu)} {_formula10(mu)}"
    e = _exponent(nu, mu)
    absdh = _abs_derivative(h)
    if absdh == 0:
        return Result("bound", name, Status.EXACT, 0, f"ḣ ≡ 0: {_label10(mu)} holds with L = 0")
    if not _continuous_derivative(h):
        lim0 = sympy.limit(absdh, _T, 0, "+")
        if lim0 is sympy.oo:
            return Result("bound", name, Status.FAILED, None,
                          f"fails {_label10(mu)}: |ḣ| → ∞ as t → 0+ (h is not C¹ on t ≥ 0)")
        return Result("bound", name, Status.UNDECIDED, None, "SymPy could not show ḣ continuous on t ≥ 0")
    R = sympy.powsimp(absdh / h**e, force=False)
    Linf = sympy.limit(R, _T, sympy.oo)
    if Linf is sympy.oo:
        return Result("bound", name, Status.FAILED, None,
                      f"fails {_label10(mu)} for ν = {nu}: |ḣ|/h^{e} = {_show(R)} → ∞ as t → ∞, so no constant L")
    if Linf.is_finite is not True or Linf.has(sympy.Limit):
        return Result("bound", name, Status.UNDECIDED, None,
                      f"SymPy could not decide lim_(t→∞) |ḣ|/h^{e} for ν = {nu} (it gave {Linf})")
    # L exists; its value: sup R over [0, ∞)
    cands = [R.subs(_T, 0), Linf]
    dR = sympy.simplify(sympy.diff(R, _T))
    crit = sympy.S.EmptySet if dR == 0 else sympy.solveset(dR, _T, sympy.Interval.open(0, sympy.oo))
    if isinstance(crit, sympy.FiniteSet) or crit is sympy.S.EmptySet:
        cands += [R.subs(_T, c) for c in crit]
        sup = sympy.simplify(sympy.Max(*cands))
        return Result("bound", name, Status.EXACT, sup,
                      f"{_label10(mu)} holds for ν = {nu}: |ḣ|/h^{e} = {_show(R)} is continuous on [0, ∞) with "
                      f"limit {Linf} at ∞; the smallest L is sup = {sup}")
    return Result("bound", name, Status.EXACT, None,
                  f"{_label10(mu)} holds for ν = {nu}: |ḣ|/h^{e} = {_show(R)} is continuous on [0, ∞) with finite "
                  f"limit {Linf} at ∞, hence bounded (L = its maximum over [0, t1] ∪ (limit + 1) beyond some t1); "
                  f"the exact sup was not found in closed form (critical points: {crit})")


# ---------------------------------------------------------------- (11)

def _decide11(h, nu):
    name = "(11) ∫_0^∞ h^ν = ∞"
    f = sympy.powdenest(h**nu, force=False)
    I = sympy.integrate(f, (_T, 0, sympy.oo))
    if I is sympy.oo:
        return Result("hypothesis", name, Status.EXACT, sympy.oo, f"(11) holds for ν = {nu}: ∫_0^∞ {_show(f)} dt = ∞")
    if not I.has(sympy.Integral, sympy.Piecewise) and I.is_finite:
        v = sympy.gammasimp(sympy.simplify(I))
        return Result("hypothesis", name, Status.FAILED, v,
                      f"fails (11) for ν = {nu}: ∫_0^∞ h^ν dt = ∫_0^∞ {_show(f)} dt = {v} < ∞")
    q = sympy.limit(sympy.log(f) / sympy.log(_T), _T, sympy.oo)
    if (q + 1).is_positive:
        return Result("hypothesis", name, Status.EXACT, sympy.oo,
                      f"(11) holds for ν = {nu}: log h^ν / log t → {q} > −1, so h^ν ≥ t^(−p) eventually "
                      f"with p < 1 and the integral diverges")
    if (q + 1).is_negative:
        return Result("hypothesis", name, Status.FAILED, None,
                      f"fails (11) for ν = {nu}: log h^ν / log t → {q} < −1, so h^ν ≤ t^(−p) eventually with "
                      f"p > 1 and ∫_0^∞ h^ν < ∞")
    if q + 1 == 0:
        c = sympy.limit(_T * f, _T, sympy.oo)
        if c is sympy.oo or c.is_positive:
            return Result("hypothesis", name, Status.EXACT, sympy.oo,
                          f"(11) holds for ν = {nu}: t·h^ν → {c} > 0, compared with ∫ dt/t = ∞")
        c2 = sympy.limit(_T * sympy.log(_T) ** 2 * f, _T, sympy.oo)
        if c2.is_finite and c2.is_nonnegative:
            return Result("hypothesis", name, Status.FAILED, None,
                          f"fails (11) for ν = {nu}: t log²t·h^ν → {c2}, compared with ∫ dt/(t log²t) < ∞")
    return Result("hypothesis", name, Status.UNDECIDED, None,
                  f"SymPy could not decide ∫_0^∞ {_show(f)} dt (integral: {I}; log h^ν/log t → {q})")


# ---------------------------------------------------------------- the set of admissible ν

def _condition(nonempty):
    """``nonempty`` (a relational in the parameters) reduced when it has one parameter."""
    nonempty = sympy.simplify(nonempty)
    syms = list(nonempty.free_symbols)
    if len(syms) == 1 and not isinstance(nonempty, sympy.logic.boolalg.BooleanAtom):
        try:
            red = sympy.reduce_inequalities([nonempty], syms[0])
            return red
        except (NotImplementedError, ValueError, TypeError):
            pass
    return nonempty


def _set11(h, a):
    """(S11, Result) of condition (11) ∫_0^∞ h^ν = ∞ over ν ≥ 1, given a = lim log h / log t."""
    n11 = "(11) ∫_0^∞ h^ν = ∞: set of ν ≥ 1"
    if a == 0:
        S11 = sympy.Interval(1, sympy.oo)
        r11 = Result("hypothesis", n11, Status.EXACT, S11,
                     "(11) holds for every ν ≥ 1: log h / log t → 0, so h^ν ≥ t^(−1/2) eventually")
    elif a is -sympy.oo:
        at1 = _decide11(h, sympy.Integer(1))
        how = at1.detail if at1.status is Status.FAILED else "h ≤ t^(−2) eventually (log h / log t → −∞)"
        S11 = sympy.S.EmptySet
        r11 = Result("hypothesis", n11, Status.FAILED, S11,
                     f"fails (11) for every ν ≥ 1: {how}; and h^ν ≤ h once h < 1")
    elif a.is_finite and a.is_negative:
        nstar = -1 / a
        edge = _decide11(h, nstar) if (nstar - 1).is_nonnegative is not False else None
        if edge is not None and edge.status is Status.UNDECIDED:
            raise _Undecided(f"(11) at the boundary ν = {nstar}: {edge.detail}")
        closed = edge is not None and edge.status is Status.EXACT
        S11 = sympy.Interval(1, nstar, False, not closed)
        why = (f"log h / log t → {a}, so (11) holds for ν < {nstar} and fails for ν > {nstar}"
               + ("" if edge is None else f"; at ν = {nstar}: {edge.detail}"))
        if S11 is sympy.S.EmptySet:
            at1 = _decide11(h, sympy.Integer(1))
            r11 = Result("hypothesis", n11, Status.FAILED, S11,
                         f"fails (11) for every ν ≥ 1: {why}; at ν = 1: {at1.detail}")
        else:
            r11 = Result("hypothesis", n11, Status.EXACT, S11, f"(11) holds exactly for ν in {S11}: {why}")
    else:
        raise _Undecided(f"SymPy could not decide the decay of h: lim log h / log t = {a}")
    return S11, r11


def _set10(h, mu, a, S11):
    """(S10, why, None) of condition (10) (or (15)) over ν ≥ 1; ``(None, None, why)`` when SymPy cannot decide it
    for symbolic ν, ``S10 = None`` when it is not needed ((11) fails)."""
    lab = _label10(mu)
    absdh = _abs_derivative(h)
    S10, why10 = None, ""
    if absdh == 0:
        S10, why10 = sympy.Interval(1, sympy.oo), "ḣ ≡ 0"
    elif not _continuous_derivative(h):
        raise _Undecided("SymPy could not show ḣ continuous on t ≥ 0")
    else:
        b = sympy.limit(sympy.log(absdh) / sympy.log(_T), _T, sympy.oo)
        if a.is_finite and b.is_finite:
            r = sympy.expand(b - _exponent(_NU, mu) * a)            # R ~ t^r(ν)
            rw = sympy.expand(r.subs(_NU, 1 + _W))
            if rw.is_negative:
                S10, why10 = sympy.Interval(1, sympy.oo), f"|ḣ|/h^e ~ t^({r}) with exponent < 0 for all ν ≥ 1"
            elif a == 0 and r.is_positive:
                S10, why10 = sympy.S.EmptySet, f"|ḣ|/h^e ~ t^({r}) → ∞ for every ν"
            elif a.is_negative:
                nu0 = sympy.solve(r, _NU)
                if len(nu0) == 1:
                    nu0 = nu0[0]
                    if (nu0 - 1).is_negative:
                        S10, why10 = sympy.Interval(1, sympy.oo), f"exponent of |ḣ|/h^e is {r} < 0 for ν ≥ 1"
                    else:
                        edge = _decide10(h, nu0, mu)
                        if edge.status is Status.UNDECIDED:
                            raise _Undecided(f"{lab} at the boundary ν = {nu0}: {edge.detail}")
                        S10 = sympy.Interval(nu0, sympy.oo, edge.status is not Status.EXACT, True)
                        why10 = (f"|ḣ|/h^e ~ t^({r}): exponent < 0 for ν > {nu0}, > 0 for ν < {nu0}; "
                                 f"at ν = {nu0}: {edge.detail}")
        if S10 is None:                      # direct limit with ν = 1 + w, w > 0 symbolic, and at ν = 1
            wp = sympy.Symbol("w", positive=True)
            try:
                L = sympy.limit(sympy.powsimp(absdh / h ** _exponent(1 + wp, mu)), _T, sympy.oo)
                at1 = _decide10(h, sympy.Integer(1), mu).status is Status.EXACT
            except (NotImplementedError, ValueError, TypeError):
                L, at1 = None, False
            if at1 and L is not None and L.is_finite and not L.has(sympy.Limit):
                S10, why10 = sympy.Interval(1, sympy.oo), f"|ḣ|/h^e → {L} as t → ∞ for every ν > 1, and {lab} holds at ν = 1"
            elif S11 is sympy.S.EmptySet:
                S10 = None
            else:
                return None, None, f"SymPy could not decide {lab} for symbolic ν (limit {L})"
    return S10, why10, None


def _admissible(mu, S10, why10, r11, S11):
    """[Result (10)/(15), Result (11), Result admissible set] from the two sets."""
    lab = _label10(mu)
    n10 = f"{lab} {_formula10(mu)}: set of ν ≥ 1"
    if S10 is None:
        r10 = Result("bound", n10, Status.UNDECIDED, None, f"SymPy could not decide {lab} (not needed: (11) fails)")
    elif S10 is sympy.S.EmptySet:
        r10 = Result("bound", n10, Status.FAILED, S10, f"fails {lab} for every ν ≥ 1: {why10}")
    else:
        r10 = Result("bound", n10, Status.EXACT, S10,
                     f"{lab} holds exactly for ν in {S10} (|ḣ|/h^e continuous on [0, ∞)): {why10}")

    # admissible set
    nA = f"admissible ν ≥ 1 ((5), {lab}, (11))"
    if S11 is sympy.S.EmptySet:
        return [r10, r11, Result("hypothesis", nA, Status.FAILED, S11,
                                 f"no ν ≥ 1 works: (11) fails for every ν ≥ 1 ({r11.detail})")]
    if S10 is sympy.S.EmptySet:
        return [r10, r11, Result("hypothesis", nA, Status.FAILED, S10,
                                 f"no ν ≥ 1 works: {lab} fails for every ν ≥ 1 ({r10.detail})")]
    lo, lo_open = S10.start, S10.left_open
    hi, hi_open = S11.end, S11.right_open
    A = sympy.Interval(lo, hi, lo_open, hi_open)
    nonempty = (sympy.Lt(lo, hi) if (lo_open or hi_open) else sympy.Le(lo, hi)) if hi is not sympy.oo else sympy.true
    cond = _condition(nonempty)
    if cond is sympy.true:
        return [r10, r11, Result("hypothesis", nA, Status.EXACT, {"nu": A, "condition": cond},
                                 f"the conditions hold exactly for ν in {A}")]
    if cond is sympy.false:
        return [r10, r11, Result("hypothesis", nA, Status.FAILED, {"nu": sympy.S.EmptySet, "condition": cond},
                                 f"no ν ≥ 1 works: {lab} needs ν in {S10}, (11) needs ν in {S11}, and they "
                                 f"do not meet")]
    return [r10, r11, Result("hypothesis", nA, Status.EXACT, {"nu": A, "condition": cond},
                             f"the conditions hold iff {cond}, then exactly for ν in {A}")]


def _nu_sets(h, mu):
    """[Result (11) set, Result (10)/(15) set, Result admissible set]."""
    a = sympy.limit(sympy.log(h) / sympy.log(_T), _T, sympy.oo)
    S11, r11 = _set11(h, a)
    S10, why10, undecided = _set10(h, mu, a, S11)
    if undecided is not None:
        lab = _label10(mu)
        return [Result("bound", f"{lab} {_formula10(mu)}: set of ν ≥ 1", Status.UNDECIDED, None, undecided), r11,
                Result("hypothesis", f"admissible ν ≥ 1 ((5), {lab}, (11))", Status.UNDECIDED, None,
                       f"{lab} undecided; (11) holds for ν in {S11}")]
    return _admissible(mu, S10, why10, r11, S11)


# ---------------------------------------------------------------- entry point

def decide_h_conditions(h, *, nu=None, mu=None, budget=10.0):
    """Decide conditions (5), (10) (or (15)) and (11) of paper 001 for a given h(t).

    Parameters
    ----------
    h : sympy expression
        h(t) in :data:`lkverify.t` (taken on t ≥ 0); other symbols must be declared positive
        (e.g. ``sympy.Symbol("beta", positive=True)``).  Floats are refused.
    nu : exact number ≥ 1 or None
        The ν of Theorem 1/2; ``None``: find the set of admissible ν ≥ 1.
    mu : exact number > 1 or None
        Given: Theorem 2, condition (15) with this μ instead of (10).
    budget : float
        Seconds; past it the remaining conditions are ``undecided``.

    Returns
    -------
    list of lkverify.report.Result
        With ``nu``: (5), (10)/(15) (value: the smallest L when found), (11) (value: the integral),
        and a summary.  Without: (5), the set of ν for (10)/(15), the set for (11), and the
        admissible set (value ``{"nu": Interval, "condition": ...}``).  ``exact`` = proved by SymPy,
        ``failed`` = refuted (reason in ``detail``), ``undecided`` = SymPy could not decide in time.

    Raises
    ------
    InputError
        For floats in h, ν or μ, parameters not declared positive, ν < 1 or μ ≤ 1.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import t
    >>> beta = sympy.Symbol("beta", positive=True)
    >>> res = decide_h_conditions((t + 1)**(-beta))
    >>> res[-1].status.value, res[-1].value["condition"], res[-1].value["nu"]
    ('exact', beta <= 1, Interval(1, 1/beta))
    >>> [r.status.value for r in decide_h_conditions((t + 1)**sympy.Rational(-1, 2), nu=3)]
    ['exact', 'exact', 'failed', 'failed']
    """
    h, nu, mu = _prepare(h, nu, mu)
    deadline = Deadline(budget)
    out: list[Result] = []
    lab = _label10(mu)
    steps = ["(5) h > 0, h → 0"]
    steps += ([f"{lab} {_formula10(mu)}", "(11) ∫_0^∞ h^ν = ∞"] if nu is not None else
              [f"{lab} {_formula10(mu)}: set of ν ≥ 1", "(11) ∫_0^∞ h^ν = ∞: set of ν ≥ 1",
               f"admissible ν ≥ 1 ((5), {lab}, (11))"])

    def undecided_rest(reason):
        for n in steps[len(out):]:
            out.append(Result("hypothesis", n, Status.UNDECIDED, None, reason))

    try:
        with deadline.enforced():
            r5 = _decide5(h)
            out.append(r5)
            if nu is not None:
                if r5.status is Status.FAILED and r5.value is None:      # h not positive: h^e meaningless
                    undecided_rest("not examined: h is not positive on t ≥ 0")
                else:
                    out.append(_decide10(h, nu, mu))
                    out.append(_decide11(h, nu))
            elif r5.status is Status.FAILED:
                return out + [Result("hypothesis", steps[-1], Status.FAILED, sympy.S.EmptySet,
                                     f"no ν ≥ 1 works: {r5.detail}")]
            elif r5.status is Status.UNDECIDED:
                undecided_rest(f"not examined: {r5.detail}")
            else:
                out.extend(_nu_sets(h, mu))
    except BudgetExceeded:
        undecided_rest(f"time budget of {budget:g} s exhausted before SymPy decided it")
    except _Undecided as exc:
        undecided_rest(str(exc))
    except (NotImplementedError, ValueError, TypeError) as exc:
        undecided_rest(f"SymPy could not decide it ({type(exc).__name__}: {exc})")
    if nu is not None:
        sts = [r.status for r in out]
        st = (Status.FAILED if Status.FAILED in sts else Status.UNDECIDED if Status.UNDECIDED in sts
              else Status.EXACT)
        thm = "Theorem 1" if mu is None else f"Theorem 2 (μ = {mu})"
        bad = [r.name.split()[0] for r in out if r.status is not Status.EXACT]
        out.append(Result("hypothesis", f"conditions of {thm} on h, ν = {nu}", st, None,
                          f"(5), {lab}, (11) hold for ν = {nu}" if st is Status.EXACT
                          else f"{st.value}: {', '.join(bad)}"))
    return out


class ConditionsOnH:
    """The conditions on h of Theorem 1 as a hypothesis of the catalogue item.

    At the run's h and ν it decides (5), (10) and (11) with :func:`decide_h_conditions`;
    when they fail at that ν it also says for which ν ≥ 1 they hold, if any.

    Parameters
    ----------
    name : str
    h : sympy UndefinedFunction
        The coefficient parameter h(t) of the system.
    nu : sympy.Symbol
        The parameter ν.
    reference : str

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2017.equations import P, h, nu
    >>> cond = ConditionsOnH("(5), (10), (11) on h", h, nu)
    >>> sub = P.substitution(P.resolve({}, use_defaults=True))        # h = (1+t)^(−7/8), ν = 1
    >>> cond.evaluate(sub).status.value
    'exact'
    >>> bad = P.substitution(P.resolve({"h": "(1+t)**(-6/5)"}, use_defaults=True))
    >>> r = cond.evaluate(bad)
    >>> r.status.value, "no ν ≥ 1 works" in r.detail
    ('failed', True)
    """

    def __init__(self, name: str, h, nu, *, mu=None, reference: str = ""):
        self.name = name
        self.h = h
        self.nu = nu
        self.mu = mu  # Theorem 2: (15) with the order μ of the damping, instead of (10)
        self.reference = reference

    def symbols(self) -> set:
        """The parameters the conditions are stated in (h and ν, and μ for (15))."""
        return {self.h, self.nu} | ({self.mu} if self.mu is not None and not sympy.sympify(self.mu).is_number else set())

    def _value_of(self, substitution, key):
        for k, v in substitution.items():
            if k == key or str(k) == str(key):
                return v
        return None

    def evaluate(self, substitution, *, budget=None) -> Result:
        """The Result of the conditions at the substituted h and ν (``hypothesis`` kind)."""
        lam = self._value_of(substitution, self.h)
        nu_value = self._value_of(substitution, self.nu)
        if lam is None or nu_value is None:
            return Result("hypothesis", self.name, Status.UNDECIDED, None,
                          "h or ν has no value: pass --set h=… and --set nu=…")
        h_expr = lam(t) if isinstance(lam, sympy.Lambda) else sympy.sympify(lam)
        mu_value = None if self.mu is None else self.mu if sympy.sympify(self.mu).is_number \
            else self._value_of(substitution, self.mu)
        if self.mu is not None and mu_value is None:
            return Result("hypothesis", self.name, Status.UNDECIDED, None, "μ has no value: pass --set mu=…")
        seconds = 10.0 if budget is None else max(float(budget), 0.5)
        parts = decide_h_conditions(h_expr, nu=nu_value, mu=mu_value, budget=seconds / 2)
        summary = parts[-1]
        detail = (f"for h = {h_expr}, ν = {nu_value}" + (f", μ = {mu_value}" if mu_value is not None else "") + ": "
                  + "; ".join(f"{p.name}: {p.status.value} ({p.detail})" for p in parts[:-1]))
        if summary.status is Status.FAILED:
            which = decide_h_conditions(h_expr, nu=None, mu=mu_value, budget=seconds / 2)[-1]
            detail += f"; for other ν: {which.detail}"
        value = {"h": str(h_expr), "nu": str(nu_value),
                 "parts": {p.name: {"status": p.status.value, "value": _plain(p.value)} for p in parts[:-1]}}
        return Result("hypothesis", self.name, summary.status, value, detail)


def _plain(value):
    """A condition's value for JSON: numbers as they are, SymPy sets and expressions as text."""
    if value is None or isinstance(value, (int, float, str)):
        return value
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return str(value)


def _corollary1_check(v, *, budget=60.0):
    """Corollary 1: for h = (t+1)^{−β} the conditions (5), (10), (11) hold iff β ≤ 1, (14)."""
    beta = sympy.Symbol("beta", positive=True)
    parts = decide_h_conditions((t + 1) ** (-beta), budget=min(float(budget), 30.0))
    found = parts[-1]
    out = [Result("hypothesis", f"h = (t+1)^(−β): {p.name}", p.status, _plain(p.value), p.detail) for p in parts]
    if found.status is Status.EXACT:
        condition = found.value["condition"]
        same = sympy.simplify(sympy.Equivalent(condition, beta <= 1)) is sympy.true
        status = Status.EXACT if same else Status.FAILED
        detail = (f"the conditions derived for h = (t+1)^(−β) are {condition}, "
                  + ("the paper's (14) β ≤ 1" if same else "not the paper's (14) β ≤ 1"))
    else:
        status, detail = found.status, f"not decided: {found.detail}"
    out.append(Result("hypothesis", "Corollary 1: (10), (11) for h = (t+1)^(−β) ⇔ (14) β ≤ 1", status,
                      {"derived": _plain(found.value)}, detail))
    for b in (sympy.Rational(7, 8), sympy.Rational(8, 7)):  # the two dampings of section 6
        r = decide_h_conditions((t + 1) ** (-b), budget=min(float(budget), 15.0))[-1]
        expect = b <= 1
        holds = r.status is Status.EXACT
        # the statement checked is "(10), (11) hold iff β ≤ 1" at this β: proved either way it goes
        status = (Status.UNDECIDED if r.status is Status.UNDECIDED else
                  Status.EXACT if holds == expect else Status.FAILED)
        out.append(Result("hypothesis", f"section 6: β = {b}", status, _plain(r.value),
                          f"{'the conditions hold' if holds else 'no ν ≥ 1 works'} for β = {b}, as (14) "
                          f"{'says' if holds == expect else 'does not say'}: {r.detail}"))
    return out


def _make_corollary1():
    from lkverify import Check

    from .equations import PAPER, P

    return Check("corollary1", parameters=P, checks=[_corollary1_check], relevant=(), paper=PAPER,
                 title="Corollary 1: h = (t+1)^(−β) satisfies (10), (11) iff β ≤ 1 (14), decided symbolically")


corollary1 = _make_corollary1()
