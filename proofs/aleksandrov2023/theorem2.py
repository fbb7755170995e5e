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
  an escaping invariant ray); the order condition for ν1, ν2 (exact);
* the printed (П.4), row by row: d/dt (Ax)_i and d/dt (By)_i derived along (1) with the library's
  derivative (chain rule, Leibniz rule), compared term by term with the printed right sides (findings).

The chain's links after the hypotheses — V̇ of the proof's functional and the estimates with
c1 … c10, m_kj, ε1, ε2, h1, h2 — are not encoded: the verdict names the first of them as missing.
"""

import sympy

from lkverify import Hypothesis, Theorem

from .decomposition import (MU, NU1, NU2, PAPER, A, B, D, Decided, P2, Q, decide_7, decide_8, decide_order,
                            printed_P4, system1)
from lkverify.certify.conditions import ConditionResult, Margin
from lkverify.status import Status

__all__ = ["theorem2", "homogeneous_of_order", "printed"]


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


_A_B = tuple(A.free_symbols | B.free_symbols)
_G = tuple(B.free_symbols | Q(sympy.symbols("u1 u2")).free_symbols | D(sympy.symbols("u1 u2")).free_symbols
           | {P2["tau"].obj}) 

#: the printed (П.4), row by row (findings about the paper)
printed = printed_P4()

theorem2 = Theorem(
    "theorem2",
    title="Theorem 2 (decomposition): (7), (8) asymptotically stable ⇒ (1) asymptotically stable; "
          "instance n = 2, μ = 3, A, B not symmetric",
    system=system1,
    hypotheses=[
        Hypothesis("mu > 1", MU - 1, reference="(Theorem 2)"),
        Decided("Q, D homogeneous of order μ", homogeneous_of_order, reference="(1)"),
        Hypothesis("A nonsingular", A.det() ** 2, reference="(1)"),
        Hypothesis("B nonsingular", B.det() ** 2, reference="(1)"),
        Decided("(7) asymptotically stable", decide_7, reads=_A_B, reference="(7)"),
        Decided("(8) asymptotically stable", decide_8, reads=_G, reference="(8)"),
        Decided("1 < (ν2+μ−1)/ν1 < μ", lambda sub: decide_order(NU1, NU2, MU), reference="(proof of Theorem 2)"),
    ],
    printed=printed,
    paper=PAPER,
)
