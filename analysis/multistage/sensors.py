"""Gyro and accelerometer error model, and the sampled sensor record.

The gyro triad delivers rotation-vector increments over each step h and the
accelerometer triad the mean specific force over each step, both in the body
frame x.  The errors of each triad are a scale factor, a constant bias and
white noise:

* gyro: ``Δφ_meas = (1 + s_g) Δφ + d h + N_g √h n``, with d the drift [rad/s]
  and N_g the angle random walk [rad/√s];
* accelerometer: ``f_meas = (1 + s_a) f + b + N_a/√h n``, with b the bias
  [m/s²] and N_a the velocity random walk [m/s/√s];

n standard normal, one draw per axis and step.  Noise streams are spawned
from the ``rng`` argument (one for the gyros, one for the accelerometers).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..core.validation import as_array, nonnegative

__all__ = ["SensorErrors", "SensorData", "corrupt"]


def _triple(x, name) -> tuple:
    arr = as_array(x, name)
    if arr.shape == ():
        arr = np.full(3, float(arr))
    if arr.shape != (3,):
        raise ValueError(f"Expected `{name}` to be a scalar or 3 components, got shape {arr.shape}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class SensorErrors:
    """Gyro and accelerometer errors, per axis of the body frame x.

    Parameters
    ----------
    gyro_scale : float or 3 floats
        Gyro scale-factor error [-].
    gyro_drift : float or 3 floats
        Gyro bias (drift) [rad/s].
    gyro_noise : float
        Angle random walk: white rate noise density [rad/√s], >= 0.
    accel_scale : float or 3 floats
        Accelerometer scale-factor error [-].
    accel_bias : float or 3 floats
        Accelerometer bias [m/s²].
    accel_noise : float
        Velocity random walk: white specific-force noise density [m/s/√s], >= 0.

    Examples
    --------
    >>> SensorErrors.plotnikov_1999().gyro_drift
    (5e-08, -5e-08, 5e-08)
    """

    gyro_scale: tuple = (0.0, 0.0, 0.0)
    gyro_drift: tuple = (0.0, 0.0, 0.0)
    gyro_noise: float = 0.0
    accel_scale: tuple = (0.0, 0.0, 0.0)
    accel_bias: tuple = (0.0, 0.0, 0.0)
    accel_noise: float = 0.0

    def __post_init__(self):
        for name in ("gyro_scale", "gyro_drift", "accel_scale", "accel_bias"):
            object.__setattr__(self, name, _triple(getattr(self, name), name))
        object.__setattr__(self, "gyro_noise", nonnegative(self.gyro_noise, "gyro_noise"))
        object.__setattr__(self, "accel_noise", nonnegative(self.accel_noise, "accel_noise"))

    @classmethod
    def plotnikov_1999(cls) -> SensorErrors:
        """The errors of Plotnikov (1999), section 5.

        Scale factors 10⁻³ % for both triads; gyro drift 0.5·10⁻⁷ s⁻¹ and
        accelerometer bias 10⁻³ m/s² "with different signs by component",
        taken here as (+, −, +).  No noise is given in the paper.

        Returns
        -------
        SensorErrors
        """
        from ...derivations.multistage.published import SECTION5

        signs = np.array([1.0, -1.0, 1.0])
        return cls(
            gyro_scale=SECTION5.scale_factor_error,
            gyro_drift=tuple(SECTION5.gyro_drift * signs),
            accel_scale=SECTION5.scale_factor_error,
            accel_bias=tuple(SECTION5.accel_bias * signs),
        )

    @property
    def is_ideal(self) -> bool:
        """True if every error is zero."""
        return not any(any(getattr(self, n)) for n in ("gyro_scale", "gyro_drift", "accel_scale", "accel_bias")) and self.gyro_noise == 0 and self.accel_noise == 0


@dataclass(frozen=True)
class SensorData:
    """Sampled truth and sensor signals on a uniform grid.

    Attributes
    ----------
    time : ndarray, shape (N+1,)
        Grid t_n = n h [s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    gyro : ndarray, shape (N, 3)
        Measured rotation-vector increments of the body over [t_n, t_{n+1}] [rad].
    accel : ndarray, shape (N, 3)
        Measured mean specific force in x over [t_n, t_{n+1}] [m/s²].
    attitude : ndarray, shape (N+1, 4)
        True μ(t_n), body x → azimuth-free horizontal frame η.
    angles : ndarray, shape (N+1, 3)
        True Krylov angles (ψ, θ, γ)(t_n) of the body relative to η [rad].
    velocity : ndarray, shape (N+1,)
        Northward ground speed [m/s].
    scenario : object
        The :class:`strapdown.analysis.multistage.trajectory.Scenario` sampled.
    """

    time: np.ndarray
    step: float
    gyro: np.ndarray
    accel: np.ndarray
    attitude: np.ndarray
    angles: np.ndarray
    velocity: np.ndarray
    scenario: object


def corrupt(data: SensorData, errors: SensorErrors, *, rng=None) -> SensorData:
    """Add sensor errors to an ideal record.

    Parameters
    ----------
    data : SensorData
        Record whose ``gyro`` and ``accel`` are the ideal signals.
    errors : SensorErrors
        The errors to add.
    rng : numpy.random.Generator, int, SeedSequence or None
        Source of the noise; two streams are spawned (gyro, accelerometer), so
        the gyro noise does not depend on whether accelerometer noise is drawn.

    Returns
    -------
    SensorData
        A copy with the measured signals.

    Raises
    ------
    TypeError
        If ``data`` or ``errors`` has the wrong type.
    """
    if not isinstance(data, SensorData):
        raise TypeError(f"Expected `data` to be a SensorData, got {type(data).__name__}")
    if not isinstance(errors, SensorErrors):
        raise TypeError(f"Expected `errors` to be a SensorErrors, got {type(errors).__name__}")
    h = data.step
    gyro_rng, accel_rng = np.random.default_rng(rng).spawn(2)
    # Δφ_meas = (1 + s_g) Δφ + d h + N_g √h n and f_meas = (1 + s_a) f + b + N_a/√h n, in one pass per triad
    gyro = _measured(data.gyro, errors.gyro_scale, np.asarray(errors.gyro_drift) * h, gyro_rng, errors.gyro_noise * np.sqrt(h) if errors.gyro_noise > 0.0 else None, "gyro")
    accel = _measured(data.accel, errors.accel_scale, np.asarray(errors.accel_bias), accel_rng, errors.accel_noise / np.sqrt(h) if errors.accel_noise > 0.0 else None, "accel")
    return replace(data, gyro=gyro, accel=accel)


_compiled: dict = {}


def _measured(signal, scale, offset, rng, noise, name: str) -> np.ndarray:
    """``(1 + scale) · signal + offset + noise · n`` per axis, n standard normal from ``rng`` (no noise term for ``noise=None``)."""
    signal = np.ascontiguousarray(signal, dtype=float)
    if signal.ndim != 2 or signal.shape[1] != 3:
        raise ValueError(f"Expected `data.{name}` with shape (N, 3), got shape {signal.shape}")
    if "measure" not in _compiled:
        import numba

        _compiled["measure"] = numba.njit(cache=True, nogil=True)(_measure)
    factor = 1.0 + np.asarray(scale, dtype=float)
    if noise is None:
        return _compiled["measure"](signal, factor, offset, np.empty((0, 3)), 0.0, np.empty_like(signal))
    n = rng.standard_normal(signal.shape)
    return _compiled["measure"](signal, factor, offset, n, float(noise), n)


def _measure(signal, factor, offset, normals, noise, out):
    """``factor · signal + offset`` per axis, plus ``normals · noise`` unless ``normals`` is empty, into ``out`` (in this order of roundings)."""
    noisy = normals.shape[0] > 0
    for i in range(signal.shape[0]):
        for k in range(3):
            x = factor[k] * signal[i, k] + offset[k]
            if noisy:
                x += normals[i, k] * noise
            out[i, k] = x
    return out
