"""Benchmark: how fast the command line refuses bad input (the speed half of the CLI contract).

The contract tests (``tests/test_cli_fuzz.py``, ``tests/test_cli_contract.py``) check
*what* a refusal says; how long it takes is measured here, where a loaded machine
shows up as a slow row rather than a failed test.

* **Fresh process**: one bad option per command, ``strapdown ...`` as a new
  process pinned to CPU 0, median of ``--repeats`` calls: start-up, imports and
  the check.  Target: every command within 1 s, and the environment commands
  within twice ``align``'s time (they check their options before importing the
  vibration library).
* **Fuzz table, in process**: every case of the fuzz table that must be refused,
  run through ``strapdown.analysis.cli.main`` after the baselines have paid the
  imports (as the tests do).  Target: the slowest under 5 s.

    python benchmarks/bench_refusals.py [--repeats 5] [--skip-table]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ENVIRONMENT = str(ROOT / "analysis" / "vibration" / "environments" / "coning-10hz.toml")

#: (label, a command line with one bad option)
BAD = [
    ("align --lat-deg 95", ["align", "--method", "analytic", "--lat-deg", "95"]),
    ("azimuth --lat-deg 95", ["azimuth", "--lat-deg", "95", "--sigma-xi-deg", "1", "--sigma-eta-deg", "1"]),
    ("drift --sample-interval -1", ["drift", "--algorithm", "panov-4s-3", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", "-1", "--duration", "1"]),
    ("environment-drift --sample-interval -1", ["environment-drift", "--environment", ENVIRONMENT, "--algorithm", "panov-4s-3", "--sample-interval", "-1"]),
    ("design-coning --samples 9", ["design-coning", "--environment", ENVIRONMENT, "--samples", "9", "--sample-interval", "0.001"]),
    ("design-sculling --previous 12", ["design-sculling", "--environment", ENVIRONMENT, "--samples", "2", "--previous", "12", "--sample-interval", "0.001"]),
    ("environment-rates --rates 1", ["environment-rates", "--environment", ENVIRONMENT, "--budget-deg-per-h", "1", "--rates", "1"]),
    ("multistage --step -1", ["multistage", "--step", "-1"]),
]


def fresh(argv, env) -> float:
    pin = ["taskset", "-c", "0"] if shutil.which("taskset") else []
    t = time.perf_counter()
    out = subprocess.run(pin + [sys.executable, "-m", "strapdown.analysis", *argv, "--quiet"], env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - t
    if out.returncode != 2:
        raise RuntimeError(f"strapdown {' '.join(argv)}: expected exit 2, got {out.returncode}: {out.stderr.strip()[:200]}")
    return seconds


def table_times() -> list:
    sys.path.insert(0, str(ROOT / "tests"))
    from cli_contract import run, warm_up
    from test_cli_fuzz import CASES, baseline_invocations

    warm_up(baseline_invocations())
    times = []
    for _, argv, expect, _ in CASES:
        if expect != "refuse":
            continue
        outcome = run(argv)
        times.append((outcome.seconds, " ".join(argv)[:90]))
    return times


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="fresh-process calls per command (the median is reported)")
    parser.add_argument("--skip-table", action="store_true", help="only the fresh-process rows")
    args = parser.parse_args(argv)
    load = os.getloadavg()
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    rows = []
    for label, command in BAD:
        fresh(command, env)  # warm the disk cache
        times = [fresh(command, env) for _ in range(args.repeats)]
        rows.append((label, min(times), statistics.median(times)))
    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f} on {os.cpu_count()} cores; each call pinned to CPU 0")
    print()
    print("| refusal (fresh process) | min [s] | median [s] |")
    print("|---|---:|---:|")
    for label, low, mid in rows:
        print(f"| `{label}` | {low:.2f} | {mid:.2f} |")
    align = next(mid for label, _, mid in rows if label.startswith("align"))
    environment = [mid for label, _, mid in rows if label.startswith(("environment", "design"))]
    ok = max(mid for _, _, mid in rows) <= 1.0 and max(environment) <= 2.0 * align
    print(f"\ntarget: every refusal within 1 s, the environment commands within 2 × align ({align:.2f} s): {'met' if ok else 'not met'}")
    if not args.skip_table:
        times = sorted(table_times())
        values = [t for t, _ in times]
        print(f"\nfuzz table, in process: {len(values)} refusals, median {statistics.median(values):.3f} s, slowest {values[-1]:.2f} s ({times[-1][1]})")
        print(f"target: the slowest under 5 s: {'met' if values[-1] < 5.0 else 'not met'}")
        ok = ok and values[-1] < 5.0
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
