"""Cases of the mutation suite (tests/test_mutations.py): systems, functionals, hand-derived V̇.

Every family below is a system, a functional and its V̇ *derived by hand* (written
in the comments, never computed with lkverify), split into terms.  From each family
the suite generates

* mutated claims, each differing from the hand-derived V̇ by a nonzero multiple of
  one nonzero term (flipped sign, wrong constant, dropped term), by a tiny exact
  term, or, for time-varying arguments, by the omitted inner derivative θ′(t);
* true claims written differently (reordered, expanded into one term, every term
  split in two, factored, using ‖s‖ = 1, Rational versus integer forms).

A mutated claim is wrong by construction: it is the true V̇ plus c·T with c ≠ 0 a
rational and T a term that does not vanish on the state manifold.  Only the
public API is used.
"""

from __future__ import annotations

import dataclasses
import random

import sympy

from lkverify import (DerivativeClaim, Equation, Functional, Parameters, System, Term, Theorem, UnitVector,
                      Vector, t, window_integral, xi)
from lkverify.declare.vectors import cross, dot

__all__ = ["Family", "ClaimCase", "FAMILIES", "MUTATED", "TRUE", "CLOSED_FORMS", "near_singular_matrices",
           "run_claim"]

R = sympy.Rational
TINY9 = R(1, 10**9)
TINY30 = R(1, 10**30)
EPS9 = R(10**9 + 1, 10**9)  # 1 + 10⁻⁹, exact


@dataclasses.dataclass(frozen=True)
class Family:
    """A system, a functional and its hand-derived V̇ (``terms``, each nonzero on the manifold)."""

    name: str
    system: System
    functional: Functional
    terms: tuple
    tiny: tuple  # (m1, m2): monomials for the 10⁻⁹ and 10⁻³⁰ mutations
    values: dict = dataclasses.field(default_factory=dict)
    variants: dict = dataclasses.field(default_factory=dict)  # name -> terms (true, written differently)
    hard: tuple = ()  # names of variants only required "not failed" (may be undecided)
    inner: dict = dataclasses.field(default_factory=dict)  # name -> terms (wrong time-varying argument)


@dataclasses.dataclass(frozen=True)
class ClaimCase:
    id: str
    kind: str
    family: Family
    terms: tuple
    values: dict
    exact_required: bool = True
    slow: bool = False  # run with `-m slow` only (the default run keeps every kind for every family: sign, dropped, ×(1 + 10⁻⁹), + 10⁻³⁰·m, time-varying arguments)


def run_claim(family: Family, terms, values=None, *, budget: float = 60.0):
    """The status of the claim ``V̇ = Σ terms`` checked by a Theorem through the public API."""
    claim = DerivativeClaim("Vdot", family.functional, family.system,
                            [Term(e) for e in terms] or [Term(sympy.S.Zero, text="0")])
    theorem = Theorem("mutation", system=family.system, functional=family.functional, claims=[claim])
    report = theorem.run(dict(family.values if values is None else values), budget=budget)
    (result,) = [r for r in report.results if r.kind == "identity" and r.name == "Vdot"]
    return result, report


# ----------------------------------------------------------------------------------------------------------
# scalar linear delay system  ẋ = −a x + b x(t − τ)
# ----------------------------------------------------------------------------------------------------------

def _scalar_delay():
    P = Parameters()
    a = P.scalar("a", positive=True, default=2)
    b = P.scalar("b", default=1)
    c = P.scalar("c", positive=True, default=1)
    tau = P.delay("tau", default=1)
    x = Vector("x", 1)
    system = System([Equation(x, [Term(-a * x(t)[0], text="-a x"), Term(b * x(t - tau)[0], text="b x(t-τ)")])],
                    parameters=P, name="scalar delay")
    return P, a, b, c, tau, x, system


def _families():
    fams = []
    # A. V = x²/2 + c∫_{t−τ}^t x²;  V̇ = x(−ax + b x_τ) + c x² − c x_τ²
    P, a, b, c, tau, x, system = _scalar_delay()
    X, Xd = x(t)[0], x(t - tau)[0]
    W = window_integral(x(xi)[0] ** 2, tau)
    V = Functional([Term(X ** 2 / 2, text="x²/2"), Term(c * W, text="c∫x²")])
    fams.append(Family(
        "scalar-window", system, V, (-a * X ** 2, b * X * Xd, c * X ** 2, -c * Xd ** 2), (X ** 2, X * Xd),
        variants={
            "readme-print": ((c - a) * X ** 2, b * X * Xd, -c * Xd ** 2),
            "quadratic-form": (-((a - c) * X ** 2 - b * X * Xd + c * Xd ** 2),),
            "completed-square": (-c * (Xd - b / (2 * c) * X) ** 2, (b ** 2 / (4 * c) + c - a) * X ** 2),
        }))
    # A'. the same at given values a = 3/2, b = 1/2, c = 1: V̇ = −x²/2 + x x_τ/2 − x_τ²
    fams.append(Family(
        "scalar-window-values", system, V, (-X ** 2 / 2, X * Xd / 2, -Xd ** 2), (X ** 2, X * Xd),
        values={"a": "3/2", "b": "1/2", "c": "1"},
        variants={
            "rational-form": (R(-1, 2) * X ** 2, R(1, 2) * X * Xd, -1 * Xd ** 2),
            "integer-over-2": ((-X ** 2 + X * Xd - 2 * Xd ** 2) / 2,),
            "decimal-rational": (R(-5, 10) * X ** 2, R(50, 100) * X * Xd, R(-10, 10) * Xd ** 2),
        }))
    # B. V = x² + ∫_{t−τ}^t (ξ − t + τ) x(ξ)² dξ;
    #    V̇ = 2x(−ax + b x_τ) + τ x² − 0·x_τ² − ∫ x²   (weight τ at ξ = t, 0 at ξ = t−τ, ∂_t weight = −1)
    P, a, b, c, tau, x, system = _scalar_delay()
    X, Xd = x(t)[0], x(t - tau)[0]
    W = window_integral(x(xi)[0] ** 2, tau)
    eta = sympy.Symbol("eta", real=True)
    Wz = sympy.Integral(x(eta)[0] ** 2, (eta, t - tau, t))
    V = Functional([Term(X ** 2, text="x²"), Term(window_integral(x(xi)[0] ** 2, tau, weight=xi - t + tau),
                                                  text="∫(ξ−t+τ)x²")])
    fams.append(Family(
        "scalar-weighted-window", system, V, (-2 * a * X ** 2, 2 * b * X * Xd, tau * X ** 2, -W), (X ** 2, X * Xd),
        variants={
            "grouped": ((tau - 2 * a) * X ** 2, 2 * b * X * Xd, -W),
            "other-dummy-variable": (-2 * a * X ** 2, 2 * b * X * Xd, tau * X ** 2, -Wz),
        }))
    # C. numbers in the system: ẋ = −3x + x(t−1)/2, V = x² + 2∫_{t−1}^t x²;
    #    V̇ = 2x(−3x + x(t−1)/2) + 2x² − 2x(t−1)² = −6x² + x x(t−1) + 2x² − 2x(t−1)²
    P = Parameters()
    x = Vector("x", 1)
    X, X1 = x(t)[0], x(t - 1)[0]
    system = System([Equation(x, [Term(-3 * X), Term(R(1, 2) * X1)])], parameters=P, name="numeric delay")
    V = Functional([Term(X ** 2), Term(2 * window_integral(x(xi)[0] ** 2, 1))])
    fams.append(Family(
        "numeric-window", system, V, (-6 * X ** 2, X * X1, 2 * X ** 2, -2 * X1 ** 2), (X ** 2, X * X1),
        variants={
            "collected": (-4 * X ** 2, X * X1, -2 * X1 ** 2),
            "rational-coefficients": (R(-8, 2) * X ** 2, R(2, 2) * X * X1, R(-6, 3) * X1 ** 2),
            "factored": (-(2 * X - X1 / 4) ** 2 - R(31, 16) * X1 ** 2,),
        }))
    # D. planar: u̇₁ = −u₁ + k u₂(t−τ), u̇₂ = −a u₂ + u₁;  V = u₁² + p u₂² + q∫u₂²;
    #    V̇ = 2u₁(−u₁ + k u₂τ) + 2p u₂(−a u₂ + u₁) + q u₂² − q u₂τ²
    P = Parameters()
    k = P.scalar("k")
    a = P.scalar("a", positive=True)
    p = P.scalar("p", positive=True)
    q = P.scalar("q", positive=True)
    tau = P.delay("tau")
    u = Vector("u", 2)
    u1, u2 = u(t)
    u1d, u2d = u(t - tau)
    system = System([Equation(u, [Term(sympy.Matrix([-u1, -a * u2]), text="(−u₁, −a u₂)"),
                                  Term(sympy.Matrix([k * u2d, 0]), text="(k u₂(t−τ), 0)"),
                                  Term(sympy.Matrix([0, u1]), text="(0, u₁)")])], parameters=P, name="planar")
    V = Functional([Term(u1 ** 2 + p * u2 ** 2), Term(q * window_integral(u(xi)[1] ** 2, tau))])
    fams.append(Family(
        "planar-delay", system, V,
        (-2 * u1 ** 2, 2 * k * u1 * u2d, -2 * a * p * u2 ** 2, 2 * p * u1 * u2, q * u2 ** 2, -q * u2d ** 2),
        (u2 ** 2, u1 * u2d),
        variants={
            "vector-form": ((sympy.Matrix([[u1, u2, u2d]]) * sympy.Matrix([[-2, p, k], [p, q - 2 * a * p, 0],
                                                                              [k, 0, -q]])
                             * sympy.Matrix([u1, u2, u2d]))[0, 0],),
            "grouped-by-state": (2 * u1 * (-u1 + k * u2d), 2 * p * u2 * (-a * u2 + u1), q * (u2 - u2d) * (u2 + u2d)),
        }))
    # E. sphere: ẇ = −k w, ṡ = s × w, ‖s‖ = 1, r a constant unit vector;  V = ½ w·w + λ(1 − s·r);
    #    V̇ = w·(−k w) − λ (s × w)·r
    P = Parameters()
    k = P.scalar("k", positive=True)
    lam = P.scalar("lam", positive=True)
    r = P.unit_vector("r")
    w, s = Vector("w"), UnitVector("s")
    W_, S_ = w(t), s(t)
    system = System([Equation(w, [Term(-k * W_, text="−k w")]),
                     Equation(s, [Term(cross(S_, W_), text="s×w")])], parameters=P, name="sphere")
    V = Functional([Term(dot(W_, W_) / 2, text="½w·w"), Term(lam * (1 - dot(S_, r)), text="λ(1−s·r)")])
    fams.append(Family(
        "sphere-poisson", system, V, (-k * dot(W_, W_), -lam * dot(cross(S_, W_), r)), (W_[0] ** 2, W_[0] * S_[1]),
        variants={
            "uses-|s|=1-factor": (-k * dot(W_, W_) * dot(S_, S_), -lam * dot(cross(S_, W_), r)),
            "triple-product-rotated": (-k * dot(W_, W_), -lam * dot(W_, cross(r, S_))),
            "plus-(s·s−1)-multiple": (-k * dot(W_, W_), -lam * dot(cross(S_, W_), r),
                                      (dot(S_, S_) - 1) * W_[0] * r[1]),
            "swapped-cross": (-k * dot(W_, W_), lam * dot(cross(W_, S_), r)),
        }))
    # F. sphere with feedback: ẇ = −k w − μ s × r, ṡ = s × w;  V = ½ w·w + μ(1 − s·r);
    #    V̇ = −k w·w − μ w·(s × r) − μ (s × w)·r, and the last two cancel: w·(s×r) = −(s×w)·r.
    P = Parameters()
    k = P.scalar("k", positive=True)
    mu = P.scalar("mu", positive=True)
    r = P.unit_vector("r")
    w, s = Vector("w"), UnitVector("s")
    W_, S_ = w(t), s(t)
    system = System([Equation(w, [Term(-k * W_, text="−k w"), Term(-mu * cross(S_, r), text="−μ s×r")]),
                     Equation(s, [Term(cross(S_, W_), text="s×w")])], parameters=P, name="sphere feedback")
    terms = (-k * dot(W_, W_), -mu * dot(W_, cross(S_, r)), -mu * dot(cross(S_, W_), r))
    variants = {"cancelled": (-k * dot(W_, W_),),
                "cancelled-with-|s|²": (-k * dot(W_, W_) * dot(S_, S_),),
                "sum-of-squares": (-k * W_[0] ** 2, -k * W_[1] ** 2, -k * W_[2] ** 2)}
    V = Functional([Term(dot(W_, W_) / 2, text="½w·w"), Term(mu * (1 - dot(S_, r)), text="μ(1−s·r)")])
    fams.append(Family("sphere-feedback", system, V, terms, (W_[1] ** 2, W_[2] * S_[0]), variants=variants))
    # F'. the same V written as ½w·w + (μ/2)‖s − r‖² (equal on the manifold); V̇ the same,
    #     since d/dt ½‖s‖² = s·(s × w) = 0 identically.
    V2 = Functional([Term(dot(W_, W_) / 2, text="½w·w"), Term(mu * dot(S_ - r, S_ - r) / 2, text="μ/2‖s−r‖²")])
    fams.append(Family("sphere-feedback-norm-form", system, V2, terms, (W_[1] ** 2, W_[2] * S_[0]),
                       variants=variants))
    # G. planar vector with a weighted window: ż = −k z + b z(t−τ);  V = ½ z·z + ∫(ξ − t + τ) z(ξ)·z(ξ) dξ;
    #    V̇ = z·(−k z + b z_τ) + τ z·z − ∫ z·z
    P = Parameters()
    k = P.scalar("k", positive=True)
    b = P.scalar("b")
    tau = P.delay("tau")
    z = Vector("z", 2)
    Z, Zd = z(t), z(t - tau)
    system = System([Equation(z, [Term(-k * Z, text="−k z"), Term(b * Zd, text="b z(t−τ)")])], parameters=P,
                    name="planar vector")
    Wzz = window_integral(dot(z(xi), z(xi)), tau)
    V = Functional([Term(dot(Z, Z) / 2), Term(window_integral(dot(z(xi), z(xi)), tau, weight=xi - t + tau))])
    fams.append(Family(
        "planar-weighted-window", system, V, (-k * dot(Z, Z), b * dot(Z, Zd), tau * dot(Z, Z), -Wzz),
        (Z[0] ** 2, Z[0] * Zd[1]),
        variants={
            "componentwise-integrals": (-k * dot(Z, Z), b * dot(Z, Zd), tau * dot(Z, Z),
                                        -window_integral(z(xi)[0] ** 2, tau), -window_integral(z(xi)[1] ** 2, tau)),
            "grouped": ((tau - k) * dot(Z, Z), b * dot(Z, Zd), -Wzz),
        }))
    # DI. double integral: ẋ = −a x + b x(t−τ);  V = ½x² + ∫_{t−τ}^t ∫_ξ^t x(ζ)² dζ dξ;
    #     d/dt of the double integral: −∫_{t−τ}^t x(ζ)² dζ (lower limit) + ∫_{t−τ}^t x(t)² dξ (under the sign)
    #     = τ x² − ∫_{t−τ}^t x²;  V̇ = −a x² + b x x_τ + τ x² − ∫ x²
    P, a, b, c, tau, x, system = _scalar_delay()
    X, Xd = x(t)[0], x(t - tau)[0]
    zeta_ = sympy.Symbol("zeta_")
    double = window_integral(sympy.Integral(x(zeta_)[0] ** 2, (zeta_, xi, t)), tau)
    V = Functional([Term(X ** 2 / 2), Term(double, text="∫∫x²")])
    fams.append(Family(
        "double-integral", system, V, (-a * X ** 2, b * X * Xd, tau * X ** 2, -window_integral(x(xi)[0] ** 2, tau)),
        (X ** 2, X * Xd),
        variants={"grouped": ((tau - a) * X ** 2, b * X * Xd, -window_integral(x(xi)[0] ** 2, tau))}))

    # ------------------------------------------------------------------------------------------------------
    # time-varying arguments θ(t): d/dt y(θ(t)) = ẏ(θ(t))·θ′(t)
    # ------------------------------------------------------------------------------------------------------
    # H1. ẏ = −a y, V = y(t − h(t))², h a coefficient:  V̇ = 2 y_h · (−a y_h)(1 − ḣ) = −2a y_h² + 2a ḣ y_h²
    P = Parameters()
    a = P.scalar("a", positive=True)
    c = P.scalar("c")
    h = P.coefficient("h")
    y = Vector("y", 1)
    Y, Yh = y(t)[0], y(t - h(t))[0]
    hd = sympy.diff(h(t), t)
    system = System([Equation(y, [Term(-a * Y, text="−a y")])], parameters=P, name="decay")
    V = Functional([Term(Yh ** 2, text="y(t−h)²")])
    tv_inner = {"omits-(1-h')": (-2 * a * Yh ** 2,), "(1+h')-instead": (-2 * a * Yh ** 2, -2 * a * hd * Yh ** 2)}
    fams.append(Family("tv-delay", system, V, (-2 * a * Yh ** 2, 2 * a * hd * Yh ** 2), (Yh ** 2, Y * Yh),
                       variants={"factored": (-2 * a * (1 - hd) * Yh ** 2,)}, inner=tv_inner))
    # H2. the same with h(t) = ½ + sin(t)/4 given as a value (as `--set "h=1/2+sin(t)/4"`)
    fams.append(Family("tv-delay-set-h", system, V, (-2 * a * Yh ** 2, 2 * a * hd * Yh ** 2), (Yh ** 2, Y * Yh),
                       values={"h": "1/2 + sin(t)/4"},
                       variants={"factored": (-2 * a * (1 - hd) * Yh ** 2,)}, inner=tv_inner))
    # H3. h written out in V: V = y(t − ½ − sin(t)/4)²;  V̇ = −2a(1 − cos(t)/4) y_h²
    he = R(1, 2) + sympy.sin(t) / 4
    Ye = y(t - he)[0]
    V3 = Functional([Term(Ye ** 2, text="y(t−½−sin t/4)²")])
    fams.append(Family(
        "tv-delay-explicit", system, V3, (-2 * a * Ye ** 2, a * sympy.cos(t) / 2 * Ye ** 2), (Ye ** 2, Y * Ye),
        variants={"factored": (-2 * a * (1 - sympy.cos(t) / 4) * Ye ** 2,),
                  "expanded-cos": (-2 * a * Ye ** 2, R(1, 2) * a * sympy.cos(t) * Ye ** 2)},
        inner={"omits-(1-h')": (-2 * a * Ye ** 2,),
               "(1+h')-instead": (-2 * a * Ye ** 2, -a * sympy.cos(t) / 2 * Ye ** 2)}))
    # H4. proportional delay: V = y(t/2)²;  V̇ = 2 y(t/2)·(−a y(t/2))·½ = −a y(t/2)²
    Y2 = y(t / 2)[0]
    V4 = Functional([Term(Y2 ** 2, text="y(t/2)²")])
    fams.append(Family("proportional", system, V4, (-a * Y2 ** 2,), (Y2 ** 2, Y * Y2),
                       variants={"halved-double": (-2 * a * Y2 ** 2 / 2,)},
                       inner={"omits-1/2": (-2 * a * Y2 ** 2,), "times-2": (-4 * a * Y2 ** 2,)}))
    # H5. neutral type: V = (y − c y(t − h(t)))²;
    #     V̇ = 2(y − c y_h)(−a y + a c (1 − ḣ) y_h)
    #        = −2a y² + 4ac y y_h − 2ac ḣ y y_h − 2ac² y_h² + 2ac² ḣ y_h²
    V5 = Functional([Term((Y - c * Yh) ** 2, text="(y − c y(t−h))²")])
    neutral_terms = (-2 * a * Y ** 2, 4 * a * c * Y * Yh, -2 * a * c * hd * Y * Yh, -2 * a * c ** 2 * Yh ** 2,
                     2 * a * c ** 2 * hd * Yh ** 2)
    neutral_inner = {"omits-(1-h')": (2 * (Y - c * Yh) * (-a * Y + a * c * Yh),),
                     "(1+h')-instead": (2 * (Y - c * Yh) * (-a * Y + a * c * (1 + hd) * Yh),)}
    fams.append(Family("neutral", system, V5, neutral_terms, (Y ** 2, Y * Yh),
                       variants={"factored": (2 * (Y - c * Yh) * (-a * Y + a * c * (1 - hd) * Yh),)},
                       inner=neutral_inner))
    fams.append(Family("neutral-set-h", system, V5, neutral_terms, (Y ** 2, Y * Yh),
                       values={"h": "1/2 + sin(t)/4", "c": "1/2"},
                       variants={"factored": (2 * (Y - c * Yh) * (-a * Y + a * c * (1 - hd) * Yh),)},
                       inner=neutral_inner))
    # H6. ẏ = −a y + b y(t − τ), V = y(t − h(t))²:
    #     V̇ = 2 y_h (1 − ḣ)(−a y_h + b y(t − h − τ))
    P = Parameters()
    a = P.scalar("a", positive=True)
    b = P.scalar("b")
    tau = P.delay("tau")
    h = P.coefficient("h")
    y = Vector("y", 1)
    Y, Yh, Yht = y(t)[0], y(t - h(t))[0], y(t - h(t) - tau)[0]
    hd = sympy.diff(h(t), t)
    system = System([Equation(y, [Term(-a * Y), Term(b * y(t - tau)[0])])], parameters=P, name="delay")
    V6 = Functional([Term(Yh ** 2)])
    fams.append(Family(
        "tv-delay-of-delay-system", system, V6,
        (-2 * a * Yh ** 2, 2 * a * hd * Yh ** 2, 2 * b * Yh * Yht, -2 * b * hd * Yh * Yht), (Yh ** 2, Yh * Yht),
        variants={"factored": (2 * Yh * (1 - hd) * (-a * Yh + b * Yht),)},
        inner={"omits-(1-h')": (-2 * a * Yh ** 2, 2 * b * Yh * Yht),
               "(1-h')-on-one-term-only": (-2 * a * Yh ** 2, 2 * a * hd * Yh ** 2, 2 * b * Yh * Yht)}))
    # H7. time-varying delay in the system: ẋ = −a x + b x(t − h(t));  V = x² + q∫_{t−h(t)}^t x²;
    #     V̇ = 2x(−a x + b x_h) + q x² − q(1 − ḣ) x_h²
    P = Parameters()
    a = P.scalar("a", positive=True)
    b = P.scalar("b")
    q = P.scalar("q", positive=True)
    h = P.coefficient("h")
    x = Vector("x", 1)
    X, Xh = x(t)[0], x(t - h(t))[0]
    hd = sympy.diff(h(t), t)
    system = System([Equation(x, [Term(-a * X), Term(b * Xh, text="b x(t−h(t))")])], parameters=P,
                    name="time-varying delay")
    V7 = Functional([Term(X ** 2), Term(q * window_integral(x(xi)[0] ** 2, h(t)), text="q∫_{t−h}^t x²")])
    tvs_terms = (-2 * a * X ** 2, 2 * b * X * Xh, q * X ** 2, -q * Xh ** 2, q * hd * Xh ** 2)
    tvs_inner = {"omits-(1-h')": (-2 * a * X ** 2, 2 * b * X * Xh, q * X ** 2, -q * Xh ** 2),
                 "(1+h')-instead": (-2 * a * X ** 2, 2 * b * X * Xh, q * X ** 2, -q * Xh ** 2, -q * hd * Xh ** 2)}
    fams.append(Family("tv-delay-system", system, V7, tvs_terms, (X ** 2, X * Xh),
                       variants={"grouped": ((q - 2 * a) * X ** 2, 2 * b * X * Xh, -q * (1 - hd) * Xh ** 2)},
                       inner=tvs_inner))
    fams.append(Family("tv-delay-system-set-h", system, V7, tvs_terms, (X ** 2, X * Xh),
                       values={"h": "1/2 + sin(t)/4", "q": "2"},
                       variants={"grouped": ((q - 2 * a) * X ** 2, 2 * b * X * Xh, -q * (1 - hd) * Xh ** 2)},
                       inner=tvs_inner))
    # H8. proportional delay in the system: ẋ = −a x + b x(t/2);  V = x² + ∫_{t/2}^t x²;
    #     V̇ = 2x(−a x + b x(t/2)) + x² − ½ x(t/2)²
    P = Parameters()
    a = P.scalar("a", positive=True)
    b = P.scalar("b")
    x = Vector("x", 1)
    X, X2 = x(t)[0], x(t / 2)[0]
    system = System([Equation(x, [Term(-a * X), Term(b * X2)])], parameters=P, name="pantograph")
    V8 = Functional([Term(X ** 2), Term(window_integral(x(xi)[0] ** 2, t / 2), text="∫_{t/2}^t x²")])
    fams.append(Family(
        "pantograph-window", system, V8, (-2 * a * X ** 2, 2 * b * X * X2, X ** 2, -X2 ** 2 / 2), (X ** 2, X * X2),
        variants={"grouped": ((1 - 2 * a) * X ** 2, 2 * b * X * X2, R(-1, 2) * X2 ** 2)},
        inner={"omits-1/2": (-2 * a * X ** 2, 2 * b * X * X2, X ** 2, -X2 ** 2),
               "times-2": (-2 * a * X ** 2, 2 * b * X * X2, X ** 2, -2 * X2 ** 2)}))
    return fams


FAMILIES = _families()


def _with(terms, i, new):
    out = list(terms)
    if new is None:
        del out[i]
    else:
        out[i] = new
    return tuple(out)


#: families that repeat another family's system at given values: only their key cases run by default
REPEATS = ("sphere-feedback-norm-form", "neutral-set-h", "tv-delay-system-set-h")


def _mutated(fams):
    cases = []
    for f in fams:
        n = len(f.terms)
        repeat = f.name in REPEATS
        for i, term in enumerate(f.terms):
            cases.append(ClaimCase(f"{f.name}-sign-{i}", "sign", f, _with(f.terms, i, -term), f.values,
                                   slow=i > 0))
            cases.append(ClaimCase(f"{f.name}-drop-{i}", "dropped", f, _with(f.terms, i, None), f.values,
                                   slow=repeat or i < n - 1))
        for i in sorted({0, n - 1}):
            cases.append(ClaimCase(f"{f.name}-times2-{i}", "constant", f, _with(f.terms, i, 2 * f.terms[i]),
                                   f.values, slow=True))
        cases.append(ClaimCase(f"{f.name}-times(1+1e-9)-0", "constant", f, _with(f.terms, 0, EPS9 * f.terms[0]),
                               f.values))
        m1, m2 = f.tiny
        cases.append(ClaimCase(f"{f.name}-plus-1e-9", "tiny", f, f.terms + (TINY9 * m1,), f.values, slow=True))
        cases.append(ClaimCase(f"{f.name}-plus-1e-30", "tiny", f, f.terms + (TINY30 * m2,), f.values))
        for name, terms in f.inner.items():
            cases.append(ClaimCase(f"{f.name}-{name}", "time-varying argument", f, terms, f.values))
    return cases


def _true(fams):
    cases = []
    for f in fams:
        kind = "time-varying argument" if f.inner else "written differently"
        cases.append(ClaimCase(f"{f.name}-as-derived", kind, f, f.terms, f.values))
        repeat = f.name in REPEATS
        cases.append(ClaimCase(f"{f.name}-reversed", kind, f, tuple(reversed(f.terms)), f.values, slow=True))
        cases.append(ClaimCase(f"{f.name}-one-expanded-term", kind, f, (sympy.expand(sympy.Add(*f.terms)),),
                               f.values))
        thirds = tuple(x for term in f.terms for x in (term / 3, 2 * term / 3))
        cases.append(ClaimCase(f"{f.name}-split-thirds", kind, f, thirds, f.values, slow=True))
        for name, terms in f.variants.items():
            cases.append(ClaimCase(f"{f.name}-{name}", kind, f, terms, f.values,
                                   exact_required=name not in f.hard))
    return cases


MUTATED = _mutated(FAMILIES)
TRUE = _true(FAMILIES)

#: (family name, hand-derived V̇) for the direct closed-form check of derivative_along
CLOSED_FORMS = [(f.name, f) for f in FAMILIES if f.inner or f.name in ("scalar-weighted-window", "double-integral")]


def near_singular_matrices(count: int, seed: int = 7):
    """Rational symmetric matrices M = L D Lᵀ, L unit lower-triangular, D = diag(d₁, …, ±ε).

    By Sylvester's law of inertia M ≻ 0 exactly when every dᵢ > 0; with ε = 10⁻ᵏ
    (k = 12 … 30) M is within about ε of singular.  Returns (M, positive_definite).
    """
    rng = random.Random(seed)
    out = []
    for j in range(count):
        n = 2 + j % 2
        L = sympy.eye(n)
        for r_ in range(n):
            for c_ in range(r_):
                L[r_, c_] = R(rng.randint(-9, 9), rng.randint(1, 4))
        eps = R(1, 10 ** rng.randint(12, 30))
        pd = j % 3 != 0
        d = [R(rng.randint(1, 9), rng.randint(1, 3)) for _ in range(n - 1)]
        d.insert(n - 1 - (j // 2) % 2 if n == 3 else n - 1, eps if pd else -eps)  # the tiny pivot last or middle
        M = L * sympy.diag(*d) * L.T
        out.append((sympy.ImmutableMatrix(M), pd))
    return out
