"""Theorem 2 of paper 004: composite adaptation (3.2)–(3.4) and the Lyapunov function (3.1).

    (3.1)  V = ½[vᵀMv + θ_eᵀΓ⁻¹θ_e + K_p V_δ + ‖η‖²],  V_δ = Σkᵢ(cᵢ − sᵢ)²,  η = Mv − ε − φᵀθ_e,
    (3.2)  u = Y_cθ_r − K_p e − αv,  θ̇_r = −ΓY_cᵀv + λ_cΓφε,
           ε̇ = −λ_cε − αv − K_p e + φᵀΓY_cᵀv − λ_cφᵀΓφε,  φ̇ = −λ_cφ + Y_cᵀ,
    (3.3)  Y_cθ = Mω̇_c + ω_r × Mω,  ω̇_c = ω̇_r − λ_c v,
    (3.4)  d(Γ⁻¹)/dt = (λ_c/2)(φφᵀ − λ(t)Γ⁻¹).

The proof differentiates V piece by piece; each piece is derived here along the loop (states
and ω_d(t) symbolic, λ any value, at the run's gains) and compared with its print:

* T1 = d/dt ½vᵀMv against (3.7): exact.
* T2 + T3 against (3.8): exact.
* T4 = d/dt ½‖η‖² against the first line of (3.9), ηᵀ(−λ_cMv + Y_cθ_e − K_pe − αv − ε̇ − φ̇ᵀθ_e − φᵀθ̇_e):
  **refuted**.  Along (1.3) Mv̇ = u − Y_cθ − λ_cMv − v × Mω: the print replaced ω × Mω by ω_r × Mω
  in Mv̇ (allowed in T1 only, under vᵀ, since vᵀ(v × Mω) = 0).  Derived: η̇ = −λ_cη − v × Mω,
  T4 = −λ_c‖η‖² − ηᵀ(v × Mω) (exact).
* The second line of (3.9) prints +(λ_c/2)‖η‖²; it equals its first line (as printed) only with
  −(λ_c/2)‖η‖² (exact both ways).
* (3.10) from the printed pieces: the slack is the quadratic form
  α‖v‖² − λ_cvᵀMz + (λ_c/4)‖z‖² + (λ_c/2)‖Mv − ε‖² in (v, Mv − ε, z = φᵀθ_e) (exact identity), positive
  semidefinite iff α ≥ λ_cσ_M² (exact, Schur complement): the hypothesis α > λ_cσ_M² suffices.
* (3.10) along the true loop: refuted at an exact rational state (θ_e = 0, e = 0, η = −(v × Mω)/λ_c,
  a fast reference rotation): the dropped −ηᵀ(v × Mω) is cubic and beats the quadratic slack.
* (3.12) on D (3.6), given (3.10): −V̇ − γV ≥ Σ (nonnegative coefficient)·(nonnegative quantity) with
  the coefficients λ_c − γ/2, (λ_c − γ)/2, λ_cλ1/4 − γ/2, K_p(1 − γ/2) (the last from
  Λeᵀe > V_δ on D); all ≥ 0 iff γ ≤ min{λ_c, λ_cλ1/2, 2}: the printed γ is the largest this
  step allows (exact).
"""

from __future__ import annotations

import sympy

from lkverify import Result, Status, cross, dot, t
from lkverify.catalogue.signal_theorem import SignalTheorem
from lkverify.memo import Memo

from lkverify.symbolic.polynomial import compare_polynomials as compare, time_derivative, plain, poly_ring, to_ring
from .equations import (PAPER, Kp, Lam, M, P, alpha, c1, c2, c3, composite_laws, k1, k2, k3, lam, lam1, lam_c,
                        omega_e, s1, s2, s3, system1, system2, theta, e)

__all__ = ["theorem2", "Abstract", "abstract_loop", "reduce_det", "gamma_coefficients", "theorem2_results",
           "bound_310_results", "GAMMA_PRINTED", "isolated_equilibrium", "property_b"]

_DINV = sympy.Symbol("DINV", real=True)


def _vec(name, n=3):
    return sympy.Matrix(sympy.symbols(f"{name}1:{n + 1}", real=True))


class Abstract:
    """The loop of Theorem 2 one level up: e, ė, ω_d, ω̇_d as signals (symbols) with known derivatives.

    The states ω, θ_r, ε, φ, Γ⁻¹ are symbols and their rates are :func:`~.equations.composite_laws`
    (the same function the simulated System is built from) with Euler (1.3) for ω; e and ω_d
    enter through their values and their derivatives ė, ω̇_d (d/dt e = ė along (1.4) is proved in
    ``zaremba1997.parametrisation``), and V_δ through d/dt(½V_δ) = ω_eᵀe along (1.4), proved
    below at the component level.  Γ = adj(Γ⁻¹)·DINV with det(Γ⁻¹)·DINV = 1 (:func:`reduce_det`).
    """

    def __init__(self, values):
        sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
        self.sub = sub
        self.M = M.xreplace(sub)
        self.w, self.wd, self.wdd = _vec("w"), _vec("wd"), _vec("wdd")
        self.e, self.ed = _vec("e"), _vec("ed")
        self.th, self.ep = _vec("th"), _vec("ep")
        self.ph = sympy.Matrix(3, 3, sympy.symbols("ph1:10", real=True))
        g = sympy.symbols("g1:7", real=True)
        self.g = g
        self.Gm = sympy.Matrix([[g[0], g[1], g[2]], [g[1], g[3], g[4]], [g[2], g[4], g[5]]])
        self.Vd = sympy.Symbol("Vdelta", nonnegative=True)
        self.det = sympy.expand(self.Gm.det())
        Gam = self.Gm.adjugate() * _DINV
        law = composite_laws(self.w, self.wd, self.wdd, self.e, self.ed, self.th, self.ep, self.ph, self.Gm, Gam, lam)
        self.law = {k: x.xreplace(sub) for k, x in law.items()}
        self.Gam = Gam
        self.theta = theta.xreplace(sub)
        self.th_e = self.th - self.theta
        self.v = self.law["v"]
        self.eta = self.M * self.v - self.ep - self.ph.T * self.th_e
        self.q = {name: sympy.sympify(x).xreplace(sub) for name, x in
                  (("lam_c", lam_c), ("alpha", alpha), ("Kp", Kp), ("Lam", Lam), ("lam1", lam1))}
        wdot = self.M.inv() * (-cross(self.w, self.M * self.w) + self.law["u"])             # (1.3)
        self.raw_rates = [(self.w, wdot), (self.wd, self.wdd), (self.e, self.ed), (self.th, self.law["theta_r"]),
                      (self.ep, self.law["eps"]), (self.ph, self.law["phi"]),
                      (sympy.Matrix(g), sympy.Matrix([self.law["G"][i, j] for i, j in
                                                      ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))])),
                      (sympy.Matrix([self.Vd]), sympy.Matrix([2 * dot(self.w - self.wd, self.e)]))]

        pairs = [(x, r) for xs, rs in self.raw_rates for x, r in zip(xs, rs)]
        self.R = poly_ring([r for _, r in pairs] + [self.eta[i] for i in range(3)], extra=[_DINV, lam] + [x for x, _ in pairs])
        self.rates = [(self.R.gens[self.R.symbols.index(x)], to_ring(self.R, r)) for x, r in pairs]
        self.det_r = to_ring(self.R, self.det)

    def poly(self, expr):
        """``expr`` in the ring of the abstract loop, reduced with det(Γ⁻¹)·DINV = 1."""
        return reduce_det(to_ring(self.R, expr), self.det_r)

    def derivative(self, V):
        """V̇ by the chain rule over the abstract states (exact, reduced with det(Γ⁻¹)·DINV = 1)."""
        Vr = to_ring(self.R, V)
        total = self.R.zero
        for x, r in self.rates:
            d = Vr.diff(x)
            if d:
                total += d * r
        return reduce_det(total, self.det_r)


def abstract_loop(values):
    return Abstract(values)


def reduce_det(p, det):
    """p = c0 + c1·DINV (a ring element, at most linear in DINV) → c0 + c1/det(Γ⁻¹) when det(Γ⁻¹) divides c1
    (exact polynomial division; the remainder, if any, stays on DINV)."""
    R = p.ring
    k = R.symbols.index(_DINV)
    dinv = R.gens[k]
    c0, c1 = R.zero, R.zero
    for monom, coeff in p.terms():
        if monom[k] == 0:
            c0 += R({monom: coeff})
        elif monom[k] == 1:
            c1 += R({monom[:k] + (0,) + monom[k + 1:]: coeff})
        else:
            raise ValueError("reduce_det: DINV enters V̇ at most linearly")
    if not c1:
        return p
    q, r = c1.div(det)
    return c0 + q + r * dinv


def _printed(a):
    """The printed right-hand sides of (3.7), (3.8) and the first line of (3.9)."""
    lc, al, kp = a.q["lam_c"], a.q["alpha"], a.q["Kp"]
    L, th_e, ph, v, e_ = a.law, a.th_e, a.ph, a.v, a.e
    Yc = L["Y_c"]
    T1 = [("−λ_cvᵀMv", -lc * dot(v, a.M * v)), ("−αvᵀv", -al * dot(v, v)), ("−K_pvᵀe", -kp * dot(v, e_)),
          ("vᵀY_cθ_e", dot(v, Yc * th_e))]
    T23 = [("θ_eᵀΓ⁻¹θ̇_e", (th_e.T * a.Gm * L["theta_r"])[0, 0]),
           ("(λ_c/4)‖θ_e‖²_φφᵀ", lc / 4 * dot(ph.T * th_e, ph.T * th_e)),
           ("−(λ_c/4)λ‖θ_e‖²_Γ⁻¹", -lc / 4 * lam * (th_e.T * a.Gm * th_e)[0, 0]),
           ("K_pω_eᵀe", kp * dot(a.w - a.wd, e_))]
    inner = (-lc * a.M * v + Yc * th_e - kp * e_ - al * v - L["eps"] - L["phi"].T * th_e - ph.T * L["theta_r"])
    T4 = [("ηᵀ(−λ_cMv + Y_cθ_e − K_pe − αv − ε̇ − φ̇ᵀθ_e − φᵀθ̇_e)", dot(a.eta, inner))]
    return {k: [(lab, a.poly(x)) for lab, x in val] for k, val in (("T1", T1), ("T23", T23), ("T4", T4))}


def theorem2_results(values):
    """(3.7), (3.8), (3.9) against the derivation; the derived T4; the second line of (3.9)."""
    a = Abstract(values)
    out = [_vdelta_lemma(a)]
    V = {"T1": dot(a.v, a.M * a.v) / 2, "T23": (a.th_e.T * a.Gm * a.th_e)[0, 0] / 2 + a.q["Kp"] * a.Vd / 2,
         "T4": dot(a.eta, a.eta) / 2}
    derived = {k: a.derivative(x) for k, x in V.items()}
    printed = _printed(a)
    for key, label in (("T1", "(3.7): T1 = d/dt ½vᵀMv"), ("T23", "(3.8): T2 + T3"),
                       ("T4", "(3.9) first line: T4 = d/dt ½‖η‖²")):
        out.append(compare(label, printed[key], [(f"{key} derived", derived[key])], reference=label.split(":")[0],
                           R=a.R))
    lc, eta = a.q["lam_c"], a.eta
    out.append(compare("T4 derived: −λ_c‖η‖² − ηᵀ(v × Mω)",
                       [("−λ_c‖η‖²", -lc * dot(eta, eta)), ("−ηᵀ(v×Mω)", -dot(eta, cross(a.v, a.M * a.w)))],
                       [("T4 derived", derived["T4"])], reference="T4 with the gyroscopic term kept", R=a.R))
    gyro = dot(eta, cross(a.v, a.M * a.w))
    out.append(compare("(3.9) first line − T4 derived = ηᵀ(v × Mω)", printed["T4"],
                       [("T4 derived", derived["T4"]), ("ηᵀ(v×Mω)", a.poly(gyro))],
                       reference="the first line of (3.9): the term −v × Mω of Mv̇ is missing", R=a.R))
    mv_e, z = a.M * a.v - a.ep, a.ph.T * a.th_e
    line2 = [("+(λ_c/2)‖η‖²", lc / 2 * dot(eta, eta)), ("−(λ_c/2)‖Mv − ε‖²", -lc / 2 * dot(mv_e, mv_e)),
             ("λ_c(Mv − ε)ᵀφᵀθ_e", lc * dot(mv_e, z)), ("−(λ_c/2)‖θ_e‖²_φφᵀ", -lc / 2 * dot(z, z))]
    out.append(compare("(3.9) second line = first line (as printed)", line2, printed["T4"],
                       reference="the second line of (3.9)", R=a.R))
    fixed = [("−(λ_c/2)‖η‖²", -lc / 2 * dot(eta, eta))] + line2[1:]
    out.append(compare("(3.9) second line with −(λ_c/2)‖η‖² = first line", fixed, printed["T4"],
                       reference="the second line of (3.9) with the sign of its first term changed", R=a.R))
    return out, a, derived, printed


def _vdelta_lemma(a):
    """d/dt(½V_δ) = ω_eᵀe along (1.4), at the component level (the rate the abstract loop gives V_δ)."""
    S, Cs, K = (s1(t), s2(t), s3(t)), (c1, c2, c3), (k1, k2, k3)
    Vd = sum((k * dot(c - s, c - s) for k, s, c in zip(K, S, Cs)), sympy.Integer(0))
    return compare("d/dt(½V_δ) = ω_eᵀe along (1.4)", [("ω_eᵀe", plain(dot(omega_e, e).xreplace(a.sub)))],
                   [("d/dt ½Σkᵢ(cᵢ − sᵢ)²", time_derivative(Vd / 2, system1, a.sub))],
                   reference="the rate of V_δ (the T3 of (3.8))")


def GAMMA_PRINTED(values):
    """γ of (3.12) as printed: min{λ_c, λ_cλ1/2, 2}."""
    lc, l1 = sympy.sympify(values["lam_c"]), sympy.sympify(values["lam1"])
    return sympy.Min(lc, lc * l1 / 2, 2)


def _sigma_M(values):
    return max(sympy.Matrix(values["M"]).eigenvals(multiple=True))


def _rhs_310(a):
    lc, kp, L = a.q["lam_c"], a.q["Kp"], a.q["Lam"]
    return [("−λ_cvᵀMv", -lc * dot(a.v, a.M * a.v)), ("−(λ_c/2)‖η‖²", -lc / 2 * dot(a.eta, a.eta)),
            ("−(λ_c/4)λ‖θ_e‖²_Γ⁻¹", -lc / 4 * lam * (a.th_e.T * a.Gm * a.th_e)[0, 0]),
            ("−K_pΛeᵀe", -kp * L * dot(a.e, a.e))]


def _witness_310(a, slack):
    """An exact rational state where V̇ > (3.10): θ_e = 0, e = 0, Γ⁻¹ = I, η = −(v × Mω)/λ_c, ω_d = (0, 0, W)."""
    lc = a.q["lam_c"]
    R = a.R
    for W in (10, 100, 1000, 10000):
        vv = sympy.Matrix([sympy.Rational(1, 10), 0, 0])
        wd_ = sympy.Matrix([0, 0, W])
        w = wd_ + vv
        ep = a.M * vv + cross(vv, a.M * w) / lc
        point = {}
        for vec, val in ((a.w, w), (a.wd, wd_), (a.e, [0, 0, 0]), (a.th, a.theta), (a.ep, ep)):
            point.update({x: sympy.sympify(y) for x, y in zip(vec, val)})
        point.update({x: (1 if i in (0, 3, 5) else 0) for i, x in enumerate(a.g)})
        point[_DINV], point[lam] = 1, a.q["lam1"]
        full = {s: point.get(s, 0) for s in R.symbols}
        value = slack.evaluate([(R.gens[i], full[s]) for i, s in enumerate(R.symbols)])
        if value < 0:
            return W, value
    return None, None


def bound_310_results(a, derived, printed):
    """(3.10): the slack of the printed pieces is a PSD form iff α ≥ λ_cσ_M²; along the true loop refuted."""
    lc, al = a.q["lam_c"], a.q["alpha"]
    R = a.R
    rhs = sum((a.poly(x) for _, x in _rhs_310(a)), R.zero)
    paper = sum((x for k in ("T1", "T23", "T4") for _, x in printed[k]), R.zero)
    true = derived["T1"] + derived["T23"] + derived["T4"]
    z = a.ph.T * a.th_e
    mv_e = a.M * a.v - a.ep
    Q = [("α‖v‖²", al * dot(a.v, a.v)), ("−λ_cvᵀMz", -lc * dot(a.v, a.M * z)), ("(λ_c/4)‖z‖²", lc / 4 * dot(z, z)),
         ("(λ_c/2)‖Mv − ε‖²", lc / 2 * dot(mv_e, mv_e))]
    out = [compare("(3.10) − (3.7)–(3.9) as printed = Q(v, Mv − ε, z = φᵀθ_e)", Q,
                   [("(3.10) − Σ printed pieces", rhs - paper)], reference="the slack of (3.10)", R=R)]
    from .corrected import young_form_psd

    res = young_form_psd(a, al, "Q")
    out.append(Result("bound", "(3.10) from the printed pieces: Q ⪰ 0 (Young's step, μ = 2σ_M)", res.status, None,
                      f"the 9 × 9 matrix of Q in (v, Mv − ε, z): {res.detail}; Schur complement: Q ⪰ 0 ⇔ "
                      f"αI − λ_cM² ⪰ 0 ⇔ α ≥ λ_cσ_M² = {lc * _sigma_M_from(a) ** 2}"))
    W, value = _witness_310(a, rhs - true)
    out.append(Result("bound", "(3.10) along the true loop (1.3), (3.2)–(3.4)",
                      Status.FAILED if value is not None else Status.UNDECIDED,
                      None if value is None else {"W": W, "rhs_minus_Vdot": str(value)},
                      "V̇ exceeds (3.10) by the dropped −ηᵀ(v × Mω): at θ_e = 0, e = 0, Γ⁻¹ = I, v = (1/10, 0, 0), "
                      f"ω_d = (0, 0, {W}), ε = Mv + (v × Mω)/λ_c (η = −(v × Mω)/λ_c): (3.10) − V̇ = {value} < 0 (exact)"
                      if value is not None else "no witness found on the ray tried"))
    return out


def _sigma_M_from(a):
    return max(a.M.eigenvals(multiple=True))


def gamma_coefficients(values, gamma=None, *, eta=None):
    """−(RHS of (3.10)) − γV on D, as coefficients of the nonnegative quantities (must all be ≥ 0).

    ``eta``: the coefficient of −‖η‖² in the bound (default λ_c/2, as printed; (3.10′) has λ_c/4).

    With qv = vᵀMv, qη = ‖η‖², qθ = θ_eᵀΓ⁻¹θ_e, V = ½(qv + qθ + K_pV_δ + qη) (3.1), λ = λ1 + δ (δ ≥ 0,
    property (b)) and, on D, eᵀe = V_δ/Λ + σ (σ > 0).  Returns (γ, {quantity: coefficient}, γ_max)
    where γ_max is the largest γ for which every coefficient is ≥ 0.
    """
    g = sympy.Symbol("gamma")
    qv, qeta, qth, Vd, sig, dl = sympy.symbols("qv qeta qtheta Vdelta sigma delta", nonnegative=True)
    lc, kp, L, l1 = (sympy.sympify(values[k]) for k in ("lam_c", "Kp", "Lam", "lam1"))
    ce = lc / 2 if eta is None else sympy.sympify(eta)
    rhs = -lc * qv - ce * qeta - lc / 4 * (l1 + dl) * qth - kp * L * (Vd / L + sig)      # (3.10) on D
    V = (qv + qth + kp * Vd + qeta) / 2                                                 # (3.1)
    E = sympy.expand(-(rhs + g * V))
    quantities = {"vᵀMv": qv, "‖η‖²": qeta, "θ_eᵀΓ⁻¹θ_e": qth, "δ·θ_eᵀΓ⁻¹θ_e": dl * qth, "V_δ": Vd, "σ": sig}
    poly = sympy.Poly(E, qv, qeta, qth, Vd, sig, dl)
    coeffs = {name: poly.coeff_monomial(q) for name, q in quantities.items()}
    bounds = [sympy.solve(sympy.Eq(c, 0), g)[0] for c in coeffs.values() if c.has(g)]
    gmax = sympy.Min(*bounds)
    gamma = GAMMA_PRINTED(values) if gamma is None else sympy.sympify(gamma)
    return gamma, {k: c.subs(g, gamma) for k, c in coeffs.items()}, gmax


def gamma_results(values, gamma=None):
    gam, coeffs, gmax = gamma_coefficients(values, gamma)
    bad = {k: c for k, c in coeffs.items() if c < 0}
    out = [Result("bound", "(3.12): V̇ + γV ≤ 0 on D (3.6), given (3.10)", Status.FAILED if bad else Status.EXACT,
                  {"gamma": str(gam), **{k: str(c) for k, c in coeffs.items()}},
                  f"γ = {gam}: −(3.10) − γV = Σ coefficient·quantity with coefficients "
                  + ", ".join(f"{k}: {c}" for k, c in coeffs.items())
                  + (f"; negative: {', '.join(bad)}" if bad else " (all ≥ 0; λ ≥ λ1 and Λeᵀe > V_δ on D)"))]
    printed = GAMMA_PRINTED(values)
    out.append(Result("constant", "γ of (3.12) against the largest γ of this step", Status.EXACT if
                      sympy.simplify(printed - gmax) == 0 else Status.FAILED, {"printed": str(printed), "largest": str(gmax)},
                      f"every coefficient ≥ 0 iff γ ≤ {gmax}; printed min{{λ_c, λ_cλ1/2, 2}} = {printed}"))
    return out


def hypotheses2(values):
    """λ_c > 0, K_p > 0, Λ > 0 and α > λ_cσ_M² (exact)."""
    lc, al = sympy.sympify(values["lam_c"]), sympy.sympify(values["alpha"])
    thr = lc * _sigma_M(values) ** 2
    margin = al - thr
    out = [Result("hypothesis", "α > λ_cσ_M² (3.2)", Status.EXACT if margin > 0 else Status.FAILED, str(margin),
                  f"α = {al}, λ_cσ_M² = {thr} (σ_M = {_sigma_M(values)}): margin {margin}")]
    for k, label in (("lam_c", "λ_c > 0"), ("Kp", "K_p > 0"), ("Lam", "Λ > 0"), ("lam1", "λ1 > 0")):
        x = sympy.sympify(values[k])
        out.append(Result("hypothesis", label, Status.EXACT if x > 0 else Status.FAILED, str(x), f"{k} = {x}"))
    return out


_RUNS = Memo(1)  # the derivations of the last values: the derivations, the links and the findings share them


def _derived(values):
    """theorem2_results, bound_310_results, gamma_results and chetaev_results at these values (once per process)."""
    from .chetaev import chetaev_results
    from .corrected import corrected_results

    key = tuple(sorted((k, str(v)) for k, v in values.items()))
    hit = _RUNS.get(key)
    if hit is None:
        out, a, derived, printed = theorem2_results(values)
        hit = _RUNS[key] = {"identities": out, "310": bound_310_results(a, derived, printed),
                            "gamma": gamma_results(values), "chetaev": chetaev_results(a, derived),
                            "corrected": corrected_results(a, derived, values)}
    return hit


#: the rows of theorem2_results that derive V̇ (links); the others compare the paper's print (findings)
_DERIVATIONS = ("d/dt(½V_δ) = ω_eᵀe along (1.4)", "(3.7): T1 = d/dt ½vᵀMv", "(3.8): T2 + T3",
                "T4 derived: −λ_c‖η‖² − ηᵀ(v × Mω)")


def _hypotheses(values):
    from .equations import reference_bounded

    return hypotheses2(values) + [Result("hypothesis", "ω_d, ω̇_d bounded (the programmed motion)",
                                         *reference_bounded(values))]


def _identities(values):
    return [r for r in _derived(values)["identities"] if r.name in _DERIVATIONS]


def property_b_printed(values) -> Result:
    """(b) of (3.4) as printed, "λ(t) ≥ λ1 > 0 for every t ≥ 0", at initial data (3.4) admits: Γ(0) = k0·I has
    ‖Γ(0)‖ = k0, so λ(0) = λ0(1 − ‖Γ(0)‖/k0) = 0 < λ1 (exact)."""
    l0, kk, l1 = (sympy.sympify(values[k]) for k in ("lam0", "k0", "lam1"))
    lam_0 = l0 * (1 - kk / kk)
    ok = lam_0 >= l1
    return Result("bound", "(b) of (3.4) as printed: λ(t) ≥ λ1 for every t ≥ 0", Status.EXACT if ok else Status.FAILED,
                  {"lambda(0)": str(lam_0), "lam1": str(l1)},
                  f"Γ(0) = k0·I = {kk}·I is admitted by (3.4) (Γ(0) = Γ(0)ᵀ > 0, ‖Γ(0)‖ ≤ k0) and gives "
                  f"λ(0) = λ0(1 − ‖Γ(0)‖/k0) = {lam_0} < λ1 = {l1}: the bound holds only from some time on "
                  f"(the chain uses t ≥ T + δ)")


def _findings(values):
    d = _derived(values)
    return ([r for r in d["identities"] if r.name not in _DERIVATIONS] + list(d["310"]) + list(d["gamma"])
            + d["chetaev"] + [property_b_printed(values)])


def chetaev_link(values, rate_status, rate="V̇_c = 2V̇ < 0 where V_c < 0, i.e. (3.10)"):
    """Chetaev's theorem for s* = (−c1, c2, −c3) (Theorem 2 (в)) with V_c of (3.11) (K_p and ‖η‖²).

    At s*, v = 0, θ_e = 0, η = 0 the terms vᵀMv, θ_eᵀΓ⁻¹θ_e, ‖η‖² vanish, and along the rotations of the
    triad about c2 by the Cayley parameter ε (only s moves) V_c = K_p(−k1‖c1 + s1‖² + k2‖c2 − s2‖² − k3‖c3 + s3‖²);
    the link decides V_c(s*) = 0 and V_c < 0 for ε ∈ (0, 1) exactly; V̇_c < 0 where V_c < 0 rests on (3.10).
    """
    from lkverify.certify.steps import Chetaev
    from lkverify.symbolic.polynomial import plain

    sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
    eps_ = sympy.Symbol("epsilon", positive=True)
    C = [sympy.Matrix(c.xreplace(sub)) for c in (c1, c2, c3)]
    axis = C[1]
    K = sympy.Matrix([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]]) * eps_
    R = (sympy.eye(3) - K).inv() * (sympy.eye(3) + K)                     # Cayley: a rotation about c2
    S_t = (s1(t), s2(t), s3(t))
    S = [plain(x) for x in S_t]
    star = [-C[0], C[1], -C[2]]
    ks = [sympy.sympify(k).xreplace(sub) for k in (k1, k2, k3)]
    signed = (-ks[0] * dot(C[0] + S[0], C[0] + S[0]) + ks[1] * dot(C[1] - S[1], C[1] - S[1])
              - ks[2] * dot(C[2] + S[2], C[2] + S[2]))
    Vc = sympy.sympify(values["Kp"]) * signed
    point = {x: v for Sx, st in zip(S, star) for x, v in zip(Sx, st)}
    curve = {x: v for Sx, st in zip(S, star) for x, v in zip(Sx, R * st)}
    return Chetaev(Vc, point, curve, eps_, (rate, rate_status),
                   name="(в) Chetaev: s = (−c1, c2, −c3) unstable")


def isolated_equilibrium(values) -> Result:
    """s* = (−c1, c2, −c3) is an isolated zero of e = Σkᵢsᵢ × cᵢ on the triads: with sᵢ = R(p)s*ᵢ (Cayley,
    R(0) = I) the Jacobian ∂e/∂p at p = 0 is nonsingular (exact), so near s* only s* has e = 0."""
    sub = P.substitution({k: x for k, x in values.items() if not k.startswith("wd")})
    C = [sympy.Matrix(c.xreplace(sub)) for c in (c1, c2, c3)]
    ks = [sympy.sympify(k).xreplace(sub) for k in (k1, k2, k3)]
    p = sympy.symbols("p1:4", real=True)
    K = sympy.Matrix([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    R = (sympy.eye(3) - K).inv() * (sympy.eye(3) + K)
    star = [-C[0], C[1], -C[2]]
    e_ = sum((k * cross(R * st, c) for k, st, c in zip(ks, star, C)), sympy.zeros(3, 1))
    at0 = {x: 0 for x in p}
    J = e_.jacobian(list(p)).xreplace(at0).applyfunc(sympy.simplify)
    det = sympy.simplify(J.det())
    zero = all(sympy.simplify(x) == 0 for x in e_.xreplace(at0))
    ok = zero and det != 0
    status = Status.EXACT if ok else (Status.FAILED if not zero else Status.UNDECIDED)   # det = 0 refutes nothing
    return Result("bound", "s* = (−c1, c2, −c3) an isolated zero of e on the triads", status, str(det), f"e(s*) = 0: {zero}; det ∂e/∂p at s* = {det} (exact; k1, k2, k3 = "
                  f"{', '.join(map(str, ks))})" + ("" if ok else ": not shown isolated"))


def _prior(name):
    """The status the earlier link ``name`` of the chain was decided with (a premise of :class:`Follows`)."""
    return lambda facts: facts.link_status(name)


def _gain_bounded(facts):
    return facts.bounded.get("(Γ⁻¹)⁻¹", (Status.UNDECIDED,))[0]


def _with_gain(link):
    """``link`` (Chetaev's) also resting on (a) of (3.4), decided earlier in the chain: (3.10′) needs λ ≥ 0."""
    from lkverify.certify.steps import Decided

    def compute(facts):
        res = link.decide(facts)
        gain = _gain_bounded(facts)
        status = Status.weakest([res.status, gain])
        return Result(res.kind, link.name, status, res.value, f"{res.detail}; λ ≥ 0 by (a) ({gain})")

    return Decided(link.name, compute)


def _rates_bounded(values):
    """v̇ and ė along the loop: polynomials in ω, sᵢ, θ_r and the references (no Γ, φ, ε, λ)?"""
    from .equations import omega, s1, s2, s3, theta_r, v, e

    def compute(facts):
        allowed = {facts.plain(x) for st in (omega, s1, s2, s3, theta_r) for x in st(t)}
        parts, refs = [], set()
        for name, sig in (("v", v), ("e", e)):
            for k in range(3):
                rate = sympy.expand(facts.rate(sig[k]))
                extra = {x for x in rate.free_symbols if x not in allowed}
                ref = {x for x in extra if str(x).startswith("wd")}
                refs |= ref
                if extra - ref:
                    parts.append((Status.FAILED, f"d/dt {name}_{k + 1} contains {sorted(map(str, extra - ref))}"))
                    continue
                try:
                    poly = sympy.Poly(rate, *sorted(allowed | ref, key=str))
                    ok = not any(c.free_symbols for c in poly.coeffs())
                except sympy.PolynomialError:
                    ok = False
                parts.append((Status.EXACT if ok else Status.UNDECIDED,
                              f"d/dt {name}_{k + 1} {'is' if ok else 'is not'} a polynomial in ω, sᵢ, θ_r, ω_d, ω̇_d"))
        for x in sorted(refs, key=str):
            parts.append(facts.reference_bounded(x))
        status = Status.weakest(st for st, _ in parts)
        bad = [why for st, why in parts if not st.is_proof]
        return Result("bound", "v̇, ė bounded on {V < V0}", status, None,
                      "; ".join(bad) if bad else "v̇ and ė are polynomials in ω, sᵢ, θ_r and the bounded references "
                      "(no Γ, φ, ε or λ): bounded where ω, sᵢ (‖sᵢ − cᵢ‖² ≤ 2V0/(K_pkᵢ)) and θ_r "
                      "(‖θ_e‖² ≤ 2k0V0 by Γ⁻¹ ⪰ I/k0) are")

    return compute


def property_b(values, beta1):
    """(b) of (3.4) for t ≥ T + δ from (3.5) along the loop with β1/2: Γ⁻¹(t) ⪰ (λ_c/2)e^{−λ_cλ0δ/2}(β1/2)I, so
    ‖Γ‖ ≤ k1 = 4e^{λ_cλ0δ/2}/(λ_cβ1) and λ ≥ λ1* = λ0(1 − k1/k0) (certified with arb); (status, detail)."""
    import flint

    from lkverify.certify.intervals.rounding import float_down, float_up

    if beta1 is None or not beta1 > 0:
        return Status.UNDECIDED, "no certified β1 > 0 of ∫φφᵀ"

    def ball(x):
        x = sympy.Rational(sympy.sympify(x))
        return flint.arb(int(x.p)) / int(x.q)

    lc, l0, kk, dl, l1 = (values[k] for k in ("lam_c", "lam0", "k0", "delta", "lam1"))
    with flint.ctx.workprec(128):
        k1 = 4 * (ball(lc) * ball(l0) * ball(dl) / 2).exp() / (ball(lc) * flint.arb(beta1))
        lam1_star = ball(l0) * (1 - k1 / ball(kk))
    k1_up, star = float_up(k1), float_down(lam1_star)
    text = (f"Γ⁻¹ ⪰ (λ_c/2)e^{{−λ_cλ0δ/2}}(β1/2)I for t ≥ T + δ (λ ≤ λ0), so ‖Γ‖ ≤ k1 = 4e^{{λ_cλ0δ/2}}/(λ_cβ1) "
            f"≤ {k1_up:.4g} (β1 = {beta1:.4g} certified)")
    if not star > 0:
        return Status.UNDECIDED, f"{text} ≥ k0 = {kk}: this bound gives no λ1 > 0 (not refuted)"
    if not star >= float(sympy.Rational(sympy.sympify(l1))):
        return Status.UNDECIDED, (f"{text} < k0 = {kk}: λ ≥ λ1* = λ0(1 − k1/k0) ≥ {star:.4g}, below the λ1 = {l1} "
                                  f"of γ (not refuted)")
    return Status.CERTIFIED, f"{text} < k0 = {kk}: λ(t) ≥ λ1* ≥ {star:.4g} ≥ λ1 = {l1} for t ≥ T + δ"


def argument(values):
    """The links after the derived pieces of V̇, on the corrected step (3.10′) of :mod:`.corrected`: (3.4) (a),
    the level set, L2, Barbalat ((2.3)), (3.5), (b), (3.12′) on D, θ_r → θ, Chetaev (3.11)."""
    from lkverify.certify.steps import Decided, Follows, Forgetting

    from .corrected import additional_hypotheses
    from .equations import G_matrix, k0, lam0, phi_matrix
    from .excitation import excitation_bounds

    d = _derived(values)
    cor = d["corrected"]
    k = cor["constants"]
    add = additional_hypotheses(values)[0]
    chet = {r.name: r.status for r in d["chetaev"]}
    iso = isolated_equilibrium(values)
    pe = excitation_bounds(values)
    lc = sympy.sympify(values["lam_c"])
    step = Status.weakest([cor["identity"].status, cor["A"].status, cor["lagrange"].status])
    W, V0 = k.get("W"), k.get("V0")

    def pe_result(facts):
        st = Status.weakest(b.status for b in pe.values())
        return Result("constant", "(3.5)", st, {n: (b.beta1, b.beta2) for n, b in pe.items()},
                      "; ".join(f"∫{n}: {b.detail}" for n, b in pe.items()))

    gam, coeffs, gmax = gamma_coefficients(values, eta=lc / 4)
    gam_ok = Status.EXACT if gmax > 0 and all(c >= 0 for c in gamma_coefficients(values, gmax, eta=lc / 4)[1].values()) \
        else Status.FAILED
    beta1 = pe["φφᵀ"].beta1 if pe["φφᵀ"].status.is_proof else None
    b_status, b_detail = property_b(values, beta1)
    s310 = "(3.10′) wherever ‖ω‖ ≤ W: V̇ ≤ −λ_cvᵀMv − (λ_c/4)‖η‖² − (λ_c/4)λ‖θ_e‖²_Γ⁻¹ − K_pΛeᵀe"
    level = f"‖ω‖ ≤ W on {{V ≤ V0}}, V0 = {V0}"
    inv, l2, rates = "{V < V0} positively invariant, V nonincreasing on it", "v, e ∈ L2", "v̇, ė bounded on {V < V0}"
    poly_rates = "v̇, ė polynomials in ω, sᵢ, θ_r, ω_d, ω̇_d"
    goal, pe_name = "(2.3): e → 0, ω → ω_d (Barbalat, Lemma 1)", "persistent excitation (3.5): β1, β2 along the programmed motion"
    loop_pe, prop_b = "(3.5) along the loop's φ for t ≥ T", "(b) of (3.4): λ(t) ≥ λ1 for t ≥ T + δ"
    added = "additional hypothesis (derived)"
    links = [
        Decided(added, lambda facts: add),
        Forgetting("Γ⁻¹", G_matrix(), phi_matrix(), lam_c / 2, lam, lam0, k0, inverse="Γ"),
        Decided(s310, lambda facts: Result("bound", s310, step, {"W": str(W)},
                                              f"W = {W}: {cor['identity'].detail}; {cor['A'].detail}; "
                                              f"{cor['lagrange'].detail}")),
        Follows(level, ((added, _prior(added)), ("Γ⁻¹ ≻ 0 (a)", _gain_bounded),
                         (cor["level"].name, cor["level"].status)),
                 f"V ≥ ½σ_m‖v‖², V ≥ ½K_pV_δ (Γ⁻¹ ≻ 0): ‖ω‖ ≤ w̄ + κ_V·V0^{{1/2}} ≤ W"
                 f" (w̄ = {k.get('w_bar')}, κ_V = {k.get('kappa_V')})"),
        Follows(inv, (("(3.10′)", _prior(s310)), (level, _prior(level)), ("λ ≥ 0 (a)", _gain_bounded)),
                 "V̇ ≤ (3.10′) ≤ 0 on {V ≤ V0}: at a first time with V = V0, V(t) ≤ V(0) < V0 — so for the initial "
                 "data with V(0) < V0 (the statement is semi-global)"),
        Follows(l2, (("(3.10′)", _prior(s310)), (inv, _prior(inv))),
                 "∫_0^∞(λ_cσ_m‖v‖² + K_pΛ‖e‖²) ≤ V(0) by (3.10′) on the invariant level set"),
        Decided(poly_rates, _rates_bounded(values)),
        Follows(rates, ((poly_rates, _prior(poly_rates)), (level, _prior(level)), ("(a): θ_r bounded", _gain_bounded)),
                 "v̇, ė are polynomials in ω, sᵢ, θ_r and the references, each bounded on {V < V0}: ‖ω‖ ≤ W, "
                 "‖sᵢ − cᵢ‖² ≤ 2V0/(K_pkᵢ), ‖θ_e‖² ≤ 2k0V0 (Γ⁻¹ ⪰ I/k0)"),
        Follows(goal, ((l2, _prior(l2)), (rates, _prior(rates))),
                 "v, e ∈ L2 with bounded derivatives tend to 0 (Lemma 1), and ω − ω_d = v − Λe"),
        Decided(pe_name, pe_result),
        Follows(loop_pe, ((goal, _prior(goal)), (pe_name, _prior(pe_name))),
                 "with e, ė, v → 0 ((2.3)) Y_c tends uniformly to its value on the programmed motion, the filter "
                 "φ̇ = −λ_cφ + Y_cᵀ is stable, so ∫_t^{t+δ}φφᵀ ⪰ (β1/2)I for t ≥ some T (T not computed)"),
        Follows(prop_b, ((loop_pe, _prior(loop_pe)), ("(a)", _gain_bounded), ("k1 < k0, λ1 ≤ λ1*", b_status)),
                 b_detail),
        Follows("(3.12′): V̇ + γ′V ≤ 0 on D (3.6) for t ≥ T + δ",
                 (("(3.10′)", _prior(s310)), (inv, _prior(inv)), ("(b)", _prior(prop_b)),
                  (f"−(3.10′) − γ′V ≥ 0 on D, γ′ = {gmax}", gam_ok)),
                 f"the coefficients of −(3.10′) − γV on D are ≥ 0 iff γ ≤ γ′ = {gmax} (min{{λ_c/2, λ_cλ1/2, 2}}; "
                 f"printed γ = min{{λ_c, λ_cλ1/2, 2}} = {GAMMA_PRINTED(values)})"),
        Follows("(а), (б): θ_r → θ, ε → 0 (PE)",
                 (("(b)", _prior(prop_b)), ("(a)", _gain_bounded), (l2, _prior(l2)), (goal, _prior(goal))),
                 "λ ≥ λ1 > 0 and Γ⁻¹ ⪰ I/k0 make θ_e ∈ L2 by (3.10′); θ̇_e bounded (Γ ≤ k0, φ, ε bounded) gives "
                 "θ_e → 0; η ∈ L2 ∩ L∞ with η̇ bounded gives η → 0, so ε = Mv − φᵀθ_e − η → 0"),
        _with_gain(chetaev_link(values, Status.weakest([step, add.status, iso.status,
                                                        chet.get("(3.11) with K_p and ‖η‖²: V̇_c = 2V̇",
                                                                 Status.UNDECIDED)]),
                                rate=f"V̇_c = 2V̇ ≤ 2(3.10′) < 0 where V_c < 0 near s*: ‖ω − ω_d‖ < W − w̄ there, and "
                                     f"e ≠ 0 (V_c < 0 needs s ≠ s*, and {iso.name}: {iso.detail})")),
    ]
    return links, {f"wd{i}": values[f"wd{i}"] for i in (1, 2, 3)}


theorem2 = SignalTheorem(
    "theorem2", system=system2, hypotheses=[_hypotheses], derivations=[_identities], argument=argument,
    findings=[_findings], paper=PAPER, derivations_link="V̇ of (3.1) piece by piece along the loop",
    relevant=("M", "k1", "k2", "k3", "Lam", "Kp", "alpha", "lam_c", "lam0", "k0", "lam1", "delta", "wd1", "wd2", "wd3"),
    conclusion="(2.3) e → 0, ω → ω_d; θ_r → θ, ε → 0; V̇ + γ′V ≤ 0 on D; s = (−c1, c2, −c3) unstable — from "
               "initial data with V(0) < V0",
    title="Theorem 2: V (3.1) along (1.3), (1.4), (3.2)–(3.4) piece by piece; the printed (3.10) refuted, the chain "
          "on the corrected (3.10′): level set, Barbalat, persistent excitation (3.5) certified, (3.12′), Chetaev")
