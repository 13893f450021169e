"""The first run against the next: a cold `strapdown report` (fresh caches) beside a warm one, in one run.

Cold means what a new user meets right after ``pip install``: an empty cache
of derived code and results (``STRAPDOWN_CACHE_DIR``) and an empty numba cache
(``NUMBA_CACHE_DIR``; an installed package keeps it in ``__pycache__`` next to
its sources, which this script leaves alone).  Each pair runs the cold report
into fresh directories, then the warm one with the caches the cold run left,
back to back, so that both see the same load on a shared machine; the ratio
cold / warm is the figure of merit (target: at most 2).  Both reports must be
byte-identical: a cold run derives everything it prints.

Run from the repository root::

    python benchmarks/bench_first_run.py [--repeat 3] [--quick]

It prints one row per pair (times, ratio, the load average of the machine
before and after) and the median ratio.
"""

import argparse
import filecmp
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _report(out: Path, env: dict, quick: bool) -> float:
    argv = [sys.executable, "-m", "strapdown.analysis", "report", "--out", str(out), "--quiet"] + (["--quick"] if quick else [])
    start = time.perf_counter()
    subprocess.run(argv, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def _same(a: Path, b: Path) -> bool:
    """Whether two report directories hold the same files with the same bytes."""
    cmp = filecmp.dircmp(a, b)

    def walk(c):
        if c.left_only or c.right_only or c.funny_files:
            return False
        _, mismatch, errors = filecmp.cmpfiles(c.left, c.right, c.common_files, shallow=False)
        return not mismatch and not errors and all(walk(s) for s in c.subdirs.values())

    return walk(cmp)


def pair(quick: bool, keep: Path | None = None) -> dict:
    """One cold run and one warm run after it, with the load average around them (the cold report copied to ``keep``)."""
    with tempfile.TemporaryDirectory(prefix="strapdown-first-run-") as tmp:
        root = Path(tmp)
        env = dict(os.environ, STRAPDOWN_CACHE_DIR=str(root / "cache"), NUMBA_CACHE_DIR=str(root / "numba"))
        env.pop("STRAPDOWN_PROGRESS_INTERVAL", None)
        load = os.getloadavg()[0]
        cold = _report(root / "cold", env, quick)
        warm = _report(root / "warm", env, quick)
        identical = _same(root / "cold", root / "warm")
        if keep is not None:
            shutil.rmtree(keep, ignore_errors=True)
            shutil.copytree(root / "cold", keep)
        return {"cold": cold, "warm": warm, "ratio": cold / warm, "load_before": load, "load_after": os.getloadavg()[0], "identical": identical}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="cold/warm pairs [count] (default 1)")
    parser.add_argument("--quick", action="store_true", help="the --quick report (default: the full report)")
    parser.add_argument("--keep", type=Path, help="copy the last cold report to this directory (to compare it with reports/)")
    args = parser.parse_args(argv)
    print(f"### First run: {'--quick' if args.quick else 'full'} report, cold (fresh caches) against warm, {os.cpu_count()} CPUs\n")
    print("| pair | cold [s] | warm [s] | cold / warm | load average before / after | reports identical |")
    print("|---:|---:|---:|---:|---|---|")
    rows = []
    for i in range(args.repeat):
        r = pair(args.quick, args.keep)
        rows.append(r)
        print(f"| {i + 1} | {r['cold']:.1f} | {r['warm']:.1f} | {r['ratio']:.2f} | {r['load_before']:.1f} / {r['load_after']:.1f} | {'yes' if r['identical'] else 'NO'} |", flush=True)
    print(f"\nmedian cold / warm: {statistics.median(r['ratio'] for r in rows):.2f}")
    if not all(r["identical"] for r in rows):
        sys.exit("a cold report differs from the warm one")


if __name__ == "__main__":
    main()
