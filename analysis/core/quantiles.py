"""Quantiles of Monte Carlo errors from the samples themselves: order statistics and their intervals.

A level-p quantile is the order statistic ``x_(⌈pM⌉)`` of the M samples (the
inverse of the empirical distribution function, numpy's ``"inverted_cdf"``): a
value some sample has, equal to the common value of identical samples.  Its
95 % interval depends on how the samples were drawn:

* one sample per independent trial: the distribution-free interval of two
  order statistics ``[x_(l), x_(u)]``, with ranks from the binomial law of the
  number of samples below the true quantile, ``P(l ≤ B < u) ≥ 0.95``,
  ``B ~ Bin(M, p)`` (David & Nagaraja, *Order Statistics*, § 7.1);
* a time series per trial (correlated samples): Woodruff's interval, the
  quantiles at ``p ∓ z·se`` where ``se`` is the standard error of the empirical
  distribution function at the estimate computed from the per-trial fractions
  below it (the trials are independent, the samples inside one are not).

An end whose rank falls outside ``1 … M`` is unknown (NaN): too few samples
resolve that tail.

Public API
----------
sample_quantiles
    Quantiles and their 95 % intervals of an ``(n_trials, n_steps)`` array of errors.
SampleQuantile
    One level: the value and its interval.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from .validation import levels as as_levels

__all__ = ["SampleQuantile", "sample_quantiles"]

#: most ranks taken by one partial sort (``np.partition``); more are read from a full sort (the same order statistics)
_PARTITION_RANKS = 8

#: normal quantile of the two-sided 95 % interval
_Z95 = 1.959963984540054


class SampleQuantile(NamedTuple):
    """A quantile of the samples and its 95 % interval [units of the samples].

    Attributes
    ----------
    level : float
        Probability level p in (0, 1).
    value : float
        The order statistic ``x_(⌈pM⌉)``.
    low, high : float
        Ends of the 95 % interval (NaN where the samples do not reach).
    """

    level: float
    value: float
    low: float
    high: float


def _binomial_ranks(m: int, p: float) -> tuple:
    """1-based ranks ``(l, u)`` with ``P(l ≤ B < u) ≥ 0.95`` for ``B ~ Bin(m, p)``, as equal-tailed as the law allows."""
    ((lo, hi),) = _binomial_rank_table(m, (p,))
    return lo, hi


def _binomial_rank_table(m: int, ps) -> list:
    """:func:`_binomial_ranks` at every level of ``ps``, from one vectorised call of ``binom.ppf`` (the same values, elementwise)."""
    from scipy.stats import binom

    p = np.asarray(ps, dtype=float)
    # P(B ≤ lo) ≥ 0.025: x_(lo) is below x_p with probability ≤ 0.025 … (lo may be 0: unknown)
    # … and x_(hi) above it with probability ≤ 0.025 (hi may be m + 1: unknown)
    ends = binom.ppf(np.array([[0.025], [0.975]]), m, p[None, :])
    return [(int(lo), int(hi) + 1) for lo, hi in zip(ends[0], ends[1])]


def sample_quantiles(errors, levels: Sequence[float], *, independent: bool | None = None) -> tuple:
    """Quantiles of Monte Carlo errors with their 95 % intervals, from order statistics.

    Parameters
    ----------
    errors : array_like
        ``(n_trials, n_steps)`` errors; trials independent, steps of one trial possibly correlated.
    levels : sequence of float
        Levels in (0, 1).
    independent : bool, optional
        Whether all samples are independent (default: when ``n_steps == 1``).

    Returns
    -------
    tuple of SampleQuantile
        One per level, in order.

    Raises
    ------
    ValueError
        For an empty array, a non-finite error or a level outside (0, 1).

    Examples
    --------
    Identical trials give their common value, with a degenerate interval:

    >>> q = sample_quantiles(np.full((10, 1), 0.25), [0.5, 0.995])
    >>> [(x.value, x.low) for x in q]
    [(0.25, 0.25), (0.25, 0.25)]
    >>> bool(np.isnan(q[1].high))  # ten trials do not reach the 0.995 tail
    True
    """
    e = np.asarray(errors, dtype=float)
    if e.ndim == 1:
        e = e[:, None]
    if e.ndim != 2 or e.size == 0:
        raise ValueError(f"Expected `errors` of shape (n_trials, n_steps) with at least one sample, got shape {e.shape}")
    if not np.all(np.isfinite(e)):
        raise ValueError("Expected finite `errors`, got NaN or infinity")
    ps = list(as_levels(levels, "levels"))
    n_trials, n_steps = e.shape
    m = e.size
    flat = e.ravel()
    iid = (n_steps == 1) if independent is None else bool(independent)

    def rank(p):  # 1-based rank of the order statistic at level p
        return min(max(math.ceil(p * m - 1e-12), 1), m)

    points = {}
    for p in ps:
        points[p] = rank(p)
    if not ps:
        return ()
    # independent samples: the interval ranks are known before any sorting, so one partial sort serves them all
    intervals = dict(zip(ps, _binomial_rank_table(m, ps))) if iid else {}
    wanted = set(points.values()) | {r for pair in intervals.values() for r in pair if 1 <= r <= m}
    sorted_at = _order_statistics(flat, wanted)
    out = []
    for p in ps:
        value = sorted_at[points[p]]
        if iid:
            lo_r, hi_r = intervals[p]
        else:
            below = np.mean(e <= value, axis=1)  # per-trial fraction below the estimate
            se = float(np.std(below, ddof=1)) / math.sqrt(n_trials) if n_trials > 1 else math.inf
            lo_p, hi_p = p - _Z95 * se, p + _Z95 * se
            lo_r = math.ceil(lo_p * m - 1e-12) if lo_p > 0 else 0
            hi_r = math.ceil(hi_p * m - 1e-12) if hi_p < 1 else m + 1
            lo_r, hi_r = min(lo_r, points[p]), max(hi_r, points[p])
        extra = {r for r in (lo_r, hi_r) if 1 <= r <= m and r not in sorted_at}
        if extra:
            sorted_at.update(_order_statistics(flat, extra))
        low = sorted_at[lo_r] if 1 <= lo_r <= m else math.nan
        high = sorted_at[hi_r] if 1 <= hi_r <= m else math.nan
        out.append(SampleQuantile(p, float(value), float(low), float(high)))
    return tuple(out)


def _order_statistics(x: np.ndarray, ranks) -> dict:
    """``{r: x_(r)}`` for 1-based ranks, by one partial sort (a full sort where many ranks make it the cheaper one)."""
    r = sorted(int(k) for k in ranks)
    # introselect repeats its passes for every rank; numpy's vectorised sort beats it beyond a few ranks
    part = np.sort(x) if len(r) > _PARTITION_RANKS else np.partition(x, [k - 1 for k in r])
    return {k: float(part[k - 1]) for k in r}
