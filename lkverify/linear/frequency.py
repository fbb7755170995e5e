"""The crossing-frequency polynomial of a linear delay system (exact algebra, SymPy).

For rational matrices and a constant kernel D, a root λ = iω crosses the imaginary axis for
the delay h exactly when z = e^{−iωh} is a unimodular root of

    q(ω, z) = det( iω(iωI − A − A_d z) − D(1 − z) ),

and every such ω is a real root of P = Res_z(q, z^{deg} q̄(ω, 1/z)) ∈ ℚ[ω].  Both the estimated
stability intervals (:mod:`.crossing`) and their certified stretches (:mod:`.stretches`) start here.
"""

from __future__ import annotations

import sympy

from .model import LinearDelaySystem

__all__ = ["frequency_polynomial"]


def frequency_polynomial(system: LinearDelaySystem):
    """``(P, q, (z, ω))``: P ∈ ℚ[ω] whose real roots contain every crossing frequency, and q(ω, z); or None.

    None when unsupported (irrational matrices, a polynomial kernel, no delayed term, a resultant ≡ 0).

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> P, q, (z, w) = frequency_polynomial(LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]]))
    >>> [round(float(r), 12) for r in sympy.real_roots(P) if r > 0]     # √0.19
    [0.435889894354]
    """
    if not (system.is_rational and system.constant_kernel):
        return None
    w, z = sympy.symbols("omega z", real=True)  # real symbols: conjugation acts on the coefficients only
    n = system.n
    D = system.kernel[0] if system.has_distributed else sympy.zeros(n, n)
    M = sympy.I * w * (sympy.I * w * sympy.eye(n) - system.A - system.Ad * z) - D * (1 - z)
    q_expr = sympy.expand(M.det(method="berkowitz"))
    q = sympy.Poly(q_expr, z, w, domain="QQ_I")
    if q.is_zero or q.degree(z) <= 0:
        return None
    dz = q.degree(z)
    qbar = sympy.Poly(sympy.expand(z ** dz * sympy.conjugate(q_expr).subs(z, 1 / z)), z, w, domain="QQ_I")
    R = sympy.Poly(sympy.resultant(q, qbar).as_expr(), w)
    if R.is_zero:
        return None
    coeffs = R.all_coeffs()
    re = sympy.Poly([sympy.re(c) for c in coeffs], w)
    im = sympy.Poly([sympy.im(c) for c in coeffs], w)
    P = re if not re.is_zero else im
    if not im.is_zero and not re.is_zero:
        P = sympy.gcd(re, im)
    P = sympy.Poly(P, w, domain="QQ")
    return P, q, (z, w)
