"""EuRoC MAV and TUM-VI style IMU files (``imu0/data.csv``).

One row per sample: ``#timestamp [ns], w_RS_S_x [rad s^-1], w_RS_S_y, w_RS_S_z,
a_RS_S_x [m s^-2], a_RS_S_y, a_RS_S_z``: the time in integer nanoseconds, the
angular rate and the specific force in the sensor frame S.  Rates, not
increments.  The path may be the CSV file or a folder holding ``imu0/data.csv``
(or ``mav0/imu0/data.csv``).

The axes are the sensor's own (the frame S of the dataset's ``sensor.yaml``); the
reader does not rotate them.  The package's analyses take x forward, y right,
z down: the gravity-direction check says where a dataset's IMU is mounted
otherwise.

Public API
----------
.. autosummary::

   read_euroc
   find_euroc_csv
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .inventory import StreamInfo
from .streams import LogContents, StreamSamples

__all__ = ["read_euroc", "find_euroc_csv"]


def find_euroc_csv(path) -> Path | None:
    """The ``data.csv`` of an EuRoC/TUM-VI IMU at ``path`` (the file, or a folder above it), or None.

    Parameters
    ----------
    path : str or Path
        A CSV file or a folder.

    Returns
    -------
    Path or None
    """
    p = Path(path)
    candidates = [p] if p.is_file() else [p / "data.csv", p / "imu0" / "data.csv", p / "mav0" / "imu0" / "data.csv"]
    for c in candidates:
        if c.is_file() and c.suffix.lower() == ".csv":
            with open(c, encoding="utf-8", errors="replace") as f:
                first = f.readline()
            if first.startswith("#") and "timestamp" in first and "w_RS_S_x" in first:
                return c
    return None


def read_euroc(path, *, topic: str | None = None, guard=None, progress: bool = False) -> LogContents:
    """Read an EuRoC/TUM-VI IMU file.

    Parameters
    ----------
    path : str or Path
        The ``data.csv`` or a folder above it.
    topic : str, optional, keyword-only
        ``"imu0"`` (the one stream) or None.
    guard : callable, optional, keyword-only
        ``guard(samples, topic)`` called before the rows are parsed (from the file size).
    progress : bool, keyword-only
        Unused.

    Returns
    -------
    LogContents

    Raises
    ------
    ValueError
        No such file, a row that is not seven numbers.

    References
    ----------
    Burri et al. (2016), "The EuRoC micro aerial vehicle datasets", IJRR 35(10); Schubert et al.
    (2018), "The TUM VI benchmark for evaluating visual-inertial odometry".
    """
    p = Path(path)
    csv = find_euroc_csv(p)
    if csv is None:
        raise ValueError(f"Expected an EuRoC/TUM-VI IMU file (a CSV whose header starts '#timestamp [ns],w_RS_S_x ...'), got {p.name}")
    name = csv.parent.name if csv.parent.name.startswith("imu") else "imu0"
    if topic not in (None, name):
        raise ValueError(f"Expected `topic` {name!r} (the one stream of {csv.name}), got {topic!r}")
    if guard is not None:
        guard(max(2, csv.stat().st_size // 60), name)  # a row holds at least about 60 characters
    try:
        stamps = np.loadtxt(csv, delimiter=",", comments="#", usecols=0, dtype=np.int64, ndmin=1)
        rows = np.loadtxt(csv, delimiter=",", comments="#", usecols=(1, 2, 3, 4, 5, 6), dtype=float, ndmin=2)
    except ValueError as e:
        raise ValueError(f"Expected rows of seven numbers (time [ns], three rates, three specific forces) in {csv.name}, got: {e}") from None
    if stamps.size < 2:
        raise ValueError(f"Expected at least two samples in {csv.name}, got {stamps.size}")
    h = float(np.median(np.diff(stamps))) * 1e-9
    start_ns = int(stamps[0]) - int(round(h * 1e9))
    t = (stamps - start_ns) * 1e-9
    rate = (t.size - 1) / (t[-1] - t[0]) if t[-1] > t[0] else 0.0
    stream = StreamInfo(name, int(t.size), float(rate), float(t[0]), float(t[-1]), "rates", True, "EuRoC/TUM-VI IMU: angular rate and specific force, sensor frame S")
    samples = StreamSamples(
        name, t, rows[:, :3], rows[:, 3:], "rates", "rate × interval (the rate held over the interval that ends at its timestamp)",
        "time in integer nanoseconds → s; rad/s and m/s² (SI in the file)", "the sensor frame S as in the file: not rotated (the package takes x forward, y right, z down)",
    )  # fmt: skip
    return LogContents("euroc", (stream,), samples, (), "EuRoC/TUM-VI", start_ns * 1e-9, float(t[-1]), None, {}, ())
