"""Time-varying rates: the conclusion V̇ ≤ −α h^ν(t) V of a theorem with a vanishing coefficient h(t).

Papers with a damping h(t)·D that tends to 0 (paper 001) do not get an autonomous W: their
V̇ ≤ W has coefficients that are powers of h(t).  Here h(t) is a measure of the steps
(``norm_measure("hh", Matrix([h(t)]))``, h ≥ 0 by its definition |h|), so the bounds
V ≥ L, V ≤ U, V̇ ≤ W are sums of monomials in the state measures whose coefficients are
sums c_k·h^{p_k}.  The pieces:

* :class:`UpperBound` — a rewrite: a measure replaced by an upper bound that a decided
  condition gives (e.g. (10) of paper 001, |ḣ| ≤ L h^{(3−ν)/2}, makes |ḣ|‖ω‖ ≤ L h^{(3−ν)/2}‖ω‖);
  the mirror of :class:`~lkverify.certify.steps.rewrites.LowerBound`.
* :func:`sup_on` — an upper bound of Σ c_k x^{p_k} over 0 < x ≤ H, term by term (exact).
* :func:`sup_in_t` — sup_{t ≥ t0} of a function of t, exactly (monotone, or critical points).
* :class:`TimeVaryingRate` — the conclusion: with H = sup_{t≥t0} h(t) (computed, not
  assumed) it proves, for every monomial m of the state measures,

      W_m(h) + α h^ν U_m(h) ≤ 0   for all 0 < h ≤ H,

  hence V̇ ≤ W ≤ −α h^ν U ≤ −α h^ν V on the region; with L_m(h) ≥ α1 > 0 on the pure squares
  it gives α1‖x(t)‖² ≤ V(t) ≤ V(t0) exp(−α∫_{t0}^t h^ν), and solutions starting in
  ‖x(t0)‖ < δ1√(α1/α2) stay in the region.  Side conditions on h (e.g. ∫h^ν = ∞ for
  attractivity) are decided by a callable and are part of the link.

Examples
--------
>>> import sympy
>>> x = sympy.Symbol("x", positive=True)
>>> sup_on(-2 * x + 3 * x**2, x, sympy.Rational(1, 2))     # −2x ≤ 0, 3x² ≤ 3/4
(3/4, None)
>>> sup_on(x**-1, x, 1)[1]                                  # unbounded as x → 0
'the term 1/x (a positive coefficient, a negative power) is unbounded as x → 0'
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import sympy

from ...declare.symbols import t as _t
from ...report.results import Result
from ...status import Status
from .chain import coefficient_sign, collect_monomials
from .rewrites import LowerBound

__all__ = ["TimeVaryingRate", "UpperBound", "sup_in_t", "sup_on"]


@dataclasses.dataclass(frozen=True)
class UpperBound(LowerBound):
    """A measure m replaced by an upper bound u ≥ m that a decided condition gives.

    ``certify(ctx)`` decides the condition at the checked values (a
    :class:`~lkverify.certify.steps.rules.Condition`: exact, certified, failed or undecided);
    ``bound`` is u in the other measures.  The bound so far must be nondecreasing in m for an
    upper bound (nonincreasing for a lower one), checked structurally.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.rules import Condition, Context
    >>> from lkverify.status import Status
    >>> P = Parameters(); x = Vector("x", 2); a, n = norm_measure("a", x(t)), norm_measure("n", x(t) / 2)
    >>> ctx = Context(System([Equation(x, [Term(-x(t))])], parameters=P), P.resolve({}), {"a": a, "n": n})
    >>> half = lambda ctx: Condition("‖x/2‖ ≤ ‖x‖", Status.EXACT)
    >>> UpperBound("n", a.symbol, half, "‖x/2‖ ≤ ‖x‖").rewrite(3 * n.symbol**2, ctx).bound
    3*a**2
    >>> UpperBound("n", a.symbol, half, "‖x/2‖ ≤ ‖x‖").rewrite(-3 * n.symbol**2, ctx).status.value
    'undecided'
    """

    text: str = "a condition"
    name = "an upper bound from a decided condition"
    side = "upper"


# ---- bounds over 0 < x ≤ H, term by term -----------------------------------------------------------
def _powers(expr, x):
    """[(c, p)] with expr = Σ c·x^p, c free of x and p an exact number; None if expr is not of that form.

    A floating-point exponent is not of that form: it is never rounded to a rational here.
    """
    out = []
    for term in sympy.Add.make_args(sympy.expand(sympy.powsimp(sympy.expand(expr), force=True))):
        c, p = term.as_coeff_exponent(x)
        if c.has(x) or not sympy.sympify(p).is_number or c.free_symbols or sympy.sympify(p).has(sympy.Float):
            return None
        out.append((c, p))
    return out


def sup_on(expr, x, H):
    """(s, why): s ≥ sup of expr over 0 < x ≤ H, bounded term by term; s None and why when a term is unbounded.

    expr = Σ c_k x^{p_k} with numeric c_k, p_k: c x^p ≤ c H^p when c > 0, p ≥ 0 or c < 0,
    p ≤ 0; ≤ 0 when c < 0, p > 0; unbounded when c > 0, p < 0.  The signs of the c_k are
    decided exactly (rationals) or in arb.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x", positive=True)
    >>> sup_on(-x ** sympy.Rational(-1, 2) + 1, x, 4)           # −x^{−1/2} ≤ −1/2
    (1/2, None)
    """
    terms = _powers(expr, x)
    if terms is None:
        return None, f"{expr} is not a sum of numeric multiples of powers of {x}"
    total = sympy.S.Zero
    for c, p in terms:
        sign, _ = coefficient_sign(c)
        if sign is None:
            return None, f"the sign of {c} is not decided"
        if sign == 0:
            continue
        if p == 0:
            total += c
        elif sign > 0 and p < 0:
            return None, f"the term {c * x**p} (a positive coefficient, a negative power) is unbounded as {x} → 0"
        elif sign > 0 or p < 0:
            total += c * H**p
        # c < 0, p > 0: the term is ≤ 0, its sup (x → 0)
    return total, None


def inf_on(expr, x, H):
    """(s, why): s ≤ inf of expr over 0 < x ≤ H (:func:`sup_on` of −expr)."""
    s, why = sup_on(-sympy.sympify(expr), x, H)
    return (None, why) if s is None else (-s, None)


def sup_in_t(f, t0=0):
    """(H, detail): H = sup_{t ≥ t0} f(t), exactly; H None when it is not decided.

    f nonincreasing on t ≥ t0 (the sign of f′ decided by SymPy): H = f(t0); otherwise the
    largest of f(t0), lim_{t→∞} f and f at the critical points, when ``solveset`` finds them all.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import t
    >>> sup_in_t((1 + t) ** sympy.Rational(-7, 8))[0]
    1
    >>> sup_in_t(t * sympy.exp(-t))[0]
    exp(-1)
    """
    u = sympy.Symbol("u", nonnegative=True)
    g = sympy.sympify(f).subs(_t, t0 + u)
    dg = sympy.diff(g, u)
    if (-dg).is_nonnegative or sympy.simplify(-dg).is_nonnegative:
        return g.subs(u, 0), f"f′ ≤ 0 for t ≥ {t0}, so sup f = f({t0})"
    try:
        crit = sympy.solveset(dg, u, sympy.Interval.open(0, sympy.oo))
        lim = sympy.limit(g, u, sympy.oo)
    except (NotImplementedError, ValueError, TypeError) as exc:
        return None, f"SymPy could not find sup f ({type(exc).__name__})"
    if not isinstance(crit, sympy.FiniteSet) and crit is not sympy.S.EmptySet:
        return None, f"the critical points of f are not all found ({crit})"
    if lim.has(sympy.Limit) or lim is sympy.oo:
        return None, f"lim f = {lim}: f is not bounded, or the limit is not decided"
    cands = [g.subs(u, 0), lim] + [g.subs(u, c) for c in crit]
    return sympy.simplify(sympy.Max(*cands)), f"the largest of f({t0}), lim f and f at {len(crit)} critical points"


def _weakest(statuses):
    for s in (Status.FAILED, Status.UNDECIDED, Status.CERTIFIED):
        if s in statuses:
            return s
    return Status.EXACT


def _decided_sign(value, statuses):
    """The sign of a numeric value (exact for rationals, arb otherwise), its status appended to ``statuses``."""
    sign, st = coefficient_sign(sympy.sympify(value))
    statuses.append(st if sign is not None else Status.UNDECIDED)
    return sign


@dataclasses.dataclass(frozen=True)
class TimeVaryingRate:
    """The conclusion V̇ ≤ −α h^ν(t) V and its envelope, from checked V ≥ L, V ≤ U, V̇ ≤ W with h-dependent coefficients.

    Parameters
    ----------
    point : tuple of str
        The state measures x(t) (norms that vanish exactly at the equilibrium), e.g. ("w", "e1", "e2").
    coefficient : str
        The measure that is the time-varying coefficient h(t) (a ``norm`` measure of ``Matrix([h(t)])``).
    power : sympy expression
        ν of the rate h^ν (in the parameters); it must be a number at the checked values.
    rate : sympy expression
        α of V̇ ≤ −α h^ν V (a parameter: the claimed rate constant, checked as given).
    conditions : callable, optional
        ``conditions(values)`` → sequence of :class:`~lkverify.certify.steps.rules.Condition`
        (e.g. ∫h^ν = ∞, which makes the envelope tend to 0): each must be exact or certified.
    t0 : number
        The initial time; H = sup_{t ≥ t0} h(t) is computed exactly (:func:`sup_in_t`).
    lam : number, optional
        λ ≥ 1 of the power rate V̇ ≤ −α h^ν V^λ (default 1, the rate above).  For λ ≠ 1, U must be
        Σ_k u_k(h) x_k² (pure squares of the point measures) and U is replaced in the test by the bound
        V^λ ≤ U^λ ≤ n^{λ−1} Σ_k ū_k^λ x_k^{2λ} (ū_k = sup_{0<h≤H} u_k, n squares; 0 ≤ V by V ≥ L;
        convexity of y^λ): W_m + α h^ν n^{λ−1} ū_k^λ [m = x_k^{2λ}] ≤ 0 for every monomial m.  The
        envelope is then algebraic, V(t) ≤ V(t0)(1 + α(λ−1)V(t0)^{λ−1}∫_{t0}^t h^ν)^{−1/(λ−1)}.

    The check, all exact or in arb: H exists; for every monomial m of the state measures,
    L_m(h) ≥ 0 and each pure square x_i² of a point measure has inf_{0<h≤H} L_m ≥ α1 > 0;
    U has no constant term; W_m(h) + α h^ν U_m(h) ≤ 0 for 0 < h ≤ H — divided by the
    smallest power of h in it, then bounded term by term (:func:`sup_on`).  Reported: α1,
    α2 = the largest sup of U's squares, the largest α the test allows, and the region of
    attraction ‖x(t0)‖ < δ2 = δ1√(α1/α2) (δ1 the region's bound on the point measures) in
    which the envelope α1‖x(t)‖² ≤ V(t) ≤ V(t0) exp(−α∫_{t0}^t h^ν) holds.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps import Rayleigh, Region, TermBound, TermwiseBound, norm_measure
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t)); N = n.symbol
    >>> hm = norm_measure("hh", sympy.Matrix([1 / (1 + t)])); H_ = hm.symbol
    >>> sys_ = System([Equation(x, [Term(-x(t) / (1 + t))])], parameters=P)
    >>> def step(role, c, factor, rel="<="):
    ...     rule = Rayleigh(x(t), sympy.eye(2), factor=factor, eigenvalue=1, norm_squared=N**2)
    ...     return TermwiseBound(role, None, sys_, "terms", [TermBound("T", c * N**2, rule)], c * N**2, [n, hm],
    ...                          relation=rel, region=Region({n: 1}), role=role, witness_time=1,
    ...                          terms=(Term(factor.subs(H_, 1 / (1 + t)) * x(t).dot(x(t)), text="T"),))
    >>> steps = {s.role: (s, s.check(P.resolve({}))) for s in (step("lower", 1, sympy.S.One, ">="),
    ...          step("upper", 1, sympy.S.One), step("vdot", -2 * H_, -2 * H_))}
    >>> rows, status, detail = TimeVaryingRate(("n",), "hh", 1, 2).certify(steps, P.resolve({}))
    >>> status.value, detail.split(";")[0]
    ('exact', 'V̇ ≤ −2·h^1 V for 0 < h ≤ H = 1 (h = 1/(t + 1), t ≥ 0)')
    >>> TimeVaryingRate(("n",), "hh", 1, 3).certify(steps, P.resolve({}))[2].split(":")[0]
    'fails at the monomial n**2'
    """

    point: tuple
    coefficient: str
    power: object
    rate: object
    conditions: Callable | None = None
    t0: object = 0
    lam: object = 1

    @property
    def link(self):
        """The link's name: (12) for λ = 1, the power rate V̇ ≤ −α h^ν V^λ and its algebraic envelope otherwise."""
        if sympy.sympify(self.lam) == 1:
            return "(12) V̇ ≤ −α h^ν(t) V on the region and the envelope V(t) ≤ V(t0) exp(−α∫h^ν)"
        return (f"V̇ ≤ −α h^ν(t) V^λ (λ = {self.lam}) on the region and the envelope "
                f"V(t) ≤ V(t0)(1 + α(λ−1)V(t0)^(λ−1)∫h^ν)^(−1/(λ−1))")

    @property
    def row(self):
        """The name of the rate's result row."""
        return "(12) V̇ ≤ −α7 h^ν V" if sympy.sympify(self.lam) == 1 else "V̇ ≤ −α8 h^ν V^λ"

    def certify(self, steps, values, *, budget=None, progress=None, **_):
        """(results, status, detail): the rate inequality, the envelope's constants, the side conditions.

        A failing side condition (e.g. ∫h^ν < ∞) fails the link but the rate and the envelope
        are still reported (they hold; they only do not tend to 0).
        """
        conds = list(self.conditions(values)) if self.conditions is not None else []
        rows, status, detail = self._certify(steps, values)
        if not rows:
            rows = [Result("region", self.row, status, None, detail)]
        rows += [Result("hypothesis", c.text, c.status, None, c.detail) for c in conds]
        bad = [c for c in conds if not c.status.is_proof]
        if bad:
            c = bad[0]
            detail = f"side condition {c.text}: {c.status.value} ({c.detail}); " + detail
            status = Status.FAILED if Status.FAILED in (c.status, status) else _weakest([c.status, status])
        elif status.is_proof:
            status = _weakest([status] + [c.status for c in conds])
            detail += "".join(f"; {c.text}" for c in conds)
        return rows, status, detail

    def _certify(self, steps, values):
        from ...declare.parameters import apply_substitution

        (ls, lres), (us, ures), (ws, wres) = (steps[r] for r in ("lower", "upper", "vdot"))
        by_name = {m.name: m for s_ in (ls, us, ws) for m in s_.measures}
        unknown = [p for p in (*self.point, self.coefficient) if p not in by_name]
        if unknown:
            return [], Status.UNDECIDED, f"the measures {', '.join(unknown)} are not measures of the steps"
        sub = ws.system.parameters.substitution(values)
        at = lambda e: apply_substitution(sympy.sympify(e), sub)  # noqa: E731
        x = by_name[self.coefficient].symbol
        tn = sympy.Symbol(str(_t), nonnegative=True)  # time runs on t ≥ 0: |h| of a power of t + 1 simplified
        h_of_t = at(by_name[self.coefficient].definition).xreplace({_t: tn}).xreplace({tn: _t})
        nu_, alpha = at(self.power), at(self.rate)
        statuses: list = []
        if not (nu_.is_number and alpha.is_number):
            return [], Status.UNDECIDED, f"ν = {nu_} and α = {alpha} must be numbers at the checked values"
        if _decided_sign(alpha, statuses) != 1:
            return [], Status.FAILED, f"the rate α = {alpha} is not positive"
        H, how = sup_in_t(h_of_t, self.t0)
        if H is None:
            return [], Status.UNDECIDED, f"sup_(t≥{self.t0}) h(t) of h = {h_of_t} not decided: {how}"
        if H is sympy.oo or not H.is_number:
            return [], Status.FAILED, f"h = {h_of_t} is not bounded on t ≥ {self.t0}: {how}"
        syms = {m.symbol for s_ in (ls, us, ws) for m in s_.measures} - {x}
        point = [by_name[p].symbol for p in self.point]
        L, U, W = (collect_monomials(r.rhs, syms) for r in (lres, ures, wres))
        alpha1, why = self._alpha1(L, point, x, H, statuses)
        if why:
            return [], Status.FAILED if "undecided" not in why else Status.UNDECIDED, why
        if U.get(sympy.S.One, 0) != 0:
            return [], Status.FAILED, f"U has the constant term {U[sympy.S.One]}, so U(0) ≠ 0"
        lam = at(self.lam)
        if lam != 1:
            U_lam, why = self._power_of_u(U, point, x, H, lam, statuses)
            if why:
                return [], Status.FAILED if "not decided" not in why else Status.UNDECIDED, why
        best, why = self._rate(U if lam == 1 else U_lam, W, x, nu_, alpha, H, statuses)
        if why:
            return [], Status.FAILED if "not decided" not in why else Status.UNDECIDED, why
        status = _weakest(statuses)
        alpha2 = self._alpha2(U, point, x, H)
        region = ws.region.at(sub) if ws.region is not None else None
        bounds = [region.bound_of(by_name[p], {}) for p in self.point] if region is not None else []
        d1 = min((b for b in bounds if b is not None), key=lambda b: float(b), default=None)
        delta2 = None if d1 is None or alpha2 is None else d1 * sympy.sqrt(alpha1 / alpha2)
        h_txt = f"h = {h_of_t}, t ≥ {self.t0}"
        if lam == 1:
            rate_txt, test_txt, env_txt = f"V̇ ≤ −{alpha}·h^{nu_} V", "W + α h^ν U ≤ 0", f"V(t0)exp(−{alpha}∫h^{nu_})"
        else:
            rate_txt, test_txt = f"V̇ ≤ −{alpha}·h^{nu_} V^{lam}", f"W + α h^ν n^(λ−1)Σ ū_k^λ x_k^(2λ) ≤ 0 (λ = {lam})"
            env_txt = f"V(t0)(1 + {alpha}·({lam}−1)V(t0)^({lam}−1)∫h^{nu_})^(−1/({lam}−1))"
        detail = (f"{rate_txt} for 0 < h ≤ H = {H} ({h_txt}); {test_txt} coefficient-wise "
                  f"({status.value}; the largest α this test allows: {float(best):.4g}); α1 = {float(alpha1):.4g}"
                  + (f", α2 = {float(alpha2):.4g}; envelope α1‖x(t)‖² ≤ V(t) ≤ {env_txt} for "
                     f"‖x(t0)‖ < δ2 = {float(delta2):.4g}" if delta2 is not None else ""))
        value = {"alpha": str(alpha), "nu": str(nu_), "H": str(H), "alpha1": float(alpha1),
                 "alpha2": None if alpha2 is None else float(alpha2), "alpha_largest": float(best),
                 "delta2": None if delta2 is None else float(delta2), "lam": str(lam)}
        rows = [Result("region", self.row, status, value, detail)]
        if delta2 is not None:
            name = "envelope α1‖x(t)‖² ≤ V(t) ≤ V(t0)exp(−α7∫h^ν)" if lam == 1 else \
                "envelope α1‖x(t)‖² ≤ V(t) ≤ V(t0)(1 + α8(λ−1)V(t0)^(λ−1)∫h^ν)^(−1/(λ−1))"
            rows.append(Result("envelope", name, status, value,
                               f"for ‖x(t0)‖ < δ2 = {float(delta2):.4g}: the solution stays in the region and "
                               f"α1‖x(t)‖² ≤ V(t) ≤ {env_txt.replace('∫', '∫_(t0)^t ')}, α1 = {float(alpha1):.4g}"))
        return rows, status, detail

    def _power_of_u(self, U, point, x, H, lam, statuses):
        """({x_k^{2λ}: n^{λ−1} ū_k^λ}, why): the bound of U^λ that replaces U in the test when λ ≠ 1.

        U = Σ_k u_k(h) x_k² must have only pure squares of point measures (else why says so);
        ū_k = sup_{0<h≤H} u_k (:func:`sup_on`, ≥ 0), and for λ ≥ 1, by convexity of y ↦ y^λ
        (power means), 0 ≤ V ≤ U ≤ Σ ū_k x_k² gives V^λ ≤ (Σ_k ū_k x_k²)^λ ≤ n^{λ−1} Σ_k ū_k^λ x_k^{2λ},
        n the number of squares.  V ≥ 0 is V ≥ L ≥ 0 (checked before).
        """
        if not (lam.is_number and lam.is_real and lam >= 1):
            return None, f"the power λ = {lam} of V^λ must be a number ≥ 1 (not decided otherwise)"
        extra = set(U) - {p**2 for p in point}
        if extra:
            return None, f"U^λ is bounded only for U a sum of squares of the point measures; U has {sorted(extra, key=str)}"
        n = len(U)
        out = {}
        for mono, c in U.items():
            s, why = sup_on(c, x, H)
            if s is None:
                return None, f"the coefficient of {mono} in U is not bounded for 0 < h ≤ H: {why}"
            if _decided_sign(s, statuses) is None:
                return None, f"the sign of sup of U's coefficient of {mono} not decided"
            out[sympy.powdenest(mono ** lam, force=True)] = n ** (lam - 1) * sympy.Max(s, 0) ** lam
        return out, None

    def _alpha1(self, L, point, x, H, statuses):
        """(α1, why): the smallest inf over 0 < h ≤ H of L's pure squares; why names a failing monomial."""
        infs = {}
        for mono, c in L.items():
            low, why = inf_on(c, x, H)
            if low is None:
                return None, f"V ≥ L: the coefficient of {mono} is not bounded below for 0 < h ≤ H: {why}"
            sign = _decided_sign(low, statuses)
            if sign is None:
                return None, f"V ≥ L: the sign of the coefficient of {mono} undecided"
            if mono.free_symbols and sign < 0:
                return None, f"V ≥ L fails: L has the monomial {mono} with inf coefficient {float(low):.4g} < 0"
            infs[mono] = low
        for p in point:
            low = infs.get(p**2)
            if low is None or _decided_sign(low, statuses) != 1:
                return None, f"V ≥ L fails: L has no square {p}**2 with a positive coefficient for 0 < h ≤ H"
        return min((infs[p**2] for p in point), key=lambda v: float(v)), None

    def _alpha2(self, U, point, x, H):
        """The largest sup over 0 < h ≤ H of U's coefficients, if U has only pure squares of point measures."""
        if set(U) - {p**2 for p in point}:
            return None
        sups = [sup_on(c, x, H)[0] for c in U.values()]
        return None if any(s is None for s in sups) else max(sups, key=lambda v: float(v))

    def _rate(self, U, W, x, nu_, alpha, H, statuses):
        """(largest α, why): W_m + α h^ν U_m ≤ 0 for every monomial; why names the first that fails."""
        best = sympy.oo
        for mono in sorted(set(U) | set(W), key=str):
            if not mono.free_symbols:
                continue
            wm, um = W.get(mono, sympy.S.Zero), U.get(mono, sympy.S.Zero) * x**nu_
            g = sympy.expand(wm + alpha * um)
            parts = [_powers(e, x) for e in (wm, um)]
            if any(p_ is None for p_ in parts):
                return None, f"the coefficient {g} of {mono} is not a sum of powers of {x}: not decided"
            q = min((p for c, p in parts[0] + parts[1] if c != 0), default=0)  # the lowest power of h in W_m, h^νU_m
            s, why = sup_on(sympy.expand(g / x**q), x, H)
            if s is None:
                return None, f"fails at the monomial {mono}: W + α h^ν U has {why}"
            sign = _decided_sign(s, statuses)
            if sign is None:
                return None, f"the sign of the bound {s} at {mono} not decided"
            if sign > 0:
                return None, (f"fails at the monomial {mono}: sup over 0 < h ≤ {H} of (W + {alpha}·h^{nu_}U)/h^{q} "
                              f"is bounded only by {float(s):.4g} > 0 (W_m = {wm}, U_m = {U.get(mono, 0)})")
            sw, _ = sup_on(sympy.expand(wm / x**q), x, H)
            su, _ = sup_on(sympy.expand(um / x**q), x, H)
            if sw is not None and su is not None and float(su) > 0:
                best = min(best, -sw / su, key=lambda v: float(v))
        return best, None
