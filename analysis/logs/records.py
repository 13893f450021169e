"""A recorded log as the alignment toolkit's record of one trial.

Public API
----------
.. autosummary::

   log_record
"""

from __future__ import annotations

import numpy as np

from ..alignment.imu import ImuRecord, Scenario, SensorErrors
from .imu_log import ImuLog

__all__ = ["log_record"]


def log_record(log: ImuLog, latitude: float, *, truth_stride: int | None = None) -> ImuRecord:
    """The log as a one-trial record (its truth from the metadata where it has it, NaN elsewhere).

    Parameters
    ----------
    log : ImuLog
        The samples.
    latitude : float
        Latitude φ [rad].
    truth_stride : int, optional, keyword-only
        Truth instants every ``truth_stride`` samples (NaN between the start
        and the end; default: the start and the end).

    Returns
    -------
    ImuRecord
    """
    N, dt = log.n_samples, log.dt
    stable = log.angles("stable")
    sc = Scenario(latitude, *(stable if stable is not None else np.zeros(3)), sample_rate=1.0 / dt, duration=N * dt)
    stride = N if truth_stride is None else int(truth_stride)
    idx = np.arange(0, N + 1, stride)
    if idx[-1] != N:
        idx = np.append(idx, N)
    angles = np.full((1, idx.size, 3), np.nan)
    end = log.angles("end")
    if end is not None:
        angles[0, -1] = end
    z = np.zeros((1, idx.size, 3))
    return ImuRecord(sc, SensorErrors(), log.dtheta[None], log.dv[None], idx * dt, angles, z, z.copy(), np.zeros((1, 3)), np.zeros((1, 3)))
