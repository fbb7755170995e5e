"""Benchmark: lkverify.linear on the issue's examples — spectral route, crossing analysis, LMI hierarchy.

Run:  python benchmarks/bench_linear.py [--orders 0,1,2,3,4]

For the classic example (Gu, Kharitonov & Chen 2003), Gu's example (interval not starting at 0)
and the distributed-delay example: the time of the crossing analysis, and per order of the
hierarchy the certified delays, the number of SDP solves, the time per solve and the total
(SDP compile, bisection, exact re-verification at the reported ends); then the certified
stable/unstable intervals (crossing delays enclosed in arb, one proof per interval) and the
interval Newton refutation at an unstable delay.  Wall and CPU time are
both printed (a loaded machine inflates the wall time).  Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import time


EXAMPLES = {
    "classic": dict(A=[[-2, 0], [0, "-0.9"]], Ad=[[-1, 0], [-1, -1]]),
    "gu": dict(A=[[0, 1], [-2, "0.1"]], Ad=[[0, 0], [1, 0]]),
    "distributed": dict(A=[["0.2", 0], ["0.2", "0.1"]], kernel=[[[-1, 0], [-1, -1]]]),
}
ANCHORS = {"classic": "margin 6.17258; Jensen 4.4715, Wirtinger 6.0593, N = 2, 3, 4: 6.1689, 6.1724, 6.1725",
           "gu": "[0.100174, 1.71785]", "distributed": "(0.2, 2.04128)"}


def _timed(f):
    w, c = time.perf_counter(), time.process_time()
    out = f()
    return out, time.perf_counter() - w, time.process_time() - c


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--orders", default="0,1,2,3,4")
    ap.add_argument("--examples", default=",".join(EXAMPLES))
    args = ap.parse_args()
    orders = [int(x) for x in args.orders.split(",")]
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, load {os.getloadavg()[0]:.1f}")
    (_, w, c) = _timed(lambda: __import__("lkverify.linear"))
    print(f"import lkverify.linear: {w:.2f} s wall, {c:.2f} s CPU")
    from lkverify.linear import (LinearDelaySystem, certified_interval, certify_stretches, refute_stability,
                                 stability_intervals)

    for name in args.examples.split(","):
        sys = LinearDelaySystem(**EXAMPLES[name])
        iv, w, c = _timed(lambda: stability_intervals(sys, h_max=10))
        print(f"\n{name} (issue: {ANCHORS[name]})")
        shown = ", ".join(f"({lo:.7g}, {hi:.7g})" for lo, hi in iv.intervals)
        print(f"  spectral/crossing: {shown}  [{w:.2f} s wall, {c:.2f} s CPU]")
        tw = tc = 0.0
        for order in orders:
            m, w, c = _timed(lambda: certified_interval(sys, iv.intervals[0], order=order))
            tw, tc = tw + w, tc + c
            lo = "" if m.lower is None else f"{m.lower:.7g} … "
            up = "none" if m.upper is None else f"{m.upper:.7g}"
            print(f"  {m.method:22s} {m.status.value:9s} {lo}{up}  {m.solves:3d} solves "
                  f"{1000 * w / max(m.solves, 1):6.1f} ms/solve  {w:6.2f} s wall  {c:6.2f} s CPU")
        print(f"  all orders: {tw:.2f} s wall, {tc:.2f} s CPU")
        st, w, c = _timed(lambda: certify_stretches(sys, 10, estimated=iv.intervals))
        shown = ", ".join(f"{s.kind} ({s.lo:.7g}, {s.hi:.7g}) {s.status.value}" for s in st)
        print(f"  certified intervals: {shown}  [{w:.2f} s wall, {c:.2f} s CPU]")
        bad = next((s for s in st if s.kind == "unstable"), None)
        if bad is not None:
            r, w, c = _timed(lambda: refute_stability(sys, bad.sample))
            print(f"  refuted at h = {bad.sample}: {r.status.value}, root {r.root.enclosure if r.root else '—'}  "
                  f"[{1000 * w:.1f} ms wall, {1000 * c:.1f} ms CPU]")


if __name__ == "__main__":
    main()
