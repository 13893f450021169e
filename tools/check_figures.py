#!/usr/bin/env python3
"""Check the layout of every report figure: no text past an edge, no wide empty margin.

The report draws each figure once, with margins fixed when the figure is built
(``strapdown.analysis.report.rendering.fixed_layout``) instead of a layout
engine or ``bbox_inches="tight"``, which would measure every text in extra
passes.  Fixed margins must still fit the labels the data produce, so this
script regenerates the report and, for every figure, measures how far its drawn
content reaches past each edge of the canvas
(:func:`strapdown.analysis.report.rendering.layout_overflow`):

* a side whose content reaches more than ``--clip`` inches past the edge is
  clipped: the check fails;
* the labels or ticks of one axes that reach more than ``--clip`` inches into
  the frame of another overlap it: the check fails too
  (:func:`strapdown.analysis.report.rendering.layout_overlaps`);
* a side with more than ``--spare`` inches of empty margin is listed as a
  warning (space the figure could give to its axes).

Exit status: 0 when no figure is clipped or overlapping, 1 otherwise, 2 for bad arguments.

Usage::

    python tools/check_figures.py [--quick] [--only SECTION ...] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="reduced Monte Carlo sizes (the figures' layout is the same)")
    parser.add_argument("--only", nargs="+", metavar="SECTION", help="sections to build (default all)")
    parser.add_argument("--out", type=Path, help="where to write the report [path] (default a temporary directory)")
    parser.add_argument("--clip", type=float, default=0.02, help="content past an edge that fails the check [in] (default 0.02)")
    parser.add_argument("--spare", type=float, default=0.4, help="empty margin listed as a warning [in] (default 0.4)")
    args = parser.parse_args(argv)

    from strapdown.analysis import report
    from strapdown.analysis.report.rendering import layout_overflow, layout_overlaps

    rows = []

    def measure(relpath, fig):
        rows.append((relpath, layout_overflow(fig), layout_overlaps(fig, args.clip)))

    with tempfile.TemporaryDirectory() as tmp:
        out = args.out if args.out is not None else Path(tmp) / "report"
        sections = None
        if args.only:
            sections = [m for m in report.discover() if m.SECTION.name in set(args.only) or m.SECTION.gathers]
        command = "strapdown report" + (" --quick" if args.quick else "")  # the stamp of the same CLI run, so that the two compare equal
        report.generate(out, quick=args.quick, show_progress=False, sections=sections, command=command, figure_check=measure)

    sides = ("left", "bottom", "right", "top")
    clipped = 0
    print(f"{'figure':48s} " + " ".join(f"{s:>7s}" for s in sides) + "   [in past the edge; negative: empty margin]")
    for relpath, over, overlaps in rows:
        flags = []
        if any(v > args.clip for v in over):
            flags.append("CLIPPED " + ", ".join(s for s, v in zip(sides, over) if v > args.clip))
        if overlaps:
            flags.append("OVERLAP " + ", ".join(f"axes {i} into axes {j} by {w:.2f} x {h:.2f} in" for i, j, w, h in overlaps))
        clipped += bool(flags)
        wide = [s for s, v in zip(sides, over) if -v > args.spare]
        if wide:
            flags.append("wide margin " + ", ".join(wide))
        print(f"{relpath:48s} " + " ".join(f"{v:7.2f}" for v in over) + ("   " + "; ".join(flags) if flags else ""))
    print(f"{len(rows)} figures, {clipped} clipped or overlapping")
    return 1 if clipped else 0


if __name__ == "__main__":
    sys.exit(main())
