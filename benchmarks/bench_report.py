"""Benchmark: the bare ``lkverify`` report, item by item and with 1 and N worker processes.

Run:  python benchmarks/bench_report.py [--jobs N]

Times every catalogue item at its defaults in this process (one after the other; wall and CPU
time), then the whole report as ``lkverify report --jobs 1`` and ``--jobs N`` run it (fresh
processes, so the catalogue load is included), each cold (a new, empty proof cache of its own),
prints the ratio, and last the ``--jobs N`` report again on its filled cache (warm), checking that
it prints the same text.  Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
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
            start, cpu = time.perf_counter(), time.process_time()
            item.run({})
            rows.append((time.perf_counter() - start, time.process_time() - cpu, item.qualified_name))
    total, total_cpu = sum(r[0] for r in rows), sum(r[1] for r in rows)
    # CPU time (this process's threads) as well as wall time: on a machine shared with other jobs the wall
    # time of an item grows with the load, its CPU time much less
    print("     wall       CPU  item")
    for s, c, name in sorted(rows, reverse=True):
        print(f"  {s:7.1f} s {c:7.1f} s  {name}")
    print(f"  {total:7.1f} s {total_cpu:7.1f} s  all {len(rows)} items, in this process (load "
          f"{os.getloadavg()[0]:.1f})")
    walls, texts = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        for run, jobs in (("cold", 1), ("cold", args.jobs), ("warm", args.jobs)):
            cache = os.path.join(tmp, f"cache-{jobs}")   # the warm run reads the cache its cold run filled
            env = {**os.environ, "LKVERIFY_CACHE_DIR": cache}
            env.pop("LKVERIFY_CACHE", None)
            start = time.perf_counter()
            out = subprocess.run([sys.executable, "-m", "lkverify", "report", "--jobs", str(jobs), "--quiet"],
                                 check=True, capture_output=True, text=True, env=env)
            walls[run, jobs] = time.perf_counter() - start
            texts[run, jobs] = out.stdout
            print(f"lkverify report --jobs {jobs}, {run}: {walls[run, jobs]:.1f} s (load {os.getloadavg()[0]:.1f})")
    print(f"ratio jobs 1 / jobs {args.jobs}, cold: {walls['cold', 1] / walls['cold', args.jobs]:.2f}")
    same = texts["cold", 1] == texts["cold", args.jobs] == texts["warm", args.jobs]
    print("the three reports print the same text" if same else "THE REPORTS DIFFER (cold/warm or jobs)")


if __name__ == "__main__":
    main()
