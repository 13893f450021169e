"""Chunked, reproducible Monte Carlo of a scalar error.

The unit of randomness is a *block* of trials.  Block ``i`` draws from the
``i``-th child of the root :class:`numpy.random.SeedSequence` (the child that
``SeedSequence.spawn`` would give, built directly from the spawn key), and
contributes one row of sums to the result.  Chunks are only groups of whole
blocks handed to a worker, and the rows are combined with the exactly rounded
:func:`math.fsum` and integer histogram counts, so the result is bit-identical
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
from dataclasses import dataclass, field

import numpy as np

from .validation import as_int, positive

__all__ = ["MonteCarloResult", "run", "collect", "root_seed_sequence", "block_seed", "map_tasks", "process_pool"]

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
        Level → error quantile [error units] (NaN if it falls outside the histogram).
    minimum, maximum : float
        Extreme errors [error units].
    aux_mean : tuple of float
        Per-trial side quantities averaged over trials.
    histogram : tuple
        ``(edges, counts, underflow, overflow)``.
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

    def covers(self, bound: float) -> str:
        """Classify ``bound`` against the rms.

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
    """Work item: blocks ``[first, last)`` of a run (picklable for process pools and dask)."""

    kernel: Callable
    entropy: object
    spawn_key: tuple
    pool_size: int
    n_trials: int
    trials_per_block: int
    first: int
    last: int
    scale: float
    half_width: float
    n_bins: int

    def __call__(self):
        root = np.random.SeedSequence(self.entropy, spawn_key=self.spawn_key, pool_size=self.pool_size)
        rows, aux_rows = [], []
        counts = np.zeros(self.n_bins + 2, dtype=np.int64)
        lo, hi = math.inf, -math.inf
        for b in range(self.first, self.last):
            n = min(self.trials_per_block, self.n_trials - b * self.trials_per_block)
            out = self.kernel(n, np.random.default_rng(block_seed(root, b)))
            errors, aux = out if isinstance(out, tuple) else (out, None)
            errors = np.asarray(errors, dtype=float).reshape(n, -1)
            m = errors.mean(axis=1)
            ms = np.einsum("ij,ij->i", errors, errors) / errors.shape[1]
            rows.append((m.sum(), (m * m).sum(), ms.sum(), (ms * ms).sum(), (ms * m).sum()))
            if aux is not None:
                aux_rows.append(np.asarray(aux, dtype=float).reshape(n, -1).sum(axis=0))
            lo, hi = min(lo, float(errors.min())), max(hi, float(errors.max()))
            u = errors.ravel() * (self.n_bins / (2.0 * self.half_width * self.scale))
            u += self.n_bins / 2.0 + 1.0
            idx = np.clip(u, 0.0, self.n_bins + 1.0).astype(np.int64)
            counts += np.bincount(idx, minlength=self.n_bins + 2)[: self.n_bins + 2]
        aux_arr = np.array(aux_rows) if aux_rows else None
        return np.array(rows), aux_arr, counts, lo, hi


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
        Progress bar over the tasks on stderr.
    desc : str, keyword-only
        Label of the bar.

    Returns
    -------
    list
        The results, in the order of ``tasks`` (whatever order they finish in).
    """
    import sys

    from tqdm import tqdm

    bar = tqdm(total=len(tasks), desc=desc, file=sys.stderr, disable=not progress, leave=False)
    try:
        if executor is None:
            out = []
            for task in tasks:
                out.append(task())
                bar.update(1)
            return out
        if hasattr(executor, "gather") and hasattr(executor, "submit"):  # dask.distributed.Client
            futures = [executor.submit(_call, task, pure=False) for task in tasks]
            out = executor.gather(futures)
            bar.update(len(tasks))
            return list(out)
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
    root = root_seed_sequence(rng)
    n_blocks = -(-n_trials // trials_per_block)
    tasks = [
        _Chunk(kernel, root.entropy, tuple(root.spawn_key), root.pool_size, n_trials, trials_per_block, first, min(first + blocks_per_chunk, n_blocks), scale, half_width, n_bins)
        for first in range(0, n_blocks, blocks_per_chunk)
    ]
    parts = map_tasks(executor, tasks, progress=progress)
    rows = np.concatenate([p[0] for p in parts])
    counts = np.sum([p[2] for p in parts], axis=0)
    lo = min(p[3] for p in parts)
    hi = max(p[4] for p in parts)
    sums = [math.fsum(rows[:, k]) for k in range(rows.shape[1])]
    aux_parts = [p[1] for p in parts if p[1] is not None]
    aux_mean = ()
    if aux_parts:
        aux = np.concatenate(aux_parts)
        aux_mean = tuple(math.fsum(aux[:, k]) / n_trials for k in range(aux.shape[1]))
    return _summarise(n_trials, sums, counts, lo, hi, scale, half_width, n_bins, quantiles, aux_mean)


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
        tqdm bar over chunks on stderr.

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


def _summarise(n, sums, counts, lo, hi, scale, half_width, n_bins, levels, aux_mean) -> MonteCarloResult:
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
    cdf = np.concatenate([[counts[0]], counts[0] + np.cumsum(inner)]) / total
    q = {}
    for level in levels:
        if not 0.0 < level < 1.0:
            raise ValueError(f"Expected quantile levels in (0, 1), got {level}")
        if level <= cdf[0] or level > cdf[-1]:
            q[float(level)] = math.nan
            continue
        i = int(np.searchsorted(cdf, level, side="left"))  # cdf[i-1] < level <= cdf[i]
        frac = (level - cdf[i - 1]) / (cdf[i] - cdf[i - 1])
        q[float(level)] = float(edges[i - 1] + frac * (edges[i] - edges[i - 1]))
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
        quantiles=q,
        minimum=lo,
        maximum=hi,
        aux_mean=aux_mean,
        histogram=(edges, inner, int(counts[0]), int(counts[-1])),
    )
