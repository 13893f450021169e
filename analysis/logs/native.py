"""The package's own log formats, ``.npz`` and ``.csv`` (``docs/recorded-logs.md``).

A log holds the samples of one IMU at a constant rate: the time at the end of
each sample interval and either the increments (angle and velocity) or the
rates (angular rate and specific force) of the three body axes, in SI units.

``.npz``
    arrays ``time`` (N,), ``dtheta`` and ``dv`` (N, 3) — or ``gyro`` and
    ``accel`` (N, 3) — and optional 0-d metadata arrays;
``.csv``
    a header row naming the columns ``time``, ``dtheta_x`` … ``dv_z`` (or
    ``gyro_x`` … ``accel_z``), one row per sample; metadata in leading comment
    lines ``# name: value``.

Metadata (all optional, SI): ``latitude`` [rad]; ``stable_heading``,
``stable_beta``, ``stable_gamma`` [rad] (the mean attitude of a rocking
block, the reference of the analytic method); ``end_heading``, ``end_beta``,
``end_gamma`` [rad] (the attitude at the end, the reference of the other
methods); ``description``.  Rates are turned into increments as rate × interval
(constant over the interval); give increments where the IMU outputs them.

A truncated or corrupt ``.npz`` is refused with a ``ValueError`` naming the file (never
``zipfile.BadZipFile``); :func:`write_log` writes atomically (a temporary file renamed into
place), so that an interrupted write leaves no half-written log.

Public API
----------
.. autosummary::

   read_log
   read_native
   write_log
"""

from __future__ import annotations

import os
import zipfile
import zlib
from pathlib import Path

import numpy as np

from .imu_log import METADATA, ImuLog
from .inventory import StreamInfo
from .streams import LogContents, StreamSamples

__all__ = ["read_log", "read_native", "write_log"]

_FRAME = "the package's body axes (x forward, y right, z down), as the format defines them: no conversion"


def _load_npz(p: Path) -> dict:
    """The arrays of an ``.npz``; a truncated or corrupt archive is a ValueError naming the file."""
    try:
        with np.load(p, allow_pickle=False) as z:
            return {k: z[k] for k in z.files}
    except (zipfile.BadZipFile, zlib.error, EOFError) as e:
        raise ValueError(f"Expected a complete .npz archive, got a truncated or corrupt file {p.name} ({type(e).__name__}: {e})") from None
    except ValueError as e:
        raise ValueError(f"Expected a complete .npz archive of numeric arrays, got {p.name} that numpy cannot read ({e})") from None


def _read_columns(p: Path):
    """``(time, a, b, held, metadata)`` of a native log, without the constant-rate check."""
    suffix = p.suffix.lower()
    if suffix == ".npz":
        data = _load_npz(p)
        meta = {k: (str(v) if k == "description" else float(v)) for k, v in data.items() if k in METADATA}
        if "time" not in data:
            raise ValueError(f"Expected an array `time` in {p.name}, got {sorted(data)}")
        t = np.asarray(data["time"], dtype=float).ravel()
        for a, b, held in (("dtheta", "dv", "increments"), ("gyro", "accel", "rates")):
            if a in data and b in data:
                A, B = np.asarray(data[a], dtype=float), np.asarray(data[b], dtype=float)
                for name, arr in ((a, A), (b, B)):
                    if arr.shape != (t.size, 3):
                        raise ValueError(f"Expected `{name}` with shape ({t.size}, 3) in {p.name}, got shape {arr.shape}")
                return t, A, B, held, meta
        raise ValueError(f"Expected arrays `dtheta` and `dv` (or `gyro` and `accel`) in {p.name}, got {sorted(data)}")
    if suffix == ".csv":
        meta, header = {}, None
        with open(p, encoding="utf-8") as f:
            for line in f:
                s = line.strip()
                if s.startswith("#"):
                    name, sep, value = s[1:].partition(":")
                    name = name.strip()
                    if sep and name in METADATA:
                        try:
                            meta[name] = value.strip() if name == "description" else float(value)
                        except ValueError:
                            raise ValueError(f"Expected a number for the metadata `{name}` in {p.name}, got {value.strip()!r}") from None
                    continue
                if s:
                    header = [c.strip() for c in s.split(",")]
                    break
            if header is None:
                raise ValueError(f"Expected a header row in {p.name}")
            try:
                rows = np.loadtxt(f, delimiter=",", ndmin=2)
            except ValueError as e:
                raise ValueError(f"Expected {len(header)} numbers per row in {p.name}, got a row numpy cannot read ({e})") from None
        if rows.size and rows.shape[1] != len(header):
            raise ValueError(f"Expected {len(header)} values per row (the header's columns) in {p.name}, got {rows.shape[1]}")
        col = {name: rows[:, i] for i, name in enumerate(header)} if rows.size else {name: np.zeros(0) for name in header}
        if "time" not in col:
            raise ValueError(f"Expected a column `time` in {p.name}, got {header}")
        t = col["time"]
        for a, b, held in (("dtheta", "dv", "increments"), ("gyro", "accel", "rates")):
            ca, cb = _columns(a, b)
            if all(c in col for c in ca + cb):
                return t, np.stack([col[c] for c in ca], axis=1), np.stack([col[c] for c in cb], axis=1), held, meta
        raise ValueError(f"Expected columns dtheta_x … dv_z (or gyro_x … accel_z) in {p.name}, got {header}")
    raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")


def read_native(path, *, topic: str | None = None, guard=None, progress: bool = False) -> LogContents:
    """Read a log of the package's own formats for :func:`~strapdown.analysis.logs.reader.read_imu_log`.

    Parameters
    ----------
    path : str or Path
        The ``.npz`` or ``.csv`` file.
    topic : str, optional, keyword-only
        ``"imu"`` (the one stream) or None.
    guard : callable, optional, keyword-only
        ``guard(samples, topic)`` called once the size is known.
    progress : bool, keyword-only
        Unused (the file is read at once).

    Returns
    -------
    LogContents

    Raises
    ------
    ValueError
        A truncated archive, missing columns, a ``topic`` other than ``"imu"``.
    """
    p = Path(path)
    if topic not in (None, "imu"):
        raise ValueError(f"Expected `topic` 'imu' (the one stream of a {p.suffix} log), got {topic!r}")
    t, a, b, held, meta = _read_columns(p)
    if guard is not None:
        guard(t.size, "imu")
    if t.size < 2:
        raise ValueError(f"Expected at least two samples in {p.name}, got {t.size}")
    names = ("dtheta", "dv") if held == "increments" else ("gyro", "accel")
    for name, arr in (("time", t), (names[0], a), (names[1], b)):
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"Expected finite numbers in {p.name}, got NaN or inf in `{name}`")
    d = np.diff(t)
    h = float(np.median(d))
    start = float(t[0] - h) if np.isfinite(h) else float(t[0])
    rate = (t.size - 1) / (t[-1] - t[0]) if t[-1] > t[0] else 0.0
    fmt = p.suffix.lower().lstrip(".")
    stream = StreamInfo("imu", int(t.size), float(rate), float(t[0] - start), float(t[-1] - start), held, True, f"the package's {fmt} format ({held})")
    conv = "increments as stored" if held == "increments" else "rate × interval (the rate held over the interval that ends at its sample)"
    units = "rad and m/s (SI, as the format defines)" if held == "increments" else "rad/s and m/s² (SI, as the format defines)"
    samples = StreamSamples("imu", t - start, a, b, held, conv, units, _FRAME)
    return LogContents(fmt, (stream,), samples, (), "", start, float(t[-1] - start), None, meta, ())

_AXES = ("x", "y", "z")


def _columns(kind_a, kind_b):
    return [f"{kind_a}_{a}" for a in _AXES], [f"{kind_b}_{a}" for a in _AXES]


def read_log(path) -> ImuLog:
    """Read a log from ``.npz`` or ``.csv`` (``docs/recorded-logs.md``) as one constant-rate :class:`ImuLog`.

    :func:`~strapdown.analysis.logs.reader.read_imu_log` reads the same files with the
    inventory, the segments between gaps and the plausibility checks.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    ImuLog

    Raises
    ------
    ValueError
        For an unknown suffix, a truncated or corrupt archive, missing columns, or samples that
        are not at a constant rate.
    OSError
        If the file cannot be read.
    """
    p = Path(path)
    t, a, b, held, meta = _read_columns(p)
    if held == "rates":
        h = _interval(t)
        a, b = a * h, b * h
    return ImuLog(t, a, b, meta)


def _interval(t) -> float:
    d = np.diff(np.asarray(t, dtype=float))
    if d.size == 0 or not np.all(d > 0):
        raise ValueError("Expected `time` strictly increasing [s]")
    return float(np.median(d))


def write_log(path, log: ImuLog, *, dtype=np.float64) -> Path:
    """Write a log as ``.npz`` (compressed) or ``.csv``.

    Parameters
    ----------
    path : str or Path
        The file; its suffix chooses the format.
    log : ImuLog
        The samples.
    dtype : numpy dtype, keyword-only
        Storage type of the increments in ``.npz`` (``float32`` halves the size;
        the time stays float64).

    Returns
    -------
    Path
    """
    p = Path(path)
    suffix = p.suffix.lower()
    meta = dict(log.metadata)
    if suffix not in (".npz", ".csv"):
        raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")
    tmp = p.with_name(f".{p.name}.partial")
    try:
        if suffix == ".npz":
            arrays = {"time": log.time, "dtheta": log.dtheta.astype(dtype), "dv": log.dv.astype(dtype)}
            arrays.update({k: np.array(v) for k, v in meta.items()})
            with open(tmp, "wb") as f:
                np.savez_compressed(f, **arrays)
        else:
            header = ["time"] + [f"dtheta_{a}" for a in _AXES] + [f"dv_{a}" for a in _AXES]
            lines = [f"# {k}: {v!r}" if not isinstance(v, str) else f"# {k}: {v}" for k, v in meta.items()]
            body = np.column_stack([log.time, log.dtheta, log.dv])
            with open(tmp, "w", encoding="utf-8", newline="\n") as f:
                f.write("\n".join(lines + [",".join(header)]) + "\n")
                np.savetxt(f, body, delimiter=",", fmt="%.17g")
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()
    return p
