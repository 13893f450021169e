"""Reading a recorded log on the command line: the options, the checks, the one-line refusals.

Every command that takes a log reads it with :func:`load_log`: the log is
read (:func:`strapdown.analysis.logs.reader.read_imu_log`), its plausibility
checks run with the command's latitude where it has one, a failed check becomes
the one-line usage error (exit 2) naming the check and the value seen, and each
warning is printed as one line on stderr.
"""

from __future__ import annotations

import math
import sys

from . import UsageError

__all__ = ["load_log", "add_log_options", "parse_segment"]


def add_log_options(parser, *, topic_option: str = "--topic", segment_option: str = "--segment") -> None:
    """Add ``--topic`` [name] and ``--segment START:END`` [s] to a command that reads a log.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    topic_option, segment_option : str, keyword-only
        The options' names.
    """
    parser.add_argument(
        topic_option, default=None, help="stream of the log to read, e.g. sensor_combined, vehicle_imu/1, IMU[0], /imu0 [name] (default: the stream of highest rate that covers the log)"
    )
    parser.add_argument(segment_option, default=None, metavar="START:END", help="stretch of the log to read, seconds from its start, either side may be empty [s] (default: the whole log)")


def parse_segment(text, option: str = "--segment"):
    """``"START:END"`` → ``(start, end)`` [s], either None; None for None.

    Parameters
    ----------
    text : str or None
        The value as typed.
    option : str
        The option, for messages.

    Returns
    -------
    tuple or None

    Raises
    ------
    UsageError
        A value that is not ``START:END`` with numbers, or an end before its start.
    """
    if text is None:
        return None
    lo, sep, hi = str(text).partition(":")
    if not sep:
        raise UsageError(f"Expected {option} as START:END in seconds from the log's start (either may be empty), got {text!r}")
    try:
        a = float(lo) if lo.strip() else None
        b = float(hi) if hi.strip() else None
    except ValueError:
        raise UsageError(f"Expected {option} as START:END with numbers [s], got {text!r}") from None
    if any(v is not None and not math.isfinite(v) for v in (a, b)) or (a is not None and b is not None and not b > a):
        raise UsageError(f"Expected {option} START:END with finite numbers and END after START, got {text!r}")
    return (a, b)


def load_log(args, *, topic_option: str = "--topic", segment_option: str = "--segment", refuse: bool = True):
    """Read, check and return the log of a command (``args.file`` or ``args.log``).

    Parameters
    ----------
    args : argparse.Namespace
        The command's options: the log (``file`` or ``log``), the topic and segment options,
        ``lat_deg`` where the command has a latitude, and the work limits.
    topic_option, segment_option : str, keyword-only
        The names of the topic and segment options (their ``dest`` is derived from them).
    refuse : bool, keyword-only
        Refuse a log that fails a check and print the warnings (``log inspect``, which shows
        the checks, passes False).

    Returns
    -------
    RecordedLog

    Raises
    ------
    UsageError
        A failed check: ``log check 'NAME' failed: ... (value seen: ...)``.
    ValueError
        A log the reader refuses (corrupt, truncated, unknown format, work beyond the limits).
    """
    from ..logs.reader import read_imu_log
    from ._options import limits_from

    path = getattr(args, "file", None) or getattr(args, "log", None)
    topic = getattr(args, topic_option.lstrip("-").replace("-", "_"), None)
    segment = parse_segment(getattr(args, segment_option.lstrip("-").replace("-", "_"), None), segment_option)
    lat_deg = getattr(args, "lat_deg", None)
    latitude = None if lat_deg is None else math.radians(float(lat_deg))
    try:
        log = read_imu_log(path, topic=topic, segment=segment, limits=limits_from(args), progress=bool(getattr(args, "progress", False)), latitude=latitude)
    except ValueError as e:
        message = str(e)
        if "`topic`" in message:
            raise UsageError(message.replace("`topic`", topic_option)) from None
        if "`segment`" in message:
            raise UsageError(message.replace("`segment`", segment_option)) from None
        raise
    if not refuse:
        return log
    name = getattr(args, "command_", "log")
    for c in log.checks.failures:
        raise UsageError(f"{log.path.name}: {c.line()}")
    for c in log.checks.warnings:
        sys.stderr.write(f"strapdown {name}: warning: {log.path.name}: {c.line()}\n")
    sys.stderr.flush()
    return log
