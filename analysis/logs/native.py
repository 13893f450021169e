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

Public API
----------
.. autosummary::

   read_log
   write_log
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .imu_log import METADATA, ImuLog

__all__ = ["read_log", "write_log"]

_AXES = ("x", "y", "z")


def _columns(kind_a, kind_b):
    return [f"{kind_a}_{a}" for a in _AXES], [f"{kind_b}_{a}" for a in _AXES]


def read_log(path) -> ImuLog:
    """Read a log from ``.npz`` or ``.csv`` (``docs/recorded-logs.md``).

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
        For an unknown suffix, missing columns, or samples that are not at a constant rate.
    OSError
        If the file cannot be read.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".npz":
        with np.load(p, allow_pickle=False) as z:
            data = {k: z[k] for k in z.files}
        meta = {k: (str(v) if k == "description" else float(v)) for k, v in data.items() if k in METADATA}
        if "time" not in data:
            raise ValueError(f"Expected an array `time` in {p.name}, got {sorted(data)}")
        t = np.asarray(data["time"], dtype=float)
        if "dtheta" in data and "dv" in data:
            return ImuLog(t, data["dtheta"], data["dv"], meta)
        if "gyro" in data and "accel" in data:
            h = _interval(t)
            return ImuLog(t, np.asarray(data["gyro"], dtype=float) * h, np.asarray(data["accel"], dtype=float) * h, meta)
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
                        meta[name] = value.strip() if name == "description" else float(value)
                    continue
                if s:
                    header = [c.strip() for c in s.split(",")]
                    break
            if header is None:
                raise ValueError(f"Expected a header row in {p.name}")
            rows = np.loadtxt(f, delimiter=",", ndmin=2)
        if rows.shape[1] != len(header):
            raise ValueError(f"Expected {len(header)} values per row (the header's columns) in {p.name}, got {rows.shape[1]}")
        col = {name: rows[:, i] for i, name in enumerate(header)}
        if "time" not in col:
            raise ValueError(f"Expected a column `time` in {p.name}, got {header}")
        t = col["time"]
        for a, b, scale in (("dtheta", "dv", None), ("gyro", "accel", "rate")):
            ca, cb = _columns(a, b)
            if all(c in col for c in ca + cb):
                A, B = np.stack([col[c] for c in ca], axis=1), np.stack([col[c] for c in cb], axis=1)
                h = 1.0 if scale is None else _interval(t)
                return ImuLog(t, A * h, B * h, meta)
        raise ValueError(f"Expected columns dtheta_x … dv_z (or gyro_x … accel_z) in {p.name}, got {header}")
    raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")


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
    if suffix == ".npz":
        arrays = {"time": log.time, "dtheta": log.dtheta.astype(dtype), "dv": log.dv.astype(dtype)}
        arrays.update({k: np.array(v) for k, v in meta.items()})
        np.savez_compressed(p, **arrays)
        return p
    if suffix == ".csv":
        header = ["time"] + [f"dtheta_{a}" for a in _AXES] + [f"dv_{a}" for a in _AXES]
        lines = [f"# {k}: {v!r}" if not isinstance(v, str) else f"# {k}: {v}" for k, v in meta.items()]
        body = np.column_stack([log.time, log.dtheta, log.dv])
        with open(p, "w", encoding="utf-8", newline="\n") as f:
            f.write("\n".join(lines + [",".join(header)]) + "\n")
            np.savetxt(f, body, delimiter=",", fmt="%.17g")
        return p
    raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")
