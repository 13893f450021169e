"""Recorded IMU logs: reading, writing, aligning and the observability of their motion.

A log holds the samples of one IMU at a constant rate: the time at the end of
each sample interval and either the increments (angle and velocity) or the
rates (angular rate and specific force) of the three body axes, in SI units.
The format is documented in ``docs/recorded-logs.md``:

``.npz``
    arrays ``time`` (N,), ``dtheta`` and ``dv`` (N, 3) — or ``gyro`` and
    ``accel`` (N, 3) — and optional 0-d metadata arrays;
``.csv``
    a header row naming the columns ``time``, ``dtheta_x`` … ``dv_z`` (or
    ``gyro_x`` … ``accel_z``), one row per sample; metadata in leading comment
    lines ``# name: value``.

Metadata (all optional, SI): ``latitude`` [rad]; ``stable_heading``,
``stable_beta``, ``stable_gamma`` [rad] (the mean attitude of a rocking
block, the reference of the analytic method); ``end_heading``, ``end_beta``,
``end_gamma`` [rad] (the attitude at the end, the reference of the other
methods); ``description``.  Rates are turned into increments as rate × interval
(constant over the interval); give increments where the IMU outputs them.

:func:`align_log` runs a method on a log once (no Monte Carlo): ``analytic``,
``inertial``, ``kalman`` (the inertial-frame coarse stage, then the filter
from its result and covariance, :mod:`~strapdown.analysis.alignment.coarse_to_fine`) or ``compass``.
:func:`recorded_problem` finds the positions of the log's motion (turns larger
than a threshold between still stretches) and builds the multi-position
observability problem of :mod:`~strapdown.analysis.alignment.observability`.

Public API
----------
ImuLog, read_log, write_log, log_record, LogAlignment, align_log,
recorded_problem, example_log, EXAMPLE_SEED, LOG_METHODS, METADATA
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.validation import as_array, positive
from .analytic import analytic_alignment
from .coarse_to_fine import coarse_model, coarse_to_fine, split_record
from .compass_loop import CompassLoopDesign, compass_loop_alignment
from .fine import FilterTuning
from .imu import ImuRecord, Scenario, SensorErrors
from .inertial import inertial_alignment
from .observability import ObservabilityProblem, stationary_problem
from .preintegration import chain_rotations, preintegrate
from .tilt_attitude import attitude_matrix

__all__ = ["ImuLog", "read_log", "write_log", "log_record", "LogAlignment", "align_log", "recorded_problem", "example_log", "EXAMPLE_SEED", "LOG_METHODS", "METADATA"]

#: Seed of the example log (``docs/examples/rocking-imu-log.npz``, :func:`example_log`).
EXAMPLE_SEED = 20261203

#: Methods :func:`align_log` runs.
LOG_METHODS = ("analytic", "inertial", "kalman", "compass")
#: Metadata a log may carry (SI units; ``description`` is text).
METADATA = ("latitude", "stable_heading", "stable_beta", "stable_gamma", "end_heading", "end_beta", "end_gamma", "description")
_AXES = ("x", "y", "z")


@dataclass(frozen=True)
class ImuLog:
    """The samples of one IMU at a constant rate.

    Attributes
    ----------
    time : ndarray
        ``(N,)`` end of each sample interval [s].
    dtheta : ndarray
        ``(N, 3)`` angle increments, body axes [rad].
    dv : ndarray
        ``(N, 3)`` velocity increments [m/s].
    metadata : dict
        Name → value, from :data:`METADATA`.
    """

    time: np.ndarray
    dtheta: np.ndarray
    dv: np.ndarray
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        t = as_array(self.time, "time").ravel()
        if t.size < 2:
            raise ValueError(f"Expected `time` of at least two samples, got {t.size}")
        d = np.diff(t)
        if not np.all(d > 0):
            raise ValueError("Expected `time` strictly increasing [s]")
        h = float(np.median(d))
        if np.max(np.abs(d - h)) > 1e-3 * h:
            raise ValueError(f"Expected `time` at a constant sample interval, got intervals from {d.min():.6g} to {d.max():.6g} s")
        object.__setattr__(self, "time", t)
        for name in ("dtheta", "dv"):
            a = as_array(getattr(self, name), name)
            if a.shape != (t.size, 3):
                raise ValueError(f"Expected `{name}` with shape ({t.size}, 3), got shape {a.shape}")
            object.__setattr__(self, name, a.astype(float))
        unknown = [k for k in self.metadata if k not in METADATA]
        if unknown:
            raise ValueError(f"Expected metadata among {METADATA}, got {unknown}")

    @property
    def dt(self) -> float:
        """Sample interval [s]."""
        return float(np.median(np.diff(self.time)))

    @property
    def n_samples(self) -> int:
        """Samples N."""
        return self.time.size

    def angles(self, which: str):
        """``(ψ, β, γ)`` of the metadata ``"stable"`` or ``"end"`` [rad], or None where the log does not carry them.

        Parameters
        ----------
        which : str
            ``"stable"`` or ``"end"``.

        Returns
        -------
        ndarray or None
        """
        keys = [f"{which}_{a}" for a in ("heading", "beta", "gamma")]
        if all(k in self.metadata for k in keys):
            return np.array([float(self.metadata[k]) for k in keys])
        return None


def _columns(kind_a, kind_b):
    return [f"{kind_a}_{a}" for a in _AXES], [f"{kind_b}_{a}" for a in _AXES]


def read_log(path) -> ImuLog:
    """Read a log from ``.npz`` or ``.csv`` (``docs/recorded-logs.md``).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    ImuLog

    Raises
    ------
    ValueError
        For an unknown suffix, missing columns, or samples that are not at a constant rate.
    OSError
        If the file cannot be read.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".npz":
        with np.load(p, allow_pickle=False) as z:
            data = {k: z[k] for k in z.files}
        meta = {k: (str(v) if k == "description" else float(v)) for k, v in data.items() if k in METADATA}
        if "time" not in data:
            raise ValueError(f"Expected an array `time` in {p.name}, got {sorted(data)}")
        t = np.asarray(data["time"], dtype=float)
        if "dtheta" in data and "dv" in data:
            return ImuLog(t, data["dtheta"], data["dv"], meta)
        if "gyro" in data and "accel" in data:
            h = _interval(t)
            return ImuLog(t, np.asarray(data["gyro"], dtype=float) * h, np.asarray(data["accel"], dtype=float) * h, meta)
        raise ValueError(f"Expected arrays `dtheta` and `dv` (or `gyro` and `accel`) in {p.name}, got {sorted(data)}")
    if suffix == ".csv":
        meta, header = {}, None
        with open(p, encoding="utf-8") as f:
            for line in f:
                s = line.strip()
                if s.startswith("#"):
                    name, sep, value = s[1:].partition(":")
                    name = name.strip()
                    if sep and name in METADATA:
                        meta[name] = value.strip() if name == "description" else float(value)
                    continue
                if s:
                    header = [c.strip() for c in s.split(",")]
                    break
            if header is None:
                raise ValueError(f"Expected a header row in {p.name}")
            rows = np.loadtxt(f, delimiter=",", ndmin=2)
        if rows.shape[1] != len(header):
            raise ValueError(f"Expected {len(header)} values per row (the header's columns) in {p.name}, got {rows.shape[1]}")
        col = {name: rows[:, i] for i, name in enumerate(header)}
        if "time" not in col:
            raise ValueError(f"Expected a column `time` in {p.name}, got {header}")
        t = col["time"]
        for a, b, scale in (("dtheta", "dv", None), ("gyro", "accel", "rate")):
            ca, cb = _columns(a, b)
            if all(c in col for c in ca + cb):
                A, B = np.stack([col[c] for c in ca], axis=1), np.stack([col[c] for c in cb], axis=1)
                h = 1.0 if scale is None else _interval(t)
                return ImuLog(t, A * h, B * h, meta)
        raise ValueError(f"Expected columns dtheta_x … dv_z (or gyro_x … accel_z) in {p.name}, got {header}")
    raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")


def _interval(t) -> float:
    d = np.diff(np.asarray(t, dtype=float))
    if d.size == 0 or not np.all(d > 0):
        raise ValueError("Expected `time` strictly increasing [s]")
    return float(np.median(d))


def write_log(path, log: ImuLog, *, dtype=np.float64) -> Path:
    """Write a log as ``.npz`` (compressed) or ``.csv``.

    Parameters
    ----------
    path : str or Path
        The file; its suffix chooses the format.
    log : ImuLog
        The samples.
    dtype : numpy dtype, keyword-only
        Storage type of the increments in ``.npz`` (``float32`` halves the size;
        the time stays float64).

    Returns
    -------
    Path
    """
    p = Path(path)
    suffix = p.suffix.lower()
    meta = dict(log.metadata)
    if suffix == ".npz":
        arrays = {"time": log.time, "dtheta": log.dtheta.astype(dtype), "dv": log.dv.astype(dtype)}
        arrays.update({k: np.array(v) for k, v in meta.items()})
        np.savez_compressed(p, **arrays)
        return p
    if suffix == ".csv":
        header = ["time"] + [f"dtheta_{a}" for a in _AXES] + [f"dv_{a}" for a in _AXES]
        lines = [f"# {k}: {v!r}" if not isinstance(v, str) else f"# {k}: {v}" for k, v in meta.items()]
        body = np.column_stack([log.time, log.dtheta, log.dv])
        with open(p, "w", encoding="utf-8", newline="\n") as f:
            f.write("\n".join(lines + [",".join(header)]) + "\n")
            np.savetxt(f, body, delimiter=",", fmt="%.17g")
        return p
    raise ValueError(f"Expected a log ending in .npz or .csv, got {p.name!r}")


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
    rng=0,
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
        Stream of the calibration and of the filter's velocity prior.

    Returns
    -------
    LogAlignment

    Raises
    ------
    ValueError
        For an unknown method or a log too short for the coarse stage.
    """
    from ..gyrocompass.rocking import as_generator
    from .estimate import wrap_angle

    if method not in LOG_METHODS:
        raise ValueError(f"Expected `method` in {LOG_METHODS}, got {method!r}")
    tuning = FilterTuning() if tuning is None else tuning
    g = as_generator(rng)
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
            res = coarse_to_fine(replace(rec, scenario=sc), tuning, cm, rng=g, score=False)
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

    The attitude is integrated from the gyros (in the frame of the first
    sample, the Earth's turn over the log neglected) and averaged over windows
    of ``window`` seconds, which removes the rocking; a new position starts at
    the first window whose mean attitude has turned by more than ``threshold``
    from the first window of the current position.  The start attitude is
    levelled and headed by the analytic alignment of the first position.

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
    from .error_model import navigation_error_model

    tuning = FilterTuning() if tuning is None else tuning
    M = max(1, int(round(min(1.0, positive(window, "window") / 10.0) / log.dt)))  # attitude samples: ten per window at least
    ep = preintegrate(log.dtheta[None], log.dv[None], log.dt, M)
    Q = chain_rotations(np.array([[1.0, 0.0, 0.0, 0.0]]), ep.rotation)[0]  # body in its start frame, at the epoch boundaries
    R = Rotation.from_quat(Q, scalar_first=True)
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


def example_log(seed: int = EXAMPLE_SEED) -> ImuLog:
    """Four minutes of a simulated navigation-grade IMU on a rocking base (``docs/examples/rocking-imu-log.npz``).

    Latitude 45°, stable heading 30°, tilts 0.5° and −0.3°, narrow-band rocking
    of σ = (0.5°, 1.5°, 1.5°) in (yaw, β, γ) with an 8 s period, the block 0.4 m
    above the rocking centre, 50 Hz, with the ``navigation`` grade of
    :data:`strapdown.analysis.alignment.sensor_models.GRADES` (turn-on biases,
    random walks, flicker and rate random walk).  The increments are rounded
    to float32, as the file stores them; the truth is in the metadata.

    Parameters
    ----------
    seed : int
        Root seed (the rocking and the sensor errors from its two children).

    Returns
    -------
    ImuLog
    """
    from .base_motion import NarrowbandMotion
    from .imu import simulate_imu
    from .sensor_models import GRADES, add_sensor_errors

    motion_seed, sensor_seed = np.random.SeedSequence(seed).spawn(2)
    sigma = np.radians([0.5, 1.5, 1.5])
    sc = Scenario(
        math.radians(45.0), heading=math.radians(30.0), beta0=math.radians(0.5), gamma0=math.radians(-0.3),
        motion=NarrowbandMotion(sigma * math.sqrt(2.0), 8.0, 0.1), lever_arm=[0.0, 0.0, -0.4], sample_rate=50.0, duration=240.0,
    )  # fmt: skip
    rec = simulate_imu(sc, None, n_trials=1, rng=np.random.default_rng(motion_seed))
    sheet = next(g for g in GRADES if g.name == "navigation")
    rec = add_sensor_errors(rec, sheet, rng=np.random.default_rng(sensor_seed))
    end = rec.truth_angles[0, -1]
    meta = {
        "latitude": sc.latitude,
        "stable_heading": sc.heading,
        "stable_beta": sc.beta0,
        "stable_gamma": sc.gamma0,
        "end_heading": float(end[0]),
        "end_beta": float(end[1]),
        "end_gamma": float(end[2]),
        "description": f"simulated: navigation-grade IMU, narrow-band rocking, 45 deg N, 50 Hz, 240 s (strapdown.analysis.alignment.recorded.example_log, seed {seed})",
    }
    as_stored = lambda x: x.astype(np.float32).astype(float)  # noqa: E731
    return ImuLog(sc.dt * np.arange(1, sc.n_samples + 1), as_stored(rec.dtheta[0]), as_stored(rec.dv[0]), meta)
