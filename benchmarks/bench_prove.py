"""Benchmark: the proved layer of a sweep (``sweep … --prove``), cells per minute, and 2 workers over 1.

Run:  python3 benchmarks/bench_prove.py [--b 13] [--h 10] [--b-range -3:0] [--h-range 1/10:2] [--workers 1,2]
      [--budget SECONDS]

Paper 002, Fig. 6 (a = 0, τ = 1, μ = 2, F = diag(h,h,h)), b and h swept as in the issue's acceptance
(13 × 10 cells by default), each cell a box on which Theorem 3's chain is run
(:mod:`lkverify.sweep.prove`).  Per worker count: the wall time of the whole sweep (cluster start,
simulations, proofs), the proofs' part, cells per minute, the cells established / failed / undecided
and the proved fraction of the hypotheses' region; then the speed-up of 2 workers over 1 (same run,
same machine).  Not a test: numbers are printed, not asserted.  Needs the cores idle to mean anything.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from lkverify.sweep import SweepOptions, sweep


def one(workers: int, args, folder: Path) -> dict:
    start = time.monotonic()
    res = sweep("aleksandrov2023.fig6", grid=[f"b={args.b_range}:{args.b}", f"h={args.h_range}:{args.h}"],
                sets=["F=diag(h,h,h)"], out=folder / f"prove-{workers}.parquet",
                options=SweepOptions(workers=workers, prove=True, t_end=args.t_end, fresh=True,
                                     prove_max_boxes=args.max_boxes, budget=args.budget))
    wall = time.monotonic() - start
    tbl = res.table.to_pydict()
    proved = np.array(tbl["proved:theorem3"], dtype=object)
    applies = np.array(tbl["applies:theorem3"], dtype=bool)
    counts = {s: int(np.sum(proved == s)) for s in ("established", "failed", "undecided")}
    return {"wall": wall, "proofs": res.timings.get("proofs", float("nan")), "counts": counts,
            "fraction": counts["established"] / max(1, int(applies.sum())), "cells": len(proved),
            "inside": bool(np.all(applies[proved == "established"]))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--b", type=int, default=13)
    ap.add_argument("--h", type=int, default=10)
    ap.add_argument("--b-range", default="-3:0")
    ap.add_argument("--h-range", default="1/10:2")
    ap.add_argument("--t-end", type=float, default=100.0)
    ap.add_argument("--max-boxes", type=int, default=3)
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--budget", type=float, default=None, help="seconds per sweep; cells not reached are undecided")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        rows = {}
        for w in (int(x) for x in args.workers.split(",")):
            rows[w] = r = one(w, args, Path(tmp))
            print(f"{w} worker(s): {r['cells']} cells in {r['wall']:.1f} s wall (proofs {r['proofs']:.1f} s): "
                  f"{60 * r['cells'] / r['wall']:.2f} cells/min; {r['counts']}; proved fraction of the hypotheses' "
                  f"cells {r['fraction']:.1%}; proved cells inside the hypotheses' region: {r['inside']}", flush=True)
        if 1 in rows and 2 in rows:
            print(f"speed-up 2 workers / 1: {rows[1]['wall'] / rows[2]['wall']:.2f} (wall), "
                  f"{rows[1]['proofs'] / rows[2]['proofs']:.2f} (proofs)")


if __name__ == "__main__":
    main()
