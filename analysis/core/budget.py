"""Work estimates: refuse a request that would exceed a stated memory or time limit, before it starts.

A typo such as ``--duration 1e12`` must not leave a user waiting for a run that
cannot finish, or exhaust the memory of a shared machine.  Every command that
does work proportional to its arguments estimates that work first, from the
arguments alone, as an :class:`Estimate` (peak memory and run time), and
:func:`check` compares it with :class:`Limits` before any array is allocated.

The cost of each hot path is a :class:`CostModel`: seconds and bytes per unit
of work (a simulator step, a Monte Carlo sample, ...) plus fixed costs.  The
constants below were measured on one core of the reference machine of
``benchmarks/README.md`` by ``benchmarks/bench_budget.py``, which also prints
how far each model is from a fresh measurement; they are rounded up, so the
estimates err on the side of refusing.  A domain adds its own hot path by
defining a :class:`CostModel` and an estimator function next to the others.

The same estimates guard the Python API: every public function whose
allocation or run time grows with a scalar argument (a duration, a horizon, a
number of trials or samples) takes ``limits=None`` (keyword-only; None means
the defaults) and raises :class:`BudgetExceeded`, a ``ValueError`` whose message
starts with the argument that asked for the work, before anything is
allocated; the command line passes its ``--time-limit`` and
``--memory-limit-mb`` down as the same :class:`Limits` and names the option.

>>> est = CONING_STEP.estimate(1e9, what="`duration` = 1e+07 s (1e9 simulator steps)")
>>> check(est, Limits(seconds=60.0, memory=1e9))
Traceback (most recent call last):
...
strapdown.analysis.core.budget.BudgetExceeded: `duration` = 1e+07 s (1e9 simulator steps): estimated memory 40 GB exceeds the limit of 1 GB (pass larger `limits`)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .validation import as_float, nonnegative, positive

__all__ = [
    "DEFAULT_TIME_LIMIT",
    "DEFAULT_MEMORY_LIMIT",
    "Estimate",
    "Limits",
    "CostModel",
    "BudgetExceeded",
    "check",
    "as_limits",
    "format_bytes",
    "format_seconds",
    "CONING_STEP",
    "MONTE_CARLO_SAMPLE",
    "MULTISTAGE_STEP",
    "AUTOCORRELATION_TERM",
    "ARRAY_ELEMENT",
    "RESPONSE_SAMPLE",
    "IMU_TRIAL_SAMPLE",
    "IMU_SAMPLE_BYTES",
    "ALIGNMENT_BLOCKS",
    "KALMAN_EPOCH",
    "KALMAN_EPOCH_BYTES",
    "VIBRATION_SAMPLE",
    "VIBRATION_DRAW",
    "VIBRATION_PAIR_BYTES",
    "FILTERED_CONING_SAMPLE",
    "SPECTRUM_SEGMENT",
    "RESPONSE_EVALUATION",
    "TRAJECTORY_STEP",
    "TRAJECTORY_SAMPLE",
    "AIDED_FIX",
    "AIDED_TRIAL_SAMPLE",
    "AIDED_EPOCH_SECONDS",
    "SENSOR_ERROR_ELEMENT",
    "INTEGRATOR_SAMPLE",
    "OBSERVABILITY_EPOCH",
    "GRAMIAN_STEP_SECONDS",
    "LOG_SAMPLE",
    "coning_simulation",
    "coning_batch",
    "coning_long_run",
    "arrays",
    "loop_response",
    "imu_record",
    "alignment_monte_carlo",
    "series_derivation",
    "monte_carlo",
    "multistage",
    "observability",
    "autocorrelation_sums",
    "vibration_monte_carlo",
    "sensor_errors",
    "recorded_log",
]

#: Default time limit [s]: five minutes, far above every documented command.
DEFAULT_TIME_LIMIT = 300.0
#: Default memory limit [bytes]: 2 GB, a fair share of a shared workstation.
DEFAULT_MEMORY_LIMIT = 2e9


def format_bytes(n: float) -> str:
    """``n`` bytes in the largest unit that keeps it above 1 (decimal prefixes).

    Parameters
    ----------
    n : float
        A number of bytes.

    Returns
    -------
    str
        For example ``"3.2 GB"``.

    Examples
    --------
    >>> format_bytes(3.2e9), format_bytes(512)
    ('3.2 GB', '512 B')
    """
    n = float(n)
    for unit, size in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if abs(n) >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.3g} B"


def format_seconds(t: float) -> str:
    """A duration [s] in seconds, hours or years, whichever reads best.

    Parameters
    ----------
    t : float
        Duration [s].

    Returns
    -------
    str
        For example ``"42 s"``, ``"3.1 h"`` or ``"2.4e+05 years"``.

    Examples
    --------
    >>> format_seconds(42.0), format_seconds(11160.0), format_seconds(7.6e12)
    ('42 s', '3.1 h', '2.41e+05 years')
    """
    t = float(t)
    if t < 3600.0:
        return f"{t:.3g} s"
    if t < 3.15e7:
        return f"{t / 3600.0:.3g} h"
    return f"{t / 3.15576e7:.3g} years"


@dataclass(frozen=True)
class Estimate:
    """Estimated peak memory and run time of one request.

    Attributes
    ----------
    seconds : float
        Estimated run time on one core of the reference machine [s].
    memory : float
        Estimated peak memory of the arrays the request allocates [bytes].
    what : str
        The request in the user's terms, e.g. ``"4.0e+14 gyro samples (--duration / --sample-interval)"``.
    """

    seconds: float
    memory: float
    what: str = "the request"

    def __add__(self, other: Estimate) -> Estimate:
        """Two requests one after the other: times add, the larger peak memory counts."""
        return Estimate(self.seconds + other.seconds, max(self.memory, other.memory), f"{self.what} and {other.what}")


@dataclass(frozen=True)
class Limits:
    """What a request may use.

    Attributes
    ----------
    seconds : float
        Largest estimated run time [s] (default :data:`DEFAULT_TIME_LIMIT`).
    memory : float
        Largest estimated peak memory [bytes] (default :data:`DEFAULT_MEMORY_LIMIT`).
    """

    seconds: float = DEFAULT_TIME_LIMIT
    memory: float = DEFAULT_MEMORY_LIMIT

    def __post_init__(self):
        positive(self.seconds, "time_limit")
        positive(self.memory, "memory_limit")


class BudgetExceeded(ValueError):
    """A request whose estimate exceeds its :class:`Limits` (a ``ValueError``).

    Parameters
    ----------
    estimate : Estimate
        The refused estimate.
    limits : Limits
        The limits it exceeds.
    resource : str
        ``"memory"`` or ``"time"``: the first limit exceeded (memory is checked first).
    """

    def __init__(self, estimate: Estimate, limits: Limits, resource: str):
        self.estimate = estimate
        self.limits = limits
        self.resource = resource
        if resource == "memory":
            text = f"estimated memory {format_bytes(estimate.memory)} exceeds the limit of {format_bytes(limits.memory)} (pass larger `limits`)"
        else:
            text = f"estimated time {format_seconds(estimate.seconds)} exceeds the limit of {format_seconds(limits.seconds)} (pass larger `limits`)"
        super().__init__(f"{estimate.what}: {text}")


def as_limits(limits: Limits | None) -> Limits:
    """``limits``, or the default :class:`Limits` when it is None.

    Parameters
    ----------
    limits : Limits or None
        What a request may use.

    Returns
    -------
    Limits

    Raises
    ------
    TypeError
        If ``limits`` is neither a :class:`Limits` nor None.
    """
    if limits is None:
        return Limits()
    if not isinstance(limits, Limits):
        raise TypeError(f"Expected `limits` to be a strapdown.analysis.core.budget.Limits or None, got {type(limits).__name__}")
    return limits


def check(estimate: Estimate, limits: Limits | None = None) -> Estimate:
    """Return ``estimate`` if it fits ``limits``; raise :class:`BudgetExceeded` otherwise.

    Parameters
    ----------
    estimate : Estimate
        What the request would use.
    limits : Limits, optional
        The limits (default: :data:`DEFAULT_TIME_LIMIT`, :data:`DEFAULT_MEMORY_LIMIT`).

    Returns
    -------
    Estimate
        ``estimate`` itself.

    Raises
    ------
    BudgetExceeded
        If the estimated memory or time exceeds its limit (or is not finite).
    TypeError
        If ``limits`` is neither a :class:`Limits` nor None.
    """
    limits = as_limits(limits)
    if not estimate.memory <= limits.memory:  # also catches NaN
        raise BudgetExceeded(estimate, limits, "memory")
    if not estimate.seconds <= limits.seconds:
        raise BudgetExceeded(estimate, limits, "time")
    return estimate


@dataclass(frozen=True)
class CostModel:
    """Linear cost of a hot path: ``fixed + per_unit · units`` in time and memory.

    Attributes
    ----------
    seconds_per_unit : float
        Run time per unit of work [s].
    bytes_per_unit : float
        Memory kept per unit of work (results that grow with the run) [bytes].
    fixed_seconds : float
        Start-up time, independent of the size [s].
    fixed_bytes : float
        Working set independent of the size (chunk buffers) [bytes].
    """

    seconds_per_unit: float
    bytes_per_unit: float
    fixed_seconds: float = 0.0
    fixed_bytes: float = 0.0

    def estimate(self, units, *, what: str, seconds_factor: float = 1.0, bytes_factor: float = 1.0, extra_bytes: float = 0.0) -> Estimate:
        """The :class:`Estimate` of ``units`` units of work.

        Parameters
        ----------
        units : float
            Amount of work (steps, samples, ...) [count]; may be huge (no arithmetic overflows).
        what : str
            The request in the user's terms (starts the refusal message).
        seconds_factor, bytes_factor : float, keyword-only
            Multipliers of the per-unit costs (e.g. a heavier algorithm).
        extra_bytes : float, keyword-only
            Working set added to :attr:`fixed_bytes` [bytes].

        Returns
        -------
        Estimate
        """
        units = nonnegative(units, "units") if math.isfinite(float(units)) else math.inf
        per_second = self.seconds_per_unit * as_float(seconds_factor, "seconds_factor")
        per_byte = self.bytes_per_unit * as_float(bytes_factor, "bytes_factor")
        seconds = self.fixed_seconds + (per_second * units if per_second else 0.0)
        extra = float(extra_bytes) if math.isinf(float(extra_bytes)) else nonnegative(extra_bytes, "extra_bytes")
        memory = self.fixed_bytes + extra + (per_byte * units if per_byte else 0.0)
        return Estimate(seconds, memory, what)


# ---------------------------------------------------------------- measured hot paths
#: Parallel-computation simulator, per algorithm step of a light algorithm (two samples, one term):
#: time; memory kept per step: the error series (24 bytes), the times (8) and the weights of the
#: drift fit (8), measured with tracemalloc (``tests/test_long_run.py``).  Heavier algorithms scale
#: the time (:func:`coning_simulation`).
CONING_STEP = CostModel(seconds_per_unit=6e-7, bytes_per_unit=40.0, fixed_seconds=0.5)
#: Azimuth Monte Carlo, per rocking sample (chunked: the working set does not grow with the run, but
#: every error is kept for its order statistics, the quantiles: 8 bytes, and 8 more for the partial
#: sort); the fixed time is the symbolic second-order theory derived once per process.
MONTE_CARLO_SAMPLE = CostModel(seconds_per_unit=1.2e-7, bytes_per_unit=16.0, fixed_seconds=6.0, fixed_bytes=2.5e8)
#: Multistage cascade (section 5 of Plotnikov 1999), per integration step (a Python loop per step).
MULTISTAGE_STEP = CostModel(seconds_per_unit=3e-5, bytes_per_unit=1.2e3, fixed_seconds=0.5)
#: Autocorrelation sum of a sample mean's variance, per lag term (arrays of the lags).
AUTOCORRELATION_TERM = CostModel(seconds_per_unit=5e-8, bytes_per_unit=48.0)
#: One float64 element of arrays that a function allocates in proportion to an argument (a few
#: elementwise passes over each).
ARRAY_ELEMENT = CostModel(seconds_per_unit=2e-8, bytes_per_unit=8.0)
#: Response of a corrected stage's tilt loop, per time sample: the grid, the zero-order-hold
#: recursion (``scipy.signal.lfilter``) and the superposed pulse, a dozen float64 arrays.
RESPONSE_SAMPLE = CostModel(seconds_per_unit=1e-7, bytes_per_unit=96.0, fixed_seconds=0.05)
#: Whole-system alignment, per trial and IMU sample: the time of the slowest method (Kalman; the
#: analytic method takes about a third of it) and the start-up (theory, pilot block).  Measured with
#: ``strapdown align`` from 1e3 to 1e5 samples and 16 to 256 trials on a shared machine, rounded up.
IMU_TRIAL_SAMPLE = CostModel(seconds_per_unit=3e-6, bytes_per_unit=0.0, fixed_seconds=1.0, fixed_bytes=2e8)
#: Memory of a simulated IMU record per trial and sample [bytes] (motion, increments, noise).
IMU_SAMPLE_BYTES = 450.0
#: Alignment Monte Carlo: trials per block (the library's defaults) and the peak memory of a block per
#: trial and sample [bytes], by method.
ALIGNMENT_BLOCKS = {"analytic": (32, 350.0), "inertial": (32, 350.0), "kalman": (128, 150.0)}
#: Kalman alignment, per trial and filter epoch (time); its gain sequence and epoch records per epoch (memory).
KALMAN_EPOCH = CostModel(seconds_per_unit=8e-6, bytes_per_unit=0.0)
KALMAN_EPOCH_BYTES = 5e4
#: Vibration Monte Carlo kernel, per realisation, sensor sample and sinusoid (the phases advance and the
#: motion is summed sinusoid by sinusoid); a velocity run (dual algorithm, six channels) takes about
#: 2.5 times longer (3 is assumed, :func:`vibration_monte_carlo`).  The fixed costs are the sensor
#: matrices and the sampling densities of the spectra (8.4 MB for one spectrum); the numba
#: compilation, once per algorithm, is not counted.
VIBRATION_SAMPLE = CostModel(seconds_per_unit=3e-8, bytes_per_unit=0.0, fixed_seconds=0.3, fixed_bytes=2e7)
#: Draws of the vibration Monte Carlo, per realisation and sinusoid: the 6×6 covariance of a random
#: frequency, its Hermitian square root (``numpy.linalg.eigh``) and the complex amplitudes (2.6 kB at the peak).
VIBRATION_DRAW = CostModel(seconds_per_unit=5e-5, bytes_per_unit=3e3)
#: Memory per antithetic pair of the vibration Monte Carlo: its spawned stream and its result row [bytes].
VIBRATION_PAIR_BYTES = 1e3
#: Product-integration weights of a vibration spectrum, per table segment (eight interpolated spectra, their
#: Legendre moments), computed once per spectrum; chunked, so the working set does not grow with the table.
SPECTRUM_SEGMENT = CostModel(seconds_per_unit=3e-5, bytes_per_unit=600.0, fixed_seconds=0.05, fixed_bytes=2e7)
#: One node of a vibration response integral, per algorithm response function integrated at it (the sensors'
#: responses, the function, the drift columns).
RESPONSE_EVALUATION = CostModel(seconds_per_unit=3e-6, bytes_per_unit=0.0, fixed_seconds=0.0, fixed_bytes=2e7)
#: DOP853 reference of a coning line seen through filtered gyros (rtol 1e-13), per sensor sample
#: (at least 16 integration steps per coning period): the integration to every sample and the states kept.
FILTERED_CONING_SAMPLE = CostModel(seconds_per_unit=3e-3, bytes_per_unit=1e3, fixed_seconds=0.5)
#: Dense DOP853 position solution of a drive (rtol 1e-12), per integration step (the step is at most
#: a twentieth of the weave period and at least 1 s): time, and the dense-output segment kept per step.
TRAJECTORY_STEP = CostModel(seconds_per_unit=3e-4, bytes_per_unit=1e3)
#: Ideal increments of a drive, per IMU sample: the true state at two Gauss–Legendre nodes (650 B at the peak).
TRAJECTORY_SAMPLE = CostModel(seconds_per_unit=4e-6, bytes_per_unit=800.0)
#: Aided filter along a drive, per GNSS fix: the error model linearised at the fix, its Van Loan
#: exponential and filterpy's predict and update (a Python loop per fix); the stacked 30 × 30 blocks,
#: gains and covariances kept per fix.
AIDED_FIX = CostModel(seconds_per_unit=5e-4, bytes_per_unit=4e4, fixed_seconds=0.5)
#: Aided navigator, per trial and IMU sample, beside its sensor errors (:data:`SENSOR_ERROR_ELEMENT`):
#: the epoch increments and the epoch loop vectorised over trials.
AIDED_TRIAL_SAMPLE = CostModel(seconds_per_unit=2e-6, bytes_per_unit=200.0)
#: Aided navigator, per epoch and call, whatever the trials (the numpy calls of one epoch step) [s].
AIDED_EPOCH_SECONDS = 3e-4
#: Sensor-error increments, per element (trial × sample × axis) and noise term (each Gauss–Markov
#: term of the flicker, the rate random walk, the white noise): time; the increments and the
#: normal draws of one term alive at once (72 B per element at the peak).
SENSOR_ERROR_ELEMENT = CostModel(seconds_per_unit=1e-7, bytes_per_unit=100.0)
#: An integrator on exact coning increments, per sample (the library's algorithms; a slow black box
#: takes longer): the increments, the step rotations, their prefix product and the errors (260 B per sample).
INTEGRATOR_SAMPLE = CostModel(seconds_per_unit=1.5e-6, bytes_per_unit=400.0)
#: Reading and checking a recorded IMU log, per sample of the stream read: the columns read
#: (float64), the increments and the checks' one-second windows; the fixed part is the chunk
#: of the file walked at a time (64 MiB), its record offsets and the records gathered from it.
LOG_SAMPLE = CostModel(seconds_per_unit=1.5e-6, bytes_per_unit=220.0, fixed_seconds=1.0, fixed_bytes=2.5e8)


#: Observability of an alignment model, per filter epoch of its covariance run (filterpy's predict and
#: update, a Python loop per epoch; 1.4e-4 to 2.2e-4 s measured on a shared machine, 12 and 18 states);
#: the fixed cost is the staircase reduction and the imports.  The memory per epoch is the gain, prior,
#: posterior and innovation covariances kept per epoch of a segment, ``8 (2n² + nm + m²)`` bytes
#: (2.7 kB for twelve states, measured), see :func:`observability`.
OBSERVABILITY_EPOCH = CostModel(seconds_per_unit=2.5e-4, bytes_per_unit=0.0, fixed_seconds=1.0, fixed_bytes=1.5e8)
#: One sub-interval of the observability Gramian (a Van Loan exponential and a matrix exponential) [s].
GRAMIAN_STEP_SECONDS = 2e-4


def observability(epochs, segment_epochs, gramian_steps, *, states: int, measurements: int, what: str) -> Estimate:
    """Estimate of the degree of observability of an alignment model over its horizon.

    Parameters
    ----------
    epochs : float
        Filter epochs over the whole horizon [count].
    segment_epochs : float
        Epochs of the longest segment (its covariances are kept at once) [count].
    gramian_steps : float
        Sub-intervals of the Gramian's sum [count].
    states, measurements : int, keyword-only
        n and m of the model [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    n, m = int(states), int(measurements)
    per_epoch = 8.0 * (2 * n * n + n * m + m * m)
    base = OBSERVABILITY_EPOCH.estimate(epochs, what=what, seconds_factor=max(1.0, n / 12.0), extra_bytes=per_epoch * float(segment_epochs))
    return Estimate(base.seconds + GRAMIAN_STEP_SECONDS * float(gramian_steps), base.memory, what)


def coning_simulation(steps, *, window: int, degree_sum: int, velocity: bool, chunk_steps: int, what: str) -> Estimate:
    """Estimate of a parallel-computation run (``strapdown.analysis.coning.simulator.simulate``).

    Time grows with the samples per step (the increment window) and with the
    total degree of the algorithm's terms; dual numbers (velocity runs) cost about
    four times more per step (five is assumed) and keep three times more per step.  The increments
    of one chunk of ``chunk_steps`` steps, with their step quaternions and prefix products, are held
    at once: about ``40 · window + 120`` bytes per step of the chunk (twice that for dual numbers),
    measured with tracemalloc.

    Parameters
    ----------
    steps : float
        Algorithm steps of the run [count].
    window : int
        Increments read per step (samples plus earlier samples) [count].
    degree_sum : int
        Sum of the degrees of the algorithm's nonlinear terms [count].
    velocity : bool
        Dual (apparent-velocity) run.
    chunk_steps : int
        Steps evaluated at once by the simulator [count].
    what : str
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    per_step = 1.0 + window / 6.0 + degree_sum / 60.0
    dual = 5.0 if velocity else 1.0
    chunk = min(float(steps), float(chunk_steps)) * (40.0 * window + 120.0) * (2 if velocity else 1)
    return CONING_STEP.estimate(steps, what=what, seconds_factor=per_step * dual, bytes_factor=3.0 if velocity else 1.0, extra_bytes=chunk)


def coning_batch(points, steps, *, window: int, degree_sum: int, velocity: bool, series: bool, what: str) -> Estimate:
    """Estimate of a batch of ``points`` parallel-computation runs of ``steps`` steps each.

    The time is that of :func:`coning_simulation` over all point-steps (an
    upper bound for the compiled kernels).  The memory is the streaming
    accumulators and parameters of each point, plus with ``series`` the error
    series of every point (one, or three for a velocity run, ``(steps + 1, 3)``
    float64 arrays).

    Parameters
    ----------
    points : float
        Parameter points of the batch [count].
    steps : float
        Steps of the longest run [count].
    window : int
        Increments read per step [count].
    degree_sum : int
        Sum of the degrees of the algorithm's nonlinear terms [count].
    velocity : bool
        Dual (apparent-velocity) run.
    series : bool
        The full error series are kept.
    what : str
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    points, steps = float(points), float(steps)
    per_step = 1.0 + window / 6.0 + degree_sum / 60.0
    work = points * steps if points and steps else 0.0
    seconds = CONING_STEP.fixed_seconds + CONING_STEP.seconds_per_unit * per_step * (5.0 if velocity else 1.0) * work
    memory = points * 400.0 + (points * (steps + 1.0) * 3 * 8 * (3 if velocity else 1) if series and points else 0.0)
    return Estimate(seconds, memory, what)


#: Arrays of a long run beside its window (parameters, sums, the kernel's own buffers) [bytes].
LONG_RUN_FIXED_BYTES = 1e5


def coning_long_run(steps, *, window: int, samples: int, degree_sum: int, series: bool, what: str) -> Estimate:
    """Estimate of one constant-memory run (``strapdown.analysis.coning.long_run.simulate_long_run``).

    The time is that of :func:`coning_batch` for one point.  The memory is one
    window of the error series (``window + 1`` rows of three float64, whose
    periodic error the compiled ``window_peak`` takes in place), whatever the
    number of steps; with
    ``series`` (the numpy engine, which holds the series) it is that of
    :func:`coning_simulation` instead.

    Parameters
    ----------
    steps : float
        Algorithm steps of the run [count].
    window : int
        Steps per window of the periodic error [count].
    samples : int
        Samples per step (the increment window of a non-cross-step algorithm) [count].
    degree_sum : int
        Sum of the degrees of the algorithm's nonlinear terms [count].
    series : bool
        The numpy engine runs (it holds the whole series).
    what : str
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    steps = float(steps)
    seconds = coning_batch(1, steps, window=samples, degree_sum=degree_sum, velocity=False, series=False, what=what).seconds
    if series:
        return Estimate(seconds, coning_simulation(steps, window=samples, degree_sum=degree_sum, velocity=False, chunk_steps=65536, what=what).memory, what)
    rows = float(window) + 1.0
    memory = LONG_RUN_FIXED_BYTES + 24.0 * rows
    return Estimate(seconds, memory, what)


def monte_carlo(samples, *, workers: int = 1, what: str) -> Estimate:
    """Estimate of the chunked azimuth Monte Carlo over ``samples`` rocking samples.

    Parameters
    ----------
    samples : float
        Rocking samples [count].
    workers : int, keyword-only
        Worker processes sharing the samples [count]; each holds one chunk.
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    workers = max(int(workers), 1)
    return MONTE_CARLO_SAMPLE.estimate(samples, what=what, seconds_factor=1.0 / workers, extra_bytes=(workers - 1) * MONTE_CARLO_SAMPLE.fixed_bytes)


def multistage(steps, *, what: str) -> Estimate:
    """Estimate of the multistage cascade over ``steps`` integration steps.

    Parameters
    ----------
    steps : float
        Integration steps [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    return MULTISTAGE_STEP.estimate(steps, what=what)


def autocorrelation_sums(points, terms, *, what: str) -> Estimate:
    """Estimate of ``points`` variance factors, each a sum over ``terms`` lags.

    Parameters
    ----------
    points : float
        Number of sums (e.g. rocking frequencies) [count].
    terms : float
        Lags per sum (samples in the averaging time) [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
        Time of all sums; memory of one (they run one after the other).
    """
    one = AUTOCORRELATION_TERM.estimate(terms, what=what)
    return Estimate(one.seconds * max(float(points), 1.0), one.memory, what)


def vibration_monte_carlo(pairs, samples, sinusoids, *, velocity: bool, chunk: int, what: str) -> Estimate:
    """Estimate of a vibration Monte Carlo: ``pairs`` antithetic pairs of realisations of ``samples`` sensor samples.

    Parameters
    ----------
    pairs : float
        Antithetic pairs [count].
    samples : float
        Sensor samples per realisation, the warm-up included [count].
    sinusoids : int
        Sinusoids per realisation (lines plus the components of the spectra) [count].
    velocity : bool, keyword-only
        Dual (apparent-velocity) run.
    chunk : int, keyword-only
        Pairs drawn at once [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
        The kernel over both members of every pair plus the draws (time); the
        pairs' streams and results, the draws of one chunk and the kernel's
        weights over the samples (memory).
    """
    pairs, samples, sinusoids = float(pairs), float(samples), float(sinusoids)
    run = VIBRATION_SAMPLE.estimate(2.0 * pairs * samples * sinusoids, what=what, seconds_factor=3.0 if velocity else 1.0)
    draws = VIBRATION_DRAW.estimate(pairs * sinusoids, what=what)
    memory = run.memory + pairs * VIBRATION_PAIR_BYTES + min(pairs, float(chunk)) * sinusoids * VIBRATION_DRAW.bytes_per_unit + 8.0 * samples
    return Estimate(run.seconds + draws.seconds, memory, what)


def sensor_errors(elements, terms, *, what: str) -> Estimate:
    """Estimate of sensor-error increments over ``elements`` trial-sample-axis elements with ``terms`` noise terms.

    Parameters
    ----------
    elements : float
        Trials × samples × 3 [count].
    terms : int
        Noise terms drawn (white noise, Gauss–Markov terms, rate random walk) [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    return SENSOR_ERROR_ELEMENT.estimate(elements, what=what, seconds_factor=max(float(terms), 1.0))


def recorded_log(samples, *, what: str) -> Estimate:
    """Estimate of reading and checking ``samples`` samples of a recorded IMU log.

    Parameters
    ----------
    samples : float
        Samples of the stream read [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    return LOG_SAMPLE.estimate(samples, what=what)


def arrays(elements, *, what: str, copies: float = 1.0) -> Estimate:
    """Estimate of float64 arrays of ``elements`` elements in all, ``copies`` of them alive at once.

    Parameters
    ----------
    elements : float
        Elements of one set of arrays [count]; may be huge.
    what : str, keyword-only
        The request in the user's terms, starting with the argument that sets the size.
    copies : float, keyword-only
        Sets of such arrays alive at the peak [count].

    Returns
    -------
    Estimate

    Examples
    --------
    >>> arrays(1e9, what="`steps` = 1e9", copies=3).memory
    24000000000.0
    """
    return ARRAY_ELEMENT.estimate(elements, what=what, seconds_factor=copies, bytes_factor=copies)


def loop_response(samples, *, what: str) -> Estimate:
    """Estimate of a tilt-loop response over ``samples`` time samples.

    Parameters
    ----------
    samples : float
        Time samples of the response [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    return RESPONSE_SAMPLE.estimate(samples, what=what)


def imu_record(trials, samples, *, held_trials=None, bytes_per_sample=None, what: str) -> Estimate:
    """Estimate of a whole-system alignment run: ``trials`` trials of ``samples`` IMU samples.

    Parameters
    ----------
    trials : float
        Monte Carlo trials [count].
    samples : float
        IMU samples per trial [count].
    held_trials : float, keyword-only, optional
        Trials whose samples are held in memory at once (default all of them).
    bytes_per_sample : float, keyword-only, optional
        Memory kept per held trial and sample [bytes] (default :data:`IMU_SAMPLE_BYTES`).
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    held = float(trials) if held_trials is None else min(float(trials), float(held_trials))
    units = float(trials) * float(samples)
    per = IMU_SAMPLE_BYTES if bytes_per_sample is None else float(bytes_per_sample)
    extra = held * float(samples) * per if per and held and samples else 0.0
    return IMU_TRIAL_SAMPLE.estimate(units, what=what, extra_bytes=extra if math.isfinite(extra) else math.inf)


def alignment_monte_carlo(trials, samples, *, method: str, epochs: float = 0.0, per_block=None, workers: int = 1, what: str) -> Estimate:
    """Estimate of a whole-system alignment Monte Carlo (each worker holds one block of trials).

    Parameters
    ----------
    trials : float
        Monte Carlo trials [count].
    samples : float
        IMU samples per trial [count].
    method : {"analytic", "inertial", "kalman"}
        Alignment method (:data:`ALIGNMENT_BLOCKS`).
    epochs : float, keyword-only
        Filter epochs per trial (Kalman) [count].
    per_block : int, keyword-only, optional
        Trials per block (default: the library's for the method).
    workers : int, keyword-only
        Worker processes sharing the trials [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate
    """
    default_block, bytes_per = ALIGNMENT_BLOCKS[method]
    workers = max(int(workers), 1)
    block = bytes_per * min(float(trials), float(per_block or default_block)) * float(samples)
    estimate = IMU_TRIAL_SAMPLE.estimate(float(trials) * float(samples), what=what, seconds_factor=1.0 / workers, extra_bytes=workers * block + (workers - 1) * IMU_TRIAL_SAMPLE.fixed_bytes)
    if method == "kalman":  # the filter runs once per epoch: short epochs cost more than the samples
        filtering = KALMAN_EPOCH.estimate(float(trials) * float(epochs), what=what, seconds_factor=1.0 / workers)
        estimate = Estimate(estimate.seconds + filtering.seconds, estimate.memory + KALMAN_EPOCH_BYTES * float(epochs), what)
    return estimate


#: Symbolic one-step error series through weight 16 (exact increment, error and drift series of a
#: registry algorithm, cold): time [s] and peak memory [bytes], measured by
#: ``benchmarks/bench_budget.py``; each weight more multiplies them by the factors below.
SERIES_AT_16 = (65.0, 3.5e8)
SERIES_GROWTH = (2.7, 1.7)


def series_derivation(max_weight, *, what: str) -> Estimate:
    """Estimate of deriving the symbolic error series of an algorithm through ``max_weight`` (cold).

    The work grows geometrically with the weight (the words of the exact
    increment multiply), and hardly with the algorithm; weights up to 11 take
    under a second.  A cached result costs nothing, but the estimate is that of
    the first derivation, so that a request never depends on what happens to
    be cached.

    Parameters
    ----------
    max_weight : int
        Highest weight (power of h) of the series [count].
    what : str, keyword-only
        The request in the user's terms.

    Returns
    -------
    Estimate

    Examples
    --------
    >>> round(series_derivation(7, what="").seconds, 3) < 0.1, format_seconds(series_derivation(20, what="").seconds)
    (True, '3.45e+03 s')
    """
    k = float(max_weight) - 16.0
    seconds = SERIES_AT_16[0] * SERIES_GROWTH[0] ** k
    memory = max(SERIES_AT_16[1] * SERIES_GROWTH[1] ** k, 1e8)
    return Estimate(seconds, memory, what)
