"""Monte Carlo of self-alignment on a rocking base: the three methods against their theory.

One trial is one rocking record (its phases or Gaussian amplitudes, random
biases, noise, quantisation residues and, for the Kalman filter, the initial
attitude error drawn from the filter's prior).  Trials run in blocks through
:func:`strapdown.analysis.core.montecarlo.run`, block ``i`` from the ``i``-th
child of the root SeedSequence, so the statistics are bit-identical for any
chunking, number of workers or executor.  Within a block every method is
vectorised over trials; the Kalman filter loops over epochs only, with gains
computed once by filterpy.

The result carries the theory that applies to the method:

``analytic``
    :func:`strapdown.analysis.alignment.theory.analytic_theory`,
    term by term;
``inertial``
    the first-order bias floors (:func:`strapdown.analysis.alignment.theory.bias_floor`);
``kalman``
    the bias floors, the linear filter's own response to the fixed biases and
    its posterior standard deviation
    (:func:`strapdown.analysis.alignment.theory.kalman_theory`),
    with the NEES and NIS averaged over trials at a few epochs against their χ²
    bands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core import budget, kalman, montecarlo
from ..core.validation import as_int
from ..core.verdicts import Verdict, all_of, in_band
from ..gyrocompass.rocking import as_generator
from .analytic import analytic_alignment
from .fine import FilterDraws, FilterTuning, draw_filter, filter_model, fine_alignment, simulate_epoch_record
from .imu import Scenario, SensorErrors, draw_imu, simulate_imu
from .inertial import inertial_alignment
from .theory import AnalyticTheory, KalmanTheory, analytic_theory, bias_floor, kalman_theory

__all__ = ["METHODS", "AlignmentOptions", "AlignmentKernel", "AlignmentDraws", "alignment_draws", "KalmanConsistency", "AlignmentMonteCarlo", "alignment_monte_carlo"]

METHODS = ("analytic", "inertial", "kalman")

#: Trial-samples the Monte Carlo kernel simulates at once (memory): its chunks of draws are merged up to this size.
SIMULATED_AT_ONCE = 1 << 18


@dataclass(frozen=True)
class AlignmentOptions:
    """Options of the three methods.

    Parameters
    ----------
    formula : str
        Analytic: ``"levelled"`` or ``"paper"``.
    observation : str
        Inertial: ``"position"`` or ``"velocity"``.
    inertial_epoch : float
        Inertial: spacing of the vector observations [s].
    tuning : FilterTuning
        Kalman: what the filter assumes.
    velocity_noise : float or None
        Kalman: true noise of the zero-velocity reference [m/s] (None: the tuning's).
    """

    formula: str = "levelled"
    observation: str = "position"
    inertial_epoch: float = 1.0
    tuning: FilterTuning = field(default_factory=FilterTuning)
    velocity_noise: float | None = None


@dataclass(frozen=True)
class AlignmentKernel:
    """Monte Carlo kernel: the azimuth errors of one block of trials.

    Parameters
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors
        Sensor errors.
    method : str
        ``"analytic"``, ``"inertial"`` or ``"kalman"``.
    options : AlignmentOptions
        Method options.
    check_epochs : tuple of int
        Kalman: epochs whose NEES and NIS are returned.
    sequence : object
        Kalman: the filter's gains and covariances (computed once).
    chunk : int
        Trials drawn at once (the unit in which the random stream is consumed);
        consecutive chunks are simulated together up to :data:`SIMULATED_AT_ONCE`
        trial-samples (memory), which does not change a trial.
    model : FineAlignmentModel or None
        Kalman: ``filter_model(scenario, options.tuning)``, computed once (None: at each call).
    score : bool
        Kalman: score the filter (NEES, NIS); False: those columns of ``aux``
        are NaN, and the records carry their truth at the start and the end only.

    Notes
    -----
    Returns ``(errors, aux)``: the azimuth error ``(n, 1)`` [rad] and per trial
    the squared tilt errors, then (Kalman) the NEES and NIS at ``check_epochs``
    and the NIS averaged over all epochs (NaN without ``score``).
    """

    scenario: Scenario
    errors: SensorErrors
    method: str
    options: AlignmentOptions
    check_epochs: tuple = ()
    sequence: object = None
    chunk: int = 32
    model: object = None
    score: bool = True

    def _model(self):
        return filter_model(self.scenario, self.options.tuning) if self.model is None else self.model

    def draw(self, n_trials: int, rng) -> AlignmentDraws:
        """The random numbers of ``n_trials`` trials, in the order :meth:`__call__` consumes them.

        Parameters
        ----------
        n_trials : int
            Trials.
        rng : Generator | SeedSequence | int | None
            Random stream.

        Returns
        -------
        AlignmentDraws
        """
        g = as_generator(rng)
        # consecutive chunks drawn as one draw and simulated at once (a trial's record does not depend on its neighbours)
        n = as_int(n_trials, "n_trials", minimum=1)
        group = self.chunk * max(1, SIMULATED_AT_ONCE // ((self.scenario.n_samples + 1) * self.chunk))
        imu = tuple(draw_imu(self.scenario, self.errors, n_trials=min(group, n - k), rng=g, chunk=self.chunk) for k in range(0, n, group))
        filt = None
        if self.method == "kalman":
            filt = draw_filter(n_trials, self.scenario.n_samples // self._model().samples_per_epoch, g)
        return AlignmentDraws(imu, filt)

    def evaluate(self, draws: AlignmentDraws):
        """Errors and side quantities of the trials of ``draws`` (see Notes).

        Parameters
        ----------
        draws : AlignmentDraws
            From :meth:`draw` of a kernel whose scenario differs from this one at most by the rocking amplitudes.

        Returns
        -------
        tuple of ndarray
            ``(errors, aux)``.
        """
        if self.method == "kalman":
            model = self._model()
            truth = "epochs" if self.score else "ends"  # unscored: the truth at the start and the end suffices
            rec = draws.epoch_record(self.scenario, self.errors, model.samples_per_epoch, truth)
            res = fine_alignment(rec, self.options.tuning, draws=draws.filter, velocity_noise=self.options.velocity_noise, sequence=self.sequence, model=model, score=self.score)
            est = res.estimate
            idx = list(self.check_epochs)
            aux = [est.tilt_error**2, res.nees[:, idx], res.nis[:, idx], res.nis.mean(axis=1, keepdims=True)]
            return est.heading_error[:, None], np.concatenate(aux, axis=1)
        parts = []
        for d in draws.imu:
            rec = simulate_imu(self.scenario, self.errors, draws=d)
            if self.method == "analytic":
                parts.append(analytic_alignment(rec, formula=self.options.formula))
            else:
                parts.append(inertial_alignment(rec, epoch=self.options.inertial_epoch, observation=self.options.observation))
        e = np.concatenate([p.heading_error for p in parts])
        t = np.concatenate([p.tilt_error for p in parts])
        return e[:, None], t**2

    def __call__(self, n_trials: int, rng):
        return self.evaluate(self.draw(n_trials, rng))


class AlignmentDraws:
    """The random numbers of a block of alignment trials: common random numbers passed explicitly.

    The same draws evaluated by kernels whose scenarios differ by the rocking
    amplitudes (a search over the amplitude) or whose filters differ (a
    comparison of filters) give the same trials.  The epoch records the filter
    reads are made once per scenario and kept with the draws.

    Parameters
    ----------
    imu : tuple of ImuDraws
        The sensor records' numbers, in groups of trials simulated at once.
    filter : FilterDraws or None
        The Kalman filter's numbers.
    """

    def __init__(self, imu: tuple, filter: FilterDraws | None = None):
        self.imu, self.filter = tuple(imu), filter
        self._records: dict = {}

    @property
    def n_trials(self) -> int:
        """Trials."""
        return sum(d.n_trials for d in self.imu)

    def epoch_record(self, scenario: Scenario, errors: SensorErrors, samples_per_epoch: int, truth: str):
        """The epoch record of these trials in ``scenario`` (made once, kept with the draws).

        Parameters
        ----------
        scenario : Scenario
            The configuration (its rocking amplitudes may differ from the drawn ones).
        errors : SensorErrors
            Sensor errors.
        samples_per_epoch : int
            M.
        truth : str
            ``"epochs"`` or ``"ends"``.

        Returns
        -------
        EpochRecord
        """
        import hashlib
        import pickle

        key = hashlib.blake2b(pickle.dumps((scenario, errors, int(samples_per_epoch), truth), protocol=5), digest_size=16).digest()
        if key not in self._records:
            self._records[key] = simulate_epoch_record(scenario, errors, samples_per_epoch, draws=self.imu, truth=truth)
        return self._records[key]


@dataclass(frozen=True)
class KalmanConsistency:
    """NEES and NIS of the fine-alignment filter averaged over trials.

    Attributes
    ----------
    times : ndarray
        ``(K,)`` epoch ends checked [s].
    nees : ndarray
        ``(K,)`` mean NEES.
    nis : ndarray
        ``(K,)`` mean NIS.
    nis_all : float
        Mean NIS over all epochs and trials.
    nees_band : tuple
        95 % band of the mean NEES of a consistent filter.
    nis_band : tuple
        95 % band of the mean NIS at one epoch.
    dim : int
        State dimension.
    meas_dim : int
        Measurement dimension.
    heading_sigma : float
        The filter's standard deviation of the azimuth error at the end [rad].
    """

    times: np.ndarray
    nees: np.ndarray
    nis: np.ndarray
    nis_all: float
    nees_band: tuple
    nis_band: tuple
    dim: int
    meas_dim: int
    heading_sigma: float

    @property
    def nees_inside(self) -> np.ndarray:
        """Whether each mean NEES lies in its band."""
        lo, hi = self.nees_band
        return (self.nees >= lo) & (self.nees <= hi)

    @property
    def nis_inside(self) -> np.ndarray:
        """Whether each mean NIS lies in its band."""
        lo, hi = self.nis_band
        return (self.nis >= lo) & (self.nis <= hi)


@dataclass(frozen=True)
class AlignmentMonteCarlo:
    """Monte Carlo of one method in one scenario, with the theory that applies [rad].

    Attributes
    ----------
    method : str
        The method.
    scenario : Scenario
        The configuration.
    errors : SensorErrors
        Sensor errors.
    result : MonteCarloResult
        Statistics of the azimuth error.
    tilt_rms : ndarray
        ``(2,)`` rms errors of β̂, γ̂.
    bias_floor : tuple
        ``(gyro, accel)``: first-order azimuth errors of the fixed biases, the floor of every method.
    theory : AnalyticTheory or None
        The analytic method's first-order theory.
    kalman : KalmanConsistency or None
        Kalman: NEES and NIS.
    kalman_theory : KalmanTheory or None
        Kalman: the linear filter's own prediction.
    """

    method: str
    scenario: Scenario
    errors: SensorErrors
    result: montecarlo.MonteCarloResult
    tilt_rms: np.ndarray
    bias_floor: tuple
    theory: AnalyticTheory | None = None
    kalman: KalmanConsistency | None = None
    kalman_theory: KalmanTheory | None = None

    def consistency(self, level: float = 0.95) -> Verdict | None:
        """Kalman: is the filter consistent? Every mean NEES and NIS at the K check epochs inside its χ² band.

        The bands are taken at ``1 − (1 − level)/(2K)`` each (Bonferroni), so
        that a consistent filter has all 2K means inside with probability at
        least ``level``: the verdict is a test at that level of the whole
        family of checks, not of each one.

        Parameters
        ----------
        level : float
            Family confidence.

        Returns
        -------
        Verdict or None
            ``"yes"`` or ``"no"``; None for the other methods.
        """
        k = self.kalman
        if k is None:
            return None
        n, K = self.result.n_trials, k.nees.size
        each = 1.0 - (1.0 - level) / (2 * K)
        text = f"every mean NEES and NIS at {K} epochs inside its χ² band of {n} trials ({level:.0%} for the family, Bonferroni)"
        nees = in_band(k.nees, kalman.chi2_band(k.dim, n, each), n=n, criterion=text, level=level)
        nis = in_band(k.nis, kalman.chi2_band(k.meas_dim, n, each), n=n, criterion=text, level=level)
        return all_of([nees, nis], criterion=text)


def _per_block(method: str, n_trials: int, trials_per_block) -> int:
    per_block = as_int(trials_per_block, "trials_per_block", minimum=1) if trials_per_block else budget.ALIGNMENT_BLOCKS[method][0]
    return min(per_block, n_trials)


def alignment_draws(
    scenario: Scenario, errors: SensorErrors | None = None, *, method: str, n_trials: int, rng=None, options: AlignmentOptions | None = None, trials_per_block: int | None = None
) -> tuple:
    """The random numbers of every block of :func:`alignment_monte_carlo`, drawn once to be passed again.

    Block ``i`` draws from the ``i``-th child of the root SeedSequence, as the
    Monte Carlo does: a run on these draws equals a run from ``rng``.

    Parameters
    ----------
    scenario : Scenario
        The configuration.
    errors : SensorErrors, optional
        Sensor errors (default ideal).
    method : str
        ``"analytic"``, ``"inertial"`` or ``"kalman"``.
    n_trials : int
        Trials, at least 2.
    rng : Generator | SeedSequence | int | None
        Root of the block streams.
    options : AlignmentOptions, optional
        Method options (the Kalman filter's epoch).
    trials_per_block : int, optional
        Trials per block.

    Returns
    -------
    tuple of AlignmentDraws
    """
    if method not in METHODS:
        raise ValueError(f"Expected `method` in {METHODS}, got {method!r}")
    errors = SensorErrors() if errors is None else errors
    options = AlignmentOptions() if options is None else options
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    per_block = _per_block(method, n_trials, trials_per_block)
    root = montecarlo.root_seed_sequence(rng)
    kernel = AlignmentKernel(scenario, errors, method, options)
    return tuple(kernel.draw(min(per_block, n_trials - b * per_block), np.random.default_rng(montecarlo.block_seed(root, b))) for b in range(-(-n_trials // per_block)))


def _check_epochs(n_epochs: int, k: int = 8) -> tuple:
    e = np.unique(np.round(np.geomspace(1, n_epochs, k)).astype(int)) - 1
    return tuple(int(x) for x in e)


def alignment_monte_carlo(
    scenario: Scenario,
    errors: SensorErrors | None = None,
    *,
    method: str,
    n_trials: int,
    rng=None,
    options: AlignmentOptions | None = None,
    executor=None,
    progress: bool = False,
    trials_per_block: int | None = None,
    draws=None,
    limits: budget.Limits | None = None,
) -> AlignmentMonteCarlo:
    """Monte Carlo of the azimuth error of one alignment method.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking, lever arm, sampling and alignment time.
    errors : SensorErrors, optional
        Sensor errors (default ideal).
    method : str
        ``"analytic"``, ``"inertial"`` or ``"kalman"``.
    n_trials : int
        Trials, at least 2.
    rng : Generator | SeedSequence | int | None
        Root of the block streams.
    options : AlignmentOptions, optional
        Method options.
    executor : Executor | dask Client | None
        Where blocks run (the result does not depend on it).
    progress : bool
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    trials_per_block : int, optional
        Trials per block (the unit of randomness; default 32, Kalman 128).
    draws : sequence of AlignmentDraws, optional
        The random numbers of every block, drawn before (:func:`alignment_draws`)
        instead of from ``rng``: the same trials as another run on these draws
        (common random numbers), here in a scenario that may differ by the rocking
        amplitudes, or for another filter.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s, on one core); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AlignmentMonteCarlo

    Raises
    ------
    ValueError
        For an unknown method, fewer than 2 trials, or a run beyond ``limits``
        (naming ``n_trials`` and the scenario's ``duration``).

    Examples
    --------
    The gyro-bias floor of the analytic method at rest:

    >>> sc = Scenario(math.radians(45.0), duration=30.0, sample_rate=10.0)
    >>> b = math.radians(0.01) / 3600.0
    >>> mc = alignment_monte_carlo(sc, SensorErrors(gyro_bias=[0.0, b, 0.0], gyro_noise=1e-6), method="analytic", n_trials=64, rng=1)
    >>> lo, hi = mc.result.mean_ci
    >>> bool(lo < mc.theory.mean < hi)
    True
    """
    if method not in METHODS:
        raise ValueError(f"Expected `method` in {METHODS}, got {method!r}")
    errors = SensorErrors() if errors is None else errors
    options = AlignmentOptions() if options is None else options
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    root = montecarlo.root_seed_sequence(rng)
    sequence, checks, model, n_epochs = None, (), None, 0
    if method == "kalman":
        model = filter_model(scenario, options.tuning)
        n_epochs = scenario.n_samples // model.samples_per_epoch
        if n_epochs < 1:
            raise ValueError(f"Expected `duration` of at least one filter epoch ({model.epoch:g} s), got {scenario.duration:g}")
    per_block = _per_block(method, n_trials, trials_per_block)
    what = f"`n_trials` = {n_trials:.3g} trials of {scenario.n_samples:.3g} samples (`duration` = {scenario.duration:.3g} s of the scenario)"
    budget.check(budget.alignment_monte_carlo(n_trials, scenario.n_samples, method=method, epochs=n_epochs, per_block=per_block, what=what), limits)
    floor = bias_floor(scenario, errors)
    theory = analytic_theory(scenario, errors, formula=options.formula) if method == "analytic" else None
    if method == "kalman":
        sequence = kalman.filter_sequence(model.F, model.Q, model.H, model.R, model.P0, n_epochs)
        checks = _check_epochs(n_epochs)
    kernel = AlignmentKernel(scenario, errors, method, options, checks, sequence, model=model)
    if draws is None:
        # histogram scale from a pilot block on its own stream (not one of the run's blocks)
        pilot, _ = kernel(min(8, n_trials), np.random.default_rng(montecarlo.block_seed(root, 2**31)))
        scale = float(np.sqrt(np.mean(pilot**2))) or 1e-12
        result = montecarlo.run(kernel, n_trials, rng=root, trials_per_block=per_block, blocks_per_chunk=1, executor=executor, scale=2.0 * scale, progress=progress)
    else:
        if sum(d.n_trials for d in draws) != n_trials:
            raise ValueError(f"Expected `draws` of {n_trials} trials (n_trials), got {sum(d.n_trials for d in draws)}")
        blocks = [montecarlo.block_output(kernel.evaluate(d), d.n_trials) for d in draws]
        scale = float(np.sqrt(np.mean(blocks[0][0] ** 2))) or 1e-12  # the histogram's scale (display only)
        result = montecarlo.summarise(blocks, scale=2.0 * scale)
    aux = np.asarray(result.aux_mean)
    tilt_rms = np.sqrt(aux[:2])
    consistency, kth = None, None
    if method == "kalman":
        k = len(checks)
        times = model.epoch * (np.asarray(checks) + 1)
        consistency = KalmanConsistency(
            times,
            aux[2 : 2 + k],
            aux[2 + k : 2 + 2 * k],
            float(aux[2 + 2 * k]),
            kalman.chi2_band(model.dim, n_trials),
            kalman.chi2_band(3, n_trials),
            model.dim,
            3,
            float(math.sqrt(sequence.posterior[-1, 2, 2])),
        )
        kth = kalman_theory(scenario, errors, model, sequence)
    return AlignmentMonteCarlo(method, scenario, errors, result, tilt_rms, floor, theory, consistency, kth)
