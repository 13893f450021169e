"""Alignment and observability of a recorded log.

:func:`align_log` runs a method on a log once (no Monte Carlo): ``analytic``,
``inertial``, ``kalman`` (the inertial-frame coarse stage, then the filter
from its result and covariance, :mod:`~strapdown.analysis.alignment.coarse_to_fine`) or ``compass``.
:func:`recorded_problem` finds the positions of the log's motion (turns larger
than a threshold between still stretches) and builds the multi-position
observability problem of :mod:`~strapdown.analysis.alignment.observability`.

Public API
----------
.. autosummary::

   log_record
   LogAlignment
   align_log
   recorded_problem
   LOG_METHODS
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from ..alignment.analytic import analytic_alignment
from ..alignment.coarse_to_fine import coarse_model, coarse_to_fine, split_record
from ..alignment.compass_loop import CompassLoopDesign, compass_loop_alignment
from ..alignment.fine import FilterDraws, FilterTuning
from ..alignment.imu import ImuRecord, Scenario, SensorErrors
from ..alignment.inertial import inertial_alignment
from ..alignment.observability import ObservabilityProblem, stationary_problem
from ..alignment.preintegration import chain_rotations, preintegrate
from ..alignment.tilt_attitude import attitude_matrix
from ..core.validation import positive
from .imu_log import ImuLog

__all__ = ["log_record", "LogAlignment", "align_log", "recorded_problem", "LOG_METHODS", "CALIBRATION_SEED"]

#: Methods :func:`align_log` runs.
LOG_METHODS = ("analytic", "inertial", "kalman", "compass")

#: Seed of the simulated trials that calibrate the coarse stage's covariance (``kalman``): a
#: property of the filter's model, not of the data, fixed so that an alignment of a recorded
#: log is a function of the log and the options alone.
CALIBRATION_SEED = 20240613


def log_record(log: ImuLog, latitude: float, *, truth_stride: int | None = None) -> ImuRecord:
    """The log as a one-trial record (its truth from the metadata where it has it, NaN elsewhere).

    Parameters
    ----------
    log : ImuLog
        The samples.
    latitude : float
        Latitude φ [rad].
    truth_stride : int, optional, keyword-only
        Truth instants every ``truth_stride`` samples (NaN between the start
        and the end; default: the start and the end).

    Returns
    -------
    ImuRecord
    """
    N, dt = log.n_samples, log.dt
    stable = log.angles("stable")
    sc = Scenario(latitude, *(stable if stable is not None else np.zeros(3)), sample_rate=1.0 / dt, duration=N * dt)
    stride = N if truth_stride is None else int(truth_stride)
    idx = np.arange(0, N + 1, stride)
    if idx[-1] != N:
        idx = np.append(idx, N)
    angles = np.full((1, idx.size, 3), np.nan)
    end = log.angles("end")
    if end is not None:
        angles[0, -1] = end
    z = np.zeros((1, idx.size, 3))
    return ImuRecord(sc, SensorErrors(), log.dtheta[None], log.dv[None], idx * dt, angles, z, z.copy(), np.zeros((1, 3)), np.zeros((1, 3)))


@dataclass(frozen=True)
class LogAlignment:
    """One method's alignment of a recorded log.

    Attributes
    ----------
    method : str
        The method.
    heading, beta, gamma : float
        Estimates at the reference instant [rad].
    reference : str
        ``"stable"`` (analytic) or ``"end"``.
    heading_sigma : float or None
        Kalman: the filter's standard deviation of the azimuth at the end [rad].
    heading_error : float or None
        Against the log's metadata, where it carries the truth [rad] (and, for
        the epoch-based methods, where the log ends on a whole epoch: the
        estimate is the attitude at the end of the last one).
    duration : float
        Length of the log [s].
    """

    method: str
    heading: float
    beta: float
    gamma: float
    reference: str
    heading_sigma: float | None
    heading_error: float | None
    duration: float


def align_log(
    log: ImuLog,
    latitude: float,
    *,
    method: str,
    tuning: FilterTuning | None = None,
    formula: str = "levelled",
    observation: str = "position",
    inertial_epoch: float = 1.0,
    coarse_duration: float = 60.0,
    compass: CompassLoopDesign | None = None,
    calibration_trials: int = 64,
    rng=None,
) -> LogAlignment:
    """Align a recorded log once with ``method``.

    Parameters
    ----------
    log : ImuLog
        The samples (at rest or rocking).
    latitude : float
        Latitude φ [rad].
    method : str, keyword-only
        From :data:`LOG_METHODS`.
    tuning : FilterTuning, optional, keyword-only
        The filter (``kalman``): its noise also calibrates the coarse stage's covariance.
    formula : str, keyword-only
        ``analytic``: ``"levelled"`` or ``"paper"``.
    observation : str, keyword-only
        ``inertial``: ``"position"`` or ``"velocity"``.
    inertial_epoch : float, keyword-only
        ``inertial``: spacing of the vector observations [s].
    coarse_duration : float, keyword-only
        T_c of the coarse stage of ``kalman`` and ``compass`` [s] (rounded down to whole filter epochs).
    compass : CompassLoopDesign, optional, keyword-only
        The compass loop.
    calibration_trials : int, keyword-only
        Simulated trials calibrating the coarse covariance (``kalman``).
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of that calibration (default :data:`CALIBRATION_SEED`).  Nothing random is
        added to the recorded data: the filter starts from zero velocity and its
        zero-velocity measurements are the log's, without synthetic noise.

    Returns
    -------
    LogAlignment

    Raises
    ------
    ValueError
        For an unknown method or a log too short for the coarse stage.
    """
    from ..alignment.estimate import wrap_angle
    from ..gyrocompass.rocking import as_generator

    if method not in LOG_METHODS:
        raise ValueError(f"Expected `method` in {LOG_METHODS}, got {method!r}")
    tuning = FilterTuning() if tuning is None else tuning
    g = as_generator(CALIBRATION_SEED if rng is None else rng)
    T = log.n_samples * log.dt
    sigma = None
    if method == "analytic":
        est = analytic_alignment(log_record(log, latitude), formula=formula)
    elif method == "inertial":
        est = inertial_alignment(log_record(log, latitude), epoch=inertial_epoch, observation=observation)
    else:
        step = tuning.epoch if method == "kalman" else (compass or CompassLoopDesign()).epoch
        M = max(1, int(round(step / log.dt)))
        k = int(positive(coarse_duration, "coarse_duration") / log.dt) // M * M
        if not 0 < k < log.n_samples - M:
            raise ValueError(f"Expected `coarse_duration` of at least one epoch and shorter than the log ({T:g} s), got {coarse_duration:g}")
        rec = log_record(log, latitude, truth_stride=M)
        head = replace(rec, scenario=replace(rec.scenario, duration=k * log.dt), dtheta=rec.dtheta[:, :k], dv=rec.dv[:, :k],
                       truth_angles=rec.truth_angles[:, : k // M + 1], truth_times=rec.truth_times[: k // M + 1])  # fmt: skip
        coarse = inertial_alignment(head)
        if method == "kalman":
            sc = replace(rec.scenario, heading=float(coarse.heading[0]), beta0=float(coarse.beta[0]), gamma0=float(coarse.gamma[0]))
            noise = SensorErrors(gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise)
            cm = coarse_model(sc, noise, coarse_duration=k * log.dt, n_trials=calibration_trials, rng=g)
            tail_epochs = (log.n_samples - k) // M
            still = FilterDraws(np.zeros((1, 3)), np.zeros((1, tail_epochs, 3)), np.zeros((1, 3)))  # no synthetic noise on recorded data
            res = coarse_to_fine(replace(rec, scenario=sc), tuning, cm, score=False, draws=still)
            est, sigma = res.fine.estimate, float(res.fine.heading_sigma[-1])
        else:
            _, tail = split_record(rec, k)
            C0 = attitude_matrix(np.stack([coarse.heading, coarse.beta, coarse.gamma], axis=-1))
            est = compass_loop_alignment(tail, compass, initial_attitude=C0).estimate
    truth = log.angles("stable" if est.reference == "stable" else "end")
    at_end = est.reference == "stable" or method in ("analytic", "inertial") or (log.n_samples - k) % M == 0
    err = float(wrap_angle(est.heading[0] - truth[0])) if truth is not None and at_end else None
    return LogAlignment(method, float(est.heading[0]), float(est.beta[0]), float(est.gamma[0]), est.reference, sigma, err, T)


def recorded_problem(log: ImuLog, latitude: float, *, tuning: FilterTuning | None = None, threshold: float = math.radians(5.0), window: float = 20.0) -> ObservabilityProblem:
    """The observability problem of a log's motion: a position wherever the block stays, turned between them.

    The attitude is integrated from the gyros in the frame of the first
    sample, and the Earth's turn is taken out of it: the gyros measure the turn
    relative to inertial space, which at rest is the Earth's rate (15°/h, 7.5°
    in half an hour: more than ``threshold``), so the turn relative to the Earth
    is the inertial one followed back by the Earth's rotation about its axis,
    ``R_E(t) = exp(−[ω_ie^b0] t) R_I(t)``, with ``ω_ie^b0 = C_n^b ω_ie^n`` from the
    analytic alignment of the first ``window`` seconds.  The attitude is averaged
    over windows of ``window`` seconds, which removes the rocking; a new position
    starts at the first window whose mean attitude has turned by more than
    ``threshold`` from the first window of the current position.  The start
    attitude is levelled and headed by the analytic alignment of the first position.

    Parameters
    ----------
    log : ImuLog
        The samples.
    latitude : float
        Latitude φ [rad].
    tuning : FilterTuning, optional, keyword-only
        Prior, noise and epoch.
    threshold : float, keyword-only
        Turn that starts a new position [rad].
    window : float, keyword-only
        Averaging window of the attitude [s] (several rocking periods).

    Returns
    -------
    ObservabilityProblem
        ``kind`` ``"recorded"``: the stationary problem for one position, a multi-position one otherwise.
    """
    from ..alignment.earth import earth_rate_ned
    from ..alignment.error_model import navigation_error_model

    tuning = FilterTuning() if tuning is None else tuning
    M = max(1, int(round(min(1.0, positive(window, "window") / 10.0) / log.dt)))  # attitude samples: ten per window at least
    ep = preintegrate(log.dtheta[None], log.dv[None], log.dt, M)
    Q = chain_rotations(np.array([[1.0, 0.0, 0.0, 0.0]]), ep.rotation)[0]  # body in its inertial start frame, at the epoch boundaries
    first_window = max(2, min(log.n_samples, int(round(window / log.dt))))
    lead = log_record(replace(log, time=log.time[:first_window], dtheta=log.dtheta[:first_window], dv=log.dv[:first_window]), latitude)
    a0 = analytic_alignment(lead)
    C0 = attitude_matrix([float(a0.heading[0]), float(a0.beta[0]), float(a0.gamma[0])])  # body to NED at the start
    w_earth = C0.T @ earth_rate_ned(latitude)  # the Earth's rate in the start body axes [rad/s]
    t_epochs = np.arange(Q.shape[0]) * ep.epoch
    R = Rotation.from_rotvec(-t_epochs[:, None] * w_earth[None, :]) * Rotation.from_quat(Q, scalar_first=True)  # body relative to the Earth
    per = max(1, int(round(window / ep.epoch)))
    n_windows = max(1, ep.n_epochs // per)
    means = [R[w * per : (w + 1) * per + 1].mean() for w in range(n_windows)]
    first = [0]
    for w in range(1, n_windows):
        if (means[first[-1]].inv() * means[w]).magnitude() > threshold:
            first.append(w)
    edges = [w * per for w in first] + [ep.n_epochs]
    head = log_record(replace(log, time=log.time[: edges[1] * M], dtheta=log.dtheta[: edges[1] * M], dv=log.dv[: edges[1] * M]), latitude)
    a = analytic_alignment(head)  # the mean attitude of the first position
    C_start = attitude_matrix([float(a.heading[0]), float(a.beta[0]), float(a.gamma[0])])
    T = ep.n_epochs * ep.epoch
    if len(edges) == 2:
        p = stationary_problem(latitude, attitude=[float(a.heading[0]), float(a.beta[0]), float(a.gamma[0])], tuning=tuning, duration=T)
        return replace(p, kind="recorded")
    models, durations = [], []
    for i, (s, e) in enumerate(zip(edges[:-1], edges[1:])):
        C = C_start @ (means[0].inv() * means[first[i]]).as_matrix()
        models.append(navigation_error_model(latitude, attitude=C, biases="body", gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise))
        durations.append((e - s) * ep.epoch)
    base = stationary_problem(latitude, tuning=tuning, duration=T)
    return ObservabilityProblem("recorded", tuple(models), tuple(durations), base.P0, base.R, tuning.epoch, float(latitude))
