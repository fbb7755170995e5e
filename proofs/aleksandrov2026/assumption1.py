"""Assumption 1 of paper 000 on the memory kernel G(ζ) = g(ζ)I, decided symbolically.

Assumption 1 (section 4) asks of the kernel G of the PID loop (13):

    1)  ∫_0^{+∞} ‖G(ξ)‖ dξ < +∞,
    2)  ∫_ζ^{+∞} ‖G(ξ)‖ dξ ≤ σ ‖G(ζ)‖  for ζ ≥ 0, with a constant σ > 0.

With G = g(ζ)I (Remark 3, g continuous on [0, +∞)) ‖G‖ = |g|·‖I‖ and ‖I‖ cancels from both sides
of 2), so for every norm the assumption reads a) ∫_0^∞ |g| < ∞ and b) ∫_ζ^∞ |g| ≤ σ|g(ζ)|.  The
smallest σ is sup_{ζ ≥ 0} R(ζ), R(ζ) = ∫_ζ^∞ |g| / |g(ζ)|; for g = e^{−aζ} (Remark 2) R ≡ 1/a.

How it is decided (SymPy only, no floating point decides anything):

* g continuous on [0, ∞): ``continuous_domain``.
* the sign of g: SymPy's assumptions on ζ ≥ 0, else the zeros of g on [0, ∞) by ``solveset``.
  A zero ζ0 refutes b): |g(ζ0)| = 0 while ∫_{ζ0}^∞ |g| > 0, shown by a point ζ1 > ζ0 with
  g(ζ1) ≠ 0 (g is continuous).  Without zeros |g| = ±g on the whole half-line.
* a): ``integrate(|g|, (ζ, 0, oo))``; if inconclusive, limit comparison with ζ^q.
* the tail T(ζ) = ∫_0^∞|g| − ∫_0^ζ|g| (or ``integrate`` from ζ to ∞), checked exactly:
  T' = −|g| and T → 0 as ζ → ∞.
* b): R = T/|g| is continuous on [0, ∞).  ``limit(R, ζ, oo) = ∞`` refutes it, with a concrete ζ
  where R(ζ) > σ (a closed form ζ(σ) from ``solveset`` when there is one); a finite limit proves
  it (R is bounded).  The exact σ = sup R is the largest of R(0), the limit and R at the critical
  points, when the sign of R' is known or ``solveset`` finds them all (not trusted for
  trigonometric R').
"""

from __future__ import annotations

import dataclasses

import sympy
from sympy.calculus.util import continuous_domain

from lkverify import InputError, zeta
from lkverify.declare import parse_value
from lkverify.options import BudgetExceeded, Deadline
from lkverify.report import Result
from lkverify.status import Status

__all__ = ["Assumption1", "Assumption1Result", "decide_assumption1"]

_Z = sympy.Symbol("zeta", nonnegative=True)      # ζ restricted to ζ ≥ 0 (printed as zeta)
_S = sympy.Symbol("s", nonnegative=True)         # the integration variable of the tail
_SIGMA = sympy.Symbol("sigma", positive=True)    # a proposed σ > 0, kept symbolic
_HALF_LINE = sympy.Interval(0, sympy.oo)


class _Undecided(Exception):
    """SymPy could not decide a step (the message says which)."""


@dataclasses.dataclass(frozen=True)
class Assumption1Result:
    """The decision of Assumption 1 for one kernel g.

    Attributes
    ----------
    status : Status
        ``exact``: proved (with a σ > 0, or at the given σ); ``failed``: refuted, the reason in
        ``detail`` and the point in ``witness``; ``undecided``: SymPy could not decide (``tried``).
    g : sympy expression
        The kernel, in :data:`lkverify.zeta`.
    sigma : sympy expression or None
        The smallest σ, sup_{ζ ≥ 0} R(ζ), when found in closed form (exact).
    integral : sympy expression or None
        ∫_0^∞ |g| dζ (``oo`` when it diverges).
    tail : sympy expression or None
        T(ζ) = ∫_ζ^∞ |g(s)| ds.
    ratio : sympy expression or None
        R(ζ) = T(ζ) / |g(ζ)|.
    witness : sympy expression, sympy.Lambda or None
        Where it fails: the ζ; for R → ∞ without a given σ, ζ(σ) as a ``Lambda`` in σ.
    given_sigma : sympy expression or None
        The σ the caller asked about, if any.
    detail : str
        One readable sentence.
    tried : tuple of str
        The steps SymPy was asked to do.

    Examples
    --------
    >>> r = decide_assumption1("exp(-2*zeta)")
    >>> r.status.value, r.sigma, r.holds
    ('exact', 1/2, True)
    """

    status: Status
    g: sympy.Expr
    sigma: sympy.Expr | None = None
    integral: sympy.Expr | None = None
    tail: sympy.Expr | None = None
    ratio: sympy.Expr | None = None
    witness: object = None
    given_sigma: sympy.Expr | None = None
    detail: str = ""
    tried: tuple = ()

    @property
    def holds(self) -> bool:
        """True when the assumption is proved (``exact``)."""
        return self.status is Status.EXACT


# ---------------------------------------------------------------- input

def _refuse_floats(name, expr, how):
    floats = expr.atoms(sympy.Float)
    if floats:
        raise InputError(f"{name}: expected an exact SymPy expression (integers, Rationals, symbols), got the "
                         f"float {sorted(floats, key=str)[0]} in {expr}; write it exactly, e.g. {how}")


def _prepare_g(g):
    if isinstance(g, str):
        g = parse_value(g, name="g", variables={"zeta": zeta, "t": zeta})
    if isinstance(g, sympy.Lambda):
        g = g(zeta)
    if isinstance(g, (sympy.MatrixBase, bool, sympy.logic.boolalg.Boolean)):
        raise InputError(f"g: expected a scalar function of zeta, got {g!r}; e.g. exp(-2*zeta)")
    try:
        g = sympy.sympify(g, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"g: expected a SymPy expression in lkverify.zeta, got {g!r}; e.g. exp(-2*zeta)") from exc
    if not isinstance(g, sympy.Expr):
        raise InputError(f"g: expected a scalar expression in lkverify.zeta, got {g!r}; e.g. exp(-2*zeta)")
    _refuse_floats("g", g, "exp(-zeta/2) instead of exp(-0.5*zeta)")
    others = g.free_symbols - {zeta}
    if others and zeta not in g.free_symbols:
        raise InputError(f"g: expected a function of zeta (lkverify.zeta), got {g} in "
                         f"{', '.join(sorted(map(str, others)))} only; write the kernel in zeta, e.g. exp(-2*zeta)")
    bad = [s for s in others if s.is_positive is not True]
    if bad:
        raise InputError(f"g: expected zeta (lkverify.zeta) and positive parameter symbols only, got "
                         f"{sorted(bad, key=str)[0]} without positive=True; declare it as "
                         f"sympy.Symbol(name, positive=True)")
    if g.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo):
        raise InputError(f"g: expected a finite function of zeta, got {g}")
    return g


def _prepare_sigma(sigma):
    if sigma is None:
        return None
    if isinstance(sigma, str):
        sigma = parse_value(sigma, name="sigma")
    if isinstance(sigma, float):
        raise InputError(f"sigma: expected an exact number, got the float {sigma!r}; e.g. sympy.Rational(1, 2)")
    try:
        sigma = sympy.sympify(sigma, strict=True)
    except (sympy.SympifyError, TypeError) as exc:
        raise InputError(f"sigma: expected an exact positive number, got {sigma!r}") from exc
    _refuse_floats("sigma", sigma, "sympy.Rational(1, 2)")
    if not isinstance(sigma, sympy.Expr) or sigma.is_positive is not True:
        raise InputError(f"sigma: expected a constant σ > 0 (Assumption 1), got {sigma}; e.g. sigma=1/2")
    return sigma


def _show(e):
    return str(e.subs(_Z, zeta)) if isinstance(e, sympy.Basic) else str(e)


def _is_closed(e):
    return isinstance(e, sympy.Expr) and not e.has(sympy.Integral, sympy.Piecewise, sympy.Limit,
                                                   sympy.AccumBounds, sympy.nan, sympy.zoo)


# ---------------------------------------------------------------- the steps

def _continuous(g, tried):
    tried.append("continuous_domain(g, [0, oo))")
    dom = continuous_domain(g.subs(_Z, zeta), zeta, _HALF_LINE)
    if dom == _HALF_LINE:
        return None
    gap = _HALF_LINE - dom
    where = gap.inf if isinstance(gap, sympy.Set) and gap is not sympy.S.EmptySet else None
    return where


def _zeros(g, tried):
    """Exact zeros of g on [0, ∞) (a few, smallest first), [] when there are none, None if unknown."""
    tried.append("solveset(g = 0, zeta, [0, oo))")
    found = sympy.solveset(g, _Z, _HALF_LINE)
    if found is sympy.S.EmptySet:
        return []
    points = _points_of(found)
    if points is None:
        return None
    if any(p.is_nonnegative is None for p in points):
        raise _Undecided(f"SymPy could not decide whether the zeros {points} of g lie in ζ ≥ 0")
    zeros = [p for p in points if p.is_nonnegative and sympy.simplify(g.subs(_Z, p)) == 0]
    return _sort_exact(zeros) if zeros else None      # a nonempty solution set with no checked zero: unknown


def _points_of(found):
    if isinstance(found, sympy.FiniteSet):
        return list(found)
    if isinstance(found, sympy.Union):
        out = []
        for part in found.args:
            pts = _points_of(part)
            if pts is None:
                return None
            out += pts
        return out
    if isinstance(found, sympy.Intersection):
        images = [a for a in found.args if isinstance(a, sympy.ImageSet)]
        if len(images) == 1 and len(images[0].lamda.variables) == 1:
            lam = images[0].lamda
            pts = [p for p in (lam(n) for n in range(-3, 4)) if p.is_nonnegative and found.contains(p) is sympy.true]
            return pts or None
    return None


def _sort_exact(points):
    try:
        return sorted(set(points))
    except TypeError:
        return list(points)


def _nonzero_after(g, z0, later):
    """A point ζ1 > ζ0 with g(ζ1) ≠ 0 proved exactly (midpoint to the next zero, ζ0 + 1, 2ζ0 + 1)."""
    cands = [(z0 + z1) / 2 for z1 in later[:1]] + [z0 + 1, 2 * z0 + 1, z0 + 2]
    for c in cands:
        v = sympy.simplify(g.subs(_Z, c))
        if v.is_zero is False:
            return c, v
    return None, None


def _absolute(g, tried):
    """(±g, None) when g has one sign on [0, ∞); (None, failure text and witness) at a zero of g."""
    if g.is_positive or g.is_nonnegative and g.is_zero is False:
        return g, None
    if g.is_negative:
        return -g, None
    zeros = _zeros(g, tried)
    if zeros is None:
        raise _Undecided(f"SymPy could not find the zeros of g on [0, ∞) (solveset gave "
                         f"{sympy.solveset(g, _Z, _HALF_LINE)}), so the sign of g is unknown")
    if not zeros:
        g0 = sympy.simplify(g.subs(_Z, 0))
        if g0.is_positive:
            return g, None
        if g0.is_negative:
            return -g, None
        raise _Undecided(f"SymPy could not decide the sign of g(0) = {g0}")
    z0 = zeros[0]
    z1, v = _nonzero_after(g, z0, zeros[1:])
    if z1 is None:
        raise _Undecided(f"g(ζ) = 0 at ζ = {z0}, but SymPy found no later point where g ≠ 0")
    return None, (z0, f"at ζ0 = {z0}, |g(ζ0)| = 0 while ∫_ζ0^∞ |g| > 0 (g is continuous and "
                      f"g({z1}) = {v} ≠ 0), so ∫_ζ^∞|g| ≤ σ|g(ζ)| fails at ζ = {z0} for every σ")


def _integral(absg, tried):
    """∫_0^∞ |g|: (value, None) if finite, (oo, reason) if it diverges."""
    tried.append("integrate(|g|, (zeta, 0, oo))")
    I = sympy.integrate(absg, (_Z, 0, sympy.oo))
    if I is sympy.oo:
        return I, f"∫_0^∞ |g| dζ = ∫_0^∞ {_show(absg)} dζ = ∞ diverges (part 1 of Assumption 1)"
    if _is_closed(I) and I.is_finite:
        return sympy.simplify(I), None
    tried.append("limit(log|g| / log zeta, zeta, oo)")
    q = sympy.limit(sympy.log(absg) / sympy.log(_Z), _Z, sympy.oo)
    if q is -sympy.oo or (q + 1).is_negative:          # |g| ≤ ζ^(−p), p > 1, eventually: converges
        if _is_closed(I):
            return I, None
        raise _Undecided(f"∫_0^∞ {_show(absg)} dζ < ∞ (log|g|/log ζ → {q} < −1), but SymPy gave no closed "
                         f"form for it ({I})")
    if q is sympy.oo or (q + 1).is_positive:
        return sympy.oo, f"∫_0^∞ |g| dζ diverges (part 1 of Assumption 1): log|g|/log ζ → {q} > −1"
    if q + 1 == 0:
        c = sympy.limit(_Z * absg, _Z, sympy.oo)
        if c is sympy.oo or c.is_positive:
            return sympy.oo, (f"∫_0^∞ |g| dζ diverges (part 1 of Assumption 1): ζ|g| → {c} > 0, compared "
                              f"with ∫ dζ/ζ = ∞")
    raise _Undecided(f"SymPy could not decide ∫_0^∞ {_show(absg)} dζ (integrate gave {I}; log|g|/log ζ → {q})")


def _tail(absg, I, tried):
    """T(ζ) = ∫_ζ^∞ |g|, checked: T' = −|g| and T → 0."""
    tried.append("integrate(|g|, (s, 0, zeta)) and integrate(|g|, (s, zeta, oo))")
    cands = []
    F = sympy.integrate(absg.subs(_Z, _S), (_S, 0, _Z))
    if _is_closed(F):
        cands.append(sympy.simplify(I - F))
    T2 = sympy.integrate(absg.subs(_Z, _S), (_S, _Z, sympy.oo), conds="none")
    if _is_closed(T2):
        cands.append(sympy.simplify(T2))
    for T in cands:
        if sympy.simplify(sympy.diff(T, _Z) + absg) == 0 and sympy.limit(T, _Z, sympy.oo) == 0:
            return T
    raise _Undecided(f"SymPy could not integrate the tail ∫_ζ^∞ |g(s)| ds, |g| = {_show(absg)}, in closed form "
                     f"with T' = −|g| and T → 0 checked (got {cands or F})")


def _exceeds(value, sigma):
    return sympy.simplify(value - sigma).is_positive


def _witness_above(R, sigma, tried):
    """A ζ ≥ 0 with R(ζ) > σ for R → ∞: solveset of R = σ + 1, else ζ = 2^k − 1."""
    tried.append("solveset(R = sigma + 1, zeta, [0, oo))")
    sol = sympy.solveset(sympy.simplify(R - sigma - 1), _Z, _HALF_LINE)
    if isinstance(sol, sympy.FiniteSet) and len(sol) >= 1:
        z = min(sol, key=sympy.default_sort_key) if len(sol) > 1 else next(iter(sol))
        if z.is_nonnegative and sympy.simplify(R.subs(_Z, z) - sigma - 1) == 0:
            return z
    for k in range(0, 80):
        z = sympy.Integer(2) ** k - 1
        if _exceeds(R.subs(_Z, z), sigma):
            return z
    return None


def _has_trig(e):
    return e.has(sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)


def _sup(R, Linf, tried):
    """(sup R over [0, ∞), the ζ where it is attained or oo for the limit) or (None, reason)."""
    R0 = sympy.simplify(R.subs(_Z, 0))
    dR = sympy.simplify(sympy.diff(R, _Z))
    if dR == 0:
        return R0, sympy.Integer(0), "R is constant"
    if dR.is_nonpositive:
        return R0, sympy.Integer(0), "R is nonincreasing (R' ≤ 0)"
    if dR.is_nonnegative:
        return Linf, sympy.oo, "R is nondecreasing (R' ≥ 0)"
    tried.append("solveset(R' = 0, zeta, (0, oo))")
    crit = sympy.solveset(dR, _Z, sympy.Interval.open(0, sympy.oo))
    if _has_trig(dR) or not (crit is sympy.S.EmptySet or isinstance(crit, sympy.FiniteSet)):
        return None, None, f"critical points not found in closed form ({crit})"
    cands = [(R0, sympy.Integer(0)), (Linf, sympy.oo)] + [(sympy.simplify(R.subs(_Z, c)), c) for c in crit]
    best = sympy.simplify(sympy.Max(*[v for v, _ in cands]))
    for v, at in cands:
        if sympy.simplify(best - v) == 0:
            return best, at, f"largest of R(0), lim R and R at the critical points {sorted(crit, key=str)}"
    return best, None, "largest of R(0), lim R and R at the critical points"


def _decide(g, sigma, tried):
    kw = dict(g=g.subs(_Z, zeta), given_sigma=sigma)
    if g == 0:
        return Assumption1Result(Status.EXACT, sigma=sympy.Integer(0), integral=sympy.Integer(0),
                                 tail=sympy.Integer(0), detail="g ≡ 0: both sides of Assumption 1 vanish, "
                                 "every σ > 0 works", tried=tuple(tried), **kw)
    gap = _continuous(g, tried)
    if gap is not None:
        return Assumption1Result(Status.FAILED, witness=gap, tried=tuple(tried), **kw,
                                 detail=f"g = {_show(g)} is not continuous on [0, ∞) (at ζ = {gap}); "
                                        f"the paper takes g continuous on [0, +∞) (Remark 3)")
    absg, zero = _absolute(g, tried)
    if zero is not None:
        return Assumption1Result(Status.FAILED, witness=zero[0], tried=tuple(tried), **kw,
                                 detail=f"fails for g = {_show(g)}: {zero[1]}")
    I, diverges = _integral(absg, tried)
    if diverges:
        return Assumption1Result(Status.FAILED, integral=sympy.oo, tried=tuple(tried), **kw,
                                 detail=f"fails for g = {_show(g)}: {diverges}")
    T = _tail(absg, I, tried)
    R = sympy.simplify(T / absg)
    kw.update(integral=I, tail=T.subs(_Z, zeta), ratio=R.subs(_Z, zeta))
    tried.append("limit(R, zeta, oo)")
    Linf = sympy.limit(R, _Z, sympy.oo)
    head = f"g = {_show(g)}: ∫_0^∞|g| = {I}, R(ζ) = ∫_ζ^∞|g| / |g(ζ)| = {_show(R)}"
    if Linf is sympy.oo:
        if sigma is not None:
            z = _witness_above(R, sigma, tried)
            return Assumption1Result(Status.FAILED, witness=z, tried=tuple(tried), **kw,
                                     detail=f"fails at σ = {sigma}: {head} → ∞ as ζ → ∞ (R(ζ) → ∞)"
                                            + ("" if z is None else
                                               f"; at ζ = {z}: R = {sympy.simplify(R.subs(_Z, z))} > σ"))
        z = _witness_above(R, _SIGMA, tried)
        lam = None if z is None else sympy.Lambda(_SIGMA, z)
        how = ("" if z is None else f"; for every σ > 0, ζ = {str(z).replace('sigma', 'σ')} gives "
                                    f"R(ζ) = σ + 1 > σ")
        return Assumption1Result(Status.FAILED, witness=lam, tried=tuple(tried), **kw,
                                 detail=f"fails: {head} → ∞ as ζ → ∞ (R(ζ) → ∞), so no constant σ{how}")
    if not (_is_closed(Linf) and Linf.is_finite):
        raise _Undecided(f"SymPy could not decide lim_(ζ→∞) R(ζ) for R = {_show(R)} (it gave {Linf})")
    best, at, why = _sup(R, Linf, tried)
    if best is None:
        if sigma is not None:
            tried.append("solveset(R > sigma, zeta, [0, oo))")
            bad = sympy.solveset(R > sigma, _Z, _HALF_LINE)
            if bad is sympy.S.EmptySet and not _has_trig(R):
                return Assumption1Result(Status.EXACT, tried=tuple(tried), **kw,
                                         detail=f"holds at σ = {sigma}: {head} ≤ σ on ζ ≥ 0")
            raise _Undecided(f"{head} is bounded (limit {Linf} at ∞) but SymPy could not compare it with σ = "
                             f"{sigma}: {why}")
        return Assumption1Result(Status.EXACT, tried=tuple(tried), **kw,
                                 detail=f"holds: {head} is continuous on [0, ∞) with finite limit {Linf} at ∞, "
                                        f"hence bounded; the smallest σ was not found in closed form ({why})")
    kw["sigma"] = best
    where = "" if at is None else (" as ζ → ∞" if at is sympy.oo else f" at ζ = {at}")
    if sigma is None:
        return Assumption1Result(Status.EXACT, tried=tuple(tried), **kw,
                                 detail=f"holds with σ = {best}: {head}, sup R = {best}{where} ({why})")
    over = sympy.simplify(sigma - best)
    if over.is_nonnegative:
        return Assumption1Result(Status.EXACT, tried=tuple(tried), **kw,
                                 detail=f"holds at σ = {sigma} ≥ sup R = {best}{where}: {head}")
    if over.is_negative:
        z = at if at not in (None, sympy.oo) else _witness_above(R, sigma, tried)
        zdet = "" if z is None else f"; at ζ = {z}: R = {sympy.simplify(R.subs(_Z, z))} > σ"
        return Assumption1Result(Status.FAILED, witness=z, tried=tuple(tried), **kw,
                                 detail=f"fails at σ = {sigma} < sup R = {best}{where}: {head}{zdet}")
    raise _Undecided(f"SymPy could not compare σ = {sigma} with sup R = {best}")


# ---------------------------------------------------------------- entry point

def decide_assumption1(g, *, sigma=None, budget=None) -> Assumption1Result:
    """Decide Assumption 1 of paper 000 for the kernel G(ζ) = g(ζ)I.

    Parameters
    ----------
    g : sympy expression, sympy.Lambda or str
        g(ζ) in :data:`lkverify.zeta` (taken on ζ ≥ 0; a string is parsed safely, ``t`` read as
        ζ).  Other symbols must be declared positive.  Floats are refused.
    sigma : exact number > 0, optional
        Given: decide ∫_ζ^∞|g| ≤ σ|g(ζ)| for ζ ≥ 0 at this σ; otherwise whether some σ > 0 works.
    budget : float or None
        Seconds (``None``: no limit); past it the result is ``undecided``.

    Returns
    -------
    Assumption1Result
        ``exact`` with ``sigma`` = sup R (the smallest σ) when found; ``failed`` with the reason and
        ``witness``; ``undecided`` with what was ``tried``.

    Raises
    ------
    InputError
        For unparsable input, floats, a g not in ζ, parameter symbols not declared positive, σ ≤ 0.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import zeta
    >>> a = sympy.Symbol("a", positive=True)
    >>> decide_assumption1(sympy.exp(-a * zeta)).sigma
    1/a
    >>> decide_assumption1((1 + zeta) * sympy.exp(-zeta)).sigma
    2
    >>> r = decide_assumption1(1 / (1 + zeta)**2)
    >>> r.status.value, r.ratio, r.witness(100)         # for σ = 100, ζ = 100 has R(ζ) = 101 > σ
    ('failed', zeta + 1, 100)
    >>> r = decide_assumption1(1 / (1 + zeta)**2, sigma=10)
    >>> r.witness, "R(ζ) → ∞" in r.detail
    (10, True)
    >>> decide_assumption1(sympy.exp(-zeta) * sympy.cos(zeta)).witness
    pi/2
    >>> decide_assumption1("1/(1+zeta)").detail
    'fails for g = 1/(zeta + 1): ∫_0^∞ |g| dζ = ∫_0^∞ 1/(zeta + 1) dζ = ∞ diverges (part 1 of Assumption 1)'
    >>> [decide_assumption1("exp(-2*zeta)", sigma=s).status.value for s in ("1/2", "49/100")]
    ['exact', 'failed']
    """
    g = _prepare_g(g)
    sigma = _prepare_sigma(sigma)
    deadline = Deadline(budget)
    gz = g.subs(zeta, _Z)
    tried: list = []
    try:
        with deadline.enforced():
            return _decide(gz, sigma, tried)
    except BudgetExceeded:
        why = f"time budget of {budget:g} s exhausted before SymPy decided it"
    except _Undecided as exc:
        why = str(exc)
    except (NotImplementedError, ValueError, TypeError, AttributeError) as exc:
        why = f"SymPy could not decide it ({type(exc).__name__}: {exc})"
    return Assumption1Result(Status.UNDECIDED, g=g, given_sigma=sigma, tried=tuple(tried),
                             detail=f"undecided for g = {g}: {why}; tried: {', '.join(tried) or 'nothing'}")


class Assumption1:
    """Assumption 1 of paper 000 as a hypothesis of the catalogue item (G = g(ζ)I).

    At the run's g it decides with :func:`decide_assumption1` whether some σ > 0 works and
    reports the smallest one, σ = sup ∫_ζ^∞|g| / |g(ζ)|.

    Parameters
    ----------
    name : str
    g : sympy UndefinedFunction
        The kernel parameter g(ζ) of the system.
    sigma : exact number > 0, optional
        Decide the inequality at this σ instead.
    reference : str

    Examples
    --------
    >>> from lkverify.proofs.aleksandrov2026.equations import P, g
    >>> hyp = Assumption1("Assumption 1", g, reference="(Assumption 1)")
    >>> r = hyp.evaluate(P.substitution(P.resolve({}, use_defaults=True)))     # g = exp(−2ζ)
    >>> r.status.value, r.value
    ('exact', 1/2)
    >>> r = hyp.evaluate(P.substitution(P.resolve({"g": "1/(1+zeta)**2"}, use_defaults=True)))
    >>> r.status.value, "R(ζ) → ∞" in r.detail
    ('failed', True)
    """

    def __init__(self, name: str, g, *, sigma=None, reference: str = ""):
        self.name = name
        self.g = g
        self.sigma = _prepare_sigma(sigma)
        self.reference = reference

    def symbols(self) -> set:
        """The parameter the assumption is stated in (g)."""
        return {self.g}

    def _value_of(self, substitution):
        for k, v in substitution.items():
            if k == self.g or str(k) == str(self.g):
                return v
        return None

    def evaluate(self, substitution, *, budget=None) -> Result:
        """The Result of Assumption 1 at the substituted g (``hypothesis`` kind; value: σ)."""
        lam = self._value_of(substitution)
        if lam is None:
            return Result("hypothesis", self.name, Status.UNDECIDED, None, "g has no value: pass --set g=…")
        g_expr = lam(zeta) if isinstance(lam, sympy.Lambda) else sympy.sympify(lam)
        seconds = 10.0 if budget is None else max(float(budget), 0.5)
        res = decide_assumption1(g_expr, sigma=self.sigma, budget=seconds)
        ref = f" {self.reference}" if self.reference else ""
        return Result("hypothesis", self.name, res.status, res.sigma, f"{ref.strip()} {res.detail}".strip())
