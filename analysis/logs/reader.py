"""One reader of IMU logs: PX4 ULog, ArduPilot DataFlash, ROS 1/2 bags, EuRoC/TUM-VI CSV, the package's own files.

:func:`read_imu_log` finds the format (by suffix and content), reads the
chosen stream with the format's module, cuts it into gap-free constant-rate
segments of increments in body axes (x forward, y right, z down; SI), says
what it found (:class:`~strapdown.analysis.logs.inventory.Inventory`) and
runs the plausibility checks (:mod:`~strapdown.analysis.logs.checks`).

======================  =====================================================
format                  module
======================  =====================================================
``.ulg``                :mod:`~strapdown.analysis.logs.ulog`
``.bin``                :mod:`~strapdown.analysis.logs.dataflash`
``.bag``, ROS 2 bag     :mod:`~strapdown.analysis.logs.rosbag`
``imu0/data.csv``       :mod:`~strapdown.analysis.logs.euroc`
``.npz``, ``.csv``      :mod:`~strapdown.analysis.logs.native`
======================  =====================================================

Public API
----------
.. autosummary::

   RecordedLog
   read_imu_log
   detect_format
   FORMATS
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

from ..core import budget
from ..core.validation import as_float
from .checks import LogChecks, check_log
from .imu_log import ImuLog
from .inventory import Inventory
from .streams import split_segments

__all__ = ["RecordedLog", "read_imu_log", "detect_format", "FORMATS"]

#: The formats :func:`read_imu_log` reads.
FORMATS = ("ulog", "dataflash", "rosbag1", "rosbag2", "euroc", "npz", "csv")


@dataclass(frozen=True)
class RecordedLog:
    """A recorded IMU log, read and checked.

    Attributes
    ----------
    path : Path
        The file (or bag directory).
    format : str
        From :data:`FORMATS`.
    topic : str
        The stream read.
    segments : tuple of ImuLog
        The gap-free constant-rate stretches, in time order: increments in body axes
        (x forward, y right, z down), SI, times from the log's start [s].  A gap starts a new one.
    inventory : Inventory
        What the log holds and how it was read.
    checks : LogChecks
        The plausibility checks.
    """

    path: Path
    format: str
    topic: str
    segments: tuple
    inventory: Inventory
    checks: LogChecks

    @property
    def held(self) -> str:
        """``"increments"`` or ``"rates"``: what the stream read holds."""
        return self.inventory.held

    @property
    def conversion(self) -> str:
        """How the samples became increments (rate × interval for rates)."""
        return self.inventory.conversion

    @property
    def n_samples(self) -> int:
        """Samples in all segments [count]."""
        return int(sum(s.n_samples for s in self.segments))

    @property
    def duration(self) -> float:
        """Time the segments cover [s]."""
        return float(sum(s.n_samples * s.dt for s in self.segments))

    @property
    def longest(self) -> ImuLog:
        """The longest segment."""
        return max(self.segments, key=lambda s: s.n_samples)

    @property
    def metadata(self) -> dict:
        """Metadata of the package's own formats (latitude, truth angles, description)."""
        return dict(self.inventory.metadata)

    def recheck(self, *, latitude: float | None = None) -> RecordedLog:
        """The same log with its checks run again (with the latitude an analysis will use).

        Parameters
        ----------
        latitude : float, optional, keyword-only
            Latitude φ [rad].

        Returns
        -------
        RecordedLog
        """
        return replace(self, checks=check_log(self.segments, self.inventory, latitude=latitude))


def detect_format(path) -> str:
    """The format of ``path`` (from :data:`FORMATS`), by suffix and content.

    Parameters
    ----------
    path : str or Path
        A file, or a ROS 2 bag / EuRoC folder.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If no reader knows it.
    FileNotFoundError
        If it does not exist.
    """
    from .euroc import find_euroc_csv

    p = Path(path)
    if not p.exists():
        raise FileNotFoundError(2, "No such file or directory", str(p))
    if p.is_dir():
        if (p / "metadata.yaml").is_file():
            return "rosbag2"
        if find_euroc_csv(p) is not None:
            return "euroc"
        raise ValueError(f"Expected a log file, a ROS 2 bag folder (with metadata.yaml) or an EuRoC folder (with imu0/data.csv), got the folder {p.name}")
    suffix = p.suffix.lower()
    with open(p, "rb") as f:
        head = f.read(16)
    if head.startswith(b"ULog"):
        return "ulog"
    if head[:2] == b"\xa3\x95":
        return "dataflash"
    if head.startswith(b"#ROSBAG"):
        return "rosbag1"
    if suffix in (".db3", ".mcap"):
        return "rosbag2"
    if suffix == ".npz":
        return "npz"
    if suffix == ".csv":
        return "euroc" if find_euroc_csv(p) is not None else "csv"
    known = {".ulg": "a ULog", ".bin": "a DataFlash log", ".bag": "a ROS 1 bag"}
    if suffix in known:
        raise ValueError(f"Expected {known[suffix]} in {p.name}, got a file that does not start like one ({head[:8]!r})")
    raise ValueError(f"Expected a log in one of the formats .ulg, .bin, .bag, a ROS 2 bag, EuRoC imu0/data.csv, .npz or .csv, got {p.name!r}")


def _window(segment):
    if segment is None:
        return None
    if not isinstance(segment, (tuple, list)) or len(segment) != 2:
        raise TypeError(f"Expected `segment` as (start, end) in seconds from the log's start, either None, got {segment!r}")
    lo = None if segment[0] is None else as_float(segment[0], "segment")
    hi = None if segment[1] is None else as_float(segment[1], "segment")
    if lo is not None and hi is not None and not hi > lo:
        raise ValueError(f"Expected `segment` with its end after its start, got ({lo:g}, {hi:g}) s")
    if (lo is not None and not math.isfinite(lo)) or (hi is not None and not math.isfinite(hi)):
        raise ValueError(f"Expected a finite `segment`, got {segment!r}")
    return (lo, hi)


def read_imu_log(path, *, topic: str | None = None, segment=None, limits: budget.Limits | None = None, progress: bool = False, latitude: float | None = None) -> RecordedLog:
    """Read an IMU log in any supported format, cut it into segments, say what it holds and check it.

    Parameters
    ----------
    path : str or Path
        The log: ``.ulg``, ``.bin``, ``.bag``, a ROS 2 bag folder, EuRoC ``imu0/data.csv``, ``.npz``, ``.csv``.
    topic : str, optional, keyword-only
        The stream to read (default: the stream of highest rate that covers the log).
    segment : tuple of (float or None), optional, keyword-only
        ``(start, end)`` [s from the log's start]: keep the samples in between (either may be None).
    limits : Limits, optional, keyword-only
        The largest work accepted (the estimate counts the samples of the stream read).
    progress : bool, keyword-only
        Progress on stderr.
    latitude : float, optional, keyword-only
        The latitude an analysis will use [rad], checked against the log's own position.

    Returns
    -------
    RecordedLog
        With ``checks``: look at ``checks.failures`` before analysing (the command line refuses them).

    Raises
    ------
    ValueError
        An unknown format, a corrupt or truncated file, no IMU stream, an unknown ``topic``, a
        ``segment`` without two samples, or work beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`).
    TypeError
        A ``segment`` that is not a pair.
    OSError
        A file that cannot be read.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from strapdown.analysis.logs.synthetic import still_truth, write_synthetic
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "still.npz"
    >>> _ = write_synthetic(path, still_truth(duration=20.0, rate=50.0))
    >>> log = read_imu_log(path)
    >>> log.format, log.topic, len(log.segments), log.checks.passed
    ('npz', 'imu', 1, True)
    """
    p = Path(path)
    window = _window(segment)
    limits = budget.as_limits(limits)
    fmt = detect_format(p)

    def guard(samples, stream):
        budget.check(budget.recorded_log(samples, what=f"`path` {p.name} ({float(samples):.3g} samples of {stream})"), limits)

    if fmt == "ulog":
        from .ulog import read_ulog as reader
    elif fmt == "dataflash":
        from .dataflash import read_dataflash as reader
    elif fmt in ("rosbag1", "rosbag2"):
        from .rosbag import read_rosbag as reader
    elif fmt == "euroc":
        from .euroc import read_euroc as reader
    else:
        from .native import read_native as reader
    c = reader(p, topic=topic, guard=guard, progress=progress)
    s = c.samples
    if latitude is not None:
        latitude = as_float(latitude, "latitude")
    segments, timing = split_segments(
        s.time, s.gyro, s.accel, held=s.held, window=window, metadata=c.metadata, logger_dropouts=c.logger_dropouts, integration=s.integration, integration_unit=s.integration_unit
    )
    inventory = Inventory(
        c.format, c.streams, s.topic, s.held, s.conversion, s.units, s.frame, timing, c.filters, c.software, c.start_time, c.duration, c.gnss, dict(c.metadata), c.notes
    )  # fmt: skip
    if not segments:
        raise ValueError(f"Expected at least one stretch of two samples without a gap in {p.name}, got none (segment {window})")
    checks = check_log(segments, inventory, latitude=latitude)
    return RecordedLog(p, c.format, s.topic, segments, inventory, checks)
