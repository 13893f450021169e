"""GNSS-aided in-motion alignment: a navigator on a manoeuvring vehicle and the Kalman filter that aligns it.

A strapdown navigator (attitude, NED velocity, latitude, longitude, height)
runs on the epoch increments (:mod:`~strapdown.analysis.alignment.preintegration`) of a vehicle driving a
:class:`~strapdown.analysis.alignment.trajectory.Manoeuvre`, from an initial attitude, velocity and
position with errors drawn from the filter's prior.  Every GNSS epoch its
velocity and position are compared with the GNSS fixes (the truth plus white
noise), and a closed-loop error-state filter over

    x = (φ, δv, δp, ε, ∇)

(attitude error ``C̃ = (I − [φ×]) C``, velocity and NED position errors, gyro and
accelerometer biases in body axes) corrects it
(:func:`strapdown.analysis.alignment.error_model.navigation_error_model` with
transport rate and position states).  The model is linearised along the true
trajectory, which every trial shares, so filterpy runs the covariances once
(:func:`aided_sequence`) and the gains serve all trials at once.

While the vehicle drives straight at constant speed its heading error acts like
the cross-track accelerometer bias only through the Earth rate; a horizontal
acceleration turns the heading error into a cross-track velocity error
``a × φ_D`` at once, and when the acceleration changes direction in the body
(a weave) the heading separates from the biases.  The *aided floor* of a
trial is what its biases leave in the heading once the filter has done what the
manoeuvre allows: the linear closed loop's response to the trial's biases
(:func:`aided_floor`); at rest it is the gyro-bias floor ``ε_E/(Ω cos φ)``,
under a weave it falls towards zero.

References
----------
Groves (2013), ch. 14 (INS/GNSS integration), sec. 14.2 (the error model).
Rogers, R. M., *Applied Mathematics in Integrated Navigation Systems*, 3rd ed.,
AIAA, 2007, ch. 12 (in-motion alignment).

Public API
----------
AidedTuning, AidedSequence, aided_sequence, AidedInputs, aided_inputs,
AidedResult, aided_alignment, aided_floor, AidedKernel, AidedMonteCarlo,
aided_monte_carlo, time_to_align, navigator_step, ned_offset
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from ..core import budget, kalman, montecarlo
from ..core import quaternion as quat
from ..core.validation import as_int, nonnegative, positive
from ..core.verdicts import Verdict
from ..gyrocompass.rocking import as_generator
from . import kernels
from .comparison import TrialSummary, floor_reached, summarise
from .earth import EARTH_RATE, SOMIGLIANA, normal_gravity
from .error_model import navigation_error_model
from .preintegration import preintegrate
from .sensor_models import SensorSpec, simulate_sensor_errors
from .trajectory import WGS84_A, WGS84_E2, Manoeuvre, radii, trajectory_increments, trajectory_state

__all__ = [
    "AidedTuning",
    "AidedSequence",
    "aided_sequence",
    "AidedInputs",
    "aided_inputs",
    "AidedResult",
    "aided_alignment",
    "aided_floor",
    "AidedKernel",
    "AidedMonteCarlo",
    "aided_monte_carlo",
    "time_to_align",
    "navigator_step",
    "ned_offset",
]


@dataclass(frozen=True)
class AidedTuning:
    """What the aided filter assumes, and the rates it runs at.

    Parameters
    ----------
    epoch : float
        Navigator step [s] (rounded to whole samples).
    gnss_interval : float
        Interval between GNSS fixes [s] (rounded to whole epochs).
    velocity_noise : float
        GNSS velocity noise, per axis [m/s].
    position_noise : float
        GNSS position noise, per axis [m].
    prior_tilt, prior_heading : float
        Prior standard deviations of the tilt and azimuth errors [rad].
    prior_velocity : float
        [m/s].
    prior_position : float
        [m].
    gyro_bias, accel_bias : float
        Prior standard deviations of the biases [rad/s, m/s²].
    gyro_noise, accel_noise : float
        Angle and velocity random walk [rad/√s, m/s/√s].
    gyro_bias_walk, accel_bias_walk : float
        Rate random walk of the biases [rad/s/√s, m/s²/√s].
    """

    epoch: float = 0.2
    gnss_interval: float = 1.0
    velocity_noise: float = 0.05
    position_noise: float = 1.0
    prior_tilt: float = math.radians(0.2)
    prior_heading: float = math.radians(3.0)
    prior_velocity: float = 0.1
    prior_position: float = 2.0
    gyro_bias: float = math.radians(1.0) / 3600.0
    accel_bias: float = 2e-3
    gyro_noise: float = 0.0
    accel_noise: float = 0.0
    gyro_bias_walk: float = 0.0
    accel_bias_walk: float = 0.0

    def __post_init__(self):
        for name in ("epoch", "gnss_interval", "velocity_noise", "position_noise", "prior_tilt", "prior_heading", "prior_velocity", "prior_position", "gyro_bias", "accel_bias"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        for name in ("gyro_noise", "accel_noise", "gyro_bias_walk", "accel_bias_walk"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))

    @classmethod
    def for_sensors(cls, gyro: SensorSpec, accel: SensorSpec, **kw) -> AidedTuning:
        """A filter that knows the sensors' turn-on biases, random walks and rate random walks.

        Parameters
        ----------
        gyro, accel : SensorSpec
            The data sheet.
        **kw
            Other fields.

        Returns
        -------
        AidedTuning
        """
        return cls(
            gyro_bias=max(gyro.turn_on_bias, 1e-12), accel_bias=max(accel.turn_on_bias, 1e-12), gyro_noise=gyro.random_walk, accel_noise=accel.random_walk,
            gyro_bias_walk=gyro.rate_random_walk, accel_bias_walk=accel.rate_random_walk, **kw,
        )  # fmt: skip


@dataclass(frozen=True)
class AidedSequence:
    """The filter's gains and covariances along a trajectory (the same for every trial).

    Attributes
    ----------
    times : ndarray
        ``(E + 1,)`` epoch boundaries of the navigator [s].
    F : ndarray
        ``(U, 15, 15)`` transitions from one fix to the next (the error model
        at the middle of the interval; the closed loop keeps the predicted
        error at zero between fixes, so the filter runs at the fixes only).
    updates : ndarray
        ``(U,)`` epochs (0-based) ending with a GNSS fix.
    gains : ndarray
        ``(U, 15, 6)`` Kalman gains at the fixes.
    posterior : ndarray
        ``(U, 15, 15)`` covariances after each fix.
    innovation : ndarray
        ``(U, 6, 6)`` innovation covariances.
    H : ndarray
        ``(6, 15)``.
    R : ndarray
        ``(6, 6)``.
    P0 : ndarray
        ``(15, 15)`` prior.
    names : tuple of str
        State names.
    """

    times: np.ndarray
    F: np.ndarray
    updates: np.ndarray
    gains: np.ndarray
    posterior: np.ndarray
    innovation: np.ndarray
    H: np.ndarray
    R: np.ndarray
    P0: np.ndarray
    names: tuple

    @property
    def heading_sigma(self) -> np.ndarray:
        """``(U,)`` the filter's azimuth standard deviation after each fix [rad]."""
        return np.sqrt(self.posterior[:, 2, 2])

    @property
    def update_times(self) -> np.ndarray:
        """``(U,)`` times of the fixes [s]."""
        return self.times[self.updates + 1]


def _prior(tuning: AidedTuning) -> np.ndarray:
    t = tuning
    return np.diag(np.square([t.prior_tilt, t.prior_tilt, t.prior_heading] + [t.prior_velocity] * 3 + [t.prior_position] * 3 + [t.gyro_bias] * 3 + [t.accel_bias] * 3))


def aided_sequence(man: Manoeuvre, tuning: AidedTuning, *, sample_rate: float, duration: float, limits: budget.Limits | None = None) -> AidedSequence:
    """Linearise the error model along the true trajectory and run filterpy's covariances through it.

    Parameters
    ----------
    man : Manoeuvre
        The drive.
    tuning : AidedTuning
        The filter.
    sample_rate : float, keyword-only
        IMU rate [Hz].
    duration : float, keyword-only
        [s].
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AidedSequence

    Raises
    ------
    ValueError
        A non-positive rate or duration, or a drive beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).
    """
    fs = positive(sample_rate, "sample_rate")
    M = max(1, int(round(tuning.epoch * fs)))
    D = M / fs
    K = max(1, int(round(tuning.gnss_interval / D)))
    T = positive(duration, "duration")
    U = int(round(T * fs)) // (M * K)
    E = U * K
    what = f"`duration` = {T:.3g} s ({U:.3g} GNSS fixes and {E:.3g} epochs of the filter)"
    budget.check(budget.AIDED_FIX.estimate(U, what=what, extra_bytes=8.0 * (E + 1)), limits)
    # the sequence depends on the rate only through the epoch D: another rate with the same epoch gets the kept one
    return _sequence(man, tuning, D, K, U, limits)


@lru_cache(maxsize=16)
def _sequence(man: Manoeuvre, tuning: AidedTuning, D: float, K: int, U: int, limits) -> AidedSequence:
    """:func:`aided_sequence` for an epoch D [s], K epochs per fix and U fixes, its arrays read-only."""
    E = U * K
    times = D * np.arange(E + 1)
    step = K * D
    mid = trajectory_state(man, step * (np.arange(U) + 0.5), limits=limits)
    models = [
        navigation_error_model(lat, velocity=v, specific_force=f, attitude=C, height=man.height, biases="body", position=True, transport=True,
                               gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise, gyro_bias_walk=tuning.gyro_bias_walk,
                               accel_bias_walk=tuning.accel_bias_walk)
        for lat, v, f, C in zip(mid.latitude, mid.velocity, mid.specific_force, mid.attitude)
    ]  # fmt: skip
    A = np.stack([m.A for m in models])
    m0 = models[0]
    n = A.shape[1]
    # Van Loan for every interval at once: F = expm(A Δ), Q = F ∫ e^{−As} Qc e^{−Aᵀs} ds
    VL = np.zeros((U, 2 * n, 2 * n))
    VL[:, :n, :n] = -A
    VL[:, :n, n:] = m0.Qc
    VL[:, n:, n:] = np.swapaxes(A, 1, 2)
    X = expm(VL * step)
    F = np.swapaxes(X[:, n:, n:], 1, 2)
    Q = F @ X[:, :n, n:]
    Q = 0.5 * (Q + np.swapaxes(Q, 1, 2))
    R = np.diag([tuning.velocity_noise**2] * 3 + [tuning.position_noise**2] * 3)
    P0 = _prior(tuning)
    kf = kalman.make_filter(F[0], Q[0], m0.H, R, np.zeros(n), P0)
    z = np.zeros((6, 1))
    gains, post, innov = [], [], []
    for u in range(U):  # filterpy's predict and update, one fix at a time
        kf.predict(F=F[u], Q=Q[u])
        kf.update(z)
        gains.append(kf.K.copy())
        post.append(kf.P.copy())
        innov.append(kf.S.copy())
    updates = K * np.arange(1, U + 1) - 1
    seq = AidedSequence(times, F, updates, np.array(gains), np.array(post), np.array(innov), m0.H, R, P0, m0.names)
    for a in (seq.times, seq.F, seq.updates, seq.gains, seq.posterior, seq.innovation, seq.H, seq.R, seq.P0):
        a.flags.writeable = False
    return seq


@dataclass(frozen=True)
class AidedInputs:
    """What every trial of a drive shares: the ideal increments, the truth at the epoch boundaries, the filter.

    Attributes
    ----------
    manoeuvre : Manoeuvre
        The drive.
    tuning : AidedTuning
        The filter.
    sample_rate : float
        [Hz].
    dtheta, dv : ndarray
        ``(N, 3)`` ideal increments [rad, m/s].
    truth_latitude, truth_longitude : ndarray
        ``(E + 1,)`` at the epoch boundaries [rad].
    truth_velocity : ndarray
        ``(E + 1, 3)`` [m/s].
    truth_attitude : ndarray
        ``(E + 1, 3, 3)``.
    truth_heading : ndarray
        ``(E + 1,)`` [rad].
    sequence : AidedSequence
        Gains and covariances.
    """

    manoeuvre: Manoeuvre
    tuning: AidedTuning
    sample_rate: float
    dtheta: np.ndarray = field(repr=False)
    dv: np.ndarray = field(repr=False)
    truth_latitude: np.ndarray = field(repr=False)
    truth_longitude: np.ndarray = field(repr=False)
    truth_velocity: np.ndarray = field(repr=False)
    truth_attitude: np.ndarray = field(repr=False)
    truth_heading: np.ndarray = field(repr=False)
    sequence: AidedSequence = field(repr=False)

    @property
    def samples_per_epoch(self) -> int:
        """M."""
        return max(1, int(round(self.tuning.epoch * self.sample_rate)))


def aided_inputs(man: Manoeuvre, tuning: AidedTuning, *, sample_rate: float = 20.0, duration: float = 300.0, limits: budget.Limits | None = None) -> AidedInputs:
    """Simulate the drive once: ideal increments, the truth at the epoch boundaries, the filter's gains.

    Parameters
    ----------
    man : Manoeuvre
        The drive.
    tuning : AidedTuning
        The filter.
    sample_rate : float, keyword-only
        IMU rate [Hz].
    duration : float, keyword-only
        [s].
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of each stage, the increments and
        the filter (default 2 GB, 300 s); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AidedInputs

    Raises
    ------
    ValueError
        A non-positive rate or duration, or a drive beyond ``limits``
        (naming ``duration`` and ``sample_rate``).
    """
    dth, dv, sol = trajectory_increments(man, sample_rate, duration, limits=limits)
    seq = aided_sequence(man, tuning, sample_rate=sample_rate, duration=duration, limits=limits)
    st = trajectory_state(man, seq.times, solution=sol)
    return AidedInputs(man, tuning, float(sample_rate), dth, dv, st.latitude, st.longitude, st.velocity, st.attitude, st.heading, seq)


@dataclass(frozen=True)
class AidedResult:
    """The aided alignment of ``n`` trials.

    Attributes
    ----------
    times : ndarray
        ``(U,)`` times of the fixes [s].
    heading_error : ndarray
        ``(n, U)`` azimuth error ``ψ̂ − ψ`` after each fix [rad].
    nees, nis : ndarray
        ``(n, U)`` at each fix.
    heading_sigma : ndarray
        ``(U,)`` the filter's azimuth standard deviation [rad].
    gyro_bias, accel_bias : ndarray
        ``(n, 3)`` the trials' true biases (turn-on), body axes.
    """

    times: np.ndarray
    heading_error: np.ndarray
    nees: np.ndarray
    nis: np.ndarray
    heading_sigma: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray


def _cross(a, b):
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1], a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2], a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def _ned_offset(lat, lon, h, lat_t, lon_t, h_t):
    """NED metres of a position from the true one (the position-error states)."""
    RN, RE = radii(lat_t)
    return np.stack([(lat - lat_t) * (RN + h_t), (lon - lon_t) * (RE + h_t) * np.cos(lat_t), -(h - h_t)], axis=-1)


def _terms(spec: SensorSpec) -> int:
    """Noise terms :func:`simulate_sensor_errors` draws for ``spec``."""
    return int(bool(spec.random_walk)) + spec.gauss_markov()[0].size + int(bool(spec.rate_random_walk))


def _trials_estimate(inputs: AidedInputs, gyro: SensorSpec, accel: SensorSpec, trials: float, held: float, calls: float, what: str) -> budget.Estimate:
    """Time of ``trials`` trials of the aided navigator and filter in ``calls`` calls, memory of ``held`` of them at once."""
    N = float(inputs.dtheta.shape[0])
    seconds = sum(budget.sensor_errors(3.0 * trials * N, _terms(s), what=what).seconds for s in (gyro, accel))
    seconds += budget.AIDED_TRIAL_SAMPLE.estimate(trials * N, what=what).seconds
    seconds += calls * budget.AIDED_EPOCH_SECONDS * N / inputs.samples_per_epoch  # the epoch loop's overhead, whatever the trials
    memory = budget.sensor_errors(3.0 * held * N, 1, what=what).memory + budget.AIDED_TRIAL_SAMPLE.estimate(held * N, what=what).memory
    return budget.Estimate(seconds, memory, what)


def aided_alignment(inputs: AidedInputs, gyro: SensorSpec, accel: SensorSpec, *, n_trials: int, rng=None, initial_errors: bool = True, gnss_noise: bool = True,
                    limits: budget.Limits | None = None) -> AidedResult:  # fmt: skip
    """Run the aided navigator and filter on ``n_trials`` trials of a drive.

    The navigator keeps its attitude as the quaternion Λ of ``C_b^n``
    (:mod:`strapdown.analysis.core.quaternion`) and steps it by the epoch
    rotation and the turn of the navigation frame; velocity with the
    rotation-compensated velocity increment, gravity, Coriolis and transport
    terms; latitude, longitude and height by the trapezoidal rule.  One step
    per epoch, vectorised over trials (:func:`navigator_step`), or the epochs
    between two fixes in one compiled loop (:func:`~strapdown.analysis.alignment.kernels.navigator_loop`,
    when it pays off: :func:`~strapdown.analysis.alignment.kernels.use_compiled`), equal to the last bit.

    Parameters
    ----------
    inputs : AidedInputs
        The drive, its truth and the filter (:func:`aided_inputs`).
    gyro, accel : SensorSpec
        The sensors (their errors are drawn per trial).
    n_trials : int, keyword-only
        Trials.
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of the sensor errors, the initial errors and the GNSS noise.
    initial_errors : bool, keyword-only
        Start from errors drawn from the prior (False: from the truth).
    gnss_noise : bool, keyword-only
        Add white noise to the fixes (False: the fixes are the truth).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AidedResult

    Raises
    ------
    ValueError
        ``n_trials`` below 1, or trials beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``n_trials``).
    """
    g = as_generator(rng)
    n = as_int(n_trials, "n_trials", minimum=1)
    seq = inputs.sequence
    fs = inputs.sample_rate
    N = inputs.dtheta.shape[0]
    M = inputs.samples_per_epoch
    budget.check(_trials_estimate(inputs, gyro, accel, n, n, 1, f"`n_trials` = {n:.3g} trials of {N:.3g} IMU samples"), limits)
    ge = simulate_sensor_errors(gyro, n_trials=n, n_samples=N, dt=1.0 / fs, rng=g, limits=limits)
    ae = simulate_sensor_errors(accel, n_trials=n, n_samples=N, dt=1.0 / fs, rng=g, limits=limits)
    ep = preintegrate(inputs.dtheta[None] + ge.increments, inputs.dv[None] + ae.increments, 1.0 / fs, M)
    D = ep.epoch
    E = seq.times.size - 1
    qt = quat.normalize(Rotation.from_matrix(inputs.truth_attitude).as_quat(scalar_first=True))
    # initial errors from the prior: C̃ = exp(−[φ×]) C, v, p and the bias estimates at zero
    x0 = g.standard_normal((n, 15)) * np.sqrt(np.diag(seq.P0)) * float(initial_errors)
    q = quat.multiply(quat.rotvec_to_quat(-x0[:, 0:3], validate=False), qt[0])
    h0 = inputs.manoeuvre.height
    lat_t, lon_t = inputs.truth_latitude, inputs.truth_longitude
    RN, RE = radii(lat_t[0])
    v = inputs.truth_velocity[0] + x0[:, 3:6]
    lat = lat_t[0] + x0[:, 6] / (RN + h0)
    lon = lon_t[0] + x0[:, 7] / ((RE + h0) * math.cos(lat_t[0]))
    h = h0 - x0[:, 8]
    bg, ba = np.zeros((n, 3)), np.zeros((n, 3))
    U = seq.updates.size
    noise = g.standard_normal((n, U, 6)) * np.sqrt(np.diag(seq.R)) * float(gnss_noise)
    heading, nees, nis = np.empty((n, U)), np.empty((n, U)), np.empty((n, U))
    Pinv, Sinv = np.linalg.inv(seq.posterior), np.linalg.inv(seq.innovation)
    KT = np.swapaxes(seq.gains, 1, 2)
    u = 0
    compiled = kernels.use_compiled(None, n * E)
    constants = np.array([EARTH_RATE, WGS84_A, WGS84_E2, *SOMIGLIANA, quat.SERIES_ANGLE])
    stop = 0
    while stop < E:  # the epochs up to the next fix, then the fix
        start, stop = stop, min(int(seq.updates[u]) + 1, E) if u < U else E
        if compiled:  # the same steps in one compiled loop, equal to the last bit
            q, v, lat, lon, h = kernels.navigator_loop(q, v, lat, lon, h, bg, ba, ep.rotation[:, start:stop], ep.velocity[:, start:stop], ep.moment[:, start:stop], D, constants)
        else:
            for j in range(start, stop):  # one step per epoch, vectorised over trials
                q, v, lat, lon, h = navigator_step(q, v, lat, lon, h, bg, ba, ep.rotation[:, j], ep.velocity[:, j], ep.moment[:, j], D)
        j = stop - 1
        if u < U and seq.updates[u] == j:
            vt = inputs.truth_velocity[j + 1]
            y = np.concatenate([v - vt, _ned_offset(lat, lon, h, lat_t[j + 1], lon_t[j + 1], h0)], axis=1) + noise[:, u]
            x = y @ KT[u]  # the closed loop keeps the predicted error at zero: the innovation is the measurement
            q = quat.normalize(quat.multiply(quat.rotvec_to_quat(x[:, 0:3], validate=False), q))
            RN, RE = radii(lat)
            v = v - x[:, 3:6]
            lat = lat - x[:, 6] / (RN + h)
            lon = lon - x[:, 7] / ((RE + h) * np.cos(lat))
            h = h + x[:, 8]
            bg, ba = bg + x[:, 9:12], ba + x[:, 12:15]
            # scoring against the truth: C̃ Cᵀ = exp(−[φ×])
            phi = -quat.quat_to_rotvec(quat.multiply(q, quat.conjugate(qt[j + 1])), validate=False)
            err = np.concatenate([phi, v - vt, _ned_offset(lat, lon, h, lat_t[j + 1], lon_t[j + 1], h0), ge.turn_on - bg, ae.turn_on - ba], axis=1)
            nees[:, u] = np.einsum("ni,ij,nj->n", err, Pinv[u], err)
            nis[:, u] = np.einsum("ni,ij,nj->n", y, Sinv[u], y)
            heading[:, u] = -phi[:, 2]
            u += 1
    return AidedResult(seq.update_times, heading, nees, nis, seq.heading_sigma, ge.turn_on, ae.turn_on)


def navigator_step(q, v, lat, lon, h, gyro_bias, accel_bias, rotation, velocity, moment, epoch):
    """One epoch of the aided navigator (local-level NED, WGS-84), vectorised over trials.

    The attitude quaternion Λ of ``C_b^n`` is stepped by the epoch rotation (the
    gyro bias estimate taken out) and the turn of the navigation frame
    ``ω_in^n = ω_ie^n + ω_en^n``; the velocity by the rotation-compensated velocity
    increment (the accelerometer bias estimate taken out, the frame's turn over the epoch by
    the velocity's first moment), gravity (with its free-air decrease), Coriolis and
    transport terms; latitude, longitude and height by the trapezoidal rule.

    Parameters
    ----------
    q : ndarray
        ``(n, 4)`` attitude quaternions of ``C_b^n``.
    v : ndarray
        ``(n, 3)`` NED velocity [m/s].
    lat, lon, h : ndarray
        ``(n,)`` latitude, longitude [rad] and height [m].
    gyro_bias, accel_bias : ndarray
        ``(n, 3)`` bias estimates, body axes [rad/s, m/s²].
    rotation : ndarray
        ``(n, 4)`` the epoch rotation (:mod:`~strapdown.analysis.alignment.preintegration`).
    velocity, moment : ndarray
        ``(n, 3)`` the epoch's velocity increment [m/s] and its first moment [m], epoch-start body frame.
    epoch : float
        The epoch D [s].

    Returns
    -------
    tuple
        ``(q, v, lat, lon, h)`` at the epoch's end.

    References
    ----------
    Groves (2013), sec. 5.4 (the local-navigation-frame equations).
    """
    D = epoch
    RN, RE = radii(lat)
    cl = np.cos(lat)
    wie = EARTH_RATE * np.stack([cl, np.zeros_like(lat), -np.sin(lat)], axis=-1)
    wen = np.stack([v[:, 1] / (RE + h), -v[:, 0] / (RN + h), -v[:, 1] * np.tan(lat) / (RE + h)], axis=-1)
    win = wie + wen
    dv_nav = quat.rotate(q, velocity - accel_bias * D) - _cross(win, quat.rotate(q, moment))
    gd = normal_gravity(lat) * (1.0 - 2.0 * h / WGS84_A)
    v_new = v + dv_nav - _cross(2.0 * wie + wen, v) * D
    v_new[:, 2] += gd * D
    va = 0.5 * (v + v_new)
    lat_new = lat + va[:, 0] * D / (RN + h)
    lon = lon + va[:, 1] * D / ((RE + h) * cl)
    h = h - va[:, 2] * D
    q = quat.multiply(quat.multiply(quat.rotvec_to_quat(-win * D, validate=False), q), quat.multiply(rotation, quat.rotvec_to_quat(-gyro_bias * D, validate=False)))
    return q, v_new, lat_new, lon, h


def ned_offset(lat, lon, h, lat_ref, lon_ref, h_ref):
    """NED metres of a position from a reference one (the position-error states, to first order).

    Parameters
    ----------
    lat, lon, h : array_like
        The position [rad, rad, m].
    lat_ref, lon_ref, h_ref : array_like
        The reference [rad, rad, m].

    Returns
    -------
    ndarray
        ``(..., 3)`` [m].
    """
    return _ned_offset(lat, lon, h, lat_ref, lon_ref, h_ref)


def aided_floor(sequence: AidedSequence, gyro_bias, accel_bias) -> np.ndarray:
    """The azimuth error each trial's biases leave after the filter: the linear closed loop's response to them.

    ``e ← F_u e`` from fix to fix and ``e ← (I − K H) e`` at every fix, from
    ``e_0 = (0, …, ε, ∇)``; the azimuth error is ``−φ_D`` at the end.

    Parameters
    ----------
    sequence : AidedSequence
        The filter along the drive.
    gyro_bias, accel_bias : array_like
        ``(n, 3)`` biases, body axes [rad/s, m/s²].

    Returns
    -------
    ndarray
        ``(n,)`` [rad].
    """
    b = np.concatenate([np.asarray(gyro_bias, dtype=float), np.asarray(accel_bias, dtype=float)], axis=1)
    e = np.zeros((b.shape[0], 15))
    e[:, 9:15] = b
    for u in range(sequence.F.shape[0]):
        e = e @ sequence.F[u].T
        e = e - (e @ sequence.H.T) @ sequence.gains[u].T
    return -e[:, 2]


@dataclass(frozen=True)
class AidedKernel:
    """Monte Carlo kernel of the aided alignment: one row per trial (final azimuth error, floor, NEES and NIS at the checks).

    Parameters
    ----------
    inputs : AidedInputs
        The drive.
    gyro, accel : SensorSpec
        The sensors.
    checks : tuple of int
        Fixes (0-based) whose NEES and NIS are returned.
    """

    inputs: AidedInputs
    gyro: SensorSpec
    accel: SensorSpec
    checks: tuple

    def __call__(self, n_trials: int, rng) -> np.ndarray:
        r = aided_alignment(self.inputs, self.gyro, self.accel, n_trials=n_trials, rng=rng)
        floor = aided_floor(self.inputs.sequence, r.gyro_bias, r.accel_bias)
        idx = list(self.checks)
        return np.concatenate([r.heading_error[:, -1:], floor[:, None], r.nees[:, idx], r.nis[:, idx]], axis=1)


@dataclass(frozen=True)
class AidedMonteCarlo:
    """Monte Carlo of the aided alignment on one drive.

    Attributes
    ----------
    manoeuvre : Manoeuvre
        The drive.
    n_trials : int
        Trials.
    error : TrialSummary
        Final azimuth error [rad].
    floor : TrialSummary
        The trials' aided floors [rad].
    residual : TrialSummary
        Error minus floor [rad].
    floor_reached : Verdict
        Whether the aided floor is reached
        (:func:`strapdown.analysis.alignment.comparison.floor_reached`).
    heading_sigma : float
        The filter's final azimuth standard deviation [rad].
    check_times : ndarray
        Times of the NEES/NIS checks [s].
    nees, nis : ndarray
        Mean NEES and NIS at the checks.
    nees_band, nis_band : tuple
        Their bands, each at ``1 − 0.05/(2K)`` for K checks, so that a
        consistent filter has all 2K means inside at 95 % together (Bonferroni).
    """

    manoeuvre: Manoeuvre
    n_trials: int
    error: TrialSummary
    floor: TrialSummary
    residual: TrialSummary
    floor_reached: Verdict
    heading_sigma: float
    check_times: np.ndarray
    nees: np.ndarray
    nis: np.ndarray
    nees_band: tuple
    nis_band: tuple

    @property
    def consistent(self) -> bool:
        """Every mean NEES and NIS inside its band."""
        ok = lambda x, b: bool(np.all((x >= b[0]) & (x <= b[1])))  # noqa: E731
        return ok(self.nees, self.nees_band) and ok(self.nis, self.nis_band)


def aided_monte_carlo(inputs: AidedInputs, gyro: SensorSpec, accel: SensorSpec, *, n_trials: int, rng=None, trials_per_block: int = 32, executor=None,
                      limits: budget.Limits | None = None) -> AidedMonteCarlo:  # fmt: skip
    """Monte Carlo of the aided alignment of one drive against the filter's own prediction and the aided floor.

    Parameters
    ----------
    inputs : AidedInputs
        The drive (:func:`aided_inputs`).
    gyro, accel : SensorSpec
        The sensors.
    n_trials : int, keyword-only
        Trials, at least 2.
    rng : Generator | SeedSequence | int | None, keyword-only
        Root of the block streams.
    trials_per_block : int, keyword-only
        Trials per block (the unit of randomness).
    executor : Executor | dask Client | None, keyword-only
        Where blocks run.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time, on one core (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AidedMonteCarlo

    Raises
    ------
    ValueError
        ``n_trials`` below 2, or trials beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``n_trials``).
    """
    n = as_int(n_trials, "n_trials", minimum=2)
    per_block = min(as_int(trials_per_block, "trials_per_block", minimum=1), n)
    blocks = -(-n // per_block)
    est = _trials_estimate(inputs, gyro, accel, n, per_block, blocks, f"`n_trials` = {n:.3g} trials of {inputs.dtheta.shape[0]:.3g} IMU samples")
    budget.check(budget.Estimate(est.seconds, est.memory + 128.0 * n + 500.0 * blocks, est.what), limits)  # the rows and one task per block
    seq = inputs.sequence
    U = seq.updates.size
    checks = tuple(int(x) for x in np.unique(np.round(np.geomspace(1, U, 6)).astype(int)) - 1)
    rows = montecarlo.collect(AidedKernel(inputs, gyro, accel, checks), n, rng=rng, trials_per_block=per_block, blocks_per_chunk=1, executor=executor)
    k = len(checks)
    e, f = rows[:, 0], rows[:, 1]
    return AidedMonteCarlo(
        inputs.manoeuvre, n, summarise(e), summarise(f), summarise(e - f), floor_reached(e, f, what="the aided floor"), float(seq.heading_sigma[-1]), seq.update_times[list(checks)],
        rows[:, 2 : 2 + k].mean(axis=0), rows[:, 2 + k : 2 + 2 * k].mean(axis=0), kalman.chi2_band(15, n, 1.0 - 0.05 / (2 * k)), kalman.chi2_band(6, n, 1.0 - 0.05 / (2 * k)),
    )  # fmt: skip


def time_to_align(sigma, times, budget: float) -> float:
    """The first time after which a predicted azimuth standard deviation stays within ``budget`` (inf if it never does).

    Parameters
    ----------
    sigma : array_like
        ``(K,)`` standard deviations [rad].
    times : array_like
        ``(K,)`` their times [s].
    budget : float
        [rad].

    Returns
    -------
    float

    >>> time_to_align([3.0, 2.0, 0.5, 0.7, 0.4], [1, 2, 3, 4, 5], 0.6)
    5.0
    """
    s, t = np.asarray(sigma, dtype=float), np.asarray(times, dtype=float)
    above = np.flatnonzero(s > budget)
    if above.size == 0:
        return float(t[0])
    if above[-1] == s.size - 1:
        return math.inf
    return float(t[above[-1] + 1])

