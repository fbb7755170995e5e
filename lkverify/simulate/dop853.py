"""The compiled DOP853 method of steps: the one integrator of :func:`~lkverify.simulate.runs.simulate` and the sweeps.

:func:`run_batch` integrates every point of a batch, one after the other, with generated native
functions ``rhs(t, y, Z, p, out)`` and ``win(t, y, Z, p, g)`` (:mod:`lkverify.simulate.native`,
signature :data:`FUNCTION`: pointers, ``Z`` flat) passed as numba first-class functions, so this
kernel is compiled once per machine (numba's disk cache) whatever the system.
:func:`lkverify.simulate.batch.integrate` prepares its arguments and is the API; this module is
numba code only (editing it recompiles the kernel: ``benchmarks/bench_compile.py``).

Method (per point; the method of :func:`lkverify.simulate.solver.solve_dde` with SciPy's DOP853, compiled)
----------------------------------------------------------------------------------------------------------
* Dormand–Prince 8(5,3) with the tableau, the error estimate, the step-size control and the
  7th-order dense output of :class:`scipy.integrate.DOP853` (read from that class's attributes);
  the first step is SciPy's ``select_initial_step`` (error order 7), computed by the caller
  (:func:`lkverify.simulate.batch.first_steps`: it keeps this kernel, and its compile time,
  smaller); steps below 10 units in the last place of t fail as SciPy's do.
* Every step is at most ``min(hcap, lags)`` long, so every delayed stage value
  ``y(t_n + c h − lag)`` lies in the accepted history: the constant initial history for
  arguments ≤ t0 (or before the first step), else the dense output of the accepted step
  containing it (a moving pointer; steps older than the longest lag are dropped unless stored).
* Steps land on the breakpoints (``targets``); there the step size proposed before the landing
  step is kept if larger, as ``solve_dde`` restarts SciPy's stepper.
* Window auxiliary states ``z_j = ∫_{t−c}^t g_j(x)`` (``wk[j] = (component, lag index)``) are
  integrated as ``ż = g(x(t)) − g(x(t−c))`` and re-synchronised after every accepted step by
  quadrature over the accepted history, as ``simulate`` does: 8-point Gauss–Legendre on every
  step piece (per-step integrals kept, the piece at the window's left end integrated anew), the
  constant history exactly; the step's dense output gets the linear ramp of the correction and
  the derivative is re-evaluated (SciPy's FSAL value follows the new state).

Outcome codes: :data:`OUTCOMES` (see :mod:`lkverify.simulate.batch`).

>>> import numpy as np
>>> from lkverify.simulate.native import native_source, load
>>> import sympy
>>> z = sympy.Symbol("Z_0_0"); fn = load(native_source({"rhs": [-z], "win": []}, {z: ("Z", 0)}))
>>> out = np.full((1, 2, 1), np.nan); code = np.zeros(1, dtype=np.int64); t_fail = np.zeros(1)
>>> stats = np.zeros((1, 4), dtype=np.int64)
>>> run_batch(fn["rhs"], fn["win"], np.zeros((1, 1)), np.array([[1.0]]), np.array([1.0]), np.array([[1.0]]),
...           np.zeros((0, 2), dtype=np.int64), np.array([[1.0, 2.0]]), np.array([2]), 0.0, np.array([1.0, 2.0]),
...           1e-8, 1e-10, np.inf, 1e8, 1000, 2e-7, np.zeros(1, dtype=np.int64), np.array([1e-3]), out, code, t_fail, stats,
...           np.zeros(1), np.zeros((0, 8, 1)))
>>> OUTCOMES[code[0]].value, (out[0, :, 0].round(10) + 0.0).tolist()       # x = 1 − t, then 1 − t + (t − 1)²/2
('success', [0.0, -0.5])
"""

from __future__ import annotations

import math

import numba
import numba.experimental.function_type  # noqa: F401 - registers numba's typing of WrapperAddressProtocol objects
import numpy as np
from numba import types
from numba.extending import intrinsic
from scipy.integrate import DOP853

from .events import BLOWUP_GROWTH, FLOOR_WINDOW
from .solver import Outcome

__all__ = ["FUNCTION", "OUTCOMES", "run_batch"]

#: outcome code → Outcome
OUTCOMES = tuple(Outcome)
_SUCCESS, _DIVERGED, _COLLAPSE, _BUDGET = (OUTCOMES.index(o) for o in
                                           (Outcome.SUCCESS, Outcome.DIVERGED, Outcome.STEP_COLLAPSE, Outcome.BUDGET))

_f8, _i8, _p8 = types.float64, types.int64, types.CPointer(types.float64)
_vec, _mat, _cube = types.float64[::1], types.float64[:, ::1], types.float64[:, :, ::1]
#: the generated functions: f(t, y*, Z*, p*, out*) (:data:`lkverify.simulate.native.NATIVE_SIGNATURE`)
FUNCTION = types.FunctionType(types.void(_f8, _p8, _p8, _p8, _p8))

# -- SciPy's DOP853 (class attributes of scipy.integrate.DOP853) ------------------------------------
_NS = DOP853.n_stages                                  # 12 stages; K[12] = f(t + h, y_new); K[13:16] dense extras
_A = np.ascontiguousarray(DOP853.A, dtype=float)
_B = np.ascontiguousarray(DOP853.B, dtype=float)
_C = np.ascontiguousarray(DOP853.C, dtype=float)
_E3 = np.ascontiguousarray(DOP853.E3, dtype=float)
_E5 = np.ascontiguousarray(DOP853.E5, dtype=float)
_D = np.ascontiguousarray(DOP853.D, dtype=float)       # (4, 16)
_AX = np.ascontiguousarray(DOP853.A_EXTRA, dtype=float)   # (3, 16)
_CX = np.ascontiguousarray(DOP853.C_EXTRA, dtype=float)
_EXPONENT = -1.0 / (DOP853.error_estimator_order + 1)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0      # scipy.integrate._ivp.rk
_GROWTH = float(BLOWUP_GROWTH)
_WINDOW = int(FLOOR_WINDOW)
_GX, _GW = (np.ascontiguousarray(a) for a in np.polynomial.legendre.leggauss(8))
# every stage in one table: row 0 f(t, y) (a refresh), rows 1 … 11 A, row 12 B (the new state, at t + h),
# rows 13 … 15 the dense output's extra stages; _ROW[st] the stages row st combines
_T = np.zeros((16, 16))
_T[1:_NS, :_NS] = _A[1:]
_T[_NS, :_NS] = _B
_T[_NS + 1:, :] = _AX
_TC = np.concatenate(([0.0], _C[1:], [1.0], _CX))
_ROW = np.array([0, *range(1, _NS + 1), _NS + 1, _NS + 2, _NS + 3], dtype=np.int64)

_KERNEL = types.void(FUNCTION, FUNCTION, _mat, _mat, _vec, _mat, types.int64[:, ::1], _mat, types.int64[::1], _f8,
                     _vec, _f8, _f8, _f8, _f8, _i8, _f8, types.int64[::1], _vec, _cube, types.int64[::1], _vec,
                     types.int64[:, ::1], _vec, _cube)


@intrinsic
def _ptr(typingctx, arr):
    """The data pointer of a C-contiguous float64 array (for the native functions)."""
    def codegen(context, builder, signature, args):
        return context.make_array(arr)(context, builder, args[0]).data

    return types.CPointer(arr.dtype)(arr), codegen


@numba.njit(_KERNEL, cache=True, error_model="numpy")
def run_batch(rhs, win, P, Y0, x0, lags, wk, targets, counts, t0, t_eval, rtol, atol, hcap, bound, max_steps,
              floor, skip, H0, out, code, t_fail, stats, store_t, store_c):
    """Every point ``i`` with ``skip[i] == 0``, one after the other.

    ``P`` (N, k) the points, ``Y0`` (N, n) initial vectors (auxiliary states included), ``x0`` (n_states,)
    the constant history, ``lags`` (N, n_lags), ``wk`` (n_windows, 2) the windows' (component, lag index),
    ``targets[i, :counts[i]]`` the breakpoints of point i then t_end, ``hcap`` the largest step asked for,
    ``H0`` the first step of every point (:func:`lkverify.simulate.batch.first_steps`; negative: f(t0, y0) is
    not finite, the point ``diverged`` at t0).
    Writes the samples at ``t_eval`` into ``out`` (N, m, n_states; untouched after a failure), the outcome
    codes into ``code``, the end or failure time into ``t_fail``, (accepted steps, rhs evaluations, rejected
    steps, stored steps) into ``stats``.  With ``store_c`` of shape (S, 8, n), S > 0, the accepted steps of
    point 0 are stored: ``[store_t[j], store_t[j + 1]]`` and its dense coefficients (y_old, F0 … F6 of
    SciPy's ``Dop853DenseOutput``); more than S steps end the run as ``budget`` with ``stats[0, 3] = -1``.

    One function, no helpers (helpers cost numba compile time: measured 12.4 s against 3.8 s on the
    DOPRI5 kernel this one replaced); a
    point's run ends by setting ``outcome`` (≥ 0) and leaving the step loop.
    """
    n, ns, nl, n_eval, nw = Y0.shape[1], x0.shape[0], lags.shape[1], t_eval.shape[0], wk.shape[0]
    n_store = store_c.shape[0]
    for pt in range(P.shape[0]):
        if skip[pt]:
            continue
        p, lag, o = P[pt], lags[pt], out[pt]
        keep = n_store > 0 and pt == 0
        n_targets = counts[pt]
        t_end = targets[pt, n_targets - 1]
        hmax, lag_max = min(hcap, t_end - t0), 0.0
        for k in range(nl):
            hmax = min(hmax, lag[k])
            lag_max = max(lag_max, lag[k])
        # accepted steps: start Ht, length Hh, dense coefficients C (y_old, F0..F6) of all n components,
        # and the Gauss–Legendre integral G of every window integrand over the step; m of them, room for cap
        cap, m, stored = 64, 0, 0
        Ht, Hh, C, G = np.empty(cap), np.empty(cap), np.empty((cap, 8, n)), np.empty((cap, max(nw, 1)))
        hint = np.empty(max(nl, 1), dtype=np.int64)
        for k in range(nl):
            hint[k] = 0
        Z = np.empty(max(nl * ns, 1))
        K = np.empty((16, n))
        y, yn, yt = np.empty(n), np.empty(n), np.empty(n)
        g, gsum, xs = np.empty(max(nw, 1)), np.empty(max(nw, 1)), np.empty(max(ns, 1))
        gx0 = np.empty(max(nw, 1))
        gx0[0] = 0.0
        for i in range(ns):
            xs[i] = x0[i]
        if nw:
            win(t0, _ptr(xs), _ptr(Z), _ptr(p), _ptr(gx0))
        yy = 0.0
        for i in range(n):
            y[i] = Y0[pt, i]
            yy += y[i] * y[i]
        ke = 0
        while ke < n_eval and t_eval[ke] <= t0:
            for i in range(ns):
                o[ke, i] = y[i]
            ke += 1
        outcome, t, n_steps, nfev, n_rej = -1, t0, 0, 0, 0
        for k in range(nl):          # before the first step every delayed argument is history
            for i in range(ns):
                Z[k * ns + i] = x0[i]
        if not yy <= bound * bound:
            outcome = _DIVERGED
        else:
            rhs(t0, _ptr(y), _ptr(Z), _ptr(p), _ptr(K[0]))
            nfev = 1
        it, h_abs, h_next = 0, 0.0, -1.0
        if outcome < 0:
            h_abs = min(H0[pt], hmax)           # SciPy's select_initial_step, computed by the caller
            if H0[pt] < 0.0:                     # f(t0, y0) not finite
                outcome = _DIVERGED
            scale = max(1.0, math.sqrt(yy))
            recent = np.empty(_WINDOW)
            for i in range(_WINDOW):
                recent[i] = 0.0
            recent_sum = 0.0
            bad = False
        refresh = False        # K[0] to re-evaluate at the step's start (a re-synchronised state)
        while outcome < 0:
            target = targets[pt, it]
            # SciPy's 10·|nextafter(t, ∞) − t|: ten units in the last place of t (the spacing above t)
            fr, ex = math.frexp(t)
            min_step = 10.0 * max(math.ldexp(1.0, ex - 53), 5e-324)
            if fr == -0.5:                              # t = −2^k: the spacing above it is the finer one
                min_step *= 0.5
            if h_abs > hmax:
                h_abs = hmax
            elif h_abs < min_step:
                h_abs = min_step
            rejected, accepted, new_h = False, False, True
            h, t_new = 0.0, t
            # the stages of one table (_T, _TC): 0 = f(t, y) when refreshed, 1 … 11, 12 = f(t + h, y_new) with
            # the error estimate (a rejection goes back to stage 1 with a smaller step), 13 … 15 the dense output's
            st = 0 if refresh else 1
            while True:
                if new_h:
                    if h_abs < min_step:
                        break
                    t_new = t + h_abs
                    if t_new > target:
                        t_new = target
                    h = t_new - t
                    h_abs = abs(h)
                    new_h = False
                s = t + _TC[st] * h
                for i in range(n):
                    acc = 0.0
                    for j in range(_ROW[st]):
                        acc += _T[st, j] * K[j, i]
                    yt[i] = y[i] + h * acc
                for k in range(nl):      # Z[k] = y(s − lag_k): history, or the stored step containing it
                    q = s - lag[k]
                    if q <= t0 or m == 0:
                        for i in range(ns):
                            Z[k * ns + i] = x0[i]
                        continue
                    j = min(hint[k], m - 1)
                    while j + 1 < m and Ht[j + 1] <= q:
                        j += 1
                    while j > 0 and Ht[j] > q:
                        j -= 1
                    hint[k] = j
                    x = (q - Ht[j]) / Hh[j]
                    x1 = 1.0 - x
                    for i in range(ns):
                        Z[k * ns + i] = C[j, 0, i] + x * (C[j, 1, i] + x1 * (C[j, 2, i] + x * (C[j, 3, i] + x1 * (
                            C[j, 4, i] + x * (C[j, 5, i] + x1 * (C[j, 6, i] + x * C[j, 7, i]))))))
                rhs(s, _ptr(yt), _ptr(Z), _ptr(p), _ptr(K[st]))
                nfev += 1
                if st == _NS:
                    e5, e3 = 0.0, 0.0
                    for i in range(n):
                        yn[i] = yt[i]
                        a5, a3 = 0.0, 0.0
                        for j in range(_NS + 1):
                            a5 += _E5[j] * K[j, i]
                            a3 += _E3[j] * K[j, i]
                        sk = atol + max(abs(y[i]), abs(yn[i])) * rtol
                        e5 += (a5 / sk) ** 2
                        e3 += (a3 / sk) ** 2
                    err = 0.0 if (e5 == 0.0 and e3 == 0.0) else h_abs * e5 / math.sqrt((e5 + 0.01 * e3) * n)
                    if err < 1.0:
                        factor = _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err ** _EXPONENT)
                        if rejected:
                            factor = min(1.0, factor)
                        h_abs *= factor
                        accepted, bad = True, False
                    else:
                        factor = _SAFETY * err ** _EXPONENT
                        if not factor > _MIN_FACTOR:       # also NaN: Python's max(0.2, nan) is 0.2
                            factor = _MIN_FACTOR
                        h_abs *= factor
                        rejected, new_h = True, True
                        n_rej += 1
                        bad = bad or not math.isfinite(err)
                        st = 1
                        continue
                if st == 15:
                    break
                st += 1
            refresh = False
            if not accepted:
                outcome = _DIVERGED if bad else _COLLAPSE
                break
            n_steps += 1
            # store the step; when full, drop the steps before t − lag_max (keeping the one containing it and
            # one before), into arrays twice as long if more than half would stay
            if m == cap:
                j = 0
                while j + 2 < m and Ht[j + 2] <= t - lag_max:
                    j += 1
                Ht2, Hh2, C2, G2 = Ht, Hh, C, G
                if m - j > cap // 2:
                    cap *= 2
                    Ht2, Hh2, C2, G2 = np.empty(cap), np.empty(cap), np.empty((cap, 8, n)), np.empty((cap, max(nw, 1)))
                m -= j
                for r in range(m):
                    Ht2[r] = Ht[j + r]
                    Hh2[r] = Hh[j + r]
                    for c in range(8):
                        for i in range(n):
                            C2[r, c, i] = C[j + r, c, i]
                    for c in range(nw):
                        G2[r, c] = G[j + r, c]
                for k in range(nl):
                    hint[k] = max(0, hint[k] - j)
                Ht, Hh, C, G = Ht2, Hh2, C2, G2
            Ht[m] = t
            Hh[m] = h
            for i in range(n):
                d = yn[i] - y[i]
                C[m, 0, i] = y[i]
                C[m, 1, i] = d
                C[m, 2, i] = h * K[0, i] - d
                C[m, 3, i] = 2.0 * d - h * (K[_NS, i] + K[0, i])
                for r in range(4):
                    acc = 0.0
                    for j in range(16):
                        acc += _D[r, j] * K[j, i]
                    C[m, 4 + r, i] = h * acc
            m += 1
            if nw:
                # z_j = ∫_{t_new − c_j}^{t_new} g_j: the constant history, the piece of the step containing the
                # window's left end, the whole steps after it (their 8-point Gauss–Legendre integrals G, the new
                # step's computed here: nodes 0–7 of the loop below, the left-end pieces nodes 8–15)
                for c in range(nw):
                    G[m - 1, c] = 0.0
                    gsum[c] = 0.0
                moved, j0, a, end, first = False, 0, 0.0, 0.0, 0
                for c in range(-1, nw):
                    if c >= 0:
                        a = t_new - lag[wk[c, 1]]
                        if a < t0:
                            gsum[c] = (t0 - a) * gx0[c]
                            first = 0
                            continue
                        j0 = m - 1
                        while j0 > 0 and Ht[j0] > a:
                            j0 -= 1
                        first = j0 + 1
                        end = Ht[j0] + Hh[j0]
                        if not end > a:
                            continue
                    for r in range(8):
                        if c < 0:
                            j, sr, wr = m - 1, t + 0.5 * (1.0 + _GX[r]) * h, 0.5 * h * _GW[r]
                        else:
                            j, sr, wr = j0, 0.5 * (a + end) + 0.5 * (end - a) * _GX[r], 0.5 * (end - a) * _GW[r]
                        x = (sr - Ht[j]) / Hh[j]
                        x1 = 1.0 - x
                        for i in range(ns):
                            xs[i] = C[j, 0, i] + x * (C[j, 1, i] + x1 * (C[j, 2, i] + x * (C[j, 3, i] + x1 * (
                                C[j, 4, i] + x * (C[j, 5, i] + x1 * (C[j, 6, i] + x * C[j, 7, i]))))))
                        win(sr, _ptr(xs), _ptr(Z), _ptr(p), _ptr(g))
                        if c < 0:
                            for cc in range(nw):
                                G[m - 1, cc] += wr * g[cc]
                        else:
                            gsum[c] += wr * g[c]
                    if c >= 0:
                        total = gsum[c]
                        for j in range(first, m):
                            total += G[j, c]
                        comp = wk[c, 0]
                        delta = total - yn[comp]
                        if delta != 0.0:
                            moved = True
                            yn[comp] = total
                            C[m - 1, 1, comp] += delta       # the ramp delta·x on the step's dense output
                refresh = moved                              # the derivative follows the new state
            if keep:
                if stored == n_store:
                    stored = -1
                    outcome = _BUDGET
                    break
                store_t[stored] = t
                store_t[stored + 1] = t_new
                for c in range(8):
                    for i in range(n):
                        store_c[stored, c, i] = C[m - 1, c, i]
                stored += 1
            yy = 0.0
            for i in range(n):
                yy += yn[i] * yn[i]
            while ke < n_eval and t_eval[ke] <= t_new:
                x = (t_eval[ke] - t) / h
                x1 = 1.0 - x
                for i in range(ns):
                    o[ke, i] = C[m - 1, 0, i] + x * (C[m - 1, 1, i] + x1 * (C[m - 1, 2, i] + x * (
                        C[m - 1, 3, i] + x1 * (C[m - 1, 4, i] + x * (C[m - 1, 5, i] + x1 * (
                            C[m - 1, 6, i] + x * C[m - 1, 7, i]))))))
                ke += 1
            if not yy <= bound * bound:
                # the first time in [t, t + h] where ‖y‖ reaches bound on the step's dense output (bisection);
                # t + h if ‖y_new‖ is not finite
                outcome = _DIVERGED
                if math.isfinite(yy):
                    lo, hi = 0.0, 1.0
                    for _ in range(60):
                        x = 0.5 * (lo + hi)
                        x1 = 1.0 - x
                        vv = 0.0
                        for i in range(n):
                            v = C[m - 1, 0, i] + x * (C[m - 1, 1, i] + x1 * (C[m - 1, 2, i] + x * (
                                C[m - 1, 3, i] + x1 * (C[m - 1, 4, i] + x * (C[m - 1, 5, i] + x1 * (
                                    C[m - 1, 6, i] + x * C[m - 1, 7, i]))))))
                            vv += v * v
                        if vv > bound * bound:
                            hi = x
                        else:
                            lo = x
                    t += hi * h
                else:
                    t = t_new
                break
            for i in range(n):
                y[i] = yn[i]
                K[0, i] = K[_NS, i]
            slot = n_steps % _WINDOW
            recent_sum += h - recent[slot]
            recent[slot] = h
            landing = t_new == target
            t = t_new
            # the restart guess at a breakpoint: the step proposed before the landing step, if larger
            h_next = h_abs if (not landing or h_next < 0.0) else max(h_next, h_abs)
            if landing:
                it += 1
                if it == n_targets:
                    outcome = _SUCCESS
                    break
                h_abs = min(min(h_next, hmax), targets[pt, it] - t)
            if n_steps >= _WINDOW and recent_sum / _WINDOW < floor:
                outcome = _DIVERGED if math.sqrt(yy) > _GROWTH * scale else _COLLAPSE
                break
            if n_steps >= max_steps:
                outcome = _BUDGET
                break
        code[pt], t_fail[pt] = outcome, t
        stats[pt, 0], stats[pt, 1], stats[pt, 2], stats[pt, 3] = n_steps, nfev, n_rej, stored
