"""The ``lkverify`` command line.

``lkverify`` (= ``lkverify report [--json]``)  report of every catalogued item at the papers' defaults
``lkverify list``                  the catalogue
``lkverify check ITEM [--set NAME=VALUE]... [--box NAME=LO:HI]... [--max-boxes N] [--json] [--budget S] [--load-limit S] [--no-cache]``
``lkverify cache {info,clear} [--json]``  the proof cache of decided reports (:mod:`lkverify.cache`)
``lkverify simulate ITEM [--set NAME=VALUE]... [--history STATE=VALUE]... [--t-end T] [--plot FILE.png] [--envelope] [--convention NAME] [--distance {combined,per-vector}] [--json] [--budget S]``
``lkverify constants ITEM [--set NAME=VALUE]... [--goal GOAL] [--plot FILE.png] [--json] [--budget S]``
``lkverify linear --set A=[[…]] [--set Ad=[[…]]] [--set D=[[…]]] [--orders 0,1,2] [--h-max H] [--h H] [--plot F.png] [--json]``

Exit codes: 0 every result holds (for the bare report: the report was produced),
1 something failed or is undecided (a budget ran out) or a theorem is not established
(a missing link), 2 bad input (one line on
stderr), 3 an internal error of lkverify (one line on stderr; set the environment
variable ``LKVERIFY_TRACEBACK=1`` to see the traceback), 130 interrupted (Ctrl-C).
Bad input is refused before any computing: values, output paths (``--plot``),
goals and budgets are checked first.

Progress lines go to stderr (whether or not it is a terminal) once a job has run for
:data:`PROGRESS_GRACE_SECONDS`, at most one a second; ``--quiet`` silences them.

Budgets (``--budget SECONDS``) are positive finite numbers up to
:data:`lkverify.options.MAX_BUDGET_SECONDS` (1e6 s); ``inf`` and larger values are
refused.  ``check``: the whole check, your own cap (default none: deterministic work limits decide).  ``constants``: the whole job
(default 150 s).  ``simulate``: all runs of the example together (default
:data:`lkverify.catalogue.examples.DEFAULT_SIMULATE_BUDGET`).  Loading a proof file is not
covered by ``--budget``: it has its own limit, ``--load-limit`` (default 60 s).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

# light imports only: ``--help``, ``--version``, ``list`` and an unknown name load no SymPy, no NumPy (the
# subcommands import what they compute with, and a subcommand's arguments are added on first use: _Parser.fill)
from ._version import __version__
from .options import LOAD_LIMIT_SECONDS, MAX_BUDGET_SECONDS, BudgetExceeded
from .catalogue.loader import catalogue, find_items  # light: proofs are imported on first use
from .errors import InputError, InternalError, UnsupportedInput

#: exit code of an unexpected exception (a bug in lkverify); see the module docstring
EXIT_INTERNAL = 3

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    #: ``fill(parser)`` adds a subcommand's arguments on first use (parsing it, or its help): those whose help or
    #: choices come from the simulator or Dask are not imported for ``--help``, ``list`` or ``check``
    fill = None

    def error(self, message):  # one line, exit code 2, no traceback
        self.exit(2, f"lkverify: error: {message} (see `lkverify --help`)\n")

    def filled(self) -> None:
        fill, self.fill = self.fill, None
        if fill is not None:
            fill(self)

    def parse_known_args(self, args=None, namespace=None):
        self.filled()
        return super().parse_known_args(args, namespace)

    def format_help(self):
        self.filled()
        return super().format_help()

    def format_usage(self):
        self.filled()
        return super().format_usage()


def _seconds(text: str) -> float:
    """argparse type of --budget / --load-limit: a positive finite number of seconds, at most 1e6."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds such as 30, got {text!r}") from None
    if not math.isfinite(v) or not v > 0:
        raise argparse.ArgumentTypeError(f"expected a positive finite number of seconds, got {text!r}; "
                                         f"pass e.g. 30 (at most {MAX_BUDGET_SECONDS:g})")
    if v > MAX_BUDGET_SECONDS:
        raise argparse.ArgumentTypeError(f"expected at most {MAX_BUDGET_SECONDS:g} seconds (about 11.6 days), "
                                         f"got {text!r}; pass a smaller budget")
    return v


def _add_load_limit(p) -> None:
    p.add_argument("--load-limit", type=_seconds, default=LOAD_LIMIT_SECONDS, metavar="SECONDS",
                   help=f"time limit for loading (importing) a proof file, not covered by --budget "
                        f"(default {LOAD_LIMIT_SECONDS:g})")


def _build_parser(*, lazy: bool = False) -> argparse.ArgumentParser:
    """The parser; ``lazy``: the subcommands' arguments that need heavy imports are added on first use."""
    p = _Parser(prog="lkverify", description="Check Lyapunov–Krasovskii stability proofs. "
                "With no command: the report of every catalogued item at the papers' defaults.")
    sub = p.add_subparsers(dest="command", parser_class=_Parser)
    p.add_argument("--quiet", action="store_true", default=False, help=QUIET_HELP)
    p.add_argument("--verbose", action="store_true", default=False, help=VERBOSE_HELP)
    _add_no_cache(p)
    p.add_argument("--version", action="version", version=f"lkverify {__version__}",
                   help="print lkverify's version (from the installed package's metadata) and exit")
    lp = sub.add_parser("list", help="list the catalogue: name, kind (theorem, check, example) and title")
    lp.add_argument("--json", action="store_true", help="print a JSON list of objects with the keys item, kind, title")
    _add_quiet(lp)
    rp = sub.add_parser("report", help="report every catalogued item at the papers' defaults (what the bare "
                        "`lkverify` does); prints progress lines on stderr, about a minute on 2 cores, a second "
                        "from the proof cache")
    rp.add_argument("--json", action="store_true", help="print a JSON list with one object per item: item, "
                    "parameters, results (kind, name, status, value, detail), verdict and versions")
    rp.add_argument("--jobs", type=int, default=None, metavar="N",
                    help="items run on a local Dask cluster of N worker processes; 1: one after the other in this "
                         "process (default: one worker per CPU when 4 or more items are to be run); the output "
                         "order is the catalogue's")
    rp.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the items on a running Dask scheduler (tcp://host:8786), or 'local' for a local "
                         "cluster of one worker per CPU; default: see --jobs")
    _add_quiet(rp)
    _add_verbose(rp)
    _add_no_cache(rp)
    cp = sub.add_parser("cache", help="the proof cache of decided reports: where it is and its size (info), or "
                        "empty it (clear)")
    cp.add_argument("action", choices=("info", "clear"),
                    help="info: the cache's directory, entries and size; clear: delete every entry")
    cp.add_argument("--json", action="store_true", help="print one JSON object")
    _add_check(sub)
    _add_simulate(sub)
    _add_constants(sub)
    _add_linear(sub)
    from .sweep import cli as sweep_cli  # light: the sweep's modules are imported when it runs

    sub.add_parser("sweep", help=sweep_cli.HELP).fill = lambda sp: sweep_cli.add_arguments(
        sp, quiet=_add_quiet, seconds=_seconds, json_help=JSON_HELP)
    if not lazy:
        for sp in dict.fromkeys(sub.choices.values()):
            sp.filled()
    return p


def _add_check(sub) -> None:
    """``lkverify check``: a theorem or check at given values, or over a box of them."""
    c = sub.add_parser("check", help="check an item's hypotheses and identities")
    c.add_argument("item", help="catalogue name (aleksandrov2023.theorem3), a paper, or path/to/proof.py[::item]")
    c.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value: a number, diag(2,2,2), [[2,0],[0,2]], or an expression in t")
    c.add_argument("--box", dest="boxes", action="append", default=[], metavar="NAME=LO:HI",
                   help="check the theorem for every value of NAME in [LO, HI] (exact rationals such as -11/10; a "
                        "float end makes the results at most certified); repeat for a box of several parameters")
    c.add_argument("--max-boxes", type=int, default=None, metavar="N",
                   help="the work limit of a --box run: pieces of the subdivision checked (default 16)")
    c.add_argument("--json", action="store_true", help=JSON_HELP)
    _add_quiet(c)
    _add_verbose(c)
    _add_no_cache(c)
    c.add_argument("--budget", type=_seconds, default=None, metavar="SECONDS",
                   help="your own time cap of the whole check; what it cuts is undecided (default: none -- the check "
                        "stops at its deterministic work limits, so its verdict is the same on any machine; at most 1e6)")
    _add_load_limit(c)


def _add_simulate(sub) -> None:
    """``lkverify simulate``: a numerical example (its arguments added on first use: they import the simulator)."""
    sub.add_parser("simulate", help="integrate a numerical example and check the paper's claims about it").fill = \
        _simulate_arguments


def _simulate_arguments(s) -> None:
    from .catalogue.examples import DEFAULT_SIMULATE_BUDGET, MAX_STEPS
    from .simulate.figures import DISTANCES
    from .simulate.rigidbody import CONVENTIONS, DEFAULT_CONVENTION
    from .simulate.solver import FLOOR_WINDOW

    s.add_argument("item", help="an example (aleksandrov2023.fig6), or path/to/file.py[::item]")
    s.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value for every run of the example")
    s.add_argument("--history", dest="histories", action="append", default=[], metavar="STATE=VALUE",
                   help="an initial history for a state: a constant vector, e.g. omega=[0.1,0.1,0.1], or one in t, "
                        "e.g. omega=[sin(t)/10,0,0] (an example with an envelope takes constant ones)")
    s.add_argument("--t-end", type=float, default=None, metavar="T", help="final time (default: the example's)")
    s.add_argument("--plot", metavar="FILE.png",
                   help="write the figure (paper style) to this file: PNG, or PDF/SVG by the suffix .pdf/.svg")
    s.add_argument("--envelope", action="store_true", help="cross-check the example's decay envelope and plot it")
    s.add_argument("--json", action="store_true", help=JSON_HELP + "; for simulate also runs (label, title, "
                   "resolved parameters, the history used and which states --history overrode), convention, "
                   "distance, figures (paths written) and versions (lkverify, numpy, scipy, sympy)")
    s.add_argument("--convention", default=None, metavar="NAME",
                   help="aircraft-angle convention of the examples' initial data (given as angles), one of: "
                        + "; ".join(f"{k}: {v}" for k, v in CONVENTIONS.items())
                        + f" (aliases gost, krylov = yzx; aerospace, nasa = zyx; default {DEFAULT_CONVENTION})")
    s.add_argument("--distance", choices=sorted(DISTANCES), default=None,
                   help="distance of the convergence claims and of the times to 1e-2 and 1e-3: "
                        + "; ".join(f"{k} = {v}" for k, v in DISTANCES.items()) + " (default combined; for the examples that name their distances)")
    _add_quiet(s)
    _add_verbose(s)
    s.add_argument("--budget", type=_seconds, default=DEFAULT_SIMULATE_BUDGET, metavar="SECONDS",
                   help=f"time budget for all runs together; a run cut short is undecided (default "
                        f"{DEFAULT_SIMULATE_BUDGET:g}). Steps are at most min(delays) long, so a run needs at least "
                        f"(t_end - t0)/min(delays) steps: more than {MAX_STEPS:.0e} is refused up front (tiny delay, "
                        f"huge --t-end), and a run whose last {FLOOR_WINDOW} steps average less than the step floor "
                        f"(t_end - t0)/{MAX_STEPS:.0e} is stopped: diverged (a blow-up) or step_collapse (stiff)")
    _add_load_limit(s)


def _add_constants(sub) -> None:
    """``lkverify constants``: the certified constants, region and envelope of a proof."""
    k = sub.add_parser("constants", help="compute and certify the constants, region and envelope of a proof")
    k.add_argument("item", help="e.g. aleksandrov2023.theorem3, aleksandrov2017.lemma1")
    k.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value (a number read exactly, diag(2,2,2), [[2,0],[0,2]], a vector [0,0,1]), "
                        "e.g. --set eps=0.9 for aleksandrov2017.lemma1")
    k.add_argument("--json", action="store_true", help=JSON_HELP)
    _add_quiet(k)
    _add_verbose(k)
    k.add_argument("--plot", metavar="FILE.png",
                   help="write the figure (envelope, or δ(ε) for a lemma): PNG, or PDF/SVG by the suffix")
    k.add_argument("--budget", type=_seconds, default=150.0, metavar="SECONDS",
                   help="time budget of the whole job; when spent the unfinished results are undecided "
                        "(default 150, at most 1e6)")
    _add_load_limit(k)
    k.add_argument("--goal", default=None, help="which trade-off to optimise, for items that offer several "
                   "(aleksandrov2023.theorem3: paper = match d1, d2, d3 and maximise δ̃; region = maximise δ̃)")


def _add_linear(sub) -> None:
    """``lkverify linear``: a user's linear delay system (issue 13)."""
    lin = sub.add_parser("linear", help="a linear delay system x' = A x + Ad x(t-h) + int_{t-h}^t D x: spectral "
                         "abscissa, stability intervals, delays certified by LK LMIs (exact re-verification)")
    lin.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                     help="A, Ad, D (constant kernel) or D0, D1, … (kernel sum D_j u^j): matrices such as "
                          "A=[[-2,0],[0,-0.9]], read exactly")
    lin.add_argument("--orders", default="0,1,2,3,4", metavar="N,N,…",
                     help="orders of the LMI hierarchy: 0 Jensen, 1 Wirtinger, ≥ 2 Bessel–Legendre (default 0,1,2,3,4)")
    lin.add_argument("--h-max", type=float, default=20.0, metavar="H",
                     help="the largest delay of the stability analysis (default 20)")
    lin.add_argument("--h", default=None, metavar="H",
                     help="one delay: report the spectrum there and solve/verify each order's LMI at it (no bisection)")
    lin.add_argument("--plot", metavar="FILE.png", help="write the spectrum and the spectral abscissa over h")
    lin.add_argument("--json", action="store_true", help=JSON_HELP)
    _add_quiet(lin)


#: progress lines start once a job has run this long (bad input is refused before: never preceded)
PROGRESS_GRACE_SECONDS = 3.0
#: at most one progress line per this many seconds (item lines of the bare report excepted)
PROGRESS_INTERVAL_SECONDS = 1.0

QUIET_HELP = "print no progress lines on stderr (by default a job longer than a few seconds prints them)"
JSON_HELP = ("print one JSON object per item instead of the table: item, parameters, results (kind, name, status, "
             "value, detail), verdict, for theorems the chain of links, and versions (lkverify, sympy, "
             "python-flint, numpy, scipy, cvxpy, clarabel)")


def _add_quiet(p) -> None:
    p.add_argument("--quiet", action="store_true", default=argparse.SUPPRESS, help=QUIET_HELP)


VERBOSE_HELP = ("the text report in full: table cells and detail lines are not cut at three lines (every line "
                "still wraps at 100 columns); --json has everything too")


def _add_verbose(p) -> None:
    p.add_argument("--verbose", action="store_true", default=argparse.SUPPRESS, help=VERBOSE_HELP)


def _add_no_cache(p) -> None:
    p.add_argument("--no-cache", action="store_true", default=argparse.SUPPRESS,
                   help="recompute and do not store: bypass the proof cache of decided reports (`lkverify cache info`; "
                        "also LKVERIFY_CACHE=off)")


def _note(msg: str) -> None:
    """A line on stderr at once (not throttled, no grace period): e.g. that a report came from the proof cache."""
    print(f"lkverify: {msg}", file=sys.stderr, flush=True)


def _progress(enabled: bool):
    """``say(msg, force=False)``: a progress line on stderr, after the grace period, throttled."""
    start = time.monotonic()
    last = [-math.inf]

    def say(msg: str, force: bool = False):
        if not enabled:
            return
        now = time.monotonic()
        if now - start < PROGRESS_GRACE_SECONDS:
            return
        if not force and now - last[0] < PROGRESS_INTERVAL_SECONDS:
            return
        last[0] = now
        print(f"[{now - start:6.1f}s] {msg}", file=sys.stderr, flush=True)

    return say


def main(argv=None) -> int:
    """Run the command line; returns the exit code (see the module docstring)."""
    try:
        args = _build_parser(lazy=True).parse_args(argv)
        if not hasattr(args, "quiet"):
            args.quiet = False
    except SystemExit as exc:  # argparse: --help (0) or a usage error (2, one line already printed)
        return exc.code if isinstance(exc.code, int) else 2
    try:
        return _dispatch(args)
    except (InputError, UnsupportedInput) as exc:  # bad input, or input lkverify does not handle: exit 2
        print(f"lkverify: error: {_one_line(exc)}{_flag_hint(exc)}", file=sys.stderr)
        return 2
    except BudgetExceeded as exc:  # a budget that no result could absorb
        print(f"lkverify: undecided: {_one_line(exc)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("lkverify: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `lkverify list | head -1`
        try:
            sys.stdout = open(os.devnull, "w")
        except OSError:  # pragma: no cover
            pass
        return 0
    except Exception as exc:  # noqa: BLE001 - the safety net: never a traceback
        if os.environ.get("LKVERIFY_TRACEBACK"):
            raise
        print(f"lkverify: internal error: {type(exc).__name__}: {_one_line(exc)[:300]} (a bug in lkverify, not "
              f"in your input as far as it knows; please report it with the command line; "
              f"LKVERIFY_TRACEBACK=1 shows the traceback)", file=sys.stderr)
        return EXIT_INTERNAL


#: the command-line option for each topic of an InputError (the library names no flag)
FLAGS = {"history": "--history", "parameters": "--set", "t_end": "--t-end", "budget": "--budget"}


def _flag_hint(exc) -> str:
    """``; on the command line: --history omega=[…]`` for an InputError that says what it is about."""
    flag = FLAGS.get(getattr(exc, "topic", None))
    if flag is None:
        return ""
    example = getattr(exc, "example", None)
    return f"; on the command line: {flag} {example}" if example else f"; on the command line: {flag}"


def _one_line(exc) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def _dispatch(args) -> int:
    if args.command == "list":  # from the index: no proof imported
        from .catalogue.index import read_index

        from .report.schema import SCHEMA_ID
        from .report.text import REPORT_WIDTH, wrap_lines

        rows = [(row.item, row.kind, row.title) for row in read_index()]
        if getattr(args, "json", False):
            print(json.dumps({"schema": SCHEMA_ID, "items": [{"item": q, "kind": k, "title": t} for q, k, t in rows]},
                             indent=2, ensure_ascii=False))
            return 0
        width = max((len(r[0]) for r in rows), default=0)
        for qualified, kind, title in rows:  # the title wraps under itself: every line fits 100 columns
            head = f"{qualified:<{width}} {kind:<8} "
            lines = wrap_lines(title, max(REPORT_WIDTH - len(head), 30), limit=None)
            print(head + lines[0])
            for line in lines[1:]:
                print(" " * len(head) + line)
        return 0
    if args.command in (None, "report"):
        return _report(json_out=getattr(args, "json", False), quiet=args.quiet, jobs=getattr(args, "jobs", None),
                       scheduler=getattr(args, "scheduler", None), verbose=args.verbose,
                       no_cache=getattr(args, "no_cache", False))
    if args.command == "cache":
        from .cache import cache_command

        return cache_command(args.action, json_out=args.json)
    if args.command == "check":
        return _check(args)
    if args.command == "simulate":
        return _simulate(args)
    if args.command == "constants":
        return _constants(args)
    if args.command == "linear":
        return _linear(args)
    if args.command == "sweep":
        from .sweep.cli import run as _sweep

        return _sweep(args, check_output_path=check_output_path, emit=_emit)
    return 0  # pragma: no cover


def _check(args) -> int:
    """``lkverify check``: each item's report at the values (or over the box), through the proof cache."""
    from .cache import cached_run, item_key, job_cache

    box = _box(args)
    values = _set_values(args.sets, box.names if box is not None else ())
    items = find_items(args.item, load_limit=args.load_limit)
    say = _progress(not args.quiet)
    path_part = args.item.partition("::")[0]
    from_file = path_part.endswith(".py") or "/" in path_part or Path(path_part).is_file()
    # a proof file is not keyed by the cache, nor is a run under a wall-clock cap (its verdict may depend on the load)
    cache = None if from_file or args.budget is not None else job_cache(getattr(args, "no_cache", False))
    if box is not None:
        from .catalogue.items import Theorem

        others = [item.qualified_name for item in items if not isinstance(item, Theorem)]
        if others:
            raise InputError(f"--box: expected theorems, got {', '.join(others[:3])} (a box is checked for "
                             f"theorems only; name one theorem, e.g. aleksandrov2023.theorem3)")
    elif args.max_boxes is not None:
        raise InputError("--max-boxes: only with --box NAME=LO:HI")
    extra = {"box": box, "max_boxes": args.max_boxes} if box is not None else {}
    reports = [cached_run(cache, item_key(cache, item.qualified_name, values, boxes=sorted(args.boxes),
                                          max_boxes=args.max_boxes),
                          lambda item=item: item.run(values, budget=args.budget, progress=say, **extra),
                          note=None if args.quiet else _note)
               for item in items]
    return _emit(reports, json_out=args.json, verbose=args.verbose)


def _linear(args) -> int:
    """``lkverify linear``: input checked first (values, orders, delays, --plot), then the job."""
    from .linear.run import linear_report

    values = _set_values(args.sets)
    try:
        orders = tuple(int(x) for x in args.orders.split(",") if x.strip())
    except ValueError:
        raise InputError(f"--orders: expected integers N ≥ 0 separated by commas, got {args.orders!r}; "
                         "e.g. --orders 0,1,2") from None
    if not orders or any(o < 0 or o > 12 for o in orders):
        raise InputError(f"--orders: expected integers 0 ≤ N ≤ 12, got {args.orders!r}; e.g. --orders 0,1,2")
    if not (math.isfinite(args.h_max) and args.h_max > 0):
        raise InputError(f"--h-max: expected a positive finite delay, got {args.h_max}")
    if args.plot:
        check_output_path(args.plot)
    report = linear_report(values, orders=orders, h_max=args.h_max, h=args.h, plot=args.plot,
                           say=_progress(not args.quiet))
    return _emit([report], json_out=args.json)


def _box(args):
    """The ``--box`` intervals as a ParameterBox (None without any); ``--max-boxes`` checked."""
    if args.max_boxes is not None and args.max_boxes < 1:
        raise InputError(f"--max-boxes: expected a positive number of pieces, got {args.max_boxes}")
    if not args.boxes:
        return None
    from .declare.boxes import parse_boxes

    return parse_boxes(args.boxes)


def _set_values(sets, box_names=()) -> dict:
    """``--set NAME=VALUE`` arguments parsed (the messages name ``--set``); admissibility is the item's.

    The names of ``--box`` intervals may appear in the values (``--set "F=diag(h,h,h)" --box h=1/2:1``)."""
    if not sets:
        return {}
    import sympy

    from .declare.parse import parse_assignment, parse_value
    from .declare.symbols import t as _t, zeta as _zeta

    variables = {"t": _t, "zeta": _zeta, **{n: sympy.Symbol(n) for n in box_names}}
    values = {}
    for text in sets:
        name, value = parse_assignment(text)
        values[name] = parse_value(value, name=name, option="--set", variables=variables)
    return values


#: the figure formats ``--plot`` writes (chosen by the file name's suffix)
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def check_output_path(path: str, *, option: str = "--plot") -> Path:
    """Refuse an output file that cannot be written, before any computing.

    Raises
    ------
    InputError
        The name does not end in ``.png``, ``.pdf`` or ``.svg``, names a directory, its folder does not
        exist or is not writable, or the file exists and is not writable.
    """
    from .report.files import check_writable_file

    return check_writable_file(path, option=option, suffixes=FIGURE_SUFFIXES, note=" (the format follows the suffix)")


def _emit(reports, *, json_out: bool, verbose: bool = False) -> int:
    """Print reports (one JSON object, a list of them, or text tables); the worst exit code."""
    if json_out:
        versions = _versions(PROOF_LIBRARIES)
        objs = [{**r.to_json(), "versions": versions} for r in reports]
        out = objs[0] if len(objs) == 1 else objs
        print(json.dumps(out, indent=2, ensure_ascii=False))
    else:
        print("\n\n".join(r.as_text(verbose=verbose) for r in reports))
    return max(_exit_code(r) for r in reports)


def _exit_code(report) -> int:
    """The report's exit code; 1 also for a theorem whose chain does not reach its conclusion (not established),
    even when every result it has holds (a missing link is not a result)."""
    return report.exit_code


def _bar(enabled: bool, label: str, say=None):
    """The fraction of a run done: a bar on a terminal (``enabled``), else a line every 10 % through ``say``."""
    from .report.progress import Progress

    return Progress(label, enabled=enabled or say is not None, say=say, tty=enabled).fraction


def _simulate(args) -> int:
    from .options import Deadline
    from .catalogue.examples import Example
    from .declare.parse import parse_assignment, parse_value
    from .declare.symbols import t as t_sym
    from .simulate.figures import convention_name

    if args.t_end is not None and not (args.t_end > 0 and args.t_end < float("inf")):
        raise InputError(f"--t-end: expected a positive finite time, got {args.t_end}")
    if args.plot is not None:
        check_output_path(args.plot)
    if args.convention is not None:
        convention_name(args.convention)  # an unknown name is bad input, before anything else
    values = _set_values(args.sets)
    histories = {}
    for h in args.histories:
        name, text = parse_assignment(h, option="--history")
        histories[name] = parse_value(text, name=f"--history {name}", option="--history", variables={"t": t_sym})
    items = [it for it in find_items(args.item, load_limit=args.load_limit)]
    examples = [it for it in items if isinstance(it, Example)]
    if not examples:
        raise InputError(f"{args.item}: not a numerical example; `lkverify list` marks examples "
                         f"(e.g. aleksandrov2023.fig6); use `lkverify check` for theorems")
    examples = [ex.with_options(values, histories=histories, convention=args.convention, distance=args.distance)
                for ex in examples]
    paths = {}
    if args.plot:
        for ex in examples:
            paths[ex.name] = args.plot if len(examples) == 1 else args.plot[:-4] + f"_{ex.name}.png"
            check_output_path(paths[ex.name])
    for ex in examples:  # refuse bad values, histories and step counts before integrating anything
        ex.prepare(values, t_end=args.t_end, histories=histories)
        if ex.envelope is not None:
            _constant_histories(ex, histories)
            ex.chi_used()  # ‖χ‖_τ of the history used: a history it cannot take is refused now
    tty = not args.json and not args.quiet and sys.stderr.isatty()
    say = _progress(not args.quiet)
    deadline = Deadline(args.budget)
    reports = []
    for ex in examples:
        trajectories = ex.simulate(values, t_end=args.t_end, histories=histories, progress=lambda m: say(m, True),
                                   fraction=lambda label: _bar(tty, label, None if tty else say), deadline=deadline)
        report = ex.run(values, trajectories=trajectories, envelope=args.envelope or ex.envelope is not None)
        written = []
        if args.plot:
            path = paths[ex.name]
            ex.plot(trajectories, path, envelope=args.envelope)
            written.append(str(path))
            say(f"figure written to {path}", True)
        reports.append((ex, report, written))
    if args.json:
        out = [_simulation_json(ex, report, written, args, histories) for ex, report, written in reports]
        print(json.dumps(out[0] if len(out) == 1 else out, indent=2, ensure_ascii=False))
    else:
        blocks = []
        for ex, report, written in reports:
            from .report.text import wrap_block

            setup = "\n".join(_setup_lines(ex, args, histories) + _integrator_lines(report))
            lines = [report.as_text(verbose=args.verbose)] + wrap_block(setup, indent="  ", limit=None)
            lines += [f"figure: {w}" for w in written]
            blocks.append("\n".join(lines))
        print("\n\n".join(blocks))
    return max(r.exit_code for _, r, _ in reports)


#: the libraries a check or a certificate rests on (their versions go into --json)
PROOF_LIBRARIES = ("lkverify", "sympy", "python-flint", "numpy", "scipy", "cvxpy", "clarabel")


def _versions(names=("lkverify", "numpy", "scipy", "sympy")) -> dict:
    """The versions of lkverify and of the libraries a job ran on (a simulation: numpy, scipy, sympy)."""
    from importlib import metadata

    out = {}
    for name in names:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:  # pragma: no cover - a source checkout without metadata
            out[name] = None
    return out


def _constant_histories(ex, histories) -> None:
    """Refuse a time-varying ``--history`` for an example whose envelope needs ‖χ‖_τ of a constant history."""
    for name, value in histories.items():
        if getattr(value, "free_symbols", None):
            raise InputError(f"--history {name}: the envelope of {ex.qualified_name} is computed from ‖χ‖_τ of a "
                             f"constant initial history; got the time-varying {_history_json({name: value})[name]}; "
                             f"pass a constant vector, e.g. --history {name}=[0.1,0.1,0.1], or simulate an "
                             f"example without an envelope (aleksandrov2023.fig6)")


def _history_json(history) -> dict:
    """State name → the history as JSON: a flat list of numbers, or of strings for entries in t."""
    import numpy as np
    import sympy

    out = {}
    for k, v in dict(history).items():
        try:
            a = np.asarray(v, dtype=float)
            out[k] = (a.ravel() if a.ndim == 2 and a.shape[1] == 1 else a).tolist()  # a column vector: flat
        except (TypeError, ValueError):
            out[k] = [str(x) for x in v] if isinstance(v, sympy.MatrixBase) else str(v)
    return out


def _run_setup(ex, values, histories) -> list:
    from .simulate.figures import plain, resolved_values, show_value

    runs = []
    for run in ex.runs:
        history = dict(run.history)  # with_options put the --history values there
        entry = {"label": run.label,
                 "parameters": {k: show_value(v) for k, v in resolved_values(run, values).items()},
                 "history": _history_json(history),
                 "history_overridden": sorted(histories),
                 "history_override": {k: _history_json({k: v})[k] for k, v in histories.items()}}
        if ex.caption is not None:
            entry["title"] = plain(ex.label_for(run.label) if len(ex.runs) > 1 else ex.title_for())
        runs.append(entry)
    return runs


def _simulation_json(ex, report, written, args, histories) -> dict:
    from .simulate.figures import DISTANCES, plain

    out = report.to_json()
    out["runs"] = _run_setup(ex, _set_values(args.sets), histories)
    out["history_overridden"] = bool(histories)
    if ex.caption is not None:
        out["title"] = plain(ex.title_for())
    if ex.convention is not None or ex.caption is not None:
        out["convention"] = ex.convention
    if ex.distance_name is not None:
        out["distance"] = {"name": ex.distance_name, "definition": DISTANCES.get(ex.distance_name)}
    if ex.envelope is not None:
        out["chi_tau"] = ex.chi_used()
    out["t_end"] = args.t_end if args.t_end is not None else ex.t_end
    out["figures"] = list(written)
    out["versions"] = _versions()
    return out


def _setup_lines(ex, args, histories) -> list:
    """The text report's lines about the run setup: history (and its override), convention, distance."""
    from .simulate.figures import DISTANCES, show_vector

    lines = []
    if histories:
        lines.append("history: overridden by --history: " + ", ".join(f"{k} = {show_vector(v)}" if _is_vector(v)
                                                                      else f"{k} = {v}" for k, v in histories.items())
                     + "; the other states from the catalogue")
    else:
        lines.append("history: the catalogue's (no --history)")
    if ex.convention is not None:
        lines.append(f"angle convention of the initial data: {ex.convention}"
                     + (" (default)" if args.convention is None else ""))
    if ex.distance_name is not None:
        lines.append(f"distance: {ex.distance_name} = {DISTANCES.get(ex.distance_name, '')}")
    if ex.envelope is not None:
        lines.append(f"‖χ‖_τ of the history used: {ex.chi_used():.4g}")
    return lines


def _integrator_lines(report) -> list:
    """Which integrator ran the runs (from the runs' results): one line."""
    used = {}
    for r in report.results:
        if str(r.kind) == "simulation" and isinstance(r.value, dict) and r.value.get("integrator"):
            used.setdefault(r.value["integrator"], []).append(r.name.removeprefix("run "))
    if not used:
        return []
    if len(used) == 1:
        return [f"integrator: {next(iter(used))}"]
    return ["integrator: " + "; ".join(f"{k} ({', '.join(v)})" for k, v in used.items())]


def _is_vector(v) -> bool:
    import numpy as np
    import sympy

    if isinstance(v, sympy.MatrixBase):  # also one with entries in t (a time-varying history)
        return True
    try:
        np.asarray(v, dtype=float)
        return True
    except (TypeError, ValueError):
        return False


def _constants(args) -> int:
    if args.plot is not None:
        check_output_path(args.plot)
    values = _set_values(args.sets)
    items = [it for it in find_items(args.item, load_limit=args.load_limit) if it.constants is not None]
    if not items:
        raise InputError(f"{args.item}: no constants job is declared for it; items with one: "
                         + ", ".join(f"{pf.paper}.{n}" for pf in catalogue() for n, it in pf.items.items()
                                     if it.constants is not None))
    if args.goal is not None:
        for item in items:
            goals = list(getattr(item.constants, "goals", None) or ["default"])
            if args.goal not in goals:
                several = len(goals) > 1
                raise InputError(f"--goal: {item.qualified_name} has {'the goals' if several else 'a single goal'} "
                                 f"{', '.join(goals)}; got {args.goal!r}; "
                                 + (f"pass one of them" if several else "drop --goal"))
    say = _progress(not args.quiet)
    reports = []
    for item in items:
        report, extra = _constants_within_budget(item, values, args, say)
        reports.append(report)
        if args.plot and extra:
            item.constants.plot(extra, args.plot, values=item.parameters.resolve(values, use_defaults=True))
            if not args.json:
                print(f"figure: {args.plot}")
        elif args.plot and not args.json:
            print(f"figure: not written ({report.verdict})")
    return _emit(reports, json_out=args.json, verbose=args.verbose)


#: a constants job that does not stop by itself at its budget is interrupted this much later
BACKSTOP_GRACE_SECONDS = 0.5


def _constants_within_budget(item, values, args, say):
    """Run the item's constants job; a job that overruns its budget is interrupted (undecided)."""
    from .options import Deadline
    from .report.results import Report, Result
    from .status import Status

    backstop = Deadline(args.budget + BACKSTOP_GRACE_SECONDS)
    try:
        with backstop.enforced():
            return item.run_constants(values, budget=args.budget, progress=say, goal=args.goal)
    except BudgetExceeded:
        pass
    detail = (f"time budget of {args.budget:g} s ran out (interrupted after {backstop.elapsed:.1f} s) before any "
              f"result was complete; raise --budget to finish")
    shown = {}
    result = Result("constant", "budget", Status.UNDECIDED, {"budget": args.budget}, detail)
    return Report(item.qualified_name, shown, (result,), f"undecided: the time budget of {args.budget:g} s ran out"), {}


def _report(*, json_out: bool, quiet: bool = False, jobs: int | None = None, scheduler: str | None = None,
            verbose: bool = False, no_cache: bool = False) -> int:
    """The bare report (:func:`lkverify.catalogue.report_job.catalogue_report`), printed."""
    from .cache import job_cache
    from .catalogue.report_job import catalogue_report

    outputs = catalogue_report(jobs=jobs, scheduler=scheduler, say=_progress(not quiet), cache=job_cache(no_cache),
                               note=None if quiet else _note)
    if json_out:
        versions = _versions(PROOF_LIBRARIES)
        print(json.dumps([{**p["json"], "versions": versions} for p in outputs], indent=2, ensure_ascii=False))
    else:
        print("lkverify: the catalogue at the papers' defaults\n")
        print("\n\n".join(p["text_verbose" if verbose else "text"] for p in outputs))
        held = sum(p["holds"] for p in outputs)
        print(f"\n{len(outputs)} items: {held} with every result holding, {len(outputs) - held} with a failed "
              f"or undecided result\n(a failed identity against a printed formula is a finding about the paper)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
