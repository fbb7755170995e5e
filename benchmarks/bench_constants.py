"""Benchmark: certified constants (issue "constants"): each template constant and the flagship.

Run:  python3 benchmarks/bench_constants.py

Prints, for aleksandrov2023.theorem3 at the Fig. 6 parameters, the time to
certify each template constant to within 1% of its estimate, the whole flagship
job (constants, parameter search, certification, simulated cross-check), and
Lemma 1's δ(ε) for ε = 0.5, 0.9, 0.99.  Numbers are printed, never asserted.
"""

from __future__ import annotations

import os
import platform
import time

from lkverify.certify import bounds
from lkverify.options import Accuracy, Budget
from lkverify.catalogue.loader import find_items


def main() -> None:
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    (th,) = find_items("aleksandrov2023.theorem3")
    values = th.parameters.resolve({}, use_defaults=True)
    for tpl in th.constants.templates:
        t0 = time.perf_counter()
        res = bounds.sup_bound(tpl.expr(values), tpl.box(values), accuracy=Accuracy(rel_gap=1e-2),
                               budget=Budget(seconds=60), enclosure="mean-value")
        print(f"constant {tpl.name:8s} estimate {res.estimate:.6g}  certified ≤ {res.certified:.6g}  "
              f"gap {res.gap:.2%}  status {res.status.value}  {res.boxes} boxes  {time.perf_counter() - t0:.2f} s")
    t0 = time.perf_counter()
    report, _ = th.run_constants({}, budget=150)
    total = time.perf_counter() - t0
    by = {r.name: r for r in report.results}
    print("flagship: " + ", ".join(f"{k} = {by[k].value['value']:.4g} ({by[k].status.value})"
                                   for k in ("d1", "d2", "d3", "delta_tilde")) + f"  in {total:.1f} s")
    (lem,) = find_items("aleksandrov2017.lemma1")
    for eps in ("0.5", "0.9", "0.99"):
        t0 = time.perf_counter()
        rep, _ = lem.run_constants({"eps": eps})
        (r,) = rep.results
        print(f"lemma1 eps={eps}: certified δ = {r.value['certified']:.6g} (sampled largest "
              f"{r.value['estimate_largest']:.6g}) {r.status.value} in {time.perf_counter() - t0:.2f} s")


if __name__ == "__main__":
    main()
