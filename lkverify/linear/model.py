"""Linear delay systems with one delay h, built from matrices.

    ẋ(t) = A x(t) + A_d x(t − h) + ∫_{t−h}^t K(t − s) x(s) ds,     K(u) = Σ_j D_j u^j,

a discrete delay (``Ad``) and a distributed delay with a constant (``kernel=[D]``) or
polynomial (``kernel=[D0, D1, …]``) kernel in the age u = t − s ∈ [0, h].  The matrices are
kept exact (SymPy; floats taken at their binary value — 0.9 is not 9/10 —, text entries
such as ``"0.9"`` read as the decimal 9/10); the float copies serve the spectral route.

The characteristic matrix is

    Δ(λ, h) = λI − A − A_d e^{−λh} − Σ_j D_j ∫_0^h u^j e^{−λu} du.

Examples
--------
>>> sys = LinearDelaySystem([[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]])
>>> sys.n, sys.has_discrete, sys.has_distributed
(2, True, False)
>>> sys.A[1, 1]
-9/10
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import sympy

from ..errors import InputError
from ..certify.matrices import _as_matrix

__all__ = ["LinearDelaySystem", "at_most_certified", "has_float", "parse_delay"]

#: Gauss–Legendre nodes used for the kernel integrals ∫_0^h u^j e^{−λu} du of polynomial kernels
KERNEL_NODES = 48


@dataclasses.dataclass(frozen=True)
class LinearDelaySystem:
    """ẋ = A x + A_d x(t−h) + ∫_{t−h}^t K(t−s) x(s) ds with K(u) = Σ_j D_j u^j (one delay h).

    Parameters
    ----------
    A : square matrix
    Ad : square matrix, optional
        The discrete-delay matrix (zero when omitted).
    kernel : sequence of square matrices, optional
        D_0, D_1, … of the kernel K(u) = Σ_j D_j u^j; ``[D]`` is a constant kernel.
    name : str
    from_float : bool
        Some input went through floating point (a Python or NumPy float, a float array, a SymPy
        ``Float``): set from the inputs (or passed True).  The entries are kept at their exact
        binary value, but every result about this system is then at most ``certified``, never
        ``exact`` (:mod:`lkverify.status`, rule 3).

    Raises
    ------
    InputError
        A matrix that is not square, not numeric, not finite, or of another size than A;
        all problems at once.

    Examples
    --------
    >>> LinearDelaySystem([[0.2, 0], [0.2, 0.1]], kernel=[[[-1, 0], [-1, -1]]]).kernel_order
    0
    >>> LinearDelaySystem([[0.2]]).from_float, LinearDelaySystem([["0.2"]]).from_float
    (True, False)
    >>> LinearDelaySystem([[1, 2]])
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: A: expected a nonempty square matrix, got row lengths [2]; pass n rows of n entries
    """

    A: object
    Ad: object = None
    kernel: tuple = ()
    name: str = "linear delay system"
    from_float: bool = False

    def __post_init__(self):
        problems = []
        floated = bool(self.from_float) or has_float([self.A, self.Ad, self.kernel])
        A = _try_matrix(self.A, "A", problems)
        n = A.rows if A is not None else None
        Ad = _try_matrix(self.Ad, "Ad", problems) if self.Ad is not None else None
        kernel = self.kernel
        if kernel is None:
            kernel = ()
        if isinstance(kernel, (sympy.MatrixBase, np.ndarray)) or (
                isinstance(kernel, (list, tuple)) and kernel and not _is_list_of_matrices(kernel)):
            kernel = (kernel,)  # one matrix: a constant kernel
        D = tuple(_try_matrix(K, f"kernel[{j}]", problems) for j, K in enumerate(kernel))
        for label, M in [("Ad", Ad)] + [(f"kernel[{j}]", K) for j, K in enumerate(D)]:
            if M is not None and n is not None and M.rows != n:
                problems.append(f"{label}: expected a {n}×{n} matrix (the size of A), got {M.rows}×{M.cols}")
        if problems:
            raise InputError("; ".join(problems))
        if Ad is None:
            Ad = sympy.zeros(n, n)
        object.__setattr__(self, "A", sympy.ImmutableMatrix(A))
        object.__setattr__(self, "Ad", sympy.ImmutableMatrix(Ad))
        object.__setattr__(self, "kernel", tuple(sympy.ImmutableMatrix(K) for K in D))
        object.__setattr__(self, "from_float", floated)

    # ------------------------------------------------------------------ properties
    @property
    def n(self) -> int:
        """The state dimension."""
        return self.A.rows

    @property
    def has_discrete(self) -> bool:
        return any(e != 0 for e in self.Ad)

    @property
    def has_distributed(self) -> bool:
        return any(e != 0 for K in self.kernel for e in K)

    @functools.cached_property
    def kernel_order(self) -> int | None:
        """The degree of the kernel polynomial (None without a distributed delay)."""
        nz = [j for j, K in enumerate(self.kernel) if any(e != 0 for e in K)]
        return max(nz) if nz else None

    @property
    def constant_kernel(self) -> bool:
        return self.kernel_order in (None, 0)

    @property
    def is_rational(self) -> bool:
        return all(e.is_Rational for M in (self.A, self.Ad, *self.kernel) for e in M)

    def floats(self):
        """(A, A_d, [D_j]) as float arrays."""
        f = lambda M: np.array(M.evalf(17).tolist(), dtype=float)  # noqa: E731
        return f(self.A), f(self.Ad), [f(K) for K in self.kernel]

    def at_zero_delay(self) -> sympy.Matrix:
        """A + A_d: the system at h = 0 (the distributed term vanishes)."""
        return sympy.Matrix(self.A + self.Ad)

    # ------------------------------------------------------------------ characteristic matrix
    def kernel_transform(self, lam: complex, h: float, *, power_shift: int = 0) -> np.ndarray:
        """Σ_j D_j ∫_0^h u^{j+power_shift} e^{−λu} du (float; the constant kernel in closed form)."""
        _, _, D = self.floats_cached()
        out = np.zeros((self.n, self.n), dtype=complex)
        if not D:
            return out
        if self.constant_kernel and power_shift <= 1:
            lh = lam * h
            if abs(lh) < 1e-3:  # series: ∫_0^h u^p e^{−λu} du = h^{p+1} Σ_k (−λh)^k / (k!(k+p+1))
                integral = h ** (power_shift + 1) * sum((-lh) ** k / (math.factorial(k) * (k + power_shift + 1))
                                                        for k in range(8))
            elif power_shift == 0:
                integral = (1 - np.exp(-lh)) / lam
            else:
                integral = (1 - np.exp(-lh) * (1 + lh)) / lam ** 2
            return D[0] * integral
        u, w = _gauss(h)
        e = np.exp(-lam * u) * w
        for j, Dj in enumerate(D):
            out += Dj * np.sum(u ** (j + power_shift) * e)
        return out

    def characteristic_matrix(self, lam: complex, h: float) -> np.ndarray:
        """Δ(λ, h) = λI − A − A_d e^{−λh} − K̂(λ) (float)."""
        A, Ad, _ = self.floats_cached()
        return lam * np.eye(self.n) - A - Ad * np.exp(-lam * h) - self.kernel_transform(lam, h)

    def characteristic_derivative(self, lam: complex, h: float) -> np.ndarray:
        """∂Δ/∂λ = I + h A_d e^{−λh} + Σ_j D_j ∫_0^h u^{j+1} e^{−λu} du."""
        _, Ad, _ = self.floats_cached()
        return np.eye(self.n) + h * Ad * np.exp(-lam * h) + self.kernel_transform(lam, h, power_shift=1)

    def floats_cached(self):
        cached = self.__dict__.get("_floats")
        if cached is None:
            cached = self.floats()
            object.__setattr__(self, "_floats", cached)
        return cached


def _is_list_of_matrices(seq) -> bool:
    first = seq[0]
    if isinstance(first, (sympy.MatrixBase, np.ndarray)):
        return True
    return isinstance(first, (list, tuple)) and bool(first) and isinstance(first[0], (list, tuple, np.ndarray))


def _decimal_strings(M, name, problems):
    """Entries given as text ("0.9", "-1/3") read exactly as rationals; other entries unchanged."""
    if not isinstance(M, (list, tuple)):
        return M
    out = []
    for i, row in enumerate(M):
        if not isinstance(row, (list, tuple)):
            return M
        new = []
        for j, v in enumerate(row):
            if isinstance(v, str):
                try:
                    v = sympy.Rational(v.strip())
                except (TypeError, ValueError):
                    problems.append(f"{name}[{i},{j}]: expected a number such as 0.9 or -1/3, got {v!r}")
                    v = 0
            new.append(v)
        out.append(new)
    return out


def _try_matrix(M, name, problems):
    try:
        return _as_matrix(_decimal_strings(M, name, problems), name)
    except InputError as exc:
        problems.append(str(exc))
        return None


@functools.lru_cache(maxsize=1)
def _legendre_nodes():
    return np.polynomial.legendre.leggauss(KERNEL_NODES)


def _gauss(h: float):
    x, w = _legendre_nodes()
    return h * (x + 1) / 2, w * h / 2


def has_float(value) -> bool:
    """True when ``value`` (a number, matrix, array, or nested lists/tuples/dicts of them) holds a float.

    Python and NumPy floats, float or complex NumPy arrays and SymPy ``Float`` atoms count; text
    such as ``"0.9"`` (read as the exact decimal) and rationals do not.

    Examples
    --------
    >>> has_float([[1, "0.5"], [sympy.Rational(1, 3), 2]]), has_float({"h": 0.5}), has_float(np.eye(2))
    (False, True, True)
    >>> has_float(sympy.Float(2) * sympy.Symbol("k")), has_float(np.array([[1, 2]]))
    (True, False)
    """
    if isinstance(value, bool):
        return False
    if isinstance(value, (float, np.floating, complex, np.complexfloating)):
        return True
    if isinstance(value, np.ndarray):
        return value.dtype.kind in "fc" or (value.dtype.kind == "O" and any(has_float(v) for v in value.flat))
    if isinstance(value, sympy.MatrixBase):
        return any(has_float(e) for e in value)
    if isinstance(value, sympy.Basic):
        return value.has(sympy.Float)
    if isinstance(value, dict):
        return any(has_float(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return any(has_float(v) for v in value)
    return False


def at_most_certified(status, inexact: bool):
    """``exact`` lowered to ``certified`` when some input went through floating point (else unchanged).

    The one place :mod:`lkverify.linear` applies rule 3 of :mod:`lkverify.status`; ``failed`` and
    ``undecided`` are kept.

    >>> from lkverify.status import Status
    >>> at_most_certified(Status.EXACT, True).value, at_most_certified(Status.EXACT, False).value
    ('certified', 'exact')
    >>> at_most_certified(Status.FAILED, True).value
    'failed'
    """
    from ..status import Status

    return Status.CERTIFIED if inexact and status is Status.EXACT else status


#: the note a result gets when a float input capped it at ``certified``
FLOAT_NOTE = ("a float input (taken at its exact binary value) makes this at most certified, never exact "
              "(lkverify.status)")


def parse_delay(value, name: str = "h") -> sympy.Rational:
    """A delay as an exact nonnegative rational (floats at their binary value).

    Examples
    --------
    >>> parse_delay("6.1725"), parse_delay(0.5)
    (2469/400, 1/2)
    >>> parse_delay(-1)
    Traceback (most recent call last):
    ...
    lkverify.errors.InputError: h: expected a delay h ≥ 0 (a finite real number), got -1
    """
    try:
        if isinstance(value, str):
            v = sympy.Rational(value)
        elif isinstance(value, float):
            v = sympy.Rational(*value.as_integer_ratio()) if math.isfinite(value) else None
        else:
            v = sympy.sympify(value)
            v = sympy.Rational(v) if isinstance(v, sympy.Float) and v.is_finite else v
            v = v if v.is_Rational else None
    except (TypeError, ValueError, sympy.SympifyError):
        v = None
    if v is None or not v.is_Rational or v < 0:
        raise InputError(f"{name}: expected a delay {name} ≥ 0 (a finite real number), got {value}")
    return v
