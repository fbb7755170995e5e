"""Benchmark: the two catalogued identity proofs, end to end.

Run:  python benchmarks/bench_identities.py [--repeat N]

Times derive + numeric witnesses + exact normal form for
aleksandrov2023.theorem3 (structured V̇, exact) and aleksandrov2026.theorem1
(printed V̇, refuted term by term), each in a fresh process-level state, and
prints the figures and their sum.  Not a test: numbers are printed, not asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

from lkverify.catalogue.loader import find_items


def run_once(name: str) -> tuple[float, str]:
    (item,) = find_items(name)
    claim = item.claims[0]
    start = time.perf_counter()
    res = claim.check({}, values={}, budget=None)
    return time.perf_counter() - start, res.status.value


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    names = ["aleksandrov2023.theorem3", "aleksandrov2026.theorem1"]
    best = {}
    for name in names:
        times = []
        for _ in range(args.repeat):
            dt, status = run_once(name)
            times.append(dt)
        best[name] = min(times)
        print(f"{name:28s} status={status:8s} best {min(times):6.2f} s   all {', '.join(f'{x:.2f}' for x in times)}")
    print(f"both identity proofs together (best of {args.repeat} each): {sum(best.values()):.2f} s")


if __name__ == "__main__":
    main()
