"""Paper 003 (Somov et al.): the parameters, the states and the closed loop (3), (11).

The attitude of the body basis B in the inertial basis I is given by the quaternion
Λ = (λ0, λ), by the Euler axis e and angle Φ (λ0 = cos(Φ/2), λ = e sin(Φ/2)) and by the
modified Rodrigues parameters (MRP) σ = e tan(Φ/4) = λ/(1 + λ0).  With the angular momentum of
the gyro cluster balanced (G ≡ 0) and u = J⁻¹M_g the control angular acceleration, (1), (2) read

    (3)  σ̇ = ¼B(σ)ω,   ω̇ = u,
    (6)  B(σ) = (1 − σ²)I + 2[σ×] + 2[σσ],         [ab] = abᵀ (the dyad of the text),
    (7)  ω = D(σ)σ̇,     D(σ) = 4Bᵀ(σ)/(1 + σ²)²,

and, differentiating (2), the Brunovsky form (8) σ̈ = a(σ, σ̇) + ¼B(σ)u with

    (9)  a(σ, σ̇) = ¼Ḃ(σ, σ̇)D(σ)σ̇,   Ḃ = −2(σ·σ̇)I + 2[σ̇×] + 2([σ̇σ] + [σσ̇]).

The auxiliary linear law v = −k0σ − k1σ̇ is the modal synthesis on one spectrum S° for all three
channels; here S° = {−α ± iβ} (so k0 = α² + β², k1 = 2α), and

    (10) u = 4B⁻¹(σ)(v − a) = D(σ)(v − a),
    (11) u = SC(D(σ)(v − a), a_m),

SC(x, a_m) of the text: q = max_i |x_i|; if q > a_m then y_i = a_m x_i/q (else y = x).

Reading of the extracted text (the Greek letters and most operators were lost): the formulas
above are the reconstruction of ``DIGEST.md``, checked by the proof modules.  Where the extracted
text says something else, the module that checks the formula says so (:mod:`.linearisation`:
the factors ¼ and 4 of (8), (10), (11); :mod:`.comparison`: x₂ⁱ = ωᵢ/4; :mod:`.kinematics`: the
condition on σ(t0)).

The catalogued instance (the paper prints no numerical example; every value can be changed
with ``--set``): J = diag(1000, 1200, 800) kg·m² (it only converts u into the torque M_g = Ju:
with G ≡ 0 it drops out of (3)), S° = {−1/10 ± i/10} s⁻¹ (k0 = 1/50, k1 = 1/5), and
a_m = 1/100 rad/s² (torques up to 12 N·m).
"""

from __future__ import annotations

import sympy

from lkverify import Equation, Parameters, System, Term, Vector, t

__all__ = ["PAPER", "P", "J", "alpha", "beta", "a_m", "k0", "k1", "sigma", "omega", "I3", "cross_matrix", "B", "D",
           "B_rate", "a_of", "v_of", "u_linear", "SC", "saturation_factor", "closed_loop", "closed_loop_10", "sigma_s", "omega_s"]

PAPER = "somov"

P = Parameters()
J = P.diagonal_matrix("J", ["J1", "J2", "J3"], default="diag(1000,1200,800)", latex="J",
                      description="inertia tensor (kg·m²); only M_g = Ju depends on it")
alpha = P.scalar("alpha", positive=True, default="1/10", latex=r"\alpha",
                 description="spectrum S° = {−α ± iβ}: decay rate α (1/s)")
beta = P.scalar("beta", positive=True, default="1/10", latex=r"\beta",
                description="spectrum S° = {−α ± iβ}: frequency β (1/s)")
a_m = P.scalar("a_m", positive=True, default="1/100", latex=r"a_m",
               description="bound a_m on every component of the control acceleration u (rad/s²)")

#: gains of v = −k0σ − k1σ̇ placing both roots of s² + k1 s + k0 at −α ± iβ
k0 = alpha ** 2 + beta ** 2
k1 = 2 * alpha

sigma = Vector("sigma", latex=r"\sigma", text="σ")
omega = Vector("omega", latex=r"\omega", text="ω")
#: σ(t), ω(t) as column matrices
sigma_s, omega_s = sympy.Matrix(sigma(t)), sympy.Matrix(omega(t))

I3 = sympy.eye(3)


def cross_matrix(x) -> sympy.Matrix:
    """[x×], the matrix with [x×]y = x × y."""
    x = sympy.Matrix(x)
    return sympy.Matrix([[0, -x[2], x[1]], [x[2], 0, -x[0]], [-x[1], x[0], 0]])


def B(s, *, sign=1) -> sympy.Matrix:
    """B(σ) of (6): (1 − σ²)I + 2[σ×] + 2[σσ] (``sign=-1``: the transposed reading −2[σ×])."""
    s = sympy.Matrix(s)
    n2 = (s.T * s)[0]
    return (1 - n2) * I3 + 2 * sign * cross_matrix(s) + 2 * s * s.T


def D(s) -> sympy.Matrix:
    """D(σ) of (7): 4Bᵀ(σ)/(1 + σ²)², the inverse of σ̇ = ¼B(σ)ω."""
    s = sympy.Matrix(s)
    return 4 * B(s).T / (1 + (s.T * s)[0]) ** 2


def B_rate(s, sd) -> sympy.Matrix:
    """Ḃ(σ, σ̇) = dB/dt: −2(σ·σ̇)I + 2[σ̇×] + 2([σ̇σ] + [σσ̇])."""
    s, sd = sympy.Matrix(s), sympy.Matrix(sd)
    return -2 * (s.T * sd)[0] * I3 + 2 * cross_matrix(sd) + 2 * (sd * s.T + s * sd.T)


def a_of(s, sd) -> sympy.Matrix:
    """a(σ, σ̇) of (9): ¼Ḃ(σ, σ̇)D(σ)σ̇ (the drift of σ̈ in the Brunovsky form (8))."""
    return B_rate(s, sd) * D(s) * sympy.Matrix(sd) / 4


def v_of(s, sd, gains=(k0, k1)) -> sympy.Matrix:
    """The auxiliary law v = −k0σ − k1σ̇."""
    return -gains[0] * sympy.Matrix(s) - gains[1] * sympy.Matrix(sd)


def u_linear(s, w) -> sympy.Matrix:
    """u of (10) in the state (σ, ω): D(σ)(v − a) with σ̇ = ¼B(σ)ω (so a = ¼Ḃω; proved in :mod:`.linearisation`)."""
    w = sympy.Matrix(w)
    sd = B(s) * w / 4
    return D(s) * (v_of(s, sd) - B_rate(s, sd) * w / 4)  # a = ¼ḂDσ̇ = ¼Ḃω: D(σ)σ̇ = ω by (7)


class saturation_factor(sympy.Function):
    """c(a_m, x1, x2, x3) = a_m/max(a_m, |x1|, |x2|, |x3|) ∈ (0, 1]: SC(x, a_m) = c x.

    A function symbol that stays unevaluated on symbolic arguments (``sympy.Max`` of the
    large rational functions of (10) compares its arguments on every rebuild, which takes
    minutes), is exact on numbers and prints as ``numpy.maximum`` for the simulator.

    Examples
    --------
    >>> saturation_factor(1, 2, -1, 0), saturation_factor(1, sympy.Rational(1, 2), 0, 0)
    (1/2, 1)
    """

    nargs = 4

    @classmethod
    def eval(cls, am, *x):
        if am.is_number and all(xi.is_number for xi in x):
            return am / sympy.Max(am, *[sympy.Abs(xi) for xi in x])
        return None

    def _eval_is_positive(self):
        return True if self.args[0].is_positive else None

    def _eval_rewrite_as_Max(self, am, *x, **kwargs):
        return am / sympy.Max(am, *[sympy.Abs(xi) for xi in x])

    def _numpycode(self, printer):
        am, *x = (printer._print(a) for a in self.args)
        inner = f"numpy.maximum(numpy.abs({x[0]}), numpy.maximum(numpy.abs({x[1]}), numpy.abs({x[2]})))"
        return f"(({am})/numpy.maximum({am}, {inner}))"

    _lambdacode = _numpycode

    def _pythoncode(self, printer):
        """Plain Python (``max``, ``abs``: numba compiles them) for the compiled family of the batch integrator."""
        am, *x = (printer._print(a) for a in self.args)
        return f"(({am})/max({am}, abs({x[0]}), abs({x[1]}), abs({x[2]})))"


def SC(x, am) -> sympy.Matrix:
    """SC(x, a_m) of (11): q = max_i|x_i|; if q > a_m then y_i = a_m x_i/q, else y = x.

    Examples
    --------
    >>> SC([2, -1, 0], 1).T
    Matrix([[1, -1/2, 0]])
    >>> SC([sympy.Rational(1, 2), 0, 0], 1).T
    Matrix([[1/2, 0, 0]])
    """
    x = sympy.Matrix(x)
    return saturation_factor(am, *x) * x


# (3), (11): the closed loop in the state (σ, ω)
closed_loop = System([
    Equation(sigma, [Term(B(sigma_s) * omega_s / 4, text="¼B(σ)ω", latex=r"\tfrac14 B(\sigma)\omega")]),
    Equation(omega, [Term(SC(u_linear(sigma_s, omega_s), a_m), text="SC(D(σ)(v − a), a_m)",
                          latex=r"\mathrm{SC}(D(\sigma)(v - a), a_m)")]),
], parameters=P, name="(3),(11)")

# (3), (10): the same loop without the saturation (σ̈ = v exactly)
closed_loop_10 = System([
    Equation(sigma, [Term(B(sigma_s) * omega_s / 4, text="¼B(σ)ω", latex=r"\tfrac14 B(\sigma)\omega")]),
    Equation(omega, [Term(u_linear(sigma_s, omega_s), text="D(σ)(v − a)", latex=r"D(\sigma)(v - a)")]),
], parameters=P, name="(3),(10)")
