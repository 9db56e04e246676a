"""``python -m inertance.engines``: grade engines on the catalogue (Markdown and JSON)."""

from __future__ import annotations

import argparse
import sys

from . import ADAPTERS, adapter
from .catalogue import scenes
from .runner import markdown, run, write


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m inertance.engines", description=__doc__)
    p.add_argument("--engines", default="mujoco,mujoco-tuned,mujoco-calibrated,pybullet,pinocchio,rapier,drake",
                   help=f"comma-separated adapters among {', '.join(ADAPTERS)} (default: %(default)s)")
    p.add_argument("--scenes", default=None, help="comma-separated scene names (file stems); default: all")
    p.add_argument("--catalogue", default=None, help="the scenes' directory (default: $INERTANCE_CATALOGUE, the source checkout's, or ./benches/engines/scenes)")
    p.add_argument("--out", default=None, help="write report.md and report.json here (default: Markdown to stdout)")
    args = p.parse_args(argv)
    try:
        adapters = [adapter(n.strip()) for n in args.engines.split(",") if n.strip()]
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
