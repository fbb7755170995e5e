"""Benchmark: lkverify's DDE simulator against jitcdde, at equal accuracy.

Run:  python3 benchmarks/bench_jitcdde.py [--t-end 100] [--repeat 3] [--profile]

Cases (t in [0, t_end], constant initial histories as catalogued):

* ``aleksandrov2023.fig1`` run 0: paper 002, Fig. 1 — a distributed-delay torque.
  lkverify turns each window integral into an auxiliary state
  ``z' = g(x(t)) - g(x(t - tau))`` and re-synchronises it by quadrature after each step (both paths);
  jitcdde integrates the same ``z'`` equation as an ordinary component.
* ``aleksandrov2026.example`` run 0: paper 000, "delayed feedback (7)" — a discrete
  delay tau = 1 in a 12-dimensional system.

What is measured
----------------
1. The jitcdde model is *generated* from ``compile_system(...).symbolic`` (the SymPy
   right-hand side lkverify itself compiles): y_i -> ``jitcdde.y(i)``,
   Z[k][i] -> ``jitcdde.y(i, t - lags[k])``, t -> ``jitcdde.t``, then ``symengine``.
   Its past is ``constant_past`` of the full initial vector lkverify uses (the window
   auxiliaries start at tau * g(x0), exact for a constant history), and the initial
   derivative jump is handled by ``step_on_discontinuities()`` (jitcdde's recommended
   way for constant pasts with fixed delays).
2. Reference: lkverify at rtol=1e-12, atol=1e-14 on a grid of 2001 points; it is
   cross-checked against jitcdde at its tightest setting and against lkverify at
   rtol=1e-11 (the differences are printed).
3. Tuning: for each tool, a ladder of (rtol, atol) is scanned from loose to tight; the
   chosen setting is the loosest one whose error — and the error at the next tighter
   rung — is <= 1e-6 (max over the grid and the state components, absolute;
   auxiliary components are not compared).
4. Times (wall clock, in this process):
   * lkverify ``total`` = ``simulate(...)`` end to end, best of --repeat: on the compiled
     integrator (row ``lkverify``; ``prepare_run``'s ``compile_system``, ``compile_family``'s
     SymPy work and the native code compiled by LLVM anew each time: the per-process cache
     of compiled families is emptied before every run, so nothing of the case is reused), and
     on SciPy's steppers (row ``scipy``, ``integrator="scipy"``, today's reference path);
     ``integrate`` is ``Trajectory.seconds`` of the same run (the kernel calls, resp.
     ``solve_dde``); ``setup`` is the difference.  The DOP853 kernel itself is compiled once per
     machine and loaded from numba's disk cache on the first run of a process (its load time
     is printed, not counted, as jitcdde's first compile with its setuptools import is not).
   * jitcdde ``setup`` = translating the SymPy rhs to symengine and building the
     ``jitcdde`` object; ``compile`` = ``compile_C()`` (symengine simplification for
     n <= 10, C code generation, gcc -O3, import), each time on a fresh ``jitcdde``
     object and so in a fresh temporary directory under a new module name — a cold
     compile, nothing cached (best of --repeat; the first compile of the process, which
     also imports setuptools, is printed separately); ``integrate`` = ``constant_past``
     + ``step_on_discontinuities`` + ``integrate(T)`` over the grid, best of --repeat
     on the compiled module; ``total`` = setup + compile + integrate.
   * ratios lkverify / jitcdde, total vs total and integrate vs integrate; the
     product's target is total ratio <= 1.  A "work" line gives lkverify's steps and
     rhs evaluations and jitcdde's step attempts (counted in an extra, untimed run).
     If lkverify is slower in total or in integration (or with --profile),
     ``simulate`` is profiled with cProfile: time per stage (the profiler inflates
     SymPy-heavy code, so compare the percentages with the unprofiled table) and the
     top functions by own time.

5. The fast path (``lkverify fast``): :func:`lkverify.simulate.family.compile_family` with
   the case's gains as runtime parameters (FAST_GRID; fig1 sweeps b and h through
   F = diag(h,h,h), as ``lkverify sweep`` does), integrated by the numba DOPRI5 of
   :mod:`lkverify.simulate.batch`.  ``setup`` = ``compile_family`` (SymPy: substitution, CSE,
   source), ``compile`` = the generated rhs compiled to native code (LLVM) in this process (the
   integrator kernel itself is compiled once per machine and loaded from numba's disk
   cache; a cold kernel compile is printed when it happens), ``integrate`` =
   ``CompiledFamily.integrate`` of the one point, wall clock, warm, best of --repeat
   (includes the per-point preparation: lags, breakpoints, initial state).  Tuned on the
   same ladder and error rule.  Its window auxiliaries are not re-synchronised.  The
   per-point time in a batch of 100 copies of the point is printed as well.

Translation notes: the rhs uses only +, *, integer powers, ``sqrt`` of constants and
``(...)**(3/10)``, which symengine prints as C ``sqrt``/``pow``.  jitcdde's ``min_step``
is lowered to 1e-16 (see MIN_STEP).  ``compile_C`` runs in an empty directory, because
setuptools' ``setup()`` would otherwise read the project's own pyproject.toml.

Not a test: numbers are printed, not asserted.  jitcdde is a benchmark-only
dependency (``python3 -m pip install jitcdde``).
"""

from __future__ import annotations

import argparse
import cProfile
import contextlib
import dataclasses
import io
import os
import platform
import pstats
import sys
import tempfile
import time
from importlib.metadata import version
import warnings

try:
    import jitcdde
    import symengine
except ImportError:
    print("jitcdde is not installed: python3 -m pip install jitcdde")
    sys.exit(2)

import numpy as np
import sympy

from lkverify.catalogue.loader import find_items
from lkverify.simulate import StepControl, compile_system, simulate
from lkverify.simulate import family as family_module
from lkverify.simulate.family import compile_family

CASES = [("aleksandrov2023.fig1", 0), ("aleksandrov2026.example", 0)]
# the fast path's runtime parameters per case: (grid names, templates replacing values, template name → the
# parameter entry giving its value at the case's point)
FAST_GRID = {
    "aleksandrov2023.fig1": (("b", "h"), {"F": "diag(h,h,h)"}, {"h": ("F", 0, 0)}),
    "aleksandrov2026.example": (("alpha1", "alpha2"), {}, {}),
}
BATCH = 100
N_GRID = 2001
TARGET = 1e-6
REF = (1e-12, 1e-14)
# (rtol, atol) rungs, loose to tight: half decades of rtol, atol = rtol/100 or rtol.
RTOLS = [1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10,
         3e-11, 1e-11]
ATOL_RATIOS = [1.0, 1e-2]
# constant_past gives the anchor at t0 the derivative 0, and jitcdde's first Bogacki–Shampine
# stage reuses it (k1 = anchor derivative), so the first step's error estimate is ~ dt·|f|:
# tolerances below ~1e-10 need a first step below jitcdde's default min_step = 1e-10.
MIN_STEP = 1e-16
JIT_TIGHTEST = REF


# -- one case -----------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Timing:
    """One tool at its chosen setting on one case (seconds)."""

    tool: str
    rtol: float
    atol: float
    error: float
    setup: float
    compile: float | None
    integrate: float
    total: float


@dataclasses.dataclass(frozen=True)
class Case:
    name: str
    label: str
    run: object
    comp: object       # lkverify CompiledSystem (for the translation and the initial vector)
    y0: np.ndarray     # full initial vector: states, then auxiliaries


class _ConstantPast:
    """A constant history seen as lkverify's ``past`` (exact quadrature of a constant)."""

    def __init__(self, y0):
        self.y0, self.t_last = y0, 0.0

    def integrate(self, g, a, b, *, with_time=False):
        if with_time:
            raise NotImplementedError("time-dependent auxiliary integrands are not benchmarked")
        return np.atleast_1d((b - a) * np.asarray(g(self.y0[None, :]), dtype=float)[0])


def load_case(name: str, index: int) -> Case:
    (ex,) = find_items(name)
    run = ex.runs[index]
    comp = compile_system(run.system, run.values)
    if comp.symbolic["quadratures"] or any(a.kind != "window" for a in comp.aux):
        raise SystemExit(f"{name}: only window auxiliaries can be translated to jitcdde; "
                         f"got {[a.kind for a in comp.aux]} and {len(comp.symbolic['quadratures'])} quadratures")
    x0 = np.zeros(comp.n_states)
    for state, sl in comp.layout.items():
        h = run.history[state]
        if callable(h):
            raise SystemExit(f"{name}: history of {state} is a function; this benchmark takes constant histories")
        x0[sl] = np.asarray(h, dtype=float)
    y0 = np.concatenate([x0, np.zeros(comp.n - comp.n_states)])
    if comp.aux:
        y0[comp.n_states:] = comp.aux_initial(0.0, _ConstantPast(y0))
    return Case(name, run.label, run, comp, y0)


def state_matrix(tr, layout) -> np.ndarray:
    """Trajectory states as one (m, n_states) array in layout order."""
    n = max(sl.stop for sl in layout.values())
    Y = np.empty((len(tr.t), n))
    for state, sl in layout.items():
        Y[:, sl] = tr.states[state]
    return Y


# -- lkverify -----------------------------------------------------------------

def run_lkverify(case: Case, grid, rtol, atol, integrator="auto"):
    """(states on grid, total s, integration s); the case's compiled functions are not reused (compiled anew)."""
    family_module._CACHE.clear()
    start = time.perf_counter()
    tr = simulate(case.run.system, history=case.run.history, t_end=float(grid[-1]), values=case.run.values,
                  step=StepControl(rtol=rtol, atol=atol), t_eval=grid, integrator=integrator)
    total = time.perf_counter() - start
    if tr.outcome.value != "success" or len(tr.t) != len(grid):
        raise RuntimeError(f"lkverify on {case.name} at rtol={rtol:g}: {tr.outcome.value} {tr.message}")
    return state_matrix(tr, case.comp.layout), total, tr.seconds


# -- lkverify fast path (compiled family, numba) ---------------------------------

def build_fast(case: Case):
    """(family, its point, setup s, numba compile s, kernel load s): compile_family, then the first compile."""
    names, templates, entries = FAST_GRID[case.name]
    resolved = case.run.system.parameters.resolve(case.run.values, use_defaults=True)
    h = {n: sympy.Symbol(n) for n in names}
    point = [float(resolved[entries[n][0]][entries[n][1], entries[n][2]]) if n in entries else float(resolved[n])
             for n in names]
    values = {k: v for k, v in case.run.values.items() if k not in names and k not in templates}
    values.update({k: sympy.sympify(v, locals={**h, "diag": sympy.diag}) for k, v in templates.items()})
    start = time.perf_counter()
    import lkverify.simulate.batch  # noqa: F401 - the kernel: from numba's disk cache, or compiled once (cold)
    kernel = time.perf_counter() - start
    start = time.perf_counter()
    fam = compile_family(case.run.system, values, grid=names)
    setup = time.perf_counter() - start
    start = time.perf_counter()
    fam.functions()
    compile_s = time.perf_counter() - start
    return fam, np.array(point, dtype=float), setup, compile_s, kernel


def run_fast(fam, point, case: Case, grid, rtol, atol, copies: int = 1):
    """(states of the first copy on grid, wall seconds of integrate, BatchResult)."""
    pts = np.repeat(point[None, :], copies, axis=0)
    start = time.perf_counter()
    res = fam.integrate(pts, case.run.history, t_end=float(grid[-1]), t_eval=grid, rtol=rtol, atol=atol)
    seconds = time.perf_counter() - start
    if res.outcomes[0].value != "success":
        raise RuntimeError(f"fast path on {case.name} at rtol={rtol:g}: {res.outcomes[0].value}")
    return res.y[0], seconds, res


# -- jitcdde ------------------------------------------------------------------

def translate(comp):
    """comp.symbolic → list of symengine expressions in jitcdde's y(i), y(i, t - lag), t.

    Returns (f_sym, notes): notes list the functions met and anything not translatable.
    """
    sym = comp.symbolic
    plain, target = {}, {}
    for i, s in enumerate(sym["y"]):
        plain[s] = sympy.Symbol(f"y_{i}")
        target[symengine.Symbol(f"y_{i}")] = jitcdde.y(i)
    for k, row in enumerate(sym["Z"]):
        for i, s in enumerate(row):
            plain[s] = sympy.Symbol(f"Z_{k}_{i}")
            target[symengine.Symbol(f"Z_{k}_{i}")] = jitcdde.y(i, jitcdde.t - comp.lags[k])
    plain[sym["t"]] = sympy.Symbol("t_")
    target[symengine.Symbol("t_")] = jitcdde.t
    notes, f_sym = [], []
    funcs = set()
    for i, e in enumerate(sym["rhs"]):
        e = e.xreplace(plain)
        funcs |= {type(f).__name__ for f in e.atoms(sympy.Function)}
        for p in e.atoms(sympy.Pow):
            if not p.exp.is_Integer:
                funcs.add(f"constant**({p.exp})" if p.base.is_number else f"state-dependent base**({p.exp})")
        se = symengine.sympify(e)
        try:
            symengine.ccode(se)
        except Exception as err:  # symengine's C printer is what jitcdde uses
            notes.append(f"component {i}: symengine cannot print {se} as C ({err})")
        f_sym.append(se.subs(target))
    notes.insert(0, f"functions met: {', '.join(sorted(funcs)) or 'none (polynomial)'}")
    return f_sym, notes


def build_jitcdde(case: Case):
    """(DDE, setup s, notes): translation and the jitcdde object, not compiled."""
    start = time.perf_counter()
    f_sym, notes = translate(case.comp)
    dde = jitcdde.jitcdde(f_sym, n=case.comp.n, delays=list(case.comp.lags), max_delay=max(case.comp.lags),
                          verbose=False)
    return dde, time.perf_counter() - start, notes


def run_jitcdde(dde, case: Case, grid, rtol, atol):
    """(states on grid, integration s) on an already compiled DDE."""
    n_states = case.comp.n_states
    start = time.perf_counter()
    dde.purge_past()
    dde.constant_past(case.y0, time=float(grid[0]))
    dde.set_integration_parameters(rtol=rtol, atol=atol, min_step=MIN_STEP)
    dde.step_on_discontinuities()
    t_now = dde.t
    early = grid[grid <= t_now]   # already stepped over: read from jitcdde's Hermite spline
    rows = [np.atleast_2d(dde.get_state().get_state(early))[:, :n_states]] if len(early) else []
    rows.append(np.array([dde.integrate(T)[:n_states] for T in grid[grid > t_now]]))
    seconds = time.perf_counter() - start
    return np.vstack(rows), seconds


def compile_jitcdde(case: Case, repeat: int):
    """Cold compiles on fresh objects: (compiled DDE, setup s, best compile s, all compile s, notes)."""
    compiles, setups = [], []
    for _ in range(repeat):
        dde, setup, notes = build_jitcdde(case)
        start = time.perf_counter()
        # jitcdde builds in its own temporary directory; setup() must not read our pyproject.toml
        with tempfile.TemporaryDirectory() as empty, contextlib.chdir(empty):
            dde.compile_C()
        compiles.append(time.perf_counter() - start)
        setups.append(setup)
    return dde, min(setups), min(compiles), compiles, notes


# -- tuning -------------------------------------------------------------------

def max_error(Y, ref) -> float:
    return float(np.max(np.abs(Y - ref)))


def tune(runner, ref, label):
    """Loosest (rtol, atol) with error <= TARGET there and at the next tighter rung.

    runner(rtol, atol) → states on the grid.  Returns ((rtol, atol), error, scan).
    """
    best, scan = None, []
    for ratio in ATOL_RATIOS:
        prev = None  # (setting, error) of the previous passing rung
        for rtol in RTOLS:
            setting = (rtol, rtol * ratio)
            try:
                err = max_error(runner(*setting), ref)
            except Exception as exc:  # noqa: BLE001 - a failed run is a failed rung
                err = float("inf")
                print(f"    {label} rtol={setting[0]:.0e} atol={setting[1]:.0e}: failed ({type(exc).__name__})")
            scan.append((setting, err))
            if err <= TARGET:
                if prev is not None:
                    break
                prev = (setting, err)
            else:
                prev = None
        if prev is not None and (best is None or prev[0] > best[0]):
            best = prev
    if best is None:
        raise RuntimeError(f"{label}: no setting on the ladder reaches {TARGET:g}")
    return best[0], best[1], scan


# -- main ---------------------------------------------------------------------

PROFILE_GROUPS = [  # (label, file suffix, function name): cumulative times, nested as indented
    ("simulate, end to end", "simulate.py", "simulate"),
    ("  compile_system (SymPy substitution, CSE, lambdify)", "simulate.py", "compile_system"),
    ("  solve_dde (the integration)", "dde.py", "solve_dde"),
    ("    SciPy rk_step (stages; calls most of the rhs below)", "rk.py", "rk_step"),
    ("    rhs: delayed-value lookup + generated f", "dde.py", "rhs"),
    ("      DenseHistory._lookup (Z rows)", "dde.py", "_lookup"),
    ("      compiled fun (lambdified rhs)", "simulate.py", "fun"),
    ("    resync of window auxiliaries (quadrature)", "simulate.py", "resync"),
]


def profile_simulate(case: Case, grid, rtol, atol, top: int = 10) -> str:
    """cProfile of one simulate run: a grouped summary, then the top functions by own time."""
    prof = cProfile.Profile()
    prof.enable()
    simulate(case.run.system, history=case.run.history, t_end=float(grid[-1]), values=case.run.values,
                  step=StepControl(rtol=rtol, atol=atol), t_eval=grid)
    prof.disable()
    stats = pstats.Stats(prof)
    total = max(ct for (_, _, name), (_, _, _, ct, _) in stats.stats.items() if name == "simulate")
    lines = []
    for label, suffix, func in PROFILE_GROUPS:
        ct = sum(v[3] for (f, _, name), v in stats.stats.items() if name == func and f.endswith(suffix))
        if ct:
            lines.append(f"  {label:58s} {ct:7.3f} s  {100 * ct / total:5.1f} %")
    out = io.StringIO()
    pstats.Stats(prof, stream=out).strip_dirs().sort_stats("tottime").print_stats(top)
    table = [ln for ln in out.getvalue().splitlines() if ln.strip()]
    start = next(i for i, ln in enumerate(table) if ln.lstrip().startswith("ncalls"))
    return "\n".join(lines + ["  top functions by own time (profiled):"] + table[start:])


def count_jitcdde_steps(dde, case: Case, grid, rtol, atol) -> int:
    """Step attempts (each 3 evaluations of f, more when the delay lies within the step) of one untimed run."""
    attempts = 0
    original = dde.try_single_step

    def counting(length):
        nonlocal attempts
        attempts += 1
        return original(length)

    dde.try_single_step = counting
    try:
        run_jitcdde(dde, case, grid, rtol, atol)
    finally:
        del dde.try_single_step
    return attempts


def bench_case(case: Case, grid, repeat: int, force_profile: bool) -> tuple:
    """Reference, cross-checks, tuning and timing of one case; prints as it goes."""
    print(f"\n== {case.name}: {case.label}  (n = {case.comp.n_states} states + {case.comp.n - case.comp.n_states} "
          f"auxiliaries, lags {case.comp.lags})")
    ref, ref_total, _ = run_lkverify(case, grid, *REF)
    near, _, _ = run_lkverify(case, grid, REF[0] * 10, REF[1] * 10)
    print(f"  reference lkverify rtol={REF[0]:.0e} atol={REF[1]:.0e}: {ref_total:.2f} s; "
          f"vs lkverify rtol=1e-11: {max_error(near, ref):.2e}")

    dde, setup_j, compile_j, compiles, notes = compile_jitcdde(case, repeat)
    for note in notes:
        print(f"  translation: {note}")
    print(f"  jitcdde compile_C (cold, fresh temp dir each): {', '.join(f'{c:.2f}' for c in compiles)} s "
          f"(first includes importing setuptools)")
    tight, tight_s = run_jitcdde(dde, case, grid, *JIT_TIGHTEST)
    print(f"  cross-check: jitcdde rtol={JIT_TIGHTEST[0]:.0e} atol={JIT_TIGHTEST[1]:.0e} vs reference: "
          f"{max_error(tight, ref):.2e}  ({tight_s:.1f} s)")

    fam, point, fast_setup, fast_compile, kernel = build_fast(case)
    print(f"  fast path: grid {fam.grid} at {point.tolist()}; compile_family {fast_setup:.3f} s, native rhs "
          f"{fast_compile:.3f} s, integrator kernel import {kernel:.3f} s"
          f"{' (cold compile: first run on this machine)' if kernel > 5 else ' (numba disk cache)'}")
    lk_set, lk_err, lk_scan = tune(lambda r, a: run_lkverify(case, grid, r, a)[0], ref, "lkverify")
    sp_set, sp_err, sp_scan = tune(lambda r, a: run_lkverify(case, grid, r, a, "scipy")[0], ref, "scipy")
    jit_set, jit_err, jit_scan = tune(lambda r, a: run_jitcdde(dde, case, grid, r, a)[0], ref, "jitcdde")
    fast_set, fast_err, fast_scan = tune(lambda r, a: run_fast(fam, point, case, grid, r, a)[0], ref, "fast")
    for tool, scan in (("lkverify", lk_scan), ("scipy", sp_scan), ("jitcdde", jit_scan), ("fast", fast_scan)):
        for ratio in ATOL_RATIOS:
            rungs = [f"{r:.0e}:{e:.1e}" for (r, a), e in scan if a == r * ratio]
            print(f"  scan {tool:8s} atol=rtol*{ratio:g}  rtol:error  {'  '.join(rungs)}")

    lk_runs = [run_lkverify(case, grid, *lk_set) for _ in range(repeat)]
    lk_total = min(r[1] for r in lk_runs)
    lk_int = min(r[2] for r in lk_runs)
    sp_runs = [run_lkverify(case, grid, *sp_set, "scipy") for _ in range(repeat)]
    sp_total, sp_int = min(r[1] for r in sp_runs), min(r[2] for r in sp_runs)
    jit_int = min(run_jitcdde(dde, case, grid, *jit_set)[1] for _ in range(repeat))
    tr = simulate(case.run.system, history=case.run.history, t_end=float(grid[-1]), values=case.run.values,
                  step=StepControl(rtol=lk_set[0], atol=lk_set[1]), t_eval=grid)
    fast_runs = [run_fast(fam, point, case, grid, *fast_set) for _ in range(repeat)]
    fast_int = min(r[1] for r in fast_runs)
    fres = fast_runs[0][2]
    batch = min(run_fast(fam, point, case, grid, *fast_set, copies=BATCH)[1] for _ in range(repeat))
    attempts = count_jitcdde_steps(dde, case, grid, *jit_set)
    print(f"  lkverify's integrator: {tr.integrator}")
    print(f"  work at the chosen settings: lkverify {tr.n_steps} steps, {tr.nfev} rhs evaluations "
          f"({1e6 * lk_int / tr.nfev:.1f} µs each, integration time / evaluations); "
          f"jitcdde {attempts} step attempts ({1e6 * jit_int / attempts:.1f} µs each)")
    print(f"  fast path at its setting: {int(fres.n_steps[0])} steps ({int(fres.n_rejected[0])} rejected), "
          f"{int(fres.nfev[0])} rhs evaluations ({1e9 * fast_int / fres.nfev[0]:.0f} ns each, integrate / "
          f"evaluations); batch of {BATCH} copies: {1e3 * batch / BATCH:.3f} ms per point "
          f"(single point {1e3 * fast_int:.3f} ms)")
    fast = Timing("fast", *fast_set, fast_err, fast_setup, fast_compile, fast_int,
                  fast_setup + fast_compile + fast_int)
    lk = Timing("lkverify", *lk_set, lk_err, lk_total - lk_int, None, lk_int, lk_total)
    sp = Timing("scipy", *sp_set, sp_err, sp_total - sp_int, None, sp_int, sp_total)
    jit = Timing("jitcdde", *jit_set, jit_err, setup_j, compile_j, jit_int, setup_j + compile_j + jit_int)
    profile = None
    if force_profile or lk.total > jit.total or lk.integrate > jit.integrate:
        profile = profile_simulate(case, grid, *lk_set)
    return lk, jit, fast, batch / BATCH, profile, sp


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--t-end", type=float, default=100.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--profile", action="store_true", help="profile lkverify even where it is faster")
    args = ap.parse_args()
    if args.repeat < 1 or not args.t_end > 1.0:
        ap.error("--repeat must be >= 1 and --t-end > 1 (longer than the delays)")
    # integrate(T) with T inside the last (long) step interpolates, and says so each time
    warnings.filterwarnings("ignore", message="The target time is smaller than the current time")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, jitcdde {version('jitcdde')}, "
          f"symengine {symengine.__version__}")
    print(f"grid: {N_GRID} points on [0, {args.t_end:g}]; error target {TARGET:g} (max abs over grid and states)")
    grid = np.linspace(0.0, args.t_end, N_GRID)
    rows = {name: bench_case(load_case(name, idx), grid, args.repeat, args.profile) for name, idx in CASES}

    print(f"\n{'case':24s} {'tool':9s} {'rtol':>7s} {'atol':>7s} {'max err':>9s} {'setup s':>8s} "
          f"{'compile s':>9s} {'integr s':>9s} {'total s':>8s}")
    for name, (lk, jit, fast, _, _, sp) in rows.items():
        for r in (lk, sp, jit, fast):
            compile_s = f"{r.compile:9.3f}" if r.compile is not None else f"{'-':>9s}"
            print(f"{name:24s} {r.tool:9s} {r.rtol:7.0e} {r.atol:7.0e} {r.error:9.2e} {r.setup:8.3f} "
                  f"{compile_s} {r.integrate:9.4f} {r.total:8.3f}")
    print("\nratio lkverify simulate / jitcdde (same run; targets integration <= 0.1, total <= 0.5):")
    for name, (lk, jit, _, _, _, sp) in rows.items():
        ti, tt = lk.integrate / jit.integrate, lk.total / jit.total
        print(f"  {name:24s} total {tt:6.2f}   integration {ti:6.2f}   "
              f"({'met' if ti <= 0.1 and tt <= 0.5 else 'not met'}; SciPy path: total {sp.total / jit.total:.2f}, "
              f"integration {sp.integrate / jit.integrate:.2f})")
    print("\nratio fast path / jitcdde (same run; target integration <= 1.0):")
    for name, (_, jit, fast, per_point, _, _) in rows.items():
        print(f"  {name:24s} total {fast.total / jit.total:6.2f}   integration {fast.integrate / jit.integrate:6.2f}"
              f"   per point in a batch of {BATCH}: {1e3 * per_point:.3f} ms ({per_point / jit.integrate:.2f} "
              f"of jitcdde's integration)")
    for name, (lk, _, _, _, profile, _) in rows.items():
        if profile:
            print(f"\nprofile of lkverify simulate, {name} at rtol={lk.rtol:.0e} atol={lk.atol:.0e}:")
            print(profile)


if __name__ == "__main__":
    main()
