"""Section 4 of paper 002: system (1), the change of variables (П.4) and the isolated subsystems (7), (8).

System (1) with constant nonsingular A, B (not necessarily symmetric) and Q, D continuous and
homogeneous of order μ > 1:

    (1)  A q̈ + B q̇ + Q(q) + ∫_{t−τ}^t D(q(ξ)) dξ = 0,

written here as a first-order system in q and p = q̇ (A ṗ = −Bp − Q(q) − ∫D(q(ξ))dξ).  The proof of
Theorem 2 changes variables to x = q̇, y = q + B⁻¹A q̇ and prints the transformed system

    (П.4)  A ẋ = −Bx − Q(y − B⁻¹Ax) − ∫_{t−τ}^t D(y(ξ) − B⁻¹Ax(ξ)) dξ,
           B ẏ = −Q(y − B⁻¹Ax) − ∫_{t−τ}^t D(y(ξ) − B⁻¹Ax(ξ)) dξ,

with the isolated subsystems without delay

    (7)  A ẋ = −B x,        (8)  B ẏ = −Q(y) − τD(y).

The catalogued instance (n = 2, μ = 3, cubic components; every coefficient is a ``--set`` parameter,
the matrices entry by entry, since the declare layer has no kind for a general square matrix):

    A = [[a11, a12], [a21, a22]] = [[2, 1], [0, 1]],    B = [[b11, b12], [b21, b22]] = [[1, 1/2], [−1/2, 2]],
    Q(q) = (k1 q1³ + g q2³, k2 q2³ − g q1³) = (−½q1³ + ½q2³, q2³ − ½q1³),
    D(q) = (d1 q1³, d2 q2³) = (q1³, q2³),      τ = 1.

Neither A nor B is symmetric; Q has a circulatory part g and a first component that alone
destabilises (k1 < 0): (8) is asymptotically stable only through the delay term, k1 + τd1 = ½ > 0
(Remark 2: stabilisation by the choice of the distributed-delay term).  With τ = 1/4 (k1 + τd1 < 0)
the ray y = (1, r) of (8) escapes and (8) is not asymptotically stable.

The decisions (each returns a :class:`~lkverify.certify.conditions.ConditionResult`):

* :func:`decide_7` — (7) from the spectrum of −A⁻¹B: exact Routh–Hurwitz test (a failure names the
  eigenvalue with Re λ ≥ 0), then a rational Lyapunov matrix P1 verified exactly, so that
  V1 = (xᵀP1x)^{ν1/2} gives m14;
* :func:`decide_8` — (8) by a homogeneous Lyapunov function V2 = (yᵀP2y)^{ν2/2}: P2 found by a
  linear programme on sampled directions (cvxpy + Clarabel), rounded to rationals, then P2 ≻ 0
  exactly and yᵀP2B⁻¹(Q(y) + τD(y)) > 0 on ‖y‖ = 1 certified in arb (never the solver status);
  a failure is an escaping invariant ray (n = 2), certified;
* :func:`decide_order` — 1 < (ν2 + μ − 1)/ν1 < μ, exact;
* :func:`derived_order_condition` — the same condition derived from the exponents of the cross terms of
  the printed V̇ estimate (:data:`PRINTED_CROSS_TERMS`): each must be of higher order than the negative
  terms for Young's inequality to absorb it near 0.

:data:`system1` is (1) in q, q̇; :data:`system_P4` is (П.4) as printed, in x, y; :func:`printed_P4` states
the printed rows as claims derived along (1).
"""

from __future__ import annotations

import dataclasses
import functools
from fractions import Fraction

import numpy as np
import sympy

from lkverify import DerivativeClaim, Equation, Functional, Parameters, System, Term, Vector, t, window_integral, xi
from lkverify.certify import find_lyapunov_matrix, homogeneous_positive_on_sphere
from lkverify.certify.conditions import ConditionResult, Margin
from lkverify.certify.intervals import enclose
from lkverify.certify.lmi import round_symmetric, solve_sdp
from lkverify.certify.matrices import matrix_positive_definite
from lkverify.report.results import Result
from lkverify.status import Status

from .equations import PAPER

__all__ = ["PAPER", "P2", "A", "B", "Q", "D", "MU", "NU1", "NU2", "tau", "q", "p", "system1", "X", "Y", "x", "y",
           "q_of_xy", "system_P4",
           "printed_P4", "decide_7", "decide_8", "decide_order", "escaping_ray", "Decided", "instance_matrices",
           "COEFFICIENTS", "PRINTED_CROSS_TERMS", "cross_term_excess", "derived_order_condition"]

#: the parameters of section 4 (a registry of their own: A and B are not those of section 5)
P2 = Parameters()
_A_DEFAULT = (("a11", 2), ("a12", 1), ("a21", 0), ("a22", 1))
_B_DEFAULT = (("b11", 1), ("b12", "1/2"), ("b21", "-1/2"), ("b22", 2))
_entries = {name: P2.scalar(name, default=value, description=f"entry {name[1:]} of the {name[0].upper()} of (1)")
            for name, value in (*_A_DEFAULT, *_B_DEFAULT)}
A = sympy.ImmutableMatrix([[_entries["a11"], _entries["a12"]], [_entries["a21"], _entries["a22"]]])
B = sympy.ImmutableMatrix([[_entries["b11"], _entries["b12"]], [_entries["b21"], _entries["b22"]]])
k1 = P2.scalar("k1", default="-1/2", description="Q_1 = k1 q1³ + g q2³")
k2 = P2.scalar("k2", default=1, description="Q_2 = k2 q2³ − g q1³")
g = P2.scalar("g", default="1/2", description="circulatory part of Q")
d1 = P2.scalar("d1", default=1, description="D_1 = d1 q1³")
d2 = P2.scalar("d2", default=1, description="D_2 = d2 q2³")
tau = P2.delay("tau", default=1)
COEFFICIENTS = ("k1", "k2", "g", "d1", "d2")

#: the order of homogeneity of Q and D in the catalogued instance, and the orders of V1, V2 chosen
MU = sympy.Integer(3)
NU1 = sympy.Integer(2)
NU2 = sympy.Integer(2)


def Q(v) -> sympy.Matrix:
    """Q(v) = (k1 v1³ + g v2³, k2 v2³ − g v1³), homogeneous of order μ = 3."""
    return sympy.Matrix([k1 * v[0] ** 3 + g * v[1] ** 3, k2 * v[1] ** 3 - g * v[0] ** 3])


def D(v) -> sympy.Matrix:
    """D(v) = (d1 v1³, d2 v2³), homogeneous of order μ = 3."""
    return sympy.Matrix([d1 * v[0] ** 3, d2 * v[1] ** 3])


q = Vector("q", 2)
p = Vector("p", 2, latex=r"\dot q", text="q̇")
_Binv = B.inv()

# (1), as A ṗ = −Bp − Q(q) − ∫D(q(ξ))dξ, q̇ = p
system1 = System([
    Equation(q, [Term(p(t), text="q̇", latex=r"\dot q")]),
    Equation(p, [Term(-B * p(t), text="−Bq̇", latex=r"-B\dot q"),
                 Term(-Q(q(t)), text="−Q(q)", latex="-Q(q)"),
                 Term(-window_integral(D(q(xi)), tau), text="−∫D(q(ξ))dξ",
                      latex=r"-\int_{t-\tau}^t D(q(\xi))\,d\xi")],
             mass=A, mass_text="A", mass_latex="A"),
], parameters=P2, name="(1)")


def X(time) -> sympy.Matrix:
    """x = q̇ (the first new variable of (П.4)) at ``time``."""
    return sympy.Matrix(p(time))


def Y(time) -> sympy.Matrix:
    """y = q + B⁻¹A q̇ (the second new variable of (П.4)) at ``time``."""
    return sympy.Matrix(q(time)) + _Binv * A * sympy.Matrix(p(time))


# (П.4) as printed, a system in the new variables x = q̇, y = q + B⁻¹Aq̇ (the proof's V̇ is taken along it)
x = Vector("x", 2)
y = Vector("y", 2)


def q_of_xy(time) -> sympy.Matrix:
    """q = y − B⁻¹Ax at ``time``, the argument of Q and D in (П.4)."""
    return sympy.Matrix(y(time)) - _Binv * A * sympy.Matrix(x(time))


_Q_P4 = Term(-Q(q_of_xy(t)), text="−Q(y − B⁻¹Ax)", latex=r"-Q(y-B^{-1}Ax)")
_D_P4 = Term(-window_integral(D(q_of_xy(xi)), tau), text="−∫D(y(ξ) − B⁻¹Ax(ξ))dξ",
             latex=r"-\int_{t-\tau}^t D(y(\xi)-B^{-1}Ax(\xi))\,d\xi")
system_P4 = System([
    Equation(x, [Term(-B * sympy.Matrix(x(t)), text="−Bx", latex="-Bx"), _Q_P4, _D_P4],
             mass=A, mass_text="A", mass_latex="A"),
    Equation(y, [_Q_P4, _D_P4], mass=B, mass_text="B", mass_latex="B"),
], parameters=P2, name="(П.4)")


def printed_P4(*, sign_Q=-1, shift=None, name_suffix="") -> list[DerivativeClaim]:
    """(П.4) as printed, row by row: d/dt of (Ax)_i and (By)_i along (1) against the printed right sides.

    The printed right sides are written in x, y and then expressed in q, q̇ by the change of
    variables itself, so the claims say exactly what the paper prints.  ``sign_Q`` and ``shift`` (the
    matrix S in Q(y − Sx), B⁻¹A as printed) exist to state mutated prints in the tests.
    """
    S = _Binv * A if shift is None else shift
    x_t, y_t = X(t), Y(t)
    common = [Term(sign_Q * Q(y_t - S * x_t), text="−Q(y − B⁻¹Ax)", latex=r"-Q(y-B^{-1}Ax)"),
              Term(-window_integral(D(Y(xi) - S * X(xi)), tau), text="−∫D(y(ξ) − B⁻¹Ax(ξ))dξ",
                   latex=r"-\int_{t-\tau}^t D(y(\xi)-B^{-1}Ax(\xi))\,d\xi")]
    claims = []
    for i in range(2):
        row = [Term(c.expr[i], text=f"[{c.text}]_{i + 1}", latex=rf"\left[{c.latex}\right]_{i + 1}") for c in common]
        claims.append(DerivativeClaim(
            f"(П.4) (Aẋ)_{i + 1}{name_suffix}", Functional([Term((A * x_t)[i], text=f"(Ax)_{i + 1}")]), system1,
            [Term((-B * x_t)[i], text=f"[−Bx]_{i + 1}", latex=rf"-[Bx]_{i + 1}"), *row],
            description=f"row {i + 1} of the first equation of (П.4), x = q̇, y = q + B⁻¹Aq̇, derived along (1)"))
        claims.append(DerivativeClaim(
            f"(П.4) (Bẏ)_{i + 1}{name_suffix}", Functional([Term((B * y_t)[i], text=f"(By)_{i + 1}")]), system1,
            row, description=f"row {i + 1} of the second equation of (П.4), derived along (1)"))
    return claims


# -- the values of a run -------------------------------------------------------------------------------

def _value(substitution, symbol):
    for k, v in substitution.items():
        if k == symbol or str(k) == str(symbol):
            return v
    return symbol


def instance_matrices(substitution) -> dict:
    """A, B and the map y ↦ B⁻¹(Q(y) + τD(y)) at the run's values: ``{"A", "B", "G", "y"}``.

    ``G`` is the right side of (8) solved for ẏ, with the sign flipped: ẏ = −G(y).
    """
    sub = {s: _value(substitution, s) for s in (*A.free_symbols, *B.free_symbols, k1, k2, g, d1, d2, tau)}
    Am, Bm = A.subs(sub), B.subs(sub)
    yv = sympy.symbols("y1 y2", real=True)
    G = None
    if Bm.det() != 0:
        G = (Bm.inv() * (Q(yv) + tau * D(yv))).subs(sub).applyfunc(sympy.expand)
    return {"A": sympy.Matrix(Am), "B": sympy.Matrix(Bm), "G": G, "y": yv}


@dataclasses.dataclass(frozen=True)
class Decided:
    """A hypothesis of Theorem 2 decided by a function of the run's values (a ConditionResult).

    ``evaluate(substitution)`` is what :class:`~lkverify.Theorem` calls for each hypothesis;
    ``symbols()`` names the parameters the decision reads.
    """

    name: str
    decide: object
    reads: tuple = ()
    reference: str = ""

    def symbols(self) -> set:
        return set(self.reads)

    def evaluate(self, substitution, *, budget=None) -> Result:
        res = self.decide(substitution)
        value = None if res.margin is None or res.margin.lo is None else res.margin.lo
        return Result("hypothesis", self.name, res.status, value, res.detail)


# -- (7) ------------------------------------------------------------------------------------------------

def decide_7(substitution) -> ConditionResult:
    """(7) A ẋ = −Bx asymptotically stable ⇔ −A⁻¹B Hurwitz: exact Routh–Hurwitz, then P1 verified exactly.

    ``failed`` names an eigenvalue of −A⁻¹B with Re λ ≥ 0; ``exact`` gives the rational P1 ≻ 0 with
    (−A⁻¹B)ᵀP1 + P1(−A⁻¹B) ≺ 0: V1 = xᵀP1x (ν1 = 2) has (∂V1/∂x)ᵀA⁻¹Bx ≥ m14‖x‖² with
    m14 = λ_min(MᵀP1 + P1M), M = A⁻¹B (the margin).
    """
    m = instance_matrices(substitution)
    if m["A"].det() == 0 or m["B"].det() == 0:
        return ConditionResult("(7) asymptotically stable", Status.FAILED, witness=0,
                               detail="A or B is singular (det = 0): (7), (8) and (П.4) are not defined")
    M = m["A"].inv() * m["B"]
    res = find_lyapunov_matrix(-M, name="(7) asymptotically stable")
    if res.status is Status.FAILED:
        why = res.detail.replace("A is not Hurwitz", "−A⁻¹B is not Hurwitz").replace("; A has", "; −A⁻¹B has")
        return dataclasses.replace(res, detail=f"−A⁻¹B = {(-M).tolist()}: {why}")
    if res.status.is_proof:
        P1 = res.certificate
        return dataclasses.replace(res, detail=(
            f"−A⁻¹B = {(-M).tolist()} is Hurwitz (exact Routh–Hurwitz test); V1 = (xᵀP1x)^{{ν1/2}} with "
            f"the rational P1 = {P1.tolist()} ≻ 0 and (A⁻¹B)ᵀP1 + P1A⁻¹B ≻ 0 with λ_min ≥ {float(res.margin.lo):.6g} "
            f"({res.status}, exact LDLᵀ in fractions; P1 found by Clarabel and re-verified)"))
    return res


# -- (8) ------------------------------------------------------------------------------------------------

#: directions sampled on the unit circle by the linear programme for P2, and the rounding denominators tried
SAMPLES = 361
DENOMINATORS = (100, 10**4, 10**6)


def _lp_P2(G, yv):
    """max m s.t. yᵀP2G(y) ≥ m on sampled unit y, P2 ⪰ I/100, tr P2 = 1 (cvxpy + Clarabel): a float P2 or None."""
    import cvxpy as cp

    f = sympy.lambdify(yv, list(G), "numpy")
    Pv, mv = cp.Variable((2, 2), symmetric=True), cp.Variable()
    rows = []
    for th in np.linspace(0.0, np.pi, SAMPLES):
        y = np.array([np.cos(th), np.sin(th)])
        gv = np.array(f(*y), dtype=float)
        rows.append(np.outer(y, gv))
    cons = [Pv >> np.eye(2) / 100, cp.trace(Pv) == 1] + [cp.sum(cp.multiply(Pv, R)) >= mv for R in rows]
    prob = cp.Problem(cp.Maximize(mv), cons)
    status = solve_sdp(prob)
    if status != cp.OPTIMAL or mv.value is None or mv.value <= 0:
        return None, status, None if mv.value is None else float(mv.value)
    return np.asarray(Pv.value, dtype=float), status, float(mv.value)


def escaping_ray(G, yv) -> tuple | None:
    """An invariant ray y = s·e of ẏ = −G(y) (n = 2) along which G(e) = λe with λ ≤ 0, certified; else None.

    On such a ray ṡ = −λ s^μ ≥ 0: the solution from any point of it does not tend to 0, so the zero
    solution of (8) is not asymptotically stable.  Rays are the real roots r of
    c(r) = G2(1, r) − r G1(1, r) (and e = (0, 1) when G1(0, 1) = 0), isolated exactly by SymPy; the
    sign of λ(r) = G1(1, r) + r G2(1, r) is decided in arb on the isolating interval.

    Returns
    -------
    tuple or None
        ``(e, λ-enclosure, how)`` with e a direction (rational, or the interval of r) and the
        enclosure of λ(e)·(1 + r²) as a pair of Fractions.
    """
    r = sympy.Symbol("r", real=True)
    G1, G2 = (sympy.expand(G[0].subs({yv[0]: 1, yv[1]: r})), sympy.expand(G[1].subs({yv[0]: 1, yv[1]: r})))
    g10, g20 = G[0].subs({yv[0]: 0, yv[1]: 1}), G[1].subs({yv[0]: 0, yv[1]: 1})
    if g10 == 0 and g20 <= 0:
        return ((0, 1), (Fraction(str(g20)), Fraction(str(g20))), "e = (0, 1): G(e) = λe exactly")
    c = sympy.Poly(G2 - r * G1, r)
    lam = sympy.Poly(G1 + r * G2, r)
    if c.is_zero:
        return None
    for (lo, hi), _mult in c.intervals(eps=sympy.Rational(1, 10**12)):
        lo, hi = sympy.Rational(lo), sympy.Rational(hi)
        if lo == hi:
            val = lam.eval(lo)
            if val <= 0:
                return ((1, lo), (Fraction(str(val)), Fraction(str(val))), f"e = (1, {lo}): G(e) = λe exactly")
            continue
        value = enclose(lam.as_expr(), {r: (lo, hi)})  # λ over the isolating interval of the root
        if value < 0:
            return ((1, (lo, hi)), (None, None), f"e = (1, r), r ∈ [{float(lo):.12g}, {float(hi):.12g}] "
                                                 f"(a root of {c.as_expr()}), λ(1 + r²) ∈ {value.str(5)}")
    return None


def decide_8(substitution) -> ConditionResult:
    """(8) B ẏ = −Q(y) − τD(y) asymptotically stable, by a certified V2 = (yᵀP2y)^{ν2/2}, or refuted by a ray.

    V̇2 along (8) is −ν2 (yᵀP2y)^{ν2/2−1} yᵀP2 G(y), G = B⁻¹(Q + τD): V2 is a Lyapunov function
    when P2 ≻ 0 (exact) and yᵀP2G(y) > 0 on ‖y‖ = 1 (certified, homogeneous of degree μ + 1).
    """
    name = "(8) asymptotically stable"
    m = instance_matrices(substitution)
    G, yv = m["G"], m["y"]
    if G is None:
        return ConditionResult(name, Status.FAILED, witness=0, detail="B is singular: (8) is not defined")
    ray = escaping_ray(G, yv)
    if ray is not None:
        e, _enc, how = ray
        return ConditionResult(name, Status.FAILED, witness=e, detail=(
            f"not asymptotically stable: ẏ = −G(y), G(y) = B⁻¹(Q(y) + τD(y)) = {list(G)}, has the invariant "
            f"ray y = s·e with G(e) = λe, λ ≤ 0 ({how}), along which ṡ = −λs^μ ≥ 0: solutions from it do not "
            f"tend to 0"))
    Pf, status, mest = _lp_P2(G, yv)
    if Pf is None:
        return ConditionResult(name, Status.UNDECIDED, detail=(
            f"no escaping ray, but no quadratic V2 found: the linear programme for P2 (Clarabel) returned "
            f"{status!r} with margin {mest}; a solver status is never a proof (try a higher-order V2)"))
    last = None
    for den in DENOMINATORS:
        P2m = round_symmetric(Pf, den)
        pd = matrix_positive_definite(P2m, name="P2")
        form = sympy.expand((sympy.Matrix(yv).T * P2m * G)[0])
        pos = homogeneous_positive_on_sphere(form, list(yv), degree=int(MU) + 1, name="yᵀP2B⁻¹(Q(y)+τD(y))")
        if pd.holds and pos.holds:
            status = Status.EXACT if pd.status is Status.EXACT and pos.status is Status.EXACT else Status.CERTIFIED
            lo = pos.margin.lo
            return ConditionResult(name, status, margin=Margin(lo, pos.margin.hi), certificate=P2m, parts=(pd, pos),
                                   detail=(f"V2 = (yᵀP2y)^{{ν2/2}}, P2 = {P2m.tolist()} ≻ 0 ({pd.status}); "
                                           f"yᵀP2B⁻¹(Q(y) + τD(y)) ≥ {float(lo):.4g}‖y‖⁴ ({pos.status}: {pos.detail}); "
                                           f"so V̇2 ≤ −ν2·{float(lo):.4g}(yᵀP2y)^{{ν2/2−1}}‖y‖⁴ along (8) "
                                           f"(P2 from a linear programme, Clarabel, rounded to denominators ≤ {den})"))
        last = pd if not pd.holds else pos
    return ConditionResult(name, Status.UNDECIDED, detail=f"the rounded P2 did not verify: {last.detail}")


# -- the order condition ---------------------------------------------------------------------------------

def decide_order(nu1, nu2, mu) -> ConditionResult:
    """The condition of the proof's last step, 1 < (ν2 + μ − 1)/ν1 < μ, exact (with ν1, ν2 ≥ 2)."""
    nu1, nu2, mu = map(sympy.Rational, (nu1, nu2, mu))
    ratio = (nu2 + mu - 1) / nu1
    lo, hi = ratio - 1, mu - ratio
    ok = lo > 0 and hi > 0 and nu1 >= 2 and nu2 >= 2
    text = (f"ν1 = {nu1}, ν2 = {nu2}, μ = {mu}: (ν2 + μ − 1)/ν1 = {ratio}, margins {ratio} − 1 = {lo}, "
            f"μ − {ratio} = {hi}; ν1, ν2 ≥ 2: {nu1 >= 2 and nu2 >= 2}")
    if ok:
        return ConditionResult("1 < (ν2+μ−1)/ν1 < μ", Status.EXACT, margin=Margin(min(lo, hi), min(lo, hi)),
                               detail=f"holds: {text}; {orders_always_exist()}")
    return ConditionResult("1 < (ν2+μ−1)/ν1 < μ", Status.FAILED, witness=(nu1, nu2, mu), detail=f"fails: {text}")


def orders_always_exist() -> str:
    """Why the order condition is no extra hypothesis of Theorem 2: ν1 = ν2 = 2 satisfies it for every μ > 1 (exact)."""
    mu = sympy.Symbol("mu", positive=True)
    ratio = (2 + mu - 1) / 2
    lo, hi = sympy.simplify(ratio - 1), sympy.simplify(mu - ratio)
    return (f"for every μ > 1 the orders ν1 = ν2 = 2 satisfy it (exact: (ν2+μ−1)/ν1 − 1 = {lo}, "
            f"μ − (ν2+μ−1)/ν1 = {hi}, both positive for μ > 1), so it is no extra hypothesis of Theorem 2")


# -- the order condition derived from the printed estimate -------------------------------------------------

_nu1, _nu2, _mu = sympy.symbols("nu1 nu2 mu", positive=True)
#: the positive cross terms of the printed V̇ estimate (before Young's inequality), as exponents of
#: ‖x(t)‖, ‖y(t)‖ and of the window integrals ∫‖x(ξ)‖^·, ∫‖y(ξ)‖^· (products of integrals add), and whether
#: the coefficient may be taken small (ε1, ε2: the term may be of the same order as −m24‖y‖^{ν2+μ−1})
PRINTED_CROSS_TERMS = (
    ("c1‖x‖^{ν1−1}‖x‖^μ", (_nu1 - 1 + _mu, 0, 0, 0), False),
    ("c1‖x‖^{ν1−1}‖y‖^μ", (_nu1 - 1, _mu, 0, 0), False),
    ("c2‖x‖^{ν1−1}∫‖x‖^μ", (_nu1 - 1, 0, _mu, 0), False),
    ("c2‖x‖^{ν1−1}∫‖y‖^μ", (_nu1 - 1, 0, 0, _mu), False),
    ("c3ε1‖y‖^{ν2−1}‖y‖^μ", (0, _nu2 - 1 + _mu, 0, 0), True),
    ("c3h1‖y‖^{ν2−1}‖x‖^μ", (_mu, _nu2 - 1, 0, 0), False),
    ("τc10‖y‖^{ν2−2}∫‖y‖^μ‖x‖^μ", (_mu, _nu2 - 2, 0, _mu), False),
    ("τc10‖y‖^{ν2−2}∫‖y‖^μ‖y‖^μ", (0, _nu2 - 2 + _mu, 0, _mu), False),
    ("τc10‖y‖^{ν2−2}∫‖y‖^μ∫‖x‖^μ", (0, _nu2 - 2, _mu, _mu), False),
    ("τc10‖y‖^{ν2−2}(∫‖y‖^μ)²", (0, _nu2 - 2, 0, 2 * _mu), False),
    ("ε2c4‖y‖^{ν2−1}∫‖y‖^μ", (0, _nu2 - 1, 0, _mu), True),
    ("h2c4‖y‖^{ν2−1}∫‖x‖^μ", (0, _nu2 - 1, _mu, 0), False),
)


@functools.lru_cache(maxsize=None)
def cross_term_excess(exponents) -> sympy.Expr:
    """w − 1 of a cross term, w its order relative to the negative terms, factored exactly.

    The negative terms of the estimate are −m14‖x‖^{ν1}, −m24‖y‖^{ν2+μ−1}, −β1∫‖x‖^{ν1}, −β2∫‖y‖^{ν2+μ−1};
    giving ‖x‖ (and ∫‖x‖^p) the weight 1/ν1 (p/ν1) and ‖y‖ (∫‖y‖^p) the weight 1/(ν2+μ−1) (p/(ν2+μ−1)),
    a product is of higher order near 0 — Young's inequality bounds it by ε times the negative terms
    on a small region (Hölder on the window for the integrals) — exactly when its weight w > 1.
    """
    ex, ey, ix, iy = exponents
    N = _nu2 + _mu - 1
    return sympy.factor(sympy.together((ex + ix) / _nu1 + (ey + iy) / N - 1))


def derived_order_condition(nu1, nu2, mu, *, printed=None) -> ConditionResult:
    """The order condition derived from the printed estimate's cross terms, against the printed one.

    ``exact`` when every cross term is of higher order (or of the same order with a small coefficient)
    at these orders *and* the printed 1 < (ν2+μ−1)/ν1 < μ agrees; ``failed`` names the terms that are
    not dominated, or says that the printed condition and the derivation disagree at these orders.
    ``printed(nu1, nu2, mu) → bool`` replaces the paper's condition (to state a mutated print).
    """
    values = {_nu1: sympy.Rational(nu1), _nu2: sympy.Rational(nu2), _mu: sympy.Rational(mu)}
    rows, bad, least = [], [], None
    for label, exps, small in PRINTED_CROSS_TERMS:
        excess = cross_term_excess(exps)
        v = excess.subs(values)
        ok = v >= 0 if small else v > 0
        rows.append(f"{label}: w − 1 = {excess} = {v}")
        if not ok:
            bad.append(f"{label} (w − 1 = {v})")
        if not small:
            least = v if least is None else min(least, v)
    printed = (decide_order(nu1, nu2, mu).status is Status.EXACT if printed is None
               else bool(printed(values[_nu1], values[_nu2], values[_mu])))
    derived = not bad
    name = "order condition = Young's steps"
    head = f"ν1 = {nu1}, ν2 = {nu2}, μ = {mu}: " + "; ".join(rows)
    if derived and printed:
        return ConditionResult(name, Status.EXACT, margin=Margin(least, least), detail=(
            f"every cross term of the printed V̇ estimate is of higher order than −m14‖x‖^ν1 − m24‖y‖^(ν2+μ−1) "
            f"(or of the same order with ε1, ε2 small), and the printed condition holds: {head}"))
    if derived != printed:
        return ConditionResult(name, Status.FAILED, witness=(nu1, nu2, mu), detail=(
            f"the printed condition {'holds' if printed else 'fails'} but the derivation from the cross terms "
            f"{'fails at ' + ', '.join(bad) if bad else 'holds'}: {head}"))
    return ConditionResult(name, Status.FAILED, witness=(nu1, nu2, mu), detail=(
        f"not of higher order: {', '.join(bad)} (the printed condition fails too): {head}"))
