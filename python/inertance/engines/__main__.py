"""``python -m inertance.engines``: grade engines on the catalogue, the random family and the
convergence sweeps (Markdown, JSON, SVG plots and an HTML page with --out).

Exit status: 0 every adapter ran on every scene; 1 an adapter failed on some scene (listed in
the report); 2 bad input (an unknown engine or scene, a missing catalogue, an engine not
installed, a negative count)."""

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
    p.add_argument("--out", default=None, help="write report.md, report.json, the SVG plots and report.html here "
                                               "(default: Markdown to stdout)")
    p.add_argument("--random", type=int, default=None, metavar="SEED",
                   help="also grade the seeded random family (inertance.engines.random_family) drawn from SEED")
    p.add_argument("--random-count", type=int, default=36, metavar="N", help="scenes in the random family (default 36)")
    p.add_argument("--convergence", action="store_true",
                   help="also refine each engine's time step and solver iterations (inertance.engines.convergence)")
    p.add_argument("--convergence-scenes", default=None,
                   help="comma-separated scenes for --convergence (default: ball-floor-e05,box-edge-30,box-flat-e05,cradle-3)")
    args = p.parse_args(argv)
    if args.random_count < 0:
        print(f"error: --random-count is a number of scenes ≥ 0, not {args.random_count}", file=sys.stderr)
        return 2
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
        sweep_scenes = []
        if args.convergence:
            from .convergence import SCENES

            chosen = [n.strip() for n in args.convergence_scenes.split(",")] if args.convergence_scenes else list(SCENES)
            sweep_scenes = scenes(args.catalogue, chosen)
    except (KeyError, ImportError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    family = []
    if args.random is not None:
        from pathlib import Path

        from .random_family import scenes as random_scenes

        family = random_scenes(args.random, args.random_count,
                               Path(args.out) / "random-scenes" if args.out else None)
    report = run(adapters, cat, family, seed=args.random)
    if args.convergence:
        from . import convergence

        report["convergence"] = convergence.run(names, sweep_scenes)
    if args.out:
        md, js = write(report, args.out)
        print(f"wrote {md}, {js}, the plots and report.html in {args.out}")
    else:
        sys.stdout.write(markdown(report))
    return 1 if report["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
