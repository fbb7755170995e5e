"""Benchmark: bound steps, one by one, and the whole chain of Theorem 3 of paper 002.

Run:  python benchmarks/bench_steps.py [--repeat N]

For every term bound of the three steps of aleksandrov2023.theorem3 (V ≥ L, V ≤ U,
V̇ ≤ W) it times the rule check alone; then each mutated term bound (0.9× a template
constant, |b| dropped, an exponent off by one) with its witness search; the printed
steps of papers 000, 001 and 002 (refuted) and their corrected forms (proved); and the
whole chain: the three steps and the certified decay, as ``lkverify check`` runs it.
Numbers are printed (best of N), never asserted.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import time

import sympy


def _best(fn, repeat):
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}")
    from lkverify.proofs.aleksandrov2017 import P as P001
    from lkverify.proofs.aleksandrov2017.theorem1_bound import corrected as c001, printed as p001
    from lkverify.proofs.aleksandrov2023 import P
    from lkverify.proofs.aleksandrov2023 import theorem3_chain as C
    from lkverify.proofs.aleksandrov2023.theorem3 import steps, theorem3
    from lkverify.proofs.aleksandrov2023.theorem3_bound import corrected as c002, printed as p002
    from lkverify.proofs.aleksandrov2026 import P as P000
    from lkverify.proofs.aleksandrov2026.theorem2_bound import REMARK3, corrected as c000, printed as p000

    values = P.resolve(dict(C.CHOICES), use_defaults=True)
    rows = []
    checked = {}
    for step in steps:
        for tb in step.bounds:
            one = dataclasses.replace(step, bounds=(tb,), rhs=tb.bound, part=tb.terms)
            dt, res = _best(lambda: one.check(values), args.repeat)
            rows.append((f"{step.name}: {' + '.join(tb.terms)[:48]}", res.status.value, dt))
        dt, res = _best(lambda: step.check(values), args.repeat)
        rows.append((f"{step.name} (whole step)", res.status.value, dt))
        checked[step.role] = (step, res)
    lower, upper, vdot = steps
    kappa = sympy.Rational(checked["lower"][1].constants["kappa1"])
    jl = "λbωᵀ∫‖s(ξ)−r‖^{μ−1}s(ξ)×r dξ"
    jb = next(tb for tb in vdot.bounds if jl in tb.terms)
    kb = next(tb for tb in lower.bounds if "(s×r)ᵀF⁻¹Θω" in tb.terms)
    mutations = {
        "0.9 × κ1 (V ≥ L)": dataclasses.replace(lower, bounds=(dataclasses.replace(
            kb, bound=-sympy.Rational(9, 10) * kappa * C.e * C.w),), rhs=0, part=kb.terms),
        "|b| dropped (V̇ ≤ W)": dataclasses.replace(vdot, bounds=(dataclasses.replace(
            jb, bound=jb.bound.replace(sympy.Abs, lambda x: x)),), rhs=0, part=jb.terms),
        "exponent + 1 (V̇ ≤ W)": dataclasses.replace(vdot, bounds=(dataclasses.replace(
            jb, bound=jb.bound * C.j),), rhs=0, part=jb.terms),
    }
    for name, step in mutations.items():
        step = dataclasses.replace(step, rhs=step.bounds[0].bound)
        dt, res = _best(lambda: step.check(values), args.repeat)
        rows.append((f"mutation: {name}", res.status.value, dt))
    printed = [("002 printed b(λ + c7τ)", p002, P.resolve({}, use_defaults=True)),
               ("002 corrected |b|", c002, P.resolve({}, use_defaults=True)),
               ("000 printed γβc7 (β = −1)", p000, P000.resolve(REMARK3, use_defaults=True)),
               ("000 corrected γ|β|c7", c000, P000.resolve(REMARK3, use_defaults=True)),
               ("001 printed h^{ν−1}ḣ", p001, P001.resolve({}, use_defaults=True)),
               ("001 corrected |ḣ|", c001, P001.resolve({}, use_defaults=True))]
    for name, step, v in printed:
        dt, res = _best(lambda: step.check(v), args.repeat)
        rows.append((name, res.status.value, dt))
    dt, report = _best(lambda: theorem3.run({}, budget=None), args.repeat)
    rows.append(("theorem3: the whole chain (check)", report.verdict.split(":")[0], dt))
    width = max(len(r[0]) for r in rows)
    for name, status, dt in rows:
        print(f"{name:<{width}}  {status:<12} {dt:8.2f} s")


if __name__ == "__main__":
    main()
