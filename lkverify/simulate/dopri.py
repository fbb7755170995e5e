"""The compiled DOPRI5 method of steps: one point of a :class:`~lkverify.simulate.family.CompiledFamily`, in numba.

:func:`run_batch` integrates every point of a batch, one after the other, with the
generated right-hand side ``rhs(t, y, Z, p, out)`` passed as a numba first-class function
(signature :data:`RHS_SIGNATURE`), so this kernel is compiled once per machine (numba's
disk cache) whatever the system.  :func:`lkverify.simulate.batch.integrate` prepares its
arguments and is the API; this module is numba code only (editing it recompiles the
kernel: 3.8 s on the 2-core machine, ``benchmarks/bench_compile.py``).

Compile time
------------
The kernel is one function with one explicit signature (:data:`_KERNEL`) and no jitted
helpers, and the code of a stage (delayed values, dense output, rhs call) is written once,
in a loop over the stages: numba's ``inline="always"`` copies and re-types a helper's IR at
every call, and every separately compiled helper is re-optimised and re-emitted by LLVM
inside each caller.  Measured cold (empty ``NUMBA_CACHE_DIR``, median of 3, 2 cores) with
the warm run of paper 002's Fig. 1 on 300 points: helpers inlined 12.5 s, 89 ms; plain
jitted helpers 7.7 s, 199 ms; this form 3.8 s, 77 ms (the same numbers bit for bit).

Method (per point; the method of steps of :mod:`lkverify.simulate.solver`, compiled)
-----------------------------------------------------------------------------------
* Dormand–Prince 5(4) with the PI step-size control and the 4th-order dense output
  ``contd5`` of Hairer & Wanner's DOPRI5 (Solving ODEs I, II.5/II.6); the error norm is
  the RMS of ``err_i / (atol + rtol·max(|y_i|, |y_new,i|))`` over all components
  (auxiliary states included).  The first step is Hairer's ``hinit`` estimate.
* Every step is at most ``min(lags)`` long, so every delayed stage value
  ``y(t_n + c h − lag)`` lies in the accepted history: the constant initial history
  for arguments ≤ t0, else the stored dense output of the accepted step containing it
  (found by a moving pointer; steps older than the longest lag are dropped).
* Steps land on the breakpoints ``t0 + Σ kᵢ lagᵢ`` with ``1 ≤ Σ kᵢ ≤ 4``
  (:func:`lkverify.simulate.events.breakpoints`, as :func:`~lkverify.simulate.solver.solve_dde`);
  after a landing step the step size proposed before it is kept.
* Auxiliary window states ``z = ∫_{t−c}^t g(x)`` are integrated as ``ż = g(x(t)) −
  g(x(t−c))`` and, unlike :func:`~lkverify.simulate.runs.simulate`, NOT re-synchronised by
  quadrature after each step: their drift is not removed.  Measured for x' = −∫_{t−1}^t x,
  x ≡ 1, on [0, 200]: z(200) − ∫_{199}^{200} x = −3.1e-10 at rtol=1e-8, atol=1e-10 and
  −3.9e-12 at rtol=1e-10 (simulate's DOP853 without re-synchronisation: 5.6e-11); the drift
  is conserved and shifts the equilibrium of x by the same amount.
  ``tests/simulate/test_family.py`` compares the states with
  :func:`~lkverify.simulate.runs.simulate` on that system over [0, 200].

Outcome codes: :data:`OUTCOMES` (see :mod:`lkverify.simulate.batch`).

>>> import numpy as np
>>> def rhs(t, y, Z, p, out):       # x' = −p x(t − 1)
...     out[0] = -p[0] * Z[0, 0]
>>> out = np.full((1, 2, 1), np.nan); code = np.zeros(1, dtype=np.int64); t_fail = np.zeros(1)
>>> stats = np.zeros((1, 3), dtype=np.int64)
>>> run_batch(compile_rhs(rhs), np.array([[1.0]]), np.array([[1.0]]), np.array([1.0]), np.array([[1.0]]),
...           np.array([[1.0, 2.0]]), np.array([2]), 0.0, np.array([1.0, 2.0]), 1e-8, 1e-10, 1e8, 1000, 2e-7,
...           np.zeros(1, dtype=np.int64), out, code, t_fail, stats)
>>> OUTCOMES[code[0]].value, out[0, :, 0].round(10).tolist()       # x = 1 − t, then 1 − t + (t − 1)²/2
('success', [0.0, -0.5])
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from .events import BLOWUP_GROWTH, FLOOR_WINDOW
from .solver import Outcome

__all__ = ["OUTCOMES", "RHS_SIGNATURE", "compile_rhs", "run_batch"]

#: outcome code → Outcome
OUTCOMES = tuple(Outcome)
_SUCCESS, _DIVERGED, _COLLAPSE, _BUDGET = (OUTCOMES.index(o) for o in
                                           (Outcome.SUCCESS, Outcome.DIVERGED, Outcome.STEP_COLLAPSE, Outcome.BUDGET))

_f8, _i8 = types.float64, types.int64
_vec, _mat = types.float64[::1], types.float64[:, ::1]
#: the generated right-hand side: rhs(t, y, Z, p, out)
RHS_SIGNATURE = types.void(_f8, _vec, _mat, _vec, _vec)
_RHS = types.FunctionType(RHS_SIGNATURE)


def compile_rhs(py_func):
    """``py_func(t, y, Z, p, out)`` compiled by numba (IEEE semantics: x/0 gives inf or nan, never raises).

    Examples
    --------
    >>> import numpy as np
    >>> def rhs(t, y, Z, p, out):
    ...     out[0] = -p[0] * Z[0, 0] / y[0]
    >>> f = compile_rhs(rhs)
    >>> out = np.empty(1); f(0.0, np.array([0.0]), np.array([[1.0]]), np.array([2.0]), out); out.tolist()
    [-inf]
    """
    return numba.njit(RHS_SIGNATURE, error_model="numpy")(py_func)


# -- the compiled kernel -----------------------------------------------------------------
# Dormand–Prince 5(4) (Hairer & Wanner, DOPRI5)
_C2, _C3, _C4, _C5 = 0.2, 0.3, 0.8, 8.0 / 9.0
_A21 = 0.2
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
_A71, _A73, _A74, _A75, _A76 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4, _E5, _E6, _E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0,
                                -1.0 / 40.0)
_D1, _D3, _D4, _D5, _D6, _D7 = (-12715105075.0 / 11282082432.0, 87487479700.0 / 32700410799.0,
                                -10690763975.0 / 1880347072.0, 701980252875.0 / 199316789632.0,
                                -1453857185.0 / 822651844.0, 69997945.0 / 29380423.0)
_SAFE, _BETA, _FAC1, _FAC2 = 0.9, 0.04, 0.2, 10.0
_EXPO1 = 0.2 - _BETA * 0.75
_EPS = float(np.finfo(float).eps)
_GROWTH = float(BLOWUP_GROWTH)
_WINDOW = int(FLOOR_WINDOW)


_KERNEL = types.void(_RHS, _mat, _mat, _vec, _mat, _mat, types.int64[::1], _f8, _vec, _f8, _f8, _f8, _i8, _f8,
                     types.int64[::1], types.float64[:, :, ::1], types.int64[::1], _vec, types.int64[:, ::1])


@numba.njit(_KERNEL, cache=True, error_model="numpy")
def run_batch(rhs, P, Y0, x0, lags, targets, counts, t0, t_eval, rtol, atol, bound, max_steps, floor, skip, out,
              code, t_fail, stats):
    """Every point ``i`` with ``skip[i] == 0``, one after the other.

    ``P`` (N, k) the points, ``Y0`` (N, n) initial vectors (auxiliary states included), ``x0`` (n_states,)
    the constant history, ``lags`` (N, n_lags), ``targets[i, :counts[i]]`` the breakpoints of point i then
    t_end.  Writes the samples at ``t_eval`` into ``out`` (N, m, n_states; untouched after a failure), the
    outcome codes into ``code``, the end or failure time into ``t_fail`` and (accepted steps, rhs
    evaluations, rejected steps) into ``stats``.

    One function, no helpers (see Compile time in the module docstring); a point's run ends by setting
    ``outcome`` (≥ 0) and leaving the step loop.
    """
    n, ns, nl, n_eval = Y0.shape[1], x0.shape[0], lags.shape[1], t_eval.shape[0]
    for pt in range(P.shape[0]):
        if skip[pt]:
            continue
        p, lag, o = P[pt], lags[pt], out[pt]
        n_targets = counts[pt]
        t_end = targets[pt, n_targets - 1]
        hmax, lag_max = t_end - t0, 0.0
        for k in range(nl):
            hmax = min(hmax, lag[k])
            lag_max = max(lag_max, lag[k])
        # the accepted steps: start Ht, length Hh, contd5 coefficients C of all n components (the states' serve
        # the delayed values and the samples, all of them the divergence crossing); m of them, room for cap
        cap, m = 64, 0
        Ht, Hh, C = np.empty(cap), np.empty(cap), np.empty((cap, 5, n))
        hint = np.empty(max(nl, 1), dtype=np.int64)      # per lag: the stored step of its last delayed value
        for k in range(nl):
            hint[k] = 0
        Z = np.empty((nl, ns))
        K = np.empty((7, n))
        y, yn, yt = np.empty(n), np.empty(n), np.empty(n)
        yy = 0.0
        for i in range(n):
            y[i] = Y0[pt, i]
            yy += y[i] * y[i]
        ke = 0
        while ke < n_eval and t_eval[ke] <= t0:
            for i in range(ns):      # element by element: a slice assignment compiles numba's shape-error formatting
                o[ke, i] = y[i]
            ke += 1
        outcome, t, n_steps, nfev, n_rej = -1, t0, 0, 0, 0
        if not yy <= bound * bound:
            outcome = _DIVERGED
        else:
            for k in range(nl):      # every delayed argument of the first two evaluations is history
                for i in range(ns):
                    Z[k, i] = x0[i]
            rhs(t0, y, Z, p, K[0])
            nfev = 1
            acc = 0.0
            for i in range(n):
                acc += K[0, i] * K[0, i]
            if not math.isfinite(acc):
                outcome = _DIVERGED
        if outcome < 0:
            # the first step: Hairer's hinit for order 5 (the delayed values of the trial Euler step are history)
            dnf, dny = 0.0, 0.0
            for i in range(n):
                sk = atol + rtol * abs(y[i])
                dnf += (K[0, i] / sk) ** 2
                dny += (y[i] / sk) ** 2
            h = 1e-6 if (dnf <= 1e-10 or dny <= 1e-10) else math.sqrt(dny / dnf) * 0.01
            h = min(h, hmax)
            for i in range(n):
                yt[i] = y[i] + h * K[0, i]
            rhs(t0 + h, yt, Z, p, K[1])
            nfev = 2
            der2 = 0.0
            for i in range(n):
                sk = atol + rtol * abs(y[i])
                der2 += ((K[1, i] - K[0, i]) / sk) ** 2
            der2 = math.sqrt(der2) / h
            der12 = max(abs(der2), math.sqrt(dnf))
            h1 = (0.01 / der12) ** 0.2 if der12 > 1e-15 else max(1e-6, h * 1e-3)
            h = min(100.0 * h, h1, hmax)
            if not (h > 0.0 and math.isfinite(h)):
                h = hmax
            scale = max(1.0, math.sqrt(yy))
            recent = np.empty(_WINDOW)       # the last _WINDOW accepted step sizes
            for i in range(_WINDOW):
                recent[i] = 0.0
            recent_sum = 0.0
            it, facold, rejected, bad = 0, 1e-4, False, False
        while outcome < 0:
            # the step: stretched by up to 1 % (never beyond hmax) or cut to land on the next target
            h_prop = min(h, hmax)
            h = h_prop
            target = targets[pt, it]
            landing = (t + 1.01 * h >= target and target - t <= hmax) or t + h >= target
            if landing:
                h = target - t
            if h <= 10.0 * _EPS * abs(t):
                outcome = _DIVERGED if bad else _COLLAPSE
                break
            t_new = target if landing else t + h
            # stages 2–7 from (t, y), K[0] = f(t, y): yt the stage state, yn the new state, K[6] = f(t_new, yn)
            for st in range(1, 7):
                if st == 1:
                    s = t + _C2 * h
                    for i in range(n):
                        yt[i] = y[i] + h * _A21 * K[0, i]
                elif st == 2:
                    s = t + _C3 * h
                    for i in range(n):
                        yt[i] = y[i] + h * (_A31 * K[0, i] + _A32 * K[1, i])
                elif st == 3:
                    s = t + _C4 * h
                    for i in range(n):
                        yt[i] = y[i] + h * (_A41 * K[0, i] + _A42 * K[1, i] + _A43 * K[2, i])
                elif st == 4:
                    s = t + _C5 * h
                    for i in range(n):
                        yt[i] = y[i] + h * (_A51 * K[0, i] + _A52 * K[1, i] + _A53 * K[2, i] + _A54 * K[3, i])
                elif st == 5:
                    s = t_new
                    for i in range(n):
                        yt[i] = y[i] + h * (_A61 * K[0, i] + _A62 * K[1, i] + _A63 * K[2, i] + _A64 * K[3, i]
                                            + _A65 * K[4, i])
                else:
                    s = t_new
                    for i in range(n):
                        yn[i] = y[i] + h * (_A71 * K[0, i] + _A73 * K[2, i] + _A74 * K[3, i] + _A75 * K[4, i]
                                            + _A76 * K[5, i])
                if st < 6:           # stages 6 and 7 share the time t + h, hence the delayed values
                    # Z[k] = y(s − lags[k]) (states): the constant history before t0, else the stored step
                    # containing it (a moving pointer) at theta, by contd5
                    for k in range(nl):
                        q = s - lag[k]
                        if q <= t0 or m == 0:
                            for i in range(ns):
                                Z[k, i] = x0[i]
                            continue
                        j = hint[k]
                        if j >= m:
                            j = m - 1
                        while j + 1 < m and Ht[j + 1] <= q:
                            j += 1
                        while j > 0 and Ht[j] > q:
                            j -= 1
                        hint[k] = j
                        theta = (q - Ht[j]) / Hh[j]
                        th1 = 1.0 - theta
                        for i in range(ns):
                            Z[k, i] = C[j, 0, i] + theta * (C[j, 1, i] + th1 * (C[j, 2, i] + theta * (
                                C[j, 3, i] + th1 * C[j, 4, i])))
                rhs(s, yt if st < 6 else yn, Z, p, K[st])
            nfev += 6
            err = 0.0
            for i in range(n):
                e = h * (_E1 * K[0, i] + _E3 * K[2, i] + _E4 * K[3, i] + _E5 * K[4, i] + _E6 * K[5, i]
                         + _E7 * K[6, i])
                sk = atol + rtol * max(abs(y[i]), abs(yn[i]))
                err += (e / sk) ** 2
            err = math.sqrt(err / n)
            # Hairer's PI step-size control: accepted?, the next step size h_new, facold
            if not math.isfinite(err):
                accepted, h_new = False, h * _FAC1
            else:
                fac11 = err ** _EXPO1
                if err > 1.0:
                    accepted, h_new = False, h / min(1.0 / _FAC1, fac11 / _SAFE)
                else:
                    h_new = h / max(1.0 / _FAC2, min(1.0 / _FAC1, fac11 / facold ** _BETA / _SAFE))
                    if rejected:
                        h_new = min(h_new, h)
                    accepted, facold = True, max(err, 1e-4)
            rejected = not accepted
            if not accepted:
                n_rej += 1
                bad = bad or not math.isfinite(err)
                h = h_new
                continue
            n_steps += 1
            # store the accepted step [t, t + h]; when full, drop the steps before t − lag_max (keeping the one
            # containing it and one before), into arrays twice as long if more than half would stay
            if m == cap:
                j = 0
                while j + 2 < m and Ht[j + 2] <= t - lag_max:
                    j += 1
                Ht2, Hh2, C2 = Ht, Hh, C
                if m - j > cap // 2:
                    cap *= 2
                    Ht2, Hh2, C2 = np.empty(cap), np.empty(cap), np.empty((cap, 5, n))
                m -= j
                for r in range(m):               # forward: in place when the arrays stay
                    Ht2[r] = Ht[j + r]
                    Hh2[r] = Hh[j + r]
                    for c in range(5):
                        for i in range(n):
                            C2[r, c, i] = C[j + r, c, i]
                Ht, Hh, C = Ht2, Hh2, C2
            Ht[m] = t
            Hh[m] = h
            yy = 0.0
            for i in range(n):
                d = yn[i] - y[i]
                b = h * K[0, i] - d
                C[m, 0, i] = y[i]
                C[m, 1, i] = d
                C[m, 2, i] = b
                C[m, 3, i] = d - h * K[6, i] - b
                C[m, 4, i] = h * (_D1 * K[0, i] + _D3 * K[2, i] + _D4 * K[3, i] + _D5 * K[4, i] + _D6 * K[5, i]
                                  + _D7 * K[6, i])
                yy += yn[i] * yn[i]
            m += 1
            while ke < n_eval and t_eval[ke] <= t_new:
                theta = (t_eval[ke] - t) / h
                th1 = 1.0 - theta
                for i in range(ns):
                    o[ke, i] = C[m - 1, 0, i] + theta * (C[m - 1, 1, i] + th1 * (C[m - 1, 2, i] + theta * (
                        C[m - 1, 3, i] + th1 * C[m - 1, 4, i])))
                ke += 1
            if not yy <= bound * bound:
                # the first time in [t, t + h] where ‖y‖ reaches bound, on the step's dense output (bisection);
                # t + h if ‖y_new‖ is not finite
                outcome = _DIVERGED
                if math.isfinite(yy):
                    lo, hi = 0.0, 1.0
                    for _ in range(60):
                        mid = 0.5 * (lo + hi)
                        th1 = 1.0 - mid
                        vv = 0.0
                        for i in range(n):
                            v = C[m - 1, 0, i] + mid * (C[m - 1, 1, i] + th1 * (C[m - 1, 2, i] + mid * (
                                C[m - 1, 3, i] + th1 * C[m - 1, 4, i])))
                            vv += v * v
                        if vv > bound * bound:
                            hi = mid
                        else:
                            lo = mid
                    t += hi * h
                else:
                    t += h
                break
            for i in range(n):
                y[i] = yn[i]
                K[0, i] = K[6, i]
            slot = n_steps % _WINDOW
            recent_sum += h - recent[slot]
            recent[slot] = h
            t = t_new
            if landing:
                it += 1
                if it == n_targets:
                    outcome = _SUCCESS
                    break
                h_new = max(h_new, h_prop)       # after a landing step the step size proposed before it is kept
            if n_steps >= _WINDOW and recent_sum / _WINDOW < floor:
                outcome = _DIVERGED if math.sqrt(yy) > _GROWTH * scale else _COLLAPSE
                break
            if n_steps >= max_steps:
                outcome = _BUDGET
                break
            h = h_new
        code[pt], t_fail[pt] = outcome, t
        stats[pt, 0], stats[pt, 1], stats[pt, 2] = n_steps, nfev, n_rej
