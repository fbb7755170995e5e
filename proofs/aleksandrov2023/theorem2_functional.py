"""The functional of the proof of Theorem 2 of paper 002 and its V̇ along (П.4), in the structured form.

For V1 = xᵀS1x, V2 = yᵀS2y (ν1 = ν2 = 2), μ = 3, S1, S2 any symmetric matrices and α1, β1, α2, β2 > 0:

    V = V1(x) + V2(y) − (∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ + ∫(α1 + β1(ξ+τ−t))‖x‖^{ν1} + ∫(α2 + β2(ξ+τ−t))‖y‖^{ν2+μ−1}.

The theorem (:mod:`.theorem2`) and its chain (:mod:`.theorem2_chain`) both read these.
"""

import sympy

from lkverify import DerivativeClaim, Functional, Term, norm_squared, quad, t, window_integral, xi

from .decomposition import A, B, D, P2, Q, q_of_xy, system_P4, tau, x, y

__all__ = ["functional", "structured_Vdot", "derivation", "S1", "S2", "alpha1", "beta1", "alpha2", "beta2"]

# The functional of the proof for V1 = xᵀS1x, V2 = yᵀS2y (ν1 = ν2 = 2), μ = 3, with S1, S2 any symmetric
# matrices (the run's P1, P2 are such matrices) and α1, β1, α2, β2 > 0 free:
#   V = V1(x) + V2(y) − (∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ + ∫(α1 + β1(ξ+τ−t))‖x‖^{ν1} + ∫(α2 + β2(ξ+τ−t))‖y‖^{ν2+μ−1}
S1 = P2.spd_matrix("S1", 2, default="diag(1,1)", latex="P_1", description="V1 = xᵀS1x (the functional's)")
S2 = P2.spd_matrix("S2", 2, default="diag(1,1)", latex="P_2", description="V2 = yᵀS2y (the functional's)")
alpha1, beta1, alpha2, beta2 = (P2.scalar(n, positive=True, default=1, latex=rf"\{n[:-1]}_{n[-1]}")
                                for n in ("alpha1", "beta1", "alpha2", "beta2"))
_Binv, _Ainv = B.inv(), A.inv()
_x, _y, _q = sympy.Matrix(x(t)), sympy.Matrix(y(t)), q_of_xy(t)
_K = window_integral(D(sympy.Matrix(y(xi))), tau, weight=xi + tau - t)   # ∫(ξ+τ−t)D(y(ξ))dξ
_J = window_integral(D(q_of_xy(xi)), tau)                                # ∫D(y(ξ) − B⁻¹Ax(ξ))dξ
_Jy = window_integral(D(sympy.Matrix(y(xi))), tau)                       # ∫D(y(ξ))dξ
_w = xi + tau - t

functional = Functional([
    Term(quad(_x, S1), text="V1 = xᵀS1x", latex=r"x^\top S_1 x"),
    Term(quad(_y, S2), text="V2 = yᵀS2y", latex=r"y^\top S_2 y"),
    Term(-2 * quad(S2 * _y, _Binv, _K), text="−(∂V2/∂y)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ",
         latex=r"-\left(\frac{\partial V_2}{\partial y}\right)^\top B^{-1}\int(\xi+\tau-t)D(y(\xi))d\xi"),
    Term(window_integral(norm_squared(x(xi)), tau, weight=alpha1 + beta1 * _w), text="∫(α1+β1(ξ+τ−t))‖x(ξ)‖²dξ",
         latex=r"\int_{t-\tau}^t(\alpha_1+\beta_1(\xi+\tau-t))\|x(\xi)\|^2d\xi"),
    Term(window_integral(norm_squared(y(xi)) ** 2, tau, weight=alpha2 + beta2 * _w), text="∫(α2+β2(ξ+τ−t))‖y(ξ)‖⁴dξ",
         latex=r"\int_{t-\tau}^t(\alpha_2+\beta_2(\xi+\tau-t))\|y(\xi)\|^4d\xi"),
], name="V of the proof of Theorem 2 (ν1 = ν2 = 2, μ = 3)")

# V̇ along (П.4) in the structured form the printed estimate (m14, c1 … c4, m24, c10, the α, β terms) bounds
structured_Vdot = [
    Term(-2 * quad(_x, S1 * _Ainv * B), text="−(∂V1/∂x)ᵀA⁻¹Bx = −2xᵀS1A⁻¹Bx", latex=r"-2x^\top S_1A^{-1}Bx"),
    Term(-2 * quad(_x, S1 * _Ainv, Q(_q)), text="−2xᵀS1A⁻¹Q(y−B⁻¹Ax)", latex=r"-2x^\top S_1A^{-1}Q(y-B^{-1}Ax)"),
    Term(-2 * quad(_x, S1 * _Ainv, _J), text="−2xᵀS1A⁻¹∫D(y(ξ)−B⁻¹Ax(ξ))dξ",
         latex=r"-2x^\top S_1A^{-1}\int_{t-\tau}^t D(y(\xi)-B^{-1}Ax(\xi))d\xi"),
    Term(-2 * quad(_y, S2 * _Binv, Q(_y) + tau * D(_y)), text="−(∂V2/∂y)ᵀB⁻¹(Q(y)+τD(y))",
         latex=r"-2y^\top S_2B^{-1}(Q(y)+\tau D(y))"),
    Term(2 * quad(_y, S2 * _Binv, Q(_y) - Q(_q)), text="2yᵀS2B⁻¹(Q(y)−Q(y−B⁻¹Ax))",
         latex=r"2y^\top S_2B^{-1}(Q(y)-Q(y-B^{-1}Ax))"),
    Term(2 * quad(_y, S2 * _Binv, _Jy - _J), text="2yᵀS2B⁻¹∫(D(y(ξ))−D(y(ξ)−B⁻¹Ax(ξ)))dξ",
         latex=r"2y^\top S_2B^{-1}\int_{t-\tau}^t(D(y(\xi))-D(y(\xi)-B^{-1}Ax(\xi)))d\xi"),
    Term(2 * quad(S2 * _Binv * (Q(_q) + _J), _Binv, _K), text="−(∂²V2/∂y² ẏ)ᵀB⁻¹∫(ξ+τ−t)D(y(ξ))dξ",
         latex=r"-\left(\frac{\partial^2V_2}{\partial y^2}\dot y\right)^\top B^{-1}\int_{t-\tau}^t(\xi+\tau-t)D(y(\xi))d\xi"),
    Term((alpha1 + beta1 * tau) * norm_squared(_x), text="(α1+β1τ)‖x‖²", latex=r"(\alpha_1+\beta_1\tau)\|x\|^2"),
    Term(-alpha1 * norm_squared(x(t - tau)), text="−α1‖x(t−τ)‖²", latex=r"-\alpha_1\|x(t-\tau)\|^2"),
    Term(-beta1 * window_integral(norm_squared(x(xi)), tau), text="−β1∫‖x(ξ)‖²dξ", latex=r"-\beta_1\int_{t-\tau}^t\|x(\xi)\|^2d\xi"),
    Term((alpha2 + beta2 * tau) * norm_squared(_y) ** 2, text="(α2+β2τ)‖y‖⁴", latex=r"(\alpha_2+\beta_2\tau)\|y\|^4"),
    Term(-alpha2 * norm_squared(y(t - tau)) ** 2, text="−α2‖y(t−τ)‖⁴", latex=r"-\alpha_2\|y(t-\tau)\|^4"),
    Term(-beta2 * window_integral(norm_squared(y(xi)) ** 2, tau), text="−β2∫‖y(ξ)‖⁴dξ", latex=r"-\beta_2\int_{t-\tau}^t\|y(\xi)\|^4d\xi"),
]

#: V̇ along (П.4): the ∫D(y(ξ))dξ terms of V̇2 and of the weighted integral cancel, leaving −(∂V2/∂y)ᵀB⁻¹(Q + τD)
derivation = DerivativeClaim("Vdot_structured", functional, system_P4, structured_Vdot,
                             description="V̇ along (П.4) in the structured form of the estimate with m14, c1…c4, "
                                         "m24, c10 (the key term −(∂V2/∂y)ᵀB⁻¹(Q(y)+τD(y)))")
