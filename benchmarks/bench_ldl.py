"""Benchmark: the exact LDLᵀ of ``lkverify.certify.matrices`` on python-flint against ``Fraction``s (issue 27).

Run:  python3 benchmarks/bench_ldl.py [--repeat 3]

For random symmetric positive-definite rational matrices of size n (entries with
denominators up to 20), times the library's elimination (flint ``fmpq``) and the same
elimination in Python ``Fraction``s (the implementation it replaced, kept here as the
baseline), checks that both give the same pivots, and prints the median times and
their ratio. Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import random
import statistics
import time
from fractions import Fraction

from lkverify.certify.matrices import _exact_ldl


def _fraction_pivots(M) -> tuple:
    """The baseline: the same diagonal-pivoting elimination in Fractions, with the witness vectors."""
    n = len(M)
    S = [row[:] for row in M]
    V = [[Fraction(int(i == j)) for i in range(n)] for j in range(n)]
    remaining, pivots = list(range(n)), []
    while remaining:
        p = max(remaining, key=lambda i: S[i][i])
        d = S[p][p]
        if d <= 0:
            break
        pivots.append(d)
        remaining.remove(p)
        for j in remaining:
            f = S[p][j] / d
            if f:
                V[j] = [a - f * b for a, b in zip(V[j], V[p])]
        for i in remaining:
            sip = S[i][p] / d
            if sip:
                for j in remaining:
                    S[i][j] -= sip * S[p][j]
    return tuple(pivots)


def _spd(n: int, rng: random.Random) -> list:
    A = [[Fraction(rng.randint(-50, 50), rng.randint(1, 20)) for _ in range(n)] for _ in range(n)]
    return [[sum(A[i][k] * A[j][k] for k in range(n)) + (n if i == j else 0) for j in range(n)] for i in range(n)]


def _median(f, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    rng = random.Random(1)
    print(f"{'n':>4}  {'flint fmpq (s)':>15}  {'Fraction (s)':>13}  {'ratio':>6}  same pivots")
    for n in (6, 12, 24, 48):
        M = _spd(n, rng)
        same = _exact_ldl(M).pivots == _fraction_pivots(M)
        fl = _median(lambda: _exact_ldl(M), args.repeat)
        fr = _median(lambda: _fraction_pivots(M), args.repeat)
        print(f"{n:>4}  {fl:>15.4f}  {fr:>13.4f}  {fr / fl:>6.1f}  {same}")


if __name__ == "__main__":
    main()
