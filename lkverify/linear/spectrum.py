"""The spectral reference: rightmost characteristic roots of a linear delay system.

The infinitesimal generator of the solution semigroup on C([−h, 0], Rⁿ) is discretised by
collocation at the N + 1 Chebyshev extremal points of [−h, 0] (Breda, Maset & Vermiglio,
"Pseudospectral differencing methods for characteristic roots of delay differential
equations", SIAM J. Sci. Comput. 27 (2005) 482–495): the rows at θ_j < 0 differentiate the
interpolant, the row at θ_0 = 0 is the right-hand side (the distributed term by
Clenshaw–Curtis quadrature on the same nodes).  The eigenvalues of that n(N+1) matrix
approximate the rightmost roots; each of them is then refined by Newton's method on the
characteristic equation Δ(λ)v = 0, cᴴv = 1 (:meth:`LinearDelaySystem.characteristic_matrix`).
Everything is floating point: the status is ``estimated``.

Examples
--------
>>> from lkverify.linear.model import LinearDelaySystem
>>> sys = LinearDelaySystem([[-2, 0], [0, -0.9]], Ad=[[-1, 0], [-1, -1]])
>>> sp = rightmost_roots(sys, 1.0)
>>> sp.status.value, sp.abscissa < 0
('estimated', True)
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from ..status import Status
from .model import LinearDelaySystem

__all__ = ["Spectrum", "rightmost_roots", "spectral_abscissa", "chebyshev", "generator_matrix"]

#: Chebyshev degree of the discretisation (n(N+1) eigenvalues)
DEFAULT_NODES = 40
#: Newton refinement: iterations and the residual ‖Δ(λ)v‖ accepted
NEWTON_STEPS = 30
NEWTON_TOL = 1e-12


@dataclasses.dataclass(frozen=True)
class Spectrum:
    """The rightmost characteristic roots at one delay (``estimated``).

    Attributes
    ----------
    h : float
    roots : ndarray of complex
        Refined roots, rightmost first (one of each conjugate pair with Im ≥ 0 kept with its pair).
    abscissa : float
        max Re λ over the refined roots.
    residuals : ndarray
        σ_min(Δ(λ)) at each refined root.
    nodes : int
    status : Status
        ``estimated`` (floating point).
    detail : str
    discretised : ndarray of complex
        All eigenvalues of the discretised generator (for plots).

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> rightmost_roots(LinearDelaySystem([[-1]], Ad=[[0]]), 1.0).stable
    True
    """

    h: float
    roots: np.ndarray
    abscissa: float
    residuals: np.ndarray
    nodes: int
    status: Status
    detail: str
    discretised: np.ndarray

    @property
    def stable(self) -> bool:
        return self.abscissa < 0


def chebyshev(N: int):
    """Chebyshev extremal points x_j = cos(jπ/N) and the differentiation matrix (Trefethen, Spectral Methods in MATLAB)."""
    x = np.cos(np.pi * np.arange(N + 1) / N)
    c = np.ones(N + 1)
    c[0] = c[-1] = 2
    c *= (-1) ** np.arange(N + 1)
    X = np.tile(x, (N + 1, 1)).T
    dX = X - X.T
    D = np.outer(c, 1 / c) / (dX + np.eye(N + 1))
    D -= np.diag(D.sum(axis=1))
    return x, D


def _clenshaw_curtis(N: int) -> np.ndarray:
    """Clenshaw–Curtis weights on [−1, 1] at x_j = cos(jπ/N) (Trefethen's clencurt)."""
    theta = np.pi * np.arange(N + 1) / N
    w = np.zeros(N + 1)
    v = np.ones(N - 1)
    inner = theta[1:-1]
    if N % 2 == 0:
        w[0] = w[N] = 1 / (N ** 2 - 1)
        for k in range(1, N // 2):
            v -= 2 * np.cos(2 * k * inner) / (4 * k ** 2 - 1)
        v -= np.cos(N * inner) / (N ** 2 - 1)
    else:
        w[0] = w[N] = 1 / N ** 2
        for k in range(1, (N - 1) // 2 + 1):
            v -= 2 * np.cos(2 * k * inner) / (4 * k ** 2 - 1)
    w[1:-1] = 2 * v / N
    return w


def generator_matrix(system: LinearDelaySystem, h: float, N: int = DEFAULT_NODES) -> np.ndarray:
    """The n(N+1) pseudospectral matrix of the generator at delay h > 0 (block j ↔ θ_j = h(x_j − 1)/2).

    >>> from lkverify.linear.model import LinearDelaySystem
    >>> generator_matrix(LinearDelaySystem([[-1]], Ad=[[0]]), 1.0, N=4).shape
    (5, 5)
    """
    n = system.n
    A, Ad, D = system.floats_cached()
    x, Dx = chebyshev(N)
    theta = h * (x - 1) / 2
    M = np.zeros((n * (N + 1), n * (N + 1)))
    M[n:, :] = np.kron(Dx[1:, :] * (2 / h), np.eye(n))
    M[:n, :n] += A
    M[:n, N * n:] += Ad
    if D:
        w = _clenshaw_curtis(N) * h / 2
        age = -theta
        for j in range(N + 1):
            K = sum(Dk * age[j] ** k for k, Dk in enumerate(D))
            M[:n, j * n:(j + 1) * n] += w[j] * K
    return M


def _newton(system: LinearDelaySystem, lam: complex, h: float):
    """Newton on Δ(λ)v = 0, cᴴv = 1 from λ (c: the singular vector of Δ(λ₀)); (λ, σ_min(Δ(λ)))."""
    n = system.n
    U, s, Vh = np.linalg.svd(system.characteristic_matrix(lam, h))
    v = Vh[-1].conj()
    c = v.copy()
    for _ in range(NEWTON_STEPS):
        Dl = system.characteristic_matrix(lam, h)
        r = Dl @ v
        if np.linalg.norm(r) < NEWTON_TOL * max(1.0, abs(lam)):
            break
        J = np.zeros((n + 1, n + 1), dtype=complex)
        J[:n, :n] = Dl
        J[:n, n] = system.characteristic_derivative(lam, h) @ v
        J[n, :n] = c.conj()
        rhs = -np.concatenate([r, [c.conj() @ v - 1]])
        try:
            step = np.linalg.solve(J, rhs)
        except np.linalg.LinAlgError:
            break
        v = v + step[:n]
        lam = lam + step[n]
    sigma = np.linalg.svd(system.characteristic_matrix(lam, h), compute_uv=False)[-1]
    return lam, sigma


def _one_blas_thread(func):
    """Run with one BLAS thread (threadpoolctl): threaded BLAS only spins on these small matrices (×15 slower
    on a loaded machine)."""
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        with _controller().limit(limits=1, user_api="blas"):
            return func(*args, **kwargs)
    return wrapper


@functools.lru_cache(maxsize=1)
def _controller():
    """One threadpoolctl controller per process (finding the libraries costs ~10 ms each time)."""
    from threadpoolctl import ThreadpoolController
    return ThreadpoolController()


@_one_blas_thread
def rightmost_roots(system: LinearDelaySystem, h, *, nodes: int = DEFAULT_NODES, count: int | None = None) -> Spectrum:
    """The rightmost characteristic roots at delay h: BMV discretisation, then Newton refinement.

    Parameters
    ----------
    system : LinearDelaySystem
    h : float
        The delay (h = 0: the eigenvalues of A + A_d).
    nodes : int
        Chebyshev degree N.
    count : int, optional
        How many rightmost eigenvalues to refine (default 2n + 4; 0: none, the discretised eigenvalues).

    Returns
    -------
    Spectrum
        ``estimated``.

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> sp = rightmost_roots(LinearDelaySystem([[-1]], Ad=[[0]]), 1.0)
    >>> round(sp.abscissa, 12)
    -1.0
    """
    h = float(h)
    if h == 0:
        A, Ad, _ = system.floats_cached()
        ev = np.linalg.eigvals(A + Ad)
        ev = ev[np.argsort(-ev.real)]
        return Spectrum(0.0, ev, float(ev.real.max()), np.zeros(len(ev)), 0, Status.ESTIMATED,
                        "h = 0: the eigenvalues of A + A_d (floating point)", ev)
    ev = np.linalg.eigvals(generator_matrix(system, h, nodes))
    ev = ev[np.argsort(-ev.real)]
    k = 2 * system.n + 4 if count is None else count
    refined, res = [], []
    for lam0 in ev[:k]:
        lam, sigma = _newton(system, complex(lam0), h)
        if abs(lam - lam0) > 0.5 * max(1.0, abs(lam0)):  # Newton wandered to another root: keep the estimate
            lam, sigma = complex(lam0), np.linalg.svd(system.characteristic_matrix(lam0, h), compute_uv=False)[-1]
        refined.append(lam)
        res.append(sigma)
    if not refined:  # count = 0: the discretised eigenvalues as they are (a coarse scan)
        return Spectrum(h, ev, float(ev.real.max()), np.full(len(ev), np.nan), nodes, Status.ESTIMATED,
                        f"{len(ev)} eigenvalues of the pseudospectral generator (Chebyshev N = {nodes}), unrefined", ev)
    order = np.argsort(-np.real(refined))
    roots, res = np.array(refined)[order], np.array(res)[order]
    tol = 1e-8 * max(1.0, float(np.max(np.abs(roots[:1]))))
    converged = int(np.sum(res < tol))
    detail = (f"{len(ev)} eigenvalues of the pseudospectral generator (Chebyshev N = {nodes}, Breda–Maset–Vermiglio), "
              f"the {k} rightmost refined by Newton on det Δ(λ) = 0 ({converged} converged; σ_min(Δ) at the rightmost "
              f"root {res[0]:.1e}); floating point")
    return Spectrum(h, roots, float(roots.real.max()), res, nodes, Status.ESTIMATED, detail, ev)


def spectral_abscissa(system: LinearDelaySystem, h, *, nodes: int = DEFAULT_NODES) -> float:
    """max Re λ over the characteristic roots at delay h (estimated; see :func:`rightmost_roots`).

    Examples
    --------
    >>> from lkverify.linear.model import LinearDelaySystem
    >>> spectral_abscissa(LinearDelaySystem([[0, 1], [-2, 0.1]], Ad=[[0, 0], [1, 0]]), 1.0) < 0
    True
    """
    return rightmost_roots(system, h, nodes=nodes).abscissa
