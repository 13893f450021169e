"""Coarse-to-fine alignment: the Kalman filter starts from the inertial-frame coarse result and its covariance.

The first ``T_c`` seconds of a record go to the inertial-frame alignment
(:mod:`~strapdown.analysis.alignment.inertial`); its attitude at ``T_c`` is where the fine-alignment filter
(:mod:`~strapdown.analysis.alignment.fine`) starts on the rest of the record, and the filter's prior is the
coarse result's own error covariance, not a draw from an assumed prior.

That covariance (:class:`CoarseModel`) has two parts.  To first order the
coarse attitude error is ``φ_c = G b + n``: a linear response G to the sensor
biases (NED-resolved, as the filter's bias states), which the fine filter must
know as a correlation between its attitude and bias states, because the
azimuth error the coarse stage leaves *is* the east gyro bias over
``Ω cos φ`` (the unobservable direction, :mod:`~strapdown.analysis.alignment.observability`); and a part n
from everything else (white noise, quantisation, rocking).  G is computed by
central differences of the coarse method on a noise-free record (it is linear
to the order kept); the covariance of n is measured on calibration trials of
the coarse stage with the biases set to zero, on a stream of their own.  The
filter's prior is then

    P0 = [[G Σ_b Gᵀ + Σ_n, ·, G Σ_b], [·, P_v, ·], [Σ_b Gᵀ, ·, Σ_b]]

with ``Σ_b`` the bias prior of the tuning and ``P_v`` its velocity (and
rocking) prior.

Public API
----------
CoarseModel, CoarseToFineResult, coarse_model, coarse_prior, split_record,
attitude_error, coarse_to_fine
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.validation import as_int, positive
from ..gyrocompass.rocking import as_generator
from .estimate import AlignmentEstimate
from .fine import FilterTuning, FineAlignmentResult, filter_model, fine_alignment
from .imu import ImuRecord, Scenario, SensorErrors, simulate_imu
from .inertial import inertial_alignment
from .tilt_attitude import attitude_matrix

__all__ = ["CoarseModel", "CoarseToFineResult", "coarse_model", "coarse_prior", "split_record", "attitude_error", "coarse_to_fine"]


def attitude_error(estimate, truth) -> np.ndarray:
    """φ of ``C̃ = (I − [φ×]) C`` (exactly: ``C̃ Cᵀ = exp(−[φ×])``) from estimated and true ``C_b^n``.

    Parameters
    ----------
    estimate, truth : array_like
        ``(..., 3, 3)`` attitude matrices.

    Returns
    -------
    ndarray
        ``(..., 3)`` [rad]: φ_N, φ_E tilt errors, ``−φ_D`` the azimuth error.

    >>> C = attitude_matrix([0.3, 0.01, -0.02])
    >>> Ce = attitude_matrix([0.3 + 1e-3, 0.01, -0.02])
    >>> round(float(-attitude_error(Ce, C)[2]), 12)
    0.001
    """
    E = np.asarray(estimate, dtype=float) @ np.swapaxes(np.asarray(truth, dtype=float), -1, -2)
    shape = E.shape[:-2]
    return -Rotation.from_matrix(E.reshape(-1, 3, 3)).as_rotvec().reshape(shape + (3,))


def split_record(record: ImuRecord, samples: int) -> tuple:
    """The first ``samples`` samples of a record and the rest, each with its own truth and scenario.

    Parameters
    ----------
    record : ImuRecord
        With its truth at a stride that divides ``samples``.
    samples : int
        Where to split [count].

    Returns
    -------
    tuple of ImuRecord
        ``(head, tail)``; the tail's times start at zero.

    Raises
    ------
    ValueError
        If the split leaves no sample on one side or falls between truth instants.
    """
    N = record.scenario.n_samples
    k = as_int(samples, "samples", minimum=1)
    if k >= N:
        raise ValueError(f"Expected `samples` below the record's {N} samples, got {k}")
    dt = record.scenario.dt
    at = np.flatnonzero(np.isclose(record.truth_times, k * dt, rtol=0.0, atol=1e-9 * max(1.0, k * dt)))
    if at.size != 1:
        raise ValueError(f"Expected the record's truth at sample {k} (a truth stride that divides it), got truth at {record.truth_times[:4].tolist()}…")
    i = int(at[0])
    sc = record.scenario
    head_sc, tail_sc = replace(sc, duration=k * dt), replace(sc, duration=(N - k) * dt)
    head = replace(record, scenario=head_sc, dtheta=record.dtheta[:, :k], dv=record.dv[:, :k], truth_times=record.truth_times[: i + 1],
                   truth_angles=record.truth_angles[:, : i + 1], truth_velocity=record.truth_velocity[:, : i + 1], truth_rates=record.truth_rates[:, : i + 1])  # fmt: skip
    tail = replace(record, scenario=tail_sc, dtheta=record.dtheta[:, k:], dv=record.dv[:, k:], truth_times=record.truth_times[i:] - k * dt,
                   truth_angles=record.truth_angles[:, i:], truth_velocity=record.truth_velocity[:, i:], truth_rates=record.truth_rates[:, i:])  # fmt: skip
    return head, tail


@dataclass(frozen=True)
class CoarseModel:
    """The inertial-frame coarse alignment's attitude error, as the fine filter's prior needs it.

    Attributes
    ----------
    duration : float
        Coarse alignment time T_c [s].
    epoch : float
        Spacing of its vector observations [s].
    observation : str
        ``"position"`` or ``"velocity"`` (:func:`strapdown.analysis.alignment.inertial.inertial_alignment`).
    sensitivity : ndarray
        ``(3, 6)`` G: φ per NED gyro bias [s] (columns 0–2) and per NED
        accelerometer bias [s²/m] (columns 3–5).
    noise_covariance : ndarray
        ``(3, 3)`` covariance Σ_n of φ from everything but the biases [rad²].
    noise_mean : ndarray
        ``(3,)`` mean of φ over the calibration trials [rad] (zero within its interval when the model holds).
    calibration_trials : int
        Trials behind Σ_n.
    """

    duration: float
    epoch: float
    observation: str
    sensitivity: np.ndarray
    noise_covariance: np.ndarray
    noise_mean: np.ndarray
    calibration_trials: int


def coarse_model(
    scenario: Scenario,
    errors: SensorErrors | None = None,
    *,
    coarse_duration: float,
    n_trials: int = 64,
    rng=None,
    epoch: float = 1.0,
    observation: str = "position",
    step_gyro: float = 1e-7,
    step_accel: float = 1e-4,
) -> CoarseModel:
    """Characterise the coarse stage of a scenario: its response to the biases and its noise covariance.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking and sampling (its duration is not used).
    errors : SensorErrors, optional
        The sensors (their biases are set to zero for the calibration trials).
    coarse_duration : float, keyword-only
        T_c [s].
    n_trials : int, keyword-only
        Calibration trials for Σ_n.
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of the calibration trials (keep it apart from the trials the model will serve).
    epoch : float, keyword-only
        Spacing of the coarse method's vector observations [s].
    observation : str, keyword-only
        ``"position"`` or ``"velocity"``.
    step_gyro, step_accel : float, keyword-only
        Bias steps of the central differences [rad/s, m/s²].

    Returns
    -------
    CoarseModel
    """
    e = SensorErrors() if errors is None else errors
    Tc = positive(coarse_duration, "coarse_duration")
    sc = replace(scenario, duration=Tc)
    n = as_int(n_trials, "n_trials", minimum=4)
    # G by central differences on the still, noise-free record: 12 trials sharing the same ideal increments
    base = simulate_imu(_still(sc), None, n_trials=1, rng=0)
    C0 = attitude_matrix(sc.stable_angles)
    steps = np.concatenate([step_gyro * np.eye(3), step_accel * np.eye(3)])
    dth = np.repeat(base.dtheta, 12, axis=0)
    dv = np.repeat(base.dv, 12, axis=0)
    for j in range(6):  # NED bias j, + then −, resolved in body axes
        body = C0.T @ steps[j]
        target = dth if j < 3 else dv
        target[2 * j] += body * sc.dt
        target[2 * j + 1] -= body * sc.dt
    rep = lambda x: np.repeat(x, 12, axis=0)  # noqa: E731
    rec = replace(base, dtheta=dth, dv=dv, truth_angles=rep(base.truth_angles), truth_velocity=rep(base.truth_velocity), truth_rates=rep(base.truth_rates),
                  gyro_bias=np.zeros((12, 3)), accel_bias=np.zeros((12, 3)))  # fmt: skip
    est = inertial_alignment(rec, epoch=epoch, observation=observation)
    phi = attitude_error(attitude_matrix(np.stack([est.heading, est.beta, est.gamma], axis=-1)), attitude_matrix(np.stack([est.true_heading, est.true_beta, est.true_gamma], axis=-1)))
    G = np.stack([(phi[2 * j] - phi[2 * j + 1]) / (2.0 * (step_gyro if j < 3 else step_accel)) for j in range(6)], axis=1)
    # Σ_n from calibration trials without biases
    quiet = replace(e, gyro_bias=np.zeros(3), accel_bias=np.zeros(3), gyro_bias_sigma=0.0, accel_bias_sigma=0.0)
    cal = simulate_imu(sc, quiet, n_trials=n, rng=as_generator(rng))
    est = inertial_alignment(cal, epoch=epoch, observation=observation)
    phi = attitude_error(attitude_matrix(np.stack([est.heading, est.beta, est.gamma], axis=-1)), attitude_matrix(np.stack([est.true_heading, est.true_beta, est.true_gamma], axis=-1)))
    return CoarseModel(Tc, float(epoch), observation, G, np.cov(phi, rowvar=False), phi.mean(axis=0), n)


def _still(sc: Scenario) -> Scenario:
    from .base_motion import StillBase

    return replace(sc, motion=StillBase())


def coarse_prior(coarse: CoarseModel, model_P0, tuning: FilterTuning) -> np.ndarray:
    """The fine filter's prior after the coarse stage: attitude from the coarse covariance, correlated with the biases.

    Parameters
    ----------
    coarse : CoarseModel
        The coarse stage.
    model_P0 : array_like
        ``(n, n)`` the filter model's own prior (its velocity and rocking blocks are kept).
    tuning : FilterTuning
        The bias prior Σ_b.

    Returns
    -------
    ndarray
        ``(n, n)``.
    """
    P0 = np.array(model_P0, dtype=float)
    Sb = np.diag([tuning.gyro_bias**2] * 3 + [tuning.accel_bias**2] * 3)
    G = coarse.sensitivity
    P0[0:3, :] = 0.0
    P0[:, 0:3] = 0.0
    P0[6:12, 6:12] = Sb
    P0[0:3, 0:3] = G @ Sb @ G.T + coarse.noise_covariance
    P0[0:3, 6:12] = G @ Sb
    P0[6:12, 0:3] = (G @ Sb).T
    return 0.5 * (P0 + P0.T)


@dataclass(frozen=True)
class CoarseToFineResult:
    """The coarse result at T_c and the fine filter's run from it.

    Attributes
    ----------
    coarse : AlignmentEstimate
        The inertial-frame alignment at T_c.
    coarse_error : ndarray
        ``(n, 3)`` its attitude error φ [rad] (NaN where the record has no truth).
    fine : FineAlignmentResult
        The filter on the rest of the record (times from T_c).
    """

    coarse: AlignmentEstimate
    coarse_error: np.ndarray
    fine: FineAlignmentResult


def coarse_to_fine(record: ImuRecord, tuning: FilterTuning, coarse: CoarseModel, *, rng=None, score: bool = True, velocity_noise: float | None = None, draws=None) -> CoarseToFineResult:
    """Coarse alignment on the first T_c seconds, then the fine filter from its result and covariance.

    Parameters
    ----------
    record : ImuRecord
        With its truth every filter epoch (``truth_stride`` = samples per epoch,
        which must divide the coarse samples).
    tuning : FilterTuning
        The fine filter (its attitude prior is replaced by the coarse covariance).
    coarse : CoarseModel
        The coarse stage (:func:`coarse_model`).
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of the velocity prior and the measurement noise of the fine filter.
    score : bool, keyword-only
        Score the filter (NEES, NIS) at every epoch.
    velocity_noise : float, optional, keyword-only
        True noise of the zero-velocity reference [m/s] (default the tuning's).
    draws : FilterDraws, optional, keyword-only
        The fine filter's random numbers, instead of ``rng`` (zeros for a recorded log: no
        synthetic noise on recorded data).

    Returns
    -------
    CoarseToFineResult

    Raises
    ------
    ValueError
        If T_c is not a whole number of filter epochs inside the record.
    """
    sc = record.scenario
    k = int(round(coarse.duration / sc.dt))
    head, tail = split_record(record, k)
    est = inertial_alignment(head, epoch=coarse.epoch, observation=coarse.observation)
    C_coarse = attitude_matrix(np.stack([est.heading, est.beta, est.gamma], axis=-1))
    C_true = attitude_matrix(head.truth_angles[:, -1])
    model = filter_model(tail.scenario, tuning)
    if k % model.samples_per_epoch:
        raise ValueError(f"Expected `coarse.duration` a whole number of filter epochs ({model.epoch:g} s), got {coarse.duration:g}")
    model = replace(model, P0=coarse_prior(coarse, model.P0, tuning))
    fine = fine_alignment(tail, tuning, rng=rng, model=model, score=score, initial_attitude=C_coarse, velocity_noise=velocity_noise, draws=draws)
    known = ~np.isnan(C_true).any(axis=(1, 2))  # a recorded log may not carry the truth
    err = np.full((record.n_trials, 3), np.nan)
    if known.any():
        err[known] = attitude_error(C_coarse[known], C_true[known])
    return CoarseToFineResult(est, err, fine)

