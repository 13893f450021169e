"""Monte Carlo of the section-5 cascade over sensor errors: percentiles of the peak errors per stage.

Each trial draws the sensor errors of both triads — bias signs and sizes,
scale factors, and white noise as angle and velocity random walk
(:class:`SensorErrorStatistics`) — adds them to one ideal record of the truth
(:func:`strapdown.analysis.multistage.sensors.corrupt`), runs the cascade and
keeps the peak yaw, pitch, roll and tilt errors of every stage (in one
compiled pass per trial that forms the peaks without keeping the series,
:func:`strapdown.analysis.multistage.stages.multistage_peaks`).  The trials
are grouped into blocks seeded from the spawn keys of one root
:class:`numpy.random.SeedSequence` (:func:`strapdown.analysis.core.montecarlo.collect`,
the seeding of the azimuth Monte Carlo), so the peaks are bit-identical for
any chunking and any number of workers.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...derivations.multistage.published import SECTION5
from ..core import budget, montecarlo
from ..core.validation import as_int, nonnegative, positive
from .sensors import SensorData, SensorErrors, corrupt
from .stage_recursion import bound_terms
from .stages import ENGINES, Stage, multistage_peaks, plotnikov_1999_stages
from .trajectory import Scenario, sample

__all__ = ["DISTRIBUTIONS", "SensorErrorStatistics", "PeakErrorKernel", "PeakStatistics", "sensor_error_monte_carlo"]

#: How a bias or scale factor is drawn from its size s: ``"normal"`` N(0, s²); ``"signs"`` ±s with equal odds.
DISTRIBUTIONS = ("normal", "signs")

#: Order of the per-trial columns: for each stage, these four peaks.
_QUANTITIES = ("yaw", "pitch", "roll", "tilt")


@dataclass(frozen=True)
class SensorErrorStatistics:
    """Statistics of the sensor errors, per axis (independent axes).

    The sizes default to those printed in Plotnikov (1999), section 5
    (:data:`strapdown.derivations.multistage.published.SECTION5`).

    Parameters
    ----------
    gyro_drift : float
        Size of the gyro bias [rad/s], >= 0.
    accel_bias : float
        Size of the accelerometer bias [m/s²], >= 0.
    gyro_scale : float
        Size of the gyro scale-factor error [-], >= 0.
    accel_scale : float
        Size of the accelerometer scale-factor error [-], >= 0.
    gyro_noise : float
        Angle random walk [rad/√s], >= 0 (every trial).
    accel_noise : float
        Velocity random walk [m/s/√s], >= 0 (every trial).
    distribution : {"normal", "signs"}
        How biases and scale factors are drawn from their sizes.

    Examples
    --------
    >>> e = SensorErrorStatistics(distribution="signs").draw(np.random.default_rng(1))
    >>> [abs(b) for b in e.accel_bias]
    [0.001, 0.001, 0.001]
    """

    gyro_drift: float = SECTION5.gyro_drift
    accel_bias: float = SECTION5.accel_bias
    gyro_scale: float = SECTION5.scale_factor_error
    accel_scale: float = SECTION5.scale_factor_error
    gyro_noise: float = 0.0
    accel_noise: float = 0.0
    distribution: str = "normal"

    def __post_init__(self):
        for name in ("gyro_drift", "accel_bias", "gyro_scale", "accel_scale", "gyro_noise", "accel_noise"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        if self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"Expected `distribution` in {DISTRIBUTIONS}, got {self.distribution!r}")

    @classmethod
    def plotnikov_1999(cls, *, gyro_noise: float = 2.9e-7, accel_noise: float = 1e-4, distribution: str = "signs") -> SensorErrorStatistics:
        """The sizes of Plotnikov (1999), section 5, with random signs, and a navigation-grade noise.

        The paper gives no noise; the defaults are an angle random walk of
        0.001 deg/√h (2.9·10⁻⁷ rad/√s) and a velocity random walk of 10 µg/√Hz
        (10⁻⁴ m/s/√s), typical of sensors whose drift is 0.01 deg/h.

        Parameters
        ----------
        gyro_noise : float
            Angle random walk [rad/√s].
        accel_noise : float
            Velocity random walk [m/s/√s].
        distribution : {"normal", "signs"}
            How biases and scale factors are drawn.

        Returns
        -------
        SensorErrorStatistics
        """
        return cls(SECTION5.gyro_drift, SECTION5.accel_bias, SECTION5.scale_factor_error, SECTION5.scale_factor_error, gyro_noise, accel_noise, distribution)

    def draw(self, rng=None) -> SensorErrors:
        """One draw of the sensor errors.

        Parameters
        ----------
        rng : numpy.random.Generator, int or None
            Source of the draw (12 numbers, in a fixed order); a Generator is
            used as it is, a seed or None (fresh entropy) makes one.

        Returns
        -------
        SensorErrors
        """
        rng = np.random.default_rng(rng)
        if self.distribution == "normal":
            u = rng.standard_normal(12)
        else:
            u = np.where(rng.random(12) < 0.5, -1.0, 1.0)
        return SensorErrors(
            gyro_scale=tuple(self.gyro_scale * u[0:3]),
            gyro_drift=tuple(self.gyro_drift * u[3:6]),
            gyro_noise=self.gyro_noise,
            accel_scale=tuple(self.accel_scale * u[6:9]),
            accel_bias=tuple(self.accel_bias * u[9:12]),
            accel_noise=self.accel_noise,
        )


@dataclass(frozen=True)
class PeakErrorKernel:
    """Monte Carlo kernel: peak errors of the cascade for ``n`` draws of the sensor errors.

    Parameters
    ----------
    ideal : SensorData
        The ideal record (no sensor errors).
    stages : tuple of Stage
        The cascade.
    statistics : SensorErrorStatistics
        What to draw.
    engine : {"compiled", "python"}
        Implementation of the cascade (:func:`strapdown.analysis.multistage.stages.multistage_peaks`).
    """

    ideal: SensorData
    stages: tuple
    statistics: SensorErrorStatistics
    engine: str = "compiled"

    def __call__(self, n_trials: int, rng) -> np.ndarray:
        """Peaks of ``n_trials`` trials.

        Parameters
        ----------
        n_trials : int
            Trials of this block.
        rng : numpy.random.Generator
            The block's generator; each trial gets a spawned child (errors, then noise).

        Returns
        -------
        ndarray, shape (n_trials, 4 m)
            (yaw, pitch, roll, tilt) peaks of stage 1, then stage 2, … [rad].
        """
        out = np.empty((n_trials, 4 * len(self.stages)))
        # every trial has the truth of the ideal record: the true attitude's terms of the peak bounds once per block
        terms = bound_terms(self.ideal.attitude, self.ideal.angles) if self.engine == "compiled" else None
        for i, trial in enumerate(rng.spawn(n_trials)):
            errors = self.statistics.draw(trial)
            out[i] = multistage_peaks(corrupt(self.ideal, errors, rng=trial), self.stages, engine=self.engine, terms=terms).ravel()
        return out


@dataclass(frozen=True)
class PeakStatistics:
    """Result of :func:`sensor_error_monte_carlo`.

    Attributes
    ----------
    peaks : ndarray, shape (n_trials, m, 4)
        Per trial, stage and quantity (yaw, pitch, roll, tilt) [rad].
    levels : tuple of float
        Percentile levels [%].
    percentiles : ndarray, shape (len(levels), m, 4)
        Percentiles of ``peaks`` over the trials [rad].
    nominal : ndarray, shape (m, 4)
        Peaks without any sensor error [rad].
    statistics : SensorErrorStatistics
        What was drawn.
    seed_entropy : int
        Entropy of the root SeedSequence (to reproduce the run).
    """

    peaks: np.ndarray
    levels: tuple
    percentiles: np.ndarray
    nominal: np.ndarray
    statistics: SensorErrorStatistics
    seed_entropy: int

    def spread(self, stage: int | None = None) -> float:
        """Largest distance of a percentile of the yaw, pitch or roll peak from the error-free run [rad].

        Parameters
        ----------
        stage : int, optional
            Stage number, 1-based; default the last stage.

        Returns
        -------
        float
            ``max |percentile − nominal|`` over the levels and the three angles.
        """
        s = self.nominal.shape[0] - 1 if stage is None else as_int(stage, "stage", minimum=1) - 1
        if s >= self.nominal.shape[0]:
            raise ValueError(f"Expected `stage` in 1..{self.nominal.shape[0]}, got {s + 1}")
        return float(np.abs(self.percentiles[:, s, :3] - self.nominal[s, :3]).max())

    def percentile(self, level: float, stage: int, quantity: str) -> float:
        """One percentile [rad].

        Parameters
        ----------
        level : float
            One of :attr:`levels` [%].
        stage : int
            Stage number, 1-based.
        quantity : {"yaw", "pitch", "roll", "tilt"}
            Which peak.

        Returns
        -------
        float
        """
        if level not in self.levels:
            raise ValueError(f"Expected `level` among {self.levels}, got {level!r}")
        if quantity not in _QUANTITIES:
            raise ValueError(f"Expected `quantity` in {_QUANTITIES}, got {quantity!r}")
        return float(self.percentiles[self.levels.index(level), stage - 1, _QUANTITIES.index(quantity)])


def sensor_error_monte_carlo(
    statistics: SensorErrorStatistics | None = None,
    n_trials: int = 200,
    *,
    scenario: Scenario | None = None,
    stages=None,
    step: float = 0.2,
    levels=(5.0, 50.0, 95.0, 99.0),
    rng=None,
    trials_per_block: int = 8,
    blocks_per_chunk: int = 4,
    executor=None,
    progress: bool = False,
    engine: str = "compiled",
    limits: budget.Limits | None = None,
) -> PeakStatistics:
    """Percentiles of the peak errors of each stage over random sensor errors.

    Parameters
    ----------
    statistics : SensorErrorStatistics, optional
        Default :meth:`SensorErrorStatistics.plotnikov_1999`.
    n_trials : int
        Number of trials, at least 2.
    scenario : Scenario, optional
        The motion (its own ``sensors`` are ignored); default section 5.
    stages : sequence of Stage, optional
        Default :func:`strapdown.analysis.multistage.stages.plotnikov_1999_stages`.
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    levels : sequence of float
        Percentile levels in [0, 100].
    rng : Generator | SeedSequence | int | None
        Root of the random streams.
    trials_per_block : int
        Trials per block (the unit of randomness).
    blocks_per_chunk : int
        Blocks per work item (does not change the result).
    executor : Executor | dask Client | None
        Where chunks run (does not change the result).
    progress : bool
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    engine : {"compiled", "python"}
        Implementation of the cascade: one compiled pass per trial, or the
        reference (plain-Python stage recursion, numpy in between); the two
        agree to round-off.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one
        core); a request beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    PeakStatistics

    Raises
    ------
    ValueError
        For ``n_trials < 2``, bad levels, a bad step, an unknown engine, or
        work beyond ``limits`` (naming ``n_trials``).
    """
    stats = SensorErrorStatistics.plotnikov_1999() if statistics is None else statistics
    if not isinstance(stats, SensorErrorStatistics):
        raise TypeError(f"Expected `statistics` to be a SensorErrorStatistics, got {type(stats).__name__}")
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    positive(step, "step")
    if engine not in ENGINES:
        raise ValueError(f"Expected `engine` in {ENGINES}, got {engine!r}")
    levels = tuple(float(v) for v in levels)
    if not levels or any(not 0.0 <= v <= 100.0 for v in levels):
        raise ValueError(f"Expected `levels` in [0, 100], got {levels}")
    sc = Scenario() if scenario is None else scenario
    steps = sc.duration / float(step)
    what = f"`n_trials` = {n_trials:.3g} runs of {steps:.3g} steps (`step` = {float(step):g} s)"
    runs = budget.multistage(float(n_trials + 1) * steps, what=what)  # the time of every run
    held = budget.multistage((as_int(trials_per_block, "trials_per_block", minimum=1) + 1.0) * steps, what=what)  # the memory of one block
    budget.check(budget.Estimate(runs.seconds, held.memory, what), limits)
    clean = replace(sc, sensors=SensorErrors())
    stages = tuple(plotnikov_1999_stages(sc.gravity, sc.earth_radius) if stages is None else stages)
    if not stages or not all(isinstance(s, Stage) for s in stages):
        raise TypeError("Expected `stages` to be a non-empty sequence of Stage")
    ideal = sample(clean, step)
    root = montecarlo.root_seed_sequence(rng)
    kernel = PeakErrorKernel(ideal, stages, stats, engine)
    rows = montecarlo.collect(kernel, n_trials, rng=root, trials_per_block=trials_per_block, blocks_per_chunk=blocks_per_chunk, executor=executor, progress=progress)
    peaks = rows.reshape(n_trials, len(stages), 4)
    nominal = multistage_peaks(ideal, stages, engine=engine)
    pct = np.percentile(peaks, levels, axis=0)
    entropy = root.entropy if isinstance(root.entropy, int) else int(np.asarray(root.entropy).ravel()[0])
    return PeakStatistics(peaks, levels, pct, nominal, stats, entropy)
