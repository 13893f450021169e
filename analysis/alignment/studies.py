"""The studies of the alignment report, as library functions with typed results.

Each study runs its Monte Carlo cases from children of one root SeedSequence,
so it is a pure function of its sizes and seed.  The canonical configurations
(sensor grades, the design scenario) are kept here once, shared by the report,
the benchmarks and the tests.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..core import montecarlo
from ..core.units import DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, rad, rad_per_s
from ..core.validation import as_array, as_int
from ..gyrocompass.azimuth import second_order_theory
from ..gyrocompass.finite_sample import mean_interval, sample_mean_statistics
from ..gyrocompass.rocking import NarrowbandRocking, SineRocking
from .base_motion import NarrowbandMotion, SineMotion, mean_variance
from .earth import EARTH_RATE, normal_gravity
from .fine import Disturbance, FilterTuning, assumed_disturbance
from .imu import Scenario, SensorErrors
from .monte_carlo import AlignmentMonteCarlo, AlignmentOptions, alignment_draws, alignment_monte_carlo
from .theory import analytic_theory

__all__ = [
    "THEORY_MARGIN",
    "NAVIGATION_GRADE",
    "DESIGN_SCENARIO",
    "kalman_options",
    "FloorRow",
    "bias_floor_study",
    "AccelBiasRow",
    "accel_bias_study",
    "NoiseRow",
    "noise_study",
    "RockingRow",
    "rocking_channel_study",
    "MismatchRow",
    "mismatch_study",
    "StatisticsRow",
    "sample_statistics_table",
    "CoverageRow",
    "coverage_study",
]

#: A theory (or a budget a check should meet) agrees with its Monte Carlo when the true mean or rms is
#: within this fraction of it, by TOST (:mod:`strapdown.analysis.core.verdicts`); a first-order theory
#: neglects terms far below 10 % in the report's cases.
THEORY_MARGIN = 0.1

#: A navigation-grade sensor set: 0.005 deg/h turn-on gyro bias, 0.002 deg/√h ARW,
#: 1e-4 m/s² accelerometer bias, 0.006 m/s/√h VRW.
NAVIGATION_GRADE = SensorErrors(
    gyro_bias_sigma=rad_per_s(0.005),
    accel_bias_sigma=1e-4,
    gyro_noise=0.002 * DEG_PER_RT_H_TO_RAD_PER_RT_S,
    accel_noise=0.006 * M_S_PER_RT_H_TO_M_S_PER_RT_S,
)

#: The design scenario: latitude 60°, heading 30°, two minutes at 10 Hz, the block 1 m above the
#: rocking centre and 0.5 m, 0.3 m off it.
DESIGN_SCENARIO = Scenario(rad(60.0), heading=rad(30.0), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=120.0)


def kalman_options(scenario: Scenario, errors: SensorErrors, *, epoch: float = 0.5, prior_heading: float = rad(1.0), disturbance: Disturbance | None = None) -> AlignmentOptions:
    """Kalman options of a filter that knows the sensors (and, unless told otherwise, the rocking).

    Parameters
    ----------
    scenario : Scenario
        The scenario (its rocking gives the disturbance model).
    errors : SensorErrors
        The sensors: the prior of the biases and the noise the filter assumes.
    epoch : float
        Measurement interval [s].
    prior_heading : float
        Prior azimuth standard deviation [rad].
    disturbance : Disturbance, optional
        The rocking model the filter assumes (default: the true one, shaping
        states when there is rocking and a lever arm).

    Returns
    -------
    AlignmentOptions
    """
    if disturbance is None:
        disturbance = assumed_disturbance(scenario.motion, scenario, kind="shaping") if np.any(scenario.lever_arm) and np.any(scenario.motion.amplitude) else Disturbance("none")
    gb = errors.gyro_bias_sigma or max(float(np.max(np.abs(errors.gyro_bias))), rad_per_s(0.001))
    ab = errors.accel_bias_sigma or max(float(np.max(np.abs(errors.accel_bias))), 1e-5)
    tuning = FilterTuning(epoch=epoch, prior_heading=prior_heading, gyro_bias=gb, accel_bias=ab, gyro_noise=errors.gyro_noise, accel_noise=errors.accel_noise, disturbance=disturbance)
    return AlignmentOptions(tuning=tuning)


def _run(scenario, errors, method, n_trials, seed, options=None):
    if options is None and method == "kalman":
        options = kalman_options(scenario, errors)
    return alignment_monte_carlo(scenario, errors, method=method, n_trials=n_trials, rng=seed, options=options)


@dataclass(frozen=True)
class FloorRow:
    """The gyro-bias floor at one latitude.

    Attributes
    ----------
    latitude : float
        Latitude [rad].
    bias : float
        East gyro bias [rad/s].
    floor : float
        ``−b/(Ω cos φ)`` [rad].
    deterministic : float
        Analytic method with the bias and no other error (every trial the same) [rad].
    results : dict
        Method → AlignmentMonteCarlo with white gyro noise added (a real interval).
    """

    latitude: float
    bias: float
    floor: float
    deterministic: float
    results: dict


def bias_floor_study(
    latitudes,
    *,
    bias: float = rad_per_s(0.01),
    noise: float = 0.0005 * DEG_PER_RT_H_TO_RAD_PER_RT_S,
    duration: float = 60.0,
    n_trials: int = 128,
    methods=("analytic", "inertial", "kalman"),
    rng=None,
) -> tuple:
    """East gyro bias b at rest: the azimuth error of every method against ``−b/(Ω cos φ)``.

    Parameters
    ----------
    latitudes : array_like
        Latitudes [rad].
    bias : float
        East gyro bias [rad/s].
    noise : float
        Angle random walk added for the interval [rad/√s].
    duration : float
        Alignment time [s].
    n_trials : int
        Trials per method and latitude.
    methods : sequence of str
        Methods.
    rng : Generator | SeedSequence | int | None
        Root seed.

    Returns
    -------
    tuple of FloorRow
    """
    root = montecarlo.root_seed_sequence(rng)
    rows = []
    for i, lat in enumerate(as_array(latitudes, "latitudes").ravel()):
        sc = Scenario(float(lat), duration=duration, sample_rate=10.0)
        det = alignment_monte_carlo(sc, SensorErrors(gyro_bias=[0.0, bias, 0.0]), method="analytic", n_trials=2, rng=montecarlo.block_seed(root, 100 + i))
        e = SensorErrors(gyro_bias=[0.0, bias, 0.0], gyro_noise=noise)
        res = {m: _run(sc, e, m, n_trials, montecarlo.block_seed(root, 10 * i + k)) for k, m in enumerate(methods)}
        rows.append(FloorRow(float(lat), bias, -bias / (EARTH_RATE * math.cos(lat)), det.result.mean, res))
    return tuple(rows)


@dataclass(frozen=True)
class AccelBiasRow:
    """An accelerometer bias at rest: azimuth and tilt terms.

    Attributes
    ----------
    axis : str
        ``"east"`` or ``"north"`` (body y or x at zero heading).
    bias : float
        The bias [m/s²].
    azimuth_theory : float
        ``tan φ · a_E/g`` (0 for north) [rad].
    tilt_theory : float
        ``a/g`` [rad].
    mc : AlignmentMonteCarlo
        Analytic method with a little accelerometer noise.
    """

    axis: str
    bias: float
    azimuth_theory: float
    tilt_theory: float
    mc: AlignmentMonteCarlo


def accel_bias_study(latitude: float, *, bias: float = 1e-3, duration: float = 30.0, n_trials: int = 256, rng=None) -> tuple:
    """East and north accelerometer biases: azimuth ``tan φ a_E/g``, tilt ``a/g``.

    Parameters
    ----------
    latitude : float
        Latitude [rad].
    bias : float
        Bias [m/s²].
    duration : float
        Alignment time [s].
    n_trials : int
        Trials.
    rng : Generator | SeedSequence | int | None
        Root seed.

    Returns
    -------
    tuple of AccelBiasRow
    """
    root = montecarlo.root_seed_sequence(rng)
    g = normal_gravity(latitude)
    sc = Scenario(latitude, duration=duration, sample_rate=10.0)
    rows = []
    for k, (axis, vec) in enumerate((("east", [0.0, bias, 0.0]), ("north", [bias, 0.0, 0.0]))):
        e = SensorErrors(accel_bias=vec, accel_noise=2e-4, gyro_noise=0.0002 * DEG_PER_RT_H_TO_RAD_PER_RT_S)
        mc = _run(sc, e, "analytic", n_trials, montecarlo.block_seed(root, k))
        rows.append(AccelBiasRow(axis, bias, math.tan(latitude) * bias / g if axis == "east" else 0.0, bias / g, mc))
    return tuple(rows)


@dataclass(frozen=True)
class NoiseRow:
    """White sensor noise at one alignment time.

    Attributes
    ----------
    duration : float
        Alignment time T [s].
    theory : float
        Analytic method: ``√(|G_ω|² N_g² + |G_t T_f|² N_a²)/√T`` [rad].
    results : dict
        Method → AlignmentMonteCarlo.
    """

    duration: float
    theory: float
    results: dict


def noise_study(durations, *, latitude: float = rad(45.0), errors: SensorErrors | None = None, n_trials: int = 128, methods=("analytic", "inertial", "kalman"), rng=None) -> tuple:
    """Angle and velocity random walk against the alignment time, every method.

    Parameters
    ----------
    durations : array_like
        Alignment times [s].
    latitude : float
        Latitude [rad].
    errors : SensorErrors, optional
        Default: ARW 0.003 deg/√h, VRW 0.03 m/s/√h, no biases.
    n_trials : int
        Trials per method and time.
    methods : sequence of str
        Methods.
    rng : Generator | SeedSequence | int | None
        Root seed.

    Returns
    -------
    tuple of NoiseRow
    """
    e = SensorErrors(gyro_noise=0.003 * DEG_PER_RT_H_TO_RAD_PER_RT_S, accel_noise=0.03 * M_S_PER_RT_H_TO_M_S_PER_RT_S) if errors is None else errors
    root = montecarlo.root_seed_sequence(rng)
    rows = []
    for i, T in enumerate(as_array(durations, "durations").ravel()):
        sc = Scenario(latitude, duration=float(T), sample_rate=10.0)
        res = {m: _run(sc, e, m, n_trials, montecarlo.block_seed(root, 10 * i + k)) for k, m in enumerate(methods)}
        rows.append(NoiseRow(float(T), analytic_theory(sc, e).rms, res))
    return tuple(rows)


@dataclass(frozen=True)
class RockingRow:
    """The analytic method under rocking, the paper's tilt channel and the whole system.

    Attributes
    ----------
    label : str
        The rocking.
    rocking_in_gyros : bool
        Whether the gyros see the rocking.
    amplitude : float
        Rocking standard deviation (narrow-band) or amplitude (sine) per rocked axis [rad].
    mc : AlignmentMonteCarlo
        Monte Carlo (formula (2), the estimates (16)).
    first_order : float
        The linear theory's rms [rad].
    second_order : float
        Tilt channel only: the second-order theory of Hrechka & Koroliov's error with the variance of
        the mean (NaN with the gyros) [rad].
    """

    label: str
    rocking_in_gyros: bool
    amplitude: float
    mc: AlignmentMonteCarlo
    first_order: float
    second_order: float

    @property
    def per_unit(self) -> float:
        """First-order rms per unit amplitude [rad/rad]."""
        return self.first_order / self.amplitude


def rocking_channel_study(*, latitude: float = rad(70.0), beta0: float = rad(2.0), gamma0: float = rad(-1.0), n_trials: int = 400, rng=None) -> tuple:
    """Formula (2) with (16) on a rocking base: with the rocking in the tilts only, and in the gyros too.

    The tilt-channel cases rock by 1° (the paper's setting); the same rockings
    reaching the gyros are scaled down to 0.001° to stay within the first-order
    range (their error is about 100° at 1°).  The two cases of a rocking share
    their trials (common random numbers: the same draws, scaled), so the gyro
    case evaluates no rocking of its own.

    Parameters
    ----------
    latitude : float
        Latitude [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    n_trials : int
        Trials per case.
    rng : Generator | SeedSequence | int | None
        Root seed.

    Returns
    -------
    tuple of RockingRow
    """
    root = montecarlo.root_seed_sequence(rng)
    tilt = np.array([0.0, 1.0, 1.0])
    cases = (
        ("narrow-band β, γ, 8 s, ζ = 0.1", lambda a: NarrowbandMotion(rad(a * tilt) * math.sqrt(2.0), 8.0, 0.1)),
        ("sine β, γ, 7 s", lambda a: SineMotion(rad(a * tilt), 7.0)),
        ("narrow-band yaw, β, γ, 8 s, ζ = 0.1", lambda a: NarrowbandMotion(rad(a * np.ones(3)) * math.sqrt(2.0), 8.0, 0.1)),
    )
    rows = []
    opts = AlignmentOptions(formula="paper")
    for k, (label, make) in enumerate(cases):
        draws = None
        for gyros, amplitude in ((False, 1.0), (True, 0.001)):
            motion = make(amplitude)
            sc = Scenario(latitude, beta0=beta0, gamma0=gamma0, motion=motion, sample_rate=10.0, duration=30.0, rocking_in_gyros=gyros)
            if draws is None:  # the trials of the first case, passed to the second (scaled)
                draws = alignment_draws(sc, method="analytic", n_trials=n_trials, rng=montecarlo.block_seed(root, k), options=opts)
            mc = alignment_monte_carlo(sc, method="analytic", n_trials=n_trials, options=opts, draws=draws)
            second = math.nan
            if not gyros:
                sd = np.sqrt(mean_variance(motion, sc.n_samples * sc.dt, sc.dt))
                second = second_order_theory(latitude, beta0, gamma0, sd[1], sd[2], kappa_xi=motion.kappa, kappa_eta=motion.kappa).rms
            rows.append(RockingRow(label, gyros, rad(amplitude), mc, mc.theory.rocking, second))
    return tuple(rows)


@dataclass(frozen=True)
class MismatchRow:
    """The Kalman filter with an assumed rocking model.

    Attributes
    ----------
    label : str
        What the filter assumes.
    disturbance : Disturbance
        Its model.
    mc : AlignmentMonteCarlo
        Monte Carlo (azimuth error, NEES, NIS).
    """

    label: str
    disturbance: Disturbance
    mc: AlignmentMonteCarlo


def mismatch_study(scenario: Scenario, errors: SensorErrors, *, period_ratios=(0.5, 0.8, 1.0, 1.25, 2.0), n_trials: int = 128, epoch: float = 0.5, rng=None) -> tuple:
    """The Kalman filter assuming the true rocking, a wrong period, white rocking, or none.

    Parameters
    ----------
    scenario : Scenario
        The true scenario (narrow-band or sine rocking and a lever arm).
    errors : SensorErrors
        Sensors (random biases drawn from the filter's prior).
    period_ratios : sequence of float
        Assumed period over the true one.
    n_trials : int
        Trials per row.
    epoch : float
        Measurement interval [s].
    rng : Generator | SeedSequence | int | None
        Root seed (the same trials for every row: common random numbers).

    Returns
    -------
    tuple of MismatchRow
    """
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    motion = scenario.motion
    models = []
    for r in period_ratios:
        assumed = replace(motion, period=motion.period * float(r))
        d = assumed_disturbance(assumed, scenario, kind="shaping")
        models.append((f"shaping, period × {float(r):g}", d))
    models.append(("white (lever-arm velocity as noise)", assumed_disturbance(motion, scenario, kind="white")))
    models.append(("none (rocking ignored)", Disturbance("none")))
    # one draw of the trials for every filter (common random numbers, passed explicitly): the same records,
    # simulated once and kept with the draws, and the same initial errors and measurement noise
    draws = alignment_draws(scenario, errors, method="kalman", n_trials=n_trials, rng=rng, options=kalman_options(scenario, errors, epoch=epoch))
    rows = []
    for label, d in models:
        opts = kalman_options(scenario, errors, epoch=epoch, disturbance=d)
        rows.append(MismatchRow(label, d, alignment_monte_carlo(scenario, errors, method="kalman", n_trials=n_trials, options=opts, draws=draws)))
    return tuple(rows)


@dataclass(frozen=True)
class StatisticsRow:
    """Finite-sample statistics of (16) for one rocking and averaging time.

    Attributes
    ----------
    label : str
        The rocking.
    duration : float
        Averaging time [s].
    stats : SampleMeanStatistics
        n, v, n_eff, the bias of σ̂², the naive interval's ratio, ν.
    """

    label: str
    duration: float
    stats: object


def _tilt_models():
    s = 1.0
    return (("narrow-band 8 s, ζ = 0.1", NarrowbandRocking(s, s, 8.0, 0.1)), ("narrow-band 8 s, ζ = 0.02", NarrowbandRocking(s, s, 8.0, 0.02)), ("sine 8 s", SineRocking(s, s, 8.0, 8.0)))


def sample_statistics_table(durations, *, dt: float = 0.1) -> tuple:
    """Effective sample size and variance bias of (16) for the canonical rockings.

    Parameters
    ----------
    durations : array_like
        Averaging times [s].
    dt : float
        Sample interval [s].

    Returns
    -------
    tuple of StatisticsRow
    """
    rows = []
    for label, model in _tilt_models():
        for T in as_array(durations, "durations").ravel():
            n = max(2, int(round(float(T) / dt)))
            rows.append(StatisticsRow(label, float(T), sample_mean_statistics(model, n, dt)))
    return tuple(rows)


@dataclass(frozen=True)
class CoverageRow:
    """Coverage of 95 % intervals of the stable tilt by Monte Carlo.

    Attributes
    ----------
    label : str
        The rocking.
    duration : float
        Averaging time [s].
    coverage : dict
        Method (``model``, ``naive``, ``batch-means``) → fraction of trials covered.
    n_trials : int
        Trials.
    """

    label: str
    duration: float
    coverage: dict
    n_trials: int


def _xi_sample(model: NarrowbandRocking, g: np.random.Generator, n_trials: int, n_steps: int, dt: float) -> np.ndarray:
    """``model.sample(g, n_trials, n_steps, dt)[0]`` without filtering η: the same normals (ξ's rows come first in
    each draw), ξ's rows only through the filter (``tests/test_alignment.py`` holds the two equal)."""
    z0 = g.standard_normal((2 * n_trials, 3))[:n_trials] * model.sigma_xi
    z = g.standard_normal((n_trials, max(n_steps - 2, 0))) * model.sigma_xi
    return model.series_from_normals(z0, z, n_steps, dt, overwrite=True)


def coverage_study(durations, *, dt: float = 0.1, n_trials: int = 2000, rng=None) -> tuple:
    """How often the 95 % intervals of the mean cover the stable tilt under narrow-band rocking.

    Parameters
    ----------
    durations : array_like
        Averaging times [s].
    dt : float
        Sample interval [s].
    n_trials : int
        Trials per time.
    rng : Generator | SeedSequence | int | None
        Root seed.

    Returns
    -------
    tuple of CoverageRow
    """
    root = montecarlo.root_seed_sequence(rng)
    label, model = _tilt_models()[0]
    rows = []
    for i, T in enumerate(as_array(durations, "durations").ravel()):
        n = max(20, int(round(float(T) / dt)))
        xi = _xi_sample(model, np.random.default_rng(montecarlo.block_seed(root, i)), n_trials, n, dt)
        cov = {m: float(mean_interval(xi, method=m, model=model, dt=dt).covers(0.0).mean()) for m in ("model", "naive", "batch-means")}
        rows.append(CoverageRow(label, float(T), cov, n_trials))
    return tuple(rows)
