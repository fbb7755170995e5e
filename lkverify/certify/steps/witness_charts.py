"""Charts of the witness search: smooth maps from unconstrained parameters onto the admissible values of
one slot (a state at one time, a history piece, the witness time), with their exact rational points.

* :class:`_Chart` — a unit 3-vector in a cap, a vector in a ball, free components, or a fixed centre;
* :class:`_FrameChart` — a frame ``s_i = Q r_i`` with Q a Cayley rotation (rational at the exact point);
* :class:`_TimeChart` — the searched witness time in [lo, hi];

with their NumPy helpers (hyperspherical angles, Cayley and Rodrigues rotations), the rounding and arb
precision of the exact recheck point (``_DENOMINATOR``, ``_PREC``) and :class:`UnsupportedClaim`, which
every layer of the search raises.  Split from :mod:`lkverify.certify.steps.witnesses`, which re-exports
what is imported from it; the method is described there.
"""

from __future__ import annotations

import math

import numpy as np
import sympy

from ...errors import InputError, UnsupportedInput
from ..intervals.convert import enclose

__all__ = ["UnsupportedClaim"]

#: rational rounding of the optimiser's point for the exact recheck
_DENOMINATOR = 10 ** 6
#: arb precision of the recheck (bits)
_PREC = 128


class UnsupportedClaim(UnsupportedInput, InputError):
    """A claim outside the witness family (frames, nested integrals, …): nothing was refuted.

    It is both an :class:`~lkverify.errors.UnsupportedInput` and an
    :class:`~lkverify.errors.InputError`.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.errors import UnsupportedInput
    >>> from lkverify.certify.steps.witnesses import search_witness
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> P = Parameters(); x = Vector("x", 1); e = norm_measure("e", x(t))
    >>> sys_ = System([Equation(x, [Term(-x(t)[0])])], parameters=P)
    >>> try:
    ...     search_witness(x(t + 1)[0], e.symbol, system=sys_, values=P.resolve({}), measures=[e], budget=1)
    ... except UnsupportedInput as exc:               # also an InputError
    ...     print(type(exc).__name__, exc)
    UnsupportedClaim lhs term 'lhs': expected the state at t or at earlier times, got x_1(t + 1) (a future value)
    """


def _lt(a, b) -> bool:
    """a < b for real constants (exact when they are rational)."""
    return bool(sympy.sympify(a - b) < 0)


# ---------------------------------------------------------------------------------------------
# charts: unconstrained parameters → admissible values
# ---------------------------------------------------------------------------------------------

class _Chart:
    """A smooth map from free parameters onto the admissible set of one slot.

    kinds: ``cap`` (unit 3-vector at angle ≤ top from a unit centre), ``ball`` (‖v − c‖ ≤ δ),
    ``free`` (components), ``fixed`` (a bound 0: the centre itself).
    """

    def __init__(self, kind: str, dim: int, *, center=None, bound=None):
        self.kind, self.dim = kind, dim
        self.center = None if center is None else sympy.ImmutableMatrix(center)
        self.bound = bound
        if kind == "cap":
            from ..charts import unit_vector_near

            try:
                if bound is None or bool(sympy.sympify(bound) >= 2):
                    ch = unit_vector_near(self.center, rho_max=sympy.pi)
                else:
                    ch = unit_vector_near(self.center, distance_max=bound)
            except InputError as exc:
                raise UnsupportedClaim(f"a region bound on a unit vector: expected ‖s − r‖ ≤ d with r a "
                                       f"constant unit vector, got centre {list(self.center)} ({exc}); bound "
                                       f"s − r with a unit r") from exc
            self.top = list(ch.region.values())[0][1]
            self.e1, self.e2 = ch.extras["e1"], ch.extras["e2"]
            self.nparams = 2
            self._c = np.array([float(v) for v in self.center])
            self._e1 = np.array([float(v) for v in self.e1])
            self._e2 = np.array([float(v) for v in self.e2])
            self._top = float(self.top)
        elif kind == "ball":
            self.nparams = dim
            self._c = np.array([float(v) for v in self.center])
            self._delta = float(bound)
        elif kind == "free":
            self.nparams = dim
        elif kind == "fixed":
            self.nparams = 0
            self._c = np.array([float(v) for v in self.center])
        else:  # pragma: no cover
            raise AssertionError(kind)

    def describe(self) -> str:
        if self.kind == "cap":
            return (f"cos(rho)·c + sin(rho)(cos(psi)·e1 + sin(psi)·e2), rho = {self.top}·sin(u)², "
                    f"c = {list(self.center)}, e1 = {list(self.e1)}, e2 = {list(self.e2)}")
        if self.kind == "ball":
            return f"c + {self.bound}·sin(u)²·direction(angles), c = {list(self.center)}"
        if self.kind == "fixed":
            return f"the centre {list(self.center)}"
        return "free components"

    # exact (sympy) and numeric forms of the same formulas
    def expr(self, p) -> list:
        """The value (one expression per component) at parameters ``p`` (symbols or rationals)."""
        if self.kind == "cap":
            u, psi = p
            rho = self.top * sympy.sin(u) ** 2
            v = sympy.cos(rho) * self.center + sympy.sin(rho) * (sympy.cos(psi) * self.e1 + sympy.sin(psi) * self.e2)
            return list(v)
        if self.kind == "ball":
            if self.dim == 1:
                return [self.center[0] + self.bound * sympy.sin(p[0])]
            radius = self.bound * sympy.sin(p[0]) ** 2
            return [c + radius * d for c, d in zip(self.center, _direction(p[1:], sympy))]
        if self.kind == "free":
            return list(p)
        return list(self.center)

    def value(self, p: np.ndarray) -> np.ndarray:
        """The numeric value at the parameters ``p``."""
        if self.kind == "cap":
            rho = self._top * math.sin(p[0]) ** 2
            return math.cos(rho) * self._c + math.sin(rho) * (math.cos(p[1]) * self._e1 + math.sin(p[1]) * self._e2)
        if self.kind == "ball":
            if self.dim == 1:
                return self._c + self._delta * math.sin(p[0])
            return self._c + self._delta * math.sin(p[0]) ** 2 * np.array(_direction(p[1:], math))
        if self.kind == "free":
            return np.array(p, dtype=float)
        return self._c.copy()

    def inverse(self, v: np.ndarray) -> np.ndarray:
        """Parameters whose value is ``v`` (projected onto the admissible set)."""
        v = np.asarray(v, dtype=float)
        if self.kind == "cap":
            n = np.linalg.norm(v)
            v = v / n if n > 0 else self._c
            rho = math.acos(min(1.0, max(-1.0, float(v @ self._c))))
            psi = math.atan2(float(v @ self._e2), float(v @ self._e1))
            return np.array([math.asin(math.sqrt(min(1.0, rho / self._top))), psi])
        if self.kind == "ball":
            d = v - self._c
            if self.dim == 1:
                return np.array([math.asin(min(1.0, max(-1.0, float(d[0]) / self._delta)))])
            rad = float(np.linalg.norm(d))
            u = math.asin(math.sqrt(min(1.0, rad / self._delta)))
            return np.concatenate([[u], _angles(d / rad if rad > 0 else np.eye(self.dim)[0])])
        if self.kind == "free":
            return v.copy()
        return np.zeros(0)

    def random(self, rng: np.random.Generator) -> np.ndarray:
        if self.kind == "cap":
            return np.array([rng.uniform(0, math.pi / 2), rng.uniform(0, 2 * math.pi)])
        if self.kind == "ball":
            if self.dim == 1:
                return np.array([rng.uniform(-math.pi / 2, math.pi / 2)])
            return np.concatenate([[rng.uniform(0, math.pi / 2)], _angles(_unit(rng, self.dim))])
        if self.kind == "free":
            return rng.normal(size=self.dim) * rng.choice([0.1, 1.0, 3.0])
        return np.zeros(0)

    def numeric(self, P: np.ndarray) -> list:
        """The values (one array per component) at the parameter columns ``P`` (shape (nparams, N))."""
        if getattr(self, "_lambdified", None) is None:
            syms = [sympy.Symbol(f"_cp{i}", real=True) for i in range(self.nparams)]
            self._lambdified = sympy.lambdify(syms, self.expr(syms), modules="numpy", cse=True, docstring_limit=0)
        return self._lambdified(*P)

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        """``(record, values)`` at the rational point near ``p``: the rational parameters (strings) and the
        exact value (one SymPy number per component), admissible by construction."""
        q = [sympy.Rational(float(x)).limit_denominator(denominator) for x in p]
        return [str(x) for x in q], self.expr(q)


def _skew_np(k: np.ndarray) -> np.ndarray:
    """``[k]×`` for the columns of ``k`` (shape (3, N)) → shape (3, 3, N)."""
    z = np.zeros_like(k[0])
    return np.array([[z, -k[2], k[1]], [k[2], z, -k[0]], [-k[1], k[0], z]])


def _cayley_np(k: np.ndarray) -> np.ndarray:
    """The Cayley rotations ``I + 2(K + K²)/(1 + ‖k‖²)``, ``K = [k]×``, for the columns of ``k`` → (3, 3, N)."""
    K = _skew_np(k)
    K2 = np.einsum("ijn,jln->iln", K, K)
    return np.eye(3)[:, :, None] + 2 * (K + K2) / (1 + np.sum(k ** 2, axis=0))


def _cayley_exact(k) -> sympy.ImmutableMatrix:
    """The Cayley rotation of a rational 3-vector ``k``: exactly orthogonal, det 1, rational entries."""
    K = sympy.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return sympy.ImmutableMatrix(sympy.eye(3) + 2 * (K + K * K) / (1 + sum(x ** 2 for x in k)))


def _rotation_np(a: np.ndarray, phi: float) -> np.ndarray:
    """The rotation by ``phi`` about the unit axis ``a`` (Rodrigues)."""
    A = _skew_np(a[:, None])[:, :, 0]
    return np.eye(3) + math.sin(phi) * A + (1 - math.cos(phi)) * A @ A


#: the largest rotation angle of a frame chart, as a fraction of π (Cayley's k = tan(θ/2)·n stays finite)
_FRAME_TOP = 0.999


class _FrameChart:
    """Frames ``s_i = Q r_i`` (i = 1, 2, 3) with ``R0 = [r1 r2 r3]`` a reference rotation and Q a rotation.

    Q is the Cayley rotation of ``k = tan(θ/2)·n``: ``Q = I + 2(K + K²)/(1 + ‖k‖²)``, ``K = [k]×``,
    the rotation by θ about n.  The parameters are ``(u, a1, a2)``: ``n = direction(a1, a2)`` and
    ``θ = θmax(n)·sin²(u)``, where θmax(n) is the largest angle about n for which every bounded
    vector stays inside its cap: ``‖Q r_i − r_i‖ = 2 sin(θ/2)·‖n × r_i‖ ≤ δ_i``, increasing in θ,
    so the map is onto the admissible set (up to rotations by more than :data:`_FRAME_TOP`·π).
    At the exact point k is rational, so Q is exactly orthogonal with rational entries and the
    triad exactly orthonormal and right-handed; admissibility ``4‖k × r_i‖² ≤ δ_i²(1 + ‖k‖²)``
    (the same identity) is checked exactly, k shrunk towards 0 if rounding left the cap.
    """

    kind = "frame"
    dim = 9
    nparams = 3
    center = None

    def __init__(self, reference, bounds: dict):
        self.reference = sympy.ImmutableMatrix(reference)
        self.bounds = dict(bounds)               # vector index (0, 1, 2) → δ
        self._R0 = np.array([[float(x) for x in row] for row in self.reference.tolist()])
        self._bounds = [(i, float(d)) for i, d in sorted(self.bounds.items())]
        self._top = min([math.pi * _FRAME_TOP] + [2 * math.asin(min(1.0, d / 2)) for _, d in self._bounds])

    def describe(self) -> str:
        cols = [list(self.reference[:, i]) for i in range(3)]
        caps = ", ".join(f"‖s{i + 1} − r{i + 1}‖ ≤ {d}" for i, d in sorted(self.bounds.items())) or "none"
        return (f"s_i = Q r_i, Q = I + 2(K + K²)/(1 + ‖k‖²), K = [k]× (Cayley; the parameters are k), "
                f"r1, r2, r3 = {cols}; k = tan(θ/2)·n(a1, a2), θ = θmax(n)·sin(u)², caps: {caps}")

    def _theta_max(self, n: np.ndarray) -> np.ndarray:
        top = np.full(n.shape[1:], math.pi * _FRAME_TOP)
        with np.errstate(divide="ignore", invalid="ignore"):
            for i, d in self._bounds:
                sin = np.linalg.norm(np.cross(n, self._R0[:, i][:, None], axis=0), axis=0)
                ratio = np.where(sin > 0, d / (2 * np.where(sin > 0, sin, 1.0)), np.inf)
                top = np.minimum(top, 2 * np.arcsin(np.minimum(1.0, ratio)))
        return top

    def _k(self, P: np.ndarray) -> np.ndarray:
        u, a1, a2 = P
        n = np.array(np.broadcast_arrays(*_direction([a1, a2], np)), dtype=float)
        theta = self._theta_max(n) * np.sin(u) ** 2
        return np.tan(theta / 2) * n

    def numeric(self, P: np.ndarray) -> list:
        P = np.asarray(P, dtype=float)
        Q = _cayley_np(self._k(P))
        S = np.einsum("ijn,jl->iln", Q, self._R0)          # S[:, l] = Q r_l
        return [S[a, l] for l in range(3) for a in range(3)]

    def value(self, p: np.ndarray) -> np.ndarray:
        return np.array([v[0] for v in self.numeric(np.asarray(p, dtype=float).reshape(3, 1))])

    def _admissible(self, k) -> bool:
        kk = sympy.Matrix(k)
        for i, d in self.bounds.items():
            gap = sympy.expand(d ** 2 * (1 + kk.dot(kk)) - 4 * _norm2(kk.cross(self.reference[:, i])))
            if gap.is_Rational:
                if gap < 0:
                    return False
            elif not enclose(gap, prec=_PREC) >= 0:
                return False
        return True

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        k = self._k(np.asarray(p, dtype=float).reshape(3, 1))[:, 0]
        q = [sympy.Rational(float(x)).limit_denominator(denominator) for x in k]
        for j in range(8):
            if self._admissible(q):
                break
            shrink = 1 - sympy.Rational(1, 10 ** 6) * 4 ** j
            q = [x * shrink for x in q]
        else:  # pragma: no cover - the shrunk point is inside unless it sits on the boundary
            q = [sympy.Integer(0)] * 3
        S = _cayley_exact(q) * self.reference
        return [str(x) for x in q], [S[a, l] for l in range(3) for a in range(3)]

    def inverse(self, v: np.ndarray) -> np.ndarray:
        T = np.asarray(v, dtype=float).reshape(3, 3).T          # columns s1, s2, s3
        U, _, Vt = np.linalg.svd(T @ self._R0.T)
        Q = U @ Vt
        if np.linalg.det(Q) < 0:
            Q = U @ np.diag([1, 1, -1]) @ Vt
        theta = math.acos(min(1.0, max(-1.0, (float(np.trace(Q)) - 1) / 2)))
        if theta < 1e-12:
            return np.zeros(3)
        w = np.array([Q[2, 1] - Q[1, 2], Q[0, 2] - Q[2, 0], Q[1, 0] - Q[0, 1]])
        if math.sin(theta) > 1e-6:
            n = w / (2 * math.sin(theta))
        else:                                                   # θ ≈ π: the axis from Q + I
            B = Q + np.eye(3)
            n = B[:, int(np.argmax(np.linalg.norm(B, axis=0)))]
        n = n / (np.linalg.norm(n) or 1.0)
        top = float(self._theta_max(n[:, None])[0])
        u = math.asin(math.sqrt(min(1.0, theta / top))) if top > 0 else 0.0
        return np.concatenate([[u], _angles(n)])

    def random(self, rng: np.random.Generator) -> np.ndarray:
        return np.concatenate([[rng.uniform(0, math.pi / 2)], _angles(_unit(rng, 3))])


class _TimeChart:
    """The witness time ``t = lo + (hi − lo) sin²(u)``; the exact time is a rational in [lo, hi]."""

    kind = "time"
    dim = 1
    nparams = 1
    center = None

    def __init__(self, lo, hi):
        self.lo, self.hi = lo, hi
        self._lo, self._hi = float(lo), float(hi)

    def describe(self) -> str:
        return f"t = {self.lo} + ({self.hi} − {self.lo})·sin(u)²"

    def numeric(self, P: np.ndarray) -> list:
        return [self._lo + (self._hi - self._lo) * np.sin(np.asarray(P[0], dtype=float)) ** 2]

    def value(self, p: np.ndarray) -> np.ndarray:
        return np.array([self._lo + (self._hi - self._lo) * math.sin(float(p[0])) ** 2])

    def exact(self, p: np.ndarray, denominator: int = _DENOMINATOR) -> tuple:
        q = sympy.Rational(float(self.value(p)[0])).limit_denominator(denominator)
        q = self.lo if _lt(q, self.lo) else self.hi if _lt(self.hi, q) else q
        return [str(q)], [q]

    def inverse(self, v: np.ndarray) -> np.ndarray:
        x = (float(np.asarray(v).ravel()[0]) - self._lo) / (self._hi - self._lo)
        return np.array([math.asin(math.sqrt(min(1.0, max(0.0, x))))])

    def random(self, rng: np.random.Generator) -> np.ndarray:
        return np.array([rng.uniform(0, math.pi / 2)])


def _norm2(v) -> sympy.Expr:
    return sympy.Add(*[x ** 2 for x in v])


def _direction(a, lib) -> list:
    """The unit vector of hyperspherical angles ``a`` (len n − 1) in R^n."""
    n = len(a) + 1
    out, prod = [], 1
    for k in range(n - 1):
        out.append(prod * lib.cos(a[k]))
        prod = prod * lib.sin(a[k])
    out.append(prod)
    return out


def _angles(d: np.ndarray) -> np.ndarray:
    """Inverse of :func:`_direction` for a unit vector ``d``."""
    n = len(d)
    a = np.zeros(n - 1)
    for k in range(n - 1):
        a[k] = math.atan2(float(np.linalg.norm(d[k + 1:])), float(d[k]))
    if n >= 2:
        a[n - 2] = math.atan2(float(d[n - 1]), float(d[n - 2]))
    return a


def _unit(rng, n) -> np.ndarray:
    v = rng.normal(size=n)
    return v / (np.linalg.norm(v) or 1.0)


def _plane_rotation(v, a, b, phi):
    """``v`` rotated by ``phi`` in the plane of the orthonormal (a, b)."""
    va, vb = float(v @ a), float(v @ b)
    c, s = math.cos(phi), math.sin(phi)
    return v - va * a - vb * b + (va * c - vb * s) * a + (va * s + vb * c) * b
