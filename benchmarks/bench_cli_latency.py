"""Latency of command-line calls: wall time of a whole ``strapdown`` process, cold and warm cache.

Each command runs as a fresh process pinned to CPU 0.  "first run" uses an
empty cache directory (``STRAPDOWN_CACHE_DIR``), so it includes generating the
derived-expression code and compiling the simulator kernels; "warm" is the
median of ``--repeats`` later runs with that cache.  Targets: ``--help`` under
0.5 s; ``azimuth … --samples 1000`` and ``stability --schuler`` under 2 s warm.

Run: ``python benchmarks/bench_cli_latency.py [--repeats 5]``.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

COMMANDS = [
    ("--help", ["--help"], 0.5),
    ("azimuth … --samples 1000", ["azimuth", "--lat-deg", "60", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1", "--samples", "1000", "--json"], 2.0),
    ("stability --schuler", ["stability", "--schuler", "--json"], 2.0),
    ("drift (panov-4s-3, 1 s)", ["drift", "--algorithm", "panov-4s-3", "--eps", "-1", "--nutation-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1", "--json"], None),
    (
        "velocity-error (lebedev-panov-6, 2 s)",
        ["velocity-error", "--algorithm", "lebedev-panov-6", "--eps", "-1", "--freq-hz", "1", "--nutation-deg", "10", "--nutation-dual", "10"]
        + ["--sample-interval", "0.01", "--duration", "2", "--json"],
        None,
    ),
]


def wall(argv, env) -> float:
    pin = ["taskset", "-c", "0"] if shutil.which("taskset") else []
    t = time.perf_counter()
    out = subprocess.run(pin + [sys.executable, "-m", "strapdown.analysis", *argv], env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - t
    if out.returncode != 0:
        raise RuntimeError(f"strapdown {' '.join(argv)} failed: {out.stderr.strip().splitlines()[-1:]}")
    return seconds


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="warm runs per command (the median is reported)")
    args = parser.parse_args(argv)
    load = os.getloadavg()
    with tempfile.TemporaryDirectory(prefix="bench-cli-") as cache:
        env = dict(os.environ, STRAPDOWN_CACHE_DIR=cache, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
        rows = []
        for label, command, target in COMMANDS:
            first = wall(command, env)
            warm = statistics.median(wall(command, env) for _ in range(args.repeats))
            rows.append((label, first, warm, target))
    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f} on {os.cpu_count()} cores; each call pinned to one")
    print()
    print("| command | first run, empty cache [s] | warm, median [s] | target (warm) |")
    print("|---|---:|---:|---|")
    for label, first, warm, target in rows:
        verdict = "" if target is None else f"< {target:g} s: {'met' if warm < target else 'NOT met'}"
        print(f"| `strapdown {label}` | {first:.2f} | {warm:.2f} | {verdict} |")
    print()
    print(f"load at end: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
