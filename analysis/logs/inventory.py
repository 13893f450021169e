"""What a recorded log holds: its streams, their timing, units, frame and the filters in front of them.

Every reader (:mod:`~strapdown.analysis.logs.reader`) returns an
:class:`Inventory` beside the samples, so that a user sees what was read and
how before trusting an analysis of it.

Public API
----------
.. autosummary::

   StreamInfo
   Gap
   Timing
   SensorFilter
   GnssTrack
   Inventory
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["StreamInfo", "Gap", "Timing", "SensorFilter", "GnssTrack", "Inventory"]


@dataclass(frozen=True)
class StreamInfo:
    """One stream (topic, message) a log holds.

    Attributes
    ----------
    topic : str
        Name to pass as ``topic`` (``"sensor_combined"``, ``"vehicle_imu/1"``, ``"IMU[0]"``, ``"/imu0"``).
    samples : int
        Messages [count].
    rate_hz : float
        Mean message rate, (samples − 1) / span [Hz] (0 for fewer than two).
    start, end : float
        First and last sample, from the log's start [s].
    held : str
        ``"increments"``, ``"rates"`` or ``"other"`` (not IMU samples: GNSS, status, ...).
    readable : bool
        Whether :func:`~strapdown.analysis.logs.reader.read_imu_log` reads it as IMU samples.
    note : str
        What the stream is, and why it is not read where it is not.
    """

    topic: str
    samples: int
    rate_hz: float
    start: float
    end: float
    held: str
    readable: bool
    note: str = ""


@dataclass(frozen=True)
class Gap:
    """An interruption of the samples: an interval longer than 1.5 nominal intervals.

    Attributes
    ----------
    start : float
        Time of the last sample before the gap, from the log's start [s].
    duration : float
        Interval between the two samples around the gap [s].
    missing : int
        Nominal samples that would fit in the gap [count].
    """

    start: float
    duration: float
    missing: int


@dataclass(frozen=True)
class Timing:
    """The time base of the chosen stream.

    Attributes
    ----------
    interval : float
        Median interval between samples [s].
    rate_hz : float
        1 / ``interval`` [Hz].
    jitter_rms, jitter_max : float
        Root-mean-square and largest departure of the intervals inside the segments from their
        segment's mean interval [s].
    gaps : tuple of Gap
        Every gap (a new segment starts after each).
    glitches : int
        Intervals shorter than half the nominal one, or not increasing (a segment starts there too) [count].
    logger_dropouts : float
        Total time the logger itself reports as lost (ULog dropout messages) [s].
    integration_interval : float or None
        Median integration interval the log states for its increments (PX4 ``gyro_integral_dt``,
        ArduPilot ``DelaT``) [s], or None.
    integration_interval_unit : str
        The unit of that field as found in the log (``"s"``, ``"us"``), or ``""``.
    """

    interval: float
    rate_hz: float
    jitter_rms: float
    jitter_max: float
    gaps: tuple = ()
    glitches: int = 0
    logger_dropouts: float = 0.0
    integration_interval: float | None = None
    integration_interval_unit: str = ""

    @property
    def missing(self) -> int:
        """Samples missing in the gaps [count]."""
        return int(sum(g.missing for g in self.gaps))


@dataclass(frozen=True)
class SensorFilter:
    """A filter parameter of the autopilot and whether it acts on the samples the log holds.

    Attributes
    ----------
    parameter : str
        The parameter's name (``IMU_GYRO_CUTOFF``, ``INS_GYRO_FILTER``).
    value : float or None
        Its value in the log [Hz, or as the autopilot defines it], or None where the log does not hold it.
    acts_on_samples : bool or None
        True where the filter is in front of the logged samples, False where it acts on another
        path (the control loop), None where the source does not decide.
    evidence : str
        Where this comes from: the autopilot's source file and what it does.
    """

    parameter: str
    value: float | None
    acts_on_samples: bool | None
    evidence: str


@dataclass(frozen=True)
class GnssTrack:
    """GNSS fixes a log holds (for the latitude check and the aided alignment).

    Attributes
    ----------
    topic : str
        Where they come from (``vehicle_gps_position``, ``GPS[0]``).
    time : ndarray
        ``(M,)`` time of each fix, from the log's start [s].
    latitude, longitude : ndarray
        ``(M,)`` [rad].
    altitude : ndarray
        ``(M,)`` above mean sea level or the ellipsoid, as the log gives it [m].
    velocity : ndarray or None
        ``(M, 3)`` north, east, down [m/s], or None where the log has no velocity.
    """

    topic: str
    time: np.ndarray
    latitude: np.ndarray
    longitude: np.ndarray
    altitude: np.ndarray
    velocity: np.ndarray | None = None

    @property
    def mean_latitude(self) -> float:
        """Mean latitude of the fixes [rad]."""
        return float(np.mean(self.latitude))


@dataclass(frozen=True)
class Inventory:
    """What a log holds and how its samples were read.

    Attributes
    ----------
    format : str
        ``"ulog"``, ``"dataflash"``, ``"rosbag1"``, ``"rosbag2"``, ``"euroc"``, ``"npz"`` or ``"csv"``.
    streams : tuple of StreamInfo
        Every stream found (IMU or not).
    topic : str
        The stream read.
    held : str
        ``"increments"`` or ``"rates"``: what that stream holds.
    conversion : str
        How the samples became increments (and what the rates are, where they are rates).
    units : str
        The units found in the log, and how they were converted to SI.
    frame : str
        The frame of the log's axes and the conversion to the package's body axes (x forward, y right, z down).
    timing : Timing
        Time base of the stream read.
    filters : tuple of SensorFilter
        The autopilot's sensor filters, and whether they act on the samples read.
    software : str
        Autopilot and version where the log states them.
    start_time : float
        The log's start in its own clock [s]; every time of the inventory is from it.
    duration : float
        From the log's start to its last message [s].
    gnss : GnssTrack or None
        GNSS fixes, where the log holds them.
    metadata : dict
        Metadata of the package's own formats (latitude, truth angles, description).
    notes : tuple of str
        Anything else the reader saw (a truncated last message, a corrupt record, a unit inferred).
    """

    format: str
    streams: tuple
    topic: str
    held: str
    conversion: str
    units: str
    frame: str
    timing: Timing
    filters: tuple = ()
    software: str = ""
    start_time: float = 0.0
    duration: float = 0.0
    gnss: GnssTrack | None = None
    metadata: dict = field(default_factory=dict)
    notes: tuple = ()
