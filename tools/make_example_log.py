"""Generate ``docs/examples/rocking-imu-log.npz``: four minutes of a navigation-grade IMU on a rocking base.

The log is a simulation, so its truth is known and stored in its metadata:
latitude 45°, stable heading 30°, tilts 0.5° and −0.3°, narrow-band rocking of
σ = (0.5°, 1.5°, 1.5°) in (yaw, β, γ) with an 8 s period, the block 0.4 m
above the rocking centre, 50 Hz, with the "navigation" grade of
:data:`strapdown.analysis.alignment.sensor_models.GRADES` (turn-on biases,
random walks, flicker and rate random walk).  Increments are stored as float32
(the file stays near 0.3 MB).  Seed 20261203: running this script again writes
the same arrays.

Usage: ``python tools/make_example_log.py [OUT]`` (default ``docs/examples/rocking-imu-log.npz``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from strapdown.analysis.alignment.base_motion import NarrowbandMotion
from strapdown.analysis.alignment.imu import Scenario, simulate_imu
from strapdown.analysis.alignment.recorded import ImuLog, write_log
from strapdown.analysis.alignment.sensor_models import GRADES, add_sensor_errors

SEED = 20261203
ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "docs" / "examples" / "rocking-imu-log.npz"


def example_log() -> ImuLog:
    """The example log (a pure function of :data:`SEED`)."""
    ss = np.random.SeedSequence(SEED)
    motion_seed, sensor_seed = ss.spawn(2)
    sigma = np.radians([0.5, 1.5, 1.5])
    sc = Scenario(
        math.radians(45.0), heading=math.radians(30.0), beta0=math.radians(0.5), gamma0=math.radians(-0.3),
        motion=NarrowbandMotion(sigma * math.sqrt(2.0), 8.0, 0.1), lever_arm=[0.0, 0.0, -0.4], sample_rate=50.0, duration=240.0,
    )  # fmt: skip
    rec = simulate_imu(sc, None, n_trials=1, rng=np.random.default_rng(motion_seed))
    sheet = next(g for g in GRADES if g.name == "navigation")
    rec = add_sensor_errors(rec, sheet, rng=np.random.default_rng(sensor_seed))
    N = sc.n_samples
    meta = {
        "latitude": sc.latitude,
        "stable_heading": sc.heading,
        "stable_beta": sc.beta0,
        "stable_gamma": sc.gamma0,
        "end_heading": float(rec.truth_angles[0, -1, 0]),
        "end_beta": float(rec.truth_angles[0, -1, 1]),
        "end_gamma": float(rec.truth_angles[0, -1, 2]),
        "description": f"simulated: navigation-grade IMU, narrow-band rocking, 45 deg N, 50 Hz, 240 s (tools/make_example_log.py, seed {SEED})",
    }
    # float32 storage, as written: the log holds what the file holds
    dth = rec.dtheta[0].astype(np.float32).astype(float)
    dv = rec.dv[0].astype(np.float32).astype(float)
    return ImuLog(sc.dt * np.arange(1, N + 1), dth, dv, meta)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0]) if argv else DEFAULT
    out.parent.mkdir(parents=True, exist_ok=True)
    write_log(out, example_log(), dtype=np.float32)
    print(f"{out}: {out.stat().st_size / 1e6:.2f} MB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
