"""A vibration environment: deterministic lines, random spectra and the sensors that see them.

An :class:`Environment` holds what a designer knows about the motion of
their IMU and its sensors, in SI units:

* **lines** (:class:`VibrationLine`): sinusoids of one frequency f on the
  six channels ``(ωx, ωy, ωz, ax, ay, az)`` — body angular rate [rad/s] and
  specific force [m/s²] — each channel ``Re(Z_c e^{i 2π f t})`` with a complex
  amplitude ``Z_c``.  A classical coning line, a classical sculling line and
  any other sinusoidal vibration are such lines;
* **spectra** (:class:`Spectrum`): stationary random vibration, a table of
  frequency against the one-sided cross-spectral density matrix ``G(f)`` of
  the six channels;
* the **gyro** and **accelerometer** triads (:class:`~strapdown.analysis.vibration.sensor_dynamics.Sensor`):
  analog filters, digital filters and decimation.

Conventions
-----------
Amplitudes are those of the *first-order* (in the vibration amplitude) body
rate and specific force.  Second-order constant parts (the axial rate of a
cone, the rectified specific force) pass the sensors unchanged (unit gain at
zero frequency) and do not enter the mean drift of an algorithm at second order
(:mod:`strapdown.analysis.vibration.drift`).

Cross-spectral densities are one-sided, after Bendat & Piersol:
``G_ab(f) = 2 S_ab(f)``, ``S_ab(f) = ∫ R_ab(τ) e^{−i2πfτ} dτ`` with
``R_ab(τ) = E[x_a(t) x_b(t + τ)]``, so that
``E[x_a(t) x_b(t + τ)] = ∫₀^∞ Re(G_ab(f) e^{i2πfτ}) df``.  A line
``x = Re(Z e^{i2πf₀t})`` has ``G_ab = ½ conj(Z_a) Z_b δ(f − f₀)``.  For coning
about +z in the positive sense (x leading y by a quarter period) the quadrature
part is negative: ``Im G_xy < 0``.

Between the frequencies of a table the auto-spectra are interpolated
linearly in log–log coordinates and the coherences
``γ_ab = G_ab / √(G_aa G_bb)`` linearly in log f; a convex combination of
correlation matrices is one, so the interpolated matrix stays positive
semidefinite.  Outside its table a spectrum is zero.

Files
-----
:func:`load_environment` reads the TOML format of ``docs/environment-files.md``;
every key is checked, and a bad one is refused with the file, the table and
the key in the message.

Public API
----------
.. autosummary::

   CHANNELS
   unit_vector
   orthonormal_pair
   VibrationLine
   Spectrum
   Environment
   coning_line
   sculling_line
   load_environment
   ENVIRONMENT_LIMITS
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from ...derivations.toml_files import read_toml
from ..core.units import DEG, STANDARD_GRAVITY
from ..core.validation import as_array, as_float, positive
from .sensor_dynamics import ANALOG_KINDS, DIGITAL_KINDS, ChannelFilter, Sensor, analog_filter, digital_filter

__all__ = ["CHANNELS", "unit_vector", "orthonormal_pair", "VibrationLine", "Spectrum", "Environment", "coning_line", "sculling_line", "load_environment", "EnvironmentLimits", "ENVIRONMENT_LIMITS"]

#: The six channels, in order: body angular rate ω [rad/s], specific force a [m/s²].
CHANNELS = ("wx", "wy", "wz", "ax", "ay", "az")


# --------------------------------------------------------------------------- lines
def unit_vector(v, name: str) -> np.ndarray:
    """``v`` normalised, refusing a zero or malformed vector (the message names ``name``).

    Parameters
    ----------
    v : array_like of three
        The vector.
    name : str
        Argument name for the message.

    Returns
    -------
    ndarray (3,)
    """
    arr = as_array(v, name)
    if arr.shape != (3,):
        raise ValueError(f"Expected `{name}` as three numbers, got shape {arr.shape}")
    n = float(np.linalg.norm(arr))
    if n == 0.0:
        raise ValueError(f"Expected `{name}` to be a nonzero vector, got {arr.tolist()}")
    return arr / n


def orthonormal_pair(w: np.ndarray) -> tuple:
    """A right-handed orthonormal pair (u, v) with u × v = w (w a unit vector).

    Parameters
    ----------
    w : ndarray (3,)
        Unit vector.

    Returns
    -------
    tuple of ndarray
    """
    k = int(np.argmin(np.abs(w)))
    e = np.zeros(3)
    e[k] = 1.0
    u = np.cross(w, e)
    u /= np.linalg.norm(u)
    return u, np.cross(w, u)


@dataclass(frozen=True, eq=False)
class VibrationLine:
    """A sinusoidal vibration of the six channels at one frequency.

    Channel c is ``Re(amplitude[c] e^{i 2π f t})``.

    Attributes
    ----------
    frequency : float
        f [Hz], > 0.
    amplitude : ndarray of complex, shape (6,)
        ``(ωx, ωy, ωz)`` [rad/s] and ``(ax, ay, az)`` [m/s²].
    label : str
        Name for listings.
    """

    frequency: float
    amplitude: np.ndarray
    label: str = ""

    def __post_init__(self):
        object.__setattr__(self, "frequency", positive(self.frequency, "frequency"))
        z = np.asarray(self.amplitude, dtype=complex)
        if z.shape != (6,) or not np.all(np.isfinite(z)):
            raise ValueError(f"Expected `amplitude` as six finite complex numbers, got shape {z.shape}")
        z = z.copy()
        z.setflags(write=False)
        object.__setattr__(self, "amplitude", z)

    @property
    def omega(self) -> float:
        """Angular frequency ω = 2π f [rad/s]."""
        return 2.0 * math.pi * self.frequency

    @property
    def power(self) -> np.ndarray:
        """``P_ab = ½ conj(Z_a) Z_b``, the line's cross-power matrix (6, 6) (module docstring)."""
        z = self.amplitude
        return 0.5 * np.conj(z)[:, None] * z[None, :]


def coning_line(freq_hz: float, half_angle: float, *, axis=(0.0, 0.0, 1.0), phase: float = 0.0, label: str = "") -> VibrationLine:
    """Classical coning of half-cone angle α about ``axis`` at frequency f, in the positive sense.

    The body's rotation vector turns on a cone, ``θ(t) = α (cos ψ u + sin ψ v)``
    with ``ψ = 2π f t + phase`` and ``(u, v, axis)`` right-handed; its body
    rate is ``(sin α/α) θ̇`` plus a constant axial rate of order α², so the
    first-order rate amplitude is ``ω sin α (v + i u) e^{i phase}``.  A reversed
    ``axis`` cones in the opposite sense.

    Parameters
    ----------
    freq_hz : float
        Coning frequency f [Hz], > 0.
    half_angle : float
        Half-cone angle α [rad], in (0, π/2).
    axis : sequence of three float, keyword-only
        Cone axis (normalised; default +z of the body).
    phase : float, keyword-only
        Phase ψ at t = 0 [rad].
    label : str, keyword-only
        Name for listings.

    Returns
    -------
    VibrationLine

    Examples
    --------
    >>> line = coning_line(10.0, math.radians(1.0))
    >>> bool(np.allclose(np.abs(line.amplitude[:2]), 2 * math.pi * 10 * math.sin(math.radians(1.0))))
    True
    """
    f = positive(freq_hz, "freq_hz")
    a = as_float(half_angle, "half_angle")
    if not 0.0 < a < math.pi / 2:
        raise ValueError(f"Expected `half_angle` in (0, π/2) rad, got {a:g}")
    w = unit_vector(axis, "axis")
    u, v = orthonormal_pair(w)
    rate = 2.0 * math.pi * f * math.sin(a) * np.exp(1j * as_float(phase, "phase")) * (v + 1j * u)
    return VibrationLine(f, np.concatenate([rate, np.zeros(3)]), label or f"coning {f:g} Hz, {math.degrees(a):g}°")


def sculling_line(freq_hz: float, angle_amplitude: float, accel_amplitude: float, *, rotation_axis=(1.0, 0.0, 0.0), accel_axis=(0.0, 1.0, 0.0),
                  angle_phase: float = 0.0, accel_phase: float = 0.0, label: str = "") -> VibrationLine:  # fmt: skip
    """Classical sculling: ``θ = θ₀ sin(νt + φ_θ)`` about ``rotation_axis``, ``a = A sin(νt + φ_a)`` along ``accel_axis``.

    The same motion as :class:`strapdown.analysis.coning.sculling_motion.ScullingMotion`
    (there with body axes only): rate ``θ₀ ν cos(νt + φ_θ) e_r``, specific force
    ``A sin(νt + φ_a) e_a``.

    Parameters
    ----------
    freq_hz : float
        f [Hz], ν = 2π f.
    angle_amplitude : float
        θ₀ [rad].
    accel_amplitude : float
        A [m/s²].
    rotation_axis, accel_axis : sequence of three float, keyword-only
        e_r and e_a in the body frame (normalised).
    angle_phase, accel_phase : float, keyword-only
        φ_θ, φ_a [rad].
    label : str, keyword-only
        Name for listings.

    Returns
    -------
    VibrationLine
    """
    f = positive(freq_hz, "freq_hz")
    nu = 2.0 * math.pi * f
    e_r = unit_vector(rotation_axis, "rotation_axis")
    e_a = unit_vector(accel_axis, "accel_axis")
    rate = as_float(angle_amplitude, "angle_amplitude") * nu * np.exp(1j * as_float(angle_phase, "angle_phase")) * e_r
    accel = -1j * as_float(accel_amplitude, "accel_amplitude") * np.exp(1j * as_float(accel_phase, "accel_phase")) * e_a
    return VibrationLine(f, np.concatenate([rate, accel]), label or f"sculling {f:g} Hz")


# --------------------------------------------------------------------------- spectra
@dataclass(frozen=True, eq=False)
class Spectrum:
    """Stationary random vibration: a table of the one-sided cross-spectral density of the six channels.

    Attributes
    ----------
    frequency : ndarray, shape (K,)
        Table frequencies [Hz], increasing, > 0 (K ≥ 2).
    density : ndarray of complex, shape (K, 6, 6)
        ``G(f)`` at the table frequencies, Hermitian positive semidefinite
        [(rad/s)²/Hz, (rad/s)(m/s²)/Hz, (m/s²)²/Hz] (module docstring).
    label : str
        Name for listings.

    Raises
    ------
    ValueError
        Frequencies not increasing or not positive, a matrix that is not
        Hermitian positive semidefinite.
    """

    frequency: np.ndarray
    density: np.ndarray
    label: str = ""

    def __post_init__(self):
        f = as_array(self.frequency, "frequency")
        if f.ndim != 1 or f.size < 2:
            raise ValueError(f"Expected `frequency` with at least two values, got shape {f.shape}")
        if np.any(f <= 0) or np.any(np.diff(f) <= 0):
            raise ValueError("Expected `frequency` positive and strictly increasing")
        g = np.asarray(self.density, dtype=complex)
        if g.shape != (f.size, 6, 6) or not np.all(np.isfinite(g)):
            raise ValueError(f"Expected `density` of shape ({f.size}, 6, 6), finite, got shape {g.shape}")
        scale = np.maximum(np.max(np.abs(g), axis=(1, 2)), 1e-300)
        if np.any(np.max(np.abs(g - np.conj(np.swapaxes(g, 1, 2))), axis=(1, 2)) > 1e-12 * scale):
            raise ValueError("Expected `density` Hermitian at every frequency")
        g = 0.5 * (g + np.conj(np.swapaxes(g, 1, 2)))
        low = np.linalg.eigvalsh(g)[:, 0]
        bad = np.nonzero(low < -1e-9 * scale)[0]
        if bad.size:
            raise ValueError(f"Expected `density` positive semidefinite (coherences at most 1), got a negative eigenvalue at {f[bad[0]]:g} Hz")
        f, g = f.copy(), g.copy()
        f.setflags(write=False)
        g.setflags(write=False)
        object.__setattr__(self, "frequency", f)
        object.__setattr__(self, "density", g)

    @property
    def band(self) -> tuple:
        """``(f_min, f_max)`` [Hz]."""
        return float(self.frequency[0]), float(self.frequency[-1])

    @cached_property
    def _tables(self) -> tuple:
        """Log frequencies, auto-spectra (K, 6) and coherences (K, 6, 6) of the table, computed once."""
        auto = np.real(np.diagonal(self.density, axis1=1, axis2=2)).copy()
        root = np.sqrt(auto)
        denom = root[:, :, None] * root[:, None, :]
        with np.errstate(divide="ignore", invalid="ignore"):
            coherence = np.where(denom > 0, self.density / np.where(denom > 0, denom, 1.0), 0.0)
        with np.errstate(divide="ignore"):
            log_auto = np.log(np.where(auto > 0, auto, 1.0))
        return np.log(self.frequency), auto, log_auto, coherence

    def _interpolation(self, flat: np.ndarray) -> tuple:
        """Table interval, weight t in log f, inside-mask and interpolated auto-spectra (n, 6) of the frequencies ``flat``."""
        table = self.frequency
        logf, auto, log_auto, _ = self._tables
        inside = (flat >= table[0]) & (flat <= table[-1])
        idx = np.clip(np.searchsorted(table, flat, side="right") - 1, 0, table.size - 2)
        lf = np.log(np.where(inside, flat, table[0]))
        lo, hi = logf[idx], logf[idx + 1]
        t = ((lf - lo) / (hi - lo))[:, None]
        a0, a1 = auto[idx], auto[idx + 1]
        both = (a0 > 0) & (a1 > 0)
        loglog = np.exp(log_auto[idx] * (1 - t) + log_auto[idx + 1] * t)
        psd = np.where(both, loglog, a0 * (1 - t) + a1 * t)
        psd[~inside] = 0.0
        return idx, t, inside, psd

    def at(self, freq) -> np.ndarray:
        """``G(f)`` interpolated (module docstring), zero outside the table; shape ``f.shape + (6, 6)``.

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz].

        Returns
        -------
        ndarray of complex
        """
        f = np.asarray(freq, dtype=float)
        idx, t, inside, psd = self._interpolation(f.ravel())
        coherence = self._tables[3]
        gamma = coherence[idx] * (1 - t)[:, :, None] + coherence[idx + 1] * t[:, :, None]
        r = np.sqrt(psd)
        out = gamma * r[:, :, None] * r[:, None, :]
        idx6 = np.arange(6)
        out[:, idx6, idx6] = psd
        out[~inside] = 0.0
        return out.reshape(f.shape + (6, 6))

    def entries(self, freq, rows, cols) -> np.ndarray:
        """The entries ``G_ab(f)`` for ``a, b`` in ``zip(rows, cols)`` only, as :meth:`at` interpolates them.

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz].
        rows, cols : sequence of int
            Channel indices a, b (0 … 5, the order of :data:`CHANNELS`).

        Returns
        -------
        ndarray of complex, shape ``f.shape + (len(rows),)``
        """
        f = np.asarray(freq, dtype=float)
        a, b = np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)
        idx, t, inside, psd = self._interpolation(f.ravel())
        coherence = self._tables[3][:, a, b]
        gamma = coherence[idx] * (1 - t) + coherence[idx + 1] * t
        out = np.where(a == b, psd[:, a], gamma * np.sqrt(psd[:, a] * psd[:, b]))
        out[~inside] = 0.0
        return out.reshape(f.shape + (a.size,))

    def trace_density(self, freq, *, weights=None) -> np.ndarray:
        """``Σ_c w_c G_cc(f)``, the weighted sum of the auto-spectra.

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz].
        weights : array_like of six, keyword-only
            Weights of the channels (default 1).

        Returns
        -------
        ndarray
        """
        w = np.ones(6) if weights is None else np.asarray(weights, dtype=float)
        g = self.at(freq)
        return np.real(np.einsum("...cc,c->...", g, w))


# --------------------------------------------------------------------------- environment
@dataclass(frozen=True, eq=False)
class Environment:
    """Lines, spectra and sensors: what a strapdown algorithm will face.

    Attributes
    ----------
    lines : tuple of VibrationLine
    spectra : tuple of Spectrum
    gyro : Sensor
        Gyro triad (filters, decimation).
    accelerometer : Sensor
        Accelerometer triad; its decimation is that of the gyro.
    name : str
    description : str
    """

    lines: tuple = ()
    spectra: tuple = ()
    gyro: Sensor = field(default_factory=Sensor)
    accelerometer: Sensor = field(default_factory=Sensor)
    name: str = "environment"
    description: str = ""

    def __post_init__(self):
        object.__setattr__(self, "lines", tuple(self.lines))
        object.__setattr__(self, "spectra", tuple(self.spectra))
        if not all(isinstance(x, VibrationLine) for x in self.lines):
            raise TypeError("Expected `lines` to hold VibrationLine")
        if not all(isinstance(x, Spectrum) for x in self.spectra):
            raise TypeError("Expected `spectra` to hold Spectrum")
        if not isinstance(self.gyro, Sensor) or not isinstance(self.accelerometer, Sensor):
            raise TypeError("Expected `gyro` and `accelerometer` to be Sensor")
        if self.gyro.decimation != self.accelerometer.decimation:
            raise ValueError(f"Expected the gyro and accelerometer at one decimation, got {self.gyro.decimation} and {self.accelerometer.decimation}")

    @property
    def decimation(self) -> int:
        """Sensor samples per algorithm sample [count]."""
        return self.gyro.decimation

    def response(self, omega, sample_interval: float) -> np.ndarray:
        """Equivalent responses of the six channels (gyro x, y, z, accelerometer x, y, z), shape ``omega.shape + (6,)``.

        Parameters
        ----------
        omega : array_like
            Angular frequencies [rad/s].
        sample_interval : float
            Algorithm sample interval h [s].

        Returns
        -------
        ndarray of complex
        """
        gyro = self.gyro.response(omega, sample_interval)
        accel = gyro if self.accelerometer == self.gyro else self.accelerometer.response(omega, sample_interval)
        return np.concatenate([gyro, accel], axis=-1)

    def with_sensors(self, gyro: Sensor | None = None, accelerometer: Sensor | None = None) -> Environment:
        """The same vibration seen through other sensors.

        Parameters
        ----------
        gyro, accelerometer : Sensor, optional
            Replacements (default: keep; a kept triad takes the decimation of the replaced one).

        Returns
        -------
        Environment
        """
        if gyro is not None and accelerometer is None:
            accelerometer = Sensor(self.accelerometer.axes, gyro.decimation)
        if accelerometer is not None and gyro is None:
            gyro = Sensor(self.gyro.axes, accelerometer.decimation)
        return Environment(self.lines, self.spectra, gyro, accelerometer, self.name, self.description)

    @property
    def has_motion(self) -> bool:
        """Some line or spectrum has a nonzero amplitude or density."""
        return any(np.any(ln.amplitude != 0) for ln in self.lines) or any(np.any(sp.density != 0) for sp in self.spectra)

    def rotation_amplitude(self) -> float:
        """Bound on the rotation-vector amplitude θ of the vibration [rad]: ``Σ |A|/ω`` over the lines plus 3σ of the spectra's angle.

        The spectra's angle variance ``∫ Σ_c G_cc(f)/ω² df`` (rate channels) is
        taken by the trapezoidal rule in ln f on the table.

        Returns
        -------
        float
        """
        lines = sum(float(np.linalg.norm(ln.amplitude[:3])) / ln.omega for ln in self.lines)
        var = 0.0
        for sp in self.spectra:
            f = sp.frequency
            g = np.real(np.trace(sp.density[:, :3, :3], axis1=1, axis2=2)) / (2.0 * math.pi * f) ** 2 * f
            var += float(np.trapezoid(g, np.log(f)))
        return lines + 3.0 * math.sqrt(var)

    def rate_amplitude(self) -> float:
        """Bound on the body-rate amplitude Ω [rad/s]: ``Σ |A|`` over the lines plus 3σ of the spectra's rate.

        Returns
        -------
        float
        """
        lines = sum(float(np.linalg.norm(ln.amplitude[:3])) for ln in self.lines)
        var = 0.0
        for sp in self.spectra:
            f = sp.frequency
            var += float(np.trapezoid(np.real(np.trace(sp.density[:, :3, :3], axis1=1, axis2=2)) * f, np.log(f)))
        return lines + 3.0 * math.sqrt(var)

    @property
    def frequency_range(self) -> tuple:
        """Lowest and highest frequency of any line or spectrum [Hz] (None if empty)."""
        values = [ln.frequency for ln in self.lines] + [f for s in self.spectra for f in s.band]
        return (min(values), max(values)) if values else None


# --------------------------------------------------------------------------- files
#: Deepest nesting of an environment file [levels]: [[spectrum]] → table = [[f, [re, im]], …].
_MAX_DEPTH = 8


@dataclass(frozen=True)
class EnvironmentLimits:
    """Limits of an environment file, checked before any arithmetic.

    Attributes
    ----------
    file_bytes : int
        Largest file size [bytes].
    lines : int
        Most lines of all kinds [count].
    spectra : int
        Most spectra [count].
    table : int
        Most rows of a spectrum table [count].
    text : int
        Longest string [characters].
    """

    file_bytes: int = 4 * 1024 * 1024
    lines: int = 1000
    spectra: int = 64
    table: int = 100_000
    text: int = 1000


#: The limits :func:`load_environment` applies by default.
ENVIRONMENT_LIMITS = EnvironmentLimits()

_TOP = {"name", "description", "line", "sculling_line", "vibration_line", "spectrum", "gyro", "accelerometer", "sampling"}
_CONING_KEYS = {"freq_hz", "half_angle_deg", "axis", "phase_deg", "label"}
_SCULLING_KEYS = {"freq_hz", "angle_amplitude_deg", "accel_amplitude_m_s2", "rotation_axis", "accel_axis", "angle_phase_deg", "accel_phase_deg", "label"}
_VIBRATION_KEYS = {"freq_hz", "rate_amplitude_deg_s", "rate_phase_deg", "accel_amplitude_m_s2", "accel_phase_deg", "label"}
_ANALOG_KEYS = {"filter", "cutoff_hz", "order", "num", "den"}
_DIGITAL_KEYS = {"digital", "digital_b", "digital_a", "digital_cutoff_hz", "digital_order", "digital_taps"}
_RATE_UNITS = {"rad/s": 1.0, "deg/s": DEG}
_ACCEL_UNITS = {"m/s2": 1.0, "g": STANDARD_GRAVITY}


def _show(value, width: int = 40) -> str:
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


class _Reader:
    """Typed access to one table of the file, with messages naming file, table and key."""

    def __init__(self, path: Path, where: str, table: dict, allowed: set, limits: EnvironmentLimits):
        self.path, self.where, self.table, self.limits = path, where, table, limits
        if not isinstance(table, dict):
            raise ValueError(f"{path}: {where} must be a table, got {type(table).__name__}")
        extra = sorted(set(table) - allowed)
        if extra:
            raise ValueError(f"{path}: {where} unknown key {_show(extra[0])} (expected one of {', '.join(sorted(allowed))})")

    def fail(self, key: str, expected: str, got) -> ValueError:
        return ValueError(f"{self.path}: {self.where} key {key!r}: expected {expected}, got {_show(got)}")

    def has(self, key: str) -> bool:
        return key in self.table

    def number(self, key: str, default=None, *, low=None, high=None, open_low=False, required=False) -> float:
        if key not in self.table:
            if required:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r}")
            return default
        v = self.table[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
            raise self.fail(key, "a finite number", v)
        v = float(v)
        if low is not None and (v < low or (open_low and v == low)):
            raise self.fail(key, f"a number {'>' if open_low else '≥'} {low:g}", v)
        if high is not None and v > high:
            raise self.fail(key, f"a number ≤ {high:g}", v)
        return v

    def integer(self, key: str, default=None, *, low: int = 1, high: int = 10**6) -> int:
        if key not in self.table:
            return default
        v = self.table[key]
        if isinstance(v, bool) or not isinstance(v, int) or not low <= v <= high:
            raise self.fail(key, f"a whole number in {low}..{high}", v)
        return v

    def text(self, key: str, default: str = "") -> str:
        if key not in self.table:
            return default
        v = self.table[key]
        if not isinstance(v, str) or len(v) > self.limits.text:
            raise self.fail(key, f"a string of at most {self.limits.text} characters", v)
        return v

    def choice(self, key: str, choices, default: str) -> str:
        if key not in self.table:
            return default
        v = self.table[key]
        if v not in choices:
            raise self.fail(key, f"one of {', '.join(repr(c) for c in choices)}", v)
        return v

    def numbers(self, key: str, default=None, *, size: int | None = None, low=None, max_size: int = 10**6, required=False) -> np.ndarray:
        if key not in self.table:
            if required:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r}")
            return None if default is None else np.asarray(default, dtype=float)
        v = self.table[key]
        what = f"a list of {size} numbers" if size else "a list of numbers"
        if not isinstance(v, list) or (size is not None and len(v) != size) or len(v) > max_size or not v:
            raise self.fail(key, what, v)
        if any(isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(float(x)) for x in v):
            raise self.fail(key, what + " (finite)", v)
        arr = np.asarray(v, dtype=float)
        if low is not None and np.any(arr < low):
            raise self.fail(key, f"{what}, each ≥ {low:g}", v)
        return arr

    def complexes(self, key: str, size: int) -> np.ndarray:
        v = self.table[key]
        what = f"a list of {size} pairs [re, im]"
        if not isinstance(v, list) or len(v) != size:
            raise self.fail(key, what, v)
        out = np.empty(size, dtype=complex)
        for i, pair in enumerate(v):
            if (not isinstance(pair, list) or len(pair) != 2
                    or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(float(x)) for x in pair)):  # fmt: skip
                raise ValueError(f"{self.path}: {self.where} key {key!r} entry {i}: expected a pair [re, im] of finite numbers, got {_show(pair)}")
            out[i] = complex(float(pair[0]), float(pair[1]))
        return out

    def vector(self, key: str, default) -> np.ndarray:
        arr = self.numbers(key, default, size=3)
        if np.linalg.norm(arr) == 0.0:
            raise self.fail(key, "a nonzero vector of three numbers", self.table.get(key))
        return arr


def _read_file(path: Path, limits: EnvironmentLimits) -> dict:
    # lines and spectra are arrays of tables holding arrays of pairs: four levels at most
    return read_toml(path, max_bytes=limits.file_bytes, max_depth=_MAX_DEPTH, kind="environment file")


def _array_of_tables(path: Path, data: dict, key: str) -> list:
    v = data.get(key, [])
    if not isinstance(v, list) or not all(isinstance(t, dict) for t in v):
        raise ValueError(f"{path}: {key!r} must be an array of tables ([[{key}]]), got {type(v).__name__}")
    return v


def _channel(path: Path, where: str, table: dict, limits) -> ChannelFilter:
    r = _Reader(path, where, table, _ANALOG_KEYS | _DIGITAL_KEYS, limits)
    kind = r.choice("filter", ANALOG_KINDS, "none")
    uses = {"none": set(), "lowpass1": {"cutoff_hz"}, "butterworth": {"cutoff_hz", "order"}, "bessel": {"cutoff_hz", "order"}, "transfer_function": {"num", "den"}}[kind]
    for key in sorted((_ANALOG_KEYS - {"filter"}) - uses):
        if r.has(key):
            raise ValueError(f"{path}: {where} key {key!r} does not apply to filter = {kind!r}")
    try:
        if kind in ("lowpass1", "butterworth", "bessel"):
            analog = analog_filter(kind, cutoff_hz=r.number("cutoff_hz", low=0.0, open_low=True, required=True), order=r.integer("order", None, low=1, high=16))
        elif kind == "transfer_function":
            analog = analog_filter(kind, num=r.numbers("num", required=True, max_size=17), den=r.numbers("den", required=True, max_size=17))
        else:
            analog = analog_filter("none")
    except ValueError as exc:
        raise ValueError(f"{path}: {where} analog filter: {exc}") from None
    dkind = r.choice("digital", DIGITAL_KINDS, "none")
    duses = {"none": set(), "coefficients": {"digital_b", "digital_a"}, "butterworth": {"digital_cutoff_hz", "digital_order"}, "moving_average": {"digital_taps"}}[dkind]
    for key in sorted((_DIGITAL_KEYS - {"digital"}) - duses):
        if r.has(key):
            raise ValueError(f"{path}: {where} key {key!r} does not apply to digital = {dkind!r}")
    try:
        if dkind == "coefficients":
            digital = digital_filter(dkind, b=r.numbers("digital_b", required=True, max_size=17), a=r.numbers("digital_a", [1.0], max_size=17))
        elif dkind == "butterworth":
            digital = digital_filter(dkind, cutoff_hz=r.number("digital_cutoff_hz", low=0.0, open_low=True, required=True), order=r.integer("digital_order", 2, low=1, high=16))
        elif dkind == "moving_average":
            taps = r.integer("digital_taps", None, low=1, high=1024)
            if taps is None:
                raise ValueError(f"{path}: {where} missing key 'digital_taps'")
            digital = digital_filter(dkind, taps=taps)
        else:
            digital = digital_filter("none")
    except ValueError as exc:
        if str(exc).startswith(str(path)):
            raise
        raise ValueError(f"{path}: {where} digital filter: {exc}") from None
    return ChannelFilter(analog, digital)


def _sensor(path: Path, data: dict, key: str, decimation: int, limits) -> Sensor:
    table = data.get(key, {})
    if not isinstance(table, dict):
        raise ValueError(f"{path}: [{key}] must be a table, got {type(table).__name__}")
    axes_tables = {a: table[a] for a in ("x", "y", "z") if a in table}
    shared = {k: v for k, v in table.items() if k not in ("x", "y", "z")}
    _Reader(path, f"[{key}]", shared, _ANALOG_KEYS | _DIGITAL_KEYS, limits)  # unknown keys
    axes = []
    for a in ("x", "y", "z"):
        own = axes_tables.get(a, {})
        if not isinstance(own, dict):
            raise ValueError(f"{path}: [{key}.{a}] must be a table, got {type(own).__name__}")
        merged = dict(shared)
        if "filter" in own:
            merged = {k: v for k, v in merged.items() if k not in _ANALOG_KEYS}
        if "digital" in own:
            merged = {k: v for k, v in merged.items() if k not in _DIGITAL_KEYS}
        merged.update(own)
        where = f"[{key}.{a}]" if a in axes_tables else f"[{key}]"
        axes.append(_channel(path, where, merged, limits))
    return Sensor(tuple(axes), decimation)


def _spectrum(path: Path, index: int, table: dict, limits) -> Spectrum:
    pairs = {f"{a}_{b}" for i, a in enumerate(CHANNELS) for b in CHANNELS[i + 1 :]}
    where = f"[[spectrum]] #{index + 1}"
    r = _Reader(path, where, table, {"freq_hz", "rate_unit", "accel_unit", "label"} | set(CHANNELS) | pairs, limits)
    freq = r.numbers("freq_hz", required=True, max_size=limits.table)
    if freq.size < 2 or np.any(freq <= 0) or np.any(np.diff(freq) <= 0):
        raise r.fail("freq_hz", "at least two frequencies, positive and strictly increasing", table["freq_hz"])
    rate_scale = _RATE_UNITS[r.choice("rate_unit", tuple(_RATE_UNITS), "rad/s")]
    accel_scale = _ACCEL_UNITS[r.choice("accel_unit", tuple(_ACCEL_UNITS), "m/s2")]
    scale = np.array([rate_scale] * 3 + [accel_scale] * 3)
    g = np.zeros((freq.size, 6, 6), dtype=complex)
    present = [c for c in CHANNELS if r.has(c)]
    if not present:
        raise ValueError(f"{path}: {where} has no auto-spectrum (expected at least one of {', '.join(CHANNELS)})")
    for i, c in enumerate(CHANNELS):
        if r.has(c):
            g[:, i, i] = r.numbers(c, size=freq.size, low=0.0) * scale[i] ** 2
    for i, a in enumerate(CHANNELS):
        for j in range(i + 1, 6):
            key = f"{a}_{CHANNELS[j]}"
            if r.has(key):
                if not (r.has(a) and r.has(CHANNELS[j])):
                    raise ValueError(f"{path}: {where} key {key!r} needs the auto-spectra {a!r} and {CHANNELS[j]!r}")
                v = r.complexes(key, freq.size) * scale[i] * scale[j]
                g[:, i, j] = v
                g[:, j, i] = np.conj(v)
    try:
        return Spectrum(freq, g, r.text("label", f"spectrum {index + 1}"))
    except ValueError as exc:
        raise ValueError(f"{path}: {where}: {exc}") from None


def load_environment(path, *, limits: EnvironmentLimits = ENVIRONMENT_LIMITS) -> Environment:
    """Read an environment file (TOML; format in ``docs/environment-files.md``).

    Parameters
    ----------
    path : str or Path
        The file.
    limits : EnvironmentLimits, keyword-only
        Limits of the file (default :data:`ENVIRONMENT_LIMITS`).

    Returns
    -------
    Environment

    Raises
    ------
    ValueError
        A file that cannot be read or is not valid TOML, an unknown key, a
        missing one, a value of the wrong kind or out of range, a filter that is
        unstable or has a gain other than 1 at zero frequency, a spectrum that
        is not positive semidefinite; the message names the file, the table
        and the key.
    TypeError
        If ``path`` is not a path (str or os.PathLike).
    """
    if not isinstance(path, (str, os.PathLike)):
        text = repr(path) if len(repr(path)) <= 60 else repr(path)[:57] + "..."
        raise TypeError(f"Expected `path` to be a file path (str or os.PathLike), got {type(path).__name__} {text}")
    path = Path(path)
    data = _read_file(path, limits)
    top = _Reader(path, "top level", data, _TOP, limits)
    lines = []
    coning = _array_of_tables(path, data, "line")
    sculling = _array_of_tables(path, data, "sculling_line")
    vibration = _array_of_tables(path, data, "vibration_line")
    if len(coning) + len(sculling) + len(vibration) > limits.lines:
        raise ValueError(f"{path}: more than the limit of {limits.lines} lines")
    for i, t in enumerate(coning):
        r = _Reader(path, f"[[line]] #{i + 1}", t, _CONING_KEYS, limits)
        f = r.number("freq_hz", low=0.0, open_low=True, required=True)
        a = r.number("half_angle_deg", low=0.0, open_low=True, high=45.0, required=True)
        lines.append(coning_line(f, a * DEG, axis=r.vector("axis", [0.0, 0.0, 1.0]), phase=r.number("phase_deg", 0.0) * DEG, label=r.text("label", "")))
    for i, t in enumerate(sculling):
        r = _Reader(path, f"[[sculling_line]] #{i + 1}", t, _SCULLING_KEYS, limits)
        f = r.number("freq_hz", low=0.0, open_low=True, required=True)
        lines.append(
            sculling_line(
                f,
                r.number("angle_amplitude_deg", low=0.0, high=45.0, required=True) * DEG,
                r.number("accel_amplitude_m_s2", low=0.0, required=True),
                rotation_axis=r.vector("rotation_axis", [1.0, 0.0, 0.0]),
                accel_axis=r.vector("accel_axis", [0.0, 1.0, 0.0]),
                angle_phase=r.number("angle_phase_deg", 0.0) * DEG,
                accel_phase=r.number("accel_phase_deg", 0.0) * DEG,
                label=r.text("label", ""),
            )
        )
    for i, t in enumerate(vibration):
        r = _Reader(path, f"[[vibration_line]] #{i + 1}", t, _VIBRATION_KEYS, limits)
        f = r.number("freq_hz", low=0.0, open_low=True, required=True)
        rate = r.numbers("rate_amplitude_deg_s", [0.0] * 3, size=3, low=0.0) * DEG * np.exp(1j * r.numbers("rate_phase_deg", [0.0] * 3, size=3) * DEG)
        accel = r.numbers("accel_amplitude_m_s2", [0.0] * 3, size=3, low=0.0) * np.exp(1j * r.numbers("accel_phase_deg", [0.0] * 3, size=3) * DEG)
        lines.append(VibrationLine(f, np.concatenate([rate, accel]), r.text("label", f"vibration {f:g} Hz")))
    spectra_tables = _array_of_tables(path, data, "spectrum")
    if len(spectra_tables) > limits.spectra:
        raise ValueError(f"{path}: more than the limit of {limits.spectra} spectra")
    spectra = [_spectrum(path, i, t, limits) for i, t in enumerate(spectra_tables)]
    sampling = data.get("sampling", {})
    rs = _Reader(path, "[sampling]", sampling, {"decimation"}, limits)
    decimation = rs.integer("decimation", 1, low=1, high=1024)
    gyro = _sensor(path, data, "gyro", decimation, limits)
    accel = _sensor(path, data, "accelerometer", decimation, limits)
    return Environment(tuple(lines), tuple(spectra), gyro, accel, top.text("name", path.stem), top.text("description", ""))
