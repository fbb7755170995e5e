"""Theorem 2 of paper 002 (decomposition): if μ > 1 and the zero solutions of (7), (8) are asymptotically
stable, the equilibrium (2) q = q̇ = 0 of system (1) is asymptotically stable.

    (1)  A q̈ + B q̇ + Q(q) + ∫_{t−τ}^t D(q(ξ)) dξ = 0,      A, B constant, nonsingular (not necessarily
         symmetric), Q, D continuous, homogeneous of order μ > 1;
    (7)  A ẋ = −B x,        (8)  B ẏ = −Q(y) − τD(y).

The proof (appendix) changes variables to x = q̇, y = q + B⁻¹Aq̇, prints the transformed system (П.4),
takes Lyapunov functions V1(x), V2(y) of (7), (8), homogeneous of orders ν1, ν2 ≥ 2, and the functional

    V = V1(x) + V2(y) − (∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ + ∫(α1 + β1(ξ+τ−t))‖x(ξ)‖^{ν1}dξ
        + ∫(α2 + β2(ξ+τ−t))‖y(ξ)‖^{ν2+μ−1}dξ,

whose estimates close by Young's inequality when 1 < (ν2 + μ − 1)/ν1 < μ.

Catalogued instance (:mod:`.decomposition`; every coefficient a ``--set`` parameter): n = 2, μ = 3,

    A = [[2, 1], [0, 1]],  B = [[1, 1/2], [−1/2, 2]]   (neither symmetric),
    Q(q) = (k1 q1³ + g q2³, k2 q2³ − g q1³),  D(q) = (d1 q1³, d2 q2³),
    k1 = −1/2, k2 = 1, g = 1/2, d1 = d2 = 1, τ = 1;   ν1 = ν2 = 2.

What is checked, at the run's values:

* the hypotheses — μ > 1; Q and D homogeneous of order μ (exact); A, B nonsingular; (7) asymptotically
  stable (exact: Routh–Hurwitz on the characteristic polynomial of −A⁻¹B, refuted with an eigenvalue
  of nonnegative real part, and a rational V1 = xᵀP1x verified exactly); (8) asymptotically stable
  (certified: a rational V2 = yᵀP2y, P2 ≻ 0 exact, −V̇2 positive on the unit circle in arb; refuted by
  an escaping invariant ray); the order condition for ν1, ν2 (exact), and the same condition derived
  from the printed V̇ estimate: each of its cross terms (c1 … c4, c10, h1, h2) must be of higher order
  than −m14‖x‖^{ν1} − m24‖y‖^{ν2+μ−1} for Young's inequality to absorb it — the derivation gives
  exactly μν1 > ν2 + μ − 1 (from the c1, c2 terms) and ν2 + μ − 1 > ν1 (from the h1, h2 terms), i.e. the
  printed 1 < (ν2+μ−1)/ν1 < μ (the other terms need only μ > 1);
* the link "(П.4) is (1) in x = q̇, y = q + B⁻¹Aq̇": the printed (П.4), row by row, against d/dt (Ax)_i
  and d/dt (By)_i derived along (1) with the library's derivative (chain rule, Leibniz rule), term by
  term, at the run's values (a mutated print fails it with the differing terms);
* V̇ of the proof's functional along (П.4) (the theorem's system), for V1 = xᵀS1x, V2 = yᵀS2y with S1,
  S2 any symmetric matrices (ν1 = ν2 = 2) and every α1, β1, α2, β2, A, B, Q, D coefficient, τ symbolic:
  exact in the structured form the printed estimate bounds term by term; the ∫D(y(ξ))dξ terms of V̇2
  and of the weighted integral cancel and −(∂V2/∂y)ᵀB⁻¹(Q(y) + τD(y)) — the m24 term, (8)'s V̇2 —
  remains.

* the chain (:mod:`.theorem2_chain`): V ≥ L, V ≤ U (the printed c7τ‖y‖∫‖y‖^μ cross term) and V̇ ≤ W term by
  term on the region max‖x(ξ)‖, max‖y(ξ)‖ ≤ δ (Rayleigh, Cauchy–Schwarz, certified suprema of the bidegree
  parts of the cubic terms, Hölder, Young, the region), then Krasovskii's theorem; α1, β1, α2, β2, η, η_L, δ
  are found at the run's values (:func:`~.theorem2_chain.find_choices`).
"""

import sympy

from lkverify import Hypothesis, Theorem
from lkverify.certify.conditions import ConditionResult, Margin
from lkverify.report.results import Result
from lkverify.status import Status

from .decomposition import (MU, NU1, NU2, PAPER, A, B, D, Decided, P2, Q, decide_7, decide_8, decide_order,
                            derived_order_condition, printed_P4, system_P4, tau)
from .theorem2_chain import CONCLUSION, find_choices, steps
from .theorem2_functional import S1, S2, derivation, functional, structured_Vdot

__all__ = ["theorem2", "homogeneous_of_order", "printed", "functional", "structured_Vdot", "derivation",
           "P4_along_1", "S1", "S2"]


def homogeneous_of_order(substitution=None) -> ConditionResult:
    """Q(λv) = λ^μ Q(v) and D(λv) = λ^μ D(v) for every λ > 0, v (exact, with the coefficients symbolic)."""
    lam = sympy.Symbol("lambda", positive=True)
    v = sympy.symbols("v1 v2", real=True)
    residue = [sympy.expand(F(tuple(lam * c for c in v))[i] - lam ** MU * F(v)[i]) for F in (Q, D) for i in range(2)]
    if all(r == 0 for r in residue):
        return ConditionResult("Q, D homogeneous of order μ", Status.EXACT, margin=Margin(MU, MU),
                               detail=f"Q(λv) − λ^μQ(v) and D(λv) − λ^μD(v) expand to 0 for μ = {MU}, every λ, v")
    return ConditionResult("Q, D homogeneous of order μ", Status.FAILED, witness=tuple(residue),
                           detail=f"not homogeneous of order μ = {MU}: residues {residue}")


#: the printed (П.4), row by row, derived along (1)
printed = printed_P4()


class P4Along1:
    """The link "(П.4) is (1) in x = q̇, y = q + B⁻¹Aq̇": the printed rows derived along (1) at the run's values.

    The chain's V̇ is taken along (П.4) as printed; this link is what makes it V̇ along (1).  A
    mutated print fails it with the term-by-term difference.
    """

    def __init__(self, claims, name="(П.4) is (1) in x = q̇, y = q + B⁻¹Aq̇"):
        self.claims, self.name = tuple(claims), name

    def symbols(self) -> set:
        return set().union(*(c.functional.expr.free_symbols | {s for term in c.terms for s in term.expr.free_symbols}
                             for c in self.claims)) & set(P2.substitution(P2.resolve({})).keys())

    def evaluate(self, substitution, *, budget=None) -> Result:
        values = {spec.name: substitution[spec.obj] for spec in P2 if spec.obj in substitution}
        if B.subs(substitution).det() == 0:
            return Result("identity", self.name, Status.FAILED, None,
                          "B is singular (det B = 0): y = q + B⁻¹Aq̇ and (П.4) are not defined")
        results = [c.check(substitution, values=values, budget=budget or 60.0) for c in self.claims]
        bad = [(c, r) for c, r in zip(self.claims, results) if r.status is not Status.EXACT]
        if not bad:
            return Result("identity", self.name, Status.EXACT, None,
                          f"each row of (П.4) as printed equals d/dt (Ax)_i, d/dt (By)_i along (1) at the run's "
                          f"values (exact): {', '.join(c.name for c in self.claims)}")
        status = Status.FAILED if any(r.status is Status.FAILED for _, r in bad) else Status.UNDECIDED
        return Result("identity", self.name, status, None,
                      "; ".join(f"{c.name}: {r.status}: {r.detail}" for c, r in bad))


P4_along_1 = P4Along1(printed)


_A_B = tuple(A.free_symbols | B.free_symbols)
_G = tuple(B.free_symbols | Q(sympy.symbols("u1 u2")).free_symbols | D(sympy.symbols("u1 u2")).free_symbols | {tau})

theorem2 = Theorem(
    "theorem2",
    title="Theorem 2 (decomposition): (7), (8) asymptotically stable ⇒ (1) asymptotically stable; "
          "instance n = 2, μ = 3, A, B not symmetric",
    system=system_P4,
    functional=functional,
    hypotheses=[
        Hypothesis("mu > 1", MU - 1, reference="(Theorem 2)"),
        Decided("Q, D homogeneous of order μ", homogeneous_of_order, reference="(1)"),
        Hypothesis("A nonsingular", A.det() ** 2, reference="(1)"),
        Hypothesis("B nonsingular", B.det() ** 2, reference="(1)"),
        Decided("(7) asymptotically stable", decide_7, reads=_A_B, reference="(7)"),
        Decided("(8) asymptotically stable", decide_8, reads=_G, reference="(8)"),
        Decided("1 < (ν2+μ−1)/ν1 < μ", lambda sub: decide_order(NU1, NU2, MU), reference="(proof of Theorem 2)"),
        Decided("order condition = Young's steps", lambda sub: derived_order_condition(NU1, NU2, MU),
                reference="(proof of Theorem 2)"),
        P4_along_1,
    ],
    claims=[derivation],
    steps=steps,
    decay=CONCLUSION,
    choices=find_choices,
    paper=PAPER,
)
