"""The studies of the alignment-design report, as library functions with typed results.

What an alignment designer asks, each answered once here for the report
(``reports/alignment-design.md``), the benchmarks and the tests:

* which errors are observable at all (:func:`observability_study`);
* how the methods compare on the same trials, each against its trials' floor
  (:func:`methods_study`);
* how long a grade of IMU takes to align, at rest and under rocking, from the
  filter's own covariance (:func:`grade_study`, :func:`rocking_design_study`),
  with Monte Carlo check points on data-sheet sensors (:func:`design_check_points`);
* how the manoeuvre of a moving vehicle sets the time of GNSS-aided alignment
  (:func:`manoeuvre_study`, :func:`aided_checks`);
* whether a simulated sensor has the Allan deviation of its data sheet (:func:`allan_study`).

Each Monte Carlo study draws from children of one root SeedSequence, so it is a
pure function of its sizes and seed.

Public API
----------
DESIGN_LATITUDE, DESIGN_SENSORS, PREDICTION_MARGIN, design_scenario, observability_study, ObservabilityStudy,
methods_study, grade_tuning, GradeCurve, grade_study, RockingRow, rocking_design_study,
CheckPoint, design_check_points, ManoeuvreRow, manoeuvre_study, aided_sensors, aided_checks, AllanStudy, allan_study,
LargeHeadingStudy, large_heading_study
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..core import kalman, montecarlo
from ..core.units import rad
from ..core.verdicts import Verdict
from .aided import AidedTuning, aided_inputs, aided_monte_carlo, aided_sequence, time_to_align
from .base_motion import NarrowbandMotion
from .comparison import MethodComparison, TrialSummary, compare_methods, summarise
from .earth import EARTH_RATE, normal_gravity
from .fine import Disturbance, FilterTuning, assumed_disturbance, filter_model, fine_alignment
from .imu import Scenario, SensorErrors, simulate_imu
from .observability import BodyRotation, ObservabilityResult, multi_position_problem, observability, rocking_problem, stationary_problem
from .sensor_models import GRADES, AllanDeviation, AllanFit, DataSheet, SensorSpec, add_sensor_errors, allan_deviation, fit_allan, simulate_sensor_errors
from .trajectory import Manoeuvre

__all__ = [
    "DESIGN_LATITUDE",
    "DESIGN_SENSORS",
    "PREDICTION_MARGIN",
    "design_scenario",
    "ObservabilityStudy",
    "observability_study",
    "methods_study",
    "grade_tuning",
    "GradeCurve",
    "grade_study",
    "RockingRow",
    "rocking_design_study",
    "CheckPoint",
    "design_check_points",
    "ManoeuvreRow",
    "manoeuvre_study",
    "aided_sensors",
    "aided_checks",
    "AllanStudy",
    "allan_study",
    "LargeHeadingStudy",
    "large_heading_study",
]

#: Latitude of the design studies [rad].
DESIGN_LATITUDE = rad(45.0)
#: The sensors of the method comparison: the navigation grade's turn-on biases and random walks
#: (the model every filter here assumes: constant biases, white noise).
DESIGN_SENSORS = SensorErrors(
    gyro_bias_sigma=GRADES[1].gyro.turn_on_bias, accel_bias_sigma=GRADES[1].accel.turn_on_bias, gyro_noise=GRADES[1].gyro.random_walk, accel_noise=GRADES[1].accel.random_walk
)
#: The rocking of the rocking cases: narrow-band, 8 s, σ = (0.5°, 1°, 1°), the block 1 m above the centre.
DESIGN_ROCKING = NarrowbandMotion(np.radians([0.5, 1.0, 1.0]) * math.sqrt(2.0), 8.0, 0.1)
DESIGN_LEVER_ARM = (0.3, 0.2, -1.0)
#: A design chart's predicted σ holds at a check point when the Monte Carlo rms is within this fraction of it.
PREDICTION_MARGIN = 0.25


def design_scenario(*, rocking: bool = False, duration: float = 300.0, sample_rate: float = 10.0) -> Scenario:
    """The design case: 45° N, heading 30°, at rest or rocking (with the block 1 m from the rocking centre).

    Parameters
    ----------
    rocking : bool, keyword-only
        Narrow-band rocking (:data:`DESIGN_ROCKING`) with the lever arm.
    duration : float, keyword-only
        Alignment time [s].
    sample_rate : float, keyword-only
        [Hz].

    Returns
    -------
    Scenario
    """
    if rocking:
        return Scenario(DESIGN_LATITUDE, heading=rad(30.0), motion=DESIGN_ROCKING, lever_arm=DESIGN_LEVER_ARM, sample_rate=sample_rate, duration=duration)
    return Scenario(DESIGN_LATITUDE, heading=rad(30.0), sample_rate=sample_rate, duration=duration)


@dataclass(frozen=True)
class ObservabilityStudy:
    """The observability of the three alignment models.

    Attributes
    ----------
    stationary : ObservabilityResult
        Twelve states at rest.
    rocking : ObservabilityResult
        With the rocking states of the fine filter.
    multi_position : ObservabilityResult
        Turned 90° about the vertical at half the horizon.
    four_position : ObservabilityResult
        Turned 90° about the vertical three times.
    """

    stationary: ObservabilityResult
    rocking: ObservabilityResult
    multi_position: ObservabilityResult
    four_position: ObservabilityResult


def observability_study(*, latitude: float = DESIGN_LATITUDE, duration: float = 300.0) -> ObservabilityStudy:
    """Rank, unobservable directions and degree of observability of the stationary, rocking and multi-position models.

    Parameters
    ----------
    latitude : float, keyword-only
        [rad].
    duration : float, keyword-only
        Horizon of the degree of observability [s].

    Returns
    -------
    ObservabilityStudy
    """
    tuning = FilterTuning(gyro_bias=DESIGN_SENSORS.gyro_bias_sigma, accel_bias=DESIGN_SENSORS.accel_bias_sigma, epoch=1.0)
    rock = replace(design_scenario(rocking=True, duration=duration), latitude=latitude)
    z90 = rad(90.0)
    return ObservabilityStudy(
        observability(stationary_problem(latitude, tuning=tuning, duration=duration)),
        observability(rocking_problem(rock, tuning)),
        observability(multi_position_problem(latitude, [BodyRotation(duration / 2, "z", z90)], duration, tuning=tuning)),
        observability(multi_position_problem(latitude, [BodyRotation(duration * k / 4, "z", z90) for k in (1, 2, 3)], duration, tuning=tuning)),
    )


def methods_study(*, n_trials: int, rng=None, rocking: bool = False, duration: float = 300.0) -> MethodComparison:
    """The methods on the same trials of the design case (navigation-grade sensors), each against its trials' floor.

    Parameters
    ----------
    n_trials : int, keyword-only
        Trials.
    rng : Generator | SeedSequence | int | None, keyword-only
        Root seed.
    rocking : bool, keyword-only
        The rocking case (the analytic method, which the rocked gyros defeat, is left out); the
        filters carry rocking states matched to its spectrum (``Disturbance`` kind ``"matched"``).
    duration : float, keyword-only
        Alignment time [s] (the coarse stage takes the first 60 s of it).

    Returns
    -------
    MethodComparison
    """
    sc = design_scenario(rocking=rocking, duration=duration)
    e = DESIGN_SENSORS
    dist = assumed_disturbance(sc.motion, sc, kind="matched") if rocking else Disturbance("none")
    tuning = FilterTuning(epoch=0.5, gyro_bias=e.gyro_bias_sigma, accel_bias=e.accel_bias_sigma, gyro_noise=e.gyro_noise, accel_noise=e.accel_noise, disturbance=dist)
    methods = ("inertial", "kalman", "coarse-to-fine", "compass") if rocking else ("analytic", "inertial", "kalman", "coarse-to-fine", "compass")
    return compare_methods(sc, e, n_trials=n_trials, rng=rng, methods=methods, tuning=tuning, coarse_duration=60.0, calibration_trials=max(32, n_trials))


def _sheet_bias(spec: SensorSpec) -> float:
    """The bias a filter over minutes should expect: the turn-on bias and the flicker floor together."""
    from .sensor_models import FLICKER_FLOOR

    return math.hypot(spec.turn_on_bias, FLICKER_FLOOR * spec.bias_instability)


def _floor(latitude: float, gyro_bias: float, accel_bias: float) -> float:
    """σ of the bias floor ``ε_E/(Ω cos φ) − tan φ ∇_E/g`` for independent biases of these σ [rad]."""
    return math.hypot(gyro_bias / (EARTH_RATE * math.cos(latitude)), math.tan(latitude) * accel_bias / normal_gravity(latitude))


def grade_tuning(sheet: DataSheet, *, latitude: float = DESIGN_LATITUDE, epoch: float = 1.0, disturbance: Disturbance | None = None) -> FilterTuning:
    """The fine filter of a grade: biases from its data sheet, its random walks, a prior heading three floors wide (at least 1°).

    Parameters
    ----------
    sheet : DataSheet
        The IMU.
    latitude : float, keyword-only
        [rad].
    epoch : float, keyword-only
        [s].
    disturbance : Disturbance, optional, keyword-only
        The rocking model of the filter.

    Returns
    -------
    FilterTuning
    """
    gb, ab = _sheet_bias(sheet.gyro), _sheet_bias(sheet.accel)
    heading = max(rad(1.0), 3.0 * _floor(latitude, gb, ab))
    return FilterTuning(
        epoch=epoch, prior_heading=heading, gyro_bias=gb, accel_bias=ab, gyro_noise=sheet.gyro.random_walk, accel_noise=sheet.accel.random_walk,
        disturbance=Disturbance("none") if disturbance is None else disturbance,
    )  # fmt: skip


@dataclass(frozen=True)
class GradeCurve:
    """A grade's predicted azimuth error against alignment time (the Kalman filter's covariance, at rest).

    Attributes
    ----------
    grade : str
        The grade.
    times : ndarray
        ``(E,)`` [s].
    sigma : ndarray
        ``(E,)`` the filter's azimuth standard deviation [rad].
    floor : float
        σ of the bias floor [rad].
    time_to_align : float
        When σ comes within 10 % of the floor [s] (inf if not within the horizon).
    """

    grade: str
    times: np.ndarray
    sigma: np.ndarray
    floor: float
    time_to_align: float


def _filter_run(scenario: Scenario, tuning: FilterTuning) -> tuple:
    """The fine filter's model and covariance sequence over the whole scenario (as :func:`fine_alignment` computes them)."""
    model = filter_model(scenario, tuning)
    E = scenario.n_samples // model.samples_per_epoch
    return model, kalman.filter_sequence(model.F, model.Q, model.H, model.R, model.P0, E)


def _sigma_curve(scenario: Scenario, tuning: FilterTuning, run: tuple | None = None) -> tuple:
    model, seq = _filter_run(scenario, tuning) if run is None else run
    E = seq.posterior.shape[0]
    return model.epoch * np.arange(1, E + 1), np.sqrt(seq.posterior[:, 2, 2])


def grade_study(grades=GRADES[:3], *, latitude: float = DESIGN_LATITUDE, duration: float = 1800.0) -> tuple:
    """Time to align at rest for each grade: the filter's azimuth σ against time, and when it reaches 1.1 × its floor.

    Parameters
    ----------
    grades : sequence of DataSheet
        The IMUs (the tactical grade cannot gyrocompass: its floor is several degrees).
    latitude : float, keyword-only
        [rad].
    duration : float, keyword-only
        Horizon [s].

    Returns
    -------
    tuple of GradeCurve
    """
    out = []
    for sheet in grades:
        tuning = grade_tuning(sheet, latitude=latitude)
        sc = Scenario(latitude, heading=rad(30.0), sample_rate=1.0, duration=duration)
        t, s = _sigma_curve(sc, tuning)
        floor = _floor(latitude, tuning.gyro_bias, tuning.accel_bias)
        out.append(GradeCurve(sheet.name, t, s, floor, time_to_align(s, t, 1.1 * floor)))
    return tuple(out)


@dataclass(frozen=True)
class RockingRow:
    """Time to align under narrow-band rocking of one amplitude, for a filter that models it or treats it as noise.

    Attributes
    ----------
    sigma : float
        Standard deviation of the rocking angles β, γ (yaw half of it) [rad].
    kind : str
        ``"shaping"`` (rocking states) or ``"white"`` (the lever-arm velocity as measurement noise).
    time_to_align : float
        When the azimuth σ comes within 10 % of the floor [s].
    sigma_end : float
        The azimuth σ at the horizon [rad].
    """

    sigma: float
    kind: str
    time_to_align: float
    sigma_end: float


def rocking_motion(sigma: float, period: float = 8.0) -> NarrowbandMotion:
    """Narrow-band rocking with β, γ of standard deviation ``sigma`` and yaw of half of it.

    Parameters
    ----------
    sigma : float
        [rad].
    period : float
        [s].

    Returns
    -------
    NarrowbandMotion
    """
    return NarrowbandMotion(np.array([0.5, 1.0, 1.0]) * sigma * math.sqrt(2.0), period, 0.1)


def rocking_design_study(sigmas, *, sheet: DataSheet = GRADES[1], latitude: float = DESIGN_LATITUDE, period: float = 8.0, duration: float = 1800.0) -> tuple:
    """Time to align against the rocking amplitude, the block at :data:`DESIGN_LEVER_ARM` from the rocking centre.

    Parameters
    ----------
    sigmas : sequence of float
        Standard deviations of the tilt rocking [rad].
    sheet : DataSheet, keyword-only
        The IMU.
    latitude : float, keyword-only
        [rad].
    period : float, keyword-only
        Rocking period [s].
    duration : float, keyword-only
        Horizon [s].

    Returns
    -------
    tuple of RockingRow
    """
    rows = []
    for s in sigmas:
        sc = Scenario(latitude, heading=rad(30.0), motion=rocking_motion(s, period), lever_arm=DESIGN_LEVER_ARM, sample_rate=10.0, duration=duration)
        for kind in ("shaping", "white"):
            tuning = grade_tuning(sheet, latitude=latitude, disturbance=assumed_disturbance(sc.motion, sc, kind=kind))
            t, sig = _sigma_curve(sc, tuning)
            floor = _floor(latitude, tuning.gyro_bias, tuning.accel_bias)
            rows.append(RockingRow(float(s), kind, time_to_align(sig, t, 1.1 * floor), float(sig[-1])))
    return tuple(rows)


@dataclass(frozen=True)
class CheckPoint:
    """A point of a design chart checked by Monte Carlo on data-sheet sensors.

    Attributes
    ----------
    label : str
        What is checked.
    time : float
        Alignment time [s].
    predicted : float
        The filter's azimuth σ there [rad].
    error : TrialSummary
        The Monte Carlo azimuth error [rad].
    """

    label: str
    time: float
    predicted: float
    error: TrialSummary

    @property
    def agreement(self) -> Verdict:
        """Does the Monte Carlo rms agree with the predicted σ within ±:data:`PREDICTION_MARGIN`? (TOST on the mean square.)"""
        return self.error.rms_agrees(self.predicted, PREDICTION_MARGIN, what="the filter's predicted σ")


@dataclass(frozen=True)
class _SheetKernel:
    """Fine alignment on records with a data sheet's errors (heading error at the end, one column)."""

    scenario: Scenario
    sheet: DataSheet
    tuning: FilterTuning
    model: object = None  # filter_model(scenario, tuning), computed once for every block (default: per block)
    sequence: object = None  # its covariance sequence (default: per block)

    def __call__(self, n_trials: int, rng) -> np.ndarray:
        model = filter_model(self.scenario, self.tuning) if self.model is None else self.model
        rec = simulate_imu(self.scenario, None, n_trials=n_trials, rng=rng, truth_stride=model.samples_per_epoch)
        rec = add_sensor_errors(rec, self.sheet, rng=rng)
        res = fine_alignment(rec, self.tuning, rng=rng, model=model, sequence=self.sequence, score=False)
        return res.estimate.heading_error[:, None]


def design_check_points(cases, *, n_trials: int, rng=None) -> tuple:
    """Monte Carlo of the fine filter on data-sheet sensors (flicker and rate random walk included) at chart points.

    Parameters
    ----------
    cases : sequence of tuple
        ``(label, sheet, sigma, time)``: the grade, the tilt rocking σ [rad]
        (0: at rest; else narrow-band at 8 s with the lever arm, the filter
        with rocking states) and the alignment time [s].
    n_trials : int, keyword-only
        Trials per point.
    rng : Generator | SeedSequence | int | None, keyword-only
        Root seed (child i for case i).

    Returns
    -------
    tuple of CheckPoint
    """
    root = montecarlo.root_seed_sequence(rng)
    out = []
    for i, (label, sheet, sigma, T) in enumerate(cases):
        if sigma > 0:  # 10 Hz: the coning of 8 s rocking stays far below the Earth rate
            sc = Scenario(DESIGN_LATITUDE, heading=rad(30.0), motion=rocking_motion(sigma), lever_arm=DESIGN_LEVER_ARM, sample_rate=10.0, duration=T)
            tuning = grade_tuning(sheet, disturbance=assumed_disturbance(sc.motion, sc, kind="shaping"))
        else:  # at rest 2 Hz suffice (the filter's epoch is 1 s)
            sc = Scenario(DESIGN_LATITUDE, heading=rad(30.0), sample_rate=2.0, duration=T)
            tuning = grade_tuning(sheet)
        run = _filter_run(sc, tuning)  # one filterpy run for the predicted σ and every block's filter
        _, sig = _sigma_curve(sc, tuning, run)
        rows = montecarlo.collect(_SheetKernel(sc, sheet, tuning, *run), n_trials, rng=montecarlo.block_seed(root, i), trials_per_block=min(64, n_trials), blocks_per_chunk=1)
        out.append(CheckPoint(label, float(T), float(sig[-1]), summarise(rows[:, 0])))
    return tuple(out)


@dataclass(frozen=True)
class ManoeuvreRow:
    """GNSS-aided alignment of one weave.

    Attributes
    ----------
    amplitude : float
        Weave amplitude [rad].
    lateral_acceleration : float
        Peak horizontal acceleration of the weave [m/s²].
    time_to_align : float
        When the azimuth σ stays within the budget [s].
    sigma_end : float
        The azimuth σ at the horizon [rad].
    """

    amplitude: float
    lateral_acceleration: float
    time_to_align: float
    sigma_end: float


def _weave(amplitude: float) -> Manoeuvre:
    return Manoeuvre(latitude=DESIGN_LATITUDE, heading=rad(30.0), speed=10.0, start_speed=10.0, weave_amplitude=amplitude, weave_period=40.0)


def aided_sensors() -> tuple:
    """The IMU of the GNSS-aided studies: the tactical grade's turn-on biases and random walks.

    Returns
    -------
    tuple of SensorSpec
        ``(gyro, accel)`` [rad/s, rad/√s; m/s², m/s/√s].
    """
    t = GRADES[3]
    return SensorSpec(t.gyro.random_walk, turn_on_bias=t.gyro.turn_on_bias), SensorSpec(t.accel.random_walk, turn_on_bias=t.accel.turn_on_bias)


def manoeuvre_study(amplitudes, *, budget: float = rad(0.5), duration: float = 180.0) -> tuple:
    """Time for GNSS-aided alignment of a tactical-grade IMU against the weave of a car at 10 m/s.

    Parameters
    ----------
    amplitudes : sequence of float
        Heading weave amplitudes (40 s period) [rad].
    budget : float, keyword-only
        Azimuth σ to reach [rad].
    duration : float, keyword-only
        Horizon [s].

    Returns
    -------
    tuple of ManoeuvreRow
    """
    gyro, accel = aided_sensors()
    tuning = AidedTuning.for_sensors(gyro, accel)
    rows = []
    for a in amplitudes:
        man = _weave(a)
        seq = aided_sequence(man, tuning, sample_rate=5.0, duration=duration)
        rows.append(ManoeuvreRow(float(a), man.lateral_acceleration, time_to_align(seq.heading_sigma, seq.update_times, budget), float(seq.heading_sigma[-1])))
    return tuple(rows)


def aided_checks(amplitudes, *, n_trials: int, rng=None, duration: float = 180.0) -> tuple:
    """Monte Carlo of the aided alignment (tactical grade) for a few weaves.

    Parameters
    ----------
    amplitudes : sequence of float
        Weave amplitudes [rad] (0: straight).
    n_trials : int, keyword-only
        Trials per weave.
    rng : Generator | SeedSequence | int | None, keyword-only
        Root seed (child i for weave i).
    duration : float, keyword-only
        [s].

    Returns
    -------
    tuple of AidedMonteCarlo
    """
    gyro, accel = aided_sensors()
    tuning = AidedTuning.for_sensors(gyro, accel)
    root = montecarlo.root_seed_sequence(rng)
    return tuple(
        aided_monte_carlo(aided_inputs(_weave(a), tuning, sample_rate=10.0, duration=duration), gyro, accel, n_trials=n_trials, rng=montecarlo.block_seed(root, i))
        for i, a in enumerate(amplitudes)
    )


@dataclass(frozen=True)
class AllanStudy:
    """A grade's gyro: the Allan deviation of its data sheet and of a simulated record.

    Attributes
    ----------
    grade : str
        The grade.
    spec : SensorSpec
        Its gyro.
    measured : AllanDeviation
        The simulated record's Allan deviation.
    expected : ndarray
        The data sheet's Allan deviation at the same τ, the IEEE Std 952 curve
        with its flat flicker floor (:meth:`SensorSpec.datasheet_allan_variance`) [rad/s].
    model : ndarray
        The simulated model's own Allan deviation at the same τ (its
        Gauss–Markov sum for the flicker noise, :meth:`SensorSpec.allan_variance`) [rad/s].
    fit : AllanFit
        N, B, K read back from the measured curve up to ``fit_tau``.
    duration : float
        Length of the record [s].
    fit_tau : float
        Longest averaging time of the fit [s]: a third of the flicker band's
        longest correlation time, beyond which the Gauss–Markov sum leaves the
        flicker floor.
    model_fit : AllanFit
        The same fit of the model's own curve at the same τ (what a perfect,
        endless record of the simulated sensor would read back).
    """

    grade: str
    spec: SensorSpec
    measured: AllanDeviation
    expected: np.ndarray
    model: np.ndarray
    fit: AllanFit
    duration: float
    fit_tau: float
    model_fit: AllanFit

    @property
    def inside(self) -> int:
        """Points where the data sheet's curve lies in the measured 95 % interval."""
        return int(np.sum((self.expected >= self.measured.low) & (self.expected <= self.measured.high)))

    @property
    def model_inside(self) -> int:
        """Points where the model's own curve lies in the measured 95 % interval."""
        return int(np.sum((self.model >= self.measured.low) & (self.model <= self.measured.high)))

    @property
    def model_departure(self) -> np.ndarray:
        """``model / expected − 1`` at each τ: how far the simulated model's Allan deviation lies from the data sheet's."""
        return self.model / self.expected - 1.0

    def model_within(self, tolerance: float) -> tuple:
        """The averaging times at which the model's Allan deviation is within ``tolerance`` of the data sheet's.

        Parameters
        ----------
        tolerance : float
            Relative tolerance, e.g. 0.05.

        Returns
        -------
        tuple of float
            ``(τ_low, τ_high)`` [s]: the first and last τ of the measured grid
            within the tolerance (NaN, NaN when none is).
        """
        ok = np.abs(self.model_departure) <= float(tolerance)
        if not ok.any():
            return (math.nan, math.nan)
        t = self.measured.taus[ok]
        return (float(t[0]), float(t[-1]))


def allan_study(sheet: DataSheet = GRADES[3], *, n_samples: int = 2**17, dt: float = 0.1, rng=None) -> AllanStudy:
    """Simulate a grade's gyro for ``n_samples`` samples and measure its Allan deviation against the data sheet.

    Parameters
    ----------
    sheet : DataSheet
        The IMU (its gyro).
    n_samples : int, keyword-only
        Samples.
    dt : float, keyword-only
        [s].
    rng : Generator | SeedSequence | int | None, keyword-only
        Random stream.

    Returns
    -------
    AllanStudy
    """
    spec = sheet.gyro
    e = simulate_sensor_errors(spec, n_trials=1, n_samples=n_samples, dt=dt, rng=rng)
    rate = e.increments[0, :, 0] / dt - e.turn_on[0, 0]
    a = allan_deviation(rate, dt, spec=spec)
    top = spec.flicker_band[1] / 3.0
    used = a.taus <= top
    expected = np.sqrt(spec.datasheet_allan_variance(a.taus))
    own = np.sqrt(spec.allan_variance(a.taus))
    fit = fit_allan(a.taus[used], a.adev[used], weights=a.edf[used])
    model = fit_allan(a.taus[used], own[used], weights=a.edf[used])
    return AllanStudy(sheet.name, spec, a, expected, own, fit, n_samples * dt, float(top), model)


@dataclass(frozen=True)
class LargeHeadingStudy:
    """Alignment from large heading errors: the unscented filter and the closed-loop error-state filter from the same starts.

    Attributes
    ----------
    initial : ndarray
        ``(n,)`` initial heading errors [rad].
    times : ndarray
        ``(K,)`` times read [s].
    unscented : ndarray
        ``(n, K)`` the unscented filter's heading error then [rad].
    error_state : ndarray
        ``(n, K)`` the error-state filter's (:mod:`~strapdown.analysis.alignment.fine`) [rad].
    unscented_sigma, error_state_sigma : ndarray
        ``(K,)`` their own azimuth σ then (trial 0's for the unscented filter) [rad].
    """

    initial: np.ndarray
    times: np.ndarray
    unscented: np.ndarray
    error_state: np.ndarray
    unscented_sigma: np.ndarray
    error_state_sigma: np.ndarray


def large_heading_study(*, n_trials: int, rng=None, prior_heading: float = rad(40.0), duration: float = 180.0) -> LargeHeadingStudy:
    """Both filters from the same large initial heading errors (navigation-grade sensors, at rest, 1 s epochs).

    Parameters
    ----------
    n_trials : int, keyword-only
        Trials (one unscented filter each).
    rng : Generator | SeedSequence | int | None, keyword-only
        Root seed: the record, the initial errors, the filters' noise.
    prior_heading : float, keyword-only
        Standard deviation of the initial heading errors, and the filters' prior [rad].
    duration : float, keyword-only
        [s].

    Returns
    -------
    LargeHeadingStudy
    """
    from .tilt_attitude import attitude_matrix
    from .unscented import UnscentedTuning, unscented_alignment

    root = montecarlo.root_seed_sequence(rng)
    s_rec, s_init, s_u, s_f = (np.random.default_rng(montecarlo.block_seed(root, k)) for k in range(4))
    e = DESIGN_SENSORS
    sc = Scenario(DESIGN_LATITUDE, heading=rad(30.0), sample_rate=5.0, duration=duration)
    rec = simulate_imu(sc, e, n_trials=n_trials, rng=s_rec, truth_stride=5)
    kw = dict(gyro_bias=e.gyro_bias_sigma, accel_bias=e.accel_bias_sigma, gyro_noise=e.gyro_noise, accel_noise=e.accel_noise)
    tilt = rad(0.1)
    x0 = s_init.standard_normal((n_trials, 3)) * np.array([prior_heading, tilt, tilt])
    u = unscented_alignment(rec, UnscentedTuning(prior_heading=prior_heading, prior_tilt=tilt, alpha=1e-3, **kw), rng=s_u, initial_errors=x0)
    f = fine_alignment(rec, FilterTuning(epoch=1.0, prior_heading=prior_heading, prior_tilt=tilt, **kw), rng=s_f, initial_attitude=attitude_matrix(rec.truth_angles[:, 0] + x0))
    idx = [k for k in (9, 29, 59, 119, u.times.size - 1) if k < u.times.size]
    return LargeHeadingStudy(x0[:, 0], u.times[idx], u.heading_error[:, idx], f.heading_error[:, idx], u.heading_sigma[0, idx], f.heading_sigma[idx])
