"""True motion and sensor signals of the example of Plotnikov (1999), section 5.

The body moves over the spherical, rotating Earth of
:mod:`strapdown.analysis.multistage.earth`.  The stages estimate its attitude
relative to the *azimuth-free horizontal frame* η of the paper: axis 2 up, axes
1 and 3 horizontal, and no absolute rotation about the vertical.  η coincides
with the geographic frame ζ = (north, up, east) at t = 0 and then turns
relative to it about the vertical by the azimuth ``w(t) = −∫Ω sin φ dτ``
(:func:`eta_azimuth`), so that its absolute rate ``(ω₁, 0, ω₃)`` has no
vertical component, as in (3.7).

Timeline (every constant is a field of :class:`Scenario`):

* at rest at latitude φ0;
* from ``rocking_start``: rocking
  ``ψ = A_ψ E(t) sin(ϖt + φ_ψ)``, ``θ = A_θ E(t) sin(ϖt + φ_θ)``,
  ``γ = A_γ E(t) sin(ϖt + φ_γ)`` with the envelope
  ``E(t) = exp(−d (t − t_d)) (1 − exp(−(t − t_r)/τ_on))`` for t > t_r;
* from ``accel_start``: northward acceleration ``a`` for ``accel_duration``,
  then constant velocity.

The printed envelope is ``E = exp(−0.1 (t − 600))`` for t = 1000…5000 s, i.e.
``d = 0.1 s⁻¹`` and ``t_d = 600 s``; it is ``≈ 4·10⁻¹⁸`` when rocking starts.
The readings ``t_d = t_r`` (default) and ``d = 10⁻³ s⁻¹`` are both parameters.
The onset factor (``τ_on``, not in the paper) keeps the yaw (phase π/2) from
jumping by 0.2 rad.

Truth models (``Scenario.truth``):

``"rotating-earth"`` (default)
    The body is fixed to the Earth while at rest; the rocking angles are
    Krylov angles relative to ζ, so the yaw relative to η grows by
    ``Ω sin φ t``.  Gyros and accelerometers see the same motion: the gyro
    increments are those of the exact inertial attitude, and the specific
    force includes the Coriolis and centripetal terms
    (:func:`strapdown.analysis.multistage.earth.specific_force_geographic`).
    :func:`specific_force_residual` checks this independently.
``"no-coriolis"``
    The inconsistent model of earlier versions: the rocking angles are
    taken relative to η (at rest the body turns with η, not with the Earth)
    and the accelerometers see only ``(V̇, g, 0)``, without the Coriolis
    specific force and V²/R, while the gyros see the Earth and transport rates.
    Kept to show what the inconsistency does.

Sensors (:mod:`strapdown.analysis.multistage.sensors`): the gyro increments are
the rotation vectors of ``λ̄(t_n) ∘ λ(t_{n+1})`` for the exact inertial
attitude λ; the accelerometers deliver the mean body-frame specific force over
each step by 3-point Gauss–Legendre quadrature.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from ...derivations.multistage.published import SECTION5
from ..core import budget
from ..core import quaternion as quat
from ..core.validation import as_float, nonnegative, positive
from . import earth
from .sensors import SensorData, SensorErrors, corrupt
from .ship_angles import angles_to_quat, wrap_angle

__all__ = [
    "TRUTH_MODELS",
    "GAUSS3",
    "Scenario",
    "Truth",
    "eta_azimuth",
    "truth",
    "CoriolisTerm",
    "coriolis_term",
    "grid",
    "sample",
    "ResidualCheck",
    "specific_force_residual",
]

#: Truth models of :class:`Scenario` (module docstring).
TRUTH_MODELS = ("rotating-earth", "no-coriolis")

#: 3-point Gauss–Legendre nodes and weights on [0, 1].
GAUSS3 = (
    np.array([0.5 - np.sqrt(0.15), 0.5, 0.5 + np.sqrt(0.15)]),
    np.array([5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0]),
)
_GL16 = tuple(0.5 * (v + 1.0) if i == 0 else 0.5 * v for i, v in enumerate(np.polynomial.legendre.leggauss(16)))


def _triple(x, name) -> tuple:
    arr = np.asarray(x, dtype=float)
    if arr.shape == ():
        arr = np.full(3, float(arr))
    if arr.shape != (3,):
        raise ValueError(f"Expected `{name}` to be a scalar or 3 components, got shape {arr.shape}")
    return tuple(as_float(v, name) for v in arr)


@dataclass(frozen=True)
class Scenario:
    """The motion of Plotnikov (1999), section 5, with every constant a parameter.

    The defaults are the printed values
    (:data:`strapdown.derivations.multistage.published.SECTION5`) except where
    the text cannot be taken literally: the envelope origin (None: the start of
    rocking, printed 600 s) and the onset time constant (not in the paper).

    Parameters
    ----------
    duration : float
        Length of the run [s], > 0.
    latitude : float
        Initial latitude φ0 [rad], in (−π/2, π/2).
    gravity : float
        Plumb-bob gravity g [m/s²], > 0.
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
    rocking_decay_origin : float or None
        Time t_d where the decaying factor is 1 [s]; None: ``rocking_start``.
    rocking_onset : float
        Onset time constant τ_on of the envelope [s], >= 0 (0: abrupt start).
    accel_start : float
        Start of the northward acceleration [s].
    accel_duration : float
        Its duration [s], >= 0.
    accel : float
        Its magnitude [m/s²].
    truth : {"rotating-earth", "no-coriolis"}
        Truth model (module docstring).
    sensors : SensorErrors
        Sensor errors.

    Examples
    --------
    >>> s = Scenario(duration=100.0)
    >>> round(s.schuler_frequency, 7)
    0.0012409
    """

    duration: float = SECTION5.duration
    latitude: float = float(np.radians(SECTION5.latitude_deg))
    gravity: float = 9.81
    earth_radius: float = 6.371e6
    earth_rate: float = 7.292115e-5
    rocking_start: float = SECTION5.rest_end
    rocking_amplitude: tuple = SECTION5.rocking_amplitude
    rocking_frequency: float = SECTION5.rocking_frequency
    rocking_phase: tuple = SECTION5.rocking_phase
    rocking_decay: float = SECTION5.envelope_decay
    rocking_decay_origin: float | None = None
    rocking_onset: float = 1.0
    accel_start: float = SECTION5.accel_start
    accel_duration: float = SECTION5.accel_duration
    accel: float = SECTION5.accel
    truth: str = "rotating-earth"
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
        if self.rocking_decay_origin is not None:
            set_(self, "rocking_decay_origin", as_float(self.rocking_decay_origin, "rocking_decay_origin"))
        set_(self, "rocking_onset", nonnegative(self.rocking_onset, "rocking_onset"))
        set_(self, "accel_start", as_float(self.accel_start, "accel_start"))
        set_(self, "accel_duration", nonnegative(self.accel_duration, "accel_duration"))
        set_(self, "accel", as_float(self.accel, "accel"))
        if self.truth not in TRUTH_MODELS:
            raise ValueError(f"Expected `truth` in {TRUTH_MODELS}, got {self.truth!r}")
        if not isinstance(self.sensors, SensorErrors):
            raise TypeError(f"Expected `sensors` to be a SensorErrors, got {type(self.sensors).__name__}")

    # ------------------------------------------------------------ derived constants
    @property
    def schuler_frequency(self) -> float:
        """Schuler frequency ``√(g/R)`` [rad/s]."""
        return float(np.sqrt(self.gravity / self.earth_radius))

    @property
    def vertical_earth_rate(self) -> float:
        """``Ω sin φ0``: the rate at which the true yaw relative to η grows at rest [rad/s]."""
        return float(self.earth_rate * np.sin(self.latitude))

    @property
    def events(self) -> tuple:
        """Times [s] where an input is not smooth (integration grids must contain them)."""
        ev = [self.rocking_start, self.accel_start, self.accel_start + self.accel_duration]
        return tuple(sorted(e for e in ev if 0.0 < e < self.duration))

    # ------------------------------------------------------------ motion, vectorised in t
    def north_velocity(self, t):
        """Northward ground speed V(t) [m/s].

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        tau = np.clip(np.asarray(t, dtype=float) - self.accel_start, 0.0, self.accel_duration)
        return self.accel * tau

    def north_acceleration(self, t):
        """Northward acceleration V̇(t) [m/s²] (right-continuous).

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        t = np.asarray(t, dtype=float)
        on = (t >= self.accel_start) & (t < self.accel_start + self.accel_duration)
        return np.where(on, self.accel, 0.0)

    def latitude_at(self, t):
        """Latitude φ(t) [rad] of the northward run on the sphere.

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        t = np.asarray(t, dtype=float)
        a, ta, T = self.accel, self.accel_start, self.accel_duration
        tau = np.clip(t - ta, 0.0, T)
        dist = 0.5 * a * tau * tau + a * T * np.maximum(t - ta - T, 0.0)
        return self.latitude + dist / self.earth_radius

    def envelope(self, t):
        """Rocking envelope E(t) [-] (0 before ``rocking_start``).

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        t = np.asarray(t, dtype=float)
        tau = t - self.rocking_start
        on = tau > 0.0
        tau_p = np.where(on, tau, 0.0)
        origin = self.rocking_start if self.rocking_decay_origin is None else self.rocking_decay_origin
        env = np.exp(-self.rocking_decay * (np.where(on, t, origin) - origin))
        if self.rocking_onset > 0.0:
            env = env * -np.expm1(-tau_p / self.rocking_onset)
        return np.where(on, env, 0.0)

    def rocking_angles(self, t):
        """Rocking Krylov angles (ψ, θ, γ) [rad], shape (..., 3).

        Relative to ζ for the truth model "rotating-earth", to η for "no-coriolis".

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        t = np.asarray(t, dtype=float)
        amp, ph = np.asarray(self.rocking_amplitude), np.asarray(self.rocking_phase)
        return amp * self.envelope(t)[..., None] * np.sin(self.rocking_frequency * t[..., None] + ph)


def eta_azimuth(scenario: Scenario, t):
    """Azimuth w(t) of η relative to ζ about the vertical [rad]: ``w' = −Ω sin φ``, ``w(0) = 0``.

    Closed form at rest and at constant velocity, 16-point Gauss–Legendre
    quadrature over the acceleration (exact to round-off).

    Parameters
    ----------
    scenario : Scenario
    t : array_like
        Time [s], >= 0.

    Returns
    -------
    ndarray
        ``v_ζ = q₂(w) ∘ v_η ∘ q̄₂(w)``.
    """
    sc = scenario
    t = np.asarray(t, dtype=float)
    ta, tb = sc.accel_start, sc.accel_start + sc.accel_duration
    x, w = _GL16
    lat_b = float(sc.latitude_at(tb))
    rate_b = sc.accel * sc.accel_duration / sc.earth_radius  # φ' at constant velocity

    def during(width):
        return width * (np.sin(sc.latitude_at(ta + width[..., None] * x)) @ w)

    full = float(during(np.array(sc.accel_duration)))

    def antiderivative(tt):
        # F(t) = ∫_{ta}^{t} sin φ dτ, piecewise; the quadrature only where ta < t < tb.
        out = np.sin(sc.latitude) * (np.minimum(tt, ta) - ta)
        inside = (tt > ta) & (tt < tb)
        out = out + np.where(tt >= tb, full, 0.0)
        if np.any(inside):
            out[inside] += during(tt[inside] - ta)
        d = np.maximum(tt - tb, 0.0)
        return out + d * np.sin(lat_b + 0.5 * rate_b * d) * np.sinc(rate_b * d / (2.0 * np.pi))

    return -sc.earth_rate * (antiderivative(np.atleast_1d(t)).reshape(t.shape) - antiderivative(np.zeros(1))[0])


class Truth(NamedTuple):
    """The true motion at given times (:func:`truth`).

    Attributes
    ----------
    attitude_inertial : ndarray, shape (..., 4)
        λ: body x → inertial ξ.
    attitude : ndarray, shape (..., 4)
        μ: body x → η.
    angles : ndarray, shape (..., 3)
        Krylov angles (ψ, θ, γ) of μ [rad] (yaw wrapped to (−π, π]).
    specific_force : ndarray, shape (..., 3)
        Specific force in body axes [m/s²].
    specific_force_geographic : ndarray, shape (..., 3)
        Specific force in ζ (north, up, east) [m/s²].
    latitude : ndarray
        φ [rad].
    velocity : ndarray
        Northward ground speed [m/s].
    eta_azimuth : ndarray
        w [rad].
    """

    attitude_inertial: np.ndarray
    attitude: np.ndarray
    angles: np.ndarray
    specific_force: np.ndarray
    specific_force_geographic: np.ndarray
    latitude: np.ndarray
    velocity: np.ndarray
    eta_azimuth: np.ndarray


def truth(scenario: Scenario, t) -> Truth:
    """The true attitude and specific force of ``scenario`` at times ``t``.

    Parameters
    ----------
    scenario : Scenario
    t : array_like
        Time [s].

    Returns
    -------
    Truth

    Raises
    ------
    TypeError
        If ``scenario`` is not a Scenario.
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    sc = scenario
    t = np.asarray(t, dtype=float)
    lat, vel, wander, mu_geo, mu, angles, f_geo, f_body = _motion(sc, t)
    lam = quat.multiply(earth.geographic_to_inertial(t, lat, np.zeros_like(lat), sc.earth_rate), mu_geo)
    return Truth(lam, mu, angles, f_body, f_geo, lat, vel, wander)


class CoriolisTerm(NamedTuple):
    """The Coriolis part of the specific force of the northward motion (:func:`coriolis_term`).

    Attributes
    ----------
    time : float
        t [s].
    velocity : float
        Northward ground speed V [m/s].
    acceleration : float
        ``2Ω sin φ V``, the magnitude of the east specific force it needs [m/s²].
    """

    time: float
    velocity: float
    acceleration: float


def coriolis_term(scenario: Scenario, t: float | None = None) -> CoriolisTerm:
    """The Coriolis term ``−2Ω sin φ V`` of the east specific force at one time (default: the end of the run).

    Parameters
    ----------
    scenario : Scenario
        The scenario.
    t : float, optional
        Time [s]; default ``scenario.duration``.

    Returns
    -------
    CoriolisTerm
    """
    t = scenario.duration if t is None else float(t)
    end = truth(scenario, np.array([t]))
    return CoriolisTerm(t, float(end.velocity[0]), float(-end.specific_force_geographic[0, 2]))


def _motion(sc: Scenario, t):
    """Position, attitudes relative to ζ and η, and the specific force (everything but λ)."""
    lat = sc.latitude_at(t)
    vel = sc.north_velocity(t)
    acc = sc.north_acceleration(t)
    wander = eta_azimuth(sc, t)
    rock = sc.rocking_angles(t)
    q_rock = angles_to_quat(rock[..., 0], rock[..., 1], rock[..., 2])
    if sc.truth == "rotating-earth":
        mu_geo = q_rock
        mu = quat.multiply(earth.axis_rotation(1, -wander), mu_geo)
        angles = np.stack([wrap_angle(rock[..., 0] - wander), rock[..., 1], rock[..., 2]], axis=-1)
        f_geo = earth.specific_force_geographic(lat, vel, acc, gravity=sc.gravity, earth_rate=sc.earth_rate, earth_radius=sc.earth_radius)
    else:
        mu = q_rock
        mu_geo = quat.multiply(earth.axis_rotation(1, wander), mu)
        angles = rock
        f_geo = np.stack([acc, np.full_like(acc, sc.gravity), np.zeros_like(acc)], axis=-1)
    f_body = quat.rotate(quat.conjugate(mu_geo), f_geo)
    return lat, vel, wander, mu_geo, mu, angles, f_geo, f_body


def _body_force(sc: Scenario, t):
    """The specific force in body axes of :func:`_motion` alone (the same operations, without the attitude relative to η)."""
    if sc.truth != "rotating-earth":
        return _motion(sc, t)[-1]
    lat = sc.latitude_at(t)
    rock = sc.rocking_angles(t)
    mu_geo = angles_to_quat(rock[..., 0], rock[..., 1], rock[..., 2])
    f_geo = earth.specific_force_geographic(lat, sc.north_velocity(t), sc.north_acceleration(t), gravity=sc.gravity, earth_rate=sc.earth_rate, earth_radius=sc.earth_radius)
    return quat.rotate(quat.conjugate(mu_geo), f_geo)


def grid(scenario: Scenario, step, *, limits: budget.Limits | None = None) -> np.ndarray:
    """Uniform time grid of step ``step`` that contains every event of ``scenario``.

    Parameters
    ----------
    scenario : Scenario
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray, shape (N+1,)
        ``t_n = n h`` [s].

    Raises
    ------
    ValueError
        If ``step`` is not positive, does not divide the duration, an event
        time is not on the grid, or the grid would exceed ``limits``.
    """
    h = positive(step, "step")
    budget.check(budget.arrays(scenario.duration / h, what=_steps_text(scenario, h)), limits)
    n = int(round(scenario.duration / h))
    if n < 1 or abs(n * h - scenario.duration) > 1e-9 * scenario.duration:
        raise ValueError(f"Expected `step` to divide the `duration` of the scenario, {scenario.duration:g} s, got {h:g} s")
    for e in scenario.events:
        if abs(e / h - round(e / h)) > 1e-6:
            raise ValueError(f"Expected `step` to put the event at t = {e:g} s on the grid, got {h:g} s")
    return np.arange(n + 1) * h


def _steps_text(scenario: Scenario, h: float) -> str:
    return f"`duration` = {scenario.duration:.3g} s of the scenario over `step` = {h:g} s ({scenario.duration / h:.3g} integration steps)"


def sample(scenario: Scenario, step: float = 0.02, *, rng=None, limits: budget.Limits | None = None) -> SensorData:
    """Sample the truth and the sensor signals of ``scenario``.

    Parameters
    ----------
    scenario : Scenario
    step : float
        Step H = h [s] (one sensor sample per step); must divide the duration and put every event on the grid.
    rng : numpy.random.Generator, int, SeedSequence or None
        Source of the sensor noise (see :func:`strapdown.analysis.multistage.sensors.corrupt`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SensorData

    Raises
    ------
    ValueError
        For a bad ``step``, or signals that would exceed ``limits``.

    Examples
    --------
    >>> d = sample(Scenario(duration=10.0, sensors=SensorErrors()), 0.5)
    >>> d.gyro.shape, bool(np.allclose(d.accel[:, 1], 9.81))
    ((20, 3), True)
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    h = positive(step, "step")
    budget.check(budget.multistage(scenario.duration / h, what=_steps_text(scenario, h)), limits)
    grid(scenario, step, limits=limits)  # the checks of the grid
    clean = replace(scenario, sensors=SensorErrors())
    if scenario.duration / h <= _KEPT_STEPS:
        t, gyro, accel, attitude, angles, velocity = _kept_signals(clean, repr(clean), h)
    else:
        t, gyro, accel, attitude, angles, velocity = _ideal_signals(clean, h)
    ideal = SensorData(time=t, step=h, gyro=gyro, accel=accel, attitude=attitude, angles=angles, velocity=velocity, scenario=scenario)
    if scenario.sensors.is_ideal:
        return ideal
    return corrupt(ideal, scenario.sensors, rng=rng)


#: Longest record [steps] whose ideal signals :func:`sample` keeps (about 4 MB each; the section-5 run at 0.2 s has 25000).
_KEPT_STEPS = 1 << 15


@functools.lru_cache(maxsize=16)
def _kept_signals(scenario: Scenario, text: str, h: float) -> tuple:
    """:func:`_ideal_signals`, kept for the last 16 motions of at most :data:`_KEPT_STEPS` steps.

    A report samples the same motion at the same step for several studies
    (the readings, the yaw study and the sensor-error Monte Carlo; the gain
    checks), which differ only in their sensor errors.  The key holds the
    scenario's ``repr`` besides the scenario, which tells −0.0 from 0.0 (they
    compare equal).
    """
    return _ideal_signals(scenario, h)


def _ideal_signals(scenario: Scenario, h: float) -> tuple:
    """Grid, ideal gyro and accelerometer signals and the truth of :func:`sample` (arrays read-only)."""
    t = np.arange(int(round(scenario.duration / h)) + 1) * h  # the grid of `grid`, checked by the caller
    x, w = GAUSS3
    at_grid = truth(scenario, t)
    lam = at_grid.attitude_inertial
    d_body = quat.multiply(quat.conjugate(lam[:-1]), lam[1:])
    gyro = quat.quat_to_rotvec(d_body, canonical=True, validate=False)
    f_nodes = _body_force(scenario, t[:-1, None] + h * x)
    accel = np.einsum("nkj,k->nj", f_nodes, w)
    out = (t, gyro, accel, at_grid.attitude, at_grid.angles, at_grid.velocity)
    for a in out:
        a.setflags(write=False)
    return out


@dataclass(frozen=True)
class ResidualCheck:
    """Outcome of :func:`specific_force_residual`.

    Attributes
    ----------
    times : ndarray, shape (K+1,)
        Check points [s].
    velocity_change : ndarray, shape (K, 3)
        ``v_ξ(t_{j+1}) − v_ξ(t_j)`` from the motion [m/s].
    integral : ndarray, shape (K, 3)
        ``∫ (f_ξ + G) dt`` over the same intervals [m/s].
    max_residual : float
        Largest ``|velocity_change − integral|`` [m/s].
    scale : float
        Largest ``|integral|`` [m/s] (to judge the residual).
    """

    times: np.ndarray
    velocity_change: np.ndarray
    integral: np.ndarray
    max_residual: float
    scale: float


def specific_force_residual(scenario: Scenario, times=None, *, max_interval: float = 10.0) -> ResidualCheck:
    """Check the truth model: the inertial velocity integrates the specific force plus gravitation.

    The inertial position and velocity of the body come from
    :func:`strapdown.analysis.multistage.earth.inertial_velocity` (geometry
    only); the specific force is the model's, in body axes, rotated to ξ with
    the true inertial attitude λ; the gravitation is
    :func:`strapdown.analysis.multistage.earth.gravitation`.  Between check
    points the integral is taken by 16-point Gauss–Legendre quadrature on
    sub-intervals of at most ``max_interval`` that do not straddle an event.

    Parameters
    ----------
    scenario : Scenario
    times : array_like, optional
        Check points [s], increasing; default every 100 s and every event.
    max_interval : float
        Longest quadrature sub-interval [s].

    Returns
    -------
    ResidualCheck
        For the truth model "rotating-earth" ``max_residual`` is at round-off;
        for "no-coriolis" it shows the missing Coriolis and centripetal terms.

    Raises
    ------
    ValueError
        If ``times`` does not increase or ``max_interval`` is not positive.
    """
    sc = scenario
    if times is None:
        times = np.union1d(np.arange(0.0, sc.duration + 1e-9, 100.0), np.array(sc.events))
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size < 2 or np.any(np.diff(times) <= 0):
        raise ValueError("Expected `times` to be at least two increasing check points")
    max_interval = positive(max_interval, "max_interval")
    x, w = _GL16
    breaks = np.union1d(times, np.array([e for e in sc.events if times[0] < e < times[-1]]))
    pieces = []
    for a, b in zip(breaks[:-1], breaks[1:]):
        n = max(1, int(np.ceil((b - a) / max_interval)))
        pieces += list(np.linspace(a, b, n + 1)[:-1])
    starts = np.array(pieces)
    ends = np.append(starts[1:], breaks[-1])
    nodes = starts[:, None] + (ends - starts)[:, None] * x
    tr = truth(sc, nodes)
    f_inertial = quat.rotate(tr.attitude_inertial, tr.specific_force)
    position = earth.inertial_position(nodes, tr.latitude, np.zeros_like(tr.latitude), sc.earth_rate, sc.earth_radius)
    total = f_inertial + earth.gravitation(position, sc.gravity, sc.earth_rate)
    piece_integrals = np.einsum("pkj,k->pj", total, w) * (ends - starts)[:, None]
    owner = np.searchsorted(times, starts, side="right") - 1
    integral = np.zeros((times.size - 1, 3))
    np.add.at(integral, owner, piece_integrals)
    lat = sc.latitude_at(times)
    ground = np.stack([sc.north_velocity(times), np.zeros_like(times), np.zeros_like(times)], axis=-1)
    v = earth.inertial_velocity(times, lat, np.zeros_like(lat), ground, sc.earth_rate, sc.earth_radius)
    dv = np.diff(v, axis=0)
    return ResidualCheck(times, dv, integral, float(np.abs(dv - integral).max()), float(np.abs(integral).max()))
