"""The model of the witness search: the claim on the piecewise-constant histories of one piece grid.

:class:`_Model` sums every window and memory integral exactly over the pieces, writes the claim
``lhs − rhs = A + Σ B_k c_k`` in one symbol per slot component, lambdifies it (vectorised over points)
for the optimiser, draws random and rotation starts, and gives the exact rational point of a candidate.
Split from :mod:`lkverify.certify.steps.witnesses`, which re-exports what is imported from it.
"""

from __future__ import annotations

import math

import numpy as np
import sympy
from sympy.core.function import AppliedUndef

from ...declare.functional import outer_integrals
from ...declare.symbols import t
from ...errors import InputError
from ...memo import Memo
from ..intervals.convert import enclose
from .measures import Measure
from .witness_charts import (_DENOMINATOR, _PREC, _TimeChart, UnsupportedClaim, _lt, _plane_rotation, _rotation_np,
                             _unit)
from .witness_problem import _U, MEMORY, _Integral, _Problem, _Slot, _evaluated, _newton_cotes, _short

#: integrand, variable, time → (atom → dummy, σ, antiderivative G) or None: SymPy's integrate is deterministic,
#: so a result is reused across claims (the dummies are private to the entry and substituted at every use)
_ANTIDERIVATIVES = Memo(512)


def integrate_factored(F, s, lo=None, hi=None):
    """∫F ds (from ``lo`` to ``hi`` when given), term by term with the factors free of s taken out first.

    The same value as ``sympy.integrate`` by linearity; SymPy's own integration is many times slower
    when the factors free of s (here: the states' values at a witness point, with their fractional
    powers) stay inside the integrand.

    >>> from sympy import exp, sqrt, symbols
    >>> s, a, t = symbols("s a t")
    >>> integrate_factored(3 * (a**2 + 1) ** sympy.Rational(13, 10) * exp(-2 * s + 2 * t) + a * s, s)
    a*s**2/2 - 3*(a**2 + 1)**(13/10)*exp(-2*s + 2*t)/2
    >>> integrate_factored(sqrt(2) * exp(-s), s, 0, 1)
    sqrt(2)*(1 - exp(-1))
    """
    limits = (s,) if lo is None else ((s, lo, hi),)
    out = []
    for term in sympy.Add.make_args(F):
        c, g = term.as_independent(s, as_Add=False)
        out.append(c * sympy.integrate(g, *limits))
    return sympy.Add(*out)

__all__: list = []  # internal: lkverify.certify.steps.witnesses (the search) re-exports _Model


class _Model:
    """The claim on the piecewise-constant histories with a given grid: exact and numeric forms."""

    def __init__(self, problem: _Problem, m: int, cse: bool = True):
        self.problem = problem
        self.m = m
        self.offsets = problem.offsets(m)
        self.npieces = len(self.offsets) - 1 if problem.history_states else 0
        # slots
        self.slots: list = []
        self.point_slot: dict = {}
        self.piece_slot: dict = {}
        count = [0, 0]

        def new_slot(st, where, chart):
            z = tuple(sympy.Symbol(f"_wz{count[0] + i}", real=True) for i in range(chart.dim))
            count[0] += chart.dim
            slot = _Slot(st, where, z, chart, count[1])
            count[1] += chart.nparams
            self.slots.append(slot)
            return slot

        for st in problem.states:
            for (s2, c) in sorted(problem.points, key=lambda k: (problem.states.index(k[0]), float(k[1]))):
                if s2 is st:
                    chart = problem.chart(st, problem.applicable(st, c, c == 0))
                    self.point_slot[(st, c)] = new_slot(st, ("point", c), chart)
            if st in problem.history_states:
                for k in range(self.npieces):
                    chart = problem.chart(st, problem.applicable(st, self.offsets[k], False))
                    self.piece_slot[(st, k)] = new_slot(st, ("piece", k), chart)
        self.time_slot = None
        if problem.time_range is not None:
            self.time_slot = new_slot(None, ("time", 0), _TimeChart(*problem.time_range))
        self.nparams = count[1]
        self.params = [sympy.Symbol(f"_wp{i}", real=True) for i in range(self.nparams)]
        self.free = np.zeros(self.nparams, dtype=bool)
        for slot in self.slots:
            if slot.chart.kind == "free":
                self.free[slot.start:slot.start + slot.chart.nparams] = True
        # the claim in the slot symbols
        self.point_map = {}
        for (st, c), slot in self.point_slot.items():
            for f, z in zip(st.functions, slot.z):
                self.point_map[f(t - c)] = z
            for atom in problem.points.get((st, c), ()):
                self.point_map[atom] = slot.z[[g for g in st.functions].index(atom.func)]
        self.measure_z = {m_.symbol: self._measure(m_) for m_ in problem.measures}
        self.terms_z = [(label, self._convert(e, f"lhs term {label!r}")) for label, e in problem.terms]
        self.rhs_z = self._convert(problem.rhs, "rhs")
        D = sympy.Add(*[e for _, e in self.terms_z]) - self.rhs_z
        # a positive constant (γ > 0) that divides lhs − rhs is factored out: the sign is the quotient's
        self.factors = []
        for c in problem.constants:
            if c.is_positive and D.xreplace({c: 0}) == 0 and not sympy.diff(D, c).has(c):
                self.factors.append(c)
                D = D.xreplace({c: 1})
        cs = self.rest = [c for c in problem.constants if c not in self.factors]
        #: the constants' values at which A, the terms and the sizes are taken (factors 1, the rest 0)
        self.base = {c: 1 for c in self.factors} | {c: 0 for c in cs}
        zero = self.base
        self.A = D.xreplace(zero)
        self.B = []
        for c in cs:
            b = sympy.diff(D, c)
            if b.free_symbols & set(cs):
                raise InputError(f"rhs: expected lhs − rhs affine in the constants {', '.join(map(str, cs))} "
                                 f"(exists= / nonnegative=), got the derivative {_short(b)} by {c}, which still "
                                 f"depends on {', '.join(sorted(str(x) for x in b.free_symbols & set(cs)))}; "
                                 f"write the bound affine in them (a common factor is divided out when its symbol "
                                 f"is positive, Symbol(..., positive=True))")
            self.B.append((c, b))
        self.B_active = [(c, b) for c, b in self.B if b != 0]
        # numeric forms
        outs = [self.A] + [b for _, b in self.B_active]
        zsyms = [z for slot in self.slots for z in slot.z]
        self.zsyms = zsyms
        # cse: common subexpressions found once make every evaluation cheaper but the build dearer (a cheap
        # search with few evaluations, the cross-examination, builds without)
        self._f = sympy.lambdify(zsyms, outs, modules="numpy", cse=cse, docstring_limit=0)
        # the sides' sizes Σ|term| + |rhs|, the absolute values taken numerically (SymPy's Abs of a large
        # expression costs seconds deciding its sign)
        parts = sympy.lambdify(zsyms, [e.xreplace(zero) for _, e in self.terms_z] + [self.rhs_z.xreplace(zero)],
                               modules="numpy", cse=cse, docstring_limit=0)
        self._size = lambda *z: sum(np.abs(np.asarray(v, dtype=float)) for v in parts(*z))
        self.scale = 1.0        # typical size of the objective (set by :meth:`calibrate`)
        self.tol = 1e-12        # improvements below this (in units of scale) are rounding noise

    # -- building -----------------------------------------------------------------------------
    def _pieces_in(self, h1, h2):
        """(k, σ_lo, σ_hi) of the pieces meeting the offsets [h2, h1]."""
        out = []
        for k in range(self.npieces):
            hi = self.offsets[k] if not _lt(h1, self.offsets[k]) else h1
            lo = self.offsets[k + 1] if _lt(h2, self.offsets[k + 1]) else h2
            if _lt(lo, hi):
                out.append((k, lo, hi))
        return out

    def _piece_map(self, st_atoms_var, k):
        rep = {}
        for atom in st_atoms_var:
            st, i = self.problem.funcs[atom.func]
            rep[atom] = self.piece_slot[(st, k)].z[i]
        return rep

    def _integral_sum(self, I: _Integral, where):
        var = I.var
        hist = [a for a in I.inner.atoms(AppliedUndef) if a.args[0] == var]
        sigma = sympy.Dummy("sigma")
        total = []
        for k, lo, hi in self._pieces_in(I.h1, I.h2):
            F = I.inner.xreplace(self._piece_map(hist, k)).xreplace(self.point_map)
            if self.problem.time is not None:
                F = F.xreplace({t: self.problem.time})
            if I.degree is None:
                G = self._antiderivative(I)
                if G is not None:        # one antiderivative for every piece (and every grid)
                    dummies, s_, g = G
                    rep = {d: (self.piece_slot[(self.problem.funcs[a.func][0], k)].z[self.problem.funcs[a.func][1]]
                               if a.args[0] == var else self.point_map.get(a, a)) for a, d in dummies.items()}
                    total.append((g.xreplace({s_: hi}) - g.xreplace({s_: lo})).xreplace(rep))
                    continue
                val = integrate_factored(F.xreplace({var: t - sigma}), sigma, lo, hi)
                if val.has(sympy.Integral):
                    raise UnsupportedClaim(f"{where}: the weight of {_short(I.node)} could not be integrated "
                                           f"exactly over a piece; use a polynomial weight in {var}")
                total.append(val)
                continue
            nodes, weights = _newton_cotes(I.degree)
            length = hi - lo
            total.append(length * sympy.Add(*[w * F.xreplace({var: t - (lo + length * x)})
                                              for x, w in zip(nodes, weights)]))
        return sympy.Add(*total)

    def _kernel_mass(self, name, lo, hi):
        """∫_lo^hi κ(u) du exactly, from one antiderivative of the kernel (cached on the problem)."""
        cache = self.problem.__dict__.setdefault("_kernel_antiderivatives", {})
        kern = self.problem.kernels[name](_U)
        if name not in cache:
            try:
                K = sympy.integrate(kern, _U)
            except RecursionError:  # SymPy's meijerint on an unusual kernel
                K = None
            cache[name] = None if K is None or K.has(sympy.Integral) or K.has(sympy.Piecewise) else K
        K = cache[name]
        if K is None:
            return sympy.Integral(kern, (_U, lo, hi))
        return K.subs(_U, hi) - K.subs(_U, lo)

    def _antiderivative(self, I: _Integral):
        """``(atom → dummy, σ, G)`` with G(σ) an antiderivative of the integrand at ξ = t − σ in dummies for the
        states (cached on the problem), or None when SymPy finds none."""
        cache = self.problem.__dict__.setdefault("_antiderivatives", {})
        if I.node not in cache:
            # the same integrand recurs in every step of a chain (and every grid): SymPy's integrate once per process
            key = (I.inner, I.var, self.problem.time)
            if key in _ANTIDERIVATIVES:
                cache[I.node] = _ANTIDERIVATIVES[key]
                return cache[I.node]
            dummies = {a: sympy.Dummy(real=True) for a in I.inner.atoms(AppliedUndef)}
            sigma = sympy.Dummy("sigma")
            F = _evaluated(I.inner.xreplace(dummies))
            if self.problem.time is not None:
                F = F.xreplace({t: self.problem.time})
            try:
                g = integrate_factored(F.xreplace({I.var: t - sigma}), sigma)
            except RecursionError:  # SymPy's meijerint on an unusual integrand: summed piece by piece instead
                g = sympy.Integral(F, sigma)
            cache[I.node] = None if g.has(sympy.Integral) or g.has(sympy.Piecewise) else (dummies, sigma, g)
            _ANTIDERIVATIVES[key] = cache[I.node]
        return cache[I.node]

    def _time_value(self):
        """What t becomes: the given time, the time slot's symbol, or 0 (autonomous claims)."""
        if self.time_slot is not None:
            return self.time_slot.z[0]
        return self.problem.time if self.problem.time is not None else sympy.Integer(0)

    def _convert(self, expr, where):
        rep = {node: self._integral_sum(self.problem.integrals[node], where) for node in outer_integrals(expr)}
        out = expr.xreplace(rep).xreplace(self.point_map).xreplace(self.measure_z)
        if out.has(t):
            if self.problem.time is None and self.problem.time_range is None:
                self._time_check(out, where)
            out = out.xreplace({t: self._time_value()})
        return out

    def _time_check(self, expr, where):
        """Raise InputError unless ``expr`` (in the slot symbols and t) is independent of t numerically."""
        syms = sorted(expr.free_symbols - {t}, key=lambda s: s.name)
        f = sympy.lambdify(syms + [t], expr, modules="numpy")
        rng = np.random.default_rng(1)
        for _ in range(3):
            p = rng.normal(size=len(syms)) * 0.3
            with np.errstate(all="ignore"):
                a, b = complex(f(*p, 0.0)), complex(f(*p, 0.731))
            if abs(a - b) > 1e-9 * (1 + abs(a)):
                raise InputError(f"{where}: expected an autonomous claim (t only through t − ξ and delays), got an "
                                 f"explicit dependence on t (a time-varying coefficient such as h(t)); pass the "
                                 f"witness time: time=1 (a number) or time=(lo, hi) to search it")

    def _measure(self, m: Measure):
        vec, window, power = self.problem.mdata[m.name]
        if m.kind == "norm":
            return sympy.sqrt(sympy.Add(*[c ** 2 for c in vec.xreplace(self.point_map)]))
        xs = [a for a in vec.atoms(AppliedUndef)]
        states = {self.problem.funcs[a.func][0] for a in xs}
        if m.kind == "sup":
            cands = []
            for k, lo, hi in self._pieces_in(window, 0):
                if all((st, k) in self.piece_slot for st in states):
                    v = vec.xreplace(self._piece_map(xs, k))
                    cands.append(sympy.sqrt(sympy.Add(*[c ** 2 for c in v])))
            for (st, c), slot in self.point_slot.items():
                if st in states and not _lt(window, c) and all((s2, c) in self.point_slot for s2 in states):
                    rep = {a: self.point_slot[(self.problem.funcs[a.func][0], c)].z[self.problem.funcs[a.func][1]]
                           for a in xs}
                    cands.append(sympy.sqrt(sympy.Add(*[e ** 2 for e in vec.xreplace(rep)])))
            cands = list(dict.fromkeys(cands))
            return cands[0] if len(cands) == 1 else sympy.Max(*cands, evaluate=False)
        total = []
        for k, lo, hi in self._pieces_in(window, 0):
            v = vec.xreplace(self._piece_map(xs, k))
            weight = hi - lo
            if m.kind == MEMORY:     # ∫ κ(u) du over the piece's offsets u = t − ξ ∈ [lo, hi], exactly
                weight = self._kernel_mass(m.name, lo, hi)
                if weight.has(sympy.Integral):
                    raise UnsupportedClaim(f"measure {m.name}: its kernel could not be integrated exactly over a "
                                           f"piece")
            total.append(weight * sympy.Pow(sympy.Add(*[c ** 2 for c in v]), power / 2))
        integral = sympy.Add(*total)
        return integral if m.kind in ("window_integral", MEMORY) else sympy.Pow(integral, 1 / power)

    # -- numeric ------------------------------------------------------------------------------
    def zvalues(self, P: np.ndarray) -> list:
        """The slot values for parameter columns ``P`` (shape (nparams, N))."""
        n = P.shape[1]
        out = []
        for slot in self.slots:
            vals = slot.chart.numeric(P[slot.start:slot.start + slot.chart.nparams])
            out.extend(np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in vals)
        return out

    def objective(self, P: np.ndarray) -> np.ndarray:
        """``min(A, B_k…)`` (to be maximised), per column of ``P``; −inf where undefined."""
        n = P.shape[1]
        with np.errstate(all="ignore"):
            outs = self._f(*self.zvalues(P))
            vals = np.min(np.array([np.broadcast_to(np.asarray(o, dtype=float), (n,)) for o in outs]), axis=0)
            if self.free.any():
                vals = vals / (1 + np.sum(P[self.free] ** 2, axis=0)) ** 2   # same sign, bounded for degree < 4
        vals = np.where(np.isfinite(vals), vals, -np.inf)
        return vals

    def calibrate(self, rng, n: int = 16) -> None:
        """Set :attr:`scale` and :attr:`tol` from the objective and the sides' sizes at random points."""
        P = np.array([self.random_params(rng) for _ in range(n)]).T.reshape(self.nparams, n)
        vals = self.objective(P)
        with np.errstate(all="ignore"):
            sizes = np.broadcast_to(np.asarray(self._size(*self.zvalues(P)), dtype=float), (n,))
        vals, sizes = np.abs(vals[np.isfinite(vals)]), sizes[np.isfinite(sizes)]
        noise = 1e-14 * (float(np.median(sizes)) if sizes.size else 1.0)
        typical = float(np.median(vals)) if vals.size else 0.0
        self.scale = max(typical, 1e3 * noise, 1e-300)
        self.tol = max(1e-12, 10 * noise / self.scale)

    def locally_positive(self, p: np.ndarray) -> bool:
        """The objective at ``p`` exceeds float noise relative to the sides' sizes *at p* (a small history)."""
        P = np.asarray(p, dtype=float).reshape(self.nparams, 1)
        with np.errstate(all="ignore"):
            val = min(float(np.asarray(o, dtype=float).ravel()[0]) for o in self._f(*self.zvalues(P)))
            size = float(np.asarray(self._size(*self.zvalues(P)), dtype=float).ravel()[0])
        return bool(np.isfinite(val) and np.isfinite(size) and val > 1e-12 * size and val > 0)

    def random_params(self, rng) -> np.ndarray:
        p = np.zeros(self.nparams)
        for slot in self.slots:
            p[slot.start:slot.start + slot.chart.nparams] = slot.chart.random(rng)
        return p

    def rotation_params(self, rng) -> np.ndarray:
        """A start whose history pieces follow a rotation of the value at t."""
        p = self.random_params(rng)
        H = float(self.problem.H) or max([float(c) for _, c in self.point_slot] + [1.0])
        for st in self.problem.rotating:
            s0 = self.point_slot.get((st, 0))
            first = s0 or self.piece_slot.get((st, self.npieces - 1)) or next(
                slot for (s2, _), slot in self.point_slot.items() if s2 is st)
            ch = first.chart
            if ch.kind == "frame":
                self._frame_rotation(st, first, p, rng, H)
                continue
            if ch.kind == "cap" and rng.random() < 0.4:
                p[first.start:first.start + 2] = [0.0, rng.uniform(0, 2 * math.pi)]
            v0 = ch.value(p[first.start:first.start + ch.nparams])
            if st.dim == 1:
                profile = rng.uniform(-1, 1, size=1)
                for k in range(self.npieces):
                    slot = self.piece_slot[(st, k)]
                    v = v0 * (1 + profile[0] * rng.random())
                    p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(v)
                continue
            center = getattr(ch, "_c", None)
            if center is not None and rng.random() < 0.6 and np.linalg.norm(center) > 0:
                a = center / np.linalg.norm(center)
            else:
                a = _unit(rng, st.dim)
            b = _unit(rng, st.dim)
            b = b - (b @ a) * a
            b = b / (np.linalg.norm(b) or 1.0)
            mode = int(rng.integers(0, 4))
            pieces_chart = (self.piece_slot.get((st, 0)) or first).chart
            top = getattr(pieces_chart, "_top", math.pi)
            amp = rng.uniform(0.3, 1.6) * (top if st.unit else math.pi) * rng.choice([-1, 1])

            def phi(sig):
                return amp * (sig, math.sin(math.pi * sig), math.sin(2 * math.pi * sig), sig ** 2)[mode]

            def place(slot, sig):
                v = _plane_rotation(v0, a, b, phi(sig))
                p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(v)

            for k in range(self.npieces):
                sig = float(self.offsets[k] + self.offsets[k + 1]) / 2 / H
                place(self.piece_slot[(st, k)], sig)
            for (s2, c), slot in self.point_slot.items():
                if s2 is st and c != 0 and float(c) <= H:
                    place(slot, float(c) / H)
        return p

    def _frame_rotation(self, st, first, p, rng, H) -> None:
        """Rotation start of a frame: the pieces are the triad at t turned about one axis by φ(σ)."""
        ch = first.chart
        if rng.random() < 0.4:
            p[first.start] = 0.0                                  # the value at t: the reference triad
        T0 = ch.value(p[first.start:first.start + ch.nparams]).reshape(3, 3).T
        a = ch._R0[:, int(rng.integers(0, 3))] if rng.random() < 0.6 else _unit(rng, 3)
        mode = int(rng.integers(0, 5))
        amp = rng.uniform(0.3, 1.6) * ch._top * rng.choice([-1, 1])

        def place(slot, sig):
            # profiles of the angle along the window; the last turns t and the oldest time oppositely
            phi = amp * (sig, math.sin(math.pi * sig), math.sin(2 * math.pi * sig), sig ** 2, sig - 0.5)[mode]
            T = _rotation_np(a, phi) @ T0
            p[slot.start:slot.start + slot.chart.nparams] = slot.chart.inverse(T.T.reshape(-1))

        if mode == 4 and first.where == ("point", 0):
            place(first, 0.0)
        for k in range(self.npieces):
            place(self.piece_slot[(st, k)], float(self.offsets[k] + self.offsets[k + 1]) / 2 / H)
        for (s2, c), slot in self.point_slot.items():
            if s2 is st and c != 0 and float(c) <= H:
                place(slot, float(c) / H)

    # -- exact -----------------------------------------------------------------------------------
    def exact_point(self, p: np.ndarray, denominator: int = _DENOMINATOR):
        """``(records, zexact, zballs)`` at the exact point near ``p``: slot label → exact parameters
        (strings), slot symbol → exact value and → its arb ball."""
        records, zexact, zballs = {}, {}, {}
        for slot in self.slots:
            record, vals = slot.chart.exact(p[slot.start:slot.start + slot.chart.nparams], denominator)
            records[slot.label] = record
            for z, v in zip(slot.z, vals):
                zexact[z] = v
                zballs[z] = enclose(v, prec=_PREC)
        return records, zexact, zballs
