"""The example log shipped with the docs (``docs/examples/rocking-imu-log.npz``).

Public API
----------
.. autosummary::

   example_log
   EXAMPLE_SEED
"""

from __future__ import annotations

import math

import numpy as np

from ..alignment.imu import Scenario
from .imu_log import ImuLog

__all__ = ["example_log", "EXAMPLE_SEED"]

#: Seed of the example log (``docs/examples/rocking-imu-log.npz``, :func:`example_log`).
EXAMPLE_SEED = 20261203


def example_log(seed: int = EXAMPLE_SEED) -> ImuLog:
    """Four minutes of a simulated navigation-grade IMU on a rocking base (``docs/examples/rocking-imu-log.npz``).

    Latitude 45°, stable heading 30°, tilts 0.5° and −0.3°, narrow-band rocking
    of σ = (0.5°, 1.5°, 1.5°) in (yaw, β, γ) with an 8 s period, the block 0.4 m
    above the rocking centre, 50 Hz, with the ``navigation`` grade of
    :data:`strapdown.analysis.alignment.sensor_models.GRADES` (turn-on biases,
    random walks, flicker and rate random walk).  The increments are rounded
    to float32, as the file stores them; the truth is in the metadata.

    Parameters
    ----------
    seed : int
        Root seed (the rocking and the sensor errors from its two children).

    Returns
    -------
    ImuLog
    """
    from ..alignment.base_motion import NarrowbandMotion
    from ..alignment.imu import simulate_imu
    from ..alignment.sensor_models import GRADES, add_sensor_errors

    motion_seed, sensor_seed = np.random.SeedSequence(seed).spawn(2)
    sigma = np.radians([0.5, 1.5, 1.5])
    sc = Scenario(
        math.radians(45.0), heading=math.radians(30.0), beta0=math.radians(0.5), gamma0=math.radians(-0.3),
        motion=NarrowbandMotion(sigma * math.sqrt(2.0), 8.0, 0.1), lever_arm=[0.0, 0.0, -0.4], sample_rate=50.0, duration=240.0,
    )  # fmt: skip
    rec = simulate_imu(sc, None, n_trials=1, rng=np.random.default_rng(motion_seed))
    sheet = next(g for g in GRADES if g.name == "navigation")
    rec = add_sensor_errors(rec, sheet, rng=np.random.default_rng(sensor_seed))
    end = rec.truth_angles[0, -1]
    meta = {
        "latitude": sc.latitude,
        "stable_heading": sc.heading,
        "stable_beta": sc.beta0,
        "stable_gamma": sc.gamma0,
        "end_heading": float(end[0]),
        "end_beta": float(end[1]),
        "end_gamma": float(end[2]),
        "description": f"simulated: navigation-grade IMU, narrow-band rocking, 45 deg N, 50 Hz, 240 s (strapdown.analysis.alignment.recorded.example_log, seed {seed})",
    }
    as_stored = lambda x: x.astype(np.float32).astype(float)  # noqa: E731
    return ImuLog(sc.dt * np.arange(1, sc.n_samples + 1), as_stored(rec.dtheta[0]), as_stored(rec.dv[0]), meta)
