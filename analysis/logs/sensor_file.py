"""Sensor files: an IMU's noise as a data sheet gives it, in TOML, for ``align`` and the alignment toolkit.

``strapdown log allan`` writes one from a static log; a designer can write one
from a data sheet.  The format (``docs/recorded-logs.md``)::

    name = "bench IMU"                     # optional
    description = "..."                    # optional
    [gyro]
    arw_deg_per_rt_h = 0.05                # angle random walk [deg/√h], required
    bias_instability_deg_per_h = 0.5       # [deg/h] (flicker floor / 0.664), default 0
    rrw_deg_per_h_per_rt_h = 0.8           # rate random walk [deg/h/√h], default 0
    arw_deg_per_rt_h_ci95 = [0.0498, 0.0502]   # optional: 95 % interval of each value
    [accel]
    vrw_m_s_per_rt_h = 0.05                # velocity random walk [m/s/√h], required
    bias_instability_ug = 10.0             # [µg], default 0

Every value ``k`` may have a companion ``k_ci95 = [low, high]``, its 95 %
interval.  Unknown keys, negative values and intervals that do not hold their
value are refused with a message naming the file, the table and the key.

Public API
----------
.. autosummary::

   SensorFile
   read_sensor_file
   sensor_file_text
   write_sensor_file
   GYRO_KEYS
   ACCEL_KEYS
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from ...derivations.toml_files import read_toml
from ..alignment.sensor_models import DataSheet, SensorSpec
from ..core.atomic import replaced_atomically
from ..core.units import DEG_PER_H_PER_RT_H_TO_RAD_PER_S_PER_RT_S, DEG_PER_H_TO_RAD_PER_S, DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, MICRO_G
from .static_noise import StaticNoise

__all__ = ["SensorFile", "read_sensor_file", "sensor_file_text", "write_sensor_file", "GYRO_KEYS", "ACCEL_KEYS"]

#: Keys of ``[gyro]``: (SensorSpec field, SI per file unit, required).
GYRO_KEYS = {
    "arw_deg_per_rt_h": ("random_walk", DEG_PER_RT_H_TO_RAD_PER_RT_S, True),
    "bias_instability_deg_per_h": ("bias_instability", DEG_PER_H_TO_RAD_PER_S, False),
    "rrw_deg_per_h_per_rt_h": ("rate_random_walk", DEG_PER_H_PER_RT_H_TO_RAD_PER_S_PER_RT_S, False),
}
#: Keys of ``[accel]``: (SensorSpec field, SI per file unit, required).
ACCEL_KEYS = {
    "vrw_m_s_per_rt_h": ("random_walk", M_S_PER_RT_H_TO_M_S_PER_RT_S, True),
    "bias_instability_ug": ("bias_instability", MICRO_G, False),
}
_MAX_BYTES = 64 * 1024
_TEXT = 1000


@dataclass(frozen=True)
class SensorFile:
    """A sensor file read (:func:`read_sensor_file`).

    Attributes
    ----------
    sheet : DataSheet
        The IMU in SI units (no turn-on bias: the file does not give one).
    intervals : dict
        ``"gyro.random_walk"`` … → ``(low, high)`` in SI, for the values that have a 95 % interval.
    description : str
        The file's description.
    """

    sheet: DataSheet
    intervals: dict = field(default_factory=dict)
    description: str = ""


def _number(path, where: str, key: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)) or value < 0:
        raise ValueError(f"{path}: {where} key {key!r}: expected a finite number ≥ 0, got {str(value)[:40]!r}")
    return float(value)


def _triad(path, data: dict, table: str, keys: dict, intervals: dict) -> SensorSpec:
    t = data.get(table)
    if not isinstance(t, dict):
        raise ValueError(f"{path}: missing table [{table}] (expected the keys {', '.join(keys)})")
    allowed = set(keys) | {f"{k}_ci95" for k in keys}
    extra = sorted(set(t) - allowed)
    if extra:
        raise ValueError(f"{path}: [{table}] unknown key {extra[0][:40]!r} (expected one of {', '.join(sorted(allowed))})")
    values = {}
    for key, (name, factor, required) in keys.items():
        if key not in t:
            if required:
                raise ValueError(f"{path}: [{table}] missing key {key!r}")
            continue
        v = _number(path, f"[{table}]", key, t[key])
        values[name] = v * factor
        ci = t.get(f"{key}_ci95")
        if ci is not None:
            if not isinstance(ci, list) or len(ci) != 2:
                raise ValueError(f"{path}: [{table}] key {key + '_ci95'!r}: expected [low, high], got {str(ci)[:40]!r}")
            lo, hi = (_number(path, f"[{table}]", f"{key}_ci95", x) for x in ci)
            if not lo <= v <= hi:
                raise ValueError(f"{path}: [{table}] key {key + '_ci95'!r}: expected an interval holding {key} = {v:g}, got [{lo:g}, {hi:g}]")
            intervals[f"{table}.{name}"] = (lo * factor, hi * factor)
    for key in t:
        if key.endswith("_ci95") and key[: -len("_ci95")] not in t:
            raise ValueError(f"{path}: [{table}] key {key!r} without its value {key[: -len('_ci95')]!r}")
    return SensorSpec(**values)


def read_sensor_file(path) -> SensorFile:
    """Read a sensor file (module docstring).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    SensorFile

    Raises
    ------
    ValueError
        A file that cannot be read, is not TOML, has unknown or missing keys,
        negative or non-numeric values, or intervals that do not hold their
        value; the message names the file, the table and the key.
    """
    p = Path(path)
    data = read_toml(p, max_bytes=_MAX_BYTES, max_depth=3, kind="sensor file")
    extra = sorted(set(data) - {"name", "description", "gyro", "accel"})
    if extra:
        raise ValueError(f"{p}: unknown key {extra[0][:40]!r} at the top level (expected name, description, [gyro], [accel])")
    texts = {}
    for key in ("name", "description"):
        v = data.get(key, p.stem if key == "name" else "")
        if not isinstance(v, str) or len(v) > _TEXT:
            raise ValueError(f"{p}: key {key!r}: expected a string of at most {_TEXT} characters, got {str(v)[:40]!r}")
        texts[key] = v
    intervals: dict = {}
    gyro = _triad(p, data, "gyro", GYRO_KEYS, intervals)
    accel = _triad(p, data, "accel", ACCEL_KEYS, intervals)
    return SensorFile(DataSheet(texts["name"], gyro, accel), intervals, texts["description"])


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def sensor_file_text(noise: StaticNoise, *, name: str = "from a static log", description: str = "") -> str:
    """The sensor file of a static log's noise (95 % intervals).

    Parameters
    ----------
    noise : StaticNoise
        From :func:`strapdown.analysis.logs.static_noise.static_noise` with ``level`` 0.95.
    name, description : str, keyword-only
        The file's name and description.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If the intervals are not 95 % ones.
    """
    if not isinstance(noise, StaticNoise):
        raise TypeError(f"Expected `noise` to be a StaticNoise, got {type(noise).__name__}")
    if abs(noise.level - 0.95) > 1e-12:
        raise ValueError(f"Expected `noise` with 95 % intervals (level 0.95), got level {noise.level:g}")
    lines = [
        "# IMU noise read off the Allan deviation of a static log (strapdown log allan);",
        "# each value with its 95 % interval (the χ² interval of the Allan-deviation point it was read at).",
        f"name = {_quote(name)}",
        f"description = {_quote(description)}",
    ]
    for table, keys, triad in (("gyro", GYRO_KEYS, noise.gyro), ("accel", ACCEL_KEYS, noise.accel)):
        lines += ["", f"[{table}]"]
        for key, (attr, factor, _) in keys.items():
            c = getattr(triad, attr)
            lines.append(f"{key} = {c.value / factor!r}")
            lines.append(f"{key}_ci95 = [{c.low / factor!r}, {c.high / factor!r}]")
    return "\n".join(lines) + "\n"


def write_sensor_file(path, noise: StaticNoise, *, name: str = "from a static log", description: str = "") -> Path:
    """Write the sensor file of ``noise`` atomically, after reading it back.

    Parameters
    ----------
    path : str or Path
        The file.
    noise : StaticNoise
        The noise (95 % intervals).
    name, description : str, keyword-only
        The file's name and description.

    Returns
    -------
    Path

    Raises
    ------
    OSError
        A directory that cannot be written.
    """
    p = Path(path)
    text = sensor_file_text(noise, name=name, description=description)
    with replaced_atomically(p) as tmp:
        tmp.write_text(text, encoding="utf-8", newline="\n")
        read_sensor_file(tmp)
    return p
