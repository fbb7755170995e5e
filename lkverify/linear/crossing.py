"""Delay margins and stability intervals by crossing-frequency analysis.

A root crosses the imaginary axis at λ = iω, ω > 0, for the delay h exactly when
z = e^{−iωh} is a unimodular root of

    q(ω, z) = det( iω(iωI − A − A_d z) − D(1 − z) ) = 0          (constant kernel D),

since ∫_0^h e^{−iωu} du = (1 − z)/(iω).  For real ω and |z| = 1, conj q(ω, z) = q̄(ω, 1/z),
so such an ω is a real root of the resultant Res_z(q, z^{deg} q̄(ω, 1/z)) — an exact
polynomial in ω for rational matrices (SymPy), whose real roots are isolated exactly.
Each crossing frequency gives the delays h = (−arg z + 2πk)/ω; a root at λ = 0 occurs
when det(A + A_d + hD) = 0.  Between consecutive crossing delays the number of roots
in the right half-plane is constant: the spectral abscissa (:mod:`.spectrum`) at the
midpoint decides each interval.  The crossing delays are computed in floating point from
exactly isolated frequencies: the status is ``estimated``.

Polynomial kernels, or irrational matrices, use a grid of the spectral abscissa over h
with bisection at each sign change (``estimated``; the detail says so).

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> res = stability_intervals(sys, h_max=10)
>>> [(round(lo, 5), round(hi, 5)) for lo, hi in res.intervals]
[(0.0, 6.17258)]
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import sympy

from ..errors import InputError, UnsupportedInput
from ..status import Status
from .frequency import frequency_polynomial
from .model import LinearDelaySystem
from .spectrum import rightmost_roots, spectral_abscissa

__all__ = ["Crossing", "StabilityIntervals", "stability_intervals", "crossing_frequencies", "frequency_polynomial"]

#: |z| − 1 accepted for a unimodular root (the frequencies are exact; z is computed in floats)
UNIMODULAR_TOL = 1e-7
#: grid of the fallback scan of the spectral abscissa over (0, h_max]
SCAN_POINTS = 200


@dataclasses.dataclass(frozen=True)
class Crossing:
    """A root on the imaginary axis: λ = iω at the delay h.

    >>> Crossing(6.17258, 0.43589).omega
    0.43589
    """

    h: float
    omega: float


@dataclasses.dataclass(frozen=True)
class StabilityIntervals:
    """The delays in [0, h_max] for which the system is exponentially stable (``estimated``).

    Attributes
    ----------
    intervals : tuple of (float, float)
        Maximal intervals of stability (open at a crossing delay; 0 included when A + A_d is Hurwitz).
    crossings : tuple of Crossing
    h_max : float
    method : str
        ``"crossing"`` (exact resultant) or ``"scan"`` (grid of the spectral abscissa).
    status : Status
        ``estimated`` (of ``intervals`` and ``crossings``).
    detail : str
    certified : tuple of CertifiedStretch
        With ``certify=True``: the delays proved stable *and* those proved unstable, interval by
        interval (:func:`lkverify.linear.stretches.certify_stretches`, ``certified`` each), or
        single sample delays where no crossing enclosures exist (``point``); empty otherwise.

    >>> StabilityIntervals(((0.0, 2.0),), (), 5.0, "crossing", Status.ESTIMATED, "").margin
    2.0
    """

    intervals: tuple
    crossings: tuple
    h_max: float
    method: str
    status: Status
    detail: str
    certified: tuple = ()

    @property
    def margin(self) -> float | None:
        """The delay margin: the end of the interval that starts at 0 (None when h = 0 is unstable)."""
        if self.intervals and self.intervals[0][0] == 0:
            return self.intervals[0][1]
        return None


def crossing_frequencies(system: LinearDelaySystem):
    """The positive real roots ω of the resultant, or None when unsupported (irrational matrices, polynomial kernel).

    Returns ``(frequencies, q, (z, ω))``: the frequencies as floats of exactly isolated roots,
    the characteristic polynomial q(ω, z) and its symbols.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
    >>> [round(w, 6) for w in crossing_frequencies(sys)[0]]
    [0.43589]
    """
    found = frequency_polynomial(system)
    if found is None:
        return None
    P, q, (z, w) = found
    roots = [float(r.evalf(30)) for r in sympy.real_roots(P) if r > 0]
    return sorted(set(roots)), q, (z, w)


def _crossings_from(system, found, h_max):
    freqs, q, (z, w) = found
    out = []
    for om in freqs:
        coeffs = [complex(c) for c in sympy.Poly(q.as_expr().subs(w, om), z).all_coeffs()]
        for zr in np.roots(coeffs):
            if abs(abs(zr) - 1) > UNIMODULAR_TOL:
                continue
            base = (-np.angle(zr)) % (2 * np.pi)
            k = 0
            while (hk := (base + 2 * np.pi * k) / om) <= h_max:
                if hk > 0:
                    out.append(Crossing(float(hk), float(om)))
                k += 1
    # a root at λ = 0: det(A + A_d + hD) = 0 (exact real roots in h)
    hs = sympy.Symbol("h")
    D = system.kernel[0] if system.has_distributed else sympy.zeros(system.n, system.n)
    p = sympy.Poly(sympy.expand((system.A + system.Ad + hs * D).det()), hs)
    if not p.is_zero and p.degree() > 0:
        out += [Crossing(float(r.evalf(30)), 0.0) for r in sympy.real_roots(p) if 0 < r <= h_max]
    return sorted(out, key=lambda c: c.h)


def _scan(system, h_max, nodes):
    grid = np.linspace(0, h_max, SCAN_POINTS + 1)
    ab = [rightmost_roots(system, h, nodes=nodes, count=0).abscissa for h in grid]
    out = []
    for i in range(SCAN_POINTS):
        if (ab[i] < 0) != (ab[i + 1] < 0):
            lo, hi = grid[i], grid[i + 1]
            for _ in range(40):
                mid = (lo + hi) / 2
                if (spectral_abscissa(system, mid, nodes=nodes) < 0) == (ab[i] < 0):
                    lo = mid
                else:
                    hi = mid
            out.append(Crossing(float((lo + hi) / 2), math.nan))
    return out


def stability_intervals(system: LinearDelaySystem, *, h_max: float = 20.0, nodes: int = 40,
                        method: str = "auto", certify: bool = False) -> StabilityIntervals:
    """Maximal delay intervals of exponential stability in [0, h_max] (``estimated``).

    Parameters
    ----------
    system : LinearDelaySystem
    h_max : float
        The largest delay considered.
    nodes : int
        Chebyshev degree of the spectral route that decides each interval.
    method : {"auto", "crossing", "scan"}
        ``auto``: the exact resultant when the matrices are rational and the kernel constant,
        else the scan; ``scan`` forces the reference path (a grid of the spectral abscissa).
    certify : bool
        Also prove stable and unstable intervals (``certified``: crossing delays enclosed in
        arb, one LMI certificate or one right half-plane root per interval; see
        :mod:`lkverify.linear.stretches`).  Costs an SDP solve per stable interval.

    Returns
    -------
    StabilityIntervals

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> gu = LinearDelaySystem([[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]])
    >>> [(round(lo, 7), round(hi, 7)) for lo, hi in stability_intervals(gu, h_max=5).intervals]
    [(0.1001683, 1.7178582)]
    >>> res = stability_intervals(LinearDelaySystem([[1]], Ad=[["-1/2"]]), h_max=5, certify=True)
    >>> res.intervals, [(c.kind, c.lo, c.hi, c.status.value) for c in res.certified]
    ((), [('unstable', 0.0, 5.0, 'certified')])
    """
    if method not in ("auto", "crossing", "scan"):
        raise InputError(f"method: expected 'auto', 'crossing' or 'scan', got {method!r}")
    if not (math.isfinite(h_max) and h_max > 0):
        raise InputError(f"h_max: expected a positive finite delay, got {h_max}")
    found = None if method == "scan" else crossing_frequencies(system)
    if found is None and method == "crossing":
        raise UnsupportedInput("crossing frequencies need rational matrices and a constant kernel; use method='scan'")
    if found is not None:
        crossings, method = _crossings_from(system, found, h_max), "crossing"
    else:
        crossings, method = _scan(system, h_max, nodes), "scan"
    cuts = sorted({0.0, float(h_max), *[c.h for c in crossings]})
    intervals = []
    for lo, hi in zip(cuts, cuts[1:]):
        if spectral_abscissa(system, (lo + hi) / 2, nodes=nodes) < 0:
            if intervals and intervals[-1][1] == lo:
                intervals[-1] = (intervals[-1][0], hi)
            else:
                intervals.append((lo, hi))
    if intervals and intervals[0][0] == 0 and spectral_abscissa(system, 0, nodes=nodes) >= 0:
        intervals[0] = (math.nextafter(0.0, 1.0), intervals[0][1])
    how = ("crossing frequencies ω: real roots of the exact resultant Res_z(q, z^m q̄(ω, 1/z)) of the "
           "characteristic quasi-polynomial with z = e^{−iωh}, isolated exactly; the delays h = (−arg z + 2πk)/ω "
           "in floating point" if method == "crossing" else
           f"a grid of {SCAN_POINTS + 1} delays with bisection of each sign change of the spectral abscissa "
           "(polynomial kernel or irrational matrices: no exact resultant)")
    detail = (f"{how}; each interval between crossing delays decided by the spectral abscissa at its midpoint; "
              f"floating point")
    certified = ()
    if certify:
        from .stretches import certify_stretches

        certified = certify_stretches(system, h_max, estimated=intervals, nodes=nodes)
    return StabilityIntervals(tuple(intervals), tuple(crossings), float(h_max), method, Status.ESTIMATED, detail,
                              certified)
