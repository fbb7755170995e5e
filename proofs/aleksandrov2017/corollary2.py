"""Corollary 2 of paper 001: for h = (t+1)^{−β} and the nonlinear damping of Theorem 2,
the equilibrium (3) of (2), (4) is asymptotically stable if and only if (14) β ≤ 1.

"If" is Theorem 2: (5), (15) |ḣ| ≤ L h^{1+(1−ν)/(μ+1)} and (11) ∫h^ν = ∞ for some ν ≥ 1.  For
h = (t+1)^{−β} they are decided here exactly (:func:`~.conditions_h.decide_h_conditions` with
the order μ of the damping): they hold iff β ≤ 1, with ν ∈ [1, 1/β].  (Theorem 2's own chain is
the verdict of ``aleksandrov2017.theorem2``.)

"Only if" the paper leaves to the reader, as Remark 2 does for linear damping.  For the
catalogued W = (ωᵀDω)^{(μ+1)/2} it is proved here with the energy

    Ṽ = ½ωᵀJω + (a1/2)‖s1 − r1‖² + (a2/2)‖s2 − r2‖²:

* dṼ/dt = −h ωᵀ grad W = −(μ+1)hW along (2), (4) (exact, Euler's theorem on homogeneous W);
* ωᵀDω ≤ k·½ωᵀJω with k = 2λ_max(D)/λ_min(J) (the matrix kJ/2 − D ⪰ 0, exact), hence, as
  ½ωᵀJω ≤ Ṽ, −dṼ/dt ≤ c h Ṽ^{κ}, c = (μ+1)k^{κ}, κ = (μ+1)/2 > 1;
* integrating, Ṽ(t)^{1−κ} ≤ Ṽ(0)^{1−κ} + (κ−1)c∫_0^t h, so for β > 1 (∫_0^∞ h = 1/(β−1) < ∞)

      lim Ṽ ≥ Ṽ∞ = (Ṽ(0)^{1−κ} + (κ−1)c/(β−1))^{−1/(κ−1)} > 0:

  the equilibrium is not attractive.  Unlike Remark 2's exponential bound, this one is algebraic
  in c, because the damping is weak near ω = 0: for the section 6 data (β = 8/7) it is 8.8·10⁻³.
"""

from __future__ import annotations

import sympy

from lkverify import Check, DerivativeClaim, Result, Status, Term, t
from lkverify.certify.matrices import matrix_positive_definite

from .conditions_h import decide_h_conditions
from .equations import PAPER, D, J, P, h, omega, s1, s2, r1, r2, a1, a2
from .example import HISTORY
from .remark2 import energy
from .theorem2 import W, mu, system4

__all__ = ["corollary2", "corollary2_constants", "energy_rate4", "limit_energy_bound"]

#: dṼ/dt along (2), (4)
energy_rate4 = DerivativeClaim("Vtilde_dot", energy, system4, [Term(-(mu + 1) * h(t) * W, text="−(μ+1)h(t)W(ω)")],
                               description="dṼ/dt along (2),(4) = −h ωᵀgrad W = −(μ+1)hW (Euler's theorem)")

_BETA = sympy.Symbol("beta", positive=True)


def corollary2_constants(values) -> dict:
    """k, κ and c of the module docstring at resolved values (exact).

    Examples
    --------
    >>> corollary2_constants(P.resolve({}, use_defaults=True))
    {'k': 2, 'kappa': 2, 'c': 16}
    """
    ej = sympy.Matrix(values["J"]).eigenvals(multiple=True)
    ed = sympy.Matrix(values["D"]).eigenvals(multiple=True)
    k = 2 * max(ed) / min(ej)
    kappa = (mu + 1) / 2
    return {"k": k, "kappa": kappa, "c": (mu + 1) * k ** kappa}


def limit_energy_bound(V0, c, kappa, tail):
    """Ṽ∞ = (Ṽ(0)^{1−κ} + (κ−1)c·tail)^{−1/(κ−1)}: the lower bound on lim Ṽ when ∫_0^∞ h = tail.

    Examples
    --------
    >>> limit_energy_bound(1, 16, 2, 7)              # Ṽ(0) = 1, c = 16, κ = 2, ∫h = 7 (β = 8/7)
    1/113
    """
    V0, c, kappa, tail = (sympy.sympify(x) for x in (V0, c, kappa, tail))
    return (V0 ** (1 - kappa) + (kappa - 1) * c * tail) ** (-1 / (kappa - 1))


def _plain(value):
    return value if value is None or isinstance(value, (int, float, str)) else str(value)


def _conditions(budget) -> list:
    parts = decide_h_conditions((t + 1) ** (-_BETA), mu=mu, budget=min(float(budget), 30.0))
    found = parts[-1]
    rows = [Result("hypothesis", f"h = (t+1)^(−β): {p.name}", p.status, _plain(p.value), p.detail) for p in parts]
    if found.status is Status.EXACT:
        condition = found.value["condition"]
        same = sympy.simplify(sympy.Equivalent(condition, _BETA <= 1)) is sympy.true
        status, detail = (Status.EXACT if same else Status.FAILED,
                          f"(5), (15), (11) for h = (t+1)^(−β) and μ = {mu} hold iff {condition}: "
                          + ("the paper's (14) β ≤ 1" if same else "not the paper's (14) β ≤ 1"))
    else:
        status, detail = found.status, f"not decided: {found.detail}"
    rows.append(Result("hypothesis", "Corollary 2, if: (15), (11) ⇔ (14) β ≤ 1", status,
                       _plain(found.value and found.value.get("condition")), detail))
    return rows


def _psd(M, name):
    res = matrix_positive_definite(sympy.Matrix(M), name=name, semidefinite=True)
    return res.status, res.detail


def _corollary2_check(v, *, budget=60.0):
    budget = 60.0 if budget is None else float(budget)
    rows = _conditions(budget)
    sub = P.substitution({k: x for k, x in v.items() if k != "h"})
    res = energy_rate4.check(sub, values=v, budget=budget / 2)
    rows.append(Result("identity", energy_rate4.name, res.status, None, f"{energy_rate4.description}: {res.detail}"))
    c = corollary2_constants(v)
    st, det = _psd(c["k"] * sympy.Matrix(v["J"]) / 2 - sympy.Matrix(v["D"]), "k J/2 - D")
    rows.append(Result("bound", "(mu+1) W <= c Vtilde^kappa", st, {"k": str(c["k"]), "c": str(c["c"]),
                                                                  "kappa": str(c["kappa"])},
                       f"k = 2λ_max(D)/λ_min(J) = {c['k']}: kJ/2 − D ⪰ 0 ({det}), so ωᵀDω ≤ k·½ωᵀJω ≤ kṼ and "
                       f"(μ+1)W = (μ+1)(ωᵀDω)^κ ≤ cṼ^κ with κ = {c['kappa']}, c = (μ+1)k^κ = {c['c']}"))
    beta = sympy.Rational(8, 7)  # the non-attractive damping of section 6
    tail = sympy.gammasimp(sympy.integrate((t + 1) ** (-beta), (t, 0, sympy.oo)))
    state = {comp: sympy.Rational(x) for st_ in system4.states for comp, x in zip(st_(t), HISTORY[st_.name])}
    V0 = sympy.sympify(energy.expr).xreplace(sub).xreplace(state)
    bound = limit_energy_bound(V0, c["c"], c["kappa"], tail)
    ok = bound.is_positive and st is Status.EXACT and res.status is Status.EXACT
    rows.append(Result("constant", "Corollary 2, only if: lim Ṽ ≥ Ṽ∞ (β = 8/7, section 6 data)",
                       Status.CERTIFIED if ok else Status.UNDECIDED,
                       {"value": float(bound), "V0": float(V0), "tail": str(tail)},
                       f"∫_0^∞ h = {tail} for h = (t+1)^(−8/7); Ṽ(0) = {float(V0):.6g} at the section 6 initial data "
                       f"(its floating-point entries taken exactly): lim Ṽ ≥ (Ṽ(0)^(1−κ) + (κ−1)c·{tail})^(−1/(κ−1)) = "
                       f"{float(bound):.4g} > 0, so the equilibrium is not attractive for β = 8/7"
                       + ("" if ok else " — not proved: a step above is not exact")))
    return rows


corollary2 = Check("corollary2", parameters=P, checks=[_corollary2_check], paper=PAPER,
                   relevant=("J", "D", "a1", "a2", "r1", "r2"),
                   title="Corollary 2: nonlinear damping (W = (ωᵀDω)², μ = 3), h = (t+1)^(−β): asymptotically "
                         "stable iff β ≤ 1 (the conditions exact; for β > 1 a certified positive limit energy)")
