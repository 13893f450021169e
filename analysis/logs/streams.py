"""From the samples of one stream to gap-free, constant-rate segments of increments.

A recorded stream has jitter, dropouts and gaps.  :func:`split_segments` cuts
it where an interval is longer than 1.5 nominal intervals (a gap: samples
missing) or shorter than half of one (a time-base glitch), and gives each
stretch between the cuts as an :class:`~strapdown.analysis.logs.imu_log.ImuLog`
on a uniform time grid: its interval is the stretch's mean interval, and the
departures of the recorded times from that grid are the jitter the
:class:`~strapdown.analysis.logs.inventory.Timing` reports.  Rates become
increments as rate × interval (the rate held constant over the interval that
ends at its sample); increments are kept as they are.

Public API
----------
.. autosummary::

   StreamSamples
   LogContents
   choose_topic
   split_segments
   GAP_FACTOR
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .imu_log import ImuLog
from .inventory import Gap, GnssTrack, StreamInfo, Timing

__all__ = ["StreamSamples", "LogContents", "choose_topic", "split_segments", "GAP_FACTOR"]

#: An interval longer than this many nominal intervals is a gap (a new segment starts after it).
GAP_FACTOR = 1.5

#: A stream "covers" the log when it spans at least this fraction of the log's duration.
_COVER = 0.8


@dataclass(frozen=True)
class StreamSamples:
    """The samples of one stream as a format's reader found them, in SI units and body axes (FRD).

    Attributes
    ----------
    topic : str
        The stream.
    time : ndarray
        ``(N,)`` time of each sample, the end of its interval, from the log's start [s].
    gyro : ndarray
        ``(N, 3)`` angle increments [rad] or angular rates [rad/s].
    accel : ndarray
        ``(N, 3)`` velocity increments [m/s] or specific force [m/s²].
    held : str
        ``"increments"`` or ``"rates"``.
    conversion : str
        How the log's fields became these samples.
    units : str
        The units found and the conversion to SI.
    frame : str
        The log's axes and the conversion to the body axes x forward, y right, z down.
    integration : ndarray or None
        ``(N,)`` integration interval the log states for each increment [s].
    integration_unit : str
        The unit of that interval in the log (``"s"``, ``"us"``).
    """

    topic: str
    time: np.ndarray
    gyro: np.ndarray
    accel: np.ndarray
    held: str
    conversion: str
    units: str
    frame: str
    integration: np.ndarray | None = None
    integration_unit: str = ""


@dataclass(frozen=True)
class LogContents:
    """What a format's reader returns: the inventory's pieces and the samples of the stream read.

    Attributes
    ----------
    format : str
        The format's name.
    streams : tuple of StreamInfo
        Every stream found.
    samples : StreamSamples
        The stream read.
    filters : tuple of SensorFilter
        The autopilot's sensor filters.
    software : str
        Autopilot and version.
    start_time : float
        The log's start in its own clock [s].
    duration : float
        From the start to the last message [s].
    gnss : GnssTrack or None
        GNSS fixes.
    metadata : dict
        Metadata of the package's formats.
    notes : tuple of str
        What else the reader saw.
    logger_dropouts : float
        Time the logger reports as lost [s].
    """

    format: str
    streams: tuple
    samples: StreamSamples
    filters: tuple = ()
    software: str = ""
    start_time: float = 0.0
    duration: float = 0.0
    gnss: GnssTrack | None = None
    metadata: dict = field(default_factory=dict)
    notes: tuple = ()
    logger_dropouts: float = 0.0


def choose_topic(streams, topic: str | None, duration: float, path_name: str) -> StreamInfo:
    """The stream to read: ``topic`` if given, else the readable stream of highest rate that covers the log.

    A stream covers the log when its first-to-last span is at least 80 % of the log's
    duration (or of the longest readable stream's span); among those the highest rate wins,
    then the most samples.

    Parameters
    ----------
    streams : sequence of StreamInfo
        The streams found.
    topic : str or None
        The stream asked for.
    duration : float
        The log's duration [s].
    path_name : str
        The file's name, for messages.

    Returns
    -------
    StreamInfo

    Raises
    ------
    ValueError
        If ``topic`` is not a readable stream of the log, or the log has none.
    """
    readable = [s for s in streams if s.readable]
    if topic is not None:
        for s in streams:
            if s.topic == topic:
                if not s.readable:
                    raise ValueError(f"Expected `topic` to be a stream of IMU samples, got {topic!r}: {s.note}")
                return s
        names = ", ".join(s.topic for s in readable) or "none"
        raise ValueError(f"Expected `topic` among the IMU streams of {path_name} ({names}), got {topic!r}")
    if not readable:
        found = ", ".join(s.topic for s in streams[:12]) or "nothing"
        raise ValueError(f"Expected a stream of IMU samples (gyro and accelerometer together) in {path_name}, found {found}")
    span = max([duration] + [s.end - s.start for s in readable])
    longest = max(s.end - s.start for s in readable)
    reference = min(span, longest) if longest > 0 else span
    covering = [s for s in readable if s.samples >= 2 and (s.end - s.start) >= _COVER * reference] or readable
    return max(covering, key=lambda s: (round(s.rate_hz), s.held == "increments", s.samples))


def split_segments(time, gyro, accel, *, held: str, window=None, metadata=None, logger_dropouts: float = 0.0, integration=None, integration_unit: str = ""):
    """Cut a stream into gap-free constant-rate segments of increments.

    Parameters
    ----------
    time : ndarray
        ``(N,)`` time of each sample (the end of its interval), from the log's start [s].
    gyro : ndarray
        ``(N, 3)`` angle increments [rad] or angular rates [rad/s], body axes.
    accel : ndarray
        ``(N, 3)`` velocity increments [m/s] or specific force [m/s²], body axes.
    held : str, keyword-only
        ``"increments"`` or ``"rates"``.
    window : tuple of (float or None), optional, keyword-only
        ``(start, end)`` [s from the log's start]: keep the samples whose time lies in ``(start, end]``.
    metadata : dict, optional, keyword-only
        Metadata given to every segment (:data:`~strapdown.analysis.logs.imu_log.METADATA`).
    logger_dropouts : float, keyword-only
        Time the logger reports as lost [s] (reported in the timing).
    integration : ndarray, optional, keyword-only
        ``(N,)`` integration interval the log states for each increment [s].
    integration_unit : str, keyword-only
        The unit that interval had in the log.

    Returns
    -------
    segments : tuple of ImuLog
        The stretches of at least two samples, in time order.
    timing : Timing

    Raises
    ------
    ValueError
        If ``held`` is not one of the two, or fewer than two samples remain in ``window``.
    """
    if held not in ("increments", "rates"):
        raise ValueError(f"Expected `held` in ('increments', 'rates'), got {held!r}")
    t = np.asarray(time, dtype=float)
    if window is not None:
        lo, hi = window
        keep = np.ones(t.size, dtype=bool)
        if lo is not None:
            keep &= t > lo
        if hi is not None:
            keep &= t <= hi
        if not np.all(keep):
            idx = np.flatnonzero(keep)
            sl = slice(idx[0], idx[-1] + 1) if idx.size else slice(0, 0)
            t, gyro, accel = t[sl], gyro[sl], accel[sl]
            integration = None if integration is None else integration[sl]
    if t.size < 2:
        raise ValueError(f"Expected at least two samples in `segment` {window}, got {t.size}")
    d = np.diff(t)
    positive = d[d > 0]
    h = float(np.median(positive)) if positive.size else float("nan")
    gap = d > GAP_FACTOR * h
    glitch = ~(d >= 0.5 * h)
    cut = np.flatnonzero(gap | glitch)
    starts = np.concatenate([[0], cut + 1])
    ends = np.concatenate([cut + 1, [t.size]])
    gaps = tuple(Gap(float(t[i]), float(d[i]), int(round(d[i] / h)) - 1) for i in np.flatnonzero(gap))
    segments, dev = [], []
    meta = dict(metadata or {})
    for s, e in zip(starts, ends):
        n = e - s
        if n < 2:
            continue
        ts = t[s:e]
        hs = (ts[-1] - ts[0]) / (n - 1)
        grid = ts[0] + hs * np.arange(n)
        dev.append(np.diff(ts) - hs)
        g, a = gyro[s:e], accel[s:e]
        if held == "rates":
            g, a = g * hs, a * hs
        segments.append(ImuLog(grid, g, a, meta))
    jit = np.concatenate(dev) if dev else np.zeros(0)
    rms = float(np.sqrt(np.mean(jit**2))) if jit.size else 0.0
    peak = float(np.max(np.abs(jit))) if jit.size else 0.0
    integ = None
    if integration is not None and np.size(integration):
        integ = float(np.median(integration))
    timing = Timing(h, 1.0 / h, rms, peak, gaps, int(np.count_nonzero(glitch)), float(logger_dropouts), integ, integration_unit if integ is not None else "")
    return tuple(segments), timing
