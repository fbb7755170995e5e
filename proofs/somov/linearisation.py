"""Feedback linearisation of paper 003: (8), (9), (10) — with u of (10), σ̈ = v exactly.

Differentiating (2) along (3) (σ̇ = ¼B(σ)ω, ω̇ = u) gives the Brunovsky form

    (8)  σ̈ = a(σ, σ̇) + ¼B(σ)u,     (9)  a(σ, σ̇) = ¼Ḃ(σ, σ̇)D(σ)σ̇  (= ¼Ḃω),

and the law (10) u = 4B⁻¹(σ)(v − a) = D(σ)(v − a) makes σ̈ = v for every v; with the modal law
v = −k0σ − k1σ̇ every channel is σ̈ᵢ + k1σ̇ᵢ + k0σᵢ = 0, with the spectrum S° = {−α ± iβ}
(k0 = α² + β², k1 = 2α).  Each identity is decided exactly (:mod:`.identities`); the control
law is a parameter of :func:`linearisation_results`, so a mutated law is refuted term by term.

Text and reconstruction (a finding, reported as ``failed``).  In the extracted text every digit
of the stacked fractions survives elsewhere — the ¼ of (3) and (6) ("4 1"), the 4 of (7), the
halves of (9) — but (8), (10) and (11) carry none: they read σ̈ = v ≡ a(σ, σ̇) + B(σ)u and
u = B⁻¹(σ)(v − a) (the three B of (10), (11) also fit σ̇ = B(σ)ω substituted in v and a, again
without ¼).  ``DIGEST.md`` restores ¼ and 4.  As extracted, (8) differs from the derivation by
¾B(σ)u, and (10) gives σ̈ = v − ¾(v − a), not v.  Whether the print or the extraction dropped
the factors cannot be decided from the text file; the report says "as extracted".  The
extracted (9) shows two halves and two brackets, not a form that can be matched term by term:
the item checks the reconstruction ¼ḂDσ̇ and its equivalent −¼BḊσ̇.
"""

from __future__ import annotations

import functools

import sympy

from lkverify import Check, Result, Status

from .equations import PAPER, P, B, B_rate, D, alpha, beta, k0, k1
from .identities import OMEGA, SD, SIG, U, A, V, matrix_identity

__all__ = ["closes_loop", "linearisation", "linearisation_results", "law_10", "law_10_as_extracted", "sigma_ddot"]


def _inverse(M):
    return M.adjugate() / M.det()


def law_10(s, v, a):
    """(10) as derived: u = 4B⁻¹(σ)(v − a)."""
    return 4 * _inverse(B(s)) * (v - a)


def law_10_as_extracted(s, v, a):
    """(10) as the extracted text reads it: u = B⁻¹(σ)(v − a) (no factor 4)."""
    return _inverse(B(s)) * (v - a)


@functools.lru_cache(maxsize=4)
def sigma_ddot(s, w, u):
    """σ̈ along (3): the chain rule on σ̇ = ¼B(σ)ω with σ̇ = ¼B(σ)ω, ω̇ = u (immutable matrices)."""
    s, w, u = (sympy.Matrix(x) for x in (s, w, u))
    f = B(s) * w / 4
    return sympy.ImmutableMatrix(f.jacobian(s) * f + f.jacobian(w) * u)


def closes_loop(law=law_10, *, label="(10)") -> Result:
    """σ̈ = v under ``law(σ, v, a)``, on the derived (8) σ̈ = a + ¼B(σ)u, for generic v and a (exact)."""
    return matrix_identity(f"{label}: sigma'' = v", A + B(SIG) * law(SIG, V, A) / 4, V,
                           text=f"with u of {label}, σ̈ = a + ¼B(σ)u equals v for every v, a")


def linearisation_results(law=law_10, *, label="(10)") -> list:
    """(8), (9) along (3) and σ̈ = v under ``law(σ, v, a)`` for generic v, a (exact)."""
    s, w, u = SIG, OMEGA, U
    sd = B(s) * w / 4
    derived = B_rate(s, sd) * D(s) * sd / 4 + B(s) * u / 4
    return [matrix_identity("(8),(9) along (3)", sigma_ddot(*(sympy.ImmutableMatrix(x) for x in (s, w, u))), derived,
                            text="σ̈ along (3) = a(σ, σ̇) + ¼B(σ)u with a = ¼Ḃ(σ,σ̇)D(σ)σ̇ of (9)"),
            closes_loop(law, label=label)]


def _a_forms() -> Result:
    s, sd = SIG, SD
    Ddot = sympy.Matrix.hstack(*[D(s)[:, j].jacobian(s) * sd for j in range(3)])
    return matrix_identity("(9) a = -B Ddot sigmadot/4", B_rate(s, sd) * D(s) * sd / 4, -B(s) * Ddot * sd / 4,
                           text="¼Ḃ(σ,σ̇)D(σ)σ̇ = −¼B(σ)Ḋ(σ,σ̇)σ̇ (from BD = 4I: ḂD + BḊ = 0)")


def _modal(v) -> Result:
    lam = sympy.Symbol("lambda")
    K0, K1 = (sympy.sympify(x).subs({alpha: v["alpha"], beta: v["beta"]}) for x in (k0, k1))
    poly = sympy.Poly(lam ** 2 + K1 * lam + K0, lam)
    roots = sympy.roots(poly)
    want = {-sympy.sympify(v["alpha"]) + sympy.I * v["beta"], -sympy.sympify(v["alpha"]) - sympy.I * v["beta"]}
    ok = {sympy.expand(r) for r in roots} == {sympy.expand(x) for x in want}
    return Result("identity", "spectrum of each channel", Status.EXACT if ok else Status.FAILED,
                  {"k0": K0, "k1": K1},
                  f"v = −k0σ − k1σ̇, k0 = α² + β² = {K0}, k1 = 2α = {K1}: σ̈ᵢ + k1σ̇ᵢ + k0σᵢ = 0 has the roots "
                  f"{', '.join(sympy.sstr(r) for r in roots)} = −α ± iβ (exact) in each of the three channels")


def _as_extracted() -> list:
    s, u = SIG, U
    # against the derived (8) σ̈ = a + ¼B(σ)u, proved along (3) above (a generic here)
    r8 = matrix_identity("printed (8) as extracted", A + B(s) * u, A + B(s) * u / 4,
                         text="finding — (8) as extracted, σ̈ = a + B(σ)u (no ¼), against the derived σ̈ = a + ¼B(σ)u; "
                              "the difference is ¾B(σ)u")
    r10 = closes_loop(law_10_as_extracted, label="printed (10) as extracted")
    r10 = Result(r10.kind, r10.name, r10.status, r10.value,
                 "finding — (10) as extracted, u = B⁻¹(σ)(v − a) (no 4): σ̈ − v = −¾(v − a) ≠ 0 unless v = a; "
                 + r10.detail)
    return [r8, r10]


def _check(v) -> list:
    return linearisation_results() + [_a_forms(), _modal(v)] + _as_extracted()


linearisation = Check("linearisation", parameters=P, checks=[_check], paper=PAPER, relevant=("alpha", "beta"),
                      title="(8)–(10): σ̈ = a + ¼B(σ)u along (3); u = 4B⁻¹(v − a) gives σ̈ = v exactly")
