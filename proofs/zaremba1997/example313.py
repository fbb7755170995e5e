"""The pointing example (3.13), (3.14) of paper 004: one body axis c0 pointed along s0(t).

    e = s0 × c0,  V_δ = (s0 − c0)²,
    (3.13)  u = M_rω̇_d + ω_d × N(ω, L_0r) − K_e e − K_v ω_e − ΛY(ω, e, ė)θ_r,
            K_e = (K_p + αΛ)I + λ_cΛM_r,  K_v = αI + λ_cM_r,
    (3.14)  D: s0·c0 > 2/Λ − 1,
    text:   "for Λ > 1 the region D surrounds s0 = c0, and as Λ decreases it tends to the unit sphere".

Checked: (3.13) is the first law of (3.2) rewritten (exact for every e, ė: it does not depend on the
pointing form of e); with x = s0·c0, ‖s0 × c0‖² = 1 − x² and ‖s0 − c0‖² = 2 − 2x on unit vectors, so
eᵀe − V_δ/Λ = (1 − x)(1 + x − 2/Λ) and (3.6) is (3.14) for x < 1 (exact).  D covers the fraction
1 − 1/Λ of the sphere (Λ > 1; empty for Λ ≤ 1): it *grows* with Λ and tends to the sphere as Λ → ∞,
not as Λ decreases — the text's last sentence has the direction reversed.
"""

from __future__ import annotations

import sympy

from lkverify import Check, Result, Status, cross, dot

from lkverify.symbolic.polynomial import compare_polynomials as compare
from .equations import PAPER, Kp, Lam, P, Y, alpha, composite_laws, lam_c

__all__ = ["example313", "control_313_results", "region_314", "region_fraction", "LAMBDAS"]

#: the Λ of the table of D against Λ (the run's Λ is added)
LAMBDAS = ("1/2", "1", "3/2", "2", "4", "10", "100")


def _vec(name):
    return sympy.Matrix(sympy.symbols(f"{name}1:4", real=True))


def control_313_results(values, printed_Ke=None):
    """(3.13) against the first law of (3.2), component by component (every vector symbolic)."""
    sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
    w, wd_, wdd, e_, ed, th = (_vec(n) for n in ("w", "wd", "wdd", "e", "ed", "th"))
    I3 = sympy.eye(3)
    law = composite_laws(w, wd_, wdd, e_, ed, th, _vec("ep"), I3, I3, I3, 0)
    M_r = sympy.diag(*th)
    L, a, kp, lc = (sympy.sympify(q).xreplace(sub) for q in (Lam, alpha, Kp, lam_c))
    Ke = (kp + a * L) * I3 + lc * L * M_r if printed_Ke is None else printed_Ke(kp, a, L, lc, M_r)
    Kv = a * I3 + lc * M_r
    we = w - wd_
    printed = [("M_rω̇_d", M_r * wdd), ("ω_d×M_rω", cross(wd_, M_r * w)), ("−K_e e", -Ke * e_), ("−K_vω_e", -Kv * we),
               ("−ΛY(ω, e, ė)θ_r", -L * Y(w, e_, ed) * th)]
    u = law["u"].xreplace(sub)
    return [compare(f"(3.13), component {i + 1}", [(lab, x[i]) for lab, x in printed],
                    [("Y_cθ_r − K_pe − αv (3.2)", u[i])], reference="(3.13)") for i in range(3)]


def region_314(values, printed_threshold=None):
    """(3.6) for the pointing case against the printed (3.14) s0·c0 > 2/Λ − 1 (or another ``printed_threshold(Λ)``): exact.

    A threshold below 2/Λ − 1 claims too large a region: it is refuted at an exact x = s0·c0 between
    the two, where eᵀe − V_δ/Λ < 0.
    """
    s, c = _vec("s0"), _vec("c0")
    x = sympy.Symbol("x", real=True)
    L = sympy.sympify(values["Lam"])
    out = [compare("‖s0 × c0‖² = ‖s0‖²‖c0‖² − (s0·c0)² (Lagrange)", [("‖s0×c0‖²", dot(cross(s, c), cross(s, c)))],
                   [("‖s0‖²‖c0‖²", dot(s, s) * dot(c, c)), ("−(s0·c0)²", -dot(s, c) ** 2)], reference="Lagrange's identity")]
    lhs = (1 - x ** 2) - (2 - 2 * x) / L        # eᵀe − V_δ/Λ on unit vectors, x = s0·c0
    fac = sympy.factor(lhs)
    roots = sorted(r for r in sympy.solve(lhs, x) if r != 1)
    derived = roots[0] if roots else sympy.Integer(1)  # eᵀe − V_δ/Λ = (1 − x)(x − derived)
    printed = 2 / L - 1 if printed_threshold is None else sympy.sympify(printed_threshold(L))
    same = sympy.expand(lhs - (1 - x) * (x - printed)) == 0
    if same:
        status, detail = Status.EXACT, "the printed region is (3.6) exactly"
    elif printed < derived:
        wx = (printed + derived) / 2
        status = Status.FAILED
        detail = (f"too large: at s0·c0 = {wx} (inside the printed region) eᵀe − V_δ/Λ = {lhs.subs(x, wx)} < 0, "
                  f"outside (3.6)")
    else:
        status, detail = Status.FAILED, f"smaller than (3.6): s0·c0 ∈ ({derived}, {printed}] is in (3.6) but not printed"
    out.append(Result("region", "(3.14): eᵀe > V_δ/Λ ⇔ s0·c0 > 2/Λ − 1 (s0 ≠ c0)", status,
                      {"derived": str(derived), "printed": str(printed)},
                      f"eᵀe − V_δ/Λ = {fac}, x = s0·c0 ∈ [−1, 1]: for x < 1 positive iff x > {derived}; printed "
                      f"threshold {printed}: {detail}"))
    return out


def region_fraction(Lam_value):
    """The fraction of the unit sphere covered by D (3.14): (1 − (2/Λ − 1))/2 = 1 − 1/Λ, clipped to [0, 1]."""
    a = 2 / sympy.sympify(Lam_value) - 1
    return sympy.Max(0, sympy.Min(1, (1 - a) / 2))


def _dependence(values):
    L = sympy.Symbol("Lambda", positive=True)
    frac = 1 - 1 / L
    grows = sympy.diff(frac, L)
    table = {str(lv): str(region_fraction(lv)) for lv in sorted({*map(sympy.Rational, LAMBDAS),
                                                                  sympy.sympify(values["Lam"])})}
    contains = Result("region", "for Λ > 1, D ∪ {c0} is a neighbourhood of s0 = c0 on the sphere",
                      Status.EXACT, table, "x > 2/Λ − 1 holds near x = 1 iff 2/Λ − 1 < 1 ⇔ Λ > 1; fraction of the sphere "
                      "covered by D against Λ: " + ", ".join(f"Λ = {k}: {v}" for k, v in table.items()))
    text = Result("region", "text: 'as Λ decreases D tends to the unit sphere'", Status.FAILED,
                  {"d_fraction_dLambda": str(grows)},
                  f"the covered fraction 1 − 1/Λ has derivative {grows} > 0 in Λ: D shrinks as Λ decreases (empty for "
                  f"Λ ≤ 1) and tends to the sphere as Λ → ∞ (the text has the direction reversed)")
    return [contains, text]


def _check(values):
    return control_313_results(values) + region_314(values) + _dependence(values)


example313 = Check("example313", parameters=P, checks=[_check], paper=PAPER,
                   relevant=("Lam", "Kp", "alpha", "lam_c"),
                   title="Pointing example: (3.13) from (3.2), the region (3.14) and how it changes with Λ")
