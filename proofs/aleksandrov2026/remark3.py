"""Remark 3 of paper 000: the PID of Theorem 2 may have a non-restoring proportional part, β ≤ 0.

The remark (section 4) says: if β ≤ 0, choose G(ζ) = a g(ζ) I with a > 0 and a scalar g,
continuous on [0, +∞), with

    (a) [а)]  ∫_0^∞ |g| < ∞,   (b) [б)]  ∫_ζ^∞ |g| ≤ σ |g(ζ)| for ζ ≥ 0,   (c) [в)]  ∫_0^∞ g > 0;

then Assumption 1 holds, and Assumption 2 reduces to β + a∫_0^∞ g > 0, "which holds for a
large enough".  Checked here, for the run's β ≤ 0, g and D, each as its own result:

* (a), (b) by :func:`~.assumption1.decide_assumption1` on g (the scale a > 0 cancels from (b):
  ∫_ζ^∞|ag| / |ag(ζ)| = ∫_ζ^∞|g| / |g(ζ)|, so Assumption 1 for aG̃ is Assumption 1 for g);
* (c) ∫_0^∞ g computed exactly;
* the reduction: with Ξ = βI + ∫_0^∞ G = (β + a∫g) I, the matrix ΞD + DΞᵀ − 2(β + a∫g)D is
  identically zero (exact, for the run's D), and D ≻ 0, so Assumption 2 ⇔ β + a∫g > 0;
* "a large enough" made exact: the threshold a* = −β / ∫_0^∞ g, Assumption 2 holding exactly for
  a > a*; with ``--set a=…`` the run's a is decided against it (exact margin β + a∫g).

A kernel without (c) (∫g ≤ 0) admits no a: the remark's construction fails, and the report says
so with the value of ∫g.  β > 0 is outside the remark (use ``aleksandrov2026.theorem2``).
Whether Theorem 2 then applies is Theorem 2's own verdict (``lkverify check
aleksandrov2026.theorem2 --set beta=… --set "g=a*…"``): this item checks the remark's reduction.
"""

from __future__ import annotations

import sympy

from lkverify import Check, InputError, Parameters, Result, Status, zeta
from lkverify.certify.matrices import matrix_positive_definite

from .assumption1 import decide_assumption1
from .equations import PAPER

__all__ = ["P3", "remark3", "threshold"]

#: the remark's own parameters: β ≤ 0, the kernel shape g, the scale a (optional) and D
P3 = Parameters()
beta = P3.scalar("beta", default=-1, latex=r"\beta", description="proportional gain β ≤ 0 (Remark 3)")
g = P3.kernel("g", default="exp(-2*zeta)", description="kernel shape: G(ζ) = a g(ζ) I")
a = P3.scalar("a", positive=True, description="scale of the kernel, G = a g I (optional: the threshold is found)")
D = P3.spd_matrix("D", 3, default="diag(2,2,2)", description="damping matrix, constant PD")


def threshold(beta_value, g_expr):
    """The exact a* = −β/∫_0^∞ g of Remark 3 (None when ∫g ≤ 0 or is not finite).

    Examples
    --------
    >>> import sympy
    >>> threshold(-1, sympy.exp(-2 * zeta))
    2
    >>> threshold(-1, sympy.exp(-zeta) * (1 - 2 * zeta)) is None      # ∫g = −1: no a works
    True
    """
    integral = sympy.integrate(g_expr, (zeta, 0, sympy.oo))
    if not (integral.is_finite and integral.is_positive):
        return None
    return -sympy.sympify(beta_value) / integral


def _kernel(values):
    lam = values["g"]
    return lam(zeta) if isinstance(lam, sympy.Lambda) else sympy.sympify(lam)


def _remark3_check(v, *, budget=60.0):
    b = sympy.sympify(v["beta"])
    if not b.is_nonpositive:
        raise InputError(f"beta: Remark 3 is about a non-restoring proportional part, expected β ≤ 0, got {b}; "
                         f"for β > 0 run aleksandrov2026.theorem2")
    gz = _kernel(v)
    rows = []
    a1 = decide_assumption1(gz, budget=min(float(budget or 60.0), 20.0))
    rows.append(Result("hypothesis", "(a), (b) Assumption 1 for G = a g I", a1.status, a1.sigma,
                       f"for every a > 0 (a cancels from ∫_ζ^∞|ag|/|ag(ζ)|): {a1.detail}"))
    integral = sympy.integrate(gz, (zeta, 0, sympy.oo))
    positive = bool(integral.is_finite and integral.is_positive)
    decided = integral.is_finite is not None and integral.is_positive is not None and not integral.has(sympy.Integral)
    rows.append(Result("hypothesis", "(c) ∫_0^∞ g > 0",
                       Status.EXACT if positive else Status.FAILED if decided else Status.UNDECIDED, str(integral),
                       f"∫_0^∞ g(ζ)dζ = {integral}" + ("" if positive else
                                                        ": no a > 0 makes β + a∫g > 0, the remark's construction fails"
                                                        if decided else ": SymPy could not decide its sign")))
    Dm = sympy.Matrix(v["D"])
    A = sympy.Symbol("a", positive=True)
    Xi = (b + A * integral) * sympy.eye(3)
    residue = sympy.simplify(Xi * Dm + Dm * Xi.T - 2 * (b + A * integral) * Dm)
    pd = matrix_positive_definite(Dm, name="D")
    status = Status.FAILED if residue != sympy.zeros(3, 3) else pd.status
    rows.append(Result("identity", "Assumption 2 ⇔ β + a∫g > 0", status,
                       None, "ΞD + DΞᵀ = 2(β + a∫g)D exactly for Ξ = (β + a∫g)I, and D ≻ 0 "
                       f"({pd.detail}), so ΞD + DΞᵀ ≻ 0 iff β + a∫g > 0"))
    if positive:
        a_star = -b / integral  # = threshold(b, g)
        rows.append(Result("constant", "a* (Assumption 2 holds iff a > a*)", Status.EXACT,
                           {"value": float(a_star), "exact": str(a_star)},
                           f"a* = −β/∫_0^∞ g = {a_star} (exact): 'a large enough' means a > {a_star}"))
        if v.get("a") is not None:
            av = sympy.sympify(v["a"])
            margin = sympy.simplify(b + av * integral)
            rows.append(Result("hypothesis", f"Assumption 2 at a = {av}",
                               Status.EXACT if margin.is_positive else Status.FAILED, str(margin),
                               f"β + a∫g = {margin} " + ("> 0" if margin.is_positive else
                                                          f"≤ 0: a = {av} is not above a* = {a_star}")))
    return rows


remark3 = Check("remark3", parameters=P3, checks=[_remark3_check], paper=PAPER, relevant=("beta", "g", "a", "D"),
                title="Remark 3: β ≤ 0 is allowed with G = a g I; Assumption 2 ⇔ β + a∫g > 0, the threshold a* exact")
