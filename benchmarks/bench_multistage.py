"""Benchmark: the 5000 s scenario of Plotnikov (1999), section 5, on one core.

Target: sampling plus both stages in under 20 s.  Run from the repository root:

    python benchmarks/bench_multistage.py
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import time  # noqa: E402

from strapdown.analysis.multistage.stages import plotnikov_1999_stages, run_multistage  # noqa: E402
from strapdown.analysis.multistage.trajectory import Scenario, sample  # noqa: E402


def main(repeats: int = 3) -> None:
    scenario = Scenario()
    stages = plotnikov_1999_stages()
    print(f"{'step [s]':>9} {'steps':>8} {'sample [s]':>11} {'2 stages [s]':>13} {'total [s]':>10} {'target':>8}")
    for step in (0.04, 0.02):
        best = None
        for _ in range(repeats):
            t0 = time.perf_counter()
            data = sample(scenario, step, rng=0)
            t1 = time.perf_counter()
            run_multistage(data, stages)
            t2 = time.perf_counter()
            if best is None or t2 - t0 < best[2]:
                best = (t1 - t0, t2 - t1, t2 - t0)
        n = int(round(scenario.duration / step))
        print(f"{step:9g} {n:8d} {best[0]:11.2f} {best[1]:13.2f} {best[2]:10.2f} {'< 20 s':>8}")


if __name__ == "__main__":
    main()
