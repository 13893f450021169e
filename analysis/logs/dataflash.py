"""ArduPilot DataFlash logs (``.bin``): the IMU streams, the batch sampler, the filters in front of them.

The field types of the format messages are decoded with ``pymavlink``'s table
(``pymavlink.DFReader.FORMAT_TO_STRUCT``: type letters, scalings of the
``c``/``e``/``L`` fields); the records are walked by
:mod:`~strapdown.analysis.logs.framing` and read with numpy.

Streams read
------------
``IMU[k]`` (also ``IMU2``, ``IMU3`` of older logs)
    ``GyrX..Z`` [rad/s] and ``AccX..Z`` [m/s²] at the main loop's logging rate: the
    *filtered* values (``AP_InertialSensor::Write_IMU_instance`` logs ``get_gyro()``,
    ``get_accel()``, which are ``_gyro_filtered``/``_accel_filtered``: the low-pass
    ``INS_GYRO_FILTER``/``INS_ACCEL_FILTER`` and the notches act on them,
    ``AP_InertialSensor_Backend.cpp``).  Turned into increments as rate × interval.
``IMT[k]`` (where logged, older logs)
    ``DelAX..Z`` [rad], ``DelVX..Z`` [m/s] over ``DelaT``/``DelvT`` [s]: the delta
    angles and velocities of the EKF, integrated from the raw samples with a coning
    correction before the filters (``_delta_angle_acc += delta_angle + delta_coning``).

Not read as streams: the batch sampler (``ISBH``/``ISBD``: bursts of
``INS_LOG_BAT_CNT`` raw samples of *one* sensor at a time, gyro and accelerometer in
turn, as int16 × ``mul``; pre-filter unless ``INS_LOG_BAT_OPT`` bit 1 asks for
post-filter samples), ``GYR``/``ACC`` (one sensor each, at its own sample times).  The
inventory lists them with their rate.

ArduPilot's body frame is FRD (x forward, y right, z down), the package's own axes;
``TimeUS`` is microseconds since boot.

Public API
----------
.. autosummary::

   read_dataflash
   record_dtype
   ARDUPILOT_FILTERS
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .framing import gather, walk_dataflash
from .inventory import GnssTrack, SensorFilter, StreamInfo
from .streams import LogContents, StreamSamples, choose_topic

__all__ = ["read_dataflash", "record_dtype", "ARDUPILOT_FILTERS"]

_CHUNK = 1 << 26
_STRUCT_TO_NUMPY = {"b": "i1", "B": "u1", "h": "<i2", "H": "<u2", "i": "<i4", "I": "<u4", "q": "<i8", "Q": "<u8", "f": "<f4", "d": "<f8", "e": "<f2"}

_FILTERED = "AP_InertialSensor::Write_IMU_instance logs get_gyro()/get_accel(), the filtered values (AP_InertialSensor_Backend.cpp, _notify_new_gyro_raw_sample)"
_DELTA = "the delta-angle accumulator integrates the raw sample with a coning correction before the filters (AP_InertialSensor_Backend.cpp, _delta_angle_acc)"

#: ArduPilot filter parameters: (acts on the IMU message, acts on the IMT increments, evidence).
ARDUPILOT_FILTERS = {
    "INS_GYRO_FILTER": (True, False, f"gyro low-pass [Hz]: {_FILTERED}; {_DELTA}"),
    "INS_ACCEL_FILTER": (True, False, f"accelerometer low-pass [Hz]: {_FILTERED}; the velocity accumulator integrates the raw sample"),
    "INS_NOTCH_ENABLE": (True, False, f"static gyro notch: {_FILTERED}"),
    "INS_HNTCH_ENABLE": (True, False, f"harmonic notch of the gyros: {_FILTERED}"),
    "INS_HNTCH_FREQ": (True, False, f"harmonic notch centre [Hz]: {_FILTERED}"),
    "INS_HNTC2_ENABLE": (True, False, f"second harmonic notch: {_FILTERED}"),
    "INS_LOG_BAT_OPT": (None, None, "batch sampler options: bit 1 logs post-filter samples in ISBD (AP_InertialSensor_Backend.cpp, log_gyro_raw)"),
}


def record_dtype(fmt: str, labels):
    """The numpy layout of a DataFlash message's fields (after its three header bytes).

    Parameters
    ----------
    fmt : str
        The format letters of its FMT record (``"QBffffff"``).
    labels : sequence of str
        The field names.

    Returns
    -------
    dtype : numpy.dtype
        Packed, little-endian; ``a`` fields are ``int16[32]``, strings are bytes.
    scales : dict
        Field → factor of the scaled letters (``c``, ``C``, ``e``, ``E``: 0.01; ``L``: 1e-7).

    Raises
    ------
    KeyError
        An unknown format letter.
    """
    from pymavlink.DFReader import FORMAT_TO_STRUCT

    fields, scales = [], {}
    for ch, name in zip(fmt, labels):
        if ch == "a":
            fields.append((name, "<i2", (32,)))
            continue
        code, mul, _ = FORMAT_TO_STRUCT[ch]
        if code.endswith("s"):
            fields.append((name, f"S{int(code[:-1])}"))
        else:
            fields.append((name, _STRUCT_TO_NUMPY[code]))
        if mul is not None:
            scales[name] = mul
    return np.dtype(fields), scales


class _Formats:
    def __init__(self):
        self.lengths = np.zeros(256, dtype=np.int64)
        self.lengths[128] = 89
        self.names, self.dtypes, self.scales = {}, {}, {}

    def add(self, rec: bytes):
        kind, length = rec[3], rec[4]
        name = rec[5:9].rstrip(b"\0").decode("ascii", "replace")
        fmt = rec[9:25].rstrip(b"\0").decode("ascii", "replace")
        labels = rec[25:89].rstrip(b"\0").decode("ascii", "replace").split(",")
        if kind == 128:
            return
        try:
            dt, sc = record_dtype(fmt, labels)
        except KeyError:
            return
        if dt.itemsize + 3 != length:
            return
        self.lengths[kind] = length
        self.names[kind], self.dtypes[kind], self.scales[kind] = name, dt, sc


def _walk(path: Path, formats: _Formats, on_chunk, progress, desc):
    from ..core.progress import bar

    notes = []
    size = path.stat().st_size
    skipped = 0
    with open(path, "rb") as f, bar(desc=desc, total=size, enabled=progress, unit="B") as pbar:
        pos = 0
        while pos < size:
            f.seek(pos)
            buf = np.frombuffer(f.read(min(_CHUNK, size - pos)), dtype=np.uint8)
            at = 0
            while True:
                off, kd, nxt, sk = walk_dataflash(buf, at, formats.lengths)
                skipped += sk
                if off.size:
                    last = off[-1]
                    if kd[-1] == 128:
                        formats.add(bytes(buf[last : last + 89]))
                    on_chunk(buf, off, kd)
                if nxt >= buf.size or nxt == at or (off.size == 0):
                    break
                if kd.size and kd[-1] != 128 and off.size < (1 << 20):
                    break
                at = nxt
            if pos + buf.size >= size:
                if nxt < buf.size - 3:
                    notes.append(f"the last {buf.size - nxt} bytes hold an incomplete record (a truncated log): not read")
                pbar.update(buf.size)
                break
            if nxt == 0:
                break
            pbar.update(nxt)
            pos += nxt
    if skipped:
        notes.append(f"{skipped} bytes between records were skipped (no record header, or a type without a format)")
    return notes


def read_dataflash(path, *, topic: str | None = None, guard=None, progress: bool = False) -> LogContents:
    """Read an ArduPilot DataFlash log: the inventory, the chosen IMU stream's samples, the filters, GNSS.

    Parameters
    ----------
    path : str or Path
        The ``.bin`` file.
    topic : str, optional, keyword-only
        ``"IMU[0]"``, ``"IMT[1]"`` ... (default: the readable stream of highest rate that covers the log).
    guard : callable, optional, keyword-only
        ``guard(samples, topic)`` called before the samples are read.
    progress : bool, keyword-only
        Progress on stderr.

    Returns
    -------
    LogContents

    Raises
    ------
    ValueError
        Not a DataFlash log, no IMU stream, an unknown ``topic``.

    References
    ----------
    ArduPilot ``libraries/AP_Logger/LogStructure.h``, ``libraries/AP_InertialSensor/LogStructure.h``,
    ``AP_InertialSensor_Logging.cpp``, ``AP_InertialSensor_Backend.cpp``.
    """
    p = Path(path)
    with open(p, "rb") as f:
        head = f.read(3)
    if len(head) < 3 or head[0] != 0xA3 or head[1] != 0x95:
        raise ValueError(f"Expected a DataFlash log (records opening with bytes A3 95), got {head.hex(' ') or 'an empty file'} at the start of {p.name}")
    fm = _Formats()
    counts, first, last = {}, {}, {}
    params, messages = {}, []

    def key_of(kind, rec_inst):
        name = fm.names.get(kind)
        if name is None:
            return None
        base, inst = name, 0
        if name[-1:].isdigit() and name[:-1] in ("IMU", "IMT", "GPS"):
            base, inst = name[:-1], int(name[-1]) - 1
        return base, inst

    def inst_column(kind, rows):
        names = fm.dtypes[kind].names
        for c in ("I", "Instance"):
            if c in names:
                return rows[c].astype(int)
        return None

    def scan(buf, off, kd):
        for kind in np.unique(kd):
            kind = int(kind)
            if kind == 128 or kind not in fm.dtypes:
                continue
            dt = fm.dtypes[kind]
            o = off[kd == kind] + 3
            name = fm.names[kind]
            if name in ("PARM", "MSG"):
                rows = gather(buf, o, dt.itemsize).view(dt).ravel()
                if name == "PARM":
                    for n, v in zip(rows["Name"], rows["Value"]):
                        params.setdefault(n.rstrip(b"\0").decode("ascii", "replace"), float(v))
                else:
                    messages.extend(m.rstrip(b"\0").decode("ascii", "replace") for m in rows["Message"][:20])
                continue
            if "TimeUS" not in dt.names:
                continue
            small = np.dtype({"names": [n for n in dt.names if n in ("TimeUS", "I", "Instance")], "formats": [dt.fields[n][0] for n in dt.names if n in ("TimeUS", "I", "Instance")],
                              "offsets": [dt.fields[n][1] for n in dt.names if n in ("TimeUS", "I", "Instance")], "itemsize": dt.itemsize})  # fmt: skip
            rows = gather(buf, o, dt.itemsize).view(small).ravel()
            inst = inst_column(kind, rows)
            base, i0 = key_of(kind, None)
            groups = [(i0, np.ones(rows.size, bool))] if inst is None else [(int(i), inst == i) for i in np.unique(inst)]
            for i, sel in groups:
                k = (kind, i)
                ts = rows["TimeUS"][sel]
                counts[k] = counts.get(k, 0) + ts.size
                first.setdefault(k, int(ts[0]))
                last[k] = int(ts[-1])

    notes = _walk(p, fm, scan, progress, f"scanning {p.name}")
    if not counts:
        raise ValueError(f"Expected timed records in the DataFlash log {p.name}, found none")
    t_start = min(first.values())
    duration = (max(last.values()) - t_start) * 1e-6
    streams, by_topic = [], {}
    for (kind, i), n in sorted(counts.items(), key=lambda kv: (fm.names[kv[0][0]], kv[0][1])):
        base, _ = key_of(kind, None)
        t0, t1 = (first[(kind, i)] - t_start) * 1e-6, (last[(kind, i)] - t_start) * 1e-6
        rate = (n - 1) / (t1 - t0) if n > 1 and t1 > t0 else 0.0
        name = f"{base}[{i}]"
        if base == "IMU":
            info = StreamInfo(name, n, rate, t0, t1, "rates", True, "filtered rates and specific force at the logging rate (INS_GYRO_FILTER, INS_ACCEL_FILTER and the notches act on them)")
        elif base == "IMT":
            info = StreamInfo(name, n, rate, t0, t1, "increments", True, "delta angles and velocities of the EKF, integrated from the raw samples before the filters")
        elif base in ("ISBH", "ISBD"):
            info = StreamInfo(name, n, rate, t0, t1, "rates", False, "batch sampler: bursts of one sensor at a time (gyro and accelerometer in turn), int16 × mul: not read as a stream")
        elif base in ("GYR", "ACC"):
            info = StreamInfo(name, n, rate, t0, t1, "rates", False, "raw samples of one sensor at its own sample times: not read as a stream")
        elif base == "GPS":
            info = StreamInfo(name, n, rate, t0, t1, "other", False, "GNSS fixes: the latitude check and the aided alignment use them")
        else:
            info = StreamInfo(name, n, rate, t0, t1, "other", False, "")
        streams.append(info)
        by_topic[name] = (kind, i)
    chosen = choose_topic(streams, topic, duration, p.name)
    if guard is not None:
        guard(chosen.samples, chosen.topic)
    kind_c, inst_c = by_topic[chosen.topic]
    base_c = chosen.topic.split("[")[0]
    gps = [(by_topic[s.topic], s.topic) for s in streams if s.topic.startswith("GPS[")][:1]
    dt_c = fm.dtypes[kind_c]
    if base_c == "IMU":
        cols = ["TimeUS", "GyrX", "GyrY", "GyrZ", "AccX", "AccY", "AccZ"]
    else:
        cols = ["TimeUS", "DelAX", "DelAY", "DelAZ", "DelVX", "DelVY", "DelVZ", "DelaT", "DelvT"]
    missing = [c for c in cols if c not in dt_c.names]
    if missing:
        raise ValueError(f"Expected the fields {missing} in {base_c} of {p.name}, got a format without them")
    out = np.empty((chosen.samples, len(cols)), dtype=np.float64)
    filled = [0]
    gps_rows = []

    def take(buf, off, kd):
        sel = kd == kind_c
        if np.any(sel):
            rows = gather(buf, off[sel] + 3, dt_c.itemsize).view(dt_c).ravel()
            inst = inst_column(kind_c, rows)
            if inst is not None:
                rows = rows[inst == inst_c]
            k = filled[0]
            m = min(rows.size, chosen.samples - k)
            for j, c in enumerate(cols):
                out[k : k + m, j] = rows[c][:m]
            filled[0] = k + m
        for (gk, gi), _ in gps:
            gsel = kd == gk
            if np.any(gsel):
                gdt = fm.dtypes[gk]
                rows = gather(buf, off[gsel] + 3, gdt.itemsize).view(gdt).ravel()
                inst = inst_column(gk, rows)
                gps_rows.append(rows if inst is None else rows[inst == gi])

    fm2 = _Formats()
    _walk(p, fm2, take, False, "")
    out = out[: filled[0]]
    time = (out[:, 0] - t_start) * 1e-6
    frame = "FRD body frame (x forward, y right, z down), ArduPilot's own: no conversion"
    if base_c == "IMU":
        conv = "rate × interval (the logged rate held over the interval that ends at its sample)"
        samples = StreamSamples(chosen.topic, time, out[:, 1:4], out[:, 4:7], "rates", conv, "rad/s and m/s² (SI in the log)", frame)
    else:
        conv = "DelA and DelV as ArduPilot integrated them, with DelaT [s]"
        samples = StreamSamples(chosen.topic, time, out[:, 1:4], out[:, 4:7], "increments", conv, "rad and m/s (SI in the log)", frame, out[:, 7], "s")
    gnss = None
    if gps_rows:
        rows = np.concatenate(gps_rows)
        sc = fm.scales.get(gps[0][0][0], {})
        names = rows.dtype.names
        if all(c in names for c in ("Lat", "Lng", "Alt", "TimeUS")):
            ok = (rows["Status"] >= 3) if "Status" in names else np.ones(rows.size, bool)
            lat = rows["Lat"] * sc.get("Lat", 1.0)
            lon = rows["Lng"] * sc.get("Lng", 1.0)
            alt = rows["Alt"] * sc.get("Alt", 1.0)
            ok &= (np.abs(lat) > 0) & (np.abs(lat) <= 90)
            if np.any(ok):
                vel = None
                if all(c in names for c in ("Spd", "GCrs", "VZ")):
                    crs = np.radians(rows["GCrs"].astype(float))
                    vel = np.stack([rows["Spd"] * np.cos(crs), rows["Spd"] * np.sin(crs), rows["VZ"]], axis=-1)[ok].astype(float)
                tg = (rows["TimeUS"][ok].astype(float) - t_start) * 1e-6
                gnss = GnssTrack(gps[0][1], tg, np.radians(lat[ok].astype(float)), np.radians(lon[ok].astype(float)), alt[ok].astype(float), vel)
    filters = []
    for name, (on_imu, on_imt, evidence) in ARDUPILOT_FILTERS.items():
        if name in params:
            filters.append(SensorFilter(name, params[name], on_imu if base_c == "IMU" else on_imt, evidence))
    filters.append(SensorFilter("sensor digital low-pass (driver)", None, True, "the IMU chip's own digital low-pass, set by its backend driver: in front of every sample"))
    software = next((m for m in messages if m.startswith(("Ardu", "APM", "Rover", "Plane", "Copter", "Sub", "Blimp"))), "ArduPilot")
    return LogContents("dataflash", tuple(streams), samples, tuple(filters), software, t_start * 1e-6, duration, gnss, {}, tuple(notes))
