"""Synthetic logs with a known truth for the tests of the log analyses (exact increments, no library code of the analyses).

* :func:`cone_log`: the exact increments of a classical cone (the regular precession of
  Lebedev & Panov 1989, eq. (4.1), integrated in closed form);
* :func:`coning_band`: the exact increments of a Gaussian coning band, x and y in quadrature,
  drawn on the record's own frequency grid;
* :func:`write_px4_ulog`: a PX4 ULog of ``sensor_combined`` (the file format of
  docs.px4.io "ULog File Format": header, flag bits, format, subscription and data messages),
  written byte by byte and read back by pyulog in the tests.
"""

from __future__ import annotations

import math
import struct

import numpy as np

from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.logs.imu_log import ImuLog


def cone(freq_hz=10.0, half_angle_deg=1.0) -> RegularPrecession:
    """Classical coning (ε = −1) of ``half_angle_deg`` at ``freq_hz``: the body's x leads y, a cone about −z of the body."""
    return RegularPrecession(-1.0, 2.0 * math.pi * freq_hz, math.radians(half_angle_deg))


def cone_log(n: int, h: float, **kw) -> ImuLog:
    """``n`` samples at interval ``h`` of :func:`cone` (exact increments); the specific force is gravity's, on −z."""
    dv = np.zeros((n, 3))
    dv[:, 2] = -9.80665 * h
    return ImuLog(h * np.arange(1, n + 1), cone(**kw).grid_increments(h, 0, n), dv)


def coning_band(n: int, h: float, f1: float, f2: float, density: float, rng) -> tuple:
    """Exact increments (x, y) of a coherent coning band of one-sided rate density ``density`` [(rad/s)²/Hz] on [f1, f2].

    The rate x is Gaussian, ``Σ Re(c_k e^{iω_k t})`` on the frequencies k/(n h) with
    ``E|c_k|² = 2 G/(n h)``; y is x delayed by a quarter period (coning about +z), so
    ``G_xy = −i G``.  The increment over ``((j−1)h, jh]`` of ``e^{iωt}`` is
    ``(1 − e^{−iωh})/(iω) e^{iωjh}``.
    """
    T = n * h
    f = np.arange(n // 2 + 1) / T
    inside = (f >= f1) & (f <= f2)
    c = np.zeros(f.size, complex)
    c[inside] = math.sqrt(density / T) * (rng.standard_normal(inside.sum()) + 1j * rng.standard_normal(inside.sum()))
    w = 2.0 * math.pi * f
    resp = np.zeros(f.size, complex)
    resp[1:] = (1.0 - np.exp(-1j * w[1:] * h)) / (1j * w[1:])
    b = c * resp * np.exp(1j * w * h)  # sample j = 0 … n−1 ends at (j + 1) h
    return np.fft.irfft(b, n) * n / 2.0, np.fft.irfft(-1j * b, n) * n / 2.0


def write_px4_ulog(path, time_us, gyro_rad, integral_dt_us, accel_m_s2) -> None:
    """A ULog holding ``sensor_combined`` (timestamp [µs], gyro_rad [rad/s, float32], gyro_integral_dt [µs], accelerometer_m_s2)."""
    fmt = "sensor_combined:uint64_t timestamp;float[3] gyro_rad;uint32_t gyro_integral_dt;float[3] accelerometer_m_s2;uint32_t accelerometer_integral_dt;"
    out = bytearray(b"ULog\x01\x12\x35" + bytes([1]) + struct.pack("<Q", int(time_us[0])))

    def message(kind: str, payload: bytes) -> None:
        out.extend(struct.pack("<HB", len(payload), ord(kind)) + payload)

    message("B", bytes(16) + bytes(24))  # compatible and incompatible flags, appended offsets: none
    message("F", fmt.encode())
    message("A", struct.pack("<BH", 0, 0) + b"sensor_combined")
    for k in range(len(time_us)):
        message("D", struct.pack("<HQ3fI3fI", 0, int(time_us[k]), *gyro_rad[k], int(integral_dt_us[k]), *accel_m_s2[k], int(integral_dt_us[k])))
    with open(path, "wb") as f:
        f.write(out)
