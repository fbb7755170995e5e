"""Theorem 2 of paper 001: system (2),(4), the proof's V and its exact structured V̇ (the chain reads them here).

See :mod:`.theorem2` for the theorem.
Theorem 2 of paper 001: nonlinear damping h(t) grad W(ω), W homogeneous of order μ + 1 > 2.

    (4)  Jω̇ + ω×Jω = −h(t) grad W(ω) − a1 s1×r1 − a2 s2×r2,

catalogued with the instance W = (ωᵀDω)^{(μ+1)/2} for μ = 3, i.e. W = (ωᵀDω)² (positive definite,
homogeneous of order μ + 1 = 4, grad W = 4(ωᵀDω)Dω), and σ = μ = 3.  Theorem 2: if (5), (15) |ḣ| ≤ L h^{1+(1−ν)/(μ+1)}
and (11) ∫h^ν = ∞ hold for some ν ≥ 1, the equilibrium is asymptotically stable.  The proof's
function, with η = a1 s1×r1 + a2 s2×r2, γ > 0 and σ ≥ 1 (σ ≥ μ in its last step),

    V = ½ωᵀJω + (a1/2)‖s1 − r1‖² + (a2/2)‖s2 − r2‖² + γh^ν(t)‖η‖^{σ−1}ωᵀJη,

and its derivative along (2), (4) in the structured form the printed estimate with α3 … α6
bounds term by term (M = a1(ω×s1)×r1 + a2(ω×s2)×r2 = −η̇):

    V̇ = −(μ+1)h(ωᵀDω)^{(μ+1)/2} + γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη − γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)
        − γh^ν‖η‖^{σ−1}(ω×Jω)ᵀη − γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη − γh^ν‖η‖^{σ+1} − γh^ν‖η‖^{σ−1}ωᵀJM.

The first term is −h·ωᵀgrad W = −(μ+1)hW (Euler's theorem for homogeneous W): the energy
only decreases through the damping.  The claim is proved for every h, ν, γ, J, D, a1, a2.
"""

import dataclasses
import functools

import sympy

from lkverify import DerivativeClaim, Functional, InputError, System, Term, dot, norm_squared, quad, t
from lkverify.declare.rigidbody import euler_equation, poisson_equations, restoring_torque_rate

from .equations import D, J, P, a1, a2, eta, gamma, h, nu, omega, r1, r2, s1, s2, s3

__all__ = ["W", "grad_W", "functional2", "derivation2", "structured", "system4", "mu", "sigma",
           "derivation_every_exponent", "Instance", "instance"]

#: the catalogued instance: W = (ωᵀDω)², homogeneous of order μ + 1 = 4, and σ = μ = 3 in V.  For these integers
#: the identity is exact in seconds.  With σ a symbol it is exact too (about 20 s of CPU, a slow test of
#: tests/catalogue/test_aleksandrov2017_theorem2.py: ‖η‖^{σ−3}, ‖η‖^{σ−1}, ‖η‖^{σ+1} share one atom in the normal
#: forms).  With μ = σ one positive symbol (W = (ωᵀDω)^{(μ+1)/2} for every μ) it is exact too, about 11 s:
#: :func:`derivation_every_exponent` (a slow test of tests/catalogue/test_aleksandrov2017_boxes.py).  Other odd
#: integers μ, σ: :func:`instance` (the items of :mod:`.theorem2_exponents`).
mu = sympy.Integer(3)
sigma = sympy.Integer(3)

M = restoring_torque_rate(omega, (s1, s2), (r1, r2), (a1, a2))  # −η̇ by (2)
_hd = sympy.Derivative(h(t), t)
_eta2 = norm_squared(eta)  # ‖η‖²


@dataclasses.dataclass(frozen=True)
class Instance:
    """Theorem 2's objects for one exponent pair: W, grad W, the system (2),(4), V and its exact structured V̇.

    Attributes
    ----------
    mu, sigma : sympy.Integer
        W = (ωᵀDω)^{(μ+1)/2} (homogeneous of order μ + 1) and the power ‖η‖^{σ−1} in V.
    W, grad_W : sympy expression, sympy Matrix
    system : System
        (2), (4) with this W.
    functional : Functional
    structured : list of Term
        The seven terms of V̇ (texts as in the module docstring).
    derivation : DerivativeClaim
        V̇ along ``system`` equals the sum of ``structured``.

    Examples
    --------
    >>> inst = instance(5)
    >>> inst.mu, inst.sigma, inst.system.name, len(inst.structured)
    (5, 5, '(2),(4) with μ = 5', 7)
    """

    mu: sympy.Integer
    sigma: sympy.Integer
    W: sympy.Expr
    grad_W: sympy.MatrixBase
    system: System
    functional: Functional
    structured: list
    derivation: DerivativeClaim


def _odd_exponent(name, value):
    """An odd integer ≥ 3 as a sympy Integer (W and ‖η‖^{σ−1} polynomial), else InputError."""
    v = sympy.sympify(value)
    if not (v.is_Integer and v >= 3 and v % 2 == 1):
        raise InputError(f"{name}: expected an odd integer ≥ 3 (W = (ωᵀDω)^((μ+1)/2) and ‖η‖^(σ−1) polynomial), "
                         f"got {value!r}; e.g. {name}=5")
    return v


def instance(mu_value=3, sigma_value=None) -> Instance:
    """The system (2),(4) with W = (ωᵀDω)^{(μ+1)/2}, V with ‖η‖^{σ−1} (σ = μ unless given) and V̇'s seven terms.

    μ and σ are odd integers ≥ 3 (everything stays polynomial: (μ+1)/2 and (σ−1)/2 are integers); one object
    per pair (cached), so a theorem and its chain share the system.  ``instance(3)`` is the catalogued
    :data:`system4`, :data:`functional2`, :data:`structured`, :data:`derivation2`.

    Examples
    --------
    >>> instance(3).system is system4, instance(3, 3) is instance(3), instance(7).W.exp
    (True, True, 4)
    """
    m = _odd_exponent("mu", mu_value)
    return _instance(int(m), int(m if sigma_value is None else _odd_exponent("sigma", sigma_value)))


@functools.lru_cache(maxsize=8)
def _instance(m: int, sg: int) -> Instance:
    """:func:`instance` for validated odd integers (one object per pair)."""
    m, sg = sympy.Integer(m), sympy.Integer(sg)
    wDw = quad(omega(t), D)
    W_m = wDw ** ((m + 1) / 2)  # W(ω) = (ωᵀDω)^{(μ+1)/2}
    grad_m = (m + 1) * wDw ** ((m - 1) / 2) * (D * omega(t))
    suffix = "" if (m, sg) == (3, 3) else f" with μ = {m}" + ("" if sg == m else f", σ = {sg}")
    system_m = System([  # (2), (4)
        euler_equation(omega, J, [
            Term(-h(t) * grad_m, text="−h(t)grad W(ω)", latex=r"-h(t)\,\mathrm{grad}\,W(\omega)"),
            Term(-eta, text="−(a1 s1×r1 + a2 s2×r2)", latex=r"-(a_1 s_1\times r_1 + a_2 s_2\times r_2)"),
        ], mass_text="J", mass_latex="J", gyroscopic_text="−ω×Jω", gyroscopic_latex=r"-\omega\times J\omega"),
        *poisson_equations(omega, (s1, s2, s3)),
    ], parameters=P, name="(2),(4)" + suffix)
    V_m = Functional([
        Term(quad(omega(t), J) / 2, text="½ωᵀJω", latex=r"\tfrac12\omega^\top J\omega"),
        Term(a1 / 2 * norm_squared(s1(t) - r1), text="(a1/2)‖s1−r1‖²", latex=r"\tfrac{a_1}{2}\|s_1-r_1\|^2"),
        Term(a2 / 2 * norm_squared(s2(t) - r2), text="(a2/2)‖s2−r2‖²", latex=r"\tfrac{a_2}{2}\|s_2-r_2\|^2"),
        Term(gamma * h(t) ** nu * _eta2 ** ((sg - 1) / 2) * quad(omega(t), J, eta), text="γh^ν‖η‖^{σ−1}ωᵀJη",
             latex=r"\gamma h^\nu(t)\|\eta\|^{\sigma-1}\omega^\top J\eta"),
    ], name="V of Theorem 2" + suffix)
    terms = _structured(m, sg, W_m, grad_m)
    claim = DerivativeClaim("Vdot_structured", V_m, system_m, terms,
                            description="V̇ along (2),(4) for W = (ωᵀDω)^{(μ+1)/2}, in the form the estimate with "
                                        "α3…α6 bounds (−(μ+1)hW from Euler's theorem on homogeneous W)"
                                        + ("" if not suffix else f" (μ = {m}, σ = {sg})"))
    return Instance(m, sg, W_m, grad_m, system_m, V_m, terms, claim)


def _structured(m, sg, W_m, grad_m):
    """The seven terms of V̇ along (2),(4) (μ = m in W, σ = sg in V)."""
    return [
        Term(-(m + 1) * h(t) * W_m, text="−(μ+1)hW"),
        Term(gamma * nu * h(t) ** (nu - 1) * _hd * _eta2 ** ((sg - 1) / 2) * quad(omega(t), J, eta),
             text="γνh^{ν−1}ḣ‖η‖^{σ−1}ωᵀJη"),
        Term(-gamma * (sg - 1) * h(t) ** nu * _eta2 ** ((sg - 3) / 2) * dot(eta, M) * quad(omega(t), J, eta),
             text="−γ(σ−1)h^ν‖η‖^{σ−3}(ηᵀM)(ωᵀJη)"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((sg - 1) / 2) * dot(omega(t).cross(J * omega(t)), eta),
             text="−γh^ν‖η‖^{σ−1}(ω×Jω)ᵀη"),
        Term(-gamma * h(t) ** (nu + 1) * _eta2 ** ((sg - 1) / 2) * dot(grad_m, eta), text="−γh^{ν+1}‖η‖^{σ−1}(grad W)ᵀη"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((sg + 1) / 2), text="−γh^ν‖η‖^{σ+1}"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((sg - 1) / 2) * quad(omega(t), J, M), text="−γh^ν‖η‖^{σ−1}ωᵀJM"),
    ]


_I3 = instance(3)
W, grad_W, system4, functional2, structured, derivation2 = (_I3.W, _I3.grad_W, _I3.system, _I3.functional,
                                                             _I3.structured, _I3.derivation)


def derivation_every_exponent() -> DerivativeClaim:
    """The structured V̇ with μ = σ a positive symbol ``mu``: W = (ωᵀDω)^{(μ+1)/2}, V with ‖η‖^{μ−1}.

    The identity (the same seven terms as :data:`derivation2`) is declared on a copy of paper 001's
    parameters with ``mu`` added, along the system (2), (4) written with that W; ``exact`` means it holds
    for every μ = σ > 0 (the theorem needs μ > 1, σ ≥ μ), not only for the catalogued μ = σ = 3.
    """
    import copy

    from .equations import P as _P

    P2 = copy.deepcopy(_P)
    m = P2.scalar("mu", positive=True, latex=r"\mu", description="exponent μ = σ (W homogeneous of order μ + 1)")
    wDw = quad(omega(t), D)
    W_m = wDw ** ((m + 1) / 2)
    grad_m = (m + 1) * wDw ** ((m - 1) / 2) * (D * omega(t))
    sys_m = System([
        euler_equation(omega, J, [Term(-h(t) * grad_m, text="−h(t)grad W(ω)"), Term(-eta, text="−η")],
                       mass_text="J", gyroscopic_text="−ω×Jω"),
        *poisson_equations(omega, (s1, s2, s3)),
    ], parameters=P2, name="(2),(4) for every μ")
    V_m = Functional([*functional2.terms[:3],
                      Term(gamma * h(t) ** nu * _eta2 ** ((m - 1) / 2) * quad(omega(t), J, eta), text="γh^ν‖η‖^{μ−1}ωᵀJη")],
                     name="V of Theorem 2, σ = μ")
    terms = [
        Term(-(m + 1) * h(t) * W_m, text="−(μ+1)hW"),
        Term(gamma * nu * h(t) ** (nu - 1) * _hd * _eta2 ** ((m - 1) / 2) * quad(omega(t), J, eta), text="ḣ-term"),
        Term(-gamma * (m - 1) * h(t) ** nu * _eta2 ** ((m - 3) / 2) * dot(eta, M) * quad(omega(t), J, eta),
             text="−γ(μ−1)h^ν‖η‖^{μ−3}(ηᵀM)(ωᵀJη)"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((m - 1) / 2) * dot(omega(t).cross(J * omega(t)), eta), text="ω×Jω-term"),
        Term(-gamma * h(t) ** (nu + 1) * _eta2 ** ((m - 1) / 2) * dot(grad_m, eta), text="grad W-term"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((m + 1) / 2), text="−γh^ν‖η‖^{μ+1}"),
        Term(-gamma * h(t) ** nu * _eta2 ** ((m - 1) / 2) * quad(omega(t), J, M), text="ωᵀJM-term"),
    ]
    return DerivativeClaim("Vdot_structured_every_mu", V_m, sys_m, terms,
                           description="V̇ along (2),(4) with μ = σ symbolic (W = (ωᵀDω)^{(μ+1)/2})")
