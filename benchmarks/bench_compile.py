"""Benchmark: the cold compile of the numba DOP853 kernel (lkverify.simulate.dop853) and its warm run time.

Run:  python3 benchmarks/bench_compile.py [--repeat N] [--runs R] [--tree DIR]

Cold compile: each of --repeat fresh interpreters (default 3) gets a new empty
``NUMBA_CACHE_DIR``, so nothing is loaded from numba's disk cache, and times

* ``import deps`` — numba, NumPy and ``lkverify.simulate`` (what dop853.py imports; not compile);
* ``import kernel`` — ``import lkverify.simulate.dop853``: the kernel has an explicit signature, so
  this is its compilation (and the write of numba's cache);
* ``native rhs`` — the module doctest's one-line right-hand side printed as LLVM IR and compiled
  (:mod:`lkverify.simulate.native`);
* ``first call`` — the first ``run_batch`` call on the module doctest's problem (x' = −x(t − 1));
* ``kernel`` = import kernel + first call: the number the target (≤ 5 s, issue 25) is about.

The table gives the median and the fastest of the runs.  One more fresh interpreter then imports
the kernel again with the last run's cache directory (a second process on the same machine: the kernel
loaded from the cache).

Warm run time: in the last cold interpreter, after the timings above, paper 002 Fig. 1
(``aleksandrov2023.fig1`` run 0, b and h swept with F = diag(h,h,h), as ``lkverify sweep`` does) on a
grid of 20 × 15 = 300 points (b in [−3, 3], h in [0.1, 2]), t_end = 100, 201 samples, default
tolerances: ``lkverify.simulate.batch.integrate`` (``CompiledFamily.integrate``), best of --runs
(default 5) after one untimed run; also per point and per right-hand-side evaluation.

``--tree DIR`` times another checkout's ``lkverify`` package instead (DIR first on PYTHONPATH; e.g.
``git archive HEAD lkverify | tar -x -C DIR`` for a before/after comparison in one session).  Numbers
are printed, never asserted; the 2-core machine should be otherwise idle.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile

from _tree import load_average, tree_env

# the child: one fresh interpreter, timings as JSON on the last line of stdout
CHILD = r'''
import json, sys, time
T = {}
s = time.perf_counter()
import numpy as np, numba
import lkverify.simulate
T["import deps"] = time.perf_counter() - s
s = time.perf_counter()
from lkverify.simulate import dop853
T["import kernel"] = time.perf_counter() - s
import sympy
from lkverify.simulate.native import load, native_source
s = time.perf_counter()
z = sympy.Symbol("Z_0_0")
fn = load(native_source({"rhs": [-z], "win": []}, {z: ("Z", 0)}))
T["native rhs"] = time.perf_counter() - s
out = np.full((1, 2, 1), np.nan); code = np.zeros(1, dtype=np.int64); t_fail = np.zeros(1)
stats = np.zeros((1, 4), dtype=np.int64)
s = time.perf_counter()
dop853.run_batch(fn["rhs"], fn["win"], np.zeros((1, 1)), np.array([[1.0]]), np.array([1.0]), np.array([[1.0]]),
                 np.zeros((0, 2), dtype=np.int64), np.array([[1.0, 2.0]]), np.array([2]), 0.0, np.array([1.0, 2.0]),
                 1e-8, 1e-10, np.inf, 1e8, 1000, 2e-7, np.zeros(1, dtype=np.int64), np.array([1e-3]), out, code,
                 t_fail, stats,
                 np.zeros(1), np.zeros((0, 8, 1)))
T["first call"] = time.perf_counter() - s
if dop853.OUTCOMES[code[0]].value != "success" or out[0, :, 0].round(10).tolist() != [0.0, -0.5]:
    raise SystemExit(f"wrong result: {code}, {out}")
T["kernel"] = T["import kernel"] + T["first call"]
T["file"] = dop853.__file__
runs = int(sys.argv[1])
if runs:
    import sympy
    from lkverify.catalogue.loader import find_items
    from lkverify.simulate.family import compile_family
    (ex,) = find_items("aleksandrov2023.fig1")
    run = ex.runs[0]
    h = {n: sympy.Symbol(n) for n in ("b", "h")}
    values = {k: v for k, v in run.values.items() if k not in ("b", "h", "F")}
    values["F"] = sympy.sympify("diag(h,h,h)", locals={**h, "diag": sympy.diag})
    fam = compile_family(run.system, values, grid=["b", "h"])
    b, hh = np.meshgrid(np.linspace(-3, 3, 20), np.linspace(0.1, 2, 15))
    pts = np.column_stack([b.ravel(), hh.ravel()])
    te = np.linspace(0.0, 100.0, 201)
    fam.integrate(pts, run.history, t_end=100.0, t_eval=te)          # untimed: the rhs compile, first touches
    best = float("inf")
    for _ in range(runs):
        s = time.perf_counter()
        res = fam.integrate(pts, run.history, t_end=100.0, t_eval=te)
        best = min(best, time.perf_counter() - s)
    T["warm"] = best
    T["points"] = len(pts)
    T["nfev"] = int(res.nfev.sum())
    T["steps"] = int(res.n_steps.sum())
    T["outcomes"] = sorted({o.value for o in res.outcomes})
print(json.dumps(T))
'''

PHASES = ("import deps", "import kernel", "native rhs", "first call", "kernel")


def child(env: dict, cache: str, runs: int = 0) -> dict:
    done = subprocess.run([sys.executable, "-c", CHILD, str(runs)], capture_output=True, text=True,
                          env={**env, "NUMBA_CACHE_DIR": cache}, cwd=tempfile.gettempdir())
    if done.returncode != 0:
        raise SystemExit(f"child failed (exit {done.returncode}): {done.stderr[-600:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="fresh interpreters with an empty cache (default 3)")
    ap.add_argument("--runs", type=int, default=5, help="timed runs of the warm batch, best shown (default 5)")
    ap.add_argument("--tree", default=None, metavar="DIR", help="time the lkverify package of this checkout")
    args = ap.parse_args()
    env, load = tree_env(args.tree), load_average()
    import numba

    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, load {load:.2f}, "
          f"Python {platform.python_version()}, numba {numba.__version__}; {args.repeat} cold runs"
          + (f"; tree {args.tree}" if args.tree else ""))
    rows, caches = [], []
    try:
        for i in range(args.repeat):
            caches.append(tempfile.mkdtemp(prefix="numba-cold-"))
            rows.append(child(env, caches[-1], args.runs if i == args.repeat - 1 else 0))
        cached = child(env, caches[-1])
    finally:
        for c in caches:
            shutil.rmtree(c, ignore_errors=True)
    print(f"module: {rows[-1]['file']}")
    print(f"{'cold (empty NUMBA_CACHE_DIR)':<32} {'median':>8} {'fastest':>8}")
    for phase in PHASES:
        v = [r[phase] for r in rows]
        print(f"{phase:<32} {statistics.median(v):7.2f}s {min(v):7.2f}s"
              + ("   target <= 5 s: " + ("ok" if statistics.median(v) <= 5.0 else "over") if phase == "kernel" else ""))
    print(f"{'cached: import + 1st call':<32} {cached['kernel']:7.2f}s  (a second process, same cache)")
    last = rows[-1]
    print(f"warm batch (paper 002 Fig. 1, {last['points']} points, t_end = 100, best of {args.runs}): "
          f"{last['warm']:.3f} s = {1e3 * last['warm'] / last['points']:.3f} ms per point, "
          f"{1e9 * last['warm'] / last['nfev']:.0f} ns per rhs evaluation ({last['steps']} steps, {last['nfev']} "
          f"evaluations; outcomes {', '.join(last['outcomes'])})")


if __name__ == "__main__":
    main()
