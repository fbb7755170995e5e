"""Instability certified: a characteristic root enclosed in the open right half-plane.

At a delay h the system ẋ = A x + A_d x(t−h) + ∫_{t−h}^t K(t−s) x(s) ds is unstable as soon as
its characteristic function

    f(s) = det Δ(s, h),   Δ(s, h) = sI − A − A_d e^{−sh} − Σ_j D_j I_j(s),   I_j(s) = ∫_0^h u^j e^{−su} du,

has a root with Re s > 0 (x = e^{st}v is then a growing solution).  Such a root is proved by
the complex interval Newton test, in python-flint ``acb`` balls:

1. the float root s₀ of the spectral route (:func:`~lkverify.linear.spectrum.rightmost_roots`) is
   refined by a few Newton steps at midpoints, and a small box S = s₀ ± r(1 + i) is built
   around it;
2. N(S) = s₀ − f(s₀)/F with F ⊇ f′(S), the entries of Δ and ∂Δ/∂s = I + hA_d e^{−sh} +
   Σ_j D_j I_{j+1}(s) evaluated on the ball S (I_0 = (1 − e^{−sh})/s, I_j = (j I_{j−1} −
   h^j e^{−sh})/s), f′ = Σ_k det(Δ with row k replaced by row k of ∂Δ/∂s) (Jacobi's formula);
3. if 0 ∉ F and N(S) lies in the interior of S, S holds exactly one root of f: for s ∈ S,
   f(s) − f(s₀) = c(s)(s − s₀) with c(s) = ∫_0^1 f′(s₀ + t(s − s₀)) dt in the convex box F, so
   s ↦ s₀ − f(s₀)/c(s) maps S into N(S) ⊂ S and its fixed point (Brouwer) is a root; two roots
   s₁ ≠ s₂ would give 0 = c(s₁ − s₂) with c ∈ F ∌ 0;
4. Re S > 0 (its lower end, outward rounded) puts that root in the *open* right half-plane;
5. cross-examination: the certified root must also be a root of the float characteristic matrix
   of :class:`~lkverify.linear.model.LinearDelaySystem` (independent code); if not, the two
   disagree and that is a bug of lkverify (:class:`~lkverify.errors.InternalError`, exit 3).

The data are read exactly: rational entries and delays as their rationals, a float at its exact
binary value (:func:`~lkverify.linear.model.parse_delay`), an irrational entry as arb's
enclosure (:func:`lkverify.certify.intervals.enclose`).  A certified root refutes "stable at
h" (``failed``, the ball is the counterexample); no certified root leaves it ``undecided``
(an LMI of :mod:`.hierarchy` is what proves stability).  A root on the imaginary axis (at
the ends of stability intervals) is never in the open half-plane: its box crosses Re s = 0.

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> classic = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> res = refute_stability(classic, 7)
>>> res.status.value, res.root.in_rhp, 0 < res.root.real[0]
('failed', True, True)
>>> refute_stability(classic, 1).status.value          # stable there: nothing to certify
'undecided'
"""

from __future__ import annotations

import dataclasses

import numpy as np
from flint import acb, acb_mat, arb, ctx

from ..certify.intervals import enclose, float_down, float_up
from ..errors import InternalError
from ..status import Status
from .model import LinearDelaySystem, parse_delay
from .spectrum import DEFAULT_NODES, rightmost_roots

__all__ = ["Instability", "RootBall", "characteristic", "newton_test", "refute_stability"]

#: arb working precisions (bits) tried in turn
PRECISIONS = (128, 256)
#: Newton steps at midpoints that refine the float root before the test
REFINE_STEPS = 8
#: half-widths of the box S tried, relative to max(1, |s₀|) (the smallest that passes is kept)
RELATIVE_RADII = (1e-20, 1e-14, 1e-9, 1e-6)
#: how many estimated roots (Im ≥ 0, rightmost first) are tried
CANDIDATES = 4


@dataclasses.dataclass(frozen=True)
class RootBall:
    """The interval Newton test on one box S = centre ± radius·(1 + i) at the delay h.

    Attributes
    ----------
    h : sympy.Rational
    centre : complex
        s₀ (a float, exact as a ball).
    radius : float
        The half-width of S in the real and the imaginary direction.
    unique : bool
        N(S) ⊂ int S and 0 ∉ F: S holds exactly one characteristic root (proved).
    in_rhp : bool
        ``unique`` and Re S > 0: that root lies in the open right half-plane (proved).
    real, imag : (float, float) or None
        Outward-rounded bounds of the root's real and imaginary parts (from N(S)); None unless ``unique``.
    enclosure : str
        N(S) as arb prints it ("" unless ``unique``).
    prec : int
    detail : str

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> ball = newton_test(LinearDelaySystem([[1]], Ad=[["-1/2"]]), 0, 0.5, 1e-6)    # s = 1 − 1/2
    >>> ball.unique, ball.in_rhp, ball.status.value
    (True, True, 'certified')
    """

    h: object
    centre: complex
    radius: float
    unique: bool
    in_rhp: bool
    real: tuple | None
    imag: tuple | None
    enclosure: str
    prec: int
    detail: str

    @property
    def status(self) -> Status:
        """``certified`` when a unique root is proved in the box, else ``undecided``."""
        return Status.CERTIFIED if self.unique else Status.UNDECIDED

    def to_json(self) -> dict:
        return {"h": str(self.h), "centre": [self.centre.real, self.centre.imag], "radius": self.radius,
                "unique": self.unique, "in_rhp": self.in_rhp, "real": list(self.real) if self.real else None,
                "imag": list(self.imag) if self.imag else None, "enclosure": self.enclosure, "prec": self.prec}


@dataclasses.dataclass(frozen=True)
class Instability:
    """The claim "stable at h" against a certified right half-plane root.

    Attributes
    ----------
    h : sympy.Rational
    status : Status
        ``failed``: a root in the open right half-plane is certified (``root``), the system is
        unstable at h; ``undecided``: none was (stability is not proved either).
    root : RootBall or None
    abscissa : float
        The estimated spectral abscissa at h (floating point).
    detail : str

    >>> Instability(0, Status.UNDECIDED, None, -1.0, "").refuted
    False
    """

    h: object
    status: Status
    root: RootBall | None
    abscissa: float
    detail: str

    @property
    def refuted(self) -> bool:
        """True when the root certifies instability."""
        return self.status is Status.FAILED


# ------------------------------------------------------------------ the characteristic function in balls
def _balls(system: LinearDelaySystem):
    """A, A_d and the D_j as nested lists of arb balls (exact rationals, enclosures otherwise)."""
    def conv(M):
        return [[arb(0) if e == 0 else enclose(e, prec=None) for e in M.row(i)] for i in range(M.rows)]
    D = [conv(K) for K in system.kernel]                  # D_j at index j (a zero D_0 keeps its place)
    return conv(system.A), conv(system.Ad), D if system.has_distributed else []


def _kernel_integrals(s: acb, h: arb, E: acb, count: int) -> list:
    """I_j(s) = ∫_0^h u^j e^{−su} du for j < count (recurrence; not finite when s may be 0)."""
    out = [(1 - E) / s]
    hj = arb(1)
    for j in range(1, count):
        hj = hj * h
        out.append((j * out[-1] - hj * E) / s)
    return out


def characteristic(system: LinearDelaySystem, s: acb, h: arb, balls=None) -> tuple:
    """Balls for f(s) = det Δ(s, h) and f′(s) at every point of the ball ``s`` (current arb precision).

    Examples
    --------
    >>> from flint import acb, arb
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> f, df = characteristic(LinearDelaySystem([[-1]], Ad=[[0]]), acb(2), arb(1))     # f = s + 1
    >>> f.contains(3), df.contains(1)
    (True, True)
    """
    A, Ad, D = balls if balls is not None else _balls(system)
    n = len(A)
    E = (-s * h).exp()
    Ks = _kernel_integrals(s, h, E, len(D) + 1) if D and h != 0 else []
    M = [[(s if i == j else acb(0)) - A[i][j] - Ad[i][j] * E for j in range(n)] for i in range(n)]
    dM = [[(acb(1) if i == j else acb(0)) + h * Ad[i][j] * E for j in range(n)] for i in range(n)]
    for k, Dk in enumerate(D if Ks else ()):
        for i in range(n):
            for j in range(n):
                if Dk[i][j] != 0:
                    M[i][j] -= Dk[i][j] * Ks[k]
                    dM[i][j] += Dk[i][j] * Ks[k + 1]
    f = acb_mat(M).det()
    df = acb(0)
    for k in range(n):      # Jacobi: d det M = Σ_k det(M with row k replaced by row k of M')
        df += acb_mat([dM[i] if i == k else M[i] for i in range(n)]).det()
    return f, df


# ------------------------------------------------------------------ the interval Newton test
def _bounds(x: arb) -> tuple:
    return float_down(x), float_up(x)


def newton_test(system: LinearDelaySystem, h, centre: complex, radius: float, *, prec: int = PRECISIONS[0]) -> RootBall:
    """The interval Newton test on S = centre ± radius·(1 + i): a unique root in S, and is Re S > 0?

    Parameters
    ----------
    system : LinearDelaySystem
    h : number or str
        The delay, read exactly (a float at its binary value).
    centre : complex
        s₀, taken at its exact binary value.
    radius : float
        > 0.
    prec : int
        arb working precision (bits).

    Returns
    -------
    RootBall
        ``unique`` only when N(S) ⊂ int S is proved; nothing is concluded from a box that fails.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys = LinearDelaySystem([[1]], Ad=[["-1/2"]])                # h = 0: f = s − 1/2
    >>> newton_test(sys, 0, 0.7, 1e-3).unique                          # the box misses the root
    False
    """
    hq = parse_delay(h)
    centre = complex(centre)
    with ctx.workprec(prec):
        hb = arb(int(hq.p)) / int(hq.q)
        balls = _balls(system)
        s0 = acb(centre.real, centre.imag)
        r = arb(radius)
        S = acb(arb(centre.real) + arb(0, r), arb(centre.imag) + arb(0, r))
        f0, _ = characteristic(system, s0, hb, balls)
        _, F = characteristic(system, S, hb, balls)
        name = f"the box {centre:.12g} ± {radius:.1e}(1 + i) at h = {hq}"
        if not (F.is_finite() and f0.is_finite()) or F.contains(0):
            return RootBall(hq, centre, radius, False, False, None, None, "", prec,
                            f"{name}: f′ on the box may vanish or is not finite: no conclusion")
        N = s0 - f0 / F
        unique = bool(N.is_finite() and S.contains_interior(N))
        if not unique:
            return RootBall(hq, centre, radius, False, False, None, None, "", prec,
                            f"{name}: N(S) = {N.str(5, radius=True)} is not inside S: no conclusion")
        in_rhp = bool(S.real > 0)
        where = ("Re S > 0: the root lies in the open right half-plane" if in_rhp else
                 "Re S is not > 0: not proved to be in the open right half-plane")
        detail = (f"{name}: N(S) = s₀ − f(s₀)/f′(S) = {N.str(15, radius=True)} ⊂ int S (arb, {prec} bits): exactly "
                  f"one root of det Δ(s, h) in S; {where}")
        return RootBall(hq, centre, radius, True, in_rhp, _bounds(N.real), _bounds(N.imag), N.str(12, radius=True),
                        prec, detail)


def _refine(system, hq, s: complex, prec: int) -> complex:
    """Newton steps on f at midpoints (arb at ``prec`` bits; no claim, only a better centre)."""
    with ctx.workprec(prec):
        hb = arb(int(hq.p)) / int(hq.q)
        balls = _balls(system)
        z = acb(s.real, s.imag)
        for _ in range(REFINE_STEPS):
            f, df = characteristic(system, z, hb, balls)
            if not (f.is_finite() and df.is_finite()) or df.contains(0):
                break
            z = (z - f / df).mid()
        out = complex(float(z.real.mid()), float(z.imag.mid()))
    return out if np.isfinite(out.real) and np.isfinite(out.imag) and abs(out - s) < 0.5 * max(1, abs(s)) else s


def _try_root(system, hq, lam: complex):
    """The first box around ``lam`` (refined) that passes the test, at each precision in turn; or the last failure."""
    last = None
    for prec in PRECISIONS:
        s0 = _refine(system, hq, lam, prec)
        scale = max(1.0, abs(s0))
        for rel in RELATIVE_RADII:
            ball = newton_test(system, hq, s0, rel * scale, prec=prec)
            if ball.unique:
                return ball
            last = ball
    return last


#: σ_min(Δ(s)) / max(1, ‖Δ(s)‖) above which the float route says the certified root is not a root
CROSS_EXAMINATION_TOL = 1e-6


def _cross_examine(system, hq, ball) -> None:
    """The certified root is a root of the float characteristic matrix too (model.py: independent code), or a bug."""
    s = complex(sum(ball.real) / 2, sum(ball.imag) / 2)
    M = system.characteristic_matrix(s, float(hq))
    sv = np.linalg.svd(M, compute_uv=False)
    if not sv[-1] <= CROSS_EXAMINATION_TOL * max(1.0, sv[0]):
        raise InternalError(f"instability: the root certified at h = {hq}, s = {ball.enclosure}, is not a root of the "
                            f"float characteristic matrix (σ_min(Δ) = {sv[-1]:.3g}, ‖Δ‖ = {sv[0]:.3g}): the ball "
                            f"arithmetic and the model disagree")


def refute_stability(system: LinearDelaySystem, h, *, nodes: int = DEFAULT_NODES) -> Instability:
    """"Stable at h" refuted by a characteristic root certified in the open right half-plane, or undecided.

    Parameters
    ----------
    system : LinearDelaySystem
    h : number or str
        The delay ≥ 0, read exactly.
    nodes : int
        Chebyshev degree of the spectral route that proposes the roots.

    Returns
    -------
    Instability
        ``failed`` with the enclosing ball, or ``undecided``.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> res = refute_stability(LinearDelaySystem([[1]], Ad=[["-1/2"]]), 1)    # x′ = x − x(t−1)/2
    >>> res.status.value, round(res.root.real[0], 6)
    ('failed', 0.768039)
    """
    hq = parse_delay(h)
    sp = rightmost_roots(system, float(hq), nodes=nodes)
    lams = [complex(x) for x in sp.roots if x.imag >= -1e-12 * max(1.0, abs(x))]
    lams = [x for x in lams if x.real > -1e-9 * max(1.0, abs(x))][:CANDIDATES]
    tried = []
    for lam in lams:
        ball = _try_root(system, hq, lam)
        if ball is not None and ball.in_rhp:
            _cross_examine(system, hq, ball)
            note = " (the float inputs taken at their exact binary value)" if system.from_float else ""
            return Instability(hq, Status.FAILED, ball, sp.abscissa,
                               f"unstable at h = {hq}{note}: a characteristic root certified in the open right "
                               f"half-plane by the interval Newton test — {ball.detail}")
        if ball is not None:
            tried.append(ball.detail)
    why = ("; ".join(tried[:2]) if tried else
           f"no estimated root with Re s ≥ 0 (estimated spectral abscissa {sp.abscissa:.6g})")
    return Instability(hq, Status.UNDECIDED, None, sp.abscissa,
                       f"no characteristic root certified in the open right half-plane at h = {hq}: {why}")
