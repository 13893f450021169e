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

>>> est = CONING_STEP.estimate(1e9, what="1e9 simulator steps")
>>> check(est, Limits(seconds=60.0, memory=1e9))
Traceback (most recent call last):
...
strapdown.analysis.core.budget.BudgetExceeded: 1e9 simulator steps: estimated memory 96 GB exceeds the limit of 1 GB (`memory_limit`)
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
    "format_bytes",
    "format_seconds",
    "CONING_STEP",
    "MONTE_CARLO_SAMPLE",
    "MULTISTAGE_STEP",
    "AUTOCORRELATION_TERM",
    "coning_simulation",
    "monte_carlo",
    "multistage",
    "autocorrelation_sums",
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
            text = f"estimated memory {format_bytes(estimate.memory)} exceeds the limit of {format_bytes(limits.memory)} (`memory_limit`)"
        else:
            text = f"estimated time {format_seconds(estimate.seconds)} exceeds the limit of {format_seconds(limits.seconds)} (`time_limit`)"
        super().__init__(f"{estimate.what}: {text}")


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
    """
    limits = Limits() if limits is None else limits
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
        memory = self.fixed_bytes + as_float(extra_bytes, "extra_bytes") + (per_byte * units if per_byte else 0.0)
        return Estimate(seconds, memory, what)


# ---------------------------------------------------------------- measured hot paths
#: Parallel-computation simulator, per algorithm step of a light algorithm (two samples, one term):
#: time, times (time + error + attitude) kept per step.  Heavier algorithms scale it (:func:`coning_simulation`).
CONING_STEP = CostModel(seconds_per_unit=6e-7, bytes_per_unit=96.0, fixed_seconds=0.5)
#: Azimuth Monte Carlo, per rocking sample (chunked: the working set does not grow with the run, but
#: every error is kept for its order statistics, the quantiles: 8 bytes, and 8 more for the partial
#: sort); the fixed time is the symbolic second-order theory derived once per process.
MONTE_CARLO_SAMPLE = CostModel(seconds_per_unit=1.2e-7, bytes_per_unit=16.0, fixed_seconds=6.0, fixed_bytes=2.5e8)
#: Multistage cascade (section 5 of Plotnikov 1999), per integration step (a Python loop per step).
MULTISTAGE_STEP = CostModel(seconds_per_unit=3e-5, bytes_per_unit=1.2e3, fixed_seconds=0.5)
#: Autocorrelation sum of a sample mean's variance, per lag term (arrays of the lags).
AUTOCORRELATION_TERM = CostModel(seconds_per_unit=5e-8, bytes_per_unit=48.0)


def coning_simulation(steps, *, window: int, degree_sum: int, velocity: bool, chunk_steps: int, what: str) -> Estimate:
    """Estimate of a parallel-computation run (``strapdown.analysis.coning.simulator.simulate``).

    Time grows with the samples per step (the increment window) and with the
    total degree of the algorithm's terms; dual numbers (velocity runs) cost about
    four times more per step (five is assumed) and keep three times more per step.  The increments
    of one chunk of ``chunk_steps`` steps are held at once.

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
    chunk = min(float(steps), float(chunk_steps)) * window * 3 * 8 * 4 * (2 if velocity else 1)
    return CONING_STEP.estimate(steps, what=what, seconds_factor=per_step * dual, bytes_factor=3.0 if velocity else 1.0, extra_bytes=chunk)


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
