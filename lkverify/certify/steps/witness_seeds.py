"""Structured starts of the witness search: where the random starts rarely land.

:func:`~lkverify.certify.steps.witnesses.find_witness` runs a local optimisation from each
start; these are the starts that reach the extremal cases of the bound steps' rules:

* **eigenvector starts** — the Hessian of ``lhs − rhs`` in the values of the vector states
  at their centres (free vectors at 0, balls at their centre), by central differences
  (exact for a quadratic form up to rounding); each eigenvector, at a few sizes, is a start.
  A Rayleigh step ``uᵀMu ≤ m‖u‖²`` with m just below λ_max is refuted at the eigenvector of
  λ_max; the recheck rounds it finely enough (1/10¹⁸) to keep a gap of 10⁻¹² relative.
* **exact eigenvectors** (:func:`exact_eigen_points`) — when ``lhs − rhs`` is, in the
  deviations of vector states from their centres, a homogeneous quadratic form wᵀQw with
  rational coefficients, the eigenvector of λ_max(Q) > 0 at 50 digits, rounded to rationals
  (1/10⁴⁰), is a point where the violation is positive however small the gap: it is checked
  exactly, not through the optimiser (a Rayleigh step m = λ_max − 10⁻²⁰).
* **concentrated histories** — every history piece at the centre but the newest or the
  oldest: the window weight at one end of the window (``∫g‖v‖^k ≤ (max g)·m`` with the
  constant a hair too small); on the ``("ends", ε)`` grids of :data:`END_GRIDS` that piece
  has length ε·H.
* **power profiles** — the pieces along one direction with sizes σ^r or (1 − σ)^r (σ the
  piece's position in the window, r in ``PROFILE_POWERS``): near the equality case of
  Hölder's inequality, ‖v‖ ∝ g^{q/(kp)} for an affine weight g.

Every start is a point of the charts' parameter space, so it is admissible; nothing here is
a refutation by itself — a witness is reported only after the exact recheck.

Examples
--------
>>> import numpy as np, sympy
>>> from lkverify import Equation, Parameters, System, Term, Vector, t
>>> from lkverify.certify.steps.measures import norm_measure
>>> from lkverify.certify.steps.witnesses import _Model, _Problem
>>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
>>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
>>> M = sympy.Matrix([[2, 1], [1, 2]])                 # λ_max = 3 at (1, 1)/√2
>>> model = _Model(_Problem((x(t).T * M * x(t))[0], 3 * n.symbol ** 2, sys_, {}, [n], None, (), ()), 1)
>>> starts = structured_starts(model, np.random.default_rng(0))
>>> v = starts[0] / np.linalg.norm(starts[0]); bool(abs(abs(v[0]) - abs(v[1])) < 1e-9)
True
"""

from __future__ import annotations

import math

import numpy as np
import sympy

__all__ = ["END_GRIDS", "PROFILE_GRIDS", "PROFILE_POWERS", "exact_eigen_points", "structured_starts"]

#: piece grids with a piece of relative length ε at both sides of every window end
END_GRIDS = (("ends", "1/1000"), ("ends", "1/1000000"))
#: fine equal-piece grids searched from the structured starts only (a profile near Hölder's equality case
#: loses about 1/(8m²) of the constant on m pieces)
PROFILE_GRIDS = (16,)
#: exponents of the power-profile starts
PROFILE_POWERS = (1.0, 0.5, 2.0)
#: sizes (relative to a ball's radius; absolute for free vectors) of the eigenvector starts
_SIZES = (1.0, 0.5, 0.1)
#: the most eigenvector directions tried (the largest eigenvalues first)
_DIRECTIONS = 4


def structured_starts(model, rng, limit: int | None = None) -> list:
    """The structured starts (parameter vectors) of a model of :mod:`.witnesses` (see the module notes).

    Ordered by priority — the first of each kind (the top eigenvector at full size, both
    signs; the newest and the oldest piece concentrated; a linear profile), then the rest —
    so that ``limit`` (the most returned; None: all) keeps one of each.
    """
    base = _centre_params(model)
    kinds = [_eigen_starts(model, base)]
    if model.npieces:
        kinds += [_concentrated_starts(model, base, rng), _profile_starts(model, base, rng)]
    heads = [k[:2] for k in kinds]
    tails = [k[2:] for k in kinds]
    out = [p for h in heads for p in h] + [p for tl in tails for p in tl]
    return out if limit is None else out[:limit]


def _vector_slots(model) -> list:
    return [s for s in model.slots if s.chart.kind in ("free", "ball", "fixed")]


def _centre_params(model):
    """Parameters with every free / ball slot at its centre, the other slots at their random values."""
    p = model.random_params(np.random.default_rng(12345))
    for slot in model.slots:
        ch = slot.chart
        if ch.kind in ("free", "ball"):
            centre = np.zeros(ch.dim) if ch.kind == "free" else ch._c
            p[slot.start:slot.start + ch.nparams] = ch.inverse(centre)
        elif ch.kind == "cap":
            p[slot.start:slot.start + ch.nparams] = ch.inverse(ch._c)
    return p


def _place(model, p, slot, value) -> None:
    p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(np.asarray(value, dtype=float))


def _radius(chart) -> float:
    return chart._delta if chart.kind == "ball" else 1.0


def _eigen_starts(model, base) -> list:
    """Eigenvectors of the Hessian of lhs − rhs in the free / ball components at their centres."""
    slots = [s for s in _vector_slots(model) if s.chart.kind in ("free", "ball")]
    if not slots:
        return []
    z0 = [float(np.asarray(v, dtype=float).ravel()[0]) for v in model.zvalues(base.reshape(-1, 1))]
    index = {z: i for i, z in enumerate(model.zsyms)}
    comps = [index[z] for s in slots for z in s.z]
    d = len(comps)
    if d > 40:
        return []
    h = 1e-3 * max(1.0, min(_radius(s.chart) for s in slots))
    cols = [np.array(z0)]
    for i in range(d):
        for j in range(i, d):
            for si, sj in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                z = np.array(z0)
                z[comps[i]] += si * h
                z[comps[j]] += sj * h
                cols.append(z)
    Z = np.array(cols).T
    with np.errstate(all="ignore"):
        vals = np.broadcast_to(np.asarray(model._f(*Z)[0], dtype=float), (Z.shape[1],))
    if not np.all(np.isfinite(vals)):
        return []
    Hm, k = np.zeros((d, d)), 1
    for i in range(d):
        for j in range(i, d):
            pp, pm, mp, mm = vals[k:k + 4]
            k += 4
            Hm[i, j] = Hm[j, i] = (pp - pm - mp + mm) / (4 * h * h)
    if not np.any(Hm):
        return []
    w, V = np.linalg.eigh(Hm)
    out = []
    for col in np.argsort(-w)[:_DIRECTIONS]:
        v = V[:, col]
        parts, pos = [], 0
        for s in slots:
            parts.append(v[pos:pos + s.chart.dim])
            pos += s.chart.dim
        top = max(float(np.linalg.norm(q)) for q in parts) or 1.0
        for size in _SIZES:
            for sign in (1, -1):
                p = base.copy()
                for s, part in zip(slots, parts):
                    centre = np.zeros(s.chart.dim) if s.chart.kind == "free" else s.chart._c
                    _place(model, p, s, centre + sign * size * _radius(s.chart) * part / top)
                out.append(p)
    return out


def _history_slots(model):
    by_state: dict = {}
    for (st, k), slot in model.piece_slot.items():
        by_state.setdefault(st, {})[k] = slot
    return by_state


def _direction_value(chart, rng, size: float):
    """A value of the chart at relative ``size`` from its centre, in a random direction."""
    if chart.kind == "cap":
        psi = rng.uniform(0, 2 * math.pi)
        rho = chart._top * min(1.0, size)
        return math.cos(rho) * chart._c + math.sin(rho) * (math.cos(psi) * chart._e1 + math.sin(psi) * chart._e2)
    if chart.kind in ("free", "ball"):
        u = rng.normal(size=chart.dim)
        u = u / (np.linalg.norm(u) or 1.0)
        centre = np.zeros(chart.dim) if chart.kind == "free" else chart._c
        return centre + size * _radius(chart) * u
    return None


def _concentrated_starts(model, base, rng) -> list:
    """All pieces at the centre but the newest or the oldest (with the point values at the centre or random)."""
    out = []
    rand = model.random_params(rng)
    for st, pieces in _history_slots(model).items():
        for k in (len(pieces) - 1, 0):
            for points in (base, rand):
                p = points.copy()
                for j, slot in pieces.items():
                    p[slot.start:slot.start + slot.chart.nparams] = base[slot.start:slot.start + slot.chart.nparams]
                value = _direction_value(pieces[k].chart, rng, 1.0)
                if value is None:
                    continue
                _place(model, p, pieces[k], value)
                out.append(p)
    return out


def _profile_starts(model, base, rng) -> list:
    """Pieces along one direction with sizes σ^r or (1 − σ)^r, σ ∈ (0, 1) the position in the window."""
    out = []
    H = float(model.problem.H) or 1.0
    for st, pieces in _history_slots(model).items():
        ch = pieces[0].chart
        if ch.kind not in ("free", "ball", "cap"):
            continue
        u = rng.normal(size=ch.dim if ch.kind != "cap" else 2)
        for r in PROFILE_POWERS:
            for newest in (True, False):
                p = base.copy()
                for k, slot in pieces.items():
                    sigma = float(model.offsets[k] + model.offsets[k + 1]) / 2 / H   # 1: oldest, 0: newest
                    size = (1 - sigma) ** r if newest else sigma ** r
                    c = slot.chart
                    if c.kind == "cap":
                        psi = math.atan2(u[1], u[0])
                        rho = c._top * size
                        v = math.cos(rho) * c._c + math.sin(rho) * (math.cos(psi) * c._e1 + math.sin(psi) * c._e2)
                    elif c.kind in ("free", "ball"):
                        centre = np.zeros(c.dim) if c.kind == "free" else c._c
                        v = centre + size * _radius(c) * u / (np.linalg.norm(u) or 1.0)
                    else:
                        continue
                    _place(model, p, slot, v)
                out.append(p)
    return out


#: the most components and the largest expression (operations) of the exact eigenvector route
_EXACT_COMPONENTS = 24
_EXACT_OPS = 4000


def exact_eigen_points(model, digits: int = 50) -> list:
    """Exact admissible slot values (slot symbol → rational) at the top eigenvector of the quadratic form.

    Only when every slot is a vector (free, a ball, or fixed at its centre) and ``lhs − rhs`` at
    the base constants is a homogeneous quadratic form in the deviations w from the centres
    with numeric coefficients; the point is ``centre + s·v`` with v the eigenvector of the
    largest eigenvalue (if > 0) and s half the smallest ball radius (1 for free vectors).
    Empty otherwise.

    Examples
    --------
    >>> from lkverify import Equation, Parameters, System, Term, Vector, t
    >>> from lkverify.certify.steps.measures import norm_measure
    >>> from lkverify.certify.steps.witnesses import _Model, _Problem
    >>> P = Parameters(); x = Vector("x", 2); n = norm_measure("n", x(t))
    >>> sys_ = System([Equation(x, [Term(-x(t))])], parameters=P)
    >>> M = sympy.Matrix([[2, 1], [1, 2]])
    >>> gap = sympy.Rational(1, 10 ** 30)
    >>> model = _Model(_Problem((x(t).T * M * x(t))[0], (3 - gap) * n.symbol ** 2, sys_, {}, [n], None, (), ()), 1)
    >>> z = exact_eigen_points(model)[0]
    >>> sympy.expand(model.A.xreplace(z)) > 0                    # exactly, at a rational point
    True
    """
    import mpmath

    slots = model.slots
    if not slots or any(s.chart.kind not in ("free", "ball", "fixed") for s in slots):
        return []
    moving = [s for s in slots if s.chart.kind != "fixed"]
    zs = [z for s in moving for z in s.z]
    if not zs or len(zs) > _EXACT_COMPONENTS:
        return []
    centre, ws = {}, []
    for s in slots:
        c = [0] * s.chart.dim if s.chart.kind == "free" else list(s.chart.center)
        for z, ci in zip(s.z, c):
            if s.chart.kind == "fixed":
                centre[z] = sympy.sympify(ci)
            else:
                w = sympy.Dummy()
                ws.append(w)
                centre[z] = sympy.sympify(ci) + w
    A = model.A.xreplace(centre)
    if sympy.count_ops(A) > _EXACT_OPS:
        return []
    try:
        poly = sympy.Poly(sympy.expand(A), *ws)
    except sympy.PolynomialError:
        return []
    if poly.is_zero or poly.total_degree() != 2 or not poly.is_homogeneous:
        return []
    coeffs = [c for c in poly.coeffs()]
    if any(sympy.sympify(c).free_symbols for c in coeffs):
        return []
    k = len(ws)
    with mpmath.workdps(digits):
        Q = mpmath.matrix(k, k)
        for monom, c in poly.terms():
            idx = [i for i, e in enumerate(monom) for _ in range(e)]
            i, j = idx
            val = mpmath.mpf(str(sympy.N(c, digits + 10)))
            if i == j:
                Q[i, i] += val
            else:
                Q[i, j] += val / 2
                Q[j, i] += val / 2
        E, V = mpmath.eigsy(Q)
        top = max(range(k), key=lambda i: E[i])
        if not E[top] > 0:
            return []
        v = [V[i, top] for i in range(k)]
        pos, scale = 0, None
        for s in moving:
            part = v[pos:pos + s.chart.dim]
            pos += s.chart.dim
            size = mpmath.sqrt(sum(x ** 2 for x in part))
            radius = mpmath.mpf(1) if s.chart.kind == "free" else mpmath.mpf(str(sympy.N(s.chart.bound, digits))) / 2
            if size > 0:
                scale = radius / size if scale is None else min(scale, radius / size)
        w = [sympy.Rational(mpmath.nstr(scale * x, digits)) for x in v]
    point = {z: e.xreplace(dict(zip(ws, w))) for z, e in centre.items()}
    for s in moving:
        if s.chart.kind == "ball":
            d2 = sum((point[z] - c) ** 2 for z, c in zip(s.z, s.chart.center))
            if not bool(d2 <= sympy.sympify(s.chart.bound) ** 2):
                return []
    return [point]
