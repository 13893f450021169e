"""A recorded IMU log: the samples of one IMU at a constant rate, as increments in body axes.

Public API
----------
.. autosummary::

   ImuLog
   METADATA
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core.validation import as_array

__all__ = ["ImuLog", "METADATA"]

#: Metadata a log may carry (SI units; ``description`` is text).
METADATA = ("latitude", "stable_heading", "stable_beta", "stable_gamma", "end_heading", "end_beta", "end_gamma", "description")


@dataclass(frozen=True)
class ImuLog:
    """The samples of one IMU at a constant rate.

    Attributes
    ----------
    time : ndarray
        ``(N,)`` end of each sample interval [s].
    dtheta : ndarray
        ``(N, 3)`` angle increments, body axes [rad].
    dv : ndarray
        ``(N, 3)`` velocity increments [m/s].
    metadata : dict
        Name → value, from :data:`METADATA`.
    """

    time: np.ndarray
    dtheta: np.ndarray
    dv: np.ndarray
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        t = as_array(self.time, "time").ravel()
        if t.size < 2:
            raise ValueError(f"Expected `time` of at least two samples, got {t.size}")
        d = np.diff(t)
        if not np.all(d > 0):
            raise ValueError("Expected `time` strictly increasing [s]")
        h = float(np.median(d))
        if np.max(np.abs(d - h)) > 1e-3 * h:
            raise ValueError(f"Expected `time` at a constant sample interval, got intervals from {d.min():.6g} to {d.max():.6g} s")
        object.__setattr__(self, "time", t)
        for name in ("dtheta", "dv"):
            a = as_array(getattr(self, name), name)
            if a.shape != (t.size, 3):
                raise ValueError(f"Expected `{name}` with shape ({t.size}, 3), got shape {a.shape}")
            object.__setattr__(self, name, a)  # as_array gives float64 (a view where the input already is: no copy of a large log)
        unknown = [k for k in self.metadata if k not in METADATA]
        if unknown:
            raise ValueError(f"Expected metadata among {METADATA}, got {unknown}")

    @property
    def dt(self) -> float:
        """Sample interval [s]."""
        return float(np.median(np.diff(self.time)))

    @property
    def n_samples(self) -> int:
        """Samples N."""
        return self.time.size

    def angles(self, which: str):
        """``(ψ, β, γ)`` of the metadata ``"stable"`` or ``"end"`` [rad], or None where the log does not carry them.

        Parameters
        ----------
        which : str
            ``"stable"`` or ``"end"``.

        Returns
        -------
        ndarray or None
        """
        keys = [f"{which}_{a}" for a in ("heading", "beta", "gamma")]
        if all(k in self.metadata for k in keys):
            return np.array([float(self.metadata[k]) for k in keys])
        return None
