"""The regulation example (2.10) of paper 004: (2.7) with ω_d = ω̇_d = 0.

Printed:

    (2.10)  u = −K_d ω − K_d Σkᵢ sᵢ × cᵢ − ΛY(ω, e, ė)θ_r.

Derived from (2.7) with ω_r = −Λe, ω̇_r = −Λė, v = ω + Λe, M_r = diag(θ_r) and
Y(ω, e, ė)θ_r = M_r ė + e × M_r ω (1.5):

    u = −K_d ω − ΛK_d Σkᵢ sᵢ × cᵢ − ΛY(ω, e, ė)θ_r.

The second printed term lacks the factor Λ (the print is right only for Λ = 1).  Both forms
are checked component by component at the run's values, the print also at Λ = 1.
"""

from __future__ import annotations

import sympy

from lkverify import Check, cross, t

from lkverify.symbolic.polynomial import compare_polynomials as compare, plain
from .equations import PAPER, EDOT, Kd, Lam, P, Y, e, omega, omega_r, omega_r_dot, theta_r, v, wd

__all__ = ["example210", "control_27", "printed_210", "example210_results"]

_ZERO = {f: sympy.Integer(0) for f in wd}  # ω_d = 0 (hence ω̇_d = 0)


def _zero_reference(expr):
    expr = sympy.sympify(expr).doit()
    expr = expr.xreplace({sympy.Derivative(f, t): 0 for f in wd})
    return expr.xreplace(_ZERO)


def control_27():
    """The two terms of u of (2.7) with M_r = diag(θ_r) (principal axes: N(ω, L_0r) = M_rω), as (label, vector)."""
    M_r = sympy.diag(*theta_r(t))
    return [("M_rω̇_r + ω_r×M_rω", M_r * omega_r_dot + cross(omega_r, M_r * omega(t))), ("−K_d v", -Kd * v)]


def printed_210():
    """The three printed terms of (2.10), as (label, vector)."""
    edot0 = EDOT
    return [("−K_d ω", -Kd * omega(t)), ("−K_d Σkᵢsᵢ×cᵢ", -Kd * e),
            ("−ΛY(ω, e, ė)θ_r", -Lam * Y(omega(t), e, edot0) * theta_r(t))]


def example210_results(v, printed=None, *, name="(2.10) as printed"):
    """(2.10) against (2.7) at ω_d = 0, component by component."""
    sub = P.substitution({k: x for k, x in v.items() if not k.startswith("wd")})
    u = control_27()
    printed = printed_210() if printed is None else printed
    out = []
    for i in range(3):
        p = [(lab, plain(_zero_reference(vec[i]).xreplace(sub))) for lab, vec in printed]
        d = [(lab, plain(_zero_reference(vec[i]).xreplace(sub))) for lab, vec in u]
        out.append(compare(f"{name}, component {i + 1}", p, d, reference=name))
    return out


def _check(v):
    corrected = [("−K_d ω", -Kd * omega(t)), ("−ΛK_d Σkᵢsᵢ×cᵢ", -Lam * Kd * e),
                 ("−ΛY(ω, e, ė)θ_r", -Lam * Y(omega(t), e, EDOT) * theta_r(t))]
    out = example210_results(v)
    out += example210_results({**v, "Lam": sympy.Integer(1)}, name="(2.10) as printed, at Λ = 1")
    out += example210_results(v, corrected, name="(2.10) with ΛK_d e")
    return out


example210 = Check("example210", parameters=P, checks=[_check], paper=PAPER,
                   relevant=("Kd", "Lam", "k1", "k2", "k3", "c1", "c2", "c3"),
                   title="Example (2.10): (2.7) at ω_d = 0 derived and compared with its print")
