"""A linearisation kept symbolic in the swept names, evaluated at many grid points without SymPy.

``lkverify sweep`` needs, at each point of a gain grid, the linear margin: is the
linearisation at the equilibrium exponentially stable there?  :func:`linearise` per point
costs SymPy time (0.7–0.9 s for paper 002's system); :func:`linear_family` linearises once,
with the grid names kept as symbols (the same code path as :func:`linearise`, in
:mod:`lkverify.linear.linearise`), and turns A, A_d, D and the delay h into one generated
function of the grid values.  :meth:`LinearFamily.evaluate`
then costs only floating-point arithmetic per point:

1. the matrices at the point (the generated function, no SymPy);
2. the pseudospectral discretisation of the generator with Chebyshev degree
   :data:`NODES` and its eigenvalues, the :data:`REFINE` rightmost refined by Newton on
   the characteristic equation (:func:`lkverify.linear.spectrum.rightmost_roots`, the
   same routine the exact path uses); a point whose rightmost root did not converge
   (σ_min(Δ(λ)) > 1e-8·max(1, |λ|)) is recomputed with 2·:data:`NODES`;
3. the verdict from the spectral abscissa α: ``"stable"`` (α < −tol), ``"unstable"``
   (α > tol), ``"critical"`` (|α| ≤ tol: the linearisation decides nothing), with
   tol = :data:`TOL`·max(1, |λ_rightmost|); ``"undefined"`` where the matrices are not
   finite or the delay is negative (no spectrum).

When λ = 0 is a root at every grid point — det(A + A_d + h D) ≡ 0 in the grid symbols,
decided exactly at construction (``structural_zero``), e.g. paper 002 at μ = 2 where the
torque has no restoring stiffness — the abscissa is ≥ 0 everywhere: it is reported as
max(α, 0) and the verdict is never ``"stable"``.

Measured (``python benchmarks/bench_linear_family.py``, 2 shared cores; paper 002 as
aleksandrov2023.fig1, a = 2, μ = 1, F = h·I on the sweep's grid b ∈ [−3, 3] × h ∈ [0.1, 2],
61 × 40 points):

* cost: the family is built in 0.8 s (one exact :func:`linearise` costs 0.9 s, so 2440 of
  them ~37 min); :meth:`~LinearFamily.evaluate` costs 4.0 ms per point (3.5 ms CPU; Newton
  dominates, the 65 × 65 eigenvalue problem at N = 12 takes ~1.5 ms);
* accuracy, on every 10th grid point at τ = 0.9, 3 and 6, against Chebyshev degree 40: the
  refined abscissa agrees to ≤ 5e-12 for every degree N ∈ {6, 8, 12, 24}, the unrefined
  discretised one at N = 12 to ≤ 3e-12; no verdict differs; the smallest |α| on the grid is
  9e-4;
* structural zeros with the exact flag switched off: paper 002 at μ = 2 gives α = 0 exactly
  (also for an irrational r in orthonormal coordinates), a defective double zero (a rotated
  Jordan block of size c) splits to |α| = 1.2e-8 at c = 3 (√ε·c).

Hence NODES = 12 (twice the degree that already suffices at τ = 6) and TOL = 1e-6: two
orders above the splitting of a defective double zero, five above the refined accuracy,
and — for a boundary crossed at a slope of order one — a critical band ~1e-6 wide, far
below any grid spacing.  All of it is floating point: the status is ``estimated``.

Examples
--------
>>> import numpy as np, sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, t
>>> P = Parameters(); a = P.scalar("a", default=1); tau = P.delay("tau", default=1)
>>> x = Vector("x", 1)
>>> sys = System([Equation(x, [Term(-a * x(t - tau)[0])])], parameters=P, name="toy")
>>> fam = linear_family(sys, {"x": [0]}, grid=("a", "tau"))         # x' = −a x(t − τ): stable iff aτ < π/2
>>> fam.A, fam.Ad, fam.delay
(Matrix([[0]]), Matrix([[-a]]), tau)
>>> batch = fam.evaluate([[1.0, 1.5], [1.0, 1.6], [0.0, 1.0]])
>>> batch.verdict
('stable', 'unstable', 'critical')
>>> batch.status.value, bool(abs(batch.abscissa[2]) < 1e-12)
('estimated', True)
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping, Sequence

import numpy as np
import sympy

from ..errors import InputError
from ..status import Status
from .linearise import COORDINATES, _linear_parts
from .model import LinearDelaySystem, has_float
from .spectrum import rightmost_roots

__all__ = ["LinearBatch", "LinearFamily", "linear_family", "NODES", "REFINE", "TOL", "VERDICTS"]

#: Chebyshev degree of the discretisation per point (2·NODES when the rightmost root does not converge)
NODES = 12
#: how many rightmost discretised eigenvalues are refined by Newton (conjugates count twice)
REFINE = 4
#: |abscissa| ≤ TOL·max(1, |λ|): "critical" (see the module docstring for the measurement behind it)
TOL = 1e-6
#: σ_min(Δ(λ)) ≤ CONVERGED·max(1, |λ|): the rightmost root converged under Newton
CONVERGED = 1e-8
#: the verdicts of a point
VERDICTS = ("stable", "unstable", "critical", "undefined")


@dataclasses.dataclass(frozen=True, eq=False)
class LinearBatch:
    """The linearisation's spectral verdict at each of N grid points (``estimated``).

    Attributes
    ----------
    names : tuple of str
        The grid names, the columns of ``points``.
    points : ndarray, shape (N, len(names))
    abscissa : ndarray, shape (N,)
        max Re λ over the characteristic roots (NaN where ``undefined``).
    verdict : tuple of str
        ``"stable"``, ``"unstable"``, ``"critical"`` or ``"undefined"`` per point.
    rightmost : ndarray of complex, shape (N,)
        The rightmost root found.
    residual : ndarray, shape (N,)
        σ_min(Δ(λ)) at the rightmost root (its distance from solving the characteristic equation).
    converged : ndarray of bool, shape (N,)
        The rightmost root passed the residual test (after the retry at twice the degree).
    delay : ndarray, shape (N,)
        The delay h at each point (0 for an ODE).
    nodes : ndarray of int, shape (N,)
        The Chebyshev degree used (0: h = 0, the eigenvalues of A + A_d, or ``undefined``).
    tol : float
    status : Status
        ``estimated`` (floating point).
    detail : str
    seconds : float
        Wall time of the evaluation.

    Examples
    --------
    >>> b = LinearBatch(("k",), np.zeros((1, 1)), np.array([-1.0]), ("stable",), np.array([-1 + 0j]),
    ...                 np.zeros(1), np.ones(1, bool), np.ones(1), np.array([12]), TOL, Status.ESTIMATED, "", 0.0)
    >>> b.counts()
    {'stable': 1, 'unstable': 0, 'critical': 0, 'undefined': 0}
    """

    names: tuple
    points: np.ndarray
    abscissa: np.ndarray
    verdict: tuple
    rightmost: np.ndarray
    residual: np.ndarray
    converged: np.ndarray
    delay: np.ndarray
    nodes: np.ndarray
    tol: float
    status: Status
    detail: str
    seconds: float

    def counts(self) -> dict:
        """How many points have each verdict."""
        return {v: sum(1 for x in self.verdict if x == v) for v in VERDICTS}


class _PointSystem:
    """The float matrices of one grid point, with :class:`LinearDelaySystem`'s characteristic matrix.

    It offers what :func:`rightmost_roots` and :func:`generator_matrix` read (``n``, ``floats_cached``,
    the characteristic matrix and its derivative), without building SymPy matrices per point.
    """

    __slots__ = ("n", "constant_kernel", "_floats")

    kernel_transform = LinearDelaySystem.kernel_transform
    characteristic_matrix = LinearDelaySystem.characteristic_matrix
    characteristic_derivative = LinearDelaySystem.characteristic_derivative

    def __init__(self, A, Ad, D):
        self.n = A.shape[0]
        self.constant_kernel = True
        self._floats = (A, Ad, [D] if D is not None else [])

    def floats_cached(self):
        return self._floats


@dataclasses.dataclass(frozen=True, repr=False)
class LinearFamily:
    """ẋ = A(p) x + A_d(p) x(t − h(p)) + ∫_{t−h(p)}^t D(p) x, exact in the grid values p (SymPy).

    Built by :func:`linear_family`; plain pickle carries it (SymPy data only: the numerical
    function is generated on first use in each process).

    Attributes
    ----------
    name : str
    grid : tuple of str
        The grid names, in the column order of :meth:`evaluate`'s points.
    symbols : tuple of sympy.Symbol
        Their symbols in ``A``, ``Ad``, ``D``, ``delay``.
    A, Ad, D : sympy.ImmutableMatrix
        In the reduced (tangent) coordinates; ``D`` the constant kernel of the window integrals
        (zero without them).
    delay : SymPy expression or None
        h (None: an ODE).
    labels : tuple of str
        The coordinates ξ (as :class:`~lkverify.linear.linearise.Linearisation` names them).
    limits : tuple of str
        Jacobian entries taken as limits (see :func:`~lkverify.linear.linearise.linearise_at`).
    structural_zero : bool
        det(A + A_d + h D) ≡ 0: λ = 0 is a root at every point (exact).
    nodes, refine : int
        Chebyshev degree and the number of refined roots per point.
    tol : float
        The critical band (relative to max(1, |λ|)).
    from_float : bool
        Some value given to :func:`linear_family` was a float: every system :meth:`at` builds is
        then at most ``certified`` (:mod:`lkverify.status`).

    Examples
    --------
    >>> import pickle
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", default=1); tau = P.delay("tau", default=1); x = Vector("x", 2)
    >>> sys = System([Equation(x, [Term(sympy.Matrix([x(t)[1], -k * x(t - tau)[0] - x(t)[1]]))])], parameters=P,
    ...              name="oscillator")
    >>> fam = linear_family(sys, {"x": [0, 0]}, grid=("k",))
    >>> fam
    LinearFamily('oscillator linearised', grid=('k',), n=2, delay=1, structural_zero=False)
    >>> pickle.loads(pickle.dumps(fam)).evaluate([[0.5], [5.0]]).verdict
    ('stable', 'unstable')
    """

    name: str
    grid: tuple
    symbols: tuple
    A: sympy.ImmutableMatrix
    Ad: sympy.ImmutableMatrix
    D: sympy.ImmutableMatrix
    delay: object
    labels: tuple
    limits: tuple = ()
    structural_zero: bool = False
    nodes: int = NODES
    refine: int = REFINE
    tol: float = TOL
    from_float: bool = False

    def __repr__(self) -> str:
        return (f"LinearFamily({self.name!r}, grid={self.grid}, n={self.n}, delay={self.delay}, "
                f"structural_zero={self.structural_zero})")

    @property
    def n(self) -> int:
        """The dimension of the reduced state ξ."""
        return self.A.rows

    @property
    def has_distributed(self) -> bool:
        return not self.D.is_zero_matrix

    def at(self, values: Mapping) -> LinearDelaySystem:
        """The linear system at one point, exactly (grid name → exact value; a float at its binary value).

        A float value (or a float given to :func:`linear_family`) marks the system ``from_float``:
        its results are then at most ``certified``.

        >>> import sympy
        >>> from lkverify import Equation, Parameters, System, Term, Vector, t
        >>> P = Parameters(); a = P.scalar("a", default=1); x = Vector("x", 1)
        >>> fam = linear_family(System([Equation(x, [Term(-a * x(t)[0] ** 3 - a * x(t)[0])])], parameters=P),
        ...                     {"x": [0]}, grid=("a",))
        >>> fam.at({"a": sympy.Rational(1, 2)}).A
        Matrix([[-1/2]])
        """
        missing = [g for g in self.grid if g not in values]
        if missing:
            raise InputError(f"{self.name}: expected a value for every grid name ({', '.join(self.grid)}), got none "
                             f"for {', '.join(missing)}; pass e.g. {{{missing[0]!r}: 1}}")
        sub = {s: sympy.sympify(values[g]) for g, s in zip(self.grid, self.symbols)}
        kernel = [self.D.xreplace(sub)] if self.has_distributed else []
        return LinearDelaySystem(self.A.xreplace(sub), Ad=self.Ad.xreplace(sub), kernel=kernel,
                                 name=f"{self.name} at {', '.join(f'{g} = {values[g]}' for g in self.grid)}",
                                 from_float=self.from_float or has_float([values[g] for g in self.grid]))

    def delay_at(self, values: Mapping):
        """The delay h at one point, exactly (0 for an ODE).

        >>> from lkverify import Equation, Parameters, System, Term, Vector, t
        >>> P = Parameters(); tau = P.delay("tau", default=1); x = Vector("x", 1)
        >>> fam = linear_family(System([Equation(x, [Term(-x(t - 2 * tau)[0])])], parameters=P), {"x": [0]},
        ...                     grid=("tau",))
        >>> fam.delay_at({"tau": sympy.Rational(3, 4)})
        3/2
        """
        if self.delay is None:
            return sympy.S.Zero
        sub = {s: sympy.sympify(values[g]) for g, s in zip(self.grid, self.symbols)}
        return sympy.sympify(self.delay).xreplace(sub)

    # ------------------------------------------------------------------ evaluation
    def _function(self):
        """p ↦ (A, A_d, D, h) as floats, generated from the SymPy data once per process (not pickled)."""
        fn = self.__dict__.get("_fn")
        if fn is None:
            h = sympy.S.Zero if self.delay is None else sympy.sympify(self.delay)
            exprs = [*self.A, *self.Ad, *self.D, h]
            fn = sympy.lambdify(self.symbols, exprs, modules="numpy", cse=True, docstring_limit=0)
            self.__dict__["_fn"] = fn
        return fn

    def __getstate__(self):
        return {k: v for k, v in self.__dict__.items() if k != "_fn"}

    def evaluate(self, points) -> LinearBatch:
        """The spectral abscissa and the verdict at each point (an (N, len(grid)) float array).

        Returns
        -------
        LinearBatch
            ``estimated``.

        Raises
        ------
        InputError
            ``points`` not of shape (N, len(grid)) or not real numbers.
        """
        start = time.perf_counter()
        pts = _as_points(points, self.grid)
        N, n = len(pts), self.n
        fn = self._function()
        out = {"abscissa": np.full(N, np.nan), "rightmost": np.full(N, np.nan + 0j), "residual": np.full(N, np.nan),
               "converged": np.zeros(N, dtype=bool), "delay": np.full(N, np.nan), "nodes": np.zeros(N, dtype=int)}
        verdict = []
        distributed = self.has_distributed
        with np.errstate(all="ignore"):
            for i, p in enumerate(pts):
                verdict.append(self._point(np.array(fn(*p), dtype=float), n, distributed, out, i))
        detail = (f"spectral abscissa of the linearisation at {N} point(s): Chebyshev degree {self.nodes} "
                  f"(Breda–Maset–Vermiglio), the {self.refine} rightmost eigenvalues refined by Newton on "
                  f"det Δ(λ) = 0; critical when |α| ≤ {self.tol:g}·max(1, |λ|)"
                  + ("; λ = 0 is a root at every point (det(A + A_d + hD) ≡ 0)" if self.structural_zero else "")
                  + "; floating point")
        return LinearBatch(self.grid, pts, out["abscissa"], tuple(verdict), out["rightmost"], out["residual"],
                           out["converged"], out["delay"], out["nodes"], self.tol, Status.ESTIMATED, detail,
                           time.perf_counter() - start)

    def _point(self, flat, n, distributed, out, i) -> str:
        """Fill row i of ``out`` from the flat (A, A_d, D, h) of one point; return its verdict."""
        k = n * n
        h = flat[-1]
        out["delay"][i] = h
        if not np.all(np.isfinite(flat)) or h < 0:
            return "undefined"
        system = _PointSystem(flat[:k].reshape(n, n), flat[k:2 * k].reshape(n, n),
                              flat[2 * k:3 * k].reshape(n, n) if distributed else None)
        sp, converged = self._spectrum(system, h)
        lam = complex(sp.roots[0])
        alpha = max(sp.abscissa, 0.0) if self.structural_zero else sp.abscissa
        out["abscissa"][i], out["rightmost"][i], out["nodes"][i] = alpha, lam, sp.nodes
        out["residual"][i], out["converged"][i] = sp.residuals[0], converged
        tol = self.tol * max(1.0, abs(lam))
        if not np.isfinite(alpha):
            return "undefined"
        if alpha > tol:
            return "unstable"
        if alpha < -tol and not self.structural_zero:
            return "stable"
        return "critical"

    def _spectrum(self, system, h):
        """(Spectrum, converged): at degree ``nodes``, again at twice it when the rightmost root did not converge."""
        best = None
        for nodes in (self.nodes, 2 * self.nodes):
            try:
                sp = rightmost_roots(system, h, nodes=nodes, count=self.refine)
            except (np.linalg.LinAlgError, ValueError):      # Newton thrown into overflow: the eigenvalues as they are
                sp = rightmost_roots(system, h, nodes=nodes, count=0)
            if h == 0:                                       # the eigenvalues of A + A_d: nothing to refine
                return sp, True
            if best is None or sp.residuals[0] < best.residuals[0]:
                best = sp
            if best.residuals[0] <= CONVERGED * max(1.0, abs(best.roots[0])):
                return best, True
        return best, False


def _as_points(points, grid) -> np.ndarray:
    try:
        pts = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"points: expected an (N, {len(grid)}) array of real numbers ({', '.join(grid)}), "
                         f"got {type(points).__name__}; pass e.g. [[{', '.join('1.0' for _ in grid)}]]") from None
    if pts.ndim == 1 and len(grid) == 1:
        pts = pts[:, None]
    if pts.ndim != 2 or pts.shape[1] != len(grid):
        raise InputError(f"points: expected an (N, {len(grid)}) array (columns {', '.join(grid)}), got shape "
                         f"{pts.shape}; pass one row per point")
    return pts


def linear_family(system, equilibrium: Mapping, values: Mapping | None = None, *, grid: Sequence[str],
                  coordinates: str = "tangent", order: Sequence[str] | None = None, nodes: int = NODES,
                  refine: int = REFINE, tol: float = TOL) -> LinearFamily:
    """Linearise ``system`` at ``equilibrium`` once, with the ``grid`` names kept symbolic.

    Parameters
    ----------
    system : lkverify.System
    equilibrium : mapping
        State name → value (as :func:`~lkverify.linear.linearise.linearise_at` takes it); it must be an
        equilibrium at every grid point (the residual vanishes identically in the grid symbols).
    values : mapping, optional
        The other parameters' values; a value may contain grid names (a template such as
        ``{"F": diag(h, h, h)}`` with ``grid=("b", "h")``); defaults fill in.
    grid : sequence of str
        Scalar parameters of the system, or names used inside ``values``; the columns of
        :meth:`LinearFamily.evaluate`'s points.
    coordinates, order
        As for :func:`~lkverify.linear.linearise.linearise_at`.
    nodes, refine, tol
        Chebyshev degree, refined roots per point and the critical band (module defaults measured).

    Raises
    ------
    InputError
        A grid name that is neither a scalar parameter nor used in ``values``, not an
        equilibrium at every grid point, not differentiable there, several delays, bad options.
    UnsupportedInput
        Memory integrals or other integrals than windows of the states.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> P = Parameters(); k = P.scalar("k", default=1); x = Vector("x", 1)
    >>> sys = System([Equation(x, [Term(k - x(t)[0])])], parameters=P, name="shifted")
    >>> linear_family(sys, {"x": [1]}, grid=("k",))
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: shifted: expected an equilibrium (ẋ = 0) at every grid point, got the residual dx/dt = k - 1 at the given point; give a point where the right-hand side vanishes for all values of k
    """
    grid = tuple(grid)
    if not grid or len(set(grid)) != len(grid) or not all(isinstance(g, str) for g in grid):
        raise InputError(f"grid: expected distinct names (strings), at least one, got {list(grid)}; "
                         f"pass e.g. grid=('b', 'h')")
    if coordinates not in COORDINATES:
        raise InputError(f"coordinates: expected one of {', '.join(COORDINATES)}, got {coordinates!r}")
    if not (isinstance(nodes, int) and nodes >= 2 and isinstance(refine, int) and refine >= 0 and tol >= 0):
        raise InputError(f"options: expected nodes ≥ 2, refine ≥ 0 (integers) and tol ≥ 0, got nodes={nodes}, "
                         f"refine={refine}, tol={tol}")
    parts = _linear_parts(system, equilibrium, values, coordinates=coordinates, order=order, keep=grid)
    n = parts.A.rows
    h = sympy.S.Zero if parts.delay is None else parts.delay
    static = (parts.A + parts.Ad + h * parts.D)
    zero = sympy.simplify(static.det(method="berkowitz")) == 0
    return LinearFamily(f"{system.name or 'system'} linearised", grid, parts.symbols, sympy.ImmutableMatrix(parts.A),
                        sympy.ImmutableMatrix(parts.Ad), sympy.ImmutableMatrix(parts.D if parts.windows else
                                                                               sympy.zeros(n, n)),
                        parts.delay, parts.labels, parts.limits, bool(zero), nodes, refine, float(tol),
                        has_float(dict(values or {})))
