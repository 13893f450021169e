"""An IMU's data sheet: every error the error budget knows, in SI units, and its TOML file.

An IMU file (UTF-8 TOML, read by :func:`strapdown.derivations.toml_files.read_toml`)
holds a name, the sample rate and two tables, ``[gyro]`` and ``[accel]``,
every value in the body axes of the sensor block (x, y, z; at rest and level,
body x points along the heading, z down)::

    name = "tactical IMU"
    sample_rate_hz = 200.0

    [gyro]
    bias_deg_per_h = [1.0, -0.5, 0.3]        # fixed bias, signed, per axis
    turn_on_bias_deg_per_h = 1.0             # 1σ of the bias of a run, per axis
    arw_deg_per_rt_h = 0.05                  # angle random walk N
    bias_instability_deg_per_h = 0.5         # B: the flicker floor of the Allan deviation is 0.664 B
    bias_instability_band_s = [1.0, 3000.0]  # correlation times the Gauss–Markov sum spans
    rrw_deg_per_h_per_rt_h = 0.1             # rate random walk K
    scale_factor_ppm = [100.0, 0.0, 0.0]     # fixed, signed
    scale_factor_sigma_ppm = 100.0           # 1σ per axis
    misalignment_urad = [0, 0, 0, 0, 0, 0]   # fixed: xy, xz, yx, yz, zx, zy
    misalignment_sigma_urad = 100.0          # 1σ of each of the six
    quantum_urad = 1.0                       # angle quantum of the accumulated output

    [accel]
    bias_ug = [100.0, 0.0, 0.0]
    turn_on_bias_ug = 1000.0
    vrw_m_s_per_rt_h = 0.06
    bias_instability_ug = 100.0
    bias_instability_band_s = [1.0, 3000.0]
    rrw_ug_per_rt_h = 10.0
    scale_factor_ppm = [0.0, 0.0, 0.0]
    scale_factor_sigma_ppm = 300.0
    misalignment_urad = [0, 0, 0, 0, 0, 0]
    misalignment_sigma_urad = 100.0
    quantum_mm_s = 0.1

Every key is optional (absent: no such error) except ``sample_rate_hz``.
The sensor model, per triad, is ``ω̃ = (I + S + M) ω + b + noise`` with
``S = diag(scale factors)`` and ``M`` the off-diagonal misalignments
(``δω_x = m_xy ω_y + m_xz ω_z``, …); the noise terms are those of
:class:`strapdown.analysis.alignment.sensor_models.SensorSpec` (random walk,
bias instability as a Gauss–Markov sum, rate random walk, turn-on bias), which
the error budget and its Monte Carlo use as they are.  An unknown key, a
missing rate, a value of the wrong kind, sign or length is refused with the
file, the table and the key.

Public API
----------
.. autosummary::

   TriadErrors
   ImuSpec
   load_imu
   example_imu
   EXAMPLE_IMUS
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from ...derivations.toml_files import read_toml
from ..alignment.sensor_models import SensorSpec
from ..core.units import DEG_PER_H_TO_RAD_PER_S, DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, PPM, SECONDS_PER_HOUR, STANDARD_GRAVITY
from ..core.validation import as_array, nonnegative, positive

__all__ = ["TriadErrors", "ImuSpec", "load_imu", "example_imu", "EXAMPLE_IMUS", "MISALIGNMENT_ORDER"]

#: Order of the six misalignments: ``m_xy`` is the part of ω_y that the x sensor reads.
MISALIGNMENT_ORDER = ("xy", "xz", "yx", "yz", "zx", "zy")
#: The example IMU files shipped with the package.
EXAMPLE_IMUS = ("tactical", "mems")
#: Largest IMU file [bytes].
MAX_FILE_BYTES = 64 * 1024
_MICRO = 1e-6


def _vec(x, name, size):
    v = as_array(x, name).reshape(-1)
    if v.size != size:
        raise ValueError(f"Expected `{name}` with {size} components, got {v.size}")
    return v


@dataclass(frozen=True)
class TriadErrors:
    """The errors of one sensor triad, SI units, body axes.

    Parameters
    ----------
    bias : array_like
        Fixed bias, 3 components [rad/s or m/s²].
    turn_on_bias : float
        1σ of the constant bias of a run, per axis [rad/s or m/s²].
    random_walk : float
        N [rad/√s or m/s/√s].
    bias_instability : float
        B [rad/s or m/s²].
    flicker_band : tuple of float
        Correlation times of the Gauss–Markov sum that stands for the flicker noise [s].
    rate_random_walk : float
        K [rad/s/√s or m/s²/√s].
    scale_factor : array_like
        Fixed scale-factor errors, 3 components [1].
    scale_factor_sigma : float
        1σ of a random scale-factor error per axis [1].
    misalignment : array_like
        Fixed misalignments in the order :data:`MISALIGNMENT_ORDER` [rad].
    misalignment_sigma : float
        1σ of each random misalignment [rad].
    quantum : float
        Quantum of the accumulated output [rad or m/s] (0: none).
    """

    bias: np.ndarray = field(default_factory=lambda: np.zeros(3))
    turn_on_bias: float = 0.0
    random_walk: float = 0.0
    bias_instability: float = 0.0
    flicker_band: tuple = (1.0, 3000.0)
    rate_random_walk: float = 0.0
    scale_factor: np.ndarray = field(default_factory=lambda: np.zeros(3))
    scale_factor_sigma: float = 0.0
    misalignment: np.ndarray = field(default_factory=lambda: np.zeros(6))
    misalignment_sigma: float = 0.0
    quantum: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "bias", _vec(self.bias, "bias", 3))
        object.__setattr__(self, "scale_factor", _vec(self.scale_factor, "scale_factor", 3))
        object.__setattr__(self, "misalignment", _vec(self.misalignment, "misalignment", 6))
        for name in ("turn_on_bias", "random_walk", "bias_instability", "rate_random_walk", "scale_factor_sigma", "misalignment_sigma", "quantum"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        self.noise_spec()  # checks the band

    def noise_spec(self) -> SensorSpec:
        """The noise terms as a :class:`~strapdown.analysis.alignment.sensor_models.SensorSpec`.

        Returns
        -------
        SensorSpec
        """
        return SensorSpec(self.random_walk, self.bias_instability, self.rate_random_walk, self.turn_on_bias, tuple(self.flicker_band))

    def matrix(self) -> np.ndarray:
        """``S + M``: the fixed scale factors on the diagonal, the fixed misalignments off it.

        Returns
        -------
        ndarray
            ``(3, 3)`` [1].
        """
        m = np.diag(self.scale_factor).astype(float)
        for value, (i, j) in zip(self.misalignment, ((0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1))):
            m[i, j] = value
        return m


@dataclass(frozen=True)
class ImuSpec:
    """An IMU: its name, sample rate and the errors of its two triads.

    Parameters
    ----------
    name : str
        Part or grade.
    sample_rate : float
        Sample rate of the increments [Hz].
    gyro : TriadErrors
        Gyro errors [rad/s …].
    accel : TriadErrors
        Accelerometer errors [m/s² …].
    """

    name: str
    sample_rate: float
    gyro: TriadErrors = field(default_factory=TriadErrors)
    accel: TriadErrors = field(default_factory=TriadErrors)

    def __post_init__(self):
        object.__setattr__(self, "sample_rate", positive(self.sample_rate, "sample_rate"))
        if not isinstance(self.gyro, TriadErrors) or not isinstance(self.accel, TriadErrors):
            raise TypeError("Expected `gyro` and `accel` to be TriadErrors")

    @property
    def sample_interval(self) -> float:
        """h = 1/f [s]."""
        return 1.0 / self.sample_rate


# --------------------------------------------------------------------------- the file
#: key → (SI factor, kind) per table; kind "vector3", "vector6", "scalar", "band".
_GYRO_KEYS = {
    "bias_deg_per_h": ("bias", DEG_PER_H_TO_RAD_PER_S, "vector3"),
    "turn_on_bias_deg_per_h": ("turn_on_bias", DEG_PER_H_TO_RAD_PER_S, "scalar"),
    "arw_deg_per_rt_h": ("random_walk", DEG_PER_RT_H_TO_RAD_PER_RT_S, "scalar"),
    "bias_instability_deg_per_h": ("bias_instability", DEG_PER_H_TO_RAD_PER_S, "scalar"),
    "bias_instability_band_s": ("flicker_band", 1.0, "band"),
    "rrw_deg_per_h_per_rt_h": ("rate_random_walk", DEG_PER_H_TO_RAD_PER_S / math.sqrt(SECONDS_PER_HOUR), "scalar"),
    "scale_factor_ppm": ("scale_factor", PPM, "vector3"),
    "scale_factor_sigma_ppm": ("scale_factor_sigma", PPM, "scalar"),
    "misalignment_urad": ("misalignment", _MICRO, "vector6"),
    "misalignment_sigma_urad": ("misalignment_sigma", _MICRO, "scalar"),
    "quantum_urad": ("quantum", _MICRO, "scalar"),
}
_UG = _MICRO * STANDARD_GRAVITY
_ACCEL_KEYS = {
    "bias_ug": ("bias", _UG, "vector3"),
    "turn_on_bias_ug": ("turn_on_bias", _UG, "scalar"),
    "vrw_m_s_per_rt_h": ("random_walk", M_S_PER_RT_H_TO_M_S_PER_RT_S, "scalar"),
    "bias_instability_ug": ("bias_instability", _UG, "scalar"),
    "bias_instability_band_s": ("flicker_band", 1.0, "band"),
    "rrw_ug_per_rt_h": ("rate_random_walk", _UG / math.sqrt(SECONDS_PER_HOUR), "scalar"),
    "scale_factor_ppm": ("scale_factor", PPM, "vector3"),
    "scale_factor_sigma_ppm": ("scale_factor_sigma", PPM, "scalar"),
    "misalignment_urad": ("misalignment", _MICRO, "vector6"),
    "misalignment_sigma_urad": ("misalignment_sigma", _MICRO, "scalar"),
    "quantum_mm_s": ("quantum", 1e-3, "scalar"),
}
_TOP = {"name", "sample_rate_hz", "gyro", "accel"}


def _number(path, where, key, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)):
        raise ValueError(f"{path}: {where} {key}: expected a finite number, got {value!r}"[:300])
    return float(value)


def _triad(path: Path, data: dict, table: str, keys: dict) -> TriadErrors:
    raw = data.get(table, {})
    if not isinstance(raw, dict):
        raise ValueError(f"{path}: [{table}] must be a table of key = value, got {type(raw).__name__}")
    unknown = sorted(set(raw) - set(keys))
    if unknown:
        raise ValueError(f"{path}: [{table}] unknown key {unknown[0]!r} (known: {', '.join(keys)})")
    values = {}
    for key, value in raw.items():
        attr, factor, kind = keys[key]
        if kind == "scalar":
            x = _number(path, f"[{table}]", key, value)
            if x < 0:
                raise ValueError(f"{path}: [{table}] {key}: expected a value >= 0, got {x:g}")
            values[attr] = x * factor
        else:
            size = {"vector3": 3, "vector6": 6, "band": 2}[kind]
            if not isinstance(value, list) or len(value) != size:
                raise ValueError(f"{path}: [{table}] {key}: expected a list of {size} numbers, got {value!r}"[:300])
            xs = np.array([_number(path, f"[{table}]", key, v) for v in value]) * factor
            if kind == "band":
                if not (0 < xs[0] < xs[1]):
                    raise ValueError(f"{path}: [{table}] {key}: expected [shortest, longest] correlation time with 0 < shortest < longest [s], got {value!r}")
                values[attr] = (float(xs[0]), float(xs[1]))
            else:
                values[attr] = xs
    return TriadErrors(**values)


def load_imu(path) -> ImuSpec:
    """Read an IMU file (module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    ImuSpec

    Raises
    ------
    ValueError
        Naming the file (and the table and key): not found, not a regular
        file, too large, not UTF-8, not TOML, an unknown key, a missing
        ``sample_rate_hz``, a value of the wrong kind, sign or length.

    Examples
    --------
    >>> imu = example_imu("tactical")
    >>> imu.name, imu.sample_rate
    ('tactical-grade IMU (example)', 200.0)
    """
    path = Path(path)
    data = read_toml(path, max_bytes=MAX_FILE_BYTES, max_depth=3, kind="IMU file")
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise ValueError(f"{path}: unknown key {unknown[0]!r} at the top level (known: name, sample_rate_hz, [gyro], [accel])")
    if "sample_rate_hz" not in data:
        raise ValueError(f"{path}: missing sample_rate_hz (the IMU's sample rate [Hz])")
    rate = _number(path, "top level", "sample_rate_hz", data["sample_rate_hz"])
    if not rate > 0:
        raise ValueError(f"{path}: sample_rate_hz: expected a rate > 0 [Hz], got {rate:g}")
    name = data.get("name", path.stem)
    if not isinstance(name, str):
        raise ValueError(f"{path}: name: expected a string, got {name!r}"[:200])
    try:
        return ImuSpec(name, rate, _triad(path, data, "gyro", _GYRO_KEYS), _triad(path, data, "accel", _ACCEL_KEYS))
    except (TypeError, ValueError) as exc:
        if str(exc).startswith(str(path)):
            raise
        raise ValueError(f"{path}: {exc}") from None


def example_imu(name: str) -> ImuSpec:
    """One of the example IMU files shipped with the package (:data:`EXAMPLE_IMUS`).

    Parameters
    ----------
    name : str
        ``"tactical"`` or ``"mems"``.

    Returns
    -------
    ImuSpec

    Raises
    ------
    ValueError
        For another name.
    """
    if name not in EXAMPLE_IMUS:
        raise ValueError(f"Expected `name` in {EXAMPLE_IMUS}, got {name!r}")
    with resources.as_file(resources.files("strapdown.analysis.navigation.imus") / f"{name}.toml") as p:
        return load_imu(p)
