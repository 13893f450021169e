"""A vibration profile through an IMU mount: the closed-form drift of a 200-point spectrum for five algorithms (target < 1 s).

* The package's example airframe profile through its example mount
  (``strapdown.analysis.vibration.examples``), the IMU's cross-spectra
  tabulated at 200 frequencies (``mount_environment(..., max_points=200)``)
  behind the qualification example's gyro and accelerometer filters
  (Butterworth-2 analog and digital, decimation by 4), and the mean coning
  drift and sculling rectification of five algorithms at h = 1 ms, in total
  and per mode band, in one quadrature (``mount_drift``): wall time of the
  whole (table and drift), best of ``--repeats``, the median beside it, and
  of the first call in the process (which loads the algorithms' compiled D
  functions from the cache);
* the same drift as five calls of ``environment_drift`` on the tabulated
  environment, for comparison;
* the table alone at the default tolerance (1e-3), its size.

Run pinned: ``taskset -c 0 python benchmarks/bench_mount.py``.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.vibration.drift import environment_drift  # noqa: E402
from strapdown.analysis.vibration.environment import load_environment  # noqa: E402
from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT, QUALIFICATION  # noqa: E402
from strapdown.analysis.vibration.mount import load_mount  # noqa: E402
from strapdown.analysis.vibration.mount_response import mount_drift, mount_environment  # noqa: E402
from strapdown.analysis.vibration.profile import load_profile  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402

ALGORITHMS = ("one-sample", "two-sample", "optimal-3", "ignagni-1996-5", "lebedev-panov-4")
H = 1e-3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="repeats of each measurement (best is kept, the median shown beside)")
    args = parser.parse_args()
    load = os.getloadavg()
    mount, excitation = load_mount(ISOLATED_MOUNT), load_profile(AIRFRAME_PROFILE)
    sensors = load_environment(QUALIFICATION)
    algorithms = [get(n) for n in ALGORITHMS]

    def through_mount():
        r = mount_environment(mount, excitation, gyro=sensors.gyro, accelerometer=sensors.accelerometer, max_points=200)
        return r, mount_drift(algorithms, r, H)

    t0 = time.perf_counter()
    response, drift = through_mount()
    first = time.perf_counter() - t0
    times = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        through_mount()
        times.append(time.perf_counter() - t0)
    separate = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        for a in algorithms:
            environment_drift(a, response.environment, H)
        separate.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    default = mount_environment(mount, excitation, gyro=sensors.gyro, accelerometer=sensors.accelerometer)
    table = time.perf_counter() - t0
    rows = [
        (f"table ({response.points} points, interpolation error {response.table_error:.2g}) and drift of {len(algorithms)} algorithms per mode band, "
         "first call in the process [s]", f"{first:.3f}", "< 1"),  # fmt: skip
        (f"the same, best of {args.repeats}; median [s]", f"{min(times):.3f}; {float(np.median(times)):.3f}", "< 1"),
        (f"five environment_drift calls on the same table, best of {args.repeats} [s]", f"{min(separate):.3f}", ""),
        (f"table at the default tolerance ({default.points} points, error {default.table_error:.2g}) [s]", f"{table:.3f}", ""),
    ]
    print("| measurement | value | target |")
    print("|---|---:|---|")
    for name, value, target in rows:
        print(f"| {name} | {value} | {target} |")
    k = 180 / np.pi * 3600
    print("\n| algorithm | coning drift vector [deg/h] | magnitude [deg/h] |")
    print("|---|---|---:|")
    for a, t in zip(algorithms, drift.total_coning):
        print(f"| {a.name} | {np.round(t * k, 5).tolist()} | {np.linalg.norm(t) * k:.4g} |")
    end = os.getloadavg()
    print(f"\nload average (1, 5, 15 min) at start {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f}; at end {end[0]:.2f}, {end[1]:.2f}, {end[2]:.2f} "
          f"on {os.cpu_count()} CPUs; CPUs allowed: {sorted(os.sched_getaffinity(0))} (pinned runs share the core with anything else scheduled on it)")  # fmt: skip


if __name__ == "__main__":
    main()
