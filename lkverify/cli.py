"""The ``lkverify`` command line.

``lkverify``                       report of every catalogued item at the papers' defaults
``lkverify list``                  the catalogue
``lkverify check ITEM [--set NAME=VALUE]... [--json] [--budget S]``

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
                    print(f"{pf.paper}.{name:<12} {item.title}")
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
            if args.json:
                out = reports[0].to_json() if len(reports) == 1 else [r.to_json() for r in reports]
                print(json.dumps(out, indent=2, ensure_ascii=False))
            else:
                print("\n\n".join(r.as_text() for r in reports))
            return max(r.exit_code for r in reports)
    except InputError as exc:
        print(f"lkverify: error: {exc}", file=sys.stderr)
        return 2
    return 0  # pragma: no cover


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
