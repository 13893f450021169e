"""True motion and sensor signals of the example of Plotnikov (1999), section 5.

The body moves over a spherical, rotating Earth.  Its attitude is given by
Krylov angles (:mod:`strapdown.analysis.multistage.ship_angles`) relative to the *azimuth-free horizontal
frame* η of the paper: axis 2 up, axes 1 and 3 horizontal, and no absolute
rotation about the vertical (so the absolute rate of η has components
``(ω1, 0, ω3)``, as in (3.7)).  η coincides with the geographic frame
``ζ = (north, up, east)`` at ``t = 0`` and then turns relative to it about the
vertical at ``−Ω sin φ``.

Timeline (every constant is a field of :class:`Scenario`):

* at rest at latitude φ0;
* from ``rocking_start``: rocking
  ``ψ = A_ψ E(t) sin(ϖt + φ_ψ)``, ``θ = A_θ E(t) sin(ϖt + φ_θ)``,
  ``γ = A_γ E(t) sin(ϖt + φ_γ)`` with the envelope
  ``E(t) = exp(−d (t − t_r)) (1 − exp(−(t − t_r)/τ_on))``;
* from ``accel_start``: northward acceleration ``a`` for ``accel_duration``,
  then constant velocity.

The printed envelope ``E = exp(−0.1 (t − 600))`` is ``≈ 4·10⁻¹⁸`` at the start
of rocking (t = 1000 s), i.e. no rocking at all; the default reads the 600 as
the rocking start and adds a smooth onset ``τ_on`` so that the yaw (phase π/2)
does not jump.  Coriolis and centripetal accelerations are neglected, as in
the paper's derivation (3.7) where ``V̇ = W``.

Sensors.  The gyro triad delivers rotation-vector increments over each step
and the accelerometer triad the mean specific force over each step.  The ideal
signals are exact (the attitude is known in closed form, the frame rotation is
integrated by 3-point Gauss–Legendre quadrature); the errors are a scale
factor, a constant bias (gyro drift) and white noise drawn from a seeded
generator.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core import quaternion as quat
from ..core.validation import as_array, as_float, nonnegative, positive
from .ship_angles import angles_to_quat

__all__ = ["SensorErrors", "Scenario", "SensorData", "sample", "GAUSS3"]

#: 3-point Gauss–Legendre nodes and weights on [0, 1].
GAUSS3 = (
    np.array([0.5 - np.sqrt(0.15), 0.5, 0.5 + np.sqrt(0.15)]),
    np.array([5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0]),
)


def _triple(x, name) -> tuple:
    arr = as_array(x, name)
    if arr.shape == ():
        arr = np.full(3, float(arr))
    if arr.shape != (3,):
        raise ValueError(f"Expected `{name}` to be a scalar or 3 components, got shape {arr.shape}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class SensorErrors:
    """Gyro and accelerometer error model (per axis of the body frame x).

    Parameters
    ----------
    gyro_scale : float or 3 floats
        Gyro scale-factor error [-].
    gyro_drift : float or 3 floats
        Gyro bias (drift) [rad/s].
    gyro_noise : float
        Angle random walk: white rate noise density [rad/√s].
    accel_scale : float or 3 floats
        Accelerometer scale-factor error [-].
    accel_bias : float or 3 floats
        Accelerometer bias [m/s²].
    accel_noise : float
        Velocity random walk: white specific-force noise density [m/s/√s].

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
        """
        return cls(gyro_scale=1e-5, gyro_drift=(0.5e-7, -0.5e-7, 0.5e-7), accel_scale=1e-5, accel_bias=(1e-3, -1e-3, 1e-3))


@dataclass(frozen=True)
class Scenario:
    """The motion of Plotnikov (1999), section 5, with every constant a parameter.

    Parameters
    ----------
    duration : float
        Length of the run [s], > 0.
    latitude : float
        Initial latitude φ0 [rad], in (−π/2, π/2).
    gravity : float
        Magnitude g of gravity [m/s²], > 0.
    earth_radius : float
        Earth radius R [m], > 0.
    earth_rate : float
        Earth rotation rate Ω [rad/s], >= 0.
    rocking_start : float
        Start t_r of rocking [s].
    rocking_amplitude : 3 floats
        Amplitudes (A_ψ, A_θ, A_γ) of yaw, pitch and roll [rad].
    rocking_frequency : float
        Angular frequency ϖ of rocking [rad/s].
    rocking_phase : 3 floats
        Phases (φ_ψ, φ_θ, φ_γ) [rad].
    rocking_decay : float
        Envelope decay rate d [1/s], >= 0.
    rocking_onset : float
        Onset time constant τ_on of the envelope [s], >= 0 (0: abrupt start).
    accel_start : float
        Start of the northward acceleration [s].
    accel_duration : float
        Its duration [s], >= 0.
    accel : float
        Its magnitude [m/s²].
    sensors : SensorErrors
        Sensor errors.

    Examples
    --------
    >>> s = Scenario(duration=100.0)
    >>> round(s.schuler_frequency, 7)
    0.0012409
    """

    duration: float = 5000.0
    latitude: float = float(np.radians(45.0))
    gravity: float = 9.81
    earth_radius: float = 6.371e6
    earth_rate: float = 7.292115e-5
    rocking_start: float = 1000.0
    rocking_amplitude: tuple = (0.2, 0.1, 0.1)
    rocking_frequency: float = float(np.pi)
    rocking_phase: tuple = (0.5 * float(np.pi), 0.0, 0.0)
    rocking_decay: float = 0.1
    rocking_onset: float = 1.0
    accel_start: float = 1200.0
    accel_duration: float = 20.0
    accel: float = 20.0
    sensors: SensorErrors = field(default_factory=SensorErrors.plotnikov_1999)

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "duration", positive(self.duration, "duration"))
        lat = as_float(self.latitude, "latitude")
        if not abs(lat) < np.pi / 2:
            raise ValueError(f"Expected `latitude` in (−π/2, π/2) rad, got {lat:g}")
        set_(self, "latitude", lat)
        set_(self, "gravity", positive(self.gravity, "gravity"))
        set_(self, "earth_radius", positive(self.earth_radius, "earth_radius"))
        set_(self, "earth_rate", nonnegative(self.earth_rate, "earth_rate"))
        set_(self, "rocking_start", as_float(self.rocking_start, "rocking_start"))
        set_(self, "rocking_amplitude", _triple(self.rocking_amplitude, "rocking_amplitude"))
        set_(self, "rocking_frequency", as_float(self.rocking_frequency, "rocking_frequency"))
        set_(self, "rocking_phase", _triple(self.rocking_phase, "rocking_phase"))
        set_(self, "rocking_decay", nonnegative(self.rocking_decay, "rocking_decay"))
        set_(self, "rocking_onset", nonnegative(self.rocking_onset, "rocking_onset"))
        set_(self, "accel_start", as_float(self.accel_start, "accel_start"))
        set_(self, "accel_duration", nonnegative(self.accel_duration, "accel_duration"))
        set_(self, "accel", as_float(self.accel, "accel"))
        if not isinstance(self.sensors, SensorErrors):
            raise TypeError(f"Expected `sensors` to be a SensorErrors, got {type(self.sensors).__name__}")

    # ------------------------------------------------------------ derived constants
    @property
    def schuler_frequency(self) -> float:
        """Schuler frequency ``√(g/R)`` [rad/s]."""
        return float(np.sqrt(self.gravity / self.earth_radius))

    @property
    def events(self) -> tuple:
        """Times [s] where an input is not smooth (integration grids must contain them)."""
        ev = [self.rocking_start, self.accel_start, self.accel_start + self.accel_duration]
        return tuple(sorted(e for e in ev if 0.0 < e < self.duration))

    # ------------------------------------------------------------ truth, vectorised in t
    def north_velocity(self, t):
        """Northward ground speed V(t) [m/s]."""
        tau = np.clip(np.asarray(t, dtype=float) - self.accel_start, 0.0, self.accel_duration)
        return self.accel * tau

    def north_acceleration(self, t):
        """Northward acceleration V'(t) [m/s²] (right-continuous)."""
        t = np.asarray(t, dtype=float)
        on = (t >= self.accel_start) & (t < self.accel_start + self.accel_duration)
        return np.where(on, self.accel, 0.0)

    def latitude_at(self, t):
        """Latitude φ(t) [rad] of the northward run on the sphere."""
        t = np.asarray(t, dtype=float)
        a, ta, T = self.accel, self.accel_start, self.accel_duration
        tau = np.clip(t - ta, 0.0, T)
        dist = 0.5 * a * tau * tau + a * T * np.maximum(t - ta - T, 0.0)
        return self.latitude + dist / self.earth_radius

    def angles(self, t):
        """True Krylov angles (ψ, θ, γ) of the body relative to η [rad], shape (..., 3)."""
        t = np.asarray(t, dtype=float)
        tau = t - self.rocking_start
        on = tau > 0.0
        tau_p = np.where(on, tau, 0.0)
        env = np.exp(-self.rocking_decay * tau_p)
        if self.rocking_onset > 0.0:
            env = env * -np.expm1(-tau_p / self.rocking_onset)
        env = np.where(on, env, 0.0)
        amp, ph = np.asarray(self.rocking_amplitude), np.asarray(self.rocking_phase)
        return amp * env[..., None] * np.sin(self.rocking_frequency * t[..., None] + ph)

    def attitude(self, t):
        """True attitude μ(t) (body x → η), shape (..., 4)."""
        a = self.angles(t)
        return angles_to_quat(a[..., 0], a[..., 1], a[..., 2])

    def _wander(self, grid):
        """Azimuth a(t) of η in ζ on ``grid`` (a' = −Ω sin φ), by Gauss quadrature per interval."""
        x, w = GAUSS3
        h = np.diff(grid)
        nodes = grid[:-1, None] + h[:, None] * x
        inc = -(self.earth_rate * np.sin(self.latitude_at(nodes)) @ w) * h
        return np.concatenate([[0.0], np.cumsum(inc)])

    def frame_rate(self, t, wander):
        """Absolute angular rate of η in η axes [rad/s] (vertical component 0).

        ``wander`` is the azimuth a(t) of η relative to ζ at the same times.
        """
        lat = self.latitude_at(t)
        w_geo = np.stack([self.earth_rate * np.cos(lat), 0.0 * lat, -self.north_velocity(t) / self.earth_radius], axis=-1)
        return _about_up(-wander, w_geo)

    def specific_force_eta(self, t, wander):
        """Specific force in η axes [m/s²]: northward acceleration plus the reaction to gravity."""
        a = self.north_acceleration(t)
        f_geo = np.stack([a, 0.0 * a + self.gravity, 0.0 * a], axis=-1)
        return _about_up(-wander, f_geo)


def _about_up(angle, v):
    """Rotate vectors ``v`` (..., 3) by ``angle`` about axis 2 (up)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] + s * v[..., 2], v[..., 1], -s * v[..., 0] + c * v[..., 2]], axis=-1)


@dataclass(frozen=True)
class SensorData:
    """Sampled truth and sensor signals on a uniform grid.

    Attributes
    ----------
    time : ndarray, shape (N+1,)
        Grid t_n = n h [s].
    step : float
        h [s].
    gyro : ndarray, shape (N, 3)
        Measured rotation-vector increments of the body over [t_n, t_{n+1}] [rad].
    accel : ndarray, shape (N, 3)
        Measured mean specific force in x over [t_n, t_{n+1}] [m/s²].
    attitude : ndarray, shape (N+1, 4)
        True μ(t_n), body x → η.
    angles : ndarray, shape (N+1, 3)
        True (ψ, θ, γ)(t_n) [rad].
    frame_rate : ndarray, shape (N+1, 3)
        Absolute rate of η in η axes at t_n [rad/s].
    velocity : ndarray, shape (N+1,)
        Northward speed [m/s].
    scenario : Scenario
    """

    time: np.ndarray
    step: float
    gyro: np.ndarray
    accel: np.ndarray
    attitude: np.ndarray
    angles: np.ndarray
    frame_rate: np.ndarray
    velocity: np.ndarray
    scenario: Scenario


def grid(scenario: Scenario, step) -> np.ndarray:
    """Uniform time grid of step ``step`` that contains every event of ``scenario``.

    Raises
    ------
    ValueError
        If ``step`` is not positive, does not divide the duration, or an event
        time is not on the grid.
    """
    h = positive(step, "step")
    n = int(round(scenario.duration / h))
    if n < 1 or abs(n * h - scenario.duration) > 1e-9 * scenario.duration:
        raise ValueError(f"Expected `step` to divide the duration {scenario.duration:g} s, got {h:g} s")
    for e in scenario.events:
        if abs(e / h - round(e / h)) > 1e-6:
            raise ValueError(f"Expected `step` to put the event at t = {e:g} s on the grid, got {h:g} s")
    return np.arange(n + 1) * h


def sample(scenario: Scenario, step: float = 0.02, *, rng=None) -> SensorData:
    """Sample the truth and the sensor signals of ``scenario``.

    Parameters
    ----------
    scenario : Scenario
    step : float
        Sampling interval h [s]; must divide the duration and put every event on the grid.
    rng : numpy.random.Generator, int or None
        Source of the sensor noise (two streams are spawned: gyro, accelerometer).

    Returns
    -------
    SensorData

    Raises
    ------
    ValueError
        For a bad ``step``.

    Examples
    --------
    >>> d = sample(Scenario(duration=10.0, sensors=SensorErrors()), 0.5)
    >>> d.gyro.shape, bool(np.allclose(d.accel[:, 1], 9.81))
    ((20, 3), True)
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    t = grid(scenario, step)
    h = float(step)
    x, w = GAUSS3
    nodes = t[:-1, None] + h * x  # (N, 3)
    wander = scenario._wander(t)
    wander_nodes = np.interp(nodes, t, wander)

    # Rotation of η over each step, in η axes at its start (ω_η turns slowly).
    rate_nodes = scenario.frame_rate(nodes, wander_nodes)  # (N, 3, 3)
    d_eta = quat.rotvec_to_quat(np.einsum("nkj,k->nj", rate_nodes, w) * h)
    mu = scenario.attitude(t)
    # Body increment λ̄_n λ_{n+1} = μ̄_n ∘ Δε_n ∘ μ_{n+1}.
    d_body = quat.multiply(quat.multiply(quat.conjugate(mu[:-1]), d_eta), mu[1:])
    gyro_true = quat.quat_to_rotvec(d_body, canonical=True, validate=False)

    f_eta = scenario.specific_force_eta(nodes, wander_nodes)
    mu_nodes = scenario.attitude(nodes)
    f_body = quat.rotate(quat.conjugate(mu_nodes), f_eta)
    accel_true = np.einsum("nkj,k->nj", f_body, w)

    s = scenario.sensors
    gyro_rng, accel_rng = np.random.default_rng(rng).spawn(2)
    gyro = (1.0 + np.asarray(s.gyro_scale)) * gyro_true + np.asarray(s.gyro_drift) * h
    if s.gyro_noise > 0.0:
        gyro = gyro + s.gyro_noise * np.sqrt(h) * gyro_rng.standard_normal(gyro.shape)
    accel = (1.0 + np.asarray(s.accel_scale)) * accel_true + np.asarray(s.accel_bias)
    if s.accel_noise > 0.0:
        accel = accel + s.accel_noise / np.sqrt(h) * accel_rng.standard_normal(accel.shape)
    return SensorData(
        time=t,
        step=h,
        gyro=gyro,
        accel=accel,
        attitude=mu,
        angles=scenario.angles(t),
        frame_rate=scenario.frame_rate(t, wander),
        velocity=scenario.north_velocity(t),
        scenario=scenario,
    )
