"""The alignment methods side by side on the same trials, each against the floor its trial's biases set.

One trial is one sensor record (rocking, turn-on biases, noise); every method
of the comparison runs on that same record (common random numbers), so their
differences are not sampling noise.  The methods:

``analytic``
    formula (2) with the averaged outputs (:mod:`~strapdown.analysis.alignment.analytic`);
``inertial``
    inertial-frame alignment over the whole record (:mod:`~strapdown.analysis.alignment.inertial`);
``kalman``
    the fine-alignment filter from an attitude drawn from its prior (:mod:`~strapdown.analysis.alignment.fine`);
``coarse-to-fine``
    the inertial-frame alignment on the first T_c seconds, then the filter
    from its result and covariance (:mod:`~strapdown.analysis.alignment.coarse_to_fine`);
``compass``
    the compass loop (:mod:`~strapdown.analysis.alignment.compass_loop`) from the same coarse result.

Every self-alignment method ends, given time, on the *bias floor* of its
trial: the azimuth error ``−ε_E/(Ω cos φ) + tan φ ∇_E/g`` of the trial's own
biases at the stable attitude (:func:`trial_floors`, the gains of
:func:`strapdown.analysis.alignment.theory.analytic_gain_values`), which no
measurement at rest can remove (:mod:`~strapdown.analysis.alignment.observability`).  The comparison reports
each method's azimuth error, its residual over the floor, whether it has
reached the floor (:func:`floor_reached`: the residual's rms at most
:data:`FLOOR_MARGIN` times the floor's, a one-sided test on the same trials
that says "yes", "no" or "not resolved") and, for the two filters, the NEES
and NIS against their χ² bands.  Trials run in blocks through
:func:`strapdown.analysis.core.montecarlo.collect`, so the rows are
bit-identical for any chunking or executor.

Public API
----------
METHODS, FLOOR_MARGIN, TrialSummary, summarise, trial_floors, floor_reached, MethodRow,
MethodComparison, ComparisonKernel, compare_methods
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import budget, kalman, montecarlo
from ..core.validation import as_array, as_int, positive
from ..core.verdicts import Verdict, equivalence, mean_within, rms_equivalence
from .analytic import analytic_alignment
from .coarse_to_fine import CoarseModel, coarse_model, coarse_to_fine, split_record
from .compass_loop import CompassLoopDesign, compass_loop_alignment
from .fine import FilterTuning, filter_model, fine_alignment
from .imu import ImuRecord, Scenario, SensorErrors, simulate_imu
from .inertial import inertial_alignment
from .theory import analytic_gain_values
from .tilt_attitude import attitude_matrix

__all__ = ["METHODS", "FLOOR_MARGIN", "TrialSummary", "summarise", "trial_floors", "floor_reached", "MethodRow", "MethodComparison", "ComparisonKernel", "compare_methods"]

METHODS = ("analytic", "inertial", "kalman", "coarse-to-fine", "compass")
_FILTERS = ("kalman", "coarse-to-fine")
#: A method has reached its trials' floor when the rms of its error above the floor is at most this
#: multiple of the floor's rms: the floor then makes at least half of the mean-square error.
FLOOR_MARGIN = 1.0


@dataclass(frozen=True)
class TrialSummary:
    """Mean and rms of one value per trial, with their 95 % intervals.

    Attributes
    ----------
    n : int
        Trials.
    mean : float
        Sample mean.
    mean_ci : tuple of float
        95 % interval of the mean (normal, from the sample standard deviation).
    rms : float
        ``√(mean of squares)``.
    rms_ci : tuple of float
        ``√`` of the 95 % interval of the mean square.
    std : float
        Sample standard deviation.
    ms_std_error : float
        Standard error of the mean square (from the per-trial squares), for
        verdicts on the rms (:func:`strapdown.analysis.core.verdicts.mean_square_within`).
    """

    n: int
    mean: float
    mean_ci: tuple
    rms: float
    rms_ci: tuple
    std: float
    ms_std_error: float = math.nan

    def rms_agrees(self, reference: float, relative_margin: float, *, what: str = "the reference", level: float = 0.95) -> Verdict:
        """Is the rms within ``relative_margin`` of ``reference``? (TOST on the mean square, :func:`~strapdown.analysis.core.verdicts.rms_equivalence`.)

        Parameters
        ----------
        reference : float
            The rms it should equal [its units].
        relative_margin : float
            The margin as a fraction of ``reference``, in (0, 1).
        what : str, keyword-only
            The reference's name in the criterion.
        level : float, keyword-only
            Confidence of the two-sided interval.

        Returns
        -------
        Verdict
        """
        text = f"rms within ±{relative_margin:.0%} of {what} (TOST, {level:.0%})"
        return rms_equivalence(self.rms**2, self.ms_std_error, self.n, reference=reference, relative_margin=relative_margin, criterion=text, level=level)

    def mean_agrees(self, reference: float, margin: float, *, what: str = "the reference", level: float = 0.95) -> Verdict:
        """Is the mean within ``±margin`` of ``reference``? (TOST, :func:`~strapdown.analysis.core.verdicts.equivalence`.)

        Parameters
        ----------
        reference : float
            The value it should equal [its units].
        margin : float
            The equivalence margin, > 0 [its units].
        what : str, keyword-only
            The reference's name in the criterion.
        level : float, keyword-only
            Confidence of the two-sided interval.

        Returns
        -------
        Verdict
        """
        text = f"mean within ±{margin:.3g} of {what} (TOST, {level:.0%})"
        return equivalence(self.mean, self.std / math.sqrt(self.n), self.n, reference=reference, margin=margin, criterion=text, level=level)


def summarise(values) -> TrialSummary:
    """Mean and rms of independent per-trial values with their 95 % intervals.

    Parameters
    ----------
    values : array_like
        ``(n,)`` one value per trial, n ≥ 2.

    Returns
    -------
    TrialSummary

    >>> s = summarise([1.0, -1.0, 1.0, -1.0])
    >>> s.mean, s.rms, s.rms_ci
    (0.0, 1.0, (1.0, 1.0))
    """
    x = np.asarray(values, dtype=float).ravel()
    n = x.size
    if n < 2:
        raise ValueError(f"Expected `values` of at least 2 trials, got {n}")
    m, s = float(x.mean()), float(x.std(ddof=1))
    sq = x * x
    mse, se_mse = float(sq.mean()), float(sq.std(ddof=1)) / math.sqrt(n)
    z = montecarlo.Z95
    lo, hi = max(mse - z * se_mse, 0.0), mse + z * se_mse
    return TrialSummary(n, m, (m - z * s / math.sqrt(n), m + z * s / math.sqrt(n)), math.sqrt(mse), (math.sqrt(lo), math.sqrt(hi)), s, se_mse)


def trial_floors(scenario: Scenario, gyro_bias, accel_bias) -> np.ndarray:
    """The azimuth error each trial's biases leave at rest: ``G_ω b_g + G_a b_a`` at the stable attitude [rad].

    Parameters
    ----------
    scenario : Scenario
        Latitude and stable attitude.
    gyro_bias : array_like
        ``(n, 3)`` gyro biases of the trials, body axes [rad/s].
    accel_bias : array_like
        ``(n, 3)`` accelerometer biases [m/s²].

    Returns
    -------
    ndarray
        ``(n,)``; at zero heading and tilt ``−ε_E/(Ω cos φ) + tan φ ∇_E/g``.
    """
    G = analytic_gain_values(scenario, "levelled")
    return np.asarray(gyro_bias, dtype=float) @ G.G_omega + np.asarray(accel_bias, dtype=float) @ G.G_accel


def floor_reached(error, floor, *, margin: float = FLOOR_MARGIN, level: float = 0.95, what: str = "the floor") -> Verdict:
    """Has a method reached its trials' floor? The rms of its residual over the floor against ``margin`` × the floor's rms.

    A residual whose *mean* is zero proves nothing: a method that has not
    begun to align has a residual of mean zero and an rms of its prior.  The
    floor is reached when what the method leaves above it is small against
    the floor itself, ``rms(e − f) ≤ κ·rms(f)``.  Both sides come from the
    same trials, so the test is on the per-trial differences
    ``d = (e − f)² − κ² f²`` (whose mean is ``rms(e − f)² − κ² rms(f)²``):
    "yes" when the interval of their mean lies below 0, "no" when it lies
    above, else "not resolved" with the trials needed
    (:func:`strapdown.analysis.core.verdicts.mean_within`).

    Parameters
    ----------
    error : array_like
        ``(n,)`` the method's azimuth error per trial [rad].
    floor : array_like
        ``(n,)`` the trial's floor [rad].
    margin : float, keyword-only
        κ > 0, the largest residual rms as a multiple of the floor rms
        (default :data:`FLOOR_MARGIN`).
    level : float, keyword-only
        Confidence of the two-sided interval (each one-sided test at (1 − level)/2).
    what : str, keyword-only
        The floor's name in the criterion.

    Returns
    -------
    Verdict
        Its ``estimate`` and ``interval`` are the mean of ``d`` [rad²].

    Raises
    ------
    ValueError
        For arrays of different sizes or fewer than 2 trials.

    >>> import numpy as np
    >>> f = np.linspace(-1.0, 1.0, 50)
    >>> floor_reached(f + 0.1 * np.cos(np.arange(50)), f).outcome
    'yes'
    >>> floor_reached(f + 3.0 * np.cos(np.arange(50)), f).outcome
    'no'
    """
    e = as_array(error, "error").ravel()
    f = as_array(floor, "floor").ravel()
    if e.size != f.size:
        raise ValueError(f"Expected `error` and `floor` of the same trials, got {e.size} and {f.size} values")
    k = positive(margin, "margin")
    d = (e - f) ** 2 - k * k * f * f
    text = f"{what} reached: rms of the error above it at most {k:g} × its rms (one-sided, {level:.0%} interval of the paired mean square)"
    return mean_within(d, high=0.0, criterion=text, margin=k, level=level)


@dataclass(frozen=True)
class ComparisonKernel:
    """Monte Carlo kernel: every method on each record of a block; one row per trial.

    Parameters
    ----------
    scenario : Scenario
        The configuration (its duration is the whole alignment).
    errors : SensorErrors
        The sensors.
    methods : tuple of str
        Methods to run, from :data:`METHODS`.
    tuning : FilterTuning
        The filter of ``kalman`` and ``coarse-to-fine``.
    coarse : CoarseModel or None
        The coarse stage of ``coarse-to-fine`` and ``compass``.
    compass : CompassLoopDesign
        The compass loop.
    check_epochs : tuple of int
        Epochs of the filters whose NEES and NIS are returned (counted from the filter's start).
    chunk : int
        Trials simulated at once (memory).

    Notes
    -----
    A row holds the trial's floor, then per method its azimuth error, then per
    filter its NEES and NIS at ``check_epochs``.
    """

    scenario: Scenario
    errors: SensorErrors
    methods: tuple
    tuning: FilterTuning
    coarse: CoarseModel | None
    compass: CompassLoopDesign
    check_epochs: tuple
    chunk: int = 32

    def __call__(self, n_trials: int, rng) -> np.ndarray:
        M = filter_model(self.scenario, self.tuning).samples_per_epoch
        rows = []
        left = int(n_trials)
        while left > 0:
            k = min(self.chunk, left)
            rec = simulate_imu(self.scenario, self.errors, n_trials=k, rng=rng, truth_stride=M)
            rows.append(self._rows(rec, rng))
            left -= k
        return np.concatenate(rows)

    def _rows(self, rec: ImuRecord, rng) -> np.ndarray:
        cols = [trial_floors(self.scenario, rec.gyro_bias, rec.accel_bias)[:, None]]
        idx = list(self.check_epochs)
        scores = []
        C_coarse = None
        for m in self.methods:
            if m == "analytic":
                cols.append(analytic_alignment(rec).heading_error[:, None])
            elif m == "inertial":
                cols.append(inertial_alignment(rec).heading_error[:, None])
            elif m == "kalman":
                res = fine_alignment(rec, self.tuning, rng=rng)
                cols.append(res.estimate.heading_error[:, None])
                scores += [res.nees[:, idx], res.nis[:, idx]]
            elif m == "coarse-to-fine":
                res = coarse_to_fine(rec, self.tuning, self.coarse, rng=rng)
                C_coarse = attitude_matrix(np.stack([res.coarse.heading, res.coarse.beta, res.coarse.gamma], axis=-1))
                cols.append(res.fine.estimate.heading_error[:, None])
                scores += [res.fine.nees[:, idx], res.fine.nis[:, idx]]
            elif m == "compass":
                head, tail = split_record(rec, int(round(self.coarse.duration / self.scenario.dt)))
                if C_coarse is None:
                    e = inertial_alignment(head, epoch=self.coarse.epoch, observation=self.coarse.observation)
                    C_coarse = attitude_matrix(np.stack([e.heading, e.beta, e.gamma], axis=-1))
                cols.append(compass_loop_alignment(tail, self.compass, initial_attitude=C_coarse).estimate.heading_error[:, None])
        return np.concatenate(cols + scores, axis=1)


@dataclass(frozen=True)
class MethodRow:
    """One method of a comparison.

    Attributes
    ----------
    method : str
        The method.
    error : TrialSummary
        Its azimuth error [rad].
    residual : TrialSummary
        Its azimuth error minus the trial's floor [rad].
    floor_reached : Verdict or None
        Whether the floor is reached (:func:`floor_reached`).
    nees, nis : ndarray or None
        Filters: mean NEES and NIS over trials at the check times.
    nees_band, nis_band : tuple or None
        Their bands, each at ``1 − 0.05/(2K)`` for K check epochs, so that a
        consistent filter has all 2K means inside at 95 % together (Bonferroni).
    dim : int or None
        Filters: state dimension.
    """

    method: str
    error: TrialSummary
    residual: TrialSummary
    floor_reached: Verdict | None = None
    nees: np.ndarray | None = None
    nis: np.ndarray | None = None
    nees_band: tuple | None = None
    nis_band: tuple | None = None
    dim: int | None = None

    @property
    def consistent(self) -> bool | None:
        """Filters: every mean NEES and NIS inside its band, a test at 95 % for the whole family of checks (None for the other methods)."""
        if self.nees is None:
            return None
        inside = lambda x, b: bool(np.all((x >= b[0]) & (x <= b[1])))  # noqa: E731
        return inside(self.nees, self.nees_band) and inside(self.nis, self.nis_band)


@dataclass(frozen=True)
class MethodComparison:
    """The methods of one scenario on the same trials.

    Attributes
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors
        The sensors.
    n_trials : int
        Trials.
    floor : TrialSummary
        The trials' floors [rad].
    rows : tuple of MethodRow
        One per method, in the order asked.
    check_times : ndarray
        Filters: the times of the NEES and NIS checks, from the filter's start [s].
    coarse : CoarseModel or None
        The coarse stage.
    """

    scenario: Scenario
    errors: SensorErrors
    n_trials: int
    floor: TrialSummary
    rows: tuple
    check_times: np.ndarray
    coarse: CoarseModel | None

    def row(self, method: str) -> MethodRow:
        """The row of ``method``.

        Parameters
        ----------
        method : str
            A method of the comparison.

        Returns
        -------
        MethodRow
        """
        for r in self.rows:
            if r.method == method:
                return r
        raise ValueError(f"Expected `method` among {[r.method for r in self.rows]}, got {method!r}")


def compare_methods(
    scenario: Scenario,
    errors: SensorErrors,
    *,
    n_trials: int,
    rng=None,
    methods=METHODS,
    tuning: FilterTuning | None = None,
    coarse_duration: float = 60.0,
    compass: CompassLoopDesign | None = None,
    calibration_trials: int = 64,
    trials_per_block: int = 32,
    executor=None,
    limits: budget.Limits | None = None,
) -> MethodComparison:
    """Run the methods on the same ``n_trials`` records and compare each with the trials' floors.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking, sampling and the whole alignment time.
    errors : SensorErrors
        The sensors.
    n_trials : int, keyword-only
        Trials, at least 2.
    rng : Generator | SeedSequence | int | None, keyword-only
        Root seed: child 0 calibrates the coarse stage, child 1 roots the trial blocks.
    methods : sequence of str, keyword-only
        From :data:`METHODS`.
    tuning : FilterTuning, optional, keyword-only
        The filter (default: one that knows the sensors, 0.5 s epochs).
    coarse_duration : float, keyword-only
        T_c of ``coarse-to-fine`` and ``compass`` [s].
    compass : CompassLoopDesign, optional, keyword-only
        The compass loop (default :class:`CompassLoopDesign` at the filter's epoch).
    calibration_trials : int, keyword-only
        Trials calibrating the coarse stage's noise covariance.
    trials_per_block : int, keyword-only
        Trials per block (the unit of randomness).
    executor : Executor | dask Client | None, keyword-only
        Where blocks run (the result does not depend on it).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time, on one core (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    MethodComparison

    Raises
    ------
    ValueError
        For an unknown method, or trials beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``n_trials``
        and the scenario's ``duration``).
    """
    methods = tuple(methods)
    unknown = [m for m in methods if m not in METHODS]
    if unknown or not methods:
        raise ValueError(f"Expected `methods` among {METHODS}, got {list(methods)}")
    n = as_int(n_trials, "n_trials", minimum=2)
    per_block = min(as_int(trials_per_block, "trials_per_block", minimum=1), n)
    root = montecarlo.root_seed_sequence(rng)
    cal_seed, trial_seed = montecarlo.block_seed(root, 0), montecarlo.block_seed(root, 1)
    if tuning is None:
        tuning = FilterTuning(
            epoch=0.5, gyro_bias=max(errors.gyro_bias_sigma, 1e-12), accel_bias=max(errors.accel_bias_sigma, 1e-12), gyro_noise=errors.gyro_noise, accel_noise=errors.accel_noise
        )
    compass = CompassLoopDesign(epoch=tuning.epoch) if compass is None else compass
    N = scenario.n_samples
    what = f"`n_trials` = {n:.3g} trials of {N:.3g} samples, {len(methods)} methods (`duration` = {scenario.duration:.3g} s of the scenario)"
    # every method is costed as the Kalman filter at the filter's epochs, the slowest (an upper bound)
    one = budget.alignment_monte_carlo(n, N, method="kalman", epochs=N / max(1, round(tuning.epoch / scenario.dt)), per_block=per_block, what=what)
    budget.check(budget.Estimate(len(methods) * one.seconds, one.memory + 500.0 * (-(-n // per_block)), what), limits)  # and one task per block
    coarse = None
    if {"coarse-to-fine", "compass"} & set(methods):
        coarse = coarse_model(scenario, errors, coarse_duration=coarse_duration, n_trials=calibration_trials, rng=cal_seed)
    model = filter_model(scenario, tuning)
    E_total = scenario.n_samples // model.samples_per_epoch
    E_fine = E_total - (int(round(coarse_duration / model.epoch)) if coarse is not None else 0)
    E_check = E_fine if "coarse-to-fine" in methods else E_total
    checks = tuple(int(x) for x in np.unique(np.round(np.geomspace(1, E_check, 6)).astype(int)) - 1)
    kernel = ComparisonKernel(scenario, errors, methods, tuning, coarse, compass, checks)
    rows = montecarlo.collect(kernel, n, rng=trial_seed, trials_per_block=per_block, blocks_per_chunk=1, executor=executor)
    floor = rows[:, 0]
    out = []
    k = len(checks)
    band_level = 1.0 - 0.05 / (2 * k)  # Bonferroni: all 2k checks of a consistent filter inside at 95 % together
    j = 1 + len(methods)
    for i, m in enumerate(methods):
        e = rows[:, 1 + i]
        extra = {}
        if m in _FILTERS:
            extra = dict(nees=rows[:, j : j + k].mean(axis=0), nis=rows[:, j + k : j + 2 * k].mean(axis=0), dim=model.dim)
            extra.update(nees_band=kalman.chi2_band(model.dim, n, band_level), nis_band=kalman.chi2_band(3, n, band_level))
            j += 2 * k
        out.append(MethodRow(m, summarise(e), summarise(e - floor), floor_reached(e, floor), **extra))
    return MethodComparison(scenario, errors, n, summarise(floor), tuple(out), model.epoch * (np.asarray(checks) + 1), coarse)
