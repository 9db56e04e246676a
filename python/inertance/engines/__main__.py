"""``python -m inertance.engines``: grade engines on the catalogue (Markdown and JSON)."""

from __future__ import annotations

import argparse
import sys

from . import ADAPTERS, ENGINE_MODULES, adapter, installed
from .catalogue import scenes
from .runner import markdown, run, write


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m inertance.engines", description=__doc__)
    p.add_argument("--engines", default=None,
                   help=f"comma-separated adapters among {', '.join(ADAPTERS)} (default: every engine adapter "
                        "whose engine is installed)")
    p.add_argument("--scenes", default=None, help="comma-separated scene names (file stems); default: all")
    p.add_argument("--catalogue", default=None, help="the scenes' directory (default: $INERTANCE_CATALOGUE, the source checkout's, or ./benches/engines/scenes)")
    p.add_argument("--out", default=None, help="write report.md and report.json here (default: Markdown to stdout)")
    args = p.parse_args(argv)
    if args.engines is None:
        names = installed()
        missing = [n for n in ENGINE_MODULES if n not in names]
        if missing:
            print(f"not installed, skipped: {', '.join(missing)}", file=sys.stderr)
        if not names:
            print("error: no engine is installed (pip install ./python[engines]); --engines exact,no-impact "
                  "runs the reference adapters", file=sys.stderr)
            return 2
    else:
        names = [n.strip() for n in args.engines.split(",") if n.strip()]
    try:
        adapters = [adapter(n) for n in names]
        cat = scenes(args.catalogue, [n.strip() for n in args.scenes.split(",")] if args.scenes else None)
    except (KeyError, ImportError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    report = run(adapters, cat)
    if args.out:
        md, js = write(report, args.out)
        print(f"wrote {md} and {js}")
    else:
        sys.stdout.write(markdown(report))
    return 1 if report["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
