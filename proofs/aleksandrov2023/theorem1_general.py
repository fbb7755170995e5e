"""The printed V̇ of (П.1) along (3) for general forms in n variables (every coefficient symbolic).

The catalogued instance (:mod:`.system3`) has n = 2 and Π̃ radial (the bound steps need it).
The identity itself needs neither: :func:`printed_vdot_claim` builds system (3) with A, B
symbolic symmetric n×n matrices, Π and Π̃ general forms of degree ``degree`` (every
coefficient a symbol), P(q) = φ(q)S with φ = Σ f_i q_i² and S a symbolic skew matrix, and
the printed V̇ as a :class:`~lkverify.DerivativeClaim`.  SymPy has no vectors of symbolic
dimension, so "general n" means one claim per n; measured (2 cores, under load ≈ 10):
n = 2: 3 s, n = 3: 8 s, n = 4: 27 s, n = 5: 136 s, all exact (degree 4); n = 3, degree 6: 16 s.

Examples
--------
>>> claim = printed_vdot_claim(2)
>>> claim.check({}, values={}, budget=120).status.value
'exact'
"""

import itertools

import sympy

from lkverify import (DerivativeClaim, Equation, Functional, Parameters, System, Term, Vector, dot, norm_power, quad, t,
                      window_integral, xi)

__all__ = ["printed_vdot_claim"]


def _form(P, name, xs, degree):
    """Σ c_m x^m over the monomials of degree ``degree``, each c_m a new real parameter."""
    monos = [m for m in itertools.product(range(degree + 1), repeat=len(xs)) if sum(m) == degree]
    return sum((P.scalar(f"{name}_{''.join(map(str, m))}") * sympy.Mul(*[x**k for x, k in zip(xs, m)])
                for m in monos), sympy.S.Zero)


def printed_vdot_claim(n: int, degree: int = 4, *, flip: str | None = None) -> DerivativeClaim:
    """The printed V̇ of (П.1) along (3) in R^n with general forms Π, Π̃ of degree ``degree``.

    ``flip`` names a printed term whose sign is flipped (for tests): ``"alpha"`` flips
    −α‖q(t−τ)‖^{μ+1}, ``"A"`` drops q̇ᵀAq̇.
    """
    P = Parameters()
    A, B = P.spd_matrix("A", n), P.spd_matrix("B", n)
    tau, mu = P.delay("tau"), P.scalar("mu", positive=True)
    lam, alpha, beta = (P.scalar(s, positive=True) for s in ("lam", "alpha", "beta"))
    xs = sympy.symbols(f"x1:{n + 1}", real=True)
    Pi, Pit = _form(P, "pi", xs, degree), _form(P, "pit", xs, degree)
    phi = sum((P.scalar(f"f{i + 1}") * xs[i] ** 2 for i in range(n)), sympy.S.Zero)
    S = sympy.zeros(n, n)
    for i, j in itertools.combinations(range(n), 2):
        S[i, j] = P.scalar(f"s{i + 1}{j + 1}")
        S[j, i] = -S[i, j]
    q, v = Vector("q", n), Vector("v", n)

    def grad(f, at):
        return sympy.ImmutableMatrix([sympy.diff(f, x) for x in xs]).xreplace(dict(zip(xs, list(at))))

    def skew(time):
        return sympy.ImmutableMatrix(phi.xreplace(dict(zip(xs, list(q(time))))) * S)

    system = System([Equation(q, [Term(v(t), text="q̇")]),
                     Equation(v, [Term(-B * v(t), text="−Bq̇"), Term(-grad(Pi, q(t)), text="−∂Π/∂q"),
                                  Term(-skew(t) * q(t), text="−P(q)q"),
                                  Term(-window_integral(grad(Pit, q(xi)), tau), text="−∫∂Π̃/∂q dξ")], mass=A)],
                    parameters=P, name=f"(3) in R^{n}")
    K = window_integral(grad(Pit, q(xi)), tau, weight=xi - t + tau)
    J = window_integral(grad(Pit, q(xi)), tau)
    mem = window_integral(norm_power(q(xi), mu + 1), tau)
    V = Functional([Term(lam / 2 * quad(v(t), A)), Term(quad(q(t), B) / 2), Term(quad(q(t), A, v(t))),
                    Term(-dot(q(t), K)),
                    Term(window_integral(norm_power(q(xi), mu + 1), tau, weight=alpha + beta * (xi - t + tau)))],
                   name="(П.1)")
    sign = -1 if flip == "alpha" else 1
    printed = [Term(-lam * quad(v(t), B), text="−λq̇ᵀBq̇"),
               *([] if flip == "A" else [Term(quad(v(t), A), text="q̇ᵀAq̇")]),
               Term(-lam * dot(v(t), grad(Pi, q(t)) + J + skew(t) * q(t)), text="−λq̇ᵀ(∂Π/∂q+∫∂Π̃/∂q+P(q)q)"),
               Term(-dot(q(t), grad(Pi, q(t)) + tau * grad(Pit, q(t))), text="−qᵀ(∂Π/∂q+τ∂Π̃/∂q)"),
               Term(-dot(v(t), K), text="−q̇ᵀ∫(ξ−t+τ)∂Π̃/∂q"), Term(-beta * mem, text="−β∫‖q‖^{μ+1}"),
               Term((alpha + beta * tau) * norm_power(q(t), mu + 1), text="(α+βτ)‖q‖^{μ+1}"),
               Term(-sign * alpha * norm_power(q(t - tau), mu + 1), text="−α‖q(t−τ)‖^{μ+1}")]
    return DerivativeClaim(f"Vdot_printed_R{n}", V, system, printed,
                           description=f"the printed V̇ of (П.1) along (3) in R^{n}, Π and Π̃ general forms of degree "
                                       f"{degree}")
