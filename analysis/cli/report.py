"""``strapdown report``: regenerate every report into ``reports/``."""

from __future__ import annotations

import time
from pathlib import Path

from . import Result


def _run(args) -> Result:
    from ..report import generate

    # The stamp names what determines the content (mode and sections), not where it was
    # written, so that regenerations into different directories stay byte-identical.
    command = "strapdown report" + (" --quick" if args.quick else "") + (" --only " + " ".join(args.only) if args.only else "")
    start = time.perf_counter()
    names = generate(Path(args.out), only=args.only, quick=args.quick, show_progress=not args.no_progress, command=command)
    elapsed = time.perf_counter() - start
    data = {"out": str(args.out), "sections": names, "quick": bool(args.quick), "seconds": round(elapsed, 3)}
    return Result(data, f"regenerated {', '.join(names)} in {args.out}/ ({elapsed:.1f} s)")


def register(commands) -> None:
    p = commands.add("report", _run, "regenerate every report (errata, algorithms, derivations, stability, azimuth)")
    p.add_argument("--out", default="reports", help="output directory (default: reports)")
    p.add_argument("--only", nargs="+", metavar="SECTION", help="rebuild only these sections (others are kept)")
    p.add_argument("--quick", action="store_true", help="reduced Monte Carlo sizes and grids (for CI)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars on stderr")
