"""A kinematically consistent inertial record of a sensor block on a rocking base.

The rocking centre is fixed on the Earth at latitude φ; the block sits at the
lever arm ``r`` (body axes) from it.  Its attitude is the stable attitude
``(ψ0, β0, γ0)`` plus the rocking of :mod:`strapdown.analysis.alignment.base_motion`,
``C_b^n(t)`` of :mod:`strapdown.analysis.alignment.tilt_attitude`.  The ideal sensors measure

* gyros: ``ω_ib^b = ω_nb^b + C_n^b ω_ie^n`` (the base does not move over the
  Earth, so the transport rate is zero);
* accelerometers: ``f^b = ω̇ × r + ω × (ω × r) + 2 (C_n^b ω_ie^n) × (ω × r) − C_n^b g^n``
  with ``ω = ω_nb^b``: the specific force of the point r, lever-arm
  accelerations and Coriolis included,

and deliver their integrals over each sample interval (angle and velocity
increments), computed by two-point Gauss–Legendre quadrature of the exact
rates (error ``O(h⁵)`` per interval for rocking far below the sample rate).
``rocking_in_gyros=False`` is the setting of Hrechka & Koroliov: the gyros see
the Earth rate at the stable attitude only, while the accelerometers see the
rocking.

Sensor errors (:class:`SensorErrors`), applied in this order to the ideal
increments: scale factors, biases (fixed, plus a random turn-on bias per trial),
white noise (angle and velocity random walk, ``N √h`` per increment) and
quantisation of the accumulated output (the increments are differences of a
quantised running sum, so the quantisation error of a sum telescopes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core import budget
from ..core.validation import as_array, as_float, as_int, nonnegative, positive
from ..gyrocompass.azimuth import check_latitude
from ..gyrocompass.rocking import as_generator
from . import kernels
from .base_motion import MotionRealisation, Spectrum, StillBase
from .earth import earth_rate_ned, gravity_ned
from .tilt_attitude import attitude_matrix, body_acceleration, body_rate

__all__ = ["SensorErrors", "Scenario", "ImuRecord", "ImuDraws", "draw_imu", "simulate_imu", "ideal_increments"]

_GAUSS = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))

#: Truth instants up to which the rocking is summed at those instants instead of evaluated over the record.
_FEW_POINTS = 8


def _check_draws(draws, errors, n_samples: int) -> None:
    """Refuse draws that lack the numbers ``errors`` need, or were drawn for another record length."""
    e = SensorErrors() if errors is None else errors
    need = {"gyro_noise": bool(e.gyro_noise), "accel_noise": bool(e.accel_noise), "gyro_start": e.gyro_quantum > 0, "accel_start": e.accel_quantum > 0}
    for name, needed in need.items():
        if needed and getattr(draws, name) is None:
            raise ValueError(f"Expected `draws` with the numbers of `{name}` (draw_imu with these errors), got none")
    for name in ("gyro_noise", "accel_noise"):
        x = getattr(draws, name)
        if x is not None and x.shape[1] != n_samples:
            raise ValueError(f"Expected `draws` of {n_samples} samples, got {x.shape[1]}")


def _vec3(value, name):
    return as_array(value, name, last=3).reshape(3)


@dataclass(frozen=True)
class SensorErrors:
    """Gyro and accelerometer errors (SI units, body axes).

    Parameters
    ----------
    gyro_bias : array_like
        Fixed gyro bias [rad/s], 3 components.
    accel_bias : array_like
        Fixed accelerometer bias [m/s²], 3 components.
    gyro_bias_sigma : float
        Standard deviation of a random turn-on gyro bias per axis and trial [rad/s].
    accel_bias_sigma : float
        Standard deviation of a random turn-on accelerometer bias [m/s²].
    gyro_noise : float
        Angle random walk: white rate noise of spectral density ``N²`` [rad/√s].
    accel_noise : float
        Velocity random walk [m/s/√s].
    gyro_scale : array_like
        Gyro scale-factor errors [1], 3 components.
    accel_scale : array_like
        Accelerometer scale-factor errors [1], 3 components.
    gyro_quantum : float
        Angle quantum of the gyro output [rad] (0: none).
    accel_quantum : float
        Velocity quantum of the accelerometer output [m/s] (0: none).
    """

    gyro_bias: np.ndarray = field(default_factory=lambda: np.zeros(3))
    accel_bias: np.ndarray = field(default_factory=lambda: np.zeros(3))
    gyro_bias_sigma: float = 0.0
    accel_bias_sigma: float = 0.0
    gyro_noise: float = 0.0
    accel_noise: float = 0.0
    gyro_scale: np.ndarray = field(default_factory=lambda: np.zeros(3))
    accel_scale: np.ndarray = field(default_factory=lambda: np.zeros(3))
    gyro_quantum: float = 0.0
    accel_quantum: float = 0.0

    def __post_init__(self):
        for name in ("gyro_bias", "accel_bias", "gyro_scale", "accel_scale"):
            object.__setattr__(self, name, _vec3(getattr(self, name), name))
        for name in ("gyro_bias_sigma", "accel_bias_sigma", "gyro_noise", "accel_noise", "gyro_quantum", "accel_quantum"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))

    @property
    def ideal(self) -> bool:
        """True when every error is zero."""
        arrays = (self.gyro_bias, self.accel_bias, self.gyro_scale, self.accel_scale)
        scalars = (self.gyro_bias_sigma, self.accel_bias_sigma, self.gyro_noise, self.accel_noise, self.gyro_quantum, self.accel_quantum)
        return not any(np.any(a) for a in arrays) and not any(scalars)


@dataclass(frozen=True)
class Scenario:
    """Where and how the block aligns: place, stable attitude, rocking, lever arm, sampling.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.
    heading : float
        Stable heading ψ0 [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    motion : rocking model
        From :mod:`strapdown.analysis.alignment.base_motion` (default no rocking).
    lever_arm : array_like
        Position of the sensor block relative to the rocking centre, body axes [m].
    sample_rate : float
        Sensor sample rate [Hz].
    duration : float
        Alignment time T [s], at least two samples.
    rocking_in_gyros : bool
        False: the gyros see the Earth rate at the stable attitude only (the paper's setting).
    """

    latitude: float
    heading: float = 0.0
    beta0: float = 0.0
    gamma0: float = 0.0
    motion: object = field(default_factory=StillBase)
    lever_arm: np.ndarray = field(default_factory=lambda: np.zeros(3))
    sample_rate: float = 100.0
    duration: float = 120.0
    rocking_in_gyros: bool = True

    def __post_init__(self):
        object.__setattr__(self, "latitude", check_latitude(self.latitude))
        for name in ("heading", "beta0", "gamma0"):
            object.__setattr__(self, name, as_float(getattr(self, name), name))
        for name in ("beta0", "gamma0"):
            if not abs(getattr(self, name)) < 0.5 * math.pi:
                raise ValueError(f"Expected `{name}` in (-π/2, π/2) rad, got {getattr(self, name):g}")
        object.__setattr__(self, "lever_arm", _vec3(self.lever_arm, "lever_arm"))
        object.__setattr__(self, "sample_rate", positive(self.sample_rate, "sample_rate"))
        object.__setattr__(self, "duration", positive(self.duration, "duration"))
        if self.n_samples < 2:
            raise ValueError(f"Expected `duration` of at least two samples (>= {2 / self.sample_rate:g} s), got {self.duration:g}")
        if not hasattr(self.motion, "draw") or not hasattr(self.motion, "spectrum"):
            raise TypeError(f"Expected `motion` to be a rocking model of base_motion, got {type(self.motion).__name__}")

    @property
    def dt(self) -> float:
        """Sample interval [s]."""
        return 1.0 / self.sample_rate

    @property
    def n_samples(self) -> int:
        """Increments in the record, ``round(T f_s)``."""
        return int(round(self.duration * self.sample_rate))

    @property
    def stable_angles(self) -> np.ndarray:
        """``(ψ0, β0, γ0)`` [rad]."""
        return np.array([self.heading, self.beta0, self.gamma0])


@dataclass(frozen=True)
class ImuRecord:
    """Increments of ``n`` trials with their truth.

    Attributes
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors
        The sensor errors applied.
    dtheta : ndarray
        ``(n, N, 3)`` angle increments [rad].
    dv : ndarray
        ``(n, N, 3)`` velocity increments [m/s].
    truth_times : ndarray
        ``(K,)`` times of the truth samples [s].
    truth_angles : ndarray
        ``(n, K, 3)`` true (ψ, β, γ) at those times [rad].
    truth_velocity : ndarray
        ``(n, K, 3)`` velocity of the block over the Earth, NED [m/s].
    truth_rates : ndarray
        ``(n, K, 3)`` time derivatives of the true angles [rad/s].
    gyro_bias : ndarray
        ``(n, 3)`` true gyro bias of each trial [rad/s].
    accel_bias : ndarray
        ``(n, 3)`` true accelerometer bias of each trial [m/s²].
    """

    scenario: Scenario
    errors: SensorErrors
    dtheta: np.ndarray
    dv: np.ndarray
    truth_times: np.ndarray
    truth_angles: np.ndarray
    truth_velocity: np.ndarray
    truth_rates: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray

    @property
    def n_trials(self) -> int:
        """Trials."""
        return self.dtheta.shape[0]


def _ideal_rates(scenario: Scenario, angles_r, rates_r, accels_r=None):
    """Ideal gyro rate and specific force at the points of one quadrature node."""
    lat = scenario.latitude
    W, g = earth_rate_ned(lat), gravity_ned(lat)
    angles = angles_r + scenario.stable_angles
    C = attitude_matrix(angles)
    w_e = np.einsum("...ji,j->...i", C, W)  # C_n^b ω_ie^n
    w = body_rate(angles, rates_r)
    if scenario.rocking_in_gyros:
        gyro = w + w_e
    else:
        gyro = np.broadcast_to(attitude_matrix(scenario.stable_angles).T @ W, w.shape)
    f = -np.einsum("...ji,j->...i", C, g)
    r = scenario.lever_arm
    if np.any(r):
        wr = np.cross(w, r)
        f = f + np.cross(body_acceleration(angles, rates_r, accels_r), r) + np.cross(w, wr) + 2.0 * np.cross(w_e, wr)
    return gyro, f


def _still(motion) -> bool:
    """Whether ``motion`` is no rocking drawn for more than one trial (or for a spectrum): made once and repeated."""
    return not np.any(motion.coefficients) and (motion.n_trials > 1 or motion.coefficients.shape[-1] > 0)


def _compiled_increments(scenario: Scenario, motion, gyro=None, accel=None):
    """The increments of both Gauss nodes in one compiled pass, with the sensor terms ``gyro`` and ``accel`` if given.

    ``gyro`` and ``accel`` are ``(bias, scale, noise)`` as
    :func:`~strapdown.analysis.alignment.kernels.sensor_increments` takes them.
    """
    N, dt = scenario.n_samples, scenario.dt
    lat = scenario.latitude
    W, g = earth_rate_ned(lat), gravity_ned(lat)
    fixed = attitude_matrix(scenario.stable_angles).T @ W
    order = 2 if np.any(scenario.lever_arm) else 1
    nodes = []
    for node in _GAUSS:
        parts, scale = motion.unit_evaluation(N, node * dt, derivatives=order)
        nodes.append((parts[0], parts[1], parts[2] if order == 2 else None))
    return kernels.sensor_increments(*nodes, scenario.stable_angles, W, g, scenario.lever_arm, fixed, scenario.rocking_in_gyros, 0.5 * dt, scale=scale, gyro=gyro, accel=accel)


def ideal_increments(scenario: Scenario, motion, *, compiled: bool | None = None):
    """Ideal angle and velocity increments of a drawn rocking: two-point Gauss quadrature of the exact rates.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, lever arm and sampling.
    motion : MotionRealisation
        The rocking of n trials (:meth:`strapdown.analysis.alignment.base_motion.SineMotion.draw` and kin).
    compiled : bool or None, keyword-only
        Fused compiled loop (:mod:`~strapdown.analysis.alignment.kernels`) or the numpy form,
        kept as the reference (equal to round-off); None (default): the loop
        when it pays off (:func:`~strapdown.analysis.alignment.kernels.use_compiled`).

    Returns
    -------
    tuple of ndarray
        ``dtheta, dv``, each ``(n, N, 3)`` [rad, m/s], ``N = scenario.n_samples``.

    Raises
    ------
    TypeError
        If ``scenario`` is not a Scenario or ``motion`` not a MotionRealisation.
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    if not isinstance(motion, MotionRealisation):
        raise TypeError(f"Expected `motion` to be a MotionRealisation (a rocking model's draw), got {type(motion).__name__}")
    N, dt = scenario.n_samples, scenario.dt
    n = motion.n_trials
    compiled = kernels.use_compiled(compiled, n * N)
    if _still(motion):  # no rocking: every trial is the first, at rest
        still = MotionRealisation(Spectrum(np.zeros(0), np.zeros((3, 0)), False), np.zeros((1, 3, 0)), motion.dt)
        return tuple(np.repeat(x, n, axis=0) for x in ideal_increments(scenario, still, compiled=compiled))
    if compiled:
        return _compiled_increments(scenario, motion)
    dtheta = np.zeros((n, N, 3))
    dv = np.zeros((n, N, 3))
    order = 2 if np.any(scenario.lever_arm) else 1
    for node in _GAUSS:
        gyro, f = _ideal_rates(scenario, *motion.evaluate(N, node * dt, derivatives=order))
        dtheta += (0.5 * dt) * gyro
        dv += (0.5 * dt) * f
    return dtheta, dv


def _quantise(x, q, start):
    """Differences of the quantised running sum of ``x`` (along axis 1), from the initial residue ``start`` [units of x]."""
    if q <= 0:
        return x
    acc = np.floor((np.cumsum(x, axis=1) + start) / q)
    first = np.floor(start / q)
    return q * np.diff(np.concatenate([first, acc], axis=1), axis=1)


@dataclass(frozen=True)
class ImuDraws:
    """The random numbers of ``n`` sensor records, drawn once: common random numbers made explicit.

    The same draws give the same trials in another scenario that differs by the
    rocking amplitudes only (:meth:`strapdown.analysis.alignment.base_motion.MotionRealisation.rescaled`,
    whose unit evaluations they share), or in the same scenario for another
    method or filter.

    Attributes
    ----------
    rocking : MotionRealisation
        The rocking of the scenario they were drawn for.
    gyro_bias, accel_bias : ndarray
        ``(n, 3)`` standard normal numbers of the turn-on biases.
    gyro_noise, accel_noise : ndarray or None
        ``(n, N, 3)`` standard normal numbers of the white noise (None without noise).
    gyro_start, accel_start : ndarray or None
        ``(n, 1, 3)`` uniform numbers in [0, 1): the initial residues of the quantised sums (None without quantisation).
    """

    rocking: object
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    gyro_noise: np.ndarray | None
    accel_noise: np.ndarray | None
    gyro_start: np.ndarray | None
    accel_start: np.ndarray | None
    _noise: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def n_trials(self) -> int:
        """Trials."""
        return self.gyro_bias.shape[0]

    def noise_term(self, sensor: str, factor: float) -> np.ndarray:
        """``factor`` times the white-noise numbers of ``sensor``, read-only and kept for the next call.

        A search over the rocking amplitude evaluates the same draws many times
        with the same noise density: the product is made once per factor (the
        last one per sensor is kept), and its values are those of the product
        made again.

        Parameters
        ----------
        sensor : str
            ``"gyro"`` or ``"accel"``.
        factor : float
            Noise density times √dt [rad or m/s per unit normal number].

        Returns
        -------
        ndarray
            ``(n, N, 3)``.

        Raises
        ------
        ValueError
            For another ``sensor``, draws without that sensor's noise numbers, or a non-finite ``factor``.
        """
        if sensor not in ("gyro", "accel"):
            raise ValueError(f"Expected `sensor` 'gyro' or 'accel', got {sensor!r}")
        numbers = self.gyro_noise if sensor == "gyro" else self.accel_noise
        if numbers is None:
            raise ValueError(f"Expected draws with {sensor} noise numbers, got draws without (drawn for errors without {sensor} noise)")
        factor = as_float(factor, "factor")
        kept = self._noise.get(sensor)
        if kept is None or kept[0] != factor or kept[1] is not numbers:
            term = factor * numbers
            term.flags.writeable = False
            kept = self._noise[sensor] = (factor, numbers, term)
        return kept[2]


def draw_imu(scenario: Scenario, errors: SensorErrors | None = None, *, n_trials: int, rng=None, chunk: int | None = None, limits: budget.Limits | None = None) -> ImuDraws:
    """Draw the random numbers of ``n_trials`` records of ``scenario`` with ``errors``.

    The stream is consumed as :func:`simulate_imu` consumes it: the rocking,
    the turn-on biases, the noise, the quantisation residues.

    Parameters
    ----------
    scenario : Scenario
        Place, rocking and sampling.
    errors : SensorErrors, optional
        Which errors need numbers (default ideal sensors).
    n_trials : int
        Trials.
    rng : Generator | SeedSequence | int | None
        Random stream.
    chunk : int, keyword-only, optional
        Consume the stream ``chunk`` trials at a time, as that many separate
        draws of ``chunk`` trials would (one draw of them all, the same numbers);
        default all the trials at once.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ImuDraws

    Raises
    ------
    ValueError
        For ``n_trials`` below 1, or draws beyond ``limits`` (naming ``n_trials``
        and the scenario's ``duration``).
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    e = SensorErrors() if errors is None else errors
    if not isinstance(e, SensorErrors):
        raise TypeError(f"Expected `errors` to be SensorErrors, got {type(e).__name__}")
    n = as_int(n_trials, "n_trials", minimum=1)
    N, dt = scenario.n_samples, scenario.dt
    what = f"`n_trials` = {n:.3g} records of {N + 1:.3g} samples (`duration` = {scenario.duration:.3g} s of the scenario)"
    budget.check(budget.imu_record(n, N + 1, what=what), limits)
    g = as_generator(rng)
    size = n if chunk is None else as_int(chunk, "chunk", minimum=1)
    if size >= n:
        rocking = scenario.motion.draw(g, n, N + 1, dt, limits=limits)
        gb, ab = g.standard_normal((n, 3)), g.standard_normal((n, 3))
        gn = g.standard_normal((n, N, 3)) if e.gyro_noise else None
        an = g.standard_normal((n, N, 3)) if e.accel_noise else None
        gs = g.random((n, 1, 3)) if e.gyro_quantum > 0 else None
        as_ = g.random((n, 1, 3)) if e.accel_quantum > 0 else None
        return ImuDraws(rocking, gb, ab, gn, an, gs, as_)
    # chunk after chunk, each chunk's numbers written into its rows (the values of a separate draw)
    gb, ab = np.empty((n, 3)), np.empty((n, 3))
    gn = np.empty((n, N, 3)) if e.gyro_noise else None
    an = np.empty((n, N, 3)) if e.accel_noise else None
    gs = np.empty((n, 1, 3)) if e.gyro_quantum > 0 else None
    as_ = np.empty((n, 1, 3)) if e.accel_quantum > 0 else None
    rockings = []
    for k in range(0, n, size):
        rows = slice(k, min(k + size, n))
        rockings.append(scenario.motion.draw(g, rows.stop - k, N + 1, dt, limits=limits))
        g.standard_normal(out=gb[rows])
        g.standard_normal(out=ab[rows])
        for normal in (gn, an):
            if normal is not None:
                g.standard_normal(out=normal[rows])
        for uniform in (gs, as_):
            if uniform is not None:
                g.random(out=uniform[rows])
    return ImuDraws(MotionRealisation.concatenate(rockings), gb, ab, gn, an, gs, as_)


def simulate_imu(
    scenario: Scenario,
    errors: SensorErrors | None = None,
    *,
    n_trials: int | None = None,
    rng=None,
    draws: ImuDraws | None = None,
    truth_stride: int | None = None,
    limits: budget.Limits | None = None,
) -> ImuRecord:
    """Sensor increments of ``n_trials`` independent rocking records.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking, lever arm and sampling.
    errors : SensorErrors, optional
        Sensor errors (default ideal sensors).
    n_trials : int
        Independent trials (with ``rng``).
    rng : Generator | SeedSequence | int | None
        Random stream (rocking phases and amplitudes, biases, noise, quantisation residues).
    draws : ImuDraws, optional
        Those random numbers drawn before (:func:`draw_imu`), instead of ``n_trials`` and ``rng``:
        the same trials again, at another rocking amplitude if ``scenario`` differs by it.
    truth_stride : int, optional
        Truth every ``truth_stride`` samples (default: at the start and the end only).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ImuRecord

    Raises
    ------
    ValueError
        For a bad size or stride, or a record beyond ``limits`` (naming
        ``n_trials`` and the scenario's ``duration``).

    Examples
    --------
    At rest with heading 0 the gyros measure the Earth rate in NED and the
    accelerometers −g:

    >>> rec = simulate_imu(Scenario(math.radians(45), duration=1.0), n_trials=1, rng=0)
    >>> w = rec.dtheta[0].sum(axis=0) / 1.0
    >>> [round(float(x) / 7.292115e-5, 9) for x in w]
    [0.707106781, 0.0, -0.707106781]
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"Expected `scenario` to be a Scenario, got {type(scenario).__name__}")
    errors = SensorErrors() if errors is None else errors
    if not isinstance(errors, SensorErrors):
        raise TypeError(f"Expected `errors` to be SensorErrors, got {type(errors).__name__}")
    N, dt = scenario.n_samples, scenario.dt
    stride = N if truth_stride is None else as_int(truth_stride, "truth_stride", minimum=1)
    if draws is None:
        draws = draw_imu(scenario, errors, n_trials=n_trials, rng=rng, limits=limits)
    elif not isinstance(draws, ImuDraws):
        raise TypeError(f"Expected `draws` to be ImuDraws, got {type(draws).__name__}")
    elif n_trials is not None or rng is not None:
        raise ValueError("Expected either `draws` or `n_trials` and `rng`, got both")
    n = draws.n_trials
    what = f"`n_trials` = {n:.3g} records of {N + 1:.3g} samples (`duration` = {scenario.duration:.3g} s of the scenario)"
    budget.check(budget.imu_record(n, N + 1, what=what), limits)
    motion = draws.rocking
    if motion.unit is not None:
        motion = motion.rescaled(scenario.motion)  # the same draw at the scenario's amplitudes (checks the model)
    elif motion.coefficients.shape[-1] != scenario.motion.spectrum(N + 1, dt).omega.size:
        raise ValueError("Expected `draws` of the scenario's rocking model, got another")
    _check_draws(draws, errors, N)
    # sensor errors
    e = errors if errors is not None else SensorErrors()
    gb = np.broadcast_to(e.gyro_bias, (n, 3)) + e.gyro_bias_sigma * draws.gyro_bias
    ab = np.broadcast_to(e.accel_bias, (n, 3)) + e.accel_bias_sigma * draws.accel_bias
    gyro_noise = draws.noise_term("gyro", e.gyro_noise * math.sqrt(dt)) if e.gyro_noise else None
    accel_noise = draws.noise_term("accel", e.accel_noise * math.sqrt(dt)) if e.accel_noise else None
    gyro_scale = 1.0 + e.gyro_scale if np.any(e.gyro_scale) else None
    accel_scale = 1.0 + e.accel_scale if np.any(e.accel_scale) else None
    compiled = kernels.use_compiled(None, n * N)
    if compiled and not _still(motion):  # the increments and the sensor terms in one compiled pass
        dtheta, dv = _compiled_increments(scenario, motion, (gb * dt, gyro_scale, gyro_noise), (ab * dt, accel_scale, accel_noise))
    else:
        dtheta, dv = ideal_increments(scenario, motion, compiled=compiled)
        if compiled:  # scale, bias and noise in one compiled pass
            kernels.add_sensor_terms(dtheta, gb * dt, scale=gyro_scale, noise=gyro_noise)
            kernels.add_sensor_terms(dv, ab * dt, scale=accel_scale, noise=accel_noise)
        else:
            if gyro_scale is not None:
                dtheta *= gyro_scale
            if accel_scale is not None:
                dv *= accel_scale
            dtheta += gb[:, None, :] * dt
            dv += ab[:, None, :] * dt
            if gyro_noise is not None:
                dtheta += gyro_noise
            if accel_noise is not None:
                dv += accel_noise
    # truth at the sample instants k·stride
    idx = np.arange(0, N + 1, stride)
    if idx[-1] != N:
        idx = np.append(idx, N)
    if idx.size <= _FEW_POINTS:  # the start and the end: the sum over frequencies, not the whole record
        ang, rate = motion.evaluate_points(idx, derivatives=1)
    else:
        (ang, rate), scale = motion.unit_evaluation(N + 1, 0.0, derivatives=1)
        ang, rate = scale * ang[:, idx], scale * rate[:, idx]
    angles = ang + scenario.stable_angles
    C = attitude_matrix(angles)
    velocity = np.einsum("...ij,...j->...i", C, np.cross(body_rate(angles, rate), scenario.lever_arm))
    if e.gyro_quantum > 0:
        dtheta = _quantise(dtheta, e.gyro_quantum, draws.gyro_start * e.gyro_quantum)
    if e.accel_quantum > 0:
        dv = _quantise(dv, e.accel_quantum, draws.accel_start * e.accel_quantum)
    return ImuRecord(scenario, errors, dtheta, dv, idx * dt, angles, velocity, rate, np.ascontiguousarray(gb), np.ascontiguousarray(ab))
