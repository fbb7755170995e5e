"""Persistent excitation certified: β1 I ≤ ∫_t^{t+δ} φᵀφ ≤ β2 I for every t ≥ 0, φ̇ = −λφ + Yᵀ(t), φ(0) = 0.

When the regressor Y(t) is a trigonometric polynomial (sums and products of sin and cos of rational
multiples of t with rational coefficients, e.g. Y along a programmed motion ω_d(t) of that kind), the
filter's output and the Gram matrix of every window are exponential polynomials, obtained exactly:

* Y(t) = Σ_k A_k e^{ν_k t} (ν_k imaginary rationals, A_k complex rational matrices: sympy's rewrite
  of sin, cos as exponentials);
* φ(t) = Σ_k A_kᵀ (e^{ν_k t} − e^{−λt})/(λ + ν_k), the exact solution of the filter from φ(0) = 0;
* G(t) = ∫_t^{t+δ} φᵀφ = Σ_κ C_κ (e^{κ(t+δ)} − e^{κt})/κ (δ·C_0 for κ = 0), κ = μ + μ' over pairs of
  exponents of φ, C_κ = Σ B_μᵀB_μ' exact.

G splits into a periodic part G_p (Re κ = 0, period 2π/g, g the gcd of the frequencies) and a
decaying part G_d (Re κ < 0) with the explicit bound ‖G_d(t)‖_F ≤ d(t) = Σ‖C_κ‖_F e^{Re κ t}|e^{κδ} − 1|/|κ|.
The bounds are certified by subdivision with arb balls (python-flint): at each midpoint m the
eigenvalue bounds of G(m) are proved by an LDLᵀ of G(m) − bI (or of bI − G(m)) in ball arithmetic,
and on [m − h, m + h] Weyl's inequality with the certified Lipschitz bound L = Σ‖C_κ‖_F sup|d/dt f_κ|
moves them by at most hL.  On [0, T0] the whole G is covered, for t ≥ T0 one period of G_p with d(T0)
subtracted.  A claimed β1 (β2) that is too large (small) is refuted at an exact rational t0 and an
exact rational vector u: uᵀG(t0)u − β‖u‖² < 0 (> 0) in ball arithmetic.

Examples
--------
Y = (cos t, sin t)ᵀ (2 × 1: φ is 1 × 2, φᵀφ is 2 × 2 of rank 1 at each t) excites both directions over
a window; a constant one does not:

>>> import sympy
>>> t = sympy.Symbol("t", real=True)
>>> pe = excitation_bounds(sympy.Matrix([sympy.cos(t), sympy.sin(t)]), t, lam=1, delta=2 * sympy.pi)
>>> pe.status.value, 0.5 < pe.beta1 <= pe.beta1_estimate <= pe.beta2_estimate <= pe.beta2 < 4
('certified', True)
>>> excitation_bounds(sympy.Matrix([1, 0]), t, lam=1, delta=2).status.value
'failed'
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np
import sympy

from ..errors import UnsupportedInput
from ..status import Status

__all__ = ["ExcitationBounds", "excitation_bounds", "filter_gram", "refute_claim"]

#: at most this many certified sub-intervals (a deterministic work limit)
MAX_INTERVALS = 40000


def _exponential_terms(expr, t) -> dict:
    """{ν: c}: ``expr`` = Σ c e^{νt} with ν, c complex rationals (sin, cos rewritten); else UnsupportedInput."""
    e = sympy.expand(sympy.powsimp(sympy.expand(sympy.sympify(expr).rewrite(sympy.exp))))
    out: dict = {}
    for term in sympy.Add.make_args(e):
        if term == 0:
            continue
        c, rest = term.as_independent(t, as_Add=False)
        rest = sympy.powsimp(rest)
        if rest == 1:
            nu = sympy.Integer(0)
        elif isinstance(rest, sympy.exp):
            nu = sympy.expand(rest.args[0] / t)
        else:
            raise UnsupportedInput(f"excitation: the regressor must be a trigonometric polynomial in t, got the "
                                   f"term {term}")
        if nu.free_symbols or c.free_symbols:
            raise UnsupportedInput(f"excitation: the regressor must be a trigonometric polynomial in t with "
                                   f"rational frequencies, got the term {term}")
        for x in (nu, c):
            re, im = x.as_real_imag()
            if not (re.is_Rational and im.is_Rational):
                raise UnsupportedInput(f"excitation: expected rational coefficients and frequencies, got {x}")
        out[nu] = out.get(nu, 0) + c
    return {k: v for k, v in out.items() if v != 0}


def filter_gram(Y, t, lam, *, transpose: bool = False) -> dict:
    """{κ: C_κ}: the Gram integrand φᵀφ = Σ C_κ e^{κt} (φφᵀ with ``transpose``) of φ̇ = −λφ + Yᵀ, φ(0) = 0.

    ``Y`` (p × q, a trigonometric polynomial in t; φ is q × p), ``lam`` > 0 rational; C_κ are exact
    complex rational p × p (q × q with ``transpose``) matrices.

    >>> t = sympy.Symbol("t", real=True)
    >>> sorted(filter_gram(sympy.Matrix([[1]]), t, 1).items())   # φ = 1 − e^{−t}: φ² = e^{−2t} − 2e^{−t} + 1
    [(-2, Matrix([[1]])), (-1, Matrix([[-2]])), (0, Matrix([[1]]))]
    """
    lam = sympy.Rational(lam)
    if lam <= 0:
        raise UnsupportedInput(f"excitation: expected λ > 0, got {lam}")
    Y = sympy.Matrix(Y)
    p, q = Y.shape
    terms: dict = {}
    for i in range(p):
        for j in range(q):
            for nu, c in _exponential_terms(Y[i, j], t).items():
                terms.setdefault(nu, sympy.zeros(q, p))[j, i] += c            # Yᵀ
    phi: dict = {}
    for nu, A in terms.items():
        k = 1 / (lam + nu)
        phi[nu] = phi.get(nu, sympy.zeros(q, p)) + A * k
        phi[-lam] = phi.get(-lam, sympy.zeros(q, p)) - A * k
    gram: dict = {}
    for mu, B in phi.items():
        for mu2, B2 in phi.items():
            prod = (B * B2.T) if transpose else (B.T * B2)
            kappa = sympy.expand(mu + mu2)
            gram[kappa] = gram.get(kappa, sympy.zeros(*prod.shape)) + prod
    return {k: v.applyfunc(sympy.expand) for k, v in gram.items() if any(x != 0 for x in v)}


class _Gram:
    """G(t) = Σ C_κ f_κ(t), f_κ(t) = (e^{κ(t+δ)} − e^{κt})/κ, evaluated in floats and in arb balls."""

    def __init__(self, integrand: Mapping, delta):
        from flint import acb, arb
        self.delta = sympy.sympify(delta)
        self.terms = []
        for kappa, C in integrand.items():
            re, im = (sympy.Rational(x) for x in kappa.as_real_imag())
            if re > 0:
                raise UnsupportedInput(f"excitation: a growing term e^({kappa}t) in the Gram integrand")
            k_ball = acb(arb(re.p) / re.q, arb(im.p) / im.q)
            Cb = [[self._acb(C[i, j]) for j in range(C.shape[1])] for i in range(C.shape[0])]
            Cf = np.array([[complex(C[i, j]) for j in range(C.shape[1])] for i in range(C.shape[0])])
            self.terms.append((re, im, k_ball, Cb, Cf))
        self.n = next(iter(integrand.values())).shape[0] if integrand else 0
        d = self._delta_ball()
        self.factors = []  # (e^{κδ} − 1)/κ and e^{κδ} − 1 as balls
        # ‖C_κ‖_F and Re κ as balls, once: the Lipschitz and decay bounds are taken on every sub-interval
        self.norms = [sum((abs(x) ** 2 for row in Cb for x in row), arb(0)).sqrt() for _, _, _, Cb, _ in self.terms]
        self.rates = [arb(re.p) / re.q for re, *_ in self.terms]
        for re, im, k, _, _ in self.terms:
            if re == 0 and im == 0:
                self.factors.append((acb(d), acb(0)))
            else:
                ekd = (k * d).exp()
                self.factors.append(((ekd - 1) / k, ekd - 1))

    @staticmethod
    def _acb(x):
        from flint import acb, arb

        re, im = (sympy.Rational(v) for v in sympy.sympify(x).as_real_imag())
        return acb(arb(re.p) / re.q, arb(im.p) / im.q)

    def _delta_ball(self):
        from ..certify.intervals import enclose

        return enclose(self.delta)

    def floats(self, ts, periodic_only=False):
        """G at the float times ``ts`` (shape (len, n, n)), for the search only (never certified)."""
        ts = np.asarray(ts, float)
        dl = float(self.delta)
        G = np.zeros((ts.size, self.n, self.n), complex)
        for re, im, _, _, Cf in self.terms:
            if periodic_only and re != 0:
                continue
            k = complex(float(re), float(im))
            f = np.full(ts.shape, dl, complex) if k == 0 else (np.exp(k * (ts + dl)) - np.exp(k * ts)) / k
            G += f[:, None, None] * Cf[None, :, :]
        return G.real

    def ball(self, tb, periodic_only=False):
        """The n × n matrix of arb balls containing G(t) for every t in the ball ``tb``."""
        from flint import acb, arb

        G = [[acb(0) for _ in range(self.n)] for _ in range(self.n)]
        for (re, im, k, Cb, _), (fac, _) in zip(self.terms, self.factors):
            if periodic_only and re != 0:
                continue
            f = fac * (k * acb(tb)).exp() if not (re == 0 and im == 0) else fac
            for i in range(self.n):
                for j in range(self.n):
                    G[i][j] += Cb[i][j] * f
        return [[arb(G[i][j].real) for j in range(self.n)] for i in range(self.n)]

    def lipschitz(self, a, periodic_only=False):
        """An arb upper bound of sup_{t ≥ a} ‖G'(t)‖_F (or of G_p')."""
        from flint import arb

        total = arb(0)
        for (re, *_), (_, em1), norm, rate in zip(self.terms, self.factors, self.norms, self.rates):
            if periodic_only and re != 0:
                continue
            total += norm * abs(em1) * (rate * a).exp()
        return total

    def decay(self, a):
        """d(a): an arb upper bound of sup_{t ≥ a} ‖G_d(t)‖_F."""
        from flint import arb

        total = arb(0)
        for (re, *_), (fac, _), norm, rate in zip(self.terms, self.factors, self.norms, self.rates):
            if re != 0:
                total += norm * abs(fac) * (rate * a).exp()
        return total

    def period(self):
        """The period of G_p (2π/g), or None when G_p is constant."""
        freqs = [abs(sympy.Rational(im)) for re, im, *_ in self.terms if re == 0 and im != 0]
        if not freqs:
            return None
        g = freqs[0]
        for f in freqs[1:]:
            g = sympy.Rational(math.gcd(g.p * f.q, f.p * g.q), g.q * f.q)
        return 2 * sympy.pi / g


def _pd_after_shift(S, b, sign):
    """Whether sign·(S − bI) ≻ 0 is proved by an LDLᵀ in arb balls (every pivot's ball > 0)."""
    n = len(S)
    A = [[(S[i][j] - (b if i == j else 0)) * sign for j in range(n)] for i in range(n)]
    for k in range(n):
        piv = A[k][k]
        if not piv > 0:
            return False
        for i in range(k + 1, n):
            f = A[i][k] / piv
            for j in range(k + 1, n):
                A[i][j] = A[i][j] - f * A[k][j]
    return True


def _bounds_at(S, lower=True):
    """A certified lower bound of λ_min (upper bound of λ_max) of the ball matrix S, or None."""
    from flint import arb

    mid = np.array([[float(x.mid()) for x in row] for row in S])
    ev = np.linalg.eigvalsh((mid + mid.T) / 2)
    target = ev[0] if lower else ev[-1]
    for slack in (1e-12, 1e-9, 1e-6, 1e-3):
        b = target - slack * max(1.0, abs(target)) if lower else target + slack * max(1.0, abs(target))
        if _pd_after_shift(S, arb(b), 1 if lower else -1):
            return b
    return None


@dataclasses.dataclass(frozen=True)
class ExcitationBounds:
    """Certified (or refuted) persistent-excitation constants: β1 ≤ λ_min(G(t)), λ_max(G(t)) ≤ β2, t ≥ 0."""

    status: Status
    beta1: float | None
    beta2: float | None
    beta1_estimate: float
    beta2_estimate: float
    detail: str
    intervals: int = 0


def excitation_bounds(Y, t, *, lam, delta, transpose: bool = False, horizon=None, loss: float = 0.1,
                      max_intervals: int = MAX_INTERVALS) -> ExcitationBounds:
    """β1, β2 of (3.5) for φ̇ = −λφ + Yᵀ(t), φ(0) = 0, certified for every t ≥ 0 (see the module).

    ``loss``: the certified β1 may be this fraction below the sampled minimum (it sets the step of
    the subdivision); ``horizon`` T0 (default: where the decaying part is below loss·β̂1/4).
    Status ``certified``, ``failed`` (λ_min(G(t0)) ≤ 0 at an exact point: no excitation) or
    ``undecided`` (the work limit).
    """
    from flint import arb

    from .intervals import float_down, float_up

    integrand = filter_gram(Y, t, lam, transpose=transpose)
    if not integrand:
        return ExcitationBounds(Status.FAILED, None, None, 0.0, 0.0, "Y = 0: φ = 0, no excitation (exact)")
    n = next(iter(integrand.values())).shape[0]
    dead = [i for i in range(n) if all(C[i, j] == 0 for C in integrand.values() for j in range(n))]
    if dead:
        return ExcitationBounds(Status.FAILED, None, None, 0.0, 0.0,
                                f"the Gram integrand is exactly 0 in the direction e{dead[0] + 1}: (e{dead[0] + 1})ᵀ"
                                f"∫φᵀφ e{dead[0] + 1} = 0 on every window, no persistent excitation (exact)")
    gram = _Gram(integrand, delta)
    P = gram.period()
    Pf = float(P) if P is not None else 1.0
    sample_to = 10.0 / float(lam) + 2 * Pf
    ts = np.linspace(0.0, sample_to, 4001)
    ev = np.linalg.eigvalsh(gram.floats(ts))
    b1_hat, b2_hat = float(ev[:, 0].min()), float(ev[:, -1].max())
    if b1_hat <= 1e-12 * max(b2_hat, 1e-300):
        k = int(np.argmin(ev[:, 0]))
        t0 = sympy.Rational(ts[k]).limit_denominator(10 ** 6)
        ref = refute_claim(gram, t0, 0, lower=True, strict=False)   # λ_min(G(t0)) ≤ 0 proved: no β1 > 0
        if ref:
            return ExcitationBounds(Status.FAILED, None, None, b1_hat, b2_hat,
                                    f"λ_min(G(t0)) ≤ 0 at t0 = {t0}: no persistent excitation ({ref})")
        return ExcitationBounds(Status.UNDECIDED, None, None, b1_hat, b2_hat,
                                f"λ_min(G) ≈ {b1_hat:.3g} at t ≈ {float(t0):.4g} (floating point): no excitation "
                                f"seen, and none certified either way")
    margin = loss * b1_hat
    T0 = horizon
    if T0 is None:
        T0 = 0.0
        while float_up(gram.decay(arb(T0))) > margin / 4:
            T0 += Pf / 4 if P is not None else 1.0
            if T0 > 1e6:
                return ExcitationBounds(Status.UNDECIDED, None, None, b1_hat, b2_hat, "the transient does not decay")
    dT0 = gram.decay(arb(T0))
    lo, hi, count = math.inf, -math.inf, 0
    for a, b, periodic in ((0.0, T0, False), (0.0, Pf, True)):
        if b <= a:
            continue
        L = float_up(gram.lipschitz(arb(a), periodic_only=periodic))
        h = margin / (2 * max(L, 1e-300))
        n = max(1, int(math.ceil((b - a) / (2 * h))))
        if count + n > max_intervals:
            return ExcitationBounds(Status.UNDECIDED, None, None, b1_hat, b2_hat,
                                    f"the subdivision needs {count + n} intervals, above the work limit {max_intervals}")
        width = (b - a) / n
        for k in range(n):
            m = arb(a + (k + 0.5) * width)
            S = gram.ball(m, periodic_only=periodic)
            l, u = _bounds_at(S, True), _bounds_at(S, False)
            if l is None or u is None:
                return ExcitationBounds(Status.UNDECIDED, None, None, b1_hat, b2_hat,
                                        f"the eigenvalue bounds at t = {a + (k + 0.5) * width:.4g} were not certified")
            # half the width, inflated past the float spacing of the midpoints and ends (no gap between pieces)
            half = arb(width / 2) * (1 + arb(2) ** -30) + arb(2) ** -40
            move = gram.lipschitz(arb(a + k * width), periodic_only=periodic) * half
            extra = dT0 if periodic else arb(0)
            lo, hi = min(lo, float_down(arb(l) - move - extra)), max(hi, float_up(arb(u) + move + extra))
        count += n
    if lo <= 0:
        return ExcitationBounds(Status.UNDECIDED, None, hi, b1_hat, b2_hat,
                                f"the certified lower bound is not positive ({lo:.3g}): refine with a smaller loss")
    return ExcitationBounds(Status.CERTIFIED, float(lo), float(hi), b1_hat, b2_hat,
                            f"β1 = {lo:.4g} ≤ λ_min(∫_t^(t+δ) G) and λ_max ≤ β2 = {hi:.4g} for every t ≥ 0 "
                            f"(certified: exact filter response, {count} sub-intervals of [0, {T0:.4g}] and of one "
                            f"period {Pf:.4g} of the periodic part, arb balls, Weyl's inequality; the transient "
                            f"beyond T0 below {float_up(dT0):.2g}); sampled β1 ≈ {b1_hat:.4g}, β2 ≈ {b2_hat:.4g}",
                            count)


def refute_claim(gram, t0, beta, *, lower: bool = True, strict: bool = True):
    """A refutation of β ≤ λ_min(G(t0)) (``lower``) or λ_max(G(t0)) ≤ β at the exact rational t0, or None.

    ``gram``: a :class:`_Gram` or an :class:`~sympy.Matrix`-free exact description returned by
    :func:`filter_gram` with its δ as ``(integrand, delta)``.  The witness u (rational) has
    uᵀG(t0)u − β‖u‖² < 0 (lower) or > 0 in arb balls; ``strict=False`` accepts ≤ 0.
    """
    from flint import arb

    if isinstance(gram, tuple):
        gram = _Gram(*gram)
    t0 = sympy.Rational(t0)
    S = gram.ball(arb(t0.p) / t0.q)
    mid = np.array([[float(x.mid()) for x in row] for row in S])
    w, V = np.linalg.eigh((mid + mid.T) / 2)
    u = V[:, 0] if lower else V[:, -1]
    uq = [sympy.Rational(x).limit_denominator(10 ** 8) for x in u]
    ub = [arb(x.p) / x.q for x in uq]
    quad = sum((ub[i] * S[i][j] * ub[j] for i in range(gram.n) for j in range(gram.n)), arb(0))
    b = sympy.Rational(beta)
    val = quad - arb(b.p) / b.q * sum((x * x for x in ub), arb(0))
    ok = (val < 0 if strict else val <= 0) if lower else val > 0
    if not ok:
        return None
    return (f"at t0 = {t0}, u = ({', '.join(map(str, uq))}): uᵀG(t0)u − β‖u‖² ∈ {val.str(5, radius=True)} "
            f"{'<' if lower else '>'} 0 (arb)")
