"""Claims about slow (algebraic) decay: the energy law E' ≈ −k h(t) E^λ judged in tail windows.

With nonlinear damping (paper 001, Theorem 2: torque −h(t) grad W, W homogeneous of order
μ + 1 > 2) the energy does not decay exponentially in ∫h but algebraically: along a run,

    d/dt E^{1−λ} = (λ − 1) k(t) h(t),   i.e.   E(t)^{1−λ} = E(a)^{1−λ} + (λ − 1) ∫_a^t k h,

with λ > 1 (λ = (μ + 1)/2 for the kinetic part of the energy).  Over a window [a, b] the
*measured rate* is

    k_w = (E(b)^{1−λ} − E(a)^{1−λ}) / ((λ − 1) ∫_a^b h),

and the law extrapolates from the end T of the run: E(∞)^{1−λ} = E(T)^{1−λ} + (λ − 1) k ∫_T^∞ h.
Two claims, the two sides of Corollary 2 of paper 001, both judged in windows of the tail of
the run (never on the last sample alone):

* :class:`DecaysAlgebraically` — the energy tends to 0 along the law: the rate is positive in
  every tail window and steady (the slowest window's rate at least ``steady`` times the
  fastest: a trajectory that settles at a positive energy has rates falling to 0), and
  ∫_T^∞ h = ∞ (decided by SymPy), so that the extrapolation with the *slowest* observed rate
  reaches 0.  The time at which that extrapolation reaches ``fraction`` · E(T) is reported.
* :class:`LimitAboveFloor` — bounded, and the energy tends to a positive limit: ∫_T^∞ h < ∞
  and the extrapolation with the *fastest* observed rate (or with a proved bound on the rate,
  ``rate``: E' ≥ −α̃ h E^λ) stays above ``fraction`` · E(T).  It is the algebraic analogue of
  :class:`~lkverify.simulate.experiments.BoundedNotAttractive` (λ = 1 there).

Both are ``simulated`` results (observed along numerical trajectories) or ``failed``.  With
``damping=None`` the claims take h from the run's parameter ``h`` (so ``--set h=…`` is followed).

What a finite run cannot show: the energy is monotone for any h ≥ 0, and over a tail where it
changes by a few per cent (E ~ t^{−1/8}) an energy tending to a small positive level has the
same steady rates.  The verdict rests on the law and on ∫_T^∞ h (exact), as Remark 2's does.

>>> import numpy as np
>>> t = np.linspace(0.0, 10.0, 11); E = 1.0 / (1.0 + 2.0 * t)       # E' = −2E², h ≡ 1, λ = 2
>>> [round(k, 12) for k in window_rates(t, E, lambda a, b: b - a, order=2, tail=0.5, windows=2)[1]]
[2.0, 2.0]
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from ..errors import InputError
from .experiments import RunClaim, _damping_expr, _tail_integral, along
from .solver import Outcome

__all__ = ["DecaysAlgebraically", "LimitAboveFloor", "window_rates"]


def window_rates(t, E, integral: Callable, *, order: float, tail: float, windows: int):
    """Measured rates k_w of the law (E^{1−λ})' = (λ − 1) k h over ``windows`` windows of the last ``tail`` of t.

    Parameters
    ----------
    t, E : arrays
        Sample times and the (positive) energy at them.
    integral : callable
        ``integral(a, b)`` → ∫_a^b h.
    order : float
        λ > 1.
    tail : float
        The fraction of the run the windows cover (0 < tail ≤ 1).
    windows : int

    Returns
    -------
    (edges, rates) : (list of float, list of float)
        The window edges (sample times) and one rate per window (nan where E is not positive).
    """
    t, E = np.asarray(t, dtype=float), np.asarray(E, dtype=float)
    edges = np.linspace(t[-1] - tail * (t[-1] - t[0]), t[-1], int(windows) + 1)
    idx = np.unique(np.searchsorted(t, edges).clip(0, len(t) - 1))
    rates = []
    for i, j in zip(idx[:-1], idx[1:]):
        if E[i] <= 0 or E[j] <= 0 or not (np.isfinite(E[i]) and np.isfinite(E[j])):
            rates.append(float("nan"))
            continue
        H = integral(float(t[i]), float(t[j]))
        rates.append(float((E[j] ** (1 - order) - E[i] ** (1 - order)) / ((order - 1) * H)))
    return [float(t[k]) for k in idx], rates


def _limit(E_T: float, rate: float, tail_integral: float, order: float) -> float:
    """(E(T)^{1−λ} + (λ − 1) k ∫_T^∞ h)^{−1/(λ−1)}: the law's limit from T (0 for an infinite tail)."""
    if not np.isfinite(tail_integral):
        return 0.0 if rate > 0 else float(E_T)
    return float((E_T ** (1 - order) + (order - 1) * max(rate, 0.0) * tail_integral) ** (-1 / (order - 1)))


@dataclasses.dataclass(frozen=True)
class _AlgebraicClaim(RunClaim):
    """Common fields: the run, the energy ``measure(states)``, the damping h(t), the order λ > 1, the tail windows."""

    run: str
    measure: Callable
    damping: object = None  # h as an expression in t (or a string); None: the run's parameter ``h``
    order: float = 2.0
    tail: float = 0.5
    windows: int = 8

    def __post_init__(self):
        problems = []
        if not (float(self.order) > 1):
            problems.append(f"order: expected λ > 1 (the exponent of E' ≈ −k h E^λ), got {self.order!r}; "
                            "for λ = 1 use BoundedNotAttractive / Converges")
        if not (0 < float(self.tail) <= 1):
            problems.append(f"tail: expected 0 < tail ≤ 1, got {self.tail!r}")
        if int(self.windows) < 2:
            problems.append(f"windows: expected at least 2 windows, got {self.windows!r}")
        if problems:
            raise InputError(f"{type(self).__name__}({self.run!r}): " + "; ".join(problems))
        if self.damping is not None:
            _damping_expr(self.damping)  # an expression in t, parsed safely (raises InputError otherwise)

    def _damping(self, tr):
        """h(t): the claim's, or (``damping=None``) the run's resolved parameter ``h`` (so --set h=… is followed)."""
        import sympy

        from ..declare.symbols import t as tsym

        if self.damping is not None:
            return _damping_expr(self.damping)
        if "h" not in tr.values:
            raise InputError(f"{type(self).__name__}({self.run!r}): damping=None takes the run's parameter h, but "
                             f"the run has no h; pass damping='(1+t)**(-1/2)' (an expression in t)")
        h = tr.values["h"]
        return _damping_expr(h(tsym) if isinstance(h, sympy.Lambda) else h)

    def _measure(self, trajectories):
        import scipy.integrate
        import sympy

        from ..declare.symbols import t as tsym

        tr = trajectories[self.run]
        hexpr = self._damping(tr)
        h = sympy.lambdify([tsym], hexpr, modules="numpy")
        E = np.asarray(along(self.measure, tr.states, tr.values), dtype=float)
        edges, rates = window_rates(tr.t, E, lambda a, b: scipy.integrate.quad(h, a, b, limit=200)[0],
                                    order=float(self.order), tail=float(self.tail), windows=int(self.windows))
        i0 = int(np.searchsorted(tr.t, edges[0]))
        slope = (float(np.log(E[-1] / E[i0]) / np.log((1 + tr.t[-1]) / (1 + tr.t[i0])))
                 if E[-1] > 0 and E[i0] > 0 and tr.t[-1] > tr.t[i0] else float("nan"))
        return tr, E, edges, rates, _tail_integral(hexpr, float(tr.t[-1])), slope, hexpr


@dataclasses.dataclass(frozen=True)
class DecaysAlgebraically(_AlgebraicClaim):
    """The energy tends to 0 along E' ≈ −k h E^λ: a steady positive rate in every tail window and ∫_T^∞ h = ∞.

    Parameters
    ----------
    run, measure, damping, order, tail, windows
        See the module docstring; ``measure(states)`` → the energy along the run.
    steady : float
        The slowest window's rate must be at least ``steady`` times the fastest one.
    fraction : float
        The reported extrapolated time is the one at which the law, with the slowest rate,
        brings the energy to ``fraction`` · E(T).

    Examples
    --------
    ``x' = −h x³``: E = x² obeys E' = −2hE² exactly (k = 2, λ = 2); with h = (1+t)^{−1/2} it
    tends to 0, with h = (1+t)^{−2} to a positive limit; ``x' = 0`` does not decay at all.

    >>> import sympy
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> from lkverify.simulate import Run
    >>> x = Vector("x", 1)
    >>> def check(rhs, damping):
    ...     sys = System([Equation(x, [Term(rhs)])], parameters=Parameters())
    ...     ex = Example("demo", runs=[Run("r", sys, history={"x": [1]})], t_end=50, series=[],
    ...                  distance=lambda s: abs(s["x"][:, 0]), samples=501)
    ...     return DecaysAlgebraically("r", lambda s: s["x"][:, 0] ** 2, damping).check(ex, ex.simulate())
    >>> res = check(-(1 + t) ** sympy.Rational(-1, 2) * x(t)[0] ** 3, "(1+t)**(-1/2)")
    >>> res.status.value, [round(k, 3) for k in res.value["rates"][:2]]
    ('simulated', [2.0, 2.0])
    >>> check(-(1 + t) ** -2 * x(t)[0] ** 3, "(1+t)**(-2)").status.value        # ∫h < ∞: a positive limit
    'failed'
    >>> check(0 * x(t)[0], "(1+t)**(-1/2)").detail.split(";")[0]                  # no decay
    'rate k of (E^(1−λ))′ = (λ−1)k·h over 8 windows of t ∈ [25, 50]: 0 … 0 (need > 0, steady within ×0.25)'
    """

    steady: float = 0.25
    fraction: float = 0.5

    @property
    def name(self):
        return f"{self.run}: energy decays to 0 (algebraically, order {float(self.order):g})"

    def check(self, example, trajectories):
        tr, E, edges, rates, tail, slope, hexpr = self._measure(trajectories)
        lo, hi = min(rates), max(rates)
        lam = float(self.order)
        steady = bool(np.all(np.isfinite(rates)) and lo > 0 and lo >= self.steady * hi)
        ok = tr.outcome is Outcome.SUCCESS and steady and not np.isfinite(tail)
        # with the slowest rate: ∫_T^{t*} h = (f^{1−λ} − 1) E(T)^{1−λ} / ((λ−1) k_min)
        need = ((self.fraction ** (1 - lam) - 1) * E[-1] ** (1 - lam) / ((lam - 1) * lo)
                if lo > 0 and E[-1] > 0 else float("inf"))
        t_star = None if np.isfinite(tail) else _time_for_integral(hexpr, float(tr.t[-1]), need)
        value = {"rates": rates, "window_edges": edges, "tail_integral": tail, "energy_end": float(E[-1]),
                 "energy_tail_start": float(E[int(np.searchsorted(tr.t, edges[0]))]), "loglog_slope": slope,
                 "integral_to_fraction": need, "t_fraction": t_star}
        detail = (f"rate k of (E^(1−λ))′ = (λ−1)k·h over {len(rates)} windows of t ∈ [{edges[0]:.4g}, {edges[-1]:.4g}]: "
                  f"{lo:.3g} … {hi:.3g} (need > 0, steady within ×{self.steady:g}); ∫_T^∞ h = {tail:.3g}; energy "
                  f"{value['energy_tail_start']:.3g} → {E[-1]:.3g} (log-log slope {slope:.3g})")
        if t_star is not None:
            detail += f"; the law with k = {lo:.3g} reaches {self.fraction:g}·E(T) at t ≈ {t_star:.3g}"
        return self._res(ok, value, detail)


@dataclasses.dataclass(frozen=True)
class LimitAboveFloor(_AlgebraicClaim):
    """Bounded, and the energy tends to a positive limit: ∫_T^∞ h < ∞ and the law's limit stays above a floor.

    The limit is extrapolated from E(T) with the fastest rate observed in the tail windows,
    or with ``rate`` when given (a proved α̃ with E' ≥ −α̃ h E^λ, which makes the floor follow
    from E(T) alone); it must exceed ``fraction`` · E(T).  The distance stays below ``bound``.

    Examples
    --------
    >>> import sympy
    >>> from lkverify import Parameters, Vector, System, Equation, Term, t
    >>> from lkverify.catalogue.examples import Example
    >>> from lkverify.simulate import Run
    >>> x = Vector("x", 1)
    >>> def check(h, damping, **kw):
    ...     sys = System([Equation(x, [Term(-h * x(t)[0] ** 3)])], parameters=Parameters())
    ...     ex = Example("demo", runs=[Run("r", sys, history={"x": [1]})], t_end=50, series=[],
    ...                  distance=lambda s: abs(s["x"][:, 0]), samples=501)
    ...     return LimitAboveFloor("r", lambda s: s["x"][:, 0] ** 2, damping, bound=2, **kw).check(ex, ex.simulate())
    >>> res = check((1 + t) ** -2, "(1+t)**(-2)")          # 1/E(∞) = 1 + 2·1 = 3
    >>> res.status.value, round(res.value["energy_limit_lower"], 4)
    ('simulated', 0.3333)
    >>> check((1 + t) ** sympy.Rational(-1, 2), "(1+t)**(-1/2)").status.value
    'failed'
    """

    bound: float = float("inf")
    fraction: float = 1e-3
    rate: float | None = None

    @property
    def name(self):
        return f"{self.run}: bounded, energy tends to a positive limit"

    def check(self, example, trajectories):
        tr, E, edges, rates, tail, slope, _ = self._measure(trajectories)
        d = np.asarray(along(example.distance, tr.states, tr.values), dtype=float)
        k = float(self.rate) if self.rate is not None else max(0.0, float(np.nanmax(rates)))
        lower = _limit(float(E[-1]), k, tail, float(self.order))
        ok = (tr.outcome is Outcome.SUCCESS and float(np.max(d)) <= self.bound and np.isfinite(tail)
              and lower > self.fraction * E[-1])
        which = "proved rate α̃" if self.rate is not None else "fastest measured rate"
        return self._res(ok, {"rates": rates, "window_edges": edges, "rate_used": k, "tail_integral": tail,
                              "energy_end": float(E[-1]), "energy_limit_lower": lower, "loglog_slope": slope,
                              "max_distance": float(np.max(d))},
                         f"max distance {np.max(d):.3g} (bound {self.bound:g}); rate k over {len(rates)} tail windows "
                         f"{min(rates):.3g} … {max(rates):.3g}, {which} {k:.3g}; ∫_T^∞ h = {tail:.3g}; energy "
                         f"{E[-1]:.3g} at T, limit ≥ {lower:.3g} (extrapolated, need > {self.fraction:g}·E(T))")


def _time_for_integral(damping, T: float, need: float) -> float | None:
    """The t with ∫_T^t h = need (h > 0), over doubling intervals [T_k, 2T_k + 1] then bisection; None if not found."""
    import scipy.integrate
    import scipy.optimize
    import sympy

    from ..declare.symbols import t as tsym

    if not np.isfinite(need):
        return None
    h = sympy.lambdify([tsym], _damping_expr(damping), modules="numpy")
    a, acc = T, 0.0
    while a < 1e300:
        b = 2 * a + 1
        piece = scipy.integrate.quad(h, a, b, limit=200)[0]
        if acc + piece >= need:
            return float(scipy.optimize.brentq(lambda s: acc + scipy.integrate.quad(h, a, s, limit=200)[0] - need,
                                               a, b, rtol=1e-6))
        a, acc = b, acc + piece
    return None
