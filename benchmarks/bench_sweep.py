"""Benchmark: gain-sweep throughput on Dask, and the speed-up of two workers over one.

Run:  python3 benchmarks/bench_sweep.py [--t-end 100] [--b 31] [--h 20]

The sweep of the issue's acceptance example (paper 002, Fig. 1: a = 2, τ = 0.9, μ = 1,
F = diag(h,h,h), b and h swept) on a LocalCluster with 1 and then 2 single-threaded worker
processes (one per core on the 2-core machine), each from scratch in a fresh Python process (the
plan's SymPy work not memoised by an earlier run, a new cluster, no chunk reused).  Printed:

* the plan (SymPy, once on the client) and the exact checks (hypotheses per point, cached);
* per worker count: the wall time of the simulation phase (cluster start + compilation on the
  workers + every point's run), the cluster start alone, and the sum of the chunks' own
  compute seconds;
* simulated points per hour on 2 cores, from the 2-worker wall time (all overheads included)
  and from the compute seconds alone (steady state);
* the speed-up of 2 workers over 1, from the wall times with and without the cluster start, and in
  the steady state (points per second after every worker finished its first chunk, which carries
  the worker's imports and JIT compilation: a fixed cost of a few seconds per worker);
* whether the tables of 1 and 2 workers are identical (NaN equal to NaN);
* the same sweep on an existing (warm) LocalCluster of 1 and of 2 workers, after a small warm-up sweep
  on it: what a user with a running cluster (``--scheduler``) sees, and the speed-up of the
  parallel part.

Not a test: numbers are printed, not asserted.  Needs the 2 cores idle to mean anything.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lkverify.sweep import SweepOptions, sweep


def one(workers, args, folder):
    out = Path(folder) / f"w{workers}.parquet"
    stamps = []
    start = time.monotonic()
    res = sweep("aleksandrov2023.fig1", grid=[f"b=-3:3:{args.b}", f"h=0.1:2:{args.h}"], sets=["F=diag(h,h,h)"],
                out=out, options=SweepOptions(t_end=args.t_end, workers=workers, fresh=True,
                                              chunk_size=args.chunk_size),
                progress=lambda done, total, sec: stamps.append((done, time.monotonic())))
    wall = time.monotonic() - start
    # steady state: from the chunk that completes the workers' first round to the last chunk
    (d0, t0), (d1, t1) = stamps[min(workers, len(stamps) - 1) - 1], stamps[-1]
    steady = (d1 - d0) / (t1 - t0) if t1 > t0 else float("nan")
    return res, wall, steady


def fresh(workers, args, folder):
    """:func:`one` in a fresh interpreter: (end-to-end seconds of the sweep call, timings, steady rate, counts)."""
    cmd = [sys.executable, __file__, "--child", str(workers), "--folder", folder, "--t-end", str(args.t_end),
           "--b", str(args.b), "--h", str(args.h), "--chunk-size", str(args.chunk_size)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def warm(workers, args, folder):
    """The same sweep on an existing LocalCluster whose workers already ran a small sweep (imports, JIT done)."""
    from distributed import LocalCluster

    grid = [f"b=-3:3:{args.b}", f"h=0.1:2:{args.h}"]
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        opts = dict(t_end=args.t_end, scheduler=cluster.scheduler_address, fresh=True, chunk_size=args.chunk_size)
        sweep("aleksandrov2023.fig1", grid=["b=-3:3:4", "h=0.1:2:8"], sets=["F=diag(h,h,h)"],
              out=Path(folder) / "warm-up.parquet", options=SweepOptions(**{**opts, "chunk_size": 4}))
        res = sweep("aleksandrov2023.fig1", grid=grid, sets=["F=diag(h,h,h)"], out=Path(folder) / f"warm{workers}.parquet",
                    options=SweepOptions(**opts))
    return res


def same_tables(a, b) -> bool:
    """Equal column by column, NaN equal to NaN (pyarrow's Table.equals says NaN != NaN)."""
    def norm(v):
        return "nan" if isinstance(v, float) and math.isnan(v) else v
    return a.column_names == b.column_names and all(
        [norm(v) for v in a.column(n).to_pylist()] == [norm(v) for v in b.column(n).to_pylist()]
        for n in a.column_names)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--t-end", type=float, default=100.0)
    ap.add_argument("--b", type=int, default=31)
    ap.add_argument("--h", type=int, default=20)
    ap.add_argument("--chunk-size", type=int, default=64)
    ap.add_argument("--no-warm", action="store_true", help="skip the runs on a warm existing cluster")
    ap.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--folder", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:   # one worker count in this fresh process: print its numbers as JSON
        res, wall, steady = one(args.child, args, args.folder)
        print(json.dumps({"wall": wall, "timings": {k: v for k, v in res.timings.items() if isinstance(v, float)},
                          "steady": steady, "counts": res.counts, "out": str(Path(args.folder) / f"w{args.child}.parquet")}))
        return
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; t_end = {args.t_end:g}, "
          f"grid {args.b} × {args.h} = {args.b * args.h} points, chunks of {args.chunk_size}")
    rows = {}
    with tempfile.TemporaryDirectory() as folder:
        import pyarrow.parquet as pq

        for w in (1, 2):
            r = fresh(w, args, folder)
            wall, tm, steady = r["wall"], r["timings"], r["steady"]
            rows[w] = (pq.read_table(r["out"]), wall, tm, steady)
            print(f"workers={w}: end to end {wall:.2f} s = plan {tm['plan']:.2f} + exact checks "
                  f"{tm['exact checks']:.2f} + simulation {tm['simulation']:.2f} (cluster start "
                  f"{tm.get('cluster start', 0):.2f}); steady state {steady:.0f} points/s; classes {r['counts']}")
    n = args.b * args.h
    s1 = rows[1][2]["simulation"]
    s2 = rows[2][2]["simulation"]
    c1 = s1 - rows[1][2].get("cluster start", 0)
    c2 = s2 - rows[2][2].get("cluster start", 0)
    print(f"points per hour on 2 cores (2 workers, simulation phase incl. cluster start and JIT): {n / s2 * 3600:,.0f}")
    print(f"points per hour on 2 cores (2 workers, excl. cluster start): {n / c2 * 3600:,.0f}")
    print(f"points per hour on 2 cores (2 workers, steady state): {rows[2][3] * 3600:,.0f}")
    print(f"speed-up 2 workers / 1: {rows[1][1] / rows[2][1]:.2f} end to end (the sweep call, fresh processes), "
          f"{s1 / s2:.2f} (simulation phase), {c1 / c2:.2f} (excl. cluster start), "
          f"{rows[2][3] / rows[1][3]:.2f} (steady state, after each worker's first chunk: imports and JIT)")
    print(f"tables of 1 and 2 workers identical: {same_tables(rows[1][0], rows[2][0])}")
    if args.no_warm:
        return
    with tempfile.TemporaryDirectory() as folder:
        w1, w2 = warm(1, args, folder), warm(2, args, folder)
    t1, t2 = w1.timings["simulation"], w2.timings["simulation"]
    print(f"warm cluster (an existing cluster, workers already past imports and JIT): simulation phase 1 worker "
          f"{t1:.1f} s, 2 workers {t2:.1f} s; speed-up {t1 / t2:.2f}; {n / t2 * 3600:,.0f} points per hour on 2 cores; "
          f"tables identical: {same_tables(w1.table, w2.table)}")


if __name__ == "__main__":
    main()
