"""Throughput and memory of the azimuth Monte Carlo on one core.

Run: ``python benchmarks/bench_montecarlo.py [--samples 1e8]``.  Prints rocking
samples per second and peak memory for each rocking model, and runs the
largest case with a progress bar on stderr.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import math  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402

from strapdown.analysis.core import montecarlo  # noqa: E402
from strapdown.analysis.gyrocompass.azimuth import AzimuthErrorKernel, azimuth_monte_carlo, second_order_theory  # noqa: E402
from strapdown.analysis.gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--samples", type=float, default=1e8, help="samples of the large run (default 1e8)")
    args = parser.parse_args()
    lat, s = math.radians(60.0), math.radians(1.0)
    second_order_theory(lat, 0.0, 0.0, s, s)  # generated code loaded once, outside the timings
    montecarlo.run(AzimuthErrorKernel(lat, 0.0, 0.0, NarrowbandRocking(s, s, 8.0, 0.1), n_steps=64, dt=0.1), 2, rng=0)  # lazy scipy imports
    print(f"{'case':<34} {'samples':>12} {'seconds':>8} {'Msamples/s':>11} {'peak traced MB':>15}")
    cases = [
        ("normal, independent instants", lambda n: azimuth_monte_carlo(lat, 0.0, 0.0, GaussianRocking(s, s), n, rng=1)),
        ("sine, independent instants", lambda n: azimuth_monte_carlo(lat, 0.0, 0.0, SineRocking(s, s), n, rng=1)),
        ("narrowband series (dt 0.1 s)", lambda n: montecarlo.run(AzimuthErrorKernel(lat, 0.0, 0.0, NarrowbandRocking(s, s, 8.0, 0.1), n_steps=1024, dt=0.1), n // 1024, rng=1, scale=0.03)),
    ]
    for name, fn in cases:
        n = 10_000_000
        tracemalloc.start()
        t = time.perf_counter()
        fn(n)
        el = time.perf_counter() - t
        peak = tracemalloc.get_traced_memory()[1] / 2**20
        tracemalloc.stop()
        print(f"{name:<34} {n:>12d} {el:>8.2f} {n / el / 1e6:>11.1f} {peak:>15.1f}")
    n = int(args.samples)
    t = time.perf_counter()
    mc = azimuth_monte_carlo(lat, 0.0, 0.0, GaussianRocking(s, s), n, rng=2, progress=True)
    el = time.perf_counter() - t
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"{'normal, large run (progress bar)':<34} {mc.result.n_samples:>12d} {el:>8.2f} {mc.result.n_samples / el / 1e6:>11.1f} {f'max RSS {rss:.0f}':>15}")
    lo, hi = (math.degrees(x) for x in mc.result.rms_ci)
    print(f"rms {math.degrees(mc.result.rms):.6f} deg, 95 % CI [{lo:.6f}, {hi:.6f}], second-order theory {math.degrees(mc.theory.rms):.6f} deg")


if __name__ == "__main__":
    main()
