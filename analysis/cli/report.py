"""``strapdown report``: regenerate the reports into a directory (``reports/`` by default).

The directory is replaced as a whole and atomically, and only if every file in
it was written by an earlier ``strapdown report`` (its manifest lists them), and none of
those was edited since (``--overwrite-modified`` replaces edited ones):
see :func:`strapdown.analysis.report.generate`.
"""

from __future__ import annotations

import time
from pathlib import Path

from . import Result

__all__ = ["report_command", "register"]


def report_command(args) -> Result:
    """Run ``strapdown report`` for the parsed arguments ``args``.

    Parameters
    ----------
    args : argparse.Namespace
        ``out``, ``only``, ``quick``, ``overwrite_modified`` and ``progress`` (set by the command-line edge).

    Returns
    -------
    Result
        The output directory, the sections rebuilt, the mode and the run time [s].

    Raises
    ------
    ValueError
        An unknown section, an empty ``--out``, an output directory that must
        not be replaced (:class:`strapdown.analysis.report.output.OutputError`),
        or generated files edited since they were written (named; kept unless
        ``--overwrite-modified``).
    """
    from ..report import generate

    # The stamp names what determines the content (mode and sections), not where it was
    # written, so that regenerations into different directories stay byte-identical.
    command = "strapdown report" + (" --quick" if args.quick else "") + (" --only " + " ".join(args.only) if args.only else "")
    if not str(args.out).strip():
        raise ValueError(f"Expected `out` to name a directory, got an empty name {args.out!r}")
    start = time.perf_counter()
    from ..report.output import ModifiedFilesError

    try:
        names = generate(Path(args.out), only=args.only, quick=args.quick, show_progress=bool(args.progress), command=command, overwrite_modified=args.overwrite_modified)
    except ModifiedFilesError as exc:
        shown = ", ".join(exc.files[:5]) + (f" and {len(exc.files) - 5} more" if len(exc.files) > 5 else "")
        raise ValueError(
            f"argument --out: {len(exc.files)} generated file(s) in {str(exc.directory)!r} changed since `strapdown report` wrote them: {shown}; "
            "they are left untouched: move them away, or pass --overwrite-modified to replace them"
        ) from None
    elapsed = time.perf_counter() - start
    data = {"out": str(args.out), "sections": names, "quick": bool(args.quick), "seconds": round(elapsed, 3)}
    return Result(data, f"regenerated {', '.join(names)} in {args.out}/ ({elapsed:.1f} s)")


def register(commands) -> None:
    """Add ``strapdown report`` to ``commands``.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    from ..report import section_names

    sections = ", ".join(section_names())
    p = commands.add("report", report_command, "regenerate every report (errata, algorithms, derivations, stability, azimuth, index, HTML)", progress="own")
    p.add_argument(
        "--out",
        default="reports",
        metavar="DIR",
        help="output directory [path] (default: reports); it must be empty, new, or hold only files an earlier `strapdown report` wrote",
    )
    p.add_argument(
        "--only",
        nargs="+",
        metavar="SECTION",
        help=f"rebuild only these sections [name], one of: {sections}; the errata, the index and the HTML edition are always rebuilt too, other sections are kept (default: all)",
    )
    p.add_argument("--quick", action="store_true", help="reduced Monte Carlo sizes and grids (for CI)")
    p.add_argument("--overwrite-modified", action="store_true", help="replace generated files edited since they were written (by default the run is refused and the edits kept)")
