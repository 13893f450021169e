"""The analyses of a recorded log on a 1-hour log at 1 kHz (3.6 M samples), one core.

* the replay of five algorithms (``strapdown.analysis.logs.replay.replay``: their
  correction sums and the attitudes they compute) — target well under 10 s;
* the environment estimate (``estimate_environment``: Welch cross-spectra, the line
  test, the spectra again with the lines removed) — target a few seconds;
* ``static_noise`` (the Allan deviation of the six channels) of the same log, for the record;
* the peak resident memory of each, in its own child process that also builds the log
  (the log itself is 3.6 M × 7 doubles, 200 MB) — target under 1 GB.

The log: exact increments of a 1° cone at 10 Hz, white gyro and accelerometer noise and
gravity.  Reading and checking a log file is the reader's part and is not timed here.

Run pinned: ``taskset -c 0 python benchmarks/bench_log_analysis.py [--quick]`` (``--quick``:
a 10-minute log).  The machine may be shared: the CPU time of the child is printed beside
its wall time.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

ALGORITHMS = ("two-sample", "miller-3", "ignagni-1996-5", "ignagni-1996-4", "lebedev-panov-6")
RATE = 1000.0


def build_log(duration: float):
    from strapdown.analysis.coning.precession import RegularPrecession
    from strapdown.analysis.logs.imu_log import ImuLog

    h = 1.0 / RATE
    n = int(round(duration * RATE))
    rng = np.random.default_rng(1)
    p = RegularPrecession(-1.0, 2 * math.pi * 10.0, math.radians(1.0)).grid_increments(h, 0, n)
    p += 1e-4 * math.sqrt(h) * rng.standard_normal((n, 3))
    dv = 1e-2 * math.sqrt(h) * rng.standard_normal((n, 3))
    dv[:, 2] -= 9.80665 * h
    return ImuLog(h * np.arange(1, n + 1), p, dv)


def part(name: str, duration: float) -> dict:
    """One measurement, in this process (a child of :func:`main`)."""
    log = build_log(duration)
    t0, c0 = time.perf_counter(), time.process_time()
    if name == "replay":
        from strapdown.analysis.logs.replay import replay
        from strapdown.derivations.coning.registry import get

        algs = [get(a) for a in ALGORITHMS]
        t0, c0 = time.perf_counter(), time.process_time()
        replay(log, algs)
    elif name == "environment":
        from strapdown.analysis.logs.environment_estimate import estimate_environment

        estimate_environment(log)
    elif name == "allan":
        from strapdown.analysis.logs.static_noise import static_noise

        static_noise(log)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return {"wall": wall, "cpu": cpu, "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, "samples": log.n_samples}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a 10-minute log instead of an hour")
    ap.add_argument("--part", choices=["replay", "environment", "allan"], help=argparse.SUPPRESS)
    ap.add_argument("--duration", type=float, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    duration = args.duration or (600.0 if args.quick else 3600.0)
    if args.part:
        print(json.dumps(part(args.part, duration)))
        return
    rows = []
    targets = {"replay": ("replay of five algorithms", "well under 10 s"), "environment": ("environment estimate", "a few seconds"), "allan": ("Allan read-off, six channels", "—")}
    for name, (label, target) in targets.items():
        out = subprocess.run([sys.executable, __file__, "--part", name, "--duration", str(duration)], check=True, capture_output=True, text=True)
        r = json.loads(out.stdout.strip().splitlines()[-1])
        rows.append((label, r, target))
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"log of {rows[0][1]['samples'] / 1e6:.2f} M samples at {RATE:g} Hz; machine load {load:.2f} (shared machine)\n")
    print("| analysis | wall [s] | CPU [s] | peak memory [MB] | target |")
    print("|---|---|---|---|---|")
    for label, r, target in rows:
        print(f"| {label} | {r['wall']:.2f} | {r['cpu']:.2f} | {r['peak_mb']:.0f} | {target}; memory < 1000 MB |")


if __name__ == "__main__":
    main()
