"""The ``lkverify`` command line.

``lkverify``                       report of every catalogued item at the papers' defaults
``lkverify list``                  the catalogue
``lkverify check ITEM [--set NAME=VALUE]... [--json] [--budget S]``
``lkverify simulate ITEM [--set NAME=VALUE]... [--history STATE=VALUE]... [--t-end T] [--plot FILE.png] [--envelope] [--json]``

Exit codes: 0 every result holds (for the bare report: the report was produced),
1 something failed or is undecided, 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from .catalogue import catalogue, find_items
from .errors import InputError
from .parse import parse_assignment

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit code 2, no traceback
        self.exit(2, f"lkverify: error: {message} (see `lkverify --help`)\n")


def _build_parser() -> argparse.ArgumentParser:
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
    c.add_argument("--budget", type=float, default=60.0, metavar="SECONDS",
                   help="time budget per identity; when spent the identity is undecided (default 60)")
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
    k = sub.add_parser("constants", help="compute and certify the constants, region and envelope of a proof")
    k.add_argument("item", help="e.g. aleksandrov2023.theorem3, aleksandrov2017.lemma1")
    k.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE")
    k.add_argument("--json", action="store_true", help="print the JSON object of the design card")
    k.add_argument("--plot", metavar="FILE.png", help="write the figure (envelope, or δ(ε) for a lemma)")
    k.add_argument("--budget", type=float, default=150.0, metavar="SECONDS",
                   help="time budget; when spent the unfinished results are undecided (default 150)")
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
    args = _build_parser().parse_args(argv)
    try:
        if args.command == "list":
            for pf in catalogue():
                for name, item in pf.items.items():
                    kind = {"Example": "example", "Check": "check"}.get(type(item).__name__, "theorem")
                    print(f"{pf.paper + '.' + name:<28} {kind:<8} {item.title}")
            return 0
        if args.command in (None, "report"):
            return _report(json_out=getattr(args, "json", False))
        if args.command == "check":
            if args.budget <= 0 or args.budget != args.budget:
                raise InputError(f"--budget: expected a positive number of seconds, got {args.budget}")
            values = dict(parse_assignment(s) for s in args.sets)
            items = find_items(args.item)
            say = _progress(not args.json and sys.stderr.isatty())
            reports = [item.run(values, budget=args.budget, progress=say) for item in items]
            return _emit(reports, json_out=args.json)
        if args.command == "simulate":
            return _simulate(args)
        if args.command == "constants":
            return _constants(args)
    except InputError as exc:
        print(f"lkverify: error: {exc}", file=sys.stderr)
        return 2
    return 0  # pragma: no cover


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
    from .example import Example
    from .parse import parse_value

    if args.t_end is not None and not (args.t_end > 0 and args.t_end < float("inf")):
        raise InputError(f"--t-end: expected a positive finite time, got {args.t_end}")
    if args.plot is not None and not args.plot.lower().endswith(".png"):
        raise InputError(f"--plot: expected a file name ending in .png, got {args.plot}")
    values = dict(parse_assignment(s) for s in args.sets)
    histories = {}
    for h in args.histories:
        name, text = parse_assignment(h)
        histories[name] = parse_value(text, name=name)
    items = [it for it in find_items(args.item)]
    examples = [it for it in items if isinstance(it, Example)]
    if not examples:
        raise InputError(f"{args.item}: not a numerical example; `lkverify list` marks examples "
                         f"(e.g. aleksandrov2023.fig6); use `lkverify check` for theorems")
    tty = not args.json and sys.stderr.isatty()
    say = _progress(tty)
    reports = []
    for ex in examples:
        trajectories = ex.simulate(values, t_end=args.t_end, histories=histories, progress=say,
                                   fraction=lambda label: _bar(tty, label))
        reports.append(ex.run(values, trajectories=trajectories, envelope=args.envelope or ex.envelope is not None))
        if args.plot:
            path = args.plot if len(examples) == 1 else args.plot.replace(".png", f"_{ex.name}.png")
            ex.plot(trajectories, path, envelope=args.envelope)
            say(f"figure written to {path}")
            if not args.json:
                print(f"figure: {path}")
    return _emit(reports, json_out=args.json)


def _constants(args) -> int:
    if not (args.budget > 0 and args.budget < float("inf")):
        raise InputError(f"--budget: expected a positive number of seconds, got {args.budget}")
    if args.plot is not None and not args.plot.lower().endswith(".png"):
        raise InputError(f"--plot: expected a file name ending in .png, got {args.plot}")
    values = dict(parse_assignment(s) for s in args.sets)
    items = [it for it in find_items(args.item) if it.constants is not None]
    if not items:
        raise InputError(f"{args.item}: no constants job is declared for it; items with one: "
                         + ", ".join(f"{pf.paper}.{n}" for pf in catalogue() for n, it in pf.items.items()
                                     if it.constants is not None))
    say = _progress(not args.json and sys.stderr.isatty())
    reports = []
    for item in items:
        report, extra = item.run_constants(values, budget=args.budget, progress=say, goal=args.goal)
        reports.append(report)
        if args.plot and extra:
            item.constants.plot(extra, args.plot, values=item.parameters.resolve(values, use_defaults=True))
            if not args.json:
                print(f"figure: {args.plot}")
    return _emit(reports, json_out=args.json)


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
