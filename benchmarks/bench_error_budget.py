"""Error budget: a one-hour budget with every source (target < 5 s on one core), and the navigator's Monte Carlo in IMU samples per second (target ≥ 10⁶).

Run pinned to one core: ``taskset -c 0 python benchmarks/bench_error_budget.py``.
Each figure is the best of three runs after a warm-up run (numba compiled and cached, the
position algorithm derived); CPU time of the process is shown beside the wall time.
"""

from __future__ import annotations

import math
import time

from strapdown.analysis.navigation.error_budget import error_budget
from strapdown.analysis.navigation.error_model import Site
from strapdown.analysis.navigation.imu_file import example_imu
from strapdown.analysis.navigation.monte_carlo import monte_carlo
from strapdown.analysis.vibration.environment import load_environment
from strapdown.analysis.vibration.examples import QUALIFICATION
from strapdown.derivations.coning.registry import get


def _best(f, runs=3):
    f()
    walls, cpus = [], []
    for _ in range(runs):
        w, c = time.perf_counter(), time.process_time()
        f()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return min(walls), min(cpus)


def main() -> None:
    site = Site(math.radians(45.0), 0.3)
    env = load_environment(QUALIFICATION)
    alg = get("two-sample")
    rows = []
    for name in ("tactical", "mems"):
        imu = example_imu(name)
        w, c = _best(lambda imu=imu: error_budget(imu, site, 3600.0, environment=env, algorithm=alg, alignment="analytic"))
        n = len(error_budget(imu, site, 3600.0, environment=env, algorithm=alg, alignment="analytic").lines)
        rows.append((f"one-hour budget, {name}, every source ({n} lines), analytic alignment, environment", f"{w:.2f} s", f"{c:.2f} s", "< 5 s"))
    imu = example_imu("tactical")
    trials = 20
    samples = trials * 3600.0 * imu.sample_rate
    w, c = _best(lambda: monte_carlo(imu, site, [60.0, 600.0, 3600.0], n_trials=trials, algorithm=alg, rng=1), runs=2)
    what = f"navigator Monte Carlo, tactical sheet (every noise term), {trials} trials × 1 h at {imu.sample_rate:g} Hz"
    rows.append((what, f"{samples / w:.3g} samples/s", f"{samples / c:.3g} samples/s", "≥ 1e6 samples/s"))
    print("| what | wall | CPU | target |")
    print("|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")


if __name__ == "__main__":
    main()
