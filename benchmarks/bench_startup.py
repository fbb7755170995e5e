"""Benchmark: cold start of the command line (issue 25): --help, --version, list, an unknown name, import lkverify.

Run:  python3 benchmarks/bench_startup.py [--repeat N] [--tree DIR]

Each command runs in a fresh interpreter (``python -m lkverify …``, so no shell shim is timed),
--repeat times (default 5); the table gives the median and the fastest wall-clock time, and the
target on an idle 2-core machine (--help, --version under 1 s; list and the refusal of an unknown
name under 2 s).  ``--tree DIR`` times another checkout's ``lkverify`` package instead (DIR is put
first on PYTHONPATH; e.g. a ``git worktree`` of an older commit, for a before/after comparison).
A first untimed run of each command warms the bytecode cache.  Numbers are printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import time

from _tree import load_average, tree_env

#: label, arguments of ``python``, expected exit code, target in seconds (None: no target)
COMMANDS = (
    ("python -c pass (the interpreter alone)", ["-c", "pass"], 0, None),
    ("python -c 'import lkverify'", ["-c", "import lkverify"], 0, None),
    ("lkverify --help", ["-m", "lkverify", "--help"], 0, 1.0),
    ("lkverify --version", ["-m", "lkverify", "--version"], 0, 1.0),
    ("lkverify list", ["-m", "lkverify", "list"], 0, 2.0),
    ("lkverify list --json", ["-m", "lkverify", "list", "--json"], 0, 2.0),
    ("lkverify check aleksandrov2023.theorm3", ["-m", "lkverify", "check", "aleksandrov2023.theorm3"], 2, 2.0),
)


def _time(argv: list, code: int, env: dict) -> float:
    start = time.perf_counter()
    done = subprocess.run([sys.executable, *argv], capture_output=True, env=env, cwd=os.path.expanduser("~"))
    seconds = time.perf_counter() - start
    if done.returncode != code:
        raise SystemExit(f"{' '.join(argv)}: exit {done.returncode}, expected {code}: {done.stderr.decode()[-300:]}")
    return seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5, help="runs of each command (default 5); the median is shown")
    ap.add_argument("--tree", default=None, metavar="DIR", help="time the lkverify package of this checkout")
    args = ap.parse_args()
    env, load = tree_env(args.tree), load_average()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, load {load:.2f}, "
          f"Python {platform.python_version()}; {args.repeat} runs each"
          + (f"; tree {args.tree}" if args.tree else ""))
    print(f"{'command':<42} {'median':>8} {'fastest':>8} {'target':>8}")
    for label, argv, code, target in COMMANDS:
        _time(argv, code, env)  # warm the bytecode cache, untimed
        runs = [_time(argv, code, env) for _ in range(args.repeat)]
        goal = f"< {target:g} s" if target is not None else ""
        mark = "" if target is None else ("  ok" if statistics.median(runs) < target else "  over")
        print(f"{label:<42} {statistics.median(runs):7.2f}s {min(runs):7.2f}s {goal:>8}{mark}")


if __name__ == "__main__":
    main()
