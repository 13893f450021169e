"""Kalman fine alignment on a rocking base, with NEES and NIS consistency.

A strapdown navigator runs in the NED frame from an initial attitude with an
error drawn from the filter's prior (the accuracy of a coarse alignment), and
its velocity is compared, every epoch, with the zero velocity of the rocking
centre.  A closed-loop error-state Kalman filter estimates

    x = (φ, δv, ε^n, ∇^n[, θ_r, θ_r'])

the attitude error φ (``C̃ = (I − [φ×]) C``; φ_N, φ_E are the tilt errors,
``−φ_D`` the azimuth error), the velocity error δv, the gyro and accelerometer
biases resolved in the navigation frame (constants while the attitude is), and
optionally the rocking itself: the angles and rates of the three axes as the
states of the second-order shaping filter ``θ'' + 2ζω0 θ' + ω0² θ = w`` per
axis, the *rocking model the filter assumes* (:class:`Disturbance`).  A block
at the lever arm r from the rocking centre moves with ``v_r = C (ω × r)
≈ L θ_r'``, ``L = −C0 [r×] J0``, which the velocity measurement sees.  The
error dynamics are

    φ' = −ω_ie × φ − ε^n,   δv' = f^n × φ − 2 ω_ie × δv + ∇^n,

discretised exactly (Van Loan), with the measurement ``z = v_INS = δv + L θ_r' + v``.

The model does not depend on the trial, so filterpy computes the gains and
covariances once (:func:`strapdown.analysis.core.kalman.filter_sequence`) and
they are applied to every trial at once; the navigator integrates the epoch
increments of :mod:`strapdown.analysis.alignment.preintegration`, one Python
step per epoch vectorised over trials.  After every update the attitude and
velocity estimates are fed back and the bias estimates compensate the sensors.

Consistency: the normalised estimation error squared (NEES, the whole state,
against the truth of the simulation) and the normalised innovation squared
(NIS = yᵀ S⁻¹ y) averaged over trials, against their two-sided χ² bands.

References
----------
Bar-Shalom, Y., Li, X. R., Kirubarajan, T., *Estimation with Applications to
Tracking and Navigation*, Wiley, 2001, sec. 5.4 (NEES and NIS tests).
Savage, P. G., *Strapdown Analytics*, 2nd ed., 2007, ch. 12 (the φ-angle error model).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core import kalman
from ..core.validation import as_array, as_float, as_int, nonnegative, positive
from ..gyrocompass.rocking import as_generator
from . import kernels
from .earth import earth_rate_ned, gravity_ned
from .error_model import alignment_error_model, skew
from .estimate import AlignmentEstimate
from .imu import ImuRecord, Scenario, SensorErrors, draw_imu, simulate_imu
from .preintegration import EpochIncrements, preintegrate
from .tilt_attitude import angles_from_matrix, attitude_matrix, euler_rate_matrix

__all__ = [
    "Disturbance",
    "FilterTuning",
    "FineAlignmentModel",
    "FineAlignmentResult",
    "EpochRecord",
    "epoch_record",
    "simulate_epoch_record",
    "draw_epoch_record",
    "FilterDraws",
    "draw_filter",
    "filter_model",
    "fine_alignment",
    "lever_velocity_sigma",
    "lever_matrix",
    "assumed_disturbance",
    "matched_rocking_block",
    "DISTURBANCE_KINDS",
    "MIN_DAMPING",
    "TRUTHS",
]

DISTURBANCE_KINDS = ("none", "white", "shaping", "matched")
#: The kinds whose rocking angles and rates are states of the filter.
_STATE_KINDS = ("shaping", "matched")
#: Smallest damping of the assumed shaping filter: a sinusoid is modelled as a lightly damped
#: oscillator, so that the filter keeps following the harmonics a rocking block adds to it.
MIN_DAMPING = 0.02


@dataclass(frozen=True)
class Disturbance:
    """The rocking as the filter models it (it reaches the measurement through the lever arm).

    Parameters
    ----------
    kind : str
        ``"none"`` (ignored), ``"white"`` (the lever-arm velocity added to the
        measurement noise), ``"shaping"`` (the rocking angles and rates of a
        second-order shaping filter driven by white noise per axis, six more
        states) or ``"matched"`` (the same six states, their transition and
        noise over one epoch matched to the spectrum of ``motion``: the
        second-order Gauss–Markov model whose one-epoch autocovariance is the
        rocking's own, see :func:`matched_rocking_block`).
    sigma : array_like
        Standard deviation of the rocking angle per axis (yaw, β, γ) [rad].
    period : float
        Natural period of the shaping filter [s].
    damping : float
        Damping ratio of the shaping filter, in [0, 1) (0: a sinusoid of random phase).
    motion : rocking model, optional
        ``"matched"`` only: the rocking whose spectrum the states match (a model of
        :mod:`strapdown.analysis.alignment.base_motion` with ``covariance``).
    """

    kind: str = "none"
    sigma: np.ndarray = field(default_factory=lambda: np.zeros(3))
    period: float = 8.0
    damping: float = 0.1
    motion: object = None

    def __post_init__(self):
        if self.kind not in DISTURBANCE_KINDS:
            raise ValueError(f"Expected `kind` in {DISTURBANCE_KINDS}, got {self.kind!r}")
        s = as_array(self.sigma, "sigma").ravel()
        s = np.repeat(s, 3) if s.size == 1 else s
        if s.size != 3 or np.any(s < 0):
            raise ValueError(f"Expected `sigma` as three values >= 0 (yaw, beta, gamma) [rad], got {s.tolist()}")
        object.__setattr__(self, "sigma", s)
        object.__setattr__(self, "period", positive(self.period, "period"))
        d = as_float(self.damping, "damping")
        if not 0.0 <= d < 1.0:
            raise ValueError(f"Expected `damping` in [0, 1), got {d:g}")
        object.__setattr__(self, "damping", d)
        if self.kind == "matched" and not callable(getattr(self.motion, "covariance", None)):
            raise TypeError(f"Expected `motion` a rocking model (with its spectrum) for kind 'matched', got {type(self.motion).__name__}")

    @property
    def has_states(self) -> bool:
        """Whether the rocking angles and rates are states of the filter (``"shaping"``, ``"matched"``)."""
        return self.kind in _STATE_KINDS


@dataclass(frozen=True)
class FilterTuning:
    """What the filter assumes: prior, sensor noise, the disturbance model, the epoch.

    Parameters
    ----------
    epoch : float
        Measurement interval [s] (rounded to whole samples).
    prior_tilt : float
        Prior standard deviation of the tilt errors φ_N, φ_E [rad].
    prior_heading : float
        Prior standard deviation of the azimuth error [rad].
    prior_velocity : float
        Prior standard deviation of the velocity error [m/s] (besides the disturbance).
    gyro_bias : float
        Prior standard deviation of each gyro bias [rad/s].
    accel_bias : float
        Prior standard deviation of each accelerometer bias [m/s²].
    gyro_noise : float
        Angle random walk assumed [rad/√s].
    accel_noise : float
        Velocity random walk assumed [m/s/√s].
    measurement_noise : float
        Standard deviation of the zero-velocity measurement [m/s].
    disturbance : Disturbance
        The rocking model the filter assumes for the lever-arm velocity.
    lever_arm_known : bool
        Compensate the lever-arm velocity with the measured rate and the known lever arm.
    """

    epoch: float = 0.1
    prior_tilt: float = math.radians(0.1)
    prior_heading: float = math.radians(1.0)
    prior_velocity: float = 1e-3
    gyro_bias: float = math.radians(0.01) / 3600.0
    accel_bias: float = 1e-3
    gyro_noise: float = 0.0
    accel_noise: float = 0.0
    measurement_noise: float = 1e-3
    disturbance: Disturbance = field(default_factory=Disturbance)
    lever_arm_known: bool = False

    def __post_init__(self):
        object.__setattr__(self, "epoch", positive(self.epoch, "epoch"))
        for name in ("prior_tilt", "prior_heading", "prior_velocity", "measurement_noise"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        for name in ("gyro_bias", "accel_bias", "gyro_noise", "accel_noise"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        if not isinstance(self.disturbance, Disturbance):
            raise TypeError(f"Expected `disturbance` to be a Disturbance, got {type(self.disturbance).__name__}")


@dataclass(frozen=True)
class FineAlignmentModel:
    """The discrete error model of the filter.

    Attributes
    ----------
    F, Q, H, R, P0 : ndarray
        Transition, process noise, measurement matrix, measurement noise and prior per epoch.
    epoch : float
        Epoch length [s].
    samples_per_epoch : int
        Samples per epoch.
    names : tuple of str
        State names.
    rocking_axes : tuple of int
        Axes (0 yaw, 1 β, 2 γ) whose angle and rate are states (12 + 2k, 13 + 2k).
    """

    F: np.ndarray
    Q: np.ndarray
    H: np.ndarray
    R: np.ndarray
    P0: np.ndarray
    epoch: float
    samples_per_epoch: int
    names: tuple
    rocking_axes: tuple = ()

    @property
    def dim(self) -> int:
        """State dimension."""
        return self.F.shape[0]

    @property
    def has_rocking_states(self) -> bool:
        """Whether the rocking angles and rates are states (``"shaping"``, ``"matched"``)."""
        return bool(self.rocking_axes)


def filter_model(scenario: Scenario, tuning: FilterTuning) -> FineAlignmentModel:
    """Discretise the error model of :mod:`strapdown.analysis.alignment.fine` for a scenario.

    Parameters
    ----------
    scenario : Scenario
        Latitude and sampling.
    tuning : FilterTuning
        What the filter assumes.

    Returns
    -------
    FineAlignmentModel
    """
    M = max(1, int(round(tuning.epoch / scenario.dt)))
    dt = M * scenario.dt
    # the continuous model (A, Qc, H and the state names, shaping states included) is the error model's
    model = alignment_error_model(scenario, tuning)
    A, Qc, H, names = model.A, model.Qc, model.H, model.names
    dist = tuning.disturbance
    axes = tuple(int(a) for a in np.flatnonzero(dist.sigma > 0)) if dist.has_states else ()
    n = A.shape[0]
    P0 = np.zeros((n, n))
    P0[0:3, 0:3] = np.diag([tuning.prior_tilt**2, tuning.prior_tilt**2, tuning.prior_heading**2])
    P0[3:6, 3:6] = tuning.prior_velocity**2 * np.eye(3)
    P0[6:9, 6:9] = tuning.gyro_bias**2 * np.eye(3)
    P0[9:12, 9:12] = tuning.accel_bias**2 * np.eye(3)
    R = tuning.measurement_noise**2 * np.eye(3)
    w = 2.0 * math.pi / dist.period
    s2 = dist.sigma**2
    L = lever_matrix(scenario)
    if dist.kind == "white" and not tuning.lever_arm_known:
        Pv = L @ np.diag(w * w * s2) @ L.T  # the lever-arm velocity of the assumed rocking
        R = R + np.diag(np.diag(Pv))
        P0[3:6, 3:6] += Pv
    F, Q = kalman.discretise(A, Qc, dt)
    if axes:
        blocks = matched_rocking_block(dist.motion, dt, period=dist.period, damping=dist.damping) if dist.kind == "matched" else None
        rate_var = np.empty(len(axes))
        for k, i in enumerate(axes):
            a, b = 12 + 2 * k, 13 + 2 * k
            if blocks is None:
                P0[a, a], P0[b, b] = s2[i], (w * w) * s2[i]
            else:  # the rocking's own covariance and one-epoch prediction (the shaping block is decoupled in A)
                Fm, Qm, R0 = (x[i] for x in blocks)
                P0[a : b + 1, a : b + 1] = R0
                F[a : b + 1, a : b + 1], Q[a : b + 1, a : b + 1] = Fm, Qm
            rate_var[k] = P0[b, b]
        rates = slice(13, n, 2)
        if not tuning.lever_arm_known:
            La = L[:, list(axes)]
            # v_INS(0) = 0, so δv(0) = −L θ_r'(0)
            Pr = np.diag(rate_var)
            P0[3:6, 3:6] += La @ Pr @ La.T
            P0[3:6, rates] = -La @ Pr
            P0[rates, 3:6] = -(La @ Pr).T
    return FineAlignmentModel(F, Q, H, R, P0, dt, M, names, axes)


def matched_rocking_block(motion, epoch: float, *, period: float, damping: float) -> tuple:
    """The second-order Gauss–Markov model of a rocking over one epoch, matched to its spectrum (per axis).

    The state of an axis is ``x = (θ, θ')``.  From the rocking's spectral
    density G, its covariance at lag τ is
    ``C(τ) = E[x(t+τ) x(t)ᵀ] = ∫ G(ω) Re[h(ω) e^{iωτ} h(ω)*ᵀ] dω`` with
    ``h = (1, iω)``.  The discrete model ``x_{k+1} = F x_k + q_k`` takes

    * the rate row of ``F`` from the rocking itself: the best linear
      prediction of ``θ'`` one epoch ahead from ``(θ, θ')`` now, the second row
      of ``C(T) C(0)⁻¹`` (the Yule–Walker equations);
    * the angle row from the shaping filter ``θ'' + 2ζω0 θ' + ω0² θ = w`` of
      the given period and damping (``e^{AT}``), which integrates the rate;
    * ``Q = C(0) − F C(0) Fᵀ``, so that the model keeps the rocking's own
      variances of angle and rate, and the prior ``C(0)``.

    A shaping filter driven by white noise has the narrow-band spectrum
    *without* its cut-off: it predicts the rate worse than the band-limited
    rocking allows, so its Q is too large and its NIS falls below the band.
    The full Yule–Walker model (both rows) predicts each epoch right but not
    several: the pair ``(θ, θ')`` is not Markov for a band-limited rocking, and
    with the angle row of ``C(T) C(0)⁻¹`` the filter grows overconfident in the
    angle (NEES above its band); the oscillator's angle row keeps the angle's
    propagation over many epochs (``tests/test_alignment_methods.py``).

    Parameters
    ----------
    motion : rocking model
        A model of :mod:`strapdown.analysis.alignment.base_motion` (its ``covariance``).
    epoch : float
        T [s].
    period : float, keyword-only
        Natural period ``2π/ω0`` of the shaping filter [s].
    damping : float, keyword-only
        Its damping ratio ζ.

    Returns
    -------
    tuple of ndarray
        ``(F, Q, C0)``, each ``(3, 2, 2)`` (per axis yaw, β, γ).  An axis
        without rocking has ``F = Q = C0 = 0``.

    Raises
    ------
    ValueError
        For an epoch or period that is not positive.

    References
    ----------
    Brockwell, P. J., Davis, R. A., *Time Series: Theory and Methods*, 2nd ed.,
    Springer, 1991, sec. 11.4 (Yule–Walker equations of a multivariate AR(1)).

    >>> from strapdown.analysis.alignment.base_motion import NarrowbandMotion
    >>> F, Q, C0 = matched_rocking_block(NarrowbandMotion(0.01, 8.0, 0.1), 0.5, period=8.0, damping=0.1)
    >>> bool(np.all(np.linalg.eigvalsh(Q[1]) > 0)), bool(abs(C0[1, 0, 0] - 0.01**2 / 2) < 1e-9)
    (True, True)
    """
    from scipy.linalg import expm

    T = positive(epoch, "epoch")
    w0 = 2.0 * math.pi / positive(period, "period")
    z = as_float(damping, "damping")
    h = (lambda w: np.ones_like(w, dtype=complex), lambda w: 1j * w)

    def cov(lag):
        out = np.empty((3, 2, 2))
        for j in range(2):
            for k in range(2):
                out[:, j, k] = motion.covariance(lambda w, j=j: h[j](w) * np.exp(1j * w * lag), h[k])
        return out

    C0, C1 = cov(0.0), cov(T)
    C0 = 0.5 * (C0 + np.swapaxes(C0, 1, 2))
    angle_row = expm(np.array([[0.0, 1.0], [-w0 * w0, -2.0 * z * w0]]) * T)[0]
    F = np.zeros((3, 2, 2))
    Q = np.zeros((3, 2, 2))
    for i in range(3):
        if C0[i, 0, 0] > 0.0:
            F[i, 0] = angle_row
            F[i, 1] = (C1[i] @ np.linalg.inv(C0[i]))[1]
            Qi = C0[i] - F[i] @ C0[i] @ F[i].T
            Q[i] = 0.5 * (Qi + Qi.T)
    return F, Q, C0


def lever_matrix(scenario: Scenario) -> np.ndarray:
    """``L = −C0 [r×] J0``: the lever-arm velocity per unit rocking rate, ``v_r ≈ L θ_r'`` [m/rad].

    Parameters
    ----------
    scenario : Scenario
        Stable attitude and lever arm.

    Returns
    -------
    ndarray
        ``(3, 3)``: NED velocity per (ψ', β', γ').
    """
    C0 = attitude_matrix(scenario.stable_angles)
    return -C0 @ skew(scenario.lever_arm) @ euler_rate_matrix(scenario.stable_angles)


def lever_velocity_sigma(motion, scenario: Scenario) -> np.ndarray:
    """Standard deviation of the lever-arm velocity per NED axis [m/s], to first order in the rocking.

    ``v = C0 (J0 θ_r' × r)`` with C0 the stable attitude and J0 the Euler-rate
    matrix there; the rate variances come from the motion's spectral density.

    Parameters
    ----------
    motion : rocking model
        From :mod:`strapdown.analysis.alignment.base_motion`.
    scenario : Scenario
        Stable attitude, lever arm and sampling.

    Returns
    -------
    ndarray
        ``(3,)``.
    """
    return _lever_sigma(scenario, motion.rate_variance(scenario.dt))


def _lever_sigma(scenario: Scenario, rate_variance) -> np.ndarray:
    """:func:`lever_velocity_sigma` from the rate variances ``(3,)`` of the rocking [rad²/s²]."""
    L = lever_matrix(scenario)
    return np.sqrt((L * L) @ rate_variance)


def assumed_disturbance(motion, scenario: Scenario, *, kind: str = "shaping") -> Disturbance:
    """The disturbance model a filter that assumes ``motion`` would use.

    Parameters
    ----------
    motion : rocking model
        The rocking model the filter assumes (the true one for a filter that knows it).
    scenario : Scenario
        Stable attitude, lever arm and sampling.
    kind : str
        ``"white"``, ``"shaping"`` or ``"matched"`` (``"none"`` when the lever arm
        is zero).  The shaping filter takes the rocking's period and damping (at
        least :data:`MIN_DAMPING`; 0.7 for white rocking); the matched states
        take the one-epoch covariances of ``motion`` itself (:func:`matched_rocking_block`).

    Returns
    -------
    Disturbance
    """
    if kind == "none":
        return Disturbance("none")
    rate_var = motion.rate_variance(scenario.dt)  # one quadrature of the density for both uses
    if not np.any(_lever_sigma(scenario, rate_var)):
        return Disturbance("none")
    sigma = motion.sigma
    rate = np.sqrt(rate_var)
    # the period whose oscillator has the rate variance of the rocking
    period = 2.0 * math.pi * float(np.max(sigma)) / float(np.max(rate)) if motion.name in ("white",) else getattr(motion, "period", 8.0)
    damping = {"sine": MIN_DAMPING, "white": 0.7}.get(motion.name, getattr(motion, "damping", MIN_DAMPING))
    return Disturbance(kind, sigma, period, max(damping, MIN_DAMPING), motion if kind == "matched" else None)


@dataclass(frozen=True)
class FineAlignmentResult:
    """Estimates at the end of the alignment and the consistency of the filter over time.

    Attributes
    ----------
    estimate : AlignmentEstimate
        Heading and tilts at the end, against the truth there.
    times : ndarray
        ``(E,)`` epoch ends [s].
    nees : ndarray
        ``(n, E)`` NEES of the whole state per trial and epoch.
    nis : ndarray
        ``(n, E)`` NIS per trial and epoch.
    heading_error : ndarray
        ``(n, E)`` azimuth error of the corrected navigator [rad].
    heading_sigma : ndarray
        ``(E,)`` the filter's standard deviation of the azimuth error [rad].
    dim : int
        State dimension (degrees of freedom of one NEES).
    meas_dim : int
        Measurement dimension (of one NIS).
    sigma : ndarray or None
        ``(E, 3)`` the filter's standard deviations of φ_N, φ_E and the azimuth error after each
        update [rad] (with ``history=True``).
    gyro_bias_estimate, accel_bias_estimate : ndarray or None
        ``(n, E, 3)`` the estimates ε̂^n [rad/s] and ∇̂^n [m/s²] after each update, NED (with ``history=True``).
    innovation : ndarray or None
        ``(n, E, 3)`` the innovations y = z − H x̂⁻ [m/s] (with ``history=True``).
    """

    estimate: AlignmentEstimate
    times: np.ndarray
    nees: np.ndarray
    nis: np.ndarray
    heading_error: np.ndarray
    heading_sigma: np.ndarray
    dim: int
    meas_dim: int
    sigma: np.ndarray | None = None
    gyro_bias_estimate: np.ndarray | None = None
    accel_bias_estimate: np.ndarray | None = None
    innovation: np.ndarray | None = None


@dataclass(frozen=True)
class EpochRecord:
    """Epoch increments of ``n`` trials with the truth at the epoch boundaries.

    Attributes
    ----------
    scenario : Scenario
        The configuration.
    increments : EpochIncrements
        Rotation, velocity and moment of every epoch.
    truth_angles : ndarray
        ``(n, E + 1, 3)`` true (ψ, β, γ) at the epoch boundaries [rad].
    truth_velocity : ndarray
        ``(n, E + 1, 3)`` true velocity of the block, NED [m/s].
    truth_rates : ndarray
        ``(n, E + 1, 3)`` time derivatives of the true angles [rad/s].
    end_rate : ndarray
        ``(n, E + 1, 3)`` gyro rate of the sample ending at each boundary (the first sample's at 0) [rad/s].
    gyro_bias, accel_bias : ndarray
        ``(n, 3)`` true biases [rad/s, m/s²].
    """

    scenario: Scenario
    increments: EpochIncrements
    truth_angles: np.ndarray
    truth_velocity: np.ndarray
    truth_rates: np.ndarray
    end_rate: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray

    @property
    def n_trials(self) -> int:
        """Trials."""
        return self.truth_angles.shape[0]


#: Where an epoch record carries the truth: at every epoch boundary, or at the start and the end.
TRUTHS = ("epochs", "ends")


def epoch_record(record: ImuRecord, samples_per_epoch: int, *, truth: str = "epochs") -> EpochRecord:
    """Condense a sample record (with its truth every ``samples_per_epoch`` samples) into epochs.

    Parameters
    ----------
    record : ImuRecord
        Increments with ``truth_stride = samples_per_epoch`` (``truth="ends"``:
        with the truth at its start and end, ``truth_stride=None``).
    samples_per_epoch : int
        M.
    truth : str, keyword-only
        ``"epochs"``: the truth at every epoch boundary; ``"ends"``: at the
        start and the end only (the boundaries between are NaN), all that
        :func:`fine_alignment` needs when it does not score the filter.

    Returns
    -------
    EpochRecord

    Raises
    ------
    ValueError
        If the truth is not where ``truth`` asks (for ``"ends"``, the record
        must end with its last whole epoch), or for an unknown ``truth``.
    """
    if truth not in TRUTHS:
        raise ValueError(f"Expected `truth` in {TRUTHS}, got {truth!r}")
    M = int(samples_per_epoch)
    sc = record.scenario
    ep = preintegrate(record.dtheta, record.dv, sc.dt, M)
    E = ep.n_epochs
    rate = np.concatenate([record.dtheta[:, :1], record.dtheta[:, M - 1 :: M][:, :E]], axis=1) / sc.dt
    fields = (record.truth_angles, record.truth_velocity, record.truth_rates)
    if truth == "ends":
        if record.truth_angles.shape[1] != 2 or not np.allclose(record.truth_times, [0.0, M * sc.dt * E]):
            raise ValueError(f"Expected the record's truth at its start and at the end of its last epoch, {M * sc.dt * E:g} s (simulate_imu(..., truth_stride=None))")
        ends = []
        for x in fields:
            y = np.full((x.shape[0], E + 1, 3), np.nan)
            y[:, [0, E]] = x
            ends.append(y)
        return EpochRecord(sc, ep, *ends, rate, record.gyro_bias, record.accel_bias)
    if record.truth_angles.shape[1] < E + 1 or not np.allclose(record.truth_times[: E + 1], M * sc.dt * np.arange(E + 1)):
        raise ValueError(f"Expected the record's truth every {M} samples (simulate_imu(..., truth_stride={M}))")
    return EpochRecord(sc, ep, *(x[:, : E + 1] for x in fields), rate, record.gyro_bias, record.accel_bias)


def draw_epoch_record(scenario: Scenario, errors: SensorErrors | None, *, n_trials: int, rng=None, chunk: int = 32) -> tuple:
    """The random numbers of :func:`simulate_epoch_record`: one :class:`~strapdown.analysis.alignment.imu.ImuDraws` per chunk of trials.

    Parameters
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors or None
        Sensor errors.
    n_trials : int
        Trials.
    rng : Generator | SeedSequence | int | None
        Random stream (consumed chunk after chunk).
    chunk : int
        Trials per chunk.

    Returns
    -------
    tuple of ImuDraws
    """
    g = as_generator(rng)
    n, chunk = as_int(n_trials, "n_trials", minimum=1), as_int(chunk, "chunk", minimum=1)
    return tuple(draw_imu(scenario, errors, n_trials=min(chunk, n - k), rng=g) for k in range(0, n, chunk))


def simulate_epoch_record(
    scenario: Scenario, errors: SensorErrors | None, samples_per_epoch: int, *, n_trials: int | None = None, rng=None, draws=None, chunk: int = 32, truth: str = "epochs"
) -> EpochRecord:
    """Simulate ``n_trials`` records in chunks and keep only their epoch increments (bounded memory).

    Parameters
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors or None
        Sensor errors.
    samples_per_epoch : int
        M.
    n_trials : int
        Trials (with ``rng``).
    rng : Generator | SeedSequence | int | None
        Random stream (consumed chunk after chunk).
    draws : tuple of ImuDraws, optional
        The random numbers drawn before (:func:`draw_epoch_record`), instead of ``n_trials`` and ``rng``.
    chunk : int
        Trials simulated at once.
    truth : str
        ``"epochs"`` or ``"ends"`` (:func:`epoch_record`).

    Returns
    -------
    EpochRecord
    """
    if truth not in TRUTHS:
        raise ValueError(f"Expected `truth` in {TRUTHS}, got {truth!r}")
    M = as_int(samples_per_epoch, "samples_per_epoch", minimum=1)
    if draws is None:
        draws = draw_epoch_record(scenario, errors, n_trials=n_trials, rng=rng, chunk=chunk)
    parts = [epoch_record(simulate_imu(scenario, errors, draws=d, truth_stride=M if truth == "epochs" else None), M, truth=truth) for d in draws]
    cat = lambda name: np.concatenate([getattr(p, name) for p in parts])  # noqa: E731
    inc = EpochIncrements(*(np.concatenate([getattr(p.increments, f) for p in parts]) for f in ("rotation", "velocity", "moment")), parts[0].increments.epoch, M)
    return EpochRecord(scenario, inc, *(cat(f) for f in _RECORD_FIELDS))


@dataclass(frozen=True)
class FilterDraws:
    """The filter's random numbers for ``n`` trials of E epochs (standard normal).

    Attributes
    ----------
    attitude : ndarray
        ``(n, 3)`` initial attitude errors, per unit of the prior's standard deviations.
    measurement : ndarray
        ``(n, E, 3)`` noise of the zero-velocity reference, per unit of its standard deviation.
    velocity : ndarray
        ``(n, 3)`` initial velocity errors, per unit of the prior's.
    """

    attitude: np.ndarray
    measurement: np.ndarray
    velocity: np.ndarray


def draw_filter(n_trials: int, n_epochs: int, rng=None) -> FilterDraws:
    """Draw the filter's random numbers, in the order :func:`fine_alignment` consumes them.

    Parameters
    ----------
    n_trials : int
        Trials.
    n_epochs : int
        Epochs E.
    rng : Generator | SeedSequence | int | None
        Random stream.

    Returns
    -------
    FilterDraws
    """
    g = as_generator(rng)
    n, E = as_int(n_trials, "n_trials", minimum=1), as_int(n_epochs, "n_epochs", minimum=1)
    return FilterDraws(g.standard_normal((n, 3)), g.standard_normal((n, E, 3)), g.standard_normal((n, 3)))


_RECORD_FIELDS = ("truth_angles", "truth_velocity", "truth_rates", "end_rate", "gyro_bias", "accel_bias")


def fine_alignment(
    record,
    tuning: FilterTuning | None = None,
    *,
    rng=None,
    draws: FilterDraws | None = None,
    velocity_noise: float | None = None,
    sequence=None,
    model: FineAlignmentModel | None = None,
    score: bool = True,
    compiled: bool | None = None,
    initial_attitude=None,
    history: bool = False,
) -> FineAlignmentResult:
    """Run the fine-alignment filter on every trial of a record.

    Parameters
    ----------
    record : EpochRecord or ImuRecord
        Epoch increments with the truth at the boundaries, or a sample record with
        its truth every epoch (``truth_stride`` = samples per epoch).
    tuning : FilterTuning, optional
        What the filter assumes (default :class:`FilterTuning`).
    rng : Generator | SeedSequence | int | None
        Stream of the initial attitude errors (drawn from the prior) and of the
        measurement noise.
    draws : FilterDraws, optional
        Those random numbers drawn before (:func:`draw_filter`), instead of ``rng``.
    velocity_noise : float, optional
        True standard deviation of the zero-velocity reference [m/s] (default:
        the filter's ``measurement_noise``, a filter that knows it).
    sequence : FilterSequence, optional
        Gains and covariances computed before for the same model (saves the filterpy run).
    model : FineAlignmentModel, optional
        ``filter_model(record.scenario, tuning)`` computed before (saves its discretisation).
    score : bool
        Score the filter against the truth at every epoch (NEES, NIS, the
        azimuth error at every epoch); False: the azimuth error at the end
        only (``heading_error`` NaN before the last epoch, NEES and NIS NaN),
        from the truth at the start and the end of the record, which is then
        all it needs (``epoch_record(..., truth="ends")``).
    compiled : bool or None, keyword-only
        Run the epochs of all trials in one compiled loop
        (:func:`~strapdown.analysis.alignment.kernels.fine_alignment_loop`) or in the numpy loop
        over epochs vectorised over trials, kept as the reference (equal to
        round-off); None (default): the loop when it pays off
        (:func:`~strapdown.analysis.alignment.kernels.use_compiled`; an epoch of the filter counts
        as 30 samples).
    initial_attitude : array_like, optional, keyword-only
        ``(n, 3, 3)`` attitudes ``C̃_b^n`` the navigator starts from (a coarse
        alignment's, whose errors the model's prior describes); default the
        true attitude turned by errors drawn from the prior.
    history : bool, keyword-only
        Keep the time histories of the filter (its standard deviations, the bias estimates and
        the innovations, and the NIS, which needs no truth) in the result; runs the numpy loop.

    Returns
    -------
    FineAlignmentResult

    Raises
    ------
    ValueError
        If the record's truth is not at every epoch, or it is shorter than one epoch.
    TypeError
        If ``record`` or ``model`` is of the wrong type.
    """
    tuning = FilterTuning() if tuning is None else tuning
    sc = record.scenario
    if model is None:
        model = filter_model(sc, tuning)
    elif not isinstance(model, FineAlignmentModel):
        raise TypeError(f"Expected `model` to be a FineAlignmentModel, got {type(model).__name__}")
    M, D = model.samples_per_epoch, model.epoch
    if isinstance(record, ImuRecord):
        record = epoch_record(record, M)
    if not isinstance(record, EpochRecord):
        raise TypeError(f"Expected `record` to be an EpochRecord or ImuRecord, got {type(record).__name__}")
    ep = record.increments
    if ep.samples_per_epoch != M:
        raise ValueError(f"Expected epochs of {M} samples (the tuning's epoch), got {ep.samples_per_epoch}")
    n, E = record.n_trials, ep.n_epochs
    seq = kalman.filter_sequence(model.F, model.Q, model.H, model.R, model.P0, E) if sequence is None else sequence
    noise = tuning.measurement_noise if velocity_noise is None else nonnegative(velocity_noise, "velocity_noise")
    if draws is None:
        draws = draw_filter(n, E, rng)
    elif draws.measurement.shape != (n, E, 3):
        raise ValueError(f"Expected `draws` for {n} trials of {E} epochs, got shape {draws.measurement.shape}")
    W, gn = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude)
    Wx = skew(W)
    E_earth = _rodrigues(-W * D)
    # everything that does not depend on the filter, for all epochs at once
    dR = _quat_to_matrix(ep.rotation)  # (n, E, 3, 3)
    ax = list(model.rocking_axes)
    if score:
        if np.isnan(record.truth_angles[:, : E + 1]).any():
            raise ValueError("Expected the record's truth at every epoch to score the filter (epoch_record(..., truth='epochs')), got NaN")
        C_true = attitude_matrix(record.truth_angles[:, : E + 1])
        v_true = record.truth_velocity[:, : E + 1]
        eps_true = np.einsum("nkij,nj->nki", C_true, record.gyro_bias)
        acc_true = np.einsum("nkij,nj->nki", C_true, record.accel_bias)
        rock_true = np.empty((n, E + 1, 2 * len(ax)))
        rock_true[:, :, 0::2] = (record.truth_angles[:, : E + 1] - sc.stable_angles)[:, :, ax]
        rock_true[:, :, 1::2] = record.truth_rates[:, : E + 1][:, :, ax]
    else:  # the azimuth error at the end: the truth at the start and the end
        C_true = np.full((n, E + 1, 3, 3), np.nan)
        C_true[:, [0, E]] = attitude_matrix(record.truth_angles[:, [0, E]])
        v_true, eps_true, acc_true = np.zeros((n, E + 1, 3)), np.zeros((n, E + 1, 3)), np.zeros((n, E + 1, 3))
        rock_true = np.zeros((n, E + 1, 2 * len(ax)))
    r = sc.lever_arm
    w_end = record.end_rate[:, 1:]  # gyro rate at each epoch end
    if initial_attitude is None:
        phi0 = draws.attitude * np.sqrt(np.diag(model.P0)[0:3])
        C = _rodrigues(-phi0) @ C_true[:, 0]  # C̃ = (I − [φ×]) C
    else:
        C = np.array(as_array(initial_attitude, "initial_attitude"), dtype=float)
        if C.shape != (n, 3, 3):
            raise ValueError(f"Expected `initial_attitude` with shape ({n}, 3, 3), got shape {C.shape}")
    meas_noise = noise * draws.measurement
    v = tuning.prior_velocity * draws.velocity  # the zero-velocity start, its error drawn from the prior
    if tuning.lever_arm_known:
        v = v + np.einsum("nij,nj->ni", C, _cross(record.end_rate[:, 0], r))
    Sinv = np.linalg.inv(seq.innovation) if score or history else None
    Pinv = np.linalg.inv(seq.posterior) if score else None
    Fdd = model.F[12:, 12:] if model.has_rocking_states else np.zeros((0, 0))
    kept = {} if history else None
    loop = kernels.fine_alignment_loop if kernels.use_compiled(compiled, 30 * n * E) and not history else _epoch_loop
    args = (C, v, dR, ep.velocity, ep.moment, meas_noise, w_end, C_true, v_true, eps_true, acc_true, rock_true, E_earth, Wx, gn, D, r,
            tuning.lever_arm_known, Fdd, model.H, seq.gains, Pinv, Sinv)  # fmt: skip
    C, nees, nis, heading_error = loop(*args, kept) if history else loop(*args)
    a = angles_from_matrix(C)
    t = record.truth_angles[:, E]
    est = AlignmentEstimate("kalman", a.heading, a.beta, a.gamma, t[:, 0], t[:, 1], t[:, 2], "end")
    extra = {}
    if history:
        extra = dict(sigma=np.sqrt(np.diagonal(seq.posterior, axis1=1, axis2=2)[:, 0:3]), gyro_bias_estimate=kept["eps"], accel_bias_estimate=kept["acc"], innovation=kept["y"])
    return FineAlignmentResult(est, D * np.arange(1, E + 1), nees, nis, heading_error, np.sqrt(seq.posterior[:, 2, 2]), model.dim, 3, **extra)


def _epoch_loop(C, v, dR, velocity, moment, meas_noise, w_end, C_true, v_true, eps_true, acc_true, rock_true, E_earth, Wx, gn, D, r, lever_arm_known, Fdd, H, gains, Pinv, Sinv, history=None):
    """The numpy reference of :func:`~strapdown.analysis.alignment.kernels.fine_alignment_loop` (same arguments): one step per epoch, vectorised over trials.

    ``history``, a dict, receives the bias estimates (``"eps"``, ``"acc"``) and the innovations (``"y"``), ``(n, E, 3)`` each;
    the NIS is computed wherever ``Sinv`` is given (it needs no truth).
    """
    n, E = dR.shape[0], dR.shape[1]
    dim, shaping = H.shape[1], Fdd.shape[0] > 0
    eps, acc = np.zeros((n, 3)), np.zeros((n, 3))
    xd = np.zeros((n, Fdd.shape[0]))
    score = Pinv is not None
    nees, nis, heading_error = np.full((n, E), np.nan), np.full((n, E), np.nan), np.empty((n, E))
    if history is not None:
        history.update(eps=np.empty((n, E, 3)), acc=np.empty((n, E, 3)), y=np.empty((n, E, 3)))
    KT = np.swapaxes(gains, 1, 2)
    HT = H.T
    err = np.empty((n, dim))
    for j in range(E):  # one step per epoch, vectorised over trials
        eb = np.einsum("nji,nj->ni", C, eps)  # C̃ᵀ ε̂^n
        ab = np.einsum("nji,nj->ni", C, acc)
        dV = np.einsum("nij,nj->ni", C, velocity[:, j] - ab * D) - np.einsum("nij,nj->ni", C, moment[:, j]) @ Wx.T
        v = v + dV + gn * D - 2.0 * D * (v @ Wx.T)
        C = E_earth @ C @ dR[:, j] @ _rodrigues(-eb * D)
        z = v + meas_noise[:, j]
        if lever_arm_known:
            z = z - np.einsum("nij,nj->ni", C, _cross(w_end[:, j] - eb, r))
        pred = np.zeros((n, dim))
        if shaping:
            xd = xd @ Fdd.T
            pred[:, 12:] = xd
        y = z - pred @ HT
        x = pred + y @ KT[j]
        C = _rodrigues(x[:, 0:3]) @ C
        v = v - x[:, 3:6]
        eps, acc = eps + x[:, 6:9], acc + x[:, 9:12]
        if shaping:
            xd = x[:, 12:]
        if history is not None:
            history["eps"][:, j], history["acc"][:, j], history["y"][:, j] = eps, acc, y
        if Sinv is not None:
            nis[:, j] = np.sum((y @ Sinv[j]) * y, axis=1)
        # consistency against the truth of the simulation
        err[:, 0:3] = _small_rotation(np.einsum("nij,nkj->nik", C, C_true[:, j + 1]))
        heading_error[:, j] = -err[:, 2]  # ψ̂ − ψ = −φ_D
        if not score:
            continue
        err[:, 3:6] = v - v_true[:, j + 1]
        err[:, 6:9] = eps_true[:, j + 1] - eps
        err[:, 9:12] = acc_true[:, j + 1] - acc
        if shaping:
            err[:, 12:] = rock_true[:, j + 1] - xd
        nees[:, j] = np.sum((err @ Pinv[j]) * err, axis=1)
    return C, nees, nis, heading_error


def _cross(a, b):
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1], a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2], a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def _rodrigues(phi):
    """Rotation matrices ``exp([φ×])`` of rotation vectors ``(..., 3)``."""
    phi = np.asarray(phi, dtype=float)
    th2 = np.sum(phi * phi, axis=-1)[..., None, None]
    small = th2 < 1e-12
    th = np.sqrt(np.where(small, 1.0, th2))
    a = np.where(small, 1.0 - th2 / 6.0, np.sin(th) / th)
    b = np.where(small, 0.5 - th2 / 24.0, (1.0 - np.cos(th)) / np.where(small, 1.0, th2))
    K = np.zeros(phi.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2], K[..., 1, 2] = -phi[..., 2], phi[..., 1], -phi[..., 0]
    K[..., 1, 0], K[..., 2, 0], K[..., 2, 1] = phi[..., 2], -phi[..., 1], phi[..., 0]
    return np.eye(3) + a * K + b * (K @ K)


def _small_rotation(Er):
    """φ with ``Er = C̃ Cᵀ = exp(−[φ×])``, from the antisymmetric part (angles below 90°)."""
    s = 0.5 * np.stack([Er[..., 2, 1] - Er[..., 1, 2], Er[..., 0, 2] - Er[..., 2, 0], Er[..., 1, 0] - Er[..., 0, 1]], axis=-1)
    sn = np.linalg.norm(s, axis=-1, keepdims=True)
    scale = np.where(sn > 1e-15, np.arcsin(np.minimum(sn, 1.0)) / np.where(sn > 1e-15, sn, 1.0), 1.0)
    return -s * scale


def _quat_to_matrix(q):
    """Rotation matrices of scalar-first unit quaternions ``(..., 4)`` (scipy)."""
    from scipy.spatial.transform import Rotation

    q = np.asarray(q, dtype=float)
    return Rotation.from_quat(q.reshape(-1, 4), scalar_first=True).as_matrix().reshape(q.shape[:-1] + (3, 3))
