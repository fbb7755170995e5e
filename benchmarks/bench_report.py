"""Benchmark: the bare ``lkverify`` report, item by item and with 1 and N worker processes.

Run:  python benchmarks/bench_report.py [--jobs N]

Times every catalogue item at its defaults in this process (one after the other), then the
whole report as ``lkverify report --jobs 1`` and ``--jobs N`` run it (fresh processes, so the
catalogue load is included), and prints the ratio.  Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=min(os.cpu_count() or 1, 4))
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}")
    from lkverify.catalogue.loader import catalogue

    rows = []
    for pf in catalogue():
        for item in pf.items.values():
            start = time.perf_counter()
            item.run({})
            rows.append((time.perf_counter() - start, item.qualified_name))
    total = sum(s for s, _ in rows)
    for s, name in sorted(rows, reverse=True):
        print(f"  {s:7.1f} s  {name}")
    print(f"  {total:7.1f} s  all {len(rows)} items, in this process")
    walls = {}
    for jobs in (1, args.jobs):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "lkverify", "report", "--jobs", str(jobs), "--quiet"],
                       check=True, capture_output=True)
        walls[jobs] = time.perf_counter() - start
        print(f"lkverify report --jobs {jobs}: {walls[jobs]:.1f} s")
    print(f"ratio jobs 1 / jobs {args.jobs}: {walls[1] / walls[args.jobs]:.2f}")


if __name__ == "__main__":
    main()
