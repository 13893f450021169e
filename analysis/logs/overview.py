"""A recorded log at a glance: its rates and specific force against time, reduced to a few thousand points, and its gaps.

Public API
----------
.. autosummary::

   LogOverview
   log_overview
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.validation import as_int

__all__ = ["LogOverview", "log_overview"]


@dataclass(frozen=True)
class LogOverview:
    """Envelopes of the rates and the specific force over bins of time.

    Attributes
    ----------
    time : ndarray
        ``(M,)`` centre of each bin, from the log's start [s].
    rate_mean, rate_min, rate_max : ndarray
        ``(M, 3)`` mean, smallest and largest angular rate in each bin [rad/s].
    force_mean, force_min, force_max : ndarray
        ``(M, 3)`` the same for the specific force [m/s²].
    gaps : tuple of Gap
        The gaps (from the inventory's timing).
    """

    time: np.ndarray
    rate_mean: np.ndarray
    rate_min: np.ndarray
    rate_max: np.ndarray
    force_mean: np.ndarray
    force_min: np.ndarray
    force_max: np.ndarray
    gaps: tuple


def log_overview(log, *, points: int = 2000) -> LogOverview:
    """Bin every segment of ``log`` into at most about ``points`` bins in all.

    Parameters
    ----------
    log : RecordedLog
        The log.
    points : int, keyword-only
        Bins in all [count] (each segment gets its share, at least one).

    Returns
    -------
    LogOverview
    """
    points = as_int(points, "points", minimum=1)
    total = max(1, log.n_samples)
    parts = {k: [] for k in ("t", "rm", "rn", "rx", "fm", "fn", "fx")}
    for seg in log.segments:
        n = seg.n_samples
        per = max(1, int(np.ceil(total / points)))
        m = max(1, n // per)
        per = n // m
        cut = m * per
        h = seg.dt
        r = (seg.dtheta[:cut] / h).reshape(m, per, 3)
        f = (seg.dv[:cut] / h).reshape(m, per, 3)
        parts["t"].append(seg.time[:cut].reshape(m, per).mean(axis=1) - 0.5 * h)
        parts["rm"].append(r.mean(axis=1))
        parts["rn"].append(r.min(axis=1))
        parts["rx"].append(r.max(axis=1))
        parts["fm"].append(f.mean(axis=1))
        parts["fn"].append(f.min(axis=1))
        parts["fx"].append(f.max(axis=1))
    c = {k: np.concatenate(v) for k, v in parts.items()}
    return LogOverview(c["t"], c["rm"], c["rn"], c["rx"], c["fm"], c["fn"], c["fx"], tuple(log.inventory.timing.gaps))
