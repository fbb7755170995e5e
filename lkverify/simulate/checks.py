"""Argument checks of :func:`lkverify.simulate.solver.solve_dde`: every problem collected, raised once."""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping

import numpy as np

from ..errors import InputError

__all__: list[str] = []

_EPS = np.finfo(float).eps
METHODS = ("DOP853", "RK45")

def _number(value, name: str, problems: list, *, allow_inf=False, allow_zero=False):
    """A positive (or non-negative) real number, else a problem is recorded and None returned."""
    v = float(value) if isinstance(value, numbers.Real) and not isinstance(value, bool) else math.nan
    if math.isnan(v) or not (allow_inf or math.isfinite(v)) or not (v > 0 or (allow_zero and v == 0)):
        want = "a non-negative number" if allow_zero else "a positive number"
        problems.append(f"{name}: expected {want}, got {value!r}")
        return None
    return v


def _named_monitors(monitors) -> list[tuple[str, Callable]]:
    items = list(monitors.items()) if isinstance(monitors, Mapping) else [
        (getattr(f, "__name__", ""), f) for f in monitors]
    named, seen = [], set()
    for i, (name, f) in enumerate(items):
        name = str(name) if name and name != "<lambda>" else f"monitor{i}"
        if name in seen:
            name = f"{name}_{i}"
        seen.add(name)
        named.append((name, f))
    return named


def _validate(fun, t_span, history, lags, method, rtol, atol, max_step, first_step, divergence_bound,
              discontinuity_order, t_eval, resync, monitors, progress):
    problems: list[str] = []
    if not callable(fun):
        problems.append(f"fun: expected a callable fun(t, y, Z, past) -> array (n,), got {type(fun).__name__}")
    t0 = t_end = None
    try:
        t0, t_end = (float(v) for v in t_span)
        if not (math.isfinite(t0) and math.isfinite(t_end) and t_end > t0):
            problems.append(f"t_span: expected finite (t0, t_end) with t_end > t0, got {tuple(t_span)!r}; "
                            "integrate forward in time")
            t0 = None
    except (TypeError, ValueError):
        problems.append(f"t_span: expected a pair (t0, t_end) of numbers, got {t_span!r}")
        t0 = None
    lag_list = [lags] if isinstance(lags, numbers.Real) else lags
    try:
        lag_arr = np.asarray(lag_list, dtype=float).reshape(-1)
        bad = [v for v in lag_arr if not (math.isfinite(v) and v > 0)]
        if bad:
            problems.append(f"lags: expected positive finite constant lags, got {list(lag_arr)!r}; "
                            "drop zero lags (use y itself) and give each lag > 0")
    except (TypeError, ValueError):
        problems.append(f"lags: expected a sequence of positive numbers, got {lags!r}")
        lag_arr = np.empty(0)
    if method not in METHODS:
        problems.append(f"method: expected one of {sorted(METHODS)}, got {method!r}")
    rtol = _number(rtol, "rtol", problems)
    if rtol is not None and rtol < 100 * _EPS:
        problems.append(f"rtol: expected rtol >= {100 * _EPS:.3g} (100 machine epsilons), got {rtol!r}")
    if np.ndim(atol) == 0:
        _number(atol, "atol", problems, allow_zero=True)
    elif not (np.all(np.isfinite(np.asarray(atol, dtype=float))) and np.all(np.asarray(atol, dtype=float) >= 0)):
        problems.append(f"atol: expected non-negative finite tolerance(s), got {atol!r}")
    max_step = _number(max_step, "max_step", problems, allow_inf=True)
    if first_step is not None:
        _number(first_step, "first_step", problems)
    _number(divergence_bound, "divergence_bound", problems, allow_inf=True)
    if not (isinstance(discontinuity_order, numbers.Integral) and not isinstance(discontinuity_order, bool)
            and discontinuity_order >= 0):
        problems.append(f"discontinuity_order: expected an integer >= 0, got {discontinuity_order!r}")
    for name, f in (("resync", resync), ("progress", progress)):
        if f is not None and not callable(f):
            problems.append(f"{name}: expected a callable or None, got {type(f).__name__}")
    try:
        named = _named_monitors(monitors)
        for name, f in named:
            if not callable(f):
                problems.append(f"monitors: expected callables monitor(t, y) -> float, "
                                f"got {type(f).__name__} for {name!r}")
    except (TypeError, AttributeError):
        problems.append(f"monitors: expected a sequence or mapping of callables, got {monitors!r}")
        named = []
    if t_eval is not None and t0 is not None:
        te = np.asarray(t_eval, dtype=float)
        if te.ndim != 1 or not np.isfinite(te).all() or (te.size and (te.min() < t0 or te.max() > t_end)):
            problems.append(f"t_eval: expected a 1-d array of times in [t0, t_end] = [{t0:g}, {t_end:g}], "
                            f"got {np.asarray(t_eval).shape} array spanning "
                            f"[{np.min(te) if te.size else 'nan'}, {np.max(te) if te.size else 'nan'}]")
    y0 = None
    if t0 is not None:
        y0 = _check_history(history, t0, lag_arr, problems)
    if problems:
        raise InputError("; ".join(problems))
    if atol is not None and np.ndim(atol) == 1 and np.shape(atol) != y0.shape:
        raise InputError(f"atol: expected a scalar or {y0.shape[0]} tolerances (one per state), got {np.shape(atol)}")
    return t0, t_end, lag_arr, y0, rtol, max_step, named


def _check_history(history, t0, lag_arr, problems):
    """y0 = history(t0) as (n,), checking dimension and finiteness at a few points."""
    points = [t0]
    if lag_arr.size:
        points += sorted(set(float(t0 - v) for v in lag_arr)) + [t0 - 0.5 * float(lag_arr.max())]
    values = []
    for s in points:
        try:
            v = np.asarray(history(s) if callable(history) else history, dtype=float)
        except (TypeError, ValueError) as exc:
            problems.append(f"history: expected a callable phi(s) -> array (n,) or a constant array, got an error "
                            f"at s={s:g}: {exc}")
            return None
        if v.ndim == 0:
            v = v.reshape(1)
        if v.ndim != 1 or v.size == 0:
            problems.append(f"history: expected a 1-d state of n >= 1 components, got shape {v.shape} at s={s:g}; "
                            "return a flat array with every state component")
            return None
        if values and v.shape != values[0].shape:
            problems.append(f"history: expected the same dimension n={values[0].shape[0]} at every s, "
                            f"got {v.shape[0]} at s={s:g}")
            return None
        if not np.isfinite(v).all():
            problems.append(f"history: expected finite values, got {v.tolist()} at s={s:g}; "
                            "fix the initial function (NaN/inf in the history)")
            return None
        values.append(v)
        if not callable(history):
            break
    return values[0].copy()

