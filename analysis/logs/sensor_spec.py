"""A sensor specification file: the noise an alignment filter assumes, from a data sheet or an Allan analysis.

The file is TOML, in the units of data sheets::

    [gyro]
    arw_deg_per_rt_h = 0.002            # angle random walk [deg/√h]
    bias_instability_deg_per_h = 0.01   # bias instability [deg/h] (optional)
    rrw_deg_per_h_per_rt_h = 0.001      # rate random walk [deg/h/√h] (optional)

    [accel]
    vrw_m_s_per_rt_h = 0.006            # velocity random walk [m/s/√h]
    bias_instability_ug = 10            # bias instability [µg] (optional)

``strapdown align --log --imu FILE`` reads it; ``strapdown log allan`` writes one
(:func:`write_sensor_spec`).  Inside the library everything is SI.

Public API
----------
.. autosummary::

   SensorSpec
   read_sensor_spec
   write_sensor_spec
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

from ..core.units import DEG_PER_H_TO_RAD_PER_S, DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, STANDARD_GRAVITY
from ..core.validation import nonnegative, positive

__all__ = ["SensorSpec", "read_sensor_spec", "write_sensor_spec"]

_RT_H = math.sqrt(3600.0)


@dataclass(frozen=True)
class SensorSpec:
    """The noise of an IMU, SI.

    Attributes
    ----------
    arw : float
        Gyro angle random walk [rad/√s].
    vrw : float
        Accelerometer velocity random walk [m/s/√s].
    gyro_bias_instability : float or None
        [rad/s].
    accel_bias_instability : float or None
        [m/s²].
    rrw : float or None
        Gyro rate random walk [rad/s/√s].
    source : str
        Where it comes from (the file).
    """

    arw: float
    vrw: float
    gyro_bias_instability: float | None = None
    accel_bias_instability: float | None = None
    rrw: float | None = None
    source: str = ""

    def __post_init__(self):
        positive(self.arw, "arw")
        positive(self.vrw, "vrw")
        for name in ("gyro_bias_instability", "accel_bias_instability", "rrw"):
            if getattr(self, name) is not None:
                nonnegative(getattr(self, name), name)


def read_sensor_spec(path) -> SensorSpec:
    """Read a sensor specification file.

    Parameters
    ----------
    path : str or Path
        The TOML file.

    Returns
    -------
    SensorSpec

    Raises
    ------
    ValueError
        A missing section or value, or a value that is not a positive number.
    """
    from ...derivations.toml_files import read_toml

    p = Path(path)
    data = read_toml(p, max_bytes=100_000, max_depth=4, kind="sensor specification")
    gyro, accel = data.get("gyro"), data.get("accel")
    if not isinstance(gyro, dict) or not isinstance(accel, dict):
        raise ValueError(f"Expected tables [gyro] and [accel] in the sensor specification {p.name}, got {sorted(data)}")

    def number(table, key, section, required):
        v = table.get(key)
        if v is None:
            if required:
                raise ValueError(f"Expected `{key}` in [{section}] of {p.name} (a sensor's noise is never taken as zero), got none")
            return None
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"Expected `{key}` in [{section}] of {p.name} to be a finite number, got {v!r}")
        return float(v)

    arw = number(gyro, "arw_deg_per_rt_h", "gyro", True)
    vrw = number(accel, "vrw_m_s_per_rt_h", "accel", True)
    bi_g = number(gyro, "bias_instability_deg_per_h", "gyro", False)
    rrw = number(gyro, "rrw_deg_per_h_per_rt_h", "gyro", False)
    bi_a = number(accel, "bias_instability_ug", "accel", False)
    if not arw > 0 or not vrw > 0:
        raise ValueError(f"Expected arw_deg_per_rt_h and vrw_m_s_per_rt_h > 0 in {p.name} (zero noise makes the filter diverge on a long log), got {arw:g} and {vrw:g}")
    return SensorSpec(
        arw * DEG_PER_RT_H_TO_RAD_PER_RT_S, vrw * M_S_PER_RT_H_TO_M_S_PER_RT_S,
        None if bi_g is None else bi_g * DEG_PER_H_TO_RAD_PER_S, None if bi_a is None else bi_a * 1e-6 * STANDARD_GRAVITY,
        None if rrw is None else rrw * DEG_PER_H_TO_RAD_PER_S / _RT_H, str(p),
    )  # fmt: skip


def write_sensor_spec(path, spec: SensorSpec, *, comment: str = "") -> Path:
    """Write ``spec`` as a sensor specification file (atomically).

    Parameters
    ----------
    path : str or Path
        The TOML file.
    spec : SensorSpec
        The noise.
    comment : str, keyword-only
        A first comment line (where the numbers come from).

    Returns
    -------
    Path
    """
    p = Path(path)
    lines = [f"# {line}" for line in comment.splitlines()] if comment else []
    lines += ["[gyro]", f"arw_deg_per_rt_h = {spec.arw / DEG_PER_RT_H_TO_RAD_PER_RT_S!r}"]
    if spec.gyro_bias_instability is not None:
        lines.append(f"bias_instability_deg_per_h = {spec.gyro_bias_instability / DEG_PER_H_TO_RAD_PER_S!r}")
    if spec.rrw is not None:
        lines.append(f"rrw_deg_per_h_per_rt_h = {spec.rrw * _RT_H / DEG_PER_H_TO_RAD_PER_S!r}")
    lines += ["", "[accel]", f"vrw_m_s_per_rt_h = {spec.vrw / M_S_PER_RT_H_TO_M_S_PER_RT_S!r}"]
    if spec.accel_bias_instability is not None:
        lines.append(f"bias_instability_ug = {spec.accel_bias_instability / (1e-6 * STANDARD_GRAVITY)!r}")
    tmp = p.with_name(f".{p.name}.partial")
    try:
        tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()
    return p
