"""The ``lkverify`` command line.

``lkverify``                       report of every catalogued item at the papers' defaults
``lkverify list``                  the catalogue
``lkverify check ITEM [--set NAME=VALUE]... [--json] [--budget S] [--load-limit S]``
``lkverify simulate ITEM [--set NAME=VALUE]... [--history STATE=VALUE]... [--t-end T] [--plot FILE.png] [--envelope] [--json] [--budget S]``
``lkverify constants ITEM [--set NAME=VALUE]... [--goal GOAL] [--plot FILE.png] [--json] [--budget S]``

Exit codes: 0 every result holds (for the bare report: the report was produced),
1 something failed or is undecided (a budget ran out), 2 bad input (one line on
stderr), 3 an internal error of lkverify (one line on stderr; set the environment
variable ``LKVERIFY_TRACEBACK=1`` to see the traceback), 130 interrupted (Ctrl-C).
Bad input is refused before any computing: values, output paths (``--plot``),
goals and budgets are checked first.

Budgets (``--budget SECONDS``) are positive finite numbers up to
:data:`lkverify.options.MAX_BUDGET_SECONDS` (1e6 s); ``inf`` and larger values are
refused.  ``check``: per identity (default 60 s).  ``constants``: the whole job
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

from .options import MAX_BUDGET_SECONDS, BudgetExceeded
from .catalogue.loader import LOAD_LIMIT_SECONDS, catalogue, find_items
from .errors import InputError, UnsupportedInput
from .declare.parse import parse_assignment, parse_value
from .declare.symbols import t as _t, zeta as _zeta

#: exit code of an unexpected exception (a bug in lkverify); see the module docstring
EXIT_INTERNAL = 3

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit code 2, no traceback
        self.exit(2, f"lkverify: error: {message} (see `lkverify --help`)\n")


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


def _build_parser() -> argparse.ArgumentParser:
    from .simulate.solver import FLOOR_WINDOW
    from .catalogue.examples import DEFAULT_SIMULATE_BUDGET, MAX_STEPS

    p = _Parser(prog="lkverify", description="Check Lyapunov–Krasovskii stability proofs. "
                "With no command: the report of every catalogued item at the papers' defaults.")
    sub = p.add_subparsers(dest="command", parser_class=_Parser)
    sub.add_parser("list", help="list the catalogue")
    rp = sub.add_parser("report", help="report every catalogued item at the papers' defaults (the default job)")
    rp.add_argument("--json", action="store_true", help="one JSON object per item, in a list")
    c = sub.add_parser("check", help="check an item's hypotheses and identities")
    c.add_argument("item", help="catalogue name (aleksandrov2023.theorem3), a paper, or path/to/proof.py[::item]")
    c.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value: a number, diag(2,2,2), [[2,0],[0,2]], or an expression in t")
    c.add_argument("--json", action="store_true", help="print the JSON object of the design card")
    c.add_argument("--budget", type=_seconds, default=60.0, metavar="SECONDS",
                   help="time budget of the whole check (hypotheses and identities); what is unfinished when it is "
                        "spent is undecided (default 60, at most 1e6)")
    _add_load_limit(c)
    s = sub.add_parser("simulate", help="integrate a numerical example and check the paper's claims about it")
    s.add_argument("item", help="an example (aleksandrov2023.fig6), or path/to/file.py[::item]")
    s.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value for every run of the example")
    s.add_argument("--history", dest="histories", action="append", default=[], metavar="STATE=VALUE",
                   help="a constant initial history for a state, e.g. omega=[0.1,0.1,0.1]")
    s.add_argument("--t-end", type=float, default=None, metavar="T", help="final time (default: the example's)")
    s.add_argument("--plot", metavar="FILE.png", help="write the figure (paper style) to this PNG file")
    s.add_argument("--envelope", action="store_true", help="cross-check the example's decay envelope and plot it")
    s.add_argument("--json", action="store_true", help="print the JSON object of the design card")
    s.add_argument("--budget", type=_seconds, default=DEFAULT_SIMULATE_BUDGET, metavar="SECONDS",
                   help=f"time budget for all runs together; a run cut short is undecided (default "
                        f"{DEFAULT_SIMULATE_BUDGET:g}). Steps are at most min(delays) long, so a run needs at least "
                        f"(t_end - t0)/min(delays) steps: more than {MAX_STEPS:.0e} is refused up front (tiny delay, "
                        f"huge --t-end), and a run whose last {FLOOR_WINDOW} steps average less than the step floor "
                        f"(t_end - t0)/{MAX_STEPS:.0e} is stopped: diverged (a blow-up) or step_collapse (stiff)")
    _add_load_limit(s)
    k = sub.add_parser("constants", help="compute and certify the constants, region and envelope of a proof")
    k.add_argument("item", help="e.g. aleksandrov2023.theorem3, aleksandrov2017.lemma1")
    k.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE")
    k.add_argument("--json", action="store_true", help="print the JSON object of the design card")
    k.add_argument("--plot", metavar="FILE.png", help="write the figure (envelope, or δ(ε) for a lemma)")
    k.add_argument("--budget", type=_seconds, default=150.0, metavar="SECONDS",
                   help="time budget of the whole job; when spent the unfinished results are undecided "
                        "(default 150, at most 1e6)")
    _add_load_limit(k)
    k.add_argument("--goal", default=None, help="which trade-off to optimise, for items that offer several "
                   "(aleksandrov2023.theorem3: paper = match d1, d2, d3 and maximise δ̃; region = maximise δ̃)")
    return p


def _progress(enabled: bool):
    start = time.monotonic()

    def say(msg: str):
        if enabled:
            print(f"[{time.monotonic() - start:6.1f}s] {msg}", file=sys.stderr, flush=True)

    return say


def main(argv=None) -> int:
    """Run the command line; returns the exit code (see the module docstring)."""
    try:
        args = _build_parser().parse_args(argv)
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
    if args.command == "list":
        rows = [(f"{pf.paper}.{name}", {"Example": "example", "Check": "check"}.get(type(item).__name__, "theorem"),
                 item.title) for pf in catalogue() for name, item in pf.items.items()]
        width = max((len(r[0]) for r in rows), default=0)
        for qualified, kind, title in rows:
            print(f"{qualified:<{width}} {kind:<8} {title}")
        return 0
    if args.command in (None, "report"):
        return _report(json_out=getattr(args, "json", False))
    if args.command == "check":
        values = _set_values(args.sets)
        items = find_items(args.item, load_limit=args.load_limit)
        say = _progress(not args.json and sys.stderr.isatty())
        reports = [item.run(values, budget=args.budget, progress=say) for item in items]
        return _emit(reports, json_out=args.json)
    if args.command == "simulate":
        return _simulate(args)
    if args.command == "constants":
        return _constants(args)
    return 0  # pragma: no cover


def _set_values(sets) -> dict:
    """``--set NAME=VALUE`` arguments parsed (the messages name ``--set``); admissibility is the item's."""
    values = {}
    for text in sets:
        name, value = parse_assignment(text)
        values[name] = parse_value(value, name=name, option="--set", variables={"t": _t, "zeta": _zeta})
    return values


def check_output_path(path: str, *, option: str = "--plot") -> Path:
    """Refuse an output file that cannot be written, before any computing.

    Raises
    ------
    InputError
        The name does not end in ``.png``, names a directory, its folder does not
        exist or is not writable, or the file exists and is not writable.
    """
    if not path.lower().endswith(".png"):
        raise InputError(f"{option}: expected a file name ending in .png, got {path}")
    p = Path(path)
    if p.is_dir():
        raise InputError(f"{option}: expected a file name, got the directory {path}; pass e.g. {p / 'figure.png'}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        what = "is not a directory" if parent.exists() else "does not exist"
        raise InputError(f"{option}: the folder {parent} of {path} {what}; expected an existing folder; "
                         f"create it first (mkdir -p {parent}) or write elsewhere")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option}: the folder {parent} is not writable; expected a folder you can write to")
    if p.exists() and not os.access(p, os.W_OK):
        raise InputError(f"{option}: {path} exists and is not writable; expected a writable file")
    return p


def _emit(reports, *, json_out: bool) -> int:
    """Print reports (one JSON object, a list of them, or text tables); the worst exit code."""
    if json_out:
        out = reports[0].to_json() if len(reports) == 1 else [r.to_json() for r in reports]
        print(json.dumps(out, indent=2, ensure_ascii=False))
    else:
        print("\n\n".join(r.as_text() for r in reports))
    return max(r.exit_code for r in reports)


def _bar(enabled: bool, label: str):
    last = [-1]

    def update(fraction: float):
        if not enabled:
            return
        k = int(40 * min(max(fraction, 0.0), 1.0))
        if k != last[0]:
            last[0] = k
            end = "\n" if k == 40 else ""
            print(f"\r  {label[:40]:40s} [{'#' * k}{'.' * (40 - k)}] {100 * fraction:5.1f}%", end=end,
                  file=sys.stderr, flush=True)

    return update


def _simulate(args) -> int:
    from .options import Deadline
    from .catalogue.examples import Example
    from .declare.parse import parse_value
    from .declare.symbols import t as t_sym

    if args.t_end is not None and not (args.t_end > 0 and args.t_end < float("inf")):
        raise InputError(f"--t-end: expected a positive finite time, got {args.t_end}")
    if args.plot is not None:
        check_output_path(args.plot)
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
    paths = {}
    if args.plot:
        for ex in examples:
            paths[ex.name] = args.plot if len(examples) == 1 else args.plot[:-4] + f"_{ex.name}.png"
            check_output_path(paths[ex.name])
    for ex in examples:  # refuse bad values, histories and step counts before integrating anything
        ex.prepare(values, t_end=args.t_end, histories=histories)
    tty = not args.json and sys.stderr.isatty()
    say = _progress(tty)
    deadline = Deadline(args.budget)
    reports = []
    for ex in examples:
        trajectories = ex.simulate(values, t_end=args.t_end, histories=histories, progress=say,
                                   fraction=lambda label: _bar(tty, label), deadline=deadline)
        reports.append(ex.run(values, trajectories=trajectories, envelope=args.envelope or ex.envelope is not None))
        if args.plot:
            path = paths[ex.name]
            ex.plot(trajectories, path, envelope=args.envelope)
            say(f"figure written to {path}")
            if not args.json:
                print(f"figure: {path}")
    return _emit(reports, json_out=args.json)


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
    say = _progress(not args.json and sys.stderr.isatty())
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
    return _emit(reports, json_out=args.json)


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


def _report(*, json_out: bool) -> int:
    say = _progress(not json_out and sys.stderr.isatty())
    reports = []
    for pf in catalogue():
        for item in pf.items.values():
            reports.append(item.run({}, progress=say))
    if json_out:
        print(json.dumps([r.to_json() for r in reports], indent=2, ensure_ascii=False))
    else:
        print("lkverify: the catalogue at the papers' defaults\n")
        print("\n\n".join(r.as_text() for r in reports))
        held = sum(r.holds for r in reports)
        print(f"\n{len(reports)} items: {held} with every result holding, {len(reports) - held} with a failed "
              f"or undecided result (a failed identity against a printed formula is a finding about the paper)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
