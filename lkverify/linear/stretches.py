"""Certified stable and unstable delay intervals: crossing delays enclosed, one proof per interval.

For a retarded system the characteristic roots depend continuously on h > 0 and can enter or
leave the right half-plane only through the imaginary axis, so on an interval of delays at which
no root is on the axis the number of roots with Re s > 0 is constant.  Hence one proof at one
delay h₀ of such an interval decides all of it:

* a root certified in the open right half-plane at h₀ (:func:`~lkverify.linear.instability.refute_stability`)
  makes the whole interval **unstable**;
* an LMI certificate at h₀ (:func:`~lkverify.linear.hierarchy.certify_delay`: no root in the closed
  right half-plane) makes the whole interval **stable**.

The delays with a root on the axis are enclosed rigorously (:func:`crossing_enclosures`): every
crossing frequency ω > 0 is a real root of the exact polynomial P of
:func:`~lkverify.linear.frequency.frequency_polynomial`, isolated by python-flint
(``fmpz_poly.complex_roots``: isolating balls, real roots with an exact zero imaginary part) at
192 bits; at each, the roots z of q(ω, z) are enclosed by arb (``acb_poly.roots``: each
ball holds exactly one root for every ω of the ball); those whose modulus may be 1 give the
delays h = (−arg z + 2πk)/ω as balls (a superset of the crossing delays: a spurious one only
splits an interval); a root s = 0 occurs where det(A + A_d + hD) = 0 (exact real roots).
Between consecutive enclosures no root is on the axis.  The intervals are reported open, their
ends the inner ends of the enclosures (within ~1e-25 of the crossing delays).  Everything
rests on arb enclosures: the status is ``certified``, never ``exact``.

Where the exact analysis does not apply (irrational matrices, a polynomial kernel, no delayed
term, s = 0 a root at every delay) only *points* are certified: the sample delay of each
estimated interval, said so in the detail.

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> half = LinearDelaySystem([[1]], Ad=[["-1/2"]])                 # x′ = x − x(t−h)/2: unstable at every h
>>> [(s.kind, s.lo, s.hi, s.status.value) for s in certify_stretches(half, 5)]
[('unstable', 0.0, 5.0, 'certified')]
"""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import sympy
from flint import acb, acb_poly, arb, ctx, fmpq, fmpz_poly

from ..status import Status
from .hierarchy import certify_delay
from .instability import refute_stability
from .frequency import frequency_polynomial
from .model import LinearDelaySystem
from .spectrum import DEFAULT_NODES, spectral_abscissa
from ..certify.intervals import float_down, float_up, lower_fraction, upper_fraction

__all__ = ["CertifiedStretch", "certify_stretches", "crossing_enclosures"]

#: arb precision (bits) of the crossing enclosures
PRECISION = 192
#: LMI orders tried at the sample delay of an estimated stable interval
ORDERS = (2, 4)


@dataclasses.dataclass(frozen=True)
class CertifiedStretch:
    """Delays (lo, hi) on which the system is proved stable or unstable (or a single sample delay).

    Attributes
    ----------
    kind : str
        ``"stable"``, ``"unstable"`` or ``"undecided"``.
    lo, hi : float
        The open interval (lo rounded up, hi rounded down); lo = hi = the sample for a point.
    point : bool
        Only the sample delay is certified (no crossing enclosures).
    sample : sympy.Rational
        The delay h₀ of the proof.
    status : Status
        ``certified`` for a stable or unstable stretch, ``undecided`` otherwise.
    detail : str

    >>> CertifiedStretch("stable", 0.0, 1.0, False, sympy.Rational(1, 2), Status.CERTIFIED, "").holds
    True
    """

    kind: str
    lo: float
    hi: float
    point: bool
    sample: object
    status: Status
    detail: str

    @property
    def holds(self) -> bool:
        return self.status.is_proof


# ------------------------------------------------------------------ crossing delays, enclosed
def _gaussian_ball(c) -> acb:
    re, im = sympy.re(c), sympy.im(c)
    return acb(arb(fmpq(int(re.p), int(re.q))), arb(fmpq(int(im.p), int(im.q))))


def _z_polynomial(q, z, w, omega: arb) -> acb_poly:
    """q(ω, z) as a polynomial in z with ball coefficients, ω in the ball ``omega``."""
    pz = sympy.Poly(q.as_expr(), z)
    coeffs = []
    for c in reversed(pz.all_coeffs()):                # constant term first
        total = acb(0)
        for (k,), a in sympy.Poly(c, w).terms() if c != 0 else ():
            total += _gaussian_ball(a) * omega ** k
        coeffs.append(total)
    return acb_poly(coeffs)


def _phase(zb: acb) -> arb:
    """arg z as a ball, away from the branch cut (arg(−z) + π when z may sit on the negative real axis)."""
    if zb.real > 0 or zb.imag > 0 or zb.imag < 0:
        return zb.arg()
    return (-zb).arg() + arb.pi()


def _delays(phi: arb, omega: arb, h_max: float) -> list:
    """The balls (−φ + 2πk)/ω, k ≥ 0, that may meet (0, h_max]."""
    out = []
    k_max = math.ceil((Fraction(h_max) * upper_fraction(omega) + upper_fraction(abs(phi)) + 1) / Fraction(6)) + 1
    for k in range(k_max + 1):
        h = (-phi + 2 * arb.pi() * k) / omega
        if h.upper() > 0 and h.lower() <= h_max:
            out.append((lower_fraction(h), upper_fraction(h)))
    return out


def _real_roots(poly: sympy.Poly) -> list:
    """Balls of the real roots of a rational polynomial (python-flint: isolated, real ones with exact zero
    imaginary part), at the current precision; empty for a constant."""
    if poly.degree() <= 0:
        return []
    coeffs = [sympy.Rational(c) for c in poly.all_coeffs()]
    scale = sympy.ilcm(*[c.q for c in coeffs])
    fz = fmpz_poly([int(c * scale) for c in reversed(coeffs)])
    return [r.real for r, _ in fz.complex_roots() if r.imag.is_exact() and r.imag == 0]


def crossing_enclosures(system: LinearDelaySystem, h_max: float):
    """Rational intervals covering every delay h ∈ (0, h_max] with a root on the imaginary axis; or (None, why).

    Returns
    -------
    (list of (Fraction, Fraction), str)
        The enclosures (sorted, overlapping ones merged) and how they were obtained; the list is
        None when the exact analysis does not apply (the string says why).

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> enc, how = crossing_enclosures(LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]]), 10)
    >>> [(round(float(a), 5), float(b - a) < 1e-20) for a, b in enc]
    [(6.17258, True)]
    """
    found = frequency_polynomial(system)
    if found is None:
        return None, ("no exact crossing analysis (irrational matrices, a polynomial kernel, no delayed term or a "
                      "resultant ≡ 0)")
    P, q, (z, w) = found
    while P.degree() > 0 and P.eval(0) == 0:          # ω = 0 is the root s = 0, decided below
        P = sympy.Poly(sympy.quo(P.as_expr(), w), w, domain="QQ")
    hs = sympy.Symbol("h")
    Dm = system.kernel[0] if system.has_distributed else sympy.zeros(system.n, system.n)
    p = sympy.Poly(sympy.expand((system.A + system.Ad + hs * Dm).det()), hs)
    if p.is_zero:
        return None, "s = 0 is a root at every delay (det(A + A_d + hD) ≡ 0)"
    out = []
    with ctx.workprec(PRECISION):
        for omega in _real_roots(P):
            if not omega > 0:                          # ω < 0: the conjugate roots (real matrices)
                if omega < 0:
                    continue
                return None, f"a crossing frequency not separated from 0 ({omega})"
            try:
                zs = _z_polynomial(q, z, w, omega).roots(tol=2.0 ** -100, maxprec=4 * PRECISION)
            except ValueError:
                return None, f"the roots z of q(ω, z) at ω ≈ {float(omega.mid()):.9g} could not be isolated"
            for zb in zs:
                if abs(zb) > 1 or abs(zb) < 1:         # certainly not unimodular: no crossing from this z
                    continue
                out += _delays(_phase(zb), omega, h_max)
        for root in _real_roots(p):                    # s = 0 a root: det(A + A_d + hD) = 0
            if root.upper() > 0 and root.lower() <= h_max:
                out.append((lower_fraction(root), upper_fraction(root)))
    out.sort()
    merged = []
    for lo, hi in out:
        if merged and lo <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(hi, merged[-1][1]))
        else:
            merged.append((lo, hi))
    how = (f"{len(merged)} crossing delay(s) in (0, {h_max:g}] enclosed: frequencies isolated by flint (192 bits), "
           f"the roots z of q(ω, z) in arb, h = (−arg z + 2πk)/ω in arb; s = 0 from det(A + A_d + hD) exactly")
    return merged, how


# ------------------------------------------------------------------ one proof per interval
def _inside(lo: Fraction, hi: Fraction) -> sympy.Rational:
    """A short decimal strictly inside (lo, hi), near the midpoint."""
    mid = (lo + hi) / 2
    for digits in range(1, 40):
        x = Fraction(round(mid * 10 ** digits), 10 ** digits)
        if lo < x < hi and abs(x - mid) <= (hi - lo) / 4:
            return sympy.Rational(x.numerator, x.denominator)
    return sympy.Rational(mid.numerator, mid.denominator)


def _decide(system, h0, orders, nodes):
    """("unstable" | "stable" | "undecided", detail) at the delay h₀ > 0."""
    if spectral_abscissa(system, float(h0), nodes=nodes) > 0:
        inst = refute_stability(system, h0, nodes=nodes)
        return ("unstable", inst.detail) if inst.refuted else ("undecided", inst.detail)
    if not system.constant_kernel:
        return "undecided", "the LMI hierarchy covers constant kernels only: stability not proved"
    last = ""
    for order in orders:
        res = certify_delay(system, h0, order=order)
        if res.holds:
            return "stable", res.detail
        last = res.detail
    return "undecided", f"no LMI order of {list(orders)} verified at h₀ = {h0}: {last}"


def certify_stretches(system: LinearDelaySystem, h_max: float, *, estimated=(), orders=ORDERS,
                      nodes: int = DEFAULT_NODES) -> tuple:
    """The delays of (0, h_max) proved stable or unstable, interval by interval (see the module docstring).

    Parameters
    ----------
    system : LinearDelaySystem
    h_max : float
    estimated : sequence of (float, float)
        The estimated stability intervals (:func:`~lkverify.linear.crossing.stability_intervals`);
        used only to place sample delays when no crossing enclosures exist (points only).
    orders : sequence of int
        LMI orders tried at the sample delay of a stable interval.
    nodes : int

    Returns
    -------
    tuple of CertifiedStretch
        In increasing h.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys_ = LinearDelaySystem(A=[[0]], Ad=[[-1]])          # x' = −x(t − h): stable iff h < π/2
    >>> [s.kind for s in certify_stretches(sys_, 2)]
    ['stable', 'unstable']
    """
    enc, how = crossing_enclosures(system, h_max)
    hm = Fraction(h_max)
    if enc is None:
        return _points(system, hm, estimated, orders, nodes, how)
    cuts = [(Fraction(0), Fraction(0)), *[(max(a, Fraction(0)), b) for a, b in enc if b > 0],
            (hm, hm)]
    out = []
    for (_, lo), (hi, _) in zip(cuts, cuts[1:]):
        lo, hi = max(lo, Fraction(0)), min(hi, hm)
        if not lo < hi:
            continue
        h0 = _inside(lo, hi)
        kind, why = _decide(system, h0, orders, nodes)
        status = Status.CERTIFIED if kind != "undecided" else Status.UNDECIDED
        lo_f, hi_f = float_up(lo), float_down(hi)
        out.append(CertifiedStretch(kind, lo_f, hi_f, False, h0, status,
                                    f"{kind} on the open interval ({lo_f:.10g}, {hi_f:.10g}): no root on the "
                                    f"imaginary axis there ({how}), so the number of right half-plane roots is that "
                                    f"at h₀ = {h0}: {why}"))
    return tuple(out)


def _points(system, hm, estimated, orders, nodes, why_not) -> tuple:
    """Only sample delays: the midpoints of the estimated stable intervals and of the gaps between them."""
    ends = sorted({0.0, float(hm), *[float(x) for iv in estimated for x in iv]})
    out = []
    for lo, hi in zip(ends, ends[1:]):
        if not lo < hi:
            continue
        h0 = _inside(Fraction(lo), Fraction(hi))
        kind, why = _decide(system, h0, orders, nodes)
        status = Status.CERTIFIED if kind != "undecided" else Status.UNDECIDED
        out.append(CertifiedStretch(kind, float(h0), float(h0), True, h0, status,
                                    f"{kind} at the single delay h = {h0} only, not on an interval ({why_not}): {why}"))
    return tuple(out)
