"""Throughput of the parallel-computation simulator (algorithm steps per second, one core).

Targets: ≥ 2·10⁶ steps/s for a batch of 256 parameter points, ≥ 10⁶ steps/s for a
single long run.  Run: ``python benchmarks/bench_simulator.py``.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.coning.precession import RegularPrecession  # noqa: E402
from strapdown.analysis.coning.simulator import simulate  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402


def _best(run, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def main():
    rng = np.random.default_rng(20261122)
    points = [RegularPrecession(rng.uniform(-2, 2), 2 * np.pi * rng.uniform(1, 20), rng.uniform(0.01, 1.0)) for _ in range(256)]
    h = 0.0025
    rows = []
    for name in ("two-sample", "panov-4s-5", "lebedev-panov-6"):
        alg = get(name)
        steps = 4000
        t = _best(lambda alg=alg, steps=steps: simulate(alg, points, h, steps * alg.samples * h))
        rows.append((name, "attitude, batch of 256 points", 256 * steps, 256 * steps / t))
        steps = 1_000_000
        t = _best(lambda alg=alg, steps=steps: simulate(alg, points[0], h, steps * alg.samples * h), repeat=1)
        rows.append((name, "attitude, single run", steps, steps / t))
        dual = RegularPrecession(0.5, 2 * np.pi, 0.2, 10.0, 100.0)
        steps = 200_000
        t = _best(lambda alg=alg, steps=steps, dual=dual: simulate(alg, dual, h, steps * alg.samples * h, velocity=True), repeat=1)
        rows.append((name, "velocity (biquaternion), single run", steps, steps / t))
    print(f"{'algorithm':<16} {'case':<38} {'steps':>10} {'steps/s':>12}")
    for name, case, steps, rate in rows:
        print(f"{name:<16} {case:<38} {steps:>10} {rate:>12.3e}")


if __name__ == "__main__":
    main()
