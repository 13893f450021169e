"""Benchmark: ``strapdown drift`` on a long run, against the compiled kernel alone.

Three rates, in gyro samples per second (panov-4s-3, 1° coning at 10 Hz, h = 2.5 ms):

* **kernel**: ``simulate_batch`` on one point, statistics only (the fused kernel and nothing else), in process;
* **long run**: ``simulate_long_run``, what the command calls (the kernel, plus one window of the
  error series and its periodic error), in process;
* **command**: ``strapdown drift --duration D`` as a fresh process pinned to CPU 0 (start-up,
  imports, the drift series and the exact drift included), with its peak RSS.

Targets: the command at least 0.8 of the kernel's rate; ``--duration 200000`` (8·10⁷ samples)
under 300 MB of peak RSS.  In-process rates are the best of ``--repeats``; CPU time is shown
beside wall time because the machine may be shared.

    python benchmarks/bench_long_run.py [--repeats 3] [--durations 200000 1000000]
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time

import numpy as np

H = 0.0025
ARGS = ["drift", "--algorithm", "panov-4s-3", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", str(H), "--json", "--quiet"]


def _in_process(repeats: int, duration: float):
    from strapdown.analysis.coning.batch import simulate_batch
    from strapdown.analysis.coning.long_run import simulate_long_run
    from strapdown.analysis.coning.precession import RegularPrecession
    from strapdown.derivations.coning.registry import get

    alg = get("panov-4s-3")
    motion = RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0))
    simulate_batch(alg, -1.0, motion.nu, motion.nutation, H, 1.0)
    simulate_long_run(alg, motion, H, 1.0)
    out = {}
    for name, call in (("kernel", lambda: simulate_batch(alg, -1.0, motion.nu, motion.nutation, H, duration)), ("long run", lambda: simulate_long_run(alg, motion, H, duration))):
        best = (np.inf, np.inf)
        for _ in range(repeats):
            w, c = time.perf_counter(), time.process_time()
            call()
            best = min(best, (time.perf_counter() - w, time.process_time() - c))
        out[name] = best
    return out


def _command(duration: float):
    pin = ["taskset", "-c", "0"] if shutil.which("taskset") else []
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    start = time.perf_counter()
    proc = subprocess.Popen(pin + [sys.executable, "-m", "strapdown.analysis", *ARGS, "--duration", repr(duration)], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"strapdown drift --duration {duration:g} failed: {proc.stderr.read().decode()[-300:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0  # MiB


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--durations", type=float, nargs="+", default=[200000.0, 1000000.0], help="--duration of the command runs [s]")
    parser.add_argument("--kernel-duration", type=float, default=200000.0, help="run length of the in-process rates [s]")
    args = parser.parse_args(argv)
    load = os.getloadavg()
    inside = _in_process(args.repeats, args.kernel_duration)
    samples = args.kernel_duration / H
    kernel_wall, kernel_cpu = inside["kernel"]
    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f} on {os.cpu_count()} cores")
    print()
    print("| what | samples | wall [s] | CPU [s] | samples/s (wall) | samples/s (CPU) | of the kernel (CPU) | peak RSS [MiB] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, (wall, cpu) in inside.items():
        print(f"| {name} (in process) | {samples:.3g} | {wall:.2f} | {cpu:.2f} | {samples / wall:.3g} | {samples / cpu:.3g} | {kernel_cpu / cpu:.2f} | |")
    ok = True
    for duration in args.durations:
        wall, cpu, rss = _command(duration)
        n = duration / H
        ratio = (n / cpu) / (samples / kernel_cpu)
        print(f"| `strapdown drift --duration {duration:g}` | {n:.3g} | {wall:.2f} | {cpu:.2f} | {n / wall:.3g} | {n / cpu:.3g} | {ratio:.2f} | {rss:.0f} |")
        if duration == 200000.0:
            ok = ok and rss < 300.0
        ok = ok and (ratio >= 0.8 or duration < max(args.durations))
    print(f"\ntargets (the command at ≥ 0.8 of the kernel's rate on the longest run; 200 000 s under 300 MB): {'met' if ok else 'not met'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
