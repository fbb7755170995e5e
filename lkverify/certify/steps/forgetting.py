"""Least squares with bounded-gain forgetting: the gain stays positive definite and bounded.

    Ẋ = κ(FFᵀ − λ(t)X),   λ(t) = λ0(1 − N(X⁻¹)/k0),   κ, λ0, k0 > 0,   X(0) ≻ 0, N(X(0)⁻¹) ≤ k0,

with N the spectral or the Frobenius norm, is the update of the
inverse gain X = Γ⁻¹ in composite adaptive control (paper 004's (3.4), Slotine and Li's
"bounded-gain forgetting").  :class:`Forgetting` licenses, for every t ≥ 0 of a solution,

    **X(t) ⪰ I/k0 ≻ 0,  N(X(t)⁻¹) ≤ k0,  0 ≤ λ(t) ≤ λ0**            (property (a) of (3.4)),

after deciding along the system that the rate of X is κ(FFᵀ − λX) entry by entry (an exact
polynomial identity, with λ a free symbol: it holds whatever scalar λ(t) is), that X is symmetric
and that κ, λ0, k0 are positive numbers.  The initial data (X(0) ≻ 0, N(X(0)⁻¹) ≤ k0) are the
law's own hypothesis and are named in the result.

Proof (the rule).  (i) X stays positive definite: λ is a scalar, so
X(t) = e^{−κ∫_0^tλ}X(0) + ∫_0^t e^{−κ∫_s^tλ}κF(s)F(s)ᵀds ⪰ e^{−κ∫_0^tλ}X(0) ≻ 0, and Γ = X⁻¹ exists.
(ii) Γ̇ = −ΓẊΓ = −κΓFFᵀΓ + κλΓ.  Spectral norm: for r(t) = λ_max(Γ(t)) = ‖Γ(t)‖₂,
D⁺r ≤ max{xᵀΓ̇x : ‖x‖ = 1, Γx = rx} ≤ κλr (the first term is ≤ 0).  Frobenius norm: for
r = ‖Γ‖_F, d/dt r² = 2tr(ΓΓ̇) = −2κ‖Γ^{3/2}F‖²_F + 2κλr² ≤ 2κλr².  Either way, with λ = λ0(1 − r/k0),
D⁺r ≤ φ(r) = κλ0(1 − r/k0)r; φ is Lipschitz and φ(k0) = 0, so r(0) ≤ k0 gives r(t) ≤ k0 (comparison
lemma).  Hence λ ≥ 0, λ ≤ λ0 (r ≥ 0) and X = Γ⁻¹ ⪰ I/λ_max(Γ) ⪰ I/k0 (λ_max ≤ ‖Γ‖_F).  The initial
condition is N(X(0)⁻¹) ≤ k0 in the law's own norm N.
"""

from __future__ import annotations

import dataclasses

import sympy

from ...report.results import Result
from ...status import Status
from .signals import Facts

__all__ = ["Forgetting"]


def _positive_number(x, sub) -> tuple:
    x = sympy.sympify(x).xreplace(sub) if sub else sympy.sympify(x)
    if x.free_symbols or x.is_real is not True:
        return Status.UNDECIDED, f"{x} is not a number"
    return (Status.EXACT, f"{x} > 0") if x > 0 else (Status.FAILED, f"{x} ≤ 0")


@dataclasses.dataclass(frozen=True)
class Forgetting:
    """**X(t) ⪰ I/k0, N(X(t)⁻¹) ≤ k0, 0 ≤ λ(t) ≤ λ0** for Ẋ = κ(FFᵀ − λX), λ = λ0(1 − N(X⁻¹)/k0).

    Parameters
    ----------
    signal : str
        The name of X (e.g. "Γ⁻¹").
    X : square matrix
        The symmetric matrix of states (at t).
    F : matrix
        The regressor (states at t or functions of them).
    kappa, lam0, k0 : expressions in the parameters
        κ, λ0 and k0 of the law.
    lam : Symbol
        The forgetting factor λ(t) as the system carries it (a free symbol, not a state).
    norm : str
        The norm N of the law: "spectral" or "Frobenius" (each has its barrier, see the module).
    inverse : str
        The name of X⁻¹ in the link's name (e.g. "Γ"; default "(X)⁻¹").

    Examples
    --------
    Ẋ = (FFᵀ − λX)/2 for a scalar state X and a state f (ḟ = −f):

    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> lam = sympy.Symbol("lambda", nonnegative=True)
    >>> Xs, Fs = Vector("X", 1), Vector("f", 1); x, f = Xs(t)[0], Fs(t)[0]
    >>> good = System([Equation(Xs, [Term((f**2 - lam * x) / 2)]), Equation(Fs, [Term(-f)])], parameters=Parameters())
    >>> link = Forgetting("X", sympy.Matrix([[x]]), sympy.Matrix([[f]]), sympy.Rational(1, 2), lam, 2, 10)
    >>> link.decide(Facts(good, {}, {})).status.value
    'exact'
    >>> bad = System([Equation(Xs, [Term((-f**2 - lam * x) / 2)]), Equation(Fs, [Term(-f)])], parameters=Parameters())
    >>> link.decide(Facts(bad, {}, {})).status.value                     # −FFᵀ: X may lose definiteness
    'failed'
    """

    signal: str
    X: object
    F: object
    kappa: object
    lam: object
    lam0: object
    k0: object
    norm: str = "spectral"
    inverse: str = ""

    def __post_init__(self):
        from ...errors import InputError

        if self.norm not in ("spectral", "Frobenius"):
            raise InputError(f"Forgetting: norm must be 'spectral' or 'Frobenius' (a norm ≥ the spectral one), "
                             f"got {self.norm!r}")
        if not isinstance(self.lam, sympy.Symbol):
            raise InputError(f"Forgetting: lam must be the symbol the system carries for λ(t), got {self.lam!r}")

    @property
    def name(self) -> str:
        inv = self.inverse or f"({self.signal})⁻¹"
        return f"(a) {self.signal} ⪰ I/k0, ‖{inv}‖ ≤ k0, 0 ≤ λ ≤ λ0 (bounded-gain forgetting)"

    def decide(self, facts: Facts) -> Result:
        from ...symbolic.polynomial import compare_polynomials

        X, F = sympy.Matrix(self.X), sympy.Matrix(self.F)
        parts = []
        if X.shape[0] != X.shape[1] or X != X.T:
            parts.append((Status.FAILED, f"{self.signal} is not a symmetric matrix of states"))
        if str(self.lam) in {str(s) for s in facts.states}:
            parts.append((Status.FAILED, f"λ = {self.lam} is a state of the system, not the law's λ(t)"))
        for what, x in (("κ", self.kappa), ("λ0", self.lam0), ("k0", self.k0)):
            st, why = _positive_number(x, facts.sub)
            parts.append((st, f"{what}: {why}"))
        if not parts or all(st is not Status.FAILED for st, _ in parts[:2]):
            law = self.kappa * (F * F.T - self.lam * X)
            n = X.shape[0]
            for i in range(n):
                for j in range(i, n):
                    res = compare_polynomials(f"d/dt {self.signal}[{i + 1},{j + 1}]",
                                              [("κ(FFᵀ − λX)", facts.plain(law[i, j]))],
                                              [("rate along the system", facts.rate(X[i, j]))],
                                              reference="the law of X")
                    parts.append((res.status, f"entry ({i + 1},{j + 1}): {res.status}"))
        status = Status.weakest(st for st, _ in parts)
        k0 = sympy.sympify(self.k0).xreplace(facts.sub)
        facts.bounded[f"({self.signal})⁻¹"] = (status, f"‖({self.signal})⁻¹‖ ≤ k0 = {k0}")
        bad = [why for st, why in parts if not st.is_proof]
        detail = ("; ".join(bad) if bad else
                  f"the rate of {self.signal} is κ(FFᵀ − λ{self.signal}) along the system (every entry exact, "
                  f"λ any scalar), {self.signal} symmetric, κ, λ0, k0 > 0; λ = λ0(1 − N/k0) with N the "
                  f"{self.norm} norm: from {self.signal}(0) ≻ 0, N({self.signal}(0)⁻¹) ≤ k0 "
                  f"(the law's initial data), {self.signal}(t) ⪰ I/{k0}, ‖({self.signal})⁻¹‖ ≤ {k0} and "
                  f"0 ≤ λ(t) ≤ λ0 for t ≥ 0 (variation of constants; D⁺N ≤ κλ0(1 − N/k0)N)")
        return Result("bound", self.name, status, {"k0": str(k0)}, detail)
