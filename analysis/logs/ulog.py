"""PX4 ULog logs (``.ulg``): the IMU streams, their time base, the filters in front of them.

The definitions (formats, parameters, version) are parsed by ``pyulog``; the
data section is walked by :mod:`~strapdown.analysis.logs.framing` in chunks
(pyulog's reader loops in Python over every message, tens of seconds for an
hour at 1 kHz) and the fields are read with the numpy layout of the formats.

Streams read
------------
``sensor_combined``
    The voted IMU: ``gyro_rad`` and ``accelerometer_m_s2`` are the delta angle and delta
    velocity that PX4 integrated, divided by their integration intervals
    ``gyro_integral_dt`` and ``accelerometer_integral_dt``
    (``src/modules/sensors/voted_sensors_update``: ``gyro_rate = delta_angle * dt_inv``).
    The increments are rate × interval again.  The interval is a ``float`` in seconds in
    older logs (PX4 before 1.11, e.g. pyulog's ``sample.ulg``) and a ``uint32_t`` in
    microseconds in newer ones: the field's type tells them apart, and the median interval
    is checked against the timestamps.
``vehicle_imu`` (one per instance, ``vehicle_imu/1`` ...)
    ``delta_angle``, ``delta_velocity`` with ``delta_angle_dt``, ``delta_velocity_dt`` [µs]:
    increments as PX4 integrated them (``src/modules/sensors/vehicle_imu/VehicleIMU.cpp``);
    usually logged far below the rate it is published at.

Both are in PX4's body frame, FRD (x forward, y right, z down), the package's own axes.
The timestamps are microseconds of the autopilot's clock, from the ULog header's start.

Filters
-------
The integrated increments are built from the raw, calibrated sensor samples:
``VehicleIMU`` integrates ``sensor_gyro`` and ``sensor_accel`` as published (no software
filter, coning-corrected), and in PX4 1.10 ``PX4Gyroscope::update`` fed the integrator the
calibrated value before its notch and low-pass filters (``val_calibrated``), which went to
``sensor_gyro`` for the controllers.  The control-loop filters ``IMU_GYRO_CUTOFF``,
``IMU_GYRO_NF0_FRQ``/``NF1``, ``IMU_DGYRO_CUTOFF``, the dynamic notches and
``IMU_ACCEL_CUTOFF`` act on ``vehicle_angular_velocity`` / ``vehicle_acceleration``
(``VehicleAngularVelocity.cpp``, ``VehicleAcceleration.cpp``), not on ``sensor_combined``.
The sensor chip's own digital low-pass (set by its driver, not a parameter in the log) is in
front of every sample.

Public API
----------
.. autosummary::

   read_ulog
   PX4_FILTERS
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .framing import gather, walk_ulog
from .inventory import GnssTrack, SensorFilter, StreamInfo
from .streams import LogContents, StreamSamples, choose_topic

__all__ = ["read_ulog", "PX4_FILTERS"]

_HEADER = b"\x55\x4c\x6f\x67\x01\x12\x35"
_CHUNK = 1 << 26  # 64 MiB of the file at a time
_NUMPY = {
    "int8_t": "i1", "uint8_t": "u1", "int16_t": "<i2", "uint16_t": "<u2", "int32_t": "<i4", "uint32_t": "<u4",
    "int64_t": "<i8", "uint64_t": "<u8", "float": "<f4", "double": "<f8", "bool": "i1", "char": "i1",
}  # fmt: skip

_VEHICLE_IMU = "src/modules/sensors/vehicle_imu/VehicleIMU.cpp (UpdateGyro/UpdateAccel integrate sensor_gyro/sensor_accel as published)"
_CONTROL = "src/modules/sensors/vehicle_angular_velocity/VehicleAngularVelocity.cpp (the control path, vehicle_angular_velocity)"
_PX4GYRO = "PX4 1.10 src/lib/drivers/gyroscope/PX4Gyroscope.cpp (integrator fed val_calibrated, before the notch and low-pass)"

#: The PX4 filter parameters and whether they act on the integrated increments (``sensor_combined``, ``vehicle_imu``).
PX4_FILTERS = {
    "IMU_GYRO_CUTOFF": (False, f"low-pass of the control loop's body rate: {_CONTROL}; {_PX4GYRO}; the increments come from {_VEHICLE_IMU}"),
    "IMU_GYRO_NF0_FRQ": (False, f"static notch of the control loop's body rate: {_CONTROL}"),
    "IMU_GYRO_NF1_FRQ": (False, f"static notch of the control loop's body rate: {_CONTROL}"),
    "IMU_GYRO_NF_FREQ": (False, f"notch of the controllers' gyro (PX4 1.10-1.11): {_PX4GYRO}"),
    "IMU_DGYRO_CUTOFF": (False, f"low-pass of the body-rate derivative (D term): {_CONTROL}"),
    "IMU_GYRO_DNF_EN": (False, f"dynamic (ESC/FFT) notches of the control loop: {_CONTROL}"),
    "IMU_GYRO_FFT_EN": (False, "FFT peak detection feeding the control loop's dynamic notches (src/modules/gyro_fft)"),
    "IMU_ACCEL_CUTOFF": (False, "low-pass of vehicle_acceleration: src/modules/sensors/vehicle_acceleration/VehicleAcceleration.cpp; the increments come from " + _VEHICLE_IMU),
    "IMU_INTEG_RATE": (True, "rate of the integrated increments (their interval is 1/IMU_INTEG_RATE): " + _VEHICLE_IMU),
}

_READABLE = {"sensor_combined": "increments", "vehicle_imu": "increments"}
_NOT_READ = {
    "sensor_gyro": "one gyro's calibrated rates (the accelerometer is another topic, sampled at other times): not read as a stream",
    "sensor_accel": "one accelerometer's specific force (the gyro is another topic): not read as a stream",
    "sensor_gyro_fifo": "raw FIFO samples of one gyro (counts × scale), without the accelerometer: not read as a stream",
    "sensor_accel_fifo": "raw FIFO samples of one accelerometer, without the gyro: not read as a stream",
    "vehicle_angular_velocity": "the control loop's body rate, after IMU_GYRO_CUTOFF and the notches: not read",
    "vehicle_acceleration": "the control loop's acceleration, after IMU_ACCEL_CUTOFF: not read",
}
_GNSS = ("vehicle_gps_position", "sensor_gps")


def _flatten(formats, name, prefix=""):
    fields = []
    for type_name, size, field_name in formats[name].fields:
        if type_name in _NUMPY:
            if size > 0:
                fields += [(f"{prefix}{field_name}[{i}]", type_name) for i in range(size)]
            else:
                fields.append((prefix + field_name, type_name))
        else:
            for i in range(max(size, 1)):
                sub = f"{prefix}{field_name}[{i}]." if size > 0 else f"{prefix}{field_name}."
                fields += _flatten(formats, type_name, sub)
    return fields


def _dtype(formats, name):
    fields = _flatten(formats, name)
    while fields and fields[-1][0].startswith("_padding"):
        fields.pop()
    return np.dtype([(n, _NUMPY[t]) for n, t in fields]), dict(fields)


def _data_ranges(path: Path, size: int):
    """Byte ranges of the data: one, or several where data was appended (flag-bits message)."""
    with open(path, "rb") as f:
        f.seek(16)
        head = f.read(3 + 40)
    if len(head) >= 43 and head[2] == ord("B"):
        offsets = [int.from_bytes(head[19 + 8 * i : 27 + 8 * i], "little") for i in range(3)]
        offsets = sorted(o for o in offsets if 16 < o < size)
        edges = [16] + offsets + [size]
        return [(a, b) for a, b in zip(edges[:-1], edges[1:]) if b > a]
    return [(16, size)]


def _walk(path: Path, ranges, on_chunk, progress, desc):
    """Walk every record of ``ranges``, a chunk of the file at a time; call ``on_chunk(buf, offsets, sizes, kinds)``.

    Returns the notes: a corrupt record (the walk stops in that range), a truncated last record.
    """
    from ..core.progress import bar

    notes = []
    total = sum(b - a for a, b in ranges)
    capacity = 1 << 20
    with open(path, "rb") as f, bar(desc=desc, total=total, enabled=progress, unit="B") as pbar:
        for lo, hi in ranges:
            pos = lo
            while pos < hi:
                f.seek(pos)
                buf = np.frombuffer(f.read(min(_CHUNK, hi - pos)), dtype=np.uint8)
                at = 0
                while True:
                    off, sz, kd, nxt, bad = walk_ulog(buf, at, capacity=capacity)
                    if off.size:
                        on_chunk(buf, off, sz, kd)
                    if bad >= 0 or off.size < capacity or nxt >= buf.size:
                        break
                    at = nxt
                if bad >= 0:
                    notes.append(f"corrupt record at byte {pos + bad} (size 0 or an unknown type): the {hi - pos - bad} bytes after it were not read")
                    pbar.update(hi - pos)
                    break
                if pos + buf.size >= hi:
                    if nxt < buf.size:
                        notes.append(f"the last {buf.size - nxt} bytes hold an incomplete record (a truncated log): not read")
                    pbar.update(buf.size)
                    break
                if nxt == 0:
                    notes.append(f"a record at byte {pos} is longer than the reading chunk: the rest was not read")
                    break
                pbar.update(nxt)
                pos += nxt
    return notes


def _ulog_definitions(path: Path):
    from pyulog import ULog
    from pyulog.core import ULogException

    try:
        with open(path, "rb") as f:
            head = f.read(16)
    except IsADirectoryError:
        raise
    if len(head) < 16 or head[:7] != _HEADER:
        raise ValueError(f"Expected a ULog file (a header starting with 'ULog'), got {head[:7]!r} at the start of {path.name}")
    try:
        u = ULog(str(path), parse_header_only=True)
    except ULogException as e:
        raise ValueError(f"Expected a readable ULog file in {path.name}, got: {e}") from None
    return u


def _software(u) -> str:
    info = u.msg_info_dict
    parts = [str(info.get("sys_name", "PX4"))]
    release = info.get("ver_sw_release")
    if isinstance(release, int) and release:
        parts.append(f"{(release >> 24) & 0xFF}.{(release >> 16) & 0xFF}.{(release >> 8) & 0xFF}")
    if info.get("ver_sw"):
        parts.append(f"git {str(info['ver_sw'])[:10]}")
    return " ".join(parts)


def read_ulog(path, *, topic: str | None = None, guard=None, progress: bool = False) -> LogContents:
    """Read a PX4 ULog: every stream's inventory, the chosen IMU stream's samples, the filters, GNSS.

    Parameters
    ----------
    path : str or Path
        The ``.ulg`` file.
    topic : str, optional, keyword-only
        ``"sensor_combined"``, ``"vehicle_imu"``, ``"vehicle_imu/1"`` ... (default: the readable
        stream of highest rate that covers the log).
    guard : callable, optional, keyword-only
        ``guard(samples, topic)`` called before the samples are read (the work estimate).
    progress : bool, keyword-only
        Progress on stderr.

    Returns
    -------
    LogContents

    Raises
    ------
    ValueError
        Not a ULog, no IMU stream, an unknown ``topic``.

    References
    ----------
    PX4 documentation, "ULog File Format"; PX4-Autopilot ``msg/SensorCombined.msg``,
    ``msg/VehicleImu.msg`` and the sources named in the module docstring.
    """
    p = Path(path)
    size = p.stat().st_size
    u = _ulog_definitions(p)
    formats = u.message_formats
    start_us = int(u.start_timestamp)
    ranges = _data_ranges(p, size)

    subs, counts, first, last = {}, {}, {}, {}
    state = {"dropouts": 0, "bad_size": 0}
    layouts = {}

    def layout(name):
        if name not in layouts:
            layouts[name] = _dtype(formats, name) if name in formats else (None, {})
        return layouts[name]

    def scan(buf, off, sz, kd):
        for i in np.flatnonzero(kd == ord("A")):
            o = off[i]
            multi, msg_id = int(buf[o + 3]), int(buf[o + 4]) | (int(buf[o + 5]) << 8)
            name = bytes(buf[o + 6 : o + 3 + sz[i]]).decode("utf-8", "replace")
            subs[msg_id] = (name, multi)
        drops = off[kd == ord("O")]
        if drops.size:
            state["dropouts"] += int(np.sum(buf[drops + 3].astype(np.int64) | (buf[drops + 4].astype(np.int64) << 8)))
        d = kd == ord("D")
        if not np.any(d):
            return
        o, s = off[d], sz[d]
        ids = buf[o + 3].astype(np.int64) | (buf[o + 4].astype(np.int64) << 8)
        for msg_id in np.unique(ids):
            sel = ids == msg_id
            name = subs.get(int(msg_id), (None, 0))[0]
            dt, fields = layout(name) if name else (None, {})
            if dt is None or "timestamp" not in dt.names:
                counts[int(msg_id)] = counts.get(int(msg_id), 0) + int(np.count_nonzero(sel))
                continue
            oo = o[sel][s[sel] - 2 >= dt.itemsize]
            state["bad_size"] += int(np.count_nonzero(sel)) - oo.size
            if not oo.size:
                continue
            t_off = dt.fields["timestamp"][1]
            ts = gather(buf, oo[[0, -1]] + 5 + t_off, 8).view("<u8").ravel()
            counts[int(msg_id)] = counts.get(int(msg_id), 0) + oo.size
            first.setdefault(int(msg_id), int(ts[0]))
            last[int(msg_id)] = int(ts[1])

    notes = _walk(p, ranges, scan, progress, f"scanning {p.name}")
    if state["bad_size"]:
        notes.append(f"{state['bad_size']} data records shorter than their format were skipped")
    t_end = max(last.values(), default=start_us)
    duration = max(0.0, (t_end - start_us) * 1e-6)

    streams = []
    by_topic = {}
    for msg_id, (name, multi) in sorted(subs.items(), key=lambda kv: (kv[1][0], kv[1][1])):
        n = counts.get(msg_id, 0)
        if n == 0:
            continue
        t0 = (first.get(msg_id, start_us) - start_us) * 1e-6
        t1 = (last.get(msg_id, start_us) - start_us) * 1e-6
        rate = (n - 1) / (t1 - t0) if n > 1 and t1 > t0 else 0.0
        name_t = name if multi == 0 else f"{name}/{multi}"
        if name in _READABLE:
            info = StreamInfo(name_t, n, rate, t0, t1, _READABLE[name], True, "increments integrated by PX4 (see strapdown.analysis.logs.ulog)")
        elif name in _NOT_READ:
            info = StreamInfo(name_t, n, rate, t0, t1, "rates", False, _NOT_READ[name])
        elif name in _GNSS:
            info = StreamInfo(name_t, n, rate, t0, t1, "other", False, "GNSS fixes: the latitude check and the aided alignment use them")
        else:
            info = StreamInfo(name_t, n, rate, t0, t1, "other", False, "")
        streams.append(info)
        by_topic[name_t] = (msg_id, name)
    chosen = choose_topic(streams, topic, duration, p.name)
    msg_id, name = by_topic[chosen.topic]
    if guard is not None:
        guard(chosen.samples, chosen.topic)
    gnss_ids = [(by_topic[s.topic][0], by_topic[s.topic][1], s.topic) for s in streams if by_topic[s.topic][1] in _GNSS and "/" not in s.topic]

    dt, fields = layout(name)
    if name == "sensor_combined":
        cols = ["timestamp"] + [f"gyro_rad[{i}]" for i in range(3)] + [f"accelerometer_m_s2[{i}]" for i in range(3)] + ["gyro_integral_dt", "accelerometer_integral_dt"]
    else:
        cols = ["timestamp_sample" if "timestamp_sample" in dt.names else "timestamp"] + [f"delta_angle[{i}]" for i in range(3)]
        cols += [f"delta_velocity[{i}]" for i in range(3)] + ["delta_angle_dt", "delta_velocity_dt"]
    missing = [c for c in cols if c not in dt.names]
    if missing:
        raise ValueError(f"Expected the fields {missing} in {name} of {p.name}, got a format without them")
    out = np.empty((chosen.samples, len(cols)), dtype=np.float64)
    stamps = np.empty(chosen.samples, dtype=np.uint64)
    gnss_rows = {g[0]: [] for g in gnss_ids}
    filled = [0]

    def take(buf, off, sz, kd):
        d = kd == ord("D")
        if not np.any(d):
            return
        o, s = off[d], sz[d]
        ids = buf[o + 3].astype(np.int64) | (buf[o + 4].astype(np.int64) << 8)
        sel = (ids == msg_id) & (s - 2 >= dt.itemsize)
        if np.any(sel):
            rec = gather(buf, o[sel] + 5, dt.itemsize).view(dt).ravel()
            k = filled[0]
            m = min(rec.size, chosen.samples - k)
            stamps[k : k + m] = rec[cols[0]][:m]
            for j, c in enumerate(cols[1:], start=1):
                out[k : k + m, j] = rec[c][:m]
            filled[0] = k + m
        for gid, gname, _ in gnss_ids:
            gdt = layout(gname)[0]
            gsel = (ids == gid) & (s - 2 >= gdt.itemsize)
            if np.any(gsel):
                gnss_rows[gid].append(gather(buf, o[gsel] + 5, gdt.itemsize).view(gdt).ravel())

    notes += [n for n in _walk(p, ranges, take, progress, f"reading {chosen.topic}") if n not in notes]
    n = filled[0]
    time = (stamps[:n].astype(np.int64) - start_us) * 1e-6
    out = out[:n]
    integration_unit = ""
    if name == "sensor_combined":
        kind = fields["gyro_integral_dt"]
        scale = 1e-6 if kind != "float" else 1.0
        integration_unit = "us" if scale == 1e-6 else "s"
        dtg, dta = out[:, 7] * scale, out[:, 8] * scale
        step = float(np.median(np.diff(time))) if n > 1 else 0.0
        med = float(np.median(dtg)) if n else 0.0
        if step > 0 and med > 0 and not 0.2 < med / step < 5.0:
            other = 1e6 if scale == 1.0 else 1e-6
            if 0.2 < med * other / step < 5.0:  # the field's type and its values disagree: the values decide
                notes.append(f"gyro_integral_dt is a {kind} but its values are in {'microseconds' if scale == 1.0 else 'seconds'} (median {med * other:.6g} s against {step:.6g} s between timestamps)")
                dtg, dta, scale = dtg * other, dta * other, scale * other
                integration_unit = "us" if integration_unit == "s" else "s"
        gyro = out[:, 1:4] * dtg[:, None]
        accel = out[:, 4:7] * dta[:, None]
        conversion = (
            f"gyro_rad × gyro_integral_dt and accelerometer_m_s2 × accelerometer_integral_dt: the increments PX4 integrated, "
            f"which sensor_combined stores divided by their interval (integral_dt in {'microseconds, uint32' if integration_unit == 'us' else 'seconds, float'})"
        )
        units = f"rad/s and m/s² times the integration interval [{integration_unit}] → rad and m/s"
        integration = dtg
    else:
        gyro, accel = out[:, 1:4], out[:, 4:7]
        integration = out[:, 7] * 1e-6
        integration_unit = "us"
        conversion = "delta_angle and delta_velocity as PX4 integrated them (vehicle_imu), with delta_angle_dt [us]"
        units = "rad and m/s (SI in the log)"
    samples = StreamSamples(chosen.topic, time, gyro, accel, "increments", conversion, units, "FRD body frame (x forward, y right, z down), PX4's own: no conversion", integration, integration_unit)

    gnss = None
    for gid, _, gtopic in gnss_ids:
        rows = np.concatenate(gnss_rows[gid]) if gnss_rows[gid] else None
        if rows is None or rows.size == 0:
            continue
        gnames = rows.dtype.names
        ok = rows["fix_type"] >= 3 if "fix_type" in gnames else np.ones(rows.size, bool)
        if "latitude_deg" in gnames:
            lat, lon, alt = rows["latitude_deg"], rows["longitude_deg"], rows["altitude_msl_m"]
        elif "lat" in gnames:
            lat, lon, alt = rows["lat"] * 1e-7, rows["lon"] * 1e-7, rows["alt"] * 1e-3
        else:
            continue
        ok &= np.isfinite(lat) & (np.abs(lat) > 0) & (np.abs(lat) <= 90)
        if not np.any(ok):
            continue
        vel = None
        if all(k in gnames for k in ("vel_n_m_s", "vel_e_m_s", "vel_d_m_s")):
            vel = np.stack([rows["vel_n_m_s"], rows["vel_e_m_s"], rows["vel_d_m_s"]], axis=-1)[ok].astype(float)
        tg = (rows["timestamp"][ok].astype(np.int64) - start_us) * 1e-6
        gnss = GnssTrack(gtopic, tg, np.radians(lat[ok].astype(float)), np.radians(lon[ok].astype(float)), alt[ok].astype(float), vel)
        break

    params = u.initial_parameters
    filters = []
    for pname, (acts, evidence) in PX4_FILTERS.items():
        if pname in params:
            v = params[pname]
            filters.append(SensorFilter(pname, float(v), acts, evidence))
    filters.append(
        SensorFilter(
            "sensor digital low-pass (driver)", None, True,
            "the IMU chip's own anti-alias / digital low-pass, configured by its driver (src/drivers/imu/...): in front of every sample; its cutoff is not a parameter in the log",
        )
    )  # fmt: skip
    if not any(f.parameter.startswith("IMU_") for f in filters):
        notes.append("the log holds no IMU_* filter parameters (a PX4 older than 1.9): the integrated increments of the drivers of that time were unfiltered too, but this log cannot say")
    if state["dropouts"]:
        notes.append(f"the logger reports {state['dropouts']} ms of dropped data (ULog dropout messages)")
    return LogContents(
        "ulog", tuple(streams), samples, tuple(filters), _software(u), start_us * 1e-6, duration, gnss, {}, tuple(notes), state["dropouts"] * 1e-3,
    )  # fmt: skip

