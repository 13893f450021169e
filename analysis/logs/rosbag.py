"""ROS 1 (``.bag``) and ROS 2 (a bag directory, or its ``.db3``/``.mcap`` file) bags: ``sensor_msgs/Imu`` topics.

Read with ``rosbags`` (``rosbags.highlevel.AnyReader``), which needs no ROS
installation.  A ``sensor_msgs/Imu`` message holds the angular velocity
[rad/s] and the linear acceleration [m/s²] of its ``header.frame_id``, sampled
at ``header.stamp``: rates, not increments (its covariance fields are kept out).

Frames: ROS's body convention (REP 103) is x forward, y left, z up (FLU), and an
accelerometer at rest reads +g on z (REP 145: the specific force).  The package's
body axes are x forward, y right, z down (FRD), so the reader turns FLU into FRD
as ``(x, −y, −z)`` for both vectors (a rotation by π about x).  A bag whose IMU
frame is not FLU (an ``imu_link`` mounted otherwise) needs that mounting too; the
gravity-direction check then warns.

Public API
----------
.. autosummary::

   read_rosbag
   FLU_TO_FRD
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .inventory import StreamInfo
from .streams import LogContents, StreamSamples, choose_topic

__all__ = ["read_rosbag", "FLU_TO_FRD"]

#: Signs that turn FLU (REP 103) vectors into FRD ones: a rotation by π about x.
FLU_TO_FRD = np.array([1.0, -1.0, -1.0])

_IMU_TYPES = ("sensor_msgs/msg/Imu", "sensor_msgs/Imu")


def read_rosbag(path, *, topic: str | None = None, guard=None, progress: bool = False) -> LogContents:
    """Read a ROS 1 or ROS 2 bag: its topics, the chosen ``sensor_msgs/Imu`` topic's samples in FRD.

    Parameters
    ----------
    path : str or Path
        A ROS 1 ``.bag`` file, or a ROS 2 bag directory (or its ``.db3``/``.mcap`` file).
    topic : str, optional, keyword-only
        The IMU topic (default: the ``sensor_msgs/Imu`` topic of highest rate that covers the bag).
    guard : callable, optional, keyword-only
        ``guard(samples, topic)`` called before the messages are read.
    progress : bool, keyword-only
        Progress on stderr.

    Returns
    -------
    LogContents

    Raises
    ------
    ValueError
        Not a bag ``rosbags`` can open, no ``sensor_msgs/Imu`` topic, an unknown ``topic``.

    References
    ----------
    ROS REP 103 "Standard Units of Measure and Coordinate Conventions"; REP 145 "Conventions for IMU
    Sensor Drivers"; ``sensor_msgs/msg/Imu``.
    """
    from rosbags.highlevel import AnyReader, AnyReaderError

    from ..core.progress import bar

    p = Path(path)
    bag = p.parent if p.suffix.lower() in (".db3", ".mcap") else p
    try:
        reader = AnyReader([bag])
        reader.open()
    except (AnyReaderError, OSError) as e:
        if isinstance(e, (FileNotFoundError, IsADirectoryError, PermissionError)):
            raise
        raise ValueError(f"Expected a ROS 1 or ROS 2 bag readable by rosbags at {p.name}, got: {e}") from None
    try:
        fmt = "rosbag1" if p.suffix.lower() == ".bag" else "rosbag2"
        start, end = reader.start_time * 1e-9, reader.end_time * 1e-9
        duration = max(0.0, end - start)
        streams = []
        for c in sorted(reader.connections, key=lambda c: c.topic):
            n = int(c.msgcount)
            rate = (n - 1) / duration if n > 1 and duration > 0 else 0.0
            imu = c.msgtype in _IMU_TYPES
            note = "sensor_msgs/Imu: angular velocity and linear acceleration (rates), FLU turned into FRD" if imu else c.msgtype
            streams.append(StreamInfo(c.topic, n, rate, 0.0, duration, "rates" if imu else "other", imu, note))
        chosen = choose_topic(streams, topic, duration, p.name)
        if guard is not None:
            guard(chosen.samples, chosen.topic)
        conns = [c for c in reader.connections if c.topic == chosen.topic]
        n = sum(int(c.msgcount) for c in conns)
        time = np.empty(n)
        rows = np.empty((n, 6))
        frames = set()
        k = 0
        with bar(desc=f"reading {chosen.topic}", total=n, enabled=progress, unit="msg") as pb:
            for conn, _, raw in reader.messages(connections=conns):
                m = reader.deserialize(raw, conn.msgtype)
                if k >= n:
                    break
                time[k] = m.header.stamp.sec + m.header.stamp.nanosec * 1e-9
                w, a = m.angular_velocity, m.linear_acceleration
                rows[k] = (w.x, w.y, w.z, a.x, a.y, a.z)
                frames.add(m.header.frame_id)
                k += 1
                if k % 65536 == 0:
                    pb.update(65536)
        time, rows = time[:k], rows[:k]
        stamps_start = float(time.min()) if k else start
        t0 = min(start, stamps_start)
        order = np.argsort(time, kind="stable")
        if np.any(order != np.arange(k)):
            time, rows = time[order], rows[order]
        gyro, accel = rows[:, :3] * FLU_TO_FRD, rows[:, 3:] * FLU_TO_FRD
        samples = StreamSamples(
            chosen.topic, time - t0, gyro, accel, "rates", "rate × interval (the sample's rate held over the interval that ends at its header.stamp)",
            "rad/s and m/s² (SI in the message)", f"REP 103 FLU ({', '.join(sorted(frames)) or 'no frame_id'}) turned into FRD as (x, −y, −z)",
        )  # fmt: skip
        notes = ("messages sorted by header.stamp (they were stored out of order)",) if np.any(order != np.arange(k)) else ()
        return LogContents(fmt, tuple(streams), samples, (), "ROS", t0, duration, None, {}, notes)
    finally:
        reader.close()
