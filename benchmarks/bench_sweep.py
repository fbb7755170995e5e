"""Benchmark: gain-sweep throughput on Dask, and the speed-up of two workers over one.

Run:  python3 benchmarks/bench_sweep.py [--t-end 100] [--b 31] [--h 20]

The sweep of the issue's acceptance example (paper 002, Fig. 1: a = 2, τ = 0.9, μ = 1,
F = diag(h,h,h), b and h swept) on a LocalCluster with 1 and then 2 single-threaded worker
processes (one per core on the 2-core machine), each from scratch (a new cluster, the system
compiled by numba on each worker, no chunk reused).  Printed:

* the plan (SymPy, once on the client) and the exact checks (hypotheses per point, cached);
* per worker count: the wall time of the simulation phase (cluster start + compilation on the
  workers + every point's run), the cluster start alone, and the sum of the chunks' own
  compute seconds;
* simulated points per hour on 2 cores, from the 2-worker wall time (all overheads included)
  and from the compute seconds alone (steady state);
* the speed-up of 2 workers over 1, from the wall times with and without the cluster start.

Not a test: numbers are printed, not asserted.  Needs the 2 cores idle to mean anything.
"""

from __future__ import annotations

import argparse
import os
import platform
import tempfile
import time
from pathlib import Path

from lkverify.sweep import SweepOptions, sweep


def one(workers, args, folder):
    out = Path(folder) / f"w{workers}.parquet"
    start = time.monotonic()
    res = sweep("aleksandrov2023.fig1", grid=[f"b=-3:3:{args.b}", f"h=0.1:2:{args.h}"], sets=["F=diag(h,h,h)"],
                out=out, options=SweepOptions(t_end=args.t_end, workers=workers, fresh=True,
                                              chunk_size=args.chunk_size))
    wall = time.monotonic() - start
    return res, wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--t-end", type=float, default=100.0)
    ap.add_argument("--b", type=int, default=31)
    ap.add_argument("--h", type=int, default=20)
    ap.add_argument("--chunk-size", type=int, default=64)
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; t_end = {args.t_end:g}, "
          f"grid {args.b} × {args.h} = {args.b * args.h} points, chunks of {args.chunk_size}")
    rows = {}
    with tempfile.TemporaryDirectory() as folder:
        for w in (1, 2):
            res, wall = one(w, args, folder)
            tm = res.timings
            rows[w] = (res, wall, tm)
            print(f"workers={w}: total {wall:.1f} s = plan {tm['plan']:.1f} + exact checks {tm['exact checks']:.2f} "
                  f"+ simulation {tm['simulation']:.1f} (cluster start {tm.get('cluster start', 0):.1f}); "
                  f"classes {res.counts}")
    n = args.b * args.h
    s1 = rows[1][2]["simulation"]
    s2 = rows[2][2]["simulation"]
    c1 = s1 - rows[1][2].get("cluster start", 0)
    c2 = s2 - rows[2][2].get("cluster start", 0)
    print(f"points per hour on 2 cores (2 workers, simulation phase incl. cluster start and JIT): {n / s2 * 3600:,.0f}")
    print(f"points per hour on 2 cores (2 workers, excl. cluster start): {n / c2 * 3600:,.0f}")
    print(f"speed-up 2 workers / 1: {s1 / s2:.2f} (simulation phase), {c1 / c2:.2f} (excl. cluster start)")
    same = rows[1][0].table.equals(rows[2][0].table)
    print(f"tables of 1 and 2 workers identical: {same}")


if __name__ == "__main__":
    main()
