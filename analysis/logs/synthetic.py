"""Synthetic logs with a known truth, written in every format the reader takes.

A :class:`SyntheticTruth` holds increments in body axes (x forward, y right,
z down), SI, at a constant rate.  :func:`write_synthetic` writes them as

``.ulg``
    PX4 ``sensor_combined`` in the layout of a newer PX4 (``layout="new"``:
    ``gyro_integral_dt`` ``uint32_t`` in microseconds, as PX4 1.11 and later) or an older
    one (``layout="old"``: ``float`` in seconds, as PX4 1.6), the IMU filter parameters
    of the newer layout, and ``vehicle_gps_position`` fixes where ``gnss`` is asked;
``.bin``
    ArduPilot DataFlash: ``IMU`` (rates) with ``held="rates"``, ``IMT`` (increments)
    with ``held="increments"``, ``PARM``, ``MSG`` and ``GPS``;
``.bag``
    ROS 1, and a ROS 2 bag folder (any other name without a suffix, or ``.db3`` given as
    the folder's name): ``sensor_msgs/Imu`` rates in ROS's FLU axes (``(x, −y, −z)`` of
    the truth), through ``rosbags``;
``data.csv``
    EuRoC/TUM-VI: nanosecond timestamps, rates and specific force;
``.npz``, ``.csv``
    the package's own formats (increments, or rates with ``held="rates"``).

The ULog and DataFlash files are written by this module with numpy (one
record layout per message, all records at once): ``pyulog``'s writer packs
every field of every message in a Python loop, minutes for an hour at 1 kHz.
The tests read them back with ``pyulog`` and ``pymavlink``, which share no code
with the writer or with the package's reader.  Rates are the increment over
its interval (float32 in the ULog and DataFlash records: the increments come
back to float32 round-off, about 6e-8 relative).  Every file is written
atomically (a temporary name renamed into place).

Public API
----------
.. autosummary::

   SyntheticTruth
   still_truth
   rocking_truth
   write_synthetic
   SYNTHETIC_FORMATS
"""

from __future__ import annotations

import math
import os
import shutil
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.validation import as_array, positive

__all__ = ["SyntheticTruth", "still_truth", "rocking_truth", "write_synthetic", "SYNTHETIC_FORMATS"]

#: What :func:`write_synthetic` writes (its ``format`` argument).
SYNTHETIC_FORMATS = ("ulog", "dataflash", "rosbag1", "rosbag2", "euroc", "npz", "csv")


@dataclass(frozen=True)
class SyntheticTruth:
    """Increments at a constant rate, the truth a synthetic log is written from.

    Attributes
    ----------
    time : ndarray
        ``(N,)`` end of each interval, from the log's start [s] (a whole number of microseconds).
    dtheta : ndarray
        ``(N, 3)`` angle increments, body axes FRD [rad].
    dv : ndarray
        ``(N, 3)`` velocity increments [m/s].
    latitude : float
        Where the log is (GNSS fixes and metadata) [rad].
    description : str
        What it is.
    """

    time: np.ndarray
    dtheta: np.ndarray
    dv: np.ndarray
    latitude: float = math.radians(45.0)
    description: str = "synthetic"

    def __post_init__(self):
        t = as_array(self.time, "time").ravel()
        for name in ("dtheta", "dv"):
            a = as_array(getattr(self, name), name)
            if a.shape != (t.size, 3):
                raise ValueError(f"Expected `{name}` with shape ({t.size}, 3), got shape {a.shape}")
            object.__setattr__(self, name, a)
        object.__setattr__(self, "time", t)

    @property
    def interval(self) -> float:
        """Sample interval [s]."""
        return float(np.median(np.diff(self.time)))

    @property
    def gyro(self) -> np.ndarray:
        """``(N, 3)`` mean angular rate over each interval [rad/s]."""
        return self.dtheta / self.interval

    @property
    def accel(self) -> np.ndarray:
        """``(N, 3)`` mean specific force over each interval [m/s²]."""
        return self.dv / self.interval


def _grid(duration: float, rate: float):
    h_us = round(1e6 / positive(rate, "rate"))
    n = int(positive(duration, "duration") * 1e6 // h_us)
    if n < 2:
        raise ValueError(f"Expected `duration` of at least two samples at `rate` = {rate:g} Hz, got {duration:g} s")
    return h_us * 1e-6, (np.arange(1, n + 1) * h_us) * 1e-6


def still_truth(duration: float = 60.0, rate: float = 100.0, *, latitude: float = math.radians(45.0), heading: float = 0.0, beta: float = 0.0, gamma: float = 0.0) -> SyntheticTruth:
    """A block at rest on the Earth: constant increments of the Earth's rate and of gravity, exactly.

    Parameters
    ----------
    duration : float
        Length [s].
    rate : float
        Sample rate [Hz] (its interval is rounded to a whole microsecond).
    latitude : float, keyword-only
        Latitude φ [rad].
    heading, beta, gamma : float, keyword-only
        Attitude ``C_b^n = R_z(ψ) R_x(−β) R_y(γ)`` [rad].

    Returns
    -------
    SyntheticTruth
    """
    from ..alignment.earth import earth_rate_ned, gravity_ned
    from ..alignment.tilt_attitude import attitude_matrix

    h, t = _grid(duration, rate)
    C = attitude_matrix([heading, beta, gamma])  # body to NED
    w = C.T @ earth_rate_ned(latitude)
    f = C.T @ (-gravity_ned(latitude))
    n = t.size
    return SyntheticTruth(t, np.tile(w * h, (n, 1)), np.tile(f * h, (n, 1)), latitude, f"at rest, heading {math.degrees(heading):g} deg")


def rocking_truth(
    duration: float = 120.0, rate: float = 100.0, *, latitude: float = math.radians(45.0), heading: float = 0.5, amplitude=(0.5, 2.0, 2.0), period: float = 8.0, seed: int = 0
) -> SyntheticTruth:
    """A block rocking sinusoidally about its stable attitude (the package's IMU simulator, ideal sensors).

    Parameters
    ----------
    duration : float
        Length [s].
    rate : float
        Sample rate [Hz].
    latitude : float, keyword-only
        Latitude φ [rad].
    heading : float, keyword-only
        Stable heading ψ0 [rad].
    amplitude : array_like, keyword-only
        Rocking amplitude (yaw, β, γ) [deg].
    period : float, keyword-only
        Rocking period [s].
    seed : int, keyword-only
        Seed of the rocking phases.

    Returns
    -------
    SyntheticTruth
    """
    from ..alignment.base_motion import SineMotion
    from ..alignment.imu import Scenario, simulate_imu

    h, t = _grid(duration, rate)
    sc = Scenario(latitude, heading, 0.0, 0.0, SineMotion(np.radians(np.asarray(amplitude, dtype=float)), period), [0.0, 0.0, 0.0], 1.0 / h, t.size * h)
    rec = simulate_imu(sc, None, n_trials=1, rng=seed)
    n = min(t.size, rec.dtheta.shape[1])
    return SyntheticTruth(t[:n], rec.dtheta[0, :n], rec.dv[0, :n], latitude, f"sine rocking, amplitude {tuple(amplitude)} deg, period {period:g} s")


# --------------------------------------------------------------------------- atomic writes
def _atomic(path: Path, write) -> Path:
    tmp = path.with_name(f".{path.name}.partial")
    if tmp.exists():
        shutil.rmtree(tmp) if tmp.is_dir() else tmp.unlink()
    try:
        write(tmp)
        if path.is_dir():
            shutil.rmtree(path)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp) if tmp.is_dir() else tmp.unlink()
    return path


# --------------------------------------------------------------------------- ULog
def _ulog_record(kind: str, payload: bytes) -> bytes:
    return struct.pack("<HB", len(payload), ord(kind)) + payload


def _ulog_info(key_type: str, name: str, value: bytes) -> bytes:
    key = f"{key_type} {name}".encode()
    return struct.pack("<B", len(key)) + key + value


_SC_NEW = [("timestamp", "uint64_t", "<u8", 0), ("gyro_rad", "float", "<f4", 3), ("gyro_integral_dt", "uint32_t", "<u4", 0),
           ("accelerometer_timestamp_relative", "int32_t", "<i4", 0), ("accelerometer_m_s2", "float", "<f4", 3),
           ("accelerometer_integral_dt", "uint32_t", "<u4", 0), ("accelerometer_clipping", "uint8_t", "u1", 0), ("gyro_clipping", "uint8_t", "u1", 0),
           ("accel_calibration_count", "uint8_t", "u1", 0), ("gyro_calibration_count", "uint8_t", "u1", 0)]  # fmt: skip
_SC_OLD = [("timestamp", "uint64_t", "<u8", 0), ("gyro_rad", "float", "<f4", 3), ("gyro_integral_dt", "float", "<f4", 0),
           ("accelerometer_timestamp_relative", "int32_t", "<i4", 0), ("accelerometer_m_s2", "float", "<f4", 3),
           ("accelerometer_integral_dt", "float", "<f4", 0), ("magnetometer_timestamp_relative", "int32_t", "<i4", 0),
           ("magnetometer_ga", "float", "<f4", 3), ("baro_timestamp_relative", "int32_t", "<i4", 0), ("baro_alt_meter", "float", "<f4", 0),
           ("baro_temp_celcius", "float", "<f4", 0)]  # fmt: skip
_GPS_NEW = [("timestamp", "uint64_t", "<u8", 0), ("latitude_deg", "double", "<f8", 0), ("longitude_deg", "double", "<f8", 0), ("altitude_msl_m", "double", "<f8", 0),
            ("vel_n_m_s", "float", "<f4", 0), ("vel_e_m_s", "float", "<f4", 0), ("vel_d_m_s", "float", "<f4", 0), ("fix_type", "uint8_t", "u1", 0)]  # fmt: skip
_GPS_OLD = [("timestamp", "uint64_t", "<u8", 0), ("lat", "int32_t", "<i4", 0), ("lon", "int32_t", "<i4", 0), ("alt", "int32_t", "<i4", 0),
            ("vel_n_m_s", "float", "<f4", 0), ("vel_e_m_s", "float", "<f4", 0), ("vel_d_m_s", "float", "<f4", 0), ("fix_type", "uint8_t", "u1", 0)]  # fmt: skip


def _format_text(name, fields) -> bytes:
    return (name + ":" + "".join(f"{t}[{n}] {f};" if n else f"{t} {f};" for f, t, _, n in fields)).encode()


def _records(msg_id: int, fields, columns: dict, n: int) -> np.ndarray:
    layout = [("size", "<u2"), ("kind", "u1"), ("msg_id", "<u2")] + [(f, d, (k,)) if k else (f, d) for f, _, d, k in fields]
    rec = np.zeros(n, dtype=np.dtype(layout))
    rec["size"] = rec.dtype.itemsize - 3
    rec["kind"] = ord("D")
    rec["msg_id"] = msg_id
    for name, value in columns.items():
        rec[name] = value
    return rec


def _write_ulog(path: Path, truth: SyntheticTruth, layout: str, gnss: bool, start_us: int = 1_000_000):
    h = truth.interval
    h_us = int(round(h * 1e6))
    stamps = start_us + np.round(truth.time * 1e6).astype(np.int64)
    sc_fields = _SC_NEW if layout == "new" else _SC_OLD
    gps_fields = _GPS_NEW if layout == "new" else _GPS_OLD
    cols = {"timestamp": stamps, "gyro_rad": truth.dtheta / h, "accelerometer_m_s2": truth.dv / h}
    cols["gyro_integral_dt"] = h_us if layout == "new" else h
    cols["accelerometer_integral_dt"] = h_us if layout == "new" else h
    defs = [_ulog_record("B", bytes(16) + struct.pack("<3Q", 0, 0, 0)), _ulog_record("F", _format_text("sensor_combined", sc_fields))]
    if gnss:
        defs.append(_ulog_record("F", _format_text("vehicle_gps_position", gps_fields)))
    defs.append(_ulog_record("I", _ulog_info("char[3]", "sys_name", b"PX4")))
    release = (1 << 24) | (15 << 16) | (0 << 8) | 255 if layout == "new" else (1 << 24) | (6 << 16) | 255
    defs.append(_ulog_record("I", _ulog_info("uint32_t", "ver_sw_release", struct.pack("<I", release))))
    if layout == "new":
        for name, value in (("IMU_GYRO_CUTOFF", 40.0), ("IMU_ACCEL_CUTOFF", 30.0), ("IMU_DGYRO_CUTOFF", 30.0), ("IMU_GYRO_NF0_FRQ", 0.0)):
            defs.append(_ulog_record("P", _ulog_info("float", name, struct.pack("<f", value))))
        defs.append(_ulog_record("P", _ulog_info("int32_t", "IMU_INTEG_RATE", struct.pack("<i", int(round(1.0 / h))))))
    defs.append(_ulog_record("A", struct.pack("<BH", 0, 0) + b"sensor_combined"))
    if gnss:
        defs.append(_ulog_record("A", struct.pack("<BH", 0, 1) + b"vehicle_gps_position"))

    def write(tmp):
        with open(tmp, "wb") as f:
            f.write(b"ULog\x01\x12\x35" + bytes([1]) + struct.pack("<Q", start_us))
            for d in defs:
                f.write(d)
            _records(0, sc_fields, cols, truth.time.size).tofile(f)
            if gnss:
                tg = np.arange(start_us, int(stamps[-1]) + 1, 200_000)
                lat = math.degrees(truth.latitude)
                g = {"timestamp": tg, "fix_type": 3}
                if layout == "new":
                    g.update(latitude_deg=lat, longitude_deg=8.5, altitude_msl_m=450.0)
                else:
                    g.update(lat=int(round(lat * 1e7)), lon=85_000_000, alt=450_000)
                _records(1, gps_fields, g, tg.size).tofile(f)

    _atomic(path, write)


# --------------------------------------------------------------------------- DataFlash
_DF_IMU = ("IMU", "QBffffffIIfBBHH", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz")
_DF_IMT = ("IMT", "QBfffffffff", "TimeUS,I,DelT,DelvT,DelaT,DelAX,DelAY,DelAZ,DelVX,DelVY,DelVZ")
_DF_GPS = ("GPS", "QBBIHBcLLeffffB", "TimeUS,I,Status,GMS,GWk,NSats,HDop,Lat,Lng,Alt,Spd,GCrs,VZ,Yaw,U")
_DF_PARM = ("PARM", "QNff", "TimeUS,Name,Value,Default")
_DF_MSG = ("MSG", "QZ", "TimeUS,Message")


def _df_dtype(fmt: str, labels: str):
    from .dataflash import record_dtype

    dt, _ = record_dtype(fmt, labels.split(","))
    return np.dtype([("h1", "u1"), ("h2", "u1"), ("kind", "u1")] + [(n, dt.fields[n][0]) for n in dt.names])


def _df_records(kind: int, spec, n: int, columns: dict) -> np.ndarray:
    dt = _df_dtype(spec[1], spec[2])
    rec = np.zeros(n, dtype=dt)
    rec["h1"], rec["h2"], rec["kind"] = 0xA3, 0x95, kind
    for k, v in columns.items():
        rec[k] = v
    return rec


def _df_fmt(kind: int, spec) -> bytes:
    name, fmt, labels = spec
    length = _df_dtype(fmt, labels).itemsize
    return bytes([0xA3, 0x95, 128, kind, length]) + name.encode().ljust(4, b"\0") + fmt.encode().ljust(16, b"\0") + labels.encode().ljust(64, b"\0")


def _write_dataflash(path: Path, truth: SyntheticTruth, held: str, gnss: bool, start_us: int = 5_000_000):
    h = truth.interval
    stamps = start_us + np.round(truth.time * 1e6).astype(np.int64)
    fmt_fmt = bytes([0xA3, 0x95, 128, 128, 89]) + b"FMT\0" + b"BBnNZ".ljust(16, b"\0") + b"Type,Length,Name,Format,Columns".ljust(64, b"\0")
    specs = {129: _DF_PARM, 130: _DF_MSG, 131: _DF_IMU if held == "rates" else _DF_IMT}
    if gnss:
        specs[132] = _DF_GPS

    def write(tmp):
        with open(tmp, "wb") as f:
            f.write(fmt_fmt)
            for kind, spec in specs.items():
                f.write(_df_fmt(kind, spec))
            params = [("INS_GYRO_FILTER", 20.0), ("INS_ACCEL_FILTER", 20.0), ("INS_HNTCH_ENABLE", 0.0)]
            _df_records(129, _DF_PARM, len(params), {"TimeUS": start_us, "Name": [p[0].encode() for p in params], "Value": [p[1] for p in params]}).tofile(f)
            _df_records(130, _DF_MSG, 1, {"TimeUS": start_us, "Message": b"ArduCopter V4.5.0 (synthetic)"}).tofile(f)
            if held == "rates":
                cols = {"TimeUS": stamps, "I": 0, "GyrX": truth.gyro[:, 0], "GyrY": truth.gyro[:, 1], "GyrZ": truth.gyro[:, 2],
                        "AccX": truth.accel[:, 0], "AccY": truth.accel[:, 1], "AccZ": truth.accel[:, 2], "GH": 1, "AH": 1}  # fmt: skip
                _df_records(131, _DF_IMU, truth.time.size, cols).tofile(f)
            else:
                cols = {"TimeUS": stamps, "I": 0, "DelT": h, "DelvT": h, "DelaT": h}
                cols.update({f"DelA{a}": truth.dtheta[:, i] for i, a in enumerate("XYZ")})
                cols.update({f"DelV{a}": truth.dv[:, i] for i, a in enumerate("XYZ")})
                _df_records(131, _DF_IMT, truth.time.size, cols).tofile(f)
            if gnss:
                tg = np.arange(start_us, int(stamps[-1]) + 1, 200_000)
                cols = {"TimeUS": tg, "Status": 3, "NSats": 12, "Lat": int(round(math.degrees(truth.latitude) * 1e7)), "Lng": 85_000_000, "Alt": 45000}
                _df_records(132, _DF_GPS, tg.size, cols).tofile(f)

    _atomic(path, write)


# --------------------------------------------------------------------------- ROS bags
def _write_rosbag(path: Path, truth: SyntheticTruth, version: int, topic: str):
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS1_NOETIC if version == 1 else Stores.ROS2_HUMBLE)
    Imu = store.types["sensor_msgs/msg/Imu"]
    Header = store.types["std_msgs/msg/Header"]
    Time = store.types["builtin_interfaces/msg/Time"]
    Vector3 = store.types["geometry_msgs/msg/Vector3"]
    Quaternion = store.types["geometry_msgs/msg/Quaternion"]
    flu = np.array([1.0, -1.0, -1.0])
    w, a = truth.gyro * flu, truth.accel * flu
    ns = np.round(truth.time * 1e9).astype(np.int64) + 1_700_000_000 * 10**9
    cov = np.zeros(9)

    def write(tmp):
        if version == 1:
            from rosbags.rosbag1 import Writer

            writer = Writer(tmp)
            serialize = store.serialize_ros1
        else:
            from rosbags.rosbag2 import Writer

            writer = Writer(tmp, version=8)
            serialize = store.serialize_cdr
        with writer:
            conn = writer.add_connection(topic, Imu.__msgtype__, typestore=store)
            for i in range(truth.time.size):
                stamp = Time(sec=int(ns[i] // 10**9), nanosec=int(ns[i] % 10**9))
                msg = Imu(
                    header=Header(seq=i, stamp=stamp, frame_id="imu_link") if version == 1 else Header(stamp=stamp, frame_id="imu_link"),
                    orientation=Quaternion(x=0.0, y=0.0, z=0.0, w=1.0), orientation_covariance=cov,
                    angular_velocity=Vector3(x=float(w[i, 0]), y=float(w[i, 1]), z=float(w[i, 2])), angular_velocity_covariance=cov,
                    linear_acceleration=Vector3(x=float(a[i, 0]), y=float(a[i, 1]), z=float(a[i, 2])), linear_acceleration_covariance=cov,
                )  # fmt: skip
                writer.write(conn, int(ns[i]), serialize(msg, Imu.__msgtype__))

    _atomic(path, write)


# --------------------------------------------------------------------------- EuRoC, native
def _write_euroc(path: Path, truth: SyntheticTruth):
    ns = np.round(truth.time * 1e9).astype(np.int64) + 1_403_636_579_758_555_392

    def write(tmp):
        with open(tmp, "w", encoding="utf-8", newline="\n") as f:
            f.write("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n")
            body = np.column_stack([truth.gyro, truth.accel])
            for k, row in zip(ns, body):
                f.write(f"{k}," + ",".join(f"{x:.17g}" for x in row) + "\n")

    path.parent.mkdir(parents=True, exist_ok=True)
    _atomic(path, write)


def _write_native(path: Path, truth: SyntheticTruth, held: str):
    from .imu_log import ImuLog
    from .native import write_log

    meta = {"latitude": truth.latitude, "description": truth.description}
    if held == "increments":
        return write_log(path, ImuLog(truth.time, truth.dtheta, truth.dv, meta))
    if path.suffix.lower() == ".npz":

        def write_npz(tmp):
            with open(tmp, "wb") as f:
                np.savez(f, time=truth.time, gyro=truth.gyro, accel=truth.accel, latitude=np.array(truth.latitude))

        return _atomic(path, write_npz)

    def write(tmp):
        with open(tmp, "w", encoding="utf-8", newline="\n") as f:
            f.write(f"# latitude: {truth.latitude!r}\ntime,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n")
            np.savetxt(f, np.column_stack([truth.time, truth.gyro, truth.accel]), delimiter=",", fmt="%.17g")

    return _atomic(path, write)


def write_synthetic(path, truth: SyntheticTruth, *, format: str | None = None, held: str = "increments", layout: str = "new", gnss: bool = False, topic: str = "/imu") -> Path:
    """Write ``truth`` as a log of ``format``.

    Parameters
    ----------
    path : str or Path
        The file (a folder for a ROS 2 bag).
    truth : SyntheticTruth
        The increments.
    format : str, optional, keyword-only
        From :data:`SYNTHETIC_FORMATS` (default: by suffix: ``.ulg``, ``.bin``, ``.bag``,
        ``data.csv`` for EuRoC, ``.npz``, ``.csv``; a name without suffix is a ROS 2 bag).
    held : str, keyword-only
        ``"increments"`` or ``"rates"``: what the native and DataFlash files hold
        (ULog ``sensor_combined`` holds both, EuRoC and ROS rates).
    layout : str, keyword-only
        ULog: ``"new"`` (PX4 1.11 and later) or ``"old"`` (PX4 1.6).
    gnss : bool, keyword-only
        ULog and DataFlash: add GNSS fixes at ``truth.latitude`` (5 Hz).
    topic : str, keyword-only
        ROS: the IMU topic.

    Returns
    -------
    Path

    Raises
    ------
    ValueError
        An unknown format, layout or ``held``.
    """
    p = Path(path)
    if held not in ("increments", "rates"):
        raise ValueError(f"Expected `held` in ('increments', 'rates'), got {held!r}")
    if layout not in ("new", "old"):
        raise ValueError(f"Expected `layout` in ('new', 'old'), got {layout!r}")
    if format is None:
        suffix = p.suffix.lower()
        format = {".ulg": "ulog", ".bin": "dataflash", ".bag": "rosbag1", ".npz": "npz", "": "rosbag2", ".db3": "rosbag2"}.get(suffix)
        if suffix == ".csv":
            format = "euroc" if p.name == "data.csv" else "csv"
    if format not in SYNTHETIC_FORMATS:
        raise ValueError(f"Expected `format` in {SYNTHETIC_FORMATS} (or a path whose suffix names one), got {format!r} for {p.name}")
    if format == "ulog":
        _write_ulog(p, truth, layout, gnss)
    elif format == "dataflash":
        _write_dataflash(p, truth, held, gnss)
    elif format in ("rosbag1", "rosbag2"):
        _write_rosbag(p, truth, 1 if format == "rosbag1" else 2, topic)
    elif format == "euroc":
        _write_euroc(p, truth)
    else:
        _write_native(p, truth, held)
    return p
