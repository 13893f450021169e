"""Chunked, reproducible Monte Carlo of a scalar error.

The unit of randomness is a *block* of trials.  Block ``i`` draws from the
``i``-th child of the root :class:`numpy.random.SeedSequence` (the child that
``SeedSequence.spawn`` would give, built directly from the spawn key), and
contributes one row of sums to the result.  Chunks are only groups of whole
blocks handed to a worker, and the rows are combined with the exactly rounded
:func:`math.fsum`, integer histogram counts and the errors themselves (whose
order statistics are the quantiles, :mod:`.quantiles`), so the result is bit-identical
for any chunk size, any number of workers and any executor (serial,
:class:`concurrent.futures.ProcessPoolExecutor`, or a ``dask.distributed``
``Client``).

A *kernel* is a picklable callable ``kernel(n_trials, rng)`` returning either
an error array of shape ``(n_trials, n_steps)`` or a pair ``(errors, aux)``
with ``aux`` of shape ``(n_trials, k)`` (per-trial side quantities whose means
are reported).  A trial is the independent unit: the samples inside a trial
may be correlated (a rocking time series), so the standard errors are computed
from the per-trial means ("batch means"), which is valid in both cases.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from . import verdicts
from .quantiles import sample_quantiles
from .validation import as_array, as_int, levels, positive
from .verdicts import Verdict

__all__ = ["MonteCarloResult", "run", "summarise", "block_output", "collect", "root_seed_sequence", "block_seed", "map_tasks", "process_pool", "ControlFit", "fit_controls", "controlled", "combine"]

#: normal quantile of the two-sided 95 % interval
Z95 = 1.959963984540054
#: default quantile levels reported
QUANTILES = (0.005, 0.025, 0.05, 0.25, 0.5, 0.75, 0.95, 0.975, 0.995)

_STATS = ("sum_mean", "sum_mean2", "sum_ms", "sum_ms2", "sum_ms_mean")


@dataclass(frozen=True)
class MonteCarloResult:
    """Summary of a Monte Carlo run.

    Attributes
    ----------
    n_trials : int
        Independent trials [count].
    n_samples : int
        Error samples (trials × steps) [count].
    mean : float
        Sample mean of the error (bias) [error units].
    mean_ci : tuple of float
        95 % interval of the mean [error units].
    mse : float
        Mean square of the error [error units²].
    mse_std_error : float
        Standard error of ``mse`` (from per-trial means) [error units²].
    rms : float
        ``√mse`` [error units].
    rms_ci : tuple of float
        95 % interval of the rms, ``√`` of the interval of ``mse`` [error units].
    quantiles : dict
        Level → error quantile [error units]: the order statistic of the errors
        (:func:`strapdown.analysis.core.quantiles.sample_quantiles`).
    minimum, maximum : float
        Extreme errors [error units].
    aux_mean : tuple of float
        Per-trial side quantities averaged over trials.
    histogram : tuple
        ``(edges, counts, underflow, overflow)``: for display (quantiles come from the errors themselves).
    aux_std_error : tuple of float
        Standard error of each entry of ``aux_mean`` (from the per-trial values,
        which are independent across trials).
    quantile_intervals : dict
        Level → ``(low, high)``, the 95 % interval of the quantile (NaN where the samples do not reach).
    """

    n_trials: int
    n_samples: int
    mean: float
    mean_ci: tuple
    mse: float
    mse_std_error: float
    rms: float
    rms_ci: tuple
    quantiles: dict
    minimum: float
    maximum: float
    aux_mean: tuple = ()
    histogram: tuple = field(default=(), repr=False, compare=False)
    aux_std_error: tuple = ()
    quantile_intervals: dict = field(default_factory=dict)

    def mean_agrees(self, reference: float, margin: float, *, what: str = "the reference", level: float = 0.95) -> Verdict:
        """Is the mean error within ``±margin`` of ``reference``? TOST from the per-trial means (:func:`.verdicts.equivalence`).

        Parameters
        ----------
        reference : float
            The value it should equal (a theory) [error units].
        margin : float
            The equivalence margin, > 0 [error units].
        what : str, keyword-only
            The reference's name in the criterion.
        level : float, keyword-only
            Confidence of the two-sided interval.

        Returns
        -------
        Verdict
        """
        se = (self.mean_ci[1] - self.mean_ci[0]) / (2.0 * Z95)
        text = f"mean within ±{margin:.3g} of {what} (TOST, {level:.0%})"
        return verdicts.equivalence(self.mean, se, self.n_trials, reference=reference, margin=margin, criterion=text, level=level)

    def rms_agrees(self, reference: float, relative_margin: float, *, what: str = "the reference", level: float = 0.95) -> Verdict:
        """Is the rms within ``relative_margin`` of ``reference``? TOST on the mean square (:func:`.verdicts.rms_equivalence`).

        Parameters
        ----------
        reference : float
            The rms it should equal (a theory, a budget) [error units].
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
        return verdicts.rms_equivalence(self.mse, self.mse_std_error, self.n_trials, reference=reference, relative_margin=relative_margin, criterion=text, level=level)

    def bound_holds(self, bound: float, *, what: str = "the bound", level: float = 0.95) -> Verdict:
        """Does the rms stay at or below ``bound``? One-sided test on the mean square (:func:`.verdicts.mean_square_within`).

        Parameters
        ----------
        bound : float
            A claimed upper bound of the rms, > 0 [error units].
        what : str, keyword-only
            The bound's name in the criterion.
        level : float, keyword-only
            Confidence of the two-sided interval (the test is one-sided at (1 − level)/2).

        Returns
        -------
        Verdict
            ``"yes"`` as :meth:`covers` says ``"holds"``, ``"no"`` as it says
            ``"fails"``, else ``"not resolved"`` with the trials needed.
        """
        text = f"rms at most {what} (one-sided, {level:.0%} interval)"
        return verdicts.mean_square_within(self.mse, self.mse_std_error, self.n_trials, high=bound, criterion=text, margin=bound, level=level)

    def covers(self, bound: float) -> str:
        """Classify ``bound`` against the rms (the words of :meth:`bound_holds`).

        Parameters
        ----------
        bound : float
            A claimed upper bound of the rms [error units].

        Returns
        -------
        str
            ``"holds"`` (upper end of the 95 % interval ≤ bound), ``"fails"``
            (lower end > bound) or ``"undecided"``.
        """
        if self.rms_ci[1] <= bound:
            return "holds"
        if self.rms_ci[0] > bound:
            return "fails"
        return "undecided"


def root_seed_sequence(rng) -> np.random.SeedSequence:
    """The root :class:`~numpy.random.SeedSequence` of a run.

    Parameters
    ----------
    rng : int, SeedSequence, Generator or None
        An int (the seed, ≥ 0), a SeedSequence (used as is), a Generator (128
        bits are drawn from it, so the run is a deterministic function of its
        state) or None (fresh entropy).

    Returns
    -------
    numpy.random.SeedSequence

    Raises
    ------
    ValueError
        For a negative seed.
    TypeError
        For anything else.
    """
    if isinstance(rng, np.random.SeedSequence):
        return rng
    if isinstance(rng, np.random.Generator):
        return np.random.SeedSequence(rng.integers(0, 2**63, size=2, dtype=np.uint64).tolist())
    if rng is None:
        return np.random.SeedSequence()
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        if rng < 0:
            raise ValueError(f"Expected `rng` seed >= 0, got {rng}")
        return np.random.SeedSequence(int(rng))
    raise TypeError(f"Expected `rng` to be a numpy Generator, SeedSequence, int or None, got {type(rng).__name__}")


def block_seed(root: np.random.SeedSequence, index: int) -> np.random.SeedSequence:
    """The ``index``-th child of ``root``, identical to ``root.spawn(index + 1)[index]``.

    Parameters
    ----------
    root : numpy.random.SeedSequence
        The root of the run.
    index : int
        Block number [count], ≥ 0.

    Returns
    -------
    numpy.random.SeedSequence
    """
    return np.random.SeedSequence(root.entropy, spawn_key=tuple(root.spawn_key) + (int(index),), pool_size=root.pool_size)


@dataclass(frozen=True)
class _Chunk:
    """Work item: the kernel's outputs on blocks ``[first, last)`` of a run (picklable for process pools and dask)."""

    kernel: Callable
    entropy: object
    spawn_key: tuple
    pool_size: int
    n_trials: int
    trials_per_block: int
    first: int
    last: int

    def __call__(self):
        root = np.random.SeedSequence(self.entropy, spawn_key=self.spawn_key, pool_size=self.pool_size)
        out = []
        for b in range(self.first, self.last):
            n = min(self.trials_per_block, self.n_trials - b * self.trials_per_block)
            out.append(block_output(self.kernel(n, np.random.default_rng(block_seed(root, b))), n))
        return out


def block_output(output, n_trials: int) -> tuple:
    """A kernel's output on one block as ``(errors, aux)``: ``(n, n_steps)`` and ``(n, k)`` or None.

    Parameters
    ----------
    output : array_like or tuple
        ``errors`` or ``(errors, aux)`` as a kernel returns them.
    n_trials : int
        Trials of the block [count].

    Returns
    -------
    tuple
    """
    errors, aux = output if isinstance(output, tuple) else (output, None)
    errors = np.asarray(errors, dtype=float).reshape(n_trials, -1)
    return errors, (None if aux is None else np.asarray(aux, dtype=float).reshape(n_trials, -1))


def _block_rows(errors: np.ndarray, aux):
    """The sums a block contributes: statistics of the per-trial means, and of the auxiliaries."""
    m = errors.mean(axis=1)
    ms = np.einsum("ij,ij->i", errors, errors) / errors.shape[1]
    row = (m.sum(), (m * m).sum(), ms.sum(), (ms * ms).sum(), (ms * m).sum())
    aux_row = None if aux is None else np.concatenate([_column_sums(aux), np.einsum("ij,ij->j", aux, aux)])
    return row, aux_row


def _column_sums(a: np.ndarray) -> np.ndarray:
    """``a.sum(axis=0)`` of a C-ordered ``(n, k)`` array, the same sums in the same order.

    With ``k ≥ 2`` contiguous columns numpy's reduction adds the rows one after
    another (an inner loop of ``k`` per row, several times slower than a pass
    down the columns); :func:`numpy.add.accumulate` makes the same additions in
    the same order in one pass.  One column is summed pairwise by ``sum``:
    it, and any other layout, keeps ``sum``.
    """
    if a.ndim == 2 and a.shape[0] and a.shape[1] >= 2 and a.flags.c_contiguous:
        return np.add.accumulate(a, axis=0)[-1]
    return a.sum(axis=0)


def map_tasks(executor, tasks: Sequence[Callable], *, progress: bool = False, desc: str = "Monte Carlo") -> list:
    """Run zero-argument callables, serially (``executor=None``) or on an executor, in order.

    Parameters
    ----------
    executor : Executor, dask Client or None
        A :class:`concurrent.futures.Executor` or a ``dask.distributed.Client``
        (anything with ``submit`` and ``gather``); None runs them here.
    tasks : sequence of callable
        Picklable zero-argument callables.
    progress : bool, keyword-only
        Progress over the tasks on stderr (:func:`strapdown.analysis.core.progress.bar`).
    desc : str, keyword-only
        Label of the bar.

    Returns
    -------
    list
        The results, in the order of ``tasks`` (whatever order they finish in).
    """
    if executor is None and not progress:  # here and silent: no bar to keep (a Monte Carlo of many small runs calls this per run)
        return [task() for task in tasks]
    from .progress import bar as progress_bar

    bar = progress_bar(total=len(tasks), desc=desc, enabled=progress)
    try:
        if executor is None:
            out = []
            for task in tasks:
                out.append(task())
                bar.update(1)
            return out
        if hasattr(executor, "gather") and hasattr(executor, "submit"):  # dask.distributed.Client
            from distributed import as_completed  # the client exists, so dask.distributed is installed

            # A task whose worker is lost is run again on another (the scheduler's allowed failures):
            # it draws from its own block seeds, so the rerun gives the same numbers.
            futures = [executor.submit(_call, task, pure=False) for task in tasks]
            for _ in as_completed(futures):  # progress as the cluster finishes tasks, in any order
                bar.update(1)
            return list(executor.gather(futures))
        futures = [executor.submit(_call, task) for task in tasks]
        out = []
        for f in futures:
            out.append(f.result())
            bar.update(1)
        return out
    finally:
        bar.close()


def _call(task):
    return task()


def _ignore_interrupt() -> None:
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


def process_pool(workers: int):
    """A :class:`concurrent.futures.ProcessPoolExecutor` whose workers leave Ctrl-C to the parent.

    On Ctrl-C the parent stops and reports it once; the workers, which ignore
    SIGINT, print no traceback of their own and end when the pool shuts down.

    Parameters
    ----------
    workers : int
        Worker processes [count], ≥ 1.

    Returns
    -------
    concurrent.futures.ProcessPoolExecutor
    """
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(as_int(workers, "workers", minimum=1), initializer=_ignore_interrupt)


def run(
    kernel: Callable,
    n_trials: int,
    *,
    rng=None,
    trials_per_block: int = 64,
    blocks_per_chunk: int = 16,
    executor=None,
    scale: float = 1.0,
    half_width: float = 20.0,
    n_bins: int = 8000,
    quantiles: Sequence[float] = QUANTILES,
    progress: bool = False,
) -> MonteCarloResult:
    """Run ``kernel`` on ``n_trials`` independent trials and summarise its errors.

    Parameters
    ----------
    kernel : callable
        ``kernel(n_trials, rng) -> errors (n_trials, n_steps)`` or ``(errors, aux)``.
    n_trials : int
        Number of independent trials [count], at least 2.
    rng : Generator, SeedSequence, int or None, keyword-only
        Root of the random streams.
    trials_per_block : int, keyword-only
        Trials per block [count] (the unit of randomness; changing it changes the draws).
    blocks_per_chunk : int, keyword-only
        Blocks per work item [count] (does not change the result).
    executor : Executor, dask Client or None, keyword-only
        Where chunks run (does not change the result).
    scale : float, keyword-only
        Error scale of the histogram [error units].
    half_width : float, keyword-only
        The histogram spans ``±half_width·scale`` [dimensionless].
    n_bins : int, keyword-only
        Histogram bins [count].
    quantiles : sequence of float, keyword-only
        Levels in (0, 1).
    progress : bool, keyword-only
        Progress bar over chunks on stderr.

    Returns
    -------
    MonteCarloResult

    Raises
    ------
    ValueError
        If ``n_trials < 2`` or a size is not positive.

    Examples
    --------
    >>> def kernel(n, rng):
    ...     return rng.standard_normal((n, 100))
    >>> a = run(kernel, 50, rng=1, trials_per_block=8, blocks_per_chunk=1)
    >>> b = run(kernel, 50, rng=1, trials_per_block=8, blocks_per_chunk=5)
    >>> a.rms == b.rms, a.rms_ci[0] < 1.0 < a.rms_ci[1]
    (True, True)
    """
    n_trials = as_int(n_trials, "n_trials", minimum=2)
    trials_per_block = as_int(trials_per_block, "trials_per_block", minimum=1)
    blocks_per_chunk = as_int(blocks_per_chunk, "blocks_per_chunk", minimum=1)
    n_bins = as_int(n_bins, "n_bins", minimum=2)
    scale = positive(scale, "scale")
    half_width = positive(half_width, "half_width")
    quantiles = levels(quantiles, "quantiles")
    root = root_seed_sequence(rng)
    n_blocks = -(-n_trials // trials_per_block)
    tasks = [
        _Chunk(kernel, root.entropy, tuple(root.spawn_key), root.pool_size, n_trials, trials_per_block, first, min(first + blocks_per_chunk, n_blocks))
        for first in range(0, n_blocks, blocks_per_chunk)
    ]
    blocks = [block for part in map_tasks(executor, tasks, progress=progress) for block in part]
    return summarise(blocks, scale=scale, half_width=half_width, n_bins=n_bins, quantiles=quantiles)


def summarise(blocks, *, scale: float = 1.0, half_width: float = 20.0, n_bins: int = 8000, quantiles: Sequence[float] = QUANTILES) -> MonteCarloResult:
    """Statistics of a kernel's outputs on consecutive blocks of trials.

    :func:`run` ends here; a caller that evaluates the same draws with several
    kernels (common random numbers, passed explicitly) summarises each
    kernel's outputs the same way.

    Parameters
    ----------
    blocks : sequence of tuple
        ``(errors, aux)`` per block, in block order (:func:`block_output`).
    scale, half_width, n_bins : float, float, int, keyword-only
        The histogram (for display), as in :func:`run`.
    quantiles : sequence of float, keyword-only
        Levels in (0, 1).

    Returns
    -------
    MonteCarloResult

    Raises
    ------
    ValueError
        For fewer than two trials.
    """
    errors = np.concatenate([e for e, _ in blocks])
    n_trials = errors.shape[0]
    if n_trials < 2:
        raise ValueError(f"Expected at least 2 trials, got {n_trials}")
    rows, aux_rows = zip(*(_block_rows(e, a) for e, a in blocks))
    rows = np.array(rows)
    sums = [math.fsum(rows[:, k]) for k in range(rows.shape[1])]
    counts = _histogram_counts(errors.ravel(), n_bins / (2.0 * half_width * scale), n_bins / 2.0 + 1.0, n_bins)
    aux_mean, aux_se = (), ()
    if aux_rows[0] is not None:
        aux = np.array(aux_rows)
        k = aux.shape[1] // 2
        aux_mean = tuple(math.fsum(aux[:, j]) / n_trials for j in range(k))
        aux_se = tuple(math.sqrt(max(math.fsum(aux[:, k + j]) / n_trials - m * m, 0.0) / (n_trials - 1)) for j, m in enumerate(aux_mean))
    q = sample_quantiles(errors, quantiles)
    summary = _summarise(n_trials, sums, counts, float(errors.min()), float(errors.max()), scale, half_width, n_bins, aux_mean)
    return replace(summary, aux_std_error=aux_se, quantiles={x.level: x.value for x in q}, quantile_intervals={x.level: (x.low, x.high) for x in q})


#: errors binned per pass of the histogram: the temporaries stay in cache (a long run bins many passes)
_HISTOGRAM_CHUNK = 1 << 16


def _histogram_counts(errors: np.ndarray, factor: float, offset: float, n_bins: int) -> np.ndarray:
    """Counts of ``errors · factor + offset`` clipped to ``[0, n_bins + 1]`` and truncated: underflow, ``n_bins`` bins, overflow.

    The errors are binned in passes of ``_HISTOGRAM_CHUNK`` (integer counts: the
    same for any passes).
    """
    counts = None
    for i in range(0, max(errors.size, 1), _HISTOGRAM_CHUNK):
        u = errors[i : i + _HISTOGRAM_CHUNK] * factor
        u += offset
        part = np.bincount(np.clip(u, 0.0, n_bins + 1.0, out=u).astype(np.int64), minlength=n_bins + 2)[: n_bins + 2]
        counts = part if counts is None else counts + part
    return counts


@dataclass(frozen=True)
class _CollectChunk:
    """Work item of :func:`collect`: the per-trial rows of blocks ``[first, last)``."""

    kernel: Callable
    entropy: object
    spawn_key: tuple
    pool_size: int
    n_trials: int
    trials_per_block: int
    first: int
    last: int

    def __call__(self):
        root = np.random.SeedSequence(self.entropy, spawn_key=self.spawn_key, pool_size=self.pool_size)
        rows = []
        for b in range(self.first, self.last):
            n = min(self.trials_per_block, self.n_trials - b * self.trials_per_block)
            out = np.asarray(self.kernel(n, np.random.default_rng(block_seed(root, b))), dtype=float)
            rows.append(out.reshape(n, -1))
        return np.concatenate(rows)


def collect(
    kernel: Callable,
    n_trials: int,
    *,
    rng=None,
    trials_per_block: int = 64,
    blocks_per_chunk: int = 16,
    executor=None,
    progress: bool = False,
) -> np.ndarray:
    """Run ``kernel`` on ``n_trials`` trials and return every trial's result, in trial order.

    The blocks and their seeds are those of :func:`run`, so the rows are
    bit-identical for any ``blocks_per_chunk``, executor and number of workers.
    Use it when the statistics wanted are not those :func:`run` summarises
    (for example exact percentiles of a per-trial peak).

    Parameters
    ----------
    kernel : callable
        ``kernel(n_trials, rng) -> array (n_trials, k)`` (or ``(n_trials,)``).
    n_trials : int
        Number of independent trials, at least 1.
    rng : Generator | SeedSequence | int | None
        Root of the random streams.
    trials_per_block : int
        Trials per block (the unit of randomness; changing it changes the draws).
    blocks_per_chunk : int
        Blocks per work item (does not change the result).
    executor : Executor | dask Client | None
        Where chunks run (does not change the result).
    progress : bool
        Progress over chunks on stderr (:func:`strapdown.analysis.core.progress.bar`).

    Returns
    -------
    ndarray, shape (n_trials, k)

    Raises
    ------
    ValueError
        If a size is not positive.

    Examples
    --------
    >>> def kernel(n, rng):
    ...     return rng.standard_normal((n, 2))
    >>> a = collect(kernel, 10, rng=3, trials_per_block=4, blocks_per_chunk=1)
    >>> b = collect(kernel, 10, rng=3, trials_per_block=4, blocks_per_chunk=3)
    >>> a.shape, bool((a == b).all())
    ((10, 2), True)
    """
    n_trials = as_int(n_trials, "n_trials", minimum=1)
    trials_per_block = as_int(trials_per_block, "trials_per_block", minimum=1)
    blocks_per_chunk = as_int(blocks_per_chunk, "blocks_per_chunk", minimum=1)
    root = root_seed_sequence(rng)
    n_blocks = -(-n_trials // trials_per_block)
    tasks = [
        _CollectChunk(kernel, root.entropy, tuple(root.spawn_key), root.pool_size, n_trials, trials_per_block, first, min(first + blocks_per_chunk, n_blocks))
        for first in range(0, n_blocks, blocks_per_chunk)
    ]
    return np.concatenate(map_tasks(executor, tasks, progress=progress))

@dataclass(frozen=True)
class ControlFit:
    """Control-variate coefficients fitted on a pilot sample.

    Attributes
    ----------
    intercepts : tuple of float
        Per value column, the pilot's controlled estimate of its mean [value units].
    coefficients : tuple of tuple of float
        Per value column, the coefficient of every control [value units per control unit];
        all zero for a column the controls do not help.
    variance_ratios : tuple of float
        Per value column, the mean square of the residuals out of sample
        (two-fold cross-fitting on the pilot) over the variance of the values,
        at most 1 [dimensionless].
    """

    intercepts: tuple
    coefficients: tuple
    variance_ratios: tuple


def fit_controls(values, controls) -> ControlFit:
    """Least-squares control-variate coefficients from a pilot sample.

    The controls must be centred at their exact means.  Applied to an
    independent sample (not the pilot), ``values − coefficients · controls``
    has the same mean as ``values`` (an unbiased estimator whose standard
    error is the ordinary one of independent draws) and, at the fitted
    coefficients, the smallest variance; a column whose fitted residual
    variance is not below its variance keeps zero coefficients (the plain
    estimator).

    Parameters
    ----------
    values : array_like, shape (n, k)
        Pilot draws of the ``k`` quantities whose means are wanted [value units].
    controls : array_like, shape (n, p)
        The same draws' controls, centred at their exact means [control units].

    Returns
    -------
    ControlFit

    Raises
    ------
    ValueError
        If the shapes disagree, an entry is not finite or ``n < 2p + 4``.

    References
    ----------
    Lavenberg, S. S. & Welch, P. D. (1981), A perspective on the use of control
    variables to increase the efficiency of Monte Carlo simulations,
    *Management Science* 27(3), 322–335; Glasserman, P. (2004), *Monte Carlo
    Methods in Financial Engineering*, Springer, sec. 4.1 (pilot coefficients).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> x = rng.standard_normal(1000)
    >>> fit = fit_controls((x + x**2)[:, None], np.stack([x, x**2 - 1.0], axis=1))
    >>> [round(c, 12) for c in fit.coefficients[0]], round(fit.intercepts[0], 12)
    ([1.0, 1.0], 1.0)
    """
    y = as_array(values, "values")
    x = as_array(controls, "controls")
    if y.ndim != 2 or x.ndim != 2 or y.shape[0] != x.shape[0]:
        raise ValueError(f"Expected `values` (n, k) and `controls` (n, p) with the same n, got {y.shape} and {x.shape}")
    n, p = x.shape
    if n < 2 * p + 4:
        raise ValueError(f"Expected at least 2p + 4 = {2 * p + 4} pilot draws, got {n}")
    scale = x.std(axis=0)
    scale[scale == 0.0] = 1.0
    design = np.concatenate([np.ones((n, 1)), x / scale], axis=1)
    # normal equations of the two halves (even and odd draws) and of the whole pilot
    halves = [(design[h::2], y[h::2]) for h in (0, 1)]
    grams = [(_products(d, d), _products(d, v)) for d, v in halves]
    gram, rhs = grams[0][0] + grams[1][0], grams[0][1] + grams[1][1]
    solution = _solve(gram, rhs)
    solution += _solve(gram, _products(design, y - combine(design, solution)))  # one step of refinement
    # the residual variance out of sample (two-fold cross-fitting): in-sample residuals flatter heavy tails
    held_out = np.empty_like(y)
    for h in (0, 1):
        d, v = halves[1 - h]
        held_out[1 - h :: 2] = v - combine(d, _solve(*grams[h]))
    intercepts, coefficients, ratios = [], [], []
    for j in range(y.shape[1]):
        var = float(y[:, j].var())
        ratio = float(np.mean(held_out[:, j] ** 2)) / var if var > 0.0 else 0.0
        if ratio < 1.0:
            intercepts.append(float(solution[0, j]))
            coefficients.append(tuple(float(c) for c in solution[1:, j] / scale))
            ratios.append(ratio)
        else:
            intercepts.append(float(y[:, j].mean()))
            coefficients.append((0.0,) * p)
            ratios.append(1.0)
    return ControlFit(tuple(intercepts), tuple(coefficients), tuple(ratios))


def combine(columns, coefficients) -> np.ndarray:
    """``columns @ coefficients`` for a tall matrix of few columns, in blocks of rows.

    The same product, in blocks small enough that BLAS keeps them on one
    thread: for a tall, thin matrix its threads cost more than they save
    (several times more on a busy machine).

    Parameters
    ----------
    columns : array_like, shape (n, p)
        The columns (for example centred controls) [any units].
    coefficients : array_like, shape (p,) or (p, k)
        Their weights [value units per column unit].

    Returns
    -------
    ndarray, shape (n,) or (n, k)

    >>> combine(np.array([[1.0, 2.0], [3.0, 4.0]]), np.array([1.0, -1.0]))
    array([-1., -1.])
    """
    a = np.asarray(columns, dtype=float)
    c = np.asarray(coefficients, dtype=float)
    flat = c.ndim == 1
    c = c.reshape(c.shape[0], -1)
    if a.ndim != 2 or a.shape[1] != c.shape[0]:
        raise ValueError(f"Expected `columns` (n, p) and `coefficients` (p, ...) with the same p, got {a.shape} and {np.shape(coefficients)}")
    out = np.empty((a.shape[0], c.shape[1]))
    for i in range(0, a.shape[0], _ROWS):
        np.matmul(a[i : i + _ROWS], c, out=out[i : i + _ROWS])
    return out[:, 0] if flat else out


#: rows per block of a product of tall matrices (small enough for one BLAS thread)
_ROWS = 1024


def _products(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``aᵀ b`` summed over blocks of ``_ROWS`` rows (small products: BLAS stays on one thread)."""
    out = np.zeros((a.shape[1], b.shape[1]))
    for i in range(0, a.shape[0], _ROWS):
        out += a[i : i + _ROWS].T @ b[i : i + _ROWS]
    return out


def _solve(gram: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve the normal equations; a control without spread (a zero column) gets a zero coefficient."""
    gram = gram.copy()
    gram.flat[:: gram.shape[0] + 1] += 1e-300  # the diagonal
    return np.linalg.solve(gram, rhs)


def controlled(result: MonteCarloResult, *, offsets, mean_column: int = 0, square_column: int = 1) -> MonteCarloResult:
    """``result`` with its mean and mean square replaced by control-variate estimates.

    The kernel of ``result`` returns in two auxiliary columns, per trial, the
    mean of ``error − control term − offsets[0]`` and of
    ``error² − control term − offsets[1]``, with control terms of zero mean and
    coefficients fixed before the run (from an independent pilot,
    :func:`fit_controls`).  Their means plus the offsets estimate the mean and
    the mean square of the error without bias, and their standard errors come
    from the independent trials; the offsets (the pilot's estimates) only keep
    the sums of squares free of cancellation.  The histogram, quantiles and
    extremes stay those of the raw errors.

    Parameters
    ----------
    result : MonteCarloResult
        A run whose kernel returned the controlled columns as auxiliaries.
    offsets : tuple of float
        The constants subtracted in the kernel [error units, error units²].
    mean_column, square_column : int
        Auxiliary columns of the controlled error and squared error.

    Returns
    -------
    MonteCarloResult

    Raises
    ------
    ValueError
        If the result has no such auxiliary columns.
    """
    if max(mean_column, square_column) >= len(result.aux_std_error):
        raise ValueError(f"Expected auxiliary columns {mean_column} and {square_column}, got {len(result.aux_std_error)} columns")
    mean = offsets[0] + result.aux_mean[mean_column]
    mse = offsets[1] + result.aux_mean[square_column]
    se_mean, se_mse = result.aux_std_error[mean_column], result.aux_std_error[square_column]
    lo, hi = max(mse - Z95 * se_mse, 0.0), max(mse + Z95 * se_mse, 0.0)
    return replace(
        result,
        mean=mean,
        mean_ci=(mean - Z95 * se_mean, mean + Z95 * se_mean),
        mse=mse,
        mse_std_error=se_mse,
        rms=math.sqrt(max(mse, 0.0)),
        rms_ci=(math.sqrt(lo), math.sqrt(hi)),
    )


def _summarise(n, sums, counts, lo, hi, scale, half_width, n_bins, aux_mean) -> MonteCarloResult:
    s_m, s_m2, s_ms, s_ms2, _ = sums
    mean = s_m / n
    mse = s_ms / n
    var_m = max(s_m2 / n - mean * mean, 0.0) * n / (n - 1)
    var_ms = max(s_ms2 / n - mse * mse, 0.0) * n / (n - 1)
    se_mean, se_mse = math.sqrt(var_m / n), math.sqrt(var_ms / n)
    mse_lo, mse_hi = max(mse - Z95 * se_mse, 0.0), mse + Z95 * se_mse
    edges = np.linspace(-half_width * scale, half_width * scale, n_bins + 1)
    inner = counts[1:-1]
    total = int(counts.sum())
    n_samples = total
    return MonteCarloResult(
        n_trials=n,
        n_samples=n_samples,
        mean=mean,
        mean_ci=(mean - Z95 * se_mean, mean + Z95 * se_mean),
        mse=mse,
        mse_std_error=se_mse,
        rms=math.sqrt(mse),
        rms_ci=(math.sqrt(mse_lo), math.sqrt(mse_hi)),
        quantiles={},
        minimum=lo,
        maximum=hi,
        aux_mean=aux_mean,
        histogram=(edges, inner, int(counts[0]), int(counts[-1])),
    )
